//! The ARAP deformer against the mathematics of local/global ARAP: rigid targets give a
//! rigid pose, the energy never increases over iterations, at convergence the gradient
//! vanishes at the free unknowns and the rotations are the polar factors, a bent bar ends
//! near-isometric, and bad input is refused without changing anything. The energy and
//! its gradient are computed here from the finite-element form `sum_t A_t |J_t - R_t|^2`,
//! not from the cotangent form the deformer uses. Runs natively and as wasm.

use akap::deform::{
    AkapOptions, ArapOptions, CauchyGreenOptions, DeformError, Deformer, Method, MethodOptions, MlsOptions,
};
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
    triangulate(&outline, &TriangulationOptions::default().with_target_edge_length(0.25)).unwrap()
}

fn figure() -> Mesh {
    triangulate(&gingerbread(), &TriangulationOptions::default().with_target_edge_length(0.2)).unwrap()
}

fn size(points: &[Point]) -> f64 {
    points.iter().map(|p| p[0].abs().max(p[1].abs())).fold(0.0, f64::max)
}

fn converged() -> ArapOptions {
    ArapOptions::default().until_converged(1e-12, 20_000)
}

/// The Jacobian `[[a, b], [c, d]]` of the affine map taking rest triangle `r` to `p`.
fn jacobian(r: [Point; 3], p: [Point; 3]) -> [[f64; 2]; 2] {
    let (e1, e2) = ([r[1][0] - r[0][0], r[1][1] - r[0][1]], [r[2][0] - r[0][0], r[2][1] - r[0][1]]);
    let (f1, f2) = ([p[1][0] - p[0][0], p[1][1] - p[0][1]], [p[2][0] - p[0][0], p[2][1] - p[0][1]]);
    let det = e1[0] * e2[1] - e2[0] * e1[1];
    let inv = [[e2[1] / det, -e2[0] / det], [-e1[1] / det, e1[0] / det]];
    let mut j = [[0.0; 2]; 2];
    for k in 0..2 {
        j[k][0] = f1[k] * inv[0][0] + f2[k] * inv[1][0];
        j[k][1] = f1[k] * inv[0][1] + f2[k] * inv[1][1];
    }
    j
}

/// The rotation closest to `j` in SO(2), as `(cos, sin)`: it maximises
/// `tr(R^T J) = cos (a + d) + sin (c - b)`.
fn closest_rotation(j: [[f64; 2]; 2]) -> [f64; 2] {
    let (x, y) = (j[0][0] + j[1][1], j[1][0] - j[0][1]);
    let r = x.hypot(y);
    [x / r, y / r]
}

fn corners(points: &[Point], t: [u32; 3]) -> [Point; 3] {
    t.map(|v| points[v as usize])
}

/// `sum_t A_t min_R |J_t - R|_F^2 = sum_t A_t (|J|^2 - 2 |(a + d, c - b)| + 2)`.
fn arap_energy(mesh: &Mesh, u: &[Point]) -> f64 {
    mesh.triangles()
        .iter()
        .map(|&t| {
            let area = mesh.signed_triangle_area(&t);
            let j = jacobian(corners(mesh.positions(), t), corners(u, t));
            let norm2 = j[0][0].powi(2) + j[0][1].powi(2) + j[1][0].powi(2) + j[1][1].powi(2);
            area * (norm2 - 2.0 * (j[0][0] + j[1][1]).hypot(j[1][0] - j[0][1]) + 2.0)
        })
        .sum()
}

/// The gradient of `sum_t A_t |J_t - R_t|^2` with `R_t` the closest rotations (by the
/// envelope theorem, the gradient of the ARAP energy): `2 A_t (J_t - R_t) grad phi_i`.
fn arap_gradient(mesh: &Mesh, u: &[Point]) -> Vec<[f64; 2]> {
    let mut g = vec![[0.0; 2]; mesh.vertex_count()];
    for &t in mesh.triangles() {
        let r = corners(mesh.positions(), t);
        let area = mesh.signed_triangle_area(&t);
        let j = jacobian(r, corners(u, t));
        let [c, s] = closest_rotation(j);
        let m = [[j[0][0] - c, j[0][1] + s], [j[1][0] - s, j[1][1] - c]];
        for i in 0..3 {
            // grad phi_i = rot90(r_{i+2} - r_{i+1}) / (2A), rot90(x, y) = (-y, x).
            let (b, e) = (r[(i + 1) % 3], r[(i + 2) % 3]);
            let grad = [-(e[1] - b[1]) / (2.0 * area), (e[0] - b[0]) / (2.0 * area)];
            let v = t[i] as usize;
            for k in 0..2 {
                g[v][k] += 2.0 * area * (m[k][0] * grad[0] + m[k][1] * grad[1]);
            }
        }
    }
    g
}

