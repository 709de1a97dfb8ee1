//! Handle bases Ψ: functions on the space of handle targets Q ∈ R^{2n} (paper §3.1; notes
//! §1), through the k handle coordinates u = Bᵀ(Q̂ − P) / r_s of [`HandleCoordinates`]
//! (P the rest handles, r_s the sampling radius; B = I and u = (Q − P) / r_s, k = 2n, unless
//! the operator is canonical or has fixed handles). Every basis starts with the k + 1
//! linear functions {1, u_1, …, u_k}; quadratic and cubic add the monomials u_a u_b (a ≤ b)
//! and u_a u_b u_c (a ≤ b ≤ c); the thin-plate spline (TPS) adds one radial function
//! ρ(‖u − u_j‖), ρ(r) = r² log r, per training sample. Scaled displacements span the same
//! function space as raw monomials, far better conditioned.
//!
//! Sizes |Ψ| with d = k: d + 1, 1 + 3d/2 + d²/2, C(d + 3, 3) and 1 + d + m (the notes §1
//! table at d = 2n).

use super::coordinates::HandleCoordinates;
use super::fit_error::{check_finite, check_length, FitError};

/// The largest handle basis accepted: 2^20 functions (a cubic basis of 50 handles has
/// 176,851; one coefficient row of 2^20 doubles is 8 MB).
pub const MAX_BASIS_SIZE: usize = 1 << 20;

/// Which functions of the handle targets a deformation operator combines.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BasisKind {
    /// 1 and the k coordinates: k + 1 functions (2n + 1 with all coordinates).
    Linear,
    /// Linear plus all products of two coordinates: 1 + 3k/2 + k²/2 functions (1 + 3n + 2n²).
    Quadratic,
    /// Quadratic plus all products of three coordinates: C(k + 3, 3) functions.
    Cubic,
    /// Linear plus one thin-plate radial function per training sample: 1 + k + m functions.
    Tps,
}

impl BasisKind {
    /// The number of functions |Ψ| with `handles` handles (all 2n coordinates) and
    /// `samples` training samples (the samples count only for [`BasisKind::Tps`]);
    /// `usize::MAX` if it does not fit.
    pub fn size(self, handles: usize, samples: usize) -> usize {
        self.size_in(handles.saturating_mul(2), samples)
    }

    /// The number of functions |Ψ| in `coordinates` handle coordinates k (see
    /// [`HandleCoordinates`]) with `samples` training samples; `usize::MAX` if it does not fit.
    pub fn size_in(self, coordinates: usize, samples: usize) -> usize {
        // Coordinate counts beyond 2^41 saturate before the products can overflow u128.
        let d = (coordinates as u128).min(1 << 41);
        let size = match self {
            Self::Linear => d + 1,
            Self::Quadratic => d + 1 + d * (d + 1) / 2,
            Self::Cubic => (d + 3) * (d + 2) * (d + 1) / 6,
            Self::Tps => d + 1 + samples as u128,
        };
        usize::try_from(size).unwrap_or(usize::MAX)
    }

    /// Whether the basis is a polynomial one (its size does not depend on the samples).
    pub fn is_polynomial(self) -> bool {
        self != Self::Tps
    }

    /// The polynomial degree (1 for the TPS's linear tail).
    pub fn degree(self) -> usize {
        match self {
            Self::Linear | Self::Tps => 1,
            Self::Quadratic => 2,
            Self::Cubic => 3,
        }
    }
}

/// The thin-plate kernel ρ(r) = r² log r as a function of s = r²: s log(s) / 2, and 0 at 0.
pub(crate) fn thin_plate(r2: f64) -> f64 {
    if r2 > 0.0 {
        0.5 * r2 * libm::log(r2)
    } else {
        0.0
    }
}

/// A handle basis Ψ fixed at training time: its kind, its handle coordinates (the rest
/// handles P and the map B) and their scale r_s, and for a TPS its centres.
#[derive(Debug, Clone, PartialEq)]
pub struct HandleBasis {
    kind: BasisKind,
    coordinates: HandleCoordinates,
    scale: f64,
    /// TPS centres in scaled coordinates u, `k` numbers each.
    centres: Vec<f64>,
    len: usize,
}

impl HandleBasis {
    /// A polynomial basis ([`BasisKind::Linear`], [`BasisKind::Quadratic`] or
    /// [`BasisKind::Cubic`]) in all coordinates around the rest handles `rest` (2n numbers)
    /// with scale `scale`. A [`BasisKind::Tps`] needs its centres: use [`HandleBasis::tps`].
    pub fn polynomial(kind: BasisKind, rest: &[f64], scale: f64) -> Result<Self, FitError> {
        Self::new(kind, HandleCoordinates::full(rest)?, scale, &[])
    }

