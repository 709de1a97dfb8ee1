//! JavaScript bindings (wasm32 only): the one module that touches wasm-bindgen and js-sys.
//!
//! Arrays cross as typed arrays: positions as `Float64Array` with x and y interleaved,
//! triangles as `Uint32Array` index triples. Every error becomes a JavaScript `Error` with
//! the message of the Rust error; nothing here panics on bad input. The TypeScript wrapper
//! in `www/src/` gives these functions their public, documented shape.

use js_sys::{Array, Float64Array, Object, Reflect};
use serde::Deserialize;
use wasm_bindgen::prelude::*;

use crate::deform::{ArapOptions, Deform, DeformerOptions, Integrator, Method, MethodOptions};
use crate::mesh::Mesh;
use crate::outline::Outline;
use crate::shapes;
use crate::triangulate::{triangulate, TriangulationOptions};

/// A validated triangle mesh.
#[wasm_bindgen(js_name = Mesh)]
pub struct JsMesh {
    mesh: Mesh,
}

#[wasm_bindgen(js_class = Mesh)]
impl JsMesh {
    /// Validates xy-interleaved positions and counter-clockwise index triples.
    #[wasm_bindgen(constructor)]
    pub fn new(positions: &[f64], triangles: &[u32]) -> Result<JsMesh, JsError> {
        Ok(Self { mesh: Mesh::from_flat(positions, triangles).map_err(to_js)? })
    }

    /// Number of vertices.
    #[wasm_bindgen(getter, js_name = vertexCount)]
    pub fn vertex_count(&self) -> usize {
        self.mesh.vertex_count()
    }

    /// Number of triangles.
    #[wasm_bindgen(getter, js_name = triangleCount)]
    pub fn triangle_count(&self) -> usize {
        self.mesh.triangle_count()
    }

    /// A copy of the positions, x and y interleaved.
    pub fn positions(&self) -> Vec<f64> {
        self.mesh.positions().iter().flatten().copied().collect()
    }

    /// A copy of the triangles, three indices each.
    pub fn triangles(&self) -> Vec<u32> {
        self.mesh.triangles().iter().flatten().copied().collect()
    }

    /// Boundary edges as index pairs, oriented with the shape on their left.
    #[wasm_bindgen(js_name = boundaryEdges)]
    pub fn boundary_edges(&self) -> Vec<u32> {
        self.mesh.boundary_edges().iter().flatten().copied().collect()
    }

    /// Boundary vertices, ascending.
    #[wasm_bindgen(js_name = boundaryVertices)]
    pub fn boundary_vertices(&self) -> Vec<u32> {
        self.mesh.boundary_vertices().collect()
    }

    /// The vertices sharing an edge with `vertex`, ascending.
    pub fn neighbors(&self, vertex: u32) -> Result<Vec<u32>, JsError> {
        let v = vertex as usize;
        if v >= self.mesh.vertex_count() {
            return Err(JsError::new(&format!(
                "vertex {vertex} is out of range: the mesh has {} vertices",
                self.mesh.vertex_count()
            )));
        }
        Ok(self.mesh.neighbors(v).to_vec())
    }

    /// Total area of the triangles.
    pub fn area(&self) -> f64 {
        self.mesh.area()
    }
}

/// Triangulation options as JavaScript passes them; every field optional.
#[derive(Deserialize, Default)]
#[serde(rename_all = "camelCase")]
struct JsTriangulationOptions {
    max_area: Option<f64>,
    target_edge_length: Option<f64>,
    min_angle: Option<f64>,
    max_vertices: Option<f64>,
}

