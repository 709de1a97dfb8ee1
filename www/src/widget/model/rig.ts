/**
 * A trained rig: a deformation operator ({@link DefOp}) with the shape and the handles it
 * was trained for, which poses that shape in closed form. It poses only while the shape
 * and the handles are those (same rest mesh, same handle points in the same order); any
 * other handle set makes it stale. {@link rigKey} names a training by its content (rest
 * mesh, handle points, training options), which `rigs/rig-cache.ts` keeps rigs under.
 */
import { DefOp, type DefOpRegions, type DefOpTraining, type DefOpTrainerOptions } from "../../defop.js";
import type { MeshData, PuppetJoint } from "../../core.js";
import { pointPosition, type MeshPoint } from "./picking.js";
import type { Shape } from "./shape.js";

/** Training options a widget takes: the trainer's, without the ones for other tools. */
export type RigTrainOptions = Pick<
  DefOpTrainerOptions,
  "energy" | "basis" | "samples" | "radius" | "sampling" | "spatial" | "seed"
>;

/**
 * The widget's spatial basis for a rig: a reduced basis of 100 functions. On the paper's
 * models it is as accurate as one function per vertex (held-out error 1.307 % against
 * 1.291 %) and evaluates 17 times faster (`lab/defop/defop.md`), and a frame on the GPU
 * computes 200 numbers on the CPU. A mesh of no more vertices takes one per vertex
 * ({@link spatialFor}).
 */
export const DEFAULT_RIG_SPATIAL = 100;

/** The spatial basis a training of `spatial` uses on a mesh of `vertexCount` vertices: one function per vertex (0) when the reduced basis would have no fewer. */
export function spatialFor(spatial: number | undefined, vertexCount: number): number {
  const asked = spatial ?? DEFAULT_RIG_SPATIAL;
  return asked >= vertexCount ? 0 : asked;
}

/** Where a rig came from. */
export type RigSource = "trained" | "cache" | "file";

export class Rig {
  readonly operator: DefOp;
  /** The rest mesh it poses. */
  readonly mesh: MeshData;
  readonly points: readonly MeshPoint[];
  /** The training's sampling radius (a file keeps it). */
  readonly radius: number | undefined;
  /** The training options; undefined for a rig from a file. */
  readonly options: RigTrainOptions | undefined;
  /** The settings the operator was trained with, as it (and its file, from version 4) keeps them; else undefined. */
  readonly training: DefOpTraining | undefined;
  readonly source: RigSource;
  /** The last shape found to have this rig's rest mesh (compared by content once per shape). */
  #shape: Shape | undefined;
  /** The joints of the puppet it was trained on, as JSON (`[]` for one shape): read once. */
  #joints: string | undefined;
  /** Where its training drew each handle's targets: read once. */
  #regions: DefOpRegions | undefined;

  constructor(
    operator: DefOp,
    mesh: MeshData,
    points: readonly MeshPoint[],
    trained: { radius: number | undefined; options: RigTrainOptions | undefined; source: RigSource },
  ) {
    if (operator.handleCount !== points.length || operator.vertexCount !== mesh.vertexCount) {
      throw new Error(
        `the rig has ${operator.handleCount} handles and ${operator.vertexCount} vertices; ` +
          `${points.length} handles and ${mesh.vertexCount} vertices were given`,
      );
    }
    this.operator = operator;
    this.mesh = mesh;
    this.points = points.map((p) => ({ triangle: p.triangle, barycentric: [...p.barycentric] }));
    this.radius = trained.radius;
    this.options = trained.options;
    this.source = trained.source;
    this.training = operator.training;
  }

  /**
   * The energy its ground truth is solved with (Compare): the operator's own training's,
   * which its file keeps; else the options it was trained with (a rig cached before files
   * kept it); else S-ARAP, the trainer's default.
   */
  get energy(): "sarap" | "arap" {
    return this.training?.energy ?? this.options?.energy ?? "sarap";
  }

