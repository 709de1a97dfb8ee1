//! As-rigid-as-possible deformation for comparison with AKAP: the per-triangle "elements"
//! energy of Liu, Zhang, Xu, Gotsman and Gortler (SGP 2008) with cotangent weights,
//! minimised by Sorkine and Alexa's local/global iteration (SGP 2007).
//!
//! With rest positions `x`, current positions `u`, and per triangle `t` a rotation `R_t`,
//!
//! `E(u, R) = 1/2 sum_t sum_(i,j) cot(theta_t^ij) |(u_i - u_j) - R_t (x_i - x_j)|^2
//!          + w/2 sum_h |sum_k beta_hk u_hk - target_h|^2`,
//!
//! the inner sum over the three edges `(i, j)` of `t`, `theta_t^ij` the rest angle opposite
//! the edge. The first part equals `sum_t A_t |J_t - R_t|_F^2` (`J_t` the Jacobian of the
//! piecewise-linear map on triangle `t`, `A_t` its rest area), so every triangle is as
//! close to a rotation as it can be.
//!
//! - **Local step**: for fixed `u`, each `R_t` maximises `tr(R^T S_t)` with
//!   `S_t = sum cot(theta) (u_i - u_j)(x_i - x_j)^T = 2 A_t J_t`: in 2D the rotation by
//!   `atan2(S_10 - S_01, S_00 + S_11)`, the polar factor of `J_t`.
//! - **Global step**: for fixed rotations, `L u = b` for x and y separately, with `L` the
//!   cotangent Laplacian (`L_ij = -sum cot`, `L_ii = sum_j sum cot`) and
//!   `b_i = sum_t sum_j cot(theta_t^ij) R_t (x_i - x_j)`.
//!
//! Each step lowers `E` (each is an exact minimisation over its own unknowns), so the
//! energy never increases over iterations.
//!
//! **Constraints.** A handle at a vertex (or at a point whose barycentric weight at one
//! vertex is 1) is a hard constraint, by elimination: that vertex's row and column of the
//! matrix become the identity row and column, its known position moves to the right-hand
//! side of the other rows (`b_f -= A_fc target_c`), and the solve returns it unchanged
//! (several handles on one vertex pin it at the mean of their targets).
//! A handle strictly inside a triangle (or on an edge) is a stiff penalty, the second part
//! of `E`, with `w = 10^6` times the mean diagonal entry of `L` (dimensionless, like the
//! cotangent weights): it adds `w beta_hk beta_hl` to entries between vertices of one
//! triangle, which are already in the pattern. Either way the matrix stays symmetric
//! positive definite (one handle removes the translations that are `L`'s null space) and
//! its pattern is that of the vertex graph: the symbolic analysis runs once per mesh, the
//! numeric factorisation once per handle set (in the first step after the handles change),
//! and every iteration only solves.
//!
//! Each step sets the targets (current handle position plus velocity)
//! and runs the configured iterations warm-started from the current pose; buffers are
//! sized when the mesh or the handle set changes, so a step allocates nothing.

use std::sync::Arc;

use sprs::CsMat;

use super::error::{out_of_memory, DeformError};
use super::handles::{diagonal, in_range, HandlePoint};
pub use super::method::IterationReport;
use super::method::{copy_into, Abilities, Build, Checkpoint, Orders, Shared, Solve, Timings};
pub use super::options::{ArapOptions, MAX_CONVERGENCE_ITERATIONS, MAX_ITERATIONS};
use super::pattern::BlockPattern;
use super::puppet::Joins;
use crate::geometry::{normalising_exponent, power_of_two, scale_by_power_of_two, Point};
use crate::mesh::Mesh;
use crate::sparse::{fill_reducing_order, Numeric, Ordering, Symbolic};

mod laplacian;
mod turning;
mod weights;

use laplacian::laplacian_of;

const NONE: usize = usize::MAX;

/// A weight this close to 1 puts a handle on a vertex (a hard constraint).
const AT_VERTEX: f64 = 1e-12;

