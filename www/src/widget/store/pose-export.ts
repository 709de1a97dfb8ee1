/**
 * Exports of the current pose: the mesh as JSON or Wavefront OBJ (the core's writers), the
 * outline or vector art as SVG, and a file download helper for pages.
 */
import { PointMapper, meshToJson, meshToObj, pathData, type PuppetPart, type VectorPath } from "../../import.js";
import type { PuppetJoint, PuppetSheet } from "../../core.js";
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
  const body = paths.map(({ path, points }) => `  ${pathElement(path, points, fill)}`);
  return [`<svg xmlns="http://www.w3.org/2000/svg" viewBox="${x0} ${y0} ${w} ${h}">`, ...body, "</svg>", ""].join("\n");
}

/** A `<path>` element for a vector path at `points` (y up, flipped to SVG's y down). */
function pathElement(path: VectorPath, points: Float64Array, fill: string): string {
  return `<path d="${pathData(path, points, { flipY: true })}" ${fillAttributes(path.fill ?? fill)} fill-rule="${path.fillRule}"/>`;
}

/** A part of a puppet with its art, as `importPuppet` gives it: its name, its sheet's
 * triangles (indices of the mesh's triangles), its depth (larger in front) and its paths
 * at rest (y up). */
export type PuppetArt = Pick<PuppetPart, "name" | "triangles" | "depth" | "paths">;

/** Inkscape's namespace, whose `label` and `groupmode` mark a layer. */
const INKSCAPE = "http://www.inkscape.org/namespaces/inkscape";

/**
 * A puppet's art in a pose as a layered SVG document: each part's paths carried through
 * its own sheet only (their points located at rest in the part's own triangles, so that
 * the torso's art under an arm stays with the torso however the arm moves, and a point
 * off its sheet follows the sheet's nearest triangle), written back to front (by `depth`,
 * parts of the same depth in their order), each part in its own layer, `<g
 * inkscape:groupmode="layer" inkscape:label="name" id="...">` (the `id` the name made an
 * XML name, unique). Paths keep their fill rule and colour as {@link vectorSvg} writes
 * them. `importPuppet` reads the file back with the same parts, names and order (a part
 * without paths has no area, so it is left out; a puppet of one part reads back as its
 * paths, the one layer being looked through).
 *
 * @param mesh The puppet's rest mesh: `positions` (x, y interleaved, y up) and `triangles`
 * (three vertex indices each), as `importPuppet` gives them.
 * @param parts The parts with their art (an `ImportedPuppet`'s `parts` as they are).
 * @param positions The pose: one x, y pair per rest vertex (a deformer's positions).
 * @param fill The colour of paths whose colour is unknown.
 * @returns The SVG text, y down, with a small margin around the posed art.
 */
export function puppetSvg(
  mesh: { positions: Float64Array; triangles: Uint32Array },
  parts: readonly PuppetArt[],
  positions: Float64Array,
  fill = DEFAULT_FILL,
): string {
  const order = parts.map((_, k) => k).sort((a, b) => parts[a]!.depth - parts[b]!.depth || a - b);
  const layers = order.map((k) => {
    const part = parts[k]!;
    return { part, points: mapOnSheet(mesh, part.triangles, part.paths, positions) };
  });
  const all = layers.flatMap(({ points }) => points.flatMap((p) => Array.from(p)));
  const b = bounds(all.length > 0 ? all : Array.from(positions));
  const margin = 0.02 * Math.max(b.maxX - b.minX, b.maxY - b.minY);
  const [x0, y0] = [b.minX - margin, -b.maxY - margin];
  const [w, h] = [b.maxX - b.minX + 2 * margin, b.maxY - b.minY + 2 * margin];
  const ids = new Set<string>();
  const body = layers.flatMap(({ part, points }) => {
    const id = uniqueId(part.name, ids);
    return [
      `  <g id="${id}" inkscape:groupmode="layer" inkscape:label="${escapeAttribute(part.name)}">`,
      ...part.paths.map((path, i) => `    ${pathElement(path, points[i]!, fill)}`),
      "  </g>",
    ];
  });
  return [
    `<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="${INKSCAPE}" viewBox="${x0} ${y0} ${w} ${h}">`,
    ...body,
    "</svg>",
    "",
  ].join("\n");
}

/**
 * The points of `paths` (each's own, at rest) carried to the pose `positions` through the
 * sheet of `triangles` alone: a mesh of those triangles and their vertices, located at
 * rest and mapped by {@link PointMapper}. Paths of a part without triangles stay where
 * they are (there is no sheet to carry them).
 */
