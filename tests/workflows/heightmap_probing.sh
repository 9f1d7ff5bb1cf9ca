# A height map instead of drawn probes (issue 21, compile side): the machinist adds a
# [heightmap] to millpath.toml and compiles for LinuxCNC and for GRBL. Each compile writes
# the probing program, _Z.txt and the nominal _Clean.gcode; the probing program probes every
# _Z.txt point in serpentine order, and LinuxCNC's interpreter (rs274) runs it with its
# PROBEOPEN/PROBECLOSE log, and the clean program. The reference dialect refuses the map.
source "$ROOT/tests/workflows/lib.bash"

cp "$ROOT/examples/plate/1234.1P.dxf" "$ROOT/examples/text/2001.mpath" .
cat >millpath.toml <<'EOF'
feed = 300
sweep_speed = 1000
sweep_height = 10
probe_feed = 100

[heightmap]
step = 10       # mm between probe points
margin = 2      # mm around the cuts
probe_depth = 4 # the probe may go 4 mm below the top
EOF

# check_set NAME DIALECT: the three files, the points probed in the _Z.txt order, serpentine
check_set() {
  local name=$1 dialect=$2
  for f in _Probing.gcode _Z.txt _Clean.gcode; do
    [ -s "$name$f" ] || fail "$dialect: $name$f not written"
  done
  [ -e "${name}_Milling.gcode" ] && fail "$dialect: a _Milling.gcode beside the probing set"
  python3 - "$name" "$dialect" <<'PY' || fail "$dialect: $name: the probing program and _Z.txt disagree"
import re, sys
name, dialect = sys.argv[1], sys.argv[2]
z = [l for l in open(f"{name}_Z.txt").read().splitlines() if l]
points, names = [], []
for l in z:
    m = re.fullmatch(r"\(\[(-?[0-9.]+) (-?[0-9.]+)\]/T=(-?[0-9.]+)\) (#[0-9]+)=", l)
    assert m, f"_Z.txt line: {l}"
    points.append((float(m[1]), float(m[2])))
    names.append(m[4])
assert names == [f"#{1000 + k}" for k in range(len(names))], names
# where each G38.2 probes, following the program's X and Y
x = y = 0.0
probed = []
prog = open(f"{name}_Probing.gcode").read()
for l in prog.splitlines():
    if l.startswith("("):
        continue
    if l.startswith("G38.2"):
        probed.append((x, y))
    for letter, v in re.findall(r"([XY])(-?[0-9.]+)", l):
        if letter == "X":
            x = float(v)
        else:
            y = float(v)
assert probed == points, f"probed {probed}\n_Z.txt {points}"
# serpentine: rows by rising Y; X rising in the first row, falling in the next, …
rows = {}
for px, py in points:
    rows.setdefault(py, []).append(px)
ys = list(rows)
assert ys == sorted(ys), ys
for j, yv in enumerate(ys):
    xs = rows[yv]
    assert xs == (sorted(xs) if j % 2 == 0 else sorted(xs, reverse=True)), (yv, xs)
    assert len(xs) == len(rows[ys[0]])
# LinuxCNC writes the log; GRBL reports [PRB:...] to the sender and knows no PROBEOPEN
has_log = f"(PROBEOPEN {name}_probes.txt)" in prog and "(PROBECLOSE)" in prog
assert has_log == (dialect == "linuxcnc"), dialect
if dialect == "grbl":
    assert "%" not in prog and "#" not in prog
print(f"{dialect} {name}: {len(points)} points in {len(ys)} rows")
PY
}

for dialect in linuxcnc grbl; do
  mkdir "$dialect" && cp 1234.1P.dxf 2001.mpath millpath.toml "$dialect/" && cd "$dialect"
  expect_status 0 "$MILLPATH" compile --dialect "$dialect" 1234.1P.dxf
  check_set 1234.1P "$dialect"
  expect_status 0 "$MILLPATH" compile --dialect "$dialect" 2001.mpath
  check_set 2001 "$dialect"
  # the clean program is one the independent checker accepts as it is
  expect_status 0 "$MILLPATH" verify --dialect "$dialect" 1234.1P_Clean.gcode
  cd ..
done

# LinuxCNC's interpreter runs both programs (batch mode, stdin closed). rs274 moves no real
# probe: a G38.2 becomes STRAIGHT_PROBE to its target, and PROBEOPEN/PROBECLOSE reach the
# machine as the comments the task turns into the log file (rs274 writes no file itself).
if command -v rs274 >/dev/null; then
  cd linuxcnc
  for p in 1234.1P_Probing.gcode 1234.1P_Clean.gcode 2001_Probing.gcode 2001_Clean.gcode; do
    status=0
    timeout 60 rs274 -g "$p" </dev/null >"$WORK/canon" 2>"$WORK/rs274err" || status=$?
    why=$(grep -v '^executing$' "$WORK/rs274err" || true)
    [ "$status" -eq 0 ] && [ -z "$why" ] || fail "rs274 $p: exit $status $why"
    grep -q 'PROGRAM_END' "$WORK/canon" || fail "rs274 $p: did not reach M30"
  done
  for name in 1234.1P 2001; do
    rs274 -g "${name}_Probing.gcode" </dev/null >"$WORK/canon" 2>/dev/null
    grep -q "COMMENT(\"PROBEOPEN ${name}_probes.txt\")" "$WORK/canon" || fail "$name: no PROBEOPEN"
    grep -q 'COMMENT("PROBECLOSE")' "$WORK/canon" || fail "$name: no PROBECLOSE"
    probes=$(grep -c 'STRAIGHT_PROBE' "$WORK/canon")
    points=$(grep -c '=$' "${name}_Z.txt")
    [ "$probes" -eq "$points" ] || fail "$name: rs274 probed $probes times for $points points"
    echo "rs274 $name: $probes probes between PROBEOPEN and PROBECLOSE"
  done
  cd ..
