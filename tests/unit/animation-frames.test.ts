/**
 * The animation's frames against the real wasm core in Node (`animation/frames.ts`,
 * `animation/playback.ts`): three keys recorded on the default figure; handles at the keys' targets
 * at the keys' times; computed twice, the same bits; the same frames from a `Deformer`
 * driven by hand (targets and substeps worked out here, not through the modules); the
 * cache made again when keys, method or stiffness change; bad input refused with nothing
 * changed; showing a frame leaves the pose there, undoably.
 */
import { beforeAll, describe, expect, it } from "vitest";
import { Deformer, init } from "../../www/src/index.js";
import { AnimationFrames } from "../../www/src/widget/animation/frames.js";
import { Animator } from "../../www/src/widget/animation/playback.js";
import { posed, dragTo, trainedRig } from "./posing-fixtures.js";
import type { Posing } from "../../www/src/widget/model/posing.js";

beforeAll(async () => {
  await init();
});

const FPS = 24;
/** The bytes of a Float64Array: equal only when every number has the same bits. */
const bytes = (values: Float64Array) =>
  new Uint8Array(values.buffer.slice(values.byteOffset, values.byteOffset + values.byteLength));

function animator(posing: Posing, fps = FPS): { animator: Animator; shown: number[]; messages: string[] } {
  const shown: number[] = [];
  const messages: string[] = [];
  const a = new Animator({
    posing,
    fps: () => fps,
    shown: (index) => shown.push(index),
    changed: () => undefined,
    info: (message) => messages.push(message),
  });
  return { animator: a, shown, messages };
}

/**
 * The default figure with a pin and a handle; keys at 0 s (rest), 0.5 s (the handle
 * dragged right and up, linear) and 1 s (dragged down, eased), captured as K does: the
 * handles where they are, with the pose.
 */
function threeKeys(): { posing: Posing; animator: Animator; targets: Float64Array[] } {
  const { posing } = posed(400);
  const { animator: a } = animator(posing);
  const targets: Float64Array[] = [];
  const at = () => posing.deformer.handlePositions();
  const size = posing.shape.size;
  a.capture(0);
  targets.push(at());
  const [x, y] = [at()[2]!, at()[3]!];
  dragTo(posing, [x + 0.15 * size, y + 0.2 * size]);
  a.capture(0.5);
  targets.push(at());
  dragTo(posing, [x + 0.1 * size, y - 0.15 * size]);
  a.capture(1, "ease");
  targets.push(at());
  return { posing, animator: a, targets };
}

