#!/usr/bin/env bash
# The extended input mode's oracle: every shared drawing and our own examples, rewritten by
# ezdxf as polylines, as nested mirrored blocks and in inches (tests/extended/make_drawings.py),
# compile with --extended to the same G-code as the LINE/ARC original; the reference mode
# warns once per ignored entity (tests/extended/oracle.py).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
bin="${CARGO_TARGET_DIR:-$PWD/target}/release/millpath"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/src"
cp examples/plate/*.dxf "$work/src/"
for f in examples/text/*.mpath tests/extended/drawings/*.mpath; do
  "$bin" text2dxf "$f" -o "$work/src/$(basename "$f" .mpath).dxf"
done
if [ -d ../shared/conformance/fixtures ]; then
  cp ../shared/conformance/fixtures/*.dxf ../shared/samples/*.dxf "$work/src/"
else
  echo "../shared is absent: the oracle runs on our own drawings only"
fi
python3 tests/extended/make_drawings.py "$work/out" "$work/src"/*.dxf
python3 tests/extended/oracle.py "$bin" "$work/out"
