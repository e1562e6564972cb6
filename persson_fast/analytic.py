"""Closed-form solutions of the stress diffusion.

Persson's stress distribution obeys the heat equation ``dP/dG = d2P/dsigma2`` in the
"diffusion time" ``G`` [Pa^2] (free variance ``2 G``), starting from ``P = delta(sigma - sigma0)``
at ``G = 0`` and absorbed at the wall ``sigma = -sigma_a(G)``.  Three boundaries have closed forms:

* ``sigma_a = 0`` (no adhesion): the method of images -- :func:`images_area`,
  :func:`images_density`, :func:`images_moments`, :func:`contact_area_no_adhesion`;
* ``sigma_a(G) = a + b G`` (a wall moving linearly in ``G``): Brownian motion with drift absorbed
  at a fixed point (Girsanov + images) -- :func:`linear_boundary_area`,
  :func:`linear_boundary_density`, :func:`linear_boundary_detachment_rate`,
  :func:`linear_boundary_load`;
* ``sigma_a = 0`` plus a second absorbing wall at a constant yield stress (Persson 2001) --
  :func:`plastic_area`.

They are the exact oracles for the numerical solvers, so they are written for full relative
accuracy (about 1e-13) also where the textbook form cancels catastrophically or overflows: tiny
areas (``sigma0 << sqrt(G)``), both normal cdfs close to 1, ``exp(-b y0)`` beyond the float range.
All functions are vectorised with numpy broadcasting; all arguments are SI; results are float64
(a numpy scalar for scalar input).  ``G = 0`` returns the ``G -> 0+`` limit.
"""
from __future__ import annotations

import numbers

import numpy as np
from scipy.special import erf, erfc, erfcx

from persson_fast._validation import (
    as_float_array,
    check_finite,
    check_nonnegative,
    check_positive,
)

__all__ = [
    "images_area",
    "images_density",
    "images_moments",
    "linear_boundary_area",
    "linear_boundary_density",
    "linear_boundary_detachment_rate",
    "linear_boundary_load",
    "plastic_area",
    "contact_area_no_adhesion",
]

_SQRT_PI = np.sqrt(np.pi)
_INV_SQRT_PI = 1.0 / _SQRT_PI

# Gauss-Legendre rule used for short integrals of smooth (entire) integrands: where a closed
# form is a difference of two nearly equal numbers, the same quantity is the integral of a
# positive function over a short interval, which 24 nodes give to rounding.
_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(24)

# Scaled arguments beyond this are clipped: every formula has reached its limit long before,
# and clipping keeps inf * 0 out of the intermediate products.
_ARG_CLIP = 1e100

# Plastic series: G_s = G / sigma_Y^2 below this uses the image (short-time) representation,
# above it the Fourier (long-time) series; both are exact, each converges fast on its side.
_PLASTIC_G_SWITCH = 0.1
_PLASTIC_IMAGES = 10  # image pairs kept for G_s < _PLASTIC_G_SWITCH (next one < 1e-100)
_LOG_TRUNCATION = np.log(1e17)  # Fourier terms kept until exp(-n^2 pi^2 G_s) < 1e-17


# --------------------------------------------------------------------------------------------
# small helpers
# --------------------------------------------------------------------------------------------
def _broadcast_flat(*arrays):
    """Broadcast the arguments; return the common shape and 1-D float64 copies."""
    arrays = np.broadcast_arrays(*arrays)
    return arrays[0].shape, [np.array(x, dtype=np.float64).ravel() for x in arrays]


def _result(x: np.ndarray, shape: tuple[int, ...]):
    """Reshape a flat result; a numpy float64 scalar for 0-d results, the array otherwise."""
    x = np.asarray(x, dtype=np.float64).reshape(shape)
    return x[()] if x.ndim == 0 else x


_SPLITTER = 134217729.0  # 2**27 + 1 (Veltkamp splitting)


def _two_sum(x, y):
    """Knuth's error-free sum: x + y = s + e exactly."""
    with np.errstate(invalid="ignore", over="ignore"):
        s = x + y
        yy = s - x
        e = (x - (s - yy)) + (y - yy)
    return s, e


