//! The constrained Newton step of [`GroundTruth`] (module documentation of
//! `ground_truth`): the factorisation of the assembled Hessian (more regularisation if a
//! pivot fails), the range-space solve for handles inside triangles, and the constrained
//! gradient that decides convergence.

use super::{GroundTruth, REGULARISATION};
use crate::defop::error::DefOpError;
use crate::defop::linear::{cholesky, cholesky_solve};

impl GroundTruth {
    /// Factors the assembled matrix, with more regularisation if a pivot fails.
    pub(super) fn factor(&mut self) -> Result<(), DefOpError> {
        let mut extra = REGULARISATION;
        for attempt in 0..4 {
            match self.numeric.refactor_values(&self.values) {
                Ok(()) => return Ok(()),
                Err(e) if attempt == 3 => return Err(e.into()),
                Err(_) => {
                    for (d, &slot) in self.diagonal_slots.iter().enumerate() {
                        self.values[slot] += 999.0 * extra * self.stiffness[d];
                    }
                    extra *= 1000.0;
                }
            }
        }
        unreachable!("the last attempt returns")
    }

    /// The constrained Newton step into `step` (range-space method for handles inside
    /// triangles).
    pub(super) fn newton_step(&mut self) -> Result<(), DefOpError> {
        self.step.copy_from_slice(&self.rhs);
        self.numeric.solve_in_place(&mut self.step)?;
        let m = 2 * self.points.len();
        if m == 0 {
            return Ok(());
        }
        let len = self.step.len();
        for r in 0..m {
            let column = &mut self.columns[r * len..(r + 1) * len];
            column.fill(0.0);
            let h = &self.handles[self.points[r / 2]];
            for (v, w) in h.vertices.iter().zip(h.weights) {
                if !self.fixed[*v as usize] {
                    column[2 * *v as usize + r % 2] += w;
                }
            }
            self.numeric.solve_in_place(column)?;
        }
        for r in 0..m {
            let h = &self.handles[self.points[r / 2]];
            let dof = |v: u32| 2 * v as usize + r % 2;
            for c in 0..m {
                let column = &self.columns[c * len..(c + 1) * len];
                self.schur[r * m + c] = h
                    .vertices
                    .iter()
                    .zip(h.weights)
                    .filter(|(v, _)| !self.fixed[**v as usize])
                    .map(|(v, w)| w * column[dof(*v)])
                    .sum();
            }
            let c_step: f64 = h.vertices.iter().zip(h.weights).map(|(v, w)| w * self.step[dof(*v)]).sum();
            self.small[r] = c_step - self.residual[r];
        }
        cholesky(&mut self.schur, m).map_err(|r| DefOpError::DependentHandles { handle: self.points[r / 2] })?;
        cholesky_solve(&self.schur, m, &mut self.small);
        for r in 0..m {
            let (lambda, column) = (self.small[r], &self.columns[r * len..(r + 1) * len]);
            for (s, y) in self.step.iter_mut().zip(column) {
                *s -= lambda * y;
            }
        }
        Ok(())
    }

    /// The infinity norm of `g + C^T μ` on the free unknowns, `μ` the least-squares
    /// multipliers (`B B^T μ = -B g` per coordinate).
    pub(super) fn constrained_gradient(&mut self) -> f64 {
        self.work.copy_from_slice(&self.grad);
        let np = self.points.len();
        for c in 0..2 {
            for (j, &k) in self.points.iter().enumerate() {
                let h = &self.handles[k];
                self.small[j] = -h
                    .vertices
                    .iter()
                    .zip(h.weights)
                    .filter(|(v, _)| !self.fixed[**v as usize])
                    .map(|(v, w)| w * self.grad[2 * *v as usize + c])
                    .sum::<f64>();
            }
            cholesky_solve(&self.gram, np, &mut self.small[..np]);
            for (j, &k) in self.points.iter().enumerate() {
                let h = &self.handles[k];
                for (v, w) in h.vertices.iter().zip(h.weights) {
                    self.work[2 * *v as usize + c] += w * self.small[j];
                }
            }
        }
        self.work.iter().enumerate().filter(|(d, _)| !self.fixed[d / 2]).fold(0.0, |m, (_, g)| m.max(g.abs()))
    }
}
