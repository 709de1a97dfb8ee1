/** A posing of the default figure with two handles, and a drag as the pointer makes it (posing and stiffness tests). */
import { expect } from "vitest";
import { builtinShape, trainDefOp, type Trained } from "../../www/src/index.js";
import { widgetSettings } from "../../www/src/widget/options.js";
import { locate } from "../../www/src/widget/model/picking.js";
import { Posing } from "../../www/src/widget/model/posing.js";
import { Rig } from "../../www/src/widget/model/rig.js";
import { meshOutline } from "../../www/src/widget/model/shape.js";
import { noTimings } from "./fixtures.js";

/** A posing of the default figure with a pin at its lowest vertex and a handle at its rightmost. */
export function posed(vertices = 800): { posing: Posing; calls: string[] } {
  const calls: string[] = [];
  const posing = new Posing(widgetSettings({ vertices }), {
    adopted: () => calls.push("adopted"),
    methodChanged: (method) => calls.push(`method ${method}`),
    handlesChanged: (count) => calls.push(`handles ${count}`),
    poseChanged: () => calls.push("pose"),
    historyChanged: () => calls.push("history"),
    schedule: () => undefined,
  });
  posing.install(meshOutline(builtinShape("gingerbread"), "gingerbread", vertices, 28));
  const p = posing.shape.mesh.positions;
  let low = 0;
  let right = 0;
  for (let v = 0; v < p.length / 2; v++) {
    if (p[2 * v + 1]! < p[2 * low + 1]!) low = v;
    if (p[2 * v]! > p[2 * right]!) right = v;
  }
  posing.addHandle(locate(p, posing.shape.mesh.triangles, p[2 * low]!, p[2 * low + 1]!, 1e-9)!);
  // The second handle inside a triangle at the right end, so that both solves run.
  const t = posing.shape.mesh.triangles;
  const triangle = Array.from({ length: t.length / 3 }, (_, f) => f).find((f) =>
    [t[3 * f], t[3 * f + 1], t[3 * f + 2]].includes(right),
  )!;
  posing.addHandle({ triangle, barycentric: [1 / 3, 1 / 3, 1 / 3] });
  return { posing, calls };
}

/** Drags handle 1 to `target` as the pointer would, running frames until it stops moving. */
export function dragTo(posing: Posing, target: [number, number]): void {
  const [x, y] = Array.from(posing.deformer.handlePositions()).slice(2, 4) as [number, number];
  posing.beginGesture();
  expect(posing.grab(1, 7, x, y, false)).toBe(true);
  posing.drag(7, ...target);
  for (let frame = 0; frame < 100 && posing.advance(noTimings()) > 0; frame++) posing.markChanged();
  posing.release(7);
}

/**
 * A rig for the posing's shape and handles, trained quickly (6 samples, ARAP), made the
 * posing's rig; the method stays the posing's (choose "defop" to pose with it).
 */
export async function trainedRig(posing: Posing): Promise<Trained> {
  const { mesh } = posing.shape;
  const points = posing.handles.map((h) => h.point);
  const trained = await trainDefOp(
    mesh.positions,
    mesh.triangles,
    { triangles: points.map((p) => p.triangle), barycentric: points.flatMap((p) => p.barycentric) },
    { samples: 6, energy: "arap" },
  );
  posing.rig = new Rig(trained.operator, mesh, points, { radius: trained.radius, options: {}, source: "trained" });
  return trained;
}
