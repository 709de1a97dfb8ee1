/**
 * The posing widget: a shape drawn with WebGL2 (an image warps with it), handles added by
 * clicking anywhere on the shape, dragged with mouse, pen or several fingers, pins that
 * stay, undo and redo per gesture, recorded sessions that replay bit for bit, exports, and
 * a heads-up display. {@link mount} puts one into any element; several on one page are
 * independent (all state lives in the instance, the DOM in a shadow root).
 *
 * Each animation frame that has work: every handle's velocity is its target (the pointer,
 * or where a pin was left) minus its current position, split into substeps no longer than
 * `maxStep`; the deformer steps; positions are read through a view of wasm memory and
 * drawn.
 */
import {
  Deformer,
  builtinShape,
  builtinShapes,
  init,
  meshFromArrays,
  triangulate,
  type DeformerOptions,
  type MeshData,
  type Metrics,
  type Outline,
  type Timings,
} from "../core.js";
import { Canvas2dRenderer } from "./canvas2d.js";
import { displacementVelocities, largestGap, substepCount, trackingVelocities } from "./drag.js";
import { download, meshJson, meshObj, outlineSvg, vectorSvg } from "./export.js";
import { PointMapper, type VectorPath } from "../import.js";
import { FILE_LIMITS, asOutline, fileKind, imageUvs, readShapeFile, type Loaded } from "./sources.js";

import { Camera } from "./camera.js";
import { GlRenderer, type MeshRenderer } from "./gl.js";
import { HelpPanel } from "./help.js";
import { History } from "./history.js";
import { Hud } from "./hud.js";
import { keyCommand, keyFocus } from "./keys.js";
import { PointerInput } from "./pointer.js";
import { HANDLE_RADIUS, drawOverlay, type OverlayHandle } from "./overlay.js";
import { locate, nearestPoint, pointPosition, type MeshPoint } from "./picking.js";
import { Recorder, parseSession, type Session, type SessionEvent } from "./session.js";
import { meshOutline, sessionShape, shapeFromMesh, type Shape } from "./shape.js";
import { Cancelled, ShapeMaker, type Prepared, type SetupRequest } from "./setup.js";
import { BusyIndicator, StatusLine } from "./status.js";
import { WorkStore, textureBlob, textureCanvas, type SavedWork } from "./persist.js";
import { WIDGET_CSS } from "./style.js";
import { defaultTexture } from "./texture.js";
import { buildToolbar, type Toolbar } from "./toolbar.js";
import { vectorTexture } from "./vector-texture.js";
import { bounds, fromPixel, toPixel, type View } from "./view.js";

/** The deformation methods the widget offers: AKAP and the paper's ablations (Figure 8). */
export const METHODS = {
  akap: { label: "AKAP", options: { method: "akap", dirichlet: true, integrator: "spiral" } },
  "akap-no-dirichlet": {
    label: "AKAP without Dirichlet step",
    options: { method: "akap", dirichlet: false, integrator: "spiral" },
  },
  "akap-linear": {
    label: "AKAP with linear steps",
    options: { method: "akap", dirichlet: true, integrator: "linear" },
  },
  "akap-simple": {
    label: "AKAP, both simplifications",
    options: { method: "akap", dirichlet: false, integrator: "linear" },
  },
  arap: { label: "ARAP (10 iterations per step)", options: { method: "arap", iterations: 10 } },
} as const satisfies Record<string, { label: string; options: DeformerOptions }>;

export type Method = keyof typeof METHODS;

export interface WidgetOptions {
  /** A built-in shape (see `builtinShapes()`); default the first one. */
  shape?: string;
  /** A shape of your own instead of a built-in one. */
  outline?: Outline;
  /** An image URL used as the texture of built-in shapes (mapped onto the bounding box). */
  texture?: string;
  /**
   * A file to start with instead: an SVG, an image (traced, and warped as the texture) or
   * a mesh (OBJ or our JSON), by URL.
   */
  src?: string;
  /** More shapes for the toolbar's list: files by URL (SVG, image, OBJ, JSON mesh). */
  gallery?: readonly GalleryItem[];
  /** About how many mesh vertices (default 1500). */
  vertices?: number;
  /** Smallest triangle angle in degrees (default 28). */
  minAngle?: number;
  method?: Method;
  /** Weight of the soft handle constraints (default 100). */
  lambda?: number;
  /** Velocities from raw pointer displacement, as in the paper, instead of target tracking. */
  paperMode?: boolean;
  /** Show the toolbar (default true). */
  controls?: boolean;
  /** Show the heads-up display (default true). */
  hud?: boolean;
  wireframe?: boolean;
  /** Draw the last frame's velocity field as arrows. */
  field?: boolean;
  /** Highlight flipped triangles (default true). */
  flipped?: boolean;
  /** Longest handle move per substep, as a fraction of the shape's size (default 0.02). */
  maxStep?: number;
  /** Most substeps per animation frame (default 8); longer moves continue next frame. */
  maxSubsteps?: number;
  /**
   * Keep the work (shape, pose, handles, settings) across reloads, in the browser's
   * IndexedDB under this key; it comes back when the widget starts without `shape`, `src`
   * or `outline`. Off by default; the app uses it. The toolbar then has "Start over".
   */
  storageKey?: string;
}

/** A file the toolbar offers beside the built-in shapes. */
export interface GalleryItem {
  name: string;
  url: string;
}

/** `detail` of the `akap-pose` event, sent after every frame that moved the shape. */
export interface PoseDetail {
  metrics: Metrics;
  handleCount: number;
  /** Milliseconds of work in the frame (solver steps and drawing); 0 outside the frame loop. */
  frameMs: number;
  /** Deformer steps in the frame. */
  steps: number;
  /** Solver stages summed over the frame's steps. */
  timings: Timings;
}

interface Handle {
  point: MeshPoint;
  /** Where the handle is going, shape units. */
  target: [number, number];
  selected: boolean;
  /** The pointer dragging it, if any, and the offset from pointer to handle at grab time. */
  pointerId: number | undefined;
  grab: [number, number];
  /** Paper mode: pointer motion not yet turned into steps. */
  pending: [number, number];
}

/** Everything undo restores: the shape and its parts, the method, the pose and the handles. */
interface Snapshot {
  shape: Shape;
  parts: Parts | undefined;
  method: Method;
  lambda: number;
  positions: Float64Array;
  atRest: boolean;
  handles: { point: MeshPoint; target: [number, number] }[];
}

/** The parts of an imported file (largest first) and the one shown. */
interface Parts {
  loaded: Extract<Loaded, { kind: "outlines" }>;
  index: number;
}

const DEFAULTS = {
  vertices: 1500,
  minAngle: 28,
  method: "akap" as Method,
  lambda: 100,
  maxStep: 0.02,
  maxSubsteps: 8,
};

/** Frames without input after which the loop stops even if pins have not settled. */
const SETTLE_FRAMES = 240;
/** A failed step is tried again with its velocities scaled by these, in turn. */
const RETRY_SCALES = [0.5, 0.25, 0.125];

export class Widget {
  /** The element the widget was mounted into; events are dispatched on it. */
  readonly target: HTMLElement;
  readonly #host: HTMLElement;
  readonly #root: HTMLElement;
  readonly #glCanvas: HTMLCanvasElement;
  readonly #overlay: HTMLCanvasElement;
  readonly #overlayContext: CanvasRenderingContext2D;
  readonly #status: StatusLine;
  readonly #busy: BusyIndicator;
  readonly #help: HelpPanel;
  readonly #renderer: MeshRenderer;
  readonly #hud: Hud;
  readonly #toolbar: Toolbar | undefined;
  readonly #resizeObserver: ResizeObserver;
  readonly #history = new History<Snapshot>();
  readonly #recorder = new Recorder();
  readonly #camera = new Camera();
  readonly #maker = new ShapeMaker();
  readonly #settings: Required<Omit<WidgetOptions, "shape" | "outline" | "texture" | "src" | "gallery" | "storageKey">>;
  readonly #store: WorkStore | undefined;
  #saveTimer: ReturnType<typeof setTimeout> | undefined;
  /** PNG encodings of imported images' textures, made once per shape for saving. */
  readonly #savedTextures = new WeakMap<Shape, Promise<Blob | undefined>>();
  readonly #gallery: readonly GalleryItem[];
  /** Files opened so far, offered again in the shape list as `file:index`. */
  readonly #files: Loaded[] = [];
  #baseTexture: TexImageSource | undefined;
  #parts: Parts | undefined;

