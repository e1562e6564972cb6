"""Entry-point plumbing of the yield wall: ``solve_diffusion(sigma_y=...)`` and
``solve_contact(hardness=...)`` (physics and the hardness forms: :mod:`persson_fast.plasticity`).

A constant sigma_Y without a detachment wall is the exact series (``method="analytic"``);
every other pair of walls goes to the compiled two-wall solver :mod:`persson_fast.plasticity.strip`
(``method="strip"``). Walls reach it as samples on one schedule: arrays as given (linear in G
between the user's times), callables sampled to rtol by :func:`persson_fast.walls.sample_wall`
(the yield wall through the mirror sigma -> -sigma, which makes it a detachment wall at
-sigma_Y for the pressure -p), the union of both schedules holding the user's times.
"""
from __future__ import annotations

import time

import numpy as np
from ..analytic.special import erfc

from .._kernels.status import GRID_CAP
from .._kernels.strip import N_DAMP as STRIP_N_DAMP
from .._validation import as_float_array, check_finite, check_level, check_n_damp, wall_rows
from ..analytic.images import images_area
from .hardness import (check_below_hardness, check_hardness,
                         check_yield_method, constant_yield, hardness_in_diffusion_time)
from ..results import ContactResult, DiffusionResult, per_contact_area, summarize_status
from ..walls import WALL_BUDGET, _call, check_wall_callable, sample_wall

__all__ = ["solve_yield_diffusion", "solve_yield_contact"]

#: a callable yield wall is sampled to this fraction of rtol: its chords bias the plastic
#: area (a concave sigma_Y(G) lies above its chords, so more yields), by up to YIELD_KAPPA
#: times the detachment wall's bound of walls.py (measured 3.4 for sigma_Y0 zeta^0.15 on the
#: seed scene: 0.85 rtol in A_pl, 0.3 rtol in A at full rtol); the estimate adds that bound
YIELD_SAMPLING = 0.25
YIELD_KAPPA = 4.0
#: "auto": a pressure whose distribution reaches the yield wall with a mass below this bound
#: (:func:`yield_wall_reach`) is solved without it (images, A_pl = 0): its effect is far below
#: the contract's absolute 1e-12
FAR_MASS = 1e-15

_OUT = ("elastic_area", "load", "plastic_area", "plastic_load", "detached_area",
        "detached_load", "error_estimate")


def _refuse_jumps(G: np.ndarray, rows: np.ndarray, name: str) -> None:
    flat = np.diff(G) == 0
    if np.any(flat) and np.any(np.diff(rows, axis=1)[:, flat] != 0):
        i = int(np.flatnonzero(flat)[0])
        raise ValueError(f"{name} jumps at G = {float(G[i])!r} [Pa^2] (a repeated G with "
                         f"different values); the two-wall solver 'strip' serves walls that "
                         f"are continuous in G (give the jump as a steep ramp)")


def _on_schedule(rows: np.ndarray, G: np.ndarray, U: np.ndarray) -> np.ndarray:
    """Rows sampled at G (linear between, the first value before G[0]) evaluated at U."""
    if U is G:
        return rows
    Gu, first = np.unique(G, return_index=True)
    return np.stack([np.interp(U, Gu, r[first]) for r in rows])


def solve_yield_diffusion(G, pressure, sigma_a, sigma_y, *, method, kinks, level, rtol,
                          n_damp, parallel, check_pressure) -> DiffusionResult:
    """``solve_diffusion`` with a yield wall (see its docstring)."""
    check_yield_method(method)
    const_y = not callable(sigma_y) and np.ndim(sigma_y) == 0
    no_lower = (not callable(sigma_a)) and bool(np.all(as_float_array(
        sigma_a, "sigma_a", "Pa") == 0))
    if const_y:
        hardness = check_hardness(sigma_y, "sigma_y")
    if const_y and no_lower and method in ("analytic", "auto"):
        return _constant(G, pressure, hardness, kinks, level, check_pressure)
    if method == "analytic":
        raise ValueError("method 'analytic' serves a constant sigma_y without a detachment wall "
                         "(sigma_a = 0) only; use method='strip' or 'auto' for these walls; got "
                         f"sigma_y = {sigma_y!r} and sigma_a = {sigma_a!r}")
    return _strip(G, pressure, sigma_a, sigma_y, method=method, kinks=kinks, level=level,
                  rtol=rtol, n_damp=n_damp, parallel=parallel, check_pressure=check_pressure)


