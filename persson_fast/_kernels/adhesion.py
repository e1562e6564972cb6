"""The self-consistent detachment stress sigma_a(zeta) (seed Eqs. 8-9), ``@njit``.

Scaled, dimensionless inputs (the model layer divides stresses by a scene scale and energies by
the work of adhesion):

    sigma_a(zeta_i) = c_i sqrt(max(g_i, 0)),   c_i = beta sqrt(dgamma E* q_i) / scale
    g_i = gamma_eff(zeta_i) / dgamma = (A(zeta1) - U_i) / A(zeta_i)                      (Eq. 9)
    U_i = U_el(zeta_i) / dgamma = sum_{k >= i} wa_k F_k + wb_k F_{k+1},  F = A S(A)

with S = 1 (``gamma_s < 0``) or S = gamma_s + (1 - gamma_s) A^2. The weights wa, wb integrate
(pi E*/2) q^2 C(q) times a function linear in q over each interval exactly (from the surface's
exact moments), so U_el is second-order accurate in the zeta grid.

The fixed point x = sigma_a is solved by Anderson acceleration (type II, ``m_hist`` past
iterates, least squares by normal equations with Tikhonov guard) or, with ``m_hist = 0``, by
plain under-relaxation with factor ``omega``. Start: the full-contact detachment stress (A = 1),
which also serves nominal tension (sigma0 < 0). In tension, an iteration that leaves the
contact branch (its iterates map to "no adhesion anywhere"; or the step safeguard has to hold
the iterate at the wall and the map again puts the wall past the start, sigma0 + F(x)_0 <= 0;
or it stalls with a contact area below rtol) ends in the separated state A = 0; contact
solutions beyond the end of the contact branch are not searched for.

Two additions share the fixed point (see :func:`solve_adhesive_one`): a yield wall sigma_Y
(every diffusion solve is then the two-wall solver of :mod:`.strip`, Eqs. 8-9 as
:func:`yield_detachment_update`), and the corrected theories yp08 and wm17 (the diffusion in
the corrected time T(G) = int S(A) dG, T iterated together with sigma_a). Every fixed point
stops only when the area at zeta1 has settled (``AREA_SETTLE``).
"""
from __future__ import annotations

import math

import numpy as np

from numba import types

from .._jit import CallingKernel, function_at, njit_inline, njit_parallel, njit_serial, prange
from . import status as st
from .schedule import fill_state
from .similarity import GRID_SIGNATURE, SMOOTH_WALL, _solve_grid_tol, solve_variant_by
from .strip import N_DAMP as STRIP_N_DAMP
from .strip import solve_strip
from .theories import correction_factor

#: the fixed point's default controls (the package's ``ADHESION_DEFAULTS``), here because the
#: compiled entry points of :mod:`persson_fast.embed` bake them in (a cached kernel is
#: recompiled when a file with compiled code changes, see :mod:`persson_fast._jit`): the
#: iteration cap, the Anderson depth, the relaxation factor and the Rannacher steps. The
#: Anderson step is taken whole (omega = 1; in tension at most TENSION_OMEGA): on the seed
#: scene at rtol 1e-4 (0 ... 100 MPa) it needs 14.2 iterations per pressure over the three
#: zeta levels against 19.5 with omega = 0.5 (the same areas within 0.35 rtol of an
#: rtol-1e-8 solve), and random probing (``benchmarks/adhesion_probe.py``, seeds 21-25, 150
#: scenes each, whole steps in tension too) finds the same rows outside rtol as with 0.5;
#: with yp08, wm17 and a yield wall (seeds 31-33, 100 scenes each) none, as with 0.5
DEFAULT_MAX_ITER = 100
DEFAULT_M_HIST = 5
DEFAULT_OMEGA = 1.0
DEFAULT_N_DAMP = 2
#: in nominal tension the relaxation factor is at most this: towards the pull-off stress the
#: fixed point is nearly singular, and whole steps from a distant start lose the end of the
#: contact branch sooner (seed scene, rtol 1e-4, from full contact: separated from 0.993
#: sigma_c on, with half steps from 0.995 sigma_c on)
TENSION_OMEGA = 0.5
#: iterations without halving the best residual after which the fixed point gives up
STALL_ITERATIONS = 10
#: the fixed point stops when the sup-norm of F(x) - x, relative to max(|x|, |sigma0|), is
#: below FIXED_POINT_STOP rtol and the last iteration changed the real contact area at zeta1
#: by at most AREA_SETTLE (rtol A + 1e-12). The residual is dominated by the largest sigma_a
#: (at zeta1), while the area is most sensitive to the small sigma_a of the first
#: magnifications, and at zero load on a sticky surface or towards the pull-off fold the map
#: is nearly singular in that direction: a small residual there can leave a large error of
#: the area, which the zeta ladder cannot see (every level stops alike). Measured on random
#: adhesive scenes (``benchmarks/adhesion_probe.py``, seeds 21-24, 150 scenes each): a
#: residual below 0.1 rtol alone left rows up to 2.8 rtol off with status 0 (8 of 817 rows
#: on seeds 21-22, estimates 0.26-0.66x the error); the settling added, or a residual of
#: 0.01 rtol alone, still missed by up to 2.7 rtol on some of the found scenes. Near the
#: fold the residual can stall at the noise of the diffusion solves before it reaches the
#: stop: the first state below FIXED_POINT_FALLBACK rtol is kept and returned if the
#: iteration then stalls or leaves the branch (the stop before these measurements). At most
#: AREA_EXTRA_ITERATIONS iterations are added past the fallback residual; the last change of
#: the area is added to the error estimate either way (with a yield wall, a residual of 0.1
#: rtol alone left 1.2 rtol at rtol 1e-6)
FIXED_POINT_STOP = 0.01
FIXED_POINT_FALLBACK = 0.1
AREA_SETTLE = 0.25
AREA_EXTRA_ITERATIONS = 10
#: consecutive iterates mapped to 'no adhesion anywhere' (F(x) = 0) after which the contact
#: branch counts as lost
LOST_ITERATIONS = 3
#: wall samples inserted in a cell of the zeta grid where gamma_eff changes sign (see
#: :func:`wall_solve`): the crossing point and CROSSING_POINTS - 1 points graded as (k/m)^2
#: towards it, on which the square-root onset of sigma_a is sampled
CROSSING_POINTS = 8
#: in a row with a crossing, a cell whose two node values of sigma_a differ by more than
#: this factor (min/max below it: the cells after a square-root onset) gets the square root's
#: shape, ceil((1 - min/max) SQRT_CELL_DENSITY) - 1 inner samples
SQRT_CELL_RATIO = 0.99
SQRT_CELL_DENSITY = 40.0
#: depth of the detachment wall's cap below the start, in widths sqrt(2 G) of the free
#: spread (see :func:`far_capped`)
FAR_WALL_WIDTHS = 12.0


