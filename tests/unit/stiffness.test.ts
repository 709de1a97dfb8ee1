/**
 * Painted stiffness in the widget's posing core, through the real wasm: the brush paints
 * the triangles whose centroids lie in its disc; a stroke is one undoable change; the
 * painting changes the pose as the core's `setStiffness` does, survives a trip through a
 * method without stiffness, is carried to a re-meshing, and a recording of it replays to
 * the same bits; bad values change nothing. The pure helpers (tint, carry) too.
 */
import { beforeAll, describe, expect, it } from "vitest";
import { Deformer, builtinShape, init, meshFromJson, meshToJson } from "../../www/src/index.js";
import { meshOutline } from "../../www/src/widget/model/shape.js";
import { carryStiffness, paintStiffness, stiffnessTint, unpainted } from "../../www/src/widget/model/stiffness.js";
import { brushSettings } from "../../www/src/widget/options.js";
import { keyCommand } from "../../www/src/widget/actions/keys.js";
import { grid } from "./fixtures.js";
import { dragTo, posed } from "./posing-fixtures.js";

beforeAll(async () => {
  await init();
});

/** Centroid of triangle `t`. */
function centroid(positions: ArrayLike<number>, triangles: ArrayLike<number>, t: number): [number, number] {
  let x = 0;
  let y = 0;
  for (let k = 0; k < 3; k++) {
    x += positions[2 * triangles[3 * t + k]!]! / 3;
    y += positions[2 * triangles[3 * t + k]! + 1]! / 3;
  }
  return [x, y];
}

/** Paints the right arm 100x stiffer with one dab of the brush: a disc of 0.2 of the size, near the arm's end. */
function paintArm(posing: ReturnType<typeof posed>["posing"]): Float64Array {
  const { positions } = posing.shape.mesh;
  let right = -Infinity;
  for (let v = 0; v < positions.length / 2; v++) right = Math.max(right, positions[2 * v]!);
  const at: [number, number] = [right - 0.15 * posing.shape.size, 0];
  // y at the rightmost vertex's height.
  for (let v = 0; v < positions.length / 2; v++) if (positions[2 * v] === right) at[1] = positions[2 * v + 1]!;
  posing.beginGesture();
  posing.markChanged();
  expect(posing.paint(at[0], at[1], 0.2 * posing.shape.size, 100)).toBe(true);
  expect(posing.paint(at[0], at[1], 0.2 * posing.shape.size, 100)).toBe(false); // nothing new
  posing.flushStiffness();
  posing.endDragGesture();
  return posing.stiffness!.slice();
}

