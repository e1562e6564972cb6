"""Sphinx configuration of the persson_fast documentation.

Build (from the repository root; warnings are errors, every cross-reference must resolve,
notebooks and guide pages are executed)::

    python -m pip install -e ".[docs]"
    python -m sphinx -W -n --keep-going -b html docs docs/_build/html

``PERSSON_FAST_DOCS_EXECUTE=off`` skips the execution of notebooks and guide pages (for
quick edits of the text; the tests and CI always execute them).
"""
from __future__ import annotations

import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import persson_fast  # noqa: E402

# --- project --------------------------------------------------------------------------------
project = "persson_fast"
author = "the persson_fast authors"
copyright = "2026, the persson_fast authors"
release = persson_fast.__version__
version = release

# --- extensions -----------------------------------------------------------------------------
extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "myst_nb",
]

source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
root_doc = "index"
templates_path = ["_templates"]
exclude_patterns = [
    "_build",
    "**.ipynb_checkpoints",
    "notebooks/README.md",          # the folder's own note; the examples page replaces it
    "api/generated/*.md",
]

# every reference must resolve: the build runs with -n (nitpicky) and -W
nitpicky = True
# names outside the package: the build runs offline, without intersphinx inventories
nitpick_ignore = [
    ("py:class", "abc.ABC"),
    ("py:class", "numpy.ndarray"),
    ("py:class", "numba.core.registry.CPUDispatcher"),
]

# --- autodoc, autosummary, numpydoc ---------------------------------------------------------
autosummary_generate = True
autosummary_imported_members = True
autodoc_default_options = {"member-order": "bysource"}
# the types are given in each docstring's Parameters section (numpydoc); the signature
# line shows the names and defaults only
autodoc_typehints = "none"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
# a parameter documented but absent, or present but undocumented, fails the build
numpydoc_validation_checks = {"PR01", "PR02"}

# --- MyST and MyST-NB -----------------------------------------------------------------------
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
nb_execution_mode = "off" if os.environ.get("PERSSON_FAST_DOCS_EXECUTE") == "off" else "force"
nb_execution_timeout = 300          # per cell [s]; the tests hold each notebook to its budget
nb_execution_raise_on_error = True  # a failing cell fails the build
nb_execution_show_tb = True
nb_merge_streams = True
# Markdown that a cell displays (the status table) is parsed as MyST, tables included
nb_render_markdown_format = "myst"
nb_execution_excludepatterns: list[str] = []

# --- HTML -----------------------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = f"persson_fast {release}"
html_static_path = ["_static"]
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version"],
}
html_context = {"default_mode": "light"}
html_show_sourcelink = False

# result records document their fields under "Attributes" (users read them, they do not
# construct them), so their constructor parameters are not checked against "Parameters"
numpydoc_validation_exclude = {
    r"\.ContactResult$", r"\.DiffusionResult$", r"\.SeparationResult$", r"\.ContactLaw$",
    r"\.GapDistribution$",
}
