//! Mesh files: exact round trips of JSON and OBJ (with texture coordinates), the OBJ
//! features we read, and malformed files reported with line and column.

use akap::geometry::Point;
use akap::import::mesh_file::{read_json, read_obj, write_json, write_json_pose, write_obj, write_obj_pose};
use akap::import::{ImportError, Limits};
use akap::shapes::gingerbread;
use akap::{triangulate, Mesh, MeshError, TriangulationOptions};
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

fn figure() -> (Mesh, Vec<Point>) {
    let mesh = triangulate(&gingerbread(), &TriangulationOptions::default().with_target_edge_length(0.1)).unwrap();
    // Texture coordinates with awkward binary fractions, to test exact printing.
    let uvs = mesh.positions().iter().map(|p| [p[0] / 3.0 + 0.1, 1.0 - p[1] / 7.0]).collect();
    (mesh, uvs)
}

fn limits() -> Limits {
    Limits::default()
}

#[test]
fn json_round_trip_is_exact() {
    let (mesh, uvs) = figure();
    for with_uvs in [false, true] {
        let text = write_json(&mesh, with_uvs.then_some(uvs.as_slice()), None, None, &limits()).unwrap();
        let back = read_json(&text, &limits()).unwrap();
        assert_eq!(back.mesh, mesh);
        assert_eq!(back.uvs.as_deref(), with_uvs.then_some(uvs.as_slice()));
        assert_eq!(text.contains("\"uvs\""), with_uvs);
    }
}

#[test]
fn json_carries_stiffness_exactly_and_refuses_bad_values() {
    let (mesh, _) = figure();
    let n = mesh.triangle_count();
    // Awkward binary fractions across the whole range, the ends included.
    let stiffness: Vec<f64> = (0..n).map(|t| [0.001, 1.0 / 3.0, 1.0, 7.1, 1000.0][t % 5]).collect();
    let text = write_json(&mesh, None, Some(&stiffness), None, &limits()).unwrap();
    let back = read_json(&text, &limits()).unwrap();
    assert_eq!((back.mesh, back.stiffness.as_deref()), (mesh.clone(), Some(&stiffness[..])));
    assert_eq!(read_json(&write_json(&mesh, None, None, None, &limits()).unwrap(), &limits()).unwrap().stiffness, None);
    // OBJ has no place for it.
    assert_eq!(read_obj(&write_obj(&mesh, None, None, &limits()).unwrap(), &limits()).unwrap().stiffness, None);

    let square = r#"{"positions": [0,0, 1,0, 1,1, 0,1], "triangles": [0,1,2, 0,2,3], "stiffness": "#;
    let message = |tail: &str| read_json(&format!("{square}{tail}}}"), &limits()).unwrap_err().to_string();
    assert_eq!(message("[1]"), "stiffness: 1 numbers for 2 triangles; one per triangle is needed");
    assert_eq!(message("[1, 0]"), "stiffness: triangle 1 has 0, expected a number from 0.001 to 1000");
    assert!(message("[1e400, 1]").starts_with("JSON error at line 1"));
    let short = write_json(&mesh, None, Some(&stiffness[1..]), None, &limits()).unwrap_err();
    assert!(matches!(short, ImportError::Stiffness { .. }), "{short}");
    let mut high = stiffness.clone();
    high[n - 1] = 1_000.000_000_1;
    let error = write_json_pose(mesh.positions(), mesh.triangles(), None, Some(&high), None, &limits()).unwrap_err();
    assert_eq!(
        error.to_string(),
        format!("stiffness: triangle {} has 1000.0000001, expected a number from 0.001 to 1000", n - 1)
    );
}

#[test]
fn obj_round_trip_is_exact() {
    let (mesh, uvs) = figure();
    for with_uvs in [false, true] {
        let text = write_obj(&mesh, with_uvs.then_some(uvs.as_slice()), None, &limits()).unwrap();
        assert!(text.starts_with("# akap mesh:"));
        let back = read_obj(&text, &limits()).unwrap();
        assert_eq!(back.mesh, mesh);
        assert_eq!(back.uvs.as_deref(), with_uvs.then_some(uvs.as_slice()));
    }
}

