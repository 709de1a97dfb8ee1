/**
 * What the widget poses, apart from the page: the shape and its deformer, the handles
 * (which pointer holds each, selection, depth order), the undo history and the replay of
 * sessions. It knows nothing of the DOM; it tells its host (the widget) what to show
 * through {@link PosingHost}.
 *
 * The interaction loop itself is the core's (`Deformer.advance`, Rust's `pose::Poser`):
 * the handles' targets, turns and held flags live in the deformer, set here as pointers
 * move, and each frame {@link Posing.advance} is one call that takes the handles toward
 * them (substeps no longer than `maxStep` of the shape's size, guarded steps, retries) or,
 * with the "defop" method and a trained {@link Rig} that fits the shape and handles, poses
 * with the rig in WebAssembly, or, with {@link Posing.rigsOnGpu}, leaves the pose to the
 * renderer's vertex shader (the deformer computes the rig's frame; its pose is evaluated
 * when read). The deformer records every change made through it while a recording runs.
 */
import {
  Deformer,
  checkStiffness,
  type DeformerOptions,
  type DeformerSetup,
  type PuppetJoint,
  type Timings,
} from "../../core.js";
import { PointMapper } from "../../import.js";
import { History } from "./history.js";
import { METHODS, methodOptions, widgetMethod, type MethodPreset } from "./methods.js";
import { locate, locateFront, nearestPoint, pointPosition, type MeshPoint } from "./picking.js";
import { Session, type SessionEvent } from "../../session.js";
import { Bones, bonesFrom, type Bone } from "./bones.js";
import { carryStiffness, paintStiffness, unpainted } from "./stiffness.js";
import type { Rig } from "./rig.js";
import type { Loaded, Shape } from "./shape.js";
import { newHandle, type Handle, type HandleState } from "./handle.js";
import { deformerJoints, importedDepths, puppetOptions, sameJoints, setDeformerJoints, stepDepth } from "./puppet.js";

export { newHandle, type Handle, type HandleState } from "./handle.js";

/** The parts of an imported file (largest first) and the one shown. */
export interface Parts {
  loaded: Extract<Loaded, { kind: "outlines" }>;
  index: number;
}

/** Everything undo restores: the shape and its parts, the method, the pose and the handles. */
export interface Snapshot {
  shape: Shape;
  parts: Parts | undefined;
  method: MethodPreset;
  lambda: number;
  positions: Float64Array;
  atRest: boolean;
  handles: HandleState[];
  /** The painted stiffness, one per triangle (a copy), or undefined for none. */
  stiffness?: Float64Array | undefined;
  /** The bones (work saved before bones existed has none). */
  bones?: Bone[] | undefined;
  /** A puppet's parts' depths and its deformer's joints (undefined for other shapes). */
  depths?: number[] | undefined;
  joints?: PuppetJoint[] | undefined;
}

/**
 * The settings posing reads (the widget's settings object, shared: the method and lambda
 * shown are written back into it).
 */
export interface PosingSettings {
  method: MethodPreset;
  /** Weight of the soft handle constraints (AKAP). */
  lambda: number;
  /** Longest handle move per substep, as a fraction of the shape's size. */
  maxStep: number;
  /** Most substeps per frame. */
  maxSubsteps: number;
  /** Velocities from raw pointer displacement (the paper's mode) instead of target tracking. */
  paperMode: boolean;
  /** Steps guarded against foldovers. */
  noFoldovers: boolean;
}

/** What the posing tells the page. */
export interface PosingHost {
  /** A new shape or deformer is in place; `refit` when the view should fit it afresh. */
  adopted(shape: Shape, deformer: Deformer, refit: boolean): void;
  /** The method in use changed (lists and HUD show it). */
  methodChanged(method: MethodPreset, lambda: number): void;
  /** The handle set changed. */
  handlesChanged(count: number): void;
  /** The pose changed outside the frame loop (undo, reset, a load). */
  poseChanged(): void;
  /** The undo history or the recording changed. */
  historyChanged(): void;
  /** Something is to be drawn or moved: a frame is wanted. */
  schedule(): void;
}

