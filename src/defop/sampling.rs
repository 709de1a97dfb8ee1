//! Training samples for a deformation operator: handle targets `Q` drawn around the
//! handles' rest positions `P`, seeded and reproducible (the paper's Section 3.3 and Fig. 1).
//!
//! - [`Sampling::Disc`]: each target uniform (by area) in the disc of radius `r` around
//!   its handle's rest position, independently per handle.
//! - [`Sampling::Voronoi`]: each target uniform in its handle's Voronoi cell among the rest
//!   positions, clipped to the shape's bounding box grown by `r` (notes, section 2.2).
//! - [`Sampling::Mixed`]: each sample, all its targets from discs or all from cells, with
//!   probability one half each (Fig. 1).
//!
//! [`regions`] gives each handle's region (disc, cell or both), the one definition the
//! sampler draws from and the widget's Region view draws.
//!
//! The rest pose `Q = P` is not drawn: training always adds it as its first sample (its
//! ground truth is the rest mesh, exactly).

use crate::geometry::Point;
use crate::random::Rng;

/// Where targets are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Sampling {
    /// In discs around the handles.
    #[default]
    Disc,
    /// In the handles' Voronoi cells (clipped to the grown bounding box).
    Voronoi,
    /// Disc or Voronoi, one half each, per sample.
    Mixed,
}

/// The default disc radius as a fraction of the shape's bounding-box diagonal.
pub const DEFAULT_RADIUS_FRACTION: f64 = 0.15;

/// The most samples a training may ask for (a TPS operator holds one function per sample,
/// so operator files hold at most this many centres).
pub const MAX_SAMPLES: usize = 100_000;

/// Why a sampler cannot be made.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum SamplingError {
    /// There are no handles.
    NoHandles,
    /// A rest position or the box is not finite.
    NotFinite,
    /// The radius is not a positive finite number.
    Radius(f64),
    /// Two handles share a rest position: their Voronoi cells are not defined.
    CoincidentHandles {
        /// The first handle.
        first: usize,
        /// The second.
        second: usize,
    },
}

impl std::fmt::Display for SamplingError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::NoHandles => f.write_str("there are no handles to sample targets for"),
            Self::NotFinite => f.write_str("a handle's rest position or the shape's box is not finite"),
            Self::Radius(r) => write!(f, "the sampling radius is {r}, expected a positive finite number"),
            Self::CoincidentHandles { first, second } => {
                write!(f, "handles {first} and {second} are at the same rest position")
            }
        }
    }
}

impl std::error::Error for SamplingError {}

/// Where a sampling draws one handle's targets: the disc of radius `r` about its rest
/// position ([`Sampling::Disc`]), its Voronoi cell ([`Sampling::Voronoi`]), or either
/// ([`Sampling::Mixed`]). The one definition the [`Sampler`] draws from and a view draws.
#[derive(Debug, Clone, PartialEq)]
pub struct Region {
    /// The handle's rest position, the disc's centre.
    pub centre: Point,
    /// The disc's radius, for disc and mixed sampling.
    pub radius: Option<f64>,
    /// The Voronoi cell among the rest positions, clipped to the shape's bounding box grown
    /// by the radius (grown further to hold every handle), as a convex polygon
    /// counter-clockwise, for Voronoi and mixed sampling.
    pub cell: Option<Vec<Point>>,
}

impl Region {
    /// Whether the sampling may draw target `q` (in the disc or the cell, boundaries
    /// included).
    pub fn contains(&self, q: Point) -> bool {
        let in_disc = self.radius.is_some_and(|r| (q[0] - self.centre[0]).hypot(q[1] - self.centre[1]) <= r);
        let in_cell = self.cell.as_ref().is_some_and(|cell| {
            (0..cell.len()).all(|k| {
                let (a, b) = (cell[k], cell[(k + 1) % cell.len()]);
                (b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0]) >= 0.0
            })
        });
        in_disc || in_cell
    }
}

