//! Distortion of a deformed mesh against its rest pose (the paper's Table 1).
//!
//! Per triangle, `sigma1 >= sigma2` are the singular values of the linear map taking the
//! rest triangle to the current one, and `rho` is the rest area over the total rest area:
//! `E_area = sum rho (sigma1 sigma2 + 1 / (sigma1 sigma2))`,
//! `E_angle = sum rho (sigma1 / sigma2 + sigma2 / sigma1)`. Both are 2 for a rigid motion
//! and larger otherwise. A triangle whose map has a non-positive determinant is flipped.
//!
//! A triangle collapsed onto a line or a point (`sigma2 = 0`) has infinite distortion: both
//! terms grow without bound as `sigma2` goes to 0 (for `sigma1 > 0`; with `sigma1 = 0` too
//! the ratio has no limit, but the area term does), so both measures of a pose with a
//! collapsed triangle are `+inf`, never NaN, and the triangle counts as flipped (its
//! determinant is 0). Poses with triangles turned over but not collapsed stay finite.

use crate::geometry::{
    binary_exponent, in_comfortable_range, normalising_exponent, power_of_two, scale_by_power_of_two, Point,
};

/// Distortion measures of a pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Metrics {
    /// Area distortion, 2 for a rigid motion, `+inf` when a triangle has collapsed.
    pub area_distortion: f64,
    /// Angle distortion, 2 for a rigid motion (or any similarity), `+inf` when a triangle
    /// has collapsed.
    pub angle_distortion: f64,
    /// Triangles turned upside down or collapsed (determinant at most 0).
    pub flipped: usize,
}

/// Singular values `(sigma1, sigma2)`, `sigma1 >= sigma2 >= 0`, and determinant of the
/// 2 x 2 matrix `[[a, b], [c, d]]`.
pub fn singular_values(a: f64, b: f64, c: f64, d: f64) -> (f64, f64, f64) {
    // sigma1,2 = (sqrt((a + d)^2 + (c - b)^2) +- sqrt((a - d)^2 + (c + b)^2)) / 2, and
    // sigma1 sigma2 = |det|: the smaller one from that, free of the difference's cancellation.
    let p = libm::hypot(a + d, c - b);
    let q = libm::hypot(a - d, c + b);
    let det = a * d - b * c;
    let sigma1 = 0.5 * (p + q);
    let sigma2 = if sigma1 > 0.0 { (det.abs() / sigma1).min(sigma1) } else { 0.0 };
    (sigma1, sigma2, det)
}

/// The map taking rest triangle `r` to current triangle `p`: `F = [p1 - p0, p2 - p0] [r1 - r0, r2 - r0]^-1`.
///
/// Outside the comfortable range (rest edges beyond about 1e-75 to 1e75) both triangles'
/// edges are first scaled by the power of two that brings the rest edges' largest component
/// into [1, 2) (which leaves `F` unchanged, exactly), so neither the inverse nor the
/// products overflow or underflow at any scale.
pub fn deformation_gradient(r: [Point; 3], p: [Point; 3]) -> [[f64; 2]; 2] {
    let (e1, e2) = ([r[1][0] - r[0][0], r[1][1] - r[0][1]], [r[2][0] - r[0][0], r[2][1] - r[0][1]]);
    let (f1, f2) = ([p[1][0] - p[0][0], p[1][1] - p[0][1]], [p[2][0] - p[0][0], p[2][1] - p[0][1]]);
    let largest = e1.iter().chain(&e2).fold(0.0f64, |m, x| m.max(x.abs()));
    let k = if largest > 0.0 && largest.is_finite() && !in_comfortable_range(largest) {
        -binary_exponent(largest)
    } else {
        0
    };
    let scale = |v: [f64; 2]| v.map(|x| scale_by_power_of_two(x, k));
    let (e1, e2, f1, f2) = (scale(e1), scale(e2), scale(f1), scale(f2));
    let det = e1[0] * e2[1] - e2[0] * e1[1];
    // Inverse of [e1 e2] (columns) is [[e2y, -e2x], [-e1y, e1x]] / det.
    let inv = [[e2[1] / det, -e2[0] / det], [-e1[1] / det, e1[0] / det]];
    let mut f = [[0.0; 2]; 2];
    for (i, row) in f.iter_mut().enumerate() {
        let (x, y) = (f1[i], f2[i]);
        row[0] = x * inv[0][0] + y * inv[1][0];
        row[1] = x * inv[0][1] + y * inv[1][1];
    }
    f
}

