//! The interaction loop (`pose::Poser`): a frame takes the handles the rest of the way to
//! their targets in as many substeps as the longest step allows; rigid drags and turns move
//! the shape rigidly; every plain step a frame takes, guarded pieces and turns included, is
//! recorded so that the session replays to the same bits; a step that stops short leaves the
//! handles no pointer holds where they stopped; the paper's mode moves a handle by its
//! target's motion; a rig poses the shape with the operator's own evaluation, once per new
//! set of targets; bad targets and indices are refused with nothing changed. Runs natively
//! and as wasm.

use akap::defop::file::read_operator;
use akap::defop::Operator;
use akap::deform::{AkapOptions, ArapOptions, DeformError, Deformer, MethodOptions, MlsOptions, MlsVariant};
use akap::geometry::Point;
use akap::pose::{replay, Poser, Tracking, MAX_TURN_STEP};
use akap::session::Event;
use akap::shapes::grid_mesh;
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

const COLUMNS: usize = 20;
const ROWS: usize = 4;

fn vertex(x: usize, y: usize) -> u32 {
    (y * (COLUMNS + 1) + x) as u32
}

/// A poser of the bar `[0, 20] x [0, 4]` (size 20) with handles on the left end's middle
/// and the right end's middle.
fn bar(method: impl Into<MethodOptions>) -> Poser {
    let mut poser = Poser::new(Deformer::new(grid_mesh(COLUMNS, ROWS), method).unwrap());
    poser.set_handle_vertices(&[vertex(0, ROWS / 2), vertex(COLUMNS, ROWS / 2)]).unwrap();
    poser
}

fn bits(points: &[Point]) -> Vec<u64> {
    points.iter().flatten().map(|x| x.to_bits()).collect()
}

fn distance(a: Point, b: Point) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

#[test]
fn a_frame_takes_as_many_substeps_as_the_longest_step_allows() {
    // ARAP pins vertex handles exactly, so the handle ends on its target.
    let mut poser = bar(ArapOptions::default());
    assert_eq!(poser.size(), 20.0);
    poser.set_tracking(Tracking { max_step: 0.02, max_substeps: 8, ..Tracking::default() }).unwrap();
    // 1.3 away with substeps of at most 0.02 * 20 = 0.4: ceil(3.25) = 4 substeps.
    poser.set_target(1, [21.3, 2.0]).unwrap();
    let report = poser.advance().unwrap();
    assert_eq!(report.steps, 4);
    assert!(!report.clamped);
    let at = poser.deformer().handle_positions()[1];
    assert!(distance(at, [21.3, 2.0]) < 1e-12, "{at:?}");
    // Reached: the next frame does nothing.
    assert_eq!(poser.advance().unwrap().steps, 0);
    // 10 away needs 25 substeps: a frame takes 8 of them, each a 25th of the way at first,
    // so the handle is 8/25 of the way there after it.
    poser.set_target(1, [31.3, 2.0]).unwrap();
    let before = poser.deformer().handle_positions()[1];
    assert_eq!(poser.advance().unwrap().steps, 8);
    let at = poser.deformer().handle_positions()[1];
    assert!((distance(at, before) - 10.0 * 8.0 / 25.0).abs() < 1e-9, "{at:?}");
}

#[test]
fn a_drag_of_every_handle_by_one_vector_translates_the_shape() {
    for method in [MethodOptions::Akap(AkapOptions::default()), MethodOptions::Arap(ArapOptions::default())] {
        let mut poser = bar(method);
        let rest = poser.deformer().positions().to_vec();
        let d = [3.0, -1.5];
        let targets: Vec<Point> = poser.targets().map(|t| [t[0] + d[0], t[1] + d[1]]).collect();
        poser.set_targets(&targets).unwrap();
        for _ in 0..4 {
            poser.advance().unwrap();
        }
        assert_eq!(poser.advance().unwrap().steps, 0, "{method:?}: the targets are reached");
        for (p, q) in rest.iter().zip(poser.deformer().positions()) {
            assert!(distance([p[0] + d[0], p[1] + d[1]], *q) < 1e-9, "{method:?}: {p:?} went to {q:?}");
        }
    }
}

