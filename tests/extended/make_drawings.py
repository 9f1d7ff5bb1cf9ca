#!/usr/bin/env python3
"""Writes the same drawings with the geometry the reference ignores, for the extended-mode
oracle (tests/extended_oracle.sh).

Usage: make_drawings.py OUT_DIR SRC.dxf...

For every source drawing, a baseline and three variants under OUT_DIR/<variant>/<same file
name>:

  base   the drawing as ezdxf writes it back (the baseline compiled in the reference mode)

  poly   every LINE and ARC of a path layer becomes an LWPOLYLINE (runs of connected
         segments of one layer and line type joined, arcs as bulges, clockwise ones with a
         negative bulge); line-type names become names of other CAD programs
         (Continuous, ACAD_ISO02W100, …)
  block  the lines, arcs and circles of each path layer and line type move into a block on
         layer 0 with line type BYBLOCK, nested in a second block, inserted rotated and
         mirrored; the INSERT carries the layer and the line type
  inch   every coordinate and height divided by 25.4, $INSUNITS = 1 (texts keep their mm
         values)

Existing INSERTs on path layers are removed first (they would add geometry in the extended
mode that the reference mode ignores). OUT_DIR/manifest.json lists, per variant and file,
how many entities the reference mode must warn about.
"""
import json
import math
import os
import re
import sys

import ezdxf
from ezdxf.math import Matrix44

PATH_LAYER = re.compile(r"^([0-9]{4})[.]([0-9]+)([A-Z])$", re.I)
ALIASES = {
    "CONTINUOUS": "Continuous",
    "DASHED": "ACAD_ISO02W100",
    "DASHDOT": "Dashdot",
    "DIVIDE": "ACAD_ISO12W100",
    "BORDER": "ACAD_ISO11W100",
    "HIDDEN": "Hidden",
    "DOT": "ACAD_ISO07W100",
    "PHANTOM": "Phantom",
}
EPS = 1e-9


def path_layer(name):
    base = re.sub(r"~[a-z]+$", "", name, flags=re.I)
    return bool(PATH_LAYER.match(base.replace("_", ".")))


def effective_lt(doc, e):
    lt = e.dxf.get("linetype", "BYLAYER")
    if lt.upper() == "BYLAYER":
        layer = doc.layers.get(e.dxf.layer) if e.dxf.layer in doc.layers else None
        return layer.dxf.get("linetype", "Continuous") if layer else "Continuous"
    return lt


def drop_path_inserts(doc):
    msp = doc.modelspace()
    for e in list(msp.query("INSERT")):
        if path_layer(e.dxf.layer):
            msp.delete_entity(e)


def path_segments(doc):
    msp = doc.modelspace()
    return [e for e in msp if e.dxftype() in ("LINE", "ARC") and path_layer(e.dxf.layer)]


def ends(e):
    """(start, end, bulge) of a LINE or counter-clockwise ARC."""
    if e.dxftype() == "LINE":
        return (e.dxf.start.x, e.dxf.start.y), (e.dxf.end.x, e.dxf.end.y), 0.0
    c, r = e.dxf.center, e.dxf.radius
    a0, a1 = math.radians(e.dxf.start_angle), math.radians(e.dxf.end_angle)
    sweep = (a1 - a0) % (2 * math.pi)
    p0 = (c.x + r * math.cos(a0), c.y + r * math.sin(a0))
    p1 = (c.x + r * math.cos(a1), c.y + r * math.sin(a1))
    return p0, p1, math.tan(sweep / 4)


def same(p, q):
    return abs(p[0] - q[0]) < EPS and abs(p[1] - q[1]) < EPS


def poly_variant(doc):
    """Runs of consecutive connected segments → LWPOLYLINEs; returns how many were made."""
    msp = doc.modelspace()
    segs = path_segments(doc)
    runs = []
    for e in segs:
        key = (e.dxf.layer, e.dxf.get("linetype", "BYLAYER"))
        p0, p1, b = ends(e)
        if e.dxftype() == "ARC" and e.dxf.extrusion.z < 0:
            raise SystemExit("mirrored arcs are not converted")
        last = runs[-1] if runs else None
        if last and last["key"] == key and same(last["pts"][-1][:2], p0):
            last["pts"][-1] = (last["pts"][-1][0], last["pts"][-1][1], b)
            last["pts"].append((p1[0], p1[1], 0.0))
        elif last and last["key"] == key and len(last["pts"]) == 2 and same(last["pts"][0][:2], p1):
            # an arc or line drawn the other way: the run goes backwards
            last["pts"].insert(0, (p0[0], p0[1], b))
        else:
            runs.append({"key": key, "pts": [(p0[0], p0[1], b), (p1[0], p1[1], 0.0)]})
        msp.delete_entity(e)
    for r in runs:
        layer, lt = r["key"]
        attribs = {"layer": layer}
        if lt.upper() != "BYLAYER":
            attribs["linetype"] = lt
        msp.add_lwpolyline([(x, y, 0, 0, b) for x, y, b in r["pts"]], format="xyseb", dxfattribs=attribs)
    rename_linetypes(doc)
    return len(runs)


