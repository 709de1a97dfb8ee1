//! Distortion of a deformed mesh against its rest pose (the paper's Table 1).
//!
//! Per triangle, `sigma1 >= sigma2` are the singular values of the linear map taking the
//! rest triangle to the current one, and `rho` is the rest area over the total rest area:
//! `E_area = sum rho (sigma1 sigma2 + 1 / (sigma1 sigma2))`,
//! `E_angle = sum rho (sigma1 / sigma2 + sigma2 / sigma1)`. Both are 2 for a rigid motion
//! and larger otherwise. A triangle whose map has a non-positive determinant is flipped.

use crate::geometry::Point;

/// Distortion measures of a pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Metrics {
    /// Area distortion, 2 for a rigid motion.
    pub area_distortion: f64,
    /// Angle distortion, 2 for a rigid motion (or any similarity).
    pub angle_distortion: f64,
    /// Triangles turned upside down (or collapsed).
    pub flipped: usize,
}

/// Singular values `(sigma1, sigma2)`, `sigma1 >= sigma2 >= 0`, and determinant of the
/// 2 x 2 matrix `[[a, b], [c, d]]`.
pub fn singular_values(a: f64, b: f64, c: f64, d: f64) -> (f64, f64, f64) {
    // sigma1,2 = (sqrt((a + d)^2 + (c - b)^2) +- sqrt((a - d)^2 + (c + b)^2)) / 2.
    let p = (a + d).hypot(c - b);
    let q = (a - d).hypot(c + b);
    (0.5 * (p + q), 0.5 * (p - q).abs(), a * d - b * c)
}

/// The map taking rest triangle `r` to current triangle `p`: `F = [p1 - p0, p2 - p0] [r1 - r0, r2 - r0]^-1`.
pub fn deformation_gradient(r: [Point; 3], p: [Point; 3]) -> [[f64; 2]; 2] {
    let (e1, e2) = ([r[1][0] - r[0][0], r[1][1] - r[0][1]], [r[2][0] - r[0][0], r[2][1] - r[0][1]]);
    let (f1, f2) = ([p[1][0] - p[0][0], p[1][1] - p[0][1]], [p[2][0] - p[0][0], p[2][1] - p[0][1]]);
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

/// Distortion of `current` against `rest` over the given triangles.
pub fn metrics(rest: &[Point], current: &[Point], triangles: &[[u32; 3]]) -> Metrics {
    let corners = |pts: &[Point], t: &[u32; 3]| [pts[t[0] as usize], pts[t[1] as usize], pts[t[2] as usize]];
    let mut total_area = 0.0;
    let (mut area, mut angle, mut flipped) = (0.0, 0.0, 0);
    for t in triangles {
        let r = corners(rest, t);
        let rest_area = 0.5 * ((r[1][0] - r[0][0]) * (r[2][1] - r[0][1]) - (r[1][1] - r[0][1]) * (r[2][0] - r[0][0]));
        let f = deformation_gradient(r, corners(current, t));
        let (s1, s2, det) = singular_values(f[0][0], f[0][1], f[1][0], f[1][1]);
        if det <= 0.0 {
            flipped += 1;
        }
        total_area += rest_area;
        let product = s1 * s2;
        area += rest_area * (product + 1.0 / product);
        angle += rest_area * (s1 / s2 + s2 / s1);
    }
    Metrics { area_distortion: area / total_area, angle_distortion: angle / total_area, flipped }
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
}
