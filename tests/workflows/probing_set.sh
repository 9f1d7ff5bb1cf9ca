# The outputs of one probed drawing are one set: a compile that cannot write one of them
# leaves the old set whole, adjust-z refuses files of different compiles, and the normal
# chain compile → probe → fill in _Z.txt → adjust-z → verify works.
source "$ROOT/tests/workflows/lib.bash"
cp "$ROOT/examples/text/2020.mpath" "$ROOT/examples/text/millpath.toml" .

# 1. compile the probed drawing: probing program, _Z.txt and _Clean.gcode
expect_status 0 "$MILLPATH" compile 2020.mpath
for f in 2020_Probing.gcode 2020_Z.txt 2020_Clean.gcode; do [ -f $f ] || fail "$f missing"; done
md5sum 2020_Probing.gcode 2020_Z.txt 2020_Clean.gcode > first.md5

# 2. one output cannot be written: immutable (tests run as root, for whom chmod stops
#    nothing); without chattr, a folder in the place of the file is the honest stand-in
unwritable() {
  if chattr +i "$1" 2>/dev/null; then
    trap 'chattr -i "$WORK/2020_Clean.gcode" 2>/dev/null || true' EXIT
    echo "made $1 immutable (chattr +i)"
  else
    echo "chattr +i is not available or not permitted here: a folder takes the file's place"
    mv "$1" "$1.saved" && mkdir "$1" && touch "$1/keep"
  fi
}
unwritable 2020_Clean.gcode

# 3. change the depth B and move a probe, compile again: it fails and says so
sed -i 's/B-0,2/B-0,5/; s/probe (50, 5)  L1/probe (45, 5)  L1/' 2020.mpath
expect_status 1 "$MILLPATH" compile 2020.mpath
grep -q "Cannot write 2020_Clean.gcode" "$WORK/err" || fail "no write error: $(cat "$WORK/err")"
grep -q "left as they were" "$WORK/err" || fail "no word on the kept set"

# 4. the old set is intact (never the new _Z.txt with the old _Clean.gcode)
chattr -i 2020_Clean.gcode 2>/dev/null || true
if [ -d 2020_Clean.gcode ]; then rm -r 2020_Clean.gcode; mv 2020_Clean.gcode.saved 2020_Clean.gcode; fi
md5sum -c --quiet first.md5 || fail "the set changed after a failed compile"
ls -a | grep -q '\.tmp$\|\.old$' && fail "temporary files left: $(ls -a)"

# 5. a hand-made mix (new probing program and _Z.txt, old _Clean.gcode) is refused, naming
#    the files and saying what to do
cp 2020_Clean.gcode old_Clean.gcode
expect_status 0 "$MILLPATH" compile 2020.mpath
cp old_Clean.gcode 2020_Clean.gcode
sed -i 's/#51=$/#51=3.1/; s/#52=$/#52=2.9/' 2020_Z.txt
expect_status 1 "$MILLPATH" adjust-z --max 1 2020
grep -q "2020_Clean.gcode and 2020_Z.txt are not from the same compile: compile the drawing again" "$WORK/err" \
  || fail "mix not refused: $(cat "$WORK/err")"
grep -q "2020_Probing.gcode and 2020_Clean.gcode are not from the same compile" "$WORK/err" \
  || fail "probing program not named"
[ ! -f 2020_Milling.gcode ] || fail "a milling program was written from a mix"
# the reference's command line refuses it the same way
expect_status 1 "$MILLPATH" pathgcodeadjustz /m1 2020
grep -q "not from the same compile" "$WORK/err" || fail "pathgcodeadjustz accepted the mix"

# 6. an unfilled _Z.txt gets one 'no measured value' per probe, at file:line
expect_status 0 "$MILLPATH" compile 2020.mpath
expect_status 1 "$MILLPATH" adjust-z --max 1 2020
[ "$(grep -c 'No measured value for probe' "$WORK/err")" -eq 2 ] || fail "$(cat "$WORK/err")"
grep -q -- "--> 2020_Z.txt:2" "$WORK/err" || fail "no location"
grep -q "does not have format" "$WORK/err" && fail "format message on an unfilled line"

# 7. the normal chain: fill in the measured heights, adjust-z, verify
sed -i 's/#51=$/#51=3.1/; s/#52=$/#52=2.9/' 2020_Z.txt
expect_status 0 "$MILLPATH" adjust-z --max 1 2020
grep -q "Z-0.4" 2020_Milling.gcode || fail "not milled at the measured depth: $(grep 'Z-0' 2020_Milling.gcode)"
expect_status 0 "$MILLPATH" verify --top 3 --tool 2 --bottom -0.5 2020_Milling.gcode
grep -q "0 error(s), 0 warning(s)" "$WORK/err" || fail "verify: $(cat "$WORK/out" "$WORK/err")"

# 8. a compile that fails now removes the outputs it can no longer stand behind
sed -i 's/mill (0, 0) -> (60, 0)/mill (0, 0) -> (61, 0)/' 2020.mpath
expect_status 1 "$MILLPATH" compile 2020.mpath
for f in 2020_Milling.gcode 2020_Probing.gcode 2020_Clean.gcode; do
  [ ! -e $f ] || fail "$f of the earlier compile left beside a failed one"
done
grep -q "Removed 2020_Milling.gcode" "$WORK/err" || fail "no warning: $(cat "$WORK/err")"
[ -f 2020_Z.txt ] || fail "the measured heights were removed"
echo "ok: probing set stays one set"
