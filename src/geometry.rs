//! Small planar geometry helpers shared by the outline checks, the mesh and the tests.
//!
//! Points are `[x, y]` arrays of `f64`. Orientation follows the usual convention: positive
//! signed area means counter-clockwise. Two predicates, for two jobs:
//!
//! - [`orientation`] decides the sign exactly (a floating-point filter, then exact expansion
//!   arithmetic when the filter cannot tell, as in Shewchuk's adaptive predicates): it orders
//!   the segments of the outline checks' sweep (`crate::sweep`), which must be consistent;
//! - [`certain_orient`] gives the sign only when double precision can tell it: it decides
//!   "touching", "degenerate" and "zero area", which mean "to double precision" throughout
//!   the crate (outline checks, [`segments_intersect`], `Mesh::new`), so that whatever the
//!   outline checks accept, spade and the mesh checks accept too.

use std::cmp::Ordering;

/// A point (or vector) in the plane, `[x, y]`.
pub type Point = [f64; 2];

/// The largest coordinate magnitude the crate accepts in outlines, meshes and poses.
///
/// The geometry itself is scale-invariant: outlines are validated and triangulated, meshes
/// validated and deformed, in coordinates scaled by a power of two (which is exact), so a
/// shape works the same at 1e-300 as at 1 or 1e300. What the limit keeps is headroom: the
/// sums and differences of a few coordinates (edges, a vertex plus its velocity) must stay
/// finite, and 1e300 leaves eight decimal orders below the largest double (1.8e308).
pub const MAX_COORDINATE: f64 = 1e300;

/// The smallest extent (the larger side of the bounding box) of an outline or a mesh.
///
/// Below about 2.2e-308 doubles are subnormal and carry fewer significant digits; a shape at
/// least 1e-300 across keeps every rounding to that grid (about 4.9e-324) more than seven
/// orders below double precision relative to its size, so it loses nothing.
pub const MIN_EXTENT: f64 = 1e-300;

/// The exponent `e` with `2^e <= m < 2^(e + 1)`, for a finite `m > 0` (normal or subnormal).
pub fn binary_exponent(m: f64) -> i32 {
    debug_assert!(m > 0.0 && m.is_finite());
    let biased = ((m.to_bits() >> 52) & 0x7ff) as i32;
    if biased == 0 {
        // Subnormal: 2^64 m is normal, and exact.
        binary_exponent(m * f64::from_bits((1023 + 64) << 52)) - 64
    } else {
        biased - 1023
    }
}

/// `x * 2^k`: exact unless the result overflows or falls below the normal range.
pub fn scale_by_power_of_two(x: f64, k: i32) -> f64 {
    let mut x = x;
    let mut k = k;
    // 2^j is a normal double for j in -1022..=1023; larger shifts go in steps of the same sign.
    while k != 0 {
        let j = k.clamp(-1000, 1000);
        x *= f64::from_bits(((j + 1023) as u64) << 52);
        k -= j;
    }
    x
}