export class Posing {
  readonly settings: PosingSettings;
  readonly history = new History<Snapshot>();
  shape!: Shape;
  deformer!: Deformer;
  /**
   * The handles, in the deformer's order. After changing the list, call
   * {@link applyHandles}: handles still in it keep their targets and turns.
   */
  handles: Handle[] = [];
  parts: Parts | undefined;
  /**
   * A puppet's parts' depths (larger in front; see `puppet.ts`), as the user ordered them;
   * undefined for other shapes.
   */
  depths: number[] | undefined;
  /** The joint selected with the joint tool (an index into {@link joints}), if any. */
  selectedJoint: number | undefined;
  /** The depth of each triangle's part, and the depths it was made from. */
  #triangleDepths: { depths: number[]; layers: Int32Array } | undefined;
  /** While a session replays: nothing is recorded. */
  replaying = false;
  /** The trained rig the widget holds (it poses with the "defop" method while it fits). */
  rig: Rig | undefined;
  /**
   * Whether a rig that poses is evaluated on the GPU (the widget's renderer is WebGL2): each
   * frame then computes only the rig's frame, the pose on the CPU when read
   * (`Deformer.setRigOnGpu`).
   */
  rigsOnGpu = false;
  /** Counts the rigs sent to the deformer on the GPU: a renderer uploads a rig's texture once per count. */
  gpuRigVersion = 0;
  /** The bones drawn on the shape (see bones.ts). */
  readonly bones: Bones = new Bones(this);
  /** Whether a step of the last frame stopped short to keep triangles from folding over. */
  clamped = false;
  /** Milliseconds of the last frame's rig evaluation (0 when the frame stepped the deformer). */
  evaluationMs = 0;
  /**
   * Each triangle's painted stiffness, or undefined for none (1 everywhere). It belongs to
   * the shape: kept across methods, and given to the deformer whenever its method takes
   * stiffness (AKAP and ARAP; {@link Deformer.hasStiffness}).
   */
  get stiffness(): Float64Array | undefined {
    return this.#stiffness;
  }
  set stiffness(values: Float64Array | undefined) {
    this.#stiffness = values;
    this.stiffnessVersion++;
  }
  #stiffness: Float64Array | undefined;
  /** Counts changes of the painting (the drawn tint is made again when it changes). */
  stiffnessVersion = 0;
  /** Painted since the deformer (and the recording) last had the painting. */
  #stiffnessPending = false;
  /** The handles as the deformer has them (what {@link applyHandles} compares with). */
  #sent: Handle[] = [];
  /** The rig the deformer poses with, and the tracking settings it has (sent when they change). */
  #rigSent: Rig | undefined;
  #trackingSent = "";
  readonly #host: PosingHost;
  #gestureBefore: Snapshot | undefined;
  #gestureChanged = false;

  /** How many parts the shape's file has, and which one is shown (1 and 0 for a single shape). */
  get partsInfo(): { count: number; index: number } {
    const parts = this.parts;
    return parts ? { count: parts.loaded.parts.length, index: parts.index } : { count: 1, index: 0 };
  }

  constructor(settings: PosingSettings, host: PosingHost) {
    this.settings = settings;
    this.#host = host;
  }

  // ---------------------------------------------------------------- shape and method

  /** Whether the pose is the rest pose (the deformer new or just reset). */
  get atRest(): boolean {
    return this.deformer.atRest;
  }

  /** Whether a recording runs (the deformer's). */
  get recording(): boolean {
    return this.deformer?.recording ?? false;
  }

  /** Makes `shape` current with a fresh deformer, without handles, at rest. */
  install(shape: Shape, orders?: Uint32Array[]): void {
    this.adopt(shape, orders, true);
    this.handles = [];
    this.applyHandles();
    this.#host.poseChanged();
  }

  /**
   * Makes `shape` current with a fresh deformer of the current method (handles and pose
   * are the caller's to set); fails without changing anything. A recording ends.
   */
  adopt(shape: Shape, orders: Uint32Array[] | undefined, refit: boolean): void {
    const { puppet } = shape;
    const options = puppet ? puppetOptions(this.deformerOptions(), puppet, puppet.joints) : this.deformerOptions();
    const deformer = new Deformer(shape.mesh.positions, shape.mesh.triangles, options, orders);
    this.deformer?.free();
    this.deformer = deformer;
    this.#sent = [];
    this.#rigSent = undefined;
    this.#trackingSent = "";
    this.#sendTracking();
    this.shape = shape;
    this.depths = puppet && importedDepths(puppet);
    this.selectedJoint = undefined;
    this.#triangleDepths = undefined;
    this.stiffness = undefined;
    this.#stiffnessPending = false;
    this.bones.forget();
    this.#host.adopted(shape, deformer, refit);
  }

  /** The method's options (see {@link shapeOptions} for a deformer of the shape). */
  deformerOptions(): DeformerOptions {
    return methodOptions(this.settings.method, this.settings.lambda);
  }

  /** The options a deformer of the shape as posed is made with: the method's, and a puppet's parts and joints now. */
  shapeOptions(): DeformerSetup {
    const { puppet } = this.shape;
    return puppet ? puppetOptions(this.deformerOptions(), puppet, this.joints) : this.deformerOptions();
  }

