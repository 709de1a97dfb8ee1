//! Prints a markdown table comparing our sparse Cholesky with faer's (supernodal and
//! simplicial, faer's own AMD) and sprs-ldl (given our AMD order) on AKAP-like matrices:
//! median times of repeated runs, fill and flop counts, and the ratio of our numeric
//! factorisation to faer's supernodal one.
//!
//! ```text
//! cargo run --release --features bench --example cholesky_table -- [--max-vertices N] [--min-vertices N]
//!     [--shape bar|gingerbread] [--variant penalty|dirichlet] [--repeats N]
//!     [--ordering amd|best]
//! ```
//!
//! `--ordering best` orders ours as the deformer does (`sparse::fill_reducing_order` on the
//! vertex graph: AMD, or from 12000 vertices nested dissection when it needs fewer flops);
//! the default is AMD on the matrix. `ours sym` includes computing the order.
//!
//! Every solution of a random right-hand side is checked against faer's (relative
//! difference below 1e-8), so a wrong factor cannot look fast; a mismatch is printed and
//! the program exits with status 1 after the table.

#[cfg(not(target_arch = "wasm32"))]
#[allow(dead_code)] // each includer uses part of the shared module
#[path = "common/mod.rs"]
mod common;

#[cfg(not(target_arch = "wasm32"))]
mod table {
    use std::hint::black_box;
    use std::process::ExitCode;
    use std::sync::Arc;
    use std::time::Instant;

    use akap::sparse::{Numeric, Symbolic};
    use sprs::{PermOwned, SymmetryCheck};
    use sprs_ldl::LdlSymbolic;

    use crate::common::faer_llt::FaerLlt;
    use crate::common::{
        default_repeats, median, random_vector, relative_difference, size_label, OrderChoice, Problem, Shape, Variant,
        SIZES,
    };

    /// Largest relative difference accepted between our solution and faer's.
    const TOLERANCE: f64 = 1e-8;

    struct Options {
        max_vertices: usize,
        min_vertices: usize,
        shapes: Vec<Shape>,
        variants: Vec<Variant>,
        repeats: Option<usize>,
        ordering: OrderChoice,
    }

    fn parse_args() -> Result<Options, String> {
        let mut options = Options {
            max_vertices: usize::MAX,
            min_vertices: 0,
            shapes: Shape::ALL.to_vec(),
            variants: Variant::ALL.to_vec(),
            repeats: None,
            ordering: OrderChoice::Amd,
        };
        let mut args = std::env::args().skip(1);
        while let Some(flag) = args.next() {
            let mut value = || args.next().ok_or_else(|| format!("{flag} needs a value"));
            let count = |v: String| v.parse::<usize>().map_err(|e| format!("{flag}: {e}"));
            match flag.as_str() {
                "--max-vertices" => options.max_vertices = count(value()?)?,
                "--min-vertices" => options.min_vertices = count(value()?)?,
                "--repeats" => options.repeats = Some(count(value()?)?.max(1)),
                "--shape" => {
                    let name = value()?;
                    options.shapes = vec![Shape::from_name(&name).ok_or(format!("unknown shape {name}"))?];
                }
                "--variant" => {
                    let name = value()?;
                    let variant = Variant::ALL.into_iter().find(|v| v.name() == name);
                    options.variants = vec![variant.ok_or(format!("unknown variant {name}"))?];
                }
                "--ordering" => {
                    let name = value()?;
                    options.ordering = OrderChoice::from_name(&name).ok_or(format!("unknown ordering {name}"))?;
                }
                "--bench" => {} // passed by `cargo bench --all-targets`
                _ => return Err(format!("unknown argument {flag}")),
            }
        }
        Ok(options)
    }

    /// Milliseconds of one run of `f`.
    fn time_ms(f: impl FnOnce()) -> f64 {
        let start = Instant::now();
        f();
        start.elapsed().as_secs_f64() * 1e3
    }

