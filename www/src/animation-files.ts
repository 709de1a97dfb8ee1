/**
 * Animations out: animated GIF and APNG from rendered frames, ZIP archives of files (an
 * SVG or PNG per frame), the `akap-animation` JSON (a rest mesh, keys and every frame's
 * vertex positions) and a sprite sheet's frame table. Thin wrappers over the Rust core
 * (`src/animation`); re-exported by the package's main module; call `init()` first.
 *
 * @example
 * ```ts
 * import { init, encodeAnimation } from "akap";
 * await init();
 * const gif = await encodeAnimation("gif", frames, { onProgress: (done, total) => console.log(done, total) });
 * ```
 *
 * @module
 */
import { coded, toFloat64, toUint32, type Coordinates } from "./internal/arrays.js";
import { assertLoaded, raw, type rawTypes } from "./internal/wasm.js";
import type { MeshToWrite } from "./import.js";
import type { PuppetJoint, PuppetSheet } from "./core.js";

/** `"gif"`: 256 colours a frame, alpha on or off (below 128 transparent); `"apng"`: lossless RGBA. */
export type AnimationFormat = "gif" | "apng";

/** A rendered frame: RGBA pixels (as `ImageData.data`, rows from the top) shown for `delayMs`. */
export interface AnimationFrame {
  rgba: Uint8Array | Uint8ClampedArray;
  width: number;
  height: number;
  /** Whole milliseconds, 1 to 65535. GIF stores centiseconds (at least 2), rounded on the
   * running total so that the animation keeps its length. */
  delayMs: number;
}

/** Options of {@link encodeAnimation}. */
export interface EncodeAnimationOptions {
  /** Called after each frame is encoded; `total` is the frame count when `frames` has a
   * `length` (an array), else `undefined`. */
  onProgress?(done: number, total: number | undefined): void;
  /** Cancels between frames: the promise rejects with an `Error` named `AbortError`. */
  signal?: AbortSignal;
  /** Play forever (default) or once. */
  loop?: boolean;
}

/**
 * Resolves after the event loop has run other tasks (a macrotask, not a microtask):
 * `setImmediate` where there is one (Node, where a chain of `MessageChannel` messages can
 * be delivered in one turn of the loop, starving timers), else a `MessageChannel` message
 * (pages: a task, without `setTimeout`'s 4 ms clamp), else `setTimeout`.
 */
function nextTask(): Promise<void> {
  const immediate = (globalThis as { setImmediate?: (callback: () => void) => unknown }).setImmediate;
  if (typeof immediate === "function") return new Promise((resolve) => immediate(resolve));
  if (typeof MessageChannel !== "function") return new Promise((resolve) => setTimeout(resolve, 0));
  return new Promise((resolve) => {
    const channel = new MessageChannel();
    channel.port1.onmessage = () => {
      channel.port1.close();
      resolve();
    };
    channel.port2.postMessage(undefined);
  });
}

function aborted(): Error {
  return new DOMException("the animation encoding was cancelled", "AbortError");
}

/**
 * Encodes frames, one at a time, into an animated GIF or APNG file's bytes. Every frame
 * must have the first frame's size. Between frames the encoder waits for a macrotask, so
 * that the page stays responsive and a cancel (`signal`) lands; the wasm encoder is freed
 * whatever happens. Rejects with the core's coded errors for bad frames (`invalid-argument`)
 * or too many of them (`limit`: 1 GiB of RGBA in all), and with an `AbortError` on cancel.
 */
export async function encodeAnimation(
  format: AnimationFormat,
  frames: Iterable<AnimationFrame> | AsyncIterable<AnimationFrame>,
  options: EncodeAnimationOptions = {},
): Promise<Uint8Array> {
  assertLoaded();
  const { onProgress, signal, loop = true } = options;
  const length = (frames as { length?: unknown }).length;
  const total = typeof length === "number" ? length : undefined;
  let encoder: rawTypes.AnimationEncoder | undefined;
  let size: [number, number] | undefined;
  try {
    if (signal?.aborted) throw aborted();
    for await (const frame of frames) {
      if (signal?.aborted) throw aborted();
      if (size === undefined) {
        size = [frame.width, frame.height];
        encoder = new raw.AnimationEncoder(format, frame.width, frame.height, { loop });
      } else if (frame.width !== size[0] || frame.height !== size[1]) {
        throw coded(
          new RangeError(
            `frame ${encoder!.frameCount} is ${frame.width} x ${frame.height}; the first was ${size[0]} x ${size[1]}`,
          ),
          "invalid-argument",
        );
      }
      encoder!.addFrame(frame.rgba, frame.delayMs);
      onProgress?.(encoder!.frameCount, total);
      await nextTask();
      if (signal?.aborted) throw aborted();
    }
    if (encoder === undefined) throw coded(new RangeError("the animation has no frames"), "invalid-argument");
    return encoder.finish();
  } finally {
    encoder?.free();
  }
}