/// The ARAP solver of one mesh (the state it derives from the mesh and the handles; the
/// mesh, handles and pose are its [`Deformer`](crate::deform::Deformer)'s).
#[derive(Debug, Clone)]
pub struct ArapSolver {
    options: ArapOptions,
    /// The rest shape's bounding-box diagonal.
    size: f64,
    /// The local and global steps work on positions scaled by `2^unit`, the power of two
    /// that brings the rest mesh's largest coordinate into [1, 2) (exact): the products of
    /// edges in `S` and the right-hand sides stay far from overflow and underflow. Within
    /// the coordinate limits `unit` is between -996 and 998, so `2^unit` and `2^-unit` are
    /// normal doubles, multiplied by directly.
    unit: i32,
    /// Per triangle, the cotangent of the rest angle at corner k, which weights the edge
    /// opposite it, from `v[k + 1]` to `v[k + 2]`, times the triangle's stiffness.
    cot: Vec<[f64; 3]>,
    /// The cotangents of the rest mesh (stiffness 1).
    rest_cot: Vec<[f64; 3]>,
    /// Per triangle, the rest edge vectors `x[v[k + 1]] - x[v[k + 2]]`, scaled by `2^unit`.
    rest_edges: Vec<[Point; 3]>,
    /// The cotangent Laplacian on the pattern of `matrix` (full symmetric CSC storage).
    laplacian: Vec<f64>,
    /// Per triangle, the slots of the 9 entries `(v[i], v[j])` (index `3 i + j`).
    triangle_slots: Vec<[usize; 9]>,
    /// A puppet's joints: per entry of `x_front - x_back = J x` squared, the slot and
    /// `c_v c_w` (the matrix gets the handles' penalty times it, so joints hold like handles).
    joint_entries: Vec<(usize, f64)>,
    /// A puppet's joints: each one's six vertices and blend coefficients.
    joints: Vec<[(u32, f64); 6]>,
    /// A puppet's pieces: per vertex, its piece of the mesh's sheets joined at the joints
    /// (empty for a single shape).
    pieces: Vec<u32>,
    /// The vertices of pieces that no handle holds, pinned where they are (a puppet's free
    /// sheets, which nothing moves: ARAP's matrix would be singular on them).
    frozen: Vec<usize>,
    /// `L` plus penalties, with pinned rows and columns replaced by the identity.
    matrix: CsMat<f64>,
    numeric: Numeric,
    /// Whether `numeric` holds the factor of the current handle set.
    factored: bool,
    penalty: f64,
    /// Per handle, the vertex it pins (a hard constraint), or `NONE` for a penalty handle.
    pinned: Vec<usize>,
    /// Per vertex: the number of handles pinning it (0 for a free vertex).
    pin_count: Vec<u32>,
    /// Entries coupling a free row to a pinned column: (value, row, column).
    coupling: Vec<(f64, usize, usize)>,
    targets: Vec<Point>,
    /// Per triangle `(cos, sin)` of the rotation of the last local step.
    rotations: Vec<[f64; 2]>,
    /// The displacement of the last step, per vertex.
    field: Vec<[f64; 2]>,
    report: IterationReport,
    // Scratch for a step, committed only on success.
    next_rotations: Vec<[f64; 2]>,
    next_targets: Vec<Point>,
    pin_target: Vec<Point>,
    rhs_x: Vec<f64>,
    rhs_y: Vec<f64>,
    /// During a step in which handles turn: each turning handle's neighbourhood vertex and
    /// its target in the rotated frame (see `turning`); empty otherwise.
    turning: Vec<(usize, Point)>,
}

impl ArapSolver {
    /// The fill-reducing order of the Laplacian (one system), the bulk of the set-up.
    pub fn orders(mesh: &Mesh) -> Orders {
        let (ptr, adj) = mesh.vertex_graph();
        Orders { systems: vec![fill_reducing_order(&ptr, &adj, mesh.positions(), 1)] }
    }

