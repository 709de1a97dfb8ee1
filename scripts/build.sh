#!/usr/bin/env bash
# Builds everything the app and the npm package need, in release mode:
#   www/pkg   the wasm package (wasm-pack, --target web, usable from pages and Node)
#   www/lib   the public TypeScript API compiled to ESM with .d.ts
#   dist      the demo app bundled by Vite
# Assumes scripts/setup.sh has run (npm start and npm test run it first).
set -euo pipefail
. "$(dirname "${BASH_SOURCE[0]}")/env.sh"

say "wasm-pack build (release)"
with_wasm_toolchain wasm-pack --quiet build --release --target web --mode no-install --no-pack \
  --out-dir www/pkg --out-name akap
say "tsc (public API to www/lib)"
tsc -p tsconfig.lib.json
say "vite build (app to dist)"
vite build --logLevel warn
say "built"
