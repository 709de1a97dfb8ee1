//! Meshes, triangulation and the built-in shapes.

use js_sys::{Array, Object};
use wasm_bindgen::prelude::*;

use super::read::{self, entries};
use super::{limits, max_coordinates, max_indices, outline_object, to_js};
use crate::mesh::Mesh;
use crate::outline::Outline;
use crate::shapes;
use crate::triangulate::{triangulate, TriangulationOptions};

/// A validated triangle mesh.
#[wasm_bindgen(js_name = Mesh)]
pub struct JsMesh {
    pub(super) mesh: Mesh,
}

/// Reads a mesh argument pair: `positions` (`Float64Array`, xy-interleaved) and
/// `triangles` (`Uint32Array`), validated.
pub(super) fn read_mesh(positions: &JsValue, triangles: &JsValue) -> Result<Mesh, JsError> {
    let positions = read_positions(positions)?;
    let triangles = read::uint32s(triangles, "triangles", max_indices())?;
    Mesh::from_flat(&positions, &triangles).map_err(to_js)
}

/// A mesh's xy-interleaved positions, refused by their vertex count beyond the limit.
pub(super) fn read_positions(positions: &JsValue) -> Result<Vec<f64>, JsError> {
    let claimed = read::length(positions, "positions")?;
    let limit = limits().max_vertices;
    if claimed > max_coordinates() as f64 {
        return Err(JsError::new(&format!(
            "the mesh has {} vertices ({claimed} numbers), more than the limit of {limit} vertices",
            claimed / 2.0
        )));
    }
    read::float64s(positions, "positions", max_coordinates())
}

#[wasm_bindgen(js_class = Mesh)]
impl JsMesh {
    /// Validates xy-interleaved positions (`Float64Array`) and counter-clockwise index
    /// triples (`Uint32Array`).
    #[wasm_bindgen(constructor)]
    pub fn new(positions: JsValue, triangles: JsValue) -> Result<JsMesh, JsError> {
        Ok(Self { mesh: read_mesh(&positions, &triangles)? })
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
    pub fn neighbors(&self, vertex: JsValue) -> Result<Vec<u32>, JsError> {
        let n = self.mesh.vertex_count();
        let v = read::count(&vertex, "vertex", usize::MAX)?;
        if v >= n {
            return Err(JsError::new(&format!("vertex {v} is out of range: the mesh has {n} vertices")));
        }
        Ok(self.mesh.neighbors(v).to_vec())
    }

    /// Total area of the triangles.
    pub fn area(&self) -> f64 {
        self.mesh.area()
    }
}

/// Reads `{ maxArea?, targetEdgeLength?, minAngle?, maxVertices? }`.
fn triangulation_options(value: &JsValue) -> Result<TriangulationOptions, JsError> {
    const NAMES: [&str; 4] = ["maxArea", "targetEdgeLength", "minAngle", "maxVertices"];
    let mut options = TriangulationOptions::default();
    for (key, field) in entries(value, "triangulation", &NAMES)? {
        let what = format!("option {key}");
        match key.as_str() {
            "maxArea" => options.max_area = Some(read::number(&field, &what)?),
            "targetEdgeLength" => options.target_edge_length = Some(read::number(&field, &what)?),
            "minAngle" => options.min_angle_degrees = read::number(&field, &what)?,
            _ => options.max_vertices = read::count(&field, &what, limits().max_vertices)?,
        }
    }
    Ok(options)
}

/// Triangulates an outline: `outer` a `Float64Array`, xy-interleaved; `holes` an array of
/// the same (or undefined); `options` `{ maxArea?, targetEdgeLength?, minAngle?,
/// maxVertices? }`.
#[wasm_bindgen]
pub fn triangulate_outline(outer: JsValue, holes: JsValue, options: JsValue) -> Result<JsMesh, JsError> {
    let options = triangulation_options(&options)?;
    let points = max_coordinates();
    let outer = read::float64s(&outer, "outline.outer", points)?;
    let holes = read::list(&holes, "outline.holes", points / 6)?
        .iter()
        .enumerate()
        .map(|(k, hole)| read::float64s(hole, &format!("outline.holes[{k}]"), points))
        .collect::<Result<Vec<_>, _>>()?;
    let total: usize = outer.len() + holes.iter().map(Vec::len).sum::<usize>();
    if total > points {
        return Err(JsError::new(&format!("the outline has {} points; the limit is {}", total / 2, points / 2)));
    }
    let outline = Outline::from_flat(&outer, &holes).map_err(to_js)?;
    let mesh = triangulate(&outline, &options).map_err(to_js)?;
    Ok(JsMesh { mesh })
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
pub fn builtin_shape(name: JsValue) -> Result<Object, JsValue> {
    let name = read::string(&name, "the shape's name", 1024)?;
    let outline = shapes::by_name(&name).ok_or_else(|| {
        JsError::new(&format!("there is no built-in shape `{name}`; the shapes are {}", shapes::NAMES.join(", ")))
    })?;
    outline_object(&outline)
}