else
  echo "skipped: rs274 (LinuxCNC's interpreter, package linuxcnc-uspace) is not installed"
fi

# the reference dialect writes PathDxf2GCode's programs, which have no height map: refused,
# located at the settings file (a settings error: exit 2), nothing written
mkdir reference && cp 1234.1P.dxf millpath.toml reference/ && cd reference
expect_status 2 "$MILLPATH" compile 1234.1P.dxf
grep -q 'needs the linuxcnc or grbl dialect' "$WORK/err" || fail "reference: $(cat "$WORK/err")"
grep -q 'millpath.toml' "$WORK/err" || fail "reference: not located at millpath.toml"
ls | grep -q gcode && fail "reference: something was written"
cd ..

# The machinist runs the probing program. LinuxCNC writes NAME_probes.txt itself (one line of
# nine numbers per contact); here the log is what it would write over a board that rises
# 0.5 mm along X and falls 0.2 mm along Y. adjust-z reads the log and writes a program whose
# cuts follow the board; LinuxCNC's interpreter runs it.
cd linuxcnc
board="3 + 0.01 * x - 0.005 * y"
write_probe_log 1234.1P_Probing.gcode "$board" linuxcnc >1234.1P_probes.txt
expect_status 0 "$MILLPATH" adjust-z --max 1 --probe-log 1234.1P_probes.txt 1234.1P_Clean.gcode
grep -q 'moves split into' "$WORK/err" || fail "adjust-z: no split count: $(cat "$WORK/err")"
[ -s 1234.1P_Milling.gcode ] || fail "adjust-z wrote no program"
grep -q '^(MILLPATH-SURFACE T=3.000 ' 1234.1P_Milling.gcode || fail "no surface record"
# the first groove (X10, Y10 → Y30 at Z1.500 nominal) now ends 0.1 mm lower than it starts
grep -q '^G01 F300.000 X10.000 Y18.000 Z1.510$' 1234.1P_Milling.gcode \
  || fail "the groove does not follow the board: $(grep -m3 '^G01' 1234.1P_Milling.gcode)"
if command -v rs274 >/dev/null; then
  status=0
  timeout 60 rs274 -g 1234.1P_Milling.gcode </dev/null >"$WORK/canon" 2>"$WORK/rs274err" || status=$?
  why=$(grep -v '^executing$' "$WORK/rs274err" || true)
  [ "$status" -eq 0 ] && [ -z "$why" ] || fail "rs274 1234.1P_Milling.gcode: exit $status $why"
  grep -q 'PROGRAM_END' "$WORK/canon" || fail "rs274: the adjusted program did not reach M30"
fi
good=$(cat 1234.1P_Milling.gcode)

# Every broken log is refused, names what is wrong, and leaves no program behind.
# refuse NAME PATTERN: adjust-z with bad.txt fails with PATTERN, no _Milling.gcode stays
refuse() {
  rm -f 1234.1P_Milling.gcode
  expect_status 1 "$MILLPATH" adjust-z --max 1 --probe-log bad.txt 1234.1P_Clean.gcode
  grep -q "$2" "$WORK/err" || fail "$1: $(cat "$WORK/err")"
  [ ! -e 1234.1P_Milling.gcode ] || fail "$1: a program was written"
}
sed '$d' 1234.1P_probes.txt >bad.txt
refuse "a missing point" 'No measurement in bad.txt for probe'
{ cat 1234.1P_probes.txt; echo "500.000000 500.000000 3.000000 0 0 0 0 0 0"; } >bad.txt
refuse "an extra point" 'matches no probe point'
sed '3s/^\([^ ]* [^ ]*\) [^ ]*/\1 nan/' 1234.1P_probes.txt >bad.txt
refuse "a NaN height" 'not a finite number'
sed '3s/^\([^ ]* [^ ]*\) [^ ]*/\1 4.5/' 1234.1P_probes.txt >bad.txt
refuse "a height beyond --max" 'by more than --max=1'
cd ..

# GRBL: the sender's console log, machine coordinates and the work offset; no contact (:0)
# is refused
cd grbl
write_probe_log 1234.1P_Probing.gcode "$board" grbl >console.txt
expect_status 0 "$MILLPATH" adjust-z --max 1 --probe-log console.txt 1234.1P_Clean.gcode
grep -q '^G01 F300.000 X10.000 Y18.000 Z1.510$' 1234.1P_Milling.gcode \
  || fail "grbl: the groove does not follow the board"
[ "$(grep -v '^%' 1234.1P_Milling.gcode | grep -c .)" -eq "$(printf '%s\n' "$good" | grep -v '^%' | grep -c .)" ] \
  || fail "grbl and linuxcnc adjust the same moves differently"
sed '0,/:1]/s/:1]/:0]/' console.txt >bad.txt
rm 1234.1P_Milling.gcode
expect_status 1 "$MILLPATH" adjust-z --max 1 --probe-log bad.txt 1234.1P_Clean.gcode
grep -q 'GRBL reports no contact here' "$WORK/err" || fail "grbl :0: $(cat "$WORK/err")"
[ ! -e 1234.1P_Milling.gcode ] || fail "grbl :0: a program was written"
cd ..
echo "heightmap probing: linuxcnc and grbl sets checked and adjusted to a probe log; 5 broken logs refused"
