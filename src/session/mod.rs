//! Recorded interaction sessions: the one definition of the JSON format the app records
//! (the deformer, a `pose::Poser`, records it; the widget reads it through the bindings'
//! `sessionJson`), replayed on a [`Deformer`] of any method by `pose::replay`.
//!
//! ```json
//! { "format": "akap-session", "version": 3,
//!   "shape": { "name": "bar", "targetEdgeLength": 0.05, "minAngle": 28 },
//!   "mesh": { "vertexCount": 812, "triangleCount": 1400 },
//!   "options": { "method": "akap", "lambda": 100, "dirichlet": true, "integrator": "spiral" },
//!   "events": [ { "handles": { "triangles": [4, 9], "barycentric": [1, 0, 0, 0.2, 0.3, 0.5] } },
//!               { "step": [0, 0, 0.01, 0.02] },
//!               { "positions": [0, 0, 1, 0, 0.5, 1] },
//!               { "options": { "method": "arap", "iterations": 10 } },
//!               { "stiffness": [1, 1, 100, 100, 1] },
//!               { "turn": { "velocities": [0, 0, 0.01, 0], "turns": [0, 0.05] } },
//!               { "bones": { "triangles": [7, 12], "barycentric": [1, 0, 0, 0.5, 0.5, 0] } },
//!               { "rig": { "checksum": "8c3f0a51d2e47b69" } },
//!               { "rigPose": [0, 0, 0.5, 0.25] },
//!               { "rig": null },
//!               { "reset": true } ] }
//! ```
//!
//! The mesh comes from one of two places. `shape.name` names a built-in shape
//! ([`crate::shapes::NAMES`]) whose outline is triangulated again with the given options
//! (`targetEdgeLength`, `maxArea`, `minAngle`, each optional, defaults as in
//! [`TriangulationOptions`]); or there is no `shape` and the mesh is inline, in
//! `mesh.positions` (x, y per vertex) and `mesh.triangles` (3 indices each, counter-clockwise).
//! Either way it must have the recorded `vertexCount` and `triangleCount`.
//!
//! `options` are the method of the recording and its settings: `method` (`"akap"`, the
//! default, or `"arap"`), AKAP's `lambda`, `dirichlet` and `integrator`, ARAP's
//! `iterations`; each optional, that method's defaults otherwise, and an option of the
//! other method is refused. Events: `handles` replaces the handles (a triangle and 3
//! barycentric coordinates per handle); `step` is one frame with two velocity components
//! per handle, exactly as passed to the deformer; `positions` puts the mesh into a pose (2
//! numbers per vertex; handles stay); `options` changes the options as the widget's method
//! list does (over the current options when it names the same method or none; another
//! method gets a new deformer on the same mesh with the pose and handles carried over);
//! `reset` (`true`; `false` does nothing) returns to the rest pose; `stiffness` paints
//! every triangle's stiffness (one number per triangle, [`crate::deform::STIFFNESS_RANGE`]),
//! or `null` for 1 everywhere; `turn` is a frame in which handles also turn (`velocities` as
//! a `step`'s, `turns` one angle per handle in radians, counter-clockwise; AKAP and ARAP);
//! `bones` replaces the bones (two points per bone, its ends, given as handles are;
//! [`Deformer::set_bones`]), laid in the pose at that point. Stiffness and bones are for
//! the methods that have them (AKAP, ARAP: such an event
//! under another method is refused on replay as the deformer refuses it, and passed over by
//! `pose::replay_to_targets`, whose method is a comparison's).
//!
//! A trained rig (a DefOp operator) posing the shape is recorded by what it poses for, not
//! by its poses: `rig` names the rig that poses from then on by [`SessionRig`] (the
//! checksum of its operator file), or `null` when none does any more (a new handle set
//! drops it too, as the poser does); `rigPose` is one frame of it, the handles' targets
//! (x and y per handle) that the rig's pose is for, a no-foldover guard's pulled-back targets
//! where it stopped short. The operator itself is not in the session: `pose::replay_with_rigs`
//! is given the rig (its file read) and evaluates it at the recorded targets, to the same
//! bits, and refuses a `rig` event whose rig is not given ([`SessionError::MissingRig`],
//! saying which is needed). A `rigPose` needs a `rig` since the last `handles` event.
//!
//! Version 1, the first sessions (`tests/sessions/*.json`), had only a built-in shape, AKAP
//! options and `handles`, `step` and `reset` events; version 2 had every event but `rig` and
//! `rigPose`. Both are still read (a file using more than its version had is refused), and
//! written back as version 3.
//!
//! Numbers are written in the shortest form that reads back to the same double, and read
//! exactly (serde_json's `float_roundtrip`), so replaying a session repeats the recording
//! bit for bit (`pose::replay`). Other methods see other handle positions, so they follow the
//! recording's *targets* instead, each handle's position before a step plus its velocity in
//! the recording: `pose::replay_to_targets`.