def _constant(G, pressure, hardness, kinks, level, check_pressure) -> DiffusionResult:
    if kinks is not None or level is not None:
        raise ValueError("kinks and level apply to the grid methods; a constant sigma_y without "
                         "a detachment wall is the exact series (method 'analytic'); got "
                         f"kinks = {kinks!r}, level = {level!r}")
    p = check_pressure(pressure, allow_negative=False)
    check_below_hardness(p, hardness, "sigma_y")
    t0 = time.perf_counter()
    out = constant_yield(p, G, hardness)
    n_p, n_t = p.size, G.size
    return DiffusionResult(
        G=G, pressure=p, sigma_a=np.zeros((n_p, n_t)), area=out["elastic_area"],
        load=out["load"], detached_area=out["detached_area"],
        detached_load=out["detached_load"], error_estimate=np.zeros((n_p, n_t)),
        method="analytic", status=np.zeros(n_p, dtype=np.int64), success=True, message="ok",
        timings={"solve": time.perf_counter() - t0}, plastic_area=out["plastic_area"],
        plastic_load=out["plastic_load"], sigma_y=hardness)


def _strip(G, pressure, sigma_a, sigma_y, *, method, kinks, level, rtol, n_damp, parallel,
           check_pressure, sigma_y_report=None) -> DiffusionResult:
    """The two-wall solver on the union of the walls' schedules."""
    from .strip import solve_two_walls

    p = check_pressure(pressure, allow_negative=True)
    n_p = p.size
    check_level(level)
    n_damp = check_n_damp(n_damp, STRIP_N_DAMP)   # one damped pair: the start is exact, smooth
    if kinks is not None and not (callable(sigma_a) or callable(sigma_y)):
        raise ValueError("kinks applies to a wall given as a callable (samples are linear "
                         f"between their points already); got kinks = {kinks!r}")
    t_wall = time.perf_counter()
    sampled, capped, user, wall_share = [], [], {}, 0.0
    for name, wall, sign in (("sigma_a", sigma_a, 1.0), ("sigma_y", sigma_y, -1.0)):
        if callable(wall):
            at_user = check_wall_callable(wall, G, name)
            # the yield wall in the mirror sigma -> -sigma is a detachment wall for -p
            tol, kappa = (rtol, 1.0) if sign > 0 else (rtol * YIELD_SAMPLING, YIELD_KAPPA)
            s = sample_wall(wall, G, sign * p, tol, kinks, at_user=at_user, name=name)
            sampled.append(s.G)
            capped.append(s.capped)
            wall_share += kappa * WALL_BUDGET * s.worst_ratio * tol / rtol
            user[name] = np.broadcast_to(at_user, (n_p, G.size)).copy()
        else:
            arr = as_float_array(wall, name, "Pa", ndim=(0, 1, 2))
            check_finite(arr, name, "Pa")
            user[name] = wall_rows(arr, name, n_p, G.size)
            _refuse_jumps(G, user[name], name)
    U = G if not sampled else np.unique(np.concatenate(sampled + [G]))
    rows = {}
    for name, wall in (("sigma_a", sigma_a), ("sigma_y", sigma_y)):
        if callable(wall):
            vals = _call(wall, U, name)
            rows[name] = np.broadcast_to(vals, (n_p, U.size)).copy()
        else:
            rows[name] = _on_schedule(user[name], G, U)
    t_wall = time.perf_counter() - t_wall
    sa, sy = rows["sigma_a"], rows["sigma_y"]
    width = sa + sy
    if np.any(width <= 0):
        k, j = np.argwhere(width <= 0)[0]
        raise ValueError(f"the walls must keep -sigma_a < sigma_y [Pa]; they meet at G = "
                         f"{float(U[j])!r} [Pa^2]: sigma_a = {float(sa[k, j])!r}, sigma_y = "
                         f"{float(sy[k, j])!r}")
    bad = ~((-sa[:, 0] < p) & (p < sy[:, 0]))
    if np.any(bad):
        k = int(np.argmax(bad))
        raise ValueError(f"pressure must lie strictly between the walls at the start, "
                         f"-sigma_a < pressure < sigma_y [Pa] (outside, the whole nominal area "
                         f"detaches or yields at once); got pressure[{k}] = {float(p[k])!r} "
                         f"with sigma_a = {float(sa[k, 0])!r}, sigma_y = {float(sy[k, 0])!r}")
    far = np.zeros(n_p, dtype=bool)
    tail = np.zeros(n_p)
    if method == "auto" and level is None and not np.any(sa):
        tail = yield_wall_reach(U, p, sy)
        far = tail <= FAR_MASS
    if np.all(far):
        t0 = time.perf_counter()
        out = _images(U, p, tail)
        timings, used = {"solve": time.perf_counter() - t0}, "analytic"
    else:
        run = np.flatnonzero(~far)
        part, timings = solve_two_walls(U, p[run], np.ascontiguousarray(sa[run]),
                                        np.ascontiguousarray(sy[run]), rtol=rtol,
                                        n_damp=n_damp,
                                        level=-1 if level is None else int(level),
                                        parallel=parallel)
        used = "strip"
        if run.size == n_p:
            out = part
        else:
            out = _images(U, p, tail)
            for name in _OUT:
                out[name][run] = part[name]
            out["status"][run] = part["status"]
            out["counts"][run] = part["counts"]
    if U is not G:
        index = np.searchsorted(U, G)
        for name in _OUT:
            out[name] = np.ascontiguousarray(out[name][:, index])
    if sampled:
        # the kernel's estimate is that of the sampled (piecewise-linear) walls; the sampling's
        # own contribution is bounded by its share of rtol (walls.py), added here (not for the
        # pressures the yield wall cannot reach: their closed form does not use the samples)
        real = out["elastic_area"] + out["plastic_area"]
        out["error_estimate"] = out["error_estimate"] + np.where(
            far[:, None], 0.0, wall_share * rtol * real)
    status = np.asarray(out["status"]).copy()
    if any(capped):
        status = np.where(status == 0, GRID_CAP, status)
    success, message = summarize_status(status)
    if any(capped):
        message += ("; a callable wall needed more samples than the cap allows for rtol: use a "
                    "larger rtol, declare kinks=, or give samples")
    if sampled:
        timings = {"sample_wall": t_wall, **timings}
    return DiffusionResult(
        G=G, pressure=p, sigma_a=user["sigma_a"], area=out["elastic_area"], load=out["load"],
        detached_area=out["detached_area"], detached_load=out["detached_load"],
        error_estimate=out["error_estimate"], method=used, status=status, success=success,
        message=message, timings=timings, counts=out.get("counts"),
        plastic_area=out["plastic_area"], plastic_load=out["plastic_load"],
        sigma_y=user["sigma_y"] if sigma_y_report is None else sigma_y_report)


