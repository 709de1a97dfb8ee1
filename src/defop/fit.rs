//! The least-squares fit of a deformation operator (paper eq. 8 and App. A; notes §2.4–2.6):
//! per coordinate ν, min_X Σ_k ‖g_k − Dᵀ X Ψ(Q_k)‖²_A subject to the rest pose
//! X Ψ(P) = c_0 (8b) and the handle constraint in its strong form Φ_Pᵀ X = S (8c for every
//! Q, not only the samples), plus, for a TPS, the side conditions Σ_k a_k = 0,
//! Σ_k a_k u_k = 0 on every row's radial weights.
//!
//! The structured solver (notes §2.5), without whitening explicitly: with the metric
//! M = D A Dᵀ (A for hat functions, I for a reduced basis), F = M⁻¹ Φ_P, W = Φ_Pᵀ F and the
//! M-orthogonal projector Π = I − F W⁻¹ Φ_Pᵀ,
//!
//! X = F W⁻¹ S + (Π Ĝ) K1 + Π (c_0 − X_p Ψ(P)) k2ᵀ,   Ĝ = M⁻¹ D A [g_1 … g_m],
//!
//! where zᵀ = cᵀ K1 + d k2ᵀ solves the small row problem min ‖Ψ_sᵀ z − c‖² s.t.
//! Ψ(P)ᵀ z = d (and the side conditions), shared by all |Φ| rows and both coordinates:
//! the constraints are eliminated by a QR factorisation of their matrix, the rest by a QR of
//! Ψ_sᵀ restricted to their null space (never the normal equations). An optional ridge
//! λ ‖z_nonlinear‖² (notes §2.6) makes polynomial fits with fewer samples than functions
//! unique. The TPS shortcut: when the rest pose is a sample and the ground truths hit the
//! handles, the optimum interpolates every sample, and one (m + k + 1)-square system gives it.
//!
//! Handle coordinates (see `coordinates`): with canonical coordinates the samples are
//! canonicalised first; the strong constraint's S expresses q̂_ℓ through the k coordinates.

use std::sync::Arc;

use nalgebra::{DMatrix, DVector};

use super::basis::{thin_plate, BasisKind, HandleBasis};
use super::coordinates::HandleCoordinates;
use super::fit_error::{check_finite, check_length, FitError};
use super::operator::{Operator, Solver};
use super::spatial::{consistent_mass, extent, mass_times_rows, resolve_points, MeshPoint, SpatialBasis};
use crate::mesh::Mesh;
use crate::sparse::{Numeric, Ordering, Symbolic};

/// One training sample: handle targets Q_k and the ground-truth deformation g_k there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample<'a> {
    /// The handle targets (2n numbers, x and y interleaved).
    pub targets: &'a [f64],
    /// The ground-truth vertex positions (2N numbers, x and y interleaved).
    pub positions: &'a [f64],
}

/// How to fit a deformation operator.
#[derive(Debug, Clone, PartialEq)]
pub struct FitOptions {
    /// The handle basis.
    pub kind: BasisKind,
    /// The scale r_s of the handle coordinates; `None`: the largest distance of a sample's
    /// target from its handle's rest position (the sampling radius).
    pub scale: Option<f64>,
    /// The ridge λ on the non-linear coefficients (0: none, the paper's fit).
    pub regularisation: f64,
    /// Whether a TPS fit may use the interpolation shortcut when it applies.
    pub tps_shortcut: bool,
    /// Whether to add the rest pose (Q = P, ground truth the identity) as a sample when the
    /// samples do not hold it.
    pub rest_sample: bool,
    /// Canonical handle coordinates (notes item 13): the samples are canonicalised (targets
    /// and ground truths moved by the rigid motion that best aligns their targets with the
    /// rest handles) and the operator moves its result back, so that it reproduces rigid
    /// motions of all handles exactly; the basis has k = 2n − 3 coordinates (0 for one
    /// handle: a translation). Valid for rigid-invariant ground truths (ARAP, S-ARAP).
    /// Samples that differ by a rigid motion become one; not with `fixed`.
    pub canonical: bool,
    /// Handles held at their rest position in every sample (indices into the handles): the
    /// basis leaves their coordinates out (k = 2(n − #fixed)), and the operator keeps them at
    /// rest whatever targets it is given for them.
    pub fixed: Vec<usize>,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            kind: BasisKind::Tps,
            scale: None,
            regularisation: 0.0,
            tps_shortcut: true,
            rest_sample: true,
            canonical: false,
            fixed: Vec::new(),
        }
    }
}

