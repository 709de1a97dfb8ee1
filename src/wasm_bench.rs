//! The wasm benchmark of our sparse Cholesky (and faer's, compiled to wasm too) on
//! AKAP-like matrices, timed with `performance.now()`. Compiled only for wasm32 with the
//! `bench` feature; `lab/sparse/bench-wasm.sh` builds it for Node and
//! `lab/sparse/bench-wasm.mjs` prints the table. The matrices come from
//! `lab/sparse/common/mod.rs`, included by path so that the native benchmarks and this one
//! measure the same matrices. Also the DefOp evaluation in double and single precision
//! (`bench_defop_eval`, run by `lab/defop/bench-defop-eval.mjs --rust`).
//!
//! An exception to "only `wasm` touches js-sys and wasm-bindgen", confined to this
//! feature-gated module.

use std::sync::Arc;

use js_sys::{Function, Reflect};
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

use crate::sparse::{Numeric, Symbolic};

#[allow(dead_code)] // each includer uses part of the shared module
#[path = "../lab/sparse/common/mod.rs"]
mod common;

use common::faer_llt::FaerLlt;
use common::{median, random_vector, relative_difference, OrderChoice, Problem, Shape, Variant};

/// `globalThis.performance.now`, looked up once.
struct Clock {
    performance: JsValue,
    now: Function,
}

impl Clock {
    fn new() -> Result<Self, JsError> {
        let performance = Reflect::get(&js_sys::global(), &"performance".into())
            .map_err(|_| JsError::new("globalThis.performance is missing"))?;
        let now = Reflect::get(&performance, &"now".into())
            .ok()
            .and_then(|f| f.dyn_into::<Function>().ok())
            .ok_or_else(|| JsError::new("performance.now is missing"))?;
        Ok(Self { performance, now })
    }

    fn ms(&self) -> f64 {
        self.now.call0(&self.performance).ok().and_then(|t| t.as_f64()).unwrap_or(f64::NAN)
    }

    /// Milliseconds of one run of `f`.
    fn time_ms(&self, f: impl FnOnce()) -> f64 {
        let start = self.ms();
        f();
        self.ms() - start
    }
}

