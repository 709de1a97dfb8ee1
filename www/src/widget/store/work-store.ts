/**
 * Keeping the user's work across reloads: the shape (a built-in shape by how it was
 * triangulated, anything else as its mesh, with an imported image's texture and an SVG's
 * paths; a puppet with its parts, their art and its joints), the pose, the handles and the
 * settings, in IndexedDB under a key the page chooses. Saved a moment after each change;
 * read once when the widget starts.
 */
import type { Bone } from "../model/bones.js";
import { builtinShape, meshFromArrays, triangulate, type PuppetJoint } from "../../core.js";
import type { ImportedPuppet, VectorPath } from "../../import.js";
import type { PuppetSource } from "../model/puppet.js";
import type { ShapeSpec } from "../../session.js";
import { shapeFromMesh, type Shape } from "../model/shape.js";
import { METHODS, type MethodPreset } from "../model/methods.js";
import type { WidgetSettings } from "../options.js";
import type { HandleState, Posing } from "../model/posing.js";
import { KeyedStore } from "./database.js";

/** Settings that come back with the work: those the toolbar shows (the method as read: checked on restoring). */
export type SavedSettings = Pick<
  WidgetSettings,
  | "vertices"
  | "minAngle"
  | "lambda"
  | "wireframe"
  | "field"
  | "flipped"
  | "paperMode"
  | "noFoldovers"
  | "hud"
  | "region"
  | "compare"
  | "training"
  | "tool"
  | "brush"
> & { method: string };

export type SavedShape =
  | { kind: "builtin"; spec: ShapeSpec }
  | {
      kind: "mesh";
      name: string;
      positions: Float64Array;
      triangles: Uint32Array;
      uvs: Float32Array;
      /** An imported image, as PNG. */
      texture?: Blob;
      vector?: VectorPath[];
      /** A puppet's parts and joints (absent: one shape; work saved before puppets were kept has none). */
      puppet?: SavedPuppet;
    };

/**
 * A puppet kept with its mesh: its parts (name, triangles, depth as imported, and art) and
 * the joints its import placed; the joints and depths of the pose are the work's. An
 * image's puppet keeps the image as the shape's texture.
 */
export interface SavedPuppet {
  parts: { name: string; triangles: Uint32Array; depth: number; paths: VectorPath[] }[];
  joints: PuppetJoint[];
  /** An SVG puppet's text, for re-meshing. */
  svg?: string;
}

export interface SavedWork {
  format: "akap-work";
  version: 1;
  settings: SavedSettings;
  shape: SavedShape;
  positions: Float64Array;
  atRest: boolean;
  handles: HandleState[];
  /** Painted stiffness, one per triangle (absent: none). */
  stiffness?: Float64Array;
  /** The bones (absent: none). */
  bones?: Bone[];
  /** The animation's keys and frame rate (absent: none; work saved before animation has none). */
  animation?: SavedAnimation;
  /** A puppet's parts' depths as ordered, and its joints (absent for other shapes). */
  depths?: number[];
  joints?: PuppetJoint[];
}

/** The animation kept with the work: its frame rate, handle set and keys (each with its pose). */
export interface SavedAnimation {
  fps: number;
  handles: { triangles: number[]; barycentric: number[] };
  keys: { time: number; easing: "linear" | "ease"; targets: Float64Array; pose: Float64Array }[];
}

/** Reads and writes one saved work under `key`. Every failure is an `Error` saying why. */
export class WorkStore {
  readonly key: string;
  readonly #store = new KeyedStore("work");

  constructor(key: string) {
    this.key = key;
  }