/// The rigid motion: rotation by `angle` about `centre`, then translation by `shift`.
fn rigid(angle: f64, centre: Point, shift: [f64; 2]) -> impl Fn(Point) -> Point {
    let (s, c) = angle.sin_cos();
    move |p| {
        let r = [p[0] - centre[0], p[1] - centre[1]];
        [centre[0] + c * r[0] - s * r[1] + shift[0], centre[1] + s * r[0] + c * r[1] + shift[1]]
    }
}

fn random_points(mesh: &Mesh, count: usize, rng: &mut Rng) -> (Vec<u32>, Vec<[f64; 3]>) {
    let tris = (0..count).map(|_| rng.below(mesh.triangle_count()) as u32).collect();
    let weights = (0..count)
        .map(|_| {
            let (x, y) = (rng.unit(), rng.unit());
            let (x, y) = if x + y > 1.0 { (1.0 - x, 1.0 - y) } else { (x, y) };
            [1.0 - x - y, x, y]
        })
        .collect();
    (tris, weights)
}

fn velocities_to(deformer: &Deformer, targets: &[Point]) -> Vec<[f64; 2]> {
    deformer.handle_positions().iter().zip(targets).map(|(p, t)| [t[0] - p[0], t[1] - p[1]]).collect()
}

#[test]
fn rigid_targets_give_a_rigid_result() {
    let mut rng = Rng::new(2008);
    // Random handles on the bar; on the figure, handles at its extremities (random ones
    // may leave a limb free, whose rotation converges slowly, which only costs time).
    let extremities = [[-0.25, 0.0], [0.25, 0.0], [0.6, 0.62], [-0.5, 1.2], [0.0, 1.25]];
    for (mesh, spread) in [(bar_with_holes(), false), (figure(), true)] {
        let scale = size(mesh.positions());
        for (angle, centre, shift, points) in [
            (0.3, [1.0, 0.2], [0.0, 0.0], false),
            (-1.1, [-2.0, 3.0], [0.5, -0.25], true),
            (2.5, [0.5, 0.5], [1.0, 2.0], false),
        ] {
            let motion = rigid(angle, centre, shift);
            let mut deformer = Deformer::new(mesh.clone(), converged()).unwrap();
            let (mut tris, weights) = random_points(&mesh, 4, &mut rng);
            let mut vertices: Vec<u32> = (0..4).map(|_| rng.below(mesh.vertex_count()) as u32).collect();
            if spread {
                tris = extremities.iter().map(|&p| triangle_near(&mesh, p)).collect();
                vertices = tris.iter().map(|&t| mesh.triangles()[t as usize][0]).collect();
            }
            if points {
                deformer.set_handle_points(&tris, &weights[..1].repeat(tris.len())).unwrap();
            } else {
                deformer.set_handle_vertices(&vertices).unwrap();
            }
            let targets: Vec<Point> = deformer.handle_positions().into_iter().map(&motion).collect();
            deformer.step(&velocities_to(&deformer, &targets)).unwrap();
            assert!(deformer.arap().unwrap().report().converged, "{:?}", deformer.arap().unwrap().report());
            let tol = 1e-9 * (scale + size(&[centre]) + size(&[shift]));
            for (p, q) in mesh.positions().iter().zip(deformer.positions()) {
                let e = motion(*p);
                assert!((q[0] - e[0]).hypot(q[1] - e[1]) <= tol, "{q:?} vs {e:?}");
            }
            let m = deformer.metrics();
            assert!((m.area_distortion - 2.0).abs() < 1e-9 && (m.angle_distortion - 2.0).abs() < 1e-9, "{m:?}");
            assert!(deformer.energy().unwrap() <= 1e-16 * mesh.area() * deformer.arap().unwrap().penalty_weight());
        }
    }
}

