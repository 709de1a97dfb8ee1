/**
 * Animations out through the public API and the real wasm in Node: encodeAnimation's
 * progress, cancel and clean-up, its GIF and APNG read back by small parsers here, and the
 * thin wrappers (ZIP, the akap-animation JSON, the sprite table).
 */
import { afterEach, beforeAll, describe, expect, it, vi } from "vitest";
import * as glue from "../../www/pkg/akap.js";
import {
  animationFromJson,
  animationToJson,
  encodeAnimation,
  init,
  spriteSheetTable,
  zipFiles,
  type AnimationFrame,
} from "../../www/src/index.js";

beforeAll(async () => {
  await init();
});

afterEach(() => {
  vi.restoreAllMocks();
});

/** A frame of `w` x `h` pixels of one colour. */
function solid(w: number, h: number, [r, g, b, a]: number[], delayMs = 100): AnimationFrame {
  const rgba = new Uint8ClampedArray(4 * w * h);
  for (let i = 0; i < w * h; i++) rgba.set([r!, g!, b!, a!], 4 * i);
  return { rgba, width: w, height: h, delayMs };
}

const colours = [
  [255, 0, 0, 255],
  [0, 255, 0, 255],
  [0, 0, 255, 255],
  [255, 255, 0, 255],
  [0, 0, 0, 0],
];

/** A GIF's screen size, and per image its size and delay (cs), by walking its blocks. */
function parseGif(bytes: Uint8Array): {
  width: number;
  height: number;
  frames: { w: number; h: number; delay: number }[];
} {
  const u16 = (at: number) => bytes[at]! | (bytes[at + 1]! << 8);
  expect(new TextDecoder().decode(bytes.subarray(0, 6))).toBe("GIF89a");
  const flags = bytes[10]!;
  let at = 13 + (flags & 0x80 ? 3 << ((flags & 7) + 1) : 0);
  const skipSubBlocks = () => {
    while (bytes[at] !== 0) at += bytes[at]! + 1;
    at += 1;
  };
  const frames: { w: number; h: number; delay: number }[] = [];
  let delay = 0;
  for (;;) {
    const block = bytes[at]!;
    if (block === 0x3b) break;
    if (block === 0x21) {
      if (bytes[at + 1] === 0xf9) delay = u16(at + 4);
      at += 2;
      skipSubBlocks();
    } else if (block === 0x2c) {
      const local = bytes[at + 9]!;
      frames.push({ w: u16(at + 5), h: u16(at + 7), delay });
      at += 10 + (local & 0x80 ? 3 << ((local & 7) + 1) : 0) + 1; // descriptor, palette, LZW size
      skipSubBlocks();
    } else {
      throw new Error(`unexpected GIF block ${block} at ${at}`);
    }
  }
  return { width: u16(6), height: u16(8), frames };
}

