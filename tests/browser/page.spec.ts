/**
 * The app in Chromium, driven as a person would: the shape is drawn where its triangles
 * are, clicking adds handles, dragging poses the shape while pins stay, undo restores the
 * pose, a recorded session replays to identical positions, touch drags work, and the
 * exports download (sessions the core refuses, and the app's recording replayed by the
 * core: session.spec.ts). Expected pixels come from the mesh geometry and the view the widget
 * reports (a mask rasterised from the triangles), never from a stored picture.
 */
import { expect, test } from "@playwright/test";
import {
  anchorPoints,
  coverage,
  expectDrawnLikeTheMesh,
  handles,
  idle,
  mapping,
  open,
  pinAndDrag,
  positions,
  prepare,
  usePrepared,
} from "./helpers.js";

usePrepared();

test("draws the default shape where its triangles are", async ({ page }) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  expect(await page.evaluate(() => window.akapDemo!.widget.renderer)).toBe("webgl2");
  expectDrawnLikeTheMesh(await coverage(page));
});

test("clicking adds handles; dragging one poses the shape while the pin stays", async ({ page }) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  const rest = await positions(page);
  const { end, pin } = await pinAndDrag(page, -80, 120);
  expect(await page.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(2);

  // The handles are where the pointer left them (pin: where it was clicked), to a pixel.
  const { toCss } = await mapping(page);
  const h = await handles(page);
  const [pinX, pinY] = toCss(h[0]!, h[1]!);
  const [dragX, dragY] = toCss(h[2]!, h[3]!);
  expect(Math.hypot(pinX - pin[0], pinY - pin[1])).toBeLessThan(0.5);
  expect(Math.hypot(dragX - end[0], dragY - end[1])).toBeLessThan(1);

  // The picture follows the deformed mesh, and the mesh really moved.
  const posed = await coverage(page);
  expectDrawnLikeTheMesh(posed);
  const before = await coverage(page, rest);
  expect(before.stray + before.missing).toBeGreaterThan(0.03 * before.maskPixels);
  const m = await page.evaluate(() => window.akapDemo!.widget.metrics);
  expect(m.flipped).toBe(0);
  expect(m.areaDistortion).toBeLessThan(2.2);
});

test("undo restores the pose before the drag, redo brings it back", async ({ page }) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  const rest = await positions(page);
  await pinAndDrag(page, -60, 100);
  const posed = await positions(page);
  expect(posed).not.toEqual(rest);
  await page.keyboard.press("Control+z");
  expect(await positions(page)).toEqual(rest);
  expect(await page.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(1);
  expectDrawnLikeTheMesh(await coverage(page));
  await page.getByRole("button", { name: "Redo" }).click();
  expect(await positions(page)).toEqual(posed);
});

test("a recorded session replays to the same positions bit for bit, also after saving and loading", async ({
  page,
}) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  await page.getByRole("button", { name: "Record" }).click();
  await pinAndDrag(page, -70, 90);
  const { toCss } = await mapping(page);
  const h = await handles(page);
  // A second drag of the pin, so the session has several gestures.
  const [x, y] = toCss(h[0]!, h[1]!);
  await page.mouse.move(x, y);
  await page.mouse.down();
  await page.mouse.move(x + 40, y - 10, { steps: 6 });
  await page.mouse.up();
  await idle(page);
  await page.getByRole("button", { name: "Stop" }).click();
  const recorded = await positions(page);

  await page.getByRole("button", { name: "Reset" }).click();
  await idle(page);
  expect(await positions(page)).not.toEqual(recorded);
  await page.getByRole("button", { name: "Replay" }).click();
  await expect(page.locator(".akap-host >> .widget")).not.toHaveAttribute("data-replaying", "true");
  await idle(page);
  expect(await positions(page)).toEqual(recorded);

  // Save, then load it in a fresh page through the file picker.
  const download = page.waitForEvent("download");
  await page.getByRole("button", { name: "Save", exact: true }).click();
  const file = await (await download).path();
  await open(page);
  await page.locator('input[name="session-file"]').setInputFiles(file);
  await expect.poll(() => positions(page)).toEqual(recorded);
});

