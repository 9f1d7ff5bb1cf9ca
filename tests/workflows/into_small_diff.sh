# A drawing under git, edited through its text: `dxf2text`, one parameter changed,
# `text2dxf --into` back. The DXF's diff must show that edit, not a rewrite: the paths the
# text leaves as they are keep every entity byte for byte (handles, `~` layers, MTEXT), and
# in the edited path only the entities of the edited element change. The drawing compiles
# as the edited text does, and ezdxf's audit finds nothing new.
source "$ROOT/tests/workflows/lib.bash"
need_shared
machine=(--feed 150 --sweep-speed 1000 --sweep-height 10)

# ezdxf's view: every entity as `layer type handle`, sorted
cat >entities.py <<'EOF'
import sys, ezdxf
doc = ezdxf.readfile(sys.argv[1])
for e in sorted(doc.modelspace(), key=lambda e: (e.dxf.layer, e.dxf.handle)):
    print(e.dxf.layer, e.dxftype(), e.dxf.handle)
EOF
# ents DXF: its entities, sorted for comm
ents() { "$PY" entities.py "$1" | LC_ALL=C sort; }
cat >audit.py <<'EOF'
import sys, ezdxf
auditor = ezdxf.readfile(sys.argv[1]).audit()
for x in auditor.errors:
    print("error", x.code, x.message)
EOF
# changed_lines OLD NEW: the lines a diff shows removed or added
changed_lines() { diff "$1" "$2" | grep -c '^[<>]' || true; }
# at_most N OLD NEW WHAT: fails unless the diff of OLD and NEW has at most N changed lines
at_most() {
  local n
  n=$(changed_lines "$2" "$3")
  echo "$4: $n changed lines"
  [ "$n" -le "$1" ] || fail "$4: $n changed lines (at most $1): $(diff "$2" "$3" | head -40)"
}
audited() {
  "$PY" audit.py "$1" >audit.out
  [ ! -s audit.out ] || fail "ezdxf audit of $1: $(cat audit.out)"
}
# gcode DRAWING PATTERN: the milling program of the one path of DRAWING the pattern names
# (in a folder of its own: the two of a comparison run at once)
gcode() {
  local f g
  f=$(basename "$1")
  g="g_$f"
  rm -rf "$g" && mkdir "$g" && cp "$1" "$g/"
  "$MILLPATH" compile "${machine[@]}" --path-pattern "$2" "$g/$f" >/dev/null 2>&1 || fail "$1 does not compile"
  sed "s/${f//./\\.}/DRAWING/g" "$g/${f%.*}_Milling.gcode"
}

# 1. shared drawings of one path (8999.16P with entities on a layer `8999_16P~REVERSE`):
#    the start text's T2 → T3
for name in 8999.14P 8999.16P; do
  cp "$SHARED/conformance/fixtures/$name.dxf" part.dxf && chmod u+w part.dxf
  cp part.dxf part.orig.dxf
  "$MILLPATH" dxf2text part.dxf >part.mpath
  "$MILLPATH" text2dxf part.mpath --into part.dxf
  cmp part.dxf part.orig.dxf || fail "$name: the unedited text changed the drawing"
  sed -i '2s/ T2 / T3 /' part.mpath
  grep -q '^  start .* T3 ' part.mpath || fail "$name: the edit did not apply"
  "$MILLPATH" text2dxf part.mpath --into part.dxf
  # the start text's MTEXT rewritten, and $HANDSEED: one entity, not the path's 80
  at_most 70 part.orig.dxf part.dxf "$name, one start text edited"
  ents part.orig.dxf >before
  ents part.dxf >after
  [ "$(LC_ALL=C comm -23 before after | wc -l)" -eq 1 ] || fail "$name: more than one entity replaced: $(LC_ALL=C comm -3 before after)"
  diff <(grep -F '~' before || true) <(grep -F '~' after || true) || fail "$name: the entities of a ~ layer changed"
  audited part.dxf
  "$MILLPATH" dxf2text part.dxf | diff part.mpath - || fail "$name: the drawing does not read as the edited text"
  diff <(gcode part.dxf '([0-9]{4})[.]([0-9]+)([A-Z])') <(gcode part.mpath '([0-9]{4})[.]([0-9]+)([A-Z])') ||
    fail "$name compiles differently from the edited text"
