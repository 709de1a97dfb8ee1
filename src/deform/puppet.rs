//! Puppets: one mesh made of sheets, one per part of a layered drawing (a torso, a head, an
//! arm, a hat), that may overlap at rest and are coupled at joints.
//!
//! A [`Puppet`] names each part's triangles and its depth (larger is in front), and its
//! joints: a hinge at one point of two parts, the front part and the part behind it. A
//! deformer of a puppet ([`super::Deformer::with_puppet`]) keeps the two sheets' points of
//! each joint together, which is a constraint between a point of one sheet and a point of
//! another, written like a handle between two sheets: the penalty
//! `mu |x_front(p) - x_back(p)|^2` on the barycentric blends of the two triangles the point
//! lies in (AKAP on the velocities, closing the current gap; ARAP on the positions). It adds
//! the 3 x 3 vertex blocks between the two triangles to the systems' patterns, which stay
//! sparse, symmetric and positive definite, analysed once per joint set.
//!
//! Sheets may be free (a hat touching nothing, no handle on it) or held by one hinge alone
//! with nothing to turn them, which leaves the systems singular. AKAP adds a tiny
//! least-motion term ([`LEAST_MOTION`]) to every unknown, so that a free sheet stays
//! (exactly: its right-hand side is zero) and no system is ever singular, and a small term
//! against turning ([`AKAP_TURN_WEIGHT`]), so that a sheet on one hinge follows it without
//! turning. ARAP pins the vertices of sheets no handle holds (through joints or the mesh)
//! where they are, and its rotations already stay unless something turns them. A mesh
//! without a puppet has none of this, and its results are unchanged.

use super::error::DeformError;
use super::handles::HandlePoint;
use crate::geometry::Point;
use crate::mesh::Mesh;

/// The weight of a joint's penalty in AKAP's systems (whose entries are dimensionless, about
/// 1 to 10 per vertex): stiff enough that the two points of a joint stay together to a tiny
/// fraction of the shape's size, and the gap left by a step is closed in the next.
pub const AKAP_JOINT_WEIGHT: f64 = 1e4;

/// The least-motion term of AKAP's systems for a puppet, relative to their typical diagonal
/// entry: added to every diagonal entry of its matrix (the velocity's squared length
/// weighted by it). It decides only what nothing else does: where a free sheet goes
/// (nowhere: its right-hand side is zero, so its velocity is exactly zero).
pub const LEAST_MOTION: f64 = 1e-8;

/// AKAP's rotation term for a puppet: the weight of the integral of the velocity field's
/// curl squared, beside the Killing energy's (whose weights are 2 to 4). A Killing field
/// may turn at no cost, so without it a sheet held by one hinge alone would take the least
/// motion by turning partly about its centre; with it, it follows its hinge without
/// turning (a head on a torso moved half its width turns by about 0.005 rad). A part that
/// something turns (a handle, a joint) turns all the same: against the handles' weight
/// (100 by default) the term is negligible, and a turning handle at a shoulder turns an arm
/// to within 2% of the angle asked.
pub const AKAP_TURN_WEIGHT: f64 = 1e-4;

/// The most parts a puppet read from a file or a drawing has (the layers of an SVG, the
/// parts of a mesh file or an operator file).
pub const MAX_PARTS: usize = 256;

/// The longest name of a part that the bindings and the mesh files take, in bytes.
pub const MAX_PART_NAME_BYTES: usize = 1024;

/// One part of a puppet: its sheet's triangles, its name and its depth.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// The part's name (from the drawing's layer: its label or id).
    pub name: String,
    /// The mesh's triangles that make up the part's sheet.
    pub triangles: Vec<u32>,
    /// The drawing order: larger is in front.
    pub depth: i32,
}

/// A joint: a hinge at one point of two parts, about which the front part turns freely,
/// both sheets keeping that point together.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Joint {
    /// Where the joint is at rest (a point of both parts' sheets).
    pub point: Point,
    /// The parts it joins, `[front, back]`, as indices into [`Puppet::parts`].
    pub parts: [usize; 2],
}

