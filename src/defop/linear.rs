//! Small dense helpers of the ground-truth solver: Cholesky of a few-by-few symmetric
//! positive definite matrix (the constraint Schur complement and Gram matrix), and the
//! first positive root of a quadratic (the S-ARAP flip cap).

/// In-place Cholesky `A = L L^T` of the row-major `n x n` matrix `a` (its lower triangle
/// becomes `L`). A pivot that is not above `1e-12` times its column's original diagonal
/// (or not finite) fails with that column.
pub(super) fn cholesky(a: &mut [f64], n: usize) -> Result<(), usize> {
    for j in 0..n {
        let original = a[j * n + j];
        let mut d = original;
        for k in 0..j {
            d -= a[j * n + k] * a[j * n + k];
        }
        let positive = d > 1e-12 * original.abs() && d.is_finite();
        if !positive {
            return Err(j);
        }
        let d = d.sqrt();
        a[j * n + j] = d;
        for i in j + 1..n {
            let mut s = a[i * n + j];
            for k in 0..j {
                s -= a[i * n + k] * a[j * n + k];
            }
            a[i * n + j] = s / d;
        }
    }
    Ok(())
}

/// Solves `L L^T x = b` in place with the factor of [`cholesky`].
pub(super) fn cholesky_solve(l: &[f64], n: usize, b: &mut [f64]) {
    for i in 0..n {
        let s: f64 = (0..i).map(|k| l[i * n + k] * b[k]).sum();
        b[i] = (b[i] - s) / l[i * n + i];
    }
    for i in (0..n).rev() {
        let s: f64 = (i + 1..n).map(|k| l[k * n + i] * b[k]).sum();
        b[i] = (b[i] - s) / l[i * n + i];
    }
}

/// The smallest `α > 0` with `c0 + c1 α + c2 α^2 = 0` (`+∞` if none), for `c0 > 0`; 0 when
/// `c0 <= 0` (the start is already flipped or collapsed). Roots by the cancellation-free
/// pair `q / c2`, `c0 / q`.
pub(super) fn first_root(c0: f64, c1: f64, c2: f64) -> f64 {
    if c0.is_nan() || c0 <= 0.0 {
        return 0.0;
    }
    if c2 == 0.0 {
        return if c1 < 0.0 { -c0 / c1 } else { f64::INFINITY };
    }
    let disc = c1 * c1 - 4.0 * c2 * c0;
    if disc < 0.0 {
        return f64::INFINITY;
    }
    let q = -0.5 * (c1 + disc.sqrt().copysign(c1));
    let mut best = f64::INFINITY;
    for root in [q / c2, c0 / q] {
        if root > 0.0 && root < best {
            best = root;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_root_is_the_smallest_positive_root() {
        // (1 - α)(1 - α/3) = 1 - 4/3 α + 1/3 α^2.
        assert!((first_root(1.0, -4.0 / 3.0, 1.0 / 3.0) - 1.0).abs() < 1e-15);
        // 1 - 2α: one root at 1/2.
        assert_eq!(first_root(1.0, -2.0, 0.0), 0.5);
        // 1 + α^2 and 1 + α: none.
        assert_eq!(first_root(1.0, 0.0, 1.0), f64::INFINITY);
        assert_eq!(first_root(1.0, 1.0, 0.0), f64::INFINITY);
        // 1 - α^2 / 4: root 2 (the negative one is ignored).
        assert!((first_root(1.0, 0.0, -0.25) - 2.0).abs() < 1e-15);
        // A tiny quadratic term: the root is near -c0/c1 without cancellation.
        assert!((first_root(1.0, -1.0, 1e-20) - 1.0).abs() < 1e-15);
        assert_eq!(first_root(0.0, -1.0, 0.0), 0.0);
    }

    #[test]
    fn cholesky_solves_and_refuses_singular_matrices() {
        // A = [[4, 2], [2, 3]], b = A (1, -2) = (0, -4).
        let mut a = vec![4.0, 2.0, 2.0, 3.0];
        cholesky(&mut a, 2).unwrap();
        let mut b = vec![0.0, -4.0];
        cholesky_solve(&a, 2, &mut b);
        assert!((b[0] - 1.0).abs() < 1e-15 && (b[1] + 2.0).abs() < 1e-15);
        let mut singular = vec![1.0, 1.0, 1.0, 1.0];
        assert_eq!(cholesky(&mut singular, 2), Err(1));
    }
}
