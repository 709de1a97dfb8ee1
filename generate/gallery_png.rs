//! Writes the gallery's textured image, `www/gallery/pip.png`: Pip, a round blob with a
//! striped and spotted skin and two eye holes, on a transparent background, anti-aliased
//! by 4 x 4 supersampling. Deterministic: running it again gives the same file.
//!
//! ```text
//! cargo run --example gallery_png [-- OUTPUT]
//! ```

#[cfg(not(target_arch = "wasm32"))]
mod pip {
    use std::f64::consts::TAU;
    use std::fs::File;
    use std::io::BufWriter;

    pub(crate) const SIZE: usize = 256;

    /// Whether a point (pixels, y down) is part of Pip: a wobbly disc with two feet, minus
    /// two eyes.
    fn inside(x: f64, y: f64) -> bool {
        let (dx, dy) = (x - 128.0, y - 124.0);
        let angle = dy.atan2(dx);
        let radius = 92.0 + 7.0 * (3.0 * angle).sin() + 4.0 * (5.0 * angle + 1.0).cos();
        let body = dx.hypot(dy) < radius;
        let foot = |cx: f64| ((x - cx) / 26.0).powi(2) + ((y - 218.0) / 14.0).powi(2) < 1.0;
        let eye = |cx: f64| ((x - cx) / 11.0).powi(2) + ((y - 104.0) / 15.0).powi(2) < 1.0;
        (body || foot(92.0) || foot(164.0)) && !eye(100.0) && !eye(156.0)
    }

    /// The skin's colour at a point: a warm vertical gradient, diagonal stripes and spots.
    fn colour(x: f64, y: f64) -> [f64; 3] {
        let t = y / SIZE as f64;
        let mut c = [255.0 - 40.0 * t, 196.0 - 90.0 * t, 70.0 + 40.0 * t];
        let stripe = ((x + y) / 22.0 * TAU).sin();
        if stripe > 0.55 {
            c = [c[0] * 0.78, c[1] * 0.62, c[2] * 0.9];
        }
        let (sx, sy) = ((x / 40.0).fract() - 0.5, ((y + 20.0 * (x / 40.0).floor()) / 40.0).fract() - 0.5);
        if sx.hypot(sy) < 0.17 {
            c = [90.0, 170.0, 220.0];
        }
        c
    }

    pub(crate) fn pixels() -> Vec<u8> {
        let mut rgba = vec![0u8; SIZE * SIZE * 4];
        const SS: usize = 4;
        for py in 0..SIZE {
            for px in 0..SIZE {
                let mut hits = 0;
                for i in 0..SS {
                    for j in 0..SS {
                        let (x, y) =
                            (px as f64 + (i as f64 + 0.5) / SS as f64, py as f64 + (j as f64 + 0.5) / SS as f64);
                        hits += usize::from(inside(x, y));
                    }
                }
                let c = colour(px as f64 + 0.5, py as f64 + 0.5);
                let alpha = (255.0 * hits as f64 / (SS * SS) as f64).round() as u8;
                let k = 4 * (py * SIZE + px);
                rgba[k..k + 4].copy_from_slice(&[c[0] as u8, c[1] as u8, c[2] as u8, alpha]);
            }
        }
        rgba
    }

    pub(crate) fn main() -> std::io::Result<()> {
        let path = std::env::args().nth(1).unwrap_or_else(|| "www/gallery/pip.png".to_string());
        let mut encoder = png::Encoder::new(BufWriter::new(File::create(&path)?), SIZE as u32, SIZE as u32);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::High);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(&pixels())?;
        writer.finish()?;
        println!("wrote {path}");
        Ok(())
    }
}

#[cfg(not(target_arch = "wasm32"))]
fn main() -> std::io::Result<()> {
    pip::main()
}

#[cfg(target_arch = "wasm32")]
fn main() {}