/// A pulled pose: pinned vertices (handles at points on vertices, so hard constraints)
/// and handles strictly inside triangles (penalty handles), pulled once.
struct Pulled {
    mesh: Mesh,
    deformer: Deformer,
    pinned: Vec<u32>,
    triangles: Vec<u32>,
    weights: Vec<[f64; 3]>,
}

/// The triangle whose centroid is nearest `p`.
fn triangle_near(mesh: &Mesh, p: Point) -> u32 {
    let distance = |t: u32| {
        let c = corners(mesh.positions(), mesh.triangles()[t as usize]);
        ((c[0][0] + c[1][0] + c[2][0]) / 3.0 - p[0]).hypot((c[0][1] + c[1][1] + c[2][1]) / 3.0 - p[1])
    };
    (0..mesh.triangle_count() as u32).min_by(|&a, &b| distance(a).total_cmp(&distance(b))).unwrap()
}

/// `pinned` vertices held in place and `pulled` points `(triangle near, weights, velocity)`.
fn pull(mesh: Mesh, iterations: usize, pinned: Vec<u32>, pulled: &[(Point, [f64; 3], [f64; 2])]) -> Pulled {
    let mut deformer = Deformer::new(mesh.clone(), ArapOptions::default().with_iterations(iterations)).unwrap();
    let (mut triangles, mut weights) = (Vec::new(), Vec::new());
    for &v in &pinned {
        let t = mesh.triangles().iter().position(|t| t.contains(&v)).unwrap();
        triangles.push(t as u32);
        weights.push(mesh.triangles()[t].map(|w| if w == v { 1.0 } else { 0.0 }));
    }
    for &(p, w, _) in pulled {
        triangles.push(triangle_near(&mesh, p));
        weights.push(w);
    }
    deformer.set_handle_points(&triangles, &weights).unwrap();
    let mut velocities = vec![[0.0, 0.0]; pinned.len()];
    velocities.extend(pulled.iter().map(|&(_, _, v)| v));
    deformer.step(&velocities).unwrap();
    Pulled { mesh, deformer, pinned, triangles, weights }
}

/// The figure with both feet pinned and the raised hand and the head pulled.
fn pulled_figure() -> Pulled {
    let mesh = figure();
    let lowest = |x: f64| {
        (0..mesh.vertex_count() as u32)
            .filter(|&v| (mesh.positions()[v as usize][0] - x).abs() < 0.1)
            .min_by(|&a, &b| mesh.positions()[a as usize][1].total_cmp(&mesh.positions()[b as usize][1]))
            .unwrap()
    };
    let feet = vec![lowest(-0.25), lowest(0.25)];
    pull(mesh, 1, feet, &[([-0.47, 1.15], [0.2, 0.3, 0.5], [0.35, -0.3]), ([0.0, 1.2], [1.0 / 3.0; 3], [0.15, -0.05])])
}

/// The bar with holes, its left end pinned and two points of its right end lifted.
fn pulled_bar() -> Pulled {
    let mesh = bar_with_holes();
    let left = (0..mesh.vertex_count() as u32).filter(|&v| mesh.positions()[v as usize][0] == 0.0).collect();
    pull(mesh, 10, left, &[([3.8, 0.2], [0.2, 0.3, 0.5], [-0.5, 1.0]), ([3.8, 0.8], [1.0 / 3.0; 3], [-0.6, 1.0])])
}

/// The penalty part of the energy, `w/2 sum_h |h - target_h|^2` over the penalty handles.
fn penalty_energy(pulled: &Pulled) -> f64 {
    let d = &pulled.deformer;
    let w = d.arap().unwrap().penalty_weight();
    let handles = d.handle_positions();
    let miss = handles.iter().zip(d.arap().unwrap().targets()).skip(pulled.pinned.len());
    miss.map(|(p, t)| 0.5 * w * ((p[0] - t[0]).powi(2) + (p[1] - t[1]).powi(2))).sum()
}