    /// The solver for a connected mesh with the order from [`Self::orders`]: cotangent
    /// weights, the Laplacian, its symbolic analysis, and every buffer.
    fn new(mesh: &Mesh, options: ArapOptions, joins: &Joins, orders: &Orders) -> Result<Self, DeformError> {
        check_options(&options)?;
        let n = mesh.vertex_count();
        orders.check(&[n])?;
        let m = mesh.triangle_count();
        let x = mesh.positions();

        // Pattern: column v holds rows N(v), v and the vertices a joint couples v with,
        // ascending (full symmetric storage).
        let pattern = BlockPattern::with_pairs(mesh, 1, &joins.extra_pairs());
        let slot = |row: usize, col: usize| pattern.slot(row, col).expect("a vertex pair of the pattern");
        let all_slots = pattern.triangle_slots(mesh);
        let mut cot = Vec::with_capacity(m);
        let mut rest_edges = Vec::with_capacity(m);
        // Cotangents and rest edges from the mesh scaled by `2^unit` (exact): free of
        // overflow and underflow at any scale, and the rest edges in the units the local and
        // global steps work in.
        // (Clamped: a validated mesh never needs it, and 2^unit and 2^-unit are then normal.)
        let unit = normalising_exponent(x.iter().copied()).clamp(-1022, 1022);
        for t in mesh.triangles() {
            let p = t.map(|v| x[v as usize].map(|c| scale_by_power_of_two(c, unit)));
            let mut c = [0.0; 3];
            let mut e = [[0.0; 2]; 3];
            for k in 0..3 {
                let (a, b) = (sub(p[(k + 1) % 3], p[k]), sub(p[(k + 2) % 3], p[k]));
                c[k] = (a[0] * b[0] + a[1] * b[1]) / (a[0] * b[1] - a[1] * b[0]);
                e[k] = sub(p[(k + 1) % 3], p[(k + 2) % 3]);
            }
            cot.push(c);
            rest_edges.push(e);
        }
        let (laplacian, penalty) = laplacian_of(&cot, &all_slots, pattern.nnz(), n, |v| slot(v, v));

        let joints: Vec<[(u32, f64); 6]> = joins.points.iter().map(Joins::blend).collect();
        let mut joint_entries = Vec::with_capacity(36 * joints.len());
        for blend in &joints {
            for &(v, cv) in blend {
                for &(w, cw) in blend {
                    joint_entries.push((slot(v as usize, w as usize), cv * cw));
                }
            }
        }
        let pieces = match joins.puppet {
            true => pieces(mesh, &joins.extra_pairs()),
            false => Vec::new(),
        };
        let matrix = pattern.matrix(laplacian.clone());
        let best = Symbolic::analyse(matrix.view(), &Ordering::Given(orders.systems[0].clone()))
            .expect("a checked vertex order is a valid ordering of the vertex Laplacian");

        Ok(Self {
            options,
            unit,
            size: diagonal(x),
            rest_cot: cot.clone(),
            cot,
            rest_edges,
            laplacian,
            triangle_slots: all_slots,
            matrix,
            numeric: Numeric::try_new(Arc::new(best)).map_err(out_of_memory)?,
            factored: false,
            penalty,
            joint_entries,
            joints,
            pieces,
            frozen: Vec::new(),
            pinned: Vec::new(),
            pin_count: vec![0; n],
            coupling: Vec::new(),
            targets: Vec::new(),
            rotations: vec![[1.0, 0.0]; m],
            field: vec![[0.0; 2]; n],
            report: IterationReport::default(),
            next_rotations: vec![[1.0, 0.0]; m],
            next_targets: Vec::new(),
            pin_target: vec![[0.0; 2]; n],
            turning: Vec::new(),
            rhs_x: vec![0.0; n],
            rhs_y: vec![0.0; n],
        })
    }

    /// The settings.
    pub fn options(&self) -> ArapOptions {
        self.options
    }

    /// The penalty weight `w` of handles inside triangles.
    pub fn penalty_weight(&self) -> f64 {
        self.penalty
    }

    /// The handles' targets of the last step (their positions when the handles were set).
    pub fn targets(&self) -> &[Point] {
        &self.targets
    }

    /// Per triangle, `(cos, sin)` of the rotation found by the last local step.
    pub fn rotations(&self) -> &[[f64; 2]] {
        &self.rotations
    }

    /// How the last step's iterations ended.
    pub fn report(&self) -> IterationReport {
        self.report
    }

    /// Factor statistics of the global system: (nnz(L), flops).
    pub fn factor_stats(&self) -> (usize, f64) {
        let s = self.numeric.symbolic();
        (s.nnz_l(), s.flops())
    }

    /// The slot of the diagonal entry `(v, v)` in `matrix`'s data.
    fn slot_of(&self, v: usize) -> usize {
        let (start, end) = (self.matrix.indptr().index(v), self.matrix.indptr().index(v + 1));
        start + self.matrix.indices()[start..end].binary_search(&v).expect("the diagonal is in the pattern")
    }