use std::fmt;

use serde::{Deserialize, Serialize};

use crate::deform::handles::check_stiffness;
use crate::deform::settings::is_whole;
use crate::deform::{AkapOptions, DeformError, Deformer, Joint, Method, MethodOptions, Part, Puppet, SettingValue};
use crate::error_code::ErrorCode;
use crate::mesh::{Mesh, MeshError};
use crate::shapes;
use crate::triangulate::{triangulate, TriangulationError, TriangulationOptions};

/// The value of the `format` field.
pub const FORMAT: &str = "akap-session";
/// The format version this code writes (and the newest it reads).
pub const VERSION: u32 = 3;
/// The oldest version this code reads.
pub const OLDEST_VERSION: u32 = 1;
/// The largest session text the bindings read, in bytes (80 MB: about a million frames of
/// a few handles, or 20,000 frames of 100 handles).
pub const MAX_BYTES: usize = 80_000_000;

/// A recorded session.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Session {
    /// Always [`FORMAT`].
    pub format: String,
    /// [`VERSION`] once read (an older file is read as the newest).
    pub version: u32,
    /// The built-in shape and how it was triangulated; `None` when the mesh is inline.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shape: Option<ShapeSpec>,
    /// The size of the recorded mesh, checked on replay, and the mesh itself when there is
    /// no `shape`.
    pub mesh: SessionMesh,
    /// The method and options of the recording at its start (left out: AKAP's defaults).
    #[serde(default)]
    pub options: RecordedOptions,
    /// A puppet's parts and joints at the start (left out for one shape).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub puppet: Option<SessionPuppet>,
    /// What happened, in order.
    pub events: Vec<Event>,
}

/// A built-in shape and its triangulation options.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct ShapeSpec {
    /// One of [`crate::shapes::NAMES`].
    pub name: String,
    /// Target edge length of the triangulation.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target_edge_length: Option<f64>,
    /// Area bound of the triangulation.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_area: Option<f64>,
    /// Minimum angle in degrees of the triangulation.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_angle: Option<f64>,
}

impl ShapeSpec {
    /// The triangulation options this spec names, defaults for the rest.
    pub fn triangulation_options(&self) -> TriangulationOptions {
        let mut options = TriangulationOptions {
            target_edge_length: self.target_edge_length,
            max_area: self.max_area,
            ..TriangulationOptions::default()
        };
        if let Some(angle) = self.min_angle {
            options.min_angle_degrees = angle;
        }
        options
    }
}

/// A puppet's parts and joints as a session records them ([`crate::deform::Puppet`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SessionPuppet {
    /// Each part: its name, triangles and depth.
    pub parts: Vec<SessionPart>,
    /// The joints.
    pub joints: Vec<SessionJoint>,
}

/// One part of a recorded puppet.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SessionPart {
    /// The part's name.
    pub name: String,
    /// Its triangles.
    pub triangles: Vec<u32>,
    /// Its depth (larger is in front).
    pub depth: i32,
}

