/**
 * Deformation operators (DefOp): a closed-form deformation trained once on sampled
 * variational deformations (ARAP or the paper's symmetric S-ARAP), then evaluated per
 * frame by a few matrix-vector products. Training runs in slices of a time budget, so a
 * page stays responsive: call {@link DefOpTrainer.advance} from a timer or a worker until
 * `done === total`, then {@link DefOpTrainer.finish}.
 *
 * @example
 * ```ts
 * import { init, defaultShape, triangulate, DefOpTrainer } from "akap";
 * await init();
 * const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.08 });
 * const trainer = new DefOpTrainer(mesh.positions, mesh.triangles, [0, 42], { samples: 50 });
 * while (trainer.advance(20).stage !== "done");
 * const op = trainer.finish();
 * const posed = op.evaluate([0, 0, 0.1, 0.3]); // two targets, x and y each
 * ```
 */
import {
  handleArrays,
  toFloat64,
  toUint32,
  type Coordinates,
  type HandleSpec,
  type Indices,
} from "./internal/arrays.js";
import type { MeshData, PuppetJoint, PuppetSheet } from "./core.js";
import { readMesh } from "./internal/mesh.js";
import { assertLoaded, raw, registerBinding, type rawTypes } from "./internal/wasm.js";

/** Options of a {@link DefOpTrainer}. */
export interface DefOpTrainerOptions {
  /** The ground truth's energy: `"sarap"` (default, the paper's; never folds a triangle) or `"arap"`. */
  energy?: "sarap" | "arap";
  /** The handle basis: `"tps"` (default, one function per sample), `"linear"`, `"quadratic"` or `"cubic"`. */
  basis?: "linear" | "quadratic" | "cubic" | "tps";
  /** Samples beyond the rest pose, 1 to 100000 (default 200). */
  samples?: number;
  /** Radius of the sampling discs (default 0.15 of the shape's bounding-box diagonal). */
  radius?: number;
  /** Where targets are drawn: in discs around the handles (default), their Voronoi cells, or both. */
  sampling?: "disc" | "voronoi" | "mixed";
  /** 0 (default): the mesh's hat functions; else the size of the reduced spatial basis (at least 3). */
  spatial?: number;
  /** Seed of the samples, a whole number (default 1): the same seed gives the same operator. */
  seed?: number;
  /**
   * Canonical handle coordinates (default false): the operator then reproduces a rigid motion
   * of all handles exactly (the shape moves rigidly with them) and is equivariant,
   * D(x, RQ + t) = R D(x, Q) + t. It works on the targets with their best-fitting rotation and
   * translation taken out, so its handle space is 3 dimensions smaller (a single handle just
   * translates the shape). Not with `fixed`.
   */
  canonical?: boolean;
  /**
   * Handles held at their rest position in every training sample, by their index in `handles`
   * (default none): the operator keeps them there, and ignores the targets given for them.
   */
  fixed?: number[];
  /**
   * A puppet's parts (as the `Deformer` and `importPuppet` give them; other fields, such as
   * `paths`, are left alone): the ground truth then keeps each joint's two points together,
   * holds the sheets no handle reaches where they are, and the operator (and its file)
   * records the puppet, so that its rig poses only that puppet. A mesh in several pieces
   * needs them.
   */
  parts?: readonly PuppetSheet[];
  /** The puppet's joints (needs `parts`; none if left out). */
  joints?: readonly PuppetJoint[];
}

export type { HandleSpec } from "./internal/arrays.js";

/** How far training is: `done` of `total` units (one per sample, one for the final fit). */
export interface DefOpProgress {
  done: number;
  total: number;
  /** `"samples"`, `"fit"` (only the final fit left) or `"done"`. */
  stage: "samples" | "fit" | "done";
}

/** Newton iterations of the training's ground-truth solves. */
export interface DefOpStats {
  /** Solves from the rest pose, and their iterations in all. */
  cold: number;
  coldIterations: number;
  /** Solves from the operator's prediction (or the nearest solved sample), and their iterations. */
  warm: number;
  warmIterations: number;
  /** Warm starts that fell back to the rest pose. */
  fallbacks: number;
  /** Warm starts from the nearest solved sample, the prediction having folded a triangle. */
  neighbourStarts: number;
  /** Samples drawn again because no flip-free pose reaches their targets. */
  redraws: number;
}

