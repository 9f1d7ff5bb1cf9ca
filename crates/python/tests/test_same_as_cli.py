"""Every example and every shared drawing, in every dialect: the files `millpath.compile`
gives are byte for byte those `millpath compile` writes, and `millpath.check`'s diagnostics
are `millpath check --format json`'s."""

import json

import millpath
import pytest
from conftest import DIALECTS, SHARED, copy_drawings, drawing_sets, run_cli, toml_text

OUTPUT_ENDS = ("_Milling.gcode", "_Probing.gcode", "_Z.txt", "_Clean.gcode")


def test_the_shared_drawings_are_there_or_said_to_be_absent():
    if not (SHARED / "conformance" / "fixtures").is_dir():
        pytest.skip("../shared is absent: only the examples are compared")
    assert any(set_id == "conformance/fixtures" for set_id, *_ in drawing_sets())


@pytest.mark.parametrize("dialect", DIALECTS)
@pytest.mark.parametrize("set_id", [s[0] for s in drawing_sets()])
def test_compile_equals_the_command_line(dialect, set_id, tmp_path):
    _, folder, settings, drawings = next(s for s in drawing_sets() if s[0] == set_id)
    settings = {**settings, "dialect": dialect}
    copy_drawings(drawings, tmp_path)
    (tmp_path / "millpath.toml").write_text(toml_text(settings))
    others = {f.name: f.read_bytes() for f in drawings}
    compared = written = 0
    for f in drawings:
        before = {p.name for p in tmp_path.iterdir()}
        cli = run_cli("compile", f.name, cwd=tmp_path)
        new = {p.name for p in tmp_path.iterdir()} - before
        cli_files = {n: (tmp_path / n).read_text() for n in sorted(new) if n.endswith(OUTPUT_ENDS)}
        for n in new:
            (tmp_path / n).unlink()
        source = f.read_bytes() if f.suffix.lower() == ".dxf" else f.read_text()
        py = millpath.compile(source, file_name=f.name, settings=settings, files=others)
        assert py.files == cli_files, f"{f.name} ({dialect}): the files differ"
        assert (cli.returncode == 0) == bool(py.files), f"{f.name}: {cli.stderr}"
        if cli.returncode != 0:
            assert py.errors, f"{f.name}: the command line failed, Python reports no error"
        compared += 1
        written += bool(py.files)
    assert compared == len(drawings)
    if set_id.startswith("examples"):
        assert written == len(drawings), "every example compiles"


def cli_check(tmp_path, name):
    out = run_cli("check", "--quiet", "--format", "json", name, cwd=tmp_path)
    return json.loads(out.stdout)


def comparable(d):
    if isinstance(d, dict):  # the command line's JSON
        loc = d.get("location", {})
        return (d["code"], d["severity"], d["message"], loc.get("line"), loc.get("column"))
    return (d.code, d.severity, d.message, d.line, d.column)


@pytest.mark.parametrize("set_id", [s[0] for s in drawing_sets()])
def test_check_equals_the_command_line(set_id, tmp_path):
    _, folder, settings, drawings = next(s for s in drawing_sets() if s[0] == set_id)
    settings = {**settings, "dialect": "linuxcnc"}
    copy_drawings(drawings, tmp_path)
    (tmp_path / "millpath.toml").write_text(toml_text(settings))
    others = {f.name: f.read_bytes() for f in drawings}
    for f in drawings:
        report = cli_check(tmp_path, f.name)
        cli = [comparable(d) for d in report_diagnostics(report)]
        py = millpath.check(f.read_bytes(), file_name=f.name, settings=settings, files=others)
        assert [comparable(d) for d in py.diagnostics] == cli, f.name
        assert py.files == {}


def report_diagnostics(report):
    if isinstance(report, list):
        return report
    for key in ("diagnostics", "messages", "findings"):
        if key in report:
            return report[key]
    raise AssertionError(f"unknown check report: {list(report)}")
