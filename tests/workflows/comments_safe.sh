# A drawing whose file name has parentheses, "Halter (v2).dxf", compiles in every dialect:
# the name goes into the G-code comments safely (a warning says how it was written), the
# independent checker is clean, and LinuxCNC's own interpreter runs the linuxcnc program.
source "$ROOT/tests/workflows/lib.bash"

for dialect in reference linuxcnc grbl; do
  mkdir "$dialect"
  cp "$ROOT/examples/plate/1234.1P.dxf" "$dialect/Halter (v2).dxf"
  cp "$ROOT/examples/plate/millpath.toml" "$dialect/"
  (
    cd "$dialect"
    # the machinist compiles the renamed drawing
    expect_status 0 "$MILLPATH" compile --dialect "$dialect" "Halter (v2).dxf"
    grep -q "is written as 'Halter \[v2\].dxf'" "$WORK/err" ||
      fail "$dialect: no warning about the changed name: $(cat "$WORK/err")"
    program="Halter (v2)_Milling.gcode"
    [ -s "$program" ] || fail "$dialect: no program written"
    grep -qxF "(Halter [v2].dxf)" "$program" || fail "$dialect: file-name comment not made safe"
    # no comment holds a second '(' (LinuxCNC: nested comment)
    if grep -nE '\([^)]*\(' "$program"; then fail "$dialect: nested comment"; fi
    # check says what compile says
    expect_status 0 "$MILLPATH" check --dialect "$dialect" "Halter (v2).dxf"
    grep -q "Halter \[v2\].dxf" "$WORK/out" || fail "$dialect: check does not warn"
    # and the independent checker has nothing to say about it
    expect_status 0 "$MILLPATH" verify --dialect "$dialect" --top 3 --tool 2 "$program"
    if grep -q "comment" "$WORK/out"; then fail "$dialect: verify: $(cat "$WORK/out")"; fi
  )
done

# LinuxCNC's interpreter runs the linuxcnc program to its end (tests/rs274.sh installs it)
if ! command -v rs274 >/dev/null; then
  echo "skipped: rs274 (LinuxCNC, package linuxcnc-uspace) is not installed"
  exit 0
fi
cd linuxcnc
status=0
err=$(timeout 60 rs274 -g "Halter (v2)_Milling.gcode" </dev/null 2>&1 >/dev/null) || status=$?
why=$(printf '%s\n' "$err" | grep -v '^executing$' || true)
[ "$status" -eq 0 ] && [ -z "$why" ] || fail "rs274 rejects the linuxcnc program: $why"
echo "rs274 runs Halter (v2)_Milling.gcode"
