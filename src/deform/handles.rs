//! Handle points, validated once for every deformer: a handle is a point of the mesh, given
//! as a vertex or as a triangle and barycentric coordinates.

use super::DeformError;
use crate::mesh::Mesh;

/// A validated handle point: the triangle it lies in, its vertices and its barycentric
/// weights (finite, at least -1e-12, summing to 1 within 1e-9).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct HandlePoint {
    pub(crate) triangle: usize,
    pub(crate) vertices: [u32; 3],
    pub(crate) weights: [f64; 3],
}

/// One handle on each vertex (weight 1 at that corner of a triangle using it).
pub(crate) fn at_vertices(mesh: &Mesh, vertices: &[u32]) -> Result<Vec<HandlePoint>, DeformError> {
    let n = mesh.vertex_count();
    if let Some((handle, &vertex)) = vertices.iter().enumerate().find(|(_, &v)| v as usize >= n) {
        return Err(DeformError::VertexOutOfRange { handle, vertex, vertex_count: n });
    }
    // A triangle using each vertex (the mesh has no unused vertex).
    let mut triangle_of = vec![0; n];
    for (t, tri) in mesh.triangles().iter().enumerate() {
        for &v in tri {
            triangle_of[v as usize] = t;
        }
    }
    Ok(vertices
        .iter()
        .map(|&vertex| {
            let triangle = triangle_of[vertex as usize];
            let corners = mesh.triangles()[triangle];
            HandlePoint { triangle, vertices: corners, weights: corners.map(|v| if v == vertex { 1.0 } else { 0.0 }) }
        })
        .collect())
}

/// Handles at points inside triangles: a triangle index and barycentric coordinates each.
pub(crate) fn in_triangles(
    mesh: &Mesh,
    triangles: &[u32],
    barycentric: &[[f64; 3]],
) -> Result<Vec<HandlePoint>, DeformError> {
    if barycentric.len() != triangles.len() {
        return Err(DeformError::Length {
            what: "barycentric",
            expected: 3 * triangles.len(),
            found: 3 * barycentric.len(),
            per: 3,
            items: "handles",
        });
    }
    let m = mesh.triangle_count();
    triangles
        .iter()
        .zip(barycentric)
        .enumerate()
        .map(|(handle, (&triangle, &w))| {
            if triangle as usize >= m {
                return Err(DeformError::TriangleOutOfRange { handle, triangle, triangle_count: m });
            }
            let valid = w.iter().all(|x| x.is_finite() && *x >= -1e-12) && (w.iter().sum::<f64>() - 1.0).abs() <= 1e-9;
            if !valid {
                return Err(DeformError::InvalidBarycentric { handle, coordinates: w });
            }
            let triangle = triangle as usize;
            Ok(HandlePoint { triangle, vertices: mesh.triangles()[triangle], weights: w })
        })
        .collect()
}
