//! The paper's comparison (Table 1, Figures 8 and 9) on our recorded sessions: every session in
//! `tests/sessions/` replayed with AKAP, its ablations, ARAP, rigid MLS and point-to-point
//! Cauchy-Green; prints the paper's Table 1 on our models and a Markdown table per session
//! (E_area, E_angle, handle error, milliseconds per frame, flipped triangles) and writes
//! it to `lab/compare/comparison.md`, with the final poses side by side in
//! `lab/compare/comparison.svg`.
//!
//! `cargo run --release --example compare [-- SESSION_DIR [OUTPUT_DIR]]`
//! (defaults `tests/sessions` and `lab/compare`).
//!
//! AKAP with the recorded options replays the velocities as recorded (so it repeats the
//! recording exactly); every other method is driven to the recording's targets (each
//! handle's position before a step plus its recorded velocity), since a positional method
//! and the ablations see other handle positions. Milliseconds per frame are the mean of
//! the deformers' own stage timings over the steps, single-threaded, natively.

use std::fmt::Write as _;

use akap::deform::metrics::{deformation_gradient, singular_values};
use akap::deform::{AkapOptions, ArapOptions, CauchyGreenOptions, Deformer, Integrator, MethodOptions, MlsOptions};
use akap::geometry::Point;
use akap::pose::{replay, replay_to_targets, Replay};
use akap::session::Session;
use akap::Mesh;

/// A row of the comparison: a label and how to build the deformer.
struct Variant {
    label: &'static str,
    short: &'static str,
    options: MethodOptions,
}

fn variants(recorded: AkapOptions) -> Vec<Variant> {
    let akap = |dirichlet: bool, integrator: Integrator| {
        MethodOptions::Akap(recorded.with_dirichlet(dirichlet).with_integrator(integrator))
    };
    vec![
        Variant { label: "AKAP", short: "AKAP", options: akap(true, Integrator::Spiral) },
        Variant {
            label: "AKAP without Dirichlet step",
            short: "no Dirichlet",
            options: akap(false, Integrator::Spiral),
        },
        Variant { label: "AKAP with linear steps", short: "linear", options: akap(true, Integrator::Linear) },
        Variant { label: "AKAP, both simplifications", short: "both", options: akap(false, Integrator::Linear) },
        Variant {
            label: "ARAP, 10 iterations per frame",
            short: "ARAP 10/frame",
            options: MethodOptions::Arap(ArapOptions::default().with_iterations(10)),
        },
        Variant {
            label: "ARAP, to convergence every frame (tolerance 1e-8, at most 2000 iterations)",
            short: "ARAP converged",
            options: MethodOptions::Arap(ArapOptions::default().until_converged(1e-8, 2000)),
        },
        Variant {
            label: "moving least squares, rigid (alpha 1)",
            short: "MLS rigid",
            options: MethodOptions::Mls(MlsOptions::default()),
        },
        Variant {
            label: "Cauchy-Green, point to point (64-vertex cage, smoothness 1e-5)",
            short: "Cauchy-Green",
            options: MethodOptions::CauchyGreen(CauchyGreenOptions::default()),
        },
    ]
}

/// One replayed pose with its measures.
struct Outcome {
    positions: Vec<Point>,
    handles: Vec<Point>,
    targets: Vec<Point>,
    area: f64,
    angle: f64,
    flipped: usize,
    /// The largest per-triangle angle distortion `sigma1 / sigma2 + sigma2 / sigma1`.
    worst_angle: f64,
    handle_error: f64,
    ms_per_frame: f64,
}

/// The largest per-triangle angle distortion of a pose.
fn worst_angle(mesh: &Mesh, positions: &[Point]) -> f64 {
    mesh.triangles()
        .iter()
        .map(|t| {
            let f = deformation_gradient(t.map(|v| mesh.positions()[v as usize]), t.map(|v| positions[v as usize]));
            let (s1, s2, _) = singular_values(f[0][0], f[0][1], f[1][0], f[1][1]);
            s1 / s2 + s2 / s1
        })
        .fold(2.0, f64::max)
}

