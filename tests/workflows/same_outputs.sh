# The two-ways workflow (docs/src/editors.md) leaves part.dxf and part.mpath side by side;
# both compile to part_Milling.gcode. `compile .` of that folder must not let one program
# replace the other's without a word ("compiled 2 of 2"): neither is compiled, each is named
# (MP214, EN/DE), the program already there stays, other drawings of the folder compile, and
# the one meant compiles by name. And `render` never writes its picture over the drawing
# it reads (`--svg part.mpath` for `--svg part.svg`: MP215).
source "$ROOT/tests/workflows/lib.bash"
cp "$ROOT/examples/plate/1234.1P.dxf" "$ROOT/examples/plate/millpath.toml" .
cp "$ROOT/examples/text/2001.mpath" .
expect_status 0 "$MILLPATH" compile 1234.1P.dxf
md5sum 1234.1P_Milling.gcode >before.md5
expect_status 0 "$MILLPATH" dxf2text 1234.1P.dxf -o 1234.1P.mpath
sed -i 's/B-0,2/B-0,4/' 1234.1P.mpath # an edit not yet written back

expect_status 1 "$MILLPATH" compile .
grep -q "MP214" "$WORK/err" || fail "no message: $(cat "$WORK/err")"
grep -q "1234.1P.dxf and ./1234.1P.mpath would write the same files" "$WORK/err" || fail "$(cat "$WORK/err")"
grep -q "compiled 1 of 3 drawings; not written: ./1234.1P.dxf, ./1234.1P.mpath" "$WORK/err" ||
  fail "summary: $(cat "$WORK/err")"
md5sum -c --quiet before.md5 || fail "the program already there was replaced"
[ -f 2001_Milling.gcode ] || fail "the other drawing of the folder was not compiled"
expect_status 1 "$MILLPATH" compile --lang de 1234.1P.dxf 1234.1P.mpath
grep -q "würden dieselben Dateien schreiben" "$WORK/err" || fail "German: $(cat "$WORK/err")"

# by name: the one meant
expect_status 0 "$MILLPATH" compile 1234.1P.mpath
grep -q "Z-0.400" 1234.1P_Milling.gcode || fail "the text's program was not written"
# one file given twice is no pair
expect_status 0 "$MILLPATH" compile 1234.1P.dxf ./1234.1P.dxf

cp 2001.mpath 2001.before
for kind in svg png html; do
  expect_status 1 "$MILLPATH" render 2001.mpath --$kind ./2001.mpath
  grep -q "MP215" "$WORK/err" || fail "render --$kind: $(cat "$WORK/err")"
  cmp -s 2001.mpath 2001.before || fail "render --$kind replaced the drawing"
done
expect_status 0 "$MILLPATH" render 2001.mpath --svg 2001.svg
grep -q "<svg" 2001.svg || fail "no picture"
echo "ok: two drawings of one name are not compiled over each other"
