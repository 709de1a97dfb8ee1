//! The interaction loop, once: a [`Poser`] owns a [`Deformer`] and moves its handles toward
//! targets the caller sets, one call a frame ([`Poser::advance`]), with the tracking policy
//! every caller shares ([`Tracking`]: the largest step, substeps, the guarded step without
//! foldovers, retries of a failed step, the largest turn per step), records what it does
//! into a session as it does it, and poses with a trained rig instead where one is given.
//! The widget's posing (through the bindings), its animation frames, `examples/pose_obj.rs`,
//! `generate/make_sessions.rs` and session replay ([`replay`]) all pose through it.
//!
//! A frame in tracking mode (the default): every handle's velocity is the rest of the way to
//! its target over the substeps left, `(target - current) / remaining`, so handles track
//! the pointer without drift; a long way is split into substeps no longer than
//! [`Tracking::max_step`] of the shape's size (one large step along a field that is only
//! infinitesimally rigid distorts the shape, the paper's Figure 2), at most
//! [`Tracking::max_substeps`] a frame, and turns into steps of at most [`MAX_TURN_STEP`].
//! With [`Tracking::no_foldovers`] each substep is the guarded step of
//! [`crate::deform::foldover`]; one that stops short ends the frame, and the handles not
//! held then stay where they stopped. A step that fails is tried again with smaller
//! velocities ([`RETRY_SCALES`]). In the paper's mode ([`Tracking::paper`]) a handle's
//! velocity is instead the raw motion of its target since the last frame, split evenly,
//! and errors accumulate, as in the paper's interface.
//!
//! Each plain step taken is recorded, when a recording runs, as it was taken (a guarded
//! step's pieces each as its own `step` or `turn` event), so that a replay repeats it to
//! the bit; so are the handles, poses, options, stiffness and bones set through the poser.
//!
//! With a trained rig ([`Poser::set_rig`]) a frame is the rig's pose for the targets; with
//! [`Tracking::no_foldovers`] the targets are pulled back along the way from the last pose's
//! until no triangle turns over that was not turned over at rest (`rig.rs`), the frame
//! reported clamped as a stopped step is. The rig is recorded by the checksum of its file
//! ([`session_rig`]) and each frame by the targets its pose is for, so that a replay given
//! the rig ([`replay_with_rigs`]) evaluates it again to the same bits.
//!
//! A rig may pose on the GPU ([`Poser::set_rig_on_gpu`]): a frame then computes only the
//! rig's short frame vector ([`crate::defop::GpuRig`]) for the renderer, and the deformer's
//! positions fall behind until something reads them: [`Poser::settle`] evaluates the
//! operator at the last frame's targets into them (the same double-precision pose a frame
//! on the CPU writes). Every method of the poser that reads or builds on the pose settles
//! first; readers of [`Poser::deformer`] call [`Poser::settle`] first (the bindings do). The
//! no-foldover guard needs the pose (it checks its triangles), so with it a frame is
//! evaluated on the CPU too and the GPU draws the targets it accepted; so does a recording
//! that cannot name its rig (it records the poses).

mod replay;
mod rig;

use std::borrow::BorrowMut;

use crate::defop::{gpu, FitError, GpuRig, Operator};
use crate::deform::{
    DeformError, Deformer, FoldoverGuard, FoldoverStepper, GuardedStep, Joint, MethodOptions, Timings,
};
use crate::geometry::Point;
use crate::mesh::MeshPoint;
use crate::session::{
    Event, MeshCounts, RecordedOptions, Session, SessionJoint, SessionMesh, SessionPuppet, ShapeSpec,
};

pub use replay::{replay, replay_to_targets, replay_with_rigs, Replay};
pub use rig::session_rig;
use rig::Rig;

/// The largest turn of a handle in one step, radians.
pub const MAX_TURN_STEP: f64 = 0.1;

/// A failed step is tried again with its velocities (and turns) scaled by these, in turn.
pub const RETRY_SCALES: [f64; 3] = [0.5, 0.25, 0.125];

/// A handle's target nearer than this share of the shape's size is reached: no step.
pub const REACHED: f64 = 1e-5;

/// Most substeps a frame may take ([`Tracking::max_substeps`]): a way longer than that
/// many steps is left to the frames after.
pub const MAX_SUBSTEPS: usize = 10_000;

/// How a [`Poser`] moves its handles toward their targets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tracking {
    /// The longest handle move of one substep, as a share of the shape's size (its
    /// bounding box's larger side); default 0.02. Above 0.
    pub max_step: f64,
    /// Most substeps a frame takes (the rest of the way is left to the next frame);
    /// default 8, at most [`MAX_SUBSTEPS`].
    pub max_substeps: usize,
    /// Whether each substep is the guarded step that turns no triangle over (default on).
    pub no_foldovers: bool,
    /// How far the guarded step splits and clamps.
    pub guard: FoldoverGuard,
    /// The paper's mode: a handle's velocity is the motion of its target since the last
    /// frame (default off).
    pub paper: bool,
}

impl Default for Tracking {
    fn default() -> Self {
        Self { max_step: 0.02, max_substeps: 8, no_foldovers: true, guard: FoldoverGuard::default(), paper: false }
    }
}

impl Tracking {
    /// Checks every setting against its range.
    pub fn check(&self) -> Result<(), DeformError> {
        if !(self.max_step > 0.0 && self.max_step <= 1e300) {
            return Err(DeformError::InvalidOption {
                name: "maxStep",
                value: self.max_step,
                expected: "a number above 0 (a share of the shape's size; 0.02 is the default)",
            });
        }
        if !(1..=MAX_SUBSTEPS).contains(&self.max_substeps) {
            return Err(DeformError::InvalidOption {
                name: "maxSubsteps",
                value: self.max_substeps as f64,
                expected: "a whole number from 1 to 10000",
            });
        }
        self.guard.check()
    }
}

/// What one [`Poser::advance`] did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Advance {
    /// Substeps taken (a rig's evaluation counts as one); 0 when nothing moved.
    pub steps: usize,
    /// Whether a step stopped short to keep triangles from folding over.
    pub clamped: bool,
    /// The deformer's stage timings, summed over the substeps (milliseconds).
    pub timings: Timings,
    /// Milliseconds of the rig's evaluation (0 when the frame stepped the deformer).
    pub evaluation: f64,
}

