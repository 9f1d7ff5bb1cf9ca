# git's merge driver, configured as docs/src/version-control.md says: two people edit one
# drawing (or one .mpath) on two branches and `git merge` merges them with `millpath merge`.
# Edits in different paths merge to the G-code of both edits; the same element edited both
# ways is a conflict (our drawing unchanged, the markers beside it, git reports it); a CAD
# re-save on one side merges with an edit on the other; content outside the paths changed on
# their side is a conflict that names it; hostile inputs exit 2 and leave ours alone.
source "$ROOT/tests/workflows/lib.bash"

mkdir bin && ln -s "$MILLPATH" bin/millpath
export PATH="$WORK/bin:$PATH"
machine=(--feed 300 --sweep-speed 1000 --sweep-height 10)

# the G-code of path $2 of drawing $1 (a drawing of several paths compiles one at a time)
gcode_of() {
  rm -rf "$WORK/g" && mkdir "$WORK/g" && cp "$1" "$WORK/g/part.dxf"
  local n=${2%%.*} k=${2#*.}
  "$MILLPATH" compile "${machine[@]}" --path-pattern "($n)[.](${k%P})(P)" "$WORK/g/part.dxf" >/dev/null 2>&1 ||
    fail "$1: path $2 does not compile"
  cat "$WORK/g/part_Milling.gcode"
}

# the drawing: two slots (paths 2001.1P and 2002.1P) and a frame on a layer of its own
cat >part.mpath <<'MP'
path 2001.1P {
  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2
  end (30, 0)
  sweep (0, 0) -> (5, 0)
  mill (5, 0) -> (25, 0)
  sweep (25, 0) -> (30, 0)
}

path 2002.1P {
  start (0, 20)  M10x3 O2 T3 I1,5 B-0,2
  end (30, 20)
  sweep (0, 20) -> (5, 20)
  mill (5, 20) -> (25, 20)
  sweep (25, 20) -> (30, 20)
}
MP
"$MILLPATH" text2dxf part.mpath -o plain.dxf
"$PY" - plain.dxf part.dxf <<'PY'
import sys, ezdxf
doc = ezdxf.readfile(sys.argv[1])
doc.layers.add("FRAME")
doc.modelspace().add_lwpolyline([(-5, -5), (35, -5), (35, 25), (-5, 25)], close=True, dxfattribs={"layer": "FRAME"})
doc.saveas(sys.argv[2])
PY
rm part.mpath plain.dxf

git init -q repo && cd repo
git config user.email t@example.com && git config user.name t
# the set-up the manual gives
git config merge.millpath.name "millpath: drawings and MillPath texts"
git config merge.millpath.driver "millpath merge %O %A %B %P"
printf '*.dxf merge=millpath\n*.mpath merge=millpath\n' >.gitattributes
cp ../part.dxf part.dxf
git add . && git commit -qm base
git branch base-version

# edit path $3 of drawing $1 with sed expression $2, through the text
edit() {
  "$MILLPATH" dxf2text "$1" >"$WORK/t.mpath"
  sed -i "$2" "$WORK/t.mpath"
  "$MILLPATH" text2dxf "$WORK/t.mpath" --into "$1"
}

# 1. edits in different paths of one drawing merge
git checkout -q -b theirs
edit part.dxf '/path 2002.1P/,/}/s/mill (5, 20) -> (25, 20)/mill (5, 20) -> (25, 20)  B-0,3/'
git commit -qam "theirs: 2002.1P B-0,3"
git checkout -q -b ours base-version
edit part.dxf '/path 2001.1P/,/}/s/B-0,2/B-0,4/'
git commit -qam "ours: 2001.1P B-0,4"
git merge -q --no-edit theirs >../merge.out 2>&1 || { cat ../merge.out; fail "edits in different paths did not merge"; }
[ ! -e part.merge.mpath ] || fail "a clean merge left part.merge.mpath"
# the merge wrote their edit into our drawing and left the rest byte for byte: the diff
# from ours is their one element (its line and text), not a rewrite of both paths
merged_lines=$(git diff HEAD^1 HEAD -- part.dxf | grep -c '^[-+][^-+]' || true)
echo "the merge changed $merged_lines lines of our drawing"
[ "$merged_lines" -le 40 ] || fail "the merge rewrote our drawing: $merged_lines changed lines"
ents() { "$PY" -c "import ezdxf,sys; [print(e.dxf.layer, e.dxftype(), e.dxf.handle) for e in ezdxf.readfile(sys.argv[1]).modelspace() if not e.dxf.layer.startswith('2002_1P')]" "$1" | LC_ALL=C sort; }
git show HEAD^1:part.dxf >../ours.dxf
diff <(ents ../ours.dxf) <(ents part.dxf) || fail "the merge changed entities outside their path"
# both edits applied by hand to the base drawing
git show base-version:part.dxf >../byhand.dxf
edit ../byhand.dxf '/path 2001.1P/,/}/s/B-0,2/B-0,4/; /path 2002.1P/,/}/s/mill (5, 20) -> (25, 20)/mill (5, 20) -> (25, 20)  B-0,3/'
for p in 2001.1P 2002.1P; do
  gcode_of part.dxf $p >../merged.gcode
  gcode_of ../byhand.dxf $p >../byhand.gcode
  cmp -s ../merged.gcode ../byhand.gcode || fail "path $p: the merge compiles differently from both edits by hand"
done
gcode_of part.dxf 2001.1P | grep -q 'Z-0.4' || fail "our edit (B-0,4) is not in the merged G-code"
git show base-version:part.dxf >../base.dxf
gcode_of part.dxf 2002.1P >../merged.gcode
gcode_of ../base.dxf 2002.1P >../base.gcode
cmp -s ../merged.gcode ../base.gcode && fail "their edit (B-0,3) is not in the merged G-code"
# the frame (not a path) is kept
"$MILLPATH" dxf2text part.dxf >/dev/null
"$PY" -c "import ezdxf,sys; sys.exit(0 if len(ezdxf.readfile('part.dxf').modelspace().query('*[layer==\"FRAME\"]')) == 1 else 1)" ||
  fail "the merge lost the FRAME layer's polyline"

# 2. the same element edited both ways: a conflict; our drawing stays; git reports it
git checkout -q -b ours2 base-version
edit part.dxf 's/mill (5, 0) -> (25, 0)/mill (5, 0) -> (25, 0)  B-0,1/'
git commit -qam "ours: B-0,1"
cp part.dxf ../ours2.dxf
git checkout -q -b theirs2 base-version
edit part.dxf 's/mill (5, 0) -> (25, 0)/mill (5, 0) -> (25, 0)  B-0,3/'
git commit -qam "theirs: B-0,3"
git checkout -q ours2
if git merge -q --no-edit theirs2 >../merge.out 2>&1; then fail "conflicting edits merged"; fi
grep -q 'CONFLICT' ../merge.out || fail "git does not report the conflict: $(cat ../merge.out)"
grep -q 'MP209' ../merge.out || fail "millpath merge did not say why: $(cat ../merge.out)"
git diff --name-only --diff-filter=U | grep -qx part.dxf || fail "git does not list part.dxf as unmerged"
cmp -s part.dxf ../ours2.dxf || fail "the conflict changed our drawing"
grep -q '^<<<<<<< ours' part.merge.mpath || fail "no conflict markers in part.merge.mpath"
grep -q '^  mill (5, 0) -> (25, 0)  B-0,1$' part.merge.mpath || fail "our side missing in the markers"
grep -q '^  mill (5, 0) -> (25, 0)  B-0,3$' part.merge.mpath || fail "their side missing in the markers"
# the other path merged cleanly inside the same text
grep -q 'path 2002.1P' part.merge.mpath || fail "the merged text lost path 2002.1P"
git merge --abort && rm part.merge.mpath

# 3. a CAD re-save (ezdxf saves anew; the ENTITIES reversed) on theirs, an edit on ours
git checkout -q -b theirs3 base-version
"$PY" - part.dxf <<'PY'
import sys, ezdxf
doc = ezdxf.readfile(sys.argv[1])
doc.saveas(sys.argv[1])
# the entities in reverse order, as another CAD program writes them
lines = open(sys.argv[1], newline="").read().split("\n")
pairs = [lines[i:i + 2] for i in range(0, len(lines) - 1, 2)]
start = next(i for i, p in enumerate(pairs) if p[1].strip() == "ENTITIES" and pairs[i - 1][1].strip() == "SECTION") + 1
end = next(i for i in range(start, len(pairs)) if pairs[i][1].strip() == "ENDSEC")
ents, cur = [], []
for p in pairs[start:end]:
    if p[0].strip() == "0" and cur:
        ents.append(cur); cur = []
    cur.append(p)
if cur: ents.append(cur)
flat = [p for e in reversed(ents) for p in e]
out = pairs[:start] + flat + pairs[end:]
open(sys.argv[1], "w", newline="").write("\n".join(x for p in out for x in p) + "\n")
PY
"$MILLPATH" dxf2text ../base.dxf >../base.mpath
"$MILLPATH" dxf2text part.dxf | cmp -s - ../base.mpath || fail "the re-save changed the paths"
cmp -s part.dxf ../base.dxf && fail "the re-save wrote the same bytes"
git commit -qam "theirs: re-saved in CAD"
git checkout -q -b ours3 base-version
edit part.dxf '/path 2001.1P/,/}/s/B-0,2/B-0,4/'
git commit -qam "ours: B-0,4"
cp part.dxf ../ours3.dxf
git merge -q --no-edit theirs3 >../merge.out 2>&1 || { cat ../merge.out; fail "a re-save and an edit did not merge"; }
gcode_of part.dxf 2001.1P | grep -q 'Z-0.4' || fail "our edit is lost after merging their re-save"

# 4. their side changes the frame (not a path): a conflict naming it, ours unchanged
git checkout -q -b theirs4 base-version
"$PY" -c "import ezdxf; d = ezdxf.readfile('part.dxf'); d.modelspace().add_line((0, -10), (30, -10), dxfattribs={'layer': 'FRAME'}); d.saveas('part.dxf')"
git commit -qam "theirs: a line on FRAME"
git checkout -q -b ours4 base-version
edit part.dxf '/path 2001.1P/,/}/s/B-0,2/B-0,4/'
git commit -qam "ours: B-0,4"
cp part.dxf ../ours4.dxf
if git merge -q --no-edit theirs4 >../merge.out 2>&1; then fail "a change outside the paths merged silently"; fi
grep -q 'MP210' ../merge.out && grep -q 'FRAME: 1 LINE added' ../merge.out ||
  fail "the conflict does not name the FRAME line: $(cat ../merge.out)"
cmp -s part.dxf ../ours4.dxf || fail "the conflict changed our drawing"
git merge --abort && rm -f part.merge.mpath

# 5. .mpath likewise: different elements merge, the same element is a conflict in the file
git checkout -q -b text base-version
"$MILLPATH" dxf2text part.dxf -o part.mpath
git add part.mpath && git commit -qm "as text"
git checkout -q -b text-theirs
sed -i 's/mill (5, 20) -> (25, 20)/mill (5, 20) -> (25, 20)  B-0,3/' part.mpath
git commit -qam "theirs: B-0,3 in 2002.1P"
git checkout -q -b text-ours text
sed -i '/path 2001.1P/,/}/s/B-0,2/B-0,4/' part.mpath
git commit -qam "ours: B-0,4 in 2001.1P"
git merge -q --no-edit text-theirs >../merge.out 2>&1 || { cat ../merge.out; fail ".mpath edits did not merge"; }
grep -q 'mill (5, 20) -> (25, 20)  B-0,3' part.mpath && grep -q 'B-0,4' part.mpath || fail "the merged text lacks an edit"
"$MILLPATH" fmt --check part.mpath >/dev/null || fail "the merged text is not canonical"
git checkout -q -b text-ours2 text
sed -i 's/mill (5, 20) -> (25, 20)/mill (5, 20) -> (25, 20)  B-0,1/' part.mpath
git commit -qam "ours: B-0,1 in 2002.1P"
if git merge -q --no-edit text-theirs >../merge.out 2>&1; then fail "the same element edited both ways merged"; fi
git diff --name-only --diff-filter=U | grep -qx part.mpath || fail "git does not list part.mpath as unmerged"
[ "$(grep -c '^<<<<<<< ours' part.mpath)" = 1 ] || fail "not one conflict in part.mpath"
grep -B1 '^=======' part.mpath | grep -q 'B-0,1' || fail "our element is not inside the markers"
git merge --abort
cd ..

# 6. hostile inputs: the driver alone, as git calls it; ours untouched, exit 2
cp repo/part.dxf ours.dxf && chmod u+w ours.dxf && cp ours.dxf ours.before
head -c 3000 ours.dxf >truncated.dxf
expect_status 2 millpath merge repo/part.dxf ours.dxf truncated.dxf part.dxf
grep -q 'truncated.dxf' "$WORK/err" || fail "the truncated drawing is not named: $(cat "$WORK/err")"
head -c 4096 /dev/urandom >binary.dxf
expect_status 2 millpath merge repo/part.dxf ours.dxf binary.dxf part.dxf
cmp -s ours.dxf ours.before || fail "a hostile input changed ours"
printf 'path 1 {\n\0\0\0\n' >binary.mpath
"$MILLPATH" dxf2text ours.dxf -o ours.mpath && cp ours.mpath ours.mpath.before
expect_status 2 millpath merge ours.mpath ours.mpath binary.mpath part.mpath
cmp -s ours.mpath ours.mpath.before || fail "a binary text changed ours"
printf 'path 2001.1P {\n  start (0, 0\n' >broken.mpath
expect_status 2 millpath merge ours.mpath ours.mpath broken.mpath part.mpath
grep -q 'broken.mpath:2' "$WORK/err" || fail "the syntax error is not located: $(cat "$WORK/err")"
# add/add: git passes an empty base; the same file added on both sides merges to itself
: >empty
cp ours.mpath o.mpath
expect_status 0 millpath merge empty o.mpath ours.mpath part.mpath
cmp -s o.mpath ours.mpath || fail "add/add of one text changed it"
expect_status 0 millpath merge missing-base o.mpath ours.mpath part.mpath
# a read-only ours is not replaced
sed 's/B-0,2/B-0,5/' ours.mpath >theirs.mpath
cp ours.mpath ro.mpath && chmod a-w ro.mpath
expect_status 2 millpath merge ours.mpath ro.mpath theirs.mpath part.mpath
cmp -s ro.mpath ours.mpath || fail "the read-only ours changed"
# German: the same start edited both ways
sed 's/B-0,2/B-0,6/' ours.mpath >theirs6.mpath
cp theirs.mpath o.mpath
expect_status 1 millpath merge --lang de ours.mpath o.mpath theirs6.mpath part.mpath
grep -q 'Konflikt(e) in den Pfaden' "$WORK/err" && grep -q 'auf beiden Seiten geändert' "$WORK/err" ||
  fail "no German conflict message: $(cat "$WORK/err")"
