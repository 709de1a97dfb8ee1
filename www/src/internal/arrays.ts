/** Conversions of user arrays to the typed arrays the wasm bindings take. Internal. */
import type { AkapError, ErrorCode } from "../errors.js";

/** `error` with a `code`, as the bindings' own errors have (see `ErrorCode`). */
export function coded<E extends Error>(error: E, code: ErrorCode): E & AkapError {
  return Object.assign(error, { code });
}

/**
 * A list of numbers, as the API takes them: a Float64Array or a plain array. Points are x
 * and y interleaved: `[x0, y0, x1, y1, ...]`. (Public through `core.ts`.)
 */
export type Coordinates = Float64Array | readonly number[];

/** Vertex or triangle indices: a Uint32Array or a plain array. (Public through `core.ts`.) */
export type Indices = Uint32Array | readonly number[];

export function toFloat64(values: Coordinates, what: string): Float64Array {
  if (values instanceof Float64Array) return values;
  if (Array.isArray(values)) return Float64Array.from(values, Number);
  throw coded(new TypeError(`${what} must be a Float64Array or an array of numbers`), "invalid-argument");
}

export function toUint32(values: Indices, what: string): Uint32Array {
  if (values instanceof Uint32Array) return values;
  if (!Array.isArray(values)) {
    throw coded(new TypeError(`${what} must be a Uint32Array or an array of numbers`), "invalid-argument");
  }
  const bad = values.findIndex((i) => !Number.isInteger(i) || i < 0 || i > 0xffffffff);
  if (bad >= 0) throw coded(new RangeError(`${what}[${bad}] is ${values[bad]}, not an index`), "invalid-argument");
  return Uint32Array.from(values);
}

/** Handles on vertices (their indices), or at points in triangles (3 barycentric coordinates each). (Public through `defop.ts`.) */
export type HandleSpec = Indices | { triangles: Indices; barycentric: Coordinates };

/** A {@link HandleSpec} as the typed arrays the bindings take (and workers are posted). */
export function handleArrays(handles: HandleSpec): Uint32Array | { triangles: Uint32Array; barycentric: Float64Array } {
  return "barycentric" in handles
    ? {
        triangles: toUint32(handles.triangles, "handles.triangles"),
        barycentric: toFloat64(handles.barycentric, "handles.barycentric"),
      }
    : toUint32(handles, "handles");
}