/// The region of each handle at `rest` in a shape whose bounding box is `bbox` (min, max)
/// for `sampling` with radius `radius`; refuses what [`Sampler::new`] refuses.
pub fn regions(
    rest: &[Point],
    bbox: [Point; 2],
    radius: f64,
    sampling: Sampling,
) -> Result<Vec<Region>, SamplingError> {
    if rest.is_empty() {
        return Err(SamplingError::NoHandles);
    }
    if !(radius.is_finite() && radius > 0.0) {
        return Err(SamplingError::Radius(radius));
    }
    let finite = |p: &Point| p[0].is_finite() && p[1].is_finite();
    if !rest.iter().chain(&bbox).all(finite) {
        return Err(SamplingError::NotFinite);
    }
    for (i, p) in rest.iter().enumerate() {
        if let Some(j) = rest[..i].iter().position(|q| q == p) {
            return Err(SamplingError::CoincidentHandles { first: j, second: i });
        }
    }
    let lo = [bbox[0][0].min(bbox[1][0]) - radius, bbox[0][1].min(bbox[1][1]) - radius];
    let hi = [bbox[0][0].max(bbox[1][0]) + radius, bbox[0][1].max(bbox[1][1]) + radius];
    // The box must hold every handle for each cell to be non-empty.
    let lo = rest.iter().fold(lo, |l, p| [l[0].min(p[0]), l[1].min(p[1])]);
    let hi = rest.iter().fold(hi, |h, p| [h[0].max(p[0]), h[1].max(p[1])]);
    let (discs, cells) = match sampling {
        Sampling::Disc => (true, false),
        Sampling::Voronoi => (false, true),
        Sampling::Mixed => (true, true),
    };
    Ok((0..rest.len())
        .map(|i| Region {
            centre: rest[i],
            radius: discs.then_some(radius),
            cell: cells.then(|| voronoi_cell(rest, i, lo, hi)),
        })
        .collect())
}

/// Draws handle targets around rest positions.
#[derive(Debug, Clone)]
pub struct Sampler {
    rest: Vec<Point>,
    radius: f64,
    sampling: Sampling,
    /// Each handle's Voronoi cell ([`regions`]) as a fan of triangles with cumulative
    /// areas (for [`Sampling::Voronoi`] and [`Sampling::Mixed`]; else empty).
    cells: Vec<Fan>,
    rng: Rng,
    seed: u64,
}

impl Sampler {
    /// A sampler for handles at `rest` in a shape whose bounding box is `bbox` (min, max),
    /// drawing each handle's targets uniformly (by area) from its [`regions`]: within
    /// `radius` (discs) or in the cells of the box grown by `radius`.
    pub fn new(
        rest: &[Point],
        bbox: [Point; 2],
        radius: f64,
        sampling: Sampling,
        seed: u64,
    ) -> Result<Self, SamplingError> {
        let cells = regions(rest, bbox, radius, sampling)?
            .iter()
            .filter_map(|region| region.cell.as_deref().map(Fan::of))
            .collect();
        Ok(Self { rest: rest.to_vec(), radius, sampling, cells, rng: Rng::new(seed), seed })
    }

    /// The number of handles.
    pub fn handle_count(&self) -> usize {
        self.rest.len()
    }

    /// The next sample: two coordinates per handle into `out` (`2 n` numbers).
    pub fn next_into(&mut self, out: &mut [f64]) {
        let mut rng = self.rng.clone();
        self.draw(&mut rng, out);
        self.rng = rng;
    }

    /// The sample named by `key`, whatever was drawn before: its own stream, seeded by the
    /// sampler's seed and the key, so that sample k of a training (key k, or a redraw's
    /// key) is the same whoever draws it and in whatever order.
    pub fn keyed_into(&self, key: u64, out: &mut [f64]) {
        let mut mix = Rng::new(self.seed ^ key.wrapping_mul(0x9E37_79B9_7F4A_7C15));
        let mut rng = Rng::new(mix.next_u64());
        self.draw(&mut rng, out);
    }

