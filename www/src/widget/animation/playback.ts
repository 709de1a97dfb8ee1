/**
 * The widget's animation: its {@link Timeline} tied to the shape and handles posed, the
 * frames computed from it ({@link AnimationFrames}, kept until the keys, method,
 * stiffness or step settings change), the playhead, and playback. Showing a frame puts
 * its pose and the timeline's handle set (targets where the frame has the handles) into
 * the posing, so after a pause the pose stays at the frame on screen, as in any animation
 * tool; showing frames is undoable: a seek is one step, a playback from Play to its end
 * or pause another, a scrub from press to release another. Key edits are not in the undo
 * history (they change the timeline, not the pose).
 */
import { AnimationFrames, framesKey, type Frame } from "./frames.js";
import { newHandle, type Posing } from "../model/posing.js";
import type { Rig } from "../model/rig.js";
import type { Shape } from "../model/shape.js";
import { bonesEvent } from "../model/bones.js";
import { unpainted } from "../model/stiffness.js";
import {
  Timeline,
  checkTime,
  frameAt,
  frameCount,
  frameTime,
  type Easing,
  type HandleSet,
  type Key,
} from "./timeline.js";

/** What the animator needs of the widget. */
export interface AnimatorHost {
  readonly posing: Posing;
  /** Frames per second (the `fps` option). */
  fps(): number;
  /** A frame's pose was put in place: draw it, report it (`index` of the frame shown). */
  shown(index: number): void;
  /** Keys, playhead or playback changed: the strip shows them again. */
  changed(): void;
  info(message: string): void;
}

/** A key as the API gives it: time, easing, and the handles' targets (a copy). */
export interface KeyInfo {
  time: number;
  easing: Easing;
  targets: Float64Array;
}

export class Animator {
  /** The keys (replaced whole by {@link restoreKeys}). */
  timeline = new Timeline();
  /** The frame on screen (or where playback resumes). */
  playhead = 0;
  playing = false;
  loop = false;
  /** The key selected in the strip (Delete deletes it), if any. */
  selected: number | undefined;
  readonly #host: AnimatorHost;
  /** The shape the keys were captured on (a new shape clears them). */
  #shape: Shape | undefined;
  #frames: AnimationFrames | undefined;
  #framesKey = "";
  /** The rig the frames were computed with, if any. */
  #rig: Rig | undefined;
  #raf = 0;
  /** Playback's clock: the time (ms) frame 0 would have been shown at. */
  #start: number | undefined;
  #whenStopped: (() => void)[] = [];

  constructor(host: AnimatorHost) {
    this.#host = host;
  }

  /** The keys in time order (copies of their targets). */
  keys(): KeyInfo[] {
    this.#checkShape();
    return this.timeline.keys.map((k) => ({ time: k.time, easing: k.easing, targets: k.targets.slice() }));
  }