describe("animation frames", () => {
  it("has a frame per 1/fps; frame 0 is the first key's pose; the handles reach each key's targets at its time", () => {
    const { posing, animator: a, targets } = threeKeys();
    const frames = a.frames();
    expect(frames.count).toBe(25);
    expect(bytes(frames.frame(0).positions)).toEqual(bytes(a.timeline.keys[0]!.pose));
    const size = posing.shape.size;
    for (const [k, index] of [0, 12, 24].entries()) {
      const h = frames.frame(index).handles;
      for (let i = 0; i < h.length; i++) expect(Math.abs(h[i]! - targets[k]![i]!)).toBeLessThan(2e-3 * size);
    }
    // Between keys the handle is on its way: at 0.25 s, half way (linear) to the second key's place.
    const mid = frames.frame(6).handles;
    const half = [0.5 * (targets[0]![2]! + targets[1]![2]!), 0.5 * (targets[0]![3]! + targets[1]![3]!)];
    expect(Math.hypot(mid[2]! - half[0]!, mid[3]! - half[1]!)).toBeLessThan(2e-3 * size);
  });

  it("computed twice gives the same bits, frame by frame", () => {
    const { animator: a } = threeKeys();
    const first = a.frames().all();
    const again = new AnimationFrames(a.frames().source);
    const second = again.all();
    again.free();
    expect(second).toHaveLength(first.length);
    first.forEach((f, i) => expect(bytes(second[i]!.positions)).toEqual(bytes(f.positions)));
  });

  it("equals a Deformer driven by hand: tracking substeps toward the interpolated targets", () => {
    const { posing, animator: a, targets } = threeKeys();
    const frames = a.frames().all();
    const { mesh, size } = posing.shape;
    const { maxStep, maxSubsteps } = posing.settings;
    const handles = a.timeline.handles!;
    const deformer = new Deformer(mesh.positions, mesh.triangles, {
      method: "akap",
      dirichlet: true,
      integrator: "spiral",
      lambda: 100,
    });
    deformer.setHandlePoints(Uint32Array.from(handles.triangles), Float64Array.from(handles.barycentric));
    deformer.setPositions(a.timeline.keys[0]!.pose);
    expect(bytes(deformer.positions())).toEqual(bytes(frames[0]!.positions));
    const smooth = (u: number) => u * u * (3 - 2 * u);
    for (let f = 1; f < frames.length; f++) {
      const t = f / FPS;
      const [from, to, e] =
        t <= 0.5 ? [targets[0]!, targets[1]!, (t - 0) / 0.5] : [targets[1]!, targets[2]!, smooth((t - 0.5) / 0.5)];
      const goal = from.map((v, i) => v + (to[i]! - v) * e);
      let now = deformer.handlePositions();
      let gap = 0;
      for (let i = 0; i < now.length; i += 2)
        gap = Math.max(gap, Math.hypot(goal[i]! - now[i]!, goal[i + 1]! - now[i + 1]!));
      if (gap > 1e-5 * size) {
        const needed = Math.max(1, Math.ceil(gap / (maxStep * size) - 1e-9));
        for (let s = 0; s < Math.min(needed, maxSubsteps); s++) {
          const v = goal.map((g, i) => (g - now[i]!) / (needed - s));
          if (deformer.stepWithoutFoldovers(v).clamped) break;
          now = deformer.handlePositions();
        }
      }
      expect(bytes(deformer.positions()), `frame ${f}`).toEqual(bytes(frames[f]!.positions));
    }
    deformer.free();
  });

  it("is computed again when the keys, the method or the stiffness change, and not otherwise", () => {
    const { posing, animator: a } = threeKeys();
    const first = a.frames();
    expect(a.frames()).toBe(first);
    a.setEasing(2, "linear");
    const second = a.frames();
    expect(second).not.toBe(first);
    expect(bytes(second.frame(20).positions)).not.toEqual(bytes(first.frame(20).positions));
    posing.setMethod("arap", 100);
    const third = a.frames();
    expect(third).not.toBe(second);
    expect(third.source.options.method).toBe("arap");
    posing.setStiffness(new Float64Array(posing.shape.mesh.triangleCount).fill(5));
    const fourth = a.frames();
    expect(fourth).not.toBe(third);
    expect(fourth.source.stiffness?.[0]).toBe(5);
    a.moveKey(1, 0.25);
    expect(a.frames()).not.toBe(fourth);
    a.deleteKey(1);
    expect(a.frames().count).toBe(25);
  });

  it("refuses bad input with nothing changed", () => {
    const { posing, animator: a } = threeKeys();
    const before = JSON.stringify(a.keys().map((k) => [k.time, k.easing, [...k.targets]]));
    const frames = a.frames();
    for (const bad of [
      () => a.capture(NaN),
      () => a.capture(-0.5),
      () => a.moveKey(3, 1),
      () => a.moveKey(0, -1),
      () => a.moveKey(0, 1),
      () => a.deleteKey(-1),
      () => a.setEasing(0, "springy" as "ease"),
      () => a.seek(NaN),
      () => frames.frame(25),
    ]) {
      expect(bad).toThrow();
      expect(JSON.stringify(a.keys().map((k) => [k.time, k.easing, [...k.targets]]))).toBe(before);
    }
    expect(a.frames()).toBe(frames);
    // Another handle set: refused, with what to do.
    posing.gesture(() => posing.addHandle(posing.handles[1]!.point));
    expect(() => a.capture(2)).toThrow(/another set of handles.*delete the keys/);
    expect(a.keys()).toHaveLength(3);
  });

  it("shows a frame in the posing (the timeline's handles, the frame's pose) as one undoable step", () => {
    const { posing, animator: a } = threeKeys();
    const before = posing.deformer.positions();
    posing.gesture(() => posing.addHandle(posing.handles[1]!.point));
    a.seek(0.5);
    expect(posing.handles).toHaveLength(2);
    expect(bytes(posing.deformer.positions())).toEqual(bytes(a.frames().frame(12).positions));
    expect(a.playhead).toBe(12);
    // Seeking past the end moves the playhead there and shows the last frame.
    a.seek(7);
    expect(a.playhead).toBe(7 * 24);
    expect(bytes(posing.deformer.positions())).toEqual(bytes(a.frames().frame(24).positions));
    posing.travel(false);
    posing.travel(false);
    expect(posing.handles).toHaveLength(3);
    posing.travel(false);
    expect(bytes(posing.deformer.positions())).toEqual(bytes(before));
  });

  it("with a fitting rig (the defop method), each frame is the rig's pose for the interpolated targets", async () => {
    const { posing, animator: a, targets } = threeKeys();
    const trained = await trainedRig(posing);
    const stepped = a.frames();
    posing.setMethod("defop", 100);
    const frames = a.frames();
    expect(frames).not.toBe(stepped);
    // 0.25 s: half way (linear) from the first key's places to the second's.
    const half = targets[0]!.map((v, i) => v + (targets[1]![i]! - v) * 0.5);
    expect(bytes(frames.frame(6).positions)).toEqual(bytes(trained.operator.evaluate(half)));
    expect(bytes(frames.frame(24).positions)).toEqual(bytes(trained.operator.evaluate(targets[2]!)));
    posing.rig!.free();
  });

  it("refuses to play without keys, and clears the keys when the shape changes", async () => {
    const { posing } = posed(400);
    const { animator: a, messages } = animator(posing);
    await expect(a.play()).rejects.toThrow(/there are no keys/);
    expect(() => a.frames()).toThrow(/there are no keys/);
    a.capture(0);
    posing.install(posed(300).posing.shape);
    expect(a.keys()).toEqual([]);
    expect(a.frameCount).toBe(0);
    expect(messages).toEqual(["The shape changed: the animation's keys were cleared."]);
  });
});
