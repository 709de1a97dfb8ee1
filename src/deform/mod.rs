//! Deformation: the As-Killing-As-Possible deformer and what it is built from.
//!
//! [`killing`] assembles the Killing-energy matrix (paper eq. (6)) whose sparsity pattern
//! is fixed by the mesh and whose values change every frame.

pub mod killing;
