//! The spatial basis Φ of a deformation operator (paper §3.1; notes §1) and the matrices it
//! needs: the hat functions φ̃_i of the mesh (|Φ| = N), or a reduced basis Φ = D Φ̃ given by
//! nodal values D (|Φ| × N, M-orthonormal: D A Dᵀ = I, with 1, x, y in its span); the
//! consistent mass matrix A_ii' = ∫ φ̃_i φ̃_i' (per triangle A_t/12 · `[[2,1,1],[1,2,1],[1,1,2]]`,
//! App. A), the lumped mass, and the linearly precise Laplacian K = L + N_b of Wang,
//! Jacobson, Barbič and Kavan (2015), which annihilates 1, x and y, whose bilaplacian
//! Kᵀ M_l⁻¹ K yields the reduced basis. Handles are [`MeshPoint`]s: a vertex, or a point of a
//! triangle given by barycentric coordinates, where the hat functions are those coordinates.

use std::collections::HashMap;

use nalgebra::DMatrix;
use sprs::{CsMat, TriMat};

use super::fit_error::FitError;
use crate::geometry::Point;
use crate::mesh::Mesh;
use crate::sparse::eigen::m_orthonormal;
use crate::sparse::mul_into;

pub use crate::mesh::MeshPoint;

/// A mesh point resolved to the hat functions that are not zero there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct HatValues {
    pub(crate) vertices: [usize; 3],
    pub(crate) weights: [f64; 3],
}

impl HatValues {
    pub(crate) fn position(&self, mesh: &Mesh) -> Point {
        let p = mesh.positions();
        let mut out = [0.0; 2];
        for (&v, &w) in self.vertices.iter().zip(&self.weights) {
            out[0] += w * p[v][0];
            out[1] += w * p[v][1];
        }
        out
    }
}

/// Checks `points` against `mesh` (as the deformers check handles: `deform::handles`)
/// and returns their hat values.
pub(crate) fn resolve_points(mesh: &Mesh, points: &[MeshPoint]) -> Result<Vec<HatValues>, FitError> {
    let resolved = crate::deform::handles::resolve(mesh, points).map_err(FitError::InvalidHandle)?;
    Ok(resolved.iter().map(|p| HatValues { vertices: p.vertices.map(|v| v as usize), weights: p.weights }).collect())
}

/// The consistent mass matrix A of the hat functions (N × N, symmetric, compressed sparse
/// column): per triangle A_t/12 · `[[2,1,1],[1,2,1],[1,1,2]]`.
pub fn consistent_mass(mesh: &Mesh) -> CsMat<f64> {
    let n = mesh.vertex_count();
    let mut tri = TriMat::with_capacity((n, n), 9 * mesh.triangle_count());
    for t in mesh.triangles() {
        let area = mesh.signed_triangle_area(t);
        for (a, &i) in t.iter().enumerate() {
            for (b, &j) in t.iter().enumerate() {
                let factor = if a == b { 2.0 } else { 1.0 };
                tri.add_triplet(i as usize, j as usize, factor * area / 12.0);
            }
        }
    }
    tri.to_csc()
}

/// The lumped mass: a third of the area of every triangle at each vertex.
pub fn lumped_mass(mesh: &Mesh) -> Vec<f64> {
    let mut mass = vec![0.0; mesh.vertex_count()];
    for t in mesh.triangles() {
        let third = mesh.signed_triangle_area(t) / 3.0;
        for &v in t {
            mass[v as usize] += third;
        }
    }
    mass
}

/// Half the cotangent of the angle at corner `a` of the triangle (a, b, c).
fn half_cot(a: Point, b: Point, c: Point) -> f64 {
    let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - a[0], c[1] - a[1]]);
    0.5 * (u[0] * v[0] + u[1] * v[1]) / (u[0] * v[1] - u[1] * v[0]).abs()
}

