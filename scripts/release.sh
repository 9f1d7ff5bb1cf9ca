#!/usr/bin/env bash
# Builds the release artefacts into target/release-artifacts/:
#   millpath-linux-x64          static Linux binary (x86_64-unknown-linux-musl), any distribution
#   millpath.exe                Windows x64 (x86_64-pc-windows-gnu, MinGW-w64)
#   millpath-linux-x64.vsix     VS Code extension with the Linux server
#   millpath-win32-x64.vsix     VS Code extension with server/millpath.exe
#   millpath-*-cp39-abi3-manylinux2014_x86_64.manylinux_2_17_x86_64.whl
#   millpath-*-cp39-abi3-win_amd64.whl
#                               the Python package (crates/python), Linux x64 (glibc 2.17 and
#                               later) and Windows x64: one wheel each for every CPython from
#                               3.9 on (maturin, in a venv of its own)
#   SHA256SUMS                  sha256sum of all of them
#
# Usage: bash scripts/release.sh [binaries] [vsix] [wheels] [sums]
# Without arguments all four parts, into an emptied folder. The release workflow
# (.github/workflows/release.yml) runs the parts one by one as its steps, so the local run
# (tests/release_artifacts.sh) tests the workflow's commands. `vsix` needs `binaries` first.
#
# Installs what it needs when missing (Debian: musl-tools, gcc-mingw-w64-x86-64; the rustup
# targets; the extension's npm packages; maturin and zig from PyPI). macOS builds come from
# the GitHub workflow.
set -euo pipefail
cd "$(dirname "$0")/.."
out=target/release-artifacts
venv=target/release-venv # maturin and zig (PyPI's ziglang), also used by tests/windows.sh

tools() {
  local pkgs=()
  command -v musl-gcc >/dev/null || pkgs+=(musl-tools)
  command -v x86_64-w64-mingw32-gcc >/dev/null || pkgs+=(gcc-mingw-w64-x86-64)
  if [ ${#pkgs[@]} -gt 0 ]; then
    apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q "${pkgs[@]}"
  fi
  for t in x86_64-unknown-linux-musl x86_64-pc-windows-gnu; do
    rustup target list --installed | grep -qx "$t" || rustup target add "$t"
  done
}

binaries() {
  local t t0
  for t in x86_64-unknown-linux-musl x86_64-pc-windows-gnu; do
    t0=$SECONDS
    cargo build --release --locked --target "$t" -p millpath --bin millpath
    echo "release: $t built in $((SECONDS - t0)) s"
  done
  cp target/x86_64-unknown-linux-musl/release/millpath "$out/millpath-linux-x64"
  cp target/x86_64-pc-windows-gnu/release/millpath.exe "$out/millpath.exe"
  # the line tables stay in target/ for backtraces; the downloads without them
  strip --strip-debug "$out/millpath-linux-x64"
  x86_64-w64-mingw32-strip --strip-debug "$out/millpath.exe"
}

vsix() { # one .vsix per platform, each with its server
  (
    cd editors/vscode
    [ -d node_modules/@vscode/vsce ] || npm ci --no-audit --no-fund
    VSCE_TARGET=linux-x64 MILLPATH_BIN="$PWD/../../$out/millpath-linux-x64" npm run --silent package
    VSCE_TARGET=win32-x64 MILLPATH_BIN="$PWD/../../$out/millpath.exe" npm run --silent package
    rm -rf server millpath.vsix
  )
  mv editors/vscode/millpath-linux-x64.vsix editors/vscode/millpath-win32-x64.vsix "$out/"
}

wheels() {
  local t0
  if ! { [ -x "$venv/bin/maturin" ] && "$venv/bin/python3" -c "import ziglang" 2>/dev/null; }; then
    python3 -m venv "$venv" && "$venv/bin/pip" install -q 'maturin[zig]>=1.9.4,<2'
  fi
  rm -f "$out"/millpath-*.whl
  # Linux: linked by zig against glibc 2.17's symbols, so the wheel is manylinux2014 (any
  # distribution since 2014) whatever the build machine's glibc; maturin refuses the tag if
  # the module needs a newer symbol. (zig is found through the venv's python3, hence PATH.)
  t0=$SECONDS
  PATH="$PWD/$venv/bin:$PATH" maturin build --quiet --release --locked --zig \
    --compatibility manylinux2014 -m crates/python/Cargo.toml --out "$out"
  echo "release: the Linux wheel built in $((SECONDS - t0)) s"
  # Windows: cross-built with the binaries' MinGW-w64 (PyO3 makes python3.dll's import library)
  t0=$SECONDS
  "$venv/bin/maturin" build --quiet --release --locked --target x86_64-pc-windows-gnu \
    -m crates/python/Cargo.toml --out "$out"
  echo "release: the Windows wheel built in $((SECONDS - t0)) s"
}

sums() { # every artefact must be there
  (
    cd "$out"
    ls millpath-linux-x64 millpath.exe millpath-linux-x64.vsix millpath-win32-x64.vsix \
      millpath-*-cp39-abi3-*manylinux_2_17_x86_64*.whl \
      millpath-*-cp39-abi3-win_amd64.whl >/dev/null
    rm -f SHA256SUMS
    sha256sum -- * >SHA256SUMS
  )
  ls -l "$out"
}

parts=("$@")
if [ ${#parts[@]} -eq 0 ]; then
  parts=(binaries vsix wheels sums)
  rm -rf "$out"
fi
for part in "${parts[@]}"; do
  case $part in
    binaries | vsix | wheels | sums) ;;
    *) echo "usage: bash scripts/release.sh [binaries] [vsix] [wheels] [sums]" >&2; exit 2 ;;
  esac
done
mkdir -p "$out"
tools
for part in "${parts[@]}"; do
  "$part"
done
