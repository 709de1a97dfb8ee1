//! Sessions: the JSON format round-trips every double exactly, the committed sessions
//! triangulate to their recorded meshes and replay deterministically, their scripted
//! targets are the motions the script describes, both methods follow them, and bad
//! sessions are refused with the event that failed. Runs natively and as wasm.

use std::f64::consts::PI;

use akap::deform::{AkapOptions, ArapOptions, DeformError, Deformer, Integrator, Method, MethodOptions, SettingValue};
use akap::geometry::Point;
use akap::pose::{replay, replay_to_targets};
use akap::session::{Event, MeshCounts, RecordedOptions, Session, SessionError, ShapeSpec};
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
    // Extremes, for the format only (these handles are not replayed).
    let extremes = vec![f64::MAX, f64::MIN_POSITIVE, -5e-324, 0.1 + 0.2, 1.0 / 3.0, -1e300];
    s.events.push(Event::Handles { triangles: vec![1, 2], barycentric: extremes });
    let text = s.to_json();
    let back = Session::from_json(&text).unwrap();
    assert_eq!(back, s);
    let bits = |s: &Session| -> Vec<u64> {
        s.events
            .iter()
            .flat_map(|e| match e {
                Event::Step(v)
                | Event::Positions(v)
                | Event::Handles { barycentric: v, .. }
                | Event::Bones { barycentric: v, .. }
                | Event::RigPose(v) => v.clone(),
                Event::Stiffness(v) => v.clone().unwrap_or_default(),
                Event::Turn { velocities, turns } => [&velocities[..], &turns[..]].concat(),
                Event::Joints(joints) => joints.iter().flat_map(|j| j.point).collect(),
                Event::Reset(_) | Event::Options(_) | Event::Rig(_) => Vec::new(),
            })
            .map(f64::to_bits)
            .collect()
    };
    // Bit for bit, -0.0 and the subnormals included.
    assert_eq!(bits(&back), bits(&s));
    assert_eq!(back.to_json(), text);
    // The documented layout: the fields of the format, one event per line.
    for key in ["\"format\": \"akap-session\"", "\"version\": 3", "\"targetEdgeLength\":0.2", "\"vertexCount\""] {
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
        // Version 1 files, read as version 3 and written back so, with nothing lost.
        assert!(text.contains("\"version\": 1,"), "{name} is a version-1 file");
        let s = Session::from_json(text).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(s.version, 3);
        let again = s.to_json();
        assert!(again.contains("\"version\": 3,"));
        assert_eq!(Session::from_json(&again).unwrap(), s);
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
    let mut arap = Deformer::new(s.mesh().unwrap(), ArapOptions::default().with_iterations(10)).unwrap();
    let result = replay_to_targets(&s, &recording.targets, &mut arap).unwrap();
    // The handles are at vertices, so hard constraints: exactly on target.
    assert_eq!(result.handle_error, Some(0.0));
    assert_eq!(result.targets, recording.targets);
    // Bending a bar of width w into radius R strains its sides by about +-w / 2R, so
    // E_area ~ 2 + (w / 2R)^2 / 3 on average over the width (a thin-beam estimate).
    let [length, height] = BAR_SIZE;
    let strain = height / 2.0 / (length / (PI / 2.0));
    let estimate = 2.0 + strain * strain / 3.0;
    let m = arap.metrics();
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
    assert!(matches!(edit("\"version\": 3", "\"version\": 4"), Err(SessionError::Version { found: 4 })));
    assert!(matches!(edit("\"version\": 3", "\"version\": 0"), Err(SessionError::Version { found: 0 })));
    assert!(matches!(edit("\"targetEdgeLength\"", "\"targetEdgeLen\""), Err(SessionError::Json(_))));
    assert!(matches!(edit("{\"reset\":true}", "{\"jump\":true}"), Err(SessionError::Json(_))));
    assert!(matches!(
        edit("\"lambda\":100.0", "\"lambda\":\"big\""),
        Err(SessionError::Options(DeformError::OptionValue { name: "lambda", .. }))
    ));
    assert!(matches!(edit("\"lambda\":100.0", "\"lambda\":[1]"), Err(SessionError::Json(_))));
    assert!(matches!(edit("\"method\":\"akap\"", "\"method\":\"bogus\""), Err(SessionError::Json(_))));
    assert!(matches!(edit("\"lambda\":100.0", "\"lambda\":-1.0"), Err(SessionError::Options(_))));

    let mut s = good.clone();
    s.shape.as_mut().unwrap().name = "dragon".into();
    assert!(matches!(s.mesh(), Err(SessionError::UnknownShape { .. })));
    let mut s = good.clone();
    s.mesh.vertex_count += 1;
    assert!(matches!(s.mesh(), Err(SessionError::MeshMismatch { .. })));
    let mut s = good.clone();
    s.options.values = vec![("lambda".into(), SettingValue::Number(-1.0))];
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

#[test]
fn version_1_files_are_read_but_not_with_what_only_version_2_has() {
    let (_, bar) = SESSIONS[0];
    let v1 = Session::from_json(bar).unwrap();
    assert_eq!(v1.options.method, None, "version 1 names no method");
    assert_eq!(v1.method_options().unwrap(), MethodOptions::Akap(AkapOptions::default()));
    let with = |from: &str, to: &str| {
        assert!(bar.contains(from));
        Session::from_json(&bar.replacen(from, to, 1))
    };
    let positions = format!("{{\"positions\":{:?}}},\n    {{\"step\"", vec![0.0; 2 * v1.mesh.vertex_count]);
    assert!(matches!(with("{\"step\"", &positions), Err(SessionError::NotInVersion { version: 1, .. })));
    assert!(matches!(
        with("\"options\": {", "\"options\": {\"method\":\"akap\","),
        Err(SessionError::NotInVersion { version: 1, .. })
    ));
    assert!(matches!(
        with("{\"step\"", "{\"options\":{\"lambda\":5.0}},\n    {\"step\""),
        Err(SessionError::NotInVersion { version: 1, .. })
    ));
    // The same edits are version 2.
    let v2 = bar.replacen("\"version\": 1,", "\"version\": 2,", 1);
    let positions = v2.replacen("{\"step\"", &positions, 1);
    assert_eq!(Session::from_json(&positions).unwrap().events.len(), v1.events.len() + 1);
}

/// The small bar's mesh, and a pose of it: sheared by 0.1, computed here.
fn bar_and_shear() -> (akap::Mesh, Vec<f64>) {
    let mesh = small_session().mesh().unwrap();
    let pose = mesh.positions().iter().flat_map(|p| [p[0] + 0.1 * p[1], p[1]]).collect();
    (mesh, pose)
}

#[test]
fn positions_and_options_events_replay_as_the_calls_they_record() {
    let (mesh, pose) = bar_and_shear();
    let handles = (vec![0u32, 5], vec![[1.0, 0.0, 0.0], [0.2, 0.3, 0.5]]);
    let v = |k: f64| vec![0.0, 0.0, 0.01 * k, 0.02];
    let setting = |name: &str, value| (name.to_owned(), value);
    let recorded = |method, values| RecordedOptions { method, values };
    let mut s = small_session();
    s.events = vec![
        Event::Handles { triangles: handles.0.clone(), barycentric: handles.1.concat() },
        Event::Step(v(1.0)),
        Event::Options(recorded(None, vec![setting("lambda", SettingValue::Number(10.0))])),
        Event::Step(v(2.0)),
        Event::Positions(pose.clone()),
        Event::Step(v(3.0)),
        Event::Options(recorded(Some(Method::Arap), vec![setting("iterations", SettingValue::Number(3.0))])),
        Event::Step(v(4.0)),
        Event::Options(recorded(Some(Method::Akap), vec![setting("integrator", SettingValue::Word("linear".into()))])),
        Event::Step(v(5.0)),
    ];
    let s = Session::from_json(&s.to_json()).unwrap();
    let mut replayed = s.recorded_deformer().unwrap();
    replay(&s, &mut replayed).unwrap();

    // The same calls made by hand.
    let pairs = |flat: &[f64]| flat.as_chunks::<2>().0.to_vec();
    let mut d = Deformer::new(mesh.clone(), AkapOptions::default()).unwrap();
    d.set_handle_points(&handles.0, &handles.1).unwrap();
    d.step(&pairs(&v(1.0))).unwrap();
    d.set_options(AkapOptions::default().with_lambda(10.0)).unwrap();
    d.step(&pairs(&v(2.0))).unwrap();
    d.set_positions(&pairs(&pose)).unwrap();
    // A positions event puts the mesh exactly into the pose.
    assert!(d.positions().iter().flatten().zip(&pose).all(|(a, b)| a.to_bits() == b.to_bits()));
    d.step(&pairs(&v(3.0))).unwrap();
    let mut a = Deformer::new(mesh.clone(), ArapOptions::default().with_iterations(3)).unwrap();
    a.set_positions(d.positions()).unwrap();
    a.set_handle_points(&handles.0, &handles.1).unwrap();
    a.step(&pairs(&v(4.0))).unwrap();
    // Another method starts from its defaults: lambda is 100 again.
    let linear = AkapOptions::default().with_integrator(Integrator::Linear);
    let mut d = Deformer::new(mesh, linear).unwrap();
    d.set_positions(a.positions()).unwrap();
    d.set_handle_points(&handles.0, &handles.1).unwrap();
    d.step(&pairs(&v(5.0))).unwrap();

    assert_eq!(replayed.options(), MethodOptions::Akap(linear));
    let bits = |p: &[Point]| p.iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(replayed.positions()), bits(d.positions()));
    // A compared method passes over options events and keeps its own.
    let mut arap = Deformer::new(s.mesh().unwrap(), ArapOptions::default().with_iterations(7)).unwrap();
    let mut recorded = s.recorded_deformer().unwrap();
    let targets = replay(&s, &mut recorded).unwrap().targets;
    replay_to_targets(&s, &targets, &mut arap).unwrap();
    assert_eq!(arap.arap().unwrap().options().iterations, 7);
}

