"""Tridiagonal building blocks (Thomas algorithm, theta-step assembly), ``@njit``."""
from __future__ import annotations

import math

import numpy as np

from .._jit import njit_inline, njit_serial


#: the continuants of :func:`thomas` and :func:`theta_step` (products of the pivots) are
#: rescaled by an exact power of two when they leave [CONTINUANT_SMALL, CONTINUANT_BIG], so
#: they neither overflow nor underflow while each pivot stays within 1e-180 ... 1e180
CONTINUANT_BIG = 2.0 ** 400
CONTINUANT_SMALL = 2.0 ** -400


@njit_serial
def theta_workspace(n):
    """The (n,) work arrays of the fixed-grid theta step: lo, di, up, a_lo, a_di, a_up, rhs,
    scratch (:func:`theta_step` uses three arrays only)."""
    return (np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n),
            np.empty(n), np.empty(n))


@njit_inline
def _continuant_row(b, a, c, d, t_1, t_2, y_1, c_1):
    """One row ``a x_(i-1) + b x_i + c x_(i+1) = d`` of the continuant elimination (see
    :func:`thomas`), given the previous row's super-diagonal ``c_1`` and the continuants
    ``t_1``, ``t_2`` (rows i-1, i-2) and ``y_1``. Returns (t, t_1, y, d', c'): the row's
    continuants (``t_1`` rescaled with them by a power of two when they leave
    [CONTINUANT_SMALL, CONTINUANT_BIG]) and the eliminated row x_i = d' - c' x_(i+1),
    d' = y / t, c' = c t_1 / t."""
    t = b * t_1 - (a * c_1) * t_2
    y = t_1 * d - a * y_1
    q = c * t_1
    if not CONTINUANT_SMALL <= abs(t) <= CONTINUANT_BIG:
        f = CONTINUANT_SMALL if abs(t) > CONTINUANT_BIG else CONTINUANT_BIG
        t *= f
        t_1 *= f
        y *= f
        q *= f
    r = 1.0 / t
    return t, t_1, y, y * r, q * r


@njit_serial
def thomas(lower, diag, upper, rhs, scratch, out):
    """Solve a tridiagonal system without pivoting (Thomas algorithm, with continuants).

    Parameters
    ----------
    lower : (n,) float64 -- sub-diagonal, ``lower[0]`` unused.
    diag : (n,) float64 -- main diagonal.
    upper : (n,) float64 -- super-diagonal, ``upper[n-1]`` unused.
    rhs : (n,) float64 -- right-hand side (not modified unless ``out`` is ``rhs``).
    scratch : (n,) float64 -- workspace.
    out : (n,) float64 -- solution (may alias ``rhs``).

    Notes
    -----
    The pivots are beta_i = th_i / th_(i-1) with the continuants
    th_i = diag_i th_(i-1) - lower_i upper_(i-1) th_(i-2), and the eliminated right-hand side
    is Y_i / th_i with Y_i = th_(i-1) rhs_i - lower_i Y_(i-1): two linear recursions, so the
    chain of dependent operations per row is a multiply and a subtract, and the one division
    per row (1/th_i) is off it (the usual form has two divisions on the chain). The
    continuants are kept in range by exact powers of two (CONTINUANT_BIG). Stable for the
    diagonally dominant matrices ``I - theta*dt*L`` produced here (cell Peclet number <= 2).
    """
    n = diag.shape[0]
    th_2 = 0.0
    th_1 = 1.0
    y_1 = 0.0
    u_1 = 0.0
    for i in range(n):
        l_i = lower[i] if i > 0 else 0.0
        u_i = upper[i] if i < n - 1 else 0.0
        t, th_2, y_1, out[i], scratch[i] = _continuant_row(diag[i], l_i, u_i, rhs[i], th_1,
                                                           th_2, y_1, u_1)
        th_1 = t
        u_1 = u_i
    for i in range(n - 2, -1, -1):
        out[i] -= scratch[i] * out[i + 1]


@njit_serial
def fitted_diffusion(peclet):
    """Exponentially fitted diffusion factor (P/2) coth(P/2) of a cell Peclet number P.

    Equals 1 + P^2/12 + O(P^4) for small P (the scheme stays second order) and makes the
    discrete flux exact for a stationary drift-diffusion layer of any thickness
    (Scharfetter-Gummel / Il'in-Allen-Southwell fitting).
    """
    x = 0.5 * abs(peclet)
    if x < 1e-4:
        return 1.0 + x * x / 3.0
    return x / math.tanh(x)


