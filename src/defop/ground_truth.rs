//! The ground truth of DefOp: the variational problem of eq. (6), `min_f E(f)` over
//! piecewise-linear maps `f` of the mesh subject to the hard constraints `f(p_l) = q_l`,
//! with `E = sum_t A_t ψ(J_t)` the ARAP (eq. 10) or S-ARAP (eq. 11) energy of
//! [`super::energy`].
//!
//! **Solver** ([`GroundTruth`], built once per mesh and handle set, then
//! [`GroundTruth::solve`] for many target sets): Newton's method. Each iteration assembles
//! the gradient and `H = sum_t H_t + ε D`, with `D` the diagonal of the rest pose's ARAP
//! Hessian and `ε = 1e-8`, and factors it with the crate's sparse Cholesky (pattern
//! analysed once, 2 x 2 blocks per vertex). `H_t` is first the exact per-triangle Hessian
//! (quadratic convergence near a minimum); if that `H` is not positive definite (the
//! factorisation finds a non-positive pivot), every `H_t` is projected to positive
//! semidefinite through its analytic eigensystem ([`Energy::hessian`]) and `ε` raised a
//! thousandfold (at most three times) if a factorisation still fails. The
//! equality-constrained Newton system is then solved:
//! - handles at vertices fix those vertices: their unknowns are eliminated (identity rows
//!   and columns, prescribed step `q - x` moved to the right-hand side);
//! - handles inside triangles give two rows each of `C x = q` on the free unknowns,
//!   solved by the range-space method: `Y = H^-1 C^T` (one solve per row),
//!   `S = C Y` (dense, `2n x 2n`, Cholesky), `λ = S^-1 (C d0 - r)`, `d = d0 - Y λ`.
//!
//! The step also removes any constraint residual `r`, so one full step puts every handle
//! on its target (to rounding; vertex handles exactly). Once there, a backtracking
//! (Armijo) line search on the true energy `E` follows the step; for S-ARAP it starts
//! below the first `α` where some `det J_t(α) = 0` (a quadratic in `α` per triangle; the
//! cap is 0.9 of it), so no iterate ever flips or collapses a triangle. When a full step
//! of the projected model is accepted, steps twice, four times... as long (up to 64, below
//! the cap) are tried while the energy keeps falling: the projection drops the energy's
//! negative curvature, and near a saddle its full steps were far too short (ARAP solves
//! on the gingerbread figure, 2,000 vertices: 28.5 iterations on average before, 18.4
//! after).
//!
//! **The S-ARAP kink.** Eq. (11) is not differentiable where `J` is conformal (`R = 0`) but
//! not a rotation: there it is the cone `ψ(Q, 0) + κ R` in the anti-similarity part
//! (`κ = 2(Q - 1)(1 - Q^-3) > 0`, notes §4 item 2), and minimisers often sit exactly on it
//! (the rest of the mesh pulls on the triangle's anisotropy with less than `κ`). Newton
//! then jumps across the apex, the gradient never vanishes, and convergence is linear at
//! best (hundreds of iterations on the gingerbread figure). The solver therefore runs a
//! small active set. A triangle whose `R` falls below `κ/2` (where the cone dominates) is
//! *held*: in the Newton model its cone is replaced by the penalty `K R^2` (`K` =
//! [`KINK_CAP`], [`Energy::held`]), smooth and pinning it within about `κ/K` of the kink,
//! so Newton converges quadratically (the line search still uses the true energy and its
//! true slope). If after a full Newton step a held triangle has `R > κ/K` (the force
//! `2 K R` holding it is twice the cone's largest subgradient `κ`), its minimum is not at
//! the kink: it is *released* and treated exactly, until it comes back within
//! `10^-3 κ` of the kink. If a step of the model does not resolvably descend the true energy
//! while it holds a triangle farther than `10^-3 κ` from its kink (a triangle held at
//! `R <= κ/2` whose minimum is elsewhere), those triangles are released and the step
//! computed again (before any step is taken as flat; every held triangle, if the line
//! search fails). Triangles are held only once the handles are on their targets, at the
//! first iteration of a stage only if already within `κ/K` of the kink (so that a warm
//! start from a solution is one), and only where `κ > 1e-10` (near rotations the kink is
//! negligible). [`SolveReport::gradient`] is the model's.
//!
//! **Stopping**: when the handles are on their targets and the constrained gradient
//! (`∇E + C^T μ`, `μ` the least-squares multipliers, on the free unknowns) has an
//! infinity norm at most `tolerance` times the rest shape's bounding-box diagonal
//! (default 1e-9: scale-invariant, since the gradient scales like lengths), or when the
//! Newton decrement `-∇E·d` falls below `(tolerance · size)^2`, or (a safety net) when
//! three steps in a row lowered the energy by less than 1e-14 of itself, the floor of
//! double precision. All three are tests of the model; a stop is accepted only if every
//! held triangle is at a minimum of the true energy too: the force holding it, `2 K R`,
//! exceeds the cone's slope `κ` by less than the tolerance (as a force on its corners).
//! Otherwise such triangles are released (until they come back within `κ/(4K)`) and the
//! iterations go on, so a solve ends at a first-order point of `E` itself, kinks
//! included. More than `max_iterations` Newton iterations (default 1000), or a line
//! search that finds no decrease, is [`DefOpError::NoConvergence`].
//!
//! **Homotopy**: the targets are reached through stages `q(s) = y + s (q - y)` from the
//! start's handle positions `y`. A stage begins with the full step onto its targets; when
//! that step would flip a triangle (S-ARAP: cap below 1) the stage is abandoned and the
//! stage length halved, after a success it doubles. Intermediate stages stop at a
//! tolerance of 1e-2 (they only lead the way to the next: S-ARAP solves on the gingerbread
//! figure took 101 iterations on average with 1e-6 and 58 with 1e-2); the last one at the
//! requested tolerance. When a stage fails from a roughly converged one, whose left-over
//! gradient is part of the first step, that one is first finished to 1e-6. A warm start with a
//! flipped or collapsed triangle under S-ARAP restarts from the rest pose (a fallback,
//! counted in [`SolveReport::fallback`] and [`GroundTruth::fallbacks`]).
//!
//! **Puppets** ([`GroundTruth::with_puppet`]): a mesh made of sheets, one per part, joined
//! at joints. The energy gets each joint's penalty, `w |x_front(p) - x_back(p)|^2` on the
//! barycentric blends of the two triangles its point lies in at rest (as the deformers'
//! joints: `crate::deform::puppet`), with `w` [`JOINT_WEIGHT`] times the mean diagonal of
//! the rest ARAP Hessian, so that the two points stay together to a tiny fraction of the
//! size; the penalty is quadratic, so its gradient and Hessian enter Newton's model
//! exactly (3 x 3 vertex blocks between the two triangles, in the pattern). Sheets that no
//! handle reaches through the mesh and the joints are held where they are at rest (their
//! vertices fixed, as handles fix vertices), so no system is singular. A part that no
//! handle holds itself but a joint does (a head on its neck) could turn freely about the
//! joint at no cost, leaving the minimum undetermined: its vertices get a weak spring to
//! their rest positions, `μ/2 D_v |x_v - x̄_v|^2` with `μ` [`LEAST_MOTION_WEIGHT`] (`D`
//! the rest ARAP Hessian's diagonal), in the energy itself, so that such a part takes the
//! least motion (it follows its joint without turning), while a part that a joint or a
//! handle turns turns all the same.
//!
//! Everything runs on positions scaled by the power of two that brings the rest mesh's
//! largest coordinate into [1, 2) (exact), and every buffer is sized when the solver is
//! built: an iteration allocates nothing.

