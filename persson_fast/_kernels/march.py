"""Adhesion as one causal forward march in G for a given scalar K (issue 41), ``@njit``.

**Status: a private prototype**, driven only by :mod:`persson_fast.adhesion.march`
(:func:`~persson_fast.adhesion.march.solve_march`); :func:`persson_fast.solve_contact` does not
use it. Its measured accuracy and speed against today's solver are in the table of
``benchmarks/march_prototype.py`` (errors 0.2-0.9 rtol at rtol 1e-4 to 1e-6, error estimate
not yet always covering the error, 0.10x to 19x today's speed).

Seed Eq. 9 with U_el(zeta) = U_el(1) - J(zeta) reads

    A(zeta) gamma_eff(zeta) = dgamma K + J(zeta),   K = A(zeta1) - U_el(1)/dgamma,
    J(zeta) = (pi E*/2) int_{q0}^{zeta q0} q^2 C(q) F(A(q)) dq,   F(A) = A S(A).

In the diffusion time G (dG = (pi/4) E*^2 q^3 C dq) the surface drops out of J:

    dj/dG = 2 beta^2 F(A) / c(G)^2,    j = J/dgamma,   c = beta (dgamma E* q)^(1/2),
    sigma_a(G) = c(G) (max(K + j(G), 0) / A(G))^(1/2).

So for a given K the wall at G depends only on what the march has computed (j, from the areas at
coarser scales) and on the current area A(G) (a local implicit relation). :func:`march_k`
marches the diffusion from zeta = 1 to zeta1 once and returns A(zeta1) and j(zeta1); the
fixed point of Eqs. 8-9 is the scalar root Phi(K) = K + j(zeta1; K) - A(zeta1; K) = 0
(the driver :mod:`persson_fast.adhesion.march`).

Scheme (scaled by the start distance y0 = sigma0 + sigma_a(G=0), as the similarity grid of
:mod:`.similarity`): xi = y / w, w^2 = 1 + 4 g, y = sigma + sigma_a the distance to the wall,
the wall on node 0, theta-steps of :func:`.tridiag.theta_step` (Crank-Nicolson, Rannacher
start: implicit-Euler half steps at the start and after the onset), the wall's drift
exponentially fitted. Steps: the mesh points G_k given by the driver (each level bisects the
previous level's intervals), one step per interval.

* The wall inside a step: sigma_a at the step's end from the step's own end area (secant
  iteration on sigma_a(G_b); each evaluation re-solves the step from the saved profile), the
  wall linear in G over the step, j by the trapezoid rule: the trapezoid (Crank-Nicolson) rule
  of the coupled system.
* The sign change of gamma_eff (K + j = 0; j increases, so at most once, from - to +): a step
  that ends with K + j > 0 while the wall still stood at 0 is split at the root G* of the cubic
  Hermite interpolant of j (values and slopes at both ends; the wall is at rest before G*, so
  the step to the end with a resting wall is the true solution up to G*).
* The onset: sigma_a^2 = c^2 (K + j)/A is smooth and vanishes linearly at G*, so sigma_a is
  smooth in tau = (G - G*)^(1/2), and the near-wall problem (a linear profile left by the
  resting wall, a wall receding as alpha tau) is self-similar in y/tau. The onset segment
  [G*, G_e] (G_e: the second level-0 mesh point after G*) is stepped uniformly in tau with
  ``m_on`` steps (the driver doubles it with each level, as it halves h): the discrete
  problem near the onset is then the same at every level in the units of the grid, its error
  scales as h^2 with the rest, and Richardson extrapolation cancels it.
* A wall receding far below the distribution (more than XC_CAP widths in xi, 8.5 standard
  deviations of the free spread) is held at that depth (it removes nothing there).
* The start: the free Gaussian at g_s = 1/(2 GS_WIDTHS^2) (the wall GS_WIDTHS free standard
  deviations away, never closer before: it only recedes before the sign change), on a grid
  2^START_FINE times finer, coarsened by dropping every other node (area and first moment
  kept) as the profile widens.
"""
from __future__ import annotations

import math

import numpy as np

from .._jit import njit_serial
from .similarity import _moments, _project_moments
from .special import ndtr, normal_pdf
from .tridiag import fitted_diffusion, theta_step

