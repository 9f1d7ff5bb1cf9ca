"""The Windows wheel inside a real Windows CPython (run under Wine by tests/windows.sh):
imports millpath from SITE (where pip installed the win_amd64 wheel), compiles every job of
JOBS (JSON: the drawings, their settings, the dialect) into OUT/<dialect>/ for windows.sh to
compare with the Linux command line byte for byte, and checks that bad input raises.

    python.exe wheel.py SITE JOBS OUT
"""

import json
import math
import os
import sys

site, jobs_file, out = sys.argv[1:4]
sys.path.insert(0, site)
import millpath  # noqa: E402  (from SITE, not from anywhere else)

native = millpath._native.__file__
assert os.path.normcase(native).startswith(os.path.normcase(site)), native
assert native.lower().endswith(".pyd"), native

with open(jobs_file, encoding="utf-8") as f:
    jobs = json.load(f)
written = 0
for job in jobs:
    drawings = {}
    for path in job["drawings"]:
        with open(path, "rb") as f:
            drawings[os.path.basename(path)] = f.read()
    folder = os.path.join(out, job["dialect"])
    os.makedirs(folder, exist_ok=True)
    settings = dict(job["settings"], dialect=job["dialect"])
    for name, data in drawings.items():
        source = data if name.lower().endswith(".dxf") else data.decode("utf-8")
        result = millpath.compile(source, file_name=name, settings=settings, files=drawings)
        if not result.files:
            sys.exit(f"{name} ({job['dialect']}): no files: {result.errors}")
        for file_name, text in result.files.items():
            # bytes, not text mode: Windows' text mode would write CR LF
            with open(os.path.join(folder, file_name), "wb") as f:
                f.write(text.encode("utf-8"))
            written += 1

# malformed input is a Python exception with its location, never a crash of the interpreter
slot = "path 1000.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (30, 0)\n  mill (0, 0) -> (30, 0)\n}\n"
for bad in ({"feed": math.nan, "sweep_speed": 1, "sweep_height": 1}, {"feed": 1}):
    try:
        millpath.compile(slot, file_name="1.mpath", settings=bad)
        sys.exit(f"settings {bad} did not raise")
    except millpath.MillpathError:
        pass
try:
    millpath.format("path x {\n  mill (0, 0) -> (12,5, 0)\n}\n")
    sys.exit("a syntax error did not raise")
except millpath.MillpathError as e:
    assert str(e).startswith("drawing.mpath:2:"), e

print(f"wheel: {written} files from {len(jobs)} jobs, {millpath.banner()!r}, "
      f"CPython {sys.version.split()[0]} on {sys.platform}, {os.path.basename(native)}")
