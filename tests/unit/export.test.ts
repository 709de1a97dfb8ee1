/** SVG exports of a pose: the outline's fill where parts overlap, vector art's colours. */
import { beforeAll, describe, expect, it } from "vitest";
import { importSvgPaths, init, triangulate, type VectorPath } from "../../www/src/index.js";
import { outlineSvg, vectorSvg } from "../../www/src/widget/store/pose-export.js";
import { bounds } from "../../www/src/widget/model/geometry.js";

beforeAll(async () => {
  await init();
});

/** The subpaths of absolute `M x y L x y ... Z` path data, as closed polygons. */
function polygons(d: string): [number, number][][] {
  const result: [number, number][][] = [];
  const tokens = d.match(/[MLZ]|-?[\d.]+(?:e[-+]?\d+)?/g)!;
  for (let i = 0; i < tokens.length;) {
    const command = tokens[i++]!;
    if (command === "Z") continue;
    const point: [number, number] = [Number(tokens[i]), Number(tokens[i + 1])];
    i += 2;
    if (command === "M") result.push([point]);
    else result[result.length - 1]!.push(point);
  }
  return result;
}

/**
 * The winding number of closed polygons around a point: +1 for each edge crossing the
 * horizontal ray to the right of the point going up with the point on its left, -1 going
 * down with the point on its right (counter-clockwise in a y-up frame counts +1).
 */
function winding(loops: [number, number][][], [px, py]: [number, number]): number {
  let w = 0;
  for (const loop of loops) {
    for (let i = 0; i < loop.length; i++) {
      const [ax, ay] = loop[i]!;
      const [bx, by] = loop[(i + 1) % loop.length]!;
      const side = (bx - ax) * (py - ay) - (by - ay) * (px - ax);
      if (ay <= py && by > py && side > 0) w += 1;
      else if (by <= py && ay > py && side < 0) w -= 1;
    }
  }
  return w;
}

describe("outline SVG of a pose whose parts overlap", () => {
  // A strip 10 x 1 with a hole, curled by (x, y) -> (r cos t, r sin t) with r = 2 + y and
  // t = 2.5 pi x / 10: one and a quarter turns, so its last quarter (x from 8 to 10) lies
  // over its first (x from 0 to 2). The map keeps orientation, so every triangle stays
  // counter-clockwise; a point's winding number is the number of layers covering it.
  const length = 10;
  const curl = (x: number, y: number): [number, number] => {
    const t = (2.5 * Math.PI * x) / length;
    return [(2 + y) * Math.cos(t), (2 + y) * Math.sin(t)];
  };
  const polar = (r: number, t: number): [number, number] => [r * Math.cos(t), r * Math.sin(t)];

  it("fills the overlap (winding 2) and leaves the hole empty (winding 0)", () => {
    const mesh = triangulate(
      { outer: [0, 0, length, 0, length, 1, 0, 1], holes: [[4, 0.25, 4, 0.75, 5, 0.75, 5, 0.25]] },
      { targetEdgeLength: 0.1 },
    );
    const posed = new Float64Array(mesh.positions.length);
    for (let v = 0; v < mesh.vertexCount; v++) {
      posed.set(curl(mesh.positions[2 * v]!, mesh.positions[2 * v + 1]!), 2 * v);
    }
    const svg = outlineSvg(posed, mesh.boundaryEdges);
    expect(svg).toContain('fill-rule="nonzero"');
    const loops = polygons(/ d="([^"]*)"/.exec(svg)![1]!);
    expect(loops).toHaveLength(2);
    // SVG's y points down: the pose's top-left corner is the picture's top-left one.
    const b = bounds(posed);
    const xs = loops.flat().map((p) => p[0]);
    const ys = loops.flat().map((p) => p[1]);
    const [left, top] = [Math.min(...xs), Math.min(...ys)];
    const inPicture = ([x, y]: [number, number]): [number, number] => [x - b.minX + left, b.maxY - y + top];
    // The winding number's sign flips with y; only zero or not matters for the nonzero rule.
    const layers = (p: [number, number]) => Math.abs(winding(loops, inPicture(p)));
    expect(layers(polar(2.5, Math.PI / 4))).toBe(2); // the overlap: x = 1 and x = 9
    expect(layers(polar(2.5, 1.5 * Math.PI))).toBe(1); // one layer: x = 6
    expect(layers(curl(4.5, 0.5))).toBe(0); // the centre of the hole
    expect(layers([0, 0])).toBe(0); // the middle of the curl, outside the strip
  });
});

describe("outline SVG export", () => {
  it("writes each boundary loop as a subpath, y flipped into the view box with a 2% margin", () => {
    // The unit square with its corner (1, 1) pulled out to (3, 1): bounds 0..3 x 0..1.
    const svg = outlineSvg([0, 0, 1, 0, 3, 1, 0, 1], [0, 1, 1, 2, 2, 3, 3, 0]);
    expect(/ d="([^"]*)"/.exec(svg)![1]).toBe("M 0 0 L 1 0 L 3 -1 L 0 -1 Z");
    const box = /viewBox="([^"]*)"/.exec(svg)![1]!.split(" ").map(Number);
    // margin 0.02 * 3; y from -(1 + margin) (the top) to margin.
    [-0.06, -1.06, 3.12, 1.12].forEach((expected, i) => expect(box[i]).toBeCloseTo(expected, 12));
  });
});

describe("vector SVG export", () => {
  const text =
    '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 20">' +
    '<g fill="red" opacity="0.5"><rect width="10" height="10" fill-opacity="0.5"/></g>' +
    '<rect x="20" width="10" height="10" fill="#0f0" fill-rule="evenodd"/>' +
    '<linearGradient id="g"><stop offset="0" stop-color="red"/><stop offset="1"/></linearGradient>' +
    '<rect x="40" width="10" height="10" fill="url(#g)"/>' +
    '<circle cx="70" cy="10" r="5" fill="none" stroke="#00f" stroke-width="2"/></svg>';

  it("writes each path in its own colour and opacity, the default only when unknown", () => {
    const paths = importSvgPaths(text);
    const svg = vectorSvg(paths.map((path) => ({ path, points: path.points })));
    const written = [...svg.matchAll(/<path d="[^"]*" ([^/]*)\/>/g)].map((m) => m[1]);
    // The stroke is its outline, filled in the stroke's colour.
    expect(written).toEqual([
      'fill="#ff0000" fill-opacity="0.25" fill-rule="nonzero"',
      'fill="#00ff00" fill-rule="evenodd"',
      'fill="#c8773a" fill-rule="nonzero"',
      'fill="#0000ff" fill-rule="nonzero"',
    ]);
    expect(paths.map((p) => p.part)).toEqual(["fill", "fill", "fill", "stroke"]);
    expect(vectorSvg([{ path: paths[2]!, points: paths[2]!.points }], "teal")).toContain('fill="teal"');
  });

  it("writes other CSS colours as they are, escaped", () => {
    const path: VectorPath = {
      element: "<path>",
      part: "fill",
      commands: "MLLZ",
      points: Float64Array.from([0, 0, 1, 0, 0, 1]),
      fillRule: "nonzero",
      fill: 'cornflowerblue"<',
    };
    expect(vectorSvg([{ path, points: path.points }])).toContain('fill="cornflowerblue&quot;&lt;"');
  });
});
