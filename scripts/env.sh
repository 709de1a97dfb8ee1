# Sourced by the other scripts: the repository root, the toolchain chosen by setup.sh,
# and helpers for printing steps.
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
export PATH="$root/node_modules/.bin:$HOME/.cargo/bin:$PATH"
if [ -f target/toolchain.env ]; then
  # shellcheck disable=SC1091
  . target/toolchain.env
fi
WASM_PATH="${WASM_PATH:-}"

# Runs a command with the wasm32-capable cargo and rustc first on PATH.
with_wasm_toolchain() {
  if [ -n "$WASM_PATH" ]; then
    PATH="$WASM_PATH:$PATH" RUSTC="$WASM_PATH/rustc" "$@"
  else
    "$@"
  fi
}

say() { printf '\033[1m%s:\033[0m %s\n' "$(basename "$0" .sh)" "$*"; }