use std::sync::Arc;

use super::energy::{Energy, Local, RestTriangle, SignedSvd, KINK_CAP};
pub use super::error::DefOpError;
use super::linear::{cholesky, first_root};
pub use super::problem::{GroundTruthOptions, Handles, SolveReport, Start, MAX_POINT_HANDLES};
use crate::deform::handles::{at_vertices, check_connected, diagonal, in_triangles, HandlePoint};
use crate::deform::pattern::BlockPattern;
use crate::deform::puppet::{pieces, Joins};
use crate::deform::{DeformError, Puppet};
use crate::geometry::{normalising_exponent, scale_by_power_of_two, Point, MAX_COORDINATE};
use crate::mesh::Mesh;
use crate::sparse::{expand_blocks, fill_reducing_order, Numeric, Ordering, Symbolic};

mod step;

const NONE: usize = usize::MAX;
/// A barycentric weight this close to 1 puts a handle on a vertex (as the deformers do).
const AT_VERTEX: f64 = 1e-12;
const REGULARISATION: f64 = 1e-8;
const FLIP_MARGIN: f64 = 0.9;
const ARMIJO: f64 = 1e-4;
/// The longest step tried beyond a full step of the projected model (see `extrapolate`).
const MAX_EXTRAPOLATION: f64 = 64.0;
const SMALLEST_STAGE: f64 = 1.0 / 65536.0;
const STAGE_TOLERANCE: f64 = 1e-2;
/// The tolerance a stage is finished to when the next one failed from its rough solution.
const FINE_STAGE_TOLERANCE: f64 = 1e-6;
/// A step lowering the energy by less than this fraction of it is flat; after
/// `FLAT_STEPS` flat steps in a row the energy has converged to what doubles resolve.
const FLAT: f64 = 1e-14;
const FLAT_STEPS: usize = 3;
/// Per triangle, how the solver treats the S-ARAP kink: as the energy is (free), held at
/// the kink (held), or as it is again for the rest of the stage (released).
const FREE: u8 = 0;
/// Kinks with a smaller slope `κ` (near rotations, `κ ≈ 6 (Q - 1)^2`) are left alone.
const KINK_MIN: f64 = 1e-10;
const HELD: u8 = 1;
const RELEASED: u8 = 2;
/// Released because, the model converged, the force holding it at the kink exceeded the
/// cone's slope `κ`: the energy descends by leaving the kink. Held again only if it comes
/// back within `κ/(4K)` of the kink (it was released beyond `κ/(2K)`, so that is no cycle).
const LEFT: u8 = 3;
/// A held triangle within `SETTLED κ` of its kink is there or on its way: a released one
/// that comes back this close is held again, and a step of the model that does not descend
/// the energy releases the held triangles farther away than this.
const SETTLED: f64 = 1e-3;
/// Handles within this fraction of the shape's size are coincident; handles are on their
/// targets within it.
const NEAR: f64 = 1e-12;

/// The weight of a puppet's joint penalty relative to the mean diagonal entry of the rest
/// ARAP Hessian (as `crate::deform::AKAP_JOINT_WEIGHT` is to AKAP's systems): a joint's
/// two points stay together to about the force on it over this weight.
pub const JOINT_WEIGHT: f64 = 1e4;

/// The weight of the spring to rest of a puppet's parts that no handle holds itself,
/// relative to the rest ARAP Hessian's diagonal: it decides only what nothing else does
/// (how such a part turns about its one joint).
pub const LEAST_MOTION_WEIGHT: f64 = 1e-6;

/// A puppet's joint in the solver: its six vertices with their blend coefficients and,
/// per coordinate, the slots of its penalty's 6 x 6 Hessian entries (`NONE` where fixed).
type JointTerm = ([(u32, f64); 6], [[usize; 36]; 2]);

/// One triangle: its rest shape, vertices and the slots of its 6 x 6 Hessian entries.
#[derive(Debug, Clone)]
struct Element {
    rest: RestTriangle,
    vertices: [usize; 3],
    /// Slot of entry `(a, b)` (local unknowns `2 corner + coordinate`) at `6 a + b`;
    /// `NONE` when either unknown is fixed.
    slots: [usize; 36],
}

