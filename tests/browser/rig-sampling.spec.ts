/**
 * What a rig keeps, in the app: a rig trained from the toolbar with Voronoi sampling and
 * ARAP shows the Voronoi cells its targets came from in the Region view (a point of a cell
 * far outside every training disc is tinted), its saved file records the sampling and the
 * energy (read back in Node, with and without wasm), and opened in a fresh page it shows
 * the same cells and Compare solves the ground truth with ARAP, its own energy: the
 * distance it reports is the ARAP ground truth's, as Node computes it, not S-ARAP's.
 */
import { readFile } from "node:fs/promises";
import { expect, test, type Page } from "@playwright/test";
import { DefOp, DefOpSolver, init, readOperatorFile } from "../../www/lib/index.js";
import { dragMouse, handles, idle, mapping, open, positions, prepare, usePrepared } from "./helpers.js";

usePrepared();

test.beforeAll(async () => {
  const wasm = await readFile(new URL("../../www/pkg/akap_bg.wasm", import.meta.url));
  await init(wasm);
});

interface RigView {
  state: string;
  source: string | undefined;
  posing: boolean;
  energy: string | undefined;
  sampling: string | undefined;
  comparison: number | undefined;
}

const rig = (page: Page): Promise<RigView> =>
  page.evaluate(() => (window.akapDemo!.widget as unknown as { rig: RigView }).rig);

/** The bar at about 300 vertices, a handle near each end. */
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
}

/** The overlay's pixel (RGBA) at a shape point. */
const pixel = (page: Page, [x, y]: [number, number]) =>
  page.evaluate(
    ([x, y]) => {
      const overlay = document.querySelector("#app .akap-host")!.shadowRoot!.querySelector("canvas.overlay");
      const { view } = window.akapDemo!.widget;
      const at = [view.offsetX + view.scale * x!, view.offsetY - view.scale * y!].map(Math.round);
      return Array.from((overlay as HTMLCanvasElement).getContext("2d")!.getImageData(at[0]!, at[1]!, 1, 1).data);
    },
    [x, y],
  );

/**
 * A point of handle 0's cell farther than 1.3 radii from every handle's rest place (so in
 * no training disc), well inside the cell and on the canvas: the cell's corners pulled
 * towards the handle, the first that qualifies.
 */
async function farInCell(page: Page, op: DefOp): Promise<[number, number]> {
  const { centres, radius, cells } = op.regions();
  const cell = cells![0]!;
  const view = await page.evaluate(() => {
    const { view } = window.akapDemo!.widget;
    const canvas = document.querySelector("#app .akap-host")!.shadowRoot!.querySelector("canvas.overlay");
    return { ...view, width: (canvas as HTMLCanvasElement).width, height: (canvas as HTMLCanvasElement).height };
  });
  for (let k = 0; k < cell.length; k += 2) {
    for (const t of [0.8, 0.7, 0.6, 0.5]) {
      const p: [number, number] = [
        centres[0]! + t * (cell[k]! - centres[0]!),
        centres[1]! + t * (cell[k + 1]! - centres[1]!),
      ];
      const far = [0, 1].every((h) => Math.hypot(p[0] - centres[2 * h]!, p[1] - centres[2 * h + 1]!) > 1.3 * radius);
      const [px, py] = [view.offsetX + view.scale * p[0], view.offsetY - view.scale * p[1]];
      if (far && px > 10 && py > 10 && px < view.width - 10 && py < view.height - 10) return p;
    }
  }
  throw new Error("no point of the cell far from the discs is on the canvas");
}

