//! Shapes from files (`crate::import`): SVG documents, images, mesh files; mesh writers;
//! texture coordinates; `PointMapper`.

use js_sys::{Array, Object, Uint32Array};
use wasm_bindgen::prelude::*;

use super::error::BindingError;
use super::mesh::{read_mesh, read_positions, JsMesh};
use super::read::{self, Options};
use super::{flat, limits, max_coordinates, max_indices, object, outlines_to_js, pairs};
use crate::import::mesh_file::{self, MeshFile};
use crate::import::puppet::{self, ImportedPuppet, PuppetOptions, DEFAULT_PUPPET_VERTICES};
use crate::import::raster::{self, MaskMode, TraceOptions};
use crate::import::svg::{self as svg_import, Part, SvgOptions, SvgPath};
use crate::import::vector::{FillRule, VectorPath};
use crate::import::warp::{self, PointMapper};
use crate::mesh::MeshError;

/// The options of an SVG import.
const SVG_OPTIONS: [&str; 5] = ["tolerance", "minArea", "strokes", "maxPoints", "maxBytes"];

/// Reads `{ tolerance?, minArea?, strokes?, maxPoints?, maxBytes? }`.
fn parse_svg_options(value: &JsValue) -> Result<SvgOptions, BindingError> {
    svg_options(&Options::read(value, "SVG import", &SVG_OPTIONS)?)
}

/// The SVG import's options of those `given`.
fn svg_options(given: &Options) -> Result<SvgOptions, BindingError> {
    let mut options = SvgOptions::default();
    options.tolerance = given.number("tolerance")?.or(options.tolerance);
    options.min_area = given.number("minArea")?.unwrap_or(options.min_area);
    options.strokes = given.boolean("strokes")?.unwrap_or(options.strokes);
    options.limits.max_points = given.count("maxPoints", usize::MAX)?.unwrap_or(options.limits.max_points);
    options.limits.max_bytes = given.count("maxBytes", usize::MAX)?.unwrap_or(options.limits.max_bytes);
    Ok(options)
}

/// The options of image tracing.
const TRACE_OPTIONS: [&str; 7] =
    ["mode", "alphaThreshold", "colourThreshold", "tolerance", "minArea", "maxPoints", "maxPixels"];

/// Reads `{ mode?, alphaThreshold?, colourThreshold?, tolerance?, minArea?, maxPoints?,
/// maxPixels? }`.
fn parse_trace_options(value: &JsValue) -> Result<TraceOptions, BindingError> {
    trace_options(&Options::read(value, "image tracing", &TRACE_OPTIONS)?)
}

/// Image tracing's options of those `given`.
fn trace_options(given: &Options) -> Result<TraceOptions, BindingError> {
    let mut options = TraceOptions::default();
    let modes = [("auto", MaskMode::Auto), ("alpha", MaskMode::Alpha), ("colour", MaskMode::Colour)];
    options.mode = given.choice("mode", &modes)?.unwrap_or(options.mode);
    options.alpha_threshold = given.number("alphaThreshold")?.unwrap_or(options.alpha_threshold);
    options.colour_threshold = given.number("colourThreshold")?.unwrap_or(options.colour_threshold);
    options.tolerance = given.number("tolerance")?.unwrap_or(options.tolerance);
    options.min_area = given.number("minArea")?.unwrap_or(options.min_area);
    options.limits.max_points = given.count("maxPoints", usize::MAX)?.unwrap_or(options.limits.max_points);
    options.limits.max_pixels = given.count("maxPixels", usize::MAX)?.unwrap_or(options.limits.max_pixels);
    Ok(options)
}

/// An SVG document argument (a string), within the byte limit of `options`.
fn svg_text(text: &JsValue, options: &SvgOptions) -> Result<String, BindingError> {
    read::string(text, "the SVG text", options.limits.max_bytes)
}

/// The filled (and stroked) region of an SVG document as outlines, largest part first.
/// `options`: `{ tolerance?, minArea?, strokes?, maxPoints?, maxBytes? }`.
#[wasm_bindgen]
pub fn import_svg(text: JsValue, options: JsValue) -> Result<Array, BindingError> {
    let options = parse_svg_options(&options)?;
    let shape = svg_import::import_svg(&svg_text(&text, &options)?, &options)?;
    outlines_to_js(&shape.outlines)
}

