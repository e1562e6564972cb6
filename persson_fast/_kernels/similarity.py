"""The stress diffusion with an absorbing wall on the front-fixed similarity grid, one
pressure at a time (``@njit``): methods "cn", "cn-plain" and "implicit-euler".

Problem, in diffusion time G:
    dP/dG = d2P/dsigma2,  P(sigma, 0) = delta(sigma - sigma0),  P(-sigma_a(G), G) = 0,
with sigma_a(G) piecewise linear in G between schedule points (a flat stretch of G is a jump).

Scheme
------
Distance to the wall y = sigma + sigma_a(G), start y0 = sigma0 + sigma_a(0). Everything is
scaled by y0 (so y0 = 1 inside). The grid follows the spreading width through the similarity
coordinate xi = y / w(G), w^2 = 1 + 4G, and the log-time s = ln(w)/2 (ds = dG / w^2). The
density p = w Q (Q the density in y) obeys the Fokker-Planck equation

    p_s = d/dxi [ p_xi + (2 xi - w v) p ],     v = d sigma_a / dG,

on the fixed grid xi_j = j h, j = 0..N, p_0 = 0 (absorbing wall), p_N = 0 (far field). Space:
conservative central differences (second order); the uniform wall drift w v is
exponentially fitted (its cell Peclet number raises the diffusion coefficient uniformly),
which keeps thin wall layers monotone and the moment identities exact. Time: theta-steps, Crank-Nicolson with a
Rannacher start (implicit-Euler half steps) after every boundary jump. Steps are uniform in
ln G (geometric in G), the natural step both while the profile is narrow (G << y0^2) and in
the late similarity regime, so the cost per decade of G is fixed. After an isolated kink of a
prescribed wall (a jump of its speed, :func:`_is_graded_kink`) the solution has a transient
singular at the kink (the wall layer restarts as sqrt(G - G_kink)), which uniform steps
resolve at order ~1.4 only; the steps of the next GRADE_SPAN e-folds of G are therefore
GRADE_STEPS times as many and graded as (G - G_kink) ~ u^2 in ln G, which keeps the ladder
second order there (issue 33).

Exact discrete bookkeeping: with the step size dt chosen from the step's growth ratio
r = w_{n+1}/w_n as dt = (r - 1)/(2 theta + 2 (1 - theta) r) and the drift evaluated with the
arithmetic mean of w, the discrete area, first moment, detached area and detached load obey
    A + detached = 1,   load = sigma0 + detached_load
to rounding error (far-field leakage aside, which is reported).

The start is an exact solution at a small G_s (free Gaussian or the linearly moving wall),
projected onto the grid so that its discrete area and first moment are exact. The two runs
(N, M) and (2N, 2M) are combined by Richardson extrapolation, which cancels the leading
O(h^2 + dt^2) error. A third run (N/2, M/2) gives a second extrapolated value, and the
error estimate is that of the returned value (:func:`_ladder_estimate`; from the first kink
of a prescribed wall on, :func:`_first_kink`, it assumes order 2; where a prescribed wall
recedes faster than a diffusion length per node spacing, cell Peclet number w v h > PE_SUB,
the layer it leaves is below the grid and the flux through the wall face is first order in
h: the estimate adds SUB_GRID times that face's advective flux, which the ladder cannot
cancel); with a tolerance
the ladder is refined (nodes and steps doubled) while the estimate misses it, up to the work
cap (then RTOL_NOT_MET or GRID_CAP). The work cap is judged by the steps the tolerance needs
(not those a dense schedule forces) and splits its cut between nodes and steps by the time
order (implicit Euler: nodes f^(1/3), steps f^(2/3)), so that a tighter rtol never buys less.
"""
from __future__ import annotations

import math

import numpy as np
from numba import types

from .._jit import njit_inline, njit_serial
from . import status as st
from .schedule import (REPEAT_ENDS, boundary_at, exact_start, fill_state, scaled_times,
                       scaled_values)
from .pieces import (GRADE_STEPS, KINK_EXTRAPOLATED_ORDER, PIECE_GRADE, PIECE_GRADED, PIECE_HALVE, PIECE_KINK, RECEDING_FACTOR, _first_kink, _is_graded_kink, _kink_count, _pair_pieces, _schedule_steps, _wall_steps)
from .special import linear_wall_area_moment, linear_wall_density, normal_pdf, ndtr
from .tridiag import fitted_diffusion, theta_step

# --- constants of the scheme (dimensionless, y0 = 1) ------------------------------------
C_START = 0.25        # latest start G_s = C_START * y0^2: start std = 0.71 y0
K_ALWAYS_FAR = 8.0    # whole schedule wall-free when the wall stays 8 widths away (< 1e-13)
K_DOMAIN = 6.5        # far end of the grid beyond the farthest profile centre, in xi units
H_BASE = 0.06         # coarse node spacing in xi at rtol = 1e-6
NPER_BASE = 5.0       # coarse steps per unit of ln G at rtol = 1e-6 (11.5 per decade)
NPER_WIDTH = 40.0     # coarse steps per profile width sqrt(2G) travelled by the wall
PECLET_MAX = 0.1       # largest cell Peclet number of the wall drift (exponentially fitted)
                       # at rtol = 1e-6, shrinking with the node spacing below (the wall
                       # layer, 1/(w|v|) wide, is resolved like the profile; at 0.25 and
                       # fixed, fast walls (b y0 = -30) kept an O(h^2) layer error of 20 rtol)
PECLET_CAP = 0.25      # ... and never above this (coarse tolerances)
PE_SUB = 1.0           # a receding wall whose cell Peclet number w v h exceeds this ...
SUB_GRID = 0.5         # ... adds SUB_GRID times its advective wall-face flux to the estimate
WORK_MAX = 4e6       # coarse node-steps above which resolution is cut (and flagged), rtol >= 1e-6
WORK_GROWTH_MAX = 30.0  # below rtol = 1e-6 the cap grows as (1e-6/rtol)^(1/2), as the work of a
                        # plain "cn" scene does, up to this factor (rtol = 1.1e-9)
WORK_TOTAL = 16.0     # hard cap on the node-steps of all runs of a solve (the ladder's three
                      # runs and its refinements; one forced step per schedule piece aside),
                      # in units of the work cap: the plain ladder takes ~5.25x its coarse work
MAX_LEVELS = 8        # at most 2^8 times finer at the start than at the end
N_MAX = 4096          # node cap of the coarse grid
MAX_REFINE = 3        # a-posteriori refinements at most (each doubles nodes and steps)
ASYMPTOTIC_SLACK = 2.0  # successive ladder differences within this factor of 2^p: asymptotic
ZERO_GUARD = 0.5      # no estimate below this share of the smaller of its neighbours
RTOL_ATOL = 1e-12     # absolute part of the accuracy contract |dA| <= rtol A + RTOL_ATOL
EXTRAPOLATED_ORDER = 3.0  # order assumed for the extrapolated error estimate (measured 3.6-4)
LEAK_TOL = 1e-10      # far-field leakage above this is flagged
K_LAYER = 1.0         # after a cut, the wall layer is smoothed over a diffusion time K_LAYER h^2
GRADE_SPAN = 1.0     # e-folds of G after a kink over which the steps are graded ...
KINK_SCALE = 1.6       # resolution factor of a tolerance-driven solve of a kinked wall ...
KINK_MIN_SCALE = 0.6   # ... and its least resolution scale (that of rtol ~ 8e-6) ...
KINK_FEW = 4           # ... where it has at most this many kinks
GAUSS3_X = (-math.sqrt(0.6), 0.0, math.sqrt(0.6))
GAUSS3_W = (5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0)