    /// The Laplacian plus the penalties of the handles, with pinned rows and columns
    /// replaced by the identity (and their couplings kept aside).
    fn assemble_matrix(&mut self, handles: &[HandlePoint]) {
        self.pin_count.fill(0);
        for &v in self.pinned.iter().filter(|&&v| v != NONE) {
            self.pin_count[v] += 1;
        }
        for &v in &self.frozen {
            self.pin_count[v] = 1;
        }
        let data = self.matrix.data_mut();
        data.copy_from_slice(&self.laplacian);
        for &(slot, c) in &self.joint_entries {
            data[slot] += self.penalty * c;
        }
        for (h, _) in handles.iter().zip(&self.pinned).filter(|(_, &pinned)| pinned == NONE) {
            let slots = self.triangle_slots[h.triangle];
            for i in 0..3 {
                for j in 0..3 {
                    data[slots[3 * i + j]] += self.penalty * h.weights[i] * h.weights[j];
                }
            }
        }
        self.coupling.clear();
        let (indptr, indices) = (self.matrix.indptr().raw_storage().to_vec(), self.matrix.indices().to_vec());
        let data = self.matrix.data_mut();
        for col in 0..indptr.len() - 1 {
            for p in indptr[col]..indptr[col + 1] {
                let row = indices[p];
                let (row_pinned, col_pinned) = (self.pin_count[row] > 0, self.pin_count[col] > 0);
                if row == col && row_pinned {
                    data[p] = 1.0;
                } else if col_pinned && !row_pinned {
                    self.coupling.push((data[p], row, col));
                    data[p] = 0.0;
                } else if row_pinned || col_pinned {
                    data[p] = 0.0;
                }
            }
        }
    }

    /// More iterations towards the current targets (at most `max_iterations`, stopping
    /// once an iteration moves no vertex further than `tolerance` times the shape's
    /// size), without changing the targets, into `next` ([`crate::deform::Deformer::iterate`]).
    /// As for the options, a tolerance of 0 allows at most [`MAX_ITERATIONS`], a tolerance
    /// (up to 1) at most [`MAX_CONVERGENCE_ITERATIONS`]. Returns the report and whether
    /// `next` holds the new pose.
    pub(crate) fn iterate(
        &mut self,
        shared: Shared<'_>,
        max_iterations: usize,
        tolerance: f64,
        next: &mut [Point],
        timings: &mut Timings,
    ) -> Result<(IterationReport, bool), DeformError> {
        check_options(&ArapOptions { iterations: max_iterations, tolerance })?;
        self.next_targets.copy_from_slice(&self.targets);
        let moved = self.run(shared, max_iterations, tolerance, next, timings)?;
        Ok((self.report, moved))
    }

    /// Iterations towards `next_targets` into `next`, committed only if all succeed;
    /// whether `next` holds the new pose.
    fn run(
        &mut self,
        shared: Shared<'_>,
        max_iterations: usize,
        tolerance: f64,
        next: &mut [Point],
        timings: &mut Timings,
    ) -> Result<bool, DeformError> {
        let clock = shared.clock;
        if shared.handles.is_empty() {
            self.field.fill([0.0, 0.0]);
            self.report = IterationReport { iterations: 0, last_move: 0.0, converged: true };
            return Ok(false);
        }
        if !self.factored {
            let t0 = clock();
            self.numeric.refactor(self.matrix.view())?;
            self.factored = true;
            timings.factorisation = clock() - t0;
        }
        // Pinned vertices go to the mean target of the handles pinning them.
        for &v in self.pinned.iter().filter(|&&v| v != NONE) {
            self.pin_target[v] = [0.0, 0.0];
        }
        for (&v, t) in self.pinned.iter().zip(&self.next_targets) {
            if v != NONE {
                let k = f64::from(self.pin_count[v]);
                self.pin_target[v][0] += t[0] / k;
                self.pin_target[v][1] += t[1] / k;
            }
        }
        for &v in &self.frozen {
            self.pin_target[v] = shared.positions[v];
        }
        next.copy_from_slice(shared.positions);
        self.next_rotations.copy_from_slice(&self.rotations);
        let mut report = IterationReport::default();
        while report.iterations < max_iterations {
            let t0 = clock();
            self.local_step(shared.mesh, next);
            self.assemble_rhs(shared);
            let t1 = clock();
            self.numeric.solve_in_place(&mut self.rhs_x)?;
            self.numeric.solve_in_place(&mut self.rhs_y)?;
            let t2 = clock();
            let mut moved: f64 = 0.0;
            let back = power_of_two(-self.unit);
            let back = |x: f64| x * back;
            for (v, p) in next.iter_mut().enumerate() {
                let q =
                    if self.pin_count[v] > 0 { self.pin_target[v] } else { [back(self.rhs_x[v]), back(self.rhs_y[v])] };
                if !in_range(&[q]) {
                    return Err(DeformError::NonFiniteResult);
                }
                moved = moved.max(libm::hypot(q[0] - p[0], q[1] - p[1]));
                *p = q;
            }
            shared.bones.project(next);
            let t3 = clock();
            timings.assembly += t1 - t0;
            timings.solve += t2 - t1;
            timings.integration += t3 - t2;
            report.iterations += 1;
            report.last_move = moved;
            if moved <= tolerance * self.size {
                report.converged = true;
                break;
            }
        }
        for ((f, p), q) in self.field.iter_mut().zip(shared.positions).zip(next.iter()) {
            *f = [q[0] - p[0], q[1] - p[1]];
        }
        std::mem::swap(&mut self.rotations, &mut self.next_rotations);
        self.report = report;
        Ok(true)
    }

