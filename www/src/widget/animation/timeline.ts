/**
 * The animation's timeline, as data (pure: nothing of the deformer or the page): keys in
 * time order, each the targets of every handle at a time (seconds) with the easing of the
 * segment that ends at it; the handle set they were captured with; the frame grid; and
 * the handles' targets at any time, interpolated between the keys.
 *
 * Rules (docs/app.md, "Animation"): the timeline starts at time 0 and ends at its last key;
 * frame `i` is at `i / fps`; before the first key the handles hold the first key's
 * targets, after the last the last's. Every key keeps the pose it was captured in; the
 * first key's is the animation's first frame. All keys share one handle set: capturing
 * with another is refused (delete the keys first), and two keys never share a time
 * (capturing at a key's time replaces it; moving a key onto another is refused). Every
 * change is checked first and either made whole or refused with nothing changed.
 */

/** How a handle moves along the segment that ends at a key. */
export type Easing = "linear" | "ease";
export const EASINGS: readonly Easing[] = ["linear", "ease"];

/** The handle set of a timeline: the points as the deformer takes them. */
export interface HandleSet {
  triangles: readonly number[];
  /** Three weights per handle. */
  barycentric: readonly number[];
}

export interface Key {
  /** Seconds from the timeline's start. */
  readonly time: number;
  /** The easing of the segment that ends at this key (unused for the first key). */
  readonly easing: Easing;
  /** The targets of every handle, xy-interleaved. */
  readonly targets: Float64Array;
  /** The whole pose (vertex positions) when the key was captured: the first frame if it is first. */
  readonly pose: Float64Array;
}

/** Defaults and bounds of the frame rate (frames per second). */
export const DEFAULT_FPS = 24;
export const FPS_RANGE: readonly [number, number] = [1, 120];
/** The longest timeline (seconds). */
export const MAX_DURATION = 600;
/** Two times closer than this (seconds) are the same time. */
export const SAME_TIME = 1e-6;

/** `u` in [0, 1] eased: linear, or smoothstep (3u² - 2u³) for "ease". */
export function ease(easing: Easing, u: number): number {
  const v = Math.min(1, Math.max(0, u));
  return easing === "linear" ? v : v * v * (3 - 2 * v);
}

/** Throws unless `fps` is a whole number within {@link FPS_RANGE}. */
export function checkFps(fps: number): void {
  const [low, high] = FPS_RANGE;
  if (!(Number.isInteger(fps) && fps >= low && fps <= high)) {
    throw new RangeError(`fps ${fps} is not a whole number from ${low} to ${high}`);
  }
}

/** Throws unless `time` is a number of seconds from 0 to {@link MAX_DURATION}. */
export function checkTime(time: number): void {
  if (!(typeof time === "number" && time >= 0 && time <= MAX_DURATION)) {
    throw new RangeError(`time ${time} is not a number of seconds from 0 to ${MAX_DURATION}`);
  }
}

export function checkEasing(easing: string): asserts easing is Easing {
  if (!(EASINGS as readonly string[]).includes(easing)) {
    throw new RangeError(`unknown easing "${easing}"; the easings are ${EASINGS.join(", ")}`);
  }
}

/** How many frames an animation of `duration` seconds has at `fps`: one at each 1/fps from 0 to the end. */
export function frameCount(duration: number, fps: number): number {
  return Math.floor(duration * fps + 1e-9) + 1;
}

/** The time of frame `index` at `fps`. */
export function frameTime(index: number, fps: number): number {
  return index / fps;
}

/** The frame at (or just before) `time`. */
export function frameAt(time: number, fps: number): number {
  return Math.max(0, Math.floor(time * fps + 1e-9));
}

/**
 * The handles' targets at `time` (into `out`): before the first key its targets, after
 * the last the last's, between keys a and b `a + (b - a) * ease(b.easing, u)` with `u`
 * the fraction of the segment's time gone.
 */
export function targetsAt(
  keys: readonly Key[],
  time: number,
  out: Float64Array = new Float64Array(keys[0]?.targets.length ?? 0),
): Float64Array {
  if (keys.length === 0) throw new RangeError("there are no keys");
  const next = keys.findIndex((k) => k.time > time);
  if (next === 0 || next === -1) {
    out.set(keys[next === 0 ? 0 : keys.length - 1]!.targets);
    return out;
  }
  const [a, b] = [keys[next - 1]!, keys[next]!];
  const e = ease(b.easing, (time - a.time) / (b.time - a.time));
  for (let i = 0; i < out.length; i++) out[i] = a.targets[i]! + (b.targets[i]! - a.targets[i]!) * e;
  return out;
}