#[test]
fn obj_polygons_negative_indices_and_comments() {
    // A unit square as one quad (fanned into two triangles) plus a triangle on top given
    // with negative indices, normals, groups, Windows line ends and a continued line.
    let text = "# a house\r\nmtllib house.mtl\r\no house\r\nv 0 0 0\r\nv 1 0\r\nv 1 1 0.0 1.0\r\nv 0 1\r\n\
                vn 0 0 1\r\ng walls\r\nf 1//1 2//1 3//1 4//1 # the square\r\nv 0.5 \\\r\n 1.5\r\ns off\r\nf -2 -3 -1\r\n";
    let file = read_obj(text, &limits()).unwrap();
    assert_eq!(file.mesh.triangles(), &[[0, 1, 2], [0, 2, 3], [3, 2, 4]]);
    assert_eq!(file.mesh.positions()[4], [0.5, 1.5]);
    assert_eq!(file.mesh.area(), 1.25);
    assert_eq!(file.uvs, None);
    // Texture coordinates per corner become per vertex.
    let text = "v 0 0\nv 1 0\nv 0 1\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2/1 3/3\n";
    assert_eq!(read_obj(text, &limits()).unwrap().uvs, Some(vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]));
}

fn obj_error(text: &str) -> String {
    read_obj(text, &limits()).unwrap_err().to_string()
}

#[test]
fn malformed_obj_says_where() {
    let square = "v 0 0\nv 1 0\nv 1 1\n";
    let cases = [
        ("v 0 0\nv 1 zero\n", "OBJ error at line 2, column 5: `zero` is not a finite number"),
        ("v 0 0\nv 1 NaN\n", "line 2, column 5: `NaN` is not a finite number"),
        ("v 0 0 2\n", "line 1, column 7: vertex 1 has z = 2; only flat meshes"),
        ("v 0\n", "line 1, column 1: a vertex needs x and y"),
        (&format!("{square}f 1 2 4\n"), "line 4, column 7: vertex index 4 is out of range: 3 defined so far"),
        (&format!("{square}f 0 1 2\n"), "vertex index 0 is out of range"),
        (&format!("{square}f -4 1 2\n"), "vertex index -4 is out of range"),
        (&format!("{square}f 1 2\n"), "a face needs at least 3 corners, found 2"),
        (&format!("{square}f 1/x 2 3\n"), "`x` is not a texture coordinate index"),
        (&format!("{square}f 1/1/1/1 2 3\n"), "texture coordinate index 1 is out of range: 0 defined so far"),
        (&format!("{square}vt 0 0\nf 1/1/1/1 2/1 3/1\n"), "`1/1/1/1` has more than three indices"),
        (
            &format!("{square}vt 0 0\nvt 1 1\nf 1/1 2/1 3/1\nf 1/2 3/1 2/1\n"),
            "line 7, column 3: vertex 1 has two different texture coordinates",
        ),
        (&format!("{square}vt 0 0\nf 1/1 2/1 3\n"), "some face corners have texture coordinates and others do not"),
        ("{\"positions\": []}\n", "line 1, column 1: unknown statement `{\"positions\":`"),
        // The mesh rules and messages of Mesh::new.
        (&format!("{square}f 1 3 2\n"), "triangle 0 is clockwise; triangles must be counter-clockwise"),
        (&format!("{square}v 5 5\nf 1 2 3\n"), "vertex 3 belongs to no triangle"),
        (square, "the mesh has no triangles"),
    ];
    for (text, expected) in cases {
        let message = obj_error(text);
        assert!(message.contains(expected), "{message:?} should contain {expected:?}");
    }
    assert!(matches!(
        read_obj("v 0 0\nv 1 0\nv 0 1\nf 1 3 2\n", &limits()),
        Err(ImportError::Mesh(MeshError::Clockwise { triangle: 0 }))
    ));
}

