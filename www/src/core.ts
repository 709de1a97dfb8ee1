/**
 * The core API: shape outlines in, validated triangle meshes out, and the deformer, in a
 * page or in Node. Call {@link init} once before anything else.
 *
 * @example
 * ```ts
 * import { init, defaultShape, triangulate } from "akap";
 * await init();
 * const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.05 });
 * console.log(mesh.vertexCount, mesh.triangleCount);
 * ```
 *
 */
import { coded, toFloat64, toUint32, type Coordinates, type Indices } from "./internal/arrays.js";
import type { MeshData, WasmSource } from "./core-types.js";
import { readMesh } from "./internal/mesh.js";
import { assertLoaded, bindingOf, load, raw, wasmMemory, wasmModule, type rawTypes } from "./internal/wasm.js";

export type { Coordinates, Indices } from "./internal/arrays.js";
export { ERROR_CODES, isAkapError, type AkapError, type ErrorCode } from "./errors.js";
export type { MeshData, WasmSource } from "./core-types.js";

/** A shape: an outer boundary and optional holes, each a closed ring in either direction. */
export interface Outline {
  outer: Coordinates;
  holes?: readonly Coordinates[];
}

/** How finely to triangulate. Every field is optional. */
export interface TriangulationOptions {
  /** Upper bound on triangle area. */
  maxArea?: number;
  /** Desired edge length (an area bound of the equilateral triangle with this edge). */
  targetEdgeLength?: number;
  /** Smallest angle in degrees that refinement enforces, 0 to 34 (default 25). */
  minAngle?: number;
  /** Largest vertex count of the result, outline points included (default 100000). */
  maxVertices?: number;
}

/**
 * Loads the WebAssembly module. In a browser it is fetched next to this module; in Node
 * it is read from disk. Pass `source` (bytes, a URL or a compiled module) to override.
 * Safe to call more than once.
 */
export function init(source?: WasmSource): Promise<void> {
  return load(source);
}

/**
 * The compiled WebAssembly module (after {@link init}). Post it to a Web Worker and call
 * `init(module)` there: the worker instantiates it without fetching or compiling again.
 */
export function compiledModule(): WebAssembly.Module {
  return wasmModule();
}

function copyOut(mesh: rawTypes.Mesh): MeshData {
  try {
    return readMesh(mesh);
  } finally {
    mesh.free();
  }
}

/**
 * Triangulates an outline: constrained Delaunay, refined to the requested triangle size
 * and minimum angle. Throws an `Error` naming the problem for invalid outlines
 * (fewer than 3 points, non-finite coordinates, self-intersections, zero area, holes
 * outside the shape, too many vertices) or options.
 */
export function triangulate(outline: Outline, options: TriangulationOptions = {}): MeshData {
  assertLoaded();
  const outer = toFloat64(outline.outer, "outline.outer");
  const holes = (outline.holes ?? []).map((hole, k) => toFloat64(hole, `outline.holes[${k}]`));
  return copyOut(raw.triangulate_outline(outer, holes, options));
}

/**
 * Triangulates an outline to about `vertices` vertices (within 3% where the outline allows:
 * the edge length guessed from the area, then corrected by the counts obtained; the same
 * rule as Rust's `triangulate_to_about`). `options.targetEdgeLength` is ignored; the
 * others apply. Returns the mesh and the edge length that made it, which `triangulate`
 * with `{ targetEdgeLength }` and the same options turns into the same mesh again.
 */
export function triangulateToVertices(
  outline: Outline,
  vertices: number,
  options: TriangulationOptions = {},
): { mesh: MeshData; targetEdgeLength: number } {
  assertLoaded();
  const outer = toFloat64(outline.outer, "outline.outer");
  const holes = (outline.holes ?? []).map((hole, k) => toFloat64(hole, `outline.holes[${k}]`));
  const made = raw.triangulate_to_vertices(outer, holes, vertices, options) as {
    mesh: rawTypes.Mesh;
    targetEdgeLength: number;
  };
  return { mesh: copyOut(made.mesh), targetEdgeLength: made.targetEdgeLength };
}

/**
 * Validates a mesh given as arrays (positions xy-interleaved, counter-clockwise triangles)
 * and returns it with its boundary. Throws an `Error` naming the first problem found.
 */
export function meshFromArrays(positions: Coordinates, triangles: Indices): MeshData {
  assertLoaded();
  return copyOut(new raw.Mesh(toFloat64(positions, "positions"), toUint32(triangles, "triangles")));
}

/**
 * Options of the {@link Deformer}: a `method` and its settings. `lambda`, `dirichlet` and
 * `integrator` apply to AKAP only, `iterations` to ARAP only, `variant` and `alpha` to MLS
 * only, `cage` and `smoothness` to Cauchy-Green only (giving one to another method throws,
 * code `invalid-option`).
 */
