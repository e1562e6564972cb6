"""The adhesive fixed point compiled apart from the diffusion solver (issue 11, item 6).

The cached fixed point takes its diffusion step, and the step the grid solver, by address
(numba first-class functions, :class:`persson_fast._jit.CallingKernel`), so that each is
compiled on its own, and on a cold cache the grid solver in a second process at once
(:func:`persson_fast._jit.compile_beside`). What must hold:

* the code called by address computes bitwise what the linked code computes (the
  ``solve_adhesive_one`` entry point of :mod:`persson_fast.embed`, the ``prange`` sweep);
* on a cold cache, a first adhesive solve loads the grid solver compiled by the second
  process (a disk-cache hit, no compile of it here) and gives bitwise the in-process result;
* with one usable CPU, or with everything compiled or cached, no second process starts.

Compile times are measured by ``benchmarks/compile_time.py``, never here.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numba
import numpy as np
import pytest

import persson_fast as pf
from persson_fast import _jit
from persson_fast.adhesion import runner as adhesion_module
from persson_fast._kernels.adhesion import (DEFAULT_M_HIST, DEFAULT_MAX_ITER, DEFAULT_N_DAMP,
                                            DEFAULT_OMEGA, solve_adhesive_one)
from persson_fast._kernels.similarity import GRID_SIGNATURE, _solve_grid_tol
from persson_fast.scene import DETACHMENT_PREFACTOR
from persson_fast.adhesion.zeta_grid import _scene_arrays, adhesion_zeta

needs_jit = pytest.mark.skipif(numba.config.DISABLE_JIT, reason="compiled code only")

PACKAGE_ROOT = str(Path(pf.__file__).resolve().parent.parent)
SEED = pf.seed_scene()
E_STAR = 2.9e9 / (1 - 0.3 ** 2)


def _scene(rtol=1e-4):
    z = adhesion_zeta(SEED, rtol)
    G, c, wa, wb, scale, _ = _scene_arrays(SEED, z, E_STAR, 0.06, DETACHMENT_PREFACTOR)
    return G, c, wa, wb, scale


@needs_jit
@pytest.mark.parametrize("onset", [True, False])
def test_fixed_point_by_address_equals_the_linked_one(onset):
    """The cached sweep (step and grid solver by address) and ``solve_adhesive_one`` (both
    linked in), row by row: bitwise equal, in compression, at zero load and in tension."""
    G, c, wa, wb, scale = _scene()
    p = np.array([-0.5e6, 0.0, 1e6, 30e6, 100e6]) / scale
    ctl = adhesion_module._controls(None)
    outs, status, its, res, _ = adhesion_module._run(G, c, wa, wb, -1.0, p, 1e-4, False, ctl,
                                                     onset=onset)
    n = G.size
    for k, sigma0 in enumerate(p):
        o = [np.zeros(n) for _ in range(8)]
        s, it, r = solve_adhesive_one(0, G, c, wa, wb, -1.0, sigma0, 1e-4, DEFAULT_N_DAMP,
                                      DEFAULT_MAX_ITER, DEFAULT_M_HIST, DEFAULT_OMEGA,
                                      np.full(n, -1.0), *o, onset)
        assert (s, it, r) == (status[k], its[k], res[k])
        for a, b in zip(o, outs):
            np.testing.assert_array_equal(a, b[k])


@needs_jit
def test_function_at_calls_the_compiled_function_by_address():
    """A kernel given a jit address (an integer) calls the function through numba's calling
    convention: its result, and its exception, come back."""
    @numba.njit
    def callee(x):
        if x < 0.0:
            raise ValueError("negative")
        return 2.0 * x

    sig = numba.types.float64(numba.types.float64)
    at = _jit.function_at(sig)

    @numba.njit
    def caller(address, x):
        f = at(address)
        return f(x) + f(1.0)

    address = _jit.jit_address(callee, sig)
    assert address == _jit.jit_address(callee, sig) != 0
    assert caller(address, 1.5) == 5.0
    with pytest.raises(ValueError, match="negative"):
        caller(address, -1.0)


def test_no_second_process_with_one_cpu(monkeypatch):
    monkeypatch.setattr(_jit, "_usable_cpus", lambda: 1)
    assert _jit.compile_beside([(_solve_grid_tol, GRID_SIGNATURE)]) is None


@pytest.mark.parametrize("attr, value", [("executable", ""), ("frozen", True)])
def test_no_second_process_without_an_interpreter(monkeypatch, attr, value):
    """A bundled application (sys.frozen) or no sys.executable: starting "python -c" there
    would start the application again, or nothing."""
    monkeypatch.setattr(_jit, "_usable_cpus", lambda: 2)
    monkeypatch.setattr(_jit, "_needs_compile", lambda dispatcher, signature: True)
    monkeypatch.setattr(_jit, "_Beside", lambda jobs: "started")
    monkeypatch.setattr(sys, attr, value, raising=False)
    assert _jit.compile_beside([(_solve_grid_tol, GRID_SIGNATURE)]) is None


def test_no_second_process_when_switched_off(monkeypatch):
    monkeypatch.setattr(_jit, "_usable_cpus", lambda: 2)
    monkeypatch.setattr(_jit, "_needs_compile", lambda dispatcher, signature: True)
    monkeypatch.setattr(_jit, "_Beside", lambda jobs: "started")
    monkeypatch.setenv("PERSSON_FAST_COMPILE_BESIDE", "0")
    assert _jit.compile_beside([(_solve_grid_tol, GRID_SIGNATURE)]) is None
    monkeypatch.setenv("PERSSON_FAST_COMPILE_BESIDE", "1")
    expected = None if numba.config.DISABLE_JIT else "started"
    assert _jit.compile_beside([(_solve_grid_tol, GRID_SIGNATURE)]) == expected


@needs_jit
def test_no_second_process_when_compiled_here():
    _jit.compile_for(_solve_grid_tol, GRID_SIGNATURE)
    assert _jit.compile_beside([(_solve_grid_tol, GRID_SIGNATURE)]) is None


def test_second_process_compiles_by_module_names(monkeypatch):
    """The jobs reach the second process as names: a dispatcher is found under the name it
    has in its module (``fixed_point`` is ``_fixed_point`` compiled), its signature too."""
    if numba.config.DISABLE_JIT:
        pytest.skip("compiled code only")
    from persson_fast._kernels import adhesion as kernels

    names = []
    monkeypatch.setattr(_jit, "_needs_compile", lambda dispatcher, signature: True)
    monkeypatch.setattr(_jit, "_Beside", lambda jobs: names.extend(jobs) or "started")
    assert _jit.compile_beside([(kernels.fixed_point, kernels.FIXED_POINT_SIGNATURE)]) == "started"
    assert names == ["persson_fast._kernels.adhesion:fixed_point:FIXED_POINT_SIGNATURE"]


def test_signature_must_be_a_module_name():
    if numba.config.DISABLE_JIT:
        pytest.skip("compiled code only")
    sig = numba.types.int64(numba.types.float64)     # not a name of the kernel's module
    with pytest.raises(ValueError, match="module-level names"):
        _jit.compile_beside([(_solve_grid_tol, sig)])


CHILD = r"""
import json, sys, warnings
from numba.core.errors import NumbaExperimentalFeatureWarning
warnings.filterwarnings("error", category=NumbaExperimentalFeatureWarning)
import numpy as np
import persson_fast as pf
from persson_fast import _jit
from persson_fast._kernels.adhesion import elastic_step, fixed_point
from persson_fast._kernels.similarity import GRID_SIGNATURE, _solve_grid_tol
before = _jit.in_disk_cache(_solve_grid_tol, GRID_SIGNATURE)
r = pf.solve_contact(pf.seed_scene(), np.array([0.0, 1e6, 1e7, 1e8]),
                     e_star=2.9e9 / (1 - 0.3 ** 2), work_of_adhesion=0.06, rtol=1e-4)
