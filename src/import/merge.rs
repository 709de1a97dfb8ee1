//! Merging filled shapes whose boundaries cross or touch (an arm drawn over a body, a
//! figure-eight path), where nesting by containment cannot decide what is filled.
//!
//! The union of the shapes, each under its own fill rule, is scan-converted onto a fine
//! grid with exact horizontal coverage and several scanlines per pixel row, and the
//! coverage is contoured like an image (marching squares, interpolated, then simplified
//! without crossings). The result follows the true boundary to a small fraction of a grid
//! cell plus the simplification tolerance; vertices no longer sit exactly on the input's.

use crate::geometry::{bounding_box, Point};
use crate::import::raster::{contour_outlines, Field, Values};
use crate::import::regions::SourceRing;
use crate::import::vector::FillRule;
use crate::import::{ImportError, Limits};
use crate::outline::Outline;

/// Grid cells along the drawing's longer side, at most.
pub(crate) const MAX_CELLS_ACROSS: f64 = 1024.0;

/// Scanlines per grid row.
const SCANLINES: usize = 4;

/// One non-horizontal edge of a ring.
struct Edge {
    shape: usize,
    a: Point,
    b: Point,
    /// +1 when the edge runs towards larger y, else -1.
    direction: i32,
}

/// The outlines of the union of the shapes (`rings[i].shape` indexes `rules`), with curves
/// already flattened. `tolerance` bounds the simplification; parts and holes below
/// `min_area` are dropped. In the rings' coordinates, largest part first.
pub(crate) fn merge(
    rings: &[SourceRing],
    rules: &[FillRule],
    tolerance: f64,
    min_area: f64,
    limits: &Limits,
) -> Result<Vec<Outline>, ImportError> {
    let Some((lo, hi)) = bounding_box(rings.iter().flat_map(|r| r.points.iter().copied())) else {
        return Ok(Vec::new());
    };
    let size = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    if size.is_nan() || size <= 0.0 {
        return Ok(Vec::new());
    }
    // Cells: fine enough for the tolerance, at most MAX_CELLS_ACROSS across, and within
    // the pixel limit.
    let mut cell = (tolerance / 2.0).max(size / MAX_CELLS_ACROSS);
    let dims = |cell: f64| (((hi[0] - lo[0]) / cell).ceil() as usize + 4, ((hi[1] - lo[1]) / cell).ceil() as usize + 4);
    let (mut width, mut height) = dims(cell);
    if width.saturating_mul(height) > limits.max_pixels {
        cell *= ((width * height) as f64 / limits.max_pixels.max(16) as f64).sqrt() * 1.01;
        (width, height) = dims(cell);
    }
    let (x0, top) = (lo[0] - 2.0 * cell, hi[1] + 2.0 * cell);

    // Edges bucketed by the grid rows they span (row 0 at the top).
    let row_of = |y: f64| (((top - y) / cell).floor().max(0.0) as usize).min(height - 1);
    let mut edges = Vec::new();
    let mut rows: Vec<Vec<u32>> = vec![Vec::new(); height];
    for ring in rings {
        let n = ring.points.len();
        for i in 0..n {
            let (a, b) = (ring.points[i], ring.points[(i + 1) % n]);
            if a[1] == b[1] {
                continue;
            }
            let direction = if b[1] > a[1] { 1 } else { -1 };
            for bucket in &mut rows[row_of(a[1].max(b[1]))..=row_of(a[1].min(b[1]))] {
                bucket.push(edges.len() as u32);
            }
            edges.push(Edge { shape: ring.shape, a, b, direction });
        }
    }

    let mut coverage = vec![0f32; width * height];
    let mut winding = vec![0i32; rules.len()];
    let mut crossings: Vec<(f64, usize, i32)> = Vec::new();
    let weight = 1.0 / SCANLINES as f64;
    for (row, bucket) in rows.iter().enumerate() {
        let line = &mut coverage[row * width..(row + 1) * width];
        for s in 0..SCANLINES {
            let y = top - (row as f64 + (s as f64 + 0.5) * weight) * cell;
            crossings.clear();
            for &e in bucket {
                let Edge { shape, a, b, direction } = edges[e as usize];
                // Half-open in y, so a scanline through a vertex counts it once.
                if y >= a[1].min(b[1]) && y < a[1].max(b[1]) {
                    let x = a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
                    crossings.push((x, shape, direction));
                }
            }
            crossings.sort_by(|p, q| p.0.total_cmp(&q.0));
            // Sweep left to right: the union is filled where any shape fills.
            let mut filling = 0usize;
            let mut start = 0.0;
            for &(x, shape, direction) in &crossings {
                let rule = rules.get(shape).copied().unwrap_or_default();
                let before = rule.fills(winding[shape]);
                winding[shape] += direction;
                let after = rule.fills(winding[shape]);
                match (before, after) {
                    (false, true) => {
                        if filling == 0 {
                            start = x;
                        }
                        filling += 1;
                    }
                    (true, false) => {
                        filling -= 1;
                        if filling == 0 {
                            add_span(line, (start - x0) / cell, (x - x0) / cell, weight);
                        }
                    }
                    _ => {}
                }
            }
            // Closed rings bring every winding back to 0.
            for &(_, shape, _) in &crossings {
                winding[shape] = 0;
            }
        }
    }

    let field = Field { values: Values::Grid(&coverage), width, height, level: 0.5 };
    let pixels_tolerance = tolerance / (2.0 * cell);
    let outlines = match contour_outlines(&field, pixels_tolerance, min_area / (cell * cell), limits) {
        Ok(outlines) => outlines,
        Err(ImportError::EmptyImage) => return Ok(Vec::new()),
        Err(e) => return Err(e),
    };
    // From grid units (y up from the grid's bottom edge) back to the rings' coordinates.
    let bottom = top - height as f64 * cell;
    let back =
        |ring: &Vec<Point>| -> Vec<Point> { ring.iter().map(|p| [x0 + p[0] * cell, bottom + p[1] * cell]).collect() };
    Ok(outlines.iter().map(|o| Outline { outer: back(&o.outer), holes: o.holes.iter().map(back).collect() }).collect())
}

