#!/usr/bin/env bash
# A drawing from a real CAD program: FreeCAD's command line exports a slot outline and drill
# circles (tests/extended/freecad/export_outline.py); FreeCAD writes every layer CONTINUOUS,
# so complete.py appends the markers, sweeps and start text; the result compiles with
# --extended to the same G-code as the same path drawn by text2dxf. Without freecadcmd the
# committed export (P7001_freecad.dxf, made by the same script) is used.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
bin="${CARGO_TARGET_DIR:-$PWD/target}/release/millpath"
here=tests/extended/freecad
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/cad" "$work/twin"
exports=("$here/P7001_freecad.dxf")
if command -v freecadcmd >/dev/null; then
  # FreeCAD 0.20 crashes on options it does not know (--version too): the script only
  freecadcmd "$here/export_outline.py" "$work/fresh.dxf" >/dev/null 2>&1 </dev/null
  test -s "$work/fresh.dxf"
  exports+=("$work/fresh.dxf")
  echo "FreeCAD exported $(grep -c -x -E 'LINE|ARC|CIRCLE' "$work/fresh.dxf") entities"
else
  echo "freecadcmd is absent (apt-get install freecad): using the committed FreeCAD export"
fi
config='path_pattern = "P([0-9]{4})[.]([0-9]+)([A-Z])"'
echo "$config" >"$work/twin/millpath.toml"
echo "$config" >"$work/cad/millpath.toml"
"$bin" text2dxf "$here/P7001.mpath" -o "$work/twin/P7001.dxf"
(cd "$work/twin" && "$bin" compile -f 150 -v 500 -s 15 P7001.dxf 2>/dev/null)
passed=0
failed=0
for e in "${exports[@]}"; do
  python3 "$here/complete.py" "$e" "$work/cad/P7001.dxf"
  rm -f "$work/cad/P7001_Milling.gcode"
  if (cd "$work/cad" && "$bin" compile -f 150 -v 500 -s 15 --extended P7001.dxf 2>/dev/null) \
    && cmp -s "$work/cad/P7001_Milling.gcode" "$work/twin/P7001_Milling.gcode"; then
    passed=$((passed + 1))
  else
    echo "FAIL: $e does not compile to the twin's G-code"
    failed=$((failed + 1))
  fi
done
echo "freecad: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
