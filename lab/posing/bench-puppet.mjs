// Frame time of a layered puppet against one shape of the same size, compiled to wasm, in
// Node. The test character (tests/fixtures/svg/layered-puppet.svg: a torso, a head over its
// top, an arm over its shoulder, a hat apart) is read three ways at about the same vertex
// count:
//   puppet  importPuppet: four sheets, joined at the neck and the shoulder;
//   sheets  the same sheets without joints (what the joints cost: the difference);
//   shape   importSvg: the character's outline as one shape (the hat, apart, left out),
//           meshed to the puppet's vertex count.
// Each is dragged the same way: two handles pin the torso's bottom, one on the hand moves
// along a circle; one step a frame. Runs are interleaved (puppet, sheets, shape, repeated)
// on this noisy machine, after one untimed round; prints the set-up (orders, analyses) and the frame time, median
// and 95th percentile over every timed frame of every round, and the ratios.
//   npm run build && node lab/posing/bench-puppet.mjs [--method akap|arap] [--rounds N] [vertices ...]
import { readFileSync } from "node:fs";
import process from "node:process";
import { URL } from "node:url";
import { performance } from "node:perf_hooks";
import { Deformer, importPuppet, importSvg, init, triangulateToVertices } from "../../www/lib/index.js";

await init();
const args = process.argv.slice(2);
const take = (flag, fallback) => {
  const at = args.indexOf(flag);
  return at >= 0 ? args.splice(at, 2)[1] : fallback;
};
const method = take("--method", "akap");
const rounds = Number(take("--rounds", "5"));
const sizes = args.map(Number).filter((n) => n > 0);
const targets = sizes.length ? sizes : [2000, 10000];
const frames = 60;
const warmup = 5;
const svg = readFileSync(new URL("../../tests/fixtures/svg/layered-puppet.svg", import.meta.url), "utf8");

const stat = (values, q) => {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.round((sorted.length - 1) * q)];
};

/** The vertex nearest to (x, y) among `vertices` (all when left out). */
function nearest(positions, x, y, vertices) {
  let best = Infinity;
  let found = -1;
  for (const v of vertices ?? Array.from({ length: positions.length / 2 }, (_, k) => k)) {
    const d = Math.hypot(positions[2 * v] - x, positions[2 * v + 1] - y);
    if (d < best) [best, found] = [d, v];
  }
  return found;
}

function partVertices(puppet, k) {
  const set = new Set();
  for (const t of puppet.parts[k].triangles) for (let c = 0; c < 3; c++) set.add(puppet.triangles[3 * t + c]);
  return [...set];
}

/** Set-up and frame times of one run: `positions`, `triangles`, the deformer's options and
 * the handles' vertices (two pins, then the hand). */
function run(positions, triangles, options, handles) {
  const start = performance.now();
  const deformer = new Deformer(positions, triangles, { method, ...options });
  const setup = performance.now() - start;
  deformer.setHandles(handles);
  const velocities = new Float64Array(2 * handles.length);
  const times = [];
  for (let f = -warmup; f < frames; f++) {
    const t = (f / frames) * Math.PI;
    // Up and round over the shoulder: 0.6 units a frame of a 200-unit drawing.
    velocities[4] = -0.6 * Math.sin(t);
    velocities[5] = 0.6 * Math.cos(t);
    const t0 = performance.now();
    deformer.step(velocities);
    if (f >= 0) times.push(performance.now() - t0);
  }
  deformer.free();
  return { setup, times };
}

console.log(
  `Method ${method}: ${rounds} interleaved rounds of ${frames} frames (after ${warmup} untimed) each; ` +
    "milliseconds, median / 95th percentile over every timed frame.",
);
console.log("");
console.log("| vertices | run | set-up ms (median) | frame ms | frame ratio to shape (median / p95) |");
console.log("|---|---|---|---|---|");
for (const target of targets) {
  const puppet = importPuppet(svg, { vertices: target });
  const n = puppet.positions.length / 2;
  const torso = partVertices(puppet, 0);
  const arm = partVertices(puppet, 2);
  // In the drawing's coordinates (y up): the torso spans x 60..140, y 80..200; the hand
  // ends at x 200, y 165..195.
  const puppetHandles = [
    nearest(puppet.positions, 70, 85, torso),
    nearest(puppet.positions, 130, 85, torso),
    nearest(puppet.positions, 197, 180, arm),
  ];
  const [outline] = importSvg(svg);
  const { mesh: shape } = triangulateToVertices(outline, n);
  const shapeHandles = [
    nearest(shape.positions, 70, 85),
    nearest(shape.positions, 130, 85),
    nearest(shape.positions, 197, 180),
  ];
  const kinds = {
    puppet: () =>
      run(puppet.positions, puppet.triangles, { parts: puppet.parts, joints: puppet.joints }, puppetHandles),
    sheets: () => run(puppet.positions, puppet.triangles, { parts: puppet.parts, joints: [] }, puppetHandles),
    shape: () => run(shape.positions, shape.triangles, {}, shapeHandles),
  };
  const results = Object.fromEntries(Object.keys(kinds).map((k) => [k, { setup: [], times: [] }]));
  // One untimed round first: the engine compiles and optimises the code on its first runs.
  for (let r = -1; r < rounds; r++) {
    for (const [kind, go] of Object.entries(kinds)) {
      const { setup, times } = go();
      if (r < 0) continue;
      results[kind].setup.push(setup);
      results[kind].times.push(...times);
    }
  }
  const base = results.shape.times;
  for (const [kind, { setup, times }] of Object.entries(results)) {
    const vertices = kind === "shape" ? shape.vertexCount : n;
    const ratio = `${(stat(times, 0.5) / stat(base, 0.5)).toFixed(2)} / ${(stat(times, 0.95) / stat(base, 0.95)).toFixed(2)}`;
    console.log(
      `| ${vertices} | ${kind} | ${stat(setup, 0.5).toFixed(1)} | ${stat(times, 0.5).toFixed(2)} / ${stat(times, 0.95).toFixed(2)} | ${ratio} |`,
    );
  }
}
