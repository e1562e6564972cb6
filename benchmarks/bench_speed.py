"""The speed targets, one thread, medians: cn against the NumPy/SciPy Crank-Nicolson, the
adhesive fixed point and pull-off on the seed scene.

Run::

    python -m pytest benchmarks/bench_speed.py --benchmark-only \
        --benchmark-columns=median,iqr,rounds
    python -m pytest benchmarks/bench_speed.py --benchmark-disable   # smoke test

The module uses only the public API and ``benchmarks/cases.py``, so the same file, copied
into the ``benchmarks/`` of an older checkout and run there (with its own ``NUMBA_CACHE_DIR``),
times that version: the before/after ratios of a change are the medians of two such runs made
one after the other on one machine.

Cases (``parallel=False`` everywhere):

* ``test_cn_selfaffine_64`` -- ``solve_contact(method="cn", rtol=1e-6)`` on the table's
  5-decade self-affine scene (``benchmarks/cases.py``, 64 pressures); error against the
  exact area erf(p / (2 sqrt G)) at every zeta of the default grid;
* ``test_numpy_cn_selfaffine`` -- :func:`persson_fast._reference.diffusion.cn_baseline` (the
  Crank-Nicolson a user would write with NumPy/SciPy) on 4 of those pressures, 1600 nodes and
  200 steps per decade. It cannot reach cn's error: the uniform grid does not resolve the
  small pressures at all (error 1 at p = 1e-3 sqrt(G1)), and its best pressure is still
  ~4e-6 off. Its time per pressure over cn's is therefore a lower bound of the ratio at equal
  error (``extra_info``: ``max_rel_error`` over the pressures and zeta, ``end_rel_error``
  per pressure at zeta1);
* ``test_adhesive_seed_16`` -- the seed scene with Delta gamma = 0.06 J/m^2, 16 pressures
  0 ... 100 MPa, rtol 1e-4 (``iterations_mean``: fixed-point iterations per pressure, summed
  over the zeta levels);
* ``test_pull_off_seed`` -- ``pull_off`` on the seed scene at rtol 1e-4 (no bracket), 3 rounds.

``extra_info`` holds ``ms_per_pressure`` where it applies.
"""
from __future__ import annotations

import numpy as np
import pytest

import persson_fast as pf
from persson_fast._reference.diffusion import cn_baseline

from benchmarks.cases import get_case

SEED_PRESSURES = np.linspace(0.0, 100e6, 16)
BASELINE_NODES = 1600


@pytest.fixture(scope="module")
def affine():
    inp = get_case("selfaffine-5dec").setup()
    pf.solve_contact(inp.surface, inp.pressure[:2], e_star=inp.e_star, method="cn",
                     rtol=1e-6, parallel=False)       # compile outside the timing
    exact = pf.images_area(inp.pressure[:, None], inp.G[None, :])
    return inp, exact


def _per_pressure(benchmark, n):
    return 1e3 * benchmark.stats.stats.median / n if benchmark.stats else float("nan")


def _max_rel(got, want):
    mask = want > 0
    return float(np.max(np.abs(got[mask] - want[mask]) / want[mask]))


def test_cn_selfaffine_64(benchmark, affine):
    inp, exact = affine
    benchmark.group = "cn vs NumPy/SciPy CN, 5-decade self-affine"
    r = benchmark(pf.solve_contact, inp.surface, inp.pressure, e_star=inp.e_star, method="cn",
                  rtol=1e-6, parallel=False)
    assert r.success, r.message
    err = _max_rel(r.area_zeta, exact)
    benchmark.extra_info["max_rel_error"] = err
    benchmark.extra_info["ms_per_pressure"] = _per_pressure(benchmark, inp.n_p)
    assert err <= 1e-6


def test_numpy_cn_selfaffine(benchmark, affine):
    inp, exact = affine
    benchmark.group = "cn vs NumPy/SciPy CN, 5-decade self-affine"
    rows = np.arange(0, inp.n_p, 16)
    zero = np.zeros_like(inp.G)

    def run():
        return np.array([cn_baseline(inp.G, zero, p, BASELINE_NODES, BASELINE_NODES / 8.0)
                         for p in inp.pressure[rows]])

    area = benchmark.pedantic(run, rounds=3, iterations=1)
    benchmark.extra_info["max_rel_error"] = _max_rel(area, exact[rows])
    benchmark.extra_info["end_rel_error"] = (np.abs(area[:, -1] - exact[rows, -1])
                                             / exact[rows, -1]).tolist()
    benchmark.extra_info["ms_per_pressure"] = _per_pressure(benchmark, rows.size)


@pytest.fixture(scope="module")
def seed():
    surface, e_star = pf.seed_scene(), pf.seed_e_star()
    pf.solve_contact(surface, SEED_PRESSURES[:2], e_star=e_star,
                     work_of_adhesion=pf.SEED_WORK_OF_ADHESION, rtol=1e-2, parallel=False)
    return surface, e_star


def test_adhesive_seed_16(benchmark, seed):
    surface, e_star = seed
    benchmark.group = "adhesive seed scene, rtol 1e-4"
    r = benchmark(pf.solve_contact, surface, SEED_PRESSURES, e_star=e_star,
                  work_of_adhesion=pf.SEED_WORK_OF_ADHESION, rtol=1e-4, parallel=False)
    assert r.success, r.message
    benchmark.extra_info["iterations_mean"] = float(np.mean(r.iterations))
    benchmark.extra_info["area"] = r.area.tolist()
    benchmark.extra_info["ms_per_pressure"] = _per_pressure(benchmark, SEED_PRESSURES.size)


def test_pull_off_seed(benchmark, seed):
    surface, e_star = seed
    benchmark.group = "pull-off seed scene, rtol 1e-4"
    pf.pull_off(surface, e_star=e_star, work_of_adhesion=pf.SEED_WORK_OF_ADHESION, rtol=1e-2)
    sigma_c, info = benchmark.pedantic(
        pf.pull_off, args=(surface,),
        kwargs={"e_star": e_star, "work_of_adhesion": pf.SEED_WORK_OF_ADHESION, "rtol": 1e-4,
                "full_output": True, "bracket": False},
        rounds=3, iterations=1)
    assert info["converged"]
    benchmark.extra_info["sigma_c"] = float(sigma_c)
    benchmark.extra_info["error_estimate"] = float(info["error_estimate"])
