# Helpers for the workflow scripts (sourced, not run on its own).

# fail MESSAGE: ends the workflow with a message.
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# expect_status N COMMAND...: runs COMMAND, fails unless it exits with N; its standard
# output and error are kept in $WORK/out and $WORK/err (and echoed on failure).
expect_status() {
  local want=$1
  shift
  local got=0
  "$@" >"$WORK/out" 2>"$WORK/err" || got=$?
  if [ "$got" -ne "$want" ]; then
    echo "--- stdout" >&2; cat "$WORK/out" >&2
    echo "--- stderr" >&2; cat "$WORK/err" >&2
    fail "exit $got (expected $want): $*"
  fi
}

# need_shared: skips the rest of the workflow (success, with a message) without ../shared.
need_shared() {
  if [ ! -d "$SHARED/conformance" ]; then
    echo "skipped: $SHARED/conformance is absent"
    exit 0
  fi
}

# write_probe_log PROBING "height(x, y, t, …)" linuxcnc|grbl: the log a controller writes at the
# G38s (t: the part's nominal top; cx, cy: the probed area's centre, w, h: its half sizes)
write_probe_log() {
  python3 - "$@" <<'PY'
import re, sys
probing, height, fmt = sys.argv[1], sys.argv[2], sys.argv[3]
# t: the nominal top of the part, as its _Z.txt says
t = float(open(probing.replace("_Probing.gcode", "_Z.txt")).read().split("/T=")[1].split(")")[0])
# x0 y0 x1 y1: the probed area, as the probing program's MILLPATH-HEIGHTMAP comment says
area = dict(re.findall(r" ([XY][01])=(-?[0-9.]+)", next(l for l in open(probing) if l.startswith("(MILLPATH-HEIGHTMAP"))))
x0, y0, x1, y1 = (float(area[k]) for k in ("X0", "Y0", "X1", "Y1"))
w, h = (x1 - x0) / 2 + 1, (y1 - y0) / 2 + 1
cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
x = y = 0.0
if fmt == "grbl":
    print("[G54:-100.000,-50.000,-20.000]")
for l in open(probing):
    if l.startswith("("):
        continue
    for letter, v in re.findall(r"([XY])(-?[0-9.]+)", l):
        if letter == "X":
            x = float(v)
        else:
            y = float(v)
    if l.startswith("G38.2"):
        z = eval(height)
        if fmt == "grbl":
            print(f"[PRB:{x - 100:.3f},{y - 50:.3f},{z - 20:.3f}:1]\nok")
        else:
            print(f"{x:.6f} {y:.6f} {z:.6f} 0 0 0 0 0 0")
PY
}