/**
 * One sample's solve, for a worker: structured-clonable, so it can be posted as it is.
 * `start` is the pose to start from (the operator fitted so far), or the rest pose.
 */
export interface DefOpJob {
  index: number;
  /** 2 numbers per handle. */
  targets: Float64Array;
  /** 2 numbers per vertex, or `undefined` for the rest pose. */
  start: Float64Array | undefined;
}

/** A worker's solution of a {@link DefOpJob}, for {@link DefOpTrainer.submit}. */
export interface DefOpJobResult {
  index: number;
  /** 2 numbers per vertex. */
  positions: Float64Array;
  iterations: number;
  /** Whether a folded start made the solve start again from the rest pose. */
  fallback: boolean;
  /** Whether the job had a start. */
  warm: boolean;
}

/** The operator {@link DefOpTrainer.finish} hands to the {@link DefOp} it makes. */
let adopting: rawTypes.DefOp | undefined;

/** Trains a {@link DefOp} for a mesh and a set of handles. */
export class DefOpTrainer {
  #inner: rawTypes.DefOpTrainer | undefined;

  /**
   * @param positions xy-interleaved vertex positions
   * @param triangles counter-clockwise index triples
   * @param handles one handle on each of these vertices, or at points in triangles (3
   *   barycentric coordinates each)
   */
  constructor(positions: Coordinates, triangles: Indices, handles: HandleSpec, options: DefOpTrainerOptions = {}) {
    assertLoaded();
    const p = toFloat64(positions, "positions");
    const t = toUint32(triangles, "triangles");
    const h = handleArrays(handles);
    this.#inner =
      h instanceof Uint32Array
        ? new raw.DefOpTrainer(p, t, h, options)
        : raw.DefOpTrainer.withHandlePoints(p, t, h.triangles, h.barycentric, options);
  }

  get #raw(): rawTypes.DefOpTrainer {
    if (!this.#inner) throw new Error("this DefOpTrainer was freed or finished");
    return this.#inner;
  }

  /** Handles at points in triangles (3 barycentric coordinates each) instead; training starts again. */
  setHandlePoints(triangles: Indices, barycentric: Coordinates): void {
    this.#raw.setHandlePoints(toUint32(triangles, "triangles"), toFloat64(barycentric, "barycentric"));
  }

  /** The sampling radius in use (the `radius` option, or its default from the mesh's size). */
  get radius(): number {
    return this.#raw.radius;
  }

  /** Trains for about `budgetMs` milliseconds (a sample, once begun, is finished). */
  advance(budgetMs: number): DefOpProgress {
    return this.#raw.advance(budgetMs) as DefOpProgress;
  }

  /**
   * Up to `max` sample solves to hand to workers (none while a batch's results are still
   * out: the next batch starts from the operator fitted to it). Each worker solves with a
   * {@link DefOpSolver} made from the same mesh, handles and energy, and its result goes to
   * {@link submit}, its failure to {@link reject}.
   */
  nextJobs(max: number): DefOpJob[] {
    return this.#raw.nextJobs(max) as DefOpJob[];
  }

  /** Takes a worker's result; refits and opens the next batch when a batch is complete. */
  submit(result: DefOpJobResult): DefOpProgress {
    const { index, positions, iterations, fallback, warm } = result;
    return this.#raw.submit(index, positions, iterations, fallback, warm) as DefOpProgress;
  }

  /**
   * A job's solve threw `error`: for codes `no-convergence` and `invalid-argument` (targets
   * no flip-free pose reaches) its sample is drawn again and the job handed out again;
   * anything else throws.
   */
  reject(index: number, error: unknown): void {
    const code = (error as { code?: unknown } | undefined)?.code;
    this.#raw.reject(index, typeof code === "string" ? code : "internal");
  }

  /** How far training is, without training. */
  progress(): DefOpProgress {
    return this.#raw.progress() as DefOpProgress;
  }

  /** Newton iterations so far, cold and warm. */
  stats(): DefOpStats {
    return this.#raw.stats() as DefOpStats;
  }

  /** The trained operator, once `done === total`; the trainer is freed. */
  finish(): DefOp {
    adopting = this.#raw.finish();
    const op = new DefOp();
    this.free();
    return op;
  }

  /** Releases the WebAssembly memory. */
  free(): void {
    this.#inner?.free();
    this.#inner = undefined;
  }
}

