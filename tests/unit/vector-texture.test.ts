/** The texture of vector art: where its pixels lie, and what is drawn (on a recording canvas). */
import { afterEach, beforeAll, describe, expect, it, vi } from "vitest";
import { init, type VectorPath } from "../../www/src/index.js";
import { boxUvs } from "../../www/src/widget/model/geometry.js";
import { textureMapping, vectorTexture } from "../../www/src/widget/shapes/vector-texture.js";

beforeAll(async () => {
  await init(); // boxUvs goes through the core's textureCoordinates
});

/** Canvas pixel of a shape point under a mapping (y flips: shape y up, canvas y down). */
function pixel(m: ReturnType<typeof textureMapping>, x: number, y: number): [number, number] {
  return [m.view.offsetX + m.view.scale * x, m.view.offsetY - m.view.scale * y];
}

describe("textureMapping", () => {
  it("covers the bounding box grown to a square about its centre, y flipped", () => {
    // A 4 x 1 box at (1, 2): the square is 4 x 4, from y = 0.5 - 2 to 3 + 1.5.
    const m = textureMapping({ minX: 1, minY: 2, maxX: 5, maxY: 3 }, 200.7);
    expect(m.side).toBe(200);
    expect(m.square).toEqual({ x0: 1, y0: 0.5, size: 4 });
    expect(pixel(m, 1, 4.5)).toEqual([0, 0]); // the square's top-left corner
    expect(pixel(m, 5, 0.5)).toEqual([200, 200]); // its bottom-right corner
    expect(pixel(m, 3, 2.5)).toEqual([100, 100]); // the box's centre is the canvas's
  });

  it("gives texture coordinates equal to boxUvs of the rest positions", () => {
    const positions = [0.3, -1.2, 7.9, 0.4, 2.5, 2.25, -0.6, 0.1, 4, -1];
    const xs = positions.filter((_, i) => i % 2 === 0);
    const ys = positions.filter((_, i) => i % 2 === 1);
    const box = { minX: Math.min(...xs), minY: Math.min(...ys), maxX: Math.max(...xs), maxY: Math.max(...ys) };
    const m = textureMapping(box, 1024);
    const uvs = boxUvs(positions);
    for (let i = 0; i < positions.length; i += 2) {
      const [px, py] = pixel(m, positions[i]!, positions[i + 1]!);
      // WebGL samples u = px / side across and, with the canvas uploaded flipped, v = 1 - py / side.
      expect(px / m.side).toBeCloseTo(uvs[i]!, 6);
      expect(1 - py / m.side).toBeCloseTo(uvs[i + 1]!, 6);
    }
  });

  it("rejects boxes and sizes it cannot use", () => {
    expect(() => textureMapping({ minX: 0, minY: 0, maxX: Infinity, maxY: 1 })).toThrow(/not a finite box/);
    expect(() => textureMapping({ minX: 1, minY: 0, maxX: 0, maxY: 1 })).toThrow(/not a finite box/);
    expect(() => textureMapping({ minX: 0, minY: 0, maxX: 1, maxY: 1 }, 0.5)).toThrow(/maxSide is 0.5/);
    // A box of no size still gets a texture (of size 1, as boxUvs).
    expect(textureMapping({ minX: 2, minY: 2, maxX: 2, maxY: 2 }, 16).square).toEqual({ x0: 1.5, y0: 1.5, size: 1 });
  });
});

describe("vectorTexture", () => {
  afterEach(() => {
    vi.unstubAllGlobals();
  });

  it("fills each path with its colour and rule through the mapping, the default when unknown", () => {
    // Node has no canvas: a recording one, and Path2D keeping its path data.
    vi.stubGlobal(
      "Path2D",
      class {
        constructor(readonly d: string) {}
      },
    );
    const calls: unknown[][] = [];
    const ctx = {
      fillStyle: "",
      setTransform: (...args: number[]) => calls.push(["setTransform", ...args]),
      fill(path: { d: string }, rule: string) {
        calls.push(["fill", path.d, rule, this.fillStyle]);
      },
    };
    const canvas = { width: 0, height: 0, getContext: () => ctx };
    const document = { createElement: () => canvas } as unknown as Document;
    const square = (x: number, fill: string | undefined, fillRule: "nonzero" | "evenodd"): VectorPath => ({
      element: "<rect>",
      part: "fill",
      commands: "MLLLZ",
      points: Float64Array.from([x, 0, x + 1, 0, x + 1, 1, x, 1]),
      fillRule,
      fill,
    });
    const red = square(0, "rgba(255, 0, 0, 0.25)", "evenodd");
    const unknown = square(2, undefined, "nonzero");
    const texture = vectorTexture(document, [red, { path: unknown }], { minX: 0, minY: 0, maxX: 3, maxY: 1 }, 300);
    expect(texture.canvas).toBe(canvas);
    expect([canvas.width, canvas.height]).toEqual([300, 300]);
    // 100 pixels per unit; the square's top (y = 2) at row 0.
    // (+ 0 turns -0 into 0: the offset is -x0 * scale.)
    expect(calls.map((call) => call.map((v) => (typeof v === "number" ? v + 0 : v)))).toEqual([
      ["setTransform", 100, 0, 0, -100, 0, 200],
      ["fill", "M 0 0 L 1 0 L 1 1 L 0 1 Z", "evenodd", "rgba(255, 0, 0, 0.25)"],
      ["fill", "M 2 0 L 3 0 L 3 1 L 2 1 Z", "nonzero", "#c8773a"],
    ]);
  });
});
