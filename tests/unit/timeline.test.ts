/**
 * The timeline as data (`timeline.ts`): easing and interpolation against values worked
 * out by hand, the frame grid, capture/move/delete/easing with their rules, and bad input
 * refused with nothing changed.
 */
import { describe, expect, it } from "vitest";
import {
  Timeline,
  checkFps,
  ease,
  frameAt,
  frameCount,
  frameTime,
  targetsAt,
  type HandleSet,
} from "../../www/src/widget/animation/timeline.js";
import { abortError, recordWebm, sheetLayout } from "../../www/src/widget/animation/formats.js";

const TWO: HandleSet = { triangles: [3, 7], barycentric: [1, 0, 0, 0.25, 0.25, 0.5] };
const POSE = Float64Array.from([0, 0, 1, 0, 0, 1]);

/** Keys at 0 (targets 0,0 / 10,0), 1 s (linear to 10,0 / 10,20) and 3 s (eased to 0,0 / 30,20). */
function threeKeys(): Timeline {
  const t = new Timeline();
  t.capture(0, TWO, [0, 0, 10, 0], POSE);
  t.capture(1, TWO, [10, 0, 10, 20], POSE, "linear");
  t.capture(3, TWO, [0, 0, 30, 20], POSE, "ease");
  return t;
}

/** What a timeline shows of itself, to compare before and after a refused change. */
const state = (t: Timeline) =>
  JSON.stringify({ keys: t.keys.map((k) => [k.time, k.easing, [...k.targets]]), handles: t.handles, v: t.version });

describe("easing", () => {
  it("is linear, or smoothstep 3u² - 2u³, clamped to [0, 1]", () => {
    expect([0, 0.25, 0.5, 1].map((u) => ease("linear", u))).toEqual([0, 0.25, 0.5, 1]);
    // 3/16 - 2/64 = 0.15625; 3/4 - 1/4 = 0.5; 27/16 - 54/64 = 0.84375
    expect([0, 0.25, 0.5, 0.75, 1].map((u) => ease("ease", u))).toEqual([0, 0.15625, 0.5, 0.84375, 1]);
    expect([ease("ease", -1), ease("ease", 2), ease("linear", 1.5)]).toEqual([0, 1, 1]);
  });
});

describe("frames", () => {
  it("one frame per 1/fps from 0 to the end, both ends included", () => {
    expect(frameCount(0, 24)).toBe(1);
    expect(frameCount(1, 24)).toBe(25);
    expect(frameCount(3, 24)).toBe(73);
    // 0.1 s at 30 fps is 3 frames' time (0.1 * 30 = 3.0000000000000004): 4 frames.
    expect(frameCount(0.1, 30)).toBe(4);
    expect(frameCount(1.05, 10)).toBe(11);
    expect(frameTime(12, 24)).toBe(0.5);
    expect([frameAt(0.5, 24), frameAt(0.51, 24), frameAt(0.1, 30)]).toEqual([12, 12, 3]);
  });

  it("refuses an fps that is not a whole number from 1 to 120", () => {
    for (const bad of [0, 0.5, 121, NaN, -24]) expect(() => checkFps(bad)).toThrow(/fps/);
    expect(() => checkFps(60)).not.toThrow();
  });
});

describe("targetsAt", () => {
  const t = threeKeys();
  it("holds the first key's targets before it and the last's after it", () => {
    const late = new Timeline();
    late.capture(2, TWO, [5, 6, 7, 8], POSE);
    late.capture(4, TWO, [9, 9, 9, 9], POSE);
    expect([...targetsAt(late.keys, 0)]).toEqual([5, 6, 7, 8]);
    expect([...targetsAt(late.keys, 2)]).toEqual([5, 6, 7, 8]);
    expect([...targetsAt(t.keys, 3)]).toEqual([0, 0, 30, 20]);
    expect([...targetsAt(t.keys, 100)]).toEqual([0, 0, 30, 20]);
  });

  it("hits each key's targets at its time", () => {
    for (const k of t.keys) expect([...targetsAt(t.keys, k.time)]).toEqual([...k.targets]);
  });

  it("interpolates linearly and eased by the easing of the segment's end key", () => {
    // 0.25 s into the linear segment 0 -> 1 s: a quarter of the way.
    expect([...targetsAt(t.keys, 0.25)]).toEqual([2.5, 0, 10, 5]);
    // 1.5 s: a quarter of the eased segment 1 -> 3 s, smoothstep(0.25) = 0.15625.
    expect([...targetsAt(t.keys, 1.5)]).toEqual([10 - 10 * 0.15625, 0, 10 + 20 * 0.15625, 20]);
    // 2 s: half way, smoothstep(0.5) = 0.5.
    expect([...targetsAt(t.keys, 2)]).toEqual([5, 0, 20, 20]);
  });
});

