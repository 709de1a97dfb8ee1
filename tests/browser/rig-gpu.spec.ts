/**
 * A trained rig posed on the GPU (WebGL2): during a drag the picture is drawn from the
 * rig's frame by the vertex shader, and the positions the shader forms (read back by
 * transform feedback) are the CPU operator's to single precision. The tolerance is the
 * rounding bound of single precision (Higham, Accuracy and Stability of Numerical
 * Algorithms, §3.1: a sum of m products is within γ_m = m u / (1 − m u) of the sum of their
 * magnitudes, u = 2⁻²⁴), computed per vertex from the very numbers the shader read:
 *
 * - for either basis, against the shader's sums done here in double precision on the same
 *   texture and frame (what `tests/defop_gpu.rs` proves within single precision of the
 *   double operator, natively and in wasm);
 * - for the hat basis, whose frame is Ψ(Q) rounded, against the double pose itself (the
 *   inputs' rounding adds 2u per term).
 */
import { expect, test, type Page } from "@playwright/test";
import { dragMouse, handles, idle, mapping, open, usePrepared } from "./helpers.js";

usePrepared();

interface Readback {
  positions: number[];
  layout: {
    reduced: boolean;
    vertexCount: number;
    terms: number;
    stride: number;
    basisY: number;
    frameY: number;
    rigidTexels: number;
  };
  texture: number[];
  frame: number[];
  drawn: boolean;
}

const U = 2 ** -24;
const gamma = (m: number) => (m * U) / (1 - m * U);

/**
 * Vertex v's position from the texture and the frame in double precision, and for each
 * coordinate the bound of the shader's rounding: γ over its sum's terms (Σ |b f|, carried
 * through the rotation) and the rigid motion's roundings (a subtraction, two products and a
 * sum, an addition: within 12 u of the magnitudes involved).
 */
function shaderSums(
  r: Readback,
  v: number,
): { at: [number, number]; bound: [number, number]; scale: [number, number] } {
  const { texture: b, frame: f, layout: l } = r;
  const sum = (row: number, vector: number): [number, number] => {
    let [s, m] = [0, 0];
    for (let t = 0; t < l.terms; t++) {
      for (let k = 0; k < 4; k++) {
        const term = b[4 * (row + t) + k]! * f[4 * (vector + t) + k]!;
        s += term;
        m += Math.abs(term);
      }
    }
    return [s, m];
  };
  const base = v * l.stride;
  const [x, mx] = sum(base, l.rigidTexels);
  const [y, my] = sum(base + l.basisY, l.rigidTexels + l.frameY);
  const [cos, sin, fx, fy, tx, ty] = f.slice(0, 6) as [number, number, number, number, number, number];
  const [dx, dy] = [x - fx, y - fy];
  const at: [number, number] = [cos * dx - sin * dy + tx, sin * dx + cos * dy + ty];
  const size =
    Math.max(Math.abs(x), Math.abs(y)) + Math.max(Math.abs(fx), Math.abs(fy)) + Math.max(Math.abs(tx), Math.abs(ty));
  const g = gamma(4 * l.terms) * (1 + 2 * U);
  const rigid = 12 * U * size;
  // The rotation mixes the two sums' errors: each coordinate carries both.
  return { at, bound: [g * (mx + my) + rigid, g * (mx + my) + rigid], scale: [mx + my, mx + my] };
}

/** The bar at about 300 vertices with a pin at its left end and a handle at its right end, a rig trained on it. */
async function rigOnTheBar(page: Page, spatial: number): Promise<void> {
  await page.evaluate(async (spatial) => {
    const w = window.akapDemo!.widget;
    await w.setShape("bar", 300);
    const p = w.mesh.positions;
    let [left, right] = [0, 0];
    for (let v = 0; v < p.length / 2; v++) {
      if (p[2 * v]! < p[2 * left]!) left = v;
      if (p[2 * v]! > p[2 * right]!) right = v;
    }
    const ys = Array.from({ length: p.length / 2 }, (_, v) => p[2 * v + 1]!);
    const middle = (Math.min(...ys) + Math.max(...ys)) / 2;
    const inset = 0.03 * (p[2 * right]! - p[2 * left]!);
    w.addHandleAt(p[2 * left]! + inset, middle);
    w.addHandleAt(p[2 * right]! - inset, middle);
    await w.train({ samples: 17, spatial, energy: "arap" });
    w.setMethod("defop");
  }, spatial);
}

const readback = (page: Page): Promise<Readback | undefined> =>
  page.evaluate(() => {
    const r = (
      window.akapDemo!.widget as unknown as { rigGpuReadback(): Record<string, unknown> | undefined }
    ).rigGpuReadback();
    if (!r) return undefined;
    const list = (a: unknown) => Array.from(a as Float32Array);
    return { ...r, positions: list(r.positions), texture: list(r.texture), frame: list(r.frame) } as Readback;
  });

for (const [name, spatial] of [
  ["a reduced basis", 40],
  ["the hat basis", 0],
] as const) {
  test(`a rig of ${name} on the GPU draws the operator's pose to single precision`, async ({ page }) => {
    test.setTimeout(120_000);
    await page.setViewportSize({ width: 1280, height: 800 });
    await open(page);
    expect(await page.evaluate(() => window.akapDemo!.widget.renderer)).toBe("webgl2");
    await rigOnTheBar(page, spatial);

    // Drag the right handle: the frames of the drag are drawn from the rig's frame.
    const { toCss } = await mapping(page);
    const h = await handles(page);
    const [x, y] = toCss(h[2]!, h[3]!);
    await dragMouse(page, [x, y], [x - 40, y - 70], 6);
    await idle(page);
    const gpu = (await readback(page))!;
    expect(gpu).toBeDefined();
    expect(gpu.drawn).toBe(true);
    expect(gpu.layout.reduced).toBe(spatial > 0);
    const cpu = await page.evaluate(() => Array.from(window.akapDemo!.widget.positions()));
    const n = gpu.layout.vertexCount;
    expect(cpu.length).toBe(2 * n);
    expect(gpu.positions.length).toBe(2 * n);

    let worst = 0;
    for (let v = 0; v < n; v++) {
      const { at, bound, scale } = shaderSums(gpu, v);
      for (const c of [0, 1]) {
        const found = gpu.positions[2 * v + c]!;
        // The shader's sums, against the same sums in double precision.
        const error = Math.abs(found - at[c]!);
        worst = Math.max(worst, error / bound[c]!);
        expect(error, `vertex ${v}, coordinate ${c}`).toBeLessThanOrEqual(bound[c]!);
        if (spatial === 0) {
          // The hat basis: the frame is Ψ(Q) rounded and the texture X rounded, each term
          // within 2u of its double value: the double pose is within these bounds too.
          const full = bound[c]! + 3 * U * scale[c]!;
          expect(Math.abs(found - cpu[2 * v + c]!), `vertex ${v}, coordinate ${c} against the CPU`).toBeLessThanOrEqual(
            full,
          );
        }
      }
    }
    // The drag moved the pose well away from rest.
    const rest = await page.evaluate(() => Array.from(window.akapDemo!.widget.mesh.positions));
    expect(Math.max(...cpu.map((p, i) => Math.abs(p - rest[i]!)))).toBeGreaterThan(0.1);
    test.info().annotations.push({ type: "worst error / bound", description: worst.toFixed(3) });
  });
}
