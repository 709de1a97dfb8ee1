//! The models of the table, their training (timed: solves apart from fits), held-out
//! ground truths, errors and evaluation timings.

use std::hint::black_box;
use std::time::Instant;

use akap::defop::sampling::{Sampler, Sampling};
use akap::defop::{
    fit, BasisKind, Energy, FitOptions, GroundTruth, MeshPoint, Operator, Sample, Start, TrainOptions, TrainStats,
    Trainer,
};
use akap::geometry::{bounding_box, Point};
use akap::triangulate::triangulate_to_about;
use akap::{shapes, Mesh, Outline, TriangulationOptions};

/// The ridge λ of a polynomial fit with fewer samples than functions (on the non-linear
/// coefficients of the handle coordinates scaled by the sampling radius).
pub(crate) const RIDGE: f64 = 1e-3;

/// Seed of the held-out targets (the training uses [`TrainOptions::default`]'s seed, 1).
pub(crate) const HELD_OUT_SEED: u64 = 1_000_003;

/// A model of the table: a mesh, its handles, how to train it and the bases of its rows.
pub(crate) struct Model {
    pub(crate) name: &'static str,
    pub(crate) mesh: Mesh,
    pub(crate) handles: Vec<MeshPoint>,
    pub(crate) options: TrainOptions,
    pub(crate) bases: Vec<BasisKind>,
    /// Whether to fit TPS on the hat functions too (a model with a reduced basis).
    pub(crate) hat_tps: bool,
    /// A remark for the table's notes.
    pub(crate) note: &'static str,
}

/// How big the run is.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Mode {
    Quick,
    Full,
}

impl Mode {
    fn pick<T>(self, quick: T, full: T) -> T {
        match self {
            Self::Quick => quick,
            Self::Full => full,
        }
    }

    pub(crate) fn name(self) -> &'static str {
        self.pick("quick", "full")
    }

    /// Held-out samples per model.
    pub(crate) fn held_out(self) -> usize {
        self.pick(20, 100)
    }

    /// Seconds of evaluation timing per operator.
    pub(crate) fn timing_seconds(self) -> f64 {
        self.pick(0.2, 1.0)
    }
}

/// The mesh of `outline` with about `vertices` vertices, and handles on the vertices
/// nearest to `spots`.
pub(crate) fn mesh_with_handles(outline: &Outline, vertices: usize, spots: &[Point]) -> (Mesh, Vec<MeshPoint>) {
    let (mesh, _) = triangulate_to_about(outline, vertices, &TriangulationOptions::default())
        .unwrap_or_else(|e| panic!("the model triangulates: {e}"));
    let handles = spots
        .iter()
        .map(|s| {
            let nearest = (0..mesh.vertex_count())
                .min_by(|&a, &b| {
                    let d = |v: usize| (mesh.positions()[v][0] - s[0]).hypot(mesh.positions()[v][1] - s[1]);
                    d(a).total_cmp(&d(b))
                })
                .expect("a mesh has vertices");
            MeshPoint::Vertex(nearest as u32)
        })
        .collect();
    (mesh, handles)
}

/// The bar: as in the paper, one moving handle (the right end) and the left end fixed (a
/// handle held at rest in every sample, `TrainOptions::fixed`).
pub(crate) fn bar(mode: Mode) -> Model {
    let [length, height] = shapes::BAR_SIZE;
    let spots = [[0.03 * length, 0.5 * height], [0.97 * length, 0.5 * height]];
    let (mesh, handles) = mesh_with_handles(&shapes::toothed_bar(), mode.pick(300, 600), &spots);
    Model {
        name: "bar",
        mesh,
        handles,
        options: TrainOptions { samples: 16, fixed: vec![0], ..TrainOptions::default() },
        bases: vec![BasisKind::Tps],
        hat_tps: false,
        note: "the left end is a fixed handle (held at rest), the right end the one moving handle",
    }
}

