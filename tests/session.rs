//! Sessions: the JSON format round-trips every double exactly, the committed sessions
//! triangulate to their recorded meshes and replay deterministically, their scripted
//! targets are the motions the script describes, both methods follow them, and bad
//! sessions are refused with the event that failed. Runs natively and as wasm.

use std::f64::consts::PI;

use akap::deform::{ArapDeformer, ArapOptions, Deform, DeformError};
use akap::geometry::Point;
use akap::session::{replay, replay_to_targets, Event, MeshCounts, Session, SessionError, ShapeSpec};
use akap::shapes::{self, BAR_SIZE};
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

const SESSIONS: [(&str, &str); 5] = [
    ("bar", include_str!("sessions/bar.json")),
    ("bar-fold", include_str!("sessions/bar-fold.json")),
    ("gingerbread", include_str!("sessions/gingerbread.json")),
    ("gingerbread-fast", include_str!("sessions/gingerbread-fast.json")),
    ("cat", include_str!("sessions/cat.json")),
];

fn session(name: &str) -> Session {
    let (_, text) = SESSIONS.iter().find(|(n, _)| *n == name).expect("a committed session");
    Session::from_json(text).unwrap()
}

fn small_session() -> Session {
    let shape = ShapeSpec { name: "bar".into(), target_edge_length: Some(0.2), max_area: None, min_angle: None };
    let mesh =
        akap::triangulate(&shapes::toothed_bar(), &akap::TriangulationOptions::default().with_target_edge_length(0.2))
            .unwrap();
    let counts = MeshCounts { vertex_count: mesh.vertex_count(), triangle_count: mesh.triangle_count() };
    let mut s = Session::new(shape, counts, Default::default());
    s.events = vec![
        Event::Handles { triangles: vec![0, 5], barycentric: vec![1.0, 0.0, 0.0, 0.2, 0.3, 0.5] },
        Event::Step(vec![0.0, 0.0, 0.01 + 0.02, -1e-310]),
        Event::Step(vec![-0.0, 5e-324, 1e-300, 1.0 / 3.0 * 1e-2]),
        Event::Reset(true),
        Event::Step(vec![0.0, 0.0, 0.01, 0.02]),
    ];
    s
}

#[test]
fn json_round_trips_every_double_exactly() {
    let mut s = small_session();
    // Extremes, for the format only (this step is not replayed).
    s.events.push(Event::Step(vec![f64::MAX, f64::MIN_POSITIVE, -5e-324, 0.1 + 0.2, 1.0 / 3.0, -1e300]));
    let text = s.to_json();
    let back = Session::from_json(&text).unwrap();
    assert_eq!(back, s);
    let bits = |s: &Session| -> Vec<u64> {
        s.events
            .iter()
            .flat_map(|e| match e {
                Event::Step(v) | Event::Handles { barycentric: v, .. } => v.clone(),
                Event::Reset(_) => Vec::new(),
            })
            .map(f64::to_bits)
            .collect()
    };
    // Bit for bit, -0.0 and the subnormals included.
    assert_eq!(bits(&back), bits(&s));
    assert_eq!(back.to_json(), text);
    // The documented layout: the fields of the format, one event per line.
    for key in ["\"format\": \"akap-session\"", "\"version\": 1", "\"targetEdgeLength\":0.2", "\"vertexCount\""] {
        assert!(text.contains(key), "{key} in {text}");
    }
    assert!(text.contains("\n    {\"reset\":true},\n"));
    assert!(text.contains("{\"handles\":{\"triangles\":[0,5],\"barycentric\":[1.0,0.0,0.0,0.2,0.3,0.5]}}"));
}

