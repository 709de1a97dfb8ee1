//! The figures: the convergence study (Fig. 8), handle trajectories (Fig. 3) and ARAP
//! against S-ARAP (Fig. 6), as SVG.

use std::fmt::Write as _;

use akap::defop::{BasisKind, Energy, Start, TrainOptions, Trainer};
use akap::deform::metrics::{metrics, Metrics};
use akap::geometry::Point;
use akap::Mesh;

use crate::models::{error, fit_basis, HeldOut, Model, Trained};

/// The bases of the convergence study, with their colours.
const BASES: [(BasisKind, &str, &str); 4] = [
    (BasisKind::Linear, "linear", "#1f77b4"),
    (BasisKind::Quadratic, "quadratic", "#2ca02c"),
    (BasisKind::Cubic, "cubic", "#d62728"),
    (BasisKind::Tps, "TPS", "#222222"),
];

/// One point of the convergence study: m, and per basis the held-out RMS error (relative
/// to the diagonal) and whether the ridge was used.
pub(crate) type ConvergencePoint = (usize, [(f64, bool); 4]);

/// The held-out error of each basis fitted to the first `m - 1` samples (with the rest
/// pose, m) for each `m` the training holds.
pub(crate) fn convergence(model: &Model, trained: &Trained, held: &HeldOut, ms: &[usize]) -> Vec<ConvergencePoint> {
    let mut points = Vec::new();
    for &m in ms.iter().filter(|&&m| m <= trained.targets.len() + 1) {
        let mut row = [(0.0, false); 4];
        for (slot, (kind, _, _)) in row.iter_mut().zip(BASES) {
            let (mut operator, _, ridge) = fit_basis(model, trained, kind, m - 1);
            *slot = (error(model, &mut operator, held).0, ridge);
        }
        eprintln!("  convergence: m = {m} done");
        points.push((m, row));
    }
    points
}

/// The convergence plot: error (log scale) against m, one line per basis; hollow markers
/// where the ridge was used.
pub(crate) fn convergence_svg(points: &[ConvergencePoint], title: &str) -> String {
    let (width, height, left, right, top, bottom) = (640.0, 420.0, 70.0, 130.0, 30.0, 50.0);
    let m_max = points.iter().map(|p| p.0).max().unwrap_or(1) as f64;
    let errors = points.iter().flat_map(|p| p.1.iter().map(|e| e.0)).filter(|e| *e > 0.0);
    let (lo, hi) = errors.fold((f64::INFINITY, 0.0f64), |(lo, hi), e| (lo.min(e), hi.max(e)));
    let (decade_lo, decade_hi) = (lo.log10().floor(), hi.log10().ceil().max(lo.log10().floor() + 1.0));
    let x = |m: f64| left + (width - left - right) * m / m_max;
    let y = |e: f64| top + (height - top - bottom) * (decade_hi - e.log10()) / (decade_hi - decade_lo);
    let mut out = svg_open(width, height);
    let _ = writeln!(out, "<text x=\"{}\" y=\"18\" text-anchor=\"middle\">{title}</text>", width / 2.0);
    // Axes, decades and the m ticks.
    let (x0, x1, y0, y1) = (left, width - right, top, height - bottom);
    let _ = writeln!(out, "<path d=\"M{x0} {y0}V{y1}H{x1}\" fill=\"none\" stroke=\"black\"/>");
    let mut decade = decade_lo;
    while decade <= decade_hi + 1e-9 {
        let yy = y(10f64.powf(decade));
        let _ = writeln!(
            out,
            "<path d=\"M{x0} {yy:.1}H{x1}\" stroke=\"#ddd\"/><text x=\"{}\" y=\"{:.1}\" text-anchor=\"end\">1e{decade}</text>",
            x0 - 6.0,
            yy + 4.0
        );
        decade += 1.0;
    }
    for p in points {
        let xx = x(p.0 as f64);
        let _ = writeln!(out, "<text x=\"{xx:.1}\" y=\"{}\" text-anchor=\"middle\">{}</text>", y1 + 16.0, p.0);
    }
    let _ = writeln!(
        out,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">samples m</text>\n\
         <text x=\"16\" y=\"{}\" text-anchor=\"middle\" transform=\"rotate(-90 16 {})\">held-out RMS error / diagonal</text>",
        (x0 + x1) / 2.0,
        height - 12.0,
        (y0 + y1) / 2.0,
        (y0 + y1) / 2.0
    );
    for (b, (_, label, colour)) in BASES.iter().enumerate() {
        let mut d = String::new();
        for (k, p) in points.iter().enumerate() {
            let _ = write!(d, "{}{:.1} {:.1}", if k == 0 { "M" } else { "L" }, x(p.0 as f64), y(p.1[b].0));
        }
        let _ = writeln!(out, "<path d=\"{d}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.5\"/>");
        for p in points {
            let fill = if p.1[b].1 { "white" } else { colour };
            let _ = writeln!(
                out,
                "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"3.5\" fill=\"{fill}\" stroke=\"{colour}\"/>",
                x(p.0 as f64),
                y(p.1[b].0)
            );
        }
        let ly = top + 20.0 + 20.0 * b as f64;
        let _ = writeln!(
            out,
            "<path d=\"M{} {ly}h24\" stroke=\"{colour}\" stroke-width=\"2\"/><text x=\"{}\" y=\"{}\">{label}</text>",
            x1 + 12.0,
            x1 + 42.0,
            ly + 4.0
        );
    }
    let _ = writeln!(out, "<text x=\"{}\" y=\"{}\" font-size=\"10\">hollow: ridge</text>", x1 + 12.0, top + 110.0);
    out + "</svg>\n"
}

