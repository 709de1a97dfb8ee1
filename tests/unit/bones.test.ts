/**
 * Bones in the widget's posing core, through the real wasm: a bone drawn on the figure's
 * arm stays straight and keeps its length, to 1e-9 of the figure's size, while the hand is
 * dragged far (the same drag without it bends that segment by more than 1e-3); undo and
 * redo take it away and back; a recording with it replays to the same bits; a method
 * without bones refuses them and keeps them for the methods that have them; a bone the
 * core refuses changes nothing; an animation's frames keep the bone straight too.
 */
import { beforeAll, describe, expect, it } from "vitest";
import { init } from "../../www/src/index.js";
import type { Bone } from "../../www/src/widget/model/bones.js";
import { locate, pointPosition, type MeshPoint } from "../../www/src/widget/model/picking.js";
import type { Posing } from "../../www/src/widget/model/posing.js";
import { Animator } from "../../www/src/widget/animation/playback.js";
import { dragTo, posed } from "./posing-fixtures.js";

beforeAll(async () => {
  await init();
});

/** The bone on the right arm, from near the shoulder to before the hand, at rest. */
const ARM: [[number, number], [number, number]] = [
  [0.33, 0.66],
  [0.53, 0.625],
];

/** Points a tenth of the way apart along the arm's bone (its ends first and last), as mesh points at rest. */
function samples(posing: Posing): MeshPoint[] {
  const { positions, triangles } = posing.shape.mesh;
  return Array.from({ length: 11 }, (_, k) => {
    const t = k / 10;
    const [[ax, ay], [bx, by]] = ARM;
    const point = locate(positions, triangles, ax + t * (bx - ax), ay + t * (by - ay));
    expect(point, `the arm's bone at ${t} lies on the figure`).toBeDefined();
    return point!;
  });
}

/** How far the sampled bone is from straight and from its rest length, at the current pose (or `positions`). */
function bend(posing: Posing, points: MeshPoint[], positions = posing.deformer.positions()): number {
  const { triangles } = posing.shape.mesh;
  const q = points.map((p) => pointPosition(positions, triangles, p));
  const [a, b] = [q[0]!, q[10]!];
  const rest = Math.hypot(ARM[1][0] - ARM[0][0], ARM[1][1] - ARM[0][1]);
  let worst = Math.abs(Math.hypot(b[0] - a[0], b[1] - a[1]) - rest);
  q.forEach(([x, y], k) => {
    const t = k / 10;
    worst = Math.max(worst, Math.hypot(x - (a[0] + t * (b[0] - a[0])), y - (a[1] + t * (b[1] - a[1]))));
  });
  return worst;
}

function armBone(points: MeshPoint[]): Bone {
  return { ends: [points[0]!, points[10]!] };
}

describe("bones", () => {
  it("a bone on the arm stays straight and keeps its length while the hand is dragged far", () => {
    for (const method of ["akap", "arap"] as const) {
      const results = [true, false].map((withBone) => {
        const { posing } = posed(800);
        posing.setMethod(method, 100);
        const points = samples(posing);
        if (withBone) posing.gesture(() => posing.bones.set([armBone(points)]));
        dragTo(posing, [0.35, 1.1]);
        dragTo(posing, [0.9, 0.2]);
        return bend(posing, points);
      });
      expect(results[0], method).toBeLessThan(1e-9 * 1.34);
      expect(results[1], method).toBeGreaterThan(1e-3 * 1.34);
    }
  });

  it("undo and redo take the bone away and back; a recording with it replays to the same bits", async () => {
    const { posing } = posed(600);
    const points = samples(posing);
    posing.startRecording();
    posing.gesture(() => posing.bones.set([armBone(points)]));
    expect(posing.bones.list).toHaveLength(1);
    dragTo(posing, [0.4, 1.0]);
    const session = posing.stopRecording()!;
    expect(session.json).toContain('{"bones":{');
    const pose = posing.deformer.positions();
    expect(posing.travel(false)).toBe(true); // the drag
    expect(posing.travel(false)).toBe(true); // the bone
    expect(posing.bones.list).toHaveLength(0);
    expect(posing.travel(true)).toBe(true);
    expect(posing.bones.list).toHaveLength(1);
    posing.reset();
    await posing.replay(session, posing.shape, async () => true);
    expect(Array.from(posing.deformer.positions())).toEqual(Array.from(pose));
    expect(posing.bones.list).toHaveLength(1);
  });

  it("a method without bones refuses them and keeps them for the methods that have them", () => {
    const { posing } = posed(600);
    const points = samples(posing);
    posing.bones.set([armBone(points)]);
    posing.setMethod("mls", 100);
    expect(posing.bones.list).toHaveLength(1);
    expect(() => posing.bones.set([armBone(points)])).toThrow(
      'method mls has no bones; choose "akap" or "arap" to draw them',
    );
    posing.setMethod("akap", 100);
    dragTo(posing, [0.35, 1.1]);
    expect(bend(posing, points)).toBeLessThan(1e-9 * 1.34);
  });

  it("a bone the core refuses changes nothing", () => {
    const { posing } = posed(600);
    const points = samples(posing);
    posing.bones.set([armBone(points)]);
    const version = posing.bones.version;
    expect(() => posing.bones.set([armBone(points), { ends: [points[3]!, points[3]!] }])).toThrow(
      "bone 1 cannot be used: its ends are at one point",
    );
    expect(posing.bones.list).toHaveLength(1);
    expect(posing.bones.version).toBe(version);
  });

  it("an animation's frames keep the bone as straight and as long as it was drawn", () => {
    const { posing } = posed(500);
    const points = samples(posing);
    posing.bones.set([armBone(points)]);
    const animator = new Animator({
      posing,
      fps: () => 12,
      shown: () => undefined,
      changed: () => undefined,
      info: () => undefined,
    });
    animator.capture(0);
    dragTo(posing, [0.35, 1.1]);
    animator.capture(0.5);
    dragTo(posing, [0.9, 0.2]);
    animator.capture(1);
    const frames = animator.frames();
    expect(frames.count).toBe(13);
    let worst = 0;
    for (let k = 0; k < frames.count; k++) worst = Math.max(worst, bend(posing, points, frames.frame(k).positions));
    expect(worst).toBeLessThan(1e-9 * 1.34);
    // Without the bone, the same keys bend it.
    posing.gesture(() => posing.bones.set([]));
    const free = animator.frames();
    const last = free.frame(free.count - 1).positions;
    expect(bend(posing, points, last)).toBeGreaterThan(1e-3 * 1.34);
  });
});
