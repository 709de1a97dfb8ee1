//! The DefOp ground-truth solver's cost: the gingerbread figure meshed to about 2,000
//! vertices, 5 vertex handles (head, hands, feet), 20 random targets (each handle
//! uniform in a disc of radius 0.1 times the shape's bounding-box diagonal around its rest
//! position). Per energy (S-ARAP, ARAP): solves cold (from the rest pose, with the
//! homotopy) and warm (from the cold solution of a nearby target: every handle moved by up
//! to 0.01 of the size); and the crate's local/global [`Deformer`] run to convergence
//! on the same cold targets, in the same run. Prints numbers only.
//!
//! `cargo run --release --example ground_truth`

use std::time::Instant;

use akap::defop::{Energy, GroundTruth, GroundTruthOptions, Handles, Start};
use akap::deform::{ArapOptions, Deformer};
use akap::geometry::Point;
use akap::shapes::gingerbread;
use akap::triangulate::triangulate_to_about;
use akap::{Mesh, TriangulationOptions};

struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in the disc of radius `r` (area-uniform).
    fn in_disc(&mut self, r: f64) -> Point {
        let (radius, angle) = (r * self.unit().sqrt(), std::f64::consts::TAU * self.unit());
        [radius * angle.cos(), radius * angle.sin()]
    }
}

fn nearest(mesh: &Mesh, p: Point) -> u32 {
    let d = |q: &Point| (q[0] - p[0]).hypot(q[1] - p[1]);
    (0..mesh.vertex_count()).min_by(|&a, &b| d(&mesh.positions()[a]).total_cmp(&d(&mesh.positions()[b]))).unwrap()
        as u32
}

fn max_distance(a: &[Point], b: &[Point]) -> f64 {
    a.iter().zip(b).map(|(p, q)| (p[0] - q[0]).hypot(p[1] - q[1])).fold(0.0, f64::max)
}

/// Mean milliseconds, mean and largest iteration counts, and totals of stages and fallbacks.
#[derive(Default)]
struct Row {
    ms: Vec<f64>,
    iterations: Vec<usize>,
    stages: usize,
    fallbacks: usize,
}

impl Row {
    fn print(&self, label: &str) {
        let n = self.ms.len() as f64;
        println!(
            "| {label} | {:.2} | {:.1} | {} | {:.2} | {} |",
            self.ms.iter().sum::<f64>() / n,
            self.iterations.iter().sum::<usize>() as f64 / n,
            self.iterations.iter().max().unwrap(),
            self.stages as f64 / n,
            self.fallbacks
        );
    }
    fn mean_ms(&self) -> f64 {
        self.ms.iter().sum::<f64>() / self.ms.len() as f64
    }
}

