//! Where the time of a DefOp training goes, on the app's default figure with the app's
//! training defaults, and how it compares with solving the same samples cold.
//!
//! The figure is `shapes::gingerbread` meshed to about 1,500 vertices (the widget's
//! default), with nine vertex handles spread over it (those of `bench-defop.mjs`); the
//! training is the widget's default (S-ARAP, TPS, 200 samples, discs of 15% of the
//! diagonal, the reduced spatial basis of 100). Printed: the training's time split into
//! ground-truth solves (cold and warm, with mean Newton iterations), the bootstrap refits
//! and the final fit; the time of solving the same samples' targets from the rest pose to
//! full accuracy (the default tolerance, 1e-9), and the ratio of the two; the held-out
//! error (100 targets drawn like the training's with another seed, solved cold to full
//! accuracy; RMS and max vertex distance in % of the diagonal).
//!
//! ```sh
//! cargo run --release --example train_speed -- [--vertices N] [--samples M] [--spatial K]
//!     [--energy sarap|arap] [--tolerance T] [--no-cold]
//! ```
//! `--tolerance` sets the training's ground-truth tolerance (default: the trainer's);
//! `--no-cold` skips the cold baseline.

#[allow(dead_code)]
#[path = "defop_table/models.rs"]
mod models;

use std::time::Instant;

use akap::defop::{Energy, Start, TrainOptions, Trainer};
use akap::geometry::Point;
use akap::shapes;

/// The handles of `bench-defop.mjs` on the figure: the vertices nearest these points.
const SPOTS: [Point; 9] = [
    [-0.48, 1.2],
    [0.45, 0.95],
    [0.0, 1.25],
    [0.0, 0.7],
    [-0.2, 0.05],
    [0.2, 0.05],
    [-0.3, 0.6],
    [0.3, 0.6],
    [0.0, 0.4],
];

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |name: &str| args.iter().position(|a| a == name).map(|i| args[i + 1].clone());
    let number = |name: &str, default: f64| value(name).map_or(default, |v| v.parse::<f64>().expect("a number"));
    let vertices = number("--vertices", 1500.0) as usize;
    let energy = match value("--energy").as_deref() {
        Some("arap") => Energy::Arap,
        _ => Energy::SArap,
    };
    let mut options = TrainOptions {
        samples: number("--samples", 200.0) as usize,
        spatial: number("--spatial", 100.0) as usize,
        energy,
        ..TrainOptions::default()
    };
    if let Some(t) = value("--tolerance") {
        options.ground_truth.tolerance = t.parse().expect("a tolerance");
    }
    let (mesh, handles) = models::mesh_with_handles(&shapes::gingerbread(), vertices, &SPOTS);
    let model = models::Model {
        name: "figure",
        mesh,
        handles,
        options: options.clone(),
        bases: Vec::new(),
        hat_tps: false,
        note: "",
    };
    println!(
        "figure: {} vertices, {} triangles, {} handles; {:?}, {} samples, spatial {}, tolerance {:e}",
        model.mesh.vertex_count(),
        model.mesh.triangle_count(),
        model.handles.len(),
        options.energy,
        options.samples,
        options.spatial,
        options.ground_truth.tolerance
    );
    let start = Instant::now();
    let mut trained = models::train(&model);
    let total = start.elapsed().as_secs_f64();
    let s = trained.stats;
    println!();
    println!("| stage | seconds | share |");
    println!("|---|--:|--:|");
    let share = |x: f64| format!("{:.0}%", 100.0 * x / total);
    println!("| ground-truth solves | {:.2} | {} |", trained.solve_seconds, share(trained.solve_seconds));
    println!("| bootstrap refits | {:.2} | {} |", trained.refit_seconds, share(trained.refit_seconds));
    println!("| final fit | {:.2} | {} |", trained.final_fit_seconds, share(trained.final_fit_seconds));
    println!("| training in all | {total:.2} | 100% |");
    println!();
    println!(
        "solves: {} cold ({:.1} iterations), {} warm ({:.1} iterations), {} neighbour starts, {} fallbacks, {} redraws",
        s.cold.0,
        s.mean_cold(),
        s.warm.0,
        s.mean_warm(),
        s.neighbour_starts,
        s.fallbacks,
        s.redraws
    );
    // Full accuracy from here on: the cold baseline and the held-out truths.
    let full = TrainOptions { ground_truth: Default::default(), ..options.clone() };
    trained.solver = Trainer::solver_for(&model.mesh, &model.handles, &full).expect("the solver");
    if !args.iter().any(|a| a == "--no-cold") {
        let (start, mut iterations, mut failed) = (Instant::now(), 0, 0);
        for t in &trained.targets {
            let points: Vec<Point> = t.chunks_exact(2).map(|c| [c[0], c[1]]).collect();
            match trained.solver.solve(&points, Start::Rest) {
                Ok(report) => iterations += report.iterations,
                Err(_) => failed += 1,
            }
        }
        let cold = start.elapsed().as_secs_f64();
        let solved = trained.targets.len() - failed;
        println!(
            "cold to full accuracy: {cold:.2} s for the {} samples' targets ({:.1} iterations each, {failed} failed); \
             training / cold = {:.2}",
            trained.targets.len(),
            iterations as f64 / solved.max(1) as f64,
            total / cold
        );
    }
    let held = models::held_out(&model, &mut trained, 100);
    let (rms, max) = models::error(&model, &mut trained.operator, &held);
    println!(
        "held-out (100 targets, {} redrawn): RMS {:.3}%, max {:.3}% of the diagonal",
        held.redrawn,
        100.0 * rms,
        100.0 * max
    );
}
