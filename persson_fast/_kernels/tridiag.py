"""Tridiagonal building blocks (Thomas algorithm, theta-step assembly), ``@njit``."""
from __future__ import annotations

import math

import numpy as np

from .._jit import njit_serial


@njit_serial
def theta_workspace(n):
    """The (n,) work arrays of a theta step (:func:`theta_step`, and the fixed-grid step):
    lo, di, up, a_lo, a_di, a_up, rhs, scratch."""
    return (np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n),
            np.empty(n), np.empty(n))


@njit_serial
def thomas(lower, diag, upper, rhs, scratch, out):
    """Solve a tridiagonal system without pivoting (Thomas algorithm).

    Parameters
    ----------
    lower : (n,) float64 -- sub-diagonal, ``lower[0]`` unused.
    diag : (n,) float64 -- main diagonal.
    upper : (n,) float64 -- super-diagonal, ``upper[n-1]`` unused.
    rhs : (n,) float64 -- right-hand side (not modified).
    scratch : (n,) float64 -- workspace.
    out : (n,) float64 -- solution (may alias ``rhs``).

    Notes
    -----
    Stable for the diagonally dominant matrices ``I - theta*dt*L`` produced here
    (cell Peclet number <= 2). Cost: 8n flops, no allocation.
    """
    n = diag.shape[0]
    beta = diag[0]
    out[0] = rhs[0] / beta
    for i in range(1, n):
        scratch[i] = upper[i - 1] / beta
        beta = diag[i] - lower[i] * scratch[i]
        out[i] = (rhs[i] - lower[i] * out[i - 1]) / beta
    for i in range(n - 2, -1, -1):
        out[i] -= scratch[i + 1] * out[i + 1]


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


@njit_serial
def operator_coefficients(h, drift, diff, n_nodes, lo, di, up):
    """Coefficients of the semi-discrete Fokker-Planck operator on interior nodes.

    L p_j = diff (p_{j+1} - 2 p_j + p_{j-1})/h^2 + (F_{j+1/2} - F_{j-1/2})/h,
    F_{j+1/2} = c_{j+1/2} (p_j + p_{j+1})/2,  c(xi) = 2 xi - drift,  xi_j = j h.

    ``diff`` is uniform in space (see :func:`fitted_diffusion`), so the discrete first
    moment obeys the same exact identity as the continuous one. Interior node
    j = 1..n_nodes-2 is stored at index j-1 of ``lo``, ``di``, ``up``.
    """
    inv_h2 = diff / (h * h)
    half_over_h = 0.5 / h
    for j in range(1, n_nodes - 1):
        c_plus = 2.0 * (j + 0.5) * h - drift
        c_minus = 2.0 * (j - 0.5) * h - drift
        k = j - 1
        lo[k] = inv_h2 - c_minus * half_over_h
        di[k] = -2.0 * inv_h2 + (c_plus - c_minus) * half_over_h
        up[k] = inv_h2 + c_plus * half_over_h


@njit_serial
def theta_step(p, h, drift, diff, dt, theta, lo, di, up, a_lo, a_di, a_up, rhs, scratch):
    """One theta-step ``(I - theta dt L) p_new = (I + (1-theta) dt L) p`` in place.

    ``p`` holds all nodes (p[0] and p[-1] are the Dirichlet zeros). theta = 1/2 is
    Crank-Nicolson, theta = 1 implicit Euler.
    """
    n_nodes = p.shape[0]
    m = n_nodes - 2
    operator_coefficients(h, drift, diff, n_nodes, lo, di, up)
    e = (1.0 - theta) * dt
    i_ = theta * dt
    for k in range(m):
        j = k + 1
        rhs[k] = p[j] + e * (lo[k] * p[j - 1] + di[k] * p[j] + up[k] * p[j + 1])
        a_lo[k] = -i_ * lo[k]
        a_di[k] = 1.0 - i_ * di[k]
        a_up[k] = -i_ * up[k]
    thomas(a_lo[:m], a_di[:m], a_up[:m], rhs[:m], scratch[:m], rhs[:m])
    for k in range(m):
        p[k + 1] = rhs[k]
