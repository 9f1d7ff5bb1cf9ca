"""The three examples of docs/src/python.md ("Paths from Python") run as written: each
compiles clean, and every G-code file it writes passes `millpath.verify` and LinuxCNC's
`rs274` (skipped where rs274 is not installed; tests/rs274.sh installs it)."""

import re
import shutil
import subprocess
import sys

import millpath
import pytest
from conftest import REPO

PAGE = REPO / "docs" / "src" / "python.md"


def examples():
    return re.findall(r"^```python\n(.*?)^```", PAGE.read_text(), re.S | re.M)


def test_the_page_has_three_examples():
    assert len(examples()) == 3


def rs274_accepts(program, cwd):
    r = subprocess.run(
        ["rs274", "-g", program.name], cwd=cwd, stdin=subprocess.DEVNULL,
        capture_output=True, text=True, timeout=120,
    )
    complaints = [l for l in r.stderr.splitlines() if l.strip() and l.strip() != "executing"]
    return r.returncode == 0 and not complaints, complaints


@pytest.mark.parametrize("n", range(3))
def test_example_runs_clean_and_its_gcode_passes_verify_and_rs274(n, tmp_path):
    script = tmp_path / f"example{n}.py"
    script.write_text(examples()[n])
    r = subprocess.run([sys.executable, script.name], cwd=tmp_path, capture_output=True,
                       text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    programs = sorted(tmp_path.glob("*.gcode"))
    assert programs, "the example writes G-code"
    for p in programs:
        report = millpath.verify(p.read_text(), dialect_or_post="linuxcnc")
        assert report.ok and report.warnings == 0, [f.message for f in report.findings]
        assert report.moves > 10
    if shutil.which("rs274") is None:
        pytest.skip("rs274 (linuxcnc-uspace) is not installed")
    for p in programs:
        ok, why = rs274_accepts(p, tmp_path)
        assert ok, f"{p.name}: {why}"


def test_the_plate_round_trips_through_dxf(tmp_path):
    ns = {}
    cwd = __import__("os").getcwd()
    try:
        __import__("os").chdir(tmp_path)
        exec(examples()[2], ns)
    finally:
        __import__("os").chdir(cwd)
    plate = ns["plate"]
    assert millpath.dxf2text(millpath.text2dxf(str(plate))) == str(plate)
    # the drawing written beside the program is the same path
    assert millpath.dxf2text((tmp_path / "3300.dxf").read_bytes()) == str(plate)
