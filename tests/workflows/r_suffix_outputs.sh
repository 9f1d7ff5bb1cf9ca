# A path's R value is part of its output names: `a.mpath` with `R_X` writes
# a_X_Milling.gcode, as the drawing a_X.dxf without one does. `compile .` of a folder with
# both must not let the later program replace the earlier one's ("compiled 2 of 2"): the
# later drawing is refused, naming both (MP219, EN/DE, at its start and the other's), the
# earlier program stays; a failing drawing does not remove the other's program as its own
# stale output; an R that leads into another folder (`R/../name`) is caught the same way;
# one drawing named twice is no pair.
source "$ROOT/tests/workflows/lib.bash"
machine=(--feed 150 --sweep-speed 1000 --sweep-height 10)
cat >a.mpath <<'EOF'
path 1111.1P {
  start (0, 0)  M3 O2 T3 I1,5 B-0,2 R_X
  end (60, 0)
  mill (0, 0) -> (60, 0)
}
EOF
sed -e 's/B-0,2 R_X/B-0,4/' a.mpath >a_X.mpath
expect_status 0 "$MILLPATH" text2dxf a_X.mpath
rm a_X.mpath

# 1. the folder: a.mpath writes a_X_Milling.gcode, a_X.dxf is refused
expect_status 1 "$MILLPATH" compile "${machine[@]}" .
grep -q "MP219" "$WORK/err" || fail "no message: $(cat "$WORK/err")"
grep -q "a_X.dxf would write ./a_X_Milling.gcode, which ./a.mpath wrote in this run" "$WORK/err" ||
  fail "the message does not name both: $(cat "$WORK/err")"
grep -q -- "--> ./a_X.dxf:.*layer 1111_1P" "$WORK/err" || fail "not located at the drawing: $(cat "$WORK/err")"
grep -q "start of the other drawing's path: ./a.mpath:2:3" "$WORK/err" ||
  fail "the other drawing's start is not named: $(cat "$WORK/err")"
grep -q "compiled 1 of 2 drawings; not written: ./a_X.dxf" "$WORK/err" || fail "summary: $(cat "$WORK/err")"
# a_X_Milling.gcode is a.mpath's program (depth 0.2), no other drawing's
ours() { grep -q "Z-0.200" a_X_Milling.gcode && ! grep -q "Z-0.[46]00" a_X_Milling.gcode; }
ours || fail "a.mpath's program was replaced"
ls -A | grep -q stage && fail "a staged program was left: $(ls -A)"

# 2. in German, named on the command line
expect_status 1 "$MILLPATH" compile --lang de "${machine[@]}" a.mpath a_X.dxf
grep -q "a_X.dxf würde a_X_Milling.gcode schreiben, das a.mpath in diesem Lauf geschrieben hat" "$WORK/err" ||
  fail "German: $(cat "$WORK/err")"
ours || fail "the German run replaced the program"

# 3. a drawing that fails leaves the other's program: it is not its own stale output
cp a_X.dxf a_X.good.dxf
sed -i 's/ O2 / O-2 /' a_X.dxf # a negative tool diameter: an error
grep -q " O-2 " a_X.dxf || fail "the error was not drawn"
expect_status 1 "$MILLPATH" compile "${machine[@]}" a.mpath a_X.dxf
grep -q "MP021" "$WORK/err" || fail "a_X.dxf did not fail: $(cat "$WORK/err")"
grep -q "MP144" "$WORK/err" && fail "a program was removed: $(cat "$WORK/err")"
[ -f a_X_Milling.gcode ] || fail "the failing drawing removed a.mpath's program"
ours || fail "the failing drawing changed a.mpath's program"
mv a_X.good.dxf a_X.dxf

# 4. an R into another folder: sub.mpath with R/../a_X writes ./a_X_Milling.gcode too
mkdir sub
sed -e 's#R_X#R/../a_X#' -e 's/B-0,2/B-0,6/' a.mpath >sub.mpath
expect_status 1 "$MILLPATH" compile "${machine[@]}" a.mpath sub.mpath
grep -q "sub.mpath would write sub/../a_X_Milling.gcode, which a.mpath wrote in this run" "$WORK/err" ||
  fail "R into another folder: $(cat "$WORK/err")"
ours || fail "sub.mpath replaced the program"

# 5. one drawing named twice is no pair; each alone compiles as before
expect_status 0 "$MILLPATH" compile "${machine[@]}" a.mpath ./a.mpath
expect_status 0 "$MILLPATH" compile "${machine[@]}" a_X.dxf
grep -q "Z-0.400" a_X_Milling.gcode || fail "a_X.dxf by name was not written"
echo "ok: an R suffix does not let one program replace another's"
