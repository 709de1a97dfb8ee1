//! The ground-truth energies of DefOp (paper §4, "Deformation energies"): per-triangle
//! Jacobians, their closed-form signed 2 x 2 SVD, the ARAP density (eq. 10)
//! `(Σ - 1)^2 + (σ - 1)^2` and the S-ARAP density (eq. 11) `(Σ - 1)^2 + (1/σ - 1)^2`, with
//! their gradients and positive semidefinite projected Hessians with respect to the
//! Jacobian and to a triangle's vertex positions.
//!
//! **Signed SVD.** For `J = [[a, b], [c, d]]` let `E = (a + d)/2`, `F = (a - d)/2`,
//! `G = (c + b)/2`, `H = (c - b)/2`, `Q = |(E, H)|`, `R = |(F, G)|`. Then `J` is the sum of
//! the similarity `[[E, -H], [H, E]]` and the anti-similarity `[[F, G], [G, -F]]`,
//! `Σ = Q + R` and `σ = Q - R` (negative exactly when `det J = Q^2 - R^2 < 0`), and
//! `J = U diag(Σ, σ) V^T` with rotations `U`, `V` by `(θ_Q + θ_R)/2` and `(θ_R - θ_Q)/2`
//! (`θ_Q = atan2(H, E)`, `θ_R = atan2(G, F)`). `σ` is computed as `det J / Σ`, free of the
//! cancellation of `Q - R`.
//!
//! **Eigensystem.** Both densities are `ψ = (Σ - 1)^2 + h(σ)` (ARAP `h = (σ - 1)^2`, S-ARAP
//! `h = (1/σ - 1)^2`). In the orthonormal basis of 2 x 2 matrices (Frobenius) made of the
//! unit similarity and anti-similarity directions, `Q` and `R` are `1/√2` times the norms of
//! the two planar components, so the Hessian of `ψ` has four eigenpairs (derived here, in
//! the spirit of Smith, De Goes and Kim's analytic eigensystems):
//! - scaling in `Σ`: `U e1 e1^T V^T`, eigenvalue `2`;
//! - scaling in `σ`: `U e2 e2^T V^T`, eigenvalue `h''(σ)`;
//! - twist (the in-plane rotation of the similarity part): eigenvalue
//!   `(ψ_Σ + ψ_σ)/(Σ + σ) = ψ_Q / (2Q)`;
//! - flip (the rotation of the anti-similarity part): eigenvalue
//!   `(ψ_Σ - ψ_σ)/(Σ - σ) = ψ_R / (2R)`.
//!
//! The gradient is `∂ψ/∂J = λ_twist [[E, -H], [H, E]] + λ_flip [[F, G], [G, -F]]`, and the
//! projected Hessian keeps the eigenvectors and clamps negative eigenvalues to 0.
//!
//! **Guards.** At `R = 0` (conformal `J`) the flip direction is arbitrary and its eigenvalue
//! is computed in a form without the division `0/0`; for S-ARAP it is `+∞` when
//! `κ = 2(Q - 1)(1 - Q^-3) > 0` (the density has a convex kink there, notes §4 item 2), and
//! is capped at [`KINK_CAP`]. At `Q = 0` (ARAP only, `σ = -Σ`) the twist eigenvalue is
//! `-∞`, projected to 0, and the similarity part of the gradient is 0. S-ARAP is `+∞` for
//! `σ <= 0` (a flipped or collapsed triangle); there gradients and Hessians are `None`.

use std::fmt;

use crate::geometry::Point;

/// A 2 x 2 Jacobian `[[a, b], [c, d]]` (rows). As a 4-vector it is `(a, b, c, d)`.
pub type Jacobian = [[f64; 2]; 2];

/// A Hessian with respect to a Jacobian, as a 4 x 4 matrix in `(a, b, c, d)`.
type Hessian = [[f64; 4]; 4];