/// The trajectories figure's data: the moving handle's path and, per tracked vertex, its
/// positions along it under the operator and the ground truth (`None` where the ground
/// truth's solve failed).
pub(crate) struct Trajectories {
    pub(crate) path: Vec<Point>,
    pub(crate) tracked: Vec<usize>,
    pub(crate) operator: Vec<Vec<Point>>,
    pub(crate) truth: Vec<Vec<Option<Point>>>,
}

/// The last handle sweeps a circle of 0.8 times the sampling radius round its rest
/// position in `steps` steps, the others at rest; `spots` name the vertices tracked.
pub(crate) fn trajectories(model: &Model, trained: &mut Trained, spots: &[Point], steps: usize) -> Trajectories {
    let n = trained.rest.len();
    let centre = trained.rest[n - 1];
    let r = 0.8 * trained.radius;
    let p = model.mesh.positions();
    let nearest = |s: &Point| {
        (0..p.len())
            .min_by(|&a, &b| (p[a][0] - s[0]).hypot(p[a][1] - s[1]).total_cmp(&(p[b][0] - s[0]).hypot(p[b][1] - s[1])))
    };
    let tracked: Vec<usize> = spots.iter().filter_map(nearest).collect();
    let mut result = Trajectories {
        path: Vec::new(),
        operator: vec![Vec::new(); tracked.len()],
        truth: vec![Vec::new(); tracked.len()],
        tracked,
    };
    for k in 0..=steps {
        let angle = std::f64::consts::TAU * k as f64 / steps as f64;
        let q = [centre[0] + r * angle.cos(), centre[1] + r * angle.sin()];
        let mut targets = trained.rest.clone();
        targets[n - 1] = q;
        result.path.push(q);
        let flat: Vec<f64> = targets.iter().flatten().copied().collect();
        let predicted = trained.operator.evaluate(&flat).expect("targets of the right length");
        let truth = trained.solver.solve(&targets, Start::Rest).ok();
        for (t, &v) in result.tracked.iter().enumerate() {
            result.operator[t].push([predicted[2 * v], predicted[2 * v + 1]]);
            result.truth[t].push(truth.as_ref().map(|s| s.positions[v]));
        }
    }
    result
}