  /** Where its training drew each handle's targets (discs, Voronoi cells or both), from the operator (one definition, in Rust). */
  regions(): DefOpRegions {
    return (this.#regions ??= this.operator.regions());
  }

  /** A rig read from an operator file: its own mesh and handles. */
  static fromBytes(bytes: Uint8Array, source: RigSource = "file"): Rig {
    const operator = DefOp.fromBytes(bytes);
    try {
      const { triangles, barycentric } = operator.handlePoints();
      const points = Array.from(triangles, (triangle, i) => ({
        triangle,
        barycentric: [barycentric[3 * i]!, barycentric[3 * i + 1]!, barycentric[3 * i + 2]!] as [
          number,
          number,
          number,
        ],
      }));
      // The file keeps the training's settings (from version 4; older files, the sampling
      // radius as the scale of the handle coordinates): `training`, not the widget's options.
      const { radius } = operator.regions();
      return new Rig(operator, operator.mesh(), points, { radius, options: undefined, source });
    } catch (error) {
      operator.free();
      throw error;
    }
  }

  /** Whether it poses `shape` with handles at `points` (in this order) and, for a puppet,
   * the deformer's `joints`. */
  fits(shape: Shape, points: readonly { point: MeshPoint }[], joints: readonly PuppetJoint[] = []): boolean {
    if (points.length !== this.points.length) return false;
    // A puppet's rig poses only the puppet with the joints it was trained with.
    this.#joints ??= JSON.stringify(this.operator.joints ?? []);
    if (this.#joints !== JSON.stringify(joints)) return false;
    const same = points.every(({ point }, i) => {
      const mine = this.points[i]!;
      return point.triangle === mine.triangle && point.barycentric.every((b, k) => b === mine.barycentric[k]);
    });
    if (!same) return false;
    if (shape !== this.#shape) {
      if (!sameMesh(shape.mesh, this.mesh)) return false;
      this.#shape = shape;
    }
    return true;
  }

  /** The handles' rest positions, 2 each. */
  restHandles(): Float64Array {
    const out = new Float64Array(2 * this.points.length);
    this.points.forEach((p, i) => {
      const [x, y] = pointPosition(this.mesh.positions, this.mesh.triangles, p);
      out[2 * i] = x;
      out[2 * i + 1] = y;
    });
    return out;
  }

  /** The operator file (the operator, its mesh and its training's settings), in double or single precision. */
  toBytes(options: { precision?: "double" | "single" } = {}): Uint8Array {
    return this.operator.toBytes(options);
  }

  free(): void {
    this.operator.free();
  }
}

function sameMesh(a: MeshData, b: MeshData): boolean {
  const equal = (x: ArrayLike<number>, y: ArrayLike<number>) => {
    if (x.length !== y.length) return false;
    for (let i = 0; i < x.length; i++) if (x[i] !== y[i]) return false;
    return true;
  };
  return equal(a.positions, b.positions) && equal(a.triangles, b.triangles);
}

/**
 * The cache key of a training: SHA-256 of the rest mesh, the handle points and the
 * options, as hex; undefined where the browser has no `crypto.subtle` (pages not served
 * securely), and then nothing is cached.
 */
export async function rigKey(
  mesh: MeshData,
  points: readonly MeshPoint[],
  options: RigTrainOptions,
  joints?: readonly PuppetJoint[],
): Promise<string | undefined> {
  const subtle = globalThis.crypto?.subtle;
  if (!subtle) return undefined;
  const handles = new Float64Array(points.flatMap((p) => [p.triangle, ...p.barycentric]));
  const keys = Object.keys(options).sort() as (keyof RigTrainOptions)[];
  const settings = new TextEncoder().encode(
    JSON.stringify([...keys.map((k): unknown[] => [k, options[k]]), ...(joints ? [["joints", joints]] : [])]),
  );
  const parts = [mesh.positions, mesh.triangles, handles, settings];
  const length = parts.reduce((sum, p) => sum + p.byteLength + 8, 0);
  const bytes = new Uint8Array(length);
  let at = 0;
  for (const part of parts) {
    // Each part's length first, so that no two different inputs join to the same bytes.
    new DataView(bytes.buffer).setFloat64(at, part.byteLength, true);
    bytes.set(new Uint8Array(part.buffer, part.byteOffset, part.byteLength), at + 8);
    at += part.byteLength + 8;
  }
  const digest = new Uint8Array(await subtle.digest("SHA-256", bytes));
  return Array.from(digest, (b) => b.toString(16).padStart(2, "0")).join("");
}
