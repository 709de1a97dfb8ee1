//! Animations out (`crate::animation`): the GIF and APNG encoder, ZIP archives of files,
//! the `akap-animation` JSON and the sprite sheet's frame table.
//!
//! Objects cross as the mesh writers' and readers' do: a mesh as `{ positions:
//! Float64Array, triangles: Uint32Array, uvs?: Float64Array, stiffness?: Float64Array }`
//! (`meshToJson`'s argument, `meshFromJson`'s result), points as `Float64Array`s of x, y
//! pairs. Fields are read with `Reflect.get` (a throwing getter becomes an error naming
//! the field) and checked by type.

use js_sys::{Array, Float64Array, Object};
use wasm_bindgen::prelude::*;

use super::error::BindingError;
use super::mesh::read_mesh;
use super::read::{self, field, optional, Options};
use super::{flat, limits, max_coordinates, max_indices, object, pairs};
use crate::animation::zip::{MAX_FILES, MAX_NAME_BYTES, MAX_ZIP_BYTES};
use crate::animation::{
    self, Animation, AnimationEncoder, AnimationError, Easing, Format, Key, SpriteSheet, MAX_FRAMES, MAX_KEYS,
};
use crate::import::mesh_file::MeshFile;

/// Animated images: `new AnimationEncoder("gif" | "apng", width, height, { loop? })`, then
/// `addFrame(rgba, delayMs)` per frame and `finish()` for the file's bytes.
#[wasm_bindgen(js_name = AnimationEncoder)]
pub struct JsAnimationEncoder {
    /// `None` once finished.
    inner: Option<AnimationEncoder>,
}

#[wasm_bindgen(js_class = AnimationEncoder)]
impl JsAnimationEncoder {
    /// An encoder of `format` (`"gif"` or `"apng"`) for frames of `width` x `height`
    /// pixels; `options`: `{ loop?: boolean }` (default true: play forever; false: once).
    #[wasm_bindgen(constructor)]
    pub fn new(
        format: JsValue,
        width: JsValue,
        height: JsValue,
        options: JsValue,
    ) -> Result<JsAnimationEncoder, BindingError> {
        let format = match format.as_string().as_deref() {
            Some("gif") => Format::Gif,
            Some("apng") => Format::Apng,
            _ => return Err(read::type_error("format", "\"gif\" or \"apng\"", &format)),
        };
        let given = Options::read(&options, "animation", &["loop"])?;
        let loop_forever = given.boolean("loop")?.unwrap_or(true);
        let width = read::count(&width, "width", u32::MAX as usize)? as u32;
        let height = read::count(&height, "height", u32::MAX as usize)? as u32;
        let encoder = AnimationEncoder::with_limits(format, width, height, loop_forever, &limits())?;
        Ok(Self { inner: Some(encoder) })
    }

    fn encoder(&mut self) -> Result<&mut AnimationEncoder, BindingError> {
        self.inner.as_mut().ok_or_else(|| AnimationError::Finished.into())
    }

    /// Encodes a frame: `rgba` (`Uint8Array` or `Uint8ClampedArray`, 4 bytes a pixel, rows
    /// from the top, as `ImageData.data`) shown for `delayMs` (a whole number from 1 to
    /// 65535).
    #[wasm_bindgen(js_name = addFrame)]
    pub fn add_frame(&mut self, rgba: JsValue, delay_ms: JsValue) -> Result<(), BindingError> {
        let encoder = self.encoder()?;
        let frame = encoder.frame_count();
        let delay = read::number(&delay_ms, "delayMs")?;
        let range = animation::DELAY_MS_RANGE;
        if !(delay.fract() == 0.0 && delay >= f64::from(*range.start()) && delay <= f64::from(*range.end())) {
            return Err(AnimationError::Delay { frame, delay_ms: delay }.into());
        }
        let rgba = read::bytes(&rgba, "the frame's pixels", 4 * limits().max_pixels)?;
        Ok(encoder.add_frame(&rgba, delay as u32)?)
    }

    /// Frames added so far.
    #[wasm_bindgen(getter, js_name = frameCount)]
    pub fn frame_count(&self) -> usize {
        self.inner.as_ref().map_or(0, AnimationEncoder::frame_count)
    }

    /// The file's bytes (a `Uint8Array`). The encoder is done after this (call `free`).
    pub fn finish(&mut self) -> Result<Vec<u8>, BindingError> {
        let encoder = self.inner.take().ok_or(AnimationError::Finished)?;
        if encoder.frame_count() == 0 {
            // Kept, so that frames can still be added.
            self.inner = Some(encoder);
            return Err(AnimationError::NoFrames.into());
        }
        Ok(encoder.finish()?)
    }
}

/// A ZIP archive (a `Uint8Array`) of `files`, `{ name: string, data: Uint8Array }[]`,
/// stored without compression in the order given.
#[wasm_bindgen(js_name = zipFiles)]
pub fn zip_files(files: JsValue) -> Result<Vec<u8>, BindingError> {
    let list = read::list(&files, "files", MAX_FILES)?;
    let mut entries = Vec::with_capacity(list.len());
    let mut total = 0u64;
    for (i, entry) in list.iter().enumerate() {
        let what = format!("files[{i}]");
        let name = read::string(&field(entry, "name", &what)?, &format!("{what}.name"), MAX_NAME_BYTES)?;
        let left = (MAX_ZIP_BYTES - total.min(MAX_ZIP_BYTES)) as usize;
        let data = read::bytes(&field(entry, "data", &what)?, &format!("{what}.data"), left)?;
        total += data.len() as u64;
        entries.push((name, data));
    }
    Ok(animation::write_zip(&entries)?)
}

