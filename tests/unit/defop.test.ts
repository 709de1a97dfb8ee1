/**
 * Deformation operators through the real wasm package in Node: a trained operator is the
 * identity at the rest targets and puts its handles exactly on any targets; the ground
 * truth of a rigid motion of the handles is that rigid motion; a canonical operator moves
 * rigidly with its handles and a fixed handle stays at rest, in wasm and in the wasm-free
 * reader alike (which also reads files of versions 1 to 3); a file keeps its training's
 * settings, in double or single precision; the regions training sampled hold its targets;
 * bad input throws with a code.
 */
import { readFileSync } from "node:fs";
import { beforeAll, describe, expect, it } from "vitest";
import {
  DefOp,
  DefOpSolver,
  DefOpTrainer,
  defaultShape,
  groundTruth,
  importPuppet,
  init,
  readOperatorFile,
  triangulate,
} from "../../www/src/index.js";

beforeAll(async () => {
  await init();
});

const mesh = () => triangulate(defaultShape(), { targetEdgeLength: 0.12 });

/** The extent of coordinate `c` (0: x, 1: y) of flat positions. */
function extent(positions: Float64Array, c: number): number {
  const values = positions.filter((_, i) => i % 2 === c);
  return Math.max(...values) - Math.min(...values);
}

/** Positions of the handle vertices, flat. */
function at(positions: Float64Array, handles: number[]): number[] {
  return handles.flatMap((v) => [positions[2 * v]!, positions[2 * v + 1]!]);
}

