#!/usr/bin/env bash
# The wasm benchmark of our sparse Cholesky (and faer's, also compiled to wasm) in Node.
# Builds the crate with the `bench` feature for Node into target/bench-pkg with the
# project's wasm flags (.cargo/config.toml: +simd128), and with --no-simd or --both also
# into target/bench-pkg-nosimd (RUSTFLAGS=-Ctarget-feature=-simd128, in the target directory
# wasm-nosimd so that the two builds do not invalidate each other); then runs
# lab/sparse/bench-wasm.mjs on each, which prints a markdown table.
#   lab/sparse/bench-wasm.sh [--no-simd|--both] [--max-vertices N] [--min-vertices N]
#                            [--shape bar|gingerbread] [--repeats N] [--ordering amd|best]
# Assumes scripts/setup.sh has run (wasm32 target, wasm-bindgen and wasm-pack on PATH).
set -euo pipefail
. "$(dirname "${BASH_SOURCE[0]}")/../../scripts/env.sh"

builds=(default)
case "${1:-}" in
  --no-simd) builds=(nosimd); shift ;;
  --both) builds=(default nosimd); shift ;;
esac

for build in "${builds[@]}"; do
  if [ "$build" = nosimd ]; then
    out=target/bench-pkg-nosimd
    say "wasm-pack build (release, bench feature, without simd128) -> $out"
    # RUSTFLAGS replaces the target's rustflags from .cargo/config.toml.
    CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}/wasm-nosimd" RUSTFLAGS="-C target-feature=-simd128" \
      with_wasm_toolchain wasm-pack --quiet build --release --target nodejs --mode no-install --no-pack \
      --out-dir "$out" --out-name akap -- --features bench
  else
    out=target/bench-pkg
    say "wasm-pack build (release, bench feature) -> $out"
    with_wasm_toolchain wasm-pack --quiet build --release --target nodejs --mode no-install --no-pack \
      --out-dir "$out" --out-name akap -- --features bench
  fi
  # The repository's package.json says "type": "module"; the nodejs target is CommonJS.
  printf '{ "type": "commonjs" }\n' >"$out/package.json"
  say "node lab/sparse/bench-wasm.mjs --pkg $out $*"
  node lab/sparse/bench-wasm.mjs --pkg "$out" "$@"
done
