/**
 * The 2D overlay above the mesh: painted stiffness as a tint and the brush's outline, the
 * outline, flipped triangles, the velocity field of the last frame (arrows, as in the
 * paper's Figure 4), Cauchy-Green's cage and the handles; for a trained rig, the regions
 * its training drew targets from (discs, Voronoi cells), handles outside them marked, and
 * the ground truth's outline as a ghost.
 */
import { doubledArea } from "../model/geometry.js";
import type { Layering } from "../model/layers.js";
import { stiffnessTint } from "../model/stiffness.js";
import { toPixel, type View } from "./projection.js";

export interface OverlayHandle {
  x: number;
  y: number;
  /** Where the handle is going (its target). */
  targetX: number;
  targetY: number;
  selected: boolean;
  dragged: boolean;
  /** Show the turning ring (a selected handle the pointer is near, or one turning). */
  ring?: boolean;
  /** How far the handle has turned in this gesture (radians), while it turns. */
  turned?: number | undefined;
  /** Outside the region a trained rig was trained on (it extrapolates there). */
  outside?: boolean;
}

export interface OverlayScene {
  positions: ArrayLike<number>;
  triangles: ArrayLike<number>;
  boundaryEdges: ArrayLike<number>;
  handles: readonly OverlayHandle[];
  /** The last field, 2 per vertex, or undefined to draw none. */
  field: ArrayLike<number> | undefined;
  showFlipped: boolean;
  /** Where a trained rig's training drew targets (shape units): discs, and cells (x and y per corner), or none. */
  regions?: { discs: readonly { x: number; y: number; r: number }[]; cells: readonly ArrayLike<number>[] } | undefined;
  /** Positions (2 per vertex) whose outline is drawn dashed over the pose: the ground truth. */
  ghost?: ArrayLike<number>;
  /** Cauchy-Green's deformed cage (2 per vertex), drawn as a thin dashed polygon. */
  cage?: ArrayLike<number>;
  /** The depth order of the parts: each layer's outline is hidden where a layer in front covers it. */
  layers?: Layering | undefined;
  /** Painted stiffness as regions of one value each (their outline loops), drawn as a tint. */
  stiffness?: Map<number, number[][]> | undefined;
  /** The brush's outline: centre and radius in shape units. */
  brush?: { x: number; y: number; r: number };
  /** Bones: x0 y0 x1 y1 each (shape units), and one being drawn. */
  bones?: ArrayLike<number>;
  boneDraft?: readonly [number, number, number, number] | undefined;
  /** A puppet's joints (shape units), shown with the joint tool. */
  joints?: readonly { x: number; y: number; selected: boolean }[] | undefined;
}

/** Handle radius in CSS pixels. */
export const HANDLE_RADIUS = 7;
/** A joint marker's half-width in CSS pixels. */
export const JOINT_RADIUS = 6;
/** The turning ring round a selected handle, in handle radii. */
export const RING_RADIUS = 2.6;
/** Most arrows drawn for the field. */
const MAX_ARROWS = 400;