    /// The local step at `u` into `next_rotations`.
    fn local_step(&mut self, mesh: &Mesh, u: &[Point]) {
        let unit = power_of_two(self.unit);
        for (((t, c), e), r) in
            mesh.triangles().iter().zip(&self.cot).zip(&self.rest_edges).zip(&mut self.next_rotations)
        {
            let p = t.map(|v| u[v as usize].map(|x| x * unit));
            if let Some(rotation) = best_rotation(p, c, e) {
                *r = rotation;
            }
        }
    }

    /// The global step's right-hand sides for the rotations in `next_rotations`, in the
    /// units of positions scaled by `2^unit`.
    fn assemble_rhs(&mut self, shared: Shared<'_>) {
        let unit = power_of_two(self.unit);
        let into = |p: Point| p.map(|x| x * unit);
        self.rhs_x.fill(0.0);
        self.rhs_y.fill(0.0);
        for (((t, c), e), r) in
            shared.mesh.triangles().iter().zip(&self.cot).zip(&self.rest_edges).zip(&self.next_rotations)
        {
            for k in 0..3 {
                let d = [c[k] * (r[0] * e[k][0] - r[1] * e[k][1]), c[k] * (r[1] * e[k][0] + r[0] * e[k][1])];
                let (i, j) = (t[(k + 1) % 3] as usize, t[(k + 2) % 3] as usize);
                self.rhs_x[i] += d[0];
                self.rhs_y[i] += d[1];
                self.rhs_x[j] -= d[0];
                self.rhs_y[j] -= d[1];
            }
        }
        for ((h, &pinned), target) in shared.handles.iter().zip(&self.pinned).zip(&self.next_targets) {
            if pinned == NONE {
                let target = into(*target);
                for (v, w) in h.vertices.iter().zip(h.weights) {
                    self.rhs_x[*v as usize] += self.penalty * w * target[0];
                    self.rhs_y[*v as usize] += self.penalty * w * target[1];
                }
            }
        }
        for &(v, target) in &self.turning {
            let target = into(target);
            self.rhs_x[v] += self.penalty * target[0];
            self.rhs_y[v] += self.penalty * target[1];
        }
        for &(value, row, col) in &self.coupling {
            let pin = into(self.pin_target[col]);
            self.rhs_x[row] -= value * pin[0];
            self.rhs_y[row] -= value * pin[1];
        }
        for (v, &count) in self.pin_count.iter().enumerate() {
            if count > 0 {
                let pin = into(self.pin_target[v]);
                self.rhs_x[v] = pin[0];
                self.rhs_y[v] = pin[1];
            }
        }
    }

