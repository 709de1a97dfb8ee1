//! What every deformer checks and computes alike, written once: handle points (a point of
//! the mesh, given as a vertex or as a triangle and barycentric coordinates) validated and
//! placed, distinct handle points counted, velocities and poses checked, the mesh's
//! connectivity, results within the coordinate limits, and the size of a shape.

use super::error::DeformError;
use super::options::STIFFNESS_RANGE;
use crate::geometry::{bounding_box, Point, MAX_COORDINATE};
use crate::mesh::{Mesh, MeshPoint};

/// A validated handle point: the triangle it lies in, its vertices and its barycentric
/// weights (finite, at least -1e-12, summing to 1 within 1e-9).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct HandlePoint {
    pub(crate) triangle: usize,
    pub(crate) vertices: [u32; 3],
    pub(crate) weights: [f64; 3],
}

impl HandlePoint {
    /// Where the point is when the mesh's vertices are at `positions`.
    pub(crate) fn position(&self, positions: &[Point]) -> Point {
        let mut p = [0.0, 0.0];
        for (v, w) in self.vertices.iter().zip(self.weights) {
            p[0] += w * positions[*v as usize][0];
            p[1] += w * positions[*v as usize][1];
        }
        p
    }
}

/// Handle points as [`super::Deformer::handle_points`] gives them: triangles and weights.
pub(crate) fn as_points<'a>(points: impl Iterator<Item = &'a HandlePoint>) -> (Vec<u32>, Vec<[f64; 3]>) {
    points.map(|p| (p.triangle as u32, p.weights)).unzip()
}

/// Points of the mesh, checked: a vertex in range (placed at weight 1 at that corner of a
/// triangle using it), or a triangle in range with barycentric coordinates that are finite,
/// at least -1e-12 and sum to 1 within 1e-9. The one check of a handle's place, for the
/// deformers and DefOp.
pub(crate) fn resolve(mesh: &Mesh, points: &[MeshPoint]) -> Result<Vec<HandlePoint>, DeformError> {
    let (n, m) = (mesh.vertex_count(), mesh.triangle_count());
    // A triangle using each vertex (the mesh has no unused vertex), if a vertex is asked for.
    let mut triangle_of = Vec::new();
    if points.iter().any(|p| matches!(p, MeshPoint::Vertex(_))) {
        triangle_of = vec![0; n];
        for (t, tri) in mesh.triangles().iter().enumerate() {
            for &v in tri {
                triangle_of[v as usize] = t;
            }
        }
    }
    points
        .iter()
        .enumerate()
        .map(|(handle, point)| match *point {
            MeshPoint::Vertex(vertex) => {
                if vertex as usize >= n {
                    return Err(DeformError::VertexOutOfRange { handle, vertex, vertex_count: n });
                }
                let triangle = triangle_of[vertex as usize];
                let corners = mesh.triangles()[triangle];
                let weights = corners.map(|v| if v == vertex { 1.0 } else { 0.0 });
                Ok(HandlePoint { triangle, vertices: corners, weights })
            }
            MeshPoint::Inside { triangle, barycentric: w } => {
                if triangle as usize >= m {
                    return Err(DeformError::TriangleOutOfRange { handle, triangle, triangle_count: m });
                }
                let valid =
                    w.iter().all(|x| x.is_finite() && *x >= -1e-12) && (w.iter().sum::<f64>() - 1.0).abs() <= 1e-9;
                if !valid {
                    return Err(DeformError::InvalidBarycentric { handle, coordinates: w });
                }
                let triangle = triangle as usize;
                Ok(HandlePoint { triangle, vertices: mesh.triangles()[triangle], weights: w })
            }
        })
        .collect()
}

/// One handle on each vertex (weight 1 at that corner of a triangle using it).
pub(crate) fn at_vertices(mesh: &Mesh, vertices: &[u32]) -> Result<Vec<HandlePoint>, DeformError> {
    let points: Vec<MeshPoint> = vertices.iter().map(|&v| MeshPoint::Vertex(v)).collect();
    resolve(mesh, &points)
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
    let points: Vec<MeshPoint> = triangles
        .iter()
        .zip(barycentric)
        .map(|(&triangle, &barycentric)| MeshPoint::Inside { triangle, barycentric })
        .collect();
    resolve(mesh, &points)
}

