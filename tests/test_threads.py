"""Parallel pressure sweeps (issue 11, items 4 and 5).

* every way of running a sweep -- ``parallel=False`` (serial), ``None`` (default), ``True``,
  ``"threads"`` and ``"prange"`` -- gives bitwise the same result, for ``solve_contact`` with
  and without adhesion and for ``solve_diffusion`` with a wall, whatever the number of
  pressures (0, 1, fewer than the thread pool's blocks, not a multiple of them);
* the disk-cached kernels run from several processes at once, on a cold cache (all of them
  compile and write it concurrently) and on the warm cache it leaves (all of them load);
  ``"prange"`` (not cached on disk) from several processes at once does not crash either;
* under numba's ``workqueue`` threading layer, which aborts the process when two threads
  enter it at once (``Concurrent access has been detected``, rc 134), ``solve_contact`` called
  from 4 Python threads at once never crashes;
* ``solve_contact`` called from threads of the user's own pool, or from a thread of the
  package's pool, finishes (pools never nest) with the serial result;
* a bad ``parallel`` is a ValueError naming it.

The checks that start processes run a script held in :data:`CHILD` (its functions also run in
this process, so the in-process result is computed by the same code). Speed is measured in
``benchmarks/bench_threads.py``, never here.
"""
from __future__ import annotations

import dataclasses
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numba
import numpy as np
import pytest

import persson_fast as pf
from persson_fast.adhesion import runner as adhesion_module
from persson_fast import sweep

#: every accepted value of ``parallel`` but the serial one
PARALLEL = [None, True, "threads", "prange"]
PARALLEL_IDS = ["default", "True", "threads", "prange"]
#: the root the package is imported from: child processes import the same code
PACKAGE_ROOT = str(Path(pf.__file__).resolve().parents[1])
#: seconds a child process may take (a cold cache compiles every kernel, ~20 s alone)
CHILD_TIMEOUT = 600