/// The ARAP or S-ARAP ground-truth solver for one mesh and one handle set.
#[derive(Debug, Clone)]
pub struct GroundTruth {
    energy: Energy,
    options: GroundTruthOptions,
    /// Positions are scaled by `2^unit` inside.
    unit: i32,
    /// The scaled rest shape's bounding-box diagonal.
    size: f64,
    rest: Vec<Point>,
    elements: Vec<Element>,
    handles: Vec<HandlePoint>,
    /// Per handle, the vertex it fixes, or `NONE` for a handle inside a triangle.
    pinned: Vec<usize>,
    /// Per vertex, whether a handle fixes it, or it is on a sheet no handle reaches.
    fixed: Vec<bool>,
    /// A puppet's vertices on sheets no handle reaches: held at rest.
    frozen: Vec<usize>,
    /// A puppet's joints: per joint, its six vertices with their blend coefficients
    /// (`x_front - x_back = sum c_k x_(v_k)`) and, per coordinate, the slot of each entry
    /// `(a, b)` of the penalty's Hessian at `6 a + b` (`NONE` where either vertex is fixed).
    joints: Vec<JointTerm>,
    /// The joints' penalty weight, `w`.
    joint_weight: f64,
    /// The weight `ρ` of the augmented term `ρ CᵀC` that conditions the model for handles
    /// inside triangles (`assemble`): the mean of the rest ARAP Hessian's diagonal.
    point_weight: f64,
    /// Per unknown, the spring to rest of parts no handle holds itself (`μ D`; 0 elsewhere).
    springs: Vec<f64>,
    /// The handles inside triangles (indices into `handles`).
    points: Vec<usize>,
    /// Per unknown, the slot of its diagonal entry.
    diagonal_slots: Vec<usize>,
    /// Per unknown, the regularisation's diagonal scale (0 for fixed unknowns).
    stiffness: Vec<f64>,
    values: Vec<f64>,
    numeric: Numeric,
    /// Cholesky factor of `B B^T` (`B` the weights of the handles inside triangles on free
    /// vertices), for the least-squares multipliers.
    gram: Vec<f64>,
    /// Per triangle, [`FREE`], [`HELD`], [`RELEASED`] or [`LEFT`].
    state: Vec<u8>,
    // Buffers, sized once.
    x: Vec<Point>,
    trial: Vec<Point>,
    saved: Vec<Point>,
    /// The gradient of the Newton model (held triangles' penalties instead of their cones).
    grad: Vec<f64>,
    /// The gradient of the energy.
    true_grad: Vec<f64>,
    rhs: Vec<f64>,
    step: Vec<f64>,
    fixed_step: Vec<f64>,
    work: Vec<f64>,
    columns: Vec<f64>,
    schur: Vec<f64>,
    small: Vec<f64>,
    residual: Vec<f64>,
    from: Vec<Point>,
    goal: Vec<Point>,
    stage_targets: Vec<Point>,
    solves: usize,
    fallbacks: usize,
}

impl GroundTruth {
    /// Prepares the solver: checks the mesh and handles, the rest triangles, the pattern and
    /// its symbolic analysis, and every buffer.
    pub fn new(
        mesh: &Mesh,
        handles: Handles<'_>,
        energy: Energy,
        options: GroundTruthOptions,
    ) -> Result<Self, DefOpError> {
        Self::build(mesh, None, handles, energy, options)
    }

    /// The solver for a puppet: `mesh` made of sheets, one per part of `puppet`, that may
    /// overlap and need not be connected, joined at its joints (module documentation).
    /// Parts and joints are checked as [`crate::deform::Deformer::with_puppet`] checks them
    /// ([`DefOpError::InvalidPuppet`]).
    pub fn with_puppet(
        mesh: &Mesh,
        puppet: &Puppet,
        handles: Handles<'_>,
        energy: Energy,
        options: GroundTruthOptions,
    ) -> Result<Self, DefOpError> {
        Self::build(mesh, Some(puppet), handles, energy, options)
    }