/// The cap on the S-ARAP flip eigenvalue at its kink (near `R = 0` with `κ > 0`), where the
/// exact value grows like `κ / (2R)` without bound.
pub const KINK_CAP: f64 = 1e8;

/// Which ground-truth energy density.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Energy {
    /// As-rigid-as-possible (eq. 10): `(Σ - 1)^2 + (σ - 1)^2`, equal to `min_R |J - R|_F^2`
    /// over rotations `R`.
    Arap,
    /// Symmetric ARAP (eq. 11): `(Σ - 1)^2 + (1/σ - 1)^2`, `+∞` for `σ <= 0`.
    SArap,
}

impl Energy {
    /// The energy's name: `"arap"` or `"s-arap"`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Arap => "arap",
            Self::SArap => "s-arap",
        }
    }

    /// Whether the energy is infinite on flipped triangles (S-ARAP).
    pub fn blocks_flips(self) -> bool {
        self == Self::SArap
    }

    /// The density `ψ(J)` (`+∞` for S-ARAP when `det J <= 0`).
    pub fn density(self, j: &Jacobian) -> f64 {
        self.density_of(&SignedSvd::new(j))
    }

    fn density_of(self, s: &SignedSvd) -> f64 {
        match self {
            Self::Arap => (s.sigma_1 - 1.0).powi(2) + (s.sigma_2 - 1.0).powi(2),
            Self::SArap if s.sigma_2 > 0.0 => (s.sigma_1 - 1.0).powi(2) + (1.0 / s.sigma_2 - 1.0).powi(2),
            Self::SArap => f64::INFINITY,
        }
    }

    /// The gradient `∂ψ/∂J`; `None` where the density is infinite.
    pub fn gradient(self, j: &Jacobian) -> Option<Jacobian> {
        Some(Modes::new(self, j)?.gradient())
    }

    /// The four eigenpairs of the Hessian `∂²ψ/∂J²` (eigenvalue, unit eigenvector as
    /// `(a, b, c, d)`), in the order scaling in `Σ`, scaling in `σ`, twist, flip; `None`
    /// where the density is infinite. Eigenvalues are exact except at the guards of the
    /// module documentation (`Q = 0`: twist `-∞`; S-ARAP kink: flip capped at
    /// [`KINK_CAP`]).
    pub fn eigensystem(self, j: &Jacobian) -> Option<[(f64, [f64; 4]); 4]> {
        Some(Modes::new(self, j)?.eigensystem())
    }

    /// The Hessian `∂²ψ/∂J²` as a 4 x 4 matrix in `(a, b, c, d)`, or with `projected` its
    /// positive semidefinite projection (negative eigenvalues set to 0); `None` where the
    /// density is infinite, and (not projected) at `Q = 0`, where it does not exist.
    pub fn hessian(self, j: &Jacobian, projected: bool) -> Option<[[f64; 4]; 4]> {
        hessian_of(&self.eigensystem(j)?, projected)
    }
}

impl Energy {
    /// The S-ARAP kink at conformal Jacobians: `(κ, R)` with `κ = 2(Q - 1)(1 - Q^-3)` the
    /// slope of the cone `ψ ≈ ψ(Q, 0) + κ R` at `R = 0`, when `κ > 0`; `None` for ARAP
    /// (smooth) and where the density is infinite.
    pub fn kink(self, j: &Jacobian) -> Option<(f64, f64)> {
        self.kink_of(&SignedSvd::new(j))
    }

    fn kink_of(self, s: &SignedSvd) -> Option<(f64, f64)> {
        if self == Self::Arap {
            return None;
        }
        let kappa = 2.0 * (s.q - 1.0) * (1.0 - 1.0 / s.q.powi(3));
        (kappa > 0.0 && s.sigma_2 > 0.0).then_some((kappa, s.r))
    }

