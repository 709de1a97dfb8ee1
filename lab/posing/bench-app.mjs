/* global requestAnimationFrame, navigator, performance */
// Frame times of the posing app in headless Chromium: for each mesh size, pin a foot,
// drag the raised hand along a quarter circle with the mouse, and collect the widget's
// per-frame work (solver steps and drawing) from its `akap-pose` events.
// Prints median, 95th percentile and worst frame, and the solver stages at the median.
//   npm run build && node lab/posing/bench-app.mjs [vertices ...]
// With --defop MANIFEST (written by `cargo run --release --example defop_table`): the
// table's octopus (about 2,000 vertices, 9 handles) opened as a rig, trained again in the
// page (its options, 1,000 samples, no cache) on 1 worker and on one per core, then posed
// by a tentacle dragged along a quarter circle: training times, whole-frame median and p95
// and the rig's evaluation time. With --frames-only, the rig from the table poses without
// training again (the frames alone: to compare builds).
//   node lab/posing/bench-app.mjs --defop target/defop-table/manifest.json [--frames-only]
// With --rig [VERTICES] [--spatial K] [--samples M]: no manifest; the app's figure meshed to
// about VERTICES (default 2000) with five handles (both feet, both hands, the head), a rig
// trained in the page (ARAP, M samples, default 60; the widget's spatial basis, 100, or K;
// 0 is the hat basis), then posed by a hand dragged along an arc: the rig's frames on the
// GPU (WebGL2: the CPU computes only the rig's frame), whole-frame median and p95 and the
// CPU time of the rig's evaluation per frame, beside the operator's whole evaluation on
// the CPU (`evaluateInto`, double precision) timed alone in a page.
//   node lab/posing/bench-app.mjs --rig 2000
import { spawn } from "node:child_process";
import { readFileSync } from "node:fs";
import process from "node:process";
import { chromium } from "@playwright/test";

const sizes = process.argv
  .slice(2)
  .map(Number)
  .filter((n) => n > 0);
const targets = sizes.length ? sizes : [1000, 5000, 10000];
const port = Number(process.env.BENCH_PORT ?? 4391);
const moves = 150;

const server = spawn(
  "node_modules/.bin/vite",
  ["preview", "--host", "127.0.0.1", "--port", String(port), "--strictPort"],
  {
    stdio: ["ignore", "pipe", "inherit"],
  },
);
await new Promise((resolve, reject) => {
  server.stdout.on("data", (d) => String(d).includes(String(port)) && resolve());
  server.on("exit", (code) => reject(new Error(`vite preview exited with ${code}`)));
});

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM_PATH ?? "/usr/bin/chromium",
  args: [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
  ],
});
const stat = (values, q) => {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.min(sorted.length - 1, Math.round((sorted.length - 1) * q))];
};
const ms = (x) => x.toFixed(1);

/** Pins nothing new: drags handle `index` of the app's widget along a quarter circle about the shape's centre. */
async function dragAround(page, index) {
  const setup = await page.evaluate((index) => {
    const w = window.akapDemo.widget;
    const h = w.handlePositions();
    const p = w.mesh.positions;
    let [cx, cy] = [0, 0];
    for (let v = 0; v < p.length / 2; v++) [cx, cy] = [cx + p[2 * v], cy + p[2 * v + 1]];
    const n = p.length / 2;
    window.benchFrames = [];
    document.getElementById("app").addEventListener("akap-pose", (e) => {
      if (e.detail.steps > 0) window.benchFrames.push({ ms: e.detail.frameMs, evaluation: e.detail.evaluationMs });
    });
    return { view: w.view, grab: [h[2 * index], h[2 * index + 1]], centre: [cx / n, cy / n] };
  }, index);
  const box = await page.locator("canvas.overlay").boundingBox();
  const { view } = setup;
  const css = ([x, y]) => [
    box.x + (view.offsetX + view.scale * x) / view.pixelRatio,
    box.y + (view.offsetY - view.scale * y) / view.pixelRatio,
  ];
  const [gx, gy] = css(setup.grab);
  const [ox, oy] = css(setup.centre);
  await page.mouse.move(gx, gy);
  await page.mouse.down();
  // A small arc (an eighth of a turn scaled to a third of the radius), one move per frame.
  const [dx, dy] = [gx - ox, gy - oy];
  for (let k = 1; k <= moves; k++) {
    const a = ((Math.PI / 4) * k) / moves;
    const [c, s] = [Math.cos(a), Math.sin(a)];
    const [rx, ry] = [c * dx - s * dy, s * dx + c * dy];
    await page.mouse.move(gx + (rx - dx) / 3, gy + (ry - dy) / 3);
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => r())));
  }
  await page.mouse.up();
  await page.evaluate(() => window.akapDemo.widget.whenIdle());
  return page.evaluate(() => window.benchFrames);
}

