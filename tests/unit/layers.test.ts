/**
 * Depth order: each part of the shape takes the layer of its nearest handle along the
 * mesh, triangles are drawn back to front (stable), boundary edges follow their triangles;
 * in the posing, a grabbed part comes to the front unless the user ordered it, and Bring
 * forward / Send back are undone like any gesture.
 */
import { beforeAll, describe, expect, it } from "vitest";
import { init, triangulate } from "../../www/src/index.js";
import { drawOrder, layering } from "../../www/src/widget/model/layers.js";
import { locate } from "../../www/src/widget/model/picking.js";
import { posed } from "./posing-fixtures.js";

beforeAll(async () => {
  await init();
});

/** A 4 x 1 bar, finely meshed. */
function bar() {
  return triangulate({ outer: [0, 0, 4, 0, 4, 1, 0, 1], holes: [] }, { targetEdgeLength: 0.1 });
}

describe("layering", () => {
  it("gives each triangle the layer of the nearer handle, and each boundary edge its triangle's", () => {
    const mesh = bar();
    const { positions: p, triangles: t, boundaryEdges: e } = mesh;
    const at = (x: number, y: number) => locate(p, t, x, y, 1e-9)!;
    // One layer only: no layering.
    expect(layering(p, t, e, [{ point: at(0.2, 0.5), layer: 3 }])).toBeUndefined();
    const layers = layering(p, t, e, [
      { point: at(0.2, 0.5), layer: 0 },
      { point: at(3.8, 0.5), layer: 5 },
    ])!;
    expect(layers.order).toEqual([0, 5]);
    // Along a straight bar the nearer handle is the nearer end: clear of the middle, the
    // left triangles are in layer 0 and the right ones in layer 5.
    let checked = 0;
    for (let f = 0; f < t.length / 3; f++) {
      const xs = [0, 1, 2].map((k) => p[2 * t[3 * f + k]!]!);
      if (Math.max(...xs) < 1.7) expect(layers.triangles[f]).toBe(0);
      else if (Math.min(...xs) > 2.3) expect(layers.triangles[f]).toBe(5);
      else continue;
      checked++;
    }
    expect(checked).toBeGreaterThan(0.8 * (t.length / 3));
    for (let i = 0; i < e.length / 2; i++) {
      const x = (p[2 * e[2 * i]!]! + p[2 * e[2 * i + 1]!]!) / 2;
      if (x < 1.7) expect(layers.edges[i]).toBe(0);
      if (x > 2.3) expect(layers.edges[i]).toBe(5);
    }
    // Back to front: every layer-0 triangle before every layer-5 one, each in its own order.
    const ordered = drawOrder(t, layers);
    const key = (k: number) => `${ordered[3 * k]},${ordered[3 * k + 1]},${ordered[3 * k + 2]}`;
    const index = new Map(
      Array.from({ length: t.length / 3 }, (_, f) => [`${t[3 * f]},${t[3 * f + 1]},${t[3 * f + 2]}`, f]),
    );
    const original = Array.from({ length: t.length / 3 }, (_, k) => index.get(key(k))!);
    expect([...original].sort((a, b) => a - b)).toEqual(Array.from({ length: t.length / 3 }, (_, f) => f));
    const back = original.filter((f) => layers.triangles[f] === 0);
    expect(original.slice(0, back.length)).toEqual([...back].sort((a, b) => a - b));
    expect(drawOrder(t, undefined)).toBe(t);
    // Each layer's outline loops enclose exactly its triangles: equal signed areas at rest.
    const area = (a: number, b: number, c: number) =>
      ((p[2 * b]! - p[2 * a]!) * (p[2 * c + 1]! - p[2 * a + 1]!) -
        (p[2 * c]! - p[2 * a]!) * (p[2 * b + 1]! - p[2 * a + 1]!)) /
      2;
    layers.order.forEach((layer, index) => {
      let triangles = 0;
      for (let f = 0; f < t.length / 3; f++)
        if (layers.triangles[f] === layer) triangles += area(t[3 * f]!, t[3 * f + 1]!, t[3 * f + 2]!);
      let loops = 0;
      for (const loop of layers.outlines[index]!) {
        for (let i = 1; i + 1 < loop.length; i++) loops += area(loop[0]!, loop[i]!, loop[i + 1]!);
      }
      expect(loops).toBeCloseTo(triangles, 12);
      expect(triangles).toBeGreaterThan(1);
    });
  });
});

describe("depth order while posing", () => {
  it("a grabbed part comes to the front; Send back keeps it behind, also when grabbed; undo restores", () => {
    const { posing } = posed(500);
    expect(posing.handles.map((h) => h.layer)).toEqual([0, 0]);
    const [x, y] = Array.from(posing.deformer.handlePositions()).slice(2, 4) as [number, number];
    posing.beginGesture();
    posing.grab(1, 4, x, y, false);
    posing.release(4);
    expect(posing.handles.map((h) => h.layer)).toEqual([0, 1]);
    // Grabbing it again changes nothing: it is in front already.
    posing.grab(1, 4, x, y, false);
    posing.release(4);
    expect(posing.handles[1]!.layer).toBe(1);

    // Handle 1 is selected: send it back.
    posing.gesture(() => expect(posing.reorder(-1)).toBe(true));
    expect(posing.handles.map((h) => [h.layer, h.ordered])).toEqual([
      [0, false],
      [-1, true],
    ]);
    posing.grab(1, 4, x, y, false);
    posing.release(4);
    expect(posing.handles[1]!.layer).toBe(-1);
    expect(posing.travel(false)).toBe(true);
    expect(posing.handles.map((h) => [h.layer, h.ordered])).toEqual([
      [0, false],
      [1, false],
    ]);
    posing.handles.forEach((h) => (h.selected = false));
    expect(posing.reorder(1)).toBe(false);
  });
});