@njit_serial
def solve_small(M, r):
    """Solve M x = r in place for a small dense system (Gaussian elimination with partial
    pivoting); M is overwritten by its factors, r by x.

    Written out (rather than ``np.linalg.solve``) because the Anderson systems are at most
    ``m_hist`` x ``m_hist`` and LAPACK's bindings roughly double the adhesive kernel's
    compile time.
    """
    n = r.shape[0]
    for k in range(n):
        piv = k
        big = abs(M[k, k])
        for i in range(k + 1, n):
            if abs(M[i, k]) > big:
                big = abs(M[i, k])
                piv = i
        if piv != k:
            for j in range(n):
                t = M[k, j]
                M[k, j] = M[piv, j]
                M[piv, j] = t
            t = r[k]
            r[k] = r[piv]
            r[piv] = t
        for i in range(k + 1, n):
            f = M[i, k] / M[k, k]
            for j in range(k + 1, n):
                M[i, j] -= f * M[k, j]
            r[i] -= f * r[k]
    for k in range(n - 1, -1, -1):
        t = r[k]
        for j in range(k + 1, n):
            t -= M[k, j] * r[j]
        r[k] = t / M[k, k]


@njit_serial
def elastic_energy_ratio(area, wa, wb, gamma_s, out_u):
    """U_el(zeta_i)/dgamma for an area profile (cumulative from zeta1 downwards)."""
    n = area.shape[0]
    out_u[n - 1] = 0.0
    acc = 0.0
    for k in range(n - 2, -1, -1):
        a0 = area[k]
        a1 = area[k + 1]
        if gamma_s >= 0.0:
            f0 = a0 * (gamma_s + (1.0 - gamma_s) * a0 * a0)
            f1 = a1 * (gamma_s + (1.0 - gamma_s) * a1 * a1)
        else:
            f0 = a0
            f1 = a1
        acc += wa[k] * f0 + wb[k] * f1
        out_u[k] = acc


@njit_serial
def detachment_update(area, c, wa, wb, gamma_s, u, g, out_x):
    """One application of Eqs. 8-9: new sigma_a from an area profile. Fills u and g too."""
    yield_detachment_update(area, area, c, wa, wb, gamma_s, u, g, out_x)


@njit_serial
def yield_detachment_update(el, real, c, wa, wb, gamma_s, u, g, out_x):
    """Eqs. 8-9 with a yield wall: U_el from the elastic area ``el`` (the yielded regions
    carry sigma_Y; the roughness finer than where they yielded is flattened plastically and
    stores no elastic energy), gamma_eff per unit real contact area ``real`` = A_el + A_pl
    with the binding energy of the real contact at zeta1 (yielded contact is atomic contact
    and binds): A(zeta) gamma_eff = A(zeta1) dgamma - U_el[A_el](zeta)."""
    n = el.shape[0]
    elastic_energy_ratio(el, wa, wb, gamma_s, u)
    a1 = real[n - 1]
    for i in range(n):
        if real[i] > 0.0:
            g[i] = (a1 - u[i]) / real[i]
        else:
            g[i] = 0.0
        out_x[i] = c[i] * math.sqrt(g[i]) if g[i] > 0.0 else 0.0


@njit_serial
def _is_crossing(g, G, i):
    """gamma_eff changes sign across the cell [G_i, G_i+1] (which has positive width)."""
    return (g[i] > 0.0) != (g[i + 1] > 0.0) and G[i + 1] > G[i]


@njit_serial
def _steep_points(x, G, i):
    """Number of wall samples inserted inside a cell without a sign change of gamma_eff
    where sigma_a changes by a large factor (near a square-root onset): 0 where
    min/max >= SQRT_CELL_RATIO."""
    lo = min(x[i], x[i + 1])
    hi = max(x[i], x[i + 1])
    if not (hi > 0.0) or lo >= SQRT_CELL_RATIO * hi or not (G[i + 1] > G[i]):
        return 0
    return int(math.ceil((1.0 - lo / hi) * SQRT_CELL_DENSITY)) - 1


