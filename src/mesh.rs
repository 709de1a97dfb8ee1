//! The triangle mesh that the triangulator produces and every solver consumes.
//!
//! A [`Mesh`] is validated once, when it is built: finite positions, indices in range,
//! counter-clockwise non-degenerate triangles, every edge shared by at most two triangles
//! with opposite orientations, and no unused vertex. It then knows its boundary (edges of
//! exactly one triangle, holes included) and its vertex adjacency, stored compactly (CSR),
//! which is what the deformers need to assemble their sparse systems.

use std::fmt;

use crate::geometry::{bounding_box, triangle_area, Point};

/// The largest vertex or triangle count a mesh may have (indices are `u32`, and a mesh this
/// large is far beyond what interactive deformation can use).
pub const MAX_MESH_ELEMENTS: usize = 1 << 24;

/// A triangle whose area is at most this fraction of the squared bounding-box diagonal is
/// rejected as degenerate.
const DEGENERATE_RELATIVE_AREA: f64 = 1e-14;

/// Why a set of positions and triangles is not a valid mesh.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum MeshError {
    /// The interleaved position array has an odd length.
    PositionsLength {
        /// Its length.
        len: usize,
    },
    /// The flat triangle index array's length is not a multiple of three.
    TrianglesLength {
        /// Its length.
        len: usize,
    },
    /// There is no triangle at all.
    Empty,
    /// More vertices or triangles than [`MAX_MESH_ELEMENTS`].
    TooLarge {
        /// What is too many: "vertices" or "triangles".
        what: &'static str,
        /// How many were given.
        count: usize,
    },
    /// A vertex has a NaN or infinite coordinate.
    NonFinitePosition {
        /// The vertex.
        vertex: usize,
    },
    /// A triangle refers to a vertex that does not exist.
    IndexOutOfRange {
        /// The triangle.
        triangle: usize,
        /// The offending index.
        index: u32,
        /// The number of vertices.
        vertex_count: usize,
    },
    /// A triangle uses the same vertex twice.
    RepeatedVertex {
        /// The triangle.
        triangle: usize,
    },
    /// A triangle has (numerically) zero area.
    Degenerate {
        /// The triangle.
        triangle: usize,
    },
    /// A triangle is clockwise; all triangles must be counter-clockwise.
    Clockwise {
        /// The triangle.
        triangle: usize,
    },
    /// An edge belongs to more than two triangles, or two triangles run along it in the same
    /// direction (their orientations disagree or they overlap).
    NonManifoldEdge {
        /// One end of the edge.
        a: u32,
        /// The other end.
        b: u32,
    },
    /// A vertex belongs to no triangle.
    UnusedVertex {
        /// The vertex.
        vertex: usize,
    },
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::PositionsLength { len } => {
                write!(f, "positions must hold x, y pairs, but their length {len} is odd")
            }
            Self::TrianglesLength { len } => {
                write!(f, "triangles must hold index triples, but their length {len} is not a multiple of 3")
            }
            Self::Empty => write!(f, "the mesh has no triangles"),
            Self::TooLarge { what, count } => {
                write!(f, "the mesh has {count} {what}, more than the limit of {MAX_MESH_ELEMENTS}")
            }
            Self::NonFinitePosition { vertex } => {
                write!(f, "vertex {vertex} has a coordinate that is not a finite number")
            }
            Self::IndexOutOfRange { triangle, index, vertex_count } => {
                write!(f, "triangle {triangle} refers to vertex {index}, but there are only {vertex_count} vertices")
            }
            Self::RepeatedVertex { triangle } => write!(f, "triangle {triangle} uses the same vertex twice"),
            Self::Degenerate { triangle } => write!(f, "triangle {triangle} is degenerate (zero area)"),
            Self::Clockwise { triangle } => {
                write!(f, "triangle {triangle} is clockwise; triangles must be counter-clockwise")
            }
            Self::NonManifoldEdge { a, b } => write!(
                f,
                "edge {a}-{b} is shared by more than two triangles or by two triangles with the same orientation"
            ),
            Self::UnusedVertex { vertex } => write!(f, "vertex {vertex} belongs to no triangle"),
        }
    }
}

impl std::error::Error for MeshError {}

/// A validated triangle mesh in the plane.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    positions: Vec<Point>,
    triangles: Vec<[u32; 3]>,
    /// Edges of exactly one triangle, oriented as in that triangle (so the shape lies to
    /// their left).
    boundary_edges: Vec<[u32; 2]>,
    is_boundary: Vec<bool>,
    /// Neighbours of vertex `v` are `neighbors[neighbor_start[v]..neighbor_start[v + 1]]`,
    /// sorted ascending.
    neighbor_start: Vec<u32>,
    neighbors: Vec<u32>,
}

