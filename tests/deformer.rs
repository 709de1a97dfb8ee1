//! The AKAP deformer against the mathematics of the paper: rigid motions reproduced
//! exactly (Appendix A), optimality conditions of both solves, near-isometric bending,
//! handle edge cases and untouched state after bad input. Runs natively and as wasm.

use akap::deform::akap::killing::KillingMatrix;
use akap::deform::{AkapOptions, ArapOptions, DeformError, Deformer, Integrator, Method, MethodOptions, Orders};
use akap::geometry::Point;
use akap::shapes::{ellipse, gingerbread};
use akap::{triangulate, Mesh, Outline, TriangulationOptions};
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use crate::common::Rng;

fn bar_with_holes() -> Mesh {
    let outline = Outline::new(vec![[0.0, 0.0], [4.0, 0.0], [4.0, 1.0], [0.0, 1.0]])
        .with_hole(ellipse([1.0, 0.5], 0.2, 0.25, 10))
        .with_hole(ellipse([2.8, 0.4], 0.3, 0.2, 12));
    triangulate(&outline, &TriangulationOptions::default().with_target_edge_length(0.2)).unwrap()
}

fn figure() -> Mesh {
    triangulate(&gingerbread(), &TriangulationOptions::default().with_target_edge_length(0.08)).unwrap()
}

/// A figure large enough for the set-up to consider nested dissection.
fn large_figure() -> Mesh {
    let mesh = triangulate(&gingerbread(), &TriangulationOptions::default().with_target_edge_length(0.0095)).unwrap();
    assert!(mesh.vertex_count() >= akap::sparse::DISSECTION_MIN_NODES, "{} vertices", mesh.vertex_count());
    mesh
}

/// The infinitesimal rigid motion `u(p) = a i (p - c) + d` in complex notation.
fn killing_field(a: f64, c: Point, d: [f64; 2]) -> impl Fn(Point) -> [f64; 2] {
    move |p| [-a * (p[1] - c[1]) + d[0], a * (p[0] - c[0]) + d[1]]
}

fn scale(points: &[Point]) -> f64 {
    points.iter().map(|p| p[0].abs().max(p[1].abs())).fold(0.0, f64::max)
}

/// Handles on a few vertices and a few barycentric points spread over the mesh.
fn place_handles(deformer: &mut Deformer, barycentric: bool, rng: &mut Rng) {
    let mesh = deformer.mesh().clone();
    if barycentric {
        let tris: Vec<u32> = (0..4).map(|_| rng.below(mesh.triangle_count()) as u32).collect();
        let weights: Vec<[f64; 3]> = (0..4)
            .map(|_| {
                let (x, y) = (rng.unit(), rng.unit());
                let (x, y) = if x + y > 1.0 { (1.0 - x, 1.0 - y) } else { (x, y) };
                [1.0 - x - y, x, y]
            })
            .collect();
        deformer.set_handle_points(&tris, &weights).unwrap();
    } else {
        let vertices: Vec<u32> = (0..5).map(|_| rng.below(mesh.vertex_count()) as u32).collect();
        deformer.set_handle_vertices(&vertices).unwrap();
    }
}

