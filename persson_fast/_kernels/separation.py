"""Compiled kernels of the mean interfacial separation, the contact stiffness and the stored
elastic energy without adhesion (see :mod:`persson_fast.separation` for the physics).

Everything is a sum over a fixed set of quadrature nodes q_k of the wavevector, with the
surface and the modulus folded into per-node constants by the Python layer:

* ``s_scale[k] = w(q_k) / E* = 1 / (2 sqrt(G(q_k)))`` [1/Pa], so s = p s_scale[k] is the
  argument of P(q, p) = erf(s);
* ``a_sep[k]  = sqrt(pi) W_k q_k^2 C(q_k) w(q_k)`` [m] (W_k: the node's quadrature weight);
* ``b_energy[k] = (pi/2) E* W_k q_k^2 C(q_k)`` [J/m^2].

Then, with F(s) = gamma_S + 3 (1 - gamma_S) erf(s)^2,

    u(p)    = sum_k a_sep[k] * Kfun(p s_scale[k]),   Kfun(s) = int_s^inf F(t) exp(-t^2) dt / t
    Q(p)    = sum_k a_sep[k] * F(s) exp(-s^2),       K(p) = p / Q(p)   (stiffness -dp/du)
    dQ/dp   = sum_k a_sep[k] s_scale[k] (F'(s) - 2 s F(s)) exp(-s^2)   (for d ln K / d ln p)
    U_el(p) = sum_k b_energy[k] * erf(s) (gamma_S + (1 - gamma_S) erf(s)^2)

Kfun(s) = gamma_S E1(s^2)/2 + 3 (1 - gamma_S) J(s), J(s) = int_s^inf erf(t)^2 exp(-t^2) dt/t.
E1 is computed here (series below 1, continued fraction above); J from two Chebyshev
expansions built once per process by the Python layer (``j_coefficients``): J itself on
[0, 2], and J = E1(s^2)/2 - exp(-2 s^2) R(s) / s^3 on [2, 6] with R smooth; above 6 the
correction is below 1e-16 relative and J = E1(s^2)/2. The sums do not call these per node:
V(x) = Kfun(e^x) exp(e^(2x)) is tabulated once per gamma_S (``build_kfun_table``, spacing
1/512 in x = ln s, exact slopes) and interpolated by cubic Hermite polynomials
(``kfun_scaled``), so a node costs one table look-up, one exp and one erf; x = ln p +
ln s_scale[k] needs no logarithm per node.

The nodes come sorted by s_scale (ascending). Nodes whose s^2 exceeds the smallest s^2 of
the row by more than ``SKIP_EXPONENT`` add less than exp(-SKIP_EXPONENT) relative to u and
Q and are not visited; for U_el the nodes with s >= ``ERF_ONE`` (erf(s) == 1.0) enter
through one precomputed suffix sum.
"""
from __future__ import annotations

import math

from .._jit import njit_serial, njit_sweeps, prange
from .status import BAD_INPUT, NONFINITE, OK, SEPARATION_UNDERFLOW

EULER_GAMMA = 0.57721566490153286061
TWO_OVER_SQRT_PI = 2.0 / math.sqrt(math.pi)
#: nodes with s^2 > min s^2 + SKIP_EXPONENT are skipped in u and Q (exp(-45) ~ 3e-20)
SKIP_EXPONENT = 45.0
#: the two ranges of the Chebyshev expansions of J (see the module docstring)
J_SPLIT = 2.0
J_END = 6.0
#: erf(s) == 1.0 in double precision for s >= ERF_ONE
ERF_ONE = 6.0
#: u or Q below this bound (2^52 times the smallest normal double, ~1e-292 m) may hold terms
#: that underflowed: each term below the smallest normal double is lost or inexact, and only
#: above the bound is every such term below 2^-52 of the sum
UNDERFLOW_BOUND = 2.0 ** 52 * 2.2250738585072014e-308


