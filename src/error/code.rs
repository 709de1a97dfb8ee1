//! [`ErrorCode`]: the stable kind of every error the crate reports, and the one mapping
//! from each area's error variants to it (`code()` on each error type, all defined here so
//! that the set and its uses are read in one place).

use std::fmt;

use super::Error;
use crate::animation::AnimationError;
use crate::defop::{DefOpError, FitError, TrainError};
use crate::deform::DeformError;
use crate::import::ImportError;
use crate::mesh::MeshError;
use crate::outline::OutlineError;
use crate::session::SessionError;
use crate::sparse::eigen::EigenError;
use crate::sparse::FactorError;
use crate::triangulate::TriangulationError;

/// What kind of error it is: a small, closed set that stays the same from version to
/// version (messages may be reworded), for callers to switch on. JavaScript sees it as the
/// `code` property of the `Error`s the bindings throw, spelt as [`ErrorCode::as_str`] gives.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ErrorCode {
    /// An argument of the wrong type or length, an index out of range, a number that is not
    /// finite, orders that do not fit the mesh, a pixel buffer that does not fit its size.
    InvalidArgument,
    /// An options object: an unknown key, a value of the wrong type or out of range, or an
    /// option of the other method.
    InvalidOption,
    /// An outline that cannot be triangulated: too few points, crossing or touching
    /// segments, zero area, holes outside or nested, coordinates beyond ±1e300.
    InvalidOutline,
    /// Positions and triangles that are not a valid mesh (given as arrays or read from a
    /// file), or a mesh the deformer cannot take (in several pieces).
    InvalidMesh,
    /// Input beyond a size limit: bytes, pixels, points, vertices, XML nesting, attributes
    /// or crossing-check work, SVG coordinates; or a mesh needing more vertices than allowed.
    Limit,
    /// A file that cannot be read: malformed XML, OBJ, JSON or session, an SVG with no
    /// filled shape or a bad attribute, an image with no shape in it.
    Import,
    /// A step's linear system could not be factored: the pose has collapsed or flipped
    /// triangles. Smaller steps, or undoing the last, usually help.
    NotPositiveDefinite,
    /// A result would not be finite or would lie beyond ±1e300: a velocity too large for
    /// the mesh, a point mapped far outside, a texture coordinate of a huge position.
    Overflow,
    /// An iterative solve did not converge within its iterations (a DefOp ground truth, the
    /// eigenproblem of a reduced basis).
    NoConvergence,
    /// Memory ran short (a solver's factor).
    OutOfMemory,
    /// A bug in akap (please report it).
    Internal,
}

impl ErrorCode {
    /// Every code, in the order of the README's table.
    pub const ALL: [ErrorCode; 11] = [
        Self::InvalidArgument,
        Self::InvalidOption,
        Self::InvalidOutline,
        Self::InvalidMesh,
        Self::Limit,
        Self::Import,
        Self::NotPositiveDefinite,
        Self::Overflow,
        Self::NoConvergence,
        Self::OutOfMemory,
        Self::Internal,
    ];

    /// The code as JavaScript sees it, e.g. `"invalid-mesh"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::InvalidArgument => "invalid-argument",
            Self::InvalidOption => "invalid-option",
            Self::InvalidOutline => "invalid-outline",
            Self::InvalidMesh => "invalid-mesh",
            Self::Limit => "limit",
            Self::Import => "import",
            Self::NotPositiveDefinite => "not-positive-definite",
            Self::Overflow => "overflow",
            Self::NoConvergence => "no-convergence",
            Self::OutOfMemory => "out-of-memory",
            Self::Internal => "internal",
        }
    }
}

impl fmt::Display for ErrorCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl Error {
    /// The kind of error (that of the area's error it holds).
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::Mesh(e) => e.code(),
            Self::Triangulation(e) => e.code(),
            Self::Session(e) => e.code(),
            Self::Import(e) => e.code(),
            Self::Deform(e) => e.code(),
            Self::Factor(e) => e.code(),
            Self::DefOp(e) => e.code(),
            Self::Animation(e) => e.code(),
        }
    }
}

