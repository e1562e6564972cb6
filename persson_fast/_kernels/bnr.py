"""Detachment rate from a Volterra integral equation: no stress grid (``@njit``).

Problem, in diffusion time G (units consistent, scale-free):
    dP/dG = d2P/dsigma2,  P(sigma, 0) = delta(sigma - sigma0),  P(-sigma_a(G), G) = 0,
with sigma_a piecewise linear in G between schedule points and equal to sa[0] before G[0].

Integral equation
-----------------
In t = 2 G (the free Gaussian then has variance t) the stress is a standard Brownian motion
started at x0 = sigma0 and absorbed at the lower boundary b(t) = -sigma_a. Its first-passage
density g(t) solves the second-kind Volterra equation of Buonocore, Nobile & Ricciardi
(Adv. Appl. Prob. 19, 784, 1987)

    g(t) = -2 Psi(b(t), t | x0, 0) + 2 int_0^t g(tau) Psi(b(t), t | b(tau), tau) dtau,
    Psi(b(t), t | y, tau) = 1/2 f(b(t), t | y, tau) [-b'(t) - (y - b(t)) / (t - tau)],

f the Gaussian transition density. For a lower boundary this follows from differentiating
P(X_t < b(t)) = int_0^t g(tau) P(X_t < b(t) | X_tau = b(tau)) dtau in t and adding
-b'(t)/2 times the identity f(b(t), t | x0, 0) = int g(tau) f(b(t), t | b(tau), tau) dtau,
which makes the kernel regular at tau = t (with b = 0 it gives g = x0 f / t, the image
solution). Everything is scaled by y0 = sigma0 + sigma_a(0) and the wall is shifted to
b(0) = 0, so that x0 = 1.

Piecewise-linear walls
----------------------
On a linear piece of the wall the kernel vanishes identically (b(t) - b(tau) = b' (t - tau)),
so g on a piece is an explicit integral over the earlier pieces; with a single linear piece
(images, linearly moving wall) the equation is solved exactly and only the quadrature of
int g dt remains. At a kink t_k of the wall (slope jump) the density is continuous but
g(t) - g(t_k) ~ sqrt(t - t_k), and the kernel seen from just after the kink varies on the
scale t - t_k. At a kink g(t_k) uses the slope of the piece on the left (the limit from the
left, where the kernel is regular).

Discretisation
--------------
The time axis is cut into segments at every schedule point after the start t_s. On each
segment the nodes are uniform in the parameter v of a smooth map of the base coordinate

    phi(t) = ln t - 2 ALPHA sqrt(kappa / t) + 2 c |b'| sqrt(t),

which is geometric in t once t >> kappa (a fixed cost per decade of G), resolves the
exponentially small onset exp(-kappa/t) of g, and adds nodes where the wall sweeps through
the profile (c per profile width travelled). The grid starts at t_s, the latest time before
which the wall has stayed sqrt(2 L_START) profile widths away from the start (the density
integrated over [0, t_s] is below ~1e-16); kappa = L_START t_s. On each side of a kink the map
is graded, t - t_k ~ v^2 (cubic polynomial maps over a zone of phi length ZONE, or over the
whole segment when it is shorter), which turns sqrt(t - t_k) into a smooth function of v.
All integrals (the kernel sums and int g dt) use the trapezoid rule in v (weights dt/dv), a
Nystroem method; as the kernel vanishes on the current piece, every node is explicit:
O(N^2) kernel evaluations in all, none at all for a straight wall.

Order
-----
On smooth maps the trapezoid rule has an error expansion c2 h^2 + c4 h^4 + ... in the
parameter step h (Euler-Maclaurin). Next to a kink the kernel K(t, tau) with t just after and
tau just before t_k is, in the graded parameters, a homogeneous function of (v, w) near the
corner; its trapezoid sums leave an additional c3 h^3 term. Three runs with N, 2N and 4N
nodes give D_N, D_2N, D_4N; R_N = (4 D_2N - D_N) / 3 removes h^2 and
F = (8 R_2N - R_N) / 7 removes h^3. The output F is fourth order: **theoretical order 4**
(measured 4.0 over the level ladder for images, linearly moving walls and kinked walls alike;
4.2 between the two coarsest levels of a strongly kinked wall). The error estimate is
|R_2N - R_N| / 7, the estimated error of R_2N, used as the estimate for F: where h^4 dominates
it is 15/8 of F's error; before the asymptotic regime it may fall slightly below it.
Next to kinks the h^3 and h^4 terms of R can have opposite signs, and at the step where their
parts of R_2N - R_N cancel the estimate falls far below F's error (issue 42: 0.73x and 0.28x
on a two-kink wall at rtol 1e-8 and 1e-7, 1.17 and 1.25 rtol off with status 0). So on a
wall with a graded kink, once this estimate meets rtol, a fourth run with 3N nodes is made
(:func:`_kink_check`): D_N, D_2N, D_3N, D_4N determine I + a h^2 + b h^3 + c h^4, whose I is
fifth order, and |F - I| (F's h^4 term itself, no cancellation of h^3 against h^4: it was
within 0.2 % of F's error there) is taken where it is larger. F stays the output.

Resolution
----------
``level >= 0``: the three runs use N_L, 2 N_L, 4 N_L nodes with N_L = N_0 2^level (each level
doubles every segment's interval count; level 0 is a coarse base with phi step H_LEVEL0).
``level = -1``: the base phi step is H_REF (rtol / 1e-6)^(1/4); when the estimate exceeds
rtol A + ATOL at some schedule point the step is reduced by (SAFETY / excess)^(1/4) and the
three runs are repeated, up to N_MAX nodes in the finest run (then RTOL_NOT_MET, with the best
result reached). On a wall with a graded kink the estimate that decides is the larger of
|R_2N - R_N| / 7 and the fourth run's |F - I| (above; the fourth run costs 9/21 of the three,
and is made only where the first estimate already meets rtol).

Plain samples and thinning
--------------------------
A slope change at a schedule point is treated as a kink (graded as above) unless it is a plain
sample of a smooth wall (:func:`_plain_breaks`): both adjacent pieces at most PLAIN_DLN long in
ln t and its curvature (slope jump over the mean adjacent piece length) within KINK_RATIO of a
neighbour's. A plain sample ends a uniform segment (a node sits on it, no grading, one interval
at least). Its sqrt(t - t_k) terms then leave an h^1.5 error term, so after the first plain
sample the two Richardson steps remove h^1.5 and h^2 instead (measured order 2.5 on 300 samples
of 0.1 + 0.5 sqrt(G); the estimate |R_2N - R_N| / 3 is conservative there, 10-100 times the
error). Sparse samples stay graded and fourth order. When more schedule points remain than the
node cap allows even at the coarsest step, the smooth stretches are thinned (every m-th plain
point, kinks and flat-G points kept), the wall through the kept points is solved, the dropped
points are interpolated (quadratic in G of the detached area and load), and the status is
WALL_THINNED; the error estimate adds |A_m - A_2m| (the same solve with stride 2m) and the
interpolation gap. In the rtol mode the area is never NaN (except NONFINITE / BAD_INPUT, or
when the kinks alone exceed the cap: GRID_CAP); a refinement stopped by the cap or the attempt
limit returns its finest result with RTOL_NOT_MET.

Cost
----
O(N^2) kernel evaluations over the nodes of all pieces after the first (none for a straight
wall, where only the free term is evaluated: O(N)). N is fixed per decade of G for a given
schedule density, but every kink is graded on both sides and a graded segment needs about
ten intervals at rtol = 1e-6 whatever its length, so N (and the cost, quadratically) grows
with the number of schedule points: a few thousand nodes for 30-130 points over five decades.
The stress-grid solver of :mod:`persson_fast._kernels.similarity` is much cheaper for such
schedules; this solver is the grid-free cross-check.

Limitation (small areas)
------------------------
A = 1 - int g dt. Where A is small (sigma0 << sqrt(G)) this difference of two numbers close to
1 keeps only an absolute accuracy of about 1e-16 .. 1e-15, so the relative error of A grows like
1e-16 / A: for A ~ 1e-11 it is ~1e-5. The error estimate always includes the absolute rounding
floor ROUND_FLOOR, so for tiny A the estimate says that rtol is not met in relative terms (the
contract |A - A_exact| <= rtol A + 1e-12 still holds). The grid solver integrates P itself and
keeps relative accuracy there.

Wall jumps (repeated G with different sa) cannot be represented: BAD_INPUT.
"""
from __future__ import annotations

