//! Point-to-point Cauchy-Green deformation (Weber, Ben-Chen and Gotsman 2009, "Complex
//! barycentric coordinates with applications to planar shape deformation", Section 5): a
//! holomorphic, hence conformal, map of the inside of a cage, fitted to the handles.
//!
//! The map is the Cauchy integral of the piecewise-linear function with values `f_j` at
//! the cage's vertices ([`coordinates`]), so each vertex `v` of the mesh goes to
//! `sum_j C_j(v) f_j`. The cage values minimise
//!
//! `E(f) = sum_k |f(p_k) - q_k|^2 + smoothness D^3 sum_e sum_(t = 1/4, 3/4) |e|/2 |f''(z_e(t))|^2`
//!
//! (handles at rest points `p_k` with targets `q_k`; the paper's integral of `|f''|^2` over
//! the cage's boundary, sampled at two points of every edge: it diverges at the cage's
//! corners, where `f'` jumps, so it is sampled away from them; `D`, the diagonal of the
//! cage's bounding box, makes the weight dimensionless). The smoothness term vanishes
//! exactly on the values of `a z + b`, and is positive otherwise (`f''` is a rational
//! function with a pole at each corner whose `f'` jumps, so it cannot vanish at all `2n`
//! samples), so with handles at two distinct points or more the normal equations
//! `(R* R + smoothness S) f = R* q` are positive definite: a dense `n x n` Cholesky
//! factorisation per handle set (and smoothness), and a frame is one small solve and one
//! product with the coordinates of every vertex. With one handle (or all at one point) the
//! map is the translation that takes the handles' mean to their targets' mean.
//!
//! Handles are met in the least-squares sense, so a handle's point of the shape may lie
//! short of its target. [`CauchyGreenDeformer::handle_positions`] are the targets, which
//! each step moves by the velocities: steps with no motion change nothing, and the pose is a
//! function of the targets alone (no history).
//!
//! Holes: the map is holomorphic on the whole inside of the cage, holes included, which
//! are mapped as if they were filled (a ring cannot be squeezed on one side without the
//! hole following).

mod cage;
mod coordinates;

use nalgebra::Complex;

pub use coordinates::{coordinates, second_derivative};

use self::coordinates::complex;
use super::error::DeformError;
use super::handles::{self, check_connected, check_pose, check_velocities, diagonal, in_range, HandlePoint};
use super::method::{copy_into, default_clock, Build, Checkpoint, Clock, Deform, Orders, Timings};
use super::metrics::{metrics, Metrics};
use super::options::{CauchyGreenOptions, Method, MethodOptions, CAGE_VERTICES_RANGE, SMOOTHNESS_RANGE};
use crate::geometry::{bounding_box, normalising_exponent, scale_by_power_of_two, Point};
use crate::mesh::Mesh;
use crate::sparse::FactorError;

type C64 = Complex<f64>;
const ZERO: C64 = Complex { re: 0.0, im: 0.0 };

/// The most coordinates (mesh vertices times cage vertices) a deformer keeps: 2^25, 512 MB,
/// a few seconds of set-up in wasm. Beyond, it is refused as out of memory (a coarser mesh
/// or a smaller cage fits).
const MAX_COORDINATES: usize = 1 << 25;

/// The Cauchy-Green deformer of one mesh.
#[derive(Debug, Clone)]
pub struct CauchyGreenDeformer {
    mesh: Mesh,
    /// The mesh's positions times `2^exponent` (largest coordinate in [1, 2)): the
    /// coordinates, the cage and the fit are computed on them (the coordinates are the same
    /// at every scale), so that no length overflows or underflows.
    unit: Vec<Point>,
    exponent: i32,
    options: CauchyGreenOptions,
    cage: Cage,
    handles: Vec<HandlePoint>,
    fit: Fit,
    targets: Vec<Point>,
    cage_image: Vec<Point>,
    positions: Vec<Point>,
    field: Vec<[f64; 2]>,
    timings: Timings,
    clock: Clock,
}

