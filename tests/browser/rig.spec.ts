/**
 * Trained rigs (DefOp) in the app and the widget: trained in the page's workers from the
 * toolbar with the progress shown to the end, the same on one worker as on several, posed by a drag exactly as `DefOp.evaluate`
 * poses in Node for the same targets, restored from the browser's cache after a reload
 * without training, saved and opened as a file, cancelled mid-way with nothing changed, a
 * failing worker reported, and the example page's shipped rig posed without training. A
 * rig dragged past a fold stops short with "No foldovers" and the HUD says so; a recording
 * of it replays to the same bits in the app, and in a fresh page once the rig is opened
 * (Load asking for the rig before).
 */
import { readFile } from "node:fs/promises";
import { expect, test, type Page } from "@playwright/test";
import { DefOp, DefOpSolver, init } from "../../www/lib/index.js";
import { dragMouse, handles, idle, mapping, open, positions, prepare, usePrepared } from "./helpers.js";

usePrepared();

test.beforeAll(async () => {
  const wasm = await readFile(new URL("../../www/pkg/akap_bg.wasm", import.meta.url));
  await init(wasm);
});

interface RigView {
  state: string;
  source: string | undefined;
  training: boolean;
  posing: boolean;
  radius: number | undefined;
  comparison: number | undefined;
}

const rig = (page: Page): Promise<RigView> =>
  page.evaluate(() => (window.akapDemo!.widget as unknown as { rig: RigView }).rig);

