//! Recorded interaction sessions: the JSON format the app records and the comparison
//! replays, and their replay on any [`Deform`] method.
//!
//! ```json
//! { "format": "akap-session", "version": 1,
//!   "shape": { "name": "bar", "targetEdgeLength": 0.05, "minAngle": 28 },
//!   "mesh": { "vertexCount": 812, "triangleCount": 1400 },
//!   "options": { "lambda": 100, "dirichlet": true, "integrator": "spiral" },
//!   "events": [ { "handles": { "triangles": [4, 9], "barycentric": [1, 0, 0, 0.2, 0.3, 0.5] } },
//!               { "step": [0, 0, 0.01, 0.02] },
//!               { "reset": true } ] }
//! ```
//!
//! `shape.name` names a built-in shape ([`crate::shapes::NAMES`]); its outline is
//! triangulated again with the given options (`targetEdgeLength`, `maxArea`, `minAngle`,
//! each optional, defaults as in [`TriangulationOptions`]) and the result must have the
//! recorded vertex and triangle counts. `options` are the AKAP options of the recording.
//! Events: `handles` replaces the handles (a triangle and 3 barycentric coordinates per
//! handle), `step` is one frame with two velocity components per handle, exactly as passed
//! to the deformer, and `reset` (`true`; `false` does nothing) returns to the rest pose.
//!
//! Numbers are written in the shortest form that reads back to the same double, and read
//! exactly (serde_json's `float_roundtrip`), so replaying a session with the recorded
//! options repeats the recording bit for bit ([`replay`]). Other methods see other handle
//! positions, so they follow the recording's *targets* instead, each handle's position
//! before a step plus its velocity in the recording: [`replay_to_targets`].

use std::fmt;

use serde::{Deserialize, Serialize};

use crate::deform::{Deform, DeformError, Deformer, DeformerOptions, Integrator};
use crate::geometry::Point;
use crate::mesh::Mesh;
use crate::shapes;
use crate::triangulate::{triangulate, TriangulationError, TriangulationOptions};

/// The value of the `format` field.
pub const FORMAT: &str = "akap-session";
/// The format version this code reads and writes.
pub const VERSION: u32 = 1;

/// A recorded session.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Session {
    /// Always [`FORMAT`].
    pub format: String,
    /// Always [`VERSION`].
    pub version: u32,
    /// The built-in shape and how it was triangulated.
    pub shape: ShapeSpec,
    /// The size of the recorded mesh, checked on replay.
    pub mesh: MeshCounts,
    /// The AKAP options of the recording.
    pub options: RecordedOptions,
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

/// Vertex and triangle counts of a mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct MeshCounts {
    /// Number of vertices.
    pub vertex_count: usize,
    /// Number of triangles.
    pub triangle_count: usize,
}

/// The AKAP options of a recording.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RecordedOptions {
    /// Weight of the soft handle constraints.
    pub lambda: f64,
    /// Whether the Dirichlet step ran.
    pub dirichlet: bool,
    /// `"spiral"` or `"linear"`.
    pub integrator: IntegratorName,
}

/// The integrator as sessions name it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum IntegratorName {
    /// Log-spiral steps.
    Spiral,
    /// Linear steps.
    Linear,
}

impl From<DeformerOptions> for RecordedOptions {
    fn from(o: DeformerOptions) -> Self {
        let integrator = match o.integrator {
            Integrator::Spiral => IntegratorName::Spiral,
            Integrator::Linear => IntegratorName::Linear,
        };
        Self { lambda: o.lambda, dirichlet: o.dirichlet, integrator }
    }
}