export interface DeformerOptions {
  /**
   * `"akap"` (default): As-Killing-As-Possible vector fields, the paper's method.
   * `"arap"`: as-rigid-as-possible local/global iterations, for comparison; each step
   * moves every handle's target by its velocity and iterates from the current pose.
   * `"mls"`: moving least squares (Schaefer et al. 2006), the classic image warp: every
   * vertex of the rest mesh goes through the map that best takes the handles' rest points
   * to their targets, weighted by closeness; closed form, no history.
   * `"cauchy-green"`: point-to-point Cauchy-Green coordinates (Weber et al. 2009): a
   * conformal (angle-preserving) map of the inside of a cage around the shape, fitted to
   * the handles in the least-squares sense; {@link Deformer.handlePositions} are then the
   * handles' targets, which the shape's points under them approach. Holes are mapped as if
   * filled. Set-up evaluates the cage's coordinates at every vertex (a fraction of a second
   * at 10,000 vertices and a 300-vertex cage).
   */
  method?: Method;
  /** AKAP: weight of the soft handle constraints, from 1e-6 to 1e10 (default 100). */
  lambda?: number;
  /** AKAP: whether the Dirichlet re-solve runs (default true). */
  dirichlet?: boolean;
  /** AKAP: how vertices follow the field: along log spirals (default) or straight lines. */
  integrator?: "spiral" | "linear";
  /**
   * ARAP: local/global iterations per step, a whole number from 1 to 1000 (default 10).
   * The limit keeps one step's work bounded (1000 iterations take about 0.1 s at 1,000
   * vertices natively, growing with the mesh); a frame needs far fewer.
   */
  iterations?: number;
  /**
   * MLS: the maps fitted at each point: `"rigid"` (default, the paper's choice),
   * `"similarity"` (with uniform scale) or `"affine"` (needs three handles not all on one
   * line; a step with fewer throws, code `invalid-argument`).
   */
  variant?: "rigid" | "similarity" | "affine";
  /** MLS: the weights' falloff, `1 / distance^(2 alpha)`, from 0.1 to 4 (default 1). */
  alpha?: number;
  /**
   * Cauchy-Green: the automatic cage's vertex count, a whole number from 8 to 1000 (default
   * 64): the map's degrees of freedom. The cage is the shape's outline offset outward by
   * about half a vertex spacing (more where a smaller cage cannot follow the shape).
   */
  cage?: number;
  /**
   * Cauchy-Green: weight of the smoothness term (the paper's integral of `|f''|^2` over the
   * cage, scaled to be dimensionless), from 1e-8 to 1e4 (default 1e-5). Larger: smoother
   * and nearer a similarity, with handles farther from their targets.
   */
  smoothness?: number;
}

/** A part of a puppet as a {@link Deformer} takes it: its sheet's triangles, name and depth
 * (the parts of {@link importPuppet}'s result, whose `paths` it leaves alone). */
export interface PuppetSheet {
  /** The part's name. */
  name: string;
  /** Indices of the mesh's triangles (not vertices) that make up the part's sheet; the
   * parts together hold every triangle exactly once. */
  triangles: Uint32Array;
  /** The drawing order: larger is in front. A whole number. */
  depth: number;
}

/** A joint: a hinge at one point of two parts, about which the front part turns freely,
 * both sheets keeping that point together. */
export interface PuppetJoint {
  /** Where it is at rest: a point on both parts' sheets. */
  point: [number, number];
  /** The parts it joins, `[front, back]`, as indices into the parts. */
  parts: [number, number];
}

/**
 * A new {@link Deformer}'s options: the method and its settings, and for a puppet (a mesh
 * made of sheets, one per part, that may overlap and need not be connected) its parts and
 * joints. AKAP and ARAP couple the sheets at the joints; a sheet with no joint and no
 * handle stays where it is, and one held by a single joint with nothing to turn it follows
 * without turning. Moving least squares and Cauchy-Green pose the whole puppet as one
 * shape. A joint naming a part out of range, a part twice, or a point not on both parts is
 * refused (code `invalid-joint`); parts that do not hold every triangle exactly once
 * (`invalid-argument`). Without `parts` a Deformer behaves as for one connected shape.
 */
export interface DeformerSetup extends DeformerOptions {
  /** The puppet's parts. */
  parts?: readonly PuppetSheet[];
  /** The joints between them (none if left out); needs `parts`. */
  joints?: readonly PuppetJoint[];
}

/** The deformation methods (see {@link DeformerOptions.method}). */
export type Method = "akap" | "arap" | "mls" | "cauchy-green";

