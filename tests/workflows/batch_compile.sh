# A folder of drawings compiled at once, one of them broken: every good drawing is written,
# the summary names the broken one, and the exit status says that something failed.
source "$ROOT/tests/workflows/lib.bash"

# the shop's folder: the plate and the text examples (a part, a project embedding it, a
# probed part), each with its millpath.toml, and one drawing with a typo in its feed
mkdir -p shop/plate shop/text
cp "$ROOT"/examples/plate/* shop/plate/
cp "$ROOT"/examples/text/* shop/text/
sed 's/2001\.1P/2002.1P/; s/ O2 / O2 F0,0001 /' shop/text/2001.mpath >shop/text/2002.mpath
grep -q 'F0,0001' shop/text/2002.mpath || fail "the broken drawing was not made"

# the whole folder, as `millpath compile .` in the shop
cd shop
expect_status 1 "$MILLPATH" compile .
cd ..
for f in plate/1234.1P_Milling.gcode text/2001_Milling.gcode text/2010_Milling.gcode \
  text/2020_Probing.gcode text/2020_Z.txt text/2020_Clean.gcode; do
  [ -s "shop/$f" ] || fail "good drawing not written: $f"
done
ls shop/text/2002* | grep -q gcode && fail "the broken drawing was written"
summary=$(tail -n 1 "$WORK/err")
case "$summary" in
  "compiled 4 of 5 drawings; not written: ./text/2002.mpath") ;;
  *) fail "summary: $summary" ;;
esac
grep -q 'error.*F 0.0001 mm/min' "$WORK/err" || fail "the broken drawing's error is not shown"

# in German as well
cd shop
expect_status 1 "$MILLPATH" compile --lang de .
cd ..
tail -n 1 "$WORK/err" | grep -qx '4 von 5 Zeichnungen übersetzt; nicht geschrieben: ./text/2002.mpath' ||
  fail "German summary: $(tail -n 1 "$WORK/err")"

# fixed, the folder compiles clean: exit 0, every drawing written
sed -i 's/ F0,0001//' shop/text/2002.mpath
cd shop
expect_status 0 "$MILLPATH" compile .
cd ..
tail -n 1 "$WORK/err" | grep -qx 'compiled 5 of 5 drawings' || fail "summary: $(tail -n 1 "$WORK/err")"
[ -s shop/text/2002_Milling.gcode ] || fail "the fixed drawing was not written"

# the reference's command line keeps the reference's rule: after the first error nothing
# more is written (reference-input.md §7.5)
need_shared
mkdir ref && cp "$SHARED"/conformance/fixtures/8999.0[1-4]P.dxf ref/
cd ref
printf '0\n' >8999.01P.dxf   # broken, and first
expect_status 1 "$MILLPATH" pathdxf2gcode /f150 /v500 /s15 8999.01P.dxf 8999.02P.dxf
ls | grep -q gcode && fail "pathdxf2gcode wrote after an error"
echo "ok: batch compile writes the good drawings and names the bad one"
