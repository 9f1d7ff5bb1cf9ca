#!/usr/bin/env bash
# Runs every fuzz target for SECONDS each (default 600) under a 1 GB memory limit and a 10 s
# per-input timeout; prints each target's executions and executions per second, and fails on
# any crash, timeout or out-of-memory. `.ci/run` calls it with a short time as a smoke run:
# under a minute per target, one build serves every target (see `smoke` below).
# `--coverage`: then the region and line coverage of crates/core/src, per stage folder, that
# the corpora of `drawing` and `compile` reach (cargo fuzz coverage + llvm-cov of the rustup
# component llvm-tools-preview); SECONDS = 0 skips the fuzzing and reports the coverage of the
# corpora as they are.
#   bash fuzz/run.sh [--coverage] [SECONDS] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")"
coverage=0
if [ "${1:-}" = --coverage ]; then
  coverage=1
  shift
fi
secs=${1:-600}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(dxf_read text_parse format_idempotent compile drawing post_load verify_ncc)
export RUSTC_BOOTSTRAP=1
command -v cargo-fuzz >/dev/null || cargo install cargo-fuzz --locked --quiet
bash seed.sh
# `drawing` runs safe Rust only (the one unsafe block, the DXF reader's line finder, is fuzzed
# under AddressSanitizer by dxf_read and compile): without the sanitizer it runs 4x faster; its
# bytes are decisions, not magic values, so comparisons are not traced either (a third faster).
# A smoke run (under 60 s a target, as in CI) needs no speed: one build for all targets, all
# under the sanitizer, at opt-level 1 with line tables only (one cheaper build instead of two)
smoke=0
[ "$secs" -gt 0 ] && [ "$secs" -lt 60 ] && [ $coverage = 0 ] && smoke=1
if [ $smoke = 1 ]; then
  export CARGO_PROFILE_RELEASE_OPT_LEVEL=1 CARGO_PROFILE_RELEASE_DEBUG=line-tables-only
fi
build_flags() {
  if [ "$1" = drawing ] && [ $smoke = 0 ]; then
    echo "--release -s none --no-trace-compares --target-dir target/nosan"
  else
    echo "--release"
  fi
}
status=0
if [ "$secs" -gt 0 ]; then
  cargo fuzz build --release >/dev/null
  [ $smoke = 1 ] || cargo fuzz build $(build_flags drawing) drawing >/dev/null
  for t in "${targets[@]}"; do
    log=$(mktemp)
    cpu=$(mktemp)
    # the CPU seconds the run took too (/usr/bin/time when there): executions per CPU second
    # do not depend on what else the machine runs
    timer=()
    [ -x /usr/bin/time ] && timer=(/usr/bin/time -f "%U %S" -o "$cpu")
    # shellcheck disable=SC2046
    if "${timer[@]}" cargo fuzz run $(build_flags "$t") "$t" "corpus/$t" -- \
        -max_total_time="$secs" -rss_limit_mb=1024 -malloc_limit_mb=1024 -timeout=10 \
        -max_len=262144 -print_final_stats=1 >"$log" 2>&1; then
      result=ok
    else
      result=FAILED; status=1
      grep -E "ERROR|panicked|SUMMARY|Test unit written" "$log" | head -20 || true
    fi
    execs=$(grep -E "stat::number_of_executed_units" "$log" | awk '{print $2}' | tail -1)
    rate=$(grep -E "stat::average_exec_per_sec" "$log" | awk '{print $2}' | tail -1)
    per_cpu=$(tail -1 "$cpu" | awk -v n="${execs:-0}" '{ if ($1 + $2 > 0) printf ", %.0f per CPU second", n / ($1 + $2) }' 2>/dev/null || true)
    echo "fuzz $t: ${secs}s, ${execs:-?} executions, ${rate:-?}/s${per_cpu}, $result"
    rm -f "$log" "$cpu"
  done
fi
if [ $coverage = 1 ]; then
  host=$(rustc -vV | sed -n 's/^host: //p')
  llvm_cov="$(rustc --print sysroot)/lib/rustlib/$host/bin/llvm-cov"
  [ -x "$llvm_cov" ] || rustup component add llvm-tools-preview
  for t in drawing compile; do
    cargo fuzz coverage "$t" "corpus/$t" >/dev/null 2>&1
    bin="target/$host/coverage/$host/release/$t"
    "$llvm_cov" export -summary-only -instr-profile="coverage/$t/coverage.profdata" "$bin" \
      >"coverage/$t/summary.json"
    echo "coverage of crates/core/src by the $t corpus ($(find "corpus/$t" -type f | wc -l) inputs):"
    python3 coverage_table.py "coverage/$t/summary.json"
  done
fi
exit $status
