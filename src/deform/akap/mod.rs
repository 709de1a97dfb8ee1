//! As-Killing-As-Possible vector fields for planar deformation (Solomon, Ben-Chen,
//! Butscher and Guibas, SGP 2011), in four files:
//!
//! - [`killing`]: the Killing energy `E_K(U) = U^T K U` of a piecewise-linear field, eq. (6),
//!   as a matrix with a fixed pattern and values per frame;
//! - [`solver`]: the [`AkapSolver`] behind a [`crate::deform::Deformer`] of this method:
//!   step 1 (soft constraints, eq. (3)), step 2 (Dirichlet re-solve, eq. (4)), and the move;
//!   its options are [`super::AkapOptions`];
//! - [`spiral`]: the move along logarithmic spirals, eqs. (14)-(16) with eq. (15)'s sign
//!   corrected (derived in its documentation), and the linear move;
//! - `turning`: turning handles, whose neighbourhoods are asked to follow a rigid motion.

pub mod killing;
pub mod solver;
pub mod spiral;
mod turning;

pub use solver::AkapSolver;
