//! Posing with a trained rig (`pose::Poser::set_rig`): with no foldovers (the default) a drag
//! whose plain evaluation turns triangles over is pulled back along the drag to the largest
//! flip-free fraction, reported clamped, the handles not held left where the pose is for;
//! without the guard the rig folds; a triangle the rig's own rest pose has turned over does
//! not block. Sessions name the rig by its file's checksum and record each frame as the
//! targets the pose is for, replaying to the same bits with the rig given and refusing,
//! saying which rig, without it. Runs natively and as wasm.
//!
//! The rig is `tests/fixtures/defop-v1-linear.defop` (see `defop_file.rs`): on the 2 × 2
//! grid with handles at (0, 0) and (2, 2) it is the affine map
//! g(x) = x + (1 − w) d_0 + w d_1, w = (x + y) / 4, d_i the handles' moves, whose Jacobian
//! I + (d_1 − d_0) [1 1] / 4 has determinant 1 + (Δx + Δy) / 4 with Δ = d_1 − d_0: every
//! triangle turns over together once Δx + Δy < −4. Moving the second handle to
//! (2, 2) + s (−1, −1) gives 1 − s/2: the fold is at s = 2.

use akap::defop::file::{read_operator, write_operator};
use akap::defop::Operator;
use akap::deform::{AkapOptions, DeformError, Deformer};
use akap::geometry::Point;
use akap::mesh::{Mesh, MeshPoint};
use akap::pose::{replay, replay_with_rigs, session_rig, Poser, Tracking};
use akap::session::{Event, Session, SessionError};
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

const FIXTURE: &[u8] = include_bytes!("fixtures/defop-v1-linear.defop");

fn rig() -> (Mesh, Operator) {
    let (mesh, operator) = read_operator(FIXTURE).unwrap();
    assert_eq!(operator.handles(), [MeshPoint::Vertex(0), MeshPoint::Vertex(8)]);
    (mesh, operator)
}

/// A poser of the rig's mesh with handles on its two vertices, posing with `operator`.
fn poser(mesh: &Mesh, operator: &Operator) -> Poser {
    let mut poser = Poser::new(Deformer::new(mesh.clone(), AkapOptions::default()).unwrap());
    poser.set_handle_vertices(&[0, 8]).unwrap();
    poser.set_rig(Some(operator.clone())).unwrap();
    poser
}

/// Twice each triangle's signed area, from plain products (no code under test).
fn areas(positions: &[Point], mesh: &Mesh) -> Vec<f64> {
    mesh.triangles()
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| positions[v as usize]);
            (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        })
        .collect()
}

fn bits(values: &[f64]) -> Vec<u64> {
    values.iter().map(|x| x.to_bits()).collect()
}

fn pose_bits(poser: &Poser) -> Vec<u64> {
    bits(poser.deformer().positions().as_flattened())
}

fn evaluate(operator: &Operator, targets: &[f64]) -> Vec<u64> {
    bits(&operator.clone().evaluate(targets).unwrap())
}

/// FNV-1a 64 (the operator file's checksum), written out here.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3))
}

#[test]
fn a_rig_dragged_past_a_fold_is_pulled_back_along_the_drag_and_folds_without_the_guard() {
    let (mesh, operator) = rig();
    let far = [-1.0, -1.0]; // s = 3: determinant 1 - 3/2 = -1/2, every triangle turned over

    // Without the guard: the plain evaluation, every triangle turned over.
    let mut plain = poser(&mesh, &operator);
    plain.set_tracking(Tracking { no_foldovers: false, ..Tracking::default() }).unwrap();
    plain.set_target(1, far).unwrap();
    let report = plain.advance().unwrap();
    assert_eq!((report.steps, report.clamped), (1, false));
    assert_eq!(pose_bits(&plain), evaluate(&operator, &[0.0, 0.0, -1.0, -1.0]));
    assert!(areas(plain.deformer().positions(), &mesh).iter().all(|&a| a < 0.0));

    // With it (the default): stopped short on the drag, at the largest fraction the
    // bisection finds (12 trials: within 2^-12 of the fold at t = 2/3 of the way).
    let mut guarded = poser(&mesh, &operator);
    assert!(guarded.tracking().no_foldovers);
    guarded.set_target(1, far).unwrap();
    let report = guarded.advance().unwrap();
    assert_eq!((report.steps, report.clamped), (1, true));
    let areas = areas(guarded.deformer().positions(), &mesh);
    assert!(areas.iter().all(|&a| a > 0.0), "{areas:?}");
    // Not held: the handle stays where the pose is for, on the drag (2, 2) + t (-3, -3).
    let at = guarded.targets().nth(1).unwrap();
    let posed = guarded.rig_targets().unwrap().to_vec();
    assert_eq!(bits(&posed), bits(&[0.0, 0.0, at[0], at[1]]));
    assert_eq!(at[0], at[1]);
    let t = (2.0 - at[0]) / 3.0;
    assert!(t < 2.0 / 3.0 && t > 2.0 / 3.0 - 2f64.powi(-12), "t = {t}");
    assert_eq!(pose_bits(&guarded), evaluate(&operator, &posed));
    // Nothing further to do: the targets are where the pose is for.
    assert_eq!(guarded.advance().unwrap().steps, 0);

    // Held by a pointer, the handle keeps its target; the pose stops short the same way.
    let mut held = poser(&mesh, &operator);
    held.grab(1).unwrap();
    held.set_target(1, far).unwrap();
    assert!(held.advance().unwrap().clamped);
    assert_eq!(held.targets().nth(1).unwrap(), far);
    assert_eq!(pose_bits(&held), pose_bits(&guarded));
    assert_eq!(held.advance().unwrap().steps, 0, "the same targets again: nothing to do");
    // Back over the fold: the whole way, not clamped.
    held.set_target(1, [1.5, 1.5]).unwrap();
    let report = held.advance().unwrap();
    assert_eq!((report.steps, report.clamped), (1, false));
    assert_eq!(pose_bits(&held), evaluate(&operator, &[0.0, 0.0, 1.5, 1.5]));

    // Turning the guard off lets the held drag fold at the next frame.
    held.set_target(1, far).unwrap();
    assert!(held.advance().unwrap().clamped);
    held.set_tracking(Tracking { no_foldovers: false, ..Tracking::default() }).unwrap();
    assert!(!held.advance().unwrap().clamped);
    assert_eq!(pose_bits(&held), evaluate(&operator, &[0.0, 0.0, -1.0, -1.0]));
}