/// What depends on the cage alone.
#[derive(Debug, Clone)]
struct Cage {
    /// In the deformer's unit scale.
    points: Vec<Point>,
    /// In the mesh's scale.
    actual: Vec<Point>,
    /// Given by the caller (not rebuilt when the options change).
    given: bool,
    /// The coordinates of every mesh vertex, a row of one per cage vertex each.
    at_vertices: Vec<C64>,
    /// The smoothness term's matrix `D^3 sum_l w_l d_l* d_l` (row-major, `n x n`), `d_l` the
    /// second-derivative coefficients at sample `l` of weight `w_l`.
    smoothness: Vec<C64>,
}

impl Cage {
    /// The cage `points` around the mesh vertices `unit`, both in the unit scale, and
    /// `2^exponent` that scale.
    fn new(unit: &[Point], points: Vec<Point>, exponent: i32, given: bool) -> Result<Self, DeformError> {
        let n = points.len();
        let entries = unit.len().saturating_mul(n);
        let bytes = entries.saturating_mul(std::mem::size_of::<C64>());
        if entries > MAX_COORDINATES {
            return Err(DeformError::OutOfMemory { bytes });
        }
        let mut at_vertices = Vec::new();
        at_vertices.try_reserve_exact(entries).map_err(|_| DeformError::OutOfMemory { bytes })?;
        at_vertices.resize(entries, ZERO);
        for (row, &v) in at_vertices.chunks_exact_mut(n).zip(unit) {
            coordinates(&points, v, row);
        }
        let (lo, hi) = bounding_box(points.iter().copied()).expect("a cage has points");
        let size = libm::hypot(hi[0] - lo[0], hi[1] - lo[1]);
        let mut smoothness = vec![ZERO; n * n];
        let mut d = vec![ZERO; n];
        for j in 0..n {
            let (a, b) = (points[j], points[(j + 1) % n]);
            let weight = size * size * size * libm::hypot(b[0] - a[0], b[1] - a[1]) / 2.0;
            for t in [0.25, 0.75] {
                second_derivative(&points, [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])], &mut d);
                add_outer_product(&mut smoothness, &d, weight);
            }
        }
        mirror_upper(&mut smoothness, n);
        let actual = points.iter().map(|p| p.map(|x| scale_by_power_of_two(x, -exponent))).collect();
        Ok(Self { points, actual, given, at_vertices, smoothness })
    }

    fn len(&self) -> usize {
        self.points.len()
    }
}

/// How the cage values follow the targets, for one handle set and smoothness.
#[derive(Debug, Clone)]
enum Fit {
    /// No handles, or all at one point (`rest`, their mean, in the mesh's scale): a
    /// translation.
    Translation { rest: Point },
    /// The handles' coordinates (`m x n`) and the Cholesky factor `L` (lower, `n x n`) of
    /// the normal equations' matrix.
    Solve { rows: Vec<C64>, factor: Vec<C64> },
}

impl Fit {
    /// The fit for handles at `rest` (in the unit scale, `2^exponent` the mesh's).
    fn new(cage: &Cage, rest: &[Point], exponent: i32, smoothness: f64) -> Result<Self, DeformError> {
        if handles::distinct_points(rest, 1e-12 * diagonal(&cage.points)) < 2 {
            let mean = mean(rest).map_or([0.0; 2], |p| p.map(|x| scale_by_power_of_two(x, -exponent)));
            return Ok(Self::Translation { rest: mean });
        }
        let n = cage.len();
        let mut rows = vec![ZERO; rest.len() * n];
        for (row, &p) in rows.chunks_exact_mut(n).zip(rest) {
            coordinates(&cage.points, p, row);
        }
        let mut matrix: Vec<C64> = cage.smoothness.iter().map(|s| s * smoothness).collect();
        for row in rows.chunks_exact(n) {
            add_outer_product(&mut matrix, row, 1.0);
        }
        mirror_upper(&mut matrix, n);
        let factor = cholesky(matrix, n).map_err(DeformError::Factor)?;
        Ok(Self::Solve { rows, factor })
    }

