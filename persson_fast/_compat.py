"""Old module paths, for pickles written by earlier versions (0.1.x).

A pickle names the module a class was defined in. Since the modules moved into subpackages,
the old names are resolved here: a module that is gone (``persson_fast.tabulated``) is an
alias of the module it became, found on first import, and a module whose name is now a
package (``persson_fast.surfaces``) answers the names it held from the module that holds them
now. Nothing here is a public path: new code imports from ``persson_fast`` itself.
"""
from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
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


class _AliasLoader(importlib.abc.Loader):
    def __init__(self, target):
        self.target = target

    def create_module(self, spec):
        return importlib.import_module(self.target)

    def exec_module(self, module):
        pass


class _MovedFinder(importlib.abc.MetaPathFinder):
    """Finds a gone module under its old name: the module it became."""

    def find_spec(self, fullname, path=None, target=None):
        if fullname not in MOVED_MODULES:
            return None
        return importlib.util.spec_from_loader(fullname, _AliasLoader(MOVED_MODULES[fullname]))


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
    """Register the finder and the packages' fallbacks (once; at ``import persson_fast``)."""
    if not any(isinstance(f, _MovedFinder) for f in sys.meta_path):
        sys.meta_path.append(_MovedFinder())
    for package, holder in BECAME_PACKAGES.items():
        module = importlib.import_module(package)
        if "__getattr__" not in vars(module):
            module.__getattr__ = _answer_from(holder)
