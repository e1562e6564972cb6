"""Batch pressures through the compiled kernels: serially, on a thread pool or over ``prange``.

The model layer owns the scaling: diffusion times and stresses reach the kernels divided by
a scene scale, so the kernels never see a Pascal.
"""
from __future__ import annotations

import contextlib
import threading
import time

import numpy as np

from ._jit import announce_compile
from ._kernels.status import RTOL_NOT_MET
from .methods import METHODS, sweep_kernels

#: absolute part of the accuracy contract |dA| <= rtol A + CONTRACT_ATOL [-]
CONTRACT_ATOL = 1e-12

#: below this many pressures one thread does the whole batch: handing rows to the pool costs
#: about 0.1 ms per call (2-core machine), the work per pressure 0.05-20 ms
PARALLEL_MIN_PRESSURES = 4
#: blocks of rows per thread handed to the pool: more blocks balance better, each costs a
#: kernel call (~10 us)
BLOCKS_PER_THREAD = 4
#: the values of ``parallel`` a caller may pass
PARALLEL_CHOICES = (None, False, True, "threads", "prange")

_pools = {}
_pool_lock = threading.Lock()
_on_worker = threading.local()
_prange_lock = threading.Lock()


def n_threads() -> int:
    """The number of threads a parallel sweep uses: numba's (``NUMBA_NUM_THREADS``, or
    ``numba.set_num_threads`` on the calling thread)."""
    import numba

    return max(1, int(numba.get_num_threads()))


def check_parallel(parallel):
    """``parallel`` validated: None, False, True, "threads" or "prange"."""
    if isinstance(parallel, (bool, np.bool_)) or parallel is None:
        return None if parallel is None else bool(parallel)
    if isinstance(parallel, str) and parallel in ("threads", "prange"):
        return parallel
    raise ValueError(f"parallel must be None, False, True, 'threads' or 'prange'; got "
                     f"parallel = {parallel!r}")


def choose_parallel(parallel, n_p: int) -> str:
    """How a sweep of ``n_p`` pressures runs: "serial", "threads" or "prange".

    * None (default): "threads" for >= PARALLEL_MIN_PRESSURES pressures when numba allows more
      than one thread, else "serial";
    * True or "threads": a pool of Python threads, each calling the disk-cached serial sweep
      kernel (it releases the GIL) on a block of rows; nothing to compile beyond the serial
      kernel, so it is the default from the first call;
    * "prange": numba's ``prange`` sweep (compiled once per process, a few seconds, not cached
      on disk: numba issue 4807); under numba's ``workqueue`` threading layer, which does not
      allow concurrent entry, such calls are serialised;
    * False: one thread.

    A call made on one of the pool's own threads (a sweep inside a parallel task) runs
    serially, so pools never nest.
    """
    parallel = check_parallel(parallel)
    if parallel is False or n_p <= 1 or getattr(_on_worker, "flag", False):
        return "serial"
    if parallel == "prange":
        return "prange"
    if n_threads() < 2 or (parallel is None and n_p < PARALLEL_MIN_PRESSURES):
        return "serial"
    return "threads"


def interleave(n: int, blocks: int) -> np.ndarray:
    """A permutation that deals n rows round-robin into ``blocks`` contiguous blocks.

    The cost per pressure varies by orders of magnitude along a pressure scan (large
    pressures are nearly free), so contiguous blocks of the caller's order are badly
    unbalanced; dealt round-robin, every block holds a sample of the whole range. Every row is
    still computed by the same code, so the results are bitwise those of a serial sweep.
    """
    if n <= blocks:
        return np.arange(n)
    return np.concatenate([np.arange(i, n, blocks) for i in range(blocks)])


def _block_bounds(n: int, blocks: int):
    """[lo, hi) of each block of :func:`interleave`'s permutation."""
    sizes = [len(range(i, n, blocks)) for i in range(min(n, blocks))]
    bounds = np.concatenate([[0], np.cumsum(sizes)])
    return [(int(bounds[i]), int(bounds[i + 1])) for i in range(len(sizes))]


