//! Moving least squares (Schaefer et al. 2006) against its definition: rigid targets give
//! the rigid motion, similar ones the similarity, affine ones the affine map, handles land
//! on their targets, the result turns with the targets, and every vertex agrees with the
//! paper's formulas written out here in its matrix form (eqs. 5, 6 and 8, not the
//! deformer's complex numbers). Bad input is refused with nothing changed. Runs natively
//! and as wasm.

use akap::deform::{DeformError, Deformer, MethodOptions, MlsOptions, MlsVariant};
use akap::geometry::Point;
use akap::shapes::grid_mesh;
use akap::Mesh;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common::Rng;

const VARIANTS: [MlsVariant; 3] = [MlsVariant::Rigid, MlsVariant::Similarity, MlsVariant::Affine];

/// A 12 x 6 grid of unit squares with handles on five vertices, not on one line.
fn setup(variant: MlsVariant, alpha: f64) -> (Mesh, Deformer, Vec<u32>) {
    let mesh = grid_mesh(12, 6);
    let handles = vec![0, 12, 13 * 6, 13 * 6 + 12, 13 * 3 + 6];
    let mut deformer = Deformer::new(mesh.clone(), MlsOptions { variant, alpha }).unwrap();
    deformer.set_handle_vertices(&handles).unwrap();
    (mesh, deformer, handles)
}

/// Steps the deformer so that handle k goes to `targets[k]`.
fn drive(deformer: &mut Deformer, targets: &[Point]) {
    let velocities: Vec<[f64; 2]> =
        deformer.handle_positions().iter().zip(targets).map(|(p, q)| [q[0] - p[0], q[1] - p[1]]).collect();
    deformer.step(&velocities).unwrap();
}

fn close(a: Point, b: Point, tolerance: f64) {
    assert!((a[0] - b[0]).hypot(a[1] - b[1]) <= tolerance, "{a:?} against {b:?}");
}

#[test]
fn maps_of_each_class_are_reproduced() {
    let rigid = |p: Point| {
        let (s, c) = 0.7f64.sin_cos();
        [c * p[0] - s * p[1] + 3.0, s * p[0] + c * p[1] - 1.0]
    };
    let similar = |p: Point| {
        let q = rigid(p);
        [1.8 * q[0], 1.8 * q[1]]
    };
    let affine = |p: Point| [1.3 * p[0] + 0.4 * p[1] + 2.0, -0.2 * p[0] + 0.7 * p[1] - 5.0];
    type Case<'a> = (&'a str, &'a dyn Fn(Point) -> Point, &'a [MlsVariant]);
    let maps: [Case; 3] = [
        ("rigid", &rigid, &VARIANTS),
        ("similarity", &similar, &[MlsVariant::Similarity, MlsVariant::Affine]),
        ("affine", &affine, &[MlsVariant::Affine]),
    ];
    // Each variant reproduces the maps of its class (and rigid motions are in every class).
    for (name, map, variants) in maps {
        for &variant in variants {
            let (mesh, mut deformer, handles) = setup(variant, 1.0);
            let targets: Vec<Point> = handles.iter().map(|&h| map(mesh.positions()[h as usize])).collect();
            drive(&mut deformer, &targets);
            for (p, q) in mesh.positions().iter().zip(deformer.positions()) {
                close(*q, map(*p), 1e-11);
            }
            assert!(deformer.metrics().flipped == 0, "{name} {variant:?}");
        }
    }
}

