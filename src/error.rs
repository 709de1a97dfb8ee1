//! The crate's top-level error, one variant per area, each with its own typed error, and
//! its `From` impls: the roof over the areas, which imports them and which none of them
//! imports. [`ErrorCode`], the stable kind of every error (JavaScript sees it as
//! `error.code`), is defined in a leaf and re-exported here; each area's error type has its
//! `code()` beside it.

use std::fmt;

use crate::animation::AnimationError;
use crate::defop::TrainError;
use crate::deform::DeformError;
use crate::import::ImportError;
use crate::mesh::MeshError;
use crate::outline::OutlineError;
use crate::session::SessionError;
use crate::sparse::FactorError;
use crate::triangulate::TriangulationError;

pub use crate::error_code::ErrorCode;

/// Any error this crate reports.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// An invalid mesh.
    Mesh(MeshError),
    /// An outline or its options could not be triangulated.
    Triangulation(TriangulationError),
    /// A session could not be read or replayed.
    Session(SessionError),
    /// An SVG, image or mesh file could not be imported.
    Import(ImportError),
    /// A deformer refused an input or a step.
    Deform(DeformError),
    /// A sparse factorisation failed (used directly, not through a deformer).
    Factor(FactorError),
    /// A deformation operator could not be trained, fitted or solved for.
    DefOp(TrainError),
    /// An animation could not be encoded, packed, written or read.
    Animation(AnimationError),
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Mesh(e) => e.fmt(f),
            Self::Triangulation(e) => e.fmt(f),
            Self::Session(e) => e.fmt(f),
            Self::Import(e) => e.fmt(f),
            Self::Deform(e) => e.fmt(f),
            Self::Factor(e) => e.fmt(f),
            Self::DefOp(e) => e.fmt(f),
            Self::Animation(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Mesh(e) => Some(e),
            Self::Triangulation(e) => Some(e),
            Self::Session(e) => Some(e),
            Self::Import(e) => Some(e),
            Self::Deform(e) => Some(e),
            Self::Factor(e) => Some(e),
            Self::DefOp(e) => Some(e),
            Self::Animation(e) => Some(e),
        }
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

impl From<AnimationError> for Error {
    fn from(e: AnimationError) -> Self {
        Self::Animation(e)
    }
}

impl From<TrainError> for Error {
    fn from(e: TrainError) -> Self {
        Self::DefOp(e)
    }
}

impl From<MeshError> for Error {
    fn from(e: MeshError) -> Self {
        Self::Mesh(e)
    }
}

impl From<TriangulationError> for Error {
    fn from(e: TriangulationError) -> Self {
        Self::Triangulation(e)
    }
}

impl From<OutlineError> for Error {
    fn from(e: OutlineError) -> Self {
        Self::Triangulation(TriangulationError::Outline(e))
    }
}

impl From<SessionError> for Error {
    fn from(e: SessionError) -> Self {
        Self::Session(e)
    }
}

impl From<ImportError> for Error {
    fn from(e: ImportError) -> Self {
        Self::Import(e)
    }
}

impl From<DeformError> for Error {
    fn from(e: DeformError) -> Self {
        Self::Deform(e)
    }
}

impl From<FactorError> for Error {
    fn from(e: FactorError) -> Self {
        Self::Factor(e)
    }
}