impl AnimationError {
    /// The kind of error: [`ErrorCode::Limit`] beyond a size limit, [`ErrorCode::Import`]
    /// for an animation file that cannot be read, the mesh file's own for its mesh,
    /// [`ErrorCode::Internal`] should an image encoder fail, otherwise
    /// [`ErrorCode::InvalidArgument`] (sizes, pixel buffers, delays, file names, an
    /// animation to write that is not valid, an encoder without frames or finished).
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::TooLarge { .. } => ErrorCode::Limit,
            Self::Syntax { .. } | Self::File { .. } => ErrorCode::Import,
            Self::Mesh(e) => e.code(),
            Self::Encoder { .. } => ErrorCode::Internal,
            Self::Size { .. }
            | Self::FrameLength { .. }
            | Self::Delay { .. }
            | Self::NoFrames
            | Self::Finished
            | Self::FileName { .. }
            | Self::Invalid { .. } => ErrorCode::InvalidArgument,
        }
    }
}

impl TrainError {
    /// The kind of error: that of the ground truth's or the fit's error it holds,
    /// [`ErrorCode::InvalidOption`] for options, [`ErrorCode::Import`] for an operator file
    /// that cannot be read, otherwise [`ErrorCode::InvalidArgument`].
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::InvalidOption { .. } => ErrorCode::InvalidOption,
            Self::TooLarge { .. } => ErrorCode::Limit,
            Self::File(_) => ErrorCode::Import,
            Self::GroundTruth(e) => e.code(),
            Self::Fit(e) => e.code(),
            _ => ErrorCode::InvalidArgument,
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
            Self::InvalidHandle(e) => e.code(),
            Self::NoConvergence { .. } => ErrorCode::NoConvergence,
            Self::Factor(e) => e.code(),
            Self::NonFiniteResult => ErrorCode::Overflow,
            _ => ErrorCode::InvalidArgument,
        }
    }
}

impl FitError {
    /// The kind of error: [`ErrorCode::InvalidOption`] for options (fixed handles and the
    /// canonical option included) and too few samples for the basis, the factorisation's
    /// own, [`ErrorCode::NoConvergence`] for a reduced basis's eigenproblem that did not
    /// converge, otherwise [`ErrorCode::InvalidArgument`].
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::InvalidOption { .. }
            | Self::TooFewSamples { .. }
            | Self::CanonicalWithFixed
            | Self::InvalidFixedHandle { .. } => ErrorCode::InvalidOption,
            Self::Factor(e) => e.code(),
            Self::InvalidHandle(e) => e.code(),
            Self::Eigen(EigenError::NotConverged { .. }) => ErrorCode::NoConvergence,
            Self::Eigen(EigenError::Factor(e)) => e.code(),
            _ => ErrorCode::InvalidArgument,
        }
    }
}

impl MeshError {
    /// The kind of error: [`ErrorCode::Limit`] for too many elements, otherwise
    /// [`ErrorCode::InvalidMesh`].
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::TooLarge { .. } => ErrorCode::Limit,
            _ => ErrorCode::InvalidMesh,
        }
    }
}

impl OutlineError {
    /// The kind of error: [`ErrorCode::Limit`] for too many points, otherwise
    /// [`ErrorCode::InvalidOutline`].
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::TooManyPoints { .. } => ErrorCode::Limit,
            _ => ErrorCode::InvalidOutline,
        }
    }
}

impl TriangulationError {
    /// The kind of error.
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::Outline(e) => e.code(),
            Self::InvalidOption { .. } => ErrorCode::InvalidOption,
            Self::ConstraintConflict { .. } => ErrorCode::InvalidOutline,
            Self::TooManyVertices { .. } => ErrorCode::Limit,
            Self::Mesh(_) | Self::Internal { .. } => ErrorCode::Internal,
        }
    }
}

