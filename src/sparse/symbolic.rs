//! Symbolic analysis: everything about the factor `L` of `P A P^T = L L^T` that depends
//! only on the sparsity pattern of `A`, computed once per pattern.
//!
//! Steps and costs (n unknowns, |A| entries of the lower triangle, |L| entries of L). The
//! pattern is read once into a symmetric adjacency [`Graph`]; every later step reads it
//! through the permutation instead of building permuted copies.
//! 1. fill-reducing order (AMD or AMF on the graph compressed to one node per group of
//!    indistinguishable unknowns, such as the 2x2 blocks of a vertex; or given),
//!    O(|A|) in practice;
//! 2. elimination tree of the permuted pattern (Liu's algorithm with path compression),
//!    O(|A| log n), and its postorder, which is folded into the permutation so that every
//!    subtree, and so every supernode, is a contiguous range of columns (the tree is
//!    relabelled, not recomputed: a postorder is an equivalent order with the same tree);
//! 3. column counts of L by walking each row subtree (row i of L is the union of the etree
//!    paths from the entries of row i of A up to i), O(|L|); steps 2 and 3 run on the
//!    graph of groups when the order eliminates each group of indistinguishable unknowns
//!    together (a quarter of the entries for 2x2 blocks), and are expanded: within a group
//!    the tree is a chain and the counts fall by one per unknown;
//! 4. fundamental supernodes (a column joins its only child's supernode when it is that
//!    child's parent and its count is one less), relaxed, and the row pattern of each
//!    supernode: its columns, the rows of A below them and the rows of its child
//!    supernodes below them, sorted all at once by a double transpose, O(|L|);
//! 5. a map from every lower-triangle entry of A to its slot in the supernodal storage of
//!    L, grouped by supernode with a counting sort, O(|A|).

use super::graph::{prefix_sums, Graph};
use super::{CsMatView, FactorError};

const NONE: usize = usize::MAX;

/// How [`super::Symbolic::analyse`] orders the unknowns. Minimum degree and minimum fill run
/// on the graph of the matrix's blocks of indistinguishable unknowns (such as the 2 x 2
/// blocks of a vertex), when it has them, and keep each block together.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Ordering {
    /// Keep the given order (for tests and for matrices that are already well ordered).
    Natural,
    /// Approximate minimum degree on the pattern of `A` (Amestoy, Davis and Duff 1996;
    /// [`super::amd_order`]).
    #[default]
    Amd,
    /// Approximate minimum mean local fill on the pattern of `A` (Rothberg and Eisenstat
    /// 1998; [`super::amf_order`]): about twice minimum degree's time, and on the vertex
    /// graphs of triangle meshes 0.81-0.96x its flops.
    Amf,
    /// Eliminate the unknowns in this order: `order[k]` is the original index of the k-th.
    Given(Vec<usize>),
}

