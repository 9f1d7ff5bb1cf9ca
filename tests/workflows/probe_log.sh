# adjust-z --probe-log: the measured heights come from the controller's own log, not typed
# by hand. Compile a probed drawing for LinuxCNC, write the log LinuxCNC would write at the
# probing program's own probe points on a tilted board, adjust-z from it: the same program
# as with the values typed into _Z.txt, byte for byte. The same from a GRBL console log.
# A log with a no-contact report, or one point short, is refused and nothing is written.
source "$ROOT/tests/workflows/lib.bash"
cp "$ROOT/examples/text/millpath.toml" .
# The start point is not at the drawing's 0/0: _Z.txt's [x y] are drawing coordinates, the
# probing program (and so the log) has output coordinates; matching must use the latter.
cat > 2021.mpath <<'EOF'
path 2021.1P {
  start (5, -3)  M10x3 O2 T3 I1,5 B-0,2
  end (65, -3)
  mill (5, -3) -> (65, -3)
  probe (10, 5)
  probe (50, 5)  L1
  probe (30, -10)
}
EOF

# 1. compile for LinuxCNC: probing program, _Z.txt (unfilled) and _Clean.gcode
expect_status 0 "$MILLPATH" compile --dialect linuxcnc 2021.mpath
cp 2021_Z.txt unfilled_Z.txt

# 2. the machine probes a board tilted in X and Y: z = 3 + 0.004·x − 0.003·y at each G38 of
#    the probing program (the XY of the G00 before it). LinuxCNC's PROBEOPEN log: X Y Z A B C
#    U V W, "%f" each, in the program's coordinates.
awk '/^G00/ { for (i = 2; i <= NF; i++) { if ($i ~ /^X/) x = substr($i, 2); if ($i ~ /^Y/) y = substr($i, 2) } }
     /^G38/ { z = sprintf("%.3f", 3 + 0.004 * x - 0.003 * y)
              printf "%f %f %f 0.000000 0.000000 0.000000 0.000000 0.000000 0.000000\n", x, y, z }' \
  2021_Probing.gcode > probes.txt
[ "$(wc -l < probes.txt)" -eq 3 ] || fail "expected 3 probe points: $(cat probes.txt)"
grep -q '^5.000000 8.000000 ' probes.txt || fail "probe points not in output coordinates: $(cat probes.txt)"

# 3. the old way, for comparison: the same heights typed into _Z.txt (in _Z.txt's order,
#    which is the probing program's order)
paste -d '' 2021_Z.txt <(cut -d' ' -f3 probes.txt) > typed_Z.txt
cp typed_Z.txt 2021_Z.txt
expect_status 0 "$MILLPATH" adjust-z --max 0.5 2021
mv 2021_Milling.gcode typed_Milling.gcode

# 4. the new way: _Z.txt as compile wrote it, the heights from the log
cp unfilled_Z.txt 2021_Z.txt
expect_status 0 "$MILLPATH" adjust-z --probe-log probes.txt --max 0.5 2021_Clean.gcode
cmp 2021_Milling.gcode typed_Milling.gcode || fail "the log gave another program than the typed values"
grep -q "MILLPATH-PROBES #51=" 2021_Milling.gcode || fail "no measured heights for verify"
expect_status 0 "$MILLPATH" verify 2021_Milling.gcode
grep -q "0 error(s), 0 warning(s)" "$WORK/err" || fail "verify: $(cat "$WORK/out" "$WORK/err")"

# 5. the linuxcnc probing program opens the log itself (PROBEOPEN 2021_probes.txt, the name
#    LinuxCNC writes it under), and LinuxCNC's interpreter accepts it and the adjusted
#    program (tests/rs274.sh installs it)
grep -q '^(PROBEOPEN 2021_probes.txt)$' 2021_Probing.gcode || fail "no PROBEOPEN"
grep -q '^(PROBECLOSE)$' 2021_Probing.gcode || fail "no PROBECLOSE"
cp probes.txt 2021_probes.txt
expect_status 0 "$MILLPATH" adjust-z --probe-log 2021_probes.txt --max 0.5 2021
cmp 2021_Milling.gcode typed_Milling.gcode || fail "another program from 2021_probes.txt"
if command -v rs274 >/dev/null; then
  status=0
  err=$(timeout 60 rs274 -g 2021_Probing.gcode </dev/null 2>&1 >/dev/null) || status=$?
  why=$(printf '%s\n' "$err" | grep -v '^executing$' || true)
  [ "$status" -eq 0 ] && [ -z "$why" ] || fail "rs274 rejects the probing program: $why"
  echo "rs274 runs 2021_Probing.gcode with PROBEOPEN/PROBECLOSE"
  status=0
  err=$(timeout 60 rs274 -g 2021_Milling.gcode </dev/null 2>&1 >/dev/null) || status=$?
  why=$(printf '%s\n' "$err" | grep -v '^executing$' || true)
  [ "$status" -eq 0 ] && [ -z "$why" ] || fail "rs274 rejects the adjusted program: $why"
  echo "rs274 runs 2021_Milling.gcode"
