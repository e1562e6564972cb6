"""The documentation is tested: it builds, it covers the API, and every example in it runs.

* The site builds with the README's docs command (``sphinx -W -n``: a warning or an
  unresolved reference fails), executing the notebooks and every guide page with code.
* Every name of ``persson_fast.__all__`` and every public name of ``persson_fast.embed`` has
  an entry in the API reference (its object inventory), and each function and class a page.
* Every Python block of README.md runs on its own, as a script in an empty folder; the
  scripts the guide pages include run as scripts too; the guide pages hold no Python block
  that is not executed.
* The examples in public docstrings (``>>>``) pass as doctests.
* The public API has parameter type hints; the docs command in README.md is the one built.
"""
from __future__ import annotations

import doctest
import inspect
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

import persson_fast as pf
from persson_fast import embed

from docs_build import DOCS, ROOT, SPHINX_ARGS, build

README = ROOT / "README.md"
#: seconds one README block or included script may take (a warm numba cache)
SCRIPT_TIMEOUT = 300


def _readme_python_blocks() -> list[str]:
    text = README.read_text(encoding="utf-8")
    return re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)


def _public_embed_names() -> list[str]:
    return list(embed.__all__)


# --------------------------------------------------------------------------------------------
# the site
# --------------------------------------------------------------------------------------------


def test_docs_build_without_warnings():
    result = build()
    assert result.returncode == 0, (
        "the documentation build failed (sphinx -W -n); its last lines:\n"
        + "\n".join(result.output.splitlines()[-60:]))


def test_every_executed_page_succeeded():
    result = build()
    assert result.exec_data, "no page was executed (MyST-NB execution records missing)"
    failed = {doc: rec.get("traceback") for doc, rec in result.exec_data.items()
              if not rec.get("succeeded")}
    assert not failed, f"pages whose execution failed: {failed}"
    guide_pages = {p.relative_to(DOCS).with_suffix("").as_posix()
                   for p in DOCS.rglob("*.md")
                   if "file_format: mystnb" in p.read_text(encoding="utf-8")}
    assert guide_pages <= set(result.exec_data), sorted(guide_pages - set(result.exec_data))


def _inventory(outdir: Path) -> set[str]:
    from sphinx.util.inventory import InventoryFile

    with open(outdir / "objects.inv", "rb") as f:
        inv = InventoryFile.load(f, "", os.path.join)
    names = set()
    for entries in inv.values() if isinstance(inv, dict) else inv.data.values():
        names.update(entries)
    return names


def test_every_public_name_has_an_api_entry():
    result = build()
    assert result.returncode == 0, "the build failed; see test_docs_build_without_warnings"
    names = _inventory(result.outdir)
    wanted = [f"persson_fast.{n}" for n in pf.__all__]
    wanted += [f"persson_fast.embed.{n}" for n in _public_embed_names()]
    missing = [n for n in wanted if n not in names]
    assert not missing, f"public names without an API entry: {missing}"
    pages = result.outdir / "api" / "generated"
    no_page = [n for n in wanted if callable(_object(n)) and not (pages / f"{n}.html").exists()]
    assert not no_page, f"public functions and classes without a page of their own: {no_page}"


def _object(dotted: str):
    module, _, name = dotted.rpartition(".")
    return getattr(embed if module == "persson_fast.embed" else pf, name)


def test_readme_names_the_docs_command():
    text = README.read_text(encoding="utf-8")
    command = "python -m sphinx " + " ".join(SPHINX_ARGS) + " docs docs/_build/html"
    assert command in text, f"README.md must give the docs command {command!r}"
    assert 'python -m pip install -e ".[docs]"' in text


def test_readme_is_a_front_page():
    lines = README.read_text(encoding="utf-8").splitlines()
    assert len(lines) <= 160, f"README.md has {len(lines)} lines; keep it a front page"


# --------------------------------------------------------------------------------------------
# examples run
# --------------------------------------------------------------------------------------------


def _run_script(source: str, tmp_path: Path, name: str) -> subprocess.CompletedProcess:
    script = tmp_path / name
    script.write_text(source, encoding="utf-8")
    env = {**os.environ, "MPLBACKEND": "Agg",
           "PYTHONPATH": os.pathsep.join([str(ROOT)] + [p for p in os.environ.get(
               "PYTHONPATH", "").split(os.pathsep) if p])}
    return subprocess.run([sys.executable, str(script)], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=SCRIPT_TIMEOUT)


README_BLOCKS = _readme_python_blocks()


def test_readme_has_python_examples():
    assert README_BLOCKS, "README.md has no ```python block"


