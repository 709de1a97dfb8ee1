//! DefOp training by bootstrapping, against what the method guarantees: a TPS operator
//! reproduces every ground-truth sample it was trained on (Prop. 1) and the rest pose, and
//! puts the handles on any targets; the same seed gives the same operator whether the
//! samples are solved here in time slices or by separate solvers in any order ("workers");
//! a solve started from the operator's prediction at a sample's targets needs at most one
//! Newton step; a canonical operator moves rigidly with rigid motions of its handles and
//! still reproduces its samples; a fixed handle is at rest in every sample and stays there
//! (the paper's bar: left end fixed, right end moving, 17 samples); bad calls are refused
//! with typed errors. Runs natively and as wasm.

use akap::defop::{
    BasisKind, Energy, FitError, MeshPoint, Operator, Start, TrainError, TrainOptions, TrainStats, Trainer,
};
use akap::geometry::Point;
use akap::shapes::toothed_bar;
use akap::{triangulate, Mesh, TriangulationOptions};
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

fn bar() -> Mesh {
    triangulate(&toothed_bar(), &TriangulationOptions::default().with_target_edge_length(0.15)).unwrap()
}

fn nearest(mesh: &Mesh, p: Point) -> u32 {
    let d = |q: &Point| (q[0] - p[0]).hypot(q[1] - p[1]);
    (0..mesh.vertex_count()).min_by(|&a, &b| d(&mesh.positions()[a]).total_cmp(&d(&mesh.positions()[b]))).unwrap()
        as u32
}

/// The bar's two ends (vertices) and a point inside a middle triangle.
fn handles(mesh: &Mesh) -> Vec<MeshPoint> {
    let middle = mesh
        .triangles()
        .iter()
        .position(|t| t.iter().all(|&v| mesh.positions()[v as usize][0].abs() < 0.3))
        .expect("a triangle near the middle");
    vec![
        MeshPoint::Vertex(nearest(mesh, [-1.0, 0.0])),
        MeshPoint::Vertex(nearest(mesh, [1.0, 0.0])),
        MeshPoint::Inside { triangle: middle as u32, barycentric: [0.2, 0.3, 0.5] },
    ]
}

fn options(samples: usize) -> TrainOptions {
    TrainOptions { samples, seed: 7, energy: Energy::Arap, ..TrainOptions::default() }
}

/// A clock that never moves: each `advance` with budget 0 runs one job.
fn frozen() -> f64 {
    0.0
}

/// The samples a training solved (targets, ground truth), its stats and its operator.
struct Trained {
    samples: Vec<(Vec<f64>, Vec<f64>)>,
    stats: TrainStats,
    operator: Operator,
}

fn samples_of(trainer: &Trainer) -> Vec<(Vec<f64>, Vec<f64>)> {
    (0..trainer.sample_count())
        .map(|k| {
            let (t, p) = trainer.sample(k).unwrap();
            (t.to_vec(), p.expect("every sample is solved").to_vec())
        })
        .collect()
}

/// Trains on this thread, one job per `advance`.
fn train_here(mesh: &Mesh, options: TrainOptions) -> Trained {
    train_with(mesh, &handles(mesh), options)
}

/// [`train_here`] with these handles.
fn train_with(mesh: &Mesh, handles: &[MeshPoint], options: TrainOptions) -> Trained {
    let mut trainer = Trainer::new(mesh, handles, options).unwrap();
    let mut calls = 0;
    while trainer.progress().stage != "done" {
        trainer.advance(0.0, frozen).unwrap();
        calls += 1;
        assert!(calls < 10_000, "training does not end");
    }
    let (samples, stats) = (samples_of(&trainer), trainer.stats());
    Trained { samples, stats, operator: trainer.finish().unwrap() }
}

fn size(mesh: &Mesh) -> f64 {
    let (lo, hi) = akap::geometry::bounding_box(mesh.positions().iter().copied()).unwrap();
    (hi[0] - lo[0]).hypot(hi[1] - lo[1])
}

