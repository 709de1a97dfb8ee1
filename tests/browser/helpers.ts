/**
 * What the browser tests share: reaching a widget in the page, reading its state, mapping
 * shape points to CSS pixels, the drawn picture against the mesh's own footprint, and
 * the gestures most tests start with.
 */
import { expect, test, type BrowserContext, type Page } from "@playwright/test";

/** Which widget: the app's, or the embedding example's mounted one or element. */
export type Which = "app" | "mounted" | "element";

export interface WidgetView {
  view: { scale: number; offsetX: number; offsetY: number; pixelRatio: number };
  mesh: { positions: Float64Array; triangles: Uint32Array };
  positions(): Float64Array;
  handlePositions(): Float64Array;
  whenIdle(): Promise<void>;
}

declare global {
  interface Window {
    widgetFor(which: Which): WidgetView;
  }
}

/** Defines `window.widgetFor` in every page of the context. */
export async function prepare(context: BrowserContext): Promise<BrowserContext> {
  await context.addInitScript(() => {
    window.widgetFor = (which) => {
      const w = window as unknown as { akapDemo?: { widget: WidgetView }; embedded?: { widget: WidgetView } };
      if (which === "app") return w.akapDemo!.widget;
      if (which === "mounted") return w.embedded!.widget;
      return (document.getElementById("element") as unknown as { widget: WidgetView }).widget;
    };
  });
  return context;
}

/** Every test's pages get `window.widgetFor`. */
export function usePrepared(): void {
  test.beforeEach(async ({ context }) => {
    await prepare(context);
  });
}

/** How the drawn picture compares with the mesh's own footprint. */
export interface Coverage {
  width: number;
  height: number;
  /** Pixels inside the mesh footprint, and pixels that look like the shape. */
  maskPixels: number;
  shapePixels: number;
  /** Shape-looking pixels more than 2 px outside the footprint. */
  stray: number;
  /** Footprint pixels more than 2 px inside that look like background. */
  missing: number;
  /** Dark pixels (outline, wireframe). */
  dark: number;
}

/**
 * Composites the widget's canvases (WebGL mesh and 2D overlay) as the screen shows them,
 * rasterises the triangles of `positions` (default: the current pose) through the
 * widget's view, and counts disagreements.
 */
export async function coverage(page: Page, positions?: number[], which: Which = "app"): Promise<Coverage> {
  // The widget draws in animation frames: read the picture once it is drawn.
  await page.evaluate((which) => window.widgetFor(which).whenIdle(), which);
  return page.evaluate(
    ({ positions, which }) => {
      const typed = window.widgetFor(which);
      const host = document.querySelector(
        `${{ app: "#app", mounted: "#mounted", element: "#element" }[which]} .akap-host`,
      )!;
      const shadow = host.shadowRoot!;
      const gl = shadow.querySelector("canvas.mesh") as HTMLCanvasElement;
      const overlay = shadow.querySelector("canvas.overlay") as HTMLCanvasElement;
      const { width, height } = gl;
      const screen = document.createElement("canvas");
      screen.width = width;
      screen.height = height;
      const sctx = screen.getContext("2d")!;
      sctx.drawImage(gl, 0, 0);
      sctx.drawImage(overlay, 0, 0);
      const pixels = sctx.getImageData(0, 0, width, height).data;

      const p = positions ?? Array.from(typed.positions());
      const t = typed.mesh.triangles;
      const { scale, offsetX, offsetY } = typed.view;
      const mask = document.createElement("canvas");
      mask.width = width;
      mask.height = height;
      const mctx = mask.getContext("2d")!;
      mctx.fillStyle = "#000";
      mctx.beginPath();
      for (let i = 0; i < t.length; i += 3) {
        for (let k = 0; k < 3; k++) {
          const v = t[i + k]!;
          const x = offsetX + scale * p[2 * v]!;
          const y = offsetY - scale * p[2 * v + 1]!;
          if (k === 0) mctx.moveTo(x, y);
          else mctx.lineTo(x, y);
        }
        mctx.closePath();
      }
      mctx.fill();
      const m = mctx.getImageData(0, 0, width, height).data;
      const inMask = (x: number, y: number) =>
        x >= 0 && y >= 0 && x < width && y < height && m[4 * (y * width + x) + 3]! > 127;
      const background = [0xf6, 0xf1, 0xe7];
      const isShape = (i: number) =>
        Math.max(...[0, 1, 2].map((k) => Math.abs(pixels[4 * i + k]! - background[k]!))) > 24;
      // Handle discs and the turning rings round selected handles (2.6 handle radii of 7 CSS
      // pixels, shown after a finger's press) may reach past the outline: leave them out.
      const h = typed.handlePositions();
      const reach = 24 * typed.view.pixelRatio;
      const nearHandle = (x: number, y: number) => {
        for (let k = 0; k < h.length; k += 2) {
          if (Math.hypot(x - (offsetX + scale * h[k]!), y - (offsetY - scale * h[k + 1]!)) < reach) return true;
        }
        return false;
      };
      const r = 2;
      let maskPixels = 0;
      let shapePixels = 0;
      let stray = 0;
      let missing = 0;
      let dark = 0;
      for (let y = 0; y < height; y++) {
        for (let x = 0; x < width; x++) {
          const i = y * width + x;
          const shape = isShape(i);
          const inside = inMask(x, y);
          if (inside) maskPixels++;
          if (shape) shapePixels++;
          if (pixels[4 * i]! + pixels[4 * i + 1]! + pixels[4 * i + 2]! < 300) dark++;
          if (shape === inside || nearHandle(x, y)) continue;
          // Disagreements count only away from the footprint's edge.
          let all = true;
          let any = false;
          for (let dy = -r; dy <= r; dy++) {
            for (let dx = -r; dx <= r; dx++) {
              const b = inMask(x + dx, y + dy);
              all &&= b;
              any ||= b;
            }
          }
          if (shape && !any) stray++;
          if (!shape && all) missing++;
        }
      }
      return { width, height, maskPixels, shapePixels, stray, missing, dark };
    },
    { positions, which },
  );
}

