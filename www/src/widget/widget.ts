/**
 * The posing widget: a shape drawn with WebGL2 (an image warps with it), handles added by
 * clicking anywhere on the shape, dragged with mouse, pen or several fingers, pins that
 * stay, undo and redo per gesture, recorded sessions that replay bit for bit, exports, a
 * heads-up display, a view that zooms and pans, help, the work kept across reloads, and
 * trained rigs (DefOp) that pose in closed form, trained in workers or opened from files.
 * {@link mount} puts one into any element; several on one page are independent (all state
 * lives in the instance, the DOM in a shadow root).
 *
 * This file is the page side: the DOM, drawing, input, files, messages. What is posed
 * (shape, deformer, handles, history, recording, the steps of a frame) is {@link Posing}'s.
 */
import {
  builtinShape,
  builtinShapes,
  init,
  limits,
  type Deformer,
  type MeshData,
  type Metrics,
  type Outline,
} from "../core.js";
import { posedMesh, posedSvg } from "./store/pose-export.js";
import { FrameLoop, type FrameHost } from "./view/frame-loop.js";
import { ShapeLoader, replaySession, type LoaderHost } from "./shapes/shape-loader.js";

import { METHODS, type MethodPreset } from "./model/methods.js";
import { widgetSettings, type GalleryItem, type WidgetOptions, type WidgetSettings } from "./options.js";
import { WorkKeeper, WorkStore, type SavedWork } from "./store/work-store.js";
import { locate } from "./model/picking.js";
import { WidgetInput, inputHost } from "./input/widget-input.js";
import { Posing } from "./model/posing.js";
import { Rigging, type RigInfo, type WidgetTrainOptions } from "./rigs/rig-manager.js";
import type { TrainProgress } from "../defop-pool.js";
import { parseSession, type Session } from "../session.js";
import { widgetToolbar } from "./actions/toolbar-actions.js";
import { meshOutline, type Shape } from "./model/shape.js";
import { fetchFile, fileKind, fileLimits, loadImage } from "./shapes/shape-files.js";
import { messageOf } from "./view/status-line.js";
import { COMPACT_WIDTH, Stage, widgetShell } from "./view/stage.js";
import { defaultTexture } from "./view/default-texture.js";
import { Brush, type BrushHost } from "./input/tool-state.js";
import { WidgetTools, type ToolParts } from "./tools-api.js";
import { Animating, type AnimatingHost, type AnimationExport } from "./animation/controller.js";
import type { AnimationExportOptions, AnimationExportFormat, SpriteSheet } from "./animation/formats.js";
import type { KeyInfo } from "./animation/playback.js";
import type { Easing } from "./animation/timeline.js";
import type { Toolbar } from "./chrome/toolbar.js";
import type { View } from "./view/projection.js";

export { METHODS, type MethodPreset } from "./model/methods.js";
export type { GalleryItem, PoseDetail, WidgetOptions, WidgetTool } from "./options.js";
export type { BrushSettings } from "./model/stiffness.js";
export type { RigInfo, WidgetTrainOptions } from "./rigs/rig-manager.js";
export type { AnimationExport } from "./animation/controller.js";
export type { AnimationExportOptions, AnimationExportFormat, SpriteSheet } from "./animation/formats.js";
export type { KeyInfo } from "./animation/playback.js";
export type { Easing } from "./animation/timeline.js";

/** What the widget's helpers see of it. */
type WidgetParts = FrameHost & LoaderHost & BrushHost & AnimatingHost;

export class Widget extends WidgetTools {
  /** The element the widget was mounted into; events are dispatched on it. */
  readonly target: HTMLElement;
  readonly #host: HTMLElement;
  readonly #root: HTMLElement;
  readonly #stage: Stage;
  readonly #toolbar: Toolbar | undefined;
  readonly #resizeObserver: ResizeObserver;
  readonly #settings: WidgetSettings;
  readonly #posing: Posing;
  readonly #rigging: Rigging;
  readonly #keeper: WorkKeeper | undefined;
  readonly #gallery: readonly GalleryItem[];
  #baseTexture: TexImageSource | undefined;
  #lastSession: Session | undefined;
  #input: WidgetInput | undefined;
  #destroyed = false;
  readonly #brush: Brush;
  readonly #frames: FrameLoop;
  readonly #loader: ShapeLoader;
  readonly #animating: Animating;
  /** The widget's parts as its helpers see them. */
  readonly #parts: WidgetParts;
  readonly #tools: ToolParts;

