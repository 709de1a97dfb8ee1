//! Geometric nested dissection: a fill-reducing order for graphs whose vertices have
//! positions in the plane (such as the vertex graphs of triangle meshes), and the
//! expansion of a vertex order to several unknowns per vertex.
//!
//! Recursive bisection (George 1973; Miller, Teng, Thurston and Vavasis for the geometric
//! version): split the vertex set at the median of the coordinate along a direction,
//! take as separator the vertices of one half that have a neighbour in the other (the
//! smaller such set over a few directions), order both halves recursively and the
//! separator last. For planar meshes the separators have about `sqrt(n)` vertices, which
//! bounds the fill by `O(n log n)`. Small parts are ordered by approximate minimum degree.

use super::amd_order;

/// Parts with at most this many vertices are ordered by minimum degree.
const LEAF_SIZE: usize = 128;

/// Directions tried for each bisection (unit vectors: x, y and the two diagonals).
const DIRECTIONS: [[f64; 2]; 4] = [
    [1.0, 0.0],
    [0.0, 1.0],
    [std::f64::consts::FRAC_1_SQRT_2, std::f64::consts::FRAC_1_SQRT_2],
    [std::f64::consts::FRAC_1_SQRT_2, -std::f64::consts::FRAC_1_SQRT_2],
];

/// A nested-dissection elimination order of a graph with vertex positions: `order[k]` is
/// the k-th vertex to eliminate. The neighbours of vertex `i` are
/// `indices[ptr[i]..ptr[i + 1]]` (symmetric; self-loops ignored).
pub fn nested_dissection_order(ptr: &[usize], indices: &[usize], positions: &[[f64; 2]]) -> Vec<usize> {
    let n = positions.len();
    assert_eq!(ptr.len(), n + 1, "ptr must have one entry per vertex plus one");
    let mut state = State { ptr, indices, positions, side: vec![0; n], order: Vec::with_capacity(n) };
    let mut vertices: Vec<usize> = (0..n).collect();
    state.dissect(&mut vertices, 1);
    state.order
}

/// Expands an order of vertices to `block` unknowns per vertex, numbered
/// `block * v + k`: each vertex's unknowns stay together, in the vertex's place.
pub fn expand_blocks(order: &[usize], block: usize) -> Vec<usize> {
    order.iter().flat_map(|&v| (0..block).map(move |k| block * v + k)).collect()
}

struct State<'a> {
    ptr: &'a [usize],
    indices: &'a [usize],
    positions: &'a [[f64; 2]],
    /// Labels vertices during a split: the region id of the current part, or that id + 1
    /// for the upper half.
    side: Vec<u32>,
    order: Vec<usize>,
}

impl State<'_> {
    fn neighbors(&self, v: usize) -> &[usize] {
        &self.indices[self.ptr[v]..self.ptr[v + 1]]
    }

    /// Appends an order of `part` to `self.order`; `label` is unique to this part.
    fn dissect(&mut self, part: &mut [usize], label: u32) {
        if part.len() <= LEAF_SIZE {
            self.order_leaf(part);
            return;
        }
        let half = part.len() / 2;
        let mut best: Option<(usize, [f64; 2])> = None;
        for dir in DIRECTIONS {
            let size = self.split(part, half, dir, label).1;
            if best.is_none_or(|(s, _)| size < s) {
                best = Some((size, dir));
            }
        }
        let (_, dir) = best.expect("at least one direction");
        let (separator_in_lower, _) = self.split(part, half, dir, label);
        // After `split`, part[..half] is the lower half, part[half..] the upper; the
        // separator is the boundary of one side towards the other.
        let (lower, upper) = part.split_at_mut(half);
        let sep_side: &mut [usize] = if separator_in_lower { lower } else { upper };
        let sep_label = if separator_in_lower { label } else { label + 1 };
        let other_label = if separator_in_lower { label + 1 } else { label };
        // Move separator vertices to the end of their side.
        let mut keep = 0;
        for i in 0..sep_side.len() {
            let v = sep_side[i];
            let on_boundary = self.neighbors(v).iter().any(|&w| self.side[w] == other_label);
            if !on_boundary {
                sep_side.swap(keep, i);
                keep += 1;
            }
        }
        debug_assert!(sep_side[keep..].iter().all(|&v| self.side[v] == sep_label));
        let separator: Vec<usize> = sep_side[keep..].to_vec();
        // Children get fresh labels far from this part's (labels grow with depth).
        let (lower, upper) = part.split_at_mut(half);
        let (lower_len, upper_len) = if separator_in_lower { (keep, upper.len()) } else { (lower.len(), keep) };
        self.relabel(&lower[..lower_len], 2 * label + 2);
        self.dissect(&mut lower[..lower_len], 2 * label + 2);
        self.relabel(&upper[..upper_len], 2 * label + 4);
        self.dissect(&mut upper[..upper_len], 2 * label + 4);
        self.order.extend_from_slice(&separator);
    }

    fn relabel(&mut self, vertices: &[usize], label: u32) {
        for &v in vertices {
            self.side[v] = label;
        }
    }

    /// Splits `part` at its median along `dir` (lower half first, labelled `label`, the
    /// upper half `label + 1`) and returns whether the smaller one-sided separator lies in
    /// the lower half, and its size.
    fn split(&mut self, part: &mut [usize], half: usize, dir: [f64; 2], label: u32) -> (bool, usize) {
        let key = |v: usize| self.positions[v][0] * dir[0] + self.positions[v][1] * dir[1];
        part.select_nth_unstable_by(half, |&a, &b| key(a).total_cmp(&key(b)));
        for &v in &part[..half] {
            self.side[v] = label;
        }
        for &v in &part[half..] {
            self.side[v] = label + 1;
        }
        let boundary = |side: &[usize], other: u32| {
            side.iter().filter(|&&v| self.neighbors(v).iter().any(|&w| self.side[w] == other)).count()
        };
        let lower = boundary(&part[..half], label + 1);
        let upper = boundary(&part[half..], label);
        if lower <= upper {
            (true, lower)
        } else {
            (false, upper)
        }
    }

    /// Orders a small part by approximate minimum degree on its induced subgraph.
    fn order_leaf(&mut self, part: &[usize]) {
        if part.len() <= 2 {
            self.order.extend_from_slice(part);
            return;
        }
        // Local numbering through `side`, which no longer matters for this part.
        let mark = u32::MAX;
        for (k, &v) in part.iter().enumerate() {
            self.side[v] = mark - 1 - k as u32;
        }
        let local = |side: &[u32], w: usize| {
            let s = side[w];
            (s > mark - 1 - part.len() as u32 && s < mark).then(|| (mark - 1 - s) as usize)
        };
        let mut ptr = vec![0];
        let mut adj = Vec::new();
        for &v in part {
            for &w in self.neighbors(v) {
                if let Some(k) = local(&self.side, w) {
                    if part[k] == w {
                        adj.push(k);
                    }
                }
            }
            ptr.push(adj.len());
        }
        let order = amd_order(part.len(), &ptr, &adj);
        self.order.extend(order.iter().map(|&k| part[k]));
        for &v in part {
            self.side[v] = 0;
        }
    }
}
