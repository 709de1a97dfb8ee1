/**
 * Puppets, without the DOM: a shape made of parts (one sheet each, sharing no vertex,
 * overlapping at rest) coupled at joints, as `importPuppet` gives them. What a part is
 * (its triangles, depth and art) and where each joint is (a rest point on two parts) are
 * the import's; here are the widget's questions about them: which part a triangle is in,
 * which parts lie under the pointer front first, where a joint is in the pose, and the
 * depth order the user changes (Forward/Back). The deformer holds the joints it poses with
 * (`Deformer.joints`); the posing keeps them for undo.
 */
import type { Deformer, DeformerOptions, DeformerSetup, PuppetJoint } from "../../core.js";
import type { PuppetPart } from "../../import.js";
import { METHODS, type MethodPreset } from "./methods.js";
import { locate, locateAll, pointPosition, type MeshPoint } from "./picking.js";

/** A puppet as the widget holds it with its shape. */
export interface Puppet {
  parts: PuppetPart[];
  /** The joints the import placed (the deformer's may have changed since). */
  joints: PuppetJoint[];
  /** Each triangle's part. */
  partOf: Int32Array;
  /** Each part's triangles as a mesh of their own: 3 vertex indices (of the whole mesh) each. */
  meshes: Uint32Array[];
  /**
   * What it was imported from, for re-meshing to import it again: an SVG's text, or an
   * image's pixels; undefined for a puppet rebuilt from a session or saved work without
   * it (it cannot be re-meshed).
   */
  source: PuppetSource | undefined;
}

/** What a puppet was imported from: an SVG's text, or an image's pixels (RGBA, row by row from the top). */
export type PuppetSource =
  { kind: "svg"; text: string } | { kind: "image"; rgba: Uint8ClampedArray; width: number; height: number };

/**
 * The widget's puppet from an imported one on a mesh with `triangles`: throws when a
 * triangle is in no part or in two, or a part names a triangle the mesh lacks.
 */
export function puppetOf(
  imported: { parts: readonly PuppetPart[]; joints: readonly PuppetJoint[] },
  triangles: ArrayLike<number>,
  source: PuppetSource | undefined,
): Puppet {
  const count = triangles.length / 3;
  const partOf = new Int32Array(count).fill(-1);
  const meshes = imported.parts.map((part, k) => {
    const mesh = new Uint32Array(3 * part.triangles.length);
    part.triangles.forEach((t, i) => {
      if (!(t < count)) throw new Error(`part ${k} (${part.name}) names triangle ${t}; the mesh has ${count}`);
      if (partOf[t] !== -1) throw new Error(`triangle ${t} is in parts ${partOf[t]} and ${k}`);
      partOf[t] = k;
      mesh.set([triangles[3 * t]!, triangles[3 * t + 1]!, triangles[3 * t + 2]!], 3 * i);
    });
    return mesh;
  });
  const lost = partOf.indexOf(-1);
  if (lost >= 0) throw new Error(`triangle ${lost} is in no part`);
  return {
    parts: [...imported.parts],
    joints: imported.joints.map((j) => ({ point: [j.point[0], j.point[1]], parts: [j.parts[0], j.parts[1]] })),
    partOf,
    meshes,
    source,
  };
}

/** Whether two puppets have the same parts (names, triangles and depths, in order). */
export function sameParts(
  a: readonly { name: string; triangles: ArrayLike<number>; depth: number }[],
  b: readonly { name: string; triangles: ArrayLike<number>; depth: number }[],
): boolean {
  return (
    a.length === b.length &&
    a.every((p, k) => {
      const q = b[k]!;
      if (p.name !== q.name || p.depth !== q.depth || p.triangles.length !== q.triangles.length) return false;
      for (let i = 0; i < p.triangles.length; i++) if (p.triangles[i] !== q.triangles[i]) return false;
      return true;
    })
  );
}

/**
 * What the status line says when a method without sheets poses a puppet (moving least
 * squares and Cauchy-Green pose the whole puppet as one shape); undefined for the others.
 */
export function oneShapeNote(method: MethodPreset): string | undefined {
  const { options, label } = METHODS[method];
  if (options.method !== "mls" && options.method !== "cauchy-green") return undefined;
  return `${label} has no sheets: it poses the whole puppet as one shape (parts bend together, joints do not hinge); AKAP and ARAP pose each part on its own sheet.`;
}

/** The parts' depths as imported. */
export function importedDepths(puppet: Puppet): number[] {
  return puppet.parts.map((p) => p.depth);
}

