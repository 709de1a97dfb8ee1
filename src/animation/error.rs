//! `AnimationError`: why an animation could not be encoded, packed, written or read.

use std::fmt;

use crate::error_code::ErrorCode;
use crate::import::ImportError;
use crate::message::Number;

/// Why an animation (GIF, APNG, ZIP of frames, `akap-animation` JSON or sprite table)
/// could not be made or read.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum AnimationError {
    /// A frame size that is not at least 1 x 1, or beyond what the format can store.
    Size {
        /// Width in pixels.
        width: u64,
        /// Height in pixels.
        height: u64,
        /// What is wrong, e.g. "GIF stores at most 65535 pixels a side".
        reason: &'static str,
    },
    /// Beyond a size limit: pixels of a frame, bytes of all frames, frames, keys, files of
    /// a ZIP, bytes of a text.
    TooLarge {
        /// What is too large, e.g. "the animation's frames".
        what: &'static str,
        /// Its size.
        size: u64,
        /// The limit.
        limit: u64,
        /// The unit of both.
        unit: &'static str,
    },
    /// A frame's RGBA buffer does not hold 4 bytes per pixel.
    FrameLength {
        /// The frame's index, from 0.
        frame: usize,
        /// Bytes expected, `4 * width * height`.
        expected: usize,
        /// Bytes given.
        found: usize,
    },
    /// A frame delay outside [`crate::animation::DELAY_MS_RANGE`].
    Delay {
        /// The frame's index, from 0.
        frame: usize,
        /// The delay given, in milliseconds.
        delay_ms: f64,
    },
    /// `finish` with no frame added.
    NoFrames,
    /// The encoder has finished (the bindings' object only; Rust's `finish` takes it).
    Finished,
    /// A file name a ZIP cannot hold safely: empty, absolute, with `..`, a duplicate...
    FileName {
        /// The name (shortened in the message when long).
        name: String,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// An animation or sprite table to write that is not valid (what the reader would
    /// refuse): counts, order, numbers out of range.
    Invalid {
        /// What is wrong.
        message: String,
    },
    /// An `akap-animation` file that cannot be read: malformed JSON (with the position)...
    Syntax {
        /// The parser's description.
        message: String,
        /// Line, from 1.
        line: usize,
        /// Column, from 1.
        column: usize,
    },
    /// ...or well-formed JSON that is not a valid animation.
    File {
        /// What is wrong.
        message: String,
    },
    /// The animation's rest mesh is invalid: the rules and errors of a JSON mesh file
    /// ([`crate::import::mesh_file::read_json`]).
    Mesh(ImportError),
    /// The image encoder failed (a bug: the input was checked before).
    Encoder {
        /// What the encoder said.
        message: String,
    },
}

/// A name for messages: at most 60 characters, then an ellipsis.
fn short(name: &str) -> String {
    match name.char_indices().nth(60) {
        Some((end, _)) => format!("{}…", &name[..end]),
        None => name.to_string(),
    }
}

impl fmt::Display for AnimationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Size { width, height, reason } => write!(f, "a frame of {width} x {height} pixels: {reason}"),
            Self::TooLarge { what, size, limit, unit } => {
                write!(f, "{what} would have {size} {unit}, more than the limit of {limit} {unit}")
            }
            Self::FrameLength { frame, expected, found } => write!(
                f,
                "frame {frame} has {found} bytes of RGBA; {expected} are needed, 4 per pixel of the animation's size"
            ),
            Self::Delay { frame, delay_ms } => write!(
                f,
                "frame {frame} has a delay of {} ms; expected a whole number of milliseconds from {} to {}",
                Number(*delay_ms),
                super::DELAY_MS_RANGE.start(),
                super::DELAY_MS_RANGE.end()
            ),
            Self::NoFrames => write!(f, "the animation has no frames; add at least one before finishing"),
            Self::Finished => write!(f, "the animation encoder has finished; make a new one"),
            Self::FileName { name, reason } => write!(f, "the file name \"{}\" {reason}", short(name)),
            Self::Invalid { message } => write!(f, "{message}"),
            Self::Syntax { message, line, column } => {
                write!(f, "the animation JSON is malformed at line {line}, column {column}: {message}")
            }
            Self::File { message } => write!(f, "the animation file is not valid: {message}"),
            Self::Mesh(e) => write!(f, "the animation's mesh: {e}"),
            Self::Encoder { message } => write!(f, "the image encoder failed: {message}"),
        }
    }
}

impl std::error::Error for AnimationError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Mesh(e) => Some(e),
            _ => None,
        }
    }
}

impl AnimationError {
    /// The kind of error: [`ErrorCode::Limit`] beyond a size limit, [`ErrorCode::Import`]
    /// for an animation file that cannot be read, the mesh file's own for its mesh,
    /// [`ErrorCode::Internal`] should an image encoder fail, otherwise
    /// [`ErrorCode::InvalidArgument`] (sizes, pixel buffers, delays, file names, an
    /// animation to write that is not valid, an encoder without frames or finished).
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::TooLarge { .. } => ErrorCode::Limit,
            Self::Syntax { .. } | Self::File { .. } => ErrorCode::Import,
            Self::Mesh(e) => e.code(),
            Self::Encoder { .. } => ErrorCode::Internal,
            Self::Size { .. }
            | Self::FrameLength { .. }
            | Self::Delay { .. }
            | Self::NoFrames
            | Self::Finished
            | Self::FileName { .. }
            | Self::Invalid { .. } => ErrorCode::InvalidArgument,
        }
    }
}

impl From<ImportError> for AnimationError {
    fn from(e: ImportError) -> Self {
        Self::Mesh(e)
    }
}