  #shape!: Shape;
  #deformer!: Deformer;
  #handles: Handle[] = [];
  #ratio = 1;
  #raf = 0;
  #idleFrames = 0;
  #atRest = true;
  #gestureBefore: Snapshot | undefined;
  #gestureChanged = false;
  #pointer: PointerInput | undefined;
  #spaceHeld = false;
  #lastField: Float64Array | undefined;
  #metrics: Metrics = { areaDistortion: 2, angleDistortion: 2, flipped: 0 };
  #replaying = false;
  #destroyed = false;
  #idleWaiters: (() => void)[] = [];

  private constructor(target: HTMLElement, options: WidgetOptions) {
    this.target = target;
    this.#gallery = options.gallery ?? [];
    this.#store = options.storageKey ? new WorkStore(options.storageKey) : undefined;
    this.#settings = {
      vertices: options.vertices ?? DEFAULTS.vertices,
      minAngle: options.minAngle ?? DEFAULTS.minAngle,
      method: options.method ?? DEFAULTS.method,
      lambda: options.lambda ?? DEFAULTS.lambda,
      paperMode: options.paperMode ?? false,
      controls: options.controls ?? true,
      hud: options.hud ?? true,
      wireframe: options.wireframe ?? false,
      field: options.field ?? false,
      flipped: options.flipped ?? true,
      maxStep: options.maxStep ?? DEFAULTS.maxStep,
      maxSubsteps: options.maxSubsteps ?? DEFAULTS.maxSubsteps,
    };
    if (!(METHODS as Record<string, unknown>)[this.#settings.method]) {
      throw new Error(`unknown method "${this.#settings.method}"; the methods are ${Object.keys(METHODS).join(", ")}`);
    }
    if (!(this.#settings.maxStep > 0) || !(this.#settings.maxSubsteps >= 1)) {
      throw new Error("maxStep must be above 0 and maxSubsteps at least 1");
    }
    const document = target.ownerDocument;
    this.#host = document.createElement("div");
    this.#host.className = "akap-host";
    this.#host.style.cssText = "display:block;width:100%;height:100%;";
    const shadow = this.#host.attachShadow({ mode: "open" });
    const style = document.createElement("style");
    style.textContent = WIDGET_CSS;
    this.#root = document.createElement("div");
    this.#root.className = "widget";
    this.#root.tabIndex = 0;
    this.#root.setAttribute("role", "application");
    this.#root.setAttribute("aria-label", "Shape posing: click the shape to add handles, drag them to pose");
    shadow.append(style, this.#root);

    const stage = document.createElement("div");
    stage.className = "stage";
    this.#glCanvas = document.createElement("canvas");
    this.#glCanvas.className = "mesh";
    this.#overlay = document.createElement("canvas");
    this.#overlay.className = "overlay";
    this.#overlay.setAttribute("aria-label", "The shape; click to add a handle, drag a handle to move it");
    this.#status = new StatusLine(document);
    this.#busy = new BusyIndicator(document);
    this.#help = new HelpPanel(document, () => this.#toggleHelp(false));
    this.#hud = new Hud(document);
    this.#hud.element.classList.toggle("hidden", !this.#settings.hud);
    stage.append(this.#glCanvas, this.#overlay, this.#status.element, this.#hud.element, this.#busy.element);
    stage.append(this.#help.element);

    if (this.#settings.controls) {
      this.#toolbar = buildToolbar(document, this.#toolbarActions(), {
        shapes: [
          ...builtinShapes().map((name) => ({ value: `builtin:${name}`, label: name })),
          ...this.#gallery.map((item, i) => ({ value: `gallery:${i}`, label: item.name })),
        ],
        methods: Object.entries(METHODS).map(([value, m]) => ({ value, label: m.label })),
        settings: this.#settings,
      });
      this.#root.append(this.#toolbar.element);
    }
    this.#root.append(stage);

    const overlayContext = this.#overlay.getContext("2d");
    if (!overlayContext) throw new Error("this browser cannot draw on a 2D canvas");
    this.#overlayContext = overlayContext;
    let renderer: MeshRenderer;
    try {
      renderer = new GlRenderer(this.#glCanvas);
    } catch {
      renderer = new Canvas2dRenderer(this.#glCanvas);
    }
    this.#renderer = renderer;
    this.#root.dataset.renderer = renderer.kind;

    this.#bindInput();
    this.#resizeObserver = new ResizeObserver(() => this.#resize());
    target.append(this.#host);
  }

  /** Creates a widget inside `target` (see {@link mount}). */
  static async create(target: HTMLElement, options: WidgetOptions = {}): Promise<Widget> {
    await init();
    const widget = new Widget(target, options);
    try {
      const name = options.outline ? undefined : (options.shape ?? builtinShapes()[0]!);
      const outline = options.outline ?? builtinShape(name!);
      widget.#baseTexture = options.texture ? await loadImage(options.texture) : defaultTexture();
      const chosen = options.src !== undefined || options.shape !== undefined || options.outline !== undefined;
      const saved = chosen ? undefined : await widget.#store?.load().catch(() => undefined);
      if (options.src) await widget.loadUrl(options.src);
      else widget.#install(meshOutline(outline, name, widget.#settings.vertices, widget.#settings.minAngle));
      if (saved) {
        await widget.#resume(saved).catch((error: unknown) => {
          widget.#status.info(`The saved work could not be restored (${messageOf(error)}); starting afresh.`);
        });
      }
      widget.#history.clear();
    } catch (error) {
      widget.destroy();
      throw error;
    }
    widget.#resizeObserver.observe(widget.#glCanvas);
    widget.#resize();
    widget.#emit("akap-ready", { vertexCount: widget.vertexCount, triangleCount: widget.triangleCount });
    return widget;
  }

  // ---------------------------------------------------------------- public API

  get vertexCount(): number {
    return this.#shape.mesh.vertexCount;
  }

  get triangleCount(): number {
    return this.#shape.mesh.triangleCount;
  }

  /** The rest mesh. */
  get mesh(): MeshData {
    return this.#shape.mesh;
  }

  /** The method in use and lambda. */
  get method(): { method: Method; lambda: number } {
    return { method: this.#settings.method, lambda: this.#settings.lambda };
  }

  /** How shape units map to device pixels of the canvas, and the device pixel ratio. */
  get view(): View & { pixelRatio: number } {
    return { ...this.#camera.view, pixelRatio: this.#ratio };
  }

  /** Which renderer draws the mesh: "webgl2", or "2d" where WebGL2 is missing. */
  get renderer(): "webgl2" | "2d" {
    return this.#renderer.kind;
  }

  /** The current positions (a copy), xy-interleaved. */
  positions(): Float64Array {
    return this.#deformer.positions();
  }

  /** Current handle positions (xy-interleaved). */
  handlePositions(): Float64Array {
    return this.#deformer.handlePositions();
  }

  get handleCount(): number {
    return this.#handles.length;
  }

  /** Distortion of the pose on screen. */
  get metrics(): Metrics {
    return { ...this.#metrics };
  }

  /** Undo and redo as the buttons offer them. */
  get canUndo(): boolean {
    return this.#history.canUndo;
  }

  get canRedo(): boolean {
    return this.#history.canRedo;
  }

  /** Adds a handle at the shape point (x, y) (shape units). Returns its index, or -1 off the shape. */
  addHandleAt(x: number, y: number): number {
    const point = locate(this.#deformer.positionsView(), this.#shape.mesh.triangles, x, y);
    if (!point) return -1;
    this.#gesture(() => this.#addHandle(point));
    return this.#handles.length - 1;
  }

  /** Removes a handle by index. */
  removeHandle(index: number): void {
    if (!(index >= 0 && index < this.#handles.length)) throw new RangeError(`there is no handle ${index}`);
    this.#gesture(() => {
      this.#handles.splice(index, 1);
      this.#applyHandles();
    });
  }

  /** Removes every handle (the pose stays). */
  clearHandles(): void {
    if (this.#handles.length === 0) return;
    this.#gesture(() => {
      this.#handles = [];
      this.#applyHandles();
    });
  }

  /** Back to the rest pose; handles stay, at their rest places. */
  reset(): void {
    this.#gesture(() => {
      this.#deformer.reset();
      this.#record({ reset: true });
      this.#atRest = true;
      this.#pinHandlesWhereTheyAre();
      this.#poseChanged();
    });
  }

  undo(): boolean {
    return this.#travel(this.#history.undo(this.#snapshot()));
  }

  redo(): boolean {
    return this.#travel(this.#history.redo(this.#snapshot()));
  }

  /** Changes the method and/or lambda. */
  setMethod(method: Method, lambda = this.#settings.lambda): void {
    if (!(METHODS as Record<string, unknown>)[method]) throw new Error(`unknown method "${method}"`);
    const options = methodOptions(method, lambda);
    this.#useOptions(options); // throws (and changes nothing) for a bad lambda
    this.#record({ options });
    this.#showMethod(method, lambda);
  }

  /** Zooms the view by `factor` about its centre, or fits the pose on screen into it (`"fit"`). */
  zoom(factor: number | "fit"): void {
    if (factor === "fit") this.#camera.fit(this.#deformer.positionsView());
    else this.#camera.zoom(this.#glCanvas.width / 2, this.#glCanvas.height / 2, factor);
    this.#draw();
  }

  /** Shows a message in the status line until the next action that succeeds. */
  showMessage(message: string, kind: "info" | "error" = "info"): void {
    if (kind === "error") this.#showError(new Error(message));
    else this.#status.info(message);
  }

  /**
   * Switches to a built-in shape, or re-meshes the current one with about `vertices`
   * vertices (meshed in a worker; see {@link remesh}). Undoable; the handles of another
   * shape are dropped.
   */
  async setShape(name: string | undefined, vertices = this.#settings.vertices): Promise<void> {
    const spec = name ?? this.#shape.spec?.name;
    if (!spec) throw new Error("this widget shows a custom outline; give a built-in shape name");
    builtinShape(spec); // an unknown name fails here, before any work
    const prepared = await this.#make({ name: spec, outline: undefined, label: spec, vertices });
    this.#gesture(() => {
      this.#settings.vertices = vertices;
      this.#parts = undefined;
      this.#install(prepared.shape, prepared.orders);
    });
  }

  /** Shows a custom outline instead (triangulated to about `vertices` vertices). Undoable. */
  async setOutline(outline: Outline, vertices = this.#settings.vertices): Promise<void> {
    const prepared = await this.#make({ name: undefined, outline, label: "custom shape", vertices });
    this.#gesture(() => {
      this.#parts = undefined;
      this.#install(prepared.shape, prepared.orders);
    });
  }