/// The trajectories figure: the rest shape, the handle's path (red), each tracked vertex's
/// trajectory under the operator (blue) and the ground truth (black, dashed).
pub(crate) fn trajectories_svg(mesh: &Mesh, t: &Trajectories, title: &str) -> String {
    let truth: Vec<Point> = t.truth.iter().flatten().flatten().copied().collect();
    let all = mesh.positions().iter().chain(&t.path).chain(t.operator.iter().flatten()).chain(&truth);
    let frame = Frame::around(all, 900.0, 300.0);
    let mut out = svg_open(frame.width, frame.height + 30.0);
    let _ = writeln!(out, "<text x=\"{}\" y=\"18\" text-anchor=\"middle\">{title}</text>", frame.width / 2.0);
    out += "<g transform=\"translate(0 30)\">\n";
    out += &pose(mesh, mesh.positions(), &frame, "#eee", "#999");
    let polyline = |points: &mut dyn Iterator<Item = Option<Point>>| {
        let mut d = String::new();
        let mut pen_up = true;
        for p in points {
            match p {
                Some(p) => {
                    let (x, y) = frame.at(p);
                    let _ = write!(d, "{}{x:.1} {y:.1}", if pen_up { "M" } else { "L" });
                    pen_up = false;
                }
                None => pen_up = true,
            }
        }
        d
    };
    let d = polyline(&mut t.path.iter().map(|p| Some(*p)));
    let _ = writeln!(out, "<path d=\"{d}\" fill=\"none\" stroke=\"#d22\" stroke-width=\"1.5\"/>");
    for (k, &v) in t.tracked.iter().enumerate() {
        let d = polyline(&mut t.truth[k].iter().copied());
        let _ = writeln!(
            out,
            "<path d=\"{d}\" fill=\"none\" stroke=\"black\" stroke-width=\"1.2\" stroke-dasharray=\"4 3\"/>"
        );
        let d = polyline(&mut t.operator[k].iter().map(|p| Some(*p)));
        let _ = writeln!(out, "<path d=\"{d}\" fill=\"none\" stroke=\"#14c\" stroke-width=\"1.2\"/>");
        let (x, y) = frame.at(mesh.positions()[v]);
        let _ = writeln!(out, "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"2.5\" fill=\"#14c\"/>");
    }
    out += "</g>\n";
    let _ = writeln!(
        out,
        "<text x=\"10\" y=\"{}\" font-size=\"11\">red: the moving handle's path; blue: the operator's trajectories; \
         black dashed: the ground truth's</text>",
        frame.height + 24.0
    );
    out + "</svg>\n"
}

/// One pose under one energy, with its distortion.
pub(crate) struct Pose {
    pub(crate) energy: Energy,
    pub(crate) positions: Vec<Point>,
    pub(crate) metrics: Metrics,
    pub(crate) iterations: usize,
}

/// The ground truths of ARAP and S-ARAP for the handle targets: every handle but the
/// first (the octopus's head) moved away from the first by `stretch` times its distance,
/// the first of `stretches` that both energies solve.
pub(crate) fn energies(model: &Model, trained: &Trained, stretches: &[f64]) -> (Vec<Point>, f64, Vec<Pose>) {
    let head = trained.rest[0];
    for &stretch in stretches {
        let targets: Vec<Point> = std::iter::once(head)
            .chain(
                trained.rest[1..]
                    .iter()
                    .map(|p| [p[0] + stretch * (p[0] - head[0]), p[1] + stretch * (p[1] - head[1])]),
            )
            .collect();
        let poses: Option<Vec<Pose>> = [Energy::Arap, Energy::SArap]
            .into_iter()
            .map(|energy| {
                let options = TrainOptions { energy, ..model.options.clone() };
                let mut solver = Trainer::solver_for(&model.mesh, &model.handles, &options).ok()?;
                let report = solver.solve(&targets, Start::Rest).ok()?;
                let m = metrics(model.mesh.positions(), &report.positions, model.mesh.triangles());
                Some(Pose { energy, positions: report.positions, metrics: m, iterations: report.iterations })
            })
            .collect();
        if let Some(poses) = poses {
            return (targets, stretch, poses);
        }
        eprintln!("  energies: a solve failed at stretch {stretch}, trying less");
    }
    panic!("no pose of {} solved under both energies", model.name);
}

