//! Raster images to outlines. The page decodes the image (PNG, JPEG, WebP) and hands over
//! RGBA pixels, row by row from the top.
//!
//! A pixel belongs to the shape when its alpha reaches a threshold, or, for an opaque
//! image, when its colour is far enough from the background (the corners' colour).
//! Marching squares traces the contours of that field through the pixel centres,
//! interpolating between neighbouring values, so anti-aliased edges give sub-pixel
//! outlines. Contours are simplified to a tolerance without letting them cross (see
//! `simplify`), tiny specks and holes are dropped, and each separate part becomes its own
//! outline, largest first.
//!
//! Output coordinates are pixels with y up: the image's bottom-left corner is the origin
//! and its top-right corner is `(width, height)`. [`crate::import::warp::texture_coordinates`]
//! maps them to texture coordinates.

use std::collections::HashMap;

use crate::geometry::{orient, polygon_area, Point};
use crate::import::regions::{assemble, RegionError, SourceRing};
use crate::import::simplify::simplify_rings;
use crate::import::vector::FillRule;
use crate::import::{ImportError, Limits};
use crate::outline::Outline;
use crate::sweep::{sweep, Find};

/// Which pixels belong to the shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MaskMode {
    /// Alpha when the image's corners are transparent (below the alpha threshold), colour
    /// otherwise.
    #[default]
    Auto,
    /// Pixels whose alpha reaches the alpha threshold.
    Alpha,
    /// Pixels whose colour is at least the colour threshold away from the background, the
    /// colour of the corners (the one closest to the other three).
    Colour,
}

/// Options of [`trace_image`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TraceOptions {
    /// How the shape is told from the background.
    pub mode: MaskMode,
    /// Alpha (0 to 255) from which a pixel belongs to the shape; above 0.
    pub alpha_threshold: f64,
    /// Distance in RGB (0 to 255 per channel, Euclidean) from the background colour from
    /// which a pixel belongs to the shape; above 0.
    pub colour_threshold: f64,
    /// Largest distance, in pixels, between a traced contour and its simplified outline.
    pub tolerance: f64,
    /// Parts and holes with a smaller area, in square pixels, are dropped (holes filled).
    pub min_area: f64,
    /// Size limits.
    pub limits: Limits,
}

impl Default for TraceOptions {
    fn default() -> Self {
        Self {
            mode: MaskMode::Auto,
            alpha_threshold: 128.0,
            colour_threshold: 48.0,
            tolerance: 0.75,
            min_area: 12.0,
            limits: Limits::default(),
        }
    }
}

impl TraceOptions {
    fn validate(&self) -> Result<(), ImportError> {
        let check = |name, value: f64, ok: bool, expected| {
            if ok {
                Ok(())
            } else {
                Err(ImportError::InvalidOption { name, value, expected })
            }
        };
        let a = self.alpha_threshold;
        check("alphaThreshold", a, a > 0.0 && a <= 255.0, "a number above 0, at most 255")?;
        let c = self.colour_threshold;
        check("colourThreshold", c, c > 0.0 && c <= 442.0, "a number above 0, at most 442")?;
        let t = self.tolerance;
        check("tolerance", t, t.is_finite() && t >= 0.0, "a finite number, 0 or more")?;
        let m = self.min_area;
        check("minArea", m, m.is_finite() && m >= 0.0, "a finite number, 0 or more")?;
        self.limits.validate()
    }
}

/// Where the values of a field come from.
enum Values<'a> {
    /// An image's alpha.
    Alpha(&'a [u8]),
    /// An image's distance from a background colour.
    Colour(&'a [u8], [f64; 3]),
}

/// The scalar field marching squares contours: one value per pixel, inside from `level`
/// on; 0 outside the grid.
struct Field<'a> {
    values: Values<'a>,
    width: usize,
    height: usize,
    level: f64,
}

