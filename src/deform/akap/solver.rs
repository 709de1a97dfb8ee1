//! The As-Killing-As-Possible solver (Solomon et al. 2011, Sections 2 and 3), behind a
//! [`Deformer`](crate::deform::Deformer) of the method `akap`.
//!
//! Each step, with handle velocities `u_i` at handle points `h_i`:
//! 1. (eq. (3), discretised as eqs. (5)-(7)) `U0 = argmin E_K(U) + lambda sum_i |U(h_i) - u_i|^2`,
//!    i.e. the SPD system `(K + lambda sum_i W_i^T W_i) U0 = lambda sum_i W_i^T u_i`, where
//!    `W_i` blends the vertex values of the handle's triangle with its barycentric weights
//!    (eq. (7) has vertex handles, `W_i` rows of the identity; lambda is eq. (3)'s, the
//!    square of eqs. (5)-(7)'s);
//! 2. (eq. (4), discretised as eq. (8)) `U = argmin E_K(U)` with `U = U0` on the boundary:
//!    `K_II U_I = -K_IB U0_B` over the interior unknowns (skipped when switched off or when
//!    no vertex is interior);
//! 3. (eqs. (13)-(16), eq. (15) corrected) every vertex moves along the logarithmic spirals
//!    fitted to its edges ([`super::spiral`]), or by `U` itself with the linear integrator.
//!
//! `K` ([`KillingMatrix`], eqs. (2) and (6)) depends on the current positions, so both
//! systems are factored anew every step, but their patterns are fixed by the mesh (a
//! barycentric handle only touches blocks of one triangle, which exist already): orderings
//! and symbolic analyses run once, when the solver is made. Handles can change between any
//! two steps. Buffers are sized when the mesh or the handle set changes; a step allocates
//! nothing. A step that fails (a pivot that is not positive, a non-finite result) leaves the
//! solver as it was.

use std::sync::Arc;

use sprs::CsMat;

use super::killing::KillingMatrix;
use super::spiral::{linear_step, spiral_step};
use super::turning::{self, rigid_field, Neighbourhood};
use crate::deform::error::{out_of_memory, DeformError};
use crate::deform::handles::{self, diagonal, in_range, HandlePoint};
use crate::deform::method::{copy_into, Abilities, Build, Checkpoint, Orders, Shared, Solve, Timings};
use crate::deform::options::{AkapOptions, Integrator, LAMBDA_RANGE};
use crate::deform::puppet::{Joins, AKAP_JOINT_WEIGHT, AKAP_TURN_WEIGHT, LEAST_MOTION};
use crate::geometry::{in_comfortable_range, normalising_exponent, scale_by_power_of_two, Point};
use crate::mesh::Mesh;
use crate::sparse::{dissection_if_large, expand_blocks, fill_or_dissection, Numeric, Ordering, Symbolic};

const NONE: usize = usize::MAX;

/// A sparse SPD system on the Killing matrix's values, with its factor.
#[derive(Debug, Clone)]
struct System {
    /// Step 1's values: a copy of K's data that the handle penalties are added to. Empty for
    /// step 2, whose factorisation reads K's data straight through its analysis's map.
    values: Vec<f64>,
    numeric: Numeric,
}

impl System {
    /// Analyses `matrix` with its unknowns (two per vertex) in the given vertex order. With
    /// `from_killing = Some(map)`, `matrix` is a submatrix of the Killing matrix `k` whose
    /// entry `p` is K's entry `map[p]`, and refactorisations read K's data; otherwise `matrix`
    /// is `k` and they read the system's own copy, `values`.
    fn new(
        matrix: &CsMat<f64>,
        k: &CsMat<f64>,
        from_killing: Option<&[usize]>,
        vertex_order: &[usize],
    ) -> Result<Self, DeformError> {
        let order = expand_blocks(vertex_order, 2);
        let symbolic = Symbolic::analyse(matrix.view(), &Ordering::Given(order))
            .expect("a vertex order expanded to blocks is a valid ordering of a square CSC matrix");
        let (symbolic, values) = match from_killing {
            Some(map) => {
                (symbolic.reading_values_through(map, k.nnz()).expect("the map has a slot of K per entry"), Vec::new())
            }
            None => (symbolic, k.data().to_vec()),
        };
        Ok(Self { values, numeric: Numeric::try_new(Arc::new(symbolic)).map_err(out_of_memory)? })
    }
}

