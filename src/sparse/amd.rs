//! Approximate minimum degree (AMD) fill-reducing ordering of a symmetric sparsity pattern.
//!
//! Implements the algorithm of P. R. Amestoy, T. A. Davis and I. S. Duff, "An approximate
//! minimum degree ordering algorithm", SIAM J. Matrix Anal. Appl. 17(4):886-905, 1996.
//!
//! Elimination is simulated on the *quotient graph*: every node is either a variable (not yet
//! eliminated) or an element (an eliminated pivot, standing for the clique its elimination
//! created). A variable `i` keeps the list `E_i` of elements it belongs to followed by the list
//! `A_i` of variables it is still adjacent to directly; an element `e` keeps its variables `L_e`.
//! Eliminating the pivot `p` forms `L_p = (A_p ∪ ⋃_{e ∈ E_p} L_e) \ {p}` and absorbs every
//! element of `E_p` into `p`, so storage never grows beyond that of the input pattern.
//!
//! Instead of exact external degrees, each variable `i ∈ L_p` gets the paper's approximate
//! degree, an upper bound (in weighted form, `n - k` counting the variables not yet eliminated)
//!
//! ```text
//! d_i = min( n - k,  d_i_old + |L_p \ i|,  |A_i \ i| + |L_p \ i| + Σ_{e ∈ E_i \ p} |L_e \ L_p| )
//! ```
//!
//! where `|L_e \ L_p|` comes, for all elements at once, from one scan of the element lists of
//! the variables of `L_p`, never from scanning `L_e` itself. The other
//! ingredients of the paper are here too: pivots are taken from degree buckets; variables with
//! identical lists (found by hashing) are merged into supervariables and eliminated together;
//! variables adjacent to nothing but the new element are eliminated with the pivot (mass
//! elimination); an element `e` with `L_e ⊆ L_p` is absorbed at once (aggressive absorption);
//! and rows with more than `max(16, 10 √n)` off-diagonal entries are left out and ordered last.

use super::priority::{Queue, Score};

/// "No node": the end of a linked list or an empty bucket.
const NONE: usize = usize::MAX;

/// Computes a fill-reducing elimination order for the symmetric pattern of an n x n matrix.
/// The pattern is given in compressed form: the neighbours of vertex `i` are
/// `indices[ptr[i]..ptr[i + 1]]`. The pattern must be symmetric (j in row i iff i in row j);
/// diagonal entries and duplicate entries are allowed and ignored.
/// Returns `order` with `order[k]` = the original index of the k-th vertex to eliminate
/// (a permutation of 0..n).
///
/// Should the pattern not be symmetric, the ordering is that of the pattern plus its transpose
/// (the union is what is used). Rows with more than `max(16, 10 √n)` distinct off-diagonal
/// entries are placed last, in increasing index order.
///
/// # Panics
///
/// If `ptr.len() != n + 1`, if `ptr` decreases anywhere, if `ptr[n] > indices.len()`, or if an
/// entry of `indices[ptr[0]..ptr[n]]` is not below `n`.
pub fn amd_order(n: usize, ptr: &[usize], indices: &[usize]) -> Vec<usize> {
    constrained_order(n, ptr, indices, Vec::new(), Score::Degree)
}

/// Approximate minimum fill ordering: as [`amd_order`] (same input, output and panics),
/// but each pivot is a supervariable of least approximate mean local fill (the fill its
/// elimination creates per variable eliminated, see the module `priority`) rather than of
/// least approximate degree. About 2x the time of [`amd_order`]; on the vertex graphs of
/// triangle meshes its orders need 0.81-0.96x the factorisation flops of AMD's.
pub fn amf_order(n: usize, ptr: &[usize], indices: &[usize]) -> Vec<usize> {
    constrained_order(n, ptr, indices, Vec::new(), Score::MeanFill)
}

