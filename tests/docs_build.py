"""One build of the documentation site per test session, shared by the tests that read it.

``build()`` runs the README's docs command (Sphinx with ``-W -n``: every warning and every
unresolved reference is an error; the notebooks and the guide pages are executed) into a
temporary folder, once per process, and returns what the tests need: the exit code, the
output, the output folder and, per executed page, MyST-NB's execution record (runtime in
seconds, success, traceback). It also lists the files that appeared under ``notebooks/``
during the build, since a notebook may not leave files there.
"""
from __future__ import annotations

import atexit
import functools
import os
import pickle
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
NOTEBOOK_DIR = ROOT / "notebooks"
#: the build command of README.md, with the output folder appended
SPHINX_ARGS = ["-W", "-n", "--keep-going", "-b", "html"]
#: the whole build may take this long [s] (notebooks ~45 s, pages ~20 s, API pages ~60 s on
#: a 2-core machine with the kernels cached)
BUILD_TIMEOUT = 1200


@dataclass
class DocsBuild:
    returncode: int
    output: str
    outdir: Path
    exec_data: dict = field(default_factory=dict)      # docname -> execution record
    new_notebook_files: list = field(default_factory=list)


def _files_under(folder: Path) -> set[str]:
    """Relative paths of the files under ``folder``, notebooks and Jupyter checkpoints aside."""
    out = set()
    for path in folder.rglob("*"):
        rel = path.relative_to(folder)
        if ".ipynb_checkpoints" in rel.parts or path.suffix == ".ipynb" or path.is_dir():
            continue
        out.add(rel.as_posix())
    return out


def _exec_data(outdir: Path) -> dict:
    """MyST-NB's execution records per document, from the pickled build environment."""
    env_file = outdir / ".doctrees" / "environment.pickle"
    if not env_file.exists():
        return {}
    with open(env_file, "rb") as f:
        env = pickle.load(f)
    return {doc: dict(meta["exec_data"]) for doc, meta in getattr(env, "nb_metadata", {}).items()
            if meta.get("exec_data")}


@functools.lru_cache(maxsize=None)
def build() -> DocsBuild:
    """Build the site once per process (the tests that need it share the result)."""
    outdir = Path(tempfile.mkdtemp(prefix="persson-fast-docs-"))
    atexit.register(shutil.rmtree, outdir, True)
    before = _files_under(NOTEBOOK_DIR)
    env = {**os.environ,
           "PYTHONPATH": os.pathsep.join([str(ROOT)] + [p for p in os.environ.get(
               "PYTHONPATH", "").split(os.pathsep) if p])}
    env.pop("MPLBACKEND", None)
    env.pop("PERSSON_FAST_DOCS_EXECUTE", None)        # the tests always execute the pages
    proc = subprocess.run([sys.executable, "-m", "sphinx", *SPHINX_ARGS, str(DOCS), str(outdir)],
                          cwd=ROOT, env=env, capture_output=True, text=True,
                          timeout=BUILD_TIMEOUT)
    return DocsBuild(proc.returncode, proc.stdout + proc.stderr, outdir, _exec_data(outdir),
                     sorted(_files_under(NOTEBOOK_DIR) - before))
