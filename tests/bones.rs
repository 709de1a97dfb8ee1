//! Bones (issue 23): a segment drawn on the shape whose triangles move as one rigid body.
//! Expected values from the mathematics: under any drag, points sampled along the bone at
//! rest stay on the segment between its ends, at their fraction of the way, and the ends
//! keep the rest length, to 1e-9 of the shape's size (the same drag without the bone bends
//! that segment by far more); a handle on the bone moves and turns it as a whole; the rest
//! of the shape follows without folding; bad bones change nothing; methods without bones
//! refuse them; a method switch carries them; a session with a bones event replays to the
//! same bits. Runs natively and as wasm.

use akap::deform::{AkapOptions, ArapOptions, DeformError, Deformer, Integrator, MethodOptions, MlsOptions};
use akap::geometry::Point;
use akap::pose::replay;
use akap::session::{Event, Session};
use akap::shapes::grid_mesh;
use akap::Mesh;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

const COLUMNS: usize = 24;
const ROWS: usize = 4;

/// The triangle of `mesh` at rest containing `p`, and `p`'s barycentric coordinates in it.
fn locate(mesh: &Mesh, p: Point) -> (u32, [f64; 3]) {
    for (t, corners) in mesh.triangles().iter().enumerate() {
        let [a, b, c] = corners.map(|v| mesh.positions()[v as usize]);
        let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        let wa = ((b[0] - p[0]) * (c[1] - p[1]) - (b[1] - p[1]) * (c[0] - p[0])) / area;
        let wb = ((c[0] - p[0]) * (a[1] - p[1]) - (c[1] - p[1]) * (a[0] - p[0])) / area;
        let w = [wa, wb, 1.0 - wa - wb];
        if w.iter().all(|&x| x >= 0.0) {
            return (t as u32, w);
        }
    }
    panic!("{p:?} is not in the mesh");
}

/// The point of triangle `t` at barycentric `w` when the vertices are at `positions`.
fn at(mesh: &Mesh, positions: &[Point], (t, w): (u32, [f64; 3])) -> Point {
    let c = mesh.triangles()[t as usize].map(|v| positions[v as usize]);
    [0, 1].map(|i| w[0] * c[0][i] + w[1] * c[1][i] + w[2] * c[2][i])
}

/// The bone's ends at rest, across the grid's lines at a slant.
const BONE: [Point; 2] = [[7.3, 2.1], [16.6, 1.45]];

/// The points a tenth of the way apart along the bone at rest (its ends first and last),
/// as mesh points.
fn bone_samples(mesh: &Mesh) -> Vec<(u32, [f64; 3])> {
    let along = |t: f64| [BONE[0][0] + t * (BONE[1][0] - BONE[0][0]), BONE[0][1] + t * (BONE[1][1] - BONE[0][1])];
    (0..=10).map(|k| locate(mesh, along(k as f64 / 10.0))).collect()
}

/// Sets the bone on `deformer` (at rest) and returns [`bone_samples`].
fn bone(mesh: &Mesh, deformer: &mut Deformer) -> Vec<(u32, [f64; 3])> {
    let points = bone_samples(mesh);
    let [a, b] = [points[0], points[10]];
    deformer.set_bones(&[a.0, b.0], &[a.1, b.1]).unwrap();
    points
}

/// How far the bone is from rigid: the largest of its length's change and each sampled
/// point's distance from where it belongs on the segment between the ends.
fn bend_of_bone(mesh: &Mesh, positions: &[Point], points: &[(u32, [f64; 3])]) -> f64 {
    let [a, b] = [at(mesh, positions, points[0]), at(mesh, positions, points[10])];
    let rest = (BONE[1][0] - BONE[0][0]).hypot(BONE[1][1] - BONE[0][1]);
    let mut worst = ((b[0] - a[0]).hypot(b[1] - a[1]) - rest).abs();
    for (k, &p) in points.iter().enumerate() {
        let t = k as f64 / 10.0;
        let q = at(mesh, positions, p);
        let on = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
        worst = worst.max((q[0] - on[0]).hypot(q[1] - on[1]));
    }
    worst
}