/// The AKAP solver of one mesh (the state it derives from the mesh and the handles; the
/// mesh, handles and pose are its [`Deformer`](crate::deform::Deformer)'s).
#[derive(Debug, Clone)]
pub struct AkapSolver {
    options: AkapOptions,
    killing: KillingMatrix,
    /// Step 1: K plus the handle penalties (same pattern as K).
    soft: System,
    /// Step 2: K restricted to interior unknowns; `None` when no vertex is interior.
    dirichlet: Option<System>,
    /// Interior vertex index of each vertex, or `NONE` on the boundary.
    interior_index: Vec<usize>,
    /// Per handle, for each of its 9 vertex pairs, the two diagonal slots of the block.
    penalty_slots: Vec<[[usize; 2]; 9]>,
    distinct_points: usize,
    /// Whether every handle weighs only on boundary vertices (then step 2 changes nothing).
    boundary_handles_only: bool,
    /// A puppet's joints: each joint's six vertices with their blend coefficients
    /// (`x_front - x_back = sum c x_v`), and the entries `mu c_i c_j` it adds to K (the
    /// slots of the two diagonal entries of each 2 x 2 block, and the value).
    joints: Vec<[(u32, f64); 6]>,
    joint_entries: Vec<([usize; 2], f64)>,
    /// A puppet's least-motion term: the slots of every diagonal entry of K (empty for a
    /// single shape, which has none).
    least_motion: Vec<usize>,
    /// Scratch: each joint's gap `x_front - x_back` in the current pose.
    gaps: Vec<Point>,
    /// Per handle, the vertices it carries when it turns ([`turning`]).
    neighbourhoods: Vec<Neighbourhood>,
    /// Scratch: the turning handles' velocities at their neighbourhoods' vertices.
    turn_targets: Vec<[f64; 2]>,
    /// Last field of step 1 and of step 2, interleaved `u1 u2` per vertex.
    soft_field: Vec<f64>,
    field: Vec<f64>,
    // Scratch for a step, committed only on success.
    next_soft: Vec<f64>,
    next_field: Vec<f64>,
    interior_rhs: Vec<f64>,
    spiral_sums: Vec<[f64; 3]>,
}

impl AkapSolver {
    /// The fill-reducing vertex orders of the two systems, the bulk of the set-up:
    /// minimum fill, and on large meshes nested dissection where it needs fewer flops.
    /// Dissection runs once, on the whole mesh; step 2 gets its interior vertices in the
    /// same order (as good as dissecting the interior graph afresh, within a few percent of
    /// flops either way, at no cost). `systems[0]` orders every vertex (step 1),
    /// `systems[1]` the interior vertices, numbered in vertex order (step 2).
    pub fn orders(mesh: &Mesh) -> Orders {
        let (ptr, adj) = mesh.vertex_graph();
        let dissection = dissection_if_large(&ptr, &adj, mesh.positions());
        let soft = fill_or_dissection(&ptr, &adj, 2, dissection.clone());
        let (interior_index, interior_count) = interior_numbering(mesh);
        let interior = if interior_count == 0 {
            Vec::new()
        } else {
            let (ptr, adj) = mesh.relabelled_vertex_graph(&interior_index);
            let interior_dissection =
                dissection.map(|order| order.iter().map(|&v| interior_index[v]).filter(|&i| i != NONE).collect());
            fill_or_dissection(&ptr, &adj, 2, interior_dissection)
        };
        Orders { systems: vec![soft, interior] }
    }