@njit_serial
def _wall_always_far(G_k, sa_k, sa0, k_far):
    """True when the wall stays k_far free-profile widths from the start at every G.

    y_c(G) = 1 + sigma_a(G) - sigma_a(0) >= k_far sqrt(2G) is checked at the schedule points
    and at the interior minimum of each linear piece (y_c linear, sqrt concave). The free
    Gaussian then never meets the wall up to a probability of order
    (e-folds of G) * Phi(-k_far), below 1e-13 for k_far = 8.
    """
    n = G_k.shape[0]
    for k in range(n):
        if 1.0 + sa_k[k] - sa0 < k_far * math.sqrt(2.0 * G_k[k]):
            return False
        if k > 0 and G_k[k] > G_k[k - 1]:
            b = (sa_k[k] - sa_k[k - 1]) / (G_k[k] - G_k[k - 1])
            if b > 0.0:
                g_star = k_far * k_far / (2.0 * b * b)
                if G_k[k - 1] < g_star < G_k[k]:
                    yc = 1.0 + sa_k[k - 1] + b * (g_star - G_k[k - 1]) - sa0
                    if yc < k_far * math.sqrt(2.0 * g_star):
                        return False
    return True


@njit_serial
def _interp_cubic(p, h, x):
    """Cubic Lagrange interpolation of the node values p at x (odd reflection at the wall)."""
    n = p.shape[0] - 1
    if x <= 0.0 or x >= n * h:
        return 0.0
    k = int(x / h)
    if k >= n:
        k = n - 1
    t = x / h - k
    # nodes k-1, k, k+1, k+2
    vals0 = -p[1] if k == 0 else p[k - 1]
    vals1 = p[k]
    vals2 = p[k + 1]
    vals3 = p[k + 2] if k + 2 <= n else 0.0
    l0 = -t * (t - 1.0) * (t - 2.0) / 6.0
    l1 = (t + 1.0) * (t - 1.0) * (t - 2.0) / 2.0
    l2 = -(t + 1.0) * t * (t - 2.0) / 2.0
    l3 = (t + 1.0) * t * (t - 1.0) / 6.0
    return l0 * vals0 + l1 * vals1 + l2 * vals2 + l3 * vals3


@njit_serial
def _moments(p, h):
    """Discrete area h*sum(p) and first moment h*sum(xi p) (p_0 = p_N = 0).

    Four partial sums each: a single running sum is a chain of dependent additions, and the
    moments are taken at every schedule point of every run.
    """
    n = p.shape[0] - 1
    a0 = 0.0
    a1 = 0.0
    a2 = 0.0
    a3 = 0.0
    m0 = 0.0
    m1 = 0.0
    m2 = 0.0
    m3 = 0.0
    j = 1
    while j + 3 < n:
        a0 += p[j]
        a1 += p[j + 1]
        a2 += p[j + 2]
        a3 += p[j + 3]
        m0 += j * p[j]
        m1 += (j + 1) * p[j + 1]
        m2 += (j + 2) * p[j + 2]
        m3 += (j + 3) * p[j + 3]
        j += 4
    while j < n:
        a0 += p[j]
        m0 += j * p[j]
        j += 1
    return ((a0 + a1) + (a2 + a3)) * h, ((m0 + m1) + (m2 + m3)) * (h * h)


@njit_serial
def _project_moments(p, h, target_area, target_m1):
    """Multiply p by (alpha + beta xi) so that its discrete area and first moment hit the targets."""
    s0 = 0.0
    s1 = 0.0
    s2 = 0.0
    for j in range(1, p.shape[0] - 1):
        x = j * h
        s0 += p[j]
        s1 += x * p[j]
        s2 += x * x * p[j]
    s0 *= h
    s1 *= h
    s2 *= h
    det = s0 * s2 - s1 * s1
    if s0 <= 0.0:
        return
    if abs(det) <= 1e-14 * s0 * s2:
        alpha = target_area / s0
        beta = 0.0
    else:
        alpha = (target_area * s2 - target_m1 * s1) / det
        beta = (s0 * target_m1 - s1 * target_area) / det
    for j in range(1, p.shape[0] - 1):
        p[j] *= alpha + beta * j * h


@njit_serial
def _cut_integrals(p, h, c):
    """Integrals of the interpolated profile over [0, c]: (mass, first moment in xi)."""
    mass = 0.0
    mom = 0.0
    k = 0
    while k * h < c:
        a = k * h
        b = min((k + 1) * h, c)
        half = 0.5 * (b - a)
        mid = 0.5 * (a + b)
        for q in range(3):
            x = mid + half * GAUSS3_X[q]
            f = _interp_cubic(p, h, x)
            mass += GAUSS3_W[q] * half * f
            mom += GAUSS3_W[q] * half * f * x
        k += 1
    return mass, mom


@njit_serial
def _jump(p, h, d_xi, tmp):
    """Shift the profile by d_xi (wall jump), cutting what falls behind the wall.

    Returns (cut_mass, cut_m1, layer_mass): the mass cut at once and its first moment in the
    old xi, and the mass that then drains through the new wall from the discontinuity the cut
    leaves there. That discontinuity is replaced by the exact short-time solution of the
    half-line problem, p(xi) erf(xi / (2 sqrt(tau))), tau = K_LAYER h^2, which conserves the
    first moment of y (as diffusion against an absorbing wall does); its O(h^2) error is
    removed by the Richardson step because tau scales with h^2. The retained area and first
    moment are kept exact by a moment projection.
    """
    n = p.shape[0] - 1
    a_old, m_old = _moments(p, h)
    cut_mass = 0.0
    cut_m1 = 0.0
    if d_xi < 0.0:
        cut_mass, cut_m1 = _cut_integrals(p, h, -d_xi)
        if cut_mass > a_old:
            cut_mass = a_old
    tmp_value_at_wall = _interp_cubic(p, h, -d_xi) if d_xi < 0.0 else 0.0
    tmp[0] = 0.0
    tmp[n] = 0.0
    for j in range(1, n):
        tmp[j] = _interp_cubic(p, h, j * h - d_xi)
    for j in range(n + 1):
        p[j] = tmp[j]
    t0 = a_old - cut_mass
    t1 = (m_old - cut_m1) + d_xi * t0
    if t0 <= 0.0:
        for j in range(n + 1):
            p[j] = 0.0
        return a_old, m_old, 0.0
    layer = 0.0
    if d_xi < 0.0:
        # value at the new wall, then the exact drain of the half-line problem over tau:
        # p(0+) * 2 sqrt(tau / pi) (the linear part of the profile drains nothing)
        p_wall = tmp_value_at_wall
        two_sqrt_tau = 2.0 * math.sqrt(K_LAYER) * h
        for j in range(1, n):
            p[j] *= math.erf(j * h / two_sqrt_tau)
        layer = p_wall * two_sqrt_tau / math.sqrt(math.pi)
        if layer > t0:
            layer = t0
        # the node sum of a layer only a few h wide misses the Euler-Maclaurin term
        # (h^2/12) f'(0), f'(0) = p_wall / sqrt(pi tau): an O(h) term, so the discrete
        # target carries it explicitly
        layer += h * h / 12.0 * 2.0 * p_wall / (math.sqrt(math.pi) * two_sqrt_tau)
        if layer > t0:
            layer = t0
        t0 -= layer
    _project_moments(p, h, t0, t1)
    return cut_mass, cut_m1, layer