describe("DefOp", () => {
  it("trains in time slices to an operator that keeps the rest pose and hits its handles", () => {
    const m = mesh();
    const handles = [0, Math.floor(m.vertexCount / 2), m.vertexCount - 1];
    const trainer = new DefOpTrainer(m.positions, m.triangles, handles, { energy: "arap", samples: 10, seed: 3 });
    expect(trainer.progress()).toEqual({ done: 0, total: 11, stage: "samples" });
    expect(() => trainer.finish()).toThrow(/not done: 0 of 11/);
    let slices = 0;
    while (trainer.advance(5).stage !== "done") slices++;
    expect(slices).toBeGreaterThan(0);
    const stats = trainer.stats();
    expect(stats.cold + stats.warm).toBe(10);
    expect(stats.cold).toBe(7); // 2n + 1 from the rest pose, the rest warm
    const op: DefOp = trainer.finish();
    expect(() => trainer.progress()).toThrow(/freed or finished/);
    expect([op.handleCount, op.vertexCount]).toEqual([3, m.vertexCount]);

    const rest = at(m.positions, handles);
    const identity = op.evaluate(rest);
    identity.forEach((x, i) => expect(Math.abs(x - m.positions[i]!)).toBeLessThan(1e-9));
    // Far outside the training discs, the handles still land on their targets.
    const far = rest.map((x, i) => x + [0.5, -0.3, 0.2, 0.6, -0.4, 0.1][i]!);
    const out = new Float64Array(2 * m.vertexCount);
    op.evaluateInto(far, out);
    at(out, handles).forEach((x, i) => expect(Math.abs(x - far[i]!)).toBeLessThan(1e-9));
    expect(() => op.evaluateInto(far, new Float64Array(3))).toThrow(/out has 3 numbers/);
    const single = new Float32Array(2 * m.vertexCount);
    op.evaluateIntoF32(far, single);
    // Computed in single precision (not the double pose rounded): within the error its
    // documentation states, 5e-7 of the bounding box's diagonal (measured: 3.7e-7).
    const diagonal = Math.hypot(...[0, 1].map((c) => extent(m.positions, c)));
    const errors = [...single].map((x, i) => Math.abs(x - out[i]!));
    expect(Math.max(...errors)).toBeLessThan(5e-7 * diagonal);
    expect(errors.filter((e, i) => single[i] !== Math.fround(out[i]!)).length).toBeGreaterThan(0);
    expect(() => op.evaluate([1, 2])).toThrow();
    op.free();
    expect(() => op.evaluate(far)).toThrow(/freed/);
  });

  it("saves and loads operators, and the wasm-free reader poses as the wasm does", () => {
    const m = mesh();
    const handles = [2, m.vertexCount - 3];
    for (const options of [
      { basis: "tps" as const },
      { basis: "quadratic" as const, samples: 20 },
      { basis: "cubic" as const, samples: 40 },
      { basis: "tps" as const, spatial: 20 },
    ]) {
      const trainer = new DefOpTrainer(m.positions, m.triangles, handles, { energy: "arap", samples: 8, ...options });
      while (trainer.advance(50).stage !== "done");
      const op = trainer.finish();
      const bytes = op.toBytes();
      const loaded = DefOp.fromBytes(bytes);
      const plain = readOperatorFile(bytes);
      expect(loaded.mesh().positions).toEqual(m.positions);
      expect([...plain.triangles]).toEqual([...m.triangles]);
      const out = new Float64Array(2 * m.vertexCount);
      for (let k = 0; k < 4; k++) {
        const q = [...plain.rest].map((x, i) => x + 0.1 * Math.sin(3 * k + i));
        const expected = op.evaluate(q);
        expect(loaded.evaluate(q)).toEqual(expected);
        plain.evaluateInto(q, out);
        out.forEach((x, i) => expect(Math.abs(x - expected[i]!)).toBeLessThan(1e-12));
      }
      // A damaged file: refused by both readers.
      const damaged = bytes.slice();
      damaged[100] = damaged[100]! ^ 1;
      expect(() => DefOp.fromBytes(damaged)).toThrow(/checksum/);
      expect(() => readOperatorFile(damaged)).toThrow(/checksum/);
      expect(() => readOperatorFile(bytes.subarray(0, bytes.length - 1))).toThrow(/bytes where/);
      op.free();
      loaded.free();
    }
  });

  it("canonical operators move rigidly with their handles, fixed handles stay, and the wasm-free reader agrees", () => {
    const m = mesh();
    const handles = [2, 40, m.vertexCount - 3];
    const rest = at(m.positions, handles);
    const move = (flat: ArrayLike<number>, angle: number, t: [number, number]) => {
      const [c, s] = [Math.cos(angle), Math.sin(angle)];
      return Array.from({ length: flat.length }, (_, i) => {
        const [x, y] = [flat[i - (i % 2)]!, flat[i - (i % 2) + 1]!];
        return i % 2 === 0 ? c * x - s * y + t[0] : s * x + c * y + t[1];
      });
    };
    const worst = (a: ArrayLike<number>, b: ArrayLike<number>) =>
      Array.from(a).reduce((w, x, i) => Math.max(w, Math.abs(x - b[i]!)), 0);
    const out = new Float64Array(2 * m.vertexCount);
    for (const options of [
      { basis: "tps" as const, canonical: true },
      { basis: "linear" as const, canonical: true },
      { basis: "tps" as const, spatial: 20, canonical: true },
      { basis: "quadratic" as const, samples: 20, fixed: [1] },
    ]) {
      const trainer = new DefOpTrainer(m.positions, m.triangles, handles, { energy: "arap", samples: 8, ...options });
      while (trainer.advance(50).stage !== "done");
      const op = trainer.finish();
      const plain = readOperatorFile(op.toBytes());
      expect(plain.canonical).toBe(options.canonical === true);
      expect([...plain.fixed]).toEqual(options.fixed ?? []);
      for (let k = 0; k < 4; k++) {
        const q = rest.map((x, i) => x + 0.3 * Math.sin(3 * k + 1.7 * i));
        const t: [number, number] = [Math.cos(k), 2 * Math.sin(k)];
        for (const targets of [q, move(q, 1.1 * k - 2, t)]) {
          const expected = op.evaluate(targets);
          plain.evaluateInto(targets, out);
          expect(worst(out, expected)).toBeLessThan(1e-12);
        }
        if (options.canonical) {
          // A rigid motion of the rest handles moves the shape rigidly.
          expect(worst(op.evaluate(move(rest, 1.1 * k - 2, t)), move(m.positions, 1.1 * k - 2, t))).toBeLessThan(1e-9);
        } else {
          // Handle 1 is fixed: its target is ignored, and it stays at rest.
          const posed = op.evaluate(q);
          expect(worst(at(posed, [handles[1]!]), rest.slice(2, 4))).toBeLessThan(1e-9);
          expect(worst(at(posed, [handles[0]!, handles[2]!]), [...q.slice(0, 2), ...q.slice(4)])).toBeLessThan(1e-9);
        }
      }
      op.free();
    }
    expect(() => new DefOpTrainer(m.positions, m.triangles, handles, { canonical: true, fixed: [0] })).toThrow(
      /cannot be combined/,
    );
    expect(
      () => new DefOpTrainer(m.positions, m.triangles, handles, { canonical: "yes" as unknown as boolean }),
    ).toThrow(/canonical/);
  });

  it("trains on a puppet, whose operator and file record it, the free hat held still", () => {
    const puppet = importPuppet(readFileSync("tests/fixtures/svg/layered-puppet.svg", "utf8"), { vertices: 300 });
    expect(puppet.parts.map((p) => p.name)).toEqual(["Torso", "Head", "Arm", "Hat"]);
    const first = (part: number) => puppet.triangles[3 * puppet.parts[part]!.triangles[0]!]!;
    const last = (part: number) => {
      const t = puppet.parts[part]!.triangles;
      return puppet.triangles[3 * t[t.length - 1]! + 2]!;
    };
    const handles = [first(0), last(0), last(2)];
    const { positions, triangles, parts, joints } = puppet;
    // A mesh in pieces needs its parts.
    expect(() => new DefOpTrainer(positions, triangles, handles, { samples: 6 })).toThrow(
      expect.objectContaining({ code: "invalid-mesh" }),
    );
    const trainer = new DefOpTrainer(positions, triangles, handles, { energy: "arap", samples: 8, parts, joints });
    while (trainer.advance(50).stage !== "done");
    const op = trainer.finish();
    const sheet = (p: { name: string; triangles: Uint32Array; depth: number }) => ({
      name: p.name,
      triangles: Array.from(p.triangles),
      depth: p.depth,
    });
    expect(op.parts!.map(sheet)).toEqual(parts.map(sheet));
    expect(op.joints).toEqual(joints);
    const bytes = op.toBytes();
    // Version 4 with the puppet flag.
    expect([bytes[8], bytes[49]]).toEqual([4, 1]);
    const plain = readOperatorFile(bytes);
    expect(plain.parts!.map(sheet)).toEqual(parts.map(sheet));
    expect(plain.joints).toEqual(joints);
    const again = DefOp.fromBytes(bytes);
    expect(again.parts!.map(sheet)).toEqual(parts.map(sheet));
    // Any targets: the two evaluators agree, and the hat, which no handle reaches, stays.
    const targets = at(positions, handles).map((x, i) => x + [3, -2, 1, 4, -5, 2][i]!);
    const posed = op.evaluate(targets);
    const out = new Float64Array(2 * plain.vertexCount);
    plain.evaluateInto(targets, out);
    out.forEach((x, i) => expect(Math.abs(x - posed[i]!)).toBeLessThan(1e-9));
    for (const t of parts[3]!.triangles) {
      for (let c = 0; c < 3; c++) {
        const v = triangles[3 * t + c]!;
        expect(Math.hypot(posed[2 * v]! - positions[2 * v]!, posed[2 * v + 1]! - positions[2 * v + 1]!)).toBeLessThan(
          1e-9,
        );
      }
    }
    expect(() => new DefOpTrainer(positions, triangles, handles, { samples: 6, joints })).toThrow(
      /joints were given without parts/,
    );
    [op, again].forEach((o) => o.free());
  });

  it("reads a version-1 operator file, with and without wasm", () => {
    // Written by the version-1 writer: a linear operator on the 2 × 2 grid, handles at
    // (0, 0) and (2, 2), exactly x + (1 − w)(q0 − p0) + w(q1 − p1), w = (x + y) / 4.
    const bytes = new Uint8Array(readFileSync("tests/fixtures/defop-v1-linear.defop"));
    const plain = readOperatorFile(bytes);
    const op = DefOp.fromBytes(bytes);
    const q = [0.3, -0.2, 2.5, 1.1];
    const out = new Float64Array(2 * plain.vertexCount);
    plain.evaluateInto(q, out);
    const expected = Array.from(plain.positions, (x, i) => {
      const [px, py] = [plain.positions[i - (i % 2)]!, plain.positions[i - (i % 2) + 1]!];
      const w = (px + py) / 4;
      const nu = i % 2;
      return x + (1 - w) * q[nu]! + w * (q[2 + nu]! - 2);
    });
    out.forEach((x, i) => expect(Math.abs(x - expected[i]!)).toBeLessThan(1e-12));
    op.evaluate(q).forEach((x, i) => expect(Math.abs(x - expected[i]!)).toBeLessThan(1e-12));
    op.free();
  });

  it("reads version-2 and version-3 files (written by those writers), the training not known", () => {
    // Version 2: handles at (0, 0), (2, 2) and (2, 0), the last fixed; exactly
    // x + (1 − x/2)(q0 − p0) + (y/2)(q1 − p1), whatever the fixed handle's target.
    const v2 = new Uint8Array(readFileSync("tests/fixtures/defop-v2-fixed.defop"));
    const q = [0.3, -0.2, 2.5, 1.1, 9, -9];
    const plain = readOperatorFile(v2);
    const op = DefOp.fromBytes(v2);
    expect([plain.training, op.training, plain.precision, [...plain.fixed]]).toEqual([
      undefined,
      undefined,
      "double",
      [2],
    ]);
    const out = new Float64Array(2 * plain.vertexCount);
    plain.evaluateInto(q, out);
    const expected = Array.from(plain.positions, (x, i) => {
      const [px, py] = [plain.positions[i - (i % 2)]!, plain.positions[i - (i % 2) + 1]!];
      const nu = i % 2;
      return x + (1 - px / 2) * q[nu]! + (py / 2) * (q[2 + nu]! - 2);
    });
    out.forEach((x, i) => expect(Math.abs(x - expected[i]!)).toBeLessThan(1e-12));
    op.evaluate(q).forEach((x, i) => expect(Math.abs(x - expected[i]!)).toBeLessThan(1e-12));
    // Version 3: two squares, each translated by its handle, joined at (0.75, 0.5).
    const v3 = new Uint8Array(readFileSync("tests/fixtures/defop-v3-puppet.defop"));
    const puppet = readOperatorFile(v3);
    const rig = DefOp.fromBytes(v3);
    expect(puppet.parts!.map((p) => [p.name, [...p.triangles], p.depth])).toEqual([
      ["left", [0, 1], 0],
      ["right", [2, 3], 1],
    ]);
    expect(puppet.joints).toEqual([{ point: [0.75, 0.5], parts: [1, 0] }]);
    expect(rig.joints).toEqual(puppet.joints);
    expect([puppet.training, rig.training]).toEqual([undefined, undefined]);
    const moved = [0.3, -0.2, 1, 0.75];
    const posed = new Float64Array(16);
    puppet.evaluateInto(moved, posed);
    posed.forEach((x, i) => {
      const shift = (i < 8 ? [0.3, -0.2] : [-0.5, 0.5])[i % 2]!;
      expect(Math.abs(x - (puppet.positions[i]! + shift))).toBeLessThan(1e-12);
    });
    // Written again: version 4, its puppet kept, still no training.
    const again = readOperatorFile(rig.toBytes());
    expect([again.parts?.length, again.training]).toEqual([2, undefined]);
    [op, rig].forEach((o) => o.free());
  });

  it("keeps the training's settings in its file, in double or single precision, with and without wasm", () => {
    const m = mesh();
    const handles = [2, 40, m.vertexCount - 3];
    const trainer = new DefOpTrainer(m.positions, m.triangles, handles, {
      energy: "arap",
      samples: 16,
      sampling: "mixed",
      spatial: 20,
      seed: 4,
      fixed: [1],
      basis: "quadratic",
    });
    const radius = trainer.radius;
    while (trainer.advance(50).stage !== "done");
    const op = trainer.finish();
    const training = {
      energy: "arap",
      basis: "quadratic",
      spatial: 20,
      samples: 16,
      sampling: "mixed",
      radius,
      seed: 4,
      canonical: false,
      fixed: new Uint32Array([1]),
    };
    expect(op.training).toEqual(training);
    const bytes = op.toBytes();
    const single = op.toBytes({ precision: "single" });
    // The coefficients (20 spatial functions × 2 × |Ψ|, |Ψ| = 1 + 4 + 10 in k = 4
    // coordinates) and D (20 × N) take 4 bytes each instead of 8.
    expect(bytes.length - single.length).toBe(4 * (20 * 2 * 15 + 20 * m.vertexCount));
    for (const file of [bytes, single]) {
      expect(DefOp.fromBytes(file).training).toEqual(training);
      expect(readOperatorFile(file).training).toEqual(training);
    }
    expect([readOperatorFile(bytes).precision, readOperatorFile(single).precision]).toEqual(["double", "single"]);
    // Single precision: the wasm and the wasm-free readers pose alike, near the double operator.
    const fromSingle = DefOp.fromBytes(single);
    const plain = readOperatorFile(single);
    const rest = at(m.positions, handles);
    const q = rest.map((x, i) => x + 0.1 * Math.sin(i));
    const out = new Float64Array(2 * m.vertexCount);
    plain.evaluateInto(q, out);
    const [exact, rounded] = [op.evaluate(q), fromSingle.evaluate(q)];
    out.forEach((x, i) => expect(Math.abs(x - rounded[i]!)).toBeLessThan(1e-12));
    const off = rounded.reduce((w, x, i) => Math.max(w, Math.abs(x - exact[i]!)), 0);
    expect(off).toBeGreaterThan(0);
    expect(off).toBeLessThan(1e-4);
    expect(() => op.toBytes({ precision: "half" as "single" })).toThrow(
      expect.objectContaining({ code: "invalid-option" }),
    );
    [op, fromSingle].forEach((o) => o.free());
  });

  it("gives the regions its training drew targets from, and which targets lie outside them", () => {
    const m = mesh();
    const handles = [2, m.vertexCount - 3];
    const rest = at(m.positions, handles);
    const xs = Array.from(m.positions).filter((_, i) => i % 2 === 0);
    const ys = Array.from(m.positions).filter((_, i) => i % 2 === 1);
    for (const sampling of ["disc", "voronoi", "mixed"] as const) {
      const trainer = new DefOpTrainer(m.positions, m.triangles, handles, { energy: "arap", samples: 6, sampling });
      const radius = trainer.radius;
      while (trainer.advance(50).stage !== "done");
      const op = trainer.finish();
      const regions = op.regions();
      expect([regions.sampling, regions.radius, [...regions.centres]]).toEqual([sampling, radius, rest]);
      expect(regions.discs).toBe(sampling !== "voronoi");
      expect(regions.cells?.length).toBe(sampling === "disc" ? undefined : 2);
      // Two handles: each cell is its half of the box grown by the radius, cut by the
      // perpendicular bisector of the two rest handles. Every corner is on the box or the
      // bisector, and nearer its own handle (or as near).
      const box = [
        Math.min(...xs) - radius,
        Math.min(...ys) - radius,
        Math.max(...xs) + radius,
        Math.max(...ys) + radius,
      ];
      regions.cells?.forEach((cell, l) => {
        for (let k = 0; k < cell.length; k += 2) {
          const [x, y] = [cell[k]!, cell[k + 1]!];
          const d = (h: number) => Math.hypot(x - rest[2 * h]!, y - rest[2 * h + 1]!);
          const onBox = [x - box[0]!, y - box[1]!, box[2]! - x, box[3]! - y].some((e) => Math.abs(e) < 1e-9);
          expect(onBox || Math.abs(d(0) - d(1)) < 1e-9).toBe(true);
          expect(d(l)).toBeLessThanOrEqual(d(1 - l) + 1e-9);
        }
      });
      // At rest inside; a step of 1.05 radius from handle 0 away from handle 1 is outside
      // its disc but (within the box) inside its cell; far beyond the box, outside both.
      expect([...op.outsideRegions(rest)]).toEqual([0, 0]);
      const away = [rest[0]! - rest[2]!, rest[1]! - rest[3]!];
      const length = Math.hypot(away[0]!, away[1]!);
      const step = [rest[0]! + (1.05 * radius * away[0]!) / length, rest[1]! + (1.05 * radius * away[1]!) / length];
      const inBox = step[0]! >= box[0]! && step[0]! <= box[2]! && step[1]! >= box[1]! && step[1]! <= box[3]!;
      expect(inBox).toBe(true);
      expect([...op.outsideRegions([...step, rest[2]!, rest[3]!])]).toEqual([sampling === "disc" ? 1 : 0, 0]);
      expect([...op.outsideRegions([box[0]! - 1, rest[1]!, ...rest.slice(2)])]).toEqual([1, 0]);
      expect(() => op.outsideRegions([0, 0])).toThrow(/2 handles/);
      op.free();
    }
  });

  it("trains the same operator with jobs solved by workers' solvers, in any order", () => {
    const m = mesh();
    const handles = [2, 40, m.vertexCount - 3];
    const options = { energy: "sarap" as const, samples: 12, seed: 5 };
    const here = new DefOpTrainer(m.positions, m.triangles, handles, options);
    while (here.advance(50).stage !== "done");
    const expected = here.finish();

    const trainer = new DefOpTrainer(m.positions, m.triangles, handles, options);
    const workers = [0, 1].map(() => new DefOpSolver(m.positions, m.triangles, handles, { energy: "sarap" }));
    let rounds = 0;
    while (trainer.progress().stage !== "done" && rounds++ < 100) {
      const jobs = trainer.nextJobs(4).reverse();
      jobs.forEach((job, k) => {
        // As a worker would get it: a structured clone.
        const copy = structuredClone(job);
        try {
          trainer.submit(workers[k % 2]!.solve(copy));
        } catch (error) {
          trainer.reject(job.index, error);
        }
      });
    }
    expect(() => trainer.reject(0, new Error("x"))).toThrow(/training cannot go on/);
    const op = trainer.finish();
    for (let k = 0; k < 3; k++) {
      const q = handles.flatMap((v, i) => [m.positions[2 * v]! + 0.05 * Math.sin(k + i), m.positions[2 * v + 1]!]);
      expect(op.evaluate(q)).toEqual(expected.evaluate(q));
    }
    workers.forEach((w) => w.free());
  });

  it("solves the ground truth, which is the rigid motion for rigid targets", () => {
    const m = mesh();
    const handles = [3, m.vertexCount - 5];
    const [c, s] = [Math.cos(0.4), Math.sin(0.4)];
    const move = (x: number, y: number) => [c * x - s * y + 0.2, s * x + c * y - 0.1];
    const targets = handles.flatMap((v) => move(m.positions[2 * v]!, m.positions[2 * v + 1]!));
    for (const energy of ["arap", "sarap"] as const) {
      const posed = groundTruth(m.positions, m.triangles, handles, targets, { energy });
      for (let v = 0; v < m.vertexCount; v++) {
        const [x, y] = move(m.positions[2 * v]!, m.positions[2 * v + 1]!);
        expect(Math.abs(posed[2 * v]! - x!)).toBeLessThan(1e-8);
        expect(Math.abs(posed[2 * v + 1]! - y!)).toBeLessThan(1e-8);
      }
    }
  });

  it("refuses bad input with codes", () => {
    const m = mesh();
    const code = (call: () => unknown) => {
      try {
        call();
      } catch (error) {
        return (error as { code?: string }).code;
      }
      return "no error";
    };
    expect(code(() => new DefOpTrainer(m.positions, m.triangles, [0, 1], { basis: "quartic" as "tps" }))).toBe(
      "invalid-option",
    );
    expect(code(() => new DefOpTrainer(m.positions, m.triangles, [0, 1], { sampels: 5 } as object))).toBe(
      "invalid-option",
    );
    expect(code(() => new DefOpTrainer(m.positions, m.triangles, [0, 0]))).toBe("invalid-argument");
    expect(code(() => new DefOpTrainer(m.positions, m.triangles, [m.vertexCount]))).toBe("invalid-argument");
    expect(code(() => new DefOpTrainer(m.positions, m.triangles, [0], { samples: 1e6 }))).toBe("invalid-option");
    expect(code(() => groundTruth(m.positions, m.triangles, [0, 5], [0, 0, NaN, 1]))).toBe("invalid-argument");
  });
});
