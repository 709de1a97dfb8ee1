//! Handle coordinates of a DefOp fit (src/defop/coordinates.rs; notes item 13). Canonical:
//! for every handle basis and both spatial bases, a rigid motion (R, t) of the rest handles
//! gives the rigid motion of the shape, D(x, RP + t) = Rx + t (which an operator without
//! the option misses by far: the samples' ground truth is not rigid-equivariant), the rest
//! pose is exact, the handles are hit at 1000 far targets, D(x, RQ + t) = R D(x, Q) + t for
//! any Q, and |Ψ| counts k = 2n − 3 coordinates; one canonical handle gives a translation.
//! Fixed handles: they stay at rest whatever their targets, the other handles are hit,
//! |Ψ| counts k = 2(n − #fixed); bad combinations are typed errors. Runs natively and as
//! wasm.

use std::f64::consts::PI;

use akap::defop::{fit, BasisKind, FitError, FitOptions, Operator, SpatialBasis};
use akap::Mesh;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common::Rng;
use crate::defop_fit::{
    diagonal, disc_targets, grid, max_difference, rest_of, samples_of, shepard, vertex_handles, KINDS,
};

/// `count` rigid motions (θ, t): θ uniform in [−π, π), t in the square of side 10.
fn motions(rng: &mut Rng, count: usize) -> Vec<(f64, [f64; 2])> {
    (0..count).map(|_| (PI * (2.0 * rng.unit() - 1.0), [10.0 * rng.unit() - 5.0, 10.0 * rng.unit() - 5.0])).collect()
}

/// Every point of `flat` (x, y interleaved) rotated by θ about the origin, then shifted by t.
fn moved(flat: &[f64], (theta, t): (f64, [f64; 2])) -> Vec<f64> {
    let (s, c) = theta.sin_cos();
    flat.chunks_exact(2).flat_map(|p| [c * p[0] - s * p[1] + t[0], s * p[0] + c * p[1] + t[1]]).collect()
}

/// The spatial bases of the fit tests: hat functions and an M-orthonormalised basis.
fn spatial_bases(mesh: &Mesh) -> Vec<SpatialBasis> {
    let extra: Vec<Vec<f64>> = (1..13)
        .map(|k| {
            mesh.positions().iter().map(|p| (0.7 * k as f64 * p[0] + 0.3 * p[1] * p[1] / k as f64).sin()).collect()
        })
        .collect();
    vec![SpatialBasis::hat(mesh), SpatialBasis::orthonormalised(mesh, &extra).unwrap()]
}

/// The largest distance over `motions` between D(x, RP + t) and Rx + t.
fn rigid_error(operator: &mut Operator, identity: &[f64], rest: &[f64], motions: &[(f64, [f64; 2])]) -> f64 {
    motions
        .iter()
        .map(|&motion| max_difference(&operator.evaluate(&moved(rest, motion)).unwrap(), &moved(identity, motion)))
        .fold(0.0, f64::max)
}

#[test]
fn canonical_operators_move_rigidly_with_their_handles() {
    let (mesh, vertices) = grid();
    let handles = vertex_handles(&vertices);
    let rest = rest_of(&mesh, &vertices);
    let size = diagonal(&mesh);
    let identity: Vec<f64> = mesh.positions().iter().flatten().copied().collect();
    let mut rng = Rng::new(21);
    let targets = disc_targets(&mut rng, &rest, 0.5, 90);
    let positions: Vec<Vec<f64>> = targets.iter().map(|t| shepard(&mesh, &vertices, t)).collect();
    let samples = samples_of(&targets, &positions);
    let rigid = motions(&mut rng, 50);
    let far = disc_targets(&mut rng, &rest, 5.0, 1000);
    let random = disc_targets(&mut rng, &rest, 1.0, 20);
    // k = 2n − 3 = 3: 1 + k, 1 + k + k(k + 1)/2, C(k + 3, 3), 1 + k + m (m: samples and rest).
    let sizes = [4, 10, 20, 1 + 3 + 91];
    for spatial in spatial_bases(&mesh) {
        for (kind, expected) in KINDS.into_iter().zip(sizes) {
            let options = FitOptions::default().with_kind(kind);
            let what = format!("{kind:?}, |Φ| = {}", spatial.len());
            let mut plain = fit(&mesh, &spatial, &handles, &samples, &options).unwrap();
            let mut operator = fit(&mesh, &spatial, &handles, &samples, &options.with_canonical(true)).unwrap();
            assert_eq!(operator.handle_basis().len(), expected, "{what}");
            assert_eq!(operator.handle_basis().coordinate_count(), 3);
            // Without the option, the rigid motions are far off; with it, exact.
            let error = rigid_error(&mut plain, &identity, &rest, &rigid);
            assert!(error > 1e-3 * size, "{what}: without the option, rigid motions off by only {error:e}");
            let error = rigid_error(&mut operator, &identity, &rest, &rigid);
            assert!(error <= 1e-9 * size, "{what}: rigid motions off by {error:e}");
            let error = max_difference(&operator.evaluate(&rest).unwrap(), &identity);
            assert!(error <= 1e-10 * size, "{what}: rest pose off by {error:e}");
            let mut worst: f64 = 0.0;
            for q in &far {
                let out = operator.evaluate(q).unwrap();
                for (l, &v) in vertices.iter().enumerate() {
                    worst = worst.max(max_difference(&out[2 * v..2 * v + 2], &q[2 * l..2 * l + 2]));
                }
            }
            assert!(worst <= 1e-9 * size, "{what}: handles missed by {worst:e}");
            for (q, &motion) in random.iter().zip(&rigid) {
                let expected = moved(&operator.evaluate(q).unwrap(), motion);
                let error = max_difference(&operator.evaluate(&moved(q, motion)).unwrap(), &expected);
                assert!(error <= 1e-9 * size, "{what}: not equivariant, off by {error:e}");
            }
            // The single-precision copy canonicalises as the operator does.
            let mut single = operator.single_precision();
            let mut out = vec![0.0f32; identity.len()];
            for (q, &motion) in random.iter().zip(&rigid) {
                let q = moved(q, motion);
                single.evaluate_into(&q, &mut out).unwrap();
                let wide: Vec<f64> = out.iter().map(|&x| f64::from(x)).collect();
                let error = max_difference(&wide, &operator.evaluate(&q).unwrap());
                assert!(error <= 1e-5 * size, "{what}: single precision off by {error:e}");
            }
        }
    }
}

