/**
 * Training a {@link DefOp} without holding up the page: {@link trainDefOp} runs the
 * training on a pool of Web Workers (module workers, one per spare core by default, at
 * least one), each with its own wasm instance of the module this page compiled. The pool's
 * lead worker holds the {@link DefOpTrainer} (so the refits between batches run there too)
 * and hands out each batch's sample solves to the others (a pool of one trains alone in
 * its worker; the lead solves nothing, so a result is taken as soon as it comes); this thread
 * only passes messages. Progress comes with the stage, samples done of total, the time so
 * far and an estimate of the time left; an `AbortSignal` stops every worker at once, and
 * the result is the same operator, bit for bit, whatever the number of workers.
 *
 * Where workers cannot run (Node, a page whose policy forbids them) the training runs on
 * this thread in slices of a few milliseconds (a sample's solve, once begun, is finished),
 * yielding to the event loop between them.
 *
 * @example
 * ```ts
 * const op = await trainDefOp(mesh.positions, mesh.triangles, [0, 42], { samples: 200 }, {
 *   onProgress: (p) => console.log(`${p.done} of ${p.total}`),
 *   signal: AbortSignal.timeout(60_000),
 * });
 * ```
 */
import { compiledModule } from "./core.js";
import {
  DefOp,
  DefOpSolver,
  DefOpTrainer,
  type DefOpJob,
  type DefOpJobResult,
  type DefOpProgress,
  type DefOpStats,
  type DefOpTrainerOptions,
} from "./defop.js";
import {
  coded,
  handleArrays,
  toFloat64,
  toUint32,
  type Coordinates,
  type HandleSpec,
  type Indices,
} from "./internal/arrays.js";
import { unbundledFile } from "./internal/wasm.js";

/** How far a {@link trainDefOp} is, with times. */
export interface TrainProgress extends Omit<DefOpProgress, "stage"> {
  /**
   * `"setup"` while the trainer is made (the spatial basis: for a reduced basis, an
   * eigenproblem; `total` is 0 then), then the trainer's stages: `"samples"`, `"fit"`,
   * `"done"`.
   */
  stage: DefOpProgress["stage"] | "setup";
  /** Milliseconds since training began. */
  elapsedMs: number;
  /** Estimated milliseconds left (from the pace so far), once a few samples are in. */
  remainingMs: number | undefined;
  /** Workers training (0: on this thread). */
  workers: number;
}

/** How a {@link trainDefOp} runs. */
export interface TrainControl {
  /**
   * Workers to train on: default one per spare core (`navigator.hardwareConcurrency - 1`,
   * at least 1); 0 trains on this thread in slices.
   */
  workers?: number;
  /** Hears progress after every sample (or slice). */
  onProgress?: (progress: TrainProgress) => void;
  /** Stops the training: the promise rejects with the signal's reason (an `AbortError`). */
  signal?: AbortSignal;
  /** Milliseconds per slice of training on this thread (default 8). */
  sliceMs?: number;
}

/** What a {@link trainDefOp} resolves to: the operator and its training's record. */
export interface Trained {
  operator: DefOp;
  /** The sampling radius used (the `radius` option or its default). */
  radius: number;
  stats: DefOpStats;
  /** Milliseconds the training took. */
  ms: number;
  /** Workers it ran on (0: this thread). */
  workers: number;
}

/** Requests to a training worker (internal). */
export type PoolRequest = { id: number } & (
  | {
      kind: "start";
      wasm: WebAssembly.Module;
      positions: Float64Array;
      triangles: Uint32Array;
      handles: Uint32Array | { triangles: Uint32Array; barycentric: Float64Array };
      options: DefOpTrainerOptions;
      /** The lead worker: it holds the trainer. */
      train: boolean;
    }
  | { kind: "run"; sliceMs: number }
  | { kind: "jobs"; max: number }
  | { kind: "solve"; job: DefOpJob }
  | { kind: "submit"; result: DefOpJobResult }
  | { kind: "reject"; index: number; code: string }
  | { kind: "finish" }
);

/** Replies of a training worker (internal). */
export type PoolReply = { id: number } & (
  | { kind: "ready"; radius: number | undefined; progress: DefOpProgress | undefined }
  | { kind: "progress"; progress: DefOpProgress; final: boolean }
  | { kind: "jobs"; jobs: DefOpJob[] }
  | { kind: "solved"; result: DefOpJobResult }
  | { kind: "unsolved"; index: number; code: string }
  | { kind: "operator"; bytes: Uint8Array; stats: DefOpStats }
  | { kind: "error"; message: string; code: string | undefined }
);

