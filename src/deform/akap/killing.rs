//! The Killing energy of a piecewise-linear vector field on a triangle mesh, as a sparse
//! symmetric matrix: the paper's eq. (2), `E_K(U) = integral of ||J + J^T||_F^2` (`J` the
//! field's Jacobian), discretised as its eqs. (5)-(7) say, with finite elements.
//!
//! Unknowns are interleaved per vertex: `U = [u1_0, u2_0, u1_1, u2_1, ...]`. On triangle f
//! with area `A_f`, the Jacobian `J = [grad U1; grad U2] = [a b; c d]` is constant and
//! `||J + J^T||_F^2 = 4a^2 + 2(b + c)^2 + 4d^2`, so `E_f(U) = A_f (4a^2 + 2(b + c)^2 + 4d^2)`
//! and `E(U) = U^T K U` with `K = sum_f A_f R_f^T R_f`, `R_f` the 3 x 6 matrix of rows
//! `2 gx.U1`, `sqrt2 (gy.U1 + gx.U2)`, `2 gy.U2` over the triangle's six unknowns. These rows
//! are what eq. (6)'s schematic `P = [2G 0; sqrt2 G sqrt2 G; 0 2G]` stands for (the middle
//! row takes the y-derivative of `U1` and the x-derivative of `U2`, not `G` twice), each
//! weighted by `sqrt(A_f)`: `K = P^T P`, the matrix of eq. (7) without the handles.
//!
//! The pattern (a 2 x 2 block for every vertex and every pair of vertices sharing an
//! edge) is fixed by the mesh; values depend on the current positions (the paper's `G` is
//! the current mesh's, so `K` changes every frame and its pattern never does, Section 3.1)
//! and are recomputed every frame by [`KillingMatrix::assemble`] without allocating.

use sprs::CsMat;

use crate::deform::pattern::BlockPattern;
use crate::geometry::{binary_exponent, in_comfortable_range, scale_by_power_of_two, Point};
use crate::mesh::Mesh;

/// The Killing-energy matrix of a mesh: fixed pattern, values for given positions.
#[derive(Debug, Clone)]
pub struct KillingMatrix {
    /// Full symmetric storage (both triangles), compressed sparse columns, `2n x 2n`.
    matrix: CsMat<f64>,
    triangles: Vec<[u32; 3]>,
    /// For triangle t and local vertices (i, j): the slots in `matrix.data()` of the entries
    /// `(2 v_i + k, 2 v_j)` for k = 0, 1 (`[t][3 i + j][0]`) and `(2 v_i + k, 2 v_j + 1)`
    /// (`[t][3 i + j][1]`); row k = 1 is the slot after row k = 0.
    slots: Vec<[[usize; 2]; 9]>,
    /// Each triangle's stiffness, the factor on its energy (`None`: 1 everywhere, and no
    /// multiplication at all).
    stiffness: Option<Vec<f64>>,
    /// The weight of the rotation term a puppet's sheets get (0: none, and no work at all).
    turn_weight: f64,
}

impl KillingMatrix {
    /// Builds the pattern for a mesh (values are zero until [`Self::assemble`]).
    pub fn new(mesh: &Mesh) -> Self {
        Self::with_pairs(mesh, &[])
    }

    /// Builds the pattern for a mesh and the extra vertex pairs `extra` (sorted, both
    /// orders of each pair: a puppet's joints, whose entries [`Self::data_mut`] adds after
    /// each [`Self::assemble`]).
    pub(crate) fn with_pairs(mesh: &Mesh, extra: &[[u32; 2]]) -> Self {
        // Column 2v and 2v + 1 hold rows 2w, 2w + 1 for w in N(v), v itself and v's extra
        // pairs, ascending.
        let pattern = BlockPattern::with_pairs(mesh, 2, extra);
        let slots = pattern
            .triangle_slots(mesh)
            .into_iter()
            .zip(mesh.triangles())
            .map(|(first, t)| {
                let mut s = [[0; 2]; 9];
                for (k, (slot, &first)) in s.iter_mut().zip(&first).enumerate() {
                    // The block's entries in column 2 v_j, then in column 2 v_j + 1.
                    *slot = [first, first + pattern.column_length(t[k % 3] as usize)];
                }
                s
            })
            .collect();
        let nnz = pattern.nnz();
        let matrix = pattern.matrix(vec![0.0; nnz]);
        Self { matrix, triangles: mesh.triangles().to_vec(), slots, stiffness: None, turn_weight: 0.0 }
    }

