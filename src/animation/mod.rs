//! Animation out (issue 23): a posed mesh played over time, as files.
//!
//! | module | what |
//! |---|---|
//! | [`encode`] | [`AnimationEncoder`]: RGBA frames, one at a time, into an animated GIF (the `gif` crate, NeuQuant for frames of more than 256 colours) or an APNG (each frame compressed by the `png` crate as it is added; the chunks around them written at the end, when the frame count is known) |
//! | [`zip`] | [`write_zip`]: files stored (not compressed) in one ZIP, e.g. an SVG or PNG per frame; [`crc32`] |
//! | [`file`](mod@file) | the `akap-animation` JSON format, its one definition: a rest mesh, keys of handle positions, and every frame's vertex positions; written and read with every check |
//! | [`sprites`] | the `akap-sprites` JSON frame table of a sprite sheet |
//!
//! Everything is plain Rust: the page renders the frames and hands over their pixels. Input
//! is checked at the boundary, against the constants here and [`Limits`](crate::import::Limits)
//! (`max_pixels` per frame, `max_animation_bytes` for all frames, `max_bytes` for the JSON
//! text), and refused with an [`AnimationError`]; nothing panics on bad input.

use std::ops::RangeInclusive;

pub mod encode;
mod error;
pub mod file;
pub mod sprites;
pub mod zip;

pub use encode::{AnimationEncoder, Format};
pub use error::AnimationError;
pub use file::{read_animation, write_animation, Animation, Easing, Key};
pub use sprites::{sprite_table, SpriteSheet};
pub use zip::{crc32, write_zip};

/// Delays a frame may be shown for, in whole milliseconds (APNG stores `ms / 1000` exactly;
/// GIF rounds to centiseconds, see [`GIF_MIN_DELAY_CS`]).
pub const DELAY_MS_RANGE: RangeInclusive<u32> = 1..=65_535;

/// The shortest GIF delay written, in centiseconds: browsers play a delay of 0 or 1 cs
/// as 10 cs, so shorter delays become 2 cs (20 ms, 50 frames a second at most).
pub const GIF_MIN_DELAY_CS: u16 = 2;

/// Frames per second of an `akap-animation` file and of a sprite table.
pub const FPS_RANGE: RangeInclusive<f64> = 1.0..=120.0;

/// Most frames of an `akap-animation` file or a sprite table (about 14 minutes at 120
/// frames a second; a file's size is bounded by [`Limits::max_bytes`](crate::import::Limits)
/// well before that for any but the smallest meshes).
pub const MAX_FRAMES: usize = 100_000;

/// Most keys of an `akap-animation` file.
pub const MAX_KEYS: usize = 10_000;
