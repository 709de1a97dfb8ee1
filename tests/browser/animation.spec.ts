/**
 * Keyframed animation in the app, as a person makes it: K with two handles placed, the
 * playhead moved on the strip, a handle dragged, K again, three keys; Play twice (the
 * frames computed afresh in between) shows the same frames, bit for bit, and they are
 * `animationFrames()`. Each export decoded back in the page: frame count, size, first and
 * last frames against the picture the stage draws. An export cancelled midway takes the
 * progress bar away and downloads nothing.
 */
import { readFile } from "node:fs/promises";
import { expect, test, type Page } from "@playwright/test";
import { animationFromJson, init } from "../../www/lib/index.js";
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

/** In the page: pixels of images and video frames, and how two of them differ. */
async function definePixelHelpers(page: Page): Promise<void> {
  await page.evaluate(() => {
    const pixels = (source: CanvasImageSource, width: number, height: number): Uint8ClampedArray => {
      const canvas = document.createElement("canvas");
      [canvas.width, canvas.height] = [width, height];
      const ctx = canvas.getContext("2d")!;
      ctx.drawImage(source, 0, 0, width, height);
      return ctx.getImageData(0, 0, width, height).data;
    };
    /** The picture the stage draws of frame `index` (a seek, then the PNG export of it). */
    const drawn = async (index: number) => {
      const w = window.akapDemo!.widget;
      w.seek(index / 24);
      await w.whenIdle();
      const bitmap = await createImageBitmap(await w.exportPng());
      return { data: pixels(bitmap, bitmap.width, bitmap.height), width: bitmap.width, height: bitmap.height };
    };
    /** Mean and largest absolute difference of two RGBA pictures' channels. */
    const difference = (a: Uint8ClampedArray, b: Uint8ClampedArray) => {
      let [sum, most] = [0, 0];
      for (let i = 0; i < a.length; i++) {
        const d = Math.abs(a[i]! - b[i]!);
        sum += d;
        most = Math.max(most, d);
      }
      return { mean: sum / a.length, most };
    };
    Object.assign(window, { pixels, drawn, difference });
  });
}

interface PixelHelpers {
  pixels(source: CanvasImageSource, width: number, height: number): Uint8ClampedArray;
  drawn(index: number): Promise<{ data: Uint8ClampedArray; width: number; height: number }>;
  difference(a: Uint8ClampedArray, b: Uint8ClampedArray): { mean: number; most: number };
}

test("a WebM export has the canvas's size, a frame per frame's time, and the drawn first and last frames", async ({
  page,
}) => {
  test.setTimeout(60_000);
  await page.setViewportSize({ width: 700, height: 560 });
  await open(page);
  await recordThreeKeys(page);
  await definePixelHelpers(page);
  const result = await page.evaluate(async () => {
    const h = window as unknown as PixelHelpers;
    const w = window.akapDemo!.widget;
    const progress: number[] = [];
    const blob = (await w.exportAnimation("webm", { onProgress: (done) => progress.push(done) })) as Blob;
    const video = document.createElement("video");
    video.muted = true;
    video.src = URL.createObjectURL(blob);
    await new Promise((resolve, reject) => {
      video.onloadedmetadata = resolve;
      video.onerror = () => reject(new Error("the video could not be read"));
    });
    // MediaRecorder writes no duration: reading to the end finds it.
    if (!Number.isFinite(video.duration)) {
      video.currentTime = 1e6;
      await new Promise((resolve) => (video.ondurationchange = resolve));
    }
    const seek = async (time: number) => {
      video.currentTime = time;
      await new Promise((resolve) => (video.onseeked = resolve));
      return h.pixels(video, video.videoWidth, video.videoHeight);
    };
    const firstFrame = await seek(0);
    const lastFrame = await seek(Math.max(0, video.duration - 0.5 / 24));
    const [first, last] = [await h.drawn(0), await h.drawn(24)];
    return {
      type: blob.type,
      size: [video.videoWidth, video.videoHeight],
      drawnSize: [first.width, first.height],
      duration: video.duration,
      progress,
      first: h.difference(firstFrame, first.data),
      last: h.difference(lastFrame, last.data),
      firstVsLast: h.difference(first.data, last.data),
    };
  });
  expect(result.type).toBe("video/webm");
  expect(result.size).toEqual(result.drawnSize);
  expect(result.progress).toEqual(Array.from({ length: FPS + 1 }, (_, i) => i + 1));
  // 25 frames of 1/24 s: about 1.04 s (the recorder's clock is the page's).
  expect(result.duration).toBeGreaterThan(0.8);
  expect(result.duration).toBeLessThan(1.6);
  // Lossy video: close on average; the first and last drawn frames differ far more.
  expect(result.firstVsLast.mean).toBeGreaterThan(1);
  expect(result.first.mean).toBeLessThan(0.35 * result.firstVsLast.mean);
  expect(result.last.mean).toBeLessThan(0.35 * result.firstVsLast.mean);
});

