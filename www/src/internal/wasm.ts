/**
 * Loads the WebAssembly module once, in a page or in Node. Internal: the public API in
 * `../index.ts` re-exports what users need.
 */
import initWasm, * as raw from "../../pkg/akap.js";

export { raw };

let ready: Promise<void> | undefined;
let loaded = false;
let memory: WebAssembly.Memory | undefined;

/** Bytes, a URL or a compiled module, as wasm-bindgen's initialiser accepts them. */
export type WasmSource = BufferSource | WebAssembly.Module | URL | string | Response;

function isNode(): boolean {
  const p = (globalThis as { process?: { versions?: { node?: string } } }).process;
  return typeof p?.versions?.node === "string" && typeof (globalThis as { window?: unknown }).window === "undefined";
}

async function readBesideThisModule(): Promise<BufferSource> {
  // A variable specifier keeps bundlers from pulling Node's fs into browser builds.
  const fsName = "node:fs/promises";
  const fs = (await import(/* @vite-ignore */ fsName)) as typeof import("node:fs/promises");
  return fs.readFile(new URL("../../pkg/akap_bg.wasm", import.meta.url));
}

/** Instantiates the module; later calls return the same promise. */
export function load(source?: WasmSource): Promise<void> {
  ready ??= (async () => {
    const input = source ?? (isNode() ? await readBesideThisModule() : undefined);
    const exports = await initWasm(input === undefined ? undefined : { module_or_path: input });
    memory = exports.memory;
    loaded = true;
  })().catch((error: unknown) => {
    ready = undefined;
    throw new Error(`could not load the akap WebAssembly module: ${String(error)}`, { cause: error });
  });
  return ready;
}

/** The module's linear memory (after `load`). Its buffer changes when it grows. */
export function wasmMemory(): WebAssembly.Memory {
  if (!memory) throw new Error("akap is not initialised: await init() first");
  return memory;
}

/** Throws a clear error when the module is used before `load` finished. */
export function assertLoaded(): void {
  if (!loaded) throw new Error("akap is not initialised: await init() first");
}
