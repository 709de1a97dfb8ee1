//! Minimum over repetitions of one numeric refactorisation of the step-1 matrix (Killing
//! energy plus handle penalties) of the built-in figure, ordered by AMD, by approximate
//! minimum fill and by nested dissection. `cargo run --release --example factor_time -- 10000`.
//!
//! With `--count` it does a fixed amount of work instead (one AMD analysis, three
//! factorisations, one solve) and prints no times, for instruction counting, which is
//! repeatable on a busy machine: `valgrind --tool=callgrind target/release/examples/factor_time 10000 --count`.

use std::sync::Arc;

use akap::deform::akap::killing::KillingMatrix;
use akap::sparse::{amd_order, amf_order, expand_blocks, nested_dissection_order, Numeric, Ordering, Symbolic};
use akap::{shapes, triangulate, TriangulationOptions};

fn main() {
    let target: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(10_000);
    let count_only = std::env::args().any(|a| a == "--count");
    let figure = shapes::gingerbread();
    let h = (1.7 * figure.area() / (2.0 * target as f64) / (3f64.sqrt() / 4.0)).sqrt();
    let mesh =
        triangulate(&figure, &TriangulationOptions::default().with_target_edge_length(h).with_max_vertices(4 * target))
            .unwrap();
    let mut k = KillingMatrix::new(&mesh);
    k.assemble(mesh.positions());
    let mut a = k.matrix().clone();
    for v in [0, 1, 2] {
        for s in k.block_slots(v, v).unwrap() {
            a.data_mut()[s[0]] += 100.0;
        }
        let [_, [_, d]] = k.block_slots(v, v).unwrap();
        a.data_mut()[d] += 100.0;
    }
    let n = mesh.vertex_count();
    let (ptr, adj) = mesh.vertex_graph();
    if count_only {
        let mut numeric = Numeric::new(Arc::new(Symbolic::analyse(a.view(), &Ordering::Amd).unwrap()));
        for _ in 0..3 {
            numeric.refactor(a.view()).unwrap();
        }
        let mut b = vec![1.0; 2 * n];
        numeric.solve_in_place(&mut b).unwrap();
        println!("n {n}, x[0] = {}", b[0]);
        return;
    }
    for (name, order) in [
        ("amd", amd_order(n, &ptr, &adj)),
        ("amf", amf_order(n, &ptr, &adj)),
        ("nd", nested_dissection_order(&ptr, &adj, mesh.positions())),
    ] {
        let t = std::time::Instant::now();
        let symbolic = Symbolic::analyse(a.view(), &Ordering::Given(expand_blocks(&order, 2))).unwrap();
        let analyse = t.elapsed().as_secs_f64() * 1e3;
        let (nnz, flops, supers, stored) =
            (symbolic.nnz_l(), symbolic.flops(), symbolic.supernode_count(), symbolic.stored_values());
        let mut numeric = Numeric::new(Arc::new(symbolic));
        let mut best = f64::INFINITY;
        for _ in 0..10 {
            let t = std::time::Instant::now();
            numeric.refactor(a.view()).unwrap();
            best = best.min(t.elapsed().as_secs_f64() * 1e3);
        }
        let mut b = vec![1.0; 2 * n];
        let mut solve = f64::INFINITY;
        for _ in 0..10 {
            let t = std::time::Instant::now();
            numeric.solve_in_place(&mut b).unwrap();
            solve = solve.min(t.elapsed().as_secs_f64() * 1e3);
        }
        println!("{name}: n {n} nnz(L) {nnz} stored {stored} flops {flops:.3e} supernodes {supers} | analyse {analyse:.1} ms, numeric {best:.2} ms ({:.2} GFlop/s), solve {solve:.2} ms", flops / best / 1e6);
    }
}
