"""Stress diffusion on a grid fixed in the stress, the wall crossing the nodes (``@njit``).

A second treatment of the moving absorbing boundary, beside the front-fixed scheme of
:mod:`persson_fast._kernels.similarity` (which maps the distance to the wall onto a fixed grid,
so that the wall always sits on node 0). Here the grid is attached to the stress itself and the
wall moves across it.

Problem, in diffusion time G (stress unit = unit of sqrt(G)):
    dP/dG = d2P/dsigma2,  P(sigma, 0) = delta(sigma - sigma0),  P(-sigma_a(G), G) = 0,
with sigma_a(G) linear in G between schedule points and sigma_a = sa[0] before G[0].

Scheme
------
*Scaling.* Stresses are measured in y0 = sigma0 + sigma_a(0) (the start distance to the wall),
G in y0^2; x = (sigma - sigma0) / y0 is the stress relative to the nominal pressure.

*Grid.* A single unscaled grid in x cannot hold both the start (width sqrt(2 G_s)) and the end
(width sqrt(2 G_end), decades wider), so the grid is stretched by the spreading width only:

    eta = x / w(G),   w^2 = c + 4 G,   c = 4 G_s          (G_s: the start, see below)

and eta_j = -K + j h, j = 0..N, is fixed. The grid is centred on the nominal pressure and does
not know where the wall is. The density p = w P obeys, in the log-time s = ln(w^2) / 4
(ds = dG / w^2), the Ornstein-Uhlenbeck form of the heat equation

    p_s = d/deta [ p_eta + 2 eta p ]

with constant coefficients (no wall drift: the grid does not follow the wall). The free
solution stays inside |eta| < K for every G: its variance in eta is 2G/(c + 4G) < 1/2, and an
absorbed density never exceeds the free one, so K = 6 leaves a tail below 1e-16 at both ends,
whatever the wall does. At the start (c = 4 G_s) the variance is 1/4: the start is resolved by
the same grid whatever G_s is.

*The wall* sits at eta_w(s) = x_w(G) / w(G), x_w = -1 - (sigma_a(G) - sigma_a(0)) / y0,
between nodes. Nodes behind it are inactive (value 0). The first active node j1 is the first
node at a distance theta h >= THETA_MIN h from the wall, so theta lies in
[THETA_MIN, 1 + THETA_MIN): a node closer than THETA_MIN h to the wall is switched off, which
keeps the closure's coefficients bounded (at most 2/(THETA_MIN h^2)) however close the wall
comes to a node. The Dirichlet condition p(eta_w) = 0 is imposed at the exact wall position by
a ghost value at node j1 - 1 taken from the quadratic through (eta_w, 0), (eta_j1, p_j1),
(eta_j1+1, p_j1+1):

    p_ghost = -2 (1 - theta)/theta p_j1 + (1 - theta)/(1 + theta) p_j1+1,

with which the central second difference at j1 is exactly the Shortley-Weller non-uniform
stencil 2 [ 0/(theta (1+theta)) - p_j1/theta + p_j1+1/(1+theta) ] / h^2 (local truncation
O(h), global error O(h^2)); the advection term uses the same quadratic. Elsewhere: conservative
central differences, fluxes F_{j+1/2} = (p_j+1 - p_j)/h + eta_{j+1/2} (p_j + p_j+1).

*Time stepping* in s: Crank-Nicolson, with a Rannacher start: the first step is replaced by
2 ``n_damp`` implicit-Euler sub-steps (no damping for n_damp = 0). Each step is taken for
u = exp(mu (s - s_n)) p, u_s = (L + mu) u, and mapped back, an exact reformulation for any
constant mu; mu is the decay rate of the mass over the previous step (clipped to
[MU_MIN, MU_MAX]), so the slowest mode, the one that carries the area when A << 1
(A ~ 1/w: rate 2 without adhesion), is integrated almost exactly and the relative time error
does not grow with the decades of G. The wall position is evaluated at both time levels: the
implicit side uses the closure at s_{n+1}, the explicit side the closure at s_n. A node
switched on during a step (receding wall) has no old value: it takes the value of the old
quadratic extrapolant through the old wall (the smooth continuation of P past the wall,
consistent to O(h^3)); a node switched off (advancing wall) just drops out of the system.
The extrapolant's coefficients grow like 1/theta, which is why THETA_MIN is as large as 1/2
(measured: with 0.02 a fast receding wall blows up; 0.2 is marginal). Steps are uniform in s
within each schedule piece (geometric in G once G >> G_s: a fixed number of steps per decade,
NPER_H / h per unit of s), and the wall may cross at most WALL_STEP base node spacings per
step (a receding wall always, so that switched-on nodes lie next to the old wall; an advancing
wall only within K_TRAVEL free standard deviations of the centre: in the far tail it switches
off nodes carrying nothing).

*Outputs.* The area is the integral of p itself: trapezoid rule over the active nodes, the
partial cell [eta_w, eta_j1] integrated exactly for the wall quadratic, and the end correction
(h^2/12) q'(eta_j1) of the Euler-Maclaurin formula (quadrature error O(h^4), below the scheme's
O(h^2)); the first moment likewise, load = y0 (sigma0/y0 A + w int eta p deta). The
detached area and detached load are taken from the identities, detached = 1 - A and
detached_load = load - sigma0 (exact bookkeeping by construction; the wall-flux versions,
the time integral of the wall derivative q'(eta_w) and of sigma_a times it, are computed as
well and returned by :func:`solve_fixedgrid_detail` -- they agree with the identities to the
discretisation error, which is what checks them).

*Start.* The exact solution at a small G_s: the linearly moving wall (or the images solution)
with the slope of the first linear piece of sigma_a, at G_s = min(C_START y0^2, end of that
piece), or the free Gaussian when the wall stays K_WALL_FAR (7) standard deviations away until
later. Schedule points before G_s come from the exact solution.

*Resolution.* Two runs (h, dt) and (h/2, dt/2); the fine one is reported and their difference
/ 3 is the error estimate (second order; measured: its worst value over a schedule is within
a factor 1.1 of the worst true error; pointwise it can miss where the error changes sign).
With ``level`` L >= 0 the spacing is H_LEVEL0 / 2^L (step NPER_H / h per unit of s); from
``rtol`` the fine spacing is H_RTOL sqrt(rtol / 1e-4) / sqrt(1 + (pe / PE_ACC)^2), pe the
largest speed (in eta per unit s) of an advancing wall near the distribution, whose layer of
thickness 1/pe sets the error scale then (measured error <= 0.27 (1 + (pe/PE_ACC)^2) h^2
relative). More than WORK_MAX node-steps: spacing and step are coarsened together and the
status is GRID_CAP.

Richardson extrapolation is not applied. The wall crosses nodes, the closure's error depends
on the fractional distance theta of the wall to the nodes, and the error is not a smooth
function of h beyond its leading term: measured on the level ladder, (4 A_h/2 - A_h) / 3 is
10-100 times more accurate than A_h/2, but its order jumps between 1.6 and 5.3 from one
level to the next (the plain areas converge at order 2.0 +- 0.1 with a moving wall, 2.2-2.6
pre-asymptotically without adhesion), so it has no error model that could set a resolution
or be checked, and the difference of the two runs would no longer estimate its error.

Wall jumps (a repeated G with another sigma_a) are not supported: status BAD_INPUT.
"""
from __future__ import annotations

