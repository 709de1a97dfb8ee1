//! A trained deformation operator and its evaluation per frame (paper eq. 3 and §4):
//! V^ν(Q) = Dᵀ (X^ν Ψ(Q)) for ν ∈ {x, y}, "evaluate Ψ at Q, then a matrix–vector product".
//! The evaluation allocates nothing: Ψ(Q) and, for a reduced spatial basis, the |Φ|
//! coefficients go to scratch buffers the operator owns.

use nalgebra::DMatrix;

use super::basis::HandleBasis;
use super::fit_error::{check_finite, check_length, FitError};
use super::kernels;
use super::sampling::{regions, Region, Sampling, SamplingError};
use super::spatial::MeshPoint;
use super::training::Training;
use crate::deform::Puppet;
use crate::geometry::bounding_box;
use crate::mesh::Mesh;

/// How a fit solved its least-squares problem.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Solver {
    /// The structured solver of the strong-constraint problem (notes §2.5).
    Structured,
    /// The TPS shortcut: the operator interpolates every sample (notes §2.5).
    TpsInterpolation,
}

/// A trained deformation operator: rest handles, handle basis, coefficients X^x, X^y
/// (|Φ| × |Ψ|) and, for a reduced spatial basis, its nodal values D (|Φ| × N). Not
/// `PartialEq`: it holds scratch buffers whose contents depend on the last evaluation.
#[derive(Debug, Clone)]
pub struct Operator {
    handles: Vec<MeshPoint>,
    basis: HandleBasis,
    solver: Solver,
    spatial_len: usize,
    vertex_count: usize,
    /// Row i of X^x then row i of X^y, for every i: `[(2i + ν)|Ψ| + j]`.
    coefficients: Vec<f64>,
    /// D by vertex: `[v |Φ| + i] = D_iv`; empty for the hat basis.
    reduction: Vec<f64>,
    /// Scratch: Ψ(Q).
    psi: Vec<f64>,
    /// Scratch for a reduced basis: X^x Ψ then X^y Ψ.
    nodal: Vec<f64>,
    /// Scratch for canonical coordinates: the canonical targets Q̂ (2n numbers; else empty).
    canonical: Vec<f64>,
    /// The puppet (parts and joints) of the mesh it was trained on, if it was one.
    puppet: Option<Puppet>,
    /// Its training's settings, when known (trained here, or read from a version-4 file).
    training: Option<Training>,
}

impl Operator {
    pub(crate) fn new(
        handles: Vec<MeshPoint>,
        basis: HandleBasis,
        solver: Solver,
        x: [DMatrix<f64>; 2],
        reduction: Option<&DMatrix<f64>>,
        vertex_count: usize,
    ) -> Self {
        let (rows, len) = x[0].shape();
        let mut coefficients = Vec::with_capacity(2 * rows * len);
        for i in 0..rows {
            for xv in &x {
                coefficients.extend(xv.row(i).iter());
            }
        }
        let reduction = reduction.map_or_else(Vec::new, |d| d.as_slice().to_vec());
        Self::with_scratch(handles, basis, solver, rows, vertex_count, coefficients, reduction)
    }

    /// The operator with its scratch buffers sized (the one place they are).
    fn with_scratch(
        handles: Vec<MeshPoint>,
        basis: HandleBasis,
        solver: Solver,
        spatial_len: usize,
        vertex_count: usize,
        coefficients: Vec<f64>,
        reduction: Vec<f64>,
    ) -> Self {
        let nodal = if reduction.is_empty() { Vec::new() } else { vec![0.0; 2 * spatial_len] };
        let psi = vec![0.0; basis.len()];
        let canonical = canonical_scratch(&basis);
        let (puppet, training) = (None, None);
        Self {
            handles,
            basis,
            solver,
            spatial_len,
            vertex_count,
            coefficients,
            reduction,
            psi,
            nodal,
            canonical,
            puppet,
            training,
        }
    }

