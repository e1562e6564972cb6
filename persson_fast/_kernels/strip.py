"""Stress diffusion between two absorbing walls, one pressure at a time (``@njit``).

Problem, in diffusion time G (Persson, J. Chem. Phys. 115, 3840 (2001); Surf. Sci. Rep. 61,
201 (2006), elastoplastic contact with adhesion):

    dP/dG = d2P/dsigma2,  P(sigma, 0) = delta(sigma - sigma0),
    P(-sigma_a(G), G) = 0 (detachment),  P(sigma_y(G), G) = 0 (yield),

with both walls piecewise linear in G between the schedule samples (the first value before
G[0]), -sigma_a < sigma_y throughout, no jumps (a repeated G carries equal values).

Scheme ("strip")
----------------
Everything is scaled by the strip width at G = 0, W0 = sigma_a(0) + sigma_y(0). The strip is
mapped onto y = (sigma + sigma_a(G)) / w(G) in [0, 1], w = sigma_a + sigma_y; the density in y,
p = w P, obeys p_G = (1/w^2) p_yy - d/dy (v p) with the frame velocity v = (sigma_a' - y w')/w.
Space: conservative central differences on y_j = j/n, p = 0 at both walls. The wall speeds are
the secants of their pieces (the schedule samples, kinks included, are step boundaries).
Time: Crank-Nicolson with the operator at the step's midpoint (the implicit midpoint rule);
the first ``n_damp`` steps are two implicit-Euler half steps each, their operator at the
start of the half step (Rannacher start), and so are the first ``n_damp`` steps after a kink
of a wall (its speed jumps by more than KINK_JUMP: the sudden change of the boundary's speed
excites grid-scale modes, which Crank-Nicolson carries on with a factor near -1 per step).
Steps grow geometrically from the start (dt = REL_STEP G), capped at MAX_STEP w^2 and by the
wall travel per step (a fraction 1/N_WIDTH of the profile width sqrt(2G)). The absorbed areas
are the discrete boundary fluxes integrated over each step, so that A_el + A_pl + D = 1 holds
to rounding; the absorbed loads are the fluxes times the walls' stresses at the time the
step's operator is taken at, and the load balance L + plastic_load - detached_load = sigma0
holds to rounding too. Why: the node stresses sigma_j = y_j w - sigma_a are linear in G
within a step, the central differences satisfy sum_j sigma_j (L p)_j h = (outflow terms at
the walls) - sum_j sigma_j' p_j h at any one G, and with the operator at the midpoint
(Crank-Nicolson) or at the start (implicit Euler) the frame motion's term cancels exactly
over the step.

Start: an exact solution at a small G_s. Either the free Gaussian N(sigma - sigma0; 2 G_s),
while both walls stay out of its reach (a reflection-principle bound of the probability of
having reached either wall by G_s <= TAIL_TOL each, :func:`_far_limit`), or the exact
density of the nearer wall alone moving linearly (:func:`linear_wall_density`), while that
wall is still on its first linear stretch and the far wall stays out of reach: a start next
to one wall does not force a narrow start (and a huge grid). Outputs at G <= G_s are the
start family's exact values. The start profile is sampled at the nodes; what its discrete
area misses (O(h^2) next to a wall) is booked as absorbed by the nearer wall, at the value
that keeps the load balance exact.

Error control: a ladder of runs (n, dt), (2n, dt/2), (4n, dt/4) gives two Richardson values
R1 = (4 A_2 - A_1)/3 and R2 = (4 A_4 - A_2)/3; the returned value is R2 and the error
estimate of the real contact area A = A_el + A_pl = 1 - D is |R2 - R1| / (2^q - 1) with
q = EXTRAPOLATED_ORDER (that of the cn kernel), the larger un-extrapolated measure |A_4 - A_2|/3
being taken too where the ladder is not in its asymptotic range. While the largest estimate
exceeds rtol A + RTOL_ATOL (or that of A_el or A_pl does: their errors partly cancel in A)
the ladder is refined (a run with twice the nodes and half the
steps added, the coarsest dropped), up to MAX_REFINE times and the node and work caps; a result
that still misses is flagged RTOL_NOT_MET (GRID_CAP where a cap stopped the refinement).

Negative density: a run whose density at a record is markedly negative (min p < -NEG_TOL
max p) with a negative mass above NEG_MASS_TOL times the area tolerance is flagged
NEGATIVE_DENSITY (the last two runs of the ladder count).
"""
from __future__ import annotations

import math

import numpy as np

from .._jit import njit_serial, njit_sweeps, prange
from . import status as st
from .schedule import REPEAT_SKIPPED, first_linear_piece, scaled_times, scaled_values
from .special import linear_wall_area_moment, linear_wall_density
from .tridiag import thomas

