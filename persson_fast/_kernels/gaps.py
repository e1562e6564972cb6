"""Compiled pieces of the interfacial gap distribution (:mod:`persson_fast.separation.gaps`), ``@njit``.

The separation carried by the spectrum above each edge of a partition in magnification
(``partial_separations``), from which the model layer forms the mean gap of the area that
leaves contact in each cell, and the mixture of truncated or mirrored Gaussians that makes the
distribution: its density and its cumulative distribution at given gaps
(``mixture_density``, ``mixture_cdf``). Lengths in metres, as the model layer passes them.
"""
from __future__ import annotations

import math

import numpy as np

from .._jit import njit_serial
from .separation import kfun_scaled

#: shapes of a component (see :mod:`persson_fast.separation.gaps`)
TRUNCATED = 0
FOLDED = 1

_SQRT2 = math.sqrt(2.0)
_SQRT_2PI = math.sqrt(2.0 * math.pi)
_SQRT_2_OVER_PI = math.sqrt(2.0 / math.pi)


@njit_serial
def partial_separations(p, area, first, s_nodes, k_nodes, gamma_s, j0, table_v, table_dv,
                        x_lo, inv_step, out):
    """u_zeta at every edge e of a partition of ln G: the separation carried by the spectrum
    above the edge, at the mean pressure p/A_e of the area still in apparent contact there,

        out[e] = sum_{m >= first[e]} k_m Kfun(s_m / A_e),   s_m = p / (2 sqrt(G_m)),

    with the quadrature weights k_m [m] of the nodes m above the edge (sqrt(pi) q^2 C w dq
    written in ln G, times the Gauss-Legendre weight), Kfun from its table (:func:`kfun_scaled`
    times exp(-x^2)). [m]
    """
    n_nodes = s_nodes.shape[0]
    for e in range(area.shape[0]):
        a = area[e]
        total = 0.0
        if a > 0.0:
            for m in range(first[e], n_nodes):
                x = s_nodes[m] / a
                x2 = x * x
                if x2 > 745.0:
                    continue
                v = kfun_scaled(math.log(x), x2, gamma_s, j0, table_v, table_dv, x_lo,
                                inv_step)
                total += k_nodes[m] * v * math.exp(-x2)
        out[e] = total


@njit_serial
def _log_norm_cdf(t):
    """ln Phi(t), the standard normal cdf, without underflow for t << 0."""
    x = -t / _SQRT2
    if x > 5.0:
        # Phi(t) = erfc(x)/2 = exp(-x^2) erfcx(x) / 2, erfcx by its continued fraction
        return -x * x + math.log(0.5 * _erfcx_large(x))
    return math.log(0.5 * math.erfc(x))


@njit_serial
def _erfcx_large(x):
    """erfcx(x) = exp(x^2) erfc(x) for x > 5 (continued fraction, relative error < 1e-15)."""
    # Lentz's algorithm for erfc(x) exp(x^2) sqrt(pi) = 1/(x + (1/2)/(x + 1/(x + (3/2)/(x + ...
    tiny = 1e-300
    f = x
    c = x
    d = 0.0
    for k in range(1, 200):
        a = 0.5 * k
        d = x + a * d
        if d == 0.0:
            d = tiny
        c = x + a / c
        if c == 0.0:
            c = tiny
        d = 1.0 / d
        delta = c * d
        f *= delta
        if abs(delta - 1.0) < 1e-16:
            break
    return 1.0 / (f * math.sqrt(math.pi))


@njit_serial
def truncated_mean(t):
    """Mean of N(t, 1) truncated to [0, inf): t + phi(t)/Phi(t). [-]"""
    return t + math.exp(-0.5 * t * t - _log_norm_cdf(t)) / _SQRT_2PI