test("an export cancelled midway takes its progress bar away and downloads nothing", async ({ page }) => {
  await page.setViewportSize({ width: 700, height: 560 });
  await open(page);
  await recordThreeKeys(page);
  const downloads: string[] = [];
  page.on("download", (d) => downloads.push(d.suggestedFilename()));
  const busy = page.locator("#app .akap-host .busy");
  await strip(page).exportMenu.selectOption("webm");
  await expect(busy).toBeVisible();
  await expect(busy.locator("progress")).toBeVisible();
  await busy.getByRole("button", { name: "Cancel" }).click();
  await expect(busy).toBeHidden();
  await expect(page.locator("#app .akap-host .status")).toHaveText("Export cancelled; nothing was saved.");
  await page.waitForTimeout(1500);
  expect(downloads).toEqual([]);
  // Through the API: a GIF aborted after three frames rejects with an AbortError, and the
  // pose on screen is the one before the export.
  const aborted = await page.evaluate(async () => {
    const w = window.akapDemo!.widget;
    const before = Array.from(w.positions());
    const controller = new AbortController();
    let frames = 0;
    const error = await w
      .exportAnimation("gif", {
        signal: controller.signal,
        onProgress: (done) => {
          frames = done;
          if (done === 3) controller.abort();
        },
      })
      .catch((e: unknown) => e as Error);
    const after = Array.from(w.positions());
    return { name: (error as Error).name, frames, same: after.every((v, i) => v === before[i]) };
  });
  expect(aborted).toEqual({ name: "AbortError", frames: 3, same: true });
  // And one that is not cancelled downloads its file.
  const download = page.waitForEvent("download");
  await strip(page).exportMenu.selectOption("webm");
  expect((await download).suggestedFilename()).toBe("animation.webm");
});

