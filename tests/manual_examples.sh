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
# copy is what the formatter writes.
#
#   ```sh / ```bash     commands: run in the chapter's folder (after its mpath blocks), with
#                       the release binary as `millpath` on PATH and HOME in the work folder;
#                       each must exit 0, except a line whose comment says `refused` or
#                       `exit status 1`, which must fail. The files a block needs that no
#                       block makes (a probe log, a CAD drawing, a git repository) are made
#                       by the chapter's fixture below; the few blocks that are not run are
#                       listed in SKIPPED with the reason (Windows shells: tests/windows.sh).
#
# Also checks that docs/src/param-table.md is the output of the param_table example (the
# table the language server's hover uses). Prints "N passed, M failed".
set -uo pipefail
cd "$(dirname "$0")/.."
target="${CARGO_TARGET_DIR:-target}"
bin="${MILLPATH:-$target/release/millpath}"
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
        sh = re.match(r"^(\s*)```(sh|bash|console|powershell|bat)\s*$", lines[i])
        if sh:
            indent, start, body = sh.group(1), i + 1, []
            i += 1
            while i < len(lines) and lines[i].strip() != "```":
                body.append(lines[i][len(indent):] if lines[i].startswith(indent) else lines[i])
                i += 1
            i += 1
            n += 1
            d = os.path.join(work, os.path.basename(path)[:-3])
            os.makedirs(d, exist_ok=True)
            open(os.path.join(work, f"{n:03}.block"), "w").write("\n".join(body) + "\n")
            open(os.path.join(work, f"{n:03}.shmeta"), "w").write(
                f"{sh.group(2)}\n{path}:{start}\n{d}\n{body[0] if body else ''}\n")
            continue
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
        open(os.path.join(d, ".has_mpath"), "w").write("")
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

# --- the shell blocks
# The blocks not run, by their page and first line, with the reason (keep this list short).
SKIPPED=(
  "docs/src/editors.md|cargo build --release|builds the VS Code extension (npm, VS Code): tests/vscode_e2e.sh"
  "docs/src/install.md|cargo install --path crates/cli|a second full release build into ~/.cargo (minutes); CI builds the same binary"
  "docs/src/playground.md|bash editors/playground/build.sh|the wasm build: .ci/run builds and tests the playground itself"
  "docs/src/python.md|python3 -m venv|the package's release build: tests/python.sh installs it so and runs the page's Python examples"
)
export EDITOR="$work/editor.sh" PATH="$(dirname "$bin"):$PATH"
home="$work/home" # the blocks' HOME (install.md's ~/.local/bin), not cargo's
export GIT_AUTHOR_NAME=manual GIT_AUTHOR_EMAIL=manual@example.org
export GIT_COMMITTER_NAME=manual GIT_COMMITTER_EMAIL=manual@example.org
mkdir -p "$home"
# the editor of the git workflow: deepens the first depth B of the text
printf '#!/bin/sh\nsed -i -E "0,/B-[0-9.,]+/s//B-3/" "$1"\n' >"$EDITOR"
chmod +x "$EDITOR"
examples=$PWD/examples
source tests/workflows/lib.bash # write_probe_log

# a height-map set of examples/text/2001.mpath in the linuxcnc dialect, in the current folder
heightmap_set() {
  cp "$examples/text/2001.mpath" .
  printf 'feed = 300\nsweep_speed = 1000\nsweep_height = 10\nprobe_feed = 50\ndialect = "linuxcnc"\n[heightmap]\nstep = 10\nmargin = 2\n' >millpath.toml
  millpath compile 2001.mpath
}

# fixture PAGE: the files the page's commands need that none of its blocks makes
fixture() {
  case $1 in
    install)
      cp "$bin" millpath-linux-x64 ;;
    editors)
      # a CAD drawing: a path layer and a dimension layer BEMASSUNG, in git
      cp "$examples/text/2001.mpath" part.mpath
      millpath text2dxf part.mpath -o part.dxf
      python3 - <<'EOF'
