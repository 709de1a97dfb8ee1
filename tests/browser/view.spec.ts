/**
 * The view and the help a new user looks for: zoom with the wheel or two fingers, pan by
 * dragging the background or with Space held, fit the pose back into view, the help panel,
 * and the layout on a phone.
 */
import { expect, test, type Page } from "@playwright/test";
import {
  anchorPoints,
  handles,
  idle,
  mapping,
  open,
  pinAndDrag,
  positions,
  prepare,
  usePrepared,
  dragMouse,
} from "./helpers.js";

usePrepared();

const view = (page: Page) => page.evaluate(() => window.akapDemo!.widget.view);
const handleCount = (page: Page) => page.evaluate(() => window.akapDemo!.widget.handleCount);

/** A CSS point of the stage that is not on the shape (the canvas's top-left corner area). */
async function background(page: Page): Promise<[number, number]> {
  const box = (await page.locator("#app canvas.overlay").boundingBox())!;
  return [box.x + 20, box.y + 20];
}

test("the wheel zooms about the pointer: the shape point under it stays", async ({ page }) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  const { grab } = await anchorPoints(page);
  const { toCss } = await mapping(page);
  // Pointer events land on whole CSS pixels: find the shape point under the one used.
  const [x, y] = toCss(...grab).map(Math.round) as [number, number];
  const box = (await page.locator("#app canvas.overlay").boundingBox())!;
  const before = await view(page);
  const under: [number, number] = [
    ((x - box.x) * before.pixelRatio - before.offsetX) / before.scale,
    (before.offsetY - (y - box.y) * before.pixelRatio) / before.scale,
  ];
  await page.mouse.move(x, y);
  await page.mouse.wheel(0, -300);
  await expect.poll(async () => (await view(page)).scale).toBeGreaterThan(1.3 * before.scale);
  const [x2, y2] = (await mapping(page)).toCss(...under);
  expect(Math.hypot(x2 - x, y2 - y)).toBeLessThan(0.01);
  expect(await handleCount(page)).toBe(0);
});

test("dragging the background or Space-dragging the shape pans; F fits a pose dragged out of sight", async ({
  page,
}) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  const before = await view(page);
  const [bx, by] = await background(page);
  await page.mouse.move(bx, by);
  await page.mouse.down();
  await page.mouse.move(bx + 100, by + 50, { steps: 5 });
  await page.mouse.up();
  const panned = await view(page);
  // To a thousandth of a pixel: pointer coordinates reach the page in single precision.
  expect(panned.offsetX - before.offsetX).toBeCloseTo(100 * panned.pixelRatio, 3);
  expect(panned.offsetY - before.offsetY).toBeCloseTo(50 * panned.pixelRatio, 3);
  expect(panned.scale).toBe(before.scale);
  expect(await handleCount(page)).toBe(0);

  // Space held: a drag that starts on the shape pans too, and adds no handle.
  const { toCss } = await mapping(page);
  const { grab } = await anchorPoints(page);
  const [gx, gy] = toCss(...grab);
  await page.locator("#app .akap-host >> .widget").focus();
  await page.keyboard.down(" ");
  await page.mouse.move(gx, gy);
  await page.mouse.down();
  await page.mouse.move(gx + 2000, gy, { steps: 4 });
  await page.mouse.up();
  await page.keyboard.up(" ");
  expect(await handleCount(page)).toBe(0);
  expect((await view(page)).offsetX - panned.offsetX).toBeCloseTo(2000 * panned.pixelRatio, 3);

  // The shape is out of sight; F brings the whole pose back into the canvas.
  await page.keyboard.press("f");
  const fitted = await view(page);
  const p = await positions(page);
  const box = (await page.locator("#app canvas.overlay").boundingBox())!;
  for (let i = 0; i < p.length; i += 2) {
    const px = (fitted.offsetX + fitted.scale * p[i]!) / fitted.pixelRatio;
    const py = (fitted.offsetY - fitted.scale * p[i + 1]!) / fitted.pixelRatio;
    expect(px).toBeGreaterThan(0);
    expect(px).toBeLessThan(box.width);
    expect(py).toBeGreaterThan(0);
    expect(py).toBeLessThan(box.height);
  }
  // Posing still lands handles under the pointer in the moved view.
  const { end } = await pinAndDrag(page, -40, 30);
  const h = await handles(page);
  const [hx, hy] = (await mapping(page)).toCss(h[2]!, h[3]!);
  expect(Math.hypot(hx - end[0], hy - end[1])).toBeLessThan(1);
});

