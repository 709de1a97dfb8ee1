//! Times rig frames through the interaction loop (`pose::Poser` with a trained rig), with
//! and without "no foldovers": a drag that folds nothing (the guard's cost is one
//! orientation pass and a copy of the pose per frame), and a drag pulled far across the
//! shape whose frames stop short (each a bisection of `clamp_trials` evaluations). Reads
//! operator files, e.g. those `defop_eval --write` writes (the figure at about 2,000
//! vertices, 9 vertex handles). Prints only; asserts nothing.
//!
//! ```text
//! cargo run --release --example defop_eval -- --write target/defop-bench
//! cargo run --release --example rig_frames -- target/defop-bench/hat.defop target/defop-bench/reduced.defop
//! ```

#[cfg(not(target_arch = "wasm32"))]
fn main() {
    use std::time::Instant;

    use akap::defop::{read_operator, MeshPoint};
    use akap::deform::{AkapOptions, Deformer};
    use akap::pose::{Poser, Tracking};

    let paths: Vec<String> = std::env::args().skip(1).collect();
    if paths.is_empty() {
        eprintln!("usage: rig_frames FILE.defop ...");
        std::process::exit(2);
    }
    let median = |mut v: Vec<f64>| -> f64 {
        v.sort_by(f64::total_cmp);
        if v.is_empty() {
            f64::NAN
        } else {
            v[v.len() / 2]
        }
    };
    for path in paths {
        let (mesh, operator) = read_operator(&std::fs::read(&path).unwrap()).unwrap();
        let vertices: Vec<u32> = operator
            .handles()
            .iter()
            .map(|h| match h {
                MeshPoint::Vertex(v) => *v,
                MeshPoint::Inside { .. } => panic!("{path}: the example takes vertex handles"),
            })
            .collect();
        let size = {
            let p = mesh.positions();
            let extent = |a: usize| {
                let (lo, hi) =
                    p.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), q| (l.min(q[a]), h.max(q[a])));
                hi - lo
            };
            extent(0).max(extent(1))
        };
        println!(
            "{path}: {} vertices, {} triangles, {} handles",
            mesh.vertex_count(),
            mesh.triangle_count(),
            vertices.len()
        );
        for guarded in [false, true] {
            let mut poser = Poser::new(Deformer::new(mesh.clone(), AkapOptions::default()).unwrap());
            poser.set_handle_vertices(&vertices).unwrap();
            poser.set_rig(Some(operator.clone())).unwrap();
            poser.set_tracking(Tracking { no_foldovers: guarded, ..Tracking::default() }).unwrap();
            let rest: Vec<[f64; 2]> = poser.targets().collect();
            let [x, y] = rest[1];
            // A small circle about the rest place of handle 1 (folds nothing), then a drag
            // straight across the shape, through handle 0's place and as far again beyond.
            let circle: Vec<[f64; 2]> = (0..120)
                .map(|k| {
                    let a = std::f64::consts::TAU * k as f64 / 120.0;
                    [x + 0.03 * size * a.cos(), y + 0.03 * size * a.sin()]
                })
                .collect();
            let [x0, y0] = rest[0];
            let across: Vec<[f64; 2]> =
                (1..=120).map(|k| k as f64 / 60.0).map(|t| [x + t * (x0 - x), y + t * (y0 - y)]).collect();
            poser.advance().unwrap();
            poser.grab(1).unwrap();
            let (mut calm, mut stopped, mut free) = (Vec::new(), Vec::new(), Vec::new());
            let frames = |targets: &[[f64; 2]], poser: &mut Poser, calm: &mut Vec<f64>, other: &mut Vec<f64>| {
                for &t in targets {
                    poser.set_target(1, t).unwrap();
                    let start = Instant::now();
                    let report = poser.advance().unwrap();
                    let ms = 1e3 * start.elapsed().as_secs_f64();
                    if report.clamped {
                        other.push(ms)
                    } else {
                        calm.push(ms)
                    }
                }
            };
            frames(&circle, &mut poser, &mut calm, &mut stopped);
            let circle_clamped = stopped.len();
            frames(&across, &mut poser, &mut free, &mut stopped);
            println!(
                "  no foldovers {}: circle {} frames, median {:.3} ms ({} stopped short); across {} frames: {} whole, \
                 median {:.3} ms; {} stopped short, median {:.3} ms",
                if guarded { "on " } else { "off" },
                circle.len(),
                median(calm),
                circle_clamped,
                across.len(),
                free.len(),
                median(free.clone()),
                stopped.len() - circle_clamped,
                median(stopped[circle_clamped..].to_vec()),
            );
        }
    }
}

#[cfg(target_arch = "wasm32")]
fn main() {}
