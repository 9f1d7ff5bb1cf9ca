# probe_split: a 60 mm groove with a probe at each end on a board that rises 0.3 mm along it.
# Without probe_split the groove is corrected once, at its start (reference-output.md §12.4),
# and its far end is 0.3 mm off. With probe_split = 5 (millpath.toml) compile writes it as
# 12 pieces; after adjust-z each piece's Z is the §12.4 correction at the piece's own start.
# rs274 accepts the adjusted program and verify finds it clean. The reference dialect
# refuses the setting, located at millpath.toml.
source "$ROOT/tests/workflows/lib.bash"
cat > millpath.toml <<'EOF'
dialect = "linuxcnc"
feed = 300
sweep_speed = 1000
sweep_height = 10
probe_feed = 50
probe_split = 5
EOF
cat > 2023.mpath <<'EOF'
path 2023.1P {
  start (0, 0)  M10x3 O2 T3 I5 B-0,2
  end (60, 0)
  mill (0, 0) -> (60, 0)
  probe (0, 0)
  probe (60, 0)
}
EOF

# 1. compile: the groove in 12 pieces, counted in the statistics
expect_status 0 "$MILLPATH" compile 2023.mpath
grep -q "Split for probes: 1 moves into 12 pieces" "$WORK/err" || fail "no split line: $(cat "$WORK/err")"
pieces=$(grep -c '^G01 F300.000 X' 2023_Clean.gcode)
[ "$pieces" -eq 12 ] || fail "expected 12 pieces, got $pieces: $(cat 2023_Clean.gcode)"
count=$(sed -n '/(Model /,/(Milling length/p' 2023_Clean.gcode | grep -c '^G')
grep -q "(Command count: $count)" 2023_Clean.gcode || fail "command count is not the $count moves"

# 2. the board: #51 (x = 0) measured 3.000, #52 (x = 60) 3.300; adjust-z
sed -e 's/#51=$/#51=3.000/' -e 's/#52=$/#52=3.300/' 2023_Z.txt > filled && mv filled 2023_Z.txt
expect_status 0 "$MILLPATH" adjust-z --max 0.5 2023_Clean.gcode

# 3. each piece from x0 to x0 + 5: Z = −0.2 + w52(x0)·0.3, the weights of §12.4 at x0
#    (1/(d + 0.001), normalised, printed with three decimals as _Clean.gcode has them)
grep '^G01 F300.000 X' 2023_Milling.gcode > pieces.txt
python3 - pieces.txt <<'EOF' || fail "the pieces do not follow the weighted correction"
import re, sys
lines = open(sys.argv[1]).read().splitlines()
assert len(lines) == 12, lines
for k, line in enumerate(lines):
    x0, x1 = 5.0 * k, 5.0 * (k + 1)
    x = float(re.search(r" X(-?[0-9.]+)", line).group(1))
    z = float(re.search(r" Z(-?[0-9.]+)", line).group(1))
    w1, w2 = 1 / (x0 + 0.001), 1 / (60 - x0 + 0.001)
    w52 = round(w2 / (w1 + w2), 3)
    want = -0.2 + w52 * 0.3
    assert abs(x - x1) < 1e-9, (line, x1)
    assert abs(z - want) <= 0.0005, (line, want)
    print(f"piece {k}: x {x0:4.1f}..{x1:4.1f}  Z {z:.3f}  (expected {want:.4f})")
# the far end is milled 0.3 mm higher than the start: the correction follows the board
first = float(re.search(r" Z(-?[0-9.]+)", lines[0]).group(1))
last = float(re.search(r" Z(-?[0-9.]+)", lines[-1]).group(1))
assert last - first > 0.2, (first, last)
EOF

# 4. LinuxCNC's interpreter runs it; verify checks it against the measured heights
if command -v rs274 >/dev/null; then
  status=0
  err=$(timeout 60 rs274 -g 2023_Milling.gcode </dev/null 2>&1 >/dev/null) || status=$?
  why=$(printf '%s\n' "$err" | grep -v '^executing$' || true)
  [ "$status" -eq 0 ] && [ -z "$why" ] || fail "rs274 rejects the adjusted program: $why"
  echo "rs274 runs 2023_Milling.gcode"
