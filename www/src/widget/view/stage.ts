/**
 * The widget's picture and what floats over it: the mesh canvas (WebGL2, or a 2D canvas
 * where WebGL2 is missing), the overlay canvas (outline, handles, field arrows, flipped
 * triangles, a rig's training regions and ground-truth ghost), the view ({@link Camera}), the
 * status line, the busy indicator, the training's progress (which never blocks posing), the
 * HUD, all in the shadow root's stage element (the widget adds the help panel and the
 * tool panel).
 *
 * A rig posed on the GPU is drawn from its frame (the renderer's shader forms the pose);
 * the overlay then draws from the positions of the vertices it needs (the outline, the
 * layers' outlines, the handles' triangles), which each frame gives on the CPU
 * (`Deformer.watchRigVertices`), so that nothing reads the whole pose. What needs the
 * whole pose (the field, bones, joints, the painting's tint, Cauchy-Green's cage) reads
 * it, and the frame is drawn from it.
 */
import { boneEnds } from "../model/bones.js";
import { Camera } from "./camera.js";
import { Canvas2dRenderer } from "./canvas2d-renderer.js";
import { GlRenderer, type MeshRenderer } from "./gl-renderer.js";
import { Hud } from "./hud.js";
import type { WidgetSettings } from "../options.js";
import { HANDLE_RADIUS, RING_RADIUS, drawOverlay, type OverlayHandle } from "./overlay.js";
import { regionOutlines } from "../model/geometry.js";
import { jointPositions } from "../model/puppet.js";
import { drawOrder, layering, partLayering, type Layering } from "../model/layers.js";
import type { Posing } from "../model/posing.js";
import type { Shape } from "../model/shape.js";
import { BusyIndicator } from "./busy-indicator.js";
import { StatusLine } from "./status-line.js";
import { WIDGET_CSS } from "./style.js";
import { toPixel } from "./projection.js";
import type { RigGpuLayout } from "../../core.js";

/** What the overlay draws beside the pose: the last velocity field, the ground truth's pose. */
export interface Extras {
  field?: Float64Array;
  ghost?: Float64Array;
  /** The pointer over the shape while the brush is on (shape units): its outline is drawn there. */
  brushAt?: [number, number] | undefined;
  /** A bone being drawn: x0 y0 x1 y1 (shape units). */
  boneDraft?: readonly [number, number, number, number] | undefined;
  /** The last press was a finger's: selected handles show their rings (a finger cannot hover). */
  touch?: boolean;
  /** A joint being moved with the joint tool: its index and where the pointer has it (shape units). */
  jointDraft?: { index: number; at: [number, number] } | undefined;
  /** Triangles flipped in the pose, as its metrics counted them: with 0 the overlay does not
   * look for them (at 50,000 vertices the look costs a millisecond a frame). */
  flipped?: number;
}

/**
 * The widget's element in the page (`host`, filling its container) and, in its shadow root
 * with the widget's CSS, the element that holds the toolbar and the stage (`root`).
 */
export function widgetShell(document: Document): { host: HTMLElement; root: HTMLElement } {
  const host = document.createElement("div");
  host.className = "akap-host";
  host.style.cssText = "display:block;width:100%;height:100%;";
  const shadow = host.attachShadow({ mode: "open" });
  const style = document.createElement("style");
  style.textContent = WIDGET_CSS;
  const root = document.createElement("div");
  root.className = "widget";
  root.tabIndex = 0;
  root.setAttribute("role", "application");
  root.setAttribute("aria-label", "Shape posing: click the shape to add handles, drag them to pose");
  shadow.append(style, root);
  return { host, root };
}

/** Widths (CSS pixels) below which the widget takes its narrow layout. */
export const COMPACT_WIDTH = 640;

export class Stage {
  readonly element: HTMLElement;
  readonly glCanvas: HTMLCanvasElement;
  readonly overlay: HTMLCanvasElement;
  readonly renderer: MeshRenderer;
  readonly camera = new Camera();
  readonly status: StatusLine;
  readonly busy: BusyIndicator;
  /** A rig's training: progress, times and Cancel, in a corner, while posing goes on. */
  readonly training: BusyIndicator;
  readonly hud: Hud;
  readonly #overlayContext: CanvasRenderingContext2D;
  /** The depth order last given to the renderer, and what it was computed for. */
  #layers: { shape: Shape; key: string; layers: Layering | undefined } | undefined;
  /** The painting's regions last drawn, and the painting they were made from. */
  #tints: { shape: Shape; version: number; regions: Map<number, number[][]> } | undefined;
  /** Device pixels per CSS pixel. */
  ratio = 1;
  /** Where {@link picture} draws the outline (kept: animation exports draw many frames). */
  #outline: HTMLCanvasElement | undefined;
  /** The rig on the GPU the renderer has (by deformer and version), and the vertices watched for the overlay. */
  #gpuRig: { deformer: Posing["deformer"]; version: number; watched: string } | undefined;
  /** Whether the last picture was drawn from a rig's frame (the overlay from the watched vertices). */
  #drewFrame = false;