#[test]
fn handles_land_on_their_targets_and_the_result_turns_with_them() {
    let mut rng = Rng::new(5);
    for variant in VARIANTS {
        for alpha in [0.5, 1.0, 2.0] {
            let (mesh, mut deformer, handles) = setup(variant, alpha);
            let targets: Vec<Point> = handles
                .iter()
                .map(|&h| {
                    let p = mesh.positions()[h as usize];
                    [p[0] + (4.0 * rng.unit() - 2.0), p[1] + (4.0 * rng.unit() - 2.0)]
                })
                .collect();
            drive(&mut deformer, &targets);
            for (&h, q) in handles.iter().zip(&targets) {
                close(deformer.positions()[h as usize], *q, 1e-12);
            }
            // Rotation invariance: targets turned and moved turn and move the result alike.
            let turn = |p: Point| {
                let (s, c) = 2.1f64.sin_cos();
                [c * p[0] - s * p[1] - 4.0, s * p[0] + c * p[1] + 7.0]
            };
            let before = deformer.positions().to_vec();
            let (_, mut turned, _) = setup(variant, alpha);
            drive(&mut turned, &targets.iter().map(|&q| turn(q)).collect::<Vec<_>>());
            for (p, q) in before.iter().zip(turned.positions()) {
                close(*q, turn(*p), 1e-10);
            }
        }
    }
}

/// The paper's deformations at `v`, in its notation: row vectors, weights
/// `w_i = |p_i - v|^(-2 alpha)`, centroids `p*`, `q*`, hatted points.
fn paper(variant: MlsVariant, alpha: f64, p: &[Point], q: &[Point], v: Point) -> Point {
    let w: Vec<f64> = p.iter().map(|pi| ((pi[0] - v[0]).powi(2) + (pi[1] - v[1]).powi(2)).powf(-alpha)).collect();
    let sw: f64 = w.iter().sum();
    let star = |x: &[Point]| {
        let s = x.iter().zip(&w).fold([0.0, 0.0], |a, (xi, wi)| [a[0] + wi * xi[0], a[1] + wi * xi[1]]);
        [s[0] / sw, s[1] / sw]
    };
    let (ps, qs) = (star(p), star(q));
    let ph: Vec<Point> = p.iter().map(|x| [x[0] - ps[0], x[1] - ps[1]]).collect();
    let qh: Vec<Point> = q.iter().map(|x| [x[0] - qs[0], x[1] - qs[1]]).collect();
    let vp = [v[0] - ps[0], v[1] - ps[1]];
    match variant {
        // Eq. 5: f_a(v) = (v - p*) (sum p^T w p^)^-1 sum w p^T q^ + q*.
        MlsVariant::Affine => {
            let mut m = [[0.0; 2]; 2];
            let mut n = [[0.0; 2]; 2];
            for i in 0..p.len() {
                for r in 0..2 {
                    for c in 0..2 {
                        m[r][c] += w[i] * ph[i][r] * ph[i][c];
                        n[r][c] += w[i] * ph[i][r] * qh[i][c];
                    }
                }
            }
            let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
            let inv = [[m[1][1] / det, -m[0][1] / det], [-m[1][0] / det, m[0][0] / det]];
            let row = [vp[0] * inv[0][0] + vp[1] * inv[1][0], vp[0] * inv[0][1] + vp[1] * inv[1][1]];
            [row[0] * n[0][0] + row[1] * n[1][0] + qs[0], row[0] * n[0][1] + row[1] * n[1][1] + qs[1]]
        }
        // Eqs. 6-8: A_i = w_i (p^_i; -p^_i_perp)(v - p*; -(v - p*)_perp)^T, f_s = sum q^_i
        // A_i / mu_s + q*, mu_s = sum w_i p^_i p^_i^T; f_r = |v - p*| f_vec / |f_vec| + q*.
        _ => {
            let neg_perp = |x: Point| [x[1], -x[0]];
            let v_rows = [vp, neg_perp(vp)];
            let mut f = [0.0; 2];
            let mut mu = 0.0;
            for i in 0..p.len() {
                let p_rows = [ph[i], neg_perp(ph[i])];
                // A_i = w_i P V^T: A[r][c] = w_i sum_k P[r][k] V[c][k]; f_vec = sum q^_i A_i.
                let a = |r: usize, c: usize| w[i] * (p_rows[r][0] * v_rows[c][0] + p_rows[r][1] * v_rows[c][1]);
                f[0] += qh[i][0] * a(0, 0) + qh[i][1] * a(1, 0);
                f[1] += qh[i][0] * a(0, 1) + qh[i][1] * a(1, 1);
                mu += w[i] * (ph[i][0] * ph[i][0] + ph[i][1] * ph[i][1]);
            }
            if variant == MlsVariant::Similarity {
                [f[0] / mu + qs[0], f[1] / mu + qs[1]]
            } else {
                let (len, flen) = (vp[0].hypot(vp[1]), f[0].hypot(f[1]));
                [len * f[0] / flen + qs[0], len * f[1] / flen + qs[1]]
            }
        }
    }
}

