/**
 * How handles move in a frame. Every handle has a target (the pointer for a dragged
 * handle, the place it was left for a pin); its velocity is target minus current
 * position, so handles track the pointer without drift. A long jump is split into
 * substeps no longer than `maxStep`, because one large step along a field that is only
 * infinitesimally rigid distorts the shape (the paper's Figure 2).
 *
 * Positions and targets are xy-interleaved, one pair per handle.
 */

/** The largest distance between a handle and its target. */
export function largestGap(current: ArrayLike<number>, targets: ArrayLike<number>): number {
  checkPairs(current, targets);
  let gap = 0;
  for (let i = 0; i < current.length; i += 2) {
    gap = Math.max(gap, Math.hypot(targets[i]! - current[i]!, targets[i + 1]! - current[i + 1]!));
  }
  return gap;
}

/** How many substeps cover `distance` with steps of at most `maxStep` (at least 1). */
export function substepCount(distance: number, maxStep: number): number {
  if (!(maxStep > 0) || !Number.isFinite(distance))
    throw new RangeError("substepCount needs maxStep > 0 and a finite distance");
  return Math.max(1, Math.ceil(distance / maxStep - 1e-9));
}

/**
 * Velocities for the next substep when `remaining` substeps (this one included) should
 * bring every handle to its target: `(target - current) / remaining`, written into `out`.
 */
export function trackingVelocities(
  current: ArrayLike<number>,
  targets: ArrayLike<number>,
  remaining: number,
  out: Float64Array = new Float64Array(current.length),
): Float64Array {
  checkPairs(current, targets);
  if (!(remaining >= 1)) throw new RangeError(`remaining substeps is ${remaining}, expected at least 1`);
  for (let i = 0; i < current.length; i++) out[i] = (targets[i]! - current[i]!) / remaining;
  return out;
}

/**
 * The paper's mode: a dragged handle's velocity is the raw pointer displacement since the
 * last frame (split evenly over `substeps`), pins get zero. Errors accumulate, as in the
 * paper's interface; tracking mode does not have that problem.
 */
export function displacementVelocities(
  displacements: ArrayLike<number>,
  substeps: number,
  out: Float64Array = new Float64Array(displacements.length),
): Float64Array {
  if (!(substeps >= 1)) throw new RangeError(`substeps is ${substeps}, expected at least 1`);
  for (let i = 0; i < displacements.length; i++) out[i] = displacements[i]! / substeps;
  return out;
}

function checkPairs(a: ArrayLike<number>, b: ArrayLike<number>): void {
  if (a.length !== b.length || a.length % 2 !== 0) {
    throw new RangeError(`expected two xy lists of equal even length, got ${a.length} and ${b.length}`);
  }
}