/// What the poser keeps of each handle beyond its point of the mesh.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct HandleState {
    /// Where the handle is going.
    target: Point,
    /// How far it is to turn, and has turned, radians counter-clockwise.
    turn: f64,
    turned: f64,
    /// Whether a pointer holds it (a handle not held stays where a stopped step left it).
    held: bool,
    /// The paper's mode: motion of the target not yet turned into steps.
    pending: Point,
}

/// A deformer posed toward targets: see the module's description. It owns its deformer
/// (`Poser<Deformer>`, the default), or borrows one (`Poser<&mut Deformer>`) for a while.
#[derive(Debug)]
pub struct Poser<D: BorrowMut<Deformer> = Deformer> {
    deformer: D,
    stepper: FoldoverStepper,
    tracking: Tracking,
    handles: Vec<HandleState>,
    /// The rest shape's size: its bounding box's larger side.
    size: f64,
    /// Whether the pose is the rest pose (a new deformer, or just reset).
    at_rest: bool,
    /// The session being recorded, and whether recording is paused (a replay runs).
    recording: Option<Session>,
    paused: bool,
    rig: Option<Rig>,
    // Scratch of a frame, sized with the handles.
    current: Vec<Point>,
    velocities: Vec<[f64; 2]>,
    turns: Vec<f64>,
    scaled: Vec<[f64; 2]>,
    scaled_turns: Vec<f64>,
    /// The last step's plain steps, as fractions of its velocities, and the plain steps it
    /// tried.
    fractions: Vec<f64>,
    attempts: usize,
}