  /** Changes the method and/or lambda (recorded). */
  setMethod(method: MethodPreset, lambda: number): void {
    if (!Object.hasOwn(METHODS, method)) throw new Error(`unknown method "${method}"`);
    const options = methodOptions(method, lambda);
    // Another method is set up with the pose and handles (the core's MethodOptions::apply);
    // throws, changing nothing, for a bad lambda.
    this.deformer.setOptions(options);
    // A method without stiffness or bones dropped them; one with them gets them back.
    if (this.stiffness) this.#sendStiffness();
    if (this.bones.list.length > 0) this.bones.resend();
    this.showMethod(method, lambda);
  }

  /** Deformer options from a session: applied, and shown as the widget's method. */
  applyOptions(options: DeformerOptions): void {
    this.deformer.setOptions(options);
    const { method, lambda } = widgetMethod(options, this.settings.lambda);
    this.showMethod(method, lambda);
  }

  showMethod(method: MethodPreset, lambda: number): void {
    this.settings.method = method;
    this.settings.lambda = lambda;
    this.#host.methodChanged(method, lambda);
  }

  /**
   * Makes `shape` (a re-meshing of the current one) current with the pose and handles
   * carried over: every new vertex goes where the old mesh's pose takes its rest position,
   * and each handle stays at its place.
   */
  carryOver(shape: Shape, orders: Uint32Array[] | undefined): void {
    const old = { shape: this.shape, positions: this.deformer.positions(), atRest: this.atRest };
    const stiffness = carryStiffness(this.stiffness, old.shape.mesh, shape.mesh, 0.05 * shape.size);
    const bones = this.bones.carried(old.shape.mesh, shape.mesh, 0.05 * shape.size);
    const targets = this.deformer.targets();
    const oldPuppet = old.shape.puppet;
    const handles = this.handles.map((h, i) => ({
      rest: pointPosition(old.shape.mesh.positions, old.shape.mesh.triangles, h.point),
      target: [targets[2 * i]!, targets[2 * i + 1]!],
      layer: h.layer,
      ordered: h.ordered,
      part: oldPuppet?.partOf[h.point.triangle],
    }));
    const carried = oldPuppet && shape.puppet && { depths: this.depths, joints: this.joints };
    this.adopt(shape, orders, false);
    this.handles = [];
    // A puppet's parts overlap at rest: each part's points are found in that part alone.
    const puppet = carried && shape.puppet?.parts.length === oldPuppet!.parts.length ? shape.puppet : undefined;
    if (puppet && carried) {
      this.depths = carried.depths;
      try {
        this.setJoints(carried.joints);
      } catch {
        // The joints the new import placed stay where a carried one would not fit.
      }
    }
    if (!old.atRest && puppet) {
      // Each part's vertices through the old part's own sheet.
      const next = new Float64Array(shape.mesh.positions);
      puppet.meshes.forEach((mesh, k) => {
        const source = subMesh(oldPuppet!.meshes[k]!, old.shape.mesh.positions, old.positions);
        const target = subMesh(mesh, shape.mesh.positions);
        const mapper = new PointMapper(source.rest, source.triangles, target.rest);
        try {
          const mapped = mapper.map(source.posed);
          target.vertices.forEach((v, i) => next.set([mapped[2 * i]!, mapped[2 * i + 1]!], 2 * v));
        } finally {
          mapper.free();
        }
      });
      this.deformer.setPositions(next);
    } else if (!old.atRest) {
      const mapper = new PointMapper(old.shape.mesh.positions, old.shape.mesh.triangles, shape.mesh.positions);
      try {
        this.deformer.setPositions(mapper.map(old.positions));
      } finally {
        mapper.free();
      }
    }
    const { positions: rest, triangles } = shape.mesh;
    const kept: number[] = [];
    for (const { rest: at, target, layer, ordered, part } of handles) {
      const own = puppet && part !== undefined ? puppet.meshes[part]! : triangles;
      const found =
        locate(rest, own, at[0], at[1], 1e-6 * shape.size) ?? locate(rest, own, at[0], at[1], 0.05 * shape.size);
      const point =
        found && own !== triangles ? { ...found, triangle: puppet!.parts[part!]!.triangles[found.triangle]! } : found;
      if (point) {
        this.handles.push({ ...newHandle(point), layer, ordered });
        kept.push(...target);
      }
    }
    this.stiffness = stiffness;
    if (stiffness) this.#sendStiffness();
    this.bones.assign(bones);
    if (bones.length > 0) this.bones.resend();
    this.applyHandles();
    this.deformer.setTargets(kept);
    this.#host.poseChanged();
  }

  // ---------------------------------------------------------------- stiffness

