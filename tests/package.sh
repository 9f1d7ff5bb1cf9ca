#!/usr/bin/env bash
# Every crate packs and builds from its package alone (`cargo package --workspace`: each
# packed crate is built against the others as packed), so `cargo install millpath` works on
# the day the crates are published. Prints the packed sizes.
set -uo pipefail
cd "$(dirname "$0")/.."
# --allow-dirty: untracked outputs of earlier CI steps (the examples' G-code) lie beside
out=$(cargo package --workspace --allow-dirty 2>&1)
status=$?
printf '%s\n' "$out" | grep -E '^ *(Packaging|Packaged)|^error'
if [ "$status" -ne 0 ]; then
  printf '%s\n' "$out" | tail -20
  exit 1
fi
echo "every crate packs and builds alone"