test("the strip: scrubbing shows each frame (undone as one step), a key dragged moves, Delete deletes it, Space plays", async ({
  page,
}) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  await recordThreeKeys(page);
  const w = () => page.evaluate(() => Array.from(window.akapDemo!.widget.positions()));
  const frames = await page.evaluate(() => window.akapDemo!.widget.animationFrames().map((f) => Array.from(f)));
  const before = await w();
  // Scrub from 0.125 s to 0.5 s: the pose follows, and is frame 12 where the pointer stops.
  const box = (await strip(page).track.boundingBox())!;
  const y = box.y + box.height / 2;
  await page.mouse.move(box.x + box.width / 16, y);
  await page.mouse.down();
  expect(await w()).toEqual(frames[3]);
  await page.mouse.move(box.x + box.width / 8, y, { steps: 4 });
  await page.mouse.move(box.x + box.width / 4, y, { steps: 4 });
  await page.mouse.up();
  expect(await w()).toEqual(frames[12]);
  await expect(strip(page).root.locator(".readout")).toHaveText("0.50 s / 1.00 s · frame 13/25");
  await page.locator("#app .akap-host .widget").focus();
  await page.keyboard.press("Control+z");
  expect(await w()).toEqual(before);

  // The playhead by keyboard on the track: End, then a frame back.
  await strip(page).track.focus();
  await page.keyboard.press("End");
  expect(await w()).toEqual(frames[24]);
  await page.keyboard.press("ArrowLeft");
  expect(await w()).toEqual(frames[23]);
  await expect(strip(page).track).toHaveAttribute("aria-valuetext", "0.96 seconds");

  // The middle key dragged from 0.5 s to 0.75 s.
  const marker = strip(page).markers.nth(1);
  const m = (await marker.boundingBox())!;
  await dragMouse(page, [m.x + m.width / 2, m.y + m.height / 2], [box.x + (box.width * 0.75) / 2, y]);
  expect(await page.evaluate(() => window.akapDemo!.widget.keys().map((k) => k.time))).toEqual([0, 0.75, 1]);
  // Selected by the drag: Delete in the strip deletes it (and no handle).
  await marker.focus();
  await page.keyboard.press("Delete");
  expect(await page.evaluate(() => window.akapDemo!.widget.keys().map((k) => k.time))).toEqual([0, 1]);
  expect(await page.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(2);

  // A tap of Space on the stage plays.
  await page.locator("#app .akap-host .widget").focus();
  await page.keyboard.press(" ");
  await expect(strip(page).play).toHaveText("Pause");
  await expect(strip(page).play).toHaveText("Play", { timeout: 10_000 });
  expect(await w()).toEqual(await page.evaluate(() => Array.from(window.akapDemo!.widget.animationFrames().at(-1)!)));

  // Loop: playback goes round (frame 0 after the last) until paused.
  await page.evaluate(() => {
    const w = window as unknown as { seen: number[] };
    w.seen = [];
    document.getElementById("app")!.addEventListener("akap-frame", (e) => {
      w.seen.push((e as CustomEvent<{ index: number }>).detail.index);
    });
  });
  await strip(page).root.getByLabel("Loop").check();
  await strip(page).play.click();
  await expect
    .poll(() =>
      page.evaluate(() => {
        const seen = (window as unknown as { seen: number[] }).seen;
        return seen.some((index, i) => i > 0 && index < seen[i - 1]!);
      }),
    )
    .toBe(true);
  await strip(page).play.click();
  await expect(strip(page).play).toHaveText("Play");

  // 12 fps: 13 frames for the same second.
  await strip(page).root.locator("input.fps").fill("12");
  await strip(page).root.locator("input.fps").press("Enter");
  expect(await page.evaluate(() => window.akapDemo!.widget.animationFrames().length)).toBe(13);

  // Another handle set: K is refused, saying what to do.
  const { toCss } = await mapping(page);
  const third = await page.evaluate(() => {
    // The centroid of a triangle half way through the list: on the shape, far from the handles.
    const { positions: p, triangles: t } = window.akapDemo!.widget.mesh;
    const f = Math.floor(t.length / 6);
    const at = (d: number) => (p[2 * t[3 * f]! + d]! + p[2 * t[3 * f + 1]! + d]! + p[2 * t[3 * f + 2]! + d]!) / 3;
    return [at(0), at(1)] as [number, number];
  });
  await page.mouse.click(...toCss(...third));
  await idle(page);
  expect(await page.evaluate(() => window.akapDemo!.widget.handleCount)).toBe(3);
  await page.keyboard.press("k");
  await expect(page.locator("#app .akap-host .status")).toContainText("another set of handles");
  expect(await page.evaluate(() => window.akapDemo!.widget.keys().length)).toBe(2);
});

