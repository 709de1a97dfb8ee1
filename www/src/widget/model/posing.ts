/**
 * What the widget poses, apart from the page: the shape and its deformer, the handles
 * (where each is going, which pointer holds it), the undo history, the recording, and the
 * steps that move the handles toward their targets. It knows nothing of the DOM; it tells
 * its host (the widget) what to show through {@link PosingHost}.
 *
 * Each frame, {@link Posing.advance} gives every handle the velocity that takes it toward its
 * target (the pointer, or where a pin was left), split into substeps no longer than
 * `maxStep` of the shape's size, and steps the deformer; a step that fails is tried again
 * with smaller velocities. With the "defop" method and a trained {@link Rig} that fits the
 * shape and handles, a frame is instead one evaluation of the rig at the handles' targets.
 */
import { Deformer, checkStiffness, type DeformerOptions, type Timings } from "../../core.js";
import { PointMapper } from "../../import.js";
import { displacementVelocities, largestGap, substepCount, trackingVelocities } from "./drag.js";
import { History } from "./history.js";
import { METHODS, methodOptions, widgetMethod, type MethodPreset } from "./methods.js";
import { locate, pointPosition, type MeshPoint } from "./picking.js";
import { Recorder, type Session, type SessionEvent } from "../../session.js";
import { Bones, bonesEvent, bonesFrom, type Bone } from "./bones.js";
import { carryStiffness, paintStiffness, unpainted } from "./stiffness.js";
import type { Rig } from "./rig.js";
import type { Loaded, Shape } from "./shape.js";
import { newHandle, type Handle, type HandleState } from "./handle.js";

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

/** A failed step is tried again with its velocities scaled by these, in turn. */
const RETRY_SCALES = [0.5, 0.25, 0.125];
/** Largest turn of a handle in one substep, radians. */
const MAX_TURN_STEP = 0.1;

export class Posing {
  readonly settings: PosingSettings;
  readonly history = new History<Snapshot>();
  readonly recorder = new Recorder();
  shape!: Shape;
  deformer!: Deformer;
  handles: Handle[] = [];
  parts: Parts | undefined;
  atRest = true;
  /** While a session replays: nothing is recorded. */
  replaying = false;
  /** The trained rig the widget holds (it poses with the "defop" method while it fits). */
  rig: Rig | undefined;
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
  /** The rig's last pose and the targets it was for (skipped when they have not moved). */
  #rigPose: Float64Array | undefined;
  #rigTargets: Float64Array | undefined;
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

  /** Makes `shape` current with a fresh deformer, without handles, at rest. */
  install(shape: Shape, orders?: Uint32Array[]): void {
    this.adopt(shape, orders, true);
    this.handles = [];
    this.atRest = true;
    this.applyHandles();
    this.#host.poseChanged();
  }

  /**
   * Makes `shape` current with a fresh deformer of the current method (handles and pose
   * are the caller's to set); fails without changing anything. A recording ends.
   */
  adopt(shape: Shape, orders: Uint32Array[] | undefined, refit: boolean): void {
    const deformer = new Deformer(shape.mesh.positions, shape.mesh.triangles, this.deformerOptions(), orders);
    this.deformer?.free();
    this.deformer = deformer;
    this.#rigTargets = undefined;
    this.shape = shape;
    this.stiffness = undefined;
    this.#stiffnessPending = false;
    this.bones.forget();
    this.recorder.stop();
    this.#host.adopted(shape, deformer, refit);
  }

  deformerOptions(): DeformerOptions {
    return methodOptions(this.settings.method, this.settings.lambda);
  }

