#!/usr/bin/python3
"""Times G-code programs with LinuxCNC's own trajectory planner.

Starts LinuxCNC (linuxcnc-uspace) headless as a simulated XYZ machine with the given axis
limits and runs each program to its end; a HAL sampler (sim.hal) records the path speed
(motion.current-vel) once every servo cycle, and a program's planner time is the span of
servo cycles from its first to its last cycle in motion. Prints one line per program:
name, seconds. Run by Debian's /usr/bin/python3 (it has the `linuxcnc` module), as root
or as a user; see tests/planner_oracle.sh.
"""

import argparse
import os
import pwd
import re
import subprocess
import sys
import tempfile
import threading
import time

import linuxcnc

HERE = os.path.dirname(os.path.abspath(__file__))
# the servo period (ns) of the machine being timed; the planner's time is counted in these
PERIOD_NS = 1_000_000
# LinuxCNC's default cutoff for constant-acceleration ramps on short segments (Hz)
RAMP_FREQ = 100.0
# a program that has not ended after this long (wall clock, s) fails the run
PROGRAM_LIMIT = 1800.0

INI = """\
[EMC]
VERSION = 1.1
MACHINE = millpath-planner-oracle

[DISPLAY]
DISPLAY = dummy

[TASK]
TASK = milltask
CYCLE_TIME = 0.001

[RS274NGC]
PARAMETER_FILE = {dir}/sim.var

[EMCIO]
EMCIO = io
CYCLE_TIME = 0.100
TOOL_TABLE = {dir}/tool.tbl

[EMCMOT]
EMCMOT = motmod
SERVO_PERIOD = {period}

[HAL]
HALFILE = {hal}

[KINS]
JOINTS = 3
KINEMATICS = trivkins coordinates=XYZ

[TRAJ]
COORDINATES = XYZ
LINEAR_UNITS = mm
ANGULAR_UNITS = degree
NO_FORCE_HOMING = 1
MAX_LINEAR_VELOCITY = {vmax}
MAX_LINEAR_ACCELERATION = {amax}
ARC_BLEND_RAMP_FREQ = {ramp}
{axes}
"""

AXIS = """
[AXIS_{name}]
MAX_VELOCITY = {v}
MAX_ACCELERATION = {a}
MIN_LIMIT = -100000
MAX_LIMIT = 100000

[JOINT_{joint}]
TYPE = LINEAR
MAX_VELOCITY = {v}
MAX_ACCELERATION = {a}
MIN_LIMIT = -100000
MAX_LIMIT = 100000
HOME_SEQUENCE = 0
"""


def triple(text):
    parts = [float(p) for p in text.split(",")]
    return parts * 3 if len(parts) == 1 else parts


def write_config(d, vel, acc, k):
    """The INI of a machine with `vel` (mm/min) and `acc` (mm/s²) per axis, run `k` times
    faster than the wall clock (see `speed_up`)."""
    vel = [v * k for v in vel]
    acc = [a * k * k for a in acc]
    axes = "".join(
        AXIS.format(name=n, joint=j, v=vel[j] / 60.0, a=acc[j])
        for j, n in enumerate("XYZ")
    )
    with open(os.path.join(d, "tool.tbl"), "w") as f:
        f.write("T1 P1 D3 ;\n")
    ini = os.path.join(d, "sim.ini")
    with open(ini, "w") as f:
        f.write(
            INI.format(
                dir=d,
                period=PERIOD_NS // k,
                ramp=RAMP_FREQ * k,
                hal=os.path.join(HERE, "sim.hal"),
                vmax=max(vel) / 60.0 * 2.0,
                amax=max(acc) * 2.0,
                axes=axes,
            )
        )
    return ini


FEED = re.compile(r"([Ff])\s*([-+]?(?:\d+\.?\d*|\.\d+))")


def speed_up(text, k):
    """The program with every F word `k` times larger (comments left alone).

    The planner moves the same way `k` times faster when every speed is `k` times larger,
    every acceleration `k²` times, the blend ramp's frequency `k` times and the servo period
    `k` times shorter: it visits the same points in the same servo cycles. The oracle counts
    cycles of the unscaled period, so its figures are the unscaled machine's.
    """
    if k == 1:
        return text
    out = []
    for line in text.splitlines(keepends=True):
        parts = re.split(r"(\([^)]*\)|;.*)", line)
        for i in range(0, len(parts), 2):
            parts[i] = FEED.sub(lambda m: f"{m.group(1)}{float(m.group(2)) * k:.6f}", parts[i])
        out.append("".join(parts))
    return "".join(out)