/// The result of analysing a sparsity pattern; shared by every numeric factorisation of
/// matrices with that pattern.
#[derive(Debug, Clone)]
pub struct Symbolic {
    pub(super) n: usize,
    /// `perm[k]` is the original index of the k-th unknown of the factorisation.
    pub(super) perm: Vec<usize>,
    /// The analysed pattern of A, to check that refactorisations use the same one.
    pub(super) a_indptr: Vec<usize>,
    pub(super) a_indices: Vec<usize>,
    /// The entries of A that land in supernode `s`, as (offset in the supernode's values,
    /// index in A's data): `a_entries[a_entry_start[s]..a_entry_start[s + 1]]`, so that
    /// each supernode is assembled just before it is factored. Entries above the diagonal
    /// of A are not read.
    pub(super) a_entry_start: Vec<usize>,
    pub(super) a_entries: Vec<(usize, usize)>,
    /// Length of the value array a refactorisation reads: A's entry count, or that of the
    /// source given to [`Self::reading_values_through`].
    pub(super) source_len: usize,
    /// Whether `a_entries` index a source other than A's own data (then the pattern of a
    /// matrix cannot be checked against them).
    pub(super) through_map: bool,
    /// Supernode `s` holds columns `super_start[s]..super_start[s + 1]` of L.
    pub(super) super_start: Vec<usize>,
    pub(super) col_to_super: Vec<usize>,
    /// Sorted (permuted) row indices of supernode `s`: `rows[row_start[s]..row_start[s + 1]]`;
    /// its own columns come first.
    pub(super) row_start: Vec<usize>,
    pub(super) rows: Vec<usize>,
    /// Values of supernode `s`, column-major with as many rows as the supernode has:
    /// `value_start[s]..value_start[s + 1]`.
    pub(super) value_start: Vec<usize>,
    /// Largest update block a supernode sends to an ancestor (rows below its columns, squared).
    pub(super) max_update: usize,
    /// Whether every supernode starts at an even column and its rows come in pairs
    /// `(2v, 2v + 1)` (a matrix of 2x2 vertex blocks, ordered vertex by vertex): updates are
    /// then scattered two rows and two columns at a time.
    pub(super) paired: bool,
    nnz_l: usize,
    flops: f64,
}

impl Symbolic {
    /// Analyses the pattern of the lower triangle (row >= column) of a square matrix in
    /// compressed sparse column form. Entries above the diagonal are ignored, so a full
    /// symmetric matrix and its lower half give the same result.
    pub fn analyse(a: CsMatView<'_>, ordering: &Ordering) -> Result<Self, FactorError> {
        let (indptr, indices) = pattern_of(a)?;
        let n = a.cols();
        let graph = Graph::of_lower_pattern(n, &indptr, &indices);
        // Groups of indistinguishable unknowns (such as a vertex's 2x2 block), if the
        // pattern has them: AMD runs on their graph, and so do the elimination tree and
        // the column counts whenever the order keeps each group together.
        let block = graph.uniform_block_size();
        let groups = (block > 1).then(|| graph.compressed(block));
        let order = match (ordering, &groups) {
            (Ordering::Natural, _) => (0..n).collect(),
            (Ordering::Amd, Some(groups)) => expand_groups(block, &groups.amd_order()),
            (Ordering::Amd, None) => graph.amd_order(),
            (Ordering::Amf, Some(groups)) => expand_groups(block, &groups.amf_order()),
            (Ordering::Amf, None) => graph.amf_order(),
            (Ordering::Given(order), _) => {
                if !is_permutation(order, n) {
                    return Err(FactorError::InvalidOrdering);
                }
                order.clone()
            }
        };

        let group_order = groups.as_ref().and_then(|_| group_order(block, &order));
        let (perm, parent, counts) = match (&groups, group_order) {
            (Some(groups), Some(group_order)) => {
                // A quarter of the entries for 2x2 blocks.
                let (group_perm, group_parent, group_counts) = tree_and_counts(groups, &group_order);
                expand_tree_and_counts(block, &group_perm, &group_parent, &group_counts)
            }
            _ => tree_and_counts(&graph, &order),
        };
        let inv = inverse(&perm);
        let super_start = relax_supernodes(&fundamental_supernodes(&parent, &counts), &parent, &counts);
        let ns = super_start.len() - 1;
        let mut col_to_super = vec![0; n];
        for s in 0..ns {
            col_to_super[super_start[s]..super_start[s + 1]].fill(s);
        }
        let (row_start, rows) = supernode_rows(&graph, &perm, &inv, &parent, &super_start, &col_to_super);

        let mut value_start = Vec::with_capacity(ns + 1);
        value_start.push(0);
        let mut max_update = 0;
        for s in 0..ns {
            let (width, height) = (super_start[s + 1] - super_start[s], row_start[s + 1] - row_start[s]);
            value_start.push(value_start[s] + width * height);
            max_update = max_update.max((height - width) * (height - width));
        }

        let (a_entry_start, a_entries) =
            a_entry_slots(&indptr, &indices, &inv, &super_start, &col_to_super, &row_start, &rows);
        let paired = super_start.iter().all(|&s| s % 2 == 0)
            && (0..ns).all(|s| {
                let rows = &rows[row_start[s]..row_start[s + 1]];
                rows.len() % 2 == 0 && rows.chunks_exact(2).all(|pair| pair[0] % 2 == 0 && pair[1] == pair[0] + 1)
            });
        let nnz_l = counts.iter().sum();
        let flops = counts.iter().map(|&c| (c * c) as f64).sum();
        Ok(Self {
            n,
            source_len: indices.len(),
            perm,
            a_indptr: indptr,
            a_indices: indices,
            a_entry_start,
            a_entries,
            through_map: false,
            super_start,
            col_to_super,
            row_start,
            rows,
            value_start,
            max_update,
            paired,
            nnz_l,
            flops,
        })
    }

