//! The inputs and outputs of the DefOp ground-truth solver ([`super::GroundTruth`]): its
//! options, the handle set, the start of a solve and its report.

use super::error::DefOpError;
use crate::geometry::Point;

/// The most handles inside triangles (the dense constraint solve is `2n x 2n`, and each
/// takes two sparse solves per iteration).
pub const MAX_POINT_HANDLES: usize = 128;

/// The solver's settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroundTruthOptions {
    /// Convergence when the constrained gradient's infinity norm is at most this fraction
    /// of the rest shape's bounding-box diagonal; in `(0, 1]`, default 1e-9.
    pub tolerance: f64,
    /// Newton iterations allowed per solve, all homotopy stages together; from 1 to
    /// 1,000,000, default 1000.
    pub max_iterations: usize,
}

impl Default for GroundTruthOptions {
    fn default() -> Self {
        Self { tolerance: 1e-9, max_iterations: 1000 }
    }
}

impl GroundTruthOptions {
    /// Sets the tolerance.
    pub fn with_tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = tolerance;
        self
    }

    /// Sets the iteration limit.
    pub fn with_max_iterations(mut self, max_iterations: usize) -> Self {
        self.max_iterations = max_iterations;
        self
    }

    pub(super) fn check(&self) -> Result<(), DefOpError> {
        if !(self.tolerance > 0.0 && self.tolerance <= 1.0) {
            return Err(DefOpError::InvalidOption {
                name: "tolerance",
                value: self.tolerance,
                expected: "a number above 0, at most 1 (a fraction of the shape's size)",
            });
        }
        if !(1..=1_000_000).contains(&self.max_iterations) {
            return Err(DefOpError::InvalidOption {
                name: "max_iterations",
                value: self.max_iterations as f64,
                expected: "a whole number from 1 to 1000000",
            });
        }
        Ok(())
    }
}

/// Where the handles are on the rest mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Handles<'a> {
    /// One handle on each of these vertices.
    Vertices(&'a [u32]),
    /// Handles at points inside triangles: a triangle index and barycentric coordinates
    /// each (checked as the deformers check them; a weight of 1 at a corner is a vertex
    /// handle).
    Points {
        /// The triangle of each handle.
        triangles: &'a [u32],
        /// The barycentric coordinates of each handle in its triangle.
        barycentric: &'a [[f64; 3]],
    },
}

/// Where a solve starts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Start<'a> {
    /// The rest pose.
    Rest,
    /// A given pose (a warm start), one position per vertex.
    Pose(&'a [Point]),
}

/// A solution and how it was found.
#[derive(Debug, Clone, PartialEq)]
pub struct SolveReport {
    /// The vertex positions.
    pub positions: Vec<Point>,
    /// The energy `E = sum_t A_t ψ(J_t)`.
    pub energy: f64,
    /// Newton iterations, all stages together.
    pub iterations: usize,
    /// Whether the warm start had a flipped or collapsed triangle (S-ARAP) and the solve
    /// restarted from the rest pose.
    pub fallback: bool,
    /// Homotopy stages solved (1 when the targets were reached in one stage).
    pub stages: usize,
    /// The final constrained gradient norm, relative to the shape's size.
    pub gradient: f64,
}