impl Field<'_> {
    /// The value at pixel `(x, y)` (y down); outside the image, 0 (background).
    fn value(&self, x: isize, y: isize) -> f64 {
        if x < 0 || y < 0 || x as usize >= self.width || y as usize >= self.height {
            return 0.0;
        }
        let i = y as usize * self.width + x as usize;
        match self.values {
            Values::Alpha(rgba) => f64::from(rgba[4 * i + 3]),
            Values::Colour(rgba, bg) => {
                // Composite over the background, then measure the distance from it.
                let px = &rgba[4 * i..4 * i + 4];
                let alpha = f64::from(px[3]) / 255.0;
                let d = |k: usize| alpha * (f64::from(px[k]) - bg[k]);
                (d(0).powi(2) + d(1).powi(2) + d(2).powi(2)).sqrt()
            }
        }
    }

    fn inside(&self, x: isize, y: isize) -> bool {
        self.value(x, y) >= self.level
    }

    /// Grid edge ids: the horizontal edge from sample `(x, y)` to `(x + 1, y)` and the
    /// vertical one from `(x, y)` to `(x, y + 1)`, for samples from -1 to the size.
    fn edge(&self, x: isize, y: isize, vertical: bool) -> u64 {
        let row = (self.width + 2) as u64;
        (((y + 1) as u64) * row + (x + 1) as u64) * 2 + u64::from(vertical)
    }

    /// Where the contour crosses an edge, in output coordinates (pixels, y up).
    fn crossing(&self, edge: u64) -> Point {
        let row = (self.width + 2) as u64;
        let vertical = edge % 2 == 1;
        let cell = edge / 2;
        let (x, y) = ((cell % row) as isize - 1, (cell / row) as isize - 1);
        let (x1, y1) = if vertical { (x, y + 1) } else { (x + 1, y) };
        let (v0, v1) = (self.value(x, y), self.value(x1, y1));
        // Kept off the samples themselves, so crossings on different edges never coincide.
        let t = ((self.level - v0) / (v1 - v0)).clamp(1e-3, 1.0 - 1e-3);
        let t = if t.is_nan() { 0.5 } else { t };
        let (px, py) = (x as f64 + 0.5 + t * (x1 - x) as f64, y as f64 + 0.5 + t * (y1 - y) as f64);
        [px, self.height as f64 - py]
    }
}

/// Traces the shape in an RGBA image (`width * height * 4` bytes, rows from the top) into
/// outlines in pixel units with y up, largest part first.
///
/// ```
/// use akap::import::raster::{trace_image, TraceOptions};
/// // A 20 x 10 transparent image with an opaque 10 x 6 block.
/// let (w, h) = (20, 10);
/// let mut rgba = vec![0u8; w * h * 4];
/// for y in 2..8 {
///     for x in 5..15 {
///         rgba[4 * (y * w + x) + 3] = 255;
///     }
/// }
/// // No simplification: marching squares cuts each corner by a quarter pixel diagonal.
/// let options = TraceOptions { tolerance: 0.0, ..TraceOptions::default() };
/// let outlines = trace_image(&rgba, w, h, &options)?;
/// assert_eq!(outlines.len(), 1);
/// assert!((outlines[0].area() - 60.0).abs() < 0.6);
/// # Ok::<(), akap::import::ImportError>(())
/// ```
pub fn trace_image(
    rgba: &[u8],
    width: usize,
    height: usize,
    options: &TraceOptions,
) -> Result<Vec<Outline>, ImportError> {
    options.validate()?;
    let limits = &options.limits;
    let pixels = width.saturating_mul(height);
    Limits::check(pixels, limits.max_pixels, "the image", "pixels")?;
    if pixels == 0 || pixels.checked_mul(4) != Some(rgba.len()) {
        return Err(ImportError::ImageSize { width, height, len: rgba.len() });
    }
    let background = match options.mode {
        MaskMode::Alpha => None,
        MaskMode::Colour => Some(corner_colour(rgba, width, height)),
        MaskMode::Auto => {
            let corners = corners(width, height);
            let transparent = corners.iter().filter(|&&i| f64::from(rgba[4 * i + 3]) < options.alpha_threshold).count();
            if transparent >= 2 {
                None
            } else {
                Some(corner_colour(rgba, width, height))
            }
        }
    };
    let field = match background {
        None => Field { values: Values::Alpha(rgba), width, height, level: options.alpha_threshold },
        Some(bg) => Field { values: Values::Colour(rgba, bg), width, height, level: options.colour_threshold },
    };
    contour_outlines(&field, options.tolerance, options.min_area, limits)
}

