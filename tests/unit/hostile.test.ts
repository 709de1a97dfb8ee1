/**
 * Hostile and careless callers, through the real wasm in Node: random JavaScript values
 * (wrong types, huge, tiny and non-finite numbers, Proxies whose traps throw, getters that
 * throw, sparse arrays, typed arrays of every kind) thrown at every binding and every
 * method of the public API. Each call must return or throw an `Error`, never trap the
 * instance, and afterwards the instance must compute exactly what it computed before.
 *
 * The budget is small in `npm test` (fixed seed); `HOSTILE_RUNS=5000 npx vitest run
 * tests/unit/hostile.test.ts` runs longer, and `HOSTILE_SEED` picks another seed.
 */
import fc from "fast-check";
import { beforeAll, describe, expect, it } from "vitest";
import * as raw from "../../www/pkg/akap.js";
import * as api from "../../www/src/index.js";
import { grid } from "./fixtures.js";

const RUNS = Number(process.env.HOSTILE_RUNS ?? 60);
const SEED = Number(process.env.HOSTILE_SEED ?? 20261201);

beforeAll(async () => {
  await api.init();
});

/** Values that run code when touched: getters and Proxy traps that throw. */
const trapping = fc.constantFrom(
  () => ({
    get lambda(): number {
      throw new Error("getter");
    },
  }),
  () =>
    new Proxy(
      {},
      {
        ownKeys: () => {
          throw new Error("ownKeys");
        },
      },
    ),
  () =>
    new Proxy([1, 2, 3], {
      get: () => {
        throw new Error("get");
      },
    }),
  () =>
    new Proxy(new Float64Array(6), {
      get: () => {
        throw new Error("typed get");
      },
    }),
  () => ({
    valueOf: () => {
      throw new Error("valueOf");
    },
    toString: () => {
      throw new Error("toString");
    },
  }),
  () => [
    1,
    {
      valueOf: () => {
        throw new Error("element");
      },
    },
    3,
  ],
  () => Object.create(null),
  () => {
    const sparse: unknown[] = new Array(3);
    sparse[2] = 1;
    return sparse;
  },
);

const numbers = fc.oneof(
  fc.double(),
  fc.constantFrom(NaN, Infinity, -Infinity, -0, 1e308, 1e-308, 2 ** 32 + 1, -1, 0.5, 1e9),
  fc.integer({ min: -5, max: 50 }),
);

const typedArrays = fc.oneof(
  fc.array(fc.double(), { maxLength: 24 }).map((a) => Float64Array.from(a)),
  fc.array(fc.integer({ min: 0, max: 2 ** 32 - 1 }), { maxLength: 24 }).map((a) => Uint32Array.from(a)),
  fc.array(fc.integer({ min: 0, max: 255 }), { maxLength: 64 }).map((a) => Uint8Array.from(a)),
  fc.array(fc.integer({ min: -100, max: 100 }), { maxLength: 12 }).map((a) => Int32Array.from(a)),
);

/** Anything a careless or hostile caller might pass. */
const hostile: fc.Arbitrary<unknown> = fc.oneof(
  fc.anything({ maxDepth: 2 }),
  numbers,
  typedArrays,
  fc.array(numbers, { maxLength: 12 }),
  trapping.map((make) => make()),
  fc.constantFrom(undefined, null, "", "gingerbread", true, 10n, Symbol("s"), () => 1),
);

/** What a healthy instance computes; compared after each property. */
function canary(): number[] {
  const mesh = api.triangulate(api.defaultShape(), { targetEdgeLength: 0.2 });
  const deformer = new api.Deformer(mesh.positions, mesh.triangles);
  try {
    deformer.setHandles([0, 20]);
    deformer.step([0, 0, 0.05, -0.02]);
    return Array.from(deformer.positions());
  } finally {
    deformer.free();
  }
}

/**
 * Calls `f`; it may return or throw an `Error`, but not trap the instance. With `coded`,
 * the `Error` must carry one of the codes (the bindings' errors all do; the public API's
 * may also pass on what a caller's own getter or `valueOf` threw).
 */
function survives(f: () => unknown, coded: boolean): void {
  try {
    f();
  } catch (error) {
    expect(error).toBeInstanceOf(Error);
    expect(error).not.toBeInstanceOf(WebAssembly.RuntimeError);
    if (coded) expect(api.ERROR_CODES).toContain((error as { code?: unknown }).code);
  }
}

/** Checks a property over hostile argument lists for `call`, then the canary. */
function property(arity: number, call: (args: unknown[]) => unknown, coded = true): void {
  const before = canary();
  fc.assert(
    fc.property(fc.array(hostile, { minLength: 0, maxLength: arity + 1 }), (args) => {
      survives(() => call(args), coded);
    }),
    { numRuns: RUNS, seed: SEED },
  );
  expect(canary()).toEqual(before);
}