@njit_serial
def _augmented_wall(G, x, g):
    """The wall samples of :func:`wall_solve`: (Ga, xa, node, na), the schedule with the
    samples inserted near a sign change of gamma_eff (``g``), the node indices in it and its
    length; na = 0 (and empty arrays) in a row without a crossing."""
    n = G.shape[0]
    n_cross = 0
    for i in range(n - 1):
        if _is_crossing(g, G, i):
            n_cross += 1
    if n_cross == 0:
        return np.empty(0), np.empty(0), np.empty(0, dtype=np.int64), 0
    m = CROSSING_POINTS
    cap = n + n_cross * m
    for i in range(n - 1):
        if not _is_crossing(g, G, i):
            cap += _steep_points(x, G, i)
    Ga = np.empty(cap)
    xa = np.empty(cap)
    node = np.empty(n, dtype=np.int64)
    j = 0
    for i in range(n):
        Ga[j] = G[i]
        xa[j] = x[i]
        node[i] = j
        j += 1
        if i == n - 1:
            continue
        if not _is_crossing(g, G, i):
            n_in = _steep_points(x, G, i)
            x0 = x[i]
            x1 = x[i + 1]
            den = x1 * x1 - x0 * x0
            for k in range(1, n_in + 1):
                xk = x0 + (x1 - x0) * (k / (n_in + 1))
                gk = G[i] + (G[i + 1] - G[i]) * ((xk * xk - x0 * x0) / den)
                if not (gk > Ga[j - 1] and gk < G[i + 1]):
                    continue
                Ga[j] = gk
                xa[j] = xk
                j += 1
            continue
        g0 = g[i]
        g1 = g[i + 1]
        width = G[i + 1] - G[i]
        gs = G[i] + width * (g0 / (g0 - g1))
        rising = g1 > 0.0
        for k in range(m):
            if rising:       # zero up to G*, then x_{i+1} sqrt((G - G*)/(G_{i+1} - G*))
                s = (k / m) ** 2
                gk = gs + (G[i + 1] - gs) * s
            else:            # x_i sqrt((G* - G)/(G* - G_i)) down to zero at G*
                s = ((m - 1 - k) / m) ** 2
                gk = gs - (gs - G[i]) * s
            if not (gk > Ga[j - 1] and gk < G[i + 1]):
                continue
            lam = (gk - G[i]) / width
            if rising:
                far = 1.0 if G[i + 1] - gs <= 0.0 else (gk - gs) / (G[i + 1] - gs)
                xa[j] = x[i] * (1.0 - lam) + x[i + 1] * math.sqrt(max(far, 0.0))
            else:
                far = 0.0 if gs - G[i] <= 0.0 else (gs - gk) / (gs - G[i])
                xa[j] = x[i] * math.sqrt(max(far, 0.0)) + x[i + 1] * lam
            Ga[j] = gk
            j += 1
    na = j
    return Ga, xa, node, na


@njit_inline
def wall_solve(grid, variant, G, x, g, sigma0, rtol, n_damp, area, load, det_a, det_l, err,
               counts):
    """The diffusion solve of one fixed-point iterate: the wall -x, linear in G between the
    nodes, except near a sign change of gamma_eff (``g``, of the last update).

    There sigma_a = c sqrt(max(g, 0)) starts (or ends) as a square root of the distance to
    the crossing G*, a kink with an infinite slope. A wall linear between the nodes
    misplaces it by a fraction of the cell, and its chords miss the square root's curvature
    in the cells after it: the zeta-grid error then depends on where the crossing falls
    between the nodes and converges erratically (issue 12). So, in a row with a crossing:

    - in the crossing cell (G* from g linear in G) the wall is sampled at G* and at
      CROSSING_POINTS - 1 points graded as (k/m)^2 away from it, as
      x_far sqrt(|G - G*| / |G_far - G*|) plus the node value on the zero side faded out
      linearly (zero at the fixed point);
    - in a cell whose node values differ by more than the factor SQRT_CELL_RATIO, sigma_a^2
      (= c^2 g, smooth) is taken linear in G and the wall sampled at points equally spaced
      in sigma_a, ceil((1 - min/max) SQRT_CELL_DENSITY) - 1 of them.

    Outputs at the nodes; in a row without a crossing this is ``solve_variant`` (with
    ``SMOOTH_WALL``) on the nodes alone.
    """
    Ga, xa, node, na = _augmented_wall(G, x, g)
    if na == 0:
        return solve_variant_by(grid, variant | SMOOTH_WALL, G, x, sigma0, rtol, np.int64(-1),
                                n_damp, area, load, det_a, det_l, err, counts)
    n = G.shape[0]
    aa = np.empty(na)
    la = np.empty(na)
    da = np.empty(na)
    dl = np.empty(na)
    ea = np.empty(na)
    kstat = solve_variant_by(grid, variant | SMOOTH_WALL, Ga[:na], xa[:na], sigma0, rtol,
                             np.int64(-1), n_damp, aa, la, da, dl, ea, counts)
    for i in range(n):
        area[i] = aa[node[i]]
        load[i] = la[node[i]]
        det_a[i] = da[node[i]]
        det_l[i] = dl[node[i]]
        err[i] = ea[node[i]]
    return kstat


