"""Closed form of the elastic-plastic strip: absorbing walls at sigma = 0 and sigma = sigma_Y.

:func:`plastic_area` gives the elastic and plastic contact-area fractions for a constant
yield stress without adhesion (Persson 2001): the Fourier (long-time) series, or its
Poisson-dual image (short-time) series where that converges faster.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # names of the type hints only
    from numpy.typing import ArrayLike

import numbers

import numpy as np
from .special import erf

from persson_fast._validation import (
    as_float_array,
    check_nonnegative,
    check_positive,
)
from .base import _broadcast_flat, _check_G, _erf_window, _result

__all__ = ["plastic_area"]

# Plastic series: G_s = G / sigma_Y^2 below this uses the image (short-time) representation,
# above it the Fourier (long-time) series; both are exact, each converges fast on its side.
_PLASTIC_G_SWITCH = 0.1
_PLASTIC_IMAGES = 10  # image pairs kept for G_s < _PLASTIC_G_SWITCH (next one < 1e-100)
_LOG_TRUNCATION = np.log(1e17)  # Fourier terms kept until exp(-n^2 pi^2 G_s) < 1e-17


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


def plastic_area(pressure: ArrayLike, G: ArrayLike, yield_stress: ArrayLike,
                 n_terms: int | None = None) -> tuple:
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

    See Also
    --------
    persson_fast.solve_diffusion : The numerical solve with ``sigma_y``.
    persson_fast.hardness_power_law : A yield stress that varies with the magnification.

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

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> elastic, plastic = pf.plastic_area(1.0, 1.0, 2.0)
    >>> print(f"{elastic:.6f} {plastic:.6f}")
    0.107977 0.446011
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