    /// Number of unknowns.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// The elimination order (postordered): `permutation()[k]` is the original index of the
    /// k-th unknown.
    pub fn permutation(&self) -> &[usize] {
        &self.perm
    }

    /// Entries of L, diagonal included.
    pub fn nnz_l(&self) -> usize {
        self.nnz_l
    }

    /// Floating-point work of one numeric factorisation, as the sum over columns of the
    /// squared column counts of L (the usual measure).
    pub fn flops(&self) -> f64 {
        self.flops
    }

    /// Number of supernodes.
    pub fn supernode_count(&self) -> usize {
        self.super_start.len() - 1
    }

    /// Number of values stored for L (supernodal storage keeps each supernode's diagonal
    /// block square, so this is a little more than [`Self::nnz_l`]).
    pub fn stored_values(&self) -> usize {
        *self.value_start.last().expect("at least the leading zero")
    }

    /// Supernode `s`: its first column, its width, its sorted rows (own columns first) and
    /// the range of its values (column-major, one column per `rows.len()` values).
    pub(super) fn supernode(&self, s: usize) -> (usize, usize, &[usize], std::ops::Range<usize>) {
        let first = self.super_start[s];
        let rows = &self.rows[self.row_start[s]..self.row_start[s + 1]];
        (first, self.super_start[s + 1] - first, rows, self.value_start[s]..self.value_start[s + 1])
    }

    /// Whether `a` has exactly the analysed pattern.
    /// The same analysis, with refactorisations reading the analysed pattern's entry `p` (in
    /// its compressed-column order) from `source[map[p]]`, `source` having `source_len`
    /// entries: a caller whose matrix is a submatrix of another one can factor straight from
    /// the other's values, without gathering them first. Only
    /// [`super::Numeric::refactor_values`] (given the source) works on the result;
    /// [`super::Numeric::refactor`] reports [`FactorError::PatternMismatch`].
    ///
    /// Errors: [`FactorError::ValueMap`] if `map` does not have one entry per entry of the
    /// analysed pattern, or if an entry of `map` is not below `source_len`.
    pub fn reading_values_through(mut self, map: &[usize], source_len: usize) -> Result<Self, FactorError> {
        if map.len() != self.a_indices.len() || map.iter().any(|&slot| slot >= source_len) {
            return Err(FactorError::ValueMap { entries: self.a_indices.len(), source_len });
        }
        for entry in &mut self.a_entries {
            entry.1 = map[entry.1];
        }
        self.source_len = source_len;
        self.through_map = true;
        Ok(self)
    }

    pub(super) fn same_pattern(&self, a: CsMatView<'_>) -> bool {
        let offset = a.indptr().index(0);
        !self.through_map
            && a.is_csc()
            && a.rows() == self.n
            && a.cols() == self.n
            && a.indices() == self.a_indices.as_slice()
            && a.indptr().raw_storage().iter().zip(&self.a_indptr).all(|(&p, &q)| p - offset == q)
    }
}

