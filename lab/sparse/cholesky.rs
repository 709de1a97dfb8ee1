//! Criterion benchmarks of our sparse Cholesky against faer's (supernodal and simplicial,
//! faer's own AMD) and sprs-ldl (given our AMD order) on AKAP-like matrices (see
//! `common/mod.rs`).
//!
//! ```text
//! cargo bench --features bench --bench cholesky                      # up to 10k vertices
//! AKAP_BENCH_MAX_VERTICES=100000 cargo bench --features bench --bench cholesky
//! cargo bench --features bench --bench cholesky -- 'gingerbread/5k'  # criterion's filter
//! ```
//!
//! Each matrix is a group `cholesky/<shape>/<size>/<variant>` with the functions
//! `ours/symbolic` (AMD ordering and analysis), `ours/numeric` (refactorisation),
//! `ours/solve`, `faer-supernodal/{symbolic,numeric,solve}`,
//! `faer-simplicial/{symbolic,numeric}` and `sprs-ldl/numeric`. The markdown tables of
//! `lab/sparse/results.md` come from `cholesky_table.rs` (beside this file), which also
//! checks the solutions against each other. The `bench` feature brings faer and sprs-ldl.

#[cfg(not(target_arch = "wasm32"))]
#[allow(dead_code)] // each includer uses part of the shared module
mod common;

#[cfg(not(target_arch = "wasm32"))]
mod native {
    use std::hint::black_box;
    use std::sync::Arc;
    use std::time::Duration;

    use akap::sparse::{Numeric, Ordering, Symbolic};
    use criterion::{BatchSize, Criterion};
    use sprs::{PermOwned, SymmetryCheck};
    use sprs_ldl::LdlSymbolic;

    use crate::common::faer_llt::FaerLlt;
    use crate::common::{random_vector, Problem, Shape, Variant, SIZES};

    /// The largest mesh benchmarked, from `AKAP_BENCH_MAX_VERTICES` (default 10 000).
    fn max_vertices() -> usize {
        std::env::var("AKAP_BENCH_MAX_VERTICES").ok().and_then(|v| v.parse().ok()).unwrap_or(10_000)
    }

    /// Every benchmark of one matrix.
    fn bench_problem(c: &mut Criterion, problem: &Problem) {
        let a = &problem.matrix;
        let b = random_vector(problem.n(), 7);
        let mut group = c.benchmark_group(format!("cholesky/{}", problem.label()));
        group.sample_size(10).warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(2));

        group.bench_function("ours/symbolic", |bench| {
            bench.iter(|| Symbolic::analyse(black_box(a.view()), &Ordering::Amd).expect("our symbolic analysis"))
        });
        let symbolic = Arc::new(Symbolic::analyse(a.view(), &Ordering::Amd).expect("our symbolic analysis"));
        let mut numeric = Numeric::new(Arc::clone(&symbolic));
        group.bench_function("ours/numeric", |bench| {
            bench.iter(|| numeric.refactor(black_box(a.view())).expect("our refactorisation"))
        });
        group.bench_function("ours/solve", |bench| {
            bench.iter_batched_ref(
                || b.clone(),
                |x| numeric.solve_in_place(x).expect("our solve"),
                BatchSize::SmallInput,
            )
        });

        let mut supernodal = FaerLlt::analyse(a, true);
        group.bench_function("faer-supernodal/symbolic", |bench| bench.iter(|| supernodal.reanalyse()));
        group.bench_function("faer-supernodal/numeric", |bench| bench.iter(|| supernodal.factor(black_box(a))));
        group.bench_function("faer-supernodal/solve", |bench| {
            bench.iter_batched_ref(|| b.clone(), |x| supernodal.solve_in_place(x), BatchSize::SmallInput)
        });
        let mut simplicial = FaerLlt::analyse(a, false);
        group.bench_function("faer-simplicial/symbolic", |bench| bench.iter(|| simplicial.reanalyse()));
        group.bench_function("faer-simplicial/numeric", |bench| bench.iter(|| simplicial.factor(black_box(a))));

        let perm = PermOwned::new(symbolic.permutation().to_vec());
        let mut ldl = LdlSymbolic::new_perm(a.view(), perm, SymmetryCheck::DontCheckSymmetry)
            .factor(a.view())
            .expect("sprs-ldl factorisation");
        group.bench_function("sprs-ldl/numeric", |bench| {
            bench.iter(|| ldl.update(black_box(a.view())).expect("sprs-ldl refactorisation"))
        });
        group.finish();
    }

    /// All matrices up to [`max_vertices`].
    pub(crate) fn cholesky(c: &mut Criterion) {
        let max = max_vertices();
        for &size in SIZES.iter().filter(|&&s| s <= max) {
            for shape in Shape::ALL {
                for variant in Variant::ALL {
                    bench_problem(c, &Problem::new(shape, size, variant));
                }
            }
        }
    }
}

#[cfg(not(target_arch = "wasm32"))]
criterion::criterion_group!(benches, native::cholesky);
#[cfg(not(target_arch = "wasm32"))]
criterion::criterion_main!(benches);

/// Nothing to benchmark on wasm32 (see `lab/sparse/bench-wasm.sh`).
#[cfg(target_arch = "wasm32")]
fn main() {}