/// All four models.
pub(crate) fn models(mode: Mode) -> Vec<Model> {
    let (aleph, aleph_handles) = mesh_with_handles(&shapes::aleph(), mode.pick(400, 1000), &shapes::aleph_handles());
    let (octopus, octopus_handles) =
        mesh_with_handles(&shapes::octopus(), mode.pick(600, 2000), &shapes::octopus_handles());
    let (crab, crab_handles) = mesh_with_handles(&shapes::crab(), mode.pick(600, 2000), &shapes::crab_handles());
    vec![
        bar(mode),
        Model {
            name: "aleph",
            mesh: aleph,
            handles: aleph_handles,
            options: TrainOptions { samples: mode.pick(59, 399), ..TrainOptions::default() },
            bases: vec![BasisKind::Linear, BasisKind::Cubic, BasisKind::Tps],
            hat_tps: false,
            note: "",
        },
        Model {
            name: "octopus",
            mesh: octopus,
            handles: octopus_handles,
            options: TrainOptions { samples: mode.pick(49, 999), spatial: 100, ..TrainOptions::default() },
            bases: vec![BasisKind::Linear, BasisKind::Quadratic, BasisKind::Tps],
            hat_tps: true,
            note: "",
        },
        Model {
            name: "crab",
            mesh: crab,
            handles: crab_handles,
            options: TrainOptions {
                samples: mode.pick(49, 499),
                spatial: 100,
                energy: Energy::Arap,
                ..TrainOptions::default()
            },
            bases: vec![BasisKind::Linear, BasisKind::Quadratic, BasisKind::Tps],
            hat_tps: false,
            note: "",
        },
    ]
}

/// A trained model: its samples (owned), the solver, timings and the TPS operator.
pub(crate) struct Trained {
    pub(crate) targets: Vec<Vec<f64>>,
    pub(crate) positions: Vec<Vec<f64>>,
    pub(crate) radius: f64,
    pub(crate) rest: Vec<Point>,
    pub(crate) solver: GroundTruth,
    pub(crate) stats: TrainStats,
    /// Seconds in the ground-truth solves.
    pub(crate) solve_seconds: f64,
    /// Seconds in the bootstrap refits between batches.
    pub(crate) refit_seconds: f64,
    /// Seconds of the final fit (the trainer's, with the basis it was asked for).
    pub(crate) final_fit_seconds: f64,
    pub(crate) operator: Operator,
}

impl Trained {
    /// The samples as the fit takes them, the first `count` of them.
    pub(crate) fn samples(&self, count: usize) -> Vec<Sample<'_>> {
        self.targets.iter().zip(&self.positions).take(count).map(|(t, p)| Sample { targets: t, positions: p }).collect()
    }
}

/// Trains `model` on this thread, solving its jobs one by one and timing the solves and the
/// fits (inside [`Trainer::submit`]) apart.
pub(crate) fn train(model: &Model) -> Trained {
    let mut trainer = Trainer::new(&model.mesh, &model.handles, model.options.clone())
        .unwrap_or_else(|e| panic!("{}: {e}", model.name));
    let mut solver = trainer.solver().expect("the trainer's solver");
    let (mut solve_seconds, mut refit_seconds, mut final_fit_seconds) = (0.0, 0.0, 0.0);
    let mut reported = 0;
    while let Some(job) = trainer.next_jobs(1).expect("jobs").pop() {
        let start = Instant::now();
        let solved = solver.solve(&job.targets, job.start.as_deref().map_or(Start::Rest, Start::Pose));
        solve_seconds += start.elapsed().as_secs_f64();
        match solved {
            Ok(report) => {
                let start = Instant::now();
                let progress = trainer
                    .submit(job.index, &report.positions, report.iterations, report.fallback, job.start.is_some())
                    .unwrap_or_else(|e| panic!("{}: {e}", model.name));
                let seconds = start.elapsed().as_secs_f64();
                if progress.stage == "done" {
                    final_fit_seconds = seconds;
                } else {
                    refit_seconds += seconds;
                }
                if 10 * progress.done >= 10 * reported + progress.total {
                    reported = progress.done;
                    eprintln!(
                        "  {}: {}/{} samples, {:.0} s solving",
                        model.name, progress.done, progress.total, solve_seconds
                    );
                }
            }
            Err(e) => trainer.reject(job.index, e).unwrap_or_else(|e| panic!("{}: {e}", model.name)),
        }
    }
    let count = trainer.sample_count();
    let (targets, positions) = (0..count)
        .map(|k| {
            let (t, p) = trainer.sample(k).expect("a drawn sample");
            (t.to_vec(), p.expect("every sample solved").to_vec())
        })
        .unzip();
    let (stats, radius, rest) = (trainer.stats(), trainer.radius(), solver.rest_handle_positions());
    let operator = trainer.finish().unwrap_or_else(|e| panic!("{}: {e}", model.name));
    Trained {
        targets,
        positions,
        radius,
        rest,
        solver,
        stats,
        solve_seconds,
        refit_seconds,
        final_fit_seconds,
        operator,
    }
}

