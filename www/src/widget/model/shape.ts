/**
 * What the widget deforms: a validated mesh with its edges, texture coordinates and size,
 * and how it was made (a built-in shape's name and triangulation, so sessions can rebuild
 * it exactly).
 */
import { limits, triangulateToVertices, type MeshData, type Outline } from "../../core.js";
import type { ImportedOutline, ImportedPuppet, VectorPath } from "../../import.js";
import { sessionMesh, type Session, type ShapeSpec } from "../../session.js";
import { bounds, boxUvs, uniqueEdges } from "./geometry.js";
import { puppetOf, sameParts, type Puppet, type PuppetSource } from "./puppet.js";

export interface Shape {
  /** What to call it (a built-in name, a file name). */
  name: string;
  mesh: MeshData;
  /** Set for built-in shapes: how to rebuild the mesh. */
  spec: ShapeSpec | undefined;
  edges: Uint32Array;
  /** Texture coordinates, 2 per vertex, v up. */
  uvs: Float32Array;
  /** Largest side of the rest bounding box. */
  size: number;
  /** The shape's own texture (an imported image); the widget's default otherwise. */
  texture?: TexImageSource;
  /** An imported SVG's filled paths in shape coordinates, for deformed vector export. */
  vector?: VectorPath[];
  /** Set for a puppet (an SVG of several layers, an image of separate regions): its parts, joints and source. */
  puppet?: Puppet;
}

/** Most vertices a widget mesh may have: the library's mesh limit (see `limits()`). */
export function maxVertices(): number {
  return limits().vertices;
}

/**
 * Triangulates an outline to about `vertices` vertices (the core's `triangulateToVertices`,
 * the one rule). `name` marks a built-in shape.
 */
export function meshOutline(
  outline: Outline,
  name: string | undefined,
  vertices: number,
  minAngle: number,
  label = name ?? "custom shape",
): Shape {
  const most = maxVertices();
  if (!(Number.isFinite(vertices) && vertices >= 50 && vertices <= most)) {
    throw new RangeError(`the vertex count ${vertices} is outside 50..${most}`);
  }
  const { mesh, targetEdgeLength: edge } = triangulateToVertices(outline, vertices, { minAngle, maxVertices: most });
  return shapeFromMesh(
    mesh,
    name === undefined ? undefined : { name, targetEdgeLength: edge, minAngle },
    undefined,
    label,
  );
}

/** A shape from a mesh; texture coordinates from its bounding box unless given. */
export function shapeFromMesh(
  mesh: MeshData,
  spec: ShapeSpec | undefined,
  uvs?: ArrayLike<number>,
  name = spec?.name ?? "custom shape",
): Shape {
  const b = bounds(mesh.positions);
  if (uvs !== undefined && uvs.length !== mesh.positions.length) {
    throw new Error(`the mesh has ${uvs.length / 2} texture coordinates for ${mesh.vertexCount} vertices`);
  }
  return {
    name,
    mesh,
    spec,
    edges: uniqueEdges(mesh.triangles, mesh.vertexCount),
    uvs: uvs === undefined ? boxUvs(mesh.positions) : Float32Array.from(uvs),
    size: Math.max(b.maxX - b.minX, b.maxY - b.minY) || 1,
  };
}

/**
 * The shape a session needs: `current` if it is that shape, else rebuilt by the core from
 * the session. Throws if its mesh is not the size the session recorded.
 */
export function sessionShape(session: Session, current: Shape): Shape {
  const shape = sessionShapeOf(session, current);
  const recorded = session.data.mesh;
  const { vertexCount, triangleCount } = shape.mesh;
  if (vertexCount !== recorded.vertexCount || triangleCount !== recorded.triangleCount) {
    throw new Error(
      `the session's mesh has ${recorded.vertexCount} vertices and ${recorded.triangleCount} triangles, ` +
        `but rebuilding it gave ${vertexCount} and ${triangleCount}`,
    );
  }
  return shape;
}

function sessionShapeOf(session: Session, current: Shape): Shape {
  const { shape: spec, mesh, puppet } = session.data;
  const now = current.spec;
  // A puppet is the current shape only with the same parts (a plain mesh only if not a puppet).
  const sameKind = puppet
    ? current.puppet !== undefined && sameParts(current.puppet.parts, puppet.parts)
    : !current.puppet;
  if (!sameKind) {
    // Rebuilt below.
  } else if (spec) {
    if (
      now &&
      now.name === spec.name &&
      now.targetEdgeLength === spec.targetEdgeLength &&
      now.minAngle === spec.minAngle &&
      spec.maxArea === undefined
    ) {
      return current;
    }
  } else if (!now && mesh.positions && mesh.triangles) {
    const m = current.mesh;
    if (sameArray(m.positions, mesh.positions) && sameArray(m.triangles, mesh.triangles)) return current;
  }
  // A shape the widget could have made keeps its spec (so it can be re-meshed and recorded by name).
  const { targetEdgeLength, minAngle } = spec ?? {};
  const widgetSpec =
    spec && targetEdgeLength !== undefined && minAngle !== undefined && spec.maxArea === undefined
      ? { name: spec.name, targetEdgeLength, minAngle }
      : undefined;
  const shape = shapeFromMesh(sessionMesh(session), widgetSpec, undefined, spec?.name ?? (puppet && "recorded puppet"));
  if (puppet) {
    // The parts and joints from the header; the session has no art (drawn with the default texture).
    const parts = puppet.parts.map((p) => ({ ...p, triangles: Uint32Array.from(p.triangles), paths: [] }));
    shape.puppet = puppetOf({ parts, joints: puppet.joints }, shape.mesh.triangles, undefined);
  }
  return shape;
}

function sameArray(a: ArrayLike<number>, b: ArrayLike<number>): boolean {
  if (a.length !== b.length) return false;
  for (let i = 0; i < a.length; i++) if (a[i] !== b[i]) return false;
  return true;
}

/**
 * What a file gives: outlines to mesh (largest first), a ready mesh, or a puppet (an SVG of
 * layers, an image of separate regions).
 */
export type Loaded =
  | {
      kind: "puppet";
      name: string;
      /** The SVG text or the image's pixels (re-meshing imports it again). */
      source: PuppetSource;
      /** The import at the vertex count of the time. */
      imported: ImportedPuppet;
      /** An image's puppet: the image, its texture. */
      texture?: TexImageSource;
    }
  | {
      kind: "outlines";
      name: string;
      parts: ImportedOutline[];
      /** The texture, and the size of the frame the outlines are in (its pixels, y up). */
      image?: { source: TexImageSource; width: number; height: number };
      /** The SVG's filled paths, for exporting the art deformed as vectors. */
      vector?: VectorPath[];
    }
  | {
      kind: "mesh";
      name: string;
      mesh: MeshData;
      uvs: Float64Array | undefined;
      /** Painted stiffness, one per triangle (JSON meshes). */
      stiffness?: Float64Array;
    };
