#!/usr/bin/env python3
"""Times whole commands, side by side: after WARMUP runs that do not count, the commands run
in turn (A B C A B C ...) RUNS times, so that a drift of the machine's speed hits all alike.
For each: wall seconds (monotonic clock around start and reap) and cpu seconds (user + sys
of the finished child, from wait4), as min / median / max. Ratios are medians of the ratios
taken run by run.

    timecmds.py [-n RUNS] [--warmup N] [--ratio A/B[:TARGET]]... NAME=COMMAND...

COMMAND is run directly when it is a plain command line (words, quotes, leading NAME=value),
else by /bin/sh; its output is thrown away. `--ratio check/tokenizer:<=2` prints
the wall-time ratio of two named commands and, with a target, whether it is met.
"""

import argparse
import os
import shlex
import statistics
import subprocess
import sys
import time


def argv_of(cmd):
    """(environment, argv) of a plain command line (words, quotes, leading NAME=value), so
    that it is timed without a shell in between; None when it needs a shell."""
    if any(c in cmd for c in "|&;<>()$`*?[]{}~\n"):
        return None
    words = shlex.split(cmd)
    env = dict(os.environ)
    while words and "=" in words[0] and words[0].split("=", 1)[0].isidentifier():
        name, value = words.pop(0).split("=", 1)
        env[name] = value
    return (env, words) if words else None


def run_once(cmd):
    plain = argv_of(cmd)
    with open(os.devnull, "wb") as null:
        t0 = time.perf_counter()
        if plain:
            env, argv = plain
            p = subprocess.Popen(argv, env=env, stdin=subprocess.DEVNULL, stdout=null, stderr=null)
        else:
            p = subprocess.Popen(["/bin/sh", "-c", cmd], stdin=subprocess.DEVNULL, stdout=null, stderr=null)
        _, status, usage = os.wait4(p.pid, 0)
        wall = time.perf_counter() - t0
    return wall, usage.ru_utime + usage.ru_stime, os.waitstatus_to_exitcode(status)


def fmt(values):
    return "%8.3f %8.3f %8.3f" % (min(values), statistics.median(values), max(values))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-n", "--runs", type=int, default=5)
    ap.add_argument("--warmup", type=int, default=1)
    ap.add_argument("--ratio", action="append", default=[])
    ap.add_argument("commands", nargs="+", metavar="NAME=COMMAND")
    a = ap.parse_args()
    cmds = []
    for c in a.commands:
        name, sep, cmd = c.partition("=")
        if not sep:
            ap.error("expected NAME=COMMAND: " + c)
        cmds.append((name, cmd))
    for _ in range(a.warmup):
        for _, cmd in cmds:
            run_once(cmd)
    walls = {n: [] for n, _ in cmds}
    cpus = {n: [] for n, _ in cmds}
    codes = {n: set() for n, _ in cmds}
    for _ in range(a.runs):
        for n, cmd in cmds:
            w, c, code = run_once(cmd)
            walls[n].append(w)
            cpus[n].append(c)
            codes[n].add(code)
    width = max(len(n) for n, _ in cmds)
    print("%-*s  %-26s  %-26s  %s" % (width, "", "wall s (min median max)", "user+sys s (min median max)", "exit"))
    for n, _ in cmds:
        print("%-*s  %s  %s  %s" % (width, n, fmt(walls[n]), fmt(cpus[n]), ",".join(map(str, sorted(codes[n])))))
    for r in a.ratio:
        pair, _, target = r.partition(":")
        x, _, y = pair.partition("/")
        if x not in walls or y not in walls:
            ap.error("unknown command in --ratio " + r)
        ratio = statistics.median(wx / wy for wx, wy in zip(walls[x], walls[y]))
        line = "%s/%s wall ratio: %.2f" % (x, y, ratio)
        if target:
            op, bound = (target[:2], target[2:]) if target[:2] in ("<=", ">=") else ("<=", target)
            ok = ratio <= float(bound) if op == "<=" else ratio >= float(bound)
            line += "   (target %s %s: %s)" % (op, bound, "met" if ok else "NOT met")
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
