//! Rigs for large shapes: an operator trained on a coarse simulation mesh (about two
//! thousand vertices) and carried to the shape's own fine mesh (tens of thousands), so
//! that training costs what the coarse mesh costs whatever the fine mesh's size, as art
//! already rides on meshes (`import::warp`).
//!
//! - [`simulation_mesh`]: the coarse mesh of a fine one: its boundary loops simplified to a
//!   tolerance of [`OUTLINE_TOLERANCE`] times the coarse edge length (never crossing, as
//!   `import::simplify` keeps them), each outline meshed by `triangulate_to_about` to its
//!   share of the vertices (by area).
//! - [`handles_on`]: the fine mesh's handles placed on the coarse mesh, where training
//!   puts them: each handle's rest position located in the coarse mesh (`warp`'s one
//!   location), its barycentric coordinates **clamped** (negative ones set to 0, the rest
//!   divided by their sum) so that a handle slightly outside the coarse mesh becomes a
//!   point of it.
//! - [`Embedding`]: every fine vertex located the same way, its barycentric coordinates
//!   **extrapolated** (kept as they are, negative outside): a fine boundary vertex slightly
//!   outside the coarse mesh (a curved outline simplified) follows the affine motion of
//!   its nearest coarse triangle, as imported art does; clamping would pull such vertices
//!   onto the coarse boundary and flatten the outline's detail. The coordinates are divided
//!   by their sum, so a fine vertex at a coarse vertex gets (1, 0, 0) exactly and with it
//!   the coarse vertex's position to the bit.
//! - [`Carried`] (`Operator::carried_to`, beside the operator): the coarse operator, the coarse mesh, the
//!   fine handles and the embedding as one operator of the fine mesh: its vertex count
//!   and handles are the fine mesh's, and its evaluation is the coarse pose (into a
//!   scratch buffer) then, per fine vertex, three products: allocation-free, about 0.1 ms
//!   for the coarse evaluation and 50,000 interpolations on top. Rigid motions carry over
//!   exactly (up to rounding): the interpolation is affine with weights summing to 1.

use super::fit_error::{check_finite, check_length, FitError};
use super::spatial::{resolve_points, MeshPoint};
use crate::geometry::{bounding_box, distance, polygon_area, Point};
use crate::import::simplify::simplify_rings;
use crate::import::warp::locate;
use crate::mesh::Mesh;
use crate::outline::Outline;
use crate::sweep::{sweep, Find};
use crate::triangulate::{triangulate_to_about, TriangulationOptions};

/// How far the simplified outline of [`simulation_mesh`] may stray from the fine mesh's
/// boundary, as a fraction of the coarse mesh's edge length: fine boundary vertices lie at
/// most this far (in coarse edges) outside the coarse mesh.
pub const OUTLINE_TOLERANCE: f64 = 0.125;

/// Segment comparisons the simplification's crossing checks may make (as the Cauchy-Green
/// cage's).
const MAX_SEGMENT_PAIRS: usize = 1 << 26;

/// Relative tolerance of the consistency checks (a carried rig read from a file): weights
/// summing to 1, handles and vertices where the coarse mesh puts them, in the mesh's size.
const TOLERANCE: f64 = 1e-9;

pub(super) fn carry_error(reason: impl Into<String>) -> FitError {
    FitError::Carry { reason: reason.into() }
}

