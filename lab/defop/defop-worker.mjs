// A training worker for lab/defop/bench-defop.mjs: its own wasm instance and DefOpSolver for
// the mesh, handles and energy it is given, then one solve per job message. A job that
// cannot be solved comes back with its error's code, for DefOpTrainer.reject.
import { parentPort, workerData } from "node:worker_threads";
import { DefOpSolver, init } from "../../www/lib/index.js";

await init();
const { positions, triangles, handles, energy } = workerData;
const solver = new DefOpSolver(positions, triangles, handles, { energy });
parentPort.on("message", (job) => {
  try {
    parentPort.postMessage({ result: solver.solve(job) });
  } catch (error) {
    parentPort.postMessage({ index: job.index, code: error?.code ?? "internal", message: String(error) });
  }
});
parentPort.postMessage({ ready: true });