else
  echo "skipped rs274: LinuxCNC (package linuxcnc-uspace) is not installed"
fi

# 6. a GRBL sender's console log: $# gives the work offset (G54 at machine -200 -100 -30),
#    each probe a [PRB:…:1] report in machine coordinates, among ok's and status reports
rm 2021_Milling.gcode
{
  printf '> $#\n[G54:-200.000,-100.000,-30.000]\n[G92:0.000,0.000,0.000]\n[TLO:0.000]\n[PRB:0.000,0.000,0.000:0]\nok\n'
  awk '{ printf "> G38.3 Z0 F50\n<Idle|MPos:%.3f,%.3f,-25.000|FS:0,0>\n[PRB:%.3f,%.3f,%.3f:1]\nok\n", $1 - 200, $2 - 100, $1 - 200, $2 - 100, $3 - 30 }' probes.txt
} > console.log
expect_status 0 "$MILLPATH" adjust-z --probe-log console.log --max 0.5 2021
cmp 2021_Milling.gcode typed_Milling.gcode || fail "the GRBL log gave another program than the typed values"

# 7. x y z lines, with bCNC's .probe header (xmin xmax xn / ymin ymax yn / zmin zmax feed,
#    two empty lines), points in the program's coordinates as bCNC prints them (%g)
rm 2021_Milling.gcode
{
  printf '5 45 2\n-7 8 2\n-10 5 50\n\n\n'
  awk '{ printf "%g %g %g\n", $1, $2, $3 }' probes.txt
} > 2021.probe
expect_status 0 "$MILLPATH" adjust-z --probe-log 2021.probe --max 0.5 2021
cmp 2021_Milling.gcode typed_Milling.gcode || fail "the .probe file gave another program than the typed values"

# 8. the grbl dialect: its probing program probes at the same points, the console log gives
#    the program of the typed values there too
mkdir grbl && cp 2021.mpath millpath.toml console.log grbl/ && cd grbl
expect_status 0 "$MILLPATH" compile --dialect grbl 2021.mpath
cp 2021_Z.txt unfilled_Z.txt
paste -d '' unfilled_Z.txt <(cut -d' ' -f3 ../probes.txt) > 2021_Z.txt
expect_status 0 "$MILLPATH" adjust-z --max 0.5 2021
mv 2021_Milling.gcode typed_Milling.gcode
cp unfilled_Z.txt 2021_Z.txt
expect_status 0 "$MILLPATH" adjust-z --probe-log console.log --max 0.5 2021
cmp 2021_Milling.gcode typed_Milling.gcode || fail "grbl dialect: the console log gave another program"
expect_status 0 "$MILLPATH" verify --dialect grbl 2021_Milling.gcode
grep -q "0 error(s), 0 warning(s)" "$WORK/err" || fail "verify grbl: $(cat "$WORK/out" "$WORK/err")"
cd ..

# 9. refusals write nothing and name the line: a no-contact report, a point missing
rm 2021_Milling.gcode
sed '0,/:1]$/s/:1]$/:0]/' console.log > nocontact.log
expect_status 1 "$MILLPATH" adjust-z --probe-log nocontact.log --max 0.5 2021
grep -q "nocontact.log:9" "$WORK/err" || fail "no location: $(cat "$WORK/err")"
grep -q "GRBL reports no contact here" "$WORK/err" || fail "$(cat "$WORK/err")"
[ ! -f 2021_Milling.gcode ] || fail "a milling program was written after a no-contact report"
sed 2d probes.txt > short.txt
expect_status 1 "$MILLPATH" adjust-z --probe-log short.txt --max 0.5 2021
grep -q "No measurement in short.txt for probe #52 at X25.000 Y-7.000" "$WORK/err" || fail "$(cat "$WORK/err")"
g38=$(grep -n "^G38" 2021_Probing.gcode | sed -n 2p | cut -d: -f1)  # the second probe move
grep -q "2021_Probing.gcode:$g38\$" "$WORK/err" || fail "missing point not located: $(cat "$WORK/err")"
[ ! -f 2021_Milling.gcode ] || fail "a milling program was written with a point missing"
# a log from another surface, beyond --max at one point
awk '{ $3 = sprintf("%f", $3 + 0.6) } 1' probes.txt > high.txt
expect_status 1 "$MILLPATH" adjust-z --probe-log high.txt --max 0.5 2021
grep -q "differs from its nominal height 3.000 by more than --max=0.5" "$WORK/err" || fail "$(cat "$WORK/err")"
# something that is no probe log at all
expect_status 1 "$MILLPATH" adjust-z --probe-log 2021.mpath --max 0.5 2021
grep -q "Not a probe log millpath reads" "$WORK/err" || fail "$(cat "$WORK/err")"
[ ! -f 2021_Milling.gcode ] || fail "a milling program was written after a refusal"
echo "ok: LinuxCNC, GRBL and bCNC logs give the typed program (linuxcnc and grbl dialects); refusals write nothing"