    /// The solver for a connected mesh, or a puppet's sheets coupled by `joins`, with
    /// orders from [`Self::orders`] (the mesh's alone: the joints' few extra entries are
    /// analysed in the mesh's order): the analyses and buffers. Orders that are not
    /// permutations of the right sizes are refused ([`DeformError::OrdersMismatch`]).
    fn new(mesh: &Mesh, options: AkapOptions, joins: &Joins, orders: &Orders) -> Result<Self, DeformError> {
        check_options(&options)?;
        let n = mesh.vertex_count();
        let (interior_index, interior_count) = interior_numbering(mesh);
        orders.check(&[n, interior_count])?;
        let mut killing = KillingMatrix::with_pairs(mesh, &joins.extra_pairs());
        if joins.puppet {
            killing.set_turn_weight(AKAP_TURN_WEIGHT);
        }
        let joints: Vec<[(u32, f64); 6]> = joins.points.iter().map(Joins::blend).collect();
        let mut joint_entries = Vec::with_capacity(36 * joints.len());
        for blend in &joints {
            for &(v, cv) in blend {
                for &(w, cw) in blend {
                    let block =
                        killing.block_slots(v as usize, w as usize).expect("the joints' pairs are in the pattern");
                    joint_entries.push(([block[0][0], block[1][1]], AKAP_JOINT_WEIGHT * cv * cw));
                }
            }
        }
        let least_motion = match joins.puppet {
            true => (0..n)
                .flat_map(|v| {
                    let block = killing.block_slots(v, v).expect("every vertex has its diagonal block");
                    [block[0][0], block[1][1]]
                })
                .collect(),
            false => Vec::new(),
        };
        let k = killing.matrix();
        let soft = System::new(k, k, None, &orders.systems[0])?;
        let dirichlet = if interior_count > 0 {
            let (matrix, from_killing) = interior_system(k, &interior_index, interior_count);
            Some(System::new(&matrix, k, Some(&from_killing), &orders.systems[1])?)
        } else {
            None
        };
        Ok(Self {
            options,
            killing,
            soft,
            dirichlet,
            interior_rhs: vec![0.0; 2 * interior_count],
            interior_index,
            penalty_slots: Vec::new(),
            gaps: vec![[0.0; 2]; joints.len()],
            joints,
            joint_entries,
            least_motion,
            distinct_points: 0,
            boundary_handles_only: true,
            neighbourhoods: Vec::new(),
            turn_targets: Vec::new(),
            soft_field: vec![0.0; 2 * n],
            field: vec![0.0; 2 * n],
            next_soft: vec![0.0; 2 * n],
            next_field: vec![0.0; 2 * n],
            spiral_sums: vec![[0.0; 3]; n],
        })
    }

    /// The settings.
    pub fn options(&self) -> AkapOptions {
        self.options
    }

    /// Factor statistics of step 1's system: (nnz(L), flops).
    pub fn factor_stats(&self) -> (usize, f64) {
        let s = self.soft.numeric.symbolic();
        (s.nnz_l(), s.flops())
    }

