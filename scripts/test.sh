#!/usr/bin/env bash
# npm test: installs what is missing, builds, and runs every check. All checks run even
# when one fails; the summary at the end lists each, and the exit code is non-zero if any
# failed. CHECKS="fmt clippy ..." runs a subset (names as in the summary).
set -uo pipefail
here="$(dirname "${BASH_SOURCE[0]}")"
bash "$here/setup.sh" --test || exit 1
. "$here/env.sh"
bash "$here/build.sh" || { say "build failed"; echo "checks: 0 passed, 1 failed"; exit 1; }

passed=()
failed=()
check() { # name, command...
  local name="$1"
  shift
  if [ -n "${CHECKS:-}" ] && [[ " $CHECKS " != *" $name "* ]]; then return; fi
  say "── $name: $*"
  local start=$SECONDS
  if "$@"; then
    passed+=("$name")
    say "── $name passed ($((SECONDS - start)) s)"
  else
    failed+=("$name")
    say "── $name FAILED ($((SECONDS - start)) s)"
  fi
}

# No import circles, in Rust (scripts/check-cycles.mjs, with its self-test) and in
# TypeScript (dependency-cruiser, which also keeps the widget's layering); each command runs
# even if one before it failed.
imports() {
  local status=0
  node scripts/check-cycles.mjs --self-test || status=1
  node scripts/check-cycles.mjs || status=1
  depcruise --config .dependency-cruiser.mjs --output-type err www/src || status=1
  return $status
}

# rustdoc with warnings as errors (broken and private links, bad HTML, ...), natively and for
# wasm32, where src/wasm/ is compiled.
docs() {
  local status=0
  RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --quiet || status=1
  RUSTDOCFLAGS="-D warnings" with_wasm_toolchain cargo doc --no-deps --quiet --target wasm32-unknown-unknown || status=1
  return $status
}

check fmt cargo fmt --all --check
check imports imports
# --features bench: the Cholesky bench and example need it (faer, sprs-ldl).
check clippy cargo clippy --all-targets --features bench --quiet -- -D warnings
check clippy-wasm with_wasm_toolchain cargo clippy --target wasm32-unknown-unknown --all-targets --quiet -- -D warnings
check doc docs
check cargo-test cargo test --quiet
check wasm-test with_wasm_toolchain wasm-pack test --node --release --mode no-install
check typecheck tsc --noEmit -p tsconfig.json
check lint bash -c 'eslint . && prettier --check . --log-level warn'
check unit vitest run
check browser env CHROMIUM_PATH="${CHROMIUM_PATH:-/usr/bin/chromium}" playwright test
check package env CHROMIUM_PATH="${CHROMIUM_PATH:-/usr/bin/chromium}" node scripts/test-package.mjs

echo
for name in "${passed[@]}"; do echo "  ok      $name"; done
for name in "${failed[@]}"; do echo "  FAILED  $name"; done
echo "checks: ${#passed[@]} passed, ${#failed[@]} failed"
[ ${#failed[@]} -eq 0 ]