  /**
   * Paints every triangle (one value per triangle, checked as the core checks it), or none
   * with undefined; the deformer gets it at once when its method takes stiffness. Throws,
   * changing nothing, for bad values.
   */
  setStiffness(values: Float64Array | undefined): void {
    if (values) checkStiffness(values, this.shape.mesh.triangleCount);
    const previous = this.stiffness;
    this.stiffness = values?.slice();
    try {
      this.#sendStiffness();
    } catch (error) {
      this.stiffness = previous;
      throw error;
    }
  }

  /**
   * One dab of the brush at (x, y) in the pose on screen: `value` on the triangles whose
   * centroids are within `radius` (shape units). The deformer gets the painting before the
   * next step or when the stroke ends ({@link flushStiffness}), so a stroke is one change.
   * Returns whether anything changed.
   */
  paint(x: number, y: number, radius: number, value: number): boolean {
    const { stiffness, changed } = paintStiffness(
      this.stiffness,
      this.deformer.positionsView(),
      this.shape.mesh.triangles,
      x,
      y,
      radius,
      value,
    );
    if (!changed) return false;
    this.stiffness = stiffness; // the same array, painted: a new version
    this.#stiffnessPending = true;
    return true;
  }

  /** Gives the deformer (and the recording) the painting if the brush changed it since. */
  flushStiffness(): void {
    if (this.#stiffnessPending) this.#sendStiffness();
  }

  #sendStiffness(): void {
    this.#stiffnessPending = false;
    if (!this.deformer.hasStiffness) return;
    // An all-1 painting is none: the deformer is then exactly the unpainted one.
    const values = unpainted(this.stiffness) ? undefined : this.stiffness;
    this.deformer.setStiffness(values);
  }

  // ---------------------------------------------------------------- handles

  /**
   * The mesh point at (x, y) in the pose on screen (or the closest within `tolerance`): on
   * a puppet, on the front-most part there.
   */
  pointAt(x: number, y: number, tolerance = 0): MeshPoint | undefined {
    const positions = this.deformer.positionsView();
    const { triangles } = this.shape.mesh;
    const layers = this.triangleDepths();
    return layers
      ? locateFront(positions, triangles, layers, x, y, tolerance)
      : locate(positions, triangles, x, y, tolerance);
  }

  /**
   * The handle at (x, y) within `radius` (shape units), or -1: the nearest, and on a puppet
   * the one on the front-most part among those within reach.
   */
  handleAt(x: number, y: number, radius: number): number {
    const at = this.deformer.handlePositions();
    const layers = this.triangleDepths();
    if (!layers) return nearestPoint(at, x, y, radius);
    let best = -1;
    let bestDistance = Infinity;
    this.handles.forEach((h, i) => {
      const distance = Math.hypot(at[2 * i]! - x, at[2 * i + 1]! - y);
      if (distance > radius) return;
      const depth = layers[h.point.triangle]!;
      const bestDepth = best < 0 ? -Infinity : layers[this.handles[best]!.point.triangle]!;
      if (depth > bestDepth || (depth === bestDepth && distance < bestDistance)) {
        best = i;
        bestDistance = distance;
      }
    });
    return best;
  }

  /** A new handle at `point`, last, its target where the point is; the others keep theirs. */
  addHandle(point: MeshPoint): Handle {
    const handle = newHandle(point);
    this.handles.push(handle);
    this.applyHandles();
    return handle;
  }

  /**
   * Gives the deformer (and the recording) the handle set, after the caller changed
   * {@link handles}: handles still in the list keep their targets, turns and pointers; new
   * ones start where they are.
   */
  applyHandles(): void {
    const deformer = this.deformer;
    const targets = deformer.targets();
    const { turns, turned } = deformer.turns();
    const before = this.#sent.map((h, i) => ({ h, i }));
    const event = this.handlesEvent();
    deformer.setHandlePoints(event.handles.triangles, event.handles.barycentric);
    this.#sent = this.handles.slice();
    this.#rigSent = undefined; // a new handle set drops the deformer's rig
    if (before.length > 0) {
      const now = deformer.targets();
      this.handles.forEach((h, i) => {
        const was = before.find((b) => b.h === h)?.i;
        if (was === undefined) return;
        now[2 * i] = targets[2 * was]!;
        now[2 * i + 1] = targets[2 * was + 1]!;
      });
      deformer.setTargets(now);
      this.handles.forEach((h, i) => {
        const was = before.find((b) => b.h === h)?.i;
        if (was !== undefined && turns[was] !== turned[was]) deformer.setTurn(i, turns[was]! - turned[was]!);
        if (h.pointerId !== undefined) deformer.setHeld(i, true);
      });
    }
    this.#host.handlesChanged(this.handles.length);
    this.#host.schedule();
  }

