/**
 * What a new user meets in the first hour, each as the steps they took: poses that fold
 * triangles over, typing in toolbar fields, sessions of other methods, messages, URL
 * parameters, the HUD, exports of overlapping poses, the view, busy states, help, a phone,
 * a reload, and imported colours.
 */
import { expect, test, type Page } from "@playwright/test";
import { dragMouse, handles, idle, mapping, open, pinAndDrag, positions, usePrepared } from "./helpers.js";

usePrepared();

/**
 * CSS pixels of the figure's feet (the lowest triangles left and right of the middle), its
 * raised hand (the leftmost triangle) and its head (just below the highest point).
 */
async function figurePoints(
  page: Page,
): Promise<{ feet: [number, number][]; hand: [number, number]; head: [number, number] }> {
  const shape = await page.evaluate(() => {
    const { positions: p, triangles: t } = window.akapDemo!.widget.mesh;
    const centroids: [number, number][] = [];
    for (let f = 0; f < t.length / 3; f++) {
      let x = 0;
      let y = 0;
      for (let k = 0; k < 3; k++) {
        x += p[2 * t[3 * f + k]!]! / 3;
        y += p[2 * t[3 * f + k]! + 1]! / 3;
      }
      centroids.push([x, y]);
    }
    const mid = centroids.reduce((s, c) => s + c[0], 0) / centroids.length;
    const lowest = (side: (c: [number, number]) => boolean) =>
      centroids.filter(side).reduce((a, b) => (b[1] < a[1] ? b : a));
    const top = centroids.reduce((a, b) => (b[1] > a[1] ? b : a));
    return {
      feet: [lowest((c) => c[0] < mid), lowest((c) => c[0] > mid)],
      hand: centroids.reduce((a, b) => (b[0] < a[0] ? b : a)),
      head: [top[0], top[1] - 0.05] as [number, number],
    };
  });
  const { toCss } = await mapping(page);
  return { feet: shape.feet.map((f) => toCss(...f)), hand: toCss(...shape.hand), head: toCss(...shape.head) };
}

/** Collects the widget's `akap-error` messages in `window.errors`. */
async function collectErrors(page: Page): Promise<() => Promise<string[]>> {
  await page.evaluate(() => {
    const w = window as unknown as { errors: string[] };
    w.errors = [];
    document.getElementById("app")!.addEventListener("akap-error", (e) => {
      w.errors.push((e as CustomEvent<{ message: string }>).detail.message);
    });
  });
  return () => page.evaluate(() => (window as unknown as { errors: string[] }).errors);
}

const statusText = (page: Page) => page.locator(".akap-host >> .status").textContent();

for (const [what, end] of [
  ["the raised hand across the body past the far hip", [950, 700]],
  ["the head down onto the hips", [620, 560]],
] as const) {
  test(`with No foldovers off, AKAP follows ${what}, however the triangles fold`, async ({ page }) => {
    // Both used to fail partway ("matrix is not positive definite") and stick for good.
    await page.setViewportSize({ width: 1280, height: 800 });
    await open(page);
    await page.getByRole("checkbox", { name: "No foldovers" }).uncheck();
    const errors = await collectErrors(page);
    const points = await figurePoints(page);
    for (const foot of points.feet) await page.mouse.click(...foot);
    const start = what.includes("hand") ? points.hand : points.head;
    await dragMouse(page, start, [...end], 40);
    expect(await errors()).toEqual([]);
    expect(await statusText(page)).toBe("");
    const { toCss } = await mapping(page);
    const h = await handles(page);
    const [x, y] = toCss(h[4]!, h[5]!);
    expect(Math.hypot(x - end[0], y - end[1])).toBeLessThan(1);
    // The pins stayed.
    for (const [i, foot] of points.feet.entries()) {
      const [fx, fy] = toCss(h[2 * i]!, h[2 * i + 1]!);
      expect(Math.hypot(fx - foot[0], fy - foot[1])).toBeLessThan(1);
    }
    // Folded triangles are shown, and counted for what is on screen.
    expect(await page.evaluate(() => window.akapDemo!.widget.metrics.flipped)).toBeGreaterThan(0);
  });

  test(`with No foldovers (the default), ${what} ends with no triangle folded`, async ({ page }) => {
    await page.setViewportSize({ width: 1280, height: 800 });
    await open(page, "?hud=true");
    const errors = await collectErrors(page);
    // Whether any frame stopped short (the akap-pose event says so, as the HUD does).
    await page.evaluate(() => {
      const w = window as unknown as { clamped: boolean };
      w.clamped = false;
      document.getElementById("app")!.addEventListener("akap-pose", (e) => {
        w.clamped ||= (e as CustomEvent<{ clamped: boolean }>).detail.clamped;
      });
    });
    const points = await figurePoints(page);
    for (const foot of points.feet) await page.mouse.click(...foot);
    const start = what.includes("hand") ? points.hand : points.head;
    const { toCss } = await mapping(page);
    await dragMouse(page, start, [...end], 40);
    expect(await errors()).toEqual([]);
    expect(await page.evaluate(() => window.akapDemo!.widget.metrics.flipped)).toBe(0);
    // The handle went a good way toward the pointer, where the shape let it; the pins stayed.
    const h = await handles(page);
    const [x, y] = toCss(h[4]!, h[5]!);
    const travelled = Math.hypot(x - start[0], y - start[1]);
    expect(travelled).toBeGreaterThan(0.3 * Math.hypot(end[0] - start[0], end[1] - start[1]));
    for (const [i, foot] of points.feet.entries()) {
      const [fx, fy] = toCss(h[2 * i]!, h[2 * i + 1]!);
      expect(Math.hypot(fx - foot[0], fy - foot[1])).toBeLessThan(1);
    }
    // Where it stopped short, the HUD said so.
    if (Math.hypot(x - end[0], y - end[1]) > 1) {
      expect(await page.evaluate(() => (window as unknown as { clamped: boolean }).clamped)).toBe(true);
    }
  });
}

