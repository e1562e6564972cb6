"""Public entry points: validate, pick a method, call the sweep, wrap the result."""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # names of the type hints only
    from collections.abc import Callable
    
    from numpy.typing import ArrayLike
    
    from .scene import Scene
    from .surfaces.base import Surface

import functools
import time
from dataclasses import replace

import numpy as np

from .analytic.images import _images_area_at, images_area
from .analytic.linear import linear_boundary_area, linear_boundary_load
from ._kernels.status import GRID_CAP, RTOL_NOT_MET
from ._validation import (as_float_array, check_finite, check_level, check_n_damp,
                          check_nondecreasing, check_nonnegative, wall_rows)
from ._jit import compiling_beside
from .adhesion.runner import ADHESIVE_JOBS, warm_adhesion, warm_adhesive_yield
from .adhesion.fixed_point import solve_adhesive_contact, yield_wall_on
from .methods import check_method, check_serves, choose_auto
from .results import (ContactResult, Deferred, DiffusionResult, per_contact_area,
                      summarize_status)
from .plasticity.hardness import YIELD_METHODS, check_below_hardness
from .plasticity.yield_wall import solve_yield_contact, solve_yield_diffusion
from .separation.elastic import contact_fields, warm_separation
from .walls import check_wall_callable, sample_wall
from .sweep import check_parallel, run_sweep, warm_sweeps
from .theories import solve_theory_contact
from .plan import finish_contact, plan_contact, refusals_text
from .scene import (
    DETACHMENT_PREFACTOR,
    _check_rtol,
    _check_zeta,
    default_zeta,
    _diffusion_times,
)

__all__ = ["solve_diffusion", "solve_contact", "default_zeta", "warmup"]


