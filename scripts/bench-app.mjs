/* global requestAnimationFrame */
// Frame times of the posing app in headless Chromium: for each mesh size, pin a foot,
// drag the raised hand along a quarter circle with the mouse, and collect the widget's
// per-frame work (solver steps and drawing) from its `akap-pose` events.
// Prints median, 95th percentile and worst frame, and the solver stages at the median.
//   npm run build && node scripts/bench-app.mjs [vertices ...]
import { spawn } from "node:child_process";
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