    /// Steps 1 (eq. (7), with the handles' penalties) and 2 (eq. (8)) into `next_soft` and
    /// `next_field`.
    ///
    /// The systems are linear in the velocities, so velocities outside the comfortable range
    /// (about 1e-75 to 1e75) are scaled by the power of two `2^e` that brings the largest
    /// component into [1, 2), and the fields scaled back: exact, and free of overflow
    /// (`lambda u` at large velocities) and underflow (tiny ones) at any scale.
    fn solve_fields(
        &mut self,
        shared: Shared<'_>,
        velocities: &[[f64; 2]],
        turns: Option<&[f64]>,
        timings: &mut Timings,
    ) -> Result<(), DeformError> {
        let clock = shared.clock;
        let lambda = self.options.lambda;
        if let Some(turns) = turns {
            turning::targets(
                shared.handles,
                &self.neighbourhoods,
                shared.positions,
                velocities,
                turns,
                &mut self.turn_targets,
            );
        }
        for (gap, pair) in self.gaps.iter_mut().zip(&self.joints) {
            *gap = [0.0, 0.0];
            for &(v, c) in pair {
                gap[0] += c * shared.positions[v as usize][0];
                gap[1] += c * shared.positions[v as usize][1];
            }
        }
        let asked =
            || velocities.iter().chain(turns.map_or(&[][..], |_| &self.turn_targets[..])).chain(self.gaps.iter());
        let largest = asked().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        let e =
            if largest == 0.0 || in_comfortable_range(largest) { 0 } else { normalising_exponent(asked().copied()) };
        let t0 = clock();
        self.killing.assemble(shared.positions);
        // A puppet's joints and least-motion term, part of the energy both steps minimise.
        let data = self.killing.data_mut();
        for &(slots, value) in &self.joint_entries {
            data[slots[0]] += value;
            data[slots[1]] += value;
        }
        for &slot in &self.least_motion {
            data[slot] += LEAST_MOTION;
        }
        let k = self.killing.matrix().data();
        self.soft.values.copy_from_slice(k);
        let data = &mut self.soft.values;
        let rhs = &mut self.next_soft;
        rhs.fill(0.0);
        // Each joint asks its two points' velocities to close the current gap:
        // mu |J U + g|^2, whose gradient puts -mu J^T g on the right-hand side.
        for (pair, gap) in self.joints.iter().zip(&self.gaps) {
            let g = gap.map(|x| scale_by_power_of_two(x, e));
            for &(v, c) in pair {
                rhs[2 * v as usize] -= AKAP_JOINT_WEIGHT * c * g[0];
                rhs[2 * v as usize + 1] -= AKAP_JOINT_WEIGHT * c * g[1];
            }
        }
        let mut at_target = 0;
        for (index, ((h, slots), u)) in shared.handles.iter().zip(&self.penalty_slots).zip(velocities).enumerate() {
            if turns.is_some_and(|turns| turns[index] != 0.0) {
                // A turning handle: its neighbourhood asked to follow the rigid motion.
                let n = &self.neighbourhoods[index];
                let w = lambda / n.vertices.len() as f64;
                for (&v, slot) in n.vertices.iter().zip(&n.slots) {
                    let t = self.turn_targets[at_target].map(|x| scale_by_power_of_two(x, e));
                    at_target += 1;
                    data[slot[0]] += w;
                    data[slot[1]] += w;
                    rhs[2 * v as usize] += w * t[0];
                    rhs[2 * v as usize + 1] += w * t[1];
                }
                continue;
            }
            let u = u.map(|x| scale_by_power_of_two(x, e));
            for i in 0..3 {
                for j in 0..3 {
                    let c = lambda * h.weights[i] * h.weights[j];
                    data[slots[3 * i + j][0]] += c;
                    data[slots[3 * i + j][1]] += c;
                }
                let v = h.vertices[i] as usize;
                rhs[2 * v] += lambda * h.weights[i] * u[0];
                rhs[2 * v + 1] += lambda * h.weights[i] * u[1];
            }
        }
        // Step 2 re-solves the interior with U0's boundary values (and a puppet's joints,
        // which are part of K here: its correction's right-hand side below has only the
        // handles' forces, since the joints' terms of K U0 and of step 1's right-hand side
        // cancel). When the penalties touch
        // boundary unknowns only, U0 already makes the interior gradient of E_K vanish, which
        // is step 2's condition, and step 2's solution is unique (K_II is positive definite):
        // U_opt = U0, so the second factorisation is skipped.
        let turning_inside = turns
            .is_some_and(|turns| turns.iter().zip(&self.neighbourhoods).any(|(&w, n)| w != 0.0 && !n.boundary_only));
        let dirichlet = self.options.dirichlet && (!self.boundary_handles_only || turning_inside);
        let t1 = clock();
        self.soft.numeric.refactor_values(&self.soft.values)?;
        let t2 = clock();
        self.soft.numeric.solve_in_place(&mut self.next_soft)?;
        let t3 = clock();
        timings.assembly = t1 - t0;
        timings.factorisation = t2 - t1;
        timings.solve = t3 - t2;

        self.next_field.copy_from_slice(&self.next_soft);
        let Some(system) = self.dirichlet.as_mut().filter(|_| dirichlet) else {
            scale_fields(e, &mut self.next_soft, &mut self.next_field);
            return Ok(());
        };
        // Step 2 as a correction of U0: K_II U_I = -K_IB U0_B is K_II (U0_I - U_I) = r_I with
        // r = K U0, and step 1's optimality, (K + lambda P) U0 = lambda W^T u, makes
        // r = lambda W^T (u - W U0): nonzero on handle vertices only, so the forward solve
        // reaches only their ancestors in the elimination tree.
        let t4 = clock();
        let rhs = &mut self.interior_rhs;
        rhs.fill(0.0);
        let u0: &[[f64; 2]] = as_pairs(&self.next_soft);
        let mut at_target = 0;
        for (index, (h, u)) in shared.handles.iter().zip(velocities).enumerate() {
            if turns.is_some_and(|turns| turns[index] != 0.0) {
                let n = &self.neighbourhoods[index];
                let w = lambda / n.vertices.len() as f64;
                for &v in &n.vertices {
                    let t = self.turn_targets[at_target].map(|x| scale_by_power_of_two(x, e));
                    at_target += 1;
                    let i = self.interior_index[v as usize];
                    if i != NONE {
                        rhs[2 * i] += w * (t[0] - u0[v as usize][0]);
                        rhs[2 * i + 1] += w * (t[1] - u0[v as usize][1]);
                    }
                }
                continue;
            }
            let u = u.map(|x| scale_by_power_of_two(x, e));
            let mut at = [0.0, 0.0];
            for (&v, &w) in h.vertices.iter().zip(&h.weights) {
                at[0] += w * u0[v as usize][0];
                at[1] += w * u0[v as usize][1];
            }
            let force = [lambda * (u[0] - at[0]), lambda * (u[1] - at[1])];
            for (&v, &w) in h.vertices.iter().zip(&h.weights) {
                let i = self.interior_index[v as usize];
                if i != NONE {
                    rhs[2 * i] += w * force[0];
                    rhs[2 * i + 1] += w * force[1];
                }
            }
        }
        let t5 = clock();
        system.numeric.refactor_values(k)?;
        let t6 = clock();
        system.numeric.solve_in_place(rhs)?;
        for (v, &i) in self.interior_index.iter().enumerate() {
            if i != NONE {
                self.next_field[2 * v] -= rhs[2 * i];
                self.next_field[2 * v + 1] -= rhs[2 * i + 1];
            }
        }
        scale_fields(e, &mut self.next_soft, &mut self.next_field);
        let t7 = clock();
        timings.assembly += t5 - t4;
        timings.factorisation += t6 - t5;
        timings.dirichlet_factorisation = t6 - t5;
        timings.solve += t7 - t6;
        Ok(())
    }
}

