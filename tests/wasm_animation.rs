//! The animation bindings called inside wasm: bad arguments refused with codes (never a
//! panic), the encoder's life cycle, and the JSON round trip through JavaScript objects.

use akap::wasm::{
    animation_from_json, animation_to_json, sprite_sheet_table, zip_files, BindingError, JsAnimationEncoder,
};
use js_sys::{Array, Float64Array, Reflect, Uint32Array, Uint8Array, Uint8ClampedArray};
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::wasm_bindgen_test as test;

fn js(body: &str) -> JsValue {
    js_sys::Function::new_no_args(body).call0(&JsValue::NULL).unwrap()
}

/// The code of the JavaScript `Error` a refused call throws, with its message.
fn code(result: Result<impl Sized, BindingError>) -> (String, String) {
    let Err(e) = result else { panic!("expected an error") };
    let value = JsValue::from(e);
    let error: &js_sys::Error = value.dyn_ref().expect("a JavaScript Error");
    let code = Reflect::get(&value, &"code".into()).unwrap().as_string().unwrap();
    (code, String::from(error.message()))
}

fn pixels(n: usize) -> JsValue {
    Uint8Array::from(vec![200u8; n].as_slice()).into()
}

#[test]
fn encoder_checks_its_arguments() {
    let new = |format: &str, w: f64, h: f64, options: &str| {
        JsAnimationEncoder::new(js(&format!("return {format}")), w.into(), h.into(), js(&format!("return {options}")))
    };
    assert_eq!(code(new("'webp'", 2.0, 2.0, "undefined")).0, "invalid-argument");
    assert_eq!(code(new("'gif'", 0.0, 2.0, "undefined")).0, "invalid-argument");
    assert_eq!(code(new("'gif'", 2.5, 2.0, "undefined")).0, "invalid-argument");
    assert_eq!(code(new("'gif'", -1.0, 2.0, "undefined")).0, "invalid-argument");
    assert_eq!(code(new("'apng'", 5000.0, 5000.0, "undefined")).0, "limit");
    assert_eq!(code(new("'gif'", 2.0, 2.0, "{ loops: true }")).0, "invalid-option");
    assert_eq!(code(new("'gif'", 2.0, 2.0, "{ loop: 1 }")).0, "invalid-option");

    let mut encoder = new("'apng'", 2.0, 2.0, "{ loop: false }").unwrap();
    assert_eq!(code(encoder.finish()).1, "the animation has no frames; add at least one before finishing");
    assert_eq!(code(encoder.add_frame(pixels(15), 10.into())).0, "invalid-argument");
    assert_eq!(code(encoder.add_frame(js("return [1, 2, 3]"), 10.into())).0, "invalid-argument");
    for delay in [JsValue::from(0), JsValue::from(1.5), JsValue::from(70_000), JsValue::from_str("10")] {
        assert_eq!(code(encoder.add_frame(pixels(16), delay)).0, "invalid-argument");
    }
    assert_eq!(encoder.frame_count(), 0);
    encoder.add_frame(pixels(16), 10.into()).unwrap();
    encoder.add_frame(Uint8ClampedArray::from(vec![9u8; 16].as_slice()).into(), 20.into()).unwrap();
    assert_eq!(encoder.frame_count(), 2);
    let png = encoder.finish().unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    assert_eq!(code(encoder.finish()).1, "the animation encoder has finished; make a new one");
    assert_eq!(code(encoder.add_frame(pixels(16), 10.into())).0, "invalid-argument");
}

#[test]
fn zip_files_checks_its_entries() {
    let zip = zip_files(js("return [{ name: 'a.txt', data: new Uint8Array([104, 105]) }]")).unwrap();
    assert_eq!(zip.len(), 30 + 5 + 2 + 46 + 5 + 22);
    assert_eq!(code(zip_files(js("return 'a'"))).0, "invalid-argument");
    assert_eq!(code(zip_files(js("return [{ name: 1, data: new Uint8Array(1) }]"))).0, "invalid-argument");
    assert_eq!(code(zip_files(js("return [{ name: 'a', data: [1] }]"))).0, "invalid-argument");
    assert_eq!(code(zip_files(js("return [null]"))).0, "invalid-argument");
    let (c, message) =
        code(zip_files(js("return [{ get name() { throw new Error('boom') }, data: new Uint8Array(1) }]")));
    assert_eq!(c, "invalid-argument");
    assert!(message.contains("boom"), "{message}");
    assert!(code(zip_files(js("return [{ name: '../x', data: new Uint8Array(1) }]"))).1.contains(".."));
}

