//! Fill-reducing orders compared on the built-in shapes: the factorisation flops
//! (`order_flops`, two unknowns per vertex as in the deformer's matrices) and the
//! ordering time of approximate minimum degree (AMD), approximate minimum fill (AMF) and
//! nested dissection (ND), printed as a markdown table, with the flops of AMF and ND
//! relative to AMD's. `cargo run --release --example orderings`.
//!
//! Greedy orders depend on the labels of the vertices (AMD's flops vary by about ±6% over
//! random relabellings of one mesh), so `--relabel K` orders K randomly relabelled copies
//! of each mesh as well and prints the ratios of the summed flops, with their range.

use std::time::Instant;

use akap::sparse::{amd_order, amf_order, nested_dissection_order, order_flops};
use akap::{shapes, triangulate, Mesh, TriangulationOptions};

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

/// Marsaglia's xorshift64, for the relabellings.
struct Rng(u64);

impl Rng {
    fn permutation(&mut self, n: usize) -> Vec<usize> {
        let mut v: Vec<usize> = (0..n).collect();
        for i in (1..n).rev() {
            let mut x = self.0;
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            self.0 = x;
            v.swap(i, (x % (i as u64 + 1)) as usize);
        }
        v
    }
}

/// The vertex graph of `mesh` with vertex `v` relabelled `label[v]`, and its positions.
fn graph(mesh: &Mesh, label: &[usize]) -> (Vec<usize>, Vec<usize>, Vec<[f64; 2]>) {
    let n = mesh.vertex_count();
    let mut vertex = vec![0; n];
    for (v, &l) in label.iter().enumerate() {
        vertex[l] = v;
    }
    let (ptr, adj) = mesh.relabelled_vertex_graph(label);
    (ptr, adj, vertex.iter().map(|&v| mesh.positions()[v]).collect())
}

/// Flops of AMD, AMF and ND on one labelling, with their ordering times in milliseconds.
fn compare(ptr: &[usize], adj: &[usize], positions: &[[f64; 2]]) -> ([f64; 3], [f64; 3]) {
    let n = positions.len();
    let (amd, amd_ms) = timed(|| amd_order(n, ptr, adj));
    let (amf, amf_ms) = timed(|| amf_order(n, ptr, adj));
    let (nd, nd_ms) = timed(|| nested_dissection_order(ptr, adj, positions));
    let flops = [&amd, &amf, &nd].map(|order| order_flops(ptr, adj, order, 2));
    (flops, [amd_ms, amf_ms, nd_ms])
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let relabel: usize =
        args.iter().position(|a| a == "--relabel").and_then(|k| args.get(k + 1)?.parse().ok()).unwrap_or(0);
    let header = if relabel > 0 { " AMF/AMD range | ND/AMD range |" } else { "" };
    println!("| shape | vertices | AMD flops | AMF/AMD | ND/AMD | AMD ms | AMF ms | ND ms |{header}");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|{}", if relabel > 0 { "---:|---:|" } else { "" });
    let figures =
        [("gingerbread", shapes::gingerbread()), ("cat", shapes::cat()), ("toothed bar", shapes::toothed_bar())];
    for (name, figure) in &figures {
        // About 1k, 5k, 10k, 16k and 50k vertices.
        for vertices in [1000, 5000, 10_000, 16_000, 50_000] {
            let target = vertices as f64 / 1.6;
            let h = (figure.area() / (2.0 * target) / (3f64.sqrt() / 4.0)).sqrt();
            let options = TriangulationOptions::default().with_target_edge_length(h).with_max_vertices(4 * vertices);
            let mesh = triangulate(figure, &options).unwrap();
            let n = mesh.vertex_count();
            let (ptr, adj, positions) = graph(&mesh, &(0..n).collect::<Vec<_>>());
            let (flops, [amd_ms, amf_ms, nd_ms]) = compare(&ptr, &adj, &positions);
            let mut line = format!(
                "| {name} | {n} | {:.3e} | {:.3} | {:.3} | {amd_ms:.1} | {amf_ms:.1} | {nd_ms:.1} |",
                flops[0],
                flops[1] / flops[0],
                flops[2] / flops[0]
            );
            if relabel > 0 {
                let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
                let mut sum = flops;
                let mut range =
                    [(flops[1] / flops[0], flops[1] / flops[0]), (flops[2] / flops[0], flops[2] / flops[0])];
                for _ in 0..relabel {
                    let (ptr, adj, positions) = graph(&mesh, &rng.permutation(n));
                    let (f, _) = compare(&ptr, &adj, &positions);
                    for k in 0..3 {
                        sum[k] += f[k];
                    }
                    for (k, r) in range.iter_mut().enumerate() {
                        *r = (r.0.min(f[k + 1] / f[0]), r.1.max(f[k + 1] / f[0]));
                    }
                }
                line = format!(
                    "| {name} | {n} | {:.3e} | {:.3} | {:.3} | {amd_ms:.1} | {amf_ms:.1} | {nd_ms:.1} | {:.2}-{:.2} | {:.2}-{:.2} |",
                    sum[0] / (relabel + 1) as f64,
                    sum[1] / sum[0],
                    sum[2] / sum[0],
                    range[0].0,
                    range[0].1,
                    range[1].0,
                    range[1].1
                );
            }
            println!("{line}");
        }
    }
}
