//! Turning handles in ARAP, through a rotated target frame: for one step, every vertex of a
//! turning handle's neighbourhood (its triangle's corners and their neighbours, as in
//! AKAP) is held, with the handles' stiff penalty, at its place turned by `omega` about the
//! handle's point and moved with the handle, `c + d + R(omega) (p - c)`. The penalties add
//! to diagonal entries (in the pattern), so the step refactors the matrix with them, and
//! the matrix of the plain handle set is put back after it. A rigid motion of every handle
//! is then a pose of zero energy meeting every target, which the iterations approach.

use super::ArapSolver;
use crate::deform::error::DeformError;
use crate::deform::handles::neighbourhood;
use crate::deform::method::{Shared, Solve, Timings};
use crate::geometry::Point;

impl ArapSolver {
    /// One step in which handles also turn: `turns[i]` radians counter-clockwise about
    /// handle `i`'s point, its neighbourhood held in the turned frame for this step (not
    /// all zero: the deformer takes a plain step then). On error the solver is unchanged.
    pub(super) fn step_turning(
        &mut self,
        shared: Shared<'_>,
        velocities: &[[f64; 2]],
        turns: &[f64],
        next: &mut [Point],
        timings: &mut Timings,
    ) -> Result<bool, DeformError> {
        self.turning.clear();
        for ((h, d), &omega) in shared.handles.iter().zip(velocities).zip(turns) {
            if omega == 0.0 {
                continue;
            }
            let c = h.position(shared.positions);
            let (s, k) = (libm::sin(omega), libm::cos(omega));
            for v in neighbourhood(shared.mesh, h) {
                let v = v as usize;
                if self.pin_count[v] > 0 {
                    continue; // held by a handle of its own
                }
                let (x, y) = (shared.positions[v][0] - c[0], shared.positions[v][1] - c[1]);
                self.turning.push((v, [c[0] + d[0] + k * x - s * y, c[1] + d[1] + s * x + k * y]));
            }
        }
        let slots: Vec<usize> = self.turning.iter().map(|&(v, _)| self.slot_of(v)).collect();
        let data = self.matrix.data_mut();
        for slot in slots {
            data[slot] += self.penalty;
        }
        self.factored = false;
        let result = self.step(shared, velocities, None, next, timings);
        // Back to the plain handle set's matrix, factored again by the next step.
        self.turning.clear();
        self.assemble_matrix(shared.handles);
        self.factored = false;
        result
    }
}
