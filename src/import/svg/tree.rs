//! A spike for issue 21 (not wired into `import_svg` yet): the drawing as usvg resolves it
//! (CSS, `<use>`, units, transforms, `switch`, markers, paint references), turned into the
//! paths our downstream steps take, in output coordinates (the root's user units, y up).
//! Visible fills become filled paths with their rule and colour; visible strokes become
//! their outlines (dashes first, then tiny-skia's stroker: width, joins, caps, miter
//! limit), filled with the nonzero rule. Groups with zero opacity, invisible paths and
//! paints with zero opacity draw nothing. Clip paths and masks are not applied yet.

use tiny_skia_path::{PathSegment, Transform};

use super::{FillColour, SvgPath};
use crate::import::error::{ElementRef, ImportError};
use crate::import::vector::{FillRule, VectorPath, Verb};
use crate::import::Limits;

/// What a usvg path contributes: its fill, or its stroke's outline.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// The path's interior.
    Fill,
    /// The area its stroke covers.
    Stroke,
}

/// The filled and stroked areas of `tree`, each with where it came from, in document order
/// (a path's fill before its stroke, as `paint-order` normally has it), within `limits`:
/// at most `max_points` points in all, every coordinate within `max_coordinate`.
pub fn visible_paths(
    tree: &usvg::Tree,
    output: [f64; 6],
    limits: &Limits,
) -> Result<Vec<(SvgPath, Part)>, ImportError> {
    let mut out = Vec::new();
    let mut points = 0usize;
    let mut stack: Vec<(&usvg::Group, f32)> = vec![(tree.root(), 1.0)];
    // Depth-first, in document order: children are pushed in reverse.
    let mut pending: Vec<(&usvg::Node, f32)> = Vec::new();
    while let Some((group, opacity)) = stack.pop() {
        for child in group.children().iter().rev() {
            pending.push((child, opacity));
        }
        while let Some((node, opacity)) = pending.pop() {
            match node {
                usvg::Node::Group(g) => {
                    let opacity = opacity * g.opacity().get();
                    if opacity > 0.0 {
                        for child in g.children().iter().rev() {
                            pending.push((child, opacity));
                        }
                    }
                }
                usvg::Node::Path(p) if p.is_visible() => {
                    let before = out.len();
                    add_path(p, opacity, output, &mut out);
                    for (path, _) in &out[before..] {
                        points += path.path.points.len();
                        if points > limits.max_points {
                            return Err(ImportError::TooManyPoints {
                                what: "the SVG's shapes",
                                needed: None,
                                limit: limits.max_points,
                            });
                        }
                        let limit = limits.max_coordinate;
                        if let Some(&value) = path.path.points.iter().flatten().find(|v| v.is_nan() || v.abs() > limit)
                        {
                            return Err(ImportError::CoordinateTooLarge {
                                element: path.element.clone(),
                                value,
                                limit,
                            });
                        }
                    }
                }
                _ => {}
            }
        }
    }
    Ok(out)
}

fn add_path(p: &usvg::Path, opacity: f32, output: [f64; 6], out: &mut Vec<(SvgPath, Part)>) {
    let element =
        ElementRef { name: "path".into(), id: (!p.id().is_empty()).then(|| p.id().to_string()), line: 0, column: 0 };
    let ts = p.abs_transform();
    if let Some(fill) = p.fill() {
        let alpha = opacity * fill.opacity().get();
        if alpha > 0.0 {
            let rule = match fill.rule() {
                usvg::FillRule::NonZero => FillRule::NonZero,
                usvg::FillRule::EvenOdd => FillRule::EvenOdd,
            };
            let path = convert(p.data(), ts, output);
            out.push((
                SvgPath { element: element.clone(), path, fill_rule: rule, fill: colour(fill.paint(), alpha) },
                Part::Fill,
            ));
        }
    }
    if let Some(stroke) = p.stroke() {
        let alpha = opacity * stroke.opacity().get();
        if alpha > 0.0 {
            // Stroked in the path's own coordinates (where width and dashes are given), with
            // the resolution scale of the transform so that round joins stay round.
            // tiny-skia's stroker's nominal accuracy is 1/(4 scale); at a thousandth of the
            // size (the flattening's) a stroked circle's area was 0.4% off, at 1e-5 of it
            // within 2e-4 (the test below).
            let b = p.data().bounds();
            let size = (b.width().hypot(b.height()) + stroke.width().get()).max(1e-6);
            let scale = 0.25 / (1e-5 * size);
            let tiny = stroke.to_tiny_skia();
            let dashed = match &tiny.dash {
                Some(dash) => p.data().dash(dash, scale),
                None => Some(p.data().clone()),
            };
            if let Some(outline) = dashed.and_then(|d| d.stroke(&tiny, scale)) {
                let path = convert(&outline, ts, output);
                out.push((
                    SvgPath { element, path, fill_rule: FillRule::NonZero, fill: colour(stroke.paint(), alpha) },
                    Part::Stroke,
                ));
            }
        }
    }
}