    /// S-ARAP with a triangle held at its kink: the cone `κ R` replaced by the penalty
    /// `K R^2` (`K` = [`KINK_CAP`], so the anti-similarity part `w`, `|w| = √2 R`, is held
    /// near 0 by the force `K w`): the density `ψ - κR + K R^2`, its gradient and its
    /// projected Hessian (flip eigenvalue `ψ_R/(2R) - κ/(2R) + K`, plus `K ŵŵ^T`, so the
    /// whole anti-similarity plane has curvature `K` more). The Hessian leaves out the
    /// second derivatives of `κ(Q) R` that involve `Q` (small once `R` is about `κ/K`); the
    /// gradient is exact. `None` where [`Self::kink`] is.
    pub fn held(self, j: &Jacobian) -> Option<(f64, Jacobian, [[f64; 4]; 4])> {
        Local::new(self, j)?.held()
    }
}

/// One triangle's terms at one Jacobian from a single signed SVD: what [`Energy::density`],
/// [`Energy::kink`], [`Energy::gradient`], [`Energy::hessian`] and [`Energy::held`] give,
/// each of which computes the SVD anew (the ground truth's assembly needs most of them per
/// triangle per iteration).
pub(crate) struct Local {
    energy: Energy,
    modes: Modes,
}

impl Local {
    /// `None` where the density is infinite (S-ARAP, `σ <= 0`).
    pub(crate) fn new(energy: Energy, j: &Jacobian) -> Option<Self> {
        Some(Self { energy, modes: Modes::new(energy, j)? })
    }

    /// [`Energy::density`].
    pub(crate) fn density(&self) -> f64 {
        self.energy.density_of(&self.modes.svd)
    }

    /// [`Energy::kink`].
    pub(crate) fn kink(&self) -> Option<(f64, f64)> {
        self.energy.kink_of(&self.modes.svd)
    }

    /// [`Energy::gradient`].
    pub(crate) fn gradient(&self) -> Jacobian {
        self.modes.gradient()
    }

    /// The Hessian, projected ([`Energy::hessian`] with `projected`), and, if asked for, the
    /// exact one where it exists.
    pub(crate) fn hessians(&self, exact: bool) -> (Option<Hessian>, Option<Hessian>) {
        let modes = self.modes.eigensystem();
        (hessian_of(&modes, true), if exact { hessian_of(&modes, false) } else { None })
    }

    /// [`Energy::held`].
    pub(crate) fn held(&self) -> Option<(f64, Jacobian, [[f64; 4]; 4])> {
        let (kappa, r) = self.kink()?;
        let mut m = self.modes.clone();
        let density = self.density() - kappa * r + KINK_CAP * r * r;
        m.flip = m.flip_smooth + KINK_CAP;
        m.flip_gradient = m.flip_smooth + KINK_CAP;
        // d(κ(Q) R)/dQ = κ'(Q) R, κ' = 2 (1 + 2 Q^-3 - 3 Q^-4), through ∂Q/∂J = S / (2Q).
        let q = m.svd.q;
        let twist = m.twist;
        m.twist -= 2.0 * (1.0 + 2.0 / q.powi(3) - 3.0 / q.powi(4)) * r / (2.0 * q);
        let gradient = m.gradient();
        m.twist = twist;
        let modes = m.eigensystem();
        let mut hessian = hessian_of(&modes, true)?;
        let w = m.anti_similarity_direction();
        for (row, wr) in hessian.iter_mut().zip(w) {
            for (x, wc) in row.iter_mut().zip(w) {
                *x += KINK_CAP * wr * wc;
            }
        }
        Some((density, gradient, hessian))
    }
}

