/**
 * The served page, in Chromium: the default shape is drawn where its triangles are, the
 * background stays clear elsewhere, the wireframe toggle draws edges, and it all holds on
 * a HiDPI screen and after a resize. Expected pixels come from the mesh geometry and the
 * view the page reports, not from a stored picture.
 */
import { expect, test, type Page } from "@playwright/test";

interface Probe {
  width: number;
  height: number;
  ratio: number;
  /** Per triangle centroid: is the pixel there the fill colour? */
  centroidsFilled: number;
  triangles: number;
  /** Pixels of the fill colour, and the mesh area in squared device pixels. */
  fillPixels: number;
  expectedFillPixels: number;
  /** Corners of the canvas are background. */
  cornersClear: boolean;
  /** Pixels that are neither fill nor background (edges). */
  edgePixels: number;
}

/** Reads the canvas and compares it with the geometry of the drawn mesh. */
async function probe(page: Page): Promise<Probe> {
  return page.evaluate(() => {
    const canvas = document.getElementById("stage") as HTMLCanvasElement;
    const ctx = canvas.getContext("2d")!;
    const { width, height } = canvas;
    const data = ctx.getImageData(0, 0, width, height).data;
    const state = window.akapDemo!.state;
    const { positions: p, triangles: t } = state.mesh;
    const { scale, offsetX, offsetY } = state.view;
    const rgb = (i: number) => [data[4 * i]!, data[4 * i + 1]!, data[4 * i + 2]!];
    const near = (c: number[], ref: number[]) => c.every((v, k) => Math.abs(v - ref[k]!) <= 6);
    const fill = [0xc8, 0x77, 0x3a];
    const background = [0xf6, 0xf1, 0xe7];
    let centroidsFilled = 0;
    let area = 0;
    for (let i = 0; i < t.length; i += 3) {
      const [a, b, c] = [t[i]!, t[i + 1]!, t[i + 2]!];
      const x = (p[2 * a]! + p[2 * b]! + p[2 * c]!) / 3;
      const y = (p[2 * a + 1]! + p[2 * b + 1]! + p[2 * c + 1]!) / 3;
      const px = Math.floor(offsetX + scale * x);
      const py = Math.floor(offsetY - scale * y);
      if (near(rgb(py * width + px), fill)) centroidsFilled++;
      area +=
        0.5 *
        ((p[2 * b]! - p[2 * a]!) * (p[2 * c + 1]! - p[2 * a + 1]!) -
          (p[2 * c]! - p[2 * a]!) * (p[2 * b + 1]! - p[2 * a + 1]!));
    }
    let fillPixels = 0;
    let edgePixels = 0;
    for (let i = 0; i < width * height; i++) {
      const c = rgb(i);
      if (near(c, fill)) fillPixels++;
      else if (!near(c, background)) edgePixels++;
    }
    const corners = [0, width - 1, (height - 1) * width, height * width - 1];
    return {
      width,
      height,
      ratio: window.devicePixelRatio,
      centroidsFilled,
      triangles: t.length / 3,
      fillPixels,
      expectedFillPixels: area * scale * scale,
      cornersClear: corners.every((i) => near(rgb(i), background)),
      edgePixels,
    };
  });
}

async function open(page: Page): Promise<void> {
  await page.goto("/");
  await expect(page.locator("body")).toHaveAttribute("data-ready", "true");
}

test("draws the default shape filled where its triangles are", async ({ page }) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  await expect(page.locator("#status")).toContainText("triangles");
  const r = await probe(page);
  expect(r.triangles).toBeGreaterThan(500);
  // Small triangles may have their centroid on the drawn boundary line: allow a few.
  expect(r.centroidsFilled).toBeGreaterThan(0.95 * r.triangles);
  expect(r.cornersClear).toBe(true);
  // The filled pixels are the mesh's area in pixels, less the boundary stroke over it.
  expect(r.fillPixels).toBeGreaterThan(0.85 * r.expectedFillPixels);
  expect(r.fillPixels).toBeLessThan(1.01 * r.expectedFillPixels);
  // The shape is fitted: it fills most of the smaller side.
  expect(r.expectedFillPixels).toBeGreaterThan(0.1 * r.width * r.height);
});

test("the wireframe toggle draws the edges and can be turned off again", async ({ page }) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  const plain = await probe(page);
  await page.getByLabel("Wireframe").check();
  const wired = await probe(page);
  expect(wired.edgePixels).toBeGreaterThan(2 * plain.edgePixels);
  expect(wired.fillPixels).toBeLessThan(0.9 * plain.fillPixels);
  await page.keyboard.press("w");
  const again = await probe(page);
  expect(again.edgePixels).toBe(plain.edgePixels);
});

test("renders at device resolution on a HiDPI screen and refits on resize", async ({ browser }) => {
  const context = await browser.newContext({ deviceScaleFactor: 2, viewport: { width: 600, height: 500 } });
  const page = await context.newPage();
  await open(page);
  const box = await page.locator("#stage").boundingBox();
  const hi = await probe(page);
  expect(hi.ratio).toBe(2);
  expect(hi.width).toBe(Math.round(box!.width * 2));
  expect(hi.height).toBe(Math.round(box!.height * 2));
  expect(hi.centroidsFilled).toBeGreaterThan(0.95 * hi.triangles);

  const frame = Number(await page.locator("#stage").getAttribute("data-frame"));
  await page.setViewportSize({ width: 400, height: 800 });
  await expect(page.locator("#stage")).not.toHaveAttribute("data-frame", String(frame));
  const resized = await probe(page);
  expect(resized.width).toBe(800);
  expect(resized.centroidsFilled).toBeGreaterThan(0.95 * resized.triangles);
  expect(resized.cornersClear).toBe(true);
  await context.close();
});
