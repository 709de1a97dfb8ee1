/**
 * Shapes into the widget: built-in shapes and outlines meshed in the set-up worker (with
 * the busy indicator and Cancel), files made shapes (an imported file's parts, one at a
 * time), re-meshing that carries the pose over; each an undoable step. The page side of
 * `shape-maker.ts`, `shape-files.ts` and `model/shape.ts`.
 */
import { builtinShape, builtinShapes, type Outline } from "../../core.js";
import { DEFAULTS, type WidgetSettings } from "../options.js";
import { restoreWork, savedShape, type SavedWork } from "../store/work-store.js";
import type { Parts, Posing } from "../model/posing.js";
import { oneShapeNote, type PuppetSource } from "../model/puppet.js";
import type { ImportedPuppet } from "../../import.js";
import { Cancelled, ShapeMaker, makeShown, type Prepared, type SetupRequest } from "./shape-maker.js";
import { meshOutline, shapeFromMesh, type Loaded } from "../model/shape.js";
import { importPuppetSource, paintVector, partShape, puppetShape, readShapeFile } from "./shape-files.js";
import type { Stage } from "../view/stage.js";

/** What the loader needs of the widget. */
export interface LoaderHost {
  readonly settings: WidgetSettings;
  readonly posing: Posing;
  readonly stage: Stage;
  /** A file was opened: the toolbar's shape list offers it from now on. */
  fileAdded(option: { value: string; label: string }): void;
  readonly document: Document;
  destroyed(): boolean;
  /** Runs one undoable change. */
  gesture(change: () => void): void;
}

export class ShapeLoader {
  /** Files opened so far, offered again in the shape list as `file:index`. */
  readonly files: Loaded[] = [];
  readonly #maker = new ShapeMaker();
  readonly #host: LoaderHost;

  constructor(host: LoaderHost) {
    this.#host = host;
  }

