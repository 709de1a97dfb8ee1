/**
 * A texture drawn from imported vector art: every path filled with its colour and fill
 * rule on a canvas that covers the shape, so the art deforms with the mesh; for a puppet,
 * an atlas with each part's art alone in its tile.
 */
import { pathData, type VectorPath } from "../../import.js";
import { DEFAULT_FILL } from "../store/pose-export.js";
import { atlasSide, type AtlasLayout } from "../model/atlas.js";
import { uvSquare, type UvSquare } from "../model/geometry.js";
import type { View } from "../view/projection.js";

/** The default longest side of a vector texture, in pixels. */
export const DEFAULT_TEXTURE_SIDE = 2048;

/** Where a texture lies in shape coordinates. */
export interface TextureMapping {
  /** The canvas's width and height in pixels (it is square). */
  side: number;
  /** The shape-coordinate square the canvas covers, the one `boxUvs` (geometry.ts) uses. */
  square: UvSquare;
  /** Shape coordinates (y up) to canvas pixels (y down, from the top-left corner):
   * `pixel = (offsetX + scale * x, offsetY - scale * y)`. */
  view: View;
}

/**
 * The canvas for a shape's bounding box `b`: it covers the {@link uvSquare} of `b` (the
 * box grown to a square about its centre), `side` = `floor(maxSide)` pixels across, the
 * square's top-left corner `(x0, y0 + size)` at pixel (0, 0) and its bottom-right corner
 * `(x0 + size, y0)` at pixel (side, side). So a point's texture coordinates, u = px / side
 * and v = 1 - py / side, are u = (x - x0) / size and v = (y - y0) / size: exactly
 * `boxUvs` of the rest positions when `b` is their bounding box (with v = 0 at the
 * canvas's bottom row, as the renderer uploads canvases flipped).
 */
export function textureMapping(
  b: { minX: number; minY: number; maxX: number; maxY: number },
  maxSide = DEFAULT_TEXTURE_SIDE,
): TextureMapping {
  if (![b.minX, b.minY, b.maxX, b.maxY].every(Number.isFinite) || b.maxX < b.minX || b.maxY < b.minY) {
    throw new RangeError(`the bounding box ${JSON.stringify(b)} is not a finite box`);
  }
  if (!(Number.isFinite(maxSide) && maxSide >= 1)) throw new RangeError(`maxSide is ${maxSide}, not a pixel count`);
  const side = Math.floor(maxSide);
  const square = uvSquare(b);
  const scale = side / square.size;
  return { side, square, view: { scale, offsetX: -square.x0 * scale, offsetY: (square.y0 + square.size) * scale } };
}

/** A texture of vector art, and where it lies. */
export interface VectorTexture extends TextureMapping {
  canvas: HTMLCanvasElement;
}

/**
 * Draws `paths` (shape coordinates, y up) into a new canvas laid out by
 * {@link textureMapping}: each path filled with its {@link VectorPath.fill} (`fill` when
 * unknown) by its fill rule, in document order, the rest transparent. Texture coordinates
 * for the mesh: `boxUvs(restPositions)` when `bounds` is the rest positions' bounding box,
 * else `squareUvs(positions, texture.square)`.
 */
export function vectorTexture(
  document: Document,
  paths: readonly (VectorPath | { path: VectorPath })[],
  bounds: { minX: number; minY: number; maxX: number; maxY: number },
  maxSide = DEFAULT_TEXTURE_SIDE,
  fill = DEFAULT_FILL,
): VectorTexture {
  const mapping = textureMapping(bounds, maxSide);
  const canvas = document.createElement("canvas");
  canvas.width = mapping.side;
  canvas.height = mapping.side;
  const ctx = canvas.getContext("2d");
  if (!ctx) throw new Error("this browser cannot draw on a canvas");
  const { scale, offsetX, offsetY } = mapping.view;
  // The path data stays in shape coordinates; the canvas maps them, flipping y.
  ctx.setTransform(scale, 0, 0, -scale, offsetX, offsetY);
  for (const entry of paths) {
    const path = "path" in entry ? entry.path : entry;
    ctx.fillStyle = fill;
    // A colour the canvas cannot parse leaves the default in place.
    if (path.fill !== undefined) ctx.fillStyle = path.fill;
    ctx.fill(new Path2D(pathData(path)), path.fillRule);
  }
  return { ...mapping, canvas };
}

/**
 * A puppet's texture atlas (see `model/atlas.ts`): a square canvas `side` pixels across
 * with each part's art (`parts[k]`, drawn as {@link vectorTexture} draws paths) alone in
 * its tile of `layout`, clipped to the tile, the rest transparent.
 */
export function atlasTexture(
  document: Document,
  parts: readonly (readonly VectorPath[])[],
  layout: AtlasLayout,
  side = atlasSide(layout),
  fill = DEFAULT_FILL,
): HTMLCanvasElement {
  const canvas = document.createElement("canvas");
  canvas.width = side;
  canvas.height = side;
  const ctx = canvas.getContext("2d");
  if (!ctx) throw new Error("this browser cannot draw on a canvas");
  layout.tiles.forEach((tile, k) => {
    const { x0, y0, size } = tile.square;
    // Shape point (x, y) to pixel (side u, side (1 - v)), where u = u0 + s (x - x0) / size
    // and v = v0 + s (y - y0) / size: the tile's texture coordinates (v up).
    const scale = (side * tile.size) / size;
    ctx.save();
    ctx.beginPath();
    ctx.rect(side * tile.u0, side * (1 - tile.v0 - tile.size), side * tile.size, side * tile.size);
    ctx.clip();
    ctx.setTransform(scale, 0, 0, -scale, side * tile.u0 - scale * x0, side * (1 - tile.v0) + scale * y0);
    for (const path of parts[k] ?? []) {
      ctx.fillStyle = fill;
      if (path.fill !== undefined) ctx.fillStyle = path.fill;
      ctx.fill(new Path2D(pathData(path)), path.fillRule);
    }
    ctx.restore();
  });
  return canvas;
}