import math

import numpy as np

from .._jit import njit_serial, njit_sweeps, prange
from . import status as st
from .schedule import (REPEAT_TESTED, boundary_at, exact_start, fill_state, scaled_times,
                       scaled_values)
from .signature import no_upper_wall
from .special import linear_wall_area_moment, linear_wall_density, normal_pdf
from .tridiag import theta_workspace, thomas

# --- constants of the scheme (dimensionless, y0 = 1) ------------------------------------
K_DOMAIN = 6.0        # grid eta in [-K, K]; free variance in eta < 1/2: tail < 1e-16
C_START = 0.25        # latest start G_s = C_START y0^2 with the exact linear-wall solution
THETA_MIN = 0.5       # a node closer than THETA_MIN h to the wall is switched off
WALL_STEP = 1.0       # the wall crosses at most this many base spacings per step
K_TRAVEL = 4.0        # an advancing wall: only within 4 free std of the centre
H_LEVEL0 = 0.1        # node spacing of level 0 of the explicit ladder (120 nodes); its
                      # error-estimate run at 2 H_LEVEL0 = 0.2 is the coarsest grid used:
                      # the central operator stays an M-matrix for |eta| < 1/h = 5
NPER_H = 0.8          # steps per unit of s times h (both modes): dt ~ 1.25 h
H_RTOL = 0.013        # reported (fine) spacing at rtol = 1e-4, scaled as sqrt(rtol): the
                      # measured error of the fine run is <= 0.27 (1 + (pe/PE_ACC)^2) h^2