export function drawOverlay(ctx: CanvasRenderingContext2D, scene: OverlayScene, view: View, ratio: number): void {
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.clearRect(0, 0, ctx.canvas.width, ctx.canvas.height);
  const p = scene.positions;
  const at = (v: number): [number, number] => toPixel(view, p[2 * v]!, p[2 * v + 1]!);

  drawOutline(ctx, scene, at, ratio);

  if (scene.stiffness) drawStiffness(ctx, scene.stiffness, at);

  if (scene.showFlipped) {
    ctx.beginPath();
    const t = scene.triangles;
    for (let f = 0; 3 * f + 2 < t.length; f++) {
      if (doubledArea(p, t, f) >= 0) continue;
      const [ax, ay] = at(t[3 * f]!);
      const [bx, by] = at(t[3 * f + 1]!);
      const [cx, cy] = at(t[3 * f + 2]!);
      ctx.moveTo(ax, ay);
      ctx.lineTo(bx, by);
      ctx.lineTo(cx, cy);
      ctx.closePath();
    }
    ctx.fillStyle = "rgba(220, 20, 60, 0.75)";
    ctx.fill();
  }

  const e = scene.boundaryEdges;
  if (scene.ghost) {
    const g = scene.ghost;
    ctx.beginPath();
    for (let i = 0; i + 1 < e.length; i += 2) {
      const [ax, ay] = toPixel(view, g[2 * e[i]!]!, g[2 * e[i]! + 1]!);
      const [bx, by] = toPixel(view, g[2 * e[i + 1]!]!, g[2 * e[i + 1]! + 1]!);
      ctx.moveTo(ax, ay);
      ctx.lineTo(bx, by);
    }
    ctx.setLineDash([5 * ratio, 4 * ratio]);
    ctx.strokeStyle = "rgba(20, 110, 60, 0.9)";
    ctx.lineWidth = 1.5 * ratio;
    ctx.stroke();
    ctx.setLineDash([]);
  }

  if (scene.regions) {
    // Discs and cells each one path, tinted and outlined alike (mixed sampling shows both).
    const paths: ((ctx: CanvasRenderingContext2D) => void)[] = [
      (ctx) => {
        for (const { x, y, r } of scene.regions!.discs) {
          const [cx, cy] = toPixel(view, x, y);
          ctx.moveTo(cx + r * view.scale, cy);
          ctx.arc(cx, cy, r * view.scale, 0, 2 * Math.PI);
        }
      },
      (ctx) => {
        for (const cell of scene.regions!.cells) {
          for (let k = 0; k + 1 < cell.length; k += 2) {
            const [x, y] = toPixel(view, cell[k]!, cell[k + 1]!);
            if (k === 0) ctx.moveTo(x, y);
            else ctx.lineTo(x, y);
          }
          ctx.closePath();
        }
      },
    ];
    for (const path of paths) {
      ctx.beginPath();
      path(ctx);
      ctx.fillStyle = "rgba(40, 120, 200, 0.08)";
      ctx.fill();
      ctx.strokeStyle = "rgba(40, 120, 200, 0.6)";
      ctx.lineWidth = ratio;
      ctx.stroke();
    }
  }

  if (scene.cage && scene.cage.length >= 6) {
    const c = scene.cage;
    ctx.beginPath();
    for (let i = 0; i + 1 < c.length; i += 2) {
      const [x, y] = toPixel(view, c[i]!, c[i + 1]!);
      if (i === 0) ctx.moveTo(x, y);
      else ctx.lineTo(x, y);
    }
    ctx.closePath();
    ctx.setLineDash([3 * ratio, 3 * ratio]);
    ctx.strokeStyle = "rgba(90, 60, 140, 0.7)";
    ctx.lineWidth = ratio;
    ctx.stroke();
    ctx.setLineDash([]);
  }

  if (scene.field) drawField(ctx, p, scene.field, view, ratio);

  if (scene.bones || scene.boneDraft) drawBones(ctx, scene.bones ?? [], scene.boneDraft, view, ratio);

  if (scene.brush) {
    const [x, y] = toPixel(view, scene.brush.x, scene.brush.y);
    ctx.beginPath();
    ctx.arc(x, y, scene.brush.r * view.scale, 0, 2 * Math.PI);
    ctx.strokeStyle = "rgba(255, 255, 255, 0.9)";
    ctx.lineWidth = 3 * ratio;
    ctx.stroke();
    ctx.strokeStyle = "rgba(20, 40, 90, 0.9)";
    ctx.lineWidth = ratio;
    ctx.stroke();
  }

  if (scene.joints) drawJoints(ctx, scene.joints, view, ratio);

  for (const h of scene.handles) {
    const [x, y] = toPixel(view, h.x, h.y);
    const [tx, ty] = toPixel(view, h.targetX, h.targetY);
    if (Math.hypot(tx - x, ty - y) > 2 * ratio) {
      ctx.beginPath();
      ctx.setLineDash([4 * ratio, 3 * ratio]);
      ctx.moveTo(x, y);
      ctx.lineTo(tx, ty);
      ctx.strokeStyle = "rgba(20, 40, 90, 0.8)";
      ctx.lineWidth = ratio;
      ctx.stroke();
      ctx.setLineDash([]);
    }
    if (h.ring) drawRing(ctx, x, y, ratio, h.turned);
    ctx.beginPath();
    ctx.arc(x, y, (h.dragged ? 1.3 : 1) * HANDLE_RADIUS * ratio, 0, 2 * Math.PI);
    ctx.fillStyle = h.selected ? "#ffd34d" : "#ffffff";
    ctx.fill();
    ctx.lineWidth = 2.5 * ratio;
    ctx.strokeStyle = h.dragged ? "#c0392b" : "#1d3557";
    ctx.stroke();
    if (h.outside) {
      ctx.beginPath();
      ctx.arc(x, y, 1.9 * HANDLE_RADIUS * ratio, 0, 2 * Math.PI);
      ctx.setLineDash([3 * ratio, 2 * ratio]);
      ctx.strokeStyle = "#e67e22";
      ctx.lineWidth = 2 * ratio;
      ctx.stroke();
      ctx.setLineDash([]);
    }
  }
}