  /** The saved work, or undefined when there is none (or it is not a work of this version). */
  async load(): Promise<SavedWork | undefined> {
    const work = (await this.#store.get(this.key)) as Partial<SavedWork> | undefined;
    return work?.format === "akap-work" && work.version === 1 ? (work as SavedWork) : undefined;
  }

  save(work: SavedWork): Promise<void> {
    return this.#store.put(this.key, work);
  }

  clear(): Promise<void> {
    return this.#store.delete(this.key);
  }
}

/** A canvas or image as a PNG blob (the texture of an imported image, to save). */
export function textureBlob(source: TexImageSource): Promise<Blob | undefined> {
  if (!(source instanceof HTMLCanvasElement)) return Promise.resolve(undefined);
  return new Promise((resolve) => source.toBlob((blob) => resolve(blob ?? undefined), "image/png"));
}

/** A saved PNG back as a canvas (the widget's textures are canvases, flipped on upload). */
export async function textureCanvas(document: Document, blob: Blob): Promise<HTMLCanvasElement> {
  const bitmap = await createImageBitmap(blob);
  const canvas = document.createElement("canvas");
  canvas.width = bitmap.width;
  canvas.height = bitmap.height;
  canvas.getContext("2d")?.drawImage(bitmap, 0, 0);
  bitmap.close();
  return canvas;
}

/**
 * The work to save: the settings, the shape (a built-in shape by its spec, anything else as
 * its mesh with `texture`, an imported image's PNG, and its vector art), pose and handles.
 */
export function savedWork(
  settings: SavedSettings,
  shape: Shape,
  pose: SavedPose,
  texture: Blob | undefined,
  animation?: SavedAnimation,
): SavedWork {
  const s = settings;
  const { mesh } = shape;
  return {
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
      noFoldovers: s.noFoldovers,
      hud: s.hud,
      region: s.region,
      compare: s.compare,
      training: { ...s.training },
      tool: s.tool,
      brush: { ...s.brush },
    },
    shape: shape.spec
      ? { kind: "builtin", spec: { ...shape.spec } }
      : {
          kind: "mesh",
          name: shape.name,
          positions: Float64Array.from(mesh.positions),
          triangles: Uint32Array.from(mesh.triangles),
          uvs: shape.uvs,
          ...(texture ? { texture } : {}),
          // A puppet's art is its parts' (drawn again into its atlas).
          ...(shape.puppet ? { puppet: savedPuppet(shape.puppet) } : shape.vector ? { vector: shape.vector } : {}),
        },
    positions: pose.positions,
    atRest: pose.atRest,
    handles: pose.handles,
    ...(pose.stiffness ? { stiffness: pose.stiffness } : {}),
    ...(pose.bones && pose.bones.length > 0 ? { bones: pose.bones } : {}),
    ...(animation ? { animation } : {}),
    ...(pose.depths ? { depths: [...pose.depths] } : {}),
    ...(pose.joints ? { joints: pose.joints.map((j) => ({ point: [...j.point], parts: [...j.parts] })) } : {}),
  };
}

function savedPuppet(puppet: NonNullable<Shape["puppet"]>): SavedPuppet {
  return {
    parts: puppet.parts.map((p) => ({
      name: p.name,
      triangles: Uint32Array.from(p.triangles),
      depth: p.depth,
      paths: p.paths,
    })),
    joints: puppet.joints.map((j) => ({ point: [...j.point], parts: [...j.parts] })),
    ...(puppet.source?.kind === "svg" ? { svg: puppet.source.text } : {}),
  };
}

/** The texture worth saving with a shape: an imported image's (vector art is drawn again). */
export function savedTexture(shape: Shape): TexImageSource | undefined {
  return !shape.spec && !shape.vector ? shape.texture : undefined;
}

/** How saved art becomes a shape's drawing (the page's, in `shapes/`). */
export interface SavedArt {
  /** Draws vector art as the shape's texture. */
  paint(shape: Shape, vector: VectorPath[]): void;
  /** A puppet's shape: its parts' art in an atlas, or an image's (`texture`) pixels. */
  puppet(imported: ImportedPuppet, name: string, source: PuppetSource | undefined, texture?: TexImageSource): Shape;
}

/**
 * The shape of saved work, rebuilt: a built-in shape triangulated as it was, or the saved
 * mesh (validated again) with its texture, its vector art drawn by `art`, and a puppet made
 * again from its parts and joints.
 */
