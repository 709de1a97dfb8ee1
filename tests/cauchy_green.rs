//! Point-to-point Cauchy-Green deformation (Weber et al. 2009) against the mathematics: the
//! closed-form coordinates and second derivatives against the Cauchy integral summed by
//! quadrature here, similarities reproduced (so two handles give the similarity taking them
//! to their targets), triangles conformal up to the mesh's discretisation error, which
//! halves when the mesh is refined, and the point-to-point fit against a dense
//! least-squares solve written out here. Bad cages, options and velocities are refused
//! with nothing changed; sessions record the settings and replay the steps. Runs natively
//! and as wasm.

use akap::deform::cauchy::{coordinates, second_derivative};
use akap::deform::metrics::{deformation_gradient, singular_values};
use akap::deform::{CauchyGreenOptions, DeformError, Deformer, MethodOptions};
use akap::geometry::Point;
use akap::pose::replay;
use akap::session::{Event, Session};
use akap::shapes::grid_mesh;
use akap::Mesh;
use nalgebra::{Complex, DMatrix, DVector};
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common::Rng;

type C64 = Complex<f64>;

fn c(p: Point) -> C64 {
    Complex::new(p[0], p[1])
}

/// A star-shaped cage (not convex) around the origin.
fn star() -> Vec<Point> {
    (0..11)
        .map(|k| {
            let t = k as f64 * std::f64::consts::TAU / 11.0;
            let r = if k % 2 == 0 { 3.0 } else { 1.7 };
            [r * t.cos() + 0.2, r * t.sin() - 0.1]
        })
        .collect()
}