#[test]
fn rigid_motions_are_reproduced_exactly() {
    let mut rng = Rng::new(2011);
    for mesh in [bar_with_holes(), figure(), large_figure()] {
        let size = scale(mesh.positions());
        for (a, c, d, lambda, dirichlet, barycentric) in [
            (0.3, [1.0, 0.2], [0.0, 0.0], 100.0, true, false),
            (-0.7, [-2.0, 3.0], [0.5, -0.25], 100.0, false, true),
            (0.05, [0.5, 0.5], [1.0, 2.0], 1.0, true, true),
            (1.2, [0.0, 0.0], [-0.3, 0.1], 1e4, true, false),
        ] {
            let options = AkapOptions::default().with_lambda(lambda).with_dirichlet(dirichlet);
            let mut deformer = Deformer::new(mesh.clone(), options).unwrap();
            place_handles(&mut deformer, barycentric, &mut rng);
            let u = killing_field(a, c, d);
            let velocities: Vec<[f64; 2]> = deformer.handle_positions().iter().map(|&p| u(p)).collect();
            deformer.step(&velocities).unwrap();

            // The field is the rigid motion itself.
            let speed = mesh.positions().iter().map(|&p| u(p)[0].hypot(u(p)[1])).fold(0.0, f64::max);
            for (p, f) in mesh.positions().iter().zip(deformer.field()) {
                let e = u(*p);
                assert!((f[0] - e[0]).hypot(f[1] - e[1]) <= 1e-9 * speed, "field {f:?} vs {e:?}");
            }
            // One spiral step is the rotation by a about the field's centre c + i d / a.
            let centre = [c[0] - d[1] / a, c[1] + d[0] / a];
            let (sin, cos) = a.sin_cos();
            let tol = 1e-9 * (size + scale(&[centre]));
            for (p, q) in mesh.positions().iter().zip(deformer.positions()) {
                let r = [p[0] - centre[0], p[1] - centre[1]];
                let expected = [centre[0] + cos * r[0] - sin * r[1], centre[1] + sin * r[0] + cos * r[1]];
                assert!((q[0] - expected[0]).hypot(q[1] - expected[1]) <= tol, "{q:?} vs {expected:?}");
            }
            let m = deformer.metrics();
            assert!((m.area_distortion - 2.0).abs() < 1e-8 && (m.angle_distortion - 2.0).abs() < 1e-8);
        }
    }
}

#[test]
fn linear_steps_dilate_rotations_by_the_expected_factor() {
    let mesh = bar_with_holes();
    let options = AkapOptions::default().with_integrator(Integrator::Linear);
    let mut deformer = Deformer::new(mesh.clone(), options).unwrap();
    deformer.set_handle_vertices(&[0, 7, 20]).unwrap();
    let (a, c) = (0.4, [2.0, 0.5]);
    let u = killing_field(a, c, [0.0, 0.0]);
    let velocities: Vec<[f64; 2]> = deformer.handle_positions().iter().map(|&p| u(p)).collect();
    deformer.step(&velocities).unwrap();
    // p + a i (p - c) = c + (1 + a i)(p - c): distances from c grow by sqrt(1 + a^2).
    let growth = (1.0 + a * a).sqrt();
    for (p, q) in mesh.positions().iter().zip(deformer.positions()) {
        let before = (p[0] - c[0]).hypot(p[1] - c[1]);
        let after = (q[0] - c[0]).hypot(q[1] - c[1]);
        assert!((after - growth * before).abs() <= 1e-9 * (1.0 + before));
    }
    assert!(deformer.metrics().area_distortion > 2.0 + 1e-3);
}

/// `K u` for the Killing matrix at `positions`.
fn killing_times(mesh: &Mesh, positions: &[Point], u: &[f64]) -> Vec<f64> {
    let mut k = KillingMatrix::new(mesh);
    k.assemble(positions);
    let mut out = vec![0.0; u.len()];
    for (v, (i, j)) in k.matrix().iter() {
        out[i] += v * u[j];
    }
    out
}

