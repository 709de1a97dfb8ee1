// Issue 16's hostile inputs through the JavaScript API, compiled to wasm, in Node: the
// same cases as `cargo run --release --example adversarial`, each timed once. Building
// the input and the set-up around it (a deformer's factorisation) is not timed.
//   npm run build && node lab/hostile/bench-adversarial.mjs [case ...]
import process from "node:process";
import { performance } from "node:perf_hooks";
import { Deformer, PointMapper, importSvg, init, triangulate } from "../../www/lib/index.js";

await init();

function gridMesh(columns, rows) {
  const positions = [];
  for (let j = 0; j <= rows; j++) for (let i = 0; i <= columns; i++) positions.push(i, j);
  const index = (i, j) => j * (columns + 1) + i;
  const triangles = [];
  for (let j = 0; j < rows; j++) {
    for (let i = 0; i < columns; i++) {
      const [a, b, c, d] = [index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)];
      triangles.push(a, b, c, a, c, d);
    }
  }
  return { positions: new Float64Array(positions), triangles: new Uint32Array(triangles) };
}

function comb(teeth, length) {
  const ring = [];
  for (let i = 0; i < teeth; i++) {
    const y = 2 * i;
    ring.push(i === 0 ? -1 : 0, y, length, y, length, y + 1, i + 1 === teeth ? -1 : 0, y + 1);
  }
  return ring;
}

function circle(n, radius) {
  const ring = [];
  for (let k = 0; k < n; k++) {
    const t = (2 * Math.PI * k) / n;
    ring.push(radius * Math.cos(t), radius * Math.sin(t));
  }
  return ring;
}

const svg = (body) => `<svg xmlns="http://www.w3.org/2000/svg" viewBox="-1 -1 2 2">${body}</svg>`;

function pathOf(ring) {
  const parts = [];
  for (let k = 0; k < ring.length; k += 2) parts.push(`${k === 0 ? "M" : "L"}${ring[k]} ${ring[k + 1]}`);
  return parts.join("") + "Z";
}

const imported = (text) => () => {
  const outlines = importSvg(text);
  const points = outlines.reduce((s, o) => s + o.outer.length / 2 + o.holes.reduce((t, h) => t + h.length / 2, 0), 0);
  return `${outlines.length} outline(s), ${points} points`;
};

const meshed = (outer) => () => `${triangulate({ outer, holes: [] }).positions.length / 2} vertices`;

function arapStep(iterations) {
  const mesh = gridMesh(32, 32);
  let deformer;
  try {
    deformer = new Deformer(mesh.positions, mesh.triangles, { method: "arap", iterations });
  } catch {
    // Refused at construction: time that instead.
    return () => new Deformer(mesh.positions, mesh.triangles, { method: "arap", iterations });
  }
  deformer.setHandles([0, 1088]);
  return () => {
    deformer.step([0, 0, 1, 1]);
    return `${iterations} iterations`;
  };
}

const cases = {
  "svg-closes": () => imported(svg(`<path d="M0 0L1 0L0 1${"Z".repeat(1_600_000)}"/>`)),
  "svg-attributes": () => {
    const attributes = Array.from({ length: 100_000 }, (_, k) => ` a${k}="${k}"`).join("");
    return imported(svg(`<path d="M0 0L1 0L0 1Z"${attributes}/>`));
  },
  "svg-polygons": () => {
    const body = Array.from({ length: 33_000 }, (_, k) => {
      const [x, y] = [(k % 182) * 0.01 - 0.91, Math.floor(k / 182) * 0.01 - 0.91];
      return `<polygon points="${x} ${y} ${x + 0.005} ${y} ${x} ${y + 0.005}"/>`;
    }).join("");
    return imported(svg(body));
  },
  "svg-long-path": () => imported(svg(`<path d="${pathOf(circle(80_000, 0.9))}"/>`)),
  "svg-comb-path": () => imported(svg(`<path d="${pathOf(comb(20_000, 40_000).map((v) => v / 40_000))}"/>`)),
  "outline-circle": () => meshed(circle(100_000, 1)),
  "outline-comb": () => meshed(comb(25_000, 50_000)),
  handles: () => {
    // 99,856 vertices: the bindings refuse meshes beyond their vertex limit (100,000), so
    // this is one grid row short of the native example's 100,489.
    const mesh = gridMesh(315, 315);
    const deformer = new Deformer(mesh.positions, mesh.triangles);
    const vertices = Uint32Array.from({ length: mesh.positions.length / 2 }, (_, k) => k);
    return () => {
      deformer.setHandles(vertices);
      return "set";
    };
  },
  "point-mapper": () => {
    const mesh = gridMesh(100, 100);
    const points = circle(100_000, 80).map((v) => v + 50);
    return () => `${new PointMapper(mesh.positions, mesh.triangles, points).length} points located`;
  },
  "arap-iterations": () => arapStep(1_000_000),
  "arap-most-iterations": () => arapStep(1000),
};

const chosen = process.argv.slice(2);
for (const name of chosen) {
  if (!(name in cases)) {
    console.error(`unknown case ${name}; the cases are ${Object.keys(cases).join(", ")}`);
    process.exit(2);
  }
}
console.log("| case | seconds | outcome |");
console.log("|---|---|---|");
for (const [name, build] of Object.entries(cases)) {
  if (chosen.length && !chosen.includes(name)) continue;
  const run = build();
  const start = performance.now();
  let outcome;
  try {
    outcome = run();
  } catch (e) {
    outcome = `error: ${String(e.message).slice(0, 110)}...`;
  }
  const seconds = (performance.now() - start) / 1000;
  console.log(`| ${name} | ${seconds.toFixed(3)} | ${outcome} |`);
}
