//! The `akap-animation` JSON format, its one definition: a rest mesh, the keys an animator
//! set (handle positions at times, with an easing into each), and every frame's vertex
//! positions, so that a game engine can play the animation without our code.
//!
//! ```json
//! {
//!   "format": "akap-animation",
//!   "version": 1,
//!   "mesh": { "positions": [x0, y0, ...], "triangles": [a0, b0, c0, ...], "uvs": [u0, v0, ...] },
//!   "fps": 30,
//!   "keys": [ { "time": 0, "easing": "linear", "handles": [x0, y0, x1, y1, ...] }, ... ],
//!   "frames": [ [x0, y0, x1, y1, ...], ... ]
//! }
//! ```
//!
//! - `mesh` is a JSON mesh file's object ([`crate::import::mesh_file`]): `positions` (the
//!   rest pose), counter-clockwise `triangles`, optional `uvs` (per vertex, OBJ's
//!   convention) and `stiffness`; read with the same checks and errors.
//! - `fps` is in [`FPS_RANGE`]; frame `i` is shown at `i / fps` seconds.
//! - `keys` (at most [`MAX_KEYS`], possibly none): `time` in seconds, at least 0, strictly
//!   increasing; `easing`, `"linear"` or `"ease"`, the timing from the previous key to this
//!   one; `handles`, the handles' x, y pairs, the same number in every key.
//! - `frames` (1 to [`MAX_FRAMES`]): each every vertex's x, y, in the order of
//!   `positions`, all finite and within ±[`MAX_COORDINATE`].
//!
//! Numbers are written in their shortest form that reads back to the same double (serde_json
//! with `float_roundtrip`), so a file round-trips bit for bit. Unknown fields are errors, and
//! a file bigger than [`Limits::max_bytes`] is refused; the writer refuses what the reader
//! would, so whatever is written within some limits reads back within them.

use serde::{Deserialize, Serialize};

use super::{AnimationError, FPS_RANGE, MAX_FRAMES, MAX_KEYS};
use crate::geometry::{Point, MAX_COORDINATE};
use crate::import::mesh_file::{self, JsonMesh, MeshFile};
use crate::import::Limits;
use crate::message::Number;

/// The format's name, the `format` field.
pub const FORMAT: &str = "akap-animation";

/// The version this crate writes and reads.
pub const VERSION: u64 = 1;

/// How a key's handles are reached from the previous key's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Easing {
    /// At constant speed.
    Linear,
    /// Slow in and out (the player's curve; the frames hold the result).
    Ease,
}

/// A key: the handles' positions at a time.
#[derive(Debug, Clone, PartialEq)]
pub struct Key {
    /// Seconds from the start, at least 0.
    pub time: f64,
    /// The timing from the previous key to this one.
    pub easing: Easing,
    /// The handles' positions.
    pub handles: Vec<Point>,
}

/// An animation: a rest mesh, keys and every frame's vertex positions.
#[derive(Debug, Clone, PartialEq)]
pub struct Animation {
    /// The rest mesh, with its texture coordinates and stiffness when it has them.
    pub mesh: MeshFile,
    /// Frames per second, in [`FPS_RANGE`].
    pub fps: f64,
    /// The keys, by increasing time.
    pub keys: Vec<Key>,
    /// Each frame's positions, one per vertex of the mesh.
    pub frames: Vec<Vec<Point>>,
}

