//! The adjacency graph of a symmetric sparsity pattern, as the symbolic analysis uses it:
//! built once from the lower triangle of `A`, then read with any permutation applied, and
//! compressed to one node per group of indistinguishable unknowns before ordering.
//!
//! Matrices from meshes have several unknowns per vertex (two for a planar velocity
//! field) whose rows and columns share one pattern. Minimum degree treats such unknowns
//! as one supervariable anyway, so ordering the graph of the groups and expanding every
//! group in place gives the same kind of order at a fraction of the cost (a quarter of the
//! edges for 2x2 blocks). Compression is used only when every group has the same size,
//! where the degrees of the compressed graph are those of the full graph divided by that
//! size, so that nothing is lost.

use super::amd::{amd_order, amf_order};

/// Off-diagonal adjacency of a symmetric pattern: the neighbours of `v` are
/// `adj[ptr[v]..ptr[v + 1]]`, in ascending order, each edge stored in both directions.
pub(super) struct Graph {
    ptr: Vec<usize>,
    adj: Vec<usize>,
}

impl Graph {
    /// The graph of the entries below the diagonal of a pattern in compressed sparse column
    /// form with sorted row indices (entries on or above the diagonal are ignored).
    pub(super) fn of_lower_pattern(n: usize, indptr: &[usize], indices: &[usize]) -> Self {
        let below = |j: usize| indices[indptr[j]..indptr[j + 1]].iter().copied().filter(move |&i| i > j);
        let mut count = vec![0; n];
        for j in 0..n {
            for i in below(j) {
                count[i] += 1;
                count[j] += 1;
            }
        }
        let ptr = prefix_sums(&count);
        let mut next = ptr.clone();
        let mut adj = vec![0; ptr[n]];
        // Column j's smaller neighbours are all written (in ascending order) before its own
        // column is read, and that column's rows ascend: every list comes out sorted.
        for j in 0..n {
            for i in below(j) {
                adj[next[i]] = j;
                next[i] += 1;
                adj[next[j]] = i;
                next[j] += 1;
            }
        }
        let graph = Self { ptr, adj };
        debug_assert!((0..n).all(|v| graph.neighbors(v).windows(2).all(|w| w[0] <= w[1])));
        graph
    }

    /// A graph given by its adjacency lists (symmetric, without self-loops).
    pub(super) fn from_adjacency(ptr: &[usize], adj: &[usize]) -> Self {
        Self { ptr: ptr.to_vec(), adj: adj.to_vec() }
    }

    /// Number of nodes.
    pub(super) fn len(&self) -> usize {
        self.ptr.len() - 1
    }

    /// The neighbours of `v`, ascending (duplicates possible if the pattern had any).
    pub(super) fn neighbors(&self, v: usize) -> &[usize] {
        &self.adj[self.ptr[v]..self.ptr[v + 1]]
    }

    /// Approximate minimum degree order of the nodes. (Callers with groups of
    /// indistinguishable nodes run it on [`Self::compressed`], see the module documentation.)
    pub(super) fn amd_order(&self) -> Vec<usize> {
        amd_order(self.len(), &self.ptr, &self.adj)
    }

    /// Approximate minimum fill order of the nodes (as [`Self::amd_order`]).
    pub(super) fn amf_order(&self) -> Vec<usize> {
        amf_order(self.len(), &self.ptr, &self.adj)
    }

    /// The graph of the groups `b g .. b g + b` (`block` = b): groups adjacent when their
    /// nodes are. Meant for a `block` from [`Self::uniform_block_size`].
    pub(super) fn compressed(&self, block: usize) -> Self {
        let groups = self.len() / block;
        let mut ptr = Vec::with_capacity(groups + 1);
        ptr.push(0);
        let mut adj = Vec::with_capacity(self.adj.len() / (block * block));
        for g in 0..groups {
            let start = adj.len();
            for &w in self.neighbors(block * g) {
                let h = w / block;
                // The list is sorted, so a repeated group comes right after itself (compare
                // within this group's list only).
                if h != g && adj[start..].last() != Some(&h) {
                    adj.push(h);
                }
            }
            ptr.push(adj.len());
        }
        Self { ptr, adj }
    }