/**
 * The settings a {@link DefOp} was trained with, as {@link DefOpTrainerOptions} names them
 * (`radius` the one used, given or by default): what its file keeps (version 4).
 */
export interface DefOpTraining {
  energy: "sarap" | "arap";
  basis: "linear" | "quadratic" | "cubic" | "tps";
  /** 0: the hat functions; else the size of the reduced spatial basis. */
  spatial: number;
  samples: number;
  sampling: "disc" | "voronoi" | "mixed";
  radius: number;
  seed: number;
  canonical: boolean;
  fixed: Uint32Array;
}

/**
 * Where a {@link DefOp}'s training drew each handle's targets (Rust's
 * `akap::defop::sampling::regions`, the one definition its sampler draws from): discs of
 * `radius` about the rest handles (`"disc"` and `"mixed"` sampling) and each handle's
 * Voronoi cell among the rest handles, clipped to the shape's bounding box grown by
 * `radius` (`"voronoi"` and `"mixed"`).
 */
export interface DefOpRegions {
  sampling: "disc" | "voronoi" | "mixed";
  radius: number;
  /** The handles' rest positions, 2 each: the discs' centres. */
  centres: Float64Array;
  /** Whether the discs are regions. */
  discs: boolean;
  /** Each handle's cell, a convex polygon counter-clockwise (x and y per corner), or undefined. */
  cells: Float64Array[] | undefined;
}

/** A trained deformation operator: handle targets in, vertex positions out. */
export class DefOp {
  #inner: rawTypes.DefOp | undefined;

  /** Made by {@link DefOpTrainer.finish}, not directly. */
  constructor() {
    if (!adopting) throw new Error("a DefOp is made by DefOpTrainer.finish()");
    this.#inner = adopting;
    adopting = undefined;
    registerBinding(this, this.#inner);
  }

  get #raw(): rawTypes.DefOp {
    if (!this.#inner) throw new Error("this DefOp was freed");
    return this.#inner;
  }

  /**
   * An operator file as {@link toBytes} writes it (the operator and its mesh), checked
   * fully: a truncated or altered file throws with code `import`.
   */
  static fromBytes(bytes: Uint8Array): DefOp {
    assertLoaded();
    adopting = raw.DefOp.fromBytes(bytes);
    return new DefOp();
  }

  /**
   * The operator file: the operator, its mesh and its training's settings, to save and load
   * with {@link fromBytes}. `precision: "single"` stores the coefficients (and a reduced
   * basis) as 32-bit floats, each the nearest to its double: about half the size.
   */
  toBytes(options: { precision?: "double" | "single" } = {}): Uint8Array {
    return this.#raw.toBytes(options);
  }

  /**
   * The settings it was trained with (its file keeps them), or `undefined` when they are
   * not known (a file written before version 4).
   */
  get training(): DefOpTraining | undefined {
    return this.#raw.training as DefOpTraining | undefined;
  }

  /**
   * Where its training drew each handle's targets: the disc, the Voronoi cell or both (for
   * an operator whose training is not known, discs of radius {@link radius}).
   */
  regions(): DefOpRegions {
    return this.#raw.regions() as DefOpRegions;
  }

  /**
   * For handle targets (2 per handle), 1 for each handle whose target lies outside every
   * region of {@link regions} (the operator extrapolates there), else 0.
   */
  outsideRegions(targets: Coordinates): Uint8Array {
    return this.#raw.outsideRegions(toFloat64(targets, "targets"));
  }

  /** The mesh at rest (the mesh it was trained for). */
  mesh(): MeshData {
    const mesh = this.#raw.mesh();
    try {
      return readMesh(mesh);
    } finally {
      mesh.free();
    }
  }

  /** The vertex positions (2 per vertex) for handle targets (2 per handle). */
  evaluate(targets: Coordinates): Float64Array {
    return this.#raw.evaluate(toFloat64(targets, "targets"));
  }

  /** {@link evaluate} into `out` (2 numbers per vertex), allocating nothing in JavaScript. */
  evaluateInto(targets: Coordinates, out: Float64Array): void {
    this.#raw.evaluateInto(toFloat64(targets, "targets"), out);
  }

  /**
   * {@link evaluateInto} in single precision: computed by the operator's single-precision
   * copy (made at the first call, 4 bytes per coefficient; Ψ(Q) in double, then `X Ψ` and
   * `Dᵀ (X Ψ)` in `f32`), about twice as fast as the double evaluation. Each position is
   * within `2 (|Ψ| + |Φ| + 6) ε₃₂` of the sum of the magnitudes of its terms
   * `Σ_i |D_iv| Σ_j |X_ij ψ_j|` from the double pose (ε₃₂ = 2⁻²³; `tests/defop_eval.rs`):
   * on the test figure within 3.7e-7 of the bounding box's diagonal, which
   * `tests/unit/defop.test.ts` checks (below 5e-7).
   */
  evaluateIntoF32(targets: Coordinates, out: Float32Array): void {
    this.#raw.evaluateIntoF32(toFloat64(targets, "targets"), out);
  }

  /**
   * The handles as points in triangles (3 barycentric coordinates each), in the operator's
   * order; a handle trained on a vertex is given in a triangle of that vertex.
   */
  handlePoints(): { triangles: Uint32Array; barycentric: Float64Array } {
    return this.#raw.handlePoints() as { triangles: Uint32Array; barycentric: Float64Array };
  }

  /**
   * The scale of its handle coordinates: for an operator trained by {@link DefOpTrainer},
   * the training's sampling radius (operator files keep it).
   */
  get radius(): number {
    return this.#raw.radius;
  }

  get handleCount(): number {
    return this.#raw.handleCount;
  }

  get vertexCount(): number {
    return this.#raw.vertexCount;
  }

  /** The parts of the puppet it was trained on (its file records them), or `undefined`
   * for one shape. */
  get parts(): PuppetSheet[] | undefined {
    return this.#raw.parts as PuppetSheet[] | undefined;
  }

  /** The joints of the puppet it was trained on, or `undefined` for one shape. */
  get joints(): PuppetJoint[] | undefined {
    return this.#raw.joints as PuppetJoint[] | undefined;
  }

  /** Releases the WebAssembly memory. */
  free(): void {
    this.#inner?.free();
    this.#inner = undefined;
    registerBinding(this, undefined);
  }
}

/** A worker's ground-truth solver for the jobs of a {@link DefOpTrainer}. */
export class DefOpSolver {
  #inner: rawTypes.DefOpSolver | undefined;