done
grep -q '^8999_16P~REVERSE LINE' before || fail "8999.16P has no entities on its ~ layer to keep"

# 2. a shared library of six paths: one parameter of path 8998.34D
cp "$SHARED/conformance/fixtures/8998.31-8998.34P.dxf" lib.dxf && chmod u+w lib.dxf
cp lib.dxf lib.orig.dxf
"$MILLPATH" dxf2text lib.dxf >lib.mpath
sed -i '/^path 8998.34D/,/^}/s/ T2 / T3 /' lib.mpath
grep -A1 '^path 8998.34D' lib.mpath | grep -q ' T3 ' || fail "the library edit did not apply"
"$MILLPATH" text2dxf lib.mpath --into lib.dxf
at_most 70 lib.orig.dxf lib.dxf "8998.31-8998.34P, one path's start text edited"
"$PY" entities.py lib.orig.dxf | grep -v '^8998_34D' >before
"$PY" entities.py lib.dxf | grep -v '^8998_34D' >after
diff before after || fail "entities of the other paths changed"
audited lib.dxf
"$MILLPATH" dxf2text lib.dxf | diff lib.mpath - || fail "the library does not read as the edited text"

# 3. a drawing of our own, two paths (one text on a `~A` layer), saved again by "CAD"
#    (ezdxf: its own handles and layout): an element's own parameter edited in path 2
cat >own.mpath <<'EOF'
path 3001.1P {
  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2
  end (30, 0)
  sweep (0, 0) -> (5, 0)
  mill (5, 0) -> (25, 0)
  sweep (25, 0) -> (30, 0)
}

path 3001.2P {
  start (0, 20)  M10x3 O2 T3 I1,5 B-0,2
  end (40, 20)
  sweep (0, 20) -> (5, 20)
  mill (5, 20) -> (15, 20)  B-0,4
  mill (15, 20) -> (25, 20)
  mill (25, 20) -> (35, 20)  B-0,3
  sweep (35, 20) -> (40, 20)
}
EOF
"$MILLPATH" text2dxf own.mpath -o own.dxf
"$PY" - own.dxf <<'EOF'
import sys, ezdxf
doc = ezdxf.readfile(sys.argv[1])
doc.saveas(sys.argv[1])
EOF
"$MILLPATH" dxf2text own.dxf >own.mpath
cp own.dxf own.orig.dxf
sed -i 's/^\(  mill (25, 20) -> (35, 20)  \)B-0,3$/\1B-0,5/' own.mpath
grep -q '(35, 20)  B-0,5$' own.mpath || fail "the edit of our own drawing did not apply"
"$MILLPATH" text2dxf own.mpath --into own.dxf
at_most 70 own.orig.dxf own.dxf "our own drawing, one element's B edited"
ents own.orig.dxf >before
ents own.dxf >after
[ "$(LC_ALL=C comm -23 before after | wc -l)" -eq 1 ] || fail "more than one entity replaced: $(LC_ALL=C comm -3 before after)"
audited own.dxf
"$MILLPATH" dxf2text own.dxf | diff own.mpath - || fail "our drawing does not read as the edited text"
for p in 1 2; do
  awk -v p="path 3001.${p}P {" '$0 == p {on = 1} on {print} on && /^}/ {on = 0}' own.mpath >one.mpath
  diff <(gcode own.dxf "(3001)[.]($p)(P)") <(gcode one.mpath '([0-9]{4})[.]([0-9]+)([A-Z])') ||
    fail "path 3001.${p}P compiles differently from the edited text"
done
grep -q 'Z-0.500' g_one.mpath/one_Milling.gcode || fail "the edit did not reach the G-code"
echo "ok: text2dxf --into changes the edited element's entities only"