    /// The energy `E` of the pose in `shared` with the best rotations and the current
    /// targets, and a puppet's joints held like handles (the quantity each iteration
    /// lowers, but for a puppet's least-motion term, which is relative to each step's start).
    pub(crate) fn energy(&self, shared: Shared<'_>) -> f64 {
        // Computed on positions scaled by 2^unit, like the rest edges, and scaled back.
        let unit = power_of_two(self.unit);
        let into = |p: Point| p.map(|x| x * unit);
        let u = shared.positions;
        let mut energy = 0.0;
        for ((t, c), e) in shared.mesh.triangles().iter().zip(&self.cot).zip(&self.rest_edges) {
            let p = t.map(|v| into(u[v as usize]));
            let r = best_rotation(p, c, e).unwrap_or([1.0, 0.0]);
            for k in 0..3 {
                let d = sub(p[(k + 1) % 3], p[(k + 2) % 3]);
                let re = [r[0] * e[k][0] - r[1] * e[k][1], r[1] * e[k][0] + r[0] * e[k][1]];
                energy += 0.5 * c[k] * ((d[0] - re[0]).powi(2) + (d[1] - re[1]).powi(2));
            }
        }
        for ((h, &pinned), target) in shared.handles.iter().zip(&self.pinned).zip(&self.targets) {
            if pinned == NONE {
                let (p, target) = (into(h.position(u)), into(*target));
                energy += 0.5 * self.penalty * ((p[0] - target[0]).powi(2) + (p[1] - target[1]).powi(2));
            }
        }
        for blend in &self.joints {
            let mut gap = [0.0, 0.0];
            for &(v, c) in blend {
                let p = into(u[v as usize]);
                gap[0] += c * p[0];
                gap[1] += c * p[1];
            }
            energy += 0.5 * self.penalty * (gap[0] * gap[0] + gap[1] * gap[1]);
        }
        scale_by_power_of_two(energy, -2 * self.unit)
    }
}

impl Solve for ArapSolver {
    fn abilities(&self) -> Abilities {
        Abilities::ALL
    }

    /// Builds the matrix of a new handle set (its factorisation waits for the next step)
    /// and sets the targets to the handles' current positions. A point at a vertex (weight
    /// 1 there, within [`AT_VERTEX`]) pins that vertex; any other point is held by the
    /// penalty.
    fn set_handles(&mut self, shared: Shared<'_>, handles: &[HandlePoint]) -> Result<(), DeformError> {
        self.frozen = match self.pieces.is_empty() || handles.is_empty() {
            true => Vec::new(),
            false => {
                let mut held = vec![false; self.pieces.len()];
                for h in handles {
                    for (&v, &w) in h.vertices.iter().zip(&h.weights) {
                        if w != 0.0 {
                            held[self.pieces[v as usize] as usize] = true;
                        }
                    }
                }
                (0..self.pieces.len()).filter(|&v| !held[self.pieces[v] as usize]).collect()
            }
        };
        self.pinned = handles
            .iter()
            .map(|p| (0..3).find(|&k| p.weights[k] >= 1.0 - AT_VERTEX).map_or(NONE, |k| p.vertices[k] as usize))
            .collect();
        self.assemble_matrix(handles);
        self.targets = handles.iter().map(|h| h.position(shared.positions)).collect();
        self.next_targets = self.targets.clone();
        self.factored = false;
        Ok(())
    }

    fn set_weights(&mut self, shared: Shared<'_>, weights: Option<&[f64]>) {
        self.weigh(shared.handles, weights);
    }

    /// Each handle's target becomes its current position plus its velocity (in handle
    /// order), then the configured local/global iterations run from the current pose. With
    /// no handles nothing moves. Turning handles: see `turning`.
    fn step(
        &mut self,
        shared: Shared<'_>,
        velocities: &[[f64; 2]],
        turns: Option<&[f64]>,
        next: &mut [Point],
        timings: &mut Timings,
    ) -> Result<bool, DeformError> {
        if let Some(turns) = turns {
            return self.step_turning(shared, velocities, turns, next, timings);
        }
        for (k, (h, v)) in shared.handles.iter().zip(velocities).enumerate() {
            let p = h.position(shared.positions);
            self.next_targets[k] = [p[0] + v[0], p[1] + v[1]];
        }
        let options = self.options;
        let moved = self.run(shared, options.iterations, options.tolerance, next, timings)?;
        std::mem::swap(&mut self.targets, &mut self.next_targets);
        Ok(moved)
    }

    /// Handles stay, their targets become their positions in the pose; a reset also puts
    /// the rotations back to the identity.
    fn pose_set(&mut self, shared: Shared<'_>, rest: bool) {
        if rest {
            self.rotations.fill([1.0, 0.0]);
        }
        self.field.fill([0.0, 0.0]);
        for (target, h) in self.targets.iter_mut().zip(shared.handles) {
            *target = h.position(shared.positions);
        }
    }

    /// How far each vertex moved in the last step.
    fn field(&self) -> &[[f64; 2]] {
        &self.field
    }