/// `1/(2 pi i) oint g(w) k(w - z) dw` for the piecewise-linear `g` with `values` at the
/// cage's vertices, by composite Simpson's rule on every edge.
fn cauchy_integral(cage: &[Point], values: &[C64], z: Point, kernel: impl Fn(C64) -> C64) -> C64 {
    let n = cage.len();
    let panels = 4000;
    let mut sum = Complex::new(0.0, 0.0);
    for j in 0..n {
        let (a, b) = (c(cage[j]), c(cage[(j + 1) % n]));
        let (fa, fb) = (values[j], values[(j + 1) % n]);
        let h = 1.0 / panels as f64;
        for i in 0..=panels {
            let t = i as f64 * h;
            let weight = if i == 0 || i == panels {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            let w = a + (b - a) * t;
            sum += (fa + (fb - fa) * t) * kernel(w - c(z)) * (b - a) * (weight * h / 3.0);
        }
    }
    sum / Complex::new(0.0, std::f64::consts::TAU)
}

#[test]
fn coordinates_and_second_derivatives_are_the_cauchy_integral() {
    let cage = star();
    let mut rng = Rng::new(3);
    let values: Vec<C64> = cage.iter().map(|_| Complex::new(rng.unit() * 4.0 - 2.0, rng.unit() * 4.0 - 2.0)).collect();
    let mut row = vec![Complex::new(0.0, 0.0); cage.len()];
    for z in [[0.2, -0.1], [0.9, 0.5], [-0.7, -0.6], [1.1, -0.2]] {
        coordinates(&cage, z, &mut row);
        let closed: C64 = row.iter().zip(&values).map(|(r, f)| r * f).sum();
        let quadrature = cauchy_integral(&cage, &values, z, |d| 1.0 / d);
        assert!((closed - quadrature).norm() < 1e-9, "F at {z:?}: {closed} against {quadrature}");
        second_derivative(&cage, z, &mut row);
        let closed: C64 = row.iter().zip(&values).map(|(r, f)| r * f).sum();
        let quadrature = cauchy_integral(&cage, &values, z, |d| 2.0 / (d * d * d));
        assert!((closed - quadrature).norm() < 1e-8, "F'' at {z:?}: {closed} against {quadrature}");
    }
}

/// A bar of 16 x 4 cells of side `1 / k` (so `k` refines it), with a cage of 40 vertices.
fn bar(k: usize) -> (Mesh, Deformer) {
    let mesh = grid_mesh(16 * k, 4 * k);
    let scale = 1.0 / k as f64;
    let mesh =
        Mesh::new(mesh.positions().iter().map(|p| [p[0] * scale, p[1] * scale]).collect(), mesh.triangles().to_vec())
            .unwrap();
    let deformer = Deformer::new(mesh.clone(), CauchyGreenOptions::default().with_cage(40)).unwrap();
    (mesh, deformer)
}

/// Steps the deformer so that every handle's target becomes `targets[k]`.
fn drive(deformer: &mut Deformer, targets: &[Point]) {
    let velocities: Vec<[f64; 2]> =
        deformer.handle_positions().iter().zip(targets).map(|(p, q)| [q[0] - p[0], q[1] - p[1]]).collect();
    deformer.step(&velocities).unwrap();
}

#[test]
fn similarities_are_reproduced_and_two_handles_give_the_similarity() {
    let (a, b) = (Complex::new(0.6, 0.9), Complex::new(-3.0, 2.0));
    let map = |p: Point| {
        let z = a * c(p) + b;
        [z.re, z.im]
    };
    for handles in [vec![0u32, 16], vec![0, 16, 84, 40, 50]] {
        let (mesh, mut deformer) = bar(1);
        deformer.set_handle_vertices(&handles).unwrap();
        let targets: Vec<Point> = handles.iter().map(|&h| map(mesh.positions()[h as usize])).collect();
        drive(&mut deformer, &targets);
        for (p, q) in mesh.positions().iter().zip(deformer.positions()) {
            let expected = map(*p);
            assert!((q[0] - expected[0]).hypot(q[1] - expected[1]) < 1e-9, "{q:?} against {expected:?}");
        }
    }
}

/// The largest `sigma_1 / sigma_2 - 1` over the triangles of the current pose.
fn worst_anisotropy(mesh: &Mesh, positions: &[Point]) -> f64 {
    mesh.triangles()
        .iter()
        .map(|t| {
            let f = deformation_gradient(t.map(|v| mesh.positions()[v as usize]), t.map(|v| positions[v as usize]));
            let (s1, s2, _) = singular_values(f[0][0], f[0][1], f[1][0], f[1][1]);
            s1 / s2 - 1.0
        })
        .fold(0.0, f64::max)
}

#[test]
fn the_map_is_conformal_up_to_the_mesh_and_refining_halves_the_error() {
    let mut errors = Vec::new();
    for k in [1, 2, 4] {
        let (mesh, mut deformer) = bar(k);
        // The left end held, the right end lifted and the middle of the top pushed down.
        let handles = [0, 4 * k * (16 * k + 1), 16 * k, (4 * k + 1) * (16 * k + 1) - 1, 4 * k * (16 * k + 1) + 8 * k];
        deformer.set_handle_vertices(&handles.map(|h| h as u32)).unwrap();
        let rest: Vec<Point> = handles.iter().map(|&h| mesh.positions()[h]).collect();
        let targets = [
            rest[0],
            rest[1],
            [rest[2][0] - 3.0, rest[2][1] + 6.0],
            [rest[3][0] - 4.0, rest[3][1] + 5.0],
            [rest[4][0], rest[4][1] - 0.5],
        ];
        drive(&mut deformer, &targets);
        assert_eq!(deformer.metrics().flipped, 0);
        errors.push(worst_anisotropy(&mesh, deformer.positions()));
    }
    // Linear interpolation of a conformal map: Jacobians off by O(h) (measured: 0.61, 0.32
    // and 0.17 for this strong bend).
    assert!(errors[2] < 0.2, "{errors:?}");
    for pair in errors.windows(2) {
        assert!(pair[1] < 0.6 * pair[0], "{errors:?}");
    }
}

#[test]
fn the_fit_is_the_dense_least_squares_solution() {
    let mesh = grid_mesh(6, 3);
    let cage: Vec<Point> =
        vec![[-0.5, -0.4], [3.0, -1.0], [6.6, -0.5], [6.4, 1.5], [6.7, 3.5], [3.0, 3.8], [-0.6, 3.4], [-0.2, 1.4]];
    let smoothness = 0.01;
    let mut deformer = Deformer::new(mesh.clone(), CauchyGreenOptions::default().with_smoothness(smoothness)).unwrap();
    deformer.set_cage(Some(&cage)).unwrap();
    assert_eq!(deformer.cauchy_green().unwrap().cage(), &cage[..], "counter-clockwise as given");
    let triangles = [0u32, 9, 30];
    let barycentric = [[1.0, 0.0, 0.0], [0.2, 0.3, 0.5], [0.0, 0.6, 0.4]];
    deformer.set_handle_points(&triangles, &barycentric).unwrap();
    let rest = deformer.handle_positions();
    let targets: Vec<Point> =
        rest.iter().enumerate().map(|(k, p)| [p[0] + 0.3 * k as f64, p[1] - 0.5 + 0.2 * p[0]]).collect();
    drive(&mut deformer, &targets);

    // E(f) = sum_k |f(p_k) - q_k|^2 + smoothness D^3 sum_e sum_t |e|/2 |f''(z_e(t))|^2 as one
    // real least-squares system in (Re f, Im f), solved by SVD.
    let n = cage.len();
    let diagonal = {
        let (xs, ys): (Vec<f64>, Vec<f64>) = cage.iter().map(|p| (p[0], p[1])).unzip();
        let span = |v: &[f64]| v.iter().cloned().fold(f64::MIN, f64::max) - v.iter().cloned().fold(f64::MAX, f64::min);
        span(&xs).hypot(span(&ys))
    };
    let mut rows: Vec<(Vec<C64>, C64)> = Vec::new();
    let mut row = vec![Complex::new(0.0, 0.0); n];
    for (p, q) in rest.iter().zip(&targets) {
        coordinates(&cage, *p, &mut row);
        rows.push((row.clone(), c(*q)));
    }
    for e in 0..n {
        let (a, b) = (cage[e], cage[(e + 1) % n]);
        let length = (b[0] - a[0]).hypot(b[1] - a[1]);
        for t in [0.25, 0.75] {
            second_derivative(&cage, [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])], &mut row);
            let w = (smoothness * diagonal.powi(3) * length / 2.0).sqrt();
            rows.push((row.iter().map(|r| r * w).collect(), Complex::new(0.0, 0.0)));
        }
    }
    // Row r z = q splits into Re: [Re r, -Im r] [x; y] = Re q and Im: [Im r, Re r] [x; y] = Im q.
    let mut a = DMatrix::<f64>::zeros(2 * rows.len(), 2 * n);
    let mut rhs = DVector::<f64>::zeros(2 * rows.len());
    for (i, (r, q)) in rows.iter().enumerate() {
        for j in 0..n {
            a[(2 * i, j)] = r[j].re;
            a[(2 * i, n + j)] = -r[j].im;
            a[(2 * i + 1, j)] = r[j].im;
            a[(2 * i + 1, n + j)] = r[j].re;
        }
        rhs[2 * i] = q.re;
        rhs[2 * i + 1] = q.im;
    }
    let solution = a.svd(true, true).solve(&rhs, 1e-14).unwrap();
    let f: Vec<C64> = (0..n).map(|j| Complex::new(solution[j], solution[n + j])).collect();
    for (v, q) in mesh.positions().iter().zip(deformer.positions()) {
        coordinates(&cage, *v, &mut row);
        let expected: C64 = row.iter().zip(&f).map(|(r, f)| r * f).sum();
        assert!((q[0] - expected.re).hypot(q[1] - expected.im) < 1e-9, "{q:?} against {expected}");
    }
    for (got, f) in deformer.cage_image().unwrap().iter().zip(&f) {
        assert!((got[0] - f.re).hypot(got[1] - f.im) < 1e-9);
    }
}