class Sampler(threading.Thread):
    """Reads halsampler's lines (`sample velocity program line`) and keeps, per program,
    the first and last sample in motion (and with `keep`, every sample)."""

    def __init__(self, env, keep):
        super().__init__(daemon=True)
        self.proc = subprocess.Popen(
            ["halsampler", "-t"], stdout=subprocess.PIPE, text=True, env=env
        )
        self.spans = {}
        self.keep = keep
        self.lock = threading.Lock()
        self.last = 0

    def run(self):
        for line in self.proc.stdout:
            parts = line.split()
            if len(parts) != 4:
                continue
            n, v, prog, at = int(parts[0]), float(parts[1]), int(parts[2]), int(parts[3])
            with self.lock:
                self.last = n
                if prog and self.keep is not None:
                    self.keep.setdefault(prog, []).append((v, at))
                if prog and abs(v) > 1e-9:
                    first, _ = self.spans.get(prog, (n, n))
                    self.spans[prog] = (first, n)

    def sample(self):
        with self.lock:
            return self.last


def start_of(prog, default):
    """Where the estimate starts the program: above the origin at the height of its first
    rapid in Z (millpath's programs begin with `G00 Z<sweep height>` and the estimate
    starts there), else `default`."""
    with open(prog) as f:
        for line in f:
            code = re.sub(r"\([^)]*\)|;.*", "", line).upper()
            if not code.strip() or code.strip() == "%":
                continue
            if re.search(r"\bG0*0\b", code) and "Z" in code and "X" not in code:
                m = re.search(r"Z\s*([-+]?[\d.]+)", code)
                if m:
                    return [0.0, 0.0, float(m.group(1))]
            if re.search(r"[XYZ]", code):
                break
    return default