/** The default pool size: one worker per spare core, at least one. */
export function defaultWorkerCount(): number {
  const cores = typeof navigator === "object" ? (navigator.hardwareConcurrency ?? 2) : 2;
  return Math.max(1, cores - 1);
}

/** Whether this environment can start module workers. */
function workersAvailable(): boolean {
  return typeof Worker === "function";
}

/**
 * Trains a deformation operator for the mesh and handles (see {@link DefOpTrainer} for
 * the options) on a pool of workers, or on this thread where there are none.
 */
export async function trainDefOp(
  positions: Coordinates,
  triangles: Indices,
  handles: HandleSpec,
  options: DefOpTrainerOptions = {},
  control: TrainControl = {},
): Promise<Trained> {
  const p = toFloat64(positions, "positions");
  const t = toUint32(triangles, "triangles");
  const h = handleArrays(handles);
  control.signal?.throwIfAborted();
  const count = control.workers ?? defaultWorkerCount();
  if (!(Number.isInteger(count) && count >= 0 && count <= 64)) {
    throw coded(new RangeError(`workers is ${count}; give a whole number from 0 to 64`), "invalid-argument");
  }
  const clock = new Clock();
  if (count === 0 || !workersAvailable()) return trainHere(p, t, h, options, control, clock);
  // One worker trains alone; with more, a lead worker holds the trainer and only hands out
  // jobs and refits, so that results are taken at once, and the others solve.
  const pool = startPool(count === 1 ? 1 : count + 1, control.signal);
  if (!pool) return trainHere(p, t, h, options, control, clock);
  try {
    return await pool.train(p, t, h, options, control, clock);
  } finally {
    pool.terminate();
  }
}

/**
 * The deformation a DefOp approximates, for handles at `targets` (2 per handle): the pose
 * of least ARAP or S-ARAP energy (default S-ARAP), solved from `start` (2 per vertex;
 * default the rest pose) in a worker, or on this thread where there are none. A solve
 * cannot be interrupted on this thread; in a worker, `signal` stops it at once.
 */
export async function solveGroundTruth(
  positions: Coordinates,
  triangles: Indices,
  handles: HandleSpec,
  targets: Coordinates,
  options: { energy?: "sarap" | "arap"; start?: Float64Array; signal?: AbortSignal } = {},
): Promise<{ positions: Float64Array; iterations: number }> {
  const job: DefOpJob = { index: 0, targets: toFloat64(targets, "targets").slice(), start: options.start?.slice() };
  options.signal?.throwIfAborted();
  const pool = workersAvailable() ? startPool(1, options.signal) : undefined;
  if (!pool) {
    const solver = new DefOpSolver(positions, triangles, handles, { energy: options.energy });
    try {
      return solver.solve(job);
    } finally {
      solver.free();
    }
  }
  try {
    return await pool.solve(positions, triangles, handles, options.energy, job);
  } finally {
    pool.terminate();
  }
}

/** A pool of `count` workers, or undefined where the page may not start workers. */
function startPool(count: number, signal: AbortSignal | undefined): Pool | undefined {
  try {
    return new Pool(count, signal);
  } catch {
    return undefined;
  }
}

/** Progress before the trainer exists. */
const SETUP = { done: 0, total: 0, stage: "setup" } as const;

/** Elapsed time and the estimate of what is left. */
class Clock {
  readonly #start = performance.now();
  /** Progress when the pace began to be measured (after the first cold samples). */
  #from: { at: number; done: number } | undefined;

