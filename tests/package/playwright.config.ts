/**
 * The package check's browser part (run by scripts/test-package.mjs, which installs the
 * packed tarball into the project at AKAP_CONSUMER): the Vite app's production build and
 * dev server, and a plain page served as static files.
 */
import { defineConfig } from "@playwright/test";
import { join } from "node:path";
import browserTests from "../../playwright.config.js";

const project = process.env.AKAP_CONSUMER ?? "";
const base = Number(process.env.PACKAGE_PORT ?? 4331);
const vite = join(import.meta.dirname, "../../node_modules/.bin/vite");
export const SERVERS = {
  build: `http://127.0.0.1:${base}`,
  dev: `http://127.0.0.1:${base + 1}`,
  plain: `http://127.0.0.1:${base + 2}`,
};

export default defineConfig({
  testDir: ".",
  testMatch: "*.spec.ts",
  timeout: 60_000,
  retries: 0,
  workers: 1,
  reporter: [["list"]],
  // Chromium as the browser tests launch it.
  use: { launchOptions: browserTests.use?.launchOptions },
  webServer: [
    {
      command: `${vite} preview --host 127.0.0.1 --port ${base} --strictPort`,
      cwd: project,
      url: `${SERVERS.build}/`,
      reuseExistingServer: false,
    },
    {
      command: `${vite} --host 127.0.0.1 --port ${base + 1} --strictPort`,
      cwd: project,
      url: `${SERVERS.dev}/`,
      reuseExistingServer: false,
    },
    {
      command: `node ${join(import.meta.dirname, "static-server.mjs")} ${project} ${base + 2}`,
      url: `${SERVERS.plain}/plain/`,
      reuseExistingServer: false,
    },
  ],
});
