"""Corrected area theories: Yang-Persson, Wang-Muser and Xu et al.

The original theory (Persson, J. Chem. Phys. 115, 3840 (2001); ``"persson01"``) gives the
relative contact area A = erf(p / sqrt(2 Vc)), where Vc(zeta) = 2 G(zeta) is the variance of
the contact stress at full contact (G from :meth:`Surface.diffusion_time`). Against exact
numerical contact mechanics it underestimates A, by about a third at small loads. The
corrections offered here replace Vc by a variance V <= Vc in A = erf(p / sqrt(2 V)):

``"yp08"``
    Yang & Persson, J. Phys.: Condens. Matter 20, 215214 (2008), Eq. for G(q) with the
    factor S(q) inside the integral, in the form of Almqvist, Campana, Prodanov & Persson,
    J. Mech. Phys. Solids 59, 2355 (2011):
    dV/dVc = S(A) = gamma + (1 - gamma) A^2, with A = erf(p / sqrt(2 V)) at the same
    magnification. Default gamma = 0.42 (Almqvist et al. 2011; Yang & Persson used 0.45).
``"wm17"``
    Wang & Mueser, Tribol. Lett. 65, 103 (2017) ("Gauging Persson theory on adhesion"):
    dV/dVc = S(A) = gamma - (2/9) A^2 + (11/9 - gamma) A^4. Default gamma = 5/9.
``"xu24"``
    Xu et al. (2024), the "fudge factors" comparison of Persson's theory with exact contact
    mechanics: the algebraic relation A = erf(p / sqrt(2 (gamma + (1 - gamma) A) Vc(zeta1)))
    at full magnification. Default gamma = 0.42 (the value of that paper's published code).

The forms are those of the cited papers written in the variance (the published codes of
Xu et al. use the same: for yp08 and wm17 an implicit step V_{n+1} = V_n + S(A_{n+1}) dVc
per magnification step, for xu24 the algebraic equation solved once per pressure).

How the package solves them
---------------------------
The ODE dV/dVc = S(erf(p / sqrt(2 V))) does not contain Vc explicitly and is scale-free:
with y = p / sqrt(2 Vc) (the original theory's argument, A = erf y) and x = p / sqrt(2 V),
every theory is A = erf(x(y)) with one function x(y) per theory and gamma. Writing
s = ln y and W = ln(x / y), the ODE becomes the scalar equation

    dW/ds = S(erf(e^(s + W))) e^(2 W) - 1,     W = 0 for y >= 6 (the delta start: A = 1,
                                                 S(1) = 1, so V = Vc until A leaves 1)

and xu24 is W = -(1/2) ln(gamma + (1 - gamma) erf(y e^W)). W(s) is tabulated once per
(theory, gamma) on 10,350 nodes (1/512 apart in ln y, from y = 1e-8 to 6; 4th-order
Runge-Kutta with 2 steps per node for yp08/wm17, a safeguarded Newton solve per node for
xu24; ~3 ms, cached per process), and from it ln A with its exact slope, interpolated by
cubic Hermite polynomials: the area of every pressure at every magnification then costs one
table look-up and one exp, relative accuracy ~4e-13 (``TABLE_RTOL`` bounds it), whatever
``rtol``.

Profiles: since the ODE is autonomous in Vc, A(zeta) of yp08 and wm17 is the same function
evaluated at Vc(zeta), exactly the solution of the ODE at each magnification. xu24 is
defined at full magnification only; its profile ``area_zeta`` applies the algebraic relation
with Vc(zeta) at each zeta, i.e. it is the xu24 area of the surface cut off at q = zeta q0.

Limits: A -> 1 at large p; at small p, V -> S(0) Vc = gamma Vc for every theory, so
A -> p / sqrt(pi gamma G1): the original small-load slope 1 / sqrt(pi G1) times
1 / sqrt(gamma) (1.543 for gamma = 0.42, 1.342 for 5/9). For yp08 gamma = 1 is the original
theory, and so is xu24 with gamma = 1: both are then computed by the original's closed form
(their tables reduce to W = 0 to rounding, which the tests check as well).

With adhesion (yp08, wm17): in the diffusion picture the corrections rescale the diffusion
time by the current contact area, dP/dG = S(A(G)) d^2P/dsigma^2, i.e. the original diffusion
in the time T(G) = int_0^G S(A) dG'. With the detachment wall -sigma_a(zeta) the area is no
longer a function of p/(2 sqrt(G)), so T is solved together with sigma_a: the adhesive fixed
point (:func:`persson_fast._kernels.adhesion.solve_adhesive_one`) iterates the pair
(sigma_a, T) at the zeta grid's nodes, T by the trapezoid rule on the grid (second order, as
the elastic energy U_el, so the zeta ladder's extrapolation and error control apply
unchanged). Eqs. 8-9 keep their form with the corrected A(zeta). The yield wall is served
the same way (the same fixed point with the two-wall solver inside; without adhesion it
iterates T alone), S taken of the real contact area A_el + A_pl. xu24 has no diffusion and
serves no wall.

Valid gamma: S(0) = gamma is the factor of the spread at vanishing contact; gamma <= 0 stops
it (V would stop growing or shrink, and A would not be defined), so gamma > 0; for wm17 the
quartic S must stay positive on [0, 1], which needs gamma > ``WM17_GAMMA_MIN`` = 0.01019.
gamma <= 1: the corrections were fitted to raise the area of the original theory (gamma = 1
is the original theory for yp08 and xu24); larger values would lower it, outside what the
papers define.
"""
from __future__ import annotations

