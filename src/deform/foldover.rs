//! No foldovers: a step that never turns a triangle over, for any method.
//!
//! A triangle *flips* in a step when it was positively oriented before the step and is not
//! after it (turned over, or collapsed to double precision). The guarded step
//! ([`FoldoverStepper::step`], [`step_without_foldovers`]):
//!
//! 1. takes the plain step, `Deformer::step(velocities)` itself; if nothing flips, that is
//!    all: a step that flips nothing is the plain step, to the bit;
//! 2. otherwise undoes it ([`Deformer::restore_checkpoint`]) and takes two half steps
//!    (`velocities * 0.5` each), each guarded the same way, halving down to pieces of
//!    `2^-max_splits` of the velocities ([`FoldoverGuard`]);
//! 3. a piece of that size that still flips is clamped: a bisection over the fraction `t`
//!    of the piece (each trial a plain step of `velocities * (piece * t)` from the state
//!    before the piece) keeps the largest `t` found flip-free, possibly none; the guarded
//!    step ends there, the pieces after it not taken.
//!
//! Every plain step taken moves by `velocities[i] * fraction` with the fraction a power of
//! two, or a power of two times a bisection's dyadic `t` (an exact product), and
//! [`GuardedStep::steps`] lists those fractions: a caller that records each as the
//! velocities times its fraction replays the guarded step with plain steps, bit for bit.
//!
//! Orientation is [`certain_orient`] on each pose scaled by the power of two that brings
//! its largest coordinate into [1, 2), the rule `Mesh::new` decides degenerate triangles
//! by: exact and the same at every scale, and a triangle squeezed until double precision
//! cannot tell its orientation counts as flipped, as the deformers' factorisations would
//! treat it. Triangles flipped or degenerate before a step are not positive then, so they
//! cannot block it.
//!
//! For methods with history (AKAP, ARAP) smaller steps follow a different path, which is
//! what lets a guarded drag go on without folding. Moving least squares and Cauchy-Green
//! map the rest shape for targets, with no history (MLS takes its targets from the current
//! pose, Cauchy-Green keeps them apart): halving the step reaches (nearly) the same pose,
//! so for them the guard amounts to stopping the handles where the straight path to their
//! targets would first flip a triangle.

use super::deformer::Deformer;
use super::error::DeformError;
use super::method::Checkpoint;
use crate::geometry::{certain_orient, normalising_exponent, power_of_two, Point};
use crate::mesh::Mesh;

/// What the guarded step needs of a deformer: plain steps, and checkpoints to undo them
/// with. [`Deformer`] is one; a test can put a deformer behind it that fails on purpose.
pub trait Undoable {
    /// The mesh in its rest pose.
    fn mesh(&self) -> &Mesh;
    /// Current vertex positions.
    fn positions(&self) -> &[Point];
    /// Number of handles.
    fn handle_count(&self) -> usize;
    /// A plain step ([`Deformer::step`]).
    fn step(&mut self, velocities: &[[f64; 2]]) -> Result<(), DeformError>;
    /// A plain step in which handles turn ([`Deformer::step_turning`]).
    fn step_turning(&mut self, velocities: &[[f64; 2]], turns: &[f64]) -> Result<(), DeformError>;
    /// [`Deformer::save_checkpoint`].
    fn save_checkpoint(&self, checkpoint: &mut Checkpoint);
    /// [`Deformer::restore_checkpoint`].
    fn restore_checkpoint(&mut self, checkpoint: &Checkpoint) -> Result<(), DeformError>;
}

impl Undoable for Deformer {
    fn mesh(&self) -> &Mesh {
        Deformer::mesh(self)
    }
    fn positions(&self) -> &[Point] {
        Deformer::positions(self)
    }
    fn handle_count(&self) -> usize {
        Deformer::handle_count(self)
    }
    fn step(&mut self, velocities: &[[f64; 2]]) -> Result<(), DeformError> {
        Deformer::step(self, velocities)
    }
    fn step_turning(&mut self, velocities: &[[f64; 2]], turns: &[f64]) -> Result<(), DeformError> {
        Deformer::step_turning(self, velocities, turns)
    }
    fn save_checkpoint(&self, checkpoint: &mut Checkpoint) {
        Deformer::save_checkpoint(self, checkpoint);
    }
    fn restore_checkpoint(&mut self, checkpoint: &Checkpoint) -> Result<(), DeformError> {
        Deformer::restore_checkpoint(self, checkpoint)
    }
}

