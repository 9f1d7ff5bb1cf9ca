"""millpath from Python: compile, check, convert and verify milling paths, and build paths
in code (:class:`Path`).

Every function calls the same Rust crates as the ``millpath`` command line: ``compile``
gives exactly the files ``millpath compile`` writes, ``format`` what ``millpath fmt``
writes. Malformed input raises :class:`MillpathError` (a ``ValueError``) with the located
message; a drawing's own problems come back as diagnostics.
"""

from __future__ import annotations

from ._native import MillpathError, banner
from ._api import (
    CompileResult,
    Diagnostic,
    Finding,
    MillpathWarning,
    Statistics,
    VerifyReport,
    check,
    compile,
    dxf2text,
    format,
    text2dxf,
    verify,
)
from ._builder import Arc, Path, text

__all__ = [
    "Arc",
    "CompileResult",
    "Diagnostic",
    "Finding",
    "MillpathError",
    "MillpathWarning",
    "Path",
    "Statistics",
    "VerifyReport",
    "banner",
    "check",
    "compile",
    "dxf2text",
    "format",
    "text",
    "text2dxf",
    "verify",
]