/// How many of `points` are distinct, where a point that lies within `tolerance` of an
/// earlier one (`hypot` of the differences at most `tolerance`) is not: the count of `i`
/// with every `j < i` farther than `tolerance`. O(n log n): points are bucketed in square
/// cells of side `tolerance / 2`, so two points in one cell are always within the
/// tolerance and only the first of a cell (by index) needs a look at the cells around
/// (3 cells each way, a margin for rounding); each cell is looked into by at most 49
/// first points. The points must lie within 2^50 tolerances of each other (handle points lie
/// in the mesh, and the deformer's tolerance is 1e-12 of its size), so that cells are
/// computed exactly enough.
pub(crate) fn distinct_points(points: &[[f64; 2]], tolerance: f64) -> usize {
    let lo = points.iter().fold([f64::INFINITY; 2], |lo, p| [lo[0].min(p[0]), lo[1].min(p[1])]);
    let side = tolerance / 2.0;
    debug_assert!(points.iter().all(|p| (p[0] - lo[0]).max(p[1] - lo[1]) < side * 2f64.powi(50)));
    let cell = |p: &[f64; 2]| [((p[0] - lo[0]) / side).floor() as i64, ((p[1] - lo[1]) / side).floor() as i64];
    // Points by cell, then by index.
    let mut order: Vec<([i64; 2], usize)> = points.iter().enumerate().map(|(i, p)| (cell(p), i)).collect();
    order.sort_unstable();
    // Exactly the rule's comparison, so that NaN distances count as near too.
    let far = |i: usize, j: usize| {
        let (p, q) = (points[i], points[j]);
        libm::hypot(q[0] - p[0], q[1] - p[1]) > tolerance
    };
    let mut count = 0;
    let mut start = 0;
    while start < order.len() {
        let (key, first) = order[start];
        let end = start + order[start..].partition_point(|(k, _)| *k == key);
        // The cells 3 rows above to 3 below in each of 7 columns are contiguous in `order`.
        let near_earlier = (-3..=3i64).any(|dx| {
            let column = key[0].saturating_add(dx);
            let (low, high) = ([column, key[1].saturating_sub(3)], [column, key[1].saturating_add(3)]);
            let from = order.partition_point(|(k, _)| *k < low);
            order[from..].iter().take_while(|(k, _)| *k <= high).any(|&(_, j)| j < first && !far(first, j))
        });
        if !near_earlier {
            count += 1;
        }
        start = end;
    }
    count
}

/// Refuses a mesh in several pieces: a deformer needs one connected piece.
pub(crate) fn check_connected(mesh: &Mesh) -> Result<(), DeformError> {
    match mesh.connected_components() {
        1 => Ok(()),
        components => Err(DeformError::Disconnected { components }),
    }
}

/// The length of the diagonal of the points' bounding box (the size of a shape).
pub(crate) fn diagonal(points: &[Point]) -> f64 {
    let (lo, hi) = bounding_box(points.iter().copied()).expect("a mesh has vertices");
    libm::hypot(hi[0] - lo[0], hi[1] - lo[1])
}

/// Checks a pose given to `set_positions`: one position per vertex, each finite and within
/// ±[`MAX_COORDINATE`].
pub(crate) fn check_pose(positions: &[[f64; 2]], vertex_count: usize) -> Result<(), DeformError> {
    if positions.len() != vertex_count {
        return Err(DeformError::Length {
            what: "positions",
            expected: 2 * vertex_count,
            found: 2 * positions.len(),
            per: 2,
            items: "vertices",
        });
    }
    for (vertex, p) in positions.iter().enumerate() {
        if !(p[0].is_finite() && p[1].is_finite()) {
            return Err(DeformError::NonFinitePosition { vertex });
        }
        if let Some(&value) = p.iter().find(|x| x.abs() > MAX_COORDINATE) {
            return Err(DeformError::PositionOutOfRange { vertex, value });
        }
    }
    Ok(())
}

