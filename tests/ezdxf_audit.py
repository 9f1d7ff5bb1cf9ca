#!/usr/bin/env python3
"""ezdxf as the oracle for DXF files written by millpath: every file must load and its audit
must report no error and no fix. Usage: ezdxf_audit.py FILE_OR_DIR...; prints one line per
file and a summary line 'N passed, M failed'."""
import os
import sys

import ezdxf


def files(args):
    for a in args:
        if os.path.isdir(a):
            for f in sorted(os.listdir(a)):
                if f.lower().endswith(".dxf"):
                    yield os.path.join(a, f)
        else:
            yield a


def main():
    passed = failed = 0
    for f in files(sys.argv[1:]):
        try:
            doc = ezdxf.readfile(f)
            auditor = doc.audit()
            problems = [f"error: {e.message}" for e in auditor.errors] + [f"fix: {e.message}" for e in auditor.fixes]
        except Exception as e:  # noqa: BLE001 - any failure to read is a failure
            problems = [f"cannot read: {e}"]
        if problems:
            failed += 1
            print(f"FAIL {f}: {'; '.join(problems[:5])}")
        else:
            passed += 1
            print(f"ok   {f}")
    print(f"{passed} passed, {failed} failed")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