def wait_for(what, check, limit):
    end = time.monotonic() + limit
    while time.monotonic() < end:
        if check():
            return
        time.sleep(0.05)
    raise SystemExit(f"planner oracle: timed out waiting for {what}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--vel", required=True, help="max velocity mm/min: one or x,y,z")
    ap.add_argument("--acc", required=True, help="max acceleration mm/s²: one or x,y,z")
    ap.add_argument(
        "--start",
        default="0,0,10",
        help="where a program starts (x,y,z) when it does not begin with a rapid in Z",
    )
    ap.add_argument(
        "--speedup",
        type=int,
        default=1,
        help="run k times faster than the wall clock (same figures; the machine must keep up)",
    )
    ap.add_argument("--tolerance", type=float, default=0.05, help="G64 P, mm")
    ap.add_argument(
        "--profiles",
        help="folder to write each program's profile to: speed and program line per cycle",
    )
    ap.add_argument("programs", nargs="+")
    args = ap.parse_args()
    vel, acc, start = triple(args.vel), triple(args.acc), triple(args.start)

    d = tempfile.mkdtemp(prefix="millpath-planner-")
    env = dict(os.environ)
    env["HOME"] = d
    env["RTAPI_FIFO_PATH"] = os.path.join(d, "rtapi_fifo")
    if os.geteuid() == 0:
        # rtapi_app refuses to run as root without an unprivileged user to fall back to
        user = env.get("PLANNER_USER", "nobody")
        env["RTAPI_UID"] = str(pwd.getpwnam(user).pw_uid)
        os.chmod(d, 0o777)
    os.environ.update(env)
    k = args.speedup
    if k < 1 or PERIOD_NS % k:
        raise SystemExit("planner oracle: --speedup must divide 1000000")
    ini = write_config(d, vel, acc, k)
    log = open(os.path.join(d, "linuxcnc.log"), "w")
    lcnc = subprocess.Popen(
        ["linuxcnc", "-r", ini], stdin=subprocess.PIPE, stdout=log, stderr=log, env=env, cwd=d
    )
    sampler = None
    try:
        def task_up():
            if lcnc.poll() is not None:
                log.flush()
                sys.stderr.write(open(log.name).read())
                raise SystemExit("planner oracle: linuxcnc ended early")
            # the display comes last; a stat made earlier misses the task's tool table
            return "DUMMY DISPLAY" in open(log.name).read()

        wait_for("LinuxCNC to start", task_up, 120)
        stat = linuxcnc.stat()
        stat.poll()
        cmd = linuxcnc.command()
        errors = linuxcnc.error_channel()
        cmd.state(linuxcnc.STATE_ESTOP_RESET)
        cmd.state(linuxcnc.STATE_ON)
        cmd.wait_complete()
        keep = {} if args.profiles else None
        sampler = Sampler(env, keep)
        sampler.start()
        wait_for("the sampler", lambda: sampler.sample() > 0, 30)

        def idle():
            stat.poll()
            return (
                stat.interp_state == linuxcnc.INTERP_IDLE and stat.queue == 0 and stat.inpos
            )

        for n, prog in enumerate(args.programs, start=1):
            # every program starts at rest at the same place (where the estimate starts)
            cmd.mode(linuxcnc.MODE_MDI)
            cmd.wait_complete()
            cmd.mdi("G90 G0 X{} Y{} Z{}".format(*start_of(prog, start)))
            cmd.wait_complete()
            time.sleep(0.2)
            wait_for("the start position", idle, 60)
            cmd.mode(linuxcnc.MODE_AUTO)
            cmd.wait_complete()
            subprocess.run(["halcmd", "sets", "program-id", str(n)], check=True, env=env)
            # the path tolerance is the machine's: the programs do not set it (an INI
            # startup code's G64 does not last into a program run, so each copy sets it)
            copy = os.path.join(d, f"program{n}.ngc")
            with open(prog) as src, open(copy, "w") as dst:
                text = src.read()
                # after a leading `%` (which must stay the first line)
                head = text[: text.index("\n") + 1] if text.startswith("%") else ""
                body = head + f"G64 P{args.tolerance}\n" + text[len(head) :]
                dst.write(speed_up(body, k))
            cmd.program_open(copy)
            cmd.wait_complete()
            cmd.auto(linuxcnc.AUTO_RUN, 0)
            started = time.monotonic()

            def done():
                stat.poll()
                if stat.paused:
                    cmd.auto(linuxcnc.AUTO_RESUME)
                if time.monotonic() - started > PROGRAM_LIMIT:
                    raise SystemExit(f"planner oracle: {prog} did not end")
                return time.monotonic() - started > 0.5 and idle()

            wait_for(prog, done, PROGRAM_LIMIT + 10)
            # the sampler's FIFO lags the planner a little: wait for later samples
            mark = sampler.sample()
            wait_for("the sampler", lambda: sampler.sample() > mark + 50, 30)
            subprocess.run(["halcmd", "sets", "program-id", "0"], check=True, env=env)
            err = errors.poll()
            if err and err[0] in (linuxcnc.NML_ERROR, linuxcnc.OPERATOR_ERROR):
                raise SystemExit(f"planner oracle: {prog}: {err[1]}")
            lost = subprocess.run(
                ["halcmd", "-s", "getp", "sampler.0.overruns"],
                check=True, env=env, capture_output=True, text=True,
            ).stdout.strip()
            if lost != "0":
                raise SystemExit(f"planner oracle: the sampler lost samples ({lost})")
            first, last = sampler.spans.get(n, (0, -1))
            seconds = (last - first + 1) * PERIOD_NS / 1e9
            print(f"{prog}\t{seconds:.3f}", flush=True)
            if keep is not None:
                os.makedirs(args.profiles, exist_ok=True)
                out = os.path.join(args.profiles, prog.replace("/", "_") + ".vel")
                with open(out, "w") as f:
                    # the line numbers count the G64 line the copy starts with
                    f.writelines(f"{v}\t{at - 1}\n" for v, at in keep.pop(n, []))
    finally:
        if sampler is not None:
            sampler.proc.terminate()
        try:
            lcnc.communicate(b"\n", timeout=60)
        except subprocess.TimeoutExpired:
            lcnc.kill()


if __name__ == "__main__":
    main()