K_LAYER = 3.0         # an advancing wall more than 3 free std away pushes no layer
PE_ACC = 1.4          # relative, pe the advancing-wall speed in eta per unit s
PECLET_MAX = 0.5      # h * (wall speed in eta) for an advancing wall: resolves its layer
WORK_MAX = 1e8        # node-steps (both runs) above which the resolution is cut (GRID_CAP)
LEAK_TOL = 1e-10      # mass lost through the grid ends above this is flagged (FAR_LEAK)
N_TV = 32             # samples per piece for the wall travel estimate
MU_MIN = -1.0         # clip of the lagged decay rate mu of the time steps (per unit s)
MU_MAX = 8.0


@njit_serial
def _wall_eta(sa, sa0, w):
    """Wall position in eta for sigma_a = sa (scaled): x_w / w, x_w = -1 - (sa - sa0)."""
    return (-1.0 - (sa - sa0)) / w


@njit_serial
def _geometry(eta_w, K, h, n):
    """First active node j1 and its distance theta (in units of h) to the effective wall.

    The effective wall is max(eta_w, -K): a wall left of the grid is replaced by the grid end,
    where the density is below 1e-16. theta lies in [THETA_MIN, 1 + THETA_MIN). Returns
    (j1, theta, on_grid) with on_grid False when the grid end acts as the wall; j1 >= n - 1
    means that fewer than two nodes are active (everything detached).
    """
    t = (eta_w + K) / h
    if t <= 0.0:
        return 1, 1.0, False
    if t >= n:
        return n, 1.0, True
    j = int(math.floor(t)) + 1
    theta = j - t
    if theta < THETA_MIN:
        j += 1
        theta += 1.0
    return j, theta, True


@njit_serial
def _extrapolant(p1, p2, theta, t):
    """Quadratic through (0, 0), (theta, p1), (theta + 1, p2) at t (units of h from the wall)."""
    return (p1 * t * (t - theta - 1.0) / (-theta)
            + p2 * t * (t - theta) / (theta + 1.0))


@njit_serial
def _wall_slope(p1, p2, theta, h):
    """Derivative of the wall quadratic at the wall: the flux into the wall per unit s."""
    return (p1 * (1.0 + theta) / theta - p2 * theta / (1.0 + theta)) / h


@njit_serial
def _integrals(p, j1, theta, eta_w, K, h, n):
    """Area int p deta and first moment int eta p deta over [eta_w, K].

    Trapezoid rule over the nodes j1..n, the partial cell [eta_w, eta_j1] integrated exactly
    for the wall quadratic, and the Euler-Maclaurin end correction (h^2/12) f'(eta_j1) taken
    from the same quadratic: O(h^4) for smooth p.
    """
    if j1 >= n - 1:
        return 0.0, 0.0
    p1 = p[j1]
    p2 = p[j1 + 1]
    eta1 = -K + j1 * h
    s0 = 0.5 * p1
    s1 = 0.5 * eta1 * p1
    for j in range(j1 + 1, n):
        e = -K + j * h
        s0 += p[j]
        s1 += e * p[j]
    th = theta
    # partial cell: int_0^theta q dt and int_0^theta t q dt (units of h)
    c0 = p1 * th * (th + 3.0) / 6.0 - p2 * th * th * th / (6.0 * (th + 1.0))
    c1 = p1 * th * th * (th + 4.0) / 12.0 - p2 * th * th * th * th / (12.0 * (th + 1.0))
    dq = (p1 * (1.0 - th) / th + p2 * th / (1.0 + th)) / h     # q'(eta_j1)
    area = h * s0 + h * c0 + h * h / 12.0 * dq
    m1 = h * s1 + eta_w * h * c0 + h * h * c1 + h * h / 12.0 * (p1 + eta1 * dq)
    return area, m1


@njit_serial
def _operator(K, h, n, lo, di, up):
    """Constant coefficients of the conservative central operator at nodes 1..n-1."""
    inv_h2 = 1.0 / (h * h)
    for j in range(1, n):
        e_minus = -K + (j - 0.5) * h
        e_plus = -K + (j + 0.5) * h
        lo[j] = inv_h2 - e_minus / h
        di[j] = -2.0 * inv_h2 + (e_plus - e_minus) / h
        up[j] = inv_h2 + e_plus / h