    fn build(
        mesh: &Mesh,
        puppet: Option<&Puppet>,
        handles: Handles<'_>,
        energy: Energy,
        options: GroundTruthOptions,
    ) -> Result<Self, DefOpError> {
        options.check()?;
        let joins = match puppet {
            Some(puppet) => puppet.joins(mesh).map_err(DefOpError::InvalidPuppet)?,
            None => {
                check_connected(mesh).map_err(|e| match e {
                    DeformError::Disconnected { components } => DefOpError::Disconnected { components },
                    other => DefOpError::InvalidHandle(other),
                })?;
                Joins::default()
            }
        };
        let points = match handles {
            Handles::Vertices(vertices) => at_vertices(mesh, vertices),
            Handles::Points { triangles, barycentric } => in_triangles(mesh, triangles, barycentric),
        }
        .map_err(DefOpError::InvalidHandle)?;
        if points.is_empty() {
            return Err(DefOpError::NoHandles);
        }
        let (n, h) = (mesh.vertex_count(), points.len());
        let unit = normalising_exponent(mesh.positions().iter().copied()).clamp(-1022, 1022);
        let rest: Vec<Point> = mesh.positions().iter().map(|p| p.map(|c| scale_by_power_of_two(c, unit))).collect();
        let size = diagonal(&rest);
        let rest_points: Vec<Point> = points.iter().map(|p| p.position(&rest)).collect();
        if let Some((first, second)) = coincident_pair(&rest_points, NEAR * size) {
            return Err(DefOpError::CoincidentHandles { first, second });
        }
        let pinned: Vec<usize> = points
            .iter()
            .map(|p| (0..3).find(|&k| p.weights[k] >= 1.0 - AT_VERTEX).map_or(NONE, |k| p.vertices[k] as usize))
            .collect();
        let mut fixed = vec![false; n];
        for &v in pinned.iter().filter(|&&v| v != NONE) {
            fixed[v] = true;
        }
        let extra = joins.extra_pairs();
        // A puppet's sheets that no handle reaches (through the mesh and the joints).
        let frozen: Vec<usize> = if joins.puppet {
            let piece = pieces(mesh, &extra);
            let mut held = vec![false; n];
            for p in &points {
                for (&v, &w) in p.vertices.iter().zip(&p.weights) {
                    if w != 0.0 {
                        held[piece[v as usize] as usize] = true;
                    }
                }
            }
            (0..n).filter(|&v| !held[piece[v] as usize]).collect()
        } else {
            Vec::new()
        };
        for &v in &frozen {
            fixed[v] = true;
        }
        let point_handles: Vec<usize> = (0..h).filter(|&k| pinned[k] == NONE).collect();
        if point_handles.len() > MAX_POINT_HANDLES {
            return Err(DefOpError::TooManyPointHandles { count: point_handles.len(), limit: MAX_POINT_HANDLES });
        }

        let pattern = BlockPattern::with_pairs(mesh, 2, &extra);
        // Entry (2 row + k, 2 col + l) from the slot of the vertex block (row, col).
        let entry = |col: usize, k: usize, l: usize, slot: usize| slot + l * pattern.column_length(col) + k;
        let triangle_slots = pattern.triangle_slots(mesh);
        let mut elements = Vec::with_capacity(mesh.triangle_count());
        let mut stiffness = vec![0.0; 2 * n];
        for (t, s) in mesh.triangles().iter().zip(&triangle_slots) {
            let vertices = t.map(|v| v as usize);
            let rest_triangle = RestTriangle::new(vertices.map(|v| rest[v]))
                .expect("a validated mesh's triangles are counter-clockwise and not degenerate");
            let mut slots = [NONE; 36];
            for a in 0..6 {
                for b in 0..6 {
                    let (vi, vj) = (vertices[a / 2], vertices[b / 2]);
                    if !fixed[vi] && !fixed[vj] {
                        slots[6 * a + b] = entry(vj, a % 2, b % 2, s[3 * (a / 2) + b / 2]);
                    }
                }
            }
            // The rest ARAP Hessian's diagonal: 2 A_t |w_v|^2 per unknown.
            for (v, w) in vertices.iter().zip(rest_triangle.weights()) {
                let d = 2.0 * rest_triangle.area * (w[0] * w[0] + w[1] * w[1]);
                stiffness[2 * v] += d;
                stiffness[2 * v + 1] += d;
            }
            elements.push(Element { rest: rest_triangle, vertices, slots });
        }
        let diagonal_slots: Vec<usize> =
            (0..2 * n).map(|d| entry(d / 2, d % 2, d % 2, pattern.slot(d / 2, d / 2).expect("diagonal"))).collect();
        let joint_weight = JOINT_WEIGHT * stiffness.iter().sum::<f64>() / stiffness.len().max(1) as f64;
        let mut springs = vec![0.0; 2 * n];
        if let Some(puppet) = puppet {
            let mut handled = vec![false; n];
            for p in &points {
                for (&v, &w) in p.vertices.iter().zip(&p.weights) {
                    handled[v as usize] |= w != 0.0;
                }
            }
            for part in &puppet.parts {
                let corners = || part.triangles.iter().flat_map(|&t| mesh.triangles()[t as usize]);
                if !corners().any(|v| handled[v as usize]) {
                    for v in corners().map(|v| v as usize).filter(|&v| !fixed[v]) {
                        springs[2 * v] = LEAST_MOTION_WEIGHT * stiffness[2 * v];
                        springs[2 * v + 1] = LEAST_MOTION_WEIGHT * stiffness[2 * v + 1];
                    }
                }
            }
        }
        let joints = joins
            .points
            .iter()
            .map(|pair| {
                let blend = Joins::blend(pair);
                let mut slots = [[NONE; 36]; 2];
                for (a, &(v, _)) in blend.iter().enumerate() {
                    for (b, &(u, _)) in blend.iter().enumerate() {
                        let (v, u) = (v as usize, u as usize);
                        if fixed[v] || fixed[u] {
                            continue;
                        }
                        let block = pattern.slot(v, u).expect("the joints' vertex pairs are in the pattern");
                        for (c, coordinate) in slots.iter_mut().enumerate() {
                            coordinate[6 * a + b] = entry(u, c, c, block);
                        }
                    }
                }
                (blend, slots)
            })
            .collect();
        for (d, s) in stiffness.iter_mut().enumerate() {
            if fixed[d / 2] {
                *s = 0.0;
            }
        }

        let gram = gram_factor(&points, &point_handles, &fixed)?;
        let (ptr, adj) = mesh.vertex_graph();
        let order = expand_blocks(&fill_reducing_order(&ptr, &adj, mesh.positions(), 2), 2);
        let nnz = pattern.nnz();
        let matrix = pattern.matrix(vec![0.0; nnz]);
        let symbolic = Symbolic::analyse(matrix.view(), &Ordering::Given(order))?;
        let numeric = Numeric::try_new(Arc::new(symbolic))?;
        let m = 2 * point_handles.len();
        Ok(Self {
            energy,
            options,
            unit,
            size,
            x: rest.clone(),
            trial: rest.clone(),
            saved: rest.clone(),
            rest,
            elements,
            handles: points,
            pinned,
            fixed,
            frozen,
            joints,
            joint_weight,
            point_weight: stiffness.iter().sum::<f64>() / stiffness.len().max(1) as f64,
            springs,
            points: point_handles,
            diagonal_slots,
            stiffness,
            values: vec![0.0; nnz],
            numeric,
            gram,
            state: vec![FREE; mesh.triangle_count()],
            grad: vec![0.0; 2 * n],
            true_grad: vec![0.0; 2 * n],
            rhs: vec![0.0; 2 * n],
            step: vec![0.0; 2 * n],
            fixed_step: vec![0.0; 2 * n],
            work: vec![0.0; 2 * n],
            columns: vec![0.0; m * 2 * n],
            schur: vec![0.0; m * m],
            small: vec![0.0; m],
            residual: vec![0.0; m],
            from: vec![[0.0; 2]; h],
            goal: vec![[0.0; 2]; h],
            stage_targets: vec![[0.0; 2]; h],
            solves: 0,
            fallbacks: 0,
        })
    }

    /// The energy minimised.
    pub fn energy(&self) -> Energy {
        self.energy
    }

    /// The options.
    pub fn options(&self) -> GroundTruthOptions {
        self.options
    }

    /// The number of handles.
    pub fn handle_count(&self) -> usize {
        self.handles.len()
    }

    /// The handles' rest positions (the paper's `P`).
    pub fn rest_handle_positions(&self) -> Vec<Point> {
        let back = |p: Point| p.map(|c| scale_by_power_of_two(c, -self.unit));
        self.handles.iter().map(|h| back(h.position(&self.rest))).collect()
    }

    /// Successful solves so far.
    pub fn solves(&self) -> usize {
        self.solves
    }

    /// Successful solves so far whose warm start had flipped triangles and restarted from
    /// the rest pose.
    pub fn fallbacks(&self) -> usize {
        self.fallbacks
    }

    /// The energy `E` of a pose (`+∞` for S-ARAP with a flipped or collapsed triangle).
    pub fn energy_of(&self, positions: &[Point]) -> Result<f64, DefOpError> {
        check_points("start", positions, self.rest.len())?;
        let scaled: Vec<Point> = positions.iter().map(|p| p.map(|c| scale_by_power_of_two(c, self.unit))).collect();
        Ok(scale_by_power_of_two(self.total_energy(&scaled), -2 * self.unit))
    }

