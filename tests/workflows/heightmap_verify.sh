# The whole height-map chain, as a machinist runs it on every example and shared drawing, for
# LinuxCNC and GRBL: compile with [heightmap] → probe (the log the controller writes, over a
# tilted board and over a bowl) → adjust-z --probe-log → verify is clean on the adjusted
# program (it checks it against the surface it records) → LinuxCNC's interpreter runs it.
# Then the mistake verify exists for: a program adjusted with the log of another board is
# found when verify is given the log of the board on the machine (verify --surface).
source "$ROOT/tests/workflows/lib.bash"


drawings=("$ROOT"/examples/plate/*.dxf "$ROOT"/examples/text/*.mpath)
if [ -d "$SHARED/conformance/fixtures" ]; then
  drawings+=("$SHARED"/conformance/fixtures/*.dxf "$SHARED"/samples/*.dxf)
else
  echo "../shared is absent: the examples only"
fi
# a board tilted 0.4 mm over the part's width and 0.3 mm over its height; a bowl 0.2 mm
# below the top in the middle, 0.3 mm above it in the corners (below every drawing's S)
boards=("t + 0.2 * (x - cx) / w - 0.15 * (y - cy) / h" "t + 0.25 * (((x - cx) / w) ** 2 + ((y - cy) / h) ** 2) - 0.2")
adjusted=0 skipped=0 rs274_runs=0
for dialect in linuxcnc grbl; do
  for drawing in "${drawings[@]}"; do
    dir="$WORK/$dialect/$(basename "$drawing")"
    mkdir -p "$dir" && cd "$dir"
    cp "$drawing" .
    # embedded parts live beside the examples
    case "$drawing" in */examples/text/*) cp "$ROOT"/examples/text/*.mpath . ;; esac
    cat >millpath.toml <<TOML
dialect = "$dialect"
feed = 300
sweep_speed = 1000
sweep_height = 10
probe_feed = 50
[heightmap]
step = 10
margin = 1
TOML
    name=$(basename "${drawing%.*}")
    # drawings with drawn probes, or that do not compile alone, are not height-map parts
    if ! "$MILLPATH" compile "$(basename "$drawing")" >/dev/null 2>&1 || [ ! -e "${name}_Probing.gcode" ]; then
      skipped=$((skipped + 1))
      continue
    fi
    for board in "${boards[@]}"; do
      write_probe_log "${name}_Probing.gcode" "$board" "$dialect" >probes.txt
      rm -f "${name}_Milling.gcode"
      expect_status 0 "$MILLPATH" adjust-z --max 3 --probe-log probes.txt "${name}_Clean.gcode"
      expect_status 0 "$MILLPATH" verify --dialect "$dialect" "${name}_Milling.gcode"
      adjusted=$((adjusted + 1))
      if [ "$dialect" = linuxcnc ] && command -v rs274 >/dev/null; then
        status=0
        timeout 60 rs274 -g "${name}_Milling.gcode" </dev/null >canon 2>rs274err || status=$?
        why=$(grep -v '^executing$' rs274err || true)
        [ "$status" -eq 0 ] && [ -z "$why" ] || fail "rs274 $dir/${name}_Milling.gcode: $status $why"
        grep -q PROGRAM_END canon || fail "rs274: $name did not reach M30"
        rs274_runs=$((rs274_runs + 1))
      fi
    done
  done
done
[ "$adjusted" -ge 8 ] || fail "only $adjusted programs adjusted"
echo "adjusted and verified $adjusted programs ($skipped drawings without a height-map set); rs274 ran $rs274_runs"

# A program adjusted to another board (a log from yesterday's blank, lower on the right: the
# program cuts deeper there) is found by verify given the log of the board on the machine.
# (A log of a higher board makes cuts shallower: no depth check can see that.)
cd "$WORK/linuxcnc/1234.1P.dxf"
write_probe_log 1234.1P_Probing.gcode "t - 0.004 * x" linuxcnc >yesterday.txt
write_probe_log 1234.1P_Probing.gcode "t" linuxcnc >today.txt
rm -f 1234.1P_Milling.gcode
expect_status 0 "$MILLPATH" adjust-z --max 3 --probe-log yesterday.txt 1234.1P_Clean.gcode
expect_status 0 "$MILLPATH" verify --dialect linuxcnc 1234.1P_Milling.gcode
expect_status 1 "$MILLPATH" verify --dialect linuxcnc --surface today.txt 1234.1P_Milling.gcode
grep -q 'below' "$WORK/err" "$WORK/out" || fail "verify --surface: $(cat "$WORK/err" "$WORK/out")"
expect_status 0 "$MILLPATH" verify --dialect linuxcnc --surface yesterday.txt 1234.1P_Milling.gcode
echo "verify --surface finds the program adjusted to another board"