@njit_serial
def _step(p, ext, j1_old, th_old, live_old, j1_new, th_new, dt, theta, mu, lo, di, up, a_lo,
          a_di, a_up, rhs, scratch, n):
    """One theta-step between two wall positions; returns the active rows solved.

    Old state: first active node j1_old at distance th_old (live_old False: all zero). The
    explicit part is evaluated on the old profile continued past the old wall by its wall
    quadratic; the implicit part carries the Shortley-Weller ghost of the new wall.

    The step is taken for u = exp(mu (s - s_old)) p, u_s = (L + mu) u, and mapped back
    (p_new = exp(-mu dt) u_new): an exact reformulation for any constant mu, with which the
    theta-method integrates the mode decaying at rate mu exactly. Returns (rows solved,
    node sum of the new profile).
    """
    if j1_new >= n - 1:
        for j in range(n + 1):
            p[j] = 0.0
        return 0, 0.0
    for j in range(n + 1):
        ext[j] = p[j]
    if live_old:
        p1 = p[j1_old]
        p2 = p[j1_old + 1]
        j_lo = j1_new - 1
        if j_lo < 1:
            j_lo = 1
        for j in range(j_lo, j1_old):
            ext[j] = _extrapolant(p1, p2, th_old, th_old - (j1_old - j))
    ext[0] = 0.0
    ext[n] = 0.0
    m = n - j1_new
    e = (1.0 - theta) * dt
    i_ = theta * dt
    for k in range(m):
        j = j1_new + k
        if e != 0.0:
            rhs[k] = ext[j] + e * (lo[j] * ext[j - 1] + (di[j] + mu) * ext[j]
                                   + up[j] * ext[j + 1])
        else:
            rhs[k] = ext[j]
        a_lo[k] = -i_ * lo[j]
        a_di[k] = 1.0 - i_ * (di[j] + mu)
        a_up[k] = -i_ * up[j]
    # ghost p_{j1-1} = c1 p_j1 + c2 p_j1+1 (zero when the grid end is the wall: theta = 1)
    th = th_new
    c1 = -2.0 * (1.0 - th) / th
    c2 = (1.0 - th) / (1.0 + th)
    a_di[0] += a_lo[0] * c1
    a_up[0] += a_lo[0] * c2
    a_lo[0] = 0.0
    thomas(a_lo[:m], a_di[:m], a_up[:m], rhs[:m], scratch[:m], rhs[:m])
    for j in range(j1_new):
        p[j] = 0.0
    back = math.exp(-mu * dt)
    total = 0.0
    for k in range(m):
        v = rhs[k] * back
        p[j1_new + k] = v
        total += v
    p[n] = 0.0
    return m, total


