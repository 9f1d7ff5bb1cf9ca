#!/usr/bin/env bash
# GRBL's own parser (gvalidate, GRBL 1.1h built from ../shared/grbl) accepts every program we
# write for a GRBL controller: the examples and every shared drawing that compiles alone
# (../shared/conformance/fixtures, ../shared/samples), each with the spindle and its start
# dwell; probed drawings also with probe_split and through adjust-z (probes filled in with
# their nominal heights); the examples' height-map probing programs and their adjusted
# programs; a plate with clamps in millpath.toml. A negative check proves gvalidate really
# rejects a program (the linuxcnc dialect's, which GRBL cannot read).
#
#   tests/grbl_accept.sh [TARGET...]   default: grbl
# A TARGET is a dialect (`--dialect TARGET`) or a post of the grbl family (`--post TARGET`),
# so another controller of the family is one more word here and in .ci/run.
#
# gvalidate's probe input never touches: G38.2 raises ALARM:5 there, so G38.2 lines are read
# as G38.3 (the same words; GRBL parses both alike). Last line: N accepted, M failed.
# Without ../shared/grbl the test is skipped with a message (MILLPATH_SHARED=DIR: another
# place for ../shared). About 15 s after the build.
set -uo pipefail
cd "$(dirname "$0")/.."
root=$PWD
shared=${MILLPATH_SHARED:-../shared}
grbl_src=$shared/grbl
if [ ! -f "$grbl_src/build.sh" ]; then
  echo "skipped: $grbl_src is absent (GRBL's parser is built from it)"
  exit 0
fi
tools=${CARGO_TARGET_DIR:-$root/target}/grbl
if [ ! -x "$tools/gvalidate" ]; then
  mkdir -p "$tools"
  bash "$grbl_src/build.sh" "$tools" >/dev/null || { echo "FAIL  building GRBL's tools"; exit 1; }
fi
gvalidate=$tools/gvalidate
if [ -z "${MILLPATH_BIN:-}" ]; then
  cargo build --release --quiet -p millpath || exit 1
fi
BIN=${MILLPATH_BIN:-${CARGO_TARGET_DIR:-$root/target}/release/millpath}
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(grbl)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

[ -d "$shared/conformance/fixtures" ] || shared=

# the option that selects a target
target_args() {
  case $1 in
  reference | linuxcnc | grbl) echo "--dialect $1" ;;
  *) echo "--post $1" ;;
  esac
}

# gvalidate_ok FILE: GRBL's parser answers every line of FILE without an error or alarm
# (G38.2 read as G38.3). What it refused is left in $why.
gvalidate_ok() {
  local dir status
  dir=$(mktemp -d "$tmp/gv.XXXX")
  sed 's/G38\.2/G38.3/g' "$1" >"$dir/program.gcode"
  # gvalidate keeps its settings in EEPROM.DAT in the working directory
  answers=$(cd "$dir" && timeout 60 "$gvalidate" program.gcode 2>&1)
  status=$?
  why=$(printf '%s\n' "$answers" | grep -n -E '^(error|ALARM)' | head -3 | sed 's/^/      line /')
  [ "$status" -eq 0 ] && [ -z "$why" ]
}

