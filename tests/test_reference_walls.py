"""The kink-to-kink quadrature reference (persson_fast._reference.walls) against the closed
forms it must reproduce, and against itself on other panels: it is the oracle of the random
kinked walls (tests/test_random_walls.py), so it is checked here without the solvers."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.special import ndtr

from persson_fast._reference.walls import piecewise_linear_area, survival, transition_density


#: NumPy >= 2.0's name; NumPy 1.x (the package supports >= 1.24) calls it trapz
_trapezoid = getattr(np, "trapezoid", None) or np.trapz


def _linear_area(sigma0, G, a, b):
    """THEORY.md section 3, written out here: Phi((y0 + bG)/sqrt(2G)) - e^(-b y0) Phi((bG -
    y0)/sqrt(2G)), y0 = sigma0 + a."""
    y0 = sigma0 + a
    G = np.asarray(G, dtype=float)
    s = np.sqrt(2.0 * np.where(G > 0, G, 1.0))
    out = ndtr((y0 + b * G) / s) - np.exp(-b * y0) * ndtr((b * G - y0) / s)
    return np.where(G > 0, out, 1.0)


@pytest.mark.parametrize("seed", range(8))
def test_a_straight_wall_split_at_random_points_is_the_closed_form(seed):
    """Breakpoints where the wall does not kink: the propagation from piece to piece must
    reproduce the one-piece closed form (to 1e-13)."""
    rng = np.random.default_rng(seed)
    a, b = rng.uniform(0.0, 0.5), rng.uniform(-1.5, 1.5)
    sigma0 = rng.uniform(0.02, 1.0)
    nodes = np.unique(np.concatenate([[0.0], rng.uniform(0.05, 1.0, 3), [1.2]]))
    G = np.unique(np.concatenate([nodes, 0.5 * (nodes[1:] + nodes[:-1]), [1e-3]]))
    area = piecewise_linear_area(G, nodes, a + b * nodes, sigma0)
    ref = _linear_area(sigma0, G, a, b)
    np.testing.assert_allclose(area, ref, rtol=1e-13, atol=1e-15)


def test_kernel_and_survival_are_consistent():
    """The survival is the integral of the killed density; the density carried over two
    halves of a time is the density over the whole (Chapman-Kolmogorov, with the wall)."""
    b, t, y0 = -0.7, 0.3, 0.4
    y = np.linspace(0.0, 12.0, 120001)
    q = transition_density(y, t, y0, b)
    assert abs(_trapezoid(q, y) - survival(np.array([y0]), t, b)[0]) < 1e-9
    x, w = np.polynomial.legendre.leggauss(200)
    mid = 0.5 * (x + 1.0) * 8.0
    half = transition_density(mid, t / 2, y0, b) * w * 4.0
    two = transition_density(y[::1000, None], t / 2, mid[None, :], b) @ half
    np.testing.assert_allclose(two, q[::1000], atol=1e-12)


def test_panels_converge():
    """A kinked wall: the default panels agree with panels four times narrower to 1e-13."""
    nodes = np.array([0.0, 0.75435330, 0.86025527, 0.92032264])
    sa = np.array([0.13802327, 0.75050109, 0.80108797, 0.79578172])
    G = np.unique(np.concatenate([nodes, 0.5 * (nodes[1:] + nodes[:-1])]))
    a = piecewise_linear_area(G, nodes, sa, 0.0609812194)
    a_fine = piecewise_linear_area(G, nodes, sa, 0.0609812194, panel_fraction=0.125)
    np.testing.assert_allclose(a, a_fine, rtol=1e-13)
    assert np.all(np.diff(a) < 0)                       # the wall only ever absorbs


def test_separated_start_and_bad_nodes():
    assert np.all(piecewise_linear_area([0.0, 1.0], [0.0, 1.0], [0.1, 0.2], -0.2) == 0.0)
    with pytest.raises(ValueError, match="G_nodes"):
        piecewise_linear_area([0.5], [0.1, 1.0], [0.1, 0.2], 1.0)
    assert math.isclose(piecewise_linear_area([0.0], [0.0, 1.0], [0.1, 0.2], 1.0)[0], 1.0)