/// The coarse simulation mesh of `fine` with about `vertices` vertices (module
/// documentation): `options`' other settings apply to each outline's meshing. Refuses a
/// mesh whose boundary loops meet (a puppet's overlapping sheets).
pub fn simulation_mesh(fine: &Mesh, vertices: usize, options: &TriangulationOptions) -> Result<Mesh, FitError> {
    let positions = fine.positions();
    let rings: Vec<Vec<Point>> =
        fine.boundary_loops().iter().map(|ring| ring.iter().map(|&v| positions[v as usize]).collect()).collect();
    let found = sweep(&rings, Find::First, usize::MAX).expect("an unlimited sweep finishes");
    if !found.meetings.is_empty() {
        return Err(carry_error("the mesh's boundary loops meet: it cannot be meshed coarse from its outline"));
    }
    let area: f64 = fine.triangles().iter().map(|t| fine.signed_triangle_area(t)).sum();
    let edge = (2.0 * area / (3f64.sqrt() * vertices.max(1) as f64)).sqrt();
    let simplified = simplify_rings(&rings, &found.parents, OUTLINE_TOLERANCE * edge, MAX_SEGMENT_PAIRS)
        .ok_or_else(|| carry_error("the mesh's outline is too complex to simplify"))?;
    // Loops run with the shape on their left: outer ones counter-clockwise, holes clockwise,
    // each hole's immediate container its outer loop.
    let outlines: Vec<Outline> = (0..simplified.len())
        .filter(|&r| polygon_area(&simplified[r]) > 0.0)
        .map(|r| Outline {
            outer: simplified[r].clone(),
            holes: (0..simplified.len())
                .filter(|&h| found.parents[h] == Some(r) && polygon_area(&simplified[h]) < 0.0)
                .map(|h| simplified[h].clone())
                .collect(),
        })
        .collect();
    let (mut all_positions, mut all_triangles) = (Vec::new(), Vec::new());
    for outline in &outlines {
        let own = outline.outer.iter().chain(outline.holes.iter().flatten()).count();
        let share = (vertices as f64 * outline.area() / area).round() as usize;
        let (mesh, _) = triangulate_to_about(outline, share.max(own).max(3), options)
            .map_err(|e| carry_error(format!("the simulation mesh could not be made: {e}")))?;
        let offset = all_positions.len() as u32;
        all_positions.extend_from_slice(mesh.positions());
        all_triangles.extend(mesh.triangles().iter().map(|t| t.map(|v| v + offset)));
    }
    Mesh::new(all_positions, all_triangles).map_err(|e| carry_error(format!("the simulation mesh is invalid: {e}")))
}

/// The rest positions of `handles` on `mesh` (checked as the deformers check handles).
fn handle_positions(mesh: &Mesh, handles: &[MeshPoint]) -> Result<Vec<Point>, FitError> {
    Ok(resolve_points(mesh, handles)?.iter().map(|h| h.position(mesh)).collect())
}

/// The handles of `fine` (points of it) placed on `coarse`, where a rig carried to `fine`
/// is trained: each in the coarse triangle that contains its rest position (or the
/// nearest), with clamped barycentric coordinates (module documentation).
pub fn handles_on(coarse: &Mesh, fine: &Mesh, handles: &[MeshPoint]) -> Result<Vec<MeshPoint>, FitError> {
    let points = handle_positions(fine, handles)?;
    let located = locate(coarse, &points).map_err(|e| carry_error(e.to_string()))?;
    Ok(located
        .into_iter()
        .map(|(triangle, w)| {
            let clamped = w.map(|x| x.max(0.0));
            let sum: f64 = clamped.iter().sum();
            MeshPoint::Inside { triangle, barycentric: clamped.map(|x| x / sum) }
        })
        .collect())
}

/// The least fraction of its area a coarse triangle keeps when [`simulation`] moves one of
/// its corners onto a handle.
const SNAP_AREA: f64 = 0.25;