import math

import numpy as np

from .._jit import njit_serial, njit_sweeps, prange
from . import status as st
from .schedule import fill_state
from .signature import no_upper_wall

# --- constants of the scheme (dimensionless, y0 = 1, t = 2 G / y0^2) -----------------------
ALPHA = 0.3           # weight of the onset term of phi (onset length 2 ALPHA sqrt(L_START))
L_START = 38.0        # start when the wall is sqrt(2 L_START) widths away: exp(-38) = 3e-17
C_APPROACH = 1.0      # phi units per profile width travelled by a wall moving into the profile
C_RECEDE = 0.25       # ... by a wall moving away from it
ZONE = 0.5            # phi length of the graded zone next to a kink
H_REF = 0.05          # base step in phi at rtol = 1e-6 (the finest of three runs has H_REF / 4)
H_LEVEL0 = 0.5        # base step of level 0 of the explicit ladder
H_MAX = 0.8           # coarsest base step allowed
N_MIN_SEG = 1         # fewest intervals per segment at the base resolution
N_MIN_GRADED = 2      # fewest intervals per graded segment at the base resolution
N_MAX = 20000         # node cap of the finest run
MAX_ATTEMPTS = 6      # resolutions tried in the rtol mode
SAFETY = 0.5          # a refinement aims at this fraction of the tolerance
ATOL = 1e-12          # absolute floor of the area tolerance in the rtol mode
ROUND_FLOOR = 2e-15   # absolute rounding floor of 1 - int g (and of the truncation at t_s)
MERGE_TOL = 1e-13     # collinear schedule points (relative) belong to one linear piece
NEWTON_ITERS = 60
# plain samples: a slope change at a schedule point is a sample of a smooth wall, not a kink,
# when the neighbouring pieces are short (at most PLAIN_DLN in ln t) and its curvature
# (slope jump over the mean adjacent piece length) is within KINK_RATIO of a neighbour's
PLAIN_DLN = 0.1
KINK_RATIO = 4.0
PLAIN_EXP = 1.5       # leading error exponent of a grid with plain samples (sqrt(t - t_k) terms)

# map types of a segment: 0 uniform, 1 graded at the left end, 2 graded at the right end,
# 3 graded at both ends
MAP_UNIFORM = 0
MAP_LEFT = 1
MAP_RIGHT = 2
MAP_BOTH = 3
# largest derivative S'(v) of each map (node density relative to uniform)
DENS_LEFT = 4.0 / 3.0  # S = 2 v^2 - v^3, max S' at v = 2/3
DENS_BOTH = 1.5        # S = 3 v^2 - 2 v^3, max S' at v = 1/2


@njit_serial
def _map_s(kind, v):
    """Segment map S(v) on [0, 1] and its derivative: (S, S').

    Graded ends behave as S ~ v^2 (t - t_k ~ v^2), so that sqrt(t - t_k) is smooth in v.
    """
    if kind == MAP_LEFT:
        return v * v * (2.0 - v), v * (4.0 - 3.0 * v)
    if kind == MAP_RIGHT:
        w = 1.0 - v
        return 1.0 - w * w * (2.0 - w), w * (4.0 - 3.0 * w)
    if kind == MAP_BOTH:
        return v * v * (3.0 - 2.0 * v), 6.0 * v * (1.0 - v)
    return v, 1.0


@njit_serial
def _phi(t, sk, cs):
    """Base coordinate phi(t) = ln t - 2 ALPHA sk / sqrt(t) + 2 cs sqrt(t) (sk = sqrt(kappa))."""
    r = math.sqrt(t)
    return math.log(t) - 2.0 * ALPHA * sk / r + 2.0 * cs * r


@njit_serial
def _dphi(t, sk, cs):
    """d phi / dt > 0."""
    r = math.sqrt(t)
    return 1.0 / t + ALPHA * sk / (t * r) + cs / r


@njit_serial
def _phi_inverse(target, t_lo, t_hi, sk, cs):
    """t in [t_lo, t_hi] with phi(t) = target: Newton in ln t, safeguarded by bisection."""
    x_lo = math.log(t_lo)
    x_hi = math.log(t_hi)
    f_lo = _phi(t_lo, sk, cs) - target
    if f_lo >= 0.0:
        return t_lo
    if _phi(t_hi, sk, cs) - target <= 0.0:
        return t_hi
    x = 0.5 * (x_lo + x_hi)
    for _ in range(NEWTON_ITERS):
        t = math.exp(x)
        f = _phi(t, sk, cs) - target
        if f > 0.0:
            x_hi = x
        else:
            x_lo = x
        dfx = _dphi(t, sk, cs) * t
        x_new = x - f / dfx
        if not (x_lo < x_new < x_hi):
            x_new = 0.5 * (x_lo + x_hi)
        if abs(x_new - x) <= 1e-15 * (1.0 + abs(x)):
            x = x_new
            break
        x = x_new
    return math.exp(x)


