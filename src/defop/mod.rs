//! DefOp (Approximating deformation operators): closed-form operators trained on
//! ground-truth deformations. This module holds the pieces, one file each:
//!
//! - [`energy`]: the ground-truth energy densities ARAP (eq. 10) and S-ARAP (eq. 11), their
//!   signed SVD, gradients and projected Hessians;
//! - `error`: [`DefOpError`];
//! - [`ground_truth`]: the variational problem (eq. 6), minimised with hard handle
//!   constraints by Newton's method ([`GroundTruth`]);
//! - `linear`: small dense helpers of the solver;
//! - `problem`: the solver's options, handles, starts and reports.

pub mod energy;
mod error;
pub mod ground_truth;
mod linear;
mod problem;

pub use energy::{Energy, RestTriangle, SignedSvd};
pub use ground_truth::{DefOpError, GroundTruth, GroundTruthOptions, Handles, SolveReport, Start};
