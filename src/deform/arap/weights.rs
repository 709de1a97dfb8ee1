//! The weights of ARAP's element energy: each triangle's cotangent weights times its
//! stiffness, painted and raised on bones ([`crate::deform::Deformer::set_stiffness`],
//! [`crate::deform::Deformer::set_bones`]), and the Laplacian and handle penalty built from
//! them (by `laplacian`).

use super::laplacian::laplacian_of;
use super::ArapSolver;
use crate::deform::handles::HandlePoint;

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