test("touch: one finger drags a handle, two fingers drag two at once", async ({ browser }) => {
  const context = await prepare(await browser.newContext({ hasTouch: true, viewport: { width: 800, height: 700 } }));
  const page = await context.newPage();
  await open(page);
  const { toCss } = await mapping(page);
  const { pin, grab } = await anchorPoints(page);
  const cdp = await context.newCDPSession(page);
  const touch = async (type: "touchStart" | "touchMove" | "touchEnd", points: [number, number][]) =>
    cdp.send("Input.dispatchTouchEvent", {
      type,
      touchPoints: points.map(([x, y], id) => ({ x, y, id })),
    });
  // Two taps add two handles.
  for (const p of [pin, grab]) {
    await touch("touchStart", [toCss(...p)]);
    await touch("touchEnd", []);
  }
  await idle(page);
  expect(await page.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(2);
  // Both fingers move their handles together.
  const a = toCss(...pin);
  const b = toCss(...grab);
  await touch("touchStart", [a, b]);
  for (let k = 1; k <= 10; k++) {
    await touch("touchMove", [
      [a[0] - 3 * k, a[1]],
      [b[0] + 2 * k, b[1] - 5 * k],
    ]);
  }
  await touch("touchEnd", []);
  await idle(page);
  const h = await handles(page);
  const [ax, ay] = toCss(h[0]!, h[1]!);
  const [bx, by] = toCss(h[2]!, h[3]!);
  expect(Math.hypot(ax - (a[0] - 30), ay - a[1])).toBeLessThan(1);
  expect(Math.hypot(bx - (b[0] + 20), by - (b[1] - 50))).toBeLessThan(1);
  expectDrawnLikeTheMesh(await coverage(page));
  await context.close();
});

test("keyboard: arrows nudge the selected handle, Delete removes it", async ({ page }) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  await pinAndDrag(page, 0, 0);
  expect(await page.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(2);
  const { toCss } = await mapping(page);
  const before = await handles(page);
  for (let k = 0; k < 3; k++) await page.keyboard.press("Shift+ArrowRight");
  await idle(page);
  const after = await handles(page);
  const [x0] = toCss(before[2]!, before[3]!);
  const [x1, y1] = toCss(after[2]!, after[3]!);
  expect(x1 - x0).toBeCloseTo(30, 0);
  expect(Math.abs(y1 - toCss(before[2]!, before[3]!)[1])).toBeLessThan(1);
  await page.keyboard.press("Delete");
  expect(await page.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(1);
});

test("exports the pose as PNG, SVG, OBJ and JSON", async ({ page }) => {
  await open(page);
  await pinAndDrag(page, -40, 60);
  const p = await positions(page);
  const n = p.length / 2;
  const get = async (name: string) => {
    const download = page.waitForEvent("download");
    await page.getByRole("button", { name, exact: true }).click();
    const d = await download;
    const fs = await import("node:fs/promises");
    return { name: d.suggestedFilename(), bytes: await fs.readFile((await d.path())!) };
  };
  const png = await get("PNG");
  expect(png.name).toBe("pose.png");
  expect(png.bytes.subarray(1, 4).toString()).toBe("PNG");
  const svg = await get("SVG");
  expect(svg.bytes.toString()).toMatch(/^<svg [^>]*viewBox=.*<path d="M/s);
  // One subpath per boundary loop: the outline and the 4 holes of the default shape.
  expect(svg.bytes.toString().match(/M/g)!.length).toBe(5);
  const obj = (await get("OBJ")).bytes.toString();
  expect(obj.split("\n").filter((l) => l.startsWith("v ")).length).toBe(n);
  expect(obj.split("\n").filter((l) => l.startsWith("vt ")).length).toBe(n);
  const json = JSON.parse((await get("JSON")).bytes.toString()) as { positions: number[] };
  expect(json.positions).toEqual(p);
});

test("renders at device resolution on a HiDPI screen and refits on resize", async ({ browser }) => {
  const context = await prepare(
    await browser.newContext({ deviceScaleFactor: 2, viewport: { width: 600, height: 500 } }),
  );
  const page = await context.newPage();
  await open(page);
  const box = (await page.locator("canvas.mesh").boundingBox())!;
  const hi = await coverage(page);
  expect(hi.width).toBe(Math.round(box.width * 2));
  expect(hi.height).toBe(Math.round(box.height * 2));
  expectDrawnLikeTheMesh(hi);
  await page.setViewportSize({ width: 400, height: 800 });
  await expect.poll(async () => (await coverage(page)).width).toBe(800);
  expectDrawnLikeTheMesh(await coverage(page));
  await context.close();
});

test("the wireframe toggle draws the edges and W turns it off again", async ({ page }) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  const plain = await coverage(page);
  await page.getByLabel("Wireframe").check();
  const wired = await coverage(page);
  expect(wired.dark).toBeGreaterThan(2 * plain.dark);
  await page.locator("canvas.overlay").focus();
  await page.keyboard.press("w");
  expect((await coverage(page)).dark).toBe(plain.dark);
});

test("the embedding example shows two widgets that work independently", async ({ page }) => {
  await page.setViewportSize({ width: 1100, height: 800 });
  await page.goto("/www/examples/embed.html");
  await expect(page.locator("body")).toHaveAttribute("data-ready", "true");
  const read = () =>
    page.evaluate(() => ({
      mounted: Array.from(window.widgetFor("mounted").positions()),
      element: Array.from(window.widgetFor("element").positions()),
    }));
  const before = await read();
  expectDrawnLikeTheMesh(await coverage(page, undefined, "mounted"));
  expectDrawnLikeTheMesh(await coverage(page, undefined, "element"));
  // Posing the mounted widget changes only it, and its event reaches the page.
  await pinAndDrag(page, -40, 50, "mounted");
  const after = await read();
  expect(after.mounted).not.toEqual(before.mounted);
  expect(after.element).toEqual(before.element);
  await expect(page.locator("#log")).toContainText("mounted: 2 handles");
  expectDrawnLikeTheMesh(await coverage(page, undefined, "mounted"));
  // And the element works on its own too.
  await pinAndDrag(page, 30, -30, "element");
  const last = await read();
  expect(last.element).not.toEqual(before.element);
  expect(last.mounted).toEqual(after.mounted);
  await expect(page.locator("#log")).toContainText("element: 2 handles");
});

for (const [method, label] of [
  ["arap", "ARAP"],
  ["mls", "moving least squares"],
  ["cauchy-green", "Cauchy-Green"],
] as const) {
  test(`switching to ${label} keeps the pose and handles, and ${label} poses the shape too`, async ({ page }) => {
    await page.setViewportSize({ width: 900, height: 700 });
    await open(page);
    await pinAndDrag(page, -30, 40);
    const posed = await positions(page);
    await page.getByRole("combobox", { name: "Method" }).selectOption(method);
    expect(await positions(page)).toEqual(posed);
    expect(await page.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(2);
    const { toCss } = await mapping(page);
    const h = await handles(page);
    const [x, y] = toCss(h[2]!, h[3]!);
    await page.mouse.move(x, y);
    await page.mouse.down();
    await page.mouse.move(x - 40, y + 30, { steps: 8 });
    await page.mouse.up();
    await idle(page);
    const after = await handles(page);
    const [ax, ay] = toCss(after[2]!, after[3]!);
    expect(Math.hypot(ax - (x - 40), ay - (y + 30))).toBeLessThan(1);
    const [px, py] = toCss(after[0]!, after[1]!);
    const [qx, qy] = toCss(h[0]!, h[1]!);
    expect(Math.hypot(px - qx, py - qy)).toBeLessThan(0.5);
    // Cauchy-Green with two handles is the similarity through them, so the whole shape
    // shrinks as they come closer.
    expectDrawnLikeTheMesh(await coverage(page), method === "cauchy-green" ? 0.02 : 0.05);
  });
}

test("a file opened through the picker becomes the shape, and it poses", async ({ page }) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  const path = await import("node:path");
  await page.locator('input[name="shape-file"]').setInputFiles(path.resolve("www/gallery/pip.png"));
  await expect.poll(() => page.evaluate(() => window.akapDemo!.widget.mesh.positions[0])).toBeGreaterThan(2);
  // The traced image is the texture: the drawing still covers exactly the mesh.
  expectDrawnLikeTheMesh(await coverage(page));
  const { end } = await pinAndDrag(page, -50, 40);
  const { toCss } = await mapping(page);
  const h = await handles(page);
  const [x, y] = toCss(h[2]!, h[3]!);
  expect(Math.hypot(x - end[0], y - end[1])).toBeLessThan(1);
  expectDrawnLikeTheMesh(await coverage(page));
});

test("an SVG with separate parts: the largest is shown, another can be picked, export stays vector", async ({
  page,
}) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  const svg =
    '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 300 100">' +
    // One shape of two separate pieces (a rectangle and a circle): one layer, not a puppet
    // (two shapes would be two layers).
    '<path d="M 10 10 H 130 V 90 H 10 Z M 250 50 A 30 30 0 1 0 190 50 A 30 30 0 1 0 250 50 Z"/></svg>';
  await page.locator('input[name="shape-file"]').setInputFiles({
    name: "two.svg",
    mimeType: "image/svg+xml",
    buffer: Buffer.from(svg),
  });
  await expect(page.locator(".status")).toContainText("2 separate parts");
  const area = () => page.evaluate(() => window.akapDemo!.widget.mesh.area);
  expect(await area()).toBeCloseTo(120 * 80, 6);
  await page.getByRole("combobox", { name: "Part" }).selectOption("1");
  await expect.poll(area).toBeLessThan(Math.PI * 30 * 30 + 1);
  expect(await area()).toBeGreaterThan(0.99 * Math.PI * 30 * 30);
  await pinAndDrag(page, 20, 20);
  const exported = await page.evaluate(() => window.akapDemo!.widget.exportSvg());
  // The path comes back (arcs of the circle as curves), moved with the mesh.
  expect(exported.match(/<path /g)!.length).toBe(1);
  expect(exported).toMatch(/ C /);
});

test("a file that cannot be read leaves the shape as it was", async ({ page }) => {
  await open(page);
  await pinAndDrag(page, 30, 30);
  const before = await positions(page);
  for (const [name, content] of [
    ["broken.svg", "<svg><path d='M 0 0 L 10'/>"],
    ["notes.txt", "hello"],
    ["empty.obj", "# nothing"],
  ]) {
    await page.locator('input[name="shape-file"]').setInputFiles({
      name: name!,
      mimeType: "text/plain",
      buffer: Buffer.from(content!),
    });
    await expect(page.locator(".status.error")).toContainText(name!);
    expect(await positions(page)).toEqual(before);
  }
});

test("<akap-deformer src=...> poses a file given by URL", async ({ page }) => {
  await page.goto("/www/examples/embed.html");
  await expect(page.locator("body")).toHaveAttribute("data-ready", "true");
  const area = await page.evaluate(async () => {
    const svg =
      '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 120 60"><rect x="10" y="5" width="100" height="50"/></svg>';
    const element = document.createElement("akap-deformer") as HTMLElement & {
      ready: Promise<{ mesh: { area: number } }>;
    };
    element.setAttribute("src", `data:image/svg+xml,${encodeURIComponent(svg)}`);
    element.setAttribute("vertices", "300");
    element.style.height = "200px";
    document.body.append(element);
    return (await element.ready).mesh.area;
  });
  expect(area).toBeCloseTo(100 * 50, 6);
});
