/**
 * Exports of the current pose: the mesh as JSON or Wavefront OBJ (the core's writers), the
 * outline or vector art as SVG, and a file download helper for pages.
 */
import { PointMapper, meshToJson, meshToObj, pathData, type VectorPath } from "../../import.js";
import { boundaryLoops } from "../model/geometry.js";
import { drawOrder, type Layering } from "../model/layers.js";
import { locate } from "../model/picking.js";
import { bounds } from "../model/geometry.js";

/** The fill of exported shapes and of vector art whose colour the importer does not know. */
export const DEFAULT_FILL = "#c8773a";

/**
 * The outline of the current pose as an SVG document: one path with every boundary loop,
 * y pointing down as SVG expects, a small margin. Each loop follows the mesh's boundary
 * edges in their direction (the shape on their left: the outer boundary counter-clockwise
 * and holes clockwise at rest), and the path fills by the nonzero rule: inside the posed
 * shape the winding number is positive (2 where a posed arm lies over the body, so the
 * overlap stays filled, as the canvas draws it), and 0 in holes and outside.
 */
export function outlineSvg(
  positions: ArrayLike<number>,
  boundaryEdges: ArrayLike<number>,
  fill = DEFAULT_FILL,
): string {
  const b = bounds(positions);
  const margin = 0.02 * Math.max(b.maxX - b.minX, b.maxY - b.minY);
  const [x0, y0] = [b.minX - margin, -b.maxY - margin];
  const [w, h] = [b.maxX - b.minX + 2 * margin, b.maxY - b.minY + 2 * margin];
  const loops = boundaryLoops(boundaryEdges);
  const outline = {
    commands: loops.map((loop) => "M" + "L".repeat(loop.length - 1) + "Z").join(""),
    points: Float64Array.from(loops.flat().flatMap((v) => [positions[2 * v]!, positions[2 * v + 1]!])),
  };
  const d = pathData(outline, outline.points, { flipY: true });
  return [
    `<svg xmlns="http://www.w3.org/2000/svg" viewBox="${x0} ${y0} ${w} ${h}" width="${400 * w}" height="${400 * h}">`,
    `  <path d="${d}" fill="${fill}" fill-rule="nonzero" stroke="#5a2d0c" stroke-width="${0.004 * Math.max(w, h)}" stroke-linejoin="round"/>`,
    "</svg>",
    "",
  ].join("\n");
}

/**
 * An imported SVG's filled paths with their points moved (as `map` gives them, y up) as
 * an SVG document: vector art stays vector. Each path keeps its fill rule and its fill
 * colour, written as `fill="#rrggbb"` with `fill-opacity` when not opaque (a `fill` that
 * is not in the `rgba(R, G, B, A)` form of {@link VectorPath.fill} is written as it is);
 * paths whose colour is unknown (gradients, say) get `fill`. Strokes are not imported, so
 * none are written.
 */
export function vectorSvg(paths: readonly { path: VectorPath; points: Float64Array }[], fill = DEFAULT_FILL): string {
  const all = paths.flatMap(({ points }) => Array.from(points));
  const b = bounds(all);
  const margin = 0.02 * Math.max(b.maxX - b.minX, b.maxY - b.minY);
  const [x0, y0] = [b.minX - margin, -b.maxY - margin];
  const [w, h] = [b.maxX - b.minX + 2 * margin, b.maxY - b.minY + 2 * margin];
  const body = paths.map(
    ({ path, points }) =>
      `  <path d="${pathData(path, points, { flipY: true })}" ${fillAttributes(path.fill ?? fill)} fill-rule="${path.fillRule}"/>`,
  );
  return [`<svg xmlns="http://www.w3.org/2000/svg" viewBox="${x0} ${y0} ${w} ${h}">`, ...body, "</svg>", ""].join("\n");
}

