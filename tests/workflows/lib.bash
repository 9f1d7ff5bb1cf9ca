# Helpers for the workflow scripts (sourced, not run on its own).

# fail MESSAGE: ends the workflow with a message.
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# expect_status N COMMAND...: runs COMMAND, fails unless it exits with N; its standard
# output and error are kept in $WORK/out and $WORK/err (and echoed on failure).
expect_status() {
  local want=$1
  shift
  local got=0
  "$@" >"$WORK/out" 2>"$WORK/err" || got=$?
  if [ "$got" -ne "$want" ]; then
    echo "--- stdout" >&2; cat "$WORK/out" >&2
    echo "--- stderr" >&2; cat "$WORK/err" >&2
    fail "exit $got (expected $want): $*"
  fi
}

# need_shared: skips the rest of the workflow (success, with a message) without ../shared.
need_shared() {
  if [ ! -d "$SHARED/conformance" ]; then
    echo "skipped: $SHARED/conformance is absent"
    exit 0
  fi
}
