/**
 * `trainDefOp` where there are no workers (Node): the training runs on this thread in
 * slices and gives the very operator `DefOpTrainer.advance` gives; progress only grows and
 * ends done, with times; an abort stops it with the signal's reason; handles at points in
 * triangles train as `setHandlePoints` does; `handlePoints` gives an operator's handles back.
 * (The worker pool itself runs in the browser tests.)
 */
import { beforeAll, describe, expect, it } from "vitest";
import { DefOpTrainer, defaultShape, init, trainDefOp, triangulate, type TrainProgress } from "../../www/src/index.js";

beforeAll(async () => {
  await init();
});

const mesh = () => triangulate(defaultShape(), { targetEdgeLength: 0.14 });

describe("trainDefOp", () => {
  it("trains on this thread to the operator advance() trains, reporting progress", async () => {
    const m = mesh();
    const handles = [0, Math.floor(m.vertexCount / 3), m.vertexCount - 1];
    const options = { energy: "arap", samples: 12, seed: 5 } as const;
    const reference = new DefOpTrainer(m.positions, m.triangles, handles, options);
    const radius = reference.radius;
    while (reference.advance(50).stage !== "done");
    const expected = reference.finish().toBytes();

    const seen: TrainProgress[] = [];
    const trained = await trainDefOp(m.positions, m.triangles, handles, options, {
      onProgress: (p) => seen.push(p),
      sliceMs: 1,
    });
    expect(trained.workers).toBe(0);
    expect(trained.radius).toBe(radius);
    expect(trained.stats.cold + trained.stats.warm).toBe(12);
    expect(Buffer.from(trained.operator.toBytes()).equals(Buffer.from(expected))).toBe(true);
    expect(seen.length).toBeGreaterThan(2);
    expect(seen.at(-1)).toMatchObject({ done: 13, total: 13, stage: "done", remainingMs: 0 });
    for (let i = 1; i < seen.length; i++) {
      expect(seen[i]!.done).toBeGreaterThanOrEqual(seen[i - 1]!.done);
      expect(seen[i]!.elapsedMs).toBeGreaterThanOrEqual(seen[i - 1]!.elapsedMs);
    }
    expect(seen.some((p) => p.remainingMs !== undefined && p.remainingMs > 0)).toBe(true);
    trained.operator.free();
  });

  it("stops when aborted, with the signal's reason", async () => {
    const m = mesh();
    const controller = new AbortController();
    let reports = 0;
    const training = trainDefOp(
      m.positions,
      m.triangles,
      [0, 5],
      { samples: 400 },
      {
        sliceMs: 1,
        signal: controller.signal,
        onProgress: () => {
          if (++reports === 3) controller.abort();
        },
      },
    );
    await expect(training).rejects.toMatchObject({ name: "AbortError" });
    expect(reports).toBe(3);
    const aborted = AbortSignal.abort(new Error("not now"));
    await expect(trainDefOp(m.positions, m.triangles, [0], {}, { signal: aborted })).rejects.toThrow("not now");
  });

  it("trains handles at points in triangles, and the operator gives them back", async () => {
    const m = mesh();
    const points = { triangles: [0, 7], barycentric: [0.2, 0.3, 0.5, 1 / 3, 1 / 3, 1 / 3] };
    const { operator } = await trainDefOp(m.positions, m.triangles, points, { samples: 6, energy: "arap" });
    const back = operator.handlePoints();
    expect(Array.from(back.triangles)).toEqual(points.triangles);
    back.barycentric.forEach((b, i) => expect(b).toBe(points.barycentric[i]));
    // A vertex handle comes back as a corner of a triangle that has the vertex.
    const v = 4;
    const { operator: atVertex } = await trainDefOp(m.positions, m.triangles, [v], { samples: 2, energy: "arap" });
    const corner = atVertex.handlePoints();
    const t = corner.triangles[0]!;
    const weights = Array.from(corner.barycentric);
    const k = weights.indexOf(1);
    expect(weights.filter((w) => w === 0)).toHaveLength(2);
    expect(m.triangles[3 * t + k]).toBe(v);
    await expect(trainDefOp(m.positions, m.triangles, [0], {}, { workers: -1 })).rejects.toMatchObject({
      code: "invalid-argument",
    });
  });
});
