//! Moving least squares deformation (Schaefer, McPhail and Warren 2006, "Image deformation
//! using moving least squares"), in its closed forms: every vertex `v` moves by the map
//! that best takes the handles' rest points `p_i` to their targets `q_i` in the
//! least-squares sense weighted by `w_i = 1 / |p_i - v|^(2 alpha)`, among the affine maps
//! (eq. 5), the similarities (eq. 6) or the rigid motions (eq. 8). Each step is one
//! evaluation at every vertex of the rest mesh: no solve, no history, O(vertices x handles).
//!
//! In complex numbers (points `x + i y`), with the weighted centroids `p*`, `q*` and
//! `p^_i = p_i - p*`, `q^_i = q_i - q*`: the similarity is `f(v) = (v - p*) c + q*` with
//! `c = sum w_i conj(p^_i) q^_i / sum w_i |p^_i|^2`, and the rigid map is
//! `f(v) = (v - p*) c/|c| + q*`, the paper's `|v - p*| f_r / |f_r|` (its `f_r` is `(v - p*)`
//! times a positive multiple of `c`). The affine map solves the 2 x 2 normal equations of
//! eq. 5. A vertex on a handle's rest point goes to that handle's target (the weight is
//! infinite there); with one handle the map is the translation, which every variant
//! reproduces.

use super::error::DeformError;
use super::handles::{in_range, HandlePoint};
use super::method::{copy_into, Abilities, Build, Checkpoint, Orders, Shared, Solve, Timings};
use super::options::{Method, MlsOptions, MlsVariant, MLS_ALPHA_RANGE};
use super::puppet::Joins;
use crate::geometry::{normalising_exponent, power_of_two, scale_by_power_of_two, Point};
use crate::mesh::Mesh;

/// The moving-least-squares solver of one mesh (the mesh, handles and pose are its
/// [`Deformer`](super::Deformer)'s).
#[derive(Debug, Clone)]
pub struct MlsSolver {
    /// The mesh's positions times `2^exponent` (largest coordinate in [1, 2)), where the
    /// map is evaluated: MLS commutes with scaling, and there the weights `1 / d^(2 alpha)`
    /// neither overflow nor underflow at any scale of the mesh.
    unit: Vec<Point>,
    exponent: i32,
    options: MlsOptions,
    field: Vec<[f64; 2]>,
    // Scratch for a step: the handles' rest points and targets in the unit scale, weights.
    rest: Vec<Point>,
    targets: Vec<Point>,
    weights: Vec<f64>,
}

impl MlsSolver {
    /// The solver for a connected mesh.
    fn new(mesh: &Mesh, options: MlsOptions) -> Result<Self, DeformError> {
        check_options(&options)?;
        // (Clamped: a validated mesh never needs it, and 2^exponent and 2^-exponent are then
        // normal, multiplied by directly in a step, as ARAP does.)
        let exponent = normalising_exponent(mesh.positions().iter().copied()).clamp(-1022, 1022);
        let unit = mesh.positions().iter().map(|p| p.map(|x| scale_by_power_of_two(x, exponent))).collect();
        Ok(Self {
            unit,
            exponent,
            options,
            field: vec![[0.0; 2]; mesh.vertex_count()],
            rest: Vec::new(),
            targets: Vec::new(),
            weights: Vec::new(),
        })
    }

    /// The settings.
    pub fn options(&self) -> MlsOptions {
        self.options
    }
}

impl Solve for MlsSolver {
    fn abilities(&self) -> Abilities {
        Abilities::NONE
    }

    fn set_handles(&mut self, _shared: Shared<'_>, handles: &[HandlePoint]) -> Result<(), DeformError> {
        self.rest = handles.iter().map(|h| h.position(&self.unit)).collect();
        self.targets = vec![[0.0; 2]; handles.len()];
        self.weights = Vec::with_capacity(handles.len());
        Ok(())
    }