  /** Frames of the animation (0 without keys). */
  get frameCount(): number {
    this.#checkShape();
    const keys = this.timeline.keys;
    return keys.length === 0 ? 0 : frameCount(this.timeline.duration, this.#host.fps());
  }

  /** The playhead's time, seconds. */
  get time(): number {
    return frameTime(this.playhead, this.#host.fps());
  }

  /**
   * Captures the pose on screen as a key at `time` (default the playhead's): the handles'
   * positions are its targets and the pose is kept with it. Returns the key's index;
   * refused (nothing changed) without handles, for a bad time, or with another handle set
   * than the keys'.
   */
  capture(time = this.time, easing?: Easing): number {
    this.#checkShape();
    this.pause();
    const posing = this.#host.posing;
    const index = this.timeline.capture(
      time,
      posing.handlesEvent().handles,
      posing.deformer.handlePositions(),
      posing.deformer.positions(),
      easing,
    );
    this.#shape = posing.shape;
    this.selected = index;
    this.#host.changed();
    return index;
  }

  moveKey(index: number, time: number): number {
    this.#checkShape();
    const moved = this.timeline.move(index, time);
    this.selected = moved;
    this.#edited();
    return moved;
  }

  deleteKey(index: number): void {
    this.#checkShape();
    this.timeline.delete(index);
    this.selected = undefined;
    this.#edited();
  }

  setEasing(index: number, easing: Easing): void {
    this.#checkShape();
    this.timeline.setEasing(index, easing);
    this.#edited();
  }

  /** Deletes every key. */
  clear(): void {
    this.pause();
    this.timeline.clear();
    this.selected = undefined;
    this.#edited();
  }

  /**
   * Keys kept with the work put back (each checked as a capture is), on the shape posed now;
   * throws, changing nothing, when they do not fit it.
   */
  restoreKeys(saved: { handles: HandleSet; keys: readonly Key[] }): void {
    const timeline = new Timeline();
    for (const k of saved.keys) timeline.capture(k.time, saved.handles, k.targets, k.pose, k.easing);
    const vertices = this.#host.posing.shape.mesh.vertexCount;
    if (timeline.keys.some((k) => k.pose.length !== 2 * vertices)) {
      throw new Error("the kept animation's poses do not fit the shape");
    }
    this.pause();
    this.#frames?.free();
    this.#frames = undefined;
    this.timeline = timeline;
    this.#shape = timeline.keys.length > 0 ? this.#host.posing.shape : undefined;
    this.selected = undefined;
    this.playhead = 0;
    this.#host.changed();
  }

  /**
   * The frames, computed from the keys now in force (the cache is made again when anything
   * they depend on changed). Throws without keys.
   */
  frames(): AnimationFrames {
    this.#checkShape();
    const { posing } = this.#host;
    const { settings, shape } = posing;
    const keys: readonly Key[] = this.timeline.keys;
    const handles = this.timeline.handles;
    if (!handles || keys.length === 0) throw new Error("there are no keys: capture one (K) first");
    const rig = posing.rig;
    const handleList = handles.triangles.map((triangle, i) => ({
      point: { triangle, barycentric: handles.barycentric.slice(3 * i, 3 * i + 3) as [number, number, number] },
    }));
    const withRig = settings.method === "defop" && rig !== undefined && rig.fits(shape, handleList, posing.joints);
    const key = framesKey({
      version: this.timeline.version,
      method: settings.method,
      lambda: settings.lambda,
      // A puppet's joints pose its frames too.
      joints: posing.shape.puppet ? posing.joints : undefined,
      stiffness: posing.stiffnessVersion,
      bones: posing.bones.version,
      fps: this.#host.fps(),
      maxStep: settings.maxStep,
      maxSubsteps: settings.maxSubsteps,
      noFoldovers: settings.noFoldovers,
      withRig,
    });
    const by = withRig ? rig : undefined;
    if (!this.#frames || key !== this.#framesKey || this.#frames.source.mesh !== shape.mesh || by !== this.#rig) {
      this.#frames?.free();
      this.#frames = new AnimationFrames({
        mesh: shape.mesh,
        options: posing.shapeOptions(),
        stiffness: unpainted(posing.stiffness) ? undefined : posing.stiffness!.slice(),
        bones: bonesEvent(posing.bones.list).bones,
        handles,
        // A copy of the list: the timeline's changes make a new AnimationFrames.
        keys: [...keys],
        fps: this.#host.fps(),
        maxStep: settings.maxStep,
        maxSubsteps: settings.maxSubsteps,
        noFoldovers: settings.noFoldovers,
        rig: withRig ? rig.operator : undefined,
      });
      this.#framesKey = key;
      this.#rig = by;
    }
    return this.#frames;
  }

  /** Every frame's vertex positions (copies). */
  positions(): Float64Array[] {
    return this.frames()
      .all()
      .map((f) => f.positions.slice());
  }