#[test]
fn malformed_json_says_where() {
    let cases = [
        ("{\"positions\": [0, 0, 1, 0, 0, 1], \"triangles\": [0, 1, 2,]}", "JSON error at line 1, column 57"),
        (
            "{\"positions\": [0, 0, 1, 0, 0, 1],\n \"triangles\": [0, 1, -2]}",
            "line 2, column 23: invalid value: integer `-2`, expected u32",
        ),
        ("{\"positions\": [0, 0, 1, 0, 0, 1], \"triangles\": [0, 1, 2], \"uv\": []}", "unknown field `uv`"),
        ("{\"positions\": [0, 0, 1e999, 0, 0, 1], \"triangles\": [0, 1, 2]}", "number out of range"),
        ("{\"triangles\": [0, 1, 2]}", "missing field `positions`"),
        ("[1, 2]", "invalid type"),
        ("{\"positions\": [0, 0, 1, 0, 0], \"triangles\": [0, 1, 2]}", "length 5 is odd"),
        ("{\"positions\": [0, 0, 1, 0, 0, 1], \"triangles\": [0, 2, 1]}", "triangle 0 is clockwise"),
        (
            "{\"positions\": [0, 0, 1, 0, 0, 1], \"triangles\": [0, 1, 2], \"uvs\": [0, 0, 1]}",
            "uvs must hold u, v pairs",
        ),
        (
            "{\"positions\": [0, 0, 1, 0, 0, 1], \"triangles\": [0, 1, 2], \"uvs\": [0, 0]}",
            "2 numbers for 3 vertices; 6 are needed",
        ),
    ];
    for (text, expected) in cases {
        let message = read_json(text, &limits()).unwrap_err().to_string();
        assert!(message.contains(expected), "{message:?} should contain {expected:?}");
    }
    // Deep nesting is an error, not a stack overflow.
    let deep = format!("{{\"positions\": {}{}}}", "[".repeat(100_000), "]".repeat(100_000));
    assert!(read_json(&deep, &limits()).unwrap_err().to_string().contains("invalid type"));
}

#[test]
fn size_limits_apply() {
    let small = Limits { max_bytes: 10, max_vertices: 2, ..Limits::default() };
    let text = "v 0 0\nv 1 0\nv 0 1\nf 1 2 3\n";
    assert_eq!(
        read_obj(text, &small).unwrap_err(),
        ImportError::TooLarge { what: "the OBJ text", size: text.len(), limit: 10, unit: "bytes" }
    );
    let few = Limits { max_vertices: 2, ..Limits::default() };
    assert!(read_obj(text, &few)
        .unwrap_err()
        .to_string()
        .contains("the mesh has 3 vertices, more than the limit of 2"));
    let json = r#"{"positions": [0, 0, 1, 0, 0, 1], "triangles": [0, 1, 2]}"#;
    assert!(matches!(read_json(json, &few), Err(ImportError::TooLarge { .. })));
    // Writers check texture coordinates too.
    let (mesh, _) = figure();
    let error = write_obj(&mesh, Some(&[[0.0, 0.0]]), None, &limits()).unwrap_err();
    let n = mesh.vertex_count();
    assert_eq!(
        error.to_string(),
        format!("texture coordinates: 2 numbers for {n} vertices; {} are needed, a u and a v per vertex", 2 * n)
    );
    assert!(write_json(&mesh, Some(&vec![[f64::NAN, 0.0]; n]), None, None, &limits()).is_err());
    // A limit of 0 is refused, not read as "unlimited".
    let zero = Limits { max_points: 0, ..Limits::default() };
    assert_eq!(
        read_obj(text, &zero).unwrap_err().to_string(),
        "option maxPoints is 0, expected a whole number, at least 1"
    );
}

/// The grid mesh of `columns` x `rows` unit squares, each split into two triangles, with
/// coordinates that print long (thirds, shifted by 1e-7 / 3).
fn grid(columns: u32, rows: u32) -> Mesh {
    let mut positions = Vec::new();
    for j in 0..=rows {
        for i in 0..=columns {
            positions.push([(i as f64 + 1e-7) / 3.0, -(j as f64 + 1e-7) / 3.0]);
        }
    }
    let at = |i: u32, j: u32| j * (columns + 1) + i;
    let mut triangles = Vec::new();
    for j in 0..rows {
        for i in 0..columns {
            let (a, b, c, d) = (at(i, j + 1), at(i + 1, j + 1), at(i + 1, j), at(i, j));
            triangles.extend([[a, b, c], [a, c, d]]);
        }
    }
    Mesh::new(positions, triangles).unwrap()
}