    /// An operator from its parts as an operator file holds them, with every length checked
    /// against the others (`coefficients`: row i of X^x then of X^y for each spatial
    /// function; `reduction`: D by vertex, empty for the hat basis).
    pub(crate) fn from_parts(
        handles: Vec<MeshPoint>,
        basis: HandleBasis,
        solver: Solver,
        spatial_len: usize,
        vertex_count: usize,
        coefficients: Vec<f64>,
        reduction: Vec<f64>,
    ) -> Result<Self, FitError> {
        let expected = 2 * spatial_len * basis.len();
        if coefficients.len() != expected {
            return Err(FitError::Length { what: "coefficients", expected, found: coefficients.len() });
        }
        let hat = reduction.is_empty();
        if (hat && spatial_len != vertex_count) || (!hat && reduction.len() != spatial_len * vertex_count) {
            let expected = spatial_len * vertex_count;
            return Err(FitError::Length { what: "reduced basis", expected, found: reduction.len() });
        }
        if 2 * handles.len() != basis.rest().len() {
            let (expected, found) = (2 * handles.len(), basis.rest().len());
            return Err(FitError::Length { what: "rest handles", expected, found });
        }
        check_finite("coefficients", &coefficients)?;
        check_finite("reduced basis", &reduction)?;
        Ok(Self::with_scratch(handles, basis, solver, spatial_len, vertex_count, coefficients, reduction))
    }

    /// The coefficients: row i of X^x then row i of X^y, for every spatial function i.
    pub(crate) fn coefficients(&self) -> &[f64] {
        &self.coefficients
    }

    /// D by vertex (`[v |Φ| + i] = D_iv`); empty for the hat basis.
    pub(crate) fn reduction(&self) -> &[f64] {
        &self.reduction
    }

    /// The puppet (parts and joints) of the mesh the operator was trained on, or `None` for
    /// one shape: a rig of a puppet poses that puppet (its operator file records it).
    pub fn puppet(&self) -> Option<&Puppet> {
        self.puppet.as_ref()
    }

    /// The operator for the mesh as the puppet `puppet` (or as one shape for `None`): what
    /// [`super::Trainer`] and the operator file's reader set. Checking the puppet against
    /// the mesh is the caller's (the trainer's ground truth and the file's reader check it).
    pub fn with_puppet(mut self, puppet: Option<Puppet>) -> Self {
        self.puppet = puppet;
        self
    }

    /// The settings it was trained with, or `None` when they are not known (an operator
    /// fitted directly, or read from a file older than version 4).
    pub fn training(&self) -> Option<&Training> {
        self.training.as_ref()
    }

    /// The operator with its training's settings (what [`super::Trainer::finish`] and the
    /// operator file's reader set).
    pub fn with_training(mut self, training: Option<Training>) -> Self {
        self.training = training;
        self
    }

    /// Its training's sampling and radius, or, when the training is not known, discs of
    /// radius the handle coordinates' scale (which a trainer sets to its radius).
    pub fn sampling(&self) -> (Sampling, f64) {
        self.training.map_or((Sampling::Disc, self.basis.scale()), |t| (t.sampling, t.radius))
    }

    /// Each handle's region its training drew targets from ([`regions`]), for `mesh`, the
    /// mesh it was trained on (whose bounding box the Voronoi cells are clipped to), for
    /// [`Operator::sampling`].
    pub fn sampling_regions(&self, mesh: &Mesh) -> Result<Vec<Region>, SamplingError> {
        let (sampling, radius) = self.sampling();
        let rest: Vec<[f64; 2]> = self.basis.rest().chunks_exact(2).map(|c| [c[0], c[1]]).collect();
        let (lo, hi) = bounding_box(mesh.positions().iter().copied()).ok_or(SamplingError::NotFinite)?;
        regions(&rest, [lo, hi], radius, sampling)
    }

    /// The handles' rest positions, as given to the fit.
    pub fn handles(&self) -> &[MeshPoint] {
        &self.handles
    }

    /// The handle basis Ψ (kind, rest handles, scale, TPS centres).
    pub fn handle_basis(&self) -> &HandleBasis {
        &self.basis
    }

    /// How the fit was solved.
    pub fn solver(&self) -> Solver {
        self.solver
    }

    /// The number of spatial basis functions |Φ|.
    pub fn spatial_len(&self) -> usize {
        self.spatial_len
    }

    /// The number of mesh vertices N.
    pub fn vertex_count(&self) -> usize {
        self.vertex_count
    }