impl From<RecordedOptions> for DeformerOptions {
    fn from(o: RecordedOptions) -> Self {
        let integrator = match o.integrator {
            IntegratorName::Spiral => Integrator::Spiral,
            IntegratorName::Linear => Integrator::Linear,
        };
        DeformerOptions { lambda: o.lambda, dirichlet: o.dirichlet, integrator }
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
    /// Back to the rest pose (when `true`).
    Reset(bool),
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
    /// The `version` field is not [`VERSION`].
    Version {
        /// The value found.
        found: u32,
    },
    /// `shape.name` is not a built-in shape.
    UnknownShape {
        /// The name found.
        name: String,
    },
    /// The shape could not be triangulated with the session's options.
    Triangulation(TriangulationError),
    /// The triangulation differs from the recorded one.
    MeshMismatch {
        /// The counts in the session.
        recorded: MeshCounts,
        /// The counts of the triangulation now.
        found: MeshCounts,
    },
    /// The recorded options are invalid.
    Options(DeformError),
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
}

impl fmt::Display for SessionError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Json(e) => write!(f, "not a valid session: {e}"),
            Self::Format { found } => write!(f, "format is {found:?}, expected {FORMAT:?}"),
            Self::Version { found } => write!(f, "session version {found} is not supported (only {VERSION})"),
            Self::UnknownShape { name } => {
                write!(f, "unknown shape {name:?}; the built-in shapes are {}", shapes::NAMES.join(", "))
            }
            Self::Triangulation(e) => write!(f, "the session's shape does not triangulate: {e}"),
            Self::MeshMismatch { recorded, found } => write!(
                f,
                "the shape triangulates to {} vertices and {} triangles, the session recorded {} and {}",
                found.vertex_count, found.triangle_count, recorded.vertex_count, recorded.triangle_count
            ),
            Self::Options(e) => write!(f, "the session's options are invalid: {e}"),
            Self::Event { index, error } => write!(f, "event {index}: {error}"),
            Self::MissingTargets { index } => write!(f, "event {index} is a step without targets"),
        }
    }
}

impl std::error::Error for SessionError {}

impl From<TriangulationError> for SessionError {
    fn from(e: TriangulationError) -> Self {
        Self::Triangulation(e)
    }
}

impl Session {
    /// An empty session of a built-in shape (nothing checked until [`Self::mesh`]).
    pub fn new(shape: ShapeSpec, mesh: MeshCounts, options: DeformerOptions) -> Self {
        Self { format: FORMAT.to_owned(), version: VERSION, shape, mesh, options: options.into(), events: Vec::new() }
    }

    /// Reads a session, checking the format name and version.
    pub fn from_json(text: &str) -> Result<Self, SessionError> {
        let session: Self = serde_json::from_str(text).map_err(|e| SessionError::Json(e.to_string()))?;
        if session.format != FORMAT {
            return Err(SessionError::Format { found: session.format });
        }
        if session.version != VERSION {
            return Err(SessionError::Version { found: session.version });
        }
        Ok(session)
    }

    /// Writes the session as JSON, one event per line.
    pub fn to_json(&self) -> String {
        let mut out = String::from("{\n");
        out += &format!("  \"format\": {},\n", json(&self.format));
        out += &format!("  \"version\": {},\n", json(&self.version));
        out += &format!("  \"shape\": {},\n", json(&self.shape));
        out += &format!("  \"mesh\": {},\n", json(&self.mesh));
        out += &format!("  \"options\": {},\n", json(&self.options));
        out += "  \"events\": [";
        for (k, event) in self.events.iter().enumerate() {
            out += if k == 0 { "\n    " } else { ",\n    " };
            out += &json(event);
        }
        out += if self.events.is_empty() { "]\n}\n" } else { "\n  ]\n}\n" };
        out
    }

    /// The triangulation options of the session's shape.
    pub fn triangulation_options(&self) -> TriangulationOptions {
        let mut options = TriangulationOptions {
            target_edge_length: self.shape.target_edge_length,
            max_area: self.shape.max_area,
            ..TriangulationOptions::default()
        };
        if let Some(angle) = self.shape.min_angle {
            options.min_angle_degrees = angle;
        }
        options
    }

    /// The session's mesh: its shape triangulated again, checked against the recording.
    pub fn mesh(&self) -> Result<Mesh, SessionError> {
        let outline = shapes::by_name(&self.shape.name)
            .ok_or_else(|| SessionError::UnknownShape { name: self.shape.name.clone() })?;
        let mesh = triangulate(&outline, &self.triangulation_options())?;
        let found = MeshCounts { vertex_count: mesh.vertex_count(), triangle_count: mesh.triangle_count() };
        if found != self.mesh {
            return Err(SessionError::MeshMismatch { recorded: self.mesh, found });
        }
        Ok(mesh)
    }

    /// The recorded AKAP options.
    pub fn deformer_options(&self) -> DeformerOptions {
        self.options.into()
    }

