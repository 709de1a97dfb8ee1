//! Fill-reducing orders compared on the built-in shapes: the factorisation flops
//! (`order_flops`, two unknowns per vertex as in the deformer's matrices) and the
//! ordering time of approximate minimum degree and of nested dissection, printed as a
//! markdown table. `cargo run --release --example orderings`.

use std::time::Instant;

use akap::sparse::{amd_order, nested_dissection_order, order_flops};
use akap::{shapes, triangulate, TriangulationOptions};

/// Minimum over a few runs of the time of `f` in milliseconds, with its last result.
fn timed<T>(mut f: impl FnMut() -> T) -> (T, f64) {
    let mut best = f64::INFINITY;
    let mut result = None;
    for _ in 0..5 {
        let t = Instant::now();
        result = Some(f());
        best = best.min(t.elapsed().as_secs_f64() * 1e3);
    }
    (result.expect("at least one run"), best)
}

fn main() {
    println!("| shape | vertices | AMD flops | ND flops | ND/AMD | AMD ms | ND ms |");
    println!("|---|---:|---:|---:|---:|---:|---:|");
    let figures =
        [("gingerbread", shapes::gingerbread()), ("cat", shapes::cat()), ("toothed bar", shapes::toothed_bar())];
    for (name, figure) in &figures {
        for target in [1000, 5000, 10_000, 50_000] {
            let h = (figure.area() / (2.0 * target as f64) / (3f64.sqrt() / 4.0)).sqrt();
            let options = TriangulationOptions::default().with_target_edge_length(h).with_max_vertices(4 * target);
            let mesh = triangulate(figure, &options).unwrap();
            let n = mesh.vertex_count();
            let mut ptr = vec![0];
            let mut adj = Vec::new();
            for v in 0..n {
                adj.extend(mesh.neighbors(v).iter().map(|&w| w as usize));
                ptr.push(adj.len());
            }
            let (amd, amd_ms) = timed(|| amd_order(n, &ptr, &adj));
            let (nd, nd_ms) = timed(|| nested_dissection_order(&ptr, &adj, mesh.positions()));
            let amd_flops = order_flops(&ptr, &adj, &amd, 2);
            let nd_flops = order_flops(&ptr, &adj, &nd, 2);
            println!(
                "| {name} | {n} | {amd_flops:.3e} | {nd_flops:.3e} | {:.2} | {amd_ms:.1} | {nd_ms:.1} |",
                nd_flops / amd_flops
            );
        }
    }
}