impl FitOptions {
    /// Sets the handle basis.
    pub fn with_kind(mut self, kind: BasisKind) -> Self {
        self.kind = kind;
        self
    }

    /// Sets the scale r_s of the handle coordinates.
    pub fn with_scale(mut self, scale: f64) -> Self {
        self.scale = Some(scale);
        self
    }

    /// Sets the ridge λ on the non-linear coefficients.
    pub fn with_regularisation(mut self, lambda: f64) -> Self {
        self.regularisation = lambda;
        self
    }

    /// Allows or forbids the TPS interpolation shortcut.
    pub fn with_tps_shortcut(mut self, allowed: bool) -> Self {
        self.tps_shortcut = allowed;
        self
    }

    /// Adds the rest pose as a sample, or not.
    pub fn with_rest_sample(mut self, add: bool) -> Self {
        self.rest_sample = add;
        self
    }

    /// Canonical handle coordinates, or not.
    pub fn with_canonical(mut self, canonical: bool) -> Self {
        self.canonical = canonical;
        self
    }

    /// Holds the handles `fixed` at rest.
    pub fn with_fixed(mut self, fixed: Vec<usize>) -> Self {
        self.fixed = fixed;
        self
    }
}

/// Fits a deformation operator for the handles `handles` of `mesh` in the spatial basis
/// `spatial` to the ground truths `samples`.
///
/// ```
/// use akap::defop::{fit, BasisKind, FitOptions, MeshPoint, Sample, SpatialBasis};
///
/// // One handle at vertex 4, (1, 1), of a 2 x 2 grid; the ground truth translates the
/// // shape with it, which a linear operator reproduces exactly.
/// let mesh = akap::shapes::grid_mesh(2, 2);
/// let translate = |q: &[f64]| -> Vec<f64> {
///     mesh.positions().iter().flat_map(|p| [p[0] + q[0] - 1.0, p[1] + q[1] - 1.0]).collect()
/// };
/// let targets = [vec![1.5, 1.0], vec![1.0, 0.5], vec![0.75, 1.25]];
/// let truths: Vec<Vec<f64>> = targets.iter().map(|q| translate(q)).collect();
/// let samples: Vec<Sample> =
///     targets.iter().zip(&truths).map(|(t, p)| Sample { targets: t, positions: p }).collect();
/// let options = FitOptions::default().with_kind(BasisKind::Linear);
/// let mut operator = fit(&mesh, &SpatialBasis::hat(&mesh), &[MeshPoint::Vertex(4)], &samples, &options)?;
/// let moved = operator.evaluate(&[3.0, -2.0])?;
/// assert!(moved.iter().zip(translate(&[3.0, -2.0])).all(|(a, b)| (a - b).abs() < 1e-12));
/// # Ok::<(), akap::defop::FitError>(())
/// ```
pub fn fit(
    mesh: &Mesh,
    spatial: &SpatialBasis,
    handles: &[MeshPoint],
    samples: &[Sample<'_>],
    options: &FitOptions,
) -> Result<Operator, FitError> {
    let (n, nv) = (handles.len(), mesh.vertex_count());
    if n == 0 {
        return Err(FitError::NoHandles);
    }
    if spatial.vertex_count() != nv {
        return Err(FitError::Length { what: "spatial basis", expected: nv, found: spatial.vertex_count() });
    }
    let hats = resolve_points(mesh, handles)?;
    let rest: Vec<f64> = hats.iter().flat_map(|h| h.position(mesh)).collect();
    let size = extent(mesh);
    for a in 0..n {
        for b in a + 1..n {
            if (rest[2 * a] - rest[2 * b]).hypot(rest[2 * a + 1] - rest[2 * b + 1]) <= 1e-12 * size {
                return Err(FitError::CoincidentHandles { first: a, second: b });
            }
        }
    }
    for s in samples {
        check_length("sample targets", s.targets, 2 * n)?;
        check_length("sample positions", s.positions, 2 * nv)?;
        check_finite("sample targets", s.targets)?;
        check_finite("sample positions", s.positions)?;
    }
    let lambda = options.regularisation;
    if !(lambda.is_finite() && lambda >= 0.0) {
        return Err(FitError::InvalidOption { name: "regularisation", value: lambda, expected: "a finite λ ≥ 0" });
    }
    let coordinates = HandleCoordinates::new(&rest, options.canonical, &options.fixed)?;
    for (k, s) in samples.iter().enumerate() {
        for &a in coordinates.fixed() {
            let moved = (s.targets[2 * a] - rest[2 * a]).hypot(s.targets[2 * a + 1] - rest[2 * a + 1]);
            if moved > 1e-9 * size {
                return Err(FitError::FixedHandleMoved { sample: k, handle: a });
            }
        }
    }
    let canonical: Vec<(Vec<f64>, Vec<f64>)> = if coordinates.is_canonical() {
        samples.iter().map(|s| canonicalised(&coordinates, s)).collect()
    } else {
        Vec::new()
    };
    let samples: Vec<Sample<'_>> = if coordinates.is_canonical() {
        canonical.iter().map(|(t, p)| Sample { targets: t, positions: p }).collect()
    } else {
        samples.to_vec()
    };
    let identity: Vec<f64> = mesh.positions().iter().flatten().copied().collect();
    let mut list: Vec<Sample<'_>> = Vec::with_capacity(samples.len() + 1);
    if options.rest_sample && !samples.iter().any(|s| s.targets == rest.as_slice()) {
        list.push(Sample { targets: &rest, positions: &identity });
    }
    list.extend_from_slice(&samples);
    if list.is_empty() {
        return Err(FitError::NoSamples);
    }
    let m = list.len();
    let scale = match options.scale {
        Some(s) => s,
        None => {
            let radius = list
                .iter()
                .flat_map(|s| s.targets.chunks_exact(2).zip(rest.chunks_exact(2)))
                .map(|(q, p)| (q[0] - p[0]).hypot(q[1] - p[1]))
                .fold(0.0, f64::max);
            if radius > 0.0 {
                radius
            } else {
                size
            }
        }
    };
    // Without coordinates (one canonical handle, every handle fixed) Ψ is the constant.
    let kind = if coordinates.is_empty() { BasisKind::Linear } else { options.kind };
    let basis = if kind.is_polynomial() {
        HandleBasis::new(kind, coordinates, scale, &[])?
    } else {
        let centres: Vec<f64> = list.iter().flat_map(|s| s.targets.iter().copied()).collect();
        HandleBasis::new(kind, coordinates, scale, &centres)?
    };
    let len = basis.len();
    if kind.is_polynomial() && lambda == 0.0 && m < len {
        return Err(FitError::TooFewSamples { samples: m, basis_size: len });
    }
    // The ridge acts on the non-linear coefficients only: the linear ones need the samples.
    if m < basis.linear_len() {
        return Err(FitError::TooFewSamples { samples: m, basis_size: basis.linear_len() });
    }

    // Ψ_s (|Ψ| × m) and a_0 = Ψ(P).
    let mut psi_s = DMatrix::zeros(len, m);
    for (k, s) in list.iter().enumerate() {
        basis.evaluate_unchecked(s.targets, psi_s.column_mut(k).as_mut_slice());
    }
    let mut a0 = DVector::zeros(len);
    basis.evaluate_unchecked(&rest, a0.as_mut_slice());

    // Ĝ^ν (|Φ| × m) and c_0^ν: the ground truths and the coordinates in the basis Φ.
    let phi_len = spatial.len();
    let nodal = |k: usize, nu: usize| -> Vec<f64> { list[k].positions.iter().skip(nu).step_by(2).copied().collect() };
    let mut g_hat = [DMatrix::zeros(phi_len, m), DMatrix::zeros(phi_len, m)];
    let mut c0 = [DVector::zeros(phi_len), DVector::zeros(phi_len)];
    let mass = consistent_mass(mesh);
    let da = spatial.reduction().map(|d| mass_times_rows(&mass, d));
    for nu in 0..2 {
        let coordinate: Vec<f64> = mesh.positions().iter().map(|p| p[nu]).collect();
        for k in 0..m {
            let g = nodal(k, nu);
            match &da {
                None => g_hat[nu].column_mut(k).copy_from_slice(&g),
                Some(da) => g_hat[nu].set_column(k, &(da * DVector::from_vec(g))),
            }
        }
        c0[nu] = match &da {
            None => DVector::from_vec(coordinate),
            Some(da) => da * DVector::from_vec(coordinate),
        };
    }
    let phi_p = spatial.at_points(&hats);

    let x = if kind == BasisKind::Tps
        && lambda == 0.0
        && options.tps_shortcut
        && shortcut_applies(&list, &rest, &g_hat, &c0, &phi_p, 1e-11 * size)
    {
        (tps_interpolation(&basis, &g_hat)?, Solver::TpsInterpolation)
    } else {
        (structured(&basis, spatial, &mass, &phi_p, &psi_s, &a0, &g_hat, &c0, lambda)?, Solver::Structured)
    };
    Ok(Operator::new(handles.to_vec(), basis, x.1, x.0, spatial.reduction(), nv))
}

