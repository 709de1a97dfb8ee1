//! One interface for every deformation method, so that callers (the JavaScript bindings,
//! session replay, the comparison) can switch between them: the [`Deform`] trait, which
//! every deformer implements beside its type, [`MethodOptions::build`], which makes the
//! deformer a method's options name, the [`Orders`] its set-up can compute apart, and the
//! stage [`Timings`] of a step.

use std::fmt;

use super::error::DeformError;
use super::metrics::Metrics;
use super::options::{methods, ArapOptions, CauchyGreenOptions, DeformerOptions, Method, MethodOptions, MlsOptions};
use crate::geometry::Point;
use crate::mesh::Mesh;

/// How a method's options make its deformer: implemented for each options type beside its
/// deformer, so that [`MethodOptions`] reaches every method through the list of methods
/// alone.
pub(crate) trait Build {
    /// Checks the settings' ranges, as building a deformer with them would.
    fn check(&self) -> Result<(), DeformError>;
    /// The fill-reducing orders the method's deformer needs for `mesh`.
    fn orders(&self, mesh: &Mesh) -> Orders;
    /// The method's deformer with orders from [`Build::orders`].
    fn build_with_orders(self, mesh: Mesh, orders: &Orders) -> Result<Box<dyn Deform>, DeformError>;
}

