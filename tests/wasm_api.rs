//! The JavaScript bindings, called from Rust inside wasm (run with `wasm-pack test --node`):
//! results match the geometry and every bad input becomes a JavaScript Error, not a panic.

use akap::wasm::{default_shape, triangulate_outline, BindingError, JsMesh};
use js_sys::{Array, Float64Array, Reflect, Uint32Array};
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::wasm_bindgen_test as test;

fn options(json: &str) -> JsValue {
    js_sys::JSON::parse(json).unwrap()
}

fn f64s(values: &[f64]) -> JsValue {
    Float64Array::from(values).into()
}

fn u32s(values: &[u32]) -> JsValue {
    Uint32Array::from(values).into()
}

/// A JavaScript value made by running `body` (a function body returning it).
fn js(body: &str) -> JsValue {
    js_sys::Function::new_no_args(body).call0(&JsValue::NULL).unwrap()
}

/// The message of the JavaScript `Error` a refused call throws, after checking that the
/// `Error` carries the Rust error's code and message.
fn message(result: Result<impl Sized, BindingError>) -> String {
    let Err(e) = result else { panic!("expected an error") };
    let (code, text) = (e.code(), e.message().to_owned());
    let value = JsValue::from(e);
    let error: &js_sys::Error = value.dyn_ref().expect("a JavaScript Error");
    assert_eq!(Reflect::get(&value, &"code".into()).unwrap().as_string().as_deref(), Some(code.as_str()));
    assert_eq!(String::from(error.message()), text);
    text
}