#: Script of the child processes; its functions are also called in this process.
#: ``python -c CHILD <command> <json arguments>`` prints one JSON line.
CHILD = r'''
import dataclasses, hashlib, json, sys, threading, time
import numpy as np
import persson_fast as pf

#: the self-affine scene of the benchmarks: 5 decades, E* = 1 GPa
def affine():
    return pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)

def affine_pressures(n):
    """n pressures from 0 to far beyond full contact (1e10 Pa; sqrt(G1) is ~3e8 Pa)."""
    if n <= 1:
        return np.full(n, 1e7)
    return np.concatenate([[0.0], np.geomspace(1e3, 1e10, n - 1)])

def seed_pressures(n):
    """n pressures on the seed scene, 0 ... 50 MPa."""
    return np.linspace(0.0, 5e7, n) if n > 1 else np.full(n, 1e7)

def contact(n, parallel, rtol=1e-4):
    return pf.solve_contact(affine(), affine_pressures(n), e_star=1e9, method="cn",
                            rtol=rtol, parallel=parallel)

def adhesive(n, parallel, rtol=1e-3):
    return pf.solve_contact(pf.seed_scene(), seed_pressures(n), e_star=pf.seed_e_star(),
                            work_of_adhesion=0.06, rtol=rtol, parallel=parallel)

def digest(res):
    """sha256 of every array of a result (names, dtypes, shapes and bytes): bitwise identity."""
    h = hashlib.sha256()
    # the dataclass fields (a profile deferred until read is computed here) and the rest
    names = set(vars(res)) | {f.name for f in dataclasses.fields(res)}
    for name in sorted(names - {"_pending"}):
        value = getattr(res, name)
        if isinstance(value, np.ndarray):
            value = np.ascontiguousarray(value)
            h.update(f"{name}:{value.dtype.str}:{value.shape}".encode())
            h.update(value.tobytes())
    return h.hexdigest()

def cache_stats():
    """Disk-cache hits and misses of the cached kernels the sweeps run in this process: the
    contact sweep, and the adhesive fixed point with the two it calls by address."""
    from persson_fast._kernels.adhesion import adhesive_sweep_serial, elastic_step, fixed_point
    from persson_fast._kernels.similarity import _solve_grid_tol
    from persson_fast._kernels.sweep import sweep_serial
    out = {}
    for name, kernel in (("sweep", sweep_serial), ("adhesive", adhesive_sweep_serial),
                         ("fixed point", fixed_point), ("adhesive step", elastic_step),
                         ("grid", _solve_grid_tol)):
        stats = kernel.stats
        out[name] = {"hits": sum(stats.cache_hits.values()),
                     "misses": sum(stats.cache_misses.values())}
    return out

def solve_all(modes, kinds=("contact", "adhesive"), n_contact=40, n_adhesive=8):
    """Digest and timings of the contact and the adhesive scene in every mode of ``modes``."""
    rows = []
    for kind, run, n in (("contact", contact, n_contact), ("adhesive", adhesive, n_adhesive)):
        if kind not in kinds:
            continue
        for mode in modes:
            t0 = time.perf_counter()
            res = run(n, mode)
            rows.append({"kind": kind, "parallel": mode, "digest": digest(res),
                         "success": bool(res.success), "wall": time.perf_counter() - t0,
                         "compile": res.timings.get("compile", 0.0)})
    return rows

def in_threads(n_threads, call):
    """``call()`` from ``n_threads`` Python threads released at once; their results."""
    barrier = threading.Barrier(n_threads)
    results = [None] * n_threads
    def work(i):
        barrier.wait()
        try:
            results[i] = call()
        except BaseException as exc:
            results[i] = exc
    threads = [threading.Thread(target=work, args=(i,)) for i in range(n_threads)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for r in results:
        if isinstance(r, BaseException):
            raise r
    return results

def cmd_solve(spec):
    t0 = time.perf_counter()
    rows = solve_all(spec["modes"], spec["kinds"])
    print(json.dumps({"file": pf.__file__, "rows": rows, "cache": cache_stats(),
                      "wall": time.perf_counter() - t0}))

def cmd_workqueue(spec):
    """4 threads at once call solve_contact in every mode of spec["modes"], spec["rounds"]
    times; every result is compared with the serial one."""
    import numba
    wanted = {}
    for mode in spec["modes"]:
        n = spec["n_prange"] if mode == "prange" else spec["n"]
        key = (spec["kind"], n)
        if key not in wanted:
            run = contact if spec["kind"] == "contact" else adhesive
            wanted[key] = digest(run(n, False))
    runs = []
    for _ in range(spec["rounds"]):
        for mode in spec["modes"]:
            n = spec["n_prange"] if mode == "prange" else spec["n"]
            run = contact if spec["kind"] == "contact" else adhesive
            got = in_threads(4, lambda: digest(run(n, mode)))
            runs.append({"parallel": mode, "n": n,
                         "equal": all(g == wanted[(spec["kind"], n)] for g in got)})
    print(json.dumps({"file": pf.__file__, "layer": numba.threading_layer(), "runs": runs}))

def cmd_nested(spec):
    """User threads, and the package's own pool threads, calling solve_contact."""
    from concurrent.futures import ThreadPoolExecutor
    from persson_fast import sweep
    from persson_fast.adhesion import runner as adhesion
    modes = []
    original = sweep.run_rows
    def spy(*args, **kwargs):
        mode = original(*args, **kwargs)
        modes.append((threading.current_thread().name, mode))
        return mode
    sweep.run_rows = adhesion.run_rows = spy
    n = spec["n"]
    want_c, want_a = digest(contact(n, False)), digest(adhesive(8, False))
    modes.clear()
    timeout = spec["timeout"]
    with ThreadPoolExecutor(4, thread_name_prefix="user") as pool:
        futures = [pool.submit(lambda: digest(contact(n, None))) for _ in range(4)]
        futures.append(pool.submit(lambda: digest(adhesive(8, None))))
        user = [f.result(timeout=timeout) for f in futures]
    modes_user = list(modes)
    modes.clear()
    inner = sweep._get_pool(sweep.n_threads())
    futures = [inner.submit(lambda p=p: digest(contact(n, p))) for p in (None, True, "threads")]
    futures.append(inner.submit(lambda: digest(adhesive(8, None))))
    pooled = [f.result(timeout=timeout) for f in futures]
    print(json.dumps({
        "user_equal": user[:4] == [want_c] * 4 and user[4] == want_a,
        "pool_equal": pooled[:3] == [want_c] * 3 and pooled[3] == want_a,
        "user_modes": sorted({m for _, m in modes_user}),
        "pool_modes": sorted({(t.split("_")[0], m) for t, m in modes}),
    }))

def cmd_thread_counts(spec):
    """Threads that set different numba thread counts call the default sweep, repeatedly."""
    import numba
    want = digest(contact(spec["n"], False))
    results = []
    def work(count):
        numba.set_num_threads(count)
        for _ in range(spec["iterations"]):
            try:
                results.append(digest(contact(spec["n"], None)) == want)
            except Exception as exc:
                results.append(repr(exc))
    threads = [threading.Thread(target=work, args=(c,)) for c in spec["counts"]]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    print(json.dumps({"calls": len(results), "failures": [r for r in results if r is not True]}))

if __name__ == "__main__":
    {"solve": cmd_solve, "workqueue": cmd_workqueue, "nested": cmd_nested,
     "thread_counts": cmd_thread_counts}[sys.argv[1]](json.loads(sys.argv[2]))
'''