test("a lambda out of range says what is allowed, stays on screen, and the widget keeps posing", async ({ page }) => {
  // A lambda of 1e308 used to be accepted, and then every step overflowed; it is refused now
  // (1e-6 to 1e10), so nothing a person can do here makes a step fail (the failure path is
  // covered by the Posing unit tests, with a jump beyond the coordinate limit).
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  await pinAndDrag(page, -20, 20);
  const h = await handles(page);
  const method = () => page.evaluate(() => window.akapDemo!.widget.method);
  // Through the API: refused with the range, and nothing changes.
  const refused = await page.evaluate(() => {
    try {
      window.akapDemo!.widget.setMethod("akap", 1e308);
      return "accepted";
    } catch (error) {
      return (error as Error).message;
    }
  });
  expect(refused).toBe("option lambda is 1e308, expected a number from 1e-6 to 1e10");
  expect(await method()).toEqual({ method: "akap", lambda: 100 });
  // Typed into the toolbar: the same words under the shape, kept there.
  const lambda = page.getByRole("spinbutton", { name: "λ" });
  await lambda.fill("1e308");
  await lambda.press("Enter");
  const status = page.locator(".akap-host >> .status.error");
  await expect(status).toContainText("option lambda is 1e308, expected a number from 1e-6 to 1e10");
  expect(await handles(page)).toEqual(h);
  await page.waitForTimeout(600);
  await expect(status).toBeVisible();
  expect(await method()).toEqual({ method: "akap", lambda: 100 });
  // Posing goes on with the lambda it had: a drag reaches the pointer, and clears the message.
  const { toCss } = await mapping(page);
  const [x, y] = toCss(h[2]!, h[3]!);
  await dragMouse(page, [x, y], [x - 30, y + 30], 5);
  await expect(page.locator(".akap-host >> .status")).toHaveText("");
  const after = await handles(page);
  const [ax, ay] = toCss(after[2]!, after[3]!);
  expect(Math.hypot(ax - (x - 30), ay - (y + 30))).toBeLessThan(1);
});