@njit_serial
def _wall_far_until(tp, bp, sp, n_pc, t, c):
    """True when y(t') = 1 - b(t') >= c sqrt(t') for every 0 < t' <= t (wall far from the start).

    y is linear on each piece and c sqrt(t') concave, so y - c sqrt(t') is convex on a piece:
    it is checked at the piece ends and at its interior minimum.
    """
    for i in range(n_pc):
        a = tp[i]
        if a >= t:
            break
        e = tp[i + 1] if i + 1 < n_pc else t
        if e > t:
            e = t
        ya = 1.0 - bp[i]
        slope_y = -sp[i]
        ye = ya + slope_y * (e - a)
        if ye < c * math.sqrt(e):
            return False
        if a > 0.0 and ya < c * math.sqrt(a):
            return False
        if slope_y > 0.0:
            ts = (c / (2.0 * slope_y)) ** 2
            if a < ts < e:
                if ya + slope_y * (ts - a) < c * math.sqrt(ts):
                    return False
    return True


@njit_serial
def _wall_at(tp, bp, sp, n_pc, t):
    """(b(t), piece index) of the piecewise-linear wall, the piece with tp[i] <= t < tp[i+1]."""
    i = n_pc - 1
    while i > 0 and tp[i] > t:
        i -= 1
    return bp[i] + sp[i] * (t - tp[i]), i


@njit_serial
def _count_nodes(seg_n, n_seg, mult):
    """Number of intervals of a run with ``mult`` times the base counts."""
    n = 0
    for i in range(n_seg):
        n += seg_n[i] * mult
    return n


@njit_serial
def _solve_grid(mult, seg_ta, seg_tb, seg_pa, seg_pb, seg_kind, seg_n, seg_cs, seg_piece,
                n_seg, sk, tp, bp, sp, D_out, E_out):
    """Build the nodes at ``mult`` times the base counts, solve the equation, integrate.

    Writes D_out[k] = int_{t_s}^{t_k} g dt and E_out[k] = int (-b) g dt at the segment ends
    (indexed by segment); returns (status, number of nodes, kernel evaluations).
    """
    n_int = _count_nodes(seg_n, n_seg, mult)
    nn = n_int + 1
    t = np.empty(nn)
    b = np.empty(nn)
    hl = np.zeros(nn)
    hr = np.zeros(nn)
    pl = np.empty(nn, dtype=np.int64)    # piece of (t_{j-1}, t_j]
    pr = np.empty(nn, dtype=np.int64)    # piece of [t_j, t_{j+1})
    seg_last = np.empty(n_seg, dtype=np.int64)
    j = 0
    for s in range(n_seg):
        n = seg_n[s] * mult
        ta = seg_ta[s]
        tb = seg_tb[s]
        pa = seg_pa[s]
        ell = seg_pb[s] - pa
        cs = seg_cs[s]
        kind = seg_kind[s]
        piece = seg_piece[s]
        dv = 1.0 / n
        _, dsv = _map_s(kind, 0.0)
        h0 = 0.5 * dv * ell * dsv / _dphi(ta, sk, cs)
        if s == 0:
            t[0] = ta
            b[0] = bp[piece] + sp[piece] * (ta - tp[piece])
            hl[0] = 0.0
            pl[0] = piece
            j = 1
        # the first node of this segment is the last one made (shared end node)
        hr[j - 1] = h0
        pr[j - 1] = piece
        t_prev = ta
        for i in range(1, n + 1):
            v = i * dv
            sv, dsv = _map_s(kind, v)
            if i == n:
                tt = tb
            else:
                tt = _phi_inverse(pa + ell * sv, t_prev, tb, sk, cs)
            t_prev = tt
            hh = 0.5 * dv * ell * dsv / _dphi(tt, sk, cs)
            t[j] = tt
            b[j] = bp[piece] + sp[piece] * (tt - tp[piece])
            hl[j] = hh
            pl[j] = piece
            pr[j] = piece
            hr[j] = hh if i < n else 0.0
            j += 1
        seg_last[s] = j - 1
    # first node index of each node's left piece (the kernel vanishes from there on; the
    # piece containing t_s starts before the grid, so its nodes have no kernel sum at all)
    pf = np.empty(nn, dtype=np.int64)
    first_of_piece = 0
    cur_piece = pl[0]
    pf[0] = 0
    for k in range(1, nn):
        if pl[k] != cur_piece:
            cur_piece = pl[k]
            first_of_piece = k - 1
        pf[k] = first_of_piece
    g = np.empty(nn)
    W = np.empty(nn)
    for k in range(nn):
        W[k] = hl[k] + hr[k]
    inv_sqrt_2pi = 1.0 / math.sqrt(2.0 * math.pi)
    n_eval = 0
    for n in range(nn):
        tn = t[n]
        bn = b[n]
        pc = pl[n]
        sn = sp[pc]
        yn = 1.0 - bn
        # free term -2 Psi(b(t), t | x0 = 1, 0)
        f0 = math.exp(-0.5 * yn * yn / tn) * inv_sqrt_2pi / math.sqrt(tn)
        gn = f0 * (sn + yn / tn)
        n_eval += 1
        m = pf[n]
        if m > 0:
            tk = tp[pc]
            bk = bp[pc]
            acc = 0.0
            for jj in range(m):
                tj = t[jj]
                d = tn - tj
                pj = pr[jj]
                dk = tk - tj
                if pj == pc - 1:
                    sj = sp[pj]
                    num = (sj - sn) * dk
                    db = sn * (tn - tk) + sj * dk
                else:
                    num = (bk - b[jj]) - sn * dk
                    db = bn - b[jj]
                br = num / d
                f = math.exp(-0.5 * db * db / d) * inv_sqrt_2pi / math.sqrt(d)
                acc += W[jj] * g[jj] * f * br
            gn += acc
            n_eval += m
        if not math.isfinite(gn):
            return st.NONFINITE, nn, n_eval
        g[n] = gn
    # cumulative integrals at the segment ends (compensated sums)
    dsum = 0.0
    dc = 0.0
    esum = 0.0
    ec = 0.0
    s = 0
    for k in range(1, nn):
        inc = hr[k - 1] * g[k - 1] + hl[k] * g[k]
        yk = inc - dc
        tt = dsum + yk
        dc = (tt - dsum) - yk
        dsum = tt
        inc = -(hr[k - 1] * g[k - 1] * b[k - 1] + hl[k] * g[k] * b[k])
        yk = inc - ec
        tt = esum + yk
        ec = (tt - esum) - yk
        esum = tt
        while s < n_seg and seg_last[s] == k:
            D_out[s] = dsum
            E_out[s] = esum
            s += 1
    return st.OK, nn, n_eval


