// DefOp in wasm, in Node, on one thread: training time (ground-truth samples with
// bootstrapped warm starts, fits) and evaluations per second, at the size of the paper's
// octopus (the built-in figure at about 2,000 vertices, 9 handles, TPS on the samples,
// the reduced spatial basis of 100 functions), for both energies. With WORKERS=k (k >= 1)
// each training runs a second time with its sample solves spread over k worker threads
// (lab/defop/defop-worker.mjs, each with its own wasm instance, jobs from
// DefOpTrainer.nextJobs), and the speed-up over one thread is printed.
//   npm run build && [WORKERS=2] node lab/defop/bench-defop.mjs [samples] [vertices]
//   [WORKERS=2] node lab/defop/bench-defop.mjs --model octopus target/defop-table/manifest.json
// With --operators MANIFEST (written by `cargo run --release --example defop_table`): times
// evaluateInto on each operator file it lists (loaded with DefOp.fromBytes, its targets
// from the manifest) and prints one JSON object, file name to milliseconds per evaluation.
//   node lab/defop/bench-defop.mjs --operators target/defop-table/manifest.json
// Evaluation alone, without training and old build against new: lab/defop/bench-defop-eval.mjs.
import { readFileSync } from "node:fs";
import process from "node:process";
import { URL } from "node:url";
import { Worker } from "node:worker_threads";
import { performance } from "node:perf_hooks";
import { DefOp, DefOpTrainer, defaultShape, init, triangulateToVertices } from "../../www/lib/index.js";

await init();

/**
 * Trains like `trainer.advance` does, but with every sample's solve on one of `count`
 * workers; resolves to the trainer once it is done.
 */
async function trainWithWorkers(trainer, count, workerData) {
  const url = new URL("./defop-worker.mjs", import.meta.url);
  const workers = Array.from({ length: count }, () => new Worker(url, { workerData }));
  await Promise.all(workers.map((w) => new Promise((ready) => w.once("message", ready))));
  const idle = [...workers];
  let outstanding = 0;
  await new Promise((resolve, fail) => {
    const dispatch = () => {
      for (const job of trainer.nextJobs(idle.length)) {
        const worker = idle.pop();
        outstanding++;
        worker.once("message", (reply) => {
          outstanding--;
          idle.push(worker);
          try {
            if (reply.result) trainer.submit(reply.result);
            else trainer.reject(reply.index, { code: reply.code });
            if (trainer.progress().stage === "done") resolve();
            else dispatch();
          } catch (error) {
            fail(error);
          }
        });
        worker.postMessage(job);
      }
      if (outstanding === 0 && trainer.progress().stage !== "done") fail(new Error("no jobs and none out"));
    };
    dispatch();
  });
  await Promise.all(workers.map((w) => w.terminate()));
  return trainer;
}

/** Milliseconds per `op.evaluateInto` over `queries`, for about a second after a warm-up. */
function evaluationMs(op, queries, vertexCount) {
  const out = new Float64Array(2 * vertexCount);
  for (const q of queries) op.evaluateInto(q, out); // warm up
  let calls = 0;
  const t0 = performance.now();
  while (performance.now() - t0 < 1000) {
    for (const q of queries) op.evaluateInto(q, out);
    calls += queries.length;
  }
  return (performance.now() - t0) / calls;
}