describe("the bindings survive anything as arguments", () => {
  const a = (args: unknown[], i: number) => args[i] as never;
  it("meshes, triangulation and shapes", () => {
    property(3, (x) => new raw.Mesh(a(x, 0), a(x, 1)).free());
    property(3, (x) => raw.triangulate_outline(a(x, 0), a(x, 1), a(x, 2)).free());
    property(1, (x) => raw.builtinShape(a(x, 0)));
    property(3, (x) => raw.deformer_orders(a(x, 0), a(x, 1), a(x, 2)));
  });

  it("imports, exports and point mapping", () => {
    property(2, (x) => raw.import_svg(a(x, 0), a(x, 1)));
    property(2, (x) => raw.import_svg_paths(a(x, 0), a(x, 1)));
    property(4, (x) => raw.trace_image(a(x, 0), a(x, 1), a(x, 2), a(x, 3)));
    property(1, (x) => raw.mesh_from_obj(a(x, 0)).free());
    property(1, (x) => raw.mesh_from_json(a(x, 0)).free());
    property(4, (x) => raw.mesh_to_obj(a(x, 0), a(x, 1), a(x, 2), a(x, 3)));
    property(6, (x) => raw.mesh_to_json(a(x, 0), a(x, 1), a(x, 2), a(x, 3), a(x, 4), a(x, 5)));
    property(3, (x) => raw.texture_coordinates(a(x, 0), a(x, 1), a(x, 2)));
    property(3, (x) => new raw.PointMapper(a(x, 0), a(x, 1), a(x, 2)).free());
    const mapper = new raw.PointMapper(grid.positions, grid.triangles, Float64Array.of(0.5, 0.5, 9, 9));
    property(1, (x) => mapper.map(a(x, 0)));
    expect(Array.from(mapper.map(grid.positions))).toEqual([0.5, 0.5, 9, 9]);
    mapper.free();
  });

  it("every deformer method, and the deformer stays usable", () => {
    for (const method of ["akap", "arap"] as const) {
      const deformer = new raw.Deformer(grid.positions, grid.triangles, { method });
      property(3, (x) => new raw.Deformer(a(x, 0), a(x, 1), a(x, 2)).free());
      property(1, (x) => deformer.setOptions(a(x, 0)));
      property(1, (x) => deformer.setHandles(a(x, 0)));
      property(2, (x) => deformer.setHandlePoints(a(x, 0), a(x, 1)));
      property(1, (x) => deformer.step(a(x, 0)));
      property(1, (x) => deformer.setPositions(a(x, 0)));
      property(1, (x) => deformer.setStiffness(a(x, 0)));
      property(2, (x) => raw.checkStiffness(a(x, 0), a(x, 1)));
      // Still a working deformer: a translation of both handles moves the grid rigidly.
      deformer.reset();
      deformer.setOptions(method === "akap" ? { lambda: 100 } : { iterations: 10 });
      deformer.setHandles(Uint32Array.of(0, 8));
      deformer.step(Float64Array.of(0.5, 0.25, 0.5, 0.25));
      const p = deformer.positions();
      for (let i = 0; i < p.length; i += 2) {
        expect(p[i]! - grid.positions[i]!).toBeCloseTo(0.5, 9);
        expect(p[i + 1]! - grid.positions[i + 1]!).toBeCloseTo(0.25, 9);
      }
      deformer.free();
    }
  });

  it("the public API, freed objects included", () => {
    property(2, (x) => api.triangulate(a(x, 0), a(x, 1)), false);
    property(2, (x) => api.meshFromArrays(a(x, 0), a(x, 1)), false);
    property(2, (x) => api.importSvg(a(x, 0), a(x, 1)), false);
    property(4, (x) => api.traceImage(a(x, 0), a(x, 1), a(x, 2), a(x, 3)), false);
    property(1, (x) => api.meshFromObj(a(x, 0)), false);
    property(1, (x) => api.meshToObj(a(x, 0)), false);
    const deformer = new api.Deformer(grid.positions, grid.triangles);
    property(1, (x) => deformer.setHandles(a(x, 0)), false);
    property(1, (x) => deformer.step(a(x, 0)), false);
    deformer.free();
    expect(() => deformer.step([])).toThrow(/freed/);
    expect(() => deformer.free()).toThrow(/freed/);
    const mapper = new api.PointMapper(grid.positions, grid.triangles, [1, 1]);
    mapper.free();
    expect(() => mapper.map(grid.positions)).toThrow(/freed/);
  });
});

