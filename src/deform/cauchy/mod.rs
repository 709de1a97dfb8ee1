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
//! short of its target. The deformer's `handle_positions` are the targets, which
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
use super::handles::{self, diagonal, in_range, HandlePoint};
use super::method::{copy_into, Abilities, Build, Checkpoint, Orders, Shared, Solve, Timings};
use super::options::{CauchyGreenOptions, CAGE_VERTICES_RANGE, SMOOTHNESS_RANGE};
use super::puppet::Joins;
use crate::geometry::{bounding_box, normalising_exponent, scale_by_power_of_two, Point};
use crate::mesh::Mesh;
use crate::sparse::FactorError;

type C64 = Complex<f64>;
const ZERO: C64 = Complex { re: 0.0, im: 0.0 };

/// The most coordinates (mesh vertices times cage vertices) a deformer keeps: 2^25, 512 MB,
/// a few seconds of set-up in wasm. Beyond, it is refused as out of memory (a coarser mesh
/// or a smaller cage fits).
const MAX_COORDINATES: usize = 1 << 25;

/// The Cauchy-Green solver of one mesh (the mesh, handles and pose are its
/// [`Deformer`](super::Deformer)'s).
#[derive(Debug, Clone)]
pub struct CauchyGreenSolver {
    /// The mesh's positions times `2^exponent` (largest coordinate in [1, 2)): the
    /// coordinates, the cage and the fit are computed on them (the coordinates are the same
    /// at every scale), so that no length overflows or underflows.
    unit: Vec<Point>,
    exponent: i32,
    options: CauchyGreenOptions,
    cage: Cage,
    fit: Fit,
    targets: Vec<Point>,
    cage_image: Vec<Point>,
    field: Vec<[f64; 2]>,
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

impl CauchyGreenSolver {
    /// The solver for a connected mesh, with an automatic cage of `options.cage` vertices.
    fn new(mesh: &Mesh, options: CauchyGreenOptions) -> Result<Self, DeformError> {
        check_options(&options)?;
        let exponent = normalising_exponent(mesh.positions().iter().copied());
        let unit: Vec<Point> = mesh.positions().iter().map(|p| p.map(|x| scale_by_power_of_two(x, exponent))).collect();
        let cage = Cage::new(&unit, cage::automatic(mesh, &unit, options.cage)?, exponent, false)?;
        Ok(Self {
            cage_image: cage.actual.clone(),
            unit,
            exponent,
            options,
            cage,
            fit: Fit::Translation { rest: [0.0; 2] },
            targets: Vec::new(),
            field: vec![[0.0; 2]; mesh.vertex_count()],
        })
    }

    /// The settings.
    pub fn options(&self) -> CauchyGreenOptions {
        self.options
    }

    /// The cage, counter-clockwise, in the rest pose.
    pub fn cage(&self) -> &[Point] {
        &self.cage.actual
    }

    fn automatic_cage(&self, mesh: &Mesh, vertices: usize) -> Result<Cage, DeformError> {
        Cage::new(&self.unit, cage::automatic(mesh, &self.unit, vertices)?, self.exponent, false)
    }

    /// Uses this cage (a simple polygon, either orientation, with the shape strictly
    /// inside), or an automatic one again with `None` ([`super::Deformer::set_cage`]).
    /// Refused with [`DeformError::InvalidCage`], changing nothing, when the cage cannot be
    /// used. The pose stays until the next step.
    pub(crate) fn set_cage(&mut self, shared: Shared<'_>, cage: Option<&[Point]>) -> Result<(), DeformError> {
        let cage = match cage {
            Some(points) => {
                let scaled: Vec<Point> =
                    points.iter().map(|p| p.map(|x| scale_by_power_of_two(x, self.exponent))).collect();
                Cage::new(&self.unit, cage::checked(shared.mesh, &self.unit, &scaled)?, self.exponent, true)?
            }
            None => self.automatic_cage(shared.mesh, self.options.cage)?,
        };
        self.fit = self.fit_for(&cage, shared.handles, self.options.smoothness)?;
        self.cage_image = cage.actual.clone();
        self.cage = cage;
        Ok(())
    }

    fn fit_for(&self, cage: &Cage, handles: &[HandlePoint], smoothness: f64) -> Result<Fit, DeformError> {
        let rest: Vec<Point> = handles.iter().map(|h| h.position(&self.unit)).collect();
        Fit::new(cage, &rest, self.exponent, smoothness)
    }
}

impl Solve for CauchyGreenSolver {
    fn abilities(&self) -> Abilities {
        Abilities::NONE
    }

    /// Fits the new handle set. A handle at the same place as one before keeps its target;
    /// the others start where their point is in the current pose.
    fn set_handles(&mut self, shared: Shared<'_>, handles: &[HandlePoint]) -> Result<(), DeformError> {
        let fit = self.fit_for(&self.cage, handles, self.options.smoothness)?;
        self.targets = handles
            .iter()
            .map(|h| match shared.handles.iter().position(|old| old == h) {
                Some(k) => self.targets[k],
                None => h.position(shared.positions),
            })
            .collect();
        self.fit = fit;
        Ok(())
    }

