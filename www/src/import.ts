/**
 * Shapes in: SVG documents and images to outlines, layered drawings to puppets, mesh files
 * (OBJ, our JSON) in and out, and helpers that carry imported art along with a deformed
 * mesh. Re-exported by the package's main module; call `init()` first.
 *
 * @example
 * ```ts
 * import { init, importSvg, triangulate } from "akap";
 * await init();
 * const [largest] = importSvg(svgText); // separate parts come out largest first
 * const mesh = triangulate(largest!, { targetEdgeLength: 5 });
 * ```
 *
 * @module
 */
import { coded, type Indices, type Coordinates, toFloat64, toUint32 } from "./internal/arrays.js";
import { assertLoaded, raw, type rawTypes } from "./internal/wasm.js";
import type { MeshData, PuppetJoint, PuppetSheet } from "./core.js";
import { readMesh } from "./internal/mesh.js";

/** An imported outline: an outer ring and holes, x and y interleaved, y pointing up. */
export interface ImportedOutline {
  outer: Float64Array;
  holes: Float64Array[];
}

/** Options of {@link importSvg} and {@link importSvgPaths}. Every field is optional. */
export interface SvgImportOptions {
  /** Largest distance between a curve and its flattened outline, in SVG user units
   * (default: 1/1000 of the drawing's size). */
  tolerance?: number;
  /** Parts and holes with a smaller area are dropped (default 0). */
  minArea?: number;
  /** Whether strokes count as the area their outline covers (default true) or only fills
   * do. */
  strokes?: boolean;
  /** Most outline points after flattening (default 100000). */
  maxPoints?: number;
  /** Largest SVG text, in bytes (default 32 MiB). */
  maxBytes?: number;
}

/**
 * The filled and stroked shapes of an SVG document as outlines with holes, one per
 * separate part, largest first. Coordinates are the root `viewBox`'s user units with y
 * flipped to point up (the `viewBox`'s bottom-left corner is the origin). The document is
 * parsed as data, never inserted into a page, and resolved as browsers draw it (by usvg):
 * CSS `<style>` sheets and classes, `<use>`/`<symbol>`, units, `transform-origin`, markers.
 * A visible stroke counts as the area its outline covers (width, joins, caps, dashes)
 * unless `strokes: false`; clip paths cut what they clip; a mask counts as the union of
 * its shapes that let anything through; hidden things and text do not count. Overlapping
 * shapes are united exactly. Malformed attributes are read as browsers read them (path
 * data drawn up to its first error). Throws an `Error` for malformed XML (with its line),
 * a number beyond the coordinate limit (naming the element), or a document with no filled
 * shape.
 */
export function importSvg(text: string, options: SvgImportOptions = {}): ImportedOutline[] {
  assertLoaded();
  return raw.import_svg(text, options) as ImportedOutline[];
}

/** One filled area of an SVG (an element's fill or its stroke's outline), in the same
 * coordinates as {@link importSvg}. */
export interface VectorPath {
  /** The element, e.g. `<path id="body"> (line 3, column 5)` (the position is known for
   * elements with an `id`; others read `<path> (line 0, column 0)`). */
  element: string;
  /** Whether this is the element's fill or its stroke (drawn as a filled outline, in the
   * stroke's colour, so that it bends with the mesh). */
  part: "fill" | "stroke";
  /** One letter per command: M (1 point), L (1), Q (2), C (3), Z (0); arcs became C. */
  commands: string;
  /** The commands' points, x and y interleaved. */
  points: Float64Array;
  fillRule: "nonzero" | "evenodd";
  /**
   * The colour (the fill's, or the stroke's for a stroke) as a CSS colour, always
   * `rgba(R, G, B, A)` when it comes from {@link importSvgPaths}: R, G, B whole numbers
   * from 0 to 255, A from 0 to 1 with the paint's opacity and the `opacity` of the element
   * and its groups multiplied in. Usable as it is as a canvas `fillStyle` or an SVG `fill`.
   * `undefined` when the paint is a gradient or a pattern: the area still counts, so draw
   * it in a colour of your choice.
   */
  fill: string | undefined;
}

/**
 * The filled areas of an SVG document as vector paths (absolute M, L, Q, C, Z) in drawing
 * order (each element's fill, then its stroke's outline) with their fill rule and colour,
 * for exporting the art deformed: map `points` through the mesh with a
 * {@link PointMapper}, then write them with {@link pathData}. Where a clip path or mask
 * applies, the path is what is left of the area, flattened to lines.
 */
