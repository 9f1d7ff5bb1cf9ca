#!/usr/bin/env bash
# The command line of millpath.exe under Wine, against the Linux build (run by
# tests/windows.sh, which sets MILLPATH_WIN (wine millpath.exe), MILLPATH_LINUX and
# HOLDOPEN). Outputs must be the same bytes on both (LF line ends: docs/src/install.md),
# messages the same but for Windows paths. Prints `ok - …`/`not ok - …` and a count.
set -uo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
W=$MILLPATH_WIN
L=$MILLPATH_LINUX
work=$(mktemp -d)
[ -n "${KEEP:-}" ] || trap 'rm -rf "$work"' EXIT
passed=0
failed=0

ok() { echo "ok - $1"; passed=$((passed + 1)); }
not_ok() { echo "not ok - $1"; failed=$((failed + 1)); }
# check NAME COMMAND...: one test, by the command's status
check() {
  local name=$1
  shift
  if "$@" >"$work/log" 2>&1; then ok "$name"; else not_ok "$name"; sed 's/^/    /' "$work/log" | head -40; fi
}
# fresh DIR FILES...: an empty folder with copies of the given files
fresh() {
  local d=$1
  shift
  rm -rf "$d" && mkdir -p "$d" && cp "$@" "$d/"
}
# same_files A B: the same files with the same bytes in two folders (outputs only)
same_files() {
  local a=$1 b=$2 n=0 f
  for f in "$a"/*.gcode "$a"/*_Z.txt "$a"/*.dxf "$a"/*.mpath; do
    [ -e "$f" ] || continue
    cmp -s "$f" "$b/$(basename "$f")" || { echo "differs: $(basename "$f")"; return 1; }
    n=$((n + 1))
  done
  [ "$(ls "$a" | wc -l)" -eq "$(ls "$b" | wc -l)" ] || { echo "file lists differ:"; ls "$a" "$b"; return 1; }
  [ "$n" -gt 0 ] || { echo "no files"; return 1; }
}
no_cr() { ! grep -l $'\r' "$@"; }

# in: DIR COMMAND... runs COMMAND in DIR, stdout to DIR.out, stderr to DIR.err, status to DIR.rc
in_dir() {
  local d=$1
  shift
  (cd "$d" && "$@") >"$d.out" 2>"$d.err"
  echo $? >"$d.rc"
}
# both NAME SRCFILES -- ARGS...: the same command in w/ (Windows) and l/ (Linux) copies
both() {
  local name=$1
  shift
  local files=()
  while [ "$1" != "--" ]; do files+=("$1"); shift; done
  shift
  mkdir -p "$work/$name"
  rm -rf "$work/$name/w" "$work/$name/l"
  mkdir "$work/$name/w" "$work/$name/l"
  [ ${#files[@]} -eq 0 ] || cp -r "${files[@]}" "$work/$name/w/"
  [ ${#files[@]} -eq 0 ] || cp -r "${files[@]}" "$work/$name/l/"
  in_dir "$work/$name/w" "$W" "$@"
  in_dir "$work/$name/l" "$L" "$@"
}
same_run() { # NAME: same status, stdout and outputs
  local d=$work/$1
  [ "$(cat "$d/w.rc")" = "$(cat "$d/l.rc")" ] || { echo "status $(cat "$d/w.rc") vs $(cat "$d/l.rc")"; cat "$d/w.err"; return 1; }
  cmp "$d/w.out" "$d/l.out" || { diff "$d/w.out" "$d/l.out" | head; return 1; }
  same_files "$d/w" "$d/l"
}

ex=$ROOT/examples
# --- compile: every example in every dialect, the same bytes as the Linux build, LF only
for dialect in reference linuxcnc grbl; do
  both "plate-$dialect" "$ex/plate/1234.1P.dxf" "$ex/plate/millpath.toml" -- compile --dialect "$dialect" 1234.1P.dxf
  check "compile plate ($dialect): same outputs as Linux" same_run "plate-$dialect"
  both "text-$dialect" "$ex"/text/*.mpath "$ex/text/millpath.toml" -- compile --dialect "$dialect" 2001.mpath 2010.mpath 2020.mpath
  check "compile text examples ($dialect): same outputs as Linux" same_run "text-$dialect"
done
check "outputs have LF line ends" no_cr "$work"/plate-reference/w/*.gcode "$work"/text-grbl/w/*.gcode "$work"/text-reference/w/*_Z.txt

# --- CRLF input everywhere: .mpath, DXF and millpath.toml with CR LF give the same G-code
crlf() { sed -i 's/$/\r/' "$@"; }
fresh "$work/crlf" "$ex"/text/*.mpath "$ex/text/millpath.toml" "$ex/plate/1234.1P.dxf"
crlf "$work"/crlf/*.mpath "$work/crlf/1234.1P.dxf" "$work/crlf/millpath.toml"
in_dir "$work/crlf" "$W" compile 2001.mpath 2010.mpath 2020.mpath 1234.1P.dxf
crlf_same() {
  [ "$(cat "$work/crlf.rc")" = 0 ] || { cat "$work/crlf.err"; return 1; }
  for f in 2001_Milling.gcode 2010_Milling.gcode 2020_Clean.gcode 2020_Z.txt; do
    cmp "$work/crlf/$f" "$work/text-reference/l/$f" || return 1
  done
  # the plate with the text examples' settings: the same as Linux with them
  mkdir -p "$work/crlf-l" && cp "$ex/plate/1234.1P.dxf" "$ex/text/millpath.toml" "$work/crlf-l/"
  (cd "$work/crlf-l" && "$L" compile 1234.1P.dxf) 2>/dev/null
  cmp "$work/crlf/1234.1P_Milling.gcode" "$work/crlf-l/1234.1P_Milling.gcode"
}
check "CRLF .mpath, DXF and millpath.toml: same G-code as LF" crlf_same

# --- check in every format: the same report, paths as given (backslashes) or as CI wants
fresh "$work/fmtsrc" "$ex/text/2010.mpath" "$ex/text/2001.mpath" "$ex/text/millpath.toml"
mkdir -p "$work/fmtsrc/sub" && cp "$ex/text/2001.mpath" "$ex/text/millpath.toml" "$work/fmtsrc/sub/"
printf 'path 2003.1P {\n  mill (0, 0) -> (x, 1)\n}\n' >"$work/fmtsrc/sub/2003.mpath"
git -C "$work/fmtsrc" init -q # the CI root (SARIF %SRCROOT%, GitHub paths)
for format in human json github sarif; do
  mkdir -p "$work/check-$format"
  rm -rf "$work/check-$format/w" "$work/check-$format/l"
  cp -r "$work/fmtsrc" "$work/check-$format/w" && cp -r "$work/fmtsrc" "$work/check-$format/l"
  in_dir "$work/check-$format/w" "$W" check --format "$format" 2010.mpath 'sub\2003.mpath' 'sub\2001.mpath'
  in_dir "$work/check-$format/l" "$L" check --format "$format" 2010.mpath sub/2003.mpath sub/2001.mpath
done
same_report() { # FORMAT: the Windows report with its paths put the Unix way is the Linux one
  local d=$work/check-$1 out
  [ "$(cat "$d/w.rc")" = 1 ] && [ "$(cat "$d/l.rc")" = 1 ] || { echo "status $(cat "$d/w.rc")"; return 1; }
  for out in out err; do
    # human and json show the path as typed (JSON doubles the backslash); SARIF's root
    # is file:///Z:/… under Wine
    sed -e 's#sub\\\\#sub/#g; s#sub\\#sub/#g; s#file:///Z:/#file:///#g; s#/check-\([a-z]*\)/w/#/check-\1/l/#g' "$d/w.$out" | cmp - "$d/l.$out" \
      || { diff <(sed -e 's#sub\\\\#sub/#g; s#sub\\#sub/#g; s#file:///Z:/#file:///#g; s#/check-\([a-z]*\)/w/#/check-\1/l/#g' "$d/w.$out") "$d/l.$out" | head; return 1; }
  done
}
for format in human json github sarif; do
  check "check --format $format: the Linux report, Windows paths" same_report "$format"
done
check "human: the path as typed" grep -q -F -- '--> sub\2003.mpath:2:' "$work/check-human/w.out"
check "github: repository path with /" grep -q -F '::error file=sub/2003.mpath,line=2' "$work/check-github/w.out"
check "sarif: %SRCROOT% is file:///Z:/…" grep -q '"uri": "file:///Z:/.*/check-sarif/w/"' "$work/check-sarif/w.out"
# a file outside the root: an absolute file:///Z:/… URI and a GitHub path with its drive
mkdir -p "$work/outside" && cp "$work/fmtsrc/sub/2003.mpath" "$work/fmtsrc/sub/millpath.toml" "$work/outside/"
(cd "$work/check-sarif/w" && "$W" check --format sarif "Z:${work//\//\\}\\outside\\2003.mpath") >"$work/outside.sarif" 2>/dev/null
check "sarif: a file outside the root as file:///Z:/…/outside/2003.mpath" \
  grep -q "\"uri\": \"file:///Z:$work/outside/2003.mpath\"" "$work/outside.sarif"
(cd "$work/check-sarif/w" && "$W" check --format github "Z:${work//\//\\}\\outside\\2003.mpath") >"$work/outside.gh" 2>/dev/null
# (GitHub's workflow commands escape `:` in a property as %3A)
check "github: a file outside the root as Z:/…" grep -q "file=Z%3A$work/outside/2003.mpath," "$work/outside.gh"
# GITHUB_WORKSPACE (canonicalised) is the root: no \\?\ prefix breaks the relative paths
(cd "$work/check-github/w/sub" && GITHUB_WORKSPACE="Z:${work//\//\\}\\check-github\\w" \
  "$W" check --format github 2003.mpath) >"$work/ws.gh" 2>/dev/null
check "github: GITHUB_WORKSPACE as the root" grep -q '::error file=sub/2003.mpath,line=2' "$work/ws.gh"

# --- dxf2text / text2dxf / fmt
both roundtrip "$ex/plate/1234.1P.dxf" -- dxf2text 1234.1P.dxf -o plate.mpath
check "dxf2text: same text as Linux" same_run roundtrip
both text2dxf "$ex/text/2010.mpath" -- text2dxf 2010.mpath -o 2010.dxf
check "text2dxf: same DXF as Linux" same_run text2dxf
both fmtcheck "$ex"/text/*.mpath -- fmt --check 2001.mpath 2010.mpath 2020.mpath
check "fmt --check on the examples: clean, as on Linux" same_run fmtcheck
fresh "$work/fmtcrlf" "$ex/text/2010.mpath"
sed -i 's/^  mill/    mill/; s/$/\r/' "$work/fmtcrlf/2010.mpath"
in_dir "$work/fmtcrlf" "$W" fmt 2010.mpath
fmt_keeps_crlf() {
  [ "$(cat "$work/fmtcrlf.rc")" = 0 ] || return 1
  sed 's/$/\r/' "$ex/text/2010.mpath" | cmp - "$work/fmtcrlf/2010.mpath"
}
check "fmt of a CRLF file: canonical, CRLF kept" fmt_keeps_crlf

# --- adjust-z and verify: the probing chain
both adjust "$ex/text/2020.mpath" "$ex/text/millpath.toml" -- compile 2020.mpath
for s in w l; do sed -i 's/#51=\r\?$/#51=3.1/; s/#52=\r\?$/#52=2.9/' "$work/adjust/$s/2020_Z.txt"; done
for s in w l; do rm -f "$work/adjust/$s.out"; done
in_dir "$work/adjust/w" "$W" adjust-z --max 1 2020
in_dir "$work/adjust/l" "$L" adjust-z --max 1 2020
check "adjust-z: same _Milling.gcode as Linux" same_run adjust
in_dir "$work/adjust/w" "$W" verify --top 3 --tool 2 --bottom -0.5 2020_Milling.gcode
in_dir "$work/adjust/l" "$L" verify --top 3 --tool 2 --bottom -0.5 2020_Milling.gcode
verify_same() { [ "$(cat "$work/adjust/w.rc")" = 0 ] && cmp "$work/adjust/w.out" "$work/adjust/l.out" && grep -q "0 error(s)" "$work/adjust/w.err"; }
check "verify: clean, the same report as Linux" verify_same

# --- the reference's command lines as Windows users type them
both compat "$ex/plate/1234.1P.dxf" -- pathdxf2gcode /f150 /v500 /s5 /z50 ./1234.1P.dxf /l de
in_dir "$work/compat/w" "$W" pathdxf2gcode /f150 /v500 /s5 /z50 '.\1234.1P.dxf' /l de
check "pathdxf2gcode /f150 /v500 /s5 /z50 .\\1234.1P.dxf /l de: same as Linux" same_run compat
both compatz "$ex/text/2020.mpath" "$ex/text/millpath.toml" -- compile 2020.mpath
for s in w l; do sed -i 's/#51=\r\?$/#51=3.1/; s/#52=\r\?$/#52=2.9/' "$work/compatz/$s/2020_Z.txt"; done
in_dir "$work/compatz/w" "$W" pathgcodeadjustz /m1 2020
in_dir "$work/compatz/l" "$L" pathgcodeadjustz /m1 2020
check "pathgcodeadjustz /m1 2020: same _Milling.gcode as Linux" same_run compatz
both compath "$ex/plate/1234.1P.dxf" -- pathdxf2gcode /?
check "pathdxf2gcode /?: the help, as on Linux" same_run compath

# --- an output another program holds open (a sender): a clear message naming the file,
# the old file kept whole, no temporaries; once it is closed the compile goes through
fresh "$work/held" "$ex"/text/*.mpath "$ex/text/millpath.toml"
(cd "$work/held" && "$W" compile 2010.mpath) >/dev/null 2>&1
md5sum "$work/held/2010_Milling.gcode" >"$work/held.md5"
(cd "$work/held" && wine "$HOLDOPEN" 2010_Milling.gcode release) >"$work/holder.out" 2>&1 &
holder=$!
for _ in $(seq 100); do grep -q held "$work/holder.out" 2>/dev/null && break; sleep 0.1; done
in_dir "$work/held" "$W" compile -f 333 2010.mpath
held_refused() {
  [ "$(cat "$work/held.rc")" = 1 ] || { echo "status $(cat "$work/held.rc")"; cat "$work/held.err"; return 1; }
  grep -q "Cannot write 2010_Milling.gcode: another program has the file open" "$work/held.err" || { cat "$work/held.err"; return 1; }
  md5sum -c --quiet "$work/held.md5" || return 1
  [ "$(ls -A "$work/held" | grep -c '\.tmp$\|\.old$')" = 0 ] || { ls -A "$work/held"; return 1; }
}
check "held-open output: message naming it, old file whole, no temporaries" held_refused
in_dir "$work/held" "$W" compile --lang de -f 333 2010.mpath
check "held-open output: the German message" grep -q "2010_Milling.gcode kann nicht geschrieben werden: ein anderes Programm hat die Datei geöffnet" "$work/held.err"
touch "$work/held/release"
wait "$holder"
in_dir "$work/held" "$W" compile -f 333 2010.mpath
check "held-open output: written once closed" grep -q "F333" "$work/held/2010_Milling.gcode"

# --- a read-only output (Wine shows a file without write bits with the read-only
# attribute): refused naming it, the file kept as it was and still read-only
fresh "$work/ro" "$ex"/text/*.mpath "$ex/text/millpath.toml"
(cd "$work/ro" && "$W" compile 2010.mpath) >/dev/null 2>&1
chmod a-w "$work/ro/2010_Milling.gcode"
md5sum "$work/ro/2010_Milling.gcode" >"$work/ro.md5"
in_dir "$work/ro" "$W" compile -f 333 2010.mpath
ro_refused() {
  [ "$(cat "$work/ro.rc")" = 1 ] || { echo "status $(cat "$work/ro.rc")"; cat "$work/ro.err"; return 1; }
  grep -q "Cannot write 2010_Milling.gcode: read-only: not replaced" "$work/ro.err" || { cat "$work/ro.err"; return 1; }
  md5sum -c --quiet "$work/ro.md5" && [ -z "$(find "$work/ro/2010_Milling.gcode" -perm -u=w)" ]
}
check "read-only output: refused naming it, kept read-only" ro_refused

# --- files staged by a compile that was killed (no chance to clean up): the next compile of
# the drawing sweeps those whose process is gone, as on Linux, and keeps a live process's
# file and an old output moved aside (the user's previous program)
fresh "$work/stale" "$ex"/text/*.mpath "$ex/text/millpath.toml"
touch "$work/stale/gone"
# a process that ran and ended: its id
dead=$(cd "$work/stale" && wine "$HOLDOPEN" 2010.mpath gone 2>/dev/null | sed -n 's/^held \([0-9]*\).*/\1/p')
(cd "$work/stale" && wine "$HOLDOPEN" 2001.mpath release) >"$work/live.out" 2>&1 &
live_holder=$!
for _ in $(seq 100); do grep -q held "$work/live.out" 2>/dev/null && break; sleep 0.1; done
live=$(sed -n 's/^held \([0-9]*\).*/\1/p' "$work/live.out")
o=2010_Milling.gcode
stale_swept() {
  [ -n "$dead" ] && [ -n "$live" ] || { echo "no process ids: dead=$dead live=$live"; return 1; }
  local f
  for f in ".$o.$dead.stage1" "..$o.$dead.stage1.$dead.stage2" ".$o.$dead.tmp" ".$o.$live.stage1" ".$o.$dead.old"; do
    echo partial >"$work/stale/$f"
  done
  (cd "$work/stale" && "$W" compile 2010.mpath) >"$work/stale.log" 2>&1 || { cat "$work/stale.log"; return 1; }
  for f in ".$o.$dead.stage1" "..$o.$dead.stage1.$dead.stage2" ".$o.$dead.tmp"; do
    [ ! -e "$work/stale/$f" ] || { echo "not swept: $f"; ls -A "$work/stale"; return 1; }
  done
  for f in ".$o.$live.stage1" ".$o.$dead.old"; do
    [ -e "$work/stale/$f" ] || { echo "swept, but it is not dead: $f"; return 1; }
  done
  grep -q G00 "$work/stale/$o"
}
check "a killed compile's staged files: swept when their process is gone, kept while it runs" stale_swept
touch "$work/stale/release"
wait "$live_holder"

echo "windows cli: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
