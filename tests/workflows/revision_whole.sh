# A drawing whose subpath lives in another file, under git: `millpath diff REV -- FILE` and
# `REV..REV` read the subpath file and millpath.toml from the revision (not the work tree),
# and `git merge` with the driver checks the merged path with its subpath found beside it.
source "$ROOT/tests/workflows/lib.bash"

git init -q repo && cd repo
git config user.email t@example.com && git config user.name t
git config merge.millpath.name "millpath: drawings and MillPath texts"
git config merge.millpath.driver "millpath merge %O %A %B %P"
printf '*.dxf merge=millpath\n*.mpath merge=millpath\n' >.gitattributes
mkdir -p "$WORK/bin" && ln -sf "$MILLPATH" "$WORK/bin/millpath"
export PATH="$WORK/bin:$PATH"

cat >millpath.toml <<'TOML'
feed = 300
sweep_speed = 1000
sweep_height = 10
TOML
# the part: one slot and the subpath 9999.1P (in 9999.mpath) along a second line
cat >2001.mpath <<'MP'
path 2001.1P {
  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2
  end (10, 20)
  mill (0, 0) -> (20, 0)
  sweep (20, 0) -> (0, 20)
  sub (0, 20) -> (10, 20)  >9999.1P
}
MP
cat >9999.mpath <<'MP'
path 9999.1P {
  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2
  end (10, 0)
  mill (0, 0) -> (10, 0)
}
MP
expect_status 0 millpath check 2001.mpath
git add . && git commit -qm base
git branch base-version

# 1. only the subpath file and millpath.toml change: the part's text stays the same
sed -i 's/B-0,2/B-0,6/' 9999.mpath
sed -i 's/sweep_height = 10/sweep_height = 12/' millpath.toml
git commit -qam "deeper subpath, higher sweeps"
expect_status 1 millpath diff HEAD~1..HEAD -- 2001.mpath
grep -q 'lowest Z -0.2 → -0.6' "$WORK/out" || fail "HEAD~1..HEAD: the subpath's depth of HEAD~1 was not read from HEAD~1: $(cat "$WORK/out")"
grep -q '9999.mpath' "$WORK/out" || fail "HEAD~1..HEAD: the subpath's moves are not named: $(cat "$WORK/out")"
# the revision against the work tree (which is HEAD): the same change
expect_status 1 millpath diff HEAD~1 -- 2001.mpath
grep -q 'lowest Z -0.2 → -0.6' "$WORK/out" || fail "HEAD~1: $(cat "$WORK/out")"
expect_status 0 millpath diff HEAD -- 2001.mpath
# the work tree changes again; HEAD~1..HEAD still compares the two commits
sed -i 's/B-0,6/B-0,9/' 9999.mpath
expect_status 1 millpath diff HEAD~1..HEAD -- 2001.mpath
grep -q 'lowest Z -0.2 → -0.6' "$WORK/out" || fail "HEAD~1..HEAD read the work tree's subpath: $(cat "$WORK/out")"
expect_status 1 millpath diff HEAD -- 2001.mpath
grep -q 'lowest Z -0.6 → -0.9' "$WORK/out" || fail "HEAD vs work tree: $(cat "$WORK/out")"
# millpath.toml alone (sweep height) reaches the G-code
git checkout -q 9999.mpath
sed -i 's/sweep_height = 12/sweep_height = 15/' millpath.toml
expect_status 1 millpath diff HEAD -- 2001.mpath
grep -q 'G-code changed' "$WORK/out" || fail "a changed millpath.toml is no change: $(cat "$WORK/out")"
git checkout -q millpath.toml

# 2. the merge driver compiles the merged path with its subpath file beside it
git checkout -q -b theirs base-version
sed -i 's/mill (0, 0) -> (20, 0)/mill (0, 0) -> (20, 0)  B-0,4/' 2001.mpath
git commit -qam "theirs: the slot deeper"
git checkout -q -b ours base-version
sed -i '/start (0, 0)/s/I1,5/I1/' 2001.mpath
git commit -qam "ours: passes of 1 mm"
git merge -q --no-edit theirs >"$WORK/merge.out" 2>&1 || fail "edits to a path with a subpath did not merge: $(cat "$WORK/merge.out")"
grep -q 'B-0,4' 2001.mpath && grep -q 'I1 ' 2001.mpath || fail "the merge lost an edit: $(cat 2001.mpath)"
expect_status 0 millpath check 2001.mpath