    /// The bytes the operator's numbers take: its coefficients X^x, X^y and, for a reduced
    /// spatial basis, its nodal values D (8 bytes each; scratch buffers not counted).
    ///
    /// ```
    /// use akap::defop::{fit, BasisKind, FitOptions, MeshPoint, Sample, SpatialBasis};
    ///
    /// // A linear operator (|Ψ| = 2n + 1 = 3) on the hat functions of a 2 x 2 grid (|Φ| =
    /// // 9 vertices): X^x and X^y are 9 x 3 each, and there is no reduced basis.
    /// let mesh = akap::shapes::grid_mesh(2, 2);
    /// let shift = |dx: f64, dy: f64| -> Vec<f64> {
    ///     mesh.positions().iter().flat_map(|p| [p[0] + dx, p[1] + dy]).collect()
    /// };
    /// let (right, up) = (shift(0.5, 0.0), shift(0.0, 0.5));
    /// let samples = [
    ///     Sample { targets: &[1.5, 1.0], positions: &right },
    ///     Sample { targets: &[1.0, 1.5], positions: &up },
    /// ];
    /// let options = FitOptions::default().with_kind(BasisKind::Linear);
    /// let operator = fit(&mesh, &SpatialBasis::hat(&mesh), &[MeshPoint::Vertex(4)], &samples, &options)?;
    /// assert_eq!(operator.stored_bytes(), 8 * 2 * 9 * 3);
    /// # Ok::<(), akap::defop::FitError>(())
    /// ```
    pub fn stored_bytes(&self) -> usize {
        8 * (self.coefficients.len() + self.reduction.len())
    }

    /// The coefficient X^ν_ij of spatial function i and handle function j for coordinate
    /// ν (0 for x, 1 for y); `None` if an index is out of range.
    pub fn coefficient(&self, coordinate: usize, i: usize, j: usize) -> Option<f64> {
        (coordinate < 2 && i < self.spatial_len && j < self.psi.len())
            .then(|| self.coefficients[(2 * i + coordinate) * self.psi.len() + j])
    }

    /// Writes the vertex positions D(v, Q) (2N numbers, x and y interleaved) for the handle
    /// targets Q (2n numbers) to `out`. Allocates nothing. Refuses wrong lengths and NaN or
    /// infinite targets. The targets of fixed handles are ignored (they stay at rest); with
    /// canonical coordinates, D(v, Q) = R*(D̂(v, Q̂) − c_P) + c_Q (see `coordinates`).
    pub fn evaluate_into(&mut self, targets: &[f64], out: &mut [f64]) -> Result<(), FitError> {
        self.check(targets, out.len())?;
        self.evaluate_rigidly(targets, |v, x, y| {
            out[2 * v] = x;
            out[2 * v + 1] = y;
        });
        Ok(())
    }

    /// [`Operator::evaluate_into`] writing single-precision positions (for a GPU buffer);
    /// computed in double precision.
    pub fn evaluate_into_f32(&mut self, targets: &[f64], out: &mut [f32]) -> Result<(), FitError> {
        self.check(targets, out.len())?;
        self.evaluate_rigidly(targets, |v, x, y| {
            out[2 * v] = x as f32;
            out[2 * v + 1] = y as f32;
        });
        Ok(())
    }

    /// The vertex positions for the handle targets Q, in a new vector (2N numbers).
    pub fn evaluate(&mut self, targets: &[f64]) -> Result<Vec<f64>, FitError> {
        let mut out = vec![0.0; 2 * self.vertex_count];
        self.evaluate_into(targets, &mut out)?;
        Ok(out)
    }

    fn check(&self, targets: &[f64], out_len: usize) -> Result<(), FitError> {
        check_length("targets", targets, 2 * self.handles.len())?;
        check_finite("targets", targets)?;
        if out_len != 2 * self.vertex_count {
            return Err(FitError::Length { what: "output", expected: 2 * self.vertex_count, found: out_len });
        }
        Ok(())
    }

    /// [`Operator::evaluate_with`] at the canonical targets Q̂, each position moved back by
    /// the rigid motion of the targets, for canonical coordinates; else that evaluation.
    fn evaluate_rigidly(&mut self, targets: &[f64], mut write: impl FnMut(usize, f64, f64)) {
        let mut canonical = std::mem::take(&mut self.canonical);
        match self.basis.coordinates().canonicalise(targets, &mut canonical) {
            Some(rigid) => self.evaluate_with(&canonical, |v, x, y| {
                let [x, y] = rigid.apply([x, y]);
                write(v, x, y)
            }),
            None => self.evaluate_with(targets, write),
        }
        self.canonical = canonical;
    }

    fn evaluate_with(&mut self, targets: &[f64], write: impl FnMut(usize, f64, f64)) {
        self.basis.evaluate_unchecked(targets, &mut self.psi);
        kernels::positions(&self.coefficients, &self.psi, &self.reduction, &mut self.nodal, write);
    }
}

/// The scratch of the canonical targets: 2n numbers for canonical coordinates, else none.
pub(super) fn canonical_scratch(basis: &HandleBasis) -> Vec<f64> {
    if basis.coordinates().is_canonical() {
        vec![0.0; basis.rest().len()]
    } else {
        Vec::new()
    }
}