/// [`amd_order`] or [`amf_order`] (as `score` says) under constraints, as CAMD (Davis's
/// SuiteSparse) does: every vertex of class `c` is eliminated before any of class `c + 1`
/// (dense rows still last), and the score decides within a class, with the vertices of later
/// classes counted in the degrees. `class.len()` must be `n`, or 0 for no constraints.
pub(super) fn constrained_order(
    n: usize,
    ptr: &[usize],
    indices: &[usize],
    class: Vec<usize>,
    score: Score,
) -> Vec<usize> {
    assert_eq!(ptr.len(), n + 1, "ordering: ptr must have n + 1 entries");
    assert!(ptr.windows(2).all(|w| w[0] <= w[1]), "ordering: ptr must be non-decreasing");
    assert!(ptr[n] <= indices.len(), "ordering: ptr[n] exceeds indices.len()");
    assert!(indices[ptr[0]..ptr[n]].iter().all(|&j| j < n), "ordering: an index is not below n");
    assert!(class.is_empty() || class.len() == n, "ordering: one class per vertex");
    if n == 0 {
        return Vec::new();
    }
    Amd::new(n, ptr, indices, class, score).run()
}

/// What a node of the quotient graph currently is.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Kind {
    /// A principal variable: the representative of a supervariable still to be eliminated.
    Variable,
    /// A variable merged into another supervariable or mass-eliminated with a pivot.
    Merged,
    /// An eliminated pivot whose element is still live.
    Element,
    /// An element absorbed into a newer one.
    Absorbed,
    /// A dense row, left out of the graph and ordered last.
    Dense,
}

/// Everything the inner loops read about one node, in one cache line: the nodes met in a scan
/// are scattered in memory, so each costs one cache miss rather than one per field.
#[derive(Clone, Copy, Debug)]
#[repr(align(64))]
struct Node {
    kind: Kind,
    /// The node's list is `iw[start..start + len]`.
    start: usize,
    len: usize,
    /// For a variable, how many entries at the front of its list are elements (`E_i`); the
    /// rest are variables (`A_i`). Zero for elements.
    elen: usize,
    /// Size of a principal variable's supervariable; 0 for every other node.
    nv: usize,
    /// Approximate external degree of a variable, or the weight `Σ nv` of an element's list.
    degree: usize,
    /// For an element met in the current step, `w - wflg = |L_e \ L_p|`; below `wflg` else.
    w: usize,
    /// Equal to the step number while the variable is in the current `L_p`.
    in_lp: usize,
}

/// Per-node marks cleared in O(1) by moving to a new stamp.
struct Marks {
    mark: Vec<usize>,
    stamp: usize,
}

impl Marks {
    fn new(n: usize) -> Self {
        Self { mark: vec![0; n], stamp: 0 }
    }

    /// Starts a new round: no node is marked afterwards.
    fn clear(&mut self) {
        if self.stamp == usize::MAX {
            self.mark.fill(0);
            self.stamp = 0;
        }
        self.stamp += 1;
    }

    fn set(&mut self, i: usize) {
        self.mark[i] = self.stamp;
    }

    fn is_set(&self, i: usize) -> bool {
        self.mark[i] == self.stamp
    }
}

/// The quotient graph and all workspace, allocated once.
struct Amd {
    n: usize,
    node: Vec<Node>,
    /// Storage of every node's list.
    iw: Vec<usize>,
    /// End of the used part of `iw`; new element lists are appended here.
    pfree: usize,
    /// Current elimination step, the mark of membership in `L_p`.
    step: usize,
    /// Base of the `w` values of the current step.
    wflg: usize,
    /// Scratch marks for comparing lists.
    scratch: Marks,
    /// What the pivots minimise, and the variables eligible as pivots.
    score: Score,
    queue: Queue,
    /// For the fill scores: the weight of each variable's external neighbours in its
    /// largest element.
    clique: Vec<usize>,
    /// Hash buckets for supervariable detection: heads by `hash % |L_p|`, chains through
    /// `hnext`. These and the next two are indexed by position in `L_p`, not by node, so
    /// that one step touches few cache lines.
    hhead: Vec<usize>,
    hnext: Vec<usize>,
    /// Full hash of a variable's lists. [`Amd::compact`] borrows it as scratch indexed by node.
    hkey: Vec<usize>,
    /// `|A_i \ L_p| + Σ |L_e \ L_p|` of each variable `i` of `L_p`.
    partial: Vec<usize>,
    /// The largest weight `|L_e|` of the elements `e ∈ E_i \ p` of each variable `i` of `L_p`.
    largest: Vec<usize>,
    /// The original indices a principal variable stands for, as a linked list with its tail.
    member_next: Vec<usize>,
    member_tail: Vec<usize>,
    /// The variables of the element being formed.
    lp: Vec<usize>,
    /// Constraint class of each node (empty: all in class 0), and the class being eliminated.
    class: Vec<usize>,
    current: usize,
}