/// The filled areas' paths in output coordinates, in drawing order: `[{ element, part:
/// "fill" | "stroke", commands: "MLQCZ"-letters, points: Float64Array, fillRule, fill }]`,
/// where a stroke is its outline, filled; `fill` is `"rgba(R, G, B, A)"` (channels 0-255,
/// alpha 0-1 with every opacity folded in) or `undefined` when the paint is a gradient or a
/// pattern.
#[wasm_bindgen]
pub fn import_svg_paths(text: JsValue, options: JsValue) -> Result<Array, BindingError> {
    let options = parse_svg_options(&options)?;
    let shape = svg_import::import_svg(&svg_text(&text, &options)?, &options)?;
    paths_to_js(&shape.paths)
}

/// Paths as [`import_svg_paths`] gives them: the one writer of them.
fn paths_to_js(paths: &[SvgPath]) -> Result<Array, BindingError> {
    let list = Array::new();
    for p in paths {
        let commands: String = p.path.verbs.iter().map(|v| v.letter()).collect();
        let rule = match p.fill_rule {
            FillRule::NonZero => "nonzero",
            FillRule::EvenOdd => "evenodd",
        };
        let entry = object(&[
            ("element", p.element.to_string().into()),
            ("part", if p.part == Part::Fill { "fill" } else { "stroke" }.into()),
            ("commands", commands.into()),
            ("points", flat(&p.path.points).into()),
            ("fillRule", rule.into()),
            ("fill", p.fill.map_or(JsValue::UNDEFINED, |c| css_colour(c).into())),
        ])?;
        list.push(&entry);
    }
    Ok(list)
}

/// Reads `{ tolerance?, minArea?, strokes?, maxPoints?, maxBytes?, vertices? }`.
fn parse_puppet_options(value: &JsValue) -> Result<PuppetOptions, BindingError> {
    const NAMES: [&str; 6] = ["tolerance", "minArea", "strokes", "maxPoints", "maxBytes", "vertices"];
    debug_assert!(SVG_OPTIONS.iter().all(|n| NAMES.contains(n)));
    let given = Options::read(value, "puppet import", &NAMES)?;
    let svg = svg_options(&given)?;
    let vertices = given.count("vertices", usize::MAX)?.unwrap_or(DEFAULT_PUPPET_VERTICES);
    Ok(PuppetOptions { svg, vertices })
}

/// A layered SVG document as a puppet, a sheet per layer, joined where layers overlap:
/// `{ positions: Float64Array, triangles: Uint32Array, parts: [{ name, triangles:
/// Uint32Array (indices of triangles), depth (larger in front), paths (each as
/// importSvgPaths gives them) }], joints: [{ point: [x, y], parts: [front, back] }],
/// skipped: string[] }`. `options`: those of [`import_svg`] and `vertices` (about how many
/// in all, default 3000).
#[wasm_bindgen(js_name = importPuppet)]
pub fn import_puppet(text: JsValue, options: JsValue) -> Result<Object, BindingError> {
    let options = parse_puppet_options(&options)?;
    let text = svg_text(&text, &options.svg)?;
    puppet_to_js(&puppet::import_puppet(&text, &options)?)
}

/// An image's separate opaque regions as a puppet, a part per region (no joints), in the
/// form [`import_puppet`] gives (parts' `paths` empty). `options`: those of
/// [`trace_image`] and `vertices` (about how many in all, default 3000).
#[wasm_bindgen(js_name = importImagePuppet)]
pub fn import_image_puppet(
    rgba: JsValue,
    width: JsValue,
    height: JsValue,
    options: JsValue,
) -> Result<Object, BindingError> {
    const NAMES: [&str; 8] =
        ["mode", "alphaThreshold", "colourThreshold", "tolerance", "minArea", "maxPoints", "maxPixels", "vertices"];
    debug_assert!(TRACE_OPTIONS.iter().all(|n| NAMES.contains(n)));
    let given = Options::read(&options, "image puppet", &NAMES)?;
    let trace = trace_options(&given)?;
    let vertices = given.count("vertices", usize::MAX)?.unwrap_or(DEFAULT_PUPPET_VERTICES);
    let pixels = trace.limits.max_pixels;
    let width = read::count(&width, "width", pixels)?;
    let height = read::count(&height, "height", pixels)?;
    let rgba = read::bytes(&rgba, "the pixels", 4 * pixels)?;
    puppet_to_js(&puppet::import_image_puppet(&rgba, width, height, &trace, vertices)?)
}

