//! The smallest eigenpairs of a sparse symmetric generalised eigenproblem `A u = lambda M u`
//! (`A` positive semidefinite, `M` positive definite), on our Cholesky: DefOp's reduced
//! spatial basis (the lowest eigenfunctions of a bilaplacian, notes section 1) needs a
//! hundred of them on meshes of thousands of vertices.
//!
//! Shift-invert subspace iteration with Rayleigh-Ritz projection: `A + sigma M` is factored
//! once; each iteration applies `(A + sigma M)^-1 M` to a block of `count + extra`
//! vectors and solves the small projected problem densely. The error of the k-th pair
//! shrinks each iteration by about `(lambda_k + sigma) / (lambda_(b+1) + sigma)`, `b` the
//! block size, so a few extra vectors buy fast convergence. Vectors known to be
//! eigenvectors (a null space, such as the constants and the linear functions of a linearly
//! precise operator) can be given to deflate: every iterate is kept M-orthogonal to them,
//! so the pairs found are the smallest of the rest.
//!
//! The result is M-orthonormal: `V^T M V = I`.

use std::sync::Arc;

use nalgebra::{DMatrix, SymmetricEigen};

use super::{CsMatView, FactorError, Numeric, Ordering, Symbolic};
use crate::random::Rng;

/// Settings of [`smallest_eigenpairs`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EigenOptions {
    /// A pair has converged when `(A + sigma M)^-1 M v` is within `tolerance` (relative) of
    /// `v / (lambda + sigma)`, as it is for an eigenpair (default 1e-8: rounding leaves
    /// about 1e-10 on meshes of a few hundred vertices, and eigenvalues are then exact to
    /// about the square, 1e-16).
    pub tolerance: f64,
    /// Most iterations (default 500).
    pub max_iterations: usize,
    /// Vectors beyond the `count` wanted in the block (0: `max(8, count / 2)`).
    pub extra: usize,
    /// The shift `sigma` (0: chosen, see [`smallest_eigenpairs`]).
    pub shift: f64,
    /// Seed of the random starting block.
    pub seed: u64,
}

impl Default for EigenOptions {
    fn default() -> Self {
        Self { tolerance: 1e-8, max_iterations: 500, extra: 0, shift: 0.0, seed: 1 }
    }
}

/// Eigenpairs, smallest first.
#[derive(Debug, Clone, PartialEq)]
pub struct Eigenpairs {
    /// The eigenvalues, ascending.
    pub values: Vec<f64>,
    /// One eigenvector per value, M-orthonormal.
    pub vectors: Vec<Vec<f64>>,
    /// Iterations run.
    pub iterations: usize,
}

/// Why the eigenpairs could not be computed.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum EigenError {
    /// `A` and `M` differ in size, or are not square.
    Shape {
        /// Rows and columns of `A`.
        a: (usize, usize),
        /// Rows and columns of `M`.
        m: (usize, usize),
    },
    /// More pairs were asked than the matrix has beyond the deflated vectors.
    TooMany {
        /// Pairs asked.
        count: usize,
        /// Pairs available.
        available: usize,
    },
    /// A deflation vector has the wrong length, or they are linearly dependent.
    Deflation,
    /// `A + sigma M` or `M` could not be factored.
    Factor(FactorError),
    /// The iteration did not converge.
    NotConverged {
        /// Iterations run.
        iterations: usize,
        /// The largest relative residual left.
        residual: f64,
    },
}

impl std::fmt::Display for EigenError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Shape { a, m } => {
                write!(f, "A is {} x {} and M is {} x {}; both must be the same square size", a.0, a.1, m.0, m.1)
            }
            Self::TooMany { count, available } => {
                write!(f, "{count} eigenpairs were asked, but only {available} are left beyond the deflated vectors")
            }
            Self::Deflation => f.write_str("the deflation vectors have the wrong length or are linearly dependent"),
            Self::Factor(e) => write!(f, "the shifted matrix could not be factored: {e}"),
            Self::NotConverged { iterations, residual } => {
                write!(f, "no convergence after {iterations} iterations (largest relative residual {residual:e})")
            }
        }
    }
}

impl std::error::Error for EigenError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Factor(e) => Some(e),
            _ => None,
        }
    }
}

