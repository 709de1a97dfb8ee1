import { describe, expect, it } from "vitest";
import { bounds } from "../../www/src/widget/model/geometry.js";
import { fitView, fromPixel, panBy, toPixel, zoomAt } from "../../www/src/widget/view/projection.js";

describe("fitView", () => {
  it("centres the box and fits its limiting side inside the margin", () => {
    // A 2 x 1 box in a 1000 x 1000 canvas with a 5% margin: width limits, 900 px for 2 units.
    const positions = [-1, 0, 1, 0, 1, 1, -1, 1];
    const view = fitView(positions, 1000, 1000, 0.05);
    expect(view.scale).toBeCloseTo(450, 12);
    expect(toPixel(view, -1, 0)).toEqual([50, 725]);
    expect(toPixel(view, 1, 1)).toEqual([950, 275]);
  });

  it("flips y so that shapes stand upright", () => {
    const view = fitView([0, 0, 1, 1], 100, 100, 0);
    const [, top] = toPixel(view, 0, 1);
    const [, bottom] = toPixel(view, 0, 0);
    expect(top).toBeLessThan(bottom);
  });

  it("keeps a finite scale for a single point", () => {
    const view = fitView([3, 4], 200, 100);
    expect(Number.isFinite(view.scale)).toBe(true);
    expect(toPixel(view, 3, 4)).toEqual([100, 50]);
  });

  it("rejects an empty list", () => {
    expect(() => bounds([])).toThrow(/empty/);
  });
});

describe("zoomAt and panBy", () => {
  const view = { scale: 120, offsetX: 300, offsetY: 400 };

  it("keeps the shape point under the zoom centre where it was", () => {
    const [x, y] = fromPixel(view, 512, 77);
    const zoomed = zoomAt(view, 512, 77, 2.5);
    expect(zoomed.scale).toBe(300);
    const [px, py] = toPixel(zoomed, x, y);
    expect(px).toBeCloseTo(512, 9);
    expect(py).toBeCloseTo(77, 9);
    // Distances between shape points grow by the factor.
    const a = toPixel(zoomed, 0, 0);
    const b = toPixel(zoomed, 1, 0);
    expect(b[0] - a[0]).toBeCloseTo(300, 9);
  });

  it("moves every shape point by the pan, scale unchanged", () => {
    const moved = panBy(view, -40, 25);
    for (const [x, y] of [
      [0, 0],
      [1.5, -2],
    ] as const) {
      const [px, py] = toPixel(view, x, y);
      const [qx, qy] = toPixel(moved, x, y);
      expect(qx - px).toBeCloseTo(-40, 9);
      expect(qy - py).toBeCloseTo(25, 9);
    }
    expect(moved.scale).toBe(view.scale);
  });
});