/// Checks velocities: one per handle, each finite.
pub(crate) fn check_velocities(velocities: &[[f64; 2]], handle_count: usize) -> Result<(), DeformError> {
    if velocities.len() != handle_count {
        return Err(DeformError::Length {
            what: "velocities",
            expected: 2 * handle_count,
            found: 2 * velocities.len(),
            per: 2,
            items: "handles",
        });
    }
    if let Some(handle) = velocities.iter().position(|v| !v[0].is_finite() || !v[1].is_finite()) {
        return Err(DeformError::NonFiniteVelocity { handle });
    }
    Ok(())
}

/// Whether every position of a step's result is finite and within ±[`MAX_COORDINATE`].
pub(crate) fn in_range(positions: &[[f64; 2]]) -> bool {
    positions.iter().flatten().all(|x| x.abs() <= MAX_COORDINATE)
}

/// Checks turns: one per handle, each finite.
pub(crate) fn check_turns(turns: &[f64], handle_count: usize) -> Result<(), DeformError> {
    if turns.len() != handle_count {
        return Err(DeformError::Length {
            what: "turns",
            expected: handle_count,
            found: turns.len(),
            per: 1,
            items: "handles",
        });
    }
    match turns.iter().position(|w| !w.is_finite()) {
        Some(handle) => Err(DeformError::NonFiniteTurn { handle }),
        None => Ok(()),
    }
}

/// The vertices a turning handle carries with it: its triangle's corners and their
/// neighbours, each once, ascending.
pub(crate) fn neighbourhood(mesh: &Mesh, handle: &HandlePoint) -> Vec<u32> {
    let mut vertices: Vec<u32> = handle.vertices.to_vec();
    for &v in &handle.vertices {
        vertices.extend_from_slice(mesh.neighbors(v as usize));
    }
    vertices.sort_unstable();
    vertices.dedup();
    vertices
}

/// Checks per-triangle stiffness: one value per triangle, each in [`STIFFNESS_RANGE`]
/// (`None`, 1 everywhere, always passes).
pub(crate) fn check_stiffness(stiffness: Option<&[f64]>, triangle_count: usize) -> Result<(), DeformError> {
    let Some(values) = stiffness else { return Ok(()) };
    if values.len() != triangle_count {
        return Err(DeformError::Length {
            what: "stiffness",
            expected: triangle_count,
            found: values.len(),
            per: 1,
            items: "triangles",
        });
    }
    match values.iter().position(|x| !STIFFNESS_RANGE.contains(x)) {
        Some(triangle) => Err(DeformError::InvalidStiffness { triangle, value: values[triangle] }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The definition, comparing every pair.
    fn brute_force(points: &[[f64; 2]], tolerance: f64) -> usize {
        (0..points.len())
            .filter(|&i| points[..i].iter().all(|q| libm::hypot(q[0] - points[i][0], q[1] - points[i][1]) > tolerance))
            .count()
    }

    #[test]
    fn distinct_points_match_the_pairwise_definition() {
        let mut state = 3u64;
        let mut next = |n: u64| {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 33) % n
        };
        for round in 0..2000 {
            let tolerance = [1e-12, 1e-3, 0.5, 7.0][round % 4];
            // Clusters: points at offsets of fractions of the tolerance around a few
            // centres, distances at and around the tolerance included.
            let fractions = [0.0, 0.3, 0.5, 0.7, 0.99, 1.0, 1.01, 1.5, 2.0, 2.5, 3.0, 5.0];
            let centres: Vec<[f64; 2]> =
                (0..1 + next(4)).map(|_| [next(5) as f64 * 3.0 * tolerance, next(5) as f64 * 0.7]).collect();
            let n = 1 + next(60) as usize;
            let points: Vec<[f64; 2]> = (0..n)
                .map(|_| {
                    let c = centres[next(centres.len() as u64) as usize];
                    let (fx, fy) = (fractions[next(12) as usize], fractions[next(12) as usize]);
                    let (sx, sy) = (if next(2) == 0 { 1.0 } else { -1.0 }, if next(2) == 0 { 1.0 } else { -1.0 });
                    [c[0] + sx * fx * tolerance, c[1] + sy * fy * tolerance]
                })
                .collect();
            assert_eq!(distinct_points(&points, tolerance), brute_force(&points, tolerance), "{points:?} {tolerance}");
        }
        assert_eq!(distinct_points(&[], 1.0), 0);
    }
}
