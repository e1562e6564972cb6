"""The package as a user installs it: a wheel and an sdist built from this tree install into a
fresh virtual environment and answer a contact problem there (slow: it builds, creates a
venv and installs the dependencies)."""
from __future__ import annotations

import subprocess
import sys
import venv
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SMOKE = ("import persson_fast as pf; "
         "r = pf.solve_contact(pf.seed_scene(), [1e6], e_star=pf.seed_e_star()); "
         "assert r.success and 0 < r.area[0] < 1, r; "
         "import importlib.resources as ir; "
         "assert ir.files('persson_fast').joinpath('py.typed').is_file(); "
         "print(pf.__version__)")


@pytest.mark.slow
def test_wheel_and_sdist_install_and_run(tmp_path):
    pytest.importorskip("build")
    dist = tmp_path / "dist"
    subprocess.run([sys.executable, "-m", "build", "--outdir", str(dist), str(ROOT)],
                   check=True, capture_output=True, timeout=600)
    wheels, sdists = sorted(dist.glob("*.whl")), sorted(dist.glob("*.tar.gz"))
    assert len(wheels) == 1 and len(sdists) == 1, list(dist.iterdir())
    for name, artefact in (("wheel", wheels[0]), ("sdist", sdists[0])):
        env = tmp_path / f"venv-{name}"
        venv.create(env, with_pip=True)
        python = env / ("Scripts" if sys.platform == "win32" else "bin") / "python"
        subprocess.run([str(python), "-m", "pip", "install", "-q", str(artefact)], check=True,
                       capture_output=True, timeout=900)
        out = subprocess.run([str(python), "-c", SMOKE], check=True, capture_output=True,
                             text=True, timeout=600, cwd=tmp_path)
        assert out.stdout.strip(), name
