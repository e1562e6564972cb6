"""Closed forms without adhesion: the method of images (one absorbing wall at sigma = 0).

:func:`images_area`, :func:`images_density` and :func:`images_moments` solve the stress
diffusion absorbed at sigma = 0 (Persson 2001); :func:`contact_area_no_adhesion` evaluates
the area for a surface over its magnifications. :func:`_gaussian_times_absorption` is the
image pair's density, shared with the linearly moving wall.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # names of the type hints only
    from numpy.typing import ArrayLike
    
    from ..surfaces.base import Surface

import numpy as np
from .special import erf

from persson_fast._validation import (
    as_float_array,
    check_finite,
    check_positive,
)
from .base import (_broadcast_flat, _check_G, _check_no_adhesion_pressure,
                            _exp_neg_square_over, _first_bad, _result, _two_sum)

__all__ = ["images_area", "images_density", "images_moments", "contact_area_no_adhesion"]


# --------------------------------------------------------------------------------------------
# method of images (sigma_a = 0)
# --------------------------------------------------------------------------------------------
def images_area(pressure: ArrayLike, G: ArrayLike) -> float | np.ndarray:
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

    See Also
    --------
    persson_fast.images_density : The stress distribution itself.
    persson_fast.images_moments : Area, load and second moment at once.
    persson_fast.solve_diffusion : The numerical solve it checks.

    Notes
    -----
    Persson, J. Chem. Phys. 115, 3840 (2001): the heat equation
    dP/dG = d2P/dsigma2 with P(0) = delta(sigma - sigma0) and P(sigma = 0) = 0 is solved by the
    image pair (images_density), whose integral over sigma >= 0 is erf(sigma0 / (2 sqrt G)).
    scipy's erf keeps full relative accuracy for small arguments, so tiny areas are exact.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> print(np.round(pf.images_area([0.5, 1.0, 2.0], 1.0), 6))
    [0.276326 0.5205   0.842701]
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


def images_density(sigma: ArrayLike, pressure: ArrayLike,
                   G: ArrayLike) -> float | np.ndarray:
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

    See Also
    --------
    persson_fast.images_area : Its integral over sigma > 0.
    persson_fast.images_moments : Its moments.

    Notes
    -----
    Persson 2001.  The difference of the two Gaussians is written as
    exp(-(sigma-sigma0)^2/4G) * (-expm1(-sigma sigma0 / G)), exact algebra that keeps full
    relative accuracy when sigma sigma0 / G is tiny and never overflows.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> sigma = np.array([0.0, 0.5, 1.0, 2.0])
    >>> print(np.round(pf.images_density(sigma, 1.0, 1.0), 6))
    [0.       0.104271 0.178318 0.189963]
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


def images_moments(pressure: ArrayLike, G: ArrayLike) -> tuple:
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

    See Also
    --------
    persson_fast.images_area : The area alone.
    persson_fast.images_density : The stress distribution.

    Notes
    -----
    The second moment follows from the Gaussian integrals of the image pair; every
    term is non-negative, so it is accurate as written.  G = 0 gives (1 or 0, sigma0, sigma0^2).

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> area, load, second = pf.images_moments(1.0, 1.0)
    >>> print(f"{area:.6f} {load:.6f} {second:.6f}")
    0.520500 1.000000 2.440282
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
# surface-level convenience
# --------------------------------------------------------------------------------------------
def contact_area_no_adhesion(surface: Surface, pressure: ArrayLike, e_star: float,
                             zeta: ArrayLike | None = None) -> tuple[np.ndarray, np.ndarray]:
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

    See Also
    --------
    persson_fast.solve_contact : The same area, and the solved cases.
    persson_fast.images_area : The closed form in the diffusion time.

    Notes
    -----
    Persson, J. Chem. Phys. 115, 3840 (2001), Eqs. 4-7 of the seed: all of the
    surface enters through G(zeta) = (pi/4) E*^2 integral_{q0}^{zeta q0} q^3 C(q) dq.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> zeta, area = pf.contact_area_no_adhesion(s, [1e5, 1e6], e_star=1e9)
    >>> area.shape
    (2, 64)
    >>> print(np.round(area[:, -1], 5))
    [0.0008  0.00802]
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