  progress(p: DefOpProgress | { done: 0; total: 0; stage: "setup" }, workers: number): TrainProgress {
    const now = performance.now();
    const elapsedMs = now - this.#start;
    let remainingMs: number | undefined;
    if (p.stage === "done") remainingMs = 0;
    else if (this.#from === undefined) {
      if (p.done > 0) this.#from = { at: now, done: p.done };
    } else if (p.done > this.#from.done) {
      remainingMs = ((now - this.#from.at) / (p.done - this.#from.done)) * (p.total - p.done);
    }
    return { ...p, elapsedMs, remainingMs, workers };
  }

  get ms(): number {
    return performance.now() - this.#start;
  }
}

/** Training on this thread, in slices, yielding between them. */
async function trainHere(
  positions: Float64Array,
  triangles: Uint32Array,
  handles: HandleSpec,
  options: DefOpTrainerOptions,
  control: TrainControl,
  clock: Clock,
): Promise<Trained> {
  control.onProgress?.(clock.progress(SETUP, 0));
  await yieldToEventLoop();
  const trainer = new DefOpTrainer(positions, triangles, handles, options);
  try {
    const slice = control.sliceMs ?? 8;
    for (;;) {
      const progress = trainer.advance(slice);
      control.onProgress?.(clock.progress(progress, 0));
      if (progress.stage === "done") break;
      await yieldToEventLoop();
      control.signal?.throwIfAborted();
    }
    const { radius } = trainer;
    const stats = trainer.stats();
    return { operator: trainer.finish(), radius, stats, ms: clock.ms, workers: 0 };
  } finally {
    trainer.free();
  }
}

function yieldToEventLoop(): Promise<void> {
  return new Promise((resolve) => setTimeout(resolve, 0));
}

/** A worker and its requests awaiting replies. */
interface Member {
  worker: Worker;
  waiting: Map<number, { resolve(reply: PoolReply): void; progress?(reply: PoolReply): void }>;
}

class Pool {
  readonly #members: Member[] = [];
  #next = 1;
  /** Set once the pool failed or was stopped: every pending and later request rejects with it. */
  #failure: Error | undefined;
  #fail: (error: Error) => void = () => {};
  readonly #failed: Promise<never>;

  constructor(count: number, signal: AbortSignal | undefined) {
    this.#failed = new Promise<never>((_, reject) => {
      this.#fail = (error) => {
        if (this.#failure) return;
        this.#failure = error;
        this.terminate();
        reject(error);
      };
    });
    this.#failed.catch(() => {});
    signal?.addEventListener("abort", () => this.#fail(abortReason(signal)), { once: true });
    try {
      for (let i = 0; i < count; i++) this.#members.push(this.#spawn(i));
    } catch (error) {
      // `new Worker` refused (a page whose policy forbids workers): none is left running.
      this.terminate();
      throw error;
    }
  }

  #spawn(index: number): Member {
    // The literal form is what bundlers recognise (and bundle the worker with its imports).
    const unbundled = unbundledFile("www/lib/defop-worker.js");
    const worker = unbundled
      ? new Worker(unbundled, { type: "module" })
      : new Worker(new URL("./defop-worker.js", import.meta.url), { type: "module" });
    const member: Member = { worker, waiting: new Map() };
    worker.onmessage = (event: MessageEvent<PoolReply>) => {
      const reply = event.data;
      const waiter = member.waiting.get(reply.id);
      if (!waiter) return;
      if (reply.kind === "progress" && !reply.final) {
        waiter.progress?.(reply);
        return;
      }
      member.waiting.delete(reply.id);
      if (reply.kind === "error") {
        this.#fail(coded(new Error(`training failed: ${reply.message}`), (reply.code ?? "internal") as never));
      } else waiter.resolve(reply);
    };
    worker.onerror = (event) => {
      event.preventDefault();
      const why = event.message || "its script could not be loaded or run";
      this.#fail(coded(new Error(`training worker ${index + 1} failed (${why}); nothing was trained`), "internal"));
    };
    worker.onmessageerror = () => {
      this.#fail(coded(new Error(`training worker ${index + 1} sent a message that could not be read`), "internal"));
    };
    return member;
  }