  handlesEvent(): { handles: { triangles: number[]; barycentric: number[] } } {
    return {
      handles: {
        triangles: this.handles.map((h) => h.point.triangle),
        barycentric: this.handles.flatMap((h) => h.point.barycentric),
      },
    };
  }

  /** Where each handle is going, xy-interleaved. */
  targets(): Float64Array {
    return this.deformer.targets();
  }

  /** Moves the targets of `handles` by (dx, dy) (the motion pending in the paper's mode too). */
  nudge(handles: readonly Handle[], dx: number, dy: number): void {
    const targets = this.deformer.targets();
    for (const h of handles) {
      const i = this.handles.indexOf(h);
      if (i >= 0) this.deformer.setTarget(i, targets[2 * i]! + dx, targets[2 * i + 1]! + dy);
    }
  }

  /** Every handle stays where it is now (its target there). */
  pinHandlesWhereTheyAre(): void {
    this.deformer.pinHandles();
    this.#host.schedule();
  }

  /** Back to the rest pose; handles stay, at their rest places. */
  reset(): void {
    this.deformer.reset();
    this.#host.schedule();
    this.#host.poseChanged();
  }

  // ---------------------------------------------------------------- pointers on handles

  /** Starts dragging a handle from a shape point; false if another pointer holds it. */
  grab(index: number, pointerId: number, x: number, y: number, additive: boolean): boolean {
    const handle = this.handles[index]!;
    if (handle.pointerId !== undefined) return false;
    if (!additive && !handle.selected) this.handles.forEach((h) => (h.selected = false));
    handle.selected = additive ? !handle.selected : true;
    // The part being dragged comes to the front, unless the user ordered it.
    if (!handle.ordered) {
      const front = Math.max(...this.handles.filter((h) => h !== handle).map((h) => h.layer));
      if (handle.layer <= front) handle.layer = front + 1;
    }
    const [px, py] = this.deformer.grab(index);
    handle.pointerId = pointerId;
    handle.grab = [px - x, py - y];
    return true;
  }

  /** The pointer moved to a shape point: its handle's new target. */
  drag(pointerId: number, x: number, y: number): void {
    const index = this.handles.findIndex((h) => h.pointerId === pointerId);
    if (index < 0) return;
    const handle = this.handles[index]!;
    this.deformer.setTarget(index, x + handle.grab[0], y + handle.grab[1]);
  }

  /**
   * Starts turning a handle with a pointer at the shape point (x, y): the handle stays where
   * it is and turns as the pointer goes round it. False if another pointer holds it.
   */
  grabTurn(index: number, pointerId: number, x: number, y: number): boolean {
    const handle = this.handles[index]!;
    if (handle.pointerId !== undefined) return false;
    this.handles.forEach((h) => (h.selected = h === handle));
    const centre = this.deformer.grab(index);
    const turn = this.deformer.turns().turns[index]!;
    handle.pointerId = pointerId;
    handle.turning = { centre, angle: Math.atan2(y - centre[1], x - centre[0]), start: turn, turn };
    return true;
  }

  /** The pointer turning a handle moved to (x, y): the handle's turn follows its angle. */
  dragTurn(pointerId: number, x: number, y: number): void {
    const index = this.handles.findIndex((h) => h.pointerId === pointerId && h.turning);
    if (index < 0) return;
    const turning = this.handles[index]!.turning!;
    const angle = Math.atan2(y - turning.centre[1], x - turning.centre[0]);
    // The change since the last move, wrapped to (-pi, pi]: turns add up past a full circle.
    let delta = angle - turning.angle;
    delta -= 2 * Math.PI * Math.round(delta / (2 * Math.PI));
    turning.angle += delta;
    turning.turn += delta;
    this.deformer.setTurn(index, turning.turn);
  }

  release(pointerId: number): void {
    const index = this.handles.findIndex((h) => h.pointerId === pointerId);
    if (index >= 0) {
      const handle = this.handles[index]!;
      handle.pointerId = undefined;
      handle.turning = undefined;
      this.deformer.release(index);
    }
    this.endDragGesture();
  }

  removeHeld(pointerId: number): void {
    const at = this.handles.findIndex((h) => h.pointerId === pointerId);
    if (at < 0) return;
    this.handles.splice(at, 1);
    this.applyHandles();
    this.#gestureChanged = true;
    this.endDragGesture();
  }

