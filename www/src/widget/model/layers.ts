/**
 * Depth order of overlapping parts, without the DOM. A puppet's parts are in the layers of
 * their depths ({@link partLayering}). Otherwise each handle has a layer (a whole
 * number; higher is in front); each part of the shape takes the layer of the handle
 * nearest to it along the rest mesh (multi-source Dijkstra over the mesh's edges, from the
 * handles' points), so a limb belongs to the handle on it. Triangles are then drawn back
 * to front (a stable sort by layer: the painter's order, which also blends translucent
 * texture correctly, where a depth buffer would cut it), and the outline of each layer is
 * hidden where a layer in front covers it.
 */
import { regionOutlines } from "./geometry.js";
import type { MeshPoint } from "./picking.js";

/** Layers of a mesh's triangles and boundary edges, and the layers in use, back to front. */
export interface Layering {
  /** The layer of each triangle. */
  triangles: Int32Array;
  /** The layer of each boundary edge (pairs of `boundaryEdges`). */
  edges: Int32Array;
  /** The distinct layers, ascending (back to front). */
  order: number[];
  /**
   * Per layer of `order`, the closed loops of vertices around its part (the part on their
   * left at rest): what it covers in any pose, drawn as a few hundred edges instead of its
   * triangles.
   */
  outlines: number[][][];
}

/**
 * The layering that `handles` (a mesh point and a layer each) give the mesh at rest, or
 * undefined when every part would be in one layer (no handles, or all in one layer).
 */
export function layering(
  positions: ArrayLike<number>,
  triangles: ArrayLike<number>,
  boundaryEdges: ArrayLike<number>,
  handles: readonly { point: MeshPoint; layer: number }[],
): Layering | undefined {
  const layers = new Set(handles.map((h) => h.layer));
  if (layers.size < 2) return undefined;
  const n = positions.length / 2;
  const neighbours = vertexNeighbours(n, triangles);
  // Nearest handle per vertex: distance along edges from the handle's point.
  const distance = new Float64Array(n).fill(Infinity);
  const owner = new Int32Array(n).fill(-1);
  const heap = new Heap();
  const from = (x: number, y: number, v: number) => Math.hypot(positions[2 * v]! - x, positions[2 * v + 1]! - y);
  handles.forEach((h, index) => {
    let x = 0;
    let y = 0;
    for (let k = 0; k < 3; k++) {
      const v = triangles[3 * h.point.triangle + k]!;
      x += h.point.barycentric[k]! * positions[2 * v]!;
      y += h.point.barycentric[k]! * positions[2 * v + 1]!;
    }
    for (let k = 0; k < 3; k++) {
      const v = triangles[3 * h.point.triangle + k]!;
      const d = from(x, y, v);
      if (d < distance[v]!) {
        distance[v] = d;
        owner[v] = index;
        heap.push(d, v);
      }
    }
  });
  for (let top = heap.pop(); top; top = heap.pop()) {
    const [d, v] = top;
    if (d > distance[v]!) continue;
    for (const w of neighbours[v]!) {
      const next = d + from(positions[2 * v]!, positions[2 * v + 1]!, w);
      if (next < distance[w]!) {
        distance[w] = next;
        owner[w] = owner[v]!;
        heap.push(next, w);
      }
    }
  }
  // A triangle belongs to the handle of its corner nearest to a handle.
  const count = triangles.length / 3;
  const triangleLayers = new Int32Array(count);
  for (let t = 0; t < count; t++) {
    let best = triangles[3 * t]!;
    for (let k = 1; k < 3; k++) if (distance[triangles[3 * t + k]!]! < distance[best]!) best = triangles[3 * t + k]!;
    triangleLayers[t] = owner[best]! >= 0 ? handles[owner[best]!]!.layer : 0;
  }
  return layeringOf(n, triangles, boundaryEdges, triangleLayers);
}

/**
 * The layering of a puppet: each triangle in the layer of its part's depth (`partOf`: the
 * part of each triangle; `depths`: each part's depth, larger in front), so parts are drawn
 * back to front by depth and each part's outline is hidden where a part in front covers it.
 */
