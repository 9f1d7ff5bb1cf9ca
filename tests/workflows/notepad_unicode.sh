# The files around a compile saved by Notepad as "Unicode" (UTF-16 LE with a byte-order
# mark, CRLF line ends): the measured _Z.txt, a probe log, _Clean.gcode, millpath.toml, a
# program given to verify. Each reads as the same text as its UTF-8 original; a UTF-16 file
# without a mark is refused naming the file and what to do.
source "$ROOT/tests/workflows/lib.bash"
cp "$ROOT/examples/text/2020.mpath" "$ROOT/examples/text/millpath.toml" .
# notepad FILE: FILE as Notepad's "Unicode" (UTF-16 LE with a mark, CRLF)
notepad() {
  python3 -c 'import sys; p = sys.argv[1]; t = open(p, encoding="utf-8").read().replace("\r\n", "\n").replace("\n", "\r\n"); open(p, "wb").write(t.encode("utf-16"))' "$1"
  head -c 2 "$1" | od -An -tx1 | grep -q 'ff fe' || fail "$1 is not UTF-16 LE with a mark"
}

# 1. compile, fill in _Z.txt, adjust-z: the reference result from UTF-8 files
expect_status 0 "$MILLPATH" compile 2020.mpath
sed -i 's/#51=$/#51=3,1/; s/#52=$/#52=2,9/' 2020_Z.txt
expect_status 0 "$MILLPATH" adjust-z --max 0.5 2020_Clean.gcode
mv 2020_Milling.gcode utf8_Milling.gcode

# 2. _Z.txt saved as "Unicode": the same program
notepad 2020_Z.txt
expect_status 0 "$MILLPATH" adjust-z --max 0.5 2020_Clean.gcode
cmp 2020_Milling.gcode utf8_Milling.gcode || fail "a UTF-16 _Z.txt gave another program"
# German too, no word of UTF-8
expect_status 0 "$MILLPATH" adjust-z --lang de --max 0.5 2020_Clean.gcode

# 3. _Clean.gcode opened and saved in Notepad as well
notepad 2020_Clean.gcode
expect_status 0 "$MILLPATH" adjust-z --max 0.5 2020_Clean.gcode
cmp 2020_Milling.gcode utf8_Milling.gcode || fail "a UTF-16 _Clean.gcode gave another program"

# 4. verify of a program saved as "Unicode"
cp utf8_Milling.gcode check_Milling.gcode
notepad check_Milling.gcode
expect_status 0 "$MILLPATH" verify --top 3 --tool 2 --bottom -0.5 utf8_Milling.gcode
cp "$WORK/err" utf8.verify
# the moves are read and found right; the one error is the mark, which LinuxCNC refuses
expect_status 1 "$MILLPATH" verify --top 3 --tool 2 --bottom -0.5 check_Milling.gcode
grep -q "check_Milling.gcode: .* 1 error(s), 0 warning(s)" "$WORK/out" "$WORK/err" || fail "verify: $(cat "$WORK/out" "$WORK/err")"
grep -q "check_Milling.gcode:1: error: a byte-order mark" "$WORK/out" "$WORK/err" || fail "verify: $(cat "$WORK/out")"
sed 's/check_Milling/utf8_Milling/' "$WORK/err" | grep -v 'byte-order mark\|^ *|' | sed 's/1 error(s)/0 error(s)/' >utf16.verify
diff utf16.verify utf8.verify || fail "the UTF-16 program was read otherwise"

# 5. millpath.toml saved as "Unicode": the same settings (feed 300 in the program)
notepad millpath.toml
expect_status 0 "$MILLPATH" compile 2020.mpath
grep -q "F300" 2020_Clean.gcode || fail "the settings of a UTF-16 millpath.toml were not read"
expect_status 0 "$MILLPATH" check 2020.mpath

# 6. a probe log saved as "Unicode" (x y z lines of the two probes)
sed -i 's/#51=$/#51=3.1/; s/#52=$/#52=2.9/' 2020_Z.txt
expect_status 0 "$MILLPATH" adjust-z --max 0.5 2020_Clean.gcode
mv 2020_Milling.gcode typed_Milling.gcode
python3 - <<'PY'
import re
x = y = 0.0
out = []
for l in open("2020_Probing.gcode"):
    for k, v in re.findall(r"([XY])(-?[0-9.]+)", l):
        if k == "X": x = float(v)
        else: y = float(v)
    if l.startswith("G38"):
        out.append(f"{x:.3f} {y:.3f} {3.1 if len(out) == 0 else 2.9:.3f}")
open("probes.txt", "w").write("\n".join(out) + "\n")
PY
[ "$(wc -l <probes.txt)" = 2 ] || fail "no probe log: $(cat probes.txt)"
notepad probes.txt
expect_status 0 "$MILLPATH" adjust-z --probe-log probes.txt --max 0.5 2020_Clean.gcode
cmp 2020_Milling.gcode typed_Milling.gcode || fail "a UTF-16 probe log gave another program"

# 7. UTF-16 without a mark: refused, naming the file and what to do (no "valid UTF-8")
python3 -c 'import sys; t = open("probes.txt", encoding="utf-16").read(); open("nomark.txt", "wb").write(t.encode("utf-16-le"))'
expect_status 1 "$MILLPATH" adjust-z --probe-log nomark.txt --max 0.5 2020_Clean.gcode
grep -q "nomark.txt.*no byte-order mark.*save it as UTF-8" "$WORK/err" || fail "no reason: $(cat "$WORK/err")"
grep -qi "valid UTF-8" "$WORK/err" && fail "still the reader's words: $(cat "$WORK/err")"
expect_status 1 "$MILLPATH" adjust-z --lang de --probe-log nomark.txt --max 0.5 2020_Clean.gcode
grep -q "als UTF-8 speichern" "$WORK/err" || fail "German: $(cat "$WORK/err")"
echo "ok: files saved by Notepad as Unicode are read"
