//! Hostile and careless inputs (issue 16), timed natively: each builds one input at the
//! size the issue names and prints how long the library takes to accept or refuse it.
//!
//! `cargo run --release --example adversarial [-- CASE ...]` runs every case, or those
//! named (the names are in the first column). Building the input and the set-up around it
//! (a deformer's factorisation, say) is not timed.

use std::fmt::Write;
use std::time::Instant;

use akap::deform::arap::MAX_ITERATIONS;
use akap::deform::{AkapOptions, ArapOptions, Deformer};
use akap::geometry::Point;
use akap::import::svg::{import_svg, SvgOptions};
use akap::import::warp::PointMapper;
use akap::shapes::{comb, grid_mesh};
use akap::{triangulate, Outline, TriangulationOptions};

/// A circle of `n` points.
fn circle(n: usize, radius: f64) -> Vec<Point> {
    (0..n)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / n as f64;
            [radius * t.cos(), radius * t.sin()]
        })
        .collect()
}

fn svg(body: &str) -> String {
    format!(r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="-1 -1 2 2">{body}</svg>"#)
}

fn path_of(points: &[Point]) -> String {
    let mut d = String::with_capacity(points.len() * 24);
    for (k, p) in points.iter().enumerate() {
        let _ = write!(d, "{}{} {}", if k == 0 { 'M' } else { 'L' }, p[0], p[1]);
    }
    d.push('Z');
    d
}

/// The outcome in a line: what came out, or the error.
fn describe<T>(result: Result<T, impl std::fmt::Display>, ok: impl Fn(&T) -> String) -> String {
    match result {
        Ok(value) => ok(&value),
        Err(e) => {
            let text = e.to_string();
            let short: String = text.chars().take(110).collect();
            format!("error: {short}{}", if short.len() < text.len() { "..." } else { "" })
        }
    }
}

fn import(text: &str) -> String {
    describe(import_svg(text, &SvgOptions::default()), |s| {
        let points: usize = s.outlines.iter().map(|o| o.rings().map(<[Point]>::len).sum::<usize>()).sum();
        format!("{} outline(s), {points} points", s.outlines.len())
    })
}

fn mesh_outline(outline: &Outline) -> String {
    describe(triangulate(outline, &TriangulationOptions::default()), |m| format!("{} vertices", m.vertex_count()))
}

type Case = (&'static str, &'static str, fn() -> (Box<dyn FnOnce() -> String>, String));

const CASES: [Case; 11] = [
    ("svg-closes", "SVG path M0 0L1 0L0 1 and 1.6 million Z", || {
        let text = svg(&format!(r#"<path d="M0 0L1 0L0 1{}"/>"#, "Z".repeat(1_600_000)));
        let size = format!("{} bytes", text.len());
        (Box::new(move || import(&text)), size)
    }),
    ("svg-attributes", "one SVG element with 100,000 attributes", || {
        let attributes: String = (0..100_000).map(|k| format!(r#" a{k}="{k}""#)).collect();
        let text = svg(&format!(r#"<path d="M0 0L1 0L0 1Z"{attributes}/>"#));
        let size = format!("{} bytes", text.len());
        (Box::new(move || import(&text)), size)
    }),
    ("svg-polygons", "33,000 small polygons", || {
        let body: String = (0..33_000)
            .map(|k| {
                let (x, y) = ((k % 182) as f64 * 0.01 - 0.91, (k / 182) as f64 * 0.01 - 0.91);
                format!(r#"<polygon points="{x} {y} {} {y} {x} {}"/>"#, x + 0.005, y + 0.005)
            })
            .collect();
        let text = svg(&body);
        let size = format!("{} bytes", text.len());
        (Box::new(move || import(&text)), size)
    }),
    ("svg-long-path", "one 80,000-point path (a circle)", || {
        let text = svg(&format!(r#"<path d="{}"/>"#, path_of(&circle(80_000, 0.9))));
        let size = format!("{} bytes", text.len());
        (Box::new(move || import(&text)), size)
    }),
    ("svg-comb-path", "one 80,000-point path (a comb)", || {
        let points: Vec<Point> = comb(20_000, 40_000.0).iter().map(|p| [p[0] / 40_000.0, p[1] / 40_000.0]).collect();
        let text = svg(&format!(r#"<path d="{}"/>"#, path_of(&points)));
        let size = format!("{} bytes", text.len());
        (Box::new(move || import(&text)), size)
    }),
    ("outline-circle", "triangulate a 100,000-point circle (defaults)", || {
        let outline = Outline::new(circle(100_000, 1.0));
        (Box::new(move || mesh_outline(&outline)), "100000 points".into())
    }),
    ("outline-comb", "triangulate a 100,000-point comb (defaults)", || {
        let outline = Outline::new(comb(25_000, 50_000.0));
        (Box::new(move || mesh_outline(&outline)), "100000 points".into())
    }),
    ("handles", "setHandles: 100,489 distinct vertex handles", || {
        let mesh = grid_mesh(316, 316);
        let vertices: Vec<u32> = (0..mesh.vertex_count() as u32).collect();
        let mut deformer = Deformer::new(mesh, AkapOptions::default()).expect("a grid deforms");
        let size = format!("{} handles", vertices.len());
        (Box::new(move || describe(deformer.set_handle_vertices(&vertices), |()| "set".into())), size)
    }),
    ("point-mapper", "PointMapper: 100,000 points outside a 20,000-triangle mesh", || {
        let mesh = grid_mesh(100, 100);
        // On a circle around the square [0, 100]^2.
        let points: Vec<Point> = circle(100_000, 80.0).iter().map(|p| [p[0] + 50.0, p[1] + 50.0]).collect();
        let size = format!("{} triangles, {} points", mesh.triangle_count(), points.len());
        let run = move || describe(PointMapper::new(&mesh, &points), |m| format!("{} points located", m.len()));
        (Box::new(run), size)
    }),
    ("arap-iterations", "ARAP step() with 1,000,000 iterations, 1,089 vertices", || arap_step(1_000_000)),
    ("arap-most-iterations", "ARAP step() with the most iterations allowed, 1,089 vertices", || {
        arap_step(MAX_ITERATIONS)
    }),
];

/// One ARAP step of `iterations` on a 32 x 32 grid, two corners pulled apart.
fn arap_step(iterations: usize) -> (Box<dyn FnOnce() -> String>, String) {
    let mesh = grid_mesh(32, 32);
    let size = format!("{} vertices", mesh.vertex_count());
    let made = Deformer::new(mesh, ArapOptions::default().with_iterations(iterations));
    let run = move || match made {
        Ok(mut deformer) => describe(
            deformer.set_handle_vertices(&[0, 1088]).and_then(|()| deformer.step(&[[0.0, 0.0], [1.0, 1.0]])),
            |()| format!("{} iterations", deformer.arap().expect("ARAP").report().iterations),
        ),
        Err(e) => format!("error: {e}"),
    };
    (Box::new(run), size)
}

fn main() {
    let chosen: Vec<String> = std::env::args().skip(1).collect();
    if let Some(unknown) = chosen.iter().find(|c| !CASES.iter().any(|(name, ..)| name == c)) {
        let names: Vec<&str> = CASES.iter().map(|(name, ..)| *name).collect();
        eprintln!("unknown case `{unknown}`; the cases are {}", names.join(", "));
        std::process::exit(2);
    }
    println!("| case | input | size | seconds | outcome |");
    println!("|---|---|---|---|---|");
    for (name, what, build) in CASES {
        if !chosen.is_empty() && !chosen.iter().any(|c| c == name) {
            continue;
        }
        let (run, size) = build();
        let start = Instant::now();
        let outcome = run();
        let seconds = start.elapsed().as_secs_f64();
        println!("| {name} | {what} | {size} | {seconds:.3} | {outcome} |");
    }
}
