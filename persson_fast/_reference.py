"""Slow, obvious NumPy/SciPy twins of the compiled building blocks (for tests and benchmarks)."""
from __future__ import annotations

import numpy as np
from scipy.linalg import solve_banded


def thomas(lower, diag, upper, rhs):
    """Tridiagonal solve with ``scipy.linalg.solve_banded`` (same argument layout as the kernel)."""
    n = diag.size
    ab = np.zeros((3, n))
    ab[0, 1:] = upper[:-1]
    ab[1] = diag
    ab[2, :-1] = lower[1:]
    return solve_banded((1, 1), ab, rhs)


def operator_matrix(h, drift, diff, n_nodes):
    """Dense matrix of the semi-discrete operator L on the interior nodes."""
    m = n_nodes - 2
    L = np.zeros((m, m))
    for k in range(m):
        j = k + 1
        c_plus = 2.0 * (j + 0.5) * h - drift
        c_minus = 2.0 * (j - 0.5) * h - drift
        L[k, k] = -2.0 * diff / h**2 + (c_plus - c_minus) / (2 * h)
        if k > 0:
            L[k, k - 1] = diff / h**2 - c_minus / (2 * h)
        if k < m - 1:
            L[k, k + 1] = diff / h**2 + c_plus / (2 * h)
    return L


def theta_step(p, h, drift, diff, dt, theta):
    """One theta-step with dense linear algebra; returns the new node values."""
    n_nodes = p.size
    L = operator_matrix(h, drift, diff, n_nodes)
    eye = np.eye(n_nodes - 2)
    rhs = (eye + (1 - theta) * dt * L) @ p[1:-1]
    out = np.zeros_like(p)
    out[1:-1] = np.linalg.solve(eye - theta * dt * L, rhs)
    return out