/** `evaluateInto` of the rig's operator, timed alone over a second in a page of its own (ms per call). */
async function evaluationAlone(rigBytes) {
  const plain = await browser.newPage();
  await plain.goto(`http://127.0.0.1:${port}/www/examples/rig.html`);
  await plain.waitForFunction(() => document.body.dataset.ready === "true");
  const alone = await plain.evaluate((bytes) => {
    const op = window.akap.DefOp.fromBytes(Uint8Array.from(bytes));
    const out = new Float64Array(2 * op.vertexCount);
    const targets = Array.from({ length: 16 }, (_, k) =>
      Float64Array.from({ length: 2 * op.handleCount }, (_, i) => 0.05 * Math.sin(k + i)),
    );
    let calls = 0;
    const started = performance.now();
    while (performance.now() - started < 1000) {
      for (const t of targets) op.evaluateInto(t, out);
      calls += targets.length;
    }
    return (performance.now() - started) / calls;
  }, rigBytes);
  await plain.close();
  return alone;
}

/**
 * A rig frame's CPU time alone (`Deformer.advance` to new targets, ms per call, timed over a
 * second in a page of its own), the rig on the GPU (its frame, with the outline's and the
 * handles' triangles' vertices watched, as the widget watches them) or on the CPU.
 */
async function frameAlone(rigBytes, onGpu) {
  const plain = await browser.newPage();
  await plain.goto(`http://127.0.0.1:${port}/www/examples/rig.html`);
  await plain.waitForFunction(() => document.body.dataset.ready === "true");
  const alone = await plain.evaluate(
    ({ bytes, onGpu }) => {
      const { DefOp, Deformer } = window.akap;
      const op = DefOp.fromBytes(Uint8Array.from(bytes));
      const mesh = op.mesh();
      const d = new Deformer(mesh.positions, mesh.triangles);
      const { triangles, barycentric } = op.handlePoints();
      d.setHandlePoints(triangles, barycentric);
      d.setRig(op);
      if (onGpu) {
        if (!d.setRigOnGpu(true)) throw new Error("the rig did not go on the GPU");
        const watched = new Set(mesh.boundaryEdges);
        for (const t of triangles) for (let k = 0; k < 3; k++) watched.add(mesh.triangles[3 * t + k]);
        d.watchRigVertices(Uint32Array.from(watched));
      }
      const rest = d.targets();
      const targets = Array.from({ length: 16 }, (_, k) =>
        Float64Array.from(rest, (x, i) => x + 0.05 * Math.sin(k + i)),
      );
      let calls = 0;
      const started = performance.now();
      while (performance.now() - started < 1000) {
        for (const t of targets) {
          d.setTargets(t);
          d.advance();
        }
        calls += targets.length;
      }
      return (performance.now() - started) / calls;
    },
    { bytes: rigBytes, onGpu },
  );
  await plain.close();
  return alone;
}

/** The frames' table: whole frames and the rig's evaluation (CPU). */
function rigFrames(frames) {
  const times = frames.map((f) => f.ms);
  const evaluations = frames.map((f) => f.evaluation).filter((e) => e !== undefined);
  console.log("| frames | frame median ms | frame p95 ms | worst ms | evaluation median ms | evaluation p95 ms |");
  console.log("|---|---|---|---|---|---|");
  console.log(
    `| ${frames.length} | ${ms(stat(times, 0.5))} | ${ms(stat(times, 0.95))} | ${ms(Math.max(...times))} | ` +
      `${stat(evaluations, 0.5).toFixed(3)} | ${stat(evaluations, 0.95).toFixed(3)} |`,
  );
}