#[test]
fn stiffness_events_replay_as_the_calls_they_record() {
    let (mesh, _) = bar_and_shear();
    let triangles = mesh.triangle_count();
    // The left half of the triangles 50x stiffer, one 0.001: values of the whole range.
    let painted: Vec<f64> = (0..triangles)
        .map(|t| {
            if t == 3 {
                0.001
            } else if t < triangles / 2 {
                50.0
            } else {
                1.0
            }
        })
        .collect();
    let handles = (vec![0u32, 5], vec![[1.0, 0.0, 0.0], [0.2, 0.3, 0.5]]);
    let v = |k: f64| vec![0.0, 0.0, 0.02 * k, 0.03];
    let mut s = small_session();
    s.events = vec![
        Event::Handles { triangles: handles.0.clone(), barycentric: handles.1.concat() },
        Event::Stiffness(Some(painted.clone())),
        Event::Step(v(1.0)),
        Event::Stiffness(None),
        Event::Step(v(2.0)),
        Event::Stiffness(Some(painted.clone())),
        Event::Step(v(3.0)),
    ];
    let text = s.to_json();
    assert!(text.contains("{\"stiffness\":null}") && text.contains("{\"stiffness\":[50.0,"), "{text}");
    let s = Session::from_json(&text).unwrap();
    let mut replayed = s.recorded_deformer().unwrap();
    replay(&s, &mut replayed).unwrap();

    let pairs = |flat: &[f64]| flat.as_chunks::<2>().0.to_vec();
    let mut d = Deformer::new(mesh.clone(), AkapOptions::default()).unwrap();
    d.set_handle_points(&handles.0, &handles.1).unwrap();
    d.set_stiffness(Some(&painted)).unwrap();
    d.step(&pairs(&v(1.0))).unwrap();
    d.set_stiffness(None).unwrap();
    d.step(&pairs(&v(2.0))).unwrap();
    d.set_stiffness(Some(&painted)).unwrap();
    d.step(&pairs(&v(3.0))).unwrap();
    let bits = |p: &[Point]| p.iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(replayed.positions()), bits(d.positions()));
    assert_eq!(replayed.stiffness(), Some(&painted[..]));
    // The painting matters: without it the pose differs.
    let mut plain = small_session();
    plain.events = s.events.iter().filter(|e| !matches!(e, Event::Stiffness(_))).cloned().collect();
    let mut unpainted = plain.recorded_deformer().unwrap();
    replay(&plain, &mut unpainted).unwrap();
    assert_ne!(bits(unpainted.positions()), bits(d.positions()));

    // A compared method without stiffness passes over the events; the recorded method
    // refuses one it cannot take, as the deformer does.
    let targets = replay(&s, &mut s.recorded_deformer().unwrap()).unwrap().targets;
    let mut mls = Deformer::new(mesh.clone(), MethodOptions::Mls(Default::default())).unwrap();
    replay_to_targets(&s, &targets, &mut mls).unwrap();
    let mut under_mls = s.clone();
    under_mls.options = RecordedOptions::of(MethodOptions::Mls(Default::default()));
    let mut deformer = under_mls.recorded_deformer().unwrap();
    let error = replay(&under_mls, &mut deformer).unwrap_err();
    assert!(error.to_string().starts_with("event 1: method mls has no stiffness"), "{error}");

    // Reading checks the length and the range, naming the event.
    let refused = |events: Vec<Event>| {
        let mut bad = small_session();
        bad.events = events;
        Session::from_json(&bad.to_json()).unwrap_err().to_string()
    };
    assert_eq!(
        refused(vec![Event::Stiffness(Some(vec![1.0; triangles - 1]))]),
        format!(
            "event 0: stiffness has {} numbers, expected {triangles} (1 for each of the {triangles} triangles)",
            triangles - 1
        )
    );
    let mut high = painted.clone();
    high[7] = 1000.5;
    assert_eq!(
        refused(vec![Event::Reset(true), Event::Stiffness(Some(high))]),
        "event 1: the stiffness of triangle 7 is 1000.5, expected a number from 0.001 to 1000"
    );
    let mut plain_options = s.clone();
    plain_options.options = RecordedOptions::default();
    let v1 = plain_options.to_json().replace("\"version\": 3", "\"version\": 1");
    assert_eq!(
        Session::from_json(&v1).unwrap_err().to_string(),
        "a version-1 session cannot have a stiffness event; version 3 sessions can"
    );
}

