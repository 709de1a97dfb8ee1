/**
 * The stiffness brush in the app, driven as a person would: the toolbar's Brush, a stroke
 * over the arm with the mouse, the tint drawn over exactly the painted triangles (read in
 * the composited pixels), no handle added, undo and redo of the stroke, Alt-drag erasing,
 * the painting in the JSON export, and B and [ ] on the keyboard.
 */
import { expect, test, type Page } from "@playwright/test";
import { anchorPoints, idle, mapping, open, usePrepared } from "./helpers.js";

usePrepared();

/** The composited picture's RGB at a CSS point of the app's widget. */
async function pixel(page: Page, css: [number, number]): Promise<[number, number, number]> {
  await idle(page);
  const box = (await page.locator("#app canvas.overlay").boundingBox())!;
  return page.evaluate(
    ({ x, y }) => {
      const shadow = document.querySelector("#app .akap-host")!.shadowRoot!;
      const gl = shadow.querySelector("canvas.mesh") as HTMLCanvasElement;
      const overlay = shadow.querySelector("canvas.overlay") as HTMLCanvasElement;
      const screen = document.createElement("canvas");
      screen.width = gl.width;
      screen.height = gl.height;
      const ctx = screen.getContext("2d")!;
      ctx.drawImage(gl, 0, 0);
      ctx.drawImage(overlay, 0, 0);
      const ratio = window.akapDemo!.widget.view.pixelRatio;
      const d = ctx.getImageData(Math.round(x * ratio), Math.round(y * ratio), 1, 1).data;
      return [d[0]!, d[1]!, d[2]!] as [number, number, number];
    },
    { x: css[0] - box.x, y: css[1] - box.y },
  );
}

/** Triangles painted to `value`, and the centroid (shape units) of each. */
async function painted(page: Page, value = 100): Promise<[number, number][]> {
  return page.evaluate((value) => {
    const w = window.akapDemo!.widget;
    const s = w.stiffness();
    if (!s) return [];
    const p = w.positions();
    const t = w.mesh.triangles;
    const out: [number, number][] = [];
    s.forEach((v, f) => {
      if (v !== value) return;
      let x = 0;
      let y = 0;
      for (let k = 0; k < 3; k++) {
        x += p[2 * t[3 * f + k]!]! / 3;
        y += p[2 * t[3 * f + k]! + 1]! / 3;
      }
      out.push([x, y]);
    });
    return out;
  }, value);
}

test("the brush paints the triangles under the stroke, tinted, undoable, erasable and exported", async ({ page }) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  const { toCss, unit } = await mapping(page);
  const { pin, grab } = await anchorPoints(page);
  const cssPin = toCss(...pin);
  const cssArm = toCss(...grab);
  const before = await pixel(page, cssArm);
  expect(before[0]).toBeGreaterThan(before[2]); // the orange shape

  await page.getByRole("combobox", { name: "Tool" }).selectOption("stiffness");
  await page.getByRole("combobox", { name: "Paint" }).selectOption("100");
  const size = page.locator('input[name="brush-size"]');
  await size.fill("20");
  await size.dispatchEvent("change");
  expect(await page.evaluate(() => window.akapDemo!.widget.brush)).toEqual({ size: 20, value: 100 });
  // A stroke of 30 px along the arm, inward from its end.
  const start: [number, number] = [cssArm[0] - 5, cssArm[1]];
  const end: [number, number] = [cssArm[0] - 35, cssArm[1]];
  await page.mouse.move(...start);
  await page.mouse.down();
  await page.mouse.move(...end, { steps: 6 });
  await page.mouse.up();
  await idle(page);

  expect(await page.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(0);
  const stiff = await painted(page);
  expect(stiff.length).toBeGreaterThan(5);
  // Every painted centroid lies within the brush (20 px) of the stroke's segment, and the
  // triangle under the stroke's middle is painted.
  const radius = 20 * unit;
  const [sx, sy] = [grab[0] - 5 * unit, grab[1]];
  const [ex] = [grab[0] - 35 * unit];
  for (const [x, y] of stiff) {
    const along = Math.min(sx, Math.max(ex, x));
    expect(Math.hypot(x - along, y - sy)).toBeLessThan(radius * 1.01 + 1e-9);
  }
  const tinted = await pixel(page, [cssArm[0] - 20, cssArm[1]]);
  expect(tinted[2]).toBeGreaterThan(tinted[0]); // blue over orange
  const far = await pixel(page, cssPin);
  expect(far[0]).toBeGreaterThan(far[2]); // untouched
  const json = await page.evaluate(
    () => JSON.parse(window.akapDemo!.widget.exportMesh("json")) as { stiffness: number[] },
  );
  expect(json.stiffness.filter((s) => s === 100).length).toBe(stiff.length);

  // Undo takes the stroke back; redo brings it again.
  await page.keyboard.press("Control+z");
  expect(await page.evaluate(() => window.akapDemo!.widget.stiffness())).toBeUndefined();
  const undone = await pixel(page, [cssArm[0] - 20, cssArm[1]]);
  expect(undone[0]).toBeGreaterThan(undone[2]);
  await page.keyboard.press("Control+Shift+z");
  expect((await painted(page)).length).toBe(stiff.length);

  // Alt-drag erases under the stroke.
  await page.keyboard.down("Alt");
  await page.mouse.move(...start);
  await page.mouse.down();
  await page.mouse.move(...end, { steps: 6 });
  await page.mouse.up();
  await page.keyboard.up("Alt");
  await idle(page);
  expect(await page.evaluate(() => window.akapDemo!.widget.stiffness())).toBeUndefined();

  // B turns the brush off: a click adds a handle again; ] enlarges the brush.
  await page.keyboard.press("b");
  expect(await page.evaluate(() => window.akapDemo!.widget.tool)).toBe("pose");
  await page.keyboard.press("]");
  expect(await page.evaluate(() => window.akapDemo!.widget.brush.size)).toBe(25);
  await page.mouse.click(...cssPin);
  expect(await page.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(1);
});