#[test]
fn square_with_hole_covers_its_area() {
    let outer = [0.0, 0.0, 3.0, 0.0, 3.0, 3.0, 0.0, 3.0];
    let holes = Array::of1(&Float64Array::from(&[1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0, 1.0][..]));
    let mesh =
        triangulate_outline(f64s(&outer), holes.into(), options(r#"{"targetEdgeLength": 0.25, "minAngle": 28}"#))
            .unwrap();
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
    let mesh = triangulate_outline(outer.into(), holes, JsValue::UNDEFINED).unwrap();
    assert!(mesh.triangle_count() > 100);
}

#[test]
fn bad_input_becomes_a_javascript_error() {
    let square = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
    let cases: Vec<(Result<JsMesh, BindingError>, &str)> = vec![
        (triangulate_outline(f64s(&[0.0, 0.0, 1.0, 0.0]), JsValue::UNDEFINED, JsValue::UNDEFINED), "at least 3"),
        (
            triangulate_outline(f64s(&[0.0, 0.0, 1.0, f64::NAN, 0.0, 1.0]), JsValue::UNDEFINED, JsValue::UNDEFINED),
            "not a finite",
        ),
        (
            triangulate_outline(
                f64s(&[0.0, 0.0, 1.0, 1.0, 1.0, 0.0, 0.0, 1.0]),
                JsValue::UNDEFINED,
                JsValue::UNDEFINED,
            ),
            "intersects itself",
        ),
        (
            triangulate_outline(f64s(&square), JsValue::UNDEFINED, options(r#"{"maxArae": 1}"#)),
            "unknown triangulation option",
        ),
        (triangulate_outline(f64s(&square), JsValue::UNDEFINED, options(r#"{"minAngle": 50}"#)), "minAngle"),
        (triangulate_outline(f64s(&square), "nope".into(), JsValue::UNDEFINED), "outline.holes must be an array"),
        (
            triangulate_outline(
                f64s(&square),
                JsValue::UNDEFINED,
                options(r#"{"targetEdgeLength": 0.0001, "maxVertices": 100}"#),
            ),
            "more than 100 vertices",
        ),
        (JsMesh::new(f64s(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0]), u32s(&[0, 2, 1])), "counter-clockwise"),
        (JsMesh::new(f64s(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0]), u32s(&[0, 1, 3])), "refers to vertex 3"),
    ];
    for (result, expected) in cases {
        let text = message(result);
        assert!(text.contains(expected), "{text:?} should mention {expected:?}");
    }
    let mesh = JsMesh::new(f64s(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0]), u32s(&[0, 1, 2])).unwrap();
    assert!(message(mesh.neighbors(3.into())).contains("out of range"));
    assert_eq!(mesh.neighbors(0.into()).unwrap(), vec![1, 2]);
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
        let mut deformer = JsDeformer::new(f64s(&positions), u32s(&triangles), options(json)).unwrap();
        let expected = if json.contains("arap") { "arap" } else { "akap" };
        assert_eq!(deformer.method(), expected);
        deformer.set_handles(u32s(&[0, 4, 3, 7])).unwrap();
        // A translation of every handle moves the whole strip rigidly.
        deformer.step(f64s(&[0.5, 0.25, 0.5, 0.25, 0.5, 0.25, 0.5, 0.25])).unwrap();
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
        (r#"{"method": "arap", "iterations": 1001}"#, "from 1 to 1000 per step"),
        (r#"{"itterations": 5}"#, "unknown deformer option"),
    ];
    for (json, expected) in cases {
        let text = message(JsDeformer::new(f64s(&positions), u32s(&triangles), options(json)));
        assert!(text.contains(expected), "{text:?} should mention {expected:?}");
    }
    let mut deformer = JsDeformer::new(f64s(&positions), u32s(&triangles), options(r#"{"method": "arap"}"#)).unwrap();
    deformer.set_options(options(r#"{"iterations": 3}"#)).unwrap();
    assert!(message(deformer.set_options(options(r#"{"method": "akap", "lambda": "big"}"#))).contains("lambda"));
    assert_eq!(deformer.method(), "arap", "a refused switch changes nothing");
    deformer.set_options(options(r#"{"method": "akap"}"#)).unwrap();
    assert_eq!(deformer.method(), "akap");
}

#[test]
fn arguments_of_the_wrong_type_are_refused_with_their_name() {
    use akap::wasm::{builtin_shape, import_svg, mesh_from_json, mesh_from_obj, JsDeformer};
    // These used to be copied by the generated glue as whatever they were (a number as a
    // string's bytes, a string as an array's elements) or to trap the instance.
    let text = message(builtin_shape(42.into()));
    assert!(text.contains("the shape's name must be a string, not the number 42"), "{text}");
    assert!(
        message(import_svg(true.into(), JsValue::UNDEFINED)).contains("the SVG text must be a string, not a boolean")
    );
    assert!(message(mesh_from_obj(1.into())).contains("the OBJ text must be a string, not the number 1"));
    assert!(message(mesh_from_json(1.into())).contains("the JSON text must be a string"));
    let positions = f64s(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0]);
    assert!(message(JsMesh::new("0,0,1,0,0,1".into(), u32s(&[0, 1, 2])))
        .contains("positions must be a Float64Array, not a string"));
    assert!(message(JsMesh::new(positions.clone(), js("return [0, 1, 2]")))
        .contains("triangles must be a Uint32Array, not an array"));
    let mut deformer = JsDeformer::new(positions, u32s(&[0, 1, 2]), JsValue::UNDEFINED).unwrap();
    assert!(message(deformer.set_handles(js("return [NaN]"))).contains("vertices must be a Uint32Array"));
    assert!(message(deformer.step(js("return 'ab'"))).contains("velocities must be a Float64Array, not a string"));
}

#[test]
fn exceptions_thrown_while_reading_arguments_become_errors_and_leave_the_instance_whole() {
    use akap::wasm::JsDeformer;
    let positions = f64s(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
    let triangles = u32s(&[0, 1, 3, 0, 3, 2]);
    let mut deformer = JsDeformer::new(positions.clone(), triangles.clone(), JsValue::UNDEFINED).unwrap();
    deformer.set_handles(u32s(&[0, 3])).unwrap();
    let getter = js("return { get lambda() { throw new Error('getter says no') } }");
    let keys = js("return new Proxy({}, { ownKeys() { throw new Error('no keys') } })");
    let array = js("return new Proxy(new Float64Array(4), { get() { throw new Error('no elements') } })");
    for _ in 0..5000 {
        assert!(message(deformer.set_options(getter.clone())).contains("getter says no"));
        assert!(message(deformer.set_options(keys.clone())).contains("no keys"));
        assert!(message(deformer.step(array.clone())).contains("velocities could not be read"));
        assert!(message(triangulate_outline(positions.clone(), JsValue::UNDEFINED, keys.clone())).contains("no keys"));
    }
    // The object that was called still works, and matches one that never saw bad input.
    deformer.step(f64s(&[0.0, 0.0, 0.1, 0.05])).unwrap();
    let mut fresh = JsDeformer::new(positions, triangles, JsValue::UNDEFINED).unwrap();
    fresh.set_handles(u32s(&[0, 3])).unwrap();
    fresh.step(f64s(&[0.0, 0.0, 0.1, 0.05])).unwrap();
    assert_eq!(deformer.positions(), fresh.positions());
}

#[test]
fn careless_callers_get_errors_in_their_own_numbers_and_never_nan() {
    use akap::wasm::{mesh_to_obj, texture_coordinates, JsDeformer, JsPointMapper};
    // A bow-tie: two triangles sharing only vertex 0.
    let bow_tie = JsMesh::new(f64s(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0, -1.0, 0.0, 0.0, -1.0]), u32s(&[0, 1, 2, 0, 3, 4]));
    assert!(message(bow_tie).starts_with("vertex 0 joins 2 fans of triangles"));
    let square = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
    let triangles = [0, 1, 2, 0, 2, 3];
    for lambda in ["1e308", "1e-300"] {
        let text =
            message(JsDeformer::new(f64s(&square), u32s(&triangles), options(&format!(r#"{{"lambda": {lambda}}}"#))));
        assert_eq!(text, format!("option lambda is {lambda}, expected a number from 1e-6 to 1e10"));
    }
    let mut deformer = JsDeformer::new(f64s(&square), u32s(&triangles), JsValue::UNDEFINED).unwrap();
    // 6 numbers where 4 vertices need 8.
    assert_eq!(
        message(deformer.set_positions(f64s(&square[..6]))),
        "positions has 6 numbers, expected 8 (2 for each of the 4 vertices)"
    );
    deformer.set_positions(f64s(&[0.5; 8])).unwrap();
    let metrics = deformer.metrics().unwrap();
    let angle = Reflect::get(&metrics, &"angleDistortion".into()).unwrap().as_f64().unwrap();
    assert_eq!(angle, f64::INFINITY);
    let mapper = JsPointMapper::new(f64s(&square), u32s(&triangles), f64s(&[0.5, 0.5])).unwrap();
    let mut deformed = square;
    deformed[5] = f64::NAN;
    assert_eq!(message(mapper.map(f64s(&deformed))), "deformed position 2 has a value that is not a finite number");
    assert_eq!(
        message(texture_coordinates(f64s(&[1e300, 0.0]), 1e-10.into(), 1.0.into())),
        "the texture coordinate of position 0 comes out beyond the range of double precision (not a finite number)"
    );
    // 2 x 50,001 vertices: two over the limit; the binding refuses the positions before
    // building the mesh (the writers' own check is tested natively).
    let (mut positions, mut strip) = (Vec::new(), Vec::new());
    for i in 0..50_001u32 {
        positions.extend([f64::from(i), 0.0, f64::from(i), 1.0]);
    }
    for i in 0..50_000u32 {
        strip.extend([2 * i, 2 * i + 2, 2 * i + 3, 2 * i, 2 * i + 3, 2 * i + 1]);
    }
    assert_eq!(
        message(mesh_to_obj(f64s(&positions), u32s(&strip), JsValue::UNDEFINED, JsValue::UNDEFINED)),
        "the mesh has 100002 vertices (200004 numbers), more than the limit of 100000 vertices"
    );
}

#[test]
fn every_code_reaches_javascript_with_its_message() {
    use akap::deform::DeformError;
    use akap::sparse::{FactorError, Numeric, Ordering, Symbolic};
    use akap::{ErrorCode, TriangulationError};
    // The codes no binding call can produce on purpose, from real Rust errors: an
    // indefinite matrix's failed factorisation (as a deformer's step reports it), memory
    // running short, and a bug.
    let mut a = sprs::TriMat::new((2, 2));
    for (i, j, v) in [(0, 0, 1.0), (1, 0, 2.0), (0, 1, 2.0), (1, 1, 1.0)] {
        a.add_triplet(i, j, v);
    }
    let a = a.to_csc::<usize>();
    let symbolic = std::sync::Arc::new(Symbolic::analyse(a.view(), &Ordering::Natural).unwrap());
    let factor = Numeric::factor(symbolic, a.view()).unwrap_err();
    let cases: [(BindingError, &str); 3] = [
        (DeformError::from(factor).into(), "not-positive-definite"),
        (DeformError::OutOfMemory { bytes: 3_000_000 }.into(), "out-of-memory"),
        (TriangulationError::Internal { message: "spade said no".into() }.into(), "internal"),
    ];
    for (error, code) in cases {
        assert_eq!(error.code().as_str(), code);
        let text = message(Err::<(), _>(error));
        assert!(!text.is_empty());
    }
    assert_eq!(
        message(Err::<(), BindingError>(DeformError::from(FactorError::OutOfMemory { bytes: 1 }).into())),
        "the step failed, the mesh may have collapsed triangles: out of memory: the factor needs 1 MB more"
    );
    // Every code converts, and the `Error`'s `code` is its own property, defined without
    // running a setter a page may have put on `Error.prototype`.
    js("Object.defineProperty(Error.prototype, 'code', { set() { throw new Error('setter ran') }, configurable: true })");
    for code in ErrorCode::ALL {
        let value = JsValue::from(BindingError::new(code, "words"));
        let own =
            Reflect::get_own_property_descriptor(value.unchecked_ref::<js_sys::Object>(), &"code".into()).unwrap();
        assert_eq!(Reflect::get(&own, &"value".into()).unwrap().as_string().as_deref(), Some(code.as_str()));
        assert_eq!(Reflect::get(&own, &"enumerable".into()).unwrap().as_bool(), Some(true));
        assert_eq!(String::from(value.unchecked_ref::<js_sys::Error>().message()), "words");
    }
    js("delete Error.prototype.code");
}

#[test]
fn a_step_without_foldovers_reports_its_plain_steps_and_refuses_bad_input_as_errors() {
    use akap::wasm::JsDeformer;
    // One triangle, a handle on every vertex, MLS: the apex pushed down through the base by
    // 3 is stopped at 2^-16 above it, after 1/4, 1/16 and 1365/4096 of a sixteenth of the
    // push (tests/foldover.rs derives these by hand).
    let (positions, triangles) = (f64s(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0]), u32s(&[0, 1, 2]));
    let mut deformer = JsDeformer::new(positions, triangles, options(r#"{"method": "mls"}"#)).unwrap();
    deformer.set_handles(u32s(&[0, 1, 2])).unwrap();
    let push = f64s(&[0.0, 0.0, 0.0, 0.0, 0.0, -3.0]);
    let getter = js("return { get maxSplits() { throw new Error('getter says no') } }");
    let array = js("return new Proxy(new Float64Array(6), { get() { throw new Error('no elements') } })");
    assert!(
        message(deformer.step_without_foldovers(push.clone(), getter, JsValue::UNDEFINED)).contains("getter says no")
    );
    assert!(message(deformer.step_without_foldovers(array, JsValue::UNDEFINED, JsValue::UNDEFINED))
        .contains("velocities could not be read"));
    let text =
        message(deformer.step_without_foldovers(push.clone(), options(r#"{"clampTrials": 31}"#), JsValue::UNDEFINED));
    assert_eq!(text, "option clampTrials is 31, expected a whole number from 0 to 30");
    assert_eq!(deformer.positions(), [0.0, 0.0, 1.0, 0.0, 0.0, 1.0]);

    let report = deformer.step_without_foldovers(push, JsValue::UNDEFINED, JsValue::UNDEFINED).unwrap();
    let get = |key: &str| Reflect::get(&report, &key.into()).unwrap();
    let steps: Vec<f64> = get("steps").dyn_into::<Array>().unwrap().iter().map(|s| s.as_f64().unwrap()).collect();
    assert_eq!(steps, [0.25, 0.0625, 0.0625 * 1365.0 / 4096.0]);
    assert_eq!(get("clamped").as_bool(), Some(true));
    assert_eq!(get("attempts").as_f64(), Some(19.0));
    assert_eq!(deformer.positions(), [0.0, 0.0, 1.0, 0.0, 0.0, 2f64.powi(-16)]);
}

#[test]
fn bones_through_the_bindings_are_checked_and_refused_as_errors() {
    use akap::wasm::JsDeformer;
    // A 4 x 1 strip of unit squares; a bone along its middle from x = 0.5 to x = 3.5.
    let mesh = akap::shapes::grid_mesh(4, 1);
    let positions = f64s(mesh.positions().as_flattened());
    let triangles = u32s(mesh.triangles().as_flattened());
    let mut deformer = JsDeformer::new(positions.clone(), triangles.clone(), options("{}")).unwrap();
    assert!(deformer.has_bones());
    let locate = |x: f64, y: f64| {
        mesh.triangles()
            .iter()
            .enumerate()
            .find_map(|(t, c)| {
                let [a, b, d] = c.map(|v| mesh.positions()[v as usize]);
                let area = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
                let wa = ((b[0] - x) * (d[1] - y) - (b[1] - y) * (d[0] - x)) / area;
                let wb = ((d[0] - x) * (a[1] - y) - (d[1] - y) * (a[0] - x)) / area;
                let w = [wa, wb, 1.0 - wa - wb];
                w.iter().all(|&v| v >= 0.0).then_some((t as u32, w))
            })
            .unwrap()
    };
    let (a, b) = (locate(0.5, 0.4), locate(3.5, 0.6));
    let text = message(deformer.set_bones(u32s(&[a.0, b.0]), f64s(&[a.1, b.1].concat()[..5])));
    assert_eq!(text, "barycentric has 5 numbers, not 3 for each bone end");
    let text = message(deformer.set_bones(u32s(&[a.0, a.0]), f64s(&[a.1, a.1].concat())));
    assert_eq!(text, "bone 0 cannot be used: its ends are at one point");
    deformer.set_bones(u32s(&[a.0, b.0]), f64s(&[a.1, b.1].concat())).unwrap();
    // MLS has none.
    let mut mls = JsDeformer::new(positions, triangles, options(r#"{"method": "mls"}"#)).unwrap();
    assert!(!mls.has_bones());
    let text = message(mls.set_bones(u32s(&[a.0, b.0]), f64s(&[a.1, b.1].concat())));
    assert_eq!(text, "method mls has no bones; choose \"akap\" or \"arap\" for it");
}