/// The fixture with vertex 4's rest place, (1, 1), moved to (3, 1) in the operator (its
/// constant coefficient): the rig's rest pose turns over the triangles that vertex leaves
/// behind, while the mesh is the grid.
fn rig_with_a_fold_at_rest() -> (Mesh, Operator) {
    let (mesh, operator) = rig();
    let mut bytes = write_operator(&mesh, &operator).unwrap();
    let end = bytes.len() - 8;
    let start = end - operator.stored_bytes();
    let psi = operator.stored_bytes() / 8 / (2 * operator.spatial_len());
    let at = start + 8 * (2 * 4 * psi); // X^x of spatial function 4, its constant term
    let constant = f64::from_le_bytes(bytes[at..at + 8].try_into().unwrap());
    assert_eq!(operator.coefficient(0, 4, 0), Some(constant));
    assert!((constant - 1.0).abs() < 1e-12, "{constant}");
    bytes[at..at + 8].copy_from_slice(&(constant + 2.0).to_le_bytes());
    let checksum = fnv1a(&bytes[..end]);
    bytes[end..].copy_from_slice(&checksum.to_le_bytes());
    let (read_mesh, folded) = read_operator(&bytes).unwrap();
    assert_eq!(read_mesh, mesh);
    (mesh, folded)
}

#[test]
fn a_triangle_the_rigs_rest_pose_has_turned_over_does_not_block() {
    let (mesh, operator) = rig_with_a_fold_at_rest();
    let rest = evaluate(&operator, &[0.0, 0.0, 2.0, 2.0]);
    let rest: Vec<Point> = rest.chunks(2).map(|p| [f64::from_bits(p[0]), f64::from_bits(p[1])]).collect();
    let at_rest = areas(&rest, &mesh);
    assert!(at_rest.iter().any(|&a| a < 0.0) && at_rest.iter().any(|&a| a > 0.0), "{at_rest:?}");

    let mut poser = poser(&mesh, &operator);
    for targets in [[0.0, 0.0, 2.0, 2.0], [0.0, 0.0, 2.1, 1.9], [0.1, -0.2, 1.7, 2.3], [0.0, 0.0, 2.0, 2.0]] {
        poser.set_targets(&[[targets[0], targets[1]], [targets[2], targets[3]]]).unwrap();
        let report = poser.advance().unwrap();
        assert_eq!((report.steps, report.clamped), (1, false), "{targets:?}");
        assert_eq!(pose_bits(&poser), evaluate(&operator, &targets));
    }
    // Past the fold of the affine part: stopped short, the triangles positive at rest kept
    // positive, the others as the rig has them.
    poser.set_target(1, [-1.0, -1.0]).unwrap();
    assert!(poser.advance().unwrap().clamped);
    let now = areas(poser.deformer().positions(), &mesh);
    for (rest, now) in at_rest.iter().zip(&now) {
        assert!(*rest < 0.0 || *now > 0.0, "{at_rest:?} {now:?}");
    }
}

/// A drag of the second handle through `points`, a frame each, held, then let go.
fn drag(poser: &mut Poser, points: &[Point]) {
    poser.grab(1).unwrap();
    for &p in points {
        poser.set_target(1, p).unwrap();
        poser.advance().unwrap();
    }
    poser.release(1).unwrap();
}

