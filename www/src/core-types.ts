/**
 * The core's plain data types that its internal helpers use too: a leaf that imports
 * nothing, so that `internal/` and the public files both take them from here (no import
 * goes back up to `core.ts`), and so that the public declarations never reach
 * wasm-bindgen's generated ones. Public through `core.ts`.
 */

/**
 * Where the WebAssembly module comes from: its bytes, its URL, a fetch `Response` or an
 * already compiled module. (The public types never reach wasm-bindgen's generated ones,
 * so a consumer's `lib` setting need not know them.)
 */
export type WasmSource = BufferSource | WebAssembly.Module | URL | string | Response;

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
