//! The triangle mesh that the triangulator produces and every solver consumes.
//!
//! A [`Mesh`] is validated once, when it is built: finite positions within
//! [`MAX_COORDINATE`] and a shape at least [`MIN_EXTENT`] across, indices in range,
//! counter-clockwise non-degenerate triangles, every edge shared by at most two triangles
//! with opposite orientations, every vertex's triangles one fan joined by edges (no
//! bow-tie), and no unused vertex. It then knows its boundary (edges of exactly one
//! triangle, holes included) and its vertex adjacency, stored compactly (CSR), which is
//! what the deformers need to assemble their sparse systems.
//!
//! Validation is scale-invariant: orientations are computed on the positions scaled by a
//! power of two (exact), and a triangle is degenerate when double precision cannot tell its
//! orientation ([`certain_orient`]), whatever its size.

use std::fmt;

use crate::error_code::ErrorCode;
use crate::geometry::{
    bounding_box, certain_orient, normalising_exponent, scale_by_power_of_two, triangle_area, Point, MAX_COORDINATE,
    MIN_EXTENT,
};
use crate::message::Number;

/// The default vertex limit of everything interactive: triangulation
/// ([`crate::TriangulationOptions::max_vertices`]) and mesh files
/// ([`crate::import::Limits::max_vertices`]). At 100,000 vertices a deformer's set-up takes
/// about a second and a frame tens of milliseconds in a browser.
pub const DEFAULT_MAX_VERTICES: usize = 100_000;

/// The largest vertex or triangle count a mesh may have (indices are `u32`, and a mesh this
/// large is far beyond what interactive deformation can use).
pub const MAX_MESH_ELEMENTS: usize = 1 << 24;

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
    /// A vertex has a coordinate larger in magnitude than [`MAX_COORDINATE`].
    CoordinateOutOfRange {
        /// The vertex.
        vertex: usize,
        /// The coordinate.
        value: f64,
    },
    /// The mesh is less than [`MIN_EXTENT`] across (both sides of its bounding box).
    TooSmall {
        /// The larger side of its bounding box.
        extent: f64,
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
    /// A triangle has zero area to double precision: its orientation, computed on the
    /// positions scaled by a power of two so that the largest coordinate is between 1 and 2,
    /// lies within its rounding error of zero (see [`certain_orient`]). Only triangles whose
    /// smallest angle is below about 1e-15 radians, or whose area is below about 1e-300 of
    /// the square of the largest coordinate, are degenerate; size alone never is.
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
    /// The triangles around a vertex form several fans that share no edge there: the mesh
    /// is pinched at the vertex (two parts meeting only there, a bow-tie, or a hole touching
    /// the boundary at a point).
    ///
    /// Such meshes are refused rather than supported: on parts joined by a point the Killing
    /// field's rigid motions are independent on each side (each part can turn about the
    /// vertex at no energy), so AKAP's systems are singular unless every part has handles,
    /// and the boundary is no longer a set of simple loops. Split the vertex into one copy
    /// per fan (the parts then deform separately), or join the parts along an edge.
    NonManifoldVertex {
        /// The vertex.
        vertex: u32,
        /// How many fans meet there (at least 2).
        fans: usize,
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
            Self::CoordinateOutOfRange { vertex, value } => write!(
                f,
                "vertex {vertex} has the coordinate {}, beyond the limit of ±{MAX_COORDINATE:e}; scale the mesh down",
                Number(*value)
            ),
            Self::TooSmall { extent } => write!(
                f,
                "the mesh is only {extent:e} across, less than the smallest size of {MIN_EXTENT:e}; scale it up"
            ),
            Self::IndexOutOfRange { triangle, index, vertex_count } => {
                write!(f, "triangle {triangle} refers to vertex {index}, but there are only {vertex_count} vertices")
            }
            Self::RepeatedVertex { triangle } => write!(f, "triangle {triangle} uses the same vertex twice"),
            Self::Degenerate { triangle } => {
                write!(
                    f,
                    "triangle {triangle} is degenerate: its corners are collinear to double precision (zero area)"
                )
            }
            Self::Clockwise { triangle } => {
                write!(f, "triangle {triangle} is clockwise; triangles must be counter-clockwise")
            }
            Self::NonManifoldEdge { a, b } => write!(
                f,
                "edge {a}-{b} is shared by more than two triangles or by two triangles with the same orientation"
            ),
            Self::UnusedVertex { vertex } => write!(f, "vertex {vertex} belongs to no triangle"),
            Self::NonManifoldVertex { vertex, fans } => write!(
                f,
                "vertex {vertex} joins {fans} fans of triangles that share no edge there (the mesh is pinched, \
                 like a bow-tie); split the vertex into one per fan, or join the parts along an edge"
            ),
        }
    }
}