if (process.argv[2] === "--rig") {
  const flag = (name, fallback) => {
    const at = process.argv.indexOf(name);
    return at > 0 ? Number(process.argv[at + 1]) : fallback;
  };
  const vertices = Number(process.argv[3]) > 0 ? Number(process.argv[3]) : 2000;
  const spatial = flag("--spatial", undefined);
  const samples = flag("--samples", 60);
  try {
    const page = await browser.newPage({ viewport: { width: 1000, height: 800 } });
    await page.goto(`http://127.0.0.1:${port}/?hud=false&vertices=${vertices}`);
    await page.waitForFunction(() => document.body.dataset.ready === "true");
    const options = { energy: "arap", samples, seed: 1, cache: false, ...(spatial === undefined ? {} : { spatial }) };
    const model = await page.evaluate(async (options) => {
      const w = window.akapDemo.widget;
      const { positions: p, triangles: t } = w.mesh;
      const centroid = (f) =>
        [0, 1].map((c) => (p[2 * t[3 * f] + c] + p[2 * t[3 * f + 1] + c] + p[2 * t[3 * f + 2] + c]) / 3);
      // Both feet (the lowest triangles left and right of the middle), both hands (leftmost,
      // rightmost), the head (highest).
      const count = t.length / 3;
      const xs = Array.from({ length: count }, (_, f) => centroid(f)[0]);
      const middle = (Math.min(...xs) + Math.max(...xs)) / 2;
      const best = (score) => {
        let at = 0;
        for (let f = 1; f < count; f++) if (score(f) > score(at)) at = f;
        return centroid(at);
      };
      const picks = [
        best((f) => (xs[f] < middle ? -centroid(f)[1] : -Infinity)),
        best((f) => (xs[f] >= middle ? -centroid(f)[1] : -Infinity)),
        best((f) => -xs[f]),
        best((f) => xs[f]),
        best((f) => centroid(f)[1]),
      ];
      for (const [x, y] of picks) w.addHandleAt(x, y);
      const started = performance.now();
      await w.train(options);
      const seconds = (performance.now() - started) / 1000;
      w.setMethod("defop");
      return { vertices: w.vertexCount, handles: w.handleCount, seconds, training: w.rig };
    }, options);
    console.log(
      `Chromium ${browser.version()}; the figure, ${model.vertices} vertices, ${model.handles} handles; ` +
        `rig trained in the page in ${model.seconds.toFixed(1)} s (${JSON.stringify(options)}, spatial ` +
        `${spatial ?? "the widget's default"})`,
    );
    const rigBytes = await page.evaluate(() => Array.from(window.akapDemo.widget.rigFile()));
    // The drag with the rig on the GPU (the app's default), then in a page that poses rigs on
    // the CPU (?gpu=false), the rig opened from its file.
    for (const gpu of [true, false]) {
      const posing = gpu ? page : await browser.newPage({ viewport: { width: 1000, height: 800 } });
      if (!gpu) {
        await posing.goto(`http://127.0.0.1:${port}/?hud=false&gpu=false`);
        await posing.waitForFunction(() => document.body.dataset.ready === "true");
        await posing.evaluate((bytes) => window.akapDemo.widget.loadRig(Uint8Array.from(bytes)), rigBytes);
      }
      const frames = await dragAround(posing, 3);
      const drawn = await posing.evaluate(() => window.akapDemo.widget.rigGpuReadback()?.drawn ?? false);
      console.log(
        `\nThe rig ${gpu ? "on the GPU" : "on the CPU (?gpu=false)"}; frames drawn from the rig's frame: ${drawn}`,
      );
      rigFrames(frames);
    }
    console.log("\nPer frame, alone (advance to new targets, over a second; performance.now() is coarse in a page):");
    console.log(`- the rig on the GPU (its frame): ${(await frameAlone(rigBytes, true)).toFixed(4)} ms`);
    console.log(`- the rig on the CPU (the whole pose, f64): ${(await frameAlone(rigBytes, false)).toFixed(4)} ms`);
    console.log(`- evaluateInto alone (f64): ${(await evaluationAlone(rigBytes)).toFixed(4)} ms`);
  } finally {
    await browser.close();
    server.kill();
  }
  process.exit(0);
}