/**
 * The outline: the boundary edges, layer by layer from the back; before each layer's
 * edges are drawn, what its part covers of the outlines behind is erased (its outline
 * loops filled, not its many triangles).
 */
function drawOutline(
  ctx: CanvasRenderingContext2D,
  scene: OverlayScene,
  at: (v: number) => [number, number],
  ratio: number,
): void {
  const { boundaryEdges: e, layers } = scene;
  ctx.strokeStyle = "#5a2d0c";
  ctx.lineWidth = 2 * ratio;
  ctx.lineJoin = "round";
  for (const [index, layer] of (layers?.order ?? [0]).entries()) {
    if (layers && index > 0) {
      ctx.beginPath();
      for (const loop of layers.outlines[index]!) {
        loop.forEach((v, i) => (i === 0 ? ctx.moveTo(...at(v)) : ctx.lineTo(...at(v))));
        ctx.closePath();
      }
      ctx.globalCompositeOperation = "destination-out";
      // Opaque, whatever was filled last (the flipped triangles' red is translucent): the
      // outlines behind are erased wholly, not left showing faintly through.
      ctx.fillStyle = "#000";
      ctx.fill("nonzero");
      ctx.globalCompositeOperation = "source-over";
    }
    ctx.beginPath();
    for (let i = 0; i + 1 < e.length; i += 2) {
      if (layers && layers.edges[i / 2] !== layer) continue;
      const [ax, ay] = at(e[i]!);
      const [bx, by] = at(e[i + 1]!);
      ctx.moveTo(ax, ay);
      ctx.lineTo(bx, by);
    }
    ctx.stroke();
  }
}

/** Joints as small diamonds with a dot, white-rimmed; the selected one filled yellow. */
function drawJoints(
  ctx: CanvasRenderingContext2D,
  joints: readonly { x: number; y: number; selected: boolean }[],
  view: View,
  ratio: number,
): void {
  const r = JOINT_RADIUS * ratio;
  for (const j of joints) {
    const [x, y] = toPixel(view, j.x, j.y);
    ctx.beginPath();
    ctx.moveTo(x, y - r);
    ctx.lineTo(x + r, y);
    ctx.lineTo(x, y + r);
    ctx.lineTo(x - r, y);
    ctx.closePath();
    ctx.fillStyle = j.selected ? "#ffd34d" : "rgba(255, 255, 255, 0.9)";
    ctx.fill();
    ctx.lineWidth = 2 * ratio;
    ctx.strokeStyle = "#0b6e4f";
    ctx.stroke();
    ctx.beginPath();
    ctx.arc(x, y, 1.5 * ratio, 0, 2 * Math.PI);
    ctx.fillStyle = "#0b6e4f";
    ctx.fill();
  }
}

/**
 * The turning ring round a selected handle: a thin circle with a knob, and while the handle
 * turns, the arc it has turned through.
 */
function drawRing(ctx: CanvasRenderingContext2D, x: number, y: number, ratio: number, turned?: number): void {
  const r = RING_RADIUS * HANDLE_RADIUS * ratio;
  ctx.beginPath();
  ctx.arc(x, y, r, 0, 2 * Math.PI);
  ctx.strokeStyle = "rgba(29, 53, 87, 0.55)";
  ctx.lineWidth = 1.5 * ratio;
  ctx.stroke();
  if (turned) {
    // Canvas y points down: a counter-clockwise turn on screen is a negative angle here.
    ctx.beginPath();
    ctx.arc(x, y, r, 0, -turned, turned > 0);
    ctx.strokeStyle = "#c0392b";
    ctx.lineWidth = 3 * ratio;
    ctx.stroke();
  }
  const angle = -(turned ?? 0);
  ctx.beginPath();
  ctx.arc(x + r * Math.cos(angle), y + r * Math.sin(angle), 0.45 * HANDLE_RADIUS * ratio, 0, 2 * Math.PI);
  ctx.fillStyle = "#1d3557";
  ctx.fill();
}

