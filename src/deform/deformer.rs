//! The one [`Deformer`]: a mesh, its handles, its pose, its painted stiffness and bones,
//! the clock and the timings of the last step, held once for every method, with the
//! method's solver behind them ([`super::method::Solve`]; AKAP, ARAP, moving least squares
//! or Cauchy-Green, as the list of methods in [`super::options`] declares them).
//!
//! The deformer checks every input (handle points, velocities, turns, poses, stiffness,
//! bones) and refuses bad ones with a [`DeformError`], changing nothing; the solver is told
//! of each change and makes the steps, into a buffer that becomes the pose only when the
//! step succeeded. A method switch ([`Deformer::set_options`] with another method's options)
//! puts a new solver behind the same state.

use super::bones::Bones;
use super::error::DeformError;
use super::handles::{self, check_connected, check_pose, check_stiffness, check_turns, check_velocities, HandlePoint};
use super::method::{default_clock, Checkpoint, Clock, IterationReport, Orders, Shared, Solver, Timings};
use super::metrics::{metrics, Metrics};
use super::options::{Method, MethodOptions};
use super::puppet::{Joins, Joint, Puppet};
use super::{AkapSolver, ArapSolver, CauchyGreenSolver};
use crate::geometry::Point;
use crate::mesh::Mesh;

/// What the solver reads of a deformer's state, borrowed field by field (so that the
/// solver itself, another field, can be borrowed mutably beside it).
macro_rules! shared {
    ($deformer:expr) => {
        Shared {
            mesh: &$deformer.mesh,
            handles: &$deformer.handles,
            positions: &$deformer.positions,
            bones: &$deformer.bones,
            clock: $deformer.clock,
        }
    };
}

/// A deformer for one mesh, of any method: handles are vertices or points in triangles;
/// each [`Deformer::step`] takes one velocity per handle, the motion asked of the handle in
/// this step (its target is its current position plus the velocity).
///
/// ```
/// use akap::deform::{ArapOptions, Deformer};
/// use akap::{shapes, triangulate, TriangulationOptions};
///
/// let mesh = triangulate(&shapes::gingerbread(), &TriangulationOptions::default().with_target_edge_length(0.05))?;
/// let mut deformer = Deformer::new(mesh, ArapOptions::default())?;
/// deformer.set_handle_vertices(&[0, 42])?;
/// deformer.step(&[[0.0, 0.0], [0.01, 0.02]])?;
/// assert_eq!(deformer.metrics().flipped, 0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug)]
pub struct Deformer {
    mesh: Mesh,
    handles: Vec<HandlePoint>,
    positions: Vec<Point>,
    /// Scratch for a step: the next pose, swapped with `positions` when the step succeeds
    /// (so the positions' address changes with each step).
    next: Vec<Point>,
    /// The stiffness painted per triangle, if any (methods with stiffness only).
    painted: Option<Vec<f64>>,
    bones: Bones,
    /// A puppet's parts and joints, if the mesh is one, and its joints placed on the sheets.
    puppet: Option<Puppet>,
    joins: Joins,
    /// The fill-reducing orders the solver was set up with (kept for a new joint set).
    orders: Orders,
    clock: Clock,
    timings: Timings,
    solver: Solver,
}

impl Deformer {
    /// A deformer of the method `options` name for a connected mesh: orderings, analyses
    /// and every buffer; at rest, without handles.
    pub fn new(mesh: Mesh, options: impl Into<MethodOptions>) -> Result<Self, DeformError> {
        Self::build(mesh, options.into(), None, None)
    }

    /// [`Self::new`] with the fill-reducing orders computed beforehand by
    /// [`MethodOptions::orders`] (perhaps in a worker): only the analyses and buffers are
    /// made here. Orders that are not permutations of the right sizes are refused
    /// ([`DeformError::OrdersMismatch`]).
    pub fn with_orders(mesh: Mesh, options: impl Into<MethodOptions>, orders: &Orders) -> Result<Self, DeformError> {
        Self::build(mesh, options.into(), Some(orders), None)
    }

