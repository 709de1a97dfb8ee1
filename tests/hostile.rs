//! Hostile and careless callers (issue 16): inputs that used to take seconds to minutes
//! (quadratic work) now give their result or a clear error. Sizes here would have taken
//! seconds with the old code; `lab/hostile/adversarial.rs` times the issue's full sizes.
//! Expected results come from the inputs' geometry, never from the code under test.
//! Runs natively and as wasm.

use akap::deform::arap::MAX_ITERATIONS;
use akap::deform::{AkapOptions, ArapOptions, DeformError, Deformer};
use akap::geometry::Point;
use akap::import::svg::{import_svg, SvgOptions};
use akap::import::vector::Verb;
use akap::import::warp::PointMapper;
use akap::import::{ImportError, Limits};
use akap::shapes::{comb, grid_mesh as grid};
use akap::{triangulate, Outline, OutlineError, Ring, TriangulationError, TriangulationOptions};
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common::Rng;

fn svg(view_box: &str, body: &str) -> String {
    format!(r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="{view_box}">{body}</svg>"#)
}

fn path_data(points: &[Point]) -> String {
    let commands: Vec<String> = points
        .iter()
        .enumerate()
        .map(|(k, p)| format!("{}{} {}", if k == 0 { 'M' } else { 'L' }, p[0], p[1]))
        .collect();
    commands.concat() + "Z"
}

#[test]
fn a_path_of_many_closepaths_parses_in_one_pass() {
    // (svgtypes, which usvg reads path data with, recurses once per repeated closepath: the
    // importer makes each run one first, or this would overflow the stack.)
    let closes = 300_000;
    let d = format!("M0 0L1 0L0 1{}", "Z".repeat(closes));
    // The triangle, y flipped in the 1 x 1 viewBox: area 1/2.
    let shape = import_svg(&svg("0 0 1 1", &format!(r#"<path d="{d}"/>"#)), &SvgOptions::default()).unwrap();
    assert_eq!(shape.outlines.len(), 1);
    assert_eq!(shape.outlines[0].area(), 0.5);
    assert_eq!(shape.paths[0].path.verbs.iter().filter(|&&v| v != Verb::Close).count(), 3);
    // A transform list of many steps that cancel out.
    let steps = "translate(1 0) translate(-1 0) ".repeat(50_000);
    let body = format!(r#"<path transform="{steps}" d="M0 0H1V1Z"/>"#);
    let shape = import_svg(&svg("0 0 1 1", &body), &SvgOptions::default()).unwrap();
    assert_eq!(shape.outlines[0].area(), 0.5);
}

#[test]
fn an_element_with_thousands_of_attributes_is_refused_before_parsing() {
    let attributes = |n: usize| -> String { (0..n).map(|k| format!(r#" a{k}="{k}""#)).collect() };
    let head = r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 1 1">"#;
    let text = format!(r#"{head}<path d="M0 0H1V1Z"{}/></svg>"#, attributes(20_000));
    // 20,001 attributes: 20,001 x 20,000 / 2 = 200 million pairs, beyond the 10 million.
    let limit = Limits::default().max_attribute_pairs;
    assert_eq!(limit, 10_000_000);
    let expected = ImportError::TooManyAttributes { line: 1, column: head.len() as u32 + 1, attributes: 20_001, limit };
    assert_eq!(import_svg(&text, &SvgOptions::default()).unwrap_err(), expected);
    let place = format!("the element at line 1, column {} has 20001", head.len() + 1);
    assert!(expected.to_string().contains(&place), "{expected}");
    // 4,001 attributes (8 million pairs, plus the root's one) are within the limit.
    let text = format!(r#"{head}<path d="M0 0H1V1Z"{}/></svg>"#, attributes(4_000));
    assert_eq!(import_svg(&text, &SvgOptions::default()).unwrap().outlines[0].area(), 0.5);
    // Many elements add up: 200 elements of 400 attributes (79,800 pairs each).
    let many = format!(r#"<g{}/>"#, attributes(400)).repeat(200);
    let text = format!(r#"{head}<path d="M0 0H1V1Z"/>{many}</svg>"#);
    let Err(ImportError::TooManyAttributes { attributes: 400, .. }) = import_svg(&text, &SvgOptions::default()) else {
        panic!("expected too many attributes");
    };
}

#[test]
fn thousands_of_small_polygons_and_deep_nesting() {
    // 5,000 triangles of legs 0.5 on a grid: each its own part, area 1/8.
    let body: String = (0..5000)
        .map(|k| {
            let (x, y) = ((k % 100) as f64, (k / 100) as f64);
            format!(r#"<polygon points="{x} {y} {} {y} {x} {}"/>"#, x + 0.5, y + 0.5)
        })
        .collect();
    let shape = import_svg(&svg("0 0 100 50", &body), &SvgOptions::default()).unwrap();
    assert_eq!(shape.outlines.len(), 5000);
    assert!(shape.outlines.iter().all(|o| o.outer.len() == 3 && o.holes.is_empty() && o.area() == 0.125));
    // Errors still name the right element: the last polygon is too large.
    let bad = format!("{body}\n<polygon id=\"last\" points=\"1 2 3 4 1e31 0\"/>");
    let message = import_svg(&svg("0 0 100 50", &bad), &SvgOptions::default()).unwrap_err().to_string();
    assert!(message.contains("<polygon id=\"last\"> (line 2, column 1)"), "{message}");
    // 400 nested squares in one even-odd path: filled between squares 0-1, 2-3, ...; the
    // squares have sides 800, 798, ..., so each part is a frame of area s^2 - (s - 2)^2.
    let squares: String = (0..400).map(|k| format!("M{k} {k}H{}V{}H{k}Z", 800 - k, 800 - k)).collect();
    let body = format!(r#"<path fill-rule="evenodd" d="{squares}"/>"#);
    let shape = import_svg(&svg("0 0 800 800", &body), &SvgOptions::default()).unwrap();
    assert_eq!(shape.outlines.len(), 200);
    for (k, outline) in shape.outlines.iter().enumerate() {
        let side = 800.0 - 4.0 * k as f64;
        assert_eq!(outline.holes.len(), 1);
        assert_eq!(outline.area(), side * side - (side - 2.0) * (side - 2.0));
    }
}

#[test]
fn long_paths_import_whole() {
    // A circle of 30,000 points: the outline is the path itself (y flipped).
    let n = 30_000;
    let circle: Vec<Point> = (0..n)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / n as f64;
            [0.9 * t.cos(), 0.9 * t.sin()]
        })
        .collect();
    let body = format!(r#"<path d="{}"/>"#, path_data(&circle));
    let shape = import_svg(&svg("-1 -1 2 2", &body), &SvgOptions::default()).unwrap();
    assert_eq!(shape.outlines.len(), 1);
    let outer = &shape.outlines[0].outer;
    assert_eq!(outer.len(), n);
    for (p, q) in circle.iter().zip(outer) {
        // usvg keeps single precision: 2^-24 of the unit, rounded twice.
        assert!((q[0] - (p[0] + 1.0)).abs() < 2e-7 && (q[1] - (1.0 - p[1])).abs() < 2e-7, "{p:?} -> {q:?}");
    }
    // A comb of 30,000 points, every long edge overlapping every other in x.
    let teeth = 7_500;
    let body = format!(r#"<path d="{}"/>"#, path_data(&comb(teeth, 1000.0)));
    let shape = import_svg(&svg("-1 0 1001 15000", &body), &SvgOptions::default()).unwrap();
    assert_eq!(shape.outlines.len(), 1);
    assert_eq!(shape.outlines[0].outer.len(), 4 * teeth);
    assert_eq!(shape.outlines[0].area(), teeth as f64 * 1000.0 + 2.0 * teeth as f64 - 1.0);
}

#[test]
fn large_outlines_are_checked_fast_and_refused_in_the_callers_terms() {
    // A comb of 12,000 points with a hole in each tooth: valid.
    let teeth = 3_000;
    let hole = |i: usize| {
        let (x, y) = (10.0 + (i % 900) as f64, 2.0 * i as f64 + 0.5);
        vec![[x, y - 0.25], [x + 10.0, y], [x, y + 0.25]]
    };
    let mut outline = Outline::new(comb(teeth, 1000.0));
    outline.holes = (0..teeth).map(hole).collect();
    let rings = outline.validated(usize::MAX).unwrap();
    assert_eq!(rings.len(), teeth + 1);
    // A hole moved into a gap between teeth lies outside; one inside another is nested.
    let mut outside = outline.clone();
    outside.holes[2500] = hole(2500).iter().map(|p| [p[0], p[1] + 1.0]).collect();
    assert_eq!(outside.validated(usize::MAX), Err(OutlineError::HoleOutside { hole: Ring(2501) }));
    // Hole 11 spans x 21 to 31 about y = 22.5, a quarter high at x = 21 tapering to 0:
    // a smaller triangle fits inside it.
    let mut nested = outline.clone();
    nested.holes[10] = vec![[22.0, 22.45], [24.0, 22.5], [22.0, 22.55]];
    let expected = OutlineError::NestedHole { hole: Ring(11), container: Ring(12) };
    assert_eq!(nested.validated(usize::MAX), Err(expected));
    // 12,000 outline points against a limit of 12,000 vertices: no room to refine.
    let outline = Outline::new(comb(teeth, 1000.0));
    let options = TriangulationOptions::default().with_max_vertices(4 * teeth);
    let error = triangulate(&outline, &options).unwrap_err();
    assert_eq!(error, TriangulationError::TooManyVertices { limit: 4 * teeth, outline_points: 4 * teeth });
    let message = error.to_string();
    assert!(message.contains("the outline has 12000 points, too many to mesh within the vertex limit of 12000"));
}

#[test]
fn tens_of_thousands_of_handles() {
    let mesh = grid(20, 20);
    let size = 20.0 * 2f64.sqrt();
    let mut deformer = Deformer::new(mesh.clone(), AkapOptions::default()).unwrap();
    // 20,000 handles within 1e-12 of the shape's size of vertex 0: one point, so the shape
    // follows it rigidly, by the mean velocity.
    let count = 20_000;
    let mut rng = Rng::new(16);
    let triangles = vec![0u32; count];
    let offset = 0.4e-12 * size;
    let barycentric: Vec<[f64; 3]> = (0..count)
        .map(|_| {
            let (u, v) = (rng.unit() * offset, rng.unit() * offset);
            [1.0 - u - v, u, v]
        })
        .collect();
    deformer.set_handle_points(&triangles, &barycentric).unwrap();
    let velocities: Vec<[f64; 2]> = (0..count).map(|k| [(k % 3) as f64, (k % 5) as f64]).collect();
    let mean = velocities.iter().fold([0.0; 2], |m, v| [m[0] + v[0] / count as f64, m[1] + v[1] / count as f64]);
    deformer.step(&velocities).unwrap();
    for (p, q) in mesh.positions().iter().zip(deformer.positions()) {
        assert!((q[0] - p[0] - mean[0]).abs() < 1e-12 && (q[1] - p[1] - mean[1]).abs() < 1e-12);
    }
    // 20,000 distinct handles that do not move: nothing moves.
    let before = deformer.positions().to_vec();
    let triangles: Vec<u32> = (0..count).map(|k| (k % mesh.triangle_count()) as u32).collect();
    let barycentric: Vec<[f64; 3]> = (0..count)
        .map(|_| {
            let (u, v) = (rng.unit(), rng.unit());
            let (u, v) = if u + v > 1.0 { (1.0 - u, 1.0 - v) } else { (u, v) };
            [1.0 - u - v, u, v]
        })
        .collect();
    deformer.set_handle_points(&triangles, &barycentric).unwrap();
    deformer.step(&vec![[0.0, 0.0]; count]).unwrap();
    for (p, q) in before.iter().zip(deformer.positions()) {
        assert!((q[0] - p[0]).abs() < 1e-9 && (q[1] - p[1]).abs() < 1e-9, "{p:?} -> {q:?}");
    }
}

#[test]
fn points_far_outside_a_mesh_follow_its_nearest_triangle() {
    // 20,000 points around a 40 x 25 grid (2,000 triangles), on a circle and far away;
    // under an affine motion every triangle moves alike, so every point must follow it.
    let mesh = grid(40, 25);
    let points: Vec<Point> = (0..20_000)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / 20_000.0;
            let r = if k % 2 == 0 { 30.0 } else { 1e4 };
            [20.0 + r * t.cos(), 12.5 + r * t.sin()]
        })
        .collect();
    let motion = |p: Point| [1.5 * p[0] - 0.5 * p[1] + 3.0, 0.25 * p[0] + 0.75 * p[1] - 2.0];
    let deformed: Vec<Point> = mesh.positions().iter().map(|&p| motion(p)).collect();
    let mapped = PointMapper::new(&mesh, &points).unwrap().map(&deformed).unwrap();
    for (p, q) in points.iter().zip(&mapped) {
        let e = motion(*p);
        assert!((q[0] - e[0]).abs() < 1e-9 * (1.0 + e[0].abs()) && (q[1] - e[1]).abs() < 1e-9 * (1.0 + e[1].abs()));
    }
    // Under a motion that bends the grid (y + x^2 / 100), a point left of it follows the
    // one triangle nearest it, (0, 10) (1, 11) (0, 11), which that motion maps by
    // y + x / 100: (-5, 10.3) goes to (-5, 10.25).
    let bend: Vec<Point> = mesh.positions().iter().map(|p| [p[0], p[1] + 0.01 * p[0] * p[0]]).collect();
    let left = PointMapper::new(&mesh, &[[-5.0, 10.3]]).unwrap().map(&bend).unwrap()[0];
    assert!((left[0] + 5.0).abs() < 1e-12 && (left[1] - 10.25).abs() < 1e-12, "{left:?}");
}

#[test]
fn arap_steps_have_a_bounded_number_of_iterations() {
    let mesh = grid(4, 4);
    let too_many = Deformer::new(mesh.clone(), ArapOptions::default().with_iterations(MAX_ITERATIONS + 1));
    let Err(DeformError::InvalidOption { name: "iterations", value, expected }) = too_many else {
        panic!("expected the iterations to be refused");
    };
    assert_eq!(value, (MAX_ITERATIONS + 1) as f64);
    assert!(expected.contains(&format!("from 1 to {MAX_ITERATIONS}")), "{expected}");
    let mut deformer = Deformer::new(mesh.clone(), ArapOptions::default().with_iterations(MAX_ITERATIONS)).unwrap();
    deformer.set_handle_vertices(&[0, 24]).unwrap();
    deformer.step(&[[0.0, 0.0], [0.5, 0.5]]).unwrap();
    // (It stops early only at an exact fixed point, where an iteration moves nothing.)
    let report = deformer.arap().unwrap().report();
    assert!(report.iterations == MAX_ITERATIONS || report.last_move == 0.0, "{report:?}");
    assert!(deformer.iterate(MAX_ITERATIONS + 1, 0.0).is_err());
    // Convergence runs stop when converged and may allow more.
    assert!(Deformer::new(mesh, ArapOptions::default().until_converged(1e-9, 5 * MAX_ITERATIONS)).is_ok());
    assert!(deformer.iterate(5 * MAX_ITERATIONS, 1e-9).unwrap().converged);
}
