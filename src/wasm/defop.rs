//! Deformation operators (DefOp) for JavaScript: `DefOpTrainer` trains one in time slices
//! (`advance(budgetMs)`), `DefOp` evaluates it, `groundTruth` solves the variational
//! deformation it approximates. Everything goes through `crate::defop`; options are read by
//! the one options reader.

use wasm_bindgen::prelude::*;

use super::error::BindingError;
use super::mesh::{read_mesh, JsMesh};
use super::puppet::{joints_to_js, parts_to_js, read_optional_puppet};
use super::read::{self, Options};
use super::{flat, limits, object, pairs};
use crate::defop::sampling::{Region, Sampling};
use crate::defop::{
    read_operator, write_operator_in, BasisKind, Energy, GroundTruth, GroundTruthOptions, Handles, MeshPoint, Operator,
    Precision, Progress, SinglePrecision, Start, TrainError, TrainOptions, Trainer,
};
use crate::deform::Puppet;
use crate::mesh::Mesh;

/// The trainer's option names.
const TRAINER_OPTIONS: [&str; 11] =
    ["energy", "basis", "samples", "radius", "sampling", "spatial", "seed", "canonical", "fixed", "parts", "joints"];
const ENERGIES: [(&str, Energy); 2] = [("sarap", Energy::SArap), ("arap", Energy::Arap)];
const BASES: [(&str, BasisKind); 4] = [
    ("linear", BasisKind::Linear),
    ("quadratic", BasisKind::Quadratic),
    ("cubic", BasisKind::Cubic),
    ("tps", BasisKind::Tps),
];
const SAMPLINGS: [(&str, Sampling); 3] =
    [("disc", Sampling::Disc), ("voronoi", Sampling::Voronoi), ("mixed", Sampling::Mixed)];
const PRECISIONS: [(&str, Precision); 2] = [("double", Precision::Double), ("single", Precision::Single)];

