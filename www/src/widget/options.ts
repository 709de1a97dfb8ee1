/**
 * The widget's options and the settings it runs with (defaults filled in, checked), and
 * the events it sends: what pages (and the custom element) see of the widget's
 * configuration. The methods it offers are `model/methods.ts`'s.
 */
import { limits, type Metrics, type Outline, type Timings, type WasmSource } from "../core.js";
import { METHODS, type MethodPreset } from "./model/methods.js";
import { coded } from "../internal/arrays.js";
import { DEFAULT_RIG_SPATIAL, type RigTrainOptions } from "./model/rig.js";
import { DEFAULT_FPS, checkFps } from "./animation/timeline.js";
import { BRUSH_SIZE_RANGE, DEFAULT_BRUSH, type BrushSettings } from "./model/stiffness.js";

export interface WidgetOptions {
  /**
   * Where the WebAssembly module is, for hosts that move the package's files: its URL,
   * bytes or a compiled `WebAssembly.Module`, as {@link init} takes. Default: beside the
   * package's modules (or whatever an earlier `init()` loaded).
   */
  wasm?: WasmSource;
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
  method?: MethodPreset;
  /** Weight of the soft handle constraints (default 100). */
  lambda?: number;
  /** Velocities from raw pointer displacement, as in the paper, instead of target tracking. */
  paperMode?: boolean;
  /**
   * A trained rig to pose at once, without training: an operator file (as "Save rig" or
   * `DefOp.toBytes` writes it) by URL, or its bytes. Its mesh and handles replace the
   * shape, and the method is "defop".
   */
  operator?: string | Uint8Array | ArrayBuffer;
  /** How the toolbar's Train (and {@link Widget.train} by default) trains a rig. */
  training?: RigTrainOptions;
  /**
   * Pose a trained rig on the GPU where the widget draws with WebGL2 (default true): a
   * frame computes only the rig's short frame vector on the CPU and the vertex shader forms
   * the pose; false evaluates the whole pose on the CPU each frame.
   */
  gpuRigs?: boolean;
  /** Show the regions a trained rig's training drew targets from (discs, Voronoi cells), and mark handles dragged outside them. */
  region?: boolean;
  /** Draw the ground truth's outline (ARAP or S-ARAP, solved in a worker) beside a rig's pose. */
  compare?: boolean;
  /** Show the toolbar (default true). */
  controls?: boolean;
  /** Show the heads-up display (default true). */
  hud?: boolean;
  wireframe?: boolean;
  /** Draw the last frame's velocity field as arrows. */
  field?: boolean;
  /** Highlight flipped triangles (default true). */
  flipped?: boolean;
  /**
   * What a press on the shape does: `"pose"` (the default) adds and drags handles;
   * `"stiffness"` paints stiffness with the brush (Alt-drag erases). Key B toggles;
   * `"bone"` draws bones, segments that move as one rigid body (a drag from end to end;
   * Alt-click removes one; AKAP and ARAP). Key O toggles. `"joint"` edits a puppet's
   * joints: drag one to move it, click where two parts overlap to add one, Delete removes
   * the selected one. Key J toggles.
   */
  tool?: WidgetTool;
  /** The stiffness brush: radius in CSS pixels (2 to 400, default 24) and the value painted (0.001 to 1000, default 100). */
  brush?: Partial<BrushSettings>;
  /**
   * Keep triangles from folding over (default true): a step that would flip one is split,
   * and stopped short where even small pieces would (the HUD says so).
   */
  noFoldovers?: boolean;
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
  /** Show the animation's timeline strip under the stage (default false; the app shows it). */
  timeline?: boolean;
  /** Frames per second of the animation (a whole number from 1 to 120, default 24). */
  fps?: number;
}

/** What a press on the shape does: pose with handles, paint stiffness, draw bones, or edit a puppet's joints. */
export type WidgetTool = "pose" | "stiffness" | "bone" | "joint";

/** The tools, in the order messages list them. */
export const TOOLS: readonly WidgetTool[] = ["pose", "stiffness", "bone", "joint"];

/** The settings a widget runs with (its options that can change while it runs). */
export type WidgetSettings = Required<
  Omit<
    WidgetOptions,
    "shape" | "outline" | "texture" | "src" | "gallery" | "storageKey" | "wasm" | "operator" | "brush" | "gpuRigs"
  >
> & { brush: BrushSettings };

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
  /** Milliseconds of a trained rig's evaluation, when a rig posed the frame. */
  evaluationMs?: number;
  /** A step stopped short to keep triangles from folding over (`noFoldovers`). */
  clamped: boolean;
}

export const DEFAULTS = {
  vertices: 1500,
  minAngle: 28,
  method: "akap" as MethodPreset,
  lambda: 100,
  maxStep: 0.02,
  maxSubsteps: 8,
};