/// One joint of a recorded puppet: its point and its parts, `[front, back]`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SessionJoint {
    /// Where it is at rest.
    pub point: [f64; 2],
    /// The parts it joins, front then back.
    pub parts: [usize; 2],
}

impl SessionPuppet {
    /// A puppet as recorded.
    pub fn of(puppet: &Puppet) -> Self {
        Self {
            parts: puppet
                .parts
                .iter()
                .map(|p| SessionPart { name: p.name.clone(), triangles: p.triangles.clone(), depth: p.depth })
                .collect(),
            joints: SessionJoint::all(&puppet.joints),
        }
    }

    /// The recorded puppet (checked by the deformer that takes it).
    pub fn puppet(&self) -> Puppet {
        Puppet {
            parts: self
                .parts
                .iter()
                .map(|p| Part { name: p.name.clone(), triangles: p.triangles.clone(), depth: p.depth })
                .collect(),
            joints: SessionJoint::joints(&self.joints),
        }
    }
}

impl SessionJoint {
    /// Joints as recorded.
    pub fn all(joints: &[Joint]) -> Vec<Self> {
        joints.iter().map(|j| Self { point: j.point, parts: j.parts }).collect()
    }

    /// The recorded joints.
    pub fn joints(recorded: &[Self]) -> Vec<Joint> {
        recorded.iter().map(|j| Joint { point: j.point, parts: j.parts }).collect()
    }
}

/// A trained rig as a session names it: the FNV-1a 64 checksum of its operator file as
/// `defop::write_operator` writes it with the session's mesh (the file's last 8 bytes,
/// little-endian), written as 16 lowercase hexadecimal digits, `{ "checksum":
/// "8c3f0a51d2e47b69" }`. A rig trained in the app and one read back from its saved file
/// have the same; a file of another version than this code writes may carry another
/// checksum in its last bytes, but names the same rig here once read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(try_from = "RigName", into = "RigName")]
pub struct SessionRig {
    /// The checksum.
    pub checksum: u64,
}

/// [`SessionRig`] in JSON.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RigName {
    checksum: String,
}

impl TryFrom<RigName> for SessionRig {
    type Error = String;
    fn try_from(name: RigName) -> Result<Self, String> {
        let digits = &name.checksum;
        match (digits.len(), u64::from_str_radix(digits, 16)) {
            (16, Ok(checksum)) if !digits.starts_with('+') => Ok(Self { checksum }),
            _ => Err(format!("a rig's checksum is 16 hexadecimal digits, not {digits:?}")),
        }
    }
}

impl From<SessionRig> for RigName {
    fn from(rig: SessionRig) -> Self {
        Self { checksum: format!("{:016x}", rig.checksum) }
    }
}

impl fmt::Display for SessionRig {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:016x}", self.checksum)
    }
}

/// Vertex and triangle counts of a mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MeshCounts {
    /// Number of vertices.
    pub vertex_count: usize,
    /// Number of triangles.
    pub triangle_count: usize,
}

impl MeshCounts {
    /// The counts of `mesh`.
    pub fn of(mesh: &Mesh) -> Self {
        Self { vertex_count: mesh.vertex_count(), triangle_count: mesh.triangle_count() }
    }
}

/// The recorded mesh: its counts, and the mesh itself when the session has no shape.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct SessionMesh {
    /// Number of vertices.
    pub vertex_count: usize,
    /// Number of triangles.
    pub triangle_count: usize,
    /// Inline mesh: x and y of every vertex.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub positions: Option<Vec<f64>>,
    /// Inline mesh: three vertex indices per triangle.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub triangles: Option<Vec<u32>>,
}

impl SessionMesh {
    /// Only the counts (the mesh comes from the session's shape).
    pub fn counts_of(counts: MeshCounts) -> Self {
        Self {
            vertex_count: counts.vertex_count,
            triangle_count: counts.triangle_count,
            positions: None,
            triangles: None,
        }
    }

