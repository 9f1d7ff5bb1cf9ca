#!/usr/bin/env bash
# GRBL 1.1's own parser (gvalidate, built from ../shared/grbl) accepts every program the
# built-in posts of the grbl family other than `grbl` write (fluidnc, grblhal; or the posts
# named as arguments): the examples and every shared drawing that compiles alone, probed
# drawings also through adjust-z (probes measured at their nominal heights). A negative
# check proves gvalidate rejects a program (the linuxcnc post's, with its % lines).
# The same check as tests/grbl_accept.sh on branch grbl33, which takes posts as words: once
# that is merged, `bash tests/grbl_accept.sh grbl fluidnc grblhal` replaces this script.
# gvalidate's probe input never touches, so G38.2 is read as G38.3 (GRBL parses both alike).
# Skipped with a message without ../shared/grbl. Last line: N accepted, M failed.
set -uo pipefail
cd "$(dirname "$0")/.."
root=$PWD
shared=${MILLPATH_SHARED:-../shared}
if [ ! -f "$shared/grbl/build.sh" ]; then
  echo "skipped: $shared/grbl is absent (GRBL's parser is built from it)"
  exit 0
fi
tools=${CARGO_TARGET_DIR:-$root/target}/grbl
if [ ! -x "$tools/gvalidate" ]; then
  mkdir -p "$tools"
  bash "$shared/grbl/build.sh" "$tools" >/dev/null || { echo "FAIL  building GRBL's tools"; exit 1; }
fi
gvalidate=$tools/gvalidate
if [ -z "${MILLPATH_BIN:-}" ]; then
  cargo build --release --quiet -p millpath || exit 1
fi
BIN=${MILLPATH_BIN:-${CARGO_TARGET_DIR:-$root/target}/release/millpath}
posts=("$@")
[ ${#posts[@]} -gt 0 ] || posts=(fluidnc grblhal)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
[ -d "$shared/conformance/fixtures" ] || shared=

# gvalidate_ok FILE: GRBL's parser answers every line without an error or alarm; what it
# refused is left in $why
gvalidate_ok() {
  local dir status answers
  dir=$(mktemp -d "$tmp/gv.XXXX")
  sed 's/G38\.2/G38.3/g' "$1" >"$dir/program.gcode"
  # gvalidate keeps its settings in EEPROM.DAT in its working directory
  answers=$(cd "$dir" && timeout 60 "$gvalidate" program.gcode 2>&1)
  status=$?
  why=$(printf '%s\n' "$answers" | grep -n -E '^(error|ALARM)' | head -3 | sed 's/^/      line /')
  [ "$status" -eq 0 ] && [ -z "$why" ]
}

# compile_all POST: the drawings compiled into $tmp/POST; prints the programs written
compile_all() {
  local out=$tmp/$1 f
  mkdir -p "$out"/plate "$out"/text "$out"/fixtures "$out"/samples
  cp examples/plate/*.dxf examples/plate/millpath.toml "$out/plate/"
  cp examples/text/*.mpath examples/text/millpath.toml "$out/text/"
  if [ -n "$shared" ]; then
    cp "$shared"/conformance/fixtures/*.dxf "$out/fixtures/"
    cp "$shared"/samples/*.dxf "$out/samples/"
  fi
  for f in "$out"/plate/*.dxf "$out"/text/*.mpath; do
    "$BIN" compile --post "$1" "$f" >/dev/null 2>&1 || echo "COMPILE-FAILED $f"
  done
  for f in "$out"/fixtures/*.dxf "$out"/samples/*.dxf; do
    [ -e "$f" ] || continue
    # a drawing that does not compile alone writes nothing: skipped
    "$BIN" compile --post "$1" --feed 150 --sweep-speed 500 --sweep-height 15 "$f" \
      >/dev/null 2>&1 || true
  done
  for f in "$out"/*/*_Z.txt; do
    [ -e "$f" ] || continue
    sed -i -E 's|/T=([-0-9.]+)\) (#[0-9]+)=$|/T=\1) \2=\1|' "$f"
    "$BIN" adjust-z --max 0.5 "${f%_Z.txt}_Clean.gcode" >/dev/null 2>&1 ||
      echo "COMPILE-FAILED adjust-z ${f%_Z.txt}_Clean.gcode"
  done
  find "$out" -name '*.gcode' | sort
}

passed=0
failed=0
for post in "${posts[@]}"; do
  ok=0
  while IFS= read -r p; do
    case $p in
    "") continue ;;
    COMPILE-FAILED*)
      echo "FAIL  ${p#COMPILE-FAILED } failed with the $post post"
      failed=$((failed + 1))
      continue
      ;;
    esac
    if gvalidate_ok "$p"; then
      passed=$((passed + 1))
      ok=$((ok + 1))
    else
      echo "FAIL  $post ${p#"$tmp"/"$post"/}"
      printf '%s\n' "$why"
      failed=$((failed + 1))
    fi
  done <<<"$(compile_all "$post")"
  echo "$post: gvalidate accepts $ok programs"
done

# negative check: a linuxcnc program (with % lines) is rejected
mkdir -p "$tmp/neg"
cp examples/text/*.mpath examples/text/millpath.toml "$tmp/neg/"
"$BIN" compile --post linuxcnc "$tmp/neg/2001.mpath" >/dev/null 2>&1
neg=$(find "$tmp/neg" -name '*_Milling.gcode' | head -1)
if [ -n "$neg" ] && ! gvalidate_ok "$neg"; then
  passed=$((passed + 1))
else
  echo "FAIL  negative check: gvalidate accepted a linuxcnc program ($neg)"
  failed=$((failed + 1))
fi
[ -n "$shared" ] || echo "(../shared/conformance is absent: only the examples were compiled)"
echo "$passed accepted, $failed failed"
[ "$failed" -eq 0 ]