/** The names of the widget's options: a misspelt one is refused, not ignored. */
export const WIDGET_OPTIONS = [
  "wasm",
  "shape",
  "outline",
  "texture",
  "src",
  "gallery",
  "vertices",
  "minAngle",
  "method",
  "lambda",
  "operator",
  "training",
  "gpuRigs",
  "region",
  "compare",
  "paperMode",
  "controls",
  "hud",
  "wireframe",
  "field",
  "flipped",
  "maxStep",
  "maxSubsteps",
  "storageKey",
  "tool",
  "brush",
  "noFoldovers",
  "timeline",
  "fps",
] as const satisfies readonly (keyof WidgetOptions)[];
// Every option of the interface is in the list (a compile-time check).
const everyOption: Record<Exclude<keyof WidgetOptions, (typeof WIDGET_OPTIONS)[number]>, never> = {};
void everyOption;

/**
 * The settings of `options`, defaults filled in; throws (code `invalid-option`) for an
 * unknown option, a method or step limits that cannot be.
 */
export function widgetSettings(options: WidgetOptions): WidgetSettings {
  const unknown = Object.keys(options).find((key) => !(WIDGET_OPTIONS as readonly string[]).includes(key));
  if (unknown !== undefined) {
    throw coded(
      new Error(`unknown widget option \`${unknown}\`; the options are ${WIDGET_OPTIONS.join(", ")}`),
      "invalid-option",
    );
  }
  const settings: WidgetSettings = {
    vertices: options.vertices ?? DEFAULTS.vertices,
    minAngle: options.minAngle ?? DEFAULTS.minAngle,
    method: options.method ?? DEFAULTS.method,
    lambda: options.lambda ?? DEFAULTS.lambda,
    training: { spatial: DEFAULT_RIG_SPATIAL, ...options.training },
    region: options.region ?? false,
    compare: options.compare ?? false,
    paperMode: options.paperMode ?? false,
    controls: options.controls ?? true,
    hud: options.hud ?? true,
    wireframe: options.wireframe ?? false,
    field: options.field ?? false,
    flipped: options.flipped ?? true,
    maxStep: options.maxStep ?? DEFAULTS.maxStep,
    maxSubsteps: options.maxSubsteps ?? DEFAULTS.maxSubsteps,
    noFoldovers: options.noFoldovers ?? true,
    tool: options.tool ?? "pose",
    brush: brushSettings(DEFAULT_BRUSH, options.brush ?? {}),
    timeline: options.timeline ?? false,
    fps: options.fps ?? DEFAULT_FPS,
  };
  try {
    checkFps(settings.fps);
  } catch (error) {
    throw coded(error as Error, "invalid-option");
  }
  checkTool(settings.tool);
  if (!Object.hasOwn(METHODS, settings.method)) {
    throw new Error(`unknown method "${settings.method}"; the methods are ${Object.keys(METHODS).join(", ")}`);
  }
  if (!(settings.maxStep > 0) || !(settings.maxSubsteps >= 1)) {
    throw new Error("maxStep must be above 0 and maxSubsteps at least 1");
  }
  return settings;
}

/**
 * `brush` over `base`, checked: a size (CSS pixels) within {@link BRUSH_SIZE_RANGE} and a
 * value within the core's stiffness range (`limits().stiffness`); throws (code `invalid-option`)
 * naming the bad one or an unknown key.
 */
export function brushSettings(base: BrushSettings, brush: Partial<BrushSettings>): BrushSettings {
  const unknown = Object.keys(brush).find((key) => key !== "size" && key !== "value");
  if (unknown !== undefined) {
    throw coded(new Error(`unknown brush option \`${unknown}\`; the options are size, value`), "invalid-option");
  }
  const next = { ...base, ...brush };
  const [low, high] = BRUSH_SIZE_RANGE;
  if (!(next.size >= low && next.size <= high)) {
    throw coded(new Error(`brush size ${next.size} is outside ${low} to ${high} pixels`), "invalid-option");
  }
  const [least, most] = limits().stiffness;
  if (!(next.value >= least && next.value <= most)) {
    throw coded(
      new Error(`brush value ${next.value} is outside the stiffness range ${least} to ${most}`),
      "invalid-option",
    );
  }
  return next;
}

/** Throws (code `invalid-option`) for a tool that is not one of {@link TOOLS}. */
export function checkTool(tool: unknown): asserts tool is WidgetTool {
  if (!TOOLS.includes(tool as WidgetTool)) {
    throw coded(new Error(`unknown tool "${String(tool)}"; the tools are ${TOOLS.join(", ")}`), "invalid-option");
  }
}