    /// A deformer of a puppet: a mesh made of sheets, one per part, that may overlap and
    /// need not be connected, coupled at the puppet's joints (see [`super::puppet`]), with
    /// orders from [`MethodOptions::orders`] if given (the mesh's: they do not depend on
    /// the joints). Parts that do not hold every triangle exactly once
    /// ([`DeformError::InvalidParts`]) and joints out of range or off their parts
    /// ([`DeformError::InvalidJoint`]) are refused. AKAP and ARAP couple the sheets in their
    /// systems; moving least squares and Cauchy-Green, which have no sheets, pose the whole
    /// puppet as one shape.
    pub fn with_puppet(
        mesh: Mesh,
        options: impl Into<MethodOptions>,
        puppet: Puppet,
        orders: Option<&Orders>,
    ) -> Result<Self, DeformError> {
        Self::build(mesh, options.into(), orders, Some(puppet))
    }

    fn build(
        mesh: Mesh,
        options: MethodOptions,
        orders: Option<&Orders>,
        puppet: Option<Puppet>,
    ) -> Result<Self, DeformError> {
        options.check()?;
        let joins = match &puppet {
            Some(puppet) => puppet.joins(&mesh)?,
            None => {
                check_connected(&mesh)?;
                Joins::default()
            }
        };
        let orders = match orders {
            Some(orders) => orders.clone(),
            None => options.orders(&mesh),
        };
        let solver = options.solver(&mesh, &joins, &orders)?;
        Ok(Self {
            positions: mesh.positions().to_vec(),
            next: mesh.positions().to_vec(),
            handles: Vec::new(),
            painted: None,
            bones: Bones::default(),
            puppet,
            joins,
            orders,
            clock: default_clock,
            timings: Timings::default(),
            solver,
            mesh,
        })
    }

    /// The puppet's parts and joints, if the deformer was made for one.
    pub fn puppet(&self) -> Option<&Puppet> {
        self.puppet.as_ref()
    }

    /// Replaces a puppet's joints (the solver's systems are analysed again for them),
    /// keeping the pose, the handles, the stiffness and the bones. Refused, changing
    /// nothing, for a deformer without a puppet and for joints the puppet's checks refuse
    /// ([`DeformError::InvalidJoint`]).
    pub fn set_joints(&mut self, joints: Vec<Joint>) -> Result<(), DeformError> {
        let Some(current) = &self.puppet else {
            return Err(DeformError::InvalidParts { reason: "the deformer was not made for a puppet".into() });
        };
        let puppet = Puppet { parts: current.parts.clone(), joints };
        let joins = puppet.joins(&self.mesh)?;
        self.rebuild(self.options(), self.orders.clone(), joins)?;
        self.puppet = Some(puppet);
        Ok(())
    }

    /// The method and its current settings.
    pub fn options(&self) -> MethodOptions {
        self.solver.options()
    }

    /// The method.
    pub fn method(&self) -> Method {
        self.options().method()
    }

    /// Puts these options into effect: options of the current method change its settings
    /// (from the next step); another method's put a solver of that method behind this
    /// deformer (its set-up runs on the same mesh), keeping the pose, the handles, the
    /// clock, and the painted stiffness and bones where the new method has them (bones laid
    /// again in the current pose); a method without them drops them. On error nothing
    /// changes.
    pub fn set_options(&mut self, options: impl Into<MethodOptions>) -> Result<(), DeformError> {
        let options = options.into();
        if options.method() == self.method() {
            return self.solver.set_options(options, shared!(self));
        }
        options.check()?;
        let orders = options.orders(&self.mesh);
        self.rebuild(options, orders, self.joins.clone())
    }