#[test]
fn the_energy_never_increases_over_iterations() {
    let mut pulled = pulled_figure();
    let mut last = f64::INFINITY;
    for iteration in 0..200 {
        let ours = arap_energy(&pulled.mesh, pulled.deformer.positions()) + penalty_energy(&pulled);
        let theirs = pulled.deformer.energy().unwrap();
        assert!((ours - theirs).abs() <= 1e-9 * ours, "iteration {iteration}: {ours} vs {theirs}");
        assert!(ours <= last * (1.0 + 1e-12), "iteration {iteration}: {ours} after {last}");
        last = ours;
        pulled.deformer.iterate(1, 0.0).unwrap();
    }
    assert!(last > 1e-3, "the pose is bent, the energy {last} cannot vanish");
}

#[test]
fn at_convergence_the_optimality_conditions_hold() {
    let Pulled { mesh, mut deformer, pinned, triangles, weights } = pulled_bar();
    let report = deformer.iterate(20_000, 1e-14).unwrap();
    assert!(report.converged, "{report:?}");
    let u = deformer.positions().to_vec();

    // Pinned vertices sit exactly at their targets (they did not move).
    for &v in &pinned {
        assert_eq!(u[v as usize], mesh.positions()[v as usize]);
    }
    // Global step: at every free vertex the gradient of the energy vanishes, i.e. the
    // ARAP gradient balances the penalty forces w beta (h - target).
    let arap = arap_gradient(&mesh, &u);
    let mut gradient = arap.clone();
    let w = deformer.arap().unwrap().penalty_weight();
    let handles = deformer.handle_positions();
    for k in pinned.len()..handles.len() {
        let (h, t) = (handles[k], deformer.arap().unwrap().targets()[k]);
        let verts = mesh.triangles()[triangles[k] as usize];
        for i in 0..3 {
            for c in 0..2 {
                gradient[verts[i] as usize][c] += w * weights[k][i] * (h[c] - t[c]);
            }
        }
    }
    // The scale of the forces: the largest ARAP force anywhere (at the pinned end).
    let force = arap.iter().map(|g| g[0].hypot(g[1])).fold(0.0, f64::max);
    assert!(force > 1e-3);
    // The penalty force is known only to w times the rounding of h - target.
    let tol = 1e-8 * force + 10.0 * w * f64::EPSILON * size(&u);
    for (v, g) in gradient.iter().enumerate() {
        if !pinned.contains(&(v as u32)) {
            assert!(g[0].hypot(g[1]) <= tol, "vertex {v}: gradient {g:?}, forces up to {force}");
        }
    }
    // Local step: each rotation is the polar factor of its triangle's Jacobian, R^T J
    // symmetric positive definite (no triangle is flipped here).
    assert_eq!(deformer.metrics().flipped, 0);
    for (&t, r) in mesh.triangles().iter().zip(deformer.arap().unwrap().rotations()) {
        let j = jacobian(corners(mesh.positions(), t), corners(&u, t));
        let [c, s] = *r;
        let rtj = [
            [c * j[0][0] + s * j[1][0], c * j[0][1] + s * j[1][1]],
            [-s * j[0][0] + c * j[1][0], -s * j[0][1] + c * j[1][1]],
        ];
        let norm = j.iter().flatten().map(|x| x.abs()).fold(0.0, f64::max);
        assert!((rtj[0][1] - rtj[1][0]).abs() <= 1e-9 * norm, "R^T J = {rtj:?} is not symmetric");
        assert!(rtj[0][0] > 0.0 && rtj[0][0] * rtj[1][1] - rtj[0][1] * rtj[1][0] > 0.0, "R^T J = {rtj:?}");
    }
}