export function importSvgPaths(text: string, options: SvgImportOptions = {}): VectorPath[] {
  assertLoaded();
  return raw.import_svg_paths(text, options) as VectorPath[];
}

/**
 * SVG path data for a vector path with the given points (its own by default, or mapped
 * ones). `flipY` negates y, turning the y-up coordinates back into SVG's y-down ones.
 * Numbers are written in their shortest exact form (the one writer, in Rust).
 */
export function pathData(
  path: Pick<VectorPath, "commands" | "points">,
  points: Coordinates = path.points,
  options: { flipY?: boolean } = {},
): string {
  // Read as the bindings read their options (Rust's `read::Options`): a misspelt key or a
  // value of the wrong type is refused by name.
  const unknown = Object.keys(options).find((key) => key !== "flipY");
  if (unknown !== undefined) {
    throw coded(new Error(`unknown pathData option \`${unknown}\`; the options are flipY`), "invalid-option");
  }
  if (options.flipY !== undefined && typeof options.flipY !== "boolean") {
    throw coded(new Error(`option flipY must be true or false, not ${typeof options.flipY}`), "invalid-option");
  }
  assertLoaded();
  return raw.path_data(path.commands, toFloat64(points, "points"), options.flipY ?? false);
}

/** Options of {@link importPuppet}: those of {@link importSvg}, and `vertices`. */
export interface PuppetImportOptions extends SvgImportOptions {
  /** About how many vertices the puppet's mesh has in all, shared between the parts by
   * area, each part getting at least a few (default 3000). */
  vertices?: number;
}

/** One part of a puppet: a layer of the drawing, with its own sheet of the mesh. */
export interface PuppetPart extends PuppetSheet {
  /** The layer's `inkscape:label`, else its `id`, else "Part N" (N its place, from 1). */
  name: string;
  /** The part's own art (fills and strokes) in drawing order, as {@link importSvgPaths}
   * gives it: draw each part's paths in its own layer, back to front by depth. */
  paths: VectorPath[];
}

/** A layered drawing as a puppet: one mesh made of sheets, one per part, joined where
 * parts overlap. Pass `positions`, `triangles`, `parts` and `joints` to a `Deformer`. */
export interface ImportedPuppet {
  /** Every sheet's vertices, x and y interleaved, in the coordinates of {@link importSvg}. */
  positions: Float64Array;
  /** Every sheet's triangles, three vertex indices each; no vertex is shared between
   * parts. */
  triangles: Uint32Array;
  /** The parts, back to front (in document order). */
  parts: PuppetPart[];
  /** One joint per pair of parts that overlap (front on back); none for a part that
   * overlaps nothing. */
  joints: PuppetJoint[];
  /** Elements that are not imported (`text`, `image`, `foreignObject`), once each. */
  skipped: string[];
}

/**
 * Reads a layered SVG document as a puppet. Its parts are its layers: the top-level groups
 * (an Inkscape layer, or any `<g>` with an `id` or `inkscape:label`) and top-level shapes
 * outside groups, back to front in document order; a `<g>` with neither is looked
 * through, and a document whose only layer is a group of several takes those. Each part is
 * read as {@link importSvg} reads a whole document (overlapping shapes of a part united,
 * holes, strokes) and meshed on its own, to about `vertices` in all shared by area. Where a
 * part overlaps a part behind it, one joint is placed well inside the overlap (at its
 * centroid when that is well inside). Layers without area are left out. Throws as
 * {@link importSvg} throws, and for more than 256 layers.
 *
 * @example
 * ```ts
 * const puppet = importPuppet(svgText, { vertices: 3000 });
 * const d = new Deformer(puppet.positions, puppet.triangles, { method: "akap", parts: puppet.parts, joints: puppet.joints });
 * ```
 */
export function importPuppet(text: string, options: PuppetImportOptions = {}): ImportedPuppet {
  assertLoaded();
  return raw.importPuppet(text, options) as ImportedPuppet;
}