/// The simulation mesh of `fine` ([`simulation_mesh`]) with each handle on a vertex of it:
/// the nearest coarse vertex not already a handle's moved onto the handle's rest position,
/// unless that leaves one of its triangles with less than a quarter of its area (then
/// the handle is a point of the mesh, as [`handles_on`] places it). A handle on a vertex is
/// pinned by the ground truth, its unknowns eliminated; a handle inside a triangle costs
/// two more sparse solves per Newton iteration (the range-space step), so on the figure
/// with nine handles training on a snapped mesh takes about half the time.
pub fn simulation(
    fine: &Mesh,
    handles: &[MeshPoint],
    vertices: usize,
    options: &TriangulationOptions,
) -> Result<(Mesh, Vec<MeshPoint>), FitError> {
    let coarse = simulation_mesh(fine, vertices, options)?;
    let points = handle_positions(fine, handles)?;
    let mut positions = coarse.positions().to_vec();
    let mut around = vec![Vec::new(); positions.len()];
    for (t, tri) in coarse.triangles().iter().enumerate() {
        tri.iter().for_each(|&v| around[v as usize].push(t));
    }
    let area = |positions: &[Point], t: usize| {
        let [a, b, c] = coarse.triangles()[t].map(|v| positions[v as usize]);
        (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
    };
    let mut taken = vec![false; positions.len()];
    let mut snapped = vec![None; points.len()];
    for (k, &p) in points.iter().enumerate() {
        let nearest = (0..positions.len())
            .filter(|&v| !taken[v])
            .min_by(|&a, &b| distance(positions[a], p).total_cmp(&distance(positions[b], p)));
        let Some(v) = nearest else { continue };
        let before: Vec<f64> = around[v].iter().map(|&t| area(&positions, t)).collect();
        let old = std::mem::replace(&mut positions[v], p);
        if around[v].iter().zip(&before).all(|(&t, &b)| area(&positions, t) >= SNAP_AREA * b) {
            taken[v] = true;
            snapped[k] = Some(v as u32);
        } else {
            positions[v] = old;
        }
    }
    let coarse = Mesh::new(positions, coarse.triangles().to_vec())
        .map_err(|e| carry_error(format!("the snapped simulation mesh is invalid: {e}")))?;
    let placed = handles_on(&coarse, fine, handles)?;
    let handles = snapped.iter().zip(placed).map(|(s, point)| s.map_or(point, MeshPoint::Vertex)).collect();
    Ok((coarse, handles))
}

/// Where each vertex of a fine mesh sits in a coarse one: a coarse triangle and barycentric
/// coordinates (extrapolated outside it; module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct Embedding {
    /// Per fine vertex, its coarse triangle.
    triangles: Vec<u32>,
    /// Per fine vertex, that triangle's vertices (read from the coarse mesh once).
    corners: Vec<[u32; 3]>,
    /// Per fine vertex, its barycentric coordinates in the order of the corners.
    weights: Vec<[f64; 3]>,
}

impl Embedding {
    /// Locates every vertex of `fine` in `coarse`. O((m + n) log m) for m coarse triangles
    /// and n fine vertices.
    pub fn new(coarse: &Mesh, fine: &Mesh) -> Result<Self, FitError> {
        let located = locate(coarse, fine.positions()).map_err(|e| carry_error(e.to_string()))?;
        let (triangles, weights) = located
            .into_iter()
            .map(|(t, w)| {
                let sum = w[0] + w[1] + w[2];
                (t, w.map(|x| x / sum))
            })
            .unzip();
        Self::from_parts(coarse, fine, triangles, weights)
    }

    /// An embedding as a file holds it, checked: a coarse triangle per fine vertex, finite
    /// weights summing to 1 that put each fine vertex where it is (to [`TOLERANCE`] of the
    /// meshes' size).
    pub(crate) fn from_parts(
        coarse: &Mesh,
        fine: &Mesh,
        triangles: Vec<u32>,
        weights: Vec<[f64; 3]>,
    ) -> Result<Self, FitError> {
        let n = fine.vertex_count();
        if triangles.len() != n || weights.len() != n {
            return Err(FitError::Length { what: "embedding", expected: n, found: triangles.len().min(weights.len()) });
        }
        let (lo, hi) = bounding_box(coarse.positions().iter().chain(fine.positions()).copied()).expect("vertices");
        let tolerance = TOLERANCE * distance(lo, hi);
        let mut corners = Vec::with_capacity(n);
        for (v, (&t, w)) in triangles.iter().zip(&weights).enumerate() {
            let Some(&tri) = coarse.triangles().get(t as usize) else {
                return Err(carry_error(format!("fine vertex {v} is in coarse triangle {t}, which does not exist")));
            };
            let sum = w[0] + w[1] + w[2];
            let [a, b, c] = tri.map(|i| coarse.positions()[i as usize]);
            let at = [0, 1].map(|k| w[0] * a[k] + w[1] * b[k] + w[2] * c[k]);
            // Written so that a NaN anywhere fails.
            let there = distance(at, fine.positions()[v]) <= tolerance;
            if !(w.iter().all(|x| x.is_finite()) && (sum - 1.0).abs() <= TOLERANCE && there) {
                return Err(carry_error(format!(
                    "the barycentric coordinates of fine vertex {v} do not put it where it is"
                )));
            }
            corners.push(tri);
        }
        Ok(Self { triangles, corners, weights })
    }