impl fmt::Display for Energy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The closed-form signed SVD of a 2 x 2 matrix (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SignedSvd {
    /// `(a + d)/2`.
    pub e: f64,
    /// `(a - d)/2`.
    pub f: f64,
    /// `(c + b)/2`.
    pub g: f64,
    /// `(c - b)/2`.
    pub h: f64,
    /// `|(E, H)|`, the size of the similarity part.
    pub q: f64,
    /// `|(F, G)|`, the size of the anti-similarity part.
    pub r: f64,
    /// The larger singular value `Σ = Q + R >= 0`.
    pub sigma_1: f64,
    /// The signed smaller singular value `σ = Q - R` (`det / Σ`; negative iff `det < 0`).
    pub sigma_2: f64,
}

impl SignedSvd {
    /// The signed SVD of `j`.
    pub fn new(j: &Jacobian) -> Self {
        let [[a, b], [c, d]] = *j;
        let (e, f, g, h) = ((a + d) / 2.0, (a - d) / 2.0, (c + b) / 2.0, (c - b) / 2.0);
        let (q, r) = (hypot(e, h), hypot(f, g));
        let sigma_1 = q + r;
        let det = a * d - b * c;
        let sigma_2 = if sigma_1 > 0.0 { (det / sigma_1).clamp(-sigma_1, sigma_1) } else { 0.0 };
        Self { e, f, g, h, q, r, sigma_1, sigma_2 }
    }

    /// The angle of `U` in `J = U diag(Σ, σ) V^T`.
    pub fn u_angle(&self) -> f64 {
        (libm::atan2(self.h, self.e) + libm::atan2(self.g, self.f)) / 2.0
    }

    /// The angle of `V` in `J = U diag(Σ, σ) V^T`.
    pub fn v_angle(&self) -> f64 {
        (libm::atan2(self.g, self.f) - libm::atan2(self.h, self.e)) / 2.0
    }
}

/// `√(x² + y²)` by the square root of IEEE 754, which is exactly rounded on every platform
/// (so the same bits natively and in wasm, where `libm::hypot` is a software routine that
/// cost the ground truth's Newton iterations a large share of their time), when `x² + y²`
/// is a normal number; else (zero, subnormal or overflowed) `libm::hypot`.
fn hypot(x: f64, y: f64) -> f64 {
    let s = x * x + y * y;
    if s.is_normal() {
        s.sqrt()
    } else {
        libm::hypot(x, y)
    }
}

/// `sum_k λ_k v_k v_k^T` over eigenpairs, with `projected` negative `λ_k` set to 0; `None`
/// if an eigenvalue kept is not finite.
fn hessian_of(modes: &[(f64, [f64; 4]); 4], projected: bool) -> Option<[[f64; 4]; 4]> {
    let mut out = [[0.0; 4]; 4];
    for &(lambda, v) in modes {
        let lambda = if projected { lambda.max(0.0) } else { lambda };
        if lambda == 0.0 {
            continue;
        }
        if !lambda.is_finite() {
            return None;
        }
        for (row, vr) in out.iter_mut().zip(v) {
            for (x, vc) in row.iter_mut().zip(v) {
                *x += lambda * vr * vc;
            }
        }
    }
    Some(out)
}

/// The signed SVD with the eigenvalues of the twist, the flip and the `σ` scaling.
#[derive(Clone)]
struct Modes {
    svd: SignedSvd,
    twist: f64,
    /// The flip eigenvalue, capped at [`KINK_CAP`].
    flip: f64,
    /// `ψ_R / (2R)` uncapped (the gradient's coefficient; any finite value at `R = 0`).
    flip_gradient: f64,
    /// `(ψ_R - κ)/(2R)`: the flip eigenvalue without the kink's cone.
    flip_smooth: f64,
    h2: f64,
}

impl Modes {
    fn new(energy: Energy, j: &Jacobian) -> Option<Self> {
        let svd = SignedSvd::new(j);
        let (q, r, big, small) = (svd.q, svd.r, svd.sigma_1, svd.sigma_2);
        match energy {
            // ψ = 2 (Q - 1)^2 + 2 R^2: ψ_Q = 4 (Q - 1), ψ_R = 4 R.
            Energy::Arap => {
                Some(Self { svd, twist: 2.0 - 2.0 / q, flip: 2.0, flip_gradient: 2.0, flip_smooth: 2.0, h2: 2.0 })
            }
            Energy::SArap => {
                if small <= 0.0 || !small.is_finite() {
                    return None;
                }
                // h'(σ) = -2 (1 - σ)/σ^3, h''(σ) = (6 - 4σ)/σ^4.
                let h1 = -2.0 * (1.0 - small) / small.powi(3);
                let h2 = (6.0 - 4.0 * small) / small.powi(4);
                let twist = (2.0 * (big - 1.0) + h1) / (2.0 * q);
                // ψ_R / (2R) = κ / (2R) + 1 + (Q^2 + Qσ + σ^2)/(Q^3 σ^3) - (Q + σ)/(Q^2 σ^2),
                // κ = ψ_R at R = 0 (exact division of differences; no 0/0).
                let kappa = 2.0 * (q - 1.0) * (1.0 - 1.0 / q.powi(3));
                let kink = if kappa > 0.0 && r > 0.0 { kappa / (2.0 * r) } else { 0.0 };
                let capped = match (kappa > 0.0, r > 0.0) {
                    (false, _) => 0.0,
                    (true, true) => kink.min(KINK_CAP),
                    (true, false) => KINK_CAP,
                };
                let qs = q * small;
                let rest = 1.0 + (q * q + qs + small * small) / (qs * qs * qs) - (q + small) / (qs * qs);
                Some(Self { svd, twist, flip: capped + rest, flip_gradient: kink + rest, flip_smooth: rest, h2 })
            }
        }
    }
}

impl Modes {
    /// `λ_twist [[E, -H], [H, E]] + λ_flip [[F, G], [G, -F]]` (module documentation).
    fn gradient(&self) -> Jacobian {
        let s = &self.svd;
        let twist = if s.q > 0.0 { self.twist } else { 0.0 };
        let flip = self.flip_gradient;
        [[twist * s.e + flip * s.f, -twist * s.h + flip * s.g], [twist * s.h + flip * s.g, twist * s.e - flip * s.f]]
    }

    /// The unit anti-similarity direction `ŵ` as a 4-vector (arbitrary at `R = 0`).
    fn anti_similarity_direction(&self) -> [f64; 4] {
        let s = &self.svd;
        let (cf, cg) = if s.r > 0.0 { (s.f / s.r, s.g / s.r) } else { (1.0, 0.0) };
        let r2 = std::f64::consts::FRAC_1_SQRT_2;
        [cf * r2, cg * r2, cg * r2, -cf * r2]
    }

    /// The eigenpairs: scaling in `Σ`, scaling in `σ`, twist, flip.
    fn eigensystem(&self) -> [(f64, [f64; 4]); 4] {
        let s = &self.svd;
        // Unit directions of the similarity part (u) and the anti-similarity part (w), and
        // their rotations in their planes (t, l), as 4-vectors; arbitrary where a part is 0.
        let (ce, ch) = if s.q > 0.0 { (s.e / s.q, s.h / s.q) } else { (1.0, 0.0) };
        let r2 = std::f64::consts::FRAC_1_SQRT_2;
        let u = [ce * r2, -ch * r2, ch * r2, ce * r2];
        let w = self.anti_similarity_direction();
        let t = [-ch * r2, -ce * r2, ce * r2, -ch * r2];
        let l = [-w[1], w[0], w[0], w[1]];
        let big: [f64; 4] = std::array::from_fn(|k| (u[k] + w[k]) * r2);
        let small: [f64; 4] = std::array::from_fn(|k| (u[k] - w[k]) * r2);
        let twist = if s.q > 0.0 { self.twist } else { f64::NEG_INFINITY };
        [(2.0, big), (self.h2, small), (twist, t), (self.flip, l)]
    }
}

/// A rest triangle: its area and the inverse of its edge matrix `D_m = [x1 - x0, x2 - x0]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RestTriangle {
    /// `D_m^-1` (rows).
    pub inverse: Jacobian,
    /// The rest area `A_t > 0`.
    pub area: f64,
}

