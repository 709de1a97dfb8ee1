//! Writes the scripted sessions of the comparison (`tests/sessions/*.json`), recorded by a
//! poser of the AKAP deformer (`akap::pose::Poser`, the app's interaction loop): each frame
//! one step to the scripted targets, its velocity the target minus the handle's current
//! position. Run once; the files are committed.
//!
//! `cargo run --release --example make_sessions [-- OUTPUT_DIR]` (default `tests/sessions`).
//!
//! - `bar`: the toothed bar, left end pinned, right end dragged along a quarter circle
//!   (its centre line bent into an arc of unchanged length), as in the paper's Figure 9;
//! - `bar-fold`: the same, bent on to a half circle (a tighter bend, more distortion);
//! - `gingerbread`: a wave of the raised hand, a reset, then the other arm raised with the
//!   feet and head held;
//! - `gingerbread-fast`: the arm raised by 90 degrees in 6 frames, held by points inside
//!   triangles (the situation of the paper's Figure 8);
//! - `cat`: a front leg lifted and bent with the other paws and the head held, then, with
//!   a new handle set, the tail raised.

use std::f64::consts::PI;

use akap::deform::{AkapOptions, Deformer};
use akap::geometry::{distance, Point};
use akap::pose::Poser;
use akap::session::{MeshCounts, Session, SessionMesh, ShapeSpec};
use akap::{shapes, Mesh};

/// A handle: a triangle and barycentric weights.
type Handle = (u32, [f64; 3]);

/// A handle at the vertex nearest `p`.
fn at_vertex(mesh: &Mesh, p: Point) -> Handle {
    let v = (0..mesh.vertex_count())
        .min_by(|&a, &b| distance(mesh.positions()[a], p).total_cmp(&distance(mesh.positions()[b], p)))
        .expect("a mesh has vertices");
    let t = mesh.triangles().iter().position(|t| t.contains(&(v as u32))).expect("every vertex is in a triangle");
    (t as u32, mesh.triangles()[t].map(|w| if w as usize == v { 1.0 } else { 0.0 }))
}

/// A handle at the centroid of the triangle whose centroid is nearest `p`.
fn in_triangle(mesh: &Mesh, p: Point) -> Handle {
    let centroid = |t: &[u32; 3]| {
        let q = t.map(|v| mesh.positions()[v as usize]);
        [(q[0][0] + q[1][0] + q[2][0]) / 3.0, (q[0][1] + q[1][1] + q[2][1]) / 3.0]
    };
    let t = (0..mesh.triangle_count())
        .min_by(|&a, &b| {
            distance(centroid(&mesh.triangles()[a]), p).total_cmp(&distance(centroid(&mesh.triangles()[b]), p))
        })
        .expect("a mesh has triangles");
    (t as u32, [1.0 / 3.0; 3])
}

fn rotate(p: Point, centre: Point, angle: f64) -> Point {
    let (s, c) = angle.sin_cos();
    let r = [p[0] - centre[0], p[1] - centre[1]];
    [centre[0] + c * r[0] - s * r[1], centre[1] + s * r[0] + c * r[1]]
}

/// Records a session: a poser of the AKAP deformer follows the script, one step a frame to
/// the scripted targets, and records each step.
struct Recorder {
    poser: Poser,
}

impl Recorder {
    fn new(name: &str, target_edge_length: f64) -> Self {
        let shape = ShapeSpec {
            name: name.to_owned(),
            target_edge_length: Some(target_edge_length),
            max_area: None,
            min_angle: Some(28.0),
        };
        let counts = MeshCounts { vertex_count: 0, triangle_count: 0 };
        let triangulation = shape.triangulation_options();
        let mut session = Session::new(shape, counts, AkapOptions::default());
        let mesh = akap::triangulate(&shapes::by_name(name).expect("a built-in shape"), &triangulation)
            .expect("the built-in shapes triangulate");
        session.mesh = SessionMesh::counts_of(MeshCounts::of(&mesh));
        let mut poser = Poser::new(Deformer::new(mesh, AkapOptions::default()).expect("a connected mesh"));
        poser.resume_recording(session);
        Self { poser }
    }

    fn mesh(&self) -> &Mesh {
        self.poser.deformer().mesh()
    }

    fn handles(&mut self, handles: &[Handle]) {
        let triangles: Vec<u32> = handles.iter().map(|h| h.0).collect();
        let weights: Vec<[f64; 3]> = handles.iter().map(|h| h.1).collect();
        self.poser.set_handle_points(&triangles, &weights).expect("valid handles");
    }

    /// One frame to these targets, in one step.
    fn step(&mut self, targets: &[Point]) {
        self.poser.set_targets(targets).expect("finite targets");
        self.poser.step_toward(1.0, None).expect("a step of the script");
    }

    fn reset(&mut self) {
        self.poser.reset();
    }

    fn rest_of(&self, handles: &[Handle]) -> Vec<Point> {
        handles
            .iter()
            .map(|&(t, w)| {
                let tri = self.mesh().triangles()[t as usize];
                let mut p = [0.0, 0.0];
                for (v, w) in tri.iter().zip(w) {
                    p[0] += w * self.mesh().positions()[*v as usize][0];
                    p[1] += w * self.mesh().positions()[*v as usize][1];
                }
                p
            })
            .collect()
    }

    fn finish(mut self) -> Session {
        let m = self.poser.deformer().metrics();
        let session = self.poser.stop_recording().expect("a recording runs");
        eprintln!(
            "{}: {} vertices, {} steps, E_area {:.4}, E_angle {:.4}, {} flipped",
            session.shape.as_ref().map_or("", |s| &s.name),
            session.mesh.vertex_count,
            session.step_count(),
            m.area_distortion,
            m.angle_distortion,
            m.flipped
        );
        session
    }
}

