"""The yield wall: elastoplastic contact with a constant penetration hardness (no adhesion).

Physics (Persson, J. Chem. Phys. 115, 3840 (2001); Surf. Sci. Rep. 61, 201 (2006), sec. 3):
the stress distribution diffuses between two absorbing walls, the detachment wall at
-sigma_a (0 without adhesion) and the yield wall at sigma_Y, the penetration hardness. What
crosses the lower wall loses contact; what crosses the upper wall has yielded and stays in
contact, carrying sigma_Y. So

* elastic area A_el(G) = int P dsigma between the walls; plastic area A_pl(G) = the mass
  absorbed at sigma_Y up to G; detached = the mass absorbed at -sigma_a;
  A_el + A_pl + detached = 1;
* the real contact area is A = A_el + A_pl;
* load: int sigma P dsigma + int sigma_Y dA_pl - int sigma_a d(detached) = p_nom.

With a constant sigma_Y and sigma_a = 0 the strip [0, sigma_Y] has the exact sine series of
:func:`persson_fast.plastic_area` (its image form at small G), which this module serves
(``method="analytic"``; ``"auto"`` takes it): relative accuracy ~1e-15, whatever rtol. Then
int sigma P dsigma = p_nom - sigma_Y A_pl exactly (the wall at 0 carries no stress).

Not in this version: a scale-dependent sigma_Y(zeta) (a power law, Nix-Gao, a table) and the
yield wall together with adhesion need a two-wall grid solver; every entry point refuses them
with a ValueError that says so, rather than answer with another model.
"""
from __future__ import annotations

import numpy as np

from ._validation import as_float_array, check_finite
from .analytic import plastic_area

#: what the entry points say when asked for what this version cannot serve
NOT_AVAILABLE = (
    "a scale-dependent yield wall (sigma_Y given as an array, a table or a callable) and a yield "
    "wall together with adhesion need the two-wall grid solver, which this version does not "
    "have; a constant hardness [Pa] without adhesion is served exactly (method 'analytic')")

#: the methods that can carry a yield wall (the others raise a ValueError naming these)
YIELD_METHODS = ("analytic", "auto")


def check_hardness(value, name: str = "hardness") -> float | None:
    """A constant yield stress: a finite number > 0 [Pa]; None passes through.

    Arrays, tables and callables (a scale-dependent sigma_Y) are refused with the reason.
    """
    if value is None:
        return None
    if callable(value) or (np.ndim(value) > 0 if not isinstance(value, (str, bytes)) else False):
        raise ValueError(f"{name}: {NOT_AVAILABLE}; got {name} = {value!r}")
    arr = as_float_array(value, name, "Pa", ndim=(0,))
    check_finite(arr, name, "Pa")
    out = float(arr)
    if not out > 0:
        raise ValueError(f"{name} must be > 0 [Pa] (the penetration hardness sigma_Y); got "
                         f"{name} = {out!r}")
    return out


def check_yield_method(method: str, name: str = "sigma_y") -> None:
    if method not in YIELD_METHODS:
        raise ValueError(f"method {method!r} cannot carry a yield wall ({name}); the methods "
                         f"that can: {', '.join(repr(m) for m in YIELD_METHODS)} (the exact "
                         f"series for a constant {name} without a detachment wall)")


def check_below_hardness(pressure: np.ndarray, hardness: float, name: str = "hardness") -> None:
    """p_nom <= sigma_Y: above it the whole nominal area yields at once (no diffusion)."""
    bad = pressure > hardness
    if np.any(bad):
        i = int(np.argmax(bad))
        raise ValueError(f"pressure must be <= {name} [Pa]: a nominal pressure above the "
                         f"hardness yields the whole nominal area at the macroscopic scale; got "
                         f"pressure[{i}] = {float(pressure[i])!r} with {name} = {hardness!r}")


def constant_yield(pressure: np.ndarray, G: np.ndarray, hardness: float) -> dict:
    """The six bookkeeping arrays (n_p, n_t) of a constant yield wall without adhesion.

    Parameters
    ----------
    pressure : (n_p,) -- nominal pressures, 0 <= p <= hardness. [Pa]
    G : (n_t,) -- diffusion times >= 0. [Pa^2]
    hardness : float -- sigma_Y > 0. [Pa]

    Returns
    -------
    dict of (n_p, n_t) arrays: ``elastic_area``, ``plastic_area``, ``detached_area``
    (1 - A_el - A_pl), ``load`` (int sigma P dsigma = p - sigma_Y A_pl), ``plastic_load``
    (sigma_Y A_pl), ``detached_load`` (0: the wall at sigma = 0 carries no stress).
    """
    p = np.asarray(pressure, dtype=float)[:, None]
    g = np.asarray(G, dtype=float)[None, :]
    elastic, plastic = plastic_area(np.broadcast_to(p, (p.shape[0], g.shape[1])),
                                    np.broadcast_to(g, (p.shape[0], g.shape[1])), hardness)
    elastic = np.asarray(elastic, dtype=float).reshape(p.shape[0], g.shape[1])
    plastic = np.asarray(plastic, dtype=float).reshape(p.shape[0], g.shape[1])
    return {
        "elastic_area": elastic,
        "plastic_area": plastic,
        "detached_area": 1.0 - elastic - plastic,
        "load": p - hardness * plastic,
        "plastic_load": hardness * plastic,
        "detached_load": np.zeros_like(elastic),
    }


def hardness_limit(pressure, hardness: float) -> np.ndarray:
    """A_pl at G -> infinity: p/sigma_Y (the whole load carried at the hardness). [-]"""
    return np.asarray(pressure, dtype=float) / hardness


__all__ = ["check_hardness", "constant_yield", "hardness_limit", "NOT_AVAILABLE",
           "YIELD_METHODS"]