/// Reads `{ positions, triangles, uvs?, stiffness? }`, a rest mesh validated.
fn read_mesh_file(value: &JsValue) -> Result<MeshFile, BindingError> {
    let what = "animation.mesh";
    let mesh = read_mesh(&field(value, "positions", what)?, &field(value, "triangles", what)?)?;
    let uvs = match optional(value, "uvs", what)? {
        Some(v) => Some(pairs(&read::float64s(&v, "animation.mesh.uvs", max_coordinates())?, "animation.mesh.uvs")?),
        None => None,
    };
    let stiffness = match optional(value, "stiffness", what)? {
        Some(v) => Some(read::float64s(&v, "animation.mesh.stiffness", max_indices())?),
        None => None,
    };
    Ok(MeshFile { mesh, uvs, stiffness })
}

/// Reads an animation object: `{ mesh, fps, keys: { time, easing, handles }[], frames:
/// Float64Array[] }`.
fn read_animation_object(value: &JsValue) -> Result<Animation, BindingError> {
    let what = "animation";
    let mesh = read_mesh_file(&field(value, "mesh", what)?)?;
    let fps = read::number(&field(value, "fps", what)?, "animation.fps")?;
    let mut keys = Vec::new();
    for (k, key) in read::list(&field(value, "keys", what)?, "animation.keys", MAX_KEYS)?.iter().enumerate() {
        let what = format!("animation.keys[{k}]");
        let time = read::number(&field(key, "time", &what)?, &format!("{what}.time"))?;
        let easing_value = field(key, "easing", &what)?;
        let easing = match easing_value.as_string().as_deref() {
            Some("linear") => Easing::Linear,
            Some("ease") => Easing::Ease,
            _ => return Err(read::type_error(&format!("{what}.easing"), "\"linear\" or \"ease\"", &easing_value)),
        };
        let handles = read::float64s(&field(key, "handles", &what)?, &format!("{what}.handles"), max_coordinates())?;
        keys.push(Key { time, easing, handles: pairs(&handles, &format!("{what}.handles"))? });
    }
    let mut frames = Vec::new();
    let frames_value = field(value, "frames", what)?;
    for (f, frame) in read::list(&frames_value, "animation.frames", MAX_FRAMES)?.iter().enumerate() {
        let what = format!("animation.frames[{f}]");
        frames.push(pairs(&read::float64s(frame, &what, max_coordinates())?, &what)?);
    }
    Ok(Animation { mesh, fps, keys, frames })
}

/// An animation as `akap-animation` JSON (version 1): `animation` is `{ mesh: {
/// positions, triangles, uvs?, stiffness? }, fps, keys: { time, easing: "linear" |
/// "ease", handles: Float64Array }[], frames: Float64Array[] }`.
#[wasm_bindgen(js_name = animationToJson)]
pub fn animation_to_json(animation: JsValue) -> Result<String, BindingError> {
    let animation = read_animation_object(&animation)?;
    Ok(animation::write_animation(&animation, &limits())?)
}

/// Reads `akap-animation` JSON into the object `animationToJson` takes.
#[wasm_bindgen(js_name = animationFromJson)]
pub fn animation_from_json(text: JsValue) -> Result<Object, BindingError> {
    let limits = limits();
    let text = read::string(&text, "the animation JSON", limits.max_bytes)?;
    let animation = animation::read_animation(&text, &limits)?;
    let file = &animation.mesh;
    let mut mesh = vec![
        ("positions", flat(file.mesh.positions()).into()),
        ("triangles", js_sys::Uint32Array::from(file.mesh.triangles().as_flattened()).into()),
    ];
    if let Some(uvs) = &file.uvs {
        mesh.push(("uvs", flat(uvs).into()));
    }
    if let Some(stiffness) = &file.stiffness {
        mesh.push(("stiffness", Float64Array::from(stiffness.as_slice()).into()));
    }
    let keys = Array::new();
    for key in &animation.keys {
        let easing = match key.easing {
            Easing::Linear => "linear",
            Easing::Ease => "ease",
        };
        let entry =
            object(&[("time", key.time.into()), ("easing", easing.into()), ("handles", flat(&key.handles).into())])?;
        keys.push(&entry);
    }
    let frames: Array = animation.frames.iter().map(|f| flat(f)).collect();
    object(&[
        ("mesh", object(&mesh)?.into()),
        ("fps", animation.fps.into()),
        ("keys", keys.into()),
        ("frames", frames.into()),
    ])
}

/// The `akap-sprites` JSON frame table of a sheet `{ frameWidth, frameHeight, columns,
/// frameCount, fps }` (every field required).
#[wasm_bindgen(js_name = spriteSheetTable)]
pub fn sprite_sheet_table(sheet: JsValue) -> Result<String, BindingError> {
    const NAMES: [&str; 5] = ["frameWidth", "frameHeight", "columns", "frameCount", "fps"];
    let given = Options::read(&sheet, "sprite sheet", &NAMES)?;
    let count = |name: &str| -> Result<u32, BindingError> {
        given
            .count(name, u32::MAX as usize)?
            .map(|n| n as u32)
            .ok_or_else(|| BindingError::option(format!("the sprite sheet needs {name}")))
    };
    let sheet = SpriteSheet {
        frame_width: count("frameWidth")?,
        frame_height: count("frameHeight")?,
        columns: count("columns")?,
        frame_count: count("frameCount")?,
        fps: given.number("fps")?.ok_or_else(|| BindingError::option("the sprite sheet needs fps"))?,
    };
    Ok(animation::sprite_table(&sheet, &limits())?)
}