def _two_prod(x, y):
    """Dekker's error-free product: x * y = p + e exactly (|x|, |y| < ~1e300)."""
    with np.errstate(invalid="ignore", over="ignore"):
        p = x * y
        cx = _SPLITTER * x
        xh = cx - (cx - x)
        xl = x - xh
        cy = _SPLITTER * y
        yh = cy - (cy - y)
        yl = y - yh
        e = ((xh * yh - p) + xh * yl + xl * yh) + xl * yl
    return p, e


def _exp_neg_square_over(hi, lo, den):
    """exp(-(hi + lo)^2 / den) with the exponent carried in double-double.

    The exponent of a Gaussian tail is large (up to ~700), so rounding it to double would cost a
    relative error of (exponent * 1e-16) in the result; carrying the square and the quotient to
    twice the working precision leaves only the rounding of exp itself.
    """
    with np.errstate(over="ignore", invalid="ignore", under="ignore"):
        sq, sq_err = _two_prod(hi, hi)
        sq_lo = sq_err + 2.0 * hi * lo
        q = sq / den
        t, t_err = _two_prod(q, den)
        q_lo = ((sq - t) - t_err + sq_lo) / den
        plain = np.exp(-q)
        fine = np.isfinite(q_lo) & np.isfinite(q)
        return np.where(fine, plain * (1.0 - np.where(fine, q_lo, 0.0)), plain)


def _scaled_ierfc(t: np.ndarray) -> np.ndarray:
    """``exp(t^2) * ierfc(t) = 1/sqrt(pi) - t * erfcx(t)`` (first repeated erfc integral).

    It equals ``-erfcx'(t) / 2`` and is positive.  For ``t < 2`` the difference loses at most a
    factor ``1 + 2 t^2 < 9`` to rounding; for ``t >= 2`` the ratio ``ierfc / erfc`` is taken from
    the continued fraction ``r_k = 1 / (2 t + 2 (k + 1) r_{k+1})`` that follows from the
    recurrence of the repeated erfc integrals (Abramowitz & Stegun 7.2.5), evaluated backwards
    from ``r_61 = 0`` (60 levels reach rounding at ``t = 2``; all terms positive, no cancellation).
    """
    t = np.asarray(t, dtype=np.float64)
    out = np.empty_like(t)
    small = t < 2.0
    ts = t[small]
    out[small] = _INV_SQRT_PI - ts * erfcx(ts)
    tl = t[~small]
    r = np.zeros_like(tl)
    for k in range(60, 0, -1):
        r = 1.0 / (2.0 * tl + 2.0 * (k + 1) * r)
    out[~small] = erfcx(tl) * r
    return out


def _erfcx_difference(u: np.ndarray, h: np.ndarray) -> np.ndarray:
    """``erfcx(u - h) - erfcx(u + h)`` for ``u >= 0``, ``h >= 0``, with full relative accuracy.

    Direct where ``h >= max(1, u) / 2`` (the two terms then differ by a factor >= 2 or so);
    otherwise ``2 * integral_{u-h}^{u+h} exp(t^2) ierfc(t) dt`` by Gauss-Legendre, since
    ``d erfcx / dt = -2 exp(t^2) ierfc(t)``.  Needs ``u - h > -26`` (no erfcx overflow).
    """
    u, h = np.broadcast_arrays(np.asarray(u, dtype=np.float64), np.asarray(h, dtype=np.float64))
    out = np.empty(u.shape)
    direct = h >= 0.5 * np.maximum(1.0, u)
    out[direct] = erfcx(u[direct] - h[direct]) - erfcx(u[direct] + h[direct])
    uq = u[~direct][:, None]
    hq = h[~direct][:, None]
    vals = _scaled_ierfc(uq + hq * _GL_NODES[None, :])
    out[~direct] = 2.0 * h[~direct] * (vals @ _GL_WEIGHTS)
    return out