#[test]
fn a_lone_handle_turned_turns_the_shape_rigidly_about_it_in_steps_of_a_tenth_of_a_radian() {
    let mut poser = Poser::new(Deformer::new(grid_mesh(COLUMNS, ROWS), AkapOptions::default()).unwrap());
    poser.set_handle_vertices(&[vertex(COLUMNS / 2, ROWS / 2)]).unwrap();
    let rest = poser.deformer().positions().to_vec();
    let c = rest[vertex(COLUMNS / 2, ROWS / 2) as usize];
    let angle = 0.45;
    poser.set_turn(0, angle).unwrap();
    let report = poser.advance().unwrap();
    assert_eq!(report.steps, (angle / MAX_TURN_STEP).ceil() as usize);
    assert_eq!(poser.turned().next(), Some(angle));
    let (s, k) = angle.sin_cos();
    for (p, q) in rest.iter().zip(poser.deformer().positions()) {
        let (x, y) = (p[0] - c[0], p[1] - c[1]);
        let turned = [c[0] + k * x - s * y, c[1] + s * x + k * y];
        assert!(distance(turned, *q) < 1e-9, "{p:?} went to {q:?}, not {turned:?}");
    }
}

/// The extreme drag of `tests/foldover.rs`: the bar's left end held (a handle on each vertex
/// of its column) and the right end's middle, handle 5, held by a pointer and pulled back
/// through the bar to `(2, 2)`, beside the held end, turning as it goes; without the guard
/// it folds the bar. Returns how many frames stopped short.
fn fold(method: MethodOptions, poser_of: impl FnOnce(&mut Poser)) -> (Poser, usize) {
    let mut poser = Poser::new(Deformer::new(grid_mesh(COLUMNS, ROWS), method).unwrap());
    let mut handles: Vec<u32> = (0..=ROWS).map(|y| vertex(0, y)).collect();
    handles.push(vertex(COLUMNS, ROWS / 2));
    poser.set_handle_vertices(&handles).unwrap();
    poser_of(&mut poser);
    poser.grab(5).unwrap();
    let mut clamped = 0;
    const FRAMES: usize = 8;
    for frame in 1..=FRAMES {
        let share = frame as f64 / FRAMES as f64;
        poser.set_target(5, [20.0 - 18.0 * share, 2.0]).unwrap();
        if method.method() == akap::deform::Method::Akap {
            poser.set_turn(5, 0.5 * share).unwrap();
        }
        clamped += usize::from(poser.advance().unwrap().clamped);
    }
    (poser, clamped)
}

#[test]
fn every_step_a_frame_takes_is_recorded_and_replays_to_the_same_bits() {
    for method in [MethodOptions::Akap(AkapOptions::default()), MethodOptions::Arap(ArapOptions::default())] {
        let (mut poser, clamped) = fold(method, |poser| poser.start_recording(None));
        assert!(clamped > 0, "{method:?}: the drag should be stopped short at least once");
        let session = poser.stop_recording().unwrap();
        if method.method() == akap::deform::Method::Akap {
            let turns = session.events.iter().filter(|e| matches!(e, Event::Turn { .. })).count();
            assert!(turns > 0, "{method:?}: the turns are recorded");
        }
        let mut replayed = session.recorded_deformer().unwrap();
        replay(&session, &mut replayed).unwrap();
        assert_eq!(bits(replayed.positions()), bits(poser.deformer().positions()), "{method:?}");
        assert_eq!(poser.deformer().metrics().flipped, 0, "{method:?}: the guard keeps every triangle");
    }
}