#[test]
fn replay_is_deterministic_and_survives_the_json() {
    let s = small_session();
    let mut first = s.recorded_deformer().unwrap();
    let mut second = s.recorded_deformer().unwrap();
    let a = replay(&s, &mut first).unwrap();
    let b = replay(&Session::from_json(&s.to_json()).unwrap(), &mut second).unwrap();
    assert_eq!(first.positions(), second.positions());
    assert_eq!(a.targets, b.targets);
    assert_eq!(a.targets.len(), 3);
    // After the reset, the step's targets are the rest handle positions plus the velocities.
    let mesh = s.mesh().unwrap();
    let t = mesh.triangles()[5].map(|v| mesh.positions()[v as usize]);
    let rest = [0.2 * t[0][0] + 0.3 * t[1][0] + 0.5 * t[2][0], 0.2 * t[0][1] + 0.3 * t[1][1] + 0.5 * t[2][1]];
    assert!((a.targets[2][1][0] - rest[0] - 0.01).abs() < 1e-15 && (a.targets[2][1][1] - rest[1] - 0.02).abs() < 1e-15);
    assert!(a.handle_error.unwrap() < 1e-2);
}

/// The bar's scripted targets: left end pinned, right end where the centre line bent into
/// a circular arc of angle `phi` and unchanged length puts it.
fn bar_targets(rest: &[Point], phi: f64) -> Vec<Point> {
    let [length, height] = BAR_SIZE;
    let radius = length / phi;
    let end = [radius * phi.sin(), height / 2.0 + radius * (1.0 - phi.cos())];
    let (s, c) = phi.sin_cos();
    rest.iter()
        .map(|p| {
            if p[0] < length / 2.0 {
                *p
            } else {
                [end[0] - s * (p[1] - height / 2.0), end[1] + c * (p[1] - height / 2.0)]
            }
        })
        .collect()
}

#[test]
fn committed_sessions_match_their_meshes_and_scripts() {
    for (name, text) in SESSIONS {
        let s = Session::from_json(text).unwrap_or_else(|e| panic!("{name}: {e}"));
        let mesh = s.mesh().unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(mesh.vertex_count(), s.mesh.vertex_count);
        assert!(s.step_count() >= 6, "{name}");
        // Every handle event is valid for this mesh.
        let mut deformer = s.recorded_deformer().unwrap();
        for event in &s.events {
            if let Event::Handles { triangles, barycentric } = event {
                let (w, _) = barycentric.as_chunks::<3>();
                deformer.set_handle_points(triangles, w).unwrap_or_else(|e| panic!("{name}: {e}"));
            }
        }
    }
    // The bar's recorded targets follow the bend, frame by frame, to rounding.
    let s = session("bar");
    let mut deformer = s.recorded_deformer().unwrap();
    let recording = replay(&s, &mut deformer).unwrap();
    let Event::Handles { triangles, barycentric } = &s.events[0] else { panic!("handles first") };
    let mesh = s.mesh().unwrap();
    let rest: Vec<Point> = triangles
        .iter()
        .zip(barycentric.as_chunks::<3>().0)
        .map(|(&t, w)| {
            let p = mesh.triangles()[t as usize].map(|v| mesh.positions()[v as usize]);
            [(0..3).map(|k| w[k] * p[k][0]).sum(), (0..3).map(|k| w[k] * p[k][1]).sum()]
        })
        .collect();
    let [length, height] = BAR_SIZE;
    assert_eq!(rest.iter().filter(|p| p[0] == 0.0).count(), 3);
    assert_eq!(rest.iter().filter(|p| p[0] == length && (0.0..=height).contains(&p[1])).count(), 3);
    let frames = recording.targets.len();
    for (k, targets) in recording.targets.iter().enumerate() {
        let expected = bar_targets(&rest, PI / 2.0 * (k + 1) as f64 / frames as f64);
        for (t, e) in targets.iter().zip(&expected) {
            assert!((t[0] - e[0]).hypot(t[1] - e[1]) < 1e-12, "frame {k}: {t:?} vs {e:?}");
        }
    }
    // AKAP (soft constraints) ends near its targets and near-isometric.
    assert!(recording.handle_error.unwrap() < 1e-3);
    let m = deformer.metrics();
    assert!(m.flipped == 0 && m.area_distortion < 2.02 && m.angle_distortion < 2.02, "{m:?}");
}