    /// Each handle's target is its current position plus its velocity, and every vertex
    /// moves to the MLS map of its rest position for those targets. With no handles nothing
    /// moves. Refused, changing nothing, for an affine map the handles do not determine
    /// (fewer than three, or all on one line) and for a result beyond the coordinate limit.
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
        let (down, up) = (power_of_two(self.exponent), power_of_two(-self.exponent));
        for ((target, h), v) in self.targets.iter_mut().zip(shared.handles).zip(velocities) {
            let p = h.position(shared.positions);
            *target = [p[0] + v[0], p[1] + v[1]].map(|x| x * down);
        }
        let map =
            Map { rest: &self.rest, targets: &self.targets, alpha: self.options.alpha, variant: self.options.variant };
        for (&v, out) in self.unit.iter().zip(next.iter_mut()) {
            let q = map.at(v, &mut self.weights).ok_or(DeformError::TooFewHandles {
                method: Method::Mls,
                needed: "three handles not all on one line for the affine map",
            })?;
            *out = q.map(|x| x * up);
        }
        if !in_range(next) {
            return Err(DeformError::NonFiniteResult);
        }
        for ((f, p), q) in self.field.iter_mut().zip(shared.positions).zip(next.iter()) {
            *f = [q[0] - p[0], q[1] - p[1]];
        }
        timings.integration = (shared.clock)() - start;
        Ok(true)
    }

    /// The next step maps the rest mesh again, for targets taken from the pose.
    fn pose_set(&mut self, _shared: Shared<'_>, _rest: bool) {
        self.field.fill([0.0; 2]);
    }

    fn field(&self) -> &[[f64; 2]] {
        &self.field
    }

    /// The field: a step maps the rest mesh for targets taken from the positions, and keeps
    /// nothing else.
    fn save(&self, checkpoint: &mut Checkpoint) {
        copy_into(&mut checkpoint.field, &self.field);
    }

    fn saved_lengths(&self, checkpoint: &Checkpoint) -> Vec<(usize, usize)> {
        vec![(checkpoint.field.len(), self.field.len())]
    }

    fn restore(&mut self, checkpoint: &Checkpoint) {
        self.field.copy_from_slice(&checkpoint.field);
    }
}

/// The MLS map of one set of handles.
struct Map<'a> {
    rest: &'a [Point],
    targets: &'a [Point],
    alpha: f64,
    variant: MlsVariant,
}

