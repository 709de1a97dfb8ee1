/**
 * The installed package in Chromium, as users embed it (see scripts/test-package.mjs): a
 * Vite app with `mount()` (production build and dev server) and a plain page with
 * `<akap-deformer>`, each drawing the shape, posed by a drag, running the core in a Web
 * Worker, and training a rig in the package's own worker pool.
 */
import { expect, test, type Page } from "@playwright/test";
import { coverage, expectDrawnLikeTheMesh, mapping, pinAndDrag, prepare, type Which } from "../browser/helpers.js";
import { SERVERS } from "./playwright.config.js";

declare global {
  interface Window {
    fromWorker(share?: boolean): Promise<{ vertices?: number; error: number | string }>;
  }
}

test.beforeEach(async ({ context }) => {
  await prepare(context);
});

/** Loads `url`, failing on any page error; waits for the widget. */
async function load(page: Page, url: string, which: Which): Promise<string[]> {
  const errors: string[] = [];
  page.on("pageerror", (error) => errors.push(error.message));
  await page.setViewportSize({ width: 800, height: 600 });
  await page.goto(url);
  await page.waitForFunction((which) => {
    try {
      return window.widgetFor(which).mesh.positions.length > 0;
    } catch {
      return false;
    }
  }, which);
  return errors;
}

/** The shape is drawn where its triangles are, and a drag poses it: the handle ends under the pointer. */
async function drawnAndPosed(page: Page, which: Which): Promise<void> {
  expectDrawnLikeTheMesh(await coverage(page, undefined, which));
  const rest = await page.evaluate((which) => Array.from(window.widgetFor(which).positions()), which);
  const { end } = await pinAndDrag(page, -70, 90, which);
  const posed = await page.evaluate((which) => Array.from(window.widgetFor(which).positions()), which);
  const moved = Math.max(...posed.map((p, i) => Math.abs(p - rest[i]!)));
  const { toCss, unit } = await mapping(page, which);
  expect(moved).toBeGreaterThan(50 * unit);
  const h = await page.evaluate((which) => Array.from(window.widgetFor(which).handlePositions()), which);
  const [x, y] = toCss(h[2]!, h[3]!);
  expect(Math.hypot(x - end[0], y - end[1])).toBeLessThan(1);
  expectDrawnLikeTheMesh(await coverage(page, undefined, which));
}

/**
 * A rig trains on the package's worker pool (a module worker loading the package's wasm)
 * for the handles placed so far, and then poses.
 */
async function rigTrainsInAWorker(page: Page, which: Which): Promise<void> {
  const started: string[] = [];
  page.on("worker", (worker) => started.push(worker.url()));
  const state = await page.evaluate(async (which) => {
    const w = window.widgetFor(which) as unknown as {
      train(o: object): Promise<void>;
      setMethod(m: string): void;
      rig: { state: string; posing: boolean };
    };
    await w.train({ samples: 6, energy: "arap", workers: 1 });
    w.setMethod("defop");
    return w.rig;
  }, which);
  expect(state).toMatchObject({ state: "ready", posing: true });
  expect(started.some((url) => /defop-worker/.test(url))).toBe(true);
}

/** A worker of the page's own poses with the package: a rotation, reproduced exactly. */
async function workerRotates(page: Page, share?: boolean): Promise<void> {
  const result = await page.evaluate((share) => window.fromWorker(share), share);
  expect(result.vertices).toBeGreaterThan(100);
  expect(result.error).toBeLessThan(1e-9);
}

for (const server of ["build", "dev"] as const) {
  test(`a Vite app (${server === "build" ? "production build" : "dev server"}): mount() draws and poses; workers pose`, async ({
    page,
  }) => {
    const errors = await load(page, `${SERVERS[server]}/`, "mounted");
    await drawnAndPosed(page, "mounted");
    await workerRotates(page, true);
    await workerRotates(page, false);
    // Re-meshing runs in the widget's own set-up worker, which loads from the package too.
    const workers = () => page.workers().map((w) => w.url());
    await page.evaluate(() =>
      (window.widgetFor("mounted") as unknown as { remesh(n: number): Promise<void> }).remesh(2500),
    );
    expect(workers().some((url) => /setup-worker/.test(url))).toBe(true);
    expect(await page.evaluate(() => window.widgetFor("mounted").mesh.positions.length / 2)).toBeGreaterThan(2000);
    expectDrawnLikeTheMesh(await coverage(page, undefined, "mounted"));
    await rigTrainsInAWorker(page, "mounted");
    expect(errors).toEqual([]);
  });
}

test("a plain page without a bundler: <akap-deformer> draws and poses; a worker poses", async ({ page }) => {
  const errors = await load(page, `${SERVERS.plain}/plain/`, "element");
  await drawnAndPosed(page, "element");
  await workerRotates(page);
  await rigTrainsInAWorker(page, "element");
  expect(errors).toEqual([]);
});

test("a host that moved the wasm passes its URL or bytes; a wrong URL is an error that says what came back", async ({
  page,
}) => {
  type Akap = typeof import("../../www/src/index.js");
  const wasm = "../node_modules/akap/www/pkg/akap_bg.wasm";
  const vertices = (source: string, asBytes: boolean) =>
    page.evaluate(
      async ({ source, asBytes }) => {
        const akap = (window as unknown as { akap: Akap }).akap;
        try {
          await akap.init(asBytes ? await (await fetch(source)).arrayBuffer() : source);
          return akap.triangulate(akap.defaultShape(), { targetEdgeLength: 0.1 }).vertexCount;
        } catch (error) {
          return String(error);
        }
      },
      { source, asBytes },
    );
  const open = async () => {
    await page.goto(`${SERVERS.plain}/plain/core.html`);
    await page.waitForFunction(() => "akap" in window);
  };
  await open();
  expect(await vertices("./missing.wasm", false)).toMatch(/missing\.wasm answered 404/);
  expect(await vertices("./core.html", false)).toMatch(/answered a text\/html that is not WebAssembly/);
  // Nothing was kept from the failures: the right URL works in the same page.
  expect(await vertices(wasm, false)).toBeGreaterThan(50);
  await open();
  expect(await vertices(wasm, true)).toBeGreaterThan(50);
});
