/**
 * The app: the posing widget filling the window, with its toolbar and HUD. URL
 * parameters pick the start: `?shape=gingerbread&vertices=5000&method=akap`, or a file
 * `?src=url`. The toolbar's shape list adds the gallery in `www/gallery/`. Internal to
 * this repository; embedding pages use `mount` or `<akap-deformer>` from the package.
 */
/// <reference types="vite/client" />
import { mount, type GalleryItem, type Method, type Widget, type WidgetOptions } from "../src/index.js";
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

async function main(): Promise<void> {
  const stage = document.getElementById("app");
  if (!stage) throw new Error("the page has no #app");
  const params = new URLSearchParams(window.location.search);
  const options: WidgetOptions = { gallery };
  const src = params.get("src");
  if (src) options.src = src;
  const shape = params.get("shape");
  if (shape) options.shape = shape;
  const vertices = params.get("vertices");
  if (vertices) options.vertices = Number(vertices);
  const method = params.get("method");
  if (method) options.method = method as Method;
  if (params.get("hud") === "false") options.hud = false;
  const widget = await mount(stage, options);
  window.akapDemo = { widget };
  document.body.dataset.ready = "true";
}

main().catch((error: unknown) => {
  const status = document.getElementById("fatal");
  if (status) status.textContent = error instanceof Error ? error.message : String(error);
  document.body.dataset.ready = "error";
  console.error(error);
});
