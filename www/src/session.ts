/**
 * Recorded interaction sessions: every call that changes the deformer, in order, as JSON.
 * Replaying the calls on the same mesh gives the same positions bit for bit (the wasm
 * code is deterministic, and JSON numbers round-trip doubles exactly).
 *
 * The format has one definition, in Rust (`src/session/`, version 3; versions 1 and 2 are
 * read too): the widget records through the core's deformer (`Deformer.startRecording`), which writes the
 * JSON, and reads sessions through `sessionJson`, which checks them and writes them back
 * as version 3. The types here describe that JSON once parsed; nothing in TypeScript
 * validates it.
 *
 * ```json
 * { "format": "akap-session", "version": 3,
 *   "shape": { "name": "gingerbread", "targetEdgeLength": 0.035, "minAngle": 28 },
 *   "mesh": { "vertexCount": 812, "triangleCount": 1400 },
 *   "options": { "method": "akap", "lambda": 100, "dirichlet": true, "integrator": "spiral" },
 *   "events": [ { "handles": { "triangles": [..], "barycentric": [.. 3 per handle ..] } },
 *               { "step": [vx0, vy0, vx1, vy1, ...] },
 *               { "positions": [.. 2 per vertex ..] },
 *               { "options": { "method": "arap", "iterations": 10 } },
 *               { "stiffness": [.. 1 per triangle ..] },
 *               { "turn": { "velocities": [..], "turns": [.. 1 per handle ..] } },
 *               { "bones": { "triangles": [.. 2 per bone ..], "barycentric": [.. 3 per end ..] } },
 *               { "joints": [ { "point": [x, y], "parts": [front, back] } ] },
 *               { "rig": { "checksum": "8c3f0a51d2e47b69" } },
 *               { "rigPose": [x0, y0, x1, y1, ...] },
 *               { "rig": null },
 *               { "reset": true } ] }
 * ```
 * `shape` names a built-in shape and how it was triangulated; a session of another shape
 * carries the mesh itself in `mesh.positions` and `mesh.triangles`. A session of a puppet
 * has a `puppet` in its header, `{ "parts": [{ "name", "triangles", "depth" }], "joints":
 * [{ "point", "parts" }] }` (its parts and its joints at the start), and `joints` events
 * (the joints replaced). A trained rig posing is named by `rig` (the checksum of its
 * operator file, `Deformer.rigChecksum`; `null` when it stops) and each of its frames
 * recorded as the targets its pose is for (`rigPose`): replaying needs that rig loaded.
 */
import type { DeformerOptions, MeshData, PuppetJoint } from "./core.js";
import type { Indices, Coordinates } from "./internal/arrays.js";
import { readMesh } from "./internal/mesh.js";
import { assertLoaded, raw } from "./internal/wasm.js";

/** A built-in shape and the triangulation that made the mesh (as the widget makes them). */
export interface ShapeSpec {
  name: string;
  targetEdgeLength: number;
  minAngle: number;
}

/** A session's `shape`: a built-in shape and its triangulation options, each optional. */
export interface SessionShape {
  name: string;
  targetEdgeLength?: number;
  minAngle?: number;
  maxArea?: number;
}

export interface SessionMesh {
  vertexCount: number;
  triangleCount: number;
  /** The mesh itself, when it is not a built-in shape. */
  positions?: number[];
  triangles?: number[];
}

/** One recorded call; arrays as typed arrays while recording, plain arrays once read. */
export type SessionEvent =
  | { handles: { triangles: Indices; barycentric: Coordinates } }
  | { step: Coordinates }
  | { positions: Coordinates }
  | { options: DeformerOptions }
  | { stiffness: Coordinates | undefined | null }
  | { turn: { velocities: Coordinates; turns: Coordinates } }
  | { bones: { triangles: Indices; barycentric: Coordinates } }
  | { joints: PuppetJoint[] }
  | { rig: { checksum: string } | null }
  | { rigPose: Coordinates }
  | { reset: true };

/** A puppet's parts and joints at the start of a session (see `Deformer`'s `parts` and `joints`). */
export interface SessionPuppet {
  /** Each part: its name, its triangles (indices into the mesh's triangles) and its depth (larger in front). */
  parts: { name: string; triangles: number[]; depth: number }[];
  joints: PuppetJoint[];
}

/** A session's JSON, parsed. */
export interface SessionData {
  format: "akap-session";
  version: 3;
  shape?: SessionShape;
  mesh: SessionMesh;
  options: DeformerOptions;
  /** A puppet's parts and joints (absent for one shape). */
  puppet?: SessionPuppet;
  events: SessionEvent[];
}

/** A session read and checked by the core: its JSON (version 3, as the core writes it) and that JSON parsed. */
export class Session {
  /** The JSON text, what Save writes. */
  readonly json: string;
  readonly data: SessionData;

  /** `json` must come from the core (`sessionJson` or `Deformer.stopRecording`). */
  private constructor(json: string) {
    this.json = json;
    this.data = JSON.parse(json) as SessionData;
  }

  /** @internal A session from JSON the core wrote. */
  static fromCoreJson(json: string): Session {
    return new Session(json);
  }
}

/**
 * Reads and checks a session file (versions 1 to 3) in the core. Throws an `Error` saying
 * what is wrong and where (`not a valid session: ... at line 3 column 12`, `event 12: ...`);
 * the mesh is checked when the session is replayed.
 */
export function parseSession(text: string): Session {
  assertLoaded();
  return Session.fromCoreJson(raw.sessionJson(text));
}

/**
 * The mesh a session needs, rebuilt by the core: its built-in shape triangulated, or its
 * inline mesh validated; either way with the recorded counts (an `Error` otherwise).
 */
export function sessionMesh(session: Session): MeshData {
  assertLoaded();
  const mesh = raw.sessionMesh(session.json);
  try {
    return readMesh(mesh);
  } finally {
    mesh.free();
  }
}
