"""Adhesion on the scenes an adhesion study scans, one thread, medians.

    python -m pytest benchmarks/bench_adhesive_scenes.py --benchmark-only \
        --benchmark-columns=median,iqr,rounds

Cases (``parallel=False``; compilation outside the timing):

* ``test_random_scenes`` -- the 40 random self-affine adhesive scenes of
  :mod:`benchmarks.adhesive_scenes` (seed 1), 4 pressures each, at rtol 1e-4: one round
  solves them all (``extra_info``: ``ms_per_pressure``, the mean over the 160 pressures);
  the per-scene distribution (median, 90th percentile, slowest tenth) comes from
  ``python -m benchmarks.adhesive_scenes``;
* ``test_sign_change_scene`` -- the self-affine scene of issue 32 whose gamma_eff changes
  sign inside the zeta range (H 0.8, q0 1e5, q1 1e9 1/m, h_rms 100 nm, E* 1 GPa, Delta gamma
  0.05 J/m^2) at 0, 1 and 5 MPa, rtol 1e-4 and 1e-6;
* ``test_pull_off_self_affine`` -- ``pull_off`` of a sticky self-affine scene (H 0.8, q0 1e4,
  q1 1e7 1/m, h_rms 10 nm, E* 1 GPa, Delta gamma 0.05 J/m^2) at rtol 1e-3 and 1e-4.

The module uses only the public API and :mod:`benchmarks.adhesive_scenes`, so the same file
copied into an older checkout (with that module) times that version.
"""
from __future__ import annotations

import numpy as np
import pytest

import persson_fast as pf

from benchmarks.adhesive_scenes import build, scenes

RANDOM = [build(params) for params in scenes(1, 40)]
SIGN_CHANGE = pf.SelfAffine(hurst=0.8, q0=1e5, q1=1e9, h_rms=1e-7)
SIGN_CHANGE_KW = dict(e_star=1e9, work_of_adhesion=0.05)
STICKY = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e7, h_rms=1e-8)


@pytest.fixture(scope="module", autouse=True)
def _warm():
    s, kw, p = RANDOM[0]
    pf.solve_contact(s, p[:2], rtol=1e-3, parallel=False, **kw)


def _solve_all(rtol):
    return [pf.solve_contact(s, p, rtol=rtol, parallel=False, **kw) for s, kw, p in RANDOM]


def test_random_scenes(benchmark):
    benchmark.group = "adhesion, 40 random self-affine scenes x 4 pressures, rtol 1e-4"
    results = benchmark.pedantic(_solve_all, args=(1e-4,), rounds=3, iterations=1)
    assert all(np.all(np.isfinite(r.area)) for r in results)
    n_p = sum(r.pressure.size for r in results)
    benchmark.extra_info["pressures"] = n_p
    benchmark.extra_info["flagged"] = int(sum(np.count_nonzero(r.status) for r in results))
    if benchmark.stats is not None and benchmark.stats.stats.data:
        benchmark.extra_info["ms_per_pressure"] = 1e3 * benchmark.stats.stats.median / n_p


@pytest.mark.parametrize("rtol", [1e-4, pytest.param(1e-6, marks=pytest.mark.slow)])
def test_sign_change_scene(benchmark, rtol):
    benchmark.group = f"adhesion, sign change of gamma_eff inside the zeta range, rtol {rtol:g}"
    p = np.array([0.0, 1e6, 5e6])
    r = benchmark.pedantic(pf.solve_contact, args=(SIGN_CHANGE, p),
                           kwargs=dict(rtol=rtol, parallel=False, **SIGN_CHANGE_KW),
                           rounds=3 if rtol > 1e-5 else 1, iterations=1)
    assert np.all(np.isfinite(r.area))
    benchmark.extra_info["status"] = r.status.tolist()
    benchmark.extra_info["estimate_over_rtol_area"] = (
        r.error_estimate / np.maximum(rtol * r.area, 1e-300)).tolist()
    if benchmark.stats is not None and benchmark.stats.stats.data:
        benchmark.extra_info["ms_per_pressure"] = 1e3 * benchmark.stats.stats.median / p.size


@pytest.mark.parametrize("rtol", [1e-3, 1e-4])
def test_pull_off_self_affine(benchmark, rtol):
    benchmark.group = f"pull_off, sticky self-affine scene, rtol {rtol:g}"
    sigma_c = benchmark.pedantic(pf.pull_off, args=(STICKY,),
                                 kwargs=dict(e_star=1e9, work_of_adhesion=0.05, rtol=rtol),
                                 rounds=3, iterations=1)
    assert float(sigma_c) > 0.0