describe("the stiffness brush", () => {
  it("paints exactly the triangles whose centroids are within the radius", () => {
    const { stiffness, changed } = paintStiffness(undefined, grid.positions, grid.triangles, 0.5, 0.5, 0.5, 10);
    expect(changed).toBe(true);
    for (let t = 0; t < 8; t++) {
      const [x, y] = centroid(grid.positions, grid.triangles, t);
      expect(stiffness[t]).toBe(Math.hypot(x - 0.5, y - 0.5) <= 0.5 ? 10 : 1);
    }
    expect(Array.from(stiffness).filter((s) => s === 10).length).toBe(2);
    // Painting again changes nothing; erasing (1) brings back none.
    expect(paintStiffness(stiffness, grid.positions, grid.triangles, 0.5, 0.5, 0.5, 10).changed).toBe(false);
    const erased = paintStiffness(stiffness, grid.positions, grid.triangles, 1, 1, 5, 1);
    expect(erased.changed && unpainted(erased.stiffness)).toBe(true);
  });

  it("tints stiff blue and soft orange, more strongly further from 1, and 1 not at all", () => {
    expect(stiffnessTint(1)).toBeUndefined();
    const alpha = (s: number) => Number(/, ([\d.]+)\)$/.exec(stiffnessTint(s)!)![1]);
    expect(stiffnessTint(10)).toMatch(/^rgba\(40, 90, 220/);
    expect(stiffnessTint(0.1)).toMatch(/^rgba\(245, 150, 20/);
    expect(alpha(1000)).toBeGreaterThan(alpha(10));
    expect(alpha(0.001)).toBe(alpha(1000));
  });

  it("checks brush settings and keys: B toggles, [ and ] resize", () => {
    expect(brushSettings({ size: 24, value: 100 }, { value: 0.1 })).toEqual({ size: 24, value: 0.1 });
    expect(() => brushSettings({ size: 24, value: 100 }, { value: 1001 })).toThrow("outside the stiffness range");
    expect(() => brushSettings({ size: 24, value: 100 }, { size: 0 })).toThrow("brush size 0");
    expect(() => brushSettings({ size: 24, value: 100 }, { colour: 1 } as never)).toThrow("unknown brush option");
    const press = { ctrlKey: false, metaKey: false, altKey: false, shiftKey: false };
    expect(keyCommand({ ...press, key: "b" })).toEqual({ kind: "brush" });
    expect(keyCommand({ ...press, key: "]" })).toMatchObject({ kind: "brush-size" });
  });
});

describe("painted stiffness while posing", () => {
  it("a stroke is one undoable change, and the painted pose is the core's with that stiffness", () => {
    const { posing } = posed(700);
    const rest = posing.deformer.positions();
    const handles = posing.handlesEvent().handles;
    const stiff = paintArm(posing);
    expect(Array.from(stiff).some((s) => s === 100) && Array.from(stiff).some((s) => s === 1)).toBe(true);
    const [x, y] = Array.from(posing.deformer.handlePositions()).slice(2, 4) as [number, number];
    // The steps the drag takes, as the core's interaction loop records them.
    posing.startRecording();
    dragTo(posing, [x - 0.4, y + 0.5]);
    const recorder = {
      steps: posing
        .stopRecording()!
        .data.events.flatMap((e) => ("step" in e ? [Float64Array.from(e.step as ArrayLike<number>)] : [])),
    };
    // The same steps on a core deformer with the painting: the same bits.
    const core = new Deformer(posing.shape.mesh.positions, posing.shape.mesh.triangles);
    core.setHandlePoints(handles.triangles, handles.barycentric);
    core.setStiffness(stiff);
    for (const v of recorder.steps) core.step(v);
    expect(Array.from(posing.deformer.positions())).toEqual(Array.from(core.positions()));
    // Without the painting the same steps pose otherwise.
    core.reset();
    core.setStiffness(undefined);
    for (const v of recorder.steps) core.step(v);
    expect(Array.from(posing.deformer.positions())).not.toEqual(Array.from(core.positions()));
    core.free();

    // Undo the drag, then the stroke: no painting, the rest pose.
    expect(posing.travel(false)).toBe(true);
    expect(posing.stiffness).toEqual(stiff);
    expect(posing.travel(false)).toBe(true);
    expect(posing.stiffness).toBeUndefined();
    expect(posing.deformer.positions()).toEqual(rest);
    expect(posing.travel(true)).toBe(true);
    expect(posing.stiffness).toEqual(stiff);
  });

  it("survives a method without stiffness, and a recording of it all replays to the same bits", async () => {
    const a = posed(500).posing;
    const b = posed(500).posing;
    const stiff = paintArm(a);
    b.setStiffness(stiff);
    a.startRecording();
    a.setMethod("mls", 100);
    expect(a.deformer.hasStiffness).toBe(false);
    expect(a.stiffness).toEqual(stiff); // kept for the methods that use it
    a.setMethod("akap", 100);
    const [x, y] = Array.from(a.deformer.handlePositions()).slice(2, 4) as [number, number];
    dragTo(a, [x - 0.3, y + 0.3]);
    dragTo(b, [x - 0.3, y + 0.3]);
    // AKAP got the painting back: it poses as the deformer that never lost it.
    expect(Array.from(a.deformer.positions())).toEqual(Array.from(b.deformer.positions()));
    const session = a.stopRecording()!;
    expect(session.json).toContain('{"stiffness":[');
    a.setStiffness(undefined);
    a.reset();
    await a.replay(session, a.shape, async () => true);
    expect(Array.from(a.deformer.positions())).toEqual(Array.from(b.deformer.positions()));
    expect(a.stiffness).toEqual(stiff);
  });

  it("bad values throw and change nothing; re-meshing carries the painting; JSON meshes keep it", () => {
    const { posing } = posed(500);
    const stiff = paintArm(posing);
    const n = posing.shape.mesh.triangleCount;
    expect(() => posing.setStiffness(new Float64Array(n).fill(2000))).toThrow(
      "the stiffness of triangle 0 is 2000, expected a number from 0.001 to 1000",
    );
    expect(() => posing.setStiffness(new Float64Array(n - 1).fill(2))).toThrow(`expected ${n}`);
    expect(posing.stiffness).toEqual(stiff);

    const old = posing.shape.mesh;
    const finer = meshOutline(builtinShape("gingerbread"), "gingerbread", 1500, 28);
    posing.gesture(() => posing.carryOver(finer, undefined));
    const carried = posing.stiffness!;
    expect(carried.length).toBe(finer.mesh.triangleCount);
    // Each new triangle has the value of the old triangle under its centroid.
    let checked = 0;
    for (let t = 0; t < finer.mesh.triangleCount; t += 7) {
      const [x, y] = centroid(finer.mesh.positions, finer.mesh.triangles, t);
      const under = Array.from({ length: old.triangleCount }, (_, f) => f).find((f) => {
        const p = old.positions;
        const [a, b, c] = [0, 1, 2].map((k) => old.triangles[3 * f + k]!);
        const side = (u: number, v: number) =>
          (p[2 * v]! - p[2 * u]!) * (y - p[2 * u + 1]!) - (p[2 * v + 1]! - p[2 * u + 1]!) * (x - p[2 * u]!);
        return side(a!, b!) > 0 && side(b!, c!) > 0 && side(c!, a!) > 0;
      });
      if (under === undefined) continue;
      expect(carried[t]).toBe(stiff[under]);
      checked++;
    }
    expect(checked).toBeGreaterThan(100);
    expect(carryStiffness(undefined, old, finer.mesh, 0.1)).toBeUndefined();

    const text = meshToJson({ ...finer.mesh, stiffness: carried });
    expect(meshFromJson(text).stiffness).toEqual(carried);
  });
});
