//! The deformers (AKAP or ARAP behind one class) and their options.

use std::sync::OnceLock;

use js_sys::{Array, Function, Object, Reflect, Uint32Array};
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

use super::error::BindingError;
use super::mesh::read_mesh;
use super::read::{self, Options};
use super::{limits, max_coordinates, object, pairs};
use crate::deform::foldover::{MAX_CLAMP_TRIALS, MAX_SPLITS};
use crate::deform::{Deform, FoldoverGuard, FoldoverStepper, Method, MethodOptions, Orders, SettingValue};

/// A deformer for one mesh: AKAP (`crate::deform::Deformer`) or ARAP
/// (`crate::deform::ArapDeformer`), chosen by the `method` option.
#[wasm_bindgen(js_name = Deformer)]
pub struct JsDeformer {
    inner: Box<dyn Deform>,
    /// The buffers of `stepWithoutFoldovers`, kept from frame to frame.
    stepper: FoldoverStepper,
}

/// The fill-reducing orders a deformer of the method in `options` needs for this mesh (the
/// bulk of its set-up), as an array of `Uint32Array`s for `Deformer.withOrders`.
#[wasm_bindgen]
pub fn deformer_orders(positions: JsValue, triangles: JsValue, options: JsValue) -> Result<Array, BindingError> {
    let options = deformer_options(&options, MethodOptions::default())?;
    let mesh = read_mesh(&positions, &triangles)?;
    let list = Array::new();
    for order in options.orders(&mesh).systems {
        let order: Vec<u32> = order.into_iter().map(|v| v as u32).collect();
        list.push(&Uint32Array::from(order.as_slice()));
    }
    Ok(list)
}

/// Checks per-triangle stiffness for a mesh of `triangle_count` triangles, as
/// `Deformer.setStiffness` does: one value per triangle (`Float64Array`), each from 0.001 to
/// 1000. For callers that keep stiffness while a method without it poses.
#[wasm_bindgen(js_name = checkStiffness)]
pub fn check_stiffness(stiffness: JsValue, triangle_count: JsValue) -> Result<(), BindingError> {
    let count = read::count(&triangle_count, "triangleCount", max_coordinates())?;
    let values = read::float64s(&stiffness, "stiffness", max_coordinates())?;
    Ok(crate::deform::handles::check_stiffness(Some(&values), count)?)
}

/// Most handles a deformer takes: one per vertex of the largest mesh.
fn max_handles() -> usize {
    limits().max_vertices
}

#[wasm_bindgen(js_class = Deformer)]
impl JsDeformer {
    /// Validates the mesh (xy-interleaved positions, counter-clockwise index triples) and
    /// prepares the solver. `options`: `{ method?: "akap" | "arap", lambda?: number,
    /// dirichlet?: boolean, integrator?: "spiral" | "linear", iterations?: number }`
    /// (the last for ARAP, the three before it for AKAP).
    #[wasm_bindgen(constructor)]
    pub fn new(positions: JsValue, triangles: JsValue, options: JsValue) -> Result<JsDeformer, BindingError> {
        let options = deformer_options(&options, MethodOptions::default())?;
        let mesh = read_mesh(&positions, &triangles)?;
        let mut inner = options.build(mesh)?;
        inner.set_clock(performance_now);
        Ok(Self { inner, stepper: FoldoverStepper::default() })
    }

    /// The constructor with the fill-reducing orders computed beforehand by
    /// `deformer_orders` (for the same mesh and method), perhaps in a worker: the bulk of the
    /// set-up is then done. `orders`: an array of `Uint32Array`s.
    #[wasm_bindgen(js_name = withOrders)]
    pub fn with_orders(
        positions: JsValue,
        triangles: JsValue,
        options: JsValue,
        orders: JsValue,
    ) -> Result<JsDeformer, BindingError> {
        let options = deformer_options(&options, MethodOptions::default())?;
        let mesh = read_mesh(&positions, &triangles)?;
        let systems = read::list(&orders, "orders", 4)?
            .iter()
            .enumerate()
            .map(|(i, order)| {
                let order = read::uint32s(order, &format!("orders[{i}]"), mesh.vertex_count())?;
                Ok(order.into_iter().map(|v| v as usize).collect())
            })
            .collect::<Result<Vec<_>, BindingError>>()?;
        let mut inner = options.build_with_orders(mesh, &Orders { systems })?;
        inner.set_clock(performance_now);
        Ok(Self { inner, stepper: FoldoverStepper::default() })
    }