#[test]
fn inline_meshes_and_arap_sessions_round_trip_and_replay() {
    let (mesh, _) = bar_and_shear();
    let options = MethodOptions::Arap(ArapOptions::default().with_iterations(4));
    let mut s = Session::with_mesh(&mesh, options);
    let handles = (vec![0u32, 5], vec![[1.0, 0.0, 0.0], [0.2, 0.3, 0.5]]);
    s.events = vec![
        Event::Handles { triangles: handles.0.clone(), barycentric: handles.1.concat() },
        Event::Step(vec![0.0, 0.0, 0.02, 0.01]),
        Event::Reset(true),
        Event::Step(vec![0.0, -0.0, -0.01, 0.03]),
    ];
    let text = s.to_json();
    assert!(!text.contains("\"shape\"") && text.contains("\"positions\":[") && text.contains("\"iterations\":4"));
    let back = Session::from_json(&text).unwrap();
    assert_eq!(back, s);
    let rebuilt = back.mesh().unwrap();
    assert_eq!((rebuilt.positions(), rebuilt.triangles()), (mesh.positions(), mesh.triangles()));
    assert_eq!(back.method_options().unwrap(), options);
    let mut replayed = back.recorded_deformer().unwrap();
    assert_eq!(replayed.options().method(), Method::Arap);
    replay(&back, &mut replayed).unwrap();
    let mut a = Deformer::new(mesh.clone(), ArapOptions::default().with_iterations(4)).unwrap();
    a.set_handle_points(&handles.0, &handles.1).unwrap();
    a.step(&[[0.0, 0.0], [0.02, 0.01]]).unwrap();
    a.reset();
    a.step(&[[0.0, -0.0], [-0.01, 0.03]]).unwrap();
    assert_eq!(replayed.positions(), a.positions());

    // Where the mesh comes from: exactly one of a shape and an inline mesh, whole.
    let shape = small_session().shape;
    let mut both = s.clone();
    both.shape = shape.clone();
    assert_eq!(Session::from_json(&both.to_json()), Err(SessionError::MeshSource));
    let mut half = s.clone();
    half.mesh.triangles = None;
    assert_eq!(Session::from_json(&half.to_json()), Err(SessionError::MeshSource));
    let mut neither = small_session();
    neither.shape = None;
    assert_eq!(Session::from_json(&neither.to_json()), Err(SessionError::MeshSource));
    let mut short = s.clone();
    short.mesh.positions.as_mut().unwrap().pop();
    assert!(matches!(Session::from_json(&short.to_json()), Err(SessionError::MeshMismatch { .. })));
    let mut broken = s.clone();
    broken.mesh.triangles.as_mut().unwrap()[0] = 1_000_000;
    let broken = Session::from_json(&broken.to_json()).unwrap();
    assert!(matches!(broken.mesh(), Err(SessionError::Mesh(_))));
}