impl<D: BorrowMut<Deformer>> Poser<D> {
    /// A poser of `deformer` (its handles, at their places, become the poser's, each with
    /// its target where it is), tracking with the default policy.
    pub fn new(deformer: D) -> Self {
        let positions = deformer.borrow().mesh().positions();
        let extent = |axis: usize| {
            let (lo, hi) = positions
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| (lo.min(p[axis]), hi.max(p[axis])));
            hi - lo
        };
        let size = extent(0).max(extent(1));
        let mut poser = Self {
            at_rest: deformer.borrow().positions() == positions,
            deformer,
            stepper: FoldoverStepper::default(),
            tracking: Tracking::default(),
            handles: Vec::new(),
            size: if size > 0.0 { size } else { 1.0 },
            recording: None,
            paused: false,
            rig: None,
            current: Vec::new(),
            velocities: Vec::new(),
            turns: Vec::new(),
            scaled: Vec::new(),
            scaled_turns: Vec::new(),
            fractions: Vec::new(),
            attempts: 0,
        };
        poser.reset_handle_states();
        poser
    }

    /// The deformer posed (read it for the pose, fields, metrics, timings). With a rig on
    /// the GPU its positions may be behind the last frame: [`Self::settle`] first.
    pub fn deformer(&self) -> &Deformer {
        self.deformer.borrow()
    }

    /// The deformer, taken back (settled: see [`Self::settle`]).
    pub fn into_deformer(mut self) -> D {
        let _ = self.settle();
        self.deformer
    }

    /// The rest shape's size, its bounding box's larger side: the unit of
    /// [`Tracking::max_step`].
    pub fn size(&self) -> f64 {
        self.size
    }

    /// The tracking policy.
    pub fn tracking(&self) -> Tracking {
        self.tracking
    }

    /// Changes the tracking policy (checked; unchanged on error). A rig evaluates again at
    /// the next frame, under the new policy.
    pub fn set_tracking(&mut self, tracking: Tracking) -> Result<(), DeformError> {
        tracking.check()?;
        self.stepper.set_guard(tracking.guard)?;
        self.tracking = tracking;
        if let Some(rig) = &mut self.rig {
            rig.asked.clear();
        }
        Ok(())
    }

    /// Whether the pose is the rest pose: the deformer new or just reset, no step or pose
    /// since.
    pub fn at_rest(&self) -> bool {
        self.at_rest
    }

    // ------------------------------------------------------------------ handles

    /// Every handle's state anew: targets where the handles are, no turn, not held.
    fn reset_handle_states(&mut self) {
        let at = self.deformer.borrow().handle_positions();
        self.handles = at.iter().map(|&target| HandleState { target, ..HandleState::default() }).collect();
        self.size_scratch();
    }

    fn size_scratch(&mut self) {
        let n = self.handles.len();
        for buffer in [&mut self.current, &mut self.velocities, &mut self.scaled] {
            buffer.clear();
            buffer.resize(n, [0.0; 2]);
        }
        for buffer in [&mut self.turns, &mut self.scaled_turns] {
            buffer.clear();
            buffer.resize(n, 0.0);
        }
        if let Some(rig) = &mut self.rig {
            rig.forget_pose();
        }
    }

    /// Handles at these points of the mesh (triangle, barycentric coordinates each),
    /// replacing any: each starts with its target where it is, not turning, not held.
    /// Recorded. A rig posing the shape is dropped (the caller checks whether it fits the
    /// new handles and gives it again).
    pub fn set_handle_points(&mut self, triangles: &[u32], barycentric: &[[f64; 3]]) -> Result<(), DeformError> {
        self.settle()?;
        self.deformer.borrow_mut().set_handle_points(triangles, barycentric)?;
        self.reset_handle_states();
        self.rig = None;
        self.record_handles();
        Ok(())
    }

    /// One handle on each of these vertices, replacing any (as [`Self::set_handle_points`]).
    pub fn set_handle_vertices(&mut self, vertices: &[u32]) -> Result<(), DeformError> {
        self.settle()?;
        self.deformer.borrow_mut().set_handle_vertices(vertices)?;
        self.reset_handle_states();
        self.rig = None;
        self.record_handles();
        Ok(())
    }

    /// One more handle at a point of the mesh, last, with its target where it is; the other
    /// handles keep their targets and turns. Recorded.
    pub fn add_handle(&mut self, triangle: u32, barycentric: [f64; 3]) -> Result<usize, DeformError> {
        self.settle()?;
        let (mut triangles, mut weights) = self.deformer.borrow().handle_points();
        triangles.push(triangle);
        weights.push(barycentric);
        self.deformer.borrow_mut().set_handle_points(&triangles, &weights)?;
        let target = *self.deformer.borrow().handle_positions().last().expect("the handle just added");
        self.handles.push(HandleState { target, ..HandleState::default() });
        self.size_scratch();
        self.rig = None;
        self.record_handles();
        Ok(self.handles.len() - 1)
    }

    /// Removes handle `index`; the others keep their targets and turns. Recorded.
    pub fn remove_handle(&mut self, index: usize) -> Result<(), DeformError> {
        self.check_handle(index)?;
        self.settle()?;
        let (mut triangles, mut weights) = self.deformer.borrow().handle_points();
        triangles.remove(index);
        weights.remove(index);
        self.deformer.borrow_mut().set_handle_points(&triangles, &weights)?;
        self.handles.remove(index);
        self.size_scratch();
        self.rig = None;
        self.record_handles();
        Ok(())
    }

    fn check_handle(&self, index: usize) -> Result<(), DeformError> {
        match index < self.handles.len() {
            true => Ok(()),
            false => Err(DeformError::HandleOutOfRange { handle: index, handle_count: self.handles.len() }),
        }
    }

    /// Number of handles.
    pub fn handle_count(&self) -> usize {
        self.handles.len()
    }

    /// Where each handle is going.
    pub fn targets(&self) -> impl ExactSizeIterator<Item = Point> + '_ {
        self.handles.iter().map(|h| h.target)
    }

    /// How far each handle is to turn, radians counter-clockwise (its turns so far and
    /// those still to make).
    pub fn turns(&self) -> impl ExactSizeIterator<Item = f64> + '_ {
        self.handles.iter().map(|h| h.turn)
    }

    /// How far each handle has turned, radians counter-clockwise.
    pub fn turned(&self) -> impl ExactSizeIterator<Item = f64> + '_ {
        self.handles.iter().map(|h| h.turned)
    }

    /// Sets handle `index`'s target (in the paper's mode, the motion since the last frame is
    /// what the next frame moves it by). Refused for an index out of range or a coordinate
    /// that is not finite.
    pub fn set_target(&mut self, index: usize, target: Point) -> Result<(), DeformError> {
        self.check_handle(index)?;
        check_target(index, &target)?;
        let h = &mut self.handles[index];
        h.pending = [h.pending[0] + target[0] - h.target[0], h.pending[1] + target[1] - h.target[1]];
        h.target = target;
        Ok(())
    }

    /// Places every handle's target, one per handle in order (undo, a re-meshing, a frame
    /// of an animation shown): no motion pending from it in the paper's mode, no turn left
    /// to make. All checked before any is set.
    pub fn set_targets(&mut self, targets: &[Point]) -> Result<(), DeformError> {
        self.check_targets(targets)?;
        for (h, &target) in self.handles.iter_mut().zip(targets) {
            h.target = target;
            h.pending = [0.0; 2];
            h.turn = h.turned;
        }
        Ok(())
    }

    /// One finite target per handle.
    fn check_targets(&self, targets: &[Point]) -> Result<(), DeformError> {
        if targets.len() != self.handles.len() {
            return Err(DeformError::Length {
                what: "targets",
                expected: 2 * self.handles.len(),
                found: 2 * targets.len(),
                per: 2,
                items: "handles",
            });
        }
        for (index, target) in targets.iter().enumerate() {
            check_target(index, target)?;
        }
        Ok(())
    }

    /// Sets how far handle `index` is to turn in all, radians counter-clockwise (turns add
    /// up: [`Self::turned`] is how far it has so far). Methods without turning handles
    /// drop the turn at the next frame.
    pub fn set_turn(&mut self, index: usize, turn: f64) -> Result<(), DeformError> {
        self.check_handle(index)?;
        if !turn.is_finite() {
            return Err(DeformError::NonFiniteTurn { handle: index });
        }
        self.handles[index].turn = turn;
        Ok(())
    }

    /// Every handle's target where it is now, no motion pending: the handles stay where
    /// they are (with a rig, where its pose is for).
    pub fn pin_handles(&mut self) {
        let _ = self.settle();
        let at = self.handle_places();
        for (h, p) in self.handles.iter_mut().zip(at) {
            h.target = p;
            h.pending = [0.0; 2];
        }
    }

    /// Where each handle is: its point of the pose, or with a rig posing, the target the
    /// rig's pose is for (the point of the pose is only near it).
    fn handle_places(&self) -> Vec<Point> {
        match &self.rig {
            Some(rig) if !rig.posed.is_empty() => rig.posed.as_chunks::<2>().0.to_vec(),
            _ => self.deformer.borrow().handle_positions(),
        }
    }

    /// A pointer takes handle `index`: it is held, its target where it is now (no motion
    /// pending from it; with a rig, where the rig's pose is for). Returns where it is.
    pub fn grab(&mut self, index: usize) -> Result<Point, DeformError> {
        self.check_handle(index)?;
        self.settle()?;
        let at = self.deformer.borrow().handle_positions()[index];
        let h = &mut self.handles[index];
        h.held = true;
        h.target = at;
        Ok(at)
    }

    /// The pointer lets handle `index` go: it stays a pin at its target.
    pub fn release(&mut self, index: usize) -> Result<(), DeformError> {
        self.set_held(index, false)
    }

    /// Whether a pointer holds handle `index` (see [`Self::grab`]), its target unchanged.
    pub fn set_held(&mut self, index: usize, held: bool) -> Result<(), DeformError> {
        self.check_handle(index)?;
        self.handles[index].held = held;
        Ok(())
    }

    /// The handles no pointer holds stay where they are (after a step stopped short).
    fn pin_unheld(&mut self) {
        let at = self.deformer.borrow().handle_positions();
        for (h, p) in self.handles.iter_mut().zip(at) {
            if !h.held {
                h.target = p;
                h.turn = h.turned;
            }
        }
    }

    // ------------------------------------------------------------------ the frame

    /// Moves the handles toward their targets (see the module's description), or poses with
    /// the rig; returns what it did. On error (a step that failed even with smaller
    /// velocities) the pose is where the steps before it left it, the turns asked for are
    /// dropped, the handles not held stay where they are, and the error is returned.
    pub fn advance(&mut self) -> Result<Advance, DeformError> {
        let mut report = Advance::default();
        if self.handles.is_empty() {
            return Ok(report);
        }
        if self.rig.is_some() {
            return self.evaluate_rig();
        }
        let longest = self.tracking.max_step * self.size;
        if self.tracking.paper {
            for (v, h) in self.velocities.iter_mut().zip(&mut self.handles) {
                *v = std::mem::take(&mut h.pending);
            }
            let distance = self.velocities.iter().fold(0.0f64, |m, d| m.max(libm::hypot(d[0], d[1])));
            if distance == 0.0 {
                return Ok(report);
            }
            let count = (self.tracking.max_substeps as f64).min(substeps(distance, longest)) as usize;
            split_evenly(&mut self.velocities, count);
            for _ in 0..count {
                self.substep(false, &mut report)?;
                if report.clamped {
                    break;
                }
            }
            report.steps = count;
            // The handles end where the deformation took them; pins stay pins.
            let at = self.deformer.borrow().handle_positions();
            for (h, p) in self.handles.iter_mut().zip(at) {
                if !h.held {
                    h.target = p;
                }
            }
            return Ok(report);
        }
        self.deformer.borrow().handle_positions_into(&mut self.current);
        let gap = self
            .current
            .iter()
            .zip(&self.handles)
            .fold(0.0f64, |m, (p, h)| m.max(libm::hypot(h.target[0] - p[0], h.target[1] - p[1])));
        let turn_gap = self.handles.iter().fold(f64::NEG_INFINITY, |m, h| m.max((h.turn - h.turned).abs()));
        let moves = gap > REACHED * self.size;
        let turning = turn_gap > 1e-9;
        if !moves && !turning {
            return Ok(report);
        }
        // Counts as numbers: a way far longer than the shape needs more substeps than a
        // frame takes, and the velocities are its share of them.
        let needed = (if moves { substeps(gap, longest) } else { 1.0 }).max((turn_gap / MAX_TURN_STEP - 1e-9).ceil());
        let count = (self.tracking.max_substeps as f64).min(needed) as usize;
        while report.steps < count && !report.clamped {
            let remaining = needed - report.steps as f64;
            match moves {
                true => toward(&self.handles, &self.current, remaining, &mut self.velocities),
                false => self.velocities.fill([0.0; 2]),
            }
            if turning {
                for (w, h) in self.turns.iter_mut().zip(&self.handles) {
                    *w = (h.turn - h.turned) / remaining;
                }
            }
            self.substep(turning, &mut report)?;
            report.steps += 1;
            self.deformer.borrow().handle_positions_into(&mut self.current);
        }
        // Stopped short to keep the triangles unfolded: handles let go stay where they are
        // (they would only stop short again), held ones keep their targets.
        if report.clamped {
            self.pin_unheld();
        }
        Ok(report)
    }

    /// One step of `velocities` (and `turns`, when `turning`), guarded when the policy says
    /// so, retried smaller when it fails; each plain step taken recorded as taken.
    fn substep(&mut self, turning: bool, report: &mut Advance) -> Result<(), DeformError> {
        let first = match self.attempt(1.0, turning, report) {
            Ok(pieces) => return self.took(pieces, report),
            Err(error) => error,
        };
        for scale in RETRY_SCALES {
            if let Ok(pieces) = self.attempt(scale, turning, report) {
                return self.took(pieces, report);
            }
        }
        // A method without turning handles, say: the turns asked for are dropped, and the
        // handles not held stay where they are (held ones keep their targets and are tried
        // again next frame, in smaller steps).
        for h in &mut self.handles {
            h.turn = h.turned;
        }
        self.pin_unheld();
        Err(first)
    }

    /// After a step that took `pieces` plain steps: the deformer's timings added to the
    /// frame's.
    fn took(&mut self, pieces: usize, report: &mut Advance) -> Result<(), DeformError> {
        if pieces == 0 {
            return Ok(());
        }
        let t = self.deformer.borrow().timings();
        let sum = &mut report.timings;
        sum.assembly += t.assembly;
        sum.factorisation += t.factorisation;
        sum.dirichlet_factorisation += t.dirichlet_factorisation;
        sum.solve += t.solve;
        sum.integration += t.integration;
        Ok(())
    }

    /// The step of `velocities * scale` (and turns), guarded or plain as the policy says.
    /// Returns how many plain steps it took.
    fn attempt(&mut self, scale: f64, turning: bool, report: &mut Advance) -> Result<usize, DeformError> {
        scale_into(&mut self.scaled, &self.velocities, scale);
        if turning {
            scale_into(&mut self.scaled_turns, &self.turns, scale);
        }
        let (velocities, turns) = (std::mem::take(&mut self.scaled), std::mem::take(&mut self.scaled_turns));
        let guard = self.tracking.no_foldovers.then_some(self.tracking.guard);
        let taken = self.take(&velocities, turning.then_some(&turns[..]), guard);
        (self.scaled, self.scaled_turns) = (velocities, turns);
        let (pieces, clamped) = taken?;
        report.clamped |= clamped;
        Ok(pieces)
    }

    /// A plain step of `velocities` (and `turns`), or with `guard` the guarded step; each
    /// plain step taken recorded as it was taken, its turns counted as made, its fraction
    /// in `fractions`. Returns how many plain steps it took and whether it stopped short.
    fn take(
        &mut self,
        velocities: &[[f64; 2]],
        turns: Option<&[f64]>,
        guard: Option<FoldoverGuard>,
    ) -> Result<(usize, bool), DeformError> {
        self.fractions.clear();
        let clamped = match guard {
            None => {
                match turns {
                    Some(turns) => self.deformer.borrow_mut().step_turning(velocities, turns)?,
                    None => self.deformer.borrow_mut().step(velocities)?,
                }
                self.fractions.push(1.0);
                self.attempts = 1;
                false
            }
            Some(guard) => {
                self.stepper.set_guard(guard)?;
                let deformer = self.deformer.borrow_mut();
                let guarded = match turns {
                    Some(turns) => self.stepper.step_turning(deformer, velocities, turns),
                    None => self.stepper.step(deformer, velocities),
                };
                let guarded = match guarded {
                    Ok(guarded) => guarded,
                    Err(error) => {
                        self.stepper.set_guard(self.tracking.guard)?;
                        return Err(error);
                    }
                };
                self.fractions.extend_from_slice(&guarded.steps);
                self.attempts = guarded.attempts;
                let clamped = guarded.clamped;
                self.stepper.set_guard(self.tracking.guard)?;
                clamped
            }
        };
        for k in 0..self.fractions.len() {
            self.stepped(velocities, turns, self.fractions[k]);
        }
        Ok((self.fractions.len(), clamped))
    }

    /// A plain step of `velocities * fraction` (and turns) was taken: its turns counted as
    /// made, recorded.
    fn stepped(&mut self, velocities: &[[f64; 2]], turns: Option<&[f64]>, fraction: f64) {
        self.at_rest = false;
        if let Some(rig) = &mut self.rig {
            rig.forget_pose();
        }
        // The stepper's own products: `step` with these repeats the piece to the bit.
        let times = |x: f64| if fraction == 1.0 { x } else { x * fraction };
        if let Some(turns) = turns {
            for (h, &w) in self.handles.iter_mut().zip(turns) {
                h.turned += times(w);
            }
        }
        // (Nothing is allocated unless a recording runs.)
        record(&mut self.recording, self.paused, || {
            let velocities = velocities.as_flattened().iter().map(|&x| times(x)).collect();
            match turns {
                Some(turns) => Event::Turn { velocities, turns: turns.iter().map(|&w| times(w)).collect() },
                None => Event::Step(velocities),
            }
        });
    }

    /// One plain step with a velocity per handle and, where given, a turn per handle, as
    /// given: no substeps, no guard, no retry (a replay's recorded step, a caller stepping by
    /// hand). The handles' targets become where the step took them and the turns count as
    /// asked and made, so a later [`Self::advance`] does not take them back. Recorded.
    pub fn step(&mut self, velocities: &[[f64; 2]], turns: Option<&[f64]>) -> Result<(), DeformError> {
        self.step_by_hand(velocities, turns)?;
        self.pin_handles();
        Ok(())
    }

    /// A plain step asked for by hand: the turns it made count as asked.
    fn step_by_hand(&mut self, velocities: &[[f64; 2]], turns: Option<&[f64]>) -> Result<(), DeformError> {
        self.settle()?;
        let before = self.turned_before(turns);
        self.take(velocities, turns, None)?;
        self.turns_asked_as_made(&before);
        Ok(())
    }

    /// The guarded step of [`crate::deform::foldover`] with these limits, velocities and,
    /// where given, turns, as given: no substeps, no retry. Each plain step it takes is
    /// recorded; the handles' targets become where it took them and the turns it made count
    /// as asked. On error the deformer is where it was.
    pub fn step_without_foldovers(
        &mut self,
        velocities: &[[f64; 2]],
        turns: Option<&[f64]>,
        guard: FoldoverGuard,
    ) -> Result<GuardedStep, DeformError> {
        guard.check()?;
        self.settle()?;
        let before = self.turned_before(turns);
        let (_, clamped) = self.take(velocities, turns, Some(guard))?;
        self.turns_asked_as_made(&before);
        self.pin_handles();
        Ok(GuardedStep { steps: self.fractions.clone(), clamped, attempts: self.attempts })
    }

    /// How far the handles have turned, before a step asked for by hand with `turns`.
    fn turned_before(&self, turns: Option<&[f64]>) -> Vec<f64> {
        turns.map_or_else(Vec::new, |_| self.handles.iter().map(|h| h.turned).collect())
    }

    /// After a step asked for by hand: the turns it made count as asked too, so that no
    /// frame turns them back.
    fn turns_asked_as_made(&mut self, before: &[f64]) {
        for (h, b) in self.handles.iter_mut().zip(before) {
            h.turn += h.turned - b;
        }
    }

    /// How many substeps the tracking takes to bring every handle to its target from where
    /// it is: the largest distance over the longest step, rounded up, at least 1 (a frame
    /// takes at most [`Tracking::max_substeps`] of them).
    pub fn substeps_needed(&self) -> f64 {
        let current = self.deformer.borrow().handle_positions();
        let gap = current
            .iter()
            .zip(&self.handles)
            .fold(0.0f64, |m, (p, h)| m.max(libm::hypot(h.target[0] - p[0], h.target[1] - p[1])));
        substeps(gap, self.tracking.max_step * self.size)
    }

    /// One plain step that takes every handle a `1 / remaining` share of the rest of its way
    /// to its target, `(target - current) / remaining` (the tracking's velocities,
    /// `remaining` the steps left including this one), with `turns` where given; the
    /// targets stay. `remaining` 1 takes the whole way, as a replay driving another method
    /// to recorded targets does. Recorded.
    pub fn step_toward(&mut self, remaining: f64, turns: Option<&[f64]>) -> Result<(), DeformError> {
        self.settle()?;
        self.deformer.borrow().handle_positions_into(&mut self.current);
        toward(&self.handles, &self.current, remaining, &mut self.velocities);
        let velocities = std::mem::take(&mut self.velocities);
        let result = self.step_by_hand(&velocities, turns);
        self.velocities = velocities;
        result
    }

    // ------------------------------------------------------------------ the rig

    /// Poses with `operator`, a trained rig, instead of stepping: each frame the pose is
    /// the rig's for the handles' targets (there is nothing to step through). Refused
    /// ([`DeformError::RigMismatch`]) for a rig of other handle or vertex counts, and
    /// ([`DeformError::InvalidParts`]) for a rig trained on another puppet than the
    /// deformer's (other parts or joints, or one for a puppet and the other not); the
    /// caller is to check it was trained for this mesh and these handle points. `None`
    /// poses with the deformer again; so does any new handle set. Recorded (a `rig` event
    /// naming the rig by [`session_rig`]).
    pub fn set_rig(&mut self, operator: Option<Operator>) -> Result<(), DeformError> {
        self.settle()?;
        let Some(operator) = operator else {
            if self.rig.take().is_some() {
                self.record(|| Event::Rig(None));
            }
            return Ok(());
        };
        let (rig, deformer) = (
            [operator.handles().len(), operator.vertex_count()],
            [self.handles.len(), self.deformer.borrow().mesh().vertex_count()],
        );
        if rig != deformer {
            return Err(DeformError::RigMismatch { rig, deformer });
        }
        if operator.puppet() != self.deformer.borrow().puppet() {
            return Err(DeformError::InvalidParts {
                reason: "the rig was trained on another puppet (its parts or joints differ from the deformer's): \
                         train it again for this puppet"
                    .into(),
            });
        }
        self.rig = Some(Rig::new(operator, self.handles.len()));
        self.announce_rig();
        Ok(())
    }

    /// Names the rig in the recording, if one runs (a `rig` event): its frames are then
    /// recorded as the targets they are for. A rig that cannot be named (it cannot be
    /// written with this mesh) is recorded by its poses.
    fn announce_rig(&mut self) {
        let Some(rig) = &mut self.rig else { return };
        rig.announced = false;
        if let (Some(session), false) = (&mut self.recording, self.paused) {
            if let Ok(named) = session_rig(self.deformer.borrow().mesh(), &rig.operator) {
                session.events.push(Event::Rig(Some(named)));
                rig.announced = true;
            }
        }
    }

    /// The targets the rig's pose is for (x and y per handle; `None` without a rig or
    /// before its first pose): where a no-foldover guard left them, the handles' targets
    /// otherwise.
    pub fn rig_targets(&self) -> Option<&[f64]> {
        self.rig.as_ref().map(|rig| rig.posed.as_slice()).filter(|posed| !posed.is_empty())
    }

    /// Whether a rig poses the shape ([`Self::set_rig`]).
    pub fn has_rig(&self) -> bool {
        self.rig.is_some()
    }

    /// The rig's handle points, to check a rig fits (`None` without one).
    pub fn rig_points(&self) -> Option<&[MeshPoint]> {
        self.rig.as_ref().map(|rig| rig.operator.handles())
    }

    /// Poses the rig on the GPU (`on`) or on the CPU: on the GPU each frame computes the
    /// rig's frame ([`Self::rig_gpu`]) and the deformer's positions wait for
    /// [`Self::settle`]. Returns whether the rig is on the GPU now (never without a rig, nor
    /// for a rig carried from a coarse mesh; a new rig starts on the CPU).
    pub fn set_rig_on_gpu(&mut self, on: bool) -> Result<bool, DeformError> {
        if !on {
            self.settle()?;
        }
        let Some(rig) = &mut self.rig else { return Ok(false) };
        // A rig carried from a coarse mesh poses the fine one by interpolation, which the
        // vertex shader does not do: it stays on the CPU.
        if on && rig.operator.carried().is_some() {
            return Ok(false);
        }
        match (on, rig.gpu.is_some()) {
            (true, false) => {
                rig.gpu = Some(GpuRig::new(&rig.operator));
                // The first frame on the GPU computes its frame even at the same targets.
                rig.asked.clear();
            }
            (false, true) => rig.gpu = None,
            _ => {}
        }
        Ok(on)
    }

    /// The rig's CPU side on the GPU (its layout, the last frame, the watched vertices'
    /// positions), if a rig poses on the GPU.
    pub fn rig_gpu(&self) -> Option<&GpuRig> {
        self.rig.as_ref().and_then(|rig| rig.gpu.as_ref())
    }

    /// The basis texture of the rig on the GPU ([`gpu::basis_texture`]), once per rig.
    pub fn rig_gpu_texture(&self) -> Option<Vec<f32>> {
        self.rig.as_ref().filter(|rig| rig.gpu.is_some()).map(|rig| gpu::basis_texture(&rig.operator))
    }

    /// Watches these vertices of the rig on the GPU ([`GpuRig::watch`]): each frame gives
    /// their positions. Returns whether a rig is on the GPU (nothing is watched without one).
    pub fn watch_rig_vertices(&mut self, vertices: &[u32]) -> Result<bool, FitError> {
        let Some(Rig { operator, gpu: Some(gpu), asked, .. }) = &mut self.rig else { return Ok(false) };
        gpu.watch(operator, vertices)?;
        asked.clear(); // the next frame gives their positions
        Ok(true)
    }

    /// Whether the deformer's positions are behind the rig's last frame on the GPU.
    pub fn is_stale(&self) -> bool {
        self.rig.as_ref().is_some_and(|rig| rig.stale)
    }

    /// Whether the rig on the GPU has the frame of the pose shown: its last frame, stale
    /// positions or not (with the foldover guard a frame is evaluated on the CPU as well, and
    /// the GPU draws the same targets). Not after a pose set otherwise (undo, a reset).
    pub fn rig_frame_current(&self) -> bool {
        self.rig.as_ref().is_some_and(|rig| rig.gpu.is_some() && !rig.posed.is_empty())
    }

    /// With a rig on the GPU, puts the rig's pose at the last frame's targets into the
    /// deformer's positions if they are behind (nothing otherwise): what every reader of the
    /// pose calls first. Not recorded (a recording records each rig frame as it is taken).
    /// On error (a pose beyond the coordinate limits) the positions stay as they were.
    pub fn settle(&mut self) -> Result<(), DeformError> {
        let Some(rig) = self.rig.as_mut().filter(|rig| rig.stale) else { return Ok(()) };
        rig.stale = false;
        let Rig { operator, posed, .. } = rig;
        self.deformer
            .borrow_mut()
            .set_positions_with(|out| operator.evaluate_into(posed, out).map_err(|_| DeformError::NonFiniteResult))
    }

    /// The rig's pose for the handles' targets, straight into the deformer's positions;
    /// nothing when the targets are those of the last evaluation. With no foldovers, pulled
    /// back along the way from the targets of the last pose until no triangle turns over
    /// that was not at rest (`rig.rs`): then reported clamped, and the handles not held stay
    /// where the pose is for, as after a step stopped short. Recorded as the targets the pose
    /// is for (or as the pose, for a rig the recording does not name). On the GPU without
    /// the guard, the rig's frame only, the positions left behind (see [`Self::settle`]).
    fn evaluate_rig(&mut self) -> Result<Advance, DeformError> {
        let rig = self.rig.as_mut().expect("a rig poses");
        for (t, h) in rig.targets.chunks_exact_mut(2).zip(&self.handles) {
            t.copy_from_slice(&h.target);
        }
        if rig.asked == rig.targets {
            return Ok(Advance::default());
        }
        let clock = self.deformer.borrow().clock();
        let started = clock();
        // On the GPU a frame computes the rig's frame only; the guard needs the pose (it checks
        // its triangles), and so does a recording that cannot name the rig (it records poses).
        let recording_poses = self.recording.is_some() && !self.paused && !rig.announced;
        let gpu_only = rig.gpu.is_some() && !self.tracking.no_foldovers && !recording_poses;
        if !gpu_only && rig.stale {
            self.settle()?;
        }
        let rig = self.rig.as_mut().expect("a rig poses");
        let (moved, clamped) = match (gpu_only, self.tracking.no_foldovers) {
            (true, _) => rig.frame_on_gpu().map(|()| (true, false))?,
            (false, true) => {
                rig.pose_without_foldovers(self.deformer.borrow_mut(), self.tracking.guard.clamp_trials)?
            }
            (false, false) => rig.pose(self.deformer.borrow_mut()).map(|()| (true, false))?,
        };
        let evaluation = clock() - started;
        if clamped {
            for (h, p) in self.handles.iter_mut().zip(rig.posed.as_chunks::<2>().0) {
                if !h.held {
                    h.target = *p;
                }
            }
            for (t, h) in rig.targets.chunks_exact_mut(2).zip(&self.handles) {
                t.copy_from_slice(&h.target);
            }
        }
        rig.asked.clone_from(&rig.targets);
        if moved {
            self.at_rest = false;
            record(&mut self.recording, self.paused, || match rig.announced {
                true => Event::RigPose(rig.posed.clone()),
                false => Event::Positions(self.deformer.borrow().positions().as_flattened().to_vec()),
            });
        }
        Ok(Advance { steps: 1, clamped, evaluation, ..Advance::default() })
    }

    /// Poses with the rig at these targets (one per handle), as given: no guard (a replay's
    /// recorded `rigPose`, whose targets are where the recording's guard left them). The
    /// handles' targets become these. Refused ([`DeformError::NoRig`]) without a rig, and
    /// for targets of another count or not finite, changing nothing. Recorded.
    pub fn pose_with_rig(&mut self, targets: &[Point]) -> Result<(), DeformError> {
        self.check_targets(targets)?;
        let rig = self.rig.as_mut().ok_or(DeformError::NoRig)?;
        rig.targets.copy_from_slice(targets.as_flattened());
        rig.pose(self.deformer.borrow_mut())?;
        rig.asked.clone_from(&rig.targets);
        self.set_targets(targets)?;
        self.at_rest = false;
        let rig = self.rig.as_ref().expect("checked above");
        record(&mut self.recording, self.paused, || match rig.announced {
            true => Event::RigPose(rig.posed.clone()),
            false => Event::Positions(self.deformer.borrow().positions().as_flattened().to_vec()),
        });
        Ok(())
    }

    // ------------------------------------------------------------------ state set through the poser

    /// Puts the mesh into a given pose (undo, a saved pose); handles stay, their targets
    /// too. Recorded.
    pub fn set_positions(&mut self, positions: &[Point]) -> Result<(), DeformError> {
        self.deformer.borrow_mut().set_positions(positions)?;
        self.at_rest = false;
        if let Some(rig) = &mut self.rig {
            rig.forget_pose();
        }
        self.record(|| Event::Positions(positions.as_flattened().to_vec()));
        Ok(())
    }

    /// Back to the rest pose; handles stay, each with its target at its rest place.
    /// Recorded.
    pub fn reset(&mut self) {
        self.deformer.borrow_mut().reset();
        self.at_rest = true;
        if let Some(rig) = &mut self.rig {
            rig.forget_pose();
        }
        self.record(|| Event::Reset(true));
        self.pin_handles();
    }

    /// Puts options into effect ([`Deformer::set_options`]: another method's switch the
    /// method, keeping pose and handles). Recorded.
    pub fn set_options(&mut self, options: impl Into<MethodOptions>) -> Result<(), DeformError> {
        let options = options.into();
        self.settle()?;
        self.deformer.borrow_mut().set_options(options)?;
        self.record(|| Event::Options(RecordedOptions::of(options)));
        Ok(())
    }

    /// Replaces a puppet's joints ([`Deformer::set_joints`]). Recorded.
    pub fn set_joints(&mut self, joints: Vec<Joint>) -> Result<(), DeformError> {
        let recorded = SessionJoint::all(&joints);
        self.settle()?;
        self.deformer.borrow_mut().set_joints(joints)?;
        self.record(|| Event::Joints(recorded));
        Ok(())
    }

    /// Sets each triangle's stiffness ([`Deformer::set_stiffness`]). Recorded (methods
    /// without stiffness take only `None`).
    pub fn set_stiffness(&mut self, stiffness: Option<&[f64]>) -> Result<(), DeformError> {
        self.settle()?;
        self.deformer.borrow_mut().set_stiffness(stiffness)?;
        if self.deformer.borrow().has_stiffness() {
            self.record(|| Event::Stiffness(stiffness.map(<[f64]>::to_vec)));
        }
        Ok(())
    }

    /// Sets the bones ([`Deformer::set_bones`]). Recorded.
    pub fn set_bones(&mut self, triangles: &[u32], barycentric: &[[f64; 3]]) -> Result<(), DeformError> {
        self.settle()?;
        self.deformer.borrow_mut().set_bones(triangles, barycentric)?;
        if self.deformer.borrow().has_bones() {
            let barycentric = barycentric.as_flattened().to_vec();
            self.record(|| Event::Bones { triangles: triangles.to_vec(), barycentric });
        }
        Ok(())
    }

    /// Sets the clock of the deformer's timings and the rig's evaluation time.
    pub fn set_clock(&mut self, clock: crate::deform::Clock) {
        self.deformer.borrow_mut().set_clock(clock);
    }

    // ------------------------------------------------------------------ recording

    /// Starts recording a session of everything the poser does from now on, replacing any
    /// recording: a header with the mesh (named by `shape` when the mesh is that built-in
    /// shape triangulated, else carried inline) and the current options, then the events
    /// that put a deformer in the current state (the pose or a reset, the handles, the
    /// stiffness and bones, the rig).
    pub fn start_recording(&mut self, shape: Option<ShapeSpec>) {
        let _ = self.settle();
        let deformer = self.deformer.borrow();
        let mesh = deformer.mesh();
        let mut session = Session::with_mesh(mesh, deformer.options());
        session.puppet = deformer.puppet().map(SessionPuppet::of);
        if let Some(shape) = shape {
            session.shape = Some(shape);
            session.mesh = SessionMesh::counts_of(MeshCounts::of(mesh));
        }
        session.events.push(match self.at_rest {
            true => Event::Reset(true),
            false => Event::Positions(deformer.positions().as_flattened().to_vec()),
        });
        if !self.handles.is_empty() {
            session.events.push(handles_event(deformer));
        }
        if let Some(stiffness) =
            deformer.stiffness().filter(|s| deformer.has_stiffness() && s.iter().any(|&x| x != 1.0))
        {
            session.events.push(Event::Stiffness(Some(stiffness.to_vec())));
        }
        let (triangles, barycentric) = deformer.bone_points();
        if !triangles.is_empty() {
            session.events.push(Event::Bones { triangles, barycentric: barycentric.as_flattened().to_vec() });
        }
        self.recording = Some(session);
        self.announce_rig();
    }

    /// Records from now on into `session`, its header and events so far the caller's (a
    /// script that writes its own header), replacing any recording; a rig posing is named
    /// in it.
    pub fn resume_recording(&mut self, session: Session) {
        self.recording = Some(session);
        self.announce_rig();
    }

    /// Whether a recording runs.
    pub fn recording(&self) -> bool {
        self.recording.is_some()
    }

    /// The session recorded so far, if a recording runs.
    pub fn recorded(&self) -> Option<&Session> {
        self.recording.as_ref()
    }

    /// Ends the recording and returns it (`None` if none ran).
    pub fn stop_recording(&mut self) -> Option<Session> {
        if let Some(rig) = &mut self.rig {
            rig.announced = false;
        }
        self.recording.take()
    }

    /// Pauses the recording (a session replays) or resumes it: while paused nothing is
    /// recorded.
    pub fn pause_recording(&mut self, paused: bool) {
        self.paused = paused;
    }

    fn record(&mut self, event: impl FnOnce() -> Event) {
        record(&mut self.recording, self.paused, event);
    }

    fn record_handles(&mut self) {
        record(&mut self.recording, self.paused, || handles_event(self.deformer.borrow()));
    }
}