else
  echo "skipped rs274: LinuxCNC (package linuxcnc-uspace) is not installed"
fi
expect_status 0 "$MILLPATH" verify 2023_Milling.gcode
grep -q "0 error(s), 0 warning(s)" "$WORK/err" || fail "verify: $(cat "$WORK/out" "$WORK/err")"

# 5. the option overrides the file; the reference dialect refuses the setting at the file
#    (exit 2, as every settings error)
expect_status 0 "$MILLPATH" compile --probe-split 20 2023.mpath
[ "$(grep -c '^G01 F300.000 X' 2023_Clean.gcode)" -eq 3 ] || fail "--probe-split 20 is not 3 pieces"
expect_status 2 "$MILLPATH" compile --dialect reference 2023.mpath
grep -q "probe_split needs the linuxcnc or grbl dialect" "$WORK/err" || fail "$(cat "$WORK/err")"
grep -q "millpath.toml" "$WORK/err" || fail "not located at millpath.toml: $(cat "$WORK/err")"
expect_status 2 "$MILLPATH" compile --probe-split 0.1 2023.mpath
grep -q -- "--probe-split=0.1 mm is below the shortest piece, 0.5 mm" "$WORK/err" || fail "$(cat "$WORK/err")"
# 6. arcs (sub-arcs on the same circle) and support bars (ramps) in pieces of 2 mm, in
#    linuxcnc and grbl: rs274 accepts the adjusted linuxcnc program, verify both
mkdir arcs && cd arcs
cat > 2025.mpath <<'EOF'
path 2025.1P {
  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2 D1 P4 U20
  end (60, 0)
  mill (0, 0) -> (30, 0) ccw around (15, 0)
  bars (30, 0) -> (60, 0)
  probe (0, 5)
  probe (60, 5)
  probe (15, -20)
}
EOF
for d in linuxcnc grbl; do
  mkdir "$d" && cp 2025.mpath "$d/"
  sed "s/^dialect = .*/dialect = \"$d\"/" ../millpath.toml > "$d/millpath.toml"
  (cd "$d" && expect_status 0 "$MILLPATH" compile --probe-split 2 2025.mpath)
  grep -q "Split for probes: [0-9]* moves into [0-9]* pieces" "$WORK/err" || fail "$d: no split"
  sed -e 's/#51=$/#51=3.050/' -e 's/#52=$/#52=2.900/' -e 's/#53=$/#53=3.100/' "$d/2025_Z.txt" > filled
  mv filled "$d/2025_Z.txt"
  (cd "$d" && expect_status 0 "$MILLPATH" adjust-z --max 0.5 2025_Clean.gcode)
  arcs=$(grep -c '^G0[23] ' "$d/2025_Milling.gcode")
  [ "$arcs" -ge 24 ] || fail "$d: the half circle (47 mm, 2 passes) is not in sub-arcs: $arcs"
  (cd "$d" && expect_status 0 "$MILLPATH" verify --dialect "$d" 2025_Milling.gcode)
  grep -q "0 error(s), 0 warning(s)" "$WORK/err" || fail "verify $d: $(cat "$WORK/out" "$WORK/err")"
done
if command -v rs274 >/dev/null; then
  status=0
  err=$(cd linuxcnc && timeout 60 rs274 -g 2025_Milling.gcode </dev/null 2>&1 >/dev/null) || status=$?
  why=$(printf '%s\n' "$err" | grep -v '^executing$' || true)
  [ "$status" -eq 0 ] && [ -z "$why" ] || fail "rs274 rejects the sub-arcs: $why"
  echo "rs274 runs the sub-arcs and bar ramps"
fi
cd ..
echo "ok: the groove follows the board in 12 pieces, arcs and bars in sub-arcs and ramps; rs274 and verify accept them"
