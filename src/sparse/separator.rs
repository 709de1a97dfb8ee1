//! Multilevel vertex separators: splits a graph into two parts of about equal weight and a
//! small separator, with no edge between the parts, for nested dissection.
//!
//! The multilevel scheme of Karypis and Kumar ("A fast and high quality multilevel scheme
//! for partitioning irregular graphs", SIAM J. Sci. Comput. 20(1), 1998), in the form
//! METIS uses for orderings: the graph is coarsened by heavy-edge matchings (each pair of
//! matched vertices collapsed into one whose weight is their sum) down to about a hundred
//! vertices; the coarsest graph is split by graph growing (breadth-first from several
//! seeds, a pseudo-peripheral vertex first) with the frontier as separator; the best few
//! separators are each projected back level by level and improved at each level by a
//! Fiduccia-Mattheyses-style refinement for vertex separators (Ashcraft and Liu, "A
//! partition improvement algorithm for generalized nested dissection", 1994): a separator
//! vertex moves into one part and pulls its neighbours of the other part into the
//! separator, moves are taken by largest decrease of separator weight under a balance
//! bound, uphill moves are allowed for a while, and each pass keeps its best prefix. The
//! smallest separator found at the finest level is returned.

use std::collections::BinaryHeap;

/// "No vertex".
pub(super) const NONE: u32 = u32::MAX;

/// Coarsening stops at graphs of about this many vertices.
const COARSEST: usize = 96;

/// Graph-growing trials for the initial separator of the coarsest graph.
const INITIAL_TRIALS: usize = 6;

/// Initial separators carried through the refinement to the finest level.
/// (Three need a tenth fewer flops on the built-in shapes than one, for twice the time.)
const KEPT: usize = 3;

/// Refinement passes per level (a pass stops the loop when it improves nothing).
const PASSES: usize = 8;

/// Largest part weight allowed, as a fraction of the total (METIS allows 0.6 for orders).
const MAX_PART: f64 = 0.6;

/// Labels of [`bisect`]'s result.
pub(super) const SEPARATOR: u8 = 2;

/// An undirected graph with vertex and edge weights: the neighbours of `v` are
/// `adj[ptr[v]..ptr[v + 1]]` (no self-loops, no duplicates), with weights `ewgt` alike.
pub(super) struct WGraph {
    pub(super) ptr: Vec<usize>,
    pub(super) adj: Vec<u32>,
    pub(super) ewgt: Vec<u32>,
    pub(super) vwgt: Vec<u32>,
}

impl WGraph {
    pub(super) fn len(&self) -> usize {
        self.vwgt.len()
    }

    pub(super) fn neighbors(&self, v: usize) -> &[u32] {
        &self.adj[self.ptr[v]..self.ptr[v + 1]]
    }

    fn total_weight(&self) -> u64 {
        self.vwgt.iter().map(|&w| u64::from(w)).sum()
    }
}

/// A small deterministic generator (xorshift) for visiting orders.
struct Rng(u64);

impl Rng {
    fn below(&mut self, n: usize) -> usize {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 % n as u64) as usize
    }
}

/// Splits `g` (connected, at least two vertices) into parts 0 and 1 and a separator
/// ([`SEPARATOR`]): `where_[v]` for every vertex. No edge joins parts 0 and 1.
pub(super) fn bisect(g: &WGraph, refiner: &mut Refiner) -> Vec<u8> {
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    let mut graphs: Vec<WGraph> = Vec::new();
    let mut maps: Vec<Vec<u32>> = Vec::new();
    loop {
        let current = graphs.last().unwrap_or(g);
        if current.len() <= COARSEST {
            break;
        }
        let (coarse, map) = coarsen(current, &mut rng);
        if coarse.len() * 20 > current.len() * 19 {
            break;
        }
        graphs.push(coarse);
        maps.push(map);
    }
    let coarsest = graphs.last().unwrap_or(g);
    let max_part = (MAX_PART * coarsest.total_weight() as f64) as u64;
    let mut best: Option<((u64, u64), Vec<u8>)> = None;
    for mut where_ in initial_separators(coarsest, max_part, refiner) {
        for level in (0..maps.len()).rev() {
            let fine = if level == 0 { g } else { &graphs[level - 1] };
            where_ = maps[level].iter().map(|&c| where_[c as usize]).collect();
            refiner.refine(fine, &mut where_, max_part, PASSES);
        }
        let pw = part_weights(g, &where_);
        let key = (pw[2], pw[0].abs_diff(pw[1]));
        if best.as_ref().is_none_or(|(k, _)| key < *k) {
            best = Some((key, where_));
        }
    }
    best.expect("at least one separator").1
}

