//! `DefOpError`: why a DefOp ground-truth solver refused a mesh, a handle set, targets or a
//! start, or could not solve. The solver is unchanged after any error.

use std::fmt;

use crate::deform::DeformError;
use crate::error_code::ErrorCode;
use crate::geometry::MAX_COORDINATE;
use crate::message::Number;
use crate::sparse::FactorError;

/// Why a DefOp ground-truth solver refused an input or could not solve.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum DefOpError {
    /// An option is out of range.
    InvalidOption {
        /// The option's name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What would be accepted.
        expected: &'static str,
    },
    /// The mesh is in several pieces.
    Disconnected {
        /// The number of pieces.
        components: usize,
    },
    /// A puppet's parts or joints that do not fit the mesh (the checks of
    /// [`crate::deform::Deformer::with_puppet`], with their message).
    InvalidPuppet(DeformError),
    /// A handle names a vertex or triangle that does not exist, or has invalid barycentric
    /// coordinates (the checks every deformer makes, with their message).
    InvalidHandle(DeformError),
    /// There is no handle: the ground truth needs at least one.
    NoHandles,
    /// More handles inside triangles (not at vertices) than the dense constraint solve takes.
    TooManyPointHandles {
        /// How many were given.
        count: usize,
        /// The most allowed.
        limit: usize,
    },
    /// Two handles are at the same rest point (within 1e-12 of the shape's size).
    CoincidentHandles {
        /// The first handle.
        first: usize,
        /// The second handle.
        second: usize,
    },
    /// A handle's constraint depends on the others (for instance a handle on an edge
    /// whose two vertices are handles, or four handles in one triangle).
    DependentHandles {
        /// The handle.
        handle: usize,
    },
    /// The number of points given does not match.
    Length {
        /// What was given: "targets" or "start".
        what: &'static str,
        /// Points expected.
        expected: usize,
        /// Points given.
        found: usize,
    },
    /// A target or a start position is NaN, infinite or beyond ±[`MAX_COORDINATE`].
    InvalidPoint {
        /// What was given: "targets" or "start".
        what: &'static str,
        /// Which point (handle or vertex).
        index: usize,
    },
    /// S-ARAP cannot put two handles on one target without collapsing the mesh.
    CoincidentTargets {
        /// The first handle.
        first: usize,
        /// The second handle.
        second: usize,
    },
    /// The handle homotopy could not move the handles further without collapsing or
    /// flipping a triangle (S-ARAP): the targets are out of reach.
    Unreachable {
        /// The fraction of the way from the start to the targets that was reached.
        reached: f64,
    },
    /// Newton's method did not reach the tolerance within the iteration limit, or its line
    /// search found no decrease.
    NoConvergence {
        /// Newton iterations run.
        iterations: usize,
        /// The last gradient norm, relative to the shape's size (`inf` if the handles were
        /// never on their targets).
        gradient: f64,
        /// The tolerance asked for.
        tolerance: f64,
    },
    /// A factorisation failed even with extra regularisation.
    Factor(FactorError),
    /// A result would be beyond ±[`MAX_COORDINATE`].
    NonFiniteResult,
}

impl fmt::Display for DefOpError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::InvalidOption { name, value, expected } => {
                write!(f, "option {name} is {}, expected {expected}", Number(*value))
            }
            Self::Disconnected { components } => {
                write!(f, "the mesh has {components} separate pieces; the ground truth needs one connected piece, or a puppet of sheets joined at joints")
            }
            Self::InvalidHandle(e) => write!(f, "invalid handle: {e}"),
            Self::InvalidPuppet(e) => write!(f, "invalid puppet: {e}"),
            Self::NoHandles => write!(f, "no handles: the ground truth needs at least one"),
            Self::TooManyPointHandles { count, limit } => write!(
                f,
                "{count} handles inside triangles, at most {limit} are supported (handles at vertices are not limited)"
            ),
            Self::CoincidentHandles { first, second } => {
                write!(f, "handles {first} and {second} are at the same rest point")
            }
            Self::DependentHandles { handle } => write!(
                f,
                "handle {handle} is determined by the other handles (its triangle's vertices are held by them)"
            ),
            Self::Length { what, expected, found } => {
                write!(f, "{what} has {found} points, expected {expected}")
            }
            Self::InvalidPoint { what, index } => {
                write!(f, "point {index} of the {what} is not a finite number within ±{MAX_COORDINATE:e}")
            }
            Self::CoincidentTargets { first, second } => write!(
                f,
                "handles {first} and {second} have the same target; S-ARAP cannot collapse the shape between them"
            ),
            Self::Unreachable { reached } => write!(
                f,
                "the targets cannot be reached without collapsing a triangle (reached {:.3} of the way)",
                reached
            ),
            Self::NoConvergence { iterations, gradient, tolerance } => write!(
                f,
                "no convergence after {iterations} Newton iterations: gradient {} of the shape's size, tolerance {}",
                Number(*gradient),
                Number(*tolerance)
            ),
            Self::Factor(e) => write!(f, "the Newton system could not be factored: {e}"),
            Self::NonFiniteResult => write!(f, "the solution would have positions beyond ±{MAX_COORDINATE:e}"),
        }
    }
}

impl std::error::Error for DefOpError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::InvalidHandle(e) | Self::InvalidPuppet(e) => Some(e),
            Self::Factor(e) => Some(e),
            _ => None,
        }
    }
}

impl DefOpError {
    /// The kind of error: [`ErrorCode::NoConvergence`] when Newton's method ran out of
    /// iterations, [`ErrorCode::InvalidMesh`] for a mesh in pieces, the handle check's or
    /// the factorisation's own, [`ErrorCode::Overflow`] for a result beyond the
    /// coordinates' range, [`ErrorCode::InvalidOption`] for options, otherwise
    /// [`ErrorCode::InvalidArgument`] (handles, targets, and targets no flip-free pose
    /// reaches).
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::InvalidOption { .. } => ErrorCode::InvalidOption,
            Self::Disconnected { .. } => ErrorCode::InvalidMesh,
            Self::InvalidHandle(e) | Self::InvalidPuppet(e) => e.code(),
            Self::NoConvergence { .. } => ErrorCode::NoConvergence,
            Self::Factor(e) => e.code(),
            Self::NonFiniteResult => ErrorCode::Overflow,
            _ => ErrorCode::InvalidArgument,
        }
    }
}

impl From<FactorError> for DefOpError {
    fn from(e: FactorError) -> Self {
        Self::Factor(e)
    }
}