d = open("part.dxf").read()
line = "  0\nLINE\n  5\nFFF0\n330\n1F\n100\nAcDbEntity\n  8\nBEMASSUNG\n100\nAcDbLine\n 10\n0.0\n 20\n-5.0\n 30\n0.0\n 11\n30.0\n 21\n-5.0\n 31\n0.0\n"
i = d.index("  0\nENDSEC", d.index("ENTITIES"))
open("part.dxf", "w").write(d[:i] + line + d[i:])
EOF
      rm part.mpath
      git init -q . && git add part.dxf && git commit -qm "part" ;;
    version-control)
      # the text examples and a drawing in git; on `theirs` the drawing's mill line is
      # deepened one way, on ours (the last commit, HEAD~1..HEAD) another
      cp "$examples/text/2001.mpath" "$examples/text/2010.mpath" "$examples/text/millpath.toml" .
      cp 2001.mpath part.mpath && millpath text2dxf part.mpath -o part.dxf
      git init -q . && git add 2001.mpath 2010.mpath millpath.toml part.dxf && git commit -qm "parts"
      git checkout -q -b theirs
      sed -i 's/mill (5, 0) -> (25, 0).*/mill (5, 0) -> (25, 0)  B-0,3/' part.mpath
      millpath text2dxf part.mpath --into part.dxf && git commit -qam "theirs: B-0,3"
      git checkout -q -
      sed -i 's/B-0,3/B-0,1/' part.mpath
      millpath text2dxf part.mpath --into part.dxf && git commit -qam "ours: B-0,1"
      rm part.mpath ;;
    posts)
      # the drawing the page compiles for two posts
      cp "$examples/text/2001.mpath" "$examples/text/millpath.toml" . ;;
    probes)
      # the NAME of the page: a compiled height-map set, its _Z.txt filled in, the logs
      heightmap_set
      for f in _Probing.gcode _Z.txt _Clean.gcode; do mv "2001$f" "NAME$f"; done
      sed -i 's/=$/=3.05/' NAME_Z.txt
      write_probe_log NAME_Probing.gcode "t + 0.05" linuxcnc >NAME_probes.txt
      cp NAME_probes.txt LOG
      # part.dxf of the LinuxCNC steps, and the log LinuxCNC writes when it probes
      cp 2001.mpath part.mpath && millpath text2dxf part.mpath -o part.dxf && rm part.mpath
      millpath compile part.dxf
      write_probe_log part_Probing.gcode "t + 0.1 * x / 30" linuxcnc >part_probes.txt ;;
    verify)
      cp "$work/tutorial/1000.mpath" .
      # 2001_Milling.gcode adjusted to a board rising 0.2 mm along X; falling.txt: one falling
      heightmap_set
      write_probe_log 2001_Probing.gcode "t + 0.2 * (x - cx + w) / (2 * w)" linuxcnc >rising.txt
      write_probe_log 2001_Probing.gcode "t + 0.2 - 0.2 * (x - cx + w) / (2 * w)" linuxcnc >falling.txt
      millpath adjust-z --probe-log rising.txt --max 0.5 2001_Clean.gcode
      # the page's own settings again (1000.mpath is milled, not probed)
      printf 'feed = 300\nsweep_speed = 1000\nsweep_height = 10\n' >millpath.toml ;;
  esac
}

shells=0
for meta in "$work"/*.shmeta; do
  [ -e "$meta" ] || continue
  { read -r lang; read -r where; read -r d; read -r first; } <"$meta"
  page=${where%%:*}
  reason=""
  for entry in "${SKIPPED[@]}"; do
    IFS='|' read -r spage sfirst sreason <<<"$entry"
    [ "$spage" = "$page" ] && [[ $first == "$sfirst"* ]] && reason=$sreason
  done
  case $lang in powershell | bat) reason="a Windows shell: tests/windows.sh runs millpath.exe under Wine" ;; esac
  if [ -n "$reason" ]; then
    echo "skipped: $where ($first): $reason"
    continue
  fi
  mkdir -p "$d"
  if [ ! -e "$d/.fixture" ]; then
    touch "$d/.fixture"
    if ! out="$(cd "$d" && HOME=$home fixture "$(basename "$d")" 2>&1)"; then
      failed=$((failed + 1))
      echo "FAIL (fixture of $(basename "$d")): $out"
      continue
    fi
  fi
  # a line meant to fail (its comment says so) must fail
  sed -E 's/^([^#]*[^# ][^#]*#.*(refused|exit status 1).*)$/! \1/' "${meta%.shmeta}.block" >"$d/.block.sh"
  if out="$(cd "$d" && HOME=$home bash -e -o pipefail .block.sh 2>&1)"; then
    passed=$((passed + 1))
    shells=$((shells + 1))
  else
    failed=$((failed + 1))
    echo "FAIL (shell block, exit $?): $where"
    echo "$out" | sed 's/^/    /'
  fi
done
echo "shell blocks run: $shells"

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
