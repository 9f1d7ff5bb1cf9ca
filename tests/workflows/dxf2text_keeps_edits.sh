# Draw in CAD, edit as text, write back (docs/src/editors.md): `dxf2text -o` never replaces a
# text that holds edits not yet written back (or comments): it refuses (MP213), naming the
# way back, in English and German; the same text again is fine; --force replaces; -o onto
# the drawing itself is refused too. The chain then goes on to text2dxf --into and compile.
source "$ROOT/tests/workflows/lib.bash"
cp "$ROOT/examples/plate/1234.1P.dxf" "$ROOT/examples/plate/millpath.toml" .
cp 1234.1P.dxf drawing.before

expect_status 0 "$MILLPATH" dxf2text 1234.1P.dxf -o 1234.1P.mpath
# running it again on the unchanged drawing: the same text, no complaint
expect_status 0 "$MILLPATH" dxf2text 1234.1P.dxf -o 1234.1P.mpath
# the user edits the text (a deeper cut, a note) and runs the first step again by habit
sed -i 's/B-0,2/B-0,4/' 1234.1P.mpath
sed -i '1i # deeper: the plywood of batch 7 is thicker' 1234.1P.mpath
cp 1234.1P.mpath edited.mpath
expect_status 1 "$MILLPATH" dxf2text 1234.1P.dxf -o 1234.1P.mpath
grep -q "MP213" "$WORK/err" && grep -q "text2dxf 1234.1P.mpath --into 1234.1P.dxf" "$WORK/err" ||
  fail "no reason given: $(cat "$WORK/err")"
cmp -s 1234.1P.mpath edited.mpath || fail "dxf2text -o replaced the edited text"
expect_status 1 "$MILLPATH" dxf2text --lang de 1234.1P.dxf -o 1234.1P.mpath
grep -q "Es wurde nichts geschrieben" "$WORK/err" || fail "German: $(cat "$WORK/err")"
# a comment alone is worth keeping too
expect_status 0 "$MILLPATH" dxf2text 1234.1P.dxf -o only-comment.mpath
echo "# fixture on the left" >>only-comment.mpath
expect_status 1 "$MILLPATH" dxf2text 1234.1P.dxf -o only-comment.mpath
grep -q "fixture on the left" only-comment.mpath || fail "the comment was lost"
# -o onto the drawing itself
expect_status 1 "$MILLPATH" dxf2text 1234.1P.dxf -o 1234.1P.dxf
cmp -s 1234.1P.dxf drawing.before || fail "dxf2text -o replaced the drawing by text"

# the way the message names: write back, then dxf2text is the same text again
expect_status 0 "$MILLPATH" text2dxf 1234.1P.mpath --into 1234.1P.dxf
expect_status 0 "$MILLPATH" compile 1234.1P.dxf
grep -q "Z-0.400" 1234.1P_Milling.gcode || fail "the deeper cut is not in the program"
expect_status 1 "$MILLPATH" dxf2text 1234.1P.dxf -o 1234.1P.mpath  # the comment is only in the text
expect_status 0 "$MILLPATH" dxf2text --force 1234.1P.dxf -o 1234.1P.mpath
grep -q "B-0,4" 1234.1P.mpath || fail "--force did not write the drawing's text"
! grep -q "batch 7" 1234.1P.mpath || fail "--force kept the old text"
echo "ok: dxf2text -o keeps edited texts"