/// The fit options of basis `kind` on `samples` samples (the rest pose added): the ridge
/// when the samples do not determine a polynomial basis.
pub(crate) fn fit_options(kind: BasisKind, handles: usize, samples: usize, radius: f64) -> (FitOptions, bool) {
    let ridge = kind.is_polynomial() && kind.size(handles, 0) > samples + 1;
    let options = FitOptions::default().with_kind(kind).with_scale(radius).with_tps_shortcut(false);
    (if ridge { options.with_regularisation(RIDGE) } else { options }, ridge)
}

/// Fits basis `kind` to the first `count` samples of `trained`; with the seconds it took
/// and whether the ridge was used.
pub(crate) fn fit_basis(model: &Model, trained: &Trained, kind: BasisKind, count: usize) -> (Operator, f64, bool) {
    let spatial = spatial_basis(model);
    let (options, ridge) = fit_options(kind, model.handles.len(), count, trained.radius);
    let start = Instant::now();
    let operator = fit(&model.mesh, &spatial, &model.handles, &trained.samples(count), &options)
        .unwrap_or_else(|e| panic!("{} {kind:?}: {e}", model.name));
    (operator, start.elapsed().as_secs_f64(), ridge)
}

/// TPS on the hat functions, fitted to all of `trained`'s samples (as the trainer's final
/// fit, the interpolation shortcut allowed); with the seconds it took.
pub(crate) fn fit_hat_tps(model: &Model, trained: &Trained) -> (Operator, f64, bool) {
    let options = FitOptions::default().with_kind(BasisKind::Tps).with_scale(trained.radius);
    let start = Instant::now();
    let samples = trained.samples(trained.targets.len());
    let operator = fit(&model.mesh, &akap::defop::SpatialBasis::hat(&model.mesh), &model.handles, &samples, &options)
        .unwrap_or_else(|e| panic!("{} TPS on hat functions: {e}", model.name));
    (operator, start.elapsed().as_secs_f64(), false)
}

/// The model's spatial basis, as its training makes it.
pub(crate) fn spatial_basis(model: &Model) -> akap::defop::SpatialBasis {
    if model.options.spatial == 0 {
        akap::defop::SpatialBasis::hat(&model.mesh)
    } else {
        akap::defop::reduced_basis(&model.mesh, model.options.spatial).expect("the reduced basis")
    }
}

/// Held-out targets (drawn like the training's, another seed) and their ground truths
/// solved from the rest pose; targets whose solve fails are drawn again (counted).
pub(crate) struct HeldOut {
    pub(crate) targets: Vec<Vec<f64>>,
    pub(crate) truths: Vec<Vec<f64>>,
    pub(crate) redrawn: usize,
    pub(crate) seconds: f64,
    /// How far the ground truths move the vertices: the mean over targets of the RMS
    /// distance from the rest pose, relative to the bounding-box diagonal.
    pub(crate) motion: f64,
}