describe("Timeline", () => {
  it("keeps keys in time order; capturing at a key's time replaces it, keeping its easing", () => {
    const t = new Timeline();
    expect(t.capture(2, TWO, [1, 1, 1, 1], POSE)).toBe(0);
    expect(t.capture(1, TWO, [2, 2, 2, 2], POSE)).toBe(0);
    expect(t.keys.map((k) => k.time)).toEqual([1, 2]);
    t.setEasing(1, "ease");
    expect(t.capture(2 + 1e-9, TWO, [3, 3, 3, 3], POSE)).toBe(1);
    expect(t.keys).toHaveLength(2);
    expect(t.keys[1]!.time).toBe(2);
    expect(t.keys[1]!.easing).toBe("ease");
    expect([...t.keys[1]!.targets]).toEqual([3, 3, 3, 3]);
    expect(t.duration).toBe(2);
  });

  it("copies what it is given", () => {
    const t = new Timeline();
    const targets = Float64Array.from([1, 2, 3, 4]);
    const pose = POSE.slice();
    t.capture(0, TWO, targets, pose);
    targets[0] = 99;
    pose[0] = 99;
    expect(t.keys[0]!.targets[0]).toBe(1);
    expect(t.keys[0]!.pose[0]).toBe(0);
  });

  it("moves and deletes keys; the last key gone, any handle set may start again", () => {
    const t = threeKeys();
    expect(t.move(0, 5)).toBe(2);
    expect(t.keys.map((k) => k.time)).toEqual([1, 3, 5]);
    expect([...t.keys[2]!.targets]).toEqual([0, 0, 10, 0]);
    t.delete(1);
    expect(t.keys.map((k) => k.time)).toEqual([1, 5]);
    t.delete(0);
    t.delete(0);
    expect(t.handles).toBeUndefined();
    const other: HandleSet = { triangles: [1], barycentric: [1, 0, 0] };
    expect(t.capture(0, other, [0, 0], POSE)).toBe(0);
  });

  it("changes the version on every change, and only then", () => {
    const t = threeKeys();
    const v = t.version;
    t.setEasing(1, "linear"); // already linear
    expect(t.version).toBe(v);
    t.setEasing(1, "ease");
    expect(t.version).toBeGreaterThan(v);
    const w = t.version;
    t.move(2, 4);
    expect(t.version).toBeGreaterThan(w);
  });

  it("refuses bad input with nothing changed", () => {
    const t = threeKeys();
    const before = state(t);
    const refused: [() => unknown, RegExp][] = [
      [() => t.capture(NaN, TWO, [0, 0, 0, 0], POSE), /time NaN/],
      [() => t.capture(-1, TWO, [0, 0, 0, 0], POSE), /time -1/],
      [() => t.capture(Infinity, TWO, [0, 0, 0, 0], POSE), /time/],
      [() => t.capture(1, TWO, [0, 0, 0, 0], POSE, "bounce" as "ease"), /unknown easing "bounce"/],
      [() => t.capture(1, TWO, [0, 0, 0], POSE), /one finite xy target per handle/],
      [() => t.capture(1, TWO, [0, 0, NaN, 0], POSE), /one finite xy target per handle/],
      [() => t.capture(1, TWO, [0, 0, 0, 0], [0, 0, 1]), /pose/],
      [() => t.capture(1, TWO, [0, 0, 0, 0], [0, 0, 1, 1]), /vertex count/],
      [() => t.capture(1, { triangles: [], barycentric: [] }, [], POSE), /add handles/],
      [() => t.capture(1, { triangles: [3, 8], barycentric: TWO.barycentric }, [0, 0, 0, 0], POSE), /another set/],
      [() => t.move(3, 1), /no key 3/],
      [() => t.move(-1, 1), /no key -1/],
      [() => t.move(0.5, 1), /no key 0.5/],
      [() => t.move(0, NaN), /time NaN/],
      [() => t.move(0, 3), /key at 3 s already/],
      [() => t.delete(3), /no key 3/],
      [() => t.setEasing(0, "cubic" as "ease"), /unknown easing/],
      [() => t.setEasing(7, "ease"), /no key 7/],
    ];
    for (const [change, message] of refused) {
      expect(change).toThrow(message);
      expect(state(t)).toBe(before);
    }
  });
});

describe("export layout and refusals (animation-export.ts)", () => {
  it("lays a sprite sheet out near square, within the canvas limits, or refuses", () => {
    // 25 frames of 100 x 100: 5 x 5.
    expect(sheetLayout(25, 100, 100)).toEqual({ columns: 5, rows: 5 });
    // Wide frames go in fewer columns: 25 of 400 x 100 -> ceil(sqrt(25 / 4)) = 3 columns, 9 rows.
    expect(sheetLayout(25, 400, 100)).toEqual({ columns: 3, rows: 9 });
    expect(sheetLayout(1, 640, 480)).toEqual({ columns: 1, rows: 1 });
    // Very wide frames: one column (ceil(sqrt(9 * 10 / 5000)) = 1), a sheet of 5000 x 90.
    expect(sheetLayout(9, 5000, 10)).toEqual({ columns: 1, rows: 9 });
    // Tall frames: ceil(sqrt(4 * 900 / 300)) = 4 columns, one row (1200 x 900).
    expect(sheetLayout(4, 300, 900)).toEqual({ columns: 4, rows: 1 });
    // 2^26 pixels at most: 4 frames of 3000 x 9000 (108 million) are refused.
    expect(() => sheetLayout(4, 3000, 9000)).toThrow(/too large/);
    expect(() => sheetLayout(400, 1000, 1000)).toThrow(/too large for a canvas/);
    expect(() => sheetLayout(2, 20000, 10)).toThrow(/too large/);
  });

  it("refuses WebM where MediaRecorder is missing (Node), before drawing anything", async () => {
    let drawn = 0;
    const painter = {
      count: 3,
      fps: 24,
      draw: () => {
        drawn++;
        throw new Error("drawn");
      },
    };
    await expect(recordWebm(painter)).rejects.toThrow(/MediaRecorder, which this environment lacks/);
    expect(drawn).toBe(0);
    expect(abortError().name).toBe("AbortError");
  });
});
