//! The deformer of any method and its interaction loop, behind one class: the JavaScript
//! `Deformer` is a `crate::pose::Poser`, which owns a `crate::deform::Deformer`; plain
//! steps and the poses, handles, options, stiffness and bones set through it are recorded
//! while a recording runs, and `advance` is the frame of the interaction loop.

use js_sys::{Array, Object, Uint32Array};
use wasm_bindgen::prelude::*;

use super::defop::JsDefOp;
use super::error::BindingError;
use super::mesh::read_mesh;
use super::options::{deformer_options, deformer_setup};
use super::puppet::{joints_to_js, parts_to_js, read_joints};
use super::read::{self, Options};
use super::session::shape_spec;
use super::{limits, max_coordinates, object, pairs, performance_now};
use crate::deform::foldover::{MAX_CLAMP_TRIALS, MAX_SPLITS};
use crate::deform::{Deformer, FoldoverGuard, Orders, Timings};
use crate::pose::{Poser, MAX_SUBSTEPS};

/// A deformer for one mesh (`crate::deform::Deformer`), of the method the `method` option
/// names, with its interaction loop (`crate::pose::Poser`).
#[wasm_bindgen(js_name = Deformer)]
pub struct JsDeformer {
    inner: Poser,
}

impl JsDeformer {
    fn made(mut deformer: Deformer) -> Self {
        deformer.set_clock(performance_now);
        Self { inner: Poser::new(deformer) }
    }

    fn deformer(&self) -> &Deformer {
        self.inner.deformer()
    }

    /// The deformer with its pose current: a rig on the GPU leaves the positions behind
    /// until they are read (`crate::pose::Poser::settle`; a pose that cannot be evaluated
    /// leaves them as they were). Every reader of the pose goes through here.
    fn posed(&mut self) -> &Deformer {
        let _ = self.inner.settle();
        self.inner.deformer()
    }
}

