//! Shape outlines: an outer boundary with optional holes, and their validation.
//!
//! An [`Outline`] is what the user draws or imports; [`crate::triangulate()`] turns it into a
//! [`crate::Mesh`]. Validation happens here, before any triangulation: at least three
//! distinct points per ring, finite coordinates, non-zero area, no ring crossing or touching
//! itself or another ring, every hole inside the outer boundary and outside the other holes.
//! Crossings and containment come from one sweep (`crate::sweep`), O(n log n) in the number
//! of points.

use std::fmt;

use crate::geometry::{bounding_box, polygon_area, Point};
use crate::sweep::{sweep, Find, Sweep};

/// Relative area below which a ring counts as having zero area (fraction of its squared
/// bounding-box diagonal).
const ZERO_AREA_RELATIVE: f64 = 1e-12;

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
    /// A ring encloses (numerically) no area.
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
            Self::ZeroArea { ring } => write!(f, "{ring} encloses no area"),
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

    /// Builds an outline from flat `x y x y ...` arrays (the JavaScript layout). An odd
    /// trailing coordinate is reported as a non-finite point.
    pub fn from_flat(outer: &[f64], holes: &[Vec<f64>]) -> Result<Self, OutlineError> {
        let ring = |k: usize, flat: &[f64]| -> Result<Vec<Point>, OutlineError> {
            if !flat.len().is_multiple_of(2) {
                return Err(OutlineError::NonFinite { ring: Ring(k), point: flat.len() / 2 });
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
            if let Some(point) = ring.iter().position(|p| !p[0].is_finite() || !p[1].is_finite()) {
                return Err(OutlineError::NonFinite { ring: Ring(k), point });
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
        // Crossings first: a figure-eight has zero signed area, but its problem is the crossing.
        let found = sweep(&rings, Find::First, usize::MAX).expect("an unlimited sweep finishes");
        first_meeting(&found)?;
        for (k, ring) in rings.iter().enumerate() {
            let (lo, hi) = bounding_box(ring.iter().copied()).expect("ring has points");
            let diagonal2 = (hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2);
            if polygon_area(ring).abs() <= ZERO_AREA_RELATIVE * diagonal2 {
                return Err(OutlineError::ZeroArea { ring: Ring(k) });
            }
        }
        // Rings do not meet, so the sweep's containment tree is exact: a hole must have the
        // outer boundary as an ancestor (else it lies outside) and as its parent (else it
        // lies inside another hole).
        let mut top = vec![0; rings.len()];
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
            (Outline::new(vec![[0.0, 0.0], [1.0, 0.0], [0.5, 1e-13]]), OutlineError::ZeroArea { ring: Ring(0) }),
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