    /// Recomputes the values, `K = P^T P` of eqs. (6)-(7), for vertex positions `positions`
    /// (same vertex count as the
    /// mesh). Any positions will do: each triangle's energy is weighted by its unsigned area
    /// (the integral of a square over it), so the matrix is positive semidefinite for flipped
    /// triangles too, and no triangle counts as thinner than [`SLIVER_LIMIT`] (see there), so
    /// its entries stay finite.
    pub fn assemble(&mut self, positions: &[Point]) {
        let data = self.matrix.data_mut();
        data.fill(0.0);
        for (f, (t, slots)) in self.triangles.iter().zip(&self.slots).enumerate() {
            let corners = [positions[t[0] as usize], positions[t[1] as usize], positions[t[2] as usize]];
            let Some((mut h, g)) = scaled_gradients(corners) else { continue };
            if let Some(stiffness) = &self.stiffness {
                // The energy's factor on this face: `h = 2A g` carries the area weight.
                h = h.map(|hi| hi.map(|x| x * stiffness[f]));
            }
            // A R^T R entry by entry: for vertices (i, j), with h = 2A g,
            //   (u1_i, u1_j): A (4 gx_i gx_j + 2 gy_i gy_j) = 2 h_x,i g_x,j + h_y,i g_y,j
            //   (u2_i, u1_j): 2A gx_i gy_j                   = h_x,i g_y,j
            //   (u1_i, u2_j): 2A gy_i gx_j                   = h_y,i g_x,j
            //   (u2_i, u2_j): A (2 gx_i gx_j + 4 gy_i gy_j) = h_x,i g_x,j + 2 h_y,i g_y,j
            for (i, hi) in h.iter().enumerate() {
                for (j, gj) in g.iter().enumerate() {
                    let [c0, c1] = slots[3 * i + j];
                    let (xx, yy) = (hi[0] * gj[0], hi[1] * gj[1]);
                    // Rows (2 v_i, 2 v_i + 1), columns (2 v_j, 2 v_j + 1).
                    data[c0] += 2.0 * xx + yy;
                    data[c0 + 1] += hi[0] * gj[1];
                    data[c1] += hi[1] * gj[0];
                    data[c1 + 1] += xx + 2.0 * yy;
                }
            }
            if self.turn_weight != 0.0 {
                // The rotation term `w A curl(U)^2`, `curl = gx.U2 - gy.U1`, entry by entry
                // with `A g_i g_j = h_i g_j / 2`.
                let w = 0.5 * self.turn_weight;
                for (i, hi) in h.iter().enumerate() {
                    for (j, gj) in g.iter().enumerate() {
                        let [c0, c1] = slots[3 * i + j];
                        data[c0] += w * hi[1] * gj[1];
                        data[c0 + 1] -= w * hi[0] * gj[1];
                        data[c1] -= w * hi[1] * gj[0];
                        data[c1 + 1] += w * hi[0] * gj[0];
                    }
                }
            }
        }
    }

    /// Sets each triangle's stiffness (one per triangle, checked by the caller), or 1
    /// everywhere with `None`. The next [`Self::assemble`] uses it.
    pub fn set_stiffness(&mut self, stiffness: Option<Vec<f64>>) {
        self.stiffness = stiffness;
    }

    /// Adds `weight` times the integral of the field's curl squared (its rotation) to the
    /// energy from the next [`Self::assemble`]: a puppet's sheets held by one hinge alone
    /// then follow it without turning (see `deform::puppet`). 0, the default, adds nothing.
    pub(crate) fn set_turn_weight(&mut self, weight: f64) {
        self.turn_weight = weight;
    }

