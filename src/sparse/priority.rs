//! The pivot queues of the minimum-degree machinery ([`super::amd`]): degree buckets for
//! approximate minimum degree, and a heap keyed by an approximate fill score for
//! approximate minimum fill.
//!
//! The fill scores follow E. Rothberg and S. C. Eisenstat, "Node selection strategies for
//! bottom-up sparse matrix ordering", SIAM J. Matrix Anal. Appl. 19(3):682-695, 1998. A
//! supervariable of weight `w` and (approximate, weighted) external degree `d` creates, when
//! eliminated, a clique on its `d` external neighbours; of its `d (d - 1) / 2` edges, those
//! inside the largest element the variable belongs to (`c` of its external neighbours)
//! already exist, so the fill is about
//!
//! ```text
//! fill = (d² - d) / 2 - (c² - c) / 2,
//! ```
//!
//! and approximate minimum mean local fill (AMMF) takes the pivot of least `fill / w`: a
//! supervariable eliminates `w` variables at once. `d` is AMD's approximate degree; `c` is
//! the weight of the largest element `e ∈ E_i` (the newest one included) less `w`.
//!
//! Measured on the vertex graphs of the built-in shapes (1k-50k vertices, averaged over
//! random relabellings, flops of [`super::order_flops`] with 2x2 blocks), AMMF needs
//! 0.81-0.96x the flops of AMD. Of the other scores of the paper, `fill - d w` (AMIND)
//! came within a few percent of AMMF but behind it at 10k vertices, and plain `fill` saved
//! only 0-5%; breaking ties by degree instead of last-in-first-out did not help.

use std::cmp::Ordering as Cmp;
use std::collections::BinaryHeap;

/// An empty link of the buckets' lists, and a variable not in the heap.
const NONE: usize = usize::MAX;

/// What the pivot of each step minimises.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum Score {
    /// The approximate external degree `d` (AMD).
    Degree,
    /// The approximate fill per eliminated variable, `fill / w` (Rothberg and Eisenstat's
    /// "approximate minimum mean local fill", AMMF).
    MeanFill,
}

impl Score {
    /// The key of a supervariable of weight `w`, external degree `d` and `c <= d` external
    /// neighbours in its largest element. The degree scores are exact in `f64` (below 2^53).
    pub(super) fn key(self, d: usize, c: usize, w: usize) -> f64 {
        let (d, c, w) = (d as f64, c as f64, w as f64);
        match self {
            Self::Degree => d,
            Self::MeanFill => 0.5 * ((d * d - d) - (c * c - c)) / w,
        }
    }
}

/// Variables bucketed by approximate degree: doubly linked lists, one per degree 0..=n.
pub(super) struct DegreeLists {
    head: Vec<usize>,
    next: Vec<usize>,
    prev: Vec<usize>,
    /// No non-empty bucket lies below this degree.
    min: usize,
    /// Variables in the lists.
    count: usize,
}

impl DegreeLists {
    fn new(n: usize) -> Self {
        Self { head: vec![NONE; n + 1], next: vec![NONE; n], prev: vec![NONE; n], min: n, count: 0 }
    }

    fn insert(&mut self, i: usize, degree: usize) {
        let first = self.head[degree];
        self.next[i] = first;
        self.prev[i] = NONE;
        if first != NONE {
            self.prev[first] = i;
        }
        self.head[degree] = i;
        self.min = self.min.min(degree);
        self.count += 1;
    }

    /// Unlinks `i`, which must be in the bucket of `degree`.
    fn remove(&mut self, i: usize, degree: usize) {
        let (prev, next) = (self.prev[i], self.next[i]);
        if prev == NONE {
            self.head[degree] = next;
        } else {
            self.next[prev] = next;
        }
        if next != NONE {
            self.prev[next] = prev;
        }
        self.count -= 1;
    }

    /// Removes and returns a variable of least degree; some bucket must be non-empty.
    fn pop_min(&mut self) -> usize {
        while self.head[self.min] == NONE {
            self.min += 1;
        }
        let i = self.head[self.min];
        self.remove(i, self.min);
        i
    }
}

/// An entry of [`ScoreHeap`]: the least key first, and among equal keys the latest
/// inserted (as the degree buckets, which are stacks).
#[derive(Clone, Copy, Debug)]
struct Entry {
    key: f64,
    seq: usize,
    node: usize,
}

impl PartialEq for Entry {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Cmp::Equal
    }
}

impl Eq for Entry {}

impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Cmp> {
        Some(self.cmp(other))
    }
}

impl Ord for Entry {
    /// Reversed, for the max-heap of the standard library.
    fn cmp(&self, other: &Self) -> Cmp {
        other.key.total_cmp(&self.key).then(self.seq.cmp(&other.seq))
    }
}

/// Variables keyed by score in a binary heap with lazy deletion: an entry is live while its
/// sequence number is the one recorded for its variable.
pub(super) struct ScoreHeap {
    heap: BinaryHeap<Entry>,
    /// Sequence number of each variable's live entry, `NONE` when it is not queued.
    live: Vec<usize>,
    next_seq: usize,
    count: usize,
}

impl ScoreHeap {
    fn new(n: usize) -> Self {
        Self { heap: BinaryHeap::with_capacity(n), live: vec![NONE; n], next_seq: 0, count: 0 }
    }

    fn insert(&mut self, i: usize, key: f64) {
        if self.live[i] == NONE {
            self.count += 1;
        }
        self.live[i] = self.next_seq;
        self.heap.push(Entry { key, seq: self.next_seq, node: i });
        self.next_seq += 1;
    }

    fn remove(&mut self, i: usize) {
        if self.live[i] != NONE {
            self.live[i] = NONE;
            self.count -= 1;
        }
    }

    /// Removes and returns a variable of least key; some variable must be queued.
    fn pop_min(&mut self) -> usize {
        loop {
            let Entry { seq, node, .. } = self.heap.pop().expect("a queued variable");
            if self.live[node] == seq {
                self.remove(node);
                return node;
            }
        }
    }
}

/// The queue of variables eligible as pivots.
pub(super) enum Queue {
    Buckets(DegreeLists),
    Heap(ScoreHeap),
}

impl Queue {
    /// An empty queue for `n` nodes, ordered as `score` requires.
    pub(super) fn new(n: usize, score: Score) -> Self {
        match score {
            Score::Degree => Self::Buckets(DegreeLists::new(n)),
            _ => Self::Heap(ScoreHeap::new(n)),
        }
    }

    /// Queues `i`, of approximate external degree `degree` and score `key`.
    pub(super) fn insert(&mut self, i: usize, degree: usize, key: f64) {
        match self {
            Self::Buckets(lists) => lists.insert(i, degree),
            Self::Heap(heap) => heap.insert(i, key),
        }
    }

    /// Takes out `i`, which must be queued with approximate external degree `degree`.
    pub(super) fn remove(&mut self, i: usize, degree: usize) {
        match self {
            Self::Buckets(lists) => lists.remove(i, degree),
            Self::Heap(heap) => heap.remove(i),
        }
    }

    pub(super) fn pop_min(&mut self) -> usize {
        match self {
            Self::Buckets(lists) => lists.pop_min(),
            Self::Heap(heap) => heap.pop_min(),
        }
    }

    pub(super) fn is_empty(&self) -> bool {
        match self {
            Self::Buckets(lists) => lists.count == 0,
            Self::Heap(heap) => heap.count == 0,
        }
    }
}
