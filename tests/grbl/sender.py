#!/usr/bin/env python3
"""Streams a G-code program through GRBL's firmware on its simulator (grbl_sim) as a real
sender does, and prints the motion time GRBL took.

The sender counts characters as GRBL's own doc/script/stream.py does: at most 127 bytes
that GRBL has not answered yet (its receive buffer is 128), one answer (`ok` or `error:N`)
freeing the oldest line. The simulator polls its stdin for a byte with select() and reads it
with getchar(): its stdin must be unbuffered (stdbuf -i0), or bytes wait in stdio's buffer
where select() does not see them until the next write; its answers are unbuffered too
(-o0), or a pipe holds them back. Comments and blanks are stripped, as stream.py does. Before the
program: the machine's `$` settings (each waiting for its `ok`) and `G10 L20 P1` making the
tool's place the program's start (X0 Y0 at the first sweep height), where millpath's
estimate starts it at rest.

The motion time is read from the step file: from the first step to the last change of
position (to within the report interval), minus the dwells (`G4 P…`) the program asks for
after its first move, which an estimate counts separately.

  sender.py --sim grbl_sim [--speedup K] [--setting '$110=5000' ...] PROGRAM
prints `SECONDS` (and the errors GRBL answered, on stderr; exit 1 when there were any).
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


def stalled(step_file, report, limit=1.0):
    """The simulator's steppers stand still in the middle of the motion for `limit` simulated
    seconds: its clock thread ran on while GRBL's main thread prepared no steps (seen on a
    busy computer, where the two threads race). The run is then worthless."""
    try:
        with open(step_file) as f:
            rows = [r for r in f.read().splitlines()[-int(limit / report) - 50:] if r and r[0] != "#"]
    except OSError:
        return False
    if len(rows) < limit / report:
        return False
    first, last = rows[-int(limit / report)], rows[-1]
    t0, t1 = float(first.split()[0]), float(last.split()[0])
    return t1 - t0 >= limit * 0.9 and first.split(None, 1)[1] == last.split(None, 1)[1]


def run(sim, speedup, settings, program, report=0.001):
    lines = [strip(l) for l in open(program, encoding="utf-8", errors="replace")]
    lines = [l for l in lines if l and l != "%"]
    z0 = first_sweep_height(lines)
    pre = list(settings) + [f"G10L20P1X0Y0Z{z0:.3f}"]
    with tempfile.TemporaryDirectory() as tmp:
        steps = os.path.join(tmp, "steps.txt")
        blocks = os.path.join(tmp, "blocks.txt")
        p = subprocess.Popen(
            ["stdbuf", "-i0", "-o0", sim, "-t", str(speedup), "-r", str(report), "-s", steps, "-b", blocks],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
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
                        if moving[0] and stalled(steps, report):
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
            # the machine idle (its status report says so), the simulator is ended: it is asked
            # to (end of input), and stopped when it does not (its GRBL thread may not end); the
            # step file is flushed at every report
            while True:
                p.stdin.write(b"?")
                try:
                    a = answers.get(timeout=10)
                except queue.Empty:
                    if stalled(steps, report):
                        raise Stalled()
                    continue
                if a is None or a.startswith("<Idle"):
                    break
                time.sleep(0.2)
            p.stdin.close()
            try:
                p.wait(timeout=3)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()
        finally:
            if p.poll() is None:
                p.kill()
                p.wait()
        t = motion_time(steps, report)
    return t - program_dwells(lines), errors


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", required=True)
    ap.add_argument("--speedup", type=float, default=10)
    ap.add_argument("--setting", action="append", default=[])
    ap.add_argument("program")
    a = ap.parse_args()
    for attempt in range(4):
        try:
            t, errors = run(a.sim, a.speedup, a.setting, a.program)
            break
        except Stalled:
            print(f"{a.program}: the simulator stalled; again", file=sys.stderr)
    else:
        sys.exit(f"{a.program}: the simulator stalled four times")
    for e in errors:
        print(f"{a.program}: GRBL answered {e}", file=sys.stderr)
    print(f"{t:.4f}")
    sys.exit(1 if errors else 0)


if __name__ == "__main__":
    main()
