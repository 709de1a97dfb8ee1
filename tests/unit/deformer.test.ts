/** The Deformer through the real wasm package in Node: rigid motions and bad input. */
import { beforeAll, describe, expect, it } from "vitest";
import { Deformer, defaultShape, init, triangulate } from "../../www/src/index.js";

beforeAll(async () => {
  await init();
});

describe("Deformer", () => {
  it("rotates the shape rigidly when the handles follow an infinitesimal rotation", () => {
    const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.08 });
    const deformer = new Deformer(mesh.positions, mesh.triangles);
    deformer.setHandlePoints([0, 40, 80], [0.2, 0.3, 0.5, 1, 0, 0, 0.1, 0.1, 0.8]);
    const [a, cx, cy] = [0.25, 0.1, 0.6];
    const h = deformer.handlePositions();
    const velocities: number[] = [];
    for (let i = 0; i < h.length; i += 2) velocities.push(-a * (h[i + 1]! - cy), a * (h[i]! - cx));
    deformer.step(velocities);
    const p = deformer.positions();
    const [s, c] = [Math.sin(a), Math.cos(a)];
    for (let v = 0; v < mesh.vertexCount; v++) {
      const [x, y] = [mesh.positions[2 * v]! - cx, mesh.positions[2 * v + 1]! - cy];
      expect(p[2 * v]!).toBeCloseTo(cx + c * x - s * y, 9);
      expect(p[2 * v + 1]!).toBeCloseTo(cy + s * x + c * y, 9);
    }
    expect(deformer.metrics().areaDistortion).toBeCloseTo(2, 9);
    const t = deformer.timings();
    expect(t.factorisation).toBeGreaterThanOrEqual(0);
    deformer.free();
  });

  it("throws clear errors and keeps its state", () => {
    const deformer = new Deformer([0, 0, 1, 0, 1, 1, 0, 1], [0, 1, 2, 0, 2, 3], { lambda: 10 });
    deformer.setHandles([0, 2]);
    deformer.step([0, 0, 0.1, 0]);
    const before = deformer.positions();
    expect(() => deformer.setHandles([0, 9])).toThrow(/only 4 vertices/);
    expect(() => deformer.step([0, 0])).toThrow(/velocities has length 2, expected 4/);
    expect(() => deformer.step([0, 0, NaN, 0])).toThrow(/not a finite number/);
    expect(() => deformer.setHandlePoints([0], [0.5, 0.2, 0.2])).toThrow(/barycentric/);
    expect(() => deformer.setOptions({ integrator: "euler" as never })).toThrow(/integrator/);
    expect(() => new Deformer([0, 0, 1, 0, 0, 1], [0, 2, 1])).toThrow(/counter-clockwise/);
    expect(() => new Deformer([0, 0, 1, 0, 0, 1], [0, 1, 2], { lamda: 1 } as never)).toThrow(/unknown deformer option/);
    expect(deformer.positions()).toEqual(before);
    expect(deformer.handleCount).toBe(2);
    deformer.free();
  });

  it("runs ARAP with the same interface", () => {
    const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.1 });
    const deformer = new Deformer(mesh.positions, mesh.triangles, { method: "arap", iterations: 5 });
    expect(deformer.method).toBe("arap");
    // Handles at vertices are hard constraints: a translation of all of them is exact.
    deformer.setHandles([0, 17, 42]);
    deformer.step([0.1, -0.2, 0.1, -0.2, 0.1, -0.2]);
    const p = deformer.positions();
    for (let v = 0; v < mesh.vertexCount; v++) {
      expect(p[2 * v]! - mesh.positions[2 * v]!).toBeCloseTo(0.1, 9);
      expect(p[2 * v + 1]! - mesh.positions[2 * v + 1]!).toBeCloseTo(-0.2, 9);
    }
    expect(deformer.metrics().areaDistortion).toBeCloseTo(2, 9);
    expect(() => deformer.setOptions({ lambda: 10 })).toThrow(/applies to method "akap"/);
    expect(() => deformer.setOptions({ method: "akap" })).toThrow(/chosen when the deformer is created/);
    expect(() => new Deformer(mesh.positions, mesh.triangles, { iterations: 3 })).toThrow(/applies to method "arap"/);
    deformer.setOptions({ iterations: 2 });
    deformer.free();
  });
});