/**
 * Distortion of the current pose against the rest pose (2 for a rigid motion; `Infinity`,
 * never `NaN`, when a triangle has collapsed onto a line or a point).
 */
export interface Metrics {
  areaDistortion: number;
  angleDistortion: number;
  /** Triangles turned upside down or collapsed. */
  flipped: number;
}

/** Milliseconds spent in each stage of the last step. */
export interface Timings {
  assembly: number;
  /** Both numeric factorisations (AKAP), or ARAP's when its handles changed. */
  factorisation: number;
  /** The part of `factorisation` spent on AKAP's step 2 (the Dirichlet re-solve); 0 for ARAP. */
  dirichletFactorisation: number;
  solve: number;
  integration: number;
}

/** Limits of {@link Deformer.stepWithoutFoldovers}. */
export interface FoldoverOptions {
  /**
   * Halvings: a step that would flip a triangle is split into two halves, each guarded the
   * same way, down to pieces of `2^-maxSplits` of the velocities; a whole number from 0 to
   * 10 (default 4: sixteenths).
   */
  maxSplits?: number;
  /**
   * Bisection trials that clamp a smallest piece that still flips to its largest flip-free
   * fraction (to `2^-clampTrials` of the piece); a whole number from 0 to 30 (default 12;
   * with 0 such a piece is not taken).
   */
  clampTrials?: number;
}

/** What {@link Deformer.stepWithoutFoldovers} did. */
export interface GuardedStep {
  /**
   * The plain steps taken, in order, each as the fraction of the velocities it moved by:
   * `[1]` when the step flipped nothing (it was then exactly {@link Deformer.step}),
   * otherwise powers of two and, last when `clamped`, the clamp's fraction; empty when
   * nothing could be taken. Calling `step` with `velocities[i] * fraction` for each, in
   * order, replays the guarded step to the bit: record those to replay it.
   */
  steps: number[];
  /** Whether a smallest piece still flipped and was clamped: the step ended short. */
  clamped: boolean;
  /** Plain steps tried, the undone ones included (1 when nothing flipped): its cost. */
  attempts: number;
}

/**
 * How {@link Deformer.advance} moves the handles toward their targets; each setting left
 * out keeps its value.
 */
export interface TrackingOptions {
  /** The longest handle move of one substep, as a share of {@link Deformer.size} (default 0.02). */
  maxStep?: number;
  /** Most substeps a frame takes, 1 to 10000 (default 8); the rest of the way is left to the next frame. */
  maxSubsteps?: number;
  /** Whether each substep is {@link Deformer.stepWithoutFoldovers} (default true). */
  noFoldovers?: boolean;
  /** The guard's halvings (see {@link FoldoverOptions}). */
  maxSplits?: number;
  /** The guard's bisection trials (see {@link FoldoverOptions}). */
  clampTrials?: number;
  /**
   * The paper's mode: a handle's velocity is its target's motion since the last frame,
   * split evenly, and errors accumulate, as in the paper's interface (default false).
   */
  paper?: boolean;
}

/** What one {@link Deformer.advance} did. */
export interface Advance {
  /** Substeps taken (a rig's evaluation counts as one); 0 when nothing moved. */
  steps: number;
  /** Whether a step stopped short to keep triangles from folding over. */
  clamped: boolean;
  /** Milliseconds of the rig's evaluation (0 when the frame stepped). */
  evaluation: number;
  /** The stage timings summed over the substeps. */
  timings: Timings;
}

/**
 * How a rig posed on the GPU ({@link Deformer.setRigOnGpu}) lays out its basis texture and
 * its frames, in texels of 4 numbers (RGBA32F; the one definition is Rust's
 * `crate::defop::gpu`). Vertex v's position is `x = Σ_{t < terms} B[v stride + t] ·
 * F[rigidTexels + t]`, `y = Σ_t B[v stride + basisY + t] · F[rigidTexels + frameY + t]`
 * (dot products of texels), then the rigid motion of the frame's head: with `F[0] = (cos,
 * sin, fromX, fromY)`, `F[1] = (toX, toY, 0, 0)`, `R (p − from) + to`.
 */
export interface RigGpuLayout {
  /** A reduced spatial basis (the frame is `X Ψ`, the texture D), or the hat basis (`Ψ`, X). */
  reduced: boolean;
  vertexCount: number;
  /** Texels of one coordinate's sum. */
  terms: number;
  /** Texels per vertex in the basis texture. */
  stride: number;
  /** Where a vertex's y row starts among its texels. */
  basisY: number;
  /** Where the y vector starts in the frame, after its head. */
  frameY: number;
  /** Texels of a frame. */
  frameTexels: number;
  /** Texels of the frame's head (the rigid motion). */
  rigidTexels: number;
}

