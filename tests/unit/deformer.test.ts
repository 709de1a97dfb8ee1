/** The Deformer through the real wasm package in Node: rigid motions and bad input. */
import { readFileSync } from "node:fs";
import { beforeAll, describe, expect, it } from "vitest";
import {
  Deformer,
  defaultShape,
  deformerOrders,
  importPuppet,
  init,
  triangulate,
  type ImportedPuppet,
  type PuppetJoint,
} from "../../www/src/index.js";

beforeAll(async () => {
  await init();
});

describe("Deformer", () => {
  it("takes orders made beforehand (as a worker would) and poses exactly as without them", () => {
    const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.08 });
    for (const options of [{}, { method: "arap" as const }]) {
      const orders = deformerOrders(mesh.positions, mesh.triangles, options);
      expect(orders.length).toBe(options.method === "arap" ? 1 : 2);
      expect(orders[0]!.length).toBe(mesh.vertexCount);
      const pose = (deformer: Deformer) => {
        deformer.setHandles([0, 60]);
        for (let k = 0; k < 3; k++) deformer.step([0, 0, 0.02, -0.01]);
        const p = deformer.positions();
        deformer.free();
        return p;
      };
      // The same orders as the constructor computes itself: the same factorisation, bit for bit.
      expect(pose(new Deformer(mesh.positions, mesh.triangles, options, orders))).toEqual(
        pose(new Deformer(mesh.positions, mesh.triangles, options)),
      );
      const broken = orders.map((o) => o.slice(1));
      expect(() => new Deformer(mesh.positions, mesh.triangles, options, broken)).toThrow(/permutation of 0\.\./);
    }
  });

  it("moving least squares: handles given a rigid motion move the whole shape by it; bad steps change nothing", () => {
    const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.08 });
    // MLS solves no system: no orders to compute.
    expect(deformerOrders(mesh.positions, mesh.triangles, { method: "mls" })).toEqual([]);
    const deformer = new Deformer(mesh.positions, mesh.triangles, { method: "mls" });
    expect(deformer.method).toBe("mls");
    deformer.setHandles([0, 40, 80]);
    const [a, tx, ty] = [0.9, 0.3, -0.2];
    const [s, c] = [Math.sin(a), Math.cos(a)];
    const rigid = (x: number, y: number) => [c * x - s * y + tx, s * x + c * y + ty] as const;
    const h = deformer.handlePositions();
    const velocities: number[] = [];
    for (let i = 0; i < h.length; i += 2) {
      const [x, y] = rigid(h[i]!, h[i + 1]!);
      velocities.push(x - h[i]!, y - h[i + 1]!);
    }
    deformer.step(velocities);
    const p = deformer.positions();
    for (let v = 0; v < mesh.vertexCount; v++) {
      const [x, y] = rigid(mesh.positions[2 * v]!, mesh.positions[2 * v + 1]!);
      expect(p[2 * v]!).toBeCloseTo(x, 10);
      expect(p[2 * v + 1]!).toBeCloseTo(y, 10);
    }
    // The affine variant with two handles: the map is not determined; nothing moves.
    deformer.setOptions({ variant: "affine" });
    deformer.setHandles([0, 40]);
    let code = "";
    try {
      deformer.step([0.1, 0, 0, 0.1]);
    } catch (e) {
      code = (e as { code: string }).code;
    }
    expect(code).toBe("invalid-argument");
    expect(deformer.positions()).toEqual(p);
    deformer.free();
  });

  it("Cauchy-Green: two handles give the similarity that takes them to their targets; a bad cage count changes nothing", () => {
    const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.08 });
    expect(deformerOrders(mesh.positions, mesh.triangles, { method: "cauchy-green" })).toEqual([]);
    const deformer = new Deformer(mesh.positions, mesh.triangles, { method: "cauchy-green", cage: 48 });
    expect(deformer.method).toBe("cauchy-green");
    // The cage: 48 vertices, every vertex of the mesh inside it (even-odd crossings).
    const rest = deformer.cage()!;
    expect(rest.length).toBe(96);
    const inside = (x: number, y: number) => {
      let odd = false;
      for (let i = 0, j = rest.length - 2; i < rest.length; j = i, i += 2) {
        const [ax, ay, bx, by] = [rest[i]!, rest[i + 1]!, rest[j]!, rest[j + 1]!];
        if (ay > y !== by > y && x < ax + ((y - ay) / (by - ay)) * (bx - ax)) odd = !odd;
      }
      return odd;
    };
    for (let v = 0; v < mesh.vertexCount; v++)
      expect(inside(mesh.positions[2 * v]!, mesh.positions[2 * v + 1]!)).toBe(true);
    deformer.setHandles([0, 40]);
    // z -> a z + b with a = 1.2 e^(0.5 i), b = 0.3 - 0.1 i.
    const [ar, ai] = [1.2 * Math.cos(0.5), 1.2 * Math.sin(0.5)];
    const similar = (x: number, y: number) => [ar * x - ai * y + 0.3, ai * x + ar * y - 0.1] as const;
    const h = deformer.handlePositions();
    const velocities: number[] = [];
    for (let i = 0; i < h.length; i += 2) {
      const [x, y] = similar(h[i]!, h[i + 1]!);
      velocities.push(x - h[i]!, y - h[i + 1]!);
    }
    deformer.step(velocities);
    const p = deformer.positions();
    for (let v = 0; v < mesh.vertexCount; v++) {
      const [x, y] = similar(mesh.positions[2 * v]!, mesh.positions[2 * v + 1]!);
      expect(p[2 * v]!).toBeCloseTo(x, 9);
      expect(p[2 * v + 1]!).toBeCloseTo(y, 9);
    }
    // The cage follows the same similarity.
    const moved = deformer.cage()!;
    for (let i = 0; i < rest.length; i += 2) {
      const [x, y] = similar(rest[i]!, rest[i + 1]!);
      expect(moved[i]!).toBeCloseTo(x, 9);
      expect(moved[i + 1]!).toBeCloseTo(y, 9);
    }
    const akap = new Deformer(mesh.positions, mesh.triangles);
    expect(akap.cage()).toBeUndefined();
    akap.free();
    expect(() => deformer.setOptions({ cage: 4 })).toThrow(/option cage is 4, expected a whole number from 8 to 1000/);
    expect(deformer.positions()).toEqual(p);
    deformer.free();
  });

  it("stiffness: 1 everywhere is the unpainted pose, bad values throw and change nothing, MLS refuses it", () => {
    const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.08 });
    const triangleCount = mesh.triangles.length / 3;
    const pose = (stiffness: number[] | undefined) => {
      const deformer = new Deformer(mesh.positions, mesh.triangles);
      deformer.setStiffness(stiffness);
      deformer.setHandles([0, 40]);
      deformer.step([0, 0, 0.05, 0.02]);
      const p = deformer.positions();
      deformer.free();
      return p;
    };
    expect(pose(new Array<number>(triangleCount).fill(1))).toEqual(pose(undefined));
    expect(pose(new Array<number>(triangleCount).fill(50))).not.toEqual(pose(undefined));
    const deformer = new Deformer(mesh.positions, mesh.triangles, { method: "arap" });
    const bad = new Array<number>(triangleCount).fill(1);
    bad[3] = 0;
    expect(() => deformer.setStiffness(bad)).toThrow(
      "the stiffness of triangle 3 is 0, expected a number from 0.001 to 1000",
    );
    expect(() => deformer.setStiffness([1, 2])).toThrow(/stiffness has 2 numbers/);
    deformer.setOptions({ method: "mls" });
    let code = "";
    try {
      deformer.setStiffness(new Array<number>(triangleCount).fill(2));
    } catch (e) {
      code = (e as { code: string }).code;
    }
    expect(code).toBe("invalid-argument");
    deformer.free();
  });

  it("rotates the shape rigidly when the handles follow an infinitesimal rotation", () => {
    const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.08 });
    const deformer = new Deformer(mesh.positions, mesh.triangles);
    deformer.setHandlePoints([0, 40, 80], [0.2, 0.3, 0.5, 1, 0, 0, 0.1, 0.1, 0.8]);
    const [a, cx, cy] = [0.25, 0.1, 0.6];
    const h = deformer.handlePositions();
    const velocities: number[] = [];
    for (let i = 0; i < h.length; i += 2) velocities.push(-a * (h[i + 1]! - cy), a * (h[i]! - cx));
    deformer.step(velocities);
    const p = deformer.positions();
    const [s, c] = [Math.sin(a), Math.cos(a)];
    for (let v = 0; v < mesh.vertexCount; v++) {
      const [x, y] = [mesh.positions[2 * v]! - cx, mesh.positions[2 * v + 1]! - cy];
      expect(p[2 * v]!).toBeCloseTo(cx + c * x - s * y, 9);
      expect(p[2 * v + 1]!).toBeCloseTo(cy + s * x + c * y, 9);
    }
    expect(deformer.metrics().areaDistortion).toBeCloseTo(2, 9);
    const t = deformer.timings();
    expect(t.factorisation).toBeGreaterThanOrEqual(0);
    deformer.free();
  });

  it("throws clear errors and keeps its state", () => {
    const deformer = new Deformer([0, 0, 1, 0, 1, 1, 0, 1], [0, 1, 2, 0, 2, 3], { lambda: 10 });
    deformer.setHandles([0, 2]);
    deformer.step([0, 0, 0.1, 0]);
    const before = deformer.positions();
    expect(() => deformer.setHandles([0, 9])).toThrow(/only 4 vertices/);
    expect(() => deformer.step([0, 0])).toThrow("velocities has 2 numbers, expected 4 (2 for each of the 2 handles)");
    expect(() => deformer.step([0, 0, NaN, 0])).toThrow(/not a finite number/);
    expect(() => deformer.setHandlePoints([0], [0.5, 0.2, 0.2])).toThrow(/barycentric/);
    expect(() => deformer.setOptions({ integrator: "euler" as never })).toThrow(/integrator/);
    expect(() => new Deformer([0, 0, 1, 0, 0, 1], [0, 2, 1])).toThrow(/counter-clockwise/);
    expect(() => new Deformer([0, 0, 1, 0, 0, 1], [0, 1, 2], { lamda: 1 } as never)).toThrow(/unknown deformer option/);
    expect(deformer.positions()).toEqual(before);
    expect(deformer.handleCount).toBe(2);
    deformer.free();
  });

  it("exposes positions as a view of wasm memory that follows steps and memory growth", () => {
    const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.1 });
    const deformer = new Deformer(mesh.positions, mesh.triangles);
    deformer.setHandles([0, 10]);
    const view = deformer.positionsView();
    expect(Array.from(view)).toEqual(Array.from(mesh.positions));
    deformer.step([0.01, 0, 0, 0.02]);
    const copy = deformer.positions(); // may grow the memory: take the view after copies
    const stepped = deformer.positionsView();
    expect(Array.from(stepped)).toEqual(Array.from(copy));
    expect(stepped[0]).not.toBe(mesh.positions[0]);
    expect(deformer.positionsView()).toBe(stepped); // cached while nothing changed
    // Allocating a big mesh grows the memory; the old view detaches, a new one is made.
    const big = triangulate(defaultShape(), { targetEdgeLength: 0.01 });
    const other = new Deformer(big.positions, big.triangles);
    expect(view.length).toBe(0); // detached
    const again = deformer.positionsView();
    expect(again.length).toBe(2 * mesh.vertexCount);
    expect(Array.from(again)).toEqual(Array.from(copy));
    other.free();
    deformer.free();
  });

  it("sets a pose and refuses bad ones without changing it", () => {
    const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.1 });
    const deformer = new Deformer(mesh.positions, mesh.triangles);
    const shifted = mesh.positions.map((x, i) => x + (i % 2 === 0 ? 0.5 : -0.25));
    deformer.setPositions(shifted);
    expect(Array.from(deformer.positionsView())).toEqual(Array.from(shifted));
    const n = mesh.vertexCount;
    // Counted in the numbers passed, not in pairs.
    expect(() => deformer.setPositions(shifted.subarray(2))).toThrow(
      `positions has ${2 * n - 2} numbers, expected ${2 * n} (2 for each of the ${n} vertices)`,
    );
    const far = shifted.slice();
    far[4] = 2e300;
    expect(() => deformer.setPositions(far)).toThrow(
      "the position of vertex 2 has the coordinate 2e300, beyond the limit of ±1e300",
    );
    const bad = shifted.slice();
    bad[7] = Number.NaN;
    expect(() => deformer.setPositions(bad)).toThrow(/vertex 3 is not a finite number/);
    expect(Array.from(deformer.positions())).toEqual(Array.from(shifted));
    deformer.free();
  });

  it("refuses lambda outside 1e-6..1e10 with the range, and stays usable", () => {
    const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.1 });
    for (const lambda of [1e308, 1e-300, 0, -1, 2e10]) {
      expect(() => new Deformer(mesh.positions, mesh.triangles, { lambda })).toThrow(
        /expected a number from 1e-6 to 1e10/,
      );
    }
    expect(() => new Deformer(mesh.positions, mesh.triangles, { lambda: 1e308 })).toThrow(
      "option lambda is 1e308, expected a number from 1e-6 to 1e10",
    );
    const deformer = new Deformer(mesh.positions, mesh.triangles, { lambda: 1e10 });
    expect(() => deformer.setOptions({ lambda: 1e-7 })).toThrow(/option lambda is 1e-7/);
    deformer.setHandles([0, 30]);
    deformer.step([0, 0, 0.01, 0.01]);
    deformer.setOptions({ lambda: 1e-6 });
    deformer.step([0, 0, 0.01, 0.01]);
    expect(deformer.positions().every(Number.isFinite)).toBe(true);
    deformer.free();
  });

  it("reports a collapsed pose as infinitely distorted, not NaN", () => {
    const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.1 });
    for (const options of [{}, { method: "arap" as const }]) {
      const deformer = new Deformer(mesh.positions, mesh.triangles, options);
      // Every vertex at one point: every triangle collapsed (both singular values 0).
      deformer.setPositions(new Float64Array(2 * mesh.vertexCount).fill(0.5));
      expect(deformer.metrics()).toEqual({
        areaDistortion: Infinity,
        angleDistortion: Infinity,
        flipped: mesh.triangleCount,
      });
      deformer.free();
    }
  });

  it("deforms a shape at 1e200 and at 1e-300 as at 1", () => {
    const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.1 });
    const pose = (scale: number) => {
      const deformer = new Deformer(
        mesh.positions.map((x) => x * scale),
        mesh.triangles,
      );
      deformer.setHandles([0, 30]);
      for (let k = 0; k < 3; k++) deformer.step([0, 0, 0.02 * scale, -0.01 * scale]);
      const p = deformer.positions().map((x) => x / scale);
      deformer.free();
      return p;
    };
    const unit = pose(1);
    for (const scale of [1e200, 1e-300]) {
      pose(scale).forEach((x, i) => expect(x).toBeCloseTo(unit[i]!, 9));
    }
  });

  it("switches method in place, keeping the pose and the handles", () => {
    const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.1 });
    const deformer = new Deformer(mesh.positions, mesh.triangles, { method: "arap", iterations: 5 });
    deformer.setHandles([0, 17, 42]);
    deformer.step([0.05, 0, 0, 0.05, 0, 0]);
    const posed = deformer.positions();
    const handles = deformer.handlePositions();
    // A bad setting of the new method changes nothing.
    expect(() => deformer.setOptions({ method: "akap", lambda: -1 })).toThrow(/option lambda/);
    expect(deformer.method).toBe("arap");
    deformer.setOptions({ method: "akap", lambda: 1e4 });
    expect(deformer.method).toBe("akap");
    expect(deformer.positions()).toEqual(posed);
    expect(deformer.handlePositions()).toEqual(handles);
    // The three handles came along: a common velocity translates the whole pose, which a
    // Killing field (a constant one, of zero energy) does exactly.
    deformer.step([0.1, -0.2, 0.1, -0.2, 0.1, -0.2]);
    const moved = deformer.positions();
    for (let i = 0; i < moved.length; i++) expect(moved[i]! - posed[i]!).toBeCloseTo(i % 2 === 0 ? 0.1 : -0.2, 9);
    // Back to ARAP with the iterations given; AKAP's settings are refused there.
    expect(() => deformer.setOptions({ method: "arap", lambda: 5 })).toThrow(/applies to method "akap" only/);
    deformer.setOptions({ method: "arap", iterations: 3 });
    expect(deformer.method).toBe("arap");
    expect(deformer.positions()).toEqual(moved);
    deformer.free();
  });

  it("runs ARAP with the same interface", () => {
    const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.1 });
    const deformer = new Deformer(mesh.positions, mesh.triangles, { method: "arap", iterations: 5 });
    expect(deformer.method).toBe("arap");
    // Handles at vertices are hard constraints: a translation of all of them is exact.
    deformer.setHandles([0, 17, 42]);
    deformer.step([0.1, -0.2, 0.1, -0.2, 0.1, -0.2]);
    const p = deformer.positions();
    for (let v = 0; v < mesh.vertexCount; v++) {
      expect(p[2 * v]! - mesh.positions[2 * v]!).toBeCloseTo(0.1, 9);
      expect(p[2 * v + 1]! - mesh.positions[2 * v + 1]!).toBeCloseTo(-0.2, 9);
    }
    expect(deformer.metrics().areaDistortion).toBeCloseTo(2, 9);
    expect(() => deformer.setOptions({ lambda: 10 })).toThrow(/applies to method "akap"/);
    expect(() => new Deformer(mesh.positions, mesh.triangles, { iterations: 3 })).toThrow(/applies to method "arap"/);
    deformer.setOptions({ iterations: 2 });
    // At most 1000 iterations per step (the core's arap::MAX_ITERATIONS), so a step ends.
    deformer.setOptions({ iterations: 1000 });
    for (const iterations of [0, 1001, 1e6]) {
      expect(() => deformer.setOptions({ iterations })).toThrow(/whole number from 1 to 1000 per step/);
    }
    expect(() => deformer.setOptions({ iterations: 2.5 })).toThrow(/must be a whole number, not the number 2.5/);
    deformer.setOptions({ iterations: 2 });
    // A pose set from outside: the handles' targets move with it, so a zero step stays.
    const shifted = p.map((x, i) => x + (i % 2 === 0 ? 0.3 : 0));
    deformer.setPositions(shifted);
    deformer.step([0, 0, 0, 0, 0, 0]);
    const q = deformer.positions();
    for (let i = 0; i < q.length; i++) expect(q[i]!).toBeCloseTo(shifted[i]!, 9);
    deformer.free();
  });
});