def _erf_window(center: np.ndarray, half: np.ndarray) -> np.ndarray:
    """``erf(center + half) - erf(center - half)`` for ``center >= half >= 0``, to full relative accuracy.

    Direct (through erfc when ``center - half >= 1/2``) unless the two terms agree to better than
    a factor 0.75 (condition number > 7); then ``(2/sqrt(pi)) integral exp(-t^2) dt`` over the
    window by Gauss-Legendre, which the window then is short enough for.  The window is passed as
    centre and half-width so that a narrow window far out keeps its width exactly.
    """
    center, half = np.broadcast_arrays(
        np.asarray(center, dtype=np.float64), np.asarray(half, dtype=np.float64)
    )
    p = center - half
    q = center + half
    upper = p >= 0.5
    big = np.where(upper, erfc(p), erf(q))
    small = np.where(upper, erfc(q), erf(p))
    out = big - small
    close = small > 0.75 * big
    if np.any(close):
        hc = half[close]
        t = center[close][:, None] + hc[:, None] * _GL_NODES[None, :]
        out[close] = 2.0 * _INV_SQRT_PI * hc * (np.exp(-t * t) @ _GL_WEIGHTS)
    return out


def _check_no_adhesion_pressure(pressure: np.ndarray) -> None:
    check_finite(pressure, "pressure", "Pa")
    bad = pressure < 0
    if np.any(bad):
        raise ValueError(
            "pressure must be >= 0 [Pa] without adhesion: a tensile nominal stress has no contact "
            f"(A = 0); got {_first_bad('pressure', pressure, bad)}. With adhesion use the "
            "linear-boundary forms or the adhesive solver."
        )


def _check_G(G) -> np.ndarray:
    G = as_float_array(G, "G", "Pa^2")
    check_nonnegative(G, "G", "Pa^2")
    return G


def _first_bad(name: str, arr: np.ndarray, mask: np.ndarray) -> str:
    if arr.ndim == 0:
        return f"{name} = {float(arr)!r}"
    idx = tuple(int(i) for i in np.argwhere(mask)[0])
    return f"{name}[{','.join(str(i) for i in idx)}] = {float(arr[idx])!r}"


# --------------------------------------------------------------------------------------------
# method of images (sigma_a = 0)
# --------------------------------------------------------------------------------------------
def images_area(pressure, G):
    """Relative contact area without adhesion, by the method of images.

    Parameters
    ----------
    pressure : array_like
        Nominal contact pressure sigma0 >= 0. [Pa]
    G : array_like
        Diffusion time G(zeta) >= 0, broadcast against `pressure`. [Pa^2]

    Returns
    -------
    area : float or ndarray
        A/A0 = erf(sigma0 / (2 sqrt(G))); at G = 0 the G -> 0+ limit (1 for sigma0 > 0, 0 for
        sigma0 = 0). [-]

    Raises
    ------
    ValueError
        If `pressure` is negative or not finite, or `G` is negative or not finite.

    Notes
    -----
    Persson, J. Chem. Phys. 115, 3840 (2001): the heat equation
    dP/dG = d2P/dsigma2 with P(0) = delta(sigma - sigma0) and P(sigma = 0) = 0 is solved by the
    image pair (images_density), whose integral over sigma >= 0 is erf(sigma0 / (2 sqrt G)).
    scipy's erf keeps full relative accuracy for small arguments, so tiny areas are exact.
    """
    pressure = as_float_array(pressure, "pressure", "Pa")
    _check_no_adhesion_pressure(pressure)
    G = _check_G(G)
    shape, (p, g) = _broadcast_flat(pressure, G)
    return _result(_images_area_flat(p, g), shape)


def _images_area_flat(p, g):
    out = np.where(p > 0, 1.0, 0.0)
    pos = g > 0
    out[pos] = erf(p[pos] / (2.0 * np.sqrt(g[pos])))
    return out


