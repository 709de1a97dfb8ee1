//! Deformation: the As-Killing-As-Possible deformer, the ARAP deformer it is compared with,
//! and what they are built from.
//!
//! - [`killing`]: the Killing-energy matrix (paper eq. (6)), fixed pattern, values per frame;
//! - [`deformer`]: the [`Deformer`] (eqs. (3), (4) and the spiral step), handles and options;
//! - [`spiral`]: the log-spiral step (eqs. (14)-(16), corrected) and the linear step;
//! - [`arap`]: the [`ArapDeformer`] (Liu et al. 2008 elements energy, local/global);
//! - [`method`]: the [`Deform`] trait both implement and [`MethodOptions`] to pick one;
//! - [`metrics`]: area and angle distortion and flipped triangles (Table 1).

pub mod arap;
pub mod deformer;
mod error;
mod handles;
pub mod killing;
pub mod method;
pub mod metrics;
pub mod spiral;

pub use arap::{ArapDeformer, ArapOptions, IterationReport};
pub use deformer::{Clock, Deformer, DeformerOptions, Integrator, Timings, LAMBDA_RANGE};
pub use error::DeformError;
pub use method::{Deform, Method, MethodOptions, Orders};
pub use metrics::Metrics;
