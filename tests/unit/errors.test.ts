/**
 * The errors akap throws, through the public API and the real wasm in Node: each code of
 * the table in docs/errors.md produced by a call that should produce it, with its message kept; and
 * every options object refusing a misspelt key, naming it and listing the known ones.
 */
import { beforeAll, describe, expect, it } from "vitest";
import * as raw from "../../www/pkg/akap.js";
import * as api from "../../www/src/index.js";
import { grid } from "./fixtures.js";

beforeAll(async () => {
  await api.init();
});

/** The error `call` throws (failing the test when it returns). */
function thrown(call: () => unknown): Error & { code?: unknown } {
  try {
    call();
  } catch (error) {
    expect(error).toBeInstanceOf(Error);
    return error as Error & { code?: unknown };
  }
  throw new Error("expected the call to throw");
}

const square = { outer: [0, 0, 1, 0, 1, 1, 0, 1] };
const svg = '<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10"><rect width="8" height="6"/></svg>';
/** A 16 x 16 image, transparent but for an opaque 8 x 8 square in the middle. */
const image = (() => {
  const rgba = new Uint8Array(4 * 16 * 16);
  for (let y = 4; y < 12; y++) for (let x = 4; x < 12; x++) rgba.set([0, 0, 0, 255], 4 * (16 * y + x));
  return rgba;
})();

describe("error codes", () => {
  it("are the ones the Rust side defines, in the same order", () => {
    expect(raw.errorCodes()).toEqual([...api.ERROR_CODES]);
  });

  // One call per code (the table in docs/errors.md): the code, and the message as the Rust
  // error words it. Three codes no call here can produce on purpose, each reaching
  // JavaScript from a real Rust error in tests/wasm_api.rs instead: `not-positive-definite`
  // (the deformers' systems stay factorable even for collapsed poses, their pivots
  // positive in rounding), `out-of-memory` (filling wasm memory takes a minute: the
  // HOSTILE_OOM run of hostile.test.ts checks it) and `internal` (a bug).
  const cases: [api.ErrorCode, () => unknown, RegExp][] = [
    [
      "invalid-argument",
      () => {
        const deformer = new api.Deformer(grid.positions, grid.triangles);
        try {
          deformer.setHandles([0, 99]);
        } finally {
          deformer.free();
        }
      },
      /^handle 1 is at vertex 99, but the mesh has only 9 vertices$/,
    ],
    ["invalid-option", () => api.triangulate(square, { minAngle: 50 }), /^option minAngle is 50, expected/],
    [
      "invalid-outline",
      // A bow-tie: the outline crosses itself.
      () => api.triangulate({ outer: [0, 0, 1, 1, 1, 0, 0, 1] }),
      /^the outline intersects itself/,
    ],
    [
      "invalid-mesh",
      () => api.meshFromArrays([0, 0, 1, 0, 0, 1], [0, 2, 1]),
      /^triangle 0 is clockwise; triangles must be counter-clockwise$/,
    ],
    [
      "invalid-joint",
      // Two triangles apart, each a part; a joint naming a third part.
      () =>
        new api.Deformer([0, 0, 1, 0, 0, 1, 5, 0, 6, 0, 5, 1], [0, 1, 2, 3, 4, 5], {
          parts: [
            { name: "a", triangles: new Uint32Array([0]), depth: 0 },
            { name: "b", triangles: new Uint32Array([1]), depth: 1 },
          ],
          joints: [{ point: [0.2, 0.2], parts: [0, 2] }],
        }),
      /^joint 0 cannot be used: it names part 2, but the puppet has 2 parts$/,
    ],
    [
      "limit",
      () => api.triangulate(square, { targetEdgeLength: 0.001, maxVertices: 100 }),
      /need more than 100 vertices/,
    ],
    ["import", () => api.meshFromObj("v 0 0\nwhat 1\n"), /^OBJ error at line 2, column 1: unknown statement `what`$/],
    [
      "overflow",
      () => api.textureCoordinates([1e300, 0], 1e-10, 1),
      /^the texture coordinate of position 0 comes out beyond the range of double precision/,
    ],
  ];
  for (const [code, call, message] of cases) {
    it(`${code}: ${message.source}`, () => {
      const error = thrown(call);
      expect(error.code).toBe(code);
      expect(error.message).toMatch(message);
      expect(api.isAkapError(error)).toBe(true);
      // An own, enumerable property, as assigned: seen by spreads and JSON.
      expect({ ...error }).toEqual({ code });
    });
  }

  it("the JavaScript layer's own argument checks carry a code too", () => {
    const error = thrown(() => api.meshFromArrays("0 0 1 0 0 1" as never, [0, 1, 2]));
    expect(error).toBeInstanceOf(TypeError);
    expect(error.code).toBe("invalid-argument");
    expect(error.message).toBe("positions must be a Float64Array or an array of numbers");
  });

  it("errors without a code are not akap's", () => {
    expect(api.isAkapError(new Error("x"))).toBe(false);
    expect(api.isAkapError(Object.assign(new Error("x"), { code: "ENOENT" }))).toBe(false);
    expect(api.isAkapError({ message: "x", code: "limit" })).toBe(false);
  });
});