/// The column counts of L (diagonal included) of a graph's nodes eliminated in `order`,
/// for [`super::ordering::order_flops`]: the elimination tree and column counts alone. The
/// graph is given by symmetric adjacency lists (`adj[ptr[v]..ptr[v + 1]]`, without
/// self-loops).
///
/// # Panics
/// If `order` is not a permutation of the nodes (a broken internal invariant of callers).
pub(super) fn order_column_counts(ptr: &[usize], adj: &[usize], order: &[usize]) -> Vec<usize> {
    let n = ptr.len() - 1;
    assert!(is_permutation(order, n), "order must be a permutation of the graph's nodes");
    let graph = Graph::from_adjacency(ptr, adj);
    let inv = inverse(order);
    let parent = elimination_tree(&graph, order, &inv);
    column_counts(&graph, order, &inv, &parent)
}

/// Eliminates the nodes of `graph` in `order`, then relabels by a postorder of the
/// elimination tree (the same fill, with subtrees contiguous; the tree is relabelled, not
/// recomputed). Returns the postordered permutation, the tree in its positions and the
/// column counts of L (diagonal included).
fn tree_and_counts(graph: &Graph, order: &[usize]) -> (Vec<usize>, Vec<usize>, Vec<usize>) {
    let parent_in_order = elimination_tree(graph, order, &inverse(order));
    let post = postorder(&parent_in_order);
    let perm: Vec<usize> = post.iter().map(|&k| order[k]).collect();
    let inv = inverse(&perm);
    let post_inv = inverse(&post);
    let parent: Vec<usize> =
        post.iter().map(|&k| parent_in_order[k]).map(|p| if p == NONE { NONE } else { post_inv[p] }).collect();
    let counts = column_counts(graph, &perm, &inv, &parent);
    (perm, parent, counts)
}

/// If `order` eliminates each group `b g .. b g + b` (`block` = b) together, in ascending
/// order, the order of the groups.
fn group_order(block: usize, order: &[usize]) -> Option<Vec<usize>> {
    let keeps_groups =
        order.chunks_exact(block).all(|c| c[0] % block == 0 && c.iter().enumerate().all(|(i, &v)| v == c[0] + i));
    keeps_groups.then(|| order.chunks_exact(block).map(|c| c[0] / block).collect())
}

/// The order of the unknowns that eliminates groups of `block` in `group_order`, each
/// group's unknowns together and ascending.
fn expand_groups(block: usize, group_order: &[usize]) -> Vec<usize> {
    group_order.iter().flat_map(|&g| (0..block).map(move |k| block * g + k)).collect()
}

/// The permutation, elimination tree and column counts of the unknowns from those of their
/// groups of `block` indistinguishable unknowns, eliminated together: within a group each
/// unknown's parent is the next one, the last one's is the first unknown of the parent
/// group; the k-th unknown of a group whose column in the group factor has `c` entries has
/// `block * c - k` (the group's own rows after it, and all unknowns of the other rows).
fn expand_tree_and_counts(
    block: usize,
    group_perm: &[usize],
    group_parent: &[usize],
    group_counts: &[usize],
) -> (Vec<usize>, Vec<usize>, Vec<usize>) {
    let perm = expand_groups(block, group_perm);
    let parent = group_parent
        .iter()
        .enumerate()
        .flat_map(|(j, &p)| {
            (0..block).map(move |k| match (k + 1 < block, p) {
                (true, _) => block * j + k + 1,
                (false, NONE) => NONE,
                (false, p) => block * p,
            })
        })
        .collect();
    let counts = group_counts.iter().flat_map(|&c| (0..block).map(move |k| block * c - k)).collect();
    (perm, parent, counts)
}

