/**
 * The widget's database in the browser (IndexedDB, opened once per page): one object
 * store for the work kept across reloads and one for trained rigs, read and written by
 * key. Every failure is an `Error` saying why.
 */

const DATABASE = "akap";
/** The object stores: the work (by the page's key, `work-store.ts`) and trained rigs (by their content, `rigs/rig-cache.ts`). */
const STORES = ["work", "rigs"] as const;

let database: Promise<IDBDatabase> | undefined;

/** The page's database of the widget, opened once (version 2 added the rigs). */
function openDatabase(): Promise<IDBDatabase> {
  database ??= new Promise((resolve, reject) => {
    if (typeof indexedDB === "undefined") {
      reject(new Error("this browser has no IndexedDB"));
      return;
    }
    const request = indexedDB.open(DATABASE, 2);
    request.onupgradeneeded = () => {
      for (const name of STORES) {
        if (!request.result.objectStoreNames.contains(name)) request.result.createObjectStore(name);
      }
    };
    request.onsuccess = () => resolve(request.result);
    request.onerror = () => reject(new Error(`the browser's storage refused: ${request.error?.message}`));
  });
  database.catch(() => (database = undefined));
  return database;
}

/** Values by key in one object store of the widget's database; every failure is an `Error` saying why. */
export class KeyedStore {
  readonly #store: (typeof STORES)[number];

  constructor(store: (typeof STORES)[number]) {
    this.#store = store;
  }

  get(key: string): Promise<unknown> {
    return this.#request("readonly", (store) => store.get(key));
  }

  async put(key: string, value: unknown): Promise<void> {
    await this.#request("readwrite", (store) => store.put(value, key));
  }

  async delete(key: string): Promise<void> {
    await this.#request("readwrite", (store) => store.delete(key));
  }

  /** Every key in the store. */
  async keys(): Promise<string[]> {
    return (await this.#request("readonly", (store) => store.getAllKeys())) as string[];
  }

  async #request(mode: IDBTransactionMode, make: (store: IDBObjectStore) => IDBRequest): Promise<unknown> {
    const db = await openDatabase();
    return new Promise((resolve, reject) => {
      const request = make(db.transaction(this.#store, mode).objectStore(this.#store));
      request.onsuccess = () => resolve(request.result);
      request.onerror = () => reject(new Error(`the browser's storage refused: ${request.error?.message}`));
    });
  }
}
