"""The path builder: a path of the ``.mpath`` language written from code.

The builder checks nothing itself (the compiler does, and its diagnostics point at the
generated text): it writes one element line per call and ``str(path)`` is that text in
canonical form, byte for byte what ``millpath fmt`` gives, so a generated part diffs and
round-trips like a hand-written one. The markers (start, end, turns, probes) are written
first, in the order ``dxf2text`` gives them (kind, then position), then the segments and
holes in the order they were added: a path built in the order it is travelled comes back
from a DXF as the same text (comments aside: a drawing has none).
"""

from __future__ import annotations

import math
from typing import List, Optional, Sequence, Tuple, Union

Point = Tuple[float, float]


def _number(v: float) -> str:
    """A coordinate as the language writes it: a plain decimal (never ``1e-05``); NaN and
    the infinities as written, for the compiler to report."""
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise TypeError(f"expected a number, got {type(v).__name__}")
    if isinstance(v, int):
        return str(v)
    if not math.isfinite(v):
        return str(v)
    r = repr(v)
    if "e" in r or "E" in r:
        # the shortest exact decimal of the same float, without exponent
        r = f"{v:.400f}".rstrip("0").rstrip(".")
        if r in ("-0", ""):
            r = "0"
    if r.endswith(".0"):
        r = r[:-2]
    return r


def _point(p: Sequence[float]) -> str:
    if len(p) != 2:
        raise ValueError(f"a point is (x, y), got {p!r}")
    return f"({_number(p[0])}, {_number(p[1])})"


def _params(params: Optional[str]) -> str:
    if params is None or params == "":
        return ""
    if not isinstance(params, str):
        raise TypeError(f"params: expected str, got {type(params).__name__}")
    if "\n" in params or "\r" in params:
        raise ValueError("params: one line of parameter text")
    return "  " + params


class Arc:
    """An arc around ``center`` of radius ``r``, counter-clockwise from ``start`` to ``end``
    degrees (as DXF stores arcs): the geometry of a ``mill``, ``mark``, ``sweep`` … element
    in place of a list of points."""

    def __init__(self, center: Point, r: float, start: float, end: float) -> None:
        self.center = center
        self.r = r
        self.start = start
        self.end = end

    def text(self) -> str:
        return (
            f"arc {_point(self.center)} r{_number(self.r)} "
            f"from {_number(self.start)} to {_number(self.end)}"
        )


Geometry = Union[Point, Arc]