@njit_serial
def _segment_counts(seg_ld, seg_nmin, n_seg, h_u, seg_n):
    """Base intervals per segment: the largest step in phi is h_u (at least the minimum)."""
    for q in range(n_seg):
        n = int(math.ceil(seg_ld[q] / h_u - 1e-9))
        seg_n[q] = n if n > seg_nmin[q] else seg_nmin[q]


@njit_serial
def _plain_breaks(tp, sp, n_pc, t_end, plain):
    """Mark the piece starts tp[i] (i >= 1) that are plain samples of a smooth wall: plain[i].

    A slope jump ds_i = sp[i] - sp[i-1] at a sample of a smooth wall shrinks with the local
    spacing: its curvature ds_i / (mean adjacent piece length) agrees with its neighbours'. A kink
    keeps a finite jump however dense the samples, so its curvature stands out (more than
    KINK_RATIO times both neighbours'). Only densely sampled stretches (adjacent pieces at most
    PLAIN_DLN long in ln t) are candidates: a sparse sample is graded like a kink (that is cheap
    and keeps the fourth order there). Returns the number of plain samples.
    """
    curv = np.zeros(n_pc + 1)
    dense = np.zeros(n_pc + 1, dtype=np.bool_)
    for i in range(n_pc + 1):
        plain[i] = False
    for i in range(1, n_pc):
        t_l = tp[i - 1]
        t_m = tp[i]
        t_r = tp[i + 1] if i + 1 < n_pc else t_end
        if t_l > 0.0 and t_r > t_m:
            dense[i] = (math.log(t_m / t_l) <= PLAIN_DLN and math.log(t_r / t_m) <= PLAIN_DLN)
        curv[i] = abs(sp[i] - sp[i - 1]) / (0.5 * (t_r - t_l))
    n_plain = 0
    for i in range(1, n_pc):
        if not dense[i]:
            continue
        ref = 0.0
        if i > 1 and curv[i - 1] > ref:
            ref = curv[i - 1]
        if i + 1 < n_pc and curv[i + 1] > ref:
            ref = curv[i + 1]
        if curv[i] <= KINK_RATIO * ref:
            plain[i] = True
            n_plain += 1
    return n_plain


@njit_serial
def _triple(mult, seg_ta, seg_tb, seg_pa, seg_pb, seg_kind, seg_n, seg_cs, seg_piece, n_seg,
            sk, tp, bp, sp, f_d, f_e, err, scratch, counts, seg_plain):
    """Runs at mult, 2 mult and 4 mult times the base counts and two Richardson steps.

    With D_h the trapezoid result at step h, R_h = (4 D_{h/2} - D_h) / 3 removes h^2 and
    F = (8 R_{h/2} - R_h) / 7 removes h^3 (present only next to wall kinks); F is returned in
    f_d (int g dt) and f_e (int -b g dt), err = |R_{h/2} - R_h| / 7 the estimated error of
    R_{h/2}, a bound for F's. counts: [0] nodes of the finest run, [1] kernel evaluations.
    Returns a status (GRID_CAP when the finest run would exceed N_MAX nodes).
    """
    n_base = _count_nodes(seg_n, n_seg, 1)
    counts[0] = 0
    counts[1] = 0
    if 4 * n_base * mult + 1 > N_MAX:
        return st.GRID_CAP
    d0 = scratch[0]
    e0 = scratch[1]
    d1 = scratch[2]
    e1 = scratch[3]
    d2 = scratch[4]
    e2 = scratch[5]
    s0, _, w0 = _solve_grid(mult, seg_ta, seg_tb, seg_pa, seg_pb, seg_kind, seg_n, seg_cs,
                             seg_piece, n_seg, sk, tp, bp, sp, d0, e0)
    counts[1] += w0
    if s0 != st.OK:
        return s0
    s1, _, w1 = _solve_grid(2 * mult, seg_ta, seg_tb, seg_pa, seg_pb, seg_kind, seg_n, seg_cs,
                             seg_piece, n_seg, sk, tp, bp, sp, d1, e1)
    counts[1] += w1
    if s1 != st.OK:
        return s1
    s2, n2, w2 = _solve_grid(4 * mult, seg_ta, seg_tb, seg_pa, seg_pb, seg_kind, seg_n, seg_cs,
                             seg_piece, n_seg, sk, tp, bp, sp, d2, e2)
    counts[1] += w2
    counts[0] = n2
    if s2 != st.OK:
        return s2
    r_plain = 2.0 ** PLAIN_EXP
    for q in range(n_seg):
        if seg_plain[q]:
            # plain samples before: D = I + a h^1.5 + b h^2 + ...; remove h^1.5, then h^2
            ra = (r_plain * d1[q] - d0[q]) / (r_plain - 1.0)
            rb = (r_plain * d2[q] - d1[q]) / (r_plain - 1.0)
            f_d[q] = (4.0 * rb - ra) / 3.0
            err[q] = abs(rb - ra) / 3.0
            ra = (r_plain * e1[q] - e0[q]) / (r_plain - 1.0)
            rb = (r_plain * e2[q] - e1[q]) / (r_plain - 1.0)
            f_e[q] = (4.0 * rb - ra) / 3.0
            continue
        ra = (4.0 * d1[q] - d0[q]) / 3.0
        rb = (4.0 * d2[q] - d1[q]) / 3.0
        f_d[q] = (8.0 * rb - ra) / 7.0
        err[q] = abs(rb - ra) / 7.0
        ra = (4.0 * e1[q] - e0[q]) / 3.0
        rb = (4.0 * e2[q] - e1[q]) / 3.0
        f_e[q] = (8.0 * rb - ra) / 7.0
    return st.OK


@njit_serial
def _kink_check(mult, seg_ta, seg_tb, seg_pa, seg_pb, seg_kind, seg_n, seg_cs, seg_piece,
                n_seg, sk, tp, bp, sp, f_d, err, scratch, d3, e3, seg_plain):
    """A fourth run at 3 ``mult`` times the base counts after :func:`_triple` (whose runs at
    mult, 2 mult, 4 mult are in ``scratch``): raise err[q] to |F - I| where that is larger.

    With h the step of the first run, D_N, D_2N, D_3N, D_4N (steps h, h/2, h/3, h/4) fix
    I + a h^2 + b h^3 + c h^4: I = (256 D_4N - 243 D_3N + 48 D_2N - D_N) / 60, fifth order.
    F = (8 R_2N - R_N) / 7 keeps the h^4 term, so |F - I| is F's error up to I's own h^5 term;
    it cannot vanish by a cancellation of the h^3 against the h^4 term as |R_2N - R_N| can.
    Segments after a plain sample (error exponents 1.5 and 2, not 2, 3, 4) keep their err.
    Returns (status, kernel evaluations).
    """
    s, _, w = _solve_grid(3 * mult, seg_ta, seg_tb, seg_pa, seg_pb, seg_kind, seg_n, seg_cs,
                          seg_piece, n_seg, sk, tp, bp, sp, d3, e3)
    if s != st.OK:
        return s, w
    for q in range(n_seg):
        if seg_plain[q]:
            continue
        fifth = (256.0 * scratch[4, q] - 243.0 * d3[q] + 48.0 * scratch[2, q]
                 - scratch[0, q]) / 60.0
        e = abs(f_d[q] - fifth)
        if e > err[q]:
            err[q] = e
    return st.OK, w


