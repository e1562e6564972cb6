"""An independent reference for piecewise-linear walls: the exact linear-wall transition
kernel propagated from kink to kink by Gauss-Legendre quadrature (NumPy/SciPy only).

In the distance to the wall y = sigma + sigma_a(G) the stress is a Brownian motion of
variance 2G with drift b = d sigma_a / dG, absorbed at y = 0 (THEORY.md section 3). On a piece
where the wall is linear, b is constant and the killed transition density from y' over a
diffusion time t is known in closed form (method of images with the Girsanov factor),

    q_b(y, t | y') = (4 pi t)^(-1/2) [exp(-(y - y' - b t)^2 / 4t)
                                      - exp(-b y') exp(-(y + y' - b t)^2 / 4t)],

and the probability of surviving it is

    S_b(y', t) = Phi((y' + b t) / sqrt(2t)) - exp(-b y') Phi((b t - y') / sqrt(2t)).

The density at the end of the first piece is q_b(y, g_1 | y0) with y0 = sigma0 + sigma_a(0);
at each later kink it is carried over the next piece by p_{k+1}(y) = int q_{b_k}(y, dG | y')
p_k(y') dy', a quadrature on composite Gauss-Legendre panels fine enough for the narrowest
Gaussian (the shortest piece), graded towards the wall down to the thinnest wall layer
(1/|b|) and the shortest time since a kink at which an area is asked. The area at any G of a
piece is int S_b(y', G - g_k) p_k(y') dy'. Nothing here shares code with the solvers: it is
the oracle of the random kinked-wall tests (tests/test_random_walls.py) and of
benchmarks/contract_table.py.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.special import log_ndtr, ndtr

#: Gauss-Legendre nodes per panel [-]
N_GAUSS = 12
#: panel width relative to the narrowest length scale (the spread sqrt(2 dG) of the
#: shortest piece; near the wall also the wall layer 1/|b|) [-]
PANEL_FRACTION = 0.5
#: half-width of the domain beyond the farthest mass centre, in spreads sqrt(2 G_end) [-]
K_FAR = 13.0
#: largest number of quadrature nodes (the kernel matrix is n x n) [-]
MAX_NODES = 12000


def _gauss_panels(hi: float, width: float, fine: float):
    """Composite Gauss-Legendre nodes and weights on [0, hi]: panels of at most ``width``,
    graded geometrically (ratio 2) down to ``fine`` towards y = 0."""
    edges = [0.0]
    w = min(fine, width)
    while edges[-1] + w < hi and w < width:
        edges.append(edges[-1] + w)
        w *= 2.0
    n_pan = max(1, int(math.ceil((hi - edges[-1]) / width)))
    edges = np.concatenate([edges[:-1], np.linspace(edges[-1], hi, n_pan + 1)])
    x, wg = np.polynomial.legendre.leggauss(N_GAUSS)
    half = 0.5 * np.diff(edges)
    mid = 0.5 * (edges[1:] + edges[:-1])
    nodes = (mid[:, None] + half[:, None] * x[None, :]).ravel()
    weights = (half[:, None] * wg[None, :]).ravel()
    return nodes, weights


def transition_density(y, t, y_from, b):
    """q_b(y, t | y_from): the killed transition density of the linear wall (arrays broadcast)."""
    y = np.asarray(y, dtype=float)
    y_from = np.asarray(y_from, dtype=float)
    four_t = 4.0 * t
    direct = -((y - y_from - b * t) ** 2) / four_t
    image = -b * y_from - ((y + y_from - b * t) ** 2) / four_t
    return (np.exp(direct) - np.exp(image)) / math.sqrt(math.pi * four_t)


def survival(y_from, t, b):
    """S_b(y_from, t): the probability that a start at y_from survives the linear wall over t."""
    y_from = np.asarray(y_from, dtype=float)
    if t <= 0.0:
        return (y_from > 0).astype(float)
    s = math.sqrt(2.0 * t)
    first = ndtr((y_from + b * t) / s)
    second = np.exp(-b * y_from + log_ndtr((b * t - y_from) / s))
    return np.clip(first - second, 0.0, 1.0)


def piecewise_linear_area(G_out, G_nodes, sigma_a_nodes, sigma0, *, panel_fraction=None):
    """A(G)/A0 below a continuous piecewise-linear wall, by quadrature of the exact kernels.

    Parameters
    ----------
    G_out : array_like -- diffusion times at which the area is wanted, in [0, G_nodes[-1]].
        [stress^2]
    G_nodes : array_like -- the wall's breakpoints, strictly increasing, G_nodes[0] = 0.
        [stress^2]
    sigma_a_nodes : array_like -- sigma_a at the breakpoints (linear in between). [stress]
    sigma0 : float -- nominal stress, sigma0 + sigma_a(0) > 0. [stress]
    panel_fraction : float or None -- panel width in units of the narrowest length scale
        (default PANEL_FRACTION); halve it to check convergence.

    Returns
    -------
    area : ndarray of G_out's shape [-]
    """
    G_nodes = np.asarray(G_nodes, dtype=float)
    sa = np.asarray(sigma_a_nodes, dtype=float)
    G_out = np.asarray(G_out, dtype=float)
    if G_nodes[0] != 0.0 or np.any(np.diff(G_nodes) <= 0):
        raise ValueError("G_nodes must start at 0 and increase strictly")
    y0 = sigma0 + sa[0]
    if y0 <= 0:
        return np.zeros(G_out.shape)
    frac = PANEL_FRACTION if panel_fraction is None else panel_fraction
    slopes = np.diff(sa) / np.diff(G_nodes)
    dg = np.diff(G_nodes)
    # length scales the panels must resolve: each piece's spread, the wall layers, the start
    width = frac * min(math.sqrt(2.0 * d) for d in dg)
    # near the wall only (graded panels): the wall layers 1/|b| and the survival's step at
    # y' ~ sqrt(2 dt) of the output times inside a piece
    fine = width
    for b in slopes:
        if b != 0.0:
            fine = min(fine, frac / abs(b))
    for g in G_out.ravel():
        k = min(max(int(np.searchsorted(G_nodes, g, side="right")) - 1, 0), len(dg) - 1)
        t = g - G_nodes[k]
        if t > 0:
            fine = min(fine, frac * math.sqrt(2.0 * t))
    g_end = float(G_nodes[-1])
    centre = y0 + np.max(sa - sa[0])
    hi = centre + K_FAR * math.sqrt(2.0 * g_end)
    y, wy = _gauss_panels(hi, width, fine)
    if y.size > MAX_NODES:
        raise ValueError(f"the quadrature needs {y.size} nodes (> {MAX_NODES}): pieces too "
                         f"short or walls too fast for this reference")
    out = np.empty(G_out.shape)
    flat_out = out.ravel()
    flat_g = G_out.ravel()
    # the density at the start of piece k (k >= 1) on the nodes; piece 0 starts from the delta
    dens = None
    for k in range(len(dg)):
        g_a, b = G_nodes[k], slopes[k]
        on = np.flatnonzero((flat_g >= g_a) & ((flat_g < G_nodes[k + 1]) | (k == len(dg) - 1)))
        for i in on:
            t = flat_g[i] - g_a
            if dens is None:
                flat_out[i] = float(survival(np.array([y0]), t, b)[0]) if t > 0 else 1.0
            else:
                flat_out[i] = float(np.sum(wy * dens * survival(y, t, b)))
        if k == len(dg) - 1:
            break
        t = dg[k]
        if dens is None:
            dens = transition_density(y, t, y0, b)
        else:
            dens = transition_density(y[:, None], t, y[None, :], b) @ (wy * dens)
    return out
