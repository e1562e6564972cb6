"""The API reference reads like numpy's and scipy's: every public name has a full docstring.

Every function and class of ``persson_fast.__all__`` and ``persson_fast.embed.__all__``
has, in its numpydoc docstring:

* Parameters (a function that takes any) and Returns (functions), or Parameters or
  Attributes (classes);
* Raises, where it raises: every function and every constructible class written in Python
  that takes arguments (the compiled entry points of ``embed`` never raise: they return a
  status code), except the few listed in ``NO_RAISES`` with the reason;
* See Also, whose every entry is a public name of the package;
* Examples with ``>>>`` lines, which ``tests/test_docs.py::test_docstring_examples_pass``
  runs as doctests (so the examples the pages show are executed, and their printed output
  checked).

Every name of ``persson_fast.embed.__all__`` (and of ``persson_fast.__all__``) is listed in
the API index ``docs/api/index.rst``, nothing public is in ``embed`` that its ``__all__``
does not name, and no public signature shows a private parameter. The tests read the
docstrings and the index; the build itself is tested in ``tests/test_docs.py``.
"""
from __future__ import annotations

import inspect
import re
import types
from pathlib import Path

import pytest
from numpydoc.docscrape import ClassDoc, FunctionDoc

import persson_fast as pf
from persson_fast import embed

ROOT = Path(__file__).resolve().parents[1]
API_INDEX = ROOT / "docs" / "api" / "index.rst"

#: functions that take arguments but raise nothing of their own, and why
NO_RAISES = {
    "warmup": "takes one flag and compiles; nothing of the caller's to refuse",
}
#: classes users read but do not construct (their fields are documented as Attributes)
RESULT_CLASSES = {"ContactResult", "DiffusionResult", "SeparationResult", "GapDistribution",
                  "ContactLaw", "Surface", "ScanWarning"}


def _public():
    """(dotted name, object) of every public function and class."""
    for module, names in ((pf, pf.__all__), (embed, embed.__all__)):
        for name in names:
            obj = getattr(module, name)
            if isinstance(obj, (dict, float, int, str)):
                continue                      # constants: documented in the index itself
            yield f"{module.__name__}.{name}", obj


PUBLIC = list(_public())
IDS = [n for n, _ in PUBLIC]


def _compiled(obj) -> bool:
    return hasattr(obj, "py_func")


def _doc(obj):
    if inspect.isclass(obj):
        return ClassDoc(obj, config={"show_class_members": False})
    return FunctionDoc(getattr(obj, "py_func", obj))


def _parameters(obj) -> list[str]:
    """The parameter names of a function or class as ``inspect.signature`` shows them (none
    for a class built in C, such as a warning without its own ``__init__``)."""
    try:
        return list(inspect.signature(getattr(obj, "py_func", obj)).parameters)
    except ValueError:
        return []


def _takes_arguments(obj) -> bool:
    return any(p not in ("self", "cls") for p in _parameters(obj))


def _public_names() -> set[str]:
    names = {f"persson_fast.{n}" for n in pf.__all__}
    names |= {f"persson_fast.embed.{n}" for n in embed.__all__}
    for name, obj in PUBLIC:
        if inspect.isclass(obj):
            names |= {f"{name}.{m}" for m in vars(obj) if not m.startswith("_")}
    return names


def test_the_check_sees_every_public_function_and_class():
    classes = [n for n, o in PUBLIC if inspect.isclass(o)]
    functions = [n for n, o in PUBLIC if not inspect.isclass(o)]
    assert len(PUBLIC) == len(classes) + len(functions) >= 48
    assert len(classes) >= 11 and len(functions) >= 37


@pytest.mark.parametrize("name, obj", PUBLIC, ids=IDS)
def test_docstring_has_parameters_and_returns(name, obj):
    doc = _doc(obj)
    if inspect.isclass(obj):
        assert doc["Parameters"] or doc["Attributes"], f"{name}: no Parameters or Attributes"
        return
    if _takes_arguments(obj):
        assert doc["Parameters"], f"{name}: no Parameters section"
    assert doc["Returns"], f"{name}: no Returns section"