#[test]
fn what_the_writers_write_the_readers_read_and_what_they_refuse_the_readers_would() {
    // One set of limits for both: a file either writes and reads back, or is refused by
    // the writer with the reader's own error.
    let mesh = grid(30, 20); // 651 vertices, 1200 triangles
    let uvs: Vec<Point> = mesh.positions().iter().map(|p| [p[0] / 7.0, p[1] / 11.0]).collect();
    let obj = write_obj(&mesh, Some(&uvs), None, &limits()).unwrap();
    let json = write_json(&mesh, Some(&uvs), None, None, &limits()).unwrap();
    for (name, limits) in [
        ("vertices", Limits { max_vertices: 650, ..limits() }),
        ("triangles", Limits { max_vertices: 599, ..limits() }),
        ("OBJ bytes", Limits { max_bytes: obj.len() - 1, ..limits() }),
        ("JSON bytes", Limits { max_bytes: json.len() - 1, ..limits() }),
        ("enough", Limits { max_vertices: 651, max_bytes: obj.len().max(json.len()), ..limits() }),
    ] {
        for (written, read) in [
            (write_obj(&mesh, Some(&uvs), None, &limits), read_obj(&obj, &limits).map(|f| f.mesh)),
            (write_json(&mesh, Some(&uvs), None, None, &limits), read_json(&json, &limits).map(|f| f.mesh)),
        ] {
            match (written, read) {
                (Ok(text), Ok(back)) => {
                    assert_eq!(back, mesh, "{name}");
                    assert!(text == obj || text == json);
                }
                (
                    Err(ImportError::TooLarge { limit: a, unit: u, .. }),
                    Err(ImportError::TooLarge { limit: b, unit: v, .. }),
                ) => {
                    assert_eq!((a, u), (b, v), "{name}")
                }
                (written, read) => panic!("{name}: written {:?}, read {:?}", written.map(|t| t.len()), read.err()),
            }
        }
    }
    assert_eq!(
        write_obj(&mesh, None, None, &Limits { max_vertices: 650, ..limits() }).unwrap_err().to_string(),
        "the mesh to write has 651 vertices, more than the limit of 650 vertices"
    );
}

#[test]
fn the_largest_mesh_within_the_default_limits_writes_within_them() {
    // 100,000 vertices at most (Limits::max_vertices); the longest numbers the writers
    // print, and the longest indices: the file stays under 32 MiB.
    let mesh = grid(399, 249); // 400 x 250 = 100,000 vertices, 198,502 triangles
    assert_eq!(mesh.vertex_count(), limits().max_vertices);
    // Rotated by 180 degrees (orientation kept) into [-2.5e-6, -1.2e-6]: 25 characters a
    // number (`-0.0000012345678901234567`), the longest the writers print.
    let k = 1.234_567_890_123_456_7e-6;
    let long = |p: &Point| [-(1.0 + p[0] / 200.0) * k, -(2.0 + p[1] / 200.0) * k];
    let positions: Vec<Point> = mesh.positions().iter().map(long).collect();
    let mesh = Mesh::new(positions, mesh.triangles().to_vec()).unwrap();
    let uvs: Vec<Point> = mesh.positions().iter().map(|p| [p[0] * 3.0, p[1] * 7.0]).collect();
    let obj = write_obj(&mesh, Some(&uvs), None, &limits()).unwrap();
    assert_eq!(obj.split_whitespace().map(str::len).max(), Some(25));
    assert!(obj.len() < limits().max_bytes, "{} bytes", obj.len());
    assert_eq!(read_obj(&obj, &limits()).unwrap().mesh, mesh);
    let json = write_json(&mesh, Some(&uvs), None, None, &limits()).unwrap();
    assert!(json.len() < obj.len());
}

