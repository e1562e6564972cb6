"""Cost of the yield wall: the two-wall solver against one wall and a NumPy/SciPy baseline.

Run::

    python -m pytest benchmarks/bench_yield.py --benchmark-only \
        --benchmark-columns=median,iqr,rounds
    python -m pytest benchmarks/bench_yield.py --benchmark-disable   # smoke test

Scene: two walls translating together at physical scales, sigma_a = a - b G (detachment) and
sigma_Y = Y + b G (yield), a = 20 MPa, Y = 280 MPa, b W = 2 (W = a + Y), G on 60 log-spaced
points from 1e-4 W^2 to 1.5 W^2, 16 pressures from 0.05 Y to 0.9 Y; the exact answer is the
strip's sine series (persson_fast._reference.yield_wall.translating_walls). Cases (one thread):

* ``test_one_wall_cn`` -- the detachment wall alone, "cn" at rtol 1e-6 (the cost without the
  second wall; error against the moving-wall closed form);
* ``test_two_walls_strip`` -- both walls, "strip" at rtol 1e-6;
* ``test_numpy_two_wall_cn`` -- the straightforward NumPy/SciPy two-wall Crank-Nicolson of
  the slow twin (uniform strip grid, banded solves, Richardson over two resolutions) on 4 of
  the pressures, at its default resolution (error ~1e-7, at or below the strip's).

``extra_info``: ``ms_per_pressure`` and ``max_rel_error`` (of the real contact area
A_el + A_pl, or of the area for one wall, relative, at every G).
"""
from __future__ import annotations

import numpy as np
import pytest

import persson_fast as pf
from persson_fast._reference.yield_wall import translating_walls, two_wall_reference

A, Y = 2e7, 2.8e8
W = A + Y
B = 2.0 / W
G = np.geomspace(1e-4, 1.5, 60) * W ** 2
PRESSURE = np.linspace(0.05, 0.9, 16) * Y
SA = A - B * G
SY = Y + B * G


@pytest.fixture(scope="module")
def exact():
    walls = [translating_walls(p, G, A, Y, B) for p in PRESSURE]
    two = np.array([v["elastic_area"] + v["plastic_area"] for v in walls])
    one = pf.linear_boundary_area(PRESSURE[:, None], G[None, :], A, -B)
    # compile outside the timing
    pf.solve_diffusion(G, PRESSURE[:2], SA, sigma_y=SY, method="strip", rtol=1e-6,
                       parallel=False)
    pf.solve_diffusion(G, PRESSURE[:2], SA, method="cn", rtol=1e-6, parallel=False)
    return one, two


def _rel(got, want):
    return float(np.max(np.abs(got - want) / want))


def test_one_wall_cn(benchmark, exact):
    one, _ = exact
    r = benchmark(pf.solve_diffusion, G, PRESSURE, SA, method="cn", rtol=1e-6, parallel=False)
    assert r.success
    benchmark.extra_info["max_rel_error"] = _rel(r.area, one)
    benchmark.extra_info["ms_per_pressure"] = 1e3 * benchmark.stats.stats.median / PRESSURE.size \
        if benchmark.stats else float("nan")


def test_two_walls_strip(benchmark, exact):
    _, two = exact
    r = benchmark(pf.solve_diffusion, G, PRESSURE, SA, sigma_y=SY, method="strip", rtol=1e-6,
                  parallel=False)
    assert r.success and r.method == "strip"
    err = _rel(r.area + r.plastic_area, two)
    benchmark.extra_info["max_rel_error"] = err
    benchmark.extra_info["ms_per_pressure"] = 1e3 * benchmark.stats.stats.median / PRESSURE.size \
        if benchmark.stats else float("nan")
    assert err <= 1e-6


def test_numpy_two_wall_cn(benchmark, exact):
    _, two = exact
    sub = PRESSURE[::5]

    def run():
        return [two_wall_reference(G, p, SA, SY) for p in sub]

    out = benchmark.pedantic(run, rounds=3, iterations=1)
    got = np.array([o["elastic_area"] + o["plastic_area"] for o in out])
    benchmark.extra_info["max_rel_error"] = _rel(got, two[::5])
    benchmark.extra_info["ms_per_pressure"] = 1e3 * benchmark.stats.stats.median / sub.size \
        if benchmark.stats else float("nan")
