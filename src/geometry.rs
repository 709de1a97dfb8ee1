//! Small planar geometry helpers shared by the outline checks, the mesh and the tests.
//!
//! Points are `[x, y]` arrays of `f64`. Orientation follows the usual convention: positive
//! signed area means counter-clockwise. [`orientation`] decides the sign exactly (a
//! floating-point filter, then exact expansion arithmetic when the filter cannot tell, as
//! in Shewchuk's adaptive predicates), and so does [`segments_intersect`].

use std::cmp::Ordering;

/// A point (or vector) in the plane, `[x, y]`.
pub type Point = [f64; 2];

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
pub fn orientation(a: Point, b: Point, c: Point) -> Ordering {
    let largest = [a, b, c].iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    if largest > 1e150 || (largest > 0.0 && largest < 1e-140) {
        let scale = 2f64.powi(-(largest.log2().floor() as i32));
        let scaled = |p: Point| [p[0] * scale, p[1] * scale];
        if largest.is_finite() {
            return filtered_orientation(scaled(a), scaled(b), scaled(c));
        }
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
/// or overlapping), decided exactly (see [`orientation`]).
pub fn segments_intersect(a: Point, b: Point, c: Point, d: Point) -> bool {
    use Ordering::{Equal, Greater, Less};
    let d1 = orientation(c, d, a);
    let d2 = orientation(c, d, b);
    let d3 = orientation(a, b, c);
    let d4 = orientation(a, b, d);
    let opposite = |x: Ordering, y: Ordering| matches!((x, y), (Less, Greater) | (Greater, Less));
    if opposite(d1, d2) && opposite(d3, d4) {
        return true;
    }
    (d1 == Equal && within(c, d, a))
        || (d2 == Equal && within(c, d, b))
        || (d3 == Equal && within(a, b, c))
        || (d4 == Equal && within(a, b, d))
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
        // And a segment test that rounding would get wrong: nearly touching.
        let (a, b) = ([0.5 + 3.0 * u, 0.5], [24.0, 24.0]);
        assert_eq!(segments_intersect(a, b, [12.0, 12.0], [12.0, 11.0]), orientation(a, b, [12.0, 12.0]).is_ge());
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