/// Table 1 of the paper on our sessions: E_area and E_angle of Cauchy-Green, converged ARAP
/// and AKAP on the bent bar and the two cartoons, the paper's values beside them, and the
/// rigid MLS row of its inset.
fn table_1(rows: &[(String, Mesh, Vec<Outcome>)], labels: &[&str]) -> String {
    const PAPER: [(&str, &str, [f64; 6]); 3] = [
        ("bar-fold", "bar", [2.356, 2.042, 2.070, 2.001, 2.036, 2.062]),
        ("cat", "elephant", [4.605, 2.019, 2.030, 2.151, 2.033, 2.054]),
        ("gingerbread", "alien", [2.596, 2.012, 2.016, 2.004, 2.013, 2.017]),
    ];
    let columns = ["Cauchy-Green", "ARAP converged", "AKAP"];
    let mut out = String::from(
        "\n## Table 1 on our models\n\n\
         The paper's Table 1 layout: each model driven to the same handle targets (the recorded \
         session's) by each method; the paper's values for its own models and poses in \
         parentheses (its bar, elephant and alien; the poses are not published, so only the \
         ordering of the methods is comparable).\n\n\
         | model | E_area CG | E_area ARAP | E_area AKAP | E_angle CG | E_angle ARAP | E_angle AKAP |\n\
         |---|---|---|---|---|---|---|\n",
    );
    for (name, paper_name, paper) in PAPER {
        let Some((_, _, poses)) = rows.iter().find(|(n, _, _)| n == name) else { continue };
        let pose = |label: &str| labels.iter().position(|l| *l == label).map(|i| &poses[i]);
        let _ = write!(out, "| {name} ({paper_name}) |");
        for (k, measure) in [|o: &Outcome| o.area, |o: &Outcome| o.angle].iter().enumerate() {
            for (c, label) in columns.iter().enumerate() {
                let value = pose(label).map_or(f64::NAN, measure);
                let _ = write!(out, " {value:.3} ({:.3}) |", paper[3 * k + c]);
            }
        }
        out += "\n";
    }
    if let Some((_, _, poses)) = rows.iter().find(|(n, _, _)| n == "bar-fold") {
        if let Some(i) = labels.iter().position(|l| *l == "MLS rigid") {
            let _ = writeln!(
                out,
                "\nRigid MLS on bar-fold: E_area {:.3}, E_angle {:.3} (the paper's inset, its bar bent: 4.951, 8.158).",
                poses[i].area, poses[i].angle
            );
        }
    }
    out
}

fn outcome(deformer: &Deformer, replay: &Replay) -> Outcome {
    let m = deformer.metrics();
    Outcome {
        worst_angle: worst_angle(deformer.mesh(), deformer.positions()),
        positions: deformer.positions().to_vec(),
        handles: deformer.shape_under_handles(),
        targets: replay.targets.last().cloned().unwrap_or_default(),
        area: m.area_distortion,
        angle: m.angle_distortion,
        flipped: m.flipped,
        handle_error: replay.handle_error.unwrap_or(f64::NAN),
        ms_per_frame: replay.frame_ms.iter().sum::<f64>() / replay.frame_ms.len().max(1) as f64,
    }
}

