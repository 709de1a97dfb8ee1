/**
 * The demo app: triangulates the built-in shape and draws it, fitted to the window and
 * sharp on HiDPI screens, with a wireframe toggle. Internal to this repository; embedding
 * pages use the public API in `www/src/`.
 */
import { defaultShape, init, triangulate, type MeshData } from "../src/index.js";
import { drawMesh } from "./render.js";
import { fitView, type View } from "./view.js";

/** Edge length for the default shape, in shape units (the figure is about 1.4 tall). */
const DEFAULT_EDGE_LENGTH = 0.035;

interface State {
  mesh: MeshData;
  view: View;
  wireframe: boolean;
  pixelRatio: number;
}

/** What the browser tests read: the drawn mesh and the view that maps it to pixels. */
declare global {
  interface Window {
    akapDemo?: { state: State };
  }
}

function element<T extends HTMLElement>(id: string): T {
  const found = document.getElementById(id);
  if (!found) throw new Error(`the page has no #${id}`);
  return found as T;
}

function showError(message: string): void {
  const status = element<HTMLElement>("status");
  status.textContent = message;
  status.classList.add("error");
}

async function main(): Promise<void> {
  const canvas = element<HTMLCanvasElement>("stage");
  const wireframe = element<HTMLInputElement>("wireframe");
  const status = element<HTMLElement>("status");
  const ctx = canvas.getContext("2d");
  if (!ctx) throw new Error("this browser cannot draw on a 2D canvas");

  await init();
  const started = performance.now();
  const mesh = triangulate(defaultShape(), { targetEdgeLength: DEFAULT_EDGE_LENGTH, minAngle: 28 });
  const elapsed = performance.now() - started;
  status.textContent = `${mesh.vertexCount} vertices, ${mesh.triangleCount} triangles (triangulated in ${elapsed.toFixed(1)} ms)`;

  const state: State = {
    mesh,
    view: { scale: 1, offsetX: 0, offsetY: 0 },
    wireframe: wireframe.checked,
    pixelRatio: 1,
  };
  window.akapDemo = { state };

  const redraw = (): void => {
    // Canvas backing store in device pixels, CSS size from the layout.
    const ratio = window.devicePixelRatio || 1;
    const rect = canvas.getBoundingClientRect();
    const width = Math.max(1, Math.round(rect.width * ratio));
    const height = Math.max(1, Math.round(rect.height * ratio));
    if (canvas.width !== width || canvas.height !== height) {
      canvas.width = width;
      canvas.height = height;
    }
    state.pixelRatio = ratio;
    state.view = fitView(state.mesh.positions, width, height);
    drawMesh(ctx, state.mesh, state.view, { wireframe: state.wireframe, pixelRatio: ratio });
    canvas.dataset.frame = String(Number(canvas.dataset.frame ?? 0) + 1);
  };

  wireframe.addEventListener("change", () => {
    state.wireframe = wireframe.checked;
    redraw();
  });
  window.addEventListener("keydown", (event) => {
    if (event.key === "w" && !event.ctrlKey && !event.metaKey && !event.altKey) {
      wireframe.checked = !wireframe.checked;
      wireframe.dispatchEvent(new Event("change"));
    }
  });
  new ResizeObserver(redraw).observe(canvas);
  redraw();
  document.body.dataset.ready = "true";
}

main().catch((error: unknown) => {
  showError(error instanceof Error ? error.message : String(error));
  document.body.dataset.ready = "error";
  console.error(error);
});
