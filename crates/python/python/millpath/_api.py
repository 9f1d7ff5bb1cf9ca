"""The functions of the package over the native module: plain values in, classes out."""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

from . import _native
from ._native import MillpathError

Source = Union[str, bytes, "object"]


class MillpathWarning(UserWarning):
    """A warning of a conversion (e.g. a text of a drawing that belongs to no element)."""


@dataclass(frozen=True)
class Diagnostic:
    """One message of the compiler, as ``millpath check --format json`` reports it."""

    code: str
    """``MP001`` …: the message's code (docs: Messages and what they mean)."""
    name: str
    severity: str
    """``"error"`` or ``"warning"``."""
    message: str
    file: Optional[str]
    line: Optional[int]
    """1-based line in the file (a DXF entity's first line; ``None`` for the whole file)."""
    column: Optional[int]
    """1-based column of a ``.mpath`` text (``None`` for DXF entities and whole files)."""
    located: str
    """``file:line:column: message`` as the command line prints it."""

    def __str__(self) -> str:
        return f"{self.severity}: {self.located}"


@dataclass(frozen=True)
class Statistics:
    """One compiled path's statistics (the lines ``compile`` prints) and its time."""

    path: str
    lines: List[str]
    seconds: float
    time: str


@dataclass(frozen=True)
class CompileResult:
    """What ``compile`` (or ``check``) gives for one drawing."""

    files: Dict[str, str]
    """Output file name → text, exactly what ``millpath compile`` writes (none after an error)."""
    diagnostics: List[Diagnostic]
    statistics: List[Statistics]
    removed_volume: Optional[float] = None
    """Material the written program removes, mm³ (the checker's stock model)."""
    info: List[str] = field(default_factory=list)

    @property
    def errors(self) -> List[Diagnostic]:
        """The diagnostics of severity error."""
        return [d for d in self.diagnostics if d.severity == "error"]

    @property
    def warnings(self) -> List[Diagnostic]:
        """The diagnostics of severity warning."""
        return [d for d in self.diagnostics if d.severity == "warning"]

    @property
    def ok(self) -> bool:
        """No error."""
        return not self.errors

    def raise_for_errors(self) -> "CompileResult":
        """Raises :class:`MillpathError` with every located error; else returns ``self``."""
        if self.errors:
            raise MillpathError("\n".join(d.located for d in self.errors))
        return self


@dataclass(frozen=True)
class Finding:
    """One finding of the G-code checker."""

    line: Optional[int]
    severity: str
    code: str
    message: str
    text: str


@dataclass(frozen=True)
class VerifyReport:
    """What ``verify`` finds in a program."""

    lines: int
    moves: int
    errors: int
    warnings: int
    removed_volume: Optional[float]
    findings: List[Finding]

    @property
    def ok(self) -> bool:
        """No error finding."""
        return self.errors == 0


def _source(value: Any, what: str) -> Union[str, bytes]:
    # a builder Path (or anything else with a canonical text) is compiled as its text
    if isinstance(value, (str, bytes)):
        return value
    if isinstance(value, (bytearray, memoryview)):
        return bytes(value)
    from ._builder import Path

    if isinstance(value, Path):
        return str(value)
    raise TypeError(f"{what}: expected str, bytes or millpath.Path, got {type(value).__name__}")


def _files(files: Optional[Mapping[str, Any]]) -> Optional[Dict[str, Union[str, bytes]]]:
    if files is None:
        return None
    if not isinstance(files, Mapping):
        raise TypeError(f"files: expected a dict of name → text or bytes, got {type(files).__name__}")
    return {name: _source(v, f"files[{name!r}]") for name, v in files.items()}


def _result(raw: Dict[str, Any]) -> CompileResult:
    return CompileResult(
        files=dict(raw["files"]),
        diagnostics=[Diagnostic(**d) for d in raw["diagnostics"]],
        statistics=[Statistics(**s) for s in raw["statistics"]],
        removed_volume=raw["removed_volume"],
        info=list(raw["info"]),
    )


def compile(
    source: Any,
    *,
    file_name: str,
    settings: Optional[Mapping[str, Any]] = None,
    files: Optional[Mapping[str, Any]] = None,
) -> CompileResult:
    """Compiles one drawing as ``millpath compile`` does, writing nothing.

    ``source`` is the text of a ``.mpath`` file (``str`` or a :class:`Path`), or the bytes of
    a DXF; ``file_name`` its name (``"3000.mpath"``, ``"plate.dxf"``: the outputs are named
    after it, and subpaths are searched beside it). ``settings`` holds ``millpath.toml``'s
    keys (``feed``, ``sweep_speed`` and ``sweep_height`` are required, as by the command
    line; ``dialect`` or ``post``, ``machine`` as a nested dict …). ``files`` maps the names
    of other files (subpaths' drawings, a post file) to their text or bytes.

    Unusable settings raise :class:`MillpathError`; the drawing's problems are the result's
    ``diagnostics`` (and then ``files`` is empty, as compile writes nothing).
    """
    raw = _native._run(
        _source(source, "source"),
        file_name,
        None if settings is None else dict(settings),
        _files(files),
        False,
    )
    return _result(raw)