export async function savedShape(document: Document, kept: SavedShape, art: SavedArt): Promise<Shape> {
  if (kept.kind === "builtin") {
    const { spec } = kept;
    const mesh = triangulate(builtinShape(spec.name), {
      targetEdgeLength: spec.targetEdgeLength,
      minAngle: spec.minAngle,
    });
    return shapeFromMesh(mesh, { ...spec });
  }
  const mesh = meshFromArrays(kept.positions, kept.triangles);
  const texture = kept.texture && (await textureCanvas(document, kept.texture));
  if (kept.puppet) {
    const { parts, joints, svg } = kept.puppet;
    const imported = { positions: mesh.positions, triangles: mesh.triangles, parts, joints, skipped: [] };
    // An image's puppet: its pixels again from the saved image (re-meshing traces them).
    const source: PuppetSource | undefined = texture
      ? { kind: "image", ...imagePixels(texture) }
      : svg === undefined
        ? undefined
        : { kind: "svg", text: svg };
    return art.puppet(imported, kept.name, source, texture);
  }
  const shape = shapeFromMesh(mesh, undefined, kept.uvs, kept.name);
  if (texture) shape.texture = texture;
  if (kept.vector) art.paint(shape, kept.vector);
  return shape;
}

/** A canvas's pixels (RGBA, rows from the top) and size. */
function imagePixels(canvas: HTMLCanvasElement): { rgba: Uint8ClampedArray; width: number; height: number } {
  const ctx = canvas.getContext("2d", { willReadFrequently: true });
  if (!ctx) throw new Error("this browser cannot read image pixels");
  const { width, height } = canvas;
  return { rgba: ctx.getImageData(0, 0, width, height).data, width, height };
}

/** What is kept: read when a save is due. */
export interface WorkSource {
  settings: SavedSettings;
  shape: Shape;
  pose(): SavedPose;
  /** The animation, when it has keys. */
  animation?(): SavedAnimation | undefined;
}

/** The pose part of the work: positions, handles, painted stiffness, bones, and a puppet's depths and joints. */
export type SavedPose = Pick<
  SavedWork,
  "positions" | "atRest" | "handles" | "stiffness" | "bones" | "depths" | "joints"
>;

/**
 * Puts `saved` back over the shape installed in `posing`: its settings, its shape (made by
 * `shape`), pose and handles; throws, with the posing and settings as they were, if it
 * cannot.
 */
export async function restoreWork(
  saved: SavedWork,
  posing: Posing,
  settings: WidgetSettings,
  shape: (saved: SavedShape) => Promise<Shape>,
): Promise<void> {
  const restored = await shape(saved.shape);
  const method = saved.settings.method;
  if (!Object.hasOwn(METHODS, method)) throw new Error(`unknown method ${method}`);
  const before = { snapshot: posing.snapshot(), settings: { ...settings } };
  try {
    // Work saved before the brush existed has no brush settings: the current ones stay.
    Object.assign(settings, saved.settings);
    settings.brush = { ...(saved.settings.brush ?? before.settings.brush) };
    settings.tool = saved.settings.tool ?? before.settings.tool;
    posing.install(restored);
    posing.restore({
      ...saved,
      shape: restored,
      parts: undefined,
      method: method as MethodPreset,
      lambda: saved.settings.lambda,
    });
  } catch (error) {
    Object.assign(settings, before.settings);
    posing.restore(before.snapshot);
    throw error;
  }
}

/**
 * Saves the work a moment after the last change (a change only asks; the save comes
 * `delay` ms after the last ask), encoding an imported image's texture once per shape.
 */
export class WorkKeeper {
  readonly store: WorkStore;
  readonly #source: () => WorkSource | undefined;
  readonly #failed: (error: unknown) => void;
  readonly #textures = new WeakMap<Shape, Promise<Blob | undefined>>();
  #timer: ReturnType<typeof setTimeout> | undefined;

  constructor(store: WorkStore, source: () => WorkSource | undefined, failed: (error: unknown) => void) {
    this.store = store;
    this.#source = source;
    this.#failed = failed;
  }

  /** Something changed: save soon. */
  changed(delay = 400): void {
    clearTimeout(this.#timer);
    this.#timer = setTimeout(() => this.#save().catch(this.#failed), delay);
  }

  /** No more saves (the widget is going away). */
  stop(): void {
    clearTimeout(this.#timer);
  }

  async #save(): Promise<void> {
    const work = this.#source();
    if (!work) return;
    const source = savedTexture(work.shape);
    let texture: Promise<Blob | undefined> | undefined;
    if (source) {
      texture = this.#textures.get(work.shape) ?? textureBlob(source);
      this.#textures.set(work.shape, texture);
    }
    await this.store.save(savedWork(work.settings, work.shape, work.pose(), await texture, work.animation?.()));
  }
}
