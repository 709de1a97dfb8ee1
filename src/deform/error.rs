//! `DeformError`: why a deformer refused an input or a step. Lengths are counted in numbers
//! (two per point or velocity, three per barycentric triple), as the flat arrays of the
//! JavaScript API hold them. The checks that raise them for every deformer are in
//! `handles.rs`.

use std::fmt;

use super::options::Method;
use crate::error_code::ErrorCode;
use crate::geometry::MAX_COORDINATE;
use crate::message::{one_of, Number};
use crate::sparse::FactorError;

/// Why the deformer refused an input or a step. The deformer is unchanged after any error.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum DeformError {
    /// The mesh is split into several pieces; deform each piece on its own.
    Disconnected {
        /// The number of pieces.
        components: usize,
    },
    /// An option is out of range.
    InvalidOption {
        /// The option's name as the JavaScript API spells it.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What would be accepted.
        expected: &'static str,
    },
    /// A handle names a vertex that does not exist.
    VertexOutOfRange {
        /// Which handle.
        handle: usize,
        /// The vertex given.
        vertex: u32,
        /// The number of vertices.
        vertex_count: usize,
    },
    /// A handle names a triangle that does not exist.
    TriangleOutOfRange {
        /// Which handle.
        handle: usize,
        /// The triangle given.
        triangle: u32,
        /// The number of triangles.
        triangle_count: usize,
    },
    /// A handle's barycentric coordinates are not finite, negative, or do not sum to 1.
    InvalidBarycentric {
        /// Which handle.
        handle: usize,
        /// The coordinates given.
        coordinates: [f64; 3],
    },
    /// The number of values does not match, counted in numbers.
    Length {
        /// What was given, e.g. "velocities".
        what: &'static str,
        /// How many numbers are expected.
        expected: usize,
        /// How many numbers were given.
        found: usize,
        /// Numbers per item (2 for points and velocities, 3 for barycentric coordinates).
        per: usize,
        /// The items, plural, e.g. "handles" or "vertices".
        items: &'static str,
    },
    /// A velocity is NaN or infinite.
    NonFiniteVelocity {
        /// Which handle.
        handle: usize,
    },
    /// A handle's turn is NaN or infinite.
    NonFiniteTurn {
        /// Index of the handle.
        handle: usize,
    },
    /// A factorisation failed: the mesh has collapsed or flipped triangles.
    Factor(FactorError),
    /// The step would put a vertex at a position that is not finite or beyond
    /// ±[`MAX_COORDINATE`] (a velocity too large for the mesh).
    NonFiniteResult,
    /// A position given to `set_positions` is NaN or infinite.
    NonFinitePosition {
        /// Which vertex.
        vertex: usize,
    },
    /// A position given to `set_positions` has a coordinate beyond ±[`MAX_COORDINATE`].
    PositionOutOfRange {
        /// Which vertex.
        vertex: usize,
        /// The coordinate.
        value: f64,
    },
    /// Orders computed beforehand do not fit the mesh: too few or too many, or one is not a
    /// permutation of its system's vertices.
    OrdersMismatch {
        /// Which order (or, when their number is wrong, how many were given).
        system: usize,
        /// The number of vertices it must order (or the number of orders expected).
        expected: usize,
    },
    /// Memory ran short while preparing the solver (a factor's storage).
    OutOfMemory {
        /// Bytes that could not be allocated.
        bytes: usize,
    },
    /// A method name that is not one of [`Method::all`].
    UnknownMethod {
        /// The name given.
        name: String,
    },
    /// A setting that no method has.
    UnknownOption {
        /// The name given.
        name: String,
        /// The method the options are for.
        method: Method,
    },
    /// A setting of another method than the one the options are for.
    ForeignOption {
        /// The setting's name.
        name: String,
        /// The method the options are for.
        method: Method,
        /// The method that has this setting.
        owner: Method,
    },
    /// A setting given a value of the wrong kind (a word for a number, say) or a whole
    /// number out of its range.
    OptionValue {
        /// The setting's name.
        name: &'static str,
        /// The value given, described.
        found: String,
        /// What would be accepted.
        expected: String,
    },
    /// The handles do not determine the method's map (MLS's affine variant with fewer than
    /// three handles, or all on one line).
    TooFewHandles {
        /// The method.
        method: Method,
        /// What it needs.
        needed: &'static str,
    },
    /// A triangle's stiffness is not a number within `STIFFNESS_RANGE`.
    InvalidStiffness {
        /// Which triangle.
        triangle: usize,
        /// The value given.
        value: f64,
    },
    /// The method does not have what was asked of it (stiffness for MLS and Cauchy-Green,
    /// which have no per-triangle energy).
    Unsupported {
        /// The method.
        method: Method,
        /// What it lacks.
        what: &'static str,
    },
    /// A bone that cannot be used: its ends at one point or not in the mesh, its segment
    /// leaving the shape, or touching another bone.
    InvalidBone {
        /// Which bone.
        bone: usize,
        /// What is wrong.
        reason: &'static str,
    },
    /// A Cauchy-Green cage that cannot be used: given with too few points, points that are
    /// not finite, edges that meet or the shape not strictly inside; or no automatic cage of
    /// the vertex count asked for fits.
    InvalidCage {
        /// What is wrong.
        reason: String,
    },
    /// A checkpoint restored to a deformer that did not save it: saved by another method,
    /// for other sizes (vertices, handles, triangles), or never saved into.
    ForeignCheckpoint {
        /// The deformer's method.
        method: Method,
        /// The method that saved the checkpoint, if any.
        saved: Option<Method>,
    },
    /// Options of another method were given; the method is chosen when the deformer is made.
    WrongMethod {
        /// The deformer's method.
        current: Method,
        /// The method of the options given.
        given: Method,
    },
    /// A handle index beyond the handles there are.
    HandleOutOfRange {
        /// The index given.
        handle: usize,
        /// How many handles there are.
        handle_count: usize,
    },
    /// A handle's target is NaN or infinite.
    InvalidTarget {
        /// Which handle.
        handle: usize,
        /// The value given.
        value: f64,
    },
    /// A puppet's parts that do not hold every triangle of the mesh exactly once.
    InvalidParts {
        /// What is wrong.
        reason: String,
    },
    /// A puppet's joint that cannot be used: a part out of range, one part twice, or a point
    /// that is not finite or not on both parts.
    InvalidJoint {
        /// Which joint.
        joint: usize,
        /// What is wrong.
        reason: String,
    },
    /// A trained rig that was not trained for this mesh and these handles.
    RigMismatch {
        /// The rig's handle and vertex counts.
        rig: [usize; 2],
        /// The deformer's.
        deformer: [usize; 2],
    },
    /// A rig's pose asked for (a session's `rigPose` replayed) with no rig posing the shape.
    NoRig,
}