#[derive(Deserialize)]
struct Header {
    format: Option<serde_json::Value>,
    version: Option<serde_json::Value>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct JsonKey {
    time: f64,
    easing: Easing,
    handles: Vec<f64>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct JsonAnimation {
    format: String,
    version: u64,
    mesh: JsonMesh,
    fps: f64,
    keys: Vec<JsonKey>,
    frames: Vec<Vec<f64>>,
}

fn flat(points: &[Point]) -> Vec<f64> {
    points.iter().flatten().copied().collect()
}

/// Why these numbers cannot be `what`'s points, if they cannot: an odd count, or a number
/// that is not finite or beyond ±[`MAX_COORDINATE`].
fn point_problem(values: &[f64], what: &str) -> Option<String> {
    if values.len() % 2 == 1 {
        return Some(format!("{what} has {} numbers; x, y pairs need an even count", values.len()));
    }
    let i = values.iter().position(|x| !(x.is_finite() && x.abs() <= MAX_COORDINATE))?;
    Some(format!(
        "{what} has {} at index {i}; positions are finite numbers within ±{MAX_COORDINATE:e}",
        Number(values[i])
    ))
}

/// What both the writer and the reader check beyond the mesh, in the file's terms (flat
/// arrays): the problem's description, if any.
fn problem(vertices: usize, fps: f64, keys: &[JsonKey], frames: &[Vec<f64>], limits: &Limits) -> Option<String> {
    let (low, high) = (*FPS_RANGE.start(), *FPS_RANGE.end());
    if !FPS_RANGE.contains(&fps) {
        return Some(format!("fps is {}, expected a number from {} to {}", Number(fps), Number(low), Number(high)));
    }
    if keys.len() > MAX_KEYS {
        return Some(format!("{} keys, more than the limit of {MAX_KEYS}", keys.len()));
    }
    let max_handles = 2 * limits.max_vertices;
    for (k, key) in keys.iter().enumerate() {
        if !(key.time.is_finite() && key.time >= 0.0) {
            return Some(format!(
                "key {k} has the time {}, expected a finite number of seconds, at least 0",
                Number(key.time)
            ));
        }
        if k > 0 && key.time <= keys[k - 1].time {
            return Some(format!(
                "key {k} has the time {}, not after key {}'s {}; keys are in order of strictly increasing time",
                Number(key.time),
                k - 1,
                Number(keys[k - 1].time)
            ));
        }
        if key.handles.len() > max_handles {
            return Some(format!(
                "key {k} has {} numbers of handles, more than the limit of {max_handles}",
                key.handles.len()
            ));
        }
        if let Some(p) = point_problem(&key.handles, &format!("key {k}'s handles")) {
            return Some(p);
        }
        if k > 0 && key.handles.len() != keys[0].handles.len() {
            return Some(format!(
                "key {k} has {} numbers of handles and key 0 has {}; every key holds the same handles",
                key.handles.len(),
                keys[0].handles.len()
            ));
        }
    }
    if frames.is_empty() || frames.len() > MAX_FRAMES {
        return Some(format!("{} frames; an animation has from 1 to {MAX_FRAMES}", frames.len()));
    }
    for (f, frame) in frames.iter().enumerate() {
        if frame.len() != 2 * vertices {
            return Some(format!(
                "frame {f} has {} numbers; {} are needed, x and y of each of the mesh's {vertices} vertices",
                frame.len(),
                2 * vertices
            ));
        }
        if let Some(p) = point_problem(frame, &format!("frame {f}")) {
            return Some(p);
        }
    }
    None
}

/// Writes an animation as `akap-animation` JSON (version 1). Refuses, as
/// [`read_animation`] with the same `limits` would, a mesh its checks refuse (as
/// [`AnimationError::Mesh`]), anything else out of order or range (as
/// [`AnimationError::Invalid`]), or a text longer than `max_bytes`.
///
/// ```
/// use akap::animation::{read_animation, write_animation, Animation, Easing, Key};
/// use akap::import::{mesh_file::MeshFile, Limits};
/// let mesh = akap::Mesh::new(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], vec![[0, 1, 2]])?;
/// let animation = Animation {
///     mesh: MeshFile { mesh, uvs: None, stiffness: None, puppet: None },
///     fps: 24.0,
///     keys: vec![Key { time: 0.0, easing: Easing::Linear, handles: vec![[0.0, 0.0]] }],
///     frames: vec![vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], vec![[0.1, 0.0], [1.0, 0.0], [0.0, 1.0]]],
/// };
/// let text = write_animation(&animation, &Limits::default())?;
/// assert!(text.starts_with(r#"{"format":"akap-animation","version":1,"mesh":{"positions":[0.0,0.0,"#));
/// assert_eq!(read_animation(&text, &Limits::default())?, animation);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_animation(animation: &Animation, limits: &Limits) -> Result<String, AnimationError> {
    let invalid = |message| AnimationError::Invalid { message };
    limits.validate().map_err(|e| invalid(e.to_string()))?;
    let file = &animation.mesh;
    if let Some(puppet) = &file.puppet {
        mesh_file::check_puppet(puppet, &file.mesh, limits)?;
    }
    let mesh = mesh_file::to_json_mesh(
        file.mesh.positions(),
        file.mesh.triangles(),
        file.uvs.as_deref(),
        file.stiffness.as_deref(),
        file.puppet.as_ref(),
        limits,
    )?;
    // Sizes first, so that nothing huge is copied before being refused.
    if animation.frames.len() > MAX_FRAMES || animation.keys.len() > MAX_KEYS {
        return Err(invalid(format!(
            "{} frames and {} keys; the limits are {MAX_FRAMES} frames and {MAX_KEYS} keys",
            animation.frames.len(),
            animation.keys.len()
        )));
    }
    let keys: Vec<JsonKey> =
        animation.keys.iter().map(|k| JsonKey { time: k.time, easing: k.easing, handles: flat(&k.handles) }).collect();
    let frames: Vec<Vec<f64>> = animation.frames.iter().map(|f| flat(f)).collect();
    if let Some(message) = problem(file.mesh.vertex_count(), animation.fps, &keys, &frames, limits) {
        return Err(invalid(message));
    }
    let json = JsonAnimation { format: FORMAT.into(), version: VERSION, mesh, fps: animation.fps, keys, frames };
    // Finite numbers and indices always serialise.
    let text = serde_json::to_string(&json).map_err(|e| invalid(e.to_string()))?;
    check_size(&text, limits)?;
    Ok(text)
}

/// Refuses an animation JSON longer than `limits.max_bytes` (reading and writing alike).
fn check_size(text: &str, limits: &Limits) -> Result<(), AnimationError> {
    if text.len() > limits.max_bytes {
        return Err(AnimationError::TooLarge {
            what: "the animation JSON",
            size: text.len() as u64,
            limit: limits.max_bytes as u64,
            unit: "bytes",
        });
    }
    Ok(())
}

fn syntax(e: &serde_json::Error) -> AnimationError {
    let (line, column) = (e.line(), e.column());
    let message = e.to_string();
    let suffix = format!(" at line {line} column {column}");
    AnimationError::Syntax { message: message.strip_suffix(&suffix).unwrap_or(&message).to_string(), line, column }
}

/// Reads an `akap-animation` file with every check: the size against `limits.max_bytes`,
/// the `format` and `version` (before anything else, so that another JSON file is named
/// for what it is not), the JSON's syntax and fields, the mesh (as a JSON mesh file), and
/// the rules of the format (see the module's documentation), each refused with a message
/// that says what and where.
pub fn read_animation(text: &str, limits: &Limits) -> Result<Animation, AnimationError> {
    let file_error = |message| AnimationError::File { message };
    limits.validate().map_err(|e| AnimationError::Invalid { message: e.to_string() })?;
    check_size(text, limits)?;
    let header: Header = serde_json::from_str(text).map_err(|e| syntax(&e))?;
    match header.format {
        Some(serde_json::Value::String(f)) if f == FORMAT => {}
        Some(other) => return Err(file_error(format!("its format is {other}, not \"{FORMAT}\""))),
        None => return Err(file_error(format!("it has no \"format\": \"{FORMAT}\""))),
    }
    match header.version {
        Some(v) if v.as_u64() == Some(VERSION) => {}
        Some(v) => return Err(file_error(format!("its version is {v}; this reader knows version {VERSION}"))),
        None => return Err(file_error("it has no \"version\"".into())),
    }
    let parsed: JsonAnimation = serde_json::from_str(text).map_err(|e| syntax(&e))?;
    let mesh = mesh_file::from_json_mesh(parsed.mesh, limits)?;
    if let Some(message) = problem(mesh.mesh.vertex_count(), parsed.fps, &parsed.keys, &parsed.frames, limits) {
        return Err(file_error(message));
    }
    let pairs = |values: &[f64]| values.chunks_exact(2).map(|p| [p[0], p[1]]).collect::<Vec<Point>>();
    Ok(Animation {
        mesh,
        fps: parsed.fps,
        keys: parsed.keys.iter().map(|k| Key { time: k.time, easing: k.easing, handles: pairs(&k.handles) }).collect(),
        frames: parsed.frames.iter().map(|f| pairs(f)).collect(),
    })
}