/** The bar at about 300 vertices, a pin at its left end and a handle at its right end. */
async function barWithTwoHandles(page: Page): Promise<void> {
  await page.evaluate(async () => {
    const w = window.akapDemo!.widget;
    await w.setShape("bar", 300);
    const p = w.mesh.positions;
    let [left, right] = [0, 0];
    for (let v = 0; v < p.length / 2; v++) {
      if (p[2 * v]! < p[2 * left]!) left = v;
      if (p[2 * v]! > p[2 * right]!) right = v;
    }
    const ys = Array.from({ length: p.length / 2 }, (_, v) => p[2 * v + 1]!);
    const middle = (Math.min(...ys) + Math.max(...ys)) / 2;
    const inset = 0.03 * (p[2 * right]! - p[2 * left]!);
    w.addHandleAt(p[2 * left]! + inset, middle);
    w.addHandleAt(p[2 * right]! - inset, middle);
  });
  expect(await page.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(2);
}

/** Records the training indicator's progress (percent) in `window.trainingProgress`. */
async function watchProgress(page: Page): Promise<() => Promise<number[]>> {
  await page.evaluate(() => {
    const w = window as unknown as { trainingProgress: number[] };
    w.trainingProgress = [];
    const element = document.querySelector("#app .akap-host")!.shadowRoot!.querySelector(".training")!;
    new MutationObserver(() => {
      const now = element.getAttribute("aria-valuenow");
      if (now !== null) w.trainingProgress.push(Number(now));
    }).observe(element, { attributes: true, attributeFilter: ["aria-valuenow"] });
  });
  return () => page.evaluate(() => (window as unknown as { trainingProgress: number[] }).trainingProgress);
}

async function trainFromToolbar(page: Page, samples: number): Promise<void> {
  await page.getByRole("spinbutton", { name: "Samples" }).fill(String(samples));
  await page.getByRole("button", { name: "Train", exact: true }).click();
}

test("a rig trained in workers poses a drag as DefOp.evaluate does, and comes back from the cache after a reload", async ({
  page,
}) => {
  test.setTimeout(90_000);
  await page.setViewportSize({ width: 1280, height: 800 });
  await open(page);
  await barWithTwoHandles(page);
  const progress = await watchProgress(page);
  await trainFromToolbar(page, 17);
  await expect.poll(async () => (await rig(page)).state, { timeout: 60_000 }).toBe("ready");
  const trained = await rig(page);
  expect(trained).toMatchObject({ source: "trained", training: false, posing: true });
  // The bar advanced to the end, never back.
  const seen = await progress();
  expect(seen.length).toBeGreaterThan(1);
  expect(seen.at(-1)).toBe(100);
  seen.slice(1).forEach((p, i) => expect(p).toBeGreaterThanOrEqual(seen[i]!));
  await expect(page.getByRole("combobox", { name: "Method" })).toHaveValue("defop");

  // Drag the right handle up; the pose is the operator's for the handles' targets.
  const { toCss } = await mapping(page);
  const h = await handles(page);
  const [x, y] = toCss(h[2]!, h[3]!);
  await dragMouse(page, [x, y], [x - 30, y - 60], 6);
  await idle(page);
  const pose = await positions(page);
  const targets = await handles(page);
  expect(Math.hypot(targets[2]! - h[2]!, targets[3]! - h[3]!)).toBeGreaterThan(0.1);
  const bytes = await page.evaluate(() =>
    Array.from((window.akapDemo!.widget as unknown as { rigFile(): Uint8Array }).rigFile()),
  );
  const op = DefOp.fromBytes(Uint8Array.from(bytes));
  const expected = op.evaluate(targets);
  expect(expected.length).toBe(pose.length);
  let worst = 0;
  expected.forEach((e, i) => (worst = Math.max(worst, Math.abs(e - pose[i]!))));
  expect(worst).toBeLessThan(1e-9);

  // Compare: the ground truth's distance from the pose, as Node's solver gives it (S-ARAP
  // from the rest pose, the rig's handle points, the same targets), over the shape's size.
  await page.getByLabel("Compare").check();
  await expect.poll(async () => (await rig(page)).comparison, { timeout: 20_000 }).toBeDefined();
  const mesh = op.mesh();
  const solver = new DefOpSolver(mesh.positions, mesh.triangles, op.handlePoints(), { energy: "sarap" });
  const truth = solver.solve({ index: 0, targets: Float64Array.from(targets), start: undefined }).positions;
  solver.free();
  const { triangles: ht, barycentric: hb } = op.handlePoints();
  op.free();
  const xs = Array.from(mesh.positions).filter((_, i) => i % 2 === 0);
  const ys = Array.from(mesh.positions).filter((_, i) => i % 2 === 1);
  const size = Math.max(Math.max(...xs) - Math.min(...xs), Math.max(...ys) - Math.min(...ys));
  let far = 0;
  for (let i = 0; i < pose.length; i += 2)
    far = Math.max(far, Math.hypot(pose[i]! - truth[i]!, pose[i + 1]! - truth[i + 1]!));
  // To the solver's tolerance: the page solved for the handles' targets, Node for where the
  // pose put the handles, which agree only to rounding.
  expect((await rig(page)).comparison).toBeCloseTo(far / size, 5);
  expect(far).toBeGreaterThan(0);

  // Region: the training discs about the handles' rest places, and a ring round a handle
  // dragged outside its disc, in the overlay's pixels.
  const { radius } = await rig(page);
  const restRight = [0, 1].map((c) => {
    return [0, 1, 2].reduce((sum, k) => sum + hb[3 + k]! * mesh.positions[2 * mesh.triangles[3 * ht[1]! + k]! + c]!, 0);
  }) as [number, number];
  await page.getByLabel("Region").check();
  const [ex, ey] = toCss(...(Array.from(await handles(page)).slice(2, 4) as [number, number]));
  await dragMouse(page, [ex, ey], [ex - 40, ey - 120], 6);
  const moved = await handles(page);
  expect(Math.hypot(moved[2]! - restRight[0], moved[3]! - restRight[1])).toBeGreaterThan(radius!);
  const pixel = (x: number, y: number) =>
    page.evaluate(
      ([x, y]) => {
        const overlay = document.querySelector("#app .akap-host")!.shadowRoot!.querySelector("canvas.overlay");
        const { view } = window.akapDemo!.widget;
        const at = [view.offsetX + view.scale * x!, view.offsetY - view.scale * y!].map(Math.round);
        return Array.from((overlay as HTMLCanvasElement).getContext("2d")!.getImageData(at[0]!, at[1]!, 1, 1).data);
      },
      [x, y],
    );
  const inDisc: [number, number] = [restRight[0], restRight[1] - 0.9 * radius!];
  expect((await pixel(...inDisc))[3]).toBeGreaterThan(0);
  const ratio = await page.evaluate(() => window.akapDemo!.widget.view.pixelRatio);
  const view = await page.evaluate(() => window.akapDemo!.widget.view);
  const ring: [number, number] = [moved[2]! + (1.9 * 7 * ratio) / view.scale, moved[3]!];
  const [r, g, b] = await pixel(...ring);
  expect(r).toBeGreaterThan(180);
  expect(g).toBeGreaterThan(80);
  expect(g).toBeLessThan(170);
  expect(b).toBeLessThan(90);
  await page.getByLabel("Region").uncheck();
  await idle(page);
  expect((await pixel(...inDisc))[3]).toBe(0);
  const posed = await positions(page);

  // The work is saved a moment after the last change; the reload reads the rig from the cache.
  await page.waitForTimeout(1000);
  await page.reload();
  await expect(page.locator("body")).toHaveAttribute("data-ready", "true");
  expect(await rig(page)).toMatchObject({ state: "ready", source: "cache", training: false, posing: true });
  expect(await positions(page)).toEqual(posed);
});

test("Save rig downloads the operator file, and Open rig poses it in a fresh page", async ({ page, browser }) => {
  test.setTimeout(90_000);
  await page.setViewportSize({ width: 1280, height: 800 });
  await open(page);
  await barWithTwoHandles(page);
  // Two solving workers and a lead, then one worker alone: the same operator, bit for bit.
  const [two, one] = await page.evaluate(async () => {
    const w = window.akapDemo!.widget as unknown as { train(o: object): Promise<void>; rigFile(): Uint8Array };
    await w.train({ samples: 8, energy: "arap", workers: 2 });
    const two = Array.from(w.rigFile());
    await w.train({ samples: 8, energy: "arap", workers: 1, cache: false });
    return [two, Array.from(w.rigFile())];
  });
  expect(two).toEqual(one);
  const { radius } = await rig(page);
  const download = page.waitForEvent("download");
  await page.getByRole("button", { name: "Save rig" }).click();
  const file = (await (await download).path())!;
  const saved = await readFile(file);
  expect(saved.subarray(0, 8).toString("latin1")).toBe("AKAPDEFO");

  const context = await prepare(await browser.newContext({ viewport: { width: 1280, height: 800 } }));
  const fresh = await context.newPage();
  await fresh.goto("/?hud=false");
  await expect(fresh.locator("body")).toHaveAttribute("data-ready", "true");
  await fresh.locator("input[name=rig-file]").setInputFiles({ name: "bar.defop", mimeType: "", buffer: saved });
  await expect.poll(async () => (await rig(fresh)).state).toBe("ready");
  // The file keeps the training's radius (Region works for it), not the other options.
  expect(await rig(fresh)).toMatchObject({ source: "file", posing: true, radius });
  expect(await fresh.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(2);
  // At rest: the operator reproduces the rest pose (to rounding).
  const rest = await fresh.evaluate(() => Array.from(window.akapDemo!.widget.mesh.positions));
  (await positions(fresh)).forEach((x, i) => expect(Math.abs(x - rest[i]!)).toBeLessThan(1e-12));
  // It poses: a handle dragged moves the shape.
  const { toCss } = await mapping(fresh);
  const h = await handles(fresh);
  const [x, y] = toCss(h[2]!, h[3]!);
  await dragMouse(fresh, [x, y], [x, y - 50], 4);
  await idle(fresh);
  const moved = await positions(fresh);
  expect(Math.max(...moved.map((x, i) => Math.abs(x - rest[i]!)))).toBeGreaterThan(0.05);
  await context.close();
});

test("Cancel mid-way leaves AKAP posing as before, and a failing worker is a clear message", async ({ page }) => {
  test.setTimeout(90_000);
  await page.setViewportSize({ width: 1280, height: 800 });
  await open(page);
  await barWithTwoHandles(page);
  const before = await positions(page);
  await trainFromToolbar(page, 5000);
  const indicator = page.locator("#app .akap-host >> .training");
  await expect(indicator).toBeVisible();
  await expect.poll(() => indicator.getAttribute("aria-valuenow").then(Number), { timeout: 30_000 }).toBeGreaterThan(0);
  await indicator.getByRole("button", { name: "Cancel" }).click();
  await expect(indicator).toBeHidden();
  await expect(page.locator(".akap-host >> .status")).toContainText("Training cancelled");
  expect(await rig(page)).toMatchObject({ state: "none", training: false });
  await expect(page.getByRole("combobox", { name: "Method" })).toHaveValue("akap");
  expect(await positions(page)).toEqual(before);
  const { toCss } = await mapping(page);
  const h = await handles(page);
  const [x, y] = toCss(h[2]!, h[3]!);
  await dragMouse(page, [x, y], [x, y - 40], 4);
  await idle(page);
  expect(await positions(page)).not.toEqual(before);

  // A worker whose script fails: the training stops with a message saying so.
  await page.route(/defop-worker/, (route) =>
    route.fulfill({ contentType: "text/javascript", body: 'throw new Error("simulated worker failure");' }),
  );
  await trainFromToolbar(page, 17);
  await expect(page.locator(".akap-host >> .status")).toContainText(/training worker \d+ failed/, { timeout: 20_000 });
  expect(await rig(page)).toMatchObject({ state: "none", training: false });
  await expect(indicator).toBeHidden();
});

test("the rig example poses its shipped rig without training", async ({ page }) => {
  await page.setViewportSize({ width: 1000, height: 700 });
  await page.goto("/www/examples/rig.html");
  await expect(page.locator("body")).toHaveAttribute("data-ready", "true");
  const state = () => page.evaluate(() => (window.widgetFor("element") as unknown as { rig: RigView }).rig);
  expect(await state()).toMatchObject({ state: "ready", source: "file", training: false, posing: true });
  const rest = await page.evaluate(() => Array.from(window.widgetFor("element").positions()));
  const { toCss } = await mapping(page, "element");
  const h = await page.evaluate(() => Array.from(window.widgetFor("element").handlePositions()));
  const [x, y] = toCss(h[0]!, h[1]!);
  await page.mouse.move(x, y);
  await page.mouse.down();
  for (let k = 1; k <= 4; k++) await page.mouse.move(x + 7.5 * k, y - 7.5 * k);
  await page.mouse.up();
  await page.evaluate(() => window.widgetFor("element").whenIdle());
  const moved = await page.evaluate(() => Array.from(window.widgetFor("element").positions()));
  expect(Math.max(...moved.map((x, i) => Math.abs(x - rest[i]!)))).toBeGreaterThan(5);
  await expect(page.locator("#log")).toContainText("evaluated in");
});

test("where the page may not start workers, a rig trains on the page's thread in slices", async ({ page }) => {
  await page.addInitScript(() => {
    // As a Content-Security-Policy without worker-src does: every `new Worker` throws.
    (window as unknown as { Worker: unknown }).Worker = function refused(): never {
      throw new DOMException("refused by the page's policy", "SecurityError");
    };
  });
  await page.setViewportSize({ width: 1280, height: 800 });
  await open(page);
  await barWithTwoHandles(page);
  const workers = await page.evaluate(async () => {
    const seen: number[] = [];
    const w = window.akapDemo!.widget as unknown as {
      train(o: object, progress: (p: { workers: number }) => void): Promise<void>;
    };
    await w.train({ samples: 8, energy: "arap" }, (p) => seen.push(p.workers));
    return seen;
  });
  expect(workers.length).toBeGreaterThan(1);
  expect(new Set(workers)).toEqual(new Set([0]));
  expect(await rig(page)).toMatchObject({ state: "ready", source: "trained", training: false });
});

/** The bits of the widget's positions, 16 hex digits per coordinate. */
const poseBits = (page: Page): Promise<string[]> =>
  page.evaluate(() =>
    Array.from(new BigUint64Array(Float64Array.from(window.akapDemo!.widget.positions()).buffer), (b) =>
      b.toString(16).padStart(16, "0"),
    ),
  );

test("a rig dragged past a fold stops short and the HUD says so; its recording replays with the rig open, and asks for it without", async ({
  page,
  browser,
}) => {
  test.setTimeout(120_000);
  await page.setViewportSize({ width: 1280, height: 800 });
  await open(page, "?hud=true");
  await barWithTwoHandles(page);
  await page.evaluate(async () => {
    const w = window.akapDemo!.widget as unknown as { train(o: object): Promise<void> };
    await w.train({ samples: 8, energy: "arap" });
  });
  await page.getByRole("combobox", { name: "Method" }).selectOption("defop");
  expect(await rig(page)).toMatchObject({ state: "ready", posing: true });
  await page.evaluate(() => {
    const w = window as unknown as { clamped: boolean };
    w.clamped = false;
    document.getElementById("app")!.addEventListener("akap-pose", (e) => {
      w.clamped ||= (e as CustomEvent<{ clamped: boolean }>).detail.clamped;
    });
  });
  await page.getByRole("button", { name: "Record" }).click();
  // The right end pulled through the pinned left end and as far again beyond it.
  const { toCss } = await mapping(page);
  const h = await handles(page);
  const [x, y] = toCss(h[2]!, h[3]!);
  const [left] = toCss(h[0]!, h[1]!);
  await dragMouse(page, [x, y], [2 * left - x, y + 20], 30);
  expect(await page.evaluate(() => (window as unknown as { clamped: boolean }).clamped)).toBe(true);
  await expect(page.locator(".akap-host >> .hud")).toContainText("no foldovers: stopped short");
  expect(await page.evaluate(() => window.akapDemo!.widget.metrics.flipped)).toBe(0);
  await page.getByRole("button", { name: "Stop" }).click();
  const recorded = await poseBits(page);
  let download = page.waitForEvent("download");
  await page.getByRole("button", { name: "Save", exact: true }).click();
  const session = await readFile((await (await download).path())!, "utf8");
  const kinds = (JSON.parse(session) as { events: object[] }).events.map((e) => Object.keys(e)[0]);
  expect(kinds).toContain("rig");
  expect(kinds).toContain("rigPose");
  // The pose at the start (the rig's, off rest by rounding) is the only one recorded.
  expect(kinds.slice(1)).not.toContain("positions");

  // The app's own replay: the same bits.
  await page.getByRole("button", { name: "Replay" }).click();
  await expect(page.locator(".akap-host >> .widget")).not.toHaveAttribute("data-replaying", "true");
  await idle(page);
  expect(await poseBits(page)).toEqual(recorded);

  // A fresh page: without the rig, Load says which rig to open; with it open, the same bits.
  download = page.waitForEvent("download");
  await page.getByRole("button", { name: "Save rig" }).click();
  const operator = await readFile((await (await download).path())!);
  const context = await prepare(await browser.newContext({ viewport: { width: 1280, height: 800 } }));
  const fresh = await context.newPage();
  await fresh.goto("/?hud=false");
  await expect(fresh.locator("body")).toHaveAttribute("data-ready", "true");
  const load = () =>
    fresh
      .locator('input[name="session-file"]')
      .setInputFiles({ name: "rig.json", mimeType: "application/json", buffer: Buffer.from(session) });
  await load();
  await expect(fresh.locator(".status")).toContainText("open that rig's .defop file");
  await fresh.locator("input[name=rig-file]").setInputFiles({ name: "bar.defop", mimeType: "", buffer: operator });
  await expect.poll(async () => (await rig(fresh)).state).toBe("ready");
  await load();
  await expect.poll(() => poseBits(fresh)).toEqual(recorded);
  await expect(fresh.getByRole("combobox", { name: "Method" })).toHaveValue("defop");
  await context.close();
});