#[test]
fn a_bent_bar_converges_to_a_low_distortion_pose() {
    let (length, width) = (8.0, 1.0);
    let outline = Outline::new(vec![[0.0, 0.0], [length, 0.0], [length, width], [0.0, width]]);
    let mesh = triangulate(&outline, &TriangulationOptions::default().with_target_edge_length(0.25)).unwrap();
    let at_x = |x: f64| -> Vec<u32> {
        (0..mesh.vertex_count() as u32).filter(|&v| mesh.positions()[v as usize][0] == x).collect()
    };
    let (left, right) = (at_x(0.0), at_x(length));
    let handles: Vec<u32> = left.iter().chain(&right).copied().collect();
    let rest: Vec<Point> = handles.iter().map(|&v| mesh.positions()[v as usize]).collect();
    let mut deformer = Deformer::new(mesh.clone(), ArapOptions::default().with_iterations(10)).unwrap();
    deformer.set_handle_vertices(&handles).unwrap();
    // The centre line bent into a quarter circle of the same length: the right end goes to
    // R (sin phi, 1 - cos phi), R = length / phi, turned by phi (an isometric target).
    let steps = 30;
    let mut targets = rest.clone();
    for k in 1..=steps {
        let phi = std::f64::consts::FRAC_PI_2 * k as f64 / steps as f64;
        let radius = length / phi;
        let end = [radius * phi.sin(), width / 2.0 + radius * (1.0 - phi.cos())];
        let (s, c) = phi.sin_cos();
        for (i, r) in rest.iter().enumerate().skip(left.len()) {
            let y = r[1] - width / 2.0;
            targets[i] = [end[0] - s * y, end[1] + c * y];
        }
        deformer.step(&velocities_to(&deformer, &targets)).unwrap();
    }
    let report = deformer.iterate(20_000, 1e-12).unwrap();
    assert!(report.converged, "{report:?}");
    for (p, t) in deformer.handle_positions().iter().zip(&targets) {
        assert_eq!(p, t, "hard constraints hold exactly");
    }
    let m = deformer.metrics();
    assert_eq!(m.flipped, 0);
    assert!(m.area_distortion < 2.02 && m.angle_distortion < 2.02, "{m:?}");
    // The bar kept its length: the centre line's ends are a quarter circle's chord apart.
    assert!(arap_energy(&mesh, deformer.positions()) < 0.01 * mesh.area());
}

#[test]
fn zero_and_one_handle() {
    let mesh = bar_with_holes();
    let mut deformer = Deformer::new(mesh.clone(), ArapOptions::default()).unwrap();
    deformer.step(&[]).unwrap();
    assert_eq!(deformer.positions(), mesh.positions());
    // One handle point (a penalty handle): the shape translates with it.
    deformer.set_handle_points(&[7], &[[0.2, 0.3, 0.5]]).unwrap();
    deformer.step(&[[0.25, -0.5]]).unwrap();
    for (p, q) in mesh.positions().iter().zip(deformer.positions()) {
        assert!((q[0] - p[0] - 0.25).abs() < 1e-9 && (q[1] - p[1] + 0.5).abs() < 1e-9, "{q:?} from {p:?}");
    }
    // The same vertex twice: pinned at the mean of the two targets.
    deformer.reset();
    assert_eq!(deformer.positions(), mesh.positions());
    deformer.set_handle_vertices(&[5, 5]).unwrap();
    deformer.step(&[[1.0, 0.0], [0.0, 1.0]]).unwrap();
    for (p, q) in mesh.positions().iter().zip(deformer.positions()) {
        assert!((q[0] - p[0] - 0.5).abs() < 1e-12 && (q[1] - p[1] - 0.5).abs() < 1e-12);
    }
}