/// `2^k` as a double, for `k` from -1022 to 1023 (a normal number): multiplying by it is the
/// exact [`scale_by_power_of_two`] in one multiplication, for hot loops.
pub fn power_of_two(k: i32) -> f64 {
    assert!((-1022..=1023).contains(&k), "2^{k} is not a normal double");
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// Whether a magnitude is within `[2^-250, 2^250]` (about 5.5e-76 to 1.8e75), where squares
/// and products of a few such values, and their reciprocals, stay far inside the normal
/// range: computations on them need no scaling to avoid overflow or underflow.
#[inline]
pub fn in_comfortable_range(magnitude: f64) -> bool {
    (f64::from_bits((1023 - 250) << 52)..=f64::from_bits((1023 + 250) << 52)).contains(&magnitude)
}

/// The power of two `2^k` that brings the largest coordinate magnitude of `points` into
/// `[1, 2)`, as `k` (0 when every coordinate is 0 or there are no points). Multiplying by it
/// is exact for coordinates within [`MAX_COORDINATE`] of shapes at least [`MIN_EXTENT`]
/// across, so geometry computed on the scaled points is that of the points themselves, free
/// of overflow and underflow.
pub fn normalising_exponent(points: impl IntoIterator<Item = Point>) -> i32 {
    let largest = points.into_iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    if largest > 0.0 && largest.is_finite() {
        -binary_exponent(largest)
    } else {
        0
    }
}

/// [`orient`] when double-precision arithmetic certifies its sign, `None` when the value is
/// within its rounding error of zero (the points are collinear to double precision).
///
/// Each of the two products carries at most three roundings (two differences and the
/// product), each of relative size at most `u = 2^-53`, and the final subtraction one more,
/// so the computed value differs from the exact one by less than `4u (|t1| + |t2|)` plus
/// terms of order `u^2`; 4.5e-16 bounds that. Products below 2^-1000 might have underflowed,
/// and are never certain: scale the points first ([`normalising_exponent`]).
pub fn certain_orient(a: Point, b: Point, c: Point) -> Option<f64> {
    let t1 = (b[0] - a[0]) * (c[1] - a[1]);
    let t2 = (b[1] - a[1]) * (c[0] - a[0]);
    let det = t1 - t2;
    let size = t1.abs() + t2.abs();
    (size >= f64::from_bits((1023 - 1000) << 52) && det.abs() > 4.5e-16 * size && det.is_finite()).then_some(det)
}

/// Twice the signed area of triangle `a b c`: positive when `a b c` turn counter-clockwise.
#[inline]
pub fn orient(a: Point, b: Point, c: Point) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Relative error bound of [`orient`] (Shewchuk's `ccwerrboundA`, `(3 + 16 eps) eps` with
/// `eps = 2^-53`): the computed sign is right when the result exceeds this times the sum of
/// the two products' magnitudes.
const ORIENT_ERROR_BOUND: f64 = (3.0 + 16.0 * f64::EPSILON / 2.0) * f64::EPSILON / 2.0;

/// The exact sign of `orient(a, b, c)`: `Greater` when `a b c` turn counter-clockwise,
/// `Less` when clockwise, `Equal` when the three points are collinear. Exact for finite
/// coordinates: when the largest is beyond 1e150 or below 1e-140, where products would
/// overflow or underflow, the three points are first scaled by a power of two (exact,
/// unless the triple also holds coordinates some 1e290 times smaller, which underflow).
///
/// This orders the outline checks' sweep; whether two segments *meet* is decided to double
/// precision by [`segments_intersect`], which uses [`certain_orient`] for touching.
pub fn orientation(a: Point, b: Point, c: Point) -> Ordering {
    let largest = [a, b, c].iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    if largest.is_finite() && (largest > 1e150 || (largest > 0.0 && largest < 1e-140)) {
        let k = -binary_exponent(largest);
        let scaled = |p: Point| p.map(|x| scale_by_power_of_two(x, k));
        return filtered_orientation(scaled(a), scaled(b), scaled(c));
    }
    filtered_orientation(a, b, c)
}

/// [`orientation`] for coordinates whose products stay in range.
fn filtered_orientation(a: Point, b: Point, c: Point) -> Ordering {
    let left = (b[0] - a[0]) * (c[1] - a[1]);
    let right = (b[1] - a[1]) * (c[0] - a[0]);
    // Differences and products of rounded differences keep their signs, so when the two
    // products have different signs (or one is zero) the sign of their difference is right.
    if (left > 0.0 && right <= 0.0) || (left < 0.0 && right >= 0.0) || left == 0.0 {
        return (left - right).partial_cmp(&0.0).unwrap_or(Ordering::Equal);
    }
    let det = left - right;
    let bound = ORIENT_ERROR_BOUND * (left.abs() + right.abs());
    if det > bound {
        Ordering::Greater
    } else if -det > bound {
        Ordering::Less
    } else {
        exact_orientation(a, b, c)
    }
}

/// The sign of `orient(a, b, c)` by exact arithmetic: the determinant expanded into six
/// products of coordinates (`bx cy - bx ay - ax cy - by cx + by ax + ay cx`; the `ax ay`
/// terms cancel), each split exactly into a rounded product and its error (a fused
/// multiply-add), summed into a non-overlapping expansion whose largest component has the
/// sign of the sum.
fn exact_orientation(a: Point, b: Point, c: Point) -> Ordering {
    let products = [(b[0], c[1]), (-b[0], a[1]), (-a[0], c[1]), (-b[1], c[0]), (b[1], a[0]), (a[1], c[0])];
    let mut expansion = [0.0; 12];
    let mut len = 0;
    for (x, y) in products {
        let product = x * y;
        let error = x.mul_add(y, -product);
        for term in [error, product] {
            // Grow-Expansion: add one term, keeping the components non-overlapping and in
            // increasing magnitude.
            let mut q = term;
            for component in &mut expansion[..len] {
                let (sum, rest) = two_sum(q, *component);
                *component = rest;
                q = sum;
            }
            expansion[len] = q;
            len += 1;
        }
    }
    expansion
        .iter()
        .rev()
        .find(|c| **c != 0.0)
        .map_or(Ordering::Equal, |c| c.partial_cmp(&0.0).unwrap_or(Ordering::Equal))
}

/// `a + b` as the rounded sum and its exact error (Knuth's two-sum).
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let sum = a + b;
    let b_virtual = sum - a;
    let a_virtual = sum - b_virtual;
    (sum, (a - a_virtual) + (b - b_virtual))
}

/// Signed area of triangle `a b c` (positive when counter-clockwise).
#[inline]
pub fn triangle_area(a: Point, b: Point, c: Point) -> f64 {
    0.5 * orient(a, b, c)
}

/// Signed area of a closed polygon given by its vertices in order (shoelace formula);
/// positive when the vertices run counter-clockwise.
pub fn polygon_area(ring: &[Point]) -> f64 {
    let n = ring.len();
    let mut twice = 0.0;
    for i in 0..n {
        let p = ring[i];
        let q = ring[(i + 1) % n];
        twice += p[0] * q[1] - q[0] * p[1];
    }
    0.5 * twice
}

/// Euclidean distance between two points.
#[inline]
pub fn distance(a: Point, b: Point) -> f64 {
    libm::hypot(a[0] - b[0], a[1] - b[1])
}

/// The interior angle at `b` of the triangle (or corner) `a b c`, in radians, in `[0, pi]`.
pub fn angle_at(a: Point, b: Point, c: Point) -> f64 {
    let u = [a[0] - b[0], a[1] - b[1]];
    let v = [c[0] - b[0], c[1] - b[1]];
    let cross = u[0] * v[1] - u[1] * v[0];
    let dot = u[0] * v[0] + u[1] * v[1];
    libm::atan2(cross.abs(), dot)
}

/// Axis-aligned bounding box `(min, max)` of a set of points; `None` when it is empty.
pub fn bounding_box(points: impl IntoIterator<Item = Point>) -> Option<(Point, Point)> {
    let mut it = points.into_iter();
    let first = it.next()?;
    let (mut lo, mut hi) = (first, first);
    for p in it {
        lo = [lo[0].min(p[0]), lo[1].min(p[1])];
        hi = [hi[0].max(p[0]), hi[1].max(p[1])];
    }
    Some((lo, hi))
}

/// Whether `p`, known to be collinear with segment `a b`, lies within its bounding box.
fn within(a: Point, b: Point, p: Point) -> bool {
    p[0] >= a[0].min(b[0]) && p[0] <= a[0].max(b[0]) && p[1] >= a[1].min(b[1]) && p[1] <= a[1].max(b[1])
}

/// Whether the closed segments `a b` and `c d` share at least one point (crossing, touching
/// or overlapping) to double precision, the one notion of meeting of the outline checks:
///
/// - they cross when each segment's ends lie strictly on opposite sides of the other's line,
///   decided exactly ([`orientation`]);
/// - they touch when an end of one lies on the other's line to double precision (its side is
///   within the rounding of the computation, [`certain_orient`]; always so when it lies on
///   the line exactly) and within that segment's bounding box.
///
/// So every pair that shares a point exactly meets (what spade's exact predicates would
/// refuse as crossing constraints), and so does every pair whose near-touch a mesh could not
/// tell from a touch (`Mesh::new` calls a triangle degenerate when [`certain_orient`] cannot
/// tell its orientation). Pass coordinates scaled by [`normalising_exponent`], so that
/// rounding is all that is uncertain.
pub fn segments_intersect(a: Point, b: Point, c: Point, d: Point) -> bool {
    use Ordering::{Greater, Less};
    let on = |p: Point, q: Point, r: Point| within(p, q, r) && certain_orient(p, q, r).is_none();
    if on(c, d, a) || on(c, d, b) || on(a, b, c) || on(a, b, d) {
        return true;
    }
    let opposite = |x: Ordering, y: Ordering| matches!((x, y), (Less, Greater) | (Greater, Less));
    opposite(orientation(c, d, a), orientation(c, d, b)) && opposite(orientation(a, b, c), orientation(a, b, d))
}

/// Whether `p` lies strictly inside the closed polygon `ring` (even-odd rule; points on the
/// boundary may go either way).
pub fn point_in_polygon(p: Point, ring: &[Point]) -> bool {
    let n = ring.len();
    let mut inside = false;
    let mut j = n - 1;
    for i in 0..n {
        let (a, b) = (ring[i], ring[j]);
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if p[0] < x {
                inside = !inside;
            }
        }
        j = i;
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_square_area_and_orientation() {
        let ccw = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert_eq!(polygon_area(&ccw), 1.0);
        let cw: Vec<Point> = ccw.iter().rev().copied().collect();
        assert_eq!(polygon_area(&cw), -1.0);
        assert_eq!(triangle_area([0.0, 0.0], [2.0, 0.0], [0.0, 3.0]), 3.0);
    }

    #[test]
    fn segment_cases() {
        let (a, b) = ([0.0, 0.0], [2.0, 0.0]);
        assert!(segments_intersect(a, b, [1.0, -1.0], [1.0, 1.0]), "crossing");
        assert!(segments_intersect(a, b, [1.0, 0.0], [1.0, 1.0]), "touching in the middle");
        assert!(segments_intersect(a, b, [1.5, 0.0], [3.0, 0.0]), "collinear overlap");
        assert!(!segments_intersect(a, b, [2.5, 0.0], [3.0, 0.0]), "collinear apart");
        assert!(!segments_intersect(a, b, [0.0, 1.0], [2.0, 1.0]), "parallel");
        assert!(!segments_intersect(a, b, [3.0, -1.0], [3.0, 1.0]), "would cross if extended");
    }

    #[test]
    fn powers_of_two_scale_exactly() {
        for (m, e) in [(1.0, 0), (1.5, 0), (2.0, 1), (0.75, -1), (1e300, 996), (1e-300, -997), (5e-324, -1074)] {
            assert_eq!(binary_exponent(m), e, "{m}");
            assert!(2f64.powi(e) <= m && m < 2f64.powi(e + 1) || e < -1022, "{m}");
        }
        assert_eq!(scale_by_power_of_two(3.0, 4), 48.0);
        assert_eq!(scale_by_power_of_two(1e-300, 1100), 1e-300 * 2f64.powi(1000) * 2f64.powi(100));
        // Below the normal range the result rounds: 0.1 * 2^-1070 is 2 * 2^-1074 (0.1 * 16 = 1.6).
        assert_eq!(scale_by_power_of_two(scale_by_power_of_two(0.1, -1070), 1070), 0.125);
        assert_eq!(normalising_exponent([[0.0, -3.0], [2.5, 1.0]]), -1);
        assert_eq!(normalising_exponent([[0.0, 0.0]]), 0);
    }

    #[test]
    fn powers_of_two_and_the_comfortable_range() {
        assert_eq!(power_of_two(0), 1.0);
        assert_eq!(power_of_two(-3), 0.125);
        assert_eq!(power_of_two(1023), 2f64.powi(1023));
        assert_eq!(power_of_two(-1022), f64::MIN_POSITIVE);
        assert!(in_comfortable_range(1.0) && in_comfortable_range(1e75) && in_comfortable_range(1e-75));
        assert!(!in_comfortable_range(1e76) && !in_comfortable_range(1e-76) && !in_comfortable_range(0.0));
        assert!(!in_comfortable_range(f64::NAN) && !in_comfortable_range(f64::INFINITY));
    }

    #[test]
    fn orientation_is_certain_unless_collinear_to_double_precision() {
        assert_eq!(certain_orient([0.0, 0.0], [1.0, 0.0], [0.0, 1.0]), Some(1.0));
        assert_eq!(certain_orient([0.0, 0.0], [0.0, 1.0], [1.0, 0.0]), Some(-1.0));
        assert_eq!(certain_orient([0.0, 0.0], [1.0, 1.0], [2.0, 2.0]), None);
        // Exactly 1e-20 (a product with zero has no rounding): certain however small.
        assert_eq!(certain_orient([0.0, 0.0], [1.0, 0.0], [0.5, 1e-20]), Some(1e-20));
        // Products of 6 that differ by 4.4e-16 are within their rounding.
        assert_eq!(certain_orient([0.0, 0.0], [1.0, 1.0], [3.0, 3.0 + 4.4e-16]), None);
        // Underflowing products are never certain.
        assert_eq!(certain_orient([0.0, 0.0], [1e-160, 0.0], [0.0, 1e-160]), None);
    }

    #[test]
    fn orientation_is_exact_where_rounding_is_not() {
        // Shewchuk's example: (0.5 + i u, 0.5 + j u), (12, 12), (24, 24) with u = 2^-53,
        // nearly collinear. Scaled by 2^53 every coordinate is an integer below 2^58, so
        // i128 gives the exact sign.
        let u = f64::EPSILON / 2.0;
        let mut wrong_by_rounding = 0;
        for i in 0..64i64 {
            for j in 0..64i64 {
                let (a, b, c) = ([0.5 + i as f64 * u, 0.5 + j as f64 * u], [12.0, 12.0], [24.0, 24.0]);
                let half = 1i128 << 52;
                let (ax, ay) = (half + i128::from(i), half + i128::from(j));
                let (bx, cx) = (12i128 << 53, 24i128 << 53);
                let exact = ((bx - ax) * (cx - ay)).cmp(&((bx - ay) * (cx - ax)));
                assert_eq!(orientation(a, b, c), exact, "i = {i}, j = {j}");
                if orient(a, b, c).partial_cmp(&0.0) != Some(exact) {
                    wrong_by_rounding += 1;
                }
            }
        }
        // The cases are hard: plain floating point gets many of them wrong.
        assert!(wrong_by_rounding > 100, "{wrong_by_rounding}");
        // Scaled by powers of two far beyond where products overflow or underflow, the
        // signs are the same.
        for (i, j) in [(3.0, 0.0), (0.0, 3.0), (5.0, 5.0), (7.0, 2.0)] {
            let (a, b, c) = ([0.5 + i * u, 0.5 + j * u], [12.0, 12.0], [24.0, 24.0]);
            let expected = orientation(a, b, c);
            for k in [-1000, -600, 600, 1000] {
                let s = 2f64.powi(k);
                let scaled = |p: Point| [p[0] * s, p[1] * s];
                assert_eq!(orientation(scaled(a), scaled(b), scaled(c)), expected, "2^{k}");
            }
        }
        // Subnormal and huge triples are scaled without overflow.
        let tiny = 5e-324;
        assert_eq!(orientation([0.0, 0.0], [tiny, 0.0], [0.0, tiny]), Ordering::Greater);
        assert_eq!(orientation([0.0, 0.0], [f64::MAX, 0.0], [0.0, -f64::MAX]), Ordering::Less);
    }

    #[test]
    fn segments_meet_exactly_or_to_double_precision() {
        let u = f64::EPSILON / 2.0;
        // (12, 12) lies on the line of a b within rounding but, exactly, off it: the two
        // segments touch to double precision whichever side it is on.
        for i in [-3.0, 3.0] {
            let (a, b) = ([0.5 + i * u, 0.5], [24.0, 24.0]);
            assert_ne!(orientation(a, b, [12.0, 12.0]), Ordering::Equal);
            assert_eq!(certain_orient(a, b, [12.0, 12.0]), None);
            assert!(segments_intersect(a, b, [12.0, 12.0], [12.0, 11.0]), "{i}");
            assert!(segments_intersect(a, b, [12.0, 12.0], [12.0, 13.0]), "{i}");
        }
        // Every pair that meets exactly meets, and a pair that does not meets only through an
        // end whose side rounding cannot tell: the near-collinear grid of Shewchuk's example
        // against the segment from (12, 12) down to (12, 11).
        let (c, d) = ([12.0, 12.0], [12.0, 11.0]);
        for i in -32..32 {
            for j in -32..32 {
                let (a, b) = ([0.5 + f64::from(i) * u, 0.5 + f64::from(j) * u], [24.0, 24.0]);
                let exact = orientation(a, b, c) != Ordering::Less;
                let meets = segments_intersect(a, b, c, d);
                assert!(meets || !exact, "({i}, {j})");
                assert!(exact || !meets || certain_orient(a, b, c).is_none(), "({i}, {j})");
            }
        }
        // Far from any rounding: apart, crossing, touching at an end.
        assert!(!segments_intersect([0.0, 0.0], [1.0, 0.0], [0.5, 1e-9], [0.5, 1.0]));
        assert!(segments_intersect([0.0, 0.0], [1.0, 1.0], [0.0, 1.0], [1.0, 0.0]));
        assert!(segments_intersect([0.0, 0.0], [1.0, 0.0], [0.5, 0.0], [0.5, 1.0]));
    }

    #[test]
    fn angles_and_containment() {
        let right = angle_at([1.0, 0.0], [0.0, 0.0], [0.0, 1.0]);
        assert!((right - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert!(point_in_polygon([0.5, 0.5], &square));
        assert!(!point_in_polygon([1.5, 0.5], &square));
    }
}