#[test]
fn a_step_stopped_short_leaves_the_handles_not_held_where_they_stopped() {
    let (poser, clamped) = fold(MethodOptions::Akap(AkapOptions::default()), |_| {});
    assert!(clamped > 0, "the drag should stop short");
    let at = poser.deformer().handle_positions();
    let targets: Vec<Point> = poser.targets().collect();
    assert_eq!(bits(&targets[..5]), bits(&at[..5]), "the pins stay where they stopped");
    assert_eq!(targets[5], [2.0, 2.0], "the held handle keeps its target");
    assert_ne!(bits(&at[5..]), bits(&targets[5..]), "it stopped short of it");
}

#[test]
fn the_papers_mode_moves_a_handle_by_its_targets_motion() {
    let mut poser = bar(ArapOptions::default());
    poser.set_tracking(Tracking { paper: true, ..Tracking::default() }).unwrap();
    poser.grab(1).unwrap();
    let start = poser.deformer().handle_positions()[1];
    // Two pointer moves before the frame: their sum, 0.6 to the right, in 2 substeps.
    poser.set_target(1, [start[0] + 0.5, start[1]]).unwrap();
    poser.set_target(1, [start[0] + 0.6, start[1]]).unwrap();
    assert_eq!(poser.advance().unwrap().steps, 2);
    let at = poser.deformer().handle_positions()[1];
    assert!(distance(at, [start[0] + 0.6, start[1]]) < 1e-12, "{at:?}");
    // Nothing pending: nothing moves.
    assert_eq!(poser.advance().unwrap().steps, 0);
}

#[test]
fn a_step_that_fails_even_smaller_returns_its_error_and_drops_the_turns() {
    // The affine MLS map needs three handles not on one line: every step fails.
    let mut poser = bar(MlsOptions::default().with_variant(MlsVariant::Affine));
    let before = bits(poser.deformer().positions());
    poser.set_target(1, [21.0, 2.0]).unwrap();
    assert!(matches!(poser.advance(), Err(DeformError::TooFewHandles { .. })));
    assert_eq!(bits(poser.deformer().positions()), before);
    // MLS has no turning handles: the turn asked for is dropped.
    let mut poser = bar(MlsOptions::default());
    poser.set_turn(1, 0.2).unwrap();
    assert!(matches!(poser.advance(), Err(DeformError::Unsupported { .. })));
    assert_eq!(poser.turns().collect::<Vec<_>>(), [0.0, 0.0]);
    assert_eq!(poser.advance().unwrap().steps, 0, "nothing is left to turn");
}

/// A poser of the linear rig fixture's mesh with the rig's handles (not yet given the rig).
fn rig_poser() -> (Poser, Operator) {
    let (mesh, operator) = read_operator(include_bytes!("fixtures/defop-v1-linear.defop")).unwrap();
    let points = operator.handles().to_vec();
    let mut deformer = Deformer::new(mesh, AkapOptions::default()).unwrap();
    let (triangles, barycentric): (Vec<u32>, Vec<[f64; 3]>) = points
        .iter()
        .map(|p| match *p {
            akap::mesh::MeshPoint::Vertex(v) => {
                let t = deformer.mesh().triangles().iter().position(|t| t.contains(&v)).unwrap();
                let w = deformer.mesh().triangles()[t].map(|c| if c == v { 1.0 } else { 0.0 });
                (t as u32, w)
            }
            akap::mesh::MeshPoint::Inside { triangle, barycentric } => (triangle, barycentric),
        })
        .unzip();
    deformer.set_handle_points(&triangles, &barycentric).unwrap();
    (Poser::new(deformer), operator)
}

