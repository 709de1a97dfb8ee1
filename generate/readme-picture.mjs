// The README's first picture, docs/images/puppet.png: the gallery's layered magician posed
// as a puppet in the app (his front arm raised high, his back arm swung out), each
// part drawn in its own layer, the coat once hidden under the arm showing.
//   npm run build && node generate/readme-picture.mjs [OUTPUT]
// Drives the built app (dist, served by vite preview) in headless Chromium through the
// pointer, as a user would: pins on the torso and legs, then each hand dragged round its
// shoulder. The picture is the widget's own PNG export.
import { spawn } from "node:child_process";
import { mkdirSync, readFileSync, writeFileSync } from "node:fs";
import { dirname } from "node:path";
import process from "node:process";
import { chromium } from "@playwright/test";

const output = process.argv[2] ?? "docs/images/puppet.png";
const port = Number(process.env.PICTURE_PORT ?? 4393);

const server = spawn(
  "node_modules/.bin/vite",
  ["preview", "--host", "127.0.0.1", "--port", String(port), "--strictPort"],
  { stdio: ["ignore", "pipe", "inherit"] },
);
await new Promise((resolve, reject) => {
  server.stdout.on("data", (d) => String(d).includes(String(port)) && resolve());
  server.on("exit", (code) => reject(new Error(`vite preview exited with ${code}`)));
});

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM_PATH ?? "/usr/bin/chromium",
  args: ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run"],
});
try {
  const page = await browser.newPage({ viewport: { width: 720, height: 720 }, deviceScaleFactor: 1 });
  await page.goto(`http://127.0.0.1:${port}/?hud=false`);
  await page.waitForSelector("body[data-ready=true]");
  const svg = readFileSync("www/gallery/magician.svg", "utf8");
  await page.evaluate(async (text) => {
    await window.akapDemo.widget.loadFile(new window.Blob([text], { type: "image/svg+xml" }), "magician.svg");
    await window.akapDemo.widget.whenIdle();
  }, svg);
  // Each part's rest bounding box, by name.
  const boxes = await page.evaluate(() => {
    const w = window.akapDemo.widget;
    const { positions: p, triangles: t } = w.mesh;
    return Object.fromEntries(
      w.parts.map((part) => {
        const b = [Infinity, Infinity, -Infinity, -Infinity];
        for (const f of part.triangles) {
          for (let k = 0; k < 3; k++) {
            const v = t[3 * f + k];
            b[0] = Math.min(b[0], p[2 * v]);
            b[1] = Math.min(b[1], p[2 * v + 1]);
            b[2] = Math.max(b[2], p[2 * v]);
            b[3] = Math.max(b[3], p[2 * v + 1]);
          }
        }
        return [part.name, b];
      }),
    );
  });
  for (const name of ["Torso", "Left arm", "Right arm", "Left leg", "Right leg"]) {
    if (!boxes[name]) throw new Error(`the magician has no part "${name}"; it has ${Object.keys(boxes).join(", ")}`);
  }
  const box = await page.locator("#app canvas.overlay").boundingBox();
  const view = await page.evaluate(() => window.akapDemo.widget.view);
  const toCss = (x, y) => [
    box.x + (view.offsetX + view.scale * x) / view.pixelRatio,
    box.y + (view.offsetY - view.scale * y) / view.pixelRatio,
  ];
  const joints = await page.evaluate(() => window.akapDemo.widget.joints);
  const names = await page.evaluate(() => window.akapDemo.widget.parts.map((p) => p.name));
  const shoulder = (arm) => joints.find((j) => names[j.parts[0]] === arm || names[j.parts[1]] === arm).point;
  const centre = (b, fx, fy) => [b[0] + fx * (b[2] - b[0]), b[1] + fy * (b[3] - b[1])];
  // Pins: the torso's middle and both feet.
  for (const [name, fx, fy] of [
    ["Torso", 0.5, 0.45],
    ["Left leg", 0.5, 0.1],
    ["Right leg", 0.5, 0.1],
  ]) {
    await page.mouse.click(...toCss(...centre(boxes[name], fx, fy)));
  }
  // Each hand (the end of its arm farthest from its shoulder) swung about the shoulder.
  const swing = async (arm, degrees) => {
    const [sx, sy] = shoulder(arm);
    const b = boxes[arm];
    const corners = [
      [b[0], b[1]],
      [b[2], b[1]],
      [(b[0] + b[2]) / 2, b[1]],
    ];
    const hand = corners.reduce((far, c) =>
      Math.hypot(c[0] - sx, c[1] - sy) > Math.hypot(far[0] - sx, far[1] - sy) ? c : far,
    );
    // A little inside the arm from its far end.
    const grab = [hand[0] + 0.1 * (sx - hand[0]), hand[1] + 0.1 * (sy - hand[1])];
    const radius = Math.hypot(grab[0] - sx, grab[1] - sy);
    const start = Math.atan2(grab[1] - sy, grab[0] - sx);
    await page.mouse.move(...toCss(...grab));
    await page.mouse.down();
    const steps = 24;
    for (let k = 1; k <= steps; k++) {
      const a = start + (((degrees * Math.PI) / 180) * k) / steps;
      await page.mouse.move(...toCss(sx + radius * Math.cos(a), sy + radius * Math.sin(a)), { steps: 2 });
    }
    await page.mouse.up();
    await page.evaluate(() => window.akapDemo.widget.whenIdle());
  };
  // Outward: counter-clockwise for an arm on the right of the torso, clockwise on the left.
  const torsoX = (boxes.Torso[0] + boxes.Torso[2]) / 2;
  const outward = (arm, degrees) => (shoulder(arm)[0] > torsoX ? degrees : -degrees);
  await swing("Right arm", outward("Right arm", 130));
  await swing("Left arm", outward("Left arm", 60));
  const png = await page.evaluate(async () => {
    const blob = await window.akapDemo.widget.exportPng();
    return Array.from(new Uint8Array(await blob.arrayBuffer()));
  });
  mkdirSync(dirname(output), { recursive: true });
  writeFileSync(output, Uint8Array.from(png));
  console.log(`wrote ${output} (${png.length} bytes)`);
} finally {
  await browser.close();
  server.kill();
}