  /**
   * Meshes an outline and orders the deformer's systems, in a worker, while the busy
   * indicator shows the stage and offers Cancel; rejects with `Cancelled` when cancelled
   * or replaced by a newer request.
   */
  async #make(
    request: Pick<SetupRequest, "name" | "outline" | "label" | "vertices"> & { minAngle?: number },
  ): Promise<Prepared> {
    const options = this.#deformerOptions();
    const full: SetupRequest = { minAngle: this.#settings.minAngle, ...request, options };
    const label = `${request.label}: ${Math.round(request.vertices)} vertices`;
    const cancel = () => this.#maker.cancel();
    this.#busy.update({ label: `${label}…`, progress: 0, cancel });
    try {
      const prepared = await this.#maker.make(full, (stage, progress) =>
        this.#busy.update({ label: `${label}: ${stage.toLowerCase()}…`, progress, cancel }),
      );
      this.#busy.update({ label: `${label}: preparing the solver…`, progress: 0.9 });
      await nextFrame();
      if (this.#destroyed) throw new Cancelled();
      // Orders made for another method (switched meanwhile) do not fit its systems.
      const sameMethod = (options.method ?? "akap") === (this.#deformerOptions().method ?? "akap");
      return { shape: prepared.shape, orders: sameMethod ? prepared.orders : undefined };
    } finally {
      this.#busy.done();
    }
  }

  /**
   * Loads a shape from a file: an SVG document (its filled shapes), an image (the shape
   * where it is opaque, or where it differs from the background; the image warps with
   * it), a mesh (OBJ or our JSON), or a recorded session (JSON), which is replayed. Files
   * with several separate parts show the largest; {@link choosePart} picks another.
   * Throws (and changes nothing) for files it cannot use; a load is one undoable step.
   */
  async loadFile(file: Blob, name = (file as File).name ?? "file"): Promise<void> {
    if (fileKind(name, file.type) === "json" && file.size <= FILE_LIMITS.bytes) {
      const text = await file.text();
      if (/"format"\s*:\s*"akap-session"/.test(text)) {
        const session = parseSession(text);
        await this.replay(session);
        this.#lastSession = session;
        this.#refreshButtons();
        return;
      }
    }
    const loaded = await readShapeFile(file, name);
    if (loaded.kind === "outlines" && loaded.parts.length === 0) throw new Error(`${name}: no shape found`);
    await this.#showFile(loaded, 0);
    this.#files.push(loaded);
    this.#toolbar?.addShape({ value: `file:${this.#files.length - 1}`, label: loaded.name });
  }

  /** Loads a shape file by URL (see {@link loadFile}). */
  async loadUrl(url: string): Promise<void> {
    let response: Response;
    try {
      response = await fetch(url);
    } catch {
      throw new Error(`${url} could not be loaded (the address is wrong, or the server refused it)`);
    }
    if (!response.ok) throw new Error(`${url}: ${response.status} ${response.statusText}`);
    const name = decodeURIComponent(new URL(url, this.target.ownerDocument.baseURI).pathname.split("/").pop() ?? url);
    await this.loadFile(await response.blob(), name);
  }

  /** Shows another separate part of the last imported file (0 is the largest). Undoable. */
  async choosePart(index: number): Promise<void> {
    const parts = this.#parts;
    if (!parts || !(index >= 0 && index < parts.loaded.parts.length)) {
      throw new RangeError(`there is no part ${index} to choose`);
    }
    await this.#showFile(parts.loaded, index);
  }

  /** Makes a loaded file (part `index` of it) the shape, as one undoable step. */
  async #showFile(loaded: Loaded, index: number): Promise<void> {
    const prepared =
      loaded.kind === "mesh"
        ? { shape: shapeFromMesh(loaded.mesh, undefined, loaded.uvs, loaded.name), orders: undefined }
        : await this.#partShape(loaded, index);
    this.#gesture(() => {
      this.#parts = loaded.kind === "outlines" ? { loaded, index } : undefined;
      this.#install(prepared.shape, prepared.orders);
    });
    if (loaded.kind === "outlines" && loaded.parts.length > 1) {
      this.#status.info(
        `${loaded.name} has ${loaded.parts.length} separate parts; showing part ${index + 1} (the parts are ordered by size)`,
      );
    }
  }

  async #partShape(loaded: Extract<Loaded, { kind: "outlines" }>, index: number): Promise<Prepared> {
    const { vertices } = this.#settings;
    const prepared = await this.#make({
      name: undefined,
      outline: asOutline(loaded.parts[index]!),
      label: loaded.name,
      vertices,
    });
    const shape = prepared.shape;
    if (loaded.image) {
      shape.uvs = imageUvs(shape.mesh.positions, loaded.image.width, loaded.image.height);
      shape.texture = loaded.image.source;
    }
    if (loaded.vector) this.#paintVector(shape, loaded.vector);
    return prepared;
  }

  /** An imported SVG's art: kept for vector export and drawn, in its colours, as the texture. */
  #paintVector(shape: Shape, vector: VectorPath[]): void {
    shape.vector = vector;
    shape.texture = vectorTexture(this.target.ownerDocument, vector, bounds(shape.mesh.positions)).canvas;
  }

  #partsInfo(): { count: number; index: number } {
    return this.#parts ? { count: this.#parts.loaded.parts.length, index: this.#parts.index } : { count: 1, index: 0 };
  }

  /**
   * Re-meshes the current shape with about `vertices` vertices and the given smallest
   * angle (a live preview of the triangulation with the wireframe on), in a worker: the
   * page stays responsive and the busy indicator offers Cancel. The pose carries over
   * (every new vertex is placed where the old mesh's pose takes its rest position), and so
   * do the handles, at the same places; one undoable step. Built-in shapes and imported
   * outlines can be re-meshed; a mesh loaded from a file cannot.
   */
  async remesh(vertices = this.#settings.vertices, minAngle = this.#settings.minAngle): Promise<void> {
    if (!this.#parts && !this.#shape.spec) throw new Error("this shape came as a mesh; it cannot be re-meshed");
    const previous = { vertices: this.#settings.vertices, minAngle: this.#settings.minAngle };
    Object.assign(this.#settings, { vertices, minAngle });
    let prepared: Prepared;
    try {
      const spec = this.#shape.spec;
      prepared = this.#parts
        ? await this.#partShape(this.#parts.loaded, this.#parts.index)
        : await this.#make({ name: spec!.name, outline: undefined, label: spec!.name, vertices, minAngle });
    } catch (error) {
      Object.assign(this.#settings, previous);
      throw error;
    }
    const { shape, orders } = prepared;
    const old = { shape: this.#shape, positions: this.#deformer.positions(), atRest: this.#atRest };
    const handles = this.#handles.map((h) => ({
      rest: pointPosition(old.shape.mesh.positions, old.shape.mesh.triangles, h.point),
      target: h.target,
    }));
    this.#gesture(() => {
      this.#adopt(shape, orders);
      this.#handles = [];
      if (!old.atRest) {
        const mapper = new PointMapper(old.shape.mesh.positions, old.shape.mesh.triangles, shape.mesh.positions);
        try {
          this.#deformer.setPositions(mapper.map(old.positions));
        } finally {
          mapper.free();
        }
      }
      this.#atRest = old.atRest;
      const rest = shape.mesh.positions;
      for (const { rest: at, target } of handles) {
        const point =
          locate(rest, shape.mesh.triangles, at[0], at[1], 1e-6 * shape.size) ??
          locate(rest, shape.mesh.triangles, at[0], at[1], 0.05 * shape.size);
        if (point) this.#handles.push({ ...newHandle(point), target: [...target] });
      }
      this.#applyHandles();
      this.#poseChanged();
    });
  }

  setDisplay(options: { wireframe?: boolean; field?: boolean; flipped?: boolean; paperMode?: boolean }): void {
    Object.assign(this.#settings, options);
    if (options.field) this.#lastField = this.#deformer.field();
    this.#draw();
  }

  get recording(): boolean {
    return this.#recorder.recording;
  }

  /** Starts recording every change of the deformer. */
  startRecording(): void {
    const start: SessionEvent[] = this.#atRest
      ? [{ reset: true }]
      : [{ positions: Array.from(this.#deformer.positionsView()) }];
    if (this.#handles.length > 0) start.push(this.#handlesEvent());
    const mesh = this.#shape.mesh;
    this.#recorder.start(
      {
        ...(this.#shape.spec ? { shape: { ...this.#shape.spec } } : {}),
        mesh: {
          vertexCount: mesh.vertexCount,
          triangleCount: mesh.triangleCount,
          ...(this.#shape.spec ? {} : { positions: Array.from(mesh.positions), triangles: Array.from(mesh.triangles) }),
        },
        options: this.#deformerOptions(),
      },
      start,
    );
    this.#refreshButtons();
  }

  /** Stops recording and returns the session (which Replay and Save then offer). */
  stopRecording(): Session | undefined {
    const session = this.#recorder.stop();
    if (session) this.#lastSession = session;
    this.#refreshButtons();
    return session;
  }

  /**
   * Replays a session (an object, or JSON text): rebuilds its mesh if needed, then repeats
   * its calls, drawing every `stepsPerFrame` steps. Resolves with the final positions.
   * The result is bit-for-bit the pose the recording ended in, with the session's method;
   * the whole replay is one undoable step, and a session that fails partway leaves
   * everything as it was before.
   */
  async replay(session: Session | string, stepsPerFrame = 4): Promise<Float64Array> {
    const s = typeof session === "string" ? parseSession(session) : session;
    if (this.#replaying) throw new Error("a replay is already running");
    this.#releasePointers();
    const shape = sessionShape(s, this.#shape);
    if (shape.mesh.vertexCount !== s.mesh.vertexCount || shape.mesh.triangleCount !== s.mesh.triangleCount) {
      throw new Error(
        `the session's mesh has ${s.mesh.vertexCount} vertices and ${s.mesh.triangleCount} triangles, ` +
          `but rebuilding it gave ${shape.mesh.vertexCount} and ${shape.mesh.triangleCount}`,
      );
    }
    const before = this.#snapshot();
    this.#replaying = true;
    this.#root.dataset.replaying = "true";
    try {
      if (shape !== this.#shape) {
        this.#parts = undefined;
        this.#install(shape);
      }
      const defaults: DeformerOptions =
        s.options.method === "arap" ? {} : { ...METHODS.akap.options, lambda: DEFAULTS.lambda };
      this.#applyOptions({ ...defaults, ...s.options });
      let steps = 0;
      for (const event of s.events) {
        if (this.#destroyed) break;
        this.#apply(event);
        if ("step" in event && ++steps % stepsPerFrame === 0) {
          this.#render();
          await nextFrame();
        }
      }
    } catch (error) {
      if (!this.#destroyed) this.#restore(before);
      throw error;
    } finally {
      this.#replaying = false;
      delete this.#root.dataset.replaying;
    }
    this.#pinHandlesWhereTheyAre();
    this.#history.push(before);
    this.#refreshButtons();
    this.#poseChanged();
    return this.#deformer.positions();
  }

  /** The current pose as JSON (`positions`, `triangles`, `uvs`) or OBJ text. */
  exportMesh(format: "json" | "obj"): string {
    const p = this.#deformer.positionsView();
    const { triangles } = this.#shape.mesh;
    return format === "json" ? meshJson(p, triangles, this.#shape.uvs) : meshObj(p, triangles, this.#shape.uvs);
  }

  /** The outline of the current pose as an SVG document. */
  exportSvg(): string {
    const positions = this.#deformer.positions();
    const vector = this.#shape.vector;
    if (!vector) return outlineSvg(positions, this.#shape.mesh.boundaryEdges);
    // An imported SVG stays vector art: its path points follow the mesh.
    const { positions: rest, triangles } = this.#shape.mesh;
    return vectorSvg(
      vector.map((path) => {
        const mapper = new PointMapper(rest, triangles, path.points);
        try {
          return { path, points: mapper.map(positions) };
        } finally {
          mapper.free();
        }
      }),
    );
  }

  /** The rendered image (the shape and its outline, no handles) as a PNG. */
  exportPng(): Promise<Blob> {
    this.#render();
    const canvas = this.target.ownerDocument.createElement("canvas");
    canvas.width = this.#glCanvas.width;
    canvas.height = this.#glCanvas.height;
    const ctx = canvas.getContext("2d");
    if (!ctx) return Promise.reject(new Error("this browser cannot draw on a 2D canvas"));
    ctx.drawImage(this.#glCanvas, 0, 0);
    const outline = this.target.ownerDocument.createElement("canvas");
    outline.width = canvas.width;
    outline.height = canvas.height;
    const outlineContext = outline.getContext("2d");
    if (outlineContext) {
      this.#drawOverlayOn(outlineContext, false);
      ctx.drawImage(outline, 0, 0);
    }
    return new Promise((resolve, reject) =>
      canvas.toBlob(
        (blob) => (blob ? resolve(blob) : reject(new Error("the image could not be encoded"))),
        "image/png",
      ),
    );
  }

  /** Resolves when no frame is pending (the pose has settled and nothing is dragged). */
  whenIdle(): Promise<void> {
    if (this.#raf === 0 && !this.#replaying) return Promise.resolve();
    return new Promise((resolve) => this.#idleWaiters.push(resolve));
  }

  /** Removes the widget from the page and frees its WebAssembly memory. */
  destroy(): void {
    if (this.#destroyed) return;
    this.#destroyed = true;
    if (this.#raf) cancelAnimationFrame(this.#raf);
    this.#raf = 0;
    this.#pointer?.destroy();
    this.#resizeObserver.disconnect();
    this.#renderer.destroy();
    this.#hud.destroy();
    this.#maker.destroy();
    this.#busy.done();
    clearTimeout(this.#saveTimer);
    this.#deformer?.free();
    this.#host.remove();
    for (const resolve of this.#idleWaiters.splice(0)) resolve();
  }

  /**
   * Forgets the saved work and starts again: the default shape at its default density, at
   * rest, without handles, with the default method and display. Undoable.
   */
  async startOver(): Promise<void> {
    await this.#store?.clear();
    const name = builtinShapes()[0]!;
    const shape = meshOutline(builtinShape(name), name, DEFAULTS.vertices, DEFAULTS.minAngle);
    this.#gesture(() => {
      Object.assign(this.#settings, { vertices: DEFAULTS.vertices, minAngle: DEFAULTS.minAngle });
      Object.assign(this.#settings, { wireframe: false, field: false, flipped: true, paperMode: false });
      this.#showMethod(DEFAULTS.method, DEFAULTS.lambda);
      this.#parts = undefined;
      this.#install(shape);
    });
    this.#syncToolbar();
  }

  // ---------------------------------------------------------------- keeping the work

  /** Puts back saved work (over the shape just installed); throws, changing nothing, if it cannot. */
  async #resume(saved: SavedWork): Promise<void> {
    const { shape: kept, settings } = saved;
    let shape: Shape;
    if (kept.kind === "builtin") {
      const spec = kept.spec;
      const mesh = triangulate(builtinShape(spec.name), {
        targetEdgeLength: spec.targetEdgeLength,
        minAngle: spec.minAngle,
      });
      shape = shapeFromMesh(mesh, { ...spec });
    } else {
      shape = shapeFromMesh(meshFromArrays(kept.positions, kept.triangles), undefined, kept.uvs, kept.name);
      if (kept.texture) shape.texture = await textureCanvas(this.target.ownerDocument, kept.texture);
      if (kept.vector) this.#paintVector(shape, kept.vector);
    }
    if (!(METHODS as Record<string, unknown>)[settings.method]) throw new Error(`unknown method ${settings.method}`);
    const before = this.#snapshot();
    try {
      Object.assign(this.#settings, settings);
      this.#hud.element.classList.toggle("hidden", !this.#settings.hud);
      this.#install(shape);
      this.#restore({ ...saved, shape, parts: undefined, method: settings.method as Method, lambda: settings.lambda });
    } catch (error) {
      this.#restore(before);
      throw error;
    }
    this.#syncToolbar();
  }

  /** Saves the work a moment after the last change (nothing while a replay runs). */
  #scheduleSave(): void {
    if (!this.#store || this.#replaying) return;
    clearTimeout(this.#saveTimer);
    this.#saveTimer = setTimeout(() => {
      this.#save().catch((error: unknown) => {
        this.#status.info(`Your work cannot be kept in this browser: ${messageOf(error)}`);
      });
    }, 400);
  }

  async #save(): Promise<void> {
    if (!this.#store || this.#destroyed) return;
    const shape = this.#shape;
    const { mesh } = shape;
    let texture: Promise<Blob | undefined> | undefined;
    if (!shape.spec && shape.texture && !shape.vector) {
      texture = this.#savedTextures.get(shape) ?? textureBlob(shape.texture);
      this.#savedTextures.set(shape, texture);
    }
    const snapshot = this.#snapshot();
    const s = this.#settings;
    const work: SavedWork = {
      format: "akap-work",
      version: 1,
      settings: {
        vertices: s.vertices,
        minAngle: s.minAngle,
        method: s.method,
        lambda: s.lambda,
        wireframe: s.wireframe,
        field: s.field,
        flipped: s.flipped,
        paperMode: s.paperMode,
        hud: s.hud,
      },
      shape: shape.spec
        ? { kind: "builtin", spec: { ...shape.spec } }
        : {
            kind: "mesh",
            name: shape.name,
            positions: Float64Array.from(mesh.positions),
            triangles: Uint32Array.from(mesh.triangles),
            uvs: shape.uvs,
            ...(texture ? { texture: await texture } : {}),
            ...(shape.vector ? { vector: shape.vector } : {}),
          },
      positions: snapshot.positions,
      atRest: snapshot.atRest,
      handles: snapshot.handles,
    };
    await this.#store.save(work);
  }

  // ---------------------------------------------------------------- shape, method and deformer

  /** Makes `shape` current with a fresh deformer, without handles, at rest. */
  #install(shape: Shape, orders?: Uint32Array[]): void {
    this.#adopt(shape, orders);
    this.#handles = [];
    this.#atRest = true;
    this.#camera.reset(shape.mesh.positions, this.#glCanvas.width, this.#glCanvas.height);
    this.#applyHandles();
    this.#poseChanged();
  }

  /**
   * Makes `shape` current with a fresh deformer of the current method (handles and pose
   * are the caller's to set); fails without changing anything. A recording ends.
   */
  #adopt(shape: Shape, orders?: Uint32Array[]): void {
    const deformer = new Deformer(shape.mesh.positions, shape.mesh.triangles, this.#deformerOptions(), orders);
    this.#deformer?.free();
    this.#deformer = deformer;
    this.#shape = shape;
    this.#recorder.stop();
    this.#lastField = undefined;
    this.#renderer.setMesh(shape.mesh.triangles, shape.edges, shape.uvs);
    const texture = shape.texture ?? this.#baseTexture;
    if (texture) this.#renderer.setTexture(texture);
    const file = this.#files.findIndex((f) => f === this.#parts?.loaded);
    this.#toolbar?.showShape(
      shape.spec ? `builtin:${shape.spec.name}` : file >= 0 ? `file:${file}` : undefined,
      shape.mesh.vertexCount,
      this.#partsInfo(),
    );
    this.#hud.showMesh(
      shape.mesh.vertexCount,
      shape.mesh.triangleCount,
      METHODS[this.#settings.method].label,
      deformer.metrics(),
    );
    this.#refreshButtons();
  }

  #deformerOptions(): DeformerOptions {
    return methodOptions(this.#settings.method, this.#settings.lambda);
  }

  /**
   * Applies deformer options. The same method only changes settings; another method (AKAP
   * and ARAP are different solvers) gets a new deformer with the current pose and handles.
   */
  #useOptions(options: DeformerOptions): void {
    const { method = "akap", ...settings } = options;
    if (method === this.#deformer.method) {
      this.#deformer.setOptions(settings);
      return;
    }
    const { positions, triangles } = this.#shape.mesh;
    const next = new Deformer(positions, triangles, options);
    try {
      next.setPositions(this.#deformer.positionsView());
      const event = this.#handlesEvent();
      next.setHandlePoints(event.handles.triangles, event.handles.barycentric);
    } catch (error) {
      next.free();
      throw error;
    }
    this.#deformer.free();
    this.#deformer = next;
  }

  /** Deformer options from a session: applied, and shown as the widget's method. */
  #applyOptions(options: DeformerOptions): void {
    this.#useOptions(options);
    const { method, lambda } = widgetMethod(options, this.#settings.lambda);
    this.#showMethod(method, lambda);
  }

  #showMethod(method: Method, lambda: number): void {
    this.#settings.method = method;
    this.#settings.lambda = lambda;
    this.#toolbar?.sync(this.#settings);
    this.#hud.showMethod(METHODS[method].label);
  }

  // ---------------------------------------------------------------- handles

  #addHandle(point: MeshPoint): Handle {
    const [x, y] = pointPosition(this.#deformer.positionsView(), this.#shape.mesh.triangles, point);
    const handle: Handle = { ...newHandle(point), target: [x, y] };
    this.#handles.push(handle);
    this.#applyHandles();
    return handle;
  }

  /** Sends the handle set to the deformer (and the recording). */
  #applyHandles(): void {
    const event = this.#handlesEvent();
    this.#deformer.setHandlePoints(event.handles.triangles, event.handles.barycentric);
    this.#record(event);
    this.#emit("akap-handles", { count: this.#handles.length });
    this.#schedule();
  }

  #handlesEvent(): { handles: { triangles: number[]; barycentric: number[] } } {
    return {
      handles: {
        triangles: this.#handles.map((h) => h.point.triangle),
        barycentric: this.#handles.flatMap((h) => h.point.barycentric),
      },
    };
  }

  #pinHandlesWhereTheyAre(): void {
    const p = this.#deformer.handlePositions();
    this.#handles.forEach((h, i) => {
      h.target = [p[2 * i]!, p[2 * i + 1]!];
      h.pending = [0, 0];
    });
    this.#schedule();
  }

  // ---------------------------------------------------------------- gestures and history

  #snapshot(): Snapshot {
    return {
      shape: this.#shape,
      parts: this.#parts,
      method: this.#settings.method,
      lambda: this.#settings.lambda,
      positions: this.#deformer.positions(),
      atRest: this.#atRest,
      handles: this.#handles.map((h) => ({ point: h.point, target: [...h.target] })),
    };
  }

  /** Undo or redo to `snapshot`, if there is one. */
  #travel(snapshot: Snapshot | undefined): boolean {
    if (snapshot) {
      this.#restore(snapshot);
      this.#status.succeeded();
    }
    this.#refreshButtons();
    return snapshot !== undefined;
  }

  #restore(snapshot: Snapshot): void {
    this.#releasePointers();
    if (snapshot.method !== this.#settings.method || snapshot.lambda !== this.#settings.lambda) {
      this.#settings.method = snapshot.method;
      this.#settings.lambda = snapshot.lambda;
      if (snapshot.shape === this.#shape) this.#useOptions(this.#deformerOptions());
      this.#showMethod(snapshot.method, snapshot.lambda);
    }
    if (snapshot.shape !== this.#shape) {
      this.#parts = snapshot.parts;
      this.#adopt(snapshot.shape);
      this.#camera.reset(snapshot.shape.mesh.positions, this.#glCanvas.width, this.#glCanvas.height);
    }
    this.#deformer.setPositions(snapshot.positions);
    this.#record({ positions: Array.from(snapshot.positions) });
    this.#atRest = snapshot.atRest;
    this.#handles = snapshot.handles.map((h) => ({ ...newHandle(h.point), target: [...h.target] }));
    this.#applyHandles();
    this.#poseChanged();
  }

  /** Runs one complete gesture (an undoable unit) that is not a drag. */
  #gesture(change: () => void): void {
    // The first shape, while the widget is made, has nothing before it.
    const before = (this.#shape as Shape | undefined) && this.#snapshot();
    change();
    if (before) this.#history.push(before);
    this.#status.succeeded();
    this.#refreshButtons();
    this.#draw();
  }

  #releasePointers(): void {
    for (const h of this.#handles) h.pointerId = undefined;
    this.#endDragGesture();
  }

  #endDragGesture(): void {
    if (this.#gestureBefore && this.#handles.every((h) => h.pointerId === undefined)) {
      if (this.#gestureChanged) this.#history.push(this.#gestureBefore);
      this.#gestureBefore = undefined;
      this.#gestureChanged = false;
      this.#refreshButtons();
    }
  }

  /** The pose on screen changed outside the frame loop: distortion, HUD, event, picture. */
  #poseChanged(): void {
    this.#metrics = this.#deformer.metrics();
    if (this.#settings.field) this.#lastField = this.#deformer.field();
    this.#hud.showMetrics(this.#metrics);
    this.#draw();
    this.#emitPose();
  }

  // ---------------------------------------------------------------- the frame loop

  #schedule(): void {
    if (this.#raf === 0 && !this.#destroyed) {
      this.#raf = requestAnimationFrame((time) => this.#frame(time));
      delete this.#root.dataset.idle;
    }
  }

  #frame(time: number): void {
    this.#raf = 0;
    if (this.#destroyed || this.#replaying) return;
    const started = performance.now();
    const timings: Timings = { assembly: 0, factorisation: 0, dirichletFactorisation: 0, solve: 0, integration: 0 };
    let substeps = 0;
    try {
      substeps = this.#advance(timings);
      if (substeps > 0) this.#status.succeeded();
    } catch (error) {
      // The deformer is unchanged; pins stay where they are, dragged handles keep their
      // targets and are tried again next frame, in smaller steps.
      this.#showError(new Error(`${messageOf(error)}. Try a smaller move, or Undo (Ctrl+Z) or Reset.`));
      const p = this.#deformer.handlePositions();
      this.#handles.forEach((h, i) => {
        if (h.pointerId === undefined) h.target = [p[2 * i]!, p[2 * i + 1]!];
      });
    }
    const dragging = this.#handles.some((h) => h.pointerId !== undefined);
    this.#idleFrames = substeps > 0 && dragging ? 0 : this.#idleFrames + 1;
    if (substeps > 0) {
      this.#atRest = false;
      this.#gestureChanged = true;
      this.#metrics = this.#deformer.metrics();
      if (this.#settings.field) this.#lastField = this.#deformer.field();
    }
    this.#render();
    this.#keepHudClear(dragging);
    if (substeps > 0) {
      const work = performance.now() - started;
      this.#hud.report({ time, work, timings, substeps, metrics: this.#metrics });
      this.#emitPose(work, substeps, timings);
    }
    if (dragging || (substeps > 0 && this.#idleFrames < SETTLE_FRAMES)) {
      this.#schedule();
    } else {
      this.#root.dataset.idle = "true";
      for (const resolve of this.#idleWaiters.splice(0)) resolve();
    }
  }

  /** Moves the handles toward their targets; returns the number of deformer steps taken. */
  #advance(timings: Timings): number {
    const n = this.#handles.length;
    if (n === 0) return 0;
    const { maxStep, maxSubsteps, paperMode } = this.#settings;
    const longest = maxStep * this.#shape.size;
    let current = this.#deformer.handlePositions();
    if (paperMode) {
      const displacement = new Float64Array(2 * n);
      this.#handles.forEach((h, i) => {
        displacement[2 * i] = h.pending[0];
        displacement[2 * i + 1] = h.pending[1];
        h.pending = [0, 0];
      });
      const distance = largestGap(new Float64Array(2 * n), displacement);
      if (distance === 0) return 0;
      const count = Math.min(substepCount(distance, longest), maxSubsteps);
      const velocities = displacementVelocities(displacement, count);
      for (let s = 0; s < count; s++) this.#step(velocities, timings);
      current = this.#deformer.handlePositions();
      // The handles end where the deformation took them; pins stay pins.
      this.#handles.forEach((h, i) => {
        if (h.pointerId === undefined) h.target = [current[2 * i]!, current[2 * i + 1]!];
      });
      return count;
    }
    const targets = new Float64Array(2 * n);
    this.#handles.forEach((h, i) => {
      targets[2 * i] = h.target[0];
      targets[2 * i + 1] = h.target[1];
    });
    const gap = largestGap(current, targets);
    if (gap <= 1e-5 * this.#shape.size) return 0;
    const needed = substepCount(gap, longest);
    const count = Math.min(needed, maxSubsteps);
    const velocities = new Float64Array(2 * n);
    for (let s = 0; s < count; s++) {
      trackingVelocities(current, targets, needed - s, velocities);
      this.#step(velocities, timings);
      current = this.#deformer.handlePositions();
    }
    return count;
  }

  /**
   * One deformer step; a step that fails (the deformer is then unchanged) is tried again
   * with smaller velocities before the error is passed on.
   */
  #step(velocities: Float64Array, timings: Timings): void {
    let taken = velocities;
    try {
      this.#deformer.step(velocities);
    } catch (error) {
      const smaller = RETRY_SCALES.map((f) => velocities.map((v) => v * f)).find((v) => {
        try {
          this.#deformer.step(v);
          return true;
        } catch {
          return false;
        }
      });
      if (!smaller) throw error;
      taken = smaller;
    }
    if (this.#recorder.recording) this.#record({ step: Array.from(taken) });
    const t = this.#deformer.timings();
    timings.assembly += t.assembly;
    timings.factorisation += t.factorisation;
    timings.dirichletFactorisation += t.dirichletFactorisation;
    timings.solve += t.solve;
    timings.integration += t.integration;
  }

  #apply(event: SessionEvent): void {
    if ("handles" in event) {
      const { triangles, barycentric } = event.handles;
      this.#deformer.setHandlePoints(triangles, barycentric);
      this.#handles = triangles.map((triangle, i) =>
        newHandle({
          triangle,
          barycentric: [barycentric[3 * i]!, barycentric[3 * i + 1]!, barycentric[3 * i + 2]!],
        }),
      );
      this.#pinHandlesWhereTheyAre();
    } else if ("step" in event) {
      this.#deformer.step(event.step);
      this.#atRest = false;
    } else if ("positions" in event) {
      this.#deformer.setPositions(event.positions);
      this.#atRest = false;
    } else if ("options" in event) {
      this.#applyOptions(event.options);
    } else {
      this.#deformer.reset();
      this.#atRest = true;
    }
  }

  #record(event: SessionEvent): void {
    if (!this.#replaying) this.#recorder.record(event);
  }

  // ---------------------------------------------------------------- drawing and the view

  #resize(): void {
    if (this.#destroyed) return;
    const ratio = this.target.ownerDocument.defaultView?.devicePixelRatio || 1;
    const rect = this.#glCanvas.getBoundingClientRect();
    const width = Math.max(1, Math.round(rect.width * ratio));
    const height = Math.max(1, Math.round(rect.height * ratio));
    for (const canvas of [this.#glCanvas, this.#overlay]) {
      if (canvas.width !== width || canvas.height !== height) {
        canvas.width = width;
        canvas.height = height;
      }
    }
    this.#ratio = ratio;
    this.#camera.resize(this.#shape.mesh.positions, width, height);
    this.#root.classList.toggle("compact", rect.width < 640);
    this.#draw();
  }

  /** Asks for the picture to be drawn anew in the next animation frame (once, however often asked). */
  #draw(): void {
    this.#schedule();
  }

  /** Draws the picture now: the mesh, then the overlay. */
  #render(): void {
    if (this.#destroyed) return;
    const s = this.#settings;
    this.#renderer.draw(this.#deformer.positionsView(), this.#camera.view, {
      wireframe: s.wireframe,
      pixelRatio: this.#ratio,
      background: "#f6f1e7",
      fill: "#c8773a",
      wire: "rgba(60, 30, 10, 0.55)",
    });
    this.#drawOverlayOn(this.#overlayContext, true);
    this.#root.dataset.frame = String(Number(this.#root.dataset.frame ?? 0) + 1);
    this.#scheduleSave();
  }

  #drawOverlayOn(ctx: CanvasRenderingContext2D, withHandles: boolean): void {
    const positions = this.#deformer.positionsView();
    const handlePositions = withHandles ? this.#deformer.handlePositions() : new Float64Array(0);
    const handles: OverlayHandle[] = withHandles
      ? this.#handles.map((h, i) => ({
          x: handlePositions[2 * i]!,
          y: handlePositions[2 * i + 1]!,
          targetX: this.#settings.paperMode ? handlePositions[2 * i]! : h.target[0],
          targetY: this.#settings.paperMode ? handlePositions[2 * i + 1]! : h.target[1],
          selected: h.selected,
          dragged: h.pointerId !== undefined,
        }))
      : [];
    drawOverlay(
      ctx,
      {
        // Re-read: handlePositions() may have grown the memory and detached the view.
        positions: positions.length > 0 ? positions : this.#deformer.positionsView(),
        triangles: this.#shape.mesh.triangles,
        boundaryEdges: this.#shape.mesh.boundaryEdges,
        handles,
        field: withHandles && this.#settings.field ? this.#lastField : undefined,
        showFlipped: this.#settings.flipped,
      },
      this.#camera.view,
      this.#ratio,
    );
  }

  /** Fades the HUD out while a dragged handle is under it (or near), so the handle shows. */
  #keepHudClear(dragging: boolean): void {
    const hud = this.#hud.element;
    if (hud.classList.contains("hidden")) return;
    let under = false;
    if (dragging) {
      const box = hud.getBoundingClientRect();
      const canvas = this.#overlay.getBoundingClientRect();
      const p = this.#deformer.handlePositions();
      const margin = 24;
      under = this.#handles.some((h, i) => {
        if (h.pointerId === undefined) return false;
        const [px, py] = toPixel(this.#camera.view, p[2 * i]!, p[2 * i + 1]!);
        const [x, y] = [canvas.left + px / this.#ratio, canvas.top + py / this.#ratio];
        return x > box.left - margin && x < box.right + margin && y > box.top - margin && y < box.bottom + margin;
      });
    }
    hud.classList.toggle("clear", under);
  }

  /** Client (CSS) pixels to device pixels of the canvas. */
  #devicePixel(clientX: number, clientY: number): [number, number] {
    const rect = this.#overlay.getBoundingClientRect();
    return [(clientX - rect.left) * this.#ratio, (clientY - rect.top) * this.#ratio];
  }

  // ---------------------------------------------------------------- input

  #bindInput(): void {
    const ratio = () => this.#ratio;
    this.#pointer = new PointerInput(this.#overlay, {
      accepting: () => !this.#replaying,
      focus: () => this.#root.focus({ preventScroll: true }),
      toShape: (clientX, clientY) => fromPixel(this.#camera.view, ...this.#devicePixel(clientX, clientY)),
      handleAt: (x, y) => {
        const radius = (1.6 * HANDLE_RADIUS * ratio()) / this.#camera.view.scale;
        return nearestPoint(this.#deformer.handlePositions(), x, y, radius);
      },
      beginGesture: () => {
        this.#gestureBefore ??= this.#snapshot();
      },
      addHandleAt: (x, y) => {
        const tolerance = (4 * ratio()) / this.#camera.view.scale;
        const point = locate(this.#deformer.positionsView(), this.#shape.mesh.triangles, x, y, tolerance);
        if (!point) return -1;
        this.#addHandle(point);
        this.#gestureChanged = true;
        this.#status.succeeded();
        return this.#handles.length - 1;
      },
      grab: (index, pointerId, x, y, additive) => {
        const handle = this.#handles[index]!;
        if (handle.pointerId !== undefined) return false; // another finger has it
        if (!additive && !handle.selected) this.#handles.forEach((h) => (h.selected = false));
        handle.selected = additive ? !handle.selected : true;
        const p = this.#deformer.handlePositions();
        handle.pointerId = pointerId;
        handle.grab = [p[2 * index]! - x, p[2 * index + 1]! - y];
        handle.target = [p[2 * index]!, p[2 * index + 1]!];
        this.#draw();
        this.#schedule();
        return true;
      },
      drag: (pointerId, x, y) => {
        const handle = this.#handles.find((h) => h.pointerId === pointerId);
        if (!handle) return;
        const next: [number, number] = [x + handle.grab[0], y + handle.grab[1]];
        handle.pending = [
          handle.pending[0] + next[0] - handle.target[0],
          handle.pending[1] + next[1] - handle.target[1],
        ];
        handle.target = next;
        this.#idleFrames = 0;
        this.#schedule();
      },
      release: (pointerId) => {
        const handle = this.#handles.find((h) => h.pointerId === pointerId);
        if (handle) handle.pointerId = undefined;
        this.#endDragGesture();
        this.#draw();
        this.#schedule();
      },
      removeHeld: (pointerId) => {
        const at = this.#handles.findIndex((h) => h.pointerId === pointerId);
        if (at < 0) return;
        this.#handles.splice(at, 1);
        this.#applyHandles();
        this.#gestureChanged = true;
        this.#endDragGesture();
        this.#draw();
      },
      removeAt: (x, y) => {
        const radius = (1.6 * HANDLE_RADIUS * ratio()) / this.#camera.view.scale;
        const index = nearestPoint(this.#deformer.handlePositions(), x, y, radius);
        if (index >= 0) this.removeHandle(index);
      },
      pressedOff: (additive) => {
        if (!additive) this.#handles.forEach((h) => (h.selected = false));
        this.#endDragGesture();
        this.#draw();
      },
      panMode: () => this.#spaceHeld,
      pan: (dx, dy) => {
        this.#camera.pan(dx * ratio(), dy * ratio());
        this.#draw();
      },
      zoom: (clientX, clientY, factor) => {
        this.#camera.zoom(...this.#devicePixel(clientX, clientY), factor);
        this.#draw();
      },
    });
    this.#root.addEventListener("keydown", (e) => this.#key(e));
    this.#root.addEventListener("keyup", (e) => {
      if (e.key === " ") this.#setSpace(false);
    });
    this.#root.addEventListener("blur", () => this.#setSpace(false), true);
    // Files dropped on the stage load like the Open button's.
    this.#overlay.addEventListener("dragover", (e) => {
      if (e.dataTransfer?.types.includes("Files")) e.preventDefault();
    });
    this.#overlay.addEventListener("drop", (e) => {
      const file = e.dataTransfer?.files[0];
      if (!file) return;
      e.preventDefault();
      this.loadFile(file).catch((error: unknown) => this.#showError(error));
    });
  }

  #setSpace(held: boolean): void {
    this.#spaceHeld = held;
    this.#overlay.classList.toggle("panning", held);
  }

  #key(e: KeyboardEvent): void {
    const focus = keyFocus(e.composedPath()[0] ?? null);
    if (e.key === " " && focus === "other") {
      e.preventDefault();
      this.#setSpace(true);
      return;
    }
    const command = keyCommand(e, focus);
    if (!command) return;
    e.preventDefault();
    switch (command.kind) {
      case "undo":
        this.undo();
        break;
      case "redo":
        this.redo();
        break;
      case "delete": {
        const keep = this.#handles.filter((h) => !h.selected);
        if (keep.length < this.#handles.length) {
          this.#gesture(() => {
            this.#handles = keep;
            this.#applyHandles();
          });
        }
        break;
      }
      case "nudge": {
        const selected = this.#handles.filter((h) => h.selected);
        const unit = this.#ratio / this.#camera.view.scale;
        const [dx, dy] = [command.dx * unit, command.dy * unit];
        if (selected.length === 0) break;
        this.#gesture(() => {
          for (const h of selected) {
            h.target = [h.target[0] + dx, h.target[1] + dy];
            h.pending = [h.pending[0] + dx, h.pending[1] + dy];
          }
          this.#schedule();
        });
        break;
      }
      case "deselect":
        if (this.#help.open) this.#toggleHelp(false);
        this.#handles.forEach((h) => (h.selected = false));
        this.#draw();
        break;
      case "toggle":
        this.setDisplay({ [command.what]: !this.#settings[command.what] });
        this.#toolbar?.sync(this.#settings);
        break;
      case "fit":
        this.zoom("fit");
        break;
      case "zoom":
        this.zoom(command.factor);
        break;
      case "help":
        this.#toggleHelp();
        break;
    }
  }

  #toggleHelp(open = !this.#help.open): void {
    this.#help.open = open;
    if (!open) this.#root.focus({ preventScroll: true });
  }

  // ---------------------------------------------------------------- toolbar, events, errors

  #toolbarActions(): Parameters<typeof buildToolbar>[1] {
    // An action that fails says why, and its fields show the settings in force again.
    const guard =
      <A extends unknown[]>(action: (...args: A) => unknown) =>
      (...args: A): void => {
        const failed = (error: unknown): void => {
          if (error instanceof Cancelled) this.#status.info(error.message);
          else this.#showError(error);
          this.#syncToolbar();
        };
        try {
          const result = action(...args);
          if (result instanceof Promise) result.catch(failed);
        } catch (error) {
          failed(error);
        }
      };
    return {
      undo: guard(() => this.undo()),
      redo: guard(() => this.redo()),
      reset: guard(() => this.reset()),
      clear: guard(() => this.clearHandles()),
      shape: guard(async (value: string) => {
        const [kind, rest] = [value.slice(0, value.indexOf(":")), value.slice(value.indexOf(":") + 1)];
        if (kind === "builtin") await this.setShape(rest);
        else if (kind === "file") await this.#showFile(this.#files[Number(rest)]!, 0);
        else await this.loadUrl(this.#gallery[Number(rest)]!.url);
      }),
      remesh: guard((vertices: number, minAngle: number) => this.remesh(vertices, minAngle)),
      open: guard((file: File) => this.loadFile(file)),
      part: guard((index: number) => this.choosePart(index)),
      method: guard((method: string, lambda: number) => {
        this.setMethod(method as Method, lambda);
        this.#status.succeeded();
      }),
      display: guard((options: { wireframe: boolean; field: boolean; flipped: boolean; paperMode: boolean }) =>
        this.setDisplay(options),
      ),
      hud: (visible: boolean) => {
        this.#settings.hud = visible;
        this.#hud.element.classList.toggle("hidden", !visible);
      },
      record: guard(() => (this.recording ? this.stopRecording() : this.startRecording())),
      replay: guard(() => (this.#lastSession ? this.replay(this.#lastSession) : undefined)),
      saveSession: guard(() => {
        if (this.#lastSession) {
          download(
            this.target.ownerDocument,
            JSON.stringify(this.#lastSession),
            "session.akap.json",
            "application/json",
          );
        }
      }),
      loadSession: guard(async (file: File) => {
        if (file.size > 80_000_000)
          throw new Error(`${file.name} is ${file.size} bytes; sessions are limited to 80 MB`);
        const session = parseSession(await file.text());
        await this.replay(session);
        this.#lastSession = session;
        this.#refreshButtons();
      }),
      export: guard(async (format: "json" | "obj" | "svg" | "png") => {
        const doc = this.target.ownerDocument;
        if (format === "png") download(doc, await this.exportPng(), "pose.png");
        else if (format === "svg") download(doc, this.exportSvg(), "pose.svg", "image/svg+xml");
        else
          download(
            doc,
            this.exportMesh(format),
            `pose.${format}`,
            format === "json" ? "application/json" : "text/plain",
          );
      }),
      fit: () => this.zoom("fit"),
      help: () => this.#toggleHelp(),
      ...(this.#store ? { startOver: guard(() => this.startOver()) } : {}),
    };
  }

  #lastSession: Session | undefined;

  /** The last recorded or loaded session. */
  get lastSession(): Session | undefined {
    return this.#lastSession;
  }

  #refreshButtons(): void {
    this.#toolbar?.refresh({
      canUndo: this.#history.canUndo,
      canRedo: this.#history.canRedo,
      recording: this.#recorder.recording,
      hasSession: this.#lastSession !== undefined,
    });
  }

  /** Every field of the toolbar back to the settings in force. */
  #syncToolbar(): void {
    this.#toolbar?.sync(this.#settings);
    this.#toolbar?.showShape(undefined, this.vertexCount, this.#partsInfo());
  }

  #showError(error: unknown): void {
    const message = messageOf(error);
    if (this.#status.kind === "error" && this.#status.text === message) return;
    this.#status.error(message);
    this.#emit("akap-error", { message });
  }

  #emitPose(
    frameMs = 0,
    steps = 0,
    timings: Timings = { assembly: 0, factorisation: 0, dirichletFactorisation: 0, solve: 0, integration: 0 },
  ): void {
    const detail: PoseDetail = {
      metrics: { ...this.#metrics },
      handleCount: this.#handles.length,
      frameMs,
      steps,
      timings,
    };
    this.#emit("akap-pose", detail);
  }

  #emit(type: string, detail: unknown): void {
    this.target.dispatchEvent(new CustomEvent(type, { detail }));
  }
}