impl JsTriangulationOptions {
    const NAMES: [&'static str; 4] = ["maxArea", "targetEdgeLength", "minAngle", "maxVertices"];

    fn parse(value: JsValue) -> Result<TriangulationOptions, JsError> {
        let given: Self = if value.is_undefined() || value.is_null() {
            Self::default()
        } else {
            // serde-wasm-bindgen reads only the fields it knows, so a misspelt option
            // would pass silently: check the keys here.
            if let Some(object) = value.dyn_ref::<Object>() {
                for key in Object::keys(object).iter() {
                    let key = key.as_string().unwrap_or_default();
                    if !Self::NAMES.contains(&key.as_str()) {
                        return Err(JsError::new(&format!(
                            "unknown triangulation option `{key}`; the options are {}",
                            Self::NAMES.join(", ")
                        )));
                    }
                }
            }
            serde_wasm_bindgen::from_value(value)
                .map_err(|e| JsError::new(&format!("invalid triangulation options: {e}")))?
        };
        let mut options = TriangulationOptions {
            max_area: given.max_area,
            target_edge_length: given.target_edge_length,
            ..TriangulationOptions::default()
        };
        if let Some(angle) = given.min_angle {
            options.min_angle_degrees = angle;
        }
        if let Some(count) = given.max_vertices {
            if !(count.is_finite() && count.fract() == 0.0 && count >= 0.0) {
                return Err(JsError::new(&format!("option maxVertices is {count}, expected a whole number")));
            }
            options.max_vertices = count.min(usize::MAX as f64) as usize;
        }
        Ok(options)
    }
}

/// Triangulates an outline: `outer` xy-interleaved, `holes` an array of the same (or
/// undefined), `options` `{ maxArea?, targetEdgeLength?, minAngle?, maxVertices? }`.
#[wasm_bindgen]
pub fn triangulate_outline(outer: &[f64], holes: JsValue, options: JsValue) -> Result<JsMesh, JsError> {
    let options = JsTriangulationOptions::parse(options)?;
    let holes = read_holes(holes)?;
    let outline = Outline::from_flat(outer, &holes).map_err(to_js)?;
    let mesh = triangulate(&outline, &options).map_err(to_js)?;
    Ok(JsMesh { mesh })
}

/// Reads an optional array of Float64Arrays (or arrays of numbers).
fn read_holes(holes: JsValue) -> Result<Vec<Vec<f64>>, JsError> {
    if holes.is_undefined() || holes.is_null() {
        return Ok(Vec::new());
    }
    let Some(list) = holes.dyn_ref::<Array>() else {
        return Err(JsError::new("holes must be an array of coordinate arrays"));
    };
    list.iter()
        .enumerate()
        .map(|(k, hole)| {
            if let Some(typed) = hole.dyn_ref::<Float64Array>() {
                Ok(typed.to_vec())
            } else if Array::is_array(&hole) {
                Ok(Float64Array::new(&hole).to_vec())
            } else {
                Err(JsError::new(&format!("hole {k} must be a Float64Array or an array of numbers")))
            }
        })
        .collect()
}

/// The built-in default shape, `{ outer: Float64Array, holes: Float64Array[] }`.
#[wasm_bindgen(js_name = defaultShape)]
pub fn default_shape() -> Result<Object, JsValue> {
    outline_object(&shapes::gingerbread())
}

/// Names of the built-in shapes; the first is the default.
#[wasm_bindgen(js_name = builtinShapes)]
pub fn builtin_shapes() -> Array {
    shapes::NAMES.iter().map(|&name| JsValue::from_str(name)).collect()
}

/// A built-in shape by name, `{ outer, holes }` as for `defaultShape`.
#[wasm_bindgen(js_name = builtinShape)]
pub fn builtin_shape(name: &str) -> Result<Object, JsValue> {
    let outline = shapes::by_name(name).ok_or_else(|| {
        JsError::new(&format!("there is no built-in shape `{name}`; the shapes are {}", shapes::NAMES.join(", ")))
    })?;
    outline_object(&outline)
}

fn outline_object(outline: &Outline) -> Result<Object, JsValue> {
    let flat = |ring: &[[f64; 2]]| Float64Array::from(ring.iter().flatten().copied().collect::<Vec<f64>>().as_slice());
    let holes: Array = outline.holes.iter().map(|h| flat(h)).collect();
    let object = Object::new();
    Reflect::set(&object, &"outer".into(), &flat(&outline.outer))?;
    Reflect::set(&object, &"holes".into(), &holes)?;
    Ok(object)
}

/// A deformer for one mesh: AKAP (`crate::deform::Deformer`) or ARAP
/// (`crate::deform::ArapDeformer`), chosen by the `method` option.
#[wasm_bindgen(js_name = Deformer)]
pub struct JsDeformer {
    inner: Box<dyn Deform>,
}

#[wasm_bindgen(js_class = Deformer)]
impl JsDeformer {
    /// Validates the mesh (xy-interleaved positions, counter-clockwise index triples) and
    /// prepares the solver. `options`: `{ method?: "akap" | "arap", lambda?: number,
    /// dirichlet?: boolean, integrator?: "spiral" | "linear", iterations?: number }`
    /// (the last for ARAP, the three before it for AKAP).
    #[wasm_bindgen(constructor)]
    pub fn new(positions: &[f64], triangles: &[u32], options: JsValue) -> Result<JsDeformer, JsError> {
        let options = parse_deformer_options(options, MethodOptions::default())?;
        let mesh = Mesh::from_flat(positions, triangles).map_err(to_js)?;
        let mut inner = options.build(mesh).map_err(to_js)?;
        inner.set_clock(performance_now);
        Ok(Self { inner })
    }