#[test]
fn one_handle_translates_and_steps_without_motion_change_nothing() {
    let (mesh, mut deformer) = bar(1);
    deformer.set_handle_vertices(&[20]).unwrap();
    deformer.step(&[[0.5, -0.25]]).unwrap();
    for (p, q) in mesh.positions().iter().zip(deformer.positions()) {
        assert!((q[0] - p[0] - 0.5).abs() < 1e-12 && (q[1] - p[1] + 0.25).abs() < 1e-12);
    }
    deformer.set_handle_vertices(&[20, 0, 84]).unwrap();
    deformer.step(&[[0.0, 0.0], [0.0, 1.0], [0.3, 0.0]]).unwrap();
    let pose = deformer.positions().to_vec();
    let targets = deformer.handle_positions();
    // The first handle kept its target; the others started from the pose.
    assert_eq!(targets[0], [mesh.positions()[20][0] + 0.5, mesh.positions()[20][1] - 0.25]);
    deformer.step(&[[0.0; 2]; 3]).unwrap();
    assert_eq!(deformer.positions(), &pose[..]);
    assert_eq!(deformer.handle_positions(), targets);
}

#[test]
fn bad_cages_options_and_velocities_change_nothing() {
    let (mesh, mut deformer) = bar(1);
    deformer.set_handle_vertices(&[0, 84]).unwrap();
    deformer.step(&[[0.0, 0.0], [0.5, 0.5]]).unwrap();
    let (pose, cage, targets) =
        (deformer.positions().to_vec(), deformer.cauchy_green().unwrap().cage().to_vec(), deformer.handle_positions());
    let outside = [[-1.0, -1.0], [17.0, -1.0], [17.0, 5.0], [-1.0, 5.0]];
    let bad: [(&str, Vec<Point>); 6] = [
        ("through the shape", vec![[-1.0, -1.0], [8.0, -1.0], [8.0, 2.0], [-1.0, 2.0]]),
        ("crossing itself", vec![[-1.0, -1.0], [17.0, 5.0], [17.0, -1.0], [-1.0, 5.0]]),
        ("not finite", vec![[-1.0, -1.0], [f64::NAN, -1.0], [17.0, 5.0], [-1.0, 5.0]]),
        ("two points", vec![[-1.0, -1.0], [17.0, 5.0]]),
        (
            "too many points",
            (0..1001)
                .map(|k| {
                    let t = k as f64 * std::f64::consts::TAU / 1001.0;
                    [8.0 + 20.0 * t.cos(), 2.0 + 20.0 * t.sin()]
                })
                .collect(),
        ),
        ("repeated points", vec![outside[0], outside[1], outside[1], outside[2], outside[3]]),
    ];
    for (what, points) in bad {
        let error = deformer.set_cage(Some(&points)).unwrap_err();
        assert!(matches!(error, DeformError::InvalidCage { .. }), "{what}: {error}");
        assert!(!error.to_string().is_empty());
    }
    for options in [
        CauchyGreenOptions::default().with_cage(7),
        CauchyGreenOptions::default().with_cage(1001),
        CauchyGreenOptions::default().with_smoothness(0.0),
        CauchyGreenOptions::default().with_smoothness(f64::NAN),
    ] {
        assert!(matches!(deformer.set_options(options), Err(DeformError::InvalidOption { .. })));
        assert!(Deformer::new(mesh.clone(), options).is_err());
    }
    assert!(matches!(deformer.step(&[[f64::NAN, 0.0], [0.0, 0.0]]), Err(DeformError::NonFiniteVelocity { .. })));
    // Targets 1.6e308 apart make a similarity that stretches the bar beyond the limit.
    assert!(matches!(deformer.step(&[[8e307, 0.0], [-8e307, 0.0]]), Err(DeformError::NonFiniteResult)));
    assert!(deformer.step(&[[0.0, 0.0]]).is_err());
    assert_eq!(
        (deformer.positions(), deformer.cauchy_green().unwrap().cage(), deformer.handle_positions()),
        (&pose[..], &cage[..], targets)
    );
    // Coordinates beyond the budget (2^25 vertex and cage pairs) are refused before any is
    // computed.
    let large = grid_mesh(200, 170);
    let error = Deformer::new(large, CauchyGreenOptions::default().with_cage(1000)).unwrap_err();
    assert!(matches!(error, DeformError::OutOfMemory { .. }), "{error}");
    // A cage given clockwise is used counter-clockwise.
    let clockwise: Vec<Point> = outside.iter().rev().copied().collect();
    deformer.set_cage(Some(&clockwise)).unwrap();
    assert_eq!(deformer.cauchy_green().unwrap().cage(), &outside[..]);
}