/// Adds coverage `weight` to the cells of a row under the span from `u0` to `u1` (in cell
/// units), partially covered cells in proportion.
fn add_span(line: &mut [f32], u0: f64, u1: f64, weight: f64) {
    let last = line.len() as f64;
    let (u0, u1) = (u0.clamp(0.0, last), u1.clamp(0.0, last));
    if u1 <= u0 {
        return;
    }
    let (i0, i1) = (u0.floor() as usize, u1.floor() as usize);
    if i0 == i1 {
        line[i0.min(line.len() - 1)] += ((u1 - u0) * weight) as f32;
        return;
    }
    line[i0] += ((i0 as f64 + 1.0 - u0) * weight) as f32;
    for cell in &mut line[i0 + 1..i1] {
        *cell += weight as f32;
    }
    if i1 < line.len() {
        line[i1] += ((u1 - i1 as f64) * weight) as f32;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: f64, y: f64, s: f64) -> Vec<Point> {
        vec![[x, y], [x + s, y], [x + s, y + s], [x, y + s]]
    }

    #[test]
    fn overlapping_squares_merge_into_their_union() {
        let rings = [
            SourceRing { points: square(0.0, 0.0, 2.0), shape: 0 },
            SourceRing { points: square(1.0, 1.0, 2.0), shape: 1 },
        ];
        let outlines = merge(&rings, &[FillRule::NonZero; 2], 0.002, 0.0, &Limits::default()).unwrap();
        assert_eq!(outlines.len(), 1);
        assert!(outlines[0].holes.is_empty());
        // Union area 7; the grid is 3/1024 per cell, and the traced corners are cut by a
        // small fraction of a cell.
        assert!((outlines[0].area() - 7.0).abs() < 0.01, "{}", outlines[0].area());
        outlines[0].validated(usize::MAX).unwrap();
    }

    #[test]
    fn a_figure_eight_fills_both_lobes_and_even_odd_overlaps_are_holes() {
        // Non-zero: both lobes of a bow tie are filled (winding +1 and -1). Where they meet
        // the trace may pinch them apart or keep a hairline neck; either way the area is 2
        // and the outlines are valid.
        let bow = [SourceRing { points: vec![[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 2.0]], shape: 0 }];
        let parts = merge(&bow, &[FillRule::NonZero], 0.002, 0.0, &Limits::default()).unwrap();
        let total: f64 = parts.iter().map(Outline::area).sum();
        assert!((total - 2.0).abs() < 0.01, "{total}");
        for part in &parts {
            part.validated(usize::MAX).unwrap();
        }
        // Even-odd within one path: two overlapping squares leave their overlap empty.
        let one = [
            SourceRing { points: square(0.0, 0.0, 2.0), shape: 0 },
            SourceRing { points: square(1.0, 1.0, 2.0), shape: 0 },
        ];
        let parts = merge(&one, &[FillRule::EvenOdd], 0.002, 0.0, &Limits::default()).unwrap();
        let total: f64 = parts.iter().map(Outline::area).sum();
        assert!((total - 6.0).abs() < 0.02, "{total}");
    }
}