  /** Changes the method and/or lambda (recorded). */
  setMethod(method: MethodPreset, lambda: number): void {
    if (!Object.hasOwn(METHODS, method)) throw new Error(`unknown method "${method}"`);
    const options = methodOptions(method, lambda);
    // Another method is set up with the pose and handles (the core's MethodOptions::apply);
    // throws, changing nothing, for a bad lambda.
    this.deformer.setOptions(options);
    this.record({ options });
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
    const handles = this.handles.map((h) => ({
      rest: pointPosition(old.shape.mesh.positions, old.shape.mesh.triangles, h.point),
      target: h.target,
      layer: h.layer,
      ordered: h.ordered,
    }));
    this.adopt(shape, orders, false);
    this.handles = [];
    if (!old.atRest) {
      const mapper = new PointMapper(old.shape.mesh.positions, old.shape.mesh.triangles, shape.mesh.positions);
      try {
        this.deformer.setPositions(mapper.map(old.positions));
      } finally {
        mapper.free();
      }
    }
    this.atRest = old.atRest;
    const { positions: rest, triangles } = shape.mesh;
    for (const { rest: at, target, layer, ordered } of handles) {
      const point =
        locate(rest, triangles, at[0], at[1], 1e-6 * shape.size) ??
        locate(rest, triangles, at[0], at[1], 0.05 * shape.size);
      if (point) this.handles.push({ ...newHandle(point), target: [...target], layer, ordered });
    }
    this.stiffness = stiffness;
    if (stiffness) this.#sendStiffness();
    this.bones.assign(bones);
    if (bones.length > 0) this.bones.resend();
    this.applyHandles();
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
    this.record({ stiffness: values?.slice() });
  }

  // ---------------------------------------------------------------- handles

  addHandle(point: MeshPoint): Handle {
    const [x, y] = pointPosition(this.deformer.positionsView(), this.shape.mesh.triangles, point);
    const handle: Handle = { ...newHandle(point), target: [x, y] };
    this.handles.push(handle);
    this.applyHandles();
    return handle;
  }