#[test]
fn both_solves_satisfy_their_optimality_conditions() {
    let mesh = figure();
    let mut rng = Rng::new(4);
    let lambda = 100.0;
    let mut deformer = Deformer::new(mesh.clone(), AkapOptions::default().with_lambda(lambda)).unwrap();
    let tris = [3u32, 100, 250, 400];
    let weights = [[0.2, 0.3, 0.5], [1.0, 0.0, 0.0], [0.6, 0.2, 0.2], [0.1, 0.1, 0.8]];
    deformer.set_handle_points(&tris, &weights).unwrap();
    let velocities: Vec<[f64; 2]> = (0..4).map(|_| [rng.unit() - 0.5, rng.unit() - 0.5]).collect();
    let positions = deformer.positions().to_vec();
    deformer.step(&velocities).unwrap();

    // Step 1: K U0 + lambda sum_i W_i^T (W_i U0 - u_i) = 0.
    let u0: Vec<f64> = deformer.soft_field().iter().flatten().copied().collect();
    let mut gradient = killing_times(&mesh, &positions, &u0);
    for ((&t, w), vel) in tris.iter().zip(&weights).zip(&velocities) {
        let verts = mesh.triangles()[t as usize];
        for k in 0..2 {
            let at_handle: f64 = (0..3).map(|i| w[i] * u0[2 * verts[i] as usize + k]).sum();
            for i in 0..3 {
                gradient[2 * verts[i] as usize + k] += lambda * w[i] * (at_handle - vel[k]);
            }
        }
    }
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!(norm(&gradient) <= 1e-9 * lambda * norm(&velocities.concat()), "{}", norm(&gradient));

    // Step 2: U = U0 on the boundary and (K U)_I = 0 at interior unknowns.
    let u: Vec<f64> = deformer.field().iter().flatten().copied().collect();
    let ku = killing_times(&mesh, &positions, &u);
    let mut interior = 0.0;
    for v in 0..mesh.vertex_count() {
        if mesh.is_boundary_vertex(v) {
            assert_eq!([u[2 * v], u[2 * v + 1]], [u0[2 * v], u0[2 * v + 1]]);
        } else {
            interior += ku[2 * v].powi(2) + ku[2 * v + 1].powi(2);
        }
    }
    let reference = norm(&killing_times(&mesh, &positions, &u0));
    assert!(interior.sqrt() <= 1e-9 * reference, "{} vs {reference}", interior.sqrt());
}

#[test]
fn bending_a_bar_along_a_quarter_circle_stays_near_isometric() {
    let (length, width) = (8.0, 1.0);
    let outline = Outline::new(vec![[0.0, 0.0], [length, 0.0], [length, width], [0.0, width]]);
    let mesh = triangulate(&outline, &TriangulationOptions::default().with_target_edge_length(0.2)).unwrap();
    let left: Vec<u32> = (0..mesh.vertex_count() as u32).filter(|&v| mesh.positions()[v as usize][0] == 0.0).collect();
    let right: Vec<u32> =
        (0..mesh.vertex_count() as u32).filter(|&v| mesh.positions()[v as usize][0] == length).collect();
    let handles: Vec<u32> = left.iter().chain(&right).copied().collect();
    let rest: Vec<Point> = handles.iter().map(|&v| mesh.positions()[v as usize]).collect();
    let mut deformer = Deformer::new(mesh, AkapOptions::default()).unwrap();
    deformer.set_handle_vertices(&handles).unwrap();
    // The bar's centre line bent into a circular arc of angle phi keeps its length: the
    // right end goes to R (sin phi, 1 - cos phi) with R = length / phi, turned by phi.
    let steps = 60;
    for k in 1..=steps {
        let phi = std::f64::consts::FRAC_PI_2 * k as f64 / steps as f64;
        let radius = length / phi;
        let end = [radius * phi.sin(), width / 2.0 + radius * (1.0 - phi.cos())];
        let (s, c) = phi.sin_cos();
        let current = deformer.handle_positions();
        let velocities: Vec<[f64; 2]> = rest
            .iter()
            .zip(&current)
            .enumerate()
            .map(|(i, (r, now))| {
                let target = if i < left.len() {
                    *r
                } else {
                    let y = r[1] - width / 2.0;
                    [end[0] - s * y, end[1] + c * y]
                };
                [target[0] - now[0], target[1] - now[1]]
            })
            .collect();
        deformer.step(&velocities).unwrap();
    }
    let m = deformer.metrics();
    assert_eq!(m.flipped, 0);
    assert!(m.area_distortion < 2.05 && m.angle_distortion < 2.05, "{m:?}");
}