/**
 * Mounts a posing widget into `element` (it fills the element; give the element a size).
 * Resolves once the WebAssembly module is loaded and the shape is meshed. Events on
 * `element`: `akap-ready`, `akap-pose` ({@link PoseDetail}), `akap-handles`, `akap-error`.
 */
export function mount(element: HTMLElement, options: WidgetOptions = {}): Promise<Widget> {
  return Widget.create(element, options);
}

/** Deformer options of a widget method; lambda applies to the AKAP variants only. */
function methodOptions(method: Method, lambda: number): DeformerOptions {
  const options: DeformerOptions = { ...METHODS[method].options };
  if (options.method === "akap") options.lambda = lambda;
  return options;
}

/** The widget method (and lambda) that deformer options describe, e.g. a session's. */
export function widgetMethod(options: DeformerOptions, lambda: number): { method: Method; lambda: number } {
  if (options.method === "arap") return { method: "arap", lambda };
  const dirichlet = options.dirichlet ?? true;
  const integrator = options.integrator ?? "spiral";
  const found = (Object.keys(METHODS) as Method[]).find((key) => {
    const m: DeformerOptions = METHODS[key].options;
    return m.method === "akap" && m.dirichlet === dirichlet && m.integrator === integrator;
  });
  return { method: found ?? "akap", lambda: options.lambda ?? lambda };
}

/** A handle at a mesh point, not held, not selected; its target is the caller's to set. */
function newHandle(point: MeshPoint): Handle {
  return { point, target: [0, 0], selected: false, pointerId: undefined, grab: [0, 0], pending: [0, 0] };
}

function messageOf(error: unknown): string {
  return error instanceof Error ? error.message : String(error);
}

function nextFrame(): Promise<void> {
  return new Promise((resolve) => requestAnimationFrame(() => resolve()));
}

function loadImage(url: string): Promise<HTMLImageElement> {
  return new Promise((resolve, reject) => {
    const image = new Image();
    image.crossOrigin = "anonymous";
    image.onload = () => resolve(image);
    image.onerror = () => reject(new Error(`the image ${url} could not be loaded`));
    image.src = url;
  });
}
