//! Cauchy-Green coordinates (Weber, Ben-Chen and Gotsman 2009, "Complex barycentric
//! coordinates with applications to planar shape deformation", Section 3): the Cauchy
//! integral of the piecewise-linear function that takes the values `f_j` at the vertices
//! `z_j` of a polygon (the cage), `F(z) = 1/(2 pi i) oint g(w) / (w - z) dw`, in closed
//! form. With `A_j = z_j - z_(j-1)` and `B_j = z_j - z` (indices around the cage),
//!
//! `F(z) = sum_j C_j(z) f_j`, `C_j(z) = 1/(2 pi i) [B_(j+1)/A_(j+1) log(B_(j+1)/B_j) - B_(j-1)/A_j log(B_j/B_(j-1))]`,
//!
//! holomorphic inside the cage, and reproducing `a z + b` from the values `a z_j + b`.
//! Integrating by parts twice, its second derivative is rational:
//! `F''(z) = 1/(2 pi i) sum_j (f_(j+1) - f_j) / (B_j B_(j+1))`, finite everywhere but at the
//! cage's vertices (so also on its edges, where the smoothness term samples it). Points are
//! complex numbers `x + i y`; cages run counter-clockwise.

use nalgebra::Complex;

use crate::geometry::Point;

/// `x + i y`.
pub(crate) fn complex(p: Point) -> Complex<f64> {
    Complex::new(p[0], p[1])
}

/// `1 / (2 pi i) = -i / (2 pi)`.
const ONE_OVER_TWO_PI_I: Complex<f64> = Complex { re: 0.0, im: -0.5 / std::f64::consts::PI };

/// The Cauchy-Green coordinates of `z`, strictly inside the counter-clockwise polygon
/// `cage`, with respect to the cage's vertices, written to `out` (one per vertex): the
/// holomorphic map with cage values `f` takes `z` to `sum_j out[j] f_j`. They sum to 1 and
/// reproduce `z` (`sum_j out[j] z_j = z`). Outside the cage or on it they are not
/// coordinates of anything (the Cauchy integral jumps across the cage).
///
/// # Panics
/// If `out` does not have one entry per cage vertex.
pub fn coordinates(cage: &[Point], z: Point, out: &mut [Complex<f64>]) {
    assert_eq!(out.len(), cage.len(), "one coordinate per cage vertex");
    out.fill(Complex::new(0.0, 0.0));
    let n = cage.len();
    let b = |j: usize| [cage[j][0] - z[0], cage[j][1] - z[1]];
    // ln |B_j| once per vertex; each edge's log(B_(j+1)/B_j) from them and the angle the
    // edge subtends at z (within (-pi, pi) for a point inside, so the principal value).
    let mut ln_b_next = 0.5 * libm::log(b(0)[0] * b(0)[0] + b(0)[1] * b(0)[1]);
    let first = ln_b_next;
    for j in 0..n {
        let k = (j + 1) % n;
        let (bj, bk) = (b(j), b(k));
        let ln_bj = ln_b_next;
        ln_b_next = if k == 0 { first } else { 0.5 * libm::log(bk[0] * bk[0] + bk[1] * bk[1]) };
        let angle = libm::atan2(bj[0] * bk[1] - bj[1] * bk[0], bj[0] * bk[0] + bj[1] * bk[1]);
        let log = Complex::new(ln_b_next - ln_bj, angle);
        // The edge from z_j to z_k carries log(B_k/B_j)/A_k into C_j (times B_k) and C_k
        // (times -B_j).
        let term = log / complex([cage[k][0] - cage[j][0], cage[k][1] - cage[j][1]]);
        out[j] += complex(bk) * term;
        out[k] -= complex(bj) * term;
    }
    for c in out.iter_mut() {
        *c *= ONE_OVER_TWO_PI_I;
    }
}

/// The coefficients of the second derivative at `z` of the map with cage values `f`:
/// `F''(z) = sum_j out[j] f_j`, for `z` anywhere but a cage vertex (inside the cage, or on
/// an edge as the limit from inside). They vanish on the values of `a z + b`.
///
/// # Panics
/// If `out` does not have one entry per cage vertex.
pub fn second_derivative(cage: &[Point], z: Point, out: &mut [Complex<f64>]) {
    assert_eq!(out.len(), cage.len(), "one coefficient per cage vertex");
    out.fill(Complex::new(0.0, 0.0));
    let n = cage.len();
    for j in 0..n {
        let k = (j + 1) % n;
        let w = ONE_OVER_TWO_PI_I
            / (complex([cage[j][0] - z[0], cage[j][1] - z[1]]) * complex([cage[k][0] - z[0], cage[k][1] - z[1]]));
        out[k] += w;
        out[j] -= w;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn star() -> Vec<Point> {
        (0..9)
            .map(|k| {
                let t = k as f64 * std::f64::consts::TAU / 9.0;
                let r = if k % 2 == 0 { 3.0 } else { 1.6 };
                [r * t.cos() + 0.3, r * t.sin() - 0.2]
            })
            .collect()
    }

    #[test]
    fn reproduce_degree_one_maps_and_their_second_derivative_vanishes() {
        let cage = star();
        let (a, b) = (Complex::new(1.3, -0.8), Complex::new(-2.0, 0.5));
        let values: Vec<Complex<f64>> = cage.iter().map(|&z| a * complex(z) + b).collect();
        let mut c = vec![Complex::new(0.0, 0.0); cage.len()];
        for z in [[0.3, -0.2], [1.0, 0.4], [-0.9, -0.3]] {
            coordinates(&cage, z, &mut c);
            let image: Complex<f64> = c.iter().zip(&values).map(|(c, f)| c * f).sum();
            assert!((image - (a * complex(z) + b)).norm() < 1e-13, "{image} at {z:?}");
            second_derivative(&cage, z, &mut c);
            let curvature: Complex<f64> = c.iter().zip(&values).map(|(c, f)| c * f).sum();
            assert!(curvature.norm() < 1e-13, "{curvature}");
        }
    }
}