@njit_serial
def _march(G_k, sa_k, i_first, g_start, start_linear, b_start, sa0, sig0, c_w, n, h,
           piece_steps, refine, n_damp, p, ext, lo, di, up, a_lo, a_di, a_up, rhs, scratch,
           out_area, out_load, out_fdet, out_fdet_load, info):
    """March one resolution from the exact start at ``g_start`` through the schedule.

    Scaled units (y0 = 1). Piece k (ending at schedule point G_k[k]) takes
    ``refine * piece_steps[k]`` steps, uniform in s. Writes, for schedule indices >= i_first,
    the area, the scaled load, and the wall-flux detached area and load (the latter two
    include the detachment before the start). ``info`` receives [steps, node-steps, leak].
    Returns a status.
    """
    K = K_DOMAIN
    p = p[: n + 1]
    ext = ext[: n + 1]
    _operator(K, h, n, lo, di, up)
    w = math.sqrt(c_w + 4.0 * g_start)
    sa_cur = boundary_at(G_k, sa_k, g_start)
    # exact start, sampled at the nodes (p = w P)
    x_w = -1.0 - (sa_cur - sa0)
    for j in range(n + 1):
        x = (-K + j * h) * w
        if start_linear:
            p[j] = w * linear_wall_density(x - x_w, 1.0, b_start, g_start)
        else:
            p[j] = w * normal_pdf(x, 2.0 * g_start)
    p[0] = 0.0
    p[n] = 0.0
    if start_linear:
        a_s, m1_s = linear_wall_area_moment(1.0, b_start, g_start)
    else:
        a_s = 1.0
        m1_s = 1.0 + sa_cur - sa0
    fdet = 1.0 - a_s
    fdet_load = (m1_s - sa_cur * a_s) - sig0
    eta_w = _wall_eta(sa_cur, sa0, w)
    j1, th, on_grid = _geometry(eta_w, K, h, n)
    live = j1 < n - 1
    for j in range(j1):
        p[j] = 0.0
    f_old = _wall_slope(p[j1], p[j1 + 1], th, h) if live else 0.0
    r_old = p[n - 1] * (1.0 / h - (K - 0.5 * h))
    leak = 0.0
    steps = 0
    work = 0.0
    damp_left = n_damp
    g_cur = g_start
    n_out = G_k.shape[0]
    mu = 0.0
    total_old = 0.0
    for j in range(j1, n):
        total_old += p[j]
    for i in range(i_first, n_out):
        g_end = G_k[i]
        if g_end > g_cur:
            v = (sa_k[i] - sa_cur) / (g_end - g_cur)
            g_a = g_cur
            sa_a = sa_cur
            w2_a = c_w + 4.0 * g_a
            w2_b = c_w + 4.0 * g_end
            m = piece_steps[i] * refine
            ds = 0.25 * math.log(w2_b / w2_a) / m
            for stp in range(m):
                if damp_left > 0:
                    # Rannacher start: the first step as 2 n_damp implicit-Euler sub-steps
                    n_sub = 2 * damp_left
                    theta = 1.0
                    damp_left = 0
                else:
                    n_sub = 1
                    theta = 0.5
                for sub in range(n_sub):
                    frac = (stp + (sub + 1.0) / n_sub) / m
                    if stp == m - 1 and sub == n_sub - 1:
                        g_b = g_end
                        sa_b = sa_k[i]
                        w2 = w2_b
                    else:
                        w2 = w2_a * (w2_b / w2_a) ** frac
                        g_b = g_a + 0.25 * (w2 - w2_a)
                        sa_b = sa_a + v * (g_b - g_a)
                    w_b = math.sqrt(w2)
                    eta_b = _wall_eta(sa_b, sa0, w_b)
                    j1_b, th_b, on_b = _geometry(eta_b, K, h, n)
                    rows, total = _step(p, ext, j1, th, live, j1_b, th_b, ds / n_sub, theta,
                                        mu, lo, di, up, a_lo, a_di, a_up, rhs, scratch, n)
                    # decay rate of the mass for the next step (lagged), clipped
                    if total > 0.0 and total_old > 0.0:
                        mu = math.log(total_old / total) / (ds / n_sub)
                        if mu < MU_MIN:
                            mu = MU_MIN
                        elif mu > MU_MAX:
                            mu = MU_MAX
                    else:
                        mu = 0.0
                    total_old = total
                    steps += 1
                    work += rows
                    live_b = j1_b < n - 1
                    f_new = _wall_slope(p[j1_b], p[j1_b + 1], th_b, h) if live_b else 0.0
                    r_new = p[n - 1] * (1.0 / h - (K - 0.5 * h))
                    dd = ds / n_sub * ((1.0 - theta) * f_old + theta * f_new)
                    if on_grid and on_b:
                        fdet += dd
                        fdet_load += dd * ((1.0 - theta) * sa_cur + theta * sa_b)
                    else:
                        leak += abs(dd)
                    leak += abs(ds / n_sub * ((1.0 - theta) * r_old + theta * r_new))
                    j1 = j1_b
                    th = th_b
                    on_grid = on_b
                    live = live_b
                    f_old = f_new
                    r_old = r_new
                    w = w_b
                    sa_cur = sa_b
            g_cur = g_end
            sa_cur = sa_k[i]
        eta_w = _wall_eta(sa_cur, sa0, w)
        if live:
            a, m1 = _integrals(p, j1, th, max(eta_w, -K), K, h, n)
        else:
            a = 0.0
            m1 = 0.0
        if not (math.isfinite(a) and math.isfinite(m1)):
            info[0] = steps
            info[1] = work
            info[2] = leak
            return st.NONFINITE
        out_area[i] = a
        out_load[i] = sig0 * a + w * m1
        out_fdet[i] = fdet
        out_fdet_load[i] = fdet_load
    info[0] = steps
    info[1] = work
    info[2] = leak
    if leak > LEAK_TOL:
        return st.FAR_LEAK
    return st.OK


@njit_serial
def _piece_steps(G_k, sa_k, i_first, g_start, sa0, c_w, h, nper, out):
    """Base step count of each schedule piece: nper per unit of s, and at most WALL_STEP
    spacings h of wall travel (total variation of eta_w, clipped to the grid) per step."""
    K = K_DOMAIN
    total = 0.0
    g_prev = g_start
    sa_prev = boundary_at(G_k, sa_k, g_start)
    for i in range(out.shape[0]):
        out[i] = 0
    for i in range(i_first, G_k.shape[0]):
        g_b = G_k[i]
        if g_b <= g_prev:
            continue
        w2_a = c_w + 4.0 * g_prev
        w2_b = c_w + 4.0 * g_b
        ds = 0.25 * math.log(w2_b / w2_a)
        m_s = math.ceil(ds * nper - 1e-9)
        v = (sa_k[i] - sa_prev) / (g_b - g_prev)
        tv = 0.0
        e_prev = min(max(_wall_eta(sa_prev, sa0, math.sqrt(w2_a)), -K), K)
        for q in range(1, N_TV + 1):
            w2 = w2_a * (w2_b / w2_a) ** (q / N_TV)
            g = g_prev + 0.25 * (w2 - w2_a)
            e = min(max(_wall_eta(sa_prev + v * (g - g_prev), sa0, math.sqrt(w2)), -K), K)
            # a receding wall switches nodes on by extrapolation: always limited; an
            # advancing one only switches nodes off, and is free in the far tail (density
            # below exp(-K_TRAVEL^2 / 2) of the peak)
            if e < e_prev or e > -K_TRAVEL * math.sqrt(2.0 * g / w2):
                tv += abs(e - e_prev)
            e_prev = e
        m_w = math.ceil(tv / (WALL_STEP * h) - 1e-9)
        m = max(m_s, m_w, 1.0)
        out[i] = int(m)
        total += m
        g_prev = g_b
        sa_prev = sa_k[i]
    return total