def check(
    source: Any,
    *,
    file_name: str,
    settings: Optional[Mapping[str, Any]] = None,
    files: Optional[Mapping[str, Any]] = None,
) -> CompileResult:
    """Checks every path of one drawing as ``millpath check`` does: the diagnostics
    ``compile`` would give, no output files (``files`` of the result is empty). The machine
    values are not required here. Arguments as :func:`compile`."""
    raw = _native._run(
        _source(source, "source"),
        file_name,
        None if settings is None else dict(settings),
        _files(files),
        True,
    )
    return _result(raw)


def dxf2text(
    data: bytes, *, file_name: str = "drawing.dxf", extended: bool = False, lang: str = "en"
) -> str:
    """The canonical ``.mpath`` text of a DXF drawing's bytes (``millpath dxf2text``).

    What the text cannot hold (a text belonging to no element …) is warned about with
    :class:`MillpathWarning`. A file that is no readable DXF raises :class:`MillpathError`.
    ``extended`` reads polylines, blocks and other CAD programs' line types.
    """
    text, diags = _native.dxf2text(_source(data, "data"), file_name, extended, lang)
    for d in diags:
        warnings.warn(Diagnostic(**d).located, MillpathWarning, stacklevel=2)
    return text


def text2dxf(
    text: Any, into: Optional[bytes] = None, *, file_name: str = "drawing.mpath", lang: str = "en"
) -> bytes:
    """A DXF drawing of a ``.mpath`` text (``millpath text2dxf``), as bytes.

    With ``into`` (the bytes of an existing drawing), that drawing with its path objects
    replaced by the text's, everything else kept (``--into``); paths of the drawing that
    the text lacks are refused. Syntax errors raise :class:`MillpathError`.
    """
    src = _source(text, "text")
    if isinstance(src, bytes):
        src = src.decode("utf-8")
    return _native.text2dxf(src, into, file_name, lang)


def format(text: str, *, file_name: str = "drawing.mpath", lang: str = "en") -> str:
    """The canonical form of a ``.mpath`` text, byte for byte what ``millpath fmt`` writes.
    Syntax errors raise :class:`MillpathError` with their locations."""
    if not isinstance(text, str):
        raise TypeError(f"text: expected str, got {type(text).__name__}")
    return _native.format(text, file_name, lang)


ClampBox = Tuple[str, Sequence[float], Sequence[float]]


def verify(
    gcode: str,
    *,
    dialect_or_post: str,
    clamps: Optional[Sequence[Union[ClampBox, Mapping[str, Any]]]] = None,
    lang: str = "en",
) -> VerifyReport:
    """Checks a G-code program as ``millpath verify`` does.

    ``dialect_or_post``: ``reference``, ``linuxcnc`` (or ``rs274``), ``grbl``, ``marlin``,
    or a built-in post's name (its family's rules). ``clamps``: keep-out boxes in machine
    coordinates, each ``(name, (xmin, ymin, zmin), (xmax, ymax, zmax))`` or a dict with
    ``name``, ``min``, ``max`` as in ``[[clamp]]``. Unusable options raise
    :class:`MillpathError`.
    """
    if not isinstance(gcode, str):
        raise TypeError(f"gcode: expected str, got {type(gcode).__name__}")
    boxes = None
    if clamps is not None:
        boxes = []
        for i, c in enumerate(clamps):
            if isinstance(c, Mapping):
                c = (c.get("name", f"clamp {i + 1}"), c["min"], c["max"])
            name, lo, hi = c
            if len(lo) != 3 or len(hi) != 3:
                raise MillpathError(f"clamps[{i}]: min and max are (x, y, z), in mm")
            boxes.append((str(name), tuple(float(v) for v in lo), tuple(float(v) for v in hi)))
    raw = _native.verify(gcode, dialect_or_post, boxes, lang)
    return VerifyReport(
        lines=raw["lines"],
        moves=raw["moves"],
        errors=raw["errors"],
        warnings=raw["warnings"],
        removed_volume=raw["removed_volume"],
        findings=[Finding(**f) for f in raw["findings"]],
    )
