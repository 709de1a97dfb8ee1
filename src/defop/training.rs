//! What a trained operator keeps of its training, beyond what its structure already says
//! (the handle basis, the spatial basis, canonical coordinates and fixed handles are the
//! operator's own): the ground truth's energy, where the samples were drawn, how many, from
//! which seed. [`super::Trainer::finish`] records it on the operator and the operator file
//! (version 4) keeps it, so that a rig read from a file is compared with the ground truth
//! of its own energy and shows the region its samples came from.

use super::energy::Energy;
use super::sampling::Sampling;

/// A training's settings, as its operator records them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Training {
    /// The ground truth's energy.
    pub energy: Energy,
    /// Where the targets were drawn.
    pub sampling: Sampling,
    /// Samples beyond the rest pose.
    pub samples: usize,
    /// The sampling radius (the option's value, or its default from the shape's size).
    pub radius: f64,
    /// The samples' seed.
    pub seed: u64,
}