# --- constants of the scheme (lengths in units of W0, diffusion times in W0^2) -----------
N_DAMP = 1              # default implicit-Euler half-step pairs at the start of each run
K_FAR = 8.0             # a wall ignored by the start stays this many start std away
TAIL_TOL = math.erfc(K_FAR / math.sqrt(2.0))  # the hit probability that allows (1.2e-15)
N_BASE = 60             # coarse intervals across the strip at level 0 (LEVEL0_SCALE)
RTOL_SCALE = 0.5        # resolution at rtol = 1e-6 in units of the constants here: measured
                        # errors 0.003-0.01 rtol at 1 (translating walls, rtol 1e-3..1e-8), so
                        # half (16x the error of an order-4 ladder, 1/4 of the work); the
                        # a-posteriori refinement covers the scenes that need more
R_STD = 6.0             # coarse intervals per start standard deviation (at least)
PECLET_MAX = 0.25       # largest coarse cell Peclet number of the wall drift, at rtol = 1e-6
REL_STEP = 0.08         # coarse step / G early on (geometric steps), at rtol = 1e-6
MAX_STEP = 4e-3         # coarse step cap / w^2 (late, uniform steps), at rtol = 1e-6
N_WIDTH = 10.0          # coarse steps per profile width sqrt(2G) travelled by a wall
LEVEL0_SCALE = 0.25     # resolution scale of level 0 of the explicit ladder
N_CAP = 16384           # most intervals of any run (the coarse grid: N_CAP / 4)
WORK_MAX = 2e8          # most node-steps of all the runs of one solve
PLAN_STOP = 64.0        # the step count stops at this many times WORK_MAX's steps
MAX_REFINE = 3          # a-posteriori refinements at most
EXTRAPOLATED_ORDER = 3.0  # order assumed for the error of the extrapolated values
ASYMPTOTIC_SLACK = 2.0  # successive ladder differences within this factor of 4: asymptotic
RTOL_ATOL = 1e-12       # absolute part of the accuracy contract |dA| <= rtol A + RTOL_ATOL
KINK_JUMP = 0.25        # a wall speed jump above this fraction of the larger speed is a
                        # kink, after which n_damp fine steps are damped again: undamped, the
                        # modes a kink excites take the density next to the wall down to -1.85
                        # times its maximum (yield wall Y + 0.5 sqrt(G) on 7 samples, sigma0 =
                        # 0.94 Y, rtol 1e-4), with the areas still within 0.005 rtol.
                        # Not at every sample: dense samples of a smooth wall jump by a few
                        # per cent each, and damping all of them costs the ladder its order
                        # (GRID_CAP on the scale-dependent hardness scenes at rtol 1e-5)
NEG_TOL = 1e-3          # NEGATIVE_DENSITY where, at a record, min p < -NEG_TOL max p ...
NEG_MASS_TOL = 1.0      # ... and the negative mass h sum max(-p, 0) exceeds NEG_MASS_TOL
                        # (rtol A + RTOL_ATOL). The outputs are sums over the nodes and
                        # trapezoid integrals of the fluxes, in which a grid-scale oscillation
                        # (alternating in space and, under Crank-Nicolson, from step to step)
                        # cancels; what could move A is a negative lobe of the order of the
                        # area's tolerance. The ratio alone is no measure: a distribution
                        # absorbed but for 2e-8 of its mass (a wall racing in) shows
                        # min p = -0.65 max p with a negative mass of 1.6e-11

# output slots
EL, LOAD, PL, PL_LOAD, DET, DET_LOAD = 0, 1, 2, 3, 4, 5
N_OUT = 6
# start kinds
START_FREE, START_LOWER, START_UPPER = 0, 1, 2


@njit_serial
def _wall_at(G_k, v_k, k, g):
    """Wall value at g on piece k = [G_k[k-1], G_k[k]] (exact at its ends)."""
    g0 = G_k[k - 1]
    g1 = G_k[k]
    if g >= g1 or g1 <= g0:
        return v_k[k]
    if g <= g0:
        return v_k[k - 1]
    return v_k[k - 1] + (v_k[k] - v_k[k - 1]) * (g - g0) / (g1 - g0)


@njit_serial
def _min_gap(G_k, dist_k, g):
    """Smallest value over [0, g] of a piecewise-linear distance given at the samples."""
    m = dist_k[0]
    n = G_k.shape[0]
    for k in range(1, n):
        if G_k[k] > g:
            # the piece k holds g: its value at g (linear, so the ends bound it)
            if G_k[k] > G_k[k - 1]:
                d = dist_k[k - 1] + (dist_k[k] - dist_k[k - 1]) * (g - G_k[k - 1]) / (
                    G_k[k] - G_k[k - 1])
                if d < m:
                    m = d
            return m
        if dist_k[k] < m:
            m = dist_k[k]
    return m


