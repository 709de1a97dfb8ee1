/**
 * Sessions between the widget and the core, in Node through the real wasm: what the
 * widget records is the core's JSON and reads back through the core's parser, replaying to
 * the same pose bit for bit; version-1 files read as version 3; malformed sessions and
 * events are refused with the core's messages, changing nothing.
 */
import { readFileSync } from "node:fs";
import { beforeAll, describe, expect, it } from "vitest";
import { builtinShape, importPuppet, init, meshFromArrays } from "../../www/src/index.js";
import { widgetSettings } from "../../www/src/widget/options.js";
import { Posing } from "../../www/src/widget/model/posing.js";
import { Session, parseSession, sessionMesh, type SessionEvent } from "../../www/src/session.js";
import { meshOutline, sessionShape, shapeFromMesh, type Shape } from "../../www/src/widget/model/shape.js";
import { puppetOf } from "../../www/src/widget/model/puppet.js";
import { noTimings } from "./fixtures.js";

beforeAll(async () => {
  await init();
});

/** The layered fixture as the widget's puppet shape (its art left out: no document here). */
function puppetShape(): Shape {
  const text = readFileSync("tests/fixtures/svg/layered-puppet.svg", "utf8");
  const imported = importPuppet(text, { vertices: 800 });
  const shape = shapeFromMesh(meshFromArrays(imported.positions, imported.triangles), undefined, undefined, "puppet");
  shape.puppet = puppetOf(imported, shape.mesh.triangles, { kind: "svg", text });
  return shape;
}

function posing(): Posing {
  const p = new Posing(widgetSettings({ vertices: 300 }), {
    adopted: () => undefined,
    methodChanged: () => undefined,
    handlesChanged: () => undefined,
    poseChanged: () => undefined,
    historyChanged: () => undefined,
    schedule: () => undefined,
  });
  p.install(meshOutline(builtinShape("gingerbread"), "gingerbread", 300, 28));
  return p;
}

/** Drags handle `index` by (dx, dy) as the frame loop would, until it arrives. */
function drag(p: Posing, index: number, dx: number, dy: number): void {
  const h = p.deformer.handlePositions();
  const [x, y] = [h[2 * index]!, h[2 * index + 1]!];
  p.grab(index, 1, x, y, false);
  p.drag(1, x + dx, y + dy);
  for (let frame = 0; frame < 100 && p.advance(noTimings()) > 0; frame++);
  p.release(1);
}

const bits = (values: ArrayLike<number>): string =>
  Array.from(new Uint8Array(Float64Array.from(values).buffer), (b) => b.toString(16).padStart(2, "0")).join("");

