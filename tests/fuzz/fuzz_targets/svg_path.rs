//! SVG path data: parsing never panics or hangs; what parses flattens within its point
//! budget, and writing the points back gives path data that parses to the same path.
#![no_main]

use akap::import::svg::parse_path_data;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let Ok(path) = parse_path_data(text, 10_000) else { return };
    let _ = path.flatten(0.01, 0, 100_000);
    if path.points.iter().all(|p| p[0].is_finite() && p[1].is_finite()) {
        let written = path.to_path_data(&path.points);
        let again = parse_path_data(&written, 10_000).expect("written path data parses");
        assert_eq!(again, path, "round trip of {written:?}");
    }
});
