# A CI lint that fails on warnings: a typo that is only a warning (D1mm: MP020, the value is
# ignored) passes a plain check, fails with --max-warnings 0 or max_warnings = 0 in
# millpath.toml, and through the GitHub Action's max-warnings input; a bad limit is refused.
source "$ROOT/tests/workflows/lib.bash"
cp "$ROOT/examples/text/2001.mpath" .
sed -i 's/O2 /O2 D1mm /' 2001.mpath

# 1. a warning alone passes, as before
expect_status 0 "$MILLPATH" check -q .
grep -q "MP020" "$WORK/out" || fail "no warning for D1mm: $(cat "$WORK/out")"

# 2. --max-warnings: more than N fails, N or fewer passes
expect_status 1 "$MILLPATH" check -q --max-warnings 0 .
grep -q "1 warning(s), more than the 0 allowed" "$WORK/err" || fail "no reason given: $(cat "$WORK/err")"
expect_status 0 "$MILLPATH" check -q --max-warnings 1 .
expect_status 1 "$MILLPATH" check -q --lang de --max-warnings 0 .
grep -q "1 Warnung(en), mehr als die erlaubten 0" "$WORK/err" || fail "German: $(cat "$WORK/err")"
# every format: the report stays one document on stdout, the reason on stderr
expect_status 1 "$MILLPATH" check -q --format json --max-warnings 0 .
python3 -c 'import json,sys; json.load(open(sys.argv[1]))' "$WORK/out" || fail "the JSON report is broken"
expect_status 1 "$MILLPATH" check -q --format sarif --max-warnings 0 .
expect_status 1 "$MILLPATH" check -q --format github --max-warnings 0 .
grep -q "^::warning file=2001.mpath,line=4" "$WORK/out" || fail "no annotation: $(cat "$WORK/out")"

# 3. max_warnings in millpath.toml; the option overrides it
echo "max_warnings = 0" >millpath.toml
expect_status 1 "$MILLPATH" check -q .
expect_status 0 "$MILLPATH" check -q --max-warnings 3 .

# 4. a bad limit: an error at the option, or at its line of millpath.toml (exit 2)
for bad in -1 NaN 1.5 x; do
  expect_status 2 "$MILLPATH" check -q --max-warnings "$bad" .
  grep -q -- "--max-warnings" "$WORK/err" || fail "--max-warnings $bad: $(cat "$WORK/err")"
done
for bad in -1 nan 1.5 '"0"'; do
  printf 'feed = 300\nmax_warnings = %s\n' "$bad" >millpath.toml
  expect_status 2 "$MILLPATH" check -q .
  grep -q "millpath.toml: TOML parse error at line 2" "$WORK/err" || fail "max_warnings = $bad: $(cat "$WORK/err")"
done
rm millpath.toml

# 5. the GitHub Action (action.yml): its check step as the runner runs it, with the inputs
step=$(sed -n 's/^ *run: \(millpath check .*\)$/\1/p' "$ROOT/action.yml")
[ -n "$step" ] || fail "no millpath check step in action.yml"
run_action() { # run_action PATHS MAX_WARNINGS
  PATH="$(dirname "$MILLPATH"):$PATH" MILLPATH_PATHS=$1 MILLPATH_MAX_WARNINGS=$2 bash -e -c "$step"
}
expect_status 0 run_action . ""
expect_status 1 run_action . 0
expect_status 0 run_action . 1
grep -q "max-warnings" "$ROOT/action.yml" || fail "no max-warnings input"
echo "ok: warnings can fail a CI lint"
