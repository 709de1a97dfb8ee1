#!/usr/bin/env node
// Times encodeAnimation in wasm (Node) on the frames of lab/animation/encode_timing.rs:
// 512 x 512, a shaded disc moving over a transparent background; GIF and APNG, ms a frame
// and bytes.
// Run after `bash scripts/build.sh`: `node lab/animation/bench-animation.mjs [FRAMES]`.
import process from "node:process";
import { performance } from "node:perf_hooks";
import { encodeAnimation, init } from "../../www/lib/index.js";

await init();
const SIZE = 512;
const count = Number(process.argv[2] ?? 10);

function frame(t) {
  const rgba = new Uint8Array(4 * SIZE * SIZE);
  const [cx, cy] = [200 + 10 * t, 256];
  for (let y = 0; y < SIZE; y++) {
    for (let x = 0; x < SIZE; x++) {
      const r = Math.hypot(x - cx, y - cy);
      if (r < 180) {
        const i = 4 * (y * SIZE + x);
        rgba[i] = Math.floor((x * 255) / SIZE);
        rgba[i + 1] = Math.floor((y * 255) / SIZE);
        rgba[i + 2] = Math.floor(255 * (1 - r / 180));
        rgba[i + 3] = 255;
      }
    }
  }
  return { rgba, width: SIZE, height: SIZE, delayMs: 40 };
}

const frames = Array.from({ length: count }, (_, t) => frame(t));
console.log(`${count} frames of ${SIZE} x ${SIZE}, wasm in Node ${process.version}`);
for (const format of ["gif", "apng"]) {
  const start = performance.now();
  const bytes = await encodeAnimation(format, frames);
  const ms = (performance.now() - start) / count;
  console.log(`${format}: ${ms.toFixed(1)} ms a frame, ${Math.round(bytes.length / count)} bytes a frame`);
}
