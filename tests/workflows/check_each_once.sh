# A CI lint over a folder where a subpath is embedded by several files: its warning is
# reported once (and counted once against --max-warnings), not once per embedding file; and a
# broken millpath.toml is annotated at its line and column on GitHub (MP201).
source "$ROOT/tests/workflows/lib.bash"
cat >2100.mpath <<'MP'
path 2100.1P {
  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2 D1mm
  end (30, 0)
  sweep (0, 0) -> (5, 0)
  mill (5, 0) -> (25, 0)
  sweep (25, 0) -> (30, 0)
}
MP
for n in 2101 2102; do
  cat >$n.mpath <<MP
path $n.1P {
  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2
  end (0, 20)
  sub (0, 0) -> (30, 0)  >2100.1P
  sweep (30, 0) -> (30, 20)
  sub (30, 20) -> (0, 20)  >2100.1P
}
MP
done

# 1. the subpath's typo once, in every format; the limit counts it once
expect_status 0 "$MILLPATH" check -q .
[ "$(grep -c "warning\[MP020\]" "$WORK/out")" = 1 ] || fail "MP020 not once: $(cat "$WORK/out")"
grep -q "checked 3 file(s): 0 error(s), 1 warning(s)" "$WORK/out" || fail "summary: $(tail -1 "$WORK/out")"
expect_status 0 "$MILLPATH" check -q --format github --max-warnings 1 .
[ "$(grep -c "^::warning file=2100.mpath,line=2,col=3" "$WORK/out")" = 1 ] || fail "annotations: $(cat "$WORK/out")"
expect_status 0 "$MILLPATH" check -q --format json .
[ "$(python3 -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["diagnostics"]))' "$WORK/out")" = 1 ] ||
  fail "JSON: $(cat "$WORK/out")"
expect_status 0 "$MILLPATH" check -q --format sarif .
[ "$(python3 -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["runs"][0]["results"]))' "$WORK/out")" = 1 ] ||
  fail "SARIF: $(cat "$WORK/out")"
# two typos in two places stay two
sed -i 's/B-0,2$/B-0,2 D2x/' 2101.mpath
expect_status 0 "$MILLPATH" check -q .
grep -q "checked 3 file(s): 0 error(s), 2 warning(s)" "$WORK/out" || fail "two warnings: $(cat "$WORK/out")"

# 2. MP201: a millpath.toml that is no TOML, annotated where the TOML reader says
printf 'feed = 300\nsweep_speed = "fast"\nsweep_height = 10\n' >millpath.toml
for lang in en de; do
  expect_status 2 "$MILLPATH" check -q --lang $lang --format github .
  grep -q "^::error file=millpath.toml,line=2,col=15,title=millpath MP201::" "$WORK/out" ||
    fail "MP201 ($lang): $(cat "$WORK/out")"
done
expect_status 2 "$MILLPATH" check -q --format sarif .
python3 - "$WORK/out" <<'PY' || fail "SARIF MP201: $(cat "$WORK/out")"
import json, sys
region = json.load(open(sys.argv[1]))["runs"][0]["results"][0]["locations"][0]["physicalLocation"]["region"]
assert region == {"startLine": 2, "startColumn": 15}, region
PY
# an error the reader gives no line for stays at the file
printf 'feed = 300\nsweep_speed = [1000\n' >millpath.toml
expect_status 2 "$MILLPATH" check -q --format github .
grep -q "^::error file=millpath.toml,line=" "$WORK/out" || fail "unclosed list: $(cat "$WORK/out")"
echo "ok: each warning once; MP201 located"