if (process.argv[2] === "--operators") {
  const manifest = JSON.parse(readFileSync(process.argv[3], "utf8"));
  const timings = {};
  for (const { file, targets } of manifest) {
    const op = DefOp.fromBytes(new Uint8Array(readFileSync(file)));
    timings[file] = evaluationMs(
      op,
      targets.map((t) => Float64Array.from(t)),
      op.vertexCount,
    );
    op.free();
  }
  console.log(JSON.stringify(timings));
  process.exit(0);
}
// The model: by default the built-in figure with nine handles (the vertices nearest to
// points spread over it); with --model NAME MANIFEST, the mesh, handles and training
// options of a model of `cargo run --release --example defop_table` (its TPS operator file
// holds the mesh; the manifest the handles and options).
let model;
if (process.argv[2] === "--model") {
  const [name, path] = process.argv.slice(3, 5);
  const entry = JSON.parse(readFileSync(path, "utf8")).find((e) => e.model === name && e.basis === "TPS");
  if (!entry?.handles) throw new Error(`no TPS operator of a model ${name} with vertex handles in ${path}`);
  const op = DefOp.fromBytes(new Uint8Array(readFileSync(entry.file)));
  const { positions, triangles } = op.mesh();
  op.free();
  const { samples, spatial, radius, fixed } = entry.training;
  model = { name, positions, triangles, handles: entry.handles, energies: [entry.training.energy] };
  model.options = { samples, spatial, fixed, ...(radius === null ? {} : { radius }), seed: 1 };
} else {
  const samples = Number(process.argv[2] ?? 1000);
  const { mesh } = triangulateToVertices(defaultShape(), Number(process.argv[3] ?? 2000));
  const spots = [
    [-0.48, 1.2],
    [0.45, 0.95],
    [0, 1.25],
    [0, 0.7],
    [-0.2, 0.05],
    [0.2, 0.05],
    [-0.3, 0.6],
    [0.3, 0.6],
    [0, 0.4],
  ];
  const p = mesh.positions;
  const handles = spots.map(([x, y]) => {
    let [best, at] = [Infinity, 0];
    for (let v = 0; v < mesh.vertexCount; v++) {
      const d = Math.hypot(p[2 * v] - x, p[2 * v + 1] - y);
      if (d < best) [best, at] = [d, v];
    }
    return at;
  });
  model = { name: "figure", positions: p, triangles: mesh.triangles, handles, energies: ["sarap", "arap"] };
  model.options = { samples, spatial: 100, seed: 1 };
}
const { positions: p, triangles, handles, options } = model;
const vertexCount = p.length / 2;
const rest = handles.flatMap((v) => [p[2 * v], p[2 * v + 1]]);

console.log(
  `${model.name}: ${vertexCount} vertices, ${triangles.length / 3} triangles, ${handles.length} handles, ${options.samples} samples, TPS, spatial ${options.spatial}`,
);
console.log("");
console.log(
  "| energy | training s | cold solves (mean iterations) | warm solves (mean iterations) | neighbour starts | redraws | evaluate ms | evaluations/s | training s, workers | speed-up |",
);
console.log("|---|---|---|---|---|---|---|---|---|---|");
const workerCount = Number(process.env.WORKERS ?? 0);
for (const energy of process.env.ENERGIES?.split(",") ?? model.energies) {
  const start = performance.now();
  const trainer = new DefOpTrainer(p, triangles, handles, { ...options, energy });
  while (trainer.advance(1000).stage !== "done");
  const seconds = (performance.now() - start) / 1000;
  const s = trainer.stats();
  const op = trainer.finish();
  const queries = Array.from({ length: 64 }, (_, k) => rest.map((x, i) => x + 0.05 * Math.sin(k + 1.7 * i)));
  const ms = evaluationMs(op, queries, vertexCount);
  const mean = (n, i) => (n ? (i / n).toFixed(1) : "-");
  let parallel = "- | -";
  if (workerCount > 0) {
    const begin = performance.now();
    const trained = await trainWithWorkers(
      new DefOpTrainer(p, triangles, handles, { ...options, energy }),
      workerCount,
      {
        positions: p,
        triangles,
        handles: Uint32Array.from(handles),
        energy,
      },
    );
    const s2 = (performance.now() - begin) / 1000;
    const [mine, theirs] = [op.evaluate(queries[0]), trained.finish().evaluate(queries[0])];
    const same = mine.every((x, i) => x === theirs[i]);
    parallel = `${s2.toFixed(1)} (${workerCount}; ${same ? "same operator" : "OPERATOR DIFFERS"}) | ${(seconds / s2).toFixed(2)}x`;
  }
  console.log(
    `| ${energy} | ${seconds.toFixed(1)} | ${s.cold} (${mean(s.cold, s.coldIterations)}) | ${s.warm} (${mean(s.warm, s.warmIterations)}) | ${s.neighbourStarts} | ${s.redraws} | ${ms.toFixed(3)} | ${Math.round(1000 / ms)} | ${parallel} |`,
  );
  op.free();
}
