//! The `akap-animation` JSON: exact round trips and every bad input refused with its error;
//! and the `akap-sprites` frame table against values worked out by hand.

use akap::animation::{
    read_animation, sprite_table, write_animation, Animation, AnimationError, Easing, Key, SpriteSheet,
};
use akap::import::mesh_file::MeshFile;
use akap::import::{ImportError, Limits};
use akap::{ErrorCode, Mesh, MeshError};
use serde_json::{json, Value};
#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

/// Numbers that print long or oddly: they must come back bit for bit.
const AWKWARD: [f64; 6] = [0.1 + 0.2, -0.0, 1e-300, 5e-324, -9.999999999999999e299, 1.0 / 3.0];

fn square() -> Animation {
    let mesh = Mesh::new(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], vec![[0, 1, 2], [0, 2, 3]]).unwrap();
    let uvs = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [1.0 / 3.0, 1.0]];
    Animation {
        mesh: MeshFile { mesh, uvs: Some(uvs), stiffness: Some(vec![1.0, 2.5]), puppet: None },
        fps: 29.97,
        keys: vec![
            Key { time: 0.0, easing: Easing::Linear, handles: vec![[0.0, 0.0], [1.0, 1.0]] },
            Key { time: 0.1 + 0.2, easing: Easing::Ease, handles: vec![[AWKWARD[0], AWKWARD[1]], [1.0, 2.0]] },
        ],
        frames: vec![
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            vec![[AWKWARD[0], AWKWARD[1]], [AWKWARD[2], AWKWARD[3]], [AWKWARD[4], AWKWARD[5]], [0.0, 1.0]],
        ],
    }
}

fn bits(points: &[[f64; 2]]) -> Vec<u64> {
    points.iter().flatten().map(|x| x.to_bits()).collect()
}

fn limits() -> Limits {
    Limits::default()
}