impl RestTriangle {
    /// The rest triangle of three counter-clockwise points; `None` if its area is not
    /// positive or not finite.
    pub fn new(rest: [Point; 3]) -> Option<Self> {
        let (e1, e2) = (sub(rest[1], rest[0]), sub(rest[2], rest[0]));
        let det = e1[0] * e2[1] - e2[0] * e1[1];
        let inverse = [[e2[1] / det, -e2[0] / det], [-e1[1] / det, e1[0] / det]];
        let area = det / 2.0;
        (area > 0.0 && area.is_finite() && inverse.iter().flatten().all(|x| x.is_finite()))
            .then_some(Self { inverse, area })
    }

    /// `∂J/∂x_v` per corner `v`: `J = sum_v x_v w_v^T`, with `w_1`, `w_2` the rows of
    /// `D_m^-1` and `w_0 = -w_1 - w_2`.
    pub fn weights(&self) -> [[f64; 2]; 3] {
        let m = self.inverse;
        [[-m[0][0] - m[1][0], -m[0][1] - m[1][1]], m[0], m[1]]
    }

    /// The Jacobian `J = D_s D_m^-1` of the affine map to the triangle `p`.
    pub fn jacobian(&self, p: [Point; 3]) -> Jacobian {
        let (f1, f2) = (sub(p[1], p[0]), sub(p[2], p[0]));
        let m = self.inverse;
        std::array::from_fn(|i| std::array::from_fn(|j| f1[i] * m[0][j] + f2[i] * m[1][j]))
    }