  private constructor(target: HTMLElement, options: WidgetOptions) {
    super();
    this.target = target;
    this.#gallery = options.gallery ?? [];
    this.#settings = widgetSettings(options);
    this.#keeper = options.storageKey
      ? new WorkKeeper(
          new WorkStore(options.storageKey),
          () =>
            this.#destroyed || this.#posing.replaying
              ? undefined
              : {
                  settings: this.#settings,
                  shape: this.#posing.shape,
                  pose: () => this.#posing.snapshot(),
                  animation: () => this.#animating.saved(),
                },
          (error) => this.#stage.status.info(`Your work cannot be kept in this browser: ${messageOf(error)}`),
        )
      : undefined;
    this.#posing = new Posing(this.#settings, {
      adopted: (shape, deformer, refit) => this.#adopted(shape, deformer, refit),
      methodChanged: (method) => {
        this.#toolbar?.sync(this.#settings);
        this.#stage.hud.showMethod(METHODS[method].label);
        this.#rigChanged();
      },
      handlesChanged: (count) => {
        this.#emit("akap-handles", { count });
        this.#rigChanged();
      },
      poseChanged: () => this.#frames.poseChanged(),
      historyChanged: () => this.#refreshButtons(),
      schedule: () => this.#frames.schedule(),
    });
    const document = target.ownerDocument;
    ({ host: this.#host, root: this.#root } = widgetShell(document));

    this.#stage = new Stage(document, () => this.#toggleHelp(false));
    // The widget's parts as its helpers see them: read when used (some are set below).
    // eslint-disable-next-line @typescript-eslint/no-this-alias
    const widget = this;
    const parts: WidgetParts = {
      get posing() {
        return widget.#posing;
      },
      get stage() {
        return widget.#stage;
      },
      get settings() {
        return widget.#settings;
      },
      get rigging() {
        return widget.#rigging;
      },
      get root() {
        return widget.#root;
      },
      get toolbar() {
        return widget.#toolbar;
      },
      document,
      destroyed: () => this.#destroyed,
      render: () => this.#render(),
      draw: () => this.#draw(),
      showError: (error) => this.#showError(error),
      emit: (type, detail) => this.#emit(type, detail),
      gesture: (change) => this.#gesture(change),
      poseChanged: () => this.#frames.poseChanged(),
      keep: () => this.#keeper?.changed(),
    };
    this.#parts = parts;
    this.#frames = new FrameLoop(parts);
    this.#loader = new ShapeLoader(parts);
    this.#rigging = new Rigging({
      posing: this.#posing,
      indicator: this.#stage.training,
      changed: () => this.#rigChanged(),
      info: (message) => this.#stage.status.info(message),
    });
    this.#stage.hud.element.classList.toggle("hidden", !this.#settings.hud);

    if (this.#settings.controls) {
      this.#toolbar = widgetToolbar(document, this, this.#settings, {
        gallery: this.#gallery,
        showFile: (index) => this.#loader.show(this.#loader.files[index]!, 0),
        keepsWork: this.#keeper !== undefined,
        failed: (error) => {
          this.#showError(error);
          this.#syncToolbar();
        },
        cancelled: (message) => {
          this.#stage.status.info(message);
          this.#syncToolbar();
        },
        succeeded: () => this.#stage.status.succeeded(),
        showHud: (visible) => {
          this.#settings.hud = visible;
          this.#stage.hud.element.classList.toggle("hidden", !visible);
        },
        help: () => this.#toggleHelp(),
      });
      this.#root.append(this.#toolbar.element);
      this.#stage.element.insertBefore(this.#toolbar.brushPanel, this.#stage.help.element);
    }
    this.#root.append(this.#stage.element);
    this.#animating = new Animating(parts);
    if (this.#animating.strip) this.#root.append(this.#animating.strip.element);
    this.#root.dataset.renderer = this.#stage.renderer.kind;

    this.#brush = new Brush(parts);
    this.#tools = {
      posing: this.#posing,
      brush: this.#brush,
      settings: this.#settings,
      gesture: (change) => this.#gesture(change),
      info: (message) => this.#stage.status.info(message),
    };
    this.#input = new WidgetInput(
      inputHost(this, parts, {
        moved: () => this.#frames.moved(),
        brush: this.#brush,
        help: (open) => this.#toggleHelp(open),
        animate: (what) => this.#animating.key(what),
      }),
    );
    this.#resizeObserver = new ResizeObserver(() => this.#resize());
    target.append(this.#host);
  }

  /** Creates a widget inside `target` (see {@link mount}). */
  static async create(target: HTMLElement, options: WidgetOptions = {}): Promise<Widget> {
    await init(options.wasm);
    const widget = new Widget(target, options);
    const posing = widget.#posing;
    try {
      const name = options.outline ? undefined : (options.shape ?? builtinShapes()[0]!);
      const outline = options.outline ?? builtinShape(name!);
      widget.#baseTexture = options.texture ? await loadImage(options.texture) : defaultTexture();
      const chosen = [options.src, options.shape, options.outline, options.operator].some((o) => o !== undefined);
      const saved = chosen ? undefined : await widget.#keeper?.store.load().catch(() => undefined);
      if (options.operator !== undefined) await widget.loadRig(options.operator);
      else if (options.src) await widget.loadUrl(options.src);
      else posing.install(meshOutline(outline, name, widget.#settings.vertices, widget.#settings.minAngle));
      if (saved) {
        await widget.#resume(saved).catch((error: unknown) => {
          widget.#stage.status.info(`The saved work could not be restored (${messageOf(error)}); starting afresh.`);
        });
      }
      posing.history.clear();
    } catch (error) {
      widget.destroy();
      throw error;
    }
    widget.#resizeObserver.observe(widget.#stage.glCanvas);
    widget.#resize();
    widget.#emit("akap-ready", { vertexCount: widget.vertexCount, triangleCount: widget.triangleCount });
    return widget;
  }

  // ---------------------------------------------------------------- public API (and tools-api.ts)

  protected get tools(): ToolParts {
    return this.#tools;
  }

  get vertexCount(): number {
    return this.#posing.shape.mesh.vertexCount;
  }

  get triangleCount(): number {
    return this.#posing.shape.mesh.triangleCount;
  }

  /** The rest mesh. */
  get mesh(): MeshData {
    return this.#posing.shape.mesh;
  }

  /** The method in use and lambda. */
  get method(): { method: MethodPreset; lambda: number } {
    return { method: this.#settings.method, lambda: this.#settings.lambda };
  }

  /** How shape units map to device pixels of the canvas, and the device pixel ratio. */
  get view(): View & { pixelRatio: number } {
    return { ...this.#stage.camera.view, pixelRatio: this.#stage.ratio };
  }

  /** Which renderer draws the mesh: "webgl2", or "2d" where WebGL2 is missing. */
  get renderer(): "webgl2" | "2d" {
    return this.#stage.renderer.kind;
  }

  /** The current positions (a copy), xy-interleaved. */
  positions(): Float64Array {
    return this.#posing.deformer.positions();
  }

  /** Current handle positions (xy-interleaved). */
  handlePositions(): Float64Array {
    return this.#posing.deformer.handlePositions();
  }

  get handleCount(): number {
    return this.#posing.handles.length;
  }

  /** Distortion of the pose on screen. */
  get metrics(): Metrics {
    return { ...this.#frames.metrics };
  }

  /** Undo and redo as the buttons offer them. */
  get canUndo(): boolean {
    return this.#posing.history.canUndo;
  }

  get canRedo(): boolean {
    return this.#posing.history.canRedo;
  }

  /** Adds a handle at the shape point (x, y) (shape units). Returns its index, or -1 off the shape. */
  addHandleAt(x: number, y: number): number {
    const posing = this.#posing;
    const point = locate(posing.deformer.positionsView(), posing.shape.mesh.triangles, x, y);
    if (!point) return -1;
    this.#gesture(() => posing.addHandle(point));
    return posing.handles.length - 1;
  }

  /** Removes a handle by index. */
  removeHandle(index: number): void {
    const posing = this.#posing;
    if (!(index >= 0 && index < posing.handles.length)) throw new RangeError(`there is no handle ${index}`);
    this.#gesture(() => {
      posing.handles.splice(index, 1);
      posing.applyHandles();
    });
  }

  /** Removes every handle (the pose stays). */
  clearHandles(): void {
    if (this.#posing.handles.length === 0) return;
    this.#gesture(() => {
      this.#posing.handles = [];
      this.#posing.applyHandles();
    });
  }

  /** Back to the rest pose; handles stay, at their rest places. */
  reset(): void {
    this.#gesture(() => this.#posing.reset());
  }

  undo(): boolean {
    return this.#travel(false);
  }

  redo(): boolean {
    return this.#travel(true);
  }

  /** Changes the method and/or lambda. */
  setMethod(method: MethodPreset, lambda = this.#settings.lambda): void {
    this.#posing.setMethod(method, lambda);
  }

  // ---------------------------------------------------------------- view, messages, shapes

  /** Zooms the view by `factor` about its centre, or fits the pose on screen into it (`"fit"`). */
  zoom(factor: number | "fit"): void {
    if (factor === "fit") this.#stage.camera.fit(this.#posing.deformer.positionsView());
    else this.#stage.camera.zoom(this.#stage.glCanvas.width / 2, this.#stage.glCanvas.height / 2, factor);
    this.#draw();
  }

  /** Shows a message in the status line until the next action that succeeds. */
  showMessage(message: string, kind: "info" | "error" = "info"): void {
    if (kind === "error") this.#showError(new Error(message));
    else this.#stage.status.info(message);
  }

  /**
   * Switches to a built-in shape, or re-meshes the current one with about `vertices`
   * vertices (meshed in a worker; see {@link remesh}). Undoable; the handles of another
   * shape are dropped.
   */
  async setShape(name: string | undefined, vertices = this.#settings.vertices): Promise<void> {
    await this.#loader.setShape(name, vertices);
  }

  /** Shows a custom outline instead (triangulated to about `vertices` vertices). Undoable. */
  async setOutline(outline: Outline, vertices = this.#settings.vertices): Promise<void> {
    await this.#loader.setOutline(outline, vertices);
  }

  /**
   * Loads a shape from a file: an SVG document (its filled shapes, in their colours), an
   * image (the shape where it is opaque, or where it differs from the background; the image
   * warps with it), a mesh (OBJ or our JSON), a recorded session (JSON), which is
   * replayed, or a trained rig (`.defop`, see {@link loadRig}). Files with several separate parts show the largest; {@link choosePart} picks
   * another. Throws (and changes nothing) for files it cannot use; a load is one undoable
   * step.
   */
  async loadFile(file: Blob, name = (file as File).name ?? "file"): Promise<void> {
    if (/\.defop$/i.test(name)) return this.loadRig(file);
    if (fileKind(name, file.type) === "json" && file.size <= fileLimits().bytes) {
      const text = await file.text();
      if (/"format"\s*:\s*"akap-session"/.test(text)) return this.loadSession(file);
    }
    await this.#loader.open(file, name);
  }

  /** Loads a shape file by URL (see {@link loadFile}). */
  async loadUrl(url: string): Promise<void> {
    const response = await fetchFile(url);
    const name = decodeURIComponent(new URL(url, this.target.ownerDocument.baseURI).pathname.split("/").pop() ?? url);
    await this.loadFile(await response.blob(), name);
  }

  /** Shows another separate part of the last imported file (0 is the largest). Undoable. */
  async choosePart(index: number): Promise<void> {
    await this.#loader.choosePart(index);
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
    await this.#loader.remesh(vertices, minAngle);
  }

  /**
   * Display options, and `paperMode` and `noFoldovers` of posing; `region` and `compare`
   * concern a trained rig (see {@link WidgetOptions}).
   */
  setDisplay(
    options: Partial<
      Pick<WidgetSettings, "wireframe" | "field" | "flipped" | "paperMode" | "noFoldovers" | "region" | "compare">
    >,
  ): void {
    Object.assign(this.#settings, options);
    if (options.field) this.#frames.lastField = this.#posing.deformer.field();
    if (options.compare) this.#rigging.compareSoon();
    this.#rigChanged();
  }

  // ---------------------------------------------------------------- trained rigs

  /**
   * Trains a rig (a DefOp operator) for the shape and the handles as they are now, on a
   * pool of workers (posing goes on meanwhile, with any method) or from the browser's cache
   * when the same training was done before; `onProgress` hears its progress, which the
   * widget also shows with a Cancel button. Options default to the widget's `training`
   * option. The rig poses while the method is "defop" and the shape and handles are the
   * ones it was trained for; resolves once it is in place. Rejects, changing nothing, when
   * there are no handles, on `options.signal`'s abort or Cancel (an `AbortError`), or when a
   * worker fails.
   */
  async train(options: WidgetTrainOptions = {}, onProgress?: (progress: TrainProgress) => void): Promise<void> {
    const rig = await this.#rigging.train({ ...this.#settings.training, ...options }, onProgress);
    // The options of the rig in use: saved with the work, so a reload finds it in the cache.
    this.#settings.training = { ...rig.options };
    this.#toolbar?.sync(this.#settings);
  }

  /** Stops the training under way (its promise rejects with an `AbortError`). */
  cancelTraining(): void {
    this.#rigging.cancel();
  }

  /** The trained rig's state. */
  get rig(): RigInfo {
    return this.#rigging.info();
  }

  /** The rig's operator file (operator and mesh), as "Save rig" downloads it. */
  rigFile(): Uint8Array {
    const rig = this.#posing.rig;
    if (!rig) throw new Error("there is no trained rig to save; Train one first");
    return rig.toBytes();
  }

  /**
   * Opens a rig: an operator file by URL, as a file or as bytes. Its mesh becomes the shape
   * with its handles at rest and the method "defop": it poses at once. One undoable step;
   * a file that is not a valid rig throws (code `import`), changing nothing.
   */
  async loadRig(source: string | Blob | Uint8Array | ArrayBuffer): Promise<void> {
    await this.#rigging.open(source, (change) => this.#gesture(change));
  }

  /** The rig's state changed (or the handles, shape or method): HUD, toolbar, picture. */
  #rigChanged(): void {
    if (!(this.#rigging as Rigging | undefined)) return;
    this.#stage.hud.showRig(this.#rigging.statusLine());
    this.#toolbar?.showRig({ hasRig: this.#posing.rig !== undefined, training: this.#rigging.training });
    this.#draw();
  }

  get recording(): boolean {
    return this.#posing.recorder.recording;
  }

  /** Starts recording every change of the deformer. */
  startRecording(): void {
    this.#posing.startRecording();
  }

  /** Stops recording and returns the session (which Replay and Save then offer). */
  stopRecording(): Session | undefined {
    const session = this.#posing.stopRecording();
    if (session) this.#lastSession = session;
    this.#refreshButtons();
    return session;
  }

  /**
   * Loads a recorded session from a file (up to `limits().sessionBytes`, 80 MB), read and
   * checked by the core, and replays it (see {@link replay}).
   */
  async loadSession(file: Blob): Promise<void> {
    const most = limits().sessionBytes;
    if (file.size > most) throw new Error(`the session is ${file.size} bytes; sessions are limited to ${most}`);
    const session = parseSession(await file.text());
    await this.replay(session);
    this.#lastSession = session;
    this.#refreshButtons();
  }

  /** The last recorded or loaded session. */
  get lastSession(): Session | undefined {
    return this.#lastSession;
  }

  /**
   * Replays a session (read by {@link parseSession}, or JSON text): rebuilds its mesh if
   * needed (in the core), then, from the rest pose without handles and with the session's
   * options, repeats its calls as the core's `session::replay` does, drawing every
   * `stepsPerFrame` steps. Resolves with the final positions.
   * The result is bit-for-bit the pose the recording ended in, with the session's method;
   * the whole replay is one undoable step, and a session that fails partway leaves
   * everything as it was before.
   */
  async replay(session: Session | string, stepsPerFrame = 4): Promise<Float64Array> {
    const s = typeof session === "string" ? parseSession(session) : session;
    await replaySession(this.#parts, s, stepsPerFrame);
    this.#refreshButtons();
    this.#frames.poseChanged();
    return this.#posing.deformer.positions();
  }

  /**
   * The current pose as JSON (`positions`, `triangles`, `uvs`, `stiffness` if painted) or
   * OBJ text; triangles back to front when parts are in depth order.
   */
  exportMesh(format: "json" | "obj"): string {
    const layers = this.#stage.layering(this.#posing);
    return posedMesh(this.#posing.shape, this.#posing.deformer.positions(), format, {
      stiffness: this.stiffness(),
      layers,
    });
  }

  /** The pose as an SVG document: an imported SVG's own paths moved with the mesh, else the outline. */
  exportSvg(): string {
    const { deformer, shape } = this.#posing;
    return posedSvg(shape.mesh, shape.vector, deformer.positions(), this.#stage.layering(this.#posing));
  }

  /** The rendered image (the shape and its outline, no handles) as a PNG. */
  exportPng(): Promise<Blob> {
    return this.#stage.png(this.#posing, this.#settings);
  }

  // ---------------------------------------------------------------- animation (README "Animation")

  /** Captures the pose as a key at `time` s (default: the playhead); returns its index. */
  captureKey(time?: number, easing?: Easing): number {
    return this.#animating.capture(time, easing);
  }

  /** The keys in time order: time, easing of the segment into it, the handles' targets. */
  keys(): KeyInfo[] {
    return this.#animating.animator.keys();
  }

  /** Moves key `index` to `time` s (not onto another key); returns its new index. */
  moveKey(index: number, time: number): number {
    return this.#animating.animator.moveKey(index, time);
  }

  deleteKey(index: number): void {
    this.#animating.animator.deleteKey(index);
  }

  /** The easing of the segment that ends at key `index`: "linear" or "ease" (smoothstep). */
  setKeyEasing(index: number, easing: Easing): void {
    this.#animating.animator.setEasing(index, easing);
  }

  /** Plays from the playhead (`loop`: again and again); resolves when playback stops. */
  play(options: { loop?: boolean } = {}): Promise<void> {
    return this.#animating.animator.play(options);
  }

  /** Stops playback; the pose stays at the frame on screen (undoable). */
  pause(): void {
    this.#animating.animator.pause();
  }

  /** Shows the frame at `time` s (one undoable step); {@link playhead} is then `time`. */
  seek(time: number): void {
    this.#animating.animator.seek(time);
  }

  /** The playhead's time, seconds (on the frame grid). */
  get playhead(): number {
    return this.#animating.animator.time;
  }

  /** Every frame's vertex positions (copies), one per 1/fps from 0 to the last key. */
  animationFrames(): Float64Array[] {
    return this.#animating.animator.positions();
  }

  /**
   * The animation as a file (see README "Animation"): "webm", "gif", "apng", "json" and
   * "svg" (a zip) give a Blob, "sprites" a PNG and its JSON table; rejects with an
   * `AbortError` on `signal`'s abort.
   */
  exportAnimation(format: "sprites", options?: AnimationExportOptions): Promise<SpriteSheet>;
  exportAnimation(format: Exclude<AnimationExportFormat, "sprites">, options?: AnimationExportOptions): Promise<Blob>;
  exportAnimation(format: AnimationExportFormat, options?: AnimationExportOptions): Promise<AnimationExport>;
  exportAnimation(format: AnimationExportFormat, options: AnimationExportOptions = {}): Promise<AnimationExport> {
    return this.#animating.export(format, options);
  }

  /**
   * Forgets the saved work and starts again: the default shape at its default density, at
   * rest, without handles or animation keys, with the default method and display. Undoable
   * (the keys excepted).
   */
  async startOver(): Promise<void> {
    await this.#keeper?.store.clear();
    this.#animating.animator.clear();
    this.#loader.startOver();
    this.#syncToolbar();
  }

  /** Resolves when no frame is pending (the pose has settled and nothing is dragged). */
  whenIdle(): Promise<void> {
    return this.#frames.whenIdle();
  }

  /** Removes the widget from the page and frees its WebAssembly memory. */
  destroy(): void {
    if (this.#destroyed) return;
    this.#destroyed = true;
    this.#frames.stop();
    this.#animating.destroy();
    this.#input?.destroy();
    this.#resizeObserver.disconnect();
    this.#stage.destroy();
    this.#loader.destroy();
    this.#keeper?.stop();
    this.#rigging.destroy();
    this.#rigging.adopt(undefined);
    (this.#posing.deformer as Deformer | undefined)?.free();
    this.#host.remove();
  }

  // ---------------------------------------------------------------- shapes

  /** A new shape or deformer is in place: renderer, lists, HUD (and the view, if asked). */
  #adopted(shape: Shape, deformer: Deformer, refit: boolean): void {
    this.#frames.lastField = undefined;
    this.#stage.renderer.setMesh(shape.mesh.triangles, shape.edges, shape.uvs);
    this.#stage.meshSet();
    const texture = shape.texture ?? this.#baseTexture;
    if (texture) this.#stage.renderer.setTexture(texture);
    if (refit) this.#stage.camera.reset(shape.mesh.positions, this.#stage.glCanvas.width, this.#stage.glCanvas.height);
    const file = this.#loader.files.findIndex((f) => f === this.#posing.parts?.loaded);
    this.#toolbar?.showShape(
      shape.spec ? `builtin:${shape.spec.name}` : file >= 0 ? `file:${file}` : undefined,
      shape.mesh.vertexCount,
      this.#posing.partsInfo,
    );
    const label = METHODS[this.#settings.method].label;
    this.#stage.hud.showMesh(shape.mesh.vertexCount, shape.mesh.triangleCount, label, deformer.metrics());
    this.#refreshButtons();
  }

  // ---------------------------------------------------------------- keeping the work

  /** Puts back saved work (over the shape just installed); throws, changing nothing, if it cannot. */
  async #resume(saved: SavedWork): Promise<void> {
    await this.#loader.resume(saved);
    try {
      if (saved.animation) this.#animating.restore(saved.animation);
    } catch (error) {
      this.#stage.status.info(`The animation's keys could not be restored (${messageOf(error)}).`);
    }
    this.#stage.hud.element.classList.toggle("hidden", !this.#settings.hud);
    this.#syncToolbar();
  }

  // ---------------------------------------------------------------- gestures

  /** Undo or redo; a success clears the messages. */
  #travel(forward: boolean): boolean {
    const moved = this.#posing.travel(forward);
    if (moved) this.#stage.status.succeeded();
    return moved;
  }

  /** Runs one complete gesture (an undoable unit) that is not a drag. */
  #gesture(change: () => void): void {
    this.#posing.gesture(change);
    this.#stage.status.succeeded();
  }

  // ---------------------------------------------------------------- drawing and the view

  #resize(): void {
    if (this.#destroyed) return;
    const width = this.#stage.resize(this.#posing.shape.mesh.positions);
    this.#root.classList.toggle("compact", width < COMPACT_WIDTH);
    this.#draw();
  }

  /** Asks for the picture to be drawn anew in the next animation frame (once, however often asked). */
  #draw(): void {
    this.#frames.schedule();
  }

  /** Draws the picture now. */
  #render(): void {
    if (this.#destroyed) return;
    this.#stage.render(this.#posing, this.#settings, {
      field: this.#frames.lastField,
      ghost: this.#rigging.comparison?.positions,
      brushAt: this.#brush.at,
      boneDraft: this.#brush.boneDraft,
      touch: this.#brush.touch,
    });
    this.#root.dataset.frame = String(Number(this.#root.dataset.frame ?? 0) + 1);
    this.#keeper?.changed();
  }

  // ---------------------------------------------------------------- input

  #toggleHelp(open = !this.#stage.help.open): void {
    this.#stage.help.open = open;
    if (!open) this.#root.focus({ preventScroll: true });
  }

  // ---------------------------------------------------------------- toolbar, events, errors

  #refreshButtons(): void {
    this.#toolbar?.refresh({
      canUndo: this.#posing.history.canUndo,
      canRedo: this.#posing.history.canRedo,
      recording: this.#posing.recorder.recording,
      hasSession: this.#lastSession !== undefined,
    });
  }

  /** Every field of the toolbar back to the settings in force. */
  #syncToolbar(): void {
    this.#toolbar?.sync(this.#settings);
    this.#toolbar?.showShape(undefined, this.vertexCount, this.#posing.partsInfo);
  }

  #showError(error: unknown): void {
    const message = messageOf(error);
    if (this.#stage.status.kind === "error" && this.#stage.status.text === message) return;
    this.#stage.status.error(message);
    this.#emit("akap-error", { message });
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
