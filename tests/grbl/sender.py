#!/usr/bin/env python3
"""Streams a G-code program through GRBL's firmware on its simulator (grbl_sim) as a real
sender does, and prints the motion time GRBL took.

The sender counts characters as GRBL's own doc/script/stream.py does: at most 127 bytes
that GRBL has not answered yet (its receive buffer is 128), one answer (`ok` or `error:N`)
freeing the oldest line. The simulator's answers are unbuffered (stdbuf -o0), or a pipe holds
them back. After the last answer the sender ends its input, and the simulator (that of
tests/grbl/build_sim.sh) ends once GRBL is idle; its clock waits for the sender while GRBL's
planner has room, so the sender's own reaction time is not GRBL's. Comments and blanks are stripped, as stream.py does. Before the
program: the machine's `$` settings (each waiting for its `ok`) and `G10 L20 P1` making the
tool's place the program's start (X0 Y0 at the first sweep height), where millpath's
estimate starts it at rest.

The motion time is read from the step file: from the first step to the last change of
position (to within the report interval), minus the dwells (`G4 P…`) the program asks for
after its first move, which an estimate counts separately.

  sender.py --sim grbl_sim [--speedup K] [--setting '$110=5000' ...] PROGRAM
prints `SECONDS<TAB>STALLS<TAB>STALLED`: the shortest motion time of the clean runs, how often in
that run the steppers stood still from speed because the simulator's GRBL thread fell behind
its clock, or the simulator gave up waiting for its GRBL thread or the sender (0: clean; a run
with stalls is repeated, at most 3 times), and the seconds
those stalls took; the errors GRBL answered go to stderr (exit 1 when there were any).
"""
import argparse
import os
import queue
import re
import subprocess
import sys
import tempfile
import threading
import time

# GRBL's receive buffer is 128 bytes; stream.py keeps to 127
RX_BUFFER = 127


def strip(line):
    return re.sub(r"\s|\(.*?\)|;.*", "", line).upper()


def first_sweep_height(lines):
    for l in lines:
        m = re.fullmatch(r"G0?0Z(-?[0-9.]+)", l)
        if m:
            return float(m.group(1))
    return 0.0


def program_dwells(lines):
    """Seconds of G4 after the first move."""
    moved = False
    total = 0.0
    for l in lines:
        if re.search(r"[XYZ]-?[0-9.]", l) and not l.startswith("G10"):
            moved = True
        m = re.match(r"G0?4P([0-9.]+)", l)
        if m and moved:
            total += float(m.group(1))
    return total


def motion_time(step_file, report):
    """First step to the last step, in simulated seconds. A block's closing line is printed
    when the next block starts (at the end: when the simulator exits), so a closing line long
    after the row before it stands for steps made right after that row: their time is taken
    at the pace of the last steps before."""
    rows = []
    with open(step_file) as f:
        for row in f:
            if row.startswith("#"):
                continue
            parts = row.replace(",", " ").split()
            if len(parts) >= 4:
                rows.append((float(parts[0]), [int(v) for v in parts[1:4]]))
    first = last = None
    pace = 0.0  # seconds per step of the last steps seen
    for (t0, p0), (t1, p1) in zip(rows, rows[1:]):
        steps = max(abs(a - b) for a, b in zip(p0, p1))
        if steps == 0:
            continue
        if first is None:
            first = t0
        if t1 - t0 > 5 * report and last is not None:
            last = t0 + steps * pace
        else:
            pace = (t1 - t0) / steps
            last = t1
    if first is None:
        return 0.0
    return last - first


class Stalled(Exception):
    pass


def stalled(step_file, block_file, report, limit=1.0):
    """The simulator's steppers stand still short of the last block's end for `limit`
    simulated seconds: its clock thread ran on while GRBL's main thread prepared no steps
    (seen on a busy computer, where the two threads race). The run is then worthless."""
    try:
        with open(step_file) as f:
            rows = [r for r in f.read().splitlines()[-int(limit / report) - 50:] if r and r[0] != "#"]
        with open(block_file) as f:
            planned = [r for r in f.read().splitlines() if r.strip()]
    except OSError:
        return False
    if len(rows) < limit / report or not planned:
        return False
    first, last = rows[-int(limit / report)], rows[-1]
    t0, t1 = float(first.split()[0]), float(last.split()[0])
    still = first.split(None, 1)[1] == last.split(None, 1)[1]
    at = [v.strip() for v in last.split(None, 1)[1].split(",")[:3]]
    target = [v.strip() for v in planned[-1].split(",")[:3]]
    return t1 - t0 >= limit * 0.9 and still and at != target