def warmup(prange: bool = False) -> dict:
    """Compile (or load from the disk cache) the kernels now; return the seconds spent.

    The serial kernels (which the default thread pool also runs) are cached on disk: the first
    call on a machine compiles them, later processes load them.

    Parameters
    ----------
    prange : bool
        Also compile numba's ``prange`` sweeps (only used with ``parallel="prange"``; not
        cached on disk, so compiled once per process).

    Returns
    -------
    dict
        Seconds spent per part: ``serial`` (the sweep kernels), ``prange`` (with
        ``prange=True``), ``adhesion``, ``separation``, ``strip``, ``adhesion_yield``. [s]

    See Also
    --------
    persson_fast.solve_contact : Compiles what it needs on its first call.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> timings = pf.warmup()
    >>> sorted(timings)
    ['adhesion', 'adhesion_yield', 'separation', 'serial', 'strip']
    """
    # on a cold cache the adhesive fixed point compiles in a second process meanwhile
    with compiling_beside(ADHESIVE_JOBS):
        timings = warm_sweeps(prange)
    t0 = time.perf_counter()
    warm_adhesion(prange)
    timings["adhesion"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    warm_separation()
    timings["separation"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    solve_diffusion(np.array([0.0, 1.0]), [0.5], 0.5, sigma_y=1.0, method="strip", rtol=1e-3)
    timings["strip"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    warm_adhesive_yield(prange)
    timings["adhesion_yield"] = time.perf_counter() - t0
    return timings

def _check_pressure(pressure, allow_negative: bool) -> np.ndarray:
    p = as_float_array(pressure, "pressure", "Pa", ndim=(0, 1))
    # the usual valid case in two reductions (min and max propagate nan); otherwise the
    # checks below, which name the offending value
    if p.size and p.max() < np.inf and (p.min() > -np.inf if allow_negative else p.min() >= 0):
        return np.atleast_1d(p).astype(np.float64)
    check_finite(p, "pressure", "Pa")
    if not allow_negative:
        bad = p < 0
        if np.any(bad):
            arr = np.atleast_1d(p)
            i = int(np.argmax(np.atleast_1d(bad)))
            label = "pressure" if p.ndim == 0 else f"pressure[{i}]"
            raise ValueError(
                f"pressure must be >= 0 [Pa] without adhesion (a tensile nominal stress "
                f"separates the surfaces); got {label} = {arr[i].item()!r}"
            )
    return np.atleast_1d(p).astype(np.float64)


#: largest |pressure| and |sigma_a| the compiled one-wall methods take [Pa]: the sweep divides
#: G by the square of the scene's stress scale, which must be a double
STRESS_MAX = 1e150
#: smallest start distance pressure + sigma_a(0) > 0 from the wall, as a share of the scene's
#: stress scale max(sqrt(G[-1]), |pressure|, |sigma_a|) [-]: the kernels divide G by its
#: square (below ~1e-154 that is inf: cn and implicit-euler flagged NONFINITE, bnr returned
#: A = 1 with status 0, fixed-grid crashed the process)
START_MIN = 1e-150


def _check_scaled_range(G: np.ndarray, rows: np.ndarray, p: np.ndarray) -> None:
    """Refuse stresses whose scaled diffusion times are not doubles (ValueError).

    The one-wall kernels work in units of the scene's stress scale (``run_sweep``) and then
    of each pressure's start distance y0 = pressure + sigma_a(0) from the wall; G over the
    square of either must be a finite double. Where the scale is sqrt(G[-1]), a y0 below
    START_MIN of it has an area below ~y0 / sqrt(pi G[-1]) < 1e-150.
    """
    for name, arr in (("pressure", p), ("sigma_a", rows)):
        big = np.abs(arr) > STRESS_MAX
        if np.any(big):
            idx = np.unravel_index(int(np.argmax(big)), arr.shape)
            raise ValueError(f"{name} must lie within +-{STRESS_MAX!r} Pa (the solvers divide G "
                             f"by the square of the largest stress, which must be a double); "
                             f"got {name}[{', '.join(str(int(i)) for i in idx)}] = "
                             f"{arr[idx].item()!r}")
    scale = max(float(np.sqrt(G[-1])), float(np.max(np.abs(p))),
                float(np.max(np.abs(rows))) if rows.size else 0.0)
    y0 = p + rows[:, 0]
    tiny = (y0 > 0.0) & (y0 < START_MIN * scale)
    if np.any(tiny):
        i = int(np.argmax(tiny))
        raise ValueError(f"pressure + sigma_a(0), the start's distance from the wall, must be 0 "
                         f"(or below) or at least {START_MIN!r} times the scene's stress scale "
                         f"max(sqrt(G[-1]), |pressure|, |sigma_a|) = {scale!r} Pa [Pa]: the "
                         f"solvers divide G by its square, which overflows below that (and "
                         f"where the scale is sqrt(G[-1]) the area is below ~1e-150 there); "
                         f"got pressure[{i}] = {p[i].item()!r} Pa with sigma_a(0) = "
                         f"{rows[i, 0].item()!r} Pa (solve such pressures in a call of their "
                         f"own, or take A = 0)")


def _is_linear(G: np.ndarray, rows: np.ndarray) -> bool:
    """True when every wall row is exactly a + b G (no jumps)."""
    if G.size < 2:
        return True
    if np.any(np.diff(G) == 0) and np.any(np.diff(rows, axis=1)[:, np.diff(G) == 0] != 0):
        return False
    span = G[-1] - G[0]
    if span == 0:
        return bool(np.all(rows == rows[:, :1]))
    b = (rows[:, -1] - rows[:, 0]) / span
    pred = rows[:, :1] + b[:, None] * (G[None, :] - G[0])
    return bool(np.all(np.abs(rows - pred) <= 1e-12 * (1.0 + np.abs(pred))))


#: solve_diffusion with a callable wall: pressures per kernel call such that the (block, n_s)
#: outputs on the sampled schedule hold at most this many values each (16 MB)
_WALL_BLOCK_ELEMENTS = 2_000_000


#: what ``solve_diffusion``'s default method (``method=None``) takes: "cn" for one wall, as
#: before; with a yield wall "auto" ("analytic" for a constant sigma_y without a detachment
#: wall, else "strip"), or "strip" itself where ``level`` or ``kinks`` ask for a grid method
DEFAULT_DIFFUSION_METHOD = "cn"


def _default_diffusion_method(sigma_y, level, kinks) -> str:
    if sigma_y is None:
        return DEFAULT_DIFFUSION_METHOD
    return "strip" if (level is not None or kinks is not None) else "auto"


def solve_diffusion(G: ArrayLike, pressure: ArrayLike,
                    sigma_a: ArrayLike | Callable[[np.ndarray], np.ndarray] = 0.0, *,
                    sigma_y: ArrayLike | Callable[[np.ndarray], np.ndarray] | None = None,
                    kinks: ArrayLike | None = None, method: str | None = None, rtol: float = 1e-6,
                    n_damp: int | None = None, parallel: bool | str | None = None,
                    level: int | None = None) -> DiffusionResult:
    """Solve the stress diffusion with a prescribed absorbing wall.

    Parameters
    ----------
    G : array_like, shape (n_t,)
        Non-decreasing diffusion times, G[0] >= 0; a repeated value is a flat stretch where the
        wall may jump. [Pa^2]
    pressure : float or array_like, shape (n_p,)
        Nominal stress sigma0 (compressive > 0). Negative values need a wall with
        sigma_a > 0; at or below -sigma_a(0) the surfaces are separated (A = 0). The
        compiled one-wall methods take ``|pressure|`` and ``|sigma_a|`` up to 1e150 Pa and a start
        distance pressure + sigma_a(0) > 0 of at least 1e-150 times the largest of
        ``sqrt(G[-1])``, ``|pressure|``, ``|sigma_a|`` (their scaled diffusion times must be doubles;
        a ValueError otherwise). [Pa]
    sigma_a : float, array_like of shape (n_t,) or (n_p, n_t), or callable
        Detachment stress: the wall sits at -sigma_a(G). Samples: linear in G between the
        given points and equal to sigma_a[0] before G[0]; their interpolation is the wall
        (its error against a curve they were taken from is not part of rtol). A vectorised
        callable ``G [Pa^2] -> sigma_a [Pa]`` (one wall for every pressure; called on arrays,
        must return finite values of the same shape on [0, G[-1]]) is followed from G = 0 and
        sampled (``persson_fast.walls.sample_wall``) finely enough that its
        piecewise-linear error is part of rtol; results are still reported at G only. [Pa]
    sigma_y : float, array_like, callable or None
        The yield wall (penetration hardness) at +sigma_y: what crosses it has yielded and
        stays in contact carrying sigma_y (``plastic_area``, ``plastic_load``; ``area`` is the
        elastic area between the walls). Forms as ``sigma_a``: a scalar, (n_t,) or (n_p, n_t)
        samples (continuous: no jumps), or a vectorised callable G -> sigma_y. A constant
        sigma_y with sigma_a = 0 is the exact series (method "analytic"; "auto" takes it);
        every other pair of walls is solved by "strip" (see ``persson_fast.plasticity.strip``;
        "auto" takes it), with rtol and ``error_estimate`` referring to the real contact
        area area + plastic_area. The walls must keep -sigma_a < sigma_y and start with
        -sigma_a < pressure < sigma_y. None (default): no yield wall. [Pa]
    kinks : array_like or None
        Only with a callable wall (sigma_a, or sigma_y with "strip"): diffusion times where
        a wall's slope jumps, put on the schedule exactly. Kinks not declared are found by the
        adaptive sampling (which puts a sample next to them, within ~1e-3 of the tolerance).
        A callable that jumps is refused (give such a wall as samples with a repeated G).
        [Pa^2]
    method : str or None
        A name in :data:`persson_fast.METHODS`: "cn", "cn-plain", "implicit-euler",
        "fixed-grid", "bnr", "analytic" (a wall linear in G, zero included), "strip" (two
        walls) or "auto" (the cheapest that meets rtol, see ``AUTO_POLICY``). None (default)
        serves every wall it is given: "cn" with one wall (as ``method="cn"``, bitwise), and
        with ``sigma_y`` "auto" ("analytic" for a constant sigma_y without a detachment
        wall, "strip" otherwise; "strip" where ``level`` or ``kinks`` is given). A method
        named explicitly that cannot serve the walls (jumps, non-linear, a yield wall)
        raises a ValueError.
    rtol : float
        Target relative accuracy of the area, in [1e-12, 0.1], with an absolute floor:
        ``|A - A_exact| <= rtol A + 1e-12``, or the status flags the result. An area far below
        1e-12 (sigma0 + sigma_a(0) << sqrt(G): A ~ sigma0 / sqrt(pi G) without a wall) is
        accurate to 1e-12 only, and may be 0.0 with status 0. [-]
    level : int or None
        Explicit resolution level >= 0 of a compiled method instead of rtol (each level
        halves the node spacing and the step, level 2 of "cn" is the rtol = 1e-6 grid); for
        convergence studies. [-]
    n_damp : int or None
        Crank-Nicolson steps replaced by implicit-Euler half steps after a wall jump
        (Rannacher damping), >= 0; for "strip", at the start of each run and after each kink
        of a wall. None (default): 2, for "strip" 1.
    parallel : None, bool, "threads" or "prange"
        Spread pressures over threads, as in :func:`solve_contact` (default: a thread pool
        over the disk-cached serial kernels for >= 4 pressures, bitwise equal to False).

    Returns
    -------
    DiffusionResult

    Raises
    ------
    ValueError
        For bad input, naming the argument, the rule, the unit and the value (G not
        finite or decreasing, a wall of another length, an unknown ``method``, ``rtol``
        outside [1e-12, 0.1], ...).

    See Also
    --------
    persson_fast.DiffusionResult : What it returns.
    persson_fast.images_area : The closed form without walls that move.
    persson_fast.solve_contact : The same from a surface and a scene.
    persson_fast.embed.diffusion_area : One pressure from numba code.

    Notes
    -----
    dP/dG = d2P/dsigma2 with P(sigma, 0) = delta(sigma - sigma0) and P(-sigma_a, G) = 0
    (seed Eqs. 4, 7 in diffusion time G). The "cn" scheme is described in
    ``persson_fast._kernels.similarity``; its order after extrapolation is 4 for smooth
    walls.

    A callable wall is sampled on 0, G, ``kinks`` and adaptively inserted points until its
    chord deviates from it by at most WALL_BUDGET * rtol * min(sqrt(2G), 1/abs(v))
    * exp(gap^2/4G) / L (module ``persson_fast.walls``: a comparison-principle bound on
    the area error, v = dsigma_a/dG where the wall moves into the distribution, gap the
    distance sigma0 + sigma_a(G) of the smallest pressure in contact, L the e-folds of G in
    which the wall meets the distribution); the deviation falls as (spacing)^2, so smooth
    walls need ~rtol^(-1/2) samples (about 8e4 for 0.1 + 0.5 sqrt(G) over 4 decades at rtol
    = 1e-8). ``method="auto"`` takes "analytic" only when the samples are exactly linear
    (a linear callable), else "cn"; "bnr" and "fixed-grid" receive the same samples ("bnr"
    grades every sample like a kink: its cost grows with their number). More than
    ``walls.MAX_POINTS`` samples: the refinement stops, status GRID_CAP and the message
    says so. ``error_estimate`` adds the chords' own part of the area error
    (``WallSampling.area_error``, the same bound summed over the final intervals with their
    actual deviations: 1-5x the sampling error where measured), and a result whose estimate
    then exceeds rtol is flagged (status 15). ``timings["sample_wall"]`` is the sampling
    time; ``sigma_a`` of the result is the callable at G.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> G = np.linspace(0.0, 1.0, 11)
    >>> r = pf.solve_diffusion(G, [0.5, 1.0], sigma_a=0.1 * G, rtol=1e-6)
    >>> print(r.method, bool(np.all(r.success)), np.round(r.area[:, -1], 5))
    cn True [0.29462 0.54436]
    """
    if method is None:
        method = _default_diffusion_method(sigma_y, level, kinks)
    method = check_method(method)
    if sigma_y is not None and method not in YIELD_METHODS:
        raise ValueError(f"method {method!r} cannot carry a yield wall (sigma_y): the methods "
                         f"that can are {', '.join(repr(m) for m in YIELD_METHODS)}; leave "
                         f"method out (the default serves every wall: 'auto' with sigma_y) or "
                         f"name one of them; got method = {method!r} with a yield wall")
    check_parallel(parallel)
    rtol = _check_rtol(rtol)
    G = as_float_array(G, "G", "Pa^2", ndim=(1,))
    if G.size == 0:
        raise ValueError("G must hold at least one diffusion time [Pa^2]; got an empty array")
    check_nonnegative(G, "G", "Pa^2")
    check_nondecreasing(G, "G", "Pa^2")
    if sigma_y is not None:
        return solve_yield_diffusion(G, pressure, sigma_a, sigma_y, method=method, kinks=kinks,
                                     level=level, rtol=rtol, n_damp=n_damp, parallel=parallel,
                                     check_pressure=_check_pressure)
    if method == "strip":
        raise ValueError("method 'strip' is the two-wall solver: it needs a yield wall "
                         "(sigma_y=...); for one wall use 'cn' or 'auto'")
    wall = None
    if callable(sigma_a):
        # a wall as a function: sampled below to the tolerance, on a schedule that holds G
        t_wall = time.perf_counter()
        at_user = check_wall_callable(sigma_a, G)
        p = _check_pressure(pressure, allow_negative=True)
        n_p, n_t = p.size, G.size
        wall = sample_wall(sigma_a, G, p, rtol, kinks, at_user=at_user)
        t_wall = time.perf_counter() - t_wall
        rows = np.broadcast_to(at_user, (n_p, n_t)).copy()
        sa = wall.sigma_a                      # 1-D: one wall for every pressure
    elif kinks is not None:
        raise ValueError("kinks applies to a callable sigma_a (samples are linear between "
                         "their points already: put a sample at each kink); got kinks = "
                         f"{kinks!r} with sigma_a given as samples")
    else:
        sa = as_float_array(sigma_a, "sigma_a", "Pa", ndim=(0, 1, 2))
        check_finite(sa, "sigma_a", "Pa")
        has_wall = bool(np.any(sa != 0))
        p = _check_pressure(pressure, allow_negative=has_wall)
        n_p, n_t = p.size, G.size
    if wall is None:                           # (a callable's rows are set above)
        rows = wall_rows(sa, "sigma_a", n_p, n_t)
    n_damp = check_n_damp(n_damp, 2)
    check_level(level)
    # the schedule the kernels see: the user's G, or the sampled callable's (it holds G)
    G_s, rows_s = (G, rows) if wall is None else (wall.G, np.broadcast_to(sa, (n_p, sa.size)))
    if sa.ndim == 0:
        linear, jumps = True, False          # a wall at rest
    else:
        distinct = rows_s if sa.ndim == 2 else rows_s[:1]
        linear = _is_linear(G_s, distinct)
        jumps = bool(np.any((np.diff(G_s) == 0)[None, :] & (np.diff(distinct, axis=1) != 0)))
    # a moving wall held at sigma_a[0] before G[0] > 0 is not one linear law from G = 0
    # (a callable wall is followed from G = 0: its schedule starts there)
    starts_late = bool(G_s[0] > 0 and sa.ndim > 0 and np.any(distinct != distinct[:, :1]))
    kind = "linear" if (linear and not starts_late) else ("jumps" if jumps else "smooth")
    use = choose_auto(kind) if method == "auto" else method
    check_serves(use, jumps=jumps, nonlinear=not linear)
    if use == "analytic" and level is not None:
        raise ValueError("level applies to compiled methods only; got method = 'analytic'")
    if use != "analytic":
        _check_scaled_range(G_s, rows_s, p)
    t0 = time.perf_counter()
    if use == "analytic":
        out = _analytic_linear(G_s, rows_s, p)
        timings = {"solve": time.perf_counter() - t0}
    elif wall is None:
        out, timings = run_sweep(G_s, rows_s, p, rtol=rtol, method=use,
                                 level=-1 if level is None else int(level),
                                 n_damp=int(n_damp), parallel=parallel)
    else:
        # a long schedule: pressures in blocks, so the (block, n_s) kernel outputs stay small;
        # results are kept at the user's G only
        names = ("area", "load", "detached_area", "detached_load", "error_estimate")
        out = {name: np.zeros((n_p, n_t)) for name in names}
        out["status"] = np.zeros(n_p, dtype=np.int64)
        out["counts"] = np.zeros((n_p, 3), dtype=np.int64)
        timings = {}
        block = max(1, _WALL_BLOCK_ELEMENTS // G_s.size)
        for lo in range(0, n_p, block):
            hi = min(n_p, lo + block)
            part, t_part = run_sweep(G_s, rows_s[lo:hi], p[lo:hi], rtol=rtol, method=use,
                                     level=-1 if level is None else int(level),
                                     n_damp=int(n_damp), parallel=parallel)
            for name in names:
                out[name][lo:hi] = part[name][:, wall.index]
            out["status"][lo:hi] = part["status"]
            out["counts"][lo:hi] = part["counts"]
            for key, value in t_part.items():
                timings[key] = timings.get(key, 0.0) + value
    if wall is not None:
        timings = {"sample_wall": t_wall, **timings}
        if use == "analytic":
            for name in ("area", "load", "detached_area", "detached_load", "error_estimate"):
                out[name] = np.ascontiguousarray(out[name][:, wall.index])
        if wall.capped:
            out["status"] = np.where(out["status"] == 0, GRID_CAP, out["status"])
        if use != "analytic":
            # the chords' own part of the area error (the kernels see only the samples)
            sampling = wall.area_error(p, out["area"])
            out["error_estimate"] = out["error_estimate"] + sampling
            if level is None:
                miss = np.any(out["error_estimate"] > rtol * np.abs(out["area"]) + 1e-12, axis=1)
                out["status"] = np.where((out["status"] == 0) & miss, RTOL_NOT_MET,
                                         out["status"])
    success, message = summarize_status(out["status"])
    if wall is not None and wall.capped:
        message += (f"; the callable sigma_a needed more than {wall.G.size} samples for rtol "
                    f"(largest wall deviation {wall.worst_ratio:.3g} times its tolerance): "
                    f"use a larger rtol, declare kinks=, or give samples")
    return DiffusionResult(
        G=G, pressure=p, sigma_a=rows, area=out["area"], load=out["load"],
        detached_area=out["detached_area"], detached_load=out["detached_load"],
        error_estimate=out["error_estimate"], method=use, status=out["status"],
        success=success, message=message, timings=timings, counts=out.get("counts"),
    )


def _images_profile(p, G):
    """A(zeta)/A0 of the closed form without adhesion, (n_p, n_z)."""
    area_z = images_area(p[:, None], G[None, :])
    return np.broadcast_to(area_z, (p.size, G.size)).astype(float)


def _analytic_linear(G, rows, p):
    """Closed forms for walls a + b G (images when a = b = 0)."""
    n_p, n_t = rows.shape
    area = np.zeros((n_p, n_t))
    load = np.zeros((n_p, n_t))
    for k in range(n_p):
        a = rows[k, 0]
        span = G[-1] - G[0]
        b = (rows[k, -1] - rows[k, 0]) / span if span > 0 else 0.0
        a0 = a - b * G[0]          # wall at G = 0 (constant before G[0] only if b == 0)
        if span > 0 and G[0] > 0 and b != 0:
            # the wall is held at sigma_a[0] before G[0]: not a single linear law
            raise ValueError(
                "method 'analytic' needs the linear wall to start at G = 0 (G[0] = 0) when it "
                "moves; use method='cn'"
            )
        if p[k] + a0 <= 0:
            area[k] = 0.0
            load[k] = 0.0
            continue
        if a0 == 0 and b == 0:
            area[k] = images_area(p[k], G)
            load[k] = np.where(area[k] > 0, p[k], 0.0)
        else:
            area[k] = linear_boundary_area(p[k], G, a0, b)
            load[k] = linear_boundary_load(p[k], G, a0, b)
    return {
        "area": area, "load": load, "detached_area": 1.0 - area,
        "detached_load": load - p[:, None], "error_estimate": np.zeros((n_p, n_t)),
        "status": np.zeros(n_p, dtype=np.int64),
    }


def _route_elastic(plan, pressure, zeta, rtol, parallel, controls):
    """No wall: the closed form erf(p / 2 sqrt G1) or a grid method."""
    surface, z = plan.surface, _check_zeta(zeta, plan.surface)
    p = _check_pressure(pressure, allow_negative=False)
    G = _diffusion_times(surface, z, plan.e_star, default_grid=zeta is None)
    use = choose_auto("linear") if plan.method == "auto" else plan.method
    t0 = time.perf_counter()
    if use == "analytic":
        # the area at zeta1 now, its profile in zeta (n_p x n_z erf calls, 40x the work of the
        # answer) only when read: area_zeta[:, -1] is bitwise this area
        area = _images_area_at(p, G[-1])
        area_z = Deferred(_images_profile, p, G)
        contact = area > 0
        # the load in contact is the pressure where A > 0 (usually at every pressure: a copy)
        load = p.copy() if contact.all() else np.where(contact, p, 0.0)
        det_a = 1.0 - area
        det_l = load - p
        err = np.zeros(p.size)
        status = np.zeros(p.size, dtype=np.int64)
        mean_p = per_contact_area(p, area)
        mean_s = mean_p.copy()              # load / A: p / A where A > 0, nan elsewhere
        timings = {"solve": time.perf_counter() - t0}
    else:
        out, timings = run_sweep(G, np.zeros((p.size, z.size)), p, rtol=rtol, method=use,
                                 parallel=parallel)
        area_z = out["area"]
        load = out["load"][:, -1]
        det_a = out["detached_area"][:, -1]
        det_l = out["detached_load"][:, -1]
        err = out["error_estimate"][:, -1]
        status = out["status"]
        area = area_z[:, -1].copy()
        mean_p, mean_s = per_contact_area(p, area), per_contact_area(load, area)
    success, message = summarize_status(status)
    zeros = (p.size, z.size)
    return ContactResult(
        pressure=p, area=area, zeta=z, G=G, area_zeta=area_z, sigma_a=Deferred(np.zeros, zeros),
        gamma_eff=Deferred(np.zeros, zeros),
        load=load, mean_contact_pressure=mean_p, mean_contact_stress=mean_s,
        detached_area=det_a, detached_load=det_l,
        error_estimate=err, method=use, status=status, success=success, message=message,
        timings=timings,
        separation_source=functools.partial(contact_fields, surface, plan.e_star,
                                            plan.energy_correction, parallel),
    )


def _route_theory(plan, pressure, zeta, rtol, parallel, controls):
    """A corrected theory without walls: the near-closed form."""
    return solve_theory_contact(plan.surface, _check_pressure(pressure, allow_negative=False),
                                _check_zeta(zeta, plan.surface), plan.e_star, plan.theory,
                                plan.theory_gamma)


def _route_yield(plan, pressure, zeta, rtol, parallel, controls):
    """A yield wall alone: the exact two-wall series or the two-wall solver."""
    z = _check_zeta(zeta, plan.surface)
    G = _diffusion_times(plan.surface, z, plan.e_star, default_grid=zeta is None)
    return solve_yield_contact(plan.surface, pressure, z, G, e=plan.e_star,
                               dg=float(plan.work_of_adhesion), method=plan.method,
                               theory=plan.theory, hardness=plan.hardness, rtol=rtol,
                               parallel=parallel, check_pressure=_check_pressure)


def _route_adhesive(plan, pressure, zeta, rtol, parallel, controls, hardness=None):
    """The detachment wall (and with ``hardness`` the yield wall too): the adhesive fixed
    point around the one- or two-wall solver. Without adhesion (a corrected theory with a
    yield wall: the fixed point then iterates the corrected time T alone) the detachment
    wall is 0 (prefactor 0)."""
    dg = plan.work_of_adhesion
    p = _check_pressure(pressure, allow_negative=dg > 0) if hardness is not None else pressure
    z = _check_zeta(zeta, plan.surface) if zeta is not None else None
    if hardness is not None:
        h1 = float(yield_wall_on(hardness, np.array([1.0]))[0])
        check_below_hardness(p, h1, "hardness at zeta = 1")
    res = solve_adhesive_contact(
        plan.surface, p, z, e_star=plan.e_star, work_of_adhesion=dg if dg > 0 else 1.0,
        energy_correction=plan.energy_correction,
        detachment_prefactor=plan.detachment_prefactor if dg > 0 else 0.0,
        method="auto" if hardness is not None else plan.method, rtol=rtol, parallel=parallel,
        controls=controls, zeta_given=zeta is not None, theory=plan.theory,
        theory_gamma=plan.theory_gamma, hardness=hardness)
    return res if hardness is None else replace(res, method="strip")


def _route_two_wall(plan, pressure, zeta, rtol, parallel, controls):
    """A yield wall with adhesion or a corrected theory: the two-wall fixed point."""
    return _route_adhesive(plan, pressure, zeta, rtol, parallel, controls,
                           hardness=plan.hardness)


#: the solver of each route of :data:`persson_fast.plan.ROUTES`
SOLVERS = {"elastic": _route_elastic, "theory": _route_theory, "yield": _route_yield,
           "adhesive-fixed-point": _route_adhesive, "two-wall-fixed-point": _route_two_wall}


def solve_contact(surface: Surface | Scene, pressure: ArrayLike, *,
                  e_star: float | None = None, work_of_adhesion: float = 0.0,
                  energy_correction: float | None = None,
                  detachment_prefactor: float = DETACHMENT_PREFACTOR, method: str = "auto",
                  rtol: float = 1e-6, zeta: ArrayLike | None = None,
                  parallel: bool | str | None = None, adhesion_controls: dict | None = None,
                  theory: str = "persson01", theory_gamma: float | None = None,
                  hardness: float | Callable[[np.ndarray], np.ndarray] | ArrayLike | None = None,
                  ) -> ContactResult:
    """Relative real contact area of a rough surface at many nominal pressures.

    Parameters
    ----------
    surface : Surface or Scene
        The roughness (e.g. :class:`CapillaryWaves`, :class:`SelfAffine`, :class:`TabulatedPSD`),
        or a :class:`Scene` that carries the surface and the scene's parameters (then
        ``e_star``, ``work_of_adhesion``, ``energy_correction`` and ``detachment_prefactor``
        stay at their defaults; the result is bitwise that of the keyword form).
    pressure : float or array_like, shape (n_p,)
        Nominal pressure p_nom = F_N / A0, >= 0 without adhesion. [Pa]
    e_star : float
        Effective modulus E* = E / (1 - nu^2) > 0, in Pa (1 GPa is 1e9); required unless a
        Scene is given. Below 1e5 Pa
        (``persson_fast.surfaces.models.E_STAR_WARN_BELOW``) a UserWarning says so; a value for
        which G(q1) (or, with adhesion, the detachment stress or U_el/Delta gamma)
        overflows float64 raises a ValueError. [Pa]
    work_of_adhesion : float
        Delta gamma >= 0. [J/m^2]  (0: no adhesion.)
    energy_correction : float or None
        gamma_S of S = gamma_S + (1 - gamma_S) P(q)^2 in the elastic energy U_el, in [0, 1];
        None: S = 1. It enters the adhesive fixed point and the separation
        (``result.separation``), not the area without adhesion. [-]
    detachment_prefactor : float
        beta of seed Eq. 8 (default 1/sqrt 2). [-]
    method : str
        A name in :data:`persson_fast.METHODS`; "auto" (default) takes the closed form where
        the scene has one (no adhesion: without a hardness, or with a constant one) and
        otherwise the cheapest measured grid method ("cn" with adhesion, "strip" with a
        yield wall). The method used is ``result.method``.
    rtol : float
        Target relative accuracy of the area, in [1e-12, 0.1]. [-]
    zeta : array_like or None
        Magnifications of the returned profiles (with adhesion also the grid of the fixed
        point, which sets its accuracy): increasing, from 1 to zeta1 = q1/q0. It must end
        at zeta1 (a last point within a relative 1e-12 is set to zeta1 exactly), so that
        ``result.area`` is always A(zeta1)/A0; a grid that stops short of zeta1 or goes
        beyond it raises a ValueError (append ``surface.q1 / surface.q0``). Default: 8 per
        decade plus the spectrum's breakpoints (without adhesion),
        :func:`persson_fast.adhesion_zeta` (with it). [-]
    parallel : None, bool, "threads" or "prange"
        Spread pressures over threads. None (default): a pool of one thread per numba thread
        for >= 4 pressures, running the disk-cached serial kernels (nothing extra to
        compile; results bitwise those of False); True or "threads": the pool always;
        "prange": numba's prange sweeps (compiled once per process, not cached); False: one
        thread.
    adhesion_controls : dict or None
        Fixed-point controls: ``max_iter`` (100), ``m_hist`` (Anderson depth, 5; 0 = plain
        relaxation), ``omega`` (relaxation, 1.0; in tension at most 0.5), ``n_damp`` (2).
    theory : str
        The area theory: "persson01" (default, the original; this path is unchanged by the
        option), or a corrected one, "yp08" (Yang & Persson 2008), "wm17" (Wang & Mueser
        2017), "xu24" (Xu et al. 2024), see ``persson_fast.theories``. Without walls
        the corrected theories are a near-closed form (``method`` "auto" or "analytic";
        relative accuracy ~1e-12 whatever ``rtol``). With adhesion, yp08 and wm17 are the
        corrected diffusion dT/dG = S(A) solved together with the detachment stress
        (error-controlled to ``rtol`` like the original; ``result.G`` stays the original
        G); separated tensions are checked against that theory's ``pull_off`` as for the
        original (see Notes). xu24 (full magnification, no walls) with adhesion raises a
        ValueError. ``result.theory`` records the theory.
    theory_gamma : float or None
        gamma of the corrected theory; None (default) takes its published default (0.42
        for yp08 and xu24, 5/9 for wm17), which ``result.theory_gamma`` records. Range
        (0, 1] ((0.01019, 1] for wm17); must be None for "persson01". [-]
    hardness : float, callable, table or None
        The yield wall sigma_Y(zeta): a constant penetration hardness > 0 [Pa], a vectorised
        callable of zeta returning Pa (``pf.hardness_power_law``, ``pf.hardness_nix_gao``,
        your own), or a table (zeta, sigma_Y) / ``pf.hardness_table`` (log-log linear
        between its points, which must span the zeta range). Then ``result.area`` is the
        real contact area A_el + A_pl (elastic plus yielded, both in contact),
        ``result.elastic_area`` and ``result.plastic_area`` the two parts (and
        ``plastic_area_zeta`` its profile). A constant one is the exact two-wall series
        (method "auto" or "analytic", error 0); a scale-dependent one (or method="strip")
        the two-wall solver on the wall sigma_Y(zeta(G)), error-controlled to rtol in the
        real area (``persson_fast.plasticity``, ``persson_fast.plasticity.strip``). With
        adhesion, or with theory "yp08"/"wm17", the adhesive fixed point runs the two-wall
        solver (method "auto" or "strip"), and separated tensions are checked against
        ``pull_off`` with the same yield wall. Nominal pressures below sigma_Y(1). None
        (default): elastic, bitwise as before.

    Returns
    -------
    ContactResult

    Raises
    ------
    ValueError
        For a bad argument (the message names it, the rule, the unit and the value), and
        for a combination of the scene's pieces that no route solves
        (the table ``persson_fast.plan.REFUSALS``):

    {refusals}

    See Also
    --------
    persson_fast.Scene : A scene to pass in place of the keywords.
    persson_fast.ContactResult : What it returns.
    persson_fast.pull_off : The pull-off stress.
    persson_fast.solve_separation : Mean separation and stiffness.
    persson_fast.scan : Many scenes at once.

    Notes
    -----
    With adhesion the detachment stress is the fixed point of seed Eqs. 8-9, solved per
    pressure in compiled code (see ``persson_fast.adhesion``); nominal tension (p < 0) is
    allowed, and below the pull-off stress the area is 0. A tension that ends separated
    although :func:`pull_off` (of the same theory and yield wall) finds contact there (the
    fixed point on the zeta grid lost the end of the contact branch), or cannot exclude it
    within its error estimate, gets status 9; so does every separated tension where
    pull_off raises (the message says why). The default zeta grid is then
    :func:`persson_fast.adhesion_zeta` (finer, and refined near zeta = 1).
    Without adhesion the whole surface enters through G(zeta) (seed Eqs. 4-7); the area is
    erf(p / (2 sqrt G1)) exactly, which "analytic" and "auto" return; "cn" solves the
    diffusion numerically (the same kernel the adhesive problem uses).

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> p = np.geomspace(1e4, 1e7, 4)
    >>> r = pf.solve_contact(s, p, e_star=1e9)
    >>> print(r.method, np.round(r.area, 5))
    analytic [8.000e-05 8.000e-04 8.020e-03 8.006e-02]
    >>> ra = pf.solve_contact(s, p, e_star=1e9, work_of_adhesion=0.05, rtol=1e-3)
    >>> print(ra.method, bool(np.all(ra.success)), np.round(ra.area, 3))
    cn True [0.    0.001 0.014 0.143]
    """
    def check_run_args():
        check_parallel(parallel)
        nonlocal rtol
        rtol = _check_rtol(rtol)

    plan = plan_contact("solve_contact", surface,
                        {"e_star": e_star, "work_of_adhesion": work_of_adhesion,
                         "energy_correction": energy_correction,
                         "detachment_prefactor": detachment_prefactor, "hardness": hardness},
                        method=method, theory=theory, theory_gamma=theory_gamma,
                        check_extra=check_run_args)
    res = SOLVERS[plan.route](plan, pressure, zeta, rtol, parallel, adhesion_controls)
    return finish_contact(plan, res, rtol)


# the refused combinations in the docstring are the table's own words
solve_contact.__doc__ = solve_contact.__doc__.replace("    {refusals}\n",
                                                      refusals_text("        ") + "\n")
