# A file the user made read-only (a proven program, the measured heights) is never replaced
# nor removed: every command that writes refuses, naming the file, in English and German.
# A compile's set of three stays the old set whole when one of them is read-only.
source "$ROOT/tests/workflows/lib.bash"
cp "$ROOT/examples/text/2020.mpath" "$ROOT/examples/text/2001.mpath" "$ROOT/examples/text/millpath.toml" .
set3=(2020_Probing.gcode 2020_Z.txt 2020_Clean.gcode)

# refused COMMAND...: exit 1, the file named with "read-only: not replaced"
refused() {
  local file=$1
  shift
  expect_status 1 "$@"
  grep -q "$file.*read-only: not replaced" "$WORK/err" || fail "$* did not name $file: $(cat "$WORK/err")"
}
writable() { [ -n "$(find "$1" -perm -u=w)" ]; }

# 1. the probing set: each one of the three read-only in turn, the drawing changed
expect_status 0 "$MILLPATH" compile 2020.mpath
md5sum "${set3[@]}" >old.md5
sed -i 's/B-0,2/B-0,3/' 2020.mpath
for f in "${set3[@]}"; do
  chmod a-w "$f"
  refused "$f" "$MILLPATH" compile 2020.mpath
  grep -q "left as they were" "$WORK/err" || fail "no word on the kept set: $(cat "$WORK/err")"
  md5sum -c --quiet old.md5 || fail "the set changed with $f read-only"
  writable "$f" && fail "$f is writable again"
  ls -A | grep -q '\.tmp$\|\.old$\|\.stage[12]$' && fail "temporaries left: $(ls -A)"
  # German
  expect_status 1 "$MILLPATH" compile --lang de 2020.mpath
  grep -q "$f kann nicht geschrieben werden: schreibgeschützt: nicht ersetzt" "$WORK/err" ||
    fail "German: $(cat "$WORK/err")"
  chmod u+w "$f"
done
# all writable again: the new set is written
expect_status 0 "$MILLPATH" compile 2020.mpath
md5sum -c --quiet old.md5 >/dev/null 2>&1 && fail "the new set was not written"

# 2. adjust-z: a read-only milling program is neither replaced nor removed as outdated
sed -i 's/#51=$/#51=3.1/; s/#52=$/#52=2.9/' 2020_Z.txt
expect_status 0 "$MILLPATH" adjust-z --max 1 2020_Clean.gcode
chmod a-w 2020_Milling.gcode
md5sum 2020_Milling.gcode >milling.md5
sed -i 's/#51=3.1$/#51=3.2/' 2020_Z.txt
refused 2020_Milling.gcode "$MILLPATH" adjust-z --max 1 2020_Clean.gcode
md5sum -c --quiet milling.md5 || fail "adjust-z replaced the read-only program"
# a failing compile does not remove it either: it says why it stays
sed -i 's/mill (0, 0) -> (60, 0)/mill (0, 0) -> (61, 0)/' 2020.mpath
expect_status 1 "$MILLPATH" compile 2020.mpath
grep -q "2020_Milling.gcode.*read-only: not removed" "$WORK/err" || fail "no word on the kept program: $(cat "$WORK/err")"
md5sum -c --quiet milling.md5 || fail "compile removed the read-only program"

# 3. fmt in place
printf 'path 2001.1P {\n  start (0,0) O2 T3 B-1\n  end (10, 0)\n  mill (0, 0) -> (10, 0)\n}\n' >2001.mpath
chmod a-w 2001.mpath
md5sum 2001.mpath >fmt.md5
refused 2001.mpath "$MILLPATH" fmt 2001.mpath
md5sum -c --quiet fmt.md5 || fail "fmt replaced the read-only file"
expect_status 1 "$MILLPATH" fmt --lang de 2001.mpath
grep -q "schreibgeschützt: nicht ersetzt" "$WORK/err" || fail "fmt German: $(cat "$WORK/err")"
chmod u+w 2001.mpath
expect_status 0 "$MILLPATH" fmt 2001.mpath

# 4. text2dxf -o and dxf2text -o
expect_status 0 "$MILLPATH" text2dxf 2001.mpath -o 2001.dxf
chmod a-w 2001.dxf
md5sum 2001.dxf >dxf.md5
sed -i 's/B-1/B-2/' 2001.mpath
refused 2001.dxf "$MILLPATH" text2dxf 2001.mpath -o 2001.dxf --force
md5sum -c --quiet dxf.md5 || fail "text2dxf replaced the read-only drawing"
chmod u+w 2001.dxf
expect_status 0 "$MILLPATH" dxf2text 2001.dxf -o back.mpath
chmod a-w back.mpath
refused back.mpath "$MILLPATH" dxf2text 2001.dxf -o back.mpath
echo "ok: read-only files are kept"