def starved(step_file, report):
    """The stalls of the simulator's steppers: how often, and how long in all (s), they stood
    still for 4 ms or more right after making 3 steps or more in 5 ms. The simulator's GRBL
    thread then did not prepare the next steps in time; a real controller never stops so
    from speed (braking to rest, its last steps before a 4 ms gap come at under a step in
    4 ms). A stall only inserts time: the steppers go on at the speed they stopped at."""
    rows = []
    with open(step_file) as f:
        for row in f:
            if row.startswith("#"):
                continue
            parts = row.replace(",", " ").split()
            if len(parts) >= 4:
                rows.append((float(parts[0]), tuple(int(v) for v in parts[1:4])))
    per_ms = max(1, round(0.001 / report))
    still_for, before = 4 * per_ms, 5 * per_ms
    count, lost = 0, 0.0
    still, counted = 0, False
    for k in range(1, len(rows)):
        regular = rows[k][0] - rows[k - 1][0] < 2 * report
        if rows[k][1] == rows[k - 1][1] and regular:
            still += 1
            if still == still_for and k - still_for - before >= 0:
                a, b = rows[k - still_for - before][1], rows[k - still_for][1]
                # steps in 5 ms by the report rows (a block's closing row, printed when the
                # next block starts, spans more: a stop at a block's end, not a stall)
                span = rows[k - still_for][0] - rows[k - still_for - before][0]
                counted = max(abs(x - y) for x, y in zip(a, b)) >= 3 and span < (before + 1) * report
                count += counted
        else:
            if counted and regular:
                # from the last step to the next, less the pace of one step before it
                lost += rows[k - 1][0] - rows[k - 1 - still][0] - report
            still, counted = 0, False
    return count, lost


