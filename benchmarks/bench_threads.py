"""Thread scaling of the pressure sweep (issue 11, item 4): ``parallel=False`` (one thread)
against the default ``parallel=None`` (a pool of ``numba.get_num_threads()`` Python threads,
each running the disk-cached serial kernel on a block of pressures).

Run (on a quiet machine: check ``uptime`` first, the load average should be below 1)::

    python -m pytest benchmarks/bench_threads.py --benchmark-only \\
        --benchmark-columns=median,iqr,rounds

Each scene is one group holding its serial and its default run, so the speed-up serial/default
is the factor in brackets after the serial median (the default being the faster). The default
run also stores it in ``extra_info["speedup_vs_serial"]`` (with ``--benchmark-json``), with the
thread count and the load average at the start. Target: >= 1.8x on 2 threads for >= 64
pressures, results bitwise equal to serial (checked after timing, untimed).

Compilation is never timed: the module fixture compiles (or loads) the kernels and runs each
scene once in both modes first; ``python -m benchmarks.compile_time`` measures compile time.
"""
from __future__ import annotations

import dataclasses
import os

import numba
import numpy as np
import pytest

import persson_fast as pf

from benchmarks.cases import _log_pressures, get_case

#: the table's 5-decade self-affine scene: its 64 pressures, and 400 on the same range
AFFINE_64 = get_case("selfaffine-5dec")
AFFINE_400 = dataclasses.replace(
    AFFINE_64, name="selfaffine-5dec-400", make_pressures=_log_pressures(400),
    description=AFFINE_64.description.replace("64 pressures", "400 pressures"))
#: the adhesive seed scene: 32 pressures 0 ... 100 MPa, Delta gamma = 0.06 J/m^2
SEED_PRESSURES = np.linspace(0.0, 100e6, 32)


def _affine(case, rtol):
    inp = case.setup()

    def run(parallel):
        return pf.solve_contact(inp.surface, inp.pressure, e_star=inp.e_star, method="cn",
                                rtol=rtol, parallel=parallel)
    return inp.pressure.size, run


def _seed(rtol):
    surface = pf.seed_scene()

    def run(parallel):
        return pf.solve_contact(surface, SEED_PRESSURES, e_star=pf.seed_e_star(),
                                work_of_adhesion=pf.SEED_WORK_OF_ADHESION, rtol=rtol,
                                parallel=parallel)
    return SEED_PRESSURES.size, run


#: group name -> builder of (number of pressures, run(parallel) -> result)
SCENES = {
    "cn selfaffine-5dec 64 pressures rtol=1e-6": lambda: _affine(AFFINE_64, 1e-6),
    "cn selfaffine-5dec 400 pressures rtol=1e-6": lambda: _affine(AFFINE_400, 1e-6),
    "adhesion seed 32 pressures rtol=1e-4": lambda: _seed(1e-4),
}
MODES = {"serial": False, "default": None}

_medians: dict = {}


@pytest.fixture(scope="module")
def scenes():
    """Every scene built, compiled and run once in each mode (untimed), with its serial
    result for the bitwise check."""
    pf.warmup()
    built = {}
    for name, build in SCENES.items():
        n_p, run = build()
        serial = run(False)
        assert serial.success, serial.message
        run(None)
        built[name] = (n_p, run, serial)
    return built


def _same_bits(a, b) -> bool:
    for field in dataclasses.fields(a):
        x, y = getattr(a, field.name), getattr(b, field.name)
        if isinstance(x, np.ndarray):
            x, y = np.ascontiguousarray(x), np.ascontiguousarray(y)
            if x.dtype != y.dtype or x.shape != y.shape or x.tobytes() != y.tobytes():
                return False
    return True


@pytest.mark.parametrize("scene, mode", [(s, m) for s in SCENES for m in MODES])
def test_threads_vs_serial(benchmark, scenes, scene, mode):
    """One scene, one mode; the serial run of a scene comes before its default run."""
    n_p, run, serial = scenes[scene]
    benchmark.group = scene
    benchmark.extra_info.update({
        "scene": scene, "parallel": MODES[mode], "n_pressures": n_p,
        "threads": numba.get_num_threads(), "load_average_1min": os.getloadavg()[0],
    })
    result = benchmark(run, MODES[mode])
    assert _same_bits(result, serial), "the result differs from the serial one"
    if benchmark.stats is None:     # --benchmark-disable: the callable ran once, untimed
        return
    median = benchmark.stats.stats.median
    _medians[(scene, mode)] = median
    benchmark.extra_info["median_s"] = median
    benchmark.extra_info["s_per_pressure"] = median / n_p
    if mode == "default" and (scene, "serial") in _medians:
        benchmark.extra_info["speedup_vs_serial"] = _medians[(scene, "serial")] / median
