//! Mesh files: our JSON (`{ "positions": [x0, y0, ...], "triangles": [a0, b0, c0, ...],
//! "uvs": [u0, v0, ...], "stiffness": [s0, s1, ...] }`, `uvs` (per vertex) and `stiffness`
//! (per triangle, the painted factor on its energy, in [`STIFFNESS_RANGE`]) optional) and Wavefront OBJ (`v`, `vt`, `f` with polygons
//! fanned into triangles, negative indices, comments). Both are read into a validated
//! [`Mesh`] (the same rules and errors as [`Mesh::new`]) and written back so that a round
//! trip gives the same numbers. Readers and writers share one set of [`Limits`]: the
//! writers refuse a mesh whose file the readers would refuse, so whatever is written within
//! some limits reads back within them. The `_pose` writers write a mesh's triangles at other
//! positions (a pose), checked only by [`Mesh::check_arrays`]: flipped or collapsed
//! triangles are written as they are, and such a file reads back only once they are undone.
//!
//! Texture coordinates, OBJ's `vt` and JSON's `uvs`, are in the crate's one convention,
//! Wavefront OBJ's (see [`crate::import::warp::texture_coordinates`]): `u` from the image's
//! left edge, `v` up from its bottom edge, `(0, 0)` at the bottom-left corner and `(1, 1)`
//! at the top-right. They are read and written as the numbers they are, never flipped.
//!
//! OBJ has no place for per-triangle values, so stiffness travels in JSON only.
//!
//! A mesh may be a puppet ([`Puppet`]: sheets, one per part, joined at joints). JSON
//! carries it whole, as `"parts": [{ "name", "triangles", "depth" }]` (triangle indices;
//! larger depth in front) and `"joints": [{ "point": [x, y], "parts": [front, back] }]`,
//! checked on reading as [`crate::deform::Deformer::with_puppet`] checks it. OBJ carries the
//! parts as groups, the OBJ way: `g name` before each part's faces, parts back to front
//! ([`obj_group_names`] makes the names fit OBJ's rules); reading, the groups become parts
//! in the order they first appear, each of depth its place. OBJ has no place for joints, so
//! they travel in JSON only. Without a puppet both formats are written exactly as before.

use std::collections::HashMap;
use std::fmt::Write;

use serde::{Deserialize, Serialize};

use crate::deform::{DeformError, Joint, Part, Puppet, MAX_PARTS, MAX_PART_NAME_BYTES, STIFFNESS_RANGE};
use crate::geometry::Point;
use crate::import::{ImportError, Limits};
use crate::mesh::Mesh;
use crate::message::Number;

/// A mesh read from a file, with its per-vertex texture coordinates if the file has them.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshFile {
    /// The validated mesh.
    pub mesh: Mesh,
    /// One `[u, v]` per vertex (v up from the image's bottom edge), or `None`.
    pub uvs: Option<Vec<Point>>,
    /// One stiffness per triangle (JSON only), or `None` (1 everywhere).
    pub stiffness: Option<Vec<f64>>,
    /// The mesh's parts and joints if it is a puppet (OBJ: its groups, without joints), or
    /// `None` for one shape.
    pub puppet: Option<Puppet>,
}

/// A mesh in our JSON layout as serde reads and writes it, unchecked; also the `mesh` of
/// an `akap-animation` file (`crate::animation::file`).
#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct JsonMesh {
    positions: Vec<f64>,
    triangles: Vec<u32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    uvs: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    stiffness: Option<Vec<f64>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    parts: Option<Vec<JsonPart>>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    joints: Option<Vec<JsonJoint>>,
}

/// A puppet's part in our JSON: its name, its triangles (indices into the mesh's
/// triangles) and its depth (larger in front).
#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct JsonPart {
    name: String,
    triangles: Vec<u32>,
    depth: i32,
}

/// A puppet's joint in our JSON: its point at rest and its parts, `[front, back]`.
#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct JsonJoint {
    point: [f64; 2],
    parts: [u32; 2],
}

fn check_size(text: &str, limits: &Limits, what: &'static str) -> Result<(), ImportError> {
    Limits::check(text.len(), limits.max_bytes, what, "bytes")
}

fn check_counts(vertices: usize, triangles: usize, limits: &Limits, what: &'static str) -> Result<(), ImportError> {
    Limits::check(vertices, limits.max_vertices, what, "vertices")?;
    Limits::check(triangles, limits.max_vertices.saturating_mul(2), what, "triangles")
}