    /// Targets, the rotations the next local step starts from (kept where a triangle's `S`
    /// has no rotational part), the field and the report. The factor is not saved: it
    /// changes only with the handles or the stiffness, and a restore after the first step
    /// of a handle set keeps the factor that step made, the same one.
    fn save(&self, checkpoint: &mut Checkpoint) {
        copy_into(&mut checkpoint.targets, &self.targets);
        copy_into(&mut checkpoint.rotations, &self.rotations);
        copy_into(&mut checkpoint.field, &self.field);
        checkpoint.report = self.report;
    }

    fn saved_lengths(&self, checkpoint: &Checkpoint) -> Vec<(usize, usize)> {
        vec![
            (checkpoint.field.len(), self.field.len()),
            (checkpoint.targets.len(), self.targets.len()),
            (checkpoint.rotations.len(), self.rotations.len()),
        ]
    }

    fn restore(&mut self, checkpoint: &Checkpoint) {
        self.targets.copy_from_slice(&checkpoint.targets);
        self.rotations.copy_from_slice(&checkpoint.rotations);
        self.field.copy_from_slice(&checkpoint.field);
        self.report = checkpoint.report;
    }
}

impl Build for ArapOptions {
    type Solver = ArapSolver;

    fn check(&self) -> Result<(), DeformError> {
        check_options(self)
    }

    fn orders(&self, mesh: &Mesh) -> Orders {
        ArapSolver::orders(mesh)
    }

    fn build(self, mesh: &Mesh, joins: &Joins, orders: &Orders) -> Result<ArapSolver, DeformError> {
        ArapSolver::new(mesh, self, joins, orders)
    }

    fn of(solver: &ArapSolver) -> Self {
        solver.options
    }

    fn configure(self, solver: &mut ArapSolver, _shared: Shared<'_>) -> Result<(), DeformError> {
        solver.options = self;
        Ok(())
    }
}

/// The rotation `(cos, sin)` maximising `tr(R^T S)` for `S = sum_k c_k d_k e_k^T`, with
/// `d_k` the current and `e_k` the rest edge opposite corner k; `None` when every
/// rotation is equally good (`S` has no rotational part).
fn best_rotation(p: [Point; 3], c: &[f64; 3], e: &[Point; 3]) -> Option<[f64; 2]> {
    let mut s = [[0.0; 2]; 2];
    for k in 0..3 {
        let d = sub(p[(k + 1) % 3], p[(k + 2) % 3]);
        for (a, row) in s.iter_mut().enumerate() {
            for (b, entry) in row.iter_mut().enumerate() {
                *entry += c[k] * d[a] * e[k][b];
            }
        }
    }
    // tr(R^T S) = cos (S00 + S11) + sin (S10 - S01).
    let (x, y) = (s[0][0] + s[1][1], s[1][0] - s[0][1]);
    let r = libm::hypot(x, y);
    (r > 0.0 && r.is_finite()).then(|| [x / r, y / r])
}

/// Each vertex's piece (numbered from 0) of the graph of the mesh's edges and the extra
/// vertex pairs `extra` (a puppet's joints): union-find with path halving.
fn pieces(mesh: &Mesh, extra: &[[u32; 2]]) -> Vec<u32> {
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

fn sub(a: Point, b: Point) -> Point {
    [a[0] - b[0], a[1] - b[1]]
}

fn check_options(options: &ArapOptions) -> Result<(), DeformError> {
    if !(0.0..=1.0).contains(&options.tolerance) {
        return Err(DeformError::InvalidOption {
            name: "tolerance",
            value: options.tolerance,
            expected: "a number from 0 to 1 (a fraction of the shape's size)",
        });
    }
    if options.tolerance == 0.0 && !(1..=MAX_ITERATIONS).contains(&options.iterations) {
        return Err(DeformError::InvalidOption {
            name: "iterations",
            value: options.iterations as f64,
            expected: "a whole number from 1 to 1000 per step (a step's work grows with it; 1000 is far more \
                       than a frame needs)",
        });
    }
    if !(1..=MAX_CONVERGENCE_ITERATIONS).contains(&options.iterations) {
        return Err(DeformError::InvalidOption {
            name: "iterations",
            value: options.iterations as f64,
            expected: "a whole number from 1 to 1000000 for a run to a tolerance",
        });
    }
    Ok(())
}
