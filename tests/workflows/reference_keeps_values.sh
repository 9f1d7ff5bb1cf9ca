# The reference's drop-in command line (`millpath pathdxf2gcode`, as scripts built around
# PathDxf2GCode call it) compiles a drawing with z-probes after the machinist filled in its
# _Z.txt: the files written stay the reference's (an empty _Z.txt), but the measured values
# are kept beside as NAME_Z.1.txt first, with a warning (MP216, EN/DE); an unfilled one is
# simply replaced; a copy that cannot be made writes nothing of the drawing.
source "$ROOT/tests/workflows/lib.bash"
cp "$ROOT/examples/text/2020.mpath" .
"$MILLPATH" text2dxf 2020.mpath -o 2020.dxf >/dev/null
ref=(pathdxf2gcode /f300 /v1000 /s10 2020.dxf)
expect_status 0 "$MILLPATH" "${ref[@]}"
cp 2020_Z.txt unfilled.txt
expect_status 0 "$MILLPATH" "${ref[@]}"
[ ! -e 2020_Z.1.txt ] || fail "an unfilled _Z.txt was kept beside"
sed -i 's/#51=/#51=2,95/; s/#52=/#52=3.1/' 2020_Z.txt
cp 2020_Z.txt filled.txt
expect_status 0 "$MILLPATH" "${ref[@]}"
cmp -s 2020_Z.1.txt filled.txt || fail "the measured values were not kept: $(ls)"
cmp -s 2020_Z.txt unfilled.txt || fail "not the reference's _Z.txt"
grep -q "MP216.*kept as 2020_Z.1.txt" "$WORK/err" || fail "no warning: $(cat "$WORK/err")"
# the kept values adjust the program as the filled file would have
cp 2020_Z.1.txt 2020_Z.txt
expect_status 0 "$MILLPATH" adjust-z --max 0.5 2020_Clean.gcode
# again, in German: the next free name
expect_status 0 "$MILLPATH" "${ref[@]}" /l de
cmp -s 2020_Z.2.txt filled.txt || fail "second copy: $(ls)"
grep -q "enthielt Messwerte" "$WORK/err" || fail "German: $(cat "$WORK/err")"
# no copy possible (a read-only folder; root writes there anyway): nothing of the drawing
# is written
if [ "$(id -u)" != 0 ]; then
  cp filled.txt 2020_Z.txt
  chmod a-w .
  expect_status 1 "$MILLPATH" "${ref[@]}"
  chmod u+w .
  cmp -s 2020_Z.txt filled.txt || fail "the values were replaced without a copy"
fi
echo "ok: pathdxf2gcode keeps measured values beside"
