/**
 * What part of the shape plane the canvas shows. Until the user zooms, pans or fits, the
 * view follows the canvas size, fitted to the rest shape; after that it is theirs: a resize
 * keeps its centre and scale, and a fit (to the pose on screen) brings a shape that was
 * posed or panned out of sight back. Zoom stays within a range around the fitted scale.
 */
import { fitView, panBy, zoomAt, type View } from "./projection.js";

/** Margin of a fitted view: room around the rest shape for poses that reach out. */
export const FIT_MARGIN = 0.12;
/** Zoom range, as factors of the fitted scale. */
export const ZOOM_RANGE = [1 / 20, 50] as const;

export class Camera {
  #view: View = { scale: 1, offsetX: 0, offsetY: 0 };
  #size: [number, number] = [1, 1];
  /** The scale a fit to the rest shape gives: the reference of the zoom range. */
  #fitScale = 1;
  #userSet = false;

  get view(): View {
    return this.#view;
  }

  /** Whether the user has zoomed, panned or fitted since the last {@link reset}. */
  get userSet(): boolean {
    return this.#userSet;
  }

  /** A new shape: the view fits its rest pose again. */
  reset(rest: ArrayLike<number>, width: number, height: number): void {
    this.#userSet = false;
    this.resize(rest, width, height);
  }

  /** The canvas is now `width` x `height` device pixels. */
  resize(rest: ArrayLike<number>, width: number, height: number): void {
    const fitted = fitView(rest, width, height, FIT_MARGIN);
    this.#fitScale = fitted.scale;
    if (this.#userSet) {
      const [w, h] = this.#size;
      this.#view = panBy(this.#view, (width - w) / 2, (height - h) / 2);
    } else {
      this.#view = fitted;
    }
    this.#size = [width, height];
  }

  /** Fits `positions` (the pose on screen) into the canvas. */
  fit(positions: ArrayLike<number>): void {
    this.#view = fitView(positions, this.#size[0], this.#size[1], FIT_MARGIN);
    this.#userSet = true;
  }

  /** Zooms by `factor` about the device pixel (px, py), within {@link ZOOM_RANGE}. */
  zoom(px: number, py: number, factor: number): void {
    const [low, high] = ZOOM_RANGE;
    const scale = Math.min(Math.max(this.#view.scale * factor, low * this.#fitScale), high * this.#fitScale);
    this.#view = zoomAt(this.#view, px, py, scale / this.#view.scale);
    this.#userSet = true;
  }

  /** Moves the view by (dx, dy) device pixels. */
  pan(dx: number, dy: number): void {
    this.#view = panBy(this.#view, dx, dy);
    this.#userSet = true;
  }
}
