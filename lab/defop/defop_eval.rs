//! Times a deformation operator (src/defop) at the size of the paper's octopus: the
//! gingerbread figure at about 2,000 vertices, 9 handles, a TPS handle basis on m = 1000
//! samples (|Ψ| = 1019) of a smooth synthetic ground truth that hits the handles and is the
//! identity at the rest pose. Prints the fit time and the evaluation time per call, for the
//! hat basis (|Φ| = N; TPS interpolation shortcut, and the structured solver for
//! comparison) and for the reduced basis of 100 functions (1, x, y and the bilaplacian's
//! lowest eigenfunctions; structured solver), and how far the single-precision output is
//! from the double one; the same for the operator's single-precision copy
//! (`Operator::single_precision`); and the operator file's size in double and single
//! precision (`write_operator_in`) with how far the single-precision file, read back,
//! poses from the operator. With `--write DIR` it also writes the operator files
//! `DIR/hat.defop` and `DIR/reduced.defop` (operator and mesh, `defop::write_operator`), which
//! `lab/defop/bench-defop-eval.mjs` times in wasm without training. Prints only; asserts
//! nothing.
//!
//! ```text
//! cargo run --release --example defop_eval [-- --write target/defop-bench]
//! ```

#[cfg(not(target_arch = "wasm32"))]
fn main() {
    use std::f64::consts::PI;
    use std::hint::black_box;
    use std::time::Instant;

    use akap::defop::{
        fit, read_operator, reduced_basis, write_operator, write_operator_in, FitOptions, MeshPoint, Precision, Sample,
        SpatialBasis,
    };

    let args: Vec<String> = std::env::args().collect();
    let write_dir =
        args.iter().position(|a| a == "--write").and_then(|i| args.get(i + 1)).map(std::path::PathBuf::from);
    use akap::triangulate::triangulate_to_about;
    use akap::{shapes, TriangulationOptions};

    let (mesh, _) = triangulate_to_about(&shapes::gingerbread(), 2000, &TriangulationOptions::default()).unwrap();
    let p = mesh.positions();
    let nv = mesh.vertex_count();
    // 9 handles by farthest-point sampling from vertex 0.
    let mut handles = vec![0usize];
    let mut distance: Vec<f64> = vec![f64::INFINITY; nv];
    while handles.len() < 9 {
        let last = p[*handles.last().unwrap()];
        for (d, q) in distance.iter_mut().zip(p) {
            *d = d.min((q[0] - last[0]).hypot(q[1] - last[1]));
        }
        let far = (0..nv).max_by(|&a, &b| distance[a].total_cmp(&distance[b])).unwrap();
        handles.push(far);
    }
    let rest: Vec<f64> = handles.iter().flat_map(|&v| p[v]).collect();
    let (lo, hi) = p.iter().fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(lo, hi), q| {
        ([lo[0].min(q[0]), lo[1].min(q[1])], [hi[0].max(q[0]), hi[1].max(q[1])])
    });
    let diagonal = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    let radius = 0.08 * diagonal;

    // Synthetic ground truth: Shepard blend of the handle displacements plus a bend that
    // vanishes at the handles and at Q = P.
    let truth = |q: &[f64]| -> Vec<f64> {
        let delta: Vec<f64> = q.iter().zip(&rest).map(|(a, b)| a - b).collect();
        let s: f64 = delta.iter().enumerate().map(|(a, x)| (0.3 + 0.05 * a as f64) * x).sum::<f64>() / diagonal;
        let bend = [0.05 * diagonal * (3.0 * s).sin(), 0.05 * diagonal * (1.0 - (2.0 * s).cos())];
        let mut out = Vec::with_capacity(2 * nv);
        for (v, x) in p.iter().enumerate() {
            if let Some(l) = handles.iter().position(|&h| h == v) {
                out.extend([q[2 * l], q[2 * l + 1]]);
                continue;
            }
            let d2: Vec<f64> = rest.chunks_exact(2).map(|r| (x[0] - r[0]).powi(2) + (x[1] - r[1]).powi(2)).collect();
            let total: f64 = d2.iter().map(|d| 1.0 / d).sum();
            let c: f64 = d2.iter().map(|d| d / (d + radius * radius)).product();
            let mut g = *x;
            for (l, d) in d2.iter().enumerate() {
                g[0] += delta[2 * l] / d / total;
                g[1] += delta[2 * l + 1] / d / total;
            }
            out.extend([g[0] + c * bend[0], g[1] + c * bend[1]]);
        }
        out
    };
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    let mut unit = move || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut disc = |r: f64| -> Vec<f64> {
        rest.chunks_exact(2)
            .flat_map(|q| {
                let (rr, a) = (r * unit().sqrt(), 2.0 * PI * unit());
                [q[0] + rr * a.cos(), q[1] + rr * a.sin()]
            })
            .collect()
    };
    // 999 samples plus the rest pose, which the fit adds: m = 1000.
    let targets: Vec<Vec<f64>> = (0..999).map(|_| disc(radius)).collect();
    let start = Instant::now();
    let positions: Vec<Vec<f64>> = targets.iter().map(|t| truth(t)).collect();
    let sampling = start.elapsed().as_secs_f64();
    let samples: Vec<Sample<'_>> =
        targets.iter().zip(&positions).map(|(t, p)| Sample { targets: t, positions: p }).collect();
    let points: Vec<MeshPoint> = handles.iter().map(|&v| MeshPoint::Vertex(v as u32)).collect();
    let queries: Vec<Vec<f64>> = (0..64).map(|_| disc(1.5 * radius)).collect();

    println!("mesh: {nv} vertices, {} triangles; 9 handles; m = 1000 samples", mesh.triangle_count());
    println!("synthetic ground truth: {:.1} ms for 999 samples", 1e3 * sampling);
    let start = Instant::now();
    let reduced = reduced_basis(&mesh, 100).unwrap();
    println!(
        "reduced basis: 1, x, y and the 97 lowest eigenfunctions in {:.0} ms",
        1e3 * start.elapsed().as_secs_f64()
    );
    let structured = FitOptions::default().with_tps_shortcut(false);
    for (name, spatial, options, file) in [
        ("hat", SpatialBasis::hat(&mesh), FitOptions::default(), Some("hat.defop")),
        ("hat", SpatialBasis::hat(&mesh), structured, None),
        ("reduced", reduced, FitOptions::default(), Some("reduced.defop")),
    ] {
        let start = Instant::now();
        let mut operator = fit(&mesh, &spatial, &points, &samples, &options).unwrap();
        let fitting = start.elapsed().as_secs_f64();
        if let (Some(dir), Some(file)) = (&write_dir, file) {
            std::fs::create_dir_all(dir).unwrap();
            std::fs::write(dir.join(file), write_operator(&mesh, &operator).unwrap()).unwrap();
        }
        let mut out = vec![0.0; 2 * nv];
        let mut out32 = vec![0.0f32; 2 * nv];
        let mut calls = 0usize;
        let start = Instant::now();
        while start.elapsed().as_secs_f64() < 1.0 {
            for q in &queries {
                operator.evaluate_into(black_box(q), &mut out).unwrap();
                calls += 1;
            }
            black_box(&out);
        }
        let per_call = start.elapsed().as_secs_f64() / calls as f64;
        let start = Instant::now();
        let mut calls32 = 0usize;
        while start.elapsed().as_secs_f64() < 1.0 {
            for q in &queries {
                operator.evaluate_into_f32(black_box(q), &mut out32).unwrap();
                calls32 += 1;
            }
            black_box(&out32);
        }
        let per_call32 = start.elapsed().as_secs_f64() / calls32 as f64;
        let worst = queries
            .iter()
            .map(|q| {
                let e = operator.evaluate(q).unwrap();
                handles
                    .iter()
                    .enumerate()
                    .map(|(l, &v)| (e[2 * v] - q[2 * l]).hypot(e[2 * v + 1] - q[2 * l + 1]))
                    .fold(0.0, f64::max)
            })
            .fold(0.0, f64::max);
        let f32_error = queries
            .iter()
            .map(|q| {
                let e = operator.evaluate(q).unwrap();
                operator.evaluate_into_f32(q, &mut out32).unwrap();
                e.iter().zip(&out32).map(|(a, &b)| (a - f64::from(b)).abs()).fold(0.0, f64::max)
            })
            .fold(0.0, f64::max);
        let mut single = operator.single_precision();
        let start = Instant::now();
        let mut calls_single = 0usize;
        while start.elapsed().as_secs_f64() < 1.0 {
            for q in &queries {
                single.evaluate_into(black_box(q), &mut out32).unwrap();
                calls_single += 1;
            }
            black_box(&out32);
        }
        let per_call_single = start.elapsed().as_secs_f64() / calls_single as f64;
        let single_error = queries
            .iter()
            .map(|q| {
                let e = operator.evaluate(q).unwrap();
                single.evaluate_into(q, &mut out32).unwrap();
                e.iter().zip(&out32).map(|(a, &b)| (a - f64::from(b)).abs()).fold(0.0, f64::max)
            })
            .fold(0.0, f64::max);
        println!(
            "{name:>7}: single-precision copy ({:.1} MB): {:.1} µs/call ({:.0}/s), {:.1e} of the diagonal from f64",
            single.coefficient_bytes() as f64 / 1e6,
            1e6 * per_call_single,
            1.0 / per_call_single,
            single_error / diagonal
        );
        let double_file = write_operator(&mesh, &operator).unwrap();
        let single_file = write_operator_in(&mesh, &operator, Precision::Single).unwrap();
        let (_, mut from_single) = read_operator(&single_file).unwrap();
        let file_error = queries
            .iter()
            .map(|q| {
                let (a, b) = (operator.evaluate(q).unwrap(), from_single.evaluate(q).unwrap());
                a.iter().zip(&b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
            })
            .fold(0.0, f64::max);
        println!(
            "{name:>7}: operator file {:.2} MB, {:.2} MB in single precision; read back, it poses {:.1e} of the diagonal from f64",
            double_file.len() as f64 / 1e6,
            single_file.len() as f64 / 1e6,
            file_error / diagonal
        );
        println!(
            "{name:>7}: |Φ| = {:4}, |Ψ| = {}, solver {:?}: fit {:.2} s; evaluate {:.1} µs/call ({:.0}/s), \
             f32 out {:.1} µs/call ({:.1e} of the diagonal from f64); handles hit to {:.1e} of the diagonal",
            spatial.len(),
            operator.handle_basis().len(),
            operator.solver(),
            fitting,
            1e6 * per_call,
            1.0 / per_call,
            1e6 * per_call32,
            f32_error / diagonal,
            worst / diagonal
        );
    }
}

#[cfg(target_arch = "wasm32")]
fn main() {}
