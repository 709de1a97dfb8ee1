//! SVG art as artists export it (issue 21): strokes as area, CSS, clones, clip paths,
//! masks, hidden things, and one cartoon exported in the styles of Inkscape and Illustrator.
//! Expected areas come from geometry: rings, rectangles, discs and their overlaps.

use std::f64::consts::PI;

use akap::import::svg::{import_svg, FillColour, Part, SvgOptions, SvgShape};
use akap::{triangulate, Outline, TriangulationOptions};
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

fn svg(body: &str) -> String {
    format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" viewBox="0 0 100 100">{body}</svg>"#
    )
}

/// Flattened finely: chords within 1e-3 of the curves, so areas agree to about
/// perimeter x 1e-3.
fn shape(body: &str, options: SvgOptions) -> SvgShape {
    import_svg(&svg(body), &SvgOptions { tolerance: Some(1e-3), ..options }).unwrap()
}

fn area(body: &str) -> f64 {
    shape(body, SvgOptions::default()).outlines.iter().map(Outline::area).sum()
}

/// usvg draws circles and arcs as cubics of a quarter turn, whose distance from the centre
/// exceeds the radius by up to 2.7e-4 of it: areas of discs and rings come out up to twice
/// that, relatively, above the exact ones.
const ROUND: f64 = 6e-4;

fn close(got: f64, expected: f64, tolerance: f64) {
    assert!((got - expected).abs() <= tolerance, "{got} against {expected} (within {tolerance})");
}

