//! Puppets: sheets that overlap at rest, coupled at joints. Expectations come from the
//! geometry (where the joint is, which sheets are held, what a rigid quarter turn is), not
//! from the code's output.

use akap::deform::{AkapOptions, ArapOptions, DeformError, Deformer, Joint, MethodOptions, Part, Puppet};
use akap::geometry::Point;
use akap::pose::Poser;
use akap::{triangulate, ErrorCode, Mesh, Outline, TriangulationOptions};

const TORSO: usize = 0;
const HEAD: usize = 1;
const ARM: usize = 2;
const HAT: usize = 3;
/// Where the arm joins the torso (inside both), and the head the torso.
const SHOULDER: Point = [1.9, 2.55];
const NECK: Point = [1.0, 2.85];

fn rectangle(x0: f64, y0: f64, x1: f64, y1: f64) -> Outline {
    Outline::new(vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]])
}

/// A torso, a head overlapping its top, an arm (in front) overlapping its right shoulder
/// and a hat touching nothing, each meshed on its own and put into one mesh with no vertex
/// shared between parts.
fn figure() -> (Mesh, Puppet) {
    let outlines = [
        ("torso", rectangle(0.0, 0.0, 2.0, 3.0), 0),
        ("head", rectangle(0.4, 2.6, 1.6, 3.8), 1),
        ("arm", rectangle(1.7, 2.3, 4.0, 2.8), 2),
        ("hat", rectangle(0.3, 4.0, 1.7, 4.4), 3),
    ];
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let mut parts = Vec::new();
    for (name, outline, depth) in outlines {
        let mesh = triangulate(&outline, &TriangulationOptions::default().with_target_edge_length(0.12)).unwrap();
        let offset = positions.len() as u32;
        let first = triangles.len() as u32;
        positions.extend_from_slice(mesh.positions());
        triangles.extend(mesh.triangles().iter().map(|t| t.map(|v| v + offset)));
        parts.push(Part { name: name.into(), triangles: (first..triangles.len() as u32).collect(), depth });
    }
    let joints = vec![Joint { point: SHOULDER, parts: [ARM, TORSO] }, Joint { point: NECK, parts: [HEAD, TORSO] }];
    (Mesh::new(positions, triangles).unwrap(), Puppet { parts, joints })
}

fn part_vertices(mesh: &Mesh, puppet: &Puppet, part: usize) -> Vec<usize> {
    let mut vertices: Vec<usize> =
        puppet.parts[part].triangles.iter().flat_map(|&t| mesh.triangles()[t as usize]).map(|v| v as usize).collect();
    vertices.sort_unstable();
    vertices.dedup();
    vertices
}

/// The point `p` of the rest mesh as a triangle of `part` and barycentric coordinates.
fn point_on(mesh: &Mesh, puppet: &Puppet, part: usize, p: Point) -> (u32, [f64; 3]) {
    for &t in &puppet.parts[part].triangles {
        let [a, b, c] = mesh.triangles()[t as usize].map(|v| mesh.positions()[v as usize]);
        let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        let w = |u: Point, v: Point| ((u[0] - p[0]) * (v[1] - p[1]) - (u[1] - p[1]) * (v[0] - p[0])) / area;
        let weights = [w(b, c), w(c, a), w(a, b)];
        if weights.iter().all(|&x| x >= -1e-12) {
            return (t, weights);
        }
    }
    panic!("{p:?} is not on part {part}");
}

fn place(positions: &[Point], mesh: &Mesh, (t, w): (u32, [f64; 3])) -> Point {
    let corners = mesh.triangles()[t as usize];
    let mut p = [0.0, 0.0];
    for (v, w) in corners.iter().zip(w) {
        p[0] += w * positions[*v as usize][0];
        p[1] += w * positions[*v as usize][1];
    }
    p
}

fn distance(a: Point, b: Point) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The rotation angle of the best rigid fit of `from` onto `to` (2D Procrustes) and the
/// largest distance of a point of `to` from the fitted image of `from`.
fn rigid_fit(from: &[Point], to: &[Point]) -> (f64, f64) {
    let n = from.len() as f64;
    let mean = |ps: &[Point]| {
        let s = ps.iter().fold([0.0, 0.0], |s, p| [s[0] + p[0], s[1] + p[1]]);
        [s[0] / n, s[1] / n]
    };
    let (cf, ct) = (mean(from), mean(to));
    let (mut dot, mut cross) = (0.0, 0.0);
    for (p, q) in from.iter().zip(to) {
        let (a, b) = ([p[0] - cf[0], p[1] - cf[1]], [q[0] - ct[0], q[1] - ct[1]]);
        dot += a[0] * b[0] + a[1] * b[1];
        cross += a[0] * b[1] - a[1] * b[0];
    }
    let angle = cross.atan2(dot);
    let (s, c) = angle.sin_cos();
    let worst = from
        .iter()
        .zip(to)
        .map(|(p, q)| {
            let a = [p[0] - cf[0], p[1] - cf[1]];
            distance([ct[0] + c * a[0] - s * a[1], ct[1] + s * a[0] + c * a[1]], *q)
        })
        .fold(0.0, f64::max);
    (angle, worst)
}

