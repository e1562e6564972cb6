"""Stress diffusion between two absorbing walls (detachment and yield), compiled, with error
control: the "strip" solver.

In Persson's theory of contact mechanics (B.N.J. Persson, J. Chem. Phys. 115, 3840 (2001);
Surf. Sci. Rep. 61, 201 (2006)) the distribution P(sigma, G) of the local normal stress obeys

    dP/dG = d2P/dsigma2,  P(sigma, 0) = delta(sigma - sigma0),

with absorbing walls at sigma = -sigma_a(G) (detachment) and sigma = sigma_y(G) (yield). This
module validates the input and runs :mod:`persson_fast._kernels.strip` over the pressures
through :func:`persson_fast.sweep.run_sweep`, as every grid method (serial, thread pool or
``prange``; the threaded results are bitwise those of a serial sweep).
"""
from __future__ import annotations

import numpy as np

from ..sweep import check_parallel, run_sweep

__all__ = ["solve_two_walls"]


def _as_array(x, name, unit, ndim):
    arr = np.asarray(x, dtype=np.float64)
    if arr.ndim not in ndim:
        raise ValueError(f"{name} must have {' or '.join(str(d) for d in ndim)} dimension(s) "
                         f"[{unit}]; got shape {arr.shape}")
    bad = ~np.isfinite(arr)
    if np.any(bad):
        idx = np.unravel_index(int(np.argmax(bad)), arr.shape) if arr.ndim else ()
        raise ValueError(f"{name} must be finite [{unit}]; got {name}{list(idx)} = "
                         f"{arr[idx].item()!r}")
    return arr


def _wall_rows(x, name, n_p, n_t):
    arr = _as_array(x, name, "Pa", (1, 2))
    if arr.ndim == 1:
        if arr.shape != (n_t,):
            raise ValueError(f"{name} must have shape (n_p, n_t) = ({n_p}, {n_t}) or (n_t,) "
                             f"[Pa]; got shape {arr.shape}")
        arr = np.repeat(arr[None, :], n_p, axis=0)
    elif arr.shape != (n_p, n_t):
        raise ValueError(f"{name} must have shape (n_p, n_t) = ({n_p}, {n_t}) [Pa]; got shape "
                         f"{arr.shape}")
    return np.array(arr, dtype=np.float64, order="C")


