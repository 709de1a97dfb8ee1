//! The `akap-animation` JSON: reading never panics or hangs; an animation that reads
//! writes back to the same text, and that text reads to the same animation.
#![no_main]

use akap::animation::{read_animation, write_animation};
use akap::import::Limits;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let limits = Limits { max_vertices: 10_000, ..Limits::default() };
    let Ok(animation) = read_animation(text, &limits) else { return };
    let written = write_animation(&animation, &limits).expect("a read animation writes within the same limits");
    let again = read_animation(&written, &limits).expect("a written animation reads");
    assert_eq!(again, animation);
    assert_eq!(write_animation(&again, &limits).expect("and writes again"), written);
});
