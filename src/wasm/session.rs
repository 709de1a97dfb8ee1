//! Sessions through `crate::session`, the format's one definition: `sessionJson` reads and
//! checks a session and writes it back as version 2, `sessionMesh` rebuilds its mesh, and
//! `SessionRecorder` records one as the widget works, so that what the widget saves is
//! what the Rust reader reads.

use wasm_bindgen::prelude::*;

use super::error::BindingError;
use super::mesh::{read_mesh, JsMesh};
use super::options::deformer_options;
use super::read::{self, Options};
use super::{limits, max_coordinates};
use crate::deform::handles::check_stiffness;
use crate::deform::MethodOptions;
use crate::session::{Event, MeshCounts, RecordedOptions, Session, SessionMesh, ShapeSpec, MAX_BYTES};

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

/// A session being recorded: each call adds an event; a call refused (with an `Error`)
/// adds nothing.
#[wasm_bindgen(js_name = SessionRecorder)]
pub struct JsSessionRecorder {
    session: Session,
    /// The options in place after the events so far.
    options: MethodOptions,
    handles: usize,
}

#[wasm_bindgen(js_class = SessionRecorder)]
impl JsSessionRecorder {
    /// Starts a session of the mesh (`positions`: `Float64Array`, xy-interleaved;
    /// `triangles`: `Uint32Array`) with deformer `options` (`{ method?, lambda?, dirichlet?,
    /// integrator?, iterations? }`, as the deformer takes them). `shape` (`{ name,
    /// targetEdgeLength?, minAngle?, maxArea? }`) names the built-in shape the mesh was
    /// triangulated from; without it (`undefined`) the session carries the mesh.
    #[wasm_bindgen(constructor)]
    pub fn new(
        options: JsValue,
        shape: JsValue,
        positions: JsValue,
        triangles: JsValue,
    ) -> Result<JsSessionRecorder, BindingError> {
        let options = deformer_options(&options, MethodOptions::default())?;
        let mesh = read_mesh(&positions, &triangles)?;
        let mut session = Session::with_mesh(&mesh, options);
        if !(shape.is_undefined() || shape.is_null()) {
            session.shape = Some(shape_spec(&shape)?);
            session.mesh = SessionMesh::counts_of(MeshCounts::of(&mesh));
        }
        Ok(Self { session, options, handles: 0 })
    }

    /// Handles: a triangle (`Uint32Array`) and 3 barycentric coordinates
    /// (`Float64Array`) each.
    pub fn handles(&mut self, triangles: JsValue, barycentric: JsValue) -> Result<(), BindingError> {
        let most = limits().max_vertices;
        let triangles = read::uint32s(&triangles, "triangles", most)?;
        let barycentric = finite(read::float64s(&barycentric, "barycentric", 3 * most)?, "barycentric")?;
        if barycentric.len() != 3 * triangles.len() {
            return Err(BindingError::argument(format!(
                "barycentric has {} numbers; {} handles need 3 each",
                barycentric.len(),
                triangles.len()
            )));
        }
        self.handles = triangles.len();
        self.session.events.push(Event::Handles { triangles, barycentric });
        Ok(())
    }

    /// A step: two velocity components per handle (`Float64Array`).
    pub fn step(&mut self, velocities: JsValue) -> Result<(), BindingError> {
        let v = finite(read::float64s(&velocities, "velocities", 2 * limits().max_vertices)?, "velocities")?;
        if v.len() != 2 * self.handles {
            return Err(BindingError::argument(format!(
                "velocities has {} numbers; {} handles need 2 each",
                v.len(),
                self.handles
            )));
        }
        self.session.events.push(Event::Step(v));
        Ok(())
    }

