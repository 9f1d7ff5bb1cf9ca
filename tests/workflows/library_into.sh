# Issue 31: a library drawing of several paths, one path edited as text and written back
# with `text2dxf --into`. The paths the text lacks are named and nothing is written unless
# --delete-missing-paths says so; writing back an unchanged text changes no byte (git sees
# no change), here and on the shared sample drawings when ../shared is there.
source "$ROOT/tests/workflows/lib.bash"
cat >lib.mpath <<'MPATH'
path 8998.1P {
  start (0, 0)  M3 O2 T3 I1,5 B2,5
  end (60, 0)
  mill (0, 0) -> (60, 0)
}

path 8998.2P {
  start (0, 20)  M3 O2 T3 I1,5 B2,5
  end (40, 20)
  mill (0, 20) -> (40, 20)
}
MPATH
expect_status 0 "$MILLPATH" text2dxf lib.mpath -o lib.dxf
git init -q . && git add lib.dxf && git -c user.name=t -c user.email=t@t commit -qm library

# 1. the text of 8998.1P alone, edited, written into the library: refused, 8998.2P named
sed -n '1,5p' lib.mpath | sed 's/T3/T4/' >one.mpath
expect_status 1 "$MILLPATH" text2dxf one.mpath --into lib.dxf
grep -q 'lib.dxf holds paths that one.mpath does not define: 8998.2P' "$WORK/err" \
  || fail "the refusal does not name 8998.2P: $(cat "$WORK/err")"
grep -q -- '--delete-missing-paths' "$WORK/err" || fail "the refusal does not say how to delete"
git diff --quiet lib.dxf || fail "the refused --into changed the drawing"

# 2. the whole text, unchanged: no byte changes, as often as it is written back
expect_status 0 "$MILLPATH" text2dxf lib.mpath --into lib.dxf
"$MILLPATH" dxf2text lib.dxf >back.mpath
expect_status 0 "$MILLPATH" text2dxf back.mpath --into lib.dxf
git add lib.dxf
for _ in 1 2; do
  expect_status 0 "$MILLPATH" text2dxf back.mpath --into lib.dxf
  git diff --quiet lib.dxf || fail "an unchanged text changed the drawing: $(git diff --stat lib.dxf)"
done

# 3. 8998.2P deleted on purpose
expect_status 0 "$MILLPATH" text2dxf one.mpath --into lib.dxf --delete-missing-paths
"$MILLPATH" dxf2text lib.dxf >after.mpath
grep -q 'path 8998.1P' after.mpath && ! grep -q '8998.2P' after.mpath \
  || fail "--delete-missing-paths did not delete 8998.2P: $(cat after.mpath)"

# 4. the shared samples: the same text twice, the same bytes
if [ -d "$SHARED/samples" ]; then
  for f in "$SHARED"/samples/*.dxf; do
    cp "$f" s.dxf && chmod u+w s.dxf # the shared drawings are read-only
    "$MILLPATH" dxf2text s.dxf >s.mpath 2>/dev/null
    expect_status 0 "$MILLPATH" text2dxf s.mpath --into s.dxf
    cp s.dxf s.once
    expect_status 0 "$MILLPATH" text2dxf s.mpath --into s.dxf
    cmp s.dxf s.once || fail "$(basename "$f"): a second --into changed the drawing"
  done
fi
echo "ok: --into names the paths it would delete, and an unchanged text changes no byte"