  /** Sends a request and waits for its reply (or the pool's failure). */
  #call(
    member: Member,
    request: DistributiveOmit<PoolRequest, "id">,
    transfer: Transferable[] = [],
    progress?: (reply: PoolReply) => void,
  ): Promise<PoolReply> {
    if (this.#failure) return Promise.reject(this.#failure);
    const id = this.#next++;
    const reply = new Promise<PoolReply>((resolve) => member.waiting.set(id, { resolve, progress }));
    member.worker.postMessage({ ...request, id } as PoolRequest, transfer);
    return Promise.race([reply, this.#failed]);
  }

  /** One ground-truth solve on the pool's first worker. */
  async solve(
    positions: Coordinates,
    triangles: Indices,
    handles: HandleSpec,
    energy: DefOpTrainerOptions["energy"],
    job: DefOpJob,
  ): Promise<{ positions: Float64Array; iterations: number }> {
    const [member] = this.#members as [Member];
    const request = {
      kind: "start",
      wasm: compiledModule(),
      positions: toFloat64(positions, "positions"),
      triangles: toUint32(triangles, "triangles"),
      handles: handleArrays(handles),
      options: { energy },
      train: false,
    } as const;
    expect(await this.#call(member, request), "ready");
    const answer = await this.#call(member, { kind: "solve", job });
    if (answer.kind === "unsolved") {
      throw coded(new Error(`no pose of least energy was found for these targets (${answer.code})`), "no-convergence");
    }
    return expect(answer, "solved").result;
  }

  async train(
    positions: Float64Array,
    triangles: Uint32Array,
    handles: Uint32Array | { triangles: Uint32Array; barycentric: Float64Array },
    options: DefOpTrainerOptions,
    control: TrainControl,
    clock: Clock,
  ): Promise<Trained> {
    const wasm = compiledModule();
    const [lead, ...others] = this.#members as [Member, ...Member[]];
    const workers = Math.max(1, others.length);
    const start = async (member: Member, train: boolean) =>
      expect(await this.#call(member, { kind: "start", wasm, positions, triangles, handles, options, train }), "ready");
    control.onProgress?.(clock.progress(SETUP, workers));
    const [ready] = await Promise.all([start(lead, true), ...others.map((m) => start(m, false))]);
    const report = (progress: DefOpProgress) => control.onProgress?.(clock.progress(progress, workers));
    report(ready.progress!);
    if (workers === 1) {
      const done = await this.#call(lead, { kind: "run", sliceMs: 100 }, [], (r) => {
        if (r.kind === "progress") report(r.progress);
      });
      report(expect(done, "progress").progress);
    } else {
      await this.#solveAll(lead, others, report);
    }
    const { bytes, stats } = expect(await this.#call(lead, { kind: "finish" }), "operator");
    if (this.#failure) throw this.#failure;
    const operator = DefOp.fromBytes(bytes);
    return { operator, radius: ready.radius!, stats, ms: clock.ms, workers };
  }

  /**
   * Hands each batch's jobs to idle solvers, passes their results to the
   * lead's trainer, and resolves when every sample is in and the operator fitted.
   */
  #solveAll(lead: Member, solvers: Member[], report: (progress: DefOpProgress) => void): Promise<void> {
    const idle = [...solvers];
    let outstanding = 0;
    let asking = false;
    return new Promise<void>((resolve, reject) => {
      const fail = (error: unknown) => reject(error instanceof Error ? error : new Error(String(error)));
      const dispatch = async (): Promise<void> => {
        if (asking || idle.length === 0) return;
        asking = true;
        const { jobs } = expect(
          await this.#call(lead, { kind: "jobs", max: idle.length }).finally(() => {
            asking = false;
          }),
          "jobs",
        );
        for (const job of jobs) {
          outstanding++;
          void solve(idle.pop()!, job).catch(fail);
        }
        if (jobs.length === 0 && outstanding === 0)
          fail(new Error("training stalled: no jobs to hand out and none out"));
      };
      const solve = async (member: Member, job: DefOpJob): Promise<void> => {
        const transfer = [job.targets.buffer, ...(job.start ? [job.start.buffer] : [])] as Transferable[];
        const answer = await this.#call(member, { kind: "solve", job }, transfer);
        idle.push(member);
        outstanding--;
        let reply: PoolReply;
        if (answer.kind === "unsolved") {
          reply = await this.#call(lead, { kind: "reject", index: answer.index, code: answer.code });
        } else {
          const { result } = expect(answer, "solved");
          reply = await this.#call(lead, { kind: "submit", result }, [result.positions.buffer as ArrayBuffer]);
        }
        const progress = expect(reply, "progress");
        report(progress.progress);
        if (progress.progress.stage === "done") resolve();
        else await dispatch();
      };
      dispatch().catch(fail);
    });
  }

  terminate(): void {
    for (const m of this.#members) m.worker.terminate();
  }
}

/** `reply` as the kind of reply asked for; another kind is a broken protocol. */
function expect<K extends PoolReply["kind"]>(reply: PoolReply, kind: K): Extract<PoolReply, { kind: K }> {
  if (reply.kind !== kind) throw new Error(`a training worker answered ${reply.kind} where ${kind} was due`);
  return reply as Extract<PoolReply, { kind: K }>;
}

/** `Omit` over each member of a union. */
type DistributiveOmit<T, K extends PropertyKey> = T extends unknown ? Omit<T, K> : never;

/** The reason an aborted signal gives, as an Error with the code `cancelled`. */
function abortReason(signal: AbortSignal): Error {
  const reason: unknown = signal.reason;
  if (reason instanceof Error) return reason;
  return new DOMException(typeof reason === "string" ? reason : "training was cancelled", "AbortError");
}