/// The bar bent by `angle`: left end pinned, the right end (three handles) following the
/// end of its centre line bent into a circular arc of unchanged length.
fn bar(angle: f64, frames: usize) -> Session {
    let mut r = Recorder::new("bar", 0.04);
    let [length, height] = shapes::BAR_SIZE;
    let ends: Vec<Point> = [0.0, length].iter().flat_map(|&x| [[x, 0.0], [x, height / 2.0], [x, height]]).collect();
    let handles: Vec<Handle> = ends.iter().map(|&p| at_vertex(r.mesh(), p)).collect();
    r.handles(&handles);
    let rest = r.rest_of(&handles);
    for k in 1..=frames {
        let phi = angle * k as f64 / frames as f64;
        let radius = length / phi;
        let end = [radius * phi.sin(), height / 2.0 + radius * (1.0 - phi.cos())];
        let (s, c) = phi.sin_cos();
        let targets: Vec<Point> = rest
            .iter()
            .enumerate()
            .map(|(i, p)| {
                if i < 3 {
                    *p
                } else {
                    let y = p[1] - height / 2.0;
                    [end[0] - s * y, end[1] + c * y]
                }
            })
            .collect();
        r.step(&targets);
    }
    r.finish()
}

fn gingerbread() -> Session {
    let mut r = Recorder::new("gingerbread", 0.04);
    let mesh = r.mesh().clone();
    let handles = [
        at_vertex(&mesh, [-0.21, -0.02]),
        at_vertex(&mesh, [0.21, -0.02]),
        in_triangle(&mesh, [0.0, 1.2]),
        at_vertex(&mesh, [0.61, 0.63]),
        at_vertex(&mesh, [-0.49, 1.2]),
    ];
    r.handles(&handles);
    let rest = r.rest_of(&handles);
    // A short wave of the raised left hand, then back to the rest pose.
    for k in 1..=12 {
        let mut targets = rest.clone();
        targets[4] = [rest[4][0] + 0.06 * (PI * k as f64 / 6.0).sin(), rest[4][1]];
        r.step(&targets);
    }
    r.reset();
    // The right arm raised: the hand swings up by 75 degrees about the shoulder.
    let shoulder = [0.22, 0.66];
    let frames = 50;
    for k in 1..=frames {
        let mut targets = rest.clone();
        targets[3] = rotate(rest[3], shoulder, 75f64.to_radians() * k as f64 / frames as f64);
        r.step(&targets);
    }
    r.finish()
}

/// Figure 8's situation: large frames (15 degrees each) and handles inside triangles, where
/// the ablations show (singular fields around handles without the Dirichlet step, dilation
/// with linear steps).
fn gingerbread_fast() -> Session {
    let mut r = Recorder::new("gingerbread", 0.04);
    let mesh = r.mesh().clone();
    let handles = [
        at_vertex(&mesh, [-0.21, -0.02]),
        at_vertex(&mesh, [0.21, -0.02]),
        in_triangle(&mesh, [0.0, 1.2]),
        in_triangle(&mesh, [0.55, 0.63]),
        in_triangle(&mesh, [-0.46, 1.15]),
    ];
    r.handles(&handles);
    let rest = r.rest_of(&handles);
    let shoulder = [0.22, 0.66];
    let frames = 6;
    for k in 1..=frames {
        let mut targets = rest.clone();
        targets[3] = rotate(rest[3], shoulder, 90f64.to_radians() * k as f64 / frames as f64);
        r.step(&targets);
    }
    r.finish()
}

fn cat() -> Session {
    let mut r = Recorder::new("cat", 0.045);
    let mesh = r.mesh().clone();
    let mut handles = vec![
        at_vertex(&mesh, [-0.45, -0.01]),
        at_vertex(&mesh, [-0.24, -0.01]),
        at_vertex(&mesh, [0.22, -0.01]),
        in_triangle(&mesh, [0.66, 0.82]),
        at_vertex(&mesh, [0.42, -0.01]),
    ];
    r.handles(&handles);
    let rest = r.rest_of(&handles);
    // The front paw lifted forward and up, turning 70 degrees about the elbow.
    let elbow = [0.40, 0.30];
    let frames = 40;
    for k in 1..=frames {
        let mut targets = rest.clone();
        targets[4] = rotate(rest[4], elbow, 70f64.to_radians() * k as f64 / frames as f64);
        r.step(&targets);
    }
    // New handles: the same ones plus the tail tip; the tail swings up by 45 degrees.
    let mut held = r.poser.deformer().handle_positions();
    handles.push(in_triangle(&mesh, [-0.82, 1.04]));
    r.handles(&handles);
    let tip = r.poser.deformer().handle_positions()[5];
    let base = [-0.55, 0.68];
    for k in 1..=frames {
        held.truncate(5);
        held.push(rotate(tip, base, -45f64.to_radians() * k as f64 / frames as f64));
        r.step(&held);
    }
    r.finish()
}

fn main() {
    let dir = std::env::args().nth(1).unwrap_or_else(|| "tests/sessions".to_owned());
    std::fs::create_dir_all(&dir).expect("can create the output directory");
    let sessions = [
        ("bar", bar(PI / 2.0, 60)),
        ("bar-fold", bar(PI, 90)),
        ("gingerbread", gingerbread()),
        ("gingerbread-fast", gingerbread_fast()),
        ("cat", cat()),
    ];
    for (file, session) in sessions {
        let path = format!("{dir}/{file}.json");
        std::fs::write(&path, session.to_json()).expect("can write the session");
        eprintln!("wrote {path}");
    }
}