def _get_pool(threads: int):
    """The package's pool of ``threads`` workers (one pool per thread count, kept for the
    process: a caller on another Python thread may still be submitting to a pool, so none is
    ever shut down while the process runs)."""
    with _pool_lock:
        pool = _pools.get(threads)
        if pool is None:
            from concurrent.futures import ThreadPoolExecutor

            pool = ThreadPoolExecutor(max_workers=threads, thread_name_prefix="persson_fast",
                                      initializer=_mark_worker)
            _pools[threads] = pool
        return pool


def _mark_worker():
    _on_worker.flag = True


def _workqueue_layer() -> bool:
    """True when numba's parallel backend may be the workqueue, which does not allow
    concurrent entry from several Python threads (it aborts the process)."""
    import numba

    layer = str(numba.config.THREADING_LAYER).lower()
    if layer in ("tbb", "omp", "safe", "threadsafe"):
        return False          # named thread-safe layers (numba raises if they are missing)
    if layer == "workqueue":
        return True
    candidates = ("tbbpool",) if layer == "forksafe" else ("tbbpool", "omppool")
    for mod in candidates:
        try:
            __import__(f"numba.np.ufunc.{mod}")
            return False
        except Exception:  # noqa: BLE001 -- an unloadable backend is simply absent
            continue
    return True


def prange_guard():
    """A context for every call of a ``prange`` kernel (compilation included): a lock under
    numba's workqueue threading layer, which aborts the process when two Python threads enter
    it at once; nothing under the thread-safe layers (OpenMP, TBB)."""
    import contextlib

    return _prange_lock if _workqueue_layer() else contextlib.nullcontext()


def run_rows(kernel_serial, kernel_prange, args, rows_in, rows_out, n: int, parallel) -> str:
    """Call a sweep kernel over ``n`` rows, serially, on a thread pool or over ``prange``.

    Parameters
    ----------
    kernel_serial, kernel_prange : numba dispatchers of one sweep body (``njit_sweeps``).
    args : list -- the kernel's positional arguments.
    rows_in, rows_out : tuple of int -- positions in ``args`` of the per-row arrays (first axis
        = row): inputs (read) and outputs (written in place, also in ``args``).
    n : int -- number of rows.
    parallel : see :func:`choose_parallel`.

    Returns
    -------
    mode : str -- "serial", "threads" or "prange", the way the rows ran.

    Notes
    -----
    With threads, the rows are dealt round-robin into ``BLOCKS_PER_THREAD`` blocks per thread
    (:func:`interleave`) and each block is one call of the serial kernel on contiguous slices;
    each row is computed by the same compiled code as in a serial sweep, so the results are
    bitwise equal. A ``KeyboardInterrupt`` while waiting cancels the blocks not yet started.
    """
    mode = choose_parallel(parallel, n)
    if mode == "serial":
        kernel_serial(*args)
        return mode
    threads = n_threads()
    blocks = max(1, min(n, BLOCKS_PER_THREAD * threads))
    order = interleave(n, blocks)
    perm = list(args)
    for i in rows_in + rows_out:
        perm[i] = np.ascontiguousarray(args[i][order])
    if mode == "prange":
        with prange_guard():
            kernel_prange(*perm)
    else:
        sliced = set(rows_in + rows_out)
        pool = _get_pool(threads)
        futures = [pool.submit(kernel_serial, *[a[lo:hi] if i in sliced else a
                                                for i, a in enumerate(perm)])
                   for lo, hi in _block_bounds(n, blocks)]
        try:
            for f in futures:
                f.result()
        except BaseException:
            for f in futures:
                f.cancel()
            raise
    for i in rows_out:
        args[i][order] = perm[i]
    return mode