#[test]
fn a_rig_poses_with_the_operators_evaluation_once_per_new_set_of_targets() {
    let (mut poser, mut operator) = rig_poser();
    poser.set_rig(Some(operator.clone())).unwrap();
    poser.start_recording(None);
    let targets: Vec<Point> = poser.targets().enumerate().map(|(i, t)| [t[0] + 0.01 * i as f64, t[1] - 0.02]).collect();
    poser.set_targets(&targets).unwrap();
    let report = poser.advance().unwrap();
    assert_eq!(report.steps, 1);
    let expected = operator.evaluate(targets.as_flattened()).unwrap();
    let posed: Vec<f64> = poser.deformer().positions().as_flattened().to_vec();
    assert_eq!(bits_of(&posed), bits_of(&expected));
    assert_eq!(poser.advance().unwrap().steps, 0, "the same targets: nothing to evaluate");
    let session = poser.stop_recording().unwrap();
    // Recorded as the targets the pose is for (the rig named before; `pose_rig.rs`).
    assert!(matches!(session.events.last(), Some(Event::RigPose(t)) if bits_of(t) == bits_of(targets.as_flattened())));
    // A rig of other counts is refused.
    poser.set_handle_vertices(&[0]).unwrap();
    assert!(!poser.has_rig(), "a new handle set drops the rig");
    assert!(matches!(poser.set_rig(Some(operator)), Err(DeformError::RigMismatch { .. })));
}

#[test]
fn a_rig_on_the_gpu_leaves_the_pose_behind_until_it_is_read_and_records_every_frame_as_on_the_cpu() {
    let (mut poser, mut operator) = rig_poser();
    // Without the foldover guard, which needs the pose on the CPU (`pose_rig.rs`).
    poser.set_tracking(Tracking { no_foldovers: false, ..Tracking::default() }).unwrap();
    let rest = bits(poser.deformer().positions());
    assert!(!poser.set_rig_on_gpu(true).unwrap(), "no rig, nothing on the GPU");
    poser.set_rig(Some(operator.clone())).unwrap();
    assert!(poser.set_rig_on_gpu(true).unwrap());
    let layout = poser.rig_gpu().unwrap().layout();
    assert_eq!(poser.rig_gpu_texture().unwrap().len(), 4 * layout.basis_texels());
    let moved = |poser: &Poser, k: f64| -> Vec<Point> {
        poser.targets().enumerate().map(|(i, t)| [t[0] + 0.01 * k * i as f64, t[1] - 0.02 * k]).collect()
    };
    // A frame computes the GPU's frame only: the positions stay where they were.
    let targets = moved(&poser, 1.0);
    poser.set_targets(&targets).unwrap();
    let before = poser.rig_gpu().unwrap().frame_values().to_vec();
    assert_eq!(poser.advance().unwrap().steps, 1);
    assert_ne!(poser.rig_gpu().unwrap().frame_values(), &before[..], "a new frame");
    assert!(poser.is_stale());
    assert_eq!(bits(poser.deformer().positions()), rest);
    assert_eq!(poser.advance().unwrap().steps, 0, "the same targets: nothing to compute");
    // Read, it is the operator's pose to the bit.
    poser.settle().unwrap();
    assert!(!poser.is_stale());
    let expected = operator.evaluate(targets.as_flattened()).unwrap();
    assert_eq!(bits_of(poser.deformer().positions().as_flattened()), bits_of(&expected));
    // What builds on the pose settles first: a grab takes the handle where the pose has it.
    let targets = moved(&poser, 2.0);
    poser.set_targets(&targets).unwrap();
    poser.advance().unwrap();
    assert!(poser.is_stale());
    let at = poser.grab(1).unwrap();
    let expected = operator.evaluate(targets.as_flattened()).unwrap();
    assert_eq!(bits_of(poser.deformer().positions().as_flattened()), bits_of(&expected));
    assert_eq!(at, poser.deformer().handle_positions()[1]);
    poser.release(1).unwrap();
    // While a recording runs, each frame is recorded as on the CPU (as its targets: the pose
    // stays behind on the GPU without the guard, which evaluates each frame on the CPU):
    // the same session as a poser on the CPU records.
    let record = |on_gpu: bool, no_foldovers: bool| {
        let (mut poser, operator) = rig_poser();
        poser.set_tracking(Tracking { no_foldovers, ..Tracking::default() }).unwrap();
        poser.set_rig(Some(operator)).unwrap();
        poser.set_rig_on_gpu(on_gpu).unwrap();
        poser.start_recording(None);
        for k in 1..4 {
            let targets = moved(&poser, k as f64);
            poser.set_targets(&targets).unwrap();
            poser.advance().unwrap();
            assert_eq!(poser.is_stale(), on_gpu && !no_foldovers);
        }
        poser.stop_recording().unwrap().to_json()
    };
    for guard in [true, false] {
        assert_eq!(record(true, guard), record(false, guard));
    }
    // Back on the CPU, the pose is current again.
    let targets = moved(&poser, 3.0);
    poser.set_targets(&targets).unwrap();
    poser.advance().unwrap();
    assert!(!poser.set_rig_on_gpu(false).unwrap());
    assert!(!poser.is_stale() && poser.rig_gpu().is_none());
    let expected = operator.evaluate(targets.as_flattened()).unwrap();
    assert_eq!(bits_of(poser.deformer().positions().as_flattened()), bits_of(&expected));
}