/// A mesh's parts and joints.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Puppet {
    /// The parts: together they hold every triangle of the mesh exactly once.
    pub parts: Vec<Part>,
    /// The joints.
    pub joints: Vec<Joint>,
}

/// A puppet's joints as the solvers take them: per joint its point on the front part's
/// sheet and on the back part's, and whether the mesh is a puppet at all (then every system
/// gets the least-motion term).
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Joins {
    pub(crate) points: Vec<[HandlePoint; 2]>,
    pub(crate) puppet: bool,
}

impl Joins {
    /// The joint's coefficients on its vertices: `+w` on the front triangle's corners,
    /// `-w` on the back's (`x_front - x_back = sum c_k x_(v_k)`).
    pub(crate) fn blend(pair: &[HandlePoint; 2]) -> [(u32, f64); 6] {
        let [a, b] = pair;
        [
            (a.vertices[0], a.weights[0]),
            (a.vertices[1], a.weights[1]),
            (a.vertices[2], a.weights[2]),
            (b.vertices[0], -b.weights[0]),
            (b.vertices[1], -b.weights[1]),
            (b.vertices[2], -b.weights[2]),
        ]
    }

    /// The vertex pairs the joints couple that the mesh's edges do not: the extra blocks
    /// of the systems' patterns.
    pub(crate) fn extra_pairs(&self) -> Vec<[u32; 2]> {
        let mut pairs = Vec::new();
        for pair in &self.points {
            for &(v, _) in &Self::blend(pair) {
                for &(w, _) in &Self::blend(pair) {
                    if v != w {
                        pairs.push([v, w]);
                    }
                }
            }
        }
        pairs.sort_unstable();
        pairs.dedup();
        pairs
    }
}

impl Puppet {
    /// Checks the puppet against `mesh` (its rest pose) and places its joints: every
    /// triangle in exactly one part, each joint joining two different parts in range at a
    /// finite point that lies on both parts' sheets (within 1e-9 of the mesh's size).
    pub(crate) fn joins(&self, mesh: &Mesh) -> Result<Joins, DeformError> {
        self.part_of_triangles(mesh)?;
        self.check_joints()?;
        let size = super::handles::diagonal(mesh.positions());
        let points = self
            .joints
            .iter()
            .enumerate()
            .map(|(joint, j)| {
                let place = |part: usize| {
                    locate(mesh, &self.parts[part].triangles, j.point, 1e-9 * size).ok_or_else(|| {
                        DeformError::InvalidJoint {
                            joint,
                            reason: format!(
                                "its point ({}, {}) is not on part {part} (\"{}\")",
                                j.point[0], j.point[1], self.parts[part].name
                            ),
                        }
                    })
                };
                Ok([place(j.parts[0])?, place(j.parts[1])?])
            })
            .collect::<Result<Vec<_>, DeformError>>()?;
        Ok(Joins { points, puppet: true })
    }

    /// Checks what can be checked without the rest positions, for a mesh of
    /// `triangle_count` triangles (say, to write a pose of the puppet's mesh): every triangle
    /// in exactly one part, each joint joining two different parts in range at a finite
    /// point. Whether each joint's point lies on both parts needs the rest mesh
    /// ([`super::Deformer::with_puppet`] checks it).
    pub fn check_indices(&self, triangle_count: usize) -> Result<(), DeformError> {
        self.part_of(triangle_count)?;
        self.check_joints()
    }

    /// Each joint joins two different parts in range at a finite point.
    fn check_joints(&self) -> Result<(), DeformError> {
        for (joint, j) in self.joints.iter().enumerate() {
            let invalid = |reason: String| DeformError::InvalidJoint { joint, reason };
            if !(j.point[0].is_finite() && j.point[1].is_finite()) {
                return Err(invalid(format!("its point {:?} is not finite", j.point)));
            }
            for &part in &j.parts {
                if part >= self.parts.len() {
                    return Err(invalid(format!(
                        "it names part {part}, but the puppet has {} parts",
                        self.parts.len()
                    )));
                }
            }
            if j.parts[0] == j.parts[1] {
                return Err(invalid(format!("it joins part {} to itself", j.parts[0])));
            }
        }
        Ok(())
    }