NOTHING_FIT = -1      # internal: not even the coarsest triple fits under N_MAX (rtol mode)


@njit_serial
def _solve_core(G, sa, sigma0, rtol, level, out_area, out_load, out_det_area, out_det_load,
                out_error, counts):
    """The BNR solve of one pressure on the wall as given (every sample kept).

    Arguments and outputs as :func:`solve_bnr_one`, which wraps this with the thinning of
    walls that have more points than the node cap allows.

    Returns
    -------
    status : int
        :mod:`persson_fast._kernels.status` code: OK, BAD_INPUT (bad arrays or a wall jump),
        NONFINITE, GRID_CAP (the node cap stopped the refinement; accuracy not guaranteed).

    Notes
    -----
    Buonocore, Nobile & Ricciardi, Adv. Appl. Prob. 19, 784 (1987). Scale-free: units only
    need to be consistent. By construction A + detached = 1 and load = sigma0 + detached load
    hold to rounding.
    """
    nt = G.shape[0]
    if counts.shape[0] < 3:
        return st.BAD_INPUT
    counts[0] = 0
    counts[1] = 0
    counts[2] = 0
    if (nt < 1 or sa.shape[0] != nt or out_area.shape[0] != nt or out_load.shape[0] != nt
            or out_det_area.shape[0] != nt or out_det_load.shape[0] != nt
            or out_error.shape[0] != nt):
        return st.BAD_INPUT
    if not (math.isfinite(sigma0) and level >= -1):
        return st.BAD_INPUT
    if level == -1 and not (rtol > 0.0 and math.isfinite(rtol)):
        return st.BAD_INPUT
    for k in range(nt):
        if not (math.isfinite(G[k]) and math.isfinite(sa[k])):
            return st.BAD_INPUT
        if k == 0:
            if G[0] < 0.0:
                return st.BAD_INPUT
        else:
            if G[k] < G[k - 1]:
                return st.BAD_INPUT
            if G[k] == G[k - 1] and sa[k] != sa[k - 1]:
                return st.BAD_INPUT      # a wall jump: not representable here
    sa0 = sa[0]
    y0 = sigma0 + sa0
    if y0 <= 0.0:
        # separated: the start lies on or below the wall
        fill_state(np.int64(0), nt, 0.0, 0.0, 1.0, -sigma0, 0.0, out_area, out_load, out_det_area,
              out_det_load, out_error)
        return st.OK
    # --- the wall in scaled units: b(t) = -(sa(G) - sa0) / y0, t = 2 G / y0^2 -------------
    tk_s = np.empty(nt + 1)
    bk_s = np.empty(nt + 1)
    tk_s[0] = 0.0
    bk_s[0] = 0.0
    m_pts = 1
    for k in range(nt):
        tt = 2.0 * (G[k] / y0) / y0
        bb = -(sa[k] - sa0) / y0
        if tt > tk_s[m_pts - 1]:
            tk_s[m_pts] = tt
            bk_s[m_pts] = bb
            m_pts += 1
    # linear pieces: maximal collinear runs (a last piece extends beyond the schedule)
    tp = np.empty(m_pts + 1)
    bp = np.empty(m_pts + 1)
    sp = np.empty(m_pts + 1)
    n_pc = 0
    i = 0
    while i < m_pts - 1:
        slope = (bk_s[i + 1] - bk_s[i]) / (tk_s[i + 1] - tk_s[i])
        tp[n_pc] = tk_s[i]
        bp[n_pc] = bk_s[i]
        sp[n_pc] = slope
        n_pc += 1
        k = i + 1
        while k + 1 < m_pts:
            pred = bk_s[i] + slope * (tk_s[k + 1] - tk_s[i])
            if abs(bk_s[k + 1] - pred) > MERGE_TOL * (1.0 + abs(pred)):
                break
            k += 1
        i = k
    if n_pc == 0:
        tp[0] = 0.0
        bp[0] = 0.0
        sp[0] = 0.0
        n_pc = 1
    t_end = tk_s[m_pts - 1]
    c_far = math.sqrt(2.0 * L_START)
    # --- outputs while the wall is still far: the free state (A = 1 to ~1e-17) --------------
    if t_end <= 0.0 or _wall_far_until(tp, bp, sp, n_pc, t_end, c_far):
        fill_state(np.int64(0), nt, 1.0, sigma0, 0.0, 0.0, 0.0, out_area, out_load, out_det_area,
              out_det_load, out_error)
        counts[0] = 0
        return st.OK
    # t_s: bisection in ln t (the schedule may span hundreds of decades of G)
    x_hi = math.log(t_end)
    x_lo = x_hi - 1400.0
    if x_lo < -740.0:
        x_lo = -740.0
    if not _wall_far_until(tp, bp, sp, n_pc, math.exp(x_lo), c_far):
        return st.BAD_INPUT      # a wall faster than any resolvable start
    for _ in range(100):
        mid = 0.5 * (x_lo + x_hi)
        if _wall_far_until(tp, bp, sp, n_pc, math.exp(mid), c_far):
            x_lo = mid
        else:
            x_hi = mid
    t_s = math.exp(x_lo)
    sk = math.sqrt(L_START * t_s)
    plain_pc = np.zeros(n_pc + 1, dtype=np.bool_)
    _plain_breaks(tp, sp, n_pc, t_end, plain_pc)
    # --- segments: between t_s and the schedule points after it; grading at kinks ---------
    max_seg = 3 * (m_pts + 1)
    seg_ta = np.empty(max_seg)
    seg_tb = np.empty(max_seg)
    seg_pa = np.empty(max_seg)
    seg_pb = np.empty(max_seg)
    seg_kind = np.empty(max_seg, dtype=np.int64)
    seg_n = np.empty(max_seg, dtype=np.int64)
    seg_ld = np.empty(max_seg)                      # phi length times the largest density
    seg_nmin = np.empty(max_seg, dtype=np.int64)
    seg_cs = np.empty(max_seg)
    seg_piece = np.empty(max_seg, dtype=np.int64)
    seg_sched = np.empty(max_seg, dtype=np.int64)   # index into tk_s of the end, or -1
    seg_plain = np.zeros(max_seg, dtype=np.bool_)   # a plain sample at or before the start
    seen_plain = False
    n_seg = 0
    ta = t_s
    k_first = 1
    while k_first < m_pts and tk_s[k_first] <= t_s:
        k_first += 1
    for k in range(k_first, m_pts):
        tb = tk_s[k]
        _, piece = _wall_at(tp, bp, sp, n_pc, 0.5 * (ta + tb))
        slope = sp[piece]
        # kinks: a piece starts at ta (> t_s) / a new piece starts at tb (< t_end)
        kl = ta > t_s and tp[piece] == ta and piece > 0 and not plain_pc[piece]
        if ta > t_s and tp[piece] == ta and piece > 0 and plain_pc[piece]:
            seen_plain = True
        kr = False
        if piece + 1 < n_pc and tp[piece + 1] == tb and k < m_pts - 1:
            kr = not plain_pc[piece + 1]
        if slope > 0.0:
            cs = C_APPROACH * slope
        else:
            cs = -C_RECEDE * slope
        pa = _phi(ta, sk, cs)
        pb = _phi(tb, sk, cs)
        ell = pb - pa
        if (kl or kr) and ell > 2.0 * ZONE:
            # graded zones of length ZONE at the kinked ends, a uniform middle
            cuts = np.empty(4)
            kinds = np.empty(3, dtype=np.int64)
            nc = 0
            cuts[0] = pa
            if kl:
                cuts[1] = pa + ZONE
                kinds[0] = MAP_LEFT
                nc = 1
            kinds[nc] = MAP_UNIFORM
            if kr:
                cuts[nc + 1] = pb - ZONE
                kinds[nc + 1] = MAP_RIGHT
                cuts[nc + 2] = pb
                nc += 2
            else:
                cuts[nc + 1] = pb
                nc += 1
            for q in range(nc):
                seg_pa[n_seg] = cuts[q]
                seg_pb[n_seg] = cuts[q + 1]
                seg_ta[n_seg] = ta if q == 0 else _phi_inverse(cuts[q], ta, tb, sk, cs)
                seg_tb[n_seg] = tb if q == nc - 1 else _phi_inverse(cuts[q + 1], ta, tb, sk, cs)
                seg_kind[n_seg] = kinds[q]
                seg_cs[n_seg] = cs
                seg_piece[n_seg] = piece
                seg_sched[n_seg] = k if q == nc - 1 else -1
                seg_plain[n_seg] = seen_plain
                dens = 1.0 if kinds[q] == MAP_UNIFORM else DENS_LEFT
                nmin = N_MIN_SEG if kinds[q] == MAP_UNIFORM else N_MIN_GRADED
                seg_ld[n_seg] = (cuts[q + 1] - cuts[q]) * dens
                seg_nmin[n_seg] = nmin
                n_seg += 1
        else:
            if kl and kr:
                kind = MAP_BOTH
                dens = DENS_BOTH
            elif kl:
                kind = MAP_LEFT
                dens = DENS_LEFT
            elif kr:
                kind = MAP_RIGHT
                dens = DENS_LEFT
            else:
                kind = MAP_UNIFORM
                dens = 1.0
            nmin = N_MIN_SEG if kind == MAP_UNIFORM else N_MIN_GRADED
            seg_ta[n_seg] = ta
            seg_tb[n_seg] = tb
            seg_pa[n_seg] = pa
            seg_pb[n_seg] = pb
            seg_kind[n_seg] = kind
            seg_cs[n_seg] = cs
            seg_piece[n_seg] = piece
            seg_sched[n_seg] = k
            seg_plain[n_seg] = seen_plain
            seg_ld[n_seg] = ell * dens
            seg_nmin[n_seg] = nmin
            n_seg += 1
        ta = tb
    if n_seg == 0:
        # every schedule point lies before the start: the free state throughout
        fill_state(np.int64(0), nt, 1.0, sigma0, 0.0, 0.0, ROUND_FLOOR, out_area, out_load, out_det_area,
              out_det_load, out_error)
        return st.OK
    # --- three runs (N, 2N, 4N) and two Richardson steps ----------------------------------
    f_d = np.empty(n_seg)
    f_e = np.empty(n_seg)
    err = np.empty(n_seg)
    t_d = np.empty(n_seg)
    t_e = np.empty(n_seg)
    t_err = np.empty(n_seg)
    scratch = np.empty((6, n_seg))
    if level >= 0:
        _segment_counts(seg_ld, seg_nmin, n_seg, H_LEVEL0, seg_n)
        mult = 1 << min(level, 30)
        status = _triple(mult, seg_ta, seg_tb, seg_pa, seg_pb, seg_kind, seg_n, seg_cs,
                         seg_piece, n_seg, sk, tp, bp, sp, f_d, f_e, err, scratch, counts,
                         seg_plain)
        if status != st.OK:
            nan = math.nan
            fill_state(np.int64(0), nt, nan, nan, nan, nan, nan, out_area, out_load, out_det_area,
                  out_det_load, out_error)
            return status
    else:
        h_u = H_REF * (rtol / 1e-6) ** 0.25
        if h_u > H_MAX:
            h_u = H_MAX
        # a tolerance finer than the node cap allows: start from the finest base that fits
        # (the refinement below then reports GRID_CAP unless the estimate already meets rtol)
        _segment_counts(seg_ld, seg_nmin, n_seg, h_u, seg_n)
        while 4 * _count_nodes(seg_n, n_seg, 1) + 1 > N_MAX and h_u < H_MAX:
            h_u *= 1.25
            _segment_counts(seg_ld, seg_nmin, n_seg, h_u, seg_n)
        have = False
        status = st.OK
        work = 0
        n_final = 0
        # a graded kink: its h^3 term can cancel the h^4 term in the estimate (_kink_check)
        kinked = False
        for q in range(n_seg):
            if seg_kind[q] != MAP_UNIFORM:
                kinked = True
        d3 = np.empty(n_seg)
        e3 = np.empty(n_seg)
        for attempt in range(MAX_ATTEMPTS):
            _segment_counts(seg_ld, seg_nmin, n_seg, h_u, seg_n)
            s3 = _triple(1, seg_ta, seg_tb, seg_pa, seg_pb, seg_kind, seg_n, seg_cs,
                         seg_piece, n_seg, sk, tp, bp, sp, t_d, t_e, t_err, scratch, counts,
                         seg_plain)
            work += counts[1]
            if s3 == st.GRID_CAP:
                status = st.RTOL_NOT_MET if have else NOTHING_FIT
                break
            if s3 != st.OK:
                status = s3
                have = False
                break
            for q in range(n_seg):
                f_d[q] = t_d[q]
                f_e[q] = t_e[q]
                err[q] = t_err[q]
            have = True
            n_final = counts[0]
            worst = 0.0
            for q in range(n_seg):
                r = err[q] / (rtol * abs(1.0 - f_d[q]) + ATOL)
                if r > worst:
                    worst = r
            if worst <= 1.0 and kinked:
                # the estimate meets rtol: check it against the fifth-order fit of four runs
                s4, w4 = _kink_check(1, seg_ta, seg_tb, seg_pa, seg_pb, seg_kind, seg_n,
                                     seg_cs, seg_piece, n_seg, sk, tp, bp, sp, f_d, err,
                                     scratch, d3, e3, seg_plain)
                work += w4
                if s4 != st.OK:
                    status = s4
                    have = False
                    break
                for q in range(n_seg):
                    r = err[q] / (rtol * abs(1.0 - f_d[q]) + ATOL)
                    if r > worst:
                        worst = r
            if worst <= 1.0:
                break
            if attempt == MAX_ATTEMPTS - 1:
                status = st.RTOL_NOT_MET
                break
            # error ~ h^4: aim at SAFETY of the tolerance, at least 15 % finer
            shrink = (SAFETY / worst) ** 0.25
            if shrink > 0.85:
                shrink = 0.85
            if shrink < 0.25:
                shrink = 0.25
            h_u *= shrink
        counts[0] = n_final
        counts[1] = work
        if not have:
            nan = math.nan
            fill_state(np.int64(0), nt, nan, nan, nan, nan, nan, out_area, out_load, out_det_area,
                  out_det_load, out_error)
            return status if status != st.OK else NOTHING_FIT
    counts[2] = counts[1]
    # --- outputs --------------------------------------------------------------------------
    q = 0
    for k in range(nt):
        tt = 2.0 * (G[k] / y0) / y0
        if tt <= t_s:
            out_area[k] = 1.0
            out_det_area[k] = 0.0
            out_load[k] = sigma0
            out_det_load[k] = 0.0
            out_error[k] = ROUND_FLOOR
            continue
        while q < n_seg - 1 and seg_tb[q] < tt:
            q += 1
        while seg_sched[q] < 0:
            q += 1
        d = f_d[q]
        a = 1.0 - d
        if a > 1.0:
            a = 1.0
        elif a < 0.0:
            a = 0.0
        d = 1.0 - a
        dl = sa0 * d + y0 * f_e[q]
        out_area[k] = a
        out_det_area[k] = d
        out_det_load[k] = dl
        out_load[k] = sigma0 + dl
        out_error[k] = err[q] + ROUND_FLOOR
        if not (math.isfinite(a) and math.isfinite(dl)):
            status = st.NONFINITE
    return status



