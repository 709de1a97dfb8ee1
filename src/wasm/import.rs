//! Shapes from files (`crate::import`): SVG documents, images, mesh files; mesh writers;
//! texture coordinates; `PointMapper`.

use js_sys::Array;
use wasm_bindgen::prelude::*;

use super::mesh::{read_mesh, read_positions, JsMesh};
use super::read::{self, entries};
use super::{flat, limits, max_coordinates, max_indices, object, outlines_to_js, pairs, to_js};
use crate::import::mesh_file::{self, MeshFile};
use crate::import::raster::{self, MaskMode, TraceOptions};
use crate::import::svg::{self as svg_import, SvgOptions};
use crate::import::vector::FillRule;
use crate::import::warp::{self, PointMapper};
use crate::mesh::MeshError;

fn parse_svg_options(value: &JsValue) -> Result<SvgOptions, JsError> {
    let mut options = SvgOptions::default();
    for (key, field) in entries(value, "SVG import", &["tolerance", "minArea", "maxPoints", "maxBytes"])? {
        let what = format!("option {key}");
        match key.as_str() {
            "tolerance" => options.tolerance = Some(read::number(&field, &what)?),
            "minArea" => options.min_area = read::number(&field, &what)?,
            "maxPoints" => options.limits.max_points = read::count(&field, &what, usize::MAX)?,
            _ => options.limits.max_bytes = read::count(&field, &what, usize::MAX)?,
        }
    }
    Ok(options)
}

fn parse_trace_options(value: &JsValue) -> Result<TraceOptions, JsError> {
    const NAMES: [&str; 7] =
        ["mode", "alphaThreshold", "colourThreshold", "tolerance", "minArea", "maxPoints", "maxPixels"];
    let mut options = TraceOptions::default();
    for (key, field) in entries(value, "image tracing", &NAMES)? {
        let what = format!("option {key}");
        match key.as_str() {
            "mode" => {
                options.mode = match field.as_string().as_deref() {
                    Some("auto") => MaskMode::Auto,
                    Some("alpha") => MaskMode::Alpha,
                    Some("colour") => MaskMode::Colour,
                    _ => return Err(JsError::new("option mode must be \"auto\", \"alpha\" or \"colour\"")),
                }
            }
            "alphaThreshold" => options.alpha_threshold = read::number(&field, &what)?,
            "colourThreshold" => options.colour_threshold = read::number(&field, &what)?,
            "tolerance" => options.tolerance = read::number(&field, &what)?,
            "minArea" => options.min_area = read::number(&field, &what)?,
            "maxPoints" => options.limits.max_points = read::count(&field, &what, usize::MAX)?,
            _ => options.limits.max_pixels = read::count(&field, &what, usize::MAX)?,
        }
    }
    Ok(options)
}

/// An SVG document argument (a string), within the byte limit of `options`.
fn svg_text(text: &JsValue, options: &SvgOptions) -> Result<String, JsError> {
    read::string(text, "the SVG text", options.limits.max_bytes)
}

/// The filled region of an SVG document as outlines, largest part first. `options`:
/// `{ tolerance?, minArea?, maxPoints?, maxBytes? }`.
#[wasm_bindgen]
pub fn import_svg(text: JsValue, options: JsValue) -> Result<Array, JsError> {
    let options = parse_svg_options(&options)?;
    let shape = svg_import::import_svg(&svg_text(&text, &options)?, &options).map_err(to_js)?;
    outlines_to_js(&shape.outlines)
}