# fill_probes DIR: every probe of every _Z.txt below DIR measured at its nominal height,
# then adjust-z writes the program to run
fill_probes() {
  local f
  for f in "$1"/*_Z.txt; do
    [ -e "$f" ] || continue
    sed -i -E 's|/T=([-0-9.]+)\) (#[0-9]+)=$|/T=\1) \2=\1|' "$f"
    "$BIN" adjust-z --max 0.5 "${f%_Z.txt}_Clean.gcode" >/dev/null 2>&1 ||
      echo "COMPILE-FAILED adjust-z ${f%_Z.txt}_Clean.gcode"
  done
}

# compile_all TARGET: compiles every program set of the test into $tmp/TARGET; prints the
# programs written (and COMPILE-FAILED lines)
compile_all() {
  local out=$tmp/$1 args f d
  read -r -a args <<<"$(target_args "$1")"
  # the examples with their own settings; again with a spindle and its start dwell
  for d in plate text; do
    for variant in plain spindle; do
      mkdir -p "$out/$d-$variant"
      cp "examples/$d"/*.dxf "examples/$d"/*.mpath "examples/$d/millpath.toml" "$out/$d-$variant/" 2>/dev/null
      local extra=()
      [ $variant = spindle ] && extra=(--spindle-rpm 12000 --spindle-dwell 1.5)
      for f in "$out/$d-$variant"/*.dxf "$out/$d-$variant"/*.mpath; do
        [ -e "$f" ] || continue
        "$BIN" compile "${args[@]}" "${extra[@]}" "$f" >/dev/null 2>&1 || echo "COMPILE-FAILED $f"
      done
      fill_probes "$out/$d-$variant"
    done
  done
  # height-map probing programs over the examples' cuts, and the adjusted programs
  mkdir -p "$out/heightmap"
  cp examples/plate/*.dxf examples/plate/millpath.toml examples/text/2001.mpath "$out/heightmap/"
  for f in "$out/heightmap"/*.dxf "$out/heightmap"/*.mpath; do
    "$BIN" compile "${args[@]}" --heightmap-step 7 --heightmap-margin 2 --spindle-rpm 9000 "$f" \
      >/dev/null 2>&1 || echo "COMPILE-FAILED heightmap $f"
  done
  fill_probes "$out/heightmap"
  # clamps beside the plate (the program must pass them: compile writes it)
  mkdir -p "$out/clamps"
  cp examples/plate/*.dxf "$out/clamps/"
  cat >"$out/clamps/millpath.toml" <<'TOML'
feed = 300
sweep_speed = 1000
sweep_height = 10
spindle_rpm = 10000
spindle_dwell = 3
[[clamp]]
name = "vice"
min = [-40, -40, 0]
max = [-20, 60, 20]
TOML
  "$BIN" compile "${args[@]}" "$out/clamps"/*.dxf >/dev/null 2>&1 || echo "COMPILE-FAILED clamps"
  # the shared drawings: plain, with spindle settings, and probed ones split for probes
  if [ -n "$shared" ]; then
    for variant in plain spindle split; do
      mkdir -p "$out/shared-$variant"
      cp "$shared"/conformance/fixtures/*.dxf "$shared"/samples/*.dxf "$out/shared-$variant/"
      local extra=()
      case $variant in
      spindle) extra=(--spindle-rpm 18000 --spindle-dwell 4) ;;
      split) extra=(--probe-split 2 --spindle-rpm 8000) ;;
      esac
      for f in "$out/shared-$variant"/*.dxf; do
        # a drawing that does not compile alone (several paths, errors) writes nothing
        "$BIN" compile "${args[@]}" "${extra[@]}" --feed 150 --sweep-speed 500 --sweep-height 15 \
          "$f" >/dev/null 2>&1 || true
      done
      if [ $variant = split ]; then
        # only the probed drawings are different here
        find "$out/shared-$variant" -name '*.gcode' ! -name '*_Clean.gcode' ! -name '*_Probing.gcode' \
          -exec sh -c 'f=$1; [ -e "${f%_Milling.gcode}_Z.txt" ] || rm "$f"' _ {} \;
      fi
      fill_probes "$out/shared-$variant"
    done
  fi
  find "$out" -name '*.gcode' | sort
}

accepted=0
failed=0
for target in "${targets[@]}"; do
  n=0
  declare -A per_set=()
  while IFS= read -r p; do
    [ -n "$p" ] || continue
    case $p in
    COMPILE-FAILED*)
      echo "FAIL  $target: ${p#COMPILE-FAILED } did not compile"
      failed=$((failed + 1))
      continue
      ;;
    esac
    if gvalidate_ok "$p"; then
      n=$((n + 1))
      set_name=${p#"$tmp/$target/"}
      set_name=${set_name%%/*}
      per_set[$set_name]=$((${per_set[$set_name]:-0} + 1))
    else
      echo "FAIL  $target: gvalidate refuses ${p#"$tmp"/}"
      printf '%s\n' "$why"
      failed=$((failed + 1))
    fi
  done <<<"$(compile_all "$target")"
  for k in $(printf '%s\n' "${!per_set[@]}" | sort); do printf '  %-16s %3d\n' "$k" "${per_set[$k]}"; done
  unset per_set
  echo "$target: gvalidate accepts $n programs"
  accepted=$((accepted + n))
done

# negative check: GRBL refuses what it cannot read (the linuxcnc dialect's program)
mkdir -p "$tmp/negative"
cp examples/plate/*.dxf examples/plate/millpath.toml "$tmp/negative/"
"$BIN" compile --dialect linuxcnc "$tmp/negative/1234.1P.dxf" >/dev/null 2>&1
if [ -f "$tmp/negative/1234.1P_Milling.gcode" ] && ! gvalidate_ok "$tmp/negative/1234.1P_Milling.gcode"; then
  echo "negative check: gvalidate refuses the linuxcnc dialect's program"
else
  echo "FAIL  negative check: gvalidate accepted the linuxcnc dialect's program"
  failed=$((failed + 1))
fi

[ -n "$shared" ] || echo "(../shared/conformance is absent: only the examples were compiled)"
echo "$accepted accepted, $failed failed"
[ "$failed" -eq 0 ]
