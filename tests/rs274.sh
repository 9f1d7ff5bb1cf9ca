#!/usr/bin/env bash
# LinuxCNC's interpreter (rs274, Debian package linuxcnc-uspace) runs every program we write
# in the `linuxcnc` dialect without an error: the examples and every shared drawing that
# compiles alone (../shared/conformance/fixtures and ../shared/samples; skipped when absent).
# Probed drawings are also taken through adjust-z (probes measured at their nominal heights).
# The same drawings in the `reference` dialect are reported, not failed: the reference writes
# F150 before G94, which resets the feed in LinuxCNC, so a first plunge has no feed.
# A negative check proves rs274 really rejects such a program. The other built-in posts of
# the rs274 family (RS274_POSTS) are checked the same way; a post that cannot probe must
# refuse the probed drawings (with its message), not write them. Mach and UCCNC probe with
# G31, which LinuxCNC's rs274 cannot parse (it has G38.x): their probing programs are kept
# out of rs274 (counted; verify reads them as compile did), the rest of their sets run. The rs274 family's style (a
# post with line numbers and `;` comments) is run through rs274 too. Last line: N passed, M failed.
set -uo pipefail
cd "$(dirname "$0")/.."
if ! command -v rs274 >/dev/null; then
  apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q linuxcnc-uspace >/dev/null
fi
if [ -z "${MILLPATH_BIN:-}" ]; then
  cargo build --release --quiet -p millpath || exit 1
fi
BIN=${MILLPATH_BIN:-${CARGO_TARGET_DIR:-$PWD/target}/release/millpath}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
shared=../shared
[ -d "$shared/conformance/fixtures" ] || shared=

# rs274_ok FILE: rs274 (batch mode, stdin closed, stop at the first error) runs FILE to its
# end with exit status 0 and prints nothing on stderr but its "executing" banner. What it
# complained about is left in $why.
rs274_ok() {
  local err status
  err=$(cd "$(dirname "$1")" && timeout 60 rs274 -g "$(basename "$1")" </dev/null 2>&1 >/dev/null)
  status=$?
  why=$(printf '%s\n' "$err" | grep -v '^executing$' | head -3 | sed 's/^/      /')
  [ "$status" -eq 0 ] && [ -z "$why" ]
}

# compile_all DIALECT: compiles the drawings into $tmp/DIALECT; prints the programs written.
compile_all() {
  local d=$1 out=$tmp/$1 f
  mkdir -p "$out"/plate "$out"/text "$out"/fixtures "$out"/samples
  # drawings and settings only (no programs left over from earlier runs)
  cp examples/plate/*.dxf examples/plate/millpath.toml "$out/plate/"
  cp examples/text/*.mpath examples/text/millpath.toml "$out/text/"
  if [ -n "$shared" ]; then
    cp "$shared"/conformance/fixtures/*.dxf "$out/fixtures/"
    cp "$shared"/samples/*.dxf "$out/samples/"
  fi
  for f in "$out"/plate/*.dxf "$out"/text/*.mpath; do
    # the examples carry their machine settings (millpath.toml) and must compile
    if ! "$BIN" compile --post "$d" "$f" >"$out/last.err" 2>&1; then
      # a post without probing refuses probed drawings (and says so): expected
      if grep -q -w "$d" <<<"$NO_PROBING" &&
        grep -q -i "prob" "$out/last.err"; then
        echo "REFUSED $f"
      else
        echo "COMPILE-FAILED $f"
      fi
    fi
  done
  for f in "$out"/fixtures/*.dxf "$out"/samples/*.dxf; do
    [ -e "$f" ] || continue
    # a drawing that does not compile alone (several paths, errors) writes nothing: skipped
    "$BIN" compile --post "$d" --feed 150 --sweep-speed 500 --sweep-height 15 "$f" \
      >/dev/null 2>&1 || true
  done
  # probed drawings: every probe measured at its nominal height, then adjust-z
  for f in "$out"/*/*_Z.txt; do
    [ -e "$f" ] || continue
    sed -i -E 's|/T=([-0-9.]+)\) (#[0-9]+)=$|/T=\1) \2=\1|' "$f"
    "$BIN" adjust-z --max 0.5 "${f%_Z.txt}_Clean.gcode" >/dev/null 2>&1 ||
      echo "COMPILE-FAILED adjust-z ${f%_Z.txt}_Clean.gcode"
  done
  find "$out" -name '*_Milling.gcode' -o -name '*_Clean.gcode' -o -name '*_Probing.gcode' | sort
}