    /// Changes some options; the others keep their values. A different `method` switches
    /// to that method (its defaults, with the options given) on the same mesh, keeping the
    /// pose and the handles: a new solver is set up (`MethodOptions::apply`).
    #[wasm_bindgen(js_name = setOptions)]
    pub fn set_options(&mut self, options: JsValue) -> Result<(), BindingError> {
        let options = deformer_options(&options, self.inner.method_options())?;
        options.apply(&mut self.inner)?;
        self.inner.set_clock(performance_now);
        Ok(())
    }

    /// `"akap"` or `"arap"`.
    #[wasm_bindgen(getter)]
    pub fn method(&self) -> String {
        self.inner.method_options().method().name().to_owned()
    }

    /// One handle on each of these vertices (a `Uint32Array`), replacing the handles.
    #[wasm_bindgen(js_name = setHandles)]
    pub fn set_handles(&mut self, vertices: JsValue) -> Result<(), BindingError> {
        let vertices = read::uint32s(&vertices, "vertices", max_handles())?;
        Ok(self.inner.set_handle_vertices(&vertices)?)
    }

    /// Handles at points in triangles: triangle indices (`Uint32Array`) and three
    /// barycentric coordinates per point (`Float64Array`), replacing the handles.
    #[wasm_bindgen(js_name = setHandlePoints)]
    pub fn set_handle_points(&mut self, triangles: JsValue, barycentric: JsValue) -> Result<(), BindingError> {
        let triangles = read::uint32s(&triangles, "triangles", max_handles())?;
        let barycentric = read::float64s(&barycentric, "barycentric", 3 * max_handles())?;
        if barycentric.len() != 3 * triangles.len() {
            return Err(BindingError::argument(format!(
                "barycentric has {} numbers; {} triangles need 3 each ({})",
                barycentric.len(),
                triangles.len(),
                3 * triangles.len()
            )));
        }
        let (weights, _) = barycentric.as_chunks::<3>();
        Ok(self.inner.set_handle_points(&triangles, weights)?)
    }

    /// Bones, segments whose triangles move as one rigid body (AKAP and ARAP): two ends per
    /// bone, each a triangle index (`Uint32Array`) and three barycentric coordinates
    /// (`Float64Array`), laid in the current pose, replacing any bones; empty arrays remove
    /// them. Refused, changing nothing, for a bone whose ends are at one point, whose segment
    /// leaves the shape or that touches another bone, and by methods without bones.
    #[wasm_bindgen(js_name = setBones)]
    pub fn set_bones(&mut self, triangles: JsValue, barycentric: JsValue) -> Result<(), BindingError> {
        let triangles = read::uint32s(&triangles, "triangles", max_handles())?;
        let barycentric = read::float64s(&barycentric, "barycentric", 3 * max_handles())?;
        let (ends, rest) = barycentric.as_chunks::<3>();
        if !rest.is_empty() {
            return Err(BindingError::argument(format!(
                "barycentric has {} numbers, not 3 for each bone end",
                barycentric.len()
            )));
        }
        Ok(self.inner.set_bones(&triangles, ends)?)
    }

    /// Whether the method has bones (`setBones`): AKAP and ARAP.
    #[wasm_bindgen(getter, js_name = hasBones)]
    pub fn has_bones(&self) -> bool {
        self.inner.has_bones()
    }

    /// One step with two velocity components per handle, in handle order (`Float64Array`).
    pub fn step(&mut self, velocities: JsValue) -> Result<(), BindingError> {
        let velocities = read::float64s(&velocities, "velocities", 2 * max_handles())?;
        Ok(self.inner.step(&pairs(&velocities, "velocities")?)?)
    }

