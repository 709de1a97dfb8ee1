// Per-frame timings of a deformer compiled to wasm (AKAP by default), in Node: a scripted
// drag of the built-in figure's raised hand with both feet pinned, at several mesh sizes.
// Prints median and 95th percentile milliseconds per stage (assembly, each of the two
// numeric factorisations, the solves, the spiral step; MLS's evaluation is its
// "spiral" column, the stage that moves the vertices; Cauchy-Green's small solve is its
// "solves" and its product with the coordinates its "spiral") and per frame. `--set
// name=value` (repeatable) passes a setting of the method, e.g. `--set cage=300`.
// `--guard` steps with `stepWithoutFoldovers` instead of `step` (the drag flips nothing, so
// this times the guard's own cost: a checkpoint and the orientation check each frame);
// compare runs with and without it interleaved, the machine's noise being larger.
// `--bones` lays a bone along the dragged arm (AKAP and ARAP): its cost, the rigid fit of
// the bone's vertices after each step, is in the "spiral" column.
//   npm run build && node lab/posing/bench-deformer.mjs [--method akap|arap|mls|cauchy-green]
//     [--set name=value ...] [--guard] [--bones] [vertices ...]
import process from "node:process";
import { performance } from "node:perf_hooks";
import { Deformer, defaultShape, init, triangulate } from "../../www/lib/index.js";

await init();
const args = process.argv.slice(2);
const methodAt = args.indexOf("--method");
const method = methodAt >= 0 ? args.splice(methodAt, 2)[1] : "akap";
const guardAt = args.indexOf("--guard");
const guard = guardAt >= 0;
if (guard) args.splice(guardAt, 1);
const bonesAt = args.indexOf("--bones");
const bones = bonesAt >= 0;
if (bones) args.splice(bonesAt, 1);
const settings = {};
for (let at = args.indexOf("--set"); at >= 0; at = args.indexOf("--set")) {
  const [name, value] = args.splice(at, 2)[1].split("=");
  settings[name] = Number.isNaN(Number(value)) ? value : Number(value);
}
const sizes = args.map(Number).filter((n) => n > 0);
const targets = sizes.length ? sizes : [1000, 5000, 10000, 50000];
const frames = 60;
// Frames stepped before timing starts (the first steps of a fresh deformer run code the
// engine has not optimised yet); their motion continues into the timed frames.
const warmup = 5;

function ringArea(ring) {
  let twice = 0;
  for (let i = 0; i < ring.length; i += 2) {
    const j = (i + 2) % ring.length;
    twice += ring[i] * ring[j + 1] - ring[j] * ring[i + 1];
  }
  return Math.abs(twice) / 2;
}

const stat = (values, q) => {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.round((sorted.length - 1) * q)];
};