def rename_linetypes(doc):
    """Every line type gets the spelling of another CAD program."""
    for old, new in ALIASES.items():
        if old in doc.linetypes and new not in doc.linetypes:
            doc.linetypes.add(new, pattern=[0.0], description=new)
    up = {k: v for k, v in ALIASES.items()}
    for layer in doc.layers:
        lt = layer.dxf.get("linetype", "Continuous")
        if lt.upper() in up:
            layer.dxf.linetype = up[lt.upper()]
    for e in doc.modelspace():
        lt = e.dxf.get("linetype", None)
        if lt and lt.upper() in up:
            e.dxf.linetype = up[lt.upper()]


def block_variant(doc, tag):
    """Path geometry into nested, rotated, mirrored blocks; returns the INSERTs made."""
    msp = doc.modelspace()
    groups = {}
    for e in msp:
        if e.dxftype() in ("LINE", "ARC", "CIRCLE") and path_layer(e.dxf.layer):
            groups.setdefault((e.dxf.layer, effective_lt(doc, e)), []).append(e)
    made = 0
    for n, ((layer, lt), ents) in enumerate(groups.items()):
        # distinct insertion points: identical warnings (same text) are reported once
        origin = (37.5 + 10 * n, -12.25)
        rot = 90.0
        # world = T(origin) · R(rot) · mirror_x · scale 2 · inner; ezdxf's `@` applies the
        # left matrix first, so the way back reads left to right
        # the quarter turn written exactly (z_rotate's cos(90°) is 6e-17, not 0)
        turn_back = Matrix44([0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])
        to_inner = (
            Matrix44.translate(-origin[0], -origin[1], 0)
            @ turn_back
            @ Matrix44.scale(-0.5, 0.5, 1)
        )
        inner = doc.blocks.new(name=f"MP_{tag}_IN_{n}")
        outer = doc.blocks.new(name=f"MP_{tag}_OUT_{n}")
        for e in ents:
            c = e.copy()
            c.dxf.layer = "0"
            c.dxf.linetype = "BYBLOCK"
            c.transform(to_inner)
            inner.add_entity(c)
            msp.delete_entity(e)
        outer.add_blockref(inner.name, (0, 0), dxfattribs={"xscale": -2, "yscale": 2, "layer": "0", "linetype": "BYBLOCK"})
        msp.add_blockref(outer.name, origin, dxfattribs={"rotation": rot, "layer": layer, "linetype": lt})
        made += 1
    return made


def inch_variant(doc):
    """Everything in inches; returns 0 (nothing to warn about: units are not an entity)."""
    m = Matrix44.scale(1 / 25.4)
    for e in list(doc.modelspace()):
        try:
            e.transform(m)
        except (NotImplementedError, AttributeError, ezdxf.DXFError):
            pass
    doc.header["$INSUNITS"] = 1
    return 0


def main():
    out, sources = sys.argv[1], sys.argv[2:]
    manifest = {}
    for variant in ("base", "poly", "block", "inch"):
        os.makedirs(os.path.join(out, variant), exist_ok=True)
        manifest[variant] = {}
        for src in sources:
            doc = ezdxf.readfile(src)
            drop_path_inserts(doc)
            if variant == "base":
                n = 0
            elif variant == "poly":
                n = poly_variant(doc)
            elif variant == "block":
                n = block_variant(doc, "B")
            else:
                n = inch_variant(doc)
            name = os.path.basename(src)
            doc.saveas(os.path.join(out, variant, name))
            manifest[variant][name] = n
    with open(os.path.join(out, "manifest.json"), "w", encoding="utf-8") as f:
        json.dump(manifest, f, indent=1, sort_keys=True)
    print(f"{len(sources)} drawings, a baseline and 3 variants written to {out}")


if __name__ == "__main__":
    main()