/// Outlines of a field: marching squares, specks dropped, rings simplified to `tolerance`
/// (pixels) without crossing, nested into parts. In pixel units, y up.
fn contour_outlines(
    field: &Field,
    tolerance: f64,
    min_area: f64,
    limits: &Limits,
) -> Result<Vec<Outline>, ImportError> {
    let max_points = limits.max_points;
    let segments = march(field, max_points.saturating_mul(CONTOUR_POINTS_PER_POINT))?;
    if segments.is_empty() {
        return Err(ImportError::EmptyImage);
    }
    let rings = link(field, &segments);
    // Specks (and holes that small) go before simplification.
    let rings: Vec<Vec<Point>> = rings
        .into_iter()
        .filter(|r| r.len() >= 3 && polygon_area(r).abs() >= min_area.max(f64::MIN_POSITIVE))
        .collect();
    let too_complex = ImportError::TooComplex { pairs: limits.max_segment_pairs };
    // Contours never meet (each cell edge holds at most one contour point); if rounding
    // made two meet, simplification keeps every point of them and assembly reports it. The
    // marching limit bounds this sweep, O(n log n); the budget is for the rounds of
    // simplification.
    let found = sweep(&rings, Find::First, usize::MAX).expect("an unlimited sweep finishes");
    let parents = if found.meetings.is_empty() { found.parents } else { vec![None; rings.len()] };
    let simplified =
        simplify_rings(&rings, &parents, tolerance, limits.max_segment_pairs).ok_or(too_complex.clone())?;
    let count: usize = simplified.iter().map(Vec::len).sum();
    Limits::check(count, max_points, "the traced outline", "points")?;
    let sources: Vec<SourceRing> = simplified.into_iter().map(|points| SourceRing { points, shape: 0 }).collect();
    let outlines = match assemble(&sources, &[FillRule::NonZero], min_area, limits.max_segment_pairs) {
        Ok(outlines) => outlines,
        Err(RegionError::TooComplex) => return Err(too_complex),
        // Simplified contours never cross (simplify_rings checks), so this is not reached.
        Err(RegionError::Crossing(..)) => return Err(ImportError::EmptyImage),
    };
    if outlines.is_empty() {
        return Err(ImportError::EmptyImage);
    }
    Ok(outlines)
}

/// Pixel indices of the four corners.
fn corners(width: usize, height: usize) -> [usize; 4] {
    [0, width - 1, (height - 1) * width, height * width - 1]
}

/// The corner colour closest to the other three (so one odd corner does not count).
fn corner_colour(rgba: &[u8], width: usize, height: usize) -> [f64; 3] {
    let colours = corners(width, height).map(|i| [0, 1, 2].map(|k| f64::from(rgba[4 * i + k])));
    let spread = |c: &[f64; 3]| -> f64 {
        colours.iter().map(|o| ((c[0] - o[0]).powi(2) + (c[1] - o[1]).powi(2) + (c[2] - o[2]).powi(2)).sqrt()).sum()
    };
    colours.into_iter().min_by(|a, b| spread(a).total_cmp(&spread(b))).expect("four corners")
}

/// How many contour points (before simplification) tracing allows per outline point of
/// [`Limits::max_points`].
const CONTOUR_POINTS_PER_POINT: usize = 20;

