# `fmt` (and every command that rewrites a user's file in place) keeps what the user wrote:
# every comment, also the one after a path's closing brace; a file with errors stays byte for
# byte; a .mpath or a drawing reached through a symbolic link is rewritten where it lives and
# the link stays a link; a read-only file is refused; git's merge driver keeps the comments.
source "$ROOT/tests/workflows/lib.bash"
cat >2001.mpath <<'MP'
# a head comment
path 2001.1P {   # after the brace
  # inside
  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2   # the start
  end (30, 0)
  sweep (0, 0) -> (5, 0)
  mill (5, 0) -> (25, 0)  # the slot
  sweep (25, 0) -> (30, 0)
}   # after the closing brace: 2001.1P is the slot of the lid
# a tail comment
MP
cp 2001.mpath original.mpath
expect_status 0 "$MILLPATH" fmt 2001.mpath
for c in "# a head comment" "# after the brace" "# inside" "# the start" "# the slot" \
  "# after the closing brace: 2001.1P is the slot of the lid" "# a tail comment"; do
  grep -qF -- "$c" 2001.mpath || fail "fmt dropped '$c': $(cat 2001.mpath)"
done
grep -qx '}  # after the closing brace: 2001.1P is the slot of the lid' 2001.mpath ||
  fail "closing line: $(cat 2001.mpath)"
# canonical now, and formatting again changes nothing
expect_status 0 "$MILLPATH" fmt --check 2001.mpath
cp 2001.mpath once.mpath
expect_status 0 "$MILLPATH" fmt 2001.mpath
cmp -s 2001.mpath once.mpath || fail "fmt is not idempotent"
# the same program as before formatting
expect_status 0 "$MILLPATH" check -q 2001.mpath original.mpath

# a file with a syntax error is not rewritten
printf 'path 2002.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  mill (0,0) -> (5\n  # keep me\n' >2002.mpath
cp 2002.mpath 2002.before
expect_status 1 "$MILLPATH" fmt 2002.mpath
cmp -s 2002.mpath 2002.before || fail "fmt changed a file with errors"

# through a symbolic link: the linked file is formatted, the link stays
mkdir lib work
cp original.mpath lib/2003.mpath
sed -i 's/2001/2003/g' lib/2003.mpath
ln -s ../lib/2003.mpath work/2003.mpath
expect_status 0 "$MILLPATH" fmt work
[ -L work/2003.mpath ] || fail "fmt replaced the link work/2003.mpath by a file"
expect_status 0 "$MILLPATH" fmt --check lib/2003.mpath

# text2dxf --into a drawing linked from a library: the library's drawing gets the change
expect_status 0 "$MILLPATH" text2dxf lib/2003.mpath -o lib/2003.dxf
ln -s ../lib/2003.dxf work/2003.dxf
sed -i 's/B-0,2/B-0,5/' lib/2003.mpath
expect_status 0 "$MILLPATH" text2dxf lib/2003.mpath --into work/2003.dxf
[ -L work/2003.dxf ] || fail "text2dxf --into replaced the link work/2003.dxf by a file"
expect_status 0 "$MILLPATH" dxf2text lib/2003.dxf
grep -q "B-0,5" "$WORK/out" || fail "the library drawing did not get the change: $(cat "$WORK/out")"

# a read-only file is refused, unchanged
cp original.mpath ro.mpath
chmod a-w ro.mpath
expect_status 1 "$MILLPATH" fmt ro.mpath
grep -q "read-only: not replaced" "$WORK/err" || fail "read-only: $(cat "$WORK/err")"
cmp -s ro.mpath original.mpath || fail "a read-only file was changed"
[ ! -w ro.mpath ] || [ "$(id -u)" = 0 ] || fail "ro.mpath became writable"

# git's merge driver (docs/src/version-control.md): the comment after `}` survives a merge
# of edits elsewhere, and the same comment changed both ways is a conflict
mkdir repo && cd repo
git init -q -b main && git config user.email t@t && git config user.name t
git config merge.millpath.driver "$MILLPATH merge %O %A %B %P"
printf '*.mpath merge=millpath\n' >.gitattributes
cp ../original.mpath 2001.mpath
git add -A && git commit -qm base
git checkout -qb theirs
sed -i 's/# the slot/# the slot, 0.2 deep/' 2001.mpath && git commit -qam theirs
git checkout -q main
sed -i 's/B-0,2   # the start/B-0,3   # the start/' 2001.mpath && git commit -qam ours
git merge -q --no-edit theirs >/dev/null 2>&1 || fail "the merge failed: $(cat 2001.mpath)"
grep -q "# the slot, 0.2 deep" 2001.mpath && grep -q "B-0,3" 2001.mpath || fail "merge: $(cat 2001.mpath)"
grep -qx '}  # after the closing brace: 2001.1P is the slot of the lid' 2001.mpath ||
  fail "the merge dropped the comment after }: $(cat 2001.mpath)"
git checkout -qb theirs2
sed -i 's/^}.*/}  # theirs/' 2001.mpath && git commit -qam theirs2
git checkout -q main
sed -i 's/^}.*/}  # ours/' 2001.mpath && git commit -qam ours2
if git merge -q --no-edit theirs2 >/dev/null 2>&1; then fail "no conflict: $(cat 2001.mpath)"; fi
grep -qx '}  # ours' 2001.mpath && grep -qx '}  # theirs' 2001.mpath || fail "conflict: $(cat 2001.mpath)"
git merge --abort
cd ..
echo "ok: fmt keeps comments, links and read-only files"