/** Options of {@link traceImage}. Every field is optional. */
export interface TraceOptions {
  /** "alpha": pixels whose alpha reaches `alphaThreshold`; "colour": pixels at least
   * `colourThreshold` away from the corners' colour; "auto" (default): alpha when the
   * corners are transparent, colour otherwise. */
  mode?: "auto" | "alpha" | "colour";
  /** Alpha from which a pixel is part of the shape, above 0 and at most 255 (default 128). */
  alphaThreshold?: number;
  /** RGB distance from the background from which a pixel is part of the shape (default 48). */
  colourThreshold?: number;
  /** Largest distance in pixels between the traced contour and the outline (default 0.75). */
  tolerance?: number;
  /** Parts and holes smaller than this many square pixels are dropped (default 12). */
  minArea?: number;
  /** Most outline points (default 100000). */
  maxPoints?: number;
  /** Largest image in pixels (default 4096 * 4096). */
  maxPixels?: number;
}

/**
 * Traces the shape in an image's RGBA pixels (rows from the top, as `ImageData.data`)
 * into outlines in pixel units with y up (the image's bottom-left corner is the origin),
 * one per separate part, largest first. Use {@link textureCoordinates} on the mesh's
 * positions to warp the image with it.
 */
export function traceImage(
  rgba: Uint8Array | Uint8ClampedArray,
  width: number,
  height: number,
  options: TraceOptions = {},
): ImportedOutline[] {
  assertLoaded();
  return raw.trace_image(pixelBytes(rgba, width, height), width, height, options) as ImportedOutline[];
}

/** The pixels as bytes, after checking the arguments' types and the size's counts. */
function pixelBytes(rgba: Uint8Array | Uint8ClampedArray, width: number, height: number): Uint8Array {
  if (!(rgba instanceof Uint8Array || rgba instanceof Uint8ClampedArray)) {
    throw coded(new TypeError("rgba must be a Uint8Array or Uint8ClampedArray"), "invalid-argument");
  }
  for (const [name, value] of [
    ["width", width],
    ["height", height],
  ] as const) {
    if (!Number.isInteger(value) || value < 1 || value > 0xffffffff)
      throw coded(new RangeError(`${name} is ${value}, not a pixel count`), "invalid-argument");
  }
  return rgba instanceof Uint8Array ? rgba : new Uint8Array(rgba.buffer, rgba.byteOffset, rgba.byteLength);
}

/** Options of {@link importImagePuppet}: those of {@link traceImage}, and `vertices`. */
export interface ImagePuppetOptions extends TraceOptions {
  /** About how many vertices the puppet's mesh has in all (default 3000). */
  vertices?: number;
}

/**
 * Traces an image's separate opaque regions (as {@link traceImage} does) into a puppet
 * with a part per region, named "Part 1" (the largest), "Part 2" and so on, in pixel units
 * with y up. Regions do not overlap, so there are no joints, and parts have no `paths`
 * (the image is their art: see {@link textureCoordinates}).
 */
export function importImagePuppet(
  rgba: Uint8Array | Uint8ClampedArray,
  width: number,
  height: number,
  options: ImagePuppetOptions = {},
): ImportedPuppet {
  assertLoaded();
  return raw.importImagePuppet(pixelBytes(rgba, width, height), width, height, options) as ImportedPuppet;
}

/**
 * Texture coordinates, interleaved, for positions in a traced image's pixel frame (y up,
 * origin at the image's bottom-left corner), in Wavefront OBJ's convention, the one the
 * widget, the mesh files and the renderers use: u = x / width from the left edge,
 * v = y / height up from the bottom edge (the centre of the top-left pixel is at
 * (0.5 / width, 1 - 0.5 / height)). Throws for a size that is not a finite number above 0,
 * a position that is not finite, and a coordinate that would overflow.
 */
export function textureCoordinates(positions: Coordinates, width: number, height: number): Float64Array {
  assertLoaded();
  return raw.texture_coordinates(toFloat64(positions, "positions"), width, height);
}

/** A mesh read from a file, with per-vertex texture coordinates if the file has them. */
export interface MeshFileData extends MeshData {
  /** u and v interleaved, one pair per vertex. */
  uvs?: Float64Array;
  /** One stiffness per triangle (JSON files only; see `Deformer.setStiffness`). */
  stiffness?: Float64Array;
}