fn main() {
    let mut args = std::env::args().skip(1);
    let session_dir = args.next().unwrap_or_else(|| "tests/sessions".to_owned());
    let output_dir = args.next().unwrap_or_else(|| "lab/compare".to_owned());
    let mut paths: Vec<_> = std::fs::read_dir(&session_dir)
        .unwrap_or_else(|e| panic!("cannot read {session_dir}: {e}"))
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    paths.sort();

    let mut table = String::new();
    let mut figure_rows = Vec::new();
    let mut labels = Vec::new();
    for path in &paths {
        let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
        let session = Session::from_json(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let mesh = session.mesh().unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let mut recorded = session.recorded_deformer().expect("the session's mesh and options");
        let recording = replay(&session, &mut recorded).unwrap_or_else(|e| panic!("{}: {e}", path.display()));

        let name = &path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        let _ = writeln!(
            table,
            "\n### {name} ({} vertices, {} triangles, {} frames)\n",
            mesh.vertex_count(),
            mesh.triangle_count(),
            session.step_count()
        );
        table += "| method | E_area | E_angle | worst triangle's E_angle | handle error | ms / frame | flipped |\n\
                  |---|---|---|---|---|---|---|\n";
        let rest = Outcome {
            positions: mesh.positions().to_vec(),
            handles: Vec::new(),
            targets: Vec::new(),
            area: 2.0,
            angle: 2.0,
            flipped: 0,
            worst_angle: 2.0,
            handle_error: 0.0,
            ms_per_frame: 0.0,
        };
        let mut poses = vec![rest];
        labels.clear();
        labels.push("rest");
        let recorded_options = session.method_options().expect("as above");
        let akap_options = match recorded_options {
            MethodOptions::Akap(options) => options,
            _ => AkapOptions::default(),
        };
        for variant in variants(akap_options) {
            let result = if variant.options == recorded_options {
                let mut deformer = session.recorded_deformer().expect("as above");
                let r = replay(&session, &mut deformer).expect("as above");
                outcome(&deformer, &r)
            } else {
                let mut deformer = Deformer::new(mesh.clone(), variant.options).expect("a connected mesh");
                let r = replay_to_targets(&session, &recording.targets, &mut deformer)
                    .unwrap_or_else(|e| panic!("{name}, {}: {e}", variant.label));
                outcome(&deformer, &r)
            };
            let _ = writeln!(
                table,
                "| {} | {:.4} | {:.4} | {:.3} | {:.2e} | {:.2} | {} |",
                variant.label,
                result.area,
                result.angle,
                result.worst_angle,
                result.handle_error,
                result.ms_per_frame,
                result.flipped
            );
            eprintln!("{name}: {} done", variant.label);
            labels.push(variant.short);
            poses.push(result);
        }
        figure_rows.push((name.clone(), mesh, poses));
    }

    let mut markdown = String::from(
        "# AKAP, its ablations, ARAP, MLS and Cauchy-Green on recorded sessions\n\n\
         Generated by `cargo run --release --example compare` from `tests/sessions/*.json` \
         (written by `cargo run --release --example make_sessions`); do not edit by hand. \
         E_area and E_angle are the paper's area and angle distortion (2 for a rigid motion), \
         averaged over triangles by rest area, and the largest angle distortion of a single \
         triangle (where local artefacts such as the singular fields of Figure 8 show); handle \
         error is the mean distance of the shape's points under the handles from their targets \
         after the last frame; ms / frame is the mean of the deformer's \
         stage timings (single thread, native release build, on a machine shared with other \
         jobs, so only roughly comparable); flipped counts inverted triangles. AKAP replays the \
         recorded velocities; the other rows are driven to the recorded targets.\n",
    );
    markdown += &table_1(&figure_rows, &labels);
    markdown += &table;
    markdown += "\nFigure: `comparison.svg` (final poses; red dots are the targets, blue the shape's \
                 points under the handles; triangles whose angle distortion exceeds 2.2 are drawn \
                 darker).\n";
    print!("{markdown}");
    std::fs::create_dir_all(&output_dir).expect("can make the output directory");
    std::fs::write(format!("{output_dir}/comparison.md"), &markdown).expect("can write the table");
    std::fs::write(format!("{output_dir}/comparison.svg"), svg(&figure_rows, &labels)).expect("can write the figure");
    eprintln!("wrote {output_dir}/comparison.md and {output_dir}/comparison.svg");
}

/// The figure: one row per session, one column per method, each pose scaled to its cell.
fn svg(rows: &[(String, Mesh, Vec<Outcome>)], labels: &[&str]) -> String {
    let (cell_w, cell_h, label_w, head_h) = (200.0, 170.0, 90.0, 24.0);
    let width = label_w + cell_w * labels.len() as f64;
    let height = head_h + cell_h * rows.len() as f64;
    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" \
         viewBox=\"0 0 {width} {height}\" font-family=\"sans-serif\" font-size=\"12\">\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    );
    // The first column is the rest pose.
    for (c, label) in labels.iter().enumerate() {
        let x = label_w + cell_w * (c as f64 + 0.5);
        let _ = writeln!(out, "<text x=\"{x}\" y=\"16\" text-anchor=\"middle\">{label}</text>");
    }
    for (r, (name, mesh, poses)) in rows.iter().enumerate() {
        let y0 = head_h + cell_h * r as f64;
        let _ = writeln!(out, "<text x=\"6\" y=\"{}\">{name}</text>", y0 + cell_h / 2.0);
        // One scale per row, so the poses of a shape compare directly.
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for pose in poses {
            for p in pose.positions.iter().chain(&pose.targets) {
                for k in 0..2 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
        let scale = ((cell_w - 16.0) / (hi[0] - lo[0])).min((cell_h - 16.0) / (hi[1] - lo[1]));
        let loops = mesh.boundary_loops();
        for (c, pose) in poses.iter().enumerate() {
            let x0 = label_w + cell_w * c as f64 + (cell_w - scale * (hi[0] - lo[0])) / 2.0;
            let top = y0 + (cell_h - scale * (hi[1] - lo[1])) / 2.0;
            let at = |p: Point| (x0 + scale * (p[0] - lo[0]), top + scale * (hi[1] - p[1]));
            let mut d = String::new();
            for ring in &loops {
                for (k, &v) in ring.iter().enumerate() {
                    let (x, y) = at(pose.positions[v as usize]);
                    let _ = write!(d, "{}{x:.1} {y:.1}", if k == 0 { "M" } else { "L" });
                }
                d += "Z";
            }
            let _ = writeln!(
                out,
                "<path d=\"{d}\" fill=\"#f3c48c\" fill-rule=\"evenodd\" stroke=\"#7a4a1e\" stroke-width=\"0.6\"/>"
            );
            // Strongly distorted triangles, darker.
            let mut dark = String::new();
            for t in mesh.triangles() {
                let rest = t.map(|v| mesh.positions()[v as usize]);
                let now = t.map(|v| pose.positions[v as usize]);
                let f = deformation_gradient(rest, now);
                let (s1, s2, det) = singular_values(f[0][0], f[0][1], f[1][0], f[1][1]);
                if det <= 0.0 || s1 / s2 + s2 / s1 > 2.2 {
                    for (k, p) in now.iter().enumerate() {
                        let (x, y) = at(*p);
                        let _ = write!(dark, "{}{x:.1} {y:.1}", if k == 0 { "M" } else { "L" });
                    }
                    dark += "Z";
                }
            }
            if !dark.is_empty() {
                let _ = writeln!(out, "<path d=\"{dark}\" fill=\"#b0412e\"/>");
            }
            for p in &pose.targets {
                let (x, y) = at(*p);
                let _ = writeln!(out, "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"3\" fill=\"#d22\"/>");
            }
            for p in &pose.handles {
                let (x, y) = at(*p);
                let _ = writeln!(out, "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"1.6\" fill=\"#14c\"/>");
            }
            let (x, y) = (label_w + cell_w * c as f64 + cell_w / 2.0, y0 + cell_h - 4.0);
            let _ = writeln!(
                out,
                "<text x=\"{x}\" y=\"{y}\" text-anchor=\"middle\" font-size=\"10\" fill=\"#555\">{:.3} / {:.3}</text>",
                pose.area, pose.angle
            );
        }
    }
    out += "</svg>\n";
    out
}
