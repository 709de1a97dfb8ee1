/**
 * A texture atlas for a puppet: one square tile per part, laid out in a grid, each tile
 * showing its part's art alone over the part's own texture square (the {@link uvSquare}
 * of the part's rest bounding box). A part's triangles take texture coordinates in its
 * tile only, so parts that overlap at rest still show their own art, and what one part
 * hid of another shows when they move apart. Pure geometry: `shapes/vector-texture.ts`
 * draws the tiles.
 */
import { bounds, squareUvs, uvSquare, type UvSquare } from "./geometry.js";

/** One part's tile: where it lies in the texture (u right, v up, both 0..1) and what it shows. */
export interface AtlasTile {
  /** The tile's bottom-left corner in texture coordinates. */
  u0: number;
  v0: number;
  /** Its side in texture coordinates. */
  size: number;
  /** The shape-coordinate square the tile shows (the part's rest bounding box, grown to a square). */
  square: UvSquare;
}

/** Tiles per row and column of the grid, and each part's tile. */
export interface AtlasLayout {
  columns: number;
  tiles: AtlasTile[];
}

/** The clear margin round each tile, as a share of its grid cell (so mipmaps do not mix neighbours). */
export const ATLAS_MARGIN = 1 / 32;

/**
 * The atlas for parts whose rest bounding boxes are `boxes`: a grid of `columns` =
 * ceil(sqrt(n)) square cells a side (rows fill from the top), each part's tile its cell less
 * a margin of {@link ATLAS_MARGIN} of the cell on every side.
 */
export function atlasLayout(boxes: readonly { minX: number; minY: number; maxX: number; maxY: number }[]): AtlasLayout {
  if (boxes.length === 0) throw new RangeError("an atlas needs at least one part");
  const columns = Math.ceil(Math.sqrt(boxes.length));
  const cell = 1 / columns;
  const tiles = boxes.map((box, i) => {
    const column = i % columns;
    const row = Math.floor(i / columns);
    return {
      u0: column * cell + ATLAS_MARGIN * cell,
      // Row 0 at the top of the texture: v is up.
      v0: 1 - (row + 1) * cell + ATLAS_MARGIN * cell,
      size: cell * (1 - 2 * ATLAS_MARGIN),
      square: uvSquare(box),
    };
  });
  return { columns, tiles };
}

/**
 * The texture's side in pixels for a layout: about 1024 pixels a cell, at least 2048 and
 * at most 4096 (what every WebGL2 device can hold).
 */
export function atlasSide(layout: AtlasLayout): number {
  return Math.min(4096, Math.max(2048, 1024 * layout.columns));
}

/**
 * Each part's triangles' vertices (`parts[k]`: triangle indices of part k), as lists of
 * vertex indices. A vertex is in one part only (a puppet shares none between parts).
 */
export function partVertices(triangles: ArrayLike<number>, parts: readonly ArrayLike<number>[]): number[][] {
  return parts.map((list) => {
    const seen = new Set<number>();
    for (let i = 0; i < list.length; i++) for (let k = 0; k < 3; k++) seen.add(triangles[3 * list[i]! + k]!);
    return [...seen].sort((a, b) => a - b);
  });
}

/**
 * The atlas for a puppet's rest mesh, and its texture coordinates (2 per vertex): each
 * part's vertices through its tile's square (`squareUvs`, the one convention), then scaled
 * into the tile. Vertices of no part map to (0, 0), a clear corner.
 */
export function puppetAtlas(
  positions: ArrayLike<number>,
  triangles: ArrayLike<number>,
  parts: readonly ArrayLike<number>[],
): { layout: AtlasLayout; uvs: Float32Array } {
  const vertices = partVertices(triangles, parts);
  const boxes = vertices.map((list) => {
    if (list.length === 0) return { minX: 0, minY: 0, maxX: 0, maxY: 0 };
    const own = new Float64Array(2 * list.length);
    list.forEach((v, i) => own.set([positions[2 * v]!, positions[2 * v + 1]!], 2 * i));
    return bounds(own);
  });
  const layout = atlasLayout(boxes);
  const uvs = new Float32Array(positions.length);
  vertices.forEach((list, k) => {
    if (list.length === 0) return;
    const tile = layout.tiles[k]!;
    const own = new Float64Array(2 * list.length);
    list.forEach((v, i) => own.set([positions[2 * v]!, positions[2 * v + 1]!], 2 * i));
    const local = squareUvs(own, tile.square);
    list.forEach((v, i) => {
      uvs[2 * v] = tile.u0 + tile.size * local[2 * i]!;
      uvs[2 * v + 1] = tile.v0 + tile.size * local[2 * i + 1]!;
    });
  });
  return { layout, uvs };
}