    /// Each triangle's stiffness, if set.
    pub fn stiffness(&self) -> Option<&[f64]> {
        self.stiffness.as_deref()
    }

    /// The matrix (full symmetric storage, CSC).
    pub fn matrix(&self) -> &CsMat<f64> {
        &self.matrix
    }

    /// The matrix's values, to add terms of the same pattern to after [`Self::assemble`].
    pub(crate) fn data_mut(&mut self) -> &mut [f64] {
        self.matrix.data_mut()
    }

    /// Slots in the matrix's data of the 2 x 2 block at vertices `(row, col)`, as
    /// `[[(2r, 2c), (2r + 1, 2c)], [(2r, 2c + 1), (2r + 1, 2c + 1)]]`, if the block is in the
    /// pattern (the vertices are equal or share an edge).
    pub fn block_slots(&self, row: usize, col: usize) -> Option<[[usize; 2]; 2]> {
        let indptr = self.matrix.indptr();
        let (start, end) = (indptr.index(2 * col), indptr.index(2 * col + 1));
        let rows = &self.matrix.indices()[start..end];
        let pos = rows.binary_search(&(2 * row)).ok()?;
        let second = indptr.index(2 * col + 1) + pos;
        Some([[start + pos, start + pos + 1], [second, second + 1]])
    }
}

/// The smallest area a triangle counts with in [`KillingMatrix::assemble`], as a fraction
/// of the square of its longest edge (an equilateral triangle has 0.43, a triangle with a
/// 0.01 degree angle about 1e-4).
///
/// A triangle's Killing energy is `|S|^2 / (4 |A|)`, with `S` bilinear in its edge vectors
/// and the field, so it grows without bound as the triangle collapses: at zero area the
/// matrix would hold infinities, and near it entries large enough to ruin the
/// factorisation's accuracy. Thinner triangles are treated as if their area were this
/// bound (same edges, same orientation): their energy is capped at `1 / SLIVER_LIMIT`
/// times that of a well-shaped triangle with the same edges. Triangles above it are
/// untouched. A triangle collapsed to a point has no energy.
pub const SLIVER_LIMIT: f64 = 1e-6;

/// For a triangle, `(h, g)` with `g_i` the gradient of its barycentric basis function i and
/// `h_i = 2A g_i = rot90(e_i)`, `e_i` the edge opposite corner i; A is the area, unsigned
/// and bounded below by [`SLIVER_LIMIT`] times the longest edge squared. `None` for a
/// triangle collapsed to a point. The gradients' common sign (that of the orientation) is
/// left out: the energy takes them in products of two.
///
/// The matrix's entries are products `h_i g_j`, which do not change when the triangle is
/// scaled (`h` scales with it, `g` inversely). Edges outside the comfortable range (about
/// 1e-75 to 1e75) are first scaled by the power of two that brings their largest component
/// into [1, 2): exact, so the entries are the same, and free of overflow and underflow in
/// the squares and areas whatever the mesh's scale. (Within it, scaling would change no bit.)
fn scaled_gradients(p: [Point; 3]) -> Option<([Point; 3], [Point; 3])> {
    let h = [0, 1, 2].map(|i| {
        let (b, c) = (p[(i + 1) % 3], p[(i + 2) % 3]);
        [b[1] - c[1], c[0] - b[0]]
    });
    let largest = h.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    if largest == 0.0 || !largest.is_finite() {
        return None;
    }
    let h = if in_comfortable_range(largest) {
        h
    } else {
        let k = -binary_exponent(largest);
        h.map(|v| v.map(|x| scale_by_power_of_two(x, k)))
    };
    let length = |v: Point| v[0] * v[0] + v[1] * v[1];
    let longest = length(h[0]).max(length(h[1])).max(length(h[2]));
    let twice_area = (h[1][0] * h[2][1] - h[1][1] * h[2][0]).abs().max(2.0 * SLIVER_LIMIT * longest);
    let inverse = 1.0 / twice_area;
    Some((h, h.map(|v| [v[0] * inverse, v[1] * inverse])))
}