impl Mesh {
    /// Validates positions and counter-clockwise triangles and builds the mesh.
    pub fn new(positions: Vec<Point>, triangles: Vec<[u32; 3]>) -> Result<Self, MeshError> {
        let n = positions.len();
        if n > MAX_MESH_ELEMENTS {
            return Err(MeshError::TooLarge { what: "vertices", count: n });
        }
        if triangles.len() > MAX_MESH_ELEMENTS {
            return Err(MeshError::TooLarge { what: "triangles", count: triangles.len() });
        }
        if triangles.is_empty() {
            return Err(MeshError::Empty);
        }
        if let Some(vertex) = positions.iter().position(|p| !p[0].is_finite() || !p[1].is_finite()) {
            return Err(MeshError::NonFinitePosition { vertex });
        }
        let (lo, hi) = bounding_box(positions.iter().copied()).ok_or(MeshError::Empty)?;
        let diagonal2 = (hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2);
        let min_area = DEGENERATE_RELATIVE_AREA * diagonal2;

        let mut used = vec![false; n];
        for (t, tri) in triangles.iter().enumerate() {
            for &index in tri {
                if index as usize >= n {
                    return Err(MeshError::IndexOutOfRange { triangle: t, index, vertex_count: n });
                }
                used[index as usize] = true;
            }
            let [a, b, c] = *tri;
            if a == b || b == c || a == c {
                return Err(MeshError::RepeatedVertex { triangle: t });
            }
            let area = triangle_area(positions[a as usize], positions[b as usize], positions[c as usize]);
            if area.abs() <= min_area {
                return Err(MeshError::Degenerate { triangle: t });
            }
            if area < 0.0 {
                return Err(MeshError::Clockwise { triangle: t });
            }
        }
        if let Some(vertex) = used.iter().position(|&u| !u) {
            return Err(MeshError::UnusedVertex { vertex });
        }

        let boundary_edges = find_boundary_edges(&triangles)?;
        let mut is_boundary = vec![false; n];
        for &[a, b] in &boundary_edges {
            is_boundary[a as usize] = true;
            is_boundary[b as usize] = true;
        }
        let (neighbor_start, neighbors) = vertex_adjacency(n, &triangles);
        Ok(Self { positions, triangles, boundary_edges, is_boundary, neighbor_start, neighbors })
    }

    /// Builds a mesh from flat arrays: positions `x0 y0 x1 y1 ...` and triangles
    /// `a0 b0 c0 a1 b1 c1 ...` (the layout the JavaScript API uses).
    pub fn from_flat(positions: &[f64], triangles: &[u32]) -> Result<Self, MeshError> {
        if !positions.len().is_multiple_of(2) {
            return Err(MeshError::PositionsLength { len: positions.len() });
        }
        if !triangles.len().is_multiple_of(3) {
            return Err(MeshError::TrianglesLength { len: triangles.len() });
        }
        let points = positions.chunks_exact(2).map(|p| [p[0], p[1]]).collect();
        let tris = triangles.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
        Self::new(points, tris)
    }

    /// Vertex positions.
    pub fn positions(&self) -> &[Point] {
        &self.positions
    }

    /// Counter-clockwise triangles as vertex index triples.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Edges that belong to exactly one triangle (outer boundary and holes), oriented as in
    /// their triangle, so the shape is on their left.
    pub fn boundary_edges(&self) -> &[[u32; 2]] {
        &self.boundary_edges
    }

    /// Whether vertex `v` lies on a boundary edge.
    pub fn is_boundary_vertex(&self, v: usize) -> bool {
        self.is_boundary[v]
    }

    /// The boundary vertices, ascending.
    pub fn boundary_vertices(&self) -> impl Iterator<Item = u32> + '_ {
        self.is_boundary.iter().enumerate().filter(|(_, &b)| b).map(|(v, _)| v as u32)
    }

    /// The vertices that share an edge with `v`, ascending.
    pub fn neighbors(&self, v: usize) -> &[u32] {
        &self.neighbors[self.neighbor_start[v] as usize..self.neighbor_start[v + 1] as usize]
    }

    /// Every edge once, as `[a, b]` with `a < b`, in ascending order.
    pub fn edges(&self) -> impl Iterator<Item = [u32; 2]> + '_ {
        (0..self.vertex_count())
            .flat_map(move |a| self.neighbors(a).iter().filter(move |&&b| b as usize > a).map(move |&b| [a as u32, b]))
    }

    /// The total area of the triangles.
    pub fn area(&self) -> f64 {
        self.triangles.iter().map(|t| self.signed_triangle_area(t)).sum()
    }

    /// Signed area of one triangle of this mesh (positive, since triangles are validated
    /// counter-clockwise at construction).
    pub fn signed_triangle_area(&self, t: &[u32; 3]) -> f64 {
        triangle_area(self.positions[t[0] as usize], self.positions[t[1] as usize], self.positions[t[2] as usize])
    }

    /// Number of edge-connected components of the vertex graph.
    pub fn connected_components(&self) -> usize {
        let n = self.vertex_count();
        let mut seen = vec![false; n];
        let mut stack = Vec::new();
        let mut components = 0;
        for start in 0..n {
            if seen[start] {
                continue;
            }
            components += 1;
            seen[start] = true;
            stack.push(start);
            while let Some(v) = stack.pop() {
                for &w in self.neighbors(v) {
                    if !seen[w as usize] {
                        seen[w as usize] = true;
                        stack.push(w as usize);
                    }
                }
            }
        }
        components
    }
}