describe("Deformer of a puppet", () => {
  const layered = readFileSync("tests/fixtures/svg/layered-puppet.svg", "utf8");

  /** The point `p` of part `k` as a triangle and barycentric coordinates. */
  function pointOn(puppet: ImportedPuppet, k: number, p: [number, number]): [number, [number, number, number]] {
    const x = (v: number) => puppet.positions[2 * v]!;
    const y = (v: number) => puppet.positions[2 * v + 1]!;
    for (const t of puppet.parts[k]!.triangles) {
      const [a, b, c] = [0, 1, 2].map((i) => puppet.triangles[3 * t + i]!) as [number, number, number];
      const area = (x(b) - x(a)) * (y(c) - y(a)) - (y(b) - y(a)) * (x(c) - x(a));
      const w = (u: number, v: number) => ((x(u) - p[0]) * (y(v) - p[1]) - (y(u) - p[1]) * (x(v) - p[0])) / area;
      const weights: [number, number, number] = [w(b, c), w(c, a), w(a, b)];
      if (weights.every((q) => q >= -1e-12)) return [t, weights];
    }
    throw new Error(`(${p.join(", ")}) is not on part ${k}`);
  }

  it("takes importPuppet's parts and joints as they are, and poses every sheet at once", () => {
    const puppet = importPuppet(layered, { vertices: 1500 });
    const d = new Deformer(puppet.positions, puppet.triangles, {
      method: "akap",
      parts: puppet.parts,
      joints: puppet.joints,
    });
    expect(d.parts!.map((p) => p.name)).toEqual(["Torso", "Head", "Arm", "Hat"]);
    expect(d.joints).toEqual(puppet.joints);
    // The torso pinned by two handles, a third on the arm's far end moved up: the hat,
    // on a sheet of its own with no joint and no handle, does not move at all.
    const arm = puppet.parts[2]!.triangles;
    let far = 0;
    for (const t of arm)
      for (let c = 0; c < 3; c++) far = Math.max(far, puppet.positions[2 * puppet.triangles[3 * t + c]!]!);
    const joint = puppet.joints.find((j) => j.parts[0] === 2)!;
    const handles = [
      pointOn(puppet, 0, [70, 90]),
      pointOn(puppet, 0, [130, 90]),
      pointOn(puppet, 2, [far - 2, joint.point[1]]),
    ];
    d.setHandlePoints(
      handles.map(([t]) => t),
      handles.flatMap(([, w]) => w),
    );
    for (let k = 0; k < 10; k++) d.step([0, 0, 0, 0, 0, 2]);
    const pose = d.positions();
    const hat = new Set(
      [...puppet.parts[3]!.triangles].flatMap((t) => [0, 1, 2].map((c) => puppet.triangles[3 * t + c]!)),
    );
    for (const v of hat) {
      expect(pose[2 * v]).toBe(puppet.positions[2 * v]);
      expect(pose[2 * v + 1]).toBe(puppet.positions[2 * v + 1]);
    }
    // The arm moved up.
    expect(
      Math.max(
        ...[...arm].map(
          (t) => pose[2 * puppet.triangles[3 * t]! + 1]! - puppet.positions[2 * puppet.triangles[3 * t]! + 1]!,
        ),
      ),
    ).toBeGreaterThan(5);
    d.free();
  });

  it("refuses bad joints with code invalid-joint and changes nothing", () => {
    const puppet = importPuppet(layered, { vertices: 800 });
    const make = (joints: PuppetJoint[]) =>
      new Deformer(puppet.positions, puppet.triangles, { parts: puppet.parts, joints });
    const code = (f: () => unknown) => {
      try {
        f();
      } catch (e) {
        return (e as { code?: string }).code;
      }
      return "none";
    };
    const hatPoint: [number, number] = [...puppet.joints[0]!.point];
    hatPoint[1] += 1000;
    for (const bad of [
      { point: puppet.joints[0]!.point, parts: [2, 9] },
      { point: puppet.joints[0]!.point, parts: [2, 2] },
      { point: hatPoint, parts: puppet.joints[0]!.parts },
    ] as PuppetJoint[]) {
      expect(code(() => make([bad]))).toBe("invalid-joint");
    }
    const d = make(puppet.joints);
    expect(code(() => d.setJoints([{ point: [0, 0], parts: [0, 7] }]))).toBe("invalid-joint");
    expect(d.joints).toEqual(puppet.joints);
    d.setJoints([]);
    expect(d.joints).toEqual([]);
    expect(code(() => new Deformer(puppet.positions, puppet.triangles, { joints: puppet.joints }))).toBe(
      "invalid-option",
    );
    // Without parts the sheets are a mesh in pieces, refused as before.
    expect(code(() => new Deformer(puppet.positions, puppet.triangles))).toBe("invalid-mesh");
    d.free();
  });
});