impl fmt::Display for DeformError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::HandleOutOfRange { handle, handle_count } => {
                write!(f, "there is no handle {handle}: there are {handle_count}")
            }
            Self::InvalidTarget { handle, value } => {
                write!(f, "the target of handle {handle} has {value}, not a finite number")
            }
            Self::RigMismatch { rig, deformer } => write!(
                f,
                "the rig was trained for {} handles on {} vertices; the deformer has {} handles on {} vertices: \
                 train it again for these handles",
                rig[0], rig[1], deformer[0], deformer[1]
            ),
            Self::NoRig => f.write_str("no trained rig poses the shape: a rig's pose needs the rig set first"),
            Self::Disconnected { components } => {
                write!(f, "the mesh has {components} separate pieces; the deformer needs one connected piece")
            }
            Self::InvalidOption { name, value, expected } => {
                write!(f, "option {name} is {}, expected {expected}", Number(*value))
            }
            Self::VertexOutOfRange { handle, vertex, vertex_count } => {
                write!(f, "handle {handle} is at vertex {vertex}, but the mesh has only {vertex_count} vertices")
            }
            Self::TriangleOutOfRange { handle, triangle, triangle_count } => {
                write!(f, "handle {handle} is in triangle {triangle}, but the mesh has only {triangle_count} triangles")
            }
            Self::InvalidBarycentric { handle, coordinates } => write!(
                f,
                "handle {handle} has barycentric coordinates {coordinates:?}; they must be finite, \
                 at least 0 and sum to 1"
            ),
            Self::Length { what, expected, found, per, items } => write!(
                f,
                "{what} has {found} numbers, expected {expected} ({per} for each of the {} {items})",
                expected / per.max(&1)
            ),
            Self::NonFiniteVelocity { handle } => write!(f, "the velocity of handle {handle} is not a finite number"),
            Self::NonFiniteTurn { handle } => write!(f, "the turn of handle {handle} is not a finite number"),
            Self::Factor(e) => write!(f, "the step failed, the mesh may have collapsed triangles: {e}"),
            Self::NonFiniteResult => write!(
                f,
                "the step would move vertices to positions that are not finite or beyond ±{MAX_COORDINATE:e}; \
                 use smaller steps"
            ),
            Self::NonFinitePosition { vertex } => write!(f, "the position of vertex {vertex} is not a finite number"),
            Self::PositionOutOfRange { vertex, value } => write!(
                f,
                "the position of vertex {vertex} has the coordinate {}, beyond the limit of ±{MAX_COORDINATE:e}",
                Number(*value)
            ),
            Self::OrdersMismatch { system, expected } => write!(
                f,
                "the orders given do not fit this mesh and method: order {system} must be a permutation of 0..{expected}"
            ),
            Self::OutOfMemory { bytes } => write!(
                f,
                "out of memory: preparing the solver needs {:.0} MB more; free deformers no longer used \
                 (free()) or use a coarser mesh",
                (*bytes as f64 / 1e6).ceil()
            ),
            Self::UnknownMethod { name } => {
                let names: Vec<&str> = Method::all().iter().map(|m| m.name()).collect();
                let name = if name.len() <= 40 { format!("{name:?}") } else { "given".into() };
                write!(f, "unknown method {name}; the methods are {}", one_of(&names))
            }
            Self::UnknownOption { name, method } => {
                let name = if name.len() <= 40 { name.as_str() } else { "given" };
                write!(f, "unknown option {name}; method {method} has {}", method.setting_names().join(", "))
            }
            Self::ForeignOption { name, method, owner } => {
                write!(f, "option {name} applies to method \"{owner}\" only, not to \"{method}\"")
            }
            Self::OptionValue { name, found, expected } => write!(f, "option {name} must be {expected}, not {found}"),
            Self::TooFewHandles { method, needed } => {
                write!(f, "method {method} needs {needed}; add handles or choose another variant")
            }
            Self::InvalidStiffness { triangle, value } => write!(
                f,
                "the stiffness of triangle {triangle} is {}, expected a number from 0.001 to 1000",
                Number(*value)
            ),
            Self::Unsupported { method, what } => {
                write!(f, "method {method} has no {what}; choose \"akap\" or \"arap\" for it")
            }
            Self::InvalidCage { reason } => write!(f, "the cage cannot be used: {reason}"),
            Self::InvalidParts { reason } => write!(f, "the puppet's parts cannot be used: {reason}"),
            Self::InvalidJoint { joint, reason } => write!(f, "joint {joint} cannot be used: {reason}"),
            Self::InvalidBone { bone, reason } => write!(f, "bone {bone} cannot be used: {reason}"),
            Self::ForeignCheckpoint { method, saved } => match saved {
                Some(saved) if saved != method => write!(
                    f,
                    "the checkpoint was saved by a deformer of method {saved}, not {method}; restore a checkpoint \
                     to the deformer that saved it"
                ),
                Some(_) => write!(
                    f,
                    "the checkpoint was saved for another mesh or handle set; restore a checkpoint to the \
                     deformer that saved it, before its handles change"
                ),
                None => write!(f, "the checkpoint holds nothing; save into it first"),
            },
            Self::WrongMethod { current, given } => write!(
                f,
                "the deformer uses method {current}, options for {given} were given; \
                 the method is chosen when the deformer is created"
            ),
        }
    }
}

impl std::error::Error for DeformError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Factor(e) => Some(e),
            _ => None,
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
            | Self::InvalidParts { .. }
            | Self::RigMismatch { .. }
            | Self::NoRig => ErrorCode::InvalidArgument,
            Self::InvalidJoint { .. } => ErrorCode::InvalidJoint,
            Self::Factor(e) => e.code(),
            Self::NonFiniteResult => ErrorCode::Overflow,
            Self::OutOfMemory { .. } => ErrorCode::OutOfMemory,
        }
    }
}

impl From<FactorError> for DeformError {
    fn from(e: FactorError) -> Self {
        Self::Factor(e)
    }
}

/// A factorisation's storage error as the deformer's (out of memory is the one expected
/// when a deformer is made).
pub(crate) fn out_of_memory(error: FactorError) -> DeformError {
    match error {
        FactorError::OutOfMemory { bytes } => DeformError::OutOfMemory { bytes },
        other => DeformError::Factor(other),
    }
}
