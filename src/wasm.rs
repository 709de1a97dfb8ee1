//! JavaScript bindings (wasm32 only): the one module that touches wasm-bindgen and js-sys.
//!
//! Arrays cross as typed arrays: positions as `Float64Array` with x and y interleaved,
//! triangles as `Uint32Array` index triples. Every error becomes a JavaScript `Error` with
//! the message of the Rust error; nothing here panics on bad input. The TypeScript wrapper
//! in `www/src/` gives these functions their public, documented shape.

use js_sys::{Array, Float64Array, Object, Reflect};
use serde::Deserialize;
use wasm_bindgen::prelude::*;

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
    let outline = shapes::gingerbread();
    let flat = |ring: &[[f64; 2]]| Float64Array::from(ring.iter().flatten().copied().collect::<Vec<f64>>().as_slice());
    let holes: Array = outline.holes.iter().map(|h| flat(h)).collect();
    let object = Object::new();
    Reflect::set(&object, &"outer".into(), &flat(&outline.outer))?;
    Reflect::set(&object, &"holes".into(), &holes)?;
    Ok(object)
}

fn to_js(error: impl std::fmt::Display) -> JsError {
    JsError::new(&error.to_string())
}
