//! A single-precision copy of a trained operator, for positions that go to a GPU buffer:
//! the same evaluation as [`Operator::evaluate_into`] (Ψ(Q) in double, then `X Ψ`, then
//! `Dᵀ (X Ψ)`), with X, D, Ψ(Q) and the sums in `f32` (the `f32x4` kernels of `kernels`):
//! half the memory traffic and twice the lanes of the double evaluation. The copy costs 4
//! bytes per coefficient (a reduced operator of |Φ| = 100, |Ψ| = 1019 on 2058 vertices:
//! 1.6 MB beside the double operator's 3.3 MB; the hat basis: 16.8 MB beside 33.5 MB).
//!
//! Accuracy: every sum of k terms is within about k ε_32 of the sum of their magnitudes; on
//! the octopus-sized test operators of `lab/defop/defop_eval.rs` the positions are within
//! 8e-7 (reduced basis) and 1.5e-6 (hat basis) of the bounding-box diagonal of the double
//! ones (the test plan asks for 1e-5). Speed in wasm (Node 20, one thread): 0.046 ms against
//! 0.073 ms for the reduced operator, 0.41 ms against 1.77 ms for the hat one.

use super::basis::HandleBasis;
use super::coordinates::Rigid;
use super::fit_error::{check_finite, check_length, FitError};
use super::kernels;
use super::operator::{canonical_scratch, Operator};

/// An operator's coefficients in single precision, with its own scratch buffers; made by
/// [`Operator::single_precision`]. Evaluating it allocates nothing.
#[derive(Debug, Clone)]
pub struct SinglePrecision {
    basis: HandleBasis,
    vertex_count: usize,
    /// The operator's coefficients rounded: row i of X^x then row i of X^y, for every i.
    coefficients: Vec<f32>,
    /// D by vertex, rounded; empty for the hat basis.
    reduction: Vec<f32>,
    /// Scratch: Ψ(Q) in double, then rounded.
    psi: Vec<f64>,
    psi32: Vec<f32>,
    /// Scratch for a reduced basis: X^x Ψ then X^y Ψ.
    nodal: Vec<f32>,
    /// Scratch for canonical coordinates: the canonical targets Q̂ (else empty).
    canonical: Vec<f64>,
}

impl Operator {
    /// A single-precision copy of this operator (coefficients rounded to `f32`), whose
    /// evaluation is about twice as fast; 4 bytes per coefficient and per entry of D.
    pub fn single_precision(&self) -> SinglePrecision {
        let round = |x: &[f64]| x.iter().map(|&v| v as f32).collect::<Vec<f32>>();
        let reduction = round(self.reduction());
        let len = self.handle_basis().len();
        SinglePrecision {
            basis: self.handle_basis().clone(),
            vertex_count: self.vertex_count(),
            coefficients: round(self.coefficients()),
            nodal: if reduction.is_empty() { Vec::new() } else { vec![0.0; 2 * self.spatial_len()] },
            reduction,
            psi: vec![0.0; len],
            psi32: vec![0.0; len],
            canonical: canonical_scratch(self.handle_basis()),
        }
    }
}

impl SinglePrecision {
    /// The number of mesh vertices N.
    pub fn vertex_count(&self) -> usize {
        self.vertex_count
    }

    /// The bytes of the single-precision coefficients (X and D).
    pub fn coefficient_bytes(&self) -> usize {
        4 * (self.coefficients.len() + self.reduction.len())
    }

    /// Writes the vertex positions D(v, Q) (2N numbers, x and y interleaved) for the handle
    /// targets Q (2n numbers) to `out`, in single precision. Allocates nothing. Refuses wrong
    /// lengths and NaN or infinite targets.
    pub fn evaluate_into(&mut self, targets: &[f64], out: &mut [f32]) -> Result<(), FitError> {
        check_length("targets", targets, self.basis.rest().len())?;
        check_finite("targets", targets)?;
        if out.len() != 2 * self.vertex_count {
            return Err(FitError::Length { what: "output", expected: 2 * self.vertex_count, found: out.len() });
        }
        let rigid = rounded_psi(&self.basis, targets, &mut self.canonical, &mut self.psi, &mut self.psi32);
        let write = |v: usize, x: f32, y: f32| {
            let [x, y] = match &rigid {
                Some(rigid) => rigid.apply([f64::from(x), f64::from(y)]).map(|c| c as f32),
                None => [x, y],
            };
            out[2 * v] = x;
            out[2 * v + 1] = y;
        };
        kernels::positions(&self.coefficients, &self.psi32, &self.reduction, &mut self.nodal, write);
        Ok(())
    }
}

/// Ψ(Q) in double, rounded into `psi32` (`psi`: its double scratch), at the targets or, for
/// canonical coordinates, at the canonical targets (into `canonical`), as the double
/// evaluation poses them; returns the targets' rigid motion that moves each position back
/// (`None` without canonical coordinates). The first step of every single-precision
/// evaluation, on the CPU ([`SinglePrecision`]) or the GPU (`super::gpu`). The targets are
/// the caller's to check.
pub(super) fn rounded_psi(
    basis: &HandleBasis,
    targets: &[f64],
    canonical: &mut [f64],
    psi: &mut [f64],
    psi32: &mut [f32],
) -> Option<Rigid> {
    let rigid = basis.coordinates().canonicalise(targets, canonical);
    let at = if rigid.is_some() { &*canonical } else { targets };
    basis.evaluate_unchecked(at, psi);
    for (single, &double) in psi32.iter_mut().zip(psi.iter()) {
        *single = double as f32;
    }
    rigid
}
