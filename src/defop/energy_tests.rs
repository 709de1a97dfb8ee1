//! The densities, their derivatives and the signed SVD against the mathematics: rotations
//! cost nothing, uniform scalings cost what eqs. (10)-(11) give, S-ARAP is symmetric under
//! inversion, ARAP is the distance to the nearest rotation (by brute force over a grid),
//! the SVD matches nalgebra's up to the sign convention, and derivatives match central
//! differences.

use nalgebra::{Matrix2, Matrix4};

use super::*;

/// A small deterministic generator of uniform numbers in `[lo, hi)`.
struct Rng(u64);

impl Rng {
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        lo + (hi - lo) * ((self.0 >> 11) as f64 / (1u64 << 53) as f64)
    }

    fn jacobian(&mut self) -> Jacobian {
        [[self.uniform(-2.0, 2.0), self.uniform(-2.0, 2.0)], [self.uniform(-2.0, 2.0), self.uniform(-2.0, 2.0)]]
    }

    /// A Jacobian with `det > 0`, away from the S-ARAP kink (`R` not tiny) and from
    /// near-collapse.
    fn positive(&mut self) -> Jacobian {
        loop {
            let j = self.jacobian();
            let s = SignedSvd::new(&j);
            if s.sigma_2 > 0.2 && s.r > 0.05 && s.sigma_1 < 2.5 {
                return j;
            }
        }
    }
}

fn rotation(angle: f64) -> Jacobian {
    let (s, c) = angle.sin_cos();
    [[c, -s], [s, c]]
}

fn flat(j: &Jacobian) -> [f64; 4] {
    [j[0][0], j[0][1], j[1][0], j[1][1]]
}

fn unflat(v: [f64; 4]) -> Jacobian {
    [[v[0], v[1]], [v[2], v[3]]]
}

const ENERGIES: [Energy; 2] = [Energy::Arap, Energy::SArap];

#[test]
fn rotations_cost_nothing() {
    for k in 0..40 {
        let j = rotation(-3.1 + 0.157 * k as f64);
        for energy in ENERGIES {
            assert!(energy.density(&j) < 1e-28, "{energy} {j:?}: {}", energy.density(&j));
            let g = energy.gradient(&j).unwrap();
            assert!(flat(&g).iter().all(|x| x.abs() < 1e-14), "{energy} {g:?}");
        }
    }
}

#[test]
fn uniform_scalings_cost_what_the_equations_give() {
    for s in [0.1, 0.5, 0.9, 1.0, 1.3, 2.0, 7.5] {
        for angle in [0.0, 0.7, -2.0] {
            let r = rotation(angle);
            let j = [[s * r[0][0], s * r[0][1]], [s * r[1][0], s * r[1][1]]];
            let arap = 2.0 * (s - 1.0) * (s - 1.0);
            let sarap = (s - 1.0) * (s - 1.0) + (1.0 / s - 1.0) * (1.0 / s - 1.0);
            assert!((Energy::Arap.density(&j) - arap).abs() <= 1e-13 * (1.0 + arap), "s = {s}");
            assert!((Energy::SArap.density(&j) - sarap).abs() <= 1e-13 * (1.0 + sarap), "s = {s}");
        }
    }
    // S-ARAP is infinite on flipped and collapsed maps, ARAP is not.
    let flipped = [[1.0, 0.0], [0.0, -0.5]];
    assert_eq!(Energy::SArap.density(&flipped), f64::INFINITY);
    assert_eq!(Energy::SArap.density(&[[1.0, 2.0], [0.5, 1.0]]), f64::INFINITY);
    // ARAP of diag(1, -1/2) with signed σ: (1 - 1)^2 + (-1/2 - 1)^2.
    assert!((Energy::Arap.density(&flipped) - 2.25).abs() < 1e-15);
    assert!(Energy::SArap.gradient(&flipped).is_none() && Energy::SArap.hessian(&flipped, true).is_none());
}

#[test]
fn s_arap_is_symmetric_under_inversion() {
    let mut rng = Rng(1);
    for _ in 0..2000 {
        let j = rng.jacobian();
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        if det < 1e-3 {
            continue;
        }
        let inverse = [[j[1][1] / det, -j[0][1] / det], [-j[1][0] / det, j[0][0] / det]];
        let (a, b) = (Energy::SArap.density(&j), Energy::SArap.density(&inverse));
        assert!((a - b).abs() <= 1e-12 * a.max(1.0), "{j:?}: {a} vs {b}");
    }
}

