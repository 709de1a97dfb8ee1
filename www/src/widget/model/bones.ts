/**
 * Bones in the widget: straight segments drawn on the shape whose triangles move as one
 * rigid body (the core's `Deformer.setBones`, AKAP and ARAP). Like painted stiffness they
 * belong to the shape: kept across methods (a method without bones poses without them and
 * gets them back when one with bones is chosen), undone and redone, saved with the work,
 * recorded in sessions (`bones` events) and carried over a re-meshing. Each bone is laid
 * in the pose it is given in: it stays as straight and as long as it was then.
 */
import type { Deformer, MeshData as Mesh } from "../../core.js";
import { coded } from "../../internal/arrays.js";
import { locate, pointPosition, type MeshPoint } from "./picking.js";

/** A bone: its two ends, points of the mesh. */
export interface Bone {
  ends: [MeshPoint, MeshPoint];
}

/** What the bones need of the posing. */
export interface BonesHost {
  readonly deformer: Deformer;
  readonly shape: { mesh: Mesh };
}

/** A `bones` event (and `Deformer.setBones`'s arguments) for these bones. */
export function bonesEvent(bones: readonly Bone[]): { bones: { triangles: number[]; barycentric: number[] } } {
  const ends = bones.flatMap((b) => b.ends);
  return { bones: { triangles: ends.map((e) => e.triangle), barycentric: ends.flatMap((e) => e.barycentric) } };
}

/** Bones from a `bones` event's arrays (two ends per bone). */
export function bonesFrom(triangles: ArrayLike<number>, barycentric: ArrayLike<number>): Bone[] {
  const end = (i: number): MeshPoint => ({
    triangle: triangles[i]!,
    barycentric: [barycentric[3 * i]!, barycentric[3 * i + 1]!, barycentric[3 * i + 2]!],
  });
  return Array.from({ length: Math.floor(triangles.length / 2) }, (_, k) => ({ ends: [end(2 * k), end(2 * k + 1)] }));
}

/** The bones' ends at `positions`, x0 y0 x1 y1 per bone. */
export function boneEnds(
  bones: readonly Bone[],
  positions: ArrayLike<number>,
  triangles: ArrayLike<number>,
): Float64Array {
  return Float64Array.from(bones.flatMap((b) => b.ends.flatMap((e) => pointPosition(positions, triangles, e))));
}

/** The bone whose segment (ends as {@link boneEnds} gives them) passes within `radius` of (x, y), or -1. */
export function boneAt(ends: ArrayLike<number>, x: number, y: number, radius: number): number {
  let best = -1;
  let bestDistance = radius;
  for (let k = 0; 4 * k + 3 < ends.length; k++) {
    const [ax, ay, bx, by] = [ends[4 * k]!, ends[4 * k + 1]!, ends[4 * k + 2]!, ends[4 * k + 3]!];
    const [dx, dy] = [bx - ax, by - ay];
    const t = Math.min(1, Math.max(0, ((x - ax) * dx + (y - ay) * dy) / (dx * dx + dy * dy || 1)));
    const distance = Math.hypot(ax + t * dx - x, ay + t * dy - y);
    if (distance <= bestDistance) {
      bestDistance = distance;
      best = k;
    }
  }
  return best;
}

/** The posing's bones. */
export class Bones {
  #list: Bone[] = [];
  /** Counts changes (the overlay draws them again). */
  version = 0;
  readonly #host: BonesHost;

  constructor(host: BonesHost) {
    this.#host = host;
  }

  get list(): readonly Bone[] {
    return this.#list;
  }

  /**
   * Replaces the bones, laid in the pose on screen; the deformer gets them (and the
   * recording a `bones` event) when its method has bones. Throws, changing nothing, for a
   * bone the core refuses (ends at one point, a segment leaving the shape, a bone touching
   * another) and, with bones given, for a method without bones.
   */
  set(bones: readonly Bone[]): void {
    const deformer = this.#host.deformer;
    if (bones.length > 0 && !deformer.hasBones) {
      throw coded(
        new Error(`method ${deformer.method} has no bones; choose "akap" or "arap" to draw them`),
        "invalid-argument",
      );
    }
    const event = bonesEvent(bones);
    if (deformer.hasBones) deformer.setBones(event.bones.triangles, event.bones.barycentric);
    this.#list = bones.map((b) => ({ ends: [b.ends[0], b.ends[1]] }));
    this.version++;
  }

  /**
   * Gives the deformer the bones again, laid in the current pose (after a method switch,
   * an undo or a re-meshing). A bone the core now refuses (the pose moved it off the shape)
   * is dropped; returns how many were.
   */
  resend(): number {
    const deformer = this.#host.deformer;
    if (!deformer.hasBones) return 0;
    const kept: Bone[] = [];
    for (const bone of this.#list) {
      try {
        const event = bonesEvent([...kept, bone]);
        deformer.setBones(event.bones.triangles, event.bones.barycentric);
        kept.push(bone);
      } catch {
        // Refused in this pose: dropped below.
      }
    }
    const event = bonesEvent(kept);
    deformer.setBones(event.bones.triangles, event.bones.barycentric);
    const dropped = this.#list.length - kept.length;
    if (dropped > 0) {
      this.#list = kept;
      this.version++;
    }
    return dropped;
  }

  /** Forgets the bones without telling the deformer (a new shape, a replay's start). */
  forget(): void {
    this.#list = [];
    this.version++;
  }

  /** Takes bones the deformer has been given (a replayed event), or is to get ({@link resend}). */
  assign(bones: Bone[]): void {
    this.#list = bones;
    this.version++;
  }

  /**
   * The bones for a re-meshing of the shape: each end where its rest place lies in the new
   * rest mesh (within `tolerance`); bones with an end off it are dropped.
   */
  carried(old: Mesh, rest: Mesh, tolerance: number): Bone[] {
    const moved: Bone[] = [];
    for (const bone of this.#list) {
      const ends = bone.ends.map((e) => {
        const [x, y] = pointPosition(old.positions, old.triangles, e);
        return locate(rest.positions, rest.triangles, x, y, tolerance);
      });
      if (ends[0] && ends[1]) moved.push({ ends: [ends[0], ends[1]] });
    }
    return moved;
  }
}
