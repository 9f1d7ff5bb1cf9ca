#!/usr/bin/env bash
# The visual diff of `millpath diff --html/--png` in Chromium: a drill moved (red, green), a
# mill segment made deeper (blue), the rest unchanged (grey); tests/diff_page.mjs checks the
# colours, the toggle, the clicks and samples the PNG. Needs editors/vscode's npm install
# (playwright-core) and chromium. A few seconds.
set -euo pipefail
cd "$(dirname "$0")/.."
bin="$(pwd)/${MILLPATH:-target/release/millpath}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/new"
printf 'feed = 300\nsweep_speed = 1000\nsweep_height = 10\n' | tee "$work/millpath.toml" >"$work/new/millpath.toml"
cat >"$work/2040.mpath" <<'MP'
path 2040.1P {
  start (0, 0)  T3 O2 I1,5 B-0,2
  end (40, 0)
  mill (0, 0) -> (20, 0)
  sweep (20, 0) -> (20, 20)
  drill (20, 20) d2
  sweep (20, 20) -> (40, 20)
  mill (40, 20) -> (40, 0)
}
MP
sed -e 's/mill (40, 20) -> (40, 0)/mill (40, 20) -> (40, 0)  B-0,6/' -e 's/(20, 20)/(25, 20)/g' \
  "$work/2040.mpath" >"$work/new/2040.mpath"
status=0
(cd "$work" && "$bin" diff 2040.mpath new/2040.mpath --html page.html --png page.png >/dev/null 2>&1) || status=$?
[ "$status" = 1 ] || { echo "FAIL: millpath diff exited $status, want 1 (changed)"; exit 1; }
node tests/diff_page.mjs "$work/page.html" "$work/page.png"
