/**
 * Finding what is under the pointer: the point of the mesh (a triangle and barycentric
 * coordinates, so handles sit exactly where the user clicked) and the nearest handle.
 * Linear scans: picking runs once per click, and 20k triangles take well under a
 * millisecond.
 */

/** A point of the mesh: a triangle and barycentric coordinates (non-negative, sum 1). */
export interface MeshPoint {
  triangle: number;
  barycentric: [number, number, number];
}

/**
 * The mesh point at (x, y) in the given positions, or the closest point of the mesh when
 * (x, y) lies outside it but within `tolerance`. Undefined when nothing is that close.
 */
export function locate(
  positions: ArrayLike<number>,
  triangles: ArrayLike<number>,
  x: number,
  y: number,
  tolerance = 0,
): MeshPoint | undefined {
  let best: MeshPoint | undefined;
  let bestDistance = tolerance;
  for (let t = 0; 3 * t + 2 < triangles.length; t++) {
    const a = triangles[3 * t]!;
    const b = triangles[3 * t + 1]!;
    const c = triangles[3 * t + 2]!;
    const ax = positions[2 * a]!;
    const ay = positions[2 * a + 1]!;
    const bx = positions[2 * b]!;
    const by = positions[2 * b + 1]!;
    const cx = positions[2 * c]!;
    const cy = positions[2 * c + 1]!;
    const area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
    if (area === 0) continue;
    const wa = ((bx - x) * (cy - y) - (by - y) * (cx - x)) / area;
    const wb = ((cx - x) * (ay - y) - (cy - y) * (ax - x)) / area;
    const wc = 1 - wa - wb;
    if (wa >= 0 && wb >= 0 && wc >= 0) return { triangle: t, barycentric: [wa, wb, wc] };
    if (tolerance <= 0) continue;
    // Outside: the closest point lies on one of the three edges.
    const edges: [number, number, number, number, number][] = [
      [ax, ay, bx, by, 0],
      [bx, by, cx, cy, 1],
      [cx, cy, ax, ay, 2],
    ];
    for (const [px, py, qx, qy, k] of edges) {
      const dx = qx - px;
      const dy = qy - py;
      const s = Math.min(1, Math.max(0, ((x - px) * dx + (y - py) * dy) / (dx * dx + dy * dy || 1)));
      const distance = Math.hypot(px + s * dx - x, py + s * dy - y);
      if (distance <= bestDistance) {
        bestDistance = distance;
        const w: [number, number, number] = [0, 0, 0];
        w[k] = 1 - s;
        w[(k + 1) % 3] = s;
        best = { triangle: t, barycentric: w };
      }
    }
  }
  return best;
}

/** Index of the point of `points` (xy-interleaved) nearest to (x, y) within `radius`, or -1. */
export function nearestPoint(points: ArrayLike<number>, x: number, y: number, radius: number): number {
  let best = -1;
  let bestDistance = radius;
  for (let i = 0; 2 * i + 1 < points.length; i++) {
    const distance = Math.hypot(points[2 * i]! - x, points[2 * i + 1]! - y);
    if (distance <= bestDistance) {
      bestDistance = distance;
      best = i;
    }
  }
  return best;
}

/** The position of a mesh point in the given positions. */
export function pointPosition(
  positions: ArrayLike<number>,
  triangles: ArrayLike<number>,
  point: MeshPoint,
): [number, number] {
  let x = 0;
  let y = 0;
  for (let k = 0; k < 3; k++) {
    const v = triangles[3 * point.triangle + k]!;
    x += point.barycentric[k]! * positions[2 * v]!;
    y += point.barycentric[k]! * positions[2 * v + 1]!;
  }
  return [x, y];
}

/**
 * The mesh point at (x, y) on the front-most triangle there: of the triangles containing
 * it, the one of the highest `layers` value (a later triangle among equals: drawn last, it
 * is on top). Off every triangle, the closest point within `tolerance` as {@link locate}
 * finds it. Undefined when nothing is that close.
 */
export function locateFront(
  positions: ArrayLike<number>,
  triangles: ArrayLike<number>,
  layers: ArrayLike<number>,
  x: number,
  y: number,
  tolerance = 0,
): MeshPoint | undefined {
  let best: MeshPoint | undefined;
  for (const point of locateAll(positions, triangles, x, y)) {
    if (!best || layers[point.triangle]! >= layers[best.triangle]!) best = point;
  }
  return best ?? locate(positions, triangles, x, y, tolerance);
}

/** Every triangle containing (x, y), as mesh points, in triangle order. */
export function locateAll(
  positions: ArrayLike<number>,
  triangles: ArrayLike<number>,
  x: number,
  y: number,
): MeshPoint[] {
  const found: MeshPoint[] = [];
  for (let t = 0; 3 * t + 2 < triangles.length; t++) {
    const a = triangles[3 * t]!;
    const b = triangles[3 * t + 1]!;
    const c = triangles[3 * t + 2]!;
    const ax = positions[2 * a]!;
    const ay = positions[2 * a + 1]!;
    const bx = positions[2 * b]!;
    const by = positions[2 * b + 1]!;
    const cx = positions[2 * c]!;
    const cy = positions[2 * c + 1]!;
    const area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
    if (area === 0) continue;
    const wa = ((bx - x) * (cy - y) - (by - y) * (cx - x)) / area;
    const wb = ((cx - x) * (ay - y) - (cy - y) * (ax - x)) / area;
    const wc = 1 - wa - wb;
    if (wa >= 0 && wb >= 0 && wc >= 0) found.push({ triangle: t, barycentric: [wa, wb, wc] });
  }
  return found;
}