/// Marching squares: directed segments between edge crossings, the shape on their left
/// (y up). Fails when there are more than `max_segments`.
fn march(field: &Field, max_segments: usize) -> Result<Vec<(u64, u64)>, ImportError> {
    let (w, h) = (field.width as isize, field.height as isize);
    let mut segments = Vec::new();
    // Inside flags of the previous and current sample rows, from x = -1 to w.
    let row = |y: isize| -> Vec<bool> { (-1..=w).map(|x| field.inside(x, y)).collect() };
    let mut upper = row(-1);
    for y in -1..h {
        let lower = row(y + 1);
        for x in -1..w {
            let i = (x + 1) as usize;
            let (a, b, c, d) = (upper[i], upper[i + 1], lower[i + 1], lower[i]);
            if a == b && b == c && c == d {
                continue;
            }
            // Corner positions (y up) and the edges between them: top, right, bottom, left.
            let corner = |dx: isize, dy: isize| [(x + dx) as f64 + 0.5, field.height as f64 - ((y + dy) as f64 + 0.5)];
            let edges = [
                (field.edge(x, y, false), a != b),
                (field.edge(x + 1, y, true), b != c),
                (field.edge(x, y + 1, false), c != d),
                (field.edge(x, y, true), d != a),
            ];
            let crossed: Vec<usize> = (0..4).filter(|&k| edges[k].1).collect();
            // The corner between edges k and k + 1 (top-right is b, and so on); edge 3 and
            // edge 0 share corner a.
            let corners = [(corner(1, 0), b), (corner(1, 1), c), (corner(0, 1), d), (corner(0, 0), a)];
            let pairs: Vec<(usize, usize)> = if crossed.len() == 2 {
                vec![(crossed[0], crossed[1])]
            } else {
                // Saddle: the centre value decides whether the inside corners connect.
                let centre = [(x, y), (x + 1, y), (x + 1, y + 1), (x, y + 1)]
                    .iter()
                    .map(|&(px, py)| field.value(px, py))
                    .sum::<f64>()
                    / 4.0;
                let connected = centre >= field.level;
                // Cut off the corners that are on the other side from the centre.
                let cut_b = b != connected;
                if cut_b {
                    vec![(0, 1), (2, 3)] // corners b and d
                } else {
                    vec![(1, 2), (3, 0)] // corners c and a
                }
            };
            for (e1, e2) in pairs {
                let (p, q) = (field.crossing(edges[e1].0), field.crossing(edges[e2].0));
                // A corner on one side only: the shared one for adjacent edges, else a's.
                let (k, inside) = if (e1 + 1) % 4 == e2 {
                    corners[e1]
                } else if (e2 + 1) % 4 == e1 {
                    corners[e2]
                } else {
                    corners[3]
                };
                let left = orient(p, q, k) > 0.0;
                segments.push(if left == inside { (edges[e1].0, edges[e2].0) } else { (edges[e2].0, edges[e1].0) });
            }
            if segments.len() > max_segments {
                return Err(ImportError::TooManyContourPoints { limit: max_segments / CONTOUR_POINTS_PER_POINT });
            }
        }
        upper = lower;
    }
    Ok(segments)
}

/// Links directed segments into closed rings of crossing points.
fn link(field: &Field, segments: &[(u64, u64)]) -> Vec<Vec<Point>> {
    let starting: HashMap<u64, usize> = segments.iter().enumerate().map(|(i, s)| (s.0, i)).collect();
    let mut used = vec![false; segments.len()];
    let mut rings = Vec::new();
    for first in 0..segments.len() {
        if used[first] {
            continue;
        }
        let mut ring = Vec::new();
        let mut s = first;
        while !used[s] {
            used[s] = true;
            ring.push(field.crossing(segments[s].0));
            match starting.get(&segments[s].1) {
                Some(&next) => s = next,
                None => break,
            }
        }
        rings.push(ring);
    }
    rings
}