/// One level of coarsening by heavy-edge matching (vertices visited in a shuffled order,
/// each matched with its unmatched neighbour of heaviest edge, lightest on ties). Returns
/// the coarse graph and the map from fine to coarse vertices.
fn coarsen(g: &WGraph, rng: &mut Rng) -> (WGraph, Vec<u32>) {
    let n = g.len();
    let mut visit: Vec<u32> = (0..n as u32).collect();
    for i in (1..n).rev() {
        visit.swap(i, rng.below(i + 1));
    }
    let mut mate = vec![NONE; n];
    for &v in &visit {
        let v = v as usize;
        if mate[v] != NONE {
            continue;
        }
        let mut best = NONE;
        let mut best_key = (0, 0);
        for k in g.ptr[v]..g.ptr[v + 1] {
            let u = g.adj[k];
            if mate[u as usize] == NONE {
                let key = (g.ewgt[k], u32::MAX - g.vwgt[u as usize]);
                if best == NONE || key > best_key {
                    best = u;
                    best_key = key;
                }
            }
        }
        if best == NONE {
            mate[v] = v as u32;
        } else {
            mate[v] = best;
            mate[best as usize] = v as u32;
        }
    }
    let mut map = vec![NONE; n];
    let mut count = 0u32;
    for v in 0..n {
        if map[v] == NONE {
            map[v] = count;
            map[mate[v] as usize] = count;
            count += 1;
        }
    }
    let nc = count as usize;
    let mut coarse = WGraph {
        ptr: Vec::with_capacity(nc + 1),
        adj: Vec::with_capacity(g.adj.len() * 3 / 5),
        ewgt: Vec::with_capacity(g.adj.len() * 3 / 5),
        vwgt: Vec::with_capacity(nc),
    };
    coarse.ptr.push(0);
    // slot[c] = position of coarse neighbour c in the list being built, or NONE.
    let mut slot = vec![usize::MAX; nc];
    for v in 0..n {
        let c = map[v];
        let u = mate[v] as usize;
        if u < v {
            continue;
        }
        let start = coarse.adj.len();
        let mut weight = g.vwgt[v];
        let members: &[usize] = if u == v { &[v][..] } else { &[v, u][..] };
        if u != v {
            weight += g.vwgt[u];
        }
        for &w in members {
            for k in g.ptr[w]..g.ptr[w + 1] {
                let d = map[g.adj[k] as usize];
                if d == c {
                    continue;
                }
                let s = slot[d as usize];
                if s == usize::MAX {
                    slot[d as usize] = coarse.adj.len();
                    coarse.adj.push(d);
                    coarse.ewgt.push(g.ewgt[k]);
                } else {
                    coarse.ewgt[s] += g.ewgt[k];
                }
            }
        }
        for &d in &coarse.adj[start..] {
            slot[d as usize] = usize::MAX;
        }
        coarse.ptr.push(coarse.adj.len());
        coarse.vwgt.push(weight);
    }
    debug_assert_eq!(coarse.len(), nc);
    (coarse, map)
}

/// Breadth-first levels from `seed` (all vertices reached get their distance in `dist`,
/// others `NONE`); returns the order of visit.
fn bfs(g: &WGraph, seed: usize, dist: &mut [u32]) -> Vec<u32> {
    dist.fill(NONE);
    let mut queue = vec![seed as u32];
    dist[seed] = 0;
    let mut head = 0;
    while head < queue.len() {
        let v = queue[head] as usize;
        head += 1;
        for &u in g.neighbors(v) {
            if dist[u as usize] == NONE {
                dist[u as usize] = dist[v] + 1;
                queue.push(u);
            }
        }
    }
    queue
}

