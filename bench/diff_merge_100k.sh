#!/usr/bin/env bash
# `millpath diff` and `millpath merge` at 100,000 elements (issue 34's hostile case), timed as
# whole processes with GNU time against their targets:
#   diff      two versions of one path of N mill segments, B changed on the start line (every
#             element's moves change: both compiles, the effect report of N elements); target
#             under 2 s on a quiet machine
#   diff-nc   the same with --no-compile (the written change only)
#   diff-many N/100 paths of 100 mill segments in one file, B changed on every start line
#             (the file read and analysed once for all its paths)
#   merge     base/ours/theirs of that path, ours and theirs each changing another element
#             (a clean merge, checked by compiling); target a few seconds
# Each row: wall seconds, CPU seconds (user+sys; above wall = both cores used), peak RSS.
# The machine may be shared: CPU seconds are the steadier figure; wall on a quiet machine is
# about max(CPU / cores used, the longer of the two compiles).
#   bash bench/diff_merge_100k.sh [N]      (default 100000; MILLPATH=… to use a built binary)
# Figures at 100,000 (2 shared cores, load 7–10, so CPU seconds above an idle machine's):
# diff 9.4 s CPU before one analysis per version, 4.7–6.1 s after; diff-many 11.8 → 5.3 s.
# Instructions (callgrind, 5,000 elements): 2.06 G → 0.87 G.
# Idle machine (load 0.6): diff 3.0 s wall / 4.8 s CPU before the analysis built models only and
# diff kept freed memory for a second, 2.0–2.2 s / 3.2–3.6 s after (page faults 342k → 166k);
# diff-many 3.15 / 5.25 → 2.27 / 3.76; diff-nc 0.54 / 0.89; merge 5.15 / 5.13.
# Load 1.4, main's binary beside this one: diff 2.27 s wall / 3.68 s CPU before the analysis
# read paths only (one model build per version), provenance used the build's walk and made the
# start's rows once per path, and the parser read plain segment lines without combinators;
# 1.64–1.80 s / 2.58–2.65 s after (perf stat: 3.53 → 2.47 s task-clock); diff-nc 0.85 → 0.48 s
# CPU, diff-many 3.56 → 3.40, merge 5.17 → 3.52–3.93. Instructions (callgrind, 20,000
# elements): 3.40 G → 2.06 G (maps and the G-code digest hashed with foldhash the last 0.14 G).
# `millpath compile` of the 100k drawing: 2.2 s CPU either way (its G-code byte-identical).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
n=${1:-100000}
command -v /usr/bin/time >/dev/null || { echo "bench/diff_merge_100k.sh needs GNU time (apt install time)" >&2; exit 2; }
if [ -z "${MILLPATH:-}" ]; then
  cargo build --release -q --manifest-path "$root/Cargo.toml" -p millpath
  MILLPATH="$root/target/release/millpath"
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# one path: a serpentine of N connected mill segments (rows of 100, 3 mm apart)
drawing() { # B-VALUE
  awk -v n="$n" -v b="$1" 'BEGIN {
    print "path 1000.1P {"; print "  start (0, 0)  M10x3 O2 T2 I1,2 B" b
    x = 0; y = 0
    for (i = 0; i < n; i++) {
      row = int(i / 100); k = i % 100
      if (k == 0 && i > 0) { nx = x; ny = y + 3 } else { nx = x + (row % 2 == 0 ? 1 : -1); ny = y + (k % 2 == 0 ? 1 : -1) }
      printf "  mill (%d, %d) -> (%d, %d)\n", x, y, nx, ny; x = nx; y = ny
    }
    printf "  end (%d, %d)\n}\n", x, y }'
}
# N/100 paths of 100 mill segments each (a zigzag row)
many() { # B-VALUE
  awk -v n="$n" -v b="$1" 'BEGIN {
    for (p = 1; p <= n / 100; p++) {
      if (p > 1) print ""
      printf "path 1000.%dP {\n  start (0, 0)  M10x3 O2 T2 I1,2 B%s\n", p, b
      for (k = 0; k < 100; k++) printf "  mill (%d, %d) -> (%d, %d)\n", k, k % 2, k + 1, (k + 1) % 2
      print "  end (100, 0)\n}" } }'
}
mkdir -p "$tmp/old" "$tmp/new" "$tmp/merge" "$tmp/many/old" "$tmp/many/new"
many -0,3 >"$tmp/many/old/1000.mpath"
many -0,5 >"$tmp/many/new/1000.mpath"
drawing -0,3 >"$tmp/old/1000.mpath"
drawing -0,5 >"$tmp/new/1000.mpath"
cp "$tmp/old/1000.mpath" "$tmp/merge/base.mpath"
sed 's/^  mill (0, 0) -> (1, 1)$/&  B-0,4/' "$tmp/merge/base.mpath" >"$tmp/merge/ours.mpath"
sed 's/^  mill (50, 0) -> (51, 1)$/&  B-0,5/' "$tmp/merge/base.mpath" >"$tmp/merge/theirs.mpath"

# row NAME TARGET EXPECTED-STATUS COMMAND...
row() {
  local name=$1 target=$2 want=$3 got=0
  shift 3
  /usr/bin/time -f '%e %U %S %M' -o "$tmp/time" "$@" >"$tmp/out" 2>"$tmp/err" || got=$?
  [ "$got" -eq "$want" ] || { cat "$tmp/err" >&2; echo "$name: exit $got, expected $want" >&2; exit 1; }
  read -r wall user sys rss < <(tail -n 1 "$tmp/time")
  awk -v n="$name" -v w="$wall" -v u="$user" -v s="$sys" -v r="$rss" -v t="$target" -v e="$n" 'BEGIN {
    printf "%-9s %7d elements  wall %6.2f s  cpu %6.2f s  peak %5d MiB  target %s s\n", n, e, w, u + s, r / 1024, t }'
}
echo "millpath diff/merge at $n elements ($(nproc) cores, load $(cut -d' ' -f1 /proc/loadavg))"
row diff 2 1 "$MILLPATH" diff "$tmp/old/1000.mpath" "$tmp/new/1000.mpath"
grep -q "on $n elements" "$tmp/out" || { echo "diff: the effect on $n elements is not reported" >&2; exit 1; }
row diff-nc 2 1 "$MILLPATH" diff --no-compile "$tmp/old/1000.mpath" "$tmp/new/1000.mpath"
row diff-many 2 1 "$MILLPATH" diff "$tmp/many/old/1000.mpath" "$tmp/many/new/1000.mpath"
grep -q "on 100 elements" "$tmp/out" || { echo "diff-many: the effect per path is not reported" >&2; exit 1; }
cp "$tmp/merge/ours.mpath" "$tmp/merge/work.mpath"
(cd "$tmp/merge" && row merge "a few" 0 "$MILLPATH" merge base.mpath work.mpath theirs.mpath 1000.mpath)
grep -q 'B-0,4' "$tmp/merge/work.mpath" && grep -q 'B-0,5' "$tmp/merge/work.mpath" ||
  { echo "merge: an edit is missing from the result" >&2; exit 1; }