@njit_serial
def wall_solve_two(G, x, g, sy, sigma0, rtol, onset, el, load, pl, pl_load, det_a, det_l, err,
                   counts):
    """:func:`wall_solve` with the yield wall sy (> sigma0 at G[0], linear in G between the
    nodes) beside the detachment wall -x, by the two-wall solver
    (:func:`persson_fast._kernels.strip.solve_strip`): outputs at the nodes, the elastic and
    plastic areas and loads, the detached area and load, the error estimate of the real
    area. The detachment wall is shaped near a sign change of gamma_eff as in
    :func:`wall_solve` (``onset``); sy is interpolated linearly in G at the inserted samples.
    A start at or past the detachment wall (sigma0 <= -x[0]) is separated from the start, one
    at the yield wall (sigma0 >= sy[0]) yielded from the start."""
    n = G.shape[0]
    if sigma0 >= sy[0]:                  # p_nom at the hardness: all yields at the start
        fill_state(np.int64(0), n, 0.0, 0.0, 0.0, 0.0, 0.0, el, load, det_a, det_l, err)
        pl[:] = 1.0
        pl_load[:] = sigma0
        return st.OK
    if sigma0 + x[0] <= 0.0:             # separated at the start
        fill_state(np.int64(0), n, 0.0, 0.0, 1.0, -sigma0, 0.0, el, load, det_a, det_l, err)
        pl[:] = 0.0
        pl_load[:] = 0.0
        return st.OK
    if onset:
        Ga, xa, node, na = _augmented_wall(G, x, g)
    else:
        Ga, xa, node, na = np.empty(0), np.empty(0), np.empty(0, dtype=np.int64), 0
    if na == 0:
        return solve_strip(G, x, sy, sigma0, rtol, np.int64(-1), STRIP_N_DAMP, el, load, pl,
                           pl_load, det_a, det_l, err, counts)
    sya = np.interp(Ga[:na], G, sy)
    out = np.empty((7, na))
    kstat = solve_strip(Ga[:na], xa[:na], sya, sigma0, rtol, np.int64(-1), STRIP_N_DAMP,
                        out[0], out[1], out[2], out[3], out[4], out[5], out[6], counts)
    for i in range(n):
        k = node[i]
        el[i] = out[0, k]
        load[i] = out[1, k]
        pl[i] = out[2, k]
        pl_load[i] = out[3, k]
        det_a[i] = out[4, k]
        det_l[i] = out[5, k]
        err[i] = out[6, k]
    return kstat


@njit_serial
def far_capped(T, x, sigma0):
    """The wall -x, never deeper than FAR_WALL_WIDTHS (K) widths of the free spread below
    the start: x_k <= K sqrt(2 T_k+1 + (y0/K)^2) - sigma0 (y0 = sigma0 + x_0, the start's
    distance to the wall, so the bound is the wall itself at T = 0; each node takes the
    bound at the next node, so that the wall linear between them stays below the curve);
    ``x`` itself where the wall never goes deeper.

    No mass of the distribution goes that deep before the end: without the wall the stress
    is a Brownian motion from sigma0 with variance 2T (the wall only removes mass), which
    reaches sigma0 - sqrt(2 K^2 T + y0^2) on no interval [T_j, 2 T_j] with a chance above
    2 Phi(-K/sqrt 2) (reflection principle), 2e-17 at K = 12, nor before T = y0^2/(2 K^2)
    with one above 2 Phi(-K): the capped wall gives the same solution. But a wall receding
    fast below the distribution (sigma_a growing faster than sqrt(G), e.g. a sticky surface
    at zero load: to 50x sqrt(G1)) widens the grid, which spans the distance from the wall
    to the distribution at every G, and with it the nodes; capped, that distance is at most
    K/sqrt 2 profile widths."""
    n = T.shape[0]
    y0 = sigma0 + x[0]
    if not (y0 > 0.0):
        return x
    k2 = FAR_WALL_WIDTHS * FAR_WALL_WIDTHS
    out = x
    for i in range(n):
        j = min(i + 1, n - 1)
        cap = math.sqrt(2.0 * k2 * T[j] + y0 * y0) - sigma0
        if x[i] > cap:
            if out is x:
                out = x.copy()
            out[i] = cap
    return out


@njit_inline
def _elastic_solve(grid, variant, T, x, g, sigma0, rtol, onset, n_damp, area, load, det_a,
                   det_l, err, counts):
    if onset:
        return wall_solve(grid, variant, T, x, g, sigma0, rtol, n_damp, area, load, det_a,
                          det_l, err, counts)
    return solve_variant_by(grid, variant | SMOOTH_WALL, T, far_capped(T, x, sigma0), sigma0,
                            rtol, np.int64(-1), n_damp, area, load, det_a, det_l, err, counts)


@njit_serial
def elastic_step(grid, variant, T, x, g, sy, sigma0, rtol, onset, n_damp, area, load, pl,
                 pl_load, det_a, det_l, err, counts):
    """The diffusion solve of one fixed-point iterate without a yield wall (``sy``, ``pl``,
    ``pl_load`` unused): :func:`wall_solve` (``onset``), else ``solve_variant`` on the nodes,
    with the grid solver ``grid`` passed by address (:data:`STEP_SIGNATURE`)."""
    return _elastic_solve(grid, variant, T, x, g, sigma0, rtol, onset, n_damp, area, load,
                          det_a, det_l, err, counts)


@njit_inline
def _yield_solve(grid, variant, T, x, g, sy, sigma0, rtol, onset, n_damp, area, load, pl,
                 pl_load, det_a, det_l, err, counts):
    if math.isinf(sy[0]):
        return _elastic_solve(grid, variant, T, x, g, sigma0, rtol, onset, n_damp, area, load,
                              det_a, det_l, err, counts)
    return wall_solve_two(T, x, g, sy, sigma0, rtol, onset, area, load, pl, pl_load, det_a,
                          det_l, err, counts)


@njit_serial
def yield_step(grid, variant, T, x, g, sy, sigma0, rtol, onset, n_damp, area, load, pl,
               pl_load, det_a, det_l, err, counts):
    """The diffusion solve of one fixed-point iterate with the yield wall ``sy``:
    :func:`wall_solve_two`; a yield wall the distribution cannot reach (sy[0] = inf) is left
    out (as :func:`elastic_step`, plastic outputs zero)."""
    return _yield_solve(grid, variant, T, x, g, sy, sigma0, rtol, onset, n_damp, area, load,
                        pl, pl_load, det_a, det_l, err, counts)


@njit_serial
def elastic_step_linked(grid, variant, T, x, g, sy, sigma0, rtol, onset, n_damp, area, load,
                        pl, pl_load, det_a, det_l, err, counts):
    """:func:`elastic_step` with the grid solver linked in (``grid`` None, unused): for
    compiled callers."""
    return _elastic_solve(_solve_grid_tol, variant, T, x, g, sigma0, rtol, onset, n_damp, area,
                          load, det_a, det_l, err, counts)