def _images_area_at(p: np.ndarray, g) -> np.ndarray:
    """:func:`images_area` of checked pressures (1-D, finite, >= 0) [Pa] at one diffusion
    time g [Pa^2]: for a finite g > 0 the erf alone, without the checks and the broadcast
    (bitwise the same values); any other g goes through :func:`images_area`."""
    if 0.0 < g < np.inf:
        return erf(p / (2.0 * np.sqrt(g)))
    return images_area(p, g)


def images_density(sigma, pressure, G):
    """Stress distribution P(sigma, G) without adhesion (method of images).

    Parameters
    ----------
    sigma : array_like
        Local normal stress at which to evaluate P (any sign; P = 0 for sigma < 0). [Pa]
    pressure : array_like
        Nominal contact pressure sigma0 >= 0. [Pa]
    G : array_like
        Diffusion time >= 0. [Pa^2]

    Returns
    -------
    density : float or ndarray
        P(sigma, G) = (4 pi G)^(-1/2) [exp(-(sigma-sigma0)^2/4G) - exp(-(sigma+sigma0)^2/4G)]
        for sigma >= 0, 0 below; broadcast shape of the inputs. [1/Pa]
        At G = 0 the delta function is returned as +inf at sigma = sigma0 > 0 and 0 elsewhere.

    Raises
    ------
    ValueError
        On non-finite `sigma`, negative or non-finite `pressure`, negative or non-finite `G`.

    Notes
    -----
    Persson 2001.  The difference of the two Gaussians is written as
    exp(-(sigma-sigma0)^2/4G) * (-expm1(-sigma sigma0 / G)), exact algebra that keeps full
    relative accuracy when sigma sigma0 / G is tiny and never overflows.
    """
    sigma = as_float_array(sigma, "sigma", "Pa")
    check_finite(sigma, "sigma", "Pa")
    pressure = as_float_array(pressure, "pressure", "Pa")
    _check_no_adhesion_pressure(pressure)
    G = _check_G(G)
    shape, (s, p, g) = _broadcast_flat(sigma, pressure, G)
    return _result(_gaussian_times_absorption(s, p, g, s, 0.0 * s, p), shape)


def _gaussian_times_absorption(sigma, sigma0, G, y, y_lo, y0):
    """N(sigma - sigma0; 2G) * (1 - exp(-y y0 / G)) for y >= 0, 0 for y < 0; delta at G = 0.

    y + y_lo is the distance to the wall in double-double (y_lo = 0 when y is exact).
    """
    out = np.zeros(np.shape(sigma))
    pos = G > 0
    yy = y + y_lo
    inside = pos & (yy >= 0)
    gi = G[inside]
    d_hi, d_lo = _two_sum(sigma[inside], -sigma0[inside])
    y0i = y0[inside]
    with np.errstate(over="ignore", invalid="ignore"):
        ratio = np.where(y0i > 0, (y[inside] + y_lo[inside]) * y0i / gi, 0.0)
    gauss = _exp_neg_square_over(d_hi, d_lo, 4.0 * gi)
    out[inside] = gauss / np.sqrt(4.0 * np.pi * gi) * (-np.expm1(-ratio))
    at_start = (~pos) & (sigma == sigma0) & (y0 > 0)
    out[at_start] = np.inf
    return out


def images_moments(pressure, G):
    """Zeroth, first and second stress moments of the image solution.

    Parameters
    ----------
    pressure : array_like
        Nominal contact pressure sigma0 >= 0. [Pa]
    G : array_like
        Diffusion time >= 0. [Pa^2]

    Returns
    -------
    area : float or ndarray
        integral P dsigma = A/A0 = erf(s), s = sigma0 / (2 sqrt G). [-]
    load : float or ndarray
        integral sigma P dsigma = sigma0 exactly (load conservation). [Pa]
    second_moment : float or ndarray
        integral sigma^2 P dsigma = (sigma0^2 + 2G) erf(s) + 2 sigma0 (G/pi)^(1/2) exp(-s^2). [Pa^2]

    Raises
    ------
    ValueError
        On negative or non-finite `pressure` or `G`.

    Notes
    -----
    The second moment follows from the Gaussian integrals of the image pair; every
    term is non-negative, so it is accurate as written.  G = 0 gives (1 or 0, sigma0, sigma0^2).
    """
    pressure = as_float_array(pressure, "pressure", "Pa")
    _check_no_adhesion_pressure(pressure)
    G = _check_G(G)
    shape, (p, g) = _broadcast_flat(pressure, G)
    area = _images_area_flat(p, g)
    load = p.copy()
    second = p * p * area
    pos = g > 0
    gp, pp = g[pos], p[pos]
    s = pp / (2.0 * np.sqrt(gp))
    second[pos] = (pp * pp + 2.0 * gp) * area[pos] + 2.0 * pp * np.sqrt(gp / np.pi) * np.exp(-s * s)
    return _result(area, shape), _result(load, shape), _result(second, shape)


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