/// The linearly precise Laplacian K = L + N_b (N × N, not symmetric, compressed sparse
/// column) of Wang et al. (2015): L the cotangent Laplacian with half-cotangent weights
/// (negative semidefinite), N_b the normal derivative at the boundary, so that K·1 = K·x =
/// K·y = 0. For a boundary edge i → p with opposite vertex q and half-cotangents c_i, c_p at
/// corners i and p, row p gets (q, −c_i − c_p), (p, c_i), (i, c_p) and row i gets
/// (q, −c_p − c_i), (i, c_p), (p, c_i).
pub fn linearly_precise_laplacian(mesh: &Mesh) -> CsMat<f64> {
    let n = mesh.vertex_count();
    let p = mesh.positions();
    let boundary: HashMap<[u32; 2], ()> = mesh.boundary_edges().iter().map(|&e| (e, ())).collect();
    let mut tri = TriMat::with_capacity((n, n), 12 * mesh.triangle_count());
    for t in mesh.triangles() {
        for k in 0..3 {
            let (i, j, q) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
            let (iu, ju, qu) = (i as usize, j as usize, q as usize);
            // Cotangent Laplacian: the corner at q weighs the edge (i, j).
            let w = half_cot(p[qu], p[iu], p[ju]);
            tri.add_triplet(iu, ju, w);
            tri.add_triplet(ju, iu, w);
            tri.add_triplet(iu, iu, -w);
            tri.add_triplet(ju, ju, -w);
            if boundary.contains_key(&[i, j]) {
                let (ci, cp) = (half_cot(p[iu], p[ju], p[qu]), half_cot(p[ju], p[qu], p[iu]));
                for (row, other) in [(ju, iu), (iu, ju)] {
                    let (own, far) = if row == ju { (ci, cp) } else { (cp, ci) };
                    tri.add_triplet(row, qu, -(ci + cp));
                    tri.add_triplet(row, row, own);
                    tri.add_triplet(row, other, far);
                }
            }
        }
    }
    tri.to_csc()
}

/// The spatial basis Φ of a deformation operator.
#[derive(Debug, Clone, PartialEq)]
pub struct SpatialBasis {
    vertex_count: usize,
    /// The nodal values D (|Φ| × N) of a reduced basis; `None` for the hat functions.
    reduction: Option<DMatrix<f64>>,
}

impl SpatialBasis {
    /// The hat functions of `mesh`: |Φ| = N, D = I.
    pub fn hat(mesh: &Mesh) -> Self {
        Self { vertex_count: mesh.vertex_count(), reduction: None }
    }

    /// A reduced basis with nodal values `d` (|Φ| × N): checks that it is M-orthonormal
    /// (D A Dᵀ = I to 1e-8) and reproduces 1, x and y (to 1e-8 of the mesh's size).
    pub fn reduced(mesh: &Mesh, d: DMatrix<f64>) -> Result<Self, FitError> {
        let n = mesh.vertex_count();
        if d.ncols() != n || d.nrows() == 0 {
            return Err(FitError::Length { what: "reduced basis", expected: n, found: d.ncols() });
        }
        if let Some(index) = d.iter().position(|x| !x.is_finite()) {
            return Err(FitError::NonFinite { what: "reduced basis", index });
        }
        let a = consistent_mass(mesh);
        let ad = mass_times_rows(&a, &d);
        let m = &d * ad.transpose();
        let identity = DMatrix::<f64>::identity(d.nrows(), d.nrows());
        if (m - identity).amax() > 1e-8 {
            return Err(FitError::InvalidSpatialBasis { reason: "D A Dᵀ is not the identity" });
        }
        let scale = extent(mesh);
        for coordinate in linear_functions(mesh) {
            let c = &ad * nalgebra::DVector::from_column_slice(&coordinate);
            let back = d.transpose() * c;
            let error = back.iter().zip(&coordinate).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
            if error > 1e-8 * scale {
                return Err(FitError::InvalidSpatialBasis { reason: "1, x and y are not in its span" });
            }
        }
        Ok(Self { vertex_count: n, reduction: Some(d) })
    }

