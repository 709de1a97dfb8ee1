//! Turning handles (issue 23): a handle that turns by omega asks its neighbourhood to follow
//! the rigid motion's Killing field `d + omega i (p - c)`. Expected values from the
//! mathematics: one turning handle on a free shape rotates the whole shape about the
//! handle, `c + (p - c) e^(i omega)`, to 1e-9; two handles asked for one rigid motion give
//! the spiral step of that rigid field (eq. (16) with `s = i omega` on every edge) through
//! the full solve, step 2 included; zero turns are the plain step to the bit; a turning
//! handle pinned elsewhere turns its triangle by about omega; bad turns change nothing;
//! methods without turning handles refuse them. Runs natively and as wasm.

use akap::deform::{
    AkapOptions, ArapOptions, DeformError, Deformer, FoldoverGuard, FoldoverStepper, MethodOptions, MlsOptions,
};
use akap::geometry::Point;
use akap::pose::replay;
use akap::session::{Event, Session};
use akap::shapes::grid_mesh;
use akap::Mesh;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

/// A 12 x 6 grid with interior vertices (so step 2 runs).
fn mesh() -> Mesh {
    grid_mesh(12, 6)
}

/// The point of triangle `t` at barycentric `w`.
fn at(mesh: &Mesh, positions: &[Point], t: u32, w: [f64; 3]) -> Point {
    let c = mesh.triangles()[t as usize].map(|v| positions[v as usize]);
    [0, 1].map(|i| w[0] * c[0][i] + w[1] * c[1][i] + w[2] * c[2][i])
}

/// `z (e^(i omega) - 1) / (i omega)` for `z = (x, y)`: the spiral step of the rigid field.
fn spiral_move(u: [f64; 2], omega: f64) -> [f64; 2] {
    let (s, c) = omega.sin_cos();
    // (e^(i w) - 1) / (i w) = (sin w + i (1 - cos w)) / w
    let f = [s / omega, (1.0 - c) / omega];
    [u[0] * f[0] - u[1] * f[1], u[0] * f[1] + u[1] * f[0]]
}

fn largest_gap(a: &[Point], b: &[Point]) -> f64 {
    a.iter().zip(b).map(|(p, q)| (p[0] - q[0]).hypot(p[1] - q[1])).fold(0.0, f64::max)
}

#[test]
fn one_turning_handle_on_a_free_shape_rotates_it_rigidly_about_the_handle() {
    let mesh = mesh();
    for options in [AkapOptions::default(), AkapOptions::default().with_dirichlet(false)] {
        let mut d = Deformer::new(mesh.clone(), options).unwrap();
        let w = [0.2, 0.3, 0.5];
        d.set_handle_points(&[40], &[w]).unwrap();
        let c = at(&mesh, mesh.positions(), 40, w);
        let omega = 0.7;
        let mut angle = 0.0;
        for _ in 0..4 {
            d.step_turning(&[[0.0, 0.0]], &[omega]).unwrap();
            angle += omega;
        }
        let (s, k) = f64::sin_cos(angle);
        let expected: Vec<Point> = mesh
            .positions()
            .iter()
            .map(|p| {
                let (x, y) = (p[0] - c[0], p[1] - c[1]);
                [c[0] + k * x - s * y, c[1] + s * x + k * y]
            })
            .collect();
        assert!(largest_gap(d.positions(), &expected) < 1e-9 * 12.0, "{}", largest_gap(d.positions(), &expected));
    }
}

