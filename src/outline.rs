//! Shape outlines: an outer boundary with optional holes, and their validation.
//!
//! An [`Outline`] is what the user draws or imports; [`crate::triangulate()`] turns it into a
//! [`crate::Mesh`]. Validation happens here, before any triangulation: at least three
//! distinct points per ring, finite coordinates within [`MAX_COORDINATE`], a shape at least
//! [`MIN_EXTENT`] across, non-zero area, no ring crossing or touching itself or another
//! ring, every hole inside the outer boundary and outside the other holes. Crossings and
//! containment come from one sweep (`crate::sweep`), O(n log n) in the number of points.
//!
//! The checks are scale-invariant: they run on the points scaled by a power of two (exact),
//! and "touching" and "zero area" mean "to double precision" (within the rounding of the
//! computation, [`crate::geometry::certain_orient`]), never "small".

use std::fmt;

use crate::error_code::ErrorCode;
use crate::geometry::{
    bounding_box, normalising_exponent, polygon_area, scale_by_power_of_two, Point, MAX_COORDINATE, MIN_EXTENT,
};
use crate::message::Number;
use crate::sweep::{sweep, Find, Sweep};

/// A polygon with optional holes. Rings are closed implicitly (the last point connects to
/// the first) and may run in either direction.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Outline {
    /// The outer boundary.
    pub outer: Vec<Point>,
    /// Holes, each strictly inside the outer boundary.
    pub holes: Vec<Vec<Point>>,
}

/// Names a ring of an outline in errors: index 0 is the outer boundary, `k >= 1` is hole
/// `k - 1`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ring(pub usize);

impl fmt::Display for Ring {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            0 => write!(f, "the outer boundary"),
            k => write!(f, "hole {}", k - 1),
        }
    }
}

/// Why an outline cannot be triangulated.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum OutlineError {
    /// A ring has fewer than three distinct points.
    TooFewPoints {
        /// The ring.
        ring: Ring,
        /// How many distinct consecutive points it has.
        count: usize,
    },
    /// A point has a NaN or infinite coordinate.
    NonFinite {
        /// The ring.
        ring: Ring,
        /// The point's index in the ring as given.
        point: usize,
    },
    /// A flat `x y x y ...` ring has an odd number of values.
    OddLength {
        /// The ring.
        ring: Ring,
        /// How many numbers it has.
        len: usize,
    },
    /// A point has a coordinate larger in magnitude than [`MAX_COORDINATE`].
    CoordinateOutOfRange {
        /// The ring.
        ring: Ring,
        /// The point's index in the ring as given.
        point: usize,
        /// The coordinate.
        value: f64,
    },
    /// The outline is less than [`MIN_EXTENT`] across (both sides of its bounding box).
    TooSmall {
        /// The larger side of its bounding box.
        extent: f64,
    },
    /// A ring encloses no area to double precision: the shoelace sum is within its rounding
    /// error of zero.
    ZeroArea {
        /// The ring.
        ring: Ring,
    },
    /// Two segments cross, touch or overlap.
    SelfIntersection {
        /// Ring of the first segment.
        ring_a: Ring,
        /// Index of the first segment (from point `segment_a` to the next).
        segment_a: usize,
        /// Ring of the second segment.
        ring_b: Ring,
        /// Index of the second segment.
        segment_b: usize,
    },
    /// A hole is not inside the outer boundary.
    HoleOutside {
        /// The hole (`Ring(k)` is hole `k - 1`).
        hole: Ring,
    },
    /// A hole lies inside another hole.
    NestedHole {
        /// The inner hole.
        hole: Ring,
        /// The hole that contains it.
        container: Ring,
    },
    /// More points than the vertex limit allows.
    TooManyPoints {
        /// Points in the outline.
        count: usize,
        /// The limit.
        limit: usize,
    },
}

