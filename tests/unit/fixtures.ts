/** What several unit tests share: a small valid mesh and empty timings for a posing's frames. */
import type { Timings } from "../../www/src/index.js";

/** A 2 x 2 grid of squares, each split in two: 9 vertices, 8 triangles. */
export const grid = (() => {
  const positions: number[] = [];
  for (let y = 0; y < 3; y++) for (let x = 0; x < 3; x++) positions.push(x, y);
  const triangles: number[] = [];
  for (let y = 0; y < 2; y++) {
    for (let x = 0; x < 2; x++) {
      const v = 3 * y + x;
      triangles.push(v, v + 1, v + 4, v, v + 4, v + 3);
    }
  }
  return { positions: Float64Array.from(positions), triangles: Uint32Array.from(triangles) };
})();

/** Timings of nothing, for `Posing.advance`. */
export const noTimings = (): Timings => ({
  assembly: 0,
  factorisation: 0,
  dirichletFactorisation: 0,
  solve: 0,
  integration: 0,
});

/**
 * Runs `run` counting the calls it makes into WebAssembly objects: every method and getter
 * of every class of the wasm-bindgen glue (the deformer, operators, meshes, ...) is wrapped
 * for the run, and each call listed as `Class.member`.
 */
export async function wasmCalls<T>(run: () => T): Promise<{ result: T; calls: string[] }> {
  const glue = (await import("../../www/pkg/akap.js")) as Record<string, unknown>;
  const calls: string[] = [];
  const restore: (() => void)[] = [];
  for (const [name, value] of Object.entries(glue)) {
    if (typeof value !== "function" || typeof value.prototype !== "object") continue;
    const proto = value.prototype as Record<string, unknown>;
    for (const key of Object.getOwnPropertyNames(proto)) {
      const descriptor = Object.getOwnPropertyDescriptor(proto, key)!;
      if (key === "constructor" || !descriptor.configurable) continue;
      const counted = { ...descriptor };
      if (typeof descriptor.value === "function") {
        const method = descriptor.value as (...args: unknown[]) => unknown;
        counted.value = function (this: unknown, ...args: unknown[]) {
          calls.push(`${name}.${key}`);
          return method.apply(this, args);
        };
      } else if (descriptor.get) {
        const get = descriptor.get;
        counted.get = function (this: unknown) {
          calls.push(`${name}.${key}`);
          return get.call(this) as unknown;
        };
      } else continue;
      Object.defineProperty(proto, key, counted);
      restore.push(() => Object.defineProperty(proto, key, descriptor));
    }
  }
  try {
    return { result: run(), calls };
  } finally {
    for (const undo of restore) undo();
  }
}
