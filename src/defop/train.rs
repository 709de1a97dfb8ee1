//! Training a deformation operator by bootstrapping (the paper's main trick, Sections 1 and
//! 3.3; notes, section 2.3): ground truths for `k + 1` targets solved from the rest pose
//! (k the handle coordinates: 2n, 2n − 3 canonical, 2(n − #fixed) with fixed handles),
//! a linear operator fitted to them, then ever larger batches whose solves start from the
//! current operator's prediction (a few Newton iterations instead of many), each batch
//! followed by a refit with the richest basis its samples support, up to `m` samples and
//! the final fit with the basis asked for.
//!
//! The work comes in jobs (one sample's solve each) so that it can run anywhere:
//! [`Trainer::advance`] runs jobs on this thread until a time budget is spent, and
//! [`Trainer::next_jobs`] / [`Trainer::submit`] hand them to workers with their own
//! [`GroundTruth`] (made by [`Trainer::solver`]) and take the results back, in any order.
//! Either way the operator depends only on the options and the seed: a job's result does
//! not depend on who solved it, and fits run on the samples in their index order.

use super::basis::BasisKind;
use super::coordinates::HandleCoordinates;
use super::energy::Energy;
use super::fit::{fit, FitOptions, Sample};
use super::fit_error::FitError;
use super::ground_truth::{DefOpError, GroundTruth, GroundTruthOptions, Handles, Start};
use super::operator::Operator;
use super::reduced::reduced_basis;
pub use super::sampling::MAX_SAMPLES;
use super::sampling::{Sampler, Sampling, SamplingError, DEFAULT_RADIUS_FRACTION};
use super::spatial::{MeshPoint, SpatialBasis};
use super::training::Training;
use crate::deform::Puppet;
use crate::error_code::ErrorCode;
use crate::geometry::{bounding_box, Point};
use crate::mesh::Mesh;

/// How to train.
#[derive(Debug, Clone, PartialEq)]
pub struct TrainOptions {
    /// The ground truth's energy (default S-ARAP, the paper's).
    pub energy: Energy,
    /// The handle basis of the final operator (default TPS).
    pub basis: BasisKind,
    /// Samples beyond the rest pose (default 200).
    pub samples: usize,
    /// The sampling radius; `None`: [`DEFAULT_RADIUS_FRACTION`] of the shape's bounding-box
    /// diagonal.
    pub radius: Option<f64>,
    /// Where targets are drawn.
    pub sampling: Sampling,
    /// The spatial basis: 0 for the hat functions, else the size of the reduced basis.
    pub spatial: usize,
    /// Seed of the samples.
    pub seed: u64,
    /// The ground-truth solver's settings.
    pub ground_truth: GroundTruthOptions,
    /// Canonical handle coordinates ([`FitOptions::canonical`]): the operator reproduces
    /// rigid motions of all handles exactly (default false).
    pub canonical: bool,
    /// Handles (indices into the handles) held at their rest position in every sample; the
    /// operator keeps them there whatever targets it is given ([`FitOptions::fixed`];
    /// default none; not with `canonical`).
    pub fixed: Vec<usize>,
    /// The mesh's parts and joints when it is a puppet (default `None`, one connected
    /// shape): the ground truth joins the sheets at the joints and holds sheets no handle
    /// reaches ([`GroundTruth::with_puppet`]), and the trained operator records the puppet
    /// ([`Operator::puppet`]), as its file does.
    pub puppet: Option<Puppet>,
}

impl Default for TrainOptions {
    fn default() -> Self {
        Self {
            energy: Energy::SArap,
            basis: BasisKind::Tps,
            samples: 200,
            radius: None,
            sampling: Sampling::Disc,
            spatial: 0,
            seed: 1,
            ground_truth: GroundTruthOptions::default(),
            canonical: false,
            fixed: Vec::new(),
            puppet: None,
        }
    }
}

/// The most memory a training may need for its samples' ground truths and its operator's
/// coefficients (1 GB; WebAssembly has 4 GB at most).
pub const MAX_TRAINING_BYTES: usize = 1_000_000_000;

/// The most times one sample is drawn again when its targets are unreachable.
pub const MAX_REDRAWS: u32 = 20;

