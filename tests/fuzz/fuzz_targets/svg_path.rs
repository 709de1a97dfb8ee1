//! SVG path data as we write it: any path (verbs and finite points from the input bytes)
//! written by `VectorPath::to_path_data` reads back, with svgtypes (the reader usvg uses),
//! as the same commands and points, exactly.
#![no_main]

use akap::import::vector::{VectorPath, Verb};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut path = VectorPath { verbs: vec![Verb::Move], points: Vec::new() };
    let mut bytes = data.chunks_exact(9);
    let mut number = || {
        let chunk = bytes.next()?;
        let value = f64::from_le_bytes(chunk[1..9].try_into().ok()?);
        Some((chunk[0], if value.is_finite() { value } else { 0.0 }))
    };
    let mut needed = 1;
    while let Some((verb, x)) = number() {
        let Some((_, y)) = number() else { break };
        path.points.push([x, y]);
        needed -= 1;
        if needed == 0 {
            let next = [Verb::Line, Verb::Quad, Verb::Cubic, Verb::Close][usize::from(verb % 4)];
            path.verbs.push(next);
            needed = next.point_count();
            if needed == 0 {
                path.verbs.push(Verb::Move);
                needed = 1;
            }
        }
    }
    while needed > 0 {
        path.points.push([0.0, 0.0]);
        needed -= 1;
    }
    let written = path.to_path_data(&path.points);
    let mut read = Vec::new();
    for segment in svgtypes::PathParser::from(written.as_str()) {
        match segment.expect("written path data parses") {
            svgtypes::PathSegment::MoveTo { x, y, .. } | svgtypes::PathSegment::LineTo { x, y, .. } => read.push([x, y]),
            svgtypes::PathSegment::Quadratic { x1, y1, x, y, .. } => read.extend([[x1, y1], [x, y]]),
            svgtypes::PathSegment::CurveTo { x1, y1, x2, y2, x, y, .. } => read.extend([[x1, y1], [x2, y2], [x, y]]),
            svgtypes::PathSegment::ClosePath { .. } => {}
            other => panic!("{other:?} in {written}"),
        }
    }
    assert_eq!(read, path.points, "round trip of {written:?}");
});
