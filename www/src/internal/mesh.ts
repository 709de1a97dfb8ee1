/** Copying meshes out of wasm. Internal. */
import type { MeshData } from "../core-types.js";
import type { rawTypes } from "./wasm.js";

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
