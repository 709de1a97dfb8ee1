//! [`AnimationEncoder`]: RGBA frames, added one at a time, into an animated GIF or APNG.
//!
//! Frames come one call at a time so that a page can report progress and cancel between
//! them. Each frame is encoded when it is added, and only the encoded bytes are kept:
//!
//! - **GIF** (the `gif` crate): each frame gets its own palette, exact when the frame has
//!   at most 256 colours (counting a transparent one), else by NeuQuant at speed
//!   [`GIF_SPEED`]. GIF has one bit of alpha: a pixel whose alpha is below 128 is
//!   transparent, any other opaque (its colour as given, alpha ignored). Each frame
//!   replaces the last (disposal "restore to background"). Delays are stored in
//!   centiseconds, rounded on the running total of the delays so that a run of 33 ms
//!   frames plays in 3, 4, 3, ... cs and stays within 5 ms of the time asked for; a
//!   frame never gets less than [`GIF_MIN_DELAY_CS`] (browsers play 0 and 1 cs as 10 cs).
//!   "Play once" is a GIF without the NETSCAPE2.0 loop extension.
//! - **APNG** (the `png` crate): the frame count goes in the `acTL` chunk, before the
//!   frames, and is only known at [`AnimationEncoder::finish`]; so each frame is filtered
//!   and compressed by `png` when it is added (a PNG of its own, whose `IDAT` data is kept)
//!   and `finish` writes the chunks around them: `IHDR`, `acTL`, then per frame `fcTL`
//!   (delay `ms / 1000` exactly, no disposal, "source" blending: each frame replaces the
//!   whole canvas, alpha included) and its data (`IDAT` for the first frame, which is also
//!   the image a viewer without APNG shows; `fdAT` with sequence numbers after), `IEND`.
//!   RGBA 8 bits per channel, lossless.
//!
//! Memory: the frames' RGBA may add up to [`Limits::max_animation_bytes`] (1 GiB by
//! default, 4 bytes per pixel per frame, counted before encoding so that the limit does
//! not depend on how well frames compress); the encoder holds the encoded frames, at most
//! about that much and usually far less, plus one frame's copy while it is encoded.

use super::{AnimationError, DELAY_MS_RANGE, GIF_MIN_DELAY_CS};
use crate::import::Limits;

/// NeuQuant's speed for GIF frames of more than 256 colours (1, best, to 30, fastest):
/// 10 samples a tenth of the pixels. Measured on 512 x 512 frames of smooth gradients
/// (`cargo run --release --example encode_timing`): see lab/animation/results.md.
pub const GIF_SPEED: i32 = 10;

/// An animated image format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Animated GIF (256 colours a frame, one bit of alpha).
    Gif,
    /// Animated PNG (lossless RGBA).
    Apng,
}

impl Format {
    /// The format's name as the bindings spell it, `"gif"` or `"apng"`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Gif => "gif",
            Self::Apng => "apng",
        }
    }
}

/// A frame's compressed image data (the `IDAT` chunks' data of its own PNG) and delay.
struct ApngFrame {
    data: Vec<Vec<u8>>,
    delay_ms: u16,
}

enum Inner {
    Gif {
        encoder: gif::Encoder<Vec<u8>>,
        /// The delays asked for so far, in ms, and those written, in cs.
        elapsed_ms: u64,
        written_cs: u64,
    },
    Apng {
        /// The `IHDR` chunk's data (the same for every frame).
        header: Vec<u8>,
        frames: Vec<ApngFrame>,
    },
}

/// An animation being encoded: [`new`](Self::new), [`add_frame`](Self::add_frame) for each
/// frame, then [`finish`](Self::finish) for the file's bytes. See the module's
/// documentation for what each format keeps of the pixels.
///
/// ```
/// use akap::animation::{AnimationEncoder, Format};
/// let mut encoder = AnimationEncoder::new(Format::Apng, 2, 1, true)?;
/// encoder.add_frame(&[255, 0, 0, 255, 0, 0, 255, 255], 100)?;
/// encoder.add_frame(&[0, 0, 255, 255, 255, 0, 0, 255], 100)?;
/// let png = encoder.finish()?;
/// assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
/// # Ok::<(), akap::animation::AnimationError>(())
/// ```
pub struct AnimationEncoder {
    format: Format,
    width: u32,
    height: u32,
    loop_forever: bool,
    /// Bytes of RGBA added so far, and the limit on them.
    rgba_bytes: u64,
    max_bytes: u64,
    frames: usize,
    inner: Inner,
}

fn encoder_error(e: impl std::fmt::Display) -> AnimationError {
    AnimationError::Encoder { message: e.to_string() }
}