    fn draw(&self, rng: &mut Rng, out: &mut [f64]) {
        assert_eq!(out.len(), 2 * self.rest.len(), "two coordinates per handle");
        let voronoi = match self.sampling {
            Sampling::Disc => false,
            Sampling::Voronoi => true,
            Sampling::Mixed => rng.uniform() < 0.5,
        };
        for (l, p) in self.rest.iter().enumerate() {
            let q = if voronoi {
                self.cells[l].sample(rng)
            } else {
                let r = self.radius * rng.uniform().sqrt();
                let angle = std::f64::consts::TAU * rng.uniform();
                [p[0] + r * libm::cos(angle), p[1] + r * libm::sin(angle)]
            };
            out[2 * l] = q[0];
            out[2 * l + 1] = q[1];
        }
    }

    /// The next `count` samples, one after the other (`2 n count` numbers).
    pub fn take(&mut self, count: usize) -> Vec<f64> {
        let mut out = vec![0.0; 2 * self.rest.len() * count];
        for sample in out.chunks_exact_mut(2 * self.rest.len()) {
            self.next_into(sample);
        }
        out
    }
}

/// The cell of handle `i`: the box `[lo, hi]` cut by the half-planes nearer to `rest[i]` than
/// to each other handle (a convex polygon, counter-clockwise).
fn voronoi_cell(rest: &[Point], i: usize, lo: Point, hi: Point) -> Vec<Point> {
    let mut cell = vec![lo, [hi[0], lo[1]], hi, [lo[0], hi[1]]];
    let p = rest[i];
    for (j, q) in rest.iter().enumerate() {
        if j == i {
            continue;
        }
        // Keep x with (x - m) . (q - p) <= 0, m the midpoint.
        let n = [q[0] - p[0], q[1] - p[1]];
        let m = [0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])];
        let side = |x: &Point| (x[0] - m[0]) * n[0] + (x[1] - m[1]) * n[1];
        let mut clipped = Vec::with_capacity(cell.len() + 1);
        for (k, a) in cell.iter().enumerate() {
            let b = cell[(k + 1) % cell.len()];
            let (sa, sb) = (side(a), side(&b));
            if sa <= 0.0 {
                clipped.push(*a);
            }
            if (sa < 0.0 && sb > 0.0) || (sa > 0.0 && sb < 0.0) {
                let t = sa / (sa - sb);
                clipped.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
            }
        }
        cell = clipped;
    }
    cell
}

/// A convex polygon as a fan of triangles from its first corner, with cumulative areas.
#[derive(Debug, Clone)]
struct Fan {
    triangles: Vec<[Point; 3]>,
    cumulative: Vec<f64>,
}

impl Fan {
    fn of(polygon: &[Point]) -> Self {
        let mut fan = Self { triangles: Vec::new(), cumulative: Vec::new() };
        let mut total = 0.0;
        for k in 1..polygon.len().saturating_sub(1) {
            let t = [polygon[0], polygon[k], polygon[k + 1]];
            let area =
                0.5 * ((t[1][0] - t[0][0]) * (t[2][1] - t[0][1]) - (t[2][0] - t[0][0]) * (t[1][1] - t[0][1])).abs();
            total += area;
            fan.triangles.push(t);
            fan.cumulative.push(total);
        }
        fan
    }

