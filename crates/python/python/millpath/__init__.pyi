"""Type hints of the millpath package (the functions are documented in their docstrings)."""

from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

Point = Tuple[float, float]
SettingsValue = Union[bool, int, float, str, Sequence[Any], Mapping[str, Any], None]

class MillpathError(ValueError):
    """Malformed input or unusable settings: the located message."""

class MillpathWarning(UserWarning):
    """A warning of a conversion."""

class Diagnostic:
    """One message of the compiler (``millpath check --format json``'s fields)."""

    code: str
    name: str
    severity: str
    message: str
    file: Optional[str]
    line: Optional[int]
    column: Optional[int]
    located: str

class Statistics:
    """One compiled path's statistics lines and estimated time."""

    path: str
    lines: List[str]
    seconds: float
    time: str

class CompileResult:
    """What ``compile`` or ``check`` gives for one drawing."""

    files: Dict[str, str]
    diagnostics: List[Diagnostic]
    statistics: List[Statistics]
    removed_volume: Optional[float]
    info: List[str]
    @property
    def errors(self) -> List[Diagnostic]:
        """The diagnostics of severity error."""
    @property
    def warnings(self) -> List[Diagnostic]:
        """The diagnostics of severity warning."""
    @property
    def ok(self) -> bool:
        """No error."""
    def raise_for_errors(self) -> CompileResult:
        """Raises MillpathError with every located error; else returns self."""

class Finding:
    """One finding of the G-code checker."""

    line: Optional[int]
    severity: str
    code: str
    message: str
    text: str

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

Source = Union[str, bytes, "Path"]

def compile(
    source: Source,
    *,
    file_name: str,
    settings: Optional[Mapping[str, SettingsValue]] = None,
    files: Optional[Mapping[str, Source]] = None,
) -> CompileResult:
    """Compiles one drawing as ``millpath compile`` does, writing nothing."""

def check(
    source: Source,
    *,
    file_name: str,
    settings: Optional[Mapping[str, SettingsValue]] = None,
    files: Optional[Mapping[str, Source]] = None,
) -> CompileResult:
    """Checks every path of one drawing as ``millpath check`` does (no output files)."""

def dxf2text(
    data: bytes, *, file_name: str = ..., extended: bool = ..., lang: str = ...
) -> str:
    """The canonical ``.mpath`` text of a DXF drawing's bytes."""

def text2dxf(
    text: Union[str, Path], into: Optional[bytes] = ..., *, file_name: str = ..., lang: str = ...
) -> bytes:
    """A DXF drawing of a ``.mpath`` text; with ``into``, that drawing's paths replaced."""

def format(text: str, *, file_name: str = ..., lang: str = ...) -> str:
    """The canonical form of a ``.mpath`` text (``millpath fmt``)."""

ClampBox = Union[Tuple[str, Sequence[float], Sequence[float]], Mapping[str, Any]]

def verify(
    gcode: str,
    *,
    dialect_or_post: str,
    clamps: Optional[Sequence[ClampBox]] = None,
    lang: str = ...,
) -> VerifyReport:
    """Checks a G-code program as ``millpath verify`` does."""

def banner() -> str:
    """The version banner written into every program."""

class Arc:
    """An arc around ``center`` of radius ``r``, counter-clockwise from ``start`` to ``end`` degrees."""

    center: Point
    r: float
    start: float
    end: float
    def __init__(self, center: Point, r: float, start: float, end: float) -> None: ...
    def text(self) -> str:
        """The arc's geometry as the language writes it."""

Geometry = Union[Point, Arc]

class Path:
    """A path of the ``.mpath`` language built from code; ``str(path)`` is its canonical text."""

    name: str
    def __init__(self, name: str, start: Point = ..., params: Optional[str] = ...) -> None: ...
    def mill(self, *geometry: Geometry, params: Optional[str] = ..., comment: Optional[str] = ...) -> Path:
        """Mill down to B along the points or one Arc."""
    def mark(self, *geometry: Geometry, params: Optional[str] = ..., comment: Optional[str] = ...) -> Path:
        """Mark down to D along the points or one Arc."""
    def sweep(self, *geometry: Geometry, params: Optional[str] = ..., comment: Optional[str] = ...) -> Path:
        """Move at sweep height along the points or one Arc."""
    def move(self, *geometry: Geometry, comment: Optional[str] = ...) -> Path:
        """A sweep that takes no parameters."""
    def bars(self, *geometry: Geometry, params: Optional[str] = ..., comment: Optional[str] = ...) -> Path:
        """Mill down to B leaving support bars."""
    def sub(self, a: Point, b: Point, name: str, params: Optional[str] = ..., comment: Optional[str] = ...) -> Path:
        """Embed the subpath ``name`` along the line from ``a`` to ``b``."""
    def helix(self, center: Point, d: float, params: Optional[str] = ..., comment: Optional[str] = ...) -> Path:
        """Mill a hole of diameter ``d`` in a helix."""
    def drill(self, center: Point, d: float, params: Optional[str] = ..., comment: Optional[str] = ...) -> Path:
        """Drill a hole of the tool's diameter."""
    def probe(self, at: Point, params: Optional[str] = ..., comment: Optional[str] = ...) -> Path:
        """A z-probe."""
    def turn(self, at: Point, comment: Optional[str] = ...) -> Path:
        """A turn marker."""
    def end(self, at: Point, comment: Optional[str] = ...) -> Path:
        """The end marker."""
    def raw_text(self) -> str:
        """The text as generated, before formatting."""
    def __str__(self) -> str:
        """The canonical text (``millpath fmt``'s)."""
    def __len__(self) -> int: ...

def text(*paths: Path, comment: Optional[str] = ...) -> str:
    """One ``.mpath`` text of several paths, in canonical form."""