impl Map<'_> {
    /// Where `v` goes; `None` when the affine map is not determined there. `weights` is
    /// room for one weight per handle, reused from vertex to vertex.
    fn at(&self, v: Point, weights: &mut Vec<f64>) -> Option<Point> {
        // On a handle's rest point the weight is infinite: the targets of the handles there.
        weights.clear();
        let (mut on, mut on_sum) = (0usize, [0.0; 2]);
        for (p, q) in self.rest.iter().zip(self.targets) {
            let d2 = (p[0] - v[0]) * (p[0] - v[0]) + (p[1] - v[1]) * (p[1] - v[1]);
            // The paper's alpha = 1 (the default) without a power function, which costs
            // one call per vertex and handle: 9,607 vertices and 156 handles took 12-25 ms
            // a frame in wasm with it, 10.3-10.6 ms without.
            let w = if self.alpha == 1.0 { 1.0 / d2 } else { libm::pow(d2, -self.alpha) };
            if d2 == 0.0 || !w.is_finite() {
                on += 1;
                on_sum = [on_sum[0] + q[0], on_sum[1] + q[1]];
            }
            weights.push(w);
        }
        if on > 0 {
            return Some([on_sum[0] / on as f64, on_sum[1] / on as f64]);
        }
        let total: f64 = weights.iter().sum();
        // Weighted means taken from the first point, so that points all at one place have
        // exactly that mean (then the hatted points are exactly 0: a translation).
        let centroid = |points: &[Point]| {
            let o = points[0];
            let mut c = [0.0; 2];
            for (p, w) in points.iter().zip(weights.iter()) {
                c = [c[0] + w * (p[0] - o[0]), c[1] + w * (p[1] - o[1])];
            }
            [o[0] + c[0] / total, o[1] + c[1] / total]
        };
        let (ps, qs) = (centroid(self.rest), centroid(self.targets));
        let d = [v[0] - ps[0], v[1] - ps[1]];
        // Weighted sums of the hatted points: sum w p^ p^T (a, b; b, c), sum w p^ q^T (the
        // affine map's), and sum w conj(p^) q^ (the similarity's).
        let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
        let mut pq = [[0.0; 2]; 2];
        for ((p, q), w) in self.rest.iter().zip(self.targets).zip(weights.iter()) {
            let (ph, qh) = ([p[0] - ps[0], p[1] - ps[1]], [q[0] - qs[0], q[1] - qs[1]]);
            a += w * ph[0] * ph[0];
            b += w * ph[0] * ph[1];
            c += w * ph[1] * ph[1];
            for (i, row) in pq.iter_mut().enumerate() {
                for (j, entry) in row.iter_mut().enumerate() {
                    *entry += w * ph[i] * qh[j];
                }
            }
        }
        let moved = match self.variant {
            MlsVariant::Affine => {
                // f(v) = (v - p*) M + q* with M = (sum w p^T p^)^-1 sum w p^T q^ (row vectors).
                let det = a * c - b * b;
                // Singular (or NaN) when the handles lie on one line.
                if det.abs().partial_cmp(&(1e-12 * (a + c) * (a + c))) != Some(std::cmp::Ordering::Greater) {
                    return None;
                }
                let inverse = [[c / det, -b / det], [-b / det, a / det]];
                let m = |i: usize, j: usize| inverse[i][0] * pq[0][j] + inverse[i][1] * pq[1][j];
                [d[0] * m(0, 0) + d[1] * m(1, 0), d[0] * m(0, 1) + d[1] * m(1, 1)]
            }
            MlsVariant::Similarity | MlsVariant::Rigid => {
                // conj(p^) q^ summed: real part p.q, imaginary part p x q.
                let (re, im) = (pq[0][0] + pq[1][1], pq[0][1] - pq[1][0]);
                let mu = a + c;
                let (cr, ci) = match self.variant {
                    _ if mu == 0.0 => (1.0, 0.0),
                    MlsVariant::Rigid => {
                        let r = libm::hypot(re, im);
                        if r == 0.0 {
                            (1.0, 0.0)
                        } else {
                            (re / r, im / r)
                        }
                    }
                    _ => (re / mu, im / mu),
                };
                [d[0] * cr - d[1] * ci, d[0] * ci + d[1] * cr]
            }
        };
        Some([moved[0] + qs[0], moved[1] + qs[1]])
    }
}

fn check_options(options: &MlsOptions) -> Result<(), DeformError> {
    if !MLS_ALPHA_RANGE.contains(&options.alpha) {
        return Err(DeformError::InvalidOption {
            name: "alpha",
            value: options.alpha,
            expected: "a number from 0.1 to 4",
        });
    }
    Ok(())
}

impl Build for MlsOptions {
    type Solver = MlsSolver;

    fn check(&self) -> Result<(), DeformError> {
        check_options(self)
    }

    /// MLS solves no linear system.
    fn orders(&self, _mesh: &Mesh) -> Orders {
        Orders { systems: Vec::new() }
    }

    fn build(self, mesh: &Mesh, _joins: &Joins, orders: &Orders) -> Result<MlsSolver, DeformError> {
        orders.check(&[])?;
        MlsSolver::new(mesh, self)
    }

    fn of(solver: &MlsSolver) -> Self {
        solver.options
    }

    fn configure(self, solver: &mut MlsSolver, _shared: Shared<'_>) -> Result<(), DeformError> {
        solver.options = self;
        Ok(())
    }
}