@njit_serial
def yield_step_linked(grid, variant, T, x, g, sy, sigma0, rtol, onset, n_damp, area, load, pl,
                      pl_load, det_a, det_l, err, counts):
    """:func:`yield_step` with the grid solver linked in (``grid`` None, unused)."""
    return _yield_solve(_solve_grid_tol, variant, T, x, g, sy, sigma0, rtol, onset, n_damp,
                        area, load, pl, pl_load, det_a, det_l, err, counts)


#: the signature of :func:`elastic_step` and :func:`yield_step` (the two are
#: interchangeable), by which the cached fixed point calls them by address, and they the
#: grid solver (:data:`~persson_fast._kernels.similarity.GRID_SIGNATURE`; see
#: :class:`persson_fast._jit.CallingKernel`)
_A = types.float64[::1]
STEP_SIGNATURE = types.int64(types.FunctionType(GRID_SIGNATURE), types.int64, _A, _A, _A, _A,
                             types.float64, types.float64, types.boolean, types.int64, _A, _A,
                             _A, _A, _A, _A, _A, types.int64[::1])


@njit_serial
def corrected_times(G, area, code, gamma, out_t):
    """The corrected diffusion times over G[-1] of an area profile (yp08, wm17).

    The corrected theories spread the stress as dV/dVc = S(A) (see
    :mod:`persson_fast.theories`): in the diffusion picture dT/dG = S(A(G)), T the time of
    the original diffusion equation. T is the trapezoid rule on the zeta grid's nodes
    (second order in the grid, as U_el, which the zeta ladder's extrapolation assumes).
    """
    n = G.shape[0]
    scale = G[n - 1]
    out_t[0] = 0.0
    s_prev = correction_factor(code, gamma, area[0])
    for i in range(1, n):
        s_i = correction_factor(code, gamma, area[i])
        out_t[i] = out_t[i - 1] + 0.5 * (s_prev + s_i) * ((G[i] - G[i - 1]) / scale)
        s_prev = s_i


@njit_serial
def _residual_norm(f, x, sigma0, lo, hi):
    num = 0.0
    den = abs(sigma0)
    for i in range(lo, hi):
        if abs(f[i]) > num:
            num = abs(f[i])
        if abs(x[i]) > den:
            den = abs(x[i])
    if den == 0.0:
        return num
    return num / den


@njit_serial
def _keep(snap, x, area, real, pl, pl_load, g, u, load, det_a, det_l, err, change, restore):
    """Copy the state of an iterate into ``snap`` (12 rows), or back (``restore``)."""
    rows = (x, area, real, pl, pl_load, g, u, load, det_a, det_l, err, change)
    for r in range(12):
        a = rows[r]
        for i in range(snap.shape[1]):
            if restore:
                a[i] = snap[r, i]
            else:
                snap[r, i] = a[i]


@njit_serial
def solve_adhesive_one(variant, G, c, wa, wb, gamma_s, sigma0, rtol, n_damp, max_iter, m_hist,
                       omega, x_init, out_area, out_sigma_a, out_g, out_u, out_load, out_det_area,
                       out_det_load, out_error, onset=True, theory=0, theory_gamma=1.0,
                       sy=None, out_pl=None, out_pl_load=None):
    """Self-consistent contact of one nominal pressure (scaled units).

    Parameters
    ----------
    variant : int -- grid variant of the diffusion solves (see ``solve_variant``; run with
        ``SMOOTH_WALL``).
    G : (n_z,) -- diffusion times at the magnifications, G[0] = 0.
    c : (n_z,) -- beta sqrt(dgamma E* q)/scale at the magnifications.
    wa, wb : (n_z - 1,) -- quadrature weights of U_el / dgamma.
    gamma_s : float -- energy correction gamma_S, or < 0 for S = 1.
    sigma0 : float -- nominal stress / scale (may be negative).
    rtol : float -- tolerance of the diffusion solves; the fixed point stops when the
        sup-norm of F(x) - x, relative to max(|x|, |sigma0|), is below FIXED_POINT_STOP rtol
        and the area at zeta1 has settled (AREA_SETTLE), or falls back to the first state
        below FIXED_POINT_FALLBACK rtol when the iteration stalls.
    n_damp, max_iter, m_hist, omega -- Rannacher steps, iteration cap, Anderson depth
        (0: plain relaxation), relaxation factor (at most TENSION_OMEGA where sigma0 < 0).
    x_init : (n_z,) -- start sigma_a; a negative first entry selects the full-contact start.
        Early iterations solve the diffusion to a looser tolerance (at most 1e-3, at least
        rtol, a tenth of the smallest residual so far); the last ones to rtol.
    out_* -- (n_z,) area, sigma_a, gamma_eff/dgamma, U_el/dgamma, load, detached area and
        load, area error estimate.
    onset : bool -- shape the square-root onset of sigma_a where gamma_eff changes sign
        (:func:`wall_solve`; default); False: the wall linear between the nodes everywhere
        (the discretisation the pull-off branch follower uses).
    sy, out_pl, out_pl_load : None (default: no yield wall), or (n_z,) -- the yield wall
        sigma_Y at the nodes (scaled, > sigma0 at zeta = 1; sy[0] = inf: a wall the
        distribution cannot reach, solved without it), and the plastic area and load
        (outputs). With it every diffusion solve is the two-wall solver
        (:func:`wall_solve_two`); Eqs. 8-9 as :func:`yield_detachment_update` (U_el from
        A_el, gamma_eff per unit real area A_el + A_pl), ``out_area`` is the real area, ``out_load`` the
        elastic load and ``out_error`` the estimate of A_el + A_pl; the corrected time
        (``theory``) takes S of the real area.
    theory, theory_gamma : int, float -- 0 (default): the original theory; YP08 or WM17 of
        :mod:`persson_fast._kernels.theories`: the corrected diffusion dT/dG = S(A(G))
        (:func:`corrected_times`), solved jointly with sigma_a: the Anderson iterate is
        (sigma_a, T/G[-1]) at the nodes, the diffusion of each iterate runs on its times T
        (kept non-decreasing), and the fixed point stops when both residuals, sigma_a's and
        that of T/G[-1] (relative to its largest value), are below the tolerance.

    Returns
    -------
    (status, iterations, residual)
    """
    if sy is None:
        none = np.empty(0)
        return fixed_point_linked(elastic_step_linked, None, variant, G, c, wa, wb, gamma_s,
                                  sigma0, rtol, n_damp, max_iter, m_hist, omega, x_init,
                                  out_area, out_sigma_a, out_g, out_u, out_load, out_det_area,
                                  out_det_load, out_error, onset, theory, theory_gamma, none,
                                  none, none)
    return fixed_point_linked(yield_step_linked, None, variant, G, c, wa, wb, gamma_s, sigma0,
                              rtol, n_damp, max_iter, m_hist, omega, x_init, out_area,
                              out_sigma_a, out_g, out_u, out_load, out_det_area, out_det_load,
                              out_error, onset, theory, theory_gamma, sy, out_pl, out_pl_load)