/// Finds the edges of exactly one triangle; rejects edges of more than two triangles and
/// pairs of triangles that traverse an edge in the same direction.
fn find_boundary_edges(triangles: &[[u32; 3]]) -> Result<Vec<[u32; 2]>, MeshError> {
    // Every directed half-edge keyed by its undirected edge; sorting groups the copies.
    let mut half_edges: Vec<(u32, u32, bool)> = Vec::with_capacity(3 * triangles.len());
    for &[a, b, c] in triangles {
        for (p, q) in [(a, b), (b, c), (c, a)] {
            half_edges.push((p.min(q), p.max(q), p < q));
        }
    }
    half_edges.sort_unstable();
    let mut boundary = Vec::new();
    let mut i = 0;
    while i < half_edges.len() {
        let (lo, hi, forward) = half_edges[i];
        let mut j = i + 1;
        while j < half_edges.len() && half_edges[j].0 == lo && half_edges[j].1 == hi {
            j += 1;
        }
        match j - i {
            1 => boundary.push(if forward { [lo, hi] } else { [hi, lo] }),
            2 if half_edges[i].2 != half_edges[i + 1].2 => {}
            _ => return Err(MeshError::NonManifoldEdge { a: lo, b: hi }),
        }
        i = j;
    }
    Ok(boundary)
}

/// Sorted vertex adjacency in compressed form (offsets, neighbours).
fn vertex_adjacency(n: usize, triangles: &[[u32; 3]]) -> (Vec<u32>, Vec<u32>) {
    let mut lists: Vec<Vec<u32>> = vec![Vec::new(); n];
    for &[a, b, c] in triangles {
        for (p, q) in [(a, b), (b, c), (c, a)] {
            lists[p as usize].push(q);
            lists[q as usize].push(p);
        }
    }
    let mut start = Vec::with_capacity(n + 1);
    let mut flat = Vec::new();
    start.push(0);
    for list in &mut lists {
        list.sort_unstable();
        list.dedup();
        flat.extend_from_slice(list);
        start.push(flat.len() as u32);
    }
    (start, flat)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two triangles forming the unit square, split along the diagonal 0-2.
    fn square() -> (Vec<Point>, Vec<[u32; 3]>) {
        (vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], vec![[0, 1, 2], [0, 2, 3]])
    }

    #[test]
    fn square_has_four_boundary_edges_and_a_shared_diagonal() {
        let (p, t) = square();
        let mesh = Mesh::new(p, t).unwrap();
        assert_eq!(mesh.area(), 1.0);
        let mut boundary = mesh.boundary_edges().to_vec();
        boundary.sort();
        assert_eq!(boundary, vec![[0, 1], [1, 2], [2, 3], [3, 0]]);
        assert_eq!(mesh.neighbors(0), &[1, 2, 3]);
        assert_eq!(mesh.neighbors(1), &[0, 2]);
        assert_eq!(mesh.edges().count(), 5);
        assert_eq!(mesh.connected_components(), 1);
        assert_eq!(mesh.boundary_vertices().count(), 4);
    }

    #[test]
    fn rejects_bad_input_with_the_right_error() {
        let (p, _) = square();
        let cases: Vec<(Vec<Point>, Vec<[u32; 3]>, MeshError)> = vec![
            (p.clone(), vec![], MeshError::Empty),
            (
                p.clone(),
                vec![[0, 1, 7], [0, 2, 3]],
                MeshError::IndexOutOfRange { triangle: 0, index: 7, vertex_count: 4 },
            ),
            (p.clone(), vec![[0, 1, 1], [0, 2, 3]], MeshError::RepeatedVertex { triangle: 0 }),
            (p.clone(), vec![[0, 2, 1], [0, 2, 3]], MeshError::Clockwise { triangle: 0 }),
            (p.clone(), vec![[0, 1, 2]], MeshError::UnusedVertex { vertex: 3 }),
            (p.clone(), vec![[0, 1, 2], [0, 1, 2], [0, 2, 3]], MeshError::NonManifoldEdge { a: 0, b: 1 }),
            (vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], vec![[0, 1, 2]], MeshError::Degenerate { triangle: 0 }),
            (
                vec![[0.0, 0.0], [f64::NAN, 0.0], [0.0, 1.0]],
                vec![[0, 1, 2]],
                MeshError::NonFinitePosition { vertex: 1 },
            ),
        ];
        for (positions, triangles, expected) in cases {
            assert_eq!(Mesh::new(positions, triangles), Err(expected));
        }
        assert_eq!(Mesh::from_flat(&[0.0; 3], &[]), Err(MeshError::PositionsLength { len: 3 }));
        assert_eq!(Mesh::from_flat(&[0.0; 4], &[0, 1]), Err(MeshError::TrianglesLength { len: 2 }));
    }

    #[test]
    fn two_separate_triangles_are_two_components() {
        let p = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [5.0, 0.0], [6.0, 0.0], [5.0, 1.0]];
        let mesh = Mesh::new(p, vec![[0, 1, 2], [3, 4, 5]]).unwrap();
        assert_eq!(mesh.connected_components(), 2);
    }
}
