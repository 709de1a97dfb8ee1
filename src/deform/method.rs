//! What every deformation method plugs into the one [`Deformer`]: the `Solve` trait, the
//! narrow part that differs between methods (each method's solver implements it beside its
//! type), the `Build` trait by which a method's options make its solver, the enum of
//! solvers written from the list of methods, the [`Orders`] a set-up can compute apart, the
//! stage [`Timings`] of a step and the [`Checkpoint`] a step is undone with.

use std::fmt;

use super::bones::Bones;
use super::error::DeformError;
use super::handles::HandlePoint;
use super::options::{methods, AkapOptions, ArapOptions, CauchyGreenOptions, Method, MethodOptions, MlsOptions};
use super::puppet::Joins;
use crate::geometry::Point;
use crate::mesh::Mesh;

#[cfg(doc)]
use super::Deformer;

/// How a method's options make its solver: implemented for each options type beside its
/// solver, so that [`MethodOptions`] reaches every method through the list of methods alone.
pub(crate) trait Build {
    /// The method's solver.
    type Solver: Solve;
    /// Checks the settings' ranges, as building a solver with them would.
    fn check(&self) -> Result<(), DeformError>;
    /// The fill-reducing orders the method's solver needs for `mesh`.
    fn orders(&self, mesh: &Mesh) -> Orders;
    /// The method's solver for a connected mesh, or a puppet's sheets coupled by `joins`,
    /// with orders from [`Build::orders`] (checked here), at rest and without handles.
    fn build(self, mesh: &Mesh, joins: &Joins, orders: &Orders) -> Result<Self::Solver, DeformError>;
    /// The settings `solver` has.
    fn of(solver: &Self::Solver) -> Self;
    /// Puts these settings (checked by [`Build::check`]) into effect on `solver`, from its
    /// next step; on error nothing changes.
    fn configure(self, solver: &mut Self::Solver, shared: Shared<'_>) -> Result<(), DeformError>;
}

/// Writes, from the list of methods, the enum of solvers and [`MethodOptions`]' dispatch
/// to [`Build`].
macro_rules! method_dispatch {
    ($($(#[$doc:meta])* $variant:ident($name:literal, $options:ident),)*) => {
        /// One method's solver (the [`Deformer`] holds one).
        #[derive(Debug)]
        pub(crate) enum Solver {
            $($(#[$doc])* $variant(<$options as Build>::Solver),)*
        }

        impl Solver {
            /// The solver behind its method's interface.
            pub(crate) fn get(&self) -> &dyn Solve {
                match self {
                    $(Self::$variant(solver) => solver,)*
                }
            }

            /// The solver behind its method's interface, to change.
            pub(crate) fn get_mut(&mut self) -> &mut dyn Solve {
                match self {
                    $(Self::$variant(solver) => solver,)*
                }
            }

            /// The method and the solver's settings.
            pub(crate) fn options(&self) -> MethodOptions {
                match self {
                    $(Self::$variant(solver) => MethodOptions::$variant(Build::of(solver)),)*
                }
            }

            /// New settings of the solver's method (checked); options of another method are
            /// refused ([`DeformError::WrongMethod`]). On error nothing changes.
            pub(crate) fn set_options(&mut self, options: MethodOptions, shared: Shared<'_>) -> Result<(), DeformError> {
                match (self, options) {
                    $((Self::$variant(solver), MethodOptions::$variant(options)) => {
                        Build::check(&options)?;
                        options.configure(solver, shared)
                    })*
                    (solver, options) => {
                        Err(DeformError::WrongMethod { current: solver.options().method(), given: options.method() })
                    }
                }
            }
        }

        impl MethodOptions {
            /// Checks the settings' ranges, as making a deformer with them would.
            pub fn check(&self) -> Result<(), DeformError> {
                match self {
                    $(Self::$variant(options) => Build::check(options),)*
                }
            }

            /// The fill-reducing orders this method's deformer needs for `mesh` (see [`Orders`]).
            pub fn orders(&self, mesh: &Mesh) -> Orders {
                match self {
                    $(Self::$variant(options) => Build::orders(options, mesh),)*
                }
            }

            /// This method's solver for `mesh` and its joins, with orders from [`Self::orders`].
            pub(crate) fn solver(self, mesh: &Mesh, joins: &Joins, orders: &Orders) -> Result<Solver, DeformError> {
                match self {
                    $(Self::$variant(options) => Ok(Solver::$variant(Build::build(options, mesh, joins, orders)?)),)*
                }
            }
        }

        $(
            impl From<$options> for MethodOptions {
                fn from(options: $options) -> Self {
                    Self::$variant(options)
                }
            }
        )*

        // Every options type of the list makes a solver.
        const _: fn() = || {
            fn builds<T: Build>() {}
            $(builds::<$options>();)*
        };
    };
}

methods!(method_dispatch);

/// The fill-reducing vertex orders a deformer's linear systems are factored in: the bulk
/// of its set-up (ordering the mesh's vertex graph). [`MethodOptions::orders`] computes them
/// for a mesh, possibly elsewhere (a worker), and [`Deformer::with_orders`] makes the
/// deformer with them, which then only analyses the systems and allocates.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Orders {
    /// One vertex order per system, in the method's order (AKAP: step 1 over every vertex,
    /// then step 2 over the interior vertices in their own numbering; ARAP: its Laplacian).
    pub systems: Vec<Vec<usize>>,
}

impl Orders {
    /// Checks that there is one order per size in `sizes`, each a permutation of `0..size`.
    pub(crate) fn check(&self, sizes: &[usize]) -> Result<(), DeformError> {
        if self.systems.len() != sizes.len() {
            return Err(DeformError::OrdersMismatch { system: self.systems.len(), expected: sizes.len() });
        }
        for (system, (order, &size)) in self.systems.iter().zip(sizes).enumerate() {
            let mut seen = vec![false; size];
            let permutation =
                order.len() == size && order.iter().all(|&v| v < size && !std::mem::replace(&mut seen[v], true));
            if !permutation {
                return Err(DeformError::OrdersMismatch { system, expected: size });
            }
        }
        Ok(())
    }
}

/// What a solver reads of its [`Deformer`]'s state: the rest mesh, the handles, the current
/// pose, the bones and the clock. The deformer owns them; a solver holds only what its method
/// derives from them (matrices, factors, fields, targets).
#[derive(Clone, Copy)]
pub(crate) struct Shared<'a> {
    pub(crate) mesh: &'a Mesh,
    pub(crate) handles: &'a [HandlePoint],
    pub(crate) positions: &'a [Point],
    pub(crate) bones: &'a Bones,
    pub(crate) clock: Clock,
}

/// What a method can do beyond plain steps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Abilities {
    /// Per-triangle stiffness ([`Deformer::set_stiffness`]).
    pub(crate) stiffness: bool,
    /// Bones ([`Deformer::set_bones`]).
    pub(crate) bones: bool,
    /// Turning handles ([`Deformer::step_turning`]).
    pub(crate) turning: bool,
}

impl Abilities {
    /// Stiffness, bones and turning handles (AKAP, ARAP).
    pub(crate) const ALL: Self = Self { stiffness: true, bones: true, turning: true };
    /// Plain steps only (MLS, Cauchy-Green).
    pub(crate) const NONE: Self = Self { stiffness: false, bones: false, turning: false };
}

/// One method's solver behind a [`Deformer`]: the narrow part that differs between methods.
/// The deformer checks every input (handles, velocities, turns, poses, stiffness) and keeps
/// the shared state; a solver is told of each change and makes the steps. Each method
/// implements it beside its type.
pub(crate) trait Solve: fmt::Debug {
    /// What the method can do beyond plain steps.
    fn abilities(&self) -> Abilities;
    /// A new handle set, `handles` (checked), replacing `shared.handles`, in the pose
    /// `shared.positions`; on error nothing changes.
    fn set_handles(&mut self, shared: Shared<'_>, handles: &[HandlePoint]) -> Result<(), DeformError>;
    /// Each triangle's weight on its energy (the painted stiffness raised on bones), or
    /// `None` for 1 everywhere: called only for methods with stiffness (checked values),
    /// with the bones in `shared` those the weights were raised on.
    fn set_weights(&mut self, _shared: Shared<'_>, _weights: Option<&[f64]>) {}
    /// One step with a velocity per handle (checked), and for methods with turning handles
    /// `turns` (one per handle, not all zero), into `next`, the stage timings into
    /// `timings`. Returns whether `next` holds the new pose (`false`: the pose stays). On
    /// error the solver is unchanged.
    fn step(
        &mut self,
        shared: Shared<'_>,
        velocities: &[[f64; 2]],
        turns: Option<&[f64]>,
        next: &mut [Point],
        timings: &mut Timings,
    ) -> Result<bool, DeformError>;
    /// The pose was set to `shared.positions` ([`Deformer::set_positions`]), or, with
    /// `rest`, put back to the rest pose ([`Deformer::reset`]).
    fn pose_set(&mut self, shared: Shared<'_>, rest: bool);
    /// The last step's velocity per vertex.
    fn field(&self) -> &[[f64; 2]];
    /// The last step's field before any smoothing.
    fn soft_field(&self) -> &[[f64; 2]] {
        self.field()
    }
    /// Where the method holds its handles when that is not their points in the pose
    /// (Cauchy-Green: its targets, met in the least-squares sense).
    fn held_at(&self) -> Option<&[Point]> {
        None
    }
    /// The polygon the method deforms the shape through, if it has one.
    fn cage_image(&self) -> Option<&[Point]> {
        None
    }
    /// Saves the state steps change beyond the pose and timings into `checkpoint`, which
    /// the deformer has begun.
    fn save(&self, checkpoint: &mut Checkpoint);
    /// The lengths [`Solve::restore`] needs: each pair the length saved in `checkpoint` and
    /// the solver's own, so that a restore can be refused before anything changes.
    fn saved_lengths(&self, checkpoint: &Checkpoint) -> Vec<(usize, usize)>;
    /// Puts back what [`Solve::save`] saved (the lengths checked).
    fn restore(&mut self, checkpoint: &Checkpoint);
}

/// How the last call of an ARAP step or of [`iterate`](super::Deformer::iterate) ended (see
/// [`super::ArapSolver::report`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct IterationReport {
    /// Iterations run.
    pub iterations: usize,
    /// The largest distance a vertex moved in the last iteration.
    pub last_move: f64,
    /// Whether `last_move` reached the tolerance.
    pub converged: bool,
}

/// The state a deformer's steps change, saved by [`Deformer::save_checkpoint`] and put back by
/// [`Deformer::restore_checkpoint`], so that a step can be undone exactly (the guarded step of
/// [`super::foldover`] does). One type for every method, each filling the buffers it has:
/// every method its positions, field and timings; AKAP its soft field; ARAP its targets,
/// the rotations its next local step starts from and its [`IterationReport`]; Cauchy-Green
/// its targets and deformed cage. What only handles, options and stiffness change (the
/// handle set, matrices, factors, cages) is not in it.
///
/// Keep one and save into it again: saving reuses its buffers, so once they have grown to
/// the deformer's sizes it allocates nothing.
#[derive(Debug, Clone, Default)]
pub struct Checkpoint {
    /// The method that saved it; `None` until something is saved.
    pub(crate) method: Option<Method>,
    pub(crate) positions: Vec<Point>,
    pub(crate) field: Vec<[f64; 2]>,
    pub(crate) soft_field: Vec<[f64; 2]>,
    pub(crate) targets: Vec<Point>,
    pub(crate) rotations: Vec<[f64; 2]>,
    pub(crate) cage_image: Vec<Point>,
    pub(crate) report: IterationReport,
    pub(crate) timings: Timings,
}

impl Checkpoint {
    /// An empty checkpoint, to save into.
    pub fn new() -> Self {
        Self::default()
    }

    /// The method that saved it, if any.
    pub fn method(&self) -> Option<Method> {
        self.method
    }

    /// The vertex positions saved (empty until something is saved).
    pub fn positions(&self) -> &[Point] {
        &self.positions
    }

    /// Starts a save by `method`: every buffer emptied (keeping its room), the report and
    /// timings cleared.
    pub(crate) fn begin(&mut self, method: Method) {
        self.method = Some(method);
        let buffers = [
            &mut self.positions,
            &mut self.field,
            &mut self.soft_field,
            &mut self.targets,
            &mut self.rotations,
            &mut self.cage_image,
        ];
        for buffer in buffers {
            buffer.clear();
        }
        self.report = IterationReport::default();
        self.timings = Timings::default();
    }

    /// Checks that `method` saved this checkpoint with buffers of the given lengths (each
    /// pair: the length saved, the length the deformer has now), so that a restore fits.
    pub(crate) fn check(&self, method: Method, lengths: &[(usize, usize)]) -> Result<(), DeformError> {
        if self.method != Some(method) || lengths.iter().any(|(saved, now)| saved != now) {
            return Err(DeformError::ForeignCheckpoint { method, saved: self.method });
        }
        Ok(())
    }
}

/// `buffer` becomes a copy of `values`, in its own room when that suffices.
pub(crate) fn copy_into<T: Copy>(buffer: &mut Vec<T>, values: &[T]) {
    buffer.clear();
    buffer.extend_from_slice(values);
}

/// Milliseconds spent in each stage of the last step.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Timings {
    /// Assembling the matrices and right-hand sides (AKAP: the Killing matrix and both
    /// systems; ARAP: the local steps and right-hand sides).
    pub assembly: f64,
    /// Numeric factorisations (AKAP: both systems; ARAP: after a change of handles).
    pub factorisation: f64,
    /// The part of `factorisation` spent on AKAP's step 2 system (the Dirichlet re-solve).
    pub dirichlet_factorisation: f64,
    /// Triangular solves.
    pub solve: f64,
    /// Moving the vertices.
    pub integration: f64,
}

/// A clock in milliseconds, for [`Timings`].
pub type Clock = fn() -> f64;

/// The clock deformers start with: milliseconds since first use natively, 0 in wasm (where
/// the bindings pass `performance.now`).
pub(crate) fn default_clock() -> f64 {
    #[cfg(not(target_arch = "wasm32"))]
    {
        static START: std::sync::OnceLock<std::time::Instant> = std::sync::OnceLock::new();
        START.get_or_init(std::time::Instant::now).elapsed().as_secs_f64() * 1e3
    }
    #[cfg(target_arch = "wasm32")]
    {
        0.0
    }
}
