#!/usr/bin/env bash
# The end-to-end workflow tests: each tests/workflows/*.sh runs one chain of commands a
# machinist runs (convert, edit, write back, compile, probe, adjust, verify …) against the
# release binary and fails loudly where the chain ends wrong. Each script gets:
#   MILLPATH  the release binary        SHARED  ../shared (may be absent: skip what needs it)
#   WORK      a fresh empty directory (the cwd)   PY  a python3 with ezdxf   ROOT  the repo
# and may `source "$ROOT/tests/workflows/lib.bash"` for `fail`, `expect_status`, `need_shared`.
# Usage: bash tests/workflows.sh [NAME...]   (names without .sh; default: all)
set -uo pipefail
cd "$(dirname "$0")/.."
root=$PWD
export MILLPATH="${MILLPATH:-$root/target/release/millpath}"
export SHARED="${SHARED:-$root/../shared}"
export PY="${PY:-python3}"
export ROOT="$root"
[ -x "$MILLPATH" ] || cargo build --release --quiet
shopt -s nullglob
names=("$@")
if [ ${#names[@]} -eq 0 ]; then
  for f in tests/workflows/*.sh; do names+=("$(basename "$f" .sh)"); done
fi
passed=0 failed=0 failures=()
for n in "${names[@]}"; do
  WORK=$(mktemp -d)
  export WORK
  echo "== workflow $n"
  if (cd "$WORK" && bash -euo pipefail "$root/tests/workflows/$n.sh"); then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    failures+=("$n")
    echo "FAILED: workflow $n"
  fi
  rm -rf "$WORK"
done
[ $failed -eq 0 ] || echo "failed workflows: ${failures[*]}"
echo "workflows: $passed passed, $failed failed"
[ $failed -eq 0 ]
