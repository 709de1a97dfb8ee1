/**
 * The posing widget: a shape drawn with WebGL2 (an image warps with it), handles added by
 * clicking anywhere on the shape, dragged with mouse, pen or several fingers, pins that
 * stay, undo and redo per gesture, recorded sessions that replay bit for bit, exports, a
 * heads-up display, a view that zooms and pans, help, the work kept across reloads, and
 * trained rigs (DefOp) that pose in closed form, trained in workers or opened from files.
 * {@link mount} puts one into any element; several on one page are independent (all state
 * lives in the instance, the DOM in a shadow root).
 *
 * The {@link Widget} class is a facade: it makes the parts (the model, the stage, the
 * managers, the toolbar and input), its commands perform the registry's actions
 * (`actions/`), which the toolbar, the keys and the help panel read too, and its getters
 * read the model. What is posed (shape, deformer, handles, history, recording, the steps
 * of a frame) is {@link Posing}'s.
 */
import {
  builtinShape,
  builtinShapes,
  init,
  type Deformer,
  type MeshData,
  type Metrics,
  type Outline,
} from "../core.js";
import type { TrainProgress } from "../defop-pool.js";
import type { Session } from "../session.js";
import type { Action } from "./actions/action.js";
import * as animation from "./actions/animation.js";
import type { WidgetParts } from "./actions/context.js";
import * as display from "./actions/display.js";
import * as exporting from "./actions/export.js";
import * as handles from "./actions/handles.js";
import { setMethod } from "./actions/method.js";
import * as rig from "./actions/rig.js";
import * as sessions from "./actions/session.js";
import * as shape from "./actions/shape.js";
import * as tools from "./actions/tools.js";
import { AnimationController, type AnimationExport } from "./animation/controller.js";
import type { AnimationExportFormat, AnimationExportOptions, SpriteSheet } from "./animation/formats.js";
import type { KeyInfo } from "./animation/playback.js";
import type { Easing } from "./animation/timeline.js";
import { HelpPanel } from "./chrome/help-panel.js";
import { buildToolbar, type Toolbar } from "./chrome/toolbar.js";
import { PointerState } from "./input/pointer-state.js";
import { WidgetInput } from "./input/widget-input.js";
import { METHODS, type MethodPreset } from "./model/methods.js";
import { Posing } from "./model/posing.js";
import type { PuppetJoint, RigGpuLayout } from "../core.js";
import { meshOutline, type Shape } from "./model/shape.js";
import type { BrushSettings } from "./model/stiffness.js";
import { widgetSettings, type WidgetOptions, type WidgetSettings, type WidgetTool } from "./options.js";
import { RigManager, type RigInfo, type WidgetTrainOptions } from "./rigs/rig-manager.js";
import { loadImage } from "./shapes/shape-files.js";
import { ShapeLoader } from "./shapes/shape-loader.js";
import { WorkKeeper, WorkStore, type SavedWork } from "./store/work-store.js";
import { defaultTexture } from "./view/default-texture.js";
import { FrameLoop } from "./view/frame-loop.js";
import type { View } from "./view/projection.js";
import { COMPACT_WIDTH, Stage, widgetShell } from "./view/stage.js";
import { messageOf } from "./view/status-line.js";

export { METHODS, type MethodPreset } from "./model/methods.js";
export type { GalleryItem, PoseDetail, WidgetOptions, WidgetTool } from "./options.js";
export type { BrushSettings } from "./model/stiffness.js";
export type { RigInfo, WidgetTrainOptions } from "./rigs/rig-manager.js";
export type { AnimationExport } from "./animation/controller.js";
export type { AnimationExportOptions, AnimationExportFormat, SpriteSheet } from "./animation/formats.js";
export type { KeyInfo } from "./animation/playback.js";
export type { Easing } from "./animation/timeline.js";

export class Widget {
  /** The element the widget was mounted into; events are dispatched on it. */
  readonly target: HTMLElement;
  readonly #host: HTMLElement;
  readonly #root: HTMLElement;
  readonly #stage: Stage;
  readonly #help: HelpPanel;
  readonly #toolbar: Toolbar | undefined;
  readonly #resizeObserver: ResizeObserver;
  readonly #settings: WidgetSettings;
  readonly #posing: Posing;
  readonly #rigs: RigManager;
  readonly #keeper: WorkKeeper | undefined;
  #baseTexture: TexImageSource | undefined;
  #input: WidgetInput | undefined;
  #destroyed = false;
  readonly #pointer: PointerState;
  readonly #frames: FrameLoop;
  readonly #loader: ShapeLoader;
  readonly #animation: AnimationController;
  /** The widget's parts as its actions and managers see them. */
  readonly #parts: WidgetParts;

