# A long compile interrupted (Ctrl-C, SIGTERM, SIGHUP) at random points leaves no temporary
# file beside its outputs, and the previous output stays whole; a compile killed outright
# (SIGKILL: no chance to clean up) leaves its staged program, which the next compile of the
# same drawing removes.
source "$ROOT/tests/workflows/lib.bash"
# job control: a background compile gets SIGINT as a foreground one (a script's background
# jobs start with SIGINT ignored, which the compile keeps)
set -m

# a big drawing: one chain of N mill segments in a serpentine (a few seconds to compile;
# written here rather than by the gen_drawings example, which would cost CI a release build)
python3 - "${SEGMENTS:-30000}" <<'PY'
import sys
n, row = int(sys.argv[1]), 100
pts, x, y, d = [(0, 0)], 0, 0, 1
for i in range(1, n + 1):
    if i % (row + 1) == 0:
        y, d = y + 3, -d
    else:
        x += d
    pts.append((x, y))
with open("1000.1P.mpath", "w") as f:
    f.write(f"path 1000.1P {{\n  start (0, 0)  O2 T3 I1,5 B-0,2\n  end ({x}, {y})\n")
    f.writelines(f"  mill ({a[0]}, {a[1]}) -> ({b[0]}, {b[1]})\n" for a, b in zip(pts, pts[1:]))
    f.write("}\n")
PY
printf 'feed = 300\nsweep_speed = 1000\nsweep_height = 10\n' >millpath.toml

# only the drawing and the outputs named: any other file is a leftover
strays() { ls -A | grep -v -x -e 1000.1P.mpath -e millpath.toml -e 1000.1P_Milling.gcode -e out -e err -e old.md5 -e new.md5 || true; }

# the previous output (another feed: an interrupted compile must leave this one or its own
# complete program, never a part)
expect_status 0 "$MILLPATH" compile --feed 250 1000.1P.mpath
md5sum <1000.1P_Milling.gcode >old.md5
start=$(date +%s%N)
expect_status 0 "$MILLPATH" compile 1000.1P.mpath
took_ms=$((($(date +%s%N) - start) / 1000000))
md5sum <1000.1P_Milling.gcode >new.md5
echo "a compile takes $took_ms ms"
expect_status 0 "$MILLPATH" compile --feed 250 1000.1P.mpath

# waits until the compile writes its staged program (at most a minute)
wait_for_stage() {
  local i
  for ((i = 0; i < 6000; i++)); do
    compgen -G '.*.stage1' >/dev/null && return 0
    kill -0 "$1" 2>/dev/null || return 1
    sleep 0.01
  done
  return 1
}

# one interrupted compile: SIGNAL after WHEN ms (or once it stages, for "staged")
interrupt() {
  local sig=$1 when=$2 status=0 staged=no
  "$MILLPATH" compile 1000.1P.mpath >out 2>err &
  local pid=$!
  if [ "$when" = staged ]; then
    wait_for_stage $pid || fail "no staged program seen: $(cat err)"
  else
    sleep "$((when / 1000)).$(printf '%03d' $((when % 1000)))"
  fi
  ls -A | grep -q '\.stage1$' && staged=yes
  kill -s "$sig" $pid 2>/dev/null || true
  wait $pid || status=$?
  case $status in
    0 | 130) ;; # done before the signal came, or interrupted
    *) fail "SIG$sig after $when: exit $status: $(cat err)" ;;
  esac
  [ -z "$(strays)" ] || fail "SIG$sig after $when (exit $status, staging: $staged) left: $(strays)"
  local sum
  sum=$(md5sum <1000.1P_Milling.gcode)
  [ "$sum" = "$(cat old.md5)" ] || [ "$sum" = "$(cat new.md5)" ] ||
    fail "SIG$sig after $when: the output is neither the previous one nor the new one"
  echo "SIG$sig after $when: exit $status, was staging: $staged"
  [ $staged = no ] || interrupted_while_staging=$((interrupted_while_staging + 1))
}

interrupted_while_staging=0
for sig in INT TERM HUP; do interrupt $sig staged; done
# random points over the whole compile (and a little past it)
span=$((took_ms + took_ms / 4 + 1))
for i in $(seq 12); do
  sigs=(INT TERM HUP)
  delay=$((RANDOM * 32768 + RANDOM))
  delay=$((delay % span))
  interrupt "${sigs[i % 3]}" "$delay"
done
[ $interrupted_while_staging -ge 3 ] || fail "only $interrupted_while_staging compiles were interrupted while staging"

# killed outright: the staged program stays, and the next compile removes it
expect_status 0 "$MILLPATH" compile --feed 250 1000.1P.mpath
"$MILLPATH" compile 1000.1P.mpath >out 2>err &
pid=$!
wait_for_stage $pid || fail "no staged program seen"
kill -KILL $pid
wait $pid || true
[ -n "$(strays)" ] || fail "SIGKILL left nothing: the sweep below tests nothing"
echo "SIGKILL left: $(strays)"
[ "$(md5sum <1000.1P_Milling.gcode)" = "$(cat old.md5)" ] || fail "SIGKILL changed the previous output"
expect_status 0 "$MILLPATH" compile 1000.1P.mpath
[ -z "$(strays)" ] || fail "the next compile left: $(strays)"
[ "$(md5sum <1000.1P_Milling.gcode)" = "$(cat new.md5)" ] || fail "the next compile's output is wrong"

# a compile started with SIGHUP ignored (nohup) keeps it ignored
expect_status 0 "$MILLPATH" compile --feed 250 1000.1P.mpath
nohup "$MILLPATH" compile 1000.1P.mpath >out 2>err &
pid=$!
wait_for_stage $pid || fail "no staged program seen"
kill -HUP $pid
wait $pid || fail "nohup compile ended by SIGHUP: $(cat err)"
[ "$(md5sum <1000.1P_Milling.gcode)" = "$(cat new.md5)" ] || fail "the nohup compile's output is wrong"
[ -z "$(strays)" ] || fail "the nohup compile left: $(strays)"
echo "ok: interrupted compiles leave no temporary file"