  /** See `Widget.setShape`. */
  async setShape(name: string | undefined, vertices: number): Promise<void> {
    const { posing, settings } = this.#host;
    const spec = name ?? posing.shape.spec?.name;
    if (!spec) throw new Error("this widget shows a custom outline; give a built-in shape name");
    builtinShape(spec); // an unknown name fails here, before any work
    const prepared = await this.make({ name: spec, outline: undefined, label: spec, vertices });
    this.#host.gesture(() => {
      settings.vertices = vertices;
      posing.parts = undefined;
      posing.install(prepared.shape, prepared.orders);
    });
  }

  /**
   * See `Widget.startOver`: the default shape at its default density, at rest, without
   * handles, with the default method and display; undoable.
   */
  startOver(): void {
    const { posing, settings } = this.#host;
    const name = builtinShapes()[0]!;
    const shape = meshOutline(builtinShape(name), name, DEFAULTS.vertices, DEFAULTS.minAngle);
    this.#host.gesture(() => {
      Object.assign(settings, { vertices: DEFAULTS.vertices, minAngle: DEFAULTS.minAngle });
      Object.assign(settings, { wireframe: false, field: false, flipped: true, paperMode: false, tool: "pose" });
      posing.showMethod(DEFAULTS.method, DEFAULTS.lambda);
      posing.parts = undefined;
      posing.install(shape);
    });
  }

  /** Saved work put back over the shape installed; throws, changing nothing, if it cannot. */
  async resume(saved: SavedWork): Promise<void> {
    const { document, posing, settings } = this.#host;
    await restoreWork(saved, posing, settings, (shape) =>
      savedShape(document, shape, {
        paint: (s, v) => paintVector(document, s, v),
        puppet: (imported, name, source, texture) => puppetShape(document, imported, name, source, texture),
      }),
    );
  }

  /** See `Widget.setOutline`. */
  async setOutline(outline: Outline, vertices: number): Promise<void> {
    const prepared = await this.make({ name: undefined, outline, label: "custom shape", vertices });
    this.#host.gesture(() => {
      this.#host.posing.parts = undefined;
      this.#host.posing.install(prepared.shape, prepared.orders);
    });
  }

  /** A shape file (not a session or rig) read and shown, and offered in the shape list. */
  async open(file: Blob, name: string): Promise<void> {
    const loaded = await readShapeFile(file, name, this.#host.settings.vertices);
    if (loaded.kind === "outlines" && loaded.parts.length === 0) throw new Error(`${name}: no shape found`);
    await this.show(loaded, 0);
    this.files.push(loaded);
    this.#host.fileAdded({ value: `file:${this.files.length - 1}`, label: loaded.name });
  }

  /** See `Widget.choosePart`. */
  async choosePart(index: number): Promise<void> {
    const parts = this.#host.posing.parts;
    if (!parts || !(index >= 0 && index < parts.loaded.parts.length)) {
      throw new RangeError(`there is no part ${index} to choose`);
    }
    await this.show(parts.loaded, index);
  }

  /** See `Widget.remesh`. */
  async remesh(vertices: number, minAngle: number): Promise<void> {
    const { posing, settings } = this.#host;
    const { parts, shape } = posing;
    if (!parts && !shape.spec && !shape.puppet) throw new Error("this shape came as a mesh; it cannot be re-meshed");
    const previous = { vertices: settings.vertices, minAngle: settings.minAngle };
    Object.assign(settings, { vertices, minAngle });
    let prepared: Prepared;
    try {
      prepared = shape.puppet
        ? this.#puppet(shape.puppet.source, shape.name, vertices, undefined, shape.texture)
        : parts
          ? await this.#partShape(parts.loaded, parts.index)
          : await this.make({ name: shape.spec!.name, outline: undefined, label: shape.spec!.name, vertices });
    } catch (error) {
      Object.assign(settings, previous);
      throw error;
    }
    this.#host.gesture(() => posing.carryOver(prepared.shape, prepared.orders));
  }

  /**
   * Meshes an outline and orders the deformer's systems, in a worker, while the busy
   * indicator shows the stage and offers Cancel; rejects with `Cancelled` when cancelled
   * or replaced by a newer request.
   */
  async make(request: Pick<SetupRequest, "name" | "outline" | "label" | "vertices">): Promise<Prepared> {
    const { posing, settings, stage } = this.#host;
    const full = { minAngle: settings.minAngle, ...request, options: posing.deformerOptions() };
    const prepared = await makeShown(this.#maker, stage.busy, full, () => posing.deformerOptions().method);
    if (this.#host.destroyed()) throw new Cancelled();
    return prepared;
  }

  /** Makes a loaded file (part `index` of it) the shape, as one undoable step. */
  async show(loaded: Loaded, index: number): Promise<void> {
    const { posing, stage } = this.#host;
    const prepared =
      loaded.kind === "mesh"
        ? { shape: shapeFromMesh(loaded.mesh, undefined, loaded.uvs, loaded.name), orders: undefined }
        : loaded.kind === "puppet"
          ? this.#puppet(loaded.source, loaded.name, this.#host.settings.vertices, loaded.imported, loaded.texture)
          : await this.#partShape(loaded, index);
    this.#host.gesture(() => {
      posing.parts = loaded.kind === "outlines" ? { loaded, index } : undefined;
      posing.install(prepared.shape, prepared.orders);
      if (loaded.kind === "mesh" && loaded.stiffness) posing.setStiffness(loaded.stiffness);
    });
    const puppet = posing.shape.puppet;
    if (puppet) {
      const names = puppet.parts.map((p) => p.name).join(", ");
      const joints = puppet.joints.length;
      stage.status.info(
        `${loaded.name} is a puppet of ${puppet.parts.length} parts (${names}) with ${joints} joint${joints === 1 ? "" : "s"}; ` +
          "every part is posed at once (the Joint tool moves, adds and removes joints)" +
          (oneShapeNote(this.#host.settings.method) ? `. ${oneShapeNote(this.#host.settings.method)}` : ""),
      );
    } else if (loaded.kind === "outlines" && loaded.parts.length > 1) {
      stage.status.info(
        `${loaded.name} has ${loaded.parts.length} separate parts; showing part ${index + 1} (the parts are ordered by size)`,
      );
    }
  }

  destroy(): void {
    this.#maker.destroy();
  }

  /**
   * A puppet's shape from its source (an SVG's text, an image's pixels, with `texture` the
   * image) at about `vertices` vertices (`imported`: the import already made at that
   * count). Meshed on the page: the deformer orders its own systems, which the joints
   * couple.
   */
  #puppet(
    source: PuppetSource | undefined,
    name: string,
    vertices: number,
    imported?: ImportedPuppet,
    texture?: TexImageSource,
  ): Prepared {
    if (!source)
      throw new Error(`${name} came from a session or saved work without its file: open the file to re-mesh it`);
    const made = imported ?? importPuppetSource(source, vertices);
    if (made.parts.length < 2) {
      throw new Error(`${name} no longer has several ${source.kind === "svg" ? "layers" : "regions"}`);
    }
    return { shape: puppetShape(this.#host.document, made, name, source, texture), orders: undefined };
  }

  #partShape(loaded: Parts["loaded"], index: number): Promise<Prepared> {
    const { vertices } = this.#host.settings;
    return partShape(this.#host.document, loaded, index, (outline, label) =>
      this.make({ name: undefined, outline, label, vertices }),
    );
  }
}