@njit_serial
def _thin_mask(G, sa, stride, keep):
    """Mark the schedule points a thinned wall keeps: keep[k]; returns how many.

    Kept: the ends, every ``stride``-th point, both points of a repeated or flat-G interval,
    and every point that is not a plain sample of a smooth stretch (the rule of
    :func:`_plain_breaks` applied to the raw samples, which it is invariant to: kinks and
    sparse points stay, so only densely sampled smooth stretches are thinned).
    """
    nt = G.shape[0]
    curv = np.zeros(nt)
    for k in range(1, nt - 1):
        dl = G[k] - G[k - 1]
        dr = G[k + 1] - G[k]
        if dl > 0.0 and dr > 0.0:
            curv[k] = abs((sa[k + 1] - sa[k]) / dr - (sa[k] - sa[k - 1]) / dl) / (0.5 * (dl + dr))
    n_keep = 0
    for k in range(nt):
        keep[k] = True
        if 0 < k < nt - 1 and k % stride != 0:
            dl = G[k] - G[k - 1]
            dr = G[k + 1] - G[k]
            if (dl > 0.0 and dr > 0.0 and G[k - 1] > 0.0 and math.log(G[k] / G[k - 1]) <= PLAIN_DLN
                    and math.log(G[k + 1] / G[k]) <= PLAIN_DLN):
                ref = 0.0
                if k > 1 and curv[k - 1] > ref:
                    ref = curv[k - 1]
                if k + 2 < nt and curv[k + 1] > ref:
                    ref = curv[k + 1]
                if curv[k] <= KINK_RATIO * ref:
                    keep[k] = False
        if keep[k]:
            n_keep += 1
    return n_keep


