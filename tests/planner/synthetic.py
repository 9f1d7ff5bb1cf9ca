#!/usr/bin/env python3
"""Writes the synthetic programs of the planner oracle (tests/planner/programs/*.ngc):
corners, polygons, many short segments, arcs of small and large radius, tiny helixes and
rapids at feeds from 150 to 3000 mm/min. Run it again after changing it; the programs are
committed so that the Rust test and the oracle read the same moves."""

import math
import os

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "programs")
HEAD = "G17 G21 G90 G94\nG0 Z5\nG0 X0 Y0\n"
TAIL = "G0 Z5\nM2\n"


def f(v):
    return f"{v:.4f}".rstrip("0").rstrip(".")


def write(name, body):
    with open(os.path.join(OUT, name + ".ngc"), "w") as out:
        out.write(f"({name})\n" + HEAD + body + TAIL)


def zigzag(feed, pitch, width, n):
    lines = [f"G1 Z-1 F{f(feed)}"]
    for i in range(n):
        x = width if i % 2 == 0 else 0.0
        lines.append(f"G1 X{f(x)} Y{f((i + 1) * pitch)}")
    return "\n".join(lines) + "\n"


def polygon(feed, sides, radius, turns):
    lines = [f"G1 X{f(radius)} Y0 F{f(feed)}", "G1 Z-1"]
    for k in range(1, sides * turns + 1):
        a = 2 * math.pi * k / sides
        lines.append(f"G1 X{f(radius * math.cos(a))} Y{f(radius * math.sin(a))}")
    return "\n".join(lines) + "\n"


def arcs(feed, radius, n):
    # full circles and a serpentine of half circles
    lines = [f"G1 X{f(radius)} Y0 F{f(feed)}", "G1 Z-1"]
    for _ in range(n):
        lines.append(f"G3 X{f(radius)} Y0 I{f(-radius)} J0")
    y = 0.0
    for i in range(n):
        lines.append(f"G{2 if i % 2 == 0 else 3} X{f(radius)} Y{f(y + 2 * radius)} I0 J{f(radius)}")
        y += 2 * radius
    return "\n".join(lines) + "\n"


def helix(feed, radius, pitch, turns):
    lines = [f"G1 X{f(radius)} Y0 F{f(feed)}", "G1 Z0"]
    for t in range(1, turns + 1):
        lines.append(f"G2 X{f(radius)} Y0 Z{f(-t * pitch)} I{f(-radius)} J0")
    return "\n".join(lines) + "\n"


def rapids(feed, n):
    lines = []
    for i in range(n):
        x, y = (i * 37) % 120, (i * 53) % 80
        lines += [f"G0 X{f(x)} Y{f(y)}", f"G0 Z1", f"G1 Z-2 F{f(feed)}", "G0 Z5"]
    return "\n".join(lines) + "\n"


def main():
    os.makedirs(OUT, exist_ok=True)
    write("zigzag_f150", zigzag(150, 1.0, 8.0, 12))
    write("zigzag_f3000", zigzag(3000, 0.5, 20.0, 80))
    write("zigzag_f1200_fine", zigzag(1200, 0.2, 2.0, 150))
    write("hexagon_f600", polygon(600, 6, 20.0, 5))
    write("polygon_200_f1500", polygon(1500, 200, 15.0, 4))
    write("polygon_36_f3000", polygon(3000, 36, 40.0, 3))
    write("arcs_r1_f600", arcs(600, 1.0, 20))
    write("arcs_r50_f3000", arcs(3000, 50.0, 4))
    write("helix_r0.5_f300", helix(300, 0.5, 0.5, 16))
    write("helix_r2_f1500", helix(1500, 2.0, 1.0, 10))
    write("rapids_f150", rapids(150, 12))
    write("rapids_f2400", rapids(2400, 30))


main()