function mapOnSheet(
  mesh: { positions: Float64Array; triangles: Uint32Array },
  triangles: ArrayLike<number>,
  paths: readonly { points: Float64Array }[],
  positions: Float64Array,
): Float64Array[] {
  const count = paths.reduce((n, p) => n + p.points.length, 0);
  if (triangles.length === 0 || count === 0) return paths.map((p) => Float64Array.from(p.points));
  // The sheet's vertices, numbered in the order met.
  const local = new Map<number, number>();
  const sheet = new Uint32Array(3 * triangles.length);
  for (let i = 0; i < triangles.length; i++) {
    const t = triangles[i]!;
    for (let c = 0; c < 3; c++) {
      const v = mesh.triangles[3 * t + c];
      if (v === undefined)
        throw new RangeError(`a part names triangle ${t}, but the mesh has ${mesh.triangles.length / 3}`);
      if (!local.has(v)) local.set(v, local.size);
      sheet[3 * i + c] = local.get(v)!;
    }
  }
  const rest = new Float64Array(2 * local.size);
  const posed = new Float64Array(2 * local.size);
  for (const [v, l] of local) {
    rest.set([mesh.positions[2 * v]!, mesh.positions[2 * v + 1]!], 2 * l);
    posed.set([positions[2 * v]!, positions[2 * v + 1]!], 2 * l);
  }
  const points = new Float64Array(count);
  let at = 0;
  for (const path of paths) {
    points.set(path.points, at);
    at += path.points.length;
  }
  const mapper = new PointMapper(rest, sheet, points);
  let mapped: Float64Array;
  try {
    mapped = mapper.map(posed);
  } finally {
    mapper.free();
  }
  at = 0;
  return paths.map((path) => mapped.slice(at, (at += path.points.length)));
}

/** An XML name for an element's `id` made of `name` (other characters become `_`, and
 * `part-` goes before one that cannot start a name), not among `taken` (then `-2`, `-3`,
 * ... is added); added to `taken`. */
function uniqueId(name: string, taken: Set<string>): string {
  let base = name.replace(/[^A-Za-z0-9_.-]/g, "_");
  if (!/^[A-Za-z_]/.test(base)) base = `part-${base}`;
  let id = base;
  for (let k = 2; taken.has(id); k++) id = `${base}-${k}`;
  taken.add(id);
  return id;
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

/** Text as an attribute's value in double quotes: `&`, `<` and `"` escaped, and white
 * space other than spaces written as character references, which XML keeps. */
function escapeAttribute(text: string): string {
  return text
    .replace(/&/g, "&amp;")
    .replace(/</g, "&lt;")
    .replace(/"/g, "&quot;")
    .replace(/[\t\n\r]/g, (c) => `&#${c.charCodeAt(0)};`);
}

/**
 * A shape in a pose (`positions`, a copy: the writer allocates in the memory a view of it
 * would see) as JSON or OBJ text, with its texture coordinates, and in JSON its painted
 * `stiffness` (OBJ has no place for it): the core's writers. With a depth order (`layers`)
 * the triangles are written back to front, as they are drawn (and the stiffness with them).
 * With a puppet (`extras.puppet`, its rest mesh, parts and joints), its parts are written
 * (their triangles renumbered with the order; OBJ's groups) and in JSON its joints where
 * they are in the pose ({@link posedJoints}), so that the file reads back as the puppet in
 * that pose.
 */
export function posedMesh(
  shape: { mesh: { triangles: Uint32Array }; uvs: ArrayLike<number> },
  positions: Float64Array,
  format: "json" | "obj",
  extras: {
    stiffness?: Float64Array | undefined;
    layers?: Layering | undefined;
    puppet?: PosedPuppet | undefined;
  } = {},
): string {
  const { triangles, order } = backToFront(shape.mesh.triangles, extras.layers);
  const pose = { positions, triangles, uvs: Float64Array.from(shape.uvs) };
  const puppet = extras.puppet;
  let sheets: Pick<PuppetSheet, "name" | "triangles" | "depth">[] | undefined;
  if (puppet) {
    const place = new Uint32Array(order.length);
    order.forEach((t, i) => (place[t] = i));
    sheets = puppet.parts.map(({ name, triangles, depth }) => ({
      name,
      depth,
      triangles: Uint32Array.from(triangles, (t) => place[t]!),
    }));
  }
  if (format === "obj") return meshToObj({ ...pose, ...(sheets ? { parts: sheets } : {}) });
  const stiffness = extras.stiffness && order.map((t) => extras.stiffness![t]!);
  const joints = puppet && posedJoints(puppet.mesh, puppet.parts, puppet.joints, positions);
  return meshToJson({ ...pose, ...(stiffness ? { stiffness } : {}), ...(sheets ? { parts: sheets, joints } : {}) });
}

/** A puppet as {@link posedMesh} takes it: its rest mesh, parts and joints. */
export interface PosedPuppet {
  mesh: { positions: Float64Array; triangles: Uint32Array };
  parts: readonly Pick<PuppetSheet, "name" | "triangles" | "depth">[];
  joints: readonly PuppetJoint[];
}

/**
 * A puppet's joints in a pose: each joint's point carried through its front part's sheet
 * and through its back part's (as {@link puppetSvg} carries art), and put halfway between
 * the two, which the deformers keep within a tiny fraction of the size of each other; so
 * the point lies on both posed sheets, as a joint's point must at rest.
 */
export function posedJoints(
  mesh: { positions: Float64Array; triangles: Uint32Array },
  parts: readonly Pick<PuppetSheet, "triangles">[],
  joints: readonly PuppetJoint[],
  positions: Float64Array,
): PuppetJoint[] {
  return joints.map(({ point, parts: [front, back] }) => {
    const at = (part: number) => {
      const sheet = parts[part];
      if (!sheet) throw new RangeError(`a joint names part ${part}, but the puppet has ${parts.length}`);
      return mapOnSheet(mesh, sheet.triangles, [{ points: Float64Array.from(point) }], positions)[0]!;
    };
    const [a, b] = [at(front), at(back)];
    return { point: [(a[0]! + b[0]!) / 2, (a[1]! + b[1]!) / 2], parts: [front, back] };
  });
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