#[test]
fn options_of_the_other_method_and_bad_lengths_are_refused_on_reading() {
    let mut s = small_session();
    s.events.truncate(2);
    let with = |options: &str, events: &str| {
        let text = s.to_json();
        let at = text.find("\"events\": [").unwrap();
        let head = text[..at].replacen(
            "\"options\": {\"method\":\"akap\",\"lambda\":100.0,\"dirichlet\":true,\"integrator\":\"spiral\"}",
            options,
            1,
        );
        Session::from_json(&format!("{head}\"events\": [{events}]}}"))
    };
    let akap = "\"options\": {}";
    assert!(with(akap, "").is_ok());
    let arap_lambda = "\"options\": {\"method\":\"arap\",\"lambda\":5}";
    assert_eq!(
        with(arap_lambda, ""),
        Err(SessionError::Options(DeformError::ForeignOption {
            name: "lambda".into(),
            method: Method::Arap,
            owner: Method::Akap
        }))
    );
    assert_eq!(
        with(akap, "{\"options\":{\"method\":\"arap\"}},{\"options\":{\"integrator\":\"linear\"}}"),
        Err(SessionError::Event {
            index: 1,
            error: DeformError::ForeignOption { name: "integrator".into(), method: Method::Arap, owner: Method::Akap }
        })
    );
    assert!(matches!(
        with(akap, "{\"options\":{\"method\":\"arap\",\"iterations\":0}}"),
        Err(SessionError::Event { index: 0, error: DeformError::InvalidOption { name: "iterations", .. } })
    ));
    assert!(matches!(
        with(akap, "{\"options\":{\"method\":\"arap\",\"iterations\":2.5}}"),
        Err(SessionError::Event { index: 0, error: DeformError::OptionValue { name: "iterations", .. } })
    ));
    assert!(matches!(
        with(akap, "{\"options\":{\"iterations\":1e3}}"),
        Err(SessionError::Event { index: 0, error: DeformError::ForeignOption { .. } })
    ));
    // Two velocity components per handle of the handles in place.
    let handles = "{\"handles\":{\"triangles\":[0,5],\"barycentric\":[1,0,0,0,1,0]}}";
    assert!(with(akap, &format!("{handles},{{\"step\":[0,0,1,1]}}")).is_ok());
    assert!(matches!(
        with(akap, &format!("{handles},{{\"step\":[0,0]}}")),
        Err(SessionError::Event { index: 1, error: DeformError::Length { expected: 4, found: 2, .. } })
    ));
    assert!(matches!(
        with(akap, "{\"positions\":[0,0]}"),
        Err(SessionError::Event { index: 0, error: DeformError::Length { what: "positions", .. } })
    ));
    let message = with(arap_lambda, "").unwrap_err().to_string();
    assert_eq!(
        message,
        "the session's options are invalid: option lambda applies to method \"akap\" only, not to \"arap\""
    );
}