/// Separators of the coarsest graph grown from several seeds, each refined; the
/// [`KEPT`] best, best first.
fn initial_separators(g: &WGraph, max_part: u64, refiner: &mut Refiner) -> Vec<Vec<u8>> {
    let n = g.len();
    let total = g.total_weight();
    let mut dist = vec![NONE; n];
    // A pseudo-peripheral vertex: the last reached from the last reached from vertex 0.
    let mut seed = *bfs(g, 0, &mut dist).last().expect("non-empty") as usize;
    seed = *bfs(g, seed, &mut dist).last().expect("non-empty") as usize;
    let mut seeds = vec![seed];
    for k in 1..INITIAL_TRIALS {
        seeds.push(k * n / INITIAL_TRIALS);
    }
    let mut found: Vec<((u64, u64), Vec<u8>)> = Vec::new();
    for seed in seeds {
        let visit = bfs(g, seed, &mut dist);
        let mut where_ = vec![1u8; n];
        let mut grown = 0;
        for &v in &visit {
            if 2 * grown >= total {
                break;
            }
            where_[v as usize] = 0;
            grown += u64::from(g.vwgt[v as usize]);
        }
        // The separator: the vertices of part 1 next to part 0.
        for v in 0..n {
            if where_[v] == 1 && g.neighbors(v).iter().any(|&u| where_[u as usize] == 0) {
                where_[v] = SEPARATOR;
            }
        }
        refiner.refine(g, &mut where_, max_part, PASSES);
        let pw = part_weights(g, &where_);
        let key = (pw[2], pw[0].abs_diff(pw[1]));
        if !found.iter().any(|(_, w)| *w == where_) {
            found.push((key, where_));
        }
    }
    found.sort_by_key(|(key, _)| *key);
    found.into_iter().take(KEPT).map(|(_, w)| w).collect()
}

fn part_weights(g: &WGraph, where_: &[u8]) -> [u64; 3] {
    let mut pw = [0; 3];
    for (v, &p) in where_.iter().enumerate() {
        pw[p as usize] += u64::from(g.vwgt[v]);
    }
    pw
}

/// A move of the refinement: `v` went from the separator to part `to` and pulled
/// `pulled[start..]` (up to the next move's start) from the other part into the separator.
struct Move {
    v: u32,
    to: u8,
    start: usize,
}

/// Scratch space of the Fiduccia-Mattheyses refinement, reused across levels and parts.
#[derive(Default)]
pub(super) struct Refiner {
    /// `locked[v] == call` while `v` is locked in the current call.
    locked: Vec<u32>,
    call: u32,
    /// Gains of moving a separator vertex to part 0 and to part 1 (valid for separator
    /// vertices during a pass).
    gains: [Vec<i64>; 2],
    heaps: [BinaryHeap<(i64, u32)>; 2],
    moves: Vec<Move>,
    pulled: Vec<u32>,
    /// The separator vertices (and perhaps some that left it), and a stamp per vertex to
    /// build that list without repeats.
    separator: Vec<u32>,
    seen: Vec<u32>,
    stamp: u32,
}

impl Refiner {
    /// Computes both gains of separator vertex `v` and queues them.
    fn enter(&mut self, g: &WGraph, where_: &[u8], v: usize) {
        // Moving to part 0 pulls the neighbours in part 1, and conversely: one scan.
        let mut pulled = [0i64; 2];
        for &u in g.neighbors(v) {
            let p = where_[u as usize];
            if p < 2 {
                pulled[1 - p as usize] += i64::from(g.vwgt[u as usize]);
            }
        }
        for (to, pulled_to) in pulled.into_iter().enumerate() {
            let gain_v = i64::from(g.vwgt[v]) - pulled_to;
            self.gains[to][v] = gain_v;
            self.heaps[to].push((gain_v, v as u32));
        }
    }

