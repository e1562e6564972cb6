"""Slow, obvious twin of :mod:`persson_fast.separation.gaps`, for tests.

The gap distribution straight from its definition, sharing no code with the package's
version beyond the surface's C(q) and G(q): the gap volume B(zeta) = A(zeta) u_zeta by
``scipy.integrate.quad`` in q (Kfun by quad of its defining integral), the mean gap of the
area leaving contact u1 = dB/dA by centred differences in ln zeta, the width h(zeta) by quad
of q C, and the density as the quad in ln zeta of -A'(zeta) times the component's density
(truncated or mirrored Gaussian, by scipy.stats / scipy.special).
"""
from __future__ import annotations

import math

import numpy as np
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import erf, erfc, ndtr


def _kfun(s, gamma_s):
    """Kfun(s) = int_s^inf [gamma_S + 3 (1 - gamma_S) erf(t)^2] exp(-t^2) dt / t."""
    if s > 27.0:
        return 0.0
    f = lambda t: (gamma_s + 3.0 * (1.0 - gamma_s) * erf(t) ** 2) * math.exp(-t * t) / t
    return quad(f, s, s + 30.0, limit=200, epsabs=0.0, epsrel=1e-12)[0]


def gap_volume(surface, e_star, p, zeta, gamma_s=1.0):
    """B(zeta) = A(zeta) sqrt(pi) int_{zeta q0}^{q1} q^2 C w Kfun(w p / (A E*)) dq. [m]"""
    q_lo = zeta * surface.q0
    g = float(surface.diffusion_time(q_lo, e_star)) if zeta > 1.0 else 0.0
    area = erf(p / (2.0 * math.sqrt(g))) if g > 0 else 1.0

    def integrand(lnq):
        q = math.exp(lnq)
        gq = float(surface.diffusion_time(q, e_star))
        if gq <= 0.0:
            return 0.0
        w = e_star / (2.0 * math.sqrt(gq))
        return q * q * q * float(surface.psd(q)) * w * _kfun(w * p / (area * e_star), gamma_s)

    val = quad(integrand, math.log(q_lo), math.log(surface.q1), limit=400, epsabs=0.0,
               epsrel=1e-10)[0]
    return area * math.sqrt(math.pi) * val, area


def components(surface, e_star, p, zeta, gamma_s=1.0, dlog=1e-4):
    """(-dA/dln zeta, u1, h) at the magnification zeta: the weight per unit ln zeta, the mean
    gap of the area leaving contact there (centred differences of B and A in ln zeta) and the
    rms of the roughness above zeta q0."""
    b_hi, a_hi = gap_volume(surface, e_star, p, zeta * math.exp(dlog), gamma_s)
    b_lo, a_lo = gap_volume(surface, e_star, p, zeta * math.exp(-dlog), gamma_s)
    weight = (a_lo - a_hi) / (2.0 * dlog)
    if not a_lo > a_hi:
        return 0.0, 0.0, 0.0
    u1 = (b_lo - b_hi) / (a_lo - a_hi)
    h2 = 2.0 * math.pi * quad(lambda q: q * float(surface.psd(q)), zeta * surface.q0,
                              surface.q1, limit=400)[0]
    return weight, u1, math.sqrt(h2)


def component_density(u, mean, width, shape):
    """The density at u >= 0 of a component of the given mean and width. [1/m]"""
    if shape == "folded":
        z1, z2 = (u - mean) / width, (u + mean) / width
        return (math.exp(-0.5 * z1 * z1) + math.exp(-0.5 * z2 * z2)) / (
            width * math.sqrt(2.0 * math.pi))
    r = mean / width

    def tmean(t):
        return t + math.exp(-0.5 * t * t) / math.sqrt(2.0 * math.pi) / ndtr(t)

    t = brentq(lambda t: tmean(t) - r, -1.0 / r - 10.0, r + 10.0, xtol=1e-14)
    z = u / width - t
    return math.exp(-0.5 * z * z) / (width * math.sqrt(2.0 * math.pi) * ndtr(t))


def density(surface, e_star, p, u, shape="truncated", gamma_s=1.0, zeta_lo=None):
    """P(u) at one gap u > 0 and pressure p: quad in ln zeta of -A' times the component
    density, from ``zeta_lo`` (default: where the weight is below 1e-14 of its peak) to
    zeta1. [1/m]"""
    z1 = surface.q1 / surface.q0

    def f(lnz):
        z = math.exp(lnz)
        if z >= z1 * math.exp(-2e-4):
            return 0.0
        w, u1, h = components(surface, e_star, p, z, gamma_s)
        return w * component_density(u, u1, h, shape) if w > 0 and u1 > 0 else 0.0

    lo = math.log(zeta_lo) if zeta_lo else 1e-6
    return quad(f, lo, math.log(z1), limit=200, epsabs=0.0, epsrel=1e-6)[0]


def contact_fraction(surface, e_star, p):
    """A(zeta1) = erf(p / (2 sqrt G1)). [-]"""
    g1 = float(surface.diffusion_time(surface.q1, e_star))
    return 1.0 - erfc(p / (2.0 * math.sqrt(g1)))
