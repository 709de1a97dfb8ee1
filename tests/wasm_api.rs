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