@pytest.mark.parametrize("index", range(len(README_BLOCKS)))
def test_readme_block_runs_on_its_own(index, tmp_path):
    proc = _run_script(README_BLOCKS[index], tmp_path, f"readme_block_{index}.py")
    assert proc.returncode == 0, (f"README.md's Python block {index + 1} failed as a script:\n"
                                  f"{README_BLOCKS[index]}\n--- stderr ---\n{proc.stderr[-3000:]}")
    leftovers = sorted(p.name for p in tmp_path.iterdir() if p.name != f"readme_block_{index}.py")
    assert not leftovers, f"README block {index + 1} left files behind: {leftovers}"


INCLUDED_SCRIPTS = sorted(DOCS.rglob("*.py"))
INCLUDED_SCRIPTS = [p for p in INCLUDED_SCRIPTS if p.name != "conf.py"]


@pytest.mark.parametrize("path", INCLUDED_SCRIPTS, ids=[p.name for p in INCLUDED_SCRIPTS])
def test_included_script_runs(path, tmp_path):
    proc = _run_script(path.read_text(encoding="utf-8"), tmp_path, path.name)
    assert proc.returncode == 0, f"{path.relative_to(ROOT)} failed:\n{proc.stderr[-3000:]}"


def test_guide_pages_hold_no_unexecuted_python():
    """A Python example in a page is a code cell (executed by the build) or an included
    script (run above), never a static block that could drift from the code."""
    offenders = []
    for page in DOCS.rglob("*.md"):
        text = page.read_text(encoding="utf-8")
        if re.search(r"^```(python|py|ipython3?|\{code-block\}\s*python)\s*$", text, flags=re.M):
            offenders.append(page.relative_to(DOCS).as_posix())
    assert not offenders, f"static Python blocks (make them code cells): {offenders}"


def _public_objects():
    for name in pf.__all__:
        yield f"persson_fast.{name}", getattr(pf, name)
    for name in embed.__all__:
        yield f"persson_fast.embed.{name}", getattr(embed, name)


def test_docstring_examples_pass():
    finder, runner = doctest.DocTestFinder(), doctest.DocTestRunner(
        optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    ran = 0
    for name, obj in _public_objects():
        if isinstance(obj, (dict, float, str)) or ">>>" not in (obj.__doc__ or ""):
            continue
        for test in finder.find(obj, name, globs={}):
            ran += len(test.examples)
            runner.run(test)
    assert ran, "no docstring example found"
    assert runner.failures == 0, f"{runner.failures} docstring example(s) failed"


# --------------------------------------------------------------------------------------------
# type hints
# --------------------------------------------------------------------------------------------


def _functions():
    """Public functions, and the constructors and public methods of the surface classes."""
    for name, obj in _public_objects():
        if isinstance(obj, (dict, float, str)):
            continue
        if inspect.isclass(obj):
            if issubclass(obj, pf.Surface):
                for attr, member in vars(obj).items():
                    method = inspect.isfunction(member) or isinstance(member, classmethod)
                    if method and (attr == "__init__" or not attr.startswith("_")):
                        yield f"{name}.{attr}", getattr(obj, attr)
            continue
        yield name, getattr(obj, "py_func", obj)      # a numba dispatcher: its Python function


@pytest.mark.parametrize("name, func", list(_functions()), ids=[n for n, _ in _functions()])
def test_public_function_parameters_have_type_hints(name, func):
    missing = [p.name for p in inspect.signature(func).parameters.values()
               if p.annotation is inspect.Parameter.empty and p.name not in ("self", "cls")]
    assert not missing, f"{name}: parameters without a type hint: {missing}"


def test_package_is_typed():
    assert (ROOT / "persson_fast" / "py.typed").exists()


def test_release_files_agree_with_the_version():
    """The version is written in persson_fast/_version.py; CITATION.cff and CHANGELOG.md
    name the same one, and pyproject.toml reads it from there."""
    citation = (ROOT / "CITATION.cff").read_text(encoding="utf-8")
    assert re.search(r"^cff-version: 1\.2\.0$", citation, flags=re.M)
    assert re.search(rf"^version: {re.escape(pf.__version__)}$", citation, flags=re.M)
    changelog = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    assert f"## [{pf.__version__}]" in changelog
    pyproject = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    assert 'dynamic = ["version"]' in pyproject
    assert 'attr = "persson_fast._version.__version__"' in pyproject
    assert (ROOT / "LICENSE").read_text(encoding="utf-8").startswith("MIT License")
