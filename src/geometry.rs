//! Small planar geometry helpers shared by the outline checks, the mesh and the tests.
//!
//! Points are `[x, y]` arrays of `f64`. Orientation follows the usual convention: positive
//! signed area means counter-clockwise.

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
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The interior angle at `b` of the triangle (or corner) `a b c`, in radians, in `[0, pi]`.
pub fn angle_at(a: Point, b: Point, c: Point) -> f64 {
    let u = [a[0] - b[0], a[1] - b[1]];
    let v = [c[0] - b[0], c[1] - b[1]];
    let cross = u[0] * v[1] - u[1] * v[0];
    let dot = u[0] * v[0] + u[1] * v[1];
    cross.abs().atan2(dot)
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
/// or overlapping) to double precision: an end whose side of the other segment is within
/// rounding ([`certain_orient`]) counts as on its line. Pass coordinates scaled by
/// [`normalising_exponent`], so that rounding is all that is uncertain.
pub fn segments_intersect(a: Point, b: Point, c: Point, d: Point) -> bool {
    let side = |p, q, r| certain_orient(p, q, r).unwrap_or(0.0);
    let d1 = side(c, d, a);
    let d2 = side(c, d, b);
    let d3 = side(a, b, c);
    let d4 = side(a, b, d);
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0)) && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0)) {
        return true;
    }
    (d1 == 0.0 && within(c, d, a))
        || (d2 == 0.0 && within(c, d, b))
        || (d3 == 0.0 && within(a, b, c))
        || (d4 == 0.0 && within(a, b, d))
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
    fn angles_and_containment() {
        let right = angle_at([1.0, 0.0], [0.0, 0.0], [0.0, 1.0]);
        assert!((right - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert!(point_in_polygon([0.5, 0.5], &square));
        assert!(!point_in_polygon([1.5, 0.5], &square));
    }
}
