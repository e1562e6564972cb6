"""Random kinked walls and their references: one table of cases for the property test
(tests/test_random_walls.py) and the contract table (benchmarks/contract_table.py).

A wall is continuous and piecewise linear in G with 1-4 kinks at random places on [0, G_end],
random values (so random slopes of either sign, receding and approaching pieces), a random
nominal stress, and a random stress scale lam (sigma -> lam sigma, G -> lam^2 G: the solvers
must not care). The output times are the breakpoints, the midpoints of the pieces and the
points an eighth into each piece (just after a kink, where the errors of a kinked wall
peak). Each wall is solved as samples on the output times (which hold the breakpoints) and as
a callable (``np.interp`` of the breakpoints: the adaptive sampling must find the kinks).

The reference is :func:`persson_fast._reference.walls.piecewise_linear_area` (the exact
linear-wall kernel carried from kink to kink by Gauss-Legendre quadrature, NumPy/SciPy only),
checked against itself on panels twice as wide; its uncertainty is that difference plus a
rounding floor.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from persson_fast._reference.walls import piecewise_linear_area

#: least length of a piece, relative to G_end (the reference's panels follow the shortest) [-]
MIN_PIECE = 0.03
#: smallest nominal stress relative to the wall's range [-]
SIGMA0_RANGE = (0.01, 2.0)
#: rounding floor of the reference, relative [-]
REF_FLOOR = 2e-13


@dataclass
class KinkedWall:
    """One random wall: breakpoints and values (scaled), nominal stress, output times."""
    seed: int
    n_kinks: int
    G_nodes: np.ndarray
    sa_nodes: np.ndarray
    sigma0: float
    G: np.ndarray
    scale: float
    ref: np.ndarray = None
    #: absolute uncertainty of the reference per output time
    ref_unc: np.ndarray = None

    def callable(self):
        """The wall as a vectorised callable G -> sigma_a (kinks not declared)."""
        gn, sn = self.G_nodes.copy(), self.sa_nodes.copy()
        return lambda g: np.interp(g, gn, sn)

    def samples(self):
        """The wall on the output times (they hold every breakpoint)."""
        return np.interp(self.G, self.G_nodes, self.sa_nodes)


def draw_wall(seed: int) -> KinkedWall:
    """The random wall number ``seed`` (a pure function of the seed)."""
    rng = np.random.default_rng(seed)
    k = int(rng.integers(1, 5))
    g_end = 1.0
    while True:
        inner = np.sort(rng.uniform(0.0, g_end, k))
        nodes = np.concatenate([[0.0], inner, [g_end]])
        if np.min(np.diff(nodes)) >= MIN_PIECE * g_end:
            break
    sa = rng.uniform(0.0, 1.0, k + 2)
    sigma0 = float(np.exp(rng.uniform(np.log(SIGMA0_RANGE[0]), np.log(SIGMA0_RANGE[1]))))
    scale = float(10.0 ** rng.uniform(-2.0, 4.0))
    lo, hi = nodes[:-1], nodes[1:]
    out = np.unique(np.concatenate([nodes, 0.5 * (lo + hi), lo + 0.125 * (hi - lo)]))
    return KinkedWall(seed=seed, n_kinks=k, G_nodes=nodes * scale ** 2, sa_nodes=sa * scale,
                      sigma0=sigma0 * scale, G=out * scale ** 2, scale=scale)


def with_reference(wall: KinkedWall) -> KinkedWall:
    """The wall with its reference areas and their uncertainty (the difference from panels
    twice as wide, which bounds the error of the finer ones, plus a rounding floor)."""
    s, s2 = wall.scale, wall.scale ** 2
    args = (wall.G / s2, wall.G_nodes / s2, wall.sa_nodes / s, wall.sigma0 / s)
    a = piecewise_linear_area(*args)
    a_coarse = piecewise_linear_area(*args, panel_fraction=1.0)
    wall.ref = a
    wall.ref_unc = np.abs(a - a_coarse) + REF_FLOOR * a
    return wall


def walls(n: int, first_seed: int = 0):
    """``n`` random walls with references, seeds first_seed ... first_seed + n - 1."""
    return [with_reference(draw_wall(first_seed + i)) for i in range(n)]
