//! `examples/pose_obj.rs`, the native command line (OBJ in, posed OBJ out), compiled into
//! this module and called directly. Expectations come from the mathematics: handles that
//! all move by one translation translate the whole mesh; a rotated input with rotated moves
//! gives the rotated pose; no motion changes nothing; files round-trip; bad input is an
//! error, not a panic.

// The example's `main` and the report fields only its summary reads.
#[allow(dead_code)]
#[path = "../examples/pose_obj.rs"]
mod example;

use akap::deform::{AkapOptions, ArapOptions, MethodOptions};
use akap::geometry::Point;
use akap::import::mesh_file::read_obj;
use akap::import::Limits;
use example::{pose_obj, run, Pose};

/// Columns and rows of the test grid's vertices: a 2 x 1 bar of 0.25 squares.
const COLUMNS: u32 = 9;
const ROWS: u32 = 5;

/// The bar as OBJ text: vertex `j * COLUMNS + i` at `(i / 4, j / 4)`, texture coordinates
/// that differ from the positions, and counter-clockwise quads (fanned into triangles).
fn bar_obj(map: impl Fn(Point) -> Point) -> String {
    let mut text = String::from("# a bar\n");
    for j in 0..ROWS {
        for i in 0..COLUMNS {
            let p = map([f64::from(i) / 4.0, f64::from(j) / 4.0]);
            text += &format!("v {} {} 0\n", p[0], p[1]);
        }
    }
    for k in 0..COLUMNS * ROWS {
        text += &format!("vt {} {}\n", f64::from(k % COLUMNS) / 8.0 + 0.1, 1.0 - f64::from(k / COLUMNS) / 3.0);
    }
    for j in 0..ROWS - 1 {
        for i in 0..COLUMNS - 1 {
            let [a, b, c, d] =
                [j * COLUMNS + i, j * COLUMNS + i + 1, (j + 1) * COLUMNS + i + 1, (j + 1) * COLUMNS + i].map(|v| v + 1);
            text += &format!("f {a}/{a} {b}/{b} {c}/{c} {d}/{d}\n");
        }
    }
    text
}

fn positions(obj: &str) -> Vec<Point> {
    read_obj(obj, &Limits::default()).unwrap().mesh.positions().to_vec()
}

fn methods() -> [MethodOptions; 2] {
    [MethodOptions::Akap(AkapOptions::default()), MethodOptions::Arap(ArapOptions::default())]
}

/// Far corners of the bar.
const LAST: u32 = COLUMNS * ROWS - 1;

#[test]
fn handles_moved_alike_translate_the_mesh() {
    let text = bar_obj(|p| p);
    let rest = positions(&text);
    let t = [0.3, -0.2];
    for method in methods() {
        let pose = Pose { moves: vec![(0, t), (LAST, t)], method, ..Pose::default() };
        let posed = pose_obj(Some(&text), &pose).unwrap();
        // |t| = 0.36 in steps of at most 2% of the bar's length 2: 10 steps.
        assert_eq!(posed.steps, 10, "{method:?}");
        let out = positions(&posed.obj);
        assert_eq!(out.len(), rest.len());
        for (v, (p, q)) in out.iter().zip(&rest).enumerate() {
            let error = (p[0] - q[0] - t[0]).hypot(p[1] - q[1] - t[1]);
            assert!(error < 1e-9, "{method:?}: vertex {v} is {error:e} off the translation");
        }
        assert!(posed.miss < 1e-9 && posed.metrics.flipped == 0, "{method:?}: {posed:?}");
    }
}

#[test]
fn a_rotated_input_gives_the_rotated_pose() {
    // A quarter turn, (x, y) -> (-y, x), is exact in floating point, and both energies are
    // invariant under rotations: rotating the bar and the moves rotates the result.
    let quarter = |p: Point| [-p[1], p[0]];
    let (text, turned) = (bar_obj(|p| p), bar_obj(quarter));
    for method in methods() {
        let bend = |d: Point| Pose {
            pins: vec![0, (ROWS - 1) * COLUMNS],
            moves: vec![(COLUMNS - 1, d), (LAST, d)],
            method,
            ..Pose::default()
        };
        let posed = pose_obj(Some(&text), &bend([0.1, 0.5])).unwrap();
        let turned_posed = pose_obj(Some(&turned), &bend(quarter([0.1, 0.5]))).unwrap();
        assert_eq!(posed.steps, 13, "{method:?}: |(0.1, 0.5)| / 0.04 = 12.7");
        assert!(posed.metrics.angle_distortion > 2.001, "{method:?}: the bend is no rigid motion");
        assert!(posed.miss < 2e-3, "{method:?}: handles end {:e} from their targets", posed.miss);
        for (v, (p, q)) in positions(&posed.obj).iter().zip(positions(&turned_posed.obj)).enumerate() {
            let r = quarter(*p);
            let error = (r[0] - q[0]).hypot(r[1] - q[1]);
            assert!(error < 1e-9, "{method:?}: vertex {v} is {error:e} off the rotated pose");
        }
    }
}

#[test]
fn pins_alone_keep_the_mesh() {
    let text = bar_obj(|p| p);
    for method in methods() {
        let pose = Pose { pins: vec![0, 20, LAST], method, ..Pose::default() };
        let posed = pose_obj(Some(&text), &pose).unwrap();
        assert_eq!(posed.steps, 1);
        for (p, q) in positions(&posed.obj).iter().zip(positions(&text)) {
            assert!((p[0] - q[0]).hypot(p[1] - q[1]) < 1e-12, "{method:?}");
        }
    }
}