describe("exceptions inside calls", () => {
  it("100,000 calls that throw from a getter or a trap leave the instance and the object whole", () => {
    const before = canary();
    const deformer = new api.Deformer(grid.positions, grid.triangles);
    deformer.setHandles([0, 8]);
    const getter = {
      get lambda(): number {
        throw new Error("getter");
      },
    };
    const keys = new Proxy(
      {},
      {
        ownKeys: () => {
          throw new Error("ownKeys");
        },
      },
    );
    for (let i = 0; i < 50_000; i++) {
      expect(() => deformer.setOptions(getter as never)).toThrow(/getter/);
      expect(() => api.triangulate(api.defaultShape(), keys as never)).toThrow(/ownKeys/);
    }
    deformer.step([0, 0, 0.1, 0]);
    const fresh = new api.Deformer(grid.positions, grid.triangles);
    fresh.setHandles([0, 8]);
    fresh.step([0, 0, 0.1, 0]);
    expect(deformer.positions()).toEqual(fresh.positions());
    deformer.free();
    fresh.free();
    expect(canary()).toEqual(before);
  }, 120_000);
});

describe("an instance that traps", () => {
  it("is marked failed: that call and every later one throw an Error that says so", async () => {
    const { guardBindings } = await import("../../www/src/internal/wasm.js");
    let trapNext = false;
    class Thing {
      free(): void {}
      poke(): number {
        if (trapNext) throw new WebAssembly.RuntimeError("unreachable");
        return 7;
      }
    }
    const fake = {
      Thing,
      make: () => new Thing(),
      twice: (x: number) => 2 * x,
      refuse: (): never => {
        throw new TypeError("bad input");
      },
    };
    const { bindings, failure } = guardBindings(fake);
    const thing = bindings.make();
    expect(thing.poke()).toBe(7);
    expect(bindings.twice(4)).toBe(8);
    // Errors thrown on purpose (bad input) pass through and leave the instance usable.
    expect(() => bindings.refuse()).toThrow(TypeError);
    expect(failure()).toBeUndefined();
    trapNext = true;
    expect(() => thing.poke()).toThrow(/instance stopped \(unreachable\) and cannot be used again/);
    expect(failure()).toBeInstanceOf(Error);
    trapNext = false;
    expect(() => bindings.twice(1)).toThrow(/cannot be used again/);
    expect(() => new bindings.Thing()).toThrow(/cannot be used again/);
    expect(() => thing.poke()).toThrow(/cannot be used again/);
  });
});

describe.runIf(process.env.HOSTILE_OOM)("memory exhausted (HOSTILE_OOM=1, about a minute)", () => {
  it("by deformers never freed: an Error saying so, and after freeing them the instance works", () => {
    const before = canary();
    const mesh = api.triangulate(api.defaultShape(), { targetEdgeLength: 0.008 });
    const kept: api.Deformer[] = [];
    let error: unknown;
    try {
      for (let i = 0; i < 1000; i++) kept.push(new api.Deformer(mesh.positions, mesh.triangles));
    } catch (e) {
      error = e;
    }
    expect(error).toBeInstanceOf(Error);
    expect(error).not.toBeInstanceOf(WebAssembly.RuntimeError);
    expect(String((error as Error).message)).toMatch(/out of memory/);
    expect((error as { code?: unknown }).code).toBe("out-of-memory");
    for (const d of kept) d.free();
    expect(canary()).toEqual(before);
  }, 600_000);

  it("by meshes, whose allocation cannot fail gracefully: the instance traps, the bindings move to a fresh one", async () => {
    const { raw: guarded } = await import("../../www/src/internal/wasm.js");
    const before = canary();
    const side = 310;
    const p: number[] = [];
    const t: number[] = [];
    for (let y = 0; y < side; y++) for (let x = 0; x < side; x++) p.push(x, y);
    for (let y = 0; y + 1 < side; y++) {
      for (let x = 0; x + 1 < side; x++) {
        const v = side * y + x;
        t.push(v, v + 1, v + side + 1, v, v + side + 1, v + side);
      }
    }
    const [positions, triangles] = [Float64Array.from(p), Uint32Array.from(t)];
    const kept: { vertexCount: number }[] = [];
    let error: unknown;
    try {
      for (let i = 0; i < 5000; i++) kept.push(new guarded.Mesh(positions, triangles));
    } catch (e) {
      error = e;
    }
    expect(error).toBeInstanceOf(Error);
    expect(error).not.toBeInstanceOf(WebAssembly.RuntimeError);
    expect(String((error as Error).message)).toMatch(/stopped \(unreachable\).*a new instance has started/);
    // Objects of the old instance say so; new ones work, and compute as before.
    expect(() => kept[0]!.vertexCount).toThrow(/cannot be used again/);
    expect(canary()).toEqual(before);
  }, 600_000);
});
