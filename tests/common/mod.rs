//! Checks shared by the integration tests. Each derives what a correct result must satisfy
//! from the geometry of the input, not from the code under test.

use akap::geometry::{angle_at, distance, orient, polygon_area, triangle_area, Point};
use akap::{Mesh, Outline};

/// Rotates every point of an outline by `angle` about the origin and shifts it by `offset`.
pub(crate) fn moved(outline: &Outline, angle: f64, offset: Point) -> Outline {
    let (s, c) = angle.sin_cos();
    let map = |ring: &Vec<Point>| -> Vec<Point> {
        ring.iter().map(|p| [c * p[0] - s * p[1] + offset[0], s * p[0] + c * p[1] + offset[1]]).collect()
    };
    Outline { outer: map(&outline.outer), holes: outline.holes.iter().map(map).collect() }
}

/// Every triangle is counter-clockwise with positive area.
pub(crate) fn assert_positive_triangles(mesh: &Mesh) {
    let p = mesh.positions();
    for (t, &[a, b, c]) in mesh.triangles().iter().enumerate() {
        let area = triangle_area(p[a as usize], p[b as usize], p[c as usize]);
        assert!(area > 0.0, "triangle {t} has area {area}");
    }
}

/// The triangles cover the outline's area minus its holes (to rounding).
pub(crate) fn assert_area_matches(mesh: &Mesh, outline: &Outline) {
    let p = mesh.positions();
    let sum: f64 =
        mesh.triangles().iter().map(|&[a, b, c]| triangle_area(p[a as usize], p[b as usize], p[c as usize])).sum();
    let expected =
        polygon_area(&outline.outer).abs() - outline.holes.iter().map(|h| polygon_area(h).abs()).sum::<f64>();
    assert!((sum - expected).abs() <= 1e-9 * expected, "triangle areas sum to {sum}, outline area is {expected}");
}

/// Every segment of the outline is covered by boundary edges of the mesh lying on it, and
/// the boundary has no other edges.
pub(crate) fn assert_outline_edges_survive(mesh: &Mesh, outline: &Outline) {
    let p = mesh.positions();
    let scale = outline.outer.iter().map(|q| q[0].abs().max(q[1].abs())).fold(0.0, f64::max);
    // Points that spade puts on a segment are on it up to rounding; 1e-13 of the outline's
    // size leaves a wide margin for that and stays below features 1e-9 across.
    let tol = 1e-13 * scale;
    let mut used = vec![false; mesh.boundary_edges().len()];
    let mut perimeter = 0.0;
    for ring in outline.rings() {
        for i in 0..ring.len() {
            let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
            let len = distance(a, b);
            perimeter += len;
            let on_segment = |q: Point| {
                orient(a, b, q).abs() <= tol * len
                    && (q[0] - a[0]) * (b[0] - a[0]) + (q[1] - a[1]) * (b[1] - a[1]) >= -tol * len
                    && (q[0] - b[0]) * (a[0] - b[0]) + (q[1] - b[1]) * (a[1] - b[1]) >= -tol * len
            };
            let mut covered = 0.0;
            for (k, &[u, v]) in mesh.boundary_edges().iter().enumerate() {
                let (pu, pv) = (p[u as usize], p[v as usize]);
                if on_segment(pu) && on_segment(pv) {
                    covered += distance(pu, pv);
                    used[k] = true;
                }
            }
            assert!(
                (covered - len).abs() <= 1e-9 * len.max(scale),
                "segment {a:?}-{b:?} of length {len} has {covered} covered"
            );
        }
    }
    let boundary: f64 = mesh.boundary_edges().iter().map(|&[u, v]| distance(p[u as usize], p[v as usize])).sum();
    assert!(
        (boundary - perimeter).abs() <= 1e-9 * perimeter,
        "boundary length {boundary}, outline perimeter {perimeter}"
    );
    assert!(used.iter().all(|&u| u), "a boundary edge lies on no outline segment");
}

/// The segments of every outline corner whose interior angle is below `below_degrees`, as
/// `(previous point, corner, next point)`.
pub(crate) fn sharp_corners(outline: &Outline, below_degrees: f64) -> Vec<[Point; 3]> {
    let mut sharp = Vec::new();
    for ring in outline.rings() {
        let n = ring.len();
        let ccw = polygon_area(ring) > 0.0;
        for i in 0..n {
            let (a, b, c) = (ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]);
            // The interior angle of a ring corner: the shape is left of a counter-clockwise
            // outer ring and right of the same ring run clockwise.
            let turn = angle_at(a, b, c).to_degrees();
            let convex = (orient(a, b, c) > 0.0) == ccw;
            let interior = if convex { turn } else { 360.0 - turn };
            // For holes the shape lies outside the ring, so their interior angles are the
            // ring's exterior ones.
            let interior =
                if std::ptr::eq(ring.as_ptr(), outline.outer.as_ptr()) { interior } else { 360.0 - interior };
            if interior < below_degrees {
                sharp.push([a, b, c]);
            }
        }
    }
    sharp
}

/// The smallest angle of a triangle, in degrees.
pub(crate) fn min_angle_degrees(a: Point, b: Point, c: Point) -> f64 {
    angle_at(c, a, b).min(angle_at(a, b, c)).min(angle_at(b, c, a)).to_degrees()
}

/// Whether `q` lies on the closed segment `a b` (to a relative tolerance).
fn on_segment(q: Point, a: Point, b: Point) -> bool {
    let len = distance(a, b);
    let tol = 1e-9 * len.max(a[0].abs().max(a[1].abs()));
    orient(a, b, q).abs() <= tol * len && distance(a, q) + distance(q, b) <= len + tol
}

/// Delaunay refinement (Ruppert, Shewchuk; Miller, Pav and Walkington) reaches the angle
/// bound everywhere except in the wedge of an input angle too small to keep: there a
/// triangle whose shortest edge spans the two segments of the corner cannot be improved
/// without cutting the input. So: every triangle with an angle below `limit` must have its
/// shortest edge joining the two sides of one of the `sharp` corners.
pub(crate) fn assert_min_angle_away_from(mesh: &Mesh, limit: f64, sharp: &[[Point; 3]]) {
    let p = mesh.positions();
    for (t, &[a, b, c]) in mesh.triangles().iter().enumerate() {
        let q = [p[a as usize], p[b as usize], p[c as usize]];
        let min = min_angle_degrees(q[0], q[1], q[2]);
        if min >= limit - 1e-6 {
            continue;
        }
        let shortest =
            (0..3).min_by(|&i, &j| distance(q[i], q[(i + 1) % 3]).total_cmp(&distance(q[j], q[(j + 1) % 3]))).unwrap();
        let (u, v) = (q[shortest], q[(shortest + 1) % 3]);
        let in_wedge = sharp.iter().any(|&[x, corner, y]| {
            (on_segment(u, x, corner) && on_segment(v, corner, y))
                || (on_segment(v, x, corner) && on_segment(u, corner, y))
        });
        assert!(
            in_wedge,
            "triangle {t} has a {min} degree angle, below {limit}, outside any sharp corner's wedge: {q:?}"
        );
    }
}

/// A small deterministic generator (xorshift64*), so tests need no extra crates.
pub(crate) struct Rng(u64);

impl Rng {
    pub(crate) fn new(seed: u64) -> Self {
        Self(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// Uniform in [0, 1).
    pub(crate) fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub(crate) fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
}
