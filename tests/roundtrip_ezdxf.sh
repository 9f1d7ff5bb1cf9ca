#!/usr/bin/env bash
# Writes every drawing of ../shared and examples/ to text and back to DXF, then lets ezdxf
# (the oracle) read and audit the written files: no error, no fix.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
bin="$PWD/target/release/millpath"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
inputs=(examples/*/*.dxf)
if [ -d ../shared/conformance/fixtures ]; then
  inputs+=(../shared/conformance/fixtures/*.dxf ../shared/samples/*.dxf)
else
  echo "../shared is absent: auditing the examples only"
fi
for f in "${inputs[@]}"; do
  s=$(basename "$f" .dxf)
  "$bin" dxf2text "$f" -o "$work/$s.mpath"
  "$bin" text2dxf "$work/$s.mpath" -o "$work/$s.dxf"
done
for f in examples/*/*.mpath; do
  s=$(basename "$f" .mpath)
  "$bin" text2dxf "$f" -o "$work/example-$s.dxf"
done
python3 tests/ezdxf_audit.py "$work" | tail -n 3
