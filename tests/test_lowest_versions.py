"""The lowest supported versions: pyproject.toml's floors, the import-time check of numba and
CI's second run on exactly the floors (.ci/run, .ci/floors.py) say the same."""
from __future__ import annotations

import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from persson_fast import _jit

ROOT = Path(__file__).resolve().parents[1]
PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]


def _floor(name):
    for requirement in PROJECT["dependencies"]:
        package, _, version = requirement.partition(">=")
        if package.strip() == name:
            return version.strip()
    raise AssertionError(f"pyproject.toml declares no floor for {name}")


def test_numba_floor_is_the_one_the_import_checks():
    assert _jit._release(_floor("numba")) == _jit.NUMBA_MIN


@pytest.mark.parametrize("version, ok", [("0.60.0", False), ("0.58.1", False), ("0.61.0", True),
                                         ("0.61.0rc1", True), ("0.62.0dev0", True),
                                         ("0.68.1", True), ("1.0.0", True)])
def test_release_parsing(version, ok):
    assert (_jit._release(version) >= _jit.NUMBA_MIN) is ok


def test_an_older_numba_is_refused_at_import_with_the_floor_named():
    """numba 0.58-0.60 would import and then fail while lowering the first adhesive kernel
    (no FunctionModel.jit_addr): the package says so at import instead."""
    code = ("import numba; numba.__version__ = '0.60.0'\n"
            "try:\n"
            "    import persson_fast\n"
            "except ImportError as exc:\n"
            "    print(exc)\n")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120, cwd=ROOT)
    assert proc.stdout.strip() == (
        "persson_fast needs numba >= 0.61 (its kernels call compiled functions through their "
        "jit address); found numba 0.60.0: pip install --upgrade 'numba>=0.61'"), proc.stderr


def test_ci_pins_exactly_the_floors():
    proc = subprocess.run([sys.executable, str(ROOT / ".ci" / "floors.py")], capture_output=True,
                          text=True, timeout=60)
    if sys.version_info[:2] != (3, 11):
        assert proc.returncode == 1 and "requires-python" in proc.stderr
        return
    assert proc.returncode == 0, proc.stderr
    pins = proc.stdout.split()
    assert pins == [f"{r.partition('>=')[0].strip()}=={r.partition('>=')[2].strip()}.*"
                    for r in PROJECT["dependencies"]]
    assert {"numpy==1.24.*", "scipy==1.10.*", "numba==0.61.*"} <= set(pins)
    assert PROJECT["requires-python"] == ">=3.11"


def test_ci_runs_the_listed_tests_on_the_floors():
    run = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert ".ci/floors.py" in run and ".ci/lowest-versions-tests.txt" in run
    listed = (ROOT / ".ci" / "lowest-versions-tests.txt").read_text(encoding="utf-8").split()
    assert listed, "the lowest-versions run lists no tests"
    for path in listed:
        assert (ROOT / path).is_file(), path
