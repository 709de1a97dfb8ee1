//! Layered SVGs as puppets (issue 35): a part per layer with its own sheet, no vertex shared
//! between parts, joints in the overlaps. Expected names, areas and places come from the
//! drawings' shapes (tests/fixtures/svg/layered-puppet.svg says how its areas are made).

use akap::deform::{AkapOptions, ArapOptions, Deformer, MethodOptions};
use std::f64::consts::PI;

use akap::geometry::{point_in_polygon, triangle_area, Point};
use akap::import::puppet::{import_image_puppet, import_puppet, ImportedPuppet, PuppetOptions};
use akap::import::raster::TraceOptions;
use akap::import::svg::MAX_LAYERS;
use akap::import::ImportError;
use akap::ErrorCode;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

const LAYERED: &str = include_str!("fixtures/svg/layered-puppet.svg");

fn svg(body: &str) -> String {
    format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" viewBox="0 0 100 100">{body}</svg>"#
    )
}

fn puppet(text: &str) -> ImportedPuppet {
    import_puppet(text, &PuppetOptions::default()).unwrap()
}

fn names(p: &ImportedPuppet) -> Vec<&str> {
    p.puppet.parts.iter().map(|part| part.name.as_str()).collect()
}

fn corners(p: &ImportedPuppet, t: u32) -> [Point; 3] {
    p.mesh.triangles()[t as usize].map(|v| p.mesh.positions()[v as usize])
}

/// The area of part `k`'s sheet.
fn part_area(p: &ImportedPuppet, k: usize) -> f64 {
    p.puppet.parts[k]
        .triangles
        .iter()
        .map(|&t| {
            let [a, b, c] = corners(p, t);
            triangle_area(a, b, c)
        })
        .sum()
}

/// Whether `q` lies in a triangle of part `k`'s sheet, as the deformer places a joint.
fn on_part(p: &ImportedPuppet, k: usize, q: Point) -> bool {
    p.puppet.parts[k].triangles.iter().any(|&t| {
        let [a, b, c] = corners(p, t);
        let area = triangle_area(a, b, c);
        [triangle_area(q, b, c), triangle_area(a, q, c), triangle_area(a, b, q)].iter().all(|&w| w >= -1e-12 * area)
    })
}

/// The fixture's shapes in output coordinates (y up: y' = 300 - y).
fn in_rect(q: Point, x0: f64, x1: f64, y0: f64, y1: f64) -> bool {
    x0 < q[0] && q[0] < x1 && 300.0 - y1 < q[1] && q[1] < 300.0 - y0
}
fn in_torso(q: Point) -> bool {
    in_rect(q, 60.0, 140.0, 100.0, 220.0)
}
fn in_head(q: Point) -> bool {
    (q[0] - 100.0).hypot(q[1] - (300.0 - 80.0)) < 30.0
}
fn in_arm(q: Point) -> bool {
    in_rect(q, 120.0, 190.0, 110.0, 130.0) || in_rect(q, 185.0, 200.0, 105.0, 135.0)
}