    /// A step in which handles also turn: two velocity components and one turn per handle
    /// (`Float64Array`s).
    pub fn turn(&mut self, velocities: JsValue, turns: JsValue) -> Result<(), BindingError> {
        let v = finite(read::float64s(&velocities, "velocities", 2 * limits().max_vertices)?, "velocities")?;
        let turns = finite(read::float64s(&turns, "turns", limits().max_vertices)?, "turns")?;
        if v.len() != 2 * self.handles || turns.len() != self.handles {
            return Err(BindingError::argument(format!(
                "velocities has {} numbers and turns {}; {} handles need 2 and 1 each",
                v.len(),
                turns.len(),
                self.handles
            )));
        }
        self.session.events.push(Event::Turn { velocities: v, turns });
        Ok(())
    }

    /// A pose: x and y of every vertex (`Float64Array`).
    pub fn positions(&mut self, positions: JsValue) -> Result<(), BindingError> {
        let p = finite(read::float64s(&positions, "positions", max_coordinates())?, "positions")?;
        let n = self.session.mesh.vertex_count;
        if p.len() != 2 * n {
            return Err(BindingError::argument(format!("positions has {} numbers; {n} vertices need 2 each", p.len())));
        }
        self.session.events.push(Event::Positions(p));
        Ok(())
    }

    /// New deformer options, as `Deformer.setOptions` takes them, or of another method (a
    /// new deformer then): recorded in full.
    pub fn options(&mut self, options: JsValue) -> Result<(), BindingError> {
        let options = deformer_options(&options, self.options)?;
        options.check()?;
        self.options = options;
        self.session.events.push(Event::Options(RecordedOptions::of(options)));
        Ok(())
    }

    /// Each triangle's stiffness (`Float64Array`, one per triangle, 0.001 to 1000), or 1
    /// everywhere with `undefined`, as `Deformer.setStiffness` takes it.
    pub fn stiffness(&mut self, stiffness: JsValue) -> Result<(), BindingError> {
        let values = if stiffness.is_undefined() {
            None
        } else {
            Some(read::float64s(&stiffness, "stiffness", max_coordinates())?)
        };
        check_stiffness(values.as_deref(), self.session.mesh.triangle_count)?;
        self.session.events.push(Event::Stiffness(values));
        Ok(())
    }

    /// New bones, as `Deformer.setBones` takes them: a triangle (`Uint32Array`) and three
    /// barycentric coordinates (`Float64Array`) per end, two ends per bone.
    pub fn bones(&mut self, triangles: JsValue, barycentric: JsValue) -> Result<(), BindingError> {
        let most = limits().max_vertices;
        let triangles = read::uint32s(&triangles, "triangles", most)?;
        let barycentric = finite(read::float64s(&barycentric, "barycentric", 3 * most)?, "barycentric")?;
        if barycentric.len() != 3 * triangles.len() || !triangles.len().is_multiple_of(2) {
            return Err(BindingError::argument(format!(
                "bones have {} triangles and {} barycentric numbers; each bone has 2 ends of 1 and 3",
                triangles.len(),
                barycentric.len()
            )));
        }
        self.session.events.push(Event::Bones { triangles, barycentric });
        Ok(())
    }

    /// Back to the rest pose.
    pub fn reset(&mut self) {
        self.session.events.push(Event::Reset(true));
    }

    /// Number of events so far.
    #[wasm_bindgen(getter, js_name = eventCount)]
    pub fn event_count(&self) -> usize {
        self.session.events.len()
    }

    /// The session as JSON (version 2), checked by reading it back.
    #[wasm_bindgen(js_name = toJson)]
    pub fn to_json(&self) -> Result<String, BindingError> {
        checked_json(&self.session)
    }
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

/// `values`, refused when one is NaN or infinite (JSON has no such numbers).
fn finite(values: Vec<f64>, what: &str) -> Result<Vec<f64>, BindingError> {
    match values.iter().position(|x| !x.is_finite()) {
        Some(i) => Err(BindingError::argument(format!("{what}[{i}] is {}, not a finite number", values[i]))),
        None => Ok(values),
    }
}
