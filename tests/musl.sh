#!/usr/bin/env bash
# The static Linux binary in CI: built for x86_64-unknown-linux-musl (profile `cross`, the
# release profile at opt-level 1: same outputs, half the build time), it must be static
# (file, ldd), run the README's command on the shipped example, and pass the reference
# conformance cases (skipped with a message when ../shared is absent). The release build
# itself (scripts/release.sh, profile release) is checked by tests/release_artifacts.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v musl-gcc >/dev/null || { apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q musl-tools file >/dev/null; }
command -v file >/dev/null || { apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q file >/dev/null; }
rustup target list --installed | grep -qx x86_64-unknown-linux-musl || rustup target add x86_64-unknown-linux-musl
cargo build --quiet --profile cross --target x86_64-unknown-linux-musl -p millpath --bin millpath
bin=${CARGO_TARGET_DIR:-$PWD/target}/x86_64-unknown-linux-musl/cross/millpath
pass=0 failed=0
check() {
  local what=$1
  shift
  if "$@"; then echo "ok - $what"; pass=$((pass + 1)); else echo "not ok - $what"; failed=$((failed + 1)); fi
}
static() { file "$bin" | grep -q 'statically linked\|static-pie linked' && ! ldd "$bin" 2>/dev/null | grep -q '=>'; }
check "the musl binary is static (file, ldd)" static
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# the README's command: the same files as the glibc build writes (when it is there)
readme() {
  local glibc=${CARGO_TARGET_DIR:-$PWD/target}/release/millpath
  mkdir -p "$tmp/musl" "$tmp/glibc"
  cp examples/plate/1234.1P.dxf examples/plate/millpath.toml "$tmp/musl/"
  "$bin" compile "$tmp/musl/1234.1P.dxf" >/dev/null 2>&1 && [ -s "$tmp/musl/1234.1P_Milling.gcode" ] || return 1
  [ -x "$glibc" ] || return 0
  cp examples/plate/1234.1P.dxf examples/plate/millpath.toml "$tmp/glibc/"
  "$glibc" compile "$tmp/glibc/1234.1P.dxf" >/dev/null 2>&1
  diff -r "$tmp/musl" "$tmp/glibc" >/dev/null
}
check "the README's command on the shipped example" readme
if [ -f ../shared/conformance/run.py ]; then
  check "the reference conformance cases" python3 ../shared/conformance/run.py --bin "$bin"
else
  echo "skipped: ../shared/conformance is not there"
fi
echo "$pass passed, $failed failed"
[ "$failed" -eq 0 ]
