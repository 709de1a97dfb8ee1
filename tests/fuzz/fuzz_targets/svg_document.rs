//! Whole SVG documents: import never panics or hangs, and what it returns are valid
//! outlines.
#![no_main]

use akap::import::svg::{import_svg, SvgOptions};
use akap::import::Limits;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let limits = Limits { max_points: 20_000, ..Limits::default() };
    if let Ok(shape) = import_svg(text, &SvgOptions { limits, ..SvgOptions::default() }) {
        for outline in &shape.outlines {
            // Nearly touching boundaries may still be refused here; never a panic.
            let _ = outline.validated(usize::MAX);
        }
    }
});
