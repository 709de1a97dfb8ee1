/**
 * Recorded interaction sessions: every call that changes the deformer, in order, as JSON.
 * Replaying the calls on the same mesh gives the same positions bit for bit (the wasm
 * code is deterministic, and JSON numbers round-trip doubles exactly).
 *
 * ```json
 * { "format": "akap-session", "version": 1,
 *   "shape": { "name": "gingerbread", "targetEdgeLength": 0.035, "minAngle": 28 },
 *   "mesh": { "vertexCount": 812, "triangleCount": 1400 },
 *   "options": { "lambda": 100, "dirichlet": true, "integrator": "spiral" },
 *   "events": [ { "handles": { "triangles": [..], "barycentric": [.. 3 per handle ..] } },
 *               { "step": [vx0, vy0, vx1, vy1, ...] },
 *               { "positions": [.. 2 per vertex ..] },
 *               { "options": { "lambda": 50 } },
 *               { "reset": true } ] }
 * ```
 * `shape` names a built-in shape and how it was triangulated; a session of another shape
 * carries the mesh itself in `mesh.positions` and `mesh.triangles`.
 */
import type { DeformerOptions } from "../core.js";

/** A built-in shape and the triangulation that made the mesh. */
export interface ShapeSpec {
  name: string;
  targetEdgeLength: number;
  minAngle: number;
}

export interface SessionMesh {
  vertexCount: number;
  triangleCount: number;
  /** The mesh itself, when it is not a built-in shape. */
  positions?: number[];
  triangles?: number[];
}

export type SessionEvent =
  | { handles: { triangles: number[]; barycentric: number[] } }
  | { step: number[] }
  | { positions: number[] }
  | { options: DeformerOptions }
  | { reset: true };

export interface Session {
  format: "akap-session";
  version: 1;
  shape?: ShapeSpec;
  mesh: SessionMesh;
  options: DeformerOptions;
  events: SessionEvent[];
}

/** Collects events while recording. */
export class Recorder {
  #session: Session | undefined;

  /** Starts a new recording; `start` events put the deformer in its current state. */
  start(header: Omit<Session, "format" | "version" | "events">, start: SessionEvent[]): void {
    this.#session = { format: "akap-session", version: 1, ...header, events: [...start] };
  }

  get recording(): boolean {
    return this.#session !== undefined;
  }

  /** Adds an event if recording (arrays are copied). */
  record(event: SessionEvent): void {
    this.#session?.events.push(copyEvent(event));
  }

  /** Ends the recording and returns it (undefined if none was running). */
  stop(): Session | undefined {
    const session = this.#session;
    this.#session = undefined;
    return session;
  }
}

function copyEvent(event: SessionEvent): SessionEvent {
  if ("handles" in event) {
    return {
      handles: { triangles: Array.from(event.handles.triangles), barycentric: Array.from(event.handles.barycentric) },
    };
  }
  if ("step" in event) return { step: Array.from(event.step) };
  if ("positions" in event) return { positions: Array.from(event.positions) };
  if ("options" in event) return { options: { ...event.options } };
  return { reset: true };
}

/** Largest session file we read (about 80 MB). */
export const MAX_SESSION_BYTES = 80_000_000;

/**
 * Reads and checks a session file. Throws an `Error` saying what is wrong and where
 * (`events[12].step[3] is not a number`); nothing else is checked against a mesh here.
 */
export function parseSession(text: string): Session {
  if (text.length > MAX_SESSION_BYTES) {
    throw new Error(`the session file is ${text.length} bytes; the limit is ${MAX_SESSION_BYTES}`);
  }
  let data: unknown;
  try {
    data = JSON.parse(text);
  } catch (error) {
    throw new Error(`the session is not valid JSON: ${(error as Error).message}`, { cause: error });
  }
  const root = record(data, "the session");
  if (root.format !== "akap-session")
    throw new Error('the file is not an akap session (format must be "akap-session")');
  if (root.version !== 1) throw new Error(`session version ${String(root.version)} is not supported (expected 1)`);
  const mesh = record(root.mesh, "mesh");
  const session: Session = {
    format: "akap-session",
    version: 1,
    mesh: {
      vertexCount: count(mesh.vertexCount, "mesh.vertexCount"),
      triangleCount: count(mesh.triangleCount, "mesh.triangleCount"),
    },
    options: record(root.options ?? {}, "options") as DeformerOptions,
    events: [],
  };
  if (mesh.positions !== undefined || mesh.triangles !== undefined) {
    session.mesh.positions = numbers(mesh.positions, "mesh.positions");
    session.mesh.triangles = numbers(mesh.triangles, "mesh.triangles").map((v, i) => count(v, `mesh.triangles[${i}]`));
  }
  if (root.shape !== undefined) {
    const shape = record(root.shape, "shape");
    if (typeof shape.name !== "string") throw new Error("shape.name must be a string");
    session.shape = {
      name: shape.name,
      targetEdgeLength: finite(shape.targetEdgeLength, "shape.targetEdgeLength"),
      minAngle: finite(shape.minAngle, "shape.minAngle"),
    };
  }
  if (!session.shape && !session.mesh.positions) throw new Error("the session names no shape and carries no mesh");
  if (!Array.isArray(root.events)) throw new Error("events must be an array");
  root.events.forEach((item: unknown, i) => {
    const where = `events[${i}]`;
    const event = record(item, where);
    const keys = Object.keys(event);
    if (keys.length !== 1) throw new Error(`${where} must have exactly one key, found ${keys.join(", ") || "none"}`);
    if ("handles" in event) {
      const h = record(event.handles, `${where}.handles`);
      session.events.push({
        handles: {
          triangles: numbers(h.triangles, `${where}.handles.triangles`),
          barycentric: numbers(h.barycentric, `${where}.handles.barycentric`),
        },
      });
    } else if ("step" in event) {
      session.events.push({ step: numbers(event.step, `${where}.step`) });
    } else if ("positions" in event) {
      session.events.push({ positions: numbers(event.positions, `${where}.positions`) });
    } else if ("options" in event) {
      session.events.push({ options: record(event.options, `${where}.options`) as DeformerOptions });
    } else if ("reset" in event) {
      session.events.push({ reset: true });
    } else {
      throw new Error(`${where} has the unknown kind "${keys[0]}"`);
    }
  });
  return session;
}

function record(value: unknown, what: string): Record<string, unknown> {
  if (typeof value !== "object" || value === null || Array.isArray(value)) throw new Error(`${what} must be an object`);
  return value as Record<string, unknown>;
}

function numbers(value: unknown, what: string): number[] {
  if (!Array.isArray(value)) throw new Error(`${what} must be an array of numbers`);
  value.forEach((x: unknown, i) => {
    if (typeof x !== "number" || !Number.isFinite(x)) throw new Error(`${what}[${i}] is not a finite number`);
  });
  return value as number[];
}

function finite(value: unknown, what: string): number {
  if (typeof value !== "number" || !Number.isFinite(value)) throw new Error(`${what} must be a finite number`);
  return value;
}

function count(value: unknown, what: string): number {
  if (!Number.isSafeInteger(value) || (value as number) < 0) throw new Error(`${what} must be a whole number`);
  return value as number;
}