impl AnimationEncoder {
    /// An encoder of frames of `width` x `height` pixels, looping forever or played once,
    /// within the default [`Limits`].
    pub fn new(format: Format, width: u32, height: u32, loop_forever: bool) -> Result<Self, AnimationError> {
        Self::with_limits(format, width, height, loop_forever, &Limits::default())
    }

    /// [`new`](Self::new) within `limits`: `max_pixels` per frame, `max_animation_bytes`
    /// for the frames' RGBA in all. Refuses a size below 1 x 1, GIF frames wider or taller
    /// than 65,535 pixels (GIF's 16 bits), and limits that
    /// [`Limits::validate`] refuses.
    pub fn with_limits(
        format: Format,
        width: u32,
        height: u32,
        loop_forever: bool,
        limits: &Limits,
    ) -> Result<Self, AnimationError> {
        limits.validate().map_err(|e| AnimationError::Invalid { message: e.to_string() })?;
        let size = |reason| AnimationError::Size { width: width.into(), height: height.into(), reason };
        if width == 0 || height == 0 {
            return Err(size("a frame needs at least 1 x 1 pixels"));
        }
        let pixels = u64::from(width) * u64::from(height);
        if pixels > limits.max_pixels as u64 {
            return Err(AnimationError::TooLarge {
                what: "a frame",
                size: pixels,
                limit: limits.max_pixels as u64,
                unit: "pixels",
            });
        }
        let inner = match format {
            Format::Gif => {
                let (Ok(w), Ok(h)) = (u16::try_from(width), u16::try_from(height)) else {
                    return Err(size("GIF stores at most 65535 pixels a side"));
                };
                let mut encoder = gif::Encoder::new(Vec::new(), w, h, &[]).map_err(encoder_error)?;
                if loop_forever {
                    encoder.set_repeat(gif::Repeat::Infinite).map_err(encoder_error)?;
                }
                Inner::Gif { encoder, elapsed_ms: 0, written_cs: 0 }
            }
            Format::Apng => Inner::Apng { header: Vec::new(), frames: Vec::new() },
        };
        Ok(Self {
            format,
            width,
            height,
            loop_forever,
            rgba_bytes: 0,
            max_bytes: limits.max_animation_bytes as u64,
            frames: 0,
            inner,
        })
    }

    /// The format being written.
    pub fn format(&self) -> Format {
        self.format
    }

    /// Frames added so far.
    pub fn frame_count(&self) -> usize {
        self.frames
    }

    /// The frames' width and height in pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Encodes a frame: `rgba`, 4 bytes per pixel (red, green, blue, alpha, not
    /// premultiplied, as `ImageData.data`), rows from the top, shown for `delay_ms`
    /// milliseconds (in [`DELAY_MS_RANGE`]). Refuses a buffer of the wrong length, a delay
    /// out of range, or a frame past the memory limit, leaving the encoder as it was.
    pub fn add_frame(&mut self, rgba: &[u8], delay_ms: u32) -> Result<(), AnimationError> {
        let frame = self.frames;
        if !DELAY_MS_RANGE.contains(&delay_ms) {
            return Err(AnimationError::Delay { frame, delay_ms: delay_ms.into() });
        }
        // Within max_pixels (a usize), so 4 w h fits a u64 and, as a length, a usize.
        let expected = 4 * u64::from(self.width) * u64::from(self.height);
        if rgba.len() as u64 != expected {
            return Err(AnimationError::FrameLength { frame, expected: expected as usize, found: rgba.len() });
        }
        let total = self.rgba_bytes + expected;
        if total > self.max_bytes {
            return Err(AnimationError::TooLarge {
                what: "the animation's frames",
                size: total,
                limit: self.max_bytes,
                unit: "bytes of RGBA (4 per pixel per frame)",
            });
        }
        match &mut self.inner {
            Inner::Gif { encoder, elapsed_ms, written_cs } => {
                let mut pixels = rgba.to_vec();
                for pixel in pixels.as_chunks_mut::<4>().0 {
                    pixel[3] = if pixel[3] < 128 { 0 } else { 255 };
                }
                // The size fits u16 (checked in `new`), the speed is in 1..=30, the length
                // is 4 w h: nothing here can panic.
                let mut gif_frame =
                    gif::Frame::from_rgba_speed(self.width as u16, self.height as u16, &mut pixels, GIF_SPEED);
                let end_ms = *elapsed_ms + u64::from(delay_ms);
                let end_cs = (end_ms + 5) / 10;
                let cs = end_cs.saturating_sub(*written_cs).clamp(GIF_MIN_DELAY_CS.into(), u16::MAX.into());
                gif_frame.delay = cs as u16;
                gif_frame.dispose = gif::DisposalMethod::Background;
                encoder.write_frame(&gif_frame).map_err(encoder_error)?;
                *elapsed_ms = end_ms;
                *written_cs += cs;
            }
            Inner::Apng { header, frames } => {
                let (ihdr, data) = compress_png(self.width, self.height, rgba)?;
                if header.is_empty() {
                    *header = ihdr;
                }
                // DELAY_MS_RANGE ends at u16::MAX.
                frames.push(ApngFrame { data, delay_ms: delay_ms as u16 });
            }
        }
        self.rgba_bytes = total;
        self.frames += 1;
        Ok(())
    }

