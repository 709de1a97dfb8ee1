/** Copying meshes out of wasm. Internal. */
import type { rawTypes } from "./wasm.js";

/** A validated triangle mesh as plain typed arrays. (Public through `core.ts`.) */
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

/** Copies a wasm mesh out as plain typed arrays (the caller frees it). Internal. */
export function readMesh(mesh: rawTypes.Mesh): MeshData {
  return {
    positions: mesh.positions(),
    triangles: mesh.triangles(),
    boundaryEdges: mesh.boundaryEdges(),
    boundaryVertices: mesh.boundaryVertices(),
    vertexCount: mesh.vertexCount,
    triangleCount: mesh.triangleCount,
    area: mesh.area(),
  };
}