#[test]
fn round_trip_is_bit_for_bit() {
    let animation = square();
    let text = write_animation(&animation, &limits()).unwrap();
    let back = read_animation(&text, &limits()).unwrap();
    assert_eq!(back, animation);
    for (a, b) in back.frames.iter().zip(&animation.frames) {
        assert_eq!(bits(a), bits(b));
    }
    for (a, b) in back.keys.iter().zip(&animation.keys) {
        assert_eq!(bits(&a.handles), bits(&b.handles));
        assert_eq!(a.time.to_bits(), b.time.to_bits());
    }
    assert_eq!(back.fps.to_bits(), 29.97f64.to_bits());
    // The layout a game engine reads, field by field.
    let value: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(value["format"], "akap-animation");
    assert_eq!(value["version"], 1);
    assert_eq!(value["mesh"]["triangles"], json!([0, 1, 2, 0, 2, 3]));
    assert_eq!(value["mesh"]["positions"].as_array().unwrap().len(), 8);
    assert_eq!(value["keys"][1]["easing"], "ease");
    assert_eq!(value["frames"][1].as_array().unwrap().len(), 8);
    let at = |key: &str| text.find(&format!("\"{key}\":")).unwrap();
    let order = ["format", "version", "mesh", "fps", "keys", "frames"].map(at);
    assert!(order.windows(2).all(|w| w[0] < w[1]), "{order:?}");
    // Written again, the same text.
    assert_eq!(write_animation(&back, &limits()).unwrap(), text);
    // Without the optional parts.
    let mut plain = square();
    plain.mesh.uvs = None;
    plain.mesh.stiffness = None;
    plain.keys.clear();
    let text = write_animation(&plain, &limits()).unwrap();
    assert!(text.contains(r#""keys":[]"#) && !text.contains("uvs"));
    assert_eq!(read_animation(&text, &limits()).unwrap(), plain);
}

/// The file of `square()` with `change` applied to its JSON value.
fn edited(change: impl FnOnce(&mut Value)) -> String {
    let mut value: Value = serde_json::from_str(&write_animation(&square(), &limits()).unwrap()).unwrap();
    change(&mut value);
    value.to_string()
}

/// The error reading `text`, checked to carry `code`.
fn refused(text: &str, code: ErrorCode) -> AnimationError {
    let e = read_animation(text, &limits()).unwrap_err();
    assert_eq!(e.code(), code, "{e}");
    e
}

fn file_message(text: &str) -> String {
    match refused(text, ErrorCode::Import) {
        AnimationError::File { message } => message,
        other => panic!("expected a File error, got {other:?}"),
    }
}

#[test]
fn reader_refuses_every_bad_input() {
    // Not JSON, or not ours.
    let e = refused("{\"format\": ", ErrorCode::Import);
    assert!(matches!(e, AnimationError::Syntax { line: 1, .. }), "{e:?}");
    let mesh_file = r#"{"positions": [0,0, 1,0, 0,1], "triangles": [0,1,2]}"#;
    assert_eq!(file_message(mesh_file), "it has no \"format\": \"akap-animation\"");
    assert_eq!(
        file_message(&edited(|v| v["format"] = json!("akap-session"))),
        "its format is \"akap-session\", not \"akap-animation\""
    );
    assert_eq!(file_message(&edited(|v| v["version"] = json!(2))), "its version is 2; this reader knows version 1");
    assert_eq!(
        file_message(&edited(|v| v.as_object_mut().unwrap().remove("version").map(drop).unwrap())),
        "it has no \"version\""
    );
    // Fields: unknown, missing, of the wrong type, an unknown easing.
    for change in [
        Box::new(|v: &mut Value| v["speed"] = json!(1)) as Box<dyn FnOnce(&mut Value)>,
        Box::new(|v: &mut Value| v.as_object_mut().unwrap().remove("frames").map(drop).unwrap()),
        Box::new(|v: &mut Value| v["fps"] = json!("fast")),
        Box::new(|v: &mut Value| v["keys"][0]["easing"] = json!("bounce")),
        Box::new(|v: &mut Value| v["keys"][0]["handle"] = json!([])),
        Box::new(|v: &mut Value| v["frames"][0][0] = json!(null)),
    ] {
        let e = refused(&edited(change), ErrorCode::Import);
        assert!(matches!(e, AnimationError::Syntax { .. }), "{e:?}");
    }
    // fps.
    assert_eq!(file_message(&edited(|v| v["fps"] = json!(0.5))), "fps is 0.5, expected a number from 1 to 120");
    assert!(file_message(&edited(|v| v["fps"] = json!(121))).starts_with("fps is 121,"));
    // Keys: time order, negative time, handles of different or odd lengths, out of range.
    assert_eq!(
        file_message(&edited(|v| v["keys"][1]["time"] = json!(0))),
        "key 1 has the time 0, not after key 0's 0; keys are in order of strictly increasing time"
    );
    assert!(file_message(&edited(|v| v["keys"][0]["time"] = json!(-1))).starts_with("key 0 has the time -1,"));
    assert_eq!(
        file_message(&edited(|v| v["keys"][1]["handles"] = json!([0, 0]))),
        "key 1 has 2 numbers of handles and key 0 has 4; every key holds the same handles"
    );
    assert_eq!(
        file_message(&edited(|v| v["keys"][0]["handles"] = json!([0, 0, 1]))),
        "key 0's handles has 3 numbers; x, y pairs need an even count"
    );
    assert!(file_message(&edited(|v| v["keys"][0]["handles"][1] = json!(1e301))).contains("at index 1"));
    // Frames: none, a wrong count, a number beyond the coordinate limit (1e300).
    assert_eq!(file_message(&edited(|v| v["frames"] = json!([]))), "0 frames; an animation has from 1 to 100000");
    assert_eq!(
        file_message(&edited(|v| v["frames"][1].as_array_mut().unwrap().truncate(6))),
        "frame 1 has 6 numbers; 8 are needed, x and y of each of the mesh's 4 vertices"
    );
    assert_eq!(
        file_message(&edited(|v| v["frames"][0][5] = json!(-1.5e300))),
        "frame 0 has -1.5e300 at index 5; positions are finite numbers within ±1e300"
    );
    // The mesh, with the mesh files' own errors and codes.
    let e = refused(&edited(|v| v["mesh"]["triangles"] = json!([0, 2, 1, 0, 3, 2])), ErrorCode::InvalidMesh);
    assert!(matches!(e, AnimationError::Mesh(ImportError::Mesh(MeshError::Clockwise { .. }))), "{e:?}");
    let e = refused(&edited(|v| v["mesh"]["uvs"] = json!([0, 0])), ErrorCode::Import);
    assert!(matches!(e, AnimationError::Mesh(ImportError::TextureCoordinates { .. })), "{e:?}");
    // Size.
    let small = Limits { max_bytes: 100, ..limits() };
    let text = write_animation(&square(), &limits()).unwrap();
    let e = read_animation(&text, &small).unwrap_err();
    assert!(matches!(e, AnimationError::TooLarge { limit: 100, .. }), "{e:?}");
    assert_eq!(e.code(), ErrorCode::Limit);
    assert!(matches!(write_animation(&square(), &small), Err(AnimationError::TooLarge { .. })));
}

#[test]
fn writer_refuses_what_the_reader_would() {
    let invalid = |animation: Animation| {
        let e = write_animation(&animation, &limits()).unwrap_err();
        assert_eq!(e.code(), ErrorCode::InvalidArgument, "{e}");
        assert!(matches!(e, AnimationError::Invalid { .. }), "{e:?}");
        e.to_string()
    };
    let mut a = square();
    a.fps = f64::NAN;
    assert_eq!(invalid(a), "fps is NaN, expected a number from 1 to 120");
    let mut a = square();
    a.keys.swap(0, 1);
    assert!(invalid(a).contains("strictly increasing time"));
    let mut a = square();
    a.frames[1].pop();
    assert!(invalid(a).starts_with("frame 1 has 6 numbers"));
    let mut a = square();
    a.frames[0][0][0] = f64::INFINITY;
    assert!(invalid(a).starts_with("frame 0 has inf at index 0"));
    let mut a = square();
    a.frames.clear();
    assert!(invalid(a).starts_with("0 frames"));
    let mut a = square();
    a.mesh.stiffness = Some(vec![1.0]);
    let e = write_animation(&a, &limits()).unwrap_err();
    assert!(matches!(e, AnimationError::Mesh(ImportError::Stiffness { .. })), "{e:?}");
}

#[test]
fn sprite_table_matches_its_layout() {
    let sheet = SpriteSheet { frame_width: 64, frame_height: 48, columns: 4, frame_count: 10, fps: 30.0 };
    let value: Value = serde_json::from_str(&sprite_table(&sheet, &limits()).unwrap()).unwrap();
    // 10 frames in rows of 4: 3 rows; the sheet 4 * 64 by 3 * 48.
    assert_eq!(value["format"], "akap-sprites");
    assert_eq!(value["version"], 1);
    assert_eq!((value["frameWidth"].as_u64(), value["frameHeight"].as_u64()), (Some(64), Some(48)));
    assert_eq!((value["columns"].as_u64(), value["rows"].as_u64()), (Some(4), Some(3)));
    assert_eq!(value["fps"].as_f64(), Some(30.0));
    assert_eq!(value["size"], json!({"w": 256, "h": 144}));
    let frames = value["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 10);
    // At 30 fps frames end at 33.3, 66.7, 100, ... ms, rounded: 33, 67, 100, 133, 167, 200,
    // 233, 267, 300, 333.
    let ends = [33, 67, 100, 133, 167, 200, 233, 267, 300, 333];
    let mut start = 0;
    for (i, frame) in frames.iter().enumerate() {
        let (column, row) = (i % 4, i / 4);
        let expected = json!({"x": column * 64, "y": row * 48, "w": 64, "h": 48, "duration": ends[i] - start});
        assert_eq!(frame, &expected, "frame {i}");
        start = ends[i];
    }
    assert_eq!(frames[9], json!({"x": 64, "y": 96, "w": 64, "h": 48, "duration": 33}));

    let bad = |sheet: SpriteSheet| sprite_table(&sheet, &limits()).unwrap_err();
    assert_eq!(bad(SpriteSheet { columns: 0, ..sheet }).to_string(), "columns is 0; it must be at least 1");
    assert_eq!(bad(SpriteSheet { frame_count: 0, ..sheet }).code(), ErrorCode::InvalidArgument);
    assert_eq!(bad(SpriteSheet { fps: 0.0, ..sheet }).code(), ErrorCode::InvalidArgument);
    // 4 * 1100 by 3 * 1100 pixels: 14.52 million... within 4096 * 4096; 4 * 2000 by 3 * 2000 is not.
    assert!(sprite_table(&SpriteSheet { frame_width: 1100, frame_height: 1100, ..sheet }, &limits()).is_ok());
    let e = bad(SpriteSheet { frame_width: 2000, frame_height: 2000, ..sheet });
    assert!(matches!(e, AnimationError::TooLarge { size: 48_000_000, .. }), "{e:?}");
    assert_eq!(e.code(), ErrorCode::Limit);
    let e = bad(SpriteSheet { frame_width: u32::MAX, frame_height: u32::MAX, columns: u32::MAX, ..sheet });
    assert_eq!(e.code(), ErrorCode::Limit);
}

#[test]
fn the_readmes_example_reads() {
    let readme = include_str!("../docs/formats.md");
    let section = &readme[readme.find("- **`akap-animation` JSON**").unwrap()..];
    let start = section.find("```json").unwrap() + "```json".len();
    let text = &section[start..start + section[start..].find("```").unwrap()];
    let animation = read_animation(text, &limits()).unwrap();
    assert_eq!((animation.mesh.mesh.vertex_count(), animation.fps), (3, 30.0));
    assert_eq!(animation.keys[1].easing, Easing::Ease);
    assert_eq!(animation.frames[1][0], [0.0125, 0.025]);
}
