/**
 * Bones in the app as a person draws them: the bone tool (the toolbar's Tool list) and a drag
 * along the figure's right arm draw a bone, shown as a bar; back to posing, the hand pulled
 * far with a pin at the feet moves the arm's bone as one piece: points along it at rest stay
 * on the segment between its ends, at their fraction of the way, and the ends keep their
 * distance, to 1e-9 of the figure's size. Alt-click with the tool removes the bone, undo
 * brings it back; under MLS the tool says the method has no bones.
 */
import { expect, test } from "@playwright/test";
import { anchorPoints, idle, mapping, open, positions, usePrepared } from "./helpers.js";

usePrepared();

/** Triangle and barycentric coordinates of (x, y) in the mesh at `p`, if inside. */
function locate(p: number[], t: number[], x: number, y: number): { f: number; w: number[] } | undefined {
  for (let f = 0; f < t.length / 3; f++) {
    const [a, b, c] = [0, 1, 2].map((k) => [p[2 * t[3 * f + k]!]!, p[2 * t[3 * f + k]! + 1]!] as const);
    const area = (b![0] - a![0]) * (c![1] - a![1]) - (b![1] - a![1]) * (c![0] - a![0]);
    const wa = ((b![0] - x) * (c![1] - y) - (b![1] - y) * (c![0] - x)) / area;
    const wb = ((c![0] - x) * (a![1] - y) - (c![1] - y) * (a![0] - x)) / area;
    const w = [wa, wb, 1 - wa - wb];
    if (w.every((v) => v >= -1e-12)) return { f, w };
  }
  return undefined;
}

function at(p: number[], t: number[], { f, w }: { f: number; w: number[] }): [number, number] {
  const c = [0, 1].map((d) => w.reduce((s, wk, k) => s + wk * p[2 * t[3 * f + k]! + d]!, 0));
  return [c[0]!, c[1]!];
}

test("a bone drawn on the arm moves as one piece; Alt-click removes it, undo brings it back", async ({ page }) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  const { toCss } = await mapping(page);
  const triangles = await page.evaluate(() => Array.from(window.akapDemo!.widget.mesh.triangles));
  const rest = await positions(page);
  const arm: [[number, number], [number, number]] = [
    [0.33, 0.66],
    [0.53, 0.625],
  ];

  await page.getByRole("combobox", { name: "Tool" }).selectOption("bone");
  await page.mouse.move(...toCss(...arm[0]));
  await page.mouse.down();
  await page.mouse.move(...toCss(...arm[1]), { steps: 6 });
  await page.mouse.up();
  await idle(page);
  const drawn = await page.evaluate(() => Array.from(window.akapDemo!.widget.bones()));
  expect(drawn).toHaveLength(4);
  // The ends are where the mouse pressed and let go, to a CSS pixel.
  const { unit } = await mapping(page);
  expect(Math.hypot(drawn[0]! - arm[0][0], drawn[1]! - arm[0][1])).toBeLessThan(1.5 * unit);
  expect(Math.hypot(drawn[2]! - arm[1][0], drawn[3]! - arm[1][1])).toBeLessThan(1.5 * unit);
  expect(await page.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(0);
  // The bar is drawn: the overlay's pixel at the bone's middle is its purple.
  const middle = toCss((drawn[0]! + drawn[2]!) / 2, (drawn[1]! + drawn[3]!) / 2);
  const box = (await page.locator("#app canvas.overlay").boundingBox())!;
  const colour = await page.evaluate(
    ({ x, y }) => {
      const overlay = document.querySelector("#app .akap-host")!.shadowRoot!.querySelector("canvas.overlay");
      const ratio = window.akapDemo!.widget.view.pixelRatio;
      const ctx = (overlay as HTMLCanvasElement).getContext("2d")!;
      return Array.from(ctx.getImageData(Math.round(x * ratio), Math.round(y * ratio), 1, 1).data);
    },
    { x: middle[0] - box.x, y: middle[1] - box.y },
  );
  expect(colour[2]!).toBeGreaterThan(colour[1]! + 40);
  expect(colour[3]!).toBeGreaterThan(200);

  // Points along the bone at rest (its ends first and last).
  const samples = Array.from({ length: 11 }, (_, k) => {
    const s = k / 10;
    const x = drawn[0]! + s * (drawn[2]! - drawn[0]!);
    const y = drawn[1]! + s * (drawn[3]! - drawn[1]!);
    return locate(rest, triangles, x, y)!;
  });
  expect(samples.every((s) => s !== undefined)).toBe(true);
  const length = Math.hypot(drawn[2]! - drawn[0]!, drawn[3]! - drawn[1]!);

  // Pose: a pin at the feet, the hand pulled far up and over.
  await page.getByRole("combobox", { name: "Tool" }).selectOption("pose");
  const { pin, grab } = await anchorPoints(page);
  await page.mouse.click(...toCss(...pin));
  const hand = toCss(...grab);
  await page.mouse.move(...hand);
  await page.mouse.down();
  for (let k = 1; k <= 12; k++) await page.mouse.move(hand[0] - 10 * k, hand[1] - 14 * k);
  await page.mouse.up();
  await idle(page);
  const posed = await positions(page);
  const q = samples.map((s) => at(posed, triangles, s));
  const [a, b] = [q[0]!, q[10]!];
  let worst = Math.abs(Math.hypot(b[0] - a[0], b[1] - a[1]) - length);
  q.forEach(([x, y], k) => {
    const s = k / 10;
    worst = Math.max(worst, Math.hypot(x - (a[0] + s * (b[0] - a[0])), y - (a[1] + s * (b[1] - a[1]))));
  });
  expect(worst).toBeLessThan(1e-9 * 1.34);
  // The arm did move and turn.
  expect(Math.hypot(a[0] - drawn[0]!, a[1] - drawn[1]!)).toBeGreaterThan(0.05);
  expect(await page.evaluate(() => window.akapDemo!.widget.metrics.flipped)).toBe(0);

  // Alt-click on the bone with the tool removes it; undo brings it back.
  await page.keyboard.press("o");
  const now = await page.evaluate(() => Array.from(window.akapDemo!.widget.bones()));
  await page.keyboard.down("Alt");
  await page.mouse.click(...toCss((now[0]! + now[2]!) / 2, (now[1]! + now[3]!) / 2));
  await page.keyboard.up("Alt");
  expect(await page.evaluate(() => window.akapDemo!.widget.bones().length)).toBe(0);
  await page.keyboard.press("Control+z");
  expect(await page.evaluate(() => window.akapDemo!.widget.bones().length)).toBe(4);

  // MLS has no bones: the tool says so.
  await page.getByRole("combobox", { name: "Method" }).selectOption("mls");
  await page.getByRole("combobox", { name: "Tool" }).selectOption("pose");
  await page.getByRole("combobox", { name: "Tool" }).selectOption("bone");
  await expect(page.locator(".akap-host >> .status")).toContainText("has no bones");
});
