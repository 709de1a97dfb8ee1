/**
 * Depth order in the app, checked in the drawn pixels: a figure traced from an image whose
 * torso is red and whose arm is blue; with the torso pinned, the arm dragged across the
 * torso is drawn above it (the dragged part comes to the front), and below it after Send
 * back; the exported mesh lists the triangles back to front.
 */
import { expect, test, type Page } from "@playwright/test";
import { idle, mapping, open, usePrepared } from "./helpers.js";

usePrepared();

/** Loads a 200 x 160 image: a red torso (x 40-100, y 10-150) and a blue arm to its right (x 100-190, y 60-80). */
async function loadFigure(page: Page): Promise<void> {
  await page.evaluate(async () => {
    const canvas = document.createElement("canvas");
    canvas.width = 200;
    canvas.height = 160;
    const ctx = canvas.getContext("2d")!;
    ctx.fillStyle = "rgb(220, 30, 30)";
    ctx.fillRect(40, 10, 60, 140);
    ctx.fillStyle = "rgb(30, 30, 220)";
    ctx.fillRect(99, 60, 91, 20);
    const blob = await new Promise<Blob>((resolve) => canvas.toBlob((b) => resolve(b!), "image/png"));
    await window.akapDemo!.widget.loadFile(blob, "figure.png");
  });
  await idle(page);
}

/**
 * A CSS point where a posed arm triangle (rest centroid right of the torso) lies over a
 * posed torso triangle (rest centroid well inside it), away from both outlines.
 */
async function overlap(page: Page): Promise<[number, number] | undefined> {
  const { toCss } = await mapping(page);
  const point = await page.evaluate(() => {
    const w = window.akapDemo!.widget;
    const rest = w.mesh.positions;
    const t = w.mesh.triangles;
    const p = w.positions();
    const centre = (q: ArrayLike<number>, f: number) =>
      [0, 1].map((d) => (q[2 * t[3 * f]! + d]! + q[2 * t[3 * f + 1]! + d]! + q[2 * t[3 * f + 2]! + d]!) / 3) as [
        number,
        number,
      ];
    let xs = [Infinity, -Infinity];
    for (let v = 0; v < rest.length / 2; v++) xs = [Math.min(xs[0]!, rest[2 * v]!), Math.max(xs[1]!, rest[2 * v]!)];
    // The torso is the left 60 of the image's 150 coloured columns (x 40-100 of 40-190).
    const split = xs[0]! + ((xs[1]! - xs[0]!) * 60) / 150;
    const inside = (f: number, x: number, y: number) => {
      const c = [0, 1, 2].map((k) => [p[2 * t[3 * f + k]!]!, p[2 * t[3 * f + k]! + 1]!]);
      const side = (a: number[], b: number[]) => (b[0]! - a[0]!) * (y - a[1]!) - (b[1]! - a[1]!) * (x - a[0]!);
      const s = [side(c[0]!, c[1]!), side(c[1]!, c[2]!), side(c[2]!, c[0]!)];
      return s.every((v) => v > 0) || s.every((v) => v < 0);
    };
    const arm: number[] = [];
    const torso: number[] = [];
    for (let f = 0; f < t.length / 3; f++) {
      const [x] = centre(rest, f);
      if (x > split + 0.1 * (xs[1]! - split)) arm.push(f);
      else if (x < split - 0.2 * (split - xs[0]!)) torso.push(f);
    }
    for (const f of arm) {
      const [x, y] = centre(p, f);
      if (torso.some((g) => inside(g, x, y))) return [x, y] as [number, number];
    }
    return undefined;
  });
  return point && toCss(...point);
}