impl fmt::Display for OutlineError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TooFewPoints { ring, count } => {
                write!(f, "{ring} has {count} distinct points; a ring needs at least 3")
            }
            Self::NonFinite { ring, point } => {
                write!(f, "point {point} of {ring} has a coordinate that is not a finite number")
            }
            Self::OddLength { ring, len } => {
                write!(f, "{ring} has {len} numbers; it needs x, y pairs, an even number")
            }
            Self::CoordinateOutOfRange { ring, point, value } => write!(
                f,
                "point {point} of {ring} has the coordinate {}, beyond the limit of ±{MAX_COORDINATE:e}; \
                 scale the outline down",
                Number(*value)
            ),
            Self::TooSmall { extent } => write!(
                f,
                "the outline is only {extent:e} across, less than the smallest size of {MIN_EXTENT:e}; scale it up"
            ),
            Self::ZeroArea { ring } => write!(f, "{ring} encloses no area (to double precision)"),
            Self::SelfIntersection { ring_a, segment_a, ring_b, segment_b } => write!(
                f,
                "the outline intersects itself: segment {segment_a} of {ring_a} meets segment {segment_b} of {ring_b}"
            ),
            Self::HoleOutside { hole } => write!(f, "{hole} is not inside the outer boundary"),
            Self::NestedHole { hole, container } => write!(f, "{hole} lies inside {container}"),
            Self::TooManyPoints { count, limit } => {
                write!(f, "the outline has {count} points, more than the vertex limit of {limit}")
            }
        }
    }
}

impl std::error::Error for OutlineError {}

impl OutlineError {
    /// The kind of error: [`ErrorCode::Limit`] for too many points, otherwise
    /// [`ErrorCode::InvalidOutline`].
    pub fn code(&self) -> ErrorCode {
        match self {
            Self::TooManyPoints { .. } => ErrorCode::Limit,
            _ => ErrorCode::InvalidOutline,
        }
    }
}

impl Outline {
    /// An outline without holes.
    pub fn new(outer: Vec<Point>) -> Self {
        Self { outer, holes: Vec::new() }
    }

    /// Adds a hole.
    pub fn with_hole(mut self, hole: Vec<Point>) -> Self {
        self.holes.push(hole);
        self
    }

    /// Builds an outline from flat `x y x y ...` arrays (the JavaScript layout).
    pub fn from_flat(outer: &[f64], holes: &[Vec<f64>]) -> Result<Self, OutlineError> {
        let ring = |k: usize, flat: &[f64]| -> Result<Vec<Point>, OutlineError> {
            if !flat.len().is_multiple_of(2) {
                return Err(OutlineError::OddLength { ring: Ring(k), len: flat.len() });
            }
            Ok(flat.chunks_exact(2).map(|p| [p[0], p[1]]).collect())
        };
        Ok(Self {
            outer: ring(0, outer)?,
            holes: holes.iter().enumerate().map(|(k, h)| ring(k + 1, h)).collect::<Result<_, _>>()?,
        })
    }

    /// All rings, the outer one first.
    pub fn rings(&self) -> impl Iterator<Item = &[Point]> {
        std::iter::once(self.outer.as_slice()).chain(self.holes.iter().map(Vec::as_slice))
    }

    /// Area enclosed: the outer boundary's minus the holes'.
    pub fn area(&self) -> f64 {
        polygon_area(&self.outer).abs() - self.holes.iter().map(|h| polygon_area(h).abs()).sum::<f64>()
    }

    /// Checks the outline and returns its rings with consecutive repeated points removed
    /// (the form the triangulator uses).
    pub fn validated(&self, max_points: usize) -> Result<Vec<Vec<Point>>, OutlineError> {
        let mut rings = Vec::with_capacity(1 + self.holes.len());
        for (k, ring) in self.rings().enumerate() {
            for (point, p) in ring.iter().enumerate() {
                if !(p[0].is_finite() && p[1].is_finite()) {
                    return Err(OutlineError::NonFinite { ring: Ring(k), point });
                }
                if let Some(&value) = p.iter().find(|x| x.abs() > MAX_COORDINATE) {
                    return Err(OutlineError::CoordinateOutOfRange { ring: Ring(k), point, value });
                }
            }
            let mut clean: Vec<Point> = Vec::with_capacity(ring.len());
            for &p in ring {
                if clean.last() != Some(&p) {
                    clean.push(p);
                }
            }
            while clean.len() > 1 && clean.first() == clean.last() {
                clean.pop();
            }
            if clean.len() < 3 {
                return Err(OutlineError::TooFewPoints { ring: Ring(k), count: clean.len() });
            }
            rings.push(clean);
        }
        let count: usize = rings.iter().map(Vec::len).sum();
        if count > max_points {
            return Err(OutlineError::TooManyPoints { count, limit: max_points });
        }
        let (lo, hi) = bounding_box(rings.iter().flatten().copied()).expect("rings have points");
        let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        if extent < MIN_EXTENT {
            return Err(OutlineError::TooSmall { extent });
        }
        // The checks run on the rings scaled by a power of two: exact, and the same at every scale.
        let k = normalising_exponent(rings.iter().flatten().copied());
        let scaled: Vec<Vec<Point>> =
            rings.iter().map(|r| r.iter().map(|p| p.map(|x| scale_by_power_of_two(x, k))).collect()).collect();
        // Crossings first: a figure-eight has zero signed area, but its problem is the crossing.
        let found = sweep(&scaled, Find::First, usize::MAX).expect("an unlimited sweep finishes");
        first_meeting(&found)?;
        for (k, ring) in scaled.iter().enumerate() {
            if !area_is_certain(ring) {
                return Err(OutlineError::ZeroArea { ring: Ring(k) });
            }
        }
        // Rings do not meet, so the sweep's containment tree is exact: a hole must have the
        // outer boundary as an ancestor (else it lies outside) and as its parent (else it
        // lies inside another hole).
        let mut top = vec![0; scaled.len()];
        for &r in &found.order {
            top[r] = found.parents[r].map_or(r, |p| top[p]);
        }
        for (k, &root) in top.iter().enumerate().skip(1) {
            if root != 0 {
                return Err(OutlineError::HoleOutside { hole: Ring(k) });
            }
            if let Some(c) = found.parents[k].filter(|&c| c != 0) {
                return Err(OutlineError::NestedHole { hole: Ring(k), container: Ring(c) });
            }
        }
        Ok(rings)
    }
}