test("keys typed into toolbar fields and lists stay there", async ({ page }) => {
  await page.setViewportSize({ width: 1280, height: 800 });
  await open(page);
  await pinAndDrag(page, 0, 0); // two handles, the second selected
  const vertices = page.getByRole("spinbutton", { name: "Vertices" });
  const before = await vertices.inputValue();
  await vertices.focus();
  await page.keyboard.press("End");
  await page.keyboard.press("Backspace");
  await page.keyboard.press("Backspace");
  await page.keyboard.type("99");
  expect(await vertices.inputValue()).toBe(`${before.slice(0, -2)}99`);
  // Arrow keys move through the method list.
  const method = page.getByRole("combobox", { name: "Method" });
  await method.focus();
  await page.keyboard.press("ArrowDown");
  await expect(method).toHaveValue("akap-no-dirichlet");
  // Backspace in the lambda field edits the number; the selected handle stays.
  const lambda = page.getByRole("spinbutton", { name: "λ" });
  await lambda.focus();
  await page.keyboard.press("End");
  await page.keyboard.press("Backspace");
  expect(await lambda.inputValue()).toBe("10");
  expect(await page.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(2);
});

/** Downloads what the toolbar button `name` saves; returns its text. */
async function downloaded(page: Page, name: string): Promise<{ text: string; path: string }> {
  const download = page.waitForEvent("download");
  await page.getByRole("button", { name, exact: true }).click();
  const d = await download;
  const path = (await d.path())!;
  const fs = await import("node:fs/promises");
  return { text: await fs.readFile(path, "utf8"), path };
}

test("Replay and Save are ready when Stop is pressed; a loaded ARAP session shows ARAP and undoes in one step", async ({
  page,
}) => {
  await page.setViewportSize({ width: 1280, height: 800 });
  await open(page, "");
  await page.getByRole("combobox", { name: "Method" }).selectOption("arap");
  await page.getByRole("button", { name: "Record" }).click();
  await pinAndDrag(page, -60, 50);
  await page.getByRole("button", { name: "Stop" }).click();
  await expect(page.getByRole("button", { name: "Replay" })).toBeEnabled();
  await expect(page.getByRole("button", { name: "Save", exact: true })).toBeEnabled();
  const recorded = await positions(page);
  const { path } = await downloaded(page, "Save");

  // A fresh start (a shape named in the URL), not the ARAP work the app kept.
  await open(page, "?shape=gingerbread");
  await expect(page.getByRole("combobox", { name: "Method" })).toHaveValue("akap");
  await pinAndDrag(page, 30, 30);
  const before = await positions(page);
  await page.locator('input[name="session-file"]').setInputFiles(path);
  await expect.poll(() => positions(page)).toEqual(recorded);
  await expect(page.getByRole("combobox", { name: "Method" })).toHaveValue("arap");
  await expect(page.locator(".akap-host >> .hud")).toContainText("ARAP");
  await page.getByRole("button", { name: "Undo" }).click();
  expect(await positions(page)).toEqual(before);
  await expect(page.getByRole("combobox", { name: "Method" })).toHaveValue("akap");
  await expect(page.locator(".akap-host >> .hud")).toContainText("AKAP");
});

test("messages: an import error goes once a file loads; information is not shown as an error", async ({ page }) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  const file = (name: string, text: string) => ({ name, mimeType: "image/svg+xml", buffer: Buffer.from(text) });
  const picker = page.locator('input[name="shape-file"]');
  await picker.setInputFiles(file("broken.svg", "<svg><path d='M 0 0 L 10'/>"));
  await expect(page.locator(".akap-host >> .status.error")).toContainText("broken.svg");
  const two =
    '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 300 100">' +
    // One shape of two separate pieces (a rectangle and a circle): one layer, not a puppet
    // (two shapes would be two layers).
    '<path d="M 10 10 H 130 V 90 H 10 Z M 250 50 A 30 30 0 1 0 190 50 A 30 30 0 1 0 250 50 Z"/></svg>';
  await picker.setInputFiles(file("two.svg", two));
  const status = page.locator(".akap-host >> .status");
  await expect(status).toContainText("2 separate parts");
  await expect(status).toHaveClass(/info/);
  await expect(status).not.toHaveClass(/error/);
  // The imported file is in the shape list, chosen.
  await expect(page.getByRole("combobox", { name: "Shape" }).locator("option:checked")).toHaveText("two.svg");
  // The next action that succeeds clears the information too.
  await pinAndDrag(page, 10, 10);
  await expect(status).toHaveText("");
});

for (const [query, complaint] of [
  ["?shape=x", "?shape=x"],
  ["?method=foo", "?method=foo"],
  ["?vertices=abc", "?vertices=abc"],
  ["?src=/no-such-file.svg", "no-such-file.svg"],
] as const) {
  test(`a bad URL parameter (${query}) starts the default figure and says what was wrong`, async ({ page }) => {
    await page.goto(`/${query}`);
    await expect(page.locator("body")).toHaveAttribute("data-ready", "true");
    await expect(page.locator(".akap-host >> .status.error")).toContainText(complaint);
    const c = await page.evaluate(() => window.akapDemo!.widget.vertexCount);
    expect(c).toBeGreaterThan(1000);
    await expect(page.getByRole("combobox", { name: "Shape" })).toHaveValue("builtin:gingerbread");
  });
}