    /// Puts a new solver of `options`' method, set up with `orders` and `joins`, behind
    /// this deformer, keeping the pose, the handles, the clock, and the painted stiffness
    /// and bones where the method has them (bones laid again in the current pose). On
    /// error nothing changes.
    fn rebuild(&mut self, options: MethodOptions, orders: Orders, joins: Joins) -> Result<(), DeformError> {
        let mut solver = options.solver(&self.mesh, &joins, &orders)?;
        let abilities = solver.get().abilities();
        let bones = match abilities.bones && !self.bones.is_empty() {
            true => {
                let (triangles, barycentric) = self.bones.points();
                Bones::new(&self.mesh, &self.positions, &triangles, &barycentric)?
            }
            false => Bones::default(),
        };
        let painted = self.painted.clone().filter(|_| abilities.stiffness);
        let shared =
            Shared { mesh: &self.mesh, handles: &[], positions: &self.positions, bones: &bones, clock: self.clock };
        solver.get_mut().pose_set(shared, false);
        if abilities.stiffness {
            let weights = bones.stiffness(painted.as_deref(), self.mesh.triangle_count());
            solver.get_mut().set_weights(shared, weights.as_deref());
        }
        solver.get_mut().set_handles(shared, &self.handles)?;
        self.solver = solver;
        self.painted = painted;
        self.bones = bones;
        self.orders = orders;
        self.joins = joins;
        Ok(())
    }

    /// Changes the settings of the current method (from the next step), never the method:
    /// options of another method are refused ([`DeformError::WrongMethod`]), as are values
    /// out of range; on error nothing changes. [`Self::set_options`] switches methods.
    pub fn set_method_options(&mut self, options: impl Into<MethodOptions>) -> Result<(), DeformError> {
        let options = options.into();
        if options.method() != self.method() {
            return Err(DeformError::WrongMethod { current: self.method(), given: options.method() });
        }
        self.set_options(options)
    }

    /// Sets the clock used for the timings (milliseconds).
    pub fn set_clock(&mut self, clock: Clock) {
        self.clock = clock;
    }

    /// The clock of the timings.
    pub fn clock(&self) -> Clock {
        self.clock
    }

    /// The mesh in its rest pose.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// One handle on each of these vertices, replacing any handles.
    pub fn set_handle_vertices(&mut self, vertices: &[u32]) -> Result<(), DeformError> {
        let handles = handles::at_vertices(&self.mesh, vertices)?;
        self.install(handles)
    }

    /// Handles at points in triangles (triangle index, barycentric coordinates), replacing
    /// any handles.
    pub fn set_handle_points(&mut self, triangles: &[u32], barycentric: &[[f64; 3]]) -> Result<(), DeformError> {
        let handles = handles::in_triangles(&self.mesh, triangles, barycentric)?;
        self.install(handles)
    }

    fn install(&mut self, handles: Vec<HandlePoint>) -> Result<(), DeformError> {
        self.solver.get_mut().set_handles(shared!(self), &handles)?;
        self.handles = handles;
        Ok(())
    }

    /// Number of handles.
    pub fn handle_count(&self) -> usize {
        self.handles.len()
    }

    /// Where the handles are on the mesh, as [`Self::set_handle_points`] takes them: a
    /// triangle and barycentric coordinates each (a handle set on a vertex is weight 1 at
    /// that corner of a triangle using it).
    pub fn handle_points(&self) -> (Vec<u32>, Vec<[f64; 3]>) {
        handles::as_points(self.handles.iter())
    }

    /// Current positions of the handle points (Cauchy-Green: the handles' targets, which
    /// the shape's points under them meet in the least-squares sense).
    pub fn handle_positions(&self) -> Vec<Point> {
        let mut positions = vec![[0.0; 2]; self.handles.len()];
        self.handle_positions_into(&mut positions);
        positions
    }

    /// [`Self::handle_positions`] into `out`, which has one place per handle (allocates
    /// nothing: the interaction loop's frames).
    pub(crate) fn handle_positions_into(&self, out: &mut [Point]) {
        match self.solver.get().held_at() {
            Some(targets) => out.copy_from_slice(targets),
            None => {
                for (p, h) in out.iter_mut().zip(&self.handles) {
                    *p = h.position(&self.positions);
                }
            }
        }
    }