GS_WIDTHS = 8.5          # start where the resting wall is this many free std away
START_FINE = 3           # the start grid is 2^START_FINE times finer than h
COARSEN_SD = (0.16, 0.32, 0.6)   # coarsen when the free std in xi reaches these
XC_CAP = 6.0             # the wall is held at most this far (in xi) below the profile centre
FAR_SD = 10.0            # grid end: this many std (in xi) beyond the centre
SECANT_TOL = 1e-12       # relative tolerance of the wall at a step's end
SECANT_MAX = 30
# info slots
I_AREA, I_J, I_STATUS, I_GSTAR, I_WORK, I_SOLVES, I_SA, I_ITER_MAX, I_Y0 = range(9)
N_INFO = 9
ST_OK = 0
ST_SEPARATED = 1
ST_SECANT = 2
ST_START_GAP = 4


@njit_serial
def _f_of(a, gamma_s):
    """F(A) = A S(A): S = 1 (gamma_s < 0) or gamma_s + (1 - gamma_s) A^2."""
    if gamma_s < 0.0:
        return a
    return a * (gamma_s + (1.0 - gamma_s) * a * a)


@njit_serial
def _hermite(Gm, v, dv, i, G):
    """Cubic Hermite interpolant of v (slopes dv) on [Gm[i], Gm[i+1]] at G."""
    a = Gm[i]
    d = Gm[i + 1] - a
    if d <= 0.0:
        return v[i]
    t = (G - a) / d
    u = 1.0 - t
    return ((1.0 + 2.0 * t) * u * u * v[i] + t * u * u * d * dv[i]
            + t * t * (3.0 - 2.0 * t) * v[i + 1] + t * t * (t - 1.0) * d * dv[i + 1])


@njit_serial
def _interval(Gm, G, i):
    """Index i of the mesh interval [Gm[i], Gm[i+1]] holding G, searched from i upwards."""
    n = Gm.shape[0]
    while i + 2 < n and Gm[i + 1] < G:
        i += 1
    return i


@njit_serial
def _advance(p, q, n, h, g_a, g_b, sae_a, sae_b, damped, lo, di, up):
    """One step of the profile p (nodes 0..n, wall at node 0) from g_a to g_b with the wall
    linear in g from sae_a to sae_b (march units), into q; returns the area of q.
    ``damped``: two implicit-Euler half steps (Rannacher) instead of Crank-Nicolson."""
    for j in range(n + 1):
        q[j] = p[j]
    qq = q[:n + 1]
    v = (sae_b - sae_a) / (g_b - g_a)
    if damped:
        g_m = 0.5 * (g_a + g_b)
        w0 = math.sqrt(1.0 + 4.0 * g_a)
        w1 = math.sqrt(1.0 + 4.0 * g_m)
        w2 = math.sqrt(1.0 + 4.0 * g_b)
        rr = w1 / w0
        drift = v * 0.5 * (w0 + w1)
        theta_step(qq, h, drift, fitted_diffusion(drift * h), (rr - 1.0) / 2.0, 1.0, lo, di,
                   up)
        rr = w2 / w1
        drift = v * 0.5 * (w1 + w2)
        theta_step(qq, h, drift, fitted_diffusion(drift * h), (rr - 1.0) / 2.0, 1.0, lo, di,
                   up)
    else:
        wa = math.sqrt(1.0 + 4.0 * g_a)
        wb = math.sqrt(1.0 + 4.0 * g_b)
        rr = wb / wa
        dt = (rr - 1.0) / (1.0 + rr)
        drift = v * 0.5 * (wa + wb)
        theta_step(qq, h, drift, fitted_diffusion(drift * h), dt, 0.5, lo, di, up)
    a, m1 = _moments(qq, h)
    return a


@njit_serial
def _cap(g, sa0m):
    """Deepest wall used (march units): the profile centre at most XC_CAP from it in xi."""
    return XC_CAP * math.sqrt(1.0 + 4.0 * g) - 1.0 + sa0m


@njit_serial
def _hermite_root(K, g_a, g_b, j_a, j_b, s_a, s_b):
    """Root in (g_a, g_b) of K + H(g), H the cubic Hermite interpolant of j (values j_a, j_b,
    slopes s_a, s_b); K + j_a <= 0 < K + j_b. Bisection safeguarded regula falsi."""
    lo = g_a
    hi = g_b
    d = g_b - g_a
    f_lo = K + j_a
    f_hi = K + j_b
    x = lo
    for it in range(200):
        x = lo - f_lo * (hi - lo) / (f_hi - f_lo)
        if not (lo < x < hi) or it % 3 == 2:
            x = 0.5 * (lo + hi)
        t = (x - g_a) / d
        u = 1.0 - t
        f = K + ((1.0 + 2.0 * t) * u * u * j_a + t * u * u * d * s_a
                 + t * t * (3.0 - 2.0 * t) * j_b + t * t * (t - 1.0) * d * s_b)
        if f > 0.0:
            hi = x
            f_hi = f
        else:
            lo = x
            f_lo = f
        if hi - lo <= 1e-15 * hi:
            break
    return 0.5 * (lo + hi)


