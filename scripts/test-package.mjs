#!/usr/bin/env node
// The `package` check (issue 17): the npm package as its users get it. Packs the tarball
// (`npm pack`, whose prepack step builds the wasm and the library in release mode), checks
// what is in it, installs it into a new project in the system's temporary folder (outside
// the repository, so nothing resolves to the working tree; the fixture is
// tests/package/consumer), then, in that project:
//   - runs a Node script that poses a mesh and checks a rotation is reproduced;
//   - type-checks a consumer .ts file against the shipped .d.ts;
//   - builds the Vite app, then tests/package/*.spec.ts load it (production build and dev
//     server), a plain page with <akap-deformer> and workers in Chromium.
// The tools (tsc, vite, Playwright) are the repository's; the package under test is the
// tarball's. KEEP=1 keeps the temporary project and prints where it is.
import { execFileSync } from "node:child_process";
import { cpSync, mkdtempSync, readdirSync, rmSync, statSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, resolve } from "node:path";
import process from "node:process";

const root = resolve(import.meta.dirname, "..");
const bin = (name) => join(root, "node_modules", ".bin", name);
const work = mkdtempSync(join(tmpdir(), "akap-package-"));
const project = join(work, "project");

/** Runs a command, its output shown; `capture` returns its standard output instead. */
function run(command, args, cwd, { env = {}, capture = false } = {}) {
  console.log(`package: ${[command, ...args].join(" ")}  (in ${cwd === root ? "the repository" : cwd})`);
  const stdio = ["ignore", capture ? "pipe" : "inherit", "inherit"];
  const output = execFileSync(command, args, { cwd, stdio, env: { ...process.env, ...env } });
  return capture ? output.toString().trim() : "";
}

/** Files the package must hold, and patterns of what it must not. */
const REQUIRED = [
  "package.json",
  "README.md",
  "LICENSE-MIT",
  "LICENSE-APACHE",
  "www/pkg/akap_bg.wasm",
  "www/pkg/akap.js",
  "www/pkg/akap.d.ts",
  "www/lib/index.js",
  "www/lib/index.d.ts",
  "www/lib/widget/shapes/setup-worker.js",
  "www/lib/defop-worker.js",
];
const FORBIDDEN = [
  /^src\//,
  /^www\/src\//,
  /^tests\//,
  /^benches\//,
  /^examples\//,
  /^scripts\//,
  /^lab\//,
  /^generate\//,
  /\.rs$/,
  /\.ts$(?<!\.d\.ts)/,
];

let failed = false;
try {
  const name = run("npm", ["pack", "--loglevel", "warn", "--pack-destination", work], root, { capture: true })
    .split("\n")
    .at(-1);
  const tarball = join(work, name);
  const files = run("tar", ["-tzf", tarball], work, { capture: true })
    .split("\n")
    .map((f) => f.replace(/^package\//, ""));
  const missing = REQUIRED.filter((f) => !files.includes(f));
  const extra = files.filter((f) => FORBIDDEN.some((p) => p.test(f)));
  if (missing.length || extra.length) {
    throw new Error(
      `the tarball lacks ${missing.join(", ") || "nothing"} and holds ${extra.join(", ") || "nothing"} it should not`,
    );
  }
  console.log(`package: ${name}: ${files.length} files, ${(statSync(tarball).size / 1024).toFixed(0)} KiB`);

  cpSync(join(root, "tests/package/consumer"), project, { recursive: true });
  run("npm", ["install", "--no-audit", "--no-fund", "--prefer-offline", tarball], project);
  run("node", ["node-check.mjs"], project);
  run(bin("tsc"), ["-p", "tsconfig.json"], project);
  run(bin("vite"), ["build", "--logLevel", "warn"], project);
  run(bin("playwright"), ["test", "-c", join(root, "tests/package/playwright.config.ts")], root, {
    env: { AKAP_CONSUMER: project },
  });
  console.log(`package: passed (${readdirSync(join(project, "dist/assets")).length} assets in the Vite build)`);
} catch (error) {
  failed = true;
  console.error(`package: FAILED: ${error instanceof Error ? error.message : String(error)}`);
} finally {
  if (process.env.KEEP) console.log(`package: kept ${work}`);
  else rmSync(work, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
