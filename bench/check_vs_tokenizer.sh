#!/usr/bin/env bash
# `millpath check` beside two yardsticks, over the same 38 shared drawings
# (../shared/conformance/fixtures and ../shared/samples), timed as whole processes in turn:
#   check      millpath check (release build, all cores)
#   tokenizer  a bare DXF group-code tokenizer (crates/dxf/examples/tokenize.rs): the floor
#   ezdxf      ezdxf.readfile on every file (bench/ezdxf_read.py); ezdxf-import: its start-up
# and prints the ratios check/tokenizer (target <= 2) and ezdxf/check (target >= 40).
# Then `check` over 100 copies of the shared drawings (a temporary folder), with 1 worker
# and with all cores, and /usr/bin/time -v of the latter: user+sys above wall = cores used.
#
#   bash bench/check_vs_tokenizer.sh          RUNS=20 COPIES=100 bash bench/...
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS=${RUNS:-10}
COPIES=${COPIES:-100}
shared=../shared
if [ ! -d "$shared/conformance/fixtures" ] || [ ! -d "$shared/samples" ]; then
  echo "../shared is absent: nothing to measure"
  exit 0
fi
python3 -c "import ezdxf" 2>/dev/null || python3 -m pip install -q ezdxf
cargo build --release --quiet -p millpath -p millpath-dxf -p millpath-core \
  --bin millpath --example tokenize --example gen_drawings
target=${CARGO_TARGET_DIR:-$PWD/target}
bin=$target/release/millpath
tok=$target/release/examples/tokenize
gen=$target/release/examples/gen_drawings
files=("$shared"/conformance/fixtures/*.dxf "$shared"/samples/*.dxf)
q() { printf '%q ' "$@"; } # one shell-quoted command line

echo "== ${#files[@]} shared drawings, $RUNS runs each, $(nproc) cores"
"$tok" "${files[@]}"
python3 bench/ezdxf_read.py "${files[@]}" 2>/dev/null
# each ratio from its own pair of commands run in turn: a second-long Python run between two
# runs of check would measure check with cold caches
python3 bench/timecmds.py -n "$RUNS" --warmup 1 --ratio 'check/tokenizer:<=2' \
  "check=$(q "$bin" check --quiet "${files[@]}")" \
  "tokenizer=$(q "$tok" "${files[@]}")"
python3 bench/timecmds.py -n "$(( (RUNS + 1) / 2 ))" --warmup 1 --ratio 'ezdxf/check:>=40' \
  "check=$(q "$bin" check --quiet "${files[@]}")" \
  "ezdxf=$(q python3 bench/ezdxf_read.py "${files[@]}")" \
  "ezdxf-import=python3 -c 'import ezdxf'"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$gen" copies "$COPIES" "$work/fixtures" "$shared"/conformance/fixtures/*.dxf
"$gen" copies "$COPIES" "$work/samples" "$shared"/samples/*.dxf
n=$(find "$work" -name '*.dxf' | wc -l)
echo
echo "== check over $COPIES copies of the shared drawings ($n files)"
python3 bench/timecmds.py -n "$(( (RUNS + 1) / 2 ))" --warmup 1 --ratio '1-worker/all-cores' \
  "all-cores=$(q "$bin" check --quiet "$work")" \
  "1-worker=RAYON_NUM_THREADS=1 $(q "$bin" check --quiet "$work")"
if [ -x /usr/bin/time ]; then
  /usr/bin/time -v -o "$work/time.txt" "$bin" check --quiet "$work" >/dev/null 2>&1 || true
  echo "/usr/bin/time -v millpath check --quiet COPIES:"
  grep -E "Elapsed|User time|System time|Percent of CPU|Maximum resident" "$work/time.txt" | sed 's/^\s*/  /'
fi
