/**
 * A training worker of `defop-pool.ts`: a wasm instance of its own (of the module the page
 * compiled, sent with `start`), a {@link DefOpSolver} for the mesh, handles and energy,
 * and, in the pool's lead worker, the {@link DefOpTrainer} itself, so that the refits
 * between batches never run on the page's thread. Requests are handled one at a time, in
 * the order they came; every reply carries its request's `id`, and any error comes back as
 * a reply (with the error's `code`), not as an uncaught exception.
 */
import { init } from "./core.js";
import { DefOpSolver, DefOpTrainer, type DefOpJobResult } from "./defop.js";
import type { PoolReply, PoolRequest } from "./defop-pool.js";

interface WorkerScope {
  onmessage: ((event: MessageEvent<PoolRequest>) => void) | null;
  postMessage(message: PoolReply, transfer: Transferable[]): void;
}

const scope = globalThis as unknown as WorkerScope;
let solver: DefOpSolver | undefined;
let trainer: DefOpTrainer | undefined;
let queue: Promise<void> = Promise.resolve();

/** Buffers of typed arrays, each once, to transfer rather than copy. */
function buffers(...arrays: (Float64Array | Uint8Array | undefined)[]): Transferable[] {
  return [...new Set(arrays.filter((a) => a !== undefined).map((a) => a.buffer as ArrayBuffer))];
}

function lead(): DefOpTrainer {
  if (!trainer) throw new Error("this training worker holds no trainer");
  return trainer;
}

async function handle(request: PoolRequest): Promise<void> {
  const post = (reply: PoolReply, transfer: Transferable[] = []) => scope.postMessage(reply, transfer);
  const { id } = request;
  try {
    switch (request.kind) {
      case "start": {
        await init(request.wasm);
        const { positions, triangles, handles, options, train } = request;
        solver = new DefOpSolver(positions, triangles, handles, { energy: options.energy });
        if (train) trainer = new DefOpTrainer(positions, triangles, handles, options);
        post({ id, kind: "ready", radius: trainer?.radius, progress: trainer?.progress() });
        break;
      }
      case "run": {
        // Alone in the pool: the trainer solves its own samples, reporting after each slice.
        let progress = lead().advance(request.sliceMs);
        while (progress.stage !== "done") {
          post({ id, kind: "progress", progress, final: false });
          progress = lead().advance(request.sliceMs);
        }
        post({ id, kind: "progress", progress, final: true });
        break;
      }
      case "jobs": {
        const jobs = lead().nextJobs(request.max);
        post({ id, kind: "jobs", jobs }, buffers(...jobs.flatMap((j) => [j.targets, j.start])));
        break;
      }
      case "solve": {
        if (!solver) throw new Error("this training worker was not started");
        let result: DefOpJobResult;
        try {
          result = solver.solve(request.job);
        } catch (error) {
          const code = (error as { code?: unknown }).code;
          post({ id, kind: "unsolved", index: request.job.index, code: typeof code === "string" ? code : "internal" });
          break;
        }
        post({ id, kind: "solved", result }, buffers(result.positions));
        break;
      }
      case "submit":
        post({ id, kind: "progress", progress: lead().submit(request.result), final: true });
        break;
      case "reject":
        lead().reject(request.index, { code: request.code });
        post({ id, kind: "progress", progress: lead().progress(), final: true });
        break;
      case "finish": {
        const stats = lead().stats();
        const op = lead().finish();
        const bytes = op.toBytes();
        op.free();
        trainer = undefined;
        post({ id, kind: "operator", bytes, stats }, buffers(bytes));
        break;
      }
    }
  } catch (error) {
    const code = (error as { code?: unknown } | undefined)?.code;
    post({
      id,
      kind: "error",
      message: error instanceof Error ? error.message : String(error),
      code: typeof code === "string" ? code : undefined,
    });
  }
}

scope.onmessage = (event) => {
  const request = event.data;
  queue = queue.then(() => handle(request));
};
