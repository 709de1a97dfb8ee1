//! The sparsity pattern every deformer's matrix has: a `block x block` block for every vertex
//! and every pair of vertices sharing an edge (AKAP's Killing matrix: 2 x 2 blocks, one row
//! and column per velocity component; ARAP's Laplacian: 1 x 1), and for a puppet every pair
//! of vertices a joint couples, in full symmetric storage,
//! compressed sparse columns, with the slots of each triangle's entries found once.

use sprs::CsMat;

use crate::mesh::Mesh;

/// The pattern of a matrix of `block x block` blocks on a mesh's vertex graph: column
/// `block v + l` holds the rows `block w + k` (`k` ascending) of `w` in `v`'s neighbours and
/// `v` itself, ascending. Every column of a vertex has the same rows.
#[derive(Debug, Clone)]
pub(crate) struct BlockPattern {
    block: usize,
    indptr: Vec<usize>,
    indices: Vec<usize>,
}

impl BlockPattern {
    /// The pattern of `mesh`'s vertex graph with `block` unknowns per vertex.
    pub(crate) fn new(mesh: &Mesh, block: usize) -> Self {
        Self::with_pairs(mesh, block, &[])
    }

    /// The pattern of `mesh`'s vertex graph and of the vertex pairs `extra` (sorted, both
    /// orders of each pair given: a puppet's joints), with `block` unknowns per vertex.
    pub(crate) fn with_pairs(mesh: &Mesh, block: usize, extra: &[[u32; 2]]) -> Self {
        let n = mesh.vertex_count();
        let mut indptr = Vec::with_capacity(block * n + 1);
        let mut indices = Vec::new();
        indptr.push(0);
        let mut rows = Vec::new();
        let mut at = 0;
        for v in 0..n {
            rows.clear();
            rows.extend(mesh.neighbors(v).iter().map(|&w| w as usize));
            rows.push(v);
            while at < extra.len() && extra[at][0] as usize == v {
                rows.push(extra[at][1] as usize);
                at += 1;
            }
            rows.sort_unstable();
            rows.dedup();
            let start = indices.len();
            for &w in &rows {
                indices.extend((0..block).map(|k| block * w + k));
            }
            indptr.push(indices.len());
            for _ in 1..block {
                indices.extend_from_within(start..indptr[indptr.len() - 1]);
                indptr.push(indices.len());
            }
        }
        Self { block, indptr, indices }
    }

    /// The slot, in the matrix's data, of the first entry of the block at vertices
    /// `(row, col)`, `(block row, block col)`, if the block is in the pattern (the vertices
    /// are equal or share an edge). Entry `(block row + k, block col + l)` is `l` columns'
    /// lengths ([`Self::column_length`]) and `k` slots further on.
    pub(crate) fn slot(&self, row: usize, col: usize) -> Option<usize> {
        let (start, end) = (self.indptr[self.block * col], self.indptr[self.block * col + 1]);
        let pos = self.indices[start..end].binary_search(&(self.block * row)).ok()?;
        Some(start + pos)
    }

    /// The number of entries in each column of vertex `col`.
    pub(crate) fn column_length(&self, col: usize) -> usize {
        self.indptr[self.block * col + 1] - self.indptr[self.block * col]
    }

    /// Per triangle, [`Self::slot`] of its 9 vertex pairs `(v[i], v[j])`, at index `3 i + j`.
    pub(crate) fn triangle_slots(&self, mesh: &Mesh) -> Vec<[usize; 9]> {
        mesh.triangles()
            .iter()
            .map(|t| {
                let mut slots = [0; 9];
                for i in 0..3 {
                    for j in 0..3 {
                        slots[3 * i + j] =
                            self.slot(t[i] as usize, t[j] as usize).expect("vertices of one triangle share an edge");
                    }
                }
                slots
            })
            .collect()
    }

    /// The matrix with this pattern and the given values (one per entry).
    pub(crate) fn matrix(self, values: Vec<f64>) -> CsMat<f64> {
        let size = self.indptr.len() - 1;
        CsMat::new_csc((size, size), self.indptr, self.indices, values)
    }

    /// The number of entries.
    pub(crate) fn nnz(&self) -> usize {
        self.indices.len()
    }
}