#[test]
fn arap_follows_the_recorded_targets() {
    let s = session("bar");
    let mut recorded = s.recorded_deformer().unwrap();
    let recording = replay(&s, &mut recorded).unwrap();
    let mut arap = ArapDeformer::new(s.mesh().unwrap(), ArapOptions::default().with_iterations(10)).unwrap();
    let result = replay_to_targets(&s, &recording.targets, &mut arap).unwrap();
    // The handles are at vertices, so hard constraints: exactly on target.
    assert_eq!(result.handle_error, Some(0.0));
    assert_eq!(result.targets, recording.targets);
    // Bending a bar of width w into radius R strains its sides by about +-w / 2R, so
    // E_area ~ 2 + (w / 2R)^2 / 3 on average over the width (a thin-beam estimate).
    let [length, height] = BAR_SIZE;
    let strain = height / 2.0 / (length / (PI / 2.0));
    let estimate = 2.0 + strain * strain / 3.0;
    let m = Deform::metrics(&arap);
    assert_eq!(m.flipped, 0);
    assert!((m.area_distortion - estimate).abs() < 0.3 * (estimate - 2.0), "{m:?} vs {estimate}");
}

#[test]
fn bad_sessions_are_refused() {
    let good = small_session();
    let text = good.to_json();
    let edit = |from: &str, to: &str| Session::from_json(&text.replacen(from, to, 1));
    assert!(matches!(Session::from_json("{"), Err(SessionError::Json(_))));
    assert!(matches!(edit("akap-session", "other"), Err(SessionError::Format { .. })));
    assert!(matches!(edit("\"version\": 1", "\"version\": 2"), Err(SessionError::Version { found: 2 })));
    assert!(matches!(edit("\"targetEdgeLength\"", "\"targetEdgeLen\""), Err(SessionError::Json(_))));
    assert!(matches!(edit("{\"reset\":true}", "{\"jump\":true}"), Err(SessionError::Json(_))));
    assert!(matches!(edit("\"lambda\":100.0", "\"lambda\":\"big\""), Err(SessionError::Json(_))));

    let mut s = good.clone();
    s.shape.name = "dragon".into();
    assert!(matches!(s.mesh(), Err(SessionError::UnknownShape { .. })));
    let mut s = good.clone();
    s.mesh.vertex_count += 1;
    assert!(matches!(s.mesh(), Err(SessionError::MeshMismatch { .. })));
    let mut s = good.clone();
    s.options.lambda = -1.0;
    assert!(matches!(s.recorded_deformer(), Err(SessionError::Options(DeformError::InvalidOption { .. }))));

    let replay_with = |events: Vec<Event>| {
        let mut s = good.clone();
        s.events = events;
        let mut deformer = s.recorded_deformer().unwrap();
        replay(&s, &mut deformer).map(|_| deformer.positions().to_vec())
    };
    let handles = Event::Handles { triangles: vec![0], barycentric: vec![1.0, 0.0, 0.0] };
    assert!(matches!(
        replay_with(vec![Event::Handles { triangles: vec![100_000], barycentric: vec![1.0, 0.0, 0.0] }]),
        Err(SessionError::Event { index: 0, error: DeformError::TriangleOutOfRange { .. } })
    ));
    assert!(matches!(
        replay_with(vec![Event::Handles { triangles: vec![0], barycentric: vec![1.0, 0.0] }]),
        Err(SessionError::Event { index: 0, error: DeformError::Length { .. } })
    ));
    assert!(matches!(
        replay_with(vec![handles.clone(), Event::Step(vec![0.1])]),
        Err(SessionError::Event { index: 1, error: DeformError::Length { .. } })
    ));
    assert!(matches!(
        replay_with(vec![handles.clone(), Event::Step(vec![0.1, 0.2, 0.3, 0.4])]),
        Err(SessionError::Event { index: 1, error: DeformError::Length { .. } })
    ));
    // Targets that do not cover the steps.
    let mut deformer = good.recorded_deformer().unwrap();
    assert!(matches!(replay_to_targets(&good, &[], &mut deformer), Err(SessionError::MissingTargets { index: 1 })));
    // A session with only a reset changes nothing.
    let positions = replay_with(vec![Event::Reset(true), Event::Reset(false)]).unwrap();
    assert_eq!(positions, good.mesh().unwrap().positions());
}