#[test]
fn signed_svd_matches_nalgebra_up_to_the_sign_convention() {
    let mut rng = Rng(2);
    for _ in 0..2000 {
        let j = rng.jacobian();
        let s = SignedSvd::new(&j);
        let svd = Matrix2::new(j[0][0], j[0][1], j[1][0], j[1][1]).svd(false, false);
        let (big, small) = (svd.singular_values.max(), svd.singular_values.min());
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        // Sign fix: nalgebra's singular values are non-negative; ours carries sign(det).
        assert!((s.sigma_1 - big).abs() <= 1e-13 * big, "{j:?}");
        assert!((s.sigma_2 - small * det.signum()).abs() <= 1e-13 * big, "{j:?}");
        // U diag(Σ, σ) V^T rebuilds J, with U and V rotations.
        let (u, v) = (rotation(s.u_angle()), rotation(s.v_angle()));
        for r in 0..2 {
            for c in 0..2 {
                let x = u[r][0] * s.sigma_1 * v[c][0] + u[r][1] * s.sigma_2 * v[c][1];
                assert!((x - j[r][c]).abs() <= 1e-13 * big.max(1.0), "{j:?} entry {r}{c}");
            }
        }
    }
}

#[test]
fn arap_is_the_distance_to_the_nearest_rotation() {
    let mut rng = Rng(3);
    let steps = 20_000;
    let delta = std::f64::consts::TAU / steps as f64;
    for _ in 0..40 {
        let j = rng.jacobian();
        let best = (0..steps)
            .map(|k| {
                let r = rotation(k as f64 * delta);
                (0..2).flat_map(|a| (0..2).map(move |b| (a, b))).map(|(a, b)| (j[a][b] - r[a][b]).powi(2)).sum::<f64>()
            })
            .fold(f64::INFINITY, f64::min);
        let psi = Energy::Arap.density(&j);
        // |J - R(θ)|^2 = |J|^2 + 2 - 4Q cos(θ - θ_Q): the grid is off by at most Q δ^2 / 2.
        let q = SignedSvd::new(&j).q;
        assert!(best >= psi - 1e-12 && best <= psi + q * delta * delta, "{j:?}: grid {best}, density {psi}");
    }
}

/// Central differences of `f` at `x` in each of the 4 directions.
fn central(f: impl Fn(&[f64; 4]) -> f64, x: [f64; 4], step: f64) -> [f64; 4] {
    std::array::from_fn(|k| {
        let (mut plus, mut minus) = (x, x);
        plus[k] += step;
        minus[k] -= step;
        (f(&plus) - f(&minus)) / (2.0 * step)
    })
}

fn assert_close(found: &[f64], expected: &[f64], relative: f64, what: &str) {
    let scale = expected.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    for (a, b) in found.iter().zip(expected) {
        assert!((a - b).abs() <= relative * scale, "{what}: {found:?} vs {expected:?}");
    }
}

#[test]
fn gradients_match_central_differences() {
    let mut rng = Rng(4);
    for energy in ENERGIES {
        for _ in 0..300 {
            let j = if energy == Energy::Arap { rng.jacobian() } else { rng.positive() };
            let g = flat(&energy.gradient(&j).unwrap());
            let fd = central(|v| energy.density(&unflat(*v)), flat(&j), 1e-6);
            assert_close(&g, &fd, 1e-6, &format!("{energy} at {j:?}"));
        }
    }
}

/// The Hessian by central differences of the analytic gradient.
fn hessian_by_differences(energy: Energy, j: &Jacobian) -> [[f64; 4]; 4] {
    let x = flat(j);
    let mut h = [[0.0; 4]; 4];
    for (k, row) in h.iter_mut().enumerate() {
        let (mut plus, mut minus) = (x, x);
        plus[k] += 1e-6;
        minus[k] -= 1e-6;
        let (gp, gm) =
            (flat(&energy.gradient(&unflat(plus)).unwrap()), flat(&energy.gradient(&unflat(minus)).unwrap()));
        for (l, entry) in row.iter_mut().enumerate() {
            *entry = (gp[l] - gm[l]) / 2e-6;
        }
    }
    h
}

fn smallest_eigenvalue(h: &[[f64; 4]; 4]) -> f64 {
    Matrix4::from_fn(|r, c| h[r][c]).symmetric_eigen().eigenvalues.min()
}

#[test]
fn hessians_match_differences_and_projection_is_psd() {
    let mut rng = Rng(5);
    let mut already_psd = 0;
    for energy in ENERGIES {
        for _ in 0..300 {
            let j = if energy == Energy::Arap { rng.jacobian() } else { rng.positive() };
            let fd = hessian_by_differences(energy, &j);
            let exact = energy.hessian(&j, false).unwrap();
            let projected = energy.hessian(&j, true).unwrap();
            assert_close(exact.as_flattened(), fd.as_flattened(), 1e-6, &format!("{energy} exact at {j:?}"));
            let scale = fd.as_flattened().iter().fold(1.0f64, |m, x| m.max(x.abs()));
            assert!(smallest_eigenvalue(&projected) >= -1e-12 * scale, "{energy} projected at {j:?}");
            if smallest_eigenvalue(&fd) > 1e-6 * scale {
                already_psd += 1;
                assert_close(projected.as_flattened(), fd.as_flattened(), 1e-6, &format!("{energy} psd at {j:?}"));
            }
        }
    }
    assert!(already_psd > 50, "only {already_psd} samples were already positive definite");
}

