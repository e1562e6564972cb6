"""What the first call on a machine costs is said the same way wherever it is said.

The compile note (``persson_fast._jit.compile_note``, logged once per process when kernels
compile), README.md and the install page all say "tens of seconds of CPU" and name
``persson-fast info`` as the command that measures it on the user's machine; README.md and
the install page quote the same measured figures, which are those of the table on the
performance page. None of them repeats the old, too low figures.
"""
from __future__ import annotations

import re
from pathlib import Path

from persson_fast._jit import FIRST_CALL_COST, FIRST_CALL_MEASURE, compile_note

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
INSTALL = ROOT / "docs" / "getting-started" / "install.md"
PERFORMANCE = ROOT / "docs" / "user-guide" / "performance.md"
#: the figures as README.md and the install page quote them
FIGURE = re.compile(r"`persson-fast figure2` (\d+–\d+ s), a first adhesive `solve_contact` "
                    r"(\d+–\d+ s), everything (\d+–\d+ s)")


def _flat(path: Path) -> str:
    return " ".join(path.read_text(encoding="utf-8").split())


def test_the_note_says_the_cost_and_the_command():
    note = compile_note("adhesion")
    assert note.startswith("compiling kernels for adhesion, once per machine: ")
    assert FIRST_CALL_COST in note and f"`{FIRST_CALL_MEASURE}`" in note


def test_readme_and_install_page_agree_with_the_note():
    figures = {}
    for path in (README, INSTALL):
        text = _flat(path)
        assert FIRST_CALL_COST in text, f"{path.name} must say {FIRST_CALL_COST!r}"
        assert f"which `{FIRST_CALL_MEASURE}` measures on your machine" in text, path.name
        m = FIGURE.search(text)
        assert m, f"{path.name} must quote the measured first-call figures"
        figures[path.name] = m.groups()
    assert figures["README.md"] == figures["install.md"], figures


def test_the_figures_are_the_performance_tables():
    figure2, adhesive, everything = FIGURE.search(_flat(README)).groups()
    table = PERFORMANCE.read_text(encoding="utf-8")
    rows = {row.split("|")[1].strip(): row.split("|")[2].strip()
            for row in table.splitlines() if row.startswith("| ") and row.count("|") >= 4}
    cpu = {k: v for k, v in rows.items()}
    assert cpu["`python -m persson_fast.cli figure2 --no-plot`"] == figure2
    assert any(k.startswith("one adhesive `solve_contact`") and v == adhesive
               for k, v in cpu.items())
    assert cpu["`persson-fast info` (compiles everything)"] == everything


def test_no_old_figure_is_left():
    stale = re.compile(r"about 9 s|about 10 s|8\.8–9\.0 s|20–22 s")
    for path in (README, INSTALL, PERFORMANCE):
        hits = stale.findall(_flat(path))
        assert not hits, f"{path.name} still says {hits}"
