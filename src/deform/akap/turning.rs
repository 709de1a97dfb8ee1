//! Turning handles: a handle that turns by `omega` (radians, counter-clockwise) in a step
//! while moving by `d` asks the field near it to be the Killing field of that rigid motion,
//! `u(p) = d + omega i (p - c)`, `c` the handle's point (the paper's linear holomorphic
//! fields with a purely imaginary `s`, eq. (13)). As eq. (3) asks `U(h) = u` softly, a
//! turning handle asks it of every vertex of its *neighbourhood* (its triangle's corners and
//! their neighbours), each with weight `lambda / |N|`: the penalty `lambda / |N| sum_(v in N)
//! |U_v - u(p_v)|^2` adds to the diagonal blocks of `K` only, so the pattern, and the
//! symbolic analysis, stay.
//!
//! A rigid motion of the whole shape is then reproduced exactly: its field is a Killing
//! field (`E_K = 0`) that meets every penalty, so it is step 1's minimiser, step 2 keeps it,
//! and the spiral step of a field with the same `s = omega i` on every edge is the rotation
//! `c + (p - c) e^(omega i)` (plus the translation) to rounding.

use crate::deform::handles::{neighbourhood, HandlePoint};
use crate::geometry::Point;
use crate::mesh::Mesh;

/// The vertices a turning handle carries with it, and their diagonal slots in `K`.
#[derive(Debug, Clone)]
pub(super) struct Neighbourhood {
    /// The handle triangle's corners and their neighbours, each once.
    pub(super) vertices: Vec<u32>,
    /// Per vertex, the slots of the x-x and y-y entries of its diagonal block.
    pub(super) slots: Vec<[usize; 2]>,
    /// Whether every vertex is on the boundary (then step 2 changes nothing for it).
    pub(super) boundary_only: bool,
}

impl Neighbourhood {
    /// The neighbourhood of `handle`; `diagonal(v)` gives the slots of vertex `v`'s block.
    pub(super) fn of(mesh: &Mesh, handle: &HandlePoint, diagonal: impl Fn(usize) -> [usize; 2]) -> Self {
        let vertices = neighbourhood(mesh, handle);
        let slots = vertices.iter().map(|&v| diagonal(v as usize)).collect();
        let boundary_only = vertices.iter().all(|&v| mesh.is_boundary_vertex(v as usize));
        Self { vertices, slots, boundary_only }
    }
}

/// The field of the rigid motion that moves `c` by `d` and turns by `omega`, at `p`.
pub(super) fn rigid_field(d: [f64; 2], omega: f64, c: Point, p: Point) -> [f64; 2] {
    [d[0] - omega * (p[1] - c[1]), d[1] + omega * (p[0] - c[0])]
}

/// Into `targets` (appended in handle order, neighbourhood order), the velocity each
/// turning handle asks of each vertex of its neighbourhood; handles that do not turn add
/// nothing.
pub(super) fn targets(
    handles: &[HandlePoint],
    neighbourhoods: &[Neighbourhood],
    positions: &[Point],
    velocities: &[[f64; 2]],
    turns: &[f64],
    targets: &mut Vec<[f64; 2]>,
) {
    targets.clear();
    for (((h, n), &d), &omega) in handles.iter().zip(neighbourhoods).zip(velocities).zip(turns) {
        if omega == 0.0 {
            continue;
        }
        let c = h.position(positions);
        targets.extend(n.vertices.iter().map(|&v| rigid_field(d, omega, c, positions[v as usize])));
    }
}
