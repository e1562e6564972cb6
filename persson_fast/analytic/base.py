"""The numerics every closed form of :mod:`persson_fast.analytic` shares.

Error-free sums and products and a Gaussian factor whose exponent is carried in
double-double (:func:`_two_sum`, :func:`_two_prod`, :func:`_exp_neg_square_over`),
differences of erf and erfcx without cancellation (:func:`_erfcx_difference`,
:func:`_erf_window`, by Gauss-Legendre where the two terms nearly agree), the broadcasting of
the arguments to flat arrays and back (:func:`_broadcast_flat`, :func:`_result`) and the
checks of the pressure and of the diffusion time G.
"""
from __future__ import annotations

import numpy as np
from .special import erf, erfc, erfcx

from persson_fast._validation import (
    as_float_array,
    check_finite,
    check_nonnegative,
)

_SQRT_PI = np.sqrt(np.pi)
_INV_SQRT_PI = 1.0 / _SQRT_PI

# Gauss-Legendre rule used for short integrals of smooth (entire) integrands: where a closed
# form is a difference of two nearly equal numbers, the same quantity is the integral of a
# positive function over a short interval, which 24 nodes give to rounding.
_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(24)


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
