/** Mesh helpers for drawing and export: unique edges, boundary loops, texture coordinates. */
import { textureCoordinates } from "../../import.js";

/** Every edge of the triangles once, as index pairs. */
export function uniqueEdges(triangles: ArrayLike<number>, vertexCount: number): Uint32Array {
  const seen = new Set<number>();
  const edges: number[] = [];
  for (let i = 0; i + 2 < triangles.length; i += 3) {
    for (let k = 0; k < 3; k++) {
      const a = triangles[i + k]!;
      const b = triangles[i + ((k + 1) % 3)]!;
      const key = Math.min(a, b) * vertexCount + Math.max(a, b);
      if (seen.has(key)) continue;
      seen.add(key);
      edges.push(a, b);
    }
  }
  return Uint32Array.from(edges);
}

/**
 * Chains boundary edges (pairs, the shape on their left) into closed loops of vertex
 * indices, each edge in its own direction: the outer boundary counter-clockwise, holes
 * clockwise (at rest, y up). The loops' winding number around a point therefore counts the
 * layers of the shape over it in any pose without flipped triangles.
 */
export function boundaryLoops(boundaryEdges: ArrayLike<number>): number[][] {
  const next = new Map<number, number[]>();
  for (let i = 0; i + 1 < boundaryEdges.length; i += 2) {
    const from = boundaryEdges[i]!;
    const list = next.get(from);
    if (list) list.push(boundaryEdges[i + 1]!);
    else next.set(from, [boundaryEdges[i + 1]!]);
  }
  const loops: number[][] = [];
  for (const start of next.keys()) {
    while ((next.get(start)?.length ?? 0) > 0) {
      const loop = [start];
      let at = next.get(start)!.pop()!;
      while (at !== start) {
        loop.push(at);
        const out = next.get(at);
        if (!out || out.length === 0) break; // open chain: cannot happen for a valid mesh
        at = out.pop()!;
      }
      loops.push(loop);
    }
  }
  return loops;
}

/**
 * The outlines of the regions of triangles that share a label: for each label, the loops
 * (see {@link boundaryLoops}) of its triangles' edges whose neighbour across is missing or
 * labelled otherwise. Filling a region's loops (nonzero) covers what its triangles cover, with
 * a few hundred edges instead of thousands of triangles (a canvas fills such a path far
 * faster).
 */
export function regionOutlines(
  triangles: ArrayLike<number>,
  labels: ArrayLike<number>,
  vertexCount: number,
): Map<number, number[][]> {
  const count = triangles.length / 3;
  const byEdge = new Map<number, number>();
  for (let t = 0; t < count; t++) {
    for (let k = 0; k < 3; k++) byEdge.set(triangles[3 * t + k]! * vertexCount + triangles[3 * t + ((k + 1) % 3)]!, t);
  }
  const rims = new Map<number, number[]>();
  for (let t = 0; t < count; t++) {
    const label = labels[t]!;
    for (let k = 0; k < 3; k++) {
      const [a, b] = [triangles[3 * t + k]!, triangles[3 * t + ((k + 1) % 3)]!];
      const twin = byEdge.get(b * vertexCount + a);
      if (twin !== undefined && labels[twin] === label) continue;
      let rim = rims.get(label);
      if (!rim) rims.set(label, (rim = []));
      rim.push(a, b);
    }
  }
  return new Map([...rims].map(([label, rim]) => [label, boundaryLoops(rim)]));
}

/**
 * The square that {@link boxUvs} maps onto the unit square: a bounding box grown in its
 * shorter direction about its centre, `[x0, x0 + size] x [y0, y0 + size]` (size 1 for a
 * box of no size).
 */
export interface UvSquare {
  x0: number;
  y0: number;
  size: number;
}

/** The {@link UvSquare} of a bounding box. */
export function uvSquare(b: { minX: number; minY: number; maxX: number; maxY: number }): UvSquare {
  const size = Math.max(b.maxX - b.minX, b.maxY - b.minY) || 1;
  return { x0: b.minX - (size - (b.maxX - b.minX)) / 2, y0: b.minY - (size - (b.maxY - b.minY)) / 2, size };
}

/**
 * Texture coordinates through a square: the square is the texture's frame, and the
 * positions' coordinates in it go through `textureCoordinates` (OBJ's convention, v up:
 * u = (x - x0) / size, v = (y - y0) / size), so the texture's bottom-left corner is the
 * square's. Needs the wasm module loaded (`init`).
 */
export function squareUvs(positions: ArrayLike<number>, square: UvSquare): Float32Array {
  const local = new Float64Array(positions.length);
  for (let i = 0; i + 1 < positions.length; i += 2) {
    local[i] = positions[i]! - square.x0;
    local[i + 1] = positions[i + 1]! - square.y0;
  }
  return Float32Array.from(textureCoordinates(local, square.size, square.size));
}

/**
 * Texture coordinates from rest positions: the bounding box mapped into [0, 1]^2 with its
 * aspect ratio kept (the longer side spans 0..1), centred in the shorter direction; that
 * is, through the {@link uvSquare} of the positions' bounding box.
 */
export function boxUvs(positions: ArrayLike<number>): Float32Array {
  return squareUvs(positions, uvSquare(bounds(positions)));
}

/** Signed doubled area of triangle `t` (positive when counter-clockwise). */
export function doubledArea(positions: ArrayLike<number>, triangles: ArrayLike<number>, t: number): number {
  const a = triangles[3 * t]!;
  const b = triangles[3 * t + 1]!;
  const c = triangles[3 * t + 2]!;
  const ax = positions[2 * a]!;
  const ay = positions[2 * a + 1]!;
  return (
    (positions[2 * b]! - ax) * (positions[2 * c + 1]! - ay) - (positions[2 * b + 1]! - ay) * (positions[2 * c]! - ax)
  );
}

/** Bounding box of xy-interleaved positions; throws for an empty list. */
export function bounds(positions: ArrayLike<number>): { minX: number; minY: number; maxX: number; maxY: number } {
  if (positions.length < 2) throw new Error("bounds of an empty point list");
  let minX = Infinity;
  let minY = Infinity;
  let maxX = -Infinity;
  let maxY = -Infinity;
  for (let i = 0; i + 1 < positions.length; i += 2) {
    const x = positions[i]!;
    const y = positions[i + 1]!;
    minX = Math.min(minX, x);
    maxX = Math.max(maxX, x);
    minY = Math.min(minY, y);
    maxY = Math.max(maxY, y);
  }
  return { minX, minY, maxX, maxY };
}