/// Why training failed or refused a call.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum TrainError {
    /// An option is out of range.
    InvalidOption {
        /// The option.
        name: &'static str,
        /// What would be accepted.
        expected: &'static str,
    },
    /// The ground truth refused the mesh, the handles or a sample.
    GroundTruth(DefOpError),
    /// A fit failed.
    Fit(FitError),
    /// The sampler refused the handles.
    Sampling(SamplingError),
    /// An operator file could not be read.
    File(super::file::OperatorFileError),
    /// [`Trainer::finish`] before every job is done.
    NotDone {
        /// Units done.
        done: usize,
        /// Units in all.
        total: usize,
    },
    /// The training would need more memory than [`MAX_TRAINING_BYTES`].
    TooLarge {
        /// Bytes needed (the samples' ground truths and the operator's coefficients).
        bytes: f64,
    },
    /// One sample's solve failed [`MAX_REDRAWS`] times, each time drawn again.
    TooManyRedraws {
        /// The sample.
        index: usize,
    },
    /// Fewer samples than the handle basis needs to be determined: its polynomial part (all
    /// of it for a polynomial basis, the linear part for TPS) has more functions than the
    /// samples and the rest pose.
    TooFewSamples {
        /// The samples asked for.
        samples: usize,
        /// The fewest that determine the basis.
        needed: usize,
    },
    /// A result for a job that was not handed out, or was already submitted, or of the
    /// wrong length.
    UnknownJob {
        /// The job's index.
        index: usize,
    },
}

impl std::fmt::Display for TrainError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::InvalidOption { name, expected } => write!(f, "training option {name} must be {expected}"),
            Self::GroundTruth(e) => write!(f, "ground truth: {e}"),
            Self::Fit(e) => write!(f, "fit: {e}"),
            Self::Sampling(e) => write!(f, "sampling: {e}"),
            Self::File(e) => e.fmt(f),
            Self::TooLarge { bytes } => write!(
                f,
                "training would need {:.0} MB (samples' ground truths and coefficients), more than the {} MB allowed; \
                 use fewer samples or a reduced spatial basis",
                bytes / 1e6,
                MAX_TRAINING_BYTES / 1_000_000
            ),
            Self::TooManyRedraws { index } => {
                write!(f, "sample {index} could not be solved in {MAX_REDRAWS} draws; try a smaller radius")
            }
            Self::NotDone { done, total } => write!(f, "training is not done: {done} of {total}"),
            Self::TooFewSamples { samples, needed } => write!(
                f,
                "{samples} samples cannot determine this handle basis: give at least {needed} \
                 (or a smaller basis, or fewer handles)"
            ),
            Self::UnknownJob { index } => {
                write!(f, "no pending job {index} takes this result (not handed out, already in, or the wrong size)")
            }
        }
    }
}

impl std::error::Error for TrainError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::GroundTruth(e) => Some(e),
            Self::Fit(e) => Some(e),
            Self::Sampling(e) => Some(e),
            Self::File(e) => Some(e),
            _ => None,
        }
    }
}

impl TrainError {
    /// The kind of error: that of the ground truth's or the fit's error it holds,
    /// [`ErrorCode::InvalidOption`] for options, [`ErrorCode::Import`] for an operator file
    /// that cannot be read, otherwise [`ErrorCode::InvalidArgument`].
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::InvalidOption { .. } => ErrorCode::InvalidOption,
            Self::TooLarge { .. } => ErrorCode::Limit,
            Self::File(_) => ErrorCode::Import,
            Self::GroundTruth(e) => e.code(),
            Self::Fit(e) => e.code(),
            _ => ErrorCode::InvalidArgument,
        }
    }
}

impl From<DefOpError> for TrainError {
    fn from(e: DefOpError) -> Self {
        Self::GroundTruth(e)
    }
}

impl From<super::file::OperatorFileError> for TrainError {
    fn from(e: super::file::OperatorFileError) -> Self {
        Self::File(e)
    }
}

impl From<FitError> for TrainError {
    fn from(e: FitError) -> Self {
        Self::Fit(e)
    }
}

/// How far training is: `done` of `total` units, one per sample and one for the final fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Progress {
    /// Units done.
    pub done: usize,
    /// Units in all.
    pub total: usize,
    /// `"samples"` while samples are solved (with refits between batches), `"fit"` when
    /// only the final fit is left, `"done"`.
    pub stage: &'static str,
}

