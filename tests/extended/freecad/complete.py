#!/usr/bin/env python3
"""Completes FreeCAD's export (export_outline.py) into a path drawing: FreeCAD writes every
layer as CONTINUOUS, so the markers, sweeps and the start text that need other line types
are appended to its ENTITIES section as text, leaving FreeCAD's own bytes as they are.

Usage: complete.py FREECAD.dxf OUT.dxf
"""
import sys

LAYER = "P7001_1P"


def entity(kind, linetype, groups):
    lines = ["  0", kind, "  8", LAYER]
    if linetype:
        lines += ["  6", linetype]
    for code, value in groups:
        lines += [f"{code:>3}", str(value)]
    return "\n".join(lines) + "\n"


def main():
    src, out = sys.argv[1], sys.argv[2]
    text = open(src, encoding="utf-8").read().replace("\r\n", "\n")
    added = entity("CIRCLE", "PHANTOM", [(10, -10.0), (20, 0.0), (30, 0.0), (40, 0.5)])
    added += entity("CIRCLE", "Phantom", [(10, 30.0), (20, 10.0), (30, 0.0), (40, 1.0)])
    for (x0, y0), (x1, y1) in [((-10, 0), (0, 0)), ((0, 0), (10, 10)), ((10, 10), (20, 10)), ((20, 10), (30, 10))]:
        added += entity("LINE", "ACAD_ISO02W100", [(10, x0), (20, y0), (30, 0), (11, x1), (21, y1), (31, 0)])
    added += entity("MTEXT", None, [(10, -10.0), (20, 0.0), (30, 0.0), (40, 0.35), (71, 5), (1, "M10x3 O2 T3 I1,5 B-0,2")])
    start = text.index("ENTITIES\n")
    end = text.index("  0\nENDSEC\n", start)
    with open(out, "w", encoding="utf-8") as f:
        f.write(text[:end] + added + text[end:])


if __name__ == "__main__":
    main()
