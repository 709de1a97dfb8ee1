/**
 * Reading the user's files into shapes: SVG documents (parsed as data by our Rust code,
 * never put into the page), images (decoded by the browser, traced by our Rust code; the
 * image becomes the texture), and mesh files (OBJ, our JSON). Size limits come first, so
 * a huge file is refused before any work; every failure is an `Error` saying why, and
 * nothing of the widget changes until a shape is fully built.
 */
import { limits, meshFromArrays, type Outline } from "../../core.js";
import { shapeFromMesh, type Loaded, type Shape } from "../model/shape.js";
import { atlasTexture, vectorTexture } from "./vector-texture.js";
import { puppetAtlas } from "../model/atlas.js";
import { bounds } from "../model/geometry.js";
import { puppetOf, type PuppetSource } from "../model/puppet.js";
import {
  importImagePuppet,
  importPuppet,
  importSvg,
  importSvgPaths,
  meshFromJson,
  meshFromObj,
  textureCoordinates,
  traceImage,
  type ImportedOutline,
  type ImportedPuppet,
  type VectorPath,
} from "../../import.js";

/** Limits on what a user file may be: the library's own (see `limits()`). */
export function fileLimits(): { bytes: number; pixels: number } {
  const { bytes, pixels } = limits();
  return { bytes, pixels };
}

export type FileKind = "svg" | "image" | "obj" | "json";

/** The kind of a file from its name and type, or undefined if we cannot read it. */
export function fileKind(name: string, type = ""): FileKind | undefined {
  const extension = /\.([a-z0-9]+)$/i.exec(name)?.[1]?.toLowerCase() ?? "";
  if (extension === "svg" || type === "image/svg+xml") return "svg";
  if (["png", "jpg", "jpeg", "webp", "gif", "bmp", "avif"].includes(extension) || type.startsWith("image/")) {
    return "image";
  }
  if (extension === "obj") return "obj";
  if (extension === "json" || type === "application/json") return "json";
  return undefined;
}

/**
 * Reads a file (or a fetched blob with a name); an SVG of two or more layers, or an image
 * of two or more separate regions, is a puppet, imported with about `vertices` vertices.
 * Throws an `Error` naming the file.
 */
export async function readShapeFile(file: Blob, name: string, vertices: number): Promise<Loaded> {
  try {
    return await read(file, name, vertices);
  } catch (error) {
    const message = error instanceof Error ? error.message : String(error);
    if (message.startsWith(name)) throw error;
    throw new Error(`${name}: ${message}`, { cause: error });
  }
}

async function read(file: Blob, name: string, vertices: number): Promise<Loaded> {
  const kind = fileKind(name, file.type);
  if (!kind) {
    throw new Error(`${name}: not a file we can read (SVG, PNG, JPEG, WebP, GIF, OBJ or JSON mesh)`);
  }
  if (file.size > fileLimits().bytes) {
    throw new Error(`${name} is ${megabytes(file.size)}; the limit is ${megabytes(fileLimits().bytes)}`);
  }
  switch (kind) {
    case "svg": {
      const text = await file.text();
      const imported = importLayers(text, vertices);
      if (imported.parts.length > 1) return { kind: "puppet", name, source: { kind: "svg", text }, imported };
      const parts = importSvg(text);
      return { kind: "outlines", name, parts, vector: importSvgPaths(text) };
    }
    case "image":
      return readImage(file, name, vertices);
    case "obj": {
      const mesh = meshFromObj(await file.text());
      return { kind: "mesh", name, mesh, uvs: mesh.uvs };
    }
    case "json": {
      const mesh = meshFromJson(await file.text());
      return { kind: "mesh", name, mesh, uvs: mesh.uvs, ...(mesh.stiffness ? { stiffness: mesh.stiffness } : {}) };
    }
  }
}

async function readImage(file: Blob, name: string, vertices: number): Promise<Loaded> {
  let bitmap: ImageBitmap;
  try {
    bitmap = await createImageBitmap(file);
  } catch {
    throw new Error(`${name}: the browser could not decode this image`);
  }
  const { width, height } = bitmap;
  if (width * height > fileLimits().pixels) {
    bitmap.close();
    throw new Error(`${name} is ${width} x ${height} pixels; the limit is ${fileLimits().pixels} pixels`);
  }
  const canvas = document.createElement("canvas");
  canvas.width = width;
  canvas.height = height;
  const ctx = canvas.getContext("2d", { willReadFrequently: true });
  if (!ctx) throw new Error("this browser cannot read image pixels");
  ctx.drawImage(bitmap, 0, 0);
  bitmap.close();
  const pixels = ctx.getImageData(0, 0, width, height).data;
  const parts = traceImage(pixels, width, height);
  // The canvas, not the bitmap, is the texture: WebGL flips canvases for upload as asked,
  // but ignores the flip for ImageBitmaps.
  if (parts.length > 1) {
    // Separate regions: a puppet, a part per region, the image the art of each.
    const source: PuppetSource = { kind: "image", rgba: pixels, width, height };
    const imported = importPuppetSource(source, vertices);
    if (imported.parts.length > 1) return { kind: "puppet", name, source, imported, texture: canvas };
  }
  return { kind: "outlines", name, parts, image: { source: canvas, width, height } };
}