/// A session recorded in the app by `tests/browser/session.spec.ts` (two drags, a change
/// to ARAP, a reset, one more drag), with the bits of the pose the app reached.
const APP_RECORDED: &str = include_str!("sessions/app/app-recorded.json");
const APP_POSE: &str = include_str!("sessions/app/app-recorded.pose.json");

#[test]
fn the_apps_recording_replays_to_the_apps_pose_bit_for_bit() {
    let s = Session::from_json(APP_RECORDED).unwrap();
    let kinds: Vec<&str> = s
        .events
        .iter()
        .map(|e| match e {
            Event::Handles { .. } => "handles",
            Event::Step(_) => "step",
            Event::Positions(_) => "positions",
            Event::Options(_) => "options",
            Event::Reset(_) => "reset",
            Event::Stiffness(_) => "stiffness",
            Event::Turn { .. } => "turn",
            Event::Bones { .. } => "bones",
            Event::Joints(_) => "joints",
            Event::Rig(_) => "rig",
            Event::RigPose(_) => "rigPose",
        })
        .collect();
    for kind in ["handles", "step", "options", "reset"] {
        assert!(kinds.contains(&kind), "the recording has a {kind} event");
    }
    let pose: serde_json::Value = serde_json::from_str(APP_POSE).unwrap();
    let expected: Vec<u64> = pose["bits"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| u64::from_str_radix(b.as_str().unwrap(), 16).unwrap())
        .collect();
    assert_eq!(expected.len(), 2 * s.mesh.vertex_count);

    let mut deformer = s.recorded_deformer().unwrap();
    replay(&s, &mut deformer).unwrap();
    // The recording switched to ARAP.
    assert_eq!(deformer.options().method(), Method::Arap);
    let found: Vec<u64> = deformer.positions().iter().flatten().map(|x| x.to_bits()).collect();
    let differing = found.iter().zip(&expected).filter(|(a, b)| a != b).count();
    assert_eq!(differing, 0, "{differing} of {} coordinates differ from the app's", expected.len());
    // And the pose really moved from rest.
    assert_ne!(deformer.positions(), s.mesh().unwrap().positions());
}

