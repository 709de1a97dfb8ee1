/**
 * The mapping between shape coordinates (y up) and canvas pixels (y down): the shape's
 * bounding box fitted into the canvas with a margin, centred, aspect ratio kept.
 */
import { bounds } from "../model/geometry.js";

/** `pixel = (offsetX + scale * x, offsetY - scale * y)`, in device pixels. */
export interface View {
  scale: number;
  offsetX: number;
  offsetY: number;
}

/**
 * Fits the box of `positions` into a `width` x `height` pixel canvas, leaving `margin`
 * (a fraction of the smaller side) free on every side.
 */
export function fitView(positions: ArrayLike<number>, width: number, height: number, margin = 0.05): View {
  const b = bounds(positions);
  const pad = margin * Math.min(width, height);
  const spanX = b.maxX - b.minX || 1;
  const spanY = b.maxY - b.minY || 1;
  const scale = Math.max(Math.min((width - 2 * pad) / spanX, (height - 2 * pad) / spanY), Number.MIN_VALUE);
  const cx = (b.minX + b.maxX) / 2;
  const cy = (b.minY + b.maxY) / 2;
  return { scale, offsetX: width / 2 - scale * cx, offsetY: height / 2 + scale * cy };
}

/** Shape coordinates to pixels. */
export function toPixel(view: View, x: number, y: number): [number, number] {
  return [view.offsetX + view.scale * x, view.offsetY - view.scale * y];
}

/** Pixels to shape coordinates (the inverse of {@link toPixel}). */
export function fromPixel(view: View, px: number, py: number): [number, number] {
  return [(px - view.offsetX) / view.scale, (view.offsetY - py) / view.scale];
}

/** The view zoomed by `factor` about the pixel (px, py), which stays over the same shape point. */
export function zoomAt(view: View, px: number, py: number, factor: number): View {
  return {
    scale: view.scale * factor,
    offsetX: px - (px - view.offsetX) * factor,
    offsetY: py - (py - view.offsetY) * factor,
  };
}

/** The view moved by (dx, dy) pixels. */
export function panBy(view: View, dx: number, dy: number): View {
  return { scale: view.scale, offsetX: view.offsetX + dx, offsetY: view.offsetY + dy };
}