    /// The number of fine vertices.
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// Whether there is no fine vertex (never, for a valid mesh).
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// Each fine vertex's coarse triangle.
    pub fn triangles(&self) -> &[u32] {
        &self.triangles
    }

    /// Each fine vertex's barycentric coordinates in its coarse triangle.
    pub fn weights(&self) -> &[[f64; 3]] {
        &self.weights
    }

    /// Writes each fine vertex's position, interpolated from the coarse positions
    /// `coarse(v)` (x and y of coarse vertex v). Allocates nothing.
    #[inline]
    pub(crate) fn interpolate(&self, coarse: impl Fn(usize) -> [f64; 2], mut write: impl FnMut(usize, f64, f64)) {
        for (v, (corners, w)) in self.corners.iter().zip(&self.weights).enumerate() {
            let [a, b, c] = corners.map(|i| coarse(i as usize));
            write(v, w[0] * a[0] + w[1] * b[0] + w[2] * c[0], w[0] * a[1] + w[1] * b[1] + w[2] * c[1]);
        }
    }
}

/// What carries an operator trained on a coarse mesh to a fine one (module
/// documentation): the coarse mesh, the fine mesh's handles and the embedding.
#[derive(Debug, Clone)]
pub struct Carried {
    coarse: Mesh,
    handles: Vec<MeshPoint>,
    embedding: Embedding,
    /// Scratch: the coarse pose (2 numbers per coarse vertex).
    pub(crate) pose: Vec<f64>,
}

impl Carried {
    /// The coarse mesh the operator was trained on.
    pub fn mesh(&self) -> &Mesh {
        &self.coarse
    }

    /// The handles, as points of the fine mesh, in the operator's order.
    pub fn handles(&self) -> &[MeshPoint] {
        &self.handles
    }

    /// The fine mesh's vertices in the coarse mesh.
    pub fn embedding(&self) -> &Embedding {
        &self.embedding
    }

    /// A pose of the coarse mesh (2 numbers per coarse vertex; a ground truth solved there,
    /// say) carried to the fine mesh as the operator's poses are. Refuses a wrong length or
    /// a number that is not finite.
    pub fn carry_pose(&self, coarse: &[f64]) -> Result<Vec<f64>, FitError> {
        check_length("coarse pose", coarse, 2 * self.coarse.vertex_count())?;
        check_finite("coarse pose", coarse)?;
        let mut out = vec![0.0; 2 * self.embedding.len()];
        self.embedding.interpolate(
            |v| [coarse[2 * v], coarse[2 * v + 1]],
            |v, x, y| {
                out[2 * v] = x;
                out[2 * v + 1] = y;
            },
        );
        Ok(out)
    }
}

impl Carried {
    /// What carries an operator trained on `coarse` with its handles at `rest` (2 numbers
    /// each) to `fine`, checked: the handles as many as the operator's, points of `fine`
    /// whose places on `coarse` ([`handles_on`]) are the operator's (to [`TOLERANCE`] of
    /// the size), the embedding of `fine`'s vertices.
    pub(super) fn new(
        coarse: Mesh,
        fine: &Mesh,
        handles: Vec<MeshPoint>,
        embedding: Embedding,
        rest: &[f64],
    ) -> Result<Self, FitError> {
        if 2 * handles.len() != rest.len() {
            let (expected, found) = (rest.len(), 2 * handles.len());
            return Err(FitError::Length { what: "carried handles", expected, found });
        }
        if embedding.len() != fine.vertex_count() {
            return Err(FitError::Length { what: "embedding", expected: fine.vertex_count(), found: embedding.len() });
        }
        let placed = handle_positions(&coarse, &handles_on(&coarse, fine, &handles)?)?;
        let (lo, hi) = bounding_box(coarse.positions().iter().copied()).expect("vertices");
        let tolerance = TOLERANCE * distance(lo, hi);
        for (a, p) in placed.iter().enumerate() {
            let there = distance(*p, [rest[2 * a], rest[2 * a + 1]]) <= tolerance;
            if !there {
                return Err(carry_error(format!(
                    "handle {a} of the fine mesh is not where the operator's handle {a} is on the coarse mesh"
                )));
            }
        }
        let pose = vec![0.0; 2 * coarse.vertex_count()];
        Ok(Self { coarse, handles, embedding, pose })
    }
}