#[test]
fn bad_input_is_refused_and_changes_nothing() {
    let mesh = bar_with_holes();
    let mut deformer = Deformer::new(mesh.clone(), ArapOptions::default()).unwrap();
    deformer.set_handle_vertices(&[0, 10]).unwrap();
    deformer.step(&[[0.0, 0.0], [0.1, 0.1]]).unwrap();
    let before = deformer.positions().to_vec();
    let rotations = deformer.arap().unwrap().rotations().to_vec();
    let targets = deformer.arap().unwrap().targets().to_vec();
    let n = mesh.vertex_count() as u32;
    let m = mesh.triangle_count() as u32;

    assert!(matches!(deformer.set_handle_vertices(&[0, n]), Err(DeformError::VertexOutOfRange { handle: 1, .. })));
    assert!(matches!(
        deformer.set_handle_points(&[m], &[[1.0, 0.0, 0.0]]),
        Err(DeformError::TriangleOutOfRange { .. })
    ));
    for w in [[0.5, 0.4, 0.0], [1.5, -0.5, 0.0], [f64::NAN, 0.5, 0.5]] {
        assert!(matches!(deformer.set_handle_points(&[0], &[w]), Err(DeformError::InvalidBarycentric { .. })));
    }
    assert!(matches!(deformer.set_handle_points(&[0, 1], &[[1.0, 0.0, 0.0]]), Err(DeformError::Length { .. })));
    assert!(matches!(deformer.step(&[[0.0, 0.0]]), Err(DeformError::Length { expected: 4, found: 2, .. })));
    assert!(matches!(
        deformer.step(&[[0.0, 0.0], [f64::INFINITY, 0.0]]),
        Err(DeformError::NonFiniteVelocity { handle: 1 })
    ));
    assert!(matches!(
        deformer.set_options(ArapOptions::default().with_iterations(0)),
        Err(DeformError::InvalidOption { name: "iterations", .. })
    ));
    assert!(matches!(
        deformer.set_options(ArapOptions::default().until_converged(-1.0, 10)),
        Err(DeformError::InvalidOption { name: "tolerance", .. })
    ));
    assert!(matches!(deformer.iterate(0, 0.0), Err(DeformError::InvalidOption { name: "iterations", .. })));
    assert!(matches!(
        deformer.set_method_options(MethodOptions::Akap(AkapOptions::default())),
        Err(DeformError::WrongMethod { current: Method::Arap, given: Method::Akap })
    ));
    assert_eq!(deformer.handle_count(), 2);
    assert_eq!(deformer.options(), MethodOptions::Arap(ArapOptions::default()));
    assert_eq!(deformer.positions(), before.as_slice());
    assert_eq!(deformer.arap().unwrap().rotations(), rotations.as_slice());
    assert_eq!(deformer.arap().unwrap().targets(), targets.as_slice());
    // The handles set before the errors still work.
    deformer.step(&[[0.0, 0.0], [0.1, 0.1]]).unwrap();

    let two = Mesh::new(
        vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [5.0, 0.0], [6.0, 0.0], [5.0, 1.0]],
        vec![[0, 1, 2], [3, 4, 5]],
    )
    .unwrap();
    assert_eq!(Deformer::new(two, ArapOptions::default()).unwrap_err(), DeformError::Disconnected { components: 2 });
    assert!(matches!(
        Deformer::new(mesh, ArapOptions::default().with_iterations(0)),
        Err(DeformError::InvalidOption { .. })
    ));
}

#[test]
fn every_method_behind_one_interface() {
    let mesh = bar_with_holes();
    for options in [
        MethodOptions::Akap(AkapOptions::default()),
        MethodOptions::Arap(ArapOptions::default()),
        MethodOptions::Mls(MlsOptions::default()),
        MethodOptions::CauchyGreen(CauchyGreenOptions::default()),
    ] {
        let mut deformer: Deformer = Deformer::new(mesh.clone(), options).unwrap();
        assert_eq!(deformer.options(), options);
        deformer.set_handle_vertices(&[0, 30]).unwrap();
        let start = deformer.handle_positions();
        deformer.step(&[[0.0, 0.0], [0.05, 0.02]]).unwrap();
        let moved = deformer.handle_positions();
        // Each moves the dragged handle the right way and leaves the pinned one near.
        assert!((moved[0][0] - start[0][0]).hypot(moved[0][1] - start[0][1]) < 0.01);
        assert!(moved[1][0] > start[1][0] && moved[1][1] > start[1][1]);
        let field = deformer.field().to_vec();
        assert_eq!(field.len(), mesh.vertex_count());
        assert!(deformer.metrics().area_distortion >= 2.0);
        deformer.reset();
        assert_eq!(deformer.positions(), mesh.positions());
        let other = match options.method() {
            Method::Akap => MethodOptions::Arap(ArapOptions::default()),
            Method::Arap | Method::Mls | Method::CauchyGreen => MethodOptions::Akap(AkapOptions::default()),
        };
        assert!(matches!(deformer.set_method_options(other), Err(DeformError::WrongMethod { .. })));
    }
}
