#!/usr/bin/env bash
# Installs what building and testing need, skipping whatever is already there.
#
#   scripts/setup.sh          toolchain for the app: wasm32 target, wasm-bindgen, wasm-pack, npm packages
#   scripts/setup.sh --test   the same, plus Chromium for the browser tests
#
# The wasm32 target comes from rustup when it can download it (an ordinary machine with
# internet). Where rustup cannot (a machine that reaches only the package registries), it
# falls back to Debian's rustc-web toolchain and builds the wasm32 standard library once
# from Debian's rust-web-src (see ARCHITECTURE.md, "Toolchain"). The choice is written to
# target/toolchain.env, which the other scripts source.
#
# Every step prints what it does; a failing step says what failed and what to try.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"

want_browser=0
for arg in "$@"; do
  case "$arg" in
    --test) want_browser=1 ;;
    *) echo "setup: unknown argument '$arg' (expected --test)" >&2; exit 2 ;;
  esac
done

step() { printf '\033[1msetup:\033[0m %s\n' "$*"; }
fail() {
  printf '\033[1;31msetup failed:\033[0m %s\n' "$1" >&2
  [ $# -gt 1 ] && printf '  what to do: %s\n' "$2" >&2
  exit 1
}

as_root() {
  if [ "$(id -u)" = 0 ]; then "$@"; elif command -v sudo >/dev/null; then sudo "$@"; else
    fail "need root for: $*" "run this script as root or install sudo"
  fi
}

apt_updated=0
apt_install() {
  command -v apt-get >/dev/null || fail "missing packages: $*" "install them with your system's package manager"
  if [ "$apt_updated" = 0 ]; then
    step "apt-get update"
    as_root apt-get update -qq || fail "apt-get update failed" "check network access to the Debian mirrors"
    apt_updated=1
  fi
  step "apt-get install $*"
  DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq "$@" >/dev/null ||
    fail "apt-get install $* failed" "run it by hand to see the error"
}

mkdir -p target
cache="${XDG_CACHE_HOME:-$HOME/.cache}/akap-setup"
mkdir -p "$cache"

# --- Rust for the host ----------------------------------------------------------------------
command -v cargo >/dev/null || fail "cargo not found" "install Rust with rustup (https://rustup.rs), then re-run"
command -v node >/dev/null || fail "node not found" "install Node.js 20 or newer, then re-run"
command -v npm >/dev/null || fail "npm not found" "install npm (comes with Node.js), then re-run"
node_major="$(node -p 'process.versions.node.split(".")[0]')"
[ "$node_major" -ge 20 ] || fail "Node.js $node_major is too old" "install Node.js 20 or newer"

# --- Rust for wasm32 -------------------------------------------------------------------------
# WASM_PATH is prepended to PATH by the build scripts; empty means "use the default cargo".
wasm_std_present() { # $1 = rustc
  local libdir
  libdir="$("$1" --print target-libdir --target wasm32-unknown-unknown 2>/dev/null)" || return 1
  compgen -G "$libdir/libstd-*.rlib" >/dev/null
}

wasm_path=""
# AKAP_WASM_TOOLCHAIN=debian skips rustup (to test the fallback, or to prefer Debian's).
prefer_debian=0
[ "${AKAP_WASM_TOOLCHAIN:-auto}" = debian ] && prefer_debian=1
if [ "$prefer_debian" = 0 ] && wasm_std_present rustc; then
  step "wasm32 target: present in $(rustc --version)"
elif [ "$prefer_debian" = 0 ] && command -v rustup >/dev/null && [ ! -f "$cache/rustup-offline" ] &&
  { step "rustup target add wasm32-unknown-unknown (up to 60 s)"; timeout 60 rustup target add wasm32-unknown-unknown >/dev/null 2>&1; } &&
  wasm_std_present rustc; then
  step "wasm32 target: installed by rustup"
else
  # rustup cannot download here: remember that so that later runs do not wait 60 s again.
  [ "$prefer_debian" = 1 ] || touch "$cache/rustup-offline"
  step "wasm32 target: using Debian's rustc-web toolchain"
  need=()
  for p in rustc-web cargo-web rust-web-src rust-web-clippy lld-22; do
    dpkg -s "$p" >/dev/null 2>&1 || need+=("$p")
  done
  [ ${#need[@]} -eq 0 ] || apt_install "${need[@]}"
  [ -x /usr/bin/rust-lld ] || fail "/usr/bin/rust-lld missing after installing lld-22" "apt-get install --reinstall rust-web-llvm lld-22"
  deb_version="$(/usr/bin/rustc --version)"
  stamp="$cache/wasm-std.stamp"
  if ! wasm_std_present /usr/bin/rustc || [ "$(cat "$stamp" 2>/dev/null)" != "$deb_version" ]; then
    step "building the wasm32 standard library from rust-web-src with $deb_version (about a minute)"
    std_crate="$cache/wasm-std"
    rm -rf "$std_crate"
    mkdir -p "$std_crate/src"
    printf '[package]\nname = "akap_wasm_std"\nversion = "0.0.0"\nedition = "2021"\n[lib]\npath = "src/lib.rs"\n' >"$std_crate/Cargo.toml"
    : >"$std_crate/src/lib.rs"
    (cd "$std_crate" && PATH="/usr/bin:$PATH" RUSTC=/usr/bin/rustc RUSTC_BOOTSTRAP=1 \
      RUSTFLAGS=-Cembed-bitcode=yes /usr/bin/cargo build -q --release \
      --target wasm32-unknown-unknown -Zbuild-std=std,panic_abort,panic_unwind,test) ||
      fail "building the wasm32 standard library failed" "check that rust-web-src matches rustc-web (apt-get install --reinstall rust-web-src)"
    sysroot_lib="$(/usr/bin/rustc --print sysroot)/lib/rustlib/wasm32-unknown-unknown/lib"
    as_root mkdir -p "$sysroot_lib"
    for f in "$std_crate"/target/wasm32-unknown-unknown/release/deps/*.rlib; do
      case "$(basename "$f")" in libakap_wasm_std-*) continue ;; esac
      as_root cp "$f" "$sysroot_lib/"
    done
    echo "$deb_version" >"$stamp"
    wasm_std_present /usr/bin/rustc || fail "wasm32 standard library not found after building it" "delete $cache and re-run"
  fi
  wasm_path="/usr/bin"
fi

# Exact wasm-bindgen version of the lock file: the CLI must match the library bit for bit.
bindgen_version="$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/version = |"/, ""); print; exit }' Cargo.lock 2>/dev/null || true)"
[ -n "$bindgen_version" ] || fail "could not read the wasm-bindgen version from Cargo.lock" "run 'cargo generate-lockfile' and re-run"
if [ "$(wasm-bindgen --version 2>/dev/null | awk '{print $2}')" != "$bindgen_version" ]; then
  step "cargo install wasm-bindgen-cli $bindgen_version (a few minutes, once)"
  # No --locked: the CLI's own lock file can pin versions that a registry mirror lacks.
  cargo install -q wasm-bindgen-cli --version "=$bindgen_version" --force ||
    fail "cargo install wasm-bindgen-cli failed" "check access to crates.io and that a C compiler is installed"
else
  step "wasm-bindgen $bindgen_version: present"
fi
if ! command -v wasm-pack >/dev/null; then
  step "cargo install wasm-pack (a few minutes, once)"
  cargo install -q wasm-pack --locked || fail "cargo install wasm-pack failed" "check access to crates.io"
else
  step "wasm-pack: present"
fi

# --- Browser for tests -----------------------------------------------------------------------
chromium=""
if [ "$want_browser" = 1 ]; then
  for c in "${CHROMIUM_PATH:-}" /usr/bin/chromium /usr/bin/chromium-browser /usr/bin/google-chrome; do
    if [ -n "$c" ] && [ -x "$c" ]; then chromium="$c"; break; fi
  done
  if [ -z "$chromium" ]; then
    apt_install chromium
    chromium=/usr/bin/chromium
  fi
  step "browser for tests: $chromium"
fi

# --- npm packages ----------------------------------------------------------------------------
if [ ! -d node_modules ] || [ package-lock.json -nt node_modules/.package-lock.json ]; then
  step "npm ci"
  npm ci --no-audit --no-fund --loglevel=error 2>&1 | tail -n 20 || fail "npm ci failed" "check access to the npm registry; delete node_modules and re-run"
else
  step "npm packages: up to date"
fi

{
  echo "WASM_PATH=\"$wasm_path\""
  [ -n "$chromium" ] && echo "CHROMIUM_PATH=\"$chromium\""
  true
} >target/toolchain.env
step "done"
