/**
 * `Deformer.stepWithoutFoldovers` through the real wasm package in Node: the plain step
 * when nothing flips, no fold where plain steps fold the bar, the reported steps replayed
 * with `step` from JavaScript's own products, the clamp on one triangle, bad input.
 */
import { beforeAll, describe, expect, it } from "vitest";
import { Deformer, init, isAkapError, type Method } from "../../www/src/index.js";

beforeAll(async () => {
  await init();
});

const [COLUMNS, ROWS] = [20, 4];

/** The bar [0, 20] x [0, 4] of unit squares, two counter-clockwise triangles each. */
const bar = (() => {
  const index = (x: number, y: number) => y * (COLUMNS + 1) + x;
  const positions: number[] = [];
  for (let y = 0; y <= ROWS; y++) for (let x = 0; x <= COLUMNS; x++) positions.push(x, y);
  const triangles: number[] = [];
  for (let y = 0; y < ROWS; y++) {
    for (let x = 0; x < COLUMNS; x++) {
      const [a, b, c, d] = [index(x, y), index(x + 1, y), index(x + 1, y + 1), index(x, y + 1)];
      triangles.push(a, b, c, a, c, d);
    }
  }
  // The left end held, and the middle of the right end, last.
  const handles = [...Array.from({ length: ROWS + 1 }, (_, y) => index(0, y)), index(COLUMNS, ROWS / 2)];
  return { positions: Float64Array.from(positions), triangles: Uint32Array.from(triangles), handles };
})();

function barDeformer(method: Method): Deformer {
  const deformer = new Deformer(bar.positions, bar.triangles, { method });
  deformer.setHandles(bar.handles);
  return deformer;
}

/** Velocities holding every handle but the last, which moves by (dx, dy). */
function drag(dx: number, dy: number): Float64Array {
  const velocities = new Float64Array(2 * bar.handles.length);
  velocities.set([dx, dy], velocities.length - 2);
  return velocities;
}

/** The bytes of a Float64Array: equal only when every number has the same bits. */
const bytes = (values: Float64Array) => new Uint8Array(values.buffer, values.byteOffset, values.byteLength);

/** The extreme drag's frame: the right end's middle pulled to (2, 2), the rest of the way in the frames left. */
const FRAMES = 8;
function dragFrame(deformer: Deformer, frame: number): Float64Array {
  const at = deformer.handlePositions();
  const share = 1 / (FRAMES - frame);
  return drag(share * (2 - at[at.length - 2]!), share * (2 - at[at.length - 1]!));
}

describe("Deformer.stepWithoutFoldovers", () => {
  it("is the plain step, bit for bit, when the step flips nothing", () => {
    for (const method of ["akap", "arap", "mls", "cauchy-green"] as const) {
      const [plain, guarded] = [barDeformer(method), barDeformer(method)];
      for (let frame = 0; frame < 3; frame++) {
        const velocities = drag(0.1 * frame, 0.4);
        plain.step(velocities);
        expect(guarded.stepWithoutFoldovers(velocities)).toEqual({ steps: [1], clamped: false, attempts: 1 });
        expect(bytes(guarded.positions())).toEqual(bytes(plain.positions()));
        expect(bytes(guarded.field())).toEqual(bytes(plain.field()));
      }
      plain.free();
      guarded.free();
    }
  });

  it("folds nothing where plain steps fold the bar, and its steps replay to the same bits", () => {
    for (const method of ["akap", "arap"] as const) {
      const plain = barDeformer(method);
      let folded = 0;
      for (let frame = 0; frame < FRAMES; frame++) {
        plain.step(dragFrame(plain, frame));
        folded = Math.max(folded, plain.metrics().flipped);
      }
      expect(folded).toBeGreaterThan(0);

      const guarded = barDeformer(method);
      const taken: Float64Array[] = [];
      let split = false;
      for (let frame = 0; frame < FRAMES; frame++) {
        const velocities = dragFrame(guarded, frame);
        const report = guarded.stepWithoutFoldovers(velocities);
        split ||= report.steps.length !== 1 || report.steps[0] !== 1;
        expect(report.attempts).toBeGreaterThanOrEqual(report.steps.length);
        // The velocities times each fraction, computed here in JavaScript.
        for (const fraction of report.steps) taken.push(velocities.map((v) => v * fraction));
        expect(guarded.metrics().flipped).toBe(0);
      }
      expect(split).toBe(true);
      const replayed = barDeformer(method);
      for (const velocities of taken) replayed.step(velocities);
      expect(bytes(replayed.positions())).toEqual(bytes(guarded.positions()));
      for (const d of [plain, guarded, replayed]) d.free();
    }
  });

  it("clamps one triangle pushed through its base where it would turn over", () => {
    // Apex (0, 1) pushed down by 3 with MLS, every vertex a handle: at height 1 - 3 f after
    // a fraction f, collapsing at f = 1/3. Taken: 1/4, 1/16 and twelve bisected bits of
    // 1/3 of the next sixteenth (1365 / 4096), the apex left at 2^-16.
    const deformer = new Deformer([0, 0, 1, 0, 0, 1], [0, 1, 2], { method: "mls" });
    deformer.setHandles([0, 1, 2]);
    const report = deformer.stepWithoutFoldovers([0, 0, 0, 0, 0, -3]);
    expect(report).toEqual({ steps: [0.25, 0.0625, (0.0625 * 1365) / 4096], clamped: true, attempts: 19 });
    expect(Array.from(deformer.positions())).toEqual([0, 0, 1, 0, 0, 2 ** -16]);
    // Without halvings, the whole push is clamped.
    deformer.reset();
    const whole = deformer.stepWithoutFoldovers([0, 0, 0, 0, 0, -3], { maxSplits: 0, clampTrials: 4 });
    // Four bits of 1/3 = 0.0101...: 5 / 16.
    expect(whole).toEqual({ steps: [5 / 16], clamped: true, attempts: 5 });
    deformer.free();
  });

  it("throws coded errors for bad input and changes nothing", () => {
    const deformer = barDeformer("akap");
    deformer.step(drag(-2, 1));
    const before = deformer.positions();
    const cases: [() => unknown, string, string | RegExp][] = [
      [() => deformer.stepWithoutFoldovers([0, 0]), "invalid-argument", /^velocities has 2 numbers, expected 12/],
      [
        () => deformer.stepWithoutFoldovers(drag(1, 0), { maxSplits: 11 }),
        "invalid-option",
        "option maxSplits is 11, expected a whole number from 0 to 10",
      ],
      [
        () => deformer.stepWithoutFoldovers(drag(1, 0), { maxSplit: 2 } as never),
        "invalid-option",
        "unknown foldover option `maxSplit`; the options are maxSplits, clampTrials",
      ],
    ];
    for (const [call, code, message] of cases) {
      let error: unknown;
      try {
        call();
      } catch (e) {
        error = e;
      }
      expect(isAkapError(error)).toBe(true);
      expect((error as { code: string }).code).toBe(code);
      expect((error as Error).message).toMatch(message);
      expect(bytes(deformer.positions())).toEqual(bytes(before));
    }
    deformer.free();
  });
});
