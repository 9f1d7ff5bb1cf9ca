"""Hostile input raises a located MillpathError (or TypeError for a wrong type), or comes
back as a diagnostic: never a crash of the interpreter, never a hang."""

import math

import millpath
import pytest

MACHINE = {"feed": 300, "sweep_speed": 1000, "sweep_height": 10}
SLOT = "path 1000.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n  end (30, 0)\n  mill (0, 0) -> (30, 0)\n}\n"


def test_a_syntax_error_raises_with_its_location():
    with pytest.raises(millpath.MillpathError, match=r"^drawing\.mpath:2:19: .*12\.5"):
        millpath.format("path x {\n  mill (0, 0) -> (12,5, 0)\n}\n")
    with pytest.raises(millpath.MillpathError, match=r"part\.mpath:2:"):
        millpath.text2dxf("path x {\n  mill (0, 0) ->\n}\n", file_name="part.mpath")


def test_nan_and_infinity_are_messages():
    p = millpath.Path("1000.1P", start=(0, 0), params="M10x3 O2 T3 B-0,2").mill((0, 0), (math.nan, 1))
    with pytest.raises(millpath.MillpathError, match=r"1000\.1P\.mpath:3:"):
        str(p)
    r = millpath.compile(p.raw_text(), file_name="1.mpath", settings=MACHINE)
    assert not r.ok and not r.files and r.errors[0].line == 3
    p = millpath.Path("1000.1P", start=(math.inf, 0), params="T3 O2")
    assert not millpath.check(p.raw_text(), file_name="1.mpath").ok


def test_unusable_settings_raise():
    with pytest.raises(millpath.MillpathError, match="feed must be > 0"):
        millpath.compile(SLOT, file_name="1.mpath", settings={**MACHINE, "feed": math.nan})
    with pytest.raises(millpath.MillpathError, match="missing machine settings: sweep_height"):
        millpath.compile(SLOT, file_name="1.mpath", settings={"feed": 1, "sweep_speed": 1})
    with pytest.raises(millpath.MillpathError, match="feeed"):
        millpath.compile(SLOT, file_name="1.mpath", settings={**MACHINE, "feeed": 3})
    with pytest.raises(millpath.MillpathError, match="dialect"):
        millpath.compile(SLOT, file_name="1.mpath", settings={**MACHINE, "dialect": "fanuc"})
    with pytest.raises(millpath.MillpathError, match="post"):
        millpath.compile(SLOT, file_name="1.mpath", settings={**MACHINE, "post": "nosuch.toml"})
    with pytest.raises(millpath.MillpathError):
        millpath.compile(SLOT, file_name="1.mpath", settings={**MACHINE, "feed": 10**400})
    with pytest.raises(TypeError):
        millpath.compile(SLOT, file_name="1.mpath", settings={**MACHINE, "feed": object()})
    deep = {}
    d = deep
    for _ in range(100):
        d["machine"] = {}
        d = d["machine"]
    with pytest.raises(TypeError, match="nested too deeply"):
        millpath.compile(SLOT, file_name="1.mpath", settings={**MACHINE, **deep})
    with pytest.raises(millpath.MillpathError, match="file name"):
        millpath.compile(SLOT, file_name="", settings=MACHINE)
    with pytest.raises(TypeError):
        millpath.compile(12, file_name="1.mpath", settings=MACHINE)


def test_settings_in_german():
    with pytest.raises(millpath.MillpathError, match="feed muss > 0 sein"):
        millpath.compile(SLOT, file_name="1.mpath", settings={**MACHINE, "feed": -1, "lang": "de"})
    r = millpath.compile(SLOT.replace("(30, 0)\n  mill", "(31, 0)\n  mill"), file_name="1.mpath",
                         settings={**MACHINE, "lang": "de"})
    assert not r.ok and "Endmarker" in r.errors[0].message or "Ende" in r.errors[0].message


def test_bad_bytes_raise_or_report():
    with pytest.raises(millpath.MillpathError, match="drawing.dxf"):
        millpath.dxf2text(b"\x00\x01 no dxf at all")
    dxf = millpath.text2dxf(SLOT)
    with pytest.raises(millpath.MillpathError):
        millpath.dxf2text(dxf[: len(dxf) // 2])
    # a truncated drawing compiled: a located error, no files
    r = millpath.compile(dxf[: len(dxf) // 2], file_name="1.dxf", settings=MACHINE)
    assert not r.ok and not r.files and r.errors[0].file == "1.dxf"
    # invalid UTF-8 in a text
    r = millpath.compile(b"path 1000.1P {\n  start (0, 0) \xff\xfe\n}\n", file_name="1.mpath",
                         settings=MACHINE)
    assert not r.ok
    with pytest.raises(millpath.MillpathError):
        millpath.text2dxf(SLOT, into=b"garbage")


def test_verify_refuses_unusable_options_and_reads_garbage():
    with pytest.raises(millpath.MillpathError):
        millpath.verify("G0 X0\n", dialect_or_post="fanuc")
    with pytest.raises(millpath.MillpathError):
        millpath.verify("G0 X0\n", dialect_or_post="linuxcnc",
                        clamps=[("v", (0, 0, math.nan), (1, 1, 1))])
    with pytest.raises(millpath.MillpathError):
        millpath.verify("G0 X0\n", dialect_or_post="linuxcnc", clamps=[("v", (2, 2, 2), (1, 1, 1))])
    with pytest.raises(millpath.MillpathError, match=r"clamps\[0\]"):
        millpath.verify("G0 X0\n", dialect_or_post="linuxcnc", clamps=[("v", (0, 0), (1, 1, 1))])
    r = millpath.verify("G1 X1e300 F\nG0 Z\x00\n" * 1000, dialect_or_post="grbl")
    assert r.errors > 0 and r.lines == 2000
    # a post's name reads as its family
    assert millpath.verify("G21\nG90\nG0 Z5\nM2\n", dialect_or_post="mach3").lines == 4


def test_a_million_segments_is_a_message_not_a_hang():
    n = 1_000_000
    lines = [f"  mill ({i}, 0) -> ({i + 1}, 0)\n" for i in range(n)]
    text = (
        "path 1000.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n"
        f"  end ({n}, 0)\n" + "".join(lines) + "}\n"
    )
    r = millpath.compile(text, file_name="1.mpath", settings=MACHINE)
    assert not r.files and r.errors, "a program of a million segments is refused"
    assert any("many" in d.message or "limit" in d.message or "more than" in d.message
               for d in r.errors), [d.message for d in r.errors[:3]]