fn colour(paint: &usvg::Paint, alpha: f32) -> Option<FillColour> {
    match paint {
        usvg::Paint::Color(c) => Some(FillColour { red: c.red, green: c.green, blue: c.blue, alpha: f64::from(alpha) }),
        _ => None,
    }
}

/// A tiny-skia path through `ts` (f32, as usvg keeps it) and then `output` (f64).
fn convert(path: &tiny_skia_path::Path, ts: Transform, output: [f64; 6]) -> VectorPath {
    let [a, b, c, d, e, f] = output;
    let place = |p: tiny_skia_path::Point| {
        let (x, y) = (f64::from(p.x), f64::from(p.y));
        let (x, y) = (
            f64::from(ts.sx) * x + f64::from(ts.kx) * y + f64::from(ts.tx),
            f64::from(ts.ky) * x + f64::from(ts.sy) * y + f64::from(ts.ty),
        );
        [a * x + c * y + e, b * x + d * y + f]
    };
    let mut verbs = Vec::new();
    let mut points = Vec::new();
    for segment in path.segments() {
        match segment {
            PathSegment::MoveTo(p) => {
                verbs.push(Verb::Move);
                points.push(place(p));
            }
            PathSegment::LineTo(p) => {
                verbs.push(Verb::Line);
                points.push(place(p));
            }
            PathSegment::QuadTo(p1, p) => {
                verbs.push(Verb::Quad);
                points.extend([place(p1), place(p)]);
            }
            PathSegment::CubicTo(p1, p2, p) => {
                verbs.push(Verb::Cubic);
                points.extend([place(p1), place(p2), place(p)]);
            }
            PathSegment::Close => verbs.push(Verb::Close),
        }
    }
    VectorPath { verbs, points }
}

#[cfg(test)]
mod tests {
    use super::super::{import_svg_usvg, SvgOptions};

    fn area(svg: &str) -> f64 {
        let shape = import_svg_usvg(svg, &SvgOptions::default().with_tolerance(0.01)).unwrap();
        shape.outlines.iter().map(|o| o.area()).sum()
    }

    #[test]
    fn a_stroked_circle_covers_its_ring_and_invisible_things_nothing() {
        let (r, w) = (40.0, 10.0);
        let ring = std::f64::consts::PI * ((r + w / 2.0) * (r + w / 2.0) - (r - w / 2.0) * (r - w / 2.0));
        let svg = format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100" width="300" height="300">
               <circle cx="50" cy="50" r="{r}" fill="none" stroke="black" stroke-width="{w}"/>
               <rect x="0" y="0" width="10" height="10" opacity="0"/>
               <rect x="0" y="0" width="10" height="10" fill-opacity="0"/>
               <rect x="0" y="0" width="10" height="10" visibility="hidden"/></svg>"#
        );
        let got = area(&svg);
        assert!((got - ring).abs() < 2e-4 * ring, "{got} against {ring}");
        // CSS classes (Illustrator's export) and <use> twice, apart: twice the area.
        let styled = r##"<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" viewBox="0 0 100 100">
            <style>.a { fill: none; stroke: none } .b { fill: #123 }</style>
            <rect class="a" x="0" y="0" width="100" height="100"/>
            <defs><rect id="s" class="b" width="10" height="20"/></defs>
            <use xlink:href="#s" x="5" y="5"/><use href="#s" x="50" y="50"/></svg>"##;
        assert!((area(styled) - 400.0).abs() < 1e-3, "{}", area(styled));
    }

    #[test]
    fn our_limits_hold_before_usvg_reads_anything() {
        use crate::import::{ImportError, Limits};
        let deep = format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg">{}<rect width="1" height="1"/>{}</svg>"#,
            "<g>".repeat(300),
            "</g>".repeat(300)
        );
        let error = import_svg_usvg(&deep, &SvgOptions::default()).unwrap_err();
        assert!(matches!(error, ImportError::TooDeep { limit: 256, .. }), "{error}");
        let small = SvgOptions { limits: Limits { max_bytes: 100, ..Limits::default() }, ..SvgOptions::default() };
        let long = format!(r#"<svg xmlns="http://www.w3.org/2000/svg">{}</svg>"#, "<g/>".repeat(30));
        assert!(matches!(import_svg_usvg(&long, &small), Err(ImportError::TooLarge { .. })));
        // Without a viewBox, y is flipped about the height, as the importer always did.
        let plain = r#"<svg xmlns="http://www.w3.org/2000/svg" height="10"><polygon points="0,0 4,0 4,2"/></svg>"#;
        let shape = import_svg_usvg(plain, &SvgOptions::default()).unwrap();
        let mut ys: Vec<f64> = shape.outlines[0].outer.iter().map(|p| p[1]).collect();
        ys.sort_by(f64::total_cmp);
        assert_eq!(ys, [8.0, 10.0, 10.0]);
    }
}