    /// The mesh itself, inline.
    pub fn inline(mesh: &Mesh) -> Self {
        Self {
            vertex_count: mesh.vertex_count(),
            triangle_count: mesh.triangle_count(),
            positions: Some(mesh.positions().iter().flatten().copied().collect()),
            triangles: Some(mesh.triangles().iter().flatten().copied().collect()),
        }
    }

    /// The recorded counts.
    pub fn counts(&self) -> MeshCounts {
        MeshCounts { vertex_count: self.vertex_count, triangle_count: self.triangle_count }
    }
}

/// A method and some of its settings, as the header's `options` and `options` events
/// record them: `{ "method"?: name, setting: value, ... }` with the settings by the names
/// of [`crate::deform::Settings`]; what is left out keeps its value (see [`Self::over`]).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RecordedOptions {
    /// The method, if named.
    pub method: Option<Method>,
    /// The settings given, by name, in order.
    pub values: Vec<(String, SettingValue)>,
}

impl RecordedOptions {
    /// Every option of a method (its settings: ARAP's `tolerance`, for convergence runs,
    /// is not one).
    pub fn of(options: MethodOptions) -> Self {
        let values = options.values().into_iter().map(|(name, value)| (name.to_owned(), value)).collect();
        Self { method: Some(options.method()), values }
    }

    /// The options these make over `base` ([`MethodOptions::over`]: `base` with the
    /// settings given changed when they name its method or none, else the other method's
    /// defaults with them; ranges checked). `index` is the event's, for errors (`None`: the
    /// header).
    pub fn over(&self, base: MethodOptions, index: Option<usize>) -> Result<MethodOptions, SessionError> {
        let values = self.values.iter().map(|(name, value)| (name.as_str(), value));
        MethodOptions::over(base, self.method, values).map_err(|error| match index {
            None => SessionError::Options(error),
            Some(index) => SessionError::Event { index, error },
        })
    }

    /// Whether these use what version 1 did not have (`method`, settings other than AKAP's).
    fn beyond_version_1(&self) -> bool {
        let version_1 = ["lambda", "dirichlet", "integrator"];
        self.method.is_some() || self.values.iter().any(|(name, _)| !version_1.contains(&name.as_str()))
    }
}

impl Serialize for RecordedOptions {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = serializer.serialize_map(Some(self.values.len() + usize::from(self.method.is_some())))?;
        if let Some(method) = self.method {
            map.serialize_entry("method", method.name())?;
        }
        for (name, value) in &self.values {
            match value {
                // A whole-number setting is written as one (`"iterations": 10`).
                SettingValue::Number(x) if is_whole(name) && x.fract() == 0.0 && x.abs() < 9e15 => {
                    map.serialize_entry(name, &(*x as i64))?
                }
                SettingValue::Number(x) => map.serialize_entry(name, x)?,
                SettingValue::Bool(b) => map.serialize_entry(name, b)?,
                SettingValue::Word(w) => map.serialize_entry(name, w)?,
            }
        }
        map.end()
    }
}

impl<'de> Deserialize<'de> for RecordedOptions {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_map(OptionsVisitor)
    }
}

/// Reads `{ "method"?: name, setting: value, ... }` in the file's order.
struct OptionsVisitor;

impl<'de> serde::de::Visitor<'de> for OptionsVisitor {
    type Value = RecordedOptions;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("an object of options")
    }

    fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<RecordedOptions, A::Error> {
        use serde::de::Error;
        use serde_json::Value;
        let mut options = RecordedOptions::default();
        while let Some((name, value)) = map.next_entry::<String, Value>()? {
            if name == "method" {
                let method = value.as_str().ok_or_else(|| A::Error::custom("options.method must be a string"))?;
                options.method = Some(Method::from_name(method).map_err(A::Error::custom)?);
                continue;
            }
            let value = match value {
                Value::Number(n) => SettingValue::Number(n.as_f64().expect("JSON numbers are doubles")),
                Value::Bool(b) => SettingValue::Bool(b),
                Value::String(w) => SettingValue::Word(w),
                _ => return Err(A::Error::custom(format!("option {name} must be a number, true, false or a word"))),
            };
            options.values.push((name, value));
        }
        Ok(options)
    }
}