/// The filled elements' paths in output coordinates:
/// `[{ element, commands: "MLQCZ"-letters, points: Float64Array, fillRule, fill }]`, where
/// `fill` is `"rgba(R, G, B, A)"` (channels 0-255, alpha 0-1 with every opacity folded in)
/// or `undefined` when the importer does not know the colour (a gradient, say).
#[wasm_bindgen]
pub fn import_svg_paths(text: JsValue, options: JsValue) -> Result<Array, JsError> {
    let options = parse_svg_options(&options)?;
    let shape = svg_import::import_svg(&svg_text(&text, &options)?, &options).map_err(to_js)?;
    let list = Array::new();
    for p in &shape.paths {
        let commands: String = p.path.verbs.iter().map(|v| v.letter()).collect();
        let rule = match p.fill_rule {
            FillRule::NonZero => "nonzero",
            FillRule::EvenOdd => "evenodd",
        };
        let entry = object(&[
            ("element", p.element.to_string().into()),
            ("commands", commands.into()),
            ("points", flat(&p.path.points).into()),
            ("fillRule", rule.into()),
            ("fill", p.fill.map_or(JsValue::UNDEFINED, |c| css_colour(c).into())),
        ])
        .map_err(|_| JsError::new("could not build a path object"))?;
        list.push(&entry);
    }
    Ok(list)
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
pub fn trace_image(rgba: JsValue, width: JsValue, height: JsValue, options: JsValue) -> Result<Array, JsError> {
    let options = parse_trace_options(&options)?;
    let pixels = options.limits.max_pixels;
    let width = read::count(&width, "width", pixels)?;
    let height = read::count(&height, "height", pixels)?;
    let rgba = read::bytes(&rgba, "the pixels", 4 * pixels)?;
    let outlines = raster::trace_image(&rgba, width, height, &options).map_err(to_js)?;
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
}

/// Reads a Wavefront OBJ mesh (xy plane) from a string.
#[wasm_bindgen]
pub fn mesh_from_obj(text: JsValue) -> Result<JsMeshFile, JsError> {
    let limits = limits();
    let text = read::string(&text, "the OBJ text", limits.max_bytes)?;
    Ok(JsMeshFile { file: mesh_file::read_obj(&text, &limits).map_err(to_js)? })
}

/// Reads a mesh in our JSON format from a string.
#[wasm_bindgen]
pub fn mesh_from_json(text: JsValue) -> Result<JsMeshFile, JsError> {
    let limits = limits();
    let text = read::string(&text, "the JSON text", limits.max_bytes)?;
    Ok(JsMeshFile { file: mesh_file::read_json(&text, &limits).map_err(to_js)? })
}

/// A mesh or a pose of one, and its optional texture coordinates, as the writers take them.
struct ToWrite {
    positions: Vec<[f64; 2]>,
    triangles: Vec<[u32; 3]>,
    uvs: Option<Vec<[f64; 2]>>,
}

fn to_write(positions: &JsValue, triangles: &JsValue, uvs: &JsValue) -> Result<ToWrite, JsError> {
    let positions = pairs(&read_positions(positions)?, "positions")?;
    let flat = read::uint32s(triangles, "triangles", max_indices())?;
    let (triangles, rest) = flat.as_chunks::<3>();
    if !rest.is_empty() {
        return Err(to_js(MeshError::TrianglesLength { len: flat.len() }));
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
pub fn mesh_to_obj(positions: JsValue, triangles: JsValue, uvs: JsValue) -> Result<String, JsError> {
    let m = to_write(&positions, &triangles, &uvs)?;
    mesh_file::write_obj_pose(&m.positions, &m.triangles, m.uvs.as_deref(), &limits()).map_err(to_js)
}

/// Writes a mesh, or a pose of one (flipped triangles as they are), in our JSON format.
#[wasm_bindgen]
pub fn mesh_to_json(positions: JsValue, triangles: JsValue, uvs: JsValue) -> Result<String, JsError> {
    let m = to_write(&positions, &triangles, &uvs)?;
    mesh_file::write_json_pose(&m.positions, &m.triangles, m.uvs.as_deref(), &limits()).map_err(to_js)
}

/// Texture coordinates (u, v interleaved) of positions (`Float64Array`) in a traced
/// image's pixel frame.
#[wasm_bindgen]
pub fn texture_coordinates(positions: JsValue, width: JsValue, height: JsValue) -> Result<Vec<f64>, JsError> {
    let width = read::number(&width, "width")?;
    let height = read::number(&height, "height")?;
    let positions = read::float64s(&positions, "positions", max_coordinates())?;
    let points = pairs(&positions, "positions")?;
    Ok(warp::texture_coordinates(&points, width, height).map_err(to_js)?.into_iter().flatten().collect())
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
    pub fn new(positions: JsValue, triangles: JsValue, points: JsValue) -> Result<JsPointMapper, JsError> {
        let mesh = read_mesh(&positions, &triangles)?;
        let points = read::float64s(&points, "points", max_coordinates())?;
        Ok(Self { inner: PointMapper::new(&mesh, &pairs(&points, "points")?).map_err(to_js)? })
    }

    /// The points carried along to `deformed` (`Float64Array`, xy-interleaved, one pair per
    /// rest vertex).
    pub fn map(&self, deformed: JsValue) -> Result<Vec<f64>, JsError> {
        let deformed = read::float64s(&deformed, "deformed positions", max_coordinates())?;
        let pairs = pairs(&deformed, "deformed positions")?;
        Ok(self.inner.map(&pairs).map_err(to_js)?.into_iter().flatten().collect())
    }

    /// Number of points.
    #[wasm_bindgen(getter)]
    pub fn length(&self) -> usize {
        self.inner.len()
    }
}
