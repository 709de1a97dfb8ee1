//! Deformation: the As-Killing-As-Possible deformer, the methods it is compared with (ARAP,
//! moving least squares, Cauchy-Green) and what every method shares. Each file stands on
//! the ones before it and none imports a later one:
//!
//! - [`options`]: the list of methods, [`Method`], [`MethodOptions`] and each method's
//!   options (plain data);
//! - `error`: [`DeformError`];
//! - [`settings`]: every method's settings by name ([`MethodOptions::over`]), read and
//!   written alike by the bindings, sessions and the command line;
//! - [`metrics`]: area and angle distortion and flipped triangles (Table 1);
//! - [`method`]: the [`Deform`] trait every deformer implements, [`MethodOptions::build`],
//!   [`Orders`], [`Timings`], [`Clock`] and the [`Checkpoint`] a step is undone with;
//! - [`foldover`]: the guarded step that never flips a triangle ([`FoldoverStepper`],
//!   [`step_without_foldovers`]): a step that would is split, then clamped;
//! - `pattern`: the sparsity pattern of both deformers' matrices, a block per vertex pair;
//! - `handles`: the checks and helpers every deformer shares (handle points, velocities,
//!   poses, connectivity, sizes);
//! - [`bones`]: segments whose triangles move as one rigid body ([`BONE_STIFFNESS`]),
//!   for the methods that have them (AKAP, ARAP);
//! - [`akap`]: the [`Deformer`] of the paper (eqs. (3), (4), (6), (14)-(16)) in three files:
//!   the Killing matrix, the spiral step, the solver;
//! - [`arap`]: the [`ArapDeformer`] (Liu et al. 2008 elements energy, local/global);
//! - [`mls`]: the [`MlsDeformer`] (Schaefer et al. 2006, rigid, similarity or affine
//!   moving least squares, in closed form);
//! - [`cauchy`]: the [`CauchyGreenDeformer`] (Weber et al. 2009, point-to-point
//!   Cauchy-Green coordinates on a cage) in three files: the coordinates, the cage, the
//!   fit.
//!
//! A new method is one more file beside `akap`, `arap`, `mls` and `cauchy` (declared here), its options
//! struct in [`options`] and one more line in the list of methods there (see
//! `ARCHITECTURE.md`, "How to add a method").

pub mod akap;
pub mod arap;
pub mod bones;
pub mod cauchy;
mod error;
pub mod foldover;
pub(crate) mod handles;
pub mod method;
pub mod metrics;
pub mod mls;
pub mod options;
pub(crate) mod pattern;
pub mod settings;

pub use akap::Deformer;
pub use arap::ArapDeformer;
pub use bones::BONE_STIFFNESS;
pub use cauchy::CauchyGreenDeformer;
pub use error::DeformError;
pub use foldover::{step_without_foldovers, FoldoverGuard, FoldoverStepper, GuardedStep};
pub use method::{Checkpoint, Clock, Deform, IterationReport, Orders, Timings};
pub use metrics::Metrics;
pub use mls::MlsDeformer;
pub use options::{
    Access, ArapOptions, CauchyGreenOptions, DeformerOptions, Integrator, Method, MethodOptions, MlsOptions,
    MlsVariant, Setting, Settings, CAGE_VERTICES_RANGE, LAMBDA_RANGE, MLS_ALPHA_RANGE, SMOOTHNESS_RANGE,
    STIFFNESS_RANGE,
};
pub use settings::SettingValue;