    /// A deformer with the recorded options on the session's mesh.
    pub fn recorded_deformer(&self) -> Result<Deformer, SessionError> {
        Deformer::new(self.mesh()?, self.deformer_options()).map_err(SessionError::Options)
    }

    /// Number of `step` events.
    pub fn step_count(&self) -> usize {
        self.events.iter().filter(|e| matches!(e, Event::Step(_))).count()
    }
}

/// One part of a session as compact JSON.
fn json<T: Serialize>(value: &T) -> String {
    serde_json::to_string(value).expect("session parts are plain data with string keys")
}

/// What a replay did.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Replay {
    /// For every step, the handles' targets: position before the step plus velocity.
    pub targets: Vec<Vec<Point>>,
    /// For every step, the milliseconds the deformer's timings report (all stages).
    pub frame_ms: Vec<f64>,
    /// Mean distance of the handles from the targets of the last event, if it was a step.
    pub handle_error: Option<f64>,
}

/// Replays the events as recorded, the velocities as given. With the recorded method and
/// options this repeats the recording exactly.
pub fn replay(session: &Session, deformer: &mut dyn Deform) -> Result<Replay, SessionError> {
    run(session, deformer, None)
}

/// Replays the events driving every handle to the recorded targets (see [`Replay::targets`]
/// of a [`replay`] with the recorded deformer): each step's velocity is the target minus
/// the handle's current position in `deformer`.
pub fn replay_to_targets(
    session: &Session,
    targets: &[Vec<Point>],
    deformer: &mut dyn Deform,
) -> Result<Replay, SessionError> {
    run(session, deformer, Some(targets))
}

fn run(session: &Session, deformer: &mut dyn Deform, targets: Option<&[Vec<Point>]>) -> Result<Replay, SessionError> {
    let mut replay = Replay::default();
    let mut velocities = Vec::new();
    let mut last_was_step = false;
    for (index, event) in session.events.iter().enumerate() {
        let refused = |error| SessionError::Event { index, error };
        last_was_step &= matches!(event, Event::Reset(false));
        match event {
            Event::Handles { triangles, barycentric } => {
                let (weights, rest) = barycentric.as_chunks::<3>();
                if !rest.is_empty() || weights.len() != triangles.len() {
                    return Err(refused(DeformError::Length {
                        what: "barycentric",
                        expected: 3 * triangles.len(),
                        found: barycentric.len(),
                        per: 3,
                        items: "handles",
                    }));
                }
                deformer.set_handle_points(triangles, weights).map_err(refused)?;
            }
            Event::Step(flat) => {
                let before = deformer.handle_positions();
                let (pairs, rest) = flat.as_chunks::<2>();
                if !rest.is_empty() {
                    return Err(refused(DeformError::Length {
                        what: "velocities",
                        expected: 2 * before.len(),
                        found: flat.len(),
                        per: 2,
                        items: "handles",
                    }));
                }
                let goal: Vec<Point> = match targets {
                    None => before.iter().zip(pairs).map(|(p, v)| [p[0] + v[0], p[1] + v[1]]).collect(),
                    Some(all) => all.get(replay.targets.len()).ok_or(SessionError::MissingTargets { index })?.clone(),
                };
                velocities.clear();
                match targets {
                    None => velocities.extend_from_slice(pairs),
                    Some(_) => {
                        if goal.len() != before.len() {
                            return Err(SessionError::MissingTargets { index });
                        }
                        velocities.extend(before.iter().zip(&goal).map(|(p, t)| [t[0] - p[0], t[1] - p[1]]));
                    }
                }
                deformer.step(&velocities).map_err(refused)?;
                let t = deformer.timings();
                replay.frame_ms.push(t.assembly + t.factorisation + t.solve + t.integration);
                replay.targets.push(goal);
                last_was_step = true;
            }
            Event::Reset(true) => deformer.reset(),
            Event::Reset(false) => {}
        }
    }
    if last_was_step {
        let goal = replay.targets.last().expect("a step was replayed");
        let handles = deformer.handle_positions();
        let total: f64 = handles.iter().zip(goal).map(|(p, t)| (p[0] - t[0]).hypot(p[1] - t[1])).sum();
        replay.handle_error = Some(if handles.is_empty() { 0.0 } else { total / handles.len() as f64 });
    }
    Ok(replay)
}
