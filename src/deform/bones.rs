//! Bones: straight segments drawn on the shape whose triangles move as one rigid body, for
//! limbs. A bone is given by its two ends, points of the mesh (a triangle and barycentric
//! coordinates, as handles are), and covers every triangle its segment meets in the pose it
//! is set in. Those triangles' vertices are its *body*; their positions then are its
//! reference shape.
//!
//! The methods that have bones (AKAP and ARAP) do two things with them:
//! - the body's triangles weigh [`BONE_STIFFNESS`] in the energy (or the painted stiffness
//!   where that is larger), so the solve itself already keeps them nearly rigid and the
//!   shape around them follows;
//! - after each step (each local/global iteration for ARAP) the body is put exactly where
//!   the rigid motion that best fits its vertices' new places (2D Procrustes, in closed form)
//!   takes its reference shape. So the body is always a rigid image of its reference: the
//!   segment stays straight and keeps its length, to rounding, however the handles pull,
//!   and a handle on the bone moves and turns it as a whole.
//!
//! Two bones may not share a vertex: a joint is a ring of free triangles between them.

use crate::deform::error::DeformError;
use crate::deform::handles::{self, diagonal, HandlePoint};
use crate::geometry::{normalising_exponent, scale_by_power_of_two, Point};
use crate::mesh::Mesh;

/// The stiffness a bone's triangles weigh in the energy at least: the top of
/// [`STIFFNESS_RANGE`](super::STIFFNESS_RANGE).
pub const BONE_STIFFNESS: f64 = 1000.0;

/// The bones of a deformer, with each one's rigid body.
#[derive(Debug, Clone, Default)]
pub(crate) struct Bones {
    /// Two per bone: its ends.
    ends: Vec<HandlePoint>,
    bodies: Vec<Body>,
}

/// The vertices one bone carries and their reference shape.
#[derive(Debug, Clone)]
struct Body {
    /// The triangles the bone's segment meets, in increasing order.
    triangles: Vec<u32>,
    /// Their vertices, each once, in increasing order.
    vertices: Vec<u32>,
    /// The vertices' positions when the bone was set, less their mean.
    reference: Vec<Point>,
}

impl Bones {
    /// Bones with ends given as `set_handle_points` takes points, two per bone (from, to),
    /// laid on the mesh at `positions`. Refused for an odd number of points, a point that is
    /// not in the mesh, a bone whose ends are at one point or whose segment leaves the
    /// shape, and two bones that share a vertex.
    pub(crate) fn new(
        mesh: &Mesh,
        positions: &[Point],
        triangles: &[u32],
        barycentric: &[[f64; 3]],
    ) -> Result<Self, DeformError> {
        if !triangles.len().is_multiple_of(2) {
            return Err(DeformError::Length {
                what: "bone triangles",
                expected: triangles.len() + 1,
                found: triangles.len(),
                per: 2,
                items: "bones",
            });
        }
        let ends = handles::in_triangles(mesh, triangles, barycentric).map_err(bone_point_error)?;
        let size = diagonal(positions);
        let e = normalising_exponent(positions.iter().copied());
        let scaled: Vec<Point> = positions.iter().map(|p| p.map(|x| scale_by_power_of_two(x, e))).collect();
        let mut owner = vec![usize::MAX; mesh.vertex_count()];
        let mut bodies = Vec::with_capacity(ends.len() / 2);
        for (bone, pair) in ends.chunks_exact(2).enumerate() {
            let [a, b] = [pair[0].position(&scaled), pair[1].position(&scaled)];
            if libm::hypot(b[0] - a[0], b[1] - a[1]) <= 1e-9 * scale_by_power_of_two(size, e) {
                return Err(DeformError::InvalidBone { bone, reason: "its ends are at one point" });
            }
            let triangles = covered(mesh, &scaled, a, b).ok_or(DeformError::InvalidBone {
                bone,
                reason: "its segment leaves the shape; draw it inside the shape",
            })?;
            let mut vertices: Vec<u32> =
                triangles.iter().flat_map(|&t| mesh.triangles()[t as usize]).collect::<Vec<u32>>();
            vertices.sort_unstable();
            vertices.dedup();
            for &v in &vertices {
                let other = std::mem::replace(&mut owner[v as usize], bone);
                if other != usize::MAX && other != bone {
                    return Err(DeformError::InvalidBone {
                        bone,
                        reason: "it touches another bone (they share vertices); leave a joint of free triangles \
                                 between bones",
                    });
                }
            }
            let count = vertices.len() as f64;
            let mut mean = [0.0, 0.0];
            for &v in &vertices {
                mean[0] += positions[v as usize][0] / count;
                mean[1] += positions[v as usize][1] / count;
            }
            let reference =
                vertices.iter().map(|&v| [positions[v as usize][0] - mean[0], positions[v as usize][1] - mean[1]]);
            bodies.push(Body { triangles, vertices: vertices.clone(), reference: reference.collect() });
        }
        Ok(Self { ends, bodies })
    }

    /// Whether there are no bones.
    pub(crate) fn is_empty(&self) -> bool {
        self.bodies.is_empty()
    }

    /// The bones' ends, two per bone, as `Deformer::bone_points` gives them.
    pub(crate) fn points(&self) -> (Vec<u32>, Vec<[f64; 3]>) {
        handles::as_points(self.ends.iter())
    }

