/**
 * Keeping the user's work across reloads: the shape (a built-in shape by how it was
 * triangulated, anything else as its mesh, with an imported image's texture and an SVG's
 * paths), the pose, the handles and the settings, in IndexedDB under a key the page
 * chooses. Saved a moment after each change; read once when the widget starts.
 */
import type { VectorPath } from "../import.js";
import type { MeshPoint } from "./picking.js";
import type { ShapeSpec } from "./session.js";
import type { ToolbarSettings } from "./toolbar.js";

/** Settings that come back with the work: those the toolbar shows. */
export type SavedSettings = ToolbarSettings;

export type SavedShape =
  | { kind: "builtin"; spec: ShapeSpec }
  | {
      kind: "mesh";
      name: string;
      positions: Float64Array;
      triangles: Uint32Array;
      uvs: Float32Array;
      /** An imported image, as PNG. */
      texture?: Blob;
      vector?: VectorPath[];
    };

export interface SavedWork {
  format: "akap-work";
  version: 1;
  settings: SavedSettings;
  shape: SavedShape;
  positions: Float64Array;
  atRest: boolean;
  handles: { point: MeshPoint; target: [number, number] }[];
}

const DATABASE = "akap";
const STORE = "work";

/** Reads and writes one saved work under `key`. Every failure is an `Error` saying why. */
export class WorkStore {
  readonly key: string;
  #database: Promise<IDBDatabase> | undefined;

  constructor(key: string) {
    this.key = key;
  }

  /** The saved work, or undefined when there is none (or it is not a work of this version). */
  async load(): Promise<SavedWork | undefined> {
    const value = await this.#request("readonly", (store) => store.get(this.key));
    const work = value as Partial<SavedWork> | undefined;
    return work?.format === "akap-work" && work.version === 1 ? (work as SavedWork) : undefined;
  }

  async save(work: SavedWork): Promise<void> {
    await this.#request("readwrite", (store) => store.put(work, this.key));
  }

  async clear(): Promise<void> {
    await this.#request("readwrite", (store) => store.delete(this.key));
  }

  #open(): Promise<IDBDatabase> {
    this.#database ??= new Promise((resolve, reject) => {
      if (typeof indexedDB === "undefined") {
        reject(new Error("this browser has no IndexedDB"));
        return;
      }
      const request = indexedDB.open(DATABASE, 1);
      request.onupgradeneeded = () => request.result.createObjectStore(STORE);
      request.onsuccess = () => resolve(request.result);
      request.onerror = () => reject(new Error(`the browser's storage refused: ${request.error?.message}`));
    });
    return this.#database;
  }

  async #request(mode: IDBTransactionMode, make: (store: IDBObjectStore) => IDBRequest): Promise<unknown> {
    const database = await this.#open();
    return new Promise((resolve, reject) => {
      const request = make(database.transaction(STORE, mode).objectStore(STORE));
      request.onsuccess = () => resolve(request.result);
      request.onerror = () => reject(new Error(`the browser's storage refused: ${request.error?.message}`));
    });
  }
}

/** A canvas or image as a PNG blob (the texture of an imported image, to save). */
export function textureBlob(source: TexImageSource): Promise<Blob | undefined> {
  if (!(source instanceof HTMLCanvasElement)) return Promise.resolve(undefined);
  return new Promise((resolve) => source.toBlob((blob) => resolve(blob ?? undefined), "image/png"));
}

/** A saved PNG back as a canvas (the widget's textures are canvases, flipped on upload). */
export async function textureCanvas(document: Document, blob: Blob): Promise<HTMLCanvasElement> {
  const bitmap = await createImageBitmap(blob);
  const canvas = document.createElement("canvas");
  canvas.width = bitmap.width;
  canvas.height = bitmap.height;
  canvas.getContext("2d")?.drawImage(bitmap, 0, 0);
  bitmap.close();
  return canvas;
}