/// A pseudo-random number in [-1, 1) from a 64-bit state (SplitMix64).
fn random(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

fn methods() -> Vec<MethodOptions> {
    vec![
        MethodOptions::Akap(AkapOptions::default()),
        MethodOptions::Akap(AkapOptions::default().with_dirichlet(false)),
        MethodOptions::Akap(AkapOptions { integrator: Integrator::Linear, ..AkapOptions::default() }),
        MethodOptions::Arap(ArapOptions::default()),
    ]
}

/// The left end's corners pinned and a handle at the right end's middle dragged about at
/// random, turning too, for 40 steps; with a bone (`with_bone`) or without. Returns the
/// worst bend of the bone's segment over the steps and the deformer.
fn drag(method: MethodOptions, with_bone: bool, seed: u64) -> (f64, Deformer) {
    let mesh = grid_mesh(COLUMNS, ROWS);
    let mut deformer = Deformer::new(mesh.clone(), method).unwrap();
    let points = if with_bone { bone(&mesh, &mut deformer) } else { bone_samples(&mesh) };
    let right = locate(&mesh, [COLUMNS as f64 - 0.3, ROWS as f64 / 2.0]);
    let handles = [locate(&mesh, [0.0, 0.0]), locate(&mesh, [0.0, ROWS as f64]), right];
    let (triangles, weights): (Vec<u32>, Vec<[f64; 3]>) = handles.iter().copied().unzip();
    deformer.set_handle_points(&triangles, &weights).unwrap();
    let turns = deformer.has_bones();
    let mut state = seed;
    let mut worst: f64 = 0.0;
    for _ in 0..40 {
        let v = [0.0, 0.0, 0.0, 0.0, 0.4 * random(&mut state), 0.4 * random(&mut state)];
        let v: Vec<[f64; 2]> = v.chunks(2).map(|p| [p[0], p[1]]).collect();
        let turn = if turns { 0.05 * random(&mut state) } else { 0.0 };
        deformer.step_turning(&v, &[0.0, 0.0, turn]).unwrap();
        worst = worst.max(bend_of_bone(&mesh, deformer.positions(), &points));
    }
    (worst, deformer)
}

#[test]
fn a_bone_stays_straight_and_keeps_its_length_under_any_drag() {
    let size = (COLUMNS as f64).hypot(ROWS as f64);
    for method in methods() {
        for seed in [1, 2, 3] {
            let (worst, deformer) = drag(method, true, seed);
            assert!(worst <= 1e-9 * size, "{method:?} seed {seed}: the bone bends by {worst:e}");
            assert_eq!(deformer.metrics().flipped, 0, "{method:?} seed {seed}");
            // Without the bone the same drag bends that segment.
            let (free, _) = drag(method, false, seed);
            assert!(free > 1e-3 * size, "{method:?} seed {seed}: without a bone the segment bends by {free:e}");
        }
    }
}

#[test]
fn a_handle_on_the_bone_moves_and_turns_it_as_a_whole() {
    let mesh = grid_mesh(COLUMNS, ROWS);
    for method in methods() {
        let mut deformer = Deformer::new(mesh.clone(), method).unwrap();
        let points = bone(&mesh, &mut deformer);
        // A pin at the left end, a handle in the middle of the bone moved and turned.
        let on_bone = locate(&mesh, [12.0, (BONE[0][1] + BONE[1][1]) / 2.0 + 0.05]);
        let pin = locate(&mesh, [0.5, 2.0]);
        deformer.set_handle_points(&[pin.0, on_bone.0], &[pin.1, on_bone.1]).unwrap();
        for _ in 0..10 {
            deformer.step_turning(&[[0.0, 0.0], [0.1, 0.3]], &[0.0, 0.04]).unwrap();
        }
        let before = [at(&mesh, mesh.positions(), points[0]), at(&mesh, mesh.positions(), points[10])];
        let after = [at(&mesh, deformer.positions(), points[0]), at(&mesh, deformer.positions(), points[10])];
        let direction = |[a, b]: [Point; 2]| (b[1] - a[1]).atan2(b[0] - a[0]);
        let turned = direction(after) - direction(before);
        assert!(turned > 0.05, "{method:?}: the bone turned by {turned}");
        let size = (COLUMNS as f64).hypot(ROWS as f64);
        assert!(bend_of_bone(&mesh, deformer.positions(), &points) <= 1e-9 * size, "{method:?}");
        assert_eq!(deformer.metrics().flipped, 0, "{method:?}");
    }
}

#[test]
fn bad_bones_change_nothing_and_methods_without_bones_refuse_them() {
    let mesh = grid_mesh(COLUMNS, ROWS);
    let mut deformer = Deformer::new(mesh.clone(), MethodOptions::Akap(AkapOptions::default())).unwrap();
    bone(&mesh, &mut deformer);
    let kept = deformer.bone_points();
    assert_eq!(kept.0.len(), 2);
    let [a, b] = BONE.map(|p| locate(&mesh, p));
    let far = locate(&mesh, [22.0, 2.0]);
    let touching = locate(&mesh, [16.8, 1.5]);
    type Case = (Vec<u32>, Vec<[f64; 3]>, &'static str);
    let cases: Vec<Case> = vec![
        (vec![a.0], vec![a.1], "bone triangles has 1 numbers, expected 2 (2 for each of the 1 bones)"),
        (vec![a.0, a.0], vec![a.1, a.1], "bone 0 cannot be used: its ends are at one point"),
        (vec![a.0, 10_000], vec![a.1, b.1], "bone 0 cannot be used: an end names a triangle that does not exist"),
        (
            vec![a.0, b.0],
            vec![a.1, [f64::NAN, 0.5, 0.5]],
            "bone 0 cannot be used: an end's barycentric coordinates are not finite, at least 0 and summing to 1",
        ),
        (
            vec![a.0, b.0, touching.0, far.0],
            vec![a.1, b.1, touching.1, far.1],
            "bone 1 cannot be used: it touches another bone (they share vertices); leave a joint of free \
             triangles between bones",
        ),
    ];
    for (triangles, barycentric, message) in cases {
        let error = deformer.set_bones(&triangles, &barycentric).unwrap_err();
        assert_eq!(error.to_string(), message);
        assert_eq!(deformer.bone_points(), kept);
    }
    // Two bones with a joint between them are fine; none removes them.
    let joint = locate(&mesh, [18.6, 1.5]);
    deformer.set_bones(&[a.0, b.0, joint.0, far.0], &[a.1, b.1, joint.1, far.1]).unwrap();
    deformer.set_bones(&[], &[]).unwrap();
    assert_eq!(deformer.bone_points().0.len(), 0);

    // A segment that leaves the shape: from one tooth of a comb to the next, across the gap.
    let comb = akap::triangulate::triangulate(
        &akap::outline::Outline::new(akap::shapes::comb(3, 6.0)),
        &akap::triangulate::TriangulationOptions::default(),
    )
    .unwrap();
    let mut on_comb = Deformer::new(comb.clone(), MethodOptions::Arap(ArapOptions::default())).unwrap();
    let [p, q] = [[4.0, 0.5], [4.0, 2.5]].map(|x| locate(&comb, x));
    let error = on_comb.set_bones(&[p.0, q.0], &[p.1, q.1]).unwrap_err();
    assert_eq!(error.to_string(), "bone 0 cannot be used: its segment leaves the shape; draw it inside the shape");
    let [p, q] = [[4.0, 0.5], [-0.5, 0.5]].map(|x| locate(&comb, x));
    on_comb.set_bones(&[p.0, q.0], &[p.1, q.1]).unwrap();

    // MLS has no bones: it refuses any and takes none.
    let mut mls = Deformer::new(mesh.clone(), MethodOptions::Mls(MlsOptions::default())).unwrap();
    let error = mls.set_bones(&[a.0, b.0], &[a.1, b.1]).unwrap_err();
    assert!(matches!(error, DeformError::Unsupported { .. }));
    assert_eq!(error.to_string(), "method mls has no bones; choose \"akap\" or \"arap\" for it");
    mls.set_bones(&[], &[]).unwrap();
}

#[test]
fn a_method_switch_carries_bones_and_stiffness_stays_as_painted() {
    let mesh = grid_mesh(COLUMNS, ROWS);
    let mut deformer = Deformer::new(mesh.clone(), MethodOptions::Akap(AkapOptions::default())).unwrap();
    let painted = vec![2.0; mesh.triangle_count()];
    deformer.set_stiffness(Some(&painted)).unwrap();
    let points = bone(&mesh, &mut deformer);
    // The bone's triangles weigh more in the energy, but the painting reads back as painted.
    assert_eq!(deformer.stiffness(), Some(&painted[..]));
    deformer.set_options(MethodOptions::Arap(ArapOptions::default())).unwrap();
    assert_eq!(deformer.bone_points().0.len(), 2);
    assert_eq!(deformer.stiffness(), Some(&painted[..]));
    let pin = locate(&mesh, [0.5, 2.0]);
    let right = locate(&mesh, [23.5, 2.0]);
    deformer.set_handle_points(&[pin.0, right.0], &[pin.1, right.1]).unwrap();
    for _ in 0..20 {
        deformer.step(&[[0.0, 0.0], [-0.2, 0.4]]).unwrap();
    }
    let size = (COLUMNS as f64).hypot(ROWS as f64);
    assert!(bend_of_bone(&mesh, deformer.positions(), &points) <= 1e-9 * size);
    // MLS poses without them.
    deformer.set_options(MethodOptions::Mls(MlsOptions::default())).unwrap();
    assert_eq!(deformer.bone_points().0.len(), 0);
}

#[test]
fn a_bones_event_replays_to_the_same_bits() {
    let mesh = grid_mesh(COLUMNS, ROWS);
    let options = MethodOptions::Akap(AkapOptions::default());
    let mut by_hand = Deformer::new(mesh.clone(), options).unwrap();
    let pin = locate(&mesh, [0.5, 2.0]);
    let right = locate(&mesh, [23.5, 2.0]);
    by_hand.set_handle_points(&[pin.0, right.0], &[pin.1, right.1]).unwrap();
    let v = [[0.0, 0.0], [-0.3, 0.5]];
    by_hand.step(&v).unwrap();
    // The bone is laid in the pose after a step.
    let [a, b] = BONE.map(|p| locate(&mesh, p));
    by_hand.set_bones(&[a.0, b.0], &[a.1, b.1]).unwrap();
    for _ in 0..5 {
        by_hand.step(&v).unwrap();
    }
    let mut s = Session::with_mesh(&mesh, options);
    let step = Event::Step(v.concat());
    s.events = vec![Event::Handles { triangles: vec![pin.0, right.0], barycentric: [pin.1, right.1].concat() }];
    s.events.push(step.clone());
    s.events.push(Event::Bones { triangles: vec![a.0, b.0], barycentric: [a.1, b.1].concat() });
    s.events.extend(std::iter::repeat_n(step, 5));
    let s = Session::from_json(&s.to_json()).unwrap();
    let mut replayed = s.recorded_deformer().unwrap();
    replay(&s, &mut replayed).unwrap();
    let bits = |p: &[Point]| p.iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(replayed.positions()), bits(by_hand.positions()));
    // An odd number of ends is refused on reading.
    let mut bad = s.clone();
    bad.events.push(Event::Bones { triangles: vec![a.0], barycentric: a.1.to_vec() });
    assert_eq!(
        Session::from_json(&bad.to_json()).unwrap_err().to_string(),
        format!("event {}: bone triangles has 1 numbers, expected 2 (2 for each of the 1 bones)", bad.events.len() - 1)
    );
}
