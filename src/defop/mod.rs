//! Deformation operators (DefOp, "Approximating deformation operators"): closed-form
//! deformations `D(x, Q) = Σ_ij C_ij φ_i(x) ψ_j(Q)` (paper eq. 3) trained on ground-truth
//! deformations (see `../shared/papers/defop-notes.md`). One file each:
//!
//! - [`energy`]: the ground-truth energy densities ARAP (eq. 10) and S-ARAP (eq. 11), their
//!   signed SVD, gradients and projected Hessians;
//! - `error`: [`DefOpError`], the ground truth's errors;
//! - [`ground_truth`]: the variational problem (eq. 6), minimised with hard handle
//!   constraints by Newton's method ([`GroundTruth`]);
//! - `linear`: small dense helpers of the solver;
//! - `problem`: the solver's options, handles, starts and reports;
//! - [`sampling`]: the training targets Q (discs, Voronoi cells, both);
//! - [`coordinates`]: the handle coordinates Ψ is a function of (all, canonical for exact
//!   rigid motions, or with fixed handles left out);
//! - [`basis`]: the handle bases Ψ (linear, quadratic, cubic, thin-plate spline);
//! - [`spatial`]: the spatial basis Φ (hat functions or a reduced M-orthonormal basis), the
//!   mass matrices and the linearly precise Laplacian;
//! - [`reduced`]: the reduced basis of Fig. 2 (the bilaplacian's lowest eigenfunctions);
//! - [`fit`](mod@fit): the structured least-squares fit of eq. (8), with `fit_error`'s
//!   [`FitError`];
//! - [`operator`]: the trained operator and its allocation-free evaluation, on the dot
//!   product blocks of `kernels` (simd128 in wasm); [`single`]: its single-precision copy;
//!   [`gpu`](mod@gpu): its evaluation on the GPU (the basis texture once per rig, a short
//!   vector per frame);
//! - [`file`](mod@file): operator files (the operator with its mesh, versioned, checksummed);
//! - [`training`]: what an operator keeps of its training ([`Training`]);
//! - [`train`]: the bootstrapped training (samples, warm starts from the current operator,
//!   refits), resumable in time slices or spread over workers as jobs.

pub mod basis;
pub mod coordinates;
pub mod energy;
mod error;
pub mod file;
pub mod fit;
pub mod fit_error;
pub mod gpu;
pub mod ground_truth;
mod kernels;
mod linear;
pub mod operator;
mod problem;
pub mod reduced;
pub mod sampling;
pub mod single;
pub mod spatial;
pub mod train;
pub mod training;

pub use basis::{BasisKind, HandleBasis};
pub use coordinates::{HandleCoordinates, Rigid};
pub use energy::{Energy, RestTriangle, SignedSvd};
pub use file::{read_operator, write_operator, write_operator_in, OperatorFileError, Precision};
pub use fit::{fit, FitOptions, Sample};
pub use fit_error::FitError;
pub use gpu::{GpuLayout, GpuRig};
pub use ground_truth::{DefOpError, GroundTruth, GroundTruthOptions, Handles, SolveReport, Start};
pub use operator::Operator;
pub use reduced::reduced_basis;
pub use single::SinglePrecision;
pub use spatial::{MeshPoint, SpatialBasis};
pub use train::{Job, Progress, TrainError, TrainOptions, TrainStats, Trainer};
pub use training::Training;