impl std::error::Error for MeshError {}

impl MeshError {
    /// The kind of error: [`ErrorCode::Limit`] for too many elements, otherwise
    /// [`ErrorCode::InvalidMesh`].
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::TooLarge { .. } => ErrorCode::Limit,
            _ => ErrorCode::InvalidMesh,
        }
    }
}

/// A point of a mesh, where a handle is: a vertex, or a point of a triangle by its
/// barycentric coordinates (the deformers' and DefOp's handles, checked by
/// `deform::handles::resolve`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MeshPoint {
    /// A vertex.
    Vertex(u32),
    /// A point of a triangle, given by its barycentric coordinates (non-negative, sum 1) in
    /// the order of the triangle's vertices.
    Inside {
        /// The triangle.
        triangle: u32,
        /// The barycentric coordinates.
        barycentric: [f64; 3],
    },
}

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
    /// Checks what every use of triangles at positions needs, a pose as much as a rest
    /// mesh: counts within [`MAX_MESH_ELEMENTS`], at least one triangle, finite coordinates
    /// within [`MAX_COORDINATE`], indices that name vertices, three different ones per
    /// triangle. [`Mesh::new`] checks this and then the geometry (orientation, size,
    /// manifoldness), which a pose need not keep: the mesh writers write poses with
    /// flipped or collapsed triangles as they are.
    pub fn check_arrays(positions: &[Point], triangles: &[[u32; 3]]) -> Result<(), MeshError> {
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
        for (vertex, p) in positions.iter().enumerate() {
            if !(p[0].is_finite() && p[1].is_finite()) {
                return Err(MeshError::NonFinitePosition { vertex });
            }
            if let Some(&value) = p.iter().find(|x| x.abs() > MAX_COORDINATE) {
                return Err(MeshError::CoordinateOutOfRange { vertex, value });
            }
        }
        for (t, tri) in triangles.iter().enumerate() {
            if let Some(&index) = tri.iter().find(|&&i| i as usize >= n) {
                return Err(MeshError::IndexOutOfRange { triangle: t, index, vertex_count: n });
            }
            let [a, b, c] = *tri;
            if a == b || b == c || a == c {
                return Err(MeshError::RepeatedVertex { triangle: t });
            }
        }
        Ok(())
    }

    /// Validates positions and counter-clockwise triangles and builds the mesh.
    pub fn new(positions: Vec<Point>, triangles: Vec<[u32; 3]>) -> Result<Self, MeshError> {
        Self::check_arrays(&positions, &triangles)?;
        let n = positions.len();
        let (lo, hi) = bounding_box(positions.iter().copied()).ok_or(MeshError::Empty)?;
        let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        if extent < MIN_EXTENT {
            return Err(MeshError::TooSmall { extent });
        }
        // Orientations on positions scaled by a power of two (exact): free of overflow and
        // underflow, and the same at every scale.
        let k = normalising_exponent(positions.iter().copied());
        let scaled = |v: u32| positions[v as usize].map(|x| scale_by_power_of_two(x, k));

        let mut used = vec![false; n];
        for (t, tri) in triangles.iter().enumerate() {
            for &index in tri {
                used[index as usize] = true;
            }
            let [a, b, c] = *tri;
            match certain_orient(scaled(a), scaled(b), scaled(c)) {
                None => return Err(MeshError::Degenerate { triangle: t }),
                Some(det) if det < 0.0 => return Err(MeshError::Clockwise { triangle: t }),
                Some(_) => {}
            }
        }
        if let Some(vertex) = used.iter().position(|&u| !u) {
            return Err(MeshError::UnusedVertex { vertex });
        }

        let (boundary_edges, glue) = find_boundary_edges(&triangles)?;
        check_fans(&triangles, &glue)?;
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

    /// The boundary as closed loops of vertices (the outer outline and each hole's), each
    /// in the direction of its edges (the shape on the left), starting at the first vertex
    /// of its first edge in [`Mesh::boundary_edges`]. Every boundary vertex has one
    /// outgoing boundary edge (bow-ties are refused), so the loops are well defined.
    pub fn boundary_loops(&self) -> Vec<Vec<u32>> {
        let mut next = vec![u32::MAX; self.vertex_count()];
        for &[a, b] in &self.boundary_edges {
            next[a as usize] = b;
        }
        let mut seen = vec![false; self.vertex_count()];
        let mut loops = Vec::new();
        for &[start, _] in &self.boundary_edges {
            if seen[start as usize] {
                continue;
            }
            let mut ring = Vec::new();
            let mut v = start;
            while !seen[v as usize] {
                seen[v as usize] = true;
                ring.push(v);
                v = next[v as usize];
            }
            loops.push(ring);
        }
        loops
    }

    /// The vertices that share an edge with `v`, ascending.
    pub fn neighbors(&self, v: usize) -> &[u32] {
        &self.neighbors[self.neighbor_start[v] as usize..self.neighbor_start[v + 1] as usize]
    }

    /// The vertex graph in compressed form with `usize` indices, as the sparse orderings
    /// ([`crate::sparse::fill_reducing_order`]) read it: the neighbours of vertex `v` are
    /// `adj[ptr[v]..ptr[v + 1]]`, ascending.
    pub fn vertex_graph(&self) -> (Vec<usize>, Vec<usize>) {
        let ptr = self.neighbor_start.iter().map(|&s| s as usize).collect();
        (ptr, self.neighbors.iter().map(|&w| w as usize).collect())
    }

    /// The graph of some of the vertices, renumbered, in the form of [`Self::vertex_graph`]:
    /// `label[v]` is vertex v's number in it, or `usize::MAX` to leave v out. Node `label[v]`
    /// has the labels of v's labelled neighbours, in the order of their vertex indices.
    ///
    /// # Panics
    /// If `label` does not have one entry per vertex, or the labels other than `usize::MAX`
    /// are not `0..m`, each once.
    pub fn relabelled_vertex_graph(&self, label: &[usize]) -> (Vec<usize>, Vec<usize>) {
        assert_eq!(label.len(), self.vertex_count(), "one label per vertex");
        let mut vertex = vec![usize::MAX; label.iter().filter(|&&l| l != usize::MAX).count()];
        for (v, &l) in label.iter().enumerate().filter(|(_, &l)| l != usize::MAX) {
            assert_eq!(std::mem::replace(&mut vertex[l], v), usize::MAX, "label {l} is given twice");
        }
        let mut ptr = Vec::with_capacity(vertex.len() + 1);
        let mut adj = Vec::new();
        ptr.push(0);
        for &v in &vertex {
            adj.extend(self.neighbors(v).iter().map(|&w| label[w as usize]).filter(|&l| l != usize::MAX));
            ptr.push(adj.len());
        }
        (ptr, adj)
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

    /// Number of connected pieces: components of the vertex graph (vertices joined by
    /// edges). Since every vertex's triangles form one fan joined by edges (bow-ties are
    /// refused, [`MeshError::NonManifoldVertex`]), these are also the pieces whose triangles
    /// are joined through shared edges: two pieces never touch, not even at a vertex.
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
/// pairs of triangles that traverse an edge in the same direction. Also returns, for each
/// edge of two triangles, the pairs of triangle corners (`3 t + i`) it joins: the corners at
/// its two ends.
#[allow(clippy::type_complexity)]
fn find_boundary_edges(triangles: &[[u32; 3]]) -> Result<(Vec<[u32; 2]>, Vec<[u32; 2]>), MeshError> {
    // Every directed half-edge keyed by its undirected edge; sorting groups the copies. With
    // each, the corners at its lower and its higher end.
    let mut half_edges: Vec<(u32, u32, bool, [u32; 2])> = Vec::with_capacity(3 * triangles.len());
    for (t, &[a, b, c]) in triangles.iter().enumerate() {
        let corner = |i: u32| 3 * t as u32 + i;
        for (p, q, cp, cq) in [(a, b, 0, 1), (b, c, 1, 2), (c, a, 2, 0)] {
            let ends = if p < q { [corner(cp), corner(cq)] } else { [corner(cq), corner(cp)] };
            half_edges.push((p.min(q), p.max(q), p < q, ends));
        }
    }
    half_edges.sort_unstable_by_key(|h| (h.0, h.1, h.2));
    let mut boundary = Vec::new();
    let mut glue = Vec::new();
    let mut i = 0;
    while i < half_edges.len() {
        let (lo, hi, forward, _) = half_edges[i];
        let mut j = i + 1;
        while j < half_edges.len() && half_edges[j].0 == lo && half_edges[j].1 == hi {
            j += 1;
        }
        match j - i {
            1 => boundary.push(if forward { [lo, hi] } else { [hi, lo] }),
            2 if half_edges[i].2 != half_edges[i + 1].2 => {
                let (s, t) = (half_edges[i].3, half_edges[i + 1].3);
                glue.push([s[0], t[0]]);
                glue.push([s[1], t[1]]);
            }
            _ => return Err(MeshError::NonManifoldEdge { a: lo, b: hi }),
        }
        i = j;
    }
    Ok((boundary, glue))
}

/// Checks that the triangles around each vertex form one fan: their corners at the vertex,
/// joined whenever two of them share an edge at it (`glue`), are all connected.
fn check_fans(triangles: &[[u32; 3]], glue: &[[u32; 2]]) -> Result<(), MeshError> {
    // Union-find over corners, with path halving.
    let mut parent: Vec<u32> = (0..3 * triangles.len() as u32).collect();
    fn root(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            let grandparent = parent[parent[x as usize] as usize];
            parent[x as usize] = grandparent;
            x = grandparent;
        }
        x
    }
    for &[a, b] in glue {
        let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
        if ra != rb {
            parent[ra.max(rb) as usize] = ra.min(rb);
        }
    }
    // Each vertex's corners by vertex, with their fan (root); more than one root is a pinch.
    let mut corners: Vec<(u32, u32)> = Vec::with_capacity(3 * triangles.len());
    for (t, tri) in triangles.iter().enumerate() {
        for (i, &v) in tri.iter().enumerate() {
            corners.push((v, root(&mut parent, 3 * t as u32 + i as u32)));
        }
    }
    corners.sort_unstable();
    corners.dedup();
    let pinched = corners.windows(2).find(|w| w[0].0 == w[1].0).map(|w| w[0].0);
    match pinched {
        Some(vertex) => {
            let fans = corners.iter().filter(|c| c.0 == vertex).count();
            Err(MeshError::NonManifoldVertex { vertex, fans })
        }
        None => Ok(()),
    }
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
    fn vertex_graphs_list_the_neighbours_in_compressed_form() {
        let (p, t) = square();
        let mesh = Mesh::new(p, t).unwrap();
        assert_eq!(mesh.vertex_graph(), (vec![0, 3, 5, 8, 10], vec![1, 2, 3, 0, 2, 0, 1, 3, 0, 2]));
        // Vertex 1 left out, vertices 0, 2, 3 numbered 2, 0, 1: node 0 is vertex 2 (neighbours
        // 0 and 3: nodes 2, 1), node 1 vertex 3 (0, 2: nodes 2, 0), node 2 vertex 0 (2, 3:
        // nodes 0, 1).
        let none = usize::MAX;
        assert_eq!(mesh.relabelled_vertex_graph(&[2, none, 0, 1]), (vec![0, 2, 4, 6], vec![2, 1, 2, 0, 0, 1]));
        let identity: Vec<usize> = (0..4).collect();
        assert_eq!(mesh.relabelled_vertex_graph(&identity), mesh.vertex_graph());
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
    fn a_vertex_where_fans_meet_without_an_edge_is_refused() {
        // Bow-tie: two triangles meeting only at vertex 0.
        let p = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]];
        assert_eq!(
            Mesh::new(p.clone(), vec![[0, 1, 2], [0, 3, 4]]),
            Err(MeshError::NonManifoldVertex { vertex: 0, fans: 2 })
        );
        // Two fans at vertex 0: one triangle, and three joined by the edges 0-4 and 0-5.
        let p6 = vec![[0.0, 0.0], [2.0, 0.0], [1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [0.5, -2.0], [1.0, -1.0]];
        let tris = vec![[0, 1, 2], [0, 3, 4], [0, 4, 5], [0, 5, 6]];
        assert_eq!(Mesh::new(p6, tris), Err(MeshError::NonManifoldVertex { vertex: 0, fans: 2 }));
        // A square ring whose diamond-shaped hole touches the outer boundary at M = (0, -2):
        // edge-connected all round, but pinched at M.
        let (a, b, c, d) = ([-2.0, -2.0], [2.0, -2.0], [2.0, 2.0], [-2.0, 2.0]);
        let (m, h1, h2, h3) = ([0.0, -2.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]);
        let ring = vec![a, b, c, d, m, h1, h2, h3];
        let (a, b, c, d, m, h1, h2, h3) = (0, 1, 2, 3, 4, 5, 6, 7);
        let tris = vec![[m, b, h1], [b, c, h1], [h1, c, h2], [c, d, h2], [h2, d, h3], [d, a, h3], [h3, a, m]];
        assert_eq!(Mesh::new(ring, tris), Err(MeshError::NonManifoldVertex { vertex: 4, fans: 2 }));
        // A closed fan around an interior vertex and an open fan on the boundary are one fan each.
        let centre = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]];
        let mesh = Mesh::new(centre, vec![[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]]).unwrap();
        assert!(!mesh.is_boundary_vertex(0));
        assert_eq!(mesh.connected_components(), 1);
        let open = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]];
        assert!(Mesh::new(open, vec![[0, 1, 2], [0, 2, 3]]).is_ok());
    }

    #[test]
    fn degenerate_means_collinear_to_double_precision_at_any_scale() {
        // The angle at the first corner of (0, 0), (1, 0), (1, h) is about h radians.
        let thin = |h: f64, s: f64| Mesh::new(vec![[0.0, 0.0], [s, 0.0], [s, s * h]], vec![[0, 1, 2]]);
        for s in [1.0, 1e-290, 1e-9, 3.7e12, 1e290] {
            assert!(thin(1e-12, s).is_ok(), "an angle of 1e-12 at scale {s}");
            assert!(thin(1.0, s).is_ok(), "a right triangle at scale {s}");
        }
        // A small triangle far from the origin is as good as near it.
        let far = vec![[1e6, 1e6], [1e6 + 1e-6, 1e6], [1e6, 1e6 + 1e-6]];
        assert!(Mesh::new(far, vec![[0, 1, 2]]).is_ok());
        // (0, 0), (1, 1), (3, 3 + 4.4e-16): the exact orientation is 4.4e-16, an angle of 7e-17
        // radians, within the rounding of the products (about 4.5e-16 * 6): no certain sign.
        let collinear = vec![[0.0, 0.0], [1.0, 1.0], [3.0, 3.0 + 4.4e-16]];
        assert_eq!(Mesh::new(collinear, vec![[0, 1, 2]]), Err(MeshError::Degenerate { triangle: 0 }));
    }

    #[test]
    fn coordinates_beyond_the_limits_are_refused_by_name() {
        let tri = |s: f64, x: f64| Mesh::new(vec![[x, 0.0], [x + s, 0.0], [x, s]], vec![[0, 1, 2]]);
        assert_eq!(tri(1.0, 2e300), Err(MeshError::CoordinateOutOfRange { vertex: 0, value: 2e300 }));
        assert!(tri(1e300, -1e300).is_ok());
        assert!(matches!(tri(1e-301, 0.0), Err(MeshError::TooSmall { .. })));
        assert!(tri(1e-300, 0.0).is_ok());
        assert!(tri(f64::INFINITY, 0.0).is_err());
    }

    #[test]
    fn two_separate_triangles_are_two_components() {
        let p = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [5.0, 0.0], [6.0, 0.0], [5.0, 1.0]];
        let mesh = Mesh::new(p, vec![[0, 1, 2], [3, 4, 5]]).unwrap();
        assert_eq!(mesh.connected_components(), 2);
    }
}
