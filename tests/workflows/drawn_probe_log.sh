# Drawn probes on LinuxCNC without typing: compile writes the probing program with
# (PROBEOPEN NAME_probes.txt) … (PROBECLOSE), so LinuxCNC writes the log itself, and
# `adjust-z --probe-log NAME_probes.txt NAME_Clean.gcode` reads it. rs274 runs the program;
# the log LinuxCNC would write at the program's own G38 points (nine numbers a contact, in
# the program's order) gives the same program, byte for byte, as the heights typed into
# _Z.txt. grbl (no such command) and the reference dialect (byte-identical) have no PROBEOPEN.
source "$ROOT/tests/workflows/lib.bash"
cp "$ROOT/examples/text/millpath.toml" .
cat > 2022.mpath <<'EOF'
path 2022.1P {
  start (5, -3)  M10x3 O2 T3 I1,5 B-0,2
  end (65, -3)
  mill (5, -3) -> (35, -3)
  mill (35, -3) -> (65, -3) ccw around (50, -3)
  probe (10, 5)
  probe (50, 5)  L1
  probe (30, -10)
}
EOF

# 1. compile for LinuxCNC: the probes wrapped in PROBEOPEN/PROBECLOSE, nothing else in there
expect_status 0 "$MILLPATH" compile --dialect linuxcnc 2022.mpath
open=$(grep -n '^(PROBEOPEN 2022_probes.txt)$' 2022_Probing.gcode | cut -d: -f1)
close=$(grep -n '^(PROBECLOSE)$' 2022_Probing.gcode | cut -d: -f1)
first=$(grep -n '^G38' 2022_Probing.gcode | head -1 | cut -d: -f1)
last=$(grep -n '^G38' 2022_Probing.gcode | tail -1 | cut -d: -f1)
[ -n "$open" ] && [ -n "$close" ] || fail "no PROBEOPEN/PROBECLOSE: $(cat 2022_Probing.gcode)"
[ "$open" -lt "$first" ] && [ "$last" -lt "$close" ] || fail "the probes are not inside the log"
[ "$(grep -c PROBEOPEN 2022_Probing.gcode)" -eq 1 ] || fail "more than one PROBEOPEN"

# 2. LinuxCNC's interpreter runs it (PROBEOPEN and PROBECLOSE are active comments there)
if command -v rs274 >/dev/null; then
  status=0
  err=$(timeout 60 rs274 -g 2022_Probing.gcode </dev/null 2>&1 >/dev/null) || status=$?
  why=$(printf '%s\n' "$err" | grep -v '^executing$' || true)
  [ "$status" -eq 0 ] && [ -z "$why" ] || fail "rs274 rejects the probing program: $why"
  echo "rs274 runs 2022_Probing.gcode with its PROBEOPEN/PROBECLOSE"
else
  echo "skipped rs274: LinuxCNC (package linuxcnc-uspace) is not installed"
fi

# 3. the log LinuxCNC writes on a board tilted in X and Y (z = 3 + 0.004·x − 0.003·y): one
#    line per G38 contact in the program's order, X Y Z A B C U V W ("%f"), at the XY of the
#    G00 before it; only what lies between PROBEOPEN and PROBECLOSE is logged
awk '/^\(PROBEOPEN / { on = 1 } /^\(PROBECLOSE\)/ { on = 0 }
     /^G00/ { for (i = 2; i <= NF; i++) { if ($i ~ /^X/) x = substr($i, 2); if ($i ~ /^Y/) y = substr($i, 2) } }
     /^G38/ && on { z = sprintf("%.3f", 3 + 0.004 * x - 0.003 * y)
                    printf "%f %f %f 0.000000 0.000000 0.000000 0.000000 0.000000 0.000000\n", x, y, z }' \
  2022_Probing.gcode > 2022_probes.txt
[ "$(wc -l < 2022_probes.txt)" -eq 3 ] || fail "expected 3 contacts: $(cat 2022_probes.txt)"

# 4. the old way: the same heights typed into _Z.txt (its order is the program's)
cp 2022_Z.txt unfilled_Z.txt
paste -d '' unfilled_Z.txt <(cut -d' ' -f3 2022_probes.txt) > 2022_Z.txt
expect_status 0 "$MILLPATH" adjust-z --max 0.5 2022
mv 2022_Milling.gcode typed_Milling.gcode

# 5. the new way, nothing typed: _Z.txt as compile wrote it, the log as LinuxCNC named it
cp unfilled_Z.txt 2022_Z.txt
expect_status 0 "$MILLPATH" adjust-z --probe-log 2022_probes.txt --max 0.5 2022_Clean.gcode
cmp 2022_Milling.gcode typed_Milling.gcode || fail "the log gave another program than the typed values"
grep -q 'Z[-0-9.]*(==' 2022_Milling.gcode || fail "no corrected Z in the result"
expect_status 0 "$MILLPATH" verify 2022_Milling.gcode
grep -q "0 error(s), 0 warning(s)" "$WORK/err" || fail "verify: $(cat "$WORK/out" "$WORK/err")"
if command -v rs274 >/dev/null; then
  status=0
  err=$(timeout 60 rs274 -g 2022_Milling.gcode </dev/null 2>&1 >/dev/null) || status=$?
  why=$(printf '%s\n' "$err" | grep -v '^executing$' || true)
  [ "$status" -eq 0 ] && [ -z "$why" ] || fail "rs274 rejects the adjusted program: $why"
fi

# 6. grbl has no PROBEOPEN (its console holds [PRB:…]); the reference dialect writes
#    PathDxf2GCode's program, which has none either
mkdir grbl ref && cp 2022.mpath millpath.toml grbl/ && cp 2022.mpath millpath.toml ref/
(cd grbl && expect_status 0 "$MILLPATH" compile --dialect grbl 2022.mpath)
grep -q 'PROBE' grbl/2022_Probing.gcode && fail "grbl program has a PROBEOPEN: $(cat grbl/2022_Probing.gcode)"
(cd ref && expect_status 0 "$MILLPATH" compile 2022.mpath)
grep -q 'PROBE' ref/2022_Probing.gcode && fail "reference program has a PROBEOPEN"
echo "ok: the LinuxCNC program logs its own probes; the log gives the typed program"