#[test]
fn animation_round_trips_through_objects() {
    let animation = js("return {
        mesh: { positions: new Float64Array([0, 0, 1, 0, 0, 1]), triangles: new Uint32Array([0, 1, 2]),
                stiffness: new Float64Array([2]) },
        fps: 12.5,
        keys: [{ time: 0, easing: 'ease', handles: new Float64Array([0.1, 0.2]) }],
        frames: [new Float64Array([0, 0, 1, 0, 0.30000000000000004, 1])],
    }");
    let text = animation_to_json(animation).unwrap();
    let back = animation_from_json(text.clone().into()).unwrap();
    let get = |v: &JsValue, k: &str| Reflect::get(v, &k.into()).unwrap();
    let mesh = get(&back, "mesh");
    assert_eq!(get(&mesh, "positions").unchecked_into::<Float64Array>().to_vec(), [0.0, 0.0, 1.0, 0.0, 0.0, 1.0]);
    assert_eq!(get(&mesh, "triangles").unchecked_into::<Uint32Array>().to_vec(), [0, 1, 2]);
    assert_eq!(get(&mesh, "stiffness").unchecked_into::<Float64Array>().to_vec(), [2.0]);
    assert!(get(&mesh, "uvs").is_undefined());
    assert_eq!(get(&back, "fps").as_f64(), Some(12.5));
    let frames: Array = get(&back, "frames").unchecked_into();
    assert_eq!(frames.get(0).unchecked_into::<Float64Array>().get_index(4), 0.1 + 0.2);
    assert_eq!(animation_to_json(back.into()).unwrap(), text);

    let bad = |body: &str| code(animation_to_json(js(body)));
    let mesh = "{ positions: new Float64Array([0, 0, 1, 0, 0, 1]), triangles: new Uint32Array([0, 1, 2]) }";
    let frame = "new Float64Array([0, 0, 1, 0, 0, 1])";
    assert_eq!(bad("return 5").0, "invalid-argument");
    assert_eq!(
        bad(&format!("return {{ mesh: {mesh}, fps: '30', keys: [], frames: [{frame}] }}")).0,
        "invalid-argument"
    );
    assert_eq!(bad(&format!("return {{ mesh: {mesh}, fps: 30, keys: [], frames: [[0, 0]] }}")).0, "invalid-argument");
    let (c, m) = bad(&format!(
        "return {{ mesh: {mesh}, fps: 30, keys: [{{ time: 0, easing: 'bounce', handles: new Float64Array(0) }}], frames: [{frame}] }}"
    ));
    assert_eq!(c, "invalid-argument");
    assert!(m.contains("easing"), "{m}");
    let clockwise = "{ positions: new Float64Array([0, 0, 0, 1, 1, 0]), triangles: new Uint32Array([0, 1, 2]) }";
    assert_eq!(bad(&format!("return {{ mesh: {clockwise}, fps: 30, keys: [], frames: [{frame}] }}")).0, "invalid-mesh");
    assert_eq!(bad(&format!("return {{ mesh: {mesh}, fps: 200, keys: [], frames: [{frame}] }}")).0, "invalid-argument");

    assert_eq!(code(animation_from_json(JsValue::from(3))).0, "invalid-argument");
    assert_eq!(code(animation_from_json("{".into())).0, "import");
    assert_eq!(code(animation_from_json(text.replace("12.5", "0.5").into())).0, "import");
}

#[test]
fn sprite_sheet_table_reads_its_layout() {
    let table =
        sprite_sheet_table(js("return { frameWidth: 4, frameHeight: 2, columns: 2, frameCount: 3, fps: 4 }")).unwrap();
    assert!(table.contains(r#""rows":2,"fps":4.0,"size":{"w":8,"h":4}"#), "{table}");
    let bad = |body: &str| code(sprite_sheet_table(js(body))).0;
    assert_eq!(bad("return { frameWidth: 4, frameHeight: 2, columns: 2, frameCount: 3 }"), "invalid-option");
    assert_eq!(
        bad("return { frameWidth: 4, frameHeight: 2, columns: 2, frameCount: 3, fps: 4, extra: 1 }"),
        "invalid-option"
    );
    assert_eq!(bad("return { frameWidth: 4.5, frameHeight: 2, columns: 2, frameCount: 3, fps: 4 }"), "invalid-option");
    assert_eq!(bad("return { frameWidth: 4, frameHeight: 2, columns: 0, frameCount: 3, fps: 4 }"), "invalid-argument");
    assert_eq!(bad("return { frameWidth: 5000, frameHeight: 5000, columns: 1, frameCount: 1, fps: 4 }"), "limit");
}