    /// Where the shape is under each handle in the current pose (the handles' points of the
    /// mesh placed on the current positions): [`Self::handle_positions`] for every method
    /// but Cauchy-Green, whose handle positions are its targets.
    pub fn shape_under_handles(&self) -> Vec<Point> {
        self.handles.iter().map(|h| h.position(&self.positions)).collect()
    }

    /// One step with a velocity per handle, in handle order. On error the deformer is
    /// unchanged.
    pub fn step(&mut self, velocities: &[[f64; 2]]) -> Result<(), DeformError> {
        check_velocities(velocities, self.handles.len())?;
        self.take_step(velocities, None)
    }

    /// One step in which handles also turn: `turns[i]` radians counter-clockwise about
    /// handle `i`'s point, its neighbourhood following that rigid motion (AKAP: its Killing
    /// field; ARAP: held in the turned frame for the step; see docs/app.md). All turns zero
    /// is exactly [`Self::step`]; methods without turning handles refuse other turns
    /// ([`DeformError::Unsupported`]).
    pub fn step_turning(&mut self, velocities: &[[f64; 2]], turns: &[f64]) -> Result<(), DeformError> {
        check_velocities(velocities, self.handles.len())?;
        check_turns(turns, self.handles.len())?;
        if turns.iter().all(|&w| w == 0.0) {
            return self.take_step(velocities, None);
        }
        if !self.solver.get().abilities().turning {
            return Err(DeformError::Unsupported { method: self.method(), what: "turning handles" });
        }
        self.take_step(velocities, Some(turns))
    }

    fn take_step(&mut self, velocities: &[[f64; 2]], turns: Option<&[f64]>) -> Result<(), DeformError> {
        let mut timings = Timings::default();
        let moved = self.solver.get_mut().step(shared!(self), velocities, turns, &mut self.next, &mut timings)?;
        if moved {
            std::mem::swap(&mut self.positions, &mut self.next);
        }
        self.timings = timings;
        Ok(())
    }

    /// Current vertex positions.
    pub fn positions(&self) -> &[Point] {
        &self.positions
    }

    /// Puts the mesh into a given pose (undo, a saved pose, a trained rig's); handles stay
    /// (ARAP and Cauchy-Green: their targets become their places in this pose). Fails,
    /// changing nothing, for a wrong length or a coordinate that is not finite or beyond
    /// ±[`crate::geometry::MAX_COORDINATE`].
    pub fn set_positions(&mut self, positions: &[Point]) -> Result<(), DeformError> {
        check_pose(positions, self.positions.len())?;
        self.positions.copy_from_slice(positions);
        self.solver.get_mut().pose_set(shared!(self), false);
        Ok(())
    }

    /// [`Self::set_positions`] with the pose written in place by `write` (x and y
    /// interleaved, `2 * vertex_count` numbers), so that a pose computed elsewhere (a
    /// trained rig's) is not copied: refused, changing nothing, when `write` fails or the
    /// pose it wrote is not finite or beyond the coordinate limits.
    pub fn set_positions_with<E: From<DeformError>>(
        &mut self,
        write: impl FnOnce(&mut [f64]) -> Result<(), E>,
    ) -> Result<(), E> {
        write(self.next.as_flattened_mut())?;
        check_pose(&self.next, self.positions.len())?;
        std::mem::swap(&mut self.positions, &mut self.next);
        self.solver.get_mut().pose_set(shared!(self), false);
        Ok(())
    }

    /// Back to the rest pose; handles stay.
    pub fn reset(&mut self) {
        self.positions.copy_from_slice(self.mesh.positions());
        self.solver.get_mut().pose_set(shared!(self), true);
    }

    /// The last step's velocity per vertex: AKAP's field after the Dirichlet step, ARAP's,
    /// moving least squares' and Cauchy-Green's displacement.
    pub fn field(&self) -> &[[f64; 2]] {
        self.solver.get().field()
    }

    /// The last step's field before any smoothing: AKAP's soft-constraint field, the others'
    /// displacement.
    pub fn soft_field(&self) -> &[[f64; 2]] {
        self.solver.get().soft_field()
    }