    /// The file's bytes. Refuses an animation without frames.
    pub fn finish(self) -> Result<Vec<u8>, AnimationError> {
        if self.frames == 0 {
            return Err(AnimationError::NoFrames);
        }
        match self.inner {
            Inner::Gif { encoder, .. } => encoder.into_inner().map_err(encoder_error),
            Inner::Apng { header, frames } => {
                Ok(write_apng(&header, frames, self.width, self.height, self.loop_forever))
            }
        }
    }
}

/// One frame as a PNG of its own (RGBA, 8 bits, `png`'s fast compression with adaptive
/// filters): its `IHDR` data and its `IDAT` chunks' data.
fn compress_png(width: u32, height: u32, rgba: &[u8]) -> Result<(Vec<u8>, Vec<Vec<u8>>), AnimationError> {
    let mut file = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut file, width, height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Fast);
        let mut writer = encoder.write_header().map_err(encoder_error)?;
        writer.write_image_data(rgba).map_err(encoder_error)?;
        writer.finish().map_err(encoder_error)?;
    }
    let mut header = Vec::new();
    let mut data = Vec::new();
    let mut at = 8;
    while at + 12 <= file.len() {
        let length = u32::from_be_bytes([file[at], file[at + 1], file[at + 2], file[at + 3]]) as usize;
        let kind = &file[at + 4..at + 8];
        let Some(body) = file.get(at + 8..at + 8 + length) else { break };
        match kind {
            b"IHDR" => header = body.to_vec(),
            b"IDAT" => data.push(body.to_vec()),
            _ => {}
        }
        at += 12 + length;
    }
    if header.len() != 13 || data.is_empty() {
        return Err(AnimationError::Encoder { message: "the PNG encoder wrote no image data".into() });
    }
    Ok((header, data))
}

/// Appends a PNG chunk: length, type, data, CRC-32 of type and data.
fn chunk(out: &mut Vec<u8>, kind: &[u8; 4], data: &[u8]) {
    out.extend_from_slice(&(data.len() as u32).to_be_bytes());
    out.extend_from_slice(kind);
    out.extend_from_slice(data);
    let crc = super::zip::crc32_update(super::crc32(kind), data);
    out.extend_from_slice(&crc.to_be_bytes());
}

/// The APNG file: signature, `IHDR`, `acTL`, per frame `fcTL` and `IDAT` or `fdAT`s,
/// `IEND`. Frames are dropped as they are copied, so the file and the frames are not all
/// held twice.
fn write_apng(header: &[u8], frames: Vec<ApngFrame>, width: u32, height: u32, loop_forever: bool) -> Vec<u8> {
    let data_bytes: usize = frames.iter().flat_map(|f| &f.data).map(|d| d.len() + 16).sum();
    let mut out = Vec::with_capacity(8 + 25 + 20 + 38 * frames.len() + data_bytes + 12);
    out.extend_from_slice(b"\x89PNG\r\n\x1a\n");
    chunk(&mut out, b"IHDR", header);
    let mut actl = Vec::with_capacity(8);
    actl.extend_from_slice(&(frames.len() as u32).to_be_bytes());
    actl.extend_from_slice(&u32::from(!loop_forever).to_be_bytes()); // plays: 0 = forever
    chunk(&mut out, b"acTL", &actl);
    let mut sequence: u32 = 0;
    for (index, frame) in frames.into_iter().enumerate() {
        let mut fctl = Vec::with_capacity(26);
        for value in [sequence, width, height, 0, 0] {
            fctl.extend_from_slice(&value.to_be_bytes());
        }
        fctl.extend_from_slice(&frame.delay_ms.to_be_bytes());
        fctl.extend_from_slice(&1000u16.to_be_bytes());
        fctl.extend_from_slice(&[0, 0]); // dispose: none; blend: source
        chunk(&mut out, b"fcTL", &fctl);
        sequence += 1;
        for data in frame.data {
            if index == 0 {
                chunk(&mut out, b"IDAT", &data);
            } else {
                let mut fdat = Vec::with_capacity(4 + data.len());
                fdat.extend_from_slice(&sequence.to_be_bytes());
                fdat.extend_from_slice(&data);
                chunk(&mut out, b"fdAT", &fdat);
                sequence += 1;
            }
        }
    }
    chunk(&mut out, b"IEND", &[]);
    out
}
