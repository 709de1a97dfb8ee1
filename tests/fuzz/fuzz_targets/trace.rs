//! Raster tracing: small images of arbitrary pixels (the first two bytes give the width
//! and height, 1 to 32) trace into valid outlines, or fail with an error.
#![no_main]

use akap::import::raster::{trace_image, TraceOptions};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let [w, h, tolerance, rest @ ..] = data else { return };
    let (w, h) = (usize::from(w % 32) + 1, usize::from(h % 32) + 1);
    let mut rgba = rest.to_vec();
    rgba.resize(w * h * 4, 0);
    let options = TraceOptions { tolerance: f64::from(*tolerance) / 64.0, min_area: 0.0, ..TraceOptions::default() };
    if let Ok(outlines) = trace_image(&rgba, w, h, &options) {
        for outline in &outlines {
            outline.validated(usize::MAX).expect("traced outlines are valid");
        }
    }
});
