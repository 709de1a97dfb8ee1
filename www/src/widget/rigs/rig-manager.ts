/**
 * The widget's trained rigs: training one for the shape and handles in a pool of workers
 * (`trainDefOp`) while posing goes on, with the stage's training indicator (stage, samples
 * done of total, time so far and left, Cancel); the browser cache (a training asked for
 * again, or after a reload, is read back, not repeated); rig files in and out; and the
 * comparison with the ground truth, solved in a worker after the pose settles.
 */
import { solveGroundTruth, trainDefOp, type TrainProgress } from "../../defop-pool.js";
import { coded } from "../../internal/arrays.js";
import { newHandle, type Posing } from "../model/posing.js";
import { shapeFromMesh } from "../model/shape.js";
import { Rig, rigKey, spatialFor, type RigTrainOptions } from "../model/rig.js";
import { RigCache } from "./rig-cache.js";
import { fetchFile } from "../shapes/shape-files.js";
import type { BusyIndicator } from "../view/busy-indicator.js";

/** {@link Widget.train}'s options: the training's, and how it runs. */
export interface WidgetTrainOptions extends RigTrainOptions {
  /** Stops the training (the promise rejects with the signal's reason; nothing changes). */
  signal?: AbortSignal;
  /** Workers (default one per spare core); 0 trains on the page's thread in slices. */
  workers?: number;
  /** Use a rig cached for the same mesh, handles and options (default true). */
  cache?: boolean;
}

/** The widget's trained rig, as {@link Widget.rig} tells it. */
export interface RigInfo {
  /** `"none"`: no rig; `"ready"`: it fits the shape and handles; `"stale"`: they changed since. */
  state: "none" | "ready" | "stale";
  /** Where it came from: trained here, the browser's cache, or a file. */
  source: "trained" | "cache" | "file" | undefined;
  /** Whether a training is under way. */
  training: boolean;
  /** Whether it poses now (the method is "defop" and it is ready). */
  posing: boolean;
  /** The training's sampling radius (shape units; a rig file keeps it). */
  radius: number | undefined;
  /** The energy Compare solves the ground truth with: the rig's own (a rig file keeps it). */
  energy: "sarap" | "arap" | undefined;
  /** Where its training drew the targets (a rig file keeps it; discs for files before version 4). */
  sampling: "disc" | "voronoi" | "mixed" | undefined;
  /** Largest vertex distance between the rig's pose and the ground truth, as a fraction of the shape's size, once compared. */
  comparison: number | undefined;
}

/** What the rig manager tells the widget. */
export interface RigManagerHost {
  readonly posing: Posing;
  readonly indicator: BusyIndicator;
  /** The rig, its state or its comparison changed: HUD, toolbar, a frame. */
  changed(): void;
  /** A message for the status line. */
  info(message: string): void;
}

/** The ground truth drawn beside a rig's pose, and how far the two are apart. */
export interface Comparison {
  positions: Float64Array;
  /** Largest distance between a vertex's two positions, as a fraction of the shape's size. */
  distance: number;
  iterations: number;
}

/** Milliseconds the pose must rest before its ground truth is solved. */
const COMPARE_DELAY_MS = 150;

export class RigManager {
  readonly #host: RigManagerHost;
  readonly #cache = new RigCache();
  #training: AbortController | undefined;
  #comparing: AbortController | undefined;
  #compareTimer: ReturnType<typeof setTimeout> | undefined;
  comparison: Comparison | undefined;
  /** The last training's progress while it runs. */
  progress: TrainProgress | undefined;

  constructor(host: RigManagerHost) {
    this.#host = host;
  }

  get rig(): Rig | undefined {
    return this.#host.posing.rig;
  }

  get training(): boolean {
    return this.#training !== undefined;
  }

  /** See `Widget.loadRig`: the rig's mesh and handles at rest, the method "defop"; `gesture` makes it one undoable step. */
  async open(source: string | Blob | Uint8Array | ArrayBuffer, gesture: (change: () => void) => void): Promise<void> {
    const rig = Rig.fromBytes(await rigBytes(source));
    const shape = shapeFromMesh(rig.mesh, undefined, undefined, "rig");
    const rest = rig.restHandles();
    const posing = this.#host.posing;
    gesture(() => {
      posing.parts = undefined;
      posing.install(shape);
      posing.handles = rig.points.map((point) =>
        newHandle({ triangle: point.triangle, barycentric: [...point.barycentric] as [number, number, number] }),
      );
      posing.applyHandles();
      posing.deformer.setTargets(rest);
      posing.showMethod("defop", posing.settings.lambda);
      this.adopt(rig);
    });
  }

