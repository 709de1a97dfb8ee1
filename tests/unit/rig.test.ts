/**
 * The widget's rigs in Node: a rig fits only its own rest mesh (by content) and its handle
 * points in order; its cache key changes with the mesh, a handle or an option and with
 * nothing else (the sampling among the options); a rig file read back poses as the
 * operator it was written from and keeps its training's energy, and a damaged file is
 * refused with code `import`.
 */
import { beforeAll, describe, expect, it } from "vitest";
import { defaultShape, init, trainDefOp, triangulate } from "../../www/src/index.js";
import { Rig, rigKey } from "../../www/src/widget/model/rig.js";
import { shapeFromMesh } from "../../www/src/widget/model/shape.js";
import type { MeshPoint } from "../../www/src/widget/model/picking.js";

beforeAll(async () => {
  await init();
});

describe("Rig", () => {
  it("fits its own mesh and handles only, keys by content, and reads back from its file", async () => {
    const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.15 });
    const points: MeshPoint[] = [
      { triangle: 0, barycentric: [0.2, 0.3, 0.5] },
      { triangle: 9, barycentric: [1, 0, 0] },
    ];
    const spec = { triangles: points.map((p) => p.triangle), barycentric: points.flatMap((p) => p.barycentric) };
    const { operator, radius } = await trainDefOp(mesh.positions, mesh.triangles, spec, { samples: 4, energy: "arap" });
    const rig = new Rig(operator, mesh, points, { radius, options: { samples: 4 }, source: "trained" });
    const handles = points.map((point) => ({ point }));

    // A copy of the mesh (another object, the same numbers) fits; moved or reordered handles do not.
    const copy = shapeFromMesh({ ...mesh, positions: mesh.positions.slice() }, undefined);
    expect(rig.fits(copy, handles)).toBe(true);
    expect(rig.fits(copy, [...handles].reverse())).toBe(false);
    expect(rig.fits(copy, handles.slice(0, 1))).toBe(false);
    const nudged = [handles[0]!, { point: { triangle: 9, barycentric: [0.5, 0.5, 0] as [number, number, number] } }];
    expect(rig.fits(copy, nudged)).toBe(false);
    const moved = mesh.positions.slice();
    moved[0]! += 1e-12;
    expect(rig.fits(shapeFromMesh({ ...mesh, positions: moved }, undefined), handles)).toBe(false);

    const key = await rigKey(mesh, points, { samples: 4, energy: "arap" });
    expect(key).toMatch(/^[0-9a-f]{64}$/);
    expect(await rigKey(mesh, points, { energy: "arap", samples: 4 })).toBe(key);
    expect(await rigKey(mesh, points, { samples: 5, energy: "arap" })).not.toBe(key);
    expect(await rigKey(mesh, points, { samples: 4, energy: "arap", sampling: "voronoi" })).not.toBe(key);
    expect(await rigKey(mesh, points.slice().reverse(), { samples: 4, energy: "arap" })).not.toBe(key);
    expect(await rigKey({ ...mesh, positions: moved }, points, { samples: 4, energy: "arap" })).not.toBe(key);

    // The file: the same handles and mesh, and the same poses.
    const bytes = rig.toBytes();
    const back = Rig.fromBytes(bytes);
    expect(back.source).toBe("file");
    expect(back.radius).toBe(radius);
    expect(back.options).toBeUndefined();
    // The file keeps the training's settings: Compare solves with its energy, ARAP.
    expect(back.training).toMatchObject({ energy: "arap", samples: 4, sampling: "disc", radius });
    expect(back.energy).toBe("arap");
    expect(back.points).toEqual(points);
    expect(back.fits(copy, handles)).toBe(true);
    const targets = handles.flatMap((_, i) => [0.1 * i, -0.2 + 0.3 * i]);
    const [a, b] = [new Float64Array(2 * mesh.vertexCount), new Float64Array(2 * mesh.vertexCount)];
    rig.operator.evaluateInto(targets, a);
    back.operator.evaluateInto(targets, b);
    expect(Array.from(b)).toEqual(Array.from(a));
    expect(Array.from(back.restHandles()).length).toBe(4);

    const damaged = bytes.slice();
    damaged[100]! ^= 1;
    expect(() => Rig.fromBytes(damaged)).toThrow(expect.objectContaining({ code: "import" }));
    expect(() => Rig.fromBytes(bytes.subarray(0, 40))).toThrow(expect.objectContaining({ code: "import" }));
    rig.free();
    back.free();
  });
});