class Path:
    """A path of the ``.mpath`` language built from code.

    ``Path("3000.1P", start=(0, 0), params="M10x3 O2 T3 I1,5 B-0,2 F150")`` begins the path
    with its start marker and the path's parameters. Each method adds element lines and
    returns the path, so calls chain. ``str(path)`` is the canonical text.
    """

    def __init__(self, name: str, start: Point = (0, 0), params: Optional[str] = None) -> None:
        if not isinstance(name, str) or not name or any(c.isspace() for c in name):
            raise ValueError(f"a path name is one word (e.g. 3000.1P), got {name!r}")
        self.name = name
        # markers (sorted as dxf2text sorts them), then segments and holes as added
        self._markers: List[Tuple[tuple, str]] = []
        self._segment_lines: List[str] = []
        self._marker(0, start, 0.5, f"start {_point(start)}{_params(params)}", params, None)

    # the element lines ---------------------------------------------------------------

    @staticmethod
    def _with_comment(line: str, comment: Optional[str]) -> str:
        if comment:
            if "\n" in comment or "\r" in comment:
                raise ValueError("comment: one line")
            line = f"{line}  # {comment}"
        return line

    def _marker(
        self, rank: int, at: Point, r: float, line: str, params: Optional[str], comment: Optional[str]
    ) -> "Path":
        # dxf2text's order of the elements that are no segments: kind, then x, y, radius,
        # then the parameter words (convert/mod.rs, canonical_cmp)
        try:
            key = (rank, float(at[0]), float(at[1]), float(r), (params or "").split())
        except (TypeError, ValueError, IndexError):
            key = (rank, 0.0, 0.0, 0.0, [])
        key = tuple(math.inf if isinstance(v, float) and math.isnan(v) else v for v in key)
        self._markers.append((key, self._with_comment(line, comment)))
        return self

    def _add(self, line: str, comment: Optional[str]) -> "Path":
        self._segment_lines.append(self._with_comment(line, comment))
        return self

    def _segments(
        self,
        kind: str,
        geometry: Sequence[Geometry],
        params: Optional[str],
        comment: Optional[str],
        tail: str = "",
    ) -> "Path":
        if len(geometry) == 1 and isinstance(geometry[0], Arc):
            return self._add(f"{kind} {geometry[0].text()}{tail}{_params(params)}", comment)
        if len(geometry) < 2 or any(isinstance(g, Arc) for g in geometry):
            raise ValueError(f"{kind}: two or more points, or one Arc")
        for a, b in zip(geometry, geometry[1:]):
            self._add(f"{kind} {_point(a)} -> {_point(b)}{tail}{_params(params)}", comment)
        return self

    def mill(self, *geometry: Geometry, params: Optional[str] = None, comment: Optional[str] = None) -> "Path":
        """Mill down to B along the points (one line element per pair) or one :class:`Arc`."""
        return self._segments("mill", geometry, params, comment)

    def mark(self, *geometry: Geometry, params: Optional[str] = None, comment: Optional[str] = None) -> "Path":
        """Mark down to D (a shallow cut) along the points or one :class:`Arc`."""
        return self._segments("mark", geometry, params, comment)

    def sweep(self, *geometry: Geometry, params: Optional[str] = None, comment: Optional[str] = None) -> "Path":
        """Move at sweep height along the points or one :class:`Arc` (parameters S, N)."""
        return self._segments("sweep", geometry, params, comment)

    def move(self, *geometry: Geometry, comment: Optional[str] = None) -> "Path":
        """A sweep that takes no parameters."""
        return self._segments("move", geometry, None, comment)

    def bars(self, *geometry: Geometry, params: Optional[str] = None, comment: Optional[str] = None) -> "Path":
        """Mill down to B leaving support bars up to D (P, U) along the points or one Arc."""
        return self._segments("bars", geometry, params, comment)

    def sub(
        self,
        a: Point,
        b: Point,
        name: str,
        params: Optional[str] = None,
        comment: Optional[str] = None,
    ) -> "Path":
        """Embed the subpath ``name`` along the line from ``a`` to ``b``."""
        if not isinstance(name, str) or not name or any(c.isspace() for c in name):
            raise ValueError(f"sub: a path name is one word, got {name!r}")
        return self._segments("sub", (a, b), params, comment, tail=f"  >{name}")

    def helix(self, center: Point, d: float, params: Optional[str] = None, comment: Optional[str] = None) -> "Path":
        """Mill a hole of diameter ``d`` (> the tool's O) down to B in a helix."""
        return self._add(f"helix {_point(center)} d{_number(d)}{_params(params)}", comment)

    def drill(self, center: Point, d: float, params: Optional[str] = None, comment: Optional[str] = None) -> "Path":
        """Drill a hole of the tool's diameter (``d`` = O) down to B."""
        return self._add(f"drill {_point(center)} d{_number(d)}{_params(params)}", comment)

    def probe(self, at: Point, params: Optional[str] = None, comment: Optional[str] = None) -> "Path":
        """A z-probe at ``at`` (parameters T, H, L, Z)."""
        return self._marker(3, at, 3, f"probe {_point(at)}{_params(params)}", params, comment)

    def turn(self, at: Point, comment: Optional[str] = None) -> "Path":
        """A turn marker: at this dead end the path returns to the last branch point."""
        return self._marker(2, at, 0.75, f"turn {_point(at)}", None, comment)

    def end(self, at: Point, comment: Optional[str] = None) -> "Path":
        """The end marker of the path."""
        return self._marker(1, at, 1, f"end {_point(at)}", None, comment)

    # the text ------------------------------------------------------------------------

    def raw_text(self) -> str:
        """The text as generated, before formatting (what ``str`` formats)."""
        markers = [line for _, line in sorted(self._markers, key=lambda m: m[0])]
        body = "".join(f"  {line}\n" for line in markers + self._segment_lines)
        return f"path {self.name} {{\n{body}}}\n"

    def __str__(self) -> str:
        from ._api import format

        return format(self.raw_text(), file_name=f"{self.name}.mpath")

    def __len__(self) -> int:
        return len(self._markers) + len(self._segment_lines)

    def __repr__(self) -> str:
        return f"<millpath.Path {self.name}: {len(self)} elements>"


def text(*paths: Path, comment: Optional[str] = None) -> str:
    """One ``.mpath`` text of several paths (a library, or a part and its subpaths), in
    canonical form; ``comment`` as the file's first lines."""
    from ._api import format

    head = ""
    if comment:
        head = "".join(f"# {line}\n" for line in comment.splitlines())
    return format(head + "".join(p.raw_text() for p in paths))
