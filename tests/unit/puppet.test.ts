/**
 * Puppets in the widget, from geometry: the texture atlas (each part's texture coordinates
 * in its own tile, through the part's own square), the depth layering (triangles back to
 * front by their part's depth, each part's outline its own), picking on the front-most part,
 * the depth steps of Forward and Back, and the atlas drawn tile by tile.
 */
import { afterEach, beforeAll, describe, expect, it, vi } from "vitest";
import { init, type VectorPath } from "../../www/src/index.js";
import { ATLAS_MARGIN, atlasLayout, puppetAtlas } from "../../www/src/widget/model/atlas.js";
import { drawOrder, partLayering } from "../../www/src/widget/model/layers.js";
import { locateFront } from "../../www/src/widget/model/picking.js";
import { partsUnder, posedPoint, puppetOf, restPoint, stepDepth } from "../../www/src/widget/model/puppet.js";
import { atlasTexture } from "../../www/src/widget/shapes/vector-texture.js";

beforeAll(async () => {
  await init(); // squareUvs goes through the core's textureCoordinates
});

/**
 * Two sheets sharing no vertex: part 0 a 2 x 2 square at the origin, part 1 a 4 x 1 bar
 * from (1, 1) to (5, 2) lying over the square's top-right corner. Two triangles each,
 * counter-clockwise.
 */
function twoSheets() {
  const positions = Float64Array.from([0, 0, 2, 0, 2, 2, 0, 2, 1, 1, 5, 1, 5, 2, 1, 2]);
  const triangles = Uint32Array.from([0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7]);
  const boundaryEdges = Uint32Array.from([0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 5, 6, 6, 7, 7, 4]);
  const parts = [
    { name: "square", triangles: Uint32Array.from([0, 1]), depth: 0, paths: [] },
    { name: "bar", triangles: Uint32Array.from([2, 3]), depth: 1, paths: [] },
  ];
  const puppet = puppetOf({ parts, joints: [{ point: [1.5, 1.5], parts: [1, 0] }] }, triangles, {
    kind: "svg",
    text: "<svg/>",
  });
  return { positions, triangles, boundaryEdges, parts, puppet };
}