_child = {"__name__": "persson_fast_child"}
exec(compile(CHILD, "<test_threads CHILD>", "exec"), _child)
contact, adhesive, digest = _child["contact"], _child["adhesive"], _child["digest"]

#: the checks that start processes need the compiled kernels (their disk cache, numba's
#: threading layer); under NUMBA_DISABLE_JIT=1 (the coverage run) there is neither
needs_jit = pytest.mark.skipif(numba.config.DISABLE_JIT,
                               reason="NUMBA_DISABLE_JIT: no compiled kernels, no disk cache")


def child_env(cache_dir=None, **extra) -> dict:
    """The environment of a child: this package first on the path, optionally its own cache."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([PACKAGE_ROOT, *filter(None, [env.get("PYTHONPATH")])])
    if cache_dir is not None:
        env["NUMBA_CACHE_DIR"] = str(cache_dir)
    env.update(extra)
    return env


def start_child(command: str, arg, env) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-c", CHILD, command, json.dumps(arg)], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def finish(proc: subprocess.Popen, timeout=CHILD_TIMEOUT) -> dict:
    """Wait for a child; its JSON report (its stderr in the failure message otherwise)."""
    try:
        out, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        proc.kill()
        out, err = proc.communicate()
        pytest.fail(f"child process did not finish within {timeout} s (deadlock?)\n{err[-3000:]}")
    assert proc.returncode == 0, f"child exited with rc {proc.returncode}\n{err[-3000:]}"
    return json.loads(out.strip().splitlines()[-1])


def run_at_once(n: int, command: str, arg, env, timeout=CHILD_TIMEOUT):
    """Start ``n`` children together; their reports and the wall time of the whole group."""
    t0 = time.perf_counter()
    procs = [start_child(command, arg, env) for _ in range(n)]
    try:
        reports = [finish(p, timeout) for p in procs]
    finally:
        for p in procs:
            if p.poll() is None:
                p.kill()
                p.wait()
    return reports, time.perf_counter() - t0


def arrays(res) -> dict:
    return {f.name: getattr(res, f.name) for f in dataclasses.fields(res)
            if isinstance(getattr(res, f.name), np.ndarray)}


def assert_bitwise(a, b) -> None:
    """Every array of two results has the same dtype, shape and bytes."""
    xa, xb = arrays(a), arrays(b)
    assert xa.keys() == xb.keys()
    for name in xa:
        x, y = np.ascontiguousarray(xa[name]), np.ascontiguousarray(xb[name])
        assert (x.dtype, x.shape) == (y.dtype, y.shape), name
        assert x.tobytes() == y.tobytes(), f"{name} differs: max |diff| = " \
            f"{np.nanmax(np.abs(x.astype(float) - y.astype(float)), initial=0)}"
    assert (a.status == b.status).all() and a.message == b.message


@pytest.fixture
def modes_used(monkeypatch):
    """The modes ("serial", "threads", "prange") the sweeps of a test actually ran in; each
    mode's sweep size (rows) is kept in ``modes_used.rows`` alongside."""
    seen = _Modes()
    original = sweep.run_rows

    def spy(*args, **kwargs):
        mode = original(*args, **kwargs)
        seen.append(mode)
        seen.rows.append(args[5] if len(args) > 5 else kwargs["n"])
        return mode

    monkeypatch.setattr(sweep, "run_rows", spy)
    monkeypatch.setattr(adhesion_module, "run_rows", spy)
    return seen


