// DefOp in wasm, in Node, on one thread: training time (ground-truth samples with
// bootstrapped warm starts, fits) and evaluations per second, at the size of the paper's
// octopus (the built-in figure at about 2,000 vertices, 9 handles, TPS on the samples,
// the reduced spatial basis of 100 functions), for both energies.
//   npm run build && node scripts/bench-defop.mjs [samples] [vertices]
// Evaluation alone, without training and old build against new: scripts/bench-defop-eval.mjs.
import process from "node:process";
import { performance } from "node:perf_hooks";
import { DefOpTrainer, defaultShape, init, triangulateToVertices } from "../www/lib/index.js";

await init();
const samples = Number(process.argv[2] ?? 1000);
const vertices = Number(process.argv[3] ?? 2000);
const { mesh } = triangulateToVertices(defaultShape(), vertices);
const p = mesh.positions;

// Nine handles: the vertices nearest to points spread over the figure.
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
const handles = spots.map(([x, y]) => {
  let [best, at] = [Infinity, 0];
  for (let v = 0; v < mesh.vertexCount; v++) {
    const d = Math.hypot(p[2 * v] - x, p[2 * v + 1] - y);
    if (d < best) [best, at] = [d, v];
  }
  return at;
});
const rest = handles.flatMap((v) => [p[2 * v], p[2 * v + 1]]);

console.log(
  `${mesh.vertexCount} vertices, ${mesh.triangleCount} triangles, 9 handles, ${samples} samples, TPS, spatial 100`,
);
console.log("");
console.log(
  "| energy | training s | cold solves (mean iterations) | warm solves (mean iterations) | neighbour starts | redraws | evaluate ms | evaluations/s |",
);
console.log("|---|---|---|---|---|---|---|---|");
for (const energy of (process.env.ENERGIES ?? "sarap,arap").split(",")) {
  const start = performance.now();
  const trainer = new DefOpTrainer(p, mesh.triangles, handles, { energy, samples, spatial: 100, seed: 1 });
  while (trainer.advance(1000).stage !== "done");
  const seconds = (performance.now() - start) / 1000;
  const s = trainer.stats();
  const op = trainer.finish();
  const out = new Float64Array(2 * mesh.vertexCount);
  const queries = Array.from({ length: 64 }, (_, k) => rest.map((x, i) => x + 0.05 * Math.sin(k + 1.7 * i)));
  for (const q of queries) op.evaluateInto(q, out); // warm up
  let calls = 0;
  const t0 = performance.now();
  while (performance.now() - t0 < 1000) {
    for (const q of queries) op.evaluateInto(q, out);
    calls += queries.length;
  }
  const ms = (performance.now() - t0) / calls;
  const mean = (n, i) => (n ? (i / n).toFixed(1) : "-");
  console.log(
    `| ${energy} | ${seconds.toFixed(1)} | ${s.cold} (${mean(s.cold, s.coldIterations)}) | ${s.warm} (${mean(s.warm, s.warmIterations)}) | ${s.neighbourStarts} | ${s.redraws} | ${ms.toFixed(3)} | ${Math.round(1000 / ms)} |`,
  );
  op.free();
}
