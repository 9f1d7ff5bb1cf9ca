#!/usr/bin/env bash
# Builds the release artefacts into target/release-artifacts/:
#   millpath-linux-x64          static Linux binary (x86_64-unknown-linux-musl), any distribution
#   millpath.exe                Windows x64 (x86_64-pc-windows-gnu, MinGW-w64)
#   millpath-linux-x64.vsix     VS Code extension with the Linux server
#   millpath-win32-x64.vsix     VS Code extension with server/millpath.exe
#   millpath-*-cp39-abi3-*.whl  the Python package (crates/python), Linux x64 and Windows x64:
#                               one wheel each for every CPython from 3.9 on (maturin, in a venv)
#   SHA256SUMS                  sha256sum of all of them
# Installs what it needs when missing (Debian: musl-tools, gcc-mingw-w64-x86-64; the rustup
# targets; the extension's npm packages). macOS builds come from the GitHub workflow
# (.github/workflows/release.yml). Checked by tests/release_artifacts.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
out=target/release-artifacts
pkgs=()
command -v musl-gcc >/dev/null || pkgs+=(musl-tools)
command -v x86_64-w64-mingw32-gcc >/dev/null || pkgs+=(gcc-mingw-w64-x86-64)
if [ ${#pkgs[@]} -gt 0 ]; then
  apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q "${pkgs[@]}"
fi
for t in x86_64-unknown-linux-musl x86_64-pc-windows-gnu; do
  rustup target list --installed | grep -qx "$t" || rustup target add "$t"
done

build() { # TARGET: the release build of the millpath binary for TARGET
  local t0=$SECONDS
  cargo build --release --locked --target "$1" -p millpath --bin millpath
  echo "release: $1 built in $((SECONDS - t0)) s"
}
build x86_64-unknown-linux-musl
build x86_64-pc-windows-gnu

rm -rf "$out" && mkdir -p "$out"
cp target/x86_64-unknown-linux-musl/release/millpath "$out/millpath-linux-x64"
cp target/x86_64-pc-windows-gnu/release/millpath.exe "$out/millpath.exe"
# the line tables stay in target/ for backtraces; the downloads without them
strip --strip-debug "$out/millpath-linux-x64"
x86_64-w64-mingw32-strip --strip-debug "$out/millpath.exe"

# one .vsix per platform, each with its server
(
  cd editors/vscode
  [ -d node_modules/@vscode/vsce ] || npm ci --no-audit --no-fund
  VSCE_TARGET=linux-x64 MILLPATH_BIN="$PWD/../../$out/millpath-linux-x64" npm run --silent package
  VSCE_TARGET=win32-x64 MILLPATH_BIN="$PWD/../../$out/millpath.exe" npm run --silent package
  rm -rf server millpath.vsix
)
mv editors/vscode/millpath-linux-x64.vsix editors/vscode/millpath-win32-x64.vsix "$out/"
# the Python wheels: maturin from PyPI in a venv of its own; the Windows one cross-built with
# the same MinGW-w64 (PyO3 makes python3.dll's import library itself)
venv=target/release-venv
[ -x "$venv/bin/maturin" ] || { python3 -m venv "$venv" && "$venv/bin/pip" install -q 'maturin>=1.9.4,<2'; }
# (the Linux one without --target: then it shares target/release with `pip install
# ./crates/python` and tests/python.sh instead of a build of its own)
for t in x86_64-unknown-linux-gnu x86_64-pc-windows-gnu; do
  t0=$SECONDS
  target=(--target "$t")
  [ "$t" != x86_64-unknown-linux-gnu ] || target=()
  "$venv/bin/maturin" build --quiet --release --locked "${target[@]}" \
    -m crates/python/Cargo.toml --out "$out"
  echo "release: the Python wheel for $t built in $((SECONDS - t0)) s"
done
(cd "$out" && sha256sum millpath-linux-x64 millpath.exe millpath-linux-x64.vsix millpath-win32-x64.vsix millpath-*.whl >SHA256SUMS)
ls -l "$out"