/// What the writers check before writing: valid limits, triangles that name vertices at
/// finite positions, texture coordinates that fit, and counts the readers accept.
fn check_writable(
    positions: &[Point],
    triangles: &[[u32; 3]],
    uvs: Option<&[Point]>,
    limits: &Limits,
) -> Result<(), ImportError> {
    limits.validate()?;
    check_counts(positions.len(), triangles.len(), limits, "the mesh to write")?;
    Mesh::check_arrays(positions, triangles)?;
    if let Some(uvs) = uvs {
        check_uvs(uvs, positions.len())?;
    }
    Ok(())
}

/// What the writers check after writing: the file's size against the readers' limit.
fn check_written(text: String, limits: &Limits, what: &'static str) -> Result<String, ImportError> {
    Limits::check(text.len(), limits.max_bytes, what, "bytes")?;
    Ok(text)
}

/// Checks stiffness against the mesh: one value per triangle, each in [`STIFFNESS_RANGE`].
fn check_stiffness(stiffness: &[f64], triangles: usize) -> Result<(), ImportError> {
    let (low, high) = (*STIFFNESS_RANGE.start(), *STIFFNESS_RANGE.end());
    let message = if stiffness.len() != triangles {
        format!("{} numbers for {triangles} triangles; one per triangle is needed", stiffness.len())
    } else if let Some(t) = stiffness.iter().position(|s| !STIFFNESS_RANGE.contains(s)) {
        format!("triangle {t} has {}, expected a number from {} to {}", Number(stiffness[t]), Number(low), Number(high))
    } else {
        return Ok(());
    };
    Err(ImportError::Stiffness { message })
}

/// Checks texture coordinates against the mesh: one finite pair per vertex.
fn check_uvs(uvs: &[Point], vertices: usize) -> Result<(), ImportError> {
    if uvs.len() != vertices {
        return Err(ImportError::TextureCoordinates {
            message: format!(
                "{} numbers for {vertices} vertices; {} are needed, a u and a v per vertex",
                2 * uvs.len(),
                2 * vertices
            ),
        });
    }
    if let Some(v) = uvs.iter().position(|t| !(t[0].is_finite() && t[1].is_finite())) {
        return Err(ImportError::TextureCoordinates { message: format!("vertex {v} has a value that is not finite") });
    }
    Ok(())
}

/// Checks a puppet's sizes against the limits: at most [`MAX_PARTS`] parts, each name at
/// most [`MAX_PART_NAME_BYTES`], at most `max_vertices` joints.
fn check_puppet_sizes(puppet: &Puppet, limits: &Limits) -> Result<(), ImportError> {
    Limits::check(puppet.parts.len(), MAX_PARTS, "the puppet", "parts")?;
    Limits::check(puppet.joints.len(), limits.max_vertices, "the puppet", "joints")?;
    if let Some((p, part)) = puppet.parts.iter().enumerate().find(|(_, part)| part.name.len() > MAX_PART_NAME_BYTES) {
        return Err(ImportError::Puppet(DeformError::InvalidParts {
            reason: format!(
                "the name of part {p} has {} bytes, more than the limit of {MAX_PART_NAME_BYTES}",
                part.name.len()
            ),
        }));
    }
    Ok(())
}

/// Checks a puppet against a pose's `triangle_count` triangles, as far as a file needs
/// (what [`Puppet::check_indices`] checks) and its sizes.
fn check_puppet_indices(puppet: &Puppet, triangle_count: usize, limits: &Limits) -> Result<(), ImportError> {
    check_puppet_sizes(puppet, limits)?;
    puppet.check_indices(triangle_count).map_err(ImportError::Puppet)
}

/// Checks a puppet against its rest mesh in full: its sizes, and every triangle in one
/// part, each joint on both its parts (as [`crate::deform::Deformer::with_puppet`] does).
pub(crate) fn check_puppet(puppet: &Puppet, mesh: &Mesh, limits: &Limits) -> Result<(), ImportError> {
    check_puppet_sizes(puppet, limits)?;
    puppet.joins(mesh).map(|_| ()).map_err(ImportError::Puppet)
}