def run(sim, speedup, settings, program, report=0.001):
    lines = [strip(l) for l in open(program, encoding="utf-8", errors="replace")]
    lines = [l for l in lines if l and l != "%"]
    z0 = first_sweep_height(lines)
    pre = list(settings) + [f"G10L20P1X0Y0Z{z0:.3f}"]
    with tempfile.TemporaryDirectory() as tmp:
        steps = os.path.join(tmp, "steps.txt")
        blocks = os.path.join(tmp, "blocks.txt")
        # the simulator's own word on its clock (tests/grbl/build_sim.sh: `starved N`)
        sim_log = os.path.join(tmp, "sim.log")
        sim_err = open(sim_log, "w")
        p = subprocess.Popen(
            ["stdbuf", "-i0", "-o0", os.path.abspath(sim), "-t", str(speedup), "-r", str(report), "-s", steps, "-b", blocks],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=sim_err,
            cwd=tmp, bufsize=0)
        try:
            answers = queue.Queue()

            def reader():
                for raw in p.stdout:
                    # each line of GRBL's comes as `# TEXT\r# `
                    a = raw.decode("ascii", "replace").strip().strip("#").strip()
                    if a:
                        if os.environ.get("GRBL_SENDER_DEBUG"):
                            print(f"< {a}", file=sys.stderr, flush=True)
                        answers.put(a)
                answers.put(None)

            threading.Thread(target=reader, daemon=True).start()
            errors = []
            pending = []  # lengths of the lines not answered yet

            moving = [False]

            def answer(timeout=float(os.environ.get("GRBL_SENDER_TIMEOUT", 600))):
                waited = 0.0
                while True:
                    try:
                        a = answers.get(timeout=2)
                    except queue.Empty:
                        waited += 2
                        if moving[0] and stalled(steps, blocks, report):
                            raise Stalled()
                        if waited >= timeout:
                            raise
                        continue
                    if a is None:
                        raise RuntimeError("grbl_sim ended early")
                    if a == "ok" or a.startswith("error"):
                        if a.startswith("error"):
                            errors.append(a)
                        return a

            def send(line):
                if os.environ.get("GRBL_SENDER_DEBUG"):
                    print(f"> {line}", file=sys.stderr, flush=True)
                p.stdin.write((line + "\n").encode())

            # GRBL's banner first (the empty EEPROM's error:7 and the defaults come before it)
            while not answers.get(timeout=60).startswith("Grbl "):
                pass
            # the settings one by one, then the program
            for s in pre:
                send(s)
                answer()
            moving[0] = True
            for l in lines:
                while pending and sum(pending) + len(l) + 1 > RX_BUFFER:
                    answer()
                    pending.pop(0)
                send(l)
                pending.append(len(l) + 1)
            while pending:
                answer()
                pending.pop(0)
            # the end of the input: the simulator ends once the machine is idle (its clock,
            # which waits for the sender while the planner has room, then runs the rest)
            p.stdin.close()
            waited = 0.0
            while True:
                try:
                    p.wait(timeout=2)
                    break
                except subprocess.TimeoutExpired:
                    waited += 2
                    if stalled(steps, blocks, report):
                        raise Stalled()
                    if waited >= float(os.environ.get("GRBL_SENDER_TIMEOUT", 600)):
                        raise
        finally:
            if p.poll() is None:
                p.kill()
                p.wait()
        if os.environ.get("GRBL_SENDER_KEEP"):
            import shutil
            shutil.copy(steps, os.environ["GRBL_SENDER_KEEP"])
        sim_err.close()
        t = motion_time(steps, report)
        stutter, lost = starved(steps, report)
        with open(sim_log) as f:
            stutter += sum(1 for l in f if l.startswith(("starved", "waited")))
    return t - program_dwells(lines), stutter, lost, errors


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--speedup", type=float, default=1000)
    ap.add_argument("--setting", action="append", default=[])
    ap.add_argument("--runs", type=int, default=1,
                    help="time the program this often and print the shortest time (the "
                    "simulator's steppers only ever lose time when its threads race)")
    ap.add_argument("program")
    a = ap.parse_args()
    # clean runs (no stall) and the others; a run with stalls is repeated
    clean, stalled_runs = [], []
    # the errors of each run GRBL answered with errors: a program GRBL's parser refuses is
    # refused again (gvalidate checks every program the same way), while a byte garbled on
    # the simulator's serial line is not (seen once on a loaded CI machine: error:2 on a
    # program gvalidate accepted; most likely its clock and main threads racing on the
    # receive buffer, which an AVR's interrupts never do): run it again
    error_runs = []
    for attempt in range(a.runs + 3):
        try:
            t, stutter, lost, errors = run(a.sim, a.speedup, a.setting, a.program)
        except Stalled:
            print(f"{a.program}: the simulator stalled; again", file=sys.stderr)
            continue
        if errors:
            error_runs.append(errors)
            if len(error_runs) >= 2:
                break
            print(f"{a.program}: GRBL answered {', '.join(errors)} in that run; again", file=sys.stderr)
            continue
        (clean if stutter == 0 else stalled_runs).append((t, stutter, lost))
        if stutter:
            print(f"{a.program}: {stutter} stalls in that run; again", file=sys.stderr)
        if len(clean) == a.runs:
            break
    errors = error_runs[-1] if len(error_runs) >= 2 or (error_runs and not clean and not stalled_runs) else []
    if errors:
        for e in errors:
            print(f"{a.program}: GRBL answered {e}", file=sys.stderr)
        sys.exit(1)
    if error_runs:
        print(f"{a.program}: GRBL answered {', '.join(error_runs[0])} once and not again: "
              "the simulator's serial line, not the program", file=sys.stderr)
    if not clean and not stalled_runs:
        sys.exit(f"{a.program}: the simulator stalled every time")
    if len(clean) > 1:
        spread = (max(clean)[0] - min(clean)[0]) / min(clean)[0]
        print(f"{a.program}: {len(clean)} clean runs, spread {100 * spread:.2f} %", file=sys.stderr)
    t, stutter, lost = min(clean or stalled_runs)
    # the time, how often GRBL's thread left the steppers without steps (0: a clean run), and
    # the time those stalls took
    print(f"{t:.4f}\t{stutter}\t{lost:.4f}")


if __name__ == "__main__":
    main()
