"""Slow, obvious twins of the mean separation, contact stiffness and elastic energy (for tests).

Persson's theory without adhesion (B.N.J. Persson, Phys. Rev. Lett. 99, 125502 (2007);
C. Yang and B.N.J. Persson, J. Phys.: Condens. Matter 20, 215214 (2008)), straight from the
formulas with ``scipy.integrate.quad`` (epsrel 1e-11, and an absolute floor of 1e-14 of the
whole integral, from a rough first pass, per piece; see :func:`_piecewise`), no numba, no tables
and no code shared with the compiled routines. Each call takes up to a few seconds. With

.. math::

    w(q) = \\left(\\pi \\int_{q_0}^{q} q'^3 C(q') dq'\\right)^{-1/2}, \\quad
    P(q, p) = \\mathrm{erf}(w p / E^*), \\quad S(P) = \\gamma_S + (1 - \\gamma_S) P^2

(``energy_correction`` = γ_S; None means S = 1, i.e. γ_S = 1):

* :func:`elastic_energy_quad` -- U_el(p) = (π/2) E* ∫ q² C P S dq.
* :func:`separation_quad` -- the double integral
  ū(p) = √π ∫ dq q² C w ∫_p^∞ (dp'/p') [γ_S + 3(1-γ_S) P²(q, p')] exp(-(w p'/E*)²),
  both integrals by ``quad`` (the inner one also for S = 1).
* :func:`separation_quad_e1` -- for S = 1 only, the inner integral is E1((w p/E*)²)/2
  (``scipy.special.exp1``), a second form.
* :func:`stiffness_quad` -- K(p) = -dp/dū
  = p / (√π ∫ dq q² C w [γ_S + 3(1-γ_S) P²] e^{-(wp/E*)²}).
* :func:`separation_energy_route` -- ū(p) = ∫_p^∞ (1/p') dU_el/dp' dp'
  = -U_el(p)/p + ∫_p^∞ U_el(p')/p'² dp' (integration by parts) with :func:`elastic_energy_quad`
  inside the outer quadrature over ln p'.

The q integrals run over ln q on the pieces between the surface's breakpoints (cut at least
every unit of ln q), except on the first piece [q0, qa], qa = min(2 q0, first breakpoint),
where w has the 1/sqrt(q - q0) singularity; there q = q0 + (qa - q0) τ², τ in [0, 1], makes the
integrand smooth. The pieces are also cut where w p/E* = 4, 1, 1/4 (the step of P; found by
``brentq`` in ln(q - q0)) and at every decade of τ above the first of those cuts.
The surface supplies C(q) (``psd``) and the exact moment ∫_{q0}^{q} q'^3 C dq' (``moment``);
both are cached per q within one call. Next to q0 the
points are carried as q - q0, and the moment at fl(q0 + δ) is corrected by the rounding
residual times q³C, so that w stays smooth in τ even where q - q0 is below the spacing of
floats at q0 (tiny p).
"""
from __future__ import annotations

import math
import warnings

import numpy as np
from scipy.integrate import IntegrationWarning, quad
from scipy.optimize import brentq
from scipy.special import erf, erfc, exp1

#: requested relative accuracy of every outer (q or ln p') quadrature piece [-]
EPSREL_OUTER = 1e-11
#: requested relative accuracy of the inner (p') quadrature [-]
EPSREL_INNER = 1e-12
#: subinterval limit handed to quad [-]
LIMIT = 400
#: the Gaussian tails exp(-x) are cut at x = TAIL (e^-50 ~ 2e-22) [-]
TAIL = 50.0
#: absolute floor of each piece, relative to the size of the whole integral [-]
ROUNDOFF = 1e-14
#: values of w p/E* at which the q range is cut (the step of erf) [-]
T_CUTS = (4.0, 1.0, 0.25)


def _gamma(energy_correction):
    """γ_S as a float; None means S = 1 (γ_S = 1)."""
    if energy_correction is None:
        return 1.0
    g = float(energy_correction)
    if not math.isfinite(g):
        raise ValueError(f"energy_correction must be finite or None; got {energy_correction!r}")
    return g


def _quad(f, a, b, epsrel, epsabs=0.0):
    """``quad`` on [a, b]; returns the value only."""
    if b <= a:
        return 0.0
    val, _err = quad(f, a, b, epsabs=epsabs, epsrel=epsrel, limit=LIMIT)
    return val


