#!/usr/bin/env bash
# Peak memory and time of `check` and `compile` per drawing size: one chain of N segments and
# N segments in chains of 10 (bench/drawings.rs, written as `.mpath` by dxf2text), for each
# N given (default 20000 100000 500000). Prints one row per case: the input's size, peak RSS
# (GNU time's maximum resident set), the ratio of the two, what the peak needs beyond ten times
# the input (the target: at most a constant, the process at rest plus the checker's stock grid
# at its bound of 4,000,000 cells of 8 bytes), and wall seconds; then the growth of check's peak
# from the smallest to the largest N.
#   bash bench/memory.sh [N...]            (MILLPATH=path/to/millpath to use a built binary)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(20000 100000 500000)
command -v /usr/bin/time >/dev/null || { echo "bench/memory.sh needs GNU time (apt install time)" >&2; exit 2; }
if [ -z "${MILLPATH:-}" ]; then
  cargo build --release -q --manifest-path "$root/Cargo.toml" -p millpath
  MILLPATH="$root/target/release/millpath"
fi
MILLPATH=$(realpath "$MILLPATH")
cargo build --release -q --manifest-path "$root/Cargo.toml" -p millpath-core --example gen_drawings
gen="$root/target/release/examples/gen_drawings"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
machine=(--feed 1000 --sweep-speed 2000 --sweep-height 5)

# peak RSS in KB and wall seconds of one command (its own status is not judged here: a
# drawing beyond a bound is refused, which is what a user sees)
measure() {
  /usr/bin/time -f "%M %e" -o "$work/time" "$@" >/dev/null 2>&1 || true
  cat "$work/time" | tail -1
}

# the constant: the process checking a drawing of one segment, plus the stock grid's bound
mkdir -p "$work/tiny"
printf 'path 1000.1P {\n  start (0, 0)  O2 T2 I1,2 B-0,3\n  end (1, 1)\n  mill (0, 0) -> (1, 1)\n}\n' \
  >"$work/tiny/1000.mpath"
read -r rest _ < <(cd "$work/tiny" && measure "$MILLPATH" check --quiet "${machine[@]}" 1000.mpath)
awk -v r="$rest" 'BEGIN { printf "at rest: %.1f MB; the constant allowed: %.1f MB (with the stock grid, 4,000,000 cells of 8 bytes)\n", r/1024, r/1024 + 32e6/1048576 }'
printf '%-8s %-12s %9s %11s %7s %10s %8s\n' command case input_MB peak_MB ratio over_10x seconds
declare -A peak
for n in "${sizes[@]}"; do
  for kind in chain chains; do
    dir="$work/$kind-$n"
    mkdir -p "$dir"
    if [ "$kind" = chain ]; then "$gen" chain "$n" "$dir/1000.1P.dxf"; else "$gen" chains "$n" 10 "$dir/1000.1P.dxf"; fi
    "$MILLPATH" dxf2text "$dir/1000.1P.dxf" -o "$dir/1000.mpath"
    rm "$dir/1000.1P.dxf"
    size=$(stat -c %s "$dir/1000.mpath")
    for cmd in check compile; do
      quiet=(); [ "$cmd" = check ] && quiet=(--quiet)
      read -r kb secs < <(cd "$dir" && measure "$MILLPATH" "$cmd" "${quiet[@]}" "${machine[@]}" 1000.mpath)
      rm -f "$dir"/*.gcode "$dir"/*_Z.txt
      peak[$cmd-$kind-$n]=$kb
      awk -v c="$cmd" -v k="$kind-$n" -v s="$size" -v m="$kb" -v t="$secs" 'BEGIN {
        printf "%-8s %-12s %9.1f %11.1f %7.1f %10.1f %8.2f\n", c, k, s/1e6, m/1024, m*1024/s, (m*1024 - 10*s)/1048576, t }'
    done
  done
done
first=${sizes[0]}
last=${sizes[${#sizes[@]}-1]}
if [ "$first" != "$last" ]; then
  for kind in chain chains; do
    awk -v k="$kind" -v a="${peak[check-$kind-$first]}" -v b="${peak[check-$kind-$last]}" \
      -v f="$first" -v l="$last" 'BEGIN {
      printf "check %s: %d -> %d segments, peak grows %.2f times (segments %.1f times)\n", k, f, l, b/a, l/f }'
  done
fi
