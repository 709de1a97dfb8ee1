//! Raster tracing on synthetic images with known areas and holes: discs, rectangles,
//! annuli, specks, colour backgrounds, noise; texture coordinates; bad input.

use std::f64::consts::PI;

use akap::geometry::{distance, Point};
use akap::import::raster::{trace_image, MaskMode, TraceOptions};
use akap::import::warp::texture_coordinates;
use akap::import::{ImportError, Limits};
use akap::{triangulate, Outline, TriangulationOptions};
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common::Rng;

/// An RGBA image whose alpha is the coverage of each pixel by a shape, sampled on an
/// `ss x ss` grid inside the pixel (`ss = 1`: the pixel centre only, a hard edge).
/// `inside` takes y-up coordinates (origin at the bottom-left corner), like the outlines.
fn coverage_image(w: usize, h: usize, ss: usize, inside: impl Fn(Point) -> bool) -> Vec<u8> {
    let mut rgba = vec![0u8; w * h * 4];
    for y in 0..h {
        for x in 0..w {
            let mut hits = 0;
            for i in 0..ss {
                for j in 0..ss {
                    let p =
                        [x as f64 + (i as f64 + 0.5) / ss as f64, h as f64 - (y as f64 + (j as f64 + 0.5) / ss as f64)];
                    hits += usize::from(inside(p));
                }
            }
            let alpha = (255.0 * hits as f64 / (ss * ss) as f64).round() as u8;
            rgba[4 * (y * w + x)..4 * (y * w + x) + 4].copy_from_slice(&[200, 40, 40, alpha]);
        }
    }
    rgba
}

fn options(tolerance: f64) -> TraceOptions {
    TraceOptions { tolerance, ..TraceOptions::default() }
}

fn disc(c: Point, r: f64) -> impl Fn(Point) -> bool {
    move |p| distance(p, c) < r
}

/// Every outline is valid and triangulates into one connected piece covering its area.
fn assert_triangulates(outlines: &[Outline]) {
    for outline in outlines {
        let mesh = triangulate(outline, &TriangulationOptions::default().with_target_edge_length(3.0)).unwrap();
        assert!((mesh.area() - outline.area()).abs() <= 1e-9 * outline.area());
        assert_eq!(mesh.connected_components(), 1);
    }
}

#[test]
fn hard_edged_disc_area_is_within_the_pixel_bound() {
    let (c, r) = ([50.0, 50.0], 30.0);
    let rgba = coverage_image(100, 100, 1, disc(c, r));
    for tolerance in [0.0, 0.5, 1.0] {
        let outlines = trace_image(&rgba, 100, 100, &options(tolerance)).unwrap();
        assert_eq!(outlines.len(), 1);
        assert!(outlines[0].holes.is_empty());
        // Contour crossings lie on segments between a pixel centre inside the disc and
        // one outside, so within one pixel of the circle; simplification adds at most the
        // tolerance. The area is off by at most the perimeter times that distance.
        let bound = 1.0 + tolerance;
        for p in &outlines[0].outer {
            assert!((distance(*p, c) - r).abs() <= bound, "{p:?}");
        }
        let area = outlines[0].area();
        assert!((area - PI * r * r).abs() <= 2.0 * PI * r * bound, "area {area} (tolerance {tolerance})");
        assert_triangulates(&outlines);
    }
}

#[test]
fn anti_aliased_disc_is_traced_to_sub_pixel_accuracy() {
    let (c, r) = ([40.3, 38.7], 25.0);
    let rgba = coverage_image(80, 80, 16, disc(c, r));
    let outlines = trace_image(&rgba, 80, 80, &options(0.0)).unwrap();
    // Interpolating coverage puts the contour within a small fraction of a pixel.
    for p in &outlines[0].outer {
        assert!((distance(*p, c) - r).abs() <= 0.1, "{p:?} is {} from the circle", distance(*p, c) - r);
    }
    let area = outlines[0].area();
    assert!((area - PI * r * r).abs() <= 2.0 * PI * r * 0.1, "{area}");
}

#[test]
fn rectangle_loses_only_its_corner_cuts() {
    // Pixels 10..50 x 5..25 opaque: a 40 x 20 rectangle. Marching squares runs through the
    // midpoints between pixel centres, i.e. along pixel edges (at 128/255 of the way for
    // the default threshold), and cuts each corner by a triangle of area 1/8.
    let rgba = coverage_image(60, 30, 1, |p| (10.0..50.0).contains(&p[0]) && (5.0..25.0).contains(&p[1]));
    let outlines = trace_image(&rgba, 60, 30, &options(0.0)).unwrap();
    let area = outlines[0].area();
    assert!((area - (800.0 - 0.5)).abs() < 0.25, "{area}");
    let simplified = trace_image(&rgba, 60, 30, &options(0.4)).unwrap();
    assert!(simplified[0].outer.len() <= 8, "{:?}", simplified[0].outer);
    assert!((simplified[0].area() - 800.0).abs() <= 120.0 * 0.4 + 0.5);
}