/**
 * A trained rig a {@link Deformer} can pose with: a `DefOp` (see {@link Deformer.setRig}).
 */
export interface RigOperator {
  readonly handleCount: number;
  readonly vertexCount: number;
}

/**
 * The fill-reducing orders a {@link Deformer} with these options needs for this mesh: the
 * bulk of its set-up (ordering the mesh's vertex graph, about two thirds of the time). Run
 * it in a worker and pass the result to the constructor to keep a page responsive.
 */
export function deformerOrders(
  positions: Coordinates,
  triangles: Indices,
  options: DeformerOptions = {},
): Uint32Array[] {
  assertLoaded();
  return raw.deformer_orders(
    toFloat64(positions, "positions"),
    toUint32(triangles, "triangles"),
    options,
  ) as Uint32Array[];
}

/**
 * Deformation of one mesh by a method of {@link Method} (As-Killing-As-Possible by default;
 * `"arap"`, `"mls"`, `"cauchy-green"`), with its interaction loop. Give it handles
 * (vertices, or points inside triangles), then either set where they are to go
 * ({@link Deformer.setTarget}, {@link Deformer.setTurn}) and call {@link Deformer.advance}
 * once a frame, which takes them there as the posing app does (substeps, no foldovers,
 * retries), or step it yourself with a velocity per handle ({@link Deformer.step},
 * {@link Deformer.stepWithoutFoldovers}). A recording ({@link Deformer.startRecording})
 * keeps every step as it is taken, and replays to the same bits. Bad input throws an
 * `Error` and leaves the deformer as it was. Call {@link Deformer.free} when done: the
 * solver lives in WebAssembly memory.
 */
export class Deformer {
  #inner: rawTypes.Deformer | undefined;
  #view: Float64Array | undefined;
  #frameView: Float32Array | undefined;
  #watchedView: Float64Array | undefined;

  /**
   * @param positions xy-interleaved vertex positions (length 2n)
   * @param triangles counter-clockwise index triples (length 3m); the mesh must be connected,
   *   but for a puppet's sheets (`options.parts`)
   * @param options the method and its settings, and a puppet's parts and joints
   * @param orders the fill-reducing orders from {@link deformerOrders} (same mesh and
   *   method), when the bulk of the set-up already ran elsewhere, e.g. in a worker
   */
  constructor(
    positions: Coordinates,
    triangles: Indices,
    options: DeformerSetup = {},
    orders?: readonly Uint32Array[],
  ) {
    assertLoaded();
    const p = toFloat64(positions, "positions");
    const t = toUint32(triangles, "triangles");
    this.#inner = orders ? raw.Deformer.withOrders(p, t, options, [...orders]) : new raw.Deformer(p, t, options);
  }

  /** The wasm object, or an Error once {@link free} was called. */
  get #raw(): rawTypes.Deformer {
    if (!this.#inner) throw new Error("this Deformer was freed; make a new one");
    return this.#inner;
  }

  /** A puppet's parts (name, triangles, depth), or `undefined` for one shape. */
  get parts(): PuppetSheet[] | undefined {
    return this.#raw.parts as PuppetSheet[] | undefined;
  }

  /** A puppet's joints (empty for one shape). */
  get joints(): PuppetJoint[] {
    return this.#raw.joints as PuppetJoint[];
  }

  /**
   * Replaces a puppet's joints (the Joint tool), keeping the pose, the handles, the
   * stiffness and the bones; the systems are analysed again for them. Refused, changing
   * nothing, for a deformer of one shape and for a joint naming a part out of range or a
   * part twice, or whose point is not on both parts (code `invalid-joint`).
   */
  setJoints(joints: readonly PuppetJoint[]): void {
    this.#raw.setJoints(joints);
  }

  /**
   * Changes some options; the others keep their values. A different `method` switches the
   * deformer to that method (its defaults, with the settings given) on the same mesh,
   * keeping the pose and the handles; that sets up a new solver, as the constructor does.
   * On error nothing changes.
   */
  setOptions(options: DeformerOptions): void {
    this.#raw.setOptions(options);
  }

  /** The method in use. */
  get method(): Method {
    return this.#raw.method as Method;
  }

  /** One handle on each of these vertices, replacing the current handles. */
  setHandles(vertices: Indices): void {
    this.#raw.setHandles(toUint32(vertices, "vertices"));
  }

  /** Handles at points inside triangles: a triangle index and 3 barycentric coordinates each. */
  setHandlePoints(triangles: Indices, barycentric: Coordinates): void {
    this.#raw.setHandlePoints(toUint32(triangles, "triangles"), toFloat64(barycentric, "barycentric"));
  }