/// Pins the torso with two handles and swings the arm's hand a quarter turn up about the
/// shoulder, frame by frame through the interaction loop.
fn swing_arm(options: MethodOptions) -> (Mesh, Puppet, Vec<Point>) {
    let (mesh, puppet) = figure();
    let mut deformer = Deformer::with_puppet(mesh.clone(), options, puppet.clone(), None).unwrap();
    let mut poser = Poser::new(&mut deformer);
    let hand: Point = [3.8, 2.55];
    for (part, p) in [(TORSO, [0.4, 0.4]), (TORSO, [1.6, 0.4]), (ARM, hand)] {
        let (t, w) = point_on(&mesh, &puppet, part, p);
        poser.add_handle(t, w).unwrap();
    }
    let radius = distance(hand, SHOULDER);
    let frames = 60;
    for frame in 1..=frames {
        let angle = std::f64::consts::FRAC_PI_2 * f64::from(frame) / f64::from(frames);
        let target = [SHOULDER[0] + radius * angle.cos(), SHOULDER[1] + radius * angle.sin()];
        poser.set_target(2, target).unwrap();
        for _ in 0..4 {
            poser.advance().unwrap();
        }
    }
    drop(poser);
    if options.method() == akap::deform::Method::Arap {
        // ARAP's iterations lag behind a turn: let them converge at the last targets.
        let report = deformer.iterate(100_000, 1e-9).unwrap();
        assert!(report.converged, "{report:?}");
    }
    let positions = deformer.positions().to_vec();
    (mesh, puppet, positions)
}

fn check_quarter_turn(options: MethodOptions, rigid_tolerance: f64) {
    let (mesh, puppet, posed) = swing_arm(options);
    let rest = mesh.positions();
    let size = {
        let (lo, hi) = akap::geometry::bounding_box(rest.iter().copied()).unwrap();
        distance(lo, hi)
    };
    // The joints' two points stay together.
    for joint in &puppet.joints {
        let front = place(&posed, &mesh, point_on(&mesh, &puppet, joint.parts[0], joint.point));
        let back = place(&posed, &mesh, point_on(&mesh, &puppet, joint.parts[1], joint.point));
        assert!(distance(front, back) < 0.005 * size, "joint {joint:?}: {front:?} and {back:?} apart");
    }
    // The torso (held) and the head (joined to it only) stay put.
    for part in [TORSO, HEAD] {
        let worst =
            part_vertices(&mesh, &puppet, part).iter().map(|&v| distance(rest[v], posed[v])).fold(0.0, f64::max);
        assert!(worst < 0.005 * size, "{} moved {worst} (size {size})", puppet.parts[part].name);
    }
    // The free hat does not move at all.
    for v in part_vertices(&mesh, &puppet, HAT) {
        assert!(distance(rest[v], posed[v]) <= 1e-10 * size, "the hat's vertex {v} moved");
    }
    // The arm turned a quarter turn, rigid to within the method's usual distortion.
    let arm = part_vertices(&mesh, &puppet, ARM);
    let from: Vec<Point> = arm.iter().map(|&v| rest[v]).collect();
    let to: Vec<Point> = arm.iter().map(|&v| posed[v]).collect();
    let (angle, worst) = rigid_fit(&from, &to);
    assert!((angle - std::f64::consts::FRAC_PI_2).abs() < 0.05, "the arm turned {angle} rad");
    assert!(worst < rigid_tolerance * size, "the arm is {worst} from rigid (size {size})");
}

#[test]
fn akap_turns_an_arm_about_its_joint_and_nothing_else_moves() {
    check_quarter_turn(AkapOptions::default().into(), 0.01);
}

#[test]
fn arap_turns_an_arm_about_its_joint_and_nothing_else_moves() {
    check_quarter_turn(ArapOptions::default().into(), 0.01);
}