#[test]
fn annulus_keeps_its_hole() {
    let (c, r1, r2) = ([60.0, 60.0], 45.0, 20.0);
    let rgba = coverage_image(120, 120, 4, |p| (r2..r1).contains(&distance(p, c)));
    let outlines = trace_image(&rgba, 120, 120, &TraceOptions::default()).unwrap();
    assert_eq!(outlines.len(), 1);
    assert_eq!(outlines[0].holes.len(), 1);
    let expected = PI * (r1 * r1 - r2 * r2);
    let bound = 2.0 * PI * (r1 + r2) * (0.25 + TraceOptions::default().tolerance);
    assert!((outlines[0].area() - expected).abs() <= bound, "{} vs {expected}", outlines[0].area());
    assert_triangulates(&outlines);
}

#[test]
fn parts_islands_and_specks() {
    // A ring with an island in its hole, a second smaller disc, a 2 x 2 speck, and a
    // 2 x 2 hole in the second disc.
    let c = [40.0, 40.0];
    let rgba = coverage_image(120, 80, 1, |p| {
        let ring = (20.0..35.0).contains(&distance(p, c)) || distance(p, c) < 8.0;
        let second =
            distance(p, [95.0, 40.0]) < 15.0 && !((94.0..96.0).contains(&p[0]) && (39.0..41.0).contains(&p[1]));
        let speck = (100.0..102.0).contains(&p[0]) && (70.0..72.0).contains(&p[1]);
        ring || second || speck
    });
    let outlines = trace_image(&rgba, 120, 80, &TraceOptions::default()).unwrap();
    // Ring: pi (35^2 - 20^2) = 2592; second disc: pi 15^2 = 707 (its 4-pixel hole filled);
    // island: pi 8^2 = 201; the speck is gone. Areas within perimeter times (1 + tolerance).
    let expected = [
        (1, PI * (35.0f64.powi(2) - 400.0), 2.0 * PI * 55.0),
        (0, PI * 225.0, 2.0 * PI * 15.0),
        (0, PI * 64.0, 2.0 * PI * 8.0),
    ];
    assert_eq!(outlines.len(), 3);
    for (outline, (holes, area, perimeter)) in outlines.iter().zip(expected) {
        assert_eq!(outline.holes.len(), holes);
        assert!((outline.area() - area).abs() <= perimeter * 1.75, "{} vs {area}", outline.area());
    }
    assert_triangulates(&outlines);
    // With no speck filter, the speck and the small hole come back.
    let all = trace_image(&rgba, 120, 80, &TraceOptions { min_area: 0.0, ..TraceOptions::default() }).unwrap();
    assert_eq!(all.len(), 4);
    assert_eq!(all[1].holes.len(), 1);
}

#[test]
fn opaque_images_use_the_background_colour() {
    // White background, dark red disc, fully opaque: auto picks colour distance.
    let (w, h) = (64, 48);
    let mut rgba = vec![255u8; w * h * 4];
    for y in 0..h {
        for x in 0..w {
            if distance([x as f64 + 0.5, (h - y) as f64 - 0.5], [30.0, 24.0]) < 15.0 {
                rgba[4 * (y * w + x)..4 * (y * w + x) + 3].copy_from_slice(&[150, 0, 0]);
            }
        }
    }
    let auto = trace_image(&rgba, w, h, &TraceOptions::default()).unwrap();
    assert_eq!(auto.len(), 1);
    assert!((auto[0].area() - PI * 225.0).abs() <= 2.0 * PI * 15.0 * 1.75);
    let colour = trace_image(&rgba, w, h, &TraceOptions { mode: MaskMode::Colour, ..TraceOptions::default() }).unwrap();
    assert_eq!(auto, colour);
    // Alpha mode sees the whole opaque image as one rectangle.
    let alpha = trace_image(&rgba, w, h, &TraceOptions { mode: MaskMode::Alpha, ..TraceOptions::default() }).unwrap();
    assert_eq!(alpha.len(), 1);
    assert!((alpha[0].area() - (w * h) as f64).abs() <= 2.0 * (w + h) as f64 * 0.75);
}

#[test]
fn noise_gives_valid_outlines() {
    // Random blobs: whatever the contours, the outlines are valid (simplification never
    // makes rings cross or swap sides).
    let mut rng = Rng::new(7);
    for &(w, h, density) in &[(40, 30, 0.5), (64, 64, 0.3), (50, 20, 0.7)] {
        let mut rgba = vec![0u8; w * h * 4];
        for px in rgba.chunks_exact_mut(4) {
            px[3] = if rng.unit() < density { 255 } else { (rng.unit() * 100.0) as u8 };
        }
        for tolerance in [0.5, 2.0] {
            let options = TraceOptions { tolerance, min_area: 2.0, ..TraceOptions::default() };
            match trace_image(&rgba, w, h, &options) {
                Ok(outlines) => {
                    for outline in &outlines {
                        outline.validated(usize::MAX).unwrap();
                    }
                }
                Err(ImportError::EmptyImage) => {}
                Err(e) => panic!("{e}"),
            }
        }
    }
}

