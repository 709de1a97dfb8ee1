//! Handle coordinates: the one linear map from handle targets to the coordinates the handle
//! basis Ψ is a function of, z = Bᵀ(Q̂ − P) / r_s, with B a 2n × k matrix of orthonormal
//! columns, and back, q̂_a = p_a + r_s (B z)_a (notes §1 and item 13). Three cases:
//!
//! - all coordinates (the paper's): B = I, k = 2n, Q̂ = Q;
//! - fixed handles: handles held at their rest position in every sample; their coordinates
//!   are left out of B (k = 2(n − #fixed)), so the targets given for them are ignored;
//! - canonical (notes item 13): Q̂ = R*ᵀ(Q − c_Q) + c_P, with c_P, c_Q the centroids of
//!   the rest handles and the targets and R* the rotation best aligning P − c_P to Q − c_Q
//!   (2D Procrustes in closed form: cos θ, sin θ ∝ Σ p′·q′, Σ p′ × q′; R* = I when both sums
//!   vanish, i.e. one handle or every target at one point). Then Σ(q̂ − p) = 0 and
//!   Σ (p − c_P) × (q̂ − p) = 0, so Q̂ − P lies in the orthogonal complement of the two
//!   translations and the infinitesimal rotation about c_P: k = 2n − 3 (n ≥ 2; 0 for one
//!   handle, whose operator is a translation). The operator evaluates
//!   D(x, Q) = R*(D̂(x, Q̂) − c_P) + c_Q: a rigid motion of all targets moves the result
//!   rigidly, exactly.
//!
//! B is B = E Q₂: E injects the free coordinates (all but the fixed handles') into R^{2n},
//! and Q₂ holds the last columns of the Householder QR factor Q = H_1 ⋯ H_c of the c
//! constraint directions (none; or t_x, t_y and, n ≥ 2, the rotation field r, normalised):
//! deterministic, computed from P alone, applied in O(n) without forming B. The reflector
//! of column j is v = x − α e_j normalised, α = −‖x‖ if x_j ≥ 0 else ‖x‖ (x: column j
//! below the diagonal after the previous reflectors), the textbook choice; the
//! TypeScript reader (`www/src/defop-file.ts`) repeats it.

use super::fit_error::{check_finite, FitError};

/// A rigid motion y = R(x − from) + to of the plane, R the rotation (cos, sin).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rigid {
    /// cos θ of the rotation.
    pub cos: f64,
    /// sin θ of the rotation.
    pub sin: f64,
    /// The point mapped to `to`.
    pub from: [f64; 2],
    /// Where `from` goes.
    pub to: [f64; 2],
}

impl Rigid {
    /// R(x − from) + to.
    pub fn apply(&self, x: [f64; 2]) -> [f64; 2] {
        let (dx, dy) = (x[0] - self.from[0], x[1] - self.from[1]);
        [self.cos * dx - self.sin * dy + self.to[0], self.sin * dx + self.cos * dy + self.to[1]]
    }

    /// The inverse: Rᵀ(y − to) + from.
    pub fn unapply(&self, y: [f64; 2]) -> [f64; 2] {
        let (dx, dy) = (y[0] - self.to[0], y[1] - self.to[1]);
        [self.cos * dx + self.sin * dy + self.from[0], -self.sin * dx + self.cos * dy + self.from[1]]
    }
}

/// The handle coordinates of an operator: its rest handles P and the map B (see the module
/// documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct HandleCoordinates {
    rest: Vec<f64>,
    canonical: bool,
    /// Fixed handles, ascending.
    fixed: Vec<usize>,
    /// The coordinates (indices into 2n) not fixed, ascending.
    free: Vec<usize>,
    /// Unit Householder vectors over the free coordinates, `free.len()` numbers each.
    reflectors: Vec<Vec<f64>>,
    /// v_r · v_s for s < r, `[r][s]`.
    gram: Vec<Vec<f64>>,
    /// The centroid c_P of the rest handles.
    centroid: [f64; 2],
}

impl HandleCoordinates {
    /// All 2n coordinates (B = I) around the rest handles `rest` (2n numbers).
    pub fn full(rest: &[f64]) -> Result<Self, FitError> {
        Self::new(rest, false, &[])
    }