@njit_serial
def _far_limit_min(G_k, dist_k, g_hi):
    """Largest g <= g_hi with min over [0, g] of the distance >= K_FAR sqrt(2 g)."""
    if _min_gap(G_k, dist_k, g_hi) >= K_FAR * math.sqrt(2.0 * g_hi):
        return g_hi
    lo = 0.0
    hi = g_hi
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if _min_gap(G_k, dist_k, mid) >= K_FAR * math.sqrt(2.0 * mid):
            lo = mid
        else:
            hi = mid
    return lo


@njit_serial
def _hit_bound(d, g):
    """Reflection-principle bound of the probability that the free diffusion from the start
    (variance 2 g at time g) has come a distance d away by time g: erfc(d / (2 sqrt g))."""
    if g <= 0.0:
        return 0.0
    if d <= 0.0:
        return 1.0
    return math.erfc(d / (2.0 * math.sqrt(g)))


@njit_serial
def _far_limit_pieces(G_k, dist_k, g_hi):
    """Largest g <= g_hi for which the sum over the schedule's pieces of the hit bounds (the
    piece's least distance against the spread at the piece's end) stays <= TAIL_TOL."""
    acc = 0.0
    n = G_k.shape[0]
    for k in range(1, n):
        g0 = G_k[k - 1]
        g1 = G_k[k]
        if g1 <= g0:
            continue
        if g0 >= g_hi:
            return g_hi
        ge = g1 if g1 < g_hi else g_hi
        t = _hit_bound(min(dist_k[k - 1], _wall_at(G_k, dist_k, k, ge)), ge)
        if acc + t <= TAIL_TOL:
            acc += t
            if ge >= g_hi:
                return g_hi
            continue
        lo = g0
        hi = ge
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            if acc + _hit_bound(min(dist_k[k - 1], _wall_at(G_k, dist_k, k, mid)),
                                mid) <= TAIL_TOL:
                lo = mid
            else:
                hi = mid
        return lo
    return g_hi


@njit_serial
def _far_limit(G_k, dist_k, g_hi):
    """Largest g <= g_hi until which the wall at distance dist_k (from the start) is out of
    the free diffusion's reach, to a probability <= TAIL_TOL: the larger of two rigorous
    bounds, the least distance over [0, g] against the spread at g (tight for a wall
    approaching), and the sum over the schedule's pieces of each piece's least distance
    against the spread at its end (tight for a wall running away, as a detachment wall does
    at low pressure: the first bound then waits for the spread at g to pass the distance
    at G = 0)."""
    a = _far_limit_min(G_k, dist_k, g_hi)
    b = _far_limit_pieces(G_k, dist_k, g_hi)
    return a if a > b else b


@njit_serial
def _exact_start(kind, sig0, y0, b, g, sa, sy, res):
    """The start family's exact outputs at g (walls sa, sy there) into res[0:6]."""
    for q in range(N_OUT):
        res[q] = 0.0
    if kind == START_FREE or g <= 0.0:
        res[EL] = 1.0
        res[LOAD] = sig0
        return
    a, m1 = linear_wall_area_moment(y0, b, g)
    res[EL] = a
    if kind == START_LOWER:       # y = sigma + sa
        load = m1 - sa * a
        res[LOAD] = load
        res[DET] = 1.0 - a
        res[DET_LOAD] = load - sig0
    else:                         # y = sy - sigma
        load = sy * a - m1
        res[LOAD] = load
        res[PL] = 1.0 - a
        res[PL_LOAD] = sig0 - load


@njit_serial
def _step_size(g, w, speed, rel, max_step, n_width):
    dt = rel * g
    if dt > max_step * w * w:
        dt = max_step * w * w
    if speed > 0.0:
        dt_w = math.sqrt(2.0 * g) / (n_width * speed)
        if dt < dt_w:
            return dt
        return dt_w
    return dt