def _fixed_point(step, grid, variant, G, c, wa, wb, gamma_s, sigma0, rtol, n_damp, max_iter,
                 m_hist, omega, x_init, out_area, out_sigma_a, out_g, out_u, out_load,
                 out_det_area, out_det_load, out_error, onset, theory, theory_gamma, sy, out_pl,
                 out_pl_load):
    """:func:`solve_adhesive_one` with the diffusion solve ``step`` (:func:`elastic_step`, or
    :func:`yield_step` with the yield wall ``sy``; an empty ``sy`` means none) and the grid
    solver ``grid`` given. Compiled as :data:`fixed_point_linked`, inlined into compiled
    callers with ``step`` linked in (the same code as a direct call), and as
    :data:`fixed_point`, which takes ``step`` and ``grid`` by address (compiled and cached
    without the diffusion solver inside it)."""
    has_yield = sy.shape[0] > 0
    n = G.shape[0]
    if sigma0 < 0.0 and omega > TENSION_OMEGA:
        omega = TENSION_OMEGA
    tol = max(FIXED_POINT_STOP * rtol, 1e-13)
    tol_fallback = max(FIXED_POINT_FALLBACK * rtol, 1e-13)
    corrected = theory != 0
    m = 2 * n if corrected else n        # the iterate: sigma_a, then T/G[-1] if corrected
    x = np.empty(m)
    fx = np.empty(m)
    f = np.empty(m)
    x_prev = np.empty(m)
    f_prev = np.empty(m)
    dX = np.zeros((m_hist if m_hist > 0 else 1, m))
    dF = np.zeros((m_hist if m_hist > 0 else 1, m))
    T = G                                # the diffusion times of the iterate
    if corrected:
        T = np.empty(n)
    area = np.empty(n)
    real = area                          # the real contact area A_el + A_pl
    prev = np.full(n, np.nan)            # ... of the previous iteration
    change = np.zeros(n)                 # |real - prev| of the last iteration
    snap = np.empty((12, n))             # the first state below the fallback residual
    have_snap = False
    snap_kstat = 0
    snap_residual = 0.0
    extra = 0
    pl = np.zeros(n)
    pl_load = np.zeros(n)
    if has_yield:
        real = np.empty(n)
    load = np.empty(n)
    det_a = np.empty(n)
    det_l = np.empty(n)
    err = np.empty(n)
    u = np.empty(n)
    g = np.empty(n)
    ones = np.ones(n)
    counts = np.zeros(3, dtype=np.int64)
    # start: the given profile, or the detachment stress of full contact; the diffusion
    # tolerance of the first solve: loose from full contact, rtol from a given start (the
    # zeta ladder's levels start from another level's solution, already near the fixed
    # point: loose first solves would only add their own error to the residual; seed scene
    # at rtol 1e-6, level 0 from level 1: 4.4 iterations instead of 7.1, and a start at the
    # fixed point itself took 9)
    rtol_it = 1e-3
    if x_init[0] >= 0.0:
        rtol_it = rtol
        for i in range(n):
            x[i] = x_init[i]
            g[i] = 1.0          # no crossing known before the first update
    else:
        detachment_update(ones, c, wa, wb, gamma_s, u, g, x)
    if corrected:                        # start from the original times (S(1) = 1)
        for i in range(n):
            x[n + i] = G[i] / G[n - 1]
    status = st.OK
    residual = np.inf
    n_hist = 0
    it = 0
    kstat = 0
    converged = False
    final_pass = False
    best = np.inf
    best_mark = np.inf
    lost = 0
    pinned = False
    it_mark = 0
    while it < max_iter:
        it += 1
        # loose early solves; the tolerance only tightens, so that the diffusion grid (and
        # with it F) stops changing as the iteration settles
        if 0.1 * residual < rtol_it:
            rtol_it = 0.1 * residual
        if rtol_it < rtol or final_pass:
            rtol_it = rtol
        if corrected:
            for i in range(n):
                T[i] = x[n + i] * G[n - 1]
        kstat = step(grid, variant, T, x[:n], g, sy, sigma0, rtol_it, onset, n_damp, area, load,
                     pl, pl_load, det_a, det_l, err, counts)
        if has_yield:
            for i in range(n):
                real[i] = area[i] + pl[i]
        if kstat == st.NONFINITE or kstat == st.BAD_INPUT:
            status = kstat
            break
        # other flags (resolution cap, far leak, jump) of an intermediate iterate are not
        # fatal: the status of the final solve is what the result reports
        if has_yield:
            yield_detachment_update(area, real, c, wa, wb, gamma_s, u, g, fx)
        else:
            detachment_update(area, c, wa, wb, gamma_s, u, g, fx)
        if corrected:
            corrected_times(G, real, theory, theory_gamma, fx[n:])
        for i in range(m):
            f[i] = fx[i] - x[i]
        residual = _residual_norm(f, x, sigma0, 0, n)
        if corrected:
            residual = max(residual, _residual_norm(f, x, 0.0, n, m))
        if not math.isfinite(residual):
            status = st.NONFINITE
            break
        # stagnation: no halving of the best residual over STALL_ITERATIONS iterations
        if residual < best:
            if residual < 0.5 * best_mark:
                best_mark = residual
                it_mark = it
            best = residual
        if it - it_mark > STALL_ITERATIONS:
            break
        # the branch is lost when the iterates map to 'no adhesion anywhere', or when the
        # iterate sits at the wall only because the safeguard below held it there and the map
        # again puts the wall past the start (sigma0 + F(x)_0 <= 0: the tension exceeds the
        # adhesion the contact can muster). Without the second test a tension below the
        # pull-off stress (or on a surface that is not sticky) stalled against the
        # safeguard and came back as not converged instead of separated
        beyond = pinned and sigma0 + fx[0] <= 0.0
        lost = lost + 1 if ((fx[0] == 0.0 or beyond) and x[0] > 0.0 and sigma0 < 0.0) else 0
        if lost >= LOST_ITERATIONS:
            break
        # the area-settling stop (AREA_SETTLE, FIXED_POINT_STOP)
        for i in range(n):
            change[i] = abs(real[i] - prev[i])
            prev[i] = real[i]
        settled = change[n - 1] <= AREA_SETTLE * (rtol * real[n - 1] + 1e-12)
        if residual <= tol_fallback:
            if rtol_it == rtol:
                if (settled and residual <= tol) or extra >= AREA_EXTRA_ITERATIONS:
                    converged = True
                    break
                # the area still moves, or the residual is above the stop: iterate on,
                # keeping this state to fall back to should the further iterations stall
                # or leave the branch (near the pull-off stress the fixed point at fixed
                # p_nom is nearly singular, and the residual can stall at the noise of the
                # diffusion solves)
                if not have_snap:
                    _keep(snap, x, area, real, pl, pl_load, g, u, load, det_a, det_l, err,
                          change, False)
                    have_snap = True
                    snap_kstat = kstat
                    snap_residual = residual
                extra += 1
            else:
                final_pass = True     # converged on a loose inner solve: confirm at rtol
        if real[n - 1] <= 0.0 and sigma0 + x[0] <= 0.0 and fx[0] <= x[0]:
            # separated and the wall keeps closing: no contact is the fixed point
            for i in range(m):
                x[i] = fx[i]
            pinned = False
            continue
        # Anderson (type II) step, or plain relaxation when m_hist == 0
        if m_hist > 0 and it > 1:
            slot = (it - 2) % m_hist
            for i in range(m):
                dX[slot, i] = x[i] - x_prev[i]
                dF[slot, i] = f[i] - f_prev[i]
            if n_hist < m_hist:
                n_hist += 1
        for i in range(m):
            x_prev[i] = x[i]
            f_prev[i] = f[i]
        if m_hist > 0 and n_hist > 0:
            M = np.zeros((n_hist, n_hist))
            r = np.zeros(n_hist)
            for a in range(n_hist):
                for b in range(n_hist):
                    s = 0.0
                    for i in range(m):
                        s += dF[a, i] * dF[b, i]
                    M[a, b] = s
                s = 0.0
                for i in range(m):
                    s += dF[a, i] * f[i]
                r[a] = s
            trace = 0.0
            for a in range(n_hist):
                trace += M[a, a]
            for a in range(n_hist):
                M[a, a] += 1e-10 * trace + 1e-300
            solve_small(M, r)
            coef = r
            for i in range(m):
                corr = 0.0
                for a in range(n_hist):
                    corr += coef[a] * (dX[a, i] + omega * dF[a, i])
                x[i] = x[i] + omega * f[i] - corr
                if x[i] < 0.0:
                    x[i] = 0.0
        else:
            for i in range(m):
                x[i] = x[i] + omega * f[i]
        # safeguard: a step must not carry a contact state across the wall (y0 <= 0), where
        # separation would lock in; backtrack towards the last iterate and drop the history
        y_min = 1e-6 * abs(sigma0)
        pinned = False
        if sigma0 + x_prev[0] > y_min and sigma0 + x[0] <= y_min:
            pinned = True
            for _ in range(60):
                for i in range(m):
                    x[i] = x_prev[i] + 0.5 * (x[i] - x_prev[i])
                if sigma0 + x[0] > y_min:
                    break
            n_hist = 0
        if corrected:          # the times of the next iterate: from 0, non-decreasing
            x[n] = 0.0
            for i in range(n + 1, m):
                if x[i] < x[i - 1]:
                    x[i] = x[i - 1]
    if not converged and status == st.OK and have_snap:
        _keep(snap, x, area, real, pl, pl_load, g, u, load, det_a, det_l, err, change, True)
        converged = True
        kstat = snap_kstat
        residual = snap_residual
    if (not converged and status == st.OK and sigma0 < 0.0
            and (lost >= LOST_ITERATIONS or real[n - 1] <= rtol)):
        # nominal tension and the iteration has left the contact branch: the surfaces
        # separate (A = 0), which is the fixed point reached
        for i in range(n):
            area[i] = 0.0
            real[i] = 0.0
            pl[i] = 0.0
            pl_load[i] = 0.0
            x[i] = 0.0
            g[i] = 0.0
            u[i] = 0.0
            load[i] = 0.0
            det_a[i] = 1.0
            det_l[i] = -sigma0
            err[i] = 0.0
        converged = True
        residual = 0.0
        kstat = st.OK
    if not converged and status == st.OK:
        status = st.NOT_CONVERGED
    if residual > 0.0:                   # not the separated state: charge the last change
        for i in range(n):
            if math.isfinite(change[i]):
                err[i] += change[i]
    if status == st.OK and kstat != st.OK:
        status = kstat
    for i in range(n):
        out_area[i] = real[i]
        out_sigma_a[i] = x[i]
        out_g[i] = g[i]
        out_u[i] = u[i]
        out_load[i] = load[i]
        out_det_area[i] = det_a[i]
        out_det_load[i] = det_l[i]
        out_error[i] = err[i]
    if has_yield:
        for i in range(n):
            out_pl[i] = pl[i]
            out_pl_load[i] = pl_load[i]
    return status, it, residual


