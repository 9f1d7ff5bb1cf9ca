#!/usr/bin/env bash
# Seed corpora for the fuzz targets, built from the project's own examples and test drawings
# (never from ../shared): written to fuzz/corpus/<target>/ (not committed).
set -euo pipefail
cd "$(dirname "$0")"
root=..
# drawing (structure-aware) starts from nothing: any bytes make a drawing
mkdir -p corpus/dxf_read corpus/text_parse corpus/format_idempotent corpus/compile corpus/drawing corpus/post_load corpus/verify_ncc
# post_load: the built-in posts and the hostile ones of the tests
cp "$root"/crates/post/posts/*.toml "$root"/crates/post/tests/hostile/*.toml corpus/post_load/
for f in "$root"/examples/*/*.dxf; do
  cp "$f" "corpus/dxf_read/$(basename "$f")"
  # the compile target reads one leading byte: even = DXF
  { printf '\x00'; cat "$f"; } > "corpus/compile/dxf-$(basename "$f")"
done
for f in "$root"/examples/*/*.mpath "$root"/grammar/tree-sitter-millpath/test/corpus/*; do
  [ -f "$f" ] || continue
  b=$(basename "$f")
  cp "$f" "corpus/text_parse/$b"
  cp "$f" "corpus/format_idempotent/$b"
  { printf '\x01'; cat "$f"; } > "corpus/compile/text-$b"
done
# verify_ncc: a small .NCC program in xCAM's exchange format (header, a contour, its milling,
# a drilling), and one cut short
printf 'H DX=30.000 DY=20.000 DZ=10.000 T=3.000\r\nG0 N="P1" X=0.000 Y=0.000 Z=-0.500 CTYPE=0\r\nG1 X=20.000 Y=0.000 Z=-0.500\r\nG5 X=20.000 Y=10.000 Z=-0.500 I=20.000 J=5.000 DIR=1\r\nGIN N="P1" C=0 IN=0 OUT=0 DFC=1 TI="T3"\r\nB X=5.000 Y=5.000 Z=-2.000 DU=3.000 TI="T3" B_MODE=0\r\n' > corpus/verify_ncc/part.ncc
head -c 120 corpus/verify_ncc/part.ncc > corpus/verify_ncc/cut.ncc
# small hostile seeds of our own
printf 'path 1000.1P {\n  start (0, 0)  O2 T2 INaN B-0,3\n  end (20, 0)\n  mill (0, 0) -> (20, 0)\n}\n' > corpus/text_parse/nan.mpath
printf '\x01path 1000.1P {\n  start (0, 0)  O2 T2 I-1 B-0,1\n  end (30, 0)\n  sweep (0, 0) -> (10, 0)\n  helix (10, 0) d8\n  sweep (10, 0) -> (30, 0)\n}\n' > corpus/compile/helix-negative-i.mpath
# drawing: a few long inputs, so that libFuzzer's length control starts long enough for
# drawings with parts, subpaths and probes (short inputs run out of decisions early)
for i in $(seq 1 32); do
  [ -f "corpus/drawing/seed-random-$i" ] || head -c 700 /dev/urandom > "corpus/drawing/seed-random-$i"
done
echo "seeded: $(find corpus -type f | wc -l) files"