@njit_serial
def _advancing_speed(G_k, sa_k, i_first, sa0, c_w):
    """Largest w |d sigma_a/dG| over pieces where the wall advances (sigma_a decreasing)
    while it is near the distribution (within K_LAYER free standard deviations of the
    centre at an end of the piece).

    It is the wall speed in eta per unit s, and 1/it the thickness of the layer it pushes;
    a wall that moves fast far from the distribution pushes no layer.
    """
    pe = 0.0
    for k in range(max(i_first, 1), G_k.shape[0]):
        dg = G_k[k] - G_k[k - 1]
        if dg > 0.0 and sa_k[k] < sa_k[k - 1]:
            w_a = math.sqrt(c_w + 4.0 * G_k[k - 1])
            w_b = math.sqrt(c_w + 4.0 * G_k[k])
            sd_a = math.sqrt(2.0 * G_k[k - 1]) / w_a
            sd_b = math.sqrt(2.0 * G_k[k]) / w_b
            if (_wall_eta(sa_k[k - 1], sa0, w_a) < -K_LAYER * sd_a
                    and _wall_eta(sa_k[k], sa0, w_b) < -K_LAYER * sd_b):
                continue
            v = (sa_k[k - 1] - sa_k[k]) / dg * w_b
            if v > pe:
                pe = v
    return pe


@njit_serial
def _check_input(G, sa, sigma0, rtol, level, n_damp, out_area, out_load, out_det_area,
                 out_det_load, out_error, counts):
    """Shapes, finiteness, ordering; repeated G with another sigma_a (a wall jump) is refused."""
    nt = G.shape[0]
    if nt < 1 or sa.shape[0] != nt or counts.shape[0] < 3:
        return False
    if (out_area.shape[0] != nt or out_load.shape[0] != nt or out_det_area.shape[0] != nt
            or out_det_load.shape[0] != nt or out_error.shape[0] != nt):
        return False
    if not math.isfinite(sigma0) or n_damp < 0 or level < -1 or level > 10:
        return False
    if level < 0 and not (rtol > 0.0 and math.isfinite(rtol)):
        return False
    for k in range(nt):
        if not (math.isfinite(G[k]) and math.isfinite(sa[k])) or G[k] < 0.0:
            return False
        if k > 0:
            if G[k] < G[k - 1]:
                return False
            if G[k] == G[k - 1] and sa[k] != sa[k - 1]:
                return False
    return True