import functools
import math
import time

import numpy as np

from ._kernels import theories as _k
from ._validation import as_float_array, check_finite, check_nondecreasing, check_nonnegative
from .results import ContactResult, per_contact_area, summarize_status

__all__ = ["THEORIES", "CORRECTED_THEORIES", "DEFAULT_GAMMA", "WM17_GAMMA_MIN", "TABLE_RTOL",
           "check_theory", "check_theory_scene", "correction_factor", "theory_area",
           "small_pressure_slope", "solve_theory_contact"]

#: every area theory solve_contact knows; "persson01" is the original (the default)
THEORIES = ("persson01", "yp08", "wm17", "xu24")
#: the corrected ones
CORRECTED_THEORIES = ("yp08", "wm17", "xu24")
#: theories that can serve a scene with adhesion (the detachment wall): the original and the
#: corrected diffusions (xu24 is an algebraic relation at full magnification, no diffusion)
ADHESIVE_THEORIES = ("persson01", "yp08", "wm17")
#: theories that can serve a scene with a yield wall (the corrected diffusions: T iterated
#: with the two-wall solver, with or without adhesion)
YIELD_THEORIES = ("persson01", "yp08", "wm17")
#: the published default gamma of each corrected theory [-]
DEFAULT_GAMMA = {"yp08": 0.42, "wm17": 5.0 / 9.0, "xu24": 0.42}
#: below this gamma the wm17 factor gamma - (2/9) A^2 + (11/9 - gamma) A^4 turns negative
#: somewhere in 0 < A < 1 (root of 81 gamma^2 - 99 gamma + 1 = 0) [-]
WM17_GAMMA_MIN = (99.0 - math.sqrt(99.0 ** 2 - 4.0 * 81.0)) / 162.0
#: bound on the relative error of the tabulated corrected areas (measured ~5e-13) [-]
TABLE_RTOL = 1e-12
#: the method name a corrected theory reports (near-closed form: one table look-up)
THEORY_METHOD = "analytic"

_CODES = {"yp08": _k.YP08, "wm17": _k.WM17, "xu24": _k.XU24}


def check_theory(theory, theory_gamma=None) -> tuple[str, float | None]:
    """Validate ``theory`` and ``theory_gamma``; return (theory, gamma actually used).

    Parameters
    ----------
    theory : str
        One of :data:`THEORIES`.
    theory_gamma : float or None
        The corrected theory's gamma; None takes :data:`DEFAULT_GAMMA`. Must be None for
        "persson01" (no parameter). [-]

    Returns
    -------
    (str, float or None) -- the theory and its gamma (None for "persson01"). [-]
    """
    if not isinstance(theory, str) or theory not in THEORIES:
        valid = ", ".join(repr(t) for t in THEORIES)
        raise ValueError(f"theory must be one of {valid} [-]; got theory = {theory!r}")
    if theory == "persson01":
        if theory_gamma is not None:
            raise ValueError(
                f"theory_gamma must be None for theory='persson01' [-] (the original theory "
                f"has no parameter; a gamma belongs to 'yp08', 'wm17' or 'xu24'); got "
                f"theory_gamma = {theory_gamma!r}")
        return theory, None
    if theory_gamma is None:
        return theory, DEFAULT_GAMMA[theory]
    if isinstance(theory_gamma, (bool, np.bool_)):
        raise ValueError(f"theory_gamma must be a real number [-]; got theory_gamma = {theory_gamma!r}")
    g_arr = as_float_array(theory_gamma, "theory_gamma", "-", ndim=(0,))
    check_finite(g_arr, "theory_gamma", "-")
    g = float(g_arr)
    lo = WM17_GAMMA_MIN if theory == "wm17" else 0.0
    if not lo < g <= 1.0:
        why = ("S(A) = gamma - (2/9) A^2 + (11/9 - gamma) A^4 must stay > 0 for A in [0, 1]"
               if theory == "wm17" else "gamma = S(0) > 0 keeps the spread of the stress going")
        raise ValueError(
            f"theory_gamma must lie in ({lo:.4g}, 1] for theory={theory!r} [-] ({why}; gamma "
            f"<= 1 is the range the correction is defined for: it raises the area of the "
            f"original theory, gamma = 1 being no correction for yp08 and xu24); got "
            f"theory_gamma = {g!r}")
    return theory, g