  constructor(document: Document) {
    this.element = document.createElement("div");
    this.element.className = "stage";
    this.glCanvas = document.createElement("canvas");
    this.glCanvas.className = "mesh";
    this.overlay = document.createElement("canvas");
    this.overlay.className = "overlay";
    this.overlay.setAttribute("aria-label", "The shape; click to add a handle, drag a handle to move it");
    this.status = new StatusLine(document);
    this.busy = new BusyIndicator(document);
    this.training = new BusyIndicator(document, "training");
    this.hud = new Hud(document);
    this.element.append(this.glCanvas, this.overlay, this.status.element, this.hud.element, this.busy.element);
    this.element.append(this.training.element);
    const overlayContext = this.overlay.getContext("2d");
    if (!overlayContext) throw new Error("this browser cannot draw on a 2D canvas");
    this.#overlayContext = overlayContext;
    let renderer: MeshRenderer;
    try {
      renderer = new GlRenderer(this.glCanvas);
    } catch {
      renderer = new Canvas2dRenderer(this.glCanvas);
    }
    this.renderer = renderer;
  }

  /**
   * Sizes the canvases to the element at device resolution and tells the camera (`rest`:
   * the rest positions it fits until the user moves the view); returns the width in CSS
   * pixels.
   */
  resize(rest: ArrayLike<number>): number {
    const ratio = this.element.ownerDocument.defaultView?.devicePixelRatio || 1;
    const rect = this.glCanvas.getBoundingClientRect();
    const width = Math.max(1, Math.round(rect.width * ratio));
    const height = Math.max(1, Math.round(rect.height * ratio));
    for (const canvas of [this.glCanvas, this.overlay]) {
      if (canvas.width !== width || canvas.height !== height) {
        canvas.width = width;
        canvas.height = height;
      }
    }
    this.ratio = ratio;
    this.camera.resize(rest, width, height);
    return rect.width;
  }

  /**
   * The depth order of the shape: a puppet's parts by their depths, else what the handles
   * give it; computed again when the shape, the depths, the handles or their layers change.
   * The renderer draws the triangles back to front.
   */
  layering(posing: Posing): Layering | undefined {
    const { puppet } = posing.shape;
    const depths = posing.depths;
    const key =
      puppet && depths
        ? `parts ${depths.join()}`
        : posing.handles.map((h) => `${h.point.triangle}/${h.point.barycentric.join()}/${h.layer}`).join(";");
    if (this.#layers?.shape !== posing.shape || this.#layers.key !== key) {
      const { positions, triangles, boundaryEdges, vertexCount } = posing.shape.mesh;
      const layers =
        puppet && depths
          ? partLayering(vertexCount, triangles, boundaryEdges, puppet.partOf, depths)
          : layering(positions, triangles, boundaryEdges, posing.handles);
      if (layers || this.#layers?.layers) this.renderer.setTriangles(drawOrder(triangles, layers));
      this.#layers = { shape: posing.shape, key, layers };
    }
    return this.#layers.layers;
  }

  /** The painted stiffness as regions of one value each (1 left out), made again when it changes. */
  #tint(posing: Posing): Map<number, number[][]> | undefined {
    const { stiffness, stiffnessVersion: version, shape } = posing;
    if (!stiffness) return undefined;
    if (this.#tints?.shape !== shape || this.#tints.version !== version) {
      const regions = regionOutlines(shape.mesh.triangles, stiffness, shape.mesh.vertexCount);
      regions.delete(1);
      this.#tints = { shape, version, regions };
    }
    return this.#tints.regions;
  }

  /** The renderer has the mesh's triangles in their own order (a new mesh was set). */
  meshSet(): void {
    this.#layers = undefined;
  }

