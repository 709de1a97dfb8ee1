//! Moving vertices along a velocity field: the paper's logarithmic-spiral step (Section
//! 2.3, eqs. (13)-(16), with the sign of eq. (15) corrected as derived below) and the plain
//! linear step `p <- p + U` it is compared with (Figure 8).
//!
//! Points are complex numbers here, `(x, y) = x + iy`.
//!
//! **The fields fitted to an edge (eq. (13)).** A linear holomorphic field is
//! `U(p) = s (p - c)` with complex `s != 0` (a rotation by `arg s` and a scaling by `|s|`
//! about the centre `c`), or a constant `U(p) = d` (a translation). Its flow from `p` is
//! the logarithmic spiral (eq. (14)) `gamma(t) = c + e^(s t) (p - c)`: it starts at `p` and
//! `gamma'(t) = s (gamma(t) - c) = U(gamma(t))`.
//!
//! **Eq. (15), corrected.** For an edge from `p_v` to `p_w` with field values `u_v`, `u_w`,
//! the field `s (p - c)` that takes both values has, subtracting the two conditions,
//! `s = (u_v - u_w) / (p_v - p_w)` (as the paper says), and from `s (p_v - c) = u_v` the
//! centre `c = p_v - u_v / s`. The paper prints `c = p_1 + u_1 / s`: with it, `U(p_1)` would
//! be `-u_1`, so the spiral would run backwards. Putting the correct centre into eq. (14) at
//! `t = 1`:
//!
//! `gamma(1) = c + e^s (p_v - c) = p_v + (e^s - 1)(p_v - c) = p_v + u_v (e^s - 1) / s`,
//!
//! since `p_v - c = u_v / s`. The centre is gone: each edge gives vertex `v` the complex
//! factor `(e^s - 1) / s` on its velocity, and eq. (16), the mean of `gamma(1)` over `v`'s
//! `d(v)` edge neighbours `w`, becomes
//!
//! `p_v,new = p_v + u_v * (1 / d(v)) sum_w (e^(s_vw) - 1) / s_vw`.
//!
//! `(e^s - 1) / s` tends to 1 as `s -> 0`, where the spiral becomes the translation
//! `p + u`: computed by its power series for small `|s|` ([`exp_ratio`]), the translations
//! (`u_v = u_w`) need no case of their own, and nearly translational edges, whose centres
//! fly off to infinity, are accurate (which is why the paper averages positions, not
//! centres). `s` is the same seen from either end of an edge, so each edge's factor is
//! computed once.
//!
//! **Rigid motions (Appendix A).** For a Killing field `U(p) = a i (p - c) + d` (an
//! infinitesimal rotation by `a` plus a translation) every edge has `s = a i`, so every
//! vertex moves by the same factor: `p + U(p) (e^(ia) - 1) / (ia)`, exactly the rotation by
//! `a` about the field's centre `c + i d / a`. (The chord of a finite rotation,
//! `(e^(ia) - 1)(p - c)`, is not a Killing field, so it is the velocities `a i (p - c) + d`
//! that are reproduced exactly, not given displacements.)

use crate::geometry::{binary_exponent, scale_by_power_of_two, Point};

/// Below this `|s|` the series is used (up to 13 terms: the first one left out is below 1e-17).
const SERIES_RADIUS: f64 = 0.25;

/// `1 / (k + 1)!` for k = 0..=12: the coefficients of `(e^s - 1) / s = sum s^k / (k + 1)!`.
const SERIES: [f64; 13] = {
    let mut c = [1.0; 13];
    let mut k = 1;
    while k < 13 {
        c[k] = c[k - 1] / (k as f64 + 1.0);
        k += 1;
    }
    c
};