fn puppet_to_js(imported: &ImportedPuppet) -> Result<Object, BindingError> {
    let ImportedPuppet { mesh, puppet, art, skipped } = imported;
    let triangles: Vec<u32> = mesh.triangles().iter().flatten().copied().collect();
    let parts = Array::new();
    for (part, paths) in puppet.parts.iter().zip(art) {
        let entry = object(&[
            ("name", part.name.as_str().into()),
            ("triangles", Uint32Array::from(part.triangles.as_slice()).into()),
            ("depth", part.depth.into()),
            ("paths", paths_to_js(paths)?.into()),
        ])?;
        parts.push(&entry);
    }
    let joints = Array::new();
    for joint in &puppet.joints {
        let [x, y] = joint.point;
        let [front, back] = joint.parts;
        let point = Array::of2(&x.into(), &y.into());
        let pair = Array::of2(&(front as u32).into(), &(back as u32).into());
        let entry = object(&[("point", point.into()), ("parts", pair.into())])?;
        joints.push(&entry);
    }
    let skipped: Array = skipped.iter().map(|s| JsValue::from_str(s)).collect();
    object(&[
        ("positions", flat(mesh.positions()).into()),
        ("triangles", Uint32Array::from(triangles.as_slice()).into()),
        ("parts", parts.into()),
        ("joints", joints.into()),
        ("skipped", skipped.into()),
    ])
}

/// A fill colour as CSS writes it, `rgba(R, G, B, A)`: exact, and usable as it is by a
/// canvas, in SVG and in CSS.
fn css_colour(c: svg_import::FillColour) -> String {
    format!("rgba({}, {}, {}, {})", c.red, c.green, c.blue, c.alpha)
}

/// Traces the shape in RGBA pixels (`Uint8Array` or `Uint8ClampedArray`, rows from the
/// top) into outlines in pixel units, y up. `options`: `{ mode?, alphaThreshold?,
/// colourThreshold?, tolerance?, minArea?, maxPoints?, maxPixels? }`.
#[wasm_bindgen]
pub fn trace_image(rgba: JsValue, width: JsValue, height: JsValue, options: JsValue) -> Result<Array, BindingError> {
    let options = parse_trace_options(&options)?;
    let pixels = options.limits.max_pixels;
    let width = read::count(&width, "width", pixels)?;
    let height = read::count(&height, "height", pixels)?;
    let rgba = read::bytes(&rgba, "the pixels", 4 * pixels)?;
    let outlines = raster::trace_image(&rgba, width, height, &options)?;
    outlines_to_js(&outlines)
}

/// A mesh read from a file, with its texture coordinates if it has them.
#[wasm_bindgen(js_name = MeshFile)]
pub struct JsMeshFile {
    file: MeshFile,
}

#[wasm_bindgen(js_class = MeshFile)]
impl JsMeshFile {
    /// The validated mesh.
    pub fn mesh(&self) -> JsMesh {
        JsMesh { mesh: self.file.mesh.clone() }
    }

    /// Per-vertex texture coordinates, u and v interleaved, or undefined.
    pub fn uvs(&self) -> Option<Vec<f64>> {
        self.file.uvs.as_ref().map(|uvs| uvs.iter().flatten().copied().collect())
    }

    /// Per-triangle stiffness (JSON files only), or undefined.
    pub fn stiffness(&self) -> Option<Vec<f64>> {
        self.file.stiffness.clone()
    }
}

/// Reads a Wavefront OBJ mesh (xy plane) from a string.
#[wasm_bindgen]
pub fn mesh_from_obj(text: JsValue) -> Result<JsMeshFile, BindingError> {
    let limits = limits();
    let text = read::string(&text, "the OBJ text", limits.max_bytes)?;
    Ok(JsMeshFile { file: mesh_file::read_obj(&text, &limits)? })
}

/// Reads a mesh in our JSON format from a string.
#[wasm_bindgen]
pub fn mesh_from_json(text: JsValue) -> Result<JsMeshFile, BindingError> {
    let limits = limits();
    let text = read::string(&text, "the JSON text", limits.max_bytes)?;
    Ok(JsMeshFile { file: mesh_file::read_json(&text, &limits)? })
}

/// A mesh or a pose of one, and its optional texture coordinates, as the writers take them.
struct ToWrite {
    positions: Vec<[f64; 2]>,
    triangles: Vec<[u32; 3]>,
    uvs: Option<Vec<[f64; 2]>>,
}

fn to_write(positions: &JsValue, triangles: &JsValue, uvs: &JsValue) -> Result<ToWrite, BindingError> {
    let positions = pairs(&read_positions(positions)?, "positions")?;
    let flat = read::uint32s(triangles, "triangles", max_indices())?;
    let (triangles, rest) = flat.as_chunks::<3>();
    if !rest.is_empty() {
        return Err(MeshError::TrianglesLength { len: flat.len() }.into());
    }
    let uvs = if uvs.is_undefined() || uvs.is_null() {
        None
    } else {
        let flat = read::float64s(uvs, "uvs", max_coordinates())?;
        Some(pairs(&flat, "uvs")?)
    };
    Ok(ToWrite { positions, triangles: triangles.to_vec(), uvs })
}