@njit_serial
def solve_fixedgrid_detail(G, sa, sigma0, rtol, level, n_damp, out_area, out_load,
                           out_det_area, out_det_load, out_error, out_flux_det,
                           out_flux_det_load, counts):
    """:func:`solve_fixedgrid_one` that also returns the wall-flux detachment.

    ``out_flux_det`` and ``out_flux_det_load`` (n_t,) receive the detached area and load
    integrated from the wall flux, int q'(eta_w) ds and int sigma_a q'(eta_w) ds (plus the
    exact detachment before the start), of the reported (fine) run, in the caller's units.
    ``counts`` (3,) int64: nodes, steps and node-steps of the work done. Returns a status.
    """
    nt = G.shape[0]
    for k in range(counts.shape[0]):
        counts[k] = 0
    if not _check_input(G, sa, sigma0, rtol, level, n_damp, out_area, out_load, out_det_area,
                        out_det_load, out_error, counts) or out_flux_det.shape[0] != nt \
            or out_flux_det_load.shape[0] != nt:
        out_area[:] = np.nan
        out_load[:] = np.nan
        out_det_area[:] = np.nan
        out_det_load[:] = np.nan
        out_error[:] = np.nan
        return st.BAD_INPUT
    if sigma0 + sa[0] <= 0.0:
        fill_state(np.int64(0), nt, 0.0, 0.0, 1.0, -sigma0, 0.0, out_area, out_load, out_det_area,
                   out_det_load, out_error)
        for k in range(nt):
            out_flux_det[k] = 1.0
            out_flux_det_load[k] = -sigma0
        return st.OK
    sa0_phys = sa[0]
    y0 = sigma0 + sa0_phys
    G_k = scaled_times(G, y0)
    sa_k = scaled_values(sa, sa0_phys, y0)
    sa0 = sa_k[0]
    sig0 = sigma0 / y0
    # the start (first linear piece of sigma_a with collinear points merged, repeated G
    # tested like the others: no jumps here; the free start sought up to the end) and the
    # schedule points up to it: exact
    b_lin, start_linear, g_start, i_first = exact_start(
        G_k, sa_k, sa0, sig0, y0, sigma0, REPEAT_TESTED, C_START, G_k[nt], False, out_area,
        out_load, out_det_area, out_det_load, out_error, out_flux_det, out_flux_det_load)
    if i_first > nt:
        return st.OK
    if start_linear:
        a_start, _ = linear_wall_area_moment(1.0, b_lin, g_start)
        if a_start <= 0.0:
            fill_state(i_first - 1, nt, 0.0, 0.0, 1.0, -sigma0, 0.0, out_area, out_load,
                       out_det_area, out_det_load, out_error)
            for k in range(i_first - 1, nt):
                out_flux_det[k] = 1.0
                out_flux_det_load[k] = -sigma0
            return st.OK
    status = st.OK
    c_w = 4.0 * g_start
    # resolution: level ladder or from rtol; the layer pushed by an advancing wall is resolved
    pe = _advancing_speed(G_k, sa_k, i_first, sa0, c_w)
    if level >= 0:
        # base of the ladder: the grid below level 0 (the error-estimate run of level 0)
        h_c = 2.0 * H_LEVEL0
        r_c = 1 << level
    else:
        # the layer pushed by an advancing wall (thickness 1/pe) sets the error scale too
        h_c = 2.0 * H_RTOL * math.sqrt(rtol / 1e-4) / math.sqrt(1.0 + (pe / PE_ACC) ** 2)
        if h_c > 2.0 * H_LEVEL0:
            h_c = 2.0 * H_LEVEL0
        r_c = 1
    if pe * h_c > PECLET_MAX:
        h_c = PECLET_MAX / pe
    n_c = 2 * int(math.ceil(K_DOMAIN / h_c))
    if n_c < 8:
        n_c = 8
    h_c = 2.0 * K_DOMAIN / n_c
    piece = np.zeros(nt + 1, dtype=np.int64)
    m_tot = _piece_steps(G_k, sa_k, i_first, g_start, sa0, c_w, h_c, NPER_H / h_c, piece)
    # work of both runs (the fine one has 2x the nodes and 2x the steps); past WORK_MAX the
    # spacing and the step are coarsened together and the result is flagged
    est = 5.0 * (n_c * r_c) * (m_tot * r_c + n_damp)
    if level < 0 and est > WORK_MAX:
        status = st.GRID_CAP
        cut = math.sqrt(est / WORK_MAX)
        n_c = 2 * int(math.ceil(K_DOMAIN / (h_c * cut)))
        if n_c < 8:
            n_c = 8
        h_c = 2.0 * K_DOMAIN / n_c
        m_tot = _piece_steps(G_k, sa_k, i_first, g_start, sa0, c_w, h_c, NPER_H / h_c, piece)
    n_a = n_c * r_c
    n_b = 2 * n_a
    nb1 = n_b + 1
    p = np.empty(nb1)
    ext = np.empty(nb1)
    lo, di, up, a_lo, a_di, a_up, rhs, scratch = theta_workspace(nb1)
    ca = np.empty(nt + 1)
    cl = np.empty(nt + 1)
    cd = np.empty(nt + 1)
    cdl = np.empty(nt + 1)
    info_c = np.zeros(3)
    info_f = np.zeros(3)
    s1 = _march(G_k, sa_k, i_first, g_start, start_linear, b_lin, sa0, sig0, c_w, n_a,
                2.0 * K_DOMAIN / n_a, piece, r_c, n_damp, p, ext, lo, di, up, a_lo, a_di,
                a_up, rhs, scratch, ca, cl, cd, cdl, info_c)
    fa = np.empty(nt + 1)
    fl = np.empty(nt + 1)
    s2 = _march(G_k, sa_k, i_first, g_start, start_linear, b_lin, sa0, sig0, c_w, n_b,
                2.0 * K_DOMAIN / n_b, piece, 2 * r_c, n_damp, p, ext, lo, di, up, a_lo,
                a_di, a_up, rhs, scratch, fa, fl, cd, cdl, info_f)
    if s1 != st.OK:
        status = s1
    if s2 != st.OK:
        status = s2
    for k in range(i_first, nt + 1):
        a = fa[k]
        if a > 1.0:
            a = 1.0
        elif a < 0.0:
            a = 0.0
        ld = fl[k] * y0
        out_area[k - 1] = a
        out_load[k - 1] = ld
        out_det_area[k - 1] = 1.0 - a
        out_det_load[k - 1] = ld - sigma0
        out_error[k - 1] = abs(fa[k] - ca[k]) / 3.0
        out_flux_det[k - 1] = cd[k]
        out_flux_det_load[k - 1] = cdl[k] * y0
        if not math.isfinite(a) or not math.isfinite(ld):
            status = st.NONFINITE
    counts[0] = n_b + 1
    counts[1] = int(info_f[0])
    counts[2] = int(info_c[1] + info_f[1])
    return status