    /// The cage values for the targets.
    fn cage_values(&self, cage: &Cage, targets: &[Point]) -> Vec<C64> {
        match *self {
            Self::Translation { rest } => {
                let shift = mean(targets).map_or(ZERO, |q| complex(q) - complex(rest));
                cage.actual.iter().map(|&z| complex(z) + shift).collect()
            }
            Self::Solve { ref rows, ref factor } => {
                let n = cage.len();
                let mut f = vec![ZERO; n];
                for (row, &q) in rows.chunks_exact(n).zip(targets) {
                    for (fj, r) in f.iter_mut().zip(row) {
                        *fj += r.conj() * complex(q);
                    }
                }
                solve(factor, n, &mut f);
                f
            }
        }
    }
}

/// The mean of `points`, if there are any.
fn mean(points: &[Point]) -> Option<Point> {
    let sum = points.iter().fold([0.0; 2], |s, p| [s[0] + p[0], s[1] + p[1]]);
    (!points.is_empty()).then(|| [sum[0] / points.len() as f64, sum[1] / points.len() as f64])
}

/// Adds `weight conj(d) d^T` to the upper triangle of the Hermitian `n x n` `matrix` (the
/// lower triangle is [`mirror_upper`]'s to fill: half the work).
fn add_outer_product(matrix: &mut [C64], d: &[C64], weight: f64) {
    let n = d.len();
    for (r, dr) in d.iter().enumerate() {
        let left = dr.conj() * weight;
        for (entry, dc) in matrix[r * n + r..(r + 1) * n].iter_mut().zip(&d[r..]) {
            *entry += left * dc;
        }
    }
}

/// Fills the lower triangle of a Hermitian matrix from its upper one.
fn mirror_upper(matrix: &mut [C64], n: usize) {
    for r in 0..n {
        for c in 0..r {
            matrix[r * n + c] = matrix[c * n + r].conj();
        }
    }
}

/// `L` with `L L* = matrix` (Hermitian positive definite, row-major `n x n`), in place: the
/// lower triangle is `L`'s.
fn cholesky(mut m: Vec<C64>, n: usize) -> Result<Vec<C64>, FactorError> {
    for j in 0..n {
        let pivot = m[j * n + j].re - m[j * n..j * n + j].iter().map(|l| l.norm_sqr()).sum::<f64>();
        if !(pivot > 0.0 && pivot.is_finite()) {
            return Err(FactorError::NotPositiveDefinite { column: j, pivot });
        }
        let diagonal = pivot.sqrt();
        m[j * n + j] = Complex::new(diagonal, 0.0);
        for i in j + 1..n {
            let mut s = m[i * n + j];
            for k in 0..j {
                s -= m[i * n + k] * m[j * n + k].conj();
            }
            m[i * n + j] = s / diagonal;
        }
    }
    Ok(m)
}

/// Solves `L L* x = b` in place, `L` from [`cholesky`].
fn solve(l: &[C64], n: usize, b: &mut [C64]) {
    for i in 0..n {
        let s: C64 = l[i * n..i * n + i].iter().zip(&b[..i]).map(|(l, y)| l * y).sum();
        b[i] = (b[i] - s) / l[i * n + i].re;
    }
    for i in (0..n).rev() {
        let s: C64 = (i + 1..n).map(|k| l[k * n + i].conj() * b[k]).sum();
        b[i] = (b[i] - s) / l[i * n + i].re;
    }
}

impl CauchyGreenDeformer {
    /// A deformer for a connected mesh, with an automatic cage of `options.cage` vertices.
    pub fn new(mesh: Mesh, options: CauchyGreenOptions) -> Result<Self, DeformError> {
        check_options(&options)?;
        check_connected(&mesh)?;
        let exponent = normalising_exponent(mesh.positions().iter().copied());
        let unit: Vec<Point> = mesh.positions().iter().map(|p| p.map(|x| scale_by_power_of_two(x, exponent))).collect();
        let cage = Cage::new(&unit, cage::automatic(&mesh, &unit, options.cage)?, exponent, false)?;
        let positions = mesh.positions().to_vec();
        let n = mesh.vertex_count();
        Ok(Self {
            cage_image: cage.actual.clone(),
            mesh,
            unit,
            exponent,
            options,
            cage,
            handles: Vec::new(),
            fit: Fit::Translation { rest: [0.0; 2] },
            targets: Vec::new(),
            positions,
            field: vec![[0.0; 2]; n],
            timings: Timings::default(),
            clock: default_clock,
        })
    }