describe("the atlas", () => {
  it("puts each part's texture coordinates in its own tile, through the part's own square", () => {
    const { positions, triangles, parts } = twoSheets();
    const { layout, uvs } = puppetAtlas(
      positions,
      triangles,
      parts.map((p) => p.triangles),
    );
    // Two parts: a grid of 2 x 2 cells of 1/2; tiles are cells less the margin.
    expect(layout.columns).toBe(2);
    const cell = 0.5;
    const [a, b] = layout.tiles as [(typeof layout.tiles)[0], (typeof layout.tiles)[0]];
    expect(a.size).toBeCloseTo(cell * (1 - 2 * ATLAS_MARGIN), 12);
    // The tiles do not overlap: side by side in the top row.
    expect(a.u0 + a.size).toBeLessThan(b.u0);
    expect(a.v0).toBeCloseTo(b.v0, 12);
    // The square (side 2): its corners are its tile's corners.
    const at = (v: number) => [uvs[2 * v]!, uvs[2 * v + 1]!];
    expect(at(0)[0]).toBeCloseTo(a.u0, 6);
    expect(at(0)[1]).toBeCloseTo(a.v0, 6);
    expect(at(2)[0]).toBeCloseTo(a.u0 + a.size, 6);
    expect(at(2)[1]).toBeCloseTo(a.v0 + a.size, 6);
    // The bar (4 x 1): its square is 4 across, the bar centred in it (y from 1 - 1.5 to 2 + 1.5).
    expect(at(4)[0]).toBeCloseTo(b.u0, 6);
    expect(at(4)[1]).toBeCloseTo(b.v0 + (b.size * 1.5) / 4, 6);
    expect(at(6)[0]).toBeCloseTo(b.u0 + b.size, 6);
    expect(at(6)[1]).toBeCloseTo(b.v0 + (b.size * 2.5) / 4, 6);
    // Every vertex of a part lies in its tile, though the parts overlap at rest.
    for (const [k, list] of [
      [0, [0, 1, 2, 3]],
      [1, [4, 5, 6, 7]],
    ] as const) {
      const tile = layout.tiles[k]!;
      for (const v of list) {
        const [u, w] = at(v);
        expect(u! >= tile.u0 - 1e-6 && u! <= tile.u0 + tile.size + 1e-6).toBe(true);
        expect(w! >= tile.v0 - 1e-6 && w! <= tile.v0 + tile.size + 1e-6).toBe(true);
      }
    }
  });

  it("lays out n parts in a grid of ceil(sqrt(n)) columns, rows from the top, tiles apart", () => {
    const box = { minX: 0, minY: 0, maxX: 1, maxY: 1 };
    const layout = atlasLayout(Array.from({ length: 5 }, () => box));
    expect(layout.columns).toBe(3);
    const cell = 1 / 3;
    layout.tiles.forEach((tile, i) => {
      const [column, row] = [i % 3, Math.floor(i / 3)];
      expect(tile.u0).toBeCloseTo(column * cell + ATLAS_MARGIN * cell, 12);
      expect(tile.v0 + tile.size).toBeCloseTo(1 - row * cell - ATLAS_MARGIN * cell, 12);
      for (const other of layout.tiles.slice(i + 1)) {
        const apart =
          tile.u0 + tile.size < other.u0 ||
          other.u0 + other.size < tile.u0 ||
          tile.v0 + tile.size < other.v0 ||
          other.v0 + other.size < tile.v0;
        expect(apart).toBe(true);
      }
    });
    expect(() => atlasLayout([])).toThrow(/at least one part/);
  });

  afterEach(() => {
    vi.unstubAllGlobals();
  });

  it("draws each part's paths alone, clipped to its tile, mapped onto it", () => {
    vi.stubGlobal(
      "Path2D",
      class {
        constructor(readonly d: string) {}
      },
    );
    const calls: unknown[][] = [];
    let transform = [1, 0, 0, 1, 0, 0];
    const ctx = {
      fillStyle: "",
      save: () => calls.push(["save"]),
      restore: () => calls.push(["restore"]),
      beginPath: () => undefined,
      rect: (...args: number[]) => calls.push(["rect", ...args]),
      clip: () => undefined,
      setTransform: (...args: number[]) => (transform = args),
      fill(path: { d: string }) {
        calls.push(["fill", path.d, this.fillStyle, transform]);
      },
    };
    const canvas = { width: 0, height: 0, getContext: () => ctx };
    const document = { createElement: () => canvas } as unknown as Document;
    const path = (fill: string): VectorPath => ({
      element: "<rect>",
      part: "fill",
      commands: "MLLLZ",
      points: Float64Array.from([0, 0, 1, 0, 1, 1, 0, 1]),
      fillRule: "nonzero",
      fill,
    });
    // Part 0's square is (0, 0)-(2, 2), part 1's (10, 0)-(14, 4).
    const layout = atlasLayout([
      { minX: 0, minY: 0, maxX: 2, maxY: 2 },
      { minX: 10, minY: 0, maxX: 14, maxY: 4 },
    ]);
    atlasTexture(document, [[path("red")], [path("blue")]], layout, 400);
    const fills = calls.filter((c) => c[0] === "fill");
    expect(fills.map((c) => c[2])).toEqual(["red", "blue"]);
    const rects = calls.filter((c) => c[0] === "rect");
    layout.tiles.forEach((tile, k) => {
      const [a, b, , , e, f] = fills[k]![3] as number[];
      // The square's bottom-left corner at the tile's, its top-right at the tile's (pixels, y down).
      const { x0, y0, size } = tile.square;
      const pixel = (x: number, y: number) => [a! * x + e!, b! * x - a! * y + f!];
      const [left, bottom] = [400 * tile.u0, 400 * (1 - tile.v0)];
      const side = 400 * tile.size;
      expect(pixel(x0, y0)[0]).toBeCloseTo(left, 9);
      expect(pixel(x0, y0)[1]).toBeCloseTo(bottom, 9);
      expect(pixel(x0 + size, y0 + size)[0]).toBeCloseTo(left + side, 9);
      expect(pixel(x0 + size, y0 + size)[1]).toBeCloseTo(bottom - side, 9);
      // The clip is the tile.
      const [, rx, ry, rw, rh] = rects[k] as number[];
      expect([rx, ry, rw, rh].map((v) => v!.toFixed(6))).toEqual(
        [left, bottom - side, side, side].map((v) => v.toFixed(6)),
      );
    });
  });
});

