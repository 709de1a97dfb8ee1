//! Deformation: the As-Killing-As-Possible method, the methods it is compared with (ARAP,
//! moving least squares, Cauchy-Green), and the one [`Deformer`] that holds what they share
//! (mesh, handles, pose, stiffness, bones, clock, timings) with one method's solver behind
//! it. Each file stands on the ones before it and none imports a later one:
//!
//! - [`options`]: the list of methods, [`Method`], [`MethodOptions`] and each method's
//!   options (plain data);
//! - `error`: [`DeformError`];
//! - [`settings`]: every method's settings by name ([`MethodOptions::over`]), read and
//!   written alike by the bindings, sessions and the command line;
//! - [`metrics`]: area and angle distortion and flipped triangles (Table 1);
//! - `pattern`: the sparsity pattern of AKAP's and ARAP's matrices, a block per vertex pair;
//! - `handles`: the checks and helpers every method shares (handle points, velocities,
//!   poses, connectivity, sizes);
//! - [`puppet`]: a mesh's parts (sheets) and the joints between them, checked and placed;
//! - [`bones`]: segments whose triangles move as one rigid body ([`BONE_STIFFNESS`]),
//!   for the methods that have them (AKAP, ARAP);
//! - [`method`]: the `Solve` trait each method's solver implements, the `Build` trait its
//!   options make it with, [`Orders`], [`Timings`], [`Clock`] and the [`Checkpoint`] a step
//!   is undone with;
//! - [`akap`]: the paper's [`AkapSolver`] (eqs. (3), (4), (6), (14)-(16)) in four files:
//!   the Killing matrix, the spiral step, turning handles, the solver;
//! - [`arap`]: the [`ArapSolver`] (Liu et al. 2008 elements energy, local/global);
//! - [`mls`]: the [`MlsSolver`] (Schaefer et al. 2006, rigid, similarity or affine
//!   moving least squares, in closed form);
//! - [`cauchy`]: the [`CauchyGreenSolver`] (Weber et al. 2009, point-to-point
//!   Cauchy-Green coordinates on a cage) in three files: the coordinates, the cage, the
//!   fit;
//! - `deformer`: the [`Deformer`], the one type every caller uses, with any method's
//!   solver behind it;
//! - [`foldover`]: the guarded step that never flips a triangle ([`FoldoverStepper`],
//!   [`step_without_foldovers`]): a step that would is split, then clamped.
//!
//! A new method is one more file beside `akap`, `arap`, `mls` and `cauchy` (declared here), its options
//! struct in [`options`] and one more line in the list of methods there (see
//! `ARCHITECTURE.md`, "How to add a method").

pub mod akap;
pub mod arap;
pub mod bones;
pub mod cauchy;
mod deformer;
mod error;
pub mod foldover;
pub(crate) mod handles;
pub mod method;
pub mod metrics;
pub mod mls;
pub mod options;
pub(crate) mod pattern;
pub mod puppet;
pub mod settings;

pub use akap::AkapSolver;
pub use arap::ArapSolver;
pub use bones::BONE_STIFFNESS;
pub use cauchy::CauchyGreenSolver;
pub use deformer::Deformer;
pub use error::DeformError;
pub use foldover::{step_without_foldovers, FoldoverGuard, FoldoverStepper, GuardedStep, Undoable};
pub use method::{Checkpoint, Clock, IterationReport, Orders, Timings};
pub use metrics::Metrics;
pub use mls::MlsSolver;
#[allow(deprecated)]
pub use options::DeformerOptions;
pub use options::{
    Access, AkapOptions, ArapOptions, CauchyGreenOptions, Integrator, Method, MethodOptions, MlsOptions, MlsVariant,
    Setting, Settings, CAGE_VERTICES_RANGE, LAMBDA_RANGE, MLS_ALPHA_RANGE, SMOOTHNESS_RANGE, STIFFNESS_RANGE,
};
pub use puppet::{Joint, Part, Puppet};
pub use settings::SettingValue;
