/**
 * The fallback renderer for browsers without WebGL2: the mesh filled with one colour on a
 * 2D canvas (no texture), with an optional wireframe.
 */
import { toPixel, type View } from "./view.js";
import type { MeshRenderer, RenderOptions } from "./gl.js";

export class Canvas2dRenderer implements MeshRenderer {
  readonly kind = "2d";
  readonly #ctx: CanvasRenderingContext2D;
  #triangles: Uint32Array = new Uint32Array(0);
  #edges: Uint32Array = new Uint32Array(0);

  constructor(canvas: HTMLCanvasElement) {
    const ctx = canvas.getContext("2d");
    if (!ctx) throw new Error("this browser can draw neither with WebGL2 nor on a 2D canvas");
    this.#ctx = ctx;
  }

  setMesh(triangles: Uint32Array, edges: Uint32Array): void {
    this.#triangles = triangles;
    this.#edges = edges;
  }

  setTexture(): void {
    // Flat colour only.
  }

  draw(positions: ArrayLike<number>, view: View, options: RenderOptions): void {
    const ctx = this.#ctx;
    const { width, height } = ctx.canvas;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.fillStyle = options.background;
    ctx.fillRect(0, 0, width, height);
    const at = (v: number): [number, number] => toPixel(view, positions[2 * v]!, positions[2 * v + 1]!);
    const t = this.#triangles;
    // One path for all triangles: no hairline seams between neighbours.
    ctx.beginPath();
    for (let i = 0; i + 2 < t.length; i += 3) {
      const [ax, ay] = at(t[i]!);
      const [bx, by] = at(t[i + 1]!);
      const [cx, cy] = at(t[i + 2]!);
      ctx.moveTo(ax, ay);
      ctx.lineTo(bx, by);
      ctx.lineTo(cx, cy);
      ctx.closePath();
    }
    ctx.fillStyle = options.fill;
    ctx.fill("nonzero");
    if (options.wireframe) {
      ctx.beginPath();
      const e = this.#edges;
      for (let i = 0; i + 1 < e.length; i += 2) {
        const [ax, ay] = at(e[i]!);
        const [bx, by] = at(e[i + 1]!);
        ctx.moveTo(ax, ay);
        ctx.lineTo(bx, by);
      }
      ctx.strokeStyle = options.wire;
      ctx.lineWidth = options.pixelRatio;
      ctx.stroke();
    }
  }

  destroy(): void {
    this.#triangles = new Uint32Array(0);
  }
}