def yield_wall_reach(U, p, sy) -> np.ndarray:
    """An upper bound of the mass that ever reaches the yield wall, per pressure.

    Without the detachment wall (which only removes mass) the stress is a Brownian motion
    from p with variance 2G; on each schedule piece [U_k, U_k+1] the wall stays above the
    smaller of its end values (linear between samples), and the probability of reaching a
    level m by G is 2 Phi(-(m - p)/sqrt(2G)) (reflection principle); the sum over the pieces
    (the first one from G = 0) bounds A_pl, and so the change of every area the wall makes.
    """
    ends = np.concatenate([[0.0], U])                      # the wall is sy[0] before U[0]
    rows = np.concatenate([sy[:, :1], sy], axis=1)
    lo = np.minimum(rows[:, :-1], rows[:, 1:]) - p[:, None]
    g = np.broadcast_to(ends[1:], lo.shape)
    with np.errstate(divide="ignore"):
        z = np.where(g > 0, lo / np.sqrt(2.0 * np.where(g > 0, g, 1.0)), np.inf)
    return np.sum(erfc(z / np.sqrt(2.0)), axis=1)


def _images(U, p, tail) -> dict:
    """The one-wall answer (images, sigma_a = 0) for pressures the yield wall never reaches:
    A_pl = 0, with the bound ``tail`` of what it would have taken as the error estimate."""
    n_p = p.size
    el = np.asarray(images_area(p[:, None], U[None, :]), dtype=float)
    zeros = np.zeros((n_p, U.size))
    return {"elastic_area": el, "load": np.broadcast_to(p[:, None], el.shape).copy(),
            "plastic_area": zeros, "plastic_load": zeros.copy(), "detached_area": 1.0 - el,
            "detached_load": zeros.copy(),
            "error_estimate": np.broadcast_to(tail[:, None], el.shape).copy(),
            "status": np.zeros(n_p, dtype=np.int64), "counts": np.zeros((n_p, 3), dtype=np.int64)}


