// SVG import speed in wasm under Node: the gallery's SVGs and a 1 MB drawing (the gallery's
// cat tiled until the text passes 1 MB), median of several runs each, with strokes (the
// default) and fills only. `--before DIR` times another build's www/pkg in the same run
// (e.g. a worktree of an older commit), interleaved, and prints both.
// Usage: node lab/svg/bench-svg.mjs [--before ../old/www/pkg] [--repeats N]
import { readFileSync } from "node:fs";
import path from "node:path";
import process from "node:process";
import { performance } from "node:perf_hooks";
import { fileURLToPath } from "node:url";

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), "../..");
const args = process.argv.slice(2);
const option = (name, fallback) => {
  const i = args.indexOf(name);
  return i >= 0 && i + 1 < args.length ? args[i + 1] : fallback;
};
const repeats = Number(option("--repeats", "9"));

async function load(dir) {
  const module = await import(path.join(path.resolve(dir), "akap.js"));
  module.initSync({ module: readFileSync(path.join(path.resolve(dir), "akap_bg.wasm")) });
  return module;
}

const builds = [["this build", await load(path.join(root, "www/pkg"))]];
if (option("--before", "")) builds.unshift(["before", await load(option("--before", ""))]);

const gallery = ["cat", "donut", "ghost"].map((name) => [
  `${name}.svg`,
  readFileSync(path.join(root, "www/gallery", `${name}.svg`), "utf8"),
]);
// The cat's drawing inside its root element, tiled on a grid 200 units apart.
const cat = gallery[0][1];
const inner = cat.slice(cat.indexOf(">", cat.indexOf("<svg")) + 1, cat.lastIndexOf("</svg>"));
const tiles = [];
let size = 0;
for (let k = 0; size < 1 << 20; k++) {
  const tile = `<g transform="translate(${(k % 40) * 200} ${Math.floor(k / 40) * 200})">${inner}</g>\n`;
  tiles.push(tile);
  size += tile.length;
}
const big = `<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 8000 ${Math.ceil(tiles.length / 40) * 200}">\n${tiles.join("")}</svg>`;
const files = [...gallery, [`${tiles.length} cats, ${(big.length / 1e6).toFixed(2)} MB`, big]];

const median = (xs) => xs.sort((a, b) => a - b)[Math.floor(xs.length / 2)];
console.log(`node ${process.version}, median of ${repeats} runs, ms per import`);
console.log("");
// An older build may not know the strokes option (before usvg it imported fills only): it
// gets one column.
const older = builds.length > 1;
const columns = builds.flatMap(([name], b) =>
  older && b === 0 ? [`${name} (fills only)`] : [name, `${name}, fills only`],
);
console.log(`| file | ${columns.join(" | ")} |`);
console.log(`|---|${columns.map(() => "--:").join("|")}|`);
for (const [name, text] of files) {
  const times = builds.map((_, b) => (older && b === 0 ? [[]] : [[], []]));
  for (let r = 0; r < repeats; r++) {
    builds.forEach(([, wasm], b) => {
      (older && b === 0 ? [undefined] : [true, false]).forEach((strokes, s) => {
        const options = strokes === undefined ? { maxPoints: 1e7 } : { strokes, maxPoints: 1e7 };
        const start = performance.now();
        let failure;
        try {
          wasm.import_svg(text, options);
        } catch (e) {
          failure = e.message;
        }
        times[b][s].push(performance.now() - start);
        if (r === 0 && failure !== undefined) console.error(`${name}: ${failure}`);
      });
    });
  }
  const cells = times.flat().map((t) => median(t).toFixed(2));
  console.log(`| ${name} | ${cells.join(" | ")} |`);
}
