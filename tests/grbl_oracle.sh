#!/usr/bin/env bash
# The GRBL oracle: GRBL 1.1h's own firmware (parser, planner, stepper) on its PC simulator
# (grbl_sim, built from ../shared/grbl) times the programs of tests/grbl/programs.tsv under
# three machines (tests/grbl/machines: a slow stiff router, a fast light machine, GRBL's
# defaults), streamed by tests/grbl/sender.py as a real sender streams them. The motion times
# are written to crates/core/tests/fixtures/grbl_times.tsv, which the Rust test grbl_oracle
# holds millpath's GRBL time model to (within 2 %).
#
#   tests/grbl_oracle.sh              time every program (several minutes) and record them
#   tests/grbl_oracle.sh --check      time the programs marked `*` again and compare with
#                                     the recording (fails beyond 2 %: the simulator's own
#                                     spread on a busy computer; one to two minutes)
# The drawings are compiled in the grbl dialect with the machine's settings; the shared
# drawings (GPL) are compiled here, never committed, and skipped when ../shared is absent.
# Without ../shared/grbl the oracle is skipped with a message (MILLPATH_SHARED=DIR: elsewhere).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
shared=${MILLPATH_SHARED:-../shared}
grbl_src=$shared/grbl
if [ ! -f "$grbl_src/build.sh" ]; then
  echo "skipped: $grbl_src is absent (GRBL's simulator is built from it)"
  exit 0
fi
# the simulator with its clock held for GRBL's main loop (tests/grbl/build_sim.sh says why)
tools=${CARGO_TARGET_DIR:-$root/target}/grbl-oracle
if [ ! -x "$tools/grbl_sim" ] || [ tests/grbl/build_sim.sh -nt "$tools/grbl_sim" ]; then
  bash tests/grbl/build_sim.sh "$grbl_src" "$tools" >/dev/null
fi
if [ -z "${MILLPATH_BIN:-}" ]; then
  cargo build --release --quiet -p millpath
fi
BIN=${MILLPATH_BIN:-${CARGO_TARGET_DIR:-$root/target}/release/millpath}
out=crates/core/tests/fixtures/grbl_times.tsv
check=${1:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT


# program MACHINE NAME: the program's file (compiled into $tmp/MACHINE when a drawing);
# nothing when its drawing is absent
program() {
  local m=$1 name=$2 dir drawing pattern=() stem
  case $name in
  synthetic/*)
    echo "tests/planner/programs/${name#synthetic/}"
    return
    ;;
  examples/plate/1234.1P.gcode) drawing=examples/plate/1234.1P.dxf ;;
  examples/text/*) drawing=examples/text/$(basename "$name" .gcode).mpath ;;
  shared/samples/2916.1P.gcode) drawing=$shared/samples/2916.1P.dxf pattern=(--path-pattern '2916\.1P') ;;
  shared/conformance/*) drawing=$shared/conformance/fixtures/$(basename "$name" .gcode).dxf ;;
  *) echo "unknown program $name" >&2; exit 1 ;;
  esac
  [ -f "$drawing" ] || return 0
  dir=$tmp/$m/$(dirname "$name")
  mkdir -p "$dir"
  # the drawing's folder (subpaths), without its millpath.toml: the machine's settings rule
  find "$(dirname "$drawing")" -maxdepth 1 \( -name '*.dxf' -o -name '*.mpath' \) -exec cp {} "$dir/" \;
  stem=$(basename "${drawing%.*}")
  "$BIN" compile --config "tests/grbl/machines/$m.toml" "${pattern[@]}" "$dir/$(basename "$drawing")" \
    >"$tmp/compile.log" 2>&1 || { cat "$tmp/compile.log" >&2; exit 1; }
  ls "$dir/$stem"*_Milling.gcode | head -1
}

# the `$` settings of a machine, one per line
settings() {
  /usr/bin/python3 - "tests/grbl/machines/$1.toml" <<'PY'
import sys, tomllib
m = tomllib.load(open(sys.argv[1], "rb")).get("machine", {})
names = {"junction_deviation": 11, "arc_tolerance": 12, "x_steps_per_mm": 100,
         "y_steps_per_mm": 101, "z_steps_per_mm": 102, "x_max_rate": 110, "y_max_rate": 111,
         "z_max_rate": 112, "x_acceleration": 120, "y_acceleration": 121, "z_acceleration": 122}
for k, v in m.items():
    n = names.get(k) or (int(k[1:]) if k.startswith("$") else None)
    if n is not None:
        print(f"--setting=${n}={v}")
PY
}

# time MACHINE: the machine's programs one after the other, into $tmp/MACHINE.tsv
time_machine() {
  local m=$1 name mark file sets t
  : >"$tmp/$m.tsv"
  while IFS=$'\t' read -r mm name mark; do
    [ "$mm" = "$m" ] || continue
    [ "$check" != --check ] || [ "$mark" = "*" ] || continue
    file=$(program "$m" "$name")
    if [ -z "$file" ]; then
      echo "note: $name skipped (../shared is absent)" >&2
      continue
    fi
    mapfile -t sets < <(settings "$m")
    t=$(/usr/bin/python3 tests/grbl/sender.py --sim "$tools/grbl_sim" --speedup "${GRBL_SIM_SPEEDUP:-1}" --runs "${GRBL_RUNS:-1}" \
      "${sets[@]}" "$file")
    printf '%s\t%s\t%s\n' "$m" "$name" "$t" | tee -a "$tmp/$m.tsv"
  done <tests/grbl/programs.tsv
}

# one program at a time: the simulator's two threads race on a busy computer (its steppers
# stall; sender.py then runs the program again), more so side by side
for m in router light defaults; do time_machine "$m"; done
for m in router light defaults; do cat "$tmp/$m.tsv"; done >"$tmp/times.tsv"

if [ "$check" = --check ]; then
  /usr/bin/python3 - "$out" "$tmp/times.tsv" <<'PY'
import sys
rec = {}
for l in open(sys.argv[1]).read().splitlines():
    if l and not l.startswith("#"):
        m, name, t = l.split("\t")[:3]
        rec[(m, name)] = float(t)
bad = 0
for line in open(sys.argv[2]).read().splitlines():
    m, name, t, stalls = line.split("\t")[:4]
    r = rec.get((m, name), float("nan"))
    ok = abs(float(t) - r) <= 0.02 * r
    # a run whose steppers stalled (the simulator's threads raced) fails too
    ok = ok and stalls == "0"
    bad += not ok
    print(f"{m}\t{name}\trecorded {r}\tnow {t}\t{(float(t) / r - 1) * 100:+.2f} %\t{'ok' if ok else 'MOVED'}")
sys.exit(1 if bad else 0)
PY
else
  {
    echo "# GRBL 1.1h's motion times (seconds, simulated clock) of the GRBL oracle's programs;"
    echo "# written by tests/grbl_oracle.sh: machine, program, time, stalls of the simulator's"
    echo "# steppers in that run (0: clean; see tests/grbl/sender.py) and the seconds they took."
    cat "$tmp/times.tsv"
  } >"$out"
fi