impl Amd {
    /// Builds the quotient graph of `pattern ∪ patternᵀ` without diagonal, duplicates and
    /// dense rows.
    fn new(n: usize, ptr: &[usize], indices: &[usize], class: Vec<usize>, score: Score) -> Self {
        let mut len = vec![0usize; n];
        for i in 0..n {
            for &j in &indices[ptr[i]..ptr[i + 1]] {
                if j != i {
                    len[i] += 1;
                    len[j] += 1;
                }
            }
        }
        let mut start = vec![0usize; n];
        let mut total = 0;
        for (s, l) in start.iter_mut().zip(len.iter_mut()) {
            *s = total;
            total += *l;
            *l = 0;
        }
        // Every entry is stored from both ends, so a symmetric input leaves half of this
        // free after deduplication; the extra n is elbow room for one-sided input. The live
        // lists never outgrow the first `total` entries.
        let mut iw = vec![0usize; total + n + 1];
        for i in 0..n {
            for &j in &indices[ptr[i]..ptr[i + 1]] {
                if j != i {
                    iw[start[i] + len[i]] = j;
                    len[i] += 1;
                    iw[start[j] + len[j]] = i;
                    len[j] += 1;
                }
            }
        }
        for (&s, l) in start.iter().zip(len.iter_mut()) {
            *l = sort_dedup(&mut iw[s..s + *l]);
        }

        let dense_above = (10.0 * (n as f64).sqrt()).max(16.0);
        let dense: Vec<bool> = len.iter().map(|&l| l as f64 > dense_above).collect();
        if dense.contains(&true) {
            for i in 0..n {
                if dense[i] {
                    len[i] = 0;
                    continue;
                }
                let s = start[i];
                let mut d = s;
                for k in s..s + len[i] {
                    let j = iw[k];
                    if !dense[j] {
                        iw[d] = j;
                        d += 1;
                    }
                }
                len[i] = d - s;
            }
        }

        let node = (0..n)
            .map(|i| Node {
                kind: if dense[i] { Kind::Dense } else { Kind::Variable },
                start: start[i],
                len: len[i],
                elen: 0,
                nv: usize::from(!dense[i]),
                degree: len[i],
                w: 0,
                in_lp: 0,
            })
            .collect();
        Self {
            n,
            node,
            iw,
            pfree: total,
            step: 0,
            wflg: 1,
            scratch: Marks::new(n),
            score,
            queue: Queue::new(n, score),
            clique: vec![0; n],
            hhead: vec![NONE; n],
            hnext: vec![NONE; n],
            hkey: vec![0; n],
            partial: vec![0; n],
            largest: vec![0; n],
            member_next: vec![NONE; n],
            member_tail: (0..n).collect(),
            lp: Vec::with_capacity(n),
            class,
            current: 0,
        }
    }

    fn class(&self, i: usize) -> usize {
        self.class.get(i).copied().unwrap_or(0)
    }

    fn run(mut self) -> Vec<usize> {
        let n = self.n;
        let mut order = Vec::with_capacity(n);
        let left_total = self.node.iter().filter(|node| node.kind == Kind::Variable).count();
        let mut by_class: Vec<usize> = (0..n).collect();
        by_class.sort_by_key(|&i| self.class(i));
        let mut next_class = 0;
        let mut left = left_total;
        while left > 0 {
            // Once a class is done, the variables of the next one enter the lists.
            while self.queue.is_empty() {
                self.current = self.class(by_class[next_class]);
                while next_class < n && self.class(by_class[next_class]) == self.current {
                    let i = by_class[next_class];
                    if self.node[i].kind == Kind::Variable {
                        self.enqueue(i);
                    }
                    next_class += 1;
                }
            }
            let p = self.queue.pop_min();
            left -= self.eliminate(p, left);
            let mut m = p;
            while m != NONE {
                order.push(m);
                m = self.member_next[m];
            }
        }
        order.extend((0..n).filter(|&i| self.node[i].kind == Kind::Dense));
        order
    }