#[test]
fn a_tps_operator_reproduces_its_samples_the_rest_pose_and_any_handle_targets() {
    let mesh = bar();
    let mut trained = train_here(&mesh, options(14));
    let (scale, n) = (size(&mesh), handles(&mesh).len());
    assert_eq!(trained.samples.len(), 14);
    for (k, (targets, truth)) in trained.samples.iter().enumerate() {
        let predicted = trained.operator.evaluate(targets).unwrap();
        let error = predicted.iter().zip(truth).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        assert!(error <= 1e-8 * scale, "sample {k} reproduced to {error:e}");
    }
    // The rest pose is the identity.
    let rest: Vec<f64> = handles(&mesh)
        .iter()
        .flat_map(|h| match *h {
            MeshPoint::Vertex(v) => mesh.positions()[v as usize],
            MeshPoint::Inside { triangle, barycentric } => {
                let t = mesh.triangles()[triangle as usize];
                let p = |k: usize| mesh.positions()[t[k] as usize];
                [0, 1].map(|c| (0..3).map(|k| barycentric[k] * p(k)[c]).sum::<f64>())
            }
        })
        .collect();
    let identity = trained.operator.evaluate(&rest).unwrap();
    let flat: Vec<f64> = mesh.positions().iter().flatten().copied().collect();
    let error = identity.iter().zip(&flat).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    assert!(error <= 1e-10 * scale, "rest pose off by {error:e}");
    // Handles land on targets far outside the training discs.
    let far: Vec<f64> =
        rest.iter().enumerate().map(|(i, x)| x + [0.9, -0.7, 0.4, 1.1, -0.8, 0.3][i % (2 * n)]).collect();
    let posed = trained.operator.evaluate(&far).unwrap();
    for (h, handle) in handles(&mesh).iter().enumerate() {
        let at = match *handle {
            MeshPoint::Vertex(v) => [posed[2 * v as usize], posed[2 * v as usize + 1]],
            MeshPoint::Inside { triangle, barycentric } => {
                let t = mesh.triangles()[triangle as usize];
                [0, 1].map(|c| (0..3).map(|k| barycentric[k] * posed[2 * t[k] as usize + c]).sum::<f64>())
            }
        };
        let miss = (at[0] - far[2 * h]).hypot(at[1] - far[2 * h + 1]);
        assert!(miss <= 1e-9 * scale, "handle {h} misses by {miss:e}");
    }
}

#[test]
fn the_same_seed_gives_the_same_operator_here_and_on_workers_in_any_order() {
    let mesh = bar();
    let mut here = train_here(&mesh, options(12));

    let mut trainer = Trainer::new(&mesh, &handles(&mesh), options(12)).unwrap();
    let mut workers = [trainer.solver().unwrap(), trainer.solver().unwrap()];
    let mut rounds = 0;
    while trainer.progress().stage != "done" {
        let mut jobs = trainer.next_jobs(3).unwrap();
        assert!(!jobs.is_empty(), "a pending batch always has jobs once the last is in");
        jobs.reverse();
        for (k, job) in jobs.iter().enumerate() {
            let solver = &mut workers[k % 2];
            let start = job.start.as_deref().map_or(Start::Rest, Start::Pose);
            match solver.solve(&job.targets, start) {
                Ok(r) => {
                    trainer.submit(job.index, &r.positions, r.iterations, r.fallback, job.start.is_some()).map(drop)
                }
                Err(error) => trainer.reject(job.index, error),
            }
            .unwrap();
        }
        rounds += 1;
        assert!(rounds < 1000);
    }
    assert_eq!(samples_of(&trainer), here.samples, "the same samples, solved to the same bits");
    let mut there = trainer.finish().unwrap();
    for (targets, _) in &here.samples {
        assert_eq!(there.evaluate(targets).unwrap(), here.operator.evaluate(targets).unwrap());
    }
}