def solve_yield_contact(surface, pressure, z, G, *, e, dg, method, theory, hardness, rtol,
                        parallel, check_pressure) -> ContactResult:
    """``solve_contact`` with a yield wall (no adhesion); ``z`` the checked zeta grid and
    ``G`` = G(zeta) with G[0] = 0."""
    if theory != "persson01":
        raise ValueError(f"hardness applies to the original theory (theory='persson01'); the "
                         f"corrected theories have no yield wall; got theory = {theory!r}")
    check_yield_method(method, "hardness")
    p = check_pressure(pressure, allow_negative=False)
    t0 = time.perf_counter()
    if not callable(hardness) and method != "strip":
        check_below_hardness(p, hardness)
        out = constant_yield(p, G, hardness)
        err, status, used = np.zeros(p.size), np.zeros(p.size, dtype=np.int64), "analytic"
    else:
        wall, kinks, report = hardness, None, hardness       # a constant through "strip"
        if callable(hardness):
            if method == "analytic":
                raise ValueError("method 'analytic' serves a constant hardness only; a "
                                 "scale-dependent one needs method='strip' or 'auto'; got "
                                 f"hardness = {hardness!r}")
            h1 = np.asarray(hardness(np.array([1.0, z[-1]])), dtype=float)
            if h1.shape != (2,) or not np.all(np.isfinite(h1)) or np.any(h1 <= 0):
                raise ValueError(f"hardness(zeta) must return finite values > 0 [Pa] of zeta's "
                                 f"shape; got {h1!r} at zeta = [1, {float(z[-1])!r}]")
            wall, kinks = hardness_in_diffusion_time(hardness, surface, e, float(z[-1]))
            report = None
        # p_nom = 0 starts on the detachment wall (sigma_a = 0): no contact at any zeta,
        # exactly; the two-wall solver takes the pressures inside the strip
        pos = np.flatnonzero(p > 0)
        out = {"elastic_area": np.zeros((p.size, G.size)),
               "plastic_area": np.zeros((p.size, G.size)),
               "detached_area": np.ones((p.size, G.size)), "load": np.zeros((p.size, G.size))}
        err, status = np.zeros(p.size), np.zeros(p.size, dtype=np.int64)
        used = "strip" if method == "strip" else "analytic"
        if pos.size:
            res = _strip(G, p[pos], 0.0, wall, method=method, kinks=kinks, level=None,
                         rtol=rtol, n_damp=None, parallel=parallel,
                         check_pressure=check_pressure, sigma_y_report=report)
            for name, val in (("elastic_area", res.area), ("plastic_area", res.plastic_area),
                              ("detached_area", res.detached_area), ("load", res.load)):
                out[name][pos] = val
            err[pos], status[pos], used = res.error_estimate[:, -1], res.status, res.method
    area_z = out["elastic_area"] + out["plastic_area"]
    area = area_z[:, -1].copy()
    zeros = np.zeros((p.size, z.size))
    success, message = summarize_status(status)
    return ContactResult(
        pressure=p, area=area, zeta=z, G=G, area_zeta=area_z, sigma_a=zeros,
        gamma_eff=zeros.copy(), load=out["load"][:, -1].copy(),
        mean_contact_pressure=per_contact_area(p, area),
        mean_contact_stress=per_contact_area(p, area),
        detached_area=out["detached_area"][:, -1].copy(), detached_load=np.zeros(p.size),
        error_estimate=np.asarray(err, dtype=float).copy(), method=used, status=status,
        success=success, message=message, timings={"solve": time.perf_counter() - t0},
        separation_source=("separation, stiffness and elastic_energy are derived for elastic "
                           f"contact only; got hardness = {hardness!r}"),
        elastic_area=out["elastic_area"][:, -1].copy(),
        plastic_area=out["plastic_area"][:, -1].copy(),
        plastic_area_zeta=out["plastic_area"], hardness=hardness)