  /** Draws the pose now: the mesh, then the overlay (with the last field and a rig's ghost, if any). */
  render(posing: Posing, settings: WidgetSettings, extras: Extras): void {
    this.layering(posing);
    const frame = this.#rigFrame(posing, settings, extras);
    this.#drewFrame = frame !== undefined;
    this.renderer.draw(
      frame ? EMPTY : posing.deformer.positionsView(),
      this.camera.view,
      {
        wireframe: settings.wireframe,
        pixelRatio: this.ratio,
        background: "#f6f1e7",
        fill: "#c8773a",
        wire: "rgba(60, 30, 10, 0.55)",
        flipped: settings.flipped,
      },
      frame,
    );
    this.drawOverlay(this.#overlayContext, posing, settings, extras, true);
  }

  /**
   * The rig's frame to draw, when a rig on the GPU has the frame of the pose shown (its
   * pose on the CPU left behind, or also evaluated for the foldover guard) and the overlay
   * can be drawn from the watched vertices; the rig's texture uploaded and the vertices
   * watched first when they changed (that frame is drawn from the pose: the watched
   * positions come with the next frame). A rig the renderer cannot take poses on the CPU.
   */
  #rigFrame(posing: Posing, settings: WidgetSettings, extras: Extras): Float32Array | undefined {
    const { deformer } = posing;
    if (!deformer.rigFrameCurrent) return undefined;
    const version = posing.gpuRigVersion;
    if (this.#gpuRig?.deformer !== deformer || this.#gpuRig.version !== version) {
      const layout = deformer.rigGpuLayout();
      const texture = deformer.rigGpuTexture();
      if (!layout || !texture || !this.renderer.setRig(layout, texture)) {
        this.renderer.clearRig();
        this.#gpuRig = undefined;
        deformer.setRigOnGpu(false);
        return undefined;
      }
      this.#gpuRig = { deformer, version, watched: "" };
    }
    const layers = this.layering(posing);
    const key = `${layers?.order.join() ?? ""} ${posing.handles.map((h) => h.point.triangle).join()}`;
    if (this.#gpuRig.watched !== key) {
      deformer.watchRigVertices(watchedVertices(posing, layers));
      this.#gpuRig.watched = key;
      return undefined;
    }
    return this.#wholePoseNeeded(posing, settings, extras) ? undefined : deformer.rigFrame();
  }