    /// Eliminates the supervariable `p` (already out of its bucket), with `left` variables
    /// still in the graph. Returns how many variables were eliminated, all now members of `p`.
    fn eliminate(&mut self, p: usize, left: usize) -> usize {
        self.step += 1;
        self.form_element(p);
        let wmax = self.external_degrees();
        let mass = self.update_lists(p);
        let eliminated = self.node[p].nv + mass;
        self.node[p].nv = 0;
        self.detect_supervariables();
        self.update_degrees(p, left - eliminated);
        self.store_element(p);
        self.wflg = wmax + 1;
        if self.wflg >= usize::MAX - self.n - 1 {
            for node in &mut self.node {
                node.w = 0;
            }
            self.wflg = 1;
        }
        eliminated
    }

    /// Gathers `L_p` into `self.lp` (taking its variables out of the queue), absorbs the
    /// elements of `E_p` and frees their lists and that of `p`.
    fn form_element(&mut self, p: usize) {
        self.lp.clear();
        let Node { start: s, elen, len, .. } = self.node[p];
        self.node[p].kind = Kind::Element;
        for k in s..s + elen {
            let e = self.iw[k];
            if self.node[e].kind != Kind::Element {
                continue;
            }
            let (es, el) = (self.node[e].start, self.node[e].len);
            for r in es..es + el {
                self.add_to_lp(self.iw[r]);
            }
            self.node[e].kind = Kind::Absorbed;
            self.node[e].len = 0;
        }
        for k in s + elen..s + len {
            self.add_to_lp(self.iw[k]);
        }
        self.node[p].len = 0;
        self.node[p].elen = 0;
    }

    fn add_to_lp(&mut self, j: usize) {
        let node = &mut self.node[j];
        if node.kind == Kind::Variable && node.in_lp != self.step {
            node.in_lp = self.step;
            self.lp.push(j);
            let degree = node.degree;
            if self.class(j) == self.current {
                self.queue.remove(j, degree);
            }
        }
    }

    /// Sets `w = wflg + |L_e \ L_p|` for every live element `e` adjacent to `L_p`, by
    /// subtracting the weight of `L_e ∩ L_p` from that of `L_e`. Returns the largest `w`.
    fn external_degrees(&mut self) -> usize {
        let wflg = self.wflg;
        let mut wmax = wflg;
        for &i in &self.lp {
            let Node { start: s, elen, nv, .. } = self.node[i];
            for &e in &self.iw[s..s + elen] {
                let element = &mut self.node[e];
                if element.kind != Kind::Element {
                    continue;
                }
                if element.w < wflg {
                    element.w = wflg + element.degree;
                    wmax = wmax.max(element.w);
                }
                debug_assert!(element.w - wflg >= nv);
                element.w -= nv;
            }
        }
        wmax
    }