#: :func:`_fixed_point` for compiled callers (``step`` a ``*_step_linked``, ``grid`` None)
fixed_point_linked = njit_inline(_fixed_point)
#: :func:`_fixed_point` compiled on its own, for :data:`FIXED_POINT_SIGNATURE`: ``step``
#: (:func:`elastic_step` or :func:`yield_step`) and ``grid`` (the grid solver) by address,
#: so that it is compiled apart from the diffusion solver (which is compiled and cached on
#: its own); the ``prange`` sweep compiles it with linked ones instead
fixed_point = njit_serial(_fixed_point)
FIXED_POINT_SIGNATURE = types.Tuple((types.int64, types.int64, types.float64))(
    types.FunctionType(STEP_SIGNATURE), types.FunctionType(GRID_SIGNATURE), types.int64, _A, _A,
    _A, _A, types.float64, types.float64, types.float64, types.int64, types.int64, types.int64,
    types.float64, _A, _A, _A, _A, _A, _A, _A, _A, _A, types.boolean, types.int64,
    types.float64, _A, _A, _A)


def _adhesive_sweep(fixed_point, step, grid, variant, G, c, wa, wb, n_z, gamma_s, pressures,
                    rtol, n_damp, max_iter, m_hist, omega, x_init, area, sigma_a, g, u, load,
                    det_area, det_load, error, status, iterations, residual, onset, theory,
                    theory_gamma, sy, pl, pl_load):
    """All pressures through :func:`_fixed_point` (``fixed_point``) with the diffusion solve
    ``step`` and the grid solver ``grid``. Every row has a zeta grid of its own: G, c, x_init
    and the outputs (n_p, n_max), wa and wb (n_p, n_max - 1), row k using its first
    ``n_z[k]`` entries (and one fewer of wa, wb); rtol, status, iterations, residual (n_p,);
    a yield wall sy (n_p, n_max) with the outputs pl, pl_load (n_p, n_max), or without one,
    sy, pl and pl_load (n_p, 0)."""
    for k in prange(pressures.shape[0]):
        n = n_z[k]
        s, it, res = fixed_point(step, grid, variant, G[k, :n], c[k, :n], wa[k, :n - 1],
                                 wb[k, :n - 1], gamma_s, pressures[k], rtol[k], n_damp, max_iter,
                                 m_hist, omega, x_init[k, :n], area[k, :n], sigma_a[k, :n],
                                 g[k, :n], u[k, :n], load[k, :n], det_area[k, :n],
                                 det_load[k, :n], error[k, :n], onset, theory, theory_gamma,
                                 sy[k, :n], pl[k, :n], pl_load[k, :n])
        status[k] = s
        iterations[k] = it
        residual[k] = res