#[test]
fn sessions_record_its_settings_and_replay_its_steps() {
    let mesh = grid_mesh(12, 4);
    let options = CauchyGreenOptions::default().with_cage(24).with_smoothness(1e-4);
    let mut session = Session::with_mesh(&mesh, MethodOptions::CauchyGreen(options));
    let (triangles, barycentric) = (vec![0u32, 40, 80], vec![[1.0, 0.0, 0.0], [0.2, 0.3, 0.5], [0.0, 0.5, 0.5]]);
    let steps = [[0.0, 0.0, 0.1, 0.3, -0.2, 0.5], [0.0, 0.0, 0.2, 0.1, 0.0, 0.4]];
    session.events = vec![
        Event::Handles { triangles: triangles.clone(), barycentric: barycentric.concat() },
        Event::Step(steps[0].to_vec()),
        Event::Step(steps[1].to_vec()),
    ];
    let text = session.to_json();
    assert!(text.contains("\"cauchy-green\"") && text.contains("\"cage\":24"), "{text}");
    let back = Session::from_json(&text).unwrap();
    assert_eq!(back.method_options().unwrap(), MethodOptions::CauchyGreen(options));
    let mut replayed = back.recorded_deformer().unwrap();
    replay(&back, &mut replayed).unwrap();

    let mut by_hand = Deformer::new(mesh, options).unwrap();
    by_hand.set_handle_points(&triangles, &barycentric).unwrap();
    for step in steps {
        by_hand.step(step.as_chunks::<2>().0).unwrap();
    }
    assert_eq!(replayed.positions(), by_hand.positions());
    assert_eq!(replayed.cage_image(), by_hand.cage_image());
}