/// Builds the AKAP-like matrix of `shape` (`"bar"` or `"gingerbread"`) meshed with about
/// `target_vertices` vertices, with four penalised handles or, if `dirichlet`, the boundary
/// eliminated, ours ordered by `ordering` (`"amd"` or `"best"`, see the shared module);
/// times our ordering and symbolic analysis, numeric refactorisation and solve
/// (and faer's supernodal and simplicial ones) as medians of `repeats` rounds, and returns
/// one JSON object: sizes, fill, milliseconds, and the relative difference between our
/// solution of a random right-hand side and faer's. A failed factorisation is reported in
/// its `error` field.
#[wasm_bindgen]
#[allow(unreachable_pub)] // exported to JavaScript; the module is private to the crate
pub fn bench_cholesky(
    target_vertices: u32,
    shape: &str,
    dirichlet: bool,
    repeats: u32,
    ordering: &str,
) -> Result<String, JsError> {
    let shape = Shape::from_name(shape).ok_or_else(|| JsError::new(&format!("unknown shape {shape:?}")))?;
    let ordering =
        OrderChoice::from_name(ordering).ok_or_else(|| JsError::new(&format!("unknown ordering {ordering:?}")))?;
    if !(100..=1_000_000).contains(&target_vertices) {
        return Err(JsError::new("target_vertices must be from 100 to 1000000"));
    }
    let clock = Clock::new()?;
    let variant = if dirichlet { Variant::Dirichlet } else { Variant::Penalty };
    let start = clock.ms();
    let problem = Problem::new(shape, target_vertices as usize, variant);
    let build_ms = clock.ms() - start;
    let a = &problem.matrix;
    let b = random_vector(problem.n(), 7);
    let mut fields = vec![
        format!("\"label\":\"{}\"", problem.label()),
        format!("\"vertices\":{}", problem.vertices),
        format!("\"n\":{}", problem.n()),
        format!("\"nnzLower\":{}", problem.nnz_lower()),
        format!("\"repeats\":{repeats}"),
        format!("\"buildMs\":{}", json_number(build_ms)),
    ];

    // Set everything up, untimed; then time each operation once per round, in turn, so
    // that load from other processes hits all of them alike.
    let symbolic = match Symbolic::analyse(a.view(), &problem.ordering(ordering)) {
        Ok(symbolic) => Arc::new(symbolic),
        Err(e) => return Ok(json_with_error(fields, &e.to_string())),
    };
    fields.push(format!("\"nnzL\":{}", symbolic.nnz_l()));
    fields.push(format!("\"flops\":{}", symbolic.flops()));
    fields.push(format!("\"supernodes\":{}", symbolic.supernode_count()));
    let mut numeric = Numeric::new(Arc::clone(&symbolic));
    let mut ours_x = b.clone();
    if let Err(e) = numeric.refactor(a.view()).and_then(|()| numeric.solve_in_place(&mut ours_x)) {
        return Ok(json_with_error(fields, &e.to_string()));
    }
    fields.push(format!("\"residual\":{}", json_number(problem.relative_residual(&ours_x, &b))));
    let mut supernodal = FaerLlt::analyse(a, true);
    supernodal.factor(a);
    let mut faer_x = b.clone();
    supernodal.solve_in_place(&mut faer_x);
    let mut simplicial = FaerLlt::analyse(a, false);
    simplicial.factor(a);
    fields.push(format!("\"faerNnzL\":{}", simplicial.stored_values()));
    fields.push(format!("\"differenceFromFaer\":{}", json_number(relative_difference(&ours_x, &faer_x))));

    let names = [
        "oursSymbolicMs",
        "oursNumericMs",
        "oursSolveMs",
        "faerSymbolicMs",
        "faerNumericMs",
        "faerSimplicialMs",
        "faerSolveMs",
    ];
    let mut samples: [Vec<f64>; 7] = Default::default();
    let mut x = b.clone();
    for _ in 0..repeats.max(1) {
        samples[0].push(clock.time_ms(|| {
            std::hint::black_box(Symbolic::analyse(a.view(), &problem.ordering(ordering)).ok());
        }));
        let (mut refactored, mut solved) = (Ok(()), Ok(()));
        samples[1].push(clock.time_ms(|| refactored = numeric.refactor(a.view())));
        x.copy_from_slice(&b);
        samples[2].push(clock.time_ms(|| solved = numeric.solve_in_place(&mut x)));
        if let Err(e) = refactored.and(solved) {
            return Ok(json_with_error(fields, &e.to_string()));
        }
        samples[3].push(clock.time_ms(|| {
            std::hint::black_box(supernodal.reanalyse());
        }));
        samples[4].push(clock.time_ms(|| supernodal.factor(a)));
        samples[5].push(clock.time_ms(|| simplicial.factor(a)));
        x.copy_from_slice(&b);
        samples[6].push(clock.time_ms(|| supernodal.solve_in_place(&mut x)));
    }
    for (name, values) in names.iter().zip(samples) {
        fields.push(format!("\"{name}\":{}", json_number(median(values))));
    }
    Ok(format!("{{{}}}", fields.join(",")))
}

