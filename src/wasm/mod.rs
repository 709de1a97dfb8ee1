//! JavaScript bindings (wasm32 only): the one module that touches wasm-bindgen and js-sys.
//!
//! Arrays cross as typed arrays: positions as `Float64Array` with x and y interleaved,
//! triangles as `Uint32Array` index triples. Every argument is read by `read`, which
//! checks its type and size (an `Error` naming the argument otherwise) and never lets a
//! JavaScript exception unwind through Rust frames; every error becomes a JavaScript
//! `Error` with the message of the Rust error and a stable `code` ([`BindingError`], the
//! codes of [`crate::ErrorCode`]); nothing here panics on bad input. Options objects are
//! read by one reader (`read::Options`), which refuses unknown keys. The
//! TypeScript wrapper in `www/src/` gives these functions their public, documented shape.
//!
//! `mesh`: meshes, triangulation, built-in shapes; `deformer`: the deformers and their
//! options; `import`: shapes from SVG, images and mesh files, and `PointMapper`; `session`:
//! recorded sessions read, checked and written by `crate::session`; `defop`: training and
//! evaluating deformation operators (`crate::defop`); `animation`: animated GIF and APNG,
//! ZIP archives, the `akap-animation` JSON and sprite tables (`crate::animation`).

mod animation;
mod defop;
mod deformer;
mod error;
mod import;
mod mesh;
mod options;
mod puppet;
mod read;
mod session;

pub use animation::{animation_from_json, animation_to_json, sprite_sheet_table, zip_files, JsAnimationEncoder};
pub use defop::{ground_truth, simulation, JsDefOp, JsDefOpSolver, JsDefOpTrainer};
pub use deformer::{check_stiffness, deformer_orders, JsDeformer};
pub use error::BindingError;
pub use import::{
    import_image_puppet, import_puppet, import_svg, import_svg_paths, mesh_from_json, mesh_from_obj, mesh_to_json,
    mesh_to_obj, path_data, texture_coordinates, trace_image, JsMeshFile, JsPointMapper,
};
pub use mesh::{builtin_shape, builtin_shapes, default_shape, triangulate_outline, triangulate_to_vertices, JsMesh};
pub use session::{session_json, session_mesh};

use js_sys::{Array, Float64Array, Function, Object, Reflect};
use wasm_bindgen::prelude::*;

use crate::deform::STIFFNESS_RANGE;
use crate::error_code::ErrorCode;
use crate::import::Limits;
use crate::outline::Outline;

/// The limits every binding checks its inputs against: the same as the importers'.
fn limits() -> Limits {
    Limits::default()
}

/// Most numbers in a positions array: two per vertex of the largest mesh.
fn max_coordinates() -> usize {
    2 * limits().max_vertices
}

/// Most indices in a triangles array: a planar mesh has fewer than two triangles per vertex.
fn max_indices() -> usize {
    6 * limits().max_vertices
}

/// A fresh object with these properties (an `ErrorCode::Internal` error should setting one
/// ever fail).
fn object(entries: &[(&str, JsValue)]) -> Result<Object, BindingError> {
    let object = Object::new();
    for (key, value) in entries {
        Reflect::set(&object, &JsValue::from_str(key), value)
            .map_err(|_| BindingError::new(ErrorCode::Internal, format!("could not set property {key}")))?;
    }
    Ok(object)
}

fn flat(points: &[[f64; 2]]) -> Float64Array {
    Float64Array::from(points.iter().flatten().copied().collect::<Vec<f64>>().as_slice())
}

/// Pairs from a flat array of `2 n` numbers (the caller's array is named `what`).
fn pairs(values: &[f64], what: &str) -> Result<Vec<[f64; 2]>, BindingError> {
    let (pairs, rest) = values.as_chunks::<2>();
    if !rest.is_empty() {
        return Err(BindingError::argument(format!(
            "{what} has {} numbers; x, y pairs need an even count",
            values.len()
        )));
    }
    Ok(pairs.to_vec())
}

/// An outline as `{ outer: Float64Array, holes: Float64Array[] }`.
fn outline_object(outline: &Outline) -> Result<Object, BindingError> {
    let holes: Array = outline.holes.iter().map(|h| flat(h)).collect();
    object(&[("outer", flat(&outline.outer).into()), ("holes", holes.into())])
}

/// Outlines as `[{ outer: Float64Array, holes: Float64Array[] }]`.
fn outlines_to_js(outlines: &[Outline]) -> Result<Array, BindingError> {
    let list = Array::new();
    for outline in outlines {
        let entry = outline_object(outline)?;
        list.push(&entry);
    }
    Ok(list)
}

/// The limits on inputs, `{ bytes, pixels, points, vertices, sessionBytes, stiffness,
/// animationBytes }`: the largest text file in bytes, image in pixels, outline in points,
/// mesh in vertices, session in bytes, the stiffness range, and the RGBA bytes of an
/// animation's frames in all. One definition
/// (`akap::import::Limits`), which the TypeScript layer reads instead of repeating it.
#[wasm_bindgen(js_name = limits)]
pub fn js_limits() -> Result<Object, BindingError> {
    let l = limits();
    object(&[
        ("bytes", (l.max_bytes as f64).into()),
        ("pixels", (l.max_pixels as f64).into()),
        ("points", (l.max_points as f64).into()),
        ("vertices", (l.max_vertices as f64).into()),
        ("sessionBytes", (crate::session::MAX_BYTES as f64).into()),
        ("stiffness", Array::of2(&(*STIFFNESS_RANGE.start()).into(), &(*STIFFNESS_RANGE.end()).into()).into()),
        ("animationBytes", (l.max_animation_bytes as f64).into()),
    ])
}

/// Every `code` the bindings' errors can carry (see `ErrorCode`), in docs/errors.md's order.
#[wasm_bindgen(js_name = errorCodes)]
pub fn error_codes() -> Array {
    ErrorCode::ALL.iter().map(|code| JsValue::from_str(code.as_str())).collect()
}

thread_local! {
    static PERFORMANCE: Option<(JsValue, Function)> = {
        let performance = Reflect::get(&js_sys::global(), &JsValue::from_str("performance")).ok();
        performance.and_then(|p| {
            let now = Reflect::get(&p, &JsValue::from_str("now")).ok()?.dyn_into::<Function>().ok()?;
            Some((p, now))
        })
    };
}

/// `performance.now()` in milliseconds, or 0 where there is no `performance`.
fn performance_now() -> f64 {
    PERFORMANCE
        .with(|p| p.as_ref().and_then(|(this, now)| now.call0(this).ok()).and_then(|v| v.as_f64()).unwrap_or(0.0))
}