/// Writes [`MethodOptions`]' dispatch to [`Build`] from the list of methods.
macro_rules! method_dispatch {
    ($($(#[$doc:meta])* $variant:ident($name:literal, $options:ident),)*) => {
        impl MethodOptions {
            /// Checks the settings' ranges, as building a deformer with them would.
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

            /// [`Self::build`] with orders from [`Self::orders`] (for this method and mesh).
            pub fn build_with_orders(self, mesh: Mesh, orders: &Orders) -> Result<Box<dyn Deform>, DeformError> {
                match self {
                    $(Self::$variant(options) => Build::build_with_orders(options, mesh, orders),)*
                }
            }
        }

        // Every options type of the list makes a deformer.
        const _: fn() = || {
            fn builds<T: Build>() {}
            $(builds::<$options>();)*
        };
    };
}

methods!(method_dispatch);

impl MethodOptions {
    /// A deformer of this method for a connected mesh.
    pub fn build(self, mesh: Mesh) -> Result<Box<dyn Deform>, DeformError> {
        let orders = self.orders(&mesh);
        self.build_with_orders(mesh, &orders)
    }
}

impl MethodOptions {
    /// Puts these options into effect on `deformer`, as the bindings' `setOptions`, the
    /// widget's method list and session replay do: options of its method change its
    /// settings; another method's replace it with a deformer of that method on the same
    /// mesh (its set-up runs), with the pose, the handles and the stiffness (where the new
    /// method has it) carried over and the clock reset to the default. On error `deformer`
    /// is unchanged.
    pub fn apply(self, deformer: &mut Box<dyn Deform>) -> Result<(), DeformError> {
        if self.method() == deformer.method_options().method() {
            return deformer.set_method_options(self);
        }
        let mut next = self.build(deformer.mesh().clone())?;
        next.set_positions(deformer.positions())?;
        // Stiffness carries over to the methods that have it.
        if let Some(stiffness) = deformer.stiffness() {
            match next.set_stiffness(Some(stiffness)) {
                Ok(()) | Err(DeformError::Unsupported { .. }) => {}
                Err(other) => return Err(other),
            }
        }
        // So do bones, laid in the same pose.
        let (triangles, barycentric) = deformer.bone_points();
        match next.set_bones(&triangles, &barycentric) {
            Ok(()) | Err(DeformError::Unsupported { .. }) => {}
            Err(other) => return Err(other),
        }
        let (triangles, barycentric) = deformer.handle_points();
        next.set_handle_points(&triangles, &barycentric)?;
        *deformer = next;
        Ok(())
    }
}

/// The fill-reducing vertex orders a deformer's linear systems are factored in: the bulk
/// of its set-up (ordering the mesh's vertex graph). [`MethodOptions::orders`] computes them
/// for a mesh, possibly elsewhere (a worker), and [`MethodOptions::build_with_orders`] makes
/// the deformer with them, which then only analyses the systems and allocates.
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

/// What every deformer offers. Handles are vertices or points in triangles; each
/// [`Deform::step`] takes one velocity per handle, the motion asked of the handle in this
/// step (its target is its current position plus the velocity). Every method refuses bad
/// input with a [`DeformError`] and is then unchanged.
pub trait Deform: fmt::Debug {
    /// The method and its current settings.
    fn method_options(&self) -> MethodOptions;
    /// Changes the settings; refuses options of another method
    /// ([`DeformError::WrongMethod`]).
    fn set_method_options(&mut self, options: MethodOptions) -> Result<(), DeformError>;
    /// Sets the clock used for the timings (milliseconds).
    fn set_clock(&mut self, clock: Clock);
    /// The mesh in its rest pose.
    fn mesh(&self) -> &Mesh;
    /// One handle on each of these vertices, replacing any handles.
    fn set_handle_vertices(&mut self, vertices: &[u32]) -> Result<(), DeformError>;
    /// Handles at points in triangles (triangle index, barycentric coordinates),
    /// replacing any handles.
    fn set_handle_points(&mut self, triangles: &[u32], barycentric: &[[f64; 3]]) -> Result<(), DeformError>;
    /// Number of handles.
    fn handle_count(&self) -> usize;
    /// Where the handles are on the mesh, as [`Deform::set_handle_points`] takes them: a
    /// triangle and barycentric coordinates each (a handle set on a vertex is weight 1 at
    /// that corner of a triangle using it).
    fn handle_points(&self) -> (Vec<u32>, Vec<[f64; 3]>);
    /// Current positions of the handle points (Cauchy-Green: the handles' targets, which
    /// the shape's points under them meet in the least-squares sense).
    fn handle_positions(&self) -> Vec<Point>;
    /// Where the shape is under each handle in the current pose (the handles' points of the
    /// mesh placed on the current positions): [`Deform::handle_positions`] for every
    /// method but Cauchy-Green, whose handle positions are its targets.
    fn shape_under_handles(&self) -> Vec<Point> {
        let (triangles, weights) = self.handle_points();
        let (corners, positions) = (self.mesh().triangles(), self.positions());
        triangles
            .iter()
            .zip(&weights)
            .map(|(&t, w)| {
                let c = corners[t as usize].map(|v| positions[v as usize]);
                [0, 1].map(|i| w[0] * c[0][i] + w[1] * c[1][i] + w[2] * c[2][i])
            })
            .collect()
    }
    /// One step with a velocity per handle, in handle order.
    fn step(&mut self, velocities: &[[f64; 2]]) -> Result<(), DeformError>;
    /// One step in which handles also turn: `turns[i]` radians counter-clockwise about
    /// handle `i`'s point, its neighbourhood following that rigid motion (AKAP: its Killing
    /// field; ARAP: held in the turned frame for the step; see the README). All turns zero is exactly [`Deform::step`]; methods
    /// without turning handles refuse other turns ([`DeformError::Unsupported`]).
    fn step_turning(&mut self, velocities: &[[f64; 2]], turns: &[f64]) -> Result<(), DeformError> {
        crate::deform::handles::check_turns(turns, self.handle_count())?;
        if turns.iter().any(|&w| w != 0.0) {
            return Err(DeformError::Unsupported { method: self.method_options().method(), what: "turning handles" });
        }
        self.step(velocities)
    }
    /// Current vertex positions.
    fn positions(&self) -> &[Point];
    /// Puts the mesh into a given pose; handles stay (ARAP: their targets move with them).
    fn set_positions(&mut self, positions: &[Point]) -> Result<(), DeformError>;
    /// The last step's velocity per vertex: AKAP's field after the Dirichlet step, ARAP's
    /// displacement.
    fn field(&self) -> &[[f64; 2]];
    /// The last step's field before any smoothing: AKAP's soft-constraint field, ARAP's
    /// displacement.
    fn soft_field(&self) -> &[[f64; 2]] {
        self.field()
    }
    /// Sets each triangle's stiffness, the factor on its energy (stiff regions bend less;
    /// one value per triangle in [`super::STIFFNESS_RANGE`], `None` for 1 everywhere):
    /// AKAP weighs its Killing energy, ARAP its element energy. Methods without a
    /// per-triangle energy (MLS, Cauchy-Green) refuse it ([`DeformError::Unsupported`]).
    fn set_stiffness(&mut self, stiffness: Option<&[f64]>) -> Result<(), DeformError> {
        match stiffness {
            None => Ok(()),
            Some(_) => Err(DeformError::Unsupported { method: self.method_options().method(), what: "stiffness" }),
        }
    }
    /// Each triangle's stiffness, if set.
    fn stiffness(&self) -> Option<&[f64]> {
        None
    }
    /// Whether the method takes per-triangle stiffness ([`Deform::set_stiffness`]).
    fn has_stiffness(&self) -> bool {
        false
    }
    /// Sets the bones (see [`super::bones`]): two mesh points per bone, its ends, given as
    /// [`Deform::set_handle_points`] takes points, replacing any bones; none removes them.
    /// Each bone covers the triangles its segment meets in the current pose, which from
    /// then on move as one rigid body. Methods without bones (MLS, Cauchy-Green) refuse any
    /// ([`DeformError::Unsupported`]). Refused, changing nothing, for a bone that cannot be
    /// used ([`DeformError::InvalidBone`]).
    fn set_bones(&mut self, triangles: &[u32], barycentric: &[[f64; 3]]) -> Result<(), DeformError> {
        if triangles.is_empty() && barycentric.is_empty() {
            return Ok(());
        }
        Err(DeformError::Unsupported { method: self.method_options().method(), what: "bones" })
    }
    /// The bones' ends, two per bone, as [`Deform::set_bones`] took them.
    fn bone_points(&self) -> (Vec<u32>, Vec<[f64; 3]>) {
        (Vec::new(), Vec::new())
    }
    /// Whether the method has bones ([`Deform::set_bones`]).
    fn has_bones(&self) -> bool {
        false
    }
    /// The polygon the method deforms the shape through, where it has one, as the last step
    /// left it: Cauchy-Green's cage (the cage values; its rest cage after a reset). `None`
    /// for methods without one.
    fn cage_image(&self) -> Option<&[Point]> {
        None
    }
    /// Saves the state steps change (see [`Checkpoint`]) into `checkpoint`, replacing what
    /// it held and reusing its buffers.
    fn save_checkpoint(&self, checkpoint: &mut Checkpoint);
    /// Puts back the state saved in `checkpoint`: the next step then gives exactly the bits
    /// it would have given had nothing happened since the save (for the handles, options
    /// and stiffness in place; changing those is not undone). Refused with
    /// [`DeformError::ForeignCheckpoint`], changing nothing, for a checkpoint saved by a
    /// deformer of another method or of other sizes (vertices, handles, triangles).
    fn restore_checkpoint(&mut self, checkpoint: &Checkpoint) -> Result<(), DeformError>;
    /// A new checkpoint of the current state ([`Deform::save_checkpoint`] into a fresh one).
    fn checkpoint(&self) -> Checkpoint {
        let mut checkpoint = Checkpoint::new();
        self.save_checkpoint(&mut checkpoint);
        checkpoint
    }
    /// Distortion of the current pose against the rest pose.
    fn metrics(&self) -> Metrics;
    /// Stage timings of the last step.
    fn timings(&self) -> Timings;
    /// Back to the rest pose; handles stay.
    fn reset(&mut self);
}

/// How the last call of ARAP's [`step`](super::ArapDeformer::step) or
/// [`iterate`](super::ArapDeformer::iterate) ended.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct IterationReport {
    /// Iterations run.
    pub iterations: usize,
    /// The largest distance a vertex moved in the last iteration.
    pub last_move: f64,
    /// Whether `last_move` reached the tolerance.
    pub converged: bool,
}

/// The state a deformer's steps change, saved by [`Deform::save_checkpoint`] and put back by
/// [`Deform::restore_checkpoint`], so that a step can be undone exactly (the guarded step of
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
