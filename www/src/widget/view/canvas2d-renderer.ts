/**
 * The fallback renderer for browsers without WebGL2: the mesh on a 2D canvas, each
 * triangle clipped and the texture drawn through the affine map that takes the triangle's
 * texture coordinates to its corners on screen (flat fill where there is no texture, or
 * where a triangle's texture coordinates have no area), with an optional wireframe.
 */
import { toPixel, type View } from "./projection.js";
import type { MeshRenderer, RenderOptions } from "./gl-renderer.js";

/** How far, in canvas pixels, each textured triangle's clip reaches past its corners. */
const GROWTH = 1;

/** A texture as the 2D canvas draws it, with its size in pixels. */
interface Texture {
  image: CanvasImageSource;
  width: number;
  height: number;
}

export class Canvas2dRenderer implements MeshRenderer {
  readonly kind = "2d";
  readonly #ctx: CanvasRenderingContext2D;
  #triangles: Uint32Array = new Uint32Array(0);
  #edges: Uint32Array = new Uint32Array(0);
  #uvs: Float32Array = new Float32Array(0);
  #texture: Texture | undefined;

  constructor(canvas: HTMLCanvasElement) {
    const ctx = canvas.getContext("2d");
    if (!ctx) throw new Error("this browser can draw neither with WebGL2 nor on a 2D canvas");
    this.#ctx = ctx;
  }

  setMesh(triangles: Uint32Array, edges: Uint32Array, uvs: Float32Array): void {
    this.#triangles = triangles;
    this.#edges = edges;
    this.#uvs = uvs;
  }

  setTriangles(triangles: Uint32Array): void {
    this.#triangles = triangles;
  }

  setTexture(image: TexImageSource): void {
    this.#texture = drawable(this.#ctx.canvas.ownerDocument, image);
  }

  /** The 2D canvas poses a rig on the CPU: it takes no rig. */
  setRig(): boolean {
    return false;
  }

  clearRig(): void {}

