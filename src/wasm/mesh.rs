//! Meshes, triangulation and the built-in shapes.

use js_sys::{Array, Object};
use wasm_bindgen::prelude::*;

use super::error::BindingError;
use super::read::{self, Options};
use super::{limits, max_coordinates, max_indices, object, outline_object};
use crate::mesh::Mesh;
use crate::outline::Outline;
use crate::shapes;
use crate::triangulate::{triangulate, triangulate_to_about, TriangulationOptions};

/// A validated triangle mesh.
#[wasm_bindgen(js_name = Mesh)]
pub struct JsMesh {
    pub(super) mesh: Mesh,
}

/// Reads a mesh argument pair: `positions` (`Float64Array`, xy-interleaved) and
/// `triangles` (`Uint32Array`), validated.
pub(super) fn read_mesh(positions: &JsValue, triangles: &JsValue) -> Result<Mesh, BindingError> {
    let positions = read_positions(positions)?;
    let triangles = read::uint32s(triangles, "triangles", max_indices())?;
    Ok(Mesh::from_flat(&positions, &triangles)?)
}

/// A mesh's xy-interleaved positions, refused by their vertex count beyond the limit.
pub(super) fn read_positions(positions: &JsValue) -> Result<Vec<f64>, BindingError> {
    let claimed = read::length(positions, "positions")?;
    let limit = limits().max_vertices;
    if claimed > max_coordinates() as f64 {
        return Err(BindingError::limit(format!(
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
    pub fn new(positions: JsValue, triangles: JsValue) -> Result<JsMesh, BindingError> {
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
    pub fn neighbors(&self, vertex: JsValue) -> Result<Vec<u32>, BindingError> {
        let n = self.mesh.vertex_count();
        let v = read::count(&vertex, "vertex", usize::MAX)?;
        if v >= n {
            return Err(BindingError::argument(format!("vertex {v} is out of range: the mesh has {n} vertices")));
        }
        Ok(self.mesh.neighbors(v).to_vec())
    }

    /// Total area of the triangles.
    pub fn area(&self) -> f64 {
        self.mesh.area()
    }
}

/// Reads `{ maxArea?, targetEdgeLength?, minAngle?, maxVertices? }`.
fn triangulation_options(value: &JsValue) -> Result<TriangulationOptions, BindingError> {
    let given = Options::read(value, "triangulation", &["maxArea", "targetEdgeLength", "minAngle", "maxVertices"])?;
    let mut options = TriangulationOptions::default();
    options.max_area = given.number("maxArea")?.or(options.max_area);
    options.target_edge_length = given.number("targetEdgeLength")?.or(options.target_edge_length);
    options.min_angle_degrees = given.number("minAngle")?.unwrap_or(options.min_angle_degrees);
    options.max_vertices = given.count("maxVertices", limits().max_vertices)?.unwrap_or(options.max_vertices);
    Ok(options)
}

/// Triangulates an outline: `outer` a `Float64Array`, xy-interleaved; `holes` an array of
/// the same (or undefined); `options` `{ maxArea?, targetEdgeLength?, minAngle?,
/// maxVertices? }`.
#[wasm_bindgen]
pub fn triangulate_outline(outer: JsValue, holes: JsValue, options: JsValue) -> Result<JsMesh, BindingError> {
    let options = triangulation_options(&options)?;
    let outline = read_outline(&outer, &holes)?;
    Ok(JsMesh { mesh: triangulate(&outline, &options)? })
}

/// Triangulates an outline (as [`triangulate_outline`] reads it) to about `vertices`
/// vertices ([`triangulate_to_about`]; `targetEdgeLength` in `options` is ignored):
/// `{ mesh: Mesh, targetEdgeLength }`, the edge length that makes the same mesh again.
#[wasm_bindgen]
pub fn triangulate_to_vertices(
    outer: JsValue,
    holes: JsValue,
    vertices: JsValue,
    options: JsValue,
) -> Result<Object, BindingError> {
    let options = triangulation_options(&options)?;
    let vertices = read::count(&vertices, "vertices", options.max_vertices)?;
    let outline = read_outline(&outer, &holes)?;
    let (mesh, edge) = triangulate_to_about(&outline, vertices, &options)?;
    object(&[("mesh", JsMesh { mesh }.into()), ("targetEdgeLength", edge.into())])
}

/// An outline argument pair: `outer` a `Float64Array`, xy-interleaved; `holes` an array of
/// the same (or undefined), within the points limit.
fn read_outline(outer: &JsValue, holes: &JsValue) -> Result<Outline, BindingError> {
    let points = max_coordinates();
    let outer = read::float64s(outer, "outline.outer", points)?;
    let holes = read::list(holes, "outline.holes", points / 6)?
        .iter()
        .enumerate()
        .map(|(k, hole)| read::float64s(hole, &format!("outline.holes[{k}]"), points))
        .collect::<Result<Vec<_>, _>>()?;
    let total: usize = outer.len() + holes.iter().map(Vec::len).sum::<usize>();
    if total > points {
        return Err(BindingError::limit(format!("the outline has {} points; the limit is {}", total / 2, points / 2)));
    }
    Ok(Outline::from_flat(&outer, &holes)?)
}

/// The built-in default shape, `{ outer: Float64Array, holes: Float64Array[] }`.
#[wasm_bindgen(js_name = defaultShape)]
pub fn default_shape() -> Result<Object, BindingError> {
    outline_object(&shapes::gingerbread())
}

/// Names of the built-in shapes; the first is the default.
#[wasm_bindgen(js_name = builtinShapes)]
pub fn builtin_shapes() -> Array {
    shapes::NAMES.iter().map(|&name| JsValue::from_str(name)).collect()
}

/// A built-in shape by name, `{ outer, holes }` as for `defaultShape`.
#[wasm_bindgen(js_name = builtinShape)]
pub fn builtin_shape(name: JsValue) -> Result<Object, BindingError> {
    let name = read::string(&name, "the shape's name", 1024)?;
    let outline = shapes::by_name(&name).ok_or_else(|| {
        BindingError::argument(format!(
            "there is no built-in shape `{name}`; the shapes are {}",
            shapes::NAMES.join(", ")
        ))
    })?;
    outline_object(&outline)
}