impl Solve for AkapSolver {
    fn abilities(&self) -> Abilities {
        Abilities::ALL
    }

    fn set_handles(&mut self, shared: Shared<'_>, handles: &[HandlePoint]) -> Result<(), DeformError> {
        self.penalty_slots = handles
            .iter()
            .map(|h| {
                let mut slots = [[0; 2]; 9];
                for i in 0..3 {
                    for j in 0..3 {
                        let block = self
                            .killing
                            .block_slots(h.vertices[i] as usize, h.vertices[j] as usize)
                            .expect("vertices of one triangle share an edge");
                        slots[3 * i + j] = [block[0][0], block[1][1]];
                    }
                }
                slots
            })
            .collect();
        let points: Vec<Point> = handles.iter().map(|h| h.position(shared.positions)).collect();
        // Two handle points closer than 1e-12 of the shape's size are one point.
        self.distinct_points = handles::distinct_points(&points, 1e-12 * diagonal(shared.positions));
        let mesh = shared.mesh;
        self.boundary_handles_only = handles
            .iter()
            .all(|h| h.vertices.iter().zip(h.weights).all(|(&v, w)| w == 0.0 || mesh.is_boundary_vertex(v as usize)));
        let killing = &self.killing;
        let diagonal = |v: usize| {
            let block = killing.block_slots(v, v).expect("every vertex has its diagonal block");
            [block[0][0], block[1][1]]
        };
        self.neighbourhoods = handles.iter().map(|h| Neighbourhood::of(mesh, h, diagonal)).collect();
        let most = self.neighbourhoods.iter().map(|n| n.vertices.len()).sum();
        self.turn_targets = Vec::with_capacity(most);
        Ok(())
    }