    /// For each variable of `L_p`: prunes `E_i` of absorbed elements (absorbing those with
    /// `L_e ⊆ L_p`) and `A_i` of everything `L_p` now covers, adds `p` to `E_i`, and records
    /// the partial degree and the hash of its lists. Variables left adjacent to `p` alone are
    /// mass-eliminated into `p`; returns their total weight.
    fn update_lists(&mut self, p: usize) -> usize {
        let (wflg, step) = (self.wflg, self.step);
        let mut mass = 0;
        for idx in 0..self.lp.len() {
            let i = self.lp[idx];
            let Node { start: s, elen, len, .. } = self.node[i];
            let mut d = s;
            let mut deg = 0;
            let mut hash = 0usize;
            let mut largest = 0;
            for k in s..s + elen {
                let e = self.iw[k];
                let element = &mut self.node[e];
                if element.kind != Kind::Element {
                    continue;
                }
                let external = element.w - wflg;
                if external == 0 {
                    // Aggressive absorption: every variable of e lies in L_p.
                    element.kind = Kind::Absorbed;
                    element.len = 0;
                    continue;
                }
                deg += external;
                largest = largest.max(element.degree);
                hash = hash.wrapping_add(e);
                self.iw[d] = e;
                d += 1;
            }
            let new_elen = d - s;
            for k in s + elen..s + len {
                let j = self.iw[k];
                let other = &self.node[j];
                if other.kind != Kind::Variable || other.in_lp == step {
                    continue;
                }
                deg += other.nv;
                hash = hash.wrapping_add(j);
                self.iw[d] = j;
                d += 1;
            }
            let new_len = d - s;
            let same_class = self.class(i) == self.class(p);
            let node = &mut self.node[i];
            if new_len == 0 && same_class {
                // Only p is adjacent: i is eliminated together with p.
                node.kind = Kind::Merged;
                mass += node.nv;
                node.nv = 0;
                node.len = 0;
                node.elen = 0;
                self.append_members(p, i);
                continue;
            }
            // i lost an element of E_p or the variable p, so there is room for p; it goes
            // at the end of E_i, the first entry of A_i moving to the end of the list.
            debug_assert!(new_len < len);
            if new_len > new_elen {
                self.iw[s + new_len] = self.iw[s + new_elen];
            }
            self.iw[s + new_elen] = p;
            node.elen = new_elen + 1;
            node.len = new_len + 1;
            self.partial[idx] = deg;
            self.largest[idx] = largest;
            self.hkey[idx] = hash;
            let bucket = hash % self.lp.len();
            self.hnext[idx] = self.hhead[bucket];
            self.hhead[bucket] = idx;
        }
        mass
    }

    /// Merges variables of `L_p` whose lists are identical (indistinguishable variables) into
    /// supervariables. Candidates share a hash bucket; all buckets are empty afterwards.
    fn detect_supervariables(&mut self) {
        let size = self.lp.len();
        for idx in 0..size {
            if self.node[self.lp[idx]].kind != Kind::Variable {
                continue;
            }
            let bucket = self.hkey[idx] % size;
            let mut a = self.hhead[bucket];
            self.hhead[bucket] = NONE;
            while a != NONE {
                // a's lists are marked for comparison only once a candidate turns up.
                let mut marked = false;
                let mut prev = a;
                let mut b = self.hnext[a];
                while b != NONE {
                    let next = self.hnext[b];
                    if self.may_match(a, b) {
                        if !marked {
                            self.mark_lists(a);
                            marked = true;
                        }
                        if self.same_lists(b) {
                            self.merge(self.lp[a], self.lp[b]);
                            self.hnext[prev] = next;
                            b = next;
                            continue;
                        }
                    }
                    prev = b;
                    b = next;
                }
                a = self.hnext[a];
            }
        }
    }

    /// Marks in `scratch` the list entries of the variable at position `a` of `L_p`.
    fn mark_lists(&mut self, a: usize) {
        self.scratch.clear();
        let Node { start: s, len, .. } = self.node[self.lp[a]];
        for k in s..s + len {
            self.scratch.set(self.iw[k]);
        }
    }

    /// Merges the indistinguishable variable `merge` into the supervariable `keep`.
    fn merge(&mut self, keep: usize, merge: usize) {
        self.node[keep].nv += self.node[merge].nv;
        let merged = &mut self.node[merge];
        merged.nv = 0;
        merged.kind = Kind::Merged;
        merged.len = 0;
        merged.elen = 0;
        self.append_members(keep, merge);
    }

    /// Whether the variables at positions `a` and `b` of `L_p` have equal hashes and list
    /// lengths, so that their lists are worth comparing.
    fn may_match(&self, a: usize, b: usize) -> bool {
        let (na, nb) = (&self.node[self.lp[a]], &self.node[self.lp[b]]);
        self.hkey[a] == self.hkey[b]
            && na.len == nb.len
            && na.elen == nb.elen
            && self.class(self.lp[a]) == self.class(self.lp[b])
    }

