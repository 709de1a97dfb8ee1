/**
 * The layered puppet fixture `tests/fixtures/svg/layered-puppet.svg` in the app: loading it,
 * its SVG units in shape units, its colours, and the drawn picture's pixels. The fixture
 * has a torso (green #2e8b57, used by nothing else) whose square 120..140 x 110..130 (SVG
 * units, y down) lies under the arm (blue #4169e1), a head over the torso's top and a hat
 * apart (#b22222 brim, #800000 crown).
 */
import { readFile } from "node:fs/promises";
import { expect, type Page } from "@playwright/test";
import { idle } from "./helpers.js";

export const GREEN = [0x2e, 0x8b, 0x57];
export const BLUE = [0x41, 0x69, 0xe1];
export const BRIM = [0xb2, 0x22, 0x22];
export const CROWN = [0x80, 0x00, 0x00];
export const FACE = [0xf4, 0xc2, 0x7a];

/** Opens the fixture as a file, as the Open button would. */
export async function loadPuppet(page: Page): Promise<void> {
  const text = await readFile(new URL("../fixtures/svg/layered-puppet.svg", import.meta.url), "utf8");
  await page.evaluate(async (text) => {
    const blob = new Blob([text], { type: "image/svg+xml" });
    await window.akapDemo!.widget.loadFile(blob, "layered-puppet.svg");
  }, text);
  await idle(page);
}

/**
 * SVG units of the fixture to shape units, from the torso part's rest bounds (SVG 60..140 x
 * 100..220): a uniform scale, y flipped (checked: the head is above the torso).
 */
export async function svgToShape(page: Page): Promise<(x: number, y: number) => [number, number]> {
  const boxes = await page.evaluate(() => {
    const w = window.akapDemo!.widget;
    const p = w.mesh.positions;
    const t = w.mesh.triangles;
    return w.parts.map((part) => {
      const box = { minX: Infinity, minY: Infinity, maxX: -Infinity, maxY: -Infinity, name: part.name };
      for (const f of part.triangles) {
        for (let k = 0; k < 3; k++) {
          const v = t[3 * f + k]!;
          box.minX = Math.min(box.minX, p[2 * v]!);
          box.maxX = Math.max(box.maxX, p[2 * v]!);
          box.minY = Math.min(box.minY, p[2 * v + 1]!);
          box.maxY = Math.max(box.maxY, p[2 * v + 1]!);
        }
      }
      return box;
    });
  });
  const torso = boxes.find((b) => b.name === "Torso")!;
  const head = boxes.find((b) => b.name === "Head")!;
  expect(head.minY, "y is up: the head is above the torso").toBeGreaterThan(torso.minY);
  const scale = (torso.maxX - torso.minX) / 80;
  expect((torso.maxY - torso.minY) / 120).toBeCloseTo(scale, 2);
  return (x, y) => [torso.minX + scale * (x - 60), torso.maxY - scale * (y - 100)];
}

/** The picture as on screen (mesh under overlay), and a reader of its pixels at CSS points. */
export async function screen(page: Page): Promise<(css: [number, number][]) => Promise<number[][]>> {
  await idle(page);
  const box = (await page.locator("#app canvas.overlay").boundingBox())!;
  return (css) =>
    page.evaluate(
      ({ points }) => {
        const shadow = document.querySelector("#app .akap-host")!.shadowRoot!;
        const gl = shadow.querySelector("canvas.mesh") as HTMLCanvasElement;
        const canvas = document.createElement("canvas");
        canvas.width = gl.width;
        canvas.height = gl.height;
        const ctx = canvas.getContext("2d")!;
        ctx.drawImage(gl, 0, 0);
        ctx.drawImage(shadow.querySelector("canvas.overlay") as HTMLCanvasElement, 0, 0);
        const r = window.akapDemo!.widget.view.pixelRatio;
        const data = ctx.getImageData(0, 0, canvas.width, canvas.height).data;
        return points.map(([x, y]) => {
          const i = 4 * (Math.round(y * r) * canvas.width + Math.round(x * r));
          return [data[i]!, data[i + 1]!, data[i + 2]!];
        });
      },
      { points: css.map(([x, y]): [number, number] => [x - box.x, y - box.y]) },
    );
}

export const near = (c: number[], target: number[], within = 40) =>
  c.every((v, k) => Math.abs(v - target[k]!) <= within);

/** CSS points on a grid over an SVG rectangle (inset by `inset` SVG units). */
export function grid(
  toCss: (x: number, y: number) => [number, number],
  svg: (x: number, y: number) => [number, number],
  [x0, y0, x1, y1]: [number, number, number, number],
  inset: number,
  n = 8,
): [number, number][] {
  const out: [number, number][] = [];
  for (let i = 0; i <= n; i++) {
    for (let j = 0; j <= n; j++) {
      const x = x0 + inset + ((x1 - x0 - 2 * inset) * i) / n;
      const y = y0 + inset + ((y1 - y0 - 2 * inset) * j) / n;
      out.push(toCss(...svg(x, y)));
    }
  }
  return out;
}

/**
 * Where `part`'s rest point (x, y) is in the current pose: through the part's own triangle
 * there (parts overlap at rest), by its barycentric coordinates.
 */
export function posedOnPart(page: Page, part: number, [x, y]: [number, number]): Promise<[number, number]> {
  return page.evaluate(
    ({ part, x, y }) => {
      const w = window.akapDemo!.widget;
      const rest = w.mesh.positions;
      const t = w.mesh.triangles;
      const posed = w.positions();
      for (const f of w.parts[part]!.triangles) {
        const [a, b, c] = [t[3 * f]!, t[3 * f + 1]!, t[3 * f + 2]!];
        const [ax, ay, bx, by, cx, cy] = [
          rest[2 * a]!,
          rest[2 * a + 1]!,
          rest[2 * b]!,
          rest[2 * b + 1]!,
          rest[2 * c]!,
          rest[2 * c + 1]!,
        ];
        const d = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay);
        const l1 = ((x - ax) * (cy - ay) - (cx - ax) * (y - ay)) / d;
        const l2 = ((bx - ax) * (y - ay) - (x - ax) * (by - ay)) / d;
        const l0 = 1 - l1 - l2;
        if (Math.min(l0, l1, l2) < -1e-9) continue;
        return [
          l0 * posed[2 * a]! + l1 * posed[2 * b]! + l2 * posed[2 * c]!,
          l0 * posed[2 * a + 1]! + l1 * posed[2 * b + 1]! + l2 * posed[2 * c + 1]!,
        ] as [number, number];
      }
      throw new Error(`(${x}, ${y}) is not on part ${part}`);
    },
    { part, x, y },
  );
}