/// The session bindings called inside wasm, and the deformer's recording: what they write is
/// the Rust format, and bad input (wrong types, throwing getters, calls that do not fit) is
/// a JavaScript `Error` that records nothing.
#[cfg(target_arch = "wasm32")]
mod bindings {
    use akap::session::Session;
    use akap::wasm::{session_json, session_mesh, JsDeformer};
    use js_sys::{Float64Array, Uint32Array};
    use wasm_bindgen::{JsCast, JsValue};
    use wasm_bindgen_test::wasm_bindgen_test as test;

    fn js(body: &str) -> JsValue {
        js_sys::Function::new_no_args(body).call0(&JsValue::NULL).unwrap()
    }

    fn message(result: Result<impl Sized, akap::wasm::BindingError>) -> String {
        let Err(e) = result else { panic!("expected an error") };
        let value = JsValue::from(e);
        String::from(value.dyn_ref::<js_sys::Error>().expect("a JavaScript Error").message())
    }

    #[test]
    fn session_json_and_session_mesh_read_through_the_rust_format() {
        let v2 = session_json(JsValue::from_str(super::SESSIONS[0].1)).unwrap();
        assert!(v2.contains("\"version\": 3,") && v2.contains("\"method\":\"akap\""));
        assert_eq!(Session::from_json(&v2).unwrap().events, super::session("bar").events);
        let mesh = session_mesh(JsValue::from_str(super::APP_RECORDED)).unwrap();
        let expected = Session::from_json(super::APP_RECORDED).unwrap().mesh().unwrap();
        assert_eq!(mesh.positions(), expected.positions().iter().flatten().copied().collect::<Vec<_>>());
        assert_eq!(message(session_json(JsValue::from(42))), "the session must be a string, not the number 42");
        assert!(message(session_json(JsValue::from_str("{"))).starts_with("not a valid session: EOF"));
    }

