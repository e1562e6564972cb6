"""Slow, obvious twin of the stress diffusion between two absorbing walls (for tests).

Elastoplastic contact in Persson's theory (B.N.J. Persson, J. Chem. Phys. 115, 3840 (2001);
Surf. Sci. Rep. 61, 201 (2006)): the distribution P(sigma, G) of the local normal stress
(sigma > 0 compressive, SI units) obeys the heat equation in the diffusion time G [Pa^2],

.. math::

    \\partial_G P = \\partial_\\sigma^2 P, \\qquad P(\\sigma, 0) = \\delta(\\sigma - \\sigma_0),

with absorbing walls at sigma = -sigma_a(G) (detachment, lower) and sigma = sigma_Y(G)
(yield, upper), -sigma_a < sigma_Y. Outputs at each requested G:

* elastic area A_el = integral of P between the walls;
* plastic area A_pl = integral over G' of the flux through the upper wall;
* detached area D = integral over G' of the flux through the lower wall
  (A_el + A_pl + D = 1);
* load L = integral of sigma P; plastic load = integral of sigma_Y(G') dA_pl(G');
  detached load = integral of (-sigma_a(G')) dD(G'). Since sigma is a martingale stopped at the
  walls, L + plastic_load + detached_load = sigma0 (exactly, for walls that do not jump).

Sign convention: ``detached_load`` here is the integral of -sigma_a dD (so that the three
loads add up to sigma0); the adhesive solver of the package reports the opposite sign
(``load = pressure + detached_load``).

Two functions, numpy/scipy only, no numba and no code shared with the compiled routines:

* :func:`translating_walls` -- the exact solution for two walls translating together,
  sigma_a(G) = a - b G, sigma_Y(G) = Y + b G (a strip of fixed width W = Y + a with drift),
  as a sine series with closed-form integrals in G (the test oracle).
* :func:`two_wall_reference` -- general walls (scalars, piecewise-linear samples with jumps,
  or callables) by Crank-Nicolson on a uniform grid spanning the strip, Richardson
  extrapolated over two resolutions. Seconds per call.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.linalg import solve_banded

__all__ = ["translating_walls", "two_wall_reference"]

OUTPUTS = ("elastic_area", "plastic_area", "detached_area", "load", "plastic_load",
           "detached_load")

#: modes are kept while exp(-k_n^2 G) exceeds exp(-_MODE_EXPONENT) times the amplitude [-]
_MODE_EXPONENT = 42.0
#: most sine modes :func:`translating_walls` sums (sets its smallest G/W^2, ~1e-8) [-]
_MAX_MODES = 200_000
#: largest amplification exp(|b| y0 / 2 - b^2 G / 4) of the mode amplitudes tolerated [-]
_MAX_AMPLIFICATION = 1e4


# --------------------------------------------------------------------------------------------
# exact solution: two walls translating together
# --------------------------------------------------------------------------------------------
def _sinh_minus_x(z):
    """sinh(z) - z without cancellation (Taylor series for |z| < 1)."""
    z = np.asarray(z, dtype=float)
    out = np.sinh(z) - z
    small = np.abs(z) < 1.0
    if np.any(small):
        zs = z[small]
        z2 = zs * zs
        term = zs * z2 / 6.0
        acc = term.copy()
        for k in range(2, 12):  # z^(2k+1)/(2k+1)!, up to z^23/23! < 4e-23
            term = term * z2 / ((2 * k) * (2 * k + 1))
            acc = acc + term
        out[small] = acc
    return out


def _hit_upper_first(y, W, b):
    """P(reach y = W before y = 0) for dy = -b dG + sqrt(2) dB started at y: the scale function
    exp(b y) gives (e^{b y} - 1)/(e^{b W} - 1), written with expm1 of one sign (no cancellation,
    no overflow)."""
    if b == 0.0:
        return y / W
    if b < 0.0:
        return math.expm1(b * y) / math.expm1(b * W)
    return math.exp(-b * (W - y)) * math.expm1(-b * y) / math.expm1(-b * W)


def _time_upper(y, W, b):
    """E[tau; exit at y = W] for dy = -b dG + sqrt(2) dB started at y in [0, W]. [Pa^2]

    u solves u'' - b u' = -h_up(y), u(0) = u(W) = 0 (h_up: :func:`_hit_upper_first`):
    u = e^{x(y-W)} phi / (2 x^2 sinh^2 t), x = b/2, t = x W, s = x y,
    phi = t cosh t sinh s - s cosh s sinh t = [(t-s) g(t+s) - (t+s) g(t-s)]/2, g(z) = sinh z - z
    (the linear parts of sinh cancel exactly); b = 0: u = y (W^2 - y^2) / (6 W).
    """
    if b == 0.0:
        return y * (W * W - y * y) / (6.0 * W)
    x = 0.5 * b
    t, s = x * W, x * y
    g = _sinh_minus_x(np.array([t + s, t - s]))
    phi = 0.5 * ((t - s) * g[0] - (t + s) * g[1])
    return math.exp(x * (y - W)) * phi / (2.0 * x * x * math.sinh(t) ** 2)


def translating_walls(sigma0, G, a, Y, b):
    """Exact two-wall solution for walls translating together (drift b).

    Parameters
    ----------
    sigma0 : float
        Nominal stress, -a <= sigma0 <= Y. [Pa]
    G : array_like
        Diffusion times, G = 0 or G >= ~1e-8 W^2 (see Raises). [Pa^2]
    a : float
        Lower wall at G = 0: sigma_a(G) = a - b G, i.e. the wall sits at sigma = -a + b G. [Pa]
    Y : float
        Upper (yield) wall at G = 0: sigma_Y(G) = Y + b G, Y > -a. [Pa]
    b : float
        Common wall speed d sigma / dG of both walls, either sign. [1/Pa]

    Returns
    -------
    out : dict of ndarray
        Arrays of the shape of `G`: ``elastic_area``, ``plastic_area``, ``detached_area`` [-],
        ``load``, ``plastic_load``, ``detached_load`` [Pa] (definitions in the module
        docstring). At G = 0: (1, 0, 0, sigma0, 0, 0) inside; a start on a wall is absorbed at
        once by that wall.

    Raises
    ------
    ValueError
        On non-finite input, negative `G`, Y <= -a, sigma0 outside [-a, Y], |b| W > 200; for
        0 < G < ~1e-8 W^2 (more than 200 000 modes); or where the early drifted regime makes
        the sine series lose more than 4 digits (exp(|b| y0' / 2 - b^2 G / 4) > 1e4 with y0' the
        start's distance to the wall the drift pushes away from).

    Notes
    -----
    With y = sigma + a - b G in [0, W], W = Y + a, the stress moves with drift -b (variance
    2 G), so P_G = P_yy + b P_y and P = exp(-beta (y - y0) - beta^2 G) Q, beta = b / 2,
    y0 = sigma0 + a, Q the absorbing strip's heat kernel
    sum (2/W) sin(k_n y0) sin(k_n y) exp(-k_n^2 G), k_n = n pi / W. With
    lambda_n = k_n^2 + beta^2, e_n = exp(-lambda_n G) and the wall-flux amplitudes

        c_lo = (2/W) sin(k_n y0) e^{beta y0} k_n,
        c_up = (2/W) sin(k_n y0) e^{beta (y0 - W)} k_n (-1)^(n+1)

    (fluxes P_y(0) = sum c_lo e_n and -P_y(W) = sum c_up e_n; integral of e^{-beta y} sin(k y)
    over the strip = k (1 - (-1)^n e^{-beta W}) / lambda):

        A_el = sum (c_lo + c_up) e_n / lambda_n
        D    = h_lo(y0) - sum c_lo e_n / lambda_n,   A_pl = h_up(y0) - sum c_up e_n / lambda_n
        L    = sum e_n [W c_up / lambda_n + b (c_lo + c_up) / lambda_n^2] + (b G - a) A_el
        detached_load = -a D + b [u_lo(y0) - sum c_lo e_n (1/lambda_n^2 + G/lambda_n)]
        plastic_load  =  Y A_pl + b [u_up(y0) - sum c_up e_n (1/lambda_n^2 + G/lambda_n)]

    where h_up = (e^{b y0} - 1)/(e^{b W} - 1) (gambler's ruin with drift, the G -> inf plastic
    area), h_lo = 1 - h_up, and u_up, u_lo = E[exit time; exit at that wall] solve
    u'' - b u' = -h, u(0) = u(W) = 0 (closed forms in :func:`_time_upper`; u_lo by the
    reflection y -> W - y, b -> -b). The G -> inf parts are summed in closed form, so only the
    decaying sums e_n remain: modes are kept until k_n^2 G > 42 + |beta| W.

    Accuracy (measured): against ``plastic_area`` (b = 0, a = 0) <= 5e-15; the identities
    A_el + A_pl + D = 1 and L + plastic_load + detached_load = sigma0 to rounding (~1e-15
    relative) for |b| W <= 10 and G/W^2 in [1e-6, 10]; the single-wall limit Y >> sqrt(G)
    agrees with ``linear_boundary_area``/``linear_boundary_load`` to ~1e-15. Rounding grows as
    the amplification exp(|beta| y0' - beta^2 G) (early times with a strong drift), which is
    refused above 1e4.
    """
    G_arr = np.asarray(G, dtype=float)
    shape = G_arr.shape
    g = G_arr.ravel()
    vals = [float(sigma0), float(a), float(Y), float(b)]
    if not (np.all(np.isfinite(g)) and all(math.isfinite(v) for v in vals)):
        raise ValueError("translating_walls: non-finite input")
    sigma0, a, Y, b = vals
    if np.any(g < 0):
        raise ValueError("translating_walls: G must be >= 0 [Pa^2]")
    W = Y + a
    if not W > 0:
        raise ValueError("translating_walls: need Y > -a (a strip of positive width) [Pa]")
    y0 = sigma0 + a
    if y0 < 0 or y0 > W:
        raise ValueError("translating_walls: sigma0 must lie in [-a, Y] [Pa]")
    if abs(b) * W > 200:
        raise ValueError("translating_walls: |b| W > 200 is not served")
    beta = 0.5 * b
    h_up = _hit_upper_first(y0, W, b)
    h_lo = _hit_upper_first(W - y0, W, -b)
    u_up = _time_upper(y0, W, b)
    u_lo = _time_upper(W - y0, W, -b)
    out = {k: np.empty(g.size) for k in OUTPUTS}
    for i, gi in enumerate(g):
        if gi == 0.0:
            inside = 0.0 < y0 < W
            vals0 = {
                "elastic_area": 1.0 if inside else 0.0,
                "plastic_area": 1.0 if y0 == W else 0.0,
                "detached_area": 1.0 if y0 == 0.0 else 0.0,
                "load": sigma0 if inside else 0.0,
                "plastic_load": Y if y0 == W else 0.0,
                "detached_load": -a if y0 == 0.0 else 0.0,
            }
            for k, v in vals0.items():
                out[k][i] = v
            continue
        y0_far = y0 if b > 0 else W - y0  # distance to the wall the drift pushes away from
        amp = math.exp(abs(beta) * y0_far - beta * beta * gi)
        if amp > _MAX_AMPLIFICATION:
            raise ValueError(
                f"translating_walls: early drifted regime (amplification {amp:.3g} > 1e4 at "
                f"G = {gi:.6g} Pa^2): the sine series would lose more than 4 digits")
        n_modes = int(math.ceil(W / math.pi * math.sqrt((_MODE_EXPONENT + abs(beta) * W) / gi)))
        n_modes = max(n_modes, 4)
        if n_modes > _MAX_MODES:
            raise ValueError(
                f"translating_walls: G/W^2 = {gi / W ** 2:.3g} needs {n_modes} modes (> "
                f"{_MAX_MODES}); small G is not served")
        n = np.arange(1, n_modes + 1, dtype=float)
        k = n * math.pi / W
        lam = k * k + beta * beta
        sgn = np.where(n % 2 == 1, 1.0, -1.0)  # (-1)^(n+1)
        # sin(k y0) from the nearer end keeps its accuracy for y0 next to W
        sin0 = np.sin(k * y0) if y0 <= 0.5 * W else sgn * np.sin(k * (W - y0))
        base = (2.0 / W) * sin0 * k * np.exp(-lam * gi)
        c_lo = base * math.exp(beta * y0)
        c_up = base * math.exp(beta * (y0 - W)) * sgn
        s_lo1, s_up1 = np.sum(c_lo / lam), np.sum(c_up / lam)
        s_lo2, s_up2 = np.sum(c_lo / lam ** 2), np.sum(c_up / lam ** 2)
        area = s_lo1 + s_up1
        det = h_lo - s_lo1
        pla = h_up - s_up1
        out["elastic_area"][i] = area
        out["detached_area"][i] = det
        out["plastic_area"][i] = pla
        out["load"][i] = W * s_up1 + b * (s_lo2 + s_up2) + (b * gi - a) * area
        out["detached_load"][i] = -a * det + b * (u_lo - s_lo2 - gi * s_lo1)
        out["plastic_load"][i] = Y * pla + b * (u_up - s_up2 - gi * s_up1)
    return {k: v.reshape(shape) for k, v in out.items()}


# --------------------------------------------------------------------------------------------
# general walls: Crank-Nicolson between the walls
# --------------------------------------------------------------------------------------------
class _Wall:
    """A wall given as a scalar, as samples on the schedule G (linear between them, a repeated G
    is a jump) or as a callable of G; ``value(g, k)`` is its stress at g in the schedule's piece
    k (G[k] <= g <= G[k+1]; before G[0] a sampled wall holds its first value)."""

    def __init__(self, spec, G, name):
        self.name = name
        self.G = G
        if callable(spec):
            self.kind, self.f = "callable", spec
            return
        arr = np.asarray(spec, dtype=float)
        if arr.ndim == 0:
            self.kind, self.c = "scalar", float(arr)
        elif arr.shape == G.shape:
            self.kind, self.v = "samples", arr
        else:
            raise ValueError(f"two_wall_reference: {name} must be a scalar, an (n_t,) array or a "
                             f"callable of G")
        if not np.all(np.isfinite(arr)):
            raise ValueError(f"two_wall_reference: {name} is not finite")

    def value(self, g, k):
        if self.kind == "scalar":
            return self.c
        if self.kind == "callable":
            v = float(self.f(g))
            if not math.isfinite(v):
                raise ValueError(f"two_wall_reference: {self.name}({g!r}) is not finite")
            return v
        if k < 0:
            return float(self.v[0])
        g0, g1 = self.G[k], self.G[k + 1]
        if g1 == g0:
            return float(self.v[k + 1])
        return float(self.v[k] + (self.v[k + 1] - self.v[k]) * (g - g0) / (g1 - g0))

    def at_sample(self, i):
        """The wall at the schedule's sample i (for a repeated G: the value given there)."""
        if self.kind == "samples":
            return float(self.v[i])
        return self.value(self.G[i], 0)


def _operator(n, w, sa_dot, w_dot):
    """Tridiagonal semi-discrete operator of p_G = (1/w^2) p_yy - d/dy (v p), v = (sa' - y w')/w,
    on the interior nodes of y_j = j/n (p_0 = p_n = 0), conservative central differences:
    returns (sub, diag, sup) and the boundary coefficients (out_lo / p_1, out_up / p_{n-1})."""
    h = 1.0 / n
    d = 1.0 / (w * w)
    yf = (np.arange(n) + 0.5) * h          # faces j + 1/2, j = 0..n-1
    vf = (sa_dot - yf * w_dot) / w
    # dp_j/dG = [ (d/h + v_{j-1/2}/2) p_{j-1} - (2d/h + v_{j+1/2}/2 - v_{j-1/2}/2) p_j
    #            + (d/h - v_{j+1/2}/2) p_{j+1} ] / h
    vm, vp = vf[:-1], vf[1:]                # faces j - 1/2 and j + 1/2 for j = 1..n-1
    sub = (d / h + 0.5 * vm) / h
    diag = -(2.0 * d / h + 0.5 * vp - 0.5 * vm) / h
    sup = (d / h - 0.5 * vp) / h
    out_lo = d / h - 0.5 * vf[0]            # -F_{1/2} / p_1
    out_up = d / h + 0.5 * vf[-1]           # F_{n-1/2} / p_{n-1}
    return sub, diag, sup, out_lo, out_up


def _apply(op, p):
    sub, diag, sup = op[:3]
    r = diag * p
    r[1:] += sub[1:] * p[:-1]
    r[:-1] += sup[:-1] * p[1:]
    return r


def _solve(op, c, rhs):
    """(I - c L) x = rhs."""
    sub, diag, sup = op[:3]
    ab = np.empty((3, diag.size))
    ab[0, 1:] = -c * sup[:-1]
    ab[0, 0] = 0.0
    ab[1] = 1.0 - c * diag
    ab[2, :-1] = -c * sub[1:]
    ab[2, -1] = 0.0
    return solve_banded((1, 1), ab, rhs)


class _State:
    """Interior node values p_j = w P(sigma_j) (density in y), and the absorbed accounts."""

    def __init__(self, p, n):
        self.p, self.n = p, n
        self.pl = self.det = self.pl_load = self.det_load = 0.0
        self.fix = None        # set by a jump for the report at the jump itself

    def moments(self, w, sa):
        h = 1.0 / self.n
        y = np.arange(1, self.n) * h
        area = h * np.sum(self.p)
        load = h * np.sum((y * w - sa) * self.p)
        return area, load


def _march(G, sigma0, wa, wy, n, plan, g_s):
    """One run on n intervals along the step plan; returns the six outputs at the G samples."""
    h = 1.0 / n
    y = np.arange(1, n) * h
    out = {k: np.empty(G.size) for k in OUTPUTS}

    def record(i, st, w, sa):
        area, load = st.moments(w, sa)
        vals = [area, load, st.pl, st.det, st.pl_load, st.det_load]
        if st.fix is not None:                   # just after a jump: the exact cuts
            e_lo, e_up, s_lo, s_up = st.fix
            vals = [area + e_lo + e_up, load + e_lo * s_lo + e_up * s_up, st.pl - e_up,
                    st.det - e_lo, st.pl_load - e_up * s_up, st.det_load - e_lo * s_lo]
        for key, v in zip(("elastic_area", "load", "plastic_area", "detached_area",
                           "plastic_load", "detached_load"), vals):
            out[key][i] = v

    st = None
    for item in plan:
        kind = item[0]
        if kind == "free":                       # before G_s: the free Gaussian, nothing absorbed
            i = item[1]
            out["elastic_area"][i], out["load"][i] = 1.0, sigma0
            for k in ("plastic_area", "detached_area", "plastic_load", "detached_load"):
                out[k][i] = 0.0
        elif kind == "start":
            _, k = item
            sa, sy = wa.value(g_s, k), wy.value(g_s, k)
            w = sa + sy
            sig = y * w - sa
            p = w * np.exp(-(sig - sigma0) ** 2 / (4.0 * g_s)) / math.sqrt(4.0 * math.pi * g_s)
            st = _State(p, n)
        elif kind == "record":
            _, i = item
            record(i, st, wa.at_sample(i) + wy.at_sample(i), wa.at_sample(i))
        elif kind == "jump":
            _, i = item                          # walls jump from sample i-1 to sample i
            _jump(st, wa.at_sample(i - 1), wy.at_sample(i - 1), wa.at_sample(i),
                  wy.at_sample(i))
        elif kind == "steps":
            _, k, gs, n_ie = item
            _steps(st, wa, wy, k, gs, n_ie)
    return out


def _steps(st, wa, wy, k, gs, n_ie):
    """March through the step boundaries gs (piece k); the first n_ie steps are done as two
    implicit-Euler half steps each (damped start), the rest by Crank-Nicolson. The absorbed
    amounts are the discrete boundary fluxes (exact discrete conservation of the area), the
    absorbed loads their products with the walls' stresses, both by the trapezoid rule in G."""
    n = st.n
    st.fix = None

    def walls(g):
        return wa.value(g, k), wy.value(g, k)

    for j in range(gs.size - 1):
        g0, g1 = gs[j], gs[j + 1]
        dt = g1 - g0
        sa0, sy0 = walls(g0)
        sa1, sy1 = walls(g1)
        sa_dot = (sa1 - sa0) / dt
        w_dot = (sa1 + sy1 - sa0 - sy0) / dt
        if j < n_ie:
            gm = 0.5 * (g0 + g1)
            sam, sym = walls(gm)
            for (ga, gb, sa_b, sy_b) in ((g0, gm, sam, sym), (gm, g1, sa1, sy1)):
                op = _operator(n, sa_b + sy_b, sa_dot, w_dot)
                c = gb - ga
                st.p = _solve(op, c, st.p)
                f_lo, f_up = op[3] * st.p[0], op[4] * st.p[-1]
                st.det += c * f_lo
                st.pl += c * f_up
                st.det_load += c * (-sa_b) * f_lo
                st.pl_load += c * sy_b * f_up
            continue
        op0 = _operator(n, sa0 + sy0, sa_dot, w_dot)
        op1 = _operator(n, sa1 + sy1, sa_dot, w_dot)
        f_lo0, f_up0 = op0[3] * st.p[0], op0[4] * st.p[-1]
        rhs = st.p + 0.5 * dt * _apply(op0, st.p)
        st.p = _solve(op1, 0.5 * dt, rhs)
        f_lo1, f_up1 = op1[3] * st.p[0], op1[4] * st.p[-1]
        st.det += 0.5 * dt * (f_lo0 + f_lo1)
        st.pl += 0.5 * dt * (f_up0 + f_up1)
        st.det_load += 0.5 * dt * (-sa0 * f_lo0 - sa1 * f_lo1)
        st.pl_load += 0.5 * dt * (sy0 * f_up0 + sy1 * f_up1)


def _jump(st, sa0, sy0, sa1, sy1):
    """Both walls jump at once from (sa0, sy0) to (sa1, sy1): the profile is carried over to the
    new strip by a cubic spline in sigma; what lies beyond a wall's new position is absorbed
    into that wall's account at the wall's new stress. The booked amounts are the change of
    the discrete area (split between the walls as the exact cut masses of the spline), so that
    A_el + A_pl + D = 1 stays exact; the half cell next to a wall that moved into the profile
    makes that booking O(h) (drained by the following steps); the values reported at the jump
itself take the exact cuts instead (``st.fix``)."""
    n = st.n
    h = 1.0 / n
    w0, w1 = sa0 + sy0, sa1 + sy1
    if not w1 > 0:
        raise ValueError("two_wall_reference: the walls cross after a jump")
    y_all = np.arange(n + 1) * h
    p_all = np.concatenate(([0.0], st.p, [0.0]))
    spl = CubicSpline(y_all, p_all)
    old_mass = h * np.sum(st.p)
    y_new_in_old = (np.arange(1, n) * h * w1 - sa1 + sa0) / w0
    inside = (y_new_in_old > 0.0) & (y_new_in_old < 1.0)
    p_new = np.zeros(n - 1)
    p_new[inside] = (w1 / w0) * spl(y_new_in_old[inside])
    lo_edge = (sa0 - sa1) / w0                 # new lower wall in old y
    up_edge = (sy1 + sa0) / w0                 # new upper wall in old y
    cut_lo = max(0.0, float(spl.integrate(0.0, min(lo_edge, 1.0)))) if lo_edge > 0 else 0.0
    cut_up = max(0.0, float(spl.integrate(max(up_edge, 0.0), 1.0))) if up_edge < 1 else 0.0
    new_mass = h * np.sum(p_new)
    booked = old_mass - new_mass
    st.fix = None
    if cut_lo + cut_up > 0.0:
        share = cut_lo / (cut_lo + cut_up)
        st.det += booked * share
        st.pl += booked * (1.0 - share)
        st.det_load += -sa1 * booked * share
        st.pl_load += sy1 * booked * (1.0 - share)
        # the report at the jump itself books the exact cuts; the rest (the half cell next to
        # the wall, O(h)) is still elastic there, at the wall's stress
        st.fix = (booked * share - cut_lo, booked * (1.0 - share) - cut_up, -sa1, sy1)
    elif new_mass > 0.0:
        p_new *= old_mass / new_mass          # nothing cut: keep the discrete area (O(h^4))
    st.p = p_new


def _probe_gap(G, sigma0, wa, wy, g_end):
    """Smallest distance of sigma0 to either wall over [0, g_end] (samples, jumps, probes)."""
    probes = [(0.0, -1), (g_end, int(np.searchsorted(G, g_end, side="right")) - 1)]
    for i in np.flatnonzero(G <= g_end):
        probes.append((G[i], i if i < G.size - 1 else i - 1))
        probes.append((G[i], i - 1))
    if "callable" in (wa.kind, wy.kind):
        for g in np.linspace(0.0, g_end, 257):
            probes.append((g, int(np.searchsorted(G, g, side="right")) - 1))
    gap = math.inf
    for g, k in probes:
        k = min(max(k, -1), G.size - 2) if G.size > 1 else -1
        sa = wa.value(g, k) if k >= 0 or wa.kind != "samples" else wa.v[0]
        sy = wy.value(g, k) if k >= 0 or wy.kind != "samples" else wy.v[0]
        gap = min(gap, sigma0 + sa, sy - sigma0)
    return gap


def _plan(G, g_s, wa, wy, n, rel_step, max_step, n_ie):
    """The coarse run's items: free values before G_s, the start, steps, jumps, records."""
    def width(g, k):
        return wa.value(g, k) + wy.value(g, k)

    plan = []
    started = False
    g = g_s
    g_event, tau0, damp = 0.0, 0.0, n_ie
    for i in range(G.size):
        if G[i] <= g_s:
            plan.append(("free", i))
            continue
        if not started:
            plan.append(("start", i - 1))
            started = True
        if i > 0 and G[i] == G[i - 1] and G[i - 1] > g_s:
            plan.append(("jump", i))
            plan.append(("record", i))
            g_event, damp = G[i], n_ie
            tau0 = (max(wa.at_sample(i) + wy.at_sample(i), 0.0) / n) ** 2
            continue
        k = i - 1
        gs = [g]
        while gs[-1] < G[i]:
            gc = gs[-1]
            dt = min(rel_step * (gc - g_event + tau0), max_step * width(gc, k) ** 2)
            if gc + 1.5 * dt >= G[i]:
                if gc + dt < G[i] and G[i] - gc > dt:
                    gs.append(0.5 * (gc + G[i]))
                gs.append(G[i])
                break
            gs.append(gc + dt)
        gs = np.array(gs)
        gs[-1] = G[i]
        plan.append(("steps", k, gs, min(damp, gs.size - 1)))
        damp -= min(damp, gs.size - 1)
        plan.append(("record", i))
        g = G[i]
    return plan


def _refine(plan):
    """The fine run's plan: every step halved (the damped start covers the same G)."""
    fine = []
    for item in plan:
        if item[0] == "steps":
            _, k, gs, n_ie = item
            mid = 0.5 * (gs[:-1] + gs[1:])
            g2 = np.empty(2 * gs.size - 1)
            g2[0::2], g2[1::2] = gs, mid
            fine.append(("steps", k, g2, 2 * n_ie))
        else:
            fine.append(item)
    return fine


def two_wall_reference(G, sigma0, sigma_a, sigma_y, n_nodes=None, rel_step=0.02,
                       max_step=1e-3, n_damp=2, richardson=True):
    """Stress diffusion between two absorbing walls by Crank-Nicolson (slow reference).

    Parameters
    ----------
    G : array_like
        (n_t,) non-decreasing diffusion times, G[0] >= 0; a repeated value is a flat stretch
        where a sampled wall may jump (outputs: before the jump at the first, after it at the
        second occurrence). [Pa^2]
    sigma0 : float
        Nominal stress, -sigma_a(0) < sigma0 < sigma_y(0). [Pa]
    sigma_a : float, array_like or callable
        Lower wall: it sits at sigma = -sigma_a(G). A scalar, (n_t,) values at the G samples
        (linear in G between them, the first value before G[0]), or a callable G -> sigma_a
        (smooth; evaluated at scalar G). [Pa]
    sigma_y : float, array_like or callable
        Upper (yield) wall at sigma = sigma_y(G), same forms. [Pa]
    n_nodes : int or None, optional
        Grid intervals of the coarse run across the strip (the fine run uses twice as many).
        None: max(200, 50 W/d), W the strip width and d the start's distance to the nearer
        wall at G_s (the start Gaussian then spans >= 5 intervals per standard deviation). [-]
    rel_step : float, optional
        Coarse step / (G - G_event) early on (geometric steps; G_event the start or the last
        jump). [-]
    max_step : float, optional
        Coarse step cap / w(G)^2, w = sigma_a + sigma_y the strip width (late, uniform steps). [-]
    n_damp : int, optional
        Steps after the start and after each jump taken as two implicit-Euler half steps. [-]
    richardson : bool, optional
        Combine the runs (n, dt) and (2n, dt/2) as (4 fine - coarse)/3 (default); False returns
        the fine run alone.

    Returns
    -------
    out : dict of ndarray
        (n_t,) arrays ``elastic_area``, ``plastic_area``, ``detached_area`` [-], ``load``,
        ``plastic_load``, ``detached_load`` [Pa] (definitions in the module docstring).

    Raises
    ------
    ValueError
        On non-finite or unordered G, negative G, a start not strictly between the walls,
        walls given in another form, or walls that cross.

    Notes
    -----
    The strip is mapped onto y = (sigma + sigma_a(G)) / w(G) in [0, 1]; the density in y,
    p = w P, obeys p_G = (1/w^2) p_yy - d/dy (v p) with the frame velocity
    v = (sigma_a' - y w')/w. Conservative central differences on y_j = j/n (p = 0 at both
    walls); the wall speeds are the secants over each step (exact for sampled walls, whose
    kinks are step boundaries). Time: Crank-Nicolson, the first ``n_damp`` steps after the
    start and after a jump as implicit-Euler half steps; steps min(rel_step (G - G_event),
    max_step w^2). The run starts at G_s = d^2/160 (d the smallest distance of sigma0 to a wall
    over [0, G_s]) from the free Gaussian N(sigma - sigma0; 2 G_s) sampled at the nodes (both
    walls >= 9 standard deviations away: the mass beyond them is < 1e-18); before G_s the free
    values (1, 0, 0, sigma0, 0, 0) are returned. The absorbed areas are the discrete boundary
    fluxes integrated by the trapezoid rule (A_el + A_pl + D = 1 to rounding), the absorbed
    loads the fluxes times the walls' stresses; the load balance holds to the discretisation
    error (~1e-9 relative after extrapolation). A jump books what lies beyond a wall's new
    position at once, at the wall's new stress (which breaks the load balance by the cut mass
    times its mean distance beyond the new wall).

    Accuracy (measured in tests/test_reference_yield.py, default settings, Richardson, G/W^2
    from 1e-4 to 1): against ``plastic_area`` (constant walls) <= 4e-8 in the areas and
    2e-8 sigma_Y in the loads; against :func:`translating_walls` (b W = +-2, +-6) <= 1.1e-7 in
    the areas and 1.7e-8 W in the loads; against ``linear_boundary_area``/``_load`` with a far
    upper wall <= 7e-9. Without Richardson the error is ~2e-6 (second order). A = 1 - A_pl - D
    holds to ~1e-12 (rounding accumulated over the steps). About 0.1 s per run of 200 nodes
    (0.2-0.4 s per call); the nodes grow as W/d for a start next to a wall.
    """
    G = np.asarray(G, dtype=float)
    if G.ndim != 1 or G.size == 0:
        raise ValueError("two_wall_reference: G must be a non-empty 1-D array [Pa^2]")
    if not np.all(np.isfinite(G)) or np.any(G < 0) or np.any(np.diff(G) < 0):
        raise ValueError("two_wall_reference: G must be finite, >= 0 and non-decreasing [Pa^2]")
    sigma0 = float(sigma0)
    if not math.isfinite(sigma0):
        raise ValueError("two_wall_reference: sigma0 is not finite")
    wa, wy = _Wall(sigma_a, G, "sigma_a"), _Wall(sigma_y, G, "sigma_y")
    sa_init = wa.v[0] if wa.kind == "samples" else wa.value(0.0, -1)
    sy_init = wy.v[0] if wy.kind == "samples" else wy.value(0.0, -1)
    if not (-sa_init < sigma0 < sy_init):
        raise ValueError("two_wall_reference: need -sigma_a(0) < sigma0 < sigma_y(0)")
    d = min(sigma0 + sa_init, sy_init - sigma0)
    g_s = d * d / 160.0
    for _ in range(200):
        d_min = _probe_gap(G, sigma0, wa, wy, g_s)
        if d_min > 0 and g_s <= d_min * d_min / 160.0 * (1 + 1e-12):
            break
        g_s = 0.5 * g_s if d_min <= 0 else d_min * d_min / 160.0
    else:
        raise ValueError("two_wall_reference: no start G_s found (a wall reaches sigma0 at once)")
    k_s = int(np.searchsorted(G, g_s, side="right")) - 1
    k_s = min(k_s, G.size - 2)
    w_s = wa.value(g_s, k_s) + wy.value(g_s, k_s) if k_s >= 0 else sa_init + sy_init
    if n_nodes is None:
        n_nodes = max(200, int(math.ceil(50.0 * w_s / d_min)))
    n = int(n_nodes)
    plan = _plan(G, g_s, wa, wy, n, rel_step, max_step, n_damp)
    fine = _march(G, sigma0, wa, wy, 2 * n, _refine(plan), g_s)
    if not richardson:
        return fine
    coarse = _march(G, sigma0, wa, wy, n, plan, g_s)
    return {k: (4.0 * fine[k] - coarse[k]) / 3.0 for k in OUTPUTS}