fn main() {
    let (mesh, edge) = triangulate_to_about(&gingerbread(), 2000, &TriangulationOptions::default()).unwrap();
    let (lo, hi) = mesh.positions().iter().fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(lo, hi), p| {
        ([lo[0].min(p[0]), lo[1].min(p[1])], [hi[0].max(p[0]), hi[1].max(p[1])])
    });
    let size = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    let at = |fx: f64, fy: f64| [lo[0] + fx * (hi[0] - lo[0]), lo[1] + fy * (hi[1] - lo[1])];
    // Head, hands, feet.
    let handles: Vec<u32> = [at(0.5, 0.93), at(0.04, 0.62), at(0.96, 0.62), at(0.25, 0.04), at(0.75, 0.04)]
        .map(|p| nearest(&mesh, p))
        .to_vec();
    let rest: Vec<Point> = handles.iter().map(|&v| mesh.positions()[v as usize]).collect();
    let mut rng = Rng(2024);
    let samples = 20;
    let targets: Vec<Vec<Point>> = (0..samples)
        .map(|_| {
            rest.iter()
                .map(|p| {
                    let d = rng.in_disc(0.1 * size);
                    [p[0] + d[0], p[1] + d[1]]
                })
                .collect()
        })
        .collect();
    let nearby: Vec<Vec<Point>> = targets
        .iter()
        .map(|t| {
            t.iter()
                .map(|p| {
                    let d = rng.in_disc(0.01 * size);
                    [p[0] + d[0], p[1] + d[1]]
                })
                .collect()
        })
        .collect();
    println!(
        "gingerbread: {} vertices, {} triangles (edge {:.4}), size {:.3}, {} vertex handles, {samples} targets in discs of radius 0.1 size",
        mesh.vertex_count(),
        mesh.triangle_count(),
        edge,
        size,
        handles.len()
    );
    let options = GroundTruthOptions::default();
    println!("ground truth: tolerance {:e} (gradient, relative to size)\n", options.tolerance);
    println!("| solve | mean ms | mean Newton iterations | max iterations | mean stages | fallbacks |");
    println!("|---|---|---|---|---|---|");
    let mut arap_solutions = Vec::new();
    let mut ground_truth_cold = 0.0;
    for energy in [Energy::SArap, Energy::Arap] {
        let t0 = Instant::now();
        let mut gt = GroundTruth::new(&mesh, Handles::Vertices(&handles), energy, options).unwrap();
        let setup = t0.elapsed().as_secs_f64() * 1e3;
        let (mut cold, mut warm) = (Row::default(), Row::default());
        for (target, near) in targets.iter().zip(&nearby) {
            let t = Instant::now();
            let report = gt.solve(target, Start::Rest).unwrap();
            cold.ms.push(t.elapsed().as_secs_f64() * 1e3);
            cold.iterations.push(report.iterations);
            cold.stages += report.stages;
            let t = Instant::now();
            let again = gt.solve(near, Start::Pose(&report.positions)).unwrap();
            warm.ms.push(t.elapsed().as_secs_f64() * 1e3);
            warm.iterations.push(again.iterations);
            warm.stages += again.stages;
            warm.fallbacks += usize::from(again.fallback);
            if energy == Energy::Arap {
                arap_solutions.push(report.positions);
            }
        }
        cold.print(&format!("{energy} cold (set-up {setup:.1} ms)"));
        warm.print(&format!("{energy} warm"));
        if energy == Energy::Arap {
            ground_truth_cold = cold.mean_ms();
        }
    }
    let tolerance = 1e-9;
    let mut arap = Deformer::new(mesh.clone(), ArapOptions::default().until_converged(tolerance, 1_000_000)).unwrap();
    arap.set_handle_vertices(&handles).unwrap();
    let mut local_global = Row::default();
    let mut difference: f64 = 0.0;
    let mut minima = Vec::new();
    let checker = GroundTruth::new(&mesh, Handles::Vertices(&handles), Energy::Arap, options).unwrap();
    for (target, solution) in targets.iter().zip(&arap_solutions) {
        arap.reset();
        let velocities: Vec<Point> = rest.iter().zip(target).map(|(p, q)| [q[0] - p[0], q[1] - p[1]]).collect();
        let t = Instant::now();
        arap.step(&velocities).unwrap();
        local_global.ms.push(t.elapsed().as_secs_f64() * 1e3);
        local_global.iterations.push(arap.arap().expect("ARAP").report().iterations);
        let apart = max_distance(arap.positions(), solution);
        if apart <= 1e-5 * size {
            difference = difference.max(apart);
        } else {
            // Another local minimum: say which is lower.
            minima.push((checker.energy_of(arap.positions()).unwrap(), checker.energy_of(solution).unwrap(), apart));
        }
    }
    local_global.print(&format!("local/global ARAP cold, until moves <= {tolerance:e} size"));
    println!(
        "\nlocal/global over Newton ARAP (cold, mean ms): {:.1}x; {} of {samples} targets reach the same pose \
         (largest vertex difference {:.1e} of the size)",
        local_global.mean_ms() / ground_truth_cold,
        samples - minima.len(),
        difference / size
    );
    for (theirs, ours, apart) in minima {
        println!(
            "  another local minimum: local/global energy {theirs:.6e}, Newton {ours:.6e}, {:.3} of the size apart",
            apart / size
        );
    }
}
