#!/usr/bin/env bash
# The planner oracle: LinuxCNC 2.9's own trajectory planner (linuxcnc-uspace, headless, a
# simulated machine) times a set of programs, and the figures are written to
# crates/core/tests/fixtures/planner_times.tsv, which the Rust test planner_oracle holds
# millpath's time model to (within 2 %).
#
# The set: the synthetic programs of tests/planner/programs (see synthetic.py), and the
# examples and some shared drawings compiled in the linuxcnc dialect with the machine of
# tests/planner/millpath.toml (the shared drawings are GPL: compiled here, never committed;
# skipped when ../shared is absent). The planner runs in real time: about 13 minutes; with
# PLANNER_SPEEDUP=20 (as CI runs it, with --check) under a minute, same figures to 1–4 ms.
#
#   tests/planner_oracle.sh            regenerate the figures
#   tests/planner_oracle.sh --check    run the planner and compare with the recorded figures
#                                      (fails when a figure moved by more than 0.5 %)
# PLANNER_SPEEDUP=K runs the simulated machine K times faster than the wall clock (every speed
# K times, every acceleration K² times, the servo period 1/K): the planner then visits the
# same points in the same servo cycles, so the figures are the same (see oracle.py).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
out=crates/core/tests/fixtures/planner_times.tsv
check=${1:-}
if ! command -v milltask >/dev/null || ! /usr/bin/python3 -c 'import linuxcnc' 2>/dev/null; then
  echo "skipped: LinuxCNC (package linuxcnc-uspace) is not installed"
  exit 0
fi
if [ -z "${MILLPATH_BIN:-}" ]; then
  cargo build --release --quiet -p millpath
fi
BIN=${MILLPATH_BIN:-${CARGO_TARGET_DIR:-$root/target}/release/millpath}
tmp=$(mktemp -d)
chmod 755 "$tmp"
trap 'rm -rf "$tmp"' EXIT
shared=../shared

# compile NAME DRAWING [ARGS]: compiles DRAWING (with the oracle's machine) to $tmp/NAME.ngc
compile() {
  local name=$1 drawing=$2 dir
  shift 2
  dir=$tmp/$(dirname "$name")
  mkdir -p "$dir"
  cp "$drawing" "$dir/"
  "$BIN" compile --config tests/planner/millpath.toml "$@" "$dir/$(basename "$drawing")" \
    >"$tmp/compile.log" 2>&1 || { cat "$tmp/compile.log" >&2; exit 1; }
  mv "$dir/$(basename "${drawing%.*}")"*_Milling.gcode "$tmp/$name.ngc"
  programs+=("$tmp/$name.ngc")
}

programs=()
for p in tests/planner/programs/*.ngc; do
  mkdir -p "$tmp/synthetic"
  cp "$p" "$tmp/synthetic/"
  programs+=("$tmp/synthetic/$(basename "$p")")
done
compile examples/plate/1234.1P examples/plate/1234.1P.dxf
# 2010 embeds 2001: both in one folder (2020 is probed: its program needs measured heights)
mkdir -p "$tmp/examples/text"
cp examples/text/*.mpath "$tmp/examples/text/"
for t in 2001 2010; do
  "$BIN" compile --config tests/planner/millpath.toml "$tmp/examples/text/$t.mpath" \
    >"$tmp/compile.log" 2>&1 || { cat "$tmp/compile.log" >&2; exit 1; }
  mv "$tmp/examples/text/${t}_Milling.gcode" "$tmp/examples/text/$t.ngc"
  programs+=("$tmp/examples/text/$t.ngc")
done
if [ -d "$shared/conformance/fixtures" ]; then
  compile shared/samples/2916.1P "$shared/samples/2916.1P.dxf" --path-pattern '2916\.1P'
  compile "shared/samples/2051.1P" "$shared/samples/2051 Pv Schlüssel.dxf" --path-pattern '2051\.1P'
  for f in 8999.02P 8999.08P 8999.14P 8999.15P "8999.23 Pv"; do
    compile "shared/conformance/$f" "$shared/conformance/fixtures/$f.dxf"
  done
else
  echo "note: $shared/conformance is absent: only the synthetic programs and the examples"
fi

read -r vel acc tol < <(/usr/bin/python3 - <<'PY'
import tomllib
m = tomllib.load(open("tests/planner/millpath.toml", "rb"))["machine"]
axes = lambda v: ",".join(str(v[a]) for a in "xyz") if isinstance(v, dict) else str(v)
print(axes(m["max_velocity"]), axes(m["max_acceleration"]), m["path_tolerance"])
PY
)
# names relative to $tmp: synthetic/…, examples/…, shared/…
(cd "$tmp" && /usr/bin/python3 "$root/tests/planner/oracle.py" --vel "$vel" --acc "$acc" \
  --tolerance "$tol" --speedup "${PLANNER_SPEEDUP:-1}" "${programs[@]#"$tmp/"}") 2> >(grep -v "tool mmap" >&2) > "$tmp/times.tsv"

if [ "$check" = --check ]; then
  /usr/bin/python3 - "$out" "$tmp/times.tsv" <<'PY'
import sys
rec = dict(l.split("\t") for l in open(sys.argv[1]).read().splitlines() if l and not l.startswith("#"))
bad = 0
for line in open(sys.argv[2]).read().splitlines():
    name, t = line.split("\t")
    r = float(rec.get(name, "nan"))
    ok = abs(float(t) - r) <= 0.005 * r
    bad += not ok
    print(f"{name}\t{r}\t{t}\t{'ok' if ok else 'MOVED'}")
sys.exit(1 if bad else 0)
PY
else
  {
    echo "# LinuxCNC 2.9 planner times (seconds) of the planner oracle's programs; written by"
    echo "# tests/planner_oracle.sh with the machine of tests/planner/millpath.toml."
    cat "$tmp/times.tsv"
  } > "$out"
  cat "$out"
fi