#[test]
fn a_stroke_covers_its_outline() {
    // A stroked circle of radius r and width w covers the ring between r - w/2 and r + w/2;
    // with its fill, the disc of radius r + w/2; with strokes off, the disc of radius r.
    let (r, w) = (30.0, 8.0);
    let ring = PI * ((r + w / 2.0) * (r + w / 2.0) - (r - w / 2.0) * (r - w / 2.0));
    let stroked = format!(r#"<circle cx="50" cy="50" r="{r}" fill="none" stroke="black" stroke-width="{w}"/>"#);
    close(area(&stroked), ring, ROUND * ring);
    let both = format!(r#"<circle cx="50" cy="50" r="{r}" fill="red" stroke="black" stroke-width="{w}"/>"#);
    let disc = PI * (r + w / 2.0) * (r + w / 2.0);
    close(area(&both), disc, ROUND * disc);
    let fills_only = shape(&both, SvgOptions { strokes: false, ..SvgOptions::default() });
    close(fills_only.outlines[0].area(), PI * r * r, ROUND * PI * r * r);
    // The stroke's outline is exported as a filled area in the stroke's colour, after the
    // fill.
    let paths = shape(&both, SvgOptions::default()).paths;
    let parts: Vec<(Part, Option<FillColour>)> = paths.iter().map(|p| (p.part, p.fill)).collect();
    let colour = |red, alpha| Some(FillColour { red, green: 0, blue: 0, alpha });
    assert_eq!(parts, [(Part::Fill, colour(255, 1.0)), (Part::Stroke, colour(0, 1.0))]);
}

#[test]
fn joins_caps_and_dashes_shape_the_stroke() {
    // A square of side s stroked with width w: the frame between s + w and s - w, less the
    // corners a bevel cuts (4 triangles of legs w/2) or a round join rounds (4 squares of
    // side w/2 less quarter discs).
    let (s, w) = (40.0, 10.0);
    let square = |join: &str| {
        area(&format!(
            r#"<rect x="30" y="30" width="{s}" height="{s}" fill="none" stroke="black" stroke-width="{w}" stroke-linejoin="{join}"/>"#
        ))
    };
    let frame = (s + w) * (s + w) - (s - w) * (s - w);
    let tolerance = 1e-3;
    close(square("miter"), frame, tolerance);
    close(square("bevel"), frame - 4.0 * (w / 2.0) * (w / 2.0) / 2.0, tolerance);
    close(square("round"), frame - 4.0 * (1.0 - PI / 4.0) * (w / 2.0) * (w / 2.0), ROUND * frame);
    // A line of length l and width w: butt caps end at its ends, square caps w/2 beyond,
    // round caps with half discs.
    let (l, w) = (60.0, 6.0);
    let line = |cap: &str| {
        area(&format!(
            r#"<line x1="20" y1="50" x2="{}" y2="50" stroke="black" stroke-width="{w}" stroke-linecap="{cap}"/>"#,
            20.0 + l
        ))
    };
    close(line("butt"), l * w, tolerance);
    close(line("square"), (l + w) * w, tolerance);
    close(line("round"), l * w + PI * (w / 2.0) * (w / 2.0), ROUND * l * w);
    // Dashes of 10 with gaps of 5 along 60: four dashes, butt caps.
    let dashed =
        format!(r#"<line x1="20" y1="50" x2="80" y2="50" stroke="black" stroke-width="{w}" stroke-dasharray="10 5"/>"#);
    let parts = shape(&dashed, SvgOptions::default()).outlines;
    assert_eq!(parts.len(), 4);
    close(parts.iter().map(Outline::area).sum(), 4.0 * 10.0 * w, tolerance);
    // A stroke-only drawing imports (the importer used to refuse it).
    assert!(import_svg(&svg(&dashed), &SvgOptions { strokes: false, ..SvgOptions::default() }).is_err());
}

#[test]
fn styles_clones_and_transform_origin_are_resolved() {
    // CSS classes as Illustrator writes them: the outline class is unfilled and unstroked.
    let styled = r#"<style>.a { fill: none; stroke: none } .b { fill: #123 }</style>
        <rect class="a" width="100" height="100"/><rect class="b" x="10" y="10" width="20" height="20"/>"#;
    assert_eq!(area(styled), 400.0);
    // A <use> of a shape twice, apart: twice its area; a <symbol> used once.
    let clones = r##"<defs><rect id="s" width="10" height="20"/></defs>
        <use xlink:href="#s" x="5" y="5"/><use href="#s" x="50" y="50"/>
        <symbol id="dot"><rect width="4" height="5"/></symbol><use href="#dot" x="80" y="5"/>"##;
    assert_eq!(area(clones), 2.0 * 200.0 + 20.0);
    // transform-origin: a 20 x 10 rectangle turned 90 degrees about its centre (50, 50)
    // covers 45..55 x 40..60, so a square over 45..55 x 40..50 lies inside it.
    let turned = r#"<rect x="40" y="45" width="20" height="10" transform="rotate(90)" transform-origin="50 50"/>
        <rect x="45" y="40" width="10" height="10"/>"#;
    close(area(turned), 200.0, 1e-9);
}

#[test]
fn hidden_things_add_nothing() {
    let square = r#"<rect x="10" y="10" width="20" height="20"/>"#;
    let hidden = r#"<rect x="50" width="30" height="30" opacity="0"/>
        <rect x="50" width="30" height="30" fill-opacity="0"/>
        <rect x="50" width="30" height="30" visibility="hidden"/>
        <g opacity="0"><rect x="50" width="30" height="30"/></g>
        <rect x="50" width="30" height="30" fill="none" stroke="black" stroke-opacity="0"/>
        <rect x="50" width="30" height="30" style="display:none"/>"#;
    assert_eq!(area(&format!("{square}{hidden}")), 400.0);
}

#[test]
fn clip_paths_intersect_what_they_clip() {
    // The square 0..40 clipped by a disc of radius 20 about its corner (40, 40): a quarter
    // disc.
    let r = 20.0;
    let quarter = PI * r * r / 4.0;
    let clipped = format!(
        r#"<clipPath id="c"><circle cx="40" cy="40" r="{r}"/></clipPath>
        <rect width="40" height="40" clip-path="url(#c)"/>"#
    );
    close(area(&clipped), quarter, ROUND * quarter);
    // On a group, with clipPathUnits="objectBoundingBox" (the unit square maps to each
    // clipped element's box), and clip-rule even-odd making a frame.
    let frame = r#"<clipPath id="f" clipPathUnits="objectBoundingBox">
            <path clip-rule="evenodd" d="M0 0H1V1H0Z M0.25 0.25H0.75V0.75H0.25Z"/></clipPath>
        <g clip-path="url(#f)"><rect width="40" height="40"/></g>"#;
    close(area(frame), 1600.0 * 0.75, 1e-6);
    // A clip path clipped in turn: the intersection of both.
    let twice = r#"<clipPath id="a"><rect width="30" height="100"/></clipPath>
        <clipPath id="b" clip-path="url(#a)"><rect width="100" height="20"/></clipPath>
        <rect width="100" height="100" clip-path="url(#b)"/>"#;
    close(area(twice), 600.0, 1e-6);
    // A nested <svg> clips to its viewport: a 10 x 10 viewport shows 100 of a 30 x 30 square.
    close(area(r#"<svg x="20" y="20" width="10" height="10"><rect width="30" height="30"/></svg>"#), 100.0, 1e-6);
    // What a clip removes is removed from the exported path too.
    let shape = shape(&clipped, SvgOptions::default());
    let exported = shape.paths[0].path.flatten(1.0, 0, 10_000).unwrap();
    let exported: f64 = exported.iter().map(|r| akap::geometry::polygon_area(r).abs()).sum();
    close(exported, quarter, ROUND * quarter);
}

#[test]
fn masks_keep_the_shapes_that_let_something_through() {
    // A white disc in a mask lets the square through there; a black one lets nothing through.
    let r = 15.0;
    let masked = |colour: &str| {
        format!(
            r#"<mask id="m" maskUnits="userSpaceOnUse" x="0" y="0" width="100" height="100">
                <circle cx="50" cy="50" r="{r}" fill="{colour}"/></mask>
            <rect width="100" height="100" mask="url(#m)"/>"#
        )
    };
    close(area(&masked("white")), PI * r * r, ROUND * PI * r * r);
    assert!(import_svg(&svg(&masked("black")), &SvgOptions::default()).is_err());
    // The mask's rectangle bounds it: a mask 20 wide keeps 20 of the 30 x 30 square.
    let narrow = r#"<mask id="n" maskUnits="userSpaceOnUse" x="0" y="0" width="20" height="100">
            <rect width="100" height="100" fill="white"/></mask>
        <rect width="30" height="30" mask="url(#n)"/>"#;
    close(area(narrow), 600.0, 1e-6);
}

#[test]
fn a_cartoon_from_inkscape_and_from_illustrator_imports_the_same() {
    let inkscape = include_str!("fixtures/svg/cat-inkscape.svg");
    let illustrator = include_str!("fixtures/svg/cat-illustrator.svg");
    let options = SvgOptions::default();
    let a = import_svg(inkscape, &options).unwrap();
    let b = import_svg(illustrator, &options).unwrap();
    // The hidden sketch layer and Illustrator's private data add nothing: the head with its
    // ears and whiskers (which start inside it) is one part.
    assert_eq!((a.outlines.len(), b.outlines.len()), (1, 1));
    let total = |s: &SvgShape| s.outlines.iter().map(Outline::area).sum::<f64>();
    close(total(&a), total(&b), 1e-6 * total(&a));
    for (p, q) in a.outlines.iter().zip(&b.outlines) {
        close(p.area(), q.area(), 1e-6 * p.area());
        assert_eq!(p.holes.len(), q.holes.len());
    }
    // The stroked head alone is the disc of radius 32; the ears and whiskers add to it, and
    // everything lies within the page.
    assert!(total(&a) > PI * 32.0 * 32.0 + 100.0, "{}", total(&a));
    assert!(total(&a) < 120.0 * 100.0);
    // Both name what they skipped (Illustrator's foreignObject), and the cartoon meshes.
    assert_eq!(b.skipped, ["foreignObject"]);
    let mesh = triangulate(&a.outlines[0], &TriangulationOptions::default().with_target_edge_length(3.0)).unwrap();
    assert!((mesh.area() - a.outlines[0].area()).abs() < 1e-9 * mesh.area());
    // Fills come in with their colours, strokes with theirs, in drawing order: ears and
    // head filled and stroked, two eyes, then the whiskers (two paths of two strokes each
    // from Inkscape, four lines from Illustrator).
    let fill = |red, green, blue| Some(FillColour { red, green, blue, alpha: 1.0 });
    let (skin, white, black) = (fill(0xf4, 0xa4, 0x60), fill(255, 255, 255), fill(0, 0, 0));
    let mut expected = [(Part::Fill, skin), (Part::Stroke, black)].repeat(3);
    expected.extend([(Part::Fill, white), (Part::Fill, white)]);
    let colours = |s: &SvgShape| s.paths.iter().map(|p| (p.part, p.fill)).collect::<Vec<_>>();
    let whiskers = |n| [(Part::Stroke, black)].repeat(n);
    assert_eq!(colours(&a), [expected.clone(), whiskers(2)].concat());
    assert_eq!(colours(&b), [expected, whiskers(4)].concat());
}