/** A file for {@link zipFiles}: a relative path (`frames/0001.svg`) and its bytes. */
export interface ZipEntry {
  name: string;
  data: Uint8Array;
}

/**
 * A ZIP archive of `files`, stored (not compressed) in the order given, names in UTF-8.
 * Refuses (`invalid-argument`) empty, absolute or duplicate names and names with `..`.
 */
export function zipFiles(files: readonly ZipEntry[]): Uint8Array {
  assertLoaded();
  return raw.zipFiles(files);
}

/** A key of an animation: the handles' positions (x, y interleaved) at `time` seconds. */
export interface AnimationKey<C = Float64Array> {
  time: number;
  /** The timing from the previous key to this one. */
  easing: "linear" | "ease";
  handles: C;
}

/** An animation as {@link animationFromJson} gives it. */
export interface AnimationData {
  /** The rest mesh, as {@link meshToJson} takes it (with a puppet's parts and joints if it
   * is one). */
  mesh: {
    positions: Float64Array;
    triangles: Uint32Array;
    uvs?: Float64Array;
    stiffness?: Float64Array;
    parts?: PuppetSheet[];
    joints?: PuppetJoint[];
  };
  /** Frames per second, 1 to 120. */
  fps: number;
  /** By strictly increasing time, each with the same number of handles. */
  keys: AnimationKey[];
  /** Every vertex's x, y per frame (at `i / fps` seconds). */
  frames: Float64Array[];
}

/** An animation for {@link animationToJson}: as {@link AnimationData}, plain arrays allowed. */
export interface AnimationToWrite {
  mesh: MeshToWrite;
  fps: number;
  keys: readonly AnimationKey<Coordinates>[];
  frames: readonly Coordinates[];
}

/**
 * Writes an animation as `akap-animation` JSON (version 1; the layout is in
 * docs/formats.md), numbers exact. Refuses what {@link animationFromJson} would.
 */
export function animationToJson(animation: AnimationToWrite): string {
  assertLoaded();
  const { mesh } = animation;
  const optional = (values: Coordinates | undefined, what: string) =>
    values === undefined ? undefined : toFloat64(values, what);
  return raw.animationToJson({
    mesh: {
      positions: toFloat64(mesh.positions, "mesh.positions"),
      triangles: toUint32(mesh.triangles, "mesh.triangles"),
      uvs: optional(mesh.uvs, "mesh.uvs"),
      stiffness: optional(mesh.stiffness, "mesh.stiffness"),
      parts: mesh.parts,
      joints: mesh.joints,
    },
    fps: animation.fps,
    keys: animation.keys.map((key, k) => ({ ...key, handles: toFloat64(key.handles, `keys[${k}].handles`) })),
    frames: animation.frames.map((frame, f) => toFloat64(frame, `frames[${f}]`)),
  });
}

/** Reads `akap-animation` JSON, checking everything (coded errors say what and where). */
export function animationFromJson(text: string): AnimationData {
  assertLoaded();
  return raw.animationFromJson(text) as AnimationData;
}

/** A sprite sheet's layout: frames of one size in rows of `columns`. */
export interface SpriteSheetLayout {
  frameWidth: number;
  frameHeight: number;
  columns: number;
  frameCount: number;
  /** Frames per second, 1 to 120. */
  fps: number;
}

/**
 * The sheet's frame table as `akap-sprites` JSON: `{ format, version, frameWidth,
 * frameHeight, columns, rows, fps, size: { w, h }, frames: [{ x, y, w, h, duration }] }`,
 * frames row by row from the top-left, durations in whole milliseconds.
 */
export function spriteSheetTable(layout: SpriteSheetLayout): string {
  assertLoaded();
  return raw.spriteSheetTable(layout);
}