/// Whether a ring's signed area is certainly not zero in double precision: twice the area is
/// the sum of `orient(p0, p_i, p_(i+1))`, each term's two products carry at most three
/// roundings of relative size `u = 2^-53` and the sum of `n` terms `n` more, so the computed
/// sum is within `(n + 4) u` times the sum of the products' magnitudes (plus `O(u^2)`) of the
/// exact one. Points scaled by a power of two first (no underflow).
fn area_is_certain(ring: &[Point]) -> bool {
    let p0 = ring[0];
    let (mut twice, mut magnitude) = (0.0, 0.0);
    for w in ring[1..].windows(2) {
        let t1 = (w[0][0] - p0[0]) * (w[1][1] - p0[1]);
        let t2 = (w[0][1] - p0[1]) * (w[1][0] - p0[0]);
        twice += t1 - t2;
        magnitude += t1.abs() + t2.abs();
    }
    let u = f64::EPSILON / 2.0;
    magnitude > 0.0 && twice.abs() > 1.01 * (ring.len() as f64 + 4.0) * u * magnitude
}

/// Rejects any two segments that meet, other than consecutive segments of one ring at
/// their shared point.
#[cfg(test)]
pub(crate) fn check_no_intersections(rings: &[Vec<Point>]) -> Result<(), OutlineError> {
    let found = sweep(rings, Find::First, usize::MAX).expect("an unlimited sweep finishes");
    first_meeting(&found)
}