/// Checks shape and storage order and returns the pattern with `indptr` starting at 0.
fn pattern_of(a: CsMatView<'_>) -> Result<(Vec<usize>, Vec<usize>), FactorError> {
    if !a.is_csc() || a.rows() != a.cols() {
        return Err(FactorError::NotSquareCsc { rows: a.rows(), cols: a.cols() });
    }
    let offset = a.indptr().index(0);
    let indptr = a.indptr().raw_storage().iter().map(|&p| p - offset).collect();
    Ok((indptr, a.indices().to_vec()))
}

fn is_permutation(order: &[usize], n: usize) -> bool {
    let mut seen = vec![false; n];
    order.len() == n && order.iter().all(|&i| i < n && !std::mem::replace(&mut seen[i], true))
}

fn inverse(perm: &[usize]) -> Vec<usize> {
    let mut inv = vec![0; perm.len()];
    for (k, &i) in perm.iter().enumerate() {
        inv[i] = k;
    }
    inv
}

/// Elimination tree of the pattern eliminated in `order` (`inv` its inverse), in
/// positions of that order: `parent[k]` is the row of the first off-diagonal entry of
/// column k of L, or `NONE` for a root. Liu's algorithm: for each row k, climb from every
/// entry j < k of row k to the root of its current subtree (compressing the path to k)
/// and hang that root on k.
fn elimination_tree(graph: &Graph, order: &[usize], inv: &[usize]) -> Vec<usize> {
    let n = order.len();
    let mut parent = vec![NONE; n];
    let mut ancestor = vec![NONE; n];
    for (k, &v) in order.iter().enumerate() {
        for &w in graph.neighbors(v) {
            let mut r = inv[w];
            if r >= k {
                continue;
            }
            while ancestor[r] != NONE && ancestor[r] != k {
                let next = ancestor[r];
                ancestor[r] = k;
                r = next;
            }
            if ancestor[r] == NONE {
                ancestor[r] = k;
                parent[r] = k;
            }
        }
    }
    parent
}

/// A postorder of the forest: `post[k]` is the k-th node visited, children (in ascending
/// order) before their parent.
fn postorder(parent: &[usize]) -> Vec<usize> {
    let n = parent.len();
    let mut first_child = vec![NONE; n];
    let mut next_sibling = vec![NONE; n];
    // Insert in descending order so that each child list ends up ascending.
    for j in (0..n).rev() {
        if parent[j] != NONE {
            next_sibling[j] = first_child[parent[j]];
            first_child[parent[j]] = j;
        }
    }
    let mut post = Vec::with_capacity(n);
    let mut stack = Vec::new();
    for root in (0..n).filter(|&j| parent[j] == NONE) {
        stack.push(root);
        while let Some(&top) = stack.last() {
            let child = first_child[top];
            if child == NONE {
                post.push(top);
                stack.pop();
            } else {
                first_child[top] = next_sibling[child];
                stack.push(child);
            }
        }
    }
    post
}

/// Entries per column of L (diagonal included), by walking every row subtree: row i of
/// L is the union of the tree paths from the entries j < i of row i of `P A P^T` up to i.
fn column_counts(graph: &Graph, perm: &[usize], inv: &[usize], parent: &[usize]) -> Vec<usize> {
    let n = perm.len();
    let mut counts = vec![1; n];
    let mut mark = vec![NONE; n];
    for i in 0..n {
        mark[i] = i;
        for &w in graph.neighbors(perm[i]) {
            let mut r = inv[w];
            if r > i {
                continue;
            }
            while mark[r] != i {
                counts[r] += 1;
                mark[r] = i;
                r = parent[r];
            }
        }
    }
    counts
}

/// Fundamental supernodes: column j + 1 joins column j's supernode when j is its only
/// child and L's column j + 1 is column j's pattern without row j.
fn fundamental_supernodes(parent: &[usize], counts: &[usize]) -> Vec<usize> {
    let n = parent.len();
    let mut children = vec![0usize; n];
    for &p in parent {
        if p != NONE {
            children[p] += 1;
        }
    }
    let mut start = vec![0];
    for j in 1..n {
        let joins = parent[j - 1] == j && counts[j - 1] == counts[j] + 1 && children[j] == 1;
        if !joins {
            start.push(j);
        }
    }
    if n > 0 {
        start.push(n);
    }
    start
}