@njit_serial
def _plan(G_k, sa_k, sy_k, speed_k, k_first, g_start, rel, max_step, n_width, gs, piece, rec,
          dt_min=0.0, m_stop=-1):
    """Coarse step boundaries from g_start through every sample after it.

    Returns the number of steps; with non-empty ``gs`` also fills the boundaries ``gs``, the
    piece of each step ``piece`` and, for each sample k >= k_first, the index ``rec[k]`` of
    its boundary. With empty ``gs`` it only counts, and stops counting past ``m_stop``
    (>= 0) steps (walls that nearly meet ask for steps ~ w^2: without a stop the count
    alone ran for hours). No step is shorter than ``dt_min`` (but at the samples).
    """
    fill = gs.shape[0] > 0
    m = 0
    g = g_start
    if fill:
        gs[0] = g
    n = G_k.shape[0]
    for k in range(k_first, n):
        b = G_k[k]
        if b > g:
            while True:
                w = _wall_at(G_k, sa_k, k, g) + _wall_at(G_k, sy_k, k, g)
                dt = _step_size(g, w, speed_k[k], rel, max_step, n_width)
                if dt < dt_min:
                    dt = dt_min
                if not fill and 0 <= m_stop < m:
                    return m
                if g + 1.5 * dt >= b:
                    if b - g > dt:
                        g = 0.5 * (g + b)
                        if fill:
                            piece[m] = k
                            gs[m + 1] = g
                        m += 1
                    g = b
                    if fill:
                        piece[m] = k
                        gs[m + 1] = g
                    m += 1
                    break
                g = g + dt
                if fill:
                    piece[m] = k
                    gs[m + 1] = g
                m += 1
        if fill:
            rec[k] = m
    return m


@njit_serial
def _assemble(w, sa_dot, w_dot, h, n, c, lo, di, up):
    """(I - c L) on the interior nodes 1..n-1 (stored at 0..n-2) for the strip operator L at
    width w; returns the boundary outflow coefficients (out_lo, out_up): flux = coef p_1 and
    coef p_{n-1}."""
    d = 1.0 / (w * w)
    dh = d / h
    for j in range(1, n):
        vm = (sa_dot - (j - 0.5) * h * w_dot) / w
        vp = (sa_dot - (j + 0.5) * h * w_dot) / w
        i = j - 1
        lo[i] = -c * (dh + 0.5 * vm) / h
        di[i] = 1.0 + c * (2.0 * dh + 0.5 * (vp - vm)) / h
        up[i] = -c * (dh - 0.5 * vp) / h
    v_lo = (sa_dot - 0.5 * h * w_dot) / w
    v_up = (sa_dot - (n - 0.5) * h * w_dot) / w
    return dh - 0.5 * v_lo, dh + 0.5 * v_up


@njit_serial
def _crank_nicolson(p, w, sa_dot, w_dot, h, n, c, lo, di, up, rhs):
    """The Crank-Nicolson system of one step with the operator L at width w: M = I - c L
    into lo, di, up (:func:`_assemble`) and rhs = (I + c L) p = 2 p - M p, from the same
    coefficients (p holds all n+1 nodes, zero at the ends; the exact load balance needs the
    explicit and the implicit half of the step to share L); returns the outflow
    coefficients."""
    out = _assemble(w, sa_dot, w_dot, h, n, c, lo, di, up)
    for j in range(1, n):
        i = j - 1
        rhs[i] = (2.0 - di[i]) * p[j] - lo[i] * p[j - 1] - up[i] * p[j + 1]
    return out


@njit_serial
def _is_kink(sa_dot0, w_dot0, sa_dot1, w_dot1):
    """Whether a wall's speed jumps between two pieces (speeds of the lower wall -sa_dot and
    of the upper wall w_dot - sa_dot) by more than KINK_JUMP of the larger speed."""
    d_lo = abs(sa_dot1 - sa_dot0)
    d_up = abs((w_dot1 - sa_dot1) - (w_dot0 - sa_dot0))
    s_lo = max(abs(sa_dot0), abs(sa_dot1))
    s_up = max(abs(w_dot0 - sa_dot0), abs(w_dot1 - sa_dot1))
    return d_lo > KINK_JUMP * s_lo or d_up > KINK_JUMP * s_up