/** A PNG's chunks: type and data. */
function pngChunks(bytes: Uint8Array): { type: string; data: DataView }[] {
  expect([...bytes.subarray(0, 8)]).toEqual([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const chunks = [];
  for (let at = 8; at < bytes.length;) {
    const length = view.getUint32(at);
    const type = new TextDecoder().decode(bytes.subarray(at + 4, at + 8));
    chunks.push({ type, data: new DataView(bytes.buffer, bytes.byteOffset + at + 8, length) });
    at += 12 + length;
  }
  return chunks;
}

describe("encodeAnimation", () => {
  it("encodes a GIF from an array, reporting progress frame by frame", async () => {
    const free = vi.spyOn(glue.AnimationEncoder.prototype, "free");
    const frames = colours.map((c, i) => solid(8, 6, c, 40 + 10 * i));
    const progress: [number, number | undefined][] = [];
    const gif = await encodeAnimation("gif", frames, { onProgress: (done, total) => progress.push([done, total]) });
    expect(progress).toEqual([1, 2, 3, 4, 5].map((done) => [done, 5]));
    const parsed = parseGif(gif);
    expect([parsed.width, parsed.height]).toEqual([8, 6]);
    // 40, 50, 60, 70, 80 ms: whole centiseconds.
    expect(parsed.frames).toEqual([4, 5, 6, 7, 8].map((delay) => ({ w: 8, h: 6, delay })));
    expect(free).toHaveBeenCalledTimes(1);
  });

  it("encodes an APNG from an async iterable, played once", async () => {
    async function* frames() {
      for (const c of colours.slice(0, 4)) {
        await Promise.resolve();
        yield solid(3, 7, c, 33);
      }
    }
    const totals: (number | undefined)[] = [];
    const png = await encodeAnimation("apng", frames(), { loop: false, onProgress: (_, total) => totals.push(total) });
    expect(totals).toEqual([undefined, undefined, undefined, undefined]);
    const chunks = pngChunks(png);
    const ihdr = chunks[0]!;
    expect([ihdr.type, ihdr.data.getUint32(0), ihdr.data.getUint32(4)]).toEqual(["IHDR", 3, 7]);
    const actl = chunks.find((c) => c.type === "acTL")!;
    expect([actl.data.getUint32(0), actl.data.getUint32(4)]).toEqual([4, 1]);
    const fctl = chunks.filter((c) => c.type === "fcTL");
    expect(fctl.map((c) => [c.data.getUint16(20), c.data.getUint16(22)])).toEqual(Array(4).fill([33, 1000]));
    expect(chunks.at(-1)!.type).toBe("IEND");
  });

  it("yields a macrotask between frames, so timers run", async () => {
    let ticks = 0;
    const timer = setInterval(() => ticks++, 0);
    try {
      const frames = Array.from({ length: 6 }, (_, i) => solid(4, 4, colours[i % 4]!));
      const seen: number[] = [];
      const busy = (ms: number) => {
        const end = performance.now() + ms;
        while (performance.now() < end);
      };
      // Each frame takes at least 3 ms, so the 1 ms interval is due whenever the encoder
      // lets the event loop turn; were it to wait for a microtask only, it never would.
      await encodeAnimation("apng", frames, { onProgress: () => (busy(3), seen.push(ticks)) });
      expect(seen[0]).toBe(0);
      expect(seen.at(-1)!).toBeGreaterThanOrEqual(4);
    } finally {
      clearInterval(timer);
    }
  });

  it("cancels mid-way with an AbortError and frees the encoder", async () => {
    const free = vi.spyOn(glue.AnimationEncoder.prototype, "free");
    const controller = new AbortController();
    let pulled = 0;
    function* frames() {
      for (let i = 0; i < 10; i++) {
        pulled++;
        yield solid(16, 16, colours[i % 4]!);
      }
    }
    const done = encodeAnimation("gif", frames(), {
      signal: controller.signal,
      onProgress: (n) => {
        if (n === 3) controller.abort();
      },
    });
    await expect(done).rejects.toMatchObject({ name: "AbortError" });
    expect(pulled).toBe(3);
    expect(free).toHaveBeenCalledTimes(1);
    // Already aborted: nothing is encoded.
    await expect(
      encodeAnimation("gif", [solid(2, 2, colours[0]!)], { signal: controller.signal }),
    ).rejects.toMatchObject({
      name: "AbortError",
    });
  });

  it("lets a cancel from a timer land between frames", async () => {
    const free = vi.spyOn(glue.AnimationEncoder.prototype, "free");
    const controller = new AbortController();
    setTimeout(() => controller.abort(), 5);
    let done = 0;
    const frames = Array.from({ length: 50 }, (_, i) => solid(8, 8, colours[i % 4]!));
    const encoding = encodeAnimation("gif", frames, {
      signal: controller.signal,
      onProgress: (n) => {
        done = n;
        const end = performance.now() + 2; // 2 ms a frame: 100 ms for all of them
        while (performance.now() < end);
      },
    });
    await expect(encoding).rejects.toMatchObject({ name: "AbortError" });
    expect(done).toBeGreaterThan(0);
    expect(done).toBeLessThan(50);
    expect(free).toHaveBeenCalledTimes(1);
  });

  it("rejects bad frames with codes, freeing the encoder", async () => {
    const free = vi.spyOn(glue.AnimationEncoder.prototype, "free");
    const mixed = [solid(4, 4, colours[0]!), solid(4, 5, colours[1]!)];
    await expect(encodeAnimation("apng", mixed)).rejects.toMatchObject({ code: "invalid-argument" });
    await expect(encodeAnimation("gif", [solid(4, 4, colours[0]!, 0)])).rejects.toMatchObject({
      code: "invalid-argument",
      message: expect.stringContaining("delay of 0 ms"),
    });
    const short = { ...solid(4, 4, colours[0]!), rgba: new Uint8Array(63) };
    await expect(encodeAnimation("gif", [short])).rejects.toMatchObject({ code: "invalid-argument" });
    await expect(encodeAnimation("gif", [])).rejects.toMatchObject({ code: "invalid-argument" });
    await expect(encodeAnimation("webp" as "gif", [solid(1, 1, colours[0]!)])).rejects.toMatchObject({
      code: "invalid-argument",
    });
    await expect(encodeAnimation("gif", [solid(0, 0, colours[0]!)])).rejects.toMatchObject({
      code: "invalid-argument",
    });
    // One encoder was made for each of the three calls with a first frame of a valid size.
    expect(free).toHaveBeenCalledTimes(3);
  });
});

describe("files", () => {
  it("zips files and refuses unsafe names", () => {
    const text = new TextEncoder();
    const zip = zipFiles([
      { name: "frames/0001.svg", data: text.encode("<svg/>") },
      { name: "check.txt", data: text.encode("123456789") },
    ]);
    const view = new DataView(zip.buffer, zip.byteOffset, zip.byteLength);
    expect(view.getUint32(0, true)).toBe(0x04034b50);
    const end = zip.length - 22;
    expect(view.getUint32(end, true)).toBe(0x06054b50);
    expect(view.getUint16(end + 10, true)).toBe(2);
    // The second file's CRC-32 is the standard check value.
    const second = 30 + "frames/0001.svg".length + 6;
    expect(view.getUint32(second + 14, true)).toBe(0xcbf43926);
    for (const name of ["", "/abs", "a/../b"]) {
      expect(() => zipFiles([{ name, data: new Uint8Array(1) }])).toThrow(
        expect.objectContaining({ code: "invalid-argument" }),
      );
    }
    const twice = [
      { name: "a", data: new Uint8Array(0) },
      { name: "a", data: new Uint8Array(0) },
    ];
    expect(() => zipFiles(twice)).toThrow(/given twice/);
  });

  it("round-trips an animation exactly", () => {
    const animation = {
      mesh: { positions: [0, 0, 1, 0, 0, 1], triangles: [0, 1, 2], uvs: [0, 0, 1, 0, 0, 1] },
      fps: 24,
      keys: [
        { time: 0, easing: "linear" as const, handles: [0, 0] },
        { time: 0.1 + 0.2, easing: "ease" as const, handles: new Float64Array([1 / 3, -0]) },
      ],
      frames: [new Float64Array([0, 0, 1, 0, 0, 1]), [0.1 + 0.2, -0, 1e-300, 5e-324, 1 / 3, 1]],
    };
    const text = animationToJson(animation);
    const back = animationFromJson(text);
    expect(back.mesh.positions).toEqual(new Float64Array([0, 0, 1, 0, 0, 1]));
    expect(back.mesh.triangles).toEqual(new Uint32Array([0, 1, 2]));
    expect(back.mesh.uvs).toEqual(new Float64Array([0, 0, 1, 0, 0, 1]));
    expect(back.fps).toBe(24);
    expect(back.keys.map((k) => [k.time, k.easing])).toEqual([
      [0, "linear"],
      [0.1 + 0.2, "ease"],
    ]);
    expect(Object.is(back.keys[1]!.handles[1], -0)).toBe(true);
    expect([...back.frames[1]!]).toEqual([0.1 + 0.2, -0, 1e-300, 5e-324, 1 / 3, 1]);
    expect(Object.is(back.frames[1]![1], -0)).toBe(true);
    expect(animationToJson(back)).toBe(text);
    expect(() => animationFromJson(text.replace('"version":1', '"version":2'))).toThrow(
      expect.objectContaining({ code: "import" }),
    );
    expect(() => animationToJson({ ...animation, fps: 500 })).toThrow(
      expect.objectContaining({ code: "invalid-argument" }),
    );
  });

  it("writes a sprite table", () => {
    const table = JSON.parse(spriteSheetTable({ frameWidth: 32, frameHeight: 16, columns: 3, frameCount: 4, fps: 8 }));
    expect(table).toMatchObject({ format: "akap-sprites", version: 1, columns: 3, rows: 2, size: { w: 96, h: 32 } });
    expect(table.frames[3]).toEqual({ x: 0, y: 16, w: 32, h: 16, duration: 125 });
    expect(() => spriteSheetTable({ frameWidth: 32, frameHeight: 16, columns: 0, frameCount: 4, fps: 8 })).toThrow(
      expect.objectContaining({ code: "invalid-argument" }),
    );
  });
});
