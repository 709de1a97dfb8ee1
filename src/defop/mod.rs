//! Deformation operators (DefOp): closed-form deformations trained on sampled variational
//! deformations (`../shared/papers/defop-notes.md`).

pub mod sampling;
