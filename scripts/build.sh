#!/usr/bin/env bash
# Builds everything the app and the npm package need, in release mode:
#   www/pkg   the wasm package (wasm-pack, --target web, usable from pages and Node)
#   www/lib   the public TypeScript API compiled to ESM with .d.ts
#   dist      the demo app bundled by Vite (not with --package: what `npm pack` needs)
# Assumes scripts/setup.sh has run (npm start and npm test run it first).
set -euo pipefail
. "$(dirname "${BASH_SOURCE[0]}")/env.sh"

say "wasm-pack build (release)"
with_wasm_toolchain wasm-pack --quiet build --release --target web --mode no-install --no-pack \
  --out-dir www/pkg --out-name akap
# wasm-pack writes a .gitignore of `*` there, which npm would honour and leave the wasm out
# of the package; the repository's own .gitignore keeps www/pkg out of git.
rm -f www/pkg/.gitignore
say "tsc (public API to www/lib)"
rm -rf www/lib
tsc -p tsconfig.lib.json
[ "${1:-}" = "--package" ] && { say "built (package)"; exit 0; }
say "vite build (app to dist)"
vite build --logLevel warn
say "built"