/// One canonical handle has no coordinates left: the operator translates the shape with it.
#[test]
fn one_canonical_handle_translates() {
    let (mesh, _) = grid();
    let vertices = [14];
    let rest = rest_of(&mesh, &vertices);
    let identity: Vec<f64> = mesh.positions().iter().flatten().copied().collect();
    let mut rng = Rng::new(22);
    let targets = disc_targets(&mut rng, &rest, 0.5, 5);
    let positions: Vec<Vec<f64>> = targets.iter().map(|t| shepard(&mesh, &vertices, t)).collect();
    for kind in KINDS {
        let options = FitOptions::default().with_kind(kind).with_canonical(true);
        let mut operator = fit(
            &mesh,
            &SpatialBasis::hat(&mesh),
            &vertex_handles(&vertices),
            &samples_of(&targets, &positions),
            &options,
        )
        .unwrap();
        assert_eq!(operator.handle_basis().len(), 1, "{kind:?}");
        for q in disc_targets(&mut rng, &rest, 3.0, 10) {
            let expected = moved(&identity, (0.0, [q[0] - rest[0], q[1] - rest[1]]));
            assert!(max_difference(&operator.evaluate(&q).unwrap(), &expected) <= 1e-12 * diagonal(&mesh));
        }
    }
}

#[test]
fn fixed_handles_stay_at_rest() {
    let (mesh, vertices) = grid();
    let handles = vertex_handles(&vertices);
    let rest = rest_of(&mesh, &vertices);
    let size = diagonal(&mesh);
    let hold = |mut q: Vec<f64>| {
        q[..2].copy_from_slice(&rest[..2]);
        q
    };
    let mut rng = Rng::new(23);
    let targets: Vec<Vec<f64>> = disc_targets(&mut rng, &rest, 0.5, 40).into_iter().map(hold).collect();
    let positions: Vec<Vec<f64>> = targets.iter().map(|t| shepard(&mesh, &vertices, t)).collect();
    let samples = samples_of(&targets, &positions);
    let far = disc_targets(&mut rng, &rest, 5.0, 1000);
    // k = 2(n − 1) = 4: 1 + k, 1 + k + k(k + 1)/2, C(k + 3, 3), 1 + k + m.
    let sizes = [5, 15, 35, 1 + 4 + 41];
    for (kind, expected) in KINDS.into_iter().zip(sizes) {
        let options = FitOptions::default().with_kind(kind).with_fixed(vec![0]);
        let mut operator = fit(&mesh, &SpatialBasis::hat(&mesh), &handles, &samples, &options).unwrap();
        assert_eq!(operator.handle_basis().len(), expected, "{kind:?}");
        let mut worst: f64 = 0.0;
        for q in &far {
            let out = operator.evaluate(q).unwrap();
            // The fixed handle's target is ignored: the same pose as with it at rest.
            assert_eq!(out, operator.evaluate(&hold(q.clone())).unwrap(), "{kind:?}");
            worst = worst.max(max_difference(&out[2 * vertices[0]..2 * vertices[0] + 2], &rest[..2]));
            for (l, &v) in vertices.iter().enumerate().skip(1) {
                worst = worst.max(max_difference(&out[2 * v..2 * v + 2], &q[2 * l..2 * l + 2]));
            }
        }
        assert!(worst <= 1e-9 * size, "{kind:?}: handles off by {worst:e}");
    }
    let hat = SpatialBasis::hat(&mesh);
    let refused = |options: FitOptions, samples| fit(&mesh, &hat, &handles, samples, &options).map(|_| ()).unwrap_err();
    let base = FitOptions::default();
    assert_eq!(refused(base.clone().with_fixed(vec![0]).with_canonical(true), &samples), FitError::CanonicalWithFixed);
    assert_eq!(refused(base.clone().with_fixed(vec![3]), &samples), FitError::InvalidFixedHandle { index: 3 });
    assert_eq!(refused(base.clone().with_fixed(vec![1, 1]), &samples), FitError::InvalidFixedHandle { index: 1 });
    let moving = samples_of(&targets[..5], &positions[..5]);
    let mut moved_sample = moving.clone();
    let shifted: Vec<f64> = targets[3].iter().enumerate().map(|(i, x)| if i == 0 { x + 0.1 } else { *x }).collect();
    moved_sample[3].targets = &shifted;
    assert_eq!(refused(base.with_fixed(vec![0]), &moved_sample), FitError::FixedHandleMoved { sample: 3, handle: 0 });
    assert_eq!(BasisKind::Cubic.size_in(4, 0), 35);
}
