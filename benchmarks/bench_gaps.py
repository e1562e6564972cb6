"""Benchmarks of issue 36: the gap distribution and the pull-off of the corrected theories
and the yield wall.

* ``gap_distribution`` of the seed scene at ten pressures (0.1 to 100 MPa) at rtol 1e-2 to
  1e-4 (default grid; the density's estimate, the trapezoid weight error and the size of the
  grid go into ``extra_info``);
* ``pull_off`` of the seed scene at rtol 1e-3 with theory yp08 and wm17 and with a yield
  wall of 2e8 Pa (estimate and branch points into ``extra_info``).
"""
import warnings

import numpy as np
import pytest

import persson_fast as pf

SEED = pf.seed_scene()
SEED_E_STAR = pf.seed_e_star()
PRESSURES = np.geomspace(1e5, 1e8, 10)


@pytest.fixture(scope="module", autouse=True)
def _warm():
    pf.gap_distribution(SEED, 1e6, e_star=SEED_E_STAR, rtol=1e-2)
    pf.pull_off(SEED, e_star=SEED_E_STAR, work_of_adhesion=0.06, theory="yp08", rtol=1e-2)


@pytest.mark.parametrize("rtol", [1e-2, 1e-3, pytest.param(1e-4, marks=pytest.mark.slow)])
def test_seed_gap_distribution(benchmark, rtol):
    benchmark.group = "gap distribution, seed scene, 10 pressures"
    g = benchmark.pedantic(pf.gap_distribution, args=(SEED, PRESSURES),
                           kwargs={"e_star": SEED_E_STAR, "rtol": rtol}, rounds=3,
                           iterations=1)
    assert g.success, g.message
    benchmark.extra_info["n_gaps"] = int(g.gaps.size)
    benchmark.extra_info["density_estimate_max"] = float(g.error_estimate.max())
    benchmark.extra_info["weight_error_max"] = float(g.weight_error.max())


@pytest.mark.parametrize("kw", [{"theory": "yp08"}, {"theory": "wm17"}, {"hardness": 2e8}],
                         ids=["yp08", "wm17", "hardness-2e8"])
def test_seed_pull_off_variants(benchmark, kw):
    benchmark.group = "seed pull-off, rtol 1e-3"

    def run():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            return pf.pull_off(SEED, e_star=SEED_E_STAR, work_of_adhesion=0.06, rtol=1e-3,
                               full_output=True, bracket=False, **kw)

    sigma_c, info = benchmark.pedantic(run, rounds=2, iterations=1)
    benchmark.extra_info["sigma_c"] = sigma_c
    benchmark.extra_info["error_estimate"] = info["error_estimate"]
    benchmark.extra_info["converged"] = info["converged"]
    benchmark.extra_info["solves"] = info["solves"]