function sameHandles(a: HandleSet, b: HandleSet): boolean {
  return (
    a.triangles.length === b.triangles.length &&
    a.triangles.every((t, i) => t === b.triangles[i]) &&
    a.barycentric.length === b.barycentric.length &&
    a.barycentric.every((w, i) => w === b.barycentric[i])
  );
}

export class Timeline {
  #keys: Key[] = [];
  #handles: HandleSet | undefined;
  /** Counts changes: whatever was computed from the keys is stale when it moves. */
  version = 0;

  /** The keys in time order (the array is the timeline's: do not change it). */
  get keys(): readonly Key[] {
    return this.#keys;
  }

  /** The handle set of the keys (undefined while there are none). */
  get handles(): HandleSet | undefined {
    return this.#handles;
  }

  /** The last key's time (0 without keys). */
  get duration(): number {
    return this.#keys.at(-1)?.time ?? 0;
  }

  /** Whether `handles` is the set the keys were captured with (any set fits while there are none). */
  fits(handles: HandleSet): boolean {
    return this.#handles === undefined || sameHandles(this.#handles, handles);
  }

  /**
   * Adds a key at `time` with the handles' `targets` and the `pose` they are in (copied),
   * replacing a key at the same time (its easing kept unless `easing` is given); returns
   * its index. Refused, changing nothing, for a bad time or easing, no handles, targets
   * that are not one finite pair per handle, or another handle set than the keys'.
   */
  capture(
    time: number,
    handles: HandleSet,
    targets: ArrayLike<number>,
    pose: ArrayLike<number>,
    easing?: Easing,
  ): number {
    checkTime(time);
    if (easing !== undefined) checkEasing(easing);
    const count = handles.triangles.length;
    if (count === 0) throw new Error("add handles before capturing a key: a key is where the handles are");
    if (handles.barycentric.length !== 3 * count) throw new RangeError("three barycentric weights per handle");
    if (targets.length !== 2 * count || !Array.from(targets).every(Number.isFinite)) {
      throw new RangeError(`a key needs one finite xy target per handle (${2 * count} numbers)`);
    }
    if (pose.length === 0 || pose.length % 2 !== 0 || !Array.from(pose).every(Number.isFinite)) {
      throw new RangeError("a key's pose is finite xy positions");
    }
    if (!this.fits(handles)) {
      throw new Error(
        `the keys were captured with another set of handles (${this.#handles!.triangles.length}); ` +
          "put the handles back as they were, or delete the keys to start an animation with these",
      );
    }
    if (this.#keys.length > 0 && this.#keys[0]!.pose.length !== pose.length) {
      throw new RangeError("the pose has another vertex count than the keys'");
    }
    const same = this.#keys.findIndex((k) => Math.abs(k.time - time) < SAME_TIME);
    const key: Key = {
      time: same >= 0 ? this.#keys[same]!.time : time,
      easing: easing ?? (same >= 0 ? this.#keys[same]!.easing : "linear"),
      targets: Float64Array.from(targets),
      pose: Float64Array.from(pose),
    };
    if (same >= 0) this.#keys[same] = key;
    else this.#keys.push(key);
    this.#handles ??= { triangles: [...handles.triangles], barycentric: [...handles.barycentric] };
    this.#sort();
    return this.#keys.indexOf(key);
  }

  /** Moves key `index` to `time`; returns its new index. Refused onto another key's time. */
  move(index: number, time: number): number {
    const key = this.#key(index);
    checkTime(time);
    if (this.#keys.some((k, i) => i !== index && Math.abs(k.time - time) < SAME_TIME)) {
      throw new RangeError(`there is a key at ${time} s already`);
    }
    const moved = { ...key, time };
    this.#keys[index] = moved;
    this.#sort();
    return this.#keys.indexOf(moved);
  }

  /** Deletes key `index`; the last key gone, the timeline forgets its handle set. */
  delete(index: number): void {
    this.#key(index);
    this.#keys.splice(index, 1);
    if (this.#keys.length === 0) this.#handles = undefined;
    this.version++;
  }

  setEasing(index: number, easing: Easing): void {
    const key = this.#key(index);
    checkEasing(easing);
    if (key.easing === easing) return;
    this.#keys[index] = { ...key, easing };
    this.version++;
  }

  /** No keys, no handle set. */
  clear(): void {
    if (this.#keys.length === 0 && this.#handles === undefined) return;
    this.#keys = [];
    this.#handles = undefined;
    this.version++;
  }

  #key(index: number): Key {
    if (!(Number.isInteger(index) && index >= 0 && index < this.#keys.length)) {
      throw new RangeError(`there is no key ${index} (there are ${this.#keys.length})`);
    }
    return this.#keys[index]!;
  }

  #sort(): void {
    this.#keys.sort((a, b) => a.time - b.time);
    this.version++;
  }
}