@njit_serial
def _march(G_k, sa_k, sy_k, gs, piece, rec, k_first, n_sub, n_damp, n, kind, sig0, y0, b0,
           g_s, rtol, p, lo, di, up, rhs, scratch, res):
    """One run on n intervals, every coarse step cut into n_sub equal steps, the first
    n_damp (of the fine steps) damped, and again after each kink of a wall. Writes res[q, k]
    for the samples k >= k_first; returns a status (OK, NEGATIVE_DENSITY, NONFINITE; the
    negative density measured against the area tolerance rtol A + RTOL_ATOL)."""
    status = st.OK
    h = 1.0 / n
    k0 = piece[0]
    sa = _wall_at(G_k, sa_k, k0, g_s)
    sy = _wall_at(G_k, sy_k, k0, g_s)
    w = sa + sy
    p[0] = 0.0
    p[n] = 0.0
    area = 0.0
    load = 0.0
    for j in range(1, n):
        sig = j * h * w - sa
        if kind == START_FREE:
            x = sig - sig0
            v = math.exp(-x * x / (4.0 * g_s)) / math.sqrt(4.0 * math.pi * g_s)
        elif kind == START_LOWER:
            v = linear_wall_density(sig + sa, y0, b0, g_s)
        else:
            v = linear_wall_density(sy - sig, y0, b0, g_s)
        p[j] = w * v
        area += p[j]
        load += sig * p[j]
    area *= h
    load *= h
    pl = 0.0
    pl_load = 0.0
    det = 0.0
    det_load = 0.0
    # what the sampled start misses goes to the nearer wall, keeping both balances exact
    if kind == START_UPPER:
        pl = 1.0 - area
        pl_load = sig0 - load
    else:
        det = 1.0 - area
        det_load = load - sig0
    m = piece.shape[0]
    n_in = n - 1
    kr = k_first
    n_rec = G_k.shape[0]
    damp_left = n_damp
    sa_dot = 0.0
    w_dot = 0.0
    for i in range(m):
        k = piece[i]
        ga = gs[i]
        gb = gs[i + 1]
        dg = G_k[k] - G_k[k - 1]
        sa_dot_prev = sa_dot
        w_dot_prev = w_dot
        sa_dot = (sa_k[k] - sa_k[k - 1]) / dg
        w_dot = (sa_k[k] + sy_k[k] - sa_k[k - 1] - sy_k[k - 1]) / dg
        if i > 0 and k != piece[i - 1] and _is_kink(sa_dot_prev, w_dot_prev, sa_dot, w_dot):
            damp_left = n_damp      # damped restart after the kink (Rannacher)
        for s in range(n_sub):
            g0 = ga + (gb - ga) * s / n_sub
            g1 = gb if s == n_sub - 1 else ga + (gb - ga) * (s + 1) / n_sub
            dt = g1 - g0
            gm = 0.5 * (g0 + g1)
            sam = _wall_at(G_k, sa_k, k, gm)
            sym = _wall_at(G_k, sy_k, k, gm)
            if damp_left > 0:
                damp_left -= 1
                sa0 = _wall_at(G_k, sa_k, k, g0)
                sy0 = _wall_at(G_k, sy_k, k, g0)
                for half in range(2):
                    # the operator at the start of the half step: with the nodes' stresses
                    # linear in G, sum sigma_j(G_b) p_b - sum sigma_j(G_a) p_a is then exactly
                    # the half step times the walls' stresses at G_a times their outflows
                    c = (gm - g0) if half == 0 else (g1 - gm)
                    sab = sa0 if half == 0 else sam
                    syb = sy0 if half == 0 else sym
                    o_lo, o_up = _assemble(sab + syb, sa_dot, w_dot, h, n, c, lo, di, up)
                    for j in range(n_in):
                        rhs[j] = p[j + 1]
                    thomas(lo[:n_in], di[:n_in], up[:n_in], rhs[:n_in], scratch[:n_in],
                           p[1:n])
                    f_lo = o_lo * p[1]
                    f_up = o_up * p[n - 1]
                    det += c * f_lo
                    pl += c * f_up
                    det_load += c * sab * f_lo
                    pl_load += c * syb * f_up
            else:
                # Crank-Nicolson with the operator at the step's midpoint (implicit midpoint
                # rule): the load moment changes by exactly dt/2 times the walls' midpoint
                # stresses times their outflows at both ends of the step
                c = 0.5 * dt
                o_lo, o_up = _crank_nicolson(p, sam + sym, sa_dot, w_dot, h, n, c, lo, di, up,
                                             rhs)
                q_lo = p[1]
                q_up = p[n - 1]
                thomas(lo[:n_in], di[:n_in], up[:n_in], rhs[:n_in], scratch[:n_in], p[1:n])
                f_lo = c * o_lo * (q_lo + p[1])
                f_up = c * o_up * (q_up + p[n - 1])
                det += f_lo
                pl += f_up
                det_load += sam * f_lo
                pl_load += sym * f_up
        # records at the boundary i + 1
        if kr < n_rec and rec[kr] == i + 1:
            sa = _wall_at(G_k, sa_k, k, gb)
            sy = _wall_at(G_k, sy_k, k, gb)
            w = sa + sy
            area = 0.0
            load = 0.0
            p_min = 0.0
            p_max = 0.0
            neg = 0.0
            for j in range(1, n):
                pj = p[j]
                area += pj
                load += (j * h * w - sa) * pj
                if pj < p_min:
                    p_min = pj
                if pj > p_max:
                    p_max = pj
                if pj < 0.0:
                    neg -= pj
            if (p_min < -NEG_TOL * p_max and neg * h > NEG_MASS_TOL * (
                    rtol * min(max(area * h + pl, 0.0), 1.0) + RTOL_ATOL)
                    and status == st.OK):
                status = st.NEGATIVE_DENSITY
            if not (math.isfinite(area) and math.isfinite(det) and math.isfinite(pl)):
                status = st.NONFINITE
            while kr < n_rec and rec[kr] == i + 1:
                res[EL, kr] = area * h
                res[LOAD, kr] = load * h
                res[PL, kr] = pl
                res[PL_LOAD, kr] = pl_load
                res[DET, kr] = det
                res[DET_LOAD, kr] = det_load
                kr += 1
    return status