/// `(E_area, E_angle)` of one triangle's map from its singular values: `+inf` for both when
/// it has collapsed (`sigma2 = 0`).
pub fn triangle_distortion(sigma1: f64, sigma2: f64) -> (f64, f64) {
    if sigma2 == 0.0 {
        return (f64::INFINITY, f64::INFINITY);
    }
    let product = sigma1 * sigma2;
    (product + 1.0 / product, sigma1 / sigma2 + sigma2 / sigma1)
}

/// `(E_area, E_angle, det)` of a triangle's map `F`, as [`triangle_distortion`] of its
/// singular values but without them (no square root: this runs per triangle per frame, and
/// a 50,000-vertex pose has 100,000): `sigma1 sigma2 = |det F|` and `sigma1^2 + sigma2^2 =
/// |F|^2` (Frobenius), so `E_area = |det| + 1 / |det|` and `E_angle = |F|^2 / |det|`, the
/// latter, which scaling `F` leaves alone, on `F` scaled by a power of two outside the
/// comfortable range. `+inf` for both when collapsed (`det = 0`, as `sigma2 = 0`).
fn map_distortion(f: [[f64; 2]; 2]) -> (f64, f64, f64) {
    let [[a, b], [c, d]] = f;
    let det = a * d - b * c;
    if det == 0.0 {
        return (f64::INFINITY, f64::INFINITY, det);
    }
    let largest = a.abs().max(b.abs()).max(c.abs()).max(d.abs());
    let k = if largest.is_finite() && !in_comfortable_range(largest) { -binary_exponent(largest) } else { 0 };
    let [a, b, c, d] = [a, b, c, d].map(|x| scale_by_power_of_two(x, k));
    let angle = (a * a + b * b + c * c + d * d) / (a * d - b * c).abs();
    (det.abs() + 1.0 / det.abs(), angle, det)
}

/// Distortion of `current` against `rest` over the given triangles.
pub fn metrics(rest: &[Point], current: &[Point], triangles: &[[u32; 3]]) -> Metrics {
    let corners = |pts: &[Point], t: &[u32; 3]| [pts[t[0] as usize], pts[t[1] as usize], pts[t[2] as usize]];
    // Rest areas are weights (only their ratios matter), taken on the rest mesh scaled by a
    // power of two into [1, 2): at 1e200 they would overflow, at 1e-200 underflow.
    // Within the coordinate limits the exponent is between -996 and 998; clamped, any rest
    // positions give a normal factor (only the ratios of the weights matter).
    let unit = power_of_two(normalising_exponent(rest.iter().copied()).clamp(-1022, 1022));
    let mut total_area = 0.0;
    let (mut area, mut angle, mut flipped) = (0.0, 0.0, 0);
    for t in triangles {
        let (r, p) = (corners(rest, t), corners(current, t));
        let (rest_area, e_area, e_angle, det) = match edge_distortion(r, p) {
            // Edges of ordinary sizes: from the edges' products, the map never formed.
            Some((rest_det, distortion)) => {
                let (e_area, e_angle, det) = distortion;
                (0.5 * (rest_det * unit) * unit, e_area, e_angle, det)
            }
            None => {
                let (e_area, e_angle, det) = map_distortion(deformation_gradient(r, p));
                (scaled_area(r, unit), e_area, e_angle, det)
            }
        };
        if det <= 0.0 {
            flipped += 1;
        }
        total_area += rest_area;
        area += rest_area * e_area;
        angle += rest_area * e_angle;
    }
    Metrics { area_distortion: area / total_area, angle_distortion: angle / total_area, flipped }
}

/// The fast path of [`metrics`] for a triangle whose rest and current edges both have
/// their largest component within `[2^-120, 2^120]` (`None` otherwise): with rest edges
/// `E = [e1 e2]`, current edges `C = [f1 f2]` and `G = C adj(E)`, the map is `F = G / det E`,
/// so `det F = det C / det E`, `E_area = |det F| + 1 / |det F|` and `E_angle = |F|^2 /
/// |det F| = |G|^2 / (|det E| |det C|)`, products of at most four edge components, far
/// from overflow and underflow in that range. Returns `det E` (twice the rest area) and
/// `(E_area, E_angle, det F)` as [`map_distortion`] gives them.
#[inline]
fn edge_distortion(r: [Point; 3], p: [Point; 3]) -> Option<(f64, (f64, f64, f64))> {
    let (e1, e2) = ([r[1][0] - r[0][0], r[1][1] - r[0][1]], [r[2][0] - r[0][0], r[2][1] - r[0][1]]);
    let (f1, f2) = ([p[1][0] - p[0][0], p[1][1] - p[0][1]], [p[2][0] - p[0][0], p[2][1] - p[0][1]]);
    let ordinary = |v: [f64; 4]| {
        let m = v.iter().fold(0.0, |m: f64, x| if x.abs() > m { x.abs() } else { m });
        (f64::from_bits((1023 - 120) << 52)..=f64::from_bits((1023 + 120) << 52)).contains(&m)
    };
    if !(ordinary([e1[0], e1[1], e2[0], e2[1]]) && ordinary([f1[0], f1[1], f2[0], f2[1]])) {
        return None;
    }
    let rest_det = e1[0] * e2[1] - e2[0] * e1[1];
    let det_c = f1[0] * f2[1] - f2[0] * f1[1];
    if det_c == 0.0 {
        return Some((rest_det, (f64::INFINITY, f64::INFINITY, 0.0)));
    }
    // G = C adj(E), adj(E) = [[e2y, -e2x], [-e1y, e1x]].
    let g = [
        f1[0] * e2[1] - f2[0] * e1[1],
        f2[0] * e1[0] - f1[0] * e2[0],
        f1[1] * e2[1] - f2[1] * e1[1],
        f2[1] * e1[0] - f1[1] * e2[0],
    ];
    let det = det_c / rest_det;
    let angle = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2] + g[3] * g[3]) / (rest_det.abs() * det_c.abs());
    Some((rest_det, (det.abs() + 1.0 / det.abs(), angle, det)))
}

