//! Hostile and careless callers of the deformers: options outside their documented ranges,
//! poses beyond the coordinate limit, lengths counted in the caller's numbers, collapsed
//! poses, and the same deformation at every scale. Runs natively and as wasm.

use akap::deform::{AkapOptions, ArapOptions, CauchyGreenOptions, DeformError, Deformer, MethodOptions, MlsOptions};
use akap::geometry::{scale_by_power_of_two, Point, MAX_COORDINATE};
use akap::shapes::gingerbread;
use akap::{triangulate, Mesh, TriangulationOptions};
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

fn figure() -> Mesh {
    triangulate(&gingerbread(), &TriangulationOptions::default().with_target_edge_length(0.1)).unwrap()
}

fn scaled_mesh(mesh: &Mesh, f: impl Fn(f64) -> f64) -> Mesh {
    Mesh::new(mesh.positions().iter().map(|p| p.map(&f)).collect(), mesh.triangles().to_vec()).unwrap()
}

fn methods() -> [MethodOptions; 5] {
    [
        MethodOptions::Akap(AkapOptions::default()),
        MethodOptions::Akap(AkapOptions::default().with_dirichlet(false)),
        MethodOptions::Arap(ArapOptions::default()),
        MethodOptions::Mls(MlsOptions::default()),
        MethodOptions::CauchyGreen(CauchyGreenOptions::default()),
    ]
}

/// Handles on two vertices and a point inside a triangle; a few steps that bend the figure.
fn pose(deformer: &mut Deformer, unit: impl Fn(f64) -> f64) {
    let n = deformer.mesh().vertex_count() as u32;
    deformer.set_handle_vertices(&[0, n / 2]).unwrap();
    deformer.set_handle_points(&[0, 7, 20], &[[1.0, 0.0, 0.0], [0.2, 0.3, 0.5], [0.0, 0.0, 1.0]]).unwrap();
    for k in 0..4 {
        let v = 0.02 * k as f64;
        deformer.step(&[[0.0, 0.0], [unit(v), unit(-0.5 * v)], [unit(0.01), unit(v)]]).unwrap();
    }
}

#[test]
fn lambda_has_the_documented_range_and_the_refusal_says_it() {
    let mesh = figure();
    for lambda in [1e-6, 1.0, 100.0, 1e10] {
        let options = MethodOptions::Akap(AkapOptions::default().with_lambda(lambda));
        let mut deformer = Deformer::new(mesh.clone(), options).unwrap();
        pose(&mut deformer, |x| x);
        assert!(deformer.positions().iter().flatten().all(|x| x.is_finite()), "lambda {lambda}");
    }
    for lambda in [0.0, -1.0, 9.9e-7, 1.01e10, 1e308, 1e-300, f64::NAN, f64::INFINITY] {
        let options = AkapOptions::default().with_lambda(lambda);
        let error = Deformer::new(mesh.clone(), MethodOptions::Akap(options)).unwrap_err();
        assert!(matches!(error, DeformError::InvalidOption { name: "lambda", .. }), "{error}");
        assert!(error.to_string().ends_with("expected a number from 1e-6 to 1e10"), "{error}");
        let mut deformer = Deformer::new(mesh.clone(), MethodOptions::default()).unwrap();
        let refused = deformer.set_method_options(MethodOptions::Akap(options)).unwrap_err();
        assert_eq!(refused.to_string(), error.to_string());
    }
    let error = Deformer::new(mesh, MethodOptions::Akap(AkapOptions::default().with_lambda(1e308))).unwrap_err();
    assert_eq!(error.to_string(), "option lambda is 1e308, expected a number from 1e-6 to 1e10");
}

#[test]
fn arap_options_have_documented_ranges() {
    let mesh = figure();
    for (options, name) in [
        (ArapOptions::default().with_iterations(0), "iterations"),
        (ArapOptions::default().with_iterations(1_000_001), "iterations"),
        // At a fixed count at most arap::MAX_ITERATIONS (1000) per step; to a tolerance at
        // most arap::MAX_CONVERGENCE_ITERATIONS.
        (ArapOptions::default().with_iterations(1001), "iterations"),
        (ArapOptions::default().until_converged(1e-9, 1_000_001), "iterations"),
        (ArapOptions::default().until_converged(-0.1, 10), "tolerance"),
        (ArapOptions::default().until_converged(1.5, 10), "tolerance"),
        (ArapOptions::default().until_converged(f64::NAN, 10), "tolerance"),
    ] {
        let error = Deformer::new(mesh.clone(), MethodOptions::Arap(options)).unwrap_err();
        assert!(matches!(error, DeformError::InvalidOption { name: n, .. } if n == name), "{error}");
    }
    let error =
        Deformer::new(mesh.clone(), MethodOptions::Arap(ArapOptions::default().with_iterations(0))).unwrap_err();
    assert_eq!(
        error.to_string(),
        "option iterations is 0, expected a whole number from 1 to 1000 per step (a step's work grows with it; \
         1000 is far more than a frame needs)"
    );
    for options in [
        ArapOptions::default().with_iterations(1),
        ArapOptions::default().with_iterations(1000),
        ArapOptions::default().until_converged(1.0, 3),
        ArapOptions::default().until_converged(1e-9, 1_000_000),
    ] {
        assert!(Deformer::new(mesh.clone(), MethodOptions::Arap(options)).is_ok());
    }
}