describe("a puppet's layering and picking", () => {
  it("draws triangles back to front by their part's depth; each part's outline is its own loop", () => {
    const { triangles, boundaryEdges, puppet } = twoSheets();
    // The square in front of the bar.
    const layers = partLayering(8, triangles, boundaryEdges, puppet.partOf, [1, 0]);
    expect(Array.from(layers.triangles)).toEqual([1, 1, 0, 0]);
    expect(layers.order).toEqual([0, 1]);
    expect(Array.from(drawOrder(triangles, layers))).toEqual([4, 5, 6, 4, 6, 7, 0, 1, 2, 0, 2, 3]);
    // The outline of each layer: its own four corners, counter-clockwise.
    expect(layers.outlines.map((loops) => loops.map((l) => [...l].sort((a, b) => a - b)))).toEqual([
      [[4, 5, 6, 7]],
      [[0, 1, 2, 3]],
    ]);
    expect(Array.from(layers.edges)).toEqual([1, 1, 1, 1, 0, 0, 0, 0]);
  });

  it("picks the front-most part under the pointer, and lists the parts there front first", () => {
    const { positions, triangles, puppet } = twoSheets();
    // (1.5, 1.5) is on both sheets; (0.5, 0.5) on the square only; (4, 1.5) on the bar only.
    const front = (depths: number[], x: number, y: number) =>
      puppet.partOf[
        locateFront(
          positions,
          triangles,
          Int32Array.from(puppet.partOf, (k) => depths[k]!),
          x,
          y,
        )!.triangle
      ];
    expect(front([0, 1], 1.5, 1.5)).toBe(1);
    expect(front([1, 0], 1.5, 1.5)).toBe(0);
    expect(front([0, 1], 0.5, 0.5)).toBe(0);
    expect(front([1, 0], 4, 1.5)).toBe(1);
    expect(partsUnder(puppet, [0, 1], positions, triangles, 1.5, 1.5).map((u) => u.part)).toEqual([1, 0]);
    expect(partsUnder(puppet, [1, 0], positions, triangles, 1.5, 1.5).map((u) => u.part)).toEqual([0, 1]);
    expect(partsUnder(puppet, [1, 0], positions, triangles, 6, 1.5)).toEqual([]);
  });

  it("finds a part's point in the pose and back, in that part alone", () => {
    const { positions, puppet } = twoSheets();
    // The bar moved up by 10: its rest point (1.5, 1.5) is at (1.5, 11.5); the square stays.
    const posed = Float64Array.from(positions);
    for (let v = 4; v < 8; v++) posed[2 * v + 1]! += 10;
    const near = (p: number[] | undefined, q: number[]) => p!.forEach((v, i) => expect(v).toBeCloseTo(q[i]!, 12));
    near(posedPoint(puppet, 1, positions, posed, 1.5, 1.5), [1.5, 11.5]);
    near(posedPoint(puppet, 0, positions, posed, 1.5, 1.5), [1.5, 1.5]);
    near(restPoint(puppet, 1, positions, posed, 1.5, 11.5), [1.5, 1.5]);
    expect(restPoint(puppet, 1, positions, posed, 1.5, 1.5)).toBeUndefined();
  });

  it("steps a part's depth past its neighbour, and not past the front or back", () => {
    expect(stepDepth([0, 1, 2], 0, 1)).toEqual([1, 0, 2]);
    expect(stepDepth([0, 1, 2], 1, -1)).toEqual([1, 0, 2]);
    expect(stepDepth([5, 1, 9], 1, 1)).toEqual([1, 5, 9]);
    expect(stepDepth([0, 1, 2], 2, 1)).toBeUndefined();
    expect(stepDepth([0, 1, 2], 0, -1)).toBeUndefined();
    // Equal depths become distinct.
    expect(stepDepth([0, 0], 0, 1)).toEqual([1, 0]);
  });

  it("refuses parts that leave a triangle out or claim one twice", () => {
    const { triangles, parts } = twoSheets();
    const part = (list: number[]) => ({ ...parts[0]!, triangles: Uint32Array.from(list) });
    expect(() => puppetOf({ parts: [part([0, 1]), part([2])], joints: [] }, triangles, undefined)).toThrow(
      /triangle 3 is in no part/,
    );
    expect(() => puppetOf({ parts: [part([0, 1, 2]), part([2, 3])], joints: [] }, triangles, undefined)).toThrow(
      /triangle 2 is in parts 0 and 1/,
    );
    expect(() => puppetOf({ parts: [part([0, 1, 2, 3, 9])], joints: [] }, triangles, undefined)).toThrow(
      /names triangle 9/,
    );
  });
});