/**
 * The depths with `part` moved one step in front (`step` 1) or behind (-1): it changes
 * places with the part next to it in depth order. Undefined when it is already the front
 * (or back) part. Depths stay the same set of numbers.
 */
export function stepDepth(depths: readonly number[], part: number, step: 1 | -1): number[] | undefined {
  const order = depths.map((d, k) => ({ d, k })).sort((a, b) => a.d - b.d || a.k - b.k);
  const at = order.findIndex((o) => o.k === part);
  const other = order[at + step];
  if (at < 0 || !other) return undefined;
  const next = [...depths];
  // Equal depths become distinct: the moved part goes just past its neighbour.
  const mine = depths[part]!;
  if (other.d === mine) next[part] = mine + step;
  else [next[part], next[other.k]] = [other.d, mine];
  return next;
}

/**
 * The parts under (x, y) in `positions` (the pose), front first, one point each: for each
 * part, its triangle there drawn last (the highest one when a part overlaps itself).
 */
export function partsUnder(
  puppet: Puppet,
  depths: readonly number[],
  positions: ArrayLike<number>,
  triangles: ArrayLike<number>,
  x: number,
  y: number,
): { part: number; point: MeshPoint }[] {
  const byPart = new Map<number, MeshPoint>();
  for (const point of locateAll(positions, triangles, x, y)) byPart.set(puppet.partOf[point.triangle]!, point);
  return [...byPart]
    .map(([part, point]) => ({ part, point }))
    .sort((a, b) => depths[b.part]! - depths[a.part]! || b.part - a.part);
}

/** Where `part`'s point at rest (x, y) is in `positions` (the pose); undefined off the part. */
export function posedPoint(
  puppet: Puppet,
  part: number,
  rest: ArrayLike<number>,
  positions: ArrayLike<number>,
  x: number,
  y: number,
  tolerance = 0,
): [number, number] | undefined {
  const mesh = puppet.meshes[part];
  const point = mesh && locate(rest, mesh, x, y, tolerance);
  return point && pointPosition(positions, mesh, point);
}

/** The rest point of `part` that is at (x, y) in `positions` (the pose); undefined off the part. */
export function restPoint(
  puppet: Puppet,
  part: number,
  rest: ArrayLike<number>,
  positions: ArrayLike<number>,
  x: number,
  y: number,
  tolerance = 0,
): [number, number] | undefined {
  return posedPoint(puppet, part, positions, rest, x, y, tolerance);
}

/**
 * Each joint's place in the pose (xy-interleaved): its front part's point there (at rest,
 * the joint's own point; the deformer keeps the two parts' points together).
 */
export function jointPositions(
  puppet: Puppet,
  joints: readonly PuppetJoint[],
  rest: ArrayLike<number>,
  positions: ArrayLike<number>,
  tolerance: number,
): Float64Array {
  const out = new Float64Array(2 * joints.length);
  joints.forEach((j, i) => {
    const [x, y] = j.point;
    out.set(posedPoint(puppet, j.parts[0], rest, positions, x, y, tolerance) ?? [x, y], 2 * i);
  });
  return out;
}

/** Deformer options for `puppet` with `joints`, added to a method's options. */
export function puppetOptions(options: DeformerOptions, puppet: Puppet, joints: readonly PuppetJoint[]): DeformerSetup {
  return {
    ...options,
    parts: puppet.parts.map((p) => ({ name: p.name, triangles: p.triangles, depth: p.depth })),
    joints: joints.map(copyJoint),
  };
}

/** The joints a puppet's deformer poses with (copies). */
export function deformerJoints(deformer: Deformer): PuppetJoint[] {
  return deformer.joints.map(copyJoint);
}

/** Gives a puppet's deformer new joints; throws (code `invalid-joint`), changing nothing, for bad ones. */
export function setDeformerJoints(deformer: Deformer, joints: readonly PuppetJoint[]): void {
  deformer.setJoints(joints.map(copyJoint));
}

function copyJoint(j: { point: readonly [number, number]; parts: readonly [number, number] }): PuppetJoint {
  return { point: [j.point[0], j.point[1]], parts: [j.parts[0], j.parts[1]] };
}

/** Whether two joint lists are the same joints in the same order. */
export function sameJoints(a: readonly PuppetJoint[], b: readonly PuppetJoint[]): boolean {
  return (
    a.length === b.length &&
    a.every((j, i) => {
      const k = b[i]!;
      return (
        j.point[0] === k.point[0] && j.point[1] === k.point[1] && j.parts[0] === k.parts[0] && j.parts[1] === k.parts[1]
      );
    })
  );
}