    /// One step that turns no triangle over (`crate::deform::foldover`): the plain step
    /// when it flips none, else halves down to `2^-maxSplits` of the velocities, the first
    /// such piece that still flips clamped to its largest flip-free fraction found by
    /// `clampTrials` bisections, and the step ending there. `options`: `{ maxSplits?,
    /// clampTrials? }` (whole numbers, 0 to 10 and 0 to 30; default 4 and 12). Returns
    /// `{ steps, clamped, attempts }`: `steps` the fraction of the velocities each plain
    /// step taken moved by, in order (`[1]` for a step that flipped nothing; `step` with
    /// `velocities[i] * fraction` each replays it to the bit), `clamped` whether the step
    /// ended short, `attempts` the plain steps tried. On error the deformer is unchanged.
    #[wasm_bindgen(js_name = stepWithoutFoldovers)]
    ///
    /// `turns` (`Float64Array`, one per handle, or `undefined`): handles also turn, as in
    /// `stepTurning`; each piece turns them by its fraction of `turns`.
    pub fn step_without_foldovers(
        &mut self,
        velocities: JsValue,
        options: JsValue,
        turns: JsValue,
    ) -> Result<Object, BindingError> {
        let guard = foldover_guard(&options)?;
        let velocities = read::float64s(&velocities, "velocities", 2 * max_handles())?;
        let velocities = pairs(&velocities, "velocities")?;
        let turns = if turns.is_undefined() { None } else { Some(read::float64s(&turns, "turns", max_handles())?) };
        self.stepper.set_guard(guard)?;
        let report = match &turns {
            None => self.stepper.step(self.inner.as_mut(), &velocities)?,
            Some(turns) => self.stepper.step_turning(self.inner.as_mut(), &velocities, turns)?,
        };
        let steps: Array = report.steps.iter().map(|&f| JsValue::from_f64(f)).collect();
        object(&[
            ("steps", steps.into()),
            ("clamped", report.clamped.into()),
            ("attempts", (report.attempts as f64).into()),
        ])
    }

    /// One step in which handles also turn: `velocities` as `step` takes them, `turns`
    /// (`Float64Array`) one angle per handle, radians counter-clockwise about the handle's
    /// point, its neighbourhood following that rigid motion (AKAP; all zero is `step`).
    #[wasm_bindgen(js_name = stepTurning)]
    pub fn step_turning(&mut self, velocities: JsValue, turns: JsValue) -> Result<(), BindingError> {
        let velocities = read::float64s(&velocities, "velocities", 2 * max_handles())?;
        let turns = read::float64s(&turns, "turns", max_handles())?;
        Ok(self.inner.step_turning(&pairs(&velocities, "velocities")?, &turns)?)
    }

    /// A copy of the current positions, x and y interleaved.
    pub fn positions(&self) -> Vec<f64> {
        self.inner.positions().iter().flatten().copied().collect()
    }

    /// Where the current positions live in wasm memory: the byte offset of `2 * vertexCount`
    /// f64 values, x and y interleaved. JavaScript wraps it in a `Float64Array` over
    /// `memory.buffer` (no copy). The address changes with every step (the deformer swaps
    /// two buffers), and a view detaches when the memory grows: ask again each frame.
    #[wasm_bindgen(js_name = positionsPointer)]
    pub fn positions_pointer(&self) -> usize {
        self.inner.positions().as_ptr() as usize
    }

    /// Puts the mesh into the given pose (`Float64Array`, xy-interleaved, length
    /// `2 * vertexCount`); handles stay.
    #[wasm_bindgen(js_name = setPositions)]
    pub fn set_positions(&mut self, positions: JsValue) -> Result<(), BindingError> {
        let positions = read::float64s(&positions, "positions", max_coordinates())?;
        Ok(self.inner.set_positions(&pairs(&positions, "positions")?)?)
    }

    /// Each triangle's stiffness (`Float64Array`, one per triangle, 0.001 to 1000), or 1
    /// everywhere with `undefined`: AKAP and ARAP only.
    #[wasm_bindgen(js_name = setStiffness)]
    pub fn set_stiffness(&mut self, stiffness: JsValue) -> Result<(), BindingError> {
        if stiffness.is_undefined() {
            return Ok(self.inner.set_stiffness(None)?);
        }
        let values = read::float64s(&stiffness, "stiffness", max_coordinates())?;
        Ok(self.inner.set_stiffness(Some(&values))?)
    }

    /// Whether the method takes per-triangle stiffness (AKAP and ARAP).
    #[wasm_bindgen(getter, js_name = hasStiffness)]
    pub fn has_stiffness(&self) -> bool {
        self.inner.has_stiffness()
    }

    /// The last velocity field after the Dirichlet step (`U_opt`; ARAP: the last step's
    /// displacement), interleaved.
    pub fn field(&self) -> Vec<f64> {
        self.inner.field().iter().flatten().copied().collect()
    }

    /// The last velocity field after the soft-constraint step (`U0`; ARAP: the last
    /// step's displacement), interleaved.
    #[wasm_bindgen(js_name = softField)]
    pub fn soft_field(&self) -> Vec<f64> {
        self.inner.soft_field().iter().flatten().copied().collect()
    }