  private constructor(target: HTMLElement, options: WidgetOptions) {
    this.target = target;
    const gallery = options.gallery ?? [];
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
                  animation: () => this.#animation.saved(),
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

    this.#stage = new Stage(document);
    this.#posing.rigsOnGpu = (options.gpuRigs ?? true) && this.#stage.renderer.kind === "webgl2";
    this.#help = new HelpPanel(document, () => this.#toggleHelp(false));
    this.#stage.element.append(this.#help.element);
    // The widget's parts as its actions and managers see them: read when used (some are set below).
    // eslint-disable-next-line @typescript-eslint/no-this-alias
    const widget = this;
    let lastSession: Session | undefined;
    const parts: WidgetParts = {
      target,
      document,
      gallery,
      get root() {
        return widget.#root;
      },
      get settings() {
        return widget.#settings;
      },
      get posing() {
        return widget.#posing;
      },
      get stage() {
        return widget.#stage;
      },
      get frames() {
        return widget.#frames;
      },
      get loader() {
        return widget.#loader;
      },
      get rigs() {
        return widget.#rigs;
      },
      get animation() {
        return widget.#animation;
      },
      get toolbar() {
        return widget.#toolbar;
      },
      get keeper() {
        return widget.#keeper;
      },
      get lastSession() {
        return lastSession;
      },
      set lastSession(session) {
        lastSession = session;
      },
      gesture: (change) => this.#gesture(change),
      draw: () => this.#draw(),
      render: () => this.#render(),
      destroyed: () => this.#destroyed,
      showError: (error) => this.#showError(error),
      emit: (type, detail) => this.#emit(type, detail),
      refreshButtons: () => this.#refreshButtons(),
      syncToolbar: () => this.#syncToolbar(),
      rigChanged: () => this.#rigChanged(),
      toggleHelp: (open) => this.#toggleHelp(open),
      helpOpen: () => this.#help.open,
      showHud: (visible) => {
        this.#settings.hud = visible;
        this.#stage.hud.element.classList.toggle("hidden", !visible);
      },
    };
    this.#parts = parts;
    this.#frames = new FrameLoop({
      get posing() {
        return widget.#posing;
      },
      stage: this.#stage,
      settings: this.#settings,
      root: this.#root,
      destroyed: () => this.#destroyed,
      render: () => this.#render(),
      showError: (error) => this.#showError(error),
      emit: (type, detail) => this.#emit(type, detail),
      rigPosed: () => {
        this.#rigs.comparison = undefined;
        this.#rigs.compareSoon();
      },
    });
    this.#loader = new ShapeLoader({
      get posing() {
        return widget.#posing;
      },
      stage: this.#stage,
      settings: this.#settings,
      document,
      fileAdded: (option) => this.#toolbar?.addShape(option),
      destroyed: () => this.#destroyed,
      gesture: (change) => this.#gesture(change),
    });
    this.#rigs = new RigManager({
      posing: this.#posing,
      indicator: this.#stage.training,
      changed: () => this.#rigChanged(),
      info: (message) => this.#stage.status.info(message),
    });
    this.#stage.hud.element.classList.toggle("hidden", !this.#settings.hud);

    if (this.#settings.controls) {
      const syncAfter = (): void => this.#syncToolbar();
      this.#toolbar = buildToolbar(
        document,
        (action, args) => action.perform(parts, args),
        { settings: this.#settings, gallery, keepsWork: this.#keeper !== undefined },
        {
          failed: (error) => {
            this.#showError(error);
            syncAfter();
          },
          cancelled: (message) => {
            this.#stage.status.info(message);
            syncAfter();
          },
          succeeded: () => this.#stage.status.succeeded(),
        },
      );
      this.#root.append(this.#toolbar.element);
      this.#stage.element.insertBefore(this.#toolbar.brushPanel, this.#help.element);
    }
    this.#root.append(this.#stage.element);
    this.#animation = new AnimationController({
      get posing() {
        return widget.#posing;
      },
      stage: this.#stage,
      settings: this.#settings,
      document,
      poseChanged: () => this.#frames.poseChanged(),
      emit: (type, detail) => this.#emit(type, detail),
      showError: (error) => this.#showError(error),
      keep: () => this.#keeper?.changed(),
    });
    if (this.#animation.strip) this.#root.append(this.#animation.strip.element);
    this.#root.dataset.renderer = this.#stage.renderer.kind;

    this.#pointer = new PointerState({ settings: this.#settings, posing: this.#posing, draw: () => this.#draw() });
    this.#input = new WidgetInput({
      posing: this.#posing,
      settings: this.#settings,
      camera: this.#stage.camera,
      root: this.#root,
      overlay: this.#stage.overlay,
      pointer: this.#pointer,
      ratio: () => this.#stage.ratio,
      devicePixel: (x, y) => this.#stage.devicePixel(x, y),
      draw: () => this.#draw(),
      moved: () => this.#frames.moved(),
      succeeded: () => this.#stage.status.succeeded(),
      failed: (error) => this.#showError(error),
      perform: (action, args) => {
        try {
          const result = action.perform(parts, args);
          if (result instanceof Promise) result.catch((error: unknown) => this.#showError(error));
        } catch (error) {
          this.#showError(error);
        }
      },
    });
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

  /** Carries out one of the registry's actions on the widget's parts. */
  #perform<A, R>(action: Action<A, R>, args: A): R {
    return action.perform(this.#parts, args);
  }

  // ---------------------------------------------------------------- the model, read

  /** Vertices of the rest mesh. */
  get vertexCount(): number {
    return this.#posing.shape.mesh.vertexCount;
  }

  /** Triangles of the rest mesh. */
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

  /** How many handles there are. */
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

  /** Whether there is an undone gesture to redo. */
  get canRedo(): boolean {
    return this.#posing.history.canRedo;
  }

  // ---------------------------------------------------------------- handles and the pose

  /** Adds a handle at the shape point (x, y) (shape units). Returns its index, or -1 off the shape. */
  addHandleAt(x: number, y: number): number {
    return this.#perform(handles.addHandle, { x, y });
  }

  /** Removes a handle by index. */
  removeHandle(index: number): void {
    this.#perform(handles.removeHandle, { index });
  }

  /** Removes every handle (the pose stays). */
  clearHandles(): void {
    this.#perform(handles.clearHandles, undefined);
  }

  /** Back to the rest pose; handles stay, at their rest places. */
  reset(): void {
    this.#perform(handles.reset, undefined);
  }

  /** Undoes the last gesture; false when there is none. */
  undo(): boolean {
    return this.#perform(handles.undo, undefined);
  }

  /** Redoes the gesture undone last; false when there is none. */
  redo(): boolean {
    return this.#perform(handles.redo, undefined);
  }

  /** Changes the method and/or lambda. */
  setMethod(method: MethodPreset, lambda = this.#settings.lambda): void {
    this.#perform(setMethod, { method, lambda });
  }

  // ---------------------------------------------------------------- view, messages, shapes

  /** Zooms the view by `factor` about its centre, or fits the pose on screen into it (`"fit"`). */
  zoom(factor: number | "fit"): void {
    this.#perform(display.zoom, { factor });
  }

  /** Shows a message in the status line until the next action that succeeds. */
  showMessage(message: string, kind: "info" | "error" = "info"): void {
    this.#perform(display.showMessage, { message, kind });
  }

  /**
   * Switches to a built-in shape, or re-meshes the current one with about `vertices`
   * vertices (meshed in a worker; see {@link remesh}). Undoable; the handles of another
   * shape are dropped.
   */
  async setShape(name: string | undefined, vertices = this.#settings.vertices): Promise<void> {
    await this.#perform(shape.setShape, { name, vertices });
  }

  /** Shows a custom outline instead (triangulated to about `vertices` vertices). Undoable. */
  async setOutline(outline: Outline, vertices = this.#settings.vertices): Promise<void> {
    await this.#perform(shape.setOutline, { outline, vertices });
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
    await this.#perform(shape.open, { file, name });
  }

  /** Loads a shape file by URL (see {@link loadFile}). */
  async loadUrl(url: string): Promise<void> {
    await this.#perform(shape.loadUrl, { url });
  }

  /** Shows another separate part of the last imported file (0 is the largest). Undoable. */
  async choosePart(index: number): Promise<void> {
    await this.#perform(shape.choosePart, { index });
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
    await this.#perform(shape.remesh, { vertices, minAngle });
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
    this.#perform(display.display, options);
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
    await this.#perform(rig.train, { options, onProgress });
  }

  /** Stops the training under way (its promise rejects with an `AbortError`). */
  cancelTraining(): void {
    this.#perform(rig.cancelTraining, undefined);
  }

  /** The trained rig's state. */
  get rig(): RigInfo {
    return this.#rigs.info();
  }

  /**
   * For tests and diagnostics: the pose of a rig on the GPU as its vertex shader forms it
   * from the rig's last frame (read back by transform feedback, single precision), with
   * what the shader read (the layout, the basis texture, the frame) and whether the last
   * picture was drawn from that frame; `undefined` when no rig poses on the GPU.
   */
  rigGpuReadback():
    | { positions: Float32Array; layout: RigGpuLayout; texture: Float32Array; frame: Float32Array; drawn: boolean }
    | undefined {
    return this.#stage.rigGpuReadback(this.#posing);
  }

  /**
   * The rig's operator file (operator, mesh and the training's settings), as "Save rig"
   * downloads it; `precision: "single"` stores the coefficients as 32-bit floats (about
   * half the size).
   */
  rigFile(options: { precision?: "double" | "single" } = {}): Uint8Array {
    return this.#perform(rig.rigFile, options);
  }

  /**
   * Opens a rig: an operator file by URL, as a file or as bytes. Its mesh becomes the shape
   * with its handles at rest and the method "defop": it poses at once. One undoable step;
   * a file that is not a valid rig throws (code `import`), changing nothing.
   */
  async loadRig(source: string | Blob | Uint8Array | ArrayBuffer): Promise<void> {
    await this.#perform(shape.loadRig, { source });
  }

  // ---------------------------------------------------------------- sessions

  /** Whether a recording runs. */
  get recording(): boolean {
    return this.#posing.recording;
  }

  /** Starts recording every change of the deformer. */
  startRecording(): void {
    this.#perform(sessions.record, { on: true });
  }

  /** Stops recording and returns the session (which Replay and Save then offer). */
  stopRecording(): Session | undefined {
    return this.#perform(sessions.record, { on: false });
  }

  /**
   * Loads a recorded session from a file (up to `limits().sessionBytes`, 80 MB), read and
   * checked by the core, and replays it (see {@link replay}).
   */
  async loadSession(file: Blob): Promise<void> {
    await this.#perform(sessions.loadSession, { file });
  }

  /** The last recorded or loaded session. */
  get lastSession(): Session | undefined {
    return this.#parts.lastSession;
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
    return (await this.#perform(sessions.replay, { session, stepsPerFrame }))!;
  }

  // ---------------------------------------------------------------- exports

  /**
   * The current pose as JSON (`positions`, `triangles`, `uvs`, `stiffness` if painted) or
   * OBJ text; triangles back to front when parts are in depth order.
   */
  exportMesh(format: "json" | "obj"): string {
    return this.#perform(exporting.exportMesh, { format });
  }

  /** The pose as an SVG document: an imported SVG's own paths moved with the mesh, else the outline. */
  exportSvg(): string {
    return this.#perform(exporting.exportSvg, undefined);
  }

  /** The rendered image (the shape and its outline, no handles) as a PNG. */
  exportPng(): Promise<Blob> {
    return this.#perform(exporting.exportPng, undefined);
  }

  // ---------------------------------------------------------------- depth order

  /**
   * Brings the selected handles' parts in front of every other part (each part of the
   * shape belongs to its nearest handle); they stay there when dragged. On a puppet, the
   * parts the selected handles are on move one step in front of the next part. Undoable;
   * false when nothing moved.
   */
  bringForward(): boolean {
    return this.#perform(handles.layer, { step: 1 });
  }

  /** Sends the selected handles' parts behind every other part (on a puppet, one step back; see {@link bringForward}). */
  sendBack(): boolean {
    return this.#perform(handles.layer, { step: -1 });
  }

  /** Each handle's layer, in handle order (higher is in front). */
  handleLayers(): number[] {
    return this.#posing.handles.map((h) => h.layer);
  }

  // ---------------------------------------------------------------- puppets (docs/app.md, "Puppets")

  /**
   * A puppet's parts (an SVG of several layers loads as one): each part's name, its
   * triangles (indices into {@link mesh}'s) and its depth now (larger is in front; the
   * Forward and Back buttons change it). Empty for other shapes.
   */
  get parts(): { name: string; triangles: Uint32Array; depth: number }[] {
    const { puppet } = this.#posing.shape;
    const depths = this.#posing.depths;
    return (puppet?.parts ?? []).map((p, k) => ({
      name: p.name,
      triangles: p.triangles,
      depth: depths?.[k] ?? p.depth,
    }));
  }

  /**
   * A puppet's joints (copies): each a rest point and the two parts it joins, `[front,
   * back]`. Empty for other shapes.
   */
  get joints(): PuppetJoint[] {
    return this.#posing.joints;
  }

  /**
   * Replaces a puppet's joints, as the joint tool does (one undoable step). Throws (code
   * `invalid-joint`), changing nothing, for a part out of range or a point not on both
   * parts.
   */
  setJoints(joints: readonly PuppetJoint[]): void {
    this.#perform(tools.setJoints, { joints });
  }

  /** Removes a puppet's joint `index` (undoable); throws (code `invalid-argument`) for no such joint. */
  removeJoint(index: number): void {
    this.#perform(tools.removeJoint, { index });
  }

  // ---------------------------------------------------------------- tools: stiffness and bones

  /** What a press on the shape does: pose, paint stiffness with the brush, draw bones, or edit a puppet's joints. */
  get tool(): WidgetTool {
    return this.#settings.tool;
  }

  /** The brush's size (CSS pixels) and the value it paints. */
  get brush(): BrushSettings {
    return { ...this.#settings.brush };
  }

  /**
   * Chooses the tool (`"pose"`, `"stiffness"`: the brush, `"bone"`: drawing bones,
   * `"joint"`: a puppet's joints) and/or changes the brush; throws (code `invalid-option`),
   * changing nothing, for an unknown tool or a brush out of range.
   */
  setTool(tool: WidgetTool, brush: Partial<BrushSettings> = {}): void {
    this.#perform(tools.setTool, { tool, brush });
  }

  /** Each triangle's painted stiffness (a copy), or undefined when none is painted. */
  stiffness(): Float64Array | undefined {
    return exporting.paintedStiffness(this.#parts);
  }

  /**
   * Paints every triangle (one value per triangle, 0.001 to 1000; undefined for none), as
   * one undoable step; throws, changing nothing, for bad values. Used by AKAP and ARAP; kept
   * (and shown) under the other methods.
   */
  setStiffness(values: ArrayLike<number> | undefined): void {
    this.#perform(tools.setStiffness, { values });
  }

  /**
   * One dab of the brush at the shape point (x, y) in the pose on screen, as a stroke of
   * one point: `value` (default the brush's) on the triangles whose centroids lie within
   * `radius` shape units (default the brush's size on screen). Undoable.
   */
  paintAt(x: number, y: number, value = this.#settings.brush.value, radius?: number): void {
    this.#perform(tools.paintAt, { x, y, value, radius });
  }

  /**
   * Adds a bone from (x0, y0) to (x1, y1), points of the shape in the pose on screen: the
   * triangles its segment meets move as one rigid body from now on (AKAP and ARAP). Returns
   * its index; undoable. Throws (code `invalid-argument`), changing nothing, for an end off
   * the shape, a segment that leaves it, a bone touching another (leave a joint of free
   * triangles between them), or a method without bones.
   */
  addBone(x0: number, y0: number, x1: number, y1: number): number {
    return this.#perform(tools.addBone, { x0, y0, x1, y1 });
  }

  /** The bones' ends in the current pose: x0 y0 x1 y1 per bone. */
  bones(): Float64Array {
    return tools.currentBoneEnds(this.#parts);
  }

  /** Removes bone `index` (undoable); throws (code `invalid-argument`) for no such bone. */
  removeBone(index: number): void {
    this.#perform(tools.removeBone, { index });
  }

  /** Removes every bone (undoable). */
  clearBones(): void {
    this.#perform(tools.removeBone, { index: "all" });
  }

  // ---------------------------------------------------------------- animation (docs/app.md, "Animation")

  /** Captures the pose as a key at `time` s (default: the playhead); returns its index. */
  captureKey(time?: number, easing?: Easing): number {
    return this.#perform(animation.captureKey, { time, easing });
  }

  /** The keys in time order: time, easing of the segment into it, the handles' targets. */
  keys(): KeyInfo[] {
    return this.#animation.animator.keys();
  }

  /** Moves key `index` to `time` s (not onto another key); returns its new index. */
  moveKey(index: number, time: number): number {
    return this.#perform(animation.moveKey, { index, time });
  }

  /** Deletes key `index`. */
  deleteKey(index: number): void {
    this.#perform(animation.deleteKey, { index });
  }

  /** The easing of the segment that ends at key `index`: "linear" or "ease" (smoothstep). */
  setKeyEasing(index: number, easing: Easing): void {
    this.#perform(animation.setKeyEasing, { index, easing });
  }

  /** Plays from the playhead (`loop`: again and again); resolves when playback stops. */
  play(options: { loop?: boolean } = {}): Promise<void> {
    return this.#perform(animation.play, options);
  }

  /** Stops playback; the pose stays at the frame on screen (undoable). */
  pause(): void {
    this.#perform(animation.pause, undefined);
  }

  /** Shows the frame at `time` s (one undoable step); {@link playhead} is then `time`. */
  seek(time: number): void {
    this.#perform(animation.seek, { time });
  }

  /** The playhead's time, seconds (on the frame grid). */
  get playhead(): number {
    return this.#animation.animator.time;
  }

  /** Every frame's vertex positions (copies), one per 1/fps from 0 to the last key. */
  animationFrames(): Float64Array[] {
    return this.#animation.animator.positions();
  }

  /**
   * The animation as a file (see docs/app.md, "Animation"): "webm", "gif", "apng", "json" and
   * "svg" (a zip) give a Blob, "sprites" a PNG and its JSON table; rejects with an
   * `AbortError` on `signal`'s abort.
   */
  exportAnimation(format: "sprites", options?: AnimationExportOptions): Promise<SpriteSheet>;
  exportAnimation(format: Exclude<AnimationExportFormat, "sprites">, options?: AnimationExportOptions): Promise<Blob>;
  exportAnimation(format: AnimationExportFormat, options?: AnimationExportOptions): Promise<AnimationExport>;
  exportAnimation(format: AnimationExportFormat, options: AnimationExportOptions = {}): Promise<AnimationExport> {
    return this.#perform(animation.exportAnimation, { format, options });
  }

  // ---------------------------------------------------------------- the widget

  /**
   * Forgets the saved work and starts again: the default shape at its default density, at
   * rest, without handles or animation keys, with the default method and display. Undoable
   * (the keys excepted).
   */
  async startOver(): Promise<void> {
    await this.#perform(shape.startOver, undefined);
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
    this.#animation.destroy();
    this.#input?.destroy();
    this.#resizeObserver.disconnect();
    this.#stage.destroy();
    this.#loader.destroy();
    this.#keeper?.stop();
    this.#rigs.destroy();
    this.#rigs.adopt(undefined);
    (this.#posing.deformer as Deformer | undefined)?.free();
    this.#host.remove();
  }

  // ---------------------------------------------------------------- what the parts are told

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

  /** Puts back saved work (over the shape just installed); throws, changing nothing, if it cannot. */
  async #resume(saved: SavedWork): Promise<void> {
    await this.#loader.resume(saved);
    // A rig from the cache with it.
    if (this.#settings.method === "defop") await this.#rigs.fromCache(this.#settings.training).catch(() => false);
    try {
      if (saved.animation) this.#animation.restore(saved.animation);
    } catch (error) {
      this.#stage.status.info(`The animation's keys could not be restored (${messageOf(error)}).`);
    }
    this.#stage.hud.element.classList.toggle("hidden", !this.#settings.hud);
    this.#syncToolbar();
  }

  /** The rig's state changed (or the handles, shape or method): HUD, toolbar, picture. */
  #rigChanged(): void {
    if (!(this.#rigs as RigManager | undefined)) return;
    this.#stage.hud.showRig(this.#rigs.statusLine());
    this.#toolbar?.showRig({ hasRig: this.#posing.rig !== undefined, training: this.#rigs.training });
    this.#draw();
  }

  /** Runs one complete gesture (an undoable unit) that is not a drag. */
  #gesture(change: () => void): void {
    this.#posing.gesture(change);
    this.#stage.status.succeeded();
  }

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
      ghost: this.#rigs.comparison?.positions,
      brushAt: this.#pointer.at,
      boneDraft: this.#pointer.boneDraft,
      jointDraft: this.#pointer.jointDraft,
      touch: this.#pointer.touch,
    });
    this.#root.dataset.frame = String(Number(this.#root.dataset.frame ?? 0) + 1);
    this.#keeper?.changed();
  }

  #toggleHelp(open = !this.#help.open): void {
    this.#help.open = open;
    if (!open) this.#root.focus({ preventScroll: true });
  }

  #refreshButtons(): void {
    this.#toolbar?.refresh({
      canUndo: this.#posing.history.canUndo,
      canRedo: this.#posing.history.canRedo,
      recording: this.#posing.recording,
      hasSession: this.#parts.lastSession !== undefined,
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