/// The JavaScript name of `value` in `names` (every value has one).
fn name_of<T: PartialEq + Copy>(names: &[(&'static str, T)], value: T) -> &'static str {
    names.iter().find(|(_, v)| *v == value).map_or("", |(name, _)| name)
}

/// Reads `{ energy?, basis?, samples?, radius?, sampling?, spatial?, seed?, canonical?,
/// fixed?, parts?, joints? }` (`parts` and `joints`: a puppet's, as the `Deformer` takes
/// them; joints need parts).
fn train_options(value: &JsValue) -> Result<TrainOptions, BindingError> {
    let given = Options::read(value, "DefOp training", &TRAINER_OPTIONS)?;
    let mut options = TrainOptions::default();
    options.energy = given.choice("energy", &ENERGIES)?.unwrap_or(options.energy);
    options.basis = given.choice("basis", &BASES)?.unwrap_or(options.basis);
    options.sampling = given.choice("sampling", &SAMPLINGS)?.unwrap_or(options.sampling);
    options.samples = given.count("samples", crate::defop::train::MAX_SAMPLES)?.unwrap_or(options.samples);
    options.spatial = given.count("spatial", limits().max_vertices)?.unwrap_or(options.spatial);
    options.seed = given.count("seed", u32::MAX as usize)?.map_or(options.seed, |s| s as u64);
    if let Some(radius) = given.number("radius")? {
        if !(radius.is_finite() && radius > 0.0) {
            return Err(BindingError::option(format!("option radius is {radius}, expected a positive length")));
        }
        options.radius = Some(radius);
    }
    options.canonical = given.boolean("canonical")?.unwrap_or(options.canonical);
    if let Some(value) = given.get("fixed") {
        let most = limits().max_vertices;
        let list = read::list(value, "fixed", most).map_err(|e| BindingError::option(e.message()))?;
        options.fixed = list
            .iter()
            .map(|a| {
                let index = a.as_f64().filter(|x| x.fract() == 0.0 && *x >= 0.0 && *x < most as f64);
                index.map(|x| x as usize).ok_or_else(|| given.wrong_type("fixed", "an array of handle indices", value))
            })
            .collect::<Result<_, _>>()?;
    }
    options.puppet = given_puppet(&given)?;
    Ok(options)
}

/// The puppet of options `{ parts?, joints? }`, as the `Deformer`'s options give it.
fn given_puppet(given: &Options) -> Result<Option<Puppet>, BindingError> {
    let none = JsValue::UNDEFINED;
    read_optional_puppet(given.get("parts").unwrap_or(&none), given.get("joints").unwrap_or(&none))
}

/// Handles at vertices (a `Uint32Array`), as mesh points.
fn vertex_handles(value: &JsValue) -> Result<Vec<MeshPoint>, BindingError> {
    Ok(read::uint32s(value, "handles", limits().max_vertices)?.into_iter().map(MeshPoint::Vertex).collect())
}

/// Handles in triangles: indices (`Uint32Array`) and 3 barycentric coordinates each.
fn point_handles(triangles: &JsValue, barycentric: &JsValue) -> Result<Vec<MeshPoint>, BindingError> {
    let most = limits().max_vertices;
    let triangles = read::uint32s(triangles, "triangles", most)?;
    let weights = read::float64s(barycentric, "barycentric", 3 * most)?;
    let (weights, rest) = weights.as_chunks::<3>();
    if !rest.is_empty() || weights.len() != triangles.len() {
        return Err(BindingError::argument(format!(
            "barycentric has {} numbers; {} triangles need 3 each",
            3 * weights.len() + rest.len(),
            triangles.len()
        )));
    }
    Ok(triangles
        .iter()
        .zip(weights)
        .map(|(&triangle, &barycentric)| MeshPoint::Inside { triangle, barycentric })
        .collect())
}

/// `{ done, total, stage }`.
fn progress_object(p: Progress) -> Result<JsValue, BindingError> {
    Ok(object(&[
        ("done", (p.done as f64).into()),
        ("total", (p.total as f64).into()),
        ("stage", JsValue::from_str(p.stage)),
    ])?
    .into())
}

/// The milliseconds of `performance.now()` (0 where there is none).
fn now() -> f64 {
    super::performance_now()
}

/// A deformation operator being trained.
#[wasm_bindgen(js_name = DefOpTrainer)]
pub struct JsDefOpTrainer {
    mesh: Mesh,
    options: TrainOptions,
    trainer: Option<Trainer>,
}

#[wasm_bindgen(js_class = DefOpTrainer)]
impl JsDefOpTrainer {
    /// A training for the mesh (`Float64Array` positions, `Uint32Array` triangles) with one
    /// handle on each vertex of `handles` (`Uint32Array`). `options`: `{ energy?: "sarap" |
    /// "arap", basis?: "linear" | "quadratic" | "cubic" | "tps", samples?, radius?, sampling?:
    /// "disc" | "voronoi" | "mixed", spatial? (0: hat functions, else the size of the reduced
    /// basis), seed?, canonical?: boolean (rigid motions of all handles reproduced exactly),
    /// fixed?: number[] (handles, by their index in `handles`, held at rest) }`. Checks
    /// everything and computes the spatial basis.
    #[wasm_bindgen(constructor)]
    pub fn new(
        positions: JsValue,
        triangles: JsValue,
        handles: JsValue,
        options: JsValue,
    ) -> Result<JsDefOpTrainer, BindingError> {
        let options = train_options(&options)?;
        let mesh = read_mesh(&positions, &triangles)?;
        let handles = vertex_handles(&handles)?;
        Self::with(mesh, &handles, options)
    }

    /// A training with handles at points in triangles (`Uint32Array` triangles, `Float64Array`
    /// barycentric coordinates, 3 each); otherwise as the constructor.
    #[wasm_bindgen(js_name = withHandlePoints)]
    pub fn with_handle_points(
        positions: JsValue,
        triangles: JsValue,
        handle_triangles: JsValue,
        barycentric: JsValue,
        options: JsValue,
    ) -> Result<JsDefOpTrainer, BindingError> {
        let options = train_options(&options)?;
        let mesh = read_mesh(&positions, &triangles)?;
        let handles = point_handles(&handle_triangles, &barycentric)?;
        Self::with(mesh, &handles, options)
    }

    fn with(mesh: Mesh, handles: &[MeshPoint], options: TrainOptions) -> Result<JsDefOpTrainer, BindingError> {
        let trainer = Trainer::new(&mesh, handles, options.clone())?;
        Ok(Self { mesh, options, trainer: Some(trainer) })
    }

    /// Handles at points in triangles instead (`Uint32Array` triangles, `Float64Array`
    /// barycentric coordinates, 3 each): training starts again with them.
    #[wasm_bindgen(js_name = setHandlePoints)]
    pub fn set_handle_points(&mut self, triangles: JsValue, barycentric: JsValue) -> Result<(), BindingError> {
        let handles = point_handles(&triangles, &barycentric)?;
        self.trainer = Some(Trainer::new(&self.mesh, &handles, self.options.clone())?);
        Ok(())
    }

    /// Trains for about `budgetMs` milliseconds (a sample's solve, once begun, is finished)
    /// and returns `{ done, total, stage }`.
    pub fn advance(&mut self, budget_ms: JsValue) -> Result<JsValue, BindingError> {
        let budget = read::number(&budget_ms, "budgetMs")?;
        let trainer = self.trainer_mut()?;
        progress_object(trainer.advance(budget, now)?)
    }

    /// Up to `max` sample solves for workers: `[{ index, targets: Float64Array, start:
    /// Float64Array | undefined }]` (none while a batch's results are outstanding). A worker
    /// solves each with a `DefOpSolver` made from the same mesh, handles and energy and
    /// hands the result to `submit`, or its failure to `reject`.
    #[wasm_bindgen(js_name = nextJobs)]
    pub fn next_jobs(&mut self, max: JsValue) -> Result<js_sys::Array, BindingError> {
        let max = read::count(&max, "max", crate::defop::train::MAX_SAMPLES)?;
        let jobs = self.trainer_mut()?.next_jobs(max)?;
        let list = js_sys::Array::new();
        for job in jobs {
            let start = job.start.as_deref().map_or(JsValue::UNDEFINED, |s| flat(s).into());
            let entry = object(&[
                ("index", (job.index as f64).into()),
                ("targets", flat(&job.targets).into()),
                ("start", start),
            ])?;
            list.push(&entry);
        }
        Ok(list)
    }

    /// A worker's result for job `index`: the vertex positions (`Float64Array`), the Newton
    /// iterations, whether it fell back to the rest pose, whether it started warm. Returns
    /// `{ done, total, stage }`.
    pub fn submit(
        &mut self,
        index: JsValue,
        positions: JsValue,
        iterations: JsValue,
        fallback: JsValue,
        warm: JsValue,
    ) -> Result<JsValue, BindingError> {
        let index = read::count(&index, "index", crate::defop::train::MAX_SAMPLES)?;
        let positions = pairs(&read::float64s(&positions, "positions", 2 * limits().max_vertices)?, "positions")?;
        let iterations = read::count(&iterations, "iterations", usize::MAX >> 11)?;
        let progress =
            self.trainer_mut()?.submit(index, &positions, iterations, fallback.is_truthy(), warm.is_truthy())?;
        progress_object(progress)
    }

    /// Job `index`'s solve threw with this `code`: for `"no-convergence"` and
    /// `"invalid-argument"` (targets no flip-free pose reaches) its sample is drawn again
    /// and the job handed out again; any other code ends the training with an error.
    pub fn reject(&mut self, index: JsValue, code: JsValue) -> Result<(), BindingError> {
        let index = read::count(&index, "index", crate::defop::train::MAX_SAMPLES)?;
        let code = read::string(&code, "code", 64)?;
        if !matches!(code.as_str(), "no-convergence" | "invalid-argument") {
            return Err(BindingError::argument(format!(
                "a sample's solve failed with code {code:?}; training cannot go on"
            )));
        }
        Ok(self.trainer_mut()?.redraw(index)?)
    }

    /// The sampling radius in use (the `radius` option, or its default from the mesh's size):
    /// targets are drawn within it of each handle's rest place.
    #[wasm_bindgen(getter)]
    pub fn radius(&self) -> Result<f64, BindingError> {
        Ok(self.trainer_ref()?.radius())
    }

    /// `{ done, total, stage }` without training.
    pub fn progress(&self) -> Result<JsValue, BindingError> {
        progress_object(self.trainer_ref()?.progress())
    }

    /// Solver iterations so far: `{ cold, coldIterations, warm, warmIterations, fallbacks,
    /// neighbourStarts, redraws }`.
    pub fn stats(&self) -> Result<JsValue, BindingError> {
        let s = self.trainer_ref()?.stats();
        Ok(object(&[
            ("cold", (s.cold.0 as f64).into()),
            ("coldIterations", (s.cold.1 as f64).into()),
            ("warm", (s.warm.0 as f64).into()),
            ("warmIterations", (s.warm.1 as f64).into()),
            ("fallbacks", (s.fallbacks as f64).into()),
            ("neighbourStarts", (s.neighbour_starts as f64).into()),
            ("redraws", (s.redraws as f64).into()),
        ])?
        .into())
    }

    /// The trained operator, once `done === total`; the trainer cannot be used after.
    pub fn finish(&mut self) -> Result<JsDefOp, BindingError> {
        let trainer = self.trainer.take().ok_or_else(finished)?;
        let progress = trainer.progress();
        if progress.done < progress.total {
            self.trainer = Some(trainer);
            return Err(TrainError::NotDone { done: progress.done, total: progress.total }.into());
        }
        Ok(JsDefOp::new(self.mesh.clone(), trainer.finish()?))
    }

    fn trainer_ref(&self) -> Result<&Trainer, BindingError> {
        self.trainer.as_ref().ok_or_else(finished)
    }

    fn trainer_mut(&mut self) -> Result<&mut Trainer, BindingError> {
        self.trainer.as_mut().ok_or_else(finished)
    }
}

fn finished() -> BindingError {
    BindingError::argument("this DefOpTrainer has finished; its operator was returned by finish()")
}

/// A trained deformation operator, with its mesh.
#[wasm_bindgen(js_name = DefOp)]
pub struct JsDefOp {
    mesh: Mesh,
    operator: Operator,
    /// The last positions evaluated into a caller's array (2N numbers; sized once, so that
    /// `evaluateInto` allocates nothing per frame beyond reading the targets).
    scratch: Vec<f64>,
    /// The same in single precision.
    scratch32: Vec<f32>,
    /// The operator's single-precision copy, made at the first `evaluateIntoF32`.
    single: Option<SinglePrecision>,
    /// Its training's sampling regions, once asked for.
    regions: std::cell::OnceCell<Vec<Region>>,
}

impl JsDefOp {
    /// The trained operator (a deformer poses with a copy).
    pub(super) fn operator(&self) -> &Operator {
        &self.operator
    }

    fn new(mesh: Mesh, operator: Operator) -> Self {
        let n = 2 * operator.vertex_count();
        let regions = std::cell::OnceCell::new();
        Self { mesh, operator, scratch: vec![0.0; n], scratch32: vec![0.0; n], single: None, regions }
    }

    /// Its training's regions for its own mesh (computed once: neither changes).
    fn sampling_regions(&self) -> Result<&[Region], BindingError> {
        if self.regions.get().is_none() {
            let regions = self
                .operator
                .sampling_regions(&self.mesh)
                .map_err(|e| BindingError::argument(format!("the operator's sampling regions: {e}")))?;
            let _ = self.regions.set(regions);
        }
        Ok(self.regions.get().map_or(&[], Vec::as_slice))
    }

    /// Refuses an output array of the wrong length.
    fn check_out(&self, length: u32) -> Result<(), BindingError> {
        let n = self.scratch.len();
        if length as usize != n {
            return Err(BindingError::argument(format!(
                "out has {length} numbers; the mesh's {} vertices need {n}",
                n / 2
            )));
        }
        Ok(())
    }
}

/// The largest operator file read, in bytes (the most a training may make).
const MAX_OPERATOR_BYTES: usize = crate::defop::train::MAX_TRAINING_BYTES;

#[wasm_bindgen(js_class = DefOp)]
impl JsDefOp {
    /// An operator file (`Uint8Array`), as `toBytes` writes it: checked fully (a truncated
    /// or altered file is an `Error` with code `import`).
    #[wasm_bindgen(js_name = fromBytes)]
    pub fn from_bytes(bytes: JsValue) -> Result<JsDefOp, BindingError> {
        let bytes = read::bytes(&bytes, "bytes", MAX_OPERATOR_BYTES)?;
        let (mesh, operator) = read_operator(&bytes).map_err(TrainError::from)?;
        Ok(Self::new(mesh, operator))
    }

    /// The operator file: the operator and its mesh (`Uint8Array`). `options`: `{
    /// precision?: "double" | "single" }` (single: the coefficients as f32, half the size).
    #[wasm_bindgen(js_name = toBytes)]
    pub fn to_bytes(&self, options: JsValue) -> Result<Vec<u8>, BindingError> {
        let given = Options::read(&options, "operator file", &["precision"])?;
        let precision = given.choice("precision", &PRECISIONS)?.unwrap_or_default();
        Ok(write_operator_in(&self.mesh, &self.operator, precision).map_err(TrainError::from)?)
    }

    /// The settings it was trained with, `{ energy, basis, spatial, samples, sampling,
    /// radius, seed, canonical, fixed }` (the trainer's option names and values; `radius`
    /// resolved, `fixed` a `Uint32Array`), or undefined when they are not known (a file
    /// older than version 4).
    #[wasm_bindgen(getter)]
    pub fn training(&self) -> Result<JsValue, BindingError> {
        let Some(t) = self.operator.training() else { return Ok(JsValue::UNDEFINED) };
        let basis = self.operator.handle_basis();
        let spatial = if !self.operator.reduction().is_empty() { self.operator.spatial_len() } else { 0 };
        let fixed: Vec<u32> = basis.coordinates().fixed().iter().map(|&a| a as u32).collect();
        Ok(object(&[
            ("energy", JsValue::from_str(name_of(&ENERGIES, t.energy))),
            ("basis", JsValue::from_str(name_of(&BASES, basis.kind()))),
            ("spatial", (spatial as f64).into()),
            ("samples", (t.samples as f64).into()),
            ("sampling", JsValue::from_str(name_of(&SAMPLINGS, t.sampling))),
            ("radius", t.radius.into()),
            ("seed", (t.seed as f64).into()),
            ("canonical", basis.coordinates().is_canonical().into()),
            ("fixed", js_sys::Uint32Array::from(fixed.as_slice()).into()),
        ])?
        .into())
    }

    /// Where its training drew each handle's targets (Rust's `sampling::regions`, the one
    /// definition the sampler draws from): `{ sampling, radius, centres: Float64Array (the
    /// rest handles, 2 each), discs: boolean, cells: Float64Array[] | undefined }`: discs of
    /// `radius` about the centres (disc and mixed sampling) and each handle's Voronoi cell, a
    /// convex polygon counter-clockwise, x and y per corner (Voronoi and mixed). For an
    /// operator whose training is not known, the discs of radius its scale.
    pub fn regions(&self) -> Result<JsValue, BindingError> {
        let regions = self.sampling_regions()?;
        let (sampling, radius) = self.operator.sampling();
        let centres: Vec<[f64; 2]> = regions.iter().map(|r| r.centre).collect();
        let cells = if regions.iter().all(|r| r.cell.is_some()) {
            let list = js_sys::Array::new();
            regions.iter().filter_map(|r| r.cell.as_deref()).for_each(|cell| {
                list.push(&flat(cell));
            });
            list.into()
        } else {
            JsValue::UNDEFINED
        };
        Ok(object(&[
            ("sampling", JsValue::from_str(name_of(&SAMPLINGS, sampling))),
            ("radius", radius.into()),
            ("centres", flat(&centres).into()),
            ("discs", JsValue::from_bool(regions.iter().all(|r| r.radius.is_some()))),
            ("cells", cells),
        ])?
        .into())
    }

    /// For handle targets (`Float64Array`, 2 per handle): a `Uint8Array`, 1 for each handle
    /// whose target lies outside every region its training drew targets from (the operator
    /// extrapolates there), else 0.
    #[wasm_bindgen(js_name = outsideRegions)]
    pub fn outside_regions(&self, targets: JsValue) -> Result<Vec<u8>, BindingError> {
        let targets = pairs(&read::float64s(&targets, "targets", 2 * limits().max_vertices)?, "targets")?;
        let regions = self.sampling_regions()?;
        if targets.len() != regions.len() {
            return Err(BindingError::argument(format!(
                "targets has {} points; the operator has {} handles",
                targets.len(),
                regions.len()
            )));
        }
        Ok(regions.iter().zip(&targets).map(|(r, &q)| u8::from(!r.contains(q))).collect())
    }

    /// The operator's mesh at rest.
    pub fn mesh(&self) -> JsMesh {
        JsMesh { mesh: self.mesh.clone() }
    }

    /// The vertex positions (`Float64Array`, 2 per vertex) for handle targets (`Float64Array`,
    /// 2 per handle).
    pub fn evaluate(&mut self, targets: JsValue) -> Result<Vec<f64>, BindingError> {
        let targets = read::float64s(&targets, "targets", 2 * limits().max_vertices)?;
        Ok(self.operator.evaluate(&targets).map_err(TrainError::from)?)
    }

    /// [`Self::evaluate`] into `out` (`Float64Array` of 2 numbers per vertex).
    #[wasm_bindgen(js_name = evaluateInto)]
    pub fn evaluate_into(&mut self, targets: JsValue, out: &js_sys::Float64Array) -> Result<(), BindingError> {
        self.check_out(out.length())?;
        let targets = read::float64s(&targets, "targets", 2 * limits().max_vertices)?;
        self.operator.evaluate_into(&targets, &mut self.scratch).map_err(TrainError::from)?;
        out.copy_from(&self.scratch);
        Ok(())
    }

    /// [`Self::evaluate_into`] in single precision (`Float32Array` out): computed by the
    /// operator's single-precision copy (`crate::defop::SinglePrecision`, made at the first
    /// call: 4 bytes per coefficient), within about (|Ψ| + |Φ|) ε_32 of the double pose's
    /// terms' magnitudes.
    #[wasm_bindgen(js_name = evaluateIntoF32)]
    pub fn evaluate_into_f32(&mut self, targets: JsValue, out: &js_sys::Float32Array) -> Result<(), BindingError> {
        self.check_out(out.length())?;
        let targets = read::float64s(&targets, "targets", 2 * limits().max_vertices)?;
        let single = self.single.get_or_insert_with(|| self.operator.single_precision());
        single.evaluate_into(&targets, &mut self.scratch32).map_err(TrainError::from)?;
        out.copy_from(&self.scratch32);
        Ok(())
    }

    /// The handles as points in triangles, in the operator's order: `{ triangles:
    /// Uint32Array, barycentric: Float64Array }` (3 each; a handle trained on a vertex is
    /// given in the first triangle of the vertex, with 1 at its corner).
    #[wasm_bindgen(js_name = handlePoints)]
    pub fn handle_points(&self) -> Result<JsValue, BindingError> {
        let handles = self.operator.handles();
        let mut triangles = Vec::with_capacity(handles.len());
        let mut barycentric = Vec::with_capacity(3 * handles.len());
        for handle in handles {
            let (triangle, weights) = match *handle {
                MeshPoint::Inside { triangle, barycentric } => (triangle, barycentric),
                MeshPoint::Vertex(v) => {
                    // A valid mesh has no unused vertex, so some triangle has it.
                    let (t, corner) = self
                        .mesh
                        .triangles()
                        .iter()
                        .enumerate()
                        .find_map(|(t, tri)| tri.iter().position(|&c| c == v).map(|corner| (t, corner)))
                        .ok_or_else(|| BindingError::argument(format!("handle vertex {v} is in no triangle")))?;
                    let mut weights = [0.0; 3];
                    weights[corner] = 1.0;
                    (t as u32, weights)
                }
            };
            triangles.push(triangle);
            barycentric.extend_from_slice(&weights);
        }
        Ok(object(&[
            ("triangles", js_sys::Uint32Array::from(triangles.as_slice()).into()),
            ("barycentric", js_sys::Float64Array::from(barycentric.as_slice()).into()),
        ])?
        .into())
    }

    /// The scale of its handle coordinates, `u = (Q − P) / r`: for an operator trained by
    /// `DefOpTrainer`, the training's sampling radius (files keep it).
    #[wasm_bindgen(getter)]
    pub fn radius(&self) -> f64 {
        self.operator.handle_basis().scale()
    }

    /// The number of handles.
    #[wasm_bindgen(getter, js_name = handleCount)]
    pub fn handle_count(&self) -> usize {
        self.operator.handles().len()
    }

    /// The number of mesh vertices.
    #[wasm_bindgen(getter, js_name = vertexCount)]
    pub fn vertex_count(&self) -> usize {
        self.operator.vertex_count()
    }

    /// The parts of the puppet the operator was trained on (`[{ name, triangles, depth }]`),
    /// or undefined for one shape.
    #[wasm_bindgen(getter)]
    pub fn parts(&self) -> Result<JsValue, BindingError> {
        match self.operator.puppet() {
            Some(puppet) => Ok(parts_to_js(&puppet.parts)?.into()),
            None => Ok(JsValue::UNDEFINED),
        }
    }

    /// The joints of the puppet the operator was trained on (`[{ point, parts: [front,
    /// back] }]`), or undefined for one shape.
    #[wasm_bindgen(getter)]
    pub fn joints(&self) -> Result<JsValue, BindingError> {
        match self.operator.puppet() {
            Some(puppet) => Ok(joints_to_js(&puppet.joints)?.into()),
            None => Ok(JsValue::UNDEFINED),
        }
    }
}

/// A ground-truth solver for a worker of a `DefOpTrainer`: made from the same mesh, handles
/// and energy, it gives the same ground truths as the trainer's own.
#[wasm_bindgen(js_name = DefOpSolver)]
pub struct JsDefOpSolver {
    solver: GroundTruth,
}

#[wasm_bindgen(js_class = DefOpSolver)]
impl JsDefOpSolver {
    /// For the mesh with one handle on each vertex of `handles` (`Uint32Array`);
    /// `options`: `{ energy?: "sarap" | "arap" }`, the trainer's.
    #[wasm_bindgen(constructor)]
    pub fn new(
        positions: JsValue,
        triangles: JsValue,
        handles: JsValue,
        options: JsValue,
    ) -> Result<JsDefOpSolver, BindingError> {
        let handles = vertex_handles(&handles)?;
        Self::made(&positions, &triangles, &handles, &options)
    }

    /// For handles at points in triangles (as `DefOpTrainer.setHandlePoints` takes them).
    #[wasm_bindgen(js_name = withHandlePoints)]
    pub fn with_handle_points(
        positions: JsValue,
        triangles: JsValue,
        handle_triangles: JsValue,
        barycentric: JsValue,
        options: JsValue,
    ) -> Result<JsDefOpSolver, BindingError> {
        let handles = point_handles(&handle_triangles, &barycentric)?;
        Self::made(&positions, &triangles, &handles, &options)
    }

    fn made(
        positions: &JsValue,
        triangles: &JsValue,
        handles: &[MeshPoint],
        options: &JsValue,
    ) -> Result<JsDefOpSolver, BindingError> {
        let given = Options::read(options, "DefOp solver", &["energy"])?;
        let energy = given.choice("energy", &ENERGIES)?.unwrap_or(Energy::SArap);
        let mesh = read_mesh(positions, triangles)?;
        let options = TrainOptions { energy, ..TrainOptions::default() };
        Ok(Self { solver: Trainer::solver_for(&mesh, handles, &options)? })
    }

    /// Solves for `targets` (`Float64Array`, 2 per handle) from `start` (`Float64Array`, 2 per
    /// vertex; `undefined`: the rest pose): `{ positions, iterations, fallback }`.
    pub fn solve(&mut self, targets: JsValue, start: JsValue) -> Result<JsValue, BindingError> {
        let most = 2 * limits().max_vertices;
        let targets = pairs(&read::float64s(&targets, "targets", most)?, "targets")?;
        let start = if start.is_undefined() || start.is_null() {
            None
        } else {
            Some(pairs(&read::float64s(&start, "start", most)?, "start")?)
        };
        let from = start.as_deref().map_or(Start::Rest, Start::Pose);
        let report = self.solver.solve(&targets, from).map_err(TrainError::from)?;
        Ok(object(&[
            ("positions", flat(&report.positions).into()),
            ("iterations", (report.iterations as f64).into()),
            ("fallback", JsValue::from_bool(report.fallback)),
        ])?
        .into())
    }
}

/// The variational deformation a DefOp approximates: the mesh's pose of least ARAP or
/// S-ARAP energy with a handle on each vertex of `handles` (`Uint32Array`) exactly at
/// `targets` (`Float64Array`, 2 per handle), from the rest pose. `options`: `{ energy?:
/// "sarap" | "arap", parts?, joints? }` (a puppet's, joined at its joints). Returns the
/// positions (`Float64Array`, 2 per vertex).
#[wasm_bindgen(js_name = groundTruth)]
pub fn ground_truth(
    positions: JsValue,
    triangles: JsValue,
    handles: JsValue,
    targets: JsValue,
    options: JsValue,
) -> Result<Vec<f64>, BindingError> {
    let given = Options::read(&options, "ground truth", &["energy", "parts", "joints"])?;
    let energy = given.choice("energy", &ENERGIES)?.unwrap_or(Energy::SArap);
    let puppet = given_puppet(&given)?;
    let mesh = read_mesh(&positions, &triangles)?;
    let handles = read::uint32s(&handles, "handles", limits().max_vertices)?;
    let targets = pairs(&read::float64s(&targets, "targets", 2 * limits().max_vertices)?, "targets")?;
    let (h, o) = (Handles::Vertices(&handles), GroundTruthOptions::default());
    let mut solver = match &puppet {
        Some(puppet) => GroundTruth::with_puppet(&mesh, puppet, h, energy, o),
        None => GroundTruth::new(&mesh, h, energy, o),
    }
    .map_err(TrainError::from)?;
    let report = solver.solve(&targets, Start::Rest).map_err(TrainError::from)?;
    Ok(report.positions.iter().flatten().copied().collect())
}
