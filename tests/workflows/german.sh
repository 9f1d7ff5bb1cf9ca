# A German workshop: millpath.toml says lang = "de", and every step of the day speaks German
# — draw as text, check, compile, verify, probe and adjust, format, render, convert, and
# mistype an option. No English message word may show (file names, codes, options, quoted
# text and G-code aside). Then the same chain once more with --lang de and no lang in the
# settings.
source "$ROOT/tests/workflows/lib.bash"

cat > millpath.toml <<'TOML'
feed = 300
sweep_speed = 1000
sweep_height = 10
lang = "de"
TOML
cat > 3001.mpath <<'TXT'
path 3001.1P {
  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2
  end (20, 0)
  mill (0, 0) -> (20, 0)
  probe (10, 5)  L1
}
TXT
# errors: B above T and a subpath that is nowhere; a warning: the entity order decides
cat > 3002.mpath <<'TXT'
path 3002.1P {
  start (0, 0)  M10x3 O2 T3 I1,5 B4
  end (20, 0)
  sub (0, 0) -> (20, 0)  >9999.1P
}
TXT
cat > 3003.mpath <<'TXT'
path 3003.1P {
  start (0, 0)  M10x3 O2 T2 I1 B0,5
  end (0, 0)
  mill (0, 0) -> (10, 0)
  mill (10, 0) -> (10, 10)
  mill (10, 10) -> (0, 10)
  mill (0, 10) -> (0, 0)
}
TXT

# English words that German messages never contain
english='\b(error|errors|warning|warnings|expected|found|line|lines|missing|not|cannot|Writing|Reading|Checking|file|files|must|value|the|is|and|of|for|with|at|from|Usage|Options|help|invalid|unexpected|required|removed|default|formatted|unreadable|path)\b'

# no_english WHAT: fails when $WORK/out or $WORK/err holds English message text
no_english() {
  local hits
  hits=$(cat "$WORK/out" "$WORK/err" \
    | grep -v '│' | grep -v '^    | ' \
    | sed -E 's/^::[a-z]+ .*::/::/' \
    | sed -E "s/'[^']*'//g; s/\`[^\`]*\`//g; s/\"[^\"]*\"//g" \
    | sed -E 's#[^ ]*[./_=][^ ]*##g; s/--?[a-z][a-z-]*//g; s/MP[0-9]+//g' \
    | grep -n -i -E -w "$english" || true)
  [ -z "$hits" ] || { cat "$WORK/err" >&2; fail "$1: English text: $hits"; }
}

# step STATUS WHAT COMMAND...: runs a step, checks its exit status and its language
step() {
  local want=$1 what=$2
  shift 2
  expect_status "$want" "$@"
  no_english "$what"
}

day() {
  local L=("$@")   # extra options: --lang de, or nothing
  step 1 "check" "$MILLPATH" check "${L[@]}" 3001.mpath 3002.mpath 3003.mpath
  grep -q "Fehler" "$WORK/out" || fail "check: no German error word"
  grep -q "Warnung" "$WORK/out" || fail "check: no German warning word"
  step 1 "check --format github" "$MILLPATH" check "${L[@]}" --format github 3002.mpath
  step 0 "compile" "$MILLPATH" compile "${L[@]}" 3001.mpath
  grep -q "Schreiben von 3001_Clean.gcode" "$WORK/err" || fail "compile: no German progress"
  step 1 "compile of a broken drawing" "$MILLPATH" compile "${L[@]}" 3002.mpath
  step 0 "verify" "$MILLPATH" verify "${L[@]}" 3001_Clean.gcode
  printf '%%\nG0 Z5\nG1 X10 Y0 Z-3\n%%\n' > bad.gcode
  step 1 "verify of a bad program" "$MILLPATH" verify "${L[@]}" bad.gcode
  # the probe measured nowhere yet: adjust-z refuses, in German
  step 1 "adjust-z" "$MILLPATH" adjust-z "${L[@]}" --max 1 3001
  step 0 "text2dxf" "$MILLPATH" text2dxf "${L[@]}" 3001.mpath -o 3001.dxf
  step 0 "dxf2text" "$MILLPATH" dxf2text "${L[@]}" 3001.dxf -o back.mpath
  sed 's/  / /' 3001.mpath > ugly.mpath
  step 1 "fmt --check" "$MILLPATH" fmt "${L[@]}" --check ugly.mpath
  grep -q "nicht formatiert" "$WORK/out" || fail "fmt: no German"
  step 2 "clap: unknown option" "$MILLPATH" check "${L[@]}" --formt json 3001.mpath
  grep -q "^Fehler: unerwartetes Argument '--formt'" "$WORK/err" || fail "clap: not German"
  step 2 "clap: bad number" "$MILLPATH" adjust-z "${L[@]}" --max abc 3001
}

day
# render has no --lang of its own here: it speaks the language of millpath.toml
step 0 "render" "$MILLPATH" render 3001.mpath --svg 3001.svg
grep -q "Schreiben von 3001.svg" "$WORK/err" || fail "render: no German progress"
step 1 "render of a broken drawing" "$MILLPATH" render 3002.mpath

sed -i '/^lang/d' millpath.toml
rm -f 3001_*.gcode 3001_*.txt
day --lang de
echo "German throughout: check, compile, verify, adjust-z, text2dxf, dxf2text, fmt, render, option errors"
