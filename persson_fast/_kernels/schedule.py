"""The scaled schedule and the exact start shared by the grid solvers (``@njit``).

The grid solvers (:mod:`persson_fast._kernels.similarity`,
:mod:`persson_fast._kernels.fixedgrid`, :mod:`persson_fast._kernels.strip`) begin alike:

*Scaled schedule.* Stresses are measured in a start scale (y0 = sigma0 + sigma_a(0), or the
width of the strip between two walls) and G in its square; the schedule gets a leading point
at G = 0 carrying the wall there (:func:`scaled_times`, :func:`scaled_values`).

*Exact start.* Up to a small G_s the solution is known exactly: the linearly moving wall with
the slope of the first linear piece of sigma_a (collinear schedule points merged,
:func:`first_linear_piece`) while G_s lies on that piece, or the free Gaussian while the wall
stays K_WALL_FAR standard deviations away (:func:`wall_far_limit`). :func:`exact_start`
chooses the later of the two starts and writes the schedule points up to it from the exact
solution.

The callers differ in small ways that each keeps (repeated G ends the linear piece where the
wall may jump there, and is tested or skipped where it may not; the free start is sought up
to a fixed G or to the end of the schedule; the detached load is formed in scaled or in the
caller's units; the wall-flux detachment is written too or not): these are arguments here,
not unified behaviour.
"""
from __future__ import annotations

import math

import numpy as np

from .._jit import njit_serial
from .special import linear_wall_area_moment

K_WALL_FAR = 7.0      # a free Gaussian is exact while the wall stays 7 std away (2 Phi(-7) = 3e-12)
MERGE_TOL = 1e-13     # relative distance within which a schedule point is collinear
# first_linear_piece: what a repeated G (a flat stretch of the schedule) does to the piece
REPEAT_ENDS = 0       # ends it (the wall may jump there)
REPEAT_TESTED = 1     # is tested for collinearity like any other point
REPEAT_SKIPPED = 2    # is skipped


@njit_serial
def scaled_times(G, scale):
    """Diffusion times in units of scale^2, with a leading point at G = 0.

    Parameters
    ----------
    G : (n_t,) float64
        Diffusion times.
    scale : float
        Stress scale (G is in stress^2).

    Returns
    -------
    G_k : (n_t + 1,) float64
        0, then G / scale^2.
    """
    nt = G.shape[0]
    G_k = np.empty(nt + 1)
    G_k[0] = 0.0
    for k in range(nt):
        G_k[k + 1] = G[k] / (scale * scale)
    return G_k


@njit_serial
def scaled_values(v, v0, scale):
    """Wall values in units of scale, with the value at G = 0 leading.

    Parameters
    ----------
    v : (n_t,) float64
        Wall values at the schedule points.
    v0 : float
        Wall value at G = 0.
    scale : float
        Stress scale.

    Returns
    -------
    v_k : (n_t + 1,) float64
        v0 / scale, then v / scale.
    """
    nt = v.shape[0]
    v_k = np.empty(nt + 1)
    v_k[0] = v0 / scale
    for k in range(nt):
        v_k[k + 1] = v[k] / scale
    return v_k


@njit_serial
def boundary_at(G_k, sa_k, g):
    """sigma_a at diffusion time g: linear between schedule points, constant outside.

    At a flat stretch (repeated G) the value after the jump is returned.
    """
    n = G_k.shape[0]
    if g <= G_k[0]:
        return sa_k[0]
    if g >= G_k[n - 1]:
        return sa_k[n - 1]
    lo = 0
    hi = n - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if G_k[mid] <= g:
            lo = mid
        else:
            hi = mid
    # G_k[lo] <= g < G_k[hi]; skip to the last of equal G values
    return sa_k[lo] + (sa_k[hi] - sa_k[lo]) * (g - G_k[lo]) / (G_k[hi] - G_k[lo])


@njit_serial
def _running_min_wall_distance(G_k, sa_k, sa0, g):
    """min over G' <= g of y_c(G') = 1 + sigma_a(G') - sigma_a(0) (scaled units)."""
    m = 1.0
    n = G_k.shape[0]
    for k in range(n):
        if G_k[k] > g:
            break
        yc = 1.0 + sa_k[k] - sa0
        if yc < m:
            m = yc
    yc = 1.0 + boundary_at(G_k, sa_k, g) - sa0
    if yc < m:
        m = yc
    return m


@njit_serial
def wall_far_limit(G_k, sa_k, sa0, g_hi):
    """Largest G <= g_hi over which the wall stays K_WALL_FAR std from the free Gaussian."""
    lo = 0.0
    hi = g_hi
    if _running_min_wall_distance(G_k, sa_k, sa0, hi) >= K_WALL_FAR * math.sqrt(2.0 * hi):
        return hi
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if _running_min_wall_distance(G_k, sa_k, sa0, mid) >= K_WALL_FAR * math.sqrt(2.0 * mid):
            lo = mid
        else:
            hi = mid
    return lo


@njit_serial
def fill_state(k_from, k_to, area, load, det_area, det_load, err, out_area, out_load,
               out_det_area, out_det_load, out_error):
    """Write one state (area, load, detached area and load, error) into outputs k_from .. k_to - 1."""
    for k in range(k_from, k_to):
        out_area[k] = area
        out_load[k] = load
        out_det_area[k] = det_area
        out_det_load[k] = det_load
        out_error[k] = err