  /** Sends the handle set to the deformer (and the recording). */
  applyHandles(): void {
    this.#rigTargets = undefined;
    const event = this.handlesEvent();
    this.deformer.setHandlePoints(event.handles.triangles, event.handles.barycentric);
    this.record(event);
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

  pinHandlesWhereTheyAre(): void {
    const p = this.deformer.handlePositions();
    this.handles.forEach((h, i) => {
      h.target = [p[2 * i]!, p[2 * i + 1]!];
      h.pending = [0, 0];
    });
    this.#host.schedule();
  }

  /** Back to the rest pose; handles stay, at their rest places. */
  reset(): void {
    this.#rigTargets = undefined;
    this.deformer.reset();
    this.record({ reset: true });
    this.atRest = true;
    this.pinHandlesWhereTheyAre();
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
    const p = this.deformer.handlePositions();
    handle.pointerId = pointerId;
    handle.grab = [p[2 * index]! - x, p[2 * index + 1]! - y];
    handle.target = [p[2 * index]!, p[2 * index + 1]!];
    return true;
  }

  /** The pointer moved to a shape point: its handle's new target. */
  drag(pointerId: number, x: number, y: number): void {
    const handle = this.handles.find((h) => h.pointerId === pointerId);
    if (!handle) return;
    const next: [number, number] = [x + handle.grab[0], y + handle.grab[1]];
    handle.pending = [handle.pending[0] + next[0] - handle.target[0], handle.pending[1] + next[1] - handle.target[1]];
    handle.target = next;
  }

  /**
   * Starts turning a handle with a pointer at the shape point (x, y): the handle stays where
   * it is and turns as the pointer goes round it. False if another pointer holds it.
   */
  grabTurn(index: number, pointerId: number, x: number, y: number): boolean {
    const handle = this.handles[index]!;
    if (handle.pointerId !== undefined) return false;
    this.handles.forEach((h) => (h.selected = h === handle));
    const p = this.deformer.handlePositions();
    handle.pointerId = pointerId;
    handle.target = [p[2 * index]!, p[2 * index + 1]!];
    handle.turning = { angle: Math.atan2(y - p[2 * index + 1]!, x - p[2 * index]!), start: handle.turn };
    return true;
  }

  /** The pointer turning a handle moved to (x, y): the handle's turn follows its angle. */
  dragTurn(pointerId: number, x: number, y: number): void {
    const handle = this.handles.find((h) => h.pointerId === pointerId && h.turning);
    if (!handle) return;
    const angle = Math.atan2(y - handle.target[1], x - handle.target[0]);
    // The change since the last move, wrapped to (-pi, pi]: turns add up past a full circle.
    let delta = angle - handle.turning!.angle;
    delta -= 2 * Math.PI * Math.round(delta / (2 * Math.PI));
    handle.turning = { ...handle.turning!, angle: handle.turning!.angle + delta };
    handle.turn += delta;
  }

  release(pointerId: number): void {
    const handle = this.handles.find((h) => h.pointerId === pointerId);
    if (handle) {
      handle.pointerId = undefined;
      handle.turning = undefined;
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

  // ---------------------------------------------------------------- gestures and history

  snapshot(): Snapshot {
    return {
      shape: this.shape,
      parts: this.parts,
      method: this.settings.method,
      lambda: this.settings.lambda,
      positions: this.deformer.positions(),
      atRest: this.atRest,
      handles: this.handles.map((h) => ({ point: h.point, target: [...h.target], layer: h.layer, ordered: h.ordered })),
      stiffness: this.stiffness?.slice(),
      bones: [...this.bones.list],
    };
  }

  restore(snapshot: Snapshot): void {
    this.releasePointers();
    this.#rigTargets = undefined;
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
    this.deformer.setPositions(snapshot.positions);
    this.record({ positions: snapshot.positions });
    this.atRest = snapshot.atRest;
    this.stiffness = snapshot.stiffness?.slice();
    this.#sendStiffness();
    this.bones.assign(snapshot.bones ?? []);
    this.bones.resend();
    this.handles = snapshot.handles.map((h) => ({
      ...newHandle(h.point),
      target: [...h.target],
      // Work saved before layers existed has none: one layer.
      layer: h.layer ?? 0,
      ordered: h.ordered ?? false,
    }));
    this.applyHandles();
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
    for (const h of this.handles) h.pointerId = undefined;
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
    return this.settings.method === "defop" && this.rig !== undefined && this.rig.fits(this.shape, this.handles);
  }

  /**
   * Moves the handles toward their targets; returns the number of deformer steps taken
   * (a rig's evaluation counts as one).
   */
  advance(timings: Timings): number {
    this.evaluationMs = 0;
    this.clamped = false;
    this.flushStiffness();
    const n = this.handles.length;
    if (n === 0) return 0;
    if (this.posingWithRig) return this.#evaluateRig(this.rig!);
    const { maxStep, maxSubsteps, paperMode } = this.settings;
    const longest = maxStep * this.shape.size;
    let current = this.deformer.handlePositions();
    if (paperMode) {
      const displacement = new Float64Array(2 * n);
      this.handles.forEach((h, i) => {
        displacement[2 * i] = h.pending[0];
        displacement[2 * i + 1] = h.pending[1];
        h.pending = [0, 0];
      });
      const distance = largestGap(new Float64Array(2 * n), displacement);
      if (distance === 0) return 0;
      const count = Math.min(substepCount(distance, longest), maxSubsteps);
      const velocities = displacementVelocities(displacement, count);
      for (let s = 0; s < count && !this.clamped; s++) this.step(velocities, timings);
      current = this.deformer.handlePositions();
      // The handles end where the deformation took them; pins stay pins.
      this.handles.forEach((h, i) => {
        if (h.pointerId === undefined) h.target = [current[2 * i]!, current[2 * i + 1]!];
      });
      return count;
    }
    const targets = new Float64Array(2 * n);
    this.handles.forEach((h, i) => {
      targets[2 * i] = h.target[0];
      targets[2 * i + 1] = h.target[1];
    });
    const gap = largestGap(current, targets);
    const turnGap = Math.max(...this.handles.map((h) => Math.abs(h.turn - h.turned)));
    const moves = gap > 1e-5 * this.shape.size;
    if (!moves && !(turnGap > 1e-9)) return 0;
    const needed = Math.max(moves ? substepCount(gap, longest) : 1, Math.ceil(turnGap / MAX_TURN_STEP - 1e-9));
    const count = Math.min(needed, maxSubsteps);
    const velocities = new Float64Array(2 * n);
    let taken = 0;
    for (; taken < count && !this.clamped; taken++) {
      trackingVelocities(current, targets, needed - taken, velocities);
      if (!moves) velocities.fill(0);
      const turns =
        turnGap > 1e-9 ? Float64Array.from(this.handles, (h) => (h.turn - h.turned) / (needed - taken)) : undefined;
      this.step(velocities, timings, turns);
      current = this.deformer.handlePositions();
    }
    // Stopped short to keep the triangles unfolded: handles let go stay where they are
    // (they would only stop short again), held ones keep their targets.
    if (this.clamped) this.pinUnheld();
    return taken;
  }

  /**
   * The rig's pose for the handles' targets (every handle goes straight to its target: the
   * pose is a function of the targets, so there is nothing to step through), recorded as a
   * pose; nothing when the targets are those of the last evaluation.
   */
  #evaluateRig(rig: Rig): number {
    const last = this.#rigTargets;
    if (
      last?.length === 2 * this.handles.length &&
      this.handles.every((h, i) => h.target[0] === last[2 * i] && h.target[1] === last[2 * i + 1])
    ) {
      return 0;
    }
    const size = 2 * this.shape.mesh.vertexCount;
    if (this.#rigPose?.length !== size) this.#rigPose = new Float64Array(size);
    const started = performance.now();
    rig.evaluate(this.handles, this.#rigPose);
    this.evaluationMs = performance.now() - started;
    this.deformer.setPositions(this.#rigPose);
    // Kept in place (allocated again only when the handle count changes).
    const kept = last?.length === 2 * this.handles.length ? last : new Float64Array(2 * this.handles.length);
    this.handles.forEach((h, i) => kept.set(h.target, 2 * i));
    this.#rigTargets = kept;
    this.atRest = false;
    this.record({ positions: this.#rigPose });
    return 1;
  }

  /**
   * One deformer step; a step that fails (the deformer is then unchanged) is tried again
   * with smaller velocities before the error is passed on. With `noFoldovers` (the
   * default) the step is the core's guarded one: split where it would flip a triangle, and
   * stopped short (`clamped`) where even small pieces would; each plain step it took is
   * recorded as it was taken, so a replay repeats it bit for bit.
   */
  step(velocities: Float64Array, timings: Timings, turns?: Float64Array): void {
    const scaled = (a: Float64Array, f: number) => (f === 1 ? a : a.map((x) => x * f));
    /** The plain steps taken: velocities and turns each, as fractions of those given. */
    const attempt = (v: Float64Array, w: Float64Array | undefined): [Float64Array, Float64Array | undefined][] => {
      if (!this.settings.noFoldovers) {
        if (w) this.deformer.stepTurning(v, w);
        else this.deformer.step(v);
        return [[v, w]];
      }
      const report = this.deformer.stepWithoutFoldovers(v, {}, w);
      if (report.clamped) this.clamped = true;
      // The core's own products: `step` with these repeats each piece to the bit.
      return report.steps.map((f) => [scaled(v, f), w && scaled(w, f)]);
    };
    let taken: [Float64Array, Float64Array | undefined][] | undefined;
    try {
      taken = attempt(velocities, turns);
    } catch (error) {
      for (const f of RETRY_SCALES) {
        try {
          taken = attempt(scaled(velocities, f), turns && scaled(turns, f));
          break;
        } catch {
          // try smaller still
        }
      }
      if (!taken) {
        // A method without turning handles, say: the turns asked for are dropped.
        this.handles.forEach((h) => (h.turn = h.turned));
        throw error;
      }
    }
    if (taken.length === 0) return;
    this.atRest = false;
    for (const [v, w] of taken) {
      if (w) {
        this.handles.forEach((h, i) => (h.turned += w[i]!));
        this.record({ turn: { velocities: v, turns: w } });
      } else {
        this.record({ step: v });
      }
    }
    const t = this.deformer.timings();
    timings.assembly += t.assembly;
    timings.factorisation += t.factorisation;
    timings.dirichletFactorisation += t.dirichletFactorisation;
    timings.solve += t.solve;
    timings.integration += t.integration;
  }

  /** After a step failed: pins stay where they are; dragged handles keep their targets. */
  pinUnheld(): void {
    const p = this.deformer.handlePositions();
    this.handles.forEach((h, i) => {
      if (h.pointerId !== undefined) return;
      h.target = [p[2 * i]!, p[2 * i + 1]!];
      h.turn = h.turned;
    });
  }

  // ---------------------------------------------------------------- recording and replay

  /** Starts recording every change of the deformer. */
  startRecording(): void {
    const start: SessionEvent[] = this.atRest ? [{ reset: true }] : [{ positions: this.deformer.positions() }];
    if (this.handles.length > 0) start.push(this.handlesEvent());
    this.flushStiffness();
    if (this.deformer.hasStiffness && !unpainted(this.stiffness)) start.push({ stiffness: this.stiffness!.slice() });
    if (this.deformer.hasBones && this.bones.list.length > 0) start.push(bonesEvent(this.bones.list));
    const { mesh, spec } = this.shape;
    this.recorder.start({ shape: spec, mesh, options: this.deformerOptions() }, start);
    this.#host.historyChanged();
  }

  stopRecording(): Session | undefined {
    const session = this.recorder.stop();
    this.#host.historyChanged();
    return session;
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
    try {
      if (shape !== this.shape) {
        this.parts = undefined;
        this.install(shape);
      }
      this.applyOptions(session.data.options);
      this.apply({ stiffness: undefined });
      this.apply({ bones: { triangles: [], barycentric: [] } });
      this.apply({ reset: true });
      this.apply({ handles: { triangles: [], barycentric: [] } });
      let steps = 0;
      for (const event of session.data.events) {
        this.apply(event);
        if (("step" in event || "turn" in event) && !(await paused(++steps))) return;
      }
    } catch (error) {
      this.restore(before);
      throw error;
    } finally {
      this.replaying = false;
    }
    this.pinHandlesWhereTheyAre();
    this.history.push(before);
  }

  /** Carries out one recorded event. */
  apply(event: SessionEvent): void {
    this.#rigTargets = undefined;
    if ("handles" in event) {
      const { triangles, barycentric } = event.handles;
      this.deformer.setHandlePoints(triangles, barycentric);
      this.handles = Array.from(triangles, (triangle, i) =>
        newHandle({
          triangle,
          barycentric: [barycentric[3 * i]!, barycentric[3 * i + 1]!, barycentric[3 * i + 2]!],
        }),
      );
      this.pinHandlesWhereTheyAre();
    } else if ("step" in event) {
      this.deformer.step(event.step);
      this.atRest = false;
    } else if ("turn" in event) {
      this.deformer.stepTurning(event.turn.velocities, event.turn.turns);
      this.atRest = false;
    } else if ("positions" in event) {
      this.deformer.setPositions(event.positions);
      this.atRest = false;
    } else if ("options" in event) {
      this.applyOptions(event.options);
    } else if ("bones" in event) {
      const { triangles, barycentric } = event.bones;
      this.deformer.setBones(triangles, barycentric);
      this.bones.assign(bonesFrom(triangles, barycentric));
    } else if ("stiffness" in event) {
      const values = event.stiffness ?? undefined;
      this.deformer.setStiffness(values);
      this.stiffness = values === undefined ? undefined : Float64Array.from(values);
      this.#stiffnessPending = false;
    } else {
      this.deformer.reset();
      this.atRest = true;
    }
  }

  record(event: SessionEvent): void {
    if (!this.replaying) this.recorder.record(event);
  }
}