/// One sample's solve: the targets, and the pose to start from (`None`: the rest pose).
#[derive(Debug, Clone, PartialEq)]
pub struct Job {
    /// The sample's index.
    pub index: usize,
    /// Two coordinates per handle.
    pub targets: Vec<Point>,
    /// The current operator's prediction, a warm start.
    pub start: Option<Vec<Point>>,
}

/// Solver iterations, cold (from the rest pose) and warm (from a prediction).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TrainStats {
    /// Samples solved from the rest pose and their Newton iterations in all.
    pub cold: (usize, usize),
    /// Samples solved from a prediction and their Newton iterations in all.
    pub warm: (usize, usize),
    /// Warm starts that fell back to the rest pose (a triangle of the start flipped).
    pub fallbacks: usize,
    /// Warm starts from the nearest solved sample, because the prediction folded a
    /// triangle (S-ARAP).
    pub neighbour_starts: usize,
    /// Samples drawn again because no flip-free deformation reaches their targets (S-ARAP
    /// cannot turn a triangle over, and targets drawn independently per handle can ask
    /// for it) or the solve did not converge.
    pub redraws: usize,
}

impl TrainStats {
    /// Mean iterations per cold solve.
    pub fn mean_cold(&self) -> f64 {
        self.cold.1 as f64 / self.cold.0.max(1) as f64
    }
    /// Mean iterations per warm solve.
    pub fn mean_warm(&self) -> f64 {
        self.warm.1 as f64 / self.warm.0.max(1) as f64
    }
}

/// A training in progress.
#[derive(Debug)]
pub struct Trainer {
    mesh: Mesh,
    handles: Vec<MeshPoint>,
    options: TrainOptions,
    radius: f64,
    /// The rest handles (2n numbers), where fixed handles are sampled.
    rest: Vec<f64>,
    spatial: SpatialBasis,
    solver: GroundTruth,
    /// Targets of every sample drawn, `2n` each (drawn a batch at a time).
    targets: Vec<Vec<f64>>,
    /// Ground truths of the samples solved so far, `2N` each.
    positions: Vec<Option<Vec<f64>>>,
    sampler: Sampler,
    /// How often each sample was drawn again (its targets were unreachable).
    redraws: Vec<u32>,
    /// Whether each sample's job is out (handed out and not returned).
    out: Vec<bool>,
    /// The end of the current batch (samples `..batch_end` are drawn).
    batch_end: usize,
    /// Jobs of the current batch waiting to be handed out, by index, in order.
    queue: std::collections::VecDeque<usize>,
    predictor: Option<Operator>,
    stats: TrainStats,
    result: Option<Operator>,
}

impl Trainer {
    /// A training of an operator for `mesh` with handles at `handles`; checks everything and
    /// computes the spatial basis (a reduced one takes about a second at 2,000 vertices).
    pub fn new(mesh: &Mesh, handles: &[MeshPoint], options: TrainOptions) -> Result<Self, TrainError> {
        if !(1..=MAX_SAMPLES).contains(&options.samples) {
            return Err(TrainError::InvalidOption { name: "samples", expected: "a whole number from 1 to 100000" });
        }
        let (lo, hi) = bounding_box(mesh.positions().iter().copied()).expect("a mesh has vertices");
        let diagonal = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
        let radius = options.radius.unwrap_or(DEFAULT_RADIUS_FRACTION * diagonal);
        let n = handles.len();
        let k = HandleCoordinates::count(n, options.canonical, options.fixed.len());
        // With the rest pose, the samples must determine the basis's polynomial part.
        let polynomial = if options.basis.is_polynomial() { options.basis.size_in(k, 0) } else { k + 1 };
        if options.samples + 1 < polynomial {
            return Err(TrainError::TooFewSamples { samples: options.samples, needed: polynomial - 1 });
        }
        let spatial_len = if options.spatial == 0 { mesh.vertex_count() } else { options.spatial };
        let coefficients = spatial_len as f64 * options.basis.size_in(k, options.samples) as f64;
        let bytes = 16.0 * (coefficients + (options.samples * mesh.vertex_count()) as f64);
        if bytes > MAX_TRAINING_BYTES as f64 {
            return Err(TrainError::TooLarge { bytes });
        }
        let solver = Self::make_solver(mesh, handles, &options)?;
        let rest = solver.rest_handle_positions();
        let flat: Vec<f64> = rest.iter().flatten().copied().collect();
        // Refuses canonical with fixed handles and bad fixed indices before any solve.
        HandleCoordinates::new(&flat, options.canonical, &options.fixed)?;
        let sampler =
            Sampler::new(&rest, [lo, hi], radius, options.sampling, options.seed).map_err(TrainError::Sampling)?;
        let spatial =
            if options.spatial == 0 { SpatialBasis::hat(mesh) } else { reduced_basis(mesh, options.spatial)? };
        let mut trainer = Self {
            mesh: mesh.clone(),
            handles: handles.to_vec(),
            radius,
            rest: flat,
            spatial,
            solver,
            targets: Vec::new(),
            positions: Vec::new(),
            sampler,
            redraws: Vec::new(),
            out: Vec::new(),
            batch_end: 0,
            queue: std::collections::VecDeque::new(),
            predictor: None,
            stats: TrainStats::default(),
            result: None,
            options,
        };
        // Enough for the first, linear, fit: k + 1 samples with the rest pose.
        trainer.draw_batch((k + 1).min(trainer.options.samples));
        Ok(trainer)
    }