@njit_serial
def truncated_location(r):
    """The location t (in units of the width) of N(t, 1) truncated to [0, inf) whose mean is
    r > 0: the root of t + phi(t)/Phi(t) = r, increasing in t (bisection to rounding, after
    a bracket from the limits t ~ -1/r for r -> 0 and t ~ r for r >> 1)."""
    lo = min(r - 1.0, -1.0 / r - 1.0)
    hi = r + 1.0
    while truncated_mean(lo) > r:
        lo = 2.0 * lo - 1.0
    while truncated_mean(hi) < r:
        hi = 2.0 * hi + 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid == lo or mid == hi:
            break
        if truncated_mean(mid) < r:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


@njit_serial
def component_locations(shape, mean, width, out_t):
    """Location of every component in units of its width: for TRUNCATED the t whose
    truncated mean is mean/width; for FOLDED mean/width itself (the published form, whose own
    mean exceeds it)."""
    for k in range(mean.shape[0]):
        r = mean[k] / width[k]
        out_t[k] = truncated_location(r) if shape == TRUNCATED else r


@njit_serial
def component_means(shape, t, width, out):
    """The mean gap of every component [m]: width (t + phi(t)/Phi(t)) truncated, and
    E|X| = width (t erf(t/sqrt 2) + sqrt(2/pi) exp(-t^2/2)) folded."""
    for k in range(t.shape[0]):
        tk = t[k]
        if shape == TRUNCATED:
            out[k] = width[k] * truncated_mean(tk)
        else:
            out[k] = width[k] * (tk * math.erf(tk / _SQRT2)
                                 + _SQRT_2_OVER_PI * math.exp(-0.5 * tk * tk))


@njit_serial
def mixture_density(shape, weight, t, width, gaps, out):
    """Density [1/m] of sum_k weight_k f_k(u) at the gaps u >= 0 (``out`` overwritten).

    TRUNCATED: f = phi(u/w - t) / (w Phi(t)) on u >= 0; FOLDED: f = (phi(u/w - t) +
    phi(u/w + t)) / w. Written in logarithms where Phi(t) underflows.
    """
    for i in range(gaps.shape[0]):
        out[i] = 0.0
    for k in range(weight.shape[0]):
        wk = width[k]
        tk = t[k]
        if weight[k] == 0.0:
            continue
        if shape == TRUNCATED:
            log_norm = math.log(weight[k] / (wk * _SQRT_2PI)) - _log_norm_cdf(tk)
            for i in range(gaps.shape[0]):
                z = gaps[i] / wk - tk
                e = log_norm - 0.5 * z * z
                if e > -745.0:
                    out[i] += math.exp(e)
        else:
            a = weight[k] / (wk * _SQRT_2PI)
            for i in range(gaps.shape[0]):
                x = gaps[i] / wk
                z1 = x - tk
                z2 = x + tk
                out[i] += a * (math.exp(-0.5 * z1 * z1) + math.exp(-0.5 * z2 * z2))


@njit_serial
def mixture_cdf(shape, weight, t, width, gaps, out):
    """sum_k weight_k F_k(u) at the gaps u >= 0 (``out`` overwritten), F_k the cumulative
    distribution of component k on [0, inf): the mass of the continuous part below u."""
    for i in range(gaps.shape[0]):
        out[i] = 0.0
    for k in range(weight.shape[0]):
        wk = width[k]
        tk = t[k]
        if weight[k] == 0.0:
            continue
        if shape == TRUNCATED:
            # F = 1 - Phi(t - u/w) / Phi(t)
            log_den = _log_norm_cdf(tk)
            for i in range(gaps.shape[0]):
                e = _log_norm_cdf(tk - gaps[i] / wk) - log_den
                out[i] += weight[k] * -math.expm1(min(e, 0.0))
        else:
            # F = Phi(u/w - t) - Phi(-u/w - t) = (erf((x - t)/sqrt2) + erf((x + t)/sqrt2)) / 2
            for i in range(gaps.shape[0]):
                x = gaps[i] / wk
                out[i] += weight[k] * 0.5 * (math.erf((x - tk) / _SQRT2)
                                             + math.erf((x + tk) / _SQRT2))