test("GIF, APNG, sprite sheet, JSON and SVG exports decode back to the frames drawn", async ({ page }) => {
  test.setTimeout(120_000);
  await page.setViewportSize({ width: 640, height: 520 });
  await open(page);
  await recordThreeKeys(page);
  await definePixelHelpers(page);
  const result = await page.evaluate(async () => {
    const h = window as unknown as PixelHelpers;
    const w = window.akapDemo!.widget;
    const [first, last] = [await h.drawn(0), await h.drawn(24)];
    const animated = async (format: "gif" | "apng") => {
      const progress: number[] = [];
      const blob = await w.exportAnimation(format, { onProgress: (done, total) => progress.push(done / total) });
      const decoder = new ImageDecoder({
        data: await blob.arrayBuffer(),
        type: format === "gif" ? "image/gif" : "image/png",
      });
      await decoder.tracks.ready;
      await decoder.completed;
      const frame = async (index: number) => {
        const { image } = await decoder.decode({ frameIndex: index });
        const data = h.pixels(image, image.displayWidth, image.displayHeight);
        const size = [image.displayWidth, image.displayHeight];
        image.close();
        return { data, size };
      };
      const count = decoder.tracks.selectedTrack!.frameCount;
      const [f0, fn] = [await frame(0), await frame(count - 1)];
      decoder.close();
      return {
        type: blob.type,
        count,
        size: f0.size,
        lastProgress: progress.at(-1),
        first: h.difference(f0.data, first.data),
        last: h.difference(fn.data, last.data),
      };
    };
    const gif = await animated("gif");
    const apng = await animated("apng");
    // The sprite sheet: its size is the table's, its first and last cells the frames drawn.
    const sheet = (await w.exportAnimation("sprites")) as { png: Blob; table: string };
    const table = JSON.parse(sheet.table) as {
      format: string;
      size: { w: number; h: number };
      frames: { x: number; y: number; w: number; h: number; duration: number }[];
    };
    const bitmap = await createImageBitmap(sheet.png);
    const cell = (k: number) => {
      const { x, y, w: cw, h: ch } = table.frames[k]!;
      const canvas = document.createElement("canvas");
      [canvas.width, canvas.height] = [cw, ch];
      const ctx = canvas.getContext("2d")!;
      ctx.drawImage(bitmap, x, y, cw, ch, 0, 0, cw, ch);
      return ctx.getImageData(0, 0, cw, ch).data;
    };
    const sprites = {
      format: table.format,
      size: [bitmap.width, bitmap.height],
      tableSize: [table.size.w, table.size.h],
      frames: table.frames.length,
      cellSize: [table.frames[0]!.w, table.frames[0]!.h],
      first: h.difference(cell(0), first.data),
      last: h.difference(cell(24), last.data),
    };
    // The JSON animation, read back in Node below; the SVG zip's entries counted here.
    const json = await ((await w.exportAnimation("json")) as Blob).text();
    const zip = new DataView(await ((await w.exportAnimation("svg")) as Blob).arrayBuffer());
    let end = zip.byteLength - 22;
    while (end > 0 && zip.getUint32(end, true) !== 0x06054b50) end--;
    const entries = zip.getUint16(end + 10, true);
    const firstName = new TextDecoder().decode(new Uint8Array(zip.buffer, 30, zip.getUint16(26, true)));
    const frames = w.animationFrames().map((f) => Array.from(f));
    const triangleCount = w.triangleCount;
    return {
      gif,
      apng,
      sprites,
      json,
      entries,
      firstName,
      frames,
      triangleCount,
      drawnSize: [first.width, first.height],
      firstVsLast: h.difference(first.data, last.data),
    };
  });
  const frameCount = FPS + 1;
  for (const format of [result.gif, result.apng]) {
    expect(format.count).toBe(frameCount);
    expect(format.size).toEqual(result.drawnSize);
    expect(format.lastProgress).toBe(1);
  }
  expect(result.gif.type).toBe("image/gif");
  expect(result.apng.type).toBe("image/apng");
  // APNG is lossless: the frames drawn, exactly. GIF's palette: close.
  expect(result.apng.first.most).toBe(0);
  expect(result.apng.last.most).toBe(0);
  expect(result.firstVsLast.mean).toBeGreaterThan(1);
  expect(result.gif.first.mean).toBeLessThan(0.25 * result.firstVsLast.mean);
  expect(result.gif.last.mean).toBeLessThan(0.25 * result.firstVsLast.mean);
  expect(result.sprites.format).toBe("akap-sprites");
  expect(result.sprites.size).toEqual(result.sprites.tableSize);
  expect(result.sprites.frames).toBe(frameCount);
  expect(result.sprites.cellSize).toEqual(result.drawnSize);
  expect(result.sprites.first.most).toBe(0);
  expect(result.sprites.last.most).toBe(0);
  expect(result.entries).toBe(frameCount);
  expect(result.firstName).toBe("frame-00.svg");
  // The JSON animation read by the package's reader: every frame, bit for bit.
  const wasm = await readFile(new URL("../../www/pkg/akap_bg.wasm", import.meta.url));
  await init(wasm);
  const animation = animationFromJson(result.json);
  expect(animation.fps).toBe(FPS);
  expect(animation.frames).toHaveLength(frameCount);
  animation.frames.forEach((f, i) => expect(Array.from(f)).toEqual(result.frames[i]));
  expect(animation.keys.map((k) => k.time)).toEqual([0, 0.5, 1]);
  expect(animation.mesh.triangles.length).toBe(result.triangleCount * 3);
});