    /// The coordinates around the rest handles `rest` (2n numbers), canonical or with the
    /// handles `fixed` (indices, any order) left out. Refuses canonical with fixed handles
    /// (a rigid motion moves them), a fixed index out of range or repeated, and, canonical,
    /// every rest handle at one point.
    pub fn new(rest: &[f64], canonical: bool, fixed: &[usize]) -> Result<Self, FitError> {
        if rest.is_empty() {
            return Err(FitError::NoHandles);
        }
        if !rest.len().is_multiple_of(2) {
            return Err(FitError::Length { what: "rest handles", expected: rest.len() + 1, found: rest.len() });
        }
        check_finite("rest handles", rest)?;
        let n = rest.len() / 2;
        if canonical && !fixed.is_empty() {
            return Err(FitError::CanonicalWithFixed);
        }
        let mut sorted = fixed.to_vec();
        sorted.sort_unstable();
        for (i, &a) in sorted.iter().enumerate() {
            if a >= n || (i > 0 && sorted[i - 1] == a) {
                return Err(FitError::InvalidFixedHandle { index: a });
            }
        }
        let free: Vec<usize> = (0..2 * n).filter(|c| sorted.binary_search(&(c / 2)).is_err()).collect();
        let inv_n = 1.0 / n as f64;
        let centroid = [0, 1].map(|nu| rest.iter().skip(nu).step_by(2).sum::<f64>() * inv_n);
        let mut columns: Vec<Vec<f64>> = Vec::new();
        if canonical {
            let s = inv_n.sqrt();
            columns.push((0..2 * n).map(|c| if c % 2 == 0 { s } else { 0.0 }).collect());
            columns.push((0..2 * n).map(|c| if c % 2 == 1 { s } else { 0.0 }).collect());
            if n >= 2 {
                let r: Vec<f64> =
                    rest.chunks_exact(2).flat_map(|p| [-(p[1] - centroid[1]), p[0] - centroid[0]]).collect();
                let norm = r.iter().map(|x| x * x).sum::<f64>().sqrt();
                if norm == 0.0 {
                    return Err(FitError::CoincidentHandles { first: 0, second: 1 });
                }
                columns.push(r.iter().map(|x| x / norm).collect());
            }
        }
        let reflectors = householder(&mut columns);
        let gram =
            (0..reflectors.len()).map(|r| (0..r).map(|s| dot(&reflectors[r], &reflectors[s])).collect()).collect();
        Ok(Self { rest: rest.to_vec(), canonical, fixed: sorted, free, reflectors, gram, centroid })
    }

    /// The rest handles P (2n numbers).
    pub fn rest(&self) -> &[f64] {
        &self.rest
    }

    /// Whether targets are canonicalised (rigid motions reproduced exactly).
    pub fn is_canonical(&self) -> bool {
        self.canonical
    }

    /// The fixed handles, ascending.
    pub fn fixed(&self) -> &[usize] {
        &self.fixed
    }

    /// The number of coordinates k.
    pub fn len(&self) -> usize {
        self.free.len() - self.reflectors.len()
    }

    /// Whether there is no coordinate (one canonical handle, or every handle fixed): the
    /// operator is then the rest pose, moved rigidly if canonical.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The number of coordinates k of `n` handles, canonical or with `fixed` handles fixed
    /// (what [`HandleCoordinates::new`] gives when it accepts them).
    pub fn count(n: usize, canonical: bool, fixed: usize) -> usize {
        let constraints = match (canonical, n) {
            (false, _) | (true, 0) => 0,
            (true, 1) => 2,
            (true, _) => 3,
        };
        (2 * n.saturating_sub(fixed)).saturating_sub(constraints)
    }

    /// Writes Bᵀ(targets − P) to `out` (k numbers); allocates nothing. `targets`: 2n numbers.
    pub(crate) fn project(&self, targets: &[f64], out: &mut [f64]) {
        self.transpose_times(|c| targets[c] - self.rest[c], out);
    }

    /// Row `a` of B (k numbers): q̂_a − p_a = r_s Σ_j B_aj z_j.
    pub fn row(&self, a: usize) -> Vec<f64> {
        let mut out = vec![0.0; self.len()];
        self.transpose_times(|c| f64::from(u8::from(c == a)), &mut out);
        out
    }

