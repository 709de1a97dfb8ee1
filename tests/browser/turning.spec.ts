/**
 * Turning a handle in the app as a person would: click a handle to select it, the ring
 * shows as the mouse comes near, a press on the ring carried a quarter turn round turns the
 * region about the handle (its triangle, read from the mesh, turns by about the angle) while
 * a pin stays; Alt-dragging a handle turns it too; undo takes the turn back.
 */
import { expect, test } from "@playwright/test";
import { anchorPoints, idle, mapping, open, positions, usePrepared } from "./helpers.js";

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
