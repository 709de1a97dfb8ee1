/**
 * Turning handles in the widget's posing core, through the real wasm: a pointer going a
 * quarter turn round a lone handle turns the whole figure rigidly about it (the core's
 * exact rotation, in substeps of at most 0.1 rad); with a pin elsewhere the handle's
 * triangle turns by about the angle and the pin stays; a recording of the turns replays
 * to the same bits; a method without turning handles says so and drops the turn.
 */
import { beforeAll, describe, expect, it } from "vitest";
import { init } from "../../www/src/index.js";
import { noTimings } from "./fixtures.js";
import { posed } from "./posing-fixtures.js";

beforeAll(async () => {
  await init();
});

/** Turns handle `index` by `angle` as a pointer would (from its right, round it), running frames until it stops. */
function turn(posing: ReturnType<typeof posed>["posing"], index: number, angle: number): void {
  const p = posing.deformer.handlePositions();
  const [cx, cy] = [p[2 * index]!, p[2 * index + 1]!];
  posing.beginGesture();
  expect(posing.grabTurn(index, 9, cx + 0.3, cy)).toBe(true);
  for (let k = 1; k <= 8; k++) {
    const a = (angle * k) / 8;
    posing.dragTurn(9, cx + 0.3 * Math.cos(a), cy + 0.3 * Math.sin(a));
  }
  for (let frame = 0; frame < 100 && posing.advance(noTimings()) > 0; frame++) posing.markChanged();
  posing.release(9);
}

describe("turning handles", () => {
  it("a lone handle turned a quarter turn turns the whole shape rigidly about it", () => {
    const { posing } = posed(500);
    posing.handles.splice(0, 1);
    posing.applyHandles();
    const rest = posing.deformer.positions();
    const [cx, cy] = Array.from(posing.deformer.handlePositions());
    turn(posing, 0, Math.PI / 2);
    const p = posing.deformer.positions();
    let worst = 0;
    for (let v = 0; v < p.length / 2; v++) {
      const [x, y] = [rest[2 * v]! - cx!, rest[2 * v + 1]! - cy!];
      worst = Math.max(worst, Math.hypot(p[2 * v]! - (cx! - y), p[2 * v + 1]! - (cy! + x)));
    }
    expect(worst).toBeLessThan(1e-9 * posing.shape.size);
    expect(posing.deformer.turns().turned[0]).toBeCloseTo(Math.PI / 2, 12);
  });

  it("with a pin, the handle's triangle turns by about the angle; the recording replays to the same bits", async () => {
    const { posing } = posed(500);
    const rest = posing.deformer.positions();
    posing.startRecording();
    turn(posing, 1, 0.6);
    const session = posing.stopRecording()!;
    expect(session.json).toContain('{"turn":{');
    const t = posing.shape.mesh.triangles;
    const f = posing.handles[1]!.point.triangle;
    const [a, b] = [t[3 * f]!, t[3 * f + 1]!];
    const direction = (q: Float64Array) => Math.atan2(q[2 * b + 1]! - q[2 * a + 1]!, q[2 * b]! - q[2 * a]!);
    const pose = posing.deformer.positions();
    const turned = direction(pose) - direction(rest);
    expect(turned).toBeGreaterThan(0.45);
    expect(turned).toBeLessThan(0.65);
    const pin = Array.from(posing.deformer.handlePositions()).slice(0, 2);
    const target = posing.targets();
    expect(Math.hypot(pin[0]! - target[0]!, pin[1]! - target[1]!)).toBeLessThan(0.01 * posing.shape.size);
    posing.reset();
    await posing.replay(session, posing.shape, async () => true);
    expect(Array.from(posing.deformer.positions())).toEqual(Array.from(pose));
  });

  it("a method without turning handles says so, and the turn is dropped", () => {
    const { posing } = posed(400);
    posing.setMethod("mls", 100);
    const p = posing.deformer.handlePositions();
    posing.grabTurn(1, 3, p[2]! + 0.2, p[3]!);
    posing.dragTurn(3, p[2]!, p[3]! + 0.2);
    expect(() => posing.advance(noTimings())).toThrow(
      'method mls has no turning handles; choose "akap" or "arap" for it',
    );
    const { turns, turned } = posing.deformer.turns();
    expect(turns[1]).toBe(turned[1]);
  });
});