def linear_boundary_area(pressure, G, a, b):
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
    < 2e-15 for y0/sqrt(G) in [1e-8, 1e3], |b| sqrt(G) <= 50, sqrt(G) from 1 Pa to 1e9 Pa.
    """
    shape, (p, g, a_, b_), y0 = _linear_inputs(pressure, G, a, b)
    out = np.where(y0 > 0, 1.0, 0.0)
    pos = g > 0
    out[pos] = _linear_area_scaled(_Drift(p[pos], g[pos], a_[pos], b_[pos]))
    return _result(out, shape)


def linear_boundary_detachment_rate(pressure, G, a, b):
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

    Notes
    -----
    The first-passage-time density of Brownian motion with drift b (variance 2G)
    to the level -y0 (inverse-Gaussian law).  Evaluated as alpha exp(-(alpha+c)^2)/(sqrt(pi) G)
    with alpha = y0/(2 sqrt G), c = b sqrt(G)/2 (no overflow; exact zero far in the tails).
    """
    shape, (p, g, a_, b_), y0 = _linear_inputs(pressure, G, a, b)
    out = np.zeros(g.shape)
    pos = g > 0
    st = _Drift(p[pos], g[pos], a_[pos], b_[pos])
    with np.errstate(over="ignore"):  # g beyond the float range (G ~ 1e-300) is inf
        out[pos] = st.alpha * st.gauss * _INV_SQRT_PI / g[pos]
    return _result(out, shape)


def linear_boundary_density(sigma, pressure, G, a, b):
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

    Notes
    -----
    Girsanov + images.  The ratio of the image term to the direct term is exactly
    exp(-y y0 / G), and y - y0 - bG = sigma - sigma0, so the density is evaluated as
    N(sigma - sigma0; 2G) * (-expm1(-y y0 / G)): no overflow of exp(-b y0), full relative
    accuracy next to the wall.  Its integral over y >= 0 is :func:`linear_boundary_area`.
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