def _piecewise(f, nodes, epsrel):
    """∫ f over the consecutive pieces [nodes[i], nodes[i+1]], summed with fsum.

    A first pass at relative accuracy 1e-6 gives the size I of the total; the final pass asks
    each piece for epsrel relative or ROUNDOFF * |I| absolute, so that pieces that add nothing
    (exponentially small tails, the rounding of q next to q0) are not pushed below rounding.
    """
    pairs = list(zip(nodes[:-1], nodes[1:]))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", IntegrationWarning)
        rough = math.fsum(abs(_quad(f, a, b, 1e-6)) for a, b in pairs)
    epsabs = ROUNDOFF * rough
    return math.fsum(_quad(f, a, b, epsrel, epsabs) for a, b in pairs)


class _Spectrum:
    """C(q) and w(q) of one surface, cached per q (the quadratures revisit the same nodes)."""

    def __init__(self, surface):
        self.surface = surface
        self.q0 = float(surface.q0)
        self.q1 = float(surface.q1)
        bps = np.asarray(surface.breakpoints(), dtype=float)
        self.breakpoints = sorted({self.q0, self.q1, *[float(b) for b in bps
                                                          if self.q0 < b < self.q1]})
        # end of the tau piece: 2 q0 or the first breakpoint above q0
        self.qa = min(2.0 * self.q0, self.breakpoints[1])
        self._cache = {}

    def m3(self, delta):
        """∫_{q0}^{q0 + delta} q'^3 C dq' for delta >= 0, also below the spacing of floats at q0.

        q = fl(q0 + delta) differs from q0 + delta by r = delta - (q - q0) (exact in float64);
        the moment at q is corrected by r q³ C(q) (error ~ r² d(q³C)/dq, far below rounding).
        Returns (q [1/m], M3 [m]).
        """
        q = min(self.q0 + delta, self.q1)
        r = delta - (q - self.q0) if q < self.q1 else 0.0
        m3 = float(self.surface.moment(3, self.q0, q)) if q > self.q0 else 0.0
        if r != 0.0:
            m3 += r * q ** 3 * float(self.surface.psd(q))
        return q, m3

    def cw(self, delta):
        """(q [1/m], C(q) [m^4], w(q) [-]) at q = q0 + delta; w = inf at delta = 0."""
        hit = self._cache.get(delta)
        if hit is None:
            q, m3 = self.m3(delta)
            c = float(self.surface.psd(q))
            w = 1.0 / math.sqrt(math.pi * m3) if m3 > 0.0 else math.inf
            hit = (q, c, w)
            self._cache[delta] = hit
        return hit

    def delta_at_t(self, t, p, e_star):
        """The q - q0 in (0, q1 - q0) where w(q) p/E* = t (w decreases), or None. [1/m]"""
        target = (p / (t * e_star)) ** 2 / math.pi  # M3 at that q
        if not (target < self.m3(self.q1 - self.q0)[1]):
            return None
        # unknown y = ln(q - q0): resolves q next to q0
        lo = math.log(self.q0) - 60.0 * math.log(10.0)  # q - q0 = 1e-60 q0
        hi = math.log(self.q1 - self.q0)

        def f(y):
            return math.log(max(self.m3(math.exp(y))[1], 1e-300)) - math.log(target)

        if f(lo) >= 0.0:
            return None
        return math.exp(brentq(f, lo, hi, xtol=1e-14, rtol=1e-14, maxiter=500))

    def integrate(self, integrand, cuts=()):
        """∫_{q0}^{q1} integrand(q, C, w) dq, piecewise (see the module docstring).

        ``cuts`` are values of q - q0 (None ignored) where the pieces are also cut. [1/m]
        """
        q0, q1, qa = self.q0, self.q1, self.qa
        d = qa - q0
        cuts = sorted(c for c in cuts if c is not None and 0.0 < c < q1 - q0)

        # first piece: q = q0 + d tau^2, dq = 2 d tau dtau (q - q0 = d tau^2 kept unrounded)
        def f_tau(tau):
            q, c, w = self.cw(d * tau * tau)
            return integrand(q, c, w) * 2.0 * d * tau

        taus = {math.sqrt(c / d) for c in cuts if c < d}
        if taus:            # below the step of P the integrand goes like ln(tau): cut decades
            taus.update(10.0 ** -k for k in range(1, 40) if 10.0 ** -k > min(taus))
        taus = [0.0] + sorted(taus) + [1.0]
        cuts = [q0 + c for c in cuts if c >= d]

        # the rest in x = ln q, cut at breakpoints, at the given cuts and every unit of ln q
        nodes = {math.log(qa), math.log(q1)}
        nodes.update(math.log(b) for b in self.breakpoints if qa < b < q1)
        nodes.update(math.log(c) for c in cuts if qa < c < q1)
        x = math.log(qa)
        while x + 1.0 < math.log(q1):
            x += 1.0
            nodes.add(x)
        nodes = sorted(nodes)

        def f_log(x):
            q, c, w = self.cw(min(math.exp(x), q1) - q0)
            return integrand(q, c, w) * q

        # one integrand over [0, 1] (tau) + [1, ...] (ln q shifted), so one _piecewise call
        shift = 1.0 - nodes[0]

        def f_all(v):
            return f_tau(v) if v <= 1.0 else f_log(v - shift)

        return _piecewise(f_all, taus + [x + shift for x in nodes[1:]], EPSREL_OUTER)

    def cuts(self, p, e_star):
        """The q - q0 where w p/E* crosses T_CUTS. [1/m]"""
        return [self.delta_at_t(t, p, e_star) for t in T_CUTS]