@njit_serial
def _solve_subset(G, sa, keep, n_keep, sigma0, rtol, level, counts):
    """_solve_core on the kept points; returns (status, indices, area, load, det, det_load, err)."""
    idx = np.empty(n_keep, dtype=np.int64)
    j = 0
    for k in range(G.shape[0]):
        if keep[k]:
            idx[j] = k
            j += 1
    g_sub = np.empty(n_keep)
    sa_sub = np.empty(n_keep)
    for j in range(n_keep):
        g_sub[j] = G[idx[j]]
        sa_sub[j] = sa[idx[j]]
    a = np.empty(n_keep)
    ld = np.empty(n_keep)
    d = np.empty(n_keep)
    dl = np.empty(n_keep)
    e = np.empty(n_keep)
    status = _solve_core(g_sub, sa_sub, sigma0, rtol, level, a, ld, d, dl, e, counts)
    return status, idx, a, ld, d, dl, e


@njit_serial
def solve_bnr_one(G, sa, sigma0, rtol, level, out_area, out_load, out_det_area, out_det_load,
                  out_error, counts):
    """Contact area and load bookkeeping of one nominal pressure from the BNR integral equation.

    Parameters
    ----------
    G : ndarray, shape (n_t,)
        Non-decreasing diffusion times, G[0] >= 0. Repeated values are allowed only with equal
        sa (a wall jump is BAD_INPUT). [stress^2]
    sa : ndarray, shape (n_t,)
        Detachment stress sigma_a at those times (wall at -sa), linear in G in between,
        sa[0] before G[0]. [stress]
    sigma0 : float
        Nominal stress (compressive > 0), same unit as sqrt(G). [stress]
    rtol : float
        Target relative accuracy of the area (used when ``level = -1``). [-]
    level : int
        -1: resolution from rtol, refined adaptively; L >= 0: the fixed runs N_L, 2 N_L,
        4 N_L with N_L = N_0 2^L (each level doubles the nodes; level 0 a coarse base). [-]
    out_area, out_load, out_det_area, out_det_load, out_error : ndarray, shape (n_t,)
        Written in place: A/A0, load int sigma P dsigma, detached area 1 - A, detached load
        int sigma_a g dG, and an error estimate of the area (see the module notes).
    counts : ndarray of int64, shape (>= 3,)
        Written in place: [0] nodes of the finest run, [1] kernel (Psi) evaluations of all
        runs together (free term included: one per node), [2] the same number (work units).

    Returns
    -------
    status : int
        :mod:`persson_fast._kernels.status` code: OK; BAD_INPUT (bad arrays or a wall jump);
        NONFINITE; RTOL_NOT_MET (rtol mode: the node cap or the attempt limit stopped the
        refinement; the outputs are the finest resolution reached, error_estimate its
        estimate); WALL_THINNED (rtol mode: more schedule points than the node cap allows even
        at the coarsest resolution; the outputs are those of a wall through a subset of the
        points, see the module notes); GRID_CAP (an explicit ``level`` over the node cap:
        nothing solved, outputs NaN).

    Notes
    -----
    Buonocore, Nobile & Ricciardi, Adv. Appl. Prob. 19, 784 (1987). Scale-free: units only
    need to be consistent. By construction A + detached = 1 and load = sigma0 + detached load
    hold to rounding. No NaN area comes back in the rtol mode unless the status is NONFINITE
    or BAD_INPUT.
    """
    status = _solve_core(G, sa, sigma0, rtol, level, out_area, out_load, out_det_area,
                         out_det_load, out_error, counts)
    if status != NOTHING_FIT:
        return status
    # --- too many schedule points for the node cap: thin the smooth stretches ---------------
    nt = G.shape[0]
    keep = np.empty(nt, dtype=np.bool_)
    keep2 = np.empty(nt, dtype=np.bool_)
    stride = 2
    while True:
        n_keep = _thin_mask(G, sa, stride, keep)
        s1, idx, a1, ld1, d1, dl1, e1 = _solve_subset(G, sa, keep, n_keep, sigma0, rtol, level,
                                                      counts)
        if s1 != NOTHING_FIT or stride >= nt:
            break
        stride *= 2
    if s1 == NOTHING_FIT:
        s1 = st.GRID_CAP                 # kinks alone exceed the cap (outputs NaN)
    if s1 != st.OK and s1 != st.RTOL_NOT_MET:
        nan = math.nan
        fill_state(np.int64(0), nt, nan, nan, nan, nan, nan, out_area, out_load, out_det_area,
                   out_det_load, out_error)
        return s1
    work = counts[1]
    n_fine = counts[0]
    # thinning error: the same solve on every second kept point of the smooth stretches
    n_keep2 = _thin_mask(G, sa, 2 * stride, keep2)
    s2, idx2, a2, ld2, d2, dl2, e2 = _solve_subset(G, sa, keep2, n_keep2, sigma0, rtol, level,
                                                   counts)
    work += counts[1]
    counts[0] = n_fine
    counts[1] = work
    counts[2] = work
    # per kept point: |A_m - A_2m| where both exist, else the larger neighbouring value
    thin = np.empty(n_keep)
    j2 = 0
    for j in range(n_keep):
        thin[j] = -1.0
        while j2 < n_keep2 and idx2[j2] < idx[j]:
            j2 += 1
        if j2 < n_keep2 and idx2[j2] == idx[j]:
            if s2 == st.OK or s2 == st.RTOL_NOT_MET:
                thin[j] = abs(a1[j] - a2[j2]) + e2[j2]
            else:
                thin[j] = 1.0
    for j in range(n_keep):
        if thin[j] < 0.0:
            lo = thin[j - 1] if j > 0 else 0.0
            hi = 0.0
            for q in range(j + 1, n_keep):
                if thin[q] >= 0.0:
                    hi = thin[q]
                    break
            thin[j] = lo if lo > hi else hi
    # outputs: kept points directly, the others by quadratic interpolation in G of the
    # detached area and load (cumulative integrals) through the three nearest kept points
    j = 0
    for k in range(nt):
        while j < n_keep - 1 and idx[j + 1] <= k:
            j += 1
        if idx[j] == k:
            out_det_area[k] = d1[j]
            out_det_load[k] = dl1[j]
            out_error[k] = e1[j] + thin[j]
        else:
            # idx[j] < k < idx[j + 1]
            # (the bracketing kept points have G[idx[j]] < G[k] < G[idx[j + 1]])
            x = G[k]
            w = (x - G[idx[j]]) / (G[idx[j + 1]] - G[idx[j]])
            dlin = (1.0 - w) * d1[j] + w * d1[j + 1]
            dq = dlin
            lq = (1.0 - w) * dl1[j] + w * dl1[j + 1]
            j0 = j - 1 if j > 0 else 0
            if j0 + 2 > n_keep - 1:
                j0 = n_keep - 3
            if j0 >= 0:
                xa = G[idx[j0]]
                xb = G[idx[j0 + 1]]
                xc = G[idx[j0 + 2]]
                if xa < xb < xc:
                    la = (x - xb) * (x - xc) / ((xa - xb) * (xa - xc))
                    lb = (x - xa) * (x - xc) / ((xb - xa) * (xb - xc))
                    lc = (x - xa) * (x - xb) / ((xc - xa) * (xc - xb))
                    dq = la * d1[j0] + lb * d1[j0 + 1] + lc * d1[j0 + 2]
                    lq = la * dl1[j0] + lb * dl1[j0 + 1] + lc * dl1[j0 + 2]
            out_det_area[k] = dq
            out_det_load[k] = lq
            # interpolation error: bounded by the gap to the linear interpolant between the
            # bracketing points
            eb = e1[j] if e1[j] > e1[j + 1] else e1[j + 1]
            tb = thin[j] if thin[j] > thin[j + 1] else thin[j + 1]
            out_error[k] = eb + tb + abs(dq - dlin)
        dd = out_det_area[k]
        if dd < 0.0:
            dd = 0.0
        elif dd > 1.0:
            dd = 1.0
        out_det_area[k] = dd
        out_area[k] = 1.0 - dd
        out_load[k] = sigma0 + out_det_load[k]
    return st.WALL_THINNED


# the sweep of the one signature of every grid method


def _bnr_sweep(G, sa_rows, sy_rows, pressures, rtol, level, n_damp, area, load, det_area,
               det_load, error, pl_area, pl_load, status, counts):
    """Solve every pressure with :func:`solve_bnr_one`.

    Arguments as in :mod:`persson_fast._kernels.signature` (no ``variant``; ``n_damp`` is
    not used: the integral equation has no damped steps): one wall, so ``sy_rows`` must be
    absent (rows of length 0, or +inf at every G; else BAD_INPUT), ``pl_area``/``pl_load``
    rows of length 0 (not requested) or n_t (set to zero).
    """
    n_p = pressures.shape[0]
    n_t = G.shape[0]
    for k in prange(n_p):
        if no_upper_wall(sy_rows, pl_area, pl_load, k, n_p, n_t):
            status[k] = solve_bnr_one(G, sa_rows[k], pressures[k], rtol, level, area[k],
                                      load[k], det_area[k], det_load[k], error[k], counts[k])
        else:
            status[k] = st.BAD_INPUT


bnr_sweep_serial, bnr_sweep_parallel = njit_sweeps(_bnr_sweep)