    /// The painted stiffness times the paper's area weight of eqs. (5)-(6): the pattern is
    /// unchanged, so nothing is analysed again; the next step assembles with it.
    fn set_weights(&mut self, _shared: Shared<'_>, weights: Option<&[f64]>) {
        self.killing.set_stiffness(weights.map(<[f64]>::to_vec));
    }

    fn step(
        &mut self,
        shared: Shared<'_>,
        velocities: &[[f64; 2]],
        turns: Option<&[f64]>,
        next: &mut [Point],
        timings: &mut Timings,
    ) -> Result<bool, DeformError> {
        let clock = shared.clock;
        // A puppet's sheets follow a single handle through its joints, so it always solves.
        let puppet = !self.least_motion.is_empty() && !shared.handles.is_empty();
        if self.distinct_points < 2 && !puppet {
            // No handle: nothing moves. One handle point: the whole shape follows it rigidly
            // (and turns with it).
            let mut mean = [0.0, 0.0];
            for v in velocities {
                mean[0] += v[0] / velocities.len() as f64;
                mean[1] += v[1] / velocities.len() as f64;
            }
            match turns {
                None => {
                    for k in 0..shared.mesh.vertex_count() {
                        self.next_soft[2 * k] = mean[0];
                        self.next_soft[2 * k + 1] = mean[1];
                    }
                }
                Some(turns) => {
                    let omega = turns.iter().sum::<f64>() / turns.len() as f64;
                    let c = shared.handles[0].position(shared.positions);
                    for (k, &p) in shared.positions.iter().enumerate() {
                        let u = rigid_field(mean, omega, c, p);
                        self.next_soft[2 * k] = u[0];
                        self.next_soft[2 * k + 1] = u[1];
                    }
                }
            }
            self.next_field.copy_from_slice(&self.next_soft);
        } else {
            self.solve_fields(shared, velocities, turns, timings)?;
        }

        let t_move = clock();
        let field: &[[f64; 2]] = as_pairs(&self.next_field);
        match self.options.integrator {
            Integrator::Spiral => {
                let mesh = shared.mesh;
                spiral_step(shared.positions, field, |v| mesh.neighbors(v), &mut self.spiral_sums, next)
            }
            Integrator::Linear => linear_step(shared.positions, field, next),
        }
        shared.bones.project(next);
        if !in_range(next) {
            return Err(DeformError::NonFiniteResult);
        }
        timings.integration = clock() - t_move;
        std::mem::swap(&mut self.soft_field, &mut self.next_soft);
        std::mem::swap(&mut self.field, &mut self.next_field);
        Ok(true)
    }

    fn pose_set(&mut self, _shared: Shared<'_>, _rest: bool) {
        self.soft_field.fill(0.0);
        self.field.fill(0.0);
    }

    /// The velocity field of the last step after step 2 (`U_opt`), per vertex.
    fn field(&self) -> &[[f64; 2]] {
        as_pairs(&self.field)
    }

    /// The velocity field of the last step after step 1 (`U0`), per vertex.
    fn soft_field(&self) -> &[[f64; 2]] {
        as_pairs(&self.soft_field)
    }