    /// A thin-plate spline basis in all coordinates with one radial function centred at each
    /// of `centres` (handle targets, 2n numbers each, at least one), around the rest handles
    /// `rest` with scale `scale`.
    pub fn tps(rest: &[f64], scale: f64, centres: &[f64]) -> Result<Self, FitError> {
        Self::new(BasisKind::Tps, HandleCoordinates::full(rest)?, scale, centres)
    }

    /// A basis of `kind` in the handle coordinates `coordinates` with scale `scale`; for a
    /// TPS, one radial function centred at each of `centres` (handle targets Q̂ as the
    /// coordinates see them, canonical if they are; 2n numbers each, at least one; a TPS
    /// needs k ≥ 1). Polynomial bases take no centres.
    pub fn new(kind: BasisKind, coordinates: HandleCoordinates, scale: f64, centres: &[f64]) -> Result<Self, FitError> {
        let d = coordinates.rest().len();
        if !kind.is_polynomial() && centres.is_empty() {
            return Err(FitError::NoSamples);
        }
        check_length("centres", centres, centres.len().div_ceil(d) * d)?;
        check_finite("centres", centres)?;
        if !(scale.is_finite() && scale > 0.0) {
            return Err(FitError::InvalidOption { name: "scale", value: scale, expected: "a positive finite length" });
        }
        let k = coordinates.len();
        let mut scaled = vec![0.0; centres.len() / d * k];
        for (u, q) in scaled.chunks_exact_mut(k.max(1)).zip(centres.chunks_exact(d)) {
            coordinates.project(q, u);
            u.iter_mut().for_each(|x| *x /= scale);
        }
        Self::from_parts(kind, coordinates, scale, scaled)
    }

    /// A basis from its parts as [`HandleBasis::coordinates`], [`HandleBasis::scale`] and
    /// [`HandleBasis::scaled_centres`] give them (an operator file), checked as the other
    /// constructors check theirs.
    pub(crate) fn from_parts(
        kind: BasisKind,
        coordinates: HandleCoordinates,
        scale: f64,
        scaled_centres: Vec<f64>,
    ) -> Result<Self, FitError> {
        check_finite("centres", &scaled_centres)?;
        let tps = kind == BasisKind::Tps;
        let k = coordinates.len();
        if tps == scaled_centres.is_empty() || (tps && k == 0) || !scaled_centres.len().is_multiple_of(k.max(1)) {
            return Err(FitError::InvalidOption {
                name: "centres",
                value: scaled_centres.len() as f64,
                expected: "centres, k ≥ 1 numbers each, for a TPS basis only",
            });
        }
        if !(scale.is_finite() && scale > 0.0) {
            return Err(FitError::InvalidOption { name: "scale", value: scale, expected: "a positive finite length" });
        }
        let len = kind.size_in(k, scaled_centres.len() / k.max(1));
        if len > MAX_BASIS_SIZE {
            return Err(FitError::InvalidOption {
                name: "handles",
                value: coordinates.rest().len() as f64 / 2.0,
                expected: "few enough handles (and samples) for at most 2^20 handle basis functions",
            });
        }
        Ok(Self { kind, coordinates, scale, centres: scaled_centres, len })
    }

    /// The kind of basis.
    pub fn kind(&self) -> BasisKind {
        self.kind
    }

    /// The number of handles n.
    pub fn handle_count(&self) -> usize {
        self.coordinates.rest().len() / 2
    }

    /// The handle coordinates: rest handles, canonical or not, fixed handles.
    pub fn coordinates(&self) -> &HandleCoordinates {
        &self.coordinates
    }

    /// The number of handle coordinates k.
    pub fn coordinate_count(&self) -> usize {
        self.coordinates.len()
    }

    /// The number of functions |Ψ|.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Always false: every basis holds at least the constant function.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The number of linear functions k + 1, which come first in every basis.
    pub fn linear_len(&self) -> usize {
        self.coordinates.len() + 1
    }

    /// The rest handles P (2n numbers).
    pub fn rest(&self) -> &[f64] {
        self.coordinates.rest()
    }

    /// The scale r_s of the coordinates u = (z − z_P) / r_s.
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// The TPS centres in scaled coordinates u (k numbers each; empty for a polynomial).
    pub fn scaled_centres(&self) -> &[f64] {
        &self.centres
    }