    /// Solves eq. (6) for one set of targets (one per handle, in handle order) from a start.
    /// On error nothing changes.
    pub fn solve(&mut self, targets: &[Point], start: Start<'_>) -> Result<SolveReport, DefOpError> {
        check_points("targets", targets, self.handles.len())?;
        let into = |p: &Point| p.map(|c| scale_by_power_of_two(c, self.unit));
        for (g, t) in self.goal.iter_mut().zip(targets) {
            *g = into(t);
        }
        if self.energy.blocks_flips() {
            if let Some((first, second)) = coincident_pair(&self.goal, NEAR * self.size) {
                return Err(DefOpError::CoincidentTargets { first, second });
            }
        }
        let mut fallback = false;
        match start {
            Start::Rest => self.x.copy_from_slice(&self.rest),
            Start::Pose(pose) => {
                check_points("start", pose, self.rest.len())?;
                for (x, p) in self.x.iter_mut().zip(pose) {
                    *x = into(p);
                }
                if self.energy.blocks_flips() && !self.total_energy(&self.x).is_finite() {
                    self.x.copy_from_slice(&self.rest);
                    fallback = true;
                }
            }
        }
        for (f, h) in self.from.iter_mut().zip(&self.handles) {
            *f = h.position(&self.x);
        }
        let mut iterations = 0;
        let (stages, gradient) = self.homotopy(&mut iterations)?;
        self.solves += 1;
        self.fallbacks += usize::from(fallback);
        let back = |p: &Point| p.map(|c| scale_by_power_of_two(c, -self.unit));
        Ok(SolveReport {
            positions: self.x.iter().map(back).collect(),
            energy: scale_by_power_of_two(self.total_energy(&self.x), -2 * self.unit),
            iterations,
            fallback,
            stages,
            gradient,
        })
    }

    /// Stages from `from` to `goal` (module documentation): the number of stages and the
    /// final gradient.
    fn homotopy(&mut self, iterations: &mut usize) -> Result<(usize, f64), DefOpError> {
        let (mut done, mut length, mut stages) = (0.0f64, 1.0f64, 0);
        // Whether `saved` was converged only to `STAGE_TOLERANCE`.
        let mut rough = false;
        self.saved.copy_from_slice(&self.x);
        loop {
            let s = (done + length).min(1.0);
            let last = s >= 1.0;
            self.set_stage_targets(s);
            let tolerance = if last { self.options.tolerance } else { self.options.tolerance.max(STAGE_TOLERANCE) };
            match self.newton(tolerance, iterations)? {
                Some(gradient) => {
                    stages += 1;
                    if last {
                        return Ok((stages, gradient));
                    }
                    done = s;
                    length = (2.0 * length).min(1.0);
                    rough = true;
                    self.saved.copy_from_slice(&self.x);
                }
                None => {
                    self.x.copy_from_slice(&self.saved);
                    if rough {
                        // A roughly converged stage's left-over gradient is part of the next
                        // first step, and can flip a triangle however short the stage: the
                        // stage is finished properly before any shorter one is tried.
                        rough = false;
                        self.set_stage_targets(done);
                        if self.newton(self.options.tolerance.max(FINE_STAGE_TOLERANCE), iterations)?.is_some() {
                            self.saved.copy_from_slice(&self.x);
                            continue;
                        }
                        self.x.copy_from_slice(&self.saved);
                    }
                    length /= 2.0;
                    if length < SMALLEST_STAGE {
                        return Err(DefOpError::Unreachable { reached: done });
                    }
                }
            }
        }
    }

    /// The handles' targets at stage `s`: `from + s (goal - from)`, the goal itself at 1.
    fn set_stage_targets(&mut self, s: f64) {
        for ((t, f), g) in self.stage_targets.iter_mut().zip(&self.from).zip(&self.goal) {
            *t = if s >= 1.0 { *g } else { [f[0] + s * (g[0] - f[0]), f[1] + s * (g[1] - f[1])] };
        }
    }

    /// Newton iterations towards `stage_targets`: `Some(gradient)` once converged, `None`
    /// when the first step onto the targets would flip a triangle (S-ARAP).
    fn newton(&mut self, tolerance: f64, iterations: &mut usize) -> Result<Option<f64>, DefOpError> {
        let mut gradient = f64::INFINITY;
        // Consecutive steps that lowered the energy by less than `FLAT` of itself.
        let mut flat = 0;
        self.state.fill(FREE);
        let start = *iterations;
        // Whether the last step was a full Newton step (only then is a held triangle that
        // has not reached its kink released).
        let mut full_step = true;
        loop {
            let feasible = self.residuals() <= NEAR * self.size;
            let restart = *iterations == start;
            // A step that is not a descent direction of the true energy (a held triangle far
            // from its kink) is computed again with every triangle released.
            let mut hold = true;
            loop {
                // The exact Hessian where it is positive definite (quadratic convergence),
                // else the projected one.
                let mut exact = feasible;
                let energy = self.assemble(restart, full_step, feasible, exact, hold);
                if feasible {
                    gradient = self.constrained_gradient() / self.size;
                    if gradient <= tolerance {
                        if self.release_pinned(tolerance) {
                            continue;
                        }
                        return Ok(Some(gradient));
                    }
                }
                let stalled =
                    DefOpError::NoConvergence { iterations: *iterations, gradient, tolerance: self.options.tolerance };
                if *iterations >= self.options.max_iterations {
                    return Err(stalled);
                }
                if exact && self.numeric.refactor_values(&self.values).is_err() {
                    exact = false;
                    self.assemble(restart, full_step, feasible, exact, hold);
                }
                if !exact {
                    self.factor()?;
                }
                // With handles inside triangles, a nearly singular exact Hessian (factored,
                // but with tiny pivots) can leave the constraints' Schur complement without a
                // numerically positive pivot: the projected model is used instead.
                if let Err(e) = self.newton_step() {
                    if !exact {
                        return Err(e);
                    }
                    exact = false;
                    self.assemble(restart, full_step, feasible, exact, hold);
                    self.factor()?;
                    self.newton_step()?;
                }
                let slope: f64 = self.grad.iter().zip(&self.step).map(|(g, d)| g * d).sum();
                // The line search is on the true energy, with its true slope (held triangles'
                // cones included).
                let true_slope: f64 = self.true_grad.iter().zip(&self.step).map(|(g, d)| g * d).sum();
                if feasible && (-slope <= (tolerance * self.size).powi(2) || flat >= FLAT_STEPS) {
                    if self.release_pinned(tolerance) {
                        flat = 0;
                        continue;
                    }
                    return Ok(Some(gradient));
                }
                let cap = if self.energy.blocks_flips() { FLIP_MARGIN * self.first_flip() } else { f64::INFINITY };
                full_step = true;
                if !feasible {
                    if cap < 1.0 {
                        return Ok(None);
                    }
                    self.move_to_trial(1.0);
                    for (k, &v) in self.pinned.iter().enumerate() {
                        if v != NONE {
                            self.trial[v] = self.stage_targets[k];
                        }
                    }
                    if !self.total_energy(&self.trial).is_finite() {
                        return Ok(None);
                    }
                    break;
                }
                // Below what the energy can resolve, a full step is taken as it comes. But
                // when the model's step does not resolvably descend the energy while it holds
                // a triangle far from its kink (R > SETTLED κ: held once R <= κ/2, and not
                // at the kink at all), the fault is the model's (its penalty K R^2 there is
                // no approximation of the energy), not rounding: such triangles are released
                // and the step computed again. Taking such steps as "flat" ended solves short
                // of the minimum (three in a row stop a stage). Triangles held near their
                // kink may raise the energy slightly (by the cone over `κ/K`) as they settle.
                let resolvable = -true_slope > 1e-12 * energy.abs();
                if !resolvable && self.release_unsettled() {
                    continue;
                }
                let mut alpha = cap.min(1.0);
                full_step = alpha == 1.0;
                let found = loop {
                    self.move_to_trial(alpha);
                    let e = self.total_energy(&self.trial);
                    let armijo = true_slope < 0.0 && e <= energy + ARMIJO * alpha * true_slope;
                    if armijo || (!resolvable && e <= energy + 1e-12 * energy.abs()) {
                        flat = if energy - e <= FLAT * energy.abs() { flat + 1 } else { 0 };
                        break Some(e);
                    }
                    alpha /= 2.0;
                    full_step = false;
                    if alpha < 1e-12 {
                        break None;
                    }
                };
                if let Some(e) = found {
                    if !exact && alpha == 1.0 {
                        self.extrapolate(cap, e);
                    }
                    break;
                }
                if hold && self.state.contains(&HELD) {
                    hold = false;
                    continue;
                }
                return Err(stalled);
            }
            if !self.trial.iter().flatten().all(|c| c.abs() <= scale_by_power_of_two(MAX_COORDINATE, self.unit)) {
                return Err(DefOpError::NonFiniteResult);
            }
            self.snap_points();
            std::mem::swap(&mut self.x, &mut self.trial);
            *iterations += 1;
        }
    }

