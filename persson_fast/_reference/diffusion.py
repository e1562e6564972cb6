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


def cn_baseline(G, sigma_a, sigma0, n_nodes, steps_per_decade, n_damp=2):
    """The Crank-Nicolson solver a user would write with NumPy/SciPy: the speed baseline.

    A uniform grid in the distance to the wall y = sigma + sigma_a(G) on [0, Y], P = 0 at
    both ends, central differences for P_G = P_yy - v P_y (v = d sigma_a / dG, the wall
    moving linearly between the schedule points), a Python time loop with one
    ``scipy.linalg.solve_banded`` per step, steps geometric in G (``steps_per_decade``), a
    Rannacher start (``n_damp`` steps as two implicit-Euler half steps each) and the area
    by the trapezoid rule. The grid cannot resolve the start delta: the march starts at
    G_s = (y0 / 4)^2 / 2 (start width a quarter of the distance to the wall, y0 =
    sigma0 + sigma_a(0)) from the exact solution of the images (a wall at rest) or of the
    linearly moving wall (``persson_fast.analytic``), whose values are also returned at
    the schedule points before G_s. Second order in h and the step.

    Parameters
    ----------
    G : (n_t,) -- increasing diffusion times, G[0] >= 0. [Pa^2]
    sigma_a : (n_t,) -- the wall -sigma_a(G), linear in G (a + b G) for the exact start. [Pa]
    sigma0 : float -- nominal stress, sigma0 + sigma_a(0) > 0. [Pa]
    n_nodes : int -- grid nodes on [0, Y], Y = y0 + travel + 8 sqrt(2 G[-1]).
    steps_per_decade : float -- time steps per decade of G.

    Returns
    -------
    area : (n_t,) -- A(G)/A0.
    """
    from ..analytic.images import images_area, images_density
    from ..analytic.linear import linear_boundary_area, linear_boundary_density

    G = np.asarray(G, dtype=float)
    sa = np.asarray(sigma_a, dtype=float)
    span = G[-1] - G[0]
    b = (sa[-1] - sa[0]) / span if span > 0 else 0.0
    a = sa[0] - b * G[0]
    y0 = sigma0 + a
    y_max = y0 + max(0.0, sa.max() - a) + 8.0 * np.sqrt(2.0 * G[-1])
    y = np.linspace(0.0, y_max, n_nodes)
    h = y[1] - y[0]
    g_s = 0.5 * (0.25 * y0) ** 2

    def exact_area(g):
        if a == 0.0 and b == 0.0:
            return images_area(sigma0, g)
        return linear_boundary_area(sigma0, g, a, b)

    area = np.empty(G.size)
    early = G <= g_s
    area[early] = exact_area(G[early]) if np.any(early) else 0.0
    if np.all(early):
        return area
    sigma = y - (a + b * g_s)
    if a == 0.0 and b == 0.0:
        p = images_density(sigma, sigma0, g_s)
    else:
        p = linear_boundary_density(sigma, sigma0, g_s, a, b)
    p[0] = p[-1] = 0.0
    m = n_nodes - 2
    # operator L = d2/dy2 - b d/dy on the interior nodes (Dirichlet ends)
    lo_c = 1.0 / h**2 + b / (2.0 * h)
    di_c = -2.0 / h**2
    up_c = 1.0 / h**2 - b / (2.0 * h)

    def step(p, dt, theta):
        inner = p[1:-1]
        lap = di_c * inner
        lap[1:] += lo_c * inner[:-1]
        lap[:-1] += up_c * inner[1:]
        rhs = inner + (1.0 - theta) * dt * lap
        ab = np.empty((3, m))
        ab[0, :] = -theta * dt * up_c
        ab[1, :] = 1.0 - theta * dt * di_c
        ab[2, :] = -theta * dt * lo_c
        out = np.zeros_like(p)
        out[1:-1] = solve_banded((1, 1), ab, rhs)
        return out

    g = g_s
    damp = n_damp
    for k in np.flatnonzero(~early):
        n_steps = max(1, int(np.ceil(np.log10(G[k] / g) * steps_per_decade)))
        ratio = (G[k] / g) ** (1.0 / n_steps)
        for _ in range(n_steps):
            g_next = g * ratio
            if damp > 0:
                half = np.sqrt(g * g_next)
                p = step(p, half - g, 1.0)
                p = step(p, g_next - half, 1.0)
                damp -= 1
            else:
                p = step(p, g_next - g, 0.5)
            g = g_next
        g = G[k]
        area[k] = np.trapezoid(p, y) if hasattr(np, "trapezoid") else np.trapz(p, y)
    return area