/// The `count` smallest eigenpairs of `A u = lambda M u` whose vectors are M-orthogonal
/// to `deflate`. `A` and `M` are symmetric and stored in full (both triangles) in
/// compressed sparse column form.
///
/// Unless [`EigenOptions::shift`] gives one, the shift starts at `1e-6 trace(A) /
/// trace(M)` (a millionth of the mean eigenvalue: positive definite whatever A's null
/// space) and, once the first Ritz values are in, moves to a twentieth of the largest
/// wanted eigenvalue: the spectra of mesh operators span many orders of magnitude (a
/// bilaplacian's, `N^2`), and a shift far above the wanted eigenvalues would not separate
/// them from the rest, while one far below them would make `A + sigma M` ill-conditioned
/// along A's null space.
pub fn smallest_eigenpairs(
    a: CsMatView<'_>,
    m: CsMatView<'_>,
    count: usize,
    deflate: &[Vec<f64>],
    options: &EigenOptions,
) -> Result<Eigenpairs, EigenError> {
    let n = a.rows();
    if a.cols() != n || m.rows() != n || m.cols() != n {
        return Err(EigenError::Shape { a: (a.rows(), a.cols()), m: (m.rows(), m.cols()) });
    }
    let available = n.saturating_sub(deflate.len());
    if count > available {
        return Err(EigenError::TooMany { count, available });
    }
    if count == 0 {
        return Ok(Eigenpairs { values: Vec::new(), vectors: Vec::new(), iterations: 0 });
    }
    let z = m_orthonormal(m, deflate).ok_or(EigenError::Deflation)?;
    let extra = if options.extra == 0 { (count / 2).max(8) } else { options.extra };
    let block = (count + extra).min(available);

    let trace = |x: CsMatView<'_>| (0..n).map(|j| x.get(j, j).copied().unwrap_or(0.0)).sum::<f64>();
    let mut shift = if options.shift > 0.0 { options.shift } else { 1e-6 * trace(a) / trace(m) };
    let mut adapt = options.shift <= 0.0;
    let shifted = |shift: f64| (&a.to_owned() + &m.map(|x| shift * x)).to_csc();
    let first = shifted(shift);
    let symbolic = Arc::new(Symbolic::analyse(first.view(), &Ordering::Amd).map_err(EigenError::Factor)?);
    let mut factor = Numeric::factor(symbolic, first.view()).map_err(EigenError::Factor)?;

    let mut rng = Rng::new(options.seed);
    let mut w = DMatrix::from_fn(n, block, |_, _| rng.uniform() - 0.5);
    let mut column = vec![0.0; n];
    let mut residual = f64::INFINITY;
    deflate_block(m, &z, &mut w);
    for iteration in 1..=options.max_iterations {
        let (values, v) = rayleigh_ritz(a, m, &w).ok_or(EigenError::Deflation)?;
        // After three iterations the Ritz values bound the wanted eigenvalues from above
        // closely enough to place the shift a twentieth of the way to the largest wanted one:
        // low enough to separate the wanted pairs from the rest, high enough to keep
        // A + sigma M well conditioned along A's null space (its condition number is about
        // lambda_max / sigma).
        if adapt && iteration == 4 {
            adapt = false;
            let target = 0.05 * values[count - 1];
            if target.is_finite() && target > 0.0 {
                shift = target;
                factor.refactor(shifted(shift).view()).map_err(EigenError::Factor)?;
            }
        }
        // The next block: (A + sigma M)^-1 M V, kept M-orthogonal to the deflated vectors.
        for k in 0..block {
            column.copy_from_slice(&mul(m, v.column(k).as_slice()));
            factor.solve_in_place(&mut column).map_err(EigenError::Factor)?;
            w.column_mut(k).copy_from_slice(&column);
        }
        deflate_block(m, &z, &mut w);
        // Convergence, measured on the inverted operator, whose largest values are the
        // wanted ones: an eigenpair has (A + sigma M)^-1 M v = v / (lambda + sigma).
        // (The residual A v - lambda M v cannot show it for eigenvalues far below the
        // norm of A, where rounding in A v alone exceeds lambda M v.)
        residual = 0.0;
        for (k, value) in values.iter().enumerate().take(count) {
            let (wk, vk) = (w.column(k), v.column(k));
            let theta = 1.0 / (value + shift);
            let r = wk.iter().zip(vk.iter()).map(|(x, y)| (x - theta * y).powi(2)).sum::<f64>().sqrt();
            residual = residual.max(r / wk.norm());
        }
        if residual <= options.tolerance {
            let vectors = (0..count).map(|k| v.column(k).iter().copied().collect()).collect();
            return Ok(Eigenpairs { values: values[..count].to_vec(), vectors, iterations: iteration });
        }
        // Unit columns: the solve scales each by about 1 / (lambda_k + sigma), which would
        // otherwise make the projected mass matrix needlessly ill-conditioned.
        for mut column in w.column_iter_mut() {
            let length = column.norm();
            column /= length;
        }
    }
    Err(EigenError::NotConverged { iterations: options.max_iterations, residual })
}