    /// The size b > 1 such that the nodes are consecutive groups `b g .. b g + b` of
    /// indistinguishable nodes (adjacent to each other, with the same other neighbours),
    /// or 1 if there is no such size.
    pub(super) fn uniform_block_size(&self) -> usize {
        let n = self.len();
        for block in [2, 3] {
            let groups = n / block;
            if groups > 0 && groups * block == n && (0..groups).all(|g| self.is_group(block * g, block)) {
                return block;
            }
        }
        1
    }

    /// Whether nodes `first..first + size` are pairwise adjacent and have the same
    /// neighbours outside the group. The lists are sorted and the group is a range, so the
    /// lists of its members must agree entry by entry, except where both hold a member.
    fn is_group(&self, first: usize, size: usize) -> bool {
        let member = |w: usize| (first..first + size).contains(&w);
        let base = self.neighbors(first);
        base.iter().filter(|&&w| member(w)).count() == size - 1
            && (first + 1..first + size).all(|v| {
                let list = self.neighbors(v);
                list.len() == base.len()
                    && list.iter().zip(base).all(|(&a, &b)| a == b || (member(a) && member(b) && a != v))
            })
    }
}

/// `[0, c0, c0 + c1, ...]`: the start of each run of given lengths.
pub(super) fn prefix_sums(count: &[usize]) -> Vec<usize> {
    let mut ptr = Vec::with_capacity(count.len() + 1);
    ptr.push(0);
    for &c in count {
        ptr.push(ptr.last().expect("non-empty") + c);
    }
    ptr
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lower pattern (CSC, diagonal included) of the 2x2-block expansion of a path
    /// 0 - 1 - 2, optionally with one off-block entry removed.
    fn block_path(broken: bool) -> (Vec<usize>, Vec<usize>) {
        let mut indptr = vec![0];
        let mut indices = Vec::new();
        for j in 0..6 {
            for i in j..6 {
                let (vi, vj): (usize, usize) = (i / 2, j / 2);
                let linked = vi.abs_diff(vj) <= 1;
                if linked && !(broken && (i, j) == (3, 0)) {
                    indices.push(i);
                }
            }
            indptr.push(indices.len());
        }
        (indptr, indices)
    }

    #[test]
    fn adjacency_is_symmetric_and_sorted() {
        let (indptr, indices) = block_path(false);
        let g = Graph::of_lower_pattern(6, &indptr, &indices);
        assert_eq!(g.neighbors(0), &[1, 2, 3]);
        assert_eq!(g.neighbors(2), &[0, 1, 3, 4, 5]);
        assert_eq!(g.neighbors(5), &[2, 3, 4]);
    }

    #[test]
    fn block_structure_is_found_only_when_exact() {
        let (indptr, indices) = block_path(false);
        assert_eq!(Graph::of_lower_pattern(6, &indptr, &indices).uniform_block_size(), 2);
        let (indptr, indices) = block_path(true);
        assert_eq!(Graph::of_lower_pattern(6, &indptr, &indices).uniform_block_size(), 1);
    }

    #[test]
    fn compressed_graph_keeps_every_edge() {
        // The 2x2-block expansion of a star with centre 2 and leaves 0, 1: leaf 1's only
        // neighbour equals leaf 0's last one, which a check against the previous list
        // once dropped.
        let edges = [(0, 2), (1, 2)];
        let mut indptr = vec![0];
        let mut indices = Vec::new();
        for j in 0..6 {
            for i in j..6 {
                let (vi, vj): (usize, usize) = (i / 2, j / 2);
                if vi == vj || edges.contains(&(vj.min(vi), vj.max(vi))) {
                    indices.push(i);
                }
            }
            indptr.push(indices.len());
        }
        let g = Graph::of_lower_pattern(6, &indptr, &indices);
        assert_eq!(g.uniform_block_size(), 2);
        let c = g.compressed(2);
        assert_eq!((c.neighbors(0), c.neighbors(1), c.neighbors(2)), (&[2][..], &[2][..], &[0, 1][..]));
    }

    #[test]
    fn minimum_degree_on_the_compressed_path_starts_at_an_end() {
        let (indptr, indices) = block_path(false);
        let g = Graph::of_lower_pattern(6, &indptr, &indices);
        let groups = g.compressed(g.uniform_block_size());
        assert_eq!((groups.neighbors(0), groups.neighbors(1), groups.neighbors(2)), (&[1][..], &[0, 2][..], &[1][..]));
        let order = groups.amd_order();
        let mut sorted = order.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, vec![0, 1, 2]);
        // On a path, minimum degree eliminates an end first; never the middle block.
        assert_ne!(order[0], 1);
    }
}