@njit_serial
def solve_fixedgrid_one(G, sa, sigma0, rtol, level, n_damp, out_area, out_load,
                        out_det_area, out_det_load, out_error, counts):
    """Contact area and load bookkeeping of one nominal pressure on a fixed stress grid.

    Parameters
    ----------
    G : (n_t,) float64
        Non-decreasing diffusion times, G[0] >= 0 (a repeated G must repeat sigma_a too:
        wall jumps are not supported).
    sa : (n_t,) float64
        Detachment stress sigma_a at those times (wall at -sa), linear in G in between,
        constant sa[0] before G[0].
    sigma0 : float
        Nominal stress (compressive > 0), same stress unit as sqrt(G).
    rtol : float
        Target relative accuracy of the area when ``level`` is -1.
    level : int
        -1: resolution from ``rtol`` (two runs h and h/2, the fine one reported);
        L >= 0: the explicit ladder, each level halving both the node spacing and the step
        size (level 0: 120 nodes, 8 steps per unit of s); the level below is run for the
        error estimate.
    n_damp : int
        Crank-Nicolson steps at the start replaced by two implicit-Euler half steps
        (Rannacher damping).
    out_area, out_load, out_det_area, out_det_load, out_error : (n_t,) float64
        Written in place: A/A0, load int sigma P dsigma, detached area 1 - A, detached load
        load - sigma0, and the error estimate |A_h/2 - A_h| / 3 of the area.
    counts : (3,) int64
        Written in place: nodes and time steps of the reported run, node-steps (active rows
        solved) of all runs.

    Returns
    -------
    status : int
        0 ok; BAD_INPUT for inconsistent arrays or a wall jump; GRID_CAP when the tolerance
        needs more than WORK_MAX node-steps (resolution cut); FAR_LEAK, NONFINITE; see
        :mod:`persson_fast._kernels.status`.

    Notes
    -----
    The scheme (fixed similarity grid eta = (sigma - sigma0) / (y0 w), off-grid Dirichlet
    closure of Shortley-Weller type, Crank-Nicolson with a Rannacher start) is described in
    the module docstring. Scale-free: only consistent units are needed.
    """
    nt = G.shape[0]
    fd = np.empty(nt)
    fdl = np.empty(nt)
    return solve_fixedgrid_detail(G, sa, sigma0, rtol, level, n_damp, out_area, out_load,
                                  out_det_area, out_det_load, out_error, fd, fdl, counts)


# the sweep of the one signature of every grid method


def _fixedgrid_sweep(G, sa_rows, sy_rows, pressures, rtol, level, n_damp, area, load, det_area,
                     det_load, error, pl_area, pl_load, status, counts):
    """Solve every pressure with :func:`solve_fixedgrid_one`.

    Arguments as in :mod:`persson_fast._kernels.signature` (no ``variant``): one wall, so
    ``sy_rows`` must be absent (rows of length 0, or +inf at every G; else BAD_INPUT),
    ``pl_area``/``pl_load`` rows of length 0 (not requested) or n_t (set to zero).
    """
    n_p = pressures.shape[0]
    n_t = G.shape[0]
    for k in prange(n_p):
        if no_upper_wall(sy_rows, pl_area, pl_load, k, n_p, n_t):
            status[k] = solve_fixedgrid_one(G, sa_rows[k], pressures[k], rtol, level, n_damp,
                                            area[k], load[k], det_area[k], det_load[k],
                                            error[k], counts[k])
        else:
            status[k] = st.BAD_INPUT


fixedgrid_sweep_serial, fixedgrid_sweep_parallel = njit_sweeps(_fixedgrid_sweep)