  /**
   * Brings the selected handles' parts in front of every other part (`step` 1) or behind
   * them (-1), keeping their order among themselves; they keep that place when grabbed.
   * False when no handle is selected.
   */
  reorder(step: 1 | -1): boolean {
    const selected = this.handles.filter((h) => h.selected);
    const others = this.handles.filter((h) => !h.selected).map((h) => h.layer);
    if (selected.length === 0) return false;
    const layers = selected.map((h) => h.layer);
    const [low, high] = [Math.min(...layers), Math.max(...layers)];
    const shift = others.length === 0 ? 0 : step > 0 ? Math.max(...others) + 1 - low : Math.min(...others) - 1 - high;
    for (const h of selected) {
      h.layer += shift;
      h.ordered = true;
    }
    this.#host.schedule();
    return true;
  }

  get dragging(): boolean {
    return this.handles.some((h) => h.pointerId !== undefined);
  }

  // ---------------------------------------------------------------- puppets

  /** The joints a puppet's deformer poses with (copies); none for other shapes. */
  get joints(): PuppetJoint[] {
    return this.shape.puppet ? deformerJoints(this.deformer) : [];
  }

  /**
   * Replaces a puppet's joints (the deformer analyses its systems again); throws (code
   * `invalid-joint`), changing nothing, for a part out of range or a point not on both
   * parts, or when the shape is no puppet.
   */
  setJoints(joints: readonly PuppetJoint[]): void {
    if (!this.shape.puppet) throw new Error("only a puppet (an SVG of several layers) has joints");
    setDeformerJoints(this.deformer, joints);
    if (this.selectedJoint !== undefined && this.selectedJoint >= joints.length) this.selectedJoint = undefined;
    this.#host.schedule();
  }

  /** Each triangle's layer: its part's depth for a puppet (see {@link depths}); undefined for other shapes. */
  triangleDepths(): Int32Array | undefined {
    const { puppet } = this.shape;
    const depths = this.depths;
    if (!puppet || !depths) return undefined;
    if (this.#triangleDepths?.depths !== depths) {
      this.#triangleDepths = { depths, layers: Int32Array.from(puppet.partOf, (part) => depths[part] ?? 0) };
    }
    return this.#triangleDepths.layers;
  }

  /**
   * Moves a puppet's part one step in front of the next part (`step` 1) or behind it (-1);
   * false when it is already in front (or at the back).
   */
  reorderPart(part: number, step: 1 | -1): boolean {
    const next = this.depths && stepDepth(this.depths, part, step);
    if (!next) return false;
    this.depths = next;
    this.#host.schedule();
    return true;
  }

  // ---------------------------------------------------------------- gestures and history

  snapshot(): Snapshot {
    const targets = this.deformer.targets();
    return {
      shape: this.shape,
      parts: this.parts,
      method: this.settings.method,
      lambda: this.settings.lambda,
      positions: this.deformer.positions(),
      atRest: this.atRest,
      handles: this.handles.map((h, i) => ({
        point: h.point,
        target: [targets[2 * i]!, targets[2 * i + 1]!],
        layer: h.layer,
        ordered: h.ordered,
      })),
      stiffness: this.stiffness?.slice(),
      bones: [...this.bones.list],
      ...(this.shape.puppet ? { depths: this.depths, joints: this.joints } : {}),
    };
  }

  restore(snapshot: Snapshot): void {
    this.releasePointers();
    if (snapshot.method !== this.settings.method || snapshot.lambda !== this.settings.lambda) {
      this.settings.method = snapshot.method;
      this.settings.lambda = snapshot.lambda;
      if (snapshot.shape === this.shape) this.deformer.setOptions(this.deformerOptions());
      this.showMethod(snapshot.method, snapshot.lambda);
    }
    if (snapshot.shape !== this.shape) {
      this.parts = snapshot.parts;
      this.adopt(snapshot.shape, undefined, true);
    }
    // At rest is the rest pose, put back as such (a reset).
    if (snapshot.atRest) this.deformer.reset();
    else this.deformer.setPositions(snapshot.positions);
    this.stiffness = snapshot.stiffness?.slice();
    this.#sendStiffness();
    this.bones.assign(snapshot.bones ?? []);
    this.bones.resend();
    this.handles = snapshot.handles.map((h) => ({
      ...newHandle(h.point),
      // Work saved before layers existed has none: one layer.
      layer: h.layer ?? 0,
      ordered: h.ordered ?? false,
    }));
    if (this.shape.puppet) {
      if (snapshot.depths) this.depths = snapshot.depths;
      if (snapshot.joints && !sameJoints(snapshot.joints, this.joints)) {
        setDeformerJoints(this.deformer, snapshot.joints);
        this.selectedJoint = undefined;
      }
    }
    this.#sent = [];
    this.applyHandles();
    this.deformer.setTargets(snapshot.handles.flatMap((h) => h.target));
    this.#host.poseChanged();
  }

