# Text as Windows writes it: a .mpath saved with a byte-order mark (Notepad), written by
# PowerShell 5's `>` (UTF-16 LE), or checked out with core.autocrlf (CRLF). Each goes
# through check, compile (the same G-code as the plain file), fmt --check and fmt (its line
# ends kept), text2dxf and dxf2text; a DXF with a BOM compiles; the pre-commit hooks pass on
# a CRLF checkout.
source "$ROOT/tests/workflows/lib.bash"

printf 'feed = 300\nsweep_speed = 1000\nsweep_height = 10\n' > millpath.toml
mkdir plain
cat > plain/3000.mpath <<'EOF'
path 3000.1P {
  start (0, 0)  M3 O2 T3 I1,5 B-0,2
  end (20, 10)
  mill (0, 0) -> (20, 0)
  mill arc (20, 5) r5 from 270 to 90  # Bogen über die Kante
}
EOF
# the plain file is canonical and compiles: the G-code every other form must give
expect_status 0 "$MILLPATH" fmt --check plain/3000.mpath
expect_status 0 "$MILLPATH" compile plain/3000.mpath
[ -s plain/3000_Milling.gcode ] || fail "no G-code from the plain file"

mkdir bom utf16 crlf
printf '\xef\xbb\xbf' > bom/3000.mpath && cat plain/3000.mpath >> bom/3000.mpath
"$PY" -c 'import sys; open(sys.argv[2], "wb").write(open(sys.argv[1], encoding="utf-8").read().encode("utf-16"))' \
  plain/3000.mpath utf16/3000.mpath
sed 's/$/\r/' plain/3000.mpath > crlf/3000.mpath
head -c 2 utf16/3000.mpath | od -An -tx1 | grep -q 'ff fe' || fail "utf16/3000.mpath has no UTF-16 LE mark"
grep -q $'\r$' crlf/3000.mpath || fail "crlf/3000.mpath has no CRLF"

for form in bom utf16 crlf; do
  f=$form/3000.mpath
  expect_status 0 "$MILLPATH" check "$f"
  grep -q '0 error(s), 0 warning(s)' "$WORK/out" "$WORK/err" || fail "$form: check found problems"
  expect_status 0 "$MILLPATH" compile "$f"
  cmp -s plain/3000_Milling.gcode "$form/3000_Milling.gcode" || fail "$form: G-code differs from the plain file's"
  # text2dxf reads it as check does; the drawing compiles to the same G-code
  expect_status 0 "$MILLPATH" text2dxf "$f" -o "$form/drawing.dxf"
  expect_status 0 "$MILLPATH" dxf2text "$form/drawing.dxf" -o "$form/back.mpath"
  expect_status 0 "$MILLPATH" text2dxf plain/3000.mpath -o "$form/plain.dxf"
  cmp -s "$form/drawing.dxf" "$form/plain.dxf" || fail "$form: text2dxf wrote another drawing than from the plain file"
done

# fmt: a BOM and CRLF are the file's own and stay (the file is canonical as it is) ...
expect_status 0 "$MILLPATH" fmt --check bom/3000.mpath crlf/3000.mpath
cp crlf/3000.mpath crlf/before.mpath
expect_status 0 "$MILLPATH" fmt bom/3000.mpath crlf/3000.mpath
cmp -s crlf/before.mpath crlf/3000.mpath || fail "fmt changed a canonical CRLF file"
head -c 3 bom/3000.mpath | od -An -tx1 | grep -q 'ef bb bf' || fail "fmt dropped the BOM"
# ... an untidy CRLF file is formatted and stays CRLF ...
sed 's/^  mill (0, 0)/  mill   (0,0)/; s/$/\r/' plain/3000.mpath > crlf/untidy.mpath
expect_status 1 "$MILLPATH" fmt --check crlf/untidy.mpath
grep -q 'untidy.mpath: not formatted' "$WORK/out" || fail "fmt --check did not name the untidy file"
expect_status 0 "$MILLPATH" fmt crlf/untidy.mpath
cmp -s crlf/untidy.mpath crlf/before.mpath || fail "fmt did not give the canonical CRLF file"
# ... mixed line ends are named as the only difference ...
{ head -n 2 crlf/3000.mpath; tail -n +3 plain/3000.mpath; } > crlf/mixed.mpath
expect_status 1 "$MILLPATH" fmt --check crlf/mixed.mpath
grep -q 'only line endings differ (mixed: 2 CRLF, 4 LF; fmt writes LF)' "$WORK/out" || fail "mixed line ends not named: $(cat "$WORK/out")"
expect_status 0 "$MILLPATH" fmt crlf/mixed.mpath
cmp -s crlf/mixed.mpath plain/3000.mpath || fail "fmt did not make the mixed file LF"
# ... and UTF-16 is written as UTF-8, with a word
expect_status 1 "$MILLPATH" fmt --check utf16/3000.mpath
grep -q 'UTF-16 LE: fmt writes it as UTF-8' "$WORK/out" || fail "fmt --check did not name UTF-16"
expect_status 0 "$MILLPATH" fmt utf16/3000.mpath
grep -q 'converted from UTF-16 LE to UTF-8' "$WORK/out" || fail "fmt did not say it converted"
cmp -s utf16/3000.mpath plain/3000.mpath || fail "fmt did not write the UTF-16 file as the plain UTF-8 one"