def check_theory_scene(theory: str, work_of_adhesion: float, hardness=None) -> None:
    """Refuse a theory for a scene with walls (adhesion, yield) it cannot serve.

    Adhesion (the detachment wall) is served by :data:`ADHESIVE_THEORIES` (the corrected
    diffusions yp08 and wm17 beside the original); the yield wall by :data:`YIELD_THEORIES`;
    xu24 (an algebraic relation at full magnification) by neither.
    """
    walls, serving = [], set(THEORIES)
    if work_of_adhesion > 0:
        walls.append(f"work_of_adhesion = {work_of_adhesion!r} J/m^2 (the detachment wall)")
        serving &= set(ADHESIVE_THEORIES)
    if hardness is not None:
        walls.append("hardness (the yield wall)")
        serving &= set(YIELD_THEORIES)
    if theory in serving:
        return
    serve = ", ".join(repr(t) for t in THEORIES if t in serving)
    why = ("is defined only at full magnification without walls (an algebraic relation at "
           "zeta1, no diffusion that could carry a wall)")
    raise ValueError(f"theory={theory!r} {why} [-]; got {'; '.join(walls)}. For this scene use "
                     f"theory={serve}")


def correction_factor(theory: str, theory_gamma, area):
    """S(A), the factor of the corrected spread dV/dVc = S(A) (yp08, wm17). [-]

    Parameters
    ----------
    theory : str -- "yp08" or "wm17" ("persson01": S = 1).
    theory_gamma : float or None -- gamma; None: the default. [-]
    area : array_like -- relative contact area A in [0, 1]. [-]
    """
    theory, gamma = check_theory(theory, theory_gamma)
    a2 = np.asarray(area, dtype=float) ** 2
    if theory == "yp08":
        return gamma + (1.0 - gamma) * a2
    if theory == "wm17":
        return gamma - (2.0 / 9.0) * a2 + (11.0 / 9.0 - gamma) * a2 * a2
    if theory == "persson01":
        return np.ones_like(a2)
    raise ValueError("theory must be 'yp08' or 'wm17' for correction_factor (xu24 has no "
                     f"spread factor; persson01 has S = 1) [-]; got theory = {theory!r}")


def small_pressure_slope(theory: str, theory_gamma=None) -> float:
    """lim_{p->0} A / (p / sqrt(pi G1)): the small-load slope relative to the original. [-]

    1 / sqrt(gamma) for every corrected theory (V -> gamma Vc as A -> 0), 1 for persson01.
    """
    theory, gamma = check_theory(theory, theory_gamma)
    return 1.0 if gamma is None else 1.0 / math.sqrt(gamma)


@functools.lru_cache(maxsize=32)
def _table(theory: str, gamma: float):
    """(w0, ln A, d ln A/ds, s_low, 1/step, build time) of one theory and gamma."""
    t0 = time.perf_counter()
    w0, LA, DA, s_low, inv_step, status, _, _ = _k.new_table(_CODES[theory], float(gamma))
    if status != 0:                              # pragma: no cover - a bug, not user input
        raise RuntimeError(f"theory table for {theory!r}, gamma = {gamma!r}: status {status}")
    LA.flags.writeable = False
    DA.flags.writeable = False
    return w0, LA, DA, s_low, inv_step, time.perf_counter() - t0