@njit_serial
def _coarsen(p, n_act, hc):
    """Drop every other node (the wall stays on node 0), keeping area and first moment."""
    a_c, m_c = _moments(p[:n_act + 1], hc)
    for j in range(n_act // 2 + 1):
        p[j] = p[2 * j]
    for j in range(n_act // 2 + 1, n_act + 1):
        p[j] = 0.0
    n_act //= 2
    hc *= 2.0
    _project_moments(p[:n_act + 1], hc, a_c, m_c)
    return n_act, hc


@njit_serial
def march_k(K, sig0, beta2, gamma_s, Gm, c2m, dc2m, j1m, base, h, n_damp, refine, m_start, m_pre,
            m_on, prof_a, prof_sa, prof_j, info):
    """March the adhesive diffusion for a given K; see the module docstring.

    Scene units (stress / scale): ``sig0`` the nominal pressure, ``Gm`` (n,) the mesh of G
    (Gm[0] = 0), ``c2m`` = c^2 and ``dc2m`` = d(c^2)/dG at the mesh points, ``base`` (n,) 1
    at the points of the level-0 mesh, ``j1m`` (n,) j with A = 1 (exact, used up to the
    start). ``h``: node spacing in xi (the start grid is
    2^START_FINE times finer). Every stretch that does not begin and end at level-0 points is
    divided into a number of steps proportional to ``refine`` (2^level), so that the
    discretisation of each level is the previous one's with every step halved: the start
    (from g_s to the first level-0 point, ``m_start refine`` steps geometric in G), the
    approach to the sign change (from the last level-0 point before G* to G*, ``m_pre refine``
    equal steps, the wall at rest) and the onset (G* to the second level-0 point after it,
    ``m_on refine`` steps uniform in (G - G*)^(1/2)). Outputs: ``prof_a``, ``prof_sa`` (scene
    units), ``prof_j`` at the mesh points (NaN where a special stretch skips them), ``info``
    (N_INFO,): the end area, j at zeta1, status, G* (-1 if none), node-steps, step solves,
    sigma_a at zeta1, most secant iterations of a step, y0.
    """
    n = Gm.shape[0]
    for k in range(N_INFO):
        info[k] = 0.0
    info[I_GSTAR] = -1.0
    for k in range(n):
        prof_a[k] = np.nan
        prof_sa[k] = np.nan
        prof_j[k] = np.nan
    sa0 = math.sqrt(c2m[0] * K) if K > 0.0 else 0.0
    y0 = sig0 + sa0
    info[I_Y0] = y0
    if not (y0 > 0.0):
        # separated at the start: no contact at any scale, J = 0
        for k in range(n):
            prof_a[k] = 0.0
            prof_sa[k] = sa0
            prof_j[k] = 0.0
        info[I_STATUS] = ST_SEPARATED
        return
    y2 = y0 * y0
    F1 = _f_of(1.0, gamma_s)
    g_s = 1.0 / (2.0 * GS_WIDTHS * GS_WIDTHS)
    gs_scene = g_s * y2
    # j with A = 1 up to the start (the wall GS_WIDTHS free std away): the exact
    # j_1(G) = (pi E*/(2 dgamma)) int_{q0}^{q(G)} q^2 C dq given at the mesh points (``j1m``),
    # interpolated by the cubic Hermite with its exact slopes dj_1/dG = 2 beta^2 / c^2 (a
    # quadrature on the level's own mesh would leave a level-independent error in j, which
    # Richardson cannot remove; it moves K, not A)
    i = 0
    prof_a[0] = 1.0
    prof_sa[0] = sa0
    prof_j[0] = 0.0
    while i + 1 < n and Gm[i + 1] <= gs_scene:
        i += 1
        prof_a[i] = 1.0
    if i == n - 1:
        # the whole spectrum before the start: full contact
        jj = j1m[n - 1]
        info[I_AREA] = 1.0
        info[I_J] = jj
        info[I_SA] = math.sqrt(c2m[n - 1] * max(K + jj, 0.0))
        return
    i_h = _interval(Gm, gs_scene, i)
    c2s = _hermite(Gm, c2m, dc2m, i_h, gs_scene)
    d_h = Gm[i_h + 1] - Gm[i_h]
    t_h = (gs_scene - Gm[i_h]) / d_h
    u_h = 1.0 - t_h
    jj = ((1.0 + 2.0 * t_h) * u_h * u_h * j1m[i_h]
          + t_h * u_h * u_h * d_h * 2.0 * beta2 * F1 / c2m[i_h]
          + t_h * t_h * (3.0 - 2.0 * t_h) * j1m[i_h + 1]
          + t_h * t_h * (t_h - 1.0) * d_h * 2.0 * beta2 * F1 / c2m[i_h + 1])
    # march units: g = G / y0^2, stresses / y0, c^2 / y0^2
    sa0m = sa0 / y0
    sa_a = math.sqrt(c2s / y2 * max(K + jj, 0.0))
    sae_a = min(sa_a, _cap(g_s, sa0m))
    w = math.sqrt(1.0 + 4.0 * g_s)
    y_c = 1.0 + sae_a - sa0m
    hs = h / (2.0 ** START_FINE)
    n_cap = int(math.ceil((XC_CAP + FAR_SD * 0.75 + 2.0) / hs)) + 8
    p = np.zeros(n_cap + 1)
    q = np.zeros(n_cap + 1)
    pb = np.zeros(n_cap + 1)
    lo = np.empty(n_cap + 1)
    di = np.empty(n_cap + 1)
    up = np.empty(n_cap + 1)
    sd_y = math.sqrt(2.0 * g_s)
    n_act = int(math.ceil((y_c / w + FAR_SD * sd_y / w + 0.5) / hs)) + 2
    if n_act > n_cap:
        n_act = n_cap
    hc = hs
    for j in range(1, n_act):
        p[j] = w * normal_pdf(j * hc * w - y_c, 2.0 * g_s)
    p[0] = 0.0
    p[n_act] = 0.0
    u = y_c / sd_y
    a_s = ndtr(u)
    m1_s = y_c * a_s + sd_y * math.exp(-0.5 * u * u) / math.sqrt(2.0 * math.pi)
    _project_moments(p[:n_act + 1], hc, a_s, m1_s / w)
    A_a = a_s
    g_a = g_s
    c2_a = c2s / y2
    fc_a = _f_of(A_a, gamma_s) / c2_a
    n_coarse = 0
    damp_left = n_damp
    onset_done = K + jj > 0.0
    v_prev = 0.0
    # the saved state at the last level-0 point (or the start)
    for j in range(n_act + 1):
        pb[j] = p[j]
    b_n, b_h, b_g, b_A, b_j, b_fc, b_damp, b_i = n_act, hc, g_a, A_a, jj, fc_a, damp_left, i
    # targets: the start stretch, geometric in G up to the first level-0 point above g_s
    k1 = i + 1
    while k1 < n - 1 and base[k1] != 1:
        k1 += 1
    n_tmax = (m_start + m_pre + m_on) * refine + 4
    tg = np.empty(n_tmax)
    tc = np.empty(n_tmax)
    tk = np.empty(n_tmax, dtype=np.int64)
    n_t = m_start * refine
    g_k1 = Gm[k1] / y2
    i_h = i
    for s in range(1, n_t + 1):
        if s == n_t:
            tg[s - 1] = g_k1
            tc[s - 1] = c2m[k1] / y2
            tk[s - 1] = k1
        else:
            gg = g_s * (g_k1 / g_s) ** (s / n_t)
            i_h = _interval(Gm, gg * y2, i_h)
            tg[s - 1] = gg
            tc[s - 1] = _hermite(Gm, c2m, dc2m, i_h, gg * y2) / y2
            tk[s - 1] = -1
    pos = 0
    next_k = k1 + 1
    rest_forced = False
    g_st = -1.0
    work = 0.0
    solves = 0.0
    it_max = 0.0
    status = ST_OK
    while True:
        if pos == n_t:
            if next_k >= n:
                break
            tg[0] = Gm[next_k] / y2
            tc[0] = c2m[next_k] / y2
            tk[0] = next_k
            n_t = 1
            pos = 0
            next_k += 1
        g_b = tg[pos]
        c2_b = tc[pos]
        kk = tk[pos]
        pos += 1
        if not (g_b > g_a):
            if kk == -2:
                jj = -K
                onset_done = True
                rest_forced = False
                damp_left = n_damp
                sa_a = 0.0
                sae_a = 0.0
                v_prev = 0.0
            continue
        # the grid's end: FAR_SD std beyond the centre
        w_b = math.sqrt(1.0 + 4.0 * g_b)
        xi_c = (1.0 + sae_a - sa0m) / math.sqrt(1.0 + 4.0 * g_a)
        if xi_c > XC_CAP:
            xi_c = XC_CAP
        need = int(math.ceil((xi_c + 0.5 + FAR_SD * math.sqrt(2.0 * g_b) / w_b) / hc)) + 2
        if need > n_act:
            if need > n_cap:
                need = n_cap
            for j in range(n_act, need + 1):
                p[j] = 0.0
            n_act = need
        damped = damp_left > 0
        if not onset_done:
            # the wall at rest (gamma_eff <= 0)
            A_b = _advance(p, q, n_act, hc, g_a, g_b, 0.0, 0.0, damped, lo, di, up)
            work += (n_act - 1) * (2.0 if damped else 1.0)
            solves += 1.0
            fc_b = _f_of(A_b, gamma_s) / c2_b
            j_b = jj + (g_b - g_a) * beta2 * (fc_a + fc_b)
            if K + j_b > 0.0 and not rest_forced:
                # the sign change inside this step: G* from the Hermite interpolant of j; back
                # to the last level-0 point, then m_pre refine equal steps to G* and
                # m_on refine steps uniform in (G - G*)^(1/2) to the second level-0 point
                # after G*
                g_st = _hermite_root(K, g_a, g_b, jj, j_b, 2.0 * beta2 * fc_a,
                                     2.0 * beta2 * fc_b)
                info[I_GSTAR] = g_st * y2
                if b_n > n_act:
                    n_act = b_n
                for j in range(b_n + 1):
                    p[j] = pb[j]
                for j in range(b_n + 1, n_act + 1):
                    p[j] = 0.0
                hc, g_a, A_a, jj, fc_a, damp_left = b_h, b_g, b_A, b_j, b_fc, b_damp
                n_pre = m_pre * refine
                nt = 0
                i_h = 0
                for s in range(1, n_pre + 1):
                    gg = g_a + (g_st - g_a) * s / n_pre
                    i_h = _interval(Gm, gg * y2, i_h)
                    tg[nt] = gg
                    tc[nt] = _hermite(Gm, c2m, dc2m, i_h, gg * y2) / y2
                    tk[nt] = -2 if s == n_pre else -1
                    nt += 1
                ke = 0
                n_b = 0
                while ke < n - 1 and n_b < 2:
                    ke += 1
                    if base[ke] == 1 and Gm[ke] > g_st * y2:
                        n_b += 1
                g_e = Gm[ke] / y2
                tau_e = math.sqrt(g_e - g_st)
                n_on = m_on * refine
                for s in range(1, n_on + 1):
                    if s == n_on:
                        tg[nt] = g_e
                        tc[nt] = c2m[ke] / y2
                        tk[nt] = ke
                    else:
                        tau = tau_e * s / n_on
                        gg = g_st + tau * tau
                        i_h = _interval(Gm, gg * y2, i_h)
                        tg[nt] = gg
                        tc[nt] = _hermite(Gm, c2m, dc2m, i_h, gg * y2) / y2
                        tk[nt] = -1
                    nt += 1
                n_t = nt
                pos = 0
                next_k = ke + 1
                rest_forced = True
                continue
            for j in range(n_act + 1):
                p[j] = q[j]
            if damped:
                damp_left -= 1
            g_a = g_b
            A_a = A_b
            fc_a = fc_b
            c2_a = c2_b
            jj = j_b
            if kk == -2:
                # arrived at G*: the sign change, the wall starts to recede
                jj = -K
                onset_done = True
                rest_forced = False
                damp_left = n_damp
                sa_a = 0.0
                sae_a = 0.0
                v_prev = 0.0
        else:
            if g_st >= 0.0 and g_a - g_st < 0.5 * (g_b - g_st) and sa_a == 0.0:
                # first step after the onset: sigma_a ~ alpha (G - G*)^(1/2)
                pred = math.sqrt(2.0 * beta2 * _f_of(A_a, gamma_s) / max(A_a, 1e-300)
                                 * (g_b - g_st))
            elif g_st >= 0.0 and g_a > g_st and kk < 0:
                pred = sa_a * math.sqrt((g_b - g_st) / (g_a - g_st))
            else:
                pred = sa_a + v_prev * (g_b - g_a)
            A_b, j_b, sa_b, sae_b, nit = _wall_step(
                p, q, n_act, hc, g_a, g_b, sa_a, sae_a, A_a, jj, fc_a, c2_b, K, beta2,
                gamma_s, sa0m, pred, damped, lo, di, up)
            work += (n_act - 1) * nit * (2.0 if damped else 1.0)
            solves += nit
            if nit > it_max:
                it_max = nit
            if nit >= SECANT_MAX:
                status |= ST_SECANT
            if damped:
                damp_left -= 1
            for j in range(n_act + 1):
                p[j] = q[j]
            v_prev = (sa_b - sa_a) / (g_b - g_a)
            g_a = g_b
            A_a = A_b
            jj = j_b
            sa_a = sa_b
            sae_a = sae_b
            c2_a = c2_b
            fc_a = _f_of(A_b, gamma_s) / c2_b
        if kk >= 0:
            prof_a[kk] = A_a
            prof_sa[kk] = sa_a * y0
            prof_j[kk] = jj
            if base[kk] == 1:
                # a level-0 point: coarsen when the profile has widened, save the state
                sd_xi = math.sqrt(2.0 * g_a) / math.sqrt(1.0 + 4.0 * g_a)
                while (n_coarse < START_FINE and sd_xi >= COARSEN_SD[n_coarse]
                       and n_act % 2 == 0):
                    n_act, hc = _coarsen(p, n_act, hc)
                    n_coarse += 1
                if not onset_done:
                    for j in range(n_act + 1):
                        pb[j] = p[j]
                    b_n, b_h, b_g, b_A, b_j, b_fc, b_damp = (n_act, hc, g_a, A_a, jj, fc_a,
                                                             damp_left)
    info[I_AREA] = A_a
    info[I_J] = jj
    info[I_STATUS] = status
    info[I_WORK] = work
    info[I_SOLVES] = solves
    info[I_SA] = sa_a * y0
    info[I_ITER_MAX] = it_max


@njit_serial
def _wall_step(p, q, n_act, hc, g_a, g_b, sa_a, sae_a, A_a, j_a, fc_a, c2_b, K, beta2,
               gamma_s, sa0m, pred, damped, lo, di, up):
    """One step with the adhesive wall: sigma_a(g_b) = c_b (max(K + j_b, 0)/A_b)^(1/2) with
    A_b the step's own end area and j_b by the trapezoid rule; secant iteration on
    sigma_a(g_b) from ``pred``. The profile of the last evaluation (whose wall is returned)
    is left in q. Returns (A_b, j_b, sa_b, sae_b, evaluations)."""
    cap_b = _cap(g_b, sa0m)
    x0 = pred
    if x0 < 0.0:
        x0 = 0.0
    sae = min(x0, cap_b)
    A_b = _advance(p, q, n_act, hc, g_a, g_b, sae_a, sae, damped, lo, di, up)
    j_b = j_a + (g_b - g_a) * beta2 * (fc_a + _f_of(A_b, gamma_s) / c2_b)
    f_new = math.sqrt(c2_b * max(K + j_b, 0.0) / A_b) if A_b > 0.0 else cap_b * 2.0 + 1.0
    r0 = f_new - x0
    nit = 1
    x1 = f_new
    x_last = x0
    while nit < SECANT_MAX:
        if abs(x1 - x_last) <= SECANT_TOL * (1.0 + abs(x1)):
            break
        sae = min(x1, cap_b)
        A_b = _advance(p, q, n_act, hc, g_a, g_b, sae_a, sae, damped, lo, di, up)
        j_b = j_a + (g_b - g_a) * beta2 * (fc_a + _f_of(A_b, gamma_s) / c2_b)
        f_new = (math.sqrt(c2_b * max(K + j_b, 0.0) / A_b) if A_b > 0.0
                 else cap_b * 2.0 + 1.0)
        r1 = f_new - x1
        nit += 1
        x_last = x1
        if abs(r1) <= SECANT_TOL * (1.0 + abs(x1)):
            break
        if r1 != r0:
            x2 = x1 - r1 * (x1 - x0) / (r1 - r0)
        else:
            x2 = f_new
        if x2 < 0.0:
            x2 = 0.5 * x1
        x0 = x1
        r0 = r1
        x1 = x2
    return A_b, j_b, x_last, min(x_last, cap_b), nit
