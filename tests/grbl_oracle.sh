#!/usr/bin/env bash
# The GRBL oracle: GRBL 1.1h's own firmware (parser, planner, stepper) on its PC simulator
# (grbl_sim, built from ../shared/grbl by tests/grbl/build_sim.sh) times the programs of
# tests/grbl/programs.tsv under three machines (tests/grbl/machines: a slow stiff router, a
# fast light machine, GRBL's defaults), streamed by tests/grbl/sender.py as a real sender
# streams them. The motion times are written to crates/core/tests/fixtures/grbl_times.tsv,
# which the Rust test grbl_oracle holds millpath's GRBL time model to (within 2 %).
#
#   tests/grbl_oracle.sh [--all] [--jobs N]   time every program (every program of every
#        shared drawing and example, under every machine: 70 programs, 34 minutes of GRBL's
#        time, about 10 minutes here with --jobs 2) and record them in the fixture
#   tests/grbl_oracle.sh --check              time the programs marked `*` again and compare
#        with the recording (fails beyond 2 %; about a minute)
#
# Resumable: each finished time is kept in target/grbl-oracle/times.tsv under a key of the
# program's text, the machine and the simulator, sender and runner; an interrupted run goes on
# where it stopped (GRBL_ORACLE_FRESH=1: time everything again). Bounded: a program that takes
# more than GRBL_ORACLE_TIMEOUT seconds (default 900) is stopped, reported, and the run fails.
# --jobs N times N programs side by side (each simulator keeps two threads busy: on a shared
# computer 1, the default, is best). Progress goes to stderr.
# The drawings are compiled in the grbl dialect with the machine's settings; the shared
# drawings (GPL) are compiled here, never committed, and skipped when ../shared is absent.
# Without ../shared/grbl the oracle is skipped with a message (MILLPATH_SHARED=DIR: elsewhere).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
shared=${MILLPATH_SHARED:-../shared}
grbl_src=$shared/grbl
mode=--all jobs=1
while [ $# -gt 0 ]; do
  case $1 in
  --all | --check) mode=$1 ;;
  --jobs) jobs=${2:?--jobs N}; shift ;;
  --jobs=*) jobs=${1#--jobs=} ;;
  *) echo "usage: tests/grbl_oracle.sh [--all | --check] [--jobs N]" >&2; exit 2 ;;
  esac
  shift
done
case $jobs in '' | *[!0-9]* | 0) echo "--jobs: a count from 1 ($jobs)" >&2; exit 2 ;; esac
if [ ! -f "$grbl_src/build.sh" ]; then
  echo "skipped: $grbl_src is absent (GRBL's simulator is built from it)"
  exit 0
fi
tools=${CARGO_TARGET_DIR:-$root/target}/grbl-oracle
if [ ! -x "$tools/grbl_sim" ] || [ tests/grbl/build_sim.sh -nt "$tools/grbl_sim" ]; then
  bash tests/grbl/build_sim.sh "$grbl_src" "$tools" >/dev/null
fi
if [ -z "${MILLPATH_BIN:-}" ]; then
  cargo build --release --quiet -p millpath
fi
BIN=${MILLPATH_BIN:-${CARGO_TARGET_DIR:-$root/target}/release/millpath}
out=crates/core/tests/fixtures/grbl_times.tsv
cache=$tools/times.tsv
timeout_s=${GRBL_ORACLE_TIMEOUT:-900}
[ -z "${GRBL_ORACLE_FRESH:-}" ] || rm -f "$cache"
touch "$cache"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# what a recorded time depends on besides the program and the machine
tool_key=$(cat tests/grbl/build_sim.sh tests/grbl/sender.py | sha1sum | cut -c1-12)

