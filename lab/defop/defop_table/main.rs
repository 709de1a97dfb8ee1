//! The DefOp paper's Table 1 and figures, reproduced on our own models (the paper's
//! numbers and meshes were lost): a toothed bar, an aleph-like glyph, an octopus-like and a
//! crab-like cartoon (`akap::shapes`), each trained with the bootstrapped [`Trainer`] and
//! fitted with the paper's handle bases. Writes `lab/defop/defop.md` (the table, the
//! convergence numbers, the distortion of ARAP and S-ARAP) and three figures:
//! `lab/defop/defop-convergence.svg` (Fig. 8), `lab/defop/defop-trajectories.svg` (Fig. 3)
//! and `lab/defop/defop-energies.svg` (Fig. 6). Progress goes to stderr.
//!
//! ```text
//! cargo run --release --example defop_table [-- [--quick] [OUTPUT_DIR]]
//! ```
//!
//! `--quick` trains on few samples and small meshes (under a minute); the default is the
//! full run. The wasm columns come from `node lab/defop/bench-defop.mjs --operators
//! target/defop-table/manifest.json`, run by this example on the operator files it
//! writes to `target/defop-table/` (the manifest lists them with targets to time) when
//! `www/lib/` is built (`bash scripts/build.sh --package`) and `node` is on the path;
//! otherwise they say so.
//!
//! [`Trainer`]: akap::defop::Trainer

#[cfg(not(target_arch = "wasm32"))]
mod figures;
#[cfg(not(target_arch = "wasm32"))]
mod models;

#[cfg(not(target_arch = "wasm32"))]
mod run {
    use std::fmt::Write as _;
    use std::path::Path;
    use std::time::Instant;

    use akap::defop::{write_operator, BasisKind, Energy, MeshPoint};

    use crate::figures;
    use crate::models::{self, Mode, RIDGE};

    /// The convergence study's sample counts (Fig. 8).
    const CONVERGENCE_M: [usize; 7] = [11, 25, 50, 100, 200, 300, 400];
    /// Where the operator files for the wasm timings go.
    const OPERATOR_DIR: &str = "target/defop-table";

    /// A row of the table: the cells before and after the wasm ones, and the operator file
    /// they time.
    struct Row {
        head: String,
        tail: String,
        file: String,
    }

