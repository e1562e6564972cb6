"""Closed forms of a wall moving linearly in G, sigma_a(G) = a + b G (adhesion).

Brownian motion with drift absorbed at a fixed point (Girsanov + images):
:func:`linear_boundary_area`, :func:`linear_boundary_density`,
:func:`linear_boundary_detachment_rate` and :func:`linear_boundary_load`, written for full
relative accuracy also for tiny areas and ``exp(-b y0)`` beyond the float range
(:class:`_Drift` carries the scaled quantities in double-double).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # names of the type hints only
    from numpy.typing import ArrayLike

import numpy as np
from .special import erfc, erfcx

from persson_fast._validation import (
    as_float_array,
    check_finite,
)
from .base import (_INV_SQRT_PI, _broadcast_flat, _check_G, _erfcx_difference,
                            _exp_neg_square_over, _result, _two_prod, _two_sum)
from .images import _gaussian_times_absorption

__all__ = ["linear_boundary_area", "linear_boundary_density", "linear_boundary_detachment_rate",
           "linear_boundary_load"]

# Scaled arguments beyond this are clipped: every formula has reached its limit long before,
# and clipping keeps inf * 0 out of the intermediate products.
_ARG_CLIP = 1e100


# --------------------------------------------------------------------------------------------
# linearly moving wall sigma_a(G) = a + b G
# --------------------------------------------------------------------------------------------
def _linear_inputs(pressure, G, a, b, extra=None):
    pressure = as_float_array(pressure, "pressure", "Pa")
    check_finite(pressure, "pressure", "Pa")
    G = _check_G(G)
    a = as_float_array(a, "a", "Pa")
    check_finite(a, "a", "Pa")
    b = as_float_array(b, "b", "1/Pa")
    check_finite(b, "b", "1/Pa")
    arrays = [pressure, G, a, b] if extra is None else [extra, pressure, G, a, b]
    shape, arrays = _broadcast_flat(*arrays)
    p, a_ = arrays[-4], arrays[-2]
    y0 = p + a_
    bad = y0 < 0
    if np.any(bad):
        i = int(np.argmax(bad))
        raise ValueError(
            "pressure must be >= -a [Pa]: the start sigma0 must lie on or above the absorbing wall "
            f"sigma = -a (sigma0 < -a means the surfaces have already separated, A = 0); got "
            f"pressure = {float(p[i])!r} with a = {float(a_[i])!r}"
        )
    return shape, arrays, y0


class _Drift:
    """Scaled quantities of the linear-wall problem on the entries with G > 0.

    alpha = y0 / (2 sqrt G) >= 0, c = b sqrt(G) / 2, by0 = b y0 (= 4 alpha c) and
    gauss = exp(-w^2), w = alpha + c = (y0 + b G) / (2 sqrt G), whose exponent is carried in
    double-double (y0 = sigma0 + a and b G as error-free sums and products) so that the Gaussian
    factor of tiny areas keeps full relative accuracy even where w^2 ~ 700.
    """

    __slots__ = ("alpha", "c", "by0", "exp_by0", "gauss")

    def __init__(self, pressure, G, a, b):
        y0_hi, y0_lo = _two_sum(pressure, a)
        root = np.sqrt(G)
        with np.errstate(over="ignore", invalid="ignore"):
            self.alpha = np.minimum(y0_hi / (2.0 * root), _ARG_CLIP)
            self.c = np.clip(0.5 * b * root, -_ARG_CLIP, _ARG_CLIP)
            self.by0, by0_err = _two_prod(b, y0_hi)
            by0_lo = by0_err + b * y0_lo
            self.exp_by0 = np.exp(-self.by0) * (1.0 - np.where(np.isfinite(by0_lo), by0_lo, 0.0))
            bg, bg_err = _two_prod(b, G)
            s, s_err = _two_sum(y0_hi, bg)
            s_lo = s_err + bg_err + y0_lo
        self.gauss = _exp_neg_square_over(s, np.where(np.isfinite(s_lo), s_lo, 0.0), 4.0 * G)

    def take(self, mask):
        new = object.__new__(_Drift)
        for name in self.__slots__:
            setattr(new, name, getattr(self, name)[mask])
        return new


def _linear_area_scaled(st: _Drift) -> np.ndarray:
    """A = (1/2)[erfc(-(alpha + c)) - exp(-4 alpha c) erfc(alpha - c)], alpha >= 0, stably.

    With u = |c| and w = alpha + c the area is rewritten, exactly, as a sum of non-negative
    terms in each regime:

    * alpha - u > 1 (A > 0.8):  c >= 0: 1 - [exp(-b y0) erfc(alpha-u) + erfc(alpha+u)] / 2;
      c < 0: 1 - [erfc(alpha-u) + exp(-w^2) erfcx(alpha+u)] / 2;
    * otherwise, with D = erfcx(u - alpha) - erfcx(u + alpha) (see _erfcx_difference):
      c >= 0: -expm1(-b y0) + exp(-w^2) D / 2;   c < 0: exp(-w^2) D / 2.
    """
    alpha, c = st.alpha, st.c
    u = np.abs(c)
    out = np.empty(alpha.shape)
    far = alpha - u > 1.0
    up = c >= 0
    m = far & up
    al, uu = alpha[m], u[m]
    out[m] = 1.0 - 0.5 * (st.exp_by0[m] * erfc(al - uu) + erfc(al + uu))
    m = far & ~up
    al, uu = alpha[m], u[m]
    out[m] = 1.0 - 0.5 * (erfc(al - uu) + st.gauss[m] * erfcx(al + uu))
    near = ~far
    d = _erfcx_difference(u[near], alpha[near])
    gauss = st.gauss[near]
    res = 0.5 * gauss * d
    upn = up[near]
    res[upn] += -np.expm1(-st.by0[near][upn])
    out[near] = res
    return out


def _linear_survivor_parts(st: _Drift):
    """Return (erfc(-(alpha+c)), T2) with T2 = exp(-4 alpha c) erfc(alpha - c) >= 0, overflow-free.

    B = [erfc(-(alpha+c)) + T2] / 2 = Phi(z1) + exp(-b y0) Phi(z2) and B - A = T2.
    """
    alpha, c = st.alpha, st.c
    w = alpha + c
    # erfc(-w) for w < 0 is a Gaussian tail: take its exponent from the double-double gauss
    first = np.where(w < 0, st.gauss * erfcx(np.abs(w)), erfc(-w))
    t2 = np.empty(alpha.shape)
    m = alpha >= c
    t2[m] = st.gauss[m] * erfcx(alpha[m] - c[m])
    m = ~m
    t2[m] = st.exp_by0[m] * erfc(alpha[m] - c[m])
    return first, t2


def linear_boundary_area(pressure: ArrayLike, G: ArrayLike, a: ArrayLike,
                         b: ArrayLike) -> float | np.ndarray:
    """Contact area for an absorbing wall moving linearly in G, sigma_a(G) = a + b G.

    Parameters
    ----------
    pressure : array_like
        Nominal pressure sigma0 (tensile allowed) with sigma0 >= -a. [Pa]
    G : array_like
        Diffusion time >= 0. [Pa^2]
    a : array_like
        Wall position at G = 0: the wall sits at sigma = -a. [Pa]
    b : array_like
        Wall speed d sigma_a / dG, either sign (b > 0: the wall recedes). [1/Pa]

    Returns
    -------
    area : float or ndarray
        A/A0 = Phi((y0 + bG)/sqrt(2G)) - exp(-b y0) Phi((bG - y0)/sqrt(2G)), y0 = sigma0 + a.
        At G = 0: 1 for y0 > 0; y0 = 0 (start on the wall) gives 0 for all G. [-]

    Raises
    ------
    ValueError
        On non-finite input, negative `G`, or `pressure` < -`a`.

    See Also
    --------
    persson_fast.linear_boundary_density : The stress distribution.
    persson_fast.linear_boundary_load : The load in contact.
    persson_fast.linear_boundary_detachment_rate : The rate at which area detaches.
    persson_fast.images_area : The resting wall, a = b = 0.

    Notes
    -----
    With y = sigma + sigma_a(G) the stress performs a Brownian motion with drift b
    and variance 2G, absorbed at y = 0; Girsanov's theorem plus the image at -y0 gives the
    formula (the Wiener process with drift and an absorbing barrier, e.g. Cox & Miller,
    The Theory of Stochastic Processes, 1965, ch. 5; here the diffusion coefficient is 1 per unit
    G).  In scaled variables alpha = y0/(2 sqrt G), c = b sqrt(G)/2 it
    reads A = [erfc(-(alpha+c)) - exp(-4 alpha c) erfc(alpha-c)]/2; the implementation
    (_linear_area_scaled) rewrites it as non-negative terms with erfcx and expm1 and evaluates the
    one remaining near-cancelling difference, erfcx(u-alpha) - erfcx(u+alpha), as the integral
    of its (positive) derivative by 24-point Gauss-Legendre; the Gaussian factor exp(-(alpha+c)^2)
    takes its exponent (y0 + bG)^2/4G in double-double.  Measured against mpmath: relative error
    < 2e-15 for y0/sqrt(G) in [1e-8, 1e3], abs(b) sqrt(G) <= 50, sqrt(G) from 1 Pa to 1e9 Pa.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> print(np.round(pf.linear_boundary_area(1.0, [0.5, 1.0], 0.2, 0.1), 6))
    [0.783421 0.627366]
    >>> print(pf.linear_boundary_area(1.0, 1.0, 0.0, 0.0) == pf.images_area(1.0, 1.0))
    True
    """
    shape, (p, g, a_, b_), y0 = _linear_inputs(pressure, G, a, b)
    out = np.where(y0 > 0, 1.0, 0.0)
    pos = g > 0
    out[pos] = _linear_area_scaled(_Drift(p[pos], g[pos], a_[pos], b_[pos]))
    return _result(out, shape)


def linear_boundary_detachment_rate(pressure: ArrayLike, G: ArrayLike, a: ArrayLike,
                                    b: ArrayLike) -> float | np.ndarray:
    """Detachment rate g = -d(A/A0)/dG for the linearly moving wall sigma_a = a + b G.

    Parameters
    ----------
    pressure : array_like
        Nominal pressure sigma0 >= -a. [Pa]
    G : array_like
        Diffusion time >= 0. [Pa^2]
    a : array_like
        Wall offset (wall at sigma = -a at G = 0). [Pa]
    b : array_like
        Wall speed d sigma_a / dG. [1/Pa]

    Returns
    -------
    rate : float or ndarray
        g = y0 (4 pi G^3)^(-1/2) exp(-(y0 + b G)^2 / 4G), y0 = sigma0 + a; 0 at G = 0
        (the G -> 0+ limit for y0 > 0; for y0 = 0 the whole mass leaves at G = 0). [1/Pa^2]

    Raises
    ------
    ValueError
        On non-finite input, negative `G`, or `pressure` < -`a`.

    See Also
    --------
    persson_fast.linear_boundary_area : The area in contact.
    persson_fast.linear_boundary_load : The load in contact.

    Notes
    -----
    The first-passage-time density of Brownian motion with drift b (variance 2G)
    to the level -y0 (inverse-Gaussian law).  Evaluated as alpha exp(-(alpha+c)^2)/(sqrt(pi) G)
    with alpha = y0/(2 sqrt G), c = b sqrt(G)/2 (no overflow; exact zero far in the tails).

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> print(f"{pf.linear_boundary_detachment_rate(1.0, 1.0, 0.2, 0.1):.6f}")
    0.221864
    """
    shape, (p, g, a_, b_), y0 = _linear_inputs(pressure, G, a, b)
    out = np.zeros(g.shape)
    pos = g > 0
    st = _Drift(p[pos], g[pos], a_[pos], b_[pos])
    with np.errstate(over="ignore"):  # g beyond the float range (G ~ 1e-300) is inf
        out[pos] = st.alpha * st.gauss * _INV_SQRT_PI / g[pos]
    return _result(out, shape)


def linear_boundary_density(sigma: ArrayLike, pressure: ArrayLike, G: ArrayLike,
                            a: ArrayLike, b: ArrayLike) -> float | np.ndarray:
    """Stress distribution P(sigma, G) for the linearly moving wall sigma_a = a + b G.

    Parameters
    ----------
    sigma : array_like
        Local stress at which to evaluate P. [Pa]
    pressure : array_like
        Nominal pressure sigma0 >= -a. [Pa]
    G : array_like
        Diffusion time >= 0. [Pa^2]
    a : array_like
        Wall offset (wall at sigma = -a at G = 0). [Pa]
    b : array_like
        Wall speed d sigma_a / dG. [1/Pa]

    Returns
    -------
    density : float or ndarray
        With y = sigma + a + b G and y0 = sigma0 + a:
        P = N(y - y0 - bG; 2G) - exp(-b y0) N(y + y0 - bG; 2G) for y >= 0, 0 for y < 0
        (N(x; v): normal pdf of variance v).  At G = 0: +inf at sigma = sigma0 (if y0 > 0),
        0 elsewhere. [1/Pa]

    Raises
    ------
    ValueError
        On non-finite input, negative `G`, or `pressure` < -`a`.

    See Also
    --------
    persson_fast.linear_boundary_area : Its integral over the contact.
    persson_fast.images_density : The resting wall.

    Notes
    -----
    Girsanov + images.  The ratio of the image term to the direct term is exactly
    exp(-y y0 / G), and y - y0 - bG = sigma - sigma0, so the density is evaluated as
    N(sigma - sigma0; 2G) * (-expm1(-y y0 / G)): no overflow of exp(-b y0), full relative
    accuracy next to the wall.  Its integral over y >= 0 is :func:`linear_boundary_area`.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> sigma = np.array([-0.2, 0.0, 1.0])
    >>> print(np.round(pf.linear_boundary_density(sigma, 1.0, 1.0, 0.2, 0.1), 6))
    [0.022255 0.066419 0.222817]
    """
    sigma = as_float_array(sigma, "sigma", "Pa")
    check_finite(sigma, "sigma", "Pa")
    shape, (s, p, g, a_, b_), y0 = _linear_inputs(pressure, G, a, b, extra=sigma)
    # y = sigma + a + b G and its rounding error, so that P keeps its relative accuracy next to
    # the wall where the three terms cancel
    bg, bg_err = _two_prod(b_, g)
    t, t_err = _two_sum(s, a_)
    y, y_err = _two_sum(t, bg)
    with np.errstate(invalid="ignore", over="ignore"):
        y_lo = y_err + t_err + bg_err
    y_lo = np.where(np.isfinite(y_lo), y_lo, 0.0)
    return _result(_gaussian_times_absorption(s, p, g, y, y_lo, y0), shape)


def linear_boundary_load(pressure: ArrayLike, G: ArrayLike, a: ArrayLike,
                         b: ArrayLike) -> float | np.ndarray:
    """Load carried by the contact, integral of sigma P over sigma >= -sigma_a(G), for sigma_a = a + bG.

    Parameters
    ----------
    pressure : array_like
        Nominal pressure sigma0 >= -a. [Pa]
    G : array_like
        Diffusion time >= 0. [Pa^2]
    a : array_like
        Wall offset (wall at sigma = -a at G = 0). [Pa]
    b : array_like
        Wall speed d sigma_a / dG. [1/Pa]

    Returns
    -------
    load : float or ndarray
        L = y0 B - a A = sigma0 B + a (B - A), where A is :func:`linear_boundary_area`,
        B = Phi((y0+bG)/sqrt(2G)) + exp(-b y0) Phi((bG-y0)/sqrt(2G)) and y0 = sigma0 + a.
        At G = 0: sigma0 (y0 > 0) or 0 (y0 = 0). [Pa]

    Raises
    ------
    ValueError
        On non-finite input, negative `G`, or `pressure` < -`a`.

    See Also
    --------
    persson_fast.linear_boundary_area : The area in contact.
    persson_fast.linear_boundary_detachment_rate : The rate at which area detaches.
    persson_fast.images_moments : The resting wall.

    Notes
    -----
    Derivation (this module): with y = sigma + sigma_a, integral y P dy over y >= 0 equals
    m Phi(m/sqrt(2G)) - m' exp(-b y0) Phi(m'/sqrt(2G)), m = y0 + bG, m' = bG - y0, because the two
    Gaussian-pdf terms of integral_0^inf y N(y - mu; v) dy = mu Phi(mu/sqrt v) + sqrt(v) phi(mu/sqrt v)
    cancel exactly (exp(-b y0) phi(m'/sqrt v) = phi(m/sqrt v)).  That is bG A + y0 B; subtracting
    sigma_a A = (a + bG) A gives L = y0 B - a A.  It satisfies the load bookkeeping of the adhesive model (detachment at -sigma_a),
    L(G) = sigma0 + integral_0^G sigma_a(G') g(G') dG'.  B - A = exp(-4 alpha c) erfc(alpha - c)
    >= 0, so the form sigma0 B + a (B - A) (a >= 0) or y0 B + abs(a) A (a < 0) is a sum of
    non-negative terms whenever sigma0 >= 0 or a < 0; only for a tensile start (sigma0 < 0 < a),
    where L itself may cross zero, is the accuracy absolute (relative to abs(sigma0) B + a (B - A)).

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> print(f"{pf.linear_boundary_load(1.0, 1.0, 0.2, 0.1):.6f}")
    1.092123
    """
    shape, (p, g, a_, b_), y0 = _linear_inputs(pressure, G, a, b)
    out = np.where(y0 > 0, p, 0.0)
    pos = g > 0
    if np.any(pos):
        st = _Drift(p[pos], g[pos], a_[pos], b_[pos])
        first, t2 = _linear_survivor_parts(st)
        big_b = 0.5 * (first + t2)
        ap, pp, yp = a_[pos], p[pos], y0[pos]
        res = np.empty(st.alpha.shape)
        m = ap >= 0
        res[m] = pp[m] * big_b[m] + ap[m] * t2[m]
        m = ~m
        if np.any(m):
            area = _linear_area_scaled(st.take(m))
            res[m] = yp[m] * big_b[m] - ap[m] * area
        out[pos] = res
    return _result(out, shape)
