#!/usr/bin/env bash
# Every complete example of the manual (docs/src/*.md) must compile.
#
#   ```mpath            a complete file with one path: `millpath compile` must succeed and
#                       write G-code
#   ```mpath,check      a complete file that is not compiled on its own (a part with
#                       variables, a library of several paths): `millpath check` must pass
#   ```mpath,fail       a complete file that `millpath compile` must reject; a line
#                       `# expect: CODE` in it names the error code that must be reported
#   ```mpath,fragment   part of a file: not run
#
# A block whose first line is `# file: NAME.mpath` is written under that name, else as
# exampleN.mpath. The blocks of one chapter share a folder (so a project finds the parts of
# the blocks before it) with a millpath.toml holding feed and sweep settings.
# A picture docs/src/img/STEM.svg must equal `millpath render STEM.mpath --svg` of the block.
# Complete blocks must also be in canonical form (millpath fmt --check), so that what readers
# copy is what the formatter writes. Also checks that docs/src/param-table.md is the output of the param_table example (the
# table the language server's hover uses). Prints "N passed, M failed".
set -uo pipefail
cd "$(dirname "$0")/.."
target="${CARGO_TARGET_DIR:-target}"
bin="$target/release/millpath"
if [ ! -x "$bin" ]; then
  cargo build --release --quiet -p millpath || exit 1
fi
bin="$(cd "$(dirname "$bin")" && pwd)/millpath"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
passed=0
failed=0

# extract: one directory per block, with kind (ok|fail) and source location
python3 - "$work" docs/src/*.md <<'PY' || { echo "extraction failed"; exit 1; }
import os, re, sys
work, files = sys.argv[1], sys.argv[2:]
n = 0
for path in files:
    lines = open(path, encoding="utf-8").read().split("\n")
    i = 0
    while i < len(lines):
        m = re.match(r"^(\s*)```mpath(,[a-z]+)?\s*$", lines[i])
        if not m:
            i += 1
            continue
        indent, kind = m.group(1), (m.group(2) or ",ok")[1:]
        start = i + 1
        body = []
        i += 1
        while i < len(lines) and lines[i].strip() != "```":
            body.append(lines[i][len(indent):] if lines[i].startswith(indent) else lines[i])
            i += 1
        i += 1
        if kind not in ("ok", "check", "fail"):
            continue
        n += 1
        d = os.path.join(work, os.path.basename(path)[:-3])
        os.makedirs(d, exist_ok=True)
        name = f"example{n}.mpath"
        if body and (fm := re.match(r"#\s*file:\s*(\S+)", body[0])):
            name = fm.group(1)
        open(os.path.join(d, name), "w").write("\n".join(body) + "\n")
        open(os.path.join(d, "millpath.toml"), "w").write(
            "feed = 300\nsweep_speed = 1000\nsweep_height = 10\n")
        open(os.path.join(work, f"{n:03}.meta"), "w").write(f"{kind}\n{path}:{start}\n{d}\n{name}\n")
PY

for meta in "$work"/*.meta; do
  { read -r kind; read -r where; read -r d; read -r name; } < "$meta"
  stem="${name%.mpath}"
  rm -f "$d/$stem"_*.gcode
  if [ "$kind" = check ]; then
    out="$(cd "$d" && "$bin" check "$name" 2>&1)"
  else
    out="$(cd "$d" && "$bin" compile "$name" 2>&1)"
  fi
  status=$?
  if [ "$kind" != fail ] && ! fmt="$(cd "$d" && "$bin" fmt --check "$name" 2>&1)"; then
    out="$out
not in canonical form (millpath fmt): $fmt"
    status=99
  fi
  # a toolpath picture in the manual (docs/src/img/STEM.svg) must be what render draws now
  if [ "$kind" = ok ] && [ -f "docs/src/img/$stem.svg" ] &&
     ! { (cd "$d" && "$bin" render "$name" --svg "$stem.svg" >/dev/null 2>&1) &&
         cmp -s "$d/$stem.svg" "docs/src/img/$stem.svg"; }; then
    out="$out
docs/src/img/$stem.svg is not the output of: millpath render $name --svg $stem.svg"
    status=98
  fi
  if [ "$kind" = ok ] && [ $status -eq 0 ] && ls "$d/$stem"_*.gcode >/dev/null 2>&1; then
    passed=$((passed + 1))
  elif [ "$kind" = check ] && [ $status -eq 0 ]; then
    passed=$((passed + 1))
  elif [ "$kind" = fail ] && [ $status -ne 0 ] &&
       { ! code="$(grep -o '^# expect: *[A-Z0-9]*' "$d/$name" | sed 's/.*: *//')" ||
         [ -z "$code" ] || grep -q "\[$code\]" <<<"$out"; }; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAIL ($kind, exit $status): $where"
    echo "$out" | sed 's/^/    /'
  fi
done

# the parameter table is generated from the hover texts
if table="$(cargo run -q -p millpath-ide --example param_table 2>&1)" &&
   diff <(echo "$table") docs/src/param-table.md >/dev/null; then
  passed=$((passed + 1))
else
  failed=$((failed + 1))
  echo "FAIL: docs/src/param-table.md differs from: cargo run -q -p millpath-ide --example param_table"
  diff <(echo "$table") docs/src/param-table.md | head -20
fi

echo "manual examples: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
