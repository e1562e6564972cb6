"""The notebooks in ``notebooks/`` run, run fast, and are stored clean.

* Every ``notebooks/*.ipynb`` is a page of the documentation site and is executed when the
  site is built (MyST-NB, kernel ``python3``, working directory the notebooks folder): the
  build of ``tests/test_docs.py`` runs them once, and these tests read its execution records,
  so CI does not run them twice. Each must succeed and finish within the time budget: 60 s,
  or the number of seconds in the environment variable ``PERSSON_FAST_NOTEBOOK_BUDGET``
  (``inf`` switches the timing check off). The budget is meant for a warm numba cache; the
  session fixture in ``conftest.py`` warms it before any test.
* A notebook may not leave files in the notebooks folder (figures are shown inline; anything a
  notebook must write goes to a temporary directory).
* Every notebook is stored without outputs, without execution counts and without widget
  state, so that stored results cannot go stale and the repository does not grow with images.
"""
from __future__ import annotations

import json
import math
import os
from pathlib import Path

import pytest

from docs_build import build

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOK_DIR = ROOT / "notebooks"
NOTEBOOKS = sorted(NOTEBOOK_DIR.glob("*.ipynb"))

#: wall-clock budget of one notebook's execution [s]
DEFAULT_BUDGET = 60.0
BUDGET_ENV = "PERSSON_FAST_NOTEBOOK_BUDGET"


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


def _ids(paths):
    return [p.name for p in paths]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=_ids(NOTEBOOKS))
def test_notebook_executes_within_budget(path, record_property):
    budget = _budget()
    result = build()
    record = result.exec_data.get(f"notebooks/{path.stem}")
    assert record is not None, (f"{path.name} was not executed by the documentation build "
                                f"(is it in docs/examples.md's toctree?)")
    assert record.get("succeeded"), f"{path.name} failed:\n{record.get('traceback')}"
    elapsed = float(record["runtime"])
    record_property("seconds", round(elapsed, 2))
    print(f"{path.name}: {elapsed:.1f} s (budget {budget:g} s)")
    assert math.isinf(budget) or elapsed <= budget, (
        f"{path.name} took {elapsed:.1f} s, over the budget of {budget:g} s "
        f"(set {BUDGET_ENV} to change it)"
    )


def test_notebooks_leave_no_files():
    new = build().new_notebook_files
    assert not new, (f"the notebooks wrote {new} into {NOTEBOOK_DIR.name}/; show figures inline "
                     "and write anything else to a temporary directory")


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