/// `(e^s - 1) / s` for a complex `s = [re, im]`, accurate for all `s` (1 at `s = 0`): the
/// factor of a vertex's velocity along the spiral of one of its edges at `t = 1`.
///
/// Per-frame fields are small, so most `s` are well inside the series' radius, where
/// Horner's rule costs a dozen complex multiply-adds instead of five transcendental calls.
pub fn exp_ratio(s: [f64; 2]) -> [f64; 2] {
    let [x, y] = s;
    let r2 = x * x + y * y;
    // The first term left out, |s|^k / (k + 1)!, is below 1e-17 in each case: for |s| < 0.01
    // with 7 terms (2.5e-19), for |s| < 0.05 with 9 (5.4e-19), for |s| < 1/4 with 13.
    if r2 < 0.01 * 0.01 {
        return series::<7>(s);
    }
    if r2 < 0.05 * 0.05 {
        return series::<9>(s);
    }
    if r2 < SERIES_RADIUS * SERIES_RADIUS {
        return series::<13>(s);
    }
    // e^s - 1 = (e^x cos y - 1) + i e^x sin y, with the real part written without
    // cancellation: e^x cos y - 1 = expm1(x) cos y - 2 sin^2(y / 2).
    let half = libm::sin(0.5 * y);
    let numerator = [libm::expm1(x) * libm::cos(y) - 2.0 * half * half, libm::exp(x) * libm::sin(y)];
    div(numerator, s)
}

/// The first `N` terms of `sum s^k / (k + 1)!`, by Horner's rule.
#[inline]
fn series<const N: usize>(s: [f64; 2]) -> [f64; 2] {
    let mut r = [SERIES[N - 1], 0.0];
    for &c in SERIES[..N - 1].iter().rev() {
        r = mul(r, s);
        r[0] += c;
    }
    r
}

#[inline]
fn mul(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] * b[0] - a[1] * b[1], a[0] * b[1] + a[1] * b[0]]
}

/// `a / b` for complex numbers, `b` not 0. Where `|b|^2` or the numerator's products leave
/// the normal range (edges and velocities beyond about 1e150 or below 1e-150), both are
/// first scaled by the power of two that brings `b`'s larger part into [1, 2): exact, so the
/// quotient is the same at every scale.
#[inline]
fn div(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    let d = b[0] * b[0] + b[1] * b[1];
    let q = [(a[0] * b[0] + a[1] * b[1]) / d, (a[1] * b[0] - a[0] * b[1]) / d];
    let m = b[0].abs().max(b[1].abs());
    if (d.is_normal() && q[0].is_finite() && q[1].is_finite()) || m == 0.0 || !m.is_finite() {
        return q;
    }
    let k = -binary_exponent(m);
    let (a, b) = (a.map(|x| scale_by_power_of_two(x, k)), b.map(|x| scale_by_power_of_two(x, k)));
    let d = b[0] * b[0] + b[1] * b[1];
    [(a[0] * b[0] + a[1] * b[1]) / d, (a[1] * b[0] - a[0] * b[1]) / d]
}

/// The spiral step, eq. (16) with eq. (15) corrected (see the module documentation): writes
/// the new position of every vertex into `out`. Neighbours of `v`
/// are `neighbors(v)`; `field[v]` is the velocity of vertex v. `sums` (one per vertex: the
/// factors' sum and their count) is scratch. `s` is the same seen from either end of an edge, so each edge's factor is
/// computed once, for its lower-numbered end, and added to both ends.
pub fn spiral_step<'a>(
    positions: &[Point],
    field: &[[f64; 2]],
    neighbors: impl Fn(usize) -> &'a [u32],
    sums: &mut [[f64; 3]],
    out: &mut [Point],
) {
    sums.fill([0.0; 3]);
    for (v, (p, u)) in positions.iter().zip(field).enumerate() {
        for &w in neighbors(v) {
            let w = w as usize;
            if w <= v {
                continue;
            }
            let du = [u[0] - field[w][0], u[1] - field[w][1]];
            let dp = [p[0] - positions[w][0], p[1] - positions[w][1]];
            if dp == [0.0, 0.0] {
                // Two vertices at one place (a collapsed edge) have no spiral between them.
                continue;
            }
            let ratio = exp_ratio(div(du, dp));
            for end in [v, w] {
                sums[end][0] += ratio[0];
                sums[end][1] += ratio[1];
                sums[end][2] += 1.0;
            }
        }
    }
    for (((o, p), u), sum) in out.iter_mut().zip(positions).zip(field).zip(sums.iter()) {
        // A vertex without edges of positive length moves straight.
        let k = sum[2];
        let factor = if k == 0.0 { [1.0, 0.0] } else { [sum[0] / k, sum[1] / k] };
        let step = mul(*u, factor);
        *o = [p[0] + step[0], p[1] + step[1]];
    }
}