#[test]
fn every_vertex_agrees_with_the_papers_formulas() {
    let mut rng = Rng::new(11);
    for variant in VARIANTS {
        for alpha in [0.5, 1.0, 1.5] {
            let mesh = grid_mesh(12, 6);
            let mut deformer = Deformer::new(mesh.clone(), MlsOptions { variant, alpha }).unwrap();
            // Handles at points inside triangles, so that no vertex sits on one.
            let triangles = [3u32, 40, 77, 101, 130, 60];
            let barycentric: Vec<[f64; 3]> = triangles.iter().map(|_| [0.2, 0.3, 0.5]).collect();
            deformer.set_handle_points(&triangles, &barycentric).unwrap();
            let rest = deformer.handle_positions();
            let targets: Vec<Point> =
                rest.iter().map(|p| [p[0] + (6.0 * rng.unit() - 3.0), p[1] + (6.0 * rng.unit() - 3.0)]).collect();
            drive(&mut deformer, &targets);
            for (v, got) in mesh.positions().iter().zip(deformer.positions()) {
                close(*got, paper(variant, alpha, &rest, &targets, *v), 1e-9);
            }
        }
    }
}

#[test]
fn bad_input_changes_nothing() {
    let (mesh, mut deformer, _) = setup(MlsVariant::Rigid, 1.0);
    drive(&mut deformer, &[[0.0, 0.0], [12.0, 1.0], [0.0, 6.0], [12.0, 7.0], [6.0, 4.0]]);
    let pose = deformer.positions().to_vec();
    let nan = [[f64::NAN, 0.0], [0.0; 2], [0.0; 2], [0.0; 2], [0.0; 2]];
    assert_eq!(deformer.step(&nan), Err(DeformError::NonFiniteVelocity { handle: 0 }));
    assert!(matches!(deformer.step(&[[0.0; 2]]), Err(DeformError::Length { .. })));
    assert!(matches!(deformer.set_handle_vertices(&[0, 999]), Err(DeformError::VertexOutOfRange { .. })));
    assert_eq!(deformer.positions(), &pose[..]);
    // The affine map needs three handles not on one line: two handles are refused at the
    // step, with nothing moved; rigid and similarity maps take one handle as a translation.
    let mut affine = Deformer::new(mesh.clone(), MlsOptions::default().with_variant(MlsVariant::Affine)).unwrap();
    affine.set_handle_vertices(&[0, 12]).unwrap();
    let error = affine.step(&[[1.0, 0.0], [0.0, 1.0]]).unwrap_err();
    assert!(matches!(error, DeformError::TooFewHandles { .. }), "{error}");
    assert_eq!(affine.positions(), mesh.positions());
    let mut one = Deformer::new(mesh.clone(), MlsOptions::default()).unwrap();
    one.set_handle_vertices(&[5]).unwrap();
    one.step(&[[2.0, -1.0]]).unwrap();
    for (p, q) in mesh.positions().iter().zip(one.positions()) {
        close(*q, [p[0] + 2.0, p[1] - 1.0], 1e-12);
    }
    // Options out of range, and another method's options, are refused.
    for alpha in [0.0, 5.0, f64::NAN] {
        let options = MlsOptions::default().with_alpha(alpha);
        assert!(matches!(Deformer::new(mesh.clone(), options), Err(DeformError::InvalidOption { name: "alpha", .. })));
        assert!(deformer.set_options(options).is_err());
    }
    assert_eq!(deformer.options(), MethodOptions::Mls(MlsOptions::default()));
    let mut boxed = Deformer::new(mesh, MethodOptions::Mls(MlsOptions::default())).unwrap();
    assert!(matches!(
        boxed.set_method_options(MethodOptions::Akap(Default::default())),
        Err(DeformError::WrongMethod { .. })
    ));
}
