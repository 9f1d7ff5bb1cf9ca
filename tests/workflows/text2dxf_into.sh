# The two-way workflow: a drawing made in CAD (with dimensions and labels beside its path)
# is turned into text, the text is edited, and the paths are written back into the drawing
# with `text2dxf --into`: the dimensions survive, the G-code is the edited text's.
source "$ROOT/tests/workflows/lib.bash"
need_shared

# ezdxf's view of a drawing: per layer that holds no path, its entities' types and handles;
# and the audit's errors and fixes.
cat >layers.py <<'EOF'
import sys, ezdxf
doc = ezdxf.readfile(sys.argv[1])
for e in sorted(doc.modelspace(), key=lambda e: (e.dxf.layer, e.dxf.handle)):
    layer = e.dxf.layer
    if layer.split("~")[0] != "8999_14P":
        print(layer, e.dxftype(), e.dxf.handle)
EOF
cat >audit.py <<'EOF'
import sys, ezdxf
auditor = ezdxf.readfile(sys.argv[1]).audit()
for x in auditor.errors:
    print("error", x.code, x.message)
for x in auditor.fixes:
    print("fix", x.code, x.message)
EOF

machine=(--feed 150 --sweep-speed 1000 --sweep-height 10)
# G-code without the input file's name in its comments (part.dxf / part.mpath)
gcode() { sed -e 's/part\.mpath/part/g' -e 's/part\.dxf/part/g' "$1"; }

# 1. the drawing from CAD, and what it compiles to
cp "$SHARED/conformance/fixtures/8999.14P.dxf" part.dxf && chmod u+w part.dxf # shared files are read-only
cp part.dxf original.dxf
mkdir original && cp part.dxf original/part.dxf
"$MILLPATH" compile "${machine[@]}" original/part.dxf >/dev/null 2>&1
"$PY" layers.py original.dxf >layers.before
grep -q '^BEMASSUNG INSERT' layers.before || fail "the drawing has no dimensions to keep"

# 2. as text
"$MILLPATH" dxf2text part.dxf >part.mpath

# 3. text2dxf over the drawing would lose the dimensions: refused, nothing changed
expect_status 1 "$MILLPATH" text2dxf part.mpath
grep -q 'BEMASSUNG' "$WORK/err" || fail "the refusal does not name BEMASSUNG: $(cat "$WORK/err")"
grep -q -- '--into part.dxf' "$WORK/err" || fail "the refusal does not say what to do"
cmp part.dxf original.dxf || fail "the refused text2dxf changed the drawing"

# 4. without an edit, written back: the same G-code as the original drawing
"$MILLPATH" text2dxf part.mpath --into part.dxf
mkdir same && cp part.dxf same/part.dxf
"$MILLPATH" compile "${machine[@]}" same/part.dxf >/dev/null 2>&1
cmp same/part_Milling.gcode original/part_Milling.gcode || fail "the written-back drawing compiles differently"

# 5. edit the text (the depth T2 → T3) and write it back into the drawing
cp original.dxf part.dxf
sed -i 's/ T2 / T3 /' part.mpath
grep -q ' T3 ' part.mpath || fail "the edit did not apply"
"$MILLPATH" text2dxf part.mpath --into part.dxf

# 6. ezdxf: every entity off the path layer is there with its handle; the audit finds
#    nothing the original did not have
"$PY" layers.py part.dxf >layers.after
diff layers.before layers.after || fail "entities off the path layer changed"
"$PY" audit.py original.dxf >audit.before
"$PY" audit.py part.dxf >audit.after
grep -q '^error' audit.after && fail "ezdxf audit: $(grep '^error' audit.after)"
diff audit.before audit.after || fail "ezdxf's audit differs from the original's"

# 7. the drawing compiles to what the edited text compiles to
mkdir text drawing
cp part.mpath text/part.mpath
cp part.dxf drawing/part.dxf
"$MILLPATH" compile "${machine[@]}" text/part.mpath >/dev/null 2>&1
"$MILLPATH" compile "${machine[@]}" drawing/part.dxf >/dev/null 2>&1
diff <(gcode text/part_Milling.gcode) <(gcode drawing/part_Milling.gcode) \
  || fail "the drawing and the edited text compile differently"
cmp -s drawing/part_Milling.gcode original/part_Milling.gcode \
  && fail "the edit did not reach the G-code"

# 8. one of the project's own examples: its text, drawn, then a dimension added in "CAD"
#    (ezdxf), then the text edited and written back
cp "$ROOT/examples/text/2010.mpath" "$ROOT/examples/text/2001.mpath" "$ROOT/examples/text/millpath.toml" .
"$MILLPATH" text2dxf 2010.mpath
"$PY" - <<'EOF'
import ezdxf
doc = ezdxf.readfile("2010.dxf")
doc.layers.add("MASSE")
doc.modelspace().add_linear_dim(base=(0, -10), p1=(0, 0), p2=(50, 0), dxfattribs={"layer": "MASSE"}).render()
doc.saveas("2010.dxf")
EOF
cp 2010.dxf 2010.cad.dxf
expect_status 1 "$MILLPATH" text2dxf 2010.mpath
grep -q 'MASSE' "$WORK/err" || fail "the refusal does not name MASSE"
cmp 2010.dxf 2010.cad.dxf || fail "the refused text2dxf changed the example drawing"
sed -i 's/ I1,5 / I1 /' 2010.mpath
grep -q ' I1 ' 2010.mpath || fail "the edit of the example did not apply"
"$MILLPATH" text2dxf 2010.mpath --into 2010.dxf
"$PY" - <<'EOF'
import ezdxf
doc = ezdxf.readfile("2010.dxf")
dims = [e for e in doc.modelspace() if e.dxf.layer == "MASSE"]
assert [e.dxftype() for e in dims] == ["DIMENSION"], dims
assert not [x for x in doc.audit().errors], "audit errors"
EOF
mkdir ex && cp 2010.dxf 2001.mpath millpath.toml ex/
mkdir ext && cp 2010.mpath 2001.mpath millpath.toml ext/
"$MILLPATH" compile ex/2010.dxf >/dev/null 2>&1
"$MILLPATH" compile ext/2010.mpath >/dev/null 2>&1
diff <(sed 's/2010\.dxf/2010/g' ex/2010_Milling.gcode) <(sed 's/2010\.mpath/2010/g' ext/2010_Milling.gcode) \
  || fail "the example drawing and its edited text compile differently"
echo "text2dxf --into: dimensions kept, G-code as the edited text"