    /// Changes some options; the others keep their values. The method cannot change.
    #[wasm_bindgen(js_name = setOptions)]
    pub fn set_options(&mut self, options: JsValue) -> Result<(), JsError> {
        let options = parse_deformer_options(options, self.inner.method_options())?;
        self.inner.set_method_options(options).map_err(to_js)
    }

    /// `"akap"` or `"arap"`.
    #[wasm_bindgen(getter)]
    pub fn method(&self) -> String {
        self.inner.method_options().method().name().to_owned()
    }

    /// One handle on each of these vertices (replacing the handles).
    #[wasm_bindgen(js_name = setHandles)]
    pub fn set_handles(&mut self, vertices: &[u32]) -> Result<(), JsError> {
        self.inner.set_handle_vertices(vertices).map_err(to_js)
    }

    /// Handles at points in triangles: triangle indices and three barycentric coordinates
    /// per point (replacing the handles).
    #[wasm_bindgen(js_name = setHandlePoints)]
    pub fn set_handle_points(&mut self, triangles: &[u32], barycentric: &[f64]) -> Result<(), JsError> {
        if barycentric.len() != 3 * triangles.len() {
            return Err(JsError::new(&format!(
                "barycentric has length {}, expected 3 per triangle ({})",
                barycentric.len(),
                3 * triangles.len()
            )));
        }
        let (weights, _) = barycentric.as_chunks::<3>();
        self.inner.set_handle_points(triangles, weights).map_err(to_js)
    }

    /// One step with two velocity components per handle, in handle order.
    pub fn step(&mut self, velocities: &[f64]) -> Result<(), JsError> {
        let (pairs, rest) = velocities.as_chunks::<2>();
        if !rest.is_empty() {
            return Err(JsError::new(&format!(
                "velocities has length {}, expected 2 per handle ({})",
                velocities.len(),
                2 * self.inner.handle_count()
            )));
        }
        self.inner.step(pairs).map_err(to_js)
    }

    /// A copy of the current positions, x and y interleaved.
    pub fn positions(&self) -> Vec<f64> {
        self.inner.positions().iter().flatten().copied().collect()
    }

    /// Where the current positions live in wasm memory: the byte offset of `2 * vertexCount`
    /// f64 values, x and y interleaved. JavaScript wraps it in a `Float64Array` over
    /// `memory.buffer` (no copy). The address changes with every step (the deformer swaps
    /// two buffers), and a view detaches when the memory grows: ask again each frame.
    #[wasm_bindgen(js_name = positionsPointer)]
    pub fn positions_pointer(&self) -> usize {
        self.inner.positions().as_ptr() as usize
    }

    /// Puts the mesh into the given pose (xy-interleaved, length `2 * vertexCount`); handles stay.
    #[wasm_bindgen(js_name = setPositions)]
    pub fn set_positions(&mut self, positions: &[f64]) -> Result<(), JsError> {
        let (pairs, rest) = positions.as_chunks::<2>();
        if !rest.is_empty() {
            return Err(JsError::new(&format!(
                "positions has length {}, expected {}",
                positions.len(),
                2 * self.inner.mesh().vertex_count()
            )));
        }
        self.inner.set_positions(pairs).map_err(to_js)
    }

    /// The last velocity field after the Dirichlet step (`U_opt`; ARAP: the last step's
    /// displacement), interleaved.
    pub fn field(&self) -> Vec<f64> {
        self.inner.field().iter().flatten().copied().collect()
    }

    /// The last velocity field after the soft-constraint step (`U0`; ARAP: the last
    /// step's displacement), interleaved.
    #[wasm_bindgen(js_name = softField)]
    pub fn soft_field(&self) -> Vec<f64> {
        self.inner.soft_field().iter().flatten().copied().collect()
    }

    /// Current positions of the handle points, interleaved.
    #[wasm_bindgen(js_name = handlePositions)]
    pub fn handle_positions(&self) -> Vec<f64> {
        self.inner.handle_positions().iter().flatten().copied().collect()
    }

    /// Number of handles.
    #[wasm_bindgen(getter, js_name = handleCount)]
    pub fn handle_count(&self) -> usize {
        self.inner.handle_count()
    }

    /// Number of vertices.
    #[wasm_bindgen(getter, js_name = vertexCount)]
    pub fn vertex_count(&self) -> usize {
        self.inner.mesh().vertex_count()
    }

    /// `{ areaDistortion, angleDistortion, flipped }` of the current pose.
    pub fn metrics(&self) -> Result<Object, JsValue> {
        let m = self.inner.metrics();
        object(&[
            ("areaDistortion", m.area_distortion.into()),
            ("angleDistortion", m.angle_distortion.into()),
            ("flipped", (m.flipped as f64).into()),
        ])
    }