def theory_area(theory: str, pressure, G, theory_gamma=None) -> np.ndarray:
    """Relative contact area of a theory without walls, at every pressure and G.

    Parameters
    ----------
    theory : str -- one of :data:`THEORIES`.
    pressure : float or array_like, shape (n_p,) -- nominal pressure, >= 0. [Pa]
    G : float or array_like, shape (n_z,) -- non-decreasing diffusion times G(zeta) >= 0
        (Vc = 2 G). [Pa^2]
    theory_gamma : float or None -- gamma; None: :data:`DEFAULT_GAMMA`. [-]

    Returns
    -------
    (n_p, n_z) ndarray -- A/A0; G = 0 gives 1 (p > 0), p = 0 gives 0. [-]
    """
    theory, gamma = check_theory(theory, theory_gamma)
    p = np.atleast_1d(as_float_array(pressure, "pressure", "Pa", ndim=(0, 1)))
    check_nonnegative(p, "pressure", "Pa")
    g = np.atleast_1d(as_float_array(G, "G", "Pa^2", ndim=(0, 1)))
    check_nonnegative(g, "G", "Pa^2")
    check_nondecreasing(g, "G", "Pa^2")
    if theory == "persson01":
        from .analytic.images import images_area
        return np.broadcast_to(images_area(p[:, None], g[None, :]), (p.size, g.size)).astype(float)
    area, _ = _sweep(theory, gamma, np.ascontiguousarray(p, dtype=np.float64),
                     np.ascontiguousarray(g, dtype=np.float64))
    return area


def _sweep(theory, gamma, p, G):
    if gamma == 1.0 and theory in ("yp08", "xu24"):      # S = 1: the original theory itself
        from .analytic.images import images_area
        area = np.broadcast_to(images_area(p[:, None], G[None, :]), (p.size, G.size))
        return area.astype(float), np.zeros(p.size, dtype=np.int64)
    w0, LA, DA, s_low, inv_step, _ = _table(theory, gamma)
    area = np.empty((p.size, G.size))
    status = np.zeros(p.size, dtype=np.int64)
    _k.theory_area_sweep(_CODES[theory], gamma, p, G, w0, LA, DA, s_low, inv_step,
                         np.empty(G.size), area, status)
    return area, status


def solve_theory_contact(surface, pressure: np.ndarray, zeta: np.ndarray, e_star: float,
                         theory: str, theory_gamma: float) -> ContactResult:
    """solve_contact for a corrected theory without walls (arguments already validated).

    Parameters
    ----------
    surface : Surface -- the roughness.
    pressure : (n_p,) float64 -- nominal pressures, >= 0. [Pa]
    zeta : (n_z,) float64 -- magnifications, zeta[0] == 1, zeta[-1] == q1/q0. [-]
    e_star : float -- effective modulus. [Pa]
    theory : str -- "yp08", "wm17" or "xu24".
    theory_gamma : float -- the gamma to use (not None). [-]

    Returns
    -------
    ContactResult -- ``area_zeta`` from the theory at each zeta (see the module notes for
    xu24), ``load`` = p where A > 0, ``error_estimate`` = TABLE_RTOL * area,
    ``theory`` and ``theory_gamma`` recorded, ``method`` = "analytic".
    """
    t0 = time.perf_counter()
    G = np.asarray(surface.diffusion_time(zeta * surface.q0, e_star), dtype=float)
    G[0] = 0.0
    fresh = _table.cache_info().currsize
    table_time = _table(theory, theory_gamma)[5]
    timings = {}
    if _table.cache_info().currsize != fresh:
        timings["table"] = table_time
    t1 = time.perf_counter()
    area_z, status = _sweep(theory, theory_gamma, pressure, G)
    timings["solve"] = time.perf_counter() - t1 + (t1 - t0 - timings.get("table", 0.0))
    area = area_z[:, -1].copy()
    load = np.where(area > 0, pressure, 0.0)
    success, message = summarize_status(status)
    zeros = np.zeros((pressure.size, zeta.size))
    return ContactResult(
        pressure=pressure, area=area, zeta=zeta, G=G, area_zeta=area_z, sigma_a=zeros,
        gamma_eff=zeros.copy(), load=load, mean_contact_pressure=per_contact_area(pressure, area),
        mean_contact_stress=per_contact_area(load, area), detached_area=1.0 - area,
        detached_load=load - pressure, error_estimate=TABLE_RTOL * area, method=THEORY_METHOD,
        status=status, success=success, message=message, timings=timings, theory=theory,
        theory_gamma=float(theory_gamma))