test("two fingers off the handles pinch-zoom and pan; no handle is left behind", async ({ browser }) => {
  const context = await prepare(await browser.newContext({ hasTouch: true, viewport: { width: 800, height: 700 } }));
  const page = await context.newPage();
  await open(page);
  const cdp = await context.newCDPSession(page);
  const touch = async (type: "touchStart" | "touchMove" | "touchEnd", points: [number, number][]) =>
    cdp.send("Input.dispatchTouchEvent", { type, touchPoints: points.map(([x, y], id) => ({ x, y, id })) });
  const before = await view(page);
  // Two fingers on the shape, moving apart: the first one's tap would add a handle, but the
  // second arrives at once, so it is a pinch.
  const { toCss } = await mapping(page);
  const { pin, grab } = await anchorPoints(page);
  const a = toCss(...pin);
  const b = toCss(...grab);
  const mid: [number, number] = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
  await touch("touchStart", [a]);
  await touch("touchStart", [a, b]);
  for (let k = 1; k <= 10; k++) {
    const s = 1 + 0.05 * k;
    await touch("touchMove", [
      [mid[0] + (a[0] - mid[0]) * s, mid[1] + (a[1] - mid[1]) * s],
      [mid[0] + (b[0] - mid[0]) * s, mid[1] + (b[1] - mid[1]) * s],
    ]);
  }
  await touch("touchEnd", []);
  await idle(page);
  const after = await view(page);
  expect(after.scale / before.scale).toBeCloseTo(1.5, 2);
  expect(await handleCount(page)).toBe(0);
  await context.close();
});

test("? opens the help with the gestures and keys; Esc closes it; so does the ? button", async ({ page }) => {
  await page.setViewportSize({ width: 1100, height: 800 });
  await open(page);
  const help = page.getByRole("dialog", { name: "Help: gestures and keys" });
  await expect(help).toBeHidden();
  await page.locator("#app .akap-host >> .widget").focus();
  await page.keyboard.press("?");
  await expect(help).toBeVisible();
  await expect(help).toContainText("undo, redo");
  await expect(help).toContainText("fit the shape in view");
  await page.keyboard.press("Escape");
  await expect(help).toBeHidden();
  await page.getByRole("button", { name: "?", exact: true }).click();
  await expect(help).toBeVisible();
  await help.getByRole("button", { name: "Close" }).click();
  await expect(help).toBeHidden();
});

test("on a phone the tools fold away, targets are finger-sized, and the HUD fades from a handle dragged under it", async ({
  browser,
}) => {
  const context = await prepare(
    await browser.newContext({ hasTouch: true, isMobile: true, viewport: { width: 390, height: 844 } }),
  );
  const page = await context.newPage();
  await open(page, "");
  const toolbar = page.locator("#app .akap-host >> .toolbar");
  const folded = (await toolbar.boundingBox())!;
  expect(folded.height).toBeLessThan(0.12 * 844);
  const heights = async () =>
    page.evaluate(() =>
      [
        ...document
          .querySelector("#app .akap-host")!
          .shadowRoot!.querySelectorAll(
            "button, select, input:not([type=checkbox]), label:has(> input[type=checkbox])",
          ),
      ]
        .filter((e) => (e as HTMLElement).offsetParent !== null)
        .map((e) => [e.textContent || (e as HTMLInputElement).name, e.getBoundingClientRect().height] as const),
    );
  for (const [name, height] of await heights()) expect(height, name).toBeGreaterThanOrEqual(44);
  await page.getByRole("button", { name: "☰ Tools" }).tap();
  await expect(page.getByRole("combobox", { name: "Method" })).toBeVisible();
  for (const [name, height] of await heights()) expect(height, name).toBeGreaterThanOrEqual(44);
  await page.getByRole("button", { name: "☰ Tools" }).tap();
  await expect(page.getByRole("combobox", { name: "Method" })).toBeHidden();

  // Drag a handle to where the HUD is: the HUD gets out of the way.
  const hud = page.locator("#app .akap-host >> .hud");
  const hudBox = (await hud.boundingBox())!;
  const { toCss } = await mapping(page);
  const { pin, grab } = await anchorPoints(page);
  const cdp = await context.newCDPSession(page);
  const touch = async (type: "touchStart" | "touchMove" | "touchEnd", points: [number, number][]) =>
    cdp.send("Input.dispatchTouchEvent", { type, touchPoints: points.map(([x, y], id) => ({ x, y, id })) });
  await touch("touchStart", [toCss(...pin)]);
  await touch("touchEnd", []);
  const start = toCss(...grab);
  const end: [number, number] = [hudBox.x + hudBox.width / 2, hudBox.y + hudBox.height / 2];
  await touch("touchStart", [start]);
  for (let k = 1; k <= 20; k++) {
    await touch("touchMove", [[start[0] + ((end[0] - start[0]) * k) / 20, start[1] + ((end[1] - start[1]) * k) / 20]]);
  }
  // The finger is still down: wait until the handle is under it.
  await expect
    .poll(async () => {
      const h = await handles(page);
      const [hx, hy] = toCss(h[2]!, h[3]!);
      return Math.hypot(hx - end[0], hy - end[1]);
    })
    .toBeLessThan(1);
  // The handle shows through: the HUD has faded out (and comes back on release).
  await expect.poll(() => hud.evaluate((e) => Number(getComputedStyle(e).opacity))).toBeLessThan(0.2);
  await touch("touchEnd", []);
  await idle(page);
  await expect.poll(() => hud.evaluate((e) => Number(getComputedStyle(e).opacity))).toBeGreaterThan(0.9);
  await context.close();
});