/// Amalgamates small supernodes with their parents (relaxed supernodes): merging a child
/// that ends just before its parent starts stores some explicit zeros (the child's columns
/// take the parent's row pattern) but makes the dense blocks larger, which the kernels run
/// much faster. Merges are accepted while the merged supernode is narrow or the fraction of
/// stored zeros small (the thresholds of Ashcraft and Grimes 1989, as CHOLMOD uses them).
fn relax_supernodes(start: &[usize], parent: &[usize], counts: &[usize]) -> Vec<usize> {
    let ns = start.len().saturating_sub(1);
    let mut col_to_super = vec![0; parent.len()];
    for s in 0..ns {
        col_to_super[start[s]..start[s + 1]].fill(s);
    }
    // A merged group of consecutive fundamental supernodes: first column, width, rows (of
    // its first column, own columns included), stored zeros, and its last fundamental one.
    struct Group {
        first: usize,
        width: usize,
        rows: usize,
        zeros: usize,
        last: usize,
    }
    let entries = |width: usize, rows: usize| width * rows - width * (width - 1) / 2;
    let mut groups: Vec<Group> = Vec::with_capacity(ns);
    for s in 0..ns {
        let width = start[s + 1] - start[s];
        let mut group = Group { first: start[s], width, rows: counts[start[s]], zeros: 0, last: s };
        if let Some(child) = groups.last() {
            let child_parent = parent[start[child.last + 1] - 1];
            if child_parent != NONE && col_to_super[child_parent] == s {
                let merged_width = child.width + width;
                let merged_rows = child.width + group.rows;
                let total = entries(merged_width, merged_rows);
                let kept = entries(child.width, child.rows) - child.zeros + entries(width, group.rows);
                let zeros = total - kept;
                let fraction = zeros as f64 / total as f64;
                let accept = merged_width <= 4
                    || (merged_width <= 16 && fraction < 0.8)
                    || (merged_width <= 48 && fraction < 0.1)
                    || fraction < 0.05;
                if accept {
                    let child = groups.pop().expect("checked above");
                    group = Group { first: child.first, width: merged_width, rows: merged_rows, zeros, last: s };
                }
            }
        }
        groups.push(group);
    }
    let mut relaxed: Vec<usize> = groups.iter().map(|g| g.first).collect();
    if ns > 0 {
        relaxed.push(start[ns]);
    }
    relaxed
}

/// The sorted row pattern of every supernode: its own columns, the rows of A below them,
/// and the rows of its child supernodes below them.
fn supernode_rows(
    graph: &Graph,
    perm: &[usize],
    inv: &[usize],
    parent: &[usize],
    super_start: &[usize],
    col_to_super: &[usize],
) -> (Vec<usize>, Vec<usize>) {
    let (n, ns) = (perm.len(), super_start.len().saturating_sub(1));
    // Child supernodes, as linked lists.
    let mut first_child = vec![NONE; ns];
    let mut next_sibling = vec![NONE; ns];
    for s in (0..ns).rev() {
        let p = parent[super_start[s + 1] - 1];
        if p != NONE {
            let ps = col_to_super[p];
            next_sibling[s] = first_child[ps];
            first_child[ps] = s;
        }
    }
    let mut row_start = vec![0; ns + 1];
    let mut rows: Vec<usize> = Vec::new();
    let mut mark = vec![NONE; n];
    for s in 0..ns {
        let (first, end) = (super_start[s], super_start[s + 1]);
        let begin = rows.len();
        mark[first..end].fill(s);
        rows.extend(first..end);
        for (c, &v) in perm[first..end].iter().enumerate().map(|(k, v)| (first + k, v)) {
            for r in graph.neighbors(v).iter().map(|&w| inv[w]).filter(|&r| r > c) {
                if mark[r] != s {
                    mark[r] = s;
                    rows.push(r);
                }
            }
        }
        let mut child = first_child[s];
        while child != NONE {
            for k in row_start[child]..row_start[child + 1] {
                let r = rows[k];
                if r >= end && mark[r] != s {
                    mark[r] = s;
                    rows.push(r);
                }
            }
            child = next_sibling[child];
        }
        debug_assert!(rows.len() > begin);
        row_start[s + 1] = rows.len();
    }
    let rows = sort_lists(n, &row_start, &rows);
    (row_start, rows)
}