#[test]
fn zero_one_and_coincident_handles() {
    let mesh = bar_with_holes();
    let mut deformer = Deformer::new(mesh.clone(), AkapOptions::default()).unwrap();
    deformer.step(&[]).unwrap();
    assert_eq!(deformer.positions(), mesh.positions());

    deformer.set_handle_vertices(&[5]).unwrap();
    deformer.step(&[[0.25, -0.5]]).unwrap();
    for (p, q) in mesh.positions().iter().zip(deformer.positions()) {
        assert!((q[0] - p[0] - 0.25).abs() < 1e-15 && (q[1] - p[1] + 0.5).abs() < 1e-15);
    }
    // The same vertex twice is one point: a rigid translation by the mean velocity.
    deformer.reset();
    deformer.set_handle_vertices(&[5, 5]).unwrap();
    deformer.step(&[[1.0, 0.0], [0.0, 1.0]]).unwrap();
    for (p, q) in mesh.positions().iter().zip(deformer.positions()) {
        assert!((q[0] - p[0] - 0.5).abs() < 1e-15 && (q[1] - p[1] - 0.5).abs() < 1e-15);
    }
}

#[test]
fn bad_input_is_refused_and_changes_nothing() {
    let mesh = bar_with_holes();
    let mut deformer = Deformer::new(mesh.clone(), AkapOptions::default()).unwrap();
    deformer.set_handle_vertices(&[0, 10]).unwrap();
    deformer.step(&[[0.0, 0.0], [0.1, 0.1]]).unwrap();
    let before = deformer.positions().to_vec();
    let field = deformer.field().to_vec();
    let n = mesh.vertex_count() as u32;
    let m = mesh.triangle_count() as u32;

    assert!(matches!(deformer.set_handle_vertices(&[0, n]), Err(DeformError::VertexOutOfRange { handle: 1, .. })));
    assert!(matches!(
        deformer.set_handle_points(&[m], &[[1.0, 0.0, 0.0]]),
        Err(DeformError::TriangleOutOfRange { .. })
    ));
    assert!(matches!(
        deformer.set_handle_points(&[0], &[[0.5, 0.4, 0.0]]),
        Err(DeformError::InvalidBarycentric { .. })
    ));
    assert!(matches!(
        deformer.set_handle_points(&[0], &[[1.5, -0.5, 0.0]]),
        Err(DeformError::InvalidBarycentric { .. })
    ));
    assert!(matches!(
        deformer.set_handle_points(&[0], &[[f64::NAN, 0.5, 0.5]]),
        Err(DeformError::InvalidBarycentric { .. })
    ));
    assert!(matches!(deformer.step(&[[0.0, 0.0]]), Err(DeformError::Length { expected: 4, found: 2, .. })));
    assert!(matches!(
        deformer.step(&[[0.0, 0.0], [f64::INFINITY, 0.0]]),
        Err(DeformError::NonFiniteVelocity { handle: 1 })
    ));
    assert!(matches!(
        deformer.set_options(AkapOptions::default().with_lambda(-1.0)),
        Err(DeformError::InvalidOption { name: "lambda", .. })
    ));
    assert_eq!(deformer.handle_count(), 2);
    assert_eq!(deformer.positions(), before.as_slice());
    assert_eq!(deformer.field(), field.as_slice());
    // The handles set before the errors still work.
    deformer.step(&[[0.0, 0.0], [0.1, 0.1]]).unwrap();

    let two = Mesh::new(
        vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [5.0, 0.0], [6.0, 0.0], [5.0, 1.0]],
        vec![[0, 1, 2], [3, 4, 5]],
    )
    .unwrap();
    assert_eq!(Deformer::new(two, AkapOptions::default()).unwrap_err(), DeformError::Disconnected { components: 2 });
}

