/**
 * The public API of akap: shape outlines in, validated triangle meshes out, in a page
 * or in Node. Call {@link init} once before anything else.
 *
 * @example
 * ```ts
 * import { init, defaultShape, triangulate } from "akap";
 * await init();
 * const mesh = triangulate(defaultShape(), { targetEdgeLength: 0.05 });
 * console.log(mesh.vertexCount, mesh.triangleCount);
 * ```
 *
 * @packageDocumentation
 */
import { assertLoaded, load, raw, type WasmSource } from "./internal/wasm.js";

export type { WasmSource };

/** A list of points, x and y interleaved: `[x0, y0, x1, y1, ...]`. */
export type Coordinates = Float64Array | readonly number[];

/** A shape: an outer boundary and optional holes, each a closed ring in either direction. */
export interface Outline {
  outer: Coordinates;
  holes?: readonly Coordinates[];
}

/** How finely to triangulate. Every field is optional. */
export interface TriangulationOptions {
  /** Upper bound on triangle area. */
  maxArea?: number;
  /** Desired edge length (an area bound of the equilateral triangle with this edge). */
  targetEdgeLength?: number;
  /** Smallest angle in degrees that refinement enforces, 0 to 34 (default 25). */
  minAngle?: number;
  /** Largest vertex count of the result, outline points included (default 100000). */
  maxVertices?: number;
}

/** A validated triangle mesh as plain typed arrays. */
export interface MeshData {
  /** Vertex positions, x and y interleaved (length 2 * vertexCount). */
  positions: Float64Array;
  /** Counter-clockwise triangles, three vertex indices each (length 3 * triangleCount). */
  triangles: Uint32Array;
  /** Edges of exactly one triangle as index pairs, the shape on their left. */
  boundaryEdges: Uint32Array;
  /** Vertices on the boundary (outer outline and holes), ascending. */
  boundaryVertices: Uint32Array;
  vertexCount: number;
  triangleCount: number;
  /** Total area of the triangles. */
  area: number;
}

/**
 * Loads the WebAssembly module. In a browser it is fetched next to this module; in Node
 * it is read from disk. Pass `source` (bytes, a URL or a compiled module) to override.
 * Safe to call more than once.
 */
export function init(source?: WasmSource): Promise<void> {
  return load(source);
}

function copyOut(mesh: raw.Mesh): MeshData {
  try {
    return {
      positions: mesh.positions(),
      triangles: mesh.triangles(),
      boundaryEdges: mesh.boundaryEdges(),
      boundaryVertices: mesh.boundaryVertices(),
      vertexCount: mesh.vertexCount,
      triangleCount: mesh.triangleCount,
      area: mesh.area(),
    };
  } finally {
    mesh.free();
  }
}

function asFloat64(coordinates: Coordinates, what: string): Float64Array {
  if (coordinates instanceof Float64Array) return coordinates;
  if (Array.isArray(coordinates)) return Float64Array.from(coordinates, Number);
  throw new TypeError(`${what} must be a Float64Array or an array of numbers`);
}

/**
 * Triangulates an outline: constrained Delaunay, refined to the requested triangle size
 * and minimum angle. Throws an `Error` naming the problem for invalid outlines
 * (fewer than 3 points, non-finite coordinates, self-intersections, zero area, holes
 * outside the shape, too many vertices) or options.
 */
export function triangulate(outline: Outline, options: TriangulationOptions = {}): MeshData {
  assertLoaded();
  const outer = asFloat64(outline.outer, "outline.outer");
  const holes = (outline.holes ?? []).map((hole, k) => asFloat64(hole, `outline.holes[${k}]`));
  return copyOut(raw.triangulate_outline(outer, holes, options));
}

/**
 * Validates a mesh given as arrays (positions xy-interleaved, counter-clockwise triangles)
 * and returns it with its boundary. Throws an `Error` naming the first problem found.
 */
export function meshFromArrays(positions: Coordinates, triangles: Uint32Array | readonly number[]): MeshData {
  assertLoaded();
  let indices: Uint32Array;
  if (triangles instanceof Uint32Array) {
    indices = triangles;
  } else {
    const bad = triangles.findIndex((i) => !Number.isInteger(i) || i < 0 || i > 0xffffffff);
    if (bad >= 0) throw new RangeError(`triangles[${bad}] is ${triangles[bad]}, not a vertex index`);
    indices = Uint32Array.from(triangles);
  }
  return copyOut(new raw.Mesh(asFloat64(positions, "positions"), indices));
}

/** The built-in default shape, a waving gingerbread figure about 1.4 units tall (y up). */
export function defaultShape(): { outer: Float64Array; holes: Float64Array[] } {
  assertLoaded();
  return raw.defaultShape() as { outer: Float64Array; holes: Float64Array[] };
}