/// The lists `values[start[s]..start[s + 1]]` of indices below `n`, each sorted, without
/// comparisons: transposing twice (list of lists for each index, then back) visits the
/// indices in ascending order.
fn sort_lists(n: usize, start: &[usize], values: &[usize]) -> Vec<usize> {
    let lists = start.len() - 1;
    let mut count = vec![0; n];
    for &v in values {
        count[v] += 1;
    }
    let by_value_start = prefix_sums(&count);
    let mut next = by_value_start[..n].to_vec();
    let mut by_value = vec![0; values.len()];
    for s in 0..lists {
        for &v in &values[start[s]..start[s + 1]] {
            by_value[next[v]] = s;
            next[v] += 1;
        }
    }
    let mut next = start[..lists].to_vec();
    let mut sorted = vec![0; values.len()];
    for v in 0..n {
        for &s in &by_value[by_value_start[v]..by_value_start[v + 1]] {
            sorted[next[s]] = v;
            next[s] += 1;
        }
    }
    sorted
}

/// For every entry of the lower triangle of `A` (index `p` in its data), its offset in the
/// values of the supernode of L that holds it, grouped by supernode (counting sort): `(a_entry_start, a_entries)` as stored in [`Symbolic`].
fn a_entry_slots(
    indptr: &[usize],
    indices: &[usize],
    inv: &[usize],
    super_start: &[usize],
    col_to_super: &[usize],
    row_start: &[usize],
    rows: &[usize],
) -> (Vec<usize>, Vec<(usize, usize)>) {
    let (n, ns) = (inv.len(), super_start.len() - 1);
    // (row, column) in L of entry p, or None above the diagonal.
    let place = |j: usize, p: usize| {
        let i = indices[p];
        (i >= j).then(|| (inv[i].max(inv[j]), inv[i].min(inv[j])))
    };
    let mut count = vec![0; ns];
    for j in 0..n {
        for p in indptr[j]..indptr[j + 1] {
            if let Some((_, c)) = place(j, p) {
                count[col_to_super[c]] += 1;
            }
        }
    }
    let start = prefix_sums(&count);
    let mut next = start[..ns].to_vec();
    // First (row, column, p) per supernode, then the offsets.
    let mut placed = vec![(0, 0, 0); start[ns]];
    for j in 0..n {
        for p in indptr[j]..indptr[j + 1] {
            if let Some((r, c)) = place(j, p) {
                let s = col_to_super[c];
                placed[next[s]] = (r, c, p);
                next[s] += 1;
            }
        }
    }
    let mut position = vec![0; n];
    let mut entries = Vec::with_capacity(placed.len());
    for s in 0..ns {
        let s_rows = &rows[row_start[s]..row_start[s + 1]];
        for (k, &r) in s_rows.iter().enumerate() {
            position[r] = k;
        }
        entries.extend(placed[start[s]..start[s + 1]].iter().map(|&(r, c, p)| {
            debug_assert_eq!(s_rows[position[r]], r, "every entry of A lies in the pattern of L");
            ((c - super_start[s]) * s_rows.len() + position[r], p)
        }));
    }
    (start, entries)
}