fn bits_of(values: &[f64]) -> Vec<u64> {
    values.iter().map(|x| x.to_bits()).collect()
}

#[test]
fn bad_targets_turns_and_indices_are_refused_changing_nothing() {
    let mut poser = bar(AkapOptions::default());
    let targets: Vec<Point> = poser.targets().collect();
    assert!(matches!(poser.set_target(2, [0.0, 0.0]), Err(DeformError::HandleOutOfRange { handle: 2, .. })));
    assert!(matches!(poser.set_target(0, [f64::NAN, 0.0]), Err(DeformError::InvalidTarget { handle: 0, .. })));
    assert!(matches!(poser.set_target(1, [0.0, f64::NEG_INFINITY]), Err(DeformError::InvalidTarget { handle: 1, .. })));
    assert!(matches!(poser.set_targets(&[[0.0, 0.0]]), Err(DeformError::Length { .. })));
    assert!(matches!(poser.set_targets(&[[0.0, 0.0], [f64::INFINITY, 0.0]]), Err(DeformError::InvalidTarget { .. })));
    assert!(matches!(poser.set_turn(0, f64::NAN), Err(DeformError::NonFiniteTurn { handle: 0 })));
    assert!(matches!(poser.remove_handle(5), Err(DeformError::HandleOutOfRange { handle: 5, .. })));
    assert!(matches!(
        poser.set_tracking(Tracking { max_step: 0.0, ..Tracking::default() }),
        Err(DeformError::InvalidOption { name: "maxStep", .. })
    ));
    assert_eq!(poser.targets().collect::<Vec<_>>(), targets);
    assert_eq!(poser.turns().collect::<Vec<_>>(), [0.0, 0.0]);
    assert_eq!(poser.advance().unwrap().steps, 0);
}

#[test]
fn adding_and_removing_a_handle_keeps_the_others_targets() {
    let mut poser = bar(AkapOptions::default());
    poser.set_target(1, [22.0, 3.0]).unwrap();
    poser.set_turn(1, 0.25).unwrap();
    let index = poser.add_handle(0, [1.0 / 3.0; 3]).unwrap();
    assert_eq!(index, 2);
    assert_eq!(poser.targets().nth(1), Some([22.0, 3.0]));
    assert_eq!(poser.turns().nth(1), Some(0.25));
    poser.remove_handle(0).unwrap();
    assert_eq!(poser.handle_count(), 2);
    assert_eq!(poser.targets().next(), Some([22.0, 3.0]));
    assert_eq!(poser.turns().next(), Some(0.25));
}

#[test]
fn a_step_by_hand_leaves_the_targets_where_it_took_the_handles() {
    for method in [MethodOptions::Akap(AkapOptions::default()), MethodOptions::Arap(ArapOptions::default())] {
        let mut poser = bar(method);
        poser.step(&[[0.0, 0.0], [0.5, 0.3]], None).unwrap();
        let at = poser.deformer().handle_positions();
        assert_eq!(bits(&poser.targets().collect::<Vec<_>>()), bits(&at), "{method:?}");
        let pose = bits(poser.deformer().positions());
        assert_eq!(poser.advance().unwrap().steps, 0, "{method:?}: nothing takes the handles back");
        assert_eq!(bits(poser.deformer().positions()), pose);
    }
}
