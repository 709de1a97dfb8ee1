//! The weights of ARAP's element energy: each triangle's cotangent weights times its
//! stiffness, painted and raised on bones ([`crate::deform::Deformer::set_stiffness`],
//! [`crate::deform::Deformer::set_bones`]), and the Laplacian and handle penalty built from
//! them.

use super::{ArapSolver, PENALTY};
use crate::deform::handles::HandlePoint;

/// The cotangent Laplacian of the per-triangle weights `cot` on the pattern (`nnz`
/// entries, `triangle_slots` per triangle, `diagonal(v)` the slot of `(v, v)` for the `n`
/// vertices), and the handles' penalty weight for it: [`PENALTY`] times its mean diagonal
/// entry.
pub(super) fn laplacian_of(
    cot: &[[f64; 3]],
    triangle_slots: &[[usize; 9]],
    nnz: usize,
    n: usize,
    diagonal: impl Fn(usize) -> usize,
) -> (Vec<f64>, f64) {
    let mut laplacian = vec![0.0; nnz];
    for (c, s) in cot.iter().zip(triangle_slots) {
        for (k, &weight) in c.iter().enumerate() {
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            laplacian[s[3 * i + i]] += weight;
            laplacian[s[3 * j + j]] += weight;
            laplacian[s[3 * i + j]] -= weight;
            laplacian[s[3 * j + i]] -= weight;
        }
    }
    let diagonal_sum: f64 = (0..n).map(|v| laplacian[diagonal(v)]).sum();
    (laplacian, PENALTY * diagonal_sum / n as f64)
}

impl ArapSolver {
    /// The cotangent weights times each triangle's weight (the painted stiffness raised on
    /// bones, `None` for 1 everywhere, exactly the unpainted solver), and the Laplacian,
    /// penalty and matrix built from them: the pattern and its analysis stay, and the next
    /// step factors anew.
    pub(super) fn weigh(&mut self, handles: &[HandlePoint], weights: Option<&[f64]>) {
        self.cot = match weights {
            None => self.rest_cot.clone(),
            Some(values) => self.rest_cot.iter().zip(values).map(|(c, s)| c.map(|x| x * s)).collect(),
        };
        let diagonal = |v: usize| self.slot_of(v);
        let (laplacian, penalty) =
            laplacian_of(&self.cot, &self.triangle_slots, self.laplacian.len(), self.pin_count.len(), diagonal);
        self.laplacian = laplacian;
        self.penalty = penalty;
        self.assemble_matrix(handles);
        self.factored = false;
    }
}
