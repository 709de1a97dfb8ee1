//! DefOp on a puppet: the ground truth joins the sheets at the joints and holds free sheets;
//! a rig trained on a puppet reproduces the ground truth on poses it was not trained on and
//! its operator file records the puppet. Expectations from the geometry: where the joint
//! is, which sheets a handle reaches, what a quarter turn of the arm puts where.

use akap::defop::{
    read_operator, write_operator, DefOpError, Energy, GroundTruth, GroundTruthOptions, Handles, MeshPoint, Start,
    TrainOptions, Trainer,
};
use akap::deform::{AkapOptions, Deformer, Joint, Part, Puppet};
use akap::geometry::Point;
use akap::pose::Poser;
use akap::{triangulate, ErrorCode, Mesh, Outline, TriangulationOptions};
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

const TORSO: usize = 0;
const HEAD: usize = 1;
const ARM: usize = 2;
const HAT: usize = 3;
/// Where the arm joins the torso (inside both), and the head the torso.
const SHOULDER: Point = [1.9, 2.55];
const NECK: Point = [1.0, 2.85];
/// The arm's far end.
const HAND: Point = [4.0, 2.55];

fn rectangle(x0: f64, y0: f64, x1: f64, y1: f64) -> Outline {
    Outline::new(vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]])
}

/// A torso, a head overlapping its top (joined at the neck), an arm in front overlapping
/// its right shoulder (joined at the shoulder) and a hat touching nothing, each meshed on
/// its own, in one mesh with no vertex shared between parts.
fn figure() -> (Mesh, Puppet) {
    let outlines = [
        ("torso", rectangle(0.0, 0.0, 2.0, 3.0)),
        ("head", rectangle(0.4, 2.6, 1.6, 3.8)),
        ("arm", rectangle(1.7, 2.3, 4.0, 2.8)),
        ("hat", rectangle(0.3, 4.0, 1.7, 4.4)),
    ];
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let mut parts = Vec::new();
    for (depth, (name, outline)) in outlines.into_iter().enumerate() {
        let mesh = triangulate(&outline, &TriangulationOptions::default().with_target_edge_length(0.2)).unwrap();
        let offset = positions.len() as u32;
        let first = triangles.len() as u32;
        positions.extend_from_slice(mesh.positions());
        triangles.extend(mesh.triangles().iter().map(|t| t.map(|v| v + offset)));
        parts.push(Part {
            name: name.into(),
            triangles: (first..triangles.len() as u32).collect(),
            depth: depth as i32,
        });
    }
    let joints = vec![Joint { point: SHOULDER, parts: [ARM, TORSO] }, Joint { point: NECK, parts: [HEAD, TORSO] }];
    (Mesh::new(positions, triangles).unwrap(), Puppet { parts, joints })
}

fn size(mesh: &Mesh) -> f64 {
    let (lo, hi) = akap::geometry::bounding_box(mesh.positions().iter().copied()).unwrap();
    (hi[0] - lo[0]).hypot(hi[1] - lo[1])
}

fn vertices_of(mesh: &Mesh, puppet: &Puppet, part: usize) -> Vec<usize> {
    let mut vertices: Vec<usize> =
        puppet.parts[part].triangles.iter().flat_map(|&t| mesh.triangles()[t as usize]).map(|v| v as usize).collect();
    vertices.sort_unstable();
    vertices.dedup();
    vertices
}

/// The vertex of `part` nearest `p`.
fn nearest(mesh: &Mesh, puppet: &Puppet, part: usize, p: Point) -> u32 {
    let d = |v: &usize| (mesh.positions()[*v][0] - p[0]).hypot(mesh.positions()[*v][1] - p[1]);
    vertices_of(mesh, puppet, part).into_iter().min_by(|a, b| d(a).total_cmp(&d(b))).unwrap() as u32
}

/// The point `p` of the rest mesh on `part`'s sheet: a triangle and barycentric weights.
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

