# A height map said in the drawing: `K10+2` in the path start text (grid step 10 mm, margin
# 2 mm), the same token in .mpath and DXF. It survives fmt, text → DXF → text, and
# `text2dxf --into`; the .mpath and its DXF compile to the same probing set in linuxcnc; the
# option overrides it; the reference dialect reports K as PathDxf2GCode does.
source "$ROOT/tests/workflows/lib.bash"
cat > millpath.toml <<'EOF'
dialect = "linuxcnc"
feed = 300
sweep_speed = 1000
sweep_height = 10
probe_feed = 50
EOF
cat > 2024.mpath <<'EOF'
# An engraving on a board that is not flat: the part says its own height map.
path 2024.1P {
  start (0, 0)  M10x3 O2 T3 I1,5 B2,8 K10+2
  end (40, 0)
  mill (0, 0) -> (40, 0)
  mill (40, 0) -> (40, 20)
  mill (40, 20) -> (0, 20)
  sweep (0, 20) -> (40, 0)
}
EOF

# 1. the formatter keeps it (the file is already canonical)
expect_status 0 "$MILLPATH" fmt --check 2024.mpath

# 2. text → DXF → text: the same text; DXF → text → DXF → text stays the same
mkdir dxf && cp millpath.toml dxf/
expect_status 0 "$MILLPATH" text2dxf 2024.mpath -o dxf/2024.dxf
expect_status 0 "$MILLPATH" dxf2text dxf/2024.dxf -o back.mpath
grep -q ' K10+2$' back.mpath || fail "K lost on the way through DXF: $(cat back.mpath)"
expect_status 0 "$MILLPATH" text2dxf back.mpath -o again.dxf
expect_status 0 "$MILLPATH" dxf2text again.dxf -o again.mpath
cmp back.mpath again.mpath || fail "dxf2text → text2dxf → dxf2text is not stable"
# the DXF carries it as the start marker's text, as every other parameter
grep -q 'K10+2' dxf/2024.dxf || fail "no K in the DXF"

# 3. text2dxf --into an existing drawing keeps it
cp dxf/2024.dxf into.dxf
sed 's/ K10+2$/ K5/' 2024.mpath > edited.mpath
expect_status 0 "$MILLPATH" text2dxf edited.mpath --into into.dxf
expect_status 0 "$MILLPATH" dxf2text into.dxf -o into.mpath
grep -q ' K5$' into.mpath || fail "text2dxf --into lost K: $(cat into.mpath)"

# 4. the text and its DXF compile to the same grid (10 mm, 2 mm around the cuts)
expect_status 0 "$MILLPATH" compile 2024.mpath
(cd dxf && expect_status 0 "$MILLPATH" compile 2024.dxf)
grep -q '^(MILLPATH-HEIGHTMAP X0=-2.000 Y0=-2.000 X1=42.000 Y1=22.000 NX=6 NY=4 STEP=10.000)$' \
  2024_Probing.gcode || fail "not the drawing's grid: $(grep HEIGHTMAP 2024_Probing.gcode)"
grep -q '^(PROBEOPEN 2024_probes.txt)$' 2024_Probing.gcode || fail "no PROBEOPEN"
cmp 2024_Z.txt dxf/2024_Z.txt || fail "the DXF gives another grid than the text"
diff <(sed 1,3d 2024_Probing.gcode) <(sed 1,3d dxf/2024_Probing.gcode) ||
  fail "the DXF gives another probing program than the text"
[ "$(wc -l < 2024_Z.txt)" -eq 24 ] || fail "expected 6 × 4 grid points"

# 5. the option is this run's choice: over the drawing's step
expect_status 0 "$MILLPATH" compile --heightmap-step 20 2024.mpath
grep -q 'STEP=20.000)$' 2024_Probing.gcode || fail "--heightmap-step did not win over K"

# 6. the reference dialect: K is unsupported there, as PathDxf2GCode reports it, with a hint
expect_status 1 "$MILLPATH" compile --dialect reference 2024.mpath
grep -q "Unsupported K value" "$WORK/err" || fail "$(cat "$WORK/err")"
grep -q "K (a height map) needs the linuxcnc or grbl dialect" "$WORK/err" || fail "$(cat "$WORK/err")"
echo "ok: K10+2 survives fmt, DXF ↔ text and --into, and gives the same grid from both"