#[test]
fn a_layered_character_gives_a_sheet_per_layer_joined_where_they_overlap() {
    let p = puppet(LAYERED);
    assert_eq!(names(&p), ["Torso", "Head", "Arm", "Hat"]);
    let depths: Vec<i32> = p.puppet.parts.iter().map(|part| part.depth).collect();
    assert!(depths.windows(2).all(|w| w[0] < w[1]), "{depths:?}");
    // Each sheet covers its shapes' area, to 1%.
    let expected = [9600.0, 900.0 * PI, 1400.0 + 450.0 - 100.0, 420.0 + 800.0];
    for (k, &area) in expected.iter().enumerate() {
        let got = part_area(&p, k);
        assert!((got / area - 1.0).abs() < 0.01, "part {k}: area {got}, expected {area}");
    }
    // Every triangle in exactly one part, and no vertex of two parts.
    let part_of = p.puppet.part_of_triangles(&p.mesh).unwrap();
    let mut vertex_part = vec![u32::MAX; p.mesh.vertex_count()];
    for (t, corners) in p.mesh.triangles().iter().enumerate() {
        for &v in corners {
            let slot = &mut vertex_part[v as usize];
            assert!(*slot == u32::MAX || *slot == part_of[t], "vertex {v} is in parts {} and {}", *slot, part_of[t]);
            *slot = part_of[t];
        }
    }
    // About the vertices asked for in all.
    let n = p.mesh.vertex_count();
    assert!((2400..=3600).contains(&n), "{n} vertices");
    // The arm and the head on the torso; nothing on the hat.
    let mut pairs: Vec<[usize; 2]> = p.puppet.joints.iter().map(|j| j.parts).collect();
    pairs.sort();
    assert_eq!(pairs, [[1, 0], [2, 0]]);
    for joint in &p.puppet.joints {
        let q = joint.point;
        let inside_front = if joint.parts[0] == 1 { in_head(q) } else { in_arm(q) };
        assert!(in_torso(q) && inside_front, "joint {joint:?} is not in both parts' shapes");
        assert!(on_part(&p, joint.parts[0], q) && on_part(&p, joint.parts[1], q), "{joint:?} is not on both sheets");
    }
    // Each part's art is its own, in drawing order.
    let ids: Vec<Vec<&str>> =
        p.art.iter().map(|paths| paths.iter().map(|a| a.element.id.as_deref().unwrap_or("")).collect()).collect();
    assert_eq!(ids, [vec!["torso", "belt"], vec!["face", "eyes"], vec!["sleeve", "hand"], vec!["brim", "crown"]]);
    let torso_green =
        |a: &&akap::import::svg::SvgPath| a.fill.is_some_and(|c| (c.red, c.green, c.blue) == (46, 139, 87));
    assert_eq!(p.art.iter().map(|paths| paths.iter().filter(torso_green).count()).collect::<Vec<_>>(), [1, 0, 0, 0]);
    assert!(p.skipped.is_empty());
    // The deformers take the puppet as it is: its joints are on both sheets.
    for options in [MethodOptions::from(AkapOptions::default()), ArapOptions::default().into()] {
        let deformer = Deformer::with_puppet(p.mesh.clone(), options, p.puppet.clone(), None).unwrap();
        assert_eq!(deformer.puppet().unwrap(), &p.puppet);
    }
}

#[test]
fn the_vertices_are_shared_by_area() {
    let p = import_puppet(LAYERED, &PuppetOptions::default().with_vertices(1000)).unwrap();
    let n = p.mesh.vertex_count();
    assert!((800..=1200).contains(&n), "{n} vertices");
    // The torso has the most area and the most vertices.
    let counts: Vec<usize> = p
        .puppet
        .parts
        .iter()
        .map(|part| {
            let mut v: Vec<u32> = part.triangles.iter().flat_map(|&t| p.mesh.triangles()[t as usize]).collect();
            v.sort_unstable();
            v.dedup();
            v.len()
        })
        .collect();
    assert!(counts[0] > counts[1] && counts[0] > counts[2] && counts[0] > counts[3], "{counts:?}");
}