    /// A reduced basis spanning 1, x, y and `extra` (nodal vectors, N numbers each), in that
    /// order, made M-orthonormal by Gram–Schmidt in the mass matrix's inner product (twice).
    pub fn orthonormalised(mesh: &Mesh, extra: &[Vec<f64>]) -> Result<Self, FitError> {
        let n = mesh.vertex_count();
        let a = consistent_mass(mesh);
        let mut vectors = linear_functions(mesh);
        for v in extra {
            if v.len() != n {
                return Err(FitError::Length { what: "basis vector", expected: n, found: v.len() });
            }
            vectors.push(v.clone());
        }
        let done = m_orthonormal(a.view(), &vectors)
            .ok_or(FitError::InvalidSpatialBasis { reason: "the vectors are linearly dependent" })?;
        let d = DMatrix::from_fn(done.len(), n, |i, j| done[i][j]);
        Ok(Self { vertex_count: n, reduction: Some(d) })
    }

    /// The number of functions |Φ|.
    pub fn len(&self) -> usize {
        self.reduction.as_ref().map_or(self.vertex_count, |d| d.nrows())
    }

    /// Always false: a mesh has vertices.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The number of mesh vertices N.
    pub fn vertex_count(&self) -> usize {
        self.vertex_count
    }

    /// The nodal values D of a reduced basis (`None` for the hat functions, D = I).
    pub fn reduction(&self) -> Option<&DMatrix<f64>> {
        self.reduction.as_ref()
    }

    /// Φ(p) for every handle: the |Φ| × n matrix Φ_P.
    pub(crate) fn at_points(&self, points: &[HatValues]) -> DMatrix<f64> {
        let mut phi = DMatrix::zeros(self.len(), points.len());
        for (l, point) in points.iter().enumerate() {
            for (&v, &w) in point.vertices.iter().zip(&point.weights) {
                match &self.reduction {
                    None => phi[(v, l)] += w,
                    Some(d) => {
                        let mut column = phi.column_mut(l);
                        column.axpy(w, &d.column(v), 1.0);
                    }
                }
            }
        }
        phi
    }
}

/// The nodal vectors of 1, x and y.
pub fn linear_functions(mesh: &Mesh) -> Vec<Vec<f64>> {
    let p = mesh.positions();
    vec![vec![1.0; p.len()], p.iter().map(|q| q[0]).collect(), p.iter().map(|q| q[1]).collect()]
}

/// The diagonal of the mesh's bounding box.
pub(crate) fn extent(mesh: &Mesh) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for q in mesh.positions() {
        for c in 0..2 {
            lo[c] = lo[c].min(q[c]);
            hi[c] = hi[c].max(q[c]);
        }
    }
    (hi[0] - lo[0]).hypot(hi[1] - lo[1])
}

