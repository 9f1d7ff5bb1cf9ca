# A shop declares its vice and a stop in millpath.toml; a plate is drawn with its last sweep
# over the vice. Every dialect refuses it at the sweep, check says the same, the editor's
# toolpath page marks it; with the vice's top lowered below the sweep height compile writes
# the program, rs274 runs it, and verify (reading the same millpath.toml, or --clamp) finds
# the vice where compile found it.
source "$ROOT/tests/workflows/lib.bash"

cat >3001.mpath <<'MPATH'
path 3001.1P {
  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2 S10
  end (60, 0)
  sweep (0, 0) -> (10, 0)
  mill (10, 0) -> (50, 0)
  sweep (50, 0) -> (60, 0)
}
MPATH
settings() {
  cat >millpath.toml <<TOML
feed = 300
sweep_speed = 1000
sweep_height = 10
dialect = "$1"
[[clamp]]
name = "vice"
min = [54, -3, 0]
max = [56, 3, $2]
[[clamp]]
name = "stop"
min = [20, 8, 0]
max = [30, 12, 20]
TOML
}

for dialect in reference linuxcnc grbl; do
  settings "$dialect" 10
  rm -f 3001_Milling.gcode
  expect_status 1 "$MILLPATH" compile 3001.mpath
  grep -q "runs into clamp 'vice'" "$WORK/err" || fail "$dialect: $(cat "$WORK/err")"
  grep -q '3001.mpath:6:3' "$WORK/err" || fail "$dialect: not at the sweep: $(cat "$WORK/err")"
  grep -q "clamp 'stop'" "$WORK/err" && fail "$dialect: the stop is not in the way"
  [ ! -e 3001_Milling.gcode ] || fail "$dialect: a program was written"
  expect_status 1 "$MILLPATH" check 3001.mpath
  grep -q "runs into clamp 'vice'" "$WORK/out" || fail "$dialect check: $(cat "$WORK/out")"
done
echo "every dialect refuses the sweep over the vice; check says so"

# the toolpath page: the boxes and the red move
expect_status 0 "$MILLPATH" render 3001.mpath --html page.html
grep -q '"name":"vice"' page.html || fail "no clamps in the page data"
grep -q '"hits":\[0\]' page.html || fail "no hit in the page data"

# lowered: compiled, rs274 runs it, verify finds the old vice where compile did
settings linuxcnc 9.99
expect_status 0 "$MILLPATH" compile 3001.mpath
if command -v rs274 >/dev/null; then
  status=0
  err=$(timeout 60 rs274 -g 3001_Milling.gcode </dev/null 2>&1 >/dev/null) || status=$?
  why=$(printf '%s\n' "$err" | grep -v '^executing$' || true)
  [ "$status" -eq 0 ] && [ -z "$why" ] || fail "rs274 rejects the program: $why"
  echo "rs274 runs 3001_Milling.gcode"
fi
expect_status 0 "$MILLPATH" verify --dialect linuxcnc 3001_Milling.gcode
expect_status 1 "$MILLPATH" verify --dialect linuxcnc --clamp vice,54,-3,0,56,3,10 3001_Milling.gcode
line=$(grep -n '^G00 X60.000' 3001_Milling.gcode | cut -d: -f1)
grep -q "3001_Milling.gcode:$line: error: the tool (radius 1.000 mm, from its tip upward) runs into clamp \"vice\"" "$WORK/out" \
  || fail "verify: $(cat "$WORK/out")"
echo "ok: clamps refuse in every dialect, the lowered vice passes, rs274 and verify agree"
