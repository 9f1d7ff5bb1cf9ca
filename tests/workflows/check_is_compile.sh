# CI runs `millpath check`, the shop runs `millpath compile`: on the same drawing both must
# say the same and end with the same status. The two examples (a layer that is no
# path layer, an empty .mpath) and a few edits a user makes.
source "$ROOT/tests/workflows/lib.bash"

cp "$ROOT"/examples/plate/* .
cp "$ROOT"/examples/text/*.mpath .

# both commands on one file: same exit status, same diagnostics (code and message lines)
same() {
  local file=$1 want=$2
  expect_status "$want" "$MILLPATH" check "$file"
  grep -E '^(error|warning)\[MP|^\[MP' "$WORK/out" | sort >check.txt || true
  expect_status "$want" "$MILLPATH" compile "$file"
  grep -E '^(error|warning)\[MP|^\[MP' "$WORK/err" | sort >compile.txt || true
  diff check.txt compile.txt >&2 || fail "check and compile differ on $file"
}

# 1. the layer renamed to 1000-1A (no path layer): both refuse, "no error-free path layer"
sed 's/^1234_1P$/1000-1A/' 1234.1P.dxf >1000.dxf
same 1000.dxf 1
grep -q 'contains no error-free path layer' check.txt || fail "1000-1A: $(cat check.txt)"

# 2. an empty .mpath: both refuse
: >empty.mpath
same empty.mpath 1
grep -q 'contains no error-free path' check.txt || fail "empty: $(cat check.txt)"

# 3. the end marker deleted
grep -v '^  end ' 2001.mpath >3001.mpath
sed -i 's/2001\.1P/3001.1P/' 3001.mpath
same 3001.mpath 1

# 4. a broken parameter text (O0)
sed 's/ O2 / O0 /; s/2001\.1P/3002.1P/' 2001.mpath >3002.mpath
same 3002.mpath 1

# 5. a lowercase path name: both accept it (reference-input.md §1.3) and warn alike
sed 's/2001\.1P/3003.1p/' 2001.mpath >3003.mpath
same 3003.mpath 0
grep -q 'did you mean 3003.1P' check.txt || fail "lowercase: $(cat check.txt)"

# 6. the good drawings: both clean
same 1234.1P.dxf 0
same 2010.mpath 0
echo "ok: check and compile agree"
