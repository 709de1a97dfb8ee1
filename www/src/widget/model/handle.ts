/** A handle of the posing: a mesh point, where it is going, and how the pointers hold it. */
import type { MeshPoint } from "./picking.js";

export interface Handle {
  point: MeshPoint;
  /** Where the handle is going, shape units. */
  target: [number, number];
  selected: boolean;
  /** The pointer dragging it, if any, and the offset from pointer to handle at grab time. */
  pointerId: number | undefined;
  grab: [number, number];
  /** Paper mode: pointer motion not yet turned into steps. */
  pending: [number, number];
  /**
   * Depth order of the part of the shape nearest to this handle (higher is in front; see
   * `layers.ts`). Grabbing a handle brings its part to the front unless `ordered`.
   */
  layer: number;
  /** The user set this handle's layer (Bring forward, Send back): grabbing keeps it. */
  ordered: boolean;
  /** How far the handle is to turn, and has turned, radians counter-clockwise (this gesture). */
  turn: number;
  turned: number;
  /** While a pointer turns the handle: the pointer's last angle about it (unwrapped), and `turn` when it began. */
  turning: { angle: number; start: number } | undefined;
}

/** What a snapshot keeps of a handle (no layer in work saved before depth order: layer 0). */
export type HandleState = Pick<Handle, "point" | "target"> & Partial<Pick<Handle, "layer" | "ordered">>;

/** A handle at a mesh point, not held, not selected; its target is the caller's to set. */
export function newHandle(point: MeshPoint): Handle {
  return {
    point,
    target: [0, 0],
    selected: false,
    pointerId: undefined,
    grab: [0, 0],
    pending: [0, 0],
    layer: 0,
    ordered: false,
    turn: 0,
    turned: 0,
    turning: undefined,
  };
}
