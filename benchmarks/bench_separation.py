"""Speed of the mean separation, the stiffness and the contact law (pytest-benchmark).

Run::

    python -m pytest benchmarks/bench_separation.py --benchmark-only \
        --benchmark-columns=median,iqr,rounds
    python -m pytest benchmarks/bench_separation.py --benchmark-disable   # smoke test

Scene: the issue's self-affine surface (H = 0.8, q0 = 1e4 /m, q1 = 1e9 /m, h_rms = 1 um,
E* = 1 GPa) and the seed scene. Cases:

* ``test_separation_1000`` -- :func:`persson_fast.solve_separation` on 1000 log-spaced
  pressures from 1e3 to 1e9 Pa (u, K and U_el; S = 1 and gamma_S = 0.45; threads as by
  default). Target: <= 10 ms.
* ``test_law_call`` -- the compiled law p(u) inside a user's ``@njit`` loop over 100,000
  separations spread over the table (``extra_info["ns_per_call"]``). Target: <= 100 ns.
* ``test_law_build`` -- :func:`persson_fast.embed.contact_law` at rtol 1e-6 and 1e-8.
* ``test_reference_one_pressure`` -- the slow reference twin (scipy quad of the double
  integral) at one pressure, for the ratio.

Every case records its largest relative error against the reference twin where it has
one (``extra_info["max_rel_error"]``).
"""
from __future__ import annotations

import numba
import numpy as np
import pytest

import persson_fast as pf
from persson_fast import embed
from persson_fast._reference.separation import separation_quad, stiffness_quad

E_STAR = 1e9
SURFACE = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
PRESSURE = np.geomspace(1e3, 1e9, 1000)
CHECK = PRESSURE[::250]


@pytest.fixture(scope="module", params=[None, 0.45], ids=["S=1", "gamma_S=0.45"])
def case(request):
    gamma = request.param
    pf.solve_separation(SURFACE, PRESSURE[:8], e_star=E_STAR, energy_correction=gamma)
    ref_u = np.array([separation_quad(SURFACE, p, E_STAR, gamma) for p in CHECK])
    ref_k = np.array([stiffness_quad(SURFACE, p, E_STAR, gamma) for p in CHECK])
    return gamma, ref_u, ref_k


def test_separation_1000(benchmark, case):
    gamma, ref_u, ref_k = case
    r = benchmark(pf.solve_separation, SURFACE, PRESSURE, e_star=E_STAR,
                  energy_correction=gamma)
    err = max(np.max(np.abs(r.separation[::250] / ref_u - 1)),
              np.max(np.abs(r.stiffness[::250] / ref_k - 1)))
    benchmark.extra_info["max_rel_error"] = float(err)
    assert err < 1e-6


@numba.njit(cache=False)
def _sum_pressures(table, gaps):
    total = 0.0
    for i in range(gaps.size):
        p, status = embed.law_pressure(table, gaps[i])
        total += p
    return total


@pytest.mark.parametrize("rtol", [1e-6, 1e-8])
def test_law_call(benchmark, rtol):
    law = embed.contact_law(SURFACE, e_star=E_STAR, rtol=rtol)
    rng = np.random.default_rng(0)
    gaps = np.exp(rng.uniform(np.log(law.separation[0]), np.log(law.separation[-1]), 100_000))
    _sum_pressures(law.table, gaps[:4])
    benchmark(_sum_pressures, law.table, gaps)
    if benchmark.stats is not None:
        benchmark.extra_info["ns_per_call"] = benchmark.stats.stats.median / gaps.size * 1e9
    benchmark.extra_info["nodes"] = int(law.separation.size)
    benchmark.extra_info["error_estimate"] = law.error_estimate


@pytest.mark.parametrize("rtol", [1e-6, 1e-8])
def test_law_build(benchmark, rtol):
    embed.contact_law(SURFACE, e_star=E_STAR, rtol=rtol)
    law = benchmark(embed.contact_law, SURFACE, e_star=E_STAR, rtol=rtol)
    benchmark.extra_info["nodes"] = int(law.separation.size)


def test_reference_one_pressure(benchmark):
    benchmark.pedantic(separation_quad, args=(SURFACE, 1e6, E_STAR, None), rounds=1,
                       iterations=1)
