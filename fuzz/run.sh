#!/usr/bin/env bash
# Runs every fuzz target for SECONDS each (default 600) under a 1 GB memory limit and a 10 s
# per-input timeout; prints each target's execution count and fails on any crash, timeout or
# out-of-memory. `.ci/run` calls it with a short time as a smoke run.
#   bash fuzz/run.sh [SECONDS] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")"
secs=${1:-600}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(dxf_read text_parse format_idempotent compile)
export RUSTC_BOOTSTRAP=1
command -v cargo-fuzz >/dev/null || cargo install cargo-fuzz --locked --quiet
bash seed.sh
cargo fuzz build --release >/dev/null
status=0
for t in "${targets[@]}"; do
  log=$(mktemp)
  if cargo fuzz run --release "$t" "corpus/$t" -- \
      -max_total_time="$secs" -rss_limit_mb=1024 -malloc_limit_mb=1024 -timeout=10 \
      -max_len=262144 -print_final_stats=1 >"$log" 2>&1; then
    result=ok
  else
    result=FAILED; status=1
    grep -E "ERROR|panicked|SUMMARY|Test unit written" "$log" | head -20 || true
  fi
  execs=$(grep -E "stat::number_of_executed_units" "$log" | awk '{print $2}' | tail -1)
  echo "fuzz $t: ${secs}s, ${execs:-?} executions, $result"
  rm -f "$log"
done
exit $status