  /** Makes `rig` the widget's rig (the old one is freed). */
  adopt(rig: Rig | undefined): void {
    const posing = this.#host.posing;
    if (posing.rig !== rig) posing.rig?.free();
    posing.rig = rig;
    this.comparison = undefined;
    this.#host.changed();
  }

  /**
   * Trains a rig for the shape and handles as they are now (or reads it from the cache)
   * and adopts it. Rejects, changing nothing, when there are no handles, a training is
   * under way, the signal aborts or a worker fails.
   */
  async train(options: WidgetTrainOptions, onProgress?: (progress: TrainProgress) => void): Promise<Rig> {
    const { signal, workers, cache = true, ...asked } = options;
    // A reduced basis needs fewer functions than the mesh has vertices.
    const training = { ...asked, spatial: spatialFor(asked.spatial, this.#host.posing.shape.mesh.vertexCount) };
    const { posing, indicator } = this.#host;
    if (this.#training) throw coded(new Error("a rig is being trained already; cancel it first"), "invalid-argument");
    if (posing.handles.length === 0) {
      throw coded(new Error("place at least one handle on the shape before training a rig"), "invalid-argument");
    }
    const shape = posing.shape;
    const points = posing.handles.map((h) => ({ triangle: h.point.triangle, barycentric: h.point.barycentric }));
    // A puppet's rig is trained on its parts and its joints now (its key tells them apart).
    const puppet = shape.puppet
      ? {
          parts: shape.puppet.parts.map(({ name, triangles, depth }) => ({ name, triangles, depth })),
          joints: posing.deformer.joints,
        }
      : undefined;
    const controller = new AbortController();
    const abort = () => controller.abort(signal?.reason);
    signal?.addEventListener("abort", abort, { once: true });
    if (signal?.aborted) abort();
    this.#training = controller;
    const cancel = () => controller.abort(new DOMException("training was cancelled; nothing changed", "AbortError"));
    try {
      const key = await rigKey(shape.mesh, points, training, puppet?.joints).catch(() => undefined);
      controller.signal.throwIfAborted();
      const cached = key && cache ? await this.#cache.load(key, shape.mesh, points).catch(() => undefined) : undefined;
      if (cached) {
        this.adopt(cached);
        return cached;
      }
      indicator.update({ label: "Training the rig…", progress: 0, cancel });
      const trained = await trainDefOp(
        shape.mesh.positions,
        shape.mesh.triangles,
        { triangles: points.map((p) => p.triangle), barycentric: points.flatMap((p) => p.barycentric) },
        { ...training, ...puppet },
        {
          workers,
          signal: controller.signal,
          onProgress: (p) => {
            this.progress = p;
            indicator.update({ label: progressLabel(p), progress: p.total > 0 ? p.done / p.total : undefined, cancel });
            onProgress?.(p);
          },
        },
      );
      const rig = new Rig(trained.operator, shape.mesh, points, {
        radius: trained.radius,
        options: training,
        source: "trained",
      });
      this.adopt(rig);
      if (key) {
        this.#cache.save(key, rig).catch((error: unknown) => {
          this.#host.info(`The rig could not be kept in this browser: ${(error as Error).message}`);
        });
      }
      return rig;
    } finally {
      signal?.removeEventListener("abort", abort);
      this.#training = undefined;
      this.progress = undefined;
      indicator.done();
      this.#host.changed();
    }
  }

  /** Stops the training under way, if any (its promise rejects with an `AbortError`). */
  cancel(): void {
    this.#training?.abort(new DOMException("training was cancelled; nothing changed", "AbortError"));
  }

  /** The rig cached for the current shape and handles with `options`, adopted; false if none. */
  async fromCache(options: RigTrainOptions): Promise<boolean> {
    const { shape, handles } = this.#host.posing;
    if (handles.length === 0) return false;
    const points = handles.map((h) => h.point);
    const key = await rigKey(shape.mesh, points, options, shape.puppet ? this.#host.posing.joints : undefined);
    const rig = key ? await this.#cache.load(key, shape.mesh, points) : undefined;
    if (rig) this.adopt(rig);
    return rig !== undefined;
  }

  /**
   * Asks for the ground truth of the rig's current pose, solved in a worker once the pose
   * has rested a moment (a newer pose stops an older solve); `changed` hears the result.
   */
  compareSoon(): void {
    clearTimeout(this.#compareTimer);
    this.#comparing?.abort();
    this.#compareTimer = setTimeout(() => void this.#compare(), COMPARE_DELAY_MS);
  }

  async #compare(): Promise<void> {
    const posing = this.#host.posing;
    const rig = posing.rig;
    if (!rig || !posing.posingWithRig) return;
    const controller = new AbortController();
    this.#comparing = controller;
    const targets = posing.targets();
    const pose = posing.deformer.positions();
    try {
      const truth = await solveGroundTruth(
        rig.mesh.positions,
        rig.mesh.triangles,
        { triangles: rig.points.map((p) => p.triangle), barycentric: rig.points.flatMap((p) => p.barycentric) },
        targets,
        // The rig's own energy (its file keeps it), not the default.
        { energy: rig.energy, signal: controller.signal },
      );
      if (controller.signal.aborted) return;
      let far = 0;
      for (let v = 0; v < pose.length; v += 2) {
        far = Math.max(far, Math.hypot(pose[v]! - truth.positions[v]!, pose[v + 1]! - truth.positions[v + 1]!));
      }
      this.comparison = { positions: truth.positions, distance: far / posing.shape.size, iterations: truth.iterations };
    } catch (error) {
      if (controller.signal.aborted) return;
      this.comparison = undefined;
      this.#host.info(`The ground truth could not be solved for this pose: ${(error as Error).message}`);
    } finally {
      if (this.#comparing === controller) this.#comparing = undefined;
    }
    this.#host.changed();
  }

  /** The rig's state, for {@link Widget.rig}. */
  info(): RigInfo {
    const posing = this.#host.posing;
    const rig = posing.rig;
    const fits = rig?.fits(posing.shape, posing.handles, posing.joints) ?? false;
    return {
      state: rig ? (fits ? "ready" : "stale") : "none",
      source: rig?.source,
      training: this.training,
      posing: posing.posingWithRig,
      radius: rig?.radius,
      energy: rig?.energy,
      sampling: rig ? (rig.training?.sampling ?? "disc") : undefined,
      comparison: this.comparison?.distance,
    };
  }

  /** A line on the rig for the HUD: what poses, and why not the rig when it does not. */
  statusLine(): string | undefined {
    const posing = this.#host.posing;
    if (posing.settings.method !== "defop") return undefined;
    const rig = posing.rig;
    if (this.#training && !posing.posingWithRig) return "training a rig; posing with AKAP meanwhile";
    if (!rig) return "no trained rig: Train to pose with one (posing with AKAP until then)";
    if (!posing.posingWithRig) return "the rig is stale (the shape or handles changed): Train again (posing with AKAP)";
    const samples = rig.training?.samples ?? rig.options?.samples;
    const sampling = { disc: "", voronoi: ", Voronoi cells", mixed: ", discs and cells" }[
      rig.training?.sampling ?? rig.options?.sampling ?? "disc"
    ];
    const known = rig.training !== undefined || rig.options !== undefined;
    const what = known
      ? `${samples === undefined ? "" : `${samples} samples, `}${rig.energy === "arap" ? "ARAP" : "S-ARAP"}${sampling}`
      : "from a file";
    const compare = this.comparison
      ? `; ground truth ${(100 * this.comparison.distance).toFixed(2)}% of the size away`
      : "";
    return `rig: ${what}${rig.source === "cache" ? " (cached)" : ""}${compare}`;
  }

  destroy(): void {
    this.cancel();
    clearTimeout(this.#compareTimer);
    this.#comparing?.abort();
  }
}

/** A rig's operator file from a URL, a file or bytes. */
export async function rigBytes(source: string | Blob | Uint8Array | ArrayBuffer): Promise<Uint8Array> {
  if (source instanceof Uint8Array) return source;
  if (source instanceof ArrayBuffer) return new Uint8Array(source);
  if (source instanceof Blob) return new Uint8Array(await source.arrayBuffer());
  return new Uint8Array(await (await fetchFile(source)).arrayBuffer());
}

/** "Training: samples 120 of 1000, about 1 min 20 s left". */
export function progressLabel(p: TrainProgress): string {
  const stage = {
    setup: "setting up (the spatial basis)",
    samples: `samples ${p.done} of ${p.total}`,
    fit: "fitting the operator",
    done: "done",
  }[p.stage];
  const left = p.remainingMs === undefined || p.stage === "done" ? "" : `, about ${duration(p.remainingMs)} left`;
  const where = p.workers > 0 ? ` on ${p.workers} worker${p.workers > 1 ? "s" : ""}` : "";
  return `Training${where}: ${stage}${left}`;
}

function duration(ms: number): string {
  const seconds = Math.max(1, Math.round(ms / 1000));
  return seconds < 60 ? `${seconds} s` : `${Math.floor(seconds / 60)} min ${seconds % 60} s`;
}
