//! The JavaScript bindings, called from Rust inside wasm (run with `wasm-pack test --node`):
//! results match the geometry and every bad input becomes a JavaScript Error, not a panic.

use akap::wasm::{default_shape, triangulate_outline, JsMesh};
use js_sys::{Array, Float64Array, Reflect};
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::wasm_bindgen_test as test;

fn options(json: &str) -> JsValue {
    js_sys::JSON::parse(json).unwrap()
}

fn message(result: Result<impl Sized, wasm_bindgen::JsError>) -> String {
    let Err(e) = result else { panic!("expected an error") };
    let value = JsValue::from(e);
    let error: &js_sys::Error = value.dyn_ref().expect("a JavaScript Error");
    String::from(error.message())
}

#[test]
fn square_with_hole_covers_its_area() {
    let outer = [0.0, 0.0, 3.0, 0.0, 3.0, 3.0, 0.0, 3.0];
    let holes = Array::of1(&Float64Array::from(&[1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0, 1.0][..]));
    let mesh =
        triangulate_outline(&outer, holes.into(), options(r#"{"targetEdgeLength": 0.25, "minAngle": 28}"#)).unwrap();
    assert!((mesh.area() - 8.0).abs() < 1e-12);
    let positions = mesh.positions();
    let triangles = mesh.triangles();
    assert_eq!(positions.len(), 2 * mesh.vertex_count());
    assert_eq!(triangles.len(), 3 * mesh.triangle_count());
    for t in triangles.chunks_exact(3) {
        let p = |i: u32| [positions[2 * i as usize], positions[2 * i as usize + 1]];
        assert!(akap::geometry::triangle_area(p(t[0]), p(t[1]), p(t[2])) > 0.0);
    }
    // The two boundary loops: 4 + 4 input points, split into more boundary vertices.
    assert_eq!(mesh.boundary_edges().len() / 2, mesh.boundary_vertices().len());
}

#[test]
fn default_shape_triangulates() {
    let shape = default_shape().unwrap();
    let outer: Float64Array = Reflect::get(&shape, &"outer".into()).unwrap().dyn_into().unwrap();
    let holes = Reflect::get(&shape, &"holes".into()).unwrap();
    assert_eq!(Array::from(&holes).length(), 4);
    let mesh = triangulate_outline(&outer.to_vec(), holes, JsValue::UNDEFINED).unwrap();
    assert!(mesh.triangle_count() > 100);
}

#[test]
fn bad_input_becomes_a_javascript_error() {
    let square = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
    let cases: Vec<(Result<JsMesh, wasm_bindgen::JsError>, &str)> = vec![
        (triangulate_outline(&[0.0, 0.0, 1.0, 0.0], JsValue::UNDEFINED, JsValue::UNDEFINED), "at least 3"),
        (
            triangulate_outline(&[0.0, 0.0, 1.0, f64::NAN, 0.0, 1.0], JsValue::UNDEFINED, JsValue::UNDEFINED),
            "not a finite",
        ),
        (
            triangulate_outline(&[0.0, 0.0, 1.0, 1.0, 1.0, 0.0, 0.0, 1.0], JsValue::UNDEFINED, JsValue::UNDEFINED),
            "intersects itself",
        ),
        (
            triangulate_outline(&square, JsValue::UNDEFINED, options(r#"{"maxArae": 1}"#)),
            "unknown triangulation option",
        ),
        (triangulate_outline(&square, JsValue::UNDEFINED, options(r#"{"minAngle": 50}"#)), "minAngle"),
        (triangulate_outline(&square, "nope".into(), JsValue::UNDEFINED), "holes must be an array"),
        (
            triangulate_outline(
                &square,
                JsValue::UNDEFINED,
                options(r#"{"targetEdgeLength": 0.0001, "maxVertices": 100}"#),
            ),
            "more than 100 vertices",
        ),
        (JsMesh::new(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0], &[0, 2, 1]), "counter-clockwise"),
        (JsMesh::new(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0], &[0, 1, 3]), "refers to vertex 3"),
    ];
    for (result, expected) in cases {
        let text = message(result);
        assert!(text.contains(expected), "{text:?} should mention {expected:?}");
    }
    let mesh = JsMesh::new(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0], &[0, 1, 2]).unwrap();
    assert!(message(mesh.neighbors(3)).contains("out of range"));
    assert_eq!(mesh.neighbors(0).unwrap(), vec![1, 2]);
}

#[test]
fn deformer_methods_and_their_options() {
    use akap::wasm::JsDeformer;
    // A 3 x 1 strip of 6 squares, each split in two.
    let mut positions = Vec::new();
    for y in 0..2 {
        for x in 0..4 {
            positions.extend([f64::from(x), f64::from(y)]);
        }
    }
    let mut triangles = Vec::new();
    for x in 0..3u32 {
        triangles.extend([x, x + 1, x + 5, x, x + 5, x + 4]);
    }
    for json in [r#"{"method": "arap", "iterations": 5}"#, r#"{"method": "akap", "lambda": 50}"#, "{}"] {
        let mut deformer = JsDeformer::new(&positions, &triangles, options(json)).unwrap();
        let expected = if json.contains("arap") { "arap" } else { "akap" };
        assert_eq!(deformer.method(), expected);
        deformer.set_handles(&[0, 4, 3, 7]).unwrap();
        // A translation of every handle moves the whole strip rigidly.
        deformer.step(&[0.5, 0.25, 0.5, 0.25, 0.5, 0.25, 0.5, 0.25]).unwrap();
        for (p, q) in positions.chunks(2).zip(deformer.positions().chunks(2)) {
            assert!((q[0] - p[0] - 0.5).abs() < 1e-9 && (q[1] - p[1] - 0.25).abs() < 1e-9, "{json}: {q:?}");
        }
        let metrics = deformer.metrics().unwrap();
        let area = Reflect::get(&metrics, &"areaDistortion".into()).unwrap().as_f64().unwrap();
        assert!((area - 2.0).abs() < 1e-9);
    }
    let cases = [
        (r#"{"method": "fem"}"#, "option method"),
        (r#"{"method": "arap", "lambda": 5}"#, "applies to method \"akap\""),
        (r#"{"iterations": 5}"#, "applies to method \"arap\""),
        (r#"{"method": "arap", "iterations": 0}"#, "whole number"),
        (r#"{"method": "arap", "iterations": 2.5}"#, "whole number"),
        (r#"{"method": "arap", "iterations": 1001}"#, "from 1 to 1000 (iterations per step"),
        (r#"{"itterations": 5}"#, "unknown deformer option"),
    ];
    for (json, expected) in cases {
        let text = message(JsDeformer::new(&positions, &triangles, options(json)));
        assert!(text.contains(expected), "{text:?} should mention {expected:?}");
    }
    let mut deformer = JsDeformer::new(&positions, &triangles, options(r#"{"method": "arap"}"#)).unwrap();
    deformer.set_options(options(r#"{"iterations": 3}"#)).unwrap();
    assert!(message(deformer.set_options(options(r#"{"method": "akap"}"#))).contains("chosen when the deformer"));
    assert_eq!(deformer.method(), "arap");
}