/// Reads our JSON mesh format. Unknown fields are errors, so a misspelt `uvs` is noticed.
///
/// ```
/// use akap::import::{mesh_file::read_json, Limits};
/// let file = read_json(r#"{"positions": [0,0, 1,0, 0,1], "triangles": [0,1,2]}"#, &Limits::default())?;
/// assert_eq!(file.mesh.triangle_count(), 1);
/// # Ok::<(), akap::import::ImportError>(())
/// ```
pub fn read_json(text: &str, limits: &Limits) -> Result<MeshFile, ImportError> {
    limits.validate()?;
    check_size(text, limits, "the JSON text")?;
    let parsed: JsonMesh = serde_json::from_str(text).map_err(|e| {
        let (line, column) = (e.line(), e.column());
        let message = e.to_string();
        let suffix = format!(" at line {line} column {column}");
        ImportError::Syntax {
            format: "JSON",
            message: message.strip_suffix(&suffix).unwrap_or(&message).to_string(),
            line,
            column,
        }
    })?;
    from_json_mesh(parsed, limits)
}

/// The checked mesh file of a parsed [`JsonMesh`] (what [`read_json`] does after parsing).
pub(crate) fn from_json_mesh(parsed: JsonMesh, limits: &Limits) -> Result<MeshFile, ImportError> {
    check_counts(parsed.positions.len() / 2, parsed.triangles.len() / 3, limits, "the mesh")?;
    let mesh = Mesh::from_flat(&parsed.positions, &parsed.triangles)?;
    let uvs = match parsed.uvs {
        None => None,
        Some(flat) => {
            if flat.len() % 2 == 1 {
                return Err(ImportError::TextureCoordinates {
                    message: format!("uvs must hold u, v pairs, but their length {} is odd", flat.len()),
                });
            }
            let pairs: Vec<Point> = flat.chunks_exact(2).map(|p| [p[0], p[1]]).collect();
            check_uvs(&pairs, mesh.vertex_count())?;
            Some(pairs)
        }
    };
    if let Some(stiffness) = &parsed.stiffness {
        check_stiffness(stiffness, mesh.triangle_count())?;
    }
    let puppet = match (parsed.parts, parsed.joints) {
        (None, None) => None,
        (None, Some(_)) => {
            return Err(ImportError::Puppet(DeformError::InvalidParts {
                reason: "the file has joints but no parts; joints join parts".into(),
            }))
        }
        (Some(parts), joints) => {
            let puppet = Puppet {
                parts: parts
                    .into_iter()
                    .map(|p| Part { name: p.name, triangles: p.triangles, depth: p.depth })
                    .collect(),
                joints: joints
                    .unwrap_or_default()
                    .into_iter()
                    .map(|j| Joint { point: j.point, parts: j.parts.map(|p| p as usize) })
                    .collect(),
            };
            check_puppet(&puppet, &mesh, limits)?;
            Some(puppet)
        }
    };
    Ok(MeshFile { mesh, uvs, stiffness: parsed.stiffness, puppet })
}

/// Writes our JSON mesh format (numbers in their shortest exact form), with `uvs`,
/// `stiffness` and a puppet's `parts` and `joints` when given (checked as [`read_json`]
/// checks them). Refuses, like
/// [`read_json`] with the same `limits`, a mesh with more vertices or triangles than they
/// allow or a text longer than `max_bytes`.
///
/// ```
/// use akap::import::{mesh_file::{read_json, write_json}, Limits};
/// let mesh = akap::Mesh::new(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1e-300]], vec![[0, 1, 2]])?;
/// let text = write_json(&mesh, None, None, None, &Limits::default())?;
/// assert_eq!(text, r#"{"positions":[0.0,0.0,1.0,0.0,0.0,1e-300],"triangles":[0,1,2]}"#);
/// let stiff = write_json(&mesh, None, Some(&[100.0]), None, &Limits::default())?;
/// assert_eq!(read_json(&stiff, &Limits::default())?.stiffness, Some(vec![100.0]));
/// assert_eq!(read_json(&text, &Limits::default())?.mesh, mesh);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_json(
    mesh: &Mesh,
    uvs: Option<&[Point]>,
    stiffness: Option<&[f64]>,
    puppet: Option<&Puppet>,
    limits: &Limits,
) -> Result<String, ImportError> {
    if let Some(puppet) = puppet {
        limits.validate()?;
        check_puppet(puppet, mesh, limits)?;
    }
    write_json_pose(mesh.positions(), mesh.triangles(), uvs, stiffness, puppet, limits)
}

