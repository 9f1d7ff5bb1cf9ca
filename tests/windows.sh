#!/usr/bin/env bash
# Windows in CI: millpath.exe cross-built with MinGW-w64 and run under Wine (Debian's
# packages, installed when missing): the reference conformance cases, the command line
# (tests/windows/cli.sh, against the Linux build's outputs) and the language server over
# stdio with the VS Code extension's protocol test client.
#
# Not run under Wine, because they test Unix things: symlink loops (ci_formats.rs, cfg(unix)),
# chattr/immutable files (probing_set.sh: a held-open file is the Windows case, tested here),
# transparent huge pages and CPU affinity (Linux-only code in main.rs/workers.rs), rs274
# (a Linux program), and the editors in a browser (the same JavaScript on every platform).
#
# Usage: bash tests/windows.sh   (MILLPATH_WINE_EXE=path skips the build and tests that .exe)
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
start=$SECONDS

# --- tools: MinGW-w64 (linker), Wine, the Rust target
pkgs=()
command -v x86_64-w64-mingw32-gcc >/dev/null || pkgs+=(gcc-mingw-w64-x86-64)
command -v wine >/dev/null || pkgs+=(wine wine64)
if [ ${#pkgs[@]} -gt 0 ]; then
  apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q "${pkgs[@]}"
fi
rustup target list --installed | grep -qx x86_64-pc-windows-gnu || rustup target add x86_64-pc-windows-gnu

# --- the binaries: the .exe (profile `cross`: the release profile at opt-level 1, see
# Cargo.toml) and the Linux release build whose outputs the .exe must match
t0=$SECONDS
if [ -z "${MILLPATH_WINE_EXE:-}" ]; then
  cargo build --quiet --profile cross --target x86_64-pc-windows-gnu -p millpath --bin millpath
  MILLPATH_WINE_EXE=$ROOT/target/x86_64-pc-windows-gnu/cross/millpath.exe
fi
cargo build --quiet --release -p millpath --bin millpath
echo "windows: builds took $((SECONDS - t0)) s"

# --- the Wine prefix (kept in the cache: its first start takes a while)
export WINEPREFIX="${XDG_CACHE_HOME:-$HOME/.cache}/millpath-wine" WINEDEBUG=-all WINEARCH=win64
export WINEDLLOVERRIDES="mscoree,mshtml=" # no Mono/Gecko installer prompts
t0=$SECONDS
[ -f "$WINEPREFIX/system.reg" ] || wineboot -i >/dev/null 2>&1
wineserver -w || true
sys32=$WINEPREFIX/drive_c/windows/system32
# Rust's std imports ProcessPrng from bcryptprimitives.dll; Wine 8 lacks that DLL: our
# stand-in (a test-harness file) in the prefix, only while Wine has none of its own
if ! ls /usr/lib/*/wine/x86_64-windows/bcryptprimitives.dll /usr/lib/wine/x86_64-windows/bcryptprimitives.dll >/dev/null 2>&1; then
  x86_64-w64-mingw32-gcc -O2 -shared -o "$sys32/bcryptprimitives.dll" \
    tests/windows/bcryptprimitives.c tests/windows/bcryptprimitives.def -lbcrypt
fi
echo "windows: Wine prefix ready in $((SECONDS - t0)) s"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
x86_64-w64-mingw32-gcc -O2 -o "$tmp/holdopen.exe" tests/windows/holdopen.c
# the .exe as a command for the runners written for a Unix binary
printf '#!/bin/sh\nexec wine "%s" "$@"\n' "$MILLPATH_WINE_EXE" >"$tmp/millpath-wine"
chmod +x "$tmp/millpath-wine"
wine "$MILLPATH_WINE_EXE" --version

# --- the command line
MILLPATH_WIN=$tmp/millpath-wine MILLPATH_LINUX=$ROOT/target/release/millpath \
  HOLDOPEN=$tmp/holdopen.exe bash tests/windows/cli.sh

# --- the reference conformance cases
if [ -f ../shared/conformance/run.py ]; then
  python3 ../shared/conformance/run.py --bin "$tmp/millpath-wine"
else
  echo "skipped: ../shared/conformance is not there"
fi

# --- the language server over stdio: the extension's protocol test client, with the server
# command `wine millpath.exe lsp` and Windows file URIs (Wine's Z: drive is /)
(
  cd editors/vscode
  [ -d node_modules/vscode-jsonrpc ] || npm ci --no-audit --no-fund
  [ -f dist/logic.js ] || npm run build
  MILLPATH_BIN="$tmp/millpath-wine" MILLPATH_WINE=1 node --test test/protocol.test.mjs
)
echo "windows: all done in $((SECONDS - start)) s"