/// Adds an event to the recording, if one runs and is not paused.
fn record(recording: &mut Option<Session>, paused: bool, event: impl FnOnce() -> Event) {
    if let (Some(session), false) = (recording, paused) {
        session.events.push(event());
    }
}

/// The deformer's handles as a session event.
fn handles_event(deformer: &Deformer) -> Event {
    let (triangles, barycentric) = deformer.handle_points();
    Event::Handles { triangles, barycentric: barycentric.as_flattened().to_vec() }
}

/// Into `out`, each handle's velocity for the rest of the way to its target from `current`
/// over `remaining` steps: `(target - current) / remaining`.
fn toward(handles: &[HandleState], current: &[Point], remaining: f64, out: &mut [[f64; 2]]) {
    for ((v, p), h) in out.iter_mut().zip(current).zip(handles) {
        *v = [(h.target[0] - p[0]) / remaining, (h.target[1] - p[1]) / remaining];
    }
}

/// The paper's mode: each handle's motion split evenly over `count` substeps.
fn split_evenly(motion: &mut [[f64; 2]], count: usize) {
    for v in motion {
        *v = [v[0] / count as f64, v[1] / count as f64];
    }
}

/// How many substeps cover `distance` with steps of at most `longest` (at least 1).
fn substeps(distance: f64, longest: f64) -> f64 {
    (distance / longest - 1e-9).ceil().max(1.0)
}

