//! Small planar geometry helpers shared by the outline checks, the mesh and the tests.
//!
//! Points are `[x, y]` arrays of `f64`. Orientation follows the usual convention: positive
//! signed area means counter-clockwise.

/// A point (or vector) in the plane, `[x, y]`.
pub type Point = [f64; 2];

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
/// or overlapping).
pub fn segments_intersect(a: Point, b: Point, c: Point, d: Point) -> bool {
    let d1 = orient(c, d, a);
    let d2 = orient(c, d, b);
    let d3 = orient(a, b, c);
    let d4 = orient(a, b, d);
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
    fn angles_and_containment() {
        let right = angle_at([1.0, 0.0], [0.0, 0.0], [0.0, 1.0]);
        assert!((right - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert!(point_in_polygon([0.5, 0.5], &square));
        assert!(!point_in_polygon([1.5, 0.5], &square));
    }
}
