/**
 * Loads the WebAssembly module once, in a page or in Node, and hands out its bindings
 * (`raw`) with every call guarded: the bindings refuse bad input with `Error`s, but should
 * the instance ever trap (a `WebAssembly.RuntimeError`: memory exhausted by an allocation
 * that is not fallible, say), its state is no longer trustworthy. That call then throws an
 * `Error` that says so, and the bindings move to a fresh instance of the same compiled
 * module (a spare copy of wasm-bindgen's glue, imported ahead, since the glue holds its
 * instance in module state and initialises once): later calls work, while objects made by
 * the old instance throw, saying to make them again. Internal: the public API in
 * `../index.ts` re-exports what users need.
 */
import initWasm, * as glue from "../../pkg/akap.js";
import type { WasmSource } from "../core-types.js";

export type * as rawTypes from "../../pkg/akap.js";

/** What to do after a trap when no fresh instance can be made. */
const RELOAD = "reload the page, or restart the process";

/**
 * `module`'s bindings with every call guarded: functions called and classes constructed
 * (and their static methods) through `guarded`, and the objects they return with their
 * methods and getters guarded too. After a trap (a `WebAssembly.RuntimeError`) every call
 * throws `failure()`, an `Error` saying the instance stopped.
 */
export function guardBindings<M extends object>(
  module: M,
  onTrap: (error: WebAssembly.RuntimeError) => string = () => RELOAD,
): { bindings: M; failure(): Error | undefined } {
  let failure: Error | undefined;
  const guarded = <T>(call: () => T): T => {
    if (failure) throw new Error(failure.message, { cause: failure });
    let result: T;
    try {
      result = call();
    } catch (error) {
      if (error instanceof WebAssembly.RuntimeError) {
        failure = new Error(
          `the akap WebAssembly instance stopped (${error.message}) and cannot be used again; ` + onTrap(error),
          { cause: error },
        );
        throw failure;
      }
      throw error;
    }
    return wrap(result);
  };
  // Objects of the bindings (they have `free`) come back with their members guarded.
  const wrap = <T>(value: T): T => {
    const object = value as { free?: unknown } | null;
    if (typeof object !== "object" || object === null || typeof object.free !== "function") return value;
    return new Proxy(object, {
      get(target, key) {
        const member = guarded(() => Reflect.get(target, key, target) as unknown);
        return typeof member === "function"
          ? (...args: unknown[]) => guarded(() => (member as (...a: unknown[]) => unknown).apply(target, args))
          : member;
      },
    }) as T;
  };
  const guard = (binding: unknown): unknown => {
    if (typeof binding !== "function") return binding;
    return new Proxy(binding as (...args: unknown[]) => unknown, {
      apply: (target, self, args) => guarded(() => Reflect.apply(target, self, args)),
      construct: (target, args) => guarded(() => Reflect.construct(target, args) as object),
      get: (target, key) => guard(Reflect.get(target, key, target)),
    });
  };
  // A plain object, not a Proxy of the module: a module namespace's properties are fixed.
  const bindings = Object.fromEntries(Object.entries(module).map(([key, value]) => [key, guard(value)])) as M;
  return { bindings, failure: () => failure };
}

/** The compiled module, for fresh instances after a trap. */
let compiled: WebAssembly.Module | undefined;
/** A copy of the glue module not yet initialised, ready to hold a fresh instance. */
let spare: typeof glue | undefined;
let spares = 0;

/** The package's name: where its files are under `node_modules/`. */
const PACKAGE = "akap";

/**
 * Where a file of the package is served from when a dev server pre-bundled this module
 * away from the files beside it (Vite's dev server serves dependencies from
 * `/node_modules/.vite/deps/` without them, vitejs/vite#8427): the package's own folder,
 * which it serves too. `undefined` when this module was not moved. The callers keep the
 * `new URL("…", import.meta.url)` form for the usual case, which bundlers recognise and
 * rewrite in production builds.
 */
export function unbundledFile(pathInPackage: string): URL | undefined {
  const here = import.meta.url;
  const at = here.indexOf("/node_modules/.vite/");
  return at < 0 ? undefined : new URL(`${here.slice(0, at)}/node_modules/${PACKAGE}/${pathInPackage}`);
}

/**
 * Imports another copy of the glue (a distinct URL is a distinct module instance). Never
 * rejects: without a spare, a trap's message says to reload instead.
 */
async function prepareSpare(): Promise<void> {
  const url = unbundledFile("www/pkg/akap.js") ?? new URL("../../pkg/akap.js", import.meta.url);
  url.searchParams.set("instance", String(++spares));
  spare = await import(/* @vite-ignore */ url.href).then(
    (copy: typeof glue) => copy,
    () => undefined,
  );
}