impl From<AkapOptions> for RecordedOptions {
    fn from(o: AkapOptions) -> Self {
        Self::of(MethodOptions::Akap(o))
    }
}

/// One event of a session.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub enum Event {
    /// New handles: a triangle and three barycentric coordinates each.
    Handles {
        /// Triangle of each handle.
        triangles: Vec<u32>,
        /// Barycentric coordinates, three per handle.
        barycentric: Vec<f64>,
    },
    /// One frame: x and y velocity of each handle.
    Step(Vec<f64>),
    /// A pose: x and y of every vertex (the handles stay).
    Positions(Vec<f64>),
    /// New options, perhaps of another method.
    Options(RecordedOptions),
    /// Back to the rest pose (when `true`).
    Reset(bool),
    /// Each triangle's stiffness (one number per triangle), or `null` for 1 everywhere.
    Stiffness(Option<Vec<f64>>),
    /// New bones ([`Deformer::set_bones`]): a triangle and three barycentric coordinates for
    /// each end, two ends per bone.
    Bones {
        /// Triangle of each end.
        triangles: Vec<u32>,
        /// Barycentric coordinates, three per end.
        barycentric: Vec<f64>,
    },
    /// A puppet's joints replaced ([`Deformer::set_joints`]).
    Joints(Vec<SessionJoint>),
    /// One frame in which handles also turn ([`Deformer::step_turning`]).
    Turn {
        /// x and y velocity of each handle.
        velocities: Vec<f64>,
        /// The turn of each handle, radians counter-clockwise.
        turns: Vec<f64>,
    },
    /// A trained rig poses the shape from now on (`null`: none does any more).
    Rig(Option<SessionRig>),
    /// One frame of the rig: the handles' targets (x and y per handle) its pose is for.
    RigPose(Vec<f64>),
}

/// Why a session could not be read or replayed.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum SessionError {
    /// Not JSON of this format (serde_json's message, with line and column).
    Json(String),
    /// The `format` field is not [`FORMAT`].
    Format {
        /// The value found.
        found: String,
    },
    /// The `version` field is not one this code reads.
    Version {
        /// The value found.
        found: u32,
    },
    /// A session uses what its version did not have.
    NotInVersion {
        /// Its version.
        version: u32,
        /// What, e.g. "a positions event".
        what: &'static str,
    },
    /// The session names no shape and carries no mesh, or names a shape and carries one too,
    /// or carries only half of one.
    MeshSource,
    /// `shape.name` is not a built-in shape.
    UnknownShape {
        /// The name found.
        name: String,
    },
    /// The shape could not be triangulated with the session's options.
    Triangulation(TriangulationError),
    /// The inline mesh is invalid.
    Mesh(MeshError),
    /// The mesh differs from the recorded counts.
    MeshMismatch {
        /// The counts in the session.
        recorded: MeshCounts,
        /// The counts of the mesh now.
        found: MeshCounts,
    },
    /// The recorded options are out of range.
    Options(DeformError),
    /// No deformer can be made on the session's mesh (it is not connected, say).
    Setup(DeformError),
    /// An event was refused.
    Event {
        /// Index of the event in `events`.
        index: usize,
        /// What the deformer said.
        error: DeformError,
    },
    /// A step asks for targets, but the targets given do not cover it.
    MissingTargets {
        /// Index of the event in `events`.
        index: usize,
    },
    /// A `rig` event names a rig that the replay was not given.
    MissingRig {
        /// Index of the event in `events`.
        index: usize,
        /// The rig it names.
        rig: SessionRig,
    },
}