    fn make_solver(mesh: &Mesh, handles: &[MeshPoint], options: &TrainOptions) -> Result<GroundTruth, TrainError> {
        // Vertices as points of a triangle using them (weight 1 at that corner), so that
        // every handle is given the one way.
        let points = crate::deform::handles::resolve(mesh, handles).map_err(FitError::InvalidHandle)?;
        let (triangles, barycentric) = crate::deform::handles::as_points(points.iter());
        let handles = Handles::Points { triangles: &triangles, barycentric: &barycentric };
        Ok(match &options.puppet {
            Some(puppet) => GroundTruth::with_puppet(mesh, puppet, handles, options.energy, options.ground_truth)?,
            None => GroundTruth::new(mesh, handles, options.energy, options.ground_truth)?,
        })
    }

    /// A ground-truth solver like this training's, for a worker's [`Job`]s.
    pub fn solver(&self) -> Result<GroundTruth, TrainError> {
        Self::make_solver(&self.mesh, &self.handles, &self.options)
    }

    /// The solver a training of `mesh` with `handles` and `options` uses, made anywhere (a
    /// worker with the same inputs gets the same solver, so the same ground truths).
    pub fn solver_for(mesh: &Mesh, handles: &[MeshPoint], options: &TrainOptions) -> Result<GroundTruth, TrainError> {
        Self::make_solver(mesh, handles, options)
    }

    /// The number of samples drawn so far (solved or not).
    pub fn sample_count(&self) -> usize {
        self.targets.len()
    }

    /// Sample `index`: its targets (`2n` numbers) and, once solved, its ground truth (`2N`).
    pub fn sample(&self, index: usize) -> Option<(&[f64], Option<&[f64]>)> {
        Some((self.targets.get(index)?, self.positions[index].as_deref()))
    }

    /// The sampling radius in use.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Solver iterations so far.
    pub fn stats(&self) -> TrainStats {
        self.stats
    }

    /// How far training is.
    pub fn progress(&self) -> Progress {
        let solved = self.positions.iter().filter(|p| p.is_some()).count();
        let total = self.options.samples + 1;
        let (done, stage) = match (&self.result, solved == self.options.samples) {
            (Some(_), _) => (total, "done"),
            (None, true) => (solved, "fit"),
            (None, false) => (solved, "samples"),
        };
        Progress { done, total, stage }
    }

    /// Up to `max` jobs of the current batch not handed out yet (none while a batch's
    /// results are outstanding: the next batch's warm starts need its refit).
    pub fn next_jobs(&mut self, max: usize) -> Result<Vec<Job>, TrainError> {
        let mut jobs = Vec::new();
        while jobs.len() < max {
            let Some(index) = self.queue.pop_front() else { break };
            let targets: Vec<Point> = self.targets[index].chunks_exact(2).map(|c| [c[0], c[1]]).collect();
            let start = self.warm_start(index)?;
            self.out[index] = true;
            jobs.push(Job { index, targets, start });
        }
        Ok(jobs)
    }