class _Modes(list):
    """The modes of the sweeps run, with their numbers of rows in ``rows``."""

    def __init__(self):
        super().__init__()
        self.rows = []

    def clear(self):
        super().clear()
        self.rows.clear()

    def as_expected(self, parallel) -> bool:
        """Every sweep ran in the mode its own number of rows asks for (the adhesive fixed
        point sweeps subsets of the pressures: a probe, a tightening, a re-centred grid)."""
        return len(self) > 0 and all(m == expected_mode(parallel, n)
                                     for m, n in zip(self, self.rows))


def expected_mode(parallel, n: int) -> str:
    """The mode a sweep of n pressures must run in on this machine."""
    if parallel is False or n <= 1:
        return "serial"
    if parallel == "prange":
        return "prange"
    if sweep.n_threads() < 2 or (parallel is None and n < sweep.PARALLEL_MIN_PRESSURES):
        return "serial"
    return "threads"


@pytest.fixture(scope="module")
def serial_results():
    return {"contact": contact(40, False), "adhesive": adhesive(8, False)}


# --- bitwise equality --------------------------------------------------------------------
@pytest.mark.parametrize("parallel", PARALLEL, ids=PARALLEL_IDS)
def test_contact_cn_bitwise_equal_to_serial(parallel, serial_results, modes_used):
    want = serial_results["contact"]
    assert want.success, want.message
    assert want.area[0] == 0.0 and want.area[-1] > 0.999  # 0 and far beyond full contact
    assert_bitwise(contact(40, parallel), want)
    assert modes_used == [expected_mode(parallel, 40)]


# the prange case is slow: the parallel adhesive sweep is compiled on every run (prange
# kernels are not cached, ~35 s on 2 cores); the other drivers stay in CI
@pytest.mark.parametrize("parallel", [pytest.param(p, marks=pytest.mark.slow) if p == "prange"
                                      else p for p in PARALLEL], ids=PARALLEL_IDS)
def test_adhesion_bitwise_equal_to_serial(parallel, serial_results, modes_used):
    want = serial_results["adhesive"]
    assert want.success, want.message
    assert_bitwise(adhesive(8, parallel), want)
    assert modes_used.as_expected(parallel), (list(modes_used), modes_used.rows)
    assert modes_used[0] == expected_mode(parallel, 8)          # the first sweep: every row


def test_adhesion_in_tension_bitwise_equal_to_serial(modes_used):
    """Tensions, some beyond pull-off (status checked against pull_off): threads == serial."""
    p = np.array([-2e6, -5e5, -1e5, 0.0, 1e5, 1e6, 1e7, 1e8, 1e9])
    run = lambda par: pf.solve_contact(pf.seed_scene(), p, e_star=pf.seed_e_star(),  # noqa: E731
                                       work_of_adhesion=0.06, rtol=1e-3, parallel=par)
    want = run(False)
    assert np.any(want.area == 0) and np.any(want.area > 0)
    assert_bitwise(run(None), want)
    assert "threads" in modes_used or sweep.n_threads() < 2


def wall_scene():
    """A smooth curved wall sigma_a(G) [Pa] and pressures from -0.25 Pa (-sigma_a(0) = -0.3 Pa)."""
    G = np.linspace(0.0, 4.0, 20) ** 2                           # [Pa^2]
    sigma_a = 0.3 + 0.2 * np.sqrt(G) - 0.01 * G                    # [Pa]
    p = np.concatenate([[-0.25, -0.1, 0.0], np.geomspace(1e-3, 20.0, 18)])
    return G, sigma_a, p