impl fmt::Display for SessionError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Json(e) => write!(f, "not a valid session: {e}"),
            Self::Format { found } => write!(f, "format is {found:?}, expected {FORMAT:?}"),
            Self::Version { found } => {
                write!(f, "session version {found} is not supported (only {OLDEST_VERSION} to {VERSION})")
            }
            Self::NotInVersion { version, what } => {
                write!(f, "a version-{version} session cannot have {what}; version {VERSION} sessions can")
            }
            Self::MeshSource => f.write_str(
                "the session must name a built-in shape or carry its mesh (mesh.positions and mesh.triangles), \
                 one of the two",
            ),
            Self::UnknownShape { name } => {
                write!(f, "unknown shape {name:?}; the built-in shapes are {}", shapes::NAMES.join(", "))
            }
            Self::Triangulation(e) => write!(f, "the session's shape does not triangulate: {e}"),
            Self::Mesh(e) => write!(f, "the session's mesh is invalid: {e}"),
            Self::MeshMismatch { recorded, found } => write!(
                f,
                "the session's mesh has {} vertices and {} triangles, the session recorded {} and {}",
                found.vertex_count, found.triangle_count, recorded.vertex_count, recorded.triangle_count
            ),
            Self::Options(e) => write!(f, "the session's options are invalid: {e}"),
            Self::Setup(e) => write!(f, "the session's mesh cannot be deformed: {e}"),
            Self::Event { index, error } => write!(f, "event {index}: {error}"),
            Self::MissingTargets { index } => write!(f, "event {index} is a step without targets"),
            Self::MissingRig { index, rig } => write!(
                f,
                "event {index} poses with a trained rig that is not loaded (the rig whose operator file has \
                 checksum {rig}): open that rig's .defop file, then replay"
            ),
        }
    }
}

impl std::error::Error for SessionError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Triangulation(e) => Some(e),
            Self::Mesh(e) => Some(e),
            Self::Options(e) | Self::Setup(e) | Self::Event { error: e, .. } => Some(e),
            _ => None,
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
            | Self::NotInVersion { .. }
            | Self::MissingRig { .. }
            | Self::MeshSource
            | Self::UnknownShape { .. }
            | Self::MeshMismatch { .. } => ErrorCode::Import,
        }
    }
}

impl From<TriangulationError> for SessionError {
    fn from(e: TriangulationError) -> Self {
        Self::Triangulation(e)
    }
}

impl Session {
    /// An empty AKAP session of a built-in shape (nothing checked until [`Self::mesh`]).
    pub fn new(shape: ShapeSpec, mesh: MeshCounts, options: AkapOptions) -> Self {
        Self {
            format: FORMAT.to_owned(),
            version: VERSION,
            shape: Some(shape),
            mesh: SessionMesh::counts_of(mesh),
            options: options.into(),
            puppet: None,
            events: Vec::new(),
        }
    }

    /// An empty session of a mesh carried inline, with any method.
    pub fn with_mesh(mesh: &Mesh, options: MethodOptions) -> Self {
        Self {
            format: FORMAT.to_owned(),
            version: VERSION,
            shape: None,
            mesh: SessionMesh::inline(mesh),
            options: RecordedOptions::of(options),
            puppet: None,
            events: Vec::new(),
        }
    }

    /// Reads a session (version 1 to 3; read as version 3) and checks it as far as it can
    /// without its mesh ([`Self::check`]).
    pub fn from_json(text: &str) -> Result<Self, SessionError> {
        let mut session: Self = serde_json::from_str(text).map_err(|e| SessionError::Json(e.to_string()))?;
        if session.format != FORMAT {
            return Err(SessionError::Format { found: session.format });
        }
        if !(OLDEST_VERSION..=VERSION).contains(&session.version) {
            return Err(SessionError::Version { found: session.version });
        }
        let beyond = match session.version {
            1 => session.beyond_version_1(),
            2 => session.beyond_version_2(),
            _ => None,
        };
        if let Some(what) = beyond {
            return Err(SessionError::NotInVersion { version: session.version, what });
        }
        session.version = VERSION;
        session.check()?;
        Ok(session)
    }

