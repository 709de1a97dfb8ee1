//! Times the animation encoders on 512 x 512 frames: GIF at NeuQuant speeds 1, 10 and 30
//! (the speed the encoder uses is `akap::animation::encode::GIF_SPEED`) and APNG.
//!
//! `cargo run --release --example encode_timing [FRAMES]`
//!
//! The frames are what the widget renders, roughly: a shaded shape (smooth gradients, far
//! more than 256 colours) moving over a transparent background.

use std::time::Instant;

use akap::animation::{AnimationEncoder, Format};

const SIZE: u32 = 512;

/// Frame `t`: a disc of gradients whose centre moves with `t`, transparent outside.
fn frame(t: u32) -> Vec<u8> {
    let mut rgba = vec![0u8; (4 * SIZE * SIZE) as usize];
    let (cx, cy) = (200.0 + 10.0 * t as f64, 256.0);
    for y in 0..SIZE {
        for x in 0..SIZE {
            let (dx, dy) = (x as f64 - cx, y as f64 - cy);
            let r = (dx * dx + dy * dy).sqrt();
            if r < 180.0 {
                let i = 4 * (y * SIZE + x) as usize;
                rgba[i] = (x * 255 / SIZE) as u8;
                rgba[i + 1] = (y * 255 / SIZE) as u8;
                rgba[i + 2] = (255.0 * (1.0 - r / 180.0)) as u8;
                rgba[i + 3] = 255;
            }
        }
    }
    rgba
}

/// NeuQuant's quality at `speed`: the mean absolute error per channel of frame 0 encoded
/// as a one-frame GIF and decoded.
fn gif_error(rgba: &[u8], speed: i32) -> f64 {
    let mut pixels = rgba.to_vec();
    let frame = gif::Frame::from_rgba_speed(SIZE as u16, SIZE as u16, &mut pixels, speed);
    let palette = frame.palette.as_ref().expect("a local palette");
    let mut sum = 0u64;
    let mut count = 0u64;
    for (p, &index) in rgba.chunks_exact(4).zip(frame.buffer.iter()) {
        if p[3] == 255 {
            for c in 0..3 {
                sum += u64::from(p[c].abs_diff(palette[3 * index as usize + c]));
                count += 1;
            }
        }
    }
    sum as f64 / count as f64
}

fn main() -> Result<(), akap::animation::AnimationError> {
    let frames: u32 = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(10);
    let rgba: Vec<Vec<u8>> = (0..frames).map(frame).collect();
    println!("{frames} frames of {SIZE} x {SIZE}");
    for speed in [1, 10, 30] {
        let start = Instant::now();
        for f in &rgba {
            let mut pixels = f.clone();
            let _ = gif::Frame::from_rgba_speed(SIZE as u16, SIZE as u16, &mut pixels, speed);
        }
        let ms = start.elapsed().as_secs_f64() * 1000.0 / f64::from(frames);
        println!(
            "GIF quantise, speed {speed:2}: {ms:7.1} ms a frame, mean error {:.2} levels",
            gif_error(&rgba[0], speed)
        );
    }
    for format in [Format::Gif, Format::Apng] {
        let start = Instant::now();
        let mut encoder = AnimationEncoder::new(format, SIZE, SIZE, true)?;
        for f in &rgba {
            encoder.add_frame(f, 40)?;
        }
        let bytes = encoder.finish()?;
        let ms = start.elapsed().as_secs_f64() * 1000.0 / f64::from(frames);
        println!("{} encoder: {ms:7.1} ms a frame, {} bytes a frame", format.name(), bytes.len() / frames as usize);
    }
    Ok(())
}
