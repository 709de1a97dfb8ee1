//! The weights of ARAP's element energy: each triangle's cotangent weights times its
//! stiffness, painted ([`ArapDeformer::set_stiffness`]) and raised on bones
//! ([`ArapDeformer::set_bones`]), and the Laplacian and handle penalty built from them (by
//! `laplacian`).

use super::laplacian::laplacian_of;
use super::ArapDeformer;
use crate::deform::bones::Bones;
use crate::deform::error::DeformError;
use crate::deform::handles::check_stiffness;

impl ArapDeformer {
    /// Sets each triangle's stiffness, the factor on its element energy (its cotangent
    /// weights times it): stiff regions bend less. One value per triangle, each in
    /// [`STIFFNESS_RANGE`](crate::deform::STIFFNESS_RANGE); `None` is 1 everywhere, exactly the
    /// unpainted deformer. The Laplacian and the handles' penalty are rebuilt (the pattern
    /// and its analysis stay), and the next step factors anew. Refused, changing nothing,
    /// for a wrong length or a value out of range.
    pub fn set_stiffness(&mut self, stiffness: Option<&[f64]>) -> Result<(), DeformError> {
        check_stiffness(stiffness, self.mesh.triangle_count())?;
        self.stiffness = stiffness.map(<[f64]>::to_vec);
        self.weigh();
        Ok(())
    }

    /// Sets the bones, two mesh points per bone (see [`crate::deform::bones`]), laid in the
    /// current pose, replacing any; none removes them. Their triangles weigh at least
    /// [`BONE_STIFFNESS`](crate::deform::BONE_STIFFNESS) in the element energy, and after
    /// each global step each bone's vertices are put where the rigid motion that best fits
    /// them takes the bone as it was set. Refused, changing nothing, for a bone that cannot
    /// be used.
    pub fn set_bones(&mut self, triangles: &[u32], barycentric: &[[f64; 3]]) -> Result<(), DeformError> {
        self.bones = Bones::new(&self.mesh, &self.positions, triangles, barycentric)?;
        self.weigh();
        Ok(())
    }

    /// The cotangent weights times each triangle's stiffness (painted, raised on bones),
    /// and the Laplacian, penalty and matrix built from them (factored at the next step).
    fn weigh(&mut self) {
        self.cot = match self.bones.stiffness(self.stiffness.as_deref(), self.mesh.triangle_count()) {
            None => self.rest_cot.clone(),
            Some(values) => self.rest_cot.iter().zip(&values).map(|(c, s)| c.map(|x| x * s)).collect(),
        };
        let diagonal = |v: usize| self.slot_of(v);
        let (laplacian, penalty) =
            laplacian_of(&self.cot, &self.triangle_slots, self.laplacian.len(), self.positions.len(), diagonal);
        self.laplacian = laplacian;
        self.penalty = penalty;
        self.assemble_matrix();
        self.factored = false;
    }
}
