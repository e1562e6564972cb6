"""Old module paths, for pickles written by earlier versions (0.1.x).

A pickle names the module a class was defined in. Since the modules moved into subpackages,
the old names are resolved here: a module that is gone (``persson_fast.tabulated``) is an
entry of ``sys.modules`` for the module it became (the same module object, its own
``__spec__`` untouched, so its relative imports stay its own), and a module whose name is now
a package (``persson_fast.surfaces``) answers the names it held from the module that holds
them now. Nothing here is a public path: new code imports from ``persson_fast`` itself.
"""
from __future__ import annotations

import importlib
import sys

#: modules that are gone -> the module they became
MOVED_MODULES = {
    "persson_fast.surface_base": "persson_fast.surfaces.base",
    "persson_fast.surface_models": "persson_fast.surfaces.registry",
    "persson_fast.tabulated": "persson_fast.surfaces.tabulated",
    "persson_fast.topography": "persson_fast.surfaces.topography",
    "persson_fast.zeta_grid": "persson_fast.adhesion.zeta_grid",
    "persson_fast.pulloff": "persson_fast.adhesion.pulloff",
    "persson_fast.pulloff_branch": "persson_fast.adhesion.branch",
    "persson_fast.yield_api": "persson_fast.plasticity.yield_wall",
    "persson_fast.strip": "persson_fast.plasticity.strip",
    "persson_fast.contact_law": "persson_fast.separation.contact_law",
    "persson_fast.gaps": "persson_fast.separation.gaps",
}
#: modules whose name is now a package -> the module that holds what they held
BECAME_PACKAGES = {
    "persson_fast.surfaces": "persson_fast.surfaces.models",
    "persson_fast.plasticity": "persson_fast.plasticity.hardness",
    "persson_fast.separation": "persson_fast.separation.elastic",
    "persson_fast.adhesion": "persson_fast.adhesion.fixed_point",
}


def _answer_from(holder: str):
    def __getattr__(name):
        if name.startswith("__"):
            raise AttributeError(name)
        try:
            return getattr(importlib.import_module(holder), name)
        except AttributeError:
            raise AttributeError(f"module {holder.rpartition('.')[0]!r} has no attribute "
                                 f"{name!r}") from None
    return __getattr__


def install() -> None:
    """Register the old names and the packages' fallbacks (at ``import persson_fast``; the
    modules named are imported by the package's own names already)."""
    for old, new in MOVED_MODULES.items():
        sys.modules.setdefault(old, importlib.import_module(new))
    for package, holder in BECAME_PACKAGES.items():
        module = importlib.import_module(package)
        if "__getattr__" not in vars(module):
            module.__getattr__ = _answer_from(holder)
