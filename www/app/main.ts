/**
 * The app: the posing widget filling the window, with its toolbar and HUD. URL
 * parameters pick the start: `?shape=gingerbread&vertices=5000&method=akap`. Internal to
 * this repository; embedding pages use `mount` or `<akap-deformer>` from the package.
 */
import { mount, type Method, type Widget, type WidgetOptions } from "../src/index.js";

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
  const options: WidgetOptions = {};
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