    /// Sets each triangle's stiffness, the factor on its energy (stiff regions bend less;
    /// one value per triangle in [`super::STIFFNESS_RANGE`], `None` for 1 everywhere,
    /// exactly the unpainted deformer): AKAP weighs its Killing energy, ARAP its element
    /// energy; the next step uses it. Methods without a per-triangle energy (MLS,
    /// Cauchy-Green) refuse it ([`DeformError::Unsupported`]). Refused, changing nothing,
    /// for a wrong length or a value out of range.
    pub fn set_stiffness(&mut self, stiffness: Option<&[f64]>) -> Result<(), DeformError> {
        if !self.has_stiffness() {
            return match stiffness {
                None => Ok(()),
                Some(_) => Err(DeformError::Unsupported { method: self.method(), what: "stiffness" }),
            };
        }
        check_stiffness(stiffness, self.mesh.triangle_count())?;
        self.painted = stiffness.map(<[f64]>::to_vec);
        self.weigh();
        Ok(())
    }

    /// Gives the solver each triangle's weight: the painting raised on the bones.
    fn weigh(&mut self) {
        let weights = self.bones.stiffness(self.painted.as_deref(), self.mesh.triangle_count());
        self.solver.get_mut().set_weights(shared!(self), weights.as_deref());
    }

    /// Each triangle's painted stiffness, if set.
    pub fn stiffness(&self) -> Option<&[f64]> {
        self.painted.as_deref()
    }

    /// Whether the method takes per-triangle stiffness ([`Self::set_stiffness`]).
    pub fn has_stiffness(&self) -> bool {
        self.solver.get().abilities().stiffness
    }

    /// Sets the bones (see [`super::bones`]): two mesh points per bone, its ends, given as
    /// [`Self::set_handle_points`] takes points, replacing any bones; none removes them.
    /// Each bone covers the triangles its segment meets in the current pose, which from then
    /// on move as one rigid body: they weigh at least [`super::BONE_STIFFNESS`] in the
    /// energy, and after each step (each of ARAP's iterations) they are put where the rigid
    /// motion that best fits them takes the bone as it was set. Methods without bones (MLS,
    /// Cauchy-Green) refuse any ([`DeformError::Unsupported`]). Refused, changing nothing,
    /// for a bone that cannot be used ([`DeformError::InvalidBone`]).
    pub fn set_bones(&mut self, triangles: &[u32], barycentric: &[[f64; 3]]) -> Result<(), DeformError> {
        if !self.has_bones() {
            if triangles.is_empty() && barycentric.is_empty() {
                return Ok(());
            }
            return Err(DeformError::Unsupported { method: self.method(), what: "bones" });
        }
        self.bones = Bones::new(&self.mesh, &self.positions, triangles, barycentric)?;
        self.weigh();
        Ok(())
    }

    /// The bones' ends, two per bone, as [`Self::set_bones`] took them.
    pub fn bone_points(&self) -> (Vec<u32>, Vec<[f64; 3]>) {
        self.bones.points()
    }

    /// Whether the method has bones ([`Self::set_bones`]).
    pub fn has_bones(&self) -> bool {
        self.solver.get().abilities().bones
    }

    /// The polygon the method deforms the shape through, where it has one, as the last step
    /// left it: Cauchy-Green's cage (the cage values; its rest cage after a reset). `None`
    /// for methods without one.
    pub fn cage_image(&self) -> Option<&[Point]> {
        self.solver.get().cage_image()
    }

    /// Saves the state steps change (see [`Checkpoint`]) into `checkpoint`, replacing what
    /// it held and reusing its buffers.
    pub fn save_checkpoint(&self, checkpoint: &mut Checkpoint) {
        checkpoint.begin(self.method());
        checkpoint.positions.extend_from_slice(&self.positions);
        checkpoint.timings = self.timings;
        self.solver.get().save(checkpoint);
    }