@pytest.mark.parametrize("method", ["cn", "fixed-grid", "bnr"])
@pytest.mark.parametrize("parallel", PARALLEL, ids=PARALLEL_IDS)
def test_diffusion_with_wall_bitwise_equal_to_serial(method, parallel, modes_used):
    if parallel == "prange" and method != "cn":
        pytest.skip("one prange kernel suffices here (each compiles per process, ~5-20 s); "
                    "test_fixedgrid/test_bnr compare their prange sweeps with the serial ones")
    G, sigma_a, p = wall_scene()
    want = pf.solve_diffusion(G, p, sigma_a, method=method, rtol=1e-3, parallel=False)
    assert want.success, want.message
    assert 0 < want.area[0, -1] < want.area[-1, -1] <= 1
    got = pf.solve_diffusion(G, p, sigma_a, method=method, rtol=1e-3, parallel=parallel)
    assert_bitwise(got, want)
    assert modes_used[-1] == expected_mode(parallel, p.size)


#: 0 and 1 pressure; 2, 3: fewer than the pool's blocks and than PARALLEL_MIN_PRESSURES;
#: 13: not a multiple of the blocks (4 per thread)
COUNTS = [0, 1, 2, 3, 13]


@pytest.mark.parametrize("n", COUNTS)
@pytest.mark.parametrize("parallel", PARALLEL, ids=PARALLEL_IDS)
def test_pressure_counts_contact(n, parallel, modes_used):
    want = contact(n, False)
    assert want.area.shape == (n,) and want.success
    modes_used.clear()
    assert_bitwise(contact(n, parallel), want)
    assert modes_used[-1] == expected_mode(parallel, n)


@pytest.mark.parametrize("n", COUNTS)
@pytest.mark.parametrize("parallel", PARALLEL, ids=PARALLEL_IDS)
def test_pressure_counts_adhesion(n, parallel, modes_used):
    want = adhesive(n, False)
    assert want.area.shape == (n,) and want.success
    modes_used.clear()
    assert_bitwise(adhesive(n, parallel), want)
    assert n == 0 or modes_used.as_expected(parallel), (list(modes_used), modes_used.rows)


@pytest.mark.parametrize("n", [0, 1, 2, 5, 7, 8, 9, 13, 16, 17, 64, 401])
@pytest.mark.parametrize("blocks", [1, 2, 3, 8])
def test_interleave_is_a_permutation_cut_into_blocks(n, blocks):
    order = sweep.interleave(n, blocks)
    assert sorted(order.tolist()) == list(range(n))
    bounds = sweep._block_bounds(n, blocks)
    if n == 0:
        assert order.size == 0
        return
    assert bounds[0][0] == 0 and bounds[-1][1] == n
    assert all(hi > lo for lo, hi in bounds)
    assert all(a[1] == b[0] for a, b in zip(bounds, bounds[1:]))
    assert max(hi - lo for lo, hi in bounds) - min(hi - lo for lo, hi in bounds) <= 1
    # each block samples the whole range: rows lo, lo + blocks, lo + 2 blocks, ...
    for i, (lo, hi) in enumerate(bounds):
        assert order[lo:hi].tolist() == list(range(i, n, len(bounds)))


def test_default_is_threads_from_the_first_call():
    """No compiled prange kernel is needed for the default to run on threads."""
    if sweep.n_threads() < 2:
        pytest.skip("numba allows one thread here")
    assert sweep.choose_parallel(None, 400) == "threads"
    assert sweep.choose_parallel(None, sweep.PARALLEL_MIN_PRESSURES) == "threads"
    assert sweep.choose_parallel(None, sweep.PARALLEL_MIN_PRESSURES - 1) == "serial"
    assert sweep.choose_parallel(True, 2) == "threads"


def test_warmup_prange_reaches_the_adhesive_prange_sweep(monkeypatch):
    """``warmup(prange=True)`` compiles the adhesive ``prange`` sweep too (a warm-up of one
    pressure would run serially and leave it to the first real call). The kernel is replaced
    by a recorder: nothing is compiled here."""
    calls = []
    monkeypatch.setattr(adhesion_module, "adhesive_sweep_parallel",
                        lambda *args: calls.append(len(args[10])))   # p_scaled
    adhesion_module.warm_adhesion(prange=True)     # what pf.warmup(prange=True) calls
    assert calls, "warmup(prange=True) never called the adhesive prange sweep"