    /// A point uniform in the polygon.
    fn sample(&self, rng: &mut Rng) -> Point {
        let total = *self.cumulative.last().expect("a cell holds its handle, so it has area");
        let pick = rng.uniform() * total;
        let k = self.cumulative.partition_point(|&c| c <= pick).min(self.triangles.len() - 1);
        let [a, b, c] = self.triangles[k];
        // Uniform in a triangle: fold the unit square's upper half onto the lower.
        let (mut u, mut v) = (rng.uniform(), rng.uniform());
        if u + v > 1.0 {
            (u, v) = (1.0 - u, 1.0 - v);
        }
        [a[0] + u * (b[0] - a[0]) + v * (c[0] - a[0]), a[1] + u * (b[1] - a[1]) + v * (c[1] - a[1])]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const REST: [Point; 3] = [[0.0, 0.0], [1.0, 0.0], [0.3, 0.8]];
    const BOX: [Point; 2] = [[-0.5, -0.5], [1.5, 1.5]];

    #[test]
    fn disc_samples_fill_the_discs_uniformly_and_repeat_with_the_seed() {
        let mut s = Sampler::new(&REST, BOX, 0.2, Sampling::Disc, 42).unwrap();
        let draws = s.take(20_000);
        let mut inner = 0;
        for q in draws.chunks_exact(6) {
            for (l, p) in REST.iter().enumerate() {
                let d = (q[2 * l] - p[0]).hypot(q[2 * l + 1] - p[1]);
                assert!(d <= 0.2 * (1.0 + 1e-12));
                inner += usize::from(l == 0 && d < 0.1);
            }
        }
        // Area-uniform: the inner disc of half the radius holds a quarter (sd ~0.003).
        let share = inner as f64 / 20_000.0;
        assert!((share - 0.25).abs() < 0.015, "{share}");
        let again = Sampler::new(&REST, BOX, 0.2, Sampling::Disc, 42).unwrap().take(20_000);
        assert_eq!(again, draws, "the same seed gives the same samples");
        let other = Sampler::new(&REST, BOX, 0.2, Sampling::Disc, 43).unwrap().take(1);
        assert_ne!(other[..], draws[..6]);
        // Keyed samples do not depend on what was drawn before, nor on the order.
        let (mut a, mut b, mut c) = ([0.0; 6], [0.0; 6], [0.0; 6]);
        s.keyed_into(5, &mut a);
        let fresh = Sampler::new(&REST, BOX, 0.2, Sampling::Disc, 42).unwrap();
        fresh.keyed_into(4, &mut c);
        fresh.keyed_into(5, &mut b);
        assert_eq!(a, b);
        assert_ne!(a, c);
        // And they fill the discs uniformly too.
        let inner = (0..20_000u64)
            .filter(|&k| {
                fresh.keyed_into(k, &mut a);
                (a[2] - REST[1][0]).hypot(a[3] - REST[1][1]) < 0.1
            })
            .count();
        assert!((inner as f64 / 20_000.0 - 0.25).abs() < 0.015, "{inner}");
    }

    #[test]
    fn voronoi_samples_are_nearest_their_handle_and_cover_the_cells_by_area() {
        let mut s = Sampler::new(&REST, BOX, 0.25, Sampling::Voronoi, 1).unwrap();
        let n = 30_000;
        let mut left_half = 0;
        for q in s.take(n).chunks_exact(6) {
            for l in 0..3 {
                let x = [q[2 * l], q[2 * l + 1]];
                let dist = |p: &Point| (x[0] - p[0]).hypot(x[1] - p[1]);
                assert!(REST.iter().all(|p| dist(&REST[l]) <= dist(p) + 1e-12), "{x:?} is not in cell {l}");
                assert!((-0.75..=1.75).contains(&x[0]) && (-0.75..=1.75).contains(&x[1]), "{x:?}");
                left_half += usize::from(l == 0 && x[0] < -0.25);
            }
        }
        // Cell 0 within [-0.75, 1.75]^2 is bounded by the bisectors x = 0.5 and
        // 0.3 x + 0.8 y = 0.365; its part with x < -0.25 is that strip below the second
        // bisector. Both areas by exact polygon clipping of the box here, independently:
        let area = |poly: &[Point]| {
            (0..poly.len())
                .map(|k| {
                    let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
                    a[0] * b[1] - b[0] * a[1]
                })
                .sum::<f64>()
                / 2.0
        };
        // y <= (0.365 - 0.3 x) / 0.8 and x <= 0.5 and the box.
        let bisector = |x: f64| (0.365 - 0.3 * x) / 0.8;
        let cell = [[-0.75, -0.75], [0.5, -0.75], [0.5, bisector(0.5)], [-0.75, bisector(-0.75)]];
        let strip = [[-0.75, -0.75], [-0.25, -0.75], [-0.25, bisector(-0.25)], [-0.75, bisector(-0.75)]];
        let expected = area(&strip) / area(&cell);
        let share = left_half as f64 / n as f64;
        assert!((share - expected).abs() < 0.015, "{share} vs {expected}");
    }

    #[test]
    fn regions_are_the_discs_and_the_cells_the_samples_come_from() {
        // Cell 0 within the box grown by 0.25, [-0.75, 1.75]^2: x <= 0.5 (the bisector with
        // handle 1) and 0.3 x + 0.8 y <= 0.365 (with handle 2), as in the test above.
        let bisector = |x: f64| (0.365 - 0.3 * x) / 0.8;
        let voronoi = regions(&REST, BOX, 0.25, Sampling::Voronoi).unwrap();
        assert_eq!(voronoi.len(), 3);
        assert_eq!((voronoi[0].centre, voronoi[0].radius), (REST[0], None));
        let cell = voronoi[0].cell.as_ref().unwrap();
        let expected = [[-0.75, -0.75], [0.5, -0.75], [0.5, bisector(0.5)], [-0.75, bisector(-0.75)]];
        assert_eq!(cell.len(), 4, "{cell:?}");
        for corner in expected {
            assert!(cell.iter().any(|c| (c[0] - corner[0]).hypot(c[1] - corner[1]) < 1e-12), "{corner:?} in {cell:?}");
        }
        // Inside a cell: in the grown box and nearest its handle (a grid over a larger box).
        for i in 0..=40 {
            for j in 0..=40 {
                let q = [-1.0 + 3.0 * f64::from(i) / 40.0 + 1e-3, -1.0 + 3.0 * f64::from(j) / 40.0 + 1e-3];
                let boxed = (-0.75..=1.75).contains(&q[0]) && (-0.75..=1.75).contains(&q[1]);
                let dist = |p: &Point| (q[0] - p[0]).hypot(q[1] - p[1]);
                for (l, region) in voronoi.iter().enumerate() {
                    let nearest = REST.iter().all(|p| dist(&REST[l]) <= dist(p));
                    assert_eq!(region.contains(q), boxed && nearest, "{q:?}, cell {l}");
                }
            }
        }
        // Discs: no cells; mixed: both, a point in either is in.
        let discs = regions(&REST, BOX, 0.25, Sampling::Disc).unwrap();
        assert!(discs.iter().all(|r| r.cell.is_none() && r.radius == Some(0.25)));
        assert!(discs[0].contains([0.0, 0.249]) && !discs[0].contains([0.0, 0.251]));
        let mixed = regions(&REST, BOX, 0.25, Sampling::Mixed).unwrap();
        assert_eq!(mixed[0].cell, voronoi[0].cell);
        assert_eq!(mixed[0].radius, Some(0.25));
        assert!(mixed[0].contains([-0.7, -0.7]) && !discs[0].contains([-0.7, -0.7]));
        // (0.45, 0) is within 0.6 of handle 1 but nearer handle 0: in disc 1, in cell 0.
        let [mixed, voronoi] = [Sampling::Mixed, Sampling::Voronoi].map(|s| regions(&REST, BOX, 0.6, s).unwrap());
        assert!(
            mixed[1].contains([0.45, 0.0]) && !voronoi[1].contains([0.45, 0.0]) && voronoi[0].contains([0.45, 0.0])
        );
        assert_eq!(regions(&REST, BOX, -1.0, Sampling::Disc).unwrap_err(), SamplingError::Radius(-1.0));
    }

    #[test]
    fn mixed_draws_both_kinds_and_bad_input_is_refused() {
        let mut s = Sampler::new(&REST, BOX, 0.05, Sampling::Mixed, 3).unwrap();
        let far = s.take(2000).chunks_exact(6).filter(|q| (q[0] - REST[0][0]).hypot(q[1] - REST[0][1]) > 0.05).count();
        // Half from cells, whose points lie beyond the small disc almost always.
        assert!((800..1200).contains(&far), "{far}");
        assert_eq!(Sampler::new(&[], BOX, 0.1, Sampling::Disc, 0).unwrap_err(), SamplingError::NoHandles);
        assert_eq!(Sampler::new(&REST, BOX, 0.0, Sampling::Disc, 0).unwrap_err(), SamplingError::Radius(0.0));
        let twice = [REST[0], REST[1], REST[0]];
        assert_eq!(
            Sampler::new(&twice, BOX, 0.1, Sampling::Voronoi, 0).unwrap_err(),
            SamplingError::CoincidentHandles { first: 0, second: 2 }
        );
        let nan = [[f64::NAN, 0.0]];
        assert_eq!(Sampler::new(&nan, BOX, 0.1, Sampling::Disc, 0).unwrap_err(), SamplingError::NotFinite);
    }
}