test("the HUD checkbox shows a HUD that started hidden, with the figures of the pose on screen", async ({ page }) => {
  await page.setViewportSize({ width: 1280, height: 800 });
  await open(page, "?hud=false");
  const hud = page.locator(".akap-host >> .hud");
  await expect(hud).toBeHidden();
  await page.getByRole("checkbox", { name: "HUD" }).check();
  await expect(hud).toBeVisible();
  // Fold triangles over (No foldovers off): the HUD counts them; after Undo it shows the
  // rest pose's figures.
  await page.getByRole("checkbox", { name: "No foldovers" }).uncheck();
  const points = await figurePoints(page);
  for (const foot of points.feet) await page.mouse.click(...foot);
  await dragMouse(page, points.head, [620, 560], 30);
  const flipped = await page.evaluate(() => window.akapDemo!.widget.metrics.flipped);
  expect(flipped).toBeGreaterThan(0);
  await expect(hud).toContainText(`flipped ${flipped}`);
  await page.keyboard.press("Control+z");
  await expect(hud).toContainText("E_area 2.0000");
  await expect(hud).toContainText("flipped 0");
});

test("a refused number goes back to the value in force; re-meshing keeps pose and handles, and undoes", async ({
  page,
}) => {
  await page.setViewportSize({ width: 1280, height: 800 });
  await open(page);
  const vertices = page.getByRole("spinbutton", { name: "Vertices" });
  const count = await vertices.inputValue();
  await vertices.fill("10");
  await vertices.press("Enter");
  await expect(page.locator(".akap-host >> .status.error")).toContainText("10");
  await expect(vertices).toHaveValue(count);

  await pinAndDrag(page, -60, 80);
  const { toCss } = await mapping(page);
  const before = { handles: await handles(page), positions: await positions(page) };
  await vertices.fill("3000");
  await vertices.press("Enter");
  await expect.poll(() => page.evaluate(() => window.akapDemo!.widget.vertexCount)).toBeGreaterThan(2500);
  await idle(page);
  const after = await handles(page);
  expect(after.length).toBe(before.handles.length);
  for (let i = 0; i < after.length; i += 2) {
    const [x0, y0] = toCss(before.handles[i]!, before.handles[i + 1]!);
    const [x1, y1] = toCss(after[i]!, after[i + 1]!);
    expect(Math.hypot(x1 - x0, y1 - y0)).toBeLessThan(2);
  }
  // The new mesh is posed like the old one: the posed bounding boxes agree to a few pixels.
  const box = (p: number[]) => {
    const xs = p.filter((_, i) => i % 2 === 0);
    const ys = p.filter((_, i) => i % 2 === 1);
    return [Math.min(...xs), Math.min(...ys), Math.max(...xs), Math.max(...ys)];
  };
  const [a, b] = [box(before.positions), box(await positions(page))];
  const { unit } = await mapping(page);
  for (let k = 0; k < 4; k++) expect(Math.abs(a[k]! - b[k]!) / unit).toBeLessThan(3);
  await page.getByRole("button", { name: "Undo" }).click();
  expect(await positions(page)).toEqual(before.positions);
  expect(await handles(page)).toEqual(before.handles);
  await expect(vertices).toHaveValue(count);
});

/** The colour of the screen at a shape point: the mesh canvas under the overlay, as composited. */
async function colourAt(page: Page, x: number, y: number): Promise<[number, number, number]> {
  await idle(page);
  return page.evaluate(
    ({ x, y }) => {
      const shadow = document.querySelector("#app .akap-host")!.shadowRoot!;
      const gl = shadow.querySelector("canvas.mesh") as HTMLCanvasElement;
      const view = window.akapDemo!.widget.view;
      const screen = document.createElement("canvas");
      screen.width = gl.width;
      screen.height = gl.height;
      const ctx = screen.getContext("2d")!;
      ctx.drawImage(gl, 0, 0);
      const px = Math.round(view.offsetX + view.scale * x);
      const py = Math.round(view.offsetY - view.scale * y);
      const d = ctx.getImageData(px, py, 1, 1).data;
      return [d[0]!, d[1]!, d[2]!] as [number, number, number];
    },
    { x, y },
  );
}