    /// The settings.
    pub fn options(&self) -> CauchyGreenOptions {
        self.options
    }

    /// Changes the settings: a new cage vertex count builds a new automatic cage (unless a
    /// cage was given), a new smoothness refits the handles. The next step uses them.
    pub fn set_options(&mut self, options: CauchyGreenOptions) -> Result<(), DeformError> {
        check_options(&options)?;
        let cage = match options.cage != self.options.cage && !self.cage.given {
            true => Some(self.automatic_cage(options.cage)?),
            false => None,
        };
        let fit = self.fit_for(cage.as_ref().unwrap_or(&self.cage), &self.handles, options.smoothness)?;
        if let Some(cage) = cage {
            self.cage_image = cage.actual.clone();
            self.cage = cage;
        }
        self.options = options;
        self.fit = fit;
        Ok(())
    }

    /// The cage, counter-clockwise, in the rest pose.
    pub fn cage(&self) -> &[Point] {
        &self.cage.actual
    }

    fn automatic_cage(&self, vertices: usize) -> Result<Cage, DeformError> {
        Cage::new(&self.unit, cage::automatic(&self.mesh, &self.unit, vertices)?, self.exponent, false)
    }

    /// Where the last step took the cage's vertices (the cage values; the rest cage after
    /// a reset). Drawn with straight edges, this is the polygon whose Cauchy integral the
    /// map is.
    pub fn cage_image(&self) -> &[Point] {
        &self.cage_image
    }

    /// Uses this cage (a simple polygon, either orientation, with the shape strictly
    /// inside), or an automatic one again with `None`. Refused with
    /// [`DeformError::InvalidCage`], changing nothing, when the cage cannot be used. The
    /// pose stays until the next step.
    pub fn set_cage(&mut self, cage: Option<&[Point]>) -> Result<(), DeformError> {
        let cage = match cage {
            Some(points) => {
                let scaled: Vec<Point> =
                    points.iter().map(|p| p.map(|x| scale_by_power_of_two(x, self.exponent))).collect();
                Cage::new(&self.unit, cage::checked(&self.mesh, &self.unit, &scaled)?, self.exponent, true)?
            }
            None => self.automatic_cage(self.options.cage)?,
        };
        self.fit = self.fit_for(&cage, &self.handles, self.options.smoothness)?;
        self.cage_image = cage.actual.clone();
        self.cage = cage;
        Ok(())
    }

    fn fit_for(&self, cage: &Cage, handles: &[HandlePoint], smoothness: f64) -> Result<Fit, DeformError> {
        let rest: Vec<Point> = handles.iter().map(|h| h.position(&self.unit)).collect();
        Fit::new(cage, &rest, self.exponent, smoothness)
    }

    /// One handle on each of these vertices, replacing any handles.
    pub fn set_handle_vertices(&mut self, vertices: &[u32]) -> Result<(), DeformError> {
        let handles = handles::at_vertices(&self.mesh, vertices)?;
        self.install(handles)
    }

    /// Handles at points in triangles, replacing any handles.
    pub fn set_handle_points(&mut self, triangles: &[u32], barycentric: &[[f64; 3]]) -> Result<(), DeformError> {
        let handles = handles::in_triangles(&self.mesh, triangles, barycentric)?;
        self.install(handles)
    }

    /// Fits the new handle set. A handle at the same place as one before keeps its target;
    /// the others start where their point is in the current pose.
    fn install(&mut self, handles: Vec<HandlePoint>) -> Result<(), DeformError> {
        let fit = self.fit_for(&self.cage, &handles, self.options.smoothness)?;
        self.targets = handles
            .iter()
            .map(|h| match self.handles.iter().position(|old| old == h) {
                Some(k) => self.targets[k],
                None => h.position(&self.positions),
            })
            .collect();
        self.handles = handles;
        self.fit = fit;
        Ok(())
    }

