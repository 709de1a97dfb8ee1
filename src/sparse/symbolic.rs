//! Symbolic analysis: everything about the factor `L` of `P A P^T = L L^T` that depends
//! only on the sparsity pattern of `A`, computed once per pattern.
//!
//! Steps and costs (n unknowns, |A| entries of the lower triangle, |L| entries of L):
//! 1. fill-reducing order (AMD, or given), O(|A|) in practice;
//! 2. elimination tree of the permuted pattern (Liu's algorithm with path compression),
//!    O(|A| log n), and its postorder, which is folded into the permutation so that every
//!    subtree, and so every supernode, is a contiguous range of columns;
//! 3. column counts of L by walking each row subtree (row i of L is the union of the etree
//!    paths from the entries of row i of A up to i), O(|L|);
//! 4. fundamental supernodes (a column joins its only child's supernode when it is that
//!    child's parent and its count is one less) and the sorted row pattern of each
//!    supernode: its columns, the rows of A below them and the rows of its child
//!    supernodes below them, O(|L|) plus sorting;
//! 5. a map from every lower-triangle entry of A to its slot in the supernodal storage of L.

use super::{amd_order, CsMatView, FactorError, Ordering};

const NONE: usize = usize::MAX;

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
        let order = match ordering {
            Ordering::Natural => (0..n).collect(),
            Ordering::Amd => {
                let (ptr, adj) = symmetric_adjacency(n, &indptr, &indices);
                amd_order(n, &ptr, &adj)
            }
            Ordering::Given(order) => {
                if !is_permutation(order, n) {
                    return Err(FactorError::InvalidOrdering);
                }
                order.clone()
            }
        };

        // Eliminate in the given order, then relabel by a postorder of the elimination
        // tree: the same fill, with subtrees contiguous.
        let lower = permuted_lower(n, &indptr, &indices, &inverse(&order));
        let parent = elimination_tree(n, &lower);
        let post = postorder(&parent);
        let perm: Vec<usize> = post.iter().map(|&k| order[k]).collect();
        let inv = inverse(&perm);
        let lower = permuted_lower(n, &indptr, &indices, &inv);
        let parent = elimination_tree(n, &lower);

        let counts = column_counts(n, &lower, &parent);
        let super_start = relax_supernodes(&fundamental_supernodes(&parent, &counts), &parent, &counts);
        let ns = super_start.len() - 1;
        let mut col_to_super = vec![0; n];
        for s in 0..ns {
            col_to_super[super_start[s]..super_start[s + 1]].fill(s);
        }
        let (row_start, rows) = supernode_rows(n, &lower, &parent, &super_start, &col_to_super);

        let mut value_start = Vec::with_capacity(ns + 1);
        value_start.push(0);
        let mut max_update = 0;
        for s in 0..ns {
            let (width, height) = (super_start[s + 1] - super_start[s], row_start[s + 1] - row_start[s]);
            value_start.push(value_start[s] + width * height);
            max_update = max_update.max((height - width) * (height - width));
        }

        let mut by_super: Vec<(usize, usize, usize)> = Vec::with_capacity(indices.len());
        for j in 0..n {
            for (p, &i) in indices.iter().enumerate().take(indptr[j + 1]).skip(indptr[j]) {
                if i < j {
                    continue;
                }
                let (r, c) = (inv[i].max(inv[j]), inv[i].min(inv[j]));
                let s = col_to_super[c];
                let s_rows = &rows[row_start[s]..row_start[s + 1]];
                let pos = s_rows.binary_search(&r).expect("every entry of A lies in the pattern of L");
                by_super.push((s, (c - super_start[s]) * s_rows.len() + pos, p));
            }
        }
        by_super.sort_unstable();
        let mut a_entry_start = vec![0; ns + 1];
        for &(s, _, _) in &by_super {
            a_entry_start[s + 1] += 1;
        }
        for s in 0..ns {
            a_entry_start[s + 1] += a_entry_start[s];
        }
        let a_entries = by_super.into_iter().map(|(_, offset, p)| (offset, p)).collect();

        let nnz_l = counts.iter().sum();
        let flops = counts.iter().map(|&c| (c * c) as f64).sum();
        Ok(Self {
            n,
            perm,
            a_indptr: indptr,
            a_indices: indices,
            a_entry_start,
            a_entries,
            super_start,
            col_to_super,
            row_start,
            rows,
            value_start,
            max_update,
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
    pub(super) fn same_pattern(&self, a: CsMatView<'_>) -> bool {
        let offset = a.indptr().index(0);
        a.is_csc()
            && a.rows() == self.n
            && a.cols() == self.n
            && a.indices() == self.a_indices.as_slice()
            && a.indptr().raw_storage().iter().zip(&self.a_indptr).all(|(&p, &q)| p - offset == q)
    }
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

/// The off-diagonal pattern of the lower triangle made symmetric, for the ordering.
fn symmetric_adjacency(n: usize, indptr: &[usize], indices: &[usize]) -> (Vec<usize>, Vec<usize>) {
    let mut count = vec![0; n + 1];
    for j in 0..n {
        for &i in &indices[indptr[j]..indptr[j + 1]] {
            if i > j {
                count[i] += 1;
                count[j] += 1;
            }
        }
    }
    let ptr = prefix_sums(&count[..n]);
    let mut next = ptr.clone();
    let mut adj = vec![0; ptr[n]];
    for j in 0..n {
        for &i in &indices[indptr[j]..indptr[j + 1]] {
            if i > j {
                adj[next[i]] = j;
                next[i] += 1;
                adj[next[j]] = i;
                next[j] += 1;
            }
        }
    }
    (ptr, adj)
}

fn prefix_sums(count: &[usize]) -> Vec<usize> {
    let mut ptr = Vec::with_capacity(count.len() + 1);
    ptr.push(0);
    for &c in count {
        ptr.push(ptr.last().expect("non-empty") + c);
    }
    ptr
}

/// The strictly-lower pattern of `P A P^T` stored both ways: by row (`row_ptr`, the
/// columns `j < i` of row `i`) and by column (`col_ptr`, the rows `i > j` of column `j`).
/// Duplicates may remain; they do no harm below.
pub(super) struct LowerPattern {
    row_ptr: Vec<usize>,
    row_cols: Vec<usize>,
    col_ptr: Vec<usize>,
    col_rows: Vec<usize>,
}

fn permuted_lower(n: usize, indptr: &[usize], indices: &[usize], inv: &[usize]) -> LowerPattern {
    let mut entries: Vec<(usize, usize)> = Vec::with_capacity(indices.len());
    for j in 0..n {
        for &i in &indices[indptr[j]..indptr[j + 1]] {
            if i > j {
                let (r, c) = (inv[i].max(inv[j]), inv[i].min(inv[j]));
                entries.push((r, c));
            }
        }
    }
    let mut row_count = vec![0; n];
    let mut col_count = vec![0; n];
    for &(r, c) in &entries {
        row_count[r] += 1;
        col_count[c] += 1;
    }
    let row_ptr = prefix_sums(&row_count);
    let col_ptr = prefix_sums(&col_count);
    let (mut row_next, mut col_next) = (row_ptr.clone(), col_ptr.clone());
    let mut row_cols = vec![0; entries.len()];
    let mut col_rows = vec![0; entries.len()];
    for &(r, c) in &entries {
        row_cols[row_next[r]] = c;
        row_next[r] += 1;
        col_rows[col_next[c]] = r;
        col_next[c] += 1;
    }
    LowerPattern { row_ptr, row_cols, col_ptr, col_rows }
}

impl LowerPattern {
    fn row(&self, i: usize) -> &[usize] {
        &self.row_cols[self.row_ptr[i]..self.row_ptr[i + 1]]
    }

    fn col(&self, j: usize) -> &[usize] {
        &self.col_rows[self.col_ptr[j]..self.col_ptr[j + 1]]
    }
}

/// Elimination tree: `parent[j]` is the row of the first off-diagonal entry of column j
/// of L, or `NONE` for a root. Liu's algorithm: for each row i, climb from every entry j of
/// row i to the root of its current subtree (compressing the path to i) and hang it on i.
fn elimination_tree(n: usize, lower: &LowerPattern) -> Vec<usize> {
    let mut parent = vec![NONE; n];
    let mut ancestor = vec![NONE; n];
    for i in 0..n {
        for &j in lower.row(i) {
            let mut r = j;
            while ancestor[r] != NONE && ancestor[r] != i {
                let next = ancestor[r];
                ancestor[r] = i;
                r = next;
            }
            if ancestor[r] == NONE {
                ancestor[r] = i;
                parent[r] = i;
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

/// Entries per column of L (diagonal included), by walking every row subtree.
fn column_counts(n: usize, lower: &LowerPattern, parent: &[usize]) -> Vec<usize> {
    let mut counts = vec![1; n];
    let mut mark = vec![NONE; n];
    for i in 0..n {
        mark[i] = i;
        for &j in lower.row(i) {
            let mut r = j;
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
    n: usize,
    lower: &LowerPattern,
    parent: &[usize],
    super_start: &[usize],
    col_to_super: &[usize],
) -> (Vec<usize>, Vec<usize>) {
    let ns = super_start.len().saturating_sub(1);
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
        for c in first..end {
            for &r in lower.col(c) {
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
        rows[begin..].sort_unstable();
        row_start[s + 1] = rows.len();
    }
    (row_start, rows)
}