@njit_serial
def exp1(x):
    """Exponential integral E1(x) = int_x^inf exp(-t)/t dt for x > 0 (relative error ~1e-15)."""
    if x <= 0.0:
        return math.inf
    if x <= 1.0:
        # E1 = -gamma - ln x - sum_{k>=1} (-x)^k / (k k!)
        total = 0.0
        term = 1.0
        for k in range(1, 60):
            term *= -x / k
            add = term / k
            total += add
            if abs(add) < 1e-17 * abs(total):
                break
        return -EULER_GAMMA - math.log(x) - total
    if x > 745.0:
        return 0.0
    # continued fraction E1 = exp(-x) / (x + 1 - 1/(x + 3 - 4/(x + 5 - ...))), modified Lentz
    b = x + 1.0
    c = 1.0 / 1e-300
    d = 1.0 / b
    h = d
    for i in range(1, 200):
        an = -float(i * i)
        b += 2.0
        d = 1.0 / (an * d + b)
        c = b + an / c
        delta = c * d
        h *= delta
        if abs(delta - 1.0) < 1e-16:
            break
    return h * math.exp(-x)


@njit_serial
def chebyshev(coef, lo, hi, x):
    """Clenshaw sum of a Chebyshev series on [lo, hi] at x."""
    t = (2.0 * x - lo - hi) / (hi - lo)
    b1 = 0.0
    b2 = 0.0
    for i in range(coef.size - 1, 0, -1):
        b1, b2 = 2.0 * t * b1 - b2 + coef[i], b1
    return t * b1 - b2 + coef[0]


@njit_serial
def erf_squared_tail(s, cheb_low, cheb_high):
    """J(s) = int_s^inf erf(t)^2 exp(-t^2) dt / t for s >= 0. [-]"""
    if s <= J_SPLIT:
        return chebyshev(cheb_low, 0.0, J_SPLIT, s)
    half_e1 = 0.5 * exp1(s * s)
    if s >= J_END:
        return half_e1
    return half_e1 - math.exp(-2.0 * s * s) * chebyshev(cheb_high, J_SPLIT, J_END, s) / (s * s * s)


@njit_serial
def separation_integrand(s, gamma_s, cheb_low, cheb_high):
    """Kfun(s) = int_s^inf (gamma_S + 3 (1 - gamma_S) erf(t)^2) exp(-t^2) dt / t. [-]"""
    value = 0.5 * gamma_s * exp1(s * s)
    if gamma_s != 1.0:
        value += 3.0 * (1.0 - gamma_s) * erf_squared_tail(s, cheb_low, cheb_high)
    return value


@njit_serial
def build_kfun_table(gamma_s, cheb_low, cheb_high, x_lo, step, out_v, out_dv):
    """Tabulate V(x) = Kfun(e^x) exp(e^(2x)) and dV/dx on x = x_lo + j step (j < out_v.size).

    V is smooth and of moderate size everywhere (about -gamma_S x at small s, 1/(2 s^2) (3 -
    2 gamma_S) at large s), so cubic Hermite interpolation of V keeps the relative accuracy
    of Kfun = V exp(-s^2) at every s. dKfun/ds = -F(s) exp(-s^2)/s gives the exact slope
    dV/dx = 2 s^2 V - F(s).
    """
    for j in range(out_v.size):
        s = math.exp(x_lo + j * step)
        s2 = s * s
        e = math.erf(s)
        f = gamma_s + 3.0 * (1.0 - gamma_s) * e * e
        v = separation_integrand(s, gamma_s, cheb_low, cheb_high) * math.exp(s2)
        out_v[j] = v
        out_dv[j] = 2.0 * s2 * v - f


@njit_serial
def kfun_scaled(x, s2, gamma_s, j0, table_v, table_dv, x_lo, inv_step):
    """V(x) = Kfun(s) exp(s^2) at x = ln s (s2 = s^2) from the table, or its limits outside.

    Below the table, Kfun = gamma_S (-x - EULER_GAMMA/2) + 3 (1 - gamma_S) J(0) (the next terms
    are O(s^2)); above it, Kfun = (3 - 2 gamma_S) E1(s^2)/2 with the asymptotic series of
    E1 (five terms; relative error below 1e-12 for s^2 > 600).
    """
    pos = (x - x_lo) * inv_step
    if pos < 0.0:
        return (gamma_s * (-x - 0.5 * EULER_GAMMA) + 3.0 * (1.0 - gamma_s) * j0) * math.exp(s2)
    j = int(pos)
    if j >= table_v.size - 1:
        r = 1.0 / s2
        series = r * (1.0 - r * (1.0 - r * (2.0 - r * (6.0 - 24.0 * r))))
        return 0.5 * (3.0 - 2.0 * gamma_s) * series
    t = pos - j
    step = 1.0 / inv_step
    t2 = t * t
    t3 = t2 * t
    h00 = 2.0 * t3 - 3.0 * t2 + 1.0
    h10 = t3 - 2.0 * t2 + t
    h01 = 3.0 * t2 - 2.0 * t3
    h11 = t3 - t2
    return (h00 * table_v[j] + h01 * table_v[j + 1]
            + step * (h10 * table_dv[j] + h11 * table_dv[j + 1]))


