"""Benchmarks of the adhesive fixed point: the seed scene, 128 pressures, adhesion on.

Setup (kernel compilation, the zeta grid) happens outside the timed callable. The time per
pressure and the fixed-point iterations per pressure go into ``extra_info``.
"""
import numpy as np
import pytest

import persson_fast as pf

SEED_E_STAR = pf.seed_e_star()
DGAMMA = pf.SEED_WORK_OF_ADHESION
PRESSURES = np.linspace(0.0, 100e6, 128)


@pytest.fixture(scope="module", autouse=True)
def _warm():
    pf.warmup()
    pf.solve_contact(pf.seed_scene(), PRESSURES[:8], e_star=SEED_E_STAR, work_of_adhesion=DGAMMA,
                     rtol=1e-2, parallel=False)
    pf.solve_contact(pf.seed_scene(), PRESSURES[:8], e_star=SEED_E_STAR, work_of_adhesion=DGAMMA,
                     rtol=1e-2, parallel=True)


@pytest.mark.parametrize("rtol", [1e-4, 1e-6])
@pytest.mark.parametrize("parallel", [False, True], ids=["serial", "parallel"])
def test_seed_adhesion_128(benchmark, rtol, parallel):
    surface = pf.seed_scene()
    benchmark.group = f"seed adhesion 128 pressures rtol={rtol:g}"
    result = benchmark(pf.solve_contact, surface, PRESSURES, e_star=SEED_E_STAR,
                       work_of_adhesion=DGAMMA, rtol=rtol, parallel=parallel)
    assert result.success, result.message
    benchmark.extra_info["pressures"] = PRESSURES.size
    benchmark.extra_info["iterations_per_pressure_mean"] = float(result.iterations.mean())
    benchmark.extra_info["n_zeta"] = int(result.zeta.size)
    if benchmark.stats is not None and benchmark.stats.stats.data:
        med = float(np.median(benchmark.stats.stats.data))
        benchmark.extra_info["s_per_pressure"] = med / PRESSURES.size