/// A sample's targets and ground truth, canonicalised: both moved by the inverse of the
/// rigid motion [`HandleCoordinates::canonicalise`] finds for its targets.
fn canonicalised(coordinates: &HandleCoordinates, sample: &Sample<'_>) -> (Vec<f64>, Vec<f64>) {
    let mut targets = vec![0.0; sample.targets.len()];
    let rigid = coordinates.canonicalise(sample.targets, &mut targets).expect("canonical coordinates");
    let positions = sample.positions.chunks_exact(2).flat_map(|g| rigid.unapply([g[0], g[1]])).collect();
    (targets, positions)
}

/// Whether the TPS shortcut applies: the rest pose is a sample with the identity as its
/// ground truth, and every ground truth hits the handles (Φ_Pᵀ ĝ_k = q_k), to `tolerance`.
fn shortcut_applies(
    list: &[Sample<'_>],
    rest: &[f64],
    g_hat: &[DMatrix<f64>; 2],
    c0: &[DVector<f64>; 2],
    phi_p: &DMatrix<f64>,
    tolerance: f64,
) -> bool {
    let Some(k0) = list.iter().position(|s| s.targets == rest) else {
        return false;
    };
    for nu in 0..2 {
        if (g_hat[nu].column(k0) - &c0[nu]).amax() > tolerance {
            return false;
        }
        let at_handles = phi_p.transpose() * &g_hat[nu];
        for (k, s) in list.iter().enumerate() {
            for l in 0..rest.len() / 2 {
                if (at_handles[(l, k)] - s.targets[2 * l + nu]).abs() > tolerance {
                    return false;
                }
            }
        }
    }
    true
}

/// The TPS shortcut: `[[K_ρ, T], [Tᵀ, 0]] [a; b] = [Ĝᵀ; 0]`, both coordinates with one LU.
fn tps_interpolation(basis: &HandleBasis, g_hat: &[DMatrix<f64>; 2]) -> Result<[DMatrix<f64>; 2], FitError> {
    let (lin, d) = (basis.linear_len(), basis.coordinate_count());
    let centres = basis.scaled_centres();
    let m = centres.len() / d;
    let size = m + lin;
    let mut system = DMatrix::zeros(size, size);
    for k in 0..m {
        let uk = &centres[k * d..(k + 1) * d];
        for l in 0..k {
            let ul = &centres[l * d..(l + 1) * d];
            let r2: f64 = uk.iter().zip(ul).map(|(a, b)| (a - b) * (a - b)).sum();
            let value = thin_plate(r2);
            system[(k, l)] = value;
            system[(l, k)] = value;
        }
        for j in 0..lin {
            let t = if j == 0 { 1.0 } else { uk[j - 1] };
            system[(k, m + j)] = t;
            system[(m + j, k)] = t;
        }
    }
    let phi_len = g_hat[0].nrows();
    let mut rhs = DMatrix::zeros(size, 2 * phi_len);
    for (nu, g) in g_hat.iter().enumerate() {
        rhs.view_mut((0, nu * phi_len), (m, phi_len)).copy_from(&g.transpose());
    }
    let lu = system.lu();
    let solution = lu.solve(&rhs).filter(|s| s.iter().all(|x| x.is_finite()));
    let solution = solution.ok_or(FitError::Singular { what: "samples" })?;
    Ok([0, 1].map(|nu| {
        DMatrix::from_fn(phi_len, size, |i, j| {
            // Ψ's order: the linear functions, then the radial ones.
            let row = if j < lin { m + j } else { j - lin };
            solution[(row, nu * phi_len + i)]
        })
    }))
}

/// The metric M of the spatial basis: the consistent mass for hat functions (sparse
/// Cholesky), the identity for a reduced basis (M-orthonormal by construction).
enum Metric {
    Mass(Box<Numeric>),
    Identity,
}

impl Metric {
    fn solve(&mut self, v: &mut [f64]) -> Result<(), FitError> {
        match self {
            Self::Mass(numeric) => Ok(numeric.solve_in_place(v)?),
            Self::Identity => Ok(()),
        }
    }
}

/// The structured solver of notes §2.5, both coordinates sharing every factorisation.
#[allow(clippy::too_many_arguments)]
fn structured(
    basis: &HandleBasis,
    spatial: &SpatialBasis,
    mass: &sprs::CsMat<f64>,
    phi_p: &DMatrix<f64>,
    psi_s: &DMatrix<f64>,
    a0: &DVector<f64>,
    g_hat: &[DMatrix<f64>; 2],
    c0: &[DVector<f64>; 2],
    lambda: f64,
) -> Result<[DMatrix<f64>; 2], FitError> {
    let mut metric = match spatial.reduction() {
        None => {
            let symbolic = Symbolic::analyse(mass.view(), &Ordering::Amd)?;
            Metric::Mass(Box::new(Numeric::factor(Arc::new(symbolic), mass.view())?))
        }
        Some(_) => Metric::Identity,
    };
    // F = M⁻¹ Φ_P, W = Φ_Pᵀ F, FW = F W⁻¹.
    let mut f = phi_p.clone();
    for mut column in f.column_iter_mut() {
        metric.solve(column.as_mut_slice())?;
    }
    let w = phi_p.transpose() * &f;
    let cholesky = w.cholesky().ok_or(FitError::Singular { what: "handles" })?;
    let fw = cholesky.solve(&f.transpose()).transpose();
    let project = |v: &DMatrix<f64>| -> DMatrix<f64> { v - &fw * (phi_p.transpose() * v) };

    let (k1, k2) = row_problem(basis, psi_s, a0, lambda)?;
    let n = phi_p.ncols();
    Ok([0, 1].map(|nu| {
        // S^ν: row ℓ holds the coefficients of Q ↦ q_ℓ^ν.
        let mut s = DMatrix::zeros(n, basis.len());
        for l in 0..n {
            let (constant, linear) = basis.coordinate(2 * l + nu);
            s[(l, 0)] = constant;
            for (j, b) in linear.into_iter().enumerate() {
                s[(l, 1 + j)] = b;
            }
        }
        let xp = &fw * s;
        let r = project(&DMatrix::from_column_slice(c0[nu].len(), 1, (&c0[nu] - &xp * a0).as_slice()));
        xp + project(&g_hat[nu]) * &k1 + r * k2.transpose()
    }))
}

/// The row problem min ‖Ψ_sᵀ z − c‖² + λ‖z_nonlinear‖² s.t. Ψ(P)ᵀ z = d and, for a TPS, the
/// side conditions: its solution is zᵀ = cᵀ K1 + d k2ᵀ; returns (K1, k2).
fn row_problem(
    basis: &HandleBasis,
    psi_s: &DMatrix<f64>,
    a0: &DVector<f64>,
    lambda: f64,
) -> Result<(DMatrix<f64>, DVector<f64>), FitError> {
    let (len, m, lin, d) = (basis.len(), psi_s.ncols(), basis.linear_len(), basis.coordinate_count());
    let tps = basis.kind() == BasisKind::Tps;
    let p = if tps { 1 + lin } else { 1 };
    let mut c = DMatrix::zeros(len, p);
    c.set_column(0, a0);
    if tps {
        for (k, u) in basis.scaled_centres().chunks_exact(d).enumerate() {
            c[(lin + k, 1)] = 1.0;
            for (a, &x) in u.iter().enumerate() {
                c[(lin + k, 2 + a)] = x;
            }
        }
    }
    let qr_c = c.qr();
    let r_c = qr_c.r();
    if !well_conditioned(&r_c) {
        return Err(FitError::Singular { what: "side conditions" });
    }
    let mut q = DMatrix::identity(len, len);
    qr_c.q_tr_mul(&mut q);
    let q = q.transpose();
    let q2 = q.columns(p, len - p).into_owned();
    let mut e1 = DVector::zeros(p);
    e1[0] = 1.0;
    let y = r_c.transpose().solve_lower_triangular(&e1).ok_or(FitError::Singular { what: "side conditions" })?;
    let zp0 = q.columns(0, p) * y;

    let ridge = if lambda > 0.0 { len - lin } else { 0 };
    let mut aug = DMatrix::zeros(m + ridge, len);
    aug.rows_mut(0, m).copy_from(&psi_s.transpose());
    for j in 0..ridge {
        aug[(m + j, lin + j)] = lambda.sqrt();
    }
    let b2 = &aug * &q2;
    if b2.nrows() < b2.ncols() {
        return Err(FitError::TooFewSamples { samples: m, basis_size: len });
    }
    let qr = b2.qr();
    let (q1, r) = (qr.q(), qr.r());
    if !well_conditioned(&r) {
        return Err(FitError::Singular { what: "samples" });
    }
    let singular = FitError::Singular { what: "samples" };
    let y = r.solve_upper_triangular(&q1.rows(0, m).transpose()).ok_or(singular.clone())?;
    let k1 = (&q2 * y).transpose();
    let v = q1.transpose() * (&aug * &zp0);
    let w = r.solve_upper_triangular(&v).ok_or(singular)?;
    let k2 = zp0 - &q2 * w;
    Ok((k1, k2))
}

/// Whether an upper-triangular factor has no diagonal entry below 1e-12 of its largest
/// (an empty one is: a basis of the constant alone has nothing left to fit).
fn well_conditioned(r: &DMatrix<f64>) -> bool {
    let diagonal = r.diagonal();
    if diagonal.is_empty() {
        return true;
    }
    let largest = diagonal.amax();
    largest > 0.0 && diagonal.iter().all(|x| x.abs() > 1e-12 * largest)
}

#[cfg(test)]
#[path = "fit_tests.rs"]
mod tests;