    /// The triangle's energy `A_t ψ(J)`.
    pub fn energy(&self, energy: Energy, p: [Point; 3]) -> f64 {
        self.area * energy.density(&self.jacobian(p))
    }

    /// The gradient of [`Self::energy`] with respect to `(x0, y0, x1, y1, x2, y2)`; `None`
    /// where the energy is infinite.
    pub fn gradient(&self, energy: Energy, p: [Point; 3]) -> Option<[f64; 6]> {
        let dpsi = energy.gradient(&self.jacobian(p))?;
        let w = self.weights();
        Some(std::array::from_fn(|k| {
            let (v, i) = (k / 2, k % 2);
            self.area * (dpsi[i][0] * w[v][0] + dpsi[i][1] * w[v][1])
        }))
    }

    /// The 6 x 6 Hessian of [`Self::energy`] in `(x0, y0, x1, y1, x2, y2)`, projected to
    /// positive semidefinite with `projected` ([`Energy::hessian`]); `None` where that is.
    pub fn hessian(&self, energy: Energy, p: [Point; 3], projected: bool) -> Option<[[f64; 6]; 6]> {
        let hj = energy.hessian(&self.jacobian(p), projected)?;
        Some(self.expand(&hj))
    }

    /// `A_t B^T H_J B` with `B = ∂vec(J)/∂x`: `J_ij = sum_v w_v[j] x_v[i]`.
    pub(crate) fn expand(&self, hj: &[[f64; 4]; 4]) -> [[f64; 6]; 6] {
        let w = self.weights();
        let mut out = [[0.0; 6]; 6];
        for (a, row) in out.iter_mut().enumerate() {
            let (v, i) = (a / 2, a % 2);
            for (b, x) in row.iter_mut().enumerate() {
                let (u, k) = (b / 2, b % 2);
                let mut sum = 0.0;
                for j in 0..2 {
                    for l in 0..2 {
                        sum += w[v][j] * hj[2 * i + j][2 * k + l] * w[u][l];
                    }
                }
                *x = self.area * sum;
            }
        }
        out
    }
}

fn sub(a: Point, b: Point) -> Point {
    [a[0] - b[0], a[1] - b[1]]
}

#[cfg(test)]
#[path = "energy_tests.rs"]
mod tests;