/// Where the point of `part` that is at `p` at rest is in `pose` (x, y interleaved).
fn follow(mesh: &Mesh, puppet: &Puppet, part: usize, p: Point, pose: &[f64]) -> Point {
    let (t, w) = point_on(mesh, puppet, part, p);
    let corners = mesh.triangles()[t as usize];
    [0, 1].map(|c| (0..3).map(|k| w[k] * pose[2 * corners[k] as usize + c]).sum())
}

/// Handles at the torso's two bottom corners and at the hand.
fn handles(mesh: &Mesh, puppet: &Puppet) -> Vec<u32> {
    vec![
        nearest(mesh, puppet, TORSO, [0.0, 0.0]),
        nearest(mesh, puppet, TORSO, [2.0, 0.0]),
        nearest(mesh, puppet, ARM, HAND),
    ]
}

fn flat(points: &[Point]) -> Vec<f64> {
    points.iter().flatten().copied().collect()
}

#[test]
fn the_ground_truth_keeps_joints_together_and_free_sheets_still() {
    let (mesh, puppet) = figure();
    let handles = handles(&mesh, &puppet);
    let scale = size(&mesh);
    for energy in [Energy::Arap, Energy::SArap] {
        let mut solver = GroundTruth::with_puppet(
            &mesh,
            &puppet,
            Handles::Vertices(&handles),
            energy,
            GroundTruthOptions::default(),
        )
        .unwrap();
        // The torso's corners stay, the hand goes a quarter turn up about the shoulder.
        let rest: Vec<Point> = handles.iter().map(|&v| mesh.positions()[v as usize]).collect();
        let hand = rest[2];
        let turned = [SHOULDER[0] - (hand[1] - SHOULDER[1]), SHOULDER[1] + (hand[0] - SHOULDER[0])];
        let report = solver.solve(&[rest[0], rest[1], turned], Start::Rest).unwrap();
        let pose = flat(&report.positions);
        // Each joint's two points together, within 0.5% of the size.
        for joint in &puppet.joints {
            let [front, back] = joint.parts;
            let a = follow(&mesh, &puppet, front, joint.point, &pose);
            let b = follow(&mesh, &puppet, back, joint.point, &pose);
            let gap = (a[0] - b[0]).hypot(a[1] - b[1]);
            assert!(gap <= 0.005 * scale, "{energy:?}: joint {:?} opens by {gap}", joint.parts);
        }
        // Pulled a tenth of the arm's length beyond its reach, the arm pulls the torso at the
        // shoulder: the joint carries that force, and still holds within 0.5% of the size.
        let pulled = [hand[0] + 0.23, hand[1]];
        let stretched = flat(&solver.solve(&[rest[0], rest[1], pulled], Start::Rest).unwrap().positions);
        let a = follow(&mesh, &puppet, ARM, SHOULDER, &stretched);
        let b = follow(&mesh, &puppet, TORSO, SHOULDER, &stretched);
        let gap = (a[0] - b[0]).hypot(a[1] - b[1]);
        assert!(gap <= 0.005 * scale, "{energy:?}: the pulled shoulder opens by {gap}");
        assert!(b[0] - SHOULDER[0] > 1e-4 * scale, "{energy:?}: the torso's shoulder is pulled along");
        // The hat, which no handle reaches, exactly where it was.
        for v in vertices_of(&mesh, &puppet, HAT) {
            assert_eq!(report.positions[v], mesh.positions()[v], "{energy:?}: the hat's vertex {v} moved");
        }
        // The arm turned a quarter turn about the shoulder: its middle, halfway from the
        // shoulder to the hand, goes where the turn takes it (within the arm's bending).
        let middle = [(SHOULDER[0] + hand[0]) / 2.0, SHOULDER[1]];
        let expected = [SHOULDER[0], SHOULDER[1] + (middle[0] - SHOULDER[0])];
        let got = follow(&mesh, &puppet, ARM, middle, &pose);
        let off = (got[0] - expected[0]).hypot(got[1] - expected[1]);
        assert!(off <= 0.03 * scale, "{energy:?}: the arm's middle is {off} from the turned arm's");
        // The head, held by the neck alone with nothing to turn it, stays with the torso.
        for v in vertices_of(&mesh, &puppet, HEAD) {
            let moved = (report.positions[v][0] - mesh.positions()[v][0])
                .hypot(report.positions[v][1] - mesh.positions()[v][1]);
            assert!(moved <= 0.02 * scale, "{energy:?}: the head's vertex {v} moved by {moved}");
        }
    }
}