    /// Whether every entry of the lists of the variable at position `b` of `L_p` is marked in
    /// `scratch`. Lists hold no duplicates, so for lists of equal length this means equality.
    fn same_lists(&self, b: usize) -> bool {
        let nb = &self.node[self.lp[b]];
        self.iw[nb.start..nb.start + nb.len].iter().all(|&x| self.scratch.is_set(x))
    }

    /// Sets the approximate degree of the variables of `L_p` still principal (`left`
    /// variables remain in the graph), puts them back in the queue and drops the others
    /// from `L_p`.
    fn update_degrees(&mut self, p: usize, left: usize) {
        let degme: usize = self.lp.iter().map(|&i| self.node[i].nv).sum();
        for idx in 0..self.lp.len() {
            let i = self.lp[idx];
            let v = &mut self.node[i];
            if v.kind != Kind::Variable {
                continue;
            }
            let others_in_lp = degme - v.nv;
            let bound = (left - v.nv).min(v.degree + others_in_lp).min(self.partial[idx] + others_in_lp);
            v.degree = bound;
            // The largest element's other variables are external neighbours of i.
            self.clique[i] = (self.largest[idx].max(degme) - v.nv).min(bound);
            if self.class(i) == self.current {
                self.enqueue(i);
            }
        }
        let node = &self.node;
        self.lp.retain(|&i| node[i].kind == Kind::Variable);
        self.node[p].degree = degme;
    }

    /// Queues the variable `i` with its current degree and score.
    fn enqueue(&mut self, i: usize) {
        let Node { degree, nv, .. } = self.node[i];
        let key = self.score.key(degree, self.clique[i], nv);
        self.queue.insert(i, degree, key);
    }

    /// Appends `L_p` to the list storage as the list of element `p`.
    fn store_element(&mut self, p: usize) {
        let need = self.lp.len();
        if need == 0 {
            return;
        }
        if self.pfree + need > self.iw.len() {
            self.compact();
            // The live lists never outgrow the input pattern, so this does not happen; it is
            // a cheap guard all the same.
            if self.pfree + need > self.iw.len() {
                self.iw.resize(self.pfree + need, 0);
            }
        }
        let s = self.pfree;
        self.iw[s..s + need].copy_from_slice(&self.lp);
        let element = &mut self.node[p];
        element.start = s;
        element.len = need;
        element.elen = 0;
        self.pfree += need;
    }

    /// Moves every live list (`len > 0`) to the front of `iw`, keeping their order. The first
    /// entry of each live list is replaced by `n + node` (list entries are below `n`, so this
    /// marks where a list starts); the entry itself waits in `hkey`.
    fn compact(&mut self) {
        let n = self.n;
        for (i, node) in self.node.iter().enumerate() {
            if node.len > 0 {
                self.hkey[i] = self.iw[node.start];
                self.iw[node.start] = n + i;
            }
        }
        let mut dst = 0;
        let mut k = 0;
        while k < self.pfree {
            let v = self.iw[k];
            if v < n {
                k += 1;
                continue;
            }
            let i = v - n;
            let l = self.node[i].len;
            self.iw[dst] = self.hkey[i];
            self.iw.copy_within(k + 1..k + l, dst + 1);
            self.node[i].start = dst;
            dst += l;
            k += l;
        }
        self.pfree = dst;
    }

    /// Makes the members of `b` members of `a` (they will be ordered together).
    fn append_members(&mut self, a: usize, b: usize) {
        let tail = self.member_tail[a];
        self.member_next[tail] = b;
        self.member_tail[a] = self.member_tail[b];
    }
}

/// Sorts `list` and moves its distinct entries to the front; returns how many there are.
fn sort_dedup(list: &mut [usize]) -> usize {
    list.sort_unstable();
    let mut d = 0;
    for k in 0..list.len() {
        if k == 0 || list[k] != list[d - 1] {
            list[d] = list[k];
            d += 1;
        }
    }
    d
}

#[cfg(test)]
#[path = "amd_tests.rs"]
mod tests;