  /**
   * One step: two velocity components per handle, in handle order. Each handle's target
   * becomes where the step took it (so a later {@link advance} keeps the pose).
   */
  step(velocities: Coordinates): void {
    this.#raw.step(toFloat64(velocities, "velocities"));
  }

  /**
   * One step in which handles also turn: `turns` has one angle per handle (radians,
   * counter-clockwise about the handle's point), and the region around each turning handle
   * follows that rigid motion (softly, as handles are held). One handle alone turns the
   * whole shape rigidly about itself. All turns 0 is exactly {@link step}. AKAP and ARAP
   * (ARAP holds the neighbourhood in the turned frame for the step); MLS and Cauchy-Green
   * throw (code `invalid-argument`) for a turn that is not 0.
   */
  stepTurning(velocities: Coordinates, turns: Coordinates): void {
    this.#raw.stepTurning(toFloat64(velocities, "velocities"), toFloat64(turns, "turns"));
  }

  /**
   * One step that turns no triangle over: a triangle positively oriented before it stays
   * so (triangles already turned over or collapsed are ignored). The plain {@link step}
   * when it flips none, bit for bit; otherwise two half steps, each guarded alike, down
   * to `2^-maxSplits` of the velocities, and the first such piece that still flips is
   * clamped to the largest flip-free fraction a bisection finds, the step ending there
   * (the handles then lag their targets; ask for the rest in the next frame). Any method;
   * AKAP and ARAP, whose steps have history, go on along another path, while MLS and
   * Cauchy-Green, functions of the targets, stop where the way to them first flips a
   * triangle. With `turns`, handles also turn as in {@link stepTurning}, each piece by its
   * fraction of them (replay with `stepTurning(velocities * f, turns * f)`). Bad input throws
   * and leaves the deformer as it was.
   */
  stepWithoutFoldovers(velocities: Coordinates, options: FoldoverOptions = {}, turns?: Coordinates): GuardedStep {
    return this.#raw.stepWithoutFoldovers(
      toFloat64(velocities, "velocities"),
      options,
      turns === undefined ? undefined : toFloat64(turns, "turns"),
    ) as GuardedStep;
  }

  /** A copy of the current positions, xy-interleaved. */
  positions(): Float64Array {
    return this.#raw.positions();
  }

  /**
   * The current positions without a copy: a view of WebAssembly memory. Read it right away
   * and call this again after the next step rather than keeping it: a step moves the
   * positions to another buffer, and growing memory detaches old views. Cheap to call;
   * the view is re-created only when one of those happened.
   */
  positionsView(): Float64Array {
    // A step swaps the position buffers, and growth replaces the memory's buffer.
    const buffer = wasmMemory().buffer;
    const pointer = this.#raw.positionsPointer();
    if (this.#view?.buffer !== buffer || this.#view.byteOffset !== pointer) {
      this.#view = new Float64Array(buffer, pointer, 2 * this.#raw.vertexCount);
    }
    return this.#view;
  }

  /**
   * Each triangle's stiffness, the factor on its energy (one per triangle, from 0.001 to
   * 1000; stiff regions bend less), or 1 everywhere with `undefined`. AKAP weighs its
   * Killing energy by it, ARAP its element energy; `"mls"` and `"cauchy-green"` have no
   * per-triangle energy and throw (code `invalid-argument`). Kept when switching between
   * AKAP and ARAP. Bad values throw and change nothing.
   */
  setStiffness(stiffness: Coordinates | undefined): void {
    this.#raw.setStiffness(stiffness === undefined ? undefined : toFloat64(stiffness, "stiffness"));
  }

  /** Whether the method takes {@link Deformer.setStiffness} (AKAP and ARAP). */
  get hasStiffness(): boolean {
    return this.#raw.hasStiffness;
  }

  /**
   * Bones: straight segments whose triangles move as one rigid body, for limbs. Two ends per
   * bone, each a triangle index and 3 barycentric coordinates (as {@link setHandlePoints}
   * takes points), laid in the current pose, replacing any bones; empty arrays remove them.
   * The triangles a bone's segment meets weigh at least 1000 in the energy and, after each
   * step, are put where the rigid motion that best fits them takes the bone as it was set:
   * the segment stays straight and keeps its length however the handles pull, and a handle
   * on it moves and turns it as a whole. AKAP and ARAP (kept when switching between them);
   * `"mls"` and `"cauchy-green"` throw (code `invalid-argument`). A bone whose ends are at one
   * point, whose segment leaves the shape, or that shares a vertex with another bone (leave
   * a joint of free triangles between bones) throws, changing nothing.
   */
  setBones(triangles: Indices, barycentric: Coordinates): void {
    this.#raw.setBones(toUint32(triangles, "triangles"), toFloat64(barycentric, "barycentric"));
  }

  /** Whether the method takes {@link Deformer.setBones} (AKAP and ARAP). */
  get hasBones(): boolean {
    return this.#raw.hasBones;
  }

  /** Puts the mesh into a given pose (xy-interleaved, length 2n); handles stay. */
  setPositions(positions: Coordinates): void {
    this.#raw.setPositions(toFloat64(positions, "positions"));
  }

  /** The last step's velocity field after the Dirichlet re-solve (U_opt; ARAP: the step's displacement), xy-interleaved. */
  field(): Float64Array {
    return this.#raw.field();
  }

  /** The last step's velocity field after the soft-constraint solve (U0; ARAP: the step's displacement), xy-interleaved. */
  softField(): Float64Array {
    return this.#raw.softField();
  }

  /**
   * Cauchy-Green's cage as the last step deformed it (the polygon whose Cauchy integral
   * the map is; the rest cage until the first step), xy-interleaved; `undefined` for the
   * other methods.
   */
  cage(): Float64Array | undefined {
    return this.#raw.cage();
  }

  /** Current positions of the handle points, xy-interleaved. */
  handlePositions(): Float64Array {
    return this.#raw.handlePositions();
  }

  get handleCount(): number {
    return this.#raw.handleCount;
  }

  get vertexCount(): number {
    return this.#raw.vertexCount;
  }

  metrics(): Metrics {
    return this.#raw.metrics() as Metrics;
  }

  timings(): Timings {
    return this.#raw.timings() as Timings;
  }

  /** Back to the rest pose; handles stay, each with its target at its rest place. */
  reset(): void {
    this.#raw.reset();
  }

  /** Whether the pose is the rest pose: new or just reset, no step or pose since. */
  get atRest(): boolean {
    return this.#raw.atRest;
  }

  /** The rest shape's size, its bounding box's larger side (the unit of {@link TrackingOptions.maxStep}). */
  get size(): number {
    return this.#raw.size;
  }

  // ---------------------------------------------------------------- the interaction loop

  /** How {@link advance} moves the handles toward their targets. Bad values throw and change nothing. */
  setTracking(options: TrackingOptions): void {
    this.#raw.setTracking(options);
  }

  /**
   * One more handle at a point inside a triangle (its index and 3 barycentric
   * coordinates), last, its target where it is; the other handles keep their targets and
   * turns. Returns its index.
   */
  addHandle(triangle: number, barycentric: Coordinates): number {
    return this.#raw.addHandle(triangle, toFloat64(barycentric, "barycentric"));
  }

  /** Removes handle `index`; the others keep their targets and turns. */
  removeHandle(index: number): void {
    this.#raw.removeHandle(index);
  }

  /** Sets where handle `index` is to go; the next {@link advance} takes it there (as far as a frame allows). */
  setTarget(index: number, x: number, y: number): void {
    this.#raw.setTarget(index, x, y);
  }

  /**
   * Places every handle's target (x and y per handle, in order): undo, a frame of an
   * animation shown. No turn is left to make.
   */
  setTargets(targets: Coordinates): void {
    this.#raw.setTargets(toFloat64(targets, "targets"));
  }

  /**
   * Sets how far handle `index` is to turn in all, radians counter-clockwise (turns add up
   * over frames, in steps of at most 0.1 radian; AKAP and ARAP).
   */
  setTurn(index: number, turn: number): void {
    this.#raw.setTurn(index, turn);
  }

  /**
   * A pointer takes handle `index`: it is held (a step that stops short leaves the handles
   * not held where they stopped), its target where it is. Returns where it is.
   */
  grab(index: number): [number, number] {
    const at = this.#raw.grab(index);
    return [at[0]!, at[1]!];
  }

  /** The pointer lets handle `index` go: it stays at its target. */
  release(index: number): void {
    this.#raw.release(index);
  }

  /** Whether a pointer holds handle `index` ({@link grab} without moving its target). */
  setHeld(index: number, held: boolean): void {
    this.#raw.setHeld(index, held);
  }

  /** Every handle's target where it is now: the handles stay where they are. */
  pinHandles(): void {
    this.#raw.pinHandles();
  }

  /** Where each handle is going, xy-interleaved. */
  targets(): Float64Array {
    return this.#raw.targets();
  }

  /** How far each handle is to turn in all (`turns`) and has turned (`turned`), radians. */
  turns(): { turns: Float64Array; turned: Float64Array } {
    const both = this.#raw.turns();
    const n = both.length / 2;
    return { turns: both.subarray(0, n), turned: both.subarray(n) };
  }

  /**
   * One frame of the interaction loop: every handle moved toward its target and turned
   * toward its turn, in substeps no longer than {@link TrackingOptions.maxStep} of the
   * shape's size, each without foldovers (a step that would fold is split, then stopped
   * short, and the handles not held stay where they stopped), a failed step tried again
   * smaller; or, with a rig ({@link setRig}), the rig's pose for the targets. One call into
   * WebAssembly; read the pose with {@link positionsView}. A step that fails even smaller
   * throws, the pose where the steps before it left it.
   */
  advance(): Advance {
    return this.#raw.advance() as Advance;
  }

  /**
   * Poses with a trained rig (a `DefOp`, copied into the deformer) instead of stepping:
   * each {@link advance} gives the rig's pose for the handles' targets, computed in
   * WebAssembly straight into the positions. With `noFoldovers` ({@link setTracking}, on
   * by default) targets whose pose would turn over a triangle not turned over at rest are
   * pulled back along the way from the last pose's, the frame reported `clamped`. `undefined`
   * steps again; so does a new handle set. Throws (code `invalid-argument`) for a rig of
   * other handle or vertex counts; the caller checks that it was trained for this mesh and
   * these handle points. A recording names the rig ({@link rigChecksum}) and records its
   * frames as their targets.
   */
  setRig(rig: RigOperator | undefined): void {
    if (rig === undefined) {
      this.#raw.clearRig();
      return;
    }
    const inner = bindingOf(rig) as rawTypes.DefOp | undefined;
    if (!inner) throw coded(new TypeError("the rig must be a DefOp that is not freed"), "invalid-argument");
    this.#raw.setRig(inner);
  }

  /** Whether a rig poses the shape ({@link setRig}). */
  get hasRig(): boolean {
    return this.#raw.hasRig;
  }

  /**
   * How a session names `rig` posing this deformer's mesh: the checksum of its operator
   * file (16 hexadecimal digits), as a recorded `rig` event has it.
   */
  rigChecksum(rig: RigOperator): string {
    const inner = bindingOf(rig) as rawTypes.DefOp | undefined;
    if (!inner) throw coded(new TypeError("the rig must be a DefOp that is not freed"), "invalid-argument");
    return this.#raw.rigChecksum(inner);
  }

  /**
   * Poses with the rig ({@link setRig}) at these targets (x and y per handle), as given,
   * without the foldover guard: a session's recorded `rigPose`. The handles' targets become
   * these. Throws without a rig.
   */
  poseWithRig(targets: Coordinates): void {
    this.#raw.poseWithRig(toFloat64(targets, "targets"));
  }

  /**
   * Poses the rig on the GPU (`true`) or on the CPU (`false`). On the GPU, {@link advance}
   * computes only the rig's frame ({@link rigFrame}: `X Ψ(Q)` for a reduced spatial basis,
   * `Ψ(Q)` for the hat basis, and a rigid motion), which a vertex shader combines with the
   * basis texture ({@link rigGpuTexture}) into the positions; the pose on the CPU is the
   * operator's, evaluated when something reads it ({@link positions},
   * {@link positionsView}, {@link handlePositions}, {@link metrics}, a step, a recording,
   * ...). With `noFoldovers` (its guard needs the pose) or a recording that cannot name
   * the rig, each frame is evaluated on the CPU too. Returns whether the rig is on the GPU
   * now (never without a rig; a new rig starts on the CPU).
   */
  setRigOnGpu(on: boolean): boolean {
    return this.#raw.setRigOnGpu(on);
  }

  /** The layout of the rig on the GPU, or `undefined` without one. */
  rigGpuLayout(): RigGpuLayout | undefined {
    return this.#raw.rigGpuLayout() as RigGpuLayout | undefined;
  }

  /**
   * The basis texture of the rig on the GPU (`vertexCount * stride` texels of 4 numbers,
   * rounded to single precision), or `undefined` without one: upload it once per rig.
   */
  rigGpuTexture(): Float32Array | undefined {
    return this.#raw.rigGpuTexture();
  }

  /**
   * The rig's last frame on the GPU (`4 * frameTexels` numbers), a view of WebAssembly
   * memory (no copy): read it right away after {@link advance}. `undefined` without a rig
   * on the GPU.
   */
  rigFrame(): Float32Array | undefined {
    const pointer = this.#raw.rigFramePointer();
    if (pointer === 0) return undefined;
    const buffer = wasmMemory().buffer;
    if (this.#frameView?.buffer !== buffer || this.#frameView.byteOffset !== pointer) {
      const layout = this.rigGpuLayout()!;
      this.#frameView = new Float32Array(buffer, pointer, 4 * layout.frameTexels);
    }
    return this.#frameView;
  }

  /**
   * Watches these vertices of the rig on the GPU: each frame also gives their positions on
   * the CPU ({@link rigWatchedPositions}), in single precision, for what is drawn over the
   * mesh. Returns whether a rig is on the GPU. Throws for a vertex out of range.
   */
  watchRigVertices(vertices: Indices): boolean {
    return this.#raw.watchRigVertices(toUint32(vertices, "vertices"));
  }

  /**
   * Positions (2 per vertex) fresh at the watched vertices as of the last frame on the GPU
   * (the others hold older values), a view of WebAssembly memory; `undefined` without a
   * rig on the GPU.
   */
  rigWatchedPositions(): Float64Array | undefined {
    const pointer = this.#raw.rigWatchedPointer();
    if (pointer === 0) return undefined;
    const buffer = wasmMemory().buffer;
    if (this.#watchedView?.buffer !== buffer || this.#watchedView.byteOffset !== pointer) {
      this.#watchedView = new Float64Array(buffer, pointer, 2 * this.#raw.vertexCount);
    }
    return this.#watchedView;
  }

  /** Whether the pose on the CPU is behind the rig's last frame on the GPU (it is evaluated when read). */
  get poseStale(): boolean {
    return this.#raw.poseStale;
  }

  /**
   * Whether the rig's last frame on the GPU ({@link rigFrame}) is that of the pose shown,
   * the pose on the CPU behind it or not (with `noFoldovers` each frame is evaluated on
   * the CPU as well); false after a pose set otherwise (undo, reset).
   */
  get rigFrameCurrent(): boolean {
    return this.#raw.rigFrameCurrent;
  }

  /**
   * Starts recording a session of everything done through this deformer from now on (the
   * steps as taken, handles, poses, options, stiffness, bones), replacing any recording.
   * `shape` names the built-in shape the mesh was triangulated from (`{ name,
   * targetEdgeLength?, minAngle?, maxArea? }`); without it the session carries the mesh.
   */
  startRecording(shape?: { name: string; targetEdgeLength?: number; minAngle?: number; maxArea?: number }): void {
    this.#raw.startRecording(shape);
  }

  /** Whether a recording runs. */
  get recording(): boolean {
    return this.#raw.recording;
  }

  /** Ends the recording and returns its JSON (an `akap-session`), or undefined if none ran. */
  stopRecording(): string | undefined {
    return this.#raw.stopRecording();
  }

  /** Pauses the recording (while a session replays) or resumes it. */
  pauseRecording(paused: boolean): void {
    this.#raw.pauseRecording(paused);
  }

  /** Releases the WebAssembly memory; the deformer cannot be used afterwards (calls throw). */
  free(): void {
    this.#raw.free();
    this.#inner = undefined;
    this.#view = undefined;
  }
}