if (process.argv[2] === "--defop") {
  const entries = JSON.parse(readFileSync(process.argv[3], "utf8"));
  const entry = entries.find((e) => e.model === "octopus" && e.basis === "TPS");
  if (!entry) throw new Error(`no TPS octopus in ${process.argv[3]}`);
  const bytes = Array.from(readFileSync(entry.file));
  const { samples, spatial, radius, energy } = entry.training;
  const options = { energy: energy === "s-arap" ? "sarap" : energy, spatial, samples: 1000, seed: 1 };
  if (radius !== null) options.radius = radius;
  try {
    const page = await browser.newPage({ viewport: { width: 1000, height: 800 } });
    await page.goto(`http://127.0.0.1:${port}/?hud=false`);
    await page.waitForFunction(() => document.body.dataset.ready === "true");
    const cores = await page.evaluate(() => navigator.hardwareConcurrency);
    const model = await page.evaluate(async (bytes) => {
      const w = window.akapDemo.widget;
      await w.loadRig(Uint8Array.from(bytes));
      return { vertices: w.vertexCount, handles: w.handleCount };
    }, bytes);
    console.log(
      `Chromium ${browser.version()}, ${cores} cores; octopus ${model.vertices} vertices, ${model.handles} handles, ` +
        `table options ${JSON.stringify(options)} (table: ${samples} samples)`,
    );
    const train = !process.argv.includes("--frames-only");
    if (train) console.log("| workers | training s |");
    if (train) console.log("|---|---|");
    for (const workers of train ? [...new Set([1, cores])] : []) {
      const seconds = await page.evaluate(
        async ({ options, workers }) => {
          const started = performance.now();
          await window.akapDemo.widget.train({ ...options, workers, cache: false });
          return (performance.now() - started) / 1000;
        },
        { options, workers },
      );
      console.log(`| ${workers} | ${seconds.toFixed(1)} |`);
    }
    // The trained operator's evaluation alone, timed over a second in a page of its own.
    const rigBytes = await page.evaluate(() => Array.from(window.akapDemo.widget.rigFile()));
    console.log(`evaluateInto alone in the page: ${(await evaluationAlone(rigBytes)).toFixed(3)} ms`);
    await page.evaluate(() => window.akapDemo.widget.setMethod("defop"));
    rigFrames(await dragAround(page, 1));
  } finally {
    await browser.close();
    server.kill();
  }
  process.exit(0);
}

console.log(`Chromium ${browser.version()}, ${moves} pointer moves per run`);
console.log(
  "| vertices | frames | steps/frame | frame median ms | frame p95 ms | worst ms | assembly | factorisation | solve | spiral |",
);
console.log("|---|---|---|---|---|---|---|---|---|---|");
try {
  for (const target of targets) {
    const page = await browser.newPage({ viewport: { width: 1000, height: 800 } });
    await page.goto(`http://127.0.0.1:${port}/?hud=false&vertices=${target}`);
    await page.waitForFunction(() => document.body.dataset.ready === "true");
    const setup = await page.evaluate(() => {
      const w = window.akapDemo.widget;
      const { positions: p, triangles: t } = w.mesh;
      const centroid = (f) =>
        [0, 1].map((c) => (p[2 * t[3 * f] + c] + p[2 * t[3 * f + 1] + c] + p[2 * t[3 * f + 2] + c]) / 3);
      let low = 0;
      let high = 0;
      for (let f = 0; f < t.length / 3; f++) {
        if (centroid(f)[1] < centroid(low)[1]) low = f;
        if (centroid(f)[1] > centroid(high)[1]) high = f;
      }
      window.benchFrames = [];
      document.getElementById("app").addEventListener("akap-pose", (e) => {
        if (e.detail.steps > 0)
          window.benchFrames.push({ ms: e.detail.frameMs, steps: e.detail.steps, t: e.detail.timings });
      });
      return { vertices: w.vertexCount, view: w.view, pin: centroid(low), grab: centroid(high) };
    });
    const box = await page.locator("canvas.overlay").boundingBox();
    const { view } = setup;
    const css = ([x, y]) => [
      box.x + (view.offsetX + view.scale * x) / view.pixelRatio,
      box.y + (view.offsetY - view.scale * y) / view.pixelRatio,
    ];
    const pin = css(setup.pin);
    const grab = css(setup.grab);
    await page.mouse.click(pin[0], pin[1]);
    await page.mouse.move(grab[0], grab[1]);
    await page.mouse.down();
    // A quarter circle around the pin, one pointer move per animation frame.
    const [dx, dy] = [grab[0] - pin[0], grab[1] - pin[1]];
    for (let k = 1; k <= moves; k++) {
      const a = ((Math.PI / 2) * k) / moves;
      const [c, s] = [Math.cos(a), Math.sin(a)];
      await page.mouse.move(pin[0] + c * dx - s * dy, pin[1] + s * dx + c * dy);
      await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => r())));
    }
    await page.mouse.up();
    await page.evaluate(() => window.akapDemo.widget.whenIdle());
    const frames = await page.evaluate(() => window.benchFrames);
    const times = frames.map((f) => f.ms);
    const median = stat(times, 0.5);
    const at = frames.find((f) => f.ms === median) ?? frames[0];
    const steps = frames.reduce((s, f) => s + f.steps, 0) / frames.length;
    console.log(
      `| ${setup.vertices} | ${frames.length} | ${steps.toFixed(2)} | ${ms(median)} | ${ms(stat(times, 0.95))} | ${ms(Math.max(...times))} | ` +
        `${ms(at.t.assembly)} | ${ms(at.t.factorisation)} | ${ms(at.t.solve)} | ${ms(at.t.integration)} |`,
    );
    await page.close();
  }
} finally {
  await browser.close();
  server.kill();
}