/// Writes `triangles` at `positions` (a pose of a mesh) as [`write_json`] writes a mesh,
/// checking only what a file needs ([`Mesh::check_arrays`], and for a puppet
/// [`Puppet::check_indices`]): a pose with flipped or collapsed triangles is written as it
/// is, and a puppet's joints as given (their points are where they are at rest, which
/// reading the file back checks against the positions written).
pub fn write_json_pose(
    positions: &[Point],
    triangles: &[[u32; 3]],
    uvs: Option<&[Point]>,
    stiffness: Option<&[f64]>,
    puppet: Option<&Puppet>,
    limits: &Limits,
) -> Result<String, ImportError> {
    let json = to_json_mesh(positions, triangles, uvs, stiffness, puppet, limits)?;
    // Arrays of finite numbers and indices always serialise.
    check_written(serde_json::to_string(&json).expect("a mesh serialises to JSON"), limits, "the JSON text")
}

/// The [`JsonMesh`] of a pose, checked as [`write_json_pose`] checks it.
pub(crate) fn to_json_mesh(
    positions: &[Point],
    triangles: &[[u32; 3]],
    uvs: Option<&[Point]>,
    stiffness: Option<&[f64]>,
    puppet: Option<&Puppet>,
    limits: &Limits,
) -> Result<JsonMesh, ImportError> {
    check_writable(positions, triangles, uvs, limits)?;
    if let Some(stiffness) = stiffness {
        check_stiffness(stiffness, triangles.len())?;
    }
    if let Some(puppet) = puppet {
        check_puppet_indices(puppet, triangles.len(), limits)?;
    }
    Ok(JsonMesh {
        positions: positions.iter().flatten().copied().collect(),
        triangles: triangles.iter().flatten().copied().collect(),
        uvs: uvs.map(|u| u.iter().flatten().copied().collect()),
        stiffness: stiffness.map(<[f64]>::to_vec),
        parts: puppet.map(|p| {
            p.parts
                .iter()
                .map(|part| JsonPart { name: part.name.clone(), triangles: part.triangles.clone(), depth: part.depth })
                .collect()
        }),
        joints: puppet.map(|p| {
            // Part indices are below `MAX_PARTS` (checked).
            p.joints.iter().map(|j| JsonJoint { point: j.point, parts: j.parts.map(|i| i as u32) }).collect()
        }),
    })
}

/// OBJ statements that carry nothing for a flat triangle mesh; they are skipped.
const OBJ_IGNORED: [&str; 34] = [
    "vn",
    "vp",
    "o",
    "s",
    "usemtl",
    "mtllib",
    "l",
    "p",
    "mg",
    "cstype",
    "deg",
    "bmat",
    "step",
    "curv",
    "curv2",
    "surf",
    "parm",
    "trim",
    "hole",
    "scrv",
    "sp",
    "end",
    "con",
    "bevel",
    "c_interp",
    "d_interp",
    "lod",
    "usemap",
    "maplib",
    "shadow_obj",
    "trace_obj",
    "ctech",
    "stech",
    "call",
];

