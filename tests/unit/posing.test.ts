/**
 * The widget's posing core in Node, through the real wasm: handles reach their targets
 * while pins stay, undo and redo restore poses exactly, a failed step changes nothing and
 * the next ones work, and re-meshing carries handles and pose over. With the "defop" method
 * a fitting rig poses each frame as its operator does; a rig for other handles is stale and
 * AKAP poses instead; a recording of rig posing replays to the same bits.
 */
import { beforeAll, describe, expect, it } from "vitest";
import { builtinShape, init } from "../../www/src/index.js";
import { meshOutline } from "../../www/src/widget/model/shape.js";
import { locate, pointPosition } from "../../www/src/widget/model/picking.js";
import { noTimings, wasmCalls } from "./fixtures.js";
import { dragTo, posed, trainedRig } from "./posing-fixtures.js";

beforeAll(async () => {
  await init();
});

describe("Posing", () => {
  it("takes a dragged handle to its target while the pin stays, and undo and redo restore poses exactly", () => {
    const { posing } = posed();
    const rest = posing.deformer.positions();
    const before = Array.from(posing.deformer.handlePositions());
    const target: [number, number] = [before[2]! - 0.3, before[3]! + 0.4];
    dragTo(posing, target);
    const after = posing.deformer.handlePositions();
    expect(Math.hypot(after[2]! - target[0], after[3]! - target[1])).toBeLessThan(1e-5 * posing.shape.size);
    expect(Math.hypot(after[0]! - before[0]!, after[1]! - before[1]!)).toBeLessThan(1e-5 * posing.shape.size);
    const pose = posing.deformer.positions();
    expect(posing.history.canUndo).toBe(true);
    expect(posing.travel(false)).toBe(true);
    expect(posing.deformer.positions()).toEqual(rest);
    expect(posing.travel(true)).toBe(true);
    expect(posing.deformer.positions()).toEqual(pose);
  });

  it("a frame of a drag with a recording running makes one call into WebAssembly, and records every step", async () => {
    const { posing } = posed();
    posing.startRecording();
    const [x, y] = Array.from(posing.deformer.handlePositions()).slice(2, 4) as [number, number];
    posing.grab(1, 3, x, y, false);
    // Far enough for several substeps and, with No foldovers (the default), guarded ones.
    posing.drag(3, x - 0.3, y + 0.2);
    const { result: steps, calls } = await wasmCalls(() => posing.advance(noTimings()));
    expect(steps).toBeGreaterThan(1);
    expect(calls).toEqual(["Deformer.advance"]);
    posing.release(3);
    const session = posing.stopRecording()!;
    expect(session.data.events.filter((e) => "step" in e).length).toBeGreaterThanOrEqual(steps);
  });

  it("a rig's frame makes one call into WebAssembly, and no pose crosses the boundary", async () => {
    const { posing } = posed(400);
    const trained = await trainedRig(posing);
    posing.setMethod("defop", 100);
    posing.startRecording();
    const [x, y] = Array.from(posing.deformer.handlePositions()).slice(2, 4) as [number, number];
    posing.grab(1, 3, x, y, false);
    posing.drag(3, x - 0.2, y + 0.3);
    expect(posing.advance(noTimings())).toBe(1); // the rig is given to the deformer here, once
    posing.drag(3, x - 0.25, y + 0.35);
    // The operator poses the deformer in place; the one call returns a small report.
    const { result: steps, calls } = await wasmCalls(() => posing.advance(noTimings()));
    expect(steps).toBe(1);
    expect(calls).toEqual(["Deformer.advance"]);
    const expected = trained.operator.evaluate(Array.from(posing.targets()));
    expect(Array.from(posing.deformer.positions())).toEqual(Array.from(expected));
    posing.release(3);
  });

  it("a step that fails changes nothing and is passed on; once the cause is gone, steps work", () => {
    const { posing } = posed();
    // The paper's mode steps by the pointer's raw displacement (in at most maxSubsteps
    // substeps): a jump of 1e301, beyond the coordinate limit (1e300), makes every step
    // fail, down to the eighth of a substep the last retry takes.
    posing.settings.paperMode = true;
    const before = posing.deformer.positions();
    const [x, y] = Array.from(posing.deformer.handlePositions()).slice(2, 4) as [number, number];
    posing.grab(1, 3, x, y, false);
    posing.drag(3, x + 1e301, y);
    expect(() => posing.advance(noTimings())).toThrow(/not finite or beyond ±1e300; use smaller steps/);
    expect(posing.deformer.positions()).toEqual(before);
    posing.release(3);
    posing.grab(1, 3, x, y, false);
    posing.drag(3, x + 0.2, y);
    expect(posing.advance(noTimings())).toBeGreaterThan(0);
    expect(posing.deformer.positions()).not.toEqual(before);
  });

  it("a lambda out of range is refused with the range and changes nothing", () => {
    const { posing, calls } = posed();
    calls.length = 0;
    expect(() => posing.setMethod("akap", 1e308)).toThrow(
      "option lambda is 1e308, expected a number from 1e-6 to 1e10",
    );
    expect(() => posing.setMethod("akap", 1e-300)).toThrow(
      "option lambda is 1e-300, expected a number from 1e-6 to 1e10",
    );
    expect(posing.settings.lambda).toBe(100);
    expect(calls).toEqual([]);
    const [x, y] = Array.from(posing.deformer.handlePositions()).slice(2, 4) as [number, number];
    posing.grab(1, 3, x, y, false);
    posing.drag(3, x + 0.2, y);
    expect(posing.advance(noTimings())).toBeGreaterThan(0);
  });

  it("with No foldovers an extreme drag folds nothing, stops short, and its recording replays to the same bits", async () => {
    const { posing } = posed(600);
    const rest = posing.deformer.positions();
    const hand = Array.from(posing.deformer.handlePositions()).slice(2, 4) as [number, number];
    const target: [number, number] = [hand[0] - 0.8, hand[1] - 1.3];
    posing.startRecording();
    // The hand pulled down through the body, below the feet.
    dragTo(posing, target);
    expect(posing.deformer.metrics().flipped).toBe(0);
    expect(posing.clamped).toBe(true);
    const session = posing.stopRecording()!;
    const pose = posing.deformer.positions();
    // Without the guard the same drag folds triangles over.
    const plain = posed(600).posing;
    plain.settings.noFoldovers = false;
    dragTo(plain, target);
    expect(plain.deformer.metrics().flipped).toBeGreaterThan(0);
    // The recording holds the plain steps the guard took: a replay repeats them exactly.
    posing.reset();
    expect(posing.deformer.positions()).toEqual(rest);
    await posing.replay(session, posing.shape, async () => true);
    expect(Array.from(posing.deformer.positions())).toEqual(Array.from(pose));
  });

  it("re-meshing carries the pose and the handles over, at their places, as one undoable step", () => {
    const { posing } = posed(600);
    dragTo(posing, [0.9, 0.2]);
    const handles = Array.from(posing.deformer.handlePositions());
    const old = posing.shape;
    const oldPose = posing.deformer.positions();
    const finer = meshOutline(builtinShape("gingerbread"), "gingerbread", 2000, 28);
    posing.gesture(() => posing.carryOver(finer, undefined));
    expect(posing.shape).toBe(finer);
    expect(posing.handles.length).toBe(2);
    const moved = posing.deformer.handlePositions();
    for (let i = 0; i < 4; i++) expect(Math.abs(moved[i]! - handles[i]!)).toBeLessThan(0.01 * finer.size);
    // Each new vertex sits where the old pose takes its rest place: its rest point located in
    // the old rest mesh, interpolated in the old pose.
    const now = posing.deformer.positions();
    const fp = finer.mesh.positions;
    for (let v = 0; v < finer.mesh.vertexCount; v += 97) {
      const at = locate(old.mesh.positions, old.mesh.triangles, fp[2 * v]!, fp[2 * v + 1]!, 1e-9);
      if (!at) continue; // outside the old mesh by a hair: extrapolated, not checked here
      const [x, y] = pointPosition(oldPose, old.mesh.triangles, at);
      expect(Math.hypot(now[2 * v]! - x, now[2 * v + 1]! - y)).toBeLessThan(1e-9 * finer.size);
    }
    expect(posing.travel(false)).toBe(true);
    expect(posing.shape).toBe(old);
    expect(Array.from(posing.deformer.handlePositions())).toEqual(handles);
  });

  it("poses with a fitting rig as its operator does, steps AKAP when the rig is stale, and replays a recording of it", async () => {
    const { posing } = posed(400);
    const trained = await trainedRig(posing);
    const { mesh } = posing.shape;
    expect(posing.posingWithRig).toBe(false); // the method is still AKAP
    posing.setMethod("defop", 100);
    expect(posing.posingWithRig).toBe(true);
    posing.startRecording();
    const [x, y] = Array.from(posing.deformer.handlePositions()).slice(2, 4) as [number, number];
    dragTo(posing, [x - 0.2, y + 0.3]);
    expect(posing.evaluationMs).toBeGreaterThanOrEqual(0);
    const targets = Array.from(posing.targets());
    const expected = trained.operator.evaluate(targets);
    expect(Array.from(posing.deformer.positions())).toEqual(Array.from(expected));
    // Unchanged targets: no evaluation, nothing recorded.
    expect(posing.advance(noTimings())).toBe(0);
    const session = posing.stopRecording()!;

    // Another handle: the rig is stale, and a drag steps the deformer (AKAP) instead.
    const t = posing.shape.mesh.triangles;
    posing.addHandle(locate(mesh.positions, t, mesh.positions[0]!, mesh.positions[1]!, 1e-9)!);
    expect(posing.posingWithRig).toBe(false);
    const before = posing.deformer.positions();
    dragTo(posing, [x - 0.1, y + 0.2]);
    expect(posing.evaluationMs).toBe(0);
    expect(Array.from(posing.deformer.positions())).not.toEqual(Array.from(before));

    // The recording replays to the rig's pose, bit for bit.
    await posing.replay(session, posing.shape, async () => true);
    expect(Array.from(posing.deformer.positions())).toEqual(Array.from(expected));
    posing.rig!.free();
  });
});