/// Most halvings a guarded step may make ([`FoldoverGuard::max_splits`]): pieces of 2^-10
/// of the step, at most some two thousand plain steps.
pub const MAX_SPLITS: u32 = 10;

/// Most bisection trials of the clamp ([`FoldoverGuard::clamp_trials`]): the fraction of
/// the last piece to 2^-30.
pub const MAX_CLAMP_TRIALS: u32 = 30;

/// How far a guarded step splits and clamps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FoldoverGuard {
    /// Halvings: a step that flips is split into halves down to pieces of `2^-max_splits`
    /// of the velocities (default 4: sixteenths), at most [`MAX_SPLITS`].
    pub max_splits: u32,
    /// Bisection trials of the clamp of a smallest piece that still flips (default 12: its
    /// largest flip-free fraction to 2^-12 of the piece), at most [`MAX_CLAMP_TRIALS`]; with
    /// 0 such a piece is not taken at all.
    pub clamp_trials: u32,
}

impl Default for FoldoverGuard {
    fn default() -> Self {
        Self { max_splits: 4, clamp_trials: 12 }
    }
}

impl FoldoverGuard {
    /// With pieces down to `2^-max_splits` of the step.
    pub fn with_max_splits(self, max_splits: u32) -> Self {
        Self { max_splits, ..self }
    }

    /// With this many bisection trials in the clamp.
    pub fn with_clamp_trials(self, clamp_trials: u32) -> Self {
        Self { clamp_trials, ..self }
    }

    /// Checks both counts against their limits.
    pub fn check(&self) -> Result<(), DeformError> {
        if self.max_splits > MAX_SPLITS {
            return Err(DeformError::InvalidOption {
                name: "maxSplits",
                value: f64::from(self.max_splits),
                expected: "a whole number from 0 to 10",
            });
        }
        if self.clamp_trials > MAX_CLAMP_TRIALS {
            return Err(DeformError::InvalidOption {
                name: "clampTrials",
                value: f64::from(self.clamp_trials),
                expected: "a whole number from 0 to 30",
            });
        }
        Ok(())
    }
}

/// What a guarded step did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct GuardedStep {
    /// The plain steps taken, in order, each as the fraction of the velocities it moved by
    /// (`Deformer::step` with `velocities[i] * fraction`): `[1.0]` when the step flipped
    /// nothing; otherwise powers of two, and last, when `clamped`, the clamp's fraction;
    /// empty when nothing could be taken.
    pub steps: Vec<f64>,
    /// Whether a smallest piece still flipped and was clamped: the step ended short of its
    /// velocities.
    pub clamped: bool,
    /// Plain steps tried, those undone included (1 when nothing flipped).
    pub attempts: usize,
}

impl GuardedStep {
    /// The share of the velocities taken: the sum of [`Self::steps`] (1 for a whole step).
    pub fn fraction(&self) -> f64 {
        self.steps.iter().sum()
    }
}

/// Guarded steps with buffers kept from one to the next: the checkpoints, the scaled
/// velocities and the report grow to the deformer's sizes once, and a step that flips
/// nothing then allocates nothing beyond the plain step's own.
#[derive(Debug, Clone, Default)]
pub struct FoldoverStepper {
    guard: FoldoverGuard,
    /// The state before the guarded step, saved once a piece has been taken (before that,
    /// `piece` holds it).
    start: Checkpoint,
    /// The state before the current piece.
    piece: Checkpoint,
    /// The velocities times the current fraction.
    scaled: Vec<[f64; 2]>,
    /// The handles' turns of the step (empty: a step without turns), and times the fraction.
    turns: Vec<f64>,
    scaled_turns: Vec<f64>,
    /// Pieces still to take, as halvings (a piece is `2^-depth` of the step), last first.
    pending: Vec<u32>,
    report: GuardedStep,
}

impl FoldoverStepper {
    /// A stepper for these limits (checked).
    pub fn new(guard: FoldoverGuard) -> Result<Self, DeformError> {
        guard.check()?;
        Ok(Self { guard, ..Self::default() })
    }

    /// The limits.
    pub fn guard(&self) -> FoldoverGuard {
        self.guard
    }

    /// Changes the limits (checked; unchanged on error).
    pub fn set_guard(&mut self, guard: FoldoverGuard) -> Result<(), DeformError> {
        guard.check()?;
        self.guard = guard;
        Ok(())
    }