def _check(p, e_star):
    p = float(p)
    e_star = float(e_star)
    if not (math.isfinite(p) and p > 0.0):
        raise ValueError(f"p must be finite and > 0 [Pa]; got {p!r}")
    if not (math.isfinite(e_star) and e_star > 0.0):
        raise ValueError(f"e_star must be finite and > 0 [Pa]; got {e_star!r}")
    return p, e_star


# ------------------------------------------------------------------------------------------
# elastic energy
# ------------------------------------------------------------------------------------------
def _energy(spec, p, e_star, gamma):
    def f(q, c, w):
        big_p = 1.0 if math.isinf(w) else erf(w * p / e_star)
        return q * q * c * big_p * (gamma + (1.0 - gamma) * big_p * big_p)

    return 0.5 * math.pi * e_star * spec.integrate(f, spec.cuts(p, e_star))


def _energy_deficit(spec, p, e_star, gamma):
    """U_el(full contact) - U_el(p) = (π/2) E* ∫ q² C (1 - P S(P)) dq, without cancellation:
    1 - P S = erfc (γ_S + (1 - γ_S)(1 + P + P²)). [J/m^2]"""
    def f(q, c, w):
        if math.isinf(w):
            return 0.0
        t = w * p / e_star
        big_p = erf(t)
        return q * q * c * erfc(t) * (gamma + (1.0 - gamma) * (1.0 + big_p + big_p * big_p))

    return 0.5 * math.pi * e_star * spec.integrate(f, spec.cuts(p, e_star))


def elastic_energy_quad(surface, p, e_star, energy_correction=None):
    """Elastic energy per nominal area stored at the squeezing pressure p, by ``quad``.

    Parameters
    ----------
    surface : persson_fast.Surface
        The rough surface (C(q), band [q0, q1]).
    p : float
        Nominal squeezing pressure, > 0. [Pa]
    e_star : float
        Effective modulus E/(1-ν²), > 0. [Pa]
    energy_correction : float or None, optional
        γ_S of S = γ_S + (1-γ_S) P²; None (default) means S = 1. [-]

    Returns
    -------
    float
        :math:`U_{el}(p) = (\\pi/2) E^* \\int_{q_0}^{q_1} q^2 C(q) P(q,p) S(P) dq`. [J/m^2]
    """
    p, e_star = _check(p, e_star)
    return _energy(_Spectrum(surface), p, e_star, _gamma(energy_correction))