  /** Whether the overlay draws something that needs the whole pose (not only the watched vertices). */
  #wholePoseNeeded(posing: Posing, settings: WidgetSettings, extras: Extras): boolean {
    const painted = posing.stiffness !== undefined && (settings.tool === "stiffness" || settings.wireframe);
    return (
      (settings.field && extras.field !== undefined) ||
      posing.bones.list.length > 0 ||
      settings.tool === "joint" ||
      extras.boneDraft !== undefined ||
      painted ||
      (settings.wireframe && posing.deformer.method === "cauchy-green")
    );
  }

  /** See `Widget.rigGpuReadback`. */
  rigGpuReadback(
    posing: Posing,
  ):
    | { positions: Float32Array; layout: RigGpuLayout; texture: Float32Array; frame: Float32Array; drawn: boolean }
    | undefined {
    const { deformer } = posing;
    // The texture first: making it may grow the memory, which detaches views of it.
    const [layout, texture] = [deformer.rigGpuLayout(), deformer.rigGpuTexture()];
    const frame = deformer.rigFrame();
    if (
      !(this.renderer instanceof GlRenderer) ||
      this.#gpuRig?.deformer !== deformer ||
      !layout ||
      !frame ||
      !texture
    ) {
      return undefined;
    }
    const positions = this.renderer.shaderPositions(EMPTY, frame);
    return { positions, layout, texture, frame: frame.slice(), drawn: this.#drewFrame };
  }

  /** Where the handles are in the picture: from the watched vertices when it was drawn from a rig's frame. */
  #handlePositions(posing: Posing): Float64Array {
    const watched = this.#drewFrame ? posing.deformer.rigWatchedPositions() : undefined;
    if (!watched) return posing.deformer.handlePositions();
    const { triangles } = posing.shape.mesh;
    const out = new Float64Array(2 * posing.handles.length);
    posing.handles.forEach((h, i) => {
      const { triangle, barycentric } = h.point;
      let [x, y] = [0, 0];
      for (let k = 0; k < 3; k++) {
        const v = triangles[3 * triangle + k]!;
        x += barycentric[k]! * watched[2 * v]!;
        y += barycentric[k]! * watched[2 * v + 1]!;
      }
      [out[2 * i], out[2 * i + 1]] = [x, y];
    });
    return out;
  }

  /**
   * The overlay on `ctx`: outline, flipped triangles, and with `withHandles` the handles,
   * the field, a rig's training regions and its ghost, and with the wireframe Cauchy-Green's cage.
   */
  drawOverlay(
    ctx: CanvasRenderingContext2D,
    posing: Posing,
    settings: WidgetSettings,
    extras: Extras,
    withHandles: boolean,
  ): void {
    const { deformer, shape } = posing;
    // Drawn from a rig's frame: the overlay from the watched vertices, the flipped triangles tinted by the renderer.
    const watched = this.#drewFrame ? deformer.rigWatchedPositions() : undefined;
    const positions = watched ?? deformer.positionsView();
    const at = withHandles ? this.#handlePositions(posing) : new Float64Array(0);
    const targets = withHandles ? posing.targets() : at;
    // Cauchy-Green's cage is structure, like the triangles: shown with the wireframe.
    const cage = withHandles && settings.wireframe ? deformer.cage() : undefined;
    const paper = settings.paperMode;
    const rig = withHandles && posing.posingWithRig ? posing.rig : undefined;
    // The regions its training drew targets from (discs, Voronoi cells or both, as Rust
    // defines them) and which handles' targets lie outside them.
    const sampled = settings.region ? rig?.regions() : undefined;
    const outside = sampled ? rig!.operator.outsideRegions(targets) : undefined;
    // A selected handle's turning ring shows while it turns, or while the pointer is near it
    // (off the handle itself: a pointer resting on the handle it just dragged shows none),
    // or, after a finger's press, whenever it is selected and not held.
    const near = (i: number) => {
      const pointer = extras.brushAt;
      if (pointer === undefined) return false;
      const pixels =
        (Math.hypot(pointer[0] - at[2 * i]!, pointer[1] - at[2 * i + 1]!) * this.camera.view.scale) / this.ratio;
      return pixels > 1.5 * HANDLE_RADIUS && pixels < (RING_RADIUS + 1.2) * HANDLE_RADIUS;
    };
    const handles: OverlayHandle[] = withHandles
      ? posing.handles.map((h, i) => ({
          x: at[2 * i]!,
          y: at[2 * i + 1]!,
          targetX: paper ? at[2 * i]! : targets[2 * i]!,
          targetY: paper ? at[2 * i + 1]! : targets[2 * i + 1]!,
          selected: h.selected,
          dragged: h.pointerId !== undefined,
          ring: h.selected && (h.turning !== undefined || (h.pointerId === undefined && (extras.touch || near(i)))),
          turned: h.turning ? h.turning.turn - h.turning.start : undefined,
          outside: outside?.[i] === 1,
        }))
      : [];
    const c = sampled?.centres;
    const regions = sampled && {
      discs: sampled.discs
        ? Array.from({ length: c!.length / 2 }, (_, i) => ({ x: c![2 * i]!, y: c![2 * i + 1]!, r: sampled.radius }))
        : [],
      cells: sampled.cells ?? [],
    };
    // Painted stiffness shows while the brush is on, and with the wireframe (structure).
    const painting = settings.tool === "stiffness";
    const stiffness = withHandles && (painting || settings.wireframe) ? this.#tint(posing) : undefined;
    const brushAt = withHandles && painting ? extras.brushAt : undefined;
    const brush = brushAt && {
      x: brushAt[0],
      y: brushAt[1],
      r: (settings.brush.size * this.ratio) / this.camera.view.scale,
    };
    const scene = {
      layers: this.layering(posing),
      // Re-read: handlePositions() and cage() may have grown the memory and detached the view.
      positions: positions.length > 0 ? positions : (deformer.rigWatchedPositions() ?? deformer.positionsView()),
      triangles: shape.mesh.triangles,
      boundaryEdges: shape.mesh.boundaryEdges,
      handles,
      field: withHandles && settings.field ? extras.field : undefined,
      showFlipped: settings.flipped && !watched && (extras.flipped ?? 1) > 0,
      regions,
      ghost: rig && settings.compare ? extras.ghost : undefined,
      cage,
      stiffness,
      brush,
      ...(withHandles && posing.bones.list.length > 0
        ? { bones: boneEnds(posing.bones.list, deformer.positionsView(), shape.mesh.triangles) }
        : {}),
      boneDraft: withHandles ? extras.boneDraft : undefined,
      joints: withHandles && settings.tool === "joint" ? this.#joints(posing, extras) : undefined,
    };
    drawOverlay(ctx, scene, this.camera.view, this.ratio);
  }

  /** A puppet's joints where they are in the pose (a joint being moved where the pointer has it). */
  #joints(posing: Posing, extras: Extras): { x: number; y: number; selected: boolean }[] | undefined {
    const { puppet, mesh, size } = posing.shape;
    if (!puppet) return undefined;
    const at = jointPositions(puppet, posing.joints, mesh.positions, posing.deformer.positionsView(), 1e-6 * size);
    const draft = extras.jointDraft;
    return Array.from({ length: at.length / 2 }, (_, i) => {
      const [x, y] = draft?.index === i ? draft.at : [at[2 * i]!, at[2 * i + 1]!];
      return { x, y, selected: posing.selectedJoint === i };
    });
  }

  /**
   * The picture as drawn (mesh and outline, no handles), on `into` (made, or resized, to
   * the canvas's size): what PNG and animation exports encode.
   */
  picture(posing: Posing, settings: WidgetSettings, into?: HTMLCanvasElement): HTMLCanvasElement {
    this.render(posing, settings, {});
    const document = this.element.ownerDocument;
    const canvas = into ?? document.createElement("canvas");
    if (canvas.width !== this.glCanvas.width) canvas.width = this.glCanvas.width;
    if (canvas.height !== this.glCanvas.height) canvas.height = this.glCanvas.height;
    const ctx = canvas.getContext("2d");
    if (!ctx) throw new Error("this browser cannot draw on a 2D canvas");
    ctx.drawImage(this.glCanvas, 0, 0);
    this.#outline ??= document.createElement("canvas");
    const outline = this.#outline;
    outline.width = canvas.width;
    outline.height = canvas.height;
    const outlineContext = outline.getContext("2d");
    if (outlineContext) {
      this.drawOverlay(outlineContext, posing, settings, {}, false);
      ctx.drawImage(outline, 0, 0);
    }
    return canvas;
  }

  /** The picture as drawn (mesh and outline, no handles) as a PNG. */
  async png(posing: Posing, settings: WidgetSettings): Promise<Blob> {
    return canvasBlob(this.picture(posing, settings), "image/png");
  }

  /** Fades the HUD out while a dragged handle is under it (or near), so the handle shows. */
  keepHudClear(posing: Posing): void {
    const hud = this.hud.element;
    if (hud.classList.contains("hidden")) return;
    let under = false;
    if (posing.dragging) {
      const box = hud.getBoundingClientRect();
      const canvas = this.overlay.getBoundingClientRect();
      const p = this.#handlePositions(posing);
      const margin = 24;
      under = posing.handles.some((h, i) => {
        if (h.pointerId === undefined) return false;
        const [px, py] = toPixel(this.camera.view, p[2 * i]!, p[2 * i + 1]!);
        const [x, y] = [canvas.left + px / this.ratio, canvas.top + py / this.ratio];
        return x > box.left - margin && x < box.right + margin && y > box.top - margin && y < box.bottom + margin;
      });
    }
    hud.classList.toggle("clear", under);
  }

  /** Client (CSS) pixels to device pixels of the canvas. */
  devicePixel(clientX: number, clientY: number): [number, number] {
    const rect = this.overlay.getBoundingClientRect();
    return [(clientX - rect.left) * this.ratio, (clientY - rect.top) * this.ratio];
  }

  destroy(): void {
    this.renderer.destroy();
    this.hud.destroy();
    this.busy.done();
    this.training.done();
  }
}

/** No positions: a picture drawn from a rig's frame reads none. */
const EMPTY = new Float64Array(0);

/**
 * The vertices the overlay reads when the picture is drawn from a rig's frame: the
 * outline's, the layers' outlines', and the corners of the handles' triangles.
 */
function watchedVertices(posing: Posing, layers: Layering | undefined): Uint32Array {
  const { boundaryEdges, triangles } = posing.shape.mesh;
  const seen = new Set<number>(boundaryEdges);
  for (const loops of layers?.outlines ?? []) for (const loop of loops) for (const v of loop) seen.add(v);
  for (const h of posing.handles) for (let k = 0; k < 3; k++) seen.add(triangles[3 * h.point.triangle + k]!);
  return Uint32Array.from(seen);
}

/** A canvas's picture encoded (`type`, e.g. "image/png"). */
export function canvasBlob(canvas: HTMLCanvasElement, type: string): Promise<Blob> {
  return new Promise((resolve, reject) =>
    canvas.toBlob((blob) => (blob ? resolve(blob) : reject(new Error("the image could not be encoded"))), type),
  );
}
