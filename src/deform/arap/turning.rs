//! Turning handles in ARAP, through a rotated target frame: for one step, every vertex of a
//! turning handle's neighbourhood (its triangle's corners and their neighbours, as in
//! AKAP) is held, with the handles' stiff penalty, at its place turned by `omega` about the
//! handle's point and moved with the handle, `c + d + R(omega) (p - c)`. The penalties add
//! to diagonal entries (in the pattern), so the step refactors the matrix with them, and
//! the matrix of the plain handle set is put back after it. A rigid motion of every handle
//! is then a pose of zero energy meeting every target, which the iterations approach.

use super::ArapDeformer;
use crate::deform::error::DeformError;
use crate::deform::handles::{check_turns, check_velocities, neighbourhood};

impl ArapDeformer {
    /// One step in which handles also turn: `turns[i]` radians counter-clockwise about
    /// handle `i`'s point, its neighbourhood held in the turned frame for this step. All
    /// zero is exactly [`Self::step`]; on error the deformer is unchanged.
    pub fn step_turning(&mut self, velocities: &[[f64; 2]], turns: &[f64]) -> Result<(), DeformError> {
        check_velocities(velocities, self.handles.len())?;
        check_turns(turns, self.handles.len())?;
        if turns.iter().all(|&w| w == 0.0) {
            return self.step(velocities);
        }
        self.turning.clear();
        for ((h, d), &omega) in self.handles.iter().zip(velocities).zip(turns) {
            if omega == 0.0 {
                continue;
            }
            let c = h.point.position(&self.positions);
            let (s, k) = (libm::sin(omega), libm::cos(omega));
            for v in neighbourhood(&self.mesh, &h.point) {
                let v = v as usize;
                if self.pin_count[v] > 0 {
                    continue; // held by a handle of its own
                }
                let (x, y) = (self.positions[v][0] - c[0], self.positions[v][1] - c[1]);
                self.turning.push((v, [c[0] + d[0] + k * x - s * y, c[1] + d[1] + s * x + k * y]));
            }
        }
        let slots: Vec<usize> = self.turning.iter().map(|&(v, _)| self.slot_of(v)).collect();
        let data = self.matrix.data_mut();
        for slot in slots {
            data[slot] += self.penalty;
        }
        self.factored = false;
        let result = self.step(velocities);
        // Back to the plain handle set's matrix, factored again by the next step.
        self.turning.clear();
        self.assemble_matrix();
        self.factored = false;
        result
    }
}