describe("sessions through the core", () => {
  it("the widget's recording is the core's JSON, reads back through the core and replays to the same pose", async () => {
    const p = posing();
    const triangles = p.shape.mesh.triangles;
    p.addHandle({ triangle: 0, barycentric: [1, 0, 0] });
    drag(p, 0, 0.05, 0); // a pose before the recording: it starts with a positions event
    p.startRecording();
    p.addHandle({ triangle: Math.floor(triangles.length / 6), barycentric: [0.2, 0.3, 0.5] });
    drag(p, 1, -0.2, 0.3);
    p.setMethod("arap", 100);
    drag(p, 1, 0.1, -0.1);
    p.setMethod("akap-linear", 50);
    p.reset();
    drag(p, 1, 0.15, 0.05);
    const pose = p.deformer.positions();
    const session = p.stopRecording()!;

    const kinds = session.data.events.map((e) => Object.keys(e)[0]);
    expect(kinds.slice(0, 3)).toEqual(["positions", "handles", "handles"]);
    for (const kind of ["step", "options", "reset"]) expect(kinds).toContain(kind);
    expect(session.data.version).toBe(3);
    expect(session.data.shape?.name).toBe("gingerbread");
    // The core reads what the widget wrote, and writes it back the same.
    const back = parseSession(session.json);
    expect(back.json).toBe(session.json);
    expect(sessionMesh(back).positions).toEqual(p.shape.mesh.positions);

    // Replayed on a fresh posing of the same shape, as the widget replays (Posing.replay).
    const q = posing();
    let steps = 0;
    await q.replay(back, q.shape, async (n) => ((steps = n), true));
    expect(bits(q.deformer.positions())).toBe(bits(pose));
    expect(steps).toBe(kinds.filter((k) => k === "step").length);
    expect(q.settings.method).toBe("akap-linear");
    expect(q.settings.lambda).toBe(50);
    // One undoable step, back to where the replay began.
    expect(q.travel(false)).toBe(true);
    expect(bits(q.deformer.positions())).toBe(bits(p.shape.mesh.positions));

    // A replay stopped by its host keeps what it did so far; one that fails leaves nothing.
    const r = posing();
    await r.replay(back, r.shape, async () => false);
    expect(r.replaying).toBe(false);
    // A step the format holds but the deformer refuses: it would carry vertices past 1e300.
    const broken = parseSession(session.json.replace(/"step": ?\[[^\]]*\]/, '"step":[1e300,0,1e300,0]'));
    const t = posing();
    const before = t.deformer.positions();
    await expect(t.replay(broken, t.shape, async () => true)).rejects.toThrow(/1e300/);
    expect(bits(t.deformer.positions())).toBe(bits(before));
    expect(t.replaying).toBe(false);
  });

  it("a puppet's session replays to the same bits, on the puppet and on a puppet rebuilt from the session", async () => {
    const p = posing();
    const shape = puppetShape();
    p.install(shape);
    const joints = p.joints;
    const arm = shape.puppet!.parts.findIndex((part) => part.name === "Arm");
    const armTorso = joints.findIndex((j) => j.parts[0] === arm);
    const hand = shape.puppet!.parts[arm]!.triangles.at(-1)!;
    p.startRecording();
    p.addHandle({ triangle: shape.puppet!.parts[0]!.triangles[0]!, barycentric: [1, 0, 0] });
    p.addHandle({ triangle: hand, barycentric: [0.2, 0.3, 0.5] });
    drag(p, 1, -5, -20);
    // A joint moved to another point of the arm over the torso (SVG 130, 120: shape x - 70, y up).
    const [x0, y0] = joints[armTorso]!.point;
    const moved = joints.map((j, i) => (i === armTorso ? { ...j, point: [x0 - 4, y0 + 1] as [number, number] } : j));
    p.setJoints(moved);
    drag(p, 1, -10, 15);
    const pose = p.deformer.positions();
    const session = p.stopRecording()!;
    expect(session.data.puppet?.parts.map((part) => part.name)).toEqual(["Torso", "Head", "Arm", "Hat"]);
    expect(session.data.puppet?.joints).toEqual(joints);
    expect(session.data.events.filter((e) => "joints" in e)).toEqual([{ joints: moved }]);

    // On the same puppet (the joints moved since): the header's joints first.
    await p.replay(parseSession(session.json), sessionShape(session, p.shape), async () => true);
    expect(p.shape).toBe(shape);
    expect(bits(p.deformer.positions())).toBe(bits(pose));
    expect(p.joints).toEqual(moved);

    // From another shape: the puppet rebuilt from the session's mesh, parts and joints.
    const q = posing();
    const rebuilt = sessionShape(session, q.shape);
    expect(rebuilt.puppet?.parts.map((part) => [part.name, Array.from(part.triangles), part.depth])).toEqual(
      shape.puppet!.parts.map((part) => [part.name, Array.from(part.triangles), part.depth]),
    );
    await q.replay(session, rebuilt, async () => true);
    expect(bits(q.deformer.positions())).toBe(bits(pose));
    expect(q.joints).toEqual(moved);
    // On one shape of the same mesh, a puppet's session rebuilds the puppet.
    expect(sessionShape(session, shapeFromMesh(shape.mesh, undefined)).puppet).toBeDefined();
  });

  it("keeps negative zeros and subnormals of the recorded numbers", () => {
    const p = posing();
    const r = p.deformer;
    r.startRecording(p.shape.spec);
    r.setHandlePoints([0], [1, 0, 0]);
    r.step([-0, 5e-324]);
    const session = Session.fromCoreJson(r.stopRecording()!);
    expect(r.recording).toBe(false);
    const step = (session.data.events[2] as { step: number[] }).step;
    expect(Object.is(step[0], -0)).toBe(true);
    expect(step[1]).toBe(5e-324);
    expect(parseSession(session.json).json).toBe(session.json);
  });

  it("refuses a call the session cannot hold, keeping the events before it", () => {
    // The deformer records what it does: a call it refuses records nothing.
    const p = posing();
    const r = p.deformer;
    r.startRecording(undefined);
    const bad: SessionEvent[] = [
      { step: [0.1, 0.2] }, // no handles yet
      { handles: { triangles: [0, 1], barycentric: [1, 0, 0] } },
      { positions: [0, 0] },
      { options: { iterations: 5 } },
      { step: [] as number[] },
    ];
    expect(() => r.step((bad[0] as { step: number[] }).step)).toThrow(/velocities has 2 numbers/);
    expect(() => r.setHandlePoints([0, 1], [1, 0, 0])).toThrow("barycentric has 3 numbers; 2 triangles need 3 each");
    expect(() => r.setPositions([0, 0])).toThrow(/positions has 2 numbers/);
    expect(() => r.setOptions({ iterations: 5 })).toThrow('option iterations applies to method "arap" only');
    expect(() => r.step([NaN])).toThrow(/velocities has 1 numbers/);
    r.step((bad[4] as { step: number[] }).step); // a step of no handles is fine
    const session = Session.fromCoreJson(r.stopRecording()!);
    expect(session.data.events).toEqual([{ reset: true }, { step: [] }]);
    // Without a shape the session carries the mesh.
    expect(session.data.shape).toBeUndefined();
    expect(session.data.mesh.positions).toEqual(Array.from(p.shape.mesh.positions));
  });

  it("reads version-1 files as version 3, with every option of the method", () => {
    const text = readFileSync(new URL("../sessions/gingerbread-fast.json", import.meta.url), "utf8");
    expect(text).toContain('"version": 1,');
    const session = parseSession(text);
    expect(session.data.version).toBe(3);
    expect(session.data.options).toEqual({ method: "akap", lambda: 100, dirichlet: true, integrator: "spiral" });
    expect(session.data.events.length).toBe((JSON.parse(text) as { events: unknown[] }).events.length);
  });

  it("refuses malformed sessions with the core's messages", () => {
    const good = {
      format: "akap-session",
      version: 2,
      shape: { name: "gingerbread", targetEdgeLength: 0.1 },
      mesh: { vertexCount: 10, triangleCount: 12 },
      events: [{ handles: { triangles: [1], barycentric: [1, 0, 0] } }, { step: [1, 2] }],
    };
    const bad = (patch: object) => JSON.stringify({ ...good, ...patch });
    expect(parseSession(bad({})).data.options).toEqual({
      method: "akap",
      lambda: 100,
      dirichlet: true,
      integrator: "spiral",
    });
    expect(() => parseSession("{")).toThrow(/^not a valid session: EOF while parsing an object at line 1 column 1$/);
    expect(() => parseSession(bad({ format: "x" }))).toThrow('format is "x", expected "akap-session"');
    expect(() => parseSession(bad({ version: 4 }))).toThrow("session version 4 is not supported (only 1 to 3)");
    expect(() => parseSession(bad({ events: [{ jump: 1 }] }))).toThrow(/unknown variant `jump`/);
    expect(() => parseSession(bad({ events: [{ step: [1, "2"] }] }))).toThrow(/invalid type: string "2"/);
    expect(() => parseSession(bad({ events: [{ step: [1], reset: true }] }))).toThrow(/not a valid session/);
    expect(() => parseSession(bad({ shape: undefined }))).toThrow(/must name a built-in shape or carry its mesh/);
    expect(() => parseSession(bad({ mesh: { vertexCount: -1, triangleCount: 1 } }))).toThrow(
      /invalid value: integer `-1`/,
    );
    expect(() => parseSession(bad({ options: { method: "arap", lambda: 5 } }))).toThrow(
      'option lambda applies to method "akap" only, not to "arap"',
    );
    expect(() => parseSession(bad({ events: [...good.events, { step: [1] }] }))).toThrow(
      "event 2: velocities has 1 numbers, expected 2 (2 for each of the 1 handles)",
    );
    expect(() => parseSession(42 as unknown as string)).toThrow("the session must be a string, not the number 42");
  });
});