/// Writes a mesh, or a pose of one (flipped triangles as they are), as Wavefront OBJ, with
/// `vt` lines when `uvs` (a `Float64Array`) are given.
#[wasm_bindgen]
pub fn mesh_to_obj(positions: JsValue, triangles: JsValue, uvs: JsValue) -> Result<String, BindingError> {
    let m = to_write(&positions, &triangles, &uvs)?;
    Ok(mesh_file::write_obj_pose(&m.positions, &m.triangles, m.uvs.as_deref(), &limits())?)
}

/// Writes a mesh, or a pose of one (flipped triangles as they are), in our JSON format,
/// with its `uvs` and per-triangle `stiffness` (`Float64Array`s) when given.
#[wasm_bindgen]
pub fn mesh_to_json(
    positions: JsValue,
    triangles: JsValue,
    uvs: JsValue,
    stiffness: JsValue,
) -> Result<String, BindingError> {
    let m = to_write(&positions, &triangles, &uvs)?;
    let stiffness = if stiffness.is_undefined() || stiffness.is_null() {
        None
    } else {
        Some(read::float64s(&stiffness, "stiffness", max_indices())?)
    };
    Ok(mesh_file::write_json_pose(&m.positions, &m.triangles, m.uvs.as_deref(), stiffness.as_deref(), &limits())?)
}

/// Texture coordinates (u, v interleaved) of positions (`Float64Array`) in a traced
/// image's pixel frame, in OBJ's convention (v up): see [`warp::texture_coordinates`].
#[wasm_bindgen]
pub fn texture_coordinates(positions: JsValue, width: JsValue, height: JsValue) -> Result<Vec<f64>, BindingError> {
    let width = read::number(&width, "width")?;
    let height = read::number(&height, "height")?;
    let positions = read::float64s(&positions, "positions", max_coordinates())?;
    let points = pairs(&positions, "positions")?;
    Ok(warp::texture_coordinates(&points, width, height)?.into_iter().flatten().collect())
}

/// Points located once in a rest mesh, then carried along to deformed positions.
#[wasm_bindgen(js_name = PointMapper)]
pub struct JsPointMapper {
    inner: PointMapper,
}

#[wasm_bindgen(js_class = PointMapper)]
impl JsPointMapper {
    /// Validates the rest mesh and locates the points (`Float64Array`, xy-interleaved) in it.
    #[wasm_bindgen(constructor)]
    pub fn new(positions: JsValue, triangles: JsValue, points: JsValue) -> Result<JsPointMapper, BindingError> {
        let mesh = read_mesh(&positions, &triangles)?;
        let points = read::float64s(&points, "points", max_coordinates())?;
        Ok(Self { inner: PointMapper::new(&mesh, &pairs(&points, "points")?)? })
    }

    /// The points carried along to `deformed` (`Float64Array`, xy-interleaved, one pair per
    /// rest vertex).
    pub fn map(&self, deformed: JsValue) -> Result<Vec<f64>, BindingError> {
        let deformed = read::float64s(&deformed, "deformed positions", max_coordinates())?;
        let pairs = pairs(&deformed, "deformed positions")?;
        Ok(self.inner.map(&pairs)?.into_iter().flatten().collect())
    }

    /// Number of points.
    #[wasm_bindgen(getter)]
    pub fn length(&self) -> usize {
        self.inner.len()
    }
}

/// SVG path data (absolute commands) for `commands` (a string of the letters M, L, Q, C, Z)
/// and their points (x and y interleaved), with y negated when `flip_y` is true (y-up
/// coordinates back to SVG's y-down ones): [`VectorPath::to_path_data`].
#[wasm_bindgen]
pub fn path_data(commands: JsValue, points: JsValue, flip_y: JsValue) -> Result<String, BindingError> {
    let commands = read::string(&commands, "commands", limits().max_bytes)?;
    let mut points = pairs(&read::float64s(&points, "points", 2 * limits().max_points)?, "points")?;
    if !points.iter().flatten().all(|x| x.is_finite()) {
        return Err(BindingError::argument("points holds a number that is not finite"));
    }
    let flip = match flip_y.as_bool() {
        Some(flip) => flip,
        None if flip_y.is_undefined() => false,
        None => return Err(read::type_error("flipY", "true or false", &flip_y)),
    };
    if flip {
        points.iter_mut().for_each(|p| p[1] = -p[1]);
    }
    let path = VectorPath::from_commands(&commands, points).map_err(BindingError::argument)?;
    Ok(path.to_path_data(&path.points))
}
