# verify on adjust-z's output, in every dialect: the program cuts at the measured surface,
# verify checks depths below it (clean), and still finds a cut made deeper by hand.
source "$ROOT/tests/workflows/lib.bash"
cp "$ROOT/examples/text/2020.mpath" "$ROOT/examples/text/millpath.toml" .
# 2020.1P: T3, I1,5, B-0,2, O2; probes #51 at (10, 5), #52 at (50, 5)
for dialect in reference linuxcnc grbl; do
  mkdir "$dialect" && cp 2020.mpath millpath.toml "$dialect/" && cd "$dialect"
  expect_status 0 "$MILLPATH" compile --dialect "$dialect" 2020.mpath
  # the machine measured the surface 0.3 higher at #51 and 0.2 lower at #52
  sed -i 's/#51=$/#51=3.3/; s/#52=$/#52=2.8/' 2020_Z.txt
  expect_status 0 "$MILLPATH" adjust-z --max 1 2020
  grep -q "(==-0.200+" 2020_Milling.gcode || fail "$dialect: no adjusted depth line"
  # the reference dialect has no stock comment: T, O and the depth are given
  expect_status 0 "$MILLPATH" verify --dialect "$dialect" --top 3 --tool 2 --bottom -0.2 2020_Milling.gcode
  grep -q "0 error(s), 0 warning(s)" "$WORK/err" || fail "$dialect: $(cat "$WORK/out" "$WORK/err")"
  if [ "$dialect" != reference ]; then
    expect_status 0 "$MILLPATH" verify --dialect "$dialect" 2020_Milling.gcode
    grep -q "0 error(s), 0 warning(s)" "$WORK/err" || fail "$dialect (stock comment): $(cat "$WORK/out")"
  fi
  # tampered: the last pass 0.5 deeper than the measured surface minus the depth (the
  # expression changed with it, so only the depth check can see it)
  sed 's/^\(G01 F300.000 X60.000 Y0.000\) Z[-0-9.]*(==-0.200+\(.*\)/\1 Z-0.491(==-0.700+\2/' \
    2020_Milling.gcode > deeper.gcode
  cmp -s 2020_Milling.gcode deeper.gcode && fail "$dialect: the tampering did not apply"
  expect_status 1 "$MILLPATH" verify --dialect "$dialect" --top 3 --tool 2 --bottom -0.2 deeper.gcode
  grep -q "below the deepest drawn depth -0.200" "$WORK/out" || fail "$dialect: $(cat "$WORK/out")"
  # tampered: only the Z changed, the expression kept
  sed 's/^\(G01 F300.000 X60.000 Y0.000\) Z[-0-9.]*(==-0.200+/\1 Z-0.491(==-0.200+/' \
    2020_Milling.gcode > changed.gcode
  expect_status 1 "$MILLPATH" verify --dialect "$dialect" --top 3 --tool 2 --bottom -0.2 changed.gcode
  grep -q "is not the value 0.009 of its probe expression" "$WORK/out" || fail "$dialect: $(cat "$WORK/out")"
  cd ..
done
echo "ok: verify clean on adjusted programs in every dialect, tampering found"
