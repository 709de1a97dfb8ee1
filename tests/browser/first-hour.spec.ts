/**
 * What a new user meets in the first hour, each as the steps they took: poses that fold
 * triangles over, typing in toolbar fields, sessions of other methods, messages, URL
 * parameters, the HUD, exports of overlapping poses, the view, busy states, help, a phone,
 * a reload, and imported colours.
 */
import { expect, test, type Page } from "@playwright/test";
import { handles, idle, mapping, open, usePrepared } from "./helpers.js";

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
  test(`AKAP follows ${what}, however the triangles fold`, async ({ page }) => {
    // Both used to fail partway ("matrix is not positive definite") and stick for good.
    await page.setViewportSize({ width: 1280, height: 800 });
    await open(page);
    const errors = await collectErrors(page);
    const points = await figurePoints(page);
    for (const foot of points.feet) await page.mouse.click(...foot);
    const start = what.includes("hand") ? points.hand : points.head;
    await page.mouse.move(...start);
    await page.mouse.down();
    for (let k = 1; k <= 40; k++) {
      await page.mouse.move(start[0] + ((end[0] - start[0]) * k) / 40, start[1] + ((end[1] - start[1]) * k) / 40);
    }
    await page.mouse.up();
    await idle(page);
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
}