# ------------------------------------------------------------------------------------------
# mean separation, double quadrature
# ------------------------------------------------------------------------------------------
def _inner(t0, gamma):
    """∫_p^∞ (dp'/p') [γ + 3(1-γ) P²(p')] exp(-(w p'/E*)²) with t0 = w p/E*, by ``quad``.

    With p' = p e^x and t = t0 e^x it is
    e^{-t0²} ∫_0^X [γ + 3(1-γ) erf²(t)] exp(-t0² (e^{2x} - 1)) dx, cut at X where
    t0² (e^{2X} - 1) = TAIL and at x = -ln t0 (t = 1) when t0 < 1. [-]
    """
    t2 = t0 * t0
    if not t2 < 1400.0:            # e^{-t0^2} underflows: the integral is 0 in float64
        return 0.0

    def f(x):
        t = t0 * math.exp(x)
        s = gamma if gamma == 1.0 else gamma + 3.0 * (1.0 - gamma) * erf(t) ** 2
        return s * math.exp(-t2 * math.expm1(2.0 * x))

    x_end = 0.5 * math.log1p(TAIL / t2)
    nodes = [0.0, x_end]
    if t0 < 1.0:
        nodes.insert(1, -math.log(t0))
    return math.exp(-t2) * _piecewise(f, nodes, EPSREL_INNER)


def separation_quad(surface, p, e_star, energy_correction=None):
    """Mean interfacial separation by the literal double quadrature.

    Parameters
    ----------
    surface : persson_fast.Surface
        The rough surface (C(q), band [q0, q1]).
    p : float
        Nominal squeezing pressure, > 0. [Pa]
    e_star : float
        Effective modulus E/(1-ν²), > 0. [Pa]
    energy_correction : float or None, optional
        γ_S of S = γ_S + (1-γ_S) P²; None (default) means S = 1. [-]

    Returns
    -------
    float
        :math:`\\bar u(p) = \\sqrt\\pi \\int dq\\, q^2 C w \\int_p^\\infty (dp'/p')
        [\\gamma_S + 3(1-\\gamma_S) P^2(q,p')] e^{-(w p'/E^*)^2}`, the inner integral by
        ``quad`` too (also for S = 1). [m]
    """
    p, e_star = _check(p, e_star)
    gamma = _gamma(energy_correction)
    spec = _Spectrum(surface)

    def f(q, c, w):
        if math.isinf(w):
            return 0.0
        return q * q * c * w * _inner(w * p / e_star, gamma)

    return math.sqrt(math.pi) * spec.integrate(f, spec.cuts(p, e_star))


def separation_quad_e1(surface, p, e_star, energy_correction=None):
    """Mean interfacial separation for S = 1 with the inner integral as E1 (second form).

    Parameters
    ----------
    surface : persson_fast.Surface
        The rough surface (C(q), band [q0, q1]).
    p : float
        Nominal squeezing pressure, > 0. [Pa]
    e_star : float
        Effective modulus E/(1-ν²), > 0. [Pa]
    energy_correction : None or 1.0, optional
        Only S = 1 has the closed inner integral; any other γ_S raises ValueError. [-]

    Returns
    -------
    float
        :math:`\\bar u(p) = (\\sqrt\\pi/2) \\int dq\\, q^2 C w E_1((w p/E^*)^2)`. [m]
    """
    p, e_star = _check(p, e_star)
    if _gamma(energy_correction) != 1.0:
        raise ValueError("separation_quad_e1 needs S = 1 (energy_correction None or 1.0); "
                         f"got energy_correction = {energy_correction!r}")
    spec = _Spectrum(surface)

    def f(q, c, w):
        if math.isinf(w):
            return 0.0
        t = w * p / e_star
        return q * q * c * w * 0.5 * exp1(t * t)

    return math.sqrt(math.pi) * spec.integrate(f, spec.cuts(p, e_star))