#[test]
fn long_random_runs_stay_finite() {
    let mesh = triangulate(
        &Outline::new(vec![[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]]),
        &TriangulationOptions::default().with_target_edge_length(0.3),
    )
    .unwrap();
    let mut rng = Rng::new(99);
    let mut deformer = Deformer::new(mesh.clone(), AkapOptions::default()).unwrap();
    for step in 0..10_000 {
        if step % 500 == 0 {
            deformer.reset();
            let handles: Vec<u32> = (0..3).map(|_| rng.below(mesh.vertex_count()) as u32).collect();
            deformer.set_handle_vertices(&handles).unwrap();
        }
        let velocities: Vec<[f64; 2]> =
            (0..deformer.handle_count()).map(|_| [0.02 * (rng.unit() - 0.5), 0.02 * (rng.unit() - 0.5)]).collect();
        let before = deformer.positions().to_vec();
        // Random pushes fold triangles over; the step must still be taken.
        deformer.step(&velocities).unwrap_or_else(|e| panic!("step {step}: {e}"));
        assert!(deformer.positions().iter().all(|p| p[0].is_finite() && p[1].is_finite()));
        assert_ne!(deformer.positions(), before.as_slice());
    }
}

#[test]
fn a_pose_set_from_outside_is_deformed_from_there() {
    // Put the bar into a rotated and shifted copy of its rest pose, then step with the
    // velocities of a rotation about a point: the spiral step must rotate the given pose,
    // so the result equals the rest pose rotated by both angles (Appendix A again).
    let mesh = bar_with_holes();
    let rest = mesh.positions().to_vec();
    let rotate = |p: Point, angle: f64, c: Point| -> Point {
        let (s, co) = angle.sin_cos();
        let (x, y) = (p[0] - c[0], p[1] - c[1]);
        [c[0] + co * x - s * y, c[1] + s * x + co * y]
    };
    let posed: Vec<Point> =
        rest.iter().map(|&p| rotate(p, 0.4, [0.0, 0.0])).map(|p| [p[0] + 1.5, p[1] - 0.5]).collect();
    let mut deformer = Deformer::new(mesh, AkapOptions::default()).unwrap();
    deformer.set_handle_vertices(&[0, 7, 30]).unwrap();
    deformer.set_positions(&posed).unwrap();
    assert_eq!(deformer.positions(), &posed[..]);

    let (a, c) = (0.25, [2.0, 0.3]);
    let u = killing_field(a, c, [0.0, 0.0]);
    let velocities: Vec<[f64; 2]> = deformer.handle_positions().into_iter().map(u).collect();
    deformer.step(&velocities).unwrap();
    let size = scale(&posed);
    for (got, &p) in deformer.positions().iter().zip(&posed) {
        let want = rotate(p, a, c);
        assert!((got[0] - want[0]).hypot(got[1] - want[1]) <= 1e-9 * size, "{got:?} vs {want:?}");
    }

    // Bad poses are refused and change nothing.
    let before = deformer.positions().to_vec();
    assert!(matches!(deformer.set_positions(&posed[1..]), Err(DeformError::Length { .. })));
    let mut bad = posed.clone();
    bad[5][1] = f64::NAN;
    assert_eq!(deformer.set_positions(&bad), Err(DeformError::NonFinitePosition { vertex: 5 }));
    assert_eq!(deformer.positions(), &before[..]);
}

#[test]
fn with_handles_on_the_boundary_only_step_two_is_step_one() {
    // The penalties then touch boundary unknowns only, so U0 already satisfies step 2's
    // condition (K U)_I = 0 and the deformer skips the second solve: check the condition
    // holds for the field it returns, and that it is U0.
    let mesh = figure();
    let boundary: Vec<u32> = mesh.boundary_vertices().step_by(37).take(4).collect();
    let mut deformer = Deformer::new(mesh.clone(), AkapOptions::default()).unwrap();
    deformer.set_handle_vertices(&boundary).unwrap();
    let velocities = [[0.01, 0.0], [0.0, -0.02], [0.015, 0.01], [-0.01, 0.005]];
    let positions = deformer.positions().to_vec();
    deformer.step(&velocities).unwrap();
    assert_eq!(deformer.field(), deformer.soft_field());
    let u: Vec<f64> = deformer.field().iter().flatten().copied().collect();
    let ku = killing_times(&mesh, &positions, &u);
    let interior: f64 = (0..mesh.vertex_count())
        .filter(|&v| !mesh.is_boundary_vertex(v))
        .map(|v| ku[2 * v].powi(2) + ku[2 * v + 1].powi(2))
        .sum();
    let reference: f64 = ku.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!(interior.sqrt() <= 1e-9 * reference, "{} vs {reference}", interior.sqrt());

    // One handle point inside the shape brings step 2 back: the fields differ.
    let interior_triangle = (0..mesh.triangle_count())
        .find(|&t| mesh.triangles()[t].iter().all(|&v| !mesh.is_boundary_vertex(v as usize)))
        .unwrap() as u32;
    let mut tris = vec![interior_triangle];
    let mut weights = vec![[0.2, 0.3, 0.5]];
    for &v in &boundary[..3] {
        let t = (0..mesh.triangle_count()).find(|&t| mesh.triangles()[t].contains(&v)).unwrap();
        tris.push(t as u32);
        weights.push(mesh.triangles()[t].map(|w| if w == v { 1.0 } else { 0.0 }));
    }
    deformer.set_handle_points(&tris, &weights).unwrap();
    deformer.step(&velocities).unwrap();
    assert_ne!(deformer.field(), deformer.soft_field());
}