def count(d):
    return [sum(d.stats.cache_hits.values()), sum(d.stats.cache_misses.values())]
print(json.dumps({"before": before, "after": _jit.in_disk_cache(_solve_grid_tol, GRID_SIGNATURE),
                  "grid": count(_solve_grid_tol), "step": count(elastic_step),
                  "fixed_point": count(fixed_point), "area": r.area.tolist(),
                  "cpus": _jit._usable_cpus()}))
"""


@needs_jit
def test_cold_cache_compiles_the_grid_solver_in_a_second_process(tmp_path):
    """A first adhesive solve on an empty cache: the grid solver comes from the disk cache,
    written by the second process (a hit here, no miss), the fixed point and its step are
    compiled here (misses); the areas bitwise those of this process. Then the cache holds
    the grid solver. numba's note that first-class functions are experimental does not
    reach the user (the child turns it into an error)."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([PACKAGE_ROOT, *filter(None, [env.get("PYTHONPATH")])])
    env["NUMBA_CACHE_DIR"] = str(tmp_path / "cache")
    proc = subprocess.run([sys.executable, "-c", CHILD], env=env, capture_output=True,
                          text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-3000:]
    rep = json.loads(proc.stdout.strip().splitlines()[-1])
    want = pf.solve_contact(SEED, np.array([0.0, 1e6, 1e7, 1e8]), e_star=E_STAR,
                            work_of_adhesion=0.06, rtol=1e-4).area
    np.testing.assert_array_equal(rep["area"], want)
    assert rep["before"] is False and rep["after"] is True
    assert rep["fixed_point"][1] >= 1 and rep["step"][1] >= 1      # compiled here
    if rep["cpus"] < 2:
        pytest.skip("one usable CPU: everything compiles in one process")
    assert rep["grid"] == [1, 0], rep                               # loaded, not compiled