#[test]
fn a_session_of_rig_posing_names_the_rig_and_replays_with_it_to_the_same_bits() {
    let (mesh, operator) = rig();
    let mut poser = poser(&mesh, &operator);
    poser.start_recording(None);
    // Past the fold on the third frame (stopped short), then back, then the other handle.
    drag(&mut poser, &[[2.1, 1.8], [1.0, 0.5], [-1.0, -1.0]]);
    let clamped_pose = pose_bits(&poser);
    drag(&mut poser, &[[0.5, 1.0], [2.5, 2.4]]);
    poser.set_target(0, [0.2, -0.1]).unwrap();
    assert!(!poser.advance().unwrap().clamped);
    let last = pose_bits(&poser);
    let session = poser.stop_recording().unwrap();

    // The rig named by its file's checksum, its frames by the targets.
    let named = session_rig(&mesh, &operator).unwrap();
    let file = write_operator(&mesh, &operator).unwrap();
    assert_eq!(named.checksum, fnv1a(&file[..file.len() - 8]));
    assert_eq!(session.events[..3], [Event::Reset(true), session.events[1].clone(), Event::Rig(Some(named))]);
    let frames: Vec<&Vec<f64>> =
        session.events.iter().filter_map(|e| if let Event::RigPose(t) = e { Some(t) } else { None }).collect();
    assert_eq!(frames.len(), 6, "every frame that posed, the clamped one too");
    assert!(!session.events.iter().any(|e| matches!(e, Event::Positions(_))));
    let text = session.to_json();
    assert!(text.contains(&format!("{{\"rig\":{{\"checksum\":\"{:016x}\"}}}}", named.checksum)), "{text}");
    assert!(text.contains("\"version\": 3"));

    // Replayed with the rig: every frame, the last pose to the bit.
    let read = Session::from_json(&text).unwrap();
    let mut deformer = read.recorded_deformer().unwrap();
    replay_with_rigs(&read, &mut deformer, std::slice::from_ref(&operator)).unwrap();
    assert_eq!(bits(deformer.positions().as_flattened()), last);
    // Up to the clamped frames: the pose the guard left.
    let mut upto = read.clone();
    upto.events.truncate(3 + 3);
    let mut deformer = read.recorded_deformer().unwrap();
    replay_with_rigs(&upto, &mut deformer, std::slice::from_ref(&operator)).unwrap();
    assert_eq!(bits(deformer.positions().as_flattened()), clamped_pose);

    // Without the rig, or with another: refused, saying which rig the session needs.
    let (_, other) = rig_with_a_fold_at_rest();
    for rigs in [vec![], vec![other]] {
        let mut deformer = read.recorded_deformer().unwrap();
        let error = replay_with_rigs(&read, &mut deformer, &rigs).unwrap_err();
        assert_eq!(error, SessionError::MissingRig { index: 2, rig: named });
        let message = error.to_string();
        assert!(message.contains(&format!("{:016x}", named.checksum)) && message.contains(".defop"), "{message}");
    }
    let mut deformer = read.recorded_deformer().unwrap();
    assert!(matches!(replay(&read, &mut deformer), Err(SessionError::MissingRig { .. })));

    // Dropping the rig is recorded; the poser steps again after it.
    let mut poser = self::poser(&mesh, &operator);
    poser.start_recording(None);
    poser.set_rig(None).unwrap();
    let events = poser.stop_recording().unwrap().events;
    assert_eq!(events.last(), Some(&Event::Rig(None)));
}

#[test]
fn rig_events_are_checked_on_reading() {
    let (mesh, operator) = rig();
    let mut poser = poser(&mesh, &operator);
    poser.start_recording(None);
    drag(&mut poser, &[[2.1, 1.8], [1.0, 0.5]]);
    let text = poser.stop_recording().unwrap().to_json();
    let named = format!("{:016x}", session_rig(&mesh, &operator).unwrap().checksum);

    // A rig pose without a rig, or of another handle count.
    let without = text.replace(&format!("{{\"rig\":{{\"checksum\":\"{named}\"}}}}"), "{\"reset\":false}");
    assert_ne!(without, text);
    assert!(matches!(Session::from_json(&without), Err(SessionError::Event { index: 3, error: DeformError::NoRig })));
    let short = text.replacen("{\"rigPose\":[0.0,0.0,", "{\"rigPose\":[", 1);
    assert_ne!(short, text);
    assert!(matches!(
        Session::from_json(&short),
        Err(SessionError::Event { error: DeformError::Length { what: "targets", .. }, .. })
    ));
    // A checksum that is not 16 hexadecimal digits.
    for bad in ["12", "+123456789abcdef", "0123456789abcdeg"] {
        let broken = text.replace(&named, bad);
        assert!(matches!(Session::from_json(&broken), Err(SessionError::Json(m)) if m.contains("16 hexadecimal")));
    }
    // Version 2 had no rig events; its other sessions still read, written back as 3.
    let old = text.replace("\"version\": 3", "\"version\": 2");
    assert!(matches!(Session::from_json(&old), Err(SessionError::NotInVersion { version: 2, what: "a rig event" })));
    let mut plain = Poser::new(Deformer::new(mesh, AkapOptions::default()).unwrap());
    plain.start_recording(None);
    plain.set_handle_vertices(&[0, 8]).unwrap();
    let two = plain.stop_recording().unwrap().to_json().replace("\"version\": 3", "\"version\": 2");
    assert_eq!(Session::from_json(&two).unwrap().version, 3);
}