#[test]
fn empty_and_zero_area_layers_are_left_out() {
    let text = svg(concat!(
        r#"<g inkscape:groupmode="layer" inkscape:label="Empty"/>"#,
        r#"<g inkscape:groupmode="layer" id="flat"><path d="M 10 10 L 90 90"/><rect width="0" height="5"/></g>"#,
        r#"<g inkscape:groupmode="layer" id="hidden" style="display:none"><rect width="50" height="50"/></g>"#,
        r#"<g inkscape:groupmode="layer"><rect x="10" y="10" width="20" height="20"/></g>"#,
        r#"<rect x="60" y="60" width="10" height="30"/>"#,
    ));
    let p = puppet(&text);
    assert_eq!(names(&p), ["Part 1", "Part 2"]);
    assert!((part_area(&p, 0) - 400.0).abs() < 1e-9 && (part_area(&p, 1) - 300.0).abs() < 1e-9);
    assert!(p.puppet.joints.is_empty());
    // Only layers without area: the error of a document without a filled shape.
    let none = svg(r#"<g id="a"/><g id="b"><line x1="0" y1="0" x2="9" y2="9"/></g>"#);
    let e = import_puppet(&none, &PuppetOptions::default()).unwrap_err();
    assert_eq!(e, ImportError::NoShapes { skipped: Vec::new() });
}

#[test]
fn a_layer_inside_another_is_joined_inside_it() {
    // A pocket (30..40 x 60..70, y down) on a coat (10..90 x 10..90), and a patch on the
    // coat only touching the pocket's edge.
    let text = svg(concat!(
        r#"<g id="coat"><rect x="10" y="10" width="80" height="80"/></g>"#,
        r#"<g id="pocket"><rect x="30" y="60" width="10" height="10"/></g>"#,
    ));
    let p = puppet(&text);
    assert_eq!(names(&p), ["coat", "pocket"]);
    assert_eq!(p.puppet.joints.len(), 1);
    let joint = p.puppet.joints[0];
    assert_eq!(joint.parts, [1, 0]);
    let [x, y] = joint.point;
    assert!(30.0 < x && x < 40.0 && 30.0 < y && y < 40.0, "{:?}", joint.point);
    // Well inside: at the pocket's centre, its overlap's centroid.
    assert!((x - 35.0).abs() < 1e-6 && (y - 35.0).abs() < 1e-6, "{:?}", joint.point);
    assert!(on_part(&p, 0, joint.point) && on_part(&p, 1, joint.point));
}

#[test]
fn shapes_that_only_touch_are_not_joined() {
    let text =
        svg(r#"<g id="a"><rect width="10" height="10"/></g><g id="b"><rect x="10" width="10" height="10"/></g>"#);
    let p = puppet(&text);
    assert_eq!(names(&p), ["a", "b"]);
    assert!(p.puppet.joints.is_empty());
}

#[test]
fn a_drawing_without_layers_is_one_part_and_wrappers_are_looked_through() {
    let p = puppet(&svg(r#"<path d="M 10 10 H 50 V 50 H 10 Z M 60 60 H 70 V 70 H 60 Z"/>"#));
    assert_eq!(names(&p), ["Part 1"]);
    assert!((part_area(&p, 0) - 1700.0).abs() < 1e-9);
    assert!(p.puppet.joints.is_empty());
    // Loose shapes without any group (a donut and its sprinkles) are one drawing, not taken
    // apart: one part, the shapes united as importSvg unites them.
    let loose = svg(concat!(
        r#"<g transform="translate(5 0)"><rect id="donut" width="40" height="40"/>"#,
        r#"<g fill="yellow"><rect x="5" y="5" width="10" height="2"/><rect x="50" width="10" height="10"/></g></g>"#,
    ));
    let p = puppet(&loose);
    assert_eq!(names(&p), ["Part 1"]);
    assert!((part_area(&p, 0) - 1700.0).abs() < 1e-9, "{}", part_area(&p, 0));
    // A group without id or label is no layer: its children are; so are the sub-layers of a
    // document's only layer.
    let wrapped = svg(concat!(
        r#"<g transform="translate(5 0)"><rect id="left" width="10" height="10"/>"#,
        r#"<g inkscape:label="right"><rect x="20" width="10" height="10"/></g></g>"#,
    ));
    assert_eq!(names(&puppet(&wrapped)), ["left", "right"]);
    let one_layer = svg(concat!(
        r#"<g inkscape:groupmode="layer" inkscape:label="Layer 1">"#,
        r#"<g id="body"><rect width="40" height="40"/></g><g id="tail"><rect x="35" y="5" width="30" height="4"/></g></g>"#,
    ));
    let p = puppet(&one_layer);
    assert_eq!(names(&p), ["body", "tail"]);
    assert_eq!(p.puppet.joints.iter().map(|j| j.parts).collect::<Vec<_>>(), [[1, 0]]);
}

#[test]
fn overlapping_shapes_of_a_layer_are_one_sheet_and_separate_ones_several_pieces() {
    // Two eyes in one layer, and a layer of two overlapping squares (2 x 100 - 25).
    let text = svg(concat!(
        r#"<g id="eyes"><circle cx="20" cy="20" r="5"/><circle cx="40" cy="20" r="5"/></g>"#,
        r#"<g id="block"><rect x="50" y="50" width="10" height="10"/><rect x="55" y="55" width="10" height="10"/></g>"#,
    ));
    // Flattened finely: within 1e-3 of the curves, the discs' areas to about 4e-4.
    let options = PuppetOptions::default();
    let p = import_puppet(&text, &PuppetOptions { svg: options.svg.with_tolerance(1e-3), ..options }).unwrap();
    assert_eq!(names(&p), ["eyes", "block"]);
    assert!((part_area(&p, 0) / (50.0 * PI) - 1.0).abs() < 0.01, "{}", part_area(&p, 0));
    assert!((part_area(&p, 1) - 175.0).abs() < 1e-6, "{}", part_area(&p, 1));
}

#[test]
fn bad_input_is_refused_clearly() {
    let e = import_puppet("<html><body/></html>", &PuppetOptions::default()).unwrap_err();
    assert_eq!(e.to_string(), "the document's root element is <html>, not <svg>");
    let e = import_puppet("not xml at all", &PuppetOptions::default()).unwrap_err();
    assert_eq!(e.code(), ErrorCode::Import);
    let square = svg(r#"<rect width="10" height="10"/>"#);
    for vertices in [0, 2, 100_001] {
        let e = import_puppet(&square, &PuppetOptions::default().with_vertices(vertices)).unwrap_err();
        assert_eq!(e.code(), ErrorCode::InvalidOption, "{e}");
        assert!(e.to_string().starts_with("option vertices is"), "{e}");
    }
    let many: String =
        (0..=MAX_LAYERS).map(|k| format!(r#"<g id="r{k}"><rect x="{k}" width="0.5" height="1"/></g>"#)).collect();
    let e = import_puppet(&svg(&many), &PuppetOptions::default()).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!("the SVG has {} layers, more than the limit of {MAX_LAYERS} layers", MAX_LAYERS + 1)
    );
}

#[test]
fn an_image_gives_a_part_per_region() {
    // Two opaque squares, 10 x 10 and 6 x 6 pixels, on a transparent 30 x 20 image.
    let (w, h) = (30, 20);
    let mut rgba = vec![0u8; 4 * w * h];
    for (x0, y0, s) in [(2, 2, 10), (20, 5, 6)] {
        for y in y0..y0 + s {
            for x in x0..x0 + s {
                rgba[4 * (y * w + x) + 3] = 255;
            }
        }
    }
    let trace = TraceOptions { min_area: 1.0, ..TraceOptions::default() };
    let p = import_image_puppet(&rgba, w, h, &trace, 200).unwrap();
    assert_eq!(names(&p), ["Part 1", "Part 2"]);
    // Each sheet covers its traced outline (the tracer's, within its bound of the square).
    let traced = akap::import::raster::trace_image(&rgba, w, h, &trace).unwrap();
    for (k, (outline, side)) in traced.iter().zip([10.0, 6.0]).enumerate() {
        assert!((part_area(&p, k) - outline.area()).abs() <= 1e-9 * outline.area());
        assert!((outline.area() - side * side).abs() <= 4.0 * side * 0.5, "{}", outline.area());
    }
    assert!(p.puppet.joints.is_empty());
    assert!(p.art.iter().all(Vec::is_empty));
    let inside = |q: Point, x0: f64, y0: f64, s: f64| {
        point_in_polygon(q, &[[x0, y0], [x0 + s, y0], [x0 + s, y0 + s], [x0, y0 + s]])
    };
    // y up: the first square spans rows 2..12 from the top, 8..18 from the bottom.
    let [a, b, c] = corners(&p, p.puppet.parts[0].triangles[0]);
    let centre = [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0];
    assert!(inside(centre, 2.0, 8.0, 10.0), "{centre:?}");
}

#[test]
fn many_stacked_layers_join_every_pair_in_bounded_work() {
    // Layers of one square, shifted a little each: every pair overlaps, so every pair is
    // joined, at a point on both sheets; the work is one overlay per pair.
    let n = 60;
    let body: String = (0..n)
        .map(|k| format!(r#"<g id="r{k}"><rect x="{}" y="10" width="50" height="50"/></g>"#, f64::from(k) * 0.5))
        .collect();
    let p = import_puppet(&svg(&body), &PuppetOptions::default().with_vertices(2000)).unwrap();
    assert_eq!(p.puppet.parts.len(), n as usize);
    assert_eq!(p.puppet.joints.len(), (n * (n - 1) / 2) as usize);
    for joint in &p.puppet.joints {
        let [front, back] = joint.parts;
        assert!(front > back && on_part(&p, front, joint.point) && on_part(&p, back, joint.point), "{joint:?}");
    }
}