# --- several processes on one disk cache -------------------------------------------------
def check_reports(reports, modes, want, kinds=("contact", "adhesive")):
    for rep in reports:
        assert Path(rep["file"]).resolve().is_relative_to(PACKAGE_ROOT), rep["file"]
        got = {(r["kind"], json.dumps(r["parallel"])): r["digest"] for r in rep["rows"]}
        assert all(r["success"] for r in rep["rows"])
        for (kind, mode), digest_ in got.items():
            assert digest_ == want[kind], f"{kind} with parallel={mode} differs from serial"
        assert len(got) == len(kinds) * len(modes)


# slow: every kernel compiled from an empty cache in two processes (~70 s on 2 cores);
# tests/test_compile_split.py keeps a cold-cache run in CI
@pytest.mark.slow
@needs_jit
def test_processes_share_a_cold_then_warm_cache(tmp_path):
    """3 processes at once on one empty cache (all compile, all write it), then 3 at once on
    the warm cache (all load it); every result bitwise equals the in-process serial one."""
    want = {"contact": digest(contact(40, False)), "adhesive": digest(adhesive(8, False))}
    modes = [None, "threads", False]
    env = child_env(tmp_path / "numba_cache")
    spec = {"modes": modes, "kinds": ["contact", "adhesive"]}
    cold, cold_wall = run_at_once(3, "solve", spec, env)
    check_reports(cold, modes, want)
    assert any(rep["cache"]["sweep"]["misses"] > 0 for rep in cold)  # the cache was cold
    assert any((tmp_path / "numba_cache").rglob("*.nbi"))
    warm, warm_wall = run_at_once(3, "solve", spec, env)
    check_reports(warm, modes, want)
    for rep in warm:
        for kernel in ("sweep", "adhesive", "fixed point", "adhesive step", "grid"):
            assert rep["cache"][kernel]["misses"] == 0 < rep["cache"][kernel]["hits"], rep["cache"]
    walls = [[round(r["wall"], 2) for r in reps] for reps in (cold, warm)]
    loads = [round(sum(x["compile"] for x in r["rows"]), 2) for r in warm]
    print(f"\ncold: 3 processes in {cold_wall:.1f} s (solving {walls[0]} s); warm: 3 processes "
          f"in {warm_wall:.1f} s (solving {walls[1]} s, of which loading the kernels {loads} s)")


@needs_jit
def test_prange_from_processes_at_once():
    """"prange" sweeps are compiled in each process (not cached on disk): 2 at once on the
    session's cache (the serial kernels load from it), no crash. The contact scene only: the
    adhesive prange sweep compiles in 6-20 s a process; it is compared in this process above."""
    want = {"contact": digest(contact(40, False))}
    reports, wall = run_at_once(2, "solve", {"modes": ["prange", None], "kinds": ["contact"]},
                                child_env())
    check_reports(reports, ["prange", None], want, kinds=("contact",))
    print(f"\nprange: 2 processes in {wall:.1f} s")


# --- numba's workqueue threading layer ---------------------------------------------------
def run_workqueue(spec, env=None):
    env = child_env(NUMBA_THREADING_LAYER="workqueue") if env is None else env
    rep = finish(start_child("workqueue", spec, env))
    assert rep["layer"] == "workqueue"
    return rep


@needs_jit
def test_workqueue_threads_from_4_python_threads():
    """Default and True run on the package's thread pool, which never enters numba's threading
    layer: 4 threads x 1000 pressures at once, 3 rounds, under workqueue."""
    rep = run_workqueue({"kind": "contact", "modes": [None, True], "n": 1000, "n_prange": 64,
                         "rounds": 3})
    assert len(rep["runs"]) == 6 and all(r["equal"] for r in rep["runs"]), rep["runs"]