/// The fill-reducing orders a deformer of the method in `options` needs for this mesh (the
/// bulk of its set-up), as an array of `Uint32Array`s for `Deformer.withOrders`.
#[wasm_bindgen]
pub fn deformer_orders(positions: JsValue, triangles: JsValue, options: JsValue) -> Result<Array, BindingError> {
    // A puppet's orders are its mesh's: its parts and joints are read (and checked by the
    // deformer that takes the orders) but change nothing here.
    let (options, _) = deformer_setup(&options)?;
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
    /// prepares the solver. `options`: `{ method?, ...the method's settings, parts?,
    /// joints? }`; with `parts` (and `joints`) the mesh is a puppet's sheets (see
    /// `crate::deform::puppet`).
    #[wasm_bindgen(constructor)]
    pub fn new(positions: JsValue, triangles: JsValue, options: JsValue) -> Result<JsDeformer, BindingError> {
        let (options, puppet) = deformer_setup(&options)?;
        let mesh = read_mesh(&positions, &triangles)?;
        Ok(Self::made(match puppet {
            Some(puppet) => Deformer::with_puppet(mesh, options, puppet, None)?,
            None => Deformer::new(mesh, options)?,
        }))
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
        let (options, puppet) = deformer_setup(&options)?;
        let mesh = read_mesh(&positions, &triangles)?;
        let systems = read::list(&orders, "orders", 4)?
            .iter()
            .enumerate()
            .map(|(i, order)| {
                let order = read::uint32s(order, &format!("orders[{i}]"), mesh.vertex_count())?;
                Ok(order.into_iter().map(|v| v as usize).collect())
            })
            .collect::<Result<Vec<_>, BindingError>>()?;
        let orders = Orders { systems };
        Ok(Self::made(match puppet {
            Some(puppet) => Deformer::with_puppet(mesh, options, puppet, Some(&orders))?,
            None => Deformer::with_orders(mesh, options, &orders)?,
        }))
    }

    /// A puppet's parts (`[{ name, triangles: Uint32Array, depth }]`), or `undefined` for a
    /// deformer of one shape.
    #[wasm_bindgen(getter)]
    pub fn parts(&self) -> Result<JsValue, BindingError> {
        match self.deformer().puppet() {
            Some(puppet) => Ok(parts_to_js(&puppet.parts)?.into()),
            None => Ok(JsValue::UNDEFINED),
        }
    }

    /// A puppet's joints (`[{ point: [x, y], parts: [front, back] }]`; empty for a deformer
    /// of one shape).
    #[wasm_bindgen(getter)]
    pub fn joints(&self) -> Result<Array, BindingError> {
        joints_to_js(self.deformer().puppet().map_or(&[][..], |p| &p.joints[..]))
    }

    /// Replaces a puppet's joints (`[{ point: [x, y], parts: [front, back] }]`), keeping the
    /// pose, the handles, the stiffness and the bones; the systems are analysed again. A
    /// part out of range, a part joined to itself or a point not on both parts is refused
    /// (code `invalid-joint`), as is a deformer of one shape; nothing changes.
    #[wasm_bindgen(js_name = setJoints)]
    pub fn set_joints(&mut self, joints: JsValue) -> Result<(), BindingError> {
        let joints = read_joints(&joints)?;
        Ok(self.inner.set_joints(joints)?)
    }

    /// Changes some options; the others keep their values. A different `method` switches
    /// to that method (its defaults, with the options given) on the same mesh, keeping the
    /// pose and the handles: a new solver is set up (`Deformer::set_options`).
    #[wasm_bindgen(js_name = setOptions)]
    pub fn set_options(&mut self, options: JsValue) -> Result<(), BindingError> {
        let options = deformer_options(&options, self.deformer().options())?;
        Ok(self.inner.set_options(options)?)
    }

    /// `"akap"` or `"arap"`.
    #[wasm_bindgen(getter)]
    pub fn method(&self) -> String {
        self.deformer().method().name().to_owned()
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
        self.deformer().has_bones()
    }

    /// One step with two velocity components per handle, in handle order (`Float64Array`).
    pub fn step(&mut self, velocities: JsValue) -> Result<(), BindingError> {
        let velocities = read::float64s(&velocities, "velocities", 2 * max_handles())?;
        Ok(self.inner.step(&pairs(&velocities, "velocities")?, None)?)
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
        let report = self.inner.step_without_foldovers(&velocities, turns.as_deref(), guard)?;
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
        Ok(self.inner.step(&pairs(&velocities, "velocities")?, Some(&turns))?)
    }

    /// A copy of the current positions, x and y interleaved.
    pub fn positions(&mut self) -> Vec<f64> {
        self.posed().positions().iter().flatten().copied().collect()
    }

    /// Where the current positions live in wasm memory: the byte offset of `2 * vertexCount`
    /// f64 values, x and y interleaved. JavaScript wraps it in a `Float64Array` over
    /// `memory.buffer` (no copy). The address changes with every step (the deformer swaps
    /// two buffers), and a view detaches when the memory grows: ask again each frame.
    #[wasm_bindgen(js_name = positionsPointer)]
    pub fn positions_pointer(&mut self) -> usize {
        self.posed().positions().as_ptr() as usize
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
        self.deformer().has_stiffness()
    }

    /// The last velocity field after the Dirichlet step (`U_opt`; ARAP: the last step's
    /// displacement), interleaved.
    pub fn field(&self) -> Vec<f64> {
        self.deformer().field().iter().flatten().copied().collect()
    }

    /// The last velocity field after the soft-constraint step (`U0`; ARAP: the last
    /// step's displacement), interleaved.
    #[wasm_bindgen(js_name = softField)]
    pub fn soft_field(&self) -> Vec<f64> {
        self.deformer().soft_field().iter().flatten().copied().collect()
    }

    /// The deformed cage of Cauchy-Green (its vertices as the last step left them),
    /// interleaved; `undefined` for the methods without a cage.
    pub fn cage(&self) -> Option<Vec<f64>> {
        self.deformer().cage_image().map(|cage| cage.iter().flatten().copied().collect())
    }

    /// Current positions of the handle points, interleaved.
    #[wasm_bindgen(js_name = handlePositions)]
    pub fn handle_positions(&mut self) -> Vec<f64> {
        self.posed().handle_positions().iter().flatten().copied().collect()
    }

    /// Number of handles.
    #[wasm_bindgen(getter, js_name = handleCount)]
    pub fn handle_count(&self) -> usize {
        self.inner.handle_count()
    }

    /// Number of vertices.
    #[wasm_bindgen(getter, js_name = vertexCount)]
    pub fn vertex_count(&self) -> usize {
        self.deformer().mesh().vertex_count()
    }

    /// `{ areaDistortion, angleDistortion, flipped }` of the current pose.
    pub fn metrics(&mut self) -> Result<Object, BindingError> {
        let m = self.posed().metrics();
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
        timings_object(&self.deformer().timings())
    }

    /// Back to the rest pose; handles stay, each with its target at its rest place.
    pub fn reset(&mut self) {
        self.inner.reset();
    }

    /// Whether the pose is the rest pose: new or just reset, no step or pose since.
    #[wasm_bindgen(getter, js_name = atRest)]
    pub fn at_rest(&self) -> bool {
        self.inner.at_rest()
    }

    /// The rest shape's size, its bounding box's larger side (the unit of `maxStep`).
    #[wasm_bindgen(getter)]
    pub fn size(&self) -> f64 {
        self.inner.size()
    }

    // ------------------------------------------------------------------ the interaction loop

    /// How `advance` moves the handles toward their targets (`crate::pose::Tracking`):
    /// `{ maxStep?, maxSubsteps?, noFoldovers?, maxSplits?, clampTrials?, paper? }` over
    /// the current policy (`maxStep` a share of `size`, default 0.02; `maxSubsteps` 1 to
    /// 10000, default 8; `noFoldovers` default true; the guard's limits as
    /// `stepWithoutFoldovers` takes them; `paper`, the paper's mode, default false).
    #[wasm_bindgen(js_name = setTracking)]
    pub fn set_tracking(&mut self, options: JsValue) -> Result<(), BindingError> {
        const NAMES: &[&str] = &["maxStep", "maxSubsteps", "noFoldovers", "maxSplits", "clampTrials", "paper"];
        let given = Options::read(&options, "tracking", NAMES)?;
        let mut tracking = self.inner.tracking();
        if let Some(x) = given.number("maxStep")? {
            tracking.max_step = x;
        }
        if let Some(n) = given.count("maxSubsteps", MAX_SUBSTEPS)? {
            tracking.max_substeps = n;
        }
        if let Some(b) = given.boolean("noFoldovers")? {
            tracking.no_foldovers = b;
        }
        if let Some(n) = given.count("maxSplits", MAX_SPLITS as usize)? {
            tracking.guard.max_splits = n as u32;
        }
        if let Some(n) = given.count("clampTrials", MAX_CLAMP_TRIALS as usize)? {
            tracking.guard.clamp_trials = n as u32;
        }
        if let Some(b) = given.boolean("paper")? {
            tracking.paper = b;
        }
        Ok(self.inner.set_tracking(tracking)?)
    }

    /// One more handle at a point of the mesh (a triangle and three barycentric
    /// coordinates, `Float64Array`), last, its target where it is; the others keep theirs.
    /// Returns its index.
    #[wasm_bindgen(js_name = addHandle)]
    pub fn add_handle(&mut self, triangle: JsValue, barycentric: JsValue) -> Result<usize, BindingError> {
        let triangle = read::count(&triangle, "triangle", u32::MAX as usize)? as u32;
        let weights = read::float64s(&barycentric, "barycentric", 3)?;
        let Ok(weights) = <[f64; 3]>::try_from(weights.as_slice()) else {
            return Err(BindingError::argument(format!("barycentric has {} numbers, not 3", weights.len())));
        };
        Ok(self.inner.add_handle(triangle, weights)?)
    }

    /// Removes handle `index`; the others keep their targets and turns.
    #[wasm_bindgen(js_name = removeHandle)]
    pub fn remove_handle(&mut self, index: JsValue) -> Result<(), BindingError> {
        let index = read::count(&index, "index", max_handles())?;
        Ok(self.inner.remove_handle(index)?)
    }

    /// Sets handle `index`'s target (`x`, `y`): where the next frames take it.
    #[wasm_bindgen(js_name = setTarget)]
    pub fn set_target(&mut self, index: JsValue, x: JsValue, y: JsValue) -> Result<(), BindingError> {
        let index = read::count(&index, "index", max_handles())?;
        let target = [read::number(&x, "x")?, read::number(&y, "y")?];
        Ok(self.inner.set_target(index, target)?)
    }

    /// Places every handle's target (`Float64Array`, x and y per handle): undo, a shown
    /// frame of an animation.
    #[wasm_bindgen(js_name = setTargets)]
    pub fn set_targets(&mut self, targets: JsValue) -> Result<(), BindingError> {
        let targets = read::float64s(&targets, "targets", 2 * max_handles())?;
        Ok(self.inner.set_targets(&pairs(&targets, "targets")?)?)
    }

    /// Sets how far handle `index` is to turn in all, radians counter-clockwise.
    #[wasm_bindgen(js_name = setTurn)]
    pub fn set_turn(&mut self, index: JsValue, turn: JsValue) -> Result<(), BindingError> {
        let index = read::count(&index, "index", max_handles())?;
        Ok(self.inner.set_turn(index, read::number(&turn, "turn")?)?)
    }

    /// A pointer takes handle `index`: held, its target where it is. Returns where it is
    /// (`Float64Array` of x and y).
    pub fn grab(&mut self, index: JsValue) -> Result<Vec<f64>, BindingError> {
        let index = read::count(&index, "index", max_handles())?;
        Ok(self.inner.grab(index)?.to_vec())
    }

    /// The pointer lets handle `index` go: it stays at its target.
    pub fn release(&mut self, index: JsValue) -> Result<(), BindingError> {
        let index = read::count(&index, "index", max_handles())?;
        Ok(self.inner.release(index)?)
    }

    /// Whether a pointer holds handle `index` (a step that stops short leaves the handles
    /// not held where they stopped); its target stays.
    #[wasm_bindgen(js_name = setHeld)]
    pub fn set_held(&mut self, index: JsValue, held: bool) -> Result<(), BindingError> {
        let index = read::count(&index, "index", max_handles())?;
        Ok(self.inner.set_held(index, held)?)
    }

    /// Every handle's target where it is now: the handles stay where they are.
    #[wasm_bindgen(js_name = pinHandles)]
    pub fn pin_handles(&mut self) {
        self.inner.pin_handles();
    }

    /// Where each handle is going, x and y interleaved.
    pub fn targets(&self) -> Vec<f64> {
        self.inner.targets().flatten().collect()
    }

    /// How far each handle is to turn in all, and has turned, radians: `turns` then
    /// `turned`, one per handle each.
    pub fn turns(&self) -> Vec<f64> {
        self.inner.turns().chain(self.inner.turned()).collect()
    }

    /// One frame: the handles moved toward their targets (`crate::pose::Poser::advance`),
    /// or the rig's pose. Returns `{ steps, clamped, evaluation, timings }`: the substeps
    /// taken, whether a step stopped short to keep triangles from folding over, the rig's
    /// evaluation in milliseconds, and the stage timings summed over the substeps (as
    /// `timings()` gives them).
    pub fn advance(&mut self) -> Result<Object, BindingError> {
        let report = self.inner.advance()?;
        object(&[
            ("steps", (report.steps as f64).into()),
            ("clamped", report.clamped.into()),
            ("evaluation", report.evaluation.into()),
            ("timings", timings_object(&report.timings)?.into()),
        ])
    }

    /// Poses with a trained rig (`DefOp`, copied) instead of stepping, until `clearRig` or a
    /// new handle set: each frame the pose is the rig's for the targets. Refused for a rig
    /// of other handle or vertex counts; the caller checks it was trained for this mesh and
    /// these handle points.
    #[wasm_bindgen(js_name = setRig)]
    pub fn set_rig(&mut self, rig: &JsDefOp) -> Result<(), BindingError> {
        Ok(self.inner.set_rig(Some(rig.operator().clone()))?)
    }

    /// Poses by stepping again.
    #[wasm_bindgen(js_name = clearRig)]
    pub fn clear_rig(&mut self) {
        self.inner.set_rig(None).expect("clearing a rig cannot fail");
    }

    /// Whether a rig poses the shape.
    #[wasm_bindgen(getter, js_name = hasRig)]
    pub fn has_rig(&self) -> bool {
        self.inner.has_rig()
    }

    /// How a session names `rig` posing this deformer's mesh (`crate::pose::session_rig`):
    /// the checksum of its operator file, 16 hexadecimal digits, as a `rig` event has it.
    #[wasm_bindgen(js_name = rigChecksum)]
    pub fn rig_checksum(&self, rig: &JsDefOp) -> Result<String, BindingError> {
        let named = crate::pose::session_rig(self.inner.deformer().mesh(), rig.operator());
        Ok(named.map_err(crate::defop::TrainError::from)?.to_string())
    }

    /// Poses with the rig at these targets (`Float64Array`, x and y per handle), as given:
    /// no guard (a session's recorded `rigPose`). The handles' targets become these.
    #[wasm_bindgen(js_name = poseWithRig)]
    pub fn pose_with_rig(&mut self, targets: JsValue) -> Result<(), BindingError> {
        let targets = read::float64s(&targets, "targets", 2 * max_handles())?;
        Ok(self.inner.pose_with_rig(&pairs(&targets, "targets")?)?)
    }

    /// Poses the rig on the GPU (`true`) or on the CPU (`false`): on the GPU, `advance`
    /// computes only the rig's frame (`rigFramePointer`), which a vertex shader combines
    /// with the basis texture (`rigGpuTexture`, laid out as `rigGpuLayout` says;
    /// `crate::defop::gpu`), and the pose is evaluated when something reads it (positions,
    /// handle positions, metrics, a step, a recording...). Returns whether the rig is on the
    /// GPU now (never without a rig; a new rig starts on the CPU).
    #[wasm_bindgen(js_name = setRigOnGpu)]
    pub fn set_rig_on_gpu(&mut self, on: bool) -> Result<bool, BindingError> {
        Ok(self.inner.set_rig_on_gpu(on)?)
    }

    /// The layout of the rig on the GPU, `{ reduced, vertexCount, terms, stride, basisY,
    /// frameY, frameTexels, rigidTexels }` (texels of 4 numbers; see `crate::defop::gpu`),
    /// or `undefined` without one.
    #[wasm_bindgen(js_name = rigGpuLayout)]
    pub fn rig_gpu_layout(&self) -> Result<JsValue, BindingError> {
        let Some(gpu) = self.inner.rig_gpu() else { return Ok(JsValue::UNDEFINED) };
        let l = gpu.layout();
        let count = |n: usize| JsValue::from_f64(n as f64);
        Ok(object(&[
            ("reduced", l.reduced.into()),
            ("vertexCount", count(l.vertex_count)),
            ("terms", count(l.terms)),
            ("stride", count(l.stride)),
            ("basisY", count(l.basis_y)),
            ("frameY", count(l.frame_y)),
            ("frameTexels", count(l.frame_texels)),
            ("rigidTexels", count(crate::defop::gpu::RIGID_TEXELS)),
        ])?
        .into())
    }

    /// The basis texture of the rig on the GPU (`Float32Array`, 4 numbers per texel,
    /// `vertexCount * stride` texels), or `undefined` without one: upload it once per rig.
    #[wasm_bindgen(js_name = rigGpuTexture)]
    pub fn rig_gpu_texture(&self) -> Option<Vec<f32>> {
        self.inner.rig_gpu_texture()
    }

    /// Where the rig's last frame lives in wasm memory (the byte offset of `4 *
    /// frameTexels` f32 numbers; 0 without a rig on the GPU): wrap it in a `Float32Array`
    /// after each `advance` (its address stays while the rig does; a view detaches when the
    /// memory grows).
    #[wasm_bindgen(js_name = rigFramePointer)]
    pub fn rig_frame_pointer(&self) -> usize {
        self.inner.rig_gpu().map_or(0, |gpu| gpu.frame_values().as_ptr() as usize)
    }

    /// Watches these vertices (`Uint32Array`) of the rig on the GPU: each frame gives their
    /// positions on the CPU (`rigWatchedPointer`), for what is drawn over the mesh. Returns
    /// whether a rig is on the GPU (nothing is watched without one). A vertex out of range
    /// is refused, changing nothing.
    #[wasm_bindgen(js_name = watchRigVertices)]
    pub fn watch_rig_vertices(&mut self, vertices: JsValue) -> Result<bool, BindingError> {
        let vertices = read::uint32s(&vertices, "vertices", limits().max_vertices)?;
        Ok(self.inner.watch_rig_vertices(&vertices).map_err(crate::defop::TrainError::from)?)
    }

    /// Where the watched vertices' positions live in wasm memory (the byte offset of `2 *
    /// vertexCount` f64 numbers, x and y interleaved, fresh at the watched vertices as of the
    /// last frame; 0 without a rig on the GPU).
    #[wasm_bindgen(js_name = rigWatchedPointer)]
    pub fn rig_watched_pointer(&self) -> usize {
        self.inner.rig_gpu().map_or(0, |gpu| gpu.watched_positions().as_ptr() as usize)
    }

    /// Whether the positions are behind the rig's last frame on the GPU (they are evaluated
    /// when read).
    #[wasm_bindgen(getter, js_name = poseStale)]
    pub fn pose_stale(&self) -> bool {
        self.inner.is_stale()
    }

    /// Whether the rig's last frame on the GPU is that of the pose shown (stale positions
    /// or not: with the foldover guard each frame is also evaluated on the CPU).
    #[wasm_bindgen(getter, js_name = rigFrameCurrent)]
    pub fn rig_frame_current(&self) -> bool {
        self.inner.rig_frame_current()
    }

    // ------------------------------------------------------------------ recording

    /// Starts recording a session of everything done through this deformer from now on,
    /// replacing any recording. `shape` (`{ name, targetEdgeLength?, minAngle?, maxArea? }`)
    /// names the built-in shape the mesh was triangulated from; without it (`undefined`) the
    /// session carries the mesh.
    #[wasm_bindgen(js_name = startRecording)]
    pub fn start_recording(&mut self, shape: JsValue) -> Result<(), BindingError> {
        let shape = if shape.is_undefined() || shape.is_null() { None } else { Some(shape_spec(&shape)?) };
        self.inner.start_recording(shape);
        Ok(())
    }

    /// Whether a recording runs.
    #[wasm_bindgen(getter)]
    pub fn recording(&self) -> bool {
        self.inner.recording()
    }

    /// Ends the recording and returns it as JSON (version 2), checked by reading it back;
    /// `undefined` if none ran.
    #[wasm_bindgen(js_name = stopRecording)]
    pub fn stop_recording(&mut self) -> Result<Option<String>, BindingError> {
        self.inner.stop_recording().map(|session| super::session::checked_json(&session)).transpose()
    }

    /// Pauses the recording (while a session replays) or resumes it.
    #[wasm_bindgen(js_name = pauseRecording)]
    pub fn pause_recording(&mut self, paused: bool) {
        self.inner.pause_recording(paused);
    }
}

/// `{ assembly, factorisation, dirichletFactorisation, solve, integration }`.
fn timings_object(t: &Timings) -> Result<Object, BindingError> {
    object(&[
        ("assembly", t.assembly.into()),
        ("factorisation", t.factorisation.into()),
        ("dirichletFactorisation", t.dirichlet_factorisation.into()),
        ("solve", t.solve.into()),
        ("integration", t.integration.into()),
    ])
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