/// The linear step `p <- p + U` (the paper's ablation in Figure 8).
pub fn linear_step(positions: &[Point], field: &[[f64; 2]], out: &mut [Point]) {
    for ((o, p), u) in out.iter_mut().zip(positions).zip(field) {
        *o = [p[0] + u[0], p[1] + u[1]];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 2], b: [f64; 2], tol: f64) -> bool {
        (a[0] - b[0]).abs() <= tol && (a[1] - b[1]).abs() <= tol
    }

    #[test]
    fn exp_ratio_matches_the_definition_and_is_smooth_at_zero() {
        // Away from 0, compare with e^s = e^x (cos y + i sin y) directly.
        for s in [[0.5f64, 0.0], [0.0, 1.0], [-1.2, 0.7], [2.0, -3.0], [0.01, 0.02]] {
            let e = [s[0].exp() * s[1].cos() - 1.0, s[0].exp() * s[1].sin()];
            assert!(close(exp_ratio(s), div(e, s), 1e-13), "{s:?}");
        }
        assert_eq!(exp_ratio([0.0, 0.0]), [1.0, 0.0]);
        // Inside its radius (up to the edge, at every angle) the series equals the closed form.
        let closed = |s: [f64; 2]| {
            let e = [s[0].exp_m1() * s[1].cos() - 2.0 * (s[1] / 2.0).sin().powi(2), s[0].exp() * s[1].sin()];
            div(e, s)
        };
        for angle in [0.0f64, 0.7, 1.9, 3.0, std::f64::consts::PI, 4.4] {
            let s = [0.249_999_999 * angle.cos(), 0.249_999_999 * angle.sin()];
            assert!(close(exp_ratio(s), closed(s), 4e-16), "{s:?}");
        }
        // ... and so do the shorter series below |s| = 0.05 and 0.01, up to their edges.
        for angle in [0.3f64, 2.2, 4.0, 5.9] {
            for radius in [0.049_999_999, 0.009_999_999, 0.0012] {
                let s = [radius * angle.cos(), radius * angle.sin()];
                assert!(close(exp_ratio(s), closed(s), 4e-16), "{s:?}");
            }
        }
        for s in [[0.2f64, 0.1], [-0.1, -0.2], [0.0, 0.249], [1e-9, -2e-9]] {
            assert!(close(exp_ratio(s), closed(s), 4e-16), "{s:?}");
        }
        // Pure imaginary s = i a: (e^{ia} - 1) / (ia) has modulus |2 sin(a/2) / a|.
        let a: f64 = 0.3;
        let r = exp_ratio([0.0, a]);
        assert!((r[0].hypot(r[1]) - (2.0 * (a / 2.0).sin() / a).abs()).abs() < 1e-15);
    }

    #[test]
    fn rigid_field_step_is_an_exact_rotation() {
        let positions = [[0.0, 0.0], [1.0, 0.0], [0.3, 0.8], [1.4, 1.1]];
        let neighbors: [&[u32]; 4] = [&[1, 2], &[0, 2, 3], &[0, 1, 3], &[1, 2]];
        let (a, c, d) = (0.4, [0.5, -0.2], [0.1, 0.3]);
        // U = a i (p - c) + d; the motion is the rotation by a about c' = c + i d / a.
        let field: Vec<[f64; 2]> =
            positions.iter().map(|p| [-a * (p[1] - c[1]) + d[0], a * (p[0] - c[0]) + d[1]]).collect();
        let centre = [c[0] - d[1] / a, c[1] + d[0] / a];
        let mut out = [[0.0; 2]; 4];
        spiral_step(&positions, &field, |v| neighbors[v], &mut [[0.0; 3]; 4], &mut out);
        let (sin, cos) = a.sin_cos();
        for (p, q) in positions.iter().zip(out) {
            let r = [p[0] - centre[0], p[1] - centre[1]];
            let expected = [centre[0] + cos * r[0] - sin * r[1], centre[1] + sin * r[0] + cos * r[1]];
            assert!(close(q, expected, 1e-14), "{q:?} vs {expected:?}");
        }
    }
}