    /// Both fields: every other buffer a step reads is assembled afresh from the positions
    /// in each step.
    fn save(&self, checkpoint: &mut Checkpoint) {
        copy_into(&mut checkpoint.field, as_pairs(&self.field));
        copy_into(&mut checkpoint.soft_field, as_pairs(&self.soft_field));
    }

    fn saved_lengths(&self, checkpoint: &Checkpoint) -> Vec<(usize, usize)> {
        let n = self.field.len() / 2;
        vec![(checkpoint.field.len(), n), (checkpoint.soft_field.len(), n)]
    }

    fn restore(&mut self, checkpoint: &Checkpoint) {
        self.field.copy_from_slice(checkpoint.field.as_flattened());
        self.soft_field.copy_from_slice(checkpoint.soft_field.as_flattened());
    }
}

impl Build for AkapOptions {
    type Solver = AkapSolver;

    fn check(&self) -> Result<(), DeformError> {
        check_options(self)
    }

    fn orders(&self, mesh: &Mesh) -> Orders {
        AkapSolver::orders(mesh)
    }

    fn build(self, mesh: &Mesh, joins: &Joins, orders: &Orders) -> Result<AkapSolver, DeformError> {
        AkapSolver::new(mesh, self, joins, orders)
    }

    fn of(solver: &AkapSolver) -> Self {
        solver.options
    }

    fn configure(self, solver: &mut AkapSolver, _shared: Shared<'_>) -> Result<(), DeformError> {
        solver.options = self;
        Ok(())
    }
}

fn check_options(options: &AkapOptions) -> Result<(), DeformError> {
    if !LAMBDA_RANGE.contains(&options.lambda) {
        return Err(DeformError::InvalidOption {
            name: "lambda",
            value: options.lambda,
            expected: "a number from 1e-6 to 1e10",
        });
    }
    Ok(())
}

/// Scales both fields back from velocities scaled by `2^k`.
fn scale_fields(k: i32, soft: &mut [f64], field: &mut [f64]) {
    if k != 0 {
        for x in soft.iter_mut().chain(field.iter_mut()) {
            *x = scale_by_power_of_two(*x, -k);
        }
    }
}

/// Views an interleaved `[x0, y0, x1, y1, ...]` buffer as pairs.
fn as_pairs(flat: &[f64]) -> &[[f64; 2]] {
    let (pairs, rest) = flat.as_chunks::<2>();
    debug_assert!(rest.is_empty());
    pairs
}

/// Each vertex's index among the interior vertices (`NONE` on the boundary), and their number.
fn interior_numbering(mesh: &Mesh) -> (Vec<usize>, usize) {
    let mut index = vec![NONE; mesh.vertex_count()];
    let mut count = 0;
    for v in (0..mesh.vertex_count()).filter(|&v| !mesh.is_boundary_vertex(v)) {
        index[v] = count;
        count += 1;
    }
    (index, count)
}

/// The interior block `K_II` of the Killing matrix: its pattern, and for each of its
/// entries the slot of K's data it comes from.
fn interior_system(k: &CsMat<f64>, interior_index: &[usize], interior_count: usize) -> (CsMat<f64>, Vec<usize>) {
    let unknown = |g: usize| {
        let i = interior_index[g / 2];
        (i != NONE).then(|| 2 * i + g % 2)
    };
    let mut indptr = vec![0];
    let mut indices = Vec::new();
    let mut from = Vec::new();
    for col in 0..k.cols() {
        let range = k.indptr().outer_inds_sz(col);
        let col_interior = unknown(col);
        for p in range {
            let row = k.indices()[p];
            if let (Some(r), Some(_)) = (unknown(row), col_interior) {
                indices.push(r);
                from.push(p);
            }
        }
        if col_interior.is_some() {
            indptr.push(indices.len());
        }
    }
    let nnz = indices.len();
    let m = 2 * interior_count;
    (CsMat::new_csc((m, m), indptr, indices, vec![0.0; nnz]), from)
}
