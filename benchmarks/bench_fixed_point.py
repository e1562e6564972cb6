"""How to solve the fixed point of Eqs. 8-9: Anderson acceleration against plain relaxation
and against continuation in sigma0 or in the work of adhesion.

Seed scene, adhesion on, 32 pressures from 0 to 100 MPa, rtol 1e-4. Each strategy reports
the fixed-point iterations per pressure (coarse and fine grid together) and its largest
deviation from the direct Anderson solve in ``extra_info``:

- ``anderson``: every pressure from the full-contact start (the default; runs over prange);
- ``plain``: plain under-relaxation, omega = 0.5, same start;
- ``sigma0-continuation``: the pressures in turn, each started from the previous one's
  sigma_a (a sequential chain; cannot run over prange);
- ``dgamma-continuation``: dgamma raised in three steps (1/4, 1/2, 1 of the target), each
  started from the previous sigma_a scaled by (dgamma ratio)^(1/2) (from full contact where
  that start would be the separated state); iterations summed.
"""
import numpy as np
import pytest

import persson_fast as pf
from persson_fast.adhesion.zeta_grid import adhesion_zeta
from persson_fast.adhesion.fixed_point import solve_adhesive_contact

SEED_E_STAR = pf.seed_e_star()
DGAMMA = pf.SEED_WORK_OF_ADHESION
RTOL = 1e-4
PRESSURES = np.linspace(0.0, 100e6, 32)
SURFACE = pf.seed_scene()
ZETA = adhesion_zeta(SURFACE, RTOL)


def _solve(p, dg=DGAMMA, start=None, controls=None):
    return solve_adhesive_contact(SURFACE, p, ZETA, e_star=SEED_E_STAR, work_of_adhesion=dg,
                                  rtol=RTOL, parallel=False, controls=controls,
                                  zeta_given=True, start=start)


def anderson():
    r = _solve(PRESSURES)
    return r.area, r.iterations


def plain():
    r = _solve(PRESSURES, controls={"m_hist": 0, "omega": 0.5})
    return r.area, r.iterations


def sigma0_continuation():
    area, its = np.empty(PRESSURES.size), np.empty(PRESSURES.size, dtype=int)
    start = None
    for k, p in enumerate(PRESSURES):
        r = _solve(np.array([p]), start=start)
        area[k], its[k], start = r.area[0], r.iterations[0], r.sigma_a[0]
    return area, its


def dgamma_continuation():
    its = np.zeros(PRESSURES.size, dtype=int)
    start, dg_prev = None, None
    for dg in (0.25 * DGAMMA, 0.5 * DGAMMA, DGAMMA):
        if start is not None:
            start = start * np.sqrt(dg / dg_prev)
            # a start with p_nom + sigma_a(1) <= 0 is the separated state A = 0, itself a
            # fixed point: those rows (p_nom = 0 while sigma_a(1) = 0) restart from full contact
            start[PRESSURES + start[:, 0] <= 0.0, 0] = -1.0
        r = _solve(PRESSURES, dg=dg, start=start)
        its += r.iterations
        start, dg_prev = r.sigma_a, dg
    return r.area, its


STRATEGIES = {"anderson": anderson, "plain": plain, "sigma0-continuation": sigma0_continuation,
              "dgamma-continuation": dgamma_continuation}


@pytest.fixture(scope="module")
def direct():
    pf.warmup()
    return anderson()[0]


@pytest.mark.parametrize("name", sorted(STRATEGIES))
def test_fixed_point_strategy(benchmark, name, direct):
    benchmark.group = "seed adhesion fixed point, 32 pressures, rtol 1e-4"
    area, its = benchmark(STRATEGIES[name])
    deviation = float(np.max(np.abs(area - direct) / direct))
    assert deviation <= 3 * RTOL, deviation
    benchmark.extra_info["iterations_per_pressure"] = float(its.mean())
    benchmark.extra_info["max_deviation_from_direct"] = deviation
    if benchmark.stats is not None and benchmark.stats.stats.data:
        benchmark.extra_info["s_per_pressure"] = float(np.median(benchmark.stats.stats.data)) / PRESSURES.size