# a syntax error in a BOM file: located as in the plain file, one format, German wholly German
printf '\xef\xbb\xbfpath 3000.2P {\n  mil (0, 0) -> (20, 0)\n  mill (12,5, 0) -> (1, 1)\n}\n' > bom/typo.mpath
expect_status 1 "$MILLPATH" check bom/typo.mpath
cat "$WORK/out" "$WORK/err" > report
grep -q '^error\[MP[0-9]*\]: `mil` is not an element kind: did you mean `mill`?$' report || fail "no did-you-mean: $(cat report)"
grep -q -- '--> bom/typo.mpath:2:3$' report || fail "typo not at 2:3"
grep -q 'write `12.5`, not `12,5`' report || fail "no decimal-point hint"
grep -q -- '--> bom/typo.mpath:3:9$' report || fail "decimal comma not at 3:9"
if grep -q '^\[MP' report; then fail "a [MPnnn] error: heading is left"; fi
expect_status 1 "$MILLPATH" check --lang de bom/typo.mpath
cat "$WORK/out" "$WORK/err" > report
grep -q '^Fehler\[MP[0-9]*\]: `mil` ist keine Elementart: `mill` gemeint?$' report || fail "German did-you-mean: $(cat report)"
if grep -q 'expected\|found' report; then fail "English words in the German report"; fi

# a DXF saved with a BOM reads as the plain drawing; a UTF-16 one is refused by name
"$MILLPATH" text2dxf plain/3000.mpath -o plain/3000.dxf >/dev/null
mkdir dxfbom && printf '\xef\xbb\xbf' > dxfbom/3000.dxf && cat plain/3000.dxf >> dxfbom/3000.dxf
expect_status 0 "$MILLPATH" compile plain/3000.dxf
expect_status 0 "$MILLPATH" compile dxfbom/3000.dxf
cmp -s plain/3000_Milling.gcode dxfbom/3000_Milling.gcode || fail "DXF with BOM: other G-code"
expect_status 0 "$MILLPATH" dxf2text dxfbom/3000.dxf -o dxfbom/back.mpath
expect_status 0 "$MILLPATH" dxf2text plain/3000.dxf -o plain/back.mpath
cmp -s dxfbom/back.mpath plain/back.mpath || fail "DXF with BOM: other text"
"$PY" -c 'import sys; open(sys.argv[2], "wb").write(open(sys.argv[1], encoding="ascii").read().encode("utf-16"))' \
  plain/3000.dxf dxfbom/u16.dxf
expect_status 1 "$MILLPATH" check dxfbom/u16.dxf
cat "$WORK/out" "$WORK/err" | grep -q 'UTF-16 LE' || fail "UTF-16 DXF not named"

# the pre-commit hooks on a checkout with core.autocrlf: the files are CRLF and pass
if git --version >/dev/null 2>&1 && "$PY" -m pre_commit --version >/dev/null 2>&1; then
  PC=("$PY" -m pre_commit)
else
  PC=()
  python3 -m venv "$WORK/pcvenv" >/dev/null 2>&1 && "$WORK/pcvenv/bin/pip" install -q pre-commit >/dev/null 2>&1 \
    && PC=("$WORK/pcvenv/bin/pre-commit")
fi
if [ ${#PC[@]} -eq 0 ]; then
  echo "skipped: the pre-commit hook part (no pre-commit, and pip could not install it)"
  exit 0
fi
export PRE_COMMIT_HOME="$WORK/pc-cache"
mkdir origin && cp plain/3000.mpath millpath.toml origin/
(
  cd origin && git init -q . && git config user.email ci@example.com && git config user.name ci
  cat > .pre-commit-config.yaml <<YAML
repos:
  - repo: local
    hooks:
      - id: millpath-check
        name: millpath check
        entry: $MILLPATH check
        language: system
        files: '\.(mpath|dxf|DXF)$'
      - id: millpath-fmt
        name: millpath fmt
        entry: $MILLPATH fmt --check
        language: system
        files: '\.mpath$'
YAML
  git add -A && git commit -qm init
)
git -c core.autocrlf=true clone -q origin checkout
cd checkout
git config core.autocrlf true
grep -q $'\r$' 3000.mpath || fail "the autocrlf checkout is not CRLF"
expect_status 0 "${PC[@]}" run --all-files
sed -i 's/(20, 0)\r$/(20,0)\r/' 3000.mpath   # an untidy edit, CRLF as the editor keeps it
expect_status 1 "${PC[@]}" run millpath-fmt --all-files
"$MILLPATH" fmt 3000.mpath
grep -q $'\r$' 3000.mpath || fail "fmt made the CRLF checkout LF"
expect_status 0 "${PC[@]}" run --all-files
echo "encodings: BOM, UTF-16 LE, CRLF and a BOM DXF read as the plain files; hooks pass on autocrlf"