function readMeshFile(file: rawTypes.MeshFile): MeshFileData {
  try {
    const mesh = file.mesh();
    try {
      const data: MeshFileData = readMesh(mesh);
      const uvs = file.uvs();
      if (uvs !== undefined) data.uvs = uvs;
      const stiffness = file.stiffness();
      if (stiffness !== undefined) data.stiffness = stiffness;
      return data;
    } finally {
      mesh.free();
    }
  } finally {
    file.free();
  }
}

/**
 * Reads a Wavefront OBJ mesh in the xy plane (`v`, `vt`, `f`; polygons are fanned into
 * triangles, negative indices count back). Validated like {@link meshFromArrays}: throws
 * an `Error` naming the line and column, or the mesh problem.
 */
export function meshFromObj(text: string): MeshFileData {
  assertLoaded();
  return readMeshFile(raw.mesh_from_obj(text));
}

/**
 * Reads our JSON mesh format: `{ "positions": [...], "triangles": [...], "uvs"?: [...],
 * "stiffness"?: [...] }` (`stiffness`: one per triangle, from 0.001 to 1000).
 */
export function meshFromJson(text: string): MeshFileData {
  assertLoaded();
  return readMeshFile(raw.mesh_from_json(text));
}

/**
 * A mesh to write: positions and triangles, optionally texture coordinates. The positions
 * may be a pose of the mesh (a deformer's): flipped or collapsed triangles are written as
 * they are; only indices, finite coordinates and sizes are checked. (Reading such a file
 * back as a mesh refuses them, as every rest mesh's are.)
 */
export interface MeshToWrite {
  positions: Coordinates;
  triangles: Indices;
  uvs?: Coordinates;
  /** One stiffness per triangle, written by {@link meshToJson} (OBJ has no place for it). */
  stiffness?: Coordinates;
}

function writeArgs(mesh: MeshToWrite): [Float64Array, Uint32Array, Float64Array | undefined] {
  const uvs = mesh.uvs === undefined ? undefined : toFloat64(mesh.uvs, "uvs");
  return [toFloat64(mesh.positions, "positions"), toUint32(mesh.triangles, "triangles"), uvs];
}

/** Writes a mesh or a pose of one as Wavefront OBJ, with `vt` lines when it has uvs. */
export function meshToObj(mesh: MeshToWrite): string {
  assertLoaded();
  return raw.mesh_to_obj(...writeArgs(mesh));
}

/** Writes a mesh or a pose of one in our JSON format, with its uvs and stiffness when given. */
export function meshToJson(mesh: MeshToWrite): string {
  assertLoaded();
  const stiffness = mesh.stiffness === undefined ? undefined : toFloat64(mesh.stiffness, "stiffness");
  return raw.mesh_to_json(...writeArgs(mesh), stiffness);
}

/**
 * Points (say, an SVG's path points) located once in a rest mesh by barycentric
 * coordinates, then carried along to any deformed pose of it. Points outside the mesh
 * follow the nearest triangle. Call {@link PointMapper.free} when done.
 */
export class PointMapper {
  #inner: rawTypes.PointMapper | undefined;

  constructor(restPositions: Coordinates, triangles: Indices, points: Coordinates) {
    assertLoaded();
    this.#inner = new raw.PointMapper(
      toFloat64(restPositions, "restPositions"),
      toUint32(triangles, "triangles"),
      toFloat64(points, "points"),
    );
  }

  /** The wasm object, or an Error once {@link free} was called. */
  get #raw(): rawTypes.PointMapper {
    if (!this.#inner) throw new Error("this PointMapper was freed; make a new one");
    return this.#inner;
  }

  /** The points in the pose `deformedPositions` (one xy pair per rest vertex). */
  map(deformedPositions: Coordinates): Float64Array {
    return this.#raw.map(toFloat64(deformedPositions, "deformedPositions"));
  }

  /** Number of points. */
  get length(): number {
    return this.#raw.length;
  }

  /** Releases the WebAssembly memory. */
  free(): void {
    this.#raw.free();
    this.#inner = undefined;
  }
}

/** Carries `points` from the rest mesh to the deformed positions in one call. */
export function mapPoints(
  restPositions: Coordinates,
  triangles: Indices,
  deformedPositions: Coordinates,
  points: Coordinates,
): Float64Array {
  const mapper = new PointMapper(restPositions, triangles, points);
  try {
    return mapper.map(deformedPositions);
  } finally {
    mapper.free();
  }
}
