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