@njit_serial
def _ladder_error(a, b, c):
    """Error estimate of the extrapolated value (4 c - b)/3 of one output from the runs
    a (n), b (2n), c (4n) (see the module docstring)."""
    q = 4.0
    d1 = b - a
    d2 = c - b
    e_lo = abs(4.0 * d2 - d1) / (3.0 * (2.0 ** EXTRAPOLATED_ORDER - 1.0))
    e_hi = abs(d2) / 3.0
    asym = d1 * d2 > 0.0 and abs(d1) <= q * ASYMPTOTIC_SLACK * abs(d2) and \
        q * abs(d2) <= ASYMPTOTIC_SLACK * abs(d1)
    return e_lo if asym else max(e_lo, e_hi)


@njit_serial
def _estimate(r_a, r_b, r_c, k_first, rtol, est):
    """Error estimate of the real contact area A = A_el + A_pl = 1 - D of R2 = (4 C - B)/3
    from the runs A (n), B (2n), C (4n); True when it, and the estimates of the two parts
    A_el and A_pl (whose errors partly cancel in A), meet rtol A + RTOL_ATOL at every sample
    (or rtol <= 0)."""
    met = True
    n = est.shape[0]
    for k in range(k_first, n):
        e = _ladder_error(r_a[DET, k], r_b[DET, k], r_c[DET, k])
        e_pl = _ladder_error(r_a[PL, k], r_b[PL, k], r_c[PL, k])
        e_el = _ladder_error(r_a[EL, k], r_b[EL, k], r_c[EL, k])
        if not math.isfinite(e + e_pl + e_el):
            met = False
            e = np.inf
        est[k] = e
        a = 1.0 - (r_c[DET, k] + (r_c[DET, k] - r_b[DET, k]) / 3.0)
        if max(e, max(e_pl, e_el)) > rtol * min(max(a, 0.0), 1.0) + RTOL_ATOL:
            met = False
    return met or rtol <= 0.0


@njit_serial
def _store(vals, kk, scale, out_el, out_load, out_pl, out_pl_load, out_det, out_det_load):
    """The six outputs of one schedule point, loads back in the caller's stress unit."""
    out_el[kk] = vals[EL]
    out_load[kk] = vals[LOAD] * scale
    out_pl[kk] = vals[PL]
    out_pl_load[kk] = vals[PL_LOAD] * scale
    out_det[kk] = vals[DET]
    out_det_load[kk] = vals[DET_LOAD] * scale


