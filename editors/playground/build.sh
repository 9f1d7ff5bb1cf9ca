#!/usr/bin/env bash
# Builds the playground, a static site, into target/playground/ (index.html + assets/):
# crates/wasm for wasm32 (profile `playground`), wasm-bindgen's glue, wasm-opt -Oz, then the
# page bundled by esbuild (build.mjs). Installs what is missing: the rustup target,
# wasm-bindgen-cli of exactly the version in Cargo.lock, npm packages (package-lock.json).
# wasm-opt comes from Debian's `binaryen` (skipped with a warning when absent).
set -euo pipefail
cd "$(dirname "$0")/../.."
target="${CARGO_TARGET_DIR:-$PWD/target}"
export PATH="${CARGO_HOME:-$HOME/.cargo}/bin:$PATH"
rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown \
  || rustup target add wasm32-unknown-unknown
want=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/[^0-9.]/, ""); print; exit }' Cargo.lock)
have=$(wasm-bindgen --version 2>/dev/null | awk '{ print $2 }' || true)
if [ "$have" != "$want" ]; then
  # not --locked: its lock file names a webpki-roots some registry mirrors lack
  cargo install wasm-bindgen-cli --version "$want"
fi
cargo build --quiet --profile playground --target wasm32-unknown-unknown -p millpath-wasm
glue="$target/playground-wasm"
rm -rf "$glue"
mkdir -p "$glue"
wasm="$target/wasm32-unknown-unknown/playground/millpath_wasm.wasm"
# wasm-opt before wasm-bindgen: binaryen 108 (Debian 12) breaks the externref table that
# wasm-bindgen's output has
if command -v wasm-opt >/dev/null; then
  wasm-opt -Oz "$wasm" -o "$glue/millpath_wasm.wasm"
  wasm="$glue/millpath_wasm.wasm"
else
  echo "warning: wasm-opt not found (Debian: apt-get install binaryen); the wasm stays larger" >&2
fi
wasm-bindgen --target web --no-typescript --out-dir "$glue" "$wasm"
cd editors/playground
[ -d node_modules ] && [ node_modules/.package-lock.json -nt package-lock.json ] \
  || npm ci --no-audit --no-fund
node build.mjs "$glue" "$target/playground"