# the built-in posts of the rs274 family, those of them that cannot probe, and those that
# probe with G31
RS274_POSTS=${RS274_POSTS:-linuxcnc mach3 uccnc centroid}
NO_PROBING="centroid"
G31_PROBING="mach3 uccnc"
passed=0
failed=0
for post in $RS274_POSTS; do
  ok=0
  refused=0
  g31=0
  programs=$(compile_all "$post")
  while IFS= read -r p; do
    [ -n "$p" ] || continue
    case $p in
    REFUSED*)
      refused=$((refused + 1))
      continue
      ;;
    COMPILE-FAILED*)
      echo "FAIL  ${p#COMPILE-FAILED } failed with the $post post"
      failed=$((failed + 1))
      continue
      ;;
    esac
    if grep -q -w "$post" <<<"$G31_PROBING" && grep -q '^G31 ' "$p"; then
      g31=$((g31 + 1))
      continue
    fi
    if rs274_ok "$p"; then
      passed=$((passed + 1))
      ok=$((ok + 1))
    else
      echo "FAIL  $post ${p#"$tmp"/"$post"/}"
      printf '%s\n' "$why"
      failed=$((failed + 1))
    fi
  done <<<"$programs"
  echo "$post: rs274 accepts $ok programs ($refused probed examples refused by the post, $g31 G31 probing programs not for rs274)"
done

# the reference dialect, for comparison (reported, not failed)
ref_ok=0
ref_bad=0
while IFS= read -r p; do
  case $p in "" | COMPILE-FAILED*) continue ;; esac
  if rs274_ok "$p"; then ref_ok=$((ref_ok + 1)); else ref_bad=$((ref_bad + 1)); fi
done <<<"$(compile_all reference)"
echo "reference dialect (for comparison): rs274 accepts $ref_ok, rejects $ref_bad programs"

# negative check: the reference output of a drawing that plunges first must be rejected
neg=$tmp/reference/plate/1234.1P_Milling.gcode
if [ -f "$neg" ] && ! rs274_ok "$neg"; then
  passed=$((passed + 1))
else
  echo "FAIL  negative check: rs274 accepted the reference output of examples/plate/1234.1P.dxf"
  failed=$((failed + 1))
fi

# the rs274 family's style: a post of our own with line numbers and `;` comments; what
# the checker accepts of it (compile checks every program) rs274 must accept too
fam=$tmp/family
mkdir -p "$fam"
cp examples/text/*.mpath examples/text/millpath.toml "$fam/"
"$BIN" post show linuxcnc | sed -e 's/^name = "linuxcnc"/name = "numbered"/' \
  -e 's/^style = "parens"/style = "semicolon"/' \
  -e 's/^\[comments\]/[line_numbers]\nstart = 10\nstep = 10\n\n[comments]/' \
  -e 's/^comment = "{indent}({text})"/comment = "{indent}; {text}"/' \
  -e 's/^statistics = "  ({text})"/statistics = "; {text}"/' >"$fam/numbered.toml"
for f in "$fam"/*.mpath; do
  "$BIN" compile --post "$fam/numbered.toml" --spindle-rpm 9000 "$f" >/dev/null 2>&1 ||
    echo "FAIL  ${f#"$tmp"/} did not compile with the numbered rs274 post"
done
family_ok=0
for p in "$fam"/*_Milling.gcode "$fam"/*_Clean.gcode "$fam"/*_Probing.gcode; do
  [ -e "$p" ] || continue
  if grep -q '^N[0-9]* ;' "$p" && rs274_ok "$p"; then
    passed=$((passed + 1))
    family_ok=$((family_ok + 1))
  else
    echo "FAIL  numbered rs274 post: ${p#"$tmp"/}"
    printf '%s\n' "$why"
    failed=$((failed + 1))
  fi
done
echo "rs274 family (line numbers, ; comments): rs274 accepts $family_ok programs"
# negative check: a line number after the command, which the checker rejects, rs274 rejects
p=$fam/2001_Milling.gcode
if [ -f "$p" ]; then
  sed -E '0,/^N([0-9]+) (G0[01]) /s//\2 N\1 /' "$p" >"$fam/moved.ngc"
  if ! rs274_ok "$fam/moved.ngc" && ! "$BIN" verify --dialect rs274 "$fam/moved.ngc" >/dev/null 2>&1; then
    passed=$((passed + 1))
  else
    echo "FAIL  negative check: a line number after the command was accepted"
    failed=$((failed + 1))
  fi
fi

[ -n "$shared" ] || echo "(../shared is absent: only the examples were compiled)"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