    /// Writes Bᵀ w to `out` for the vector w with entries `w(c)`, c < 2n: w restricted to
    /// the free coordinates, then H_c ⋯ H_1 applied as w − 2 Σ_r α_r v_r with
    /// α_r = v_r·w − 2 Σ_{s<r} α_s (v_r·v_s), and the first c entries dropped.
    fn transpose_times(&self, w: impl Fn(usize) -> f64, out: &mut [f64]) {
        let w = |i: usize| w(self.free[i]);
        let c = self.reflectors.len();
        let mut alpha = [0.0f64; 3];
        for (r, (v, gram)) in self.reflectors.iter().zip(&self.gram).enumerate() {
            let mut a: f64 = (r..v.len()).map(|i| v[i] * w(i)).sum();
            for (alpha_s, g) in alpha.iter().zip(gram) {
                a -= 2.0 * alpha_s * g;
            }
            alpha[r] = a;
        }
        for (j, value) in out.iter_mut().enumerate() {
            let i = c + j;
            let mut x = w(i);
            for (alpha_r, v) in alpha.iter().zip(&self.reflectors) {
                x -= 2.0 * alpha_r * v[i];
            }
            *value = x;
        }
    }

    /// For canonical coordinates, writes the canonical targets Q̂ to `out` (2n numbers) and
    /// returns the rigid motion from canonical to actual positions (R*, c_P, c_Q), else
    /// `None` and leaves `out` alone. Allocates nothing; `targets`: 2n finite numbers.
    pub fn canonicalise(&self, targets: &[f64], out: &mut [f64]) -> Option<Rigid> {
        if !self.canonical {
            return None;
        }
        let inv_n = 1.0 / (self.rest.len() / 2) as f64;
        let to = [0, 1].map(|nu| targets.iter().skip(nu).step_by(2).sum::<f64>() * inv_n);
        let from = self.centroid;
        let (mut dot, mut cross) = (0.0, 0.0);
        for (q, p) in targets.chunks_exact(2).zip(self.rest.chunks_exact(2)) {
            let (px, py, qx, qy) = (p[0] - from[0], p[1] - from[1], q[0] - to[0], q[1] - to[1]);
            dot += px * qx + py * qy;
            cross += px * qy - py * qx;
        }
        let h = dot.hypot(cross);
        let (cos, sin) = if h > 0.0 { (dot / h, cross / h) } else { (1.0, 0.0) };
        let rigid = Rigid { cos, sin, from, to };
        for ((o, q), p) in out.chunks_exact_mut(2).zip(targets.chunks_exact(2)).zip(self.rest.chunks_exact(2)) {
            // q̂ = p + (Rᵀ(q − c_Q) − (p − c_P)): exactly p when Q = P.
            let (qx, qy) = (q[0] - to[0], q[1] - to[1]);
            let d = [cos * qx + sin * qy - (p[0] - from[0]), -sin * qx + cos * qy - (p[1] - from[1])];
            o[0] = p[0] + d[0];
            o[1] = p[1] + d[1];
        }
        Some(rigid)
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The Householder vectors of the QR factorisation of `columns` (each as long as the
/// others), reducing them in place.
fn householder(columns: &mut [Vec<f64>]) -> Vec<Vec<f64>> {
    let mut reflectors = Vec::with_capacity(columns.len());
    for j in 0..columns.len() {
        let x = &columns[j];
        let sigma = x[j..].iter().map(|v| v * v).sum::<f64>().sqrt();
        let alpha = if x[j] >= 0.0 { -sigma } else { sigma };
        let mut v = x.clone();
        v[..j].fill(0.0);
        v[j] -= alpha;
        let norm = v[j..].iter().map(|a| a * a).sum::<f64>().sqrt();
        v[j..].iter_mut().for_each(|a| *a /= norm);
        for column in &mut columns[j + 1..] {
            let s = 2.0 * dot(&v[j..], &column[j..]);
            column[j..].iter_mut().zip(&v[j..]).for_each(|(c, vi)| *c -= s * vi);
        }
        reflectors.push(v);
    }
    reflectors
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lift(coordinates: &HandleCoordinates) -> Vec<Vec<f64>> {
        (0..coordinates.rest().len()).map(|a| coordinates.row(a)).collect()
    }

    /// B has orthonormal columns, spans the complement of the rigid directions (canonical)
    /// or of the fixed coordinates, and has the expected k.
    #[test]
    fn b_is_orthonormal_and_spans_the_right_subspace() {
        let rest = [0.3, -1.0, 2.0, 0.5, -0.7, 1.1, 1.4, 2.2];
        let n = rest.len() / 2;
        for (canonical, fixed, k) in [(false, vec![], 8), (true, vec![], 5), (false, vec![2, 0], 4)] {
            let coordinates = HandleCoordinates::new(&rest, canonical, &fixed).unwrap();
            assert_eq!(coordinates.len(), k);
            assert_eq!(HandleCoordinates::count(n, canonical, fixed.len()), k);
            let b = lift(&coordinates);
            for i in 0..k {
                for j in 0..k {
                    let g: f64 = b.iter().map(|row| row[i] * row[j]).sum();
                    assert!((g - f64::from(u8::from(i == j))).abs() < 1e-14, "BᵀB[{i}][{j}] = {g}");
                }
                let column: Vec<f64> = b.iter().map(|row| row[i]).collect();
                if canonical {
                    let (cx, cy) =
                        (rest.iter().step_by(2).sum::<f64>() / 4.0, rest.iter().skip(1).step_by(2).sum::<f64>() / 4.0);
                    let tx: f64 = column.iter().step_by(2).sum();
                    let ty: f64 = column.iter().skip(1).step_by(2).sum();
                    let rot: f64 = (0..n)
                        .map(|a| (rest[2 * a] - cx) * column[2 * a + 1] - (rest[2 * a + 1] - cy) * column[2 * a])
                        .sum();
                    assert!(tx.abs() < 1e-14 && ty.abs() < 1e-14 && rot.abs() < 1e-14);
                }
                for &a in &fixed {
                    assert_eq!([column[2 * a], column[2 * a + 1]], [0.0, 0.0]);
                }
            }
        }
        assert_eq!(HandleCoordinates::new(&rest, true, &[1]).unwrap_err(), FitError::CanonicalWithFixed);
        assert_eq!(HandleCoordinates::new(&rest, false, &[4]).unwrap_err(), FitError::InvalidFixedHandle { index: 4 });
        assert_eq!(
            HandleCoordinates::new(&rest, false, &[1, 1]).unwrap_err(),
            FitError::InvalidFixedHandle { index: 1 }
        );
        assert_eq!(HandleCoordinates::new(&[1.0, 2.0], true, &[]).unwrap().len(), 0);
    }

    /// A rigid motion of the rest handles canonicalises back to them, and the rigid motion
    /// returned is that motion; the rest handles canonicalise to themselves exactly.
    #[test]
    fn rigid_motions_canonicalise_to_the_rest_handles() {
        let rest = [0.3, -1.0, 2.0, 0.5, -0.7, 1.1];
        let coordinates = HandleCoordinates::new(&rest, true, &[]).unwrap();
        let mut out = [0.0; 6];
        let identity = coordinates.canonicalise(&rest, &mut out).unwrap();
        assert_eq!(out, rest);
        assert_eq!((identity.cos, identity.sin), (1.0, 0.0));
        for (theta, t) in [(0.7, [1.0, -2.0]), (-2.9, [0.0, 3.5]), (3.1, [-1e3, 2.0])] {
            let (s, c) = f64::sin_cos(theta);
            let moved: Vec<f64> =
                rest.chunks_exact(2).flat_map(|p| [c * p[0] - s * p[1] + t[0], s * p[0] + c * p[1] + t[1]]).collect();
            let rigid = coordinates.canonicalise(&moved, &mut out).unwrap();
            assert!((rigid.cos - c).abs() < 1e-14 && (rigid.sin - s).abs() < 1e-14);
            for (a, b) in out.iter().zip(&rest) {
                assert!((a - b).abs() < 1e-12, "{out:?}");
            }
            let back = rigid.apply([rest[0], rest[1]]);
            assert!((back[0] - moved[0]).abs() < 1e-12 && (back[1] - moved[1]).abs() < 1e-12);
            let there = rigid.unapply(back);
            assert!((there[0] - rest[0]).abs() < 1e-12 && (there[1] - rest[1]).abs() < 1e-12);
        }
        // Every target at one point: R = I, the canonical handles all at c_P.
        let rigid = coordinates.canonicalise(&[5.0, 5.0, 5.0, 5.0, 5.0, 5.0], &mut out).unwrap();
        assert_eq!((rigid.cos, rigid.sin), (1.0, 0.0));
    }
}