/** After a trap: the bindings move to a fresh instance if one can be made now. */
function restart(): string {
  const copy = spare;
  if (!copy || !compiled) return RELOAD;
  spare = undefined;
  try {
    memory = copy.initSync({ module: compiled }).memory;
  } catch {
    return RELOAD;
  }
  current = guardBindings(copy, restart);
  Object.assign(raw, current.bindings);
  void prepareSpare();
  return "a new instance has started: make the objects you had (deformers, meshes, mappers) again";
}

let current = guardBindings(glue, restart);

/** The bindings, every call guarded (see the module's note). */
export const raw = { ...current.bindings };
let ready: Promise<void> | undefined;
let loaded = false;
let memory: WebAssembly.Memory | undefined;

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

/** The module compiled from `source` (bytes, a URL, a response or a module), or from the file beside this one. */
async function compile(source?: WasmSource): Promise<WebAssembly.Module> {
  if (source instanceof WebAssembly.Module) return source;
  if (source === undefined && isNode()) return WebAssembly.compile(await readBesideThisModule());
  if (source === undefined) {
    const url = unbundledFile("www/pkg/akap_bg.wasm") ?? new URL("../../pkg/akap_bg.wasm", import.meta.url);
    return WebAssembly.compile(await fetchWasm(url, true));
  }
  if (typeof source === "string" || source instanceof URL) return WebAssembly.compile(await fetchWasm(source, false));
  if (source instanceof Response) return WebAssembly.compile(await source.arrayBuffer());
  return WebAssembly.compile(source);
}

/**
 * The bytes at `url`, refused unless they are a WebAssembly module (servers answer a missing
 * file with their index page, too). `beside`: the URL was the default, so the message says
 * how to pass another.
 */
async function fetchWasm(url: string | URL, beside: boolean): Promise<ArrayBuffer> {
  const response = await fetch(url);
  const bytes = response.ok ? await response.arrayBuffer() : new ArrayBuffer(0);
  const magic = new Uint8Array(bytes, 0, Math.min(4, bytes.byteLength));
  if (String(magic) === "0,97,115,109") return bytes;
  const got = response.ok
    ? `a ${response.headers.get("content-type") ?? "file"} that is not WebAssembly`
    : `${response.status} ${response.statusText}`;
  throw new Error(
    `${response.url || String(url)} answered ${got}` +
      (beside
        ? "; if a bundler or server moved akap's files, pass the module to init(): its URL, bytes or a WebAssembly.Module"
        : ""),
  );
}

/** Instantiates the module; later calls return the same promise. */
export function load(source?: WasmSource): Promise<void> {
  ready ??= (async () => {
    compiled = await compile(source);
    const exports = await initWasm({ module_or_path: compiled });
    memory = exports.memory;
    loaded = true;
    await prepareSpare();
  })().catch((error: unknown) => {
    ready = undefined;
    throw new Error(`could not load the akap WebAssembly module: ${String(error)}`, { cause: error });
  });
  return ready;
}

/**
 * The compiled module (after `load`): hand it to a Worker, whose `init(module)` then
 * instantiates it without fetching or compiling again.
 */
export function wasmModule(): WebAssembly.Module {
  if (!compiled) throw new Error("akap is not initialised: await init() first");
  return compiled;
}

/** The module's linear memory (after `load`). Its buffer changes when it grows. */
export function wasmMemory(): WebAssembly.Memory {
  if (!memory) throw new Error("akap is not initialised: await init() first");
  return memory;
}

/** Throws a clear error when the module is used before `load` finished. */
export function assertLoaded(): void {
  const failure = current.failure();
  if (failure) throw new Error(failure.message, { cause: failure });
  if (!loaded) throw new Error("akap is not initialised: await init() first");
}

/**
 * The binding object behind each public wrapper that another wrapper hands to Rust (a
 * `DefOp` a `Deformer` poses with): wrappers keep their binding object private, and
 * register it here so that the other wrapper can find it without an import between the
 * two.
 */
const bindingObjects = new WeakMap<object, unknown>();

/** Registers `inner` as the binding object behind `wrapper` (`undefined`: freed). */
export function registerBinding(wrapper: object, inner: unknown): void {
  if (inner === undefined) bindingObjects.delete(wrapper);
  else bindingObjects.set(wrapper, inner);
}

/** The binding object behind `wrapper`, if it registered one and is not freed. */
export function bindingOf(wrapper: object): unknown {
  return bindingObjects.get(wrapper);
}
