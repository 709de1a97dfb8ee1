/**
 * The animation's frames, computed from a {@link Timeline} against the posing core. Frame
 * 0 is the first key's pose; each next frame sets every handle's target to the
 * timeline's interpolation at the frame's time and takes the steps a frame of dragging
 * takes: one `Deformer.advance`, the core's interaction loop (the largest gap split into
 * substeps of at most `maxStep` of the shape's size, at most `maxSubsteps` of them, each
 * with the tracking velocities `(target - current) / remaining`, through the guarded step
 * when `noFoldovers` is on, a failed step retried with smaller velocities). AKAP is
 * path-dependent, so frame i is defined by the frames before it: they are computed in
 * order, on a deformer of the animation's own made afresh from the rest mesh (the user's
 * deformer is never stepped), so computing twice gives the same bits. With a trained rig
 * that fits the handles (the "defop" method), the deformer poses with it: a frame is the
 * rig's pose for the targets.
 *
 * Frames are kept once computed; whoever holds an {@link AnimationFrames} makes a new one
 * when the keys, method, stiffness, bones, handles or step settings change ({@link framesKey}).
 */
import { Deformer, type DeformerOptions, type MeshData, type RigOperator } from "../../core.js";
import { frameCount, frameTime, targetsAt, type HandleSet, type Key } from "./timeline.js";

/** What the frames are computed from (the arrays are not copied: do not change them). */
export interface FrameSource {
  mesh: Pick<MeshData, "positions" | "triangles">;
  options: DeformerOptions;
  /** Per-triangle stiffness, or undefined for none (given only to methods that take it). */
  stiffness: Float64Array | undefined;
  /** The bones as `Deformer.setBones` takes them (given only to methods that have them), laid in the first key's pose. */
  bones?: { triangles: number[]; barycentric: number[] } | undefined;
  handles: HandleSet;
  keys: readonly Key[];
  fps: number;
  /** Longest handle move per substep, as a share of the shape's size. */
  maxStep: number;
  maxSubsteps: number;
  noFoldovers: boolean;
  /** A trained rig (a `DefOp`) that poses instead of steps (the "defop" method with a fitting rig). */
  rig?: RigOperator | undefined;
}

/** One frame: the vertex positions and the handles' positions, xy-interleaved. */
export interface Frame {
  positions: Float64Array;
  handles: Float64Array;
  /** A step stopped short to keep triangles from folding over. */
  clamped: boolean;
}

/**
 * One frame of tracking on `deformer`: the handles' targets set and one `advance`, as a
 * frame of dragging takes them. Returns the substeps taken and whether a step stopped short.
 */
export function trackFrame(deformer: Deformer, targets: Float64Array): { steps: number; clamped: boolean } {
  deformer.setTargets(targets);
  const { steps, clamped } = deformer.advance();
  return { steps, clamped };
}

/** What the frames depend on beyond the timeline's version, as one comparable string. */
export function framesKey(parts: Record<string, unknown>): string {
  return JSON.stringify(parts);
}

export class AnimationFrames {
  readonly source: FrameSource;
  readonly #frames: Frame[] = [];
  #deformer: Deformer | undefined;
  #targets: Float64Array;

  constructor(source: FrameSource) {
    if (source.keys.length === 0) throw new Error("there are no keys: capture one (K) first");
    this.source = source;
    this.#targets = new Float64Array(source.keys[0]!.targets.length);
  }

  /** How many frames the animation has: one per 1/fps from 0 to the last key. */
  get count(): number {
    const { keys, fps } = this.source;
    return frameCount(keys.at(-1)!.time, fps);
  }

  /** How many frames are computed so far. */
  get computed(): number {
    return this.#frames.length;
  }

  /** Frame `index`, computing the frames up to it (in order) if needed. */
  frame(index: number): Frame {
    if (!(Number.isInteger(index) && index >= 0 && index < this.count)) {
      throw new RangeError(`there is no frame ${index} (there are ${this.count})`);
    }
    while (this.#frames.length <= index) this.#frames.push(this.#next());
    return this.#frames[index]!;
  }

  /** Every frame's positions (computed if needed; the arrays are the cache's). */
  all(): Frame[] {
    if (this.count > 0) this.frame(this.count - 1);
    return this.#frames.slice();
  }

  /** The deformer of the animation is freed (frames computed stay readable). */
  free(): void {
    this.#deformer?.free();
    this.#deformer = undefined;
  }

  #next(): Frame {
    const s = this.source;
    const deformer = this.#start();
    const index = this.#frames.length;
    if (index === 0) return this.#read(deformer, false);
    targetsAt(s.keys, frameTime(index, s.fps), this.#targets);
    let clamped: boolean;
    try {
      ({ clamped } = trackFrame(deformer, this.#targets));
    } catch (error) {
      throw new Error(`frame ${index} of the animation could not be posed: ${(error as Error).message}`, {
        cause: error,
      });
    }
    return this.#read(deformer, clamped);
  }

  /** The animation's deformer, made at the first key's pose on the first call. */
  #start(): Deformer {
    if (this.#deformer) return this.#deformer;
    const s = this.source;
    const deformer = new Deformer(s.mesh.positions, s.mesh.triangles, s.options);
    try {
      if (s.stiffness && deformer.hasStiffness) deformer.setStiffness(s.stiffness);
      deformer.setHandlePoints(Uint32Array.from(s.handles.triangles), Float64Array.from(s.handles.barycentric));
      deformer.setPositions(s.keys[0]!.pose);
      if (s.bones && s.bones.triangles.length > 0 && deformer.hasBones) {
        deformer.setBones(s.bones.triangles, s.bones.barycentric);
      }
      deformer.setTracking({ maxStep: s.maxStep, maxSubsteps: s.maxSubsteps, noFoldovers: s.noFoldovers });
      if (s.rig) deformer.setRig(s.rig);
    } catch (error) {
      deformer.free();
      throw error;
    }
    this.#deformer = deformer;
    return deformer;
  }

  #read(deformer: Deformer, clamped: boolean): Frame {
    return { positions: deformer.positions(), handles: deformer.handlePositions(), clamped };
  }
}