WARMUP_CHILD = r"""
import json
import persson_fast as pf
from persson_fast import _jit
from persson_fast._kernels.similarity import GRID_SIGNATURE, _solve_grid_tol
started = []
original = _jit.compile_beside
def spy(jobs):
    b = original(jobs)
    started.append(b is not None)
    return b
_jit.compile_beside = spy
from persson_fast._kernels.adhesion import fixed_point
pf.warmup()
print(json.dumps({"started": started, "cpus": _jit._usable_cpus(),
                  "grid_misses": sum(_solve_grid_tol.stats.cache_misses.values()),
                  "fixed_point": [sum(fixed_point.stats.cache_hits.values()),
                                  sum(fixed_point.stats.cache_misses.values())]}))
"""


# slow: fills an empty cache first (~60 s on 2 cores); the cold-cache split stays in CI
@pytest.mark.slow
@needs_jit
def test_a_warm_cache_starts_no_second_process(tmp_path):
    """``pf.warmup()`` twice on one cache. The first compiles the adhesive fixed point in a
    second process while it compiles the contact sweeps (with the grid solver, linked in),
    then loads it; the second finds everything in the cache (the explicit compiles use
    numba's own key, the argument types), so it starts no second process and compiles
    nothing."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([PACKAGE_ROOT, *filter(None, [env.get("PYTHONPATH")])])
    env["NUMBA_CACHE_DIR"] = str(tmp_path / "cache")
    reps = []
    for _ in range(2):
        proc = subprocess.run([sys.executable, "-c", WARMUP_CHILD], env=env,
                              capture_output=True, text=True, timeout=900)
        assert proc.returncode == 0, proc.stderr[-3000:]
        reps.append(json.loads(proc.stdout.strip().splitlines()[-1]))
    assert not any(reps[1]["started"]), reps
    assert reps[1]["grid_misses"] == 0 and reps[1]["fixed_point"] == [1, 0], reps
    if reps[0]["cpus"] >= 2:
        assert reps[0]["started"][0] is True, reps
        assert reps[0]["fixed_point"] == [1, 0], reps                # loaded, not compiled