/** The drawing covers the mesh's triangles, and the mesh at least `minShare` of the canvas. */
export function expectDrawnLikeTheMesh(c: Coverage, minShare = 0.05): void {
  expect(c.maskPixels).toBeGreaterThan(minShare * c.width * c.height);
  expect(c.stray).toBeLessThan(0.002 * c.maskPixels);
  expect(c.missing).toBeLessThan(0.002 * c.maskPixels);
}

export async function open(page: Page, query = "?hud=false"): Promise<void> {
  await page.goto(`/${query}`);
  await expect(page.locator("body")).toHaveAttribute("data-ready", "true");
}

/** Widget state read through the page. */
export const positions = (page: Page): Promise<number[]> =>
  page.evaluate(() => Array.from(window.akapDemo!.widget.positions()));
export const handles = (page: Page): Promise<number[]> =>
  page.evaluate(() => Array.from(window.akapDemo!.widget.handlePositions()));
export const idle = (page: Page): Promise<void> => page.evaluate(() => window.akapDemo!.widget.whenIdle());

/** CSS pixel of a shape point, and shape units per CSS pixel. */
export async function mapping(
  page: Page,
  which: Which = "app",
): Promise<{ toCss: (x: number, y: number) => [number, number]; unit: number }> {
  const selector = { app: "#app", mounted: "#mounted", element: "#element" }[which];
  const box = (await page.locator(`${selector} canvas.overlay`).boundingBox())!;
  const view = await page.evaluate((which) => window.widgetFor(which).view, which);
  return {
    toCss: (x, y) => [
      box.x + (view.offsetX + view.scale * x) / view.pixelRatio,
      box.y + (view.offsetY - view.scale * y) / view.pixelRatio,
    ],
    unit: view.pixelRatio / view.scale,
  };
}

/** Two well separated points inside the rest shape: near the lowest vertex and the rightmost. */
export async function anchorPoints(
  page: Page,
  which: Which = "app",
): Promise<{ pin: [number, number]; grab: [number, number] }> {
  return page.evaluate((which) => {
    const { positions: p, triangles: t } = window.widgetFor(which).mesh;
    const centroid = (f: number): [number, number] => {
      let x = 0;
      let y = 0;
      for (let k = 0; k < 3; k++) {
        x += p[2 * t[3 * f + k]!]! / 3;
        y += p[2 * t[3 * f + k]! + 1]! / 3;
      }
      return [x, y];
    };
    let low = 0;
    let right = 0;
    for (let f = 0; f < t.length / 3; f++) {
      if (centroid(f)[1] < centroid(low)[1]) low = f;
      if (centroid(f)[0] > centroid(right)[0]) right = f;
    }
    return { pin: centroid(low), grab: centroid(right) };
  }, which);
}

/** Adds a pin and drags a second handle by (dx, dy) CSS pixels in steps; returns the pointer's end. */
export async function pinAndDrag(
  page: Page,
  dx: number,
  dy: number,
  which: Which = "app",
): Promise<{ end: [number, number]; pin: [number, number] }> {
  const { toCss } = await mapping(page, which);
  const { pin, grab } = await anchorPoints(page, which);
  const [px, py] = toCss(...pin);
  await page.mouse.click(px, py);
  const [gx, gy] = toCss(...grab);
  await page.mouse.move(gx, gy);
  await page.mouse.down();
  for (let k = 1; k <= 12; k++) await page.mouse.move(gx + (dx * k) / 12, gy + (dy * k) / 12);
  await page.mouse.up();
  await page.evaluate((which) => window.widgetFor(which).whenIdle(), which);
  return { end: [gx + dx, gy + dy], pin: [px, py] };
}

/** Drags the mouse from one CSS point to another in `steps` moves, then waits for the widget to settle. */
export async function dragMouse(page: Page, from: [number, number], to: [number, number], steps = 8): Promise<void> {
  await page.mouse.move(...from);
  await page.mouse.down();
  await page.mouse.move(...to, { steps });
  await page.mouse.up();
  await idle(page);
}
