/**
 * A session recorded in the app, replayed by the core: the app records a session (two
 * drags, a change of method, a reset, one more drag) and saves it; the committed copy of
 * such a recording (`tests/sessions/app/app-recorded.json`, with the bits of the final
 * pose the app reached, `app-recorded.pose.json`) loads back through the file picker to
 * exactly that pose, and `tests/session.rs` replays it in Rust, natively and in wasm, to
 * the same bits.
 *
 * To record the fixture again (after a change of the format, the mesher or a deformer):
 * build, then `AKAP_BLESS_SESSION=1 npx playwright test tests/browser/session.spec.ts`.
 * The test writes both files and then fails on purpose, so that blessing is never silent.
 */
import { readFile, writeFile } from "node:fs/promises";
import { expect, test, type Page } from "@playwright/test";
import { handles, idle, mapping, open, pinAndDrag, usePrepared } from "./helpers.js";

usePrepared();

const FIXTURE = "tests/sessions/app/app-recorded.json";
const POSE = "tests/sessions/app/app-recorded.pose.json";

/** The bits of the widget's positions, 16 hex digits per coordinate (exact, -0 included). */
const poseBits = (page: Page): Promise<string[]> =>
  page.evaluate(() =>
    Array.from(new BigUint64Array(Float64Array.from(window.akapDemo!.widget.positions()).buffer), (b) =>
      b.toString(16).padStart(16, "0"),
    ),
  );

/** Drags handle `index` by (dx, dy) CSS pixels in steps. */
async function dragHandle(page: Page, index: number, dx: number, dy: number): Promise<void> {
  const { toCss } = await mapping(page);
  const h = await handles(page);
  const [x, y] = toCss(h[2 * index]!, h[2 * index + 1]!);
  await page.mouse.move(x, y);
  await page.mouse.down();
  await page.mouse.move(x + dx, y + dy, { steps: 8 });
  await page.mouse.up();
  await idle(page);
}

test("a session recorded in the app replays to the recorded pose; the committed recording to its committed bits", async ({
  page,
}) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page, "?hud=false&shape=gingerbread&vertices=400");
  await page.getByRole("button", { name: "Record" }).click();
  await pinAndDrag(page, -70, 90);
  await dragHandle(page, 1, 30, -20);
  await page.getByRole("combobox", { name: "Method" }).selectOption("arap");
  await dragHandle(page, 1, -40, 10);
  await page.getByRole("button", { name: "Reset" }).click();
  await idle(page);
  await dragHandle(page, 1, 50, 40);
  await page.getByRole("button", { name: "Stop" }).click();
  const recorded = await poseBits(page);
  const download = page.waitForEvent("download");
  await page.getByRole("button", { name: "Save", exact: true }).click();
  const saved = await readFile((await (await download).path())!, "utf8");
  const kinds = (JSON.parse(saved) as { events: object[] }).events.map((e) => Object.keys(e)[0]);
  for (const kind of ["handles", "step", "options", "reset"]) expect(kinds).toContain(kind);
  expect(saved).toContain('"version": 3,');

  // The app's own replay reaches the recorded pose.
  await page.getByRole("button", { name: "Replay" }).click();
  await expect(page.locator(".akap-host >> .widget")).not.toHaveAttribute("data-replaying", "true");
  await idle(page);
  expect(await poseBits(page)).toEqual(recorded);

  if (process.env.AKAP_BLESS_SESSION) {
    await writeFile(FIXTURE, saved);
    await writeFile(POSE, JSON.stringify({ vertexCount: recorded.length / 2, bits: recorded }, null, 0) + "\n");
    throw new Error(`wrote ${FIXTURE} and ${POSE}; run again without AKAP_BLESS_SESSION`);
  }

  // The committed recording, loaded in a fresh page, reaches its committed pose.
  const pose = JSON.parse(await readFile(POSE, "utf8")) as { bits: string[] };
  await open(page);
  await page.locator('input[name="session-file"]').setInputFiles(FIXTURE);
  await expect.poll(() => poseBits(page)).toEqual(pose.bits);
  await expect(page.getByRole("combobox", { name: "Method" })).toHaveValue("arap");
});

test("a session the core refuses is reported with the core's message and changes nothing", async ({ page }) => {
  await open(page);
  await pinAndDrag(page, 50, 50);
  const posed = await poseBits(page);
  const load = (text: string) =>
    page.locator('input[name="session-file"]').setInputFiles({
      name: "broken.json",
      mimeType: "application/json",
      buffer: Buffer.from(text),
    });
  await load('{"format":"akap-session","version":2,"mesh":{"vertexCount":3,"triangleCount":1},"events":[]}');
  await expect(page.locator(".status")).toContainText("must name a built-in shape or carry its mesh");
  expect(await poseBits(page)).toEqual(posed);
  await load(
    '{"format":"akap-session","version":2,"shape":{"name":"gingerbread"},"mesh":{"vertexCount":3,"triangleCount":1},' +
      '"events":[{"step":[1,2]}]}',
  );
  await expect(page.locator(".status")).toContainText("event 0: velocities has 2 numbers, expected 0");
  expect(await poseBits(page)).toEqual(posed);
  expect(await page.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(2);
});