test("the work survives a reload, and Start over begins afresh", async ({ page }) => {
  await page.setViewportSize({ width: 1280, height: 800 });
  await open(page);
  await page.getByRole("combobox", { name: "Method" }).selectOption("arap");
  await page.getByLabel("Wireframe").check();
  await pinAndDrag(page, -50, 60);
  const work = { positions: await positions(page), handles: await handles(page) };
  // Saved a moment after the last change.
  await page.waitForTimeout(1000);
  await page.reload();
  await expect(page.locator("body")).toHaveAttribute("data-ready", "true");
  expect(await positions(page)).toEqual(work.positions);
  expect(await handles(page)).toEqual(work.handles);
  await expect(page.getByRole("combobox", { name: "Method" })).toHaveValue("arap");
  await expect(page.getByLabel("Wireframe")).toBeChecked();
  // The restored pose poses on: the dragged handle follows another drag.
  const { toCss } = await mapping(page);
  const [x, y] = toCss(work.handles[2]!, work.handles[3]!);
  await dragMouse(page, [x, y], [x + 20, y - 20], 4);
  const h = await handles(page);
  const [hx, hy] = toCss(h[2]!, h[3]!);
  expect(Math.hypot(hx - (x + 20), hy - (y - 20))).toBeLessThan(1);

  await page.getByRole("button", { name: "Start over" }).click();
  await expect.poll(() => handleCount(page)).toBe(0);
  const rest = await page.evaluate(() => Array.from(window.akapDemo!.widget.mesh.positions));
  expect(await positions(page)).toEqual(rest);
  await expect(page.getByRole("combobox", { name: "Method" })).toHaveValue("akap");
  await page.waitForTimeout(1000);
  await page.reload();
  await expect(page.locator("body")).toHaveAttribute("data-ready", "true");
  expect(await handleCount(page)).toBe(0);
  expect(await positions(page)).toEqual(rest);
});

test("re-meshing to 40k vertices runs beside the page with its stage shown, and Cancel leaves everything as it was", async ({
  page,
}) => {
  test.setTimeout(60_000);
  await page.setViewportSize({ width: 1280, height: 800 });
  await open(page);
  const count = () => page.evaluate(() => window.akapDemo!.widget.vertexCount);
  const before = await count();
  const vertices = page.getByRole("spinbutton", { name: "Vertices" });
  const busy = page.locator("#app .akap-host >> .busy");
  // Count the page's animation frames while the busy indicator shows.
  await page.evaluate(() => {
    const w = window as unknown as { busyFrames: number };
    w.busyFrames = 0;
    const shadow = document.querySelector("#app .akap-host")!.shadowRoot!;
    const tick = () => {
      if (!shadow.querySelector(".busy")!.classList.contains("hidden")) w.busyFrames++;
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  });
  await vertices.fill("40000");
  await vertices.press("Enter");
  await expect(busy).toBeVisible();
  await expect(busy).toContainText("40000 vertices");
  await expect(busy.getByRole("button", { name: "Cancel" })).toBeVisible();
  await expect.poll(count, { timeout: 30_000 }).toBeGreaterThan(35_000);
  await expect(busy).toBeHidden();
  expect(await page.evaluate(() => (window as unknown as { busyFrames: number }).busyFrames)).toBeGreaterThan(5);
  // It poses.
  const { end } = await pinAndDrag(page, -30, 30);
  const h = await handles(page);
  const [x, y] = (await mapping(page)).toCss(h[2]!, h[3]!);
  expect(Math.hypot(x - end[0], y - end[1])).toBeLessThan(1);

  // Cancel: back to the mesh, pose and field as they were.
  const posed = await positions(page);
  const shown = await vertices.inputValue();
  await vertices.fill("45000");
  await vertices.press("Enter");
  await busy.getByRole("button", { name: "Cancel" }).click();
  await expect(busy).toBeHidden();
  await expect(page.locator("#app .akap-host >> .status")).toContainText("cancelled");
  expect(await positions(page)).toEqual(posed);
  await expect(vertices).toHaveValue(shown);
  expect(await count()).not.toBe(before);
});