/// `A x` for `A` in compressed sparse column form, in a new vector.
fn mul(a: CsMatView<'_>, x: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; a.rows()];
    super::mul_into(a, x, &mut y);
    y
}

/// The vectors made M-orthonormal (Gram-Schmidt in M's inner product, twice); `None` if
/// one has the wrong length or they are (numerically) dependent.
pub fn m_orthonormal(m: CsMatView<'_>, vectors: &[Vec<f64>]) -> Option<Vec<Vec<f64>>> {
    let n = m.rows();
    let mut basis: Vec<Vec<f64>> = Vec::with_capacity(vectors.len());
    for v in vectors {
        if v.len() != n {
            return None;
        }
        let mut v = v.clone();
        let original = dot(&v, &mul(m, &v)).sqrt();
        for _ in 0..2 {
            for b in &basis {
                let c = dot(&v, &mul(m, b));
                v.iter_mut().zip(b).for_each(|(x, y)| *x -= c * y);
            }
        }
        let length = dot(&v, &mul(m, &v)).sqrt();
        // Also refuses NaN lengths.
        if length.is_nan() || length <= 1e-10 * original {
            return None;
        }
        v.iter_mut().for_each(|x| *x /= length);
        basis.push(v);
    }
    Some(basis)
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Removes from every column of `w` its M-projection on the M-orthonormal `z` (twice, for
/// rounding).
fn deflate_block(m: CsMatView<'_>, z: &[Vec<f64>], w: &mut DMatrix<f64>) {
    let mz: Vec<Vec<f64>> = z.iter().map(|v| mul(m, v)).collect();
    for mut col in w.column_iter_mut() {
        for _ in 0..2 {
            for (v, mv) in z.iter().zip(&mz) {
                let c: f64 = col.iter().zip(mv).map(|(x, y)| x * y).sum();
                col.iter_mut().zip(v).for_each(|(x, y)| *x -= c * y);
            }
        }
    }
}

/// The Ritz pairs of `(A, M)` on the span of `w`'s columns, values ascending, vectors
/// M-orthonormal; `None` if the columns are (numerically) dependent.
fn rayleigh_ritz(a: CsMatView<'_>, m: CsMatView<'_>, w: &DMatrix<f64>) -> Option<(Vec<f64>, DMatrix<f64>)> {
    let (n, b) = w.shape();
    let mut aw = DMatrix::zeros(n, b);
    let mut mw = DMatrix::zeros(n, b);
    for k in 0..b {
        aw.column_mut(k).copy_from_slice(&mul(a, w.column(k).as_slice()));
        mw.column_mut(k).copy_from_slice(&mul(m, w.column(k).as_slice()));
    }
    let small_a = symmetric(w.transpose() * aw);
    let small_m = symmetric(w.transpose() * mw);
    // M-orthonormalise through the Cholesky factor of the projected M: C = L^-1 A L^-T.
    let l = small_m.cholesky()?.l();
    let l_inv = l.clone().try_inverse()?;
    let c = symmetric(&l_inv * small_a * l_inv.transpose());
    let eigen = SymmetricEigen::new(c);
    let mut order: Vec<usize> = (0..b).collect();
    order.sort_by(|&i, &j| eigen.eigenvalues[i].total_cmp(&eigen.eigenvalues[j]));
    let values = order.iter().map(|&i| eigen.eigenvalues[i]).collect();
    let y = DMatrix::from_fn(b, b, |r, k| eigen.eigenvectors[(r, order[k])]);
    Some((values, w * (l_inv.transpose() * y)))
}

fn symmetric(x: DMatrix<f64>) -> DMatrix<f64> {
    (&x + x.transpose()) * 0.5
}

#[cfg(test)]
mod tests {
    use super::*;
    use sprs::TriMat;

    /// The path graph's Laplacian (Neumann ends) on `n` nodes, in full.
    fn path_laplacian(n: usize) -> sprs::CsMat<f64> {
        let mut t = TriMat::new((n, n));
        for i in 0..n - 1 {
            t.add_triplet(i, i, 1.0);
            t.add_triplet(i + 1, i + 1, 1.0);
            t.add_triplet(i, i + 1, -1.0);
            t.add_triplet(i + 1, i, -1.0);
        }
        t.to_csc()
    }

    fn identity(n: usize) -> sprs::CsMat<f64> {
        sprs::CsMat::eye_csc(n)
    }

    #[test]
    fn the_path_laplacian_has_its_known_spectrum() {
        // Eigenvalues 2 - 2 cos(k pi / n), k = 0..n; the constant (k = 0) is deflated.
        let n = 200;
        let (a, m) = (path_laplacian(n), identity(n));
        let found = smallest_eigenpairs(a.view(), m.view(), 12, &[vec![1.0; n]], &EigenOptions::default()).unwrap();
        for (k, value) in found.values.iter().enumerate() {
            let exact = 2.0 - 2.0 * (std::f64::consts::PI * (k + 1) as f64 / n as f64).cos();
            assert!((value - exact).abs() <= 1e-10 * exact, "{k}: {value} vs {exact}");
        }
        // Each vector is the cosine mode cos(k pi (i + 1/2) / n), up to sign.
        for (k, v) in found.vectors.iter().enumerate() {
            let mode: Vec<f64> =
                (0..n).map(|i| (std::f64::consts::PI * (k + 1) as f64 * (i as f64 + 0.5) / n as f64).cos()).collect();
            let scale = dot(&mode, &mode).sqrt();
            let c = dot(v, &mode) / scale;
            assert!((c.abs() - 1.0).abs() < 1e-9, "{k}: |cos| {c}");
        }
    }

    #[test]
    fn matches_a_dense_generalised_solve_and_is_m_orthonormal() {
        // A 2D grid Laplacian plus a varying positive diagonal, M a varying positive
        // tridiagonal mass: compared with the dense L^-1 A L^-T eigenvalues.
        let (side, count) = (9, 12);
        let n = side * side;
        let mut rng = Rng::new(5);
        let mut ta = TriMat::new((n, n));
        let mut tm = TriMat::new((n, n));
        let id = |i: usize, j: usize| j * side + i;
        for j in 0..side {
            for i in 0..side {
                let v = id(i, j);
                ta.add_triplet(v, v, 0.1 * rng.uniform());
                tm.add_triplet(v, v, 1.0 + rng.uniform());
                for (p, q) in [(i + 1, j), (i, j + 1)] {
                    if p < side && q < side {
                        let w = id(p, q);
                        let c = 0.5 + rng.uniform();
                        for (r, s, x) in [(v, v, c), (w, w, c), (v, w, -c), (w, v, -c)] {
                            ta.add_triplet(r, s, x);
                        }
                        let mass = 0.1 * rng.uniform();
                        tm.add_triplet(v, w, mass);
                        tm.add_triplet(w, v, mass);
                    }
                }
            }
        }
        let (a, m) = (ta.to_csc::<usize>(), tm.to_csc::<usize>());
        let found = smallest_eigenpairs(a.view(), m.view(), count, &[], &EigenOptions::default()).unwrap();

        let dense = |x: &sprs::CsMat<f64>| DMatrix::from_fn(n, n, |r, c| x.get(r, c).copied().unwrap_or(0.0));
        let l_inv = dense(&m).cholesky().unwrap().l().try_inverse().unwrap();
        let c = symmetric(&l_inv * dense(&a) * l_inv.transpose());
        let mut exact: Vec<f64> = SymmetricEigen::new(c).eigenvalues.iter().copied().collect();
        exact.sort_by(f64::total_cmp);
        for (k, (value, exact)) in found.values.iter().zip(&exact).enumerate() {
            assert!((value - exact).abs() <= 1e-9 * exact.abs().max(1e-3), "{k}: {value} vs {exact}");
        }
        for (i, u) in found.vectors.iter().enumerate() {
            for (j, v) in found.vectors.iter().enumerate() {
                let expected = if i == j { 1.0 } else { 0.0 };
                assert!((dot(u, &mul(m.view(), v)) - expected).abs() < 1e-10, "V^T M V at {i}, {j}");
            }
        }
    }

    #[test]
    fn bad_requests_are_refused() {
        let (a, m) = (path_laplacian(10), identity(10));
        let options = EigenOptions::default();
        let ones = vec![1.0; 10];
        assert_eq!(
            smallest_eigenpairs(a.view(), m.view(), 10, std::slice::from_ref(&ones), &options).unwrap_err(),
            EigenError::TooMany { count: 10, available: 9 }
        );
        assert_eq!(
            smallest_eigenpairs(a.view(), m.view(), 2, &[ones.clone(), ones.clone()], &options).unwrap_err(),
            EigenError::Deflation
        );
        let small = identity(9);
        assert!(matches!(smallest_eigenpairs(a.view(), small.view(), 2, &[], &options), Err(EigenError::Shape { .. })));
        let stingy = EigenOptions { max_iterations: 1, tolerance: 1e-14, ..options };
        assert!(matches!(
            smallest_eigenpairs(path_laplacian(300).view(), identity(300).view(), 5, &[], &stingy),
            Err(EigenError::NotConverged { iterations: 1, .. })
        ));
    }
}
