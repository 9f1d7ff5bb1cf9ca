"""Region and line coverage of crates/core/src per stage folder, from `llvm-cov export
-summary-only` JSON (fuzz/run.sh --coverage)."""
import json
import sys
from collections import defaultdict

MARK = "crates/core/src/"

data = json.load(open(sys.argv[1]))["data"][0]["files"]
totals = defaultdict(lambda: [0, 0, 0, 0])
for f in data:
    name = f["filename"]
    if MARK not in name:
        continue
    rest = name.split(MARK, 1)[1]
    stage = rest.split("/")[0] + "/" if "/" in rest else "(top-level files)"
    # adjust-z is a command of its own, not a stage of compile: its own row
    if rest.startswith("probe/adjustz/"):
        stage = "probe/adjustz/"
    s = f["summary"]
    t = totals[stage]
    t[0] += s["regions"]["covered"]
    t[1] += s["regions"]["count"]
    t[2] += s["lines"]["covered"]
    t[3] += s["lines"]["count"]
every = [sum(t[i] for t in totals.values()) for i in range(4)]


def pct(a, b):
    return f"{100.0 * a / b:5.1f} %" if b else "    - "


print(f"  {'stage':<20} {'regions':>9} {'lines':>9}")
for stage in sorted(totals):
    t = totals[stage]
    print(f"  {stage:<20} {pct(t[0], t[1]):>9} {pct(t[2], t[3]):>9}")
print(f"  {'crates/core/src':<20} {pct(every[0], every[1]):>9} {pct(every[2], every[3]):>9}")