  draw(positions: ArrayLike<number>, view: View, options: RenderOptions): void {
    const ctx = this.#ctx;
    const { width, height } = ctx.canvas;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.fillStyle = options.background;
    ctx.fillRect(0, 0, width, height);
    const at = (v: number): [number, number] => toPixel(view, positions[2 * v]!, positions[2 * v + 1]!);
    const t = this.#triangles;
    // A flat fill under everything: where there is no texture, and in the hairline seams
    // that clipping each triangle on its own leaves between neighbours.
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
    if (this.#texture) this.#drawTextured(at, this.#texture);
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

  /**
   * Each triangle clipped, the texture drawn through the affine map from texture pixels to
   * screen pixels that takes its three texture points to its three corners. Texture
   * coordinates are OBJ's (v up from the bottom edge) and the image's rows run from the
   * top, so (u, v) is texture pixel (u * width, (1 - v) * height).
   */
  #drawTextured(at: (v: number) => [number, number], texture: Texture): void {
    const ctx = this.#ctx;
    const t = this.#triangles;
    const uv = this.#uvs;
    const texel = (v: number): [number, number] => [uv[2 * v]! * texture.width, (1 - uv[2 * v + 1]!) * texture.height];
    for (let i = 0; i + 2 < t.length; i += 3) {
      const [a, b, c] = [t[i]!, t[i + 1]!, t[i + 2]!];
      const texels = [texel(a), texel(b), texel(c)];
      const m = affineThrough(texels, [at(a), at(b), at(c)]);
      if (!m) continue; // no texture area: the flat fill shows
      ctx.save();
      ctx.beginPath();
      // The clip grown by a pixel about the centroid: neighbours overlap, so no seam of the
      // fill shows through their antialiased edges.
      const corners = [at(a), at(b), at(c)];
      const mx = (corners[0]![0] + corners[1]![0] + corners[2]![0]) / 3;
      const my = (corners[0]![1] + corners[1]![1] + corners[2]![1]) / 3;
      for (const [k, [x, y]] of corners.entries()) {
        const reach = Math.hypot(x - mx, y - my);
        const grow = reach > 0 ? 1 + GROWTH / reach : 1;
        if (k === 0) ctx.moveTo(mx + (x - mx) * grow, my + (y - my) * grow);
        else ctx.lineTo(mx + (x - mx) * grow, my + (y - my) * grow);
      }
      ctx.closePath();
      ctx.clip();
      ctx.setTransform(m[0], m[1], m[2], m[3], m[4], m[5]);
      // Only the texels under the triangle (and a pixel around them, for the grown clip).
      const x0 = Math.max(0, Math.floor(Math.min(...texels.map((p) => p[0])) - 1));
      const y0 = Math.max(0, Math.floor(Math.min(...texels.map((p) => p[1])) - 1));
      const x1 = Math.min(texture.width, Math.ceil(Math.max(...texels.map((p) => p[0])) + 1));
      const y1 = Math.min(texture.height, Math.ceil(Math.max(...texels.map((p) => p[1])) + 1));
      if (x1 > x0 && y1 > y0) ctx.drawImage(texture.image, x0, y0, x1 - x0, y1 - y0, x0, y0, x1 - x0, y1 - y0);
      ctx.restore();
    }
  }

  destroy(): void {
    this.#triangles = new Uint32Array(0);
    this.#texture = undefined;
  }
}

/**
 * The affine map `(x, y) -> (a x + c y + e, b x + d y + f)`, as `[a, b, c, d, e, f]` for
 * `setTransform`, that takes the points `from` to the points `to`; undefined when `from`
 * has no area (or the map would not be finite).
 */
export function affineThrough(
  from: readonly [number, number][],
  to: readonly [number, number][],
): [number, number, number, number, number, number] | undefined {
  const [p0, p1, p2] = from as [[number, number], [number, number], [number, number]];
  const [q0, q1, q2] = to as [[number, number], [number, number], [number, number]];
  const [ux, uy, vx, vy] = [p1[0] - p0[0], p1[1] - p0[1], p2[0] - p0[0], p2[1] - p0[1]];
  const det = ux * vy - vx * uy;
  if (det === 0) return undefined;
  const [sx, sy, tx, ty] = [q1[0] - q0[0], q1[1] - q0[1], q2[0] - q0[0], q2[1] - q0[1]];
  // The linear part L solves L (ux, uy) = (sx, sy) and L (vx, vy) = (tx, ty).
  const a = (sx * vy - tx * uy) / det;
  const c = (tx * ux - sx * vx) / det;
  const b = (sy * vy - ty * uy) / det;
  const d = (ty * ux - sy * vx) / det;
  const m: [number, number, number, number, number, number] = [
    a,
    b,
    c,
    d,
    q0[0] - (a * p0[0] + c * p0[1]),
    q0[1] - (b * p0[0] + d * p0[1]),
  ];
  return m.every(Number.isFinite) ? m : undefined;
}

/** A texture source as something `drawImage` takes, with its size in pixels. */
function drawable(document: Document, image: TexImageSource): Texture {
  if (image instanceof ImageData) {
    const canvas = document.createElement("canvas");
    canvas.width = image.width;
    canvas.height = image.height;
    canvas.getContext("2d")?.putImageData(image, 0, 0);
    return { image: canvas, width: image.width, height: image.height };
  }
  if (image instanceof HTMLImageElement) return { image, width: image.naturalWidth, height: image.naturalHeight };
  if (image instanceof HTMLVideoElement) return { image, width: image.videoWidth, height: image.videoHeight };
  if (typeof VideoFrame !== "undefined" && image instanceof VideoFrame) {
    return { image, width: image.displayWidth, height: image.displayHeight };
  }
  const sized = image as HTMLCanvasElement | OffscreenCanvas | ImageBitmap;
  return { image: sized, width: sized.width, height: sized.height };
}