/// The area of a triangle scaled by `factor`.
fn scaled_area(r: [Point; 3], factor: f64) -> f64 {
    let r = r.map(|p| p.map(|x| x * factor));
    0.5 * ((r[1][0] - r[0][0]) * (r[2][1] - r[0][1]) - (r[1][1] - r[0][1]) * (r[2][0] - r[0][0]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn singular_values_of_known_maps() {
        let (s1, s2, det) = singular_values(3.0, 0.0, 0.0, 2.0);
        assert_eq!((s1, s2, det), (3.0, 2.0, 6.0));
        // A rotation by 0.7 times a scaling by 2: both singular values 2.
        let (s, c) = 0.7f64.sin_cos();
        let (s1, s2, _) = singular_values(2.0 * c, -2.0 * s, 2.0 * s, 2.0 * c);
        assert!((s1 - 2.0).abs() < 1e-15 && (s2 - 2.0).abs() < 1e-15);
        // A reflection: determinant -1.
        assert_eq!(singular_values(1.0, 0.0, 0.0, -1.0), (1.0, 1.0, -1.0));
    }

    #[test]
    fn distortion_without_singular_values_is_distortion_with_them() {
        let maps = [[2.0, 0.3, -0.4, 0.7], [1.0, 0.0, 0.0, 1.0], [0.1, 5.0, -3.0, 0.2], [1e-150, 3e-151, 0.0, 2e-150]];
        for [a, b, c, d] in maps {
            let (s1, s2, det) = singular_values(a, b, c, d);
            let (area, angle) = triangle_distortion(s1, s2);
            let (area2, angle2, det2) = map_distortion([[a, b], [c, d]]);
            assert_eq!(det2, det);
            assert!((area2 - area).abs() <= 1e-13 * area && (angle2 - angle).abs() <= 1e-13 * angle, "{a} {b} {c} {d}");
        }
        // Scaled tiny maps keep the angle term: a similarity shrunk 2^-300 (whose entries'
        // squares, 2^-600, are out of the comfortable range) scores 2.
        let f = scale_by_power_of_two(1.0, -300);
        assert_eq!(map_distortion([[f, 0.0], [0.0, f]]).1, 2.0);
        assert_eq!(map_distortion([[1.0, 2.0], [2.0, 4.0]]), (f64::INFINITY, f64::INFINITY, 0.0));
    }

    #[test]
    fn the_fast_path_agrees_with_the_map() {
        let r = [[0.1, 0.2], [1.3, -0.1], [0.4, 0.9]];
        for p in [
            [[2.0, 1.0], [2.5, 3.0], [0.0, 1.5]],
            [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]],
            [[0.0, 0.0], [-1.0, 0.2], [0.3, 1.0]],
        ] {
            let (rest_det, (area, angle, det)) = edge_distortion(r, p).unwrap();
            let (area2, angle2, det2) = map_distortion(deformation_gradient(r, p));
            assert!((rest_det - 2.0 * scaled_area(r, 1.0)).abs() <= 1e-15);
            assert_eq!(det <= 0.0, det2 <= 0.0, "{p:?}");
            for (x, y) in [(area, area2), (angle, angle2), (det, det2)] {
                assert!(x == y || (x - y).abs() <= 1e-13 * y.abs(), "{p:?}: {x} against {y}");
            }
        }
        // Edges beyond 2^120 take the scaled path.
        assert!(edge_distortion([[0.0, 0.0], [1e40, 0.0], [0.0, 1e40]], r).is_none());
    }

    #[test]
    fn rigid_motion_scores_two_and_stretch_scores_more() {
        let rest = [[0.0, 0.0], [1.0, 0.0], [0.2, 0.9], [1.1, 1.0]];
        let tris = [[0, 1, 2], [1, 3, 2]];
        let (s, c) = 1.1f64.sin_cos();
        let moved: Vec<Point> = rest.iter().map(|p| [c * p[0] - s * p[1] + 5.0, s * p[0] + c * p[1] - 1.0]).collect();
        let m = metrics(&rest, &moved, &tris);
        assert!((m.area_distortion - 2.0).abs() < 1e-12 && (m.angle_distortion - 2.0).abs() < 1e-12);
        assert_eq!(m.flipped, 0);
        // Stretch x by 2: sigma = (2, 1), E_area = 2 + 1/2, E_angle = 2 + 1/2.
        let stretched: Vec<Point> = rest.iter().map(|p| [2.0 * p[0], p[1]]).collect();
        let m = metrics(&rest, &stretched, &tris);
        assert!((m.area_distortion - 2.5).abs() < 1e-12 && (m.angle_distortion - 2.5).abs() < 1e-12);
        let mirrored: Vec<Point> = rest.iter().map(|p| [-p[0], p[1]]).collect();
        assert_eq!(metrics(&rest, &mirrored, &tris).flipped, 2);
    }

    #[test]
    fn collapsed_triangles_have_infinite_distortion_and_count_as_flipped() {
        let rest = [[0.0, 0.0], [1.0, 0.0], [0.2, 0.9], [1.1, 1.0]];
        let tris = [[0, 1, 2], [1, 3, 2]];
        // Onto the x axis: sigma = (something, 0) for both triangles.
        let line: Vec<Point> = rest.iter().map(|p| [p[0], 0.0]).collect();
        let m = metrics(&rest, &line, &tris);
        assert_eq!((m.area_distortion, m.angle_distortion, m.flipped), (f64::INFINITY, f64::INFINITY, 2));
        // Of two separate triangles one onto a point (sigma = (0, 0)), the other stretched
        // but whole: still infinite, never NaN.
        let rest = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [5.0, 0.0], [6.0, 0.0], [5.0, 1.0]];
        let point = [[0.5, 0.5], [0.5, 0.5], [0.5, 0.5], [5.0, 0.0], [7.0, 0.0], [5.0, 1.0]];
        let m = metrics(&rest, &point, &[[0, 1, 2], [3, 4, 5]]);
        assert_eq!((m.area_distortion, m.angle_distortion, m.flipped), (f64::INFINITY, f64::INFINITY, 1));
        assert_eq!(triangle_distortion(0.0, 0.0), (f64::INFINITY, f64::INFINITY));
        // Shrunk by 1e-3 without collapsing: sigma1 = sigma2 = 1e-3, so E_area = 1e-6 + 1e6
        // and E_angle = 2, finite.
        let small: Vec<Point> = rest.iter().map(|p| [1e-3 * p[0], 1e-3 * p[1]]).collect();
        let m = metrics(&rest, &small, &tris);
        assert!((m.area_distortion - (1e-6 + 1e6)).abs() < 1e-6 && (m.angle_distortion - 2.0).abs() < 1e-9, "{m:?}");
    }

    #[test]
    fn thin_maps_keep_their_small_singular_value_and_scale_does_not_matter() {
        // diag(1, 1e-20): sigma2 = 1e-20, which (p - q) / 2 loses to cancellation.
        assert_eq!(singular_values(1.0, 0.0, 0.0, 1e-20), (1.0, 1e-20, 1e-20));
        assert_eq!(triangle_distortion(1.0, 1e-20), (1e-20 + 1e20, 1e20 + 1e-20));
        let rest = [[0.0, 0.0], [1.0, 0.0], [0.2, 0.9], [1.1, 1.0]];
        let tris = [[0, 1, 2], [1, 3, 2]];
        let stretched: Vec<Point> = rest.iter().map(|p| [2.0 * p[0], p[1]]).collect();
        let unit = metrics(&rest, &stretched, &tris);
        for s in [1e-300, 1e200, 1e300] {
            let scale = |pts: &[Point]| pts.iter().map(|p| [s * p[0], s * p[1]]).collect::<Vec<Point>>();
            let m = metrics(&scale(&rest), &scale(&stretched), &tris);
            assert!((m.area_distortion - unit.area_distortion).abs() < 1e-12, "{m:?} at {s}");
            assert!((m.angle_distortion - unit.angle_distortion).abs() < 1e-12, "{m:?} at {s}");
        }
    }
}