/// A fresh directory for one test's files.
fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("akap-pose-obj-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn args(list: &[&str]) -> Vec<String> {
    list.iter().map(|s| s.to_string()).collect()
}

#[test]
fn command_line_writes_an_obj_that_reads_back() {
    let dir = scratch("round-trip");
    let (input, output) = (dir.join("in.obj"), dir.join("out.obj"));
    std::fs::write(&input, bar_obj(|p| p)).unwrap();
    let (i, o) = (input.to_str().unwrap(), output.to_str().unwrap());
    let report = run(&args(&[i, o, "--pin", "0", "--move", "44:0.1,0.3", "--steps", "7"])).unwrap();
    assert!(report.contains("7 steps") && report.contains("texture coordinates kept"), "{report}");
    let before = read_obj(&std::fs::read_to_string(&input).unwrap(), &Limits::default()).unwrap();
    let after = read_obj(&std::fs::read_to_string(&output).unwrap(), &Limits::default()).unwrap();
    assert_eq!(after.mesh.vertex_count(), 45);
    assert_eq!(after.mesh.triangles(), before.mesh.triangles());
    assert_eq!(after.uvs, before.uvs);
    assert!(before.uvs.is_some());
    // The pinned corner stays near its place, the moved one arrives near its target.
    let (p, q) = (after.mesh.positions()[0], after.mesh.positions()[44]);
    assert!(p[0].hypot(p[1]) < 1e-3 && (q[0] - 2.1).hypot(q[1] - 1.3) < 1e-3, "{p:?} {q:?}");

    // The built-in figure, out of the box: about 1,500 vertices, no texture coordinates.
    let report = run(&args(&[o])).unwrap();
    let figure = read_obj(&std::fs::read_to_string(&output).unwrap(), &Limits::default()).unwrap();
    assert!(figure.mesh.vertex_count().abs_diff(1500) <= 150, "{report}");
    assert!(figure.uvs.is_none() && report.contains("0 triangles flipped"), "{report}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let pin = Pose { pins: vec![0], ..Pose::default() };
    let files = [
        ("v 0 0\nv 1 0\nf 1 2 3\n", "vertex index 3 is out of range"),
        ("v 0 0\nv nan 0\nv 0 1\nf 1 2 3\n", "`nan` is not a finite number"),
        ("v 0 0 1\nv 1 0\nv 0 1\nf 1 2 3\n", "only flat meshes"),
        ("v 0 0\nv 1 0\nv 0 1\nf 1 3 2\n", "clockwise"),
        ("hello\n", "unknown statement"),
        ("", "no triangle"),
        ("v 0 0\nv 1 0\nv 0 1\nv 5 5\nv 6 5\nv 5 6\nf 1 2 3\nf 4 5 6\n", "2 separate pieces"),
    ];
    for (text, message) in files {
        let error = pose_obj(Some(text), &pin).unwrap_err();
        assert!(error.contains(message), "{text:?}: {error}");
    }
    let text = bar_obj(|p| p);
    for (pose, message) in [
        (Pose::default(), "no handles"),
        (Pose { pins: vec![45], ..Pose::default() }, "vertex 45 is out of range"),
        (Pose { pins: vec![3], moves: vec![(3, [1.0, 0.0])], ..Pose::default() }, "two handles"),
        (Pose { moves: vec![(3, [1e300, 0.0])], ..Pose::default() }, "steps: 1 to 100000"),
        (Pose { pins: vec![0], steps: Some(0), ..Pose::default() }, "0 steps"),
        (Pose { method: MethodOptions::Akap(AkapOptions::default().with_lambda(-1.0)), ..pin.clone() }, "lambda"),
    ] {
        let error = pose_obj(Some(&text), &pose).unwrap_err();
        assert!(error.contains(message), "{pose:?}: {error}");
    }

    let dir = scratch("errors");
    let missing = dir.join("missing.obj");
    let (m, o) = (missing.to_str().unwrap(), dir.join("out.obj"));
    let o = o.to_str().unwrap();
    for (line, message) in [
        (vec![m, o, "--pin", "0"], "cannot read"),
        (vec![], "no output file"),
        (vec!["-", o, "--move", "3"], "VERTEX:DX,DY"),
        (vec!["-", o, "--move", "3:0.1,inf"], "not a finite number"),
        (vec!["-", o, "--pin", "-1"], "not a vertex number"),
        (vec!["-", o, "--pin"], "--pin needs a value"),
        (vec!["-", o, "--steps", "-3"], "--steps takes a whole number"),
        (vec!["-", o, "--method", "linear"], "unknown method"),
        (vec!["-", o, "--method", "arap", "--lambda", "5"], "option lambda applies to method \"akap\" only"),
        (vec!["-", o, "--set", "integrator=euler"], "must be \"spiral\" or \"linear\", not \"euler\""),
        (vec!["-", o, "--set", "lamda=5"], "unknown option lamda; method akap has lambda, dirichlet, integrator"),
        (vec!["-", o, "--set", "lambda"], "--set takes NAME=VALUE"),
        (vec!["-", o, "--method", "arap", "--set", "iterations=0"], "option iterations is 0"),
        (vec!["-", o, "--frobnicate"], "unknown option"),
        (vec!["a.obj", "b.obj", "c.obj"], "3 files"),
    ] {
        let error = run(&args(&line)).unwrap_err();
        assert!(error.contains(message), "{line:?}: {error}");
    }
    assert!(!std::path::Path::new(o).exists(), "nothing is written on error");
    assert!(run(&args(&["--help"])).unwrap().contains("usage: pose_obj"));
    std::fs::remove_dir_all(&dir).unwrap();
}