describe("a misspelt option is refused by every options object", () => {
  // Each call succeeds with the key spelt right (checked first), and throws naming the
  // misspelt key and listing the known ones otherwise.
  const triangulation = "maxArea, targetEdgeLength, minAngle, maxVertices";
  const deformer = "method, lambda, dirichlet, integrator, iterations, variant, alpha, cage, smoothness";
  // A new deformer's options also take a puppet's parts and joints.
  const setup = `${deformer}, parts, joints`;
  const svgImport = "tolerance, minArea, strokes, maxPoints, maxBytes";
  const tracing = "mode, alphaThreshold, colourThreshold, tolerance, minArea, maxPoints, maxPixels";
  const { positions, triangles } = grid;
  const cases: [string, string, (options: object) => unknown, object, object][] = [
    ["triangulation", triangulation, (o) => api.triangulate(square, o), { minAngle: 20 }, { minAngel: 20 }],
    ["deformer", setup, (o) => new api.Deformer(positions, triangles, o).free(), { lambda: 5 }, { lamda: 5 }],
    [
      "deformer",
      deformer,
      (o) => {
        const d = new api.Deformer(positions, triangles);
        try {
          d.setOptions(o);
        } finally {
          d.free();
        }
      },
      { dirichlet: false },
      { dirichlett: false },
    ],
    [
      "deformer",
      setup,
      (o) => {
        // The orders, then the constructor that takes them (`withOrders`), each reading `o`.
        const orders = api.deformerOrders(positions, triangles, o);
        new api.Deformer(positions, triangles, o, orders).free();
      },
      { method: "arap" },
      { methd: "arap" },
    ],
    [
      "deformer",
      setup,
      (o) => raw.Deformer.withOrders(positions, triangles, o, api.deformerOrders(positions, triangles)).free(),
      { integrator: "linear" },
      { Integrator: "linear" },
    ],
    ["SVG import", svgImport, (o) => api.importSvg(svg, o), { tolerance: 0.1 }, { tolerence: 0.1 }],
    ["SVG import", svgImport, (o) => api.importSvgPaths(svg, o), { minArea: 1 }, { min_area: 1 }],
    ["image tracing", tracing, (o) => api.traceImage(image, 16, 16, o), { mode: "alpha" }, { mood: "alpha" }],
  ];
  for (const [what, names, call, right, wrong] of cases) {
    const [key] = Object.keys(wrong);
    it(`${what}: ${key}`, () => {
      expect(() => call(right)).not.toThrow();
      const error = thrown(() => call(wrong));
      expect(error.code).toBe("invalid-option");
      expect(error.message).toBe(`unknown ${what} option \`${key}\`; the options are ${names}`);
    });
  }

  it("pathData (read in TypeScript, as the bindings read theirs)", () => {
    const [path] = api.importSvgPaths(svg);
    // The 8 x 6 rectangle at the top of a 10 x 10 viewBox: y up, from 4 to 10; flipped, -10 to -4.
    expect(api.pathData(path!, path!.points, { flipY: true })).toBe("M 0 -10 L 8 -10 L 8 -4 L 0 -4 Z");
    const error = thrown(() => api.pathData(path!, path!.points, { flipy: true } as never));
    expect(error.code).toBe("invalid-option");
    expect(error.message).toBe("unknown pathData option `flipy`; the options are flipY");
    const wrong = thrown(() => api.pathData(path!, path!.points, { flipY: "yes" } as never));
    expect(wrong.code).toBe("invalid-option");
    expect(wrong.message).toBe("option flipY must be true or false, not string");
  });

  it("a value of the wrong type names the option", () => {
    const cases: [() => unknown, string | RegExp][] = [
      [() => api.triangulate(square, { maxArea: "1" as never }), "option maxArea must be a number, not a string"],
      [
        () => new api.Deformer(positions, triangles, { dirichlet: 1 as never }),
        "option dirichlet must be true or false, not the number 1",
      ],
      [
        () => new api.Deformer(positions, triangles, { method: "fem" as never }),
        'option method is "fem", expected "akap", "arap", "mls" or "cauchy-green"',
      ],
      [
        () => api.traceImage(image, 16, 16, { mode: 3 as never }),
        'option mode must be "auto", "alpha" or "colour", not the number 3',
      ],
      [
        () => api.importSvg(svg, { maxPoints: 2.5 }),
        /^option maxPoints is 2\.5, expected a whole number from 0 to \d+$/,
      ],
      [() => api.triangulate(square, [] as never), "triangulation options must be an object, not an array"],
    ];
    for (const [call, message] of cases) {
      const error = thrown(call);
      expect(error.code).toBe("invalid-option");
      if (typeof message === "string") expect(error.message).toBe(message);
      else expect(error.message).toMatch(message);
    }
  });
});
