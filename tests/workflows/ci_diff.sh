# The pull-request diff in CI: the step action.yml runs with `diff: true` (and the GitLab job
# of docs/src/version-control.md), scripts/ci-diff.sh, against a scratch repository with a
# base commit and a pull-request commit: the summary names every changed drawing and what it
# does to the part, each changed drawing gets a PNG, unchanged and deleted ones none; a
# revision git does not know exits 2.
source "$ROOT/tests/workflows/lib.bash"

mkdir bin && ln -s "$MILLPATH" bin/millpath
export PATH="$WORK/bin:$PATH"

slot() { # slot NAME Y END: a .mpath with one slot at height Y milled to x=END
  cat <<MP
path $1 {
  start (0, $2)  M10x3 O2 T3 I1,5 B-0,2
  end (30, $2)
  sweep (0, $2) -> (5, $2)
  mill (5, $2) -> ($3, $2)
  sweep ($3, $2) -> (30, $2)
}
MP
}

git init -q repo && cd repo
git config user.email t@example.com && git config user.name t
mkdir parts
slot 2001.1P 0 25 >parts/a.mpath
slot 2002.1P 20 25 >b.mpath
slot 2003.1P 40 25 >same.mpath
slot 2004.1P 60 25 >gone.mpath
"$MILLPATH" text2dxf b.mpath -o c.dxf
git add . && git commit -qm base
base=$(git rev-parse HEAD)

# the pull request: a slot shortened, a DXF's slot lengthened, one drawing deleted
slot 2001.1P 0 20 >parts/a.mpath
slot 2002.1P 20 28 >b.mpath
"$MILLPATH" text2dxf b.mpath -o c.dxf
git rm -q gone.mpath
git commit -qam "pull request"

expect_status 0 bash "$ROOT/scripts/ci-diff.sh" "$base" ../pictures
summary=$WORK/out
for f in parts/a.mpath b.mpath c.dxf gone.mpath; do
  grep -qF "### ${base:0:10}:$f → HEAD:$f" "$summary" || fail "the summary does not name $f"
done
grep -qF same.mpath "$summary" && fail "the summary names the unchanged same.mpath"
grep -qF "**48 mm**" "$summary" || fail "the summary lacks parts/a.mpath's new milling length"
grep -qF '`2004.1P`: removed' "$summary" || fail "the summary lacks gone.mpath's removed path"
for png in parts_a.mpath.png b.mpath.png c.dxf.png; do
  [ "$(head -c 8 "$WORK/pictures/$png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
    fail "$png is not a PNG"
done
[ "$(ls "$WORK/pictures" | wc -l)" -eq 3 ] || fail "pictures beyond the changed drawings: $(ls "$WORK/pictures")"

# nothing changed: a summary that says so, no picture
expect_status 0 bash "$ROOT/scripts/ci-diff.sh" HEAD ../none
grep -qF "No drawing changed." "$WORK/out" || fail "an empty pull request's summary: $(cat "$WORK/out")"
[ -z "$(ls "$WORK/none")" ] || fail "pictures for an empty pull request"

# a base git does not know: exit 2, said on stderr
expect_status 2 bash "$ROOT/scripts/ci-diff.sh" no-such-rev ../bad
[ -s "$WORK/err" ] || fail "no message for an unknown base"
