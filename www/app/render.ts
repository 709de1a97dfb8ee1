/** Draws a mesh on a 2D canvas: filled, with an optional wireframe and its boundary. */
import type { MeshData } from "../src/index.js";
import { toPixel, type View } from "./view.js";

export interface Style {
  background: string;
  fill: string;
  wire: string;
  boundary: string;
}

export const STYLE: Style = {
  background: "#f6f1e7",
  fill: "#c8773a",
  wire: "rgba(60, 30, 10, 0.55)",
  boundary: "#5a2d0c",
};

/** Clears the canvas and draws the mesh; `wireframe` adds every edge. Sizes in device pixels. */
export function drawMesh(
  ctx: CanvasRenderingContext2D,
  mesh: MeshData,
  view: View,
  options: { wireframe: boolean; pixelRatio: number },
  style: Style = STYLE,
): void {
  const { width, height } = ctx.canvas;
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.fillStyle = style.background;
  ctx.fillRect(0, 0, width, height);

  const p = mesh.positions;
  const t = mesh.triangles;
  const at = (v: number): [number, number] => toPixel(view, p[2 * v]!, p[2 * v + 1]!);

  // One path for all triangles: no hairline seams between neighbours.
  ctx.beginPath();
  for (let i = 0; i < t.length; i += 3) {
    const [ax, ay] = at(t[i]!);
    const [bx, by] = at(t[i + 1]!);
    const [cx, cy] = at(t[i + 2]!);
    ctx.moveTo(ax, ay);
    ctx.lineTo(bx, by);
    ctx.lineTo(cx, cy);
    ctx.closePath();
  }
  ctx.fillStyle = style.fill;
  ctx.fill("nonzero");

  if (options.wireframe) {
    ctx.beginPath();
    for (let i = 0; i < t.length; i += 3) {
      for (let k = 0; k < 3; k++) {
        const a = t[i + k]!;
        const b = t[i + ((k + 1) % 3)]!;
        if (a > b) continue; // each interior edge once; boundary edges are drawn below
        const [ax, ay] = at(a);
        const [bx, by] = at(b);
        ctx.moveTo(ax, ay);
        ctx.lineTo(bx, by);
      }
    }
    ctx.strokeStyle = style.wire;
    ctx.lineWidth = options.pixelRatio;
    ctx.stroke();
  }

  ctx.beginPath();
  const e = mesh.boundaryEdges;
  for (let i = 0; i < e.length; i += 2) {
    const [ax, ay] = at(e[i]!);
    const [bx, by] = at(e[i + 1]!);
    ctx.moveTo(ax, ay);
    ctx.lineTo(bx, by);
  }
  ctx.strokeStyle = style.boundary;
  ctx.lineWidth = 2 * options.pixelRatio;
  ctx.lineJoin = "round";
  ctx.stroke();
}