/**
 * Checks per-triangle stiffness for a mesh of `triangleCount` triangles as
 * {@link Deformer.setStiffness} does (one value per triangle, each from 0.001 to 1000),
 * throwing the same `Error`; for keeping stiffness while a method without it poses.
 */
export function checkStiffness(stiffness: Coordinates, triangleCount: number): void {
  assertLoaded();
  raw.checkStiffness(toFloat64(stiffness, "stiffness"), triangleCount);
}

/** The limits on what the functions take (the same in Rust, the bindings and the widget). */
export interface Limits {
  /** Largest text file (SVG, OBJ, JSON), in bytes. */
  bytes: number;
  /** Largest image, in pixels (width times height). */
  pixels: number;
  /** Most points of an outline (imported or given to `triangulate`). */
  points: number;
  /** Most vertices of a mesh. */
  vertices: number;
  /** Largest recorded session (JSON), in bytes. */
  sessionBytes: number;
  /** The range of per-triangle stiffness ({@link Deformer.setStiffness}): 0.001 to 1000. */
  stiffness: [number, number];
  /** Most bytes of RGBA an animation's frames may add up to, 4 per pixel per frame (1 GiB;
   * see `encodeAnimation`). */
  animationBytes: number;
}

/** The limits on inputs; bigger inputs are refused with an `Error` saying so. */
export function limits(): Limits {
  assertLoaded();
  return raw.limits() as Limits;
}

/** The built-in default shape, a waving gingerbread figure about 1.4 units tall (y up). */
export function defaultShape(): { outer: Float64Array; holes: Float64Array[] } {
  assertLoaded();
  return raw.defaultShape() as { outer: Float64Array; holes: Float64Array[] };
}

/** Names of the built-in shapes; the first is {@link defaultShape}. */
export function builtinShapes(): string[] {
  assertLoaded();
  return raw.builtinShapes() as string[];
}

/** A built-in shape by name (see {@link builtinShapes}); throws for an unknown name. */
export function builtinShape(name: string): { outer: Float64Array; holes: Float64Array[] } {
  assertLoaded();
  return raw.builtinShape(name) as { outer: Float64Array; holes: Float64Array[] };
}