#[test]
fn a_drag_that_flips_triangles_never_sticks() {
    // The reproduction: the default figure, one handle still and one circling; at
    // step 406 a triangle flips, and the deformer used to refuse every later step (its
    // matrix then had a negative pivot). Every step must succeed, triangles flipped or not.
    let mesh = triangulate(&gingerbread(), &TriangulationOptions::default().with_target_edge_length(0.05)).unwrap();
    let mut deformer = Deformer::new(mesh, AkapOptions::default()).unwrap();
    deformer.set_handle_vertices(&[0, 500]).unwrap();
    let mut most_flipped = 0;
    for i in 0..700 {
        let t = f64::from(i) / 20.0;
        deformer.step(&[[0.0, 0.0], [0.02 * t.cos(), 0.02 * t.sin()]]).unwrap_or_else(|e| panic!("step {i}: {e}"));
        most_flipped = most_flipped.max(deformer.metrics().flipped);
    }
    assert!(most_flipped > 0, "the drag should fold some triangles over");
    deformer.step(&[[0.0, 0.0], [0.0, 0.0]]).unwrap();
}

#[test]
fn rigid_motions_are_reproduced_from_flipped_and_collapsed_poses() {
    // The Killing energy of a rigid field is zero on any triangle, flipped or collapsed, so
    // from any pose a rigid handle motion must give that rigid field, and the spiral step
    // must rotate every vertex exactly (a vertex's edges of zero length carry no spiral).
    let mesh = figure();
    let rest = mesh.positions().to_vec();
    let interior = |t: &[u32; 3]| t.iter().all(|&v| !mesh.is_boundary_vertex(v as usize));
    let t = *mesh.triangles().iter().find(|t| interior(t)).unwrap();
    let [a, b, c] = t.map(|v| v as usize);
    let mid = [0.5 * (rest[b][0] + rest[c][0]), 0.5 * (rest[b][1] + rest[c][1])];
    let past = |s: f64| [rest[a][0] + s * (mid[0] - rest[a][0]), rest[a][1] + s * (mid[1] - rest[a][1])];
    let (angle, centre) = (0.2, [0.3, -0.1]);
    let u = killing_field(angle, centre, [0.05, 0.02]);
    for (name, moved) in [
        ("flipped", past(1.5)),
        ("sliver", past(1.0)),
        ("almost a sliver", past(1.0 - 1e-12)),
        ("two vertices at one place", rest[b]),
    ] {
        let mut pose = rest.clone();
        pose[a] = moved;
        let mut deformer = Deformer::new(mesh.clone(), AkapOptions::default()).unwrap();
        deformer.set_positions(&pose).unwrap();
        deformer.set_handle_vertices(&[0, 500, a as u32, 100]).unwrap();
        let velocities: Vec<[f64; 2]> = deformer.handle_positions().into_iter().map(&u).collect();
        deformer.step(&velocities).unwrap_or_else(|e| panic!("{name}: {e}"));
        let size = scale(&pose);
        for (f, &p) in deformer.field().iter().zip(&pose) {
            let want = u(p);
            assert!((f[0] - want[0]).hypot(f[1] - want[1]) <= 1e-9 * size, "{name}: field {f:?} vs {want:?}");
        }
        // The step is the rotation by `angle` about the field's centre, plus nothing else.
        let fixed = [centre[0] - 0.02 / angle, centre[1] + 0.05 / angle];
        for (got, &p) in deformer.positions().iter().zip(&pose) {
            let (s, co) = angle.sin_cos();
            let (x, y) = (p[0] - fixed[0], p[1] - fixed[1]);
            let want = [fixed[0] + co * x - s * y, fixed[1] + s * x + co * y];
            assert!((got[0] - want[0]).hypot(got[1] - want[1]) <= 1e-9 * size, "{name}: {got:?} vs {want:?}");
        }
    }
}