/** The painted regions tinted by their stiffness, one path per value. */
function drawStiffness(
  ctx: CanvasRenderingContext2D,
  regions: Map<number, number[][]>,
  at: (v: number) => [number, number],
): void {
  for (const [value, loops] of regions) {
    const tint = stiffnessTint(value);
    if (tint === undefined) continue;
    ctx.beginPath();
    for (const loop of loops) {
      loop.forEach((v, i) => (i === 0 ? ctx.moveTo(...at(v)) : ctx.lineTo(...at(v))));
      ctx.closePath();
    }
    ctx.fillStyle = tint;
    ctx.fill("nonzero");
  }
}

/** Arrows for a subset of vertices, the longest scaled to 40 CSS pixels. */
function drawField(
  ctx: CanvasRenderingContext2D,
  positions: ArrayLike<number>,
  field: ArrayLike<number>,
  view: View,
  ratio: number,
): void {
  const n = field.length / 2;
  let longest = 0;
  for (let v = 0; v < n; v++) longest = Math.max(longest, Math.hypot(field[2 * v]!, field[2 * v + 1]!));
  if (!(longest > 0)) return;
  const scale = (40 * ratio) / (longest * view.scale);
  const stride = Math.max(1, Math.ceil(n / MAX_ARROWS));
  ctx.beginPath();
  for (let v = 0; v < n; v += stride) {
    const [x, y] = toPixel(view, positions[2 * v]!, positions[2 * v + 1]!);
    const [tx, ty] = toPixel(
      view,
      positions[2 * v]! + scale * field[2 * v]!,
      positions[2 * v + 1]! + scale * field[2 * v + 1]!,
    );
    const length = Math.hypot(tx - x, ty - y);
    if (length < ratio) continue;
    ctx.moveTo(x, y);
    ctx.lineTo(tx, ty);
    // Arrow head.
    const ux = (tx - x) / length;
    const uy = (ty - y) / length;
    const head = Math.min(6 * ratio, length / 2);
    ctx.moveTo(tx, ty);
    ctx.lineTo(tx - head * (ux + 0.5 * uy), ty - head * (uy - 0.5 * ux));
    ctx.moveTo(tx, ty);
    ctx.lineTo(tx - head * (ux - 0.5 * uy), ty - head * (uy + 0.5 * ux));
  }
  ctx.strokeStyle = "rgba(10, 60, 140, 0.85)";
  ctx.lineWidth = 1.2 * ratio;
  ctx.stroke();
}

/** Bones as thick bars with round ends, white-rimmed so they show on any art; the one being drawn dashed. */
function drawBones(
  ctx: CanvasRenderingContext2D,
  bones: ArrayLike<number>,
  draft: readonly [number, number, number, number] | undefined,
  view: View,
  ratio: number,
): void {
  const segment = (ax: number, ay: number, bx: number, by: number) => {
    const [x0, y0] = toPixel(view, ax, ay);
    const [x1, y1] = toPixel(view, bx, by);
    ctx.moveTo(x0, y0);
    ctx.lineTo(x1, y1);
  };
  ctx.save();
  ctx.lineCap = "round";
  ctx.beginPath();
  for (let k = 0; 4 * k + 3 < bones.length; k++) {
    segment(bones[4 * k]!, bones[4 * k + 1]!, bones[4 * k + 2]!, bones[4 * k + 3]!);
  }
  ctx.strokeStyle = "rgba(255, 255, 255, 0.9)";
  ctx.lineWidth = 9 * ratio;
  ctx.stroke();
  ctx.strokeStyle = "rgba(90, 40, 140, 0.95)";
  ctx.lineWidth = 5 * ratio;
  ctx.stroke();
  if (draft) {
    ctx.beginPath();
    segment(...draft);
    ctx.setLineDash([6 * ratio, 4 * ratio]);
    ctx.strokeStyle = "rgba(90, 40, 140, 0.95)";
    ctx.lineWidth = 3 * ratio;
    ctx.stroke();
  }
  ctx.restore();
}