test("an imported SVG is drawn in its own colours, and exported in them", async ({ page }) => {
  await page.setViewportSize({ width: 1000, height: 700 });
  await open(page);
  const svg =
    '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 200 100">' +
    '<rect width="120" height="100" fill="#dd2222"/><circle cx="150" cy="50" r="45" style="fill: rgb(34, 34, 221)"/></svg>';
  await page.locator('input[name="shape-file"]').setInputFiles({
    name: "two-colours.svg",
    mimeType: "image/svg+xml",
    buffer: Buffer.from(svg),
  });
  await expect(page.getByRole("combobox", { name: "Shape" }).locator("option:checked")).toHaveText("two-colours.svg");
  // Shape coordinates are the viewBox's with y up: the rect's middle (40, 50), the circle's (170, 50).
  const near = (c: number[], want: number[]) => Math.max(...c.map((v, i) => Math.abs(v - want[i]!)));
  expect(near(await colourAt(page, 40, 50), [0xdd, 0x22, 0x22])).toBeLessThan(12);
  expect(near(await colourAt(page, 170, 50), [0x22, 0x22, 0xdd])).toBeLessThan(12);
  // Posed, the colours move with the mesh; the SVG export keeps each path's colour.
  await pinAndDrag(page, 20, -30);
  const exported = await page.evaluate(() => window.akapDemo!.widget.exportSvg());
  expect(exported).toContain('fill="#dd2222"');
  expect(exported).toContain('fill="#2222dd"');
});

test("the SVG export of a pose whose parts overlap fills the overlap, as the canvas does", async ({ page }) => {
  await page.setViewportSize({ width: 1280, height: 800 });
  await open(page);
  const points = await figurePoints(page);
  for (const foot of points.feet) await page.mouse.click(...foot);
  await dragMouse(page, points.hand, [760, 520], 30);
  const { text } = await downloaded(page, "SVG");
  const filled = await page.evaluate(async (svg) => {
    const p = window.akapDemo!.widget.positions();
    const t = window.akapDemo!.widget.mesh.triangles;
    // A point covered by two triangles (the arm over the body), away from any edge.
    const inside = (x: number, y: number, f: number) => {
      const [a, b, c] = [t[3 * f]!, t[3 * f + 1]!, t[3 * f + 2]!];
      const side = (i: number, j: number) =>
        (p[2 * j]! - p[2 * i]!) * (y - p[2 * i + 1]!) - (p[2 * j + 1]! - p[2 * i + 1]!) * (x - p[2 * i]!);
      const s = [side(a, b), side(b, c), side(c, a)];
      return s.every((v) => v > 1e-6) || s.every((v) => v < -1e-6);
    };
    let minX = Infinity;
    let minY = Infinity;
    let maxX = -Infinity;
    let maxY = -Infinity;
    for (let i = 0; i < p.length; i += 2) {
      minX = Math.min(minX, p[i]!);
      maxX = Math.max(maxX, p[i]!);
      minY = Math.min(minY, p[i + 1]!);
      maxY = Math.max(maxY, p[i + 1]!);
    }
    const overlaps: [number, number][] = [];
    for (let gx = 0; gx <= 60; gx++) {
      for (let gy = 0; gy <= 60; gy++) {
        const x = minX + ((maxX - minX) * gx) / 60;
        const y = minY + ((maxY - minY) * gy) / 60;
        let count = 0;
        for (let f = 0; f < t.length / 3 && count < 2; f++) if (inside(x, y, f)) count++;
        if (count >= 2) overlaps.push([x, y]);
      }
    }
    // The export fits the pose in its viewBox with equal margins, y down.
    const [, , vw, vh] = /viewBox="([^"]+)"/.exec(svg)![1]!.split(" ").map(Number) as [number, number, number, number];
    const margin = (vw - (maxX - minX)) / 2;
    const image = new Image();
    image.src = URL.createObjectURL(new Blob([svg], { type: "image/svg+xml" }));
    await image.decode();
    const k = 800 / vw;
    const canvas = document.createElement("canvas");
    canvas.width = 800;
    canvas.height = Math.ceil(vh * k);
    const ctx = canvas.getContext("2d")!;
    ctx.drawImage(image, 0, 0, canvas.width, canvas.height);
    return overlaps.map(([x, y]) => {
      // The pose's bounding box sits in the viewBox with the margin on every side, y down.
      const px = Math.round((x - minX + margin) * k);
      const py = Math.round((maxY + margin - y) * k);
      return ctx.getImageData(px, py, 1, 1).data[3]!;
    });
  }, text);
  expect(filled.length).toBeGreaterThan(3);
  for (const alpha of filled) expect(alpha).toBe(255);
});