    /// The coefficients of the function Q ↦ q̂_a (coordinate a of the targets as the
    /// coordinates see them) in this basis: `(constant, linear)`, meaning
    /// q̂_a = constant · ψ_0 + Σ_j linear_j ψ_{1+j} (k numbers: r_s times row a of B); every
    /// other coefficient is zero.
    pub fn coordinate(&self, a: usize) -> (f64, Vec<f64>) {
        let mut row = self.coordinates.row(a);
        row.iter_mut().for_each(|x| *x *= self.scale);
        (self.coordinates.rest()[a], row)
    }

    /// Writes Ψ(Q̂) to `out` (|Ψ| numbers) for handle targets `z` = Q̂ (2n numbers, already
    /// canonical for canonical coordinates); allocates nothing. Refuses wrong lengths and NaN
    /// or infinite targets.
    pub fn evaluate_into(&self, z: &[f64], out: &mut [f64]) -> Result<(), FitError> {
        check_length("targets", z, self.coordinates.rest().len())?;
        check_finite("targets", z)?;
        if out.len() != self.len {
            return Err(FitError::Length { what: "output", expected: self.len, found: out.len() });
        }
        self.evaluate_unchecked(z, out);
        Ok(())
    }

    /// [`HandleBasis::evaluate_into`] without the checks (lengths are the caller's invariant).
    pub(crate) fn evaluate_unchecked(&self, z: &[f64], out: &mut [f64]) {
        let d = self.coordinates.len();
        out[0] = 1.0;
        let inv = 1.0 / self.scale;
        self.coordinates.project(z, &mut out[1..=d]);
        for u in &mut out[1..=d] {
            *u *= inv;
        }
        let (linear, rest) = out.split_at_mut(d + 1);
        let u = &linear[1..];
        let mut k = 0;
        match self.kind {
            BasisKind::Linear => {}
            BasisKind::Quadratic | BasisKind::Cubic => {
                for a in 0..d {
                    for b in a..d {
                        rest[k] = u[a] * u[b];
                        k += 1;
                    }
                }
                if self.kind == BasisKind::Cubic {
                    for a in 0..d {
                        for b in a..d {
                            let ab = u[a] * u[b];
                            for &uc in &u[b..] {
                                rest[k] = ab * uc;
                                k += 1;
                            }
                        }
                    }
                }
            }
            BasisKind::Tps => {
                for (value, centre) in rest.iter_mut().zip(self.centres.chunks_exact(d.max(1))) {
                    let r2: f64 = u.iter().zip(centre).map(|(a, c)| (a - c) * (a - c)).sum();
                    *value = thin_plate(r2);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every exponent vector in `vars` variables of total degree at most `degree`.
    fn exponents(vars: usize, degree: usize) -> Vec<Vec<usize>> {
        if vars == 0 {
            return vec![Vec::new()];
        }
        let mut all = Vec::new();
        for e in 0..=degree {
            for mut tail in exponents(vars - 1, degree - e) {
                tail.insert(0, e);
                all.push(tail);
            }
        }
        all
    }

    fn binomial(n: usize, k: usize) -> usize {
        (0..k).fold(1, |acc, i| acc * (n - i) / (i + 1))
    }

    /// Test plan 1: sizes for n = 1..11 equal the paper's formulas, counted by enumerating
    /// the monomials, and the basis's values are exactly those monomials.
    #[test]
    fn sizes_match_the_formulas_and_the_enumerated_monomials() {
        for n in 1..=11usize {
            let d = 2 * n;
            let rest: Vec<f64> = (0..d).map(|a| 0.3 * a as f64 - 1.0).collect();
            let z: Vec<f64> = (0..d).map(|a| rest[a] + 0.5 * (0.7 + 0.13 * a as f64).sin()).collect();
            let u: Vec<f64> = z.iter().zip(&rest).map(|(z, r)| (z - r) / 0.5).collect();
            for (kind, degree, formula) in [
                (BasisKind::Linear, 1, 2 * n + 1),
                (BasisKind::Quadratic, 2, 1 + 3 * n + 2 * n * n),
                (BasisKind::Cubic, 3, binomial(2 * n + 3, 3)),
            ] {
                if degree == 3 {
                    // 1 + 11n/3 + 4n² + 4n³/3, the paper's form, times 3.
                    assert_eq!(3 * formula, 3 + 11 * n + 12 * n * n + 4 * n * n * n);
                }
                let monomials = exponents(d, degree);
                assert_eq!(monomials.len(), formula, "{kind:?}, n = {n}");
                let basis = HandleBasis::polynomial(kind, &rest, 0.5).unwrap();
                assert_eq!(basis.len(), formula);
                assert_eq!(kind.size(n, 0), formula);
                if n <= 4 {
                    let mut values = vec![0.0; basis.len()];
                    basis.evaluate_into(&z, &mut values).unwrap();
                    let mut expected: Vec<f64> =
                        monomials.iter().map(|e| e.iter().zip(&u).map(|(&k, &x)| x.powi(k as i32)).product()).collect();
                    values.sort_by(f64::total_cmp);
                    expected.sort_by(f64::total_cmp);
                    for (v, e) in values.iter().zip(&expected) {
                        assert!((v - e).abs() <= 1e-14 * (1.0 + e.abs()), "{kind:?} n = {n}: {v} vs {e}");
                    }
                }
            }
            let m = 7;
            let centres: Vec<f64> = (0..m * d).map(|i| (i as f64 * 0.37).cos()).collect();
            let tps = HandleBasis::tps(&rest, 0.5, &centres).unwrap();
            assert_eq!(tps.len(), 1 + 2 * n + m);
            assert_eq!(BasisKind::Tps.size(n, m), 1 + 2 * n + m);
        }
        // The table's TPS entries: octopus 1019 at m = 1000, crab 523 at m = 500.
        assert_eq!(BasisKind::Tps.size(9, 1000), 1019);
        assert_eq!(BasisKind::Tps.size(11, 500), 523);
    }

    #[test]
    fn tps_values_are_r_squared_log_r_of_scaled_distances() {
        let rest = [1.0, 2.0];
        let basis = HandleBasis::tps(&rest, 2.0, &[1.0, 2.0, 3.0, 2.0]).unwrap();
        let mut out = [0.0; 5];
        basis.evaluate_into(&[1.0, 2.0], &mut out).unwrap();
        // At the rest pose: u = 0; distance 0 to the first centre, 1 to the second.
        assert_eq!(out, [1.0, 0.0, 0.0, 0.0, 0.0]);
        basis.evaluate_into(&[5.0, 2.0], &mut out).unwrap();
        // u = (2, 0): distances 2 and 1.
        assert_eq!(&out[..3], &[1.0, 2.0, 0.0]);
        assert!((out[3] - 4.0 * 2f64.ln()).abs() < 1e-15);
        assert_eq!(out[4], 0.0);
    }

    #[test]
    fn bad_inputs_are_typed_errors() {
        let basis = HandleBasis::polynomial(BasisKind::Quadratic, &[0.0, 0.0], 1.0).unwrap();
        let mut out = vec![0.0; basis.len()];
        assert_eq!(
            basis.evaluate_into(&[0.0], &mut out),
            Err(FitError::Length { what: "targets", expected: 2, found: 1 })
        );
        assert_eq!(
            basis.evaluate_into(&[0.0, f64::NAN], &mut out),
            Err(FitError::NonFinite { what: "targets", index: 1 })
        );
        assert!(matches!(basis.evaluate_into(&[0.0, 0.0], &mut out[..2]), Err(FitError::Length { .. })));
        assert!(HandleBasis::polynomial(BasisKind::Linear, &[0.0, 0.0], 0.0).is_err());
        assert!(HandleBasis::polynomial(BasisKind::Linear, &[0.0], 1.0).is_err());
        assert_eq!(HandleBasis::polynomial(BasisKind::Linear, &[], 1.0), Err(FitError::NoHandles));
        assert!(HandleBasis::polynomial(BasisKind::Tps, &[0.0, 0.0], 1.0).is_err());
        assert!(HandleBasis::tps(&[0.0, 0.0], 1.0, &[0.0, 0.0, 1.0]).is_err());
        assert_eq!(HandleBasis::tps(&[0.0, 0.0], 1.0, &[]), Err(FitError::NoSamples));
        // 200 handles: a cubic basis of C(403, 3) = 10,827,401 functions is refused.
        assert_eq!(BasisKind::Cubic.size(200, 0), 10_827_401);
        assert!(matches!(
            HandleBasis::polynomial(BasisKind::Cubic, &[0.0; 400], 1.0),
            Err(FitError::InvalidOption { name: "handles", .. })
        ));
        assert_eq!(BasisKind::Cubic.size(usize::MAX, 0), usize::MAX);
    }
}