    pub(crate) fn main() {
        let args: Vec<String> = std::env::args().skip(1).collect();
        let mode = if args.iter().any(|a| a == "--quick") { Mode::Quick } else { Mode::Full };
        let output = args.iter().find(|a| !a.starts_with("--")).cloned().unwrap_or_else(|| "lab/defop".to_owned());
        let started = Instant::now();
        std::fs::create_dir_all(OPERATOR_DIR).expect("can make the operator directory");
        std::fs::create_dir_all(&output).expect("can make the output directory");
        let mut rows = Vec::new();
        let mut manifest = Vec::new();
        let mut notes = String::new();
        let mut extra = String::new();
        for model in models::models(mode) {
            let (n, nv) = (model.handles.len() - model.options.fixed.len(), model.mesh.vertex_count());
            eprintln!(
                "{}: {nv} vertices, {} triangles, {n} handles, {} samples, {}",
                model.name,
                model.mesh.triangle_count(),
                model.options.samples,
                model.options.energy.name()
            );
            let mut trained = models::train(&model);
            let held = models::held_out(&model, &mut trained, mode.held_out());
            eprintln!("  held-out ground truths: {:.1} s, {} redrawn", held.seconds, held.redrawn);
            let stats = trained.stats;
            let m = trained.targets.len() + 1;
            // Each basis on the model's spatial basis, and with `hat_tps` TPS on the hat
            // functions too (the paper's evaluation figure is for both).
            let variants =
                model.bases.iter().map(|&kind| (kind, false)).chain(model.hat_tps.then_some((BasisKind::Tps, true)));
            for (kind, hat) in variants {
                let (mut operator, fit_seconds, ridge) = if hat {
                    models::fit_hat_tps(&model, &trained)
                } else if kind == BasisKind::Tps {
                    (trained.operator.clone(), trained.final_fit_seconds, false)
                } else {
                    models::fit_basis(&model, &trained, kind, m - 1)
                };
                let label = if hat { format!("{}, hat", basis_name(kind)) } else { basis_name(kind).to_owned() };
                let (rms, max) = models::error(&model, &mut operator, &held);
                let native_ms = models::evaluation_ms(&mut operator, &held, mode.timing_seconds());
                let file = format!("{OPERATOR_DIR}/{}-{}.akdo", model.name, label.replace(", ", "-"));
                let bytes = write_operator(&model.mesh, &operator).expect("a fitted operator writes");
                std::fs::write(&file, bytes).expect("can write the operator file");
                let queries: Vec<&Vec<f64>> = held.targets.iter().take(16).collect();
                // What `bench-defop.mjs --model` needs to train the model again in wasm: the
                // handles (vertex ids) and the options, as the JavaScript API names them.
                let vertex_handles: Option<Vec<u32>> =
                    model.handles.iter().map(|h| if let MeshPoint::Vertex(v) = h { Some(*v) } else { None }).collect();
                let training = serde_json::json!({
                    "energy": if model.options.energy == Energy::SArap { "sarap" } else { "arap" },
                    "samples": model.options.samples,
                    "spatial": model.options.spatial,
                    "radius": model.options.radius,
                    "fixed": model.options.fixed,
                });
                manifest.push(serde_json::json!({
                    "file": file.clone(),
                    "targets": queries,
                    "model": model.name,
                    "basis": label,
                    "handles": vertex_handles,
                    "training": training,
                }));
                let head = format!(
                    "| {} | {}{} | {} | {n} | {m} | {} | {} | {:.1} | {:.1} | {:.1} / {:.1} | {:.2} | {:.3} | {:.0} |",
                    model.name,
                    label,
                    if ridge { " (ridge)" } else { "" },
                    model.mesh.triangle_count(),
                    operator.spatial_len(),
                    operator.handle_basis().len(),
                    trained.solve_seconds,
                    trained.refit_seconds,
                    stats.mean_warm(),
                    stats.mean_cold(),
                    fit_seconds,
                    native_ms,
                    1e3 / native_ms,
                );
                let mb = operator.stored_bytes() as f64 / 1e6;
                let tail = format!(" {:.3} | {:.3} | {mb:.2} |", 100.0 * rms, 100.0 * max);
                rows.push(Row { head, tail, file });
                eprintln!("  {label}: fit {fit_seconds:.2} s, {native_ms:.3} ms, error {:.3}%", 100.0 * rms);
            }
            let _ = writeln!(
                notes,
                "- {}: {} {}, {nv} vertices, radius {:.3} ({:.2} of the diagonal); {} cold and {} warm solves, \
                 {} warm starts from a neighbour, {} fallbacks to the rest pose, {} redraws; held-out ground truths \
                 {:.1} s ({} redrawn), moving the vertices by {:.2}% of the diagonal (RMS){}{}.",
                model.name,
                model.options.energy.name(),
                if model.options.spatial == 0 {
                    "hat basis".to_owned()
                } else {
                    format!("reduced basis of {}", model.options.spatial)
                },
                trained.radius,
                trained.radius / models::diagonal(&model.mesh),
                stats.cold.0,
                stats.warm.0,
                stats.neighbour_starts,
                stats.fallbacks,
                stats.redraws,
                held.seconds,
                held.redrawn,
                100.0 * held.motion,
                if model.note.is_empty() { "" } else { "; " },
                model.note
            );
            match model.name {
                "aleph" => extra += &convergence_section(&model, &trained, &held, &output, mode),
                "bar" => extra += &trajectories_section(&model, &mut trained, &output, mode),
                "octopus" => extra += &energies_section(&model, &trained, &output),
                _ => {}
            }
        }
        let manifest_path = format!("{OPERATOR_DIR}/manifest.json");
        std::fs::write(&manifest_path, serde_json::Value::Array(manifest).to_string()).expect("can write the manifest");
        let wasm = wasm_timings(&manifest_path);
        let mut table = String::from(
            "| model | basis | triangles | n | m | \\|Φ\\| | \\|Ψ\\| | sampling s | refits s | iterations warm / cold | \
             fit s | eval ms | fps | eval ms (wasm) | fps (wasm) | held-out RMS % | held-out max % | MB |\n\
             |---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
        );
        for row in &rows {
            let wasm_cells = match wasm.as_ref().ok().and_then(|w| w.get(&row.file)) {
                Some(ms) => format!(" {ms:.3} | {:.0} |", 1e3 / ms),
                None => " — | — |".to_owned(),
            };
            let _ = writeln!(table, "{}{wasm_cells}{}", row.head, row.tail);
        }
        let markdown = markdown(mode, &table, &notes, &extra, &wasm, started.elapsed().as_secs_f64());
        std::fs::write(format!("{output}/defop.md"), &markdown).expect("can write the table");
        print!("{markdown}");
        eprintln!("wrote {output}/defop.md in {:.0} s", started.elapsed().as_secs_f64());
    }