#[test]
fn two_handles_asked_for_one_rigid_motion_give_its_spiral_step_through_the_full_solve() {
    let mesh = mesh();
    let mut d = Deformer::new(mesh.clone(), AkapOptions::default()).unwrap();
    let (ta, tb) = (30u32, 101u32);
    let (wa, wb) = ([0.3, 0.3, 0.4], [0.6, 0.2, 0.2]);
    d.set_handle_points(&[ta, tb], &[wa, wb]).unwrap();
    let (ca, cb) = (at(&mesh, mesh.positions(), ta, wa), at(&mesh, mesh.positions(), tb, wb));
    let (da, omega) = ([0.4, -0.25], 0.35);
    // The rigid field through (ca, da, omega): its value at cb is b's velocity.
    let field = |p: Point| [da[0] - omega * (p[1] - ca[1]), da[1] + omega * (p[0] - ca[0])];
    d.step_turning(&[da, field(cb)], &[omega, omega]).unwrap();
    // Every vertex: p + u(p) (e^(i omega) - 1) / (i omega), eq. (16) for one s on every edge.
    let expected: Vec<Point> = mesh
        .positions()
        .iter()
        .map(|&p| {
            let m = spiral_move(field(p), omega);
            [p[0] + m[0], p[1] + m[1]]
        })
        .collect();
    assert!(largest_gap(d.positions(), &expected) < 1e-9 * 12.0, "{}", largest_gap(d.positions(), &expected));
    // The field is the rigid one everywhere (both steps).
    for (v, p) in mesh.positions().iter().enumerate() {
        let f = field(*p);
        assert!((d.field()[v][0] - f[0]).abs() < 1e-9 && (d.field()[v][1] - f[1]).abs() < 1e-9);
    }
}

#[test]
fn zero_turns_are_the_plain_step_and_a_pinned_turning_handle_turns_its_triangle() {
    let mesh = mesh();
    let handles = (vec![6u32, 120], vec![[1.0 / 3.0; 3], [0.2, 0.5, 0.3]]);
    let make = || {
        let mut d = Deformer::new(mesh.clone(), AkapOptions::default()).unwrap();
        d.set_handle_points(&handles.0, &handles.1).unwrap();
        d
    };
    let (mut a, mut b) = (make(), make());
    let v = [[0.0, 0.0], [0.3, 0.2]];
    a.step(&v).unwrap();
    b.step_turning(&v, &[0.0, 0.0]).unwrap();
    let bits = |d: &Deformer| d.positions().iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a), bits(&b));

    // Handle 1 turns by 0.4 in 4 steps while handle 0 holds: its triangle's edges turn by
    // about 0.4 (the neighbourhood is asked to, softly, against the pin).
    let mut d = make();
    for _ in 0..4 {
        d.step_turning(&[[0.0, 0.0], [0.0, 0.0]], &[0.0, 0.1]).unwrap();
    }
    let [p, q, _] = mesh.triangles()[120].map(|v| v as usize);
    let direction = |x: &[Point]| (x[q][1] - x[p][1]).atan2(x[q][0] - x[p][0]);
    let turned = direction(d.positions()) - direction(mesh.positions());
    assert!((0.3..0.42).contains(&turned), "turned by {turned}");
    // The pin stayed, to the softness of its constraint (lambda 100).
    let pin = at(&mesh, d.positions(), 6, [1.0 / 3.0; 3]);
    let rest = at(&mesh, mesh.positions(), 6, [1.0 / 3.0; 3]);
    let drift = (pin[0] - rest[0]).hypot(pin[1] - rest[1]);
    assert!(drift < 0.005 * 12.0, "the pin drifted by {drift}");
}

#[test]
fn bad_turns_change_nothing_and_methods_without_them_refuse_them() {
    let mesh = mesh();
    let mut d = Deformer::new(mesh.clone(), AkapOptions::default()).unwrap();
    d.set_handle_vertices(&[0, 50]).unwrap();
    d.step(&[[0.0, 0.0], [0.1, 0.0]]).unwrap();
    let before = d.positions().to_vec();
    let v = [[0.0, 0.0], [0.1, 0.0]];
    assert_eq!(d.step_turning(&v, &[0.0, f64::NAN]), Err(DeformError::NonFiniteTurn { handle: 1 }));
    assert_eq!(
        d.step_turning(&v, &[0.1]).unwrap_err().to_string(),
        "turns has 1 numbers, expected 2 (1 for each of the 2 handles)"
    );
    assert_eq!(d.positions(), &before[..]);

    let mut mls = Deformer::new(mesh, MethodOptions::Mls(MlsOptions::default())).unwrap();
    mls.set_handle_vertices(&[0, 50]).unwrap();
    let error = mls.step_turning(&v, &[0.0, 0.2]).unwrap_err();
    assert_eq!(error.to_string(), "method mls has no turning handles; choose \"akap\" or \"arap\" for it");
    mls.step_turning(&v, &[0.0, 0.0]).unwrap();
}