@njit_serial
def first_linear_piece(G_k, v_k, repeats, open_end):
    """End and slope of the first linear stretch of a wall from G = 0.

    Parameters
    ----------
    G_k : (n,) float64
        Scaled schedule, G_k[0] = 0, non-decreasing, >= 0.
    v_k : (n,) float64
        Wall values there; v_k[0] is the value at G = 0.
    repeats : int
        What a repeated G does to the stretch: REPEAT_ENDS (it ends there), REPEAT_TESTED
        (its point is tested for collinearity like the others) or REPEAT_SKIPPED.
    open_end : bool
        A stretch that reaches the end of the schedule (or a schedule without G > 0) ends at
        infinity; else at the last point (0 without G > 0).

    Returns
    -------
    end : float
        G_k where the stretch ends: the last of the points collinear (to MERGE_TOL) with the
        first piece after G = 0.
    slope : float
        d v / d G on the first piece (0 without G > 0).
    """
    n = G_k.shape[0]
    k = 1
    while k < n and G_k[k] == 0.0:
        k += 1
    if k >= n:
        return (np.inf if open_end else 0.0), 0.0
    end = G_k[k]
    b = (v_k[k] - v_k[0]) / end
    k += 1
    while k < n:
        if G_k[k] > G_k[k - 1] or (repeats == REPEAT_TESTED and G_k[k] == G_k[k - 1]):
            pred = v_k[0] + b * G_k[k]
            if abs(v_k[k] - pred) > MERGE_TOL * (1.0 + abs(pred)):
                return end, b
            end = G_k[k]
        elif repeats != REPEAT_SKIPPED:
            return end, b
        k += 1
    return (np.inf if open_end else end), b


@njit_serial
def exact_start(G_k, sa_k, sa0, sig0, y0, sigma0, repeats, c_start, g_far_hi,
                det_load_scaled, out_area, out_load, out_det_area, out_det_load, out_error,
                out_flux_det, out_flux_det_load):
    """The start of a one-wall grid solve and the exact outputs up to it.

    The start G_s is the later of: the end of the first linear piece of sigma_a (at most
    ``c_start``), from which on the linearly moving wall is exact, and the last G (at most
    ``g_far_hi``) up to which the wall stays K_WALL_FAR std from the free Gaussian.

    Parameters
    ----------
    G_k, sa_k : (n_t + 1,) float64
        Scaled schedule with the leading point at G = 0 (:func:`scaled_times`,
        :func:`scaled_values`; unit y0 = sigma0 + sigma_a(0)).
    sa0, sig0 : float
        sigma_a(0) and sigma0 in units of y0.
    y0, sigma0 : float
        The scale y0 and sigma0 in the caller's units.
    repeats : int
        Repeated G in the first linear piece, see :func:`first_linear_piece`.
    c_start : float
        Latest linear-wall start (scaled).
    g_far_hi : float
        Latest free-Gaussian start (scaled); none for g_far_hi <= 0.
    det_load_scaled : bool
        The detached load formed in scaled units, (load - sig0) y0, or else from the load in
        the caller's units, load y0 - sigma0.
    out_area, out_load, out_det_area, out_det_load, out_error : (n_t,) float64
        Written for the schedule points up to the start: area, load, detached area and load
        (caller's units), error 0.
    out_flux_det, out_flux_det_load : (n_t,) or (0,) float64
        Written like the detached area and load unless empty.

    Returns
    -------
    b_lin : float
        Slope of the first linear piece (scaled).
    start_linear : bool
        The start is the linearly moving wall (else the free Gaussian).
    g_start : float
        The start G_s (scaled).
    i_first : int
        First index of G_k after the start (n_t + 1 when every point lies before it).
    """
    nt = G_k.shape[0] - 1
    piece_end, b_lin = first_linear_piece(G_k, sa_k, repeats, False)
    g_lin = min(c_start, piece_end)
    g_free = wall_far_limit(G_k, sa_k, sa0, g_far_hi) if g_far_hi > 0.0 else 0.0
    start_linear = g_lin >= g_free
    g_start = g_lin if start_linear else g_free
    flux = out_flux_det.shape[0] > 0
    i_first = 1
    while i_first <= nt and G_k[i_first] <= g_start:
        g = G_k[i_first]
        s_here = sa_k[i_first]
        if g == 0.0:
            a = 1.0
            m1 = 1.0
        elif start_linear:
            a, m1 = linear_wall_area_moment(1.0, b_lin, g)
        else:
            a = 1.0
            m1 = 1.0 + s_here - sa0
        if det_load_scaled:
            ld = m1 - s_here * a
            out_load[i_first - 1] = ld * y0
            out_det_load[i_first - 1] = (ld - sig0) * y0
        else:
            ld = (m1 - s_here * a) * y0
            out_load[i_first - 1] = ld
            out_det_load[i_first - 1] = ld - sigma0
        out_area[i_first - 1] = a
        out_det_area[i_first - 1] = 1.0 - a
        out_error[i_first - 1] = 0.0
        if flux:
            out_flux_det[i_first - 1] = out_det_area[i_first - 1]
            out_flux_det_load[i_first - 1] = out_det_load[i_first - 1]
        i_first += 1
    return b_lin, start_linear, g_start, i_first
