/** The public API in Node, through the real wasm package (built by scripts/build.sh). */
import { beforeAll, describe, expect, it } from "vitest";
import {
  defaultShape,
  importSvg,
  init,
  limits,
  meshFromArrays,
  triangulate,
  triangulateToVertices,
} from "../../www/src/index.js";

beforeAll(async () => {
  await init();
});

function ringArea(ring: ArrayLike<number>): number {
  let twice = 0;
  const n = ring.length / 2;
  for (let i = 0; i < n; i++) {
    const j = (i + 1) % n;
    twice += ring[2 * i]! * ring[2 * j + 1]! - ring[2 * j]! * ring[2 * i + 1]!;
  }
  return twice / 2;
}

describe("triangulateToVertices", () => {
  it("meshes to within 3% of a vertex count, and its edge length makes the same mesh", () => {
    const outline = { outer: [0, 0, 4, 0, 4, 4, 0, 4], holes: [[1, 1, 1, 2, 2, 2, 2, 1]] };
    for (const [shape, vertices] of [
      [defaultShape(), 1500],
      [outline, 5000],
    ] as const) {
      const { mesh, targetEdgeLength } = triangulateToVertices(shape, vertices, { minAngle: 28 });
      expect(Math.abs(mesh.vertexCount - vertices)).toBeLessThanOrEqual(0.03 * vertices);
      const again = triangulate(shape, { targetEdgeLength, minAngle: 28 });
      expect(again.positions).toEqual(mesh.positions);
      expect(again.triangles).toEqual(mesh.triangles);
    }
    expect(() => triangulateToVertices(outline, 2)).toThrow(/vertices/);
    expect(() => triangulateToVertices(outline, 1.5)).toThrow(/whole number/);
    expect(() => triangulateToVertices(outline, 100, { vertexes: 3 } as never)).toThrow(/unknown triangulation option/);
  });
});

describe("triangulate", () => {
  it("covers a square with a hole exactly, with counter-clockwise triangles", () => {
    const mesh = triangulate(
      { outer: [0, 0, 4, 0, 4, 4, 0, 4], holes: [[1, 1, 1, 2, 2, 2, 2, 1]] },
      { targetEdgeLength: 0.3, minAngle: 25 },
    );
    expect(mesh.positions.length).toBe(2 * mesh.vertexCount);
    expect(mesh.triangles.length).toBe(3 * mesh.triangleCount);
    let sum = 0;
    const p = mesh.positions;
    for (let i = 0; i < mesh.triangles.length; i += 3) {
      const [a, b, c] = [mesh.triangles[i]!, mesh.triangles[i + 1]!, mesh.triangles[i + 2]!];
      const area = ringArea([p[2 * a]!, p[2 * a + 1]!, p[2 * b]!, p[2 * b + 1]!, p[2 * c]!, p[2 * c + 1]!]);
      expect(area).toBeGreaterThan(0);
      sum += area;
    }
    expect(sum).toBeCloseTo(15, 10);
    expect(mesh.area).toBeCloseTo(15, 10);
    // Area bound from the edge length: sqrt(3)/4 h^2 per triangle at most.
    expect(mesh.triangleCount).toBeGreaterThanOrEqual(15 / ((Math.sqrt(3) / 4) * 0.09));
  });

  it("triangulates the default shape to its outline's area", () => {
    const shape = defaultShape();
    const expected = Math.abs(ringArea(shape.outer)) - shape.holes.reduce((s, h) => s + Math.abs(ringArea(h)), 0);
    const mesh = triangulate(shape, { targetEdgeLength: 0.05 });
    expect(mesh.area).toBeCloseTo(expected, 9);
    expect(mesh.boundaryEdges.length / 2).toBe(mesh.boundaryVertices.length);
  });

  it("throws Errors that name the problem", () => {
    expect(() => triangulate({ outer: [0, 0, 1, 0] })).toThrow(/at least 3/);
    expect(() => triangulate({ outer: [0, 0, 2, 2, 2, 0, 0, 1] })).toThrow(/intersects itself/);
    expect(() => triangulate({ outer: [0, 0, 1, 0, NaN, 1] })).toThrow(/not a finite number/);
    expect(() => triangulate({ outer: [0, 0, 1, 0, 0, 1] }, { minAngle: 60 })).toThrow(/minAngle/);
    expect(() => triangulate({ outer: [0, 0, 1, 0, 0, 1] }, { typo: 1 } as never)).toThrow(
      /unknown triangulation option/,
    );
    expect(() => triangulate({ outer: "0,0" as never })).toThrow(TypeError);
  });
});