@njit_serial
def solve_strip(G, sa, sy, sigma0, rtol, level, n_damp, out_el, out_load, out_pl,
                out_pl_load, out_det, out_det_load, out_err, counts):
    """Two-wall diffusion of one nominal stress, with error control.

    Parameters
    ----------
    G : (n_t,) float64 -- non-decreasing diffusion times, G[0] >= 0. [stress^2]
    sa, sy : (n_t,) float64 -- sigma_a (lower wall at -sa) and sigma_y (upper wall) at G,
        linear in between, sa[0], sy[0] before G[0]; sa + sy > 0. [stress]
    sigma0 : float -- nominal stress, -sa[0] < sigma0 < sy[0]. [stress]
    rtol : float -- target relative accuracy of the real contact area A_el + A_pl. [-]
    level : int -- >= 0: explicit resolution (doubling per level), no refinement; -1: rtol.
    n_damp : int -- coarse steps after the start taken as two implicit-Euler half steps.
    out_* : (n_t,) float64 -- elastic area, load, plastic area, plastic load, detached area,
        detached load (integral of sigma_a dD), error estimate of A_el + A_pl.
    counts : (3,) int64 -- coarse intervals, coarse steps, refinements done.

    Returns
    -------
    status : int -- see :mod:`persson_fast._kernels.status`.
    """
    nt = G.shape[0]
    if (sa.shape[0] != nt or sy.shape[0] != nt or out_el.shape[0] != nt
            or out_err.shape[0] != nt or counts.shape[0] < 3):
        return st.BAD_INPUT
    counts[0] = 0
    counts[1] = 0
    counts[2] = 0
    if nt == 0:
        return st.OK
    scale = sa[0] + sy[0]
    if not (scale > 0.0 and math.isfinite(scale) and math.isfinite(sigma0)):
        return st.BAD_INPUT
    if not (-sa[0] < sigma0 < sy[0]) or n_damp < 0:
        return st.BAD_INPUT
    for k in range(nt):
        if not (math.isfinite(G[k]) and math.isfinite(sa[k]) and math.isfinite(sy[k])):
            return st.BAD_INPUT
        if sa[k] + sy[k] <= 0.0 or G[k] < 0.0 or (k > 0 and G[k] < G[k - 1]):
            return st.BAD_INPUT
    # scaled schedule with a leading point at G = 0
    n_k = nt + 1
    G_k = scaled_times(G, scale)
    sa_k = scaled_values(sa, sa[0], scale)
    sy_k = scaled_values(sy, sy[0], scale)
    sig0 = sigma0 / scale
    g_end = G_k[nt]
    speed_k = np.zeros(n_k)
    d_lo = np.empty(n_k)
    d_up = np.empty(n_k)
    for k in range(n_k):
        d_lo[k] = sig0 + sa_k[k]
        d_up[k] = sy_k[k] - sig0
        if k > 0 and G_k[k] > G_k[k - 1]:
            dg = G_k[k] - G_k[k - 1]
            speed_k[k] = max(abs(sa_k[k] - sa_k[k - 1]), abs(sy_k[k] - sy_k[k - 1])) / dg
    # the start: free Gaussian, or the nearer wall's exact linear solution
    g_far_lo = _far_limit(G_k, d_lo, g_end)
    g_far_up = _far_limit(G_k, d_up, g_end)
    g_free = min(g_far_lo, g_far_up)
    near_lower = d_lo[0] <= d_up[0]
    if near_lower:
        end_lin, b_lin = first_linear_piece(G_k, sa_k, REPEAT_SKIPPED, True)
        g_lin = min(end_lin, g_far_up)
        y0 = d_lo[0]
    else:
        end_lin, b_lin = first_linear_piece(G_k, sy_k, REPEAT_SKIPPED, True)
        g_lin = min(end_lin, g_far_lo)
        y0 = d_up[0]
    if g_free >= g_lin:
        kind = START_FREE
        g_s = g_free
    else:
        kind = START_LOWER if near_lower else START_UPPER
        g_s = g_lin
    if g_s > g_end:
        g_s = g_end
    res0 = np.empty(N_OUT)
    k_first = 1
    while k_first < n_k and G_k[k_first] <= g_s:
        _exact_start(kind, sig0, y0, b_lin, G_k[k_first], sa_k[k_first], sy_k[k_first], res0)
        kk = k_first - 1
        _store(res0, kk, scale, out_el, out_load, out_pl, out_pl_load, out_det, out_det_load)
        out_err[kk] = 0.0
        k_first += 1
    if k_first >= n_k:
        return st.OK
    if not g_s > 0.0:
        for kk in range(k_first - 1, nt):
            out_el[kk] = np.nan
            out_err[kk] = np.nan
        return st.START_UNRESOLVED
    status = st.OK
    # resolution: a priori from rtol (or level), the start's width and the wall drift
    if level >= 0:
        s = LEVEL0_SCALE * 2.0 ** level
    else:
        s = RTOL_SCALE * (1e-6 / rtol) ** 0.25
    k_s = k_first      # the piece holding g_s
    w_s = _wall_at(G_k, sa_k, k_s, g_s) + _wall_at(G_k, sy_k, k_s, g_s)
    std_y = math.sqrt(2.0 * g_s) / w_s
    pe = 0.0
    for k in range(k_s, n_k):
        w_max = max(sa_k[k] + sy_k[k], sa_k[k - 1] + sy_k[k - 1])
        if speed_k[k] * w_max > pe:
            pe = speed_k[k] * w_max
    n_f = max(N_BASE * s, R_STD * math.sqrt(s) / std_y, pe * s / PECLET_MAX, 16.0)
    n_c = int(math.ceil(n_f))
    if n_c > N_CAP // 4:
        n_c = N_CAP // 4
        status = st.START_UNRESOLVED if R_STD / std_y > N_CAP // 4 else st.GRID_CAP
    rel = REL_STEP / s
    max_step = MAX_STEP / s
    n_width = N_WIDTH * s
    empty_f = np.empty(0)
    empty_i = np.empty(0, dtype=np.int64)
    rec = np.zeros(n_k, dtype=np.int64)
    per_step = 21.0 * (n_c + 1.0)
    m_stop = int(PLAN_STOP * WORK_MAX / per_step)
    m = _plan(G_k, sa_k, sy_k, speed_k, k_s, g_s, rel, max_step, n_width, empty_f, empty_i,
              rec, 0.0, m_stop)
    work = per_step * m
    dt_min = 0.0
    if work > WORK_MAX:
        # cut the step densities (not below one step per piece), flagged
        f = WORK_MAX / work
        rel /= f
        max_step /= f
        n_width *= f
        m = _plan(G_k, sa_k, sy_k, speed_k, k_s, g_s, rel, max_step, n_width, empty_f,
                  empty_i, rec, 0.0, m_stop)
        status = st.GRID_CAP
        if per_step * m > PLAN_STOP * WORK_MAX / 16.0:
            # still far over (the walls nearly meet: steps ~ w^2): the steps no shorter than
            # the work cap allows over the whole range
            dt_min = (G_k[n_k - 1] - g_s) * per_step / WORK_MAX
            m = _plan(G_k, sa_k, sy_k, speed_k, k_s, g_s, rel, max_step, n_width, empty_f,
                      empty_i, rec, dt_min, -1)
    gs = np.empty(m + 1)
    piece = np.empty(m, dtype=np.int64)
    _plan(G_k, sa_k, sy_k, speed_k, k_s, g_s, rel, max_step, n_width, gs, piece, rec, dt_min,
          -1)
    counts[0] = n_c
    counts[1] = m
    # the ladder
    size = 4 * n_c + 1
    p = np.empty(size)
    lo = np.empty(size)
    di = np.empty(size)
    up = np.empty(size)
    rhs = np.empty(size)
    scratch = np.empty(size)
    res = np.zeros((3, N_OUT, n_k))
    run_status = np.zeros(3, dtype=np.int64)
    est = np.zeros(n_k)
    j = 0
    met = True
    work_done = 0.0
    while True:
        n_j = n_c << j
        if n_j + 1 > p.shape[0]:
            p = np.empty(n_j + 1)
            lo = np.empty(n_j + 1)
            di = np.empty(n_j + 1)
            up = np.empty(n_j + 1)
            rhs = np.empty(n_j + 1)
            scratch = np.empty(n_j + 1)
        slot = j % 3
        run_status[slot] = _march(G_k, sa_k, sy_k, gs, piece, rec, k_first, np.int64(1 << j),
                                  np.int64(n_damp), n_j, kind, sig0, y0, b_lin, g_s,
                                  rtol, p, lo, di, up, rhs, scratch, res[slot])
        work_done += (n_j + 1.0) * m * (1 << j)
        if j >= 2:
            met = _estimate(res[(j - 2) % 3], res[(j - 1) % 3], res[slot], k_first,
                            rtol if level < 0 else 0.0, est)
            if met:
                break
            if j - 2 >= MAX_REFINE:
                if status == st.OK:
                    status = st.RTOL_NOT_MET
                break
            if (n_c << (j + 1)) > N_CAP or work_done + (
                    (n_c << (j + 1)) + 1.0) * m * (1 << (j + 1)) > WORK_MAX:
                status = st.GRID_CAP
                break
        j += 1
    counts[2] = j - 2
    if met and status == st.GRID_CAP:
        status = st.OK      # a capped resolution whose estimate meets rtol is fine
    for kk in range(2):
        s_k = run_status[(j - 1 + kk) % 3]
        if s_k != st.OK:
            status = s_k
    sb = (j - 1) % 3
    sc = j % 3
    vals = np.empty(N_OUT)
    for k in range(k_first, n_k):
        kk = k - 1
        for q in range(N_OUT):
            vals[q] = (4.0 * res[sc, q, k] - res[sb, q, k]) / 3.0
        _store(vals, kk, scale, out_el, out_load, out_pl, out_pl_load, out_det, out_det_load)
        out_err[kk] = est[k]
        if not (math.isfinite(vals[EL]) and math.isfinite(vals[DET]) and
                math.isfinite(vals[PL]) and math.isfinite(vals[LOAD])):
            status = st.NONFINITE
    return status


def _sweep(G, sa_rows, sy_rows, sigma0, rtol, level, n_damp, el, load, det, det_load, err,
           pl, pl_load, status, counts):
    """Solve every pressure (row) with :func:`solve_strip`.

    Arguments as in :mod:`persson_fast._kernels.signature` (no ``variant``): both walls, so
    ``sy_rows`` and the plastic outputs ``pl``, ``pl_load`` must have rows of length n_t
    (else BAD_INPUT); ``el`` receives the elastic area, ``err`` the error estimate of the real
    contact area el + pl, ``counts`` coarse intervals, coarse steps and refinements.
    """
    n_p = sigma0.shape[0]
    n_t = G.shape[0]
    for i in prange(n_p):
        if (pl.shape[0] != n_p or pl_load.shape[0] != n_p or pl.shape[1] != n_t
                or pl_load.shape[1] != n_t or sy_rows.shape[0] != n_p):
            status[i] = st.BAD_INPUT
        else:
            status[i] = solve_strip(G, sa_rows[i], sy_rows[i], sigma0[i], rtol, level, n_damp,
                                    el[i], load[i], pl[i], pl_load[i], det[i], det_load[i],
                                    err[i], counts[i])


sweep_serial, sweep_parallel = njit_sweeps(_sweep)
