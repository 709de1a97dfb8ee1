//! Per-frame timings of the AKAP deformer natively: a scripted drag on the built-in
//! figure at several mesh sizes, printing median and 95th-percentile milliseconds per
//! stage. `cargo run --release --example deformer_frames [-- 1000 5000 10000]`.

use akap::deform::{AkapOptions, Deformer};
use akap::triangulate::triangulate_to_about;
use akap::{shapes, TriangulationOptions};

fn percentile(values: &mut [f64], q: f64) -> f64 {
    values.sort_by(f64::total_cmp);
    values[((values.len() - 1) as f64 * q).round() as usize]
}

fn main() {
    let sizes: Vec<usize> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let sizes = if sizes.is_empty() { vec![1000, 5000, 10000, 50000] } else { sizes };
    let figure = shapes::gingerbread();
    println!("| vertices | triangles | nnz(L) step 1 | assembly | factorisation | solve | integration | frame (median / p95) |");
    println!("|---|---|---|---|---|---|---|---|");
    for target in sizes {
        let options = TriangulationOptions::default().with_max_vertices(4 * target);
        let (mesh, _) = triangulate_to_about(&figure, target, &options).expect("the figure triangulates");
        let n = mesh.vertex_count();
        let m = mesh.triangle_count();
        let feet: Vec<u32> = (0..n as u32).filter(|&v| mesh.positions()[v as usize][1] < 0.0).collect();
        let hand = (0..n as u32)
            .min_by(|&a, &b| {
                let d = |v: u32| {
                    let p = mesh.positions()[v as usize];
                    (p[0] + 0.48).hypot(p[1] - 1.2)
                };
                d(a).total_cmp(&d(b))
            })
            .expect("vertices");
        let mut deformer = Deformer::new(mesh, AkapOptions::default()).expect("connected mesh");
        let mut handles = feet.clone();
        handles.push(hand);
        deformer.set_handle_vertices(&handles).expect("valid handles");
        let mut stages: [Vec<f64>; 5] = Default::default();
        for frame in 0..40 {
            let mut v = vec![[0.0, 0.0]; handles.len()];
            let t = frame as f64 / 40.0 * std::f64::consts::TAU;
            *v.last_mut().expect("hand") = [0.01 * t.cos(), 0.01 * t.sin()];
            let start = std::time::Instant::now();
            deformer.step(&v).expect("step");
            let total = start.elapsed().as_secs_f64() * 1e3;
            let timings = deformer.timings();
            for (s, x) in stages.iter_mut().zip([
                timings.assembly,
                timings.factorisation,
                timings.solve,
                timings.integration,
                total,
            ]) {
                s.push(x);
            }
        }
        let (nnz, _) = deformer.akap().expect("AKAP").factor_stats();
        let med: Vec<String> = stages.iter_mut().map(|s| format!("{:.2}", percentile(s, 0.5))).collect();
        let p95 = percentile(&mut stages[4], 0.95);
        println!("| {n} | {m} | {nnz} | {} | {} | {} | {} | {} / {p95:.2} |", med[0], med[1], med[2], med[3], med[4]);
    }
}