#[test]
fn eigenvectors_are_orthonormal_eigenvectors() {
    let mut rng = Rng(6);
    for energy in ENERGIES {
        for _ in 0..100 {
            let j = if energy == Energy::Arap { rng.jacobian() } else { rng.positive() };
            let modes = energy.eigensystem(&j).unwrap();
            let fd = hessian_by_differences(energy, &j);
            for (a, (lambda, v)) in modes.iter().enumerate() {
                for (b, (_, w)) in modes.iter().enumerate() {
                    let dot: f64 = v.iter().zip(w).map(|(x, y)| x * y).sum();
                    assert!((dot - f64::from(u8::from(a == b))).abs() < 1e-12);
                }
                let hv: Vec<f64> = fd.iter().map(|row| row.iter().zip(v).map(|(x, y)| x * y).sum()).collect();
                let lv: Vec<f64> = v.iter().map(|x| lambda * x).collect();
                assert_close(&hv, &lv, 1e-5, &format!("{energy} mode {a} at {j:?}"));
            }
        }
    }
}

/// A random counter-clockwise rest triangle and a deformed copy.
fn triangle(rng: &mut Rng, flip_free: bool) -> (RestTriangle, [Point; 3]) {
    loop {
        let rest: [Point; 3] = std::array::from_fn(|_| [rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)]);
        let Some(t) = RestTriangle::new(rest) else { continue };
        if t.area < 0.1 {
            continue;
        }
        let p = rest.map(|x| [x[0] + rng.uniform(-0.3, 0.3), x[1] + rng.uniform(-0.3, 0.3)]);
        let s = SignedSvd::new(&t.jacobian(p));
        if !flip_free || (s.sigma_2 > 0.2 && s.r > 0.05) {
            return (t, p);
        }
    }
}

fn perturbed(p: [Point; 3], k: usize, h: f64) -> [Point; 3] {
    let mut q = p;
    q[k / 2][k % 2] += h;
    q
}

#[test]
fn vertex_gradient_and_hessian_match_differences_of_the_triangle_energy() {
    let mut rng = Rng(7);
    for energy in ENERGIES {
        for _ in 0..200 {
            let (t, p) = triangle(&mut rng, energy == Energy::SArap);
            // The rest triangle maps to itself with J = I.
            let j = t.jacobian(p);
            let g = t.gradient(energy, p).unwrap();
            let fd: Vec<f64> = (0..6)
                .map(|k| (t.energy(energy, perturbed(p, k, 1e-6)) - t.energy(energy, perturbed(p, k, -1e-6))) / 2e-6)
                .collect();
            assert_close(&g, &fd, 1e-6, &format!("{energy} gradient at {j:?}"));
            let h = t.hessian(energy, p, false).unwrap();
            // Row k of the (symmetric) Hessian against differences of the gradient along k.
            for (k, row) in h.iter().enumerate() {
                let (gp, gm) = (
                    t.gradient(energy, perturbed(p, k, 1e-6)).unwrap(),
                    t.gradient(energy, perturbed(p, k, -1e-6)).unwrap(),
                );
                let column: Vec<f64> = (0..6).map(|l| (gp[l] - gm[l]) / 2e-6).collect();
                assert_close(row, &column, 1e-6, &format!("{energy} Hessian row {k}"));
            }
            // Translations are in the kernel of the projected vertex Hessian.
            let hp = t.hessian(energy, p, true).unwrap();
            for axis in 0..2 {
                for row in &hp {
                    let sum: f64 = (0..3).map(|v| row[2 * v + axis]).sum();
                    assert!(sum.abs() < 1e-9 * row.iter().fold(1.0f64, |m, x| m.max(x.abs())));
                }
            }
        }
    }
    // The rest pose: zero energy and zero gradient.
    let rest = [[0.0, 0.0], [1.0, 0.2], [0.3, 0.9]];
    let t = RestTriangle::new(rest).unwrap();
    for energy in ENERGIES {
        assert!(t.energy(energy, rest) < 1e-28);
        assert!(t.gradient(energy, rest).unwrap().iter().all(|x| x.abs() < 1e-14));
    }
    assert!(RestTriangle::new([[0.0, 0.0], [0.3, 0.9], [1.0, 0.2]]).is_none(), "clockwise");
}

#[test]
fn the_held_model_has_the_gradient_of_its_density() {
    let mut rng = Rng(8);
    let mut checked = 0;
    while checked < 200 {
        let j = rng.jacobian();
        let Some((kappa, r)) = Energy::SArap.kink(&j) else { continue };
        // Near the kink, where the solver holds triangles, but not so near that the penalty's
        // curvature K swamps the differences.
        if r > kappa / 2.0 || r < 1e-3 || SignedSvd::new(&j).sigma_2 < 0.2 {
            continue;
        }
        let (_, g, _) = Energy::SArap.held(&j).unwrap();
        let fd = central(|v| Energy::SArap.held(&unflat(*v)).unwrap().0, flat(&j), 1e-7);
        assert_close(&flat(&g), &fd, 1e-6, &format!("held at {j:?}"));
        checked += 1;
    }
}
