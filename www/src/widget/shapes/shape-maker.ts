/**
 * Making a shape ready to pose, off the main thread: a Web Worker (its own wasm instance,
 * `setup-worker.ts`) triangulates the outline to the vertex count asked and computes the
 * deformer's fill-reducing orders, the bulk of the set-up (about two thirds), while the
 * page stays responsive; the widget then builds the deformer with those orders. Progress
 * comes as stages; a new request or {@link ShapeMaker.cancel} stops the one under way.
 * Where workers cannot run (no `Worker`, a page that forbids them), the work runs on the
 * main thread after a frame, so the busy indicator shows first.
 */
import { builtinShape, compiledModule, type DeformerOptions, type Outline } from "../../core.js";
import { unbundledFile } from "../../internal/wasm.js";
import { meshOutline, type Shape } from "../model/shape.js";
import { BUSY_DELAY_MS, type BusyIndicator } from "../view/busy-indicator.js";

/** What to make: an outline (or a built-in shape by name) meshed to about `vertices`. */
export interface SetupRequest {
  outline: Outline | undefined;
  /** A built-in shape's name (its outline is read in the worker). */
  name: string | undefined;
  label: string;
  vertices: number;
  minAngle: number;
  options: DeformerOptions;
}

/** Messages to the worker: the request, and the compiled module it instantiates (once). */
export interface SetupMessage {
  id: number;
  request: SetupRequest;
  wasm: WebAssembly.Module;
}

/** Messages from the worker. */
export type SetupReply =
  | { id: number; kind: "progress"; stage: string; fraction: number }
  | { id: number; kind: "done"; shape: Shape; orders: Uint32Array[] }
  | { id: number; kind: "error"; message: string };

/** A shape and, when a worker made it, the orders its deformer needs. */
export interface Prepared {
  shape: Shape;
  orders: Uint32Array[] | undefined;
}

/** The request was replaced by a newer one, or cancelled; nothing changed. */
export class Cancelled extends Error {
  constructor() {
    super("cancelled; nothing changed");
    this.name = "Cancelled";
  }
}

interface Pending {
  id: number;
  resolve(prepared: Prepared): void;
  reject(error: Error): void;
  progress(stage: string, fraction: number): void;
}

export class ShapeMaker {
  /** The worker; null once it could not be started (then work runs here). */
  #worker: Worker | null | undefined;
  #pending: Pending | undefined;
  #next = 1;

  /** Makes the shape; `progress` hears the stages. Rejects with {@link Cancelled} if superseded. */
  make(request: SetupRequest, progress: (stage: string, fraction: number) => void): Promise<Prepared> {
    this.cancel();
    const worker = this.#start();
    if (!worker) return here(request, progress);
    return new Promise<Prepared>((resolve, reject) => {
      const pending: Pending = { id: this.#next++, resolve, reject, progress };
      this.#pending = pending;
      worker.postMessage({ id: pending.id, request, wasm: compiledModule() } satisfies SetupMessage);
    });
  }

  /** Stops the work under way (the worker is ended; a new one starts with the next request). */
  cancel(): void {
    const pending = this.#pending;
    if (!pending) return;
    this.#pending = undefined;
    this.#worker?.terminate();
    this.#worker = undefined;
    pending.reject(new Cancelled());
  }

  destroy(): void {
    this.cancel();
    this.#worker?.terminate();
    this.#worker = null;
  }

  #start(): Worker | null {
    if (this.#worker !== undefined) return this.#worker;
    try {
      // The literal form is what bundlers recognise (and bundle the worker with its imports).
      const unbundled = unbundledFile("www/lib/widget/shapes/setup-worker.js");
      const worker = unbundled
        ? new Worker(unbundled, { type: "module" })
        : new Worker(new URL("./setup-worker.js", import.meta.url), { type: "module" });
      worker.onmessage = (event: MessageEvent<SetupReply>) => this.#reply(event.data);
      worker.onerror = (event) => {
        // A worker that cannot load (blocked, or its script missing): work here from now on.
        event.preventDefault();
        this.#worker = null;
        const pending = this.#pending;
        this.#pending = undefined;
        pending?.reject(new Error(`the set-up worker failed: ${event.message || "it could not load"}`));
      };
      this.#worker = worker;
    } catch {
      this.#worker = null;
    }
    return this.#worker;
  }

  #reply(reply: SetupReply): void {
    const pending = this.#pending;
    if (!pending || reply.id !== pending.id) return;
    if (reply.kind === "progress") {
      pending.progress(reply.stage, reply.fraction);
      return;
    }
    this.#pending = undefined;
    if (reply.kind === "done") pending.resolve({ shape: reply.shape, orders: reply.orders });
    else pending.reject(new Error(reply.message));
  }
}

/** The stages, with the fraction of the work done when each begins (measured at 40k vertices). */
export const STAGES = { meshing: ["Meshing", 0.05], ordering: ["Ordering the solver's unknowns", 0.35] } as const;

/** The request on this thread, once the busy indicator has had time to show. */
async function here(request: SetupRequest, progress: (stage: string, fraction: number) => void): Promise<Prepared> {
  progress(...STAGES.meshing);
  await new Promise((resolve) => setTimeout(resolve, BUSY_DELAY_MS + 50));
  return { shape: makeShape(request), orders: undefined };
}

/** The shape a request asks for (in the worker or here). */
export function makeShape(request: SetupRequest): Shape {
  const outline = request.outline ?? builtinShape(request.name!);
  return meshOutline(outline, request.name, request.vertices, request.minAngle, request.label);
}

/**
 * Makes a shape with `maker` while `busy` shows the stage, the progress and Cancel.
 * `methodNow` is the deformer method when the result arrives: orders made for another
 * method (switched meanwhile) are dropped, since they do not fit its systems.
 */
export async function makeShown(
  maker: ShapeMaker,
  busy: BusyIndicator,
  request: SetupRequest,
  methodNow: () => DeformerOptions["method"],
): Promise<Prepared> {
  const label = `${request.label}: ${Math.round(request.vertices)} vertices`;
  const cancel = () => maker.cancel();
  busy.update({ label: `${label}…`, progress: 0, cancel });
  try {
    const prepared = await maker.make(request, (stage, progress) =>
      busy.update({ label: `${label}: ${stage.toLowerCase()}…`, progress, cancel }),
    );
    busy.update({ label: `${label}: preparing the solver…`, progress: 0.9 });
    await new Promise((resolve) => requestAnimationFrame(resolve));
    const same = (request.options.method ?? "akap") === (methodNow() ?? "akap");
    return { shape: prepared.shape, orders: same ? prepared.orders : undefined };
  } finally {
    busy.done();
  }
}