fn first_meeting(found: &Sweep) -> Result<(), OutlineError> {
    match found.meetings.first() {
        Some(&[(ring_a, segment_a), (ring_b, segment_b)]) => {
            Err(OutlineError::SelfIntersection { ring_a: Ring(ring_a), segment_a, ring_b: Ring(ring_b), segment_b })
        }
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::segments_intersect;

    fn square(x: f64, y: f64, s: f64) -> Vec<Point> {
        vec![[x, y], [x + s, y], [x + s, y + s], [x, y + s]]
    }

    #[test]
    fn accepts_square_with_hole_and_drops_repeated_points() {
        let mut outer = square(0.0, 0.0, 10.0);
        outer.insert(1, outer[0]);
        outer.push(outer[0]);
        let outline = Outline::new(outer).with_hole(square(4.0, 4.0, 2.0));
        let rings = outline.validated(100).unwrap();
        assert_eq!(rings[0].len(), 4);
        assert_eq!(outline.area(), 96.0);
    }

    #[test]
    fn rejects_each_kind_of_bad_outline() {
        let bowtie = vec![[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 1.0]];
        let cases = [
            (Outline::new(vec![[0.0, 0.0], [1.0, 0.0]]), OutlineError::TooFewPoints { ring: Ring(0), count: 2 }),
            (
                Outline::new(vec![[0.0, 0.0], [f64::INFINITY, 0.0], [0.0, 1.0]]),
                OutlineError::NonFinite { ring: Ring(0), point: 1 },
            ),
            // Collinear to double precision: the last segment passes through (1, 1), folding
            // back onto the first.
            (
                Outline::new(vec![[0.0, 0.0], [1.0, 1.0], [3.0, 3.0 + 4.4e-16]]),
                OutlineError::SelfIntersection { ring_a: Ring(0), segment_a: 0, ring_b: Ring(0), segment_b: 2 },
            ),
            (
                Outline::new(vec![[0.0, 0.0], [1.0, 0.0], [f64::NAN, 1.0]]),
                OutlineError::NonFinite { ring: Ring(0), point: 2 },
            ),
            (
                Outline::new(vec![[0.0, 0.0], [1.0, 0.0], [0.0, -1.5e300]]),
                OutlineError::CoordinateOutOfRange { ring: Ring(0), point: 2, value: -1.5e300 },
            ),
            (Outline::new(vec![[0.0, 0.0], [1e-301, 0.0], [0.0, 2e-301]]), OutlineError::TooSmall { extent: 2e-301 }),
            (
                Outline::new(bowtie),
                OutlineError::SelfIntersection { ring_a: Ring(0), segment_a: 0, ring_b: Ring(0), segment_b: 2 },
            ),
            (
                Outline::new(square(0.0, 0.0, 10.0)).with_hole(square(20.0, 0.0, 1.0)),
                OutlineError::HoleOutside { hole: Ring(1) },
            ),
            (
                Outline::new(square(0.0, 0.0, 10.0)).with_hole(square(2.0, 2.0, 6.0)).with_hole(square(4.0, 4.0, 1.0)),
                OutlineError::NestedHole { hole: Ring(2), container: Ring(1) },
            ),
        ];
        for (outline, expected) in cases {
            assert_eq!(outline.validated(1000), Err(expected.clone()), "{expected}");
        }
        assert_eq!(
            Outline::new(square(0.0, 0.0, 1.0)).validated(3),
            Err(OutlineError::TooManyPoints { count: 4, limit: 3 })
        );
    }

    #[test]
    fn thin_and_tiny_or_huge_rings_are_valid_when_double_precision_tells_their_area() {
        // Area 5e-14 (exact: a product with zero has no rounding), angles of 2e-13 radians.
        let thin = Outline::new(vec![[0.0, 0.0], [1.0, 0.0], [0.5, 1e-13]]);
        assert!(thin.validated(10).is_ok());
        for s in [1e-300, 1e-150, 1e150, 1e300] {
            let square = Outline::new(square(-0.5 * s, -0.5 * s, s)).with_hole(square(-0.1 * s, -0.1 * s, 0.2 * s));
            assert!(square.validated(10).is_ok(), "at scale {s}");
        }
        // The shoelace sum 4.4e-16 of products of magnitude 6 is within its rounding error.
        assert!(!area_is_certain(&[[0.0, 0.0], [1.0, 1.0], [3.0, 3.0 + 4.4e-16]]));
        assert!(area_is_certain(&[[0.0, 0.0], [1.0, 0.0], [0.5, 1e-13]]));
        assert_eq!(
            Outline::from_flat(&[0.0, 0.0, 1.0, 0.0, 1.0], &[]),
            Err(OutlineError::OddLength { ring: Ring(0), len: 5 })
        );
    }

    #[test]
    fn reports_a_pair_of_segments_that_really_cross() {
        let outline = Outline::new(square(0.0, 0.0, 10.0)).with_hole(square(5.0, 5.0, 10.0));
        let Err(OutlineError::SelfIntersection { ring_a, segment_a, ring_b, segment_b }) = outline.validated(100)
        else {
            panic!("expected an intersection");
        };
        assert_ne!(ring_a, ring_b);
        let rings: Vec<&[Point]> = outline.rings().collect();
        let seg = |r: Ring, i: usize| (rings[r.0][i], rings[r.0][(i + 1) % rings[r.0].len()]);
        let ((a, b), (c, d)) = (seg(ring_a, segment_a), seg(ring_b, segment_b));
        assert!(segments_intersect(a, b, c, d));
    }

    #[test]
    fn collinear_ring_folds_back_on_itself() {
        let line = Outline::new(vec![[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]);
        assert!(matches!(line.validated(100), Err(OutlineError::SelfIntersection { .. })));
    }

    #[test]
    fn ring_folding_back_on_itself_is_an_intersection() {
        let spike = vec![[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [2.0, 3.0], [2.0, 1.0], [0.0, 2.0]];
        assert!(matches!(Outline::new(spike).validated(100), Err(OutlineError::SelfIntersection { .. })));
    }

    #[test]
    fn hole_touching_the_outer_boundary_is_an_intersection() {
        let outline = Outline::new(square(0.0, 0.0, 10.0)).with_hole(vec![[0.0, 5.0], [3.0, 4.0], [3.0, 6.0]]);
        assert!(matches!(outline.validated(100), Err(OutlineError::SelfIntersection { .. })));
    }
}