#[test]
fn a_part_held_by_one_hinge_alone_does_not_turn_and_a_free_part_stays() {
    // Only the torso is held and moved sideways: the arm and the head, hinged to it with
    // nothing to turn them, follow without turning; the hat stays.
    for options in [MethodOptions::from(AkapOptions::default()), ArapOptions::default().into()] {
        let (mesh, puppet) = figure();
        let mut poser = Poser::new(Deformer::with_puppet(mesh.clone(), options, puppet.clone(), None).unwrap());
        for p in [[0.4, 0.4], [1.6, 0.4]] {
            let (t, w) = point_on(&mesh, &puppet, TORSO, p);
            poser.add_handle(t, w).unwrap();
        }
        let shift = 0.5;
        for frame in 1..=20 {
            let dx = shift * f64::from(frame) / 20.0;
            poser.set_targets(&[[0.4 + dx, 0.4], [1.6 + dx, 0.4]]).unwrap();
            for _ in 0..3 {
                poser.advance().unwrap();
            }
        }
        for _ in 0..40 {
            poser.advance().unwrap();
        }
        let rest = mesh.positions();
        let posed = poser.deformer().positions();
        for part in [TORSO, HEAD, ARM] {
            for v in part_vertices(&mesh, &puppet, part) {
                let moved = [posed[v][0] - rest[v][0], posed[v][1] - rest[v][1]];
                assert!(
                    distance(moved, [shift, 0.0]) < 0.01 * shift,
                    "{:?}: {} vertex {v} moved {moved:?}",
                    options.method(),
                    puppet.parts[part].name
                );
            }
        }
        for v in part_vertices(&mesh, &puppet, HAT) {
            assert!(distance(rest[v], posed[v]) <= 1e-10, "{:?}: the hat moved", options.method());
        }
    }
}

#[test]
fn moving_least_squares_and_cauchy_green_pose_a_puppet_as_one_shape() {
    use akap::deform::{CauchyGreenOptions, MlsOptions};
    for options in [MethodOptions::from(MlsOptions::default()), CauchyGreenOptions::default().into()] {
        let (mesh, puppet) = figure();
        let mut deformer = Deformer::with_puppet(mesh.clone(), options, puppet.clone(), None).unwrap();
        let points: Vec<(u32, [f64; 3])> = [(TORSO, [0.4, 0.4]), (TORSO, [1.6, 0.4]), (HAT, [1.0, 4.2])]
            .iter()
            .map(|&(part, p)| point_on(&mesh, &puppet, part, p))
            .collect();
        let (triangles, barycentric): (Vec<u32>, Vec<[f64; 3]>) = points.into_iter().unzip();
        deformer.set_handle_points(&triangles, &barycentric).unwrap();
        // Every handle moved by the same translation: the whole puppet, one shape, follows.
        deformer.step(&[[0.1, 0.2], [0.1, 0.2], [0.1, 0.2]]).unwrap();
        for (p, q) in mesh.positions().iter().zip(deformer.positions()) {
            assert!(distance([p[0] + 0.1, p[1] + 0.2], *q) < 1e-3, "{:?}", options.method());
        }
    }
}

#[test]
fn joints_are_placed_anew_and_bad_ones_refused_changing_nothing() {
    let (mesh, puppet) = figure();
    let mut deformer = Deformer::with_puppet(mesh.clone(), AkapOptions::default(), puppet.clone(), None).unwrap();
    let code = |e: DeformError| akap::Error::from(e).code();
    let bad = [
        Joint { point: SHOULDER, parts: [ARM, 7] },
        Joint { point: SHOULDER, parts: [ARM, ARM] },
        Joint { point: [3.5, 2.5], parts: [ARM, TORSO] },
        Joint { point: [f64::NAN, 2.5], parts: [ARM, TORSO] },
    ];
    for joint in bad {
        let error = deformer.set_joints(vec![joint]).unwrap_err();
        assert_eq!(code(error.clone()), ErrorCode::InvalidJoint, "{error}");
        assert_eq!(deformer.puppet().unwrap().joints, puppet.joints);
        let made = Deformer::with_puppet(
            mesh.clone(),
            AkapOptions::default(),
            Puppet { parts: puppet.parts.clone(), joints: vec![joint] },
            None,
        );
        assert_eq!(code(made.unwrap_err()), ErrorCode::InvalidJoint);
    }
    // Parts that do not hold every triangle once.
    let mut parts = puppet.parts.clone();
    parts[HAT].triangles.pop();
    let missing = Deformer::with_puppet(mesh.clone(), AkapOptions::default(), Puppet { parts, joints: vec![] }, None);
    assert!(matches!(missing.unwrap_err(), DeformError::InvalidParts { .. }));
    let mut parts = puppet.parts.clone();
    parts[HAT].triangles.push(0);
    let twice = Deformer::with_puppet(mesh.clone(), AkapOptions::default(), Puppet { parts, joints: vec![] }, None);
    assert!(matches!(twice.unwrap_err(), DeformError::InvalidParts { .. }));
    // Without a puppet, a mesh in pieces is refused as before.
    assert!(matches!(
        Deformer::new(mesh.clone(), AkapOptions::default()).unwrap_err(),
        DeformError::Disconnected { components: 4 }
    ));
    // A joint moved: accepted, and the deformer poses with it.
    let moved = vec![Joint { point: [1.85, 2.4], parts: [ARM, TORSO] }];
    deformer.set_joints(moved.clone()).unwrap();
    assert_eq!(deformer.puppet().unwrap().joints, moved);
    deformer.set_handle_vertices(&[0]).unwrap();
    deformer.step(&[[0.01, 0.0]]).unwrap();
}