  /** Undo (or redo, `forward`); false when there is nothing to go back (or forth) to. */
  travel(forward: boolean): boolean {
    const current = this.snapshot();
    const snapshot = forward ? this.history.redo(current) : this.history.undo(current);
    if (snapshot) this.restore(snapshot);
    this.#host.historyChanged();
    return snapshot !== undefined;
  }

  /** Runs one complete gesture (an undoable unit) that is not a drag. */
  gesture(change: () => void): void {
    // The first shape, while the widget is made, has nothing before it.
    const before = (this.shape as Shape | undefined) && this.snapshot();
    change();
    if (before) this.history.push(before);
    this.#host.historyChanged();
    this.#host.schedule();
  }

  /** A drag or press begins: the state before it is kept for undo (once for overlapping ones). */
  beginGesture(): void {
    this.#gestureBefore ??= this.snapshot();
  }

  /** The gesture under way changed something (it will be undoable). */
  markChanged(): void {
    this.#gestureChanged = true;
  }

  releasePointers(): void {
    this.handles.forEach((h, i) => {
      if (h.pointerId === undefined) return;
      h.pointerId = undefined;
      h.turning = undefined;
      this.deformer.release(i);
    });
    this.endDragGesture();
  }

  endDragGesture(): void {
    if (this.#gestureBefore && !this.dragging) {
      if (this.#gestureChanged) this.history.push(this.#gestureBefore);
      this.#gestureBefore = undefined;
      this.#gestureChanged = false;
      this.#host.historyChanged();
    }
  }

  // ---------------------------------------------------------------- steps

  /** Whether the "defop" method is chosen and the rig fits the shape and the handles. */
  get posingWithRig(): boolean {
    return (
      this.settings.method === "defop" && this.rig !== undefined && this.rig.fits(this.shape, this.handles, this.joints)
    );
  }

  /**
   * Moves the handles toward their targets, one call into the core (`Deformer.advance`);
   * adds the frame's stage timings to `timings` and returns the number of steps taken (a
   * rig's evaluation counts as one).
   */
  advance(timings: Timings): number {
    this.evaluationMs = 0;
    this.clamped = false;
    this.flushStiffness();
    if (this.handles.length === 0) return 0;
    this.#sendTracking();
    this.#sendRig();
    const frame = this.deformer.advance();
    this.clamped = frame.clamped;
    this.evaluationMs = frame.evaluation;
    const t = frame.timings;
    timings.assembly += t.assembly;
    timings.factorisation += t.factorisation;
    timings.dirichletFactorisation += t.dirichletFactorisation;
    timings.solve += t.solve;
    timings.integration += t.integration;
    return frame.steps;
  }

  /** The tracking settings to the deformer when they changed (no call otherwise). */
  #sendTracking(): void {
    const { maxStep, maxSubsteps, noFoldovers, paperMode } = this.settings;
    const key = `${maxStep} ${maxSubsteps} ${noFoldovers} ${paperMode}`;
    if (key === this.#trackingSent) return;
    this.deformer.setTracking({ maxStep, maxSubsteps, noFoldovers, paper: paperMode });
    this.#trackingSent = key;
  }

  /**
   * The rig to the deformer when the one that poses changed: it poses while it fits (no
   * call otherwise; a new handle set drops the deformer's rig, and {@link applyHandles}
   * forgets it).
   */
  #sendRig(): void {
    const rig = this.posingWithRig ? this.rig : undefined;
    if (rig === this.#rigSent) return;
    this.deformer.setRig(rig?.operator);
    if (rig && this.rigsOnGpu && this.deformer.setRigOnGpu(true)) this.gpuRigVersion++;
    this.#rigSent = rig;
  }

  // ---------------------------------------------------------------- recording and replay

  /** Starts recording every change of the deformer (the deformer records; see `Deformer.startRecording`). */
  startRecording(): void {
    this.flushStiffness();
    this.deformer.startRecording(this.shape.spec);
    this.#host.historyChanged();
  }

  stopRecording(): Session | undefined {
    const json = this.deformer.stopRecording();
    this.#host.historyChanged();
    return json === undefined ? undefined : Session.fromCoreJson(json);
  }

  /**
   * Replays `session` on `shape` as the core's `session::replay` does: from the rest pose
   * without handles and with the session's header options (every one of them, as
   * `sessionJson` writes them), each event carried out in order. `paused` is awaited after
   * each step with the count so far (the widget draws then) and stops the replay by
   * returning false. The whole replay is one undoable step; one that fails partway leaves
   * everything as it was.
   */
  async replay(session: Session, shape: Shape, paused: (steps: number) => Promise<boolean>): Promise<void> {
    if (this.replaying) throw new Error("a replay is already running");
    this.releasePointers();
    const before = this.snapshot();
    this.replaying = true;
    this.deformer.pauseRecording(true);
    try {
      if (shape !== this.shape) {
        this.parts = undefined;
        this.install(shape);
      }
      this.applyOptions(session.data.options);
      // A puppet's joints as the recording started.
      const puppet = session.data.puppet;
      if (puppet && !sameJoints(puppet.joints, this.joints)) this.apply({ joints: puppet.joints });
      this.apply({ stiffness: undefined });
      this.apply({ bones: { triangles: [], barycentric: [] } });
      this.apply({ reset: true });
      this.apply({ handles: { triangles: [], barycentric: [] } });
      let steps = 0;
      for (const event of session.data.events) {
        this.apply(event);
        if (("step" in event || "turn" in event || "rigPose" in event) && !(await paused(++steps))) return;
      }
    } catch (error) {
      this.restore(before);
      throw error;
    } finally {
      this.replaying = false;
      this.deformer.pauseRecording(false);
    }
    this.pinHandlesWhereTheyAre();
    this.history.push(before);
  }

  /**
   * Carries out one recorded event. A `rig` event poses with the widget's rig (the
   * "defop" method shown) when it is the rig the session names, and throws, saying so,
   * when it is not; `rigPose` poses with it at the recorded targets.
   */
  apply(event: SessionEvent): void {
    if ("handles" in event) {
      const { triangles, barycentric } = event.handles;
      this.deformer.setHandlePoints(triangles, barycentric);
      this.handles = Array.from(triangles, (triangle, i) =>
        newHandle({
          triangle,
          barycentric: [barycentric[3 * i]!, barycentric[3 * i + 1]!, barycentric[3 * i + 2]!],
        }),
      );
      this.#sent = this.handles.slice();
      this.#rigSent = undefined;
    } else if ("step" in event) {
      this.deformer.step(event.step);
    } else if ("turn" in event) {
      this.deformer.stepTurning(event.turn.velocities, event.turn.turns);
    } else if ("positions" in event) {
      this.deformer.setPositions(event.positions);
    } else if ("options" in event) {
      this.applyOptions(event.options);
    } else if ("bones" in event) {
      const { triangles, barycentric } = event.bones;
      this.deformer.setBones(triangles, barycentric);
      this.bones.assign(bonesFrom(triangles, barycentric));
    } else if ("joints" in event) {
      setDeformerJoints(this.deformer, event.joints);
      this.selectedJoint = undefined;
    } else if ("stiffness" in event) {
      const values = event.stiffness ?? undefined;
      this.deformer.setStiffness(values);
      this.stiffness = values === undefined ? undefined : Float64Array.from(values);
      this.#stiffnessPending = false;
    } else if ("rig" in event) {
      this.#applyRig(event.rig?.checksum);
    } else if ("rigPose" in event) {
      this.deformer.poseWithRig(event.rigPose);
    } else {
      this.deformer.reset();
    }
  }

  /** A recorded `rig` event: the rig named by `checksum` poses (the widget's, if it is that rig), or none (undefined). */
  #applyRig(checksum: string | undefined): void {
    if (checksum === undefined) {
      this.deformer.setRig(undefined);
      this.#rigSent = undefined;
      return;
    }
    const rig = this.rig;
    if (rig === undefined || this.deformer.rigChecksum(rig.operator) !== checksum) {
      throw new Error(
        `the session poses with a trained rig that is not loaded (the rig whose operator file has checksum ${checksum}): ` +
          'open that rig\'s .defop file ("Open rig…"), then replay',
      );
    }
    this.deformer.setRig(rig.operator);
    if (this.rigsOnGpu && this.deformer.setRigOnGpu(true)) this.gpuRigVersion++;
    this.#rigSent = rig;
    if (this.settings.method !== "defop") this.showMethod("defop", this.settings.lambda);
  }
}

/**
 * The mesh of some triangles (3 vertex indices each) on its own: their vertices in order,
 * their rest positions and, given, posed ones, and the triangles numbered among them.
 */
function subMesh(
  triangles: ArrayLike<number>,
  rest: ArrayLike<number>,
  posed: ArrayLike<number> = rest,
): { vertices: number[]; rest: Float64Array; posed: Float64Array; triangles: Uint32Array } {
  const vertices = [...new Set(Array.from(triangles))];
  const index = new Map(vertices.map((v, i) => [v, i]));
  const pick = (from: ArrayLike<number>) => {
    const out = new Float64Array(2 * vertices.length);
    vertices.forEach((v, i) => out.set([from[2 * v]!, from[2 * v + 1]!], 2 * i));
    return out;
  };
  return {
    vertices,
    rest: pick(rest),
    posed: pick(posed),
    triangles: Uint32Array.from(triangles, (v) => index.get(v)!),
  };
}