@njit_serial
def _stretch(p, h, ratio, tmp):
    """Re-express the profile on the grid of a larger width: p'(xi) = ratio p(ratio xi)."""
    n = p.shape[0] - 1
    tmp[0] = 0.0
    tmp[n] = 0.0
    for j in range(1, n):
        tmp[j] = ratio * _interp_cubic(p, h, ratio * j * h)
    for j in range(n + 1):
        p[j] = tmp[j]


@njit_serial
def _fluxes(p, h, drift, diff):
    """Mass fluxes out of the grid at the wall and at the far end (per unit s)."""
    n = p.shape[0] - 1
    c_wall = h - drift
    c_far = 2.0 * (n - 0.5) * h - drift
    f_wall = p[1] * (diff / h + 0.5 * c_wall)
    f_far = p[n - 1] * (diff / h - 0.5 * c_far)
    return f_wall, f_far


@njit_serial
def march(G_k, sa_k, i_first, g_start, start_linear, b_start, sa0, sigma0, n_nodes, h,
          n_steps_per_lng, n_steps_per_width, refine, n_damp, theta_main, coarsen_at,
          piece_flags, p, tmp, lo, di, up, out_area, out_load, out_det_area, out_det_load,
          out_sub, counts):
    """March one resolution from the exact start at ``g_start`` through the schedule.

    Scaled units (y0 = 1). Each schedule piece gets ``refine`` times the steps that
    ``n_steps_per_lng`` (per unit of ln G) and ``n_steps_per_width`` (per profile width
    travelled by the wall) ask for, so that two resolutions step in exact ratio. At each
    diffusion time in ``coarsen_at`` the grid drops every other node (the profile has widened);
    a moment projection keeps the discrete area and first moment. Fills outputs for schedule
    indices >= ``i_first``. ``theta_main``: 0.5 (Crank-Nicolson) or 1 (implicit Euler) for
    the undamped steps. ``piece_flags[i]`` (per schedule index, for the piece ending there):
    PIECE_HALVE takes ``refine // 2`` steps on it (a piece one step of the coarsest run shares
    with its neighbour, see :func:`_pair_pieces`), PIECE_KINK starts ``n_damp`` damped steps
    after the point, PIECE_GRADE marks a piece that starts at a kink: the steps of the next
    GRADE_SPAN e-folds of G are graded (GRADE_STEPS times as many, (G - G_kink) ~ u^2 in
    ln G). ``out_sub`` receives the sub-grid uncertainty of a fast receding wall accumulated
    up to each output (SUB_GRID, PE_SUB). Adds the steps and node-steps taken to
    ``counts[1]``, ``counts[2]``. Returns (status, leak), leak the mass lost through the far
    end.
    """
    n = n_nodes - 1
    p = p[: n + 1]
    tmp = tmp[: n + 1]
    i_coarse = 0
    n_coarse = coarsen_at.shape[0]
    w = math.sqrt(1.0 + 4.0 * g_start)
    # exact start profile on the grid
    sa_s = boundary_at(G_k, sa_k, g_start)
    yc = 1.0 + sa_s - sa0
    for j in range(n + 1):
        y = j * h * w
        if start_linear:
            p[j] = w * linear_wall_density(y, 1.0, b_start, g_start)
        else:
            p[j] = w * normal_pdf(y - yc, 2.0 * g_start)
    p[0] = 0.0
    p[n] = 0.0
    if start_linear:
        a_s, m1_s = linear_wall_area_moment(1.0, b_start, g_start)
    else:
        sd = math.sqrt(2.0 * g_start)
        u = yc / sd
        a_s = ndtr(u)
        m1_s = yc * a_s + sd * math.exp(-0.5 * u * u) / math.sqrt(2.0 * math.pi)
    _project_moments(p, h, a_s, m1_s / w)
    det = 1.0 - a_s
    load_s = m1_s - sa_s * a_s
    det_load = load_s - sigma0
    leak = 0.0
    det_c = 0.0
    det_load_c = 0.0
    # the sub-grid uncertainty of the wall flux where a receding wall outruns the node
    # spacing (cell Peclet number w v h > PE_SUB, see SUB_GRID)
    sub_unc = 0.0
    jumped = False
    damp_left = 0
    # the last kink (a point whose next piece is flagged PIECE_GRADE), 0 before any
    g_kink = g_start if (i_first < G_k.shape[0] and piece_flags[i_first] & PIECE_GRADE) else 0.0
    g_cur = g_start
    sa_cur = sa_s
    n_out = G_k.shape[0]
    for i in range(i_first, n_out):
        g_end = G_k[i]
        if g_end <= g_cur:
            # a flat stretch of G: the wall jumps
            d = sa_k[i] - sa_cur
            if d != 0.0:
                jumped = True
                cut_mass, cut_m1, layer = _jump(p, h, d / w, tmp)
                det += cut_mass
                det_load -= w * cut_m1 - sa_cur * cut_mass
                sa_cur = sa_k[i]
                if layer > 0.0:
                    # the layer drained during tau = K_LAYER h^2 of log-time: advance the clock
                    g_next = G_k[i + 1] if i + 1 < n_out else g_cur
                    v_next = 0.0
                    w_new = w * math.exp(2.0 * K_LAYER * h * h)
                    g_new = 0.25 * (w_new * w_new - 1.0)
                    if g_next > g_cur:
                        v_next = (sa_k[i + 1] - sa_cur) / (g_next - g_cur)
                        limit = g_cur + 0.25 * (g_next - g_cur)
                        if g_new > limit:
                            g_new = limit
                            w_new = math.sqrt(1.0 + 4.0 * g_new)
                    else:
                        g_new = g_cur
                        w_new = w
                    a_l, m_l = _moments(p, h)
                    dg = g_new - g_cur
                    target_m1y = w * m_l + v_next * a_l * dg
                    _stretch(p, h, w_new / w, tmp)
                    _project_moments(p, h, a_l, target_m1y / w_new)
                    sa_cur = sa_cur + v_next * dg
                    det += layer
                    det_load += sa_cur * layer
                    g_cur = g_new
                    w = w_new
                damp_left = n_damp
        else:
            v = (sa_k[i] - sa_cur) / (g_end - g_cur)
            while g_cur < g_end:
                # coarsen when due; a coarsening time is an exact step boundary of both runs
                while i_coarse < n_coarse and g_cur >= coarsen_at[i_coarse]:
                    i_coarse += 1
                    if n % 2 == 0:
                        a_c, m_c = _moments(p, h)
                        for j in range(n // 2 + 1):
                            p[j] = p[2 * j]
                        n //= 2
                        h *= 2.0
                        p = p[: n + 1]
                        tmp = tmp[: n + 1]
                        _project_moments(p, h, a_c, m_c)
                g_stop = g_end
                sa_stop = sa_k[i]
                if i_coarse < n_coarse and coarsen_at[i_coarse] < g_end:
                    g_stop = coarsen_at[i_coarse]
                    sa_stop = sa_cur + v * (g_stop - g_cur)
                w_stop = math.sqrt(1.0 + 4.0 * g_stop)
                lng = math.log(g_stop / g_cur)
                m = int(math.ceil(lng * n_steps_per_lng - 1e-9))
                # the wall may travel at most 1/n_steps_per_width of the profile width per step
                per_width = n_steps_per_width if v < 0.0 else n_steps_per_width * RECEDING_FACTOR
                m_wall = _wall_steps(g_cur, g_stop, sa_cur, sa_stop, per_width, lng,
                                     n_steps_per_lng)
                if m_wall > m:
                    m = m_wall
                if m < 1:
                    m = 1
                if piece_flags[i] & PIECE_HALVE and refine >= 2:
                    m *= refine // 2
                else:
                    m *= refine
                # within GRADE_SPAN e-folds of G after a kink, GRADE_STEPS times the steps,
                # graded as tau = GRADE_SPAN u^2 (tau = ln(G / G_kink), u uniform): the error
                # of the singular transient after the kink stays second order in the step
                m_all = m
                u_a = 0.0
                du = 0.0
                if g_kink > 0.0:
                    tau_a = math.log(g_cur / g_kink)
                    if tau_a < GRADE_SPAN:
                        m_all = GRADE_STEPS * m
                        u_a = math.sqrt(tau_a / GRADE_SPAN)
                        du = (math.sqrt(math.log(g_stop / g_kink) / GRADE_SPAN) - u_a) / m_all
                ratio = g_stop / g_cur if m == 1 else (g_stop / g_cur) ** (1.0 / m)
                g_a = g_cur
                for step in range(m_all):
                    if damp_left > 0:
                        n_sub = 2
                        theta = 1.0
                        damp_left -= 1
                    else:
                        n_sub = 1
                        theta = theta_main
                    counts[1] += n_sub
                    counts[2] += n_sub * (n - 1)
                    if du > 0.0:
                        u_b = u_a + du * (step + 1.0)
                        step_ratio = g_kink * math.exp(GRADE_SPAN * u_b * u_b) / g_a
                    else:
                        step_ratio = ratio
                    rho = step_ratio if n_sub == 1 else math.sqrt(step_ratio)
                    for sub in range(n_sub):
                        if step == m_all - 1 and sub == n_sub - 1:
                            g_b = g_stop
                            w_b = w_stop
                            sa_b = sa_stop
                        else:
                            g_b = g_a * rho
                            w_b = math.sqrt(1.0 + 4.0 * g_b)
                            sa_b = sa_cur + v * (g_b - g_a)
                        rr = w_b / w
                        dt = (rr - 1.0) / (2.0 * theta + 2.0 * (1.0 - theta) * rr)
                        drift = v * 0.5 * (w + w_b)
                        # fit only a wall moving into the distribution (v < 0): then 2 xi and
                        # -w v add up and the layer at the wall is real; a receding wall leaves
                        # no layer and fitting would only add diffusion where the mass sits
                        diff = fitted_diffusion(drift * h) if v < 0.0 else 1.0
                        fw0, ff0 = _fluxes(p, h, drift, diff)
                        p1_a = p[1]
                        theta_step(p, h, drift, diff, dt, theta, lo, di, up)
                        fw1, ff1 = _fluxes(p, h, drift, diff)
                        if drift * h > PE_SUB:
                            # the advective part of the flux through the wall face,
                            # -drift (p_0 + p_1)/2: where the wall recedes by more than a
                            # diffusion length per node spacing, the layer it leaves is
                            # below the grid and this flux is not the wall's (its error is
                            # first order in h, measured 1-2x this term)
                            sub_unc += SUB_GRID * dt * drift * 0.5 * (
                                (1.0 - theta) * abs(p1_a) + theta * abs(p[1]))
                        d_det = dt * ((1.0 - theta) * fw0 + theta * fw1)
                        # compensated (Kahan) sums: thousands of tiny increments
                        yk = d_det - det_c
                        tk = det + yk
                        det_c = (tk - det) - yk
                        det = tk
                        yk = (theta * sa_cur + (1.0 - theta) * sa_b) * d_det - det_load_c
                        tk = det_load + yk
                        det_load_c = (tk - det_load) - yk
                        det_load = tk
                        leak += dt * ((1.0 - theta) * ff0 + theta * ff1)
                        w = w_b
                        g_a = g_b
                        sa_cur = sa_b
                g_cur = g_stop
                sa_cur = sa_stop
            g_cur = g_end
            sa_cur = sa_k[i]
            if piece_flags[i] & PIECE_KINK:
                damp_left = n_damp
            if i + 1 < n_out and piece_flags[i + 1] & PIECE_GRADE:
                g_kink = g_cur
        a, m1 = _moments(p, h)
        if not (math.isfinite(a) and math.isfinite(m1)):
            return st.NONFINITE, leak
        out_area[i] = a
        out_load[i] = w * m1 - sa_cur * a
        out_det_area[i] = det
        out_det_load[i] = det_load
        out_sub[i] = sub_unc
    if leak > LEAK_TOL:
        return st.FAR_LEAK, leak
    if jumped:
        return st.WALL_JUMP, leak
    return st.OK, leak


#: grid variants of this kernel: (theta of the undamped steps, Richardson extrapolation,
#: order of the result in the resolution, exponent of the space refinement per time refinement)
CN = 0              # Crank-Nicolson, Richardson-extrapolated: order 4
CN_PLAIN = 1        # Crank-Nicolson, the finer of the two runs: order 2
IMPLICIT_EULER = 2  # implicit Euler, the finer run: order 1 in the step
SMOOTH_WALL = 8     # added to a variant: no kink detection (the adhesive fixed point's walls)
#: resolution of level 0 of the explicit ladder, relative to the rtol = 1e-6 grid of "cn"
LEVEL0_SCALE = 0.25
#: error constants of the unextrapolated variants at unit scale (measured on the images and
#: moving-wall oracles, with a margin): plain CN's error is CN_PLAIN_C / scale^2, implicit
#: Euler's IE_C / scale_t (its space error is that of plain CN)
CN_PLAIN_C = 1e-3
IE_C = 0.012


@njit_serial
def variant_resolution(variant, rtol, level):
    """(space scale, time scale, theta, extrapolate) of a grid variant.

    ``level >= 0`` is the explicit ladder (both scales double per level, from LEVEL0_SCALE);
    else the scales follow from ``rtol`` and the variant's order: the node spacing is
    H_BASE / space scale and the steps per ln G are NPER_BASE * time scale. The last entry
    is the work cap in coarse node-steps: WORK_MAX, grown below rtol = 1e-6 as
    (1e-6/rtol)^(1/2) up to WORK_GROWTH_MAX (the level ladder keeps WORK_MAX).
    """
    theta = 1.0 if variant == IMPLICIT_EULER else 0.5
    extrapolate = variant == CN
    if level >= 0:
        s = LEVEL0_SCALE * 2.0 ** level
        return s, s, theta, extrapolate, WORK_MAX
    work_max = WORK_MAX * min(max(1.0, math.sqrt(1e-6 / rtol)), WORK_GROWTH_MAX)
    if variant == CN:
        s = (1e-6 / rtol) ** 0.25
        return s, s, theta, extrapolate, work_max
    s = max(LEVEL0_SCALE, math.sqrt(CN_PLAIN_C / rtol))
    if variant == CN_PLAIN:
        return s, s, theta, extrapolate, work_max
    return s, max(LEVEL0_SCALE, IE_C / rtol), theta, extrapolate, work_max


@njit_serial
def solve_one(G, sa, sigma0, rtol, n_damp, out_area, out_load, out_det_area, out_det_load,
              out_error):
    """The "cn" variant of :func:`solve_grid` at tolerance ``rtol`` (no work counts)."""
    counts = np.zeros(3, dtype=np.int64)
    sx, stp, theta, extrapolate, work_max = variant_resolution(CN, rtol, np.int64(-1))
    return _solve_grid_tol(G, sa, sigma0, sx, stp, theta, extrapolate, work_max, n_damp, rtol,
                           out_area, out_load, out_det_area, out_det_load, out_error, counts)


@njit_inline
def solve_variant(variant, G, sa, sigma0, rtol, level, n_damp, out_area, out_load,
                  out_det_area, out_det_load, out_error, counts):
    """One pressure with grid variant ``variant`` (CN, CN_PLAIN, IMPLICIT_EULER).

    With ``level`` < 0 the resolution follows from ``rtol`` and the result is refined until
    its error estimate meets ``rtol`` (or the work cap: then flagged); an explicit
    ``level`` >= 0 is solved at that resolution only. ``variant | SMOOTH_WALL`` skips the
    kink detection of :func:`_first_kink` (the adhesive fixed point and its pull-off branch:
    their wall is a node interpolant in zeta whose error the zeta ladder controls).
    """
    return solve_variant_by(_solve_grid_tol, variant, G, sa, sigma0, rtol, level, n_damp,
                            out_area, out_load, out_det_area, out_det_load, out_error, counts)


@njit_inline
def solve_variant_by(grid, variant, G, sa, sigma0, rtol, level, n_damp, out_area, out_load,
                     out_det_area, out_det_load, out_error, counts):
    """:func:`solve_variant` through ``grid``: :func:`_solve_grid_tol` itself, or passed by
    address (a first-class function of :data:`GRID_SIGNATURE`, see
    :class:`persson_fast._jit.CallingKernel`)."""
    detect = (variant & SMOOTH_WALL) == 0
    base = variant if detect else variant - SMOOTH_WALL
    sx, stp, theta, extrapolate, work_max = variant_resolution(base, rtol, level)
    return grid(G, sa, sigma0, sx, stp, theta, extrapolate, work_max, n_damp,
                rtol if level < 0 else 0.0, out_area, out_load, out_det_area, out_det_load,
                out_error, counts, detect)


@njit_serial
def _ladder_estimate(area_b, area_c, area_f, keep_b, i_first, extrapolate, order, rtol, est,
                     kink_first, sub_f, zero_guard):
    """Error estimate of the returned area from three runs in exact 2:1 ratio; True when it
    meets ``rtol`` (|error| <= rtol A + RTOL_ATOL at every output, or ``rtol`` <= 0).

    B, C, F: the runs at spacing 4h, 2h, h (steps alike). The result is the Richardson
    extrapolation R = (4F - C)/3 of the order-2 pair (``extrapolate``), else F (scheme order
    ``order``). With d1 = C - B, d2 = F - C, a ladder in its asymptotic range has
    d1/d2 ~ 2^p (p = 2 for the pair): then the error of R is |R(h) - R(2h)|/(2^q - 1),
    R(h) - R(2h) = (4 d2 - d1)/3, taken with q = EXTRAPOLATED_ORDER = 3 (the order the
    extrapolated results show on moving and kinked walls, 3 to 4: at order 4 the estimate
    is about 2x the error, at order 2 about 0.6x); from the first kink of the wall on
    (``kink_first``, see :func:`_first_kink`) with q = KINK_EXTRAPOLATED_ORDER = 2, the order
    the extrapolation keeps across a jump of the wall speed; the error of F is
    |d2|/(2^order - 1).
    Where the ratio is off by more than ASYMPTOTIC_SLACK (or the signs differ) the ladder
    is not asymptotic and the larger, un-extrapolated measure is taken as well: |d2|/3 for
    R (the error of F), |d2| for F. Implicit Euler (``order`` 1, not extrapolated) errs by
    a dt + b h^2, both halved per run: the three runs give that error as (d1 - 5 d2)/3, and
    the larger of it and |d2| is taken. ``sub_f`` (the finest run's sub-grid uncertainty
    of a fast receding wall, first order in h) is added; no estimate is left below
    ``zero_guard`` times the smaller of its neighbours'. A non-finite B (the coarsest run)
    leaves the un-extrapolated measure. Where B skipped the point (``keep_b`` False: it crossed a pair
    of pieces in one step, see :func:`_pair_pieces`; never the first or last point) the
    estimate is the larger of its neighbours' (the error of R is smooth in G; B's value there
    would have to be interpolated, which fails where the error changes fast after the start).
    """
    met = True
    q = 4.0 if extrapolate else 2.0 ** order
    n = area_f.shape[0]
    for k in range(i_first, n):
        if not keep_b[k]:
            continue
        d1 = area_c[k] - area_b[k]
        d2 = area_f[k] - area_c[k]
        if extrapolate:
            q_ext = EXTRAPOLATED_ORDER if k < kink_first else KINK_EXTRAPOLATED_ORDER
            e_lo = abs(4.0 * d2 - d1) / (3.0 * (2.0 ** q_ext - 1.0))
            # the error of F; from the first kink on the extrapolation can be worse than F
            # where the ladder is not asymptotic (measured: 8x F's error at a coarse level),
            # so the un-extrapolated difference itself, which bounds both
            e_hi = abs(d2) / 3.0 if k < kink_first else abs(d2)
            a = area_f[k] + d2 / 3.0
        else:
            e_lo = abs(d2) / (q - 1.0)
            e_hi = abs(d2)
            a = area_f[k]
        asym = d1 * d2 > 0.0 and abs(d1) <= q * ASYMPTOTIC_SLACK * abs(d2) and \
            q * abs(d2) <= ASYMPTOTIC_SLACK * abs(d1)
        e = e_lo if asym else max(e_lo, e_hi)
        if order < 1.5 and not extrapolate:
            # implicit Euler: the error of F is a dt + b h^2 (first order in the step, second
            # in the nodes, both halved per run); B, C, F solve for both parts, the error of F
            # being (d1 - 5 d2)/3. Where the two parts have opposite signs, |d2| alone can sit
            # far below it (measured 0.51x on a callable wall, issue 33)
            e = max(e, abs(d1 - 5.0 * d2) / 3.0)
        if not math.isfinite(e):
            e = e_hi
        if not math.isfinite(e):
            met = False
        # the sub-grid uncertainty of a fast receding wall (first order in h: the ladder
        # does not cancel it), that of the finest run
        e += sub_f[k]
        est[k] = e
        if e > rtol * min(max(a, 0.0), 1.0) + RTOL_ATOL:
            met = False
    for k in range(i_first + 1, n - 1):
        if keep_b[k]:
            continue
        e = max(est[k - 1], est[k + 1], sub_f[k])
        est[k] = e
        a = area_f[k] + (area_f[k] - area_c[k]) / 3.0 if extrapolate else area_f[k]
        if e > rtol * min(max(a, 0.0), 1.0) + RTOL_ATOL:
            met = False
    # a difference of runs can pass through zero at a G where the error does not (their
    # zeros sit at slightly different G): no estimate below zero_guard (ZERO_GUARD on a
    # prescribed wall) times the smaller of its neighbours' (measured 0.05x the error at a
    # kink point, issue 33)
    e_prev = est[i_first]
    for k in range(i_first + 1, n - 1 if zero_guard > 0.0 else 0):
        e_here = est[k]
        guard = zero_guard * min(e_prev, est[k + 1])
        e_prev = e_here
        if e_here < guard:
            est[k] = guard
            a = area_f[k] + (area_f[k] - area_c[k]) / 3.0 if extrapolate else area_f[k]
            if guard > rtol * min(max(a, 0.0), 1.0) + RTOL_ATOL:
                met = False
    return met or rtol <= 0.0


@njit_serial
def solve_grid(G, sa, sigma0, scale_x, scale_t, theta, extrapolate, work_max, n_damp,
               out_area, out_load, out_det_area, out_det_load, out_error, counts):
    """Contact area and load bookkeeping of one nominal pressure, in consistent units, at a
    given resolution (no a-posteriori refinement: see :func:`solve_variant`).

    Parameters
    ----------
    G : (n_t,) float64 -- non-decreasing diffusion times, G[0] >= 0 (repeats = wall jumps).
    sa : (n_t,) float64 -- detachment stress sigma_a at those times (wall at -sa), linear in
        between, constant sa[0] before G[0].
    sigma0 : float -- nominal stress (compressive > 0), same stress unit as sqrt(G).
    scale_x, scale_t : float -- resolution in space and time: the coarse node spacing is
        H_BASE / scale_x, the coarse steps per unit of ln G NPER_BASE * scale_t.
    theta : float -- 0.5 (Crank-Nicolson) or 1 (implicit Euler) for the undamped steps.
    extrapolate : bool -- report the Richardson extrapolation of the runs (N, M), (2N, 2M)
        (order 2 -> 4 for Crank-Nicolson); else the finer run.
    work_max : float -- coarse node-steps past which the resolution is cut (GRID_CAP).
    n_damp : int -- Crank-Nicolson steps replaced by two implicit-Euler half steps after
        each wall jump (Rannacher damping).
    out_* : (n_t,) float64 -- area A/A0, load int sigma P, detached area, detached load
        int sigma_a g dG, and an error estimate of the returned area (from a third run
        (N/2, M/2), see :func:`_ladder_estimate`).
    counts : (3,) int64 -- set to the coarse nodes, then steps and node-steps of all runs.

    Returns
    -------
    status : int -- 0 ok, see :mod:`persson_fast._kernels.status`.

    Notes
    -----
    The whole computation is scale-free: units only need to be consistent
    (stress and sqrt(G) in the same unit).
    """
    return _solve_grid_tol(G, sa, sigma0, scale_x, scale_t, theta, extrapolate, work_max,
                           n_damp, 0.0, out_area, out_load, out_det_area, out_det_load,
                           out_error, counts)


@njit_serial
def _solve_grid_tol(G, sa, sigma0, scale_x, scale_t, theta, extrapolate, work_max, n_damp,
                    rtol, out_area, out_load, out_det_area, out_det_load, out_error, counts,
                    detect_kinks=True):
    """:func:`solve_grid` with a-posteriori control: while the error estimate of the returned
    area misses ``rtol`` (``rtol`` > 0) the ladder is refined (nodes and steps doubled) up to
    the work cap; a result that still misses it is flagged RTOL_NOT_MET.
    """
    nt = G.shape[0]
    if sa.shape[0] != nt or out_area.shape[0] != nt:
        return st.BAD_INPUT
    # wall position at G = 0 and survival of the jumps at G = 0
    k0 = -1
    for k in range(nt):
        if G[k] == 0.0:
            k0 = k
        else:
            break
    sa0 = sa[0] if k0 < 0 else sa[k0]
    separated = sigma0 + sa[0] <= 0.0
    for k in range(k0 + 1):
        if sigma0 + sa[k] <= 0.0:
            separated = True
    if separated:
        fill_state(np.int64(0), nt, 0.0, 0.0, 1.0, -sigma0, 0.0, out_area, out_load, out_det_area,
                    out_det_load, out_error)
        return st.OK
    y0 = sigma0 + sa0
    G_k = scaled_times(G, y0)
    sa_k = scaled_values(sa, sa0, y0)
    sa0s = sa0 / y0
    sig0s = sigma0 / y0
    # the wall never comes near the distribution: the free solution is exact (A = 1)
    if _wall_always_far(G_k, sa_k, sa0s, K_ALWAYS_FAR):
        fill_state(np.int64(0), nt, 1.0, sigma0, 0.0, 0.0, 0.0, out_area, out_load, out_det_area,
                    out_det_load, out_error)
        return st.OK
    # the start (a repeated G ends the first linear piece: the wall may jump there) and the
    # outputs up to it from the exact start family
    no_flux = np.empty(0)
    b_lin, start_linear, g_start, i_first = exact_start(
        G_k, sa_k, sa0s, sig0s, y0, sigma0, REPEAT_ENDS, C_START, C_START, True, out_area,
        out_load, out_det_area, out_det_load, out_error, no_flux, no_flux)
    if i_first > nt:
        return st.OK
    if g_start <= 0.0:
        return st.START_UNRESOLVED
    # everything detached before the grid would start: the rest is the empty state
    if start_linear:
        a_start, _ = linear_wall_area_moment(1.0, b_lin, g_start)
        if a_start <= 0.0:
            fill_state(i_first - 1, nt, 0.0, 0.0, 1.0, -sigma0, 0.0, out_area, out_load,
                        out_det_area, out_det_load, out_error)
            return st.OK
    # a wall with a few isolated kinks: the ladder after a kink converges erratically (its
    # extrapolated value was measured 8x worse than the finer run, with a ladder that looked
    # asymptotic), so a solve to a tolerance takes KINK_SCALE times the resolution, at least
    # KINK_MIN_SCALE (on 2400 random one-kink walls at rtol 1e-4 and 1e-6 against bnr: no
    # miss, from 20 in 900 without); a smooth wall sampled coarsely has a 'kink' at most
    # samples and keeps the resolution of its tolerance
    kink_first = _first_kink(G_k, sa_k, i_first) if detect_kinks else nt + 1
    if rtol > 0.0 and kink_first <= nt and _kink_count(G_k, sa_k, kink_first) <= KINK_FEW:
        scale_x = max(KINK_SCALE * scale_x, KINK_MIN_SCALE)
        scale_t = max(KINK_SCALE * scale_t, KINK_MIN_SCALE)
    # grid: domain, spacing (tolerance, start width, Peclet), step density
    status = st.OK
    h_c = H_BASE / scale_x
    if h_c > 0.25:
        h_c = 0.25
    nper = NPER_BASE * scale_t
    if nper < 1.0:
        nper = 1.0
    nper_width = NPER_WIDTH * scale_t
    w_s = math.sqrt(1.0 + 4.0 * g_start)
    std_start = math.sqrt(2.0 * g_start) / w_s
    xi_far = (1.0 + boundary_at(G_k, sa_k, g_start) - sa0s) / w_s
    pe = 0.0
    for k in range(i_first, nt + 1):
        wk = math.sqrt(1.0 + 4.0 * G_k[k])
        c = (1.0 + sa_k[k] - sa0s) / wk
        if c > xi_far:
            xi_far = c
        dg = G_k[k] - G_k[k - 1]
        if dg > 0.0 and sa_k[k] < sa_k[k - 1]:
            # a wall moving into the distribution builds a layer of width 1/(w |v|)
            v = (sa_k[k - 1] - sa_k[k]) / dg * wk
            if v > pe:
                pe = v
    xi_max = xi_far + K_DOMAIN
    h_top = 0.25
    # (the extrapolated "cn" only: the others' error is dominated elsewhere, and a finer
    # grid would cost them steps under the work cap)
    pe_max = min(PECLET_CAP, PECLET_MAX / scale_x) if extrapolate else PECLET_CAP
    if pe * h_top > pe_max:
        h_top = pe_max / pe
    if h_c > h_top:
        h_c = h_top
    # work cap, judged by the resolution the tolerance needs: the coarse steps the step
    # densities ask for, not rounded up per schedule piece (densely sampled schedules force
    # extra steps, which are not needed resolution); past work_max the node spacing and the
    # step are coarsened together, balanced by the scheme's order in time (CN: h^2 + dt^2,
    # both by f^(1/2); implicit Euler: h^2 + dt, nodes by f^(1/3), steps by f^(2/3)), so
    # that more work always buys a better answer
    m_need = 0.0
    g_prev = g_start
    for k in range(i_first, nt + 1):
        g_k = G_k[k]
        if g_k <= g_prev:
            continue
        sa_prev = boundary_at(G_k, sa_k, g_prev)
        pw = nper_width if sa_k[k] < sa_prev else nper_width * RECEDING_FACTOR
        lng = math.log(g_k / g_prev)
        d_sa = abs(sa_k[k] - sa_prev)
        m_w = 0.0
        if d_sa > 0.0:
            m_w = lng / (2.0 * math.asinh(0.5 / (pw * d_sa / (g_k - g_prev)
                                                  * math.sqrt(0.5 * g_k))))
        m_need += max(lng * nper, m_w)
        g_prev = g_k
    if m_need < 1.0:
        m_need = 1.0
    work_need = m_need * xi_max / h_c
    if work_need > work_max:
        status = st.GRID_CAP
        f_cut = work_max / work_need
        f_x = f_cut ** (1.0 / 3.0) if theta > 0.75 else math.sqrt(f_cut)
        h_new = h_c / f_x
        if h_new > h_top:
            h_new = max(h_c, h_top)
        f_t = f_cut * h_new / h_c
        h_c = h_new
        nper *= f_t
        nper_width *= f_t
        # (no floor on the steps per width travelled: a floor let a fast wall force 1e8
        # steps past the cap; the steps per ln G are bounded by the range of ln G)
        if nper < 0.05:
            nper = 0.05
        work_need = work_max
    # the start may be narrower than h_c resolves: begin finer, then coarsen by factors of 2
    # each time the profile width (sqrt(2G)/w, at most 1/sqrt 2) has grown past r_std new
    # spacings
    r_std = min(6.0, 0.6 / h_c)
    h_0 = h_c
    n_levels = 0
    while h_0 > std_start / r_std and n_levels < MAX_LEVELS:
        h_0 *= 0.5
        n_levels += 1
    if h_0 > std_start / r_std:
        status = st.START_UNRESOLVED
    coarsen_at = np.empty(n_levels)
    hh = h_0
    for k in range(n_levels):
        hh *= 2.0
        s2 = (r_std * hh) ** 2
        coarsen_at[k] = s2 / (2.0 - 4.0 * s2) if s2 < 0.4 else np.inf
    # the coarse grid is a multiple of 2 * 2^n_levels, so that the ladder's half grid
    # coarsens as often as the others
    block = 2 << n_levels
    n_c = int(math.ceil(xi_max / (h_0 * block))) * block
    if n_c < 8 * block:
        n_c = 8 * block
    if n_c > N_MAX:
        n_c = (N_MAX // block) * block
        status = st.GRID_CAP
    h_c = xi_max / n_c
    cap_status = status
    # the ladder: run j has n_c 2^(j-1) intervals and 2^j times the steps of run 0; the
    # result is the pair (j-1, j) (extrapolated or the finer), its error estimate uses run
    # j-2 too (see _ladder_estimate); refine (j += 1) while the estimate misses rtol
    n_half = n_c // 2
    nper_h = 0.5 * nper
    nper_width_h = 0.5 * nper_width
    order = 2.0 if theta < 0.75 else 1.0
    size = 2 * n_c + 1
    p = np.empty(size)
    tmp = np.empty(size)
    lo, di, up = np.empty(size), np.empty(size), np.empty(size)
    r_area = np.empty((3, nt + 1))
    r_load = np.empty((3, nt + 1))
    r_det = np.empty((3, nt + 1))
    r_det_load = np.empty((3, nt + 1))
    r_sub = np.zeros((3, nt + 1))
    no_sub = np.zeros(nt + 1)
    run_status = np.zeros(3, dtype=np.int64)
    est = np.zeros(nt + 1)
    # where the schedule forces steps, the coarsest run crosses pairs of pieces in one step
    # (its own thinned schedule), so that the coarse and fine runs keep one and two steps
    # per piece instead of the two and four an exact 2:1:1/2 ladder would force
    piece_flags = np.zeros(nt + 1, dtype=np.int64)
    if detect_kinks:
        # the piece after a kink, and those starting within GRADE_SPAN e-folds of G after
        # it: graded steps (see march), never paired
        g_kink = 0.0
        for k in range(max(i_first - 1, 1), nt + 1):
            if k < nt and _is_graded_kink(G_k, sa_k, k):
                piece_flags[k + 1] |= PIECE_GRADE
                g_kink = G_k[k]
            elif g_kink > 0.0 and k < nt and G_k[k] > 0.0 and \
                    math.log(G_k[k] / g_kink) < GRADE_SPAN:
                piece_flags[k + 1] |= PIECE_GRADED
    keep = np.ones(nt + 1, dtype=np.bool_)
    keep_all = np.ones(nt + 1, dtype=np.bool_)
    # hard cap on the work of all runs: the first ladder (runs of n_half, 2 n_half, 4 n_half
    # intervals at 1/2, 1, 2 times the coarse steps, beyond one step per piece) must fit in
    # WORK_TOTAL work_max; where the steps a fast wall forces on a piece make it miss, the
    # step densities are cut further (flagged)
    work_total = WORK_TOTAL * work_max
    for _ in range(4):
        w1 = 0.0
        for jj in range(3):
            w1 += (_schedule_steps(G_k, sa_k, i_first, g_start, nper_h, nper_width_h,
                                   piece_flags, np.int64(1 << jj), n_levels)
                   * ((n_half << jj) + 1))
        if w1 <= work_total:
            break
        status = st.GRID_CAP
        cap_status = status
        f_w = 0.9 * work_total / w1
        nper *= f_w
        nper_width *= f_w
        nper_h = 0.5 * nper
        nper_width_h = 0.5 * nper_width
    n_keep = _pair_pieces(G_k, sa_k, i_first, g_start, nper, nper_width, coarsen_at,
                          piece_flags, keep)
    G_t = np.empty(n_keep)
    sa_t = np.empty(n_keep)
    flags_t = np.zeros(n_keep, dtype=np.int64)
    i_first_t = i_first
    kk = 0
    for k in range(nt + 1):
        if keep[k]:
            G_t[kk] = G_k[k]
            sa_t[kk] = sa_k[k]
            flags_t[kk] = piece_flags[k] & (PIECE_KINK | PIECE_GRADE)
            kk += 1
        elif k < i_first:
            i_first_t -= 1
    t_area = np.empty(n_keep)
    t_load = np.empty(n_keep)
    t_det = np.empty(n_keep)
    t_det_load = np.empty(n_keep)
    t_sub = np.empty(n_keep)
    j = 0
    met = True
    work_0 = counts[2]
    while True:
        n_j = n_half << j
        if n_j + 1 > size:
            size = n_j + 1
            p = np.empty(size)
            tmp = np.empty(size)
            lo, di, up = np.empty(size), np.empty(size), np.empty(size)
        slot = j % 3
        if j == 0 and n_keep < nt + 1:
            s_j, _ = march(G_t, sa_t, i_first_t, g_start, start_linear, b_lin, sa0s, sig0s,
                           n_j + 1, 2.0 * h_c, nper_h, nper_width_h, np.int64(1), n_damp, theta,
                           coarsen_at, flags_t, p[: n_j + 1], tmp[: n_j + 1], lo, di, up,
                           t_area, t_load, t_det, t_det_load, t_sub, counts)
            kk = 0
            for k in range(nt + 1):
                if keep[k]:
                    r_area[slot, k] = t_area[kk]
                    kk += 1
                else:
                    r_area[slot, k] = np.nan
        else:
            s_j, _ = march(G_k, sa_k, i_first, g_start, start_linear, b_lin, sa0s, sig0s,
                           n_j + 1, 2.0 * h_c / (1 << j), nper_h, nper_width_h, np.int64(1 << j),
                           n_damp, theta, coarsen_at, piece_flags, p[: n_j + 1], tmp[: n_j + 1],
                           lo, di, up, r_area[slot],
                           r_load[slot], r_det[slot], r_det_load[slot], r_sub[slot], counts)
        run_status[slot] = s_j
        if j >= 2:
            sb = (j - 2) % 3
            sc = (j - 1) % 3
            # the coarsest run of the first ladder may have skipped points
            # (the adhesive fixed point's walls, detect_kinks False, leave the sub-grid term
            # and the zero guard out: its inner estimates are charged by the fixed point's
            # own control, which took the sub-grid term 16-30x over the error on late-onset
            # scenes; its results stay as they were)
            met = _ladder_estimate(r_area[sb], r_area[sc], r_area[slot],
                                   keep if j == 2 else keep_all, i_first, extrapolate, order,
                                   rtol, est, kink_first,
                                   r_sub[slot] if detect_kinks else no_sub,
                                   ZERO_GUARD if detect_kinks else 0.0)
            if met or rtol <= 0.0:
                break
            # refine: the next pair's coarse run does 4^(j-1) times the coarse work of the
            # first pair
            if (j - 2 >= MAX_REFINE or 4.0 ** (j - 1) * work_need > work_max
                    or (n_half << j) > N_MAX):
                break
            # ... and the next run within the hard cap of all runs (steps a fast wall forces
            # on a piece included)
            if (counts[2] - work_0 + _schedule_steps(G_k, sa_k, i_first, g_start, nper_h,
                                                      nper_width_h, piece_flags,
                                                      np.int64(1 << (j + 1)), n_levels)
                    * ((n_half << (j + 1)) + 1) > work_total):
                status = st.GRID_CAP
                break
        j += 1
    counts[0] = (n_half << (j - 1)) + 1
    # a work-capped grid whose estimate meets rtol is no longer flagged (bnr does the same)
    if cap_status == st.GRID_CAP and met and rtol > 0.0:
        status = st.OK
    elif not met and rtol > 0.0 and status == st.OK:
        status = st.RTOL_NOT_MET
    # the flags of the returned pair (the coarsest run only serves the estimate)
    for k in range(2):
        s_k = run_status[(j - 1 + k) % 3]
        if s_k != st.OK:
            status = s_k
    sc = (j - 1) % 3
    sf = j % 3
    # Richardson weights of an order-2 pair, or the finer run
    wf = 4.0 / 3.0 if extrapolate else 1.0
    wc = wf - 1.0
    for k in range(i_first, nt + 1):
        a = wf * r_area[sf, k] - wc * r_area[sc, k]
        d = wf * r_det[sf, k] - wc * r_det[sc, k]
        # the extrapolation may overshoot [0, 1] by rounding-size amounts: clip, keeping
        # A + detached = 1
        if a > 1.0:
            d += a - 1.0
            a = 1.0
        elif a < 0.0:
            d += a
            a = 0.0
        out_area[k - 1] = a
        out_load[k - 1] = (wf * r_load[sf, k] - wc * r_load[sc, k]) * y0
        out_det_area[k - 1] = d
        out_det_load[k - 1] = (wf * r_det_load[sf, k] - wc * r_det_load[sc, k]) * y0
        out_error[k - 1] = est[k]
        if not math.isfinite(a):
            status = st.NONFINITE
    return status


#: the signature of :func:`_solve_grid_tol` as :func:`solve_variant_by` calls it, by which
#: kernels compiled apart from it take it by address
_A = types.float64[::1]
GRID_SIGNATURE = types.int64(_A, _A, types.float64, types.float64, types.float64,
                             types.float64, types.boolean, types.float64, types.int64,
                             types.float64, _A, _A, _A, _A, _A, types.int64[::1], types.boolean)