    /// Each handle's target moves by its velocity, and every vertex goes where the map
    /// fitted to the targets takes its rest position. With no handles nothing moves.
    /// Refused, changing nothing, for a result beyond the coordinate limit.
    fn step(
        &mut self,
        shared: Shared<'_>,
        velocities: &[[f64; 2]],
        _turns: Option<&[f64]>,
        next: &mut [Point],
        timings: &mut Timings,
    ) -> Result<bool, DeformError> {
        if shared.handles.is_empty() {
            self.field.fill([0.0; 2]);
            return Ok(false);
        }
        let start = (shared.clock)();
        let targets: Vec<Point> =
            self.targets.iter().zip(velocities).map(|(p, v)| [p[0] + v[0], p[1] + v[1]]).collect();
        let f = self.fit.cage_values(&self.cage, &targets);
        let solved = (shared.clock)();
        let n = self.cage.len();
        for (row, out) in self.cage.at_vertices.chunks_exact(n).zip(next.iter_mut()) {
            let z: C64 = row.iter().zip(&f).map(|(c, f)| c * f).sum();
            *out = [z.re, z.im];
        }
        let image: Vec<Point> = f.iter().map(|z| [z.re, z.im]).collect();
        // (The cage lies outside the shape: its image may go beyond the limits where the
        // shape's does not.)
        if !in_range(next) || next.iter().flatten().any(|x| x.is_nan()) {
            return Err(DeformError::NonFiniteResult);
        }
        for ((d, p), q) in self.field.iter_mut().zip(shared.positions).zip(next.iter()) {
            *d = [q[0] - p[0], q[1] - p[1]];
        }
        self.cage_image = image;
        self.targets = targets;
        *timings = Timings { solve: solved - start, integration: (shared.clock)() - solved, ..Timings::default() };
        Ok(true)
    }

    /// Handles stay, their targets become their points in the pose (the next step maps the
    /// rest mesh again, for those targets moved); at rest the cage is the rest cage again.
    fn pose_set(&mut self, shared: Shared<'_>, rest: bool) {
        self.targets = shared.handles.iter().map(|h| h.position(shared.positions)).collect();
        if rest {
            self.cage_image.clone_from(&self.cage.actual);
        }
        self.field.fill([0.0; 2]);
    }

    fn field(&self) -> &[[f64; 2]] {
        &self.field
    }

    /// The handles' targets: where each step has asked them to be (their points in the pose
    /// when they were set, moved by every step's velocities since). The shape's point under
    /// a handle lies near its target, not on it: handles are fitted in the least-squares
    /// sense.
    fn held_at(&self) -> Option<&[Point]> {
        Some(&self.targets)
    }

    /// Where the last step took the cage's vertices (the cage values; the rest cage after
    /// a reset). Drawn with straight edges, this is the polygon whose Cauchy integral the
    /// map is.
    fn cage_image(&self) -> Option<&[Point]> {
        Some(&self.cage_image)
    }

    /// Targets (apart from the positions: setting the pose would reset them), the deformed
    /// cage and the field.
    fn save(&self, checkpoint: &mut Checkpoint) {
        copy_into(&mut checkpoint.targets, &self.targets);
        copy_into(&mut checkpoint.cage_image, &self.cage_image);
        copy_into(&mut checkpoint.field, &self.field);
    }

    fn saved_lengths(&self, checkpoint: &Checkpoint) -> Vec<(usize, usize)> {
        vec![
            (checkpoint.field.len(), self.field.len()),
            (checkpoint.targets.len(), self.targets.len()),
            (checkpoint.cage_image.len(), self.cage_image.len()),
        ]
    }

    fn restore(&mut self, checkpoint: &Checkpoint) {
        self.targets.copy_from_slice(&checkpoint.targets);
        self.cage_image.copy_from_slice(&checkpoint.cage_image);
        self.field.copy_from_slice(&checkpoint.field);
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

impl Build for CauchyGreenOptions {
    type Solver = CauchyGreenSolver;

    fn check(&self) -> Result<(), DeformError> {
        check_options(self)
    }

    /// Cauchy-Green solves dense systems only.
    fn orders(&self, _mesh: &Mesh) -> Orders {
        Orders { systems: Vec::new() }
    }

    fn build(self, mesh: &Mesh, _joins: &Joins, orders: &Orders) -> Result<CauchyGreenSolver, DeformError> {
        orders.check(&[])?;
        CauchyGreenSolver::new(mesh, self)
    }

    fn of(solver: &CauchyGreenSolver) -> Self {
        solver.options
    }

    /// A new cage vertex count builds a new automatic cage (unless a cage was given), a new
    /// smoothness refits the handles. The next step uses them.
    fn configure(self, solver: &mut CauchyGreenSolver, shared: Shared<'_>) -> Result<(), DeformError> {
        let cage = match self.cage != solver.options.cage && !solver.cage.given {
            true => Some(solver.automatic_cage(shared.mesh, self.cage)?),
            false => None,
        };
        let fit = solver.fit_for(cage.as_ref().unwrap_or(&solver.cage), shared.handles, self.smoothness)?;
        if let Some(cage) = cage {
            solver.cage_image = cage.actual.clone();
            solver.cage = cage;
        }
        solver.options = self;
        solver.fit = fit;
        Ok(())
    }
}