#[test]
fn training_warm_starts_and_its_operator_predicts_its_samples_exactly() {
    let mesh = bar();
    let s_arap = TrainOptions { energy: Energy::SArap, ..options(24) };
    let stats = train_here(&mesh, s_arap).stats;
    // 2n + 1 = 7 cold solves, then warm ones (from the operator's prediction, or the
    // nearest solved sample where the prediction folds a triangle); targets that no
    // flip-free pose reaches are drawn again.
    assert_eq!((stats.cold.0, stats.warm.0), (7, 17), "{stats:?}");
    // A TPS operator reproduces its samples, so a solve started from its prediction at a
    // sample's targets starts at that sample's minimum and stays there: with ARAP (smooth)
    // in at most one Newton step; with S-ARAP (whose kink at similarities may take the
    // solver a few steps to settle) at the same pose and energy.
    let scale = size(&mesh);
    for energy in [Energy::Arap, Energy::SArap] {
        let options = TrainOptions { energy, ..options(12) };
        let mut trained = train_here(&mesh, options.clone());
        let mut solver = Trainer::new(&mesh, &handles(&mesh), options).unwrap().solver().unwrap();
        for (targets, truth) in &trained.samples {
            let predicted = trained.operator.evaluate(targets).unwrap();
            let start: Vec<Point> = predicted.chunks(2).map(|c| [c[0], c[1]]).collect();
            let goal: Vec<Point> = targets.chunks(2).map(|c| [c[0], c[1]]).collect();
            let report = solver.solve(&goal, Start::Pose(&start)).unwrap();
            assert!(!report.fallback);
            if energy == Energy::Arap {
                assert!(report.iterations <= 1, "{} iterations", report.iterations);
            }
            let error = report.positions.iter().flatten().zip(truth).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
            assert!(error <= 1e-6 * scale, "{energy:?}: {error:e} from the sample's minimum");
            let truth: Vec<Point> = truth.chunks(2).map(|c| [c[0], c[1]]).collect();
            let sample_energy = solver.energy_of(&truth).unwrap();
            assert!(report.energy >= sample_energy * (1.0 - 1e-9), "{energy:?}: the sample was no minimum");
        }
    }
}

#[test]
fn polynomial_bases_bootstrap_through_the_smaller_ones() {
    let mesh = bar();
    // n = 3: quadratic needs 1 + 9 + 18 = 28 samples with the rest pose.
    let quadratic = TrainOptions { basis: BasisKind::Quadratic, ..options(30) };
    let trained = train_here(&mesh, quadratic);
    assert_eq!(trained.operator.handle_basis().kind(), BasisKind::Quadratic);
    // Too few to determine the basis: refused before any solve, saying how many it needs.
    let too_few = TrainOptions { basis: BasisKind::Quadratic, ..options(20) };
    let error = Trainer::new(&mesh, &handles(&mesh), too_few).unwrap_err();
    assert_eq!(error, TrainError::TooFewSamples { samples: 20, needed: 27 });
    assert!(error.to_string().contains("at least 27"), "{error}");
    // TPS needs its linear part: 2n + 1 = 7 functions, so 6 samples and the rest pose.
    let tps = |samples| Trainer::new(&mesh, &handles(&mesh), options(samples)).map(|_| ());
    assert_eq!(tps(5), Err(TrainError::TooFewSamples { samples: 5, needed: 6 }));
    assert_eq!(tps(6), Ok(()));
}

#[test]
fn bad_calls_are_refused() {
    let mesh = bar();
    let h = handles(&mesh);
    let zero = Trainer::new(&mesh, &h, options(0)).unwrap_err();
    assert!(matches!(zero, TrainError::InvalidOption { name: "samples", .. }));
    let outside = [MeshPoint::Vertex(mesh.vertex_count() as u32)];
    assert!(Trainer::new(&mesh, &outside, options(6)).is_err());

    let mut trainer = Trainer::new(&mesh, &h, options(6)).unwrap();
    let job = trainer.next_jobs(1).unwrap().remove(0);
    let solved = trainer.solver().unwrap().solve(&job.targets, Start::Rest).unwrap();
    // A job not handed out, a wrong size, then the right one, then the same again.
    assert_eq!(trainer.submit(3, &solved.positions, 1, false, false), Err(TrainError::UnknownJob { index: 3 }));
    assert!(trainer.submit(job.index, &solved.positions[1..], 1, false, false).is_err());
    trainer.submit(job.index, &solved.positions, solved.iterations, false, false).unwrap();
    assert_eq!(
        trainer.submit(job.index, &solved.positions, 1, false, false),
        Err(TrainError::UnknownJob { index: job.index })
    );
    assert_eq!(trainer.progress().done, 1);
    assert!(matches!(trainer.finish(), Err(TrainError::NotDone { done: 1, total: 7 })));
}

/// Every point of `flat` rotated by θ about the origin, then shifted by t.
fn moved(flat: &[f64], theta: f64, t: [f64; 2]) -> Vec<f64> {
    let (s, c) = theta.sin_cos();
    flat.chunks_exact(2).flat_map(|p| [c * p[0] - s * p[1] + t[0], s * p[0] + c * p[1] + t[1]]).collect()
}

fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

#[test]
fn a_canonical_operator_moves_rigidly_and_reproduces_its_samples() {
    let mesh = bar();
    let canonical = TrainOptions { canonical: true, ..options(12) };
    let mut trained = train_here(&mesh, canonical);
    let scale = size(&mesh);
    let operator = &mut trained.operator;
    assert_eq!(operator.handle_basis().coordinate_count(), 3);
    // The rest targets: where the rest pose puts the handles (exact, a constraint).
    let identity: Vec<f64> = mesh.positions().iter().flatten().copied().collect();
    let rest = operator.handle_basis().rest().to_vec();
    assert!(max_difference(&operator.evaluate(&rest).unwrap(), &identity) <= 1e-10 * scale);
    for (k, (theta, t)) in [(0.5, [0.3, -2.0]), (-2.5, [4.0, 1.0]), (3.0, [0.0, 0.0])].into_iter().enumerate() {
        let error = max_difference(&operator.evaluate(&moved(&rest, theta, t)).unwrap(), &moved(&identity, theta, t));
        assert!(error <= 1e-9 * scale, "motion {k}: off by {error:e}");
        let (q, _) = &trained.samples[k];
        let expected = moved(&operator.evaluate(q).unwrap(), theta, t);
        let error = max_difference(&operator.evaluate(&moved(q, theta, t)).unwrap(), &expected);
        assert!(error <= 1e-9 * scale, "sample {k} moved: off by {error:e}");
    }
    // ARAP is rigid-invariant: the canonicalised samples are ground truths too, and a TPS
    // interpolates them; moved back, the operator reproduces the samples.
    for (k, (targets, truth)) in trained.samples.iter().enumerate() {
        let error = max_difference(&operator.evaluate(targets).unwrap(), truth);
        assert!(error <= 1e-8 * scale, "sample {k} reproduced to {error:e}");
    }
}

/// The paper's bar (Table 1): the left end fixed, the right end moving, 17 samples.
#[test]
fn a_fixed_handle_stays_at_rest() {
    let mesh = bar();
    let ends = [MeshPoint::Vertex(nearest(&mesh, [-1.0, 0.0])), MeshPoint::Vertex(nearest(&mesh, [1.0, 0.0]))];
    let [left, right] = ends.map(|h| match h {
        MeshPoint::Vertex(v) => v as usize,
        MeshPoint::Inside { .. } => unreachable!(),
    });
    let rest = mesh.positions()[left];
    let fixed = TrainOptions { fixed: vec![0], samples: 17, seed: 3, ..TrainOptions::default() };
    let mut trained = train_with(&mesh, &ends, fixed);
    let scale = size(&mesh);
    assert_eq!(trained.samples.len(), 17);
    assert_eq!(trained.operator.handle_basis().len(), 1 + 2 + 18, "TPS: 1 + k + m, k = 2");
    for (targets, truth) in &trained.samples {
        assert_eq!(targets[..2], rest, "the fixed handle is sampled at rest");
        assert!(max_difference(&truth[2 * left..2 * left + 2], &rest) <= 1e-9 * scale);
        let error = max_difference(&trained.operator.evaluate(targets).unwrap(), truth);
        assert!(error <= 1e-8 * scale, "sample reproduced to {error:e}");
    }
    for q in [[5.0, -3.0, 1.4, 0.6], [-1.0, 0.0, 0.2, -0.9], [0.0, 2.0, 3.0, 3.0]] {
        let posed = trained.operator.evaluate(&q).unwrap();
        assert!(max_difference(&posed[2 * left..2 * left + 2], &rest) <= 1e-9 * scale, "the fixed end moved");
        assert!(max_difference(&posed[2 * right..2 * right + 2], &q[2..]) <= 1e-9 * scale, "the free end missed");
    }
    let both = TrainOptions { fixed: vec![0], canonical: true, ..TrainOptions::default() };
    assert_eq!(Trainer::new(&mesh, &ends, both).unwrap_err(), TrainError::Fit(FitError::CanonicalWithFixed));
    let outside = TrainOptions { fixed: vec![2], ..TrainOptions::default() };
    assert_eq!(
        Trainer::new(&mesh, &ends, outside).unwrap_err(),
        TrainError::Fit(FitError::InvalidFixedHandle { index: 2 })
    );
}
