/**
 * Turning a handle in the app as a person would: click a handle to select it, the ring
 * shows as the mouse comes near, a press on the ring carried a quarter turn round turns the
 * region about the handle (its triangle, read from the mesh, turns by about the angle) while
 * a pin stays; Alt-dragging a handle turns it too; undo takes the turn back.
 */
import { expect, test } from "@playwright/test";
import { anchorPoints, idle, mapping, open, positions, prepare, usePrepared } from "./helpers.js";

usePrepared();

test("the ring round a selected handle turns it; Alt-drag too; undo takes it back", async ({ page }) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  const { toCss } = await mapping(page);
  const { pin, grab } = await anchorPoints(page);
  await page.mouse.click(...toCss(...pin));
  const hand = toCss(...grab);
  await page.mouse.click(...hand); // adds the handle, selected
  await idle(page);
  const rest = await positions(page);
  const wrap = (a: number) => a - 2 * Math.PI * Math.round(a / (2 * Math.PI));
  const triangleDirection = (p: number[], t: number[], f: number) =>
    Math.atan2(p[2 * t[3 * f + 1]! + 1]! - p[2 * t[3 * f]! + 1]!, p[2 * t[3 * f + 1]!]! - p[2 * t[3 * f]!]!);
  const { triangles, handle } = await page.evaluate(() => {
    const w = window.akapDemo!.widget;
    return { triangles: Array.from(w.mesh.triangles), handle: Array.from(w.handlePositions()) };
  });
  // The handle's triangle: the one whose centroid is nearest the handle at rest.
  let f = 0;
  let best = Infinity;
  for (let k = 0; k < triangles.length / 3; k++) {
    const c = [0, 1].map(
      (d) =>
        (rest[2 * triangles[3 * k]! + d]! +
          rest[2 * triangles[3 * k + 1]! + d]! +
          rest[2 * triangles[3 * k + 2]! + d]!) /
        3,
    );
    const dist = Math.hypot(c[0]! - handle[2]!, c[1]! - handle[3]!);
    if (dist < best) [best, f] = [dist, k];
  }
  // The ring is 2.6 handle radii (7 px) out: press on it to the right, go a quarter turn round (up on screen).
  const r = 2.6 * 7;
  const around = (a: number): [number, number] => [hand[0] + r * Math.cos(a), hand[1] - r * Math.sin(a)];
  await page.mouse.move(...around(0));
  await page.mouse.down();
  for (let k = 1; k <= 12; k++) await page.mouse.move(...around((Math.PI / 2) * (k / 12)));
  await page.mouse.up();
  await idle(page);
  expect(await page.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(2);
  const turned = await positions(page);
  const angle = wrap(triangleDirection(turned, triangles, f) - triangleDirection(rest, triangles, f));
  expect(angle).toBeGreaterThan(0.75 * (Math.PI / 2));
  expect(angle).toBeLessThan(1.1 * (Math.PI / 2));
  expect(await page.evaluate(() => window.akapDemo!.widget.metrics.flipped)).toBe(0);

  // Undo: back to before the turn.
  await page.keyboard.press("Control+z");
  expect(await positions(page)).toEqual(rest);

  // Alt-drag on the handle turns it the other way.
  await page.keyboard.down("Alt");
  await page.mouse.move(hand[0] + 30, hand[1]);
  await page.mouse.move(...hand);
  await page.mouse.down();
  for (let k = 1; k <= 12; k++) {
    const a = -(Math.PI / 3) * (k / 12);
    await page.mouse.move(hand[0] + 40 * Math.cos(a), hand[1] - 40 * Math.sin(a));
  }
  await page.mouse.up();
  await page.keyboard.up("Alt");
  await idle(page);
  const back = wrap(triangleDirection(await positions(page), triangles, f) - triangleDirection(rest, triangles, f));
  expect(back).toBeLessThan(-0.6 * (Math.PI / 3));
});

test("with a finger the ring shows round the selected handle, and a finger going round it turns the handle", async ({
  browser,
}) => {
  const context = await prepare(await browser.newContext({ hasTouch: true, viewport: { width: 900, height: 700 } }));
  const page = await context.newPage();
  await open(page);
  const cdp = await context.newCDPSession(page);
  const touch = async (type: "touchStart" | "touchMove" | "touchEnd", points: [number, number][]) =>
    cdp.send("Input.dispatchTouchEvent", { type, touchPoints: points.map(([x, y], id) => ({ x, y, id })) });
  const tap = async (at: [number, number]) => {
    await touch("touchStart", [at]);
    await touch("touchEnd", []);
    await idle(page);
  };
  /** The overlay's alpha at a CSS point of the app's widget. */
  const alpha = async (css: [number, number]) => {
    const box = (await page.locator("#app canvas.overlay").boundingBox())!;
    return page.evaluate(
      ({ x, y }) => {
        const overlay = document.querySelector("#app .akap-host")!.shadowRoot!.querySelector("canvas.overlay");
        const ratio = window.akapDemo!.widget.view.pixelRatio;
        const ctx = (overlay as HTMLCanvasElement).getContext("2d")!;
        return ctx.getImageData(Math.round(x * ratio), Math.round(y * ratio), 1, 1).data[3]!;
      },
      { x: css[0] - box.x, y: css[1] - box.y },
    );
  };
  const { toCss } = await mapping(page);
  const { pin, grab } = await anchorPoints(page);
  await tap(toCss(...pin));
  const hand = toCss(...grab);
  await tap(hand); // adds the handle, selected
  expect(await page.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(2);
  // The ring's knob, 2.6 handle radii (7 px) to the right, is drawn: a finger cannot hover.
  const r = 2.6 * 7;
  expect(await alpha([hand[0] + r, hand[1]])).toBeGreaterThan(200);
  const rest = await positions(page);
  const handle = await page.evaluate(() => Array.from(window.akapDemo!.widget.handlePositions()));
  // A finger on the ring, going a quarter turn round (up on screen).
  const around = (a: number): [number, number] => [hand[0] + r * Math.cos(a), hand[1] - r * Math.sin(a)];
  await touch("touchStart", [around(0)]);
  for (let k = 1; k <= 12; k++) await touch("touchMove", [around((Math.PI / 2) * (k / 12))]);
  await touch("touchEnd", []);
  await idle(page);
  expect(await page.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(2);
  // The vertex nearest the handle turned about it by most of the quarter turn.
  const turned = await positions(page);
  let v = 0;
  for (let k = 1; k < rest.length / 2; k++) {
    const d = (i: number) => Math.hypot(rest[2 * i]! - handle[2]!, rest[2 * i + 1]! - handle[3]!);
    if (d(k) > 0.01 && (d(v) <= 0.01 || d(k) < d(v))) v = k;
  }
  const direction = (p: number[]) => Math.atan2(p[2 * v + 1]! - handle[3]!, p[2 * v]! - handle[2]!);
  const now = await page.evaluate(() => Array.from(window.akapDemo!.widget.handlePositions()));
  const turnedBy = Math.atan2(turned[2 * v + 1]! - now[3]!, turned[2 * v]! - now[2]!) - direction(rest);
  const wrapped = turnedBy - 2 * Math.PI * Math.round(turnedBy / (2 * Math.PI));
  expect(wrapped).toBeGreaterThan(0.6 * (Math.PI / 2));
  await context.close();
});