@njit_serial
def _first_at_least(sorted_x, value):
    """Smallest index k with sorted_x[k] >= value (sorted_x.size if none)."""
    lo = 0
    hi = sorted_x.size
    while lo < hi:
        mid = (lo + hi) // 2
        if sorted_x[mid] < value:
            lo = mid + 1
        else:
            hi = mid
    return lo


@njit_serial
def separation_one(p, s_scale, ln_s_scale, a_sep, b_energy, b_suffix, gamma_s, j0,
                   table_v, table_dv, x_lo, inv_step):
    """(u, Q, dQ/dp, U_el) at one pressure p > 0; K = p / Q. Units as in the module
    docstring (dQ/dp in m/Pa).

    ``s_scale`` is sorted ascending (``ln_s_scale`` its logarithm); ``b_suffix[k]`` = sum of
    b_energy[k:] (the energy of the nodes where erf(s) == 1.0 in double precision,
    s >= ``ERF_ONE``); the table is :func:`build_kfun_table`'s.
    """
    n = s_scale.size
    s_min = p * s_scale[0]
    k_skip = _first_at_least(s_scale, math.sqrt(s_min * s_min + SKIP_EXPONENT) / p)
    k_one = _first_at_least(s_scale, ERF_ONE / p)
    ln_p = math.log(p)
    u = 0.0
    q = 0.0
    dq = 0.0
    energy = b_suffix[k_one] if k_one < n else 0.0
    for k in range(max(k_one, k_skip)):
        s = p * s_scale[k]
        e = math.erf(s) if k < k_one else 1.0
        if k < k_one:
            energy += b_energy[k] * e * (gamma_s + (1.0 - gamma_s) * e * e)
        if k < k_skip:
            s2 = s * s
            decay = math.exp(-s2)
            v = kfun_scaled(ln_p + ln_s_scale[k], s2, gamma_s, j0, table_v, table_dv, x_lo,
                            inv_step)
            f = gamma_s + 3.0 * (1.0 - gamma_s) * e * e
            u += a_sep[k] * v * decay
            q += a_sep[k] * f * decay
            df = 6.0 * (1.0 - gamma_s) * e * TWO_OVER_SQRT_PI * decay
            dq += a_sep[k] * s_scale[k] * (df - 2.0 * s * f) * decay
    return u, q, dq, energy


def _separation_sweep(pressure, s_scale, ln_s_scale, a_sep, b_energy, b_suffix, gamma_s, j0,
                      table_v, table_dv, x_lo, inv_step,
                      out_u, out_q, out_dq, out_energy, out_status):
    """Rows of :func:`separation_one`; out_status 0 ok, BAD_INPUT for p <= 0 or not finite,
    NONFINITE when a sum is not finite, SEPARATION_UNDERFLOW when u or Q lies below
    ``UNDERFLOW_BOUND`` (u ~ exp(-p^2/(4 G1)) at large p: terms of the sums may have
    underflowed, u may be 0 and K = p/Q inf or inexact)."""
    for i in prange(pressure.size):
        p = pressure[i]
        if not (p > 0.0) or not math.isfinite(p):
            out_u[i] = math.nan
            out_q[i] = math.nan
            out_dq[i] = math.nan
            out_energy[i] = math.nan
            out_status[i] = BAD_INPUT
            continue
        u, q, dq, energy = separation_one(p, s_scale, ln_s_scale, a_sep, b_energy, b_suffix,
                                          gamma_s, j0, table_v, table_dv, x_lo, inv_step)
        out_u[i] = u
        out_q[i] = q
        out_dq[i] = dq
        out_energy[i] = energy
        ok = math.isfinite(u) and math.isfinite(q) and math.isfinite(energy)
        if not ok:
            out_status[i] = NONFINITE
        elif u < UNDERFLOW_BOUND or q < UNDERFLOW_BOUND:
            out_status[i] = SEPARATION_UNDERFLOW
        else:
            out_status[i] = OK


separation_sweep, separation_sweep_prange = njit_sweeps(_separation_sweep)