def solve_two_walls(G, pressures, sa_rows, sy_rows, *, rtol, n_damp=1, level=-1,
                    parallel=None):
    """Contact areas and loads between a detachment and a yield wall, one row per pressure.

    Parameters
    ----------
    G : array_like
        (n_t,) diffusion times, G[0] >= 0, non-decreasing (a repeated G must carry equal wall
        values: the walls do not jump). [Pa^2]
    pressures : array_like
        (n_p,) nominal stresses sigma0, -sa[:, 0] < sigma0 < sy[:, 0]. [Pa]
    sa_rows : array_like
        (n_p, n_t) or (n_t,) detachment stress sigma_a at G: the lower wall sits at
        sigma = -sigma_a; linear in G between samples, sa[:, 0] before G[0]. [Pa]
    sy_rows : array_like
        (n_p, n_t) or (n_t,) yield stress sigma_y at G (the upper wall), same rules;
        sa + sy > 0 at every sample. [Pa]
    rtol : float
        Target relative accuracy of the real contact area A = A_el + A_pl:
        |dA| <= rtol A + 1e-12, in [1e-12, 0.1]. [-]
    n_damp : int, optional
        Steps of each run after the start, and after each kink of a wall (a speed jump of
        more than 25 %), taken as two implicit-Euler half steps (Rannacher).
        The default 1 keeps the error ladder asymptotic (measured: with 2 the first ladder's
        estimate overstates the error up to ~1e3 times, so it refines needlessly). [-]
    level : int, optional
        -1 (default): resolution from `rtol`, refined a posteriori; >= 0: explicit resolution
        (nodes and steps double per level), no refinement (convergence studies).
    parallel : None, bool, "threads" or "prange", optional
        See :func:`persson_fast.sweep.choose_parallel`.

    Returns
    -------
    out : dict
        (n_p, n_t) arrays ``elastic_area``, ``plastic_area``, ``detached_area`` [-],
        ``load`` (integral of sigma P), ``plastic_load`` (integral of sigma_y dA_pl),
        ``detached_load`` (integral of sigma_a dD, positive for sigma_a > 0) [Pa] and
        ``error_estimate`` (of A_el + A_pl) [-]; ``status`` (n_p,) int64 (codes of
        :mod:`persson_fast._kernels.status`: OK, RTOL_NOT_MET, GRID_CAP, START_UNRESOLVED,
        NEGATIVE_DENSITY, NONFINITE); ``counts`` (n_p, 3) int64 (coarse intervals, coarse
        steps, refinements). Identities: A_el + A_pl + D = 1 to rounding,
        load + plastic_load - detached_load = sigma0 to rounding (the scheme conserves the
        load moment exactly, see :mod:`persson_fast._kernels.strip`).
    timings : dict
        Seconds: ``solve``, and ``compile`` when this call compiled the kernel.

    Raises
    ------
    ValueError
        On arrays of the wrong shape or non-finite values, decreasing or negative G, a wall
        that changes over a repeated G, sigma0 not strictly between the walls at G = 0,
        sa + sy <= 0 at a sample, rtol outside [1e-12, 0.1], n_damp < 0 or a bad `parallel`.

    Notes
    -----
    Crank-Nicolson on the strip mapped onto [0, 1], started from an exact solution at a small
    G, Richardson-extrapolated over a ladder of three runs whose spread gives the error
    estimate (see :mod:`persson_fast._kernels.strip`). Measured against the exact series of
    two translating walls (|b| W <= 6, rtol = 1e-6): error <= 0.3 rtol, estimate ~2x the
    error; about 4 ms per pressure on 40 G points (one core).
    """
    G = _as_array(G, "G", "Pa^2", (1,))
    n_t = G.size
    if n_t == 0:
        raise ValueError("G must hold at least one diffusion time [Pa^2]; got an empty array")
    if G[0] < 0:
        raise ValueError(f"G must be >= 0 [Pa^2]; got G[0] = {G[0]!r}")
    dec = np.flatnonzero(np.diff(G) < 0)
    if dec.size:
        i = int(dec[0]) + 1
        raise ValueError(f"G must be non-decreasing [Pa^2]; got G[{i}] = {G[i]!r} < "
                         f"G[{i - 1}] = {G[i - 1]!r}")
    p = _as_array(pressures, "pressures", "Pa", (0, 1))
    p = np.array(np.atleast_1d(p), dtype=np.float64, order="C")
    G = np.array(G, dtype=np.float64, order="C")
    n_p = p.size
    sa = _wall_rows(sa_rows, "sa_rows", n_p, n_t)
    sy = _wall_rows(sy_rows, "sy_rows", n_p, n_t)
    rtol = float(rtol)
    if not (np.isfinite(rtol) and 1e-12 <= rtol <= 0.1):
        raise ValueError(f"rtol must be finite and lie in [1e-12, 0.1] [-]; got rtol = {rtol!r}")
    if int(n_damp) != n_damp or n_damp < 0:
        raise ValueError(f"n_damp must be an integer >= 0 [-]; got n_damp = {n_damp!r}")
    if int(level) != level or level < -1:
        raise ValueError(f"level must be -1 (rtol) or an integer >= 0 [-]; got level = "
                         f"{level!r}")
    check_parallel(parallel)
    flat = np.flatnonzero(np.diff(G) == 0)
    for name, w in (("sa_rows", sa), ("sy_rows", sy)):
        jump = np.abs(w[:, flat + 1] - w[:, flat]) > 0
        if np.any(jump):
            r, c = np.argwhere(jump)[0]
            i = int(flat[c]) + 1
            raise ValueError(f"{name} must not jump over a repeated G (the walls are "
                             f"continuous) [Pa]; got {name}[{r}, {i}] = {w[r, i]!r} != "
                             f"{name}[{r}, {i - 1}] = {w[r, i - 1]!r} at G = {G[i]!r} Pa^2")
    width = sa + sy
    if np.any(width <= 0):
        r, i = np.argwhere(width <= 0)[0]
        raise ValueError(f"the walls must not cross: need sa + sy > 0 [Pa]; got "
                         f"sa_rows[{r}, {i}] + sy_rows[{r}, {i}] = {width[r, i]!r}")
    inside = (-sa[:, 0] < p) & (p < sy[:, 0])
    if not np.all(inside):
        r = int(np.argmin(inside))
        raise ValueError(f"pressures must lie strictly between the walls at G = 0: "
                         f"-sa < sigma0 < sy [Pa]; got pressures[{r}] = {p[r]!r} with "
                         f"sa = {sa[r, 0]!r}, sy = {sy[r, 0]!r}")
    out, timings = run_sweep(G, sa, p, sy_rows=sy, rtol=rtol, method="strip", level=int(level),
                             n_damp=int(n_damp), parallel=parallel)
    out["elastic_area"] = out.pop("area")
    return out, timings