test("a rig trained with Voronoi sampling shows its cells, and its file keeps the sampling and the energy Compare uses", async ({
  page,
  browser,
}) => {
  test.setTimeout(120_000);
  await page.setViewportSize({ width: 1280, height: 800 });
  await open(page);
  await barWithTwoHandles(page);
  await page.getByRole("combobox", { name: "Energy" }).selectOption("arap");
  await page.getByRole("combobox", { name: "Sampling" }).selectOption("voronoi");
  await page.getByRole("spinbutton", { name: "Samples" }).fill("8");
  await page.getByRole("button", { name: "Train", exact: true }).click();
  await expect.poll(async () => (await rig(page)).state, { timeout: 60_000 }).toBe("ready");
  expect(await rig(page)).toMatchObject({ source: "trained", posing: true, energy: "arap", sampling: "voronoi" });

  // The file records the sampling and the energy.
  const bytes = Uint8Array.from(
    await page.evaluate(() => Array.from((window.akapDemo!.widget as unknown as { rigFile(): Uint8Array }).rigFile())),
  );
  const op = DefOp.fromBytes(bytes);
  expect(op.training).toMatchObject({ energy: "arap", sampling: "voronoi", samples: 8 });
  expect(readOperatorFile(bytes).training).toMatchObject({ energy: "arap", sampling: "voronoi", samples: 8 });
  const regions = op.regions();
  expect([regions.discs, regions.cells?.length]).toEqual([false, 2]);

  // Region: a point of a cell beyond every disc is tinted; without Region it is not.
  const point = await farInCell(page, op);
  await page.getByLabel("Region").check();
  await idle(page);
  expect((await pixel(page, point))[3]).toBeGreaterThan(0);
  await page.getByLabel("Region").uncheck();
  await idle(page);
  expect((await pixel(page, point))[3]).toBe(0);

  // A fresh page opens the file: the same sampling and energy, the same cells drawn.
  const context = await prepare(await browser.newContext({ viewport: { width: 1280, height: 800 } }));
  const fresh = await context.newPage();
  await open(fresh);
  await fresh
    .locator("input[name=rig-file]")
    .setInputFiles({ name: "bar.defop", mimeType: "", buffer: Buffer.from(bytes) });
  await expect.poll(async () => (await rig(fresh)).state).toBe("ready");
  expect(await rig(fresh)).toMatchObject({ source: "file", posing: true, energy: "arap", sampling: "voronoi" });
  const there = await farInCell(fresh, op);
  await fresh.getByLabel("Region").check();
  await idle(fresh);
  expect((await pixel(fresh, there))[3]).toBeGreaterThan(0);
  await fresh.getByLabel("Region").uncheck();

  // Compare in the fresh page (whose rig came from the file alone) solves with ARAP.
  const { toCss } = await mapping(fresh);
  const h = await handles(fresh);
  const [x, y] = toCss(h[2]!, h[3]!);
  // Squeezed lengthwise and bent: where S-ARAP's barrier against compression (1/σ) makes
  // its ground truth differ from ARAP's.
  await dragMouse(fresh, [x, y], [x - 250, y - 80], 8);
  const pose = await positions(fresh);
  const targets = await handles(fresh);
  await fresh.getByLabel("Compare").check();
  await expect.poll(async () => (await rig(fresh)).comparison, { timeout: 20_000 }).toBeDefined();
  const mesh = op.mesh();
  const xs = Array.from(mesh.positions).filter((_, i) => i % 2 === 0);
  const ys = Array.from(mesh.positions).filter((_, i) => i % 2 === 1);
  const size = Math.max(Math.max(...xs) - Math.min(...xs), Math.max(...ys) - Math.min(...ys));
  const distance = (energy: "arap" | "sarap") => {
    const solver = new DefOpSolver(mesh.positions, mesh.triangles, op.handlePoints(), { energy });
    const truth = solver.solve({ index: 0, targets: Float64Array.from(targets), start: undefined }).positions;
    solver.free();
    let far = 0;
    for (let i = 0; i < pose.length; i += 2)
      far = Math.max(far, Math.hypot(pose[i]! - truth[i]!, pose[i + 1]! - truth[i + 1]!));
    return far / size;
  };
  const [arap, sarap] = [distance("arap"), distance("sarap")];
  // The two energies' ground truths are told apart here, far beyond the solver's tolerance.
  expect(Math.abs(arap - sarap)).toBeGreaterThan(1e-4);
  expect((await rig(fresh)).comparison).toBeCloseTo(arap, 5);
  op.free();
  await context.close();
});
