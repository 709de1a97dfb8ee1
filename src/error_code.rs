//! [`ErrorCode`]: the stable kind of every error the crate reports, a closed set. A leaf:
//! it imports nothing of the crate. Each area's error type maps its variants to it with a
//! `code()` written beside the type; [`crate::Error::code`] passes on that of the area's
//! error it holds.

use std::fmt;

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
    /// A puppet's joint that cannot be used: a part index out of range, a part joined to
    /// itself, or a point that is not on both parts.
    InvalidJoint,
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
    /// Every code, in the order of the table in docs/errors.md.
    pub const ALL: [ErrorCode; 12] = [
        Self::InvalidArgument,
        Self::InvalidOption,
        Self::InvalidOutline,
        Self::InvalidMesh,
        Self::InvalidJoint,
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
            Self::InvalidJoint => "invalid-joint",
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
