//! A fixed amount of factorisation work for instruction counting under
//! `valgrind --tool=callgrind` (repeatable on a busy machine, unlike timings):
//! one analysis and three numeric factorisations of the step-1 matrix of the figure.
//! `cargo build --release --example factor_count && valgrind --tool=callgrind target/release/examples/factor_count 10000`

use std::sync::Arc;

use akap::deform::killing::KillingMatrix;
use akap::sparse::{amd_order, expand_blocks, Numeric, Ordering, Symbolic};
use akap::{shapes, triangulate, TriangulationOptions};

fn main() {
    let target: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(10_000);
    let figure = shapes::gingerbread();
    let h = (1.7 * figure.area() / (2.0 * target as f64) / (3f64.sqrt() / 4.0)).sqrt();
    let options = TriangulationOptions::default().with_target_edge_length(h).with_max_vertices(4 * target);
    let mesh = triangulate(&figure, &options).expect("triangulates");
    let mut k = KillingMatrix::new(&mesh);
    k.assemble(mesh.positions());
    let mut a = k.matrix().clone();
    for v in 0..3 {
        let [[d0, _], [_, d1]] = k.block_slots(v, v).expect("diagonal block");
        a.data_mut()[d0] += 100.0;
        a.data_mut()[d1] += 100.0;
    }
    let n = mesh.vertex_count();
    let mut ptr = vec![0];
    let mut adj = Vec::new();
    for v in 0..n {
        adj.extend(mesh.neighbors(v).iter().map(|&w| w as usize));
        ptr.push(adj.len());
    }
    let order = expand_blocks(&amd_order(n, &ptr, &adj), 2);
    let symbolic = Symbolic::analyse(a.view(), &Ordering::Given(order)).expect("analyses");
    let mut numeric = Numeric::new(Arc::new(symbolic));
    for _ in 0..3 {
        numeric.refactor(a.view()).expect("factors");
    }
    let mut b = vec![1.0; 2 * n];
    numeric.solve_in_place(&mut b).expect("solves");
    println!("n {n}, x[0] = {}", b[0]);
}
