//! One interface for every deformation method, so that callers (the JavaScript bindings,
//! session replay, the comparison) can switch between them: the [`Deform`] trait, which
//! both [`Deformer`] (AKAP) and [`ArapDeformer`] implement, and [`MethodOptions`], which
//! names a method with its settings and builds a boxed deformer.

use std::fmt;

use super::arap::{ArapDeformer, ArapOptions};
use super::deformer::{Clock, Deformer, DeformerOptions, Timings};
use super::error::DeformError;
use super::metrics::Metrics;
use crate::geometry::Point;
use crate::mesh::Mesh;

/// The deformation methods.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// As-Killing-As-Possible vector fields (the paper).
    Akap,
    /// As-rigid-as-possible local/global iterations.
    Arap,
}

impl Method {
    /// The name the JavaScript API and sessions use: `"akap"` or `"arap"`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Akap => "akap",
            Self::Arap => "arap",
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A method with its settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MethodOptions {
    /// AKAP with these options.
    Akap(DeformerOptions),
    /// ARAP with these options.
    Arap(ArapOptions),
}

impl Default for MethodOptions {
    fn default() -> Self {
        Self::Akap(DeformerOptions::default())
    }
}

impl MethodOptions {
    /// Which method.
    pub fn method(&self) -> Method {
        match self {
            Self::Akap(_) => Method::Akap,
            Self::Arap(_) => Method::Arap,
        }
    }

    /// Checks the settings' ranges, as building a deformer with them would.
    pub fn check(&self) -> Result<(), DeformError> {
        match self {
            Self::Akap(options) => super::deformer::check_options(options),
            Self::Arap(options) => super::arap::check_options(options),
        }
    }

    /// A deformer of this method for a connected mesh.
    pub fn build(self, mesh: Mesh) -> Result<Box<dyn Deform>, DeformError> {
        let orders = self.orders(&mesh);
        self.build_with_orders(mesh, &orders)
    }

    /// The fill-reducing orders this method's deformer needs for `mesh` (see [`Orders`]).
    pub fn orders(&self, mesh: &Mesh) -> Orders {
        match self {
            Self::Akap(_) => Deformer::orders(mesh),
            Self::Arap(_) => ArapDeformer::orders(mesh),
        }
    }

    /// [`Self::build`] with orders from [`Self::orders`] (for this method and mesh).
    pub fn build_with_orders(self, mesh: Mesh, orders: &Orders) -> Result<Box<dyn Deform>, DeformError> {
        Ok(match self {
            Self::Akap(options) => Box::new(Deformer::with_orders(mesh, options, orders)?),
            Self::Arap(options) => Box::new(ArapDeformer::with_orders(mesh, options, orders)?),
        })
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
    /// Current positions of the handle points.
    fn handle_positions(&self) -> Vec<Point>;
    /// One step with a velocity per handle, in handle order.
    fn step(&mut self, velocities: &[[f64; 2]]) -> Result<(), DeformError>;
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
    /// Distortion of the current pose against the rest pose.
    fn metrics(&self) -> Metrics;
    /// Stage timings of the last step.
    fn timings(&self) -> Timings;
    /// Back to the rest pose; handles stay.
    fn reset(&mut self);
}

impl Deform for Deformer {
    fn method_options(&self) -> MethodOptions {
        MethodOptions::Akap(self.options())
    }
    fn set_method_options(&mut self, options: MethodOptions) -> Result<(), DeformError> {
        match options {
            MethodOptions::Akap(options) => self.set_options(options),
            other => Err(DeformError::WrongMethod { current: Method::Akap, given: other.method() }),
        }
    }
    fn set_clock(&mut self, clock: Clock) {
        Deformer::set_clock(self, clock);
    }
    fn mesh(&self) -> &Mesh {
        Deformer::mesh(self)
    }
    fn set_handle_vertices(&mut self, vertices: &[u32]) -> Result<(), DeformError> {
        Deformer::set_handle_vertices(self, vertices)
    }
    fn set_handle_points(&mut self, triangles: &[u32], barycentric: &[[f64; 3]]) -> Result<(), DeformError> {
        Deformer::set_handle_points(self, triangles, barycentric)
    }
    fn handle_count(&self) -> usize {
        Deformer::handle_count(self)
    }
    fn handle_positions(&self) -> Vec<Point> {
        Deformer::handle_positions(self)
    }
    fn step(&mut self, velocities: &[[f64; 2]]) -> Result<(), DeformError> {
        Deformer::step(self, velocities)
    }
    fn positions(&self) -> &[Point] {
        Deformer::positions(self)
    }
    fn set_positions(&mut self, positions: &[Point]) -> Result<(), DeformError> {
        Deformer::set_positions(self, positions)
    }
    fn field(&self) -> &[[f64; 2]] {
        Deformer::field(self)
    }
    fn soft_field(&self) -> &[[f64; 2]] {
        Deformer::soft_field(self)
    }
    fn metrics(&self) -> Metrics {
        Deformer::metrics(self)
    }
    fn timings(&self) -> Timings {
        Deformer::timings(self)
    }
    fn reset(&mut self) {
        Deformer::reset(self);
    }
}

impl Deform for ArapDeformer {
    fn method_options(&self) -> MethodOptions {
        MethodOptions::Arap(self.options())
    }
    fn set_method_options(&mut self, options: MethodOptions) -> Result<(), DeformError> {
        match options {
            MethodOptions::Arap(options) => self.set_options(options),
            other => Err(DeformError::WrongMethod { current: Method::Arap, given: other.method() }),
        }
    }
    fn set_clock(&mut self, clock: Clock) {
        ArapDeformer::set_clock(self, clock);
    }
    fn mesh(&self) -> &Mesh {
        ArapDeformer::mesh(self)
    }
    fn set_handle_vertices(&mut self, vertices: &[u32]) -> Result<(), DeformError> {
        ArapDeformer::set_handle_vertices(self, vertices)
    }
    fn set_handle_points(&mut self, triangles: &[u32], barycentric: &[[f64; 3]]) -> Result<(), DeformError> {
        ArapDeformer::set_handle_points(self, triangles, barycentric)
    }
    fn handle_count(&self) -> usize {
        ArapDeformer::handle_count(self)
    }
    fn handle_positions(&self) -> Vec<Point> {
        ArapDeformer::handle_positions(self)
    }
    fn step(&mut self, velocities: &[[f64; 2]]) -> Result<(), DeformError> {
        ArapDeformer::step(self, velocities)
    }
    fn positions(&self) -> &[Point] {
        ArapDeformer::positions(self)
    }
    fn set_positions(&mut self, positions: &[Point]) -> Result<(), DeformError> {
        ArapDeformer::set_positions(self, positions)
    }
    fn field(&self) -> &[[f64; 2]] {
        ArapDeformer::field(self)
    }
    fn metrics(&self) -> Metrics {
        ArapDeformer::metrics(self)
    }
    fn timings(&self) -> Timings {
        ArapDeformer::timings(self)
    }
    fn reset(&mut self) {
        ArapDeformer::reset(self);
    }
}