@pytest.mark.parametrize("name, obj", PUBLIC, ids=IDS)
def test_docstring_has_raises_where_it_raises(name, obj):
    short = name.rpartition(".")[2]
    if _compiled(obj) or short in RESULT_CLASSES or not _takes_arguments(obj):
        return
    doc = _doc(obj)
    if short in NO_RAISES:
        assert not doc["Raises"], f"{name} documents Raises now: drop it from NO_RAISES"
        return
    assert doc["Raises"], f"{name}: no Raises section"
    assert all(r.type for r in doc["Raises"]), f"{name}: a Raises entry without its type"


@pytest.mark.parametrize("name", ["persson_fast.solve_contact", "persson_fast.pull_off",
                                  "persson_fast.gap_distribution"])
def test_the_entry_points_document_what_they_refuse(name):
    doc = _doc(getattr(pf, name.rpartition(".")[2]))
    assert any(r.type == "ValueError" for r in doc["Raises"]), name


@pytest.mark.parametrize("name", ["hardness_power_law", "hardness_nix_gao", "hardness_table"])
def test_the_hardness_helpers_say_what_they_return(name):
    doc = _doc(getattr(pf, name))
    assert doc["Returns"] and doc["Returns"][0].desc, name
    assert all(p.type and p.desc for p in doc["Parameters"]), (
        f"{name}: each parameter with its type on the first line and its description below")


@pytest.mark.parametrize("name, obj", PUBLIC, ids=IDS)
def test_docstring_has_see_also_to_public_names(name, obj):
    doc = _doc(obj)
    assert doc["See Also"], f"{name}: no See Also section"
    known = _public_names()
    targets = [t for funcs, _ in doc["See Also"] for t, _role in funcs]
    unknown = [t for t in targets if t not in known]
    assert not unknown, f"{name}: See Also names what is not public: {unknown}"


@pytest.mark.parametrize("name, obj", PUBLIC, ids=IDS)
def test_docstring_has_examples_that_doctest_runs(name, obj):
    doc = _doc(obj)
    text = "\n".join(doc["Examples"])
    assert ">>>" in text, f"{name}: no Examples section with >>> lines"
    import doctest

    found = doctest.DocTestFinder().find(obj, name, globs={})
    assert sum(len(t.examples) for t in found) >= 2, f"{name}: doctest finds no examples"


def _index_entries() -> dict[str, set[str]]:
    """Names the API index lists, per module (autosummary entries and ``.. data::``)."""
    text = API_INDEX.read_text(encoding="utf-8")
    out: dict[str, set[str]] = {}
    module = None
    for line in text.splitlines():
        m = re.match(r"\.\. module:: (\S+)", line)
        if m:
            module = m.group(1)
            continue
        m = re.match(r"\.\. data:: (\w+)", line) or re.match(r"   (\w+)$", line)
        if m and module:
            out.setdefault(module, set()).add(m.group(1))
    return out


@pytest.mark.parametrize("module", [pf, embed], ids=["persson_fast", "persson_fast.embed"])
def test_every_public_name_is_in_the_api_index(module):
    listed = _index_entries().get(module.__name__, set())
    missing = [n for n in module.__all__ if n not in listed]
    assert not missing, f"{module.__name__}: names of __all__ not in docs/api/index.rst: {missing}"
    extra = [n for n in listed if n not in module.__all__]
    assert not extra, f"docs/api/index.rst lists names {module.__name__}.__all__ lacks: {extra}"


def test_embed_makes_public_only_what_it_documents():
    """Imports that embed's kernels use are private there (``_njit_serial``, ...): the module
    exposes its ``__all__`` and nothing else but modules and typing helpers."""
    allowed = {"annotations", "TYPE_CHECKING"}      # from __future__ / typing
    public = [n for n, v in vars(embed).items()
              if not n.startswith("_") and not isinstance(v, types.ModuleType)
              and n not in allowed]
    stray = sorted(set(public) - set(embed.__all__))
    assert not stray, f"persson_fast.embed exposes names outside its __all__: {stray}"


@pytest.mark.parametrize("name, obj", PUBLIC, ids=IDS)
def test_signature_shows_no_private_parameter(name, obj):
    private = [p for p in _parameters(obj) if p.startswith("_")]
    assert not private, f"{name} shows private parameters {private}"


def test_gap_distribution_still_builds_with_its_private_field():
    """The shown signature hides ``_components``; the dataclass still takes it."""
    import dataclasses

    fields = [f.name for f in dataclasses.fields(pf.GapDistribution)]
    assert "_components" in fields
    assert "_components" not in inspect.signature(pf.GapDistribution).parameters
