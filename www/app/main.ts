/**
 * The app: the posing widget filling the window, with its toolbar and HUD. URL
 * parameters pick the start: `?shape=gingerbread&vertices=5000&method=akap`, or a file
 * `?src=url`. The toolbar's shape list adds the gallery in `www/gallery/`. Internal to
 * this repository; embedding pages use `mount` or `<akap-deformer>` from the package.
 */
/// <reference types="vite/client" />
import {
  METHODS,
  builtinShapes,
  init,
  mount,
  type GalleryItem,
  type MethodPreset,
  type Widget,
  type WidgetOptions,
} from "../src/index.js";
import { maxVertices } from "../src/widget/model/shape.js";
import galleryIndex from "../gallery/index.json";

/** The gallery files, as URLs the bundler serves. */
const galleryFiles = import.meta.glob<string>("../gallery/*.{svg,png}", {
  query: "?url",
  import: "default",
  eager: true,
});
const gallery: GalleryItem[] = galleryIndex.flatMap((item) => {
  const url = galleryFiles[`../gallery/${item.file}`];
  return url ? [{ name: item.name, url }] : [];
});

/** What the browser tests and benchmarks read. */
declare global {
  interface Window {
    akapDemo?: { widget: Widget };
  }
}

/**
 * Widget options from the URL, and what was wrong with it: a parameter that cannot be used
 * is left out (the widget starts with its default) and named in the message.
 */
function optionsFromUrl(params: URLSearchParams): { options: WidgetOptions; problems: string[] } {
  // The app keeps the user's work across reloads (not when the URL asks for a shape).
  const options: WidgetOptions = { gallery, storageKey: "akap-app", timeline: true };
  const problems: string[] = [];
  const shape = params.get("shape");
  if (shape !== null) {
    if (builtinShapes().includes(shape)) options.shape = shape;
    else problems.push(`?shape=${shape} is not a built-in shape (${builtinShapes().join(", ")})`);
  }
  const vertices = params.get("vertices");
  if (vertices !== null) {
    const count = Number(vertices);
    if (vertices.trim() !== "" && Number.isFinite(count) && count >= 50 && count <= maxVertices()) {
      options.vertices = count;
    } else {
      problems.push(`?vertices=${vertices} is not a number from 50 to ${maxVertices()}`);
    }
  }
  const method = params.get("method");
  if (method !== null) {
    if (Object.hasOwn(METHODS, method)) options.method = method as MethodPreset;
    else problems.push(`?method=${method} is not a method (${Object.keys(METHODS).join(", ")})`);
  }
  const hud = params.get("hud");
  if (hud === "false") options.hud = false;
  else if (hud !== null && hud !== "true") problems.push(`?hud=${hud} is not true or false`);
  const gpu = params.get("gpu");
  if (gpu === "false") options.gpuRigs = false;
  else if (gpu !== null && gpu !== "true") problems.push(`?gpu=${gpu} is not true or false`);
  const src = params.get("src");
  if (src) options.src = src;
  return { options, problems };
}

async function main(): Promise<void> {
  const stage = document.getElementById("app");
  if (!stage) throw new Error("the page has no #app");
  await init();
  const { options, problems } = optionsFromUrl(new URLSearchParams(window.location.search));
  let widget: Widget;
  try {
    widget = await mount(stage, options);
  } catch (error) {
    // Most likely the file of ?src=: start with the default figure and say why.
    problems.push(error instanceof Error ? error.message : String(error));
    widget = await mount(stage, { ...options, src: undefined });
  }
  if (problems.length > 0) {
    widget.showMessage(`${problems.join("; ")}. Showing the default instead.`, "error");
  }
  window.akapDemo = { widget };
  document.body.dataset.ready = "true";
}

main().catch((error: unknown) => {
  const status = document.getElementById("fatal");
  if (status) status.textContent = error instanceof Error ? error.message : String(error);
  document.body.dataset.ready = "error";
  console.error(error);
});