    /// `{ assembly, factorisation, solve, integration }`: milliseconds of the last step.
    pub fn timings(&self) -> Result<Object, JsValue> {
        let t = self.inner.timings();
        object(&[
            ("assembly", t.assembly.into()),
            ("factorisation", t.factorisation.into()),
            ("solve", t.solve.into()),
            ("integration", t.integration.into()),
        ])
    }

    /// Back to the rest pose (handles stay).
    pub fn reset(&mut self) {
        self.inner.reset();
    }
}

fn object(entries: &[(&str, JsValue)]) -> Result<Object, JsValue> {
    let object = Object::new();
    for (key, value) in entries {
        Reflect::set(&object, &JsValue::from_str(key), value)?;
    }
    Ok(object)
}

/// Reads `{ method?, lambda?, dirichlet?, integrator?, iterations? }` over `base`, refusing
/// unknown keys and options of the other method. A different `method` starts from that
/// method's defaults.
fn parse_deformer_options(value: JsValue, base: MethodOptions) -> Result<MethodOptions, JsError> {
    const NAMES: [&str; 5] = ["method", "lambda", "dirichlet", "integrator", "iterations"];
    if value.is_undefined() || value.is_null() {
        return Ok(base);
    }
    let Some(object) = value.dyn_ref::<Object>() else {
        return Err(JsError::new("deformer options must be an object"));
    };
    let get = |key: &str| Reflect::get(object, &JsValue::from_str(key)).map_err(|_| JsError::new("unreadable option"));
    let keys: Vec<String> = Object::keys(object).iter().map(|k| k.as_string().unwrap_or_default()).collect();
    let mut options = base;
    if keys.iter().any(|k| k == "method") {
        let method = match get("method")?.as_string().as_deref() {
            Some("akap") => Method::Akap,
            Some("arap") => Method::Arap,
            _ => return Err(JsError::new("option method must be \"akap\" or \"arap\"")),
        };
        if method != base.method() {
            options = match method {
                Method::Akap => MethodOptions::Akap(DeformerOptions::default()),
                Method::Arap => MethodOptions::Arap(ArapOptions::default()),
            };
        }
    }
    let only = |name: &str, method: &str| JsError::new(&format!("option {name} applies to method \"{method}\" only"));
    for key in keys.iter().filter(|k| *k != "method") {
        let field = get(key)?;
        match (key.as_str(), &mut options) {
            ("lambda", MethodOptions::Akap(o)) => {
                o.lambda = field.as_f64().ok_or_else(|| JsError::new("option lambda must be a number"))?;
            }
            ("dirichlet", MethodOptions::Akap(o)) => {
                o.dirichlet = field.as_bool().ok_or_else(|| JsError::new("option dirichlet must be true or false"))?;
            }
            ("integrator", MethodOptions::Akap(o)) => {
                o.integrator = match field.as_string().as_deref() {
                    Some("spiral") => Integrator::Spiral,
                    Some("linear") => Integrator::Linear,
                    _ => return Err(JsError::new("option integrator must be \"spiral\" or \"linear\"")),
                };
            }
            ("iterations", MethodOptions::Arap(o)) => {
                o.iterations = match field.as_f64() {
                    Some(n) if n.fract() == 0.0 && (1.0..=1e6).contains(&n) => n as usize,
                    _ => return Err(JsError::new("option iterations must be a whole number from 1 to 1000000")),
                };
            }
            ("lambda" | "dirichlet" | "integrator", _) => return Err(only(key, "akap")),
            ("iterations", _) => return Err(only(key, "arap")),
            (other, _) => {
                return Err(JsError::new(&format!(
                    "unknown deformer option `{other}`; the options are {}",
                    NAMES.join(", ")
                )))
            }
        }
    }
    Ok(options)
}

thread_local! {
    static PERFORMANCE: Option<(JsValue, js_sys::Function)> = {
        let performance = Reflect::get(&js_sys::global(), &JsValue::from_str("performance")).ok();
        performance.and_then(|p| {
            let now = Reflect::get(&p, &JsValue::from_str("now")).ok()?.dyn_into::<js_sys::Function>().ok()?;
            Some((p, now))
        })
    };
}

/// `performance.now()` in milliseconds, or 0 where there is no `performance`.
fn performance_now() -> f64 {
    PERFORMANCE
        .with(|p| p.as_ref().and_then(|(this, now)| now.call0(this).ok()).and_then(|v| v.as_f64()).unwrap_or(0.0))
}

fn to_js(error: impl std::fmt::Display) -> JsError {
    JsError::new(&error.to_string())
}