/// Reads a Wavefront OBJ mesh in the xy plane: `v x y [z]` (z must be 0), `vt u v`, and
/// faces `f a b c ...` whose corners are `v`, `v/vt`, `v//vn` or `v/vt/vn` (1-based, or
/// negative: counted back from the last vertex so far), fanned into triangles from their
/// first corner. Texture coordinates become per-vertex, so a vertex used with two
/// different ones is an error.
///
/// Groups (`g name`) make the mesh a puppet: each group is a part, named by the `g`
/// statement (a `g` of several names is one part named by them all, a space between; `g`
/// alone is `default`), holding the faces that follow it until the next `g` (a name seen
/// before adds to its part), in the order the groups first hold a face, each of depth its
/// place (0 at the back). Faces before the first `g` are in `default`; groups without
/// faces make no part. At most [`MAX_PARTS`] parts, and names of at most
/// [`MAX_PART_NAME_BYTES`]. A file without `g` is one shape (`puppet` is `None`).
pub fn read_obj(text: &str, limits: &Limits) -> Result<MeshFile, ImportError> {
    limits.validate()?;
    check_size(text, limits, "the OBJ text")?;
    let mut positions: Vec<Point> = Vec::new();
    let mut texcoords: Vec<Point> = Vec::new();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    // Per vertex, the texture coordinate its corners use (checked to agree).
    let mut uv_of: Vec<Option<Point>> = Vec::new();
    let mut corners_with_uv = (0usize, 0usize); // (with, without)
                                                // Groups: whether any `g` was seen, the parts' names and triangles, the part of each
                                                // name, and the current group's name and part (found at its first face).
    let mut grouped = false;
    let mut groups: Vec<(String, Vec<u32>)> = Vec::new();
    let mut group_of: HashMap<String, usize> = HashMap::new();
    let mut group = String::from("default");
    let mut group_part: Option<usize> = None;
    let mut lines = text.split('\n').enumerate().peekable();
    let mut joined = String::new();
    while let Some((index, raw)) = lines.next() {
        let line_number = index + 1;
        // A trailing backslash continues the statement on the next line.
        let mut line = raw.strip_suffix('\r').unwrap_or(raw);
        if line.ends_with('\\') {
            joined.clear();
            joined.push_str(&line[..line.len() - 1]);
            for (_, next) in lines.by_ref() {
                let next = next.strip_suffix('\r').unwrap_or(next);
                match next.strip_suffix('\\') {
                    Some(part) => joined.push_str(part),
                    None => {
                        joined.push_str(next);
                        break;
                    }
                }
                joined.push(' ');
            }
            line = &joined;
        }
        let content = line.split('#').next().unwrap_or("");
        let column_of =
            |token: &str| content[..token.as_ptr() as usize - content.as_ptr() as usize].chars().count() + 1;
        let error = |token: &str, message: String| ImportError::Syntax {
            format: "OBJ",
            message,
            line: line_number,
            column: column_of(token),
        };
        let mut tokens = content.split_ascii_whitespace();
        let Some(keyword) = tokens.next() else { continue };
        let args: Vec<&str> = tokens.collect();
        let number = |token: &str| -> Result<f64, ImportError> {
            match token.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(error(token, format!("`{token}` is not a finite number"))),
            }
        };
        match keyword {
            "v" => {
                if !(2..=7).contains(&args.len()) {
                    return Err(error(
                        keyword,
                        format!("a vertex needs x and y (and z = 0), found {} numbers", args.len()),
                    ));
                }
                let values = args.iter().map(|a| number(a)).collect::<Result<Vec<f64>, _>>()?;
                if values.len() > 2 && values[2] != 0.0 {
                    return Err(error(
                        args[2],
                        format!(
                            "vertex {} has z = {}; only flat meshes in the xy plane can be read",
                            positions.len() + 1,
                            values[2]
                        ),
                    ));
                }
                Limits::check(positions.len() + 1, limits.max_vertices, "the mesh", "vertices")?;
                positions.push([values[0], values[1]]);
                uv_of.push(None);
            }
            "vt" => {
                if !(1..=3).contains(&args.len()) {
                    return Err(error(
                        keyword,
                        format!("a texture coordinate needs u and v, found {} numbers", args.len()),
                    ));
                }
                let u = number(args[0])?;
                let v = args.get(1).map(|a| number(a)).transpose()?.unwrap_or(0.0);
                Limits::check(texcoords.len() + 1, limits.max_vertices, "the mesh", "texture coordinates")?;
                texcoords.push([u, v]);
            }
            "f" => {
                if args.len() < 3 {
                    return Err(error(keyword, format!("a face needs at least 3 corners, found {}", args.len())));
                }
                let mut corners = Vec::with_capacity(args.len());
                for token in &args {
                    let mut parts = token.split('/');
                    let resolve =
                        |part: Option<&str>, count: usize, what: &str| -> Result<Option<usize>, ImportError> {
                            let Some(part) = part.filter(|p| !p.is_empty()) else { return Ok(None) };
                            let index: i64 =
                                part.parse().map_err(|_| error(token, format!("`{part}` is not a {what} index")))?;
                            let resolved = if index > 0 { index - 1 } else { count as i64 + index };
                            if index == 0 || resolved < 0 || resolved >= count as i64 {
                                return Err(error(
                                    token,
                                    format!("{what} index {index} is out of range: {count} defined so far"),
                                ));
                            }
                            Ok(Some(resolved as usize))
                        };
                    let v = resolve(parts.next(), positions.len(), "vertex")?
                        .ok_or_else(|| error(token, "a face corner needs a vertex index".to_string()))?;
                    let t = resolve(parts.next(), texcoords.len(), "texture coordinate")?;
                    if parts.clone().count() > 1 {
                        return Err(error(token, format!("`{token}` has more than three indices")));
                    }
                    match t {
                        Some(t) => {
                            corners_with_uv.0 += 1;
                            let uv = texcoords[t];
                            match uv_of[v] {
                                Some(existing) if existing != uv => {
                                    return Err(error(
                                        token,
                                        format!(
                                        "vertex {} has two different texture coordinates; one per vertex is supported",
                                        v + 1
                                    ),
                                    ))
                                }
                                _ => uv_of[v] = Some(uv),
                            }
                        }
                        None => corners_with_uv.1 += 1,
                    }
                    corners.push(v as u32);
                }
                let part = match group_part {
                    Some(part) => part,
                    None => {
                        let next = groups.len();
                        let part = *group_of.entry(group.clone()).or_insert(next);
                        if part == next {
                            Limits::check(next + 1, MAX_PARTS, "the OBJ's groups", "parts")?;
                            groups.push((group.clone(), Vec::new()));
                        }
                        group_part = Some(part);
                        part
                    }
                };
                for i in 1..corners.len() - 1 {
                    groups[part].1.push(triangles.len() as u32);
                    triangles.push([corners[0], corners[i], corners[i + 1]]);
                }
                Limits::check(triangles.len(), limits.max_vertices.saturating_mul(2), "the mesh", "triangles")?;
            }
            "g" => {
                let name = if args.is_empty() { "default".to_string() } else { args.join(" ") };
                if name.len() > MAX_PART_NAME_BYTES {
                    return Err(error(
                        keyword,
                        format!("the group's name has {} bytes, more than {MAX_PART_NAME_BYTES}", name.len()),
                    ));
                }
                grouped = true;
                group = name;
                group_part = None;
            }
            other if OBJ_IGNORED.contains(&other) => {}
            other => return Err(error(other, format!("unknown statement `{other}`"))),
        }
    }
    let uvs = match corners_with_uv {
        (0, _) => None,
        (_, 0) => Some(uv_of.iter().map(|uv| uv.unwrap_or([0.0, 0.0])).collect()),
        _ => {
            return Err(ImportError::TextureCoordinates {
                message: "some face corners have texture coordinates and others do not".to_string(),
            })
        }
    };
    let mesh = Mesh::new(positions, triangles)?;
    let puppet = grouped.then(|| Puppet {
        parts: groups
            .into_iter()
            .enumerate()
            .map(|(depth, (name, triangles))| Part { name, triangles, depth: depth as i32 })
            .collect(),
        joints: Vec::new(),
    });
    Ok(MeshFile { mesh, uvs, stiffness: None, puppet })
}

