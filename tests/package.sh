#!/usr/bin/env bash
# Every crate packs and builds from its package alone (`cargo package --workspace`: each
# packed crate is built against the others as packed), so `cargo install millpath` works on
# the day the crates are published. Prints the packed sizes.
set -uo pipefail
cd "$(dirname "$0")/.."
# Cargo unpacks the packed crates of `--workspace` into its registry cache as a local
# registry's (a folder named after the registry's path, `-…`), and never again for the same
# name and version: an earlier run's sources would be built instead of these. Ours go.
home=${CARGO_HOME:-$HOME/.cargo}
for d in "$home"/registry/src/-*/millpath-[0-9]* "$home"/registry/src/-*/millpath-*-[0-9]* \
  "$home"/registry/src/-*/tree-sitter-millpath-[0-9]*; do
  [ -d "$d" ] && rm -rf "$d"
done
# and their builds of an earlier run (the check shares target/: a registry crate's build is
# never rebuilt either; without their fingerprints all of ours are built again)
rm -rf target/package target/debug/.fingerprint/millpath-* \
  target/debug/.fingerprint/tree-sitter-millpath-*
# --allow-dirty: untracked outputs of earlier CI steps (the examples' G-code) lie beside
out=$(cargo package --workspace --allow-dirty 2>&1)
status=$?
printf '%s\n' "$out" | grep -E '^ *(Packaging|Packaged)|^error'
if [ "$status" -ne 0 ]; then
  printf '%s\n' "$out" | tail -20
  exit 1
fi
echo "every crate packs and builds alone"