impl ImportError {
    /// The kind of error: the mesh's own for an invalid mesh in a file, otherwise by what
    /// went wrong ([`ErrorCode::Import`] for what is wrong with the file itself).
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::Mesh(e) => e.code(),
            Self::TooLarge { .. }
            | Self::TooDeep { .. }
            | Self::CoordinateTooLarge { .. }
            | Self::TooManyAttributes { .. }
            | Self::TooComplex { .. }
            | Self::TooManyPoints { .. }
            | Self::TooManyContourPoints { .. } => ErrorCode::Limit,
            Self::Xml { .. }
            | Self::Svg { .. }
            | Self::NotSvg { .. }
            | Self::NoShapes { .. }
            | Self::EmptyImage
            | Self::Syntax { .. }
            | Self::TextureCoordinates { .. }
            | Self::Stiffness { .. } => ErrorCode::Import,
            Self::ImageSize { .. } | Self::Length { .. } | Self::NonFinite { .. } => ErrorCode::InvalidArgument,
            Self::NonFiniteResult { .. } => ErrorCode::Overflow,
            Self::InvalidOption { .. } => ErrorCode::InvalidOption,
        }
    }
}

impl DeformError {
    /// The kind of error: a failed factorisation's own, otherwise by what went wrong.
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::Disconnected { .. } => ErrorCode::InvalidMesh,
            Self::InvalidOption { .. }
            | Self::WrongMethod { .. }
            | Self::UnknownMethod { .. }
            | Self::UnknownOption { .. }
            | Self::ForeignOption { .. }
            | Self::OptionValue { .. } => ErrorCode::InvalidOption,
            Self::VertexOutOfRange { .. }
            | Self::TriangleOutOfRange { .. }
            | Self::InvalidBarycentric { .. }
            | Self::Length { .. }
            | Self::NonFiniteVelocity { .. }
            | Self::NonFiniteTurn { .. }
            | Self::NonFinitePosition { .. }
            | Self::PositionOutOfRange { .. }
            | Self::OrdersMismatch { .. }
            | Self::TooFewHandles { .. }
            | Self::InvalidCage { .. }
            | Self::InvalidBone { .. }
            | Self::InvalidStiffness { .. }
            | Self::Unsupported { .. }
            | Self::ForeignCheckpoint { .. }
            | Self::HandleOutOfRange { .. }
            | Self::InvalidTarget { .. }
            | Self::RigMismatch { .. } => ErrorCode::InvalidArgument,
            Self::Factor(e) => e.code(),
            Self::NonFiniteResult => ErrorCode::Overflow,
            Self::OutOfMemory { .. } => ErrorCode::OutOfMemory,
        }
    }
}

impl FactorError {
    /// The kind of error: [`ErrorCode::NotPositiveDefinite`] for a failed pivot,
    /// [`ErrorCode::OutOfMemory`], and otherwise [`ErrorCode::InvalidArgument`] (a matrix,
    /// ordering or right-hand side that does not fit, or a solve without a factor: only
    /// direct callers of [`crate::sparse`] can cause these).
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::NotPositiveDefinite { .. } => ErrorCode::NotPositiveDefinite,
            Self::OutOfMemory { .. } => ErrorCode::OutOfMemory,
            _ => ErrorCode::InvalidArgument,
        }
    }
}

impl SessionError {
    /// The kind of error: the wrapped error's for a shape that does not triangulate,
    /// invalid options and refused events; [`ErrorCode::Import`] for a session file that
    /// cannot be read or does not match its shape.
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::Triangulation(e) => e.code(),
            Self::Mesh(e) => e.code(),
            Self::Options(e) | Self::Setup(e) | Self::Event { error: e, .. } => e.code(),
            Self::MissingTargets { .. } => ErrorCode::InvalidArgument,
            Self::Json(_)
            | Self::Format { .. }
            | Self::Version { .. }
            | Self::NotInVersion1 { .. }
            | Self::MeshSource
            | Self::UnknownShape { .. }
            | Self::MeshMismatch { .. } => ErrorCode::Import,
        }
    }
}