    /// One guarded step of `deformer` with a velocity per handle (see the module's
    /// description). On error (bad velocities, or a plain step that fails) the deformer is
    /// back where it was and the error returned.
    pub fn step(
        &mut self,
        deformer: &mut (impl Undoable + ?Sized),
        velocities: &[[f64; 2]],
    ) -> Result<&GuardedStep, DeformError> {
        self.turns.clear();
        self.run(deformer, velocities)
    }

    /// [`Self::step`] of a step in which handles also turn ([`Deformer::step_turning`]): each
    /// piece turns them by the same fraction of `turns` as it moves them, so the report's
    /// fractions replay with `step_turning(velocities * f, turns * f)`.
    pub fn step_turning(
        &mut self,
        deformer: &mut (impl Undoable + ?Sized),
        velocities: &[[f64; 2]],
        turns: &[f64],
    ) -> Result<&GuardedStep, DeformError> {
        self.turns.clear();
        if turns.iter().any(|&w| w != 0.0) {
            crate::deform::handles::check_turns(turns, deformer.handle_count())?;
            self.turns.extend_from_slice(turns);
        }
        self.run(deformer, velocities)
    }

    fn run(
        &mut self,
        deformer: &mut (impl Undoable + ?Sized),
        velocities: &[[f64; 2]],
    ) -> Result<&GuardedStep, DeformError> {
        self.report.steps.clear();
        self.report.clamped = false;
        self.report.attempts = 1;
        deformer.save_checkpoint(&mut self.piece);
        // The plain step itself; a failed one leaves the deformer unchanged.
        if self.turns.is_empty() {
            deformer.step(velocities)?;
        } else {
            deformer.step_turning(velocities, &self.turns)?;
        }
        if !self.flipped(deformer) {
            self.report.steps.push(1.0);
            return Ok(&self.report);
        }
        deformer.restore_checkpoint(&self.piece)?;
        if let Err(error) = self.pieces(deformer, velocities) {
            // Back to the start (a failed plain step left the deformer where it was).
            deformer.restore_checkpoint(&self.start)?;
            return Err(error);
        }
        Ok(&self.report)
    }

    /// The rest of a step whose whole flipped (and was undone), from the state in `piece`,
    /// which the deformer is in.
    fn pieces(&mut self, deformer: &mut (impl Undoable + ?Sized), velocities: &[[f64; 2]]) -> Result<(), DeformError> {
        deformer.save_checkpoint(&mut self.start);
        self.pending.clear();
        if self.split_or_clamp(deformer, velocities, 0)? {
            return Ok(());
        }
        // Whether `piece` holds the deformer's current state.
        let mut saved = true;
        while let Some(depth) = self.pending.pop() {
            let fraction = power_of_two(-(depth as i32));
            if !saved {
                deformer.save_checkpoint(&mut self.piece);
            }
            self.attempt(deformer, velocities, fraction)?;
            if !self.flipped(deformer) {
                self.report.steps.push(fraction);
                saved = false;
                continue;
            }
            deformer.restore_checkpoint(&self.piece)?;
            saved = true;
            if self.split_or_clamp(deformer, velocities, depth)? {
                break;
            }
        }
        Ok(())
    }

    /// After the piece of `2^-depth` from the state in `piece` flipped and was undone: its
    /// two halves to take next, or at the limit its clamp, which ends the guarded step
    /// (`true`).
    fn split_or_clamp(
        &mut self,
        deformer: &mut (impl Undoable + ?Sized),
        velocities: &[[f64; 2]],
        depth: u32,
    ) -> Result<bool, DeformError> {
        if depth < self.guard.max_splits {
            self.pending.extend([depth + 1, depth + 1]);
            return Ok(false);
        }
        let fraction = power_of_two(-(depth as i32));
        self.report.clamped = true;
        let t = self.clamp(deformer, velocities, fraction)?;
        if t > 0.0 {
            self.report.steps.push(fraction * t);
        }
        Ok(true)
    }

    /// Whether the deformer's step from the state in `piece` flipped a triangle.
    fn flipped(&self, deformer: &(impl Undoable + ?Sized)) -> bool {
        flips(&self.piece.positions, deformer.positions(), deformer.mesh().triangles())
    }

