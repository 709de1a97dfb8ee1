//! Sessions through `crate::session`, the format's one definition: `sessionJson` reads and
//! checks a session and writes it back as version 2, `sessionMesh` rebuilds its mesh; the
//! deformer (`Deformer.startRecording`, a `crate::pose::Poser`) records them, so that what
//! the widget saves is what the Rust reader reads.

use wasm_bindgen::prelude::*;

use super::error::BindingError;
use super::mesh::JsMesh;
use super::read::{self, Options};
use crate::session::{RecordedOptions, Session, ShapeSpec, MAX_BYTES};

fn read_session(text: &JsValue) -> Result<Session, BindingError> {
    let text = read::string(text, "the session", MAX_BYTES)?;
    Ok(Session::from_json(&text)?)
}

/// Reads a session (JSON text, version 1 or 2), checks everything that does not need its
/// mesh (see `Session::check`), and returns it as version-2 JSON, one event per line, with
/// every option of the recorded method in the header (`options` left out of a file are
/// that method's defaults), so that a replay starts from them alone.
#[wasm_bindgen(js_name = sessionJson)]
pub fn session_json(text: JsValue) -> Result<String, BindingError> {
    let mut session = read_session(&text)?;
    session.options = RecordedOptions::of(session.method_options()?);
    Ok(session.to_json())
}

/// The mesh of a session (JSON text): its built-in shape triangulated again, or its inline
/// mesh validated; either way checked against the recorded counts.
#[wasm_bindgen(js_name = sessionMesh)]
pub fn session_mesh(text: JsValue) -> Result<JsMesh, BindingError> {
    Ok(JsMesh { mesh: read_session(&text)?.mesh()? })
}

/// `{ name, targetEdgeLength?, minAngle?, maxArea? }`.
pub(super) fn shape_spec(value: &JsValue) -> Result<ShapeSpec, BindingError> {
    let given = Options::read(value, "shape", &["name", "targetEdgeLength", "minAngle", "maxArea"])?;
    let shapes: Vec<(&str, &str)> = crate::shapes::NAMES.iter().map(|&name| (name, name)).collect();
    let Some(name) = given.choice("name", &shapes)? else {
        return Err(BindingError::option("shape.name is missing"));
    };
    Ok(ShapeSpec {
        name: name.to_string(),
        target_edge_length: given.number("targetEdgeLength")?,
        max_area: given.number("maxArea")?,
        min_angle: given.number("minAngle")?,
    })
}

/// A recorded session as JSON (version 2), checked by reading it back and refused beyond
/// the size a session may have.
pub(super) fn checked_json(session: &Session) -> Result<String, BindingError> {
    let text = session.to_json();
    if text.len() > MAX_BYTES {
        return Err(BindingError::argument(format!(
            "the session is {} bytes, more than the {MAX_BYTES} a session may have",
            text.len()
        )));
    }
    Session::from_json(&text)?;
    Ok(text)
}