  /**
   * Moves the playhead to `time` (seconds, on the frame grid) and shows its frame (past the
   * last key, the last frame) as one undoable step; without keys it only moves the playhead.
   */
  seek(time: number): void {
    checkTime(time);
    this.pause();
    const index = frameAt(time, this.#host.fps());
    if (this.frameCount === 0) {
      this.playhead = index;
      this.#host.changed();
      return;
    }
    this.#host.posing.gesture(() => this.show(index));
  }

  /**
   * Moves the playhead to frame `index` and puts its pose in place (past the last key, the
   * last frame's; the caller makes it undoable): the timeline's handles, their targets
   * where the frame has them.
   */
  show(index: number): Frame {
    const frames = this.frames();
    const frame = frames.frame(Math.min(index, frames.count - 1));
    const posing = this.#host.posing;
    const handles = this.timeline.handles!;
    const current = posing.handlesEvent().handles;
    const same =
      current.triangles.length === handles.triangles.length &&
      current.triangles.every((t, i) => t === handles.triangles[i]) &&
      current.barycentric.every((b, i) => b === handles.barycentric[i]);
    if (!same) {
      posing.handles = handles.triangles.map((triangle, i) =>
        newHandle({ triangle, barycentric: handles.barycentric.slice(3 * i, 3 * i + 3) as [number, number, number] }),
      );
      posing.applyHandles();
    }
    posing.deformer.setPositions(frame.positions);
    posing.deformer.setTargets(frame.handles);
    this.playhead = index;
    this.#host.shown(index);
    this.#host.changed();
    return frame;
  }

  /**
   * Plays from the playhead (from the start when it is at the end) in real time at the
   * frame rate, computing frames as it goes (slower than real time while they take longer
   * than a frame to compute); `loop` starts again after the last frame. Resolves when
   * playback stops (the end, or {@link pause}); rejects without keys.
   */
  async play(options: { loop?: boolean } = {}): Promise<void> {
    const frames = this.frames();
    if (options.loop !== undefined) this.loop = options.loop;
    const stopped = new Promise<void>((resolve) => this.#whenStopped.push(resolve));
    if (this.playing) return stopped;
    if (this.playhead >= frames.count - 1) this.playhead = 0;
    const posing = this.#host.posing;
    posing.releasePointers();
    posing.beginGesture();
    posing.markChanged();
    this.playing = true;
    this.show(this.playhead);
    // The clock starts at the first animation frame's time (rAF's times may precede now).
    this.#start = undefined;
    this.#raf = requestAnimationFrame((now) => this.#tick(now));
    return stopped;
  }

  /** Stops playback at the frame on screen. */
  pause(): void {
    if (this.#raf) cancelAnimationFrame(this.#raf);
    this.#raf = 0;
    if (!this.playing) return;
    this.playing = false;
    this.#host.posing.endDragGesture();
    this.#host.changed();
    for (const resolve of this.#whenStopped.splice(0)) resolve();
  }

  /** The widget goes away. */
  destroy(): void {
    this.pause();
    this.#frames?.free();
  }

  #tick(now: number): void {
    this.#raf = 0;
    if (!this.playing) return;
    const posing = this.#host.posing;
    if (posing.dragging) return this.pause();
    const fps = this.#host.fps();
    let frames: AnimationFrames;
    try {
      frames = this.frames();
    } catch (error) {
      this.pause();
      this.#host.info((error as Error).message);
      return;
    }
    const count = frames.count;
    this.#start ??= now - (1000 * this.playhead) / fps;
    let wanted = Math.max(0, Math.floor(((now - this.#start) * fps) / 1000));
    // One frame to compute at most per tick, so that the page stays responsive: while
    // frames take longer than 1/fps to compute, playback runs slower than real time.
    if (wanted > frames.computed && frames.computed < count) {
      wanted = frames.computed;
      this.#start = now - (1000 * wanted) / fps;
    }
    let last = false;
    if (wanted >= count) {
      if (this.loop && count > 1) {
        this.#start += (1000 * count * Math.floor(wanted / count)) / fps;
        wanted %= count;
      } else [wanted, last] = [count - 1, true];
    }
    try {
      if (wanted !== this.playhead) this.show(wanted);
    } catch (error) {
      this.pause();
      this.#host.info((error as Error).message);
      return;
    }
    if (last) this.pause();
    else this.#raf = requestAnimationFrame((t) => this.#tick(t));
  }

  /** The keys belong to the shape they were captured on: another shape clears them. */
  #checkShape(): void {
    if (this.timeline.keys.length > 0 && this.#shape !== this.#host.posing.shape) {
      this.pause();
      this.timeline.clear();
      this.selected = undefined;
      this.playhead = 0;
      this.#host.info("The shape changed: the animation's keys were cleared.");
      this.#host.changed();
    }
  }

  #edited(): void {
    const count = this.frameCount;
    if (this.playhead >= count) this.playhead = Math.max(0, count - 1);
    this.#host.changed();
  }
}