/// The energies figure: the rest pose and each energy's pose side by side, targets in red,
/// flipped triangles dark.
pub(crate) fn energies_svg(mesh: &Mesh, targets: &[Point], poses: &[Pose], title: &str) -> String {
    let all = mesh.positions().iter().chain(targets).chain(poses.iter().flat_map(|p| &p.positions));
    let cell = 320.0;
    let frame = Frame::around(all, cell, cell);
    let width = cell * (1 + poses.len()) as f64;
    let mut out = svg_open(width, cell + 50.0);
    let _ = writeln!(out, "<text x=\"{}\" y=\"18\" text-anchor=\"middle\">{title}</text>", width / 2.0);
    let panels = std::iter::once(("rest".to_owned(), mesh.positions(), None))
        .chain(poses.iter().map(|p| (p.energy.name().to_owned(), p.positions.as_slice(), Some(p.metrics))));
    for (k, (label, positions, m)) in panels.enumerate() {
        let _ = writeln!(out, "<g transform=\"translate({} 30)\">", cell * k as f64);
        out += &pose(mesh, positions, &frame, "#f3c48c", "#7a4a1e");
        let mut dark = String::new();
        for t in mesh.triangles() {
            let [a, b, c] = t.map(|v| positions[v as usize]);
            if (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]) <= 0.0 {
                for (i, p) in [a, b, c].iter().enumerate() {
                    let (x, y) = frame.at(*p);
                    let _ = write!(dark, "{}{x:.1} {y:.1}", if i == 0 { "M" } else { "L" });
                }
                dark += "Z";
            }
        }
        if !dark.is_empty() {
            let _ = writeln!(out, "<path d=\"{dark}\" fill=\"#b0412e\"/>");
        }
        if m.is_some() {
            for p in targets {
                let (x, y) = frame.at(*p);
                let _ = writeln!(out, "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"3\" fill=\"#d22\"/>");
            }
        }
        let caption = m.map_or(label.clone(), |m| {
            format!(
                "{label}: E_area {:.3}, E_angle {:.3}, {} flipped",
                m.area_distortion, m.angle_distortion, m.flipped
            )
        });
        let _ = writeln!(
            out,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{caption}</text>\n</g>",
            cell / 2.0,
            cell + 12.0
        );
    }
    out + "</svg>\n"
}

/// A uniform scale from shape coordinates (y up) to a `width` x `height` box (y down).
struct Frame {
    lo: Point,
    hi: Point,
    scale: f64,
    width: f64,
    height: f64,
}

impl Frame {
    fn around<'a>(points: impl Iterator<Item = &'a Point>, width: f64, height: f64) -> Self {
        let (lo, hi) = akap::geometry::bounding_box(points.copied()).expect("points to draw");
        let margin = 10.0;
        let scale = ((width - 2.0 * margin) / (hi[0] - lo[0])).min((height - 2.0 * margin) / (hi[1] - lo[1]));
        Self { lo, hi, scale, width, height }
    }

    fn at(&self, p: Point) -> (f64, f64) {
        let (w, h) = (self.scale * (self.hi[0] - self.lo[0]), self.scale * (self.hi[1] - self.lo[1]));
        let (x0, y0) = ((self.width - w) / 2.0, (self.height - h) / 2.0);
        (x0 + self.scale * (p[0] - self.lo[0]), y0 + self.scale * (self.hi[1] - p[1]))
    }
}

/// A pose's outline (outer boundary and holes) as a filled SVG path.
fn pose(mesh: &Mesh, positions: &[Point], frame: &Frame, fill: &str, stroke: &str) -> String {
    let mut d = String::new();
    for ring in mesh.boundary_loops() {
        for (k, &v) in ring.iter().enumerate() {
            let (x, y) = frame.at(positions[v as usize]);
            let _ = write!(d, "{}{x:.1} {y:.1}", if k == 0 { "M" } else { "L" });
        }
        d += "Z";
    }
    format!("<path d=\"{d}\" fill=\"{fill}\" fill-rule=\"evenodd\" stroke=\"{stroke}\" stroke-width=\"0.8\"/>\n")
}

fn svg_open(width: f64, height: f64) -> String {
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" \
         viewBox=\"0 0 {width} {height}\" font-family=\"sans-serif\" font-size=\"12\">\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    )
}