/** An imported outline as the core's `Outline`. */
export function asOutline(part: ImportedOutline): Outline {
  return { outer: part.outer, holes: part.holes };
}

function megabytes(bytes: number): string {
  return `${(bytes / 1024 / 1024).toFixed(1)} MB`;
}

/**
 * Part `index` of a loaded file as a shape: `mesh` meshes its outline (the widget does it
 * in a worker); an image becomes the texture, warped with the mesh, and SVG art is drawn
 * in its colours as the texture (and kept for vector export).
 */
export async function partShape<P extends { shape: Shape }>(
  document: Document,
  loaded: Extract<Loaded, { kind: "outlines" }>,
  index: number,
  mesh: (outline: Outline, label: string) => Promise<P>,
): Promise<P> {
  const prepared = await mesh(asOutline(loaded.parts[index]!), loaded.name);
  const shape = prepared.shape;
  if (loaded.image) {
    const { width, height } = loaded.image;
    shape.uvs = Float32Array.from(textureCoordinates(shape.mesh.positions, width, height));
    shape.texture = loaded.image.source;
  }
  if (loaded.vector) paintVector(document, shape, loaded.vector);
  return prepared;
}

/** An SVG's layers as a puppet with about `vertices` vertices in all (one part: not a puppet). */
export function importLayers(text: string, vertices: number): ImportedPuppet {
  return importPuppet(text, { vertices });
}

/**
 * A puppet imported again from its source at about `vertices` vertices: an SVG's layers,
 * or an image's separate regions.
 */
export function importPuppetSource(source: PuppetSource, vertices: number): ImportedPuppet {
  return source.kind === "svg"
    ? importLayers(source.text, vertices)
    : importImagePuppet(source.rgba, source.width, source.height, { vertices });
}

/**
 * A puppet as a shape: one mesh of every part's sheet, the parts and the joints the import
 * placed. An image's puppet (`texture`, the image, with an image `source`) takes the image
 * as its texture (its regions do not overlap, so each part shows its own pixels);
 * otherwise a texture atlas has each part's art alone in its tile (`model/atlas.ts`), so
 * what one part hides of another shows when they move apart, and the art, every part's
 * paths back to front, is kept for vector export. Parts without art (a puppet from a
 * session) are drawn with the widget's texture.
 */
export function puppetShape(
  document: Document,
  imported: ImportedPuppet,
  name: string,
  source: PuppetSource | undefined,
  texture?: TexImageSource,
): Shape {
  const mesh = meshFromArrays(imported.positions, imported.triangles);
  const puppet = puppetOf(imported, mesh.triangles, source);
  if (source?.kind === "image") {
    if (!texture) throw new Error(`${name}: the image of this puppet is missing`);
    const uvs = textureCoordinates(mesh.positions, source.width, source.height);
    const shape = shapeFromMesh(mesh, undefined, uvs, name);
    shape.puppet = puppet;
    shape.texture = texture;
    return shape;
  }
  if (puppet.parts.every((p) => p.paths.length === 0)) {
    // No art (a puppet rebuilt from a session): the widget's texture over the whole.
    const shape = shapeFromMesh(mesh, undefined, undefined, name);
    shape.puppet = puppet;
    return shape;
  }
  const { layout, uvs } = puppetAtlas(
    mesh.positions,
    mesh.triangles,
    puppet.parts.map((p) => p.triangles),
  );
  const shape = shapeFromMesh(mesh, undefined, uvs, name);
  shape.puppet = puppet;
  shape.vector = [...puppet.parts].sort((a, b) => a.depth - b.depth).flatMap((p) => p.paths);
  shape.texture = atlasTexture(
    document,
    puppet.parts.map((p) => p.paths),
    layout,
  );
  return shape;
}

/** Imported SVG art on a shape: kept for vector export, and drawn in its colours as the texture. */
export function paintVector(document: Document, shape: Shape, vector: VectorPath[]): void {
  shape.vector = vector;
  shape.texture = vectorTexture(document, vector, bounds(shape.mesh.positions)).canvas;
}

/** An image by URL (a texture), loaded for drawing across origins where the server allows it. */
export function loadImage(url: string): Promise<HTMLImageElement> {
  return new Promise((resolve, reject) => {
    const image = new Image();
    image.crossOrigin = "anonymous";
    image.onload = () => resolve(image);
    image.onerror = () => reject(new Error(`the image ${url} could not be loaded`));
    image.src = url;
  });
}

/** `fetch(url)`, with an error that says what went wrong when it fails or is not OK. */
export async function fetchFile(url: string): Promise<Response> {
  let response: Response;
  try {
    response = await fetch(url);
  } catch {
    throw new Error(`${url} could not be loaded (the address is wrong, or the server refused it)`);
  }
  if (!response.ok) throw new Error(`${url}: ${response.status} ${response.statusText}`);
  return response;
}
