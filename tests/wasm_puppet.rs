//! `importPuppet` and `importImagePuppet` as JavaScript sees them (run with `wasm-pack test
//! --node`): the names the issue fixes, the parts' paths as `importSvgPaths` gives them,
//! options read by the one reader.

use akap::wasm::{import_image_puppet, import_puppet, import_svg_paths, BindingError};
use js_sys::{Array, Float64Array, Reflect, Uint32Array, Uint8Array};
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::wasm_bindgen_test as test;

const LAYERED: &str = include_str!("fixtures/svg/layered-puppet.svg");

fn get(value: &JsValue, key: &str) -> JsValue {
    Reflect::get(value, &key.into()).unwrap()
}

fn options(json: &str) -> JsValue {
    js_sys::JSON::parse(json).unwrap()
}

/// The code of the JavaScript `Error` a refused call throws, and its message.
fn refused(result: Result<impl Sized, BindingError>) -> (String, String) {
    let Err(e) = result else { panic!("expected an error") };
    let value = JsValue::from(e);
    let error: &js_sys::Error = value.dyn_ref().expect("a JavaScript Error");
    (get(&value, "code").as_string().unwrap(), String::from(error.message()))
}

#[test]
fn a_puppet_has_the_names_the_issue_fixes() {
    let puppet: JsValue = import_puppet(LAYERED.into(), options(r#"{"vertices": 1000}"#)).unwrap().into();
    let positions: Float64Array = get(&puppet, "positions").dyn_into().unwrap();
    let triangles: Uint32Array = get(&puppet, "triangles").dyn_into().unwrap();
    assert_eq!(triangles.length() % 3, 0);
    let vertices = positions.length() / 2;
    assert!(triangles.to_vec().iter().all(|&v| v < vertices));
    let parts: Array = get(&puppet, "parts").dyn_into().unwrap();
    let names: Vec<String> = parts.iter().map(|p| get(&p, "name").as_string().unwrap()).collect();
    assert_eq!(names, ["Torso", "Head", "Arm", "Hat"]);
    let mut count = 0;
    for (k, part) in parts.iter().enumerate() {
        assert_eq!(get(&part, "depth").as_f64(), Some(k as f64));
        let own: Uint32Array = get(&part, "triangles").dyn_into().unwrap();
        assert!(own.to_vec().iter().all(|&t| t < triangles.length() / 3));
        count += own.length();
    }
    assert_eq!(count, triangles.length() / 3, "every triangle in one part");
    let joints: Array = get(&puppet, "joints").dyn_into().unwrap();
    let mut pairs: Vec<Vec<f64>> = joints
        .iter()
        .map(|j| {
            let point: Array = get(&j, "point").dyn_into().unwrap();
            assert_eq!(point.length(), 2);
            assert!(point.iter().all(|x| x.as_f64().is_some_and(f64::is_finite)));
            let parts: Array = get(&j, "parts").dyn_into().unwrap();
            parts.iter().map(|p| p.as_f64().unwrap()).collect()
        })
        .collect();
    pairs.sort_by(|a, b| a.partial_cmp(b).unwrap());
    assert_eq!(pairs, [[1.0, 0.0], [2.0, 0.0]]);
    assert_eq!(Array::from(&get(&puppet, "skipped")).length(), 0);
    // The parts' paths together are the document's, in the form importSvgPaths gives.
    let all = import_svg_paths(LAYERED.into(), JsValue::UNDEFINED).unwrap();
    let json = |v: &JsValue| {
        // Float64Arrays as plain arrays, so that JSON compares them.
        let plain = js_sys::Function::new_with_args(
            "v",
            "return JSON.stringify(v, (k, x) => x instanceof Float64Array ? Array.from(x) : x)",
        );
        plain.call1(&JsValue::NULL, v).unwrap().as_string().unwrap()
    };
    let joined = Array::new();
    for part in parts.iter() {
        for path in Array::from(&get(&part, "paths")).iter() {
            joined.push(&path);
        }
    }
    assert_eq!(json(&joined), json(&all));
}

#[test]
fn puppet_options_are_read_by_the_one_reader() {
    let (code, message) = refused(import_puppet(LAYERED.into(), options(r#"{"vertice": 1000}"#)));
    assert_eq!(code, "invalid-option");
    assert!(message.contains("unknown puppet import option `vertice`"), "{message}");
    assert!(message.contains("vertices"), "{message}");
    let (code, message) = refused(import_puppet(LAYERED.into(), options(r#"{"vertices": 2}"#)));
    assert_eq!(code, "invalid-option");
    assert!(message.contains("option vertices is 2"), "{message}");
    let (code, _) = refused(import_puppet(LAYERED.into(), options(r#"{"strokes": "yes"}"#)));
    assert_eq!(code, "invalid-option");
    let (code, message) = refused(import_puppet("<html/>".into(), JsValue::UNDEFINED));
    assert_eq!(code, "import");
    assert!(message.contains("not <svg>"), "{message}");
    let (code, _) = refused(import_puppet(3.into(), JsValue::UNDEFINED));
    assert_eq!(code, "invalid-argument");
}

#[test]
fn an_image_puppet_has_a_part_per_region() {
    let (w, h) = (20usize, 10usize);
    let mut rgba = vec![0u8; 4 * w * h];
    for (x0, s) in [(1, 6), (12, 5)] {
        for y in 2..2 + s {
            for x in x0..x0 + s {
                rgba[4 * (y * w + x) + 3] = 255;
            }
        }
    }
    let pixels: JsValue = Uint8Array::from(rgba.as_slice()).into();
    let puppet: JsValue = import_image_puppet(
        pixels,
        (w as u32).into(),
        (h as u32).into(),
        options(r#"{"minArea": 1, "vertices": 100}"#),
    )
    .unwrap()
    .into();
    let parts: Array = get(&puppet, "parts").dyn_into().unwrap();
    let names: Vec<String> = parts.iter().map(|p| get(&p, "name").as_string().unwrap()).collect();
    assert_eq!(names, ["Part 1", "Part 2"]);
    assert_eq!(Array::from(&get(&puppet, "joints")).length(), 0);
    assert!(parts.iter().all(|p| Array::from(&get(&p, "paths")).length() == 0));
}