    /// Puts every handle inside a triangle on its stage target in `trial` exactly (to
    /// rounding): the step's range-space solve meets `C d = r` only to the accuracy of the
    /// sparse solves (on a 500-vertex mesh with nine such handles, about 1e-11 of the size),
    /// above the [`NEAR`] that decides feasibility, so solves never became feasible. Each
    /// handle's left-over residual `r` is spread over its triangle's free corners as the
    /// least-norm correction `x_v += w_v r / Σ w_u²`, twice (two handles may share a
    /// triangle); a correction of the order of rounding, which flips nothing.
    fn snap_points(&mut self) {
        for _ in 0..2 {
            for &k in &self.points {
                let h = &self.handles[k];
                let free = |v: &u32| !self.fixed[*v as usize];
                let norm: f64 = h.vertices.iter().zip(h.weights).filter(|(v, _)| free(v)).map(|(_, w)| w * w).sum();
                if norm == 0.0 {
                    continue;
                }
                let p = h.position(&self.trial);
                let r = [self.stage_targets[k][0] - p[0], self.stage_targets[k][1] - p[1]];
                for (v, w) in h.vertices.iter().zip(h.weights) {
                    if free(v) {
                        let x = &mut self.trial[*v as usize];
                        x[0] += w * r[0] / norm;
                        x[1] += w * r[1] / norm;
                    }
                }
            }
        }
    }

    /// `fixed_step` (target minus position of fixed unknowns, 0 elsewhere) and `residual`
    /// (target minus position of each handle inside a triangle); returns the largest.
    fn residuals(&mut self) -> f64 {
        self.fixed_step.fill(0.0);
        let mut largest: f64 = 0.0;
        for (k, &v) in self.pinned.iter().enumerate() {
            if v != NONE {
                for c in 0..2 {
                    self.fixed_step[2 * v + c] = self.stage_targets[k][c] - self.x[v][c];
                    largest = largest.max(self.fixed_step[2 * v + c].abs());
                }
            }
        }
        for &v in &self.frozen {
            for c in 0..2 {
                self.fixed_step[2 * v + c] = self.rest[v][c] - self.x[v][c];
                largest = largest.max(self.fixed_step[2 * v + c].abs());
            }
        }
        for (j, &k) in self.points.iter().enumerate() {
            let p = self.handles[k].position(&self.x);
            for (c, pc) in p.iter().enumerate() {
                self.residual[2 * j + c] = self.stage_targets[k][c] - pc;
                largest = largest.max(self.residual[2 * j + c].abs());
            }
        }
        largest
    }

