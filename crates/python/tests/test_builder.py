"""The builder: its text is `millpath fmt`'s, it round-trips through DXF, and 1,000 random
builder programs (hypothesis) neither crash nor get other diagnostics than the command
line's `check` gives on the same text."""

import json
import math

import millpath
import pytest
from conftest import run_cli
from hypothesis import HealthCheck, given, settings, strategies as st

MACHINE = {"feed": 300, "sweep_speed": 1000, "sweep_height": 10, "dialect": "linuxcnc"}


def slot():
    return (
        millpath.Path("2001.1P", start=(0, 0), params="M10x3 O2 T3 I1,5 B-0,2")
        .end((30, 0))
        .sweep((0, 0), (5, 0))
        .mill((5, 0), (25, 0), comment="the slot")
        .sweep((25, 0), (30, 0))
    )


def test_text_is_the_formatters(tmp_path):
    p = slot()
    (tmp_path / "2001.mpath").write_text(p.raw_text())
    assert run_cli("fmt", "2001.mpath", cwd=tmp_path).returncode == 0
    assert str(p) == (tmp_path / "2001.mpath").read_text()
    assert str(p).startswith("path 2001.1P {\n  start (0, 0)  M10x3 O2 T3 I1,5 B-0,2\n")
    assert "  mill (5, 0) -> (25, 0)  # the slot\n" in str(p)


def test_every_element_kind_and_an_arc():
    p = (
        millpath.Path("2010.1P", start=(0, 0), params="M10x3 O2 T3 I1,5 B-0,2 D2,5")
        .end((50, 0))
        .sweep((0, 0), (10, 10))
        .sub((10, 10), (40, 10), "2001.1P")
        .sweep((40, 10), (40, 20))
        .mark((40, 20), (10, 20))
        .sweep((10, 20), (30, 40))
        .helix((30, 40), 8, params="I0,5")
        .sweep((30, 40), (60, 30), params="N1")
        .drill((60, 30), 2)
        .sweep((60, 30), (60, 1))
        .mill(millpath.Arc((60, 11), 10, 270, 360))
        .sweep((70, 11), (50, 0))
        .probe((10, 5), params="L1")
    )
    text = str(p)
    assert "  sub (10, 10) -> (40, 10)  >2001.1P\n" in text
    assert "  mill arc (60, 11) r10 from 270 to 360\n" in text
    r = millpath.compile(p, file_name="2010.mpath", settings=MACHINE,
                         files={"2001.mpath": slot()})
    assert r.ok, [str(d) for d in r.diagnostics]
    assert sorted(r.files) == ["2010_Clean.gcode", "2010_Probing.gcode", "2010_Z.txt"]


def test_numbers_are_plain_decimals():
    p = millpath.Path("1.1P", start=(1e-5, 1e16), params="T3 O2").end((0.1 + 0.2, -0.0))
    assert "start (0.00001, 10000000000000000)" in str(p)
    assert "end (0.30000000000000004, -0)" in str(p)


def test_text_round_trips_through_dxf():
    # comments are no part of a drawing: a path without them comes back as it was
    p = millpath.Path("2001.1P", start=(0, 0), params="M10x3 O2 T3 I1,5 B-0,2")
    p.sweep((0, 0), (5, 0)).mill((5, 0), (25, 0)).sweep((25, 0), (28, 3)).drill((28, 3), 2)
    p.sweep((28, 3), (30, 0))
    p.end((30, 0)).probe((3, 3), params="L1")
    assert millpath.dxf2text(millpath.text2dxf(str(p))) == str(p)
    # into an existing drawing: the same drawing back when nothing changed
    dxf = millpath.text2dxf(str(p))
    assert millpath.text2dxf(str(p), into=dxf) == dxf


coordinate = st.one_of(
    st.integers(-200, 200),
    st.floats(-200, 200, allow_nan=False).map(lambda v: round(v, 3)),
    st.sampled_from([0.5, 1e-4, 1e9, -0.0]),
)
point = st.tuples(coordinate, coordinate)
words = st.lists(
    st.sampled_from(["B-0,2", "B1", "D2", "I1", "N1", "F200", "Qx", "S12", "B", "Zz", "O2"]),
    max_size=3,
).map(" ".join)
element = st.one_of(
    st.tuples(st.sampled_from(["mill", "mark", "sweep", "bars"]), st.lists(point, min_size=2, max_size=4), words),
    st.tuples(st.sampled_from(["helix", "drill"]), st.tuples(point, st.sampled_from([2, 3, 8])), words),
    st.tuples(st.just("probe"), st.tuples(point), words),
    st.tuples(st.just("arc"), st.tuples(point, st.integers(1, 20), st.integers(0, 359), st.integers(0, 359)), words),
)
program = st.tuples(
    point,
    st.sampled_from(["M10x3 O2 T3 I1,5 B-0,2", "O2 T3", "M10x3 O2 T3 B-0,2 D2,5", "T3"]),
    st.lists(element, max_size=8),
    st.one_of(st.none(), point),
)

GENERATED = []


def build(spec):
    start, params, elements, end = spec
    p = millpath.Path("4000.1P", start=start, params=params)
    for kind, geometry, ws in elements:
        if kind in ("helix", "drill"):
            getattr(p, kind)(geometry[0], geometry[1], params=ws)
        elif kind == "probe":
            p.probe(geometry[0], params=ws)
        elif kind == "arc":
            c, r, a, b = geometry
            p.mill(millpath.Arc(c, r, a, b), params=ws)
        else:
            getattr(p, kind)(*geometry, params=ws)
    if end is not None:
        p.end(end)
    return p


@settings(max_examples=1000, deadline=None, database=None, derandomize=True,
          suppress_health_check=list(HealthCheck))
@given(program)
def test_random_builder_programs_do_not_crash(spec):
    p = build(spec)
    text = str(p)
    r = millpath.check(text, file_name="4000.mpath", settings=MACHINE)
    assert all(d.severity in ("error", "warning") for d in r.diagnostics)
    c = millpath.compile(text, file_name="4000.mpath", settings=MACHINE)
    assert c.ok == bool(c.files)
    GENERATED.append((text, r.diagnostics))


def test_random_programs_get_the_command_lines_diagnostics(tmp_path):
    if len(GENERATED) < 1000:
        pytest.skip("runs after test_random_builder_programs_do_not_crash")
    (tmp_path / "millpath.toml").write_text(
        'feed = 300\nsweep_speed = 1000\nsweep_height = 10\ndialect = "linuxcnc"\n')
    for i, (text, _) in enumerate(GENERATED):
        d = tmp_path / f"p{i:04}"
        d.mkdir()
        (d / "4000.mpath").write_text(text)
    out = run_cli("check", "--quiet", "--format", "json", ".", cwd=tmp_path)
    report = json.loads(out.stdout)
    by_file = {}
    for d in report["diagnostics"]:
        f = d["location"]["file"].split("/")[-2]
        loc = d["location"]
        by_file.setdefault(f, []).append(
            (d["code"], d["severity"], d["message"], loc.get("line"), loc.get("column")))
    for i, (_, diags) in enumerate(GENERATED):
        ours = [(d.code, d.severity, d.message, d.line, d.column) for d in diags]
        assert ours == by_file.get(f"p{i:04}", []), f"program {i}"