def is_compiled(func) -> bool:
    """True once a numba dispatcher holds a compiled signature.

    Reads the dispatcher's ``overloads`` mapping (cheap) rather than ``signatures`` (which
    rebuilds a list on every call and costs tens of microseconds).
    """
    overloads = getattr(func, "overloads", None)
    if overloads is not None:
        return len(overloads) > 0
    return len(getattr(func, "signatures", ())) > 0


#: the outputs of every grid sweep, in the order of the kernel signature
#: (:mod:`persson_fast._kernels.signature`): the one-wall ones, then the plastic pair
OUTPUTS = ("area", "load", "detached_area", "detached_load", "error_estimate")
PLASTIC_OUTPUTS = ("plastic_area", "plastic_load")


def run_sweep(G, sa_rows, pressures, *, rtol, method="cn", level=-1, n_damp=2, parallel=None,
              sy_rows=None):
    """Solve the diffusion for every pressure with a compiled method.

    Parameters
    ----------
    G : (n_t,) float64 -- diffusion times. [Pa^2]
    sa_rows : (n_p, n_t) float64 -- the lower wall (at -sigma_a) per pressure. [Pa]
    pressures : (n_p,) float64 -- nominal pressures. [Pa]
    rtol : float -- target relative accuracy. [-]
    method : str -- a compiled entry of :data:`persson_fast.METHODS`.
    level : int -- >= 0: explicit resolution level (doubles per level), ignoring rtol.
    n_damp : int -- Rannacher damping steps after wall jumps (for "strip": after the start
        and each kink).
    parallel : None, bool, "threads" or "prange" -- see :func:`choose_parallel`.
    sy_rows : (n_p, n_t) float64 or None -- the upper (yield) wall per pressure [Pa]; None:
        none (the kernel receives rows of length 0, and no plastic outputs are requested).
        A method without an upper wall answers finite values with status BAD_INPUT.

    Returns
    -------
    dict of arrays (area, load, detached_area, detached_load, error_estimate, with
    ``sy_rows`` also plastic_area and plastic_load, (n_p, n_t); status (n_p,); counts
    (n_p, 3): the method's work counters) and timings (seconds: ``solve``, ``compile`` if
    this call compiled the kernel).
    """
    G = np.ascontiguousarray(G, dtype=np.float64)
    sa_rows = np.ascontiguousarray(sa_rows, dtype=np.float64)
    pressures = np.ascontiguousarray(pressures, dtype=np.float64)
    n_p, n_t = sa_rows.shape
    upper = sy_rows is not None
    if upper:
        sy_rows = np.ascontiguousarray(sy_rows, dtype=np.float64)
    scaled = METHODS[method].get("scene_scale", True)
    scale = _scene_scale(G, sa_rows, pressures) if scaled else 1.0
    names = OUTPUTS + (PLASTIC_OUTPUTS if upper else ())
    out = {name: np.zeros((n_p, n_t)) for name in names}
    status = np.zeros(n_p, dtype=np.int64)
    counts = np.zeros((n_p, 3), dtype=np.int64)
    serial, par_kernel, lead = sweep_kernels(method)
    timings = {}
    mode = choose_parallel(parallel, n_p)
    kernel = par_kernel if mode == "prange" else serial
    if not is_compiled(kernel):
        t0 = time.perf_counter()
        with prange_guard() if mode == "prange" else contextlib.nullcontext():
            _warm(method, kernel)
        timings["compile"] = time.perf_counter() - t0
    if scaled:
        G, sa_rows, pressures = G / scale**2, sa_rows / scale, pressures / scale
        sy_rows = sy_rows / scale if upper else None
    args, rows_in, rows_out = _sweep_args(lead, G, sa_rows, sy_rows, pressures, rtol, level,
                                          n_damp, out, status, counts)
    t0 = time.perf_counter()
    run_rows(serial, par_kernel, args, rows_in, rows_out, n_p, parallel)
    timings["solve"] = time.perf_counter() - t0
    if scaled:
        for name in ("load", "detached_load") + (("plastic_load",) if upper else ()):
            out[name] *= scale
    if level < 0 and not METHODS[method].get("controls_error", True):
        # a method without its own a-posteriori control: a result whose error estimate
        # exceeds rtol at a returned G says so (the contract: within rtol, or flagged)
        over = np.any(out["error_estimate"] > rtol * np.abs(out["area"]) + CONTRACT_ATOL,
                      axis=1)
        status[(status == 0) & over] = RTOL_NOT_MET
    out["status"] = status
    out["counts"] = counts
    return out, timings