    /// What of version 2 the session uses, if anything.
    fn beyond_version_1(&self) -> Option<&'static str> {
        if self.shape.is_none() {
            return Some("a mesh without a shape");
        }
        if self.mesh.positions.is_some() || self.mesh.triangles.is_some() {
            return Some("an inline mesh");
        }
        if self.puppet.is_some() {
            return Some("a puppet");
        }
        if self.options.beyond_version_1() {
            return Some("options naming a method or ARAP's iterations");
        }
        self.events
            .iter()
            .find_map(|e| match e {
                Event::Positions(_) => Some("a positions event"),
                Event::Options(_) => Some("an options event"),
                Event::Stiffness(_) => Some("a stiffness event"),
                Event::Turn { .. } => Some("a turn event"),
                Event::Bones { .. } => Some("a bones event"),
                Event::Joints(_) => Some("a joints event"),
                _ => None,
            })
            .or_else(|| self.beyond_version_2())
    }

    /// What of version 3 the session uses, if anything.
    fn beyond_version_2(&self) -> Option<&'static str> {
        self.events.iter().find_map(|e| match e {
            Event::Rig(_) => Some("a rig event"),
            Event::RigPose(_) => Some("a rigPose event"),
            _ => None,
        })
    }

    /// Checks everything that does not need the mesh built: where the mesh comes from and
    /// the inline mesh's array lengths, the options of the header and of every `options`
    /// event (ranges, and options of the method in use at that point), and every event's
    /// array lengths (3 barycentric coordinates per handle, 2 velocity components per
    /// handle of the handles in place, 2 numbers per vertex), stiffness (one value per
    /// triangle, each in range), and that a `rigPose` has a rig to pose with (a `rig`
    /// since the last `handles`). Triangle indices, barycentric coordinates and velocities
    /// are checked by the deformer on replay.
    pub fn check(&self) -> Result<(), SessionError> {
        let counts = self.mesh.counts();
        match (&self.shape, &self.mesh.positions, &self.mesh.triangles) {
            (Some(_), None, None) => {}
            (None, Some(p), Some(t)) => {
                let found = MeshCounts { vertex_count: p.len() / 2, triangle_count: t.len() / 3 };
                if p.len() % 2 != 0 || t.len() % 3 != 0 || found != counts {
                    return Err(SessionError::MeshMismatch { recorded: counts, found });
                }
            }
            _ => return Err(SessionError::MeshSource),
        }
        let mut options = self.method_options()?;
        let mut handles = 0;
        let mut rig = false;
        for (index, event) in self.events.iter().enumerate() {
            let length = |what, expected, found, per, items| {
                let error = DeformError::Length { what, expected, found, per, items };
                SessionError::Event { index, error }
            };
            match event {
                Event::Handles { triangles, barycentric } => {
                    if barycentric.len() != 3 * triangles.len() {
                        return Err(length("barycentric", 3 * triangles.len(), barycentric.len(), 3, "handles"));
                    }
                    handles = triangles.len();
                    rig = false;
                }
                Event::Rig(named) => rig = named.is_some(),
                Event::RigPose(_) if !rig => return Err(SessionError::Event { index, error: DeformError::NoRig }),
                Event::RigPose(t) if t.len() != 2 * handles => {
                    return Err(length("targets", 2 * handles, t.len(), 2, "handles"))
                }
                Event::Step(v) | Event::Turn { velocities: v, .. } if v.len() != 2 * handles => {
                    return Err(length("velocities", 2 * handles, v.len(), 2, "handles"))
                }
                Event::Turn { turns, .. } if turns.len() != handles => {
                    return Err(length("turns", handles, turns.len(), 1, "handles"))
                }
                Event::Positions(p) if p.len() != 2 * counts.vertex_count => {
                    return Err(length("positions", 2 * counts.vertex_count, p.len(), 2, "vertices"))
                }
                Event::Options(o) => options = o.over(options, Some(index))?,
                Event::Stiffness(s) => check_stiffness(s.as_deref(), counts.triangle_count)
                    .map_err(|error| SessionError::Event { index, error })?,
                Event::Bones { triangles, barycentric } => {
                    if barycentric.len() != 3 * triangles.len() {
                        return Err(length("bone barycentric", 3 * triangles.len(), barycentric.len(), 3, "bone ends"));
                    }
                    if !triangles.len().is_multiple_of(2) {
                        return Err(length("bone triangles", triangles.len() + 1, triangles.len(), 2, "bones"));
                    }
                }
                Event::Joints(_) if self.puppet.is_none() => {
                    let error =
                        DeformError::InvalidParts { reason: "joints were recorded for a mesh without parts".into() };
                    return Err(SessionError::Event { index, error });
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// Writes the session as JSON, one event per line.
    pub fn to_json(&self) -> String {
        let mut out = String::from("{\n");
        out += &format!("  \"format\": {},\n", json(&self.format));
        out += &format!("  \"version\": {},\n", json(&self.version));
        if let Some(shape) = &self.shape {
            out += &format!("  \"shape\": {},\n", json(shape));
        }
        out += &format!("  \"mesh\": {},\n", json(&self.mesh));
        out += &format!("  \"options\": {},\n", json(&self.options));
        if let Some(puppet) = &self.puppet {
            out += &format!("  \"puppet\": {},\n", json(puppet));
        }
        out += "  \"events\": [";
        for (k, event) in self.events.iter().enumerate() {
            out += if k == 0 { "\n    " } else { ",\n    " };
            out += &json(event);
        }
        out += if self.events.is_empty() { "]\n}\n" } else { "\n  ]\n}\n" };
        out
    }

    /// The session's mesh: its shape triangulated again, or its inline mesh validated;
    /// checked against the recorded counts.
    pub fn mesh(&self) -> Result<Mesh, SessionError> {
        let mesh = match (&self.shape, &self.mesh.positions, &self.mesh.triangles) {
            (Some(shape), None, None) => {
                let outline = shapes::by_name(&shape.name)
                    .ok_or_else(|| SessionError::UnknownShape { name: shape.name.clone() })?;
                triangulate(&outline, &shape.triangulation_options())?
            }
            (None, Some(positions), Some(triangles)) => {
                Mesh::from_flat(positions, triangles).map_err(SessionError::Mesh)?
            }
            _ => return Err(SessionError::MeshSource),
        };
        let found = MeshCounts::of(&mesh);
        if found != self.mesh.counts() {
            return Err(SessionError::MeshMismatch { recorded: self.mesh.counts(), found });
        }
        Ok(mesh)
    }

    /// The method and options the recording starts with.
    pub fn method_options(&self) -> Result<MethodOptions, SessionError> {
        self.options.over(MethodOptions::default(), None)
    }

    /// A deformer of the recorded method and options on the session's mesh (and puppet).
    pub fn recorded_deformer(&self) -> Result<Deformer, SessionError> {
        let (mesh, options) = (self.mesh()?, self.method_options()?);
        match &self.puppet {
            Some(puppet) => Deformer::with_puppet(mesh, options, puppet.puppet(), None),
            None => Deformer::new(mesh, options),
        }
        .map_err(SessionError::Setup)
    }

    /// Number of `step` events.
    pub fn step_count(&self) -> usize {
        self.events.iter().filter(|e| matches!(e, Event::Step(_) | Event::Turn { .. })).count()
    }
}

/// One part of a session as compact JSON.
fn json<T: Serialize>(value: &T) -> String {
    serde_json::to_string(value).expect("session parts are plain data with string keys")
}
