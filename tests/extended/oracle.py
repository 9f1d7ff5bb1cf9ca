#!/usr/bin/env python3
"""The extended-mode oracle: the same path drawn as LINE/ARC and as polylines/blocks/inches
compiles to identical G-code, and the reference mode warns once per ignored entity.

Usage: oracle.py MILLPATH_BIN DIR

DIR holds what make_drawings.py wrote (base/, poly/, block/, inch/, manifest.json). For
every file of every variant:
  1. `compile --extended` of the variant gives the same output files and the same exit status
     as `compile` of the baseline: byte for byte, or equal once `-0.000` is read as `0.000`
     (an arc rebuilt from a bulge, or a drawing scaled from inches, can land a coordinate
     of 0 on -1e-15 instead of +1e-15; the number printed is the same);
  2. `check --format json` of the variant (reference mode) has exactly as many
     IgnoredEntity warnings as the manifest says, each with a file line.
Prints one line per failure and closes with 'N passed, M failed'.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

NEG_ZERO = re.compile(rb"-0\.000(?![0-9])")
COMMENT = re.compile(rb"\([^)]*\)")
MACHINE = ["--feed", "150", "--sweep-speed", "500", "--sweep-height", "15"]


def compile_outputs(binary, folder, name, extended):
    """Exit status and {output file: bytes} of compiling one file in a copy of its folder."""
    work = tempfile.mkdtemp(prefix="oracle-")
    try:
        for f in os.listdir(folder):
            shutil.copy(os.path.join(folder, f), work)
        before = set(os.listdir(work))
        cmd = [binary, "compile", *MACHINE, *(["--extended"] if extended else []), name]
        p = subprocess.run(cmd, cwd=work, capture_output=True, timeout=120)
        outs = {}
        for f in sorted(set(os.listdir(work)) - before):
            with open(os.path.join(work, f), "rb") as fh:
                outs[f] = fh.read()
        return p.returncode, outs, p.stderr.decode("utf-8", "replace")
    finally:
        shutil.rmtree(work, ignore_errors=True)


def first_difference(a, b):
    al, bl = a.decode("utf-8", "replace").split("\n"), b.decode("utf-8", "replace").split("\n")
    for i in range(max(len(al), len(bl))):
        x = al[i] if i < len(al) else "<end>"
        y = bl[i] if i < len(bl) else "<end>"
        if x != y:
            return f"line {i + 1}: {x!r} vs {y!r}"
    return "identical"


def main():
    binary, root = os.path.abspath(sys.argv[1]), sys.argv[2]
    manifest = json.load(open(os.path.join(root, "manifest.json"), encoding="utf-8"))
    base_dir = os.path.join(root, "base")
    baseline = {}
    passed = failed = 0
    signed_zero = []
    for variant in ("poly", "block", "inch"):
        vdir = os.path.join(root, variant)
        for name, expected_warnings in sorted(manifest[variant].items()):
            if name not in baseline:
                baseline[name] = compile_outputs(binary, base_dir, name, False)
            b_code, b_outs, _ = baseline[name]
            v_code, v_outs, v_err = compile_outputs(binary, vdir, name, True)
            problems = []
            if v_code != b_code:
                problems.append(f"exit {v_code}, baseline {b_code}: {v_err.strip().splitlines()[-3:]}")
            if sorted(v_outs) != sorted(b_outs):
                problems.append(f"outputs {sorted(v_outs)}, baseline {sorted(b_outs)}")
            for f in sorted(set(v_outs) & set(b_outs)):
                if v_outs[f] == b_outs[f]:
                    continue
                if NEG_ZERO.sub(b"0.000", v_outs[f]) == NEG_ZERO.sub(b"0.000", b_outs[f]):
                    where = "comments" if COMMENT.sub(b"", v_outs[f]) == COMMENT.sub(b"", b_outs[f]) else "moves"
                    signed_zero.append(f"{variant}/{f} ({where})")
                else:
                    problems.append(f"{f} differs at {first_difference(b_outs[f], v_outs[f])}")
            p = subprocess.run(
                [binary, "check", "--format", "json", name],
                cwd=vdir,
                capture_output=True,
                timeout=120,
            )
            report = json.loads(p.stdout.decode("utf-8"))
            ignored = [d for d in report["diagnostics"] if d["name"] == "IgnoredEntity"]
            if len(ignored) != expected_warnings:
                problems.append(f"{len(ignored)} IgnoredEntity warnings, expected {expected_warnings}")
            if any(not d.get("location", {}).get("line") for d in ignored):
                problems.append("a warning without a file line")
            if problems:
                failed += 1
                print(f"FAIL {variant}/{name}: " + "; ".join(problems))
            else:
                passed += 1
    if signed_zero:
        print(f"equal except the sign of a printed zero: {', '.join(signed_zero)}")
    print(f"{passed} passed, {failed} failed")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