    /// Measures one matrix and prints its row; returns whether the solutions agreed.
    ///
    /// Every factorisation is set up first; then each of `repeats` rounds times every
    /// operation once, in turn, so that load from other processes hits all of them alike
    /// and the ratios stay meaningful. Each column is the median over the rounds.
    fn row(problem: &Problem, repeats: usize, ordering: OrderChoice) -> bool {
        let a = &problem.matrix;
        let n = problem.n();
        let b = random_vector(n, 7);
        let solve = |f: &mut dyn FnMut(&mut [f64])| {
            let mut x = b.clone();
            f(&mut x);
            x
        };

        let symbolic = match Symbolic::analyse(a.view(), &problem.ordering(ordering)) {
            Ok(symbolic) => Arc::new(symbolic),
            Err(e) => {
                println!("| {} | our symbolic analysis failed: {e} |", problem.label());
                return false;
            }
        };
        let mut numeric = Numeric::new(Arc::clone(&symbolic));
        if let Err(e) = numeric.refactor(a.view()) {
            println!("| {} | our factorisation failed: {e} |", problem.label());
            return false;
        }
        let ours_x = solve(&mut |x| numeric.solve_in_place(x).expect("our solve"));
        let mut supernodal = FaerLlt::analyse(a, true);
        supernodal.factor(a);
        let faer_x = solve(&mut |x| supernodal.solve_in_place(x));
        let mut simplicial = FaerLlt::analyse(a, false);
        simplicial.factor(a);
        let simplicial_x = solve(&mut |x| simplicial.solve_in_place(x));
        // sprs-ldl (simplicial up-looking LDL^T) with our order.
        let perm = PermOwned::new(symbolic.permutation().to_vec());
        let mut ldl = LdlSymbolic::new_perm(a.view(), perm, SymmetryCheck::DontCheckSymmetry)
            .factor(a.view())
            .expect("sprs-ldl factorisation");
        let ldl_x = ldl.solve(&b);

        // ours symbolic, numeric, solve; faer symbolic, supernodal numeric, simplicial
        // numeric, solve; sprs-ldl numeric.
        let mut samples: [Vec<f64>; 8] = Default::default();
        let mut x = b.clone();
        for _ in 0..repeats {
            samples[0].push(time_ms(|| {
                black_box(Symbolic::analyse(a.view(), &problem.ordering(ordering)).expect("our symbolic analysis"));
            }));
            samples[1].push(time_ms(|| numeric.refactor(a.view()).expect("our refactorisation")));
            x.copy_from_slice(&b);
            samples[2].push(time_ms(|| numeric.solve_in_place(&mut x).expect("our solve")));
            samples[3].push(time_ms(|| {
                black_box(supernodal.reanalyse());
            }));
            samples[4].push(time_ms(|| supernodal.factor(a)));
            samples[5].push(time_ms(|| simplicial.factor(a)));
            x.copy_from_slice(&b);
            samples[6].push(time_ms(|| supernodal.solve_in_place(&mut x)));
            samples[7].push(time_ms(|| ldl.update(a.view()).expect("sprs-ldl refactorisation")));
        }
        let [ours_symbolic_ms, ours_numeric_ms, ours_solve_ms, faer_symbolic_ms, faer_numeric_ms, faer_simplicial_ms, faer_solve_ms, ldl_numeric_ms] =
            samples.map(median);

        let differences = [
            relative_difference(&ours_x, &faer_x),
            relative_difference(&simplicial_x, &faer_x),
            relative_difference(&ldl_x, &faer_x),
        ];
        let agree = differences.iter().all(|&d| d < TOLERANCE);
        let check = if agree {
            format!("{:.0e}", differences[0])
        } else {
            format!(
                "**MISMATCH** ours {:.1e}, simplicial {:.1e}, sprs-ldl {:.1e}",
                differences[0], differences[1], differences[2]
            )
        };
        println!(
            "| {} | {} | {} | {} | {} | {} | {} | {:.2e} | {:.2} | {:.2} | {:.3} | {:.2} | {:.2} | {:.2} | {:.3} | {:.2} | **{:.2}** | {} | {} |",
            problem.label(),
            problem.vertices,
            n,
            problem.nnz_lower(),
            symbolic.nnz_l(),
            simplicial.stored_values(),
            ldl.nnz() + n,
            symbolic.flops(),
            ours_symbolic_ms,
            ours_numeric_ms,
            ours_solve_ms,
            faer_symbolic_ms,
            faer_numeric_ms,
            faer_simplicial_ms,
            faer_solve_ms,
            ldl_numeric_ms,
            ours_numeric_ms / faer_numeric_ms,
            check,
            repeats,
        );
        agree
    }

    pub(crate) fn main() -> ExitCode {
        let options = match parse_args() {
            Ok(options) => options,
            Err(message) => {
                eprintln!("cholesky_table: {message}");
                return ExitCode::from(2);
            }
        };
        println!("ours ordered by: {}", options.ordering.name());
        println!();
        println!(
            "| matrix | vertices | n | nnz(A) lower | nnz(L) ours | nnz(L) faer (simplicial) | nnz(L) sprs-ldl | flops ours \
             | ours sym ms | ours num ms | ours solve ms | faer sym ms | faer sn num ms | faer simpl num ms \
             | faer solve ms | sprs-ldl num ms | ours / faer sn num | check | reps |"
        );
        println!("|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|");
        let mut all_agree = true;
        for &size in SIZES.iter().filter(|&&s| (options.min_vertices..=options.max_vertices).contains(&s)) {
            for &shape in &options.shapes {
                for &variant in &options.variants {
                    let problem = Problem::new(shape, size, variant);
                    let repeats = options.repeats.unwrap_or_else(|| default_repeats(size));
                    all_agree &= row(&problem, repeats, options.ordering);
                }
            }
            eprintln!("cholesky_table: {} done", size_label(size));
        }
        if all_agree {
            ExitCode::SUCCESS
        } else {
            eprintln!("cholesky_table: some solutions differ from faer's by more than {TOLERANCE:e}");
            ExitCode::FAILURE
        }
    }
}

#[cfg(not(target_arch = "wasm32"))]
fn main() -> std::process::ExitCode {
    table::main()
}

#[cfg(target_arch = "wasm32")]
fn main() {}