_FIXED_POINT_AT = function_at(FIXED_POINT_SIGNATURE)
_STEP_AT = function_at(STEP_SIGNATURE)
_GRID_AT = function_at(GRID_SIGNATURE)
#: the sweep's loop for first-class functions, compiled on its own (not inlined: a call with
#: more than 30 arguments reaches numba as a call with *args, which its inliner refuses)
_adhesive_rows = njit_serial(_adhesive_sweep)


def _adhesive_sweep_at(fixed_point, step, grid, variant, G, c, wa, wb, n_z, gamma_s,
                       pressures, rtol, n_damp, max_iter, m_hist, omega, x_init, area, sigma_a,
                       g, u, load, det_area, det_load, error, status, iterations, residual,
                       onset, theory, theory_gamma, sy, pl, pl_load):
    """:func:`_adhesive_sweep` with the three functions given by their jit addresses
    (:class:`persson_fast._jit.CallingKernel`)."""
    _adhesive_rows(_FIXED_POINT_AT(fixed_point), _STEP_AT(step), _GRID_AT(grid), variant, G, c,
                   wa, wb, n_z, gamma_s, pressures, rtol, n_damp, max_iter, m_hist, omega, x_init,
                   area, sigma_a, g, u, load, det_area, det_load, error, status, iterations,
                   residual, onset, theory, theory_gamma, sy, pl, pl_load)


#: the cached sweep: :data:`fixed_point`, the step and the grid solver all by address (so it
#: is compiled without them, a loop of calls); the ``prange`` sweep (compiled per process) is
#: given :data:`fixed_point` with a ``*_step_linked`` and ``grid`` None, all linked in
adhesive_sweep_serial = CallingKernel(njit_serial(_adhesive_sweep_at),
                                      (FIXED_POINT_SIGNATURE, STEP_SIGNATURE, GRID_SIGNATURE))
adhesive_sweep_parallel = njit_parallel(_adhesive_sweep)