    /// Energy, gradient, the regularised projected Hessian on the free unknowns (identity
    /// on fixed ones) and the right-hand side `-g - H_uf d_f` (`d_f` on fixed unknowns).
    fn assemble(&mut self, restart: bool, full_step: bool, feasible: bool, exact: bool, hold: bool) -> f64 {
        // A triangle is held once its cone dominates, or, at the first iteration of a stage,
        // only if it is at the kink already (a warm start from a solution stays one).
        let hold_below = if restart { 1.0 / KINK_CAP } else { 0.5 };
        self.grad.fill(0.0);
        self.true_grad.fill(0.0);
        self.values.fill(0.0);
        self.rhs.fill(0.0);
        let mut energy = 0.0;
        for (el, state) in self.elements.iter().zip(self.state.iter_mut()) {
            let p = el.vertices.map(|v| self.x[v]);
            let j = el.rest.jacobian(p);
            let local = Local::new(self.energy, &j);
            *state = match (local.as_ref().and_then(Local::kink), *state) {
                (_, HELD) if !hold => RELEASED,
                (_, state) if !hold => state,
                (Some((kappa, r)), LEFT) if feasible && kappa > KINK_MIN && r <= kappa / (4.0 * KINK_CAP) => HELD,
                (_, LEFT) => LEFT,
                (Some((kappa, r)), FREE) if feasible && kappa > KINK_MIN && r <= kappa * hold_below => HELD,
                (Some((kappa, r)), RELEASED) if feasible && kappa > KINK_MIN && r <= kappa * SETTLED => HELD,
                (Some((kappa, r)), HELD) if full_step && r > kappa / KINK_CAP => RELEASED,
                (None, HELD) => RELEASED,
                (_, state) => state,
            };
            let Some((local, (Some(projected), exact_hessian))) = local.map(|l| {
                let hessians = l.hessians(exact);
                (l, hessians)
            }) else {
                // Infinite energy: never an iterate (the line search keeps S-ARAP finite).
                energy = f64::INFINITY;
                continue;
            };
            let true_dpsi = local.gradient();
            energy += el.rest.area * local.density();
            let held = if *state == HELD { local.held() } else { None };
            let (dpsi, hj) = match held {
                Some((_, g, h)) => (g, h),
                None if exact => (true_dpsi, exact_hessian.unwrap_or(projected)),
                None => (true_dpsi, projected),
            };
            let w = el.rest.weights();
            let h6 = el.rest.expand(&hj);
            for a in 0..6 {
                let (v, i) = (el.vertices[a / 2], a % 2);
                let row = 2 * v + i;
                self.grad[row] += el.rest.area * (dpsi[i][0] * w[a / 2][0] + dpsi[i][1] * w[a / 2][1]);
                self.true_grad[row] += el.rest.area * (true_dpsi[i][0] * w[a / 2][0] + true_dpsi[i][1] * w[a / 2][1]);
                if self.fixed[v] {
                    continue;
                }
                for (b, hab) in h6[a].iter().enumerate() {
                    let col = 2 * el.vertices[b / 2] + b % 2;
                    self.rhs[row] -= hab * self.fixed_step[col];
                    if el.slots[6 * a + b] != NONE {
                        self.values[el.slots[6 * a + b]] += hab;
                    }
                }
            }
        }
        // The joints' penalty, w |sum c_k x_k|^2 per coordinate: quadratic, so exact.
        let w = self.joint_weight;
        for (blend, slots) in &self.joints {
            for (c, coordinate) in slots.iter().enumerate() {
                let gap: f64 = blend.iter().map(|&(v, k)| k * self.x[v as usize][c]).sum();
                energy += w * gap * gap;
                for (a, &(v, cv)) in blend.iter().enumerate() {
                    let row = 2 * v as usize + c;
                    self.grad[row] += 2.0 * w * cv * gap;
                    self.true_grad[row] += 2.0 * w * cv * gap;
                    if self.fixed[v as usize] {
                        continue;
                    }
                    for (b, &(u, cu)) in blend.iter().enumerate() {
                        let h = 2.0 * w * cv * cu;
                        self.rhs[row] -= h * self.fixed_step[2 * u as usize + c];
                        if coordinate[6 * a + b] != NONE {
                            self.values[coordinate[6 * a + b]] += h;
                        }
                    }
                }
            }
        }
        // Handles inside triangles: the model gets `ρ CᵀC` and the right-hand side `ρ Cᵀ r`,
        // which leaves the constrained step unchanged (it meets `C d = r`) but makes the
        // matrix definite along the constraints. Without it, with no vertex pinned, the
        // energy's rigid motions are held only by the `ε D` regularisation, `H⁻¹` is
        // dominated by them and the constraints' Schur complement `C H⁻¹ Cᵀ` loses its
        // positive definiteness to cancellation (nine handles on a 500-vertex mesh).
        for (j, &k) in self.points.iter().enumerate() {
            let h = &self.handles[k];
            let el = &self.elements[h.triangle];
            for c in 0..2 {
                let r = self.residual[2 * j + c];
                for (&va, wa) in h.vertices.iter().zip(h.weights) {
                    if self.fixed[va as usize] {
                        continue;
                    }
                    let la = el.vertices.iter().position(|&u| u == va as usize).expect("a corner");
                    self.rhs[2 * va as usize + c] += self.point_weight * wa * r;
                    for (&vb, wb) in h.vertices.iter().zip(h.weights) {
                        let lb = el.vertices.iter().position(|&u| u == vb as usize).expect("a corner");
                        let slot = el.slots[6 * (2 * la + c) + 2 * lb + c];
                        if slot != NONE {
                            self.values[slot] += self.point_weight * wa * wb;
                        }
                    }
                }
            }
        }
        // The springs to rest, mu D / 2 (x - rest)^2 per unknown.
        for (d, &k) in self.springs.iter().enumerate().filter(|(_, &k)| k != 0.0) {
            let offset = self.x[d / 2][d % 2] - self.rest[d / 2][d % 2];
            energy += 0.5 * k * offset * offset;
            self.grad[d] += k * offset;
            self.true_grad[d] += k * offset;
            self.values[self.diagonal_slots[d]] += k;
        }
        for (d, &slot) in self.diagonal_slots.iter().enumerate() {
            if self.fixed[d / 2] {
                self.values[slot] = 1.0;
                self.rhs[d] = self.fixed_step[d];
            } else {
                self.values[slot] += REGULARISATION * self.stiffness[d];
                self.rhs[d] -= self.grad[d];
            }
        }
        energy
    }

    /// Releases every held triangle farther than `SETTLED κ` from its kink ([`RELEASED`]:
    /// held again if it comes back); whether there was one.
    fn release_unsettled(&mut self) -> bool {
        let mut released = false;
        for (el, state) in self.elements.iter().zip(self.state.iter_mut()) {
            if *state == HELD {
                let j = el.rest.jacobian(el.vertices.map(|v| self.x[v]));
                if self.energy.kink(&j).is_none_or(|(kappa, r)| r > kappa * SETTLED) {
                    *state = RELEASED;
                    released = true;
                }
            }
        }
        released
    }