    /// The handles' targets: where each step has asked them to be (their points in the pose
    /// when they were set, moved by every step's velocities since). The shape's point under
    /// a handle lies near its target, not on it: handles are fitted in the least-squares
    /// sense.
    pub fn handle_positions(&self) -> Vec<Point> {
        self.targets.clone()
    }

    /// One step: each handle's target moves by its velocity, and every vertex goes where the
    /// map fitted to the targets takes its rest position. With no handles nothing moves.
    /// Refused, changing nothing, for bad velocities and for a result beyond the coordinate
    /// limit.
    pub fn step(&mut self, velocities: &[[f64; 2]]) -> Result<(), DeformError> {
        check_velocities(velocities, self.handles.len())?;
        if self.handles.is_empty() {
            self.field.fill([0.0; 2]);
            return Ok(());
        }
        let start = (self.clock)();
        let targets: Vec<Point> =
            self.targets.iter().zip(velocities).map(|(p, v)| [p[0] + v[0], p[1] + v[1]]).collect();
        let f = self.fit.cage_values(&self.cage, &targets);
        let solved = (self.clock)();
        let n = self.cage.len();
        let next: Vec<Point> = self
            .cage
            .at_vertices
            .chunks_exact(n)
            .map(|row| {
                let z: C64 = row.iter().zip(&f).map(|(c, f)| c * f).sum();
                [z.re, z.im]
            })
            .collect();
        let image: Vec<Point> = f.iter().map(|z| [z.re, z.im]).collect();
        // (The cage lies outside the shape: its image may go beyond the limits where the
        // shape's does not.)
        if !in_range(&next) || next.iter().flatten().any(|x| x.is_nan()) {
            return Err(DeformError::NonFiniteResult);
        }
        for ((d, p), q) in self.field.iter_mut().zip(&self.positions).zip(&next) {
            *d = [q[0] - p[0], q[1] - p[1]];
        }
        self.positions = next;
        self.cage_image = image;
        self.targets = targets;
        self.timings = Timings { solve: solved - start, integration: (self.clock)() - solved, ..Timings::default() };
        Ok(())
    }

    /// Current vertex positions.
    pub fn positions(&self) -> &[Point] {
        &self.positions
    }

    /// Puts the mesh into a given pose; handles stay, their targets become their points in
    /// this pose. (The next step maps the rest mesh again, for those targets moved.)
    pub fn set_positions(&mut self, positions: &[Point]) -> Result<(), DeformError> {
        check_pose(positions, self.positions.len())?;
        self.positions.copy_from_slice(positions);
        self.targets = self.handles.iter().map(|h| h.position(positions)).collect();
        self.field.fill([0.0; 2]);
        Ok(())
    }

    /// Back to the rest pose; handles stay, their targets at their rest points.
    pub fn reset(&mut self) {
        self.positions.copy_from_slice(self.mesh.positions());
        self.targets = self.handles.iter().map(|h| h.position(self.mesh.positions())).collect();
        self.cage_image.clone_from(&self.cage.actual);
        self.field.fill([0.0; 2]);
    }
}

fn check_options(options: &CauchyGreenOptions) -> Result<(), DeformError> {
    if !CAGE_VERTICES_RANGE.contains(&options.cage) {
        return Err(DeformError::InvalidOption {
            name: "cage",
            value: options.cage as f64,
            expected: "a whole number from 8 to 1000",
        });
    }
    if !SMOOTHNESS_RANGE.contains(&options.smoothness) {
        return Err(DeformError::InvalidOption {
            name: "smoothness",
            value: options.smoothness,
            expected: "a number from 1e-8 to 1e4",
        });
    }
    Ok(())
}