#[test]
fn turn_events_and_guarded_turning_pieces_replay_to_the_same_bits() {
    let mesh = mesh();
    let handles = (vec![6u32, 120], vec![[1.0 / 3.0; 3], [0.2, 0.5, 0.3]]);
    let make = || {
        let mut d = Deformer::new(mesh.clone(), AkapOptions::default()).unwrap();
        d.set_handle_points(&handles.0, &handles.1).unwrap();
        d
    };
    // Hard turns, guarded: the stepper splits or clamps where a piece would fold.
    let mut guarded = make();
    let mut stepper = FoldoverStepper::new(FoldoverGuard::default()).unwrap();
    let (v, turns) = ([[0.0, 0.0], [1.5, -0.5]], [0.0, 1.2]);
    let mut events = vec![Event::Handles { triangles: handles.0.clone(), barycentric: handles.1.concat() }];
    for _ in 0..6 {
        let report = stepper.step_turning(&mut guarded, &v, &turns).unwrap().clone();
        for f in report.steps {
            events.push(Event::Turn {
                velocities: v.iter().flat_map(|u| [u[0] * f, u[1] * f]).collect(),
                turns: turns.iter().map(|w| w * f).collect(),
            });
        }
    }
    assert!(events.len() > 7, "some step was split: {} events", events.len());
    assert_eq!(akap::deform::foldover::newly_flipped(mesh.positions(), guarded.positions(), mesh.triangles()), 0);
    let mut s = Session::with_mesh(&mesh, MethodOptions::Akap(AkapOptions::default()));
    s.events = events;
    let s = Session::from_json(&s.to_json()).unwrap();
    let mut replayed = s.recorded_deformer().unwrap();
    replay(&s, &mut replayed).unwrap();
    let bits = |p: &[Point]| p.iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(replayed.positions()), bits(guarded.positions()));
    // A turn event with the wrong number of turns is refused on reading.
    let mut bad = s.clone();
    bad.events.push(Event::Turn { velocities: vec![0.0; 4], turns: vec![0.1] });
    assert_eq!(
        Session::from_json(&bad.to_json()).unwrap_err().to_string(),
        format!("event {}: turns has 1 numbers, expected 2 (1 for each of the 2 handles)", bad.events.len() - 1)
    );
}

#[test]
fn arap_turns_a_lone_handle_through_a_rotated_target_frame_toward_the_rigid_rotation() {
    let mesh = mesh();
    let w = [0.2, 0.3, 0.5];
    let c = at(&mesh, mesh.positions(), 40, w);
    let omega: f64 = 0.5;
    let (s, k) = omega.sin_cos();
    let expected: Vec<Point> = mesh
        .positions()
        .iter()
        .map(|p| {
            let (x, y) = (p[0] - c[0], p[1] - c[1]);
            [c[0] + k * x - s * y, c[1] + s * x + k * y]
        })
        .collect();
    // Run to convergence: the rotated shape meets every target at zero energy.
    let mut d = Deformer::new(mesh.clone(), ArapOptions::default().until_converged(1e-14, 100_000)).unwrap();
    d.set_handle_points(&[40], &[w]).unwrap();
    d.step_turning(&[[0.0, 0.0]], &[omega]).unwrap();
    let gap = largest_gap(d.positions(), &expected);
    assert!(gap < 1e-7 * 12.0, "{gap}");
    // A plain step afterwards is the plain handle set's again: a zero velocity moves nothing.
    let pose = d.positions().to_vec();
    d.step(&[[0.0, 0.0]]).unwrap();
    assert!(largest_gap(d.positions(), &pose) < 1e-7 * 12.0);
    // Zero turns are the plain step, bit for bit.
    let make = || {
        let mut d = Deformer::new(mesh.clone(), ArapOptions::default()).unwrap();
        d.set_handle_points(&[6, 120], &[[1.0 / 3.0; 3], w]).unwrap();
        d
    };
    let (mut a, mut b) = (make(), make());
    a.step(&[[0.0, 0.0], [0.3, 0.1]]).unwrap();
    b.step_turning(&[[0.0, 0.0], [0.3, 0.1]], &[0.0, 0.0]).unwrap();
    let bits = |d: &Deformer| d.positions().iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a), bits(&b));
}
