// Runs the wasm Cholesky benchmark (src/wasm_bench.rs) in Node and prints a markdown table.
// Usage: node lab/sparse/bench-wasm.mjs [--pkg target/bench-pkg] [--max-vertices N]
//          [--min-vertices N] [--shape bar|gingerbread] [--repeats N] [--ordering amd|best]
// `--ordering best` orders ours as the deformer does (AMD, or from 12000 vertices nested
// dissection when it needs fewer flops); the default is AMD.
// Built by lab/sparse/bench-wasm.sh (wasm-pack --target nodejs, CommonJS output).
import { createRequire } from "node:module";
import path from "node:path";
import process from "node:process";

const args = process.argv.slice(2);
const option = (name, fallback) => {
  const i = args.indexOf(name);
  return i >= 0 && i + 1 < args.length ? args[i + 1] : fallback;
};
const pkg = path.resolve(option("--pkg", "target/bench-pkg"));
const maxVertices = Number(option("--max-vertices", "100000"));
const minVertices = Number(option("--min-vertices", "0"));
const shapes = option("--shape", "") ? [option("--shape", "")] : ["bar", "gingerbread"];
const fixedRepeats = option("--repeats", "");
const ordering = option("--ordering", "amd");
const sizes = [1000, 5000, 10000, 50000, 100000].filter((s) => s >= minVertices && s <= maxVertices);
const defaultRepeats = (size) => (size <= 10000 ? 15 : size <= 50000 ? 7 : 5);

const require = createRequire(import.meta.url);
const wasm = require(path.join(pkg, "akap.js"));

const fixed = (x, digits) => (x === null || x === undefined ? "n/a" : x.toFixed(digits));
console.log(`wasm build: ${pkg} (simd128: ${wasm.bench_simd128() ? "on" : "off"}), node ${process.version}`);
console.log(`ours ordered by: ${ordering}`);
console.log("");
console.log(
  "| matrix | vertices | n | nnz(L) ours | nnz(L) faer | ours sym ms | ours num ms | ours solve ms " +
    "| faer sym ms | faer sn num ms | faer simpl num ms | faer solve ms | ours / faer sn num | check | reps |",
);
console.log("|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|");
let failed = false;
for (const size of sizes) {
  for (const shape of shapes) {
    for (const dirichlet of [false, true]) {
      const repeats = fixedRepeats ? Number(fixedRepeats) : defaultRepeats(size);
      const r = JSON.parse(wasm.bench_cholesky(size, shape, dirichlet, repeats, ordering));
      if (r.error) {
        failed = true;
        console.log(`| ${r.label} | ${r.vertices} | ${r.n} | **error: ${r.error}** |`);
        continue;
      }
      const agree = r.differenceFromFaer !== null && r.differenceFromFaer < 1e-8;
      failed ||= !agree;
      const check = agree ? r.differenceFromFaer.toExponential(0) : `**MISMATCH** ${r.differenceFromFaer}`;
      console.log(
        `| ${r.label} | ${r.vertices} | ${r.n} | ${r.nnzL} | ${r.faerNnzL} | ${fixed(r.oursSymbolicMs, 2)} ` +
          `| ${fixed(r.oursNumericMs, 2)} | ${fixed(r.oursSolveMs, 3)} | ${fixed(r.faerSymbolicMs, 2)} ` +
          `| ${fixed(r.faerNumericMs, 2)} | ${fixed(r.faerSimplicialMs, 2)} | ${fixed(r.faerSolveMs, 3)} ` +
          `| **${fixed(r.oursNumericMs / r.faerNumericMs, 2)}** | ${check} | ${repeats} |`,
      );
    }
  }
}
if (failed) {
  console.error("bench-wasm: a factorisation failed or disagreed with faer");
  process.exitCode = 1;
}