const shape = defaultShape();
const area = ringArea(shape.outer) - shape.holes.reduce((s, h) => s + ringArea(h), 0);
console.log(
  `Method ${method}${Object.keys(settings).length ? ` ${JSON.stringify(settings)}` : ""}${guard ? ", guarded (stepWithoutFoldovers)" : ""}${bones ? ", a bone along the arm" : ""}. Milliseconds, median / 95th percentile over ${frames} frames (after ${warmup} untimed); ` +
    "factorisation 1 and 2: step 1's " +
    "(soft constraints) and step 2's (Dirichlet) numeric factorisations.",
);
console.log("");
console.log(
  `| vertices | triangles | handles | setup ms | assembly | factorisation 1 | factorisation 2 | solves | spiral | frame |`,
);
console.log(`|---|---|---|---|---|---|---|---|---|---|`);
for (const target of targets) {
  // Refinement makes about 1.7x the triangles the area bound alone asks for.
  const h = Math.sqrt((1.7 * area) / (2 * target) / (Math.sqrt(3) / 4));
  const mesh = triangulate(shape, { targetEdgeLength: h, maxVertices: 4 * target });
  const p = mesh.positions;
  const feet = [];
  let hand = 0;
  let best = Infinity;
  for (let v = 0; v < mesh.vertexCount; v++) {
    if (p[2 * v + 1] < 0) feet.push(v);
    const d = Math.hypot(p[2 * v] + 0.48, p[2 * v + 1] - 1.2);
    if (d < best) [best, hand] = [d, v];
  }
  const start = performance.now();
  const deformer = new Deformer(mesh.positions, mesh.triangles, { method, ...settings });
  deformer.setHandles([...feet, hand]);
  const setup = performance.now() - start;
  if (bones) layBone(deformer, mesh, hand);
  const velocities = new Float64Array(2 * (feet.length + 1));
  const stages = { assembly: [], soft: [], dirichlet: [], solve: [], integration: [], frame: [], outside: [] };
  // Guarded frames that took more than the one plain step.
  let split = 0;
  for (let f = -warmup; f < frames; f++) {
    const t = (f / frames) * 2 * Math.PI;
    velocities[2 * feet.length] = 0.01 * Math.cos(t);
    velocities[2 * feet.length + 1] = 0.01 * Math.sin(t);
    const t0 = performance.now();
    if (guard) {
      if (deformer.stepWithoutFoldovers(velocities).attempts > 1) split++;
    } else {
      deformer.step(velocities);
    }
    if (f < 0) continue;
    stages.frame.push(performance.now() - t0);
    const timings = deformer.timings();
    stages.assembly.push(timings.assembly);
    stages.soft.push(timings.factorisation - timings.dirichletFactorisation);
    stages.dirichlet.push(timings.dirichletFactorisation);
    stages.solve.push(timings.solve);
    stages.integration.push(timings.integration);
    // The frame's time outside the timed stages: the call and, guarded, the guard's own work.
    const inside = timings.assembly + timings.factorisation + timings.solve + timings.integration;
    stages.outside.push(stages.frame.at(-1) - inside);
  }
  const cell = (k) => `${stat(stages[k], 0.5).toFixed(2)} / ${stat(stages[k], 0.95).toFixed(2)}`;
  const columns = ["assembly", "soft", "dirichlet", "solve", "integration", "frame"].map(cell).join(" | ");
  console.log(
    `| ${mesh.vertexCount} | ${mesh.triangleCount} | ${feet.length + 1} | ${setup.toFixed(0)} | ${columns} |`,
  );
  console.log(`(outside the stages: ${cell("outside")} ms a frame)`);
  if (split > 0) console.log(`(guarded: ${split} of ${frames + warmup} frames were split or clamped)`);
  deformer.free();
}

/**
 * A bone along the arm: from a tenth to 35 hundredths of the way from the hand's vertex
 * toward the shoulder, at (-0.22, 0.78); its ends located in the rest mesh.
 */
function layBone(deformer, mesh, hand) {
  const p = mesh.positions;
  const t = mesh.triangles;
  const along = (s) => [p[2 * hand] + s * (-0.22 - p[2 * hand]), p[2 * hand + 1] + s * (0.78 - p[2 * hand + 1])];
  const locate = ([x, y]) => {
    for (let f = 0; f < t.length / 3; f++) {
      const [a, b, c] = [0, 1, 2].map((k) => [p[2 * t[3 * f + k]], p[2 * t[3 * f + k] + 1]]);
      const area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
      const wa = ((b[0] - x) * (c[1] - y) - (b[1] - y) * (c[0] - x)) / area;
      const wb = ((c[0] - x) * (a[1] - y) - (c[1] - y) * (a[0] - x)) / area;
      if (wa >= 0 && wb >= 0 && wa + wb <= 1) return { f, w: [wa, wb, 1 - wa - wb] };
    }
    throw new Error(`the bone's end (${x}, ${y}) is off the figure`);
  };
  const ends = [locate(along(0.1)), locate(along(0.35))];
  deformer.setBones(
    ends.map((e) => e.f),
    ends.flatMap((e) => e.w),
  );
}
