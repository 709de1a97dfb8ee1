//! The reduced spatial basis of the paper's Fig. 2: the functions 1, x and y, then the
//! lowest eigenfunctions of the linearly precise bilaplacian of Wang et al. (2015) (notes,
//! section 1): `A_s u = lambda A u` with `A_s = K^T M_l^-1 K` (K the linearly precise
//! Laplacian, M_l the lumped mass) and A the consistent mass, whose null space holds 1, x
//! and y exactly. Those three are deflated from the eigenproblem and put first, as the fit's
//! rest-pose constraint needs them exactly in the span (notes, item 11); the result is
//! A-orthonormal (`D A D^T = I`).

use sprs::CsMat;

use super::fit_error::FitError;
use super::spatial::{consistent_mass, linear_functions, linearly_precise_laplacian, lumped_mass, SpatialBasis};
use crate::mesh::Mesh;
use crate::sparse::eigen::{smallest_eigenpairs, EigenOptions};

/// The smallest reduced basis: 1, x and y alone.
pub const MIN_REDUCED_SIZE: usize = 3;

/// The linearly precise bilaplacian `K^T M_l^-1 K` of `mesh`, symmetric and stored in full.
pub fn linearly_precise_bilaplacian(mesh: &Mesh) -> CsMat<f64> {
    let k = linearly_precise_laplacian(mesh);
    let inverse_mass: Vec<f64> = lumped_mass(mesh).iter().map(|m| 1.0 / m).collect();
    // M_l^-1 K: row i of K over m_i.
    let mut scaled = k.clone();
    for mut column in scaled.outer_iterator_mut() {
        for (i, value) in column.iter_mut() {
            *value *= inverse_mass[i];
        }
    }
    let kt = k.transpose_view().to_csc();
    let product: CsMat<f64> = (&kt * &scaled).to_csc();
    // Exactly symmetric: the two triangles summed in different orders may differ by rounding.
    let transposed = product.transpose_view().to_csc();
    (&product + &transposed).map(|x| 0.5 * x).to_csc()
}

/// The reduced spatial basis of `size` functions (at least [`MIN_REDUCED_SIZE`], at most the
/// vertex count): 1, x, y and the `size - 3` lowest eigenfunctions of the linearly precise
/// bilaplacian, A-orthonormal.
pub fn reduced_basis(mesh: &Mesh, size: usize) -> Result<SpatialBasis, FitError> {
    let n = mesh.vertex_count();
    if !(MIN_REDUCED_SIZE..=n).contains(&size) {
        return Err(FitError::InvalidOption {
            name: "spatial",
            value: size as f64,
            expected: "a reduced basis of at least 3 functions (1, x, y) and at most one per vertex",
        });
    }
    let a_s = linearly_precise_bilaplacian(mesh);
    let mass = consistent_mass(mesh);
    let deflate = linear_functions(mesh);
    let pairs = smallest_eigenpairs(a_s.view(), mass.view(), size - 3, &deflate, &EigenOptions::default())
        .map_err(FitError::Eigen)?;
    SpatialBasis::orthonormalised(mesh, &pairs.vectors)
}

#[cfg(test)]
mod tests {
    use nalgebra::{DMatrix, SymmetricEigen};

    use super::*;
    use crate::shapes::grid_mesh;

    #[test]
    fn the_bilaplacian_vanishes_on_linear_functions_and_is_symmetric() {
        let mesh = grid_mesh(6, 4);
        let a_s = linearly_precise_bilaplacian(&mesh);
        let n = mesh.vertex_count();
        for f in linear_functions(&mesh) {
            let mut out = vec![0.0; n];
            crate::sparse::mul_into(a_s.view(), &f, &mut out);
            assert!(out.iter().all(|x| x.abs() < 1e-11), "{out:?}");
        }
        for (j, column) in a_s.outer_iterator().enumerate() {
            for (i, &v) in column.iter() {
                assert_eq!(a_s.get(j, i).copied(), Some(v), "A_s[{i},{j}]");
            }
        }
    }

    #[test]
    fn matches_the_dense_eigenfunctions_and_is_mass_orthonormal() {
        let mesh = grid_mesh(7, 5);
        let n = mesh.vertex_count();
        let size = 12;
        let basis = reduced_basis(&mesh, size).unwrap();
        let d = basis.reduction().unwrap();
        assert_eq!(d.shape(), (size, n));

        // Dense reference: the generalised eigenvalues of (A_s, A), from L^-1 A_s L^-T.
        let dense = |x: &CsMat<f64>| DMatrix::from_fn(n, n, |r, c| x.get(r, c).copied().unwrap_or(0.0));
        let (a_s, mass) = (dense(&linearly_precise_bilaplacian(&mesh)), dense(&consistent_mass(&mesh)));
        let l_inv = mass.clone().cholesky().unwrap().l().try_inverse().unwrap();
        let c = &l_inv * &a_s * l_inv.transpose();
        let mut exact: Vec<f64> = SymmetricEigen::new((&c + c.transpose()) * 0.5).eigenvalues.iter().copied().collect();
        exact.sort_by(f64::total_cmp);
        // Three zeros (1, x, y), then the rest.
        assert!(exact[..3].iter().all(|x| x.abs() < 1e-8 * exact[3]), "{:?}", &exact[..4]);

        // D A D^T = I, and the Rayleigh quotients of rows 3.. are the next eigenvalues.
        let product = d * &mass * d.transpose();
        assert!((product - DMatrix::identity(size, size)).amax() < 1e-10);
        let rayleigh = d * &a_s * d.transpose();
        for k in 0..3 {
            assert!(rayleigh[(k, k)].abs() < 1e-8 * exact[3], "row {k} is linear");
        }
        for k in 3..size {
            let (found, expected) = (rayleigh[(k, k)], exact[k]);
            assert!((found - expected).abs() <= 1e-8 * expected, "{k}: {found} vs {expected}");
        }
    }

    #[test]
    fn sizes_out_of_range_are_refused() {
        let mesh = grid_mesh(2, 2);
        assert!(matches!(reduced_basis(&mesh, 2), Err(FitError::InvalidOption { name: "spatial", .. })));
        assert!(matches!(reduced_basis(&mesh, 10), Err(FitError::InvalidOption { name: "spatial", .. })));
        assert_eq!(reduced_basis(&mesh, 3).unwrap().len(), 3);
    }
}
