/** The import API in Node, through the real wasm package (built by scripts/build.sh). */
import { readFileSync } from "node:fs";
import { beforeAll, describe, expect, it } from "vitest";
import {
  importImagePuppet,
  importPuppet,
  importSvg,
  importSvgPaths,
  init,
  mapPoints,
  meshFromJson,
  meshFromObj,
  meshToJson,
  meshToObj,
  pathData,
  PointMapper,
  textureCoordinates,
  traceImage,
  triangulate,
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

const svg = (body: string, viewBox = "0 0 100 100") =>
  `<svg xmlns="http://www.w3.org/2000/svg" viewBox="${viewBox}">${body}</svg>`;

describe("importSvg", () => {
  it("gives outlines with holes, y up, largest first", () => {
    const outlines = importSvg(
      svg(
        '<path fill-rule="evenodd" d="M10 10 H90 V60 H10 Z M20 20 h10 v10 h-10 z"/><rect x="0" y="80" width="5" height="5"/>',
      ),
    );
    expect(outlines).toHaveLength(2);
    const [body, speck] = outlines;
    expect(Math.abs(ringArea(body!.outer))).toBe(4000);
    expect(body!.holes).toHaveLength(1);
    expect(Math.abs(ringArea(body!.holes[0]!))).toBe(100);
    // The viewBox's top edge (y = 0) is at y = 100 after the flip.
    expect(Math.max(...body!.outer.filter((_, i) => i % 2 === 1))).toBe(90);
    expect(Math.abs(ringArea(speck!.outer))).toBe(25);
    const mesh = triangulate(body!, { targetEdgeLength: 5 });
    expect(mesh.area).toBeCloseTo(3900, 9);
  });

  it("imports every gallery SVG into one piece that triangulates", () => {
    const index = JSON.parse(readFileSync("www/gallery/index.json", "utf8")) as { file: string; kind: string }[];
    const svgs = index.filter((entry) => entry.kind === "svg");
    expect(svgs.length).toBeGreaterThanOrEqual(2);
    // The layered characters (Inkscape layers, one per puppet part) are checked below.
    const flat = svgs.filter(
      (entry) => !readFileSync(`www/gallery/${entry.file}`, "utf8").includes("inkscape:groupmode"),
    );
    expect(flat.length).toBeGreaterThanOrEqual(2);
    for (const entry of flat) {
      const outlines = importSvg(readFileSync(`www/gallery/${entry.file}`, "utf8"));
      expect(outlines).toHaveLength(1);
      expect(outlines[0]!.holes.length).toBeGreaterThan(0);
      expect(triangulate(outlines[0]!, { targetEdgeLength: 6 }).triangleCount).toBeGreaterThan(100);
    }
  });

  it("imports the gallery's layered characters: labelled layers whose union triangulates", () => {
    // Milo: the hat floats free of the rest; Basil: every part overlaps the body.
    const expected: Record<string, { layers: string[]; pieces: number }> = {
      "magician.svg": {
        layers: ["Left arm", "Right leg", "Left leg", "Torso", "Head", "Right arm", "Hat"],
        pieces: 2,
      },
      "dragon.svg": { layers: ["Tail", "Hind leg", "Body", "Front leg", "Wing", "Head"], pieces: 1 },
    };
    const index = JSON.parse(readFileSync("www/gallery/index.json", "utf8")) as { file: string }[];
    expect(index[0]!.file).toBe("magician.svg");
    for (const [file, { layers, pieces }] of Object.entries(expected)) {
      expect(index.map((entry) => entry.file)).toContain(file);
      const text = readFileSync(`www/gallery/${file}`, "utf8");
      const labels = [...text.matchAll(/<g inkscape:groupmode="layer" id="[^"]+" inkscape:label="([^"]+)">/g)];
      expect(labels.map((match) => match[1])).toEqual(layers);
      const outlines = importSvg(text);
      expect(outlines).toHaveLength(pieces);
      for (const outline of outlines) {
        expect(triangulate(outline, { targetEdgeLength: 6 }).triangleCount).toBeGreaterThan(100);
      }
    }
  });

  it("throws Errors that say what and where, and checks option names", () => {
    // Path data is drawn up to its first error, as browsers draw it: here, nothing.
    expect(() => importSvg(svg('<path d="M0 0 L 5"/>'))).toThrow(/no filled shape/);
    expect(() => importSvg(svg('<path d="M0 0 L 1e999 0 L 0 1 Z"/>'))).toThrow(
      /<path> \(line 1, column \d+\) is too large/,
    );
    expect(() => importSvg("<svg")).toThrow(/not well-formed XML at line 1/);
    expect(() => importSvg(svg("<text>hi</text>"))).toThrow(/no filled shape \(unsupported elements skipped: text\)/);
    expect(() => importSvg(svg('<rect width="1" height="1"/>'), { tolerence: 1 } as never)).toThrow(
      /unknown SVG import option `tolerence`/,
    );
    expect(() => importSvg(svg('<rect width="1" height="1"/>'), { tolerance: -1 })).toThrow(/option tolerance/);
    expect(() => importSvg(svg('<rect width="1" height="1"/>'), { maxBytes: 10 })).toThrow(
      /the SVG text is \d+ bytes; the limit is 10/,
    );
  });
});

describe("importPuppet", () => {
  const layered = readFileSync("tests/fixtures/svg/layered-puppet.svg", "utf8");

  it("gives a sheet per layer, named and in depth order, joined where layers overlap", () => {
    const puppet = importPuppet(layered, { vertices: 1500 });
    expect(puppet.positions).toBeInstanceOf(Float64Array);
    expect(puppet.triangles).toBeInstanceOf(Uint32Array);
    expect(puppet.parts.map((p) => p.name)).toEqual(["Torso", "Head", "Arm", "Hat"]);
    expect(puppet.parts.map((p) => p.depth)).toEqual([0, 1, 2, 3]);
    // Every triangle in one part, and no vertex in two.
    const owner = new Int32Array(puppet.positions.length / 2).fill(-1);
    let count = 0;
    puppet.parts.forEach((part, k) => {
      expect(part.triangles).toBeInstanceOf(Uint32Array);
      count += part.triangles.length;
      for (const t of part.triangles) {
        for (let c = 0; c < 3; c++) {
          const v = puppet.triangles[3 * t + c]!;
          expect(owner[v] === -1 || owner[v] === k).toBe(true);
          owner[v] = k;
        }
      }
    });
    expect(count).toBe(puppet.triangles.length / 3);
    // The torso's area: its rectangle, 80 x 120.
    let area = 0;
    for (const t of puppet.parts[0]!.triangles) {
      const [a, b, c] = [0, 1, 2].map((k) => puppet.triangles[3 * t + k]!) as [number, number, number];
      const x = (v: number) => puppet.positions[2 * v]!;
      const y = (v: number) => puppet.positions[2 * v + 1]!;
      area += ((x(b) - x(a)) * (y(c) - y(a)) - (y(b) - y(a)) * (x(c) - x(a))) / 2;
    }
    expect(area).toBeCloseTo(9600, 6);
    const pairs = puppet.joints.map((j) => j.parts).sort((p, q) => p[0] - q[0]);
    expect(pairs).toEqual([
      [1, 0],
      [2, 0],
    ]);
    for (const { point } of puppet.joints) expect(point).toHaveLength(2);
    // Each part's art is its own, in the form importSvgPaths gives.
    expect(puppet.parts.flatMap((p) => p.paths)).toEqual(importSvgPaths(layered));
    expect(puppet.parts[0]!.paths.map((p) => p.fill)).toEqual(["rgba(46, 139, 87, 1)", "rgba(139, 69, 19, 1)"]);
    expect(puppet.skipped).toEqual([]);
  });

  it("checks its options by name and refuses what is not an SVG", () => {
    expect(() => importPuppet(layered, { vertexes: 10 } as never)).toThrow(/unknown puppet import option `vertexes`/);
    expect(() => importPuppet(layered, { vertices: 1 })).toThrow(/option vertices is 1/);
    expect(() => importPuppet("<html/>")).toThrow(/not <svg>/);
  });

  it("gives an image a part per separate region", () => {
    const [w, h] = [20, 10];
    const rgba = new Uint8ClampedArray(4 * w * h);
    for (const [x0, s] of [
      [1, 6],
      [12, 5],
    ] as const) {
      for (let y = 2; y < 2 + s; y++) for (let x = x0; x < x0 + s; x++) rgba[4 * (y * w + x) + 3] = 255;
    }
    const puppet = importImagePuppet(rgba, w, h, { minArea: 1, vertices: 100 });
    expect(puppet.parts.map((p) => p.name)).toEqual(["Part 1", "Part 2"]);
    expect(puppet.joints).toEqual([]);
    expect(() => importImagePuppet(rgba, 0, h)).toThrow(/not a pixel count/);
  });
});

describe("vector export", () => {
  it("maps path points through a deformed mesh and writes path data", () => {
    const text = svg('<path d="M10 10 C 30 0 70 0 90 10 L 90 90 H 10 Z"/>');
    const [path] = importSvgPaths(text);
    expect(path!.commands).toBe("MCLLZ");
    expect(path!.fillRule).toBe("nonzero");
    expect(path!.element).toMatch(/^<path> \(line 1/);
    expect(path!.part).toBe("fill");
    const mesh = triangulate(importSvg(text)[0]!, { targetEdgeLength: 10 });
    // Shift the whole mesh by (5, -2): every point, control points outside included, follows.
    const moved = mesh.positions.map((v, i) => v + (i % 2 === 0 ? 5 : -2));
    const mapped = mapPoints(mesh.positions, mesh.triangles, moved, path!.points);
    path!.points.forEach((v, i) => expect(mapped[i]).toBeCloseTo(v + (i % 2 === 0 ? 5 : -2), 9));
    const mapper = new PointMapper(mesh.positions, mesh.triangles, path!.points);
    expect(mapper.length).toBe(path!.points.length / 2);
    const n = mesh.vertexCount;
    expect(() => mapper.map([0, 0])).toThrow(
      `deformed positions have 2 numbers, expected ${2 * n} (2 for each of the ${n} rest vertices)`,
    );
    const broken = moved.slice();
    broken[3] = NaN;
    expect(() => mapper.map(broken)).toThrow("deformed position 1 has a value that is not a finite number");
    mapper.free();
    expect(pathData(path!)).toBe("M 10 90 C 30 100 70 100 90 90 L 90 10 L 10 10 Z");
    expect(pathData(path!, path!.points, { flipY: true })).toBe(
      "M 10 -90 C 30 -100 70 -100 90 -90 L 90 -10 L 10 -10 Z",
    );
    // Shortest exact numbers, exponents outside 1e-6..1e21, no "-0"; bad paths refused.
    expect(
      pathData({ commands: "MLZ", points: Float64Array.from([1e-300, 0, 0.1, 2e21]) }, undefined, { flipY: true }),
    ).toBe("M 1e-300 0 L 0.1 -2e21 Z");
    expect(() => pathData({ commands: "MX", points: new Float64Array(2) })).toThrow(/unknown path command 'X'/);
    expect(() => pathData({ commands: "MC", points: new Float64Array(4) })).toThrow(
      "the commands take 4 points, but 2 were given",
    );
    expect(() => pathData({ commands: "M", points: Float64Array.from([0, NaN]) })).toThrow(/not finite/);
  });

  it("gives each path its fill colour as rgba(), opacities folded in, undefined when unknown", () => {
    const paths = importSvgPaths(
      svg(
        '<g fill="red" opacity="0.5"><rect width="10" height="10" fill-opacity="0.5"/></g>' +
          '<g color="#0f0"><rect x="20" width="10" height="10" fill="currentColor"/></g>' +
          '<linearGradient id="g"><stop offset="0" stop-color="red"/><stop offset="1"/></linearGradient>' +
          '<rect x="40" width="10" height="10" fill="url(#g)"/>' +
          '<rect x="60" width="10" height="10" fill="red" style="fill: hsl(240, 100%, 50%)"/>' +
          '<rect x="80" width="10" height="10"/>',
      ),
    );
    // 1 (red) x 0.5 (fill-opacity) x 0.5 (the group's opacity); currentColor is the
    // inherited color; a gradient is unknown; style overrides the attribute
    // (hsl(240, 100%, 50%) is blue); no fill at all is black.
    expect(paths.map((p) => p.fill)).toEqual([
      "rgba(255, 0, 0, 0.25)",
      "rgba(0, 255, 0, 1)",
      undefined,
      "rgba(0, 0, 255, 1)",
      "rgba(0, 0, 0, 1)",
    ]);
    expect(paths.every((p) => "fill" in p)).toBe(true);
  });
});

describe("huge coordinates", () => {
  // A drawing whose coordinates the geometry cannot work with in double precision is
  // refused by the import, naming the element and the limit, not later by the mesher in
  // its own terms.
  const cases = [
    [
      '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 1e308 1e308"><rect width="1e308" height="1e308"/></svg>',
      "<svg>",
      "its viewBox holds 1e308",
    ],
    [
      '<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 0 L 1e308 0 L 1e308 1e308 Z"/></svg>',
      "<path>",
      "its d holds 1e308",
    ],
    // 1e20 x 1e15, in usvg's single precision.
    [
      svg('<rect transform="scale(1e20)" width="1e15" height="10"/>', "0 0 10 10"),
      "<rect>",
      "it reaches 1.000000007031981e35 in the drawing's units",
    ],
  ] as const;
  for (const [text, element, reach] of cases) {
    it(`refuses ${text.slice(text.indexOf(">") + 1, -6)}`, () => {
      for (const read of [importSvg, importSvgPaths]) {
        let message = "";
        try {
          read(text);
        } catch (e) {
          message = (e as Error).message;
        }
        expect(message).toContain(`${element} (line 1, column`);
        expect(message).toContain(`is too large: ${reach}`);
        expect(message).toContain("beyond ±1e30, the limit for the geometry to work in double precision");
      }
    });
  }

  it("imports and meshes a drawing just inside the limit", () => {
    const [shape] = importSvg(svg('<rect width="1e29" height="5e28"/>', "0 0 1e29 1e29"));
    const mesh = triangulate(shape!, { targetEdgeLength: 1e28 });
    // usvg keeps geometry in single precision.
    expect(mesh.area / 5e57).toBeCloseTo(1, 6);
  });
});

/** A w x h RGBA image, opaque where `inside(x, y)` holds for the pixel centre (y down). */
function image(w: number, h: number, inside: (x: number, y: number) => boolean): Uint8ClampedArray {
  const rgba = new Uint8ClampedArray(w * h * 4);
  for (let y = 0; y < h; y++) {
    for (let x = 0; x < w; x++) {
      if (inside(x + 0.5, y + 0.5)) rgba.set([30, 120, 200, 255], 4 * (y * w + x));
    }
  }
  return rgba;
}

describe("textureCoordinates", () => {
  it("follow OBJ's convention: u from the left, v up from the bottom row", () => {
    // A 4 x 2 image in its traced frame (y up, origin at the bottom-left corner): the
    // centre of its top-left pixel is (0.5, 1.5), of its bottom-right pixel (3.5, 0.5).
    const uvs = textureCoordinates([0.5, 1.5, 3.5, 0.5, 0, 0, 4, 2], 4, 2);
    expect(Array.from(uvs)).toEqual([0.5 / 4, 1 - 0.5 / 2, 3.5 / 4, 0.5 / 2, 0, 0, 1, 1]);
  });

  it("put each vertex of a traced image on its own pixel", () => {
    // Rows from the top, as ImageData: an opaque 40 x 20 block in a clear 2-pixel margin,
    // its quadrants red (top left), green (top right), blue (bottom left), white.
    const [w, h] = [44, 24];
    const colours = [
      [255, 0, 0],
      [0, 255, 0],
      [0, 0, 255],
      [255, 255, 255],
    ];
    const rgba = new Uint8ClampedArray(w * h * 4);
    for (let row = 2; row < h - 2; row++) {
      for (let column = 2; column < w - 2; column++) {
        const quadrant = (row < h / 2 ? 0 : 2) + (column < w / 2 ? 0 : 1);
        rgba.set([...colours[quadrant]!, 255], 4 * (row * w + column));
      }
    }
    const mesh = triangulate(traceImage(rgba, w, h, { tolerance: 0.25 })[0]!, { targetEdgeLength: 2 });
    const uvs = textureCoordinates(mesh.positions, w, h);
    let checked = 0;
    for (let i = 0; i < mesh.positions.length; i += 2) {
      const [x, y] = [mesh.positions[i]!, mesh.positions[i + 1]!];
      // Skip the seams between quadrants and the traced edge, where neighbours blend.
      if (Math.abs(x - w / 2) < 1 || Math.abs(y - h / 2) < 1 || x < 3 || x > w - 3 || y < 3 || y > h - 3) continue;
      // The quadrant from the position (y up), the colour from the pixel under (u, v):
      // column u * w, row (1 - v) * h from the top.
      const quadrant = (y > h / 2 ? 0 : 2) + (x < w / 2 ? 0 : 1);
      const [column, row] = [Math.floor(uvs[i]! * w), Math.floor((1 - uvs[i + 1]!) * h)];
      expect(Array.from(rgba.subarray(4 * (row * w + column), 4 * (row * w + column) + 3))).toEqual(colours[quadrant]);
      checked++;
    }
    expect(checked).toBeGreaterThan(20);
  });
});

describe("traceImage", () => {
  it("traces an annulus into one outline with a hole, within the pixel bound", () => {
    const r = (x: number, y: number) => Math.hypot(x - 50, y - 40);
    const rgba = image(100, 80, (x, y) => r(x, y) < 30 && r(x, y) >= 12);
    const outlines = traceImage(rgba, 100, 80, { tolerance: 0.5 });
    expect(outlines).toHaveLength(1);
    expect(outlines[0]!.holes).toHaveLength(1);
    const area = Math.abs(ringArea(outlines[0]!.outer)) - Math.abs(ringArea(outlines[0]!.holes[0]!));
    const expected = Math.PI * (30 * 30 - 12 * 12);
    expect(Math.abs(area - expected)).toBeLessThanOrEqual(2 * Math.PI * (30 + 12) * 1.5);
    const mesh = triangulate(outlines[0]!, { targetEdgeLength: 4 });
    const uvs = textureCoordinates(mesh.positions, 100, 80);
    expect(uvs.length).toBe(mesh.positions.length);
    expect(uvs.every((t) => t >= 0 && t <= 1)).toBe(true);
    expect(() => textureCoordinates([1, 2, NaN, 0], 100, 80)).toThrow(
      "position 1 has a value that is not a finite number",
    );
    expect(() => textureCoordinates([1e300, 0], 1e-10, 80)).toThrow(
      /texture coordinate of position 0 comes out beyond/,
    );
  });

  it("rejects bad sizes and options", () => {
    const rgba = new Uint8Array(4 * 6);
    expect(() => traceImage(rgba, 3, 3)).toThrow(
      "a 3 x 3 image needs 36 bytes of RGBA pixels (4 per pixel), but 24 were given",
    );
    expect(() => traceImage(rgba, 3, 2)).toThrow(/no pixel of the image belongs to the shape/);
    expect(() => traceImage(rgba, 3, 2, { mode: "grey" } as never)).toThrow(/option mode/);
    expect(() => traceImage(rgba, 3, 2, { alphaThreshold: 0 })).toThrow(/alphaThreshold/);
    expect(() => traceImage(rgba, 2.5, 2)).toThrow(RangeError);
  });
});

describe("mesh files", () => {
  const positions = [0, 0, 1, 0, 1, 1, 0, 1];
  const triangles = [0, 1, 2, 0, 2, 3];
  const uvs = [0, 1, 1, 1, 1, 0, 0, 0];

  it("round-trips OBJ and JSON exactly, with texture coordinates", () => {
    const obj = meshToObj({ positions, triangles, uvs });
    expect(obj).toContain("vt 1 0");
    const fromObj = meshFromObj(obj);
    expect(Array.from(fromObj.positions)).toEqual(positions);
    expect(Array.from(fromObj.triangles)).toEqual(triangles);
    expect(Array.from(fromObj.uvs!)).toEqual(uvs);
    const json = meshToJson({ positions: [0.1, 0.2, 1 / 3, 0, 0, 2 / 3], triangles: [0, 1, 2] });
    const fromJson = meshFromJson(json);
    expect(Array.from(fromJson.positions)).toEqual([0.1, 0.2, 1 / 3, 0, 0, 2 / 3]);
    expect(fromJson.uvs).toBeUndefined();
    expect(fromJson.boundaryVertices.length).toBe(3);
  });

  it("writes a pose as it is, a flipped triangle too, and refuses indices and numbers that cannot be", () => {
    // The square with vertex 3 carried across the diagonal: triangle 1 (0, 2, 3) flips.
    const pose = [0, 0, 1, 0, 1, 1, 0.9, 0.1];
    const obj = meshToObj({ positions: pose, triangles, uvs });
    expect(obj.split("\n").filter((l) => l.startsWith("v "))).toEqual(["v 0 0 0", "v 1 0 0", "v 1 1 0", "v 0.9 0.1 0"]);
    expect(Array.from(JSON.parse(meshToJson({ positions: pose, triangles })).positions)).toEqual(pose);
    expect(() => meshFromObj(obj)).toThrow("triangle 1 is clockwise; triangles must be counter-clockwise");
    for (const write of [meshToObj, meshToJson]) {
      expect(() => write({ positions: [0, 0, 1, 0, 1, NaN], triangles: [0, 1, 2] })).toThrow(/vertex 2/);
      expect(() => write({ positions: pose, triangles: [0, 1, 4] })).toThrow(/refers to vertex 4/);
      expect(() => write({ positions: pose, triangles: [0, 1, 1] })).toThrow(/same vertex/);
      expect(() => write({ positions: pose, triangles: [0, 1] })).toThrow(/not a multiple of 3/);
    }
  });

  it("writes only what it reads back: 100,000 vertices at most, the readers' limit", () => {
    // A strip of 2 x 50,001 vertices: 100,002, two over the limit.
    const strip = (columns: number) => {
      const p: number[] = [];
      const t: number[] = [];
      for (let i = 0; i < columns; i++) p.push(i, 0, i, 1);
      for (let i = 0; i + 1 < columns; i++) t.push(2 * i, 2 * i + 2, 2 * i + 3, 2 * i, 2 * i + 3, 2 * i + 1);
      return { positions: p, triangles: t };
    };
    for (const write of [meshToObj, meshToJson]) {
      expect(() => write(strip(50_001))).toThrow(
        "the mesh has 100002 vertices (200004 numbers), more than the limit of 100000 vertices",
      );
    }
    const largest = strip(50_000);
    expect(meshFromObj(meshToObj(largest)).vertexCount).toBe(100_000);
    expect(meshFromJson(meshToJson(largest)).vertexCount).toBe(100_000);
  });

  it("reads OBJ polygons and reports errors with their line", () => {
    const mesh = meshFromObj("# square\nv 0 0\nv 1 0\nv 1 1\nv 0 1\nf 1 2 3 4\n");
    expect(mesh.triangleCount).toBe(2);
    expect(() => meshFromObj("v 0 0\nv 1 x\n")).toThrow(/OBJ error at line 2, column 5/);
    expect(() => meshFromObj("v 0 0\nv 1 0\nv 0 1\nf 1 3 2\n")).toThrow(/counter-clockwise/);
    expect(() => meshFromJson('{"positions": [], "triangles": [], "extra": 1}')).toThrow(/unknown field `extra`/);
    // A writer writes what it is given (a pose may be clockwise); the reader holds it to a mesh's rules.
    expect(() => meshFromObj(meshToObj({ positions, triangles: [0, 2, 1] }))).toThrow(/clockwise/);
    expect(() => meshToJson({ positions, triangles, uvs: [0, 1] })).toThrow(
      "texture coordinates: 2 numbers for 4 vertices; 8 are needed, a u and a v per vertex",
    );
  });
});
