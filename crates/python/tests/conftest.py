"""Shared fixtures of the package's tests (run by tests/python.sh in a fresh venv with the
package installed as the README says): the command line to compare with, the repository's
examples and the shared drawings (skipped without ../shared)."""

import os
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
SHARED = REPO.parent / "shared"
MACHINE = {"feed": 150, "sweep_speed": 500, "sweep_height": 15}
DIALECTS = ["reference", "linuxcnc", "grbl"]


def millpath_bin() -> str:
    b = os.environ.get("MILLPATH_BIN") or str(REPO / "target" / "release" / "millpath")
    if not Path(b).exists():
        pytest.skip(f"no millpath binary at {b} (cargo build --release -p millpath)")
    return b


def run_cli(*args, cwd):
    return subprocess.run(
        [millpath_bin(), *args], cwd=cwd, capture_output=True, text=True, timeout=300
    )


def toml_text(settings: dict) -> str:
    """The millpath.toml the command line reads for the same settings (flat keys only)."""
    lines = []
    for k, v in settings.items():
        lines.append(f"{k} = {v!r}" if not isinstance(v, str) else f'{k} = "{v}"')
    return "\n".join(lines) + "\n"


def drawing_sets():
    """(id, folder, settings, drawings): the examples with their own millpath.toml values,
    the shared fixtures and samples with the machine values of tests/rs274.sh."""
    import tomllib

    sets = []
    for ex in ("plate", "text"):
        d = REPO / "examples" / ex
        with open(d / "millpath.toml", "rb") as f:
            s = tomllib.load(f)
        files = sorted(p for p in d.iterdir() if p.suffix in (".dxf", ".mpath"))
        sets.append((f"examples/{ex}", d, s, files))
    for sub in ("conformance/fixtures", "samples"):
        d = SHARED / sub
        if d.is_dir():
            files = sorted(p for p in d.iterdir() if p.suffix.lower() == ".dxf")
            sets.append((sub, d, dict(MACHINE), files))
    return sets


@pytest.fixture
def workdir(tmp_path):
    return tmp_path


def copy_drawings(files, into: Path):
    for f in files:
        dest = into / f.name
        shutil.copyfile(f, dest)
        os.chmod(dest, 0o644)