def _sweep_args(lead, G, sa_rows, sy_rows, pressures, rtol, level, n_damp, out, status,
                counts):
    """The positional arguments of a sweep (:mod:`persson_fast._kernels.signature`) and the
    positions of its per-row inputs and outputs (for :func:`run_rows`).

    ``sy_rows`` None: rows of length 0 for the upper wall and, unless ``out`` holds them, for
    the plastic outputs (absent, not requested).
    """
    n_p = pressures.shape[0]
    absent = np.zeros((n_p, 0))
    outs = [out[name] if name in out else absent for name in OUTPUTS + PLASTIC_OUTPUTS]
    args = [*lead, G, sa_rows, absent if sy_rows is None else sy_rows, pressures, float(rtol),
            int(level), int(n_damp), *outs, status, counts]
    first = len(lead)
    rows_in = (first + 1, first + 2, first + 3)
    rows_out = tuple(range(first + 7, len(args)))
    return args, rows_in, rows_out


def _scene_scale(G, sa_rows, pressures) -> float:
    """A stress scale of the scene [Pa]: sqrt of the largest G, else the largest stress."""
    candidates = [np.sqrt(np.max(G)) if G.size else 0.0,
                  np.max(np.abs(pressures)) if pressures.size else 0.0,
                  np.max(np.abs(sa_rows)) if sa_rows.size else 0.0]
    scale = max(candidates)
    return float(scale) if scale > 0 and np.isfinite(scale) else 1.0


def _warm(method, kernel) -> None:
    """Compile (or load from the disk cache) ``kernel``, a sweep of ``method``, by one call on
    a two-point schedule (with an upper wall for a two-wall method), built by the same
    :func:`_sweep_args` as every solve, so that it has the solves' types."""
    _, _, lead = sweep_kernels(method)
    two = bool(METHODS[method].get("two_walls", False))
    out = {name: np.zeros((1, 2)) for name in OUTPUTS + (PLASTIC_OUTPUTS if two else ())}
    args, _, _ = _sweep_args(lead, np.array([0.0, 1.0]), np.zeros((1, 2)),
                             np.ones((1, 2)) if two else None, np.array([0.5]), 1e-3, -1, 2,
                             out, np.zeros(1, dtype=np.int64), np.zeros((1, 3), dtype=np.int64))
    if hasattr(kernel, "_cache"):             # a disk-cached serial sweep
        import numba

        # the first sweep of a grid method on a machine compiles it
        announce_compile(f"method {method!r}", [(kernel, tuple(numba.typeof(a) for a in args))])
    kernel(*args)


def warm_sweeps(prange: bool = False, method: str = "cn") -> dict:
    """Compile (or load from the disk cache) the sweep kernels of ``method`` (default the
    default method of :func:`persson_fast.solve_diffusion`); the seconds spent per kernel
    (``serial``; ``prange`` too when asked). :func:`persson_fast.warmup` adds the adhesive
    kernels."""
    timings = {}
    serial, parallel, _ = sweep_kernels(method)
    for name, kernel in (("serial", serial), ("prange", parallel)):
        if name == "prange" and not prange:
            continue
        t0 = time.perf_counter()
        with prange_guard() if name == "prange" else contextlib.nullcontext():
            _warm(method, kernel)
        timings[name] = time.perf_counter() - t0
    return timings
