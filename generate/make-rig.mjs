// Makes the rig that www/examples/rig.html ships: Boo the ghost of the gallery meshed to
// about 450 vertices, 5 handles (head, sides, the two outer feet), trained with S-ARAP on
// a TPS basis and a reduced spatial basis of 32 functions (a small file that still poses
// well), written to www/examples/ghost.defop. Deterministic: the same inputs and seed give
// the same bytes, so the committed file can be made again and compared.
//
//   npm run build && node generate/make-rig.mjs [samples]
import { readFileSync, writeFileSync } from "node:fs";
import { performance } from "node:perf_hooks";
import process from "node:process";
import { URL } from "node:url";
import { importSvg, init, trainDefOp, triangulateToVertices } from "../www/lib/index.js";

await init();
const samples = Number(process.argv[2] ?? 120);
const svg = readFileSync(new URL("../www/gallery/ghost.svg", import.meta.url), "utf8");
const [ghost] = importSvg(svg);
const { mesh } = triangulateToVertices(ghost, 450, { minAngle: 28 });
const p = mesh.positions;
let [minX, minY, maxX, maxY] = [Infinity, Infinity, -Infinity, -Infinity];
for (let v = 0; v < mesh.vertexCount; v++) {
  [minX, maxX] = [Math.min(minX, p[2 * v]), Math.max(maxX, p[2 * v])];
  [minY, maxY] = [Math.min(minY, p[2 * v + 1]), Math.max(maxY, p[2 * v + 1])];
}
// Where the handles go, as fractions of the bounding box (y up), each on its nearest vertex.
const spots = [
  [0.5, 0.92],
  [0.06, 0.45],
  [0.94, 0.45],
  [0.12, 0.12],
  [0.88, 0.12],
];
const handles = spots.map(([fx, fy]) => {
  const [x, y] = [minX + fx * (maxX - minX), minY + fy * (maxY - minY)];
  let best = 0;
  for (let v = 1; v < mesh.vertexCount; v++) {
    if (Math.hypot(p[2 * v] - x, p[2 * v + 1] - y) < Math.hypot(p[2 * best] - x, p[2 * best + 1] - y)) best = v;
  }
  return best;
});
const started = performance.now();
const { operator, stats } = await trainDefOp(mesh.positions, mesh.triangles, handles, {
  energy: "sarap",
  basis: "tps",
  samples,
  spatial: 32,
  seed: 1,
});
const bytes = operator.toBytes();
const out = new URL("../www/examples/ghost.defop", import.meta.url);
writeFileSync(out, bytes);
console.log(
  `${mesh.vertexCount} vertices, handles ${handles.join(", ")}, ${samples} samples: ` +
    `${((performance.now() - started) / 1000).toFixed(1)} s, ${stats.redraws} redraws, ` +
    `${bytes.length} bytes -> ${out.pathname}`,
);