#[test]
fn a_pose_with_flipped_and_collapsed_triangles_is_written_as_it_is() {
    let (mesh, uvs) = figure();
    // The pose: the rest mesh sheared, then one vertex of triangle 0 carried across the
    // opposite edge (the triangle flips) and triangle 1 squashed to a point.
    let mut pose: Vec<Point> = mesh.positions().iter().map(|p| [p[0] + 0.5 * p[1], p[1] - 3.0]).collect();
    let [a, b, c] = mesh.triangles()[0].map(|v| v as usize);
    let mid = [(pose[b][0] + pose[c][0]) / 2.0, (pose[b][1] + pose[c][1]) / 2.0];
    pose[a] = [2.0 * mid[0] - pose[a][0], 2.0 * mid[1] - pose[a][1]];
    let [d, e, f] = mesh.triangles()[1].map(|v| v as usize);
    (pose[e], pose[f]) = (pose[d], pose[d]);
    let triangles = mesh.triangles();

    let obj = write_obj_pose(&pose, triangles, Some(&uvs), None, &limits()).unwrap();
    let written: Vec<Point> = (obj.lines().filter_map(|l| l.strip_prefix("v ")))
        .map(|l| {
            let n: Vec<f64> = l.split(' ').map(|x| x.parse().unwrap()).collect();
            assert_eq!(n[2], 0.0);
            [n[0], n[1]]
        })
        .collect();
    assert_eq!(written, pose);
    assert_eq!(obj.lines().filter(|l| l.starts_with("f ")).count(), triangles.len());
    // Read back, the file is held to a rest mesh's rules.
    assert!(matches!(read_obj(&obj, &limits()), Err(ImportError::Mesh(MeshError::Clockwise { triangle: 0 }))));

    let json = write_json_pose(&pose, triangles, None, None, None, &limits()).unwrap();
    let value: serde_json::Value = serde_json::from_str(&json).unwrap();
    let numbers: Vec<f64> = value["positions"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    assert_eq!(numbers, pose.iter().flatten().copied().collect::<Vec<_>>());

    // The rest positions through the pose writers: the mesh writers' text exactly.
    assert_eq!(
        write_obj_pose(mesh.positions(), triangles, Some(&uvs), None, &limits()).unwrap(),
        write_obj(&mesh, Some(&uvs), None, &limits()).unwrap()
    );
    assert_eq!(
        write_json_pose(mesh.positions(), triangles, None, None, None, &limits()).unwrap(),
        write_json(&mesh, None, None, None, &limits()).unwrap()
    );
}

#[test]
fn a_pose_that_names_no_vertex_or_is_not_finite_is_refused() {
    let (mesh, _) = figure();
    let n = mesh.vertex_count();
    let t = mesh.triangles();
    let error = |p: &[Point], t: &[[u32; 3]]| write_obj_pose(p, t, None, None, &limits()).unwrap_err();
    let mut nan = mesh.positions().to_vec();
    nan[7][1] = f64::NAN;
    assert!(matches!(error(&nan, t), ImportError::Mesh(MeshError::NonFinitePosition { vertex: 7 })));
    let mut far = mesh.positions().to_vec();
    far[3][0] = 1e301;
    assert!(matches!(error(&far, t), ImportError::Mesh(MeshError::CoordinateOutOfRange { vertex: 3, .. })));
    let mut out = t.to_vec();
    out[5][2] = n as u32;
    assert!(matches!(error(mesh.positions(), &out), ImportError::Mesh(MeshError::IndexOutOfRange { triangle: 5, .. })));
    let mut twice = t.to_vec();
    twice[2][1] = twice[2][0];
    assert!(matches!(error(mesh.positions(), &twice), ImportError::Mesh(MeshError::RepeatedVertex { triangle: 2 })));
    assert!(matches!(error(mesh.positions(), &[]), ImportError::Mesh(MeshError::Empty)));
    assert!(write_json_pose(&nan, t, None, None, None, &limits()).is_err());
}