@njit_inline
def _theta_row(i, lo0, up0, e_d, e, i_, p):
    """Row i (node i + 1) of the theta step: (sub-diagonal, super-diagonal, right-hand side)
    of ``(I - i_ L) p_new = (I + e L) p``; the diagonal is the constant 1 - i_ (1 - 2 diff/h^2)."""
    jf = i + 1.0
    l_i = lo0 - jf
    u_i = up0 + jf
    d = e_d * p[i + 1] + e * (l_i * p[i] + u_i * p[i + 2])
    return -i_ * l_i, -i_ * u_i, d


@njit_serial
def theta_step(p, h, drift, diff, dt, theta, lo, di, up):
    """One theta-step ``(I - theta dt L) p_new = (I + (1-theta) dt L) p`` in place.

    ``p`` holds all nodes (p[0] and p[-1] are the Dirichlet zeros). theta = 1/2 is
    Crank-Nicolson, theta = 1 implicit Euler. L is the semi-discrete Fokker-Planck operator
    on the interior nodes,

        L p_j = diff (p_{j+1} - 2 p_j + p_{j-1})/h^2 + (F_{j+1/2} - F_{j-1/2})/h,
        F_{j+1/2} = c_{j+1/2} (p_j + p_{j+1})/2,  c(xi) = 2 xi - drift,  xi_j = j h,

    with ``diff`` uniform in space (see :func:`fitted_diffusion`), so that the discrete first
    moment obeys the same exact identity as the continuous one. Its coefficients are linear
    in the node index (lo_j = lo0 - j, up_j = up0 + j, a constant diagonal), so they are
    formed in the loop.

    The tridiagonal solve is a twisted Thomas algorithm written with continuants (see
    :func:`thomas`): rows 0 .. k-1 are eliminated downwards and rows m-1 .. k+1 upwards in
    one loop (two independent chains), row k = m // 2 is solved from both, and the back
    substitution runs outwards from it, again two chains in one loop. Each elimination keeps
    the pivots as ratios of continuants, th_i = b th_(i-1) - a_i c_(i-1) th_(i-2) downwards
    (mirrored upwards), with the right-hand side Y_i = th_(i-1) d_i - a_i Y_(i-1): linear
    recursions whose one division per row is off the chain. The continuants are kept in
    range by exact powers of two (CONTINUANT_BIG). The matrices here are diagonally dominant
    M-matrices (cell Peclet number <= 2), for which the recursion is as stable as the usual
    form. ``lo``, ``di`` and ``up`` (at least as long as ``p``) hold the eliminated rows.
    """
    m = p.shape[0] - 2
    inv_h2 = diff / (h * h)
    dh = drift * (0.5 / h)
    lo0 = inv_h2 + 0.5 + dh
    up0 = inv_h2 + 0.5 - dh
    d_l = 1.0 - 2.0 * inv_h2
    e = (1.0 - theta) * dt
    i_ = theta * dt
    b = 1.0 - i_ * d_l
    e_d = 1.0 + e * d_l
    k = m // 2
    n_bot = m - 1 - k               # k or k - 1 rows below the middle row
    # downwards: rows 0 .. k-1 -> x_i = di_i - up_i x_(i+1); upwards: rows m-1 .. k+1 ->
    # x_i = di_i - lo_i x_(i-1)
    t_2 = 0.0
    t_1 = 1.0
    y_1 = 0.0
    c_1 = 0.0
    s_2 = 0.0
    s_1 = 1.0
    z_1 = 0.0
    a_1 = 0.0
    for i in range(k):
        a, c, d = _theta_row(i, lo0, up0, e_d, e, i_, p)
        t, t_2, y_1, di[i], up[i] = _continuant_row(b, a, c, d, t_1, t_2, y_1, c_1)
        t_1 = t
        c_1 = c
        if i < n_bot:
            j = m - 1 - i
            a, c, d = _theta_row(j, lo0, up0, e_d, e, i_, p)
            t, s_2, z_1, di[j], lo[j] = _continuant_row(b, c, a, d, s_1, s_2, z_1, a_1)
            s_1 = t
            a_1 = a
    a, c, d = _theta_row(k, lo0, up0, e_d, e, i_, p)
    num = d
    den = b
    if k > 0:
        num -= a * di[k - 1]
        den -= a * up[k - 1]
    if n_bot > 0:
        num -= c * di[k + 1]
        den -= c * lo[k + 1]
    x_k = num / den
    p[k + 1] = x_k
    x_u = x_k
    x_d = x_k
    for s in range(1, k + 1):
        i = k - s
        x_u = di[i] - up[i] * x_u
        p[i + 1] = x_u
        if s <= n_bot:
            j = k + s
            x_d = di[j] - lo[j] * x_d
            p[j + 1] = x_d