    fn basis_name(kind: BasisKind) -> &'static str {
        match kind {
            BasisKind::Linear => "linear",
            BasisKind::Quadratic => "quadratic",
            BasisKind::Cubic => "cubic",
            BasisKind::Tps => "TPS",
        }
    }

    fn convergence_section(
        model: &models::Model,
        trained: &models::Trained,
        held: &models::HeldOut,
        output: &str,
        mode: Mode,
    ) -> String {
        let ms: Vec<usize> = match mode {
            Mode::Full => CONVERGENCE_M.to_vec(),
            Mode::Quick => vec![11, 25, 40, 60],
        };
        let points = figures::convergence(model, trained, held, &ms);
        let title = format!("{}: held-out error against m (n = {})", model.name, model.handles.len());
        std::fs::write(format!("{output}/defop-convergence.svg"), figures::convergence_svg(&points, &title))
            .expect("can write the figure");
        let mut s = format!(
            "\n## Convergence (Fig. 8)\n\n![convergence](defop-convergence.svg)\n\n{}, n = {}: the first m − 1 training \
             samples and the rest pose, fitted with each basis, against the same {} held-out targets; RMS vertex error \
             in % of the bounding-box diagonal. *Ridge*: λ = {RIDGE} on the non-linear coefficients where m is below \
             the basis size (quadratic {}, cubic {}).\n\n| m | linear | quadratic | cubic | TPS |\n|---|---|---|---|---|\n",
            model.name,
            model.handles.len(),
            held.targets.len(),
            BasisKind::Quadratic.size(model.handles.len(), 0),
            BasisKind::Cubic.size(model.handles.len(), 0),
        );
        for (m, errors) in &points {
            let cells: Vec<String> = errors
                .iter()
                .map(|(e, ridge)| format!("{:.3}{}", 100.0 * e, if *ridge { " (ridge)" } else { "" }))
                .collect();
            let _ = writeln!(s, "| {m} | {} |", cells.join(" | "));
        }
        s
    }

    fn trajectories_section(model: &models::Model, trained: &mut models::Trained, output: &str, mode: Mode) -> String {
        let spots = [[0.6, 0.2], [1.2, 0.2], [1.6, 0.4], [1.8, 0.0], [1.9, 0.3]];
        let steps = if mode == Mode::Quick { 24 } else { 72 };
        let t = figures::trajectories(model, trained, &spots, steps);
        let title = format!(
            "{}, TPS (m = {}): trajectories as the right handle circles",
            model.name,
            trained.targets.len() + 1
        );
        std::fs::write(format!("{output}/defop-trajectories.svg"), figures::trajectories_svg(&model.mesh, &t, &title))
            .expect("can write the figure");
        let failed = t.truth.first().map_or(0, |v| v.iter().filter(|p| p.is_none()).count());
        format!(
            "\n## Trajectories (Fig. 3)\n\n![trajectories](defop-trajectories.svg)\n\nThe bar's TPS operator: the right \
             handle goes round a circle of 0.8 sampling radii about its rest position in {steps} steps, the left handle \
             at rest; the trajectories of {} vertices under the operator (blue) and the S-ARAP ground truth solved from \
             the rest pose at each step (black, dashed; {failed} steps without a solution).\n",
            t.tracked.len()
        )
    }

    fn energies_section(model: &models::Model, trained: &models::Trained, output: &str) -> String {
        let stretches = [0.6, 0.5, 0.4, 0.3, 0.2];
        let (targets, stretch, poses) = figures::energies(model, trained, &stretches);
        let title = format!("{}: one pose under ARAP and S-ARAP", model.name);
        std::fs::write(
            format!("{output}/defop-energies.svg"),
            figures::energies_svg(&model.mesh, &targets, &poses, &title),
        )
        .expect("can write the figure");
        let mut s = format!(
            "\n## ARAP against S-ARAP (Fig. 6)\n\n![energies](defop-energies.svg)\n\nThe {}'s tentacle tips moved \
             away from its head by {stretch} times their distance (the largest of {stretches:?} both energies solve), \
             solved from the rest pose under each energy; flipped triangles dark. E_area and E_angle as in \
             `lab/compare/comparison.md` (`akap::deform::metrics`: 2 for a rigid motion).\n\n\
             | energy | E_area | E_angle | flipped | Newton iterations |\n|---|---|---|---|---|\n",
            model.name
        );
        for p in &poses {
            let _ = writeln!(
                s,
                "| {} | {:.4} | {:.4} | {} | {} |",
                p.energy.name(),
                p.metrics.area_distortion,
                p.metrics.angle_distortion,
                p.metrics.flipped,
                p.iterations
            );
        }
        s
    }

    /// The wasm evaluation milliseconds per operator file, from the bench script.
    fn wasm_timings(manifest: &str) -> Result<std::collections::HashMap<String, f64>, String> {
        if !Path::new("www/lib/index.js").exists() {
            return Err("www/lib is not built (`bash scripts/build.sh --package`)".to_owned());
        }
        eprintln!("wasm timings: node lab/defop/bench-defop.mjs --operators {manifest}");
        let output = std::process::Command::new("node")
            .args(["lab/defop/bench-defop.mjs", "--operators", manifest])
            .output()
            .map_err(|e| format!("cannot run node: {e}"))?;
        if !output.status.success() {
            return Err(format!("the bench script failed: {}", String::from_utf8_lossy(&output.stderr)));
        }
        let text = String::from_utf8_lossy(&output.stdout);
        let value: serde_json::Value = serde_json::from_str(&text).map_err(|e| format!("bench output: {e}"))?;
        let map = value.as_object().ok_or("bench output is not an object")?;
        Ok(map.iter().filter_map(|(k, v)| Some((k.clone(), v.as_f64()?))).collect())
    }

    fn machine() -> String {
        let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|s| {
                s.lines()
                    .find(|l| l.starts_with("model name"))
                    .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_owned())
            })
            .unwrap_or_else(|| "unknown CPU".to_owned());
        format!("{cpu}, {cores} cores available (all timings single-threaded)")
    }

    fn markdown(
        mode: Mode,
        table: &str,
        notes: &str,
        extra: &str,
        wasm: &Result<std::collections::HashMap<String, f64>, String>,
        seconds: f64,
    ) -> String {
        let quick = if mode == Mode::Quick {
            "\n**Quick run** (`--quick`): few samples and small meshes, to check that everything runs; not the \
             paper's sizes. The full run is the command without `--quick`.\n"
        } else {
            ""
        };
        let wasm_note = match wasm {
            Ok(_) => {
                "wasm: `node lab/defop/bench-defop.mjs --operators target/defop-table/manifest.json` (run by this \
                      example), the same operator files through the JS API's `DefOp.fromBytes` and `evaluateInto`, \
                      Node, one thread."
                    .to_owned()
            }
            Err(why) => format!(
                "wasm columns empty: {why}. Build the package and run again, or time the operator files alone with \
                 `node lab/defop/bench-defop.mjs --operators target/defop-table/manifest.json`."
            ),
        };
        format!(
            "# DefOp: Table 1 and figures on our models\n\nGenerated by `cargo run --release --example defop_table{}` \
             ({} mode, {:.0} s) on {}; do not edit by hand.\n{quick}\n\
             The paper's table lost its numbers; these are its rows (bar TPS; aleph linear, cubic, TPS; octopus and crab \
             linear, quadratic, TPS; the octopus's TPS also on the hat functions, *TPS, hat*) on our own shapes (`akap::shapes::{{toothed_bar, aleph, octopus, crab}}`), with our \
             columns. n counts the moving handles (the bar also has a fixed one). m counts the rest pose (the trainer's samples + 1). *sampling s*: the ground-truth solves \
             (bootstrapped: warm starts from the current operator); *refits s*: the bootstrap's intermediate fits; \
             *iterations warm / cold*: mean Newton iterations per solve from a prediction / from the rest pose; *fit s*: \
             the final fit of the row's basis on all samples (TPS: the trainer's own final fit). *eval ms*, *fps*: one \
             `Operator::evaluate_into` (all vertices, double precision), native release build, mean over a loop of \
             held-out targets. *held-out*: {} targets drawn like the training's (discs, seed {}), ground truth solved \
             from the rest pose; RMS: mean over targets of the RMS vertex distance, max: the largest vertex distance, \
             both in % of the bounding-box diagonal. *MB*: the operator's coefficients and reduced basis (f64). \
             *(ridge)*: a polynomial basis larger than m, fitted with λ = {RIDGE}.\n\n{table}\n{wasm_note}\n\n{notes}{extra}",
            if mode == Mode::Quick { " -- --quick" } else { "" },
            mode.name(),
            seconds,
            machine(),
            mode.held_out(),
            models::HELD_OUT_SEED,
        )
    }
}

#[cfg(not(target_arch = "wasm32"))]
fn main() {
    run::main();
}

#[cfg(target_arch = "wasm32")]
fn main() {}
