/**
 * Painted stiffness, without the DOM: the brush (every triangle whose centroid lies in
 * the brush's disc gets the brush's value), the tint that shows it, and a painting carried
 * to a re-meshing of the shape. Values are the core's per-triangle stiffness (the factor on
 * the triangle's energy, see `Deformer.setStiffness`): 1 is unpainted, above 1 stiffer,
 * below 1 softer. The range (0.001 to 1000) is the core's; the brush only offers values
 * within it.
 */
import { locate } from "./picking.js";

/** What the brush paints: its radius in CSS pixels and the stiffness it leaves. */
export interface BrushSettings {
  /** Radius in CSS pixels of the screen (the disc is the same size at any zoom). */
  size: number;
  /** The stiffness painted; 1 erases. */
  value: number;
}

/** The brush's values offered by the toolbar (all within the core's range). */
export const BRUSH_VALUES = [0.1, 1, 10, 100, 1000] as const;
/** The brush the widget starts with. */
export const DEFAULT_BRUSH: BrushSettings = { size: 24, value: 100 };
/** The brush sizes allowed, CSS pixels. */
export const BRUSH_SIZE_RANGE = [2, 400] as const;

/**
 * Paints `value` on every triangle whose centroid (in `positions`, the pose on screen) lies
 * within `radius` of (x, y), into `stiffness` (one per triangle; made, all 1, when
 * undefined). Returns the painting and whether any triangle changed.
 */
export function paintStiffness(
  stiffness: Float64Array | undefined,
  positions: ArrayLike<number>,
  triangles: ArrayLike<number>,
  x: number,
  y: number,
  radius: number,
  value: number,
): { stiffness: Float64Array; changed: boolean } {
  const count = triangles.length / 3;
  const out = stiffness ?? new Float64Array(count).fill(1);
  let changed = false;
  const r2 = radius * radius;
  for (let t = 0; t < count; t++) {
    let cx = 0;
    let cy = 0;
    for (let k = 0; k < 3; k++) {
      const v = triangles[3 * t + k]!;
      cx += positions[2 * v]!;
      cy += positions[2 * v + 1]!;
    }
    const dx = cx / 3 - x;
    const dy = cy / 3 - y;
    if (dx * dx + dy * dy <= r2 && out[t] !== value) {
      out[t] = value;
      changed = true;
    }
  }
  return { stiffness: out, changed };
}

/** Whether a painting leaves every triangle at 1 (the same as none). */
export function unpainted(stiffness: Float64Array | undefined): boolean {
  return stiffness === undefined || stiffness.every((s) => s === 1);
}

/**
 * The tint of a triangle of stiffness `s`, or undefined for 1: blue for stiffer, its
 * opacity growing with log10(s) up to 1000; orange for softer, down to 0.001.
 */
export function stiffnessTint(s: number): string | undefined {
  if (s === 1) return undefined;
  const strength = Math.min(1, Math.abs(Math.log10(s)) / 3);
  const alpha = (0.2 + 0.45 * strength).toFixed(3);
  return s > 1 ? `rgba(40, 90, 220, ${alpha})` : `rgba(245, 150, 20, ${alpha})`;
}

/**
 * A painting of `old` carried to `next`, a re-meshing of the same shape: each new
 * triangle takes the value of the old triangle under its centroid (at rest), or of the
 * nearest within `tolerance` on the boundary. Undefined when nothing was painted.
 */
export function carryStiffness(
  stiffness: Float64Array | undefined,
  old: { positions: ArrayLike<number>; triangles: ArrayLike<number> },
  next: { positions: ArrayLike<number>; triangles: ArrayLike<number> },
  tolerance: number,
): Float64Array | undefined {
  if (unpainted(stiffness)) return undefined;
  const count = next.triangles.length / 3;
  const out = new Float64Array(count).fill(1);
  for (let t = 0; t < count; t++) {
    let cx = 0;
    let cy = 0;
    for (let k = 0; k < 3; k++) {
      const v = next.triangles[3 * t + k]!;
      cx += next.positions[2 * v]!;
      cy += next.positions[2 * v + 1]!;
    }
    const under = locate(old.positions, old.triangles, cx / 3, cy / 3, tolerance);
    if (under) out[t] = stiffness![under.triangle]!;
  }
  return out;
}