    /// Releases ([`LEFT`]) every held triangle whose minimum is not at its kink, once the
    /// held model has converged; whether there was one. Every stop goes through this, so a
    /// solve ends at a first-order point of the energy itself, not only of the model.
    ///
    /// At a minimum of the model a held triangle sits where the rest of the mesh pulls its
    /// anti-similarity part with the penalty's force `2 K R` (the `R`-derivative of `K R^2`).
    /// The kink is a minimum of the true energy in that direction only if that force is at
    /// most the cone's slope `κ` (its largest subgradient); the excess `2 K R - κ` is the
    /// slope at which the true energy descends by leaving the kink, and it counts when, as
    /// a force on the triangle's corners (`A_t (2 K R - κ) ∂R/∂x`), it exceeds the
    /// gradient tolerance. Without this check the solver stopped at the model's minimum with
    /// triangles pinned at kinks that the true energy leaves, and even far from them (a
    /// triangle is held once `R <= κ/2`, and released during a stage only after a full
    /// step, beyond `κ/K`: a force of twice the cone's slope).
    fn release_pinned(&mut self, tolerance: f64) -> bool {
        let mut released = false;
        for (el, state) in self.elements.iter().zip(self.state.iter_mut()) {
            if *state != HELD {
                continue;
            }
            let j = el.rest.jacobian(el.vertices.map(|v| self.x[v]));
            let Some((kappa, r)) = self.energy.kink(&j) else { continue };
            let excess = 2.0 * KINK_CAP * r - kappa;
            if excess <= 0.0 {
                continue;
            }
            // ∂R/∂J = [[F, G], [G, -F]] / (2R), and ∂J_ik/∂x_(v,i) = w_v[k].
            let s = SignedSvd::new(&j);
            let dr = [[s.f, s.g], [s.g, -s.f]].map(|row| row.map(|x| x / (2.0 * r)));
            let force = el
                .rest
                .weights()
                .iter()
                .flat_map(|w| (0..2).map(move |i| (dr[i][0] * w[0] + dr[i][1] * w[1]).abs()))
                .fold(0.0, f64::max);
            if el.rest.area * excess * force > tolerance * self.size {
                *state = LEFT;
                released = true;
            }
        }
        released
    }

    /// The smallest `α > 0` at which a triangle's determinant vanishes along `step`.
    fn first_flip(&self) -> f64 {
        let mut first = f64::INFINITY;
        for el in &self.elements {
            let [a, b, c] = el.vertices;
            let d = |v: usize| [self.step[2 * v], self.step[2 * v + 1]];
            let (e1, e2) = (sub(self.x[b], self.x[a]), sub(self.x[c], self.x[a]));
            let (f1, f2) = (sub(d(b), d(a)), sub(d(c), d(a)));
            // det([e1 + α f1, e2 + α f2]) = c0 + α c1 + α^2 c2.
            let c0 = e1[0] * e2[1] - e1[1] * e2[0];
            let c1 = e1[0] * f2[1] - e1[1] * f2[0] + f1[0] * e2[1] - f1[1] * e2[0];
            let c2 = f1[0] * f2[1] - f1[1] * f2[0];
            first = first.min(first_root(c0, c1, c2));
        }
        first
    }

    /// After a full step of the projected model was accepted (to `energy`): moves `trial` to
    /// that step doubled while the energy keeps falling, at most [`MAX_EXTRAPOLATION`] times and below
    /// `cap`. The projected Hessian drops the energy's negative curvature, so near a
    /// saddle its steps are far too short: on the gingerbread figure, ARAP solves spent
    /// dozens of full steps each lowering the energy by a millionth.
    fn extrapolate(&mut self, cap: f64, energy: f64) {
        let (mut best, mut alpha) = (energy, 1.0);
        while 2.0 * alpha <= cap.min(MAX_EXTRAPOLATION) {
            self.move_to_trial(2.0 * alpha);
            let e = self.total_energy(&self.trial);
            // Not below (or NaN): stop.
            if e.partial_cmp(&best) != Some(std::cmp::Ordering::Less) {
                break;
            }
            (best, alpha) = (e, 2.0 * alpha);
        }
        self.move_to_trial(alpha);
    }

    fn move_to_trial(&mut self, alpha: f64) {
        for (v, (t, x)) in self.trial.iter_mut().zip(&self.x).enumerate() {
            *t = [x[0] + alpha * self.step[2 * v], x[1] + alpha * self.step[2 * v + 1]];
        }
    }

    fn total_energy(&self, positions: &[Point]) -> f64 {
        let joints: f64 = (self.joints.iter())
            .flat_map(|(blend, _)| {
                (0..2).map(|c| blend.iter().map(|&(v, k)| k * positions[v as usize][c]).sum::<f64>().powi(2))
            })
            .sum();
        let elements: f64 =
            self.elements.iter().map(|el| el.rest.energy(self.energy, el.vertices.map(|v| positions[v]))).sum();
        let springs: f64 = (self.springs.iter().enumerate())
            .filter(|(_, &k)| k != 0.0)
            .map(|(d, &k)| 0.5 * k * (positions[d / 2][d % 2] - self.rest[d / 2][d % 2]).powi(2))
            .sum();
        elements + self.joint_weight * joints + springs
    }
}

/// Checks points given by the caller: the count, and each finite within the limits.
fn check_points(what: &'static str, points: &[Point], expected: usize) -> Result<(), DefOpError> {
    if points.len() != expected {
        return Err(DefOpError::Length { what, expected, found: points.len() });
    }
    match points.iter().position(|p| !p.iter().all(|c| c.abs() <= MAX_COORDINATE)) {
        Some(index) => Err(DefOpError::InvalidPoint { what, index }),
        None => Ok(()),
    }
}

/// The Cholesky factor of `B B^T` for the handles inside triangles (`B` their weights on
/// free vertices); a dependent handle is refused.
fn gram_factor(handles: &[HandlePoint], points: &[usize], fixed: &[bool]) -> Result<Vec<f64>, DefOpError> {
    let np = points.len();
    let mut gram = vec![0.0; np * np];
    for (r, &a) in points.iter().enumerate() {
        for (c, &b) in points.iter().enumerate() {
            let (ha, hb) = (&handles[a], &handles[b]);
            let mut sum = 0.0;
            for (va, wa) in ha.vertices.iter().zip(ha.weights) {
                for (vb, wb) in hb.vertices.iter().zip(hb.weights) {
                    if va == vb && !fixed[*va as usize] {
                        sum += wa * wb;
                    }
                }
            }
            gram[r * np + c] = sum;
        }
    }
    cholesky(&mut gram, np).map_err(|r| DefOpError::DependentHandles { handle: points[r] })?;
    Ok(gram)
}

/// Two points within `tolerance` of each other, if any (the lower index first): a sweep
/// over the points sorted by x.
fn coincident_pair(points: &[Point], tolerance: f64) -> Option<(usize, usize)> {
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| points[a][0].total_cmp(&points[b][0]));
    for (i, &a) in order.iter().enumerate() {
        for &b in &order[i + 1..] {
            if points[b][0] - points[a][0] > tolerance {
                break;
            }
            if libm::hypot(points[b][0] - points[a][0], points[b][1] - points[a][1]) <= tolerance {
                return Some((a.min(b), a.max(b)));
            }
        }
    }
    None
}

fn sub(a: Point, b: Point) -> Point {
    [a[0] - b[0], a[1] - b[1]]
}