/** `fill` (and `fill-opacity`) attributes for a CSS colour: `rgba()` as SVG 1.1 writes it. */
function fillAttributes(colour: string): string {
  const rgba = /^rgba\((\d{1,3}), (\d{1,3}), (\d{1,3}), ([^)]+)\)$/.exec(colour);
  const channels = rgba?.slice(1, 4).map(Number);
  const alpha = Number(rgba?.[4]);
  if (!channels || channels.some((c) => c > 255) || !(alpha >= 0 && alpha <= 1)) {
    return `fill="${escapeAttribute(colour)}"`;
  }
  const hex = "#" + channels.map((c) => c.toString(16).padStart(2, "0")).join("");
  return alpha === 1 ? `fill="${hex}"` : `fill="${hex}" fill-opacity="${alpha}"`;
}

function escapeAttribute(text: string): string {
  return text.replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/"/g, "&quot;");
}

/**
 * A shape in a pose (`positions`, a copy: the writer allocates in the memory a view of it
 * would see) as JSON or OBJ text, with its texture coordinates, and in JSON its painted
 * `stiffness` (OBJ has no place for it): the core's writers. With a depth order (`layers`)
 * the triangles are written back to front, as they are drawn (and the stiffness with them).
 */
export function posedMesh(
  shape: { mesh: { triangles: Uint32Array }; uvs: ArrayLike<number> },
  positions: Float64Array,
  format: "json" | "obj",
  extras: { stiffness?: Float64Array | undefined; layers?: Layering | undefined } = {},
): string {
  const { triangles, order } = backToFront(shape.mesh.triangles, extras.layers);
  const pose = { positions, triangles, uvs: Float64Array.from(shape.uvs) };
  if (format === "obj") return meshToObj(pose);
  const stiffness = extras.stiffness && order.map((t) => extras.stiffness![t]!);
  return meshToJson({ ...pose, ...(stiffness ? { stiffness } : {}) });
}

/** The triangles in drawing order, and the original index of each. */
function backToFront(
  triangles: Uint32Array,
  layers: Layering | undefined,
): { triangles: Uint32Array; order: number[] } {
  const order = Array.from({ length: triangles.length / 3 }, (_, t) => t);
  if (!layers) return { triangles, order };
  order.sort((a, b) => layers.triangles[a]! - layers.triangles[b]! || a - b);
  return { triangles: drawOrder(triangles, layers), order };
}

/**
 * The SVG of a shape in a pose: an imported SVG's own paths, their points carried through the
 * mesh (vector art stays vector), or else the posed outline. With a depth order (`layers`)
 * the paths are written back to front, each in the layer of the triangle under the middle of
 * its points at rest (the outline is one path, filled where any part is).
 */
export function posedSvg(
  mesh: { positions: Float64Array; triangles: Uint32Array; boundaryEdges: ArrayLike<number> },
  vector: readonly VectorPath[] | undefined,
  positions: Float64Array,
  layers?: Layering,
): string {
  if (!vector) return outlineSvg(positions, mesh.boundaryEdges);
  const layer = (path: VectorPath): number => {
    if (!layers) return 0;
    const p = path.points;
    const b = bounds(p);
    const middle = locate(mesh.positions, mesh.triangles, (b.minX + b.maxX) / 2, (b.minY + b.maxY) / 2, Infinity);
    return middle ? layers.triangles[middle.triangle]! : 0;
  };
  const ordered = vector.map((path, i) => ({ path, i, layer: layer(path) }));
  ordered.sort((a, b) => a.layer - b.layer || a.i - b.i);
  return vectorSvg(
    ordered.map(({ path }) => {
      const mapper = new PointMapper(mesh.positions, mesh.triangles, path.points);
      try {
        return { path, points: mapper.map(positions) };
      } finally {
        mapper.free();
      }
    }),
  );
}

/** Offers `data` to the user as a file download. */
export function download(document: Document, data: Blob | string, filename: string, type = "text/plain"): void {
  const blob = typeof data === "string" ? new Blob([data], { type }) : data;
  const url = URL.createObjectURL(blob);
  const link = document.createElement("a");
  link.href = url;
  link.download = filename;
  link.style.display = "none";
  document.body.append(link);
  link.click();
  link.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}
