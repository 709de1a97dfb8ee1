import { defineConfig } from "vite";

export default defineConfig({
  root: ".",
  build: {
    outDir: "dist",
    target: "es2022",
    rollupOptions: { input: { main: "index.html", embed: "www/examples/embed.html", rig: "www/examples/rig.html" } },
  },
  // The set-up worker is an ES module (it imports the wasm package).
  worker: { format: "es" },
  server: { host: "127.0.0.1", port: 5173 },
  preview: { host: "127.0.0.1", port: 4173 },
  test: {
    include: ["tests/unit/**/*.test.ts"],
    environment: "node",
  },
});
