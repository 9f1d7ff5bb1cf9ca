# `millpath check` in CI: the GitHub Action runs `check --format github .` inside the
# repository; annotations must carry repository paths (no ./) to land on pull-request lines.
# A JSON consumer gets a document even when there is nothing to check; --quiet prints only
# the report; a symbolic-link loop reads every drawing once.
source "$ROOT/tests/workflows/lib.bash"

# a repository with drawings in a folder, one of them broken
mkdir -p repo/parts empty
git -C repo init -q
cp "$ROOT/examples/text/2001.mpath" "$ROOT/examples/text/millpath.toml" repo/parts/
printf 'path 3001.1P {\n' >repo/parts/3001.mpath
cd repo/parts

# what the Action runs (paths: "."), without and with GITHUB_WORKSPACE
expect_status 1 env -u GITHUB_WORKSPACE "$MILLPATH" check --format github .
grep -q '^::error file=parts/3001.mpath,line=' "$WORK/out" || fail "github: $(cat "$WORK/out")"
if grep -q 'file=\./' "$WORK/out"; then fail "github: ./ in a path"; fi
expect_status 1 env GITHUB_WORKSPACE="$WORK/repo" "$MILLPATH" check --format github ./
grep -q '^::error file=parts/3001.mpath,' "$WORK/out" || fail "github with GITHUB_WORKSPACE: $(cat "$WORK/out")"

# --quiet: the report only, no progress lines
expect_status 1 "$MILLPATH" check --quiet .
[ ! -s "$WORK/err" ] || fail "--quiet printed: $(cat "$WORK/err")"
grep -q 'checked 2 file(s): 1 error(s)' "$WORK/out" || fail "--quiet report: $(cat "$WORK/out")"

# a symlink loop: each drawing read once, no error for the loop
ln -s .. loop
expect_status 1 "$MILLPATH" check .
reads=$(grep -c '^---- Reading' "$WORK/err" || true)
[ "$reads" -eq 2 ] || fail "symlink loop: $reads reads (expected 2): $(cat "$WORK/err")"
rm loop

# nothing to check: still a JSON (and SARIF) document, exit 3
cd "$WORK/empty"
expect_status 3 "$MILLPATH" check --format json .
"$PY" -c 'import json,sys; d=json.load(sys.stdin); assert d["errors"] == 1, d' <"$WORK/out" ||
  fail "json on an empty folder: $(cat "$WORK/out")"
expect_status 3 "$MILLPATH" check --format sarif .
"$PY" -c 'import json,sys; d=json.load(sys.stdin); assert d["runs"][0]["results"], d' <"$WORK/out" ||
  fail "sarif on an empty folder: $(cat "$WORK/out")"
echo "ci formats ok"
