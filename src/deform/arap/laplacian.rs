//! ARAP's cotangent Laplacian from per-triangle weights, and the handles' penalty weight
//! scaled to it: what the set-up ([`super::ArapDeformer`]'s constructor) and a new
//! stiffness or bones (`weights`) build the matrix from.

/// Penalty weight of handles inside triangles, relative to the mean diagonal of `L`.
const PENALTY: f64 = 1e6;

/// The cotangent Laplacian of the per-triangle weights `cot` on the pattern (`nnz`
/// entries, `triangle_slots` per triangle, `diagonal(v)` the slot of `(v, v)` for the `n`
/// vertices), and the handles' penalty weight for it: [`PENALTY`] times its mean diagonal
/// entry.
pub(super) fn laplacian_of(
    cot: &[[f64; 3]],
    triangle_slots: &[[usize; 9]],
    nnz: usize,
    n: usize,
    diagonal: impl Fn(usize) -> usize,
) -> (Vec<f64>, f64) {
    let mut laplacian = vec![0.0; nnz];
    for (c, s) in cot.iter().zip(triangle_slots) {
        for (k, &weight) in c.iter().enumerate() {
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            laplacian[s[3 * i + i]] += weight;
            laplacian[s[3 * j + j]] += weight;
            laplacian[s[3 * i + j]] -= weight;
            laplacian[s[3 * j + i]] -= weight;
        }
    }
    let diagonal_sum: f64 = (0..n).map(|v| laplacian[diagonal(v)]).sum();
    (laplacian, PENALTY * diagonal_sum / n as f64)
}