    /// Puts back the state saved in `checkpoint`: the next step then gives exactly the bits
    /// it would have given had nothing happened since the save (for the handles, options
    /// and stiffness in place; changing those is not undone). Refused with
    /// [`DeformError::ForeignCheckpoint`], changing nothing, for a checkpoint saved by a
    /// deformer of another method or of other sizes (vertices, handles, triangles).
    pub fn restore_checkpoint(&mut self, checkpoint: &Checkpoint) -> Result<(), DeformError> {
        let mut lengths = self.solver.get().saved_lengths(checkpoint);
        lengths.push((checkpoint.positions.len(), self.positions.len()));
        checkpoint.check(self.method(), &lengths)?;
        self.solver.get_mut().restore(checkpoint);
        self.positions.copy_from_slice(&checkpoint.positions);
        self.timings = checkpoint.timings;
        Ok(())
    }

    /// A new checkpoint of the current state ([`Self::save_checkpoint`] into a fresh one).
    pub fn checkpoint(&self) -> Checkpoint {
        let mut checkpoint = Checkpoint::new();
        self.save_checkpoint(&mut checkpoint);
        checkpoint
    }

    /// Distortion of the current pose against the rest pose.
    pub fn metrics(&self) -> Metrics {
        metrics(self.mesh.positions(), &self.positions, self.mesh.triangles())
    }

    /// Stage timings of the last step.
    pub fn timings(&self) -> Timings {
        self.timings
    }

    /// AKAP's solver, for its own quantities ([`AkapSolver::factor_stats`]); `None` for
    /// another method.
    pub fn akap(&self) -> Option<&AkapSolver> {
        match &self.solver {
            Solver::Akap(solver) => Some(solver),
            _ => None,
        }
    }

    /// ARAP's solver, for its own quantities (its targets, rotations, the last step's
    /// [`IterationReport`], its penalty weight, factor statistics); `None` for another
    /// method.
    pub fn arap(&self) -> Option<&ArapSolver> {
        match &self.solver {
            Solver::Arap(solver) => Some(solver),
            _ => None,
        }
    }

    /// Cauchy-Green's solver, for its rest cage; `None` for another method.
    pub fn cauchy_green(&self) -> Option<&CauchyGreenSolver> {
        match &self.solver {
            Solver::CauchyGreen(solver) => Some(solver),
            _ => None,
        }
    }

    /// ARAP: more local/global iterations towards the current targets (at most
    /// `max_iterations`, stopping once an iteration moves no vertex further than
    /// `tolerance` times the shape's size), without changing the targets (see
    /// [`ArapSolver`]). Other methods refuse it ([`DeformError::Unsupported`]).
    pub fn iterate(&mut self, max_iterations: usize, tolerance: f64) -> Result<IterationReport, DeformError> {
        let method = self.method();
        let shared = shared!(self);
        let Solver::Arap(solver) = &mut self.solver else {
            return Err(DeformError::Unsupported { method, what: "iterations towards the targets" });
        };
        let mut timings = Timings::default();
        let (report, moved) = solver.iterate(shared, max_iterations, tolerance, &mut self.next, &mut timings)?;
        if moved {
            std::mem::swap(&mut self.positions, &mut self.next);
        }
        self.timings = timings;
        Ok(report)
    }

    /// ARAP's energy `E` of the current pose with the best rotations and the current
    /// targets (the quantity each iteration lowers); `None` for another method.
    pub fn energy(&self) -> Option<f64> {
        self.arap().map(|solver| solver.energy(shared!(self)))
    }

    /// Cauchy-Green: uses this cage (a simple polygon, either orientation, with the shape
    /// strictly inside), or an automatic one again with `None`. Refused with
    /// [`DeformError::InvalidCage`], changing nothing, when the cage cannot be used; other
    /// methods refuse it ([`DeformError::Unsupported`]). The pose stays until the next step.
    pub fn set_cage(&mut self, cage: Option<&[Point]>) -> Result<(), DeformError> {
        let method = self.method();
        let shared = shared!(self);
        let Solver::CauchyGreen(solver) = &mut self.solver else {
            return Err(DeformError::Unsupported { method, what: "a cage" });
        };
        solver.set_cage(shared, cage)
    }
}