test("an imported SVG animates to one SVG per frame with its own paths and colours, moving", async ({ page }) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  const svg =
    '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 200 100">' +
    '<rect width="120" height="100" fill="#dd2222"/><circle cx="150" cy="50" r="45" fill="#2222dd"/></svg>';
  await page.locator('input[name="shape-file"]').setInputFiles({
    name: "two-colours.svg",
    mimeType: "image/svg+xml",
    buffer: Buffer.from(svg),
  });
  await expect(page.getByRole("combobox", { name: "Shape" }).locator("option:checked")).toHaveText("two-colours.svg");
  await recordThreeKeys(page);
  const files = await page.evaluate(async () => {
    const zip = new Uint8Array(await (await window.akapDemo!.widget.exportAnimation("svg")).arrayBuffer());
    // Stored entries one after another: local header (30 bytes, name, data).
    const view = new DataView(zip.buffer);
    const out: { name: string; text: string }[] = [];
    for (let at = 0; view.getUint32(at, true) === 0x04034b50;) {
      const size = view.getUint32(at + 18, true);
      const [nameLength, extra] = [view.getUint16(at + 26, true), view.getUint16(at + 28, true)];
      const name = new TextDecoder().decode(zip.subarray(at + 30, at + 30 + nameLength));
      const start = at + 30 + nameLength + extra;
      out.push({ name, text: new TextDecoder().decode(zip.subarray(start, start + size)) });
      at = start + size;
    }
    return out;
  });
  expect(files).toHaveLength(FPS + 1);
  expect(files[0]!.name).toBe("frame-00.svg");
  expect(files.at(-1)!.name).toBe("frame-24.svg");
  for (const { text } of [files[0]!, files.at(-1)!]) {
    expect(text).toContain('fill="#dd2222"');
    expect(text).toContain('fill="#2222dd"');
    expect(text.match(/<path /g)).toHaveLength(2);
  }
  // The paths move with the frames.
  expect(files[0]!.text).not.toBe(files.at(-1)!.text);
});

test("the keys and fps are kept with the work: after a reload the same frames, bit for bit; Start over forgets them", async ({
  page,
}) => {
  await page.setViewportSize({ width: 900, height: 700 });
  await open(page);
  await recordThreeKeys(page);
  await strip(page).root.locator("input.fps").fill("12");
  await strip(page).root.locator("input.fps").press("Enter");
  const read = () =>
    page.evaluate(() => {
      const w = window.akapDemo!.widget;
      return {
        keys: w.keys().map((k) => [k.time, k.easing, Array.from(k.targets)]),
        frames: w.animationFrames().map((f) => Array.from(f)),
      };
    });
  const before = await read();
  expect(before.frames).toHaveLength(13);
  // Saved a moment after the last change.
  await page.waitForTimeout(1000);
  await page.reload();
  await expect(page.locator("body")).toHaveAttribute("data-ready", "true");
  await expect(strip(page).markers).toHaveCount(3);
  await expect(strip(page).root.locator("input.fps")).toHaveValue("12");
  expect(await read()).toEqual(before);
  // Start over forgets them, also after a reload.
  await page.getByRole("button", { name: "Start over" }).click();
  await expect(strip(page).markers).toHaveCount(0);
  await page.waitForTimeout(1000);
  await page.reload();
  await expect(page.locator("body")).toHaveAttribute("data-ready", "true");
  expect(await page.evaluate(() => window.akapDemo!.widget.keys().length)).toBe(0);
});