    #[test]
    fn the_deformers_recording_writes_what_the_reader_reads_and_refuses_what_does_not_fit() {
        let (mesh, _) = super::bar_and_shear();
        let positions: JsValue = Float64Array::from(&mesh.positions().concat()[..]).into();
        let triangles: JsValue = Uint32Array::from(&mesh.triangles().concat()[..]).into();
        let arap = js("return { method: 'arap', iterations: 3 }");
        let mut d = JsDeformer::new(positions.clone(), triangles.clone(), arap.clone()).unwrap();
        d.start_recording(JsValue::UNDEFINED).unwrap();
        d.set_handle_points(
            Uint32Array::from(&[0u32, 5][..]).into(),
            Float64Array::from(&[1.0, 0.0, 0.0, 0.2, 0.3, 0.5][..]).into(),
        )
        .unwrap();
        d.step(Float64Array::from(&[0.0, -0.0, 0.01, 0.02][..]).into()).unwrap();
        // Refused calls record nothing.
        assert!(d.step(Float64Array::from(&[0.0, 0.0][..]).into()).is_err());
        let foreign = d.set_options(js("return { lambda: 5 }"));
        assert_eq!(message(foreign), "option lambda applies to method \"akap\" only, not to \"arap\"");
        d.set_options(js("return { method: 'akap', lambda: 5 }")).unwrap();
        let triangle_count = mesh.triangle_count();
        let stiff = vec![7.0; triangle_count];
        d.set_stiffness(Float64Array::from(&stiff[..]).into()).unwrap();
        let short = d.set_stiffness(Float64Array::from(&stiff[1..]).into());
        assert_eq!(
            message(short),
            format!(
                "stiffness has {} numbers, expected {triangle_count} (1 for each of the {triangle_count} triangles)",
                triangle_count - 1
            )
        );
        assert!(
            message(d.set_stiffness(Float64Array::from(&[0.0; 1][..]).into())).starts_with("stiffness has 1 numbers")
        );
        d.set_stiffness(JsValue::UNDEFINED).unwrap();
        d.reset();
        let session = Session::from_json(&d.stop_recording().unwrap().unwrap()).unwrap();
        // The start (at rest), then each call as made.
        assert_eq!(session.events.len(), 7);
        assert!(session.shape.is_none());
        assert_eq!(session.mesh().unwrap().positions(), mesh.positions());
        assert_eq!(session.events[0], akap::session::Event::Reset(true));
        assert_eq!(session.events[2], akap::session::Event::Step(vec![0.0, -0.0, 0.01, 0.02]));
        assert!(matches!(session.events[2], akap::session::Event::Step(ref v) if v[1].is_sign_negative()));
        assert_eq!(session.events[4], akap::session::Event::Stiffness(Some(stiff)));
        assert_eq!(session.events[5], akap::session::Event::Stiffness(None));

        let dragon = d.start_recording(js("return { name: 'dragon' }"));
        assert!(message(dragon).starts_with("option name is \"dragon\", expected \"gingerbread\""));
        let throwing = js("return { get name() { throw new Error('boom'); } }");
        assert!(message(d.start_recording(throwing)).contains("boom"));
        assert!(!d.recording(), "a refused start records nothing");
    }
}
