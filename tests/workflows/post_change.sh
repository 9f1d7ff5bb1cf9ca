# Issue 32: a post change leaves no program of the earlier post that an operator could take
# for current. Compiled for linuxcnc, then for xcam: the new NAME_Milling.NCC, and the old
# NAME_Milling.gcode (millpath's, of this drawing) removed with a warning; and back. A file
# of the user's own with such a name stays untouched; an adjusted program (measured heights)
# stays, with a warning located at its measurement; in German too.
source "$ROOT/tests/workflows/lib.bash"
cp "$ROOT/examples/text/2001.mpath" "$ROOT/examples/text/2020.mpath" "$ROOT/examples/text/millpath.toml" .
cp millpath.toml settings
post() { { cat settings; echo "post = \"$1\""; } > millpath.toml; }

# 1. linuxcnc, then xcam: the .gcode goes, said so
post linuxcnc
expect_status 0 "$MILLPATH" compile 2001.mpath
[ -f 2001_Milling.gcode ] || fail "no 2001_Milling.gcode"
echo "my own notes" > 2001_Milling.nc
post xcam
expect_status 0 "$MILLPATH" compile 2001.mpath
[ -f 2001_Milling.NCC ] || fail "no 2001_Milling.NCC"
[ ! -e 2001_Milling.gcode ] || fail "the linuxcnc program of the earlier compile stays beside the .NCC"
grep -q 'warning\[MP217\]: Removed 2001_Milling.gcode: .*another post; this compile wrote 2001_Milling.NCC' "$WORK/err" \
  || fail "no warning naming the removed program: $(cat "$WORK/err")"
[ "$(cat 2001_Milling.nc)" = "my own notes" ] || fail "a file of the user's own was touched"
! grep -q '2001_Milling.nc\b' "$WORK/err" || fail "a file of the user's own was reported: $(cat "$WORK/err")"

# 2. and back, in German: the .NCC goes
post linuxcnc
expect_status 0 "$MILLPATH" compile --lang de 2001.mpath
[ -f 2001_Milling.gcode ] && [ ! -e 2001_Milling.NCC ] || fail "the .NCC stays beside the .gcode"
grep -q 'Warnung\[MP217\]: 2001_Milling.NCC entfernt' "$WORK/err" || fail "no German warning: $(cat "$WORK/err")"
"$MILLPATH" verify --dialect linuxcnc --top 3 --tool 2 2001_Milling.gcode >/dev/null 2>&1 \
  || fail "the new program does not verify"

# 3. measured heights: 2020 probed and adjusted for linuxcnc, then its probes taken out and
#    compiled for xcam: the adjusted program stays, the warning at its banner line (set=)
expect_status 0 "$MILLPATH" compile 2020.mpath
sed -i 's/#51=$/#51=3.02/; s/#52=$/#52=2.97/' 2020_Z.txt
expect_status 0 "$MILLPATH" adjust-z --max 0.5 2020_Clean.gcode
cp 2020_Milling.gcode adjusted
sed -i '/probe (/d' 2020.mpath
post xcam
expect_status 0 "$MILLPATH" compile 2020.mpath
[ -f 2020_Milling.NCC ] || fail "no 2020_Milling.NCC"
cmp 2020_Milling.gcode adjusted || fail "the adjusted program (measured heights) was not kept as it was"
grep -q 'warning\[MP218\]: 2020_Milling.gcode is this drawing.s program for another post and holds measured heights' "$WORK/err" \
  || fail "no warning for the kept program: $(cat "$WORK/err")"
grep -q -- '--> .*2020_Milling.gcode:2$' "$WORK/err" || fail "the warning is not located at line 2: $(cat "$WORK/err")"
echo "ok: a post change removes the earlier post's program, keeps measured ones and the user's own"