/// The names a puppet's parts take as OBJ groups (`g name`), in the parts' order: each on
/// one line and one name, as OBJ's rules ask (white space, control characters, `#` and `\`
/// become `_`), an empty name becomes `Part N` (N its place, from 1), and names made the
/// same get `_2`, `_3`, ..., each within [`MAX_PART_NAME_BYTES`], so that each part reads
/// back as a group of its own.
///
/// ```
/// use akap::deform::Part;
/// use akap::import::mesh_file::obj_group_names;
/// let part = |name: &str| Part { name: name.into(), triangles: vec![], depth: 0 };
/// let names = obj_group_names(&[part("left arm"), part("left\tarm"), part(" "), part("")]);
/// assert_eq!(names, ["left_arm", "left_arm_2", "_", "Part_4"]);
/// ```
pub fn obj_group_names(parts: &[Part]) -> Vec<String> {
    let mut taken: std::collections::HashSet<String> = std::collections::HashSet::new();
    let mut names = Vec::with_capacity(parts.len());
    for (p, part) in parts.iter().enumerate() {
        let clean: String = part
            .name
            .chars()
            .map(|c| if c.is_whitespace() || c.is_control() || c == '#' || c == '\\' { '_' } else { c })
            .collect();
        let base = if clean.is_empty() { format!("Part_{}", p + 1) } else { clean };
        let mut name = truncate(&base, MAX_PART_NAME_BYTES).to_string();
        let mut k = 2;
        while taken.contains(&name) {
            let suffix = format!("_{k}");
            name = format!("{}{suffix}", truncate(&base, MAX_PART_NAME_BYTES - suffix.len()));
            k += 1;
        }
        taken.insert(name.clone());
        names.push(name);
    }
    names
}

