"""The notebooks in ``notebooks/`` run, run fast, and are stored clean.

* Every ``notebooks/*.ipynb`` is executed with nbclient (kernel ``python3``, working directory
  the notebooks folder, at most ``NOTEBOOK_TIMEOUT`` seconds per notebook) and must finish
  within the time budget: 60 s, or the number of seconds in the environment variable
  ``PERSSON_FAST_NOTEBOOK_BUDGET`` (``inf`` switches the timing check off). The budget is meant
  for a warm numba cache; the session fixture in ``conftest.py`` warms it before any test.
* A notebook may not leave files in the notebooks folder (figures are shown inline; anything a
  notebook must write goes to a temporary directory).
* Every notebook is stored without outputs, without execution counts and without widget
  state, so that stored results cannot go stale and the repository does not grow with images.

Skipped when nbclient (or nbformat) is not installed: ``pip install -e ".[notebooks]"``.
"""
from __future__ import annotations

import asyncio
import json
import math
import os
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOK_DIR = ROOT / "notebooks"
NOTEBOOKS = sorted(NOTEBOOK_DIR.glob("*.ipynb"))

#: wall-clock budget of one notebook, kernel start included [s]
DEFAULT_BUDGET = 60.0
BUDGET_ENV = "PERSSON_FAST_NOTEBOOK_BUDGET"
#: hard limit of one notebook's execution [s] (raised to the budget if that is larger)
NOTEBOOK_TIMEOUT = 120.0
KERNEL_NAME = "python3"


def _budget() -> float:
    raw = os.environ.get(BUDGET_ENV, "").strip()
    if not raw:
        return DEFAULT_BUDGET
    try:
        value = float(raw)
    except ValueError:
        raise ValueError(f"{BUDGET_ENV} must be a number of seconds (or 'inf'); got {raw!r}") from None
    if not value > 0:
        raise ValueError(f"{BUDGET_ENV} must be > 0 [s]; got {raw!r}")
    return value


def _files_under(folder: Path) -> set[str]:
    """Relative paths of the files under ``folder``, notebooks and Jupyter checkpoints aside."""
    out = set()
    for path in folder.rglob("*"):
        rel = path.relative_to(folder)
        if ".ipynb_checkpoints" in rel.parts or path.suffix == ".ipynb":
            continue
        out.add(rel.as_posix())
    return out


def _ids(paths):
    return [p.name for p in paths]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=_ids(NOTEBOOKS))
def test_notebook_executes_within_budget(path, monkeypatch, record_property):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")

    budget = _budget()
    timeout = max(NOTEBOOK_TIMEOUT, budget)
    # the kernel imports this checkout of the package and shows figures inline
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join(
        [str(ROOT)] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
    monkeypatch.delenv("MPLBACKEND", raising=False)

    nb = nbformat.read(path, as_version=4)
    client = nbclient.NotebookClient(
        nb,
        kernel_name=KERNEL_NAME,
        timeout=None,          # no per-cell limit: the whole notebook is limited below
        resources={"metadata": {"path": str(NOTEBOOK_DIR)}},
    )
    before = _files_under(NOTEBOOK_DIR)

    async def run():
        return await asyncio.wait_for(client.async_execute(),
                                      None if math.isinf(timeout) else timeout)

    t0 = time.perf_counter()
    try:
        asyncio.run(run())
    except (asyncio.TimeoutError, nbclient.exceptions.DeadKernelError):
        # cancelling the execution at the time limit shuts the kernel down, which nbclient
        # may report as a dead kernel
        if time.perf_counter() - t0 < timeout:
            raise
        pytest.fail(f"{path.name} did not finish within {timeout:g} s")
    elapsed = time.perf_counter() - t0

    record_property("seconds", round(elapsed, 2))
    print(f"{path.name}: {elapsed:.1f} s (budget {budget:g} s)")
    new = sorted(_files_under(NOTEBOOK_DIR) - before)
    assert not new, (f"{path.name} wrote {new} into {NOTEBOOK_DIR.name}/; show figures inline "
                     "and write anything else to a temporary directory")
    assert elapsed <= budget, (
        f"{path.name} took {elapsed:.1f} s, over the budget of {budget:g} s "
        f"(set {BUDGET_ENV} to change it)"
    )


@pytest.mark.parametrize("path", NOTEBOOKS, ids=_ids(NOTEBOOKS))
def test_notebook_is_stored_without_outputs(path):
    nb = json.loads(path.read_text(encoding="utf-8"))
    problems = []
    for i, cell in enumerate(nb.get("cells", [])):
        if cell.get("cell_type") != "code":
            continue
        if cell.get("outputs"):
            problems.append(f"cell {i} has {len(cell['outputs'])} output(s)")
        if cell.get("execution_count") is not None:
            problems.append(f"cell {i} has execution_count {cell['execution_count']}")
    if "widgets" in nb.get("metadata", {}):
        problems.append("the notebook metadata holds widget state")
    assert not problems, (
        f"{path.name} must be stored stripped ({'; '.join(problems)}); clear the outputs, "
        "e.g. jupyter nbconvert --clear-output --inplace " + f"notebooks/{path.name}"
    )


def test_notebooks_exist():
    assert NOTEBOOKS, f"no notebooks found in {NOTEBOOK_DIR.name}/"