#[test]
fn a_step_that_fails_leaves_the_deformer_ready_for_smaller_ones() {
    // A velocity far too large for the mesh overflows the spiral step: the step is refused,
    // nothing changes, and a smaller step from there succeeds.
    let mesh = figure();
    let mut deformer = Deformer::new(mesh, AkapOptions::default()).unwrap();
    deformer.set_handle_vertices(&[0, 40]).unwrap();
    deformer.step(&[[0.0, 0.0], [0.01, 0.0]]).unwrap();
    let before = deformer.positions().to_vec();
    assert_eq!(deformer.step(&[[0.0, 0.0], [1e300, -1e300]]), Err(DeformError::NonFiniteResult));
    assert_eq!(deformer.positions(), before.as_slice());
    deformer.step(&[[0.0, 0.0], [0.01, -0.01]]).unwrap();
    assert_ne!(deformer.positions(), before.as_slice());
}

#[test]
fn orders_made_beforehand_give_the_same_deformation_and_bad_ones_are_refused() {
    // Any permutation orders a system correctly (only the fill differs), so a deformer made
    // with the identity order or the reversed one poses like one that ordered itself, to
    // rounding; orders of the wrong sizes, or with a vertex twice, are refused.
    let mesh = figure();
    let n = mesh.vertex_count();
    let interior = (0..n).filter(|&v| !mesh.is_boundary_vertex(v)).count();
    for options in [MethodOptions::Akap(AkapOptions::default()), MethodOptions::Arap(ArapOptions::default())] {
        let own = options.orders(&mesh);
        let sizes: Vec<usize> = own.systems.iter().map(Vec::len).collect();
        assert_eq!(sizes, if options.method() == Method::Akap { vec![n, interior] } else { vec![n] });
        let pose = |orders: &Orders| {
            let mut deformer = Deformer::with_orders(mesh.clone(), options, orders).unwrap();
            deformer.set_handle_vertices(&[0, 40, 90]).unwrap();
            for _ in 0..5 {
                deformer.step(&[[0.0, 0.0], [0.01, -0.02], [-0.015, 0.01]]).unwrap();
            }
            deformer.positions().to_vec()
        };
        let reference = pose(&own);
        let identity = Orders { systems: sizes.iter().map(|&s| (0..s).collect()).collect() };
        let reversed = Orders { systems: sizes.iter().map(|&s| (0..s).rev().collect()).collect() };
        for other in [identity, reversed] {
            for (p, q) in pose(&other).iter().zip(&reference) {
                assert!((p[0] - q[0]).hypot(p[1] - q[1]) <= 1e-10, "{p:?} vs {q:?}");
            }
        }
        let mut twice = own.clone();
        twice.systems[0][1] = twice.systems[0][0];
        let mut short = own.clone();
        short.systems[0].pop();
        let mut extra = own.clone();
        extra.systems.push(Vec::new());
        for (bad, system) in [(twice, 0), (short, 0), (extra, sizes.len() + 1)] {
            let error = Deformer::with_orders(mesh.clone(), options, &bad).unwrap_err();
            assert!(matches!(error, DeformError::OrdersMismatch { system: s, .. } if s == system), "{error}");
        }
    }
}
