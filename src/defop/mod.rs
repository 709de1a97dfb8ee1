//! Deformation operators (DefOp): closed-form deformations `D(x, Q) = Σ_ij C_ij φ_i(x) ψ_j(Q)`
//! trained on sampled energy minimisers (paper eq. 3; see `../shared/papers/defop-notes.md`).
//!
//! [`sampling`] draws the training targets Q, [`basis`] holds the handle bases Ψ (linear,
//! quadratic, cubic, thin-plate spline), [`spatial`] the spatial basis Φ (hat functions or a
//! reduced M-orthonormal basis) with the mass matrices and the linearly precise Laplacian,
//! [`reduced`] the reduced basis of Fig. 2 (the bilaplacian's lowest eigenfunctions),
//! [`fit`](mod@fit) the structured least-squares fit of eq. (8) and [`operator`] the trained
//! operator and its allocation-free evaluation.

pub mod basis;
pub mod fit;
pub mod fit_error;
pub mod operator;
pub mod reduced;
pub mod sampling;
pub mod spatial;

pub use basis::{BasisKind, HandleBasis};
pub use fit::{fit, FitOptions, Sample};
pub use fit_error::FitError;
pub use operator::Operator;
pub use reduced::reduced_basis;
pub use spatial::{MeshPoint, SpatialBasis};