def linear_boundary_load(pressure, G, a, b):
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

    Notes
    -----
    Derivation (this module): with y = sigma + sigma_a, integral y P dy over y >= 0 equals
    m Phi(m/sqrt(2G)) - m' exp(-b y0) Phi(m'/sqrt(2G)), m = y0 + bG, m' = bG - y0, because the two
    Gaussian-pdf terms of integral_0^inf y N(y - mu; v) dy = mu Phi(mu/sqrt v) + sqrt(v) phi(mu/sqrt v)
    cancel exactly (exp(-b y0) phi(m'/sqrt v) = phi(m/sqrt v)).  That is bG A + y0 B; subtracting
    sigma_a A = (a + bG) A gives L = y0 B - a A.  It satisfies the load bookkeeping of the adhesive model (detachment at -sigma_a),
    L(G) = sigma0 + integral_0^G sigma_a(G') g(G') dG'.  B - A = exp(-4 alpha c) erfc(alpha - c)
    >= 0, so the form sigma0 B + a (B - A) (a >= 0) or y0 B + |a| A (a < 0) is a sum of
    non-negative terms whenever sigma0 >= 0 or a < 0; only for a tensile start (sigma0 < 0 < a),
    where L itself may cross zero, is the accuracy absolute (relative to |sigma0| B + a (B - A)).
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


# --------------------------------------------------------------------------------------------
# elastic-plastic strip: absorbing walls at sigma = 0 and sigma = sigma_Y
# --------------------------------------------------------------------------------------------
def _check_n_terms(n_terms):
    if n_terms is None:
        return None
    if isinstance(n_terms, bool) or not isinstance(n_terms, numbers.Integral) or n_terms < 1:
        raise ValueError(f"n_terms must be None or an integer >= 1 [-]; got n_terms = {n_terms!r}")
    return int(n_terms)


def _plastic_fourier(s, s_comp, gs, n_max):
    """Fourier (eigenfunction) series for elastic and plastic fractions; s in [0, 1], gs > 0."""
    n = np.arange(1, n_max + 1, dtype=np.float64)
    decay = np.exp(-np.outer(gs, n * n) * np.pi**2)  # (m, N)
    odd = (np.arange(1, n_max + 1) % 2 == 1).astype(np.float64)
    # elastic: symmetric under s <-> 1 - s for odd n; use the smaller angle for accuracy
    x_el = np.pi * np.minimum(s, s_comp)
    elastic = (4.0 / np.pi) * ((np.sin(np.outer(x_el, n)) / n * odd * decay).sum(axis=1))
    # plastic: s - (2/pi) sum_n (-1)^(n+1) sin(n x) / n exp(-n^2 pi^2 G_s), x = pi s; the
    # summand equals sin(n x') / n, x' = pi (1 - s): take whichever angle is small, so that
    # sin(n x) near n pi never comes from a rounded angle
    low = s <= 0.5
    sign = np.where(low[:, None], np.where(np.arange(1, n_max + 1) % 2 == 1, 1.0, -1.0)[None, :], 1.0)
    angle = np.where(low, s, s_comp) * np.pi
    plastic = s - (2.0 / np.pi) * ((sign * np.sin(np.outer(angle, n)) / n * decay).sum(axis=1))
    return np.clip(elastic, 0.0, 1.0), np.clip(plastic, 0.0, 1.0)


def _plastic_images(s, s_comp, gs):
    """Image (short-time) series; s in [0, 1], 0 < gs; exact, converges fast for gs < ~0.3."""
    tau = 2.0 * np.sqrt(gs)
    s_el = np.minimum(s, s_comp)
    elastic = erf(s_el / tau)
    half_el = s_el / tau
    for m in range(1, _PLASTIC_IMAGES + 1):
        elastic = elastic + (-1.0) ** m * _erf_window(m / tau, half_el)
    plastic = np.zeros_like(s)
    half = s / tau
    for j in range(1, 2 * _PLASTIC_IMAGES, 2):
        plastic = plastic + _erf_window(j / tau, half)
    return np.clip(elastic, 0.0, 1.0), np.clip(plastic, 0.0, 1.0)


def plastic_area(pressure, G, yield_stress, n_terms=None):
    """Elastic and plastic contact-area fractions for a constant yield stress (no adhesion).

    Parameters
    ----------
    pressure : array_like
        Nominal pressure sigma0, 0 <= sigma0 <= yield_stress. [Pa]
    G : array_like
        Diffusion time >= 0. [Pa^2]
    yield_stress : array_like
        Penetration hardness / yield stress sigma_Y > 0 (the upper absorbing wall). [Pa]
    n_terms : int or None, optional
        Number of Fourier harmonics n = 1..n_terms (the elastic series uses the odd ones).
        None (default) picks the representation and length for ~1e-16 truncation: the Fourier
        series with exp(-n^2 pi^2 G_s) < 1e-17 for G_s = G/sigma_Y^2 >= 0.1 (at most 7 terms) and
        the equivalent image series for G_s < 0.1.  An integer forces the Fourier series. [-]

    Returns
    -------
    elastic : float or ndarray
        A_el/A0 = (4/pi) sum_{n odd} sin(n x)/n exp(-n^2 pi^2 G_s), x = pi sigma0/sigma_Y. [-]
    plastic : float or ndarray
        Plastically deformed fraction A_pl/A0 (mass absorbed at sigma = sigma_Y up to G):
        (2/pi) sum_{n>=1} (-1)^(n+1) sin(n x)/n [1 - exp(-n^2 pi^2 G_s)]
        = sigma0/sigma_Y - (2/pi) sum_{n>=1} sin(n x')/n exp(-n^2 pi^2 G_s), x' = pi - x. [-]
        At G = 0 the G -> 0+ limits: (1, 0) inside, (0, 0) at sigma0 = 0, (0, 1) at sigma_Y.

    Raises
    ------
    ValueError
        On non-finite input, negative `pressure` or `G`, `yield_stress` <= 0,
        `pressure` > `yield_stress`, or a bad `n_terms`.

    Notes
    -----
    Persson, J. Chem. Phys. 115, 3840 (2001): the heat equation on
    0 < sigma < sigma_Y with absorbing walls has P = (2/sigma_Y) sum sin(n pi sigma0/sigma_Y)
    sin(n pi sigma/sigma_Y) exp(-n^2 pi^2 G_s).  Integrating P gives A_el; integrating the
    flux -dP/dsigma at sigma_Y over G (each mode gives sigma_Y^2 (1 - exp(-n^2 pi^2 G_s))/(n pi)^2)
    gives A_pl, and sum (-1)^(n+1) sin(nx)/n = x/2 turns it into the second form above
    (A_pl -> sigma0/sigma_Y, the gambler's-ruin value, as G -> inf).
    For small G_s the Poisson-dual image sums (tau = 2 sqrt(G_s), s = sigma0/sigma_Y,
    s_el = min(s, 1 - s)) are used instead:
    A_el = erf(s_el/tau) + sum_{m>=1} (-1)^m [erf((m+s_el)/tau) - erf((m-s_el)/tau)],
    A_pl = sum_{j odd} [erf((j+s)/tau) - erf((j-s)/tau)], each window difference evaluated
    without cancellation (_erf_window).
    """
    pressure = as_float_array(pressure, "pressure", "Pa")
    check_nonnegative(pressure, "pressure", "Pa")
    G = _check_G(G)
    yield_stress = as_float_array(yield_stress, "yield_stress", "Pa")
    check_positive(yield_stress, "yield_stress", "Pa")
    n_terms = _check_n_terms(n_terms)
    shape, (p, g, sy) = _broadcast_flat(pressure, G, yield_stress)
    bad = p > sy
    if np.any(bad):
        i = int(np.argmax(bad))
        raise ValueError(
            "pressure must be <= yield_stress [Pa]: a nominal pressure above the yield stress "
            f"deforms the whole nominal area plastically; got pressure = {float(p[i])!r} with "
            f"yield_stress = {float(sy[i])!r}"
        )
    s = p / sy
    s_comp = (sy - p) / sy
    with np.errstate(under="ignore"):
        gs = (g / sy) / sy
    elastic = np.where((p > 0) & (p < sy), 1.0, 0.0)
    plastic = np.where(p == sy, 1.0, 0.0)
    pos = gs > 0
    if n_terms is not None:
        four, img = pos, np.zeros_like(pos)
    else:
        four = pos & (gs >= _PLASTIC_G_SWITCH)
        img = pos & (gs < _PLASTIC_G_SWITCH)
    if np.any(four):
        gsf = gs[four]
        if n_terms is None:
            n_max = int(np.ceil(np.sqrt(_LOG_TRUNCATION / (np.pi**2 * gsf.min()))))
        else:
            n_max = n_terms
        elastic[four], plastic[four] = _plastic_fourier(s[four], s_comp[four], gsf, max(n_max, 1))
    if np.any(img):
        elastic[img], plastic[img] = _plastic_images(s[img], s_comp[img], gs[img])
    return _result(elastic, shape), _result(plastic, shape)


# --------------------------------------------------------------------------------------------
# surface-level convenience
# --------------------------------------------------------------------------------------------
def contact_area_no_adhesion(surface, pressure, e_star, zeta=None):
    """A(zeta)/A0 without adhesion for a surface, by the method of images.

    Parameters
    ----------
    surface : object
        Anything with attributes `q0`, `q1` [1/m] (q1 > q0 > 0) and a method
        ``diffusion_time(q, e_star)`` returning G(q) [Pa^2] (e.g. the models in
        ``persson_fast.surfaces``).
    pressure : array_like
        Nominal pressures sigma0 >= 0, scalar or 1-D of length n_p. [Pa]
    e_star : float
        Effective modulus E* = E / (1 - nu^2) > 0. [Pa]
    zeta : array_like, optional
        Magnifications, 1-D, each in [1, q1/q0]. Default: 64 points log-spaced from 1 to
        zeta1 = q1/q0, end points exact. [-]

    Returns
    -------
    zeta : ndarray, shape (n_z,)
        The magnifications used. [-]
    area : ndarray, shape (n_p, n_z)
        A(zeta)/A0 = erf(sigma0 / (2 sqrt(G(zeta)))). [-]

    Raises
    ------
    ValueError
        On bad `pressure`, `e_star`, `zeta`, a surface with bad q0/q1, or a diffusion time that is
        negative or not finite.

    Notes
    -----
    Persson, J. Chem. Phys. 115, 3840 (2001), Eqs. 4-7 of the seed: all of the
    surface enters through G(zeta) = (pi/4) E*^2 integral_{q0}^{zeta q0} q^3 C(q) dq.
    """
    e_star_arr = as_float_array(e_star, "e_star", "Pa", ndim=(0,))
    check_positive(e_star_arr, "e_star", "Pa")
    pressure = as_float_array(pressure, "pressure", "Pa", ndim=(0, 1))
    _check_no_adhesion_pressure(pressure)
    pressure = np.atleast_1d(pressure)
    for attr in ("q0", "q1", "diffusion_time"):
        if not hasattr(surface, attr):
            raise ValueError(
                f"surface must have attributes q0, q1 [1/m] and a method diffusion_time(q, e_star) "
                f"[Pa^2]; {type(surface).__name__} has no {attr!r}"
            )
    q0 = as_float_array(surface.q0, "surface.q0", "1/m", ndim=(0,))
    check_positive(q0, "surface.q0", "1/m")
    q1 = as_float_array(surface.q1, "surface.q1", "1/m", ndim=(0,))
    check_positive(q1, "surface.q1", "1/m")
    if not q1 > q0:
        raise ValueError(
            f"surface.q1 must be > surface.q0 [1/m]; got q0 = {float(q0)!r}, q1 = {float(q1)!r}"
        )
    zeta1 = float(q1 / q0)
    if zeta is None:
        zeta_arr = np.geomspace(1.0, zeta1, 64)
        zeta_arr[0], zeta_arr[-1] = 1.0, zeta1
    else:
        zeta_arr = as_float_array(zeta, "zeta", "-", ndim=(1,))
        check_finite(zeta_arr, "zeta", "-")
        bad = (zeta_arr < 1.0) | (zeta_arr > zeta1 * (1.0 + 4.0 * np.finfo(float).eps))
        if np.any(bad):
            raise ValueError(
                f"zeta must lie in [1, q1/q0] = [1, {zeta1!r}] [-]; got {_first_bad('zeta', zeta_arr, bad)}"
            )
    G = as_float_array(surface.diffusion_time(zeta_arr * float(q0), float(e_star_arr)), "G", "Pa^2")
    G = np.broadcast_to(G, zeta_arr.shape)
    if np.any(~np.isfinite(G)) or np.any(G < 0):
        bad = ~(np.isfinite(G) & (G >= 0))
        raise ValueError(
            "surface.diffusion_time must return finite values >= 0 [Pa^2]; got "
            + _first_bad("G", np.asarray(G), bad)
        )
    area = np.asarray(images_area(pressure[:, None], G[None, :]), dtype=np.float64)
    return zeta_arr, area