    /// The deformed cage of Cauchy-Green (its vertices as the last step left them),
    /// interleaved; `undefined` for the methods without a cage.
    pub fn cage(&self) -> Option<Vec<f64>> {
        self.inner.cage_image().map(|cage| cage.iter().flatten().copied().collect())
    }

    /// Current positions of the handle points, interleaved.
    #[wasm_bindgen(js_name = handlePositions)]
    pub fn handle_positions(&self) -> Vec<f64> {
        self.inner.handle_positions().iter().flatten().copied().collect()
    }

    /// Number of handles.
    #[wasm_bindgen(getter, js_name = handleCount)]
    pub fn handle_count(&self) -> usize {
        self.inner.handle_count()
    }

    /// Number of vertices.
    #[wasm_bindgen(getter, js_name = vertexCount)]
    pub fn vertex_count(&self) -> usize {
        self.inner.mesh().vertex_count()
    }

    /// `{ areaDistortion, angleDistortion, flipped }` of the current pose.
    pub fn metrics(&self) -> Result<Object, BindingError> {
        let m = self.inner.metrics();
        object(&[
            ("areaDistortion", m.area_distortion.into()),
            ("angleDistortion", m.angle_distortion.into()),
            ("flipped", (m.flipped as f64).into()),
        ])
    }

    /// `{ assembly, factorisation, dirichletFactorisation, solve, integration }`:
    /// milliseconds of the last step (`dirichletFactorisation` is the part of
    /// `factorisation` spent on AKAP's step 2).
    pub fn timings(&self) -> Result<Object, BindingError> {
        let t = self.inner.timings();
        object(&[
            ("assembly", t.assembly.into()),
            ("factorisation", t.factorisation.into()),
            ("dirichletFactorisation", t.dirichlet_factorisation.into()),
            ("solve", t.solve.into()),
            ("integration", t.integration.into()),
        ])
    }

    /// Back to the rest pose (handles stay).
    pub fn reset(&mut self) {
        self.inner.reset();
    }
}

/// Reads `{ maxSplits?, clampTrials? }` over the defaults.
fn foldover_guard(value: &JsValue) -> Result<FoldoverGuard, BindingError> {
    let given = Options::read(value, "foldover", &["maxSplits", "clampTrials"])?;
    let mut guard = FoldoverGuard::default();
    if let Some(n) = given.count("maxSplits", MAX_SPLITS as usize)? {
        guard.max_splits = n as u32;
    }
    if let Some(n) = given.count("clampTrials", MAX_CLAMP_TRIALS as usize)? {
        guard.clamp_trials = n as u32;
    }
    Ok(guard)
}

/// The deformer options' names: `method`, then every method's settings.
fn names() -> &'static [&'static str] {
    static NAMES: OnceLock<Vec<&'static str>> = OnceLock::new();
    NAMES.get_or_init(|| std::iter::once("method").chain(MethodOptions::all_setting_names()).collect())
}

/// Reads `{ method?, ...settings }` over `base` as [`MethodOptions::over`] makes them: a
/// different `method` starts from that method's defaults; an unknown key, a setting of
/// another method and a value of the wrong type are refused.
pub(super) fn deformer_options(value: &JsValue, base: MethodOptions) -> Result<MethodOptions, BindingError> {
    let given = Options::read(value, "deformer", names())?;
    let methods: Vec<(&str, Method)> = Method::all().iter().map(|&m| (m.name(), m)).collect();
    let method = given.choice("method", &methods)?;
    let mut values = Vec::new();
    for name in given.names().filter(|&name| name != "method") {
        let value = given.get(name).expect("a name given has a value");
        let value = if let Some(x) = value.as_f64() {
            SettingValue::Number(x)
        } else if let Some(b) = value.as_bool() {
            SettingValue::Bool(b)
        } else if let Some(w) = value.as_string() {
            SettingValue::Word(w)
        } else {
            return Err(given.wrong_type(name, "a number, true, false or a string", value));
        };
        values.push((name, value));
    }
    Ok(MethodOptions::over(base, method, values.iter().map(|(name, value)| (*name, value)))?)
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
pub(super) fn performance_now() -> f64 {
    PERFORMANCE
        .with(|p| p.as_ref().and_then(|(this, now)| now.call0(this).ok()).and_then(|v| v.as_f64()).unwrap_or(0.0))
}