pub(crate) fn held_out(model: &Model, trained: &mut Trained, count: usize) -> HeldOut {
    let (lo, hi) = bounding_box(model.mesh.positions().iter().copied()).expect("a mesh has vertices");
    let mut sampler = Sampler::new(&trained.rest, [lo, hi], trained.radius, Sampling::Disc, HELD_OUT_SEED)
        .expect("the training's sampler accepted these handles");
    assert_eq!(model.options.sampling, Sampling::Disc, "held-out targets are drawn as the training's");
    let start = Instant::now();
    let (mut targets, mut truths, mut redrawn): (_, Vec<Vec<f64>>, _) = (Vec::new(), Vec::new(), 0);
    while targets.len() < count {
        let mut t = sampler.take(1);
        for &h in &model.options.fixed {
            t[2 * h..2 * h + 2].copy_from_slice(&trained.rest[h]);
        }
        let points: Vec<Point> = t.chunks_exact(2).map(|c| [c[0], c[1]]).collect();
        match trained.solver.solve(&points, Start::Rest) {
            Ok(report) => {
                truths.push(report.positions.iter().flatten().copied().collect());
                targets.push(t);
            }
            Err(_) => redrawn += 1,
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    let rest: Vec<f64> = model.mesh.positions().iter().flatten().copied().collect();
    let motion = truths.iter().map(|t| rms_distance(t, &rest)).sum::<f64>() / count as f64 / diagonal(&model.mesh);
    HeldOut { targets, truths, redrawn, seconds, motion }
}

/// The bounding-box diagonal of a mesh at rest.
pub(crate) fn diagonal(mesh: &Mesh) -> f64 {
    let (lo, hi) = bounding_box(mesh.positions().iter().copied()).expect("a mesh has vertices");
    (hi[0] - lo[0]).hypot(hi[1] - lo[1])
}

/// The RMS distance between two poses (2 numbers per vertex each).
fn rms_distance(a: &[f64], b: &[f64]) -> f64 {
    let squares: f64 =
        a.chunks_exact(2).zip(b.chunks_exact(2)).map(|(p, q)| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sum();
    (2.0 * squares / a.len() as f64).sqrt()
}

/// Errors of `operator` on the held-out samples, relative to the bounding-box diagonal:
/// the mean over samples of the RMS vertex distance, and the largest vertex distance.
pub(crate) fn error(model: &Model, operator: &mut Operator, held: &HeldOut) -> (f64, f64) {
    let mut out = vec![0.0; 2 * model.mesh.vertex_count()];
    let (mut rms, mut max) = (0.0, 0.0f64);
    for (t, truth) in held.targets.iter().zip(&held.truths) {
        operator.evaluate_into(t, &mut out).expect("targets of the right length");
        rms += rms_distance(&out, truth);
        for (a, b) in out.chunks_exact(2).zip(truth.chunks_exact(2)) {
            max = max.max((a[0] - b[0]).hypot(a[1] - b[1]));
        }
    }
    let diagonal = diagonal(&model.mesh);
    (rms / held.targets.len() as f64 / diagonal, max / diagonal)
}

/// Milliseconds per evaluation, natively: a loop over the held-out targets for `seconds`.
pub(crate) fn evaluation_ms(operator: &mut Operator, held: &HeldOut, seconds: f64) -> f64 {
    let mut out = vec![0.0; 2 * operator.vertex_count()];
    for t in &held.targets {
        operator.evaluate_into(t, &mut out).expect("targets of the right length");
    }
    let (start, mut calls) = (Instant::now(), 0usize);
    while start.elapsed().as_secs_f64() < seconds {
        for t in &held.targets {
            operator.evaluate_into(black_box(t), &mut out).expect("as above");
            calls += 1;
        }
        black_box(&out);
    }
    1e3 * start.elapsed().as_secs_f64() / calls as f64
}