# program MACHINE NAME DIR: the program's file (a drawing's compiled into DIR); nothing when
# its drawing is absent
program() {
  local m=$1 name=$2 dir=$3 drawing pattern height output args=() row stem
  if [ "${name#synthetic/}" != "$name" ]; then
    echo "tests/planner/programs/${name#synthetic/}"
    return
  fi
  row=$(awk -F'\t' -v n="$name" '$1 == n' tests/grbl/drawings.tsv)
  [ -n "$row" ] || { echo "unknown program $name (tests/grbl/drawings.tsv)" >&2; return 1; }
  IFS=$'\t' read -r _ drawing pattern height output <<<"$row"
  drawing=${drawing/#shared\//$shared/}
  [ -f "$drawing" ] || return 0
  [ "$pattern" = - ] || args+=(--path-pattern "$pattern")
  [ "$height" = - ] || args+=(--sweep-height "$height")
  mkdir -p "$dir"
  # the drawing's folder (subpaths), without its millpath.toml: the machine's settings rule
  find "$(dirname "$drawing")" -maxdepth 1 \( -name '*.dxf' -o -name '*.mpath' \) -exec cp {} "$dir/" \;
  stem=$(basename "${drawing%.*}")
  "$BIN" compile --config "tests/grbl/machines/$m.toml" "${args[@]}" "$dir/$(basename "$drawing")" \
    >"$dir/compile.log" 2>&1 || { cat "$dir/compile.log" >&2; return 1; }
  [ -f "$dir/${stem}_$output.gcode" ] || { echo "$name: no ${stem}_$output.gcode" >&2; return 1; }
  echo "$dir/${stem}_$output.gcode"
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

# time_one INDEX MACHINE NAME: a line `machine name seconds stalls stalled` into $tmp/INDEX.row
# (from the cache when its key is there), or `… TIMEOUT|FAILED` into $tmp/INDEX.bad
time_one() {
  local i=$1 m=$2 name=$3 file key sets t start row
  file=$(program "$m" "$name" "$tmp/c$i") || { printf '%s\t%s\tFAILED (compile)\n' "$m" "$name" >"$tmp/$i.bad"; return 0; }
  if [ -z "$file" ]; then
    echo "note: $name skipped (../shared is absent)" >&2
    return 0
  fi
  key=$(cat "$file" "tests/grbl/machines/$m.toml" | sha1sum | cut -c1-12)-$tool_key
  if [ "$mode" = --all ] && row=$(awk -F'\t' -v k="$key" '$1 == k' "$cache" | tail -1) && [ -n "$row" ]; then
    printf '%s\t%s\t%s\n' "$m" "$name" "$(cut -f2- <<<"$row")" >"$tmp/$i.row"
    echo "[$i/$total] $m $name: $(cut -f2 <<<"$row") s (recorded before)" >&2
    return 0
  fi
  mapfile -t sets < <(settings "$m")
  start=$(date +%s)
  if t=$(timeout --kill-after=10 "$timeout_s" /usr/bin/python3 tests/grbl/sender.py --sim "$tools/grbl_sim" \
    --speedup "${GRBL_SIM_SPEEDUP:-1000}" --runs "${GRBL_RUNS:-1}" "${sets[@]}" "$file" 2>"$tmp/$i.log"); then
    printf '%s\t%s\t%s\n' "$m" "$name" "$t" >"$tmp/$i.row"
    printf '%s\t%s\n' "$key" "$t" >>"$cache"
    echo "[$i/$total] $m $name: $(cut -f1 <<<"$t") s of GRBL's time in $(($(date +%s) - start)) s" >&2
  else
    local rc=$?
    [ $rc -eq 124 ] || [ $rc -eq 137 ] && t="TIMEOUT after ${timeout_s} s" || t="FAILED ($rc): $(tail -1 "$tmp/$i.log")"
    printf '%s\t%s\t%s\n' "$m" "$name" "$t" >"$tmp/$i.bad"
    echo "[$i/$total] $m $name: $t" >&2
  fi
}

# the programs of this run, in the order of programs.tsv
grep -v '^#' tests/grbl/programs.tsv | awk -F'\t' -v mode="$mode" 'NF >= 2 && (mode != "--check" || $3 == "*")' >"$tmp/list"
total=$(wc -l <"$tmp/list")
i=0
while IFS=$'\t' read -r m name _; do
  i=$((i + 1))
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
  time_one "$i" "$m" "$name" &
done <"$tmp/list"
wait
for k in $(seq 1 "$total"); do [ ! -f "$tmp/$k.row" ] || cat "$tmp/$k.row"; done >"$tmp/times.tsv"
bad=0
for k in $(seq 1 "$total"); do [ ! -f "$tmp/$k.bad" ] || { cat "$tmp/$k.bad" >&2; bad=$((bad + 1)); }; done
if [ "$bad" -gt 0 ]; then
  echo "$bad of $total programs not timed (above); the fixture is left as it was" >&2
  exit 1
fi

if [ "$mode" = --check ]; then
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
  echo "recorded $(wc -l <"$tmp/times.tsv") programs in $out" >&2
fi