@needs_jit
def test_workqueue_prange_from_4_python_threads():
    """"prange" under workqueue is serialised, including its first call (which compiles):
    4 threads at once, 3 rounds, then default and True mixed in."""
    rep = run_workqueue({"kind": "contact", "modes": ["prange", None, True], "n": 1000,
                         "n_prange": 64, "rounds": 3})
    assert len(rep["runs"]) == 9 and all(r["equal"] for r in rep["runs"]), rep["runs"]


# slow: the prange adhesive sweep compiled (not cached) and run from 4 threads (~40 s);
# the prange and threads workqueue tests above stay in CI
@pytest.mark.slow
@needs_jit
def test_workqueue_adhesion_from_4_python_threads():
    """The adhesive sweep under workqueue from 4 threads: default, True and "prange"."""
    rep = run_workqueue({"kind": "adhesive", "modes": ["prange", None, True], "n": 64,
                         "n_prange": 8, "rounds": 2})
    assert len(rep["runs"]) == 6 and all(r["equal"] for r in rep["runs"]), rep["runs"]


# --- nesting -----------------------------------------------------------------------------
@needs_jit
def test_calls_from_user_threads_and_pool_threads_finish():
    """4 user threads x 400 pressures (and an adhesive solve) on the default, and solves from
    inside the package's own pool, finish with the serial result (pools never nest)."""
    rep = finish(start_child("nested", {"n": 400, "timeout": 120}, child_env()), timeout=300)
    assert rep["user_equal"] and rep["pool_equal"], rep
    threaded = "threads" if sweep.n_threads() >= 2 else "serial"
    # (the adhesive fixed point also sweeps subsets of its pressures: a subset of fewer than
    # PARALLEL_MIN_PRESSURES rows runs serially, as a call with that many pressures would)
    assert (threaded in rep["user_modes"] and set(rep["user_modes"]) <= {threaded, "serial"}
            or sweep.n_threads() < 2), rep
    # the parallel calls made on a pool thread ran serially there
    assert rep["pool_modes"] == [["persson", "serial"]], rep


@needs_jit
def test_threads_with_different_thread_counts():
    """Callers on threads with different ``numba.set_num_threads`` (2, 3, 4 of
    NUMBA_NUM_THREADS=4) share the package's pools safely: no "cannot schedule new futures
    after shutdown", the serial result every time."""
    spec = {"counts": [2, 3, 4], "n": 24, "iterations": 150}
    rep = finish(start_child("thread_counts", spec, child_env(NUMBA_NUM_THREADS="4")),
                 timeout=300)
    assert rep["calls"] == 450 and not rep["failures"], rep["failures"][:3]


# --- validation --------------------------------------------------------------------------
BAD = ["yes", "Threads", "serial", 2, 0, 1.0, [True]]


@pytest.mark.parametrize("bad", BAD, ids=repr)
def test_bad_parallel_names_parallel(bad):
    s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    calls = [
        lambda: pf.solve_contact(s, [1e6, 2e6], e_star=1e9, method="cn", parallel=bad),
        lambda: pf.solve_contact(pf.seed_scene(), [1e6, 2e6], e_star=pf.seed_e_star(),
                                 work_of_adhesion=0.06, rtol=1e-3, parallel=bad),
        lambda: pf.solve_diffusion([0.0, 1.0], [0.5, 1.0], method="cn", parallel=bad),
    ]
    for call in calls:
        with pytest.raises(ValueError, match="parallel"):
            call()


@pytest.mark.parametrize("bad", ["yes", 2], ids=repr)
def test_bad_parallel_refused_without_a_compiled_sweep(bad):
    """Refused also where no compiled sweep runs: the closed form, no pressures."""
    s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    calls = [
        lambda: pf.solve_contact(s, [1e6], e_star=1e9, parallel=bad),            # auto: analytic
        lambda: pf.solve_contact(s, [1e6], e_star=1e9, method="analytic", parallel=bad),
        lambda: pf.solve_diffusion([0.0, 1.0], [0.5], method="analytic", parallel=bad),
        lambda: pf.solve_contact(pf.seed_scene(), [], e_star=pf.seed_e_star(),
                                 work_of_adhesion=0.06, parallel=bad),
    ]
    for call in calls:
        with pytest.raises(ValueError, match="parallel"):
            call()