impl Deform for CauchyGreenDeformer {
    fn method_options(&self) -> MethodOptions {
        MethodOptions::CauchyGreen(self.options)
    }
    fn set_method_options(&mut self, options: MethodOptions) -> Result<(), DeformError> {
        match options {
            MethodOptions::CauchyGreen(options) => self.set_options(options),
            other => Err(DeformError::WrongMethod { current: Method::CauchyGreen, given: other.method() }),
        }
    }
    fn set_clock(&mut self, clock: Clock) {
        self.clock = clock;
    }
    fn mesh(&self) -> &Mesh {
        &self.mesh
    }
    fn set_handle_vertices(&mut self, vertices: &[u32]) -> Result<(), DeformError> {
        CauchyGreenDeformer::set_handle_vertices(self, vertices)
    }
    fn set_handle_points(&mut self, triangles: &[u32], barycentric: &[[f64; 3]]) -> Result<(), DeformError> {
        CauchyGreenDeformer::set_handle_points(self, triangles, barycentric)
    }
    fn handle_count(&self) -> usize {
        self.handles.len()
    }
    fn handle_points(&self) -> (Vec<u32>, Vec<[f64; 3]>) {
        handles::as_points(self.handles.iter())
    }
    fn handle_positions(&self) -> Vec<Point> {
        CauchyGreenDeformer::handle_positions(self)
    }
    fn step(&mut self, velocities: &[[f64; 2]]) -> Result<(), DeformError> {
        CauchyGreenDeformer::step(self, velocities)
    }
    fn positions(&self) -> &[Point] {
        &self.positions
    }
    fn set_positions(&mut self, positions: &[Point]) -> Result<(), DeformError> {
        CauchyGreenDeformer::set_positions(self, positions)
    }
    fn field(&self) -> &[[f64; 2]] {
        &self.field
    }
    fn cage_image(&self) -> Option<&[Point]> {
        Some(&self.cage_image)
    }
    /// Positions, targets (apart from the positions: [`CauchyGreenDeformer::set_positions`]
    /// would reset them), the deformed cage, field and timings.
    fn save_checkpoint(&self, checkpoint: &mut Checkpoint) {
        checkpoint.begin(Method::CauchyGreen);
        copy_into(&mut checkpoint.positions, &self.positions);
        copy_into(&mut checkpoint.targets, &self.targets);
        copy_into(&mut checkpoint.cage_image, &self.cage_image);
        copy_into(&mut checkpoint.field, &self.field);
        checkpoint.timings = self.timings;
    }
    fn restore_checkpoint(&mut self, checkpoint: &Checkpoint) -> Result<(), DeformError> {
        let n = self.positions.len();
        checkpoint.check(
            Method::CauchyGreen,
            &[
                (checkpoint.positions.len(), n),
                (checkpoint.field.len(), n),
                (checkpoint.targets.len(), self.targets.len()),
                (checkpoint.cage_image.len(), self.cage_image.len()),
            ],
        )?;
        self.positions.copy_from_slice(&checkpoint.positions);
        self.targets.copy_from_slice(&checkpoint.targets);
        self.cage_image.copy_from_slice(&checkpoint.cage_image);
        self.field.copy_from_slice(&checkpoint.field);
        self.timings = checkpoint.timings;
        Ok(())
    }
    fn metrics(&self) -> Metrics {
        metrics(self.mesh.positions(), &self.positions, self.mesh.triangles())
    }
    fn timings(&self) -> Timings {
        self.timings
    }
    fn reset(&mut self) {
        CauchyGreenDeformer::reset(self);
    }
}

impl Build for CauchyGreenOptions {
    fn check(&self) -> Result<(), DeformError> {
        check_options(self)
    }
    /// Cauchy-Green solves dense systems only.
    fn orders(&self, _mesh: &Mesh) -> Orders {
        Orders { systems: Vec::new() }
    }
    fn build_with_orders(self, mesh: Mesh, orders: &Orders) -> Result<Box<dyn Deform>, DeformError> {
        orders.check(&[])?;
        Ok(Box::new(CauchyGreenDeformer::new(mesh, self)?))
    }
}