    /// The part of each triangle, checking that the parts hold every triangle exactly once.
    pub fn part_of_triangles(&self, mesh: &Mesh) -> Result<Vec<u32>, DeformError> {
        self.part_of(mesh.triangle_count())
    }

    /// The part of each of `count` triangles, checking that the parts hold each exactly once.
    fn part_of(&self, count: usize) -> Result<Vec<u32>, DeformError> {
        if self.parts.is_empty() {
            return Err(DeformError::InvalidParts { reason: "a puppet needs at least one part".into() });
        }
        const NONE: u32 = u32::MAX;
        let mut part_of = vec![NONE; count];
        for (p, part) in self.parts.iter().enumerate() {
            for &t in &part.triangles {
                let Some(slot) = part_of.get_mut(t as usize) else {
                    return Err(DeformError::InvalidParts {
                        reason: format!("part {p} names triangle {t}, but the mesh has {count} triangles"),
                    });
                };
                if *slot != NONE {
                    return Err(DeformError::InvalidParts {
                        reason: format!("triangle {t} is in part {} and in part {p}", *slot),
                    });
                }
                *slot = p as u32;
            }
        }
        if let Some(t) = part_of.iter().position(|&p| p == NONE) {
            return Err(DeformError::InvalidParts { reason: format!("triangle {t} is in no part") });
        }
        Ok(part_of)
    }
}

/// The point `p` of the triangles `triangles` of `mesh` at rest: the triangle that holds it
/// best (largest smallest barycentric coordinate), if one holds it within `tolerance`, with
/// its barycentric coordinates clamped to the triangle.
fn locate(mesh: &Mesh, triangles: &[u32], p: Point, tolerance: f64) -> Option<HandlePoint> {
    let x = mesh.positions();
    let mut best: Option<(f64, usize, [f64; 3])> = None;
    for &t in triangles {
        let corners = mesh.triangles()[t as usize];
        let [a, b, c] = corners.map(|v| x[v as usize]);
        let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if area <= 0.0 {
            continue;
        }
        let signed = |u: Point, v: Point| (u[0] - p[0]) * (v[1] - p[1]) - (u[1] - p[1]) * (v[0] - p[0]);
        let w = [signed(b, c) / area, signed(c, a) / area, signed(a, b) / area];
        let least = w[0].min(w[1]).min(w[2]);
        // Distance outside the triangle, about: the negative weight times the height.
        let longest =
            [a, b, c].iter().zip([b, c, a]).map(|(u, v)| libm::hypot(u[0] - v[0], u[1] - v[1])).fold(0.0, f64::max);
        let outside = -least * area / longest.max(f64::MIN_POSITIVE);
        if outside > tolerance {
            continue;
        }
        if best.is_none_or(|(l, _, _)| least > l) {
            best = Some((least, t as usize, w));
        }
    }
    best.map(|(_, triangle, w)| {
        let w = w.map(|x| x.max(0.0));
        let sum = w[0] + w[1] + w[2];
        HandlePoint { triangle, vertices: mesh.triangles()[triangle], weights: w.map(|x| x / sum) }
    })
}

/// Each vertex's piece (numbered from 0) of the graph of the mesh's edges and the extra
/// vertex pairs `extra` (a puppet's joints): union-find with path halving.
pub(crate) fn pieces(mesh: &Mesh, extra: &[[u32; 2]]) -> Vec<u32> {
    let n = mesh.vertex_count();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut v: usize) -> usize {
        while parent[v] != v {
            parent[v] = parent[parent[v]];
            v = parent[v];
        }
        v
    }
    for [a, b] in mesh.edges().chain(extra.iter().copied()) {
        let (a, b) = (root(&mut parent, a as usize), root(&mut parent, b as usize));
        if a != b {
            parent[a.max(b)] = a.min(b);
        }
    }
    let mut number = vec![u32::MAX; n];
    let mut count = 0;
    (0..n)
        .map(|v| {
            let r = root(&mut parent, v);
            if number[r] == u32::MAX {
                number[r] = count;
                count += 1;
            }
            number[r]
        })
        .collect()
}