# ------------------------------------------------------------------------------------------
# stiffness
# ------------------------------------------------------------------------------------------
def stiffness_quad(surface, p, e_star, energy_correction=None):
    """Contact stiffness per nominal area K = -dp/dū, by ``quad``.

    Parameters
    ----------
    surface : persson_fast.Surface
        The rough surface (C(q), band [q0, q1]).
    p : float
        Nominal squeezing pressure, > 0. [Pa]
    e_star : float
        Effective modulus E/(1-ν²), > 0. [Pa]
    energy_correction : float or None, optional
        γ_S of S = γ_S + (1-γ_S) P²; None (default) means S = 1. [-]

    Returns
    -------
    float
        :math:`K(p) = p / (\\sqrt\\pi \\int dq\\, q^2 C w [\\gamma_S + 3(1-\\gamma_S) P^2]
        e^{-(w p/E^*)^2})`. [Pa/m]
    """
    p, e_star = _check(p, e_star)
    gamma = _gamma(energy_correction)
    spec = _Spectrum(surface)

    def f(q, c, w):
        if math.isinf(w):
            return 0.0
        t = w * p / e_star
        big_p = erf(t)
        return q * q * c * w * (gamma + 3.0 * (1.0 - gamma) * big_p * big_p) * math.exp(-t * t)

    return p / (math.sqrt(math.pi) * spec.integrate(f, spec.cuts(p, e_star)))


# ------------------------------------------------------------------------------------------
# mean separation, energy route
# ------------------------------------------------------------------------------------------
def separation_energy_route(surface, p, e_star, energy_correction=None):
    """Mean interfacial separation from the elastic energy: ū = ∫_p^∞ (1/p') dU_el/dp' dp'.

    Parameters
    ----------
    surface : persson_fast.Surface
        The rough surface (C(q), band [q0, q1]).
    p : float
        Nominal squeezing pressure, > 0. [Pa]
    e_star : float
        Effective modulus E/(1-ν²), > 0. [Pa]
    energy_correction : float or None, optional
        γ_S of S = γ_S + (1-γ_S) P²; None (default) means S = 1. [-]

    Returns
    -------
    float
        ū(p) [m].

    Notes
    -----
    By parts, ū = -U_el(p)/p + ∫_p^∞ U_el(p')/p'² dp' (U_el is bounded by its full-contact
    value U_f = (π E*/2) ∫ q² C dq, which S(1) = 1 makes independent of γ_S). Above
    p_m = max(p, p_f), p_f = E*/w(q1) (where w p/E* = 1 at q1, so contact is nearly full), the
    integrand is written with the deficit V = U_f - U_el (computed directly from erfc, no
    cancellation), which decays like erfc(p'/p_f):

    .. math:: \\bar u = -\\frac{U_{el}(p)}{p} + \\int_p^{p_m} \\frac{U_{el}}{p'^2} dp'
              + \\frac{U_f}{p_m} - \\int_{p_m}^{p_t} \\frac{V}{p'^2} dp'

    with p_t = p_f (t_m² + TAIL)^{1/2}, t_m = p_m/p_f. For p >= p_f this is
    V(p)/p - ∫_p^{p_t} V/p'² dp'. Both integrals run over ln p' (``quad``, cut every unit),
    with U_el and V by the same q quadrature as :func:`elastic_energy_quad`.
    """
    p, e_star = _check(p, e_star)
    gamma = _gamma(energy_correction)
    spec = _Spectrum(surface)
    u_full = 0.5 * math.pi * e_star * float(surface.moment(2, spec.q0, spec.q1))
    _q1, _c1, w1 = spec.cw(spec.q1 - spec.q0)
    p_f = e_star / w1
    p_m = max(p, p_f)
    p_t = p_f * math.sqrt((p_m / p_f) ** 2 + TAIL)

    def log_nodes(a, b):
        xs = [math.log(a)]
        while xs[-1] + 1.0 < math.log(b):
            xs.append(xs[-1] + 1.0)
        xs.append(math.log(b))
        return xs

    def outer(fun, a, b):
        if b <= a:
            return 0.0
        return _piecewise(fun, log_nodes(a, b), EPSREL_OUTER)

    def u_over_p(x):        # U_el(p')/p'^2 dp' = U_el(p')/p' d(ln p')
        pp = math.exp(x)
        return _energy(spec, pp, e_star, gamma) / pp

    def v_over_p(x):
        pp = math.exp(x)
        return _energy_deficit(spec, pp, e_star, gamma) / pp

    terms = [outer(u_over_p, p, p_m), u_full / p_m, -outer(v_over_p, p_m, p_t)]
    if p < p_f:
        terms.append(-_energy(spec, p, e_star, gamma) / p)
    else:                   # p = p_m: -U_el(p)/p + U_f/p = V(p)/p
        terms[1] = 0.0
        terms.append(_energy_deficit(spec, p, e_star, gamma) / p)
    return math.fsum(terms)
