# Issue 31: the heights measured on the machine survive the next compile. A probing set is
# compiled, its _Z.txt filled in (as typed: a decimal comma), adjusted; the unchanged
# drawing compiled again (alone and as its folder) keeps the values and the adjusted program
# byte for byte. A drawing whose probe moved keeps the old file beside (never over an earlier
# one) and carries the value of the probe that did not move into the new _Z.txt.
source "$ROOT/tests/workflows/lib.bash"
cp "$ROOT/examples/text/2020.mpath" "$ROOT/examples/text/millpath.toml" .

# 1. compile, probe, fill in, adjust
expect_status 0 "$MILLPATH" compile 2020.mpath
grep -q '#51=$' 2020_Z.txt || fail "compile wrote no empty #51: $(cat 2020_Z.txt)"
sed -i 's/#51=$/#51=2,95/; s/#52=$/#52=3.1/' 2020_Z.txt
expect_status 0 "$MILLPATH" adjust-z --max 0.5 2020_Clean.gcode
mkdir keep && cp 2020_Z.txt 2020_Milling.gcode keep/

# 2. compiled again, the file alone and the folder: nothing the machinist made is lost
for args in "2020.mpath" "."; do
  expect_status 0 "$MILLPATH" compile "$args"
  cmp 2020_Z.txt keep/2020_Z.txt || fail "compile $args changed the measured values: $(cat 2020_Z.txt)"
  cmp 2020_Milling.gcode keep/2020_Milling.gcode || fail "compile $args changed the adjusted program"
  grep -q 'Keeping (measured values of the same probes) .*2020_Z.txt' "$WORK/err" \
    || fail "compile $args does not say it kept 2020_Z.txt: $(cat "$WORK/err")"
  ! grep -q MP144 "$WORK/err" || fail "compile $args removed a program of this set: $(cat "$WORK/err")"
done
expect_status 0 "$MILLPATH" adjust-z --max 0.5 2020_Clean.gcode
cmp 2020_Milling.gcode keep/2020_Milling.gcode || fail "adjust-z after the recompile wrote another program"

# 3. probe L1 moved in the drawing: the old file beside, #51 carried over, #52 to be measured
sed -i 's/probe (50, 5)/probe (45, 5)/' 2020.mpath
expect_status 0 "$MILLPATH" compile 2020.mpath
cmp 2020_Z.1.txt keep/2020_Z.txt || fail "the old measured values were not kept as 2020_Z.1.txt"
grep -q 'kept as 2020_Z.1.txt. 1 carried over to the new 2020_Z.txt' "$WORK/err" \
  || fail "no warning naming the kept file: $(cat "$WORK/err")"
grep -q 'Removed 2020_Milling.gcode' "$WORK/err" || fail "the program of the other set stays"
grep -qx '(\[10.000 5.000\]/T=3.000) #51=2,95' 2020_Z.txt || fail "#51 not carried over: $(cat 2020_Z.txt)"
grep -qx '(\[45.000 5.000\]/L:1/T=3.000) #52=' 2020_Z.txt || fail "#52 is not empty: $(cat 2020_Z.txt)"
expect_status 1 "$MILLPATH" adjust-z --max 0.5 2020_Clean.gcode
grep -q 'No measured value for probe #52' "$WORK/err" || fail "adjust-z took an unmeasured probe"
sed -i 's/#52=$/#52=3.05/' 2020_Z.txt
expect_status 0 "$MILLPATH" adjust-z --max 0.5 2020_Clean.gcode

# 4. moved again, in German: a second side file, the first untouched
cp 2020_Z.txt keep/second
sed -i 's/probe (45, 5)/probe (40, 5)/' 2020.mpath
expect_status 0 "$MILLPATH" compile --lang de 2020.mpath
grep -q 'als 2020_Z.2.txt aufbewahrt. 1 in die neue 2020_Z.txt übernommen' "$WORK/err" \
  || fail "no German warning: $(cat "$WORK/err")"
cmp 2020_Z.1.txt keep/2020_Z.txt || fail "the first side file changed"
cmp 2020_Z.2.txt keep/second || fail "the second side file is not the previous _Z.txt"
echo "ok: measured values kept over recompiles, carried over where the probe did not move"