    /// The stiffness each triangle weighs: the painted value (1 where none), raised to
    /// [`BONE_STIFFNESS`] on the bones' triangles; `None` when nothing is painted and there
    /// are no bones.
    pub(crate) fn stiffness(&self, painted: Option<&[f64]>, triangle_count: usize) -> Option<Vec<f64>> {
        if self.is_empty() {
            return painted.map(<[f64]>::to_vec);
        }
        let mut values = painted.map_or_else(|| vec![1.0; triangle_count], <[f64]>::to_vec);
        for &t in self.bodies.iter().flat_map(|b| &b.triangles) {
            values[t as usize] = values[t as usize].max(BONE_STIFFNESS);
        }
        Some(values)
    }

    /// Puts each bone's body where the rigid motion that best fits its vertices at
    /// `positions` (least squares) takes its reference shape.
    pub(crate) fn project(&self, positions: &mut [Point]) {
        for body in &self.bodies {
            fit_rigidly(body, positions);
        }
    }
}

/// The rigid motion `p -> m + R q` that best fits the body's reference `q_i` to its
/// vertices' places `p_i`: `m` their mean, and `R`'s angle that of `sum (q_i . d_i, q_i x d_i)`
/// with `d_i = p_i - m` (2D Procrustes). Both sums are taken on values scaled by powers of
/// two, so that neither overflows nor underflows; only their direction matters. Vertices
/// whose places do not fix an angle (all at their mean) are left where they are.
fn fit_rigidly(body: &Body, positions: &mut [Point]) {
    let count = body.vertices.len() as f64;
    let mut mean = [0.0, 0.0];
    for &v in &body.vertices {
        mean[0] += positions[v as usize][0] / count;
        mean[1] += positions[v as usize][1] / count;
    }
    let offset = |v: u32| [positions[v as usize][0] - mean[0], positions[v as usize][1] - mean[1]];
    let ed = normalising_exponent(body.vertices.iter().map(|&v| offset(v)));
    let eq = normalising_exponent(body.reference.iter().copied());
    let [mut dot, mut cross] = [0.0, 0.0];
    for (&v, q) in body.vertices.iter().zip(&body.reference) {
        let d = offset(v).map(|x| scale_by_power_of_two(x, ed));
        let q = q.map(|x| scale_by_power_of_two(x, eq));
        dot += q[0] * d[0] + q[1] * d[1];
        cross += q[0] * d[1] - q[1] * d[0];
    }
    let length = libm::hypot(dot, cross);
    if !(length > 0.0 && length.is_finite()) {
        return;
    }
    let [c, s] = [dot / length, cross / length];
    for (&v, q) in body.vertices.iter().zip(&body.reference) {
        positions[v as usize] = [mean[0] + c * q[0] - s * q[1], mean[1] + s * q[0] + c * q[1]];
    }
}

/// The triangles (at `positions`, scaled so the largest coordinate is about 1) that the
/// segment from `a` to `b` meets, touching included to about 1e-12 of the shape's size, or
/// `None` when the triangles do not cover the whole segment (it crosses a hole or leaves
/// the outline). Triangles of no area at these positions are passed over. O(triangles).
fn covered(mesh: &Mesh, positions: &[Point], a: Point, b: Point) -> Option<Vec<u32>> {
    let size = diagonal(positions);
    let direction = [b[0] - a[0], b[1] - a[1]];
    let cross = |u: Point, v: Point| u[0] * v[1] - u[1] * v[0];
    let mut met = Vec::new();
    let mut spans = Vec::new();
    for (t, corners) in mesh.triangles().iter().enumerate() {
        let p = corners.map(|v| positions[v as usize]);
        let area = cross([p[1][0] - p[0][0], p[1][1] - p[0][1]], [p[2][0] - p[0][0], p[2][1] - p[0][1]]);
        if area == 0.0 {
            continue;
        }
        let side = area.signum();
        // The segment's parameters t in [0, 1] with a + t (b - a) on the inner side of every edge.
        let [mut lo, mut hi] = [0.0f64, 1.0f64];
        for k in 0..3 {
            let (from, to) = (p[k], p[(k + 1) % 3]);
            let edge = [to[0] - from[0], to[1] - from[1]];
            let tolerance = 1e-12 * size * libm::hypot(edge[0], edge[1]);
            let at_a = side * cross(edge, [a[0] - from[0], a[1] - from[1]]) + tolerance;
            let slope = side * cross(edge, direction);
            if slope > 0.0 {
                lo = lo.max(-at_a / slope);
            } else if slope < 0.0 {
                hi = hi.min(-at_a / slope);
            } else if at_a < 0.0 {
                hi = -1.0;
            }
        }
        if lo <= hi {
            met.push(t as u32);
            spans.push([lo, hi]);
        }
    }
    spans.sort_unstable_by(|x, y| x[0].total_cmp(&y[0]));
    let mut reached = 0.0f64;
    for [lo, hi] in spans {
        if lo > reached + 1e-9 {
            return None;
        }
        reached = reached.max(hi);
    }
    (reached >= 1.0 - 1e-9).then_some(met)
}

/// A bone end's error from the handle checks, named by its bone.
fn bone_point_error(error: DeformError) -> DeformError {
    match error {
        DeformError::TriangleOutOfRange { handle, .. } => {
            DeformError::InvalidBone { bone: handle / 2, reason: "an end names a triangle that does not exist" }
        }
        DeformError::InvalidBarycentric { handle, .. } => DeformError::InvalidBone {
            bone: handle / 2,
            reason: "an end's barycentric coordinates are not finite, at least 0 and summing to 1",
        },
        DeformError::Length { expected, found, per, .. } => {
            DeformError::Length { what: "bone barycentric", expected, found, per, items: "bone ends" }
        }
        other => other,
    }
}
