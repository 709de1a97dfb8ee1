//! Mesh files of puppets: JSON carries parts and joints, OBJ carries parts as groups (`g`).
//! Expectations are the formats as documented (docs/formats.md) and the geometry of a small
//! puppet drawn by hand: a torso, an arm overlapping its shoulder, a hat touching nothing.

use akap::animation::{read_animation, write_animation, Animation, Easing, Key};
use akap::deform::{DeformError, Joint, Part, Puppet};
use akap::geometry::Point;
use akap::import::mesh_file::{read_json, read_obj, write_json, write_json_pose, write_obj, write_obj_pose, MeshFile};
use akap::import::{ImportError, Limits};
use akap::{ErrorCode, Mesh};
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

/// A point inside both the torso and the arm.
const SHOULDER: Point = [1.75, 1.75];

fn rectangle(x0: f64, y0: f64, x1: f64, y1: f64) -> [Point; 4] {
    [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
}

/// The torso (vertices 1-4 in OBJ's numbering, triangles 0 and 1), the arm (5-8, triangles
/// 2 and 3) and the hat (9-12, triangles 4 and 5), each a rectangle of two triangles. The
/// parts are listed out of depth order: the arm (depth 1), the torso (0), the hat (2).
fn figure() -> (Mesh, Puppet) {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for corners in [rectangle(0.0, 0.0, 2.0, 2.0), rectangle(1.5, 1.5, 4.0, 2.5), rectangle(0.0, 3.0, 1.0, 3.5)] {
        let o = positions.len() as u32;
        positions.extend(corners);
        triangles.extend([[o, o + 1, o + 2], [o, o + 2, o + 3]]);
    }
    let part = |name: &str, triangles: Vec<u32>, depth| Part { name: name.into(), triangles, depth };
    let puppet = Puppet {
        parts: vec![part("left arm", vec![2, 3], 1), part("torso", vec![0, 1], 0), part("hat", vec![4, 5], 2)],
        joints: vec![Joint { point: SHOULDER, parts: [0, 1] }],
    };
    (Mesh::new(positions, triangles).unwrap(), puppet)
}

fn limits() -> Limits {
    Limits::default()
}

/// The corners of each triangle of a part, in the part's order.
fn corners(mesh: &Mesh, part: &Part) -> Vec<[Point; 3]> {
    part.triangles.iter().map(|&t| mesh.triangles()[t as usize].map(|v| mesh.positions()[v as usize])).collect()
}

#[test]
fn json_carries_parts_and_joints_as_documented() {
    let (mesh, puppet) = figure();
    let text = write_json(&mesh, None, None, Some(&puppet), &limits()).unwrap();
    let plain = write_json(&mesh, None, None, None, &limits()).unwrap();
    // The puppet follows the mesh's fields, in the documented layout.
    let tail = concat!(
        r#","parts":[{"name":"left arm","triangles":[2,3],"depth":1},"#,
        r#"{"name":"torso","triangles":[0,1],"depth":0},{"name":"hat","triangles":[4,5],"depth":2}],"#,
        r#""joints":[{"point":[1.75,1.75],"parts":[0,1]}]}"#
    );
    assert_eq!(text, format!("{}{tail}", plain.strip_suffix('}').unwrap()));
    let back = read_json(&text, &limits()).unwrap();
    assert_eq!(back, MeshFile { mesh: mesh.clone(), uvs: None, stiffness: None, puppet: Some(puppet.clone()) });
    // Parts without joints: a puppet with none.
    let no_joints = text.replace(r#","joints":[{"point":[1.75,1.75],"parts":[0,1]}]"#, "");
    assert_eq!(read_json(&no_joints, &limits()).unwrap().puppet, Some(Puppet { joints: vec![], ..puppet }));
    assert_eq!(read_json(&plain, &limits()).unwrap().puppet, None);
}

/// The error reading `tail` (fields after the mesh's) with the figure's mesh.
fn json_error(tail: &str) -> ImportError {
    let (mesh, _) = figure();
    let plain = write_json(&mesh, None, None, None, &limits()).unwrap();
    let text = format!("{},{tail}}}", plain.strip_suffix('}').unwrap());
    read_json(&text, &limits()).unwrap_err()
}

#[test]
fn bad_puppets_in_json_are_refused_saying_where() {
    let parts = r#""parts":[{"name":"torso","triangles":[0,1],"depth":0},{"name":"arm","triangles":[2,3],"depth":1},{"name":"hat","triangles":[4,5],"depth":2}]"#;
    let cases: [(String, &str, ErrorCode); 7] = [
        (
            r#""joints":[{"point":[1.75,1.75],"parts":[1,0]}]"#.into(),
            "the file's puppet: the puppet's parts cannot be used: the file has joints but no parts",
            ErrorCode::InvalidArgument,
        ),
        (
            parts.replace("[4,5]", "[4,6]"),
            "part 2 names triangle 6, but the mesh has 6 triangles",
            ErrorCode::InvalidArgument,
        ),
        (parts.replace("[4,5]", "[4,0]"), "triangle 0 is in part 0 and in part 2", ErrorCode::InvalidArgument),
        (parts.replace("[4,5]", "[4]"), "triangle 5 is in no part", ErrorCode::InvalidArgument),
        (
            format!(r#"{parts},"joints":[{{"point":[3.5,2],"parts":[1,0]}}]"#),
            r#"joint 0 cannot be used: its point (3.5, 2) is not on part 0 ("torso")"#,
            ErrorCode::InvalidJoint,
        ),
        (
            format!(
                r#"{parts},"joints":[{{"point":[1.75,1.75],"parts":[1,0]}},{{"point":[1.75,1.75],"parts":[1,3]}}]"#
            ),
            "joint 1 cannot be used: it names part 3, but the puppet has 3 parts",
            ErrorCode::InvalidJoint,
        ),
        (
            format!(r#"{parts},"joints":[{{"point":[1.75,1.75],"parts":[1,1]}}]"#),
            "joint 0 cannot be used: it joins part 1 to itself",
            ErrorCode::InvalidJoint,
        ),
    ];
    for (tail, message, code) in cases {
        let error = json_error(&tail);
        assert!(matches!(error, ImportError::Puppet(_)), "{tail}: {error:?}");
        assert!(error.to_string().contains(message), "{tail}: {error}");
        assert_eq!(error.code(), code, "{tail}");
    }
    // What JSON itself says is wrong, with its line and column.
    for (tail, message) in [
        (parts.replace(r#""depth":2"#, r#""depth":2.5"#), "invalid type: floating point `2.5`, expected i32"),
        (parts.replace(r#""depth":2"#, r#""depth":2,"colour":"red""#), "unknown field `colour`"),
        (format!(r#"{parts},"joints":[{{"point":[1,2,3],"parts":[1,0]}}]"#), "trailing characters"),
        (format!(r#"{parts},"joints":[{{"point":[1,2],"parts":[-1,0]}}]"#), "invalid value: integer `-1`"),
    ] {
        match json_error(&tail) {
            ImportError::Syntax { format: "JSON", message: m, line: 1, .. } => assert!(m.contains(message), "{m}"),
            other => panic!("{tail}: {other:?}"),
        }
    }
    // Limits: the names' length and the number of parts.
    let long = "x".repeat(1025);
    let error = json_error(&parts.replace("\"hat\"", &format!("\"{long}\"")));
    assert!(error.to_string().contains("the name of part 2 has 1025 bytes, more than the limit of 1024"), "{error}");
    let mut many: Vec<String> = (0..256).map(|i| format!(r#"{{"name":"p{i}","triangles":[],"depth":{i}}}"#)).collect();
    many.push(r#"{"name":"all","triangles":[0,1,2,3,4,5],"depth":256}"#.into());
    let error = json_error(&format!(r#""parts":[{}]"#, many.join(",")));
    assert!(matches!(error, ImportError::TooLarge { size: 257, limit: 256, unit: "parts", .. }), "{error:?}");
}

#[test]
fn json_writers_refuse_what_the_reader_would() {
    let (mesh, puppet) = figure();
    let off = Puppet { joints: vec![Joint { point: [3.5, 2.0], parts: [0, 1] }], ..puppet.clone() };
    let error = write_json(&mesh, None, None, Some(&off), &limits()).unwrap_err();
    assert_eq!(error.code(), ErrorCode::InvalidJoint);
    // A pose's joints are written as given (they are rest points): only their indices and
    // the parts are checked.
    let pose: Vec<Point> = mesh.positions().iter().map(|p| [p[0] + 10.0, p[1]]).collect();
    assert!(write_json_pose(&pose, mesh.triangles(), None, None, Some(&off), &limits()).is_ok());
    let mut missing = puppet.clone();
    missing.parts[2].triangles.pop();
    let error = write_json_pose(&pose, mesh.triangles(), None, None, Some(&missing), &limits()).unwrap_err();
    assert_eq!(error, ImportError::Puppet(DeformError::InvalidParts { reason: "triangle 5 is in no part".into() }));
    let stray = Puppet { joints: vec![Joint { point: SHOULDER, parts: [0, 3] }], ..puppet };
    assert!(write_obj_pose(&pose, mesh.triangles(), None, Some(&stray), &limits()).is_err());
}

#[test]
fn obj_writes_parts_as_groups_back_to_front() {
    let (mesh, puppet) = figure();
    let text = write_obj(&mesh, None, Some(&puppet), &limits()).unwrap();
    let plain = write_obj(&mesh, None, None, &limits()).unwrap();
    let vertices = plain.lines().filter(|l| l.starts_with('v')).collect::<Vec<_>>().join("\n");
    // Back to front: the torso (depth 0), the arm (1), the hat (2); the arm's name made one
    // OBJ name.
    let expected = format!(
        "# akap mesh: 12 vertices, 6 triangles\n{vertices}\n\
         g torso\nf 1 2 3\nf 1 3 4\ng left_arm\nf 5 6 7\nf 5 7 8\ng hat\nf 9 10 11\nf 9 11 12\n"
    );
    assert_eq!(text, expected);
    // Read back: the same parts in depth order, depths their places, the same triangles
    // (the same corners), and no joints (OBJ has no place for them).
    let back = read_obj(&text, &limits()).unwrap();
    assert_eq!(back.mesh.positions(), mesh.positions());
    let read = back.puppet.unwrap();
    assert!(read.joints.is_empty());
    let names: Vec<(&str, i32)> = read.parts.iter().map(|p| (p.name.as_str(), p.depth)).collect();
    assert_eq!(names, [("torso", 0), ("left_arm", 1), ("hat", 2)]);
    for (r, original) in read.parts.iter().zip([1, 0, 2]) {
        assert_eq!(corners(&back.mesh, r), corners(&mesh, &puppet.parts[original]));
    }
    // Once in depth order with OBJ names, a puppet's file reads back to itself exactly.
    let again = write_obj(&back.mesh, None, Some(&read), &limits()).unwrap();
    assert_eq!(again, text);
}

#[test]
fn obj_groups_are_read_the_obj_way() {
    // Triangle k has vertices 3k + 1 to 3k + 3 (no vertex unused, none shared).
    let triangles =
        |n: usize| -> String { (0..n).map(|k| format!("v {x} 0\nv {} 0\nv {x} 1\n", k * 2 + 1, x = k * 2)).collect() };
    let read = |n: usize, faces: &str| read_obj(&format!("{}{faces}", triangles(n)), &limits());
    let parts = |n: usize, faces: &str| -> Vec<(String, Vec<u32>, i32)> {
        read(n, faces).unwrap().puppet.unwrap().parts.into_iter().map(|p| (p.name, p.triangles, p.depth)).collect()
    };
    let part = |name: &str, triangles: &[u32], depth| (name.to_string(), triangles.to_vec(), depth);
    // Faces before any group are in `default`; a group without faces makes no part; a name
    // seen again adds to its part; a polygon's triangles are all in its group; `g` alone is
    // `default`; several names are one part, named by them all.
    let quad = "v 20 0\nv 21 0\nv 21 1\nv 20 1\n";
    assert_eq!(
        parts(
            4,
            &format!(
                "{quad}f 1 2 3\ng empty\ng a\nf 4 5 6\ng b c # a comment\nf 7 8 9\ng a\nf 10 11 12\ng\nf 13 14 15 16\n"
            )
        ),
        [part("default", &[0, 4, 5], 0), part("a", &[1, 3], 1), part("b c", &[2], 2)]
    );
    // Only groups after the faces: every face is in `default`.
    assert_eq!(parts(1, "f 1 2 3\ng unused\n"), [part("default", &[0], 0)]);
    // No group at all: one shape, as before.
    assert_eq!(read(1, "f 1 2 3\n").unwrap().puppet, None);
    // Limits: a name's length (with its line and column), the number of parts.
    let long = format!("f 1 2 3\n  g {}\nf 4 5 6\n", "x".repeat(1025));
    match read(2, &long).unwrap_err() {
        ImportError::Syntax { format: "OBJ", line: 8, column: 3, message } => assert!(message.contains("1025 bytes")),
        other => panic!("{other:?}"),
    }
    let many: String = (0..257).map(|i| format!("g p{i}\nf {} {} {}\n", 3 * i + 1, 3 * i + 2, 3 * i + 3)).collect();
    let error = read(257, &many).unwrap_err();
    assert!(matches!(error, ImportError::TooLarge { size: 257, limit: 256, unit: "parts", .. }), "{error:?}");
    assert_eq!(read(256, &many[..many.find("g p256").unwrap()]).unwrap().puppet.unwrap().parts.len(), 256);
}

#[test]
fn an_animation_file_carries_the_puppet() {
    let (mesh, puppet) = figure();
    let rest = mesh.positions().to_vec();
    let animation = Animation {
        mesh: MeshFile { mesh, uvs: None, stiffness: None, puppet: Some(puppet.clone()) },
        fps: 30.0,
        keys: vec![Key { time: 0.0, easing: Easing::Linear, handles: vec![[0.0, 0.0]] }],
        frames: vec![rest],
    };
    let text = write_animation(&animation, &limits()).unwrap();
    assert_eq!(read_animation(&text, &limits()).unwrap(), animation);
    let off = Puppet { joints: vec![Joint { point: [3.5, 2.0], parts: [0, 1] }], ..puppet };
    let bad = Animation { mesh: MeshFile { puppet: Some(off), ..animation.mesh.clone() }, ..animation };
    assert!(write_animation(&bad, &limits()).is_err());
}
