"""Special functions and exact moving-wall solutions usable inside ``@njit`` code."""
from __future__ import annotations

import math

from .._jit import njit_serial

SQRT2 = math.sqrt(2.0)
SQRT2PI = math.sqrt(2.0 * math.pi)


@njit_serial
def ndtr(u):
    """Standard normal cdf Phi(u), full relative accuracy in the lower tail."""
    return 0.5 * math.erfc(-u / SQRT2)


@njit_serial
def log_ndtr(u):
    """log Phi(u), accurate for very negative u (asymptotic series below -20)."""
    if u > -20.0:
        return math.log(0.5 * math.erfc(-u / SQRT2))
    # Phi(u) ~ phi(u)/(-u) * (1 - 1/u^2 + 3/u^4 - 15/u^6)
    u2 = u * u
    series = 1.0 - 1.0 / u2 + 3.0 / (u2 * u2) - 15.0 / (u2 * u2 * u2)
    return -0.5 * u2 - math.log(-u * SQRT2PI) + math.log(series)


@njit_serial
def normal_pdf(x, var):
    """Density of a centred normal law of variance ``var`` at ``x``."""
    return math.exp(-0.5 * x * x / var) / math.sqrt(2.0 * math.pi * var)


@njit_serial
def _image_weight(b, y0, u2):
    """exp(-b*y0) * Phi(u2) without overflow."""
    lg = -b * y0 + log_ndtr(u2)
    if lg < -745.0:
        return 0.0
    return math.exp(lg)


@njit_serial
def linear_wall_area_moment(y0, b, G):
    """Exact area and first moment for a wall moving linearly in diffusion time.

    Distance to the wall y = sigma + sigma_a(G) with sigma_a = a + b G, start y0 > 0 at G = 0.
    Returns (A, M1) with A = int_0^inf Q dy and M1 = int_0^inf y Q dy, where
    Q = N(y - y0 - bG; 2G) - exp(-b y0) N(y + y0 - bG; 2G)  .
    M1 = (y0 + bG) Phi(u1) - (bG - y0) exp(-b y0) Phi(u2), u1,2 = (bG +- y0)/sqrt(2G).
    """
    if G <= 0.0:
        return 1.0, y0
    s = math.sqrt(2.0 * G)
    mu1 = y0 + b * G
    mu2 = b * G - y0
    p1 = ndtr(mu1 / s)
    w2 = _image_weight(b, y0, mu2 / s)
    area = p1 - w2
    m1 = mu1 * p1 - mu2 * w2
    if area < 0.0:
        area = 0.0
    if m1 < 0.0:
        m1 = 0.0
    return area, m1


@njit_serial
def linear_wall_density(y, y0, b, G):
    """Exact density Q(y, G) >= 0 of the linearly moving wall problem (y >= 0)."""
    if y <= 0.0:
        return 0.0
    v = 2.0 * G
    d1 = y - y0 - b * G
    # Q = N(d1) (1 - exp(-b y0) N(d2)/N(d1)) with d2 = y + y0 - bG; since
    # d2^2 - d1^2 = 4 y0 (y - bG), the exponent is exactly -y0 y / G (<= 0, no overflow)
    e = -y0 * y / G
    q = normal_pdf(d1, v) * (-math.expm1(e))
    if q < 0.0:
        q = 0.0
    return q
