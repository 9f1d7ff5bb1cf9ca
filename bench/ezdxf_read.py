#!/usr/bin/env python3
"""The ezdxf side of bench/check_vs_tokenizer.sh: ezdxf.readfile on every file given (a file
ezdxf refuses is counted, not fatal). Prints how many files were read and how many entities."""

import sys

import ezdxf

read = entities = refused = 0
for f in sys.argv[1:]:
    try:
        doc = ezdxf.readfile(f)
    except Exception as e:  # a broken test drawing: ezdxf's verdict, not ours
        print(f"{f}: {type(e).__name__}: {e}", file=sys.stderr)
        refused += 1
        continue
    read += 1
    entities += len(doc.modelspace())
print(f"ezdxf read {read} file(s), {entities} model-space entities; refused {refused}")
