// DefOp evaluation alone, in wasm, in Node, on one thread: no training. The operator files
// come from the native example (the paper's octopus size: about 2,000 vertices, 9 handles,
// TPS on 1000 samples; hat basis and reduced basis of 100):
//   cargo run --release --example defop_eval -- --write target/defop-bench
//   node lab/defop/bench-defop-eval.mjs [--lib www/lib]... [--rounds 7] [--ms 300] [files...]
// Each round times `evaluateInto` (Float64Array out) and `evaluateIntoF32` (Float32Array
// out) of every file for about `--ms` milliseconds each. With several `--lib` directories
// (copies of www/lib with their www/pkg beside them, e.g. an old and a new build) the rounds
// alternate between them, so that a noisy machine slows both alike; the table gives the
// median over rounds and the fastest round. With `--rust target/bench-pkg` (the `bench`
// build of lab/sparse/bench-wasm.sh) it also times, from Rust inside wasm, the double
// evaluation against the operator's single-precision copy (`Operator::single_precision`),
// which the JavaScript API does not expose.
import { readFileSync } from "node:fs";
import { createRequire } from "node:module";
import path from "node:path";
import process from "node:process";
import { performance } from "node:perf_hooks";
import { pathToFileURL } from "node:url";

const args = process.argv.slice(2);
const libs = [];
const files = [];
let rust;
let rounds = 7;
let ms = 300;
for (let i = 0; i < args.length; i++) {
  if (args[i] === "--lib") libs.push(args[++i]);
  else if (args[i] === "--rounds") rounds = Number(args[++i]);
  else if (args[i] === "--ms") ms = Number(args[++i]);
  else if (args[i] === "--rust") rust = args[++i];
  else files.push(args[i]);
}
if (libs.length === 0) libs.push("www/lib");
if (files.length === 0) files.push("target/defop-bench/reduced.defop", "target/defop-bench/hat.defop");

const builds = [];
for (const lib of libs) {
  const api = await import(pathToFileURL(path.resolve(lib, "index.js")).href);
  await api.init();
  const operators = files.map((file) => {
    const bytes = new Uint8Array(readFileSync(file));
    const { rest } = api.readOperatorFile(bytes);
    // Targets near the rest pose, as a drag would give them.
    const queries = Array.from({ length: 64 }, (_, k) =>
      Float64Array.from(rest, (x, i) => x + 0.05 * Math.sin(k + 1.7 * i)),
    );
    const op = api.DefOp.fromBytes(bytes);
    return { file: path.basename(file), op, queries };
  });
  builds.push({ lib, operators });
}

/** Milliseconds per call of `evaluate(q)` over the queries, for about `ms` milliseconds. */
function time(queries, evaluate) {
  for (const q of queries) evaluate(q); // warm up
  let calls = 0;
  const t0 = performance.now();
  let t = t0;
  while (t - t0 < ms) {
    for (const q of queries) evaluate(q);
    calls += queries.length;
    t = performance.now();
  }
  return (t - t0) / calls;
}

const results = new Map();
const record = (key, value) => (results.get(key) ?? results.set(key, []).get(key)).push(value);
for (let round = 0; round < rounds; round++) {
  // Alternate the order of the builds from round to round too.
  const order = round % 2 === 0 ? builds : [...builds].reverse();
  for (const { lib, operators } of order) {
    for (const { file, op, queries } of operators) {
      const out = new Float64Array(2 * op.vertexCount);
      const out32 = new Float32Array(2 * op.vertexCount);
      record(
        `${lib}|${file}|f64`,
        time(queries, (q) => op.evaluateInto(q, out)),
      );
      record(
        `${lib}|${file}|f32`,
        time(queries, (q) => op.evaluateIntoF32(q, out32)),
      );
    }
  }
}

console.log(`node ${process.version}, ${rounds} rounds of ${ms} ms per build, file and precision`);
console.log("");
console.log("| build | operator | output | median ms/eval | evaluations/s | fastest ms/eval |");
console.log("|---|---|---|--:|--:|--:|");
for (const [key, values] of results) {
  const [lib, file, precision] = key.split("|");
  const sorted = [...values].sort((a, b) => a - b);
  const median = sorted[Math.floor(sorted.length / 2)];
  console.log(
    `| ${lib} | ${file} | ${precision} | ${median.toFixed(4)} | ${Math.round(1000 / median)} | ${sorted[0].toFixed(4)} |`,
  );
}
for (const { operators } of builds) for (const { op } of operators) op.free();

if (rust) {
  const wasm = createRequire(import.meta.url)(path.resolve(rust, "akap.js"));
  console.log("");
  console.log(`From Rust in wasm (${rust}): double evaluation and the single-precision copy`);
  console.log("");
  console.log(
    "| operator | double median ms | double evaluations/s | single median ms | single evaluations/s | single copy MB | single − double / diagonal |",
  );
  console.log("|---|--:|--:|--:|--:|--:|--:|");
  for (const file of files) {
    const r = JSON.parse(wasm.bench_defop_eval(new Uint8Array(readFileSync(file)), rounds, ms));
    console.log(
      `| ${path.basename(file)} | ${r.doubleMedianMs.toFixed(4)} | ${Math.round(1000 / r.doubleMedianMs)} | ${r.singleMedianMs.toFixed(4)} | ${Math.round(1000 / r.singleMedianMs)} | ${(r.singleBytes / 1e6).toFixed(1)} | ${r.singleDifference.toExponential(1)} |`,
    );
  }
}
