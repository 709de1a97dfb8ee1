/**
 * Posing with a trained rig in the widget's posing core, in Node through the real wasm:
 * with "No foldovers" (the default) a drag whose plain evaluation turns triangles over
 * stops short of the fold and says so (`clamped`, which the HUD shows), without it the rig
 * folds; a recording names the rig by its checksum and records its frames as targets,
 * replaying with that rig to the same bits (the "defop" method shown), and refusing,
 * saying which rig, without it.
 */
import { beforeAll, describe, expect, it } from "vitest";
import { init } from "../../www/src/index.js";
import { parseSession } from "../../www/src/session.js";
import { Rig } from "../../www/src/widget/model/rig.js";
import { noTimings } from "./fixtures.js";
import { dragTo, posed, trainedRig } from "./posing-fixtures.js";

beforeAll(async () => {
  await init();
});

/** Twice each triangle's signed area in `positions` (plain products). */
function areas(positions: ArrayLike<number>, triangles: ArrayLike<number>): number[] {
  const out: number[] = [];
  for (let f = 0; f < triangles.length / 3; f++) {
    const [a, b, c] = [triangles[3 * f]!, triangles[3 * f + 1]!, triangles[3 * f + 2]!];
    const [ax, ay, bx, by, cx, cy] = [
      positions[2 * a]!,
      positions[2 * a + 1]!,
      positions[2 * b]!,
      positions[2 * b + 1]!,
      positions[2 * c]!,
      positions[2 * c + 1]!,
    ];
    out.push((bx - ax) * (cy - ay) - (by - ay) * (cx - ax));
  }
  return out;
}

const bits = (values: ArrayLike<number>): string =>
  Array.from(new Uint8Array(Float64Array.from(values).buffer), (b) => b.toString(16).padStart(2, "0")).join("");

describe("posing with a rig", () => {
  it("stops a drag short of a fold with No foldovers and says so, and folds without", async () => {
    const { posing } = posed(300);
    const trained = await trainedRig(posing);
    posing.setMethod("defop", 100);
    const { mesh, size } = posing.shape;
    const rest = Array.from(posing.deformer.handlePositions());
    // The handle dragged across the figure, far past the pin: the rig's own evaluation
    // there turns triangles over.
    const far: [number, number] = [rest[2]! - 2 * size, rest[3]! - 0.5 * size];
    const plain = areas(trained.operator.evaluate([rest[0]!, rest[1]!, ...far]), mesh.triangles);
    expect(plain.filter((a) => a <= 0).length).toBeGreaterThan(0);
    // The rig's rest pose: the triangles it has turned over may stay so.
    const atRest = areas(trained.operator.evaluate(rest), mesh.triangles);

    expect(posing.settings.noFoldovers).toBe(true);
    let clamped = false;
    const [x, y] = [rest[2]!, rest[3]!];
    posing.grab(1, 5, x, y, false);
    for (let k = 1; k <= 10; k++) {
      posing.drag(5, x + (far[0] - x) * (k / 10), y + (far[1] - y) * (k / 10));
      posing.advance(noTimings());
      clamped ||= posing.clamped;
      const now = areas(posing.deformer.positions(), mesh.triangles);
      const folded = now.filter((a, f) => a <= 0 && atRest[f]! > 0).length;
      expect(folded, `frame ${k}`).toBe(0);
    }
    posing.release(5);
    expect(clamped).toBe(true);

    // Let go, the handle keeps its target; without the guard the rig is evaluated there
    // again at once, and folds.
    expect(Array.from(posing.deformer.targets()).slice(2)).toEqual(far);
    posing.settings.noFoldovers = false;
    expect(posing.advance(noTimings())).toBe(1);
    expect(posing.clamped).toBe(false);
    const now = areas(posing.deformer.positions(), mesh.triangles);
    expect(now.filter((a) => a <= 0).length).toBeGreaterThan(0);
    posing.rig!.free();
  });

  it("a recording names the rig and its frames' targets, and replays with that rig to the same bits", async () => {
    const { posing: p } = posed(300);
    const trained = await trainedRig(p);
    p.setMethod("defop", 100);
    p.startRecording();
    const [x, y] = Array.from(p.deformer.handlePositions()).slice(2, 4) as [number, number];
    const size = p.shape.size;
    dragTo(p, [x - 0.2 * size, y + 0.3 * size]);
    dragTo(p, [x - 2 * size, y - 0.5 * size]); // stopped short of the fold
    const pose = p.deformer.positions();
    const session = p.stopRecording()!;
    const kinds = session.data.events.map((e) => Object.keys(e)[0]);
    expect(kinds).toContain("rig");
    expect(kinds).toContain("rigPose");
    expect(kinds).not.toContain("positions");
    expect(session.data.version).toBe(3);
    const checksum = p.deformer.rigChecksum(trained.operator);
    expect(checksum).toMatch(/^[0-9a-f]{16}$/);
    expect(session.data.events).toContainEqual({ rig: { checksum } });

    // On another posing of the shape with the rig loaded: the same bits, the rig posing.
    const { posing: q } = posed(300);
    const points = q.handles.map((h) => h.point);
    q.rig = new Rig(trained.operator, q.shape.mesh, points, { radius: trained.radius, options: {}, source: "file" });
    let steps = 0;
    await q.replay(parseSession(session.json), q.shape, async (n) => ((steps = n), true));
    expect(bits(q.deformer.positions())).toBe(bits(pose));
    expect(steps).toBe(kinds.filter((k) => k === "rigPose").length);
    expect(q.settings.method).toBe("defop");
    expect(q.posingWithRig).toBe(true);
    // Nothing moves after: the handles stay where the rig's pose is for.
    expect(q.advance(noTimings())).toBe(0);

    // Without the rig: refused, saying which rig, nothing changed.
    const { posing: r } = posed(300);
    const before = r.deformer.positions();
    await expect(r.replay(parseSession(session.json), r.shape, async () => true)).rejects.toThrow(
      new RegExp(`checksum ${checksum}.*Open rig`),
    );
    expect(bits(r.deformer.positions())).toBe(bits(before));
    trained.operator.free();
  });
});
