"""Core speed benchmarks (pytest-benchmark), fed by the case table in ``cases.py``.

Run::

    python -m pytest benchmarks --benchmark-only --benchmark-columns=median,iqr,rounds
    python -m pytest benchmarks --benchmark-disable     # each benchmark once, as a smoke test

Compile time is never timed here: the module fixture compiles (or loads) the kernels first;
``python -m benchmarks.compile_time`` measures it in fresh processes. Each benchmark stores in
``extra_info`` the case, the sizes and, when timing is on, the median time per pressure and per
pressure x zeta node (a size-free throughput).
"""
from __future__ import annotations

import numba
import numpy as np
import pytest

import persson_fast as pf
from persson_fast.sweep import run_sweep

from benchmarks.cases import CASES, get_case

RTOL = 1e-6
SWEEP_CASE = "sweep-1000"


@pytest.fixture(scope="module", autouse=True)
def _warm_kernels():
    """Compile (or load from the cache) both sweep kernels before anything is timed."""
    pf.warmup()


@pytest.fixture(scope="module")
def inputs():
    """Inputs of every case, built once and outside the timed callables."""
    return {case.name: case.setup() for case in CASES}


def _describe(benchmark, case_name, inp, **extra) -> None:
    benchmark.extra_info.update({
        "case": case_name,
        "n_pressures": inp.n_p,
        "n_z": inp.n_z,
        "rtol": RTOL,
        "threads": numba.get_num_threads(),
        **extra,
    })


def _record_time(benchmark, inp) -> None:
    """Median time per pressure (and per pressure x node), only when timing is on."""
    if benchmark.stats is None:  # --benchmark-disable: the callable ran once, untimed
        return
    median = benchmark.stats.stats.median
    benchmark.extra_info["median_s"] = median
    benchmark.extra_info["s_per_pressure"] = median / inp.n_p
    benchmark.extra_info["ns_per_pressure_node"] = 1e9 * median / (inp.n_p * inp.n_z)


def _exact_area(inp) -> np.ndarray:
    """erf(p / (2 sqrt G1)), the exact non-adhesive area (method of images)."""
    return pf.images_area(inp.pressure, inp.G[-1])


@pytest.mark.parametrize("case_name", [case.name for case in CASES])
def test_solve_contact_cn(benchmark, inputs, case_name):
    """solve_contact with the Crank-Nicolson solver (the kernel the adhesive problem uses)."""
    benchmark.group = "solve_contact cn"
    inp = inputs[case_name]
    _describe(benchmark, case_name, inp, method="cn")
    res = benchmark(pf.solve_contact, inp.surface, inp.pressure, e_star=inp.e_star,
                    method="cn", rtol=RTOL)
    _record_time(benchmark, inp)
    assert res.success, res.message
    err = float(np.max(np.abs(res.area - _exact_area(inp))))
    benchmark.extra_info["max_abs_error_vs_exact"] = err
    assert err <= 10 * RTOL


@pytest.mark.parametrize("case_name", [case.name for case in CASES])
def test_solve_contact_analytic(benchmark, inputs, case_name):
    """The closed form on the same scenes, for comparison with "cn"."""
    benchmark.group = "solve_contact analytic"
    inp = inputs[case_name]
    _describe(benchmark, case_name, inp, method="analytic")
    res = benchmark(pf.solve_contact, inp.surface, inp.pressure, e_star=inp.e_star,
                    method="analytic", rtol=RTOL)
    _record_time(benchmark, inp)
    assert res.success, res.message
    assert np.allclose(res.area, _exact_area(inp), rtol=0, atol=1e-12)


@pytest.mark.parametrize("parallel", [False, True], ids=["serial", "parallel"])
def test_sweep_1000(benchmark, inputs, parallel):
    """run_sweep over 1000 pressures, one thread against numba's thread pool."""
    benchmark.group = "sweep 1000 pressures"
    inp = inputs[SWEEP_CASE]
    assert inp.n_p == 1000, get_case(SWEEP_CASE).description
    _describe(benchmark, SWEEP_CASE, inp, method="cn", parallel=parallel)
    out, timings = benchmark(run_sweep, inp.G, inp.sigma_a, inp.pressure, rtol=RTOL,
                             parallel=parallel)
    _record_time(benchmark, inp)
    assert "compile" not in timings  # the module fixture compiled the kernels
    assert np.all(out["status"] == 0)
    err = float(np.max(np.abs(out["area"][:, -1] - _exact_area(inp))))
    benchmark.extra_info["max_abs_error_vs_exact"] = err
    assert err <= 10 * RTOL