  /**
   * For the trainer's mesh and handles (vertices, or `{ triangles, barycentric }` as given
   * to {@link DefOpTrainer.setHandlePoints}) and its energy: the same solver as the
   * trainer's own, so the same ground truths.
   */
  constructor(
    positions: Coordinates,
    triangles: Indices,
    handles: HandleSpec,
    options: { energy?: "sarap" | "arap" } = {},
  ) {
    assertLoaded();
    const p = toFloat64(positions, "positions");
    const t = toUint32(triangles, "triangles");
    const h = handleArrays(handles);
    this.#inner =
      h instanceof Uint32Array
        ? new raw.DefOpSolver(p, t, h, options)
        : raw.DefOpSolver.withHandlePoints(p, t, h.triangles, h.barycentric, options);
  }

  get #raw(): rawTypes.DefOpSolver {
    if (!this.#inner) throw new Error("this DefOpSolver was freed");
    return this.#inner;
  }

  /** Solves a job; throws (with a code) when it cannot, for {@link DefOpTrainer.reject}. */
  solve(job: DefOpJob): DefOpJobResult {
    const r = this.#raw.solve(job.targets, job.start) as {
      positions: Float64Array;
      iterations: number;
      fallback: boolean;
    };
    return { index: job.index, ...r, warm: job.start !== undefined };
  }

  /** Releases the WebAssembly memory. */
  free(): void {
    this.#inner?.free();
    this.#inner = undefined;
  }
}

/**
 * The deformation a DefOp approximates: the pose of least ARAP or S-ARAP energy (default)
 * with a handle on each vertex of `handles` exactly at `targets` (2 per handle), solved
 * from the rest pose by Newton's method; for a puppet (`parts` and `joints`), with its
 * sheets joined at the joints. Returns the positions (2 per vertex).
 */
export function groundTruth(
  positions: Coordinates,
  triangles: Indices,
  handles: Indices,
  targets: Coordinates,
  options: { energy?: "sarap" | "arap"; parts?: readonly PuppetSheet[]; joints?: readonly PuppetJoint[] } = {},
): Float64Array {
  assertLoaded();
  return raw.groundTruth(
    toFloat64(positions, "positions"),
    toUint32(triangles, "triangles"),
    toUint32(handles, "handles"),
    toFloat64(targets, "targets"),
    options,
  );
}
