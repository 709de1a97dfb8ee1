//! The `akap-sprites` JSON frame table of a sprite sheet, its one definition: where each
//! frame of an animation lies in one image of all of them, row by row, and how long it is
//! shown.
//!
//! ```json
//! {
//!   "format": "akap-sprites", "version": 1,
//!   "frameWidth": 64, "frameHeight": 48, "columns": 4, "rows": 3, "fps": 30.0,
//!   "size": { "w": 256, "h": 144 },
//!   "frames": [ { "x": 0, "y": 0, "w": 64, "h": 48, "duration": 33 }, ... ]
//! }
//! ```
//!
//! Frame `i` is at column `i % columns`, row `i / columns` (row-major, from the top-left
//! corner, y down as in the image): `x = (i % columns) * frameWidth`, `y = (i / columns) *
//! frameHeight`. `rows` is `ceil(frameCount / columns)`, `size` the sheet's pixels,
//! `columns * frameWidth` by `rows * frameHeight` (the last row may be part empty).
//! `duration` is in whole milliseconds, rounded on the running total, so that the
//! durations add up to the animation's length: frame `i` lasts `round(1000 (i + 1) / fps)
//! - round(1000 i / fps)` (33, 34, 33, ... at 30 fps).

use serde::Serialize;

use super::{AnimationError, FPS_RANGE, MAX_FRAMES};
use crate::import::Limits;
use crate::message::Number;

/// The format's name, the `format` field.
pub const FORMAT: &str = "akap-sprites";

/// A sprite sheet's layout: frames of one size in rows of `columns`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpriteSheet {
    /// A frame's width in pixels, at least 1.
    pub frame_width: u32,
    /// A frame's height in pixels, at least 1.
    pub frame_height: u32,
    /// Frames per row, at least 1.
    pub columns: u32,
    /// Frames, from 1 to [`MAX_FRAMES`].
    pub frame_count: u32,
    /// Frames per second, in [`FPS_RANGE`].
    pub fps: f64,
}

#[derive(Serialize)]
struct Size {
    w: u64,
    h: u64,
}

#[derive(Serialize)]
struct Entry {
    x: u64,
    y: u64,
    w: u32,
    h: u32,
    duration: u64,
}

#[derive(Serialize)]
#[serde(rename_all = "camelCase")]
struct Table {
    format: &'static str,
    version: u32,
    frame_width: u32,
    frame_height: u32,
    columns: u32,
    rows: u64,
    fps: f64,
    size: Size,
    frames: Vec<Entry>,
}

/// The frame table of `sheet` as `akap-sprites` JSON (version 1). Refuses sizes and counts
/// below 1, more than [`MAX_FRAMES`] frames, an fps outside [`FPS_RANGE`]
/// ([`AnimationError::Invalid`]), and a sheet of more than `limits.max_pixels` pixels
/// ([`AnimationError::TooLarge`]).
///
/// ```
/// use akap::animation::{sprite_table, SpriteSheet};
/// let sheet = SpriteSheet { frame_width: 10, frame_height: 20, columns: 2, frame_count: 3, fps: 10.0 };
/// let json = sprite_table(&sheet, &akap::import::Limits::default())?;
/// assert!(json.contains(r#""rows":2,"fps":10.0,"size":{"w":20,"h":40}"#));
/// assert!(json.ends_with(r#"{"x":0,"y":20,"w":10,"h":20,"duration":100}]}"#));
/// # Ok::<(), akap::animation::AnimationError>(())
/// ```
pub fn sprite_table(sheet: &SpriteSheet, limits: &Limits) -> Result<String, AnimationError> {
    let invalid = |message: String| Err(AnimationError::Invalid { message });
    let &SpriteSheet { frame_width, frame_height, columns, frame_count, fps } = sheet;
    for (name, value) in [("frameWidth", frame_width), ("frameHeight", frame_height), ("columns", columns)] {
        if value == 0 {
            return invalid(format!("{name} is 0; it must be at least 1"));
        }
    }
    if frame_count == 0 || frame_count as usize > MAX_FRAMES {
        return invalid(format!("frameCount is {frame_count}, expected a whole number from 1 to {MAX_FRAMES}"));
    }
    if !FPS_RANGE.contains(&fps) {
        return invalid(format!(
            "fps is {}, expected a number from {} to {}",
            Number(fps),
            Number(*FPS_RANGE.start()),
            Number(*FPS_RANGE.end())
        ));
    }
    let rows = u64::from(frame_count).div_ceil(u64::from(columns));
    let size = Size { w: u64::from(columns) * u64::from(frame_width), h: rows * u64::from(frame_height) };
    // Each factor is below 2^32, so the product of the sides fits a u128.
    let pixels = u128::from(size.w) * u128::from(size.h);
    if pixels > limits.max_pixels as u128 {
        return Err(AnimationError::TooLarge {
            what: "the sprite sheet",
            size: u64::try_from(pixels).unwrap_or(u64::MAX),
            limit: limits.max_pixels as u64,
            unit: "pixels",
        });
    }
    let end_ms = |i: u64| (1000.0 * i as f64 / fps).round() as u64;
    let frames = (0..u64::from(frame_count))
        .map(|i| Entry {
            x: (i % u64::from(columns)) * u64::from(frame_width),
            y: (i / u64::from(columns)) * u64::from(frame_height),
            w: frame_width,
            h: frame_height,
            duration: end_ms(i + 1) - end_ms(i),
        })
        .collect();
    let table = Table { format: FORMAT, version: 1, frame_width, frame_height, columns, rows, fps, size, frames };
    serde_json::to_string(&table).map_err(|e| AnimationError::Encoder { message: e.to_string() })
}