#[test]
fn a_puppet_that_does_not_fit_is_refused_and_a_mesh_in_pieces_still_is() {
    let (mesh, puppet) = figure();
    let handles = handles(&mesh, &puppet);
    let solve = |p: Option<&Puppet>| {
        let h = Handles::Vertices(&handles);
        match p {
            Some(p) => GroundTruth::with_puppet(&mesh, p, h, Energy::Arap, GroundTruthOptions::default()),
            None => GroundTruth::new(&mesh, h, Energy::Arap, GroundTruthOptions::default()),
        }
    };
    assert!(matches!(solve(None), Err(DefOpError::Disconnected { components: 4 })));
    let off = Puppet { joints: vec![Joint { point: [3.5, 2.55], parts: [ARM, TORSO] }], ..puppet.clone() };
    let error = solve(Some(&off)).unwrap_err();
    assert!(matches!(error, DefOpError::InvalidPuppet(_)), "{error:?}");
    assert_eq!(error.code(), ErrorCode::InvalidJoint);
    let mut short = puppet;
    short.parts[HAT].triangles.pop();
    assert_eq!(solve(Some(&short)).unwrap_err().code(), ErrorCode::InvalidArgument);
}

#[test]
fn a_rig_trained_on_a_puppet_reproduces_held_out_ground_truths_and_its_file_records_the_puppet() {
    let (mesh, puppet) = figure();
    let handle_vertices = handles(&mesh, &puppet);
    let handles: Vec<MeshPoint> = handle_vertices.iter().map(|&v| MeshPoint::Vertex(v)).collect();
    let options = TrainOptions {
        samples: 40,
        seed: 5,
        energy: Energy::Arap,
        puppet: Some(puppet.clone()),
        ..TrainOptions::default()
    };
    let mut trainer = Trainer::new(&mesh, &handles, options.clone()).unwrap();
    let radius = trainer.radius();
    while trainer.progress().stage != "done" {
        trainer.advance(0.0, || 0.0).unwrap();
    }
    let mut operator = trainer.finish().unwrap();
    assert_eq!(operator.puppet(), Some(&puppet));
    let mut solver = Trainer::solver_for(&mesh, &handles, &options).unwrap();

    // Held-out targets: each handle moved within the sampling radius, in directions and
    // lengths the samples did not use.
    let scale = size(&mesh);
    let rest: Vec<Point> = handle_vertices.iter().map(|&v| mesh.positions()[v as usize]).collect();
    let (mut squared, mut moved, mut count) = (0.0, 0.0, 0.0);
    for k in 0..12 {
        let targets: Vec<Point> = rest
            .iter()
            .enumerate()
            .map(|(h, p)| {
                let angle = 2.399 * (3 * k + h) as f64;
                let length = radius * (0.3 + 0.6 * ((k * 7 + h * 3) % 10) as f64 / 10.0);
                [p[0] + length * angle.cos(), p[1] + length * angle.sin()]
            })
            .collect();
        let truth = solver.solve(&targets, Start::Rest).unwrap().positions;
        let predicted = operator.evaluate(&flat(&targets)).unwrap();
        for (v, t) in truth.iter().enumerate() {
            let p = [predicted[2 * v], predicted[2 * v + 1]];
            squared += (p[0] - t[0]).powi(2) + (p[1] - t[1]).powi(2);
            moved += (t[0] - mesh.positions()[v][0]).powi(2) + (t[1] - mesh.positions()[v][1]).powi(2);
            count += 1.0;
        }
        // The hat stays where it is in every pose the rig gives.
        for v in vertices_of(&mesh, &puppet, HAT) {
            let p = [predicted[2 * v], predicted[2 * v + 1]];
            let off = (p[0] - mesh.positions()[v][0]).hypot(p[1] - mesh.positions()[v][1]);
            assert!(off <= 1e-9 * scale, "pose {k}: the rig moves the hat by {off}");
        }
    }
    let (rms, motion) = ((squared / count).sqrt() / scale, (moved / count).sqrt() / scale);
    // The usual DefOp error (lab/defop/defop.md: 1% to 3% of the diagonal, RMS), and well
    // below the motion itself.
    assert!(rms <= 0.03, "held-out RMS error {:.3}% of the diagonal", 100.0 * rms);
    assert!(rms <= 0.25 * motion, "held-out RMS error {rms} against a motion of {motion}");

    // The operator file records the puppet, and reads back with it.
    let bytes = write_operator(&mesh, &operator).unwrap();
    let (read_mesh, read) = read_operator(&bytes).unwrap();
    assert_eq!(read_mesh, mesh);
    assert_eq!(read.puppet(), Some(&puppet));
    // The puppet flag set (byte 49), and the file of the same operator without a puppet
    // with the puppet's section before the checksum.
    let plain = write_operator(&mesh, &operator.clone().with_puppet(None)).unwrap();
    assert_eq!((bytes[8], plain[8], bytes[49], plain[49]), (4, 4, 1, 0));
    let body = plain.len() - 8;
    assert_eq!((&bytes[12..49], &bytes[50..body]), (&plain[12..49], &plain[50..body]));
    let section = &bytes[body..bytes.len() - 8];
    let name_bytes: usize = puppet.parts.iter().map(|p| p.name.len()).sum();
    assert_eq!(section.len(), 8 + 12 * 4 + name_bytes + 4 * mesh.triangle_count() + 24 * 2);
    assert_eq!(section[..8], [4, 0, 0, 0, 2, 0, 0, 0], "4 parts, 2 joints");
    assert_eq!(read_operator(&plain).unwrap().1.puppet(), None);
    // Damaged: every truncation of the section, and flips throughout it, refused.
    for cut in body..bytes.len() {
        assert!(read_operator(&bytes[..cut]).is_err(), "{cut} bytes read");
    }
    for at in (body..bytes.len()).step_by(7) {
        let mut altered = bytes.clone();
        altered[at] ^= 0x04;
        assert!(read_operator(&altered).is_err(), "a flip at byte {at} was not noticed");
    }
    // An operator's puppet must fit the mesh it is written with.
    let off = Puppet { joints: vec![Joint { point: [3.5, 2.55], parts: [ARM, TORSO] }], ..puppet.clone() };
    assert!(write_operator(&mesh, &operator.clone().with_puppet(Some(off))).is_err());

    // The rig poses the puppet it was trained on, and no other.
    let poser = |puppet: Puppet| {
        let mut deformer = Deformer::with_puppet(mesh.clone(), AkapOptions::default(), puppet, None).unwrap();
        deformer.set_handle_vertices(&handle_vertices).unwrap();
        Poser::new(deformer)
    };
    let mut same = poser(puppet.clone());
    same.set_rig(Some(operator.clone())).unwrap();
    let moved = Puppet { joints: vec![Joint { point: [1.95, 2.5], parts: [ARM, TORSO] }], ..puppet };
    let error = poser(moved).set_rig(Some(operator)).unwrap_err();
    assert!(error.to_string().contains("trained on another puppet"), "{error}");
}