#[test]
fn a_recorded_puppet_session_replays_to_the_same_bits() {
    use akap::pose::replay;
    use akap::session::Session;
    for options in [MethodOptions::from(AkapOptions::default()), ArapOptions::default().into()] {
        let (mesh, puppet) = figure();
        let mut poser = Poser::new(Deformer::with_puppet(mesh.clone(), options, puppet.clone(), None).unwrap());
        poser.start_recording(None);
        for (part, p) in [(TORSO, [0.4, 0.4]), (ARM, [3.8, 2.55]), (HEAD, [1.0, 3.5])] {
            let (t, w) = point_on(&mesh, &puppet, part, p);
            poser.add_handle(t, w).unwrap();
        }
        for frame in 1..=10 {
            let f = f64::from(frame);
            poser.set_target(1, [3.8 - 0.05 * f, 2.55 + 0.1 * f]).unwrap();
            poser.set_target(2, [1.0 + 0.02 * f, 3.5]).unwrap();
            poser.advance().unwrap();
            if frame == 5 {
                poser.set_joints(vec![Joint { point: [1.85, 2.5], parts: [ARM, TORSO] }]).unwrap();
            }
        }
        let recorded = poser.deformer().positions().to_vec();
        let session = Session::from_json(&poser.recorded().unwrap().to_json()).unwrap();
        assert_eq!(session.puppet.as_ref().unwrap().puppet().parts, puppet.parts);
        let mut deformer = session.recorded_deformer().unwrap();
        replay(&session, &mut deformer).unwrap();
        assert_eq!(deformer.positions(), &recorded[..], "{:?}", options.method());
        assert_eq!(deformer.puppet().unwrap().joints.len(), 1);
    }
}

#[test]
fn a_turning_handle_at_the_shoulder_turns_the_arm_alone() {
    // ARAP's few iterations a step lag behind a turn that only the handle's neighbourhood is
    // asked to make; with enough of them it turns as far.
    for options in [MethodOptions::from(AkapOptions::default()), ArapOptions { iterations: 300, tolerance: 0.0 }.into()]
    {
        let (mesh, puppet) = figure();
        let mut deformer = Deformer::with_puppet(mesh.clone(), options, puppet.clone(), None).unwrap();
        let mut poser = Poser::new(&mut deformer);
        for (part, p) in [(TORSO, [0.4, 0.4]), (TORSO, [1.6, 0.4]), (ARM, SHOULDER)] {
            let (t, w) = point_on(&mesh, &puppet, part, p);
            poser.add_handle(t, w).unwrap();
        }
        let turn = 0.6;
        poser.set_turn(2, turn).unwrap();
        for _ in 0..40 {
            poser.advance().unwrap();
        }
        drop(poser);
        if options.method() == akap::deform::Method::Arap {
            deformer.iterate(100_000, 1e-9).unwrap();
        }
        let (rest, posed) = (mesh.positions(), deformer.positions());
        let arm = part_vertices(&mesh, &puppet, ARM);
        let from: Vec<Point> = arm.iter().map(|&v| rest[v]).collect();
        let to: Vec<Point> = arm.iter().map(|&v| posed[v]).collect();
        let (angle, worst) = rigid_fit(&from, &to);
        assert!((angle - turn).abs() < 0.03, "{:?}: the arm turned {angle}", options.method());
        assert!(worst < 0.01 * 4.0, "{:?}: the arm is {worst} from rigid", options.method());
        let torso_moved =
            part_vertices(&mesh, &puppet, TORSO).iter().map(|&v| distance(rest[v], posed[v])).fold(0.0, f64::max);
        assert!(torso_moved < 0.03, "{:?}: the torso moved {torso_moved}", options.method());
    }
}