describe("meshFromArrays", () => {
  it("accepts a valid mesh and finds its boundary", () => {
    const mesh = meshFromArrays([0, 0, 1, 0, 1, 1, 0, 1], [0, 1, 2, 0, 2, 3]);
    expect(Array.from(mesh.boundaryVertices)).toEqual([0, 1, 2, 3]);
    expect(mesh.area).toBe(1);
  });

  it("rejects clockwise triangles and bad indices", () => {
    expect(() => meshFromArrays([0, 0, 1, 0, 0, 1], [0, 2, 1])).toThrow(/counter-clockwise/);
    expect(() => meshFromArrays([0, 0, 1, 0, 0, 1], [0, 1, 5])).toThrow(/refers to vertex 5/);
    expect(() => meshFromArrays([0, 0, 1, 0, 0, 1], [0, 1, -1])).toThrow(RangeError);
  });

  it("refuses a bow-tie by its vertex, and triangulates near-touches and tiny or huge shapes", () => {
    expect(() => meshFromArrays([0, 0, 1, 0, 0, 1, -1, 0, 0, -1], [0, 1, 2, 0, 3, 4])).toThrow(
      /vertex 0 joins 2 fans of triangles that share no edge there/,
    );
    // A notch whose tip comes within 1e-9 of the opposite side.
    const notch = triangulate({ outer: [0, 0, 2, 0, 2, 2, 1, 1e-9, 0, 2] }, { targetEdgeLength: 0.1 });
    expect(notch.area).toBeCloseTo(2 + 1e-9, 12);
    for (const scale of [1e-300, 1e200]) {
      const mesh = triangulate(
        { outer: [0, 0, 4, 0, 4, 3, 0, 3].map((x) => x * scale) },
        { targetEdgeLength: 0.5 * scale },
      );
      expect(mesh.vertexCount).toBeGreaterThan(40);
    }
    expect(() => triangulate({ outer: [0, 0, 2e300, 0, 0, 1] })).toThrow(
      "point 1 of the outer boundary has the coordinate 2e300, beyond the limit of ±1e300; scale the outline down",
    );
  });
});

describe("limits", () => {
  it("are the README's, and the ones every function enforces", () => {
    // README: "32 MB per file, 4096 x 4096 pixels, 100000 vertices" (and 100000 outline
    // points), and sessions up to 80 MB.
    const l = limits();
    expect(l).toEqual({
      bytes: 32 * 1024 * 1024,
      pixels: 4096 * 4096,
      points: 100_000,
      vertices: 100_000,
      sessionBytes: 80_000_000,
      stiffness: [0.001, 1000],
      animationBytes: 1024 * 1024 * 1024,
    });
    expect(() => triangulate(defaultShape(), { maxVertices: l.vertices + 1 })).toThrow(
      `option maxVertices is ${l.vertices + 1}, expected a whole number from 0 to ${l.vertices}`,
    );
    const svg = `<svg xmlns="http://www.w3.org/2000/svg">${" ".repeat(l.bytes)}</svg>`;
    expect(() => importSvg(svg)).toThrow(`; the limit is ${l.bytes}`);
    const positions = new Float64Array(2 * l.vertices + 2);
    expect(() => meshFromArrays(positions, [0, 1, 2])).toThrow(
      `the mesh has ${l.vertices + 1} vertices (${2 * l.vertices + 2} numbers), more than the limit of ${l.vertices} vertices`,
    );
  });
});
