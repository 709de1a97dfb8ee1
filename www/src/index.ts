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
export function meshFromArrays(positions: Coordinates, triangles: Indices): MeshData {
  assertLoaded();
  return copyOut(new raw.Mesh(asFloat64(positions, "positions"), asUint32(triangles, "triangles")));
}

/** Vertex or triangle indices. */
export type Indices = Uint32Array | readonly number[];

function asUint32(indices: Indices, what: string): Uint32Array {
  if (indices instanceof Uint32Array) return indices;
  if (!Array.isArray(indices)) throw new TypeError(`${what} must be a Uint32Array or an array of numbers`);
  const bad = indices.findIndex((i) => !Number.isInteger(i) || i < 0 || i > 0xffffffff);
  if (bad >= 0) throw new RangeError(`${what}[${bad}] is ${indices[bad]}, not an index`);
  return Uint32Array.from(indices);
}

/** Options of the {@link Deformer}. */
export interface DeformerOptions {
  /** Weight of the soft handle constraints (default 100). */
  lambda?: number;
  /** Whether the Dirichlet re-solve runs (default true). */
  dirichlet?: boolean;
  /** How vertices follow the field: along log spirals (default) or straight lines. */
  integrator?: "spiral" | "linear";
}

/** Distortion of the current pose against the rest pose (2 for a rigid motion). */
export interface Metrics {
  areaDistortion: number;
  angleDistortion: number;
  /** Triangles turned upside down. */
  flipped: number;
}

/** Milliseconds spent in each stage of the last step. */
export interface Timings {
  assembly: number;
  factorisation: number;
  solve: number;
  integration: number;
}

/**
 * As-Killing-As-Possible deformation of one mesh. Give it handles (vertices, or points
 * inside triangles), then call {@link Deformer.step} with a velocity per handle each
 * frame. Bad input throws an `Error` and leaves the deformer as it was. Call
 * {@link Deformer.free} when done: the solver lives in WebAssembly memory.
 */
export class Deformer {
  readonly #raw: raw.Deformer;

  /**
   * @param positions xy-interleaved vertex positions (length 2n)
   * @param triangles counter-clockwise index triples (length 3m); the mesh must be connected
   */
  constructor(positions: Coordinates, triangles: Indices, options: DeformerOptions = {}) {
    assertLoaded();
    this.#raw = new raw.Deformer(asFloat64(positions, "positions"), asUint32(triangles, "triangles"), options);
  }

  /** Changes some options; the others keep their values. */
  setOptions(options: DeformerOptions): void {
    this.#raw.setOptions(options);
  }

  /** One handle on each of these vertices, replacing the current handles. */
  setHandles(vertices: Indices): void {
    this.#raw.setHandles(asUint32(vertices, "vertices"));
  }

  /** Handles at points inside triangles: a triangle index and 3 barycentric coordinates each. */
  setHandlePoints(triangles: Indices, barycentric: Coordinates): void {
    this.#raw.setHandlePoints(asUint32(triangles, "triangles"), asFloat64(barycentric, "barycentric"));
  }

  /** One step: two velocity components per handle, in handle order. */
  step(velocities: Coordinates): void {
    this.#raw.step(asFloat64(velocities, "velocities"));
  }

  /** A copy of the current positions, xy-interleaved. */
  positions(): Float64Array {
    return this.#raw.positions();
  }

  /** The last step's velocity field after the Dirichlet re-solve (U_opt), xy-interleaved. */
  field(): Float64Array {
    return this.#raw.field();
  }

  /** The last step's velocity field after the soft-constraint solve (U0), xy-interleaved. */
  softField(): Float64Array {
    return this.#raw.softField();
  }

  /** Current positions of the handle points, xy-interleaved. */
  handlePositions(): Float64Array {
    return this.#raw.handlePositions();
  }

  get handleCount(): number {
    return this.#raw.handleCount;
  }

  get vertexCount(): number {
    return this.#raw.vertexCount;
  }

  metrics(): Metrics {
    return this.#raw.metrics() as Metrics;
  }

  timings(): Timings {
    return this.#raw.timings() as Timings;
  }

  /** Back to the rest pose; handles stay. */
  reset(): void {
    this.#raw.reset();
  }

  /** Releases the WebAssembly memory; the deformer cannot be used afterwards. */
  free(): void {
    this.#raw.free();
  }
}

/** The built-in default shape, a waving gingerbread figure about 1.4 units tall (y up). */
export function defaultShape(): { outer: Float64Array; holes: Float64Array[] } {
  assertLoaded();
  return raw.defaultShape() as { outer: Float64Array; holes: Float64Array[] };
}
export * from "./import.js";