    /// Improves the separator of `where_` by up to `passes` passes of moves, keeping
    /// every part within `max_part` (or not heavier than it was).
    fn refine(&mut self, g: &WGraph, where_: &mut [u8], max_part: u64, passes: usize) {
        let n = g.len();
        // Scratch space only grows: the gains are written before they are read, the
        // stamps only increase, and a new call's lock is a new stamp.
        if self.locked.len() < n {
            self.locked.resize(n, 0);
            self.seen.resize(n, 0);
            for gains in &mut self.gains {
                gains.resize(n, 0);
            }
        }
        self.call += 1;
        let call = self.call;
        self.separator.clear();
        self.separator.extend((0..n as u32).filter(|&v| where_[v as usize] == SEPARATOR));
        let mut pw = part_weights(g, where_);
        let limit = (n / 100).clamp(20, 100);
        for _ in 0..passes {
            let bound = max_part.max(pw[0]).max(pw[1]);
            for heap in &mut self.heaps {
                heap.clear();
            }
            let separator = std::mem::take(&mut self.separator);
            for &v in &separator {
                self.enter(g, where_, v as usize);
            }
            self.moves.clear();
            self.pulled.clear();
            let start_key = (pw[2], pw[0].abs_diff(pw[1]));
            let mut best_key = start_key;
            let mut best_len = 0;
            loop {
                // Valid tops of both queues.
                let mut tops = [None, None];
                for (to, top) in tops.iter_mut().enumerate() {
                    while let Some(&(gain_v, v)) = self.heaps[to].peek() {
                        let vi = v as usize;
                        if where_[vi] != SEPARATOR || self.locked[vi] == call || self.gains[to][vi] != gain_v {
                            self.heaps[to].pop();
                            continue;
                        }
                        if pw[to] + u64::from(g.vwgt[vi]) <= bound {
                            *top = Some(gain_v);
                        }
                        break;
                    }
                }
                let to = match tops {
                    [None, None] => break,
                    [Some(_), None] => 0,
                    [None, Some(_)] => 1,
                    [Some(a), Some(b)] => usize::from(!(a > b || (a == b && pw[0] <= pw[1]))),
                };
                let (_, v) = self.heaps[to].pop().expect("a valid top");
                let vi = v as usize;
                let other = 1 - to;
                let wv = i64::from(g.vwgt[vi]);
                where_[vi] = to as u8;
                self.locked[vi] = call;
                pw[2] -= u64::from(g.vwgt[vi]);
                pw[to] += u64::from(g.vwgt[vi]);
                // Separator neighbours of v would now pull v if they moved to `other`.
                for &u in g.neighbors(vi) {
                    let u = u as usize;
                    if where_[u] == SEPARATOR && self.locked[u] != call {
                        self.gains[other][u] -= wv;
                        self.heaps[other].push((self.gains[other][u], u as u32));
                    }
                }
                let start = self.pulled.len();
                for &u in g.neighbors(vi) {
                    let u = u as usize;
                    if where_[u] != other as u8 {
                        continue;
                    }
                    where_[u] = SEPARATOR;
                    let wu = i64::from(g.vwgt[u]);
                    pw[other] -= g.vwgt[u] as u64;
                    pw[2] += g.vwgt[u] as u64;
                    self.pulled.push(u as u32);
                    // Separator neighbours of u would no longer pull it moving to `to`.
                    for &x in g.neighbors(u) {
                        let x = x as usize;
                        if where_[x] == SEPARATOR && self.locked[x] != call {
                            self.gains[to][x] += wu;
                            self.heaps[to].push((self.gains[to][x], x as u32));
                        }
                    }
                    if self.locked[u] != call {
                        self.enter(g, where_, u);
                    }
                }
                self.moves.push(Move { v, to: to as u8, start });
                let key = (pw[2], pw[0].abs_diff(pw[1]));
                if key < best_key {
                    best_key = key;
                    best_len = self.moves.len();
                } else if self.moves.len() - best_len > limit {
                    break;
                }
            }
            // Undo the moves after the best prefix.
            while self.moves.len() > best_len {
                let m = self.moves.pop().expect("a move");
                let other = 1 - m.to;
                for &u in &self.pulled[m.start..] {
                    where_[u as usize] = other;
                    pw[other as usize] += u64::from(g.vwgt[u as usize]);
                    pw[2] -= u64::from(g.vwgt[u as usize]);
                }
                self.pulled.truncate(m.start);
                where_[m.v as usize] = SEPARATOR;
                pw[m.to as usize] -= u64::from(g.vwgt[m.v as usize]);
                pw[2] += u64::from(g.vwgt[m.v as usize]);
            }
            for m in &self.moves {
                self.locked[m.v as usize] = 0;
            }
            // The separator now: the old one and the vertices pulled into it, if still there.
            self.stamp += 1;
            let mut next = separator;
            next.extend_from_slice(&self.pulled);
            next.retain(|&v| {
                let keep = where_[v as usize] == SEPARATOR && self.seen[v as usize] != self.stamp;
                self.seen[v as usize] = self.stamp;
                keep
            });
            self.separator = next;
            if best_key >= start_key {
                break;
            }
        }
    }
}
