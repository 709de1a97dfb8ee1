//! SVG import: path data, shapes and transforms against hand-computed outlines; fill rules
//! and holes; malformed input read as browsers read it; vector export through a deformed
//! mesh. usvg keeps geometry in single precision, so points compare to about 1e-7 of their
//! magnitude. Strokes, styles, clones, clips and editors' files: `import_svg_art`.

use std::f64::consts::PI;

use akap::geometry::{distance, polygon_area, Point};
use akap::import::svg::{import_svg, FillColour, SvgOptions, SvgShape};
use akap::import::warp::PointMapper;
use akap::import::{ImportError, Limits};
use akap::{triangulate, Outline, TriangulationOptions};
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

fn svg(body: &str, attributes: &str) -> String {
    format!(r#"<svg xmlns="http://www.w3.org/2000/svg" {attributes}>{body}</svg>"#)
}

fn import(body: &str, attributes: &str) -> SvgShape {
    import_svg(&svg(body, attributes), &SvgOptions::default()).unwrap()
}

fn error(body: &str, attributes: &str) -> String {
    import_svg(&svg(body, attributes), &SvgOptions::default()).unwrap_err().to_string()
}

/// The ring rotated to start at its lowest-then-leftmost point and run counter-clockwise,
/// so rings can be compared regardless of where they start.
fn canonical(ring: &[Point]) -> Vec<Point> {
    let mut r = ring.to_vec();
    if polygon_area(&r) < 0.0 {
        r.reverse();
    }
    let start = (0..r.len()).min_by(|&i, &j| (r[i][1], r[i][0]).partial_cmp(&(r[j][1], r[j][0])).unwrap()).unwrap();
    r.rotate_left(start);
    r
}

fn assert_ring(actual: &[Point], expected: &[Point]) {
    let (a, e) = (canonical(actual), canonical(expected));
    assert_eq!(a.len(), e.len(), "{a:?} vs {e:?}");
    for (p, q) in a.iter().zip(&e) {
        assert!(distance(*p, *q) < 1e-6 * (1.0 + p[0].abs().max(p[1].abs())), "{a:?} vs {e:?}");
    }
}

#[test]
fn absolute_and_relative_commands_with_view_box_flip() {
    // viewBox 0 0 100 50: y' = 50 - y.
    let shape = import(r#"<path d="M 10 10 h 80 v 30 H 10 Z"/>"#, r#"viewBox="0 0 100 50""#);
    assert_eq!(shape.outlines.len(), 1);
    assert_ring(&shape.outlines[0].outer, &[[10.0, 40.0], [90.0, 40.0], [90.0, 10.0], [10.0, 10.0]]);
    // Relative moveto with implicit linetos, and V/L; the viewBox origin moves to 0.
    let shape = import(r#"<path d="m10 10 20 0 0 20 L 10 30 z"/>"#, r#"viewBox="5 0 40 40""#);
    assert_ring(&shape.outlines[0].outer, &[[5.0, 30.0], [25.0, 30.0], [25.0, 10.0], [5.0, 10.0]]);
    // Without a viewBox, y' = height - y.
    let shape = import(r#"<polygon points="0,0 4,0 4,2"/>"#, r#"height="10""#);
    assert_ring(&shape.outlines[0].outer, &[[0.0, 10.0], [4.0, 10.0], [4.0, 8.0]]);
}

#[test]
fn smooth_curves_reflect_their_control_points() {
    // S after C reflects the second control point; T after Q the control point; S after
    // anything else starts from the current point.
    // Without a viewBox or height, y' = -y: the points below are (x, -y) of the path's.
    let shape = import(r#"<path d="M0 0 C1 0 2 0 3 0 s 1 2 1 3 q 0 1 -1 1 t -2 0 L 0 0 S 1 1 2 2"/>"#, "");
    let points: Vec<Point> = shape.paths[0].path.points.iter().map(|p| [p[0], -p[1]]).collect();
    assert_eq!(points[4], [4.0, 0.0], "S reflects (2, 0) about (3, 0)");
    assert_eq!(&points[5..7], &[[4.0, 2.0], [4.0, 3.0]], "relative to (3, 0)");
    assert_eq!(&points[7..9], &[[4.0, 4.0], [3.0, 4.0]]);
    assert_eq!(points[9], [2.0, 4.0], "T reflects (4, 4) about (3, 4)");
    assert_eq!(points[10], [1.0, 4.0]);
    assert_eq!(points[12], [0.0, 0.0], "S after L: the first control point is the current point");
}

/// All points of every ring of the outline lie within `tol` of the ellipse with centre
/// `c`, semi-axes `a`, `b` rotated by `phi`.
fn assert_on_ellipse(points: &[Point], c: Point, a: f64, b: f64, phi: f64, tol: f64) {
    let (s, k) = phi.sin_cos();
    for p in points {
        let (dx, dy) = (p[0] - c[0], p[1] - c[1]);
        let (u, v) = (k * dx + s * dy, -s * dx + k * dy);
        // Distance to the ellipse, to first order: |F| / |grad F| with F = (u/a)^2 + (v/b)^2 - 1.
        let f = (u / a).powi(2) + (v / b).powi(2) - 1.0;
        let grad = (2.0 * u / (a * a)).hypot(2.0 * v / (b * b));
        assert!((f / grad).abs() <= tol, "{p:?} is {} from the ellipse", f / grad);
    }
}

#[test]
fn arcs_follow_the_implementation_notes() {
    // A full circle from two half arcs (large-arc and sweep flags), radius 20 about (50, 50)
    // with viewBox 0 0 100 100: the centre stays at (50, 50) after the flip.
    let tol = 0.01;
    let shape = import_svg(
        &svg(r#"<path d="M 50 50 m -20 0 a 20 20 0 1 0 40 0 a 20 20 0 1 0 -40 0 z"/>"#, r#"viewBox="0 0 100 100""#),
        &SvgOptions::default().with_tolerance(tol),
    )
    .unwrap();
    let outer = &shape.outlines[0].outer;
    // Points are on the curve: arcs become cubics of at most 90 degrees (usvg's, through
    // kurbo), whose radius is off by at most 2.7e-4 of the radius.
    assert_on_ellipse(outer, [50.0, 50.0], 20.0, 20.0, 0.0, 2.8e-4 * 20.0);
    // The inscribed polygon's area is short of the disc's by at most perimeter * tolerance.
    let area = polygon_area(outer).abs();
    assert!(area < PI * 400.0 && PI * 400.0 - area < 2.0 * PI * 20.0 * tol, "{area}");

    // Radii too small to reach the end point are scaled up (F.6.6): a half circle of
    // radius 5 centred (5, 0), closed by its diameter.
    // (Without a viewBox, y' = -y; the ring is given back in the path's coordinates.)
    let path = &import(r#"<path d="M0 0 A 1 1 0 0 1 10 0 Z"/>"#, "").paths[0].path;
    let ring: Vec<Point> = path.flatten(1e-3, 0, 10_000).unwrap()[0].iter().map(|p| [p[0], -p[1]]).collect();
    assert_on_ellipse(&ring[..ring.len() - 1], [5.0, 0.0], 5.0, 5.0, 0.0, 2.8e-4 * 5.0);
    // sweep-flag 1 goes the positive-angle way, from +x towards +y: from angle pi to 2 pi,
    // through (5, -5) (the upper half on screen, where y points down).
    assert!(ring.iter().any(|p| distance(*p, [5.0, -5.0]) < 1e-5));
    assert!((polygon_area(&ring).abs() - PI * 12.5).abs() < 2.0 * PI * 5.0 * 1e-3);

    // A rotated ellipse arc: semi-axes 4 and 2 turned 30 degrees, through two points
    // computed from its parametric form; the centre must come out as (1, 2).
    let (a, b, phi) = (4.0, 2.0, 30f64.to_radians());
    let at = |t: f64| {
        let (s, k) = phi.sin_cos();
        [1.0 + a * t.cos() * k - b * t.sin() * s, 2.0 + a * t.cos() * s + b * t.sin() * k]
    };
    let (p, q) = (at(0.3), at(2.5));
    let d = format!("M{} {} A 4 2 30 0 1 {} {}", p[0], p[1], q[0], q[1]);
    let arc = &import(&format!(r#"<path d="{d}"/>"#), "").paths[0].path;
    let ring: Vec<Point> = arc.flatten(1e-4, 0, 10_000).unwrap()[0].iter().map(|p| [p[0], -p[1]]).collect();
    let ring = &ring;
    assert_on_ellipse(ring, [1.0, 2.0], a, b, phi, 2.8e-4 * a);
    // The small arc between the two parameters: its midpoint is the point at t = 1.4.
    assert!(ring.iter().any(|r| distance(*r, at(1.4)) < 0.01));
}

#[test]
fn transforms_compose_through_groups() {
    // rect (0,0)-(4,2), rotated 90 degrees then shifted by (10, 0): corners (10,0), (10,4),
    // (8,4), (8,0); no viewBox or height, so y' = -y.
    let shape = import(r#"<g transform="translate(10 0)"><rect width="4" height="2" transform="rotate(90)"/></g>"#, "");
    assert_ring(&shape.outlines[0].outer, &[[10.0, 0.0], [10.0, -4.0], [8.0, -4.0], [8.0, 0.0]]);
    // Nested groups: scale(2) then skewX(45) then matrix; the unit square (0,0)-(1,1)
    // goes through matrix(1 0 0 1 3 0) (shift 3), skewX(45) (x += y), scale(2).
    let shape = import(
        r#"<g transform="scale(2)"><g transform="skewX(45)"><path transform="matrix(1 0 0 1 3 0)" d="M0 0H1V1H0z"/></g></g>"#,
        "",
    );
    assert_ring(&shape.outlines[0].outer, &[[6.0, 0.0], [8.0, 0.0], [10.0, -2.0], [8.0, -2.0]]);
    // Rotation about a centre keeps the centre: rotate(180 5 5) of (4,4)-(6,5) is (4,5)-(6,6).
    let shape = import(r#"<rect x="4" y="4" width="2" height="1" transform="rotate(180, 5, 5)"/>"#, "");
    assert_ring(&shape.outlines[0].outer, &[[4.0, -5.0], [6.0, -5.0], [6.0, -6.0], [4.0, -6.0]]);
    // A nested svg places its viewBox into its box (xMidYMid meet): viewBox 0 0 1 1 into a
    // 4 x 2 box at (10, 0) scales by 2 and centres horizontally (offset 1).
    let shape = import(r#"<svg x="10" width="4" height="2" viewBox="0 0 1 1"><rect width="1" height="1"/></svg>"#, "");
    assert_ring(&shape.outlines[0].outer, &[[11.0, 0.0], [13.0, 0.0], [13.0, -2.0], [11.0, -2.0]]);
}

#[test]
fn basic_shapes_have_their_areas() {
    let tol = 1e-3;
    let options = SvgOptions::default().with_tolerance(tol);
    let area = |body: &str| {
        let shape = import_svg(&svg(body, ""), &options).unwrap();
        assert_eq!(shape.outlines.len(), 1);
        shape.outlines[0].area()
    };
    // Rounded rect: the corners lose (4 - pi) r^2 in all.
    let rounded = area(r#"<rect x="1" y="1" width="10" height="6" rx="2"/>"#);
    let expected = 60.0 - (4.0 - PI) * 4.0;
    assert!((rounded - expected).abs() < 30.0 * tol, "{rounded} vs {expected}");
    // ry larger than half the height is clamped to 3.
    let clamped = area(r#"<rect width="10" height="6" rx="1" ry="9"/>"#);
    assert!((clamped - (60.0 - (4.0 - PI) * 3.0)).abs() < 30.0 * tol, "{clamped}");
    let circle = area(r#"<circle cx="5" cy="5" r="3"/>"#);
    assert!((circle - 9.0 * PI).abs() < 2.0 * PI * 3.0 * tol);
    let ellipse = area(r#"<ellipse cx="5" cy="5" rx="4" ry="1"/>"#);
    assert!((ellipse - 4.0 * PI).abs() < 2.0 * PI * 4.0 * tol);
    assert_eq!(area(r#"<polyline points="0 0 4 0 4 4"/>"#), 8.0);
    assert_eq!(area(r#"<polygon points="0,0,4,0,4,4,0,4"/>"#), 16.0);
    // Units: 1in = 96 user units.
    assert_eq!(area(r#"<rect width="1in" height="2"/>"#), 192.0);
}

#[test]
fn fill_rules_holes_and_parts() {
    let square = |x: f64, s: f64| format!("M{x} {x}h{s}v{s}h-{s}z");
    let ring = |x: f64, s: f64| format!("M{x} {x}v{s}h{s}v-{s}z"); // the other way round
                                                                   // Even-odd: an inner square is a hole whichever way it runs.
    let d = format!("{}{}", square(0.0, 10.0), square(2.0, 2.0));
    let shape = import(&format!(r#"<path fill-rule="evenodd" d="{d}"/>"#), "");
    assert_eq!((shape.outlines.len(), shape.outlines[0].holes.len()), (1, 1));
    assert_eq!(shape.outlines[0].area(), 96.0);
    // Non-zero: the same path has no hole, the reversed inner square makes one.
    let shape = import(&format!(r#"<path d="{d}"/>"#), "");
    assert_eq!(shape.outlines[0].holes.len(), 0);
    let shape =
        import(&format!(r#"<path style="fill-rule: nonzero" d="{}{}"/>"#, square(0.0, 10.0), ring(2.0, 2.0)), "");
    assert_eq!(shape.outlines[0].holes.len(), 1);
    // A shape inside a hole is a separate part, and separate shapes are separate parts,
    // largest first.
    let body = format!(
        r#"<path fill-rule="evenodd" d="{}{}"/><path d="{}"/><rect x="20" width="3" height="3"/>"#,
        square(0.0, 10.0),
        square(2.0, 6.0),
        square(4.0, 1.0)
    );
    let areas: Vec<f64> = import(&body, "").outlines.iter().map(Outline::area).collect();
    assert_eq!(areas, vec![64.0, 9.0, 1.0]);
    // min_area drops small parts and fills small holes.
    let options = SvgOptions { min_area: 5.0, ..SvgOptions::default() };
    let areas: Vec<f64> = import_svg(&svg(&body, ""), &options).unwrap().outlines.iter().map(Outline::area).collect();
    assert_eq!(areas, vec![64.0, 9.0]);
}

#[test]
fn unfilled_and_hidden_elements_do_not_count() {
    let body = r#"
        <defs><rect width="100" height="100"/></defs>
        <rect width="50" height="50" fill="none"/>
        <g style="fill: none"><circle r="40"/><circle r="30" fill="red"/></g>
        <g display="none"><rect width="70" height="70"/></g>
        <line x2="100" y2="100"/>
        <text>hello</text>
        <rect width="1" height="1" style="fill:transparent"/>"#;
    let shape = import(body, "");
    assert_eq!(shape.outlines.len(), 1, "only the red circle");
    assert!((shape.outlines[0].area() - 900.0 * PI).abs() < 10.0);
    assert_eq!(shape.skipped, vec!["text".to_string()]);
    assert_eq!(shape.paths.len(), 1);
    assert_eq!(
        error(r##"<use href="#missing"/><text>hi</text>"##, ""),
        "the SVG has no filled shape (unsupported elements skipped: text)"
    );
}

#[test]
fn malformed_documents_say_what_and_where() {
    let cases: [(String, &str); 3] = [
        (
            "<svg><path d='M0 0'></svg>".to_string(),
            "not well-formed XML at line 1, column 21: expected 'path' tag, not 'svg'",
        ),
        (r#"<html xmlns="http://www.w3.org/2000/svg"/>"#.to_string(), "root element is <html>, not <svg>"),
        (svg("<path d='M0 0 L1'/>", ""), "the SVG has no filled shape"),
    ];
    for (text, expected) in cases {
        let message = import_svg(&text, &SvgOptions::default()).unwrap_err().to_string();
        assert!(message.contains(expected), "{message:?} should contain {expected:?}");
    }
}

#[test]
fn malformed_attributes_are_read_as_browsers_read_them() {
    let area = |body: &str| import(body, r#"viewBox="0 0 100 100""#).outlines.iter().map(Outline::area).sum::<f64>();
    // Path data is drawn up to its first error (SVG 2, "error handling" of path data).
    assert_eq!(area(r#"<path d="M0 0h10v10h-10z L1"/>"#), 100.0);
    // (A number out of range is refused, naming the element: see the coordinate limit.)
    assert!(
        error(r#"<path d="M0 0h10v10h-10z M0 0H1e999V1z"/>"#, "").contains("<path> (line 1, column 42) is too large")
    );
    // An odd number of coordinates: the last one is ignored.
    assert_eq!(area(r#"<polygon points="0 0 4 0 4 4 9"/>"#), 8.0);
    // An invalid value is ignored and the property's default applies: non-zero, no
    // transform.
    assert_eq!(area(r#"<path fill-rule="odd" d="M0 0H10V10H0Z M2 2H4V4H2Z"/>"#), 100.0);
    assert_eq!(area(r#"<rect width="2" height="3" transform="spin(3)"/>"#), 6.0);
    // Percentages are of the viewport (the root's viewBox).
    assert!((area(r#"<rect width="50%" height="10"/>"#) - 500.0).abs() < 1e-3);
}

#[test]
fn overlapping_shapes_are_united_exactly() {
    // Two overlapping squares (union 7), an arm across a body, and a self-crossing path.
    let shape = import(r#"<rect width="2" height="2"/><rect x="1" y="1" width="2" height="2"/>"#, "");
    assert_eq!(shape.outlines.len(), 1);
    assert!((shape.outlines[0].area() - 7.0).abs() < 1e-6, "{}", shape.outlines[0].area());
    assert_ring(
        &shape.outlines[0].outer,
        &[[0.0, 0.0], [2.0, 0.0], [2.0, -1.0], [3.0, -1.0], [3.0, -3.0], [1.0, -3.0], [1.0, -2.0], [0.0, -2.0]],
    );
    let body =
        r#"<circle cx="50" cy="50" r="30"/><rect x="70" y="45" width="25" height="10" transform="rotate(-20 70 50)"/>"#;
    let shape = import(body, r#"viewBox="0 0 100 100""#);
    assert_eq!(shape.outlines.len(), 1);
    let mesh = triangulate(&shape.outlines[0], &TriangulationOptions::default().with_target_edge_length(3.0)).unwrap();
    assert_eq!(mesh.connected_components(), 1);
    // The disc plus the part of the arm outside it: more than the disc, less than both.
    let (disc, arm) = (PI * 900.0, 250.0);
    assert!(mesh.area() > disc + 100.0 && mesh.area() < disc + arm, "{}", mesh.area());
    // A frame whose hole another shape covers: no hole (boundaries apart, so nesting
    // decides exactly).
    let body = r#"<path fill-rule="evenodd" d="M0 0H10V10H0Z M2 2H8V8H2Z"/><rect x="1" y="1" width="8" height="8"/>"#;
    let shape = import(body, "");
    assert_eq!((shape.outlines.len(), shape.outlines[0].holes.len()), (1, 0));
    assert!((shape.outlines[0].area() - 100.0).abs() < 1e-6);
    // A figure eight under non-zero fills both lobes (winding +1 and -1).
    let eight = import(r#"<path d="M0 0L2 2V0L0 2z"/>"#, "");
    let area: f64 = eight.outlines.iter().map(Outline::area).sum();
    assert!((area - 2.0).abs() < 1e-6, "{area}");
}

#[test]
fn hostile_documents_hit_limits_not_the_stack() {
    // Deep nesting is refused (the walk is iterative, so this is a limit, not a crash).
    let deep = format!("{}<rect width='1' height='1'/>{}", "<g>".repeat(300), "</g>".repeat(300));
    assert!(error(&deep, "").contains("nests deeper than 256 elements"));
    // Entity expansion is bounded by the XML parser.
    let laughs = r#"<?xml version="1.0"?><!DOCTYPE svg [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;"><!ENTITY c "&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;"><!ENTITY d "&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;">]><svg xmlns="http://www.w3.org/2000/svg"><text>&d;&d;&d;</text></svg>"#;
    assert!(matches!(import_svg(laughs, &SvgOptions::default()), Err(ImportError::Xml { .. })));
    // Size limits.
    let small = SvgOptions { limits: Limits { max_bytes: 100, ..Limits::default() }, ..SvgOptions::default() };
    assert!(matches!(
        import_svg(&svg(&"<g/>".repeat(30), ""), &small),
        Err(ImportError::TooLarge { what: "the SVG text", .. })
    ));
    let few = SvgOptions { limits: Limits { max_points: 50, ..Limits::default() }, ..SvgOptions::default() };
    let circle = svg(r#"<circle r="1000"/>"#, "");
    let too_fine = SvgOptions { tolerance: Some(1e-9), ..few };
    let message = import_svg(&circle, &too_fine).unwrap_err().to_string();
    assert!(message.starts_with("the outline flattened to the tolerance would need "), "{message}");
    assert!(message.ends_with(" points, more than the limit of 50 (maxPoints)"), "{message}");
    // Points counted over the whole document, reported against the caller's limit (not
    // what was left of it for the last element: "more than 0 points").
    let polygon = |n: usize| {
        let points: Vec<String> = (0..n).map(|i| format!("{i},{}", i % 2)).collect();
        format!(r#"<polygon points="{}"/>"#, points.join(" "))
    };
    for body in [
        polygon(30) + &polygon(30),
        polygon(30)
            + r#"<path d="M0 0 L1 1 L2 0 L3 1 L4 0 L5 1 L6 0 L7 1 L8 0 L9 1 L10 0 L11 1 L12 0 L13 1 L14 0 L15 1 L16 0 L17 1 L18 0 L19 1 L20 0 L21 1 L22 0 Z"/>"#,
    ] {
        let message = import_svg(&svg(&body, ""), &few).unwrap_err().to_string();
        assert_eq!(message, "the SVG's shapes have more than 50 points (the maxPoints limit)");
    }
    // Thousands of segments stacked in one column: the crossing check sweeps them in
    // O(n log n), within its budget; a smaller budget gives up.
    let zigzag: Vec<String> = (0..3000).map(|i| format!("{},{}", i % 2, i)).collect();
    let text = svg(&format!(r#"<polygon points="{} -5,3000 -5,0"/>"#, zigzag.join(" ")), "");
    let outlines = import_svg(&text, &SvgOptions::default()).map(|s| s.outlines.len());
    assert_eq!(outlines, Ok(1));
    let budget =
        SvgOptions { limits: Limits { max_segment_pairs: 10_000, ..Limits::default() }, ..SvgOptions::default() };
    let message = import_svg(&text, &budget).unwrap_err().to_string();
    assert!(message.contains("more than 10000 comparisons of segments"), "{message}");
    // Huge but finite coordinates do not hang the flattener.
    let huge = svg(r#"<path d="M0 0 C 1e300 -1e300 -1e300 1e300 1 1 Z"/>"#, "");
    assert!(import_svg(&huge, &SvgOptions::default().with_tolerance(1.0)).is_err());
    // Bad options.
    assert!(import_svg(&circle, &SvgOptions::default().with_tolerance(0.0)).is_err());
}

#[test]
fn imported_outlines_triangulate() {
    let body = r#"<path fill-rule="evenodd" d="M10 10 C 40 -10 80 30 90 60 S 40 100 10 80 Q -10 50 10 10 Z
        M 40 40 a 8 5 20 1 1 16 0 a 8 5 20 1 1 -16 0 Z"/>"#;
    let shape = import(body, r#"viewBox="0 0 100 100""#);
    let outline = &shape.outlines[0];
    assert_eq!(outline.holes.len(), 1);
    let mesh = triangulate(outline, &TriangulationOptions::default().with_target_edge_length(4.0)).unwrap();
    assert!((mesh.area() - outline.area()).abs() < 1e-9 * outline.area());
    assert_eq!(mesh.connected_components(), 1);
}

#[test]
fn vector_paths_follow_the_deformed_mesh() {
    let text = svg(r#"<path d="M10 10 C 30 0 60 0 90 10 L 90 60 Q 50 90 10 60 Z"/>"#, r#"viewBox="0 0 100 100""#);
    let shape = import_svg(&text, &SvgOptions::default()).unwrap();
    let path = &shape.paths[0].path;
    // Writing the points back gives path data that parses (with svgtypes, the reader usvg
    // uses) to the same commands and points.
    let data = path.to_path_data(&path.points);
    let mut read = Vec::new();
    for segment in svgtypes::PathParser::from(data.as_str()) {
        match segment.unwrap() {
            svgtypes::PathSegment::MoveTo { abs: true, x, y } | svgtypes::PathSegment::LineTo { abs: true, x, y } => {
                read.push([x, y])
            }
            svgtypes::PathSegment::CurveTo { abs: true, x1, y1, x2, y2, x, y } => {
                read.extend([[x1, y1], [x2, y2], [x, y]])
            }
            svgtypes::PathSegment::Quadratic { abs: true, x1, y1, x, y } => read.extend([[x1, y1], [x, y]]),
            svgtypes::PathSegment::ClosePath { .. } => {}
            other => panic!("{other:?} in {data}"),
        }
    }
    assert_eq!(read, path.points);
    // Through an affine deformation of the mesh, every point (control points outside the
    // mesh included) moves by that same affine map.
    let mesh = triangulate(&shape.outlines[0], &TriangulationOptions::default().with_target_edge_length(8.0)).unwrap();
    let motion = |p: Point| [0.8 * p[0] - 0.6 * p[1] + 5.0, 0.6 * p[0] + 0.8 * p[1] - 2.0];
    let deformed: Vec<Point> = mesh.positions().iter().map(|&p| motion(p)).collect();
    let mapped = PointMapper::new(&mesh, &path.points).unwrap().map(&deformed).unwrap();
    for (q, &p) in mapped.iter().zip(&path.points) {
        assert!(distance(*q, motion(p)) < 1e-9, "{p:?}");
    }
}

/// The fill colour of each filled element, in document order.
fn fills(body: &str, attributes: &str) -> Vec<Option<FillColour>> {
    import(body, attributes).paths.iter().map(|p| p.fill).collect()
}

fn rgba(red: u8, green: u8, blue: u8, alpha: f64) -> Option<FillColour> {
    Some(FillColour { red, green, blue, alpha })
}

const SQUARE: &str = r#"width="1" height="1""#;

#[test]
fn fill_colours_follow_the_css_cascade() {
    let r = |attributes: &str| format!("<rect {SQUARE} {attributes}/>");
    // No fill anywhere: the initial value, opaque black.
    assert_eq!(fills(&r(""), ""), vec![rgba(0, 0, 0, 1.0)]);
    // fill inherits; a group's opacity applies to its children and multiplies with the
    // element's fill-opacity: 1 x 0.5 x 0.5.
    let body = format!(r#"<g fill="red" opacity="0.5">{}</g>"#, r(r#"fill-opacity="0.5""#));
    assert_eq!(fills(&body, ""), vec![rgba(255, 0, 0, 0.25)]);
    // opacity multiplies down the tree (and takes percentages); fill-opacity inherits, and
    // an element's own replaces its parent's instead of multiplying.
    let body = format!(r#"<g opacity="50%"><g opacity="0.5">{}</g></g>"#, r(""));
    assert_eq!(fills(&body, ""), vec![rgba(0, 0, 0, 0.25)]);
    let body = format!(r#"<g fill-opacity="0.5">{}{}</g>"#, r(""), r(r#"fill-opacity="0.75""#));
    assert_eq!(fills(&body, ""), vec![rgba(0, 0, 0, 0.5), rgba(0, 0, 0, 0.75)]);
    // Alpha values are clamped to 0..1; invalid ones are ignored, as CSS ignores them.
    assert_eq!(fills(&r(r#"fill-opacity="3" opacity="lots""#), ""), vec![rgba(0, 0, 0, 1.0)]);
    // currentColor takes the inherited color; the root's color counts too.
    let body = format!(r##"<g color="#0f0">{}</g>"##, r(r#"fill="currentColor""#));
    assert_eq!(fills(&body, ""), vec![rgba(0, 255, 0, 1.0)]);
    assert_eq!(fills(&r(r#"fill="currentColor""#), r#"color="blue""#), vec![rgba(0, 0, 255, 1.0)]);
    // A fill of currentColor inherits as the keyword, so it uses each element's own color.
    let body = format!(r#"<g fill="currentColor" color="red">{}{}</g>"#, r(r#"color="blue""#), r(""));
    assert_eq!(fills(&body, ""), vec![rgba(0, 0, 255, 1.0), rgba(255, 0, 0, 1.0)]);
    // A style declaration overrides the attribute; inherit keeps the parent's value.
    assert_eq!(fills(&r(r#"fill="red" style="fill: #00f""#), ""), vec![rgba(0, 0, 255, 1.0)]);
    let body = format!(r#"<g style="fill:lime;opacity:0.5">{}</g>"#, r(r#"fill="inherit" opacity="inherit""#));
    assert_eq!(fills(&body, ""), vec![rgba(0, 255, 0, 0.25)]);
}

#[test]
fn fill_colours_in_every_css_notation() {
    // Values from CSS Color: the named colours' table, hex digits doubled in #rgb,
    // percentages of 255, hsl(120, 100%, 50%) is lime.
    let cases = [
        ("cornflowerblue", (100, 149, 237)),
        ("#abc", (0xaa, 0xbb, 0xcc)),
        ("#FF8000", (255, 128, 0)),
        ("rgb(10, 20, 30)", (10, 20, 30)),
        ("rgb(100%, 0%, 100%)", (255, 0, 255)),
        ("hsl(120, 100%, 50%)", (0, 255, 0)),
    ];
    for (value, (red, green, blue)) in cases {
        assert_eq!(
            fills(&format!(r#"<rect {SQUARE} fill="{value}"/>"#), ""),
            vec![rgba(red, green, blue, 1.0)],
            "{value}"
        );
    }
    // An alpha in the colour itself is kept to 1/255 and multiplies with the opacities.
    let [Some(c)] = fills(&format!(r#"<rect {SQUARE} fill="rgba(0, 0, 255, 0.5)" opacity="0.5"/>"#), "")[..] else {
        panic!("one colour expected")
    };
    assert_eq!((c.red, c.green, c.blue), (0, 0, 255));
    assert!((c.alpha - 0.25).abs() <= 0.5 / 255.0, "{}", c.alpha);
}

#[test]
fn paint_servers_and_unknown_fills() {
    // A gradient: the colour is unknown, the shape counts. A reference to nothing without a
    // fallback paints nothing (SVG 2 paint servers); with one, the fallback; a value that
    // does not parse is ignored, so the fill is inherited (black here).
    let gradient = r#"<linearGradient id="g"><stop offset="0" stop-color="red"/><stop offset="1" stop-color="blue"/></linearGradient>"#;
    let shape = import(&format!(r##"{gradient}<rect width="2" height="3" fill="url(#g)"/>"##), "");
    assert_eq!((shape.paths.len(), shape.paths[0].fill, shape.outlines[0].area()), (1, None, 6.0));
    assert!(error(r##"<rect width="2" height="3" fill="url(#missing)"/>"##, "").contains("no filled shape"));
    assert_eq!(fills(r##"<rect width="2" height="3" fill="url(#missing) red"/>"##, ""), vec![rgba(255, 0, 0, 1.0)]);
    assert_eq!(fills(r#"<rect width="2" height="3" fill="glitter"/>"#, ""), vec![rgba(0, 0, 0, 1.0)]);
}

#[test]
fn coordinates_beyond_the_limit_are_refused_in_the_users_terms() {
    let limit = Limits::default().max_coordinate;
    // A number beyond the limit is named with its attribute; points beyond it once placed,
    // with where they reach.
    let cases = [
        (
            svg(r#"<rect width="1e308" height="1e308"/>"#, r#"viewBox="0 0 1e308 1e308""#),
            "<svg>",
            "its viewBox holds 1e308",
        ),
        (
            svg(r#"<path id="huge" d="M 0 0 L 1e308 0 L 1e308 1e308 Z"/>"#, ""),
            "<path id=\"huge\">",
            "its d holds 1e308",
        ),
        (svg(r#"<path d="M 0 0 L 1e999 0 L 0 1 Z"/>"#, ""), "<path>", "its d holds a number out of range"),
        (
            svg(r#"<g transform="scale(1e20)"><rect id="r" width="1e15" height="10"/></g>"#, r#"viewBox="0 0 10 10""#),
            "<rect id=\"r\"> (line 1, column 88)",
            // 1e20 x 1e15 in usvg's single precision.
            "it reaches 1.000000007031981e35 in the drawing's units (after its transforms and viewBoxes)",
        ),
    ];
    for (text, element, reach) in cases {
        let error = import_svg(&text, &SvgOptions::default()).unwrap_err();
        assert!(matches!(error, ImportError::CoordinateTooLarge { .. }), "{error:?}");
        let message = error.to_string();
        for part in [element, reach, &format!("beyond ±{limit:e}, the limit")] {
            assert!(message.contains(part), "{message:?} should contain {part:?}");
        }
    }
    // The limit is an option.
    let tight = SvgOptions { limits: Limits { max_coordinate: 100.0, ..Limits::default() }, ..SvgOptions::default() };
    let text = svg(r#"<rect x="50" width="60" height="1"/>"#, "");
    assert!(import_svg(&text, &tight)
        .unwrap_err()
        .to_string()
        .contains("it reaches 1.1e2 in the drawing's units (after its transforms and viewBoxes), beyond ±1e2"));
}

#[test]
fn drawings_up_to_the_coordinate_limit_triangulate() {
    // A square with a square hole, reaching exactly the limit: import and meshing work in
    // double precision, and the mesh has the area of the square less the hole's.
    // (Half the limit: usvg's single precision rounds 1e30 up, past it.)
    let limit = Limits::default().max_coordinate / 2.0;
    let text = svg(
        &format!(r#"<path fill-rule="evenodd" d="M0 0H{limit}V{limit}H0Z M{q} {q}h{q}v{q}h-{q}z"/>"#, q = limit / 4.0),
        &format!(r#"viewBox="0 0 {limit} {limit}""#),
    );
    let shape = import_svg(&text, &SvgOptions::default()).unwrap();
    let options = TriangulationOptions::default().with_target_edge_length(limit / 10.0);
    let mesh = triangulate(&shape.outlines[0], &options).unwrap();
    let expected = limit * limit * (1.0 - 1.0 / 16.0);
    assert!((mesh.area() - expected).abs() < 1e-6 * expected, "{}", mesh.area());
}