#[test]
fn every_method_deforms_the_same_at_every_scale() {
    // Scaling by 2^j is exact, and every computation that multiplies lengths works on
    // values scaled by powers of two: the same pose scaled, to the last bit (but where a
    // coordinate falls below the normal range, within one step of 4.9e-324).
    let unit_mesh = figure();
    for method in methods() {
        let mut unit = Deformer::new(unit_mesh.clone(), method).unwrap();
        pose(&mut unit, |x| x);
        for j in [-990, -400, 400, 990] {
            let s = |x: f64| scale_by_power_of_two(x, j);
            let mut scaled = Deformer::new(scaled_mesh(&unit_mesh, s), method).unwrap();
            pose(&mut scaled, s);
            for (p, q) in scaled.positions().iter().zip(unit.positions()) {
                for (x, y) in p.iter().zip(q) {
                    assert!((x - s(*y)).abs() <= f64::from_bits(1), "{method:?} at 2^{j}: {p:?} vs {q:?}");
                }
            }
            let (a, b) = (scaled.metrics(), unit.metrics());
            assert!((a.area_distortion - b.area_distortion).abs() < 1e-12 * b.area_distortion, "{a:?} {b:?}");
            assert!((a.angle_distortion - b.angle_distortion).abs() < 1e-12 * b.angle_distortion, "{a:?} {b:?}");
        }
        // At 1e-300 and 1e200 the mesh itself is rounded, but the pose is the same to the
        // precision of its coordinates. (Cauchy-Green's automatic cage is an offset that
        // i_overlay computes with directions in fixed point, about 1e-5 of the margin; the
        // offsets of a mesh and of its rounded copy differ by that, and so do the maps.
        // Measured: 1.3e-5 on this figure, about 3 across; scaling by powers of two is exact.)
        let tolerance = if matches!(method, MethodOptions::CauchyGreen(_)) { 1e-4 } else { 1e-10 };
        for factor in [1e-300, 1e200] {
            let s = |x: f64| x * factor;
            let mut scaled = Deformer::new(scaled_mesh(&unit_mesh, s), method).unwrap();
            pose(&mut scaled, s);
            for (p, q) in scaled.positions().iter().zip(unit.positions()) {
                let d = (p[0] / factor - q[0]).hypot(p[1] / factor - q[1]);
                assert!(d < tolerance, "{method:?} at {factor}: {p:?} vs {q:?}");
            }
        }
    }
}

#[test]
fn poses_beyond_the_coordinate_limit_are_refused_and_change_nothing() {
    let mesh = scaled_mesh(&figure(), |x| 5e299 * x); // at most 5e299 from the origin
    for method in methods() {
        let mut deformer = Deformer::new(mesh.clone(), method).unwrap();
        deformer.set_handle_vertices(&[0, 30]).unwrap();
        deformer.step(&[[0.0, 0.0], [1e298, 0.0]]).unwrap();
        let before = deformer.positions().to_vec();
        let mut far = before.clone();
        far[3][1] = -2e300;
        assert_eq!(deformer.set_positions(&far), Err(DeformError::PositionOutOfRange { vertex: 3, value: -2e300 }));
        // One handle translates the shape: by 1e300 it would reach 1.5e300.
        deformer.set_handle_vertices(&[30]).unwrap();
        let error = deformer.step(&[[MAX_COORDINATE, MAX_COORDINATE]]).unwrap_err();
        assert_eq!(error, DeformError::NonFiniteResult, "{method:?}");
        assert!(error.to_string().contains("beyond ±1e300"), "{error}");
        assert_eq!(deformer.positions(), before.as_slice());
        deformer.step(&[[1e298, 1e298]]).unwrap();
    }
}

#[test]
fn lengths_are_counted_in_numbers() {
    let mesh = figure();
    let n = mesh.vertex_count();
    for method in methods() {
        let mut deformer = Deformer::new(mesh.clone(), method).unwrap();
        // One point short: 2n - 2 numbers where 2n are needed.
        let error = deformer.set_positions(&mesh.positions()[1..]).unwrap_err();
        assert_eq!(
            error.to_string(),
            format!("positions has {} numbers, expected {} (2 for each of the {n} vertices)", 2 * n - 2, 2 * n)
        );
        deformer.set_handle_vertices(&[0, 1, 2]).unwrap();
        let error = deformer.step(&[[0.0, 0.0]]).unwrap_err();
        assert_eq!(error.to_string(), "velocities has 2 numbers, expected 6 (2 for each of the 3 handles)");
        let error = deformer.set_handle_points(&[0, 1], &[[1.0, 0.0, 0.0]]).unwrap_err();
        assert_eq!(error.to_string(), "barycentric has 3 numbers, expected 6 (3 for each of the 2 handles)");
    }
}

#[test]
fn a_collapsed_pose_has_infinite_distortion_not_nan() {
    let mesh = figure();
    let m = mesh.triangle_count();
    for method in methods() {
        let mut deformer = Deformer::new(mesh.clone(), method).unwrap();
        // Every vertex on the line y = 0: every triangle collapsed (sigma2 = 0).
        let flat: Vec<Point> = mesh.positions().iter().map(|p| [p[0], 0.0]).collect();
        deformer.set_positions(&flat).unwrap();
        let metrics = deformer.metrics();
        assert_eq!(metrics.area_distortion, f64::INFINITY);
        assert_eq!(metrics.angle_distortion, f64::INFINITY);
        assert_eq!(metrics.flipped, m);
        // Every vertex at one point: the same.
        deformer.set_positions(&vec![[0.25, -1.0]; mesh.vertex_count()]).unwrap();
        let metrics = deformer.metrics();
        assert_eq!((metrics.area_distortion, metrics.angle_distortion), (f64::INFINITY, f64::INFINITY));
    }
}
