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

# adjust-z cannot adjust a height map yet: a filled-in grid _Z.txt is refused with one
# message, and no _Milling.gcode (which would mill the nominal depths) is written
cd linuxcnc
sed -i 's/=$/=3.05/' 1234.1P_Z.txt
expect_status 1 "$MILLPATH" adjust-z --max 1 1234.1P
grep -q 'points of a height map' "$WORK/err" || fail "adjust-z: $(cat "$WORK/err")"
[ ! -e 1234.1P_Milling.gcode ] || fail "adjust-z wrote a program for a height map"
echo "heightmap probing: linuxcnc and grbl sets checked; adjust-z refuses the grid"