    /// A plain step of `velocities * fraction`.
    fn attempt(
        &mut self,
        deformer: &mut (impl Undoable + ?Sized),
        velocities: &[[f64; 2]],
        fraction: f64,
    ) -> Result<(), DeformError> {
        self.scaled.clear();
        self.scaled.extend(velocities.iter().map(|v| [v[0] * fraction, v[1] * fraction]));
        self.report.attempts += 1;
        if self.turns.is_empty() {
            return deformer.step(&self.scaled);
        }
        self.scaled_turns.clear();
        self.scaled_turns.extend(self.turns.iter().map(|w| w * fraction));
        deformer.step_turning(&self.scaled, &self.scaled_turns)
    }

    /// The largest fraction `t` of the piece `velocities * piece` that the bisection finds
    /// flip-free (0 when none), from the state in `piece`; the deformer is left after that
    /// step (or in `piece` for 0).
    fn clamp(
        &mut self,
        deformer: &mut (impl Undoable + ?Sized),
        velocities: &[[f64; 2]],
        piece: f64,
    ) -> Result<f64, DeformError> {
        let (mut good, mut bad) = (0.0, 1.0);
        // Whether the deformer is after the step of `good` (else in `piece`).
        let mut at_good = false;
        for _ in 0..self.guard.clamp_trials {
            let t = 0.5 * (good + bad);
            if at_good {
                deformer.restore_checkpoint(&self.piece)?;
            }
            self.attempt(deformer, velocities, piece * t)?;
            at_good = !self.flipped(deformer);
            if at_good {
                good = t;
            } else {
                bad = t;
                deformer.restore_checkpoint(&self.piece)?;
            }
        }
        if good > 0.0 && !at_good {
            // The same step again from the same state: the same bits, flip-free.
            self.attempt(deformer, velocities, piece * good)?;
            debug_assert!(!self.flipped(deformer));
        }
        Ok(good)
    }
}

/// [`FoldoverStepper::step`] with a stepper made for this one step (a caller stepping
/// every frame keeps a [`FoldoverStepper`] instead, whose buffers are reused).
pub fn step_without_foldovers(
    deformer: &mut (impl Undoable + ?Sized),
    velocities: &[[f64; 2]],
    guard: &FoldoverGuard,
) -> Result<GuardedStep, DeformError> {
    let mut stepper = FoldoverStepper::new(*guard)?;
    stepper.step(deformer, velocities).cloned()
}

/// The triangles positive in `before` and not in `after` (the two poses of one mesh,
/// `triangles` its index triples): those a step between them flipped.
pub fn newly_flipped(before: &[Point], after: &[Point], triangles: &[[u32; 3]]) -> usize {
    let (b, a) = (Pose::new(before), Pose::new(after));
    triangles.iter().filter(|t| !a.positive(t) && b.positive(t)).count()
}

/// Into `out`, whether each triangle is positive in `positions` (the orientation this
/// module decides with): a trained rig's guard (`pose`) watches these, having no step to
/// split.
pub fn positive_triangles(positions: &[Point], triangles: &[[u32; 3]], out: &mut Vec<bool>) {
    let pose = Pose::new(positions);
    out.clear();
    out.extend(triangles.iter().map(|t| pose.positive(t)));
}

/// Whether a step from `before` to `after` flipped a triangle (see [`newly_flipped`]).
fn flips(before: &[Point], after: &[Point], triangles: &[[u32; 3]]) -> bool {
    // Most triangles are positive after the step: the pose before is looked at only for
    // those that are not.
    let a = Pose::new(after);
    let mut not_positive = triangles.iter().filter(|t| !a.positive(t)).peekable();
    if not_positive.peek().is_none() {
        return false;
    }
    let b = Pose::new(before);
    not_positive.any(|t| b.positive(t))
}

/// A pose with the power of two that brings its largest coordinate into [1, 2).
struct Pose<'a> {
    positions: &'a [Point],
    scale: f64,
}

impl<'a> Pose<'a> {
    fn new(positions: &'a [Point]) -> Self {
        // (Clamped: a pose within the coordinate limits never needs it.)
        let k = normalising_exponent(positions.iter().copied()).clamp(-1022, 1023);
        Self { positions, scale: power_of_two(k) }
    }

    /// Whether triangle `t` is positively oriented to double precision.
    fn positive(&self, t: &[u32; 3]) -> bool {
        let [a, b, c] = t.map(|v| self.positions[v as usize].map(|x| x * self.scale));
        certain_orient(a, b, c).is_some_and(|d| d > 0.0)
    }
}