#[test]
fn texture_coordinates_map_the_image_onto_the_mesh() {
    // A disc below the image's middle (y up): mirrored top to bottom it would lie elsewhere.
    let (w, h) = (64, 32);
    let (centre, radius) = ([20.0, 10.0], 8.0);
    let rgba = coverage_image(w, h, 2, disc(centre, radius));
    let outlines = trace_image(&rgba, w, h, &TraceOptions::default()).unwrap();
    let mesh = triangulate(&outlines[0], &TriangulationOptions::default().with_target_edge_length(2.0)).unwrap();
    let uvs = texture_coordinates(mesh.positions(), w as f64, h as f64).unwrap();
    for (uv, p) in uvs.iter().zip(mesh.positions()) {
        assert!((0.0..=1.0).contains(&uv[0]) && (0.0..=1.0).contains(&uv[1]));
        // OBJ's convention: v up from the bottom row, so the pixel under (u, v) is column
        // u * w and row (1 - v) * h from the top; its centre in the traced frame (y up) is
        // within a pixel of the vertex, so near the disc.
        let (column, row) =
            ((uv[0] * w as f64).min(w as f64 - 1.0) as usize, ((1.0 - uv[1]) * h as f64).min(h as f64 - 1.0) as usize);
        let pixel_centre = [column as f64 + 0.5, h as f64 - (row as f64 + 0.5)];
        assert!(distance(pixel_centre, centre) < radius + 2.0, "{p:?} samples pixel ({column}, {row})");
    }
}

#[test]
fn bad_images_are_errors() {
    let rgba = vec![0u8; 4 * 6];
    let t = TraceOptions::default();
    assert_eq!(trace_image(&rgba, 3, 3, &t), Err(ImportError::ImageSize { width: 3, height: 3, len: 24 }));
    assert!(matches!(trace_image(&[], 0, 0, &t), Err(ImportError::ImageSize { .. })));
    assert_eq!(trace_image(&rgba, 3, 2, &t), Err(ImportError::EmptyImage));
    let small = TraceOptions { limits: Limits { max_pixels: 5, ..Limits::default() }, ..t };
    assert!(matches!(trace_image(&rgba, 3, 2, &small), Err(ImportError::TooLarge { what: "the image", .. })));
    assert!(matches!(trace_image(&rgba, usize::MAX, 2, &t), Err(ImportError::TooLarge { .. })));
    for bad in [
        TraceOptions { alpha_threshold: 0.0, ..t },
        TraceOptions { colour_threshold: f64::NAN, ..t },
        TraceOptions { tolerance: -1.0, ..t },
        TraceOptions { min_area: f64::INFINITY, ..t },
    ] {
        assert!(matches!(trace_image(&rgba, 3, 2, &bad), Err(ImportError::InvalidOption { .. })), "{bad:?}");
    }
    let message = trace_image(&rgba, 3, 3, &t).unwrap_err().to_string();
    assert_eq!(message, "a 3 x 3 image needs 36 bytes of RGBA pixels (4 per pixel), but 24 were given");
    // No pixels at all: said so, not "needs 0 bytes, but 0 were given".
    let message = trace_image(&[], 0, 0, &t).unwrap_err().to_string();
    assert_eq!(message, "the image is 0 x 0 pixels: it has no pixels (0 bytes were given)");
    let message = trace_image(&[], 5, 0, &t).unwrap_err().to_string();
    assert_eq!(message, "the image is 5 x 0 pixels: it has no pixels (0 bytes were given)");
    // Sizes whose byte count overflows a 32-bit usize are stated exactly.
    let wide = ImportError::ImageSize { width: 4_294_967_295, height: 2, len: 8 };
    assert_eq!(
        wide.to_string(),
        "a 4294967295 x 2 image needs 34359738360 bytes of RGBA pixels (4 per pixel), but 8 were given"
    );
    // An image tracing to more contour points than 20 times maxPoints says so in the
    // caller's numbers.
    let few = TraceOptions { limits: Limits { max_points: 3, ..Limits::default() }, ..t };
    let (w, h) = (64, 32);
    let noisy: Vec<u8> = (0..w * h).flat_map(|i| [0, 0, 0, if (i * 7919) % 13 < 6 { 255 } else { 0 }]).collect();
    let message = trace_image(&noisy, w, h, &few).unwrap_err().to_string();
    assert_eq!(
        message,
        "the image traces to contours of more than 60 points before simplification, 20 times the limit of 3 \
         outline points (maxPoints); raise maxPoints, or trace a smaller or simpler image"
    );
}