    /// Where sample `index`'s solve starts: the current operator's prediction, or, when
    /// that folds a triangle under S-ARAP (which a flip-free solve cannot start from), the
    /// ground truth of the solved sample whose targets are nearest; the rest pose before
    /// the first fit.
    fn warm_start(&mut self, index: usize) -> Result<Option<Vec<Point>>, TrainError> {
        let Some(operator) = &mut self.predictor else { return Ok(None) };
        let predicted = to_points(&operator.evaluate(&self.targets[index])?);
        let folds = self.options.energy == Energy::SArap
            && self.mesh.triangles().iter().any(|t| {
                let [a, b, c] = t.map(|v| predicted[v as usize]);
                (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]) <= 0.0
            });
        if !folds {
            return Ok(Some(predicted));
        }
        self.stats.neighbour_starts += 1;
        let here = &self.targets[index];
        let distance = |t: &[f64]| t.iter().zip(here).map(|(a, b)| (a - b) * (a - b)).sum::<f64>();
        let nearest = self
            .positions
            .iter()
            .enumerate()
            .filter_map(|(k, p)| p.as_ref().map(|p| (distance(&self.targets[k]), p)))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        Ok(nearest.map(|(_, p)| to_points(p)))
    }

    /// Job `index` could not be solved (its targets are unreachable without a flip,
    /// [`DefOpError::Unreachable`], or Newton's method ran out of iterations,
    /// [`DefOpError::NoConvergence`]): its sample is drawn again (from its own keyed stream,
    /// so the same whoever reports it) and the job waits to be handed out again. After
    /// [`MAX_REDRAWS`] draws of one sample, training fails with that error.
    pub fn reject(&mut self, index: usize, error: DefOpError) -> Result<(), TrainError> {
        if !self.out.get(index).copied().unwrap_or(false) {
            return Err(TrainError::UnknownJob { index });
        }
        let redrawable = matches!(error, DefOpError::Unreachable { .. } | DefOpError::NoConvergence { .. });
        if !redrawable || self.redraws[index] >= MAX_REDRAWS {
            return Err(TrainError::GroundTruth(error));
        }
        self.redraw(index)
    }

    /// Draws job `index`'s sample again (its solve failed; see [`Trainer::reject`], which
    /// checks why), and the job waits to be handed out again. Refused for a job that is not
    /// out, and after [`MAX_REDRAWS`] draws of one sample.
    pub fn redraw(&mut self, index: usize) -> Result<(), TrainError> {
        if !self.out.get(index).copied().unwrap_or(false) {
            return Err(TrainError::UnknownJob { index });
        }
        if self.redraws[index] >= MAX_REDRAWS {
            return Err(TrainError::TooManyRedraws { index });
        }
        self.out[index] = false;
        self.redraws[index] += 1;
        self.stats.redraws += 1;
        self.draw(index);
        self.queue.push_front(index);
        Ok(())
    }

    /// Takes the ground truth of job `index` (its vertex positions) and how it was found;
    /// refits and opens the next batch once the batch is complete, and fits the final
    /// operator once every sample is in.
    pub fn submit(
        &mut self,
        index: usize,
        positions: &[Point],
        iterations: usize,
        fallback: bool,
        warm: bool,
    ) -> Result<Progress, TrainError> {
        if !self.out.get(index).copied().unwrap_or(false) || positions.len() != self.mesh.vertex_count() {
            return Err(TrainError::UnknownJob { index });
        }
        self.out[index] = false;
        self.positions[index] = Some(positions.iter().flatten().copied().collect());
        let tally = if warm { &mut self.stats.warm } else { &mut self.stats.cold };
        tally.0 += 1;
        tally.1 += iterations;
        self.stats.fallbacks += usize::from(fallback);
        if self.positions[..self.batch_end].iter().all(Option::is_some) {
            self.end_batch()?;
        }
        Ok(self.progress())
    }

    /// Solves jobs on this thread until `budget_ms` milliseconds (by `clock`) have passed or
    /// training is done; a job, once begun, is finished.
    pub fn advance(&mut self, budget_ms: f64, clock: fn() -> f64) -> Result<Progress, TrainError> {
        let start = clock();
        while self.result.is_none() {
            let Some(job) = self.next_jobs(1)?.pop() else { break };
            let from = job.start.as_deref().map_or(Start::Rest, Start::Pose);
            match self.solver.solve(&job.targets, from) {
                Ok(report) => {
                    let warm = job.start.is_some();
                    self.submit(job.index, &report.positions, report.iterations, report.fallback, warm)?;
                }
                Err(error) => self.reject(job.index, error)?,
            }
            if clock() - start >= budget_ms {
                break;
            }
        }
        Ok(self.progress())
    }

    /// The trained operator, once [`Progress::done`] equals [`Progress::total`], recording
    /// its training's settings ([`Operator::training`]).
    pub fn finish(self) -> Result<Operator, TrainError> {
        let progress = self.progress();
        let o = &self.options;
        let training =
            Training { energy: o.energy, sampling: o.sampling, samples: o.samples, radius: self.radius, seed: o.seed };
        let operator = self.result.ok_or(TrainError::NotDone { done: progress.done, total: progress.total })?;
        Ok(operator.with_training(Some(training)))
    }

    /// The samples so far (the rest pose is added by the fit).
    fn samples(&self) -> Vec<Sample<'_>> {
        self.targets
            .iter()
            .zip(&self.positions)
            .filter_map(|(t, p)| p.as_ref().map(|p| Sample { targets: t, positions: p }))
            .collect()
    }

    fn end_batch(&mut self) -> Result<(), TrainError> {
        let solved = self.batch_end;
        let k = HandleCoordinates::count(self.handles.len(), self.options.canonical, self.options.fixed.len());
        let kind = if solved == self.options.samples {
            self.options.basis
        } else {
            bootstrap_basis(self.options.basis, k, solved + 1)
        };
        let options = FitOptions::default()
            .with_kind(kind)
            .with_scale(self.radius)
            .with_tps_shortcut(false)
            .with_canonical(self.options.canonical)
            .with_fixed(self.options.fixed.clone());
        let operator = fit(&self.mesh, &self.spatial, &self.handles, &self.samples(), &options)?;
        if solved == self.options.samples {
            self.result = Some(operator.with_puppet(self.options.puppet.clone()));
        } else {
            self.predictor = Some(operator);
            let size = solved.min(self.options.samples - solved);
            self.draw_batch(size);
        }
        Ok(())
    }

    fn draw_batch(&mut self, size: usize) {
        let n = self.handles.len();
        for index in self.batch_end..self.batch_end + size {
            self.targets.push(vec![0.0; 2 * n]);
            self.positions.push(None);
            self.redraws.push(0);
            self.out.push(false);
            self.draw(index);
            self.queue.push_back(index);
        }
        self.batch_end += size;
    }

    /// Draws sample `index`'s targets: key `index` for its first draw, then one key per
    /// redraw beyond every first draw's.
    fn draw(&mut self, index: usize) {
        let redraw = u64::from(self.redraws[index]);
        let key = if redraw == 0 { index as u64 } else { (MAX_SAMPLES as u64) * redraw + index as u64 };
        self.sampler.keyed_into(key, &mut self.targets[index]);
        for &a in &self.options.fixed {
            self.targets[index][2 * a..2 * a + 2].copy_from_slice(&self.rest[2 * a..2 * a + 2]);
        }
    }
}

/// The basis to bootstrap with from `samples` samples (the rest pose included) in
/// `coordinates` handle coordinates: the one asked for when the samples determine it (a TPS
/// always; a polynomial with at least as many samples as functions), else the richest
/// polynomial they do.
fn bootstrap_basis(wanted: BasisKind, coordinates: usize, samples: usize) -> BasisKind {
    if wanted == BasisKind::Tps || wanted.size_in(coordinates, 0) <= samples {
        return wanted;
    }
    [BasisKind::Quadratic, BasisKind::Linear]
        .into_iter()
        .find(|k| k.degree() < wanted.degree() && k.size_in(coordinates, 0) <= samples)
        .unwrap_or(BasisKind::Linear)
}

fn to_points(flat: &[f64]) -> Vec<Point> {
    flat.chunks_exact(2).map(|c| [c[0], c[1]]).collect()
}
