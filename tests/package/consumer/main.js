// A Vite app: the widget mounted, and the core in a worker of the app's own.
import { mount, compiledModule } from "akap";

const widget = await mount(document.getElementById("mounted"), { hud: false });
window.embedded = { widget };
// The worker is handed the page's compiled module half the time and finds the wasm itself otherwise.
window.fromWorker = (share) =>
  new Promise((resolve) => {
    const worker = new Worker(new URL("./worker.js", import.meta.url), { type: "module" });
    worker.onmessage = (event) => resolve(event.data);
    worker.onerror = (event) => resolve({ error: event.message || "the worker did not load" });
    worker.postMessage({ wasm: share ? compiledModule() : undefined });
  });
