/**
 * A handle of the posing: a mesh point, how the pointers hold it, and its depth order.
 * Where it is going and how far it is to turn are the deformer's (`Deformer.targets`,
 * `Deformer.turns`), which moves it there.
 */
import type { MeshPoint } from "./picking.js";

export interface Handle {
  point: MeshPoint;
  selected: boolean;
  /** The pointer dragging it, if any, and the offset from pointer to handle at grab time. */
  pointerId: number | undefined;
  grab: [number, number];
  /**
   * Depth order of the part of the shape nearest to this handle (higher is in front; see
   * `layers.ts`). Grabbing a handle brings its part to the front unless `ordered`.
   */
  layer: number;
  /** The user set this handle's layer (Bring forward, Send back): grabbing keeps it. */
  ordered: boolean;
  /**
   * While a pointer turns the handle: where the handle was taken (the centre of the turn),
   * the pointer's last angle about it (unwrapped), the turn asked for when it began and
   * the turn asked for now (radians counter-clockwise; turns add up over gestures).
   */
  turning: { centre: [number, number]; angle: number; start: number; turn: number } | undefined;
}

/** What a snapshot keeps of a handle (no layer in work saved before depth order: layer 0). */
export type HandleState = Pick<Handle, "point"> & { target: [number, number] } & Partial<
    Pick<Handle, "layer" | "ordered">
  >;

/** A handle at a mesh point, not held, not selected. */
export function newHandle(point: MeshPoint): Handle {
  return {
    point,
    selected: false,
    pointerId: undefined,
    grab: [0, 0],
    layer: 0,
    ordered: false,
    turning: undefined,
  };
}