/// The longest start of `text` of at most `bytes` bytes that ends on a character.
fn truncate(text: &str, bytes: usize) -> &str {
    let mut end = bytes.min(text.len());
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    &text[..end]
}

/// Writes a Wavefront OBJ: `v x y 0` per vertex, `vt u v` per vertex when `uvs` are given
/// (then faces are `f a/a b/b c/c`), and one `f` per triangle. Numbers are in their shortest
/// exact form, in exponent form outside 1e-6 to 1e21 (`1e-300`, not 300 zeros). Refuses,
/// like [`read_obj`] with the same `limits`, a mesh with more vertices or triangles than
/// they allow or a text longer than `max_bytes`.
///
/// With a puppet, its parts are written as groups, back to front (by depth, parts of the
/// same depth in their order): `g name` ([`obj_group_names`]), then the part's faces in
/// its order, so that [`read_obj`] reads the same parts back, in depth order, with the
/// triangles renumbered in the order written (the same numbers when each part's triangles
/// follow the part behind it's, as an imported puppet's do). Its joints are not written:
/// OBJ has no place for them (write JSON to keep them).
///
/// ```
/// use akap::import::{mesh_file::{read_obj, write_obj}, ImportError, Limits};
/// let mesh = akap::Mesh::new(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1e-300]], vec![[0, 1, 2]])?;
/// let text = write_obj(&mesh, None, None, &Limits::default())?;
/// assert_eq!(text, "# akap mesh: 3 vertices, 1 triangles\nv 0 0 0\nv 1 0 0\nv 0 1e-300 0\nf 1 2 3\n");
/// assert_eq!(read_obj(&text, &Limits::default())?.mesh, mesh);
/// let small = Limits { max_bytes: 40, ..Limits::default() };
/// assert!(matches!(write_obj(&mesh, None, None, &small), Err(ImportError::TooLarge { .. })));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_obj(
    mesh: &Mesh,
    uvs: Option<&[Point]>,
    puppet: Option<&Puppet>,
    limits: &Limits,
) -> Result<String, ImportError> {
    write_obj_pose(mesh.positions(), mesh.triangles(), uvs, puppet, limits)
}

/// Writes `triangles` at `positions` (a pose of a mesh) as [`write_obj`] writes a mesh,
/// checking only what a file needs ([`Mesh::check_arrays`], and for a puppet
/// [`Puppet::check_indices`]): a pose with flipped or collapsed triangles is written as it
/// is.
pub fn write_obj_pose(
    positions: &[Point],
    triangles: &[[u32; 3]],
    uvs: Option<&[Point]>,
    puppet: Option<&Puppet>,
    limits: &Limits,
) -> Result<String, ImportError> {
    check_writable(positions, triangles, uvs, limits)?;
    if let Some(puppet) = puppet {
        check_puppet_indices(puppet, triangles.len(), limits)?;
    }
    let mut out = String::new();
    let _ = writeln!(out, "# akap mesh: {} vertices, {} triangles", positions.len(), triangles.len());
    for p in positions {
        let _ = writeln!(out, "v {} {} 0", Number(p[0]), Number(p[1]));
    }
    for t in uvs.unwrap_or(&[]) {
        let _ = writeln!(out, "vt {} {}", Number(t[0]), Number(t[1]));
    }
    let face = |out: &mut String, t: &[u32; 3]| {
        let [a, b, c] = t.map(|i| i + 1);
        if uvs.is_some() {
            let _ = writeln!(out, "f {a}/{a} {b}/{b} {c}/{c}");
        } else {
            let _ = writeln!(out, "f {a} {b} {c}");
        }
    };
    match puppet {
        None => triangles.iter().for_each(|t| face(&mut out, t)),
        Some(puppet) => {
            let names = obj_group_names(&puppet.parts);
            let mut order: Vec<usize> = (0..puppet.parts.len()).collect();
            order.sort_by_key(|&p| puppet.parts[p].depth);
            for p in order {
                let _ = writeln!(out, "g {}", names[p]);
                puppet.parts[p].triangles.iter().for_each(|&t| face(&mut out, &triangles[t as usize]));
            }
        }
    }
    check_written(out, limits, "the OBJ text")
}
