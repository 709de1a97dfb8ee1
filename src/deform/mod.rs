//! Deformation: the As-Killing-As-Possible deformer and what it is built from.
//!
//! - [`killing`]: the Killing-energy matrix (paper eq. (6)), fixed pattern, values per frame;
//! - [`deformer`]: the [`Deformer`] (eqs. (3), (4) and the spiral step), handles and options;
//! - [`spiral`]: the log-spiral step (eqs. (14)-(16), corrected) and the linear step;
//! - [`metrics`]: area and angle distortion and flipped triangles (Table 1).

pub mod deformer;
pub mod killing;
pub mod metrics;
pub mod spiral;

pub use deformer::{Clock, DeformError, Deformer, DeformerOptions, Integrator, Timings};
pub use metrics::Metrics;