/// `D A` for a symmetric `a`: every row of `d` times `a`.
pub(crate) fn mass_times_rows(a: &CsMat<f64>, d: &DMatrix<f64>) -> DMatrix<f64> {
    let n = d.ncols();
    let mut out = DMatrix::zeros(d.nrows(), n);
    let (mut row, mut product) = (vec![0.0; n], vec![0.0; n]);
    for i in 0..d.nrows() {
        row.iter_mut().enumerate().for_each(|(j, x)| *x = d[(i, j)]);
        mul_into(a.view(), &row, &mut product);
        for (j, &x) in product.iter().enumerate() {
            out[(i, j)] = x;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    fn dot(a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).map(|(x, y)| x * y).sum()
    }

    use crate::triangulate::{triangulate, TriangulationOptions};

    fn bar() -> Mesh {
        triangulate(&shapes::toothed_bar(), &TriangulationOptions::default().with_target_edge_length(0.15)).unwrap()
    }

    /// K annihilates 1, x and y (test plan 10), on an irregular mesh with a long boundary.
    #[test]
    fn linearly_precise_laplacian_annihilates_affine_functions() {
        for mesh in [shapes::grid_mesh(4, 3), bar()] {
            let k = linearly_precise_laplacian(&mesh);
            let mut out = vec![0.0; mesh.vertex_count()];
            let scale: f64 = k.data().iter().map(|x| x.abs()).fold(0.0, f64::max);
            for f in linear_functions(&mesh) {
                mul_into(k.view(), &f, &mut out);
                let worst = out.iter().map(|x| x.abs()).fold(0.0, f64::max);
                assert!(worst <= 1e-12 * scale.max(1.0), "|K f| = {worst}");
            }
        }
        // Not merely zero: on the unit grid the interior rows are the five-point Laplacian
        // (axis edges weigh ½cot 45° · 2 = 1, diagonals ½cot 90° · 2 = 0), which maps x² to
        // (x+1)² + (x−1)² − 2x² = 2.
        let mesh = shapes::grid_mesh(4, 3);
        let k = linearly_precise_laplacian(&mesh);
        let q: Vec<f64> = mesh.positions().iter().map(|p| p[0] * p[0]).collect();
        let mut out = vec![0.0; q.len()];
        mul_into(k.view(), &q, &mut out);
        for (v, value) in out.iter().enumerate() {
            if !mesh.is_boundary_vertex(v) {
                assert!((value - 2.0).abs() < 1e-12, "vertex {v}: {value}");
            }
        }
    }

    #[test]
    fn masses_integrate_the_area() {
        let mesh = bar();
        let a = consistent_mass(&mesh);
        let ones = vec![1.0; mesh.vertex_count()];
        let mut out = vec![0.0; mesh.vertex_count()];
        mul_into(a.view(), &ones, &mut out);
        // 1ᵀ A 1 = ∫ 1 = area; and lumped = row sums of A.
        assert!((dot(&ones, &out) - mesh.area()).abs() <= 1e-12 * mesh.area());
        for (l, r) in lumped_mass(&mesh).iter().zip(&out) {
            assert!((l - r).abs() <= 1e-14);
        }
        // ∫ x² over the unit square is 1/3, exact for the consistent mass of x's nodal values
        // (x is linear, so x² integrates exactly with the P1 mass matrix).
        let square = shapes::grid_mesh(3, 3);
        let a = consistent_mass(&square);
        let x: Vec<f64> = square.positions().iter().map(|p| p[0] / 3.0).collect();
        let mut ax = vec![0.0; x.len()];
        mul_into(a.view(), &x, &mut ax);
        assert!((dot(&x, &ax) / 9.0 - 1.0 / 3.0).abs() < 1e-14);
    }

    #[test]
    fn orthonormalised_basis_is_m_orthonormal_and_holds_affine_functions() {
        let mesh = bar();
        let extra: Vec<Vec<f64>> =
            (1..6).map(|k| mesh.positions().iter().map(|p| (k as f64 * p[0] + p[1] * p[1]).sin()).collect()).collect();
        let basis = SpatialBasis::orthonormalised(&mesh, &extra).unwrap();
        assert_eq!(basis.len(), 8);
        let d = basis.reduction().unwrap().clone();
        // `reduced` checks D A Dᵀ = I and 1, x, y in the span.
        assert!(SpatialBasis::reduced(&mesh, d.clone()).is_ok());
        // The first three functions span 1, x, y: the first is 1/√area, the next two are
        // affine (least-squares residual against 1, x, y is zero).
        let first = 1.0 / mesh.area().sqrt();
        assert!(d.row(0).iter().all(|x| (x - first).abs() < 1e-12));
        let affine =
            DMatrix::from_fn(mesh.vertex_count(), 3, |v, c| [1.0, mesh.positions()[v][0], mesh.positions()[v][1]][c]);
        for r in 1..3 {
            let row = d.row(r).transpose();
            let c = affine.clone().svd(true, true).solve(&row, 1e-12).unwrap();
            assert!((&affine * c - row).amax() < 1e-10, "row {r} is not affine");
        }
        let row = d.row(3).transpose();
        let c = affine.clone().svd(true, true).solve(&row, 1e-12).unwrap();
        assert!((&affine * c - row).amax() > 1e-3, "row 3 is affine");
        let dependent = vec![vec![2.0; mesh.vertex_count()]];
        assert!(matches!(SpatialBasis::orthonormalised(&mesh, &dependent), Err(FitError::InvalidSpatialBasis { .. })));
        let mut scaled = d;
        scaled *= 2.0;
        assert!(matches!(SpatialBasis::reduced(&mesh, scaled), Err(FitError::InvalidSpatialBasis { .. })));
    }
}