/// Times a DefOp evaluation of the operator file `bytes` (as `defop::write_operator` writes
/// it), in double precision (`Operator::evaluate_into`) and with its single-precision copy
/// (`SinglePrecision::evaluate_into`), alternating in `rounds` rounds of about `ms`
/// milliseconds each on 64 target sets near the rest pose, after a warm-up (each call is a
/// separate wasm function, so that V8 tiers it up). Returns one JSON object: the median and
/// fastest milliseconds per evaluation of each, and the largest difference between the two
/// over the bounding-box diagonal.
#[wasm_bindgen]
#[allow(unreachable_pub)] // exported to JavaScript; the module is private to the crate
pub fn bench_defop_eval(bytes: &[u8], rounds: u32, ms: f64) -> Result<String, JsError> {
    use crate::defop::{Operator, SinglePrecision};

    #[inline(never)]
    fn double(operator: &mut Operator, q: &[f64], out: &mut [f64]) {
        operator.evaluate_into(q, out).ok();
    }
    #[inline(never)]
    fn single(copy: &mut SinglePrecision, q: &[f64], out: &mut [f32]) {
        copy.evaluate_into(q, out).ok();
    }

    let (mesh, mut operator) = crate::defop::read_operator(bytes).map_err(|e| JsError::new(&e.to_string()))?;
    let mut copy = operator.single_precision();
    let clock = Clock::new()?;
    let rest = operator.handle_basis().rest().to_vec();
    let queries: Vec<Vec<f64>> = (0..64)
        .map(|k| rest.iter().enumerate().map(|(i, x)| x + 0.05 * (k as f64 + 1.7 * i as f64).sin()).collect())
        .collect();
    let mut out = vec![0.0; 2 * operator.vertex_count()];
    let mut out32 = vec![0.0f32; out.len()];
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in mesh.positions() {
        for c in 0..2 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    let diagonal = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    let mut difference: f64 = 0.0;
    for q in &queries {
        double(&mut operator, q, &mut out);
        single(&mut copy, q, &mut out32);
        for (a, b) in out.iter().zip(&out32) {
            difference = difference.max((a - f64::from(*b)).abs());
        }
    }
    let mut samples: [Vec<f64>; 2] = Default::default();
    for round in 0..=rounds {
        for (which, values) in samples.iter_mut().enumerate() {
            let (start, mut calls) = (clock.ms(), 0usize);
            while clock.ms() - start < ms {
                for q in &queries {
                    if which == 0 {
                        double(&mut operator, q, &mut out);
                    } else {
                        single(&mut copy, q, &mut out32);
                    }
                }
                calls += queries.len();
            }
            // Round 0 warms up.
            if round > 0 {
                values.push((clock.ms() - start) / calls as f64);
            }
        }
    }
    std::hint::black_box((&out, &out32));
    let mut fields = vec![
        format!("\"vertices\":{}", operator.vertex_count()),
        format!("\"spatial\":{}", operator.spatial_len()),
        format!("\"psi\":{}", operator.handle_basis().len()),
        format!("\"singleBytes\":{}", copy.coefficient_bytes()),
        format!("\"singleDifference\":{}", json_number(difference / diagonal)),
    ];
    for (name, mut values) in ["double", "single"].into_iter().zip(samples) {
        values.sort_by(f64::total_cmp);
        let fastest = values.first().copied().unwrap_or(f64::NAN);
        fields.push(format!("\"{name}FastestMs\":{}", json_number(fastest)));
        fields.push(format!("\"{name}MedianMs\":{}", json_number(median(values))));
    }
    Ok(format!("{{{}}}", fields.join(",")))
}

/// Whether this build was compiled with wasm SIMD (`-C target-feature=+simd128`).
#[wasm_bindgen]
#[allow(unreachable_pub)] // exported to JavaScript
pub fn bench_simd128() -> bool {
    cfg!(target_feature = "simd128")
}

/// A JSON number, or `null` for NaN and infinities (which JSON cannot spell).
fn json_number(x: f64) -> String {
    if x.is_finite() {
        x.to_string()
    } else {
        "null".to_string()
    }
}

fn json_with_error(mut fields: Vec<String>, error: &str) -> String {
    fields.push(format!("\"error\":\"{}\"", error.replace('\\', "\\\\").replace('"', "\\\"")));
    format!("{{{}}}", fields.join(","))
}
