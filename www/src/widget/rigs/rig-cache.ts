/**
 * Trained rigs kept in the browser's IndexedDB by their content ({@link rigKey}: rest
 * mesh, handle points, training options), the 16 newest, so a reload or a return to the
 * same handles does not train again.
 */
import { DefOp } from "../../defop.js";
import type { MeshData } from "../../core.js";
import type { MeshPoint } from "../model/picking.js";
import { Rig, type RigTrainOptions } from "../model/rig.js";
import { KeyedStore } from "../store/database.js";

/** What the cache keeps of a rig. */
interface CachedRig {
  format: "akap-rig";
  version: 1;
  bytes: Uint8Array;
  radius: number;
  options: RigTrainOptions;
  savedAt: number;
}

/** Rigs kept at most; the oldest go first. */
const CACHED_RIGS = 16;

/** Trained rigs in the browser's IndexedDB, by {@link rigKey}. */
export class RigCache {
  readonly #store = new KeyedStore("rigs");

  /** The rig cached under `key` for `mesh` and `points`, or undefined. */
  async load(key: string, mesh: MeshData, points: readonly MeshPoint[]): Promise<Rig | undefined> {
    const cached = (await this.#store.get(key)) as Partial<CachedRig> | undefined;
    if (cached?.format !== "akap-rig" || cached.version !== 1 || !(cached.bytes instanceof Uint8Array))
      return undefined;
    const operator = DefOp.fromBytes(cached.bytes);
    try {
      return new Rig(operator, mesh, points, { radius: cached.radius, options: cached.options, source: "cache" });
    } catch (error) {
      operator.free();
      throw error;
    }
  }

  async save(key: string, rig: Rig): Promise<void> {
    const entry: CachedRig = {
      format: "akap-rig",
      version: 1,
      bytes: rig.toBytes(),
      radius: rig.radius ?? 0,
      options: rig.options ?? {},
      savedAt: Date.now(),
    };
    await this.#store.put(key, entry);
    const keys = await this.#store.keys();
    if (keys.length <= CACHED_RIGS) return;
    const dated = await Promise.all(
      keys.map(async (k) => ({ k, at: ((await this.#store.get(k)) as Partial<CachedRig> | undefined)?.savedAt ?? 0 })),
    );
    dated.sort((a, b) => a.at - b.at);
    for (const { k } of dated.slice(0, keys.length - CACHED_RIGS)) await this.#store.delete(k);
  }
}
