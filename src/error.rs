//! The crate's top-level error: one variant per area, each with its own typed error.

use std::fmt;

use crate::import::ImportError;
use crate::mesh::MeshError;
use crate::outline::OutlineError;
use crate::session::SessionError;
use crate::triangulate::TriangulationError;

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
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Mesh(e) => e.fmt(f),
            Self::Triangulation(e) => e.fmt(f),
            Self::Session(e) => e.fmt(f),
            Self::Import(e) => e.fmt(f),
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
        }
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