export function partLayering(
  vertexCount: number,
  triangles: ArrayLike<number>,
  boundaryEdges: ArrayLike<number>,
  partOf: ArrayLike<number>,
  depths: readonly number[],
): Layering {
  const triangleLayers = Int32Array.from(partOf, (part) => depths[part] ?? 0);
  return layeringOf(vertexCount, triangles, boundaryEdges, triangleLayers);
}

/** The layering whose triangles have the given layers: the boundary edges' layers, the order, the outlines. */
function layeringOf(
  n: number,
  triangles: ArrayLike<number>,
  boundaryEdges: ArrayLike<number>,
  triangleLayers: Int32Array,
): Layering {
  const byEdge = new Map<number, number>();
  for (let t = 0; t < triangleLayers.length; t++) {
    for (let k = 0; k < 3; k++) byEdge.set(triangles[3 * t + k]! * n + triangles[3 * t + ((k + 1) % 3)]!, t);
  }
  const order = [...new Set(triangleLayers)].sort((a, b) => a - b);
  const regions = regionOutlines(triangles, triangleLayers, n);
  const edges = new Int32Array(boundaryEdges.length / 2);
  for (let e = 0; e < edges.length; e++) {
    const t = byEdge.get(boundaryEdges[2 * e]! * n + boundaryEdges[2 * e + 1]!);
    edges[e] = t === undefined ? 0 : triangleLayers[t]!;
  }
  return { triangles: triangleLayers, edges, order, outlines: order.map((layer) => regions.get(layer) ?? []) };
}

/** The triangles (3 indices each) back to front: stable by layer, as given without a layering. */
export function drawOrder(triangles: Uint32Array, layers: Layering | undefined): Uint32Array {
  if (!layers) return triangles;
  const count = triangles.length / 3;
  const order = Array.from({ length: count }, (_, t) => t).sort(
    (a, b) => layers.triangles[a]! - layers.triangles[b]! || a - b,
  );
  const out = new Uint32Array(triangles.length);
  order.forEach((t, i) => out.set(triangles.subarray(3 * t, 3 * t + 3), 3 * i));
  return out;
}

function vertexNeighbours(n: number, triangles: ArrayLike<number>): number[][] {
  const out: number[][] = Array.from({ length: n }, () => []);
  for (let i = 0; i < triangles.length; i += 3) {
    for (let k = 0; k < 3; k++) {
      const a = triangles[i + k]!;
      const b = triangles[i + ((k + 1) % 3)]!;
      out[a]!.push(b);
      out[b]!.push(a);
    }
  }
  return out;
}

/** A binary min-heap of (key, value) pairs. */
class Heap {
  readonly #keys: number[] = [];
  readonly #values: number[] = [];

  push(key: number, value: number): void {
    const keys = this.#keys;
    const values = this.#values;
    let i = keys.length;
    keys.push(key);
    values.push(value);
    while (i > 0) {
      const parent = (i - 1) >> 1;
      if (keys[parent]! <= key) break;
      keys[i] = keys[parent]!;
      values[i] = values[parent]!;
      i = parent;
    }
    keys[i] = key;
    values[i] = value;
  }

  pop(): [number, number] | undefined {
    const keys = this.#keys;
    const values = this.#values;
    if (keys.length === 0) return undefined;
    const top: [number, number] = [keys[0]!, values[0]!];
    const key = keys.pop()!;
    const value = values.pop()!;
    const size = keys.length;
    if (size > 0) {
      let i = 0;
      for (;;) {
        let child = 2 * i + 1;
        if (child >= size) break;
        if (child + 1 < size && keys[child + 1]! < keys[child]!) child++;
        if (keys[child]! >= key) break;
        keys[i] = keys[child]!;
        values[i] = values[child]!;
        i = child;
      }
      keys[i] = key;
      values[i] = value;
    }
    return top;
  }
}