/// `out` becomes `values` times `scale` (`values` itself for 1).
fn scale_into<T: Copy + Scale>(out: &mut [T], values: &[T], scale: f64) {
    for (o, v) in out.iter_mut().zip(values) {
        *o = if scale == 1.0 { *v } else { v.scale(scale) };
    }
}

/// Values a step can be scaled by.
trait Scale {
    fn scale(&self, by: f64) -> Self;
}

impl Scale for f64 {
    fn scale(&self, by: f64) -> Self {
        self * by
    }
}

impl Scale for [f64; 2] {
    fn scale(&self, by: f64) -> Self {
        [self[0] * by, self[1] * by]
    }
}

/// A finite target (one beyond the coordinate limits is asked for, and the step toward it
/// refused, as a velocity that large is).
fn check_target(handle: usize, target: &Point) -> Result<(), DeformError> {
    match target.iter().find(|x| !x.is_finite()) {
        Some(&value) => Err(DeformError::InvalidTarget { handle, value }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn handles(targets: &[Point]) -> Vec<HandleState> {
        targets.iter().map(|&target| HandleState { target, ..HandleState::default() }).collect()
    }

    #[test]
    fn substeps_bring_every_handle_exactly_to_its_target_with_bounded_steps() {
        let mut p = [[0.0, 0.0], [1.0, 1.0]];
        let targets = [[0.25, -0.1], [1.0, 1.05]];
        let gap = p.iter().zip(&targets).fold(0.0f64, |m, (p, t)| m.max(libm::hypot(t[0] - p[0], t[1] - p[1])));
        assert!((gap - 0.25f64.hypot(0.1)).abs() < 1e-15);
        let n = substeps(gap, 0.05);
        assert_eq!(n, (gap / 0.05).ceil());
        // Perfect tracking: each substep moves by the velocity.
        let h = handles(&targets);
        let mut v = [[0.0; 2]; 2];
        for s in 0..n as usize {
            toward(&h, &p, n - s as f64, &mut v);
            assert!(v[0][0].hypot(v[0][1]) <= 0.05 + 1e-12);
            for (p, v) in p.iter_mut().zip(&v) {
                *p = [p[0] + v[0], p[1] + v[1]];
            }
        }
        for (p, t) in p.iter().zip(&targets) {
            assert!((p[0] - t[0]).abs() < 1e-14 && (p[1] - t[1]).abs() < 1e-14, "{p:?} {t:?}");
        }
    }

    #[test]
    fn a_handle_that_fell_short_is_aimed_at_its_target_again() {
        // The handle reached only 80% of the way: the next velocity is the whole gap left.
        let mut v = [[0.0; 2]];
        toward(&handles(&[[1.0, 0.0]]), &[[0.8, 0.0]], 1.0, &mut v);
        assert_eq!(v, [[0.19999999999999996, 0.0]]);
    }

    #[test]
    fn exact_multiples_need_no_extra_substep_and_nothing_to_do_is_one() {
        assert_eq!(substeps(0.3, 0.1), 3.0);
        assert_eq!(substeps(0.0, 0.1), 1.0);
        assert!(Tracking { max_step: 0.0, ..Tracking::default() }.check().is_err());
    }

    #[test]
    fn the_papers_mode_splits_the_motion_evenly() {
        let mut motion = [[0.75, -1.5], [0.0, 0.0]];
        split_evenly(&mut motion, 3);
        assert_eq!(motion, [[0.25, -0.5], [0.0, 0.0]]);
    }
}