async function colour(page: Page, css: [number, number]): Promise<[number, number, number]> {
  await idle(page);
  const box = (await page.locator("#app canvas.overlay").boundingBox())!;
  return page.evaluate(
    ({ x, y }) => {
      const shadow = document.querySelector("#app .akap-host")!.shadowRoot!;
      const screen = document.createElement("canvas");
      const gl = shadow.querySelector("canvas.mesh") as HTMLCanvasElement;
      screen.width = gl.width;
      screen.height = gl.height;
      const ctx = screen.getContext("2d")!;
      ctx.drawImage(gl, 0, 0);
      ctx.drawImage(shadow.querySelector("canvas.overlay") as HTMLCanvasElement, 0, 0);
      const r = window.akapDemo!.widget.view.pixelRatio;
      const d = ctx.getImageData(Math.round(x * r), Math.round(y * r), 1, 1).data;
      return [d[0]!, d[1]!, d[2]!] as [number, number, number];
    },
    { x: css[0] - box.x, y: css[1] - box.y },
  );
}

test("the arm dragged across the torso is drawn above it, and below it after Send back", async ({ page }) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  await loadFigure(page);
  const { toCss } = await mapping(page);
  const b = await page.evaluate(() => {
    const p = window.akapDemo!.widget.mesh.positions;
    const xs = p.filter((_, i) => i % 2 === 0);
    const ys = p.filter((_, i) => i % 2 === 1);
    return { minX: Math.min(...xs), maxX: Math.max(...xs), minY: Math.min(...ys), maxY: Math.max(...ys) };
  });
  const [w, h] = [b.maxX - b.minX, b.maxY - b.minY];
  // Pins on the torso (its middle column, high and low); the arm's end grabbed.
  // Image pixels (column, row from the top) to shape units: the coloured block spans
  // columns 40-190 and rows 10-150.
  const image = (column: number, row: number) =>
    toCss(b.minX + ((column - 40) / 150) * w, b.minY + ((150 - row) / 140) * h);
  for (const row of [35, 125]) await page.mouse.click(...image(70, row));
  // The arm's end swung about the shoulder (100, 70), over the top, until the arm lies
  // across the torso.
  const swing = (degrees: number) => {
    const a = (degrees * Math.PI) / 180;
    return image(100 + 85 * Math.cos(a), 70 - 85 * Math.sin(a));
  };
  await page.mouse.move(...swing(0));
  await page.mouse.down();
  for (let degrees = 10; degrees <= 170; degrees += 10) await page.mouse.move(...swing(degrees), { steps: 4 });
  await page.mouse.up();
  await idle(page);
  expect(await page.evaluate(() => window.akapDemo!.widget.handleLayers())).toEqual([0, 1, 2]);

  // No foldovers (the default): the swing folds no triangle.
  expect(await page.evaluate(() => window.akapDemo!.widget.metrics.flipped)).toBe(0);
  const at = await overlap(page);
  expect(at, "the arm lies over the torso somewhere").toBeDefined();
  const above = await colour(page, at!);
  expect(above[2]).toBeGreaterThan(above[0] + 60); // blue: the arm in front

  // The arm's handle is selected (it was dragged): send it back.
  await page.getByRole("button", { name: "Back" }).click();
  expect(await page.evaluate(() => window.akapDemo!.widget.handleLayers())).toEqual([0, 1, -1]);
  const below = await colour(page, at!);
  expect(below[0]).toBeGreaterThan(below[2] + 60); // red: the torso in front

  // The exported mesh lists the arm's triangles (now behind) first; undo brings the arm forward again.
  const json = await page.evaluate(
    () => JSON.parse(window.akapDemo!.widget.exportMesh("json")) as { triangles: number[] },
  );
  const mesh = await page.evaluate(() => Array.from(window.akapDemo!.widget.mesh.triangles));
  expect(json.triangles.length).toBe(mesh.length);
  expect(json.triangles).not.toEqual(mesh);
  await page.keyboard.press("Control+z");
  expect(await page.evaluate(() => window.akapDemo!.widget.handleLayers())).toEqual([0, 1, 2]);
  const again = await colour(page, at!);
  expect(again[2]).toBeGreaterThan(again[0] + 60);
});
