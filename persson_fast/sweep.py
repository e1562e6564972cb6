"""Batch pressures through the compiled kernels, serially or over ``prange`` threads.

The model layer owns the scaling: diffusion times and stresses reach the kernels divided by
a scene scale, so the kernels never see a Pascal.
"""
from __future__ import annotations

import time

import numpy as np

from ._kernels.sweep import sweep_parallel, sweep_serial
from .methods import METHODS

#: below this many pressures the thread start-up costs more than it saves
PARALLEL_MIN_PRESSURES = 4
#: the parallel kernels are not cached on disk, so compiling them costs ~4 s per process
#: (2-core machine); before they are compiled, only a batch this large goes parallel
PARALLEL_COMPILE_PRESSURES = 1000


def choose_parallel(parallel, n_p: int, kernel) -> bool:
    """The ``parallel=None`` cost model: threads when the parallel kernel is compiled and
    there are >= PARALLEL_MIN_PRESSURES pressures, or when the batch is large enough
    (>= PARALLEL_COMPILE_PRESSURES) to pay for compiling it. ``pf.warmup()`` compiles it."""
    if parallel is not None:
        return bool(parallel)
    if is_compiled(kernel):
        return n_p >= PARALLEL_MIN_PRESSURES
    return n_p >= PARALLEL_COMPILE_PRESSURES


def interleave(n: int) -> np.ndarray:
    """A permutation that deals n items round-robin over the threads.

    ``prange`` hands each thread a contiguous block; per-pressure cost varies by orders of
    magnitude along a pressure scan (large pressures are nearly free), so contiguous blocks
    are badly unbalanced. Dealing the rows out round-robin balances them; every row is still
    computed by the same code, so serial and parallel results stay bitwise equal.
    """
    import numba

    t = max(1, int(numba.get_num_threads()))
    return np.concatenate([np.arange(i, n, t) for i in range(t)]) if n > t else np.arange(n)


def is_compiled(func) -> bool:
    """True once a numba dispatcher holds a compiled signature.

    Reads the dispatcher's ``overloads`` mapping (cheap) rather than ``signatures`` (which
    rebuilds a list on every call and costs tens of microseconds).
    """
    overloads = getattr(func, "overloads", None)
    if overloads is not None:
        return len(overloads) > 0
    return len(getattr(func, "signatures", ())) > 0


def _kernels_for(method: str):
    """(serial, parallel, leading arguments, takes n_damp) of a method's sweep kernels."""
    info = METHODS[method]
    if info["family"] == "grid":
        return sweep_serial, sweep_parallel, (int(info["variant"]),), True
    if info["family"] == "fixed-grid":
        from ._kernels.fixedgrid import fixedgrid_sweep_parallel, fixedgrid_sweep_serial
        return fixedgrid_sweep_serial, fixedgrid_sweep_parallel, (), True
    if info["family"] == "integral":
        from ._kernels.bnr import bnr_sweep_parallel, bnr_sweep_serial
        return bnr_sweep_serial, bnr_sweep_parallel, (), False
    raise ValueError(f"method {method!r} has no compiled sweep")


def run_sweep(G, sa_rows, pressures, *, rtol, method="cn", level=-1, n_damp=2, parallel=None):
    """Solve the diffusion for every pressure with a compiled method.

    Parameters
    ----------
    G : (n_t,) float64 -- diffusion times. [Pa^2]
    sa_rows : (n_p, n_t) float64 -- wall positions per pressure. [Pa]
    pressures : (n_p,) float64 -- nominal pressures. [Pa]
    rtol : float -- target relative accuracy. [-]
    method : str -- a compiled entry of :data:`persson_fast.METHODS`.
    level : int -- >= 0: explicit resolution level (doubles per level), ignoring rtol.
    n_damp : int -- Rannacher damping steps after wall jumps.
    parallel : bool or None -- None: see :func:`choose_parallel`.

    Returns
    -------
    dict of arrays (area, load, detached_area, detached_load, error_estimate, status,
    counts (n_p, 3): nodes, steps, node-steps) and timings (seconds: ``solve``, ``compile``
    if this call compiled the kernel).
    """
    G = np.ascontiguousarray(G, dtype=np.float64)
    sa_rows = np.ascontiguousarray(sa_rows, dtype=np.float64)
    pressures = np.ascontiguousarray(pressures, dtype=np.float64)
    n_p, n_t = sa_rows.shape
    scale = _scene_scale(G, sa_rows, pressures)
    Gs = G / scale**2
    sas = sa_rows / scale
    ps = pressures / scale
    out = {name: np.zeros((n_p, n_t)) for name in
           ("area", "load", "detached_area", "detached_load", "error_estimate")}
    status = np.zeros(n_p, dtype=np.int64)
    counts = np.zeros((n_p, 3), dtype=np.int64)
    serial, par_kernel, lead, damped = _kernels_for(method)
    parallel = choose_parallel(parallel, n_p, par_kernel)
    kernel = par_kernel if parallel else serial
    timings = {}
    if not is_compiled(kernel):
        t0 = time.perf_counter()
        _warm(kernel, lead, damped)
        timings["compile"] = time.perf_counter() - t0
    order = interleave(n_p) if parallel else np.arange(n_p)
    sas_o = np.ascontiguousarray(sas[order])
    ps_o = np.ascontiguousarray(ps[order])
    mid = (float(rtol), int(level)) + ((int(n_damp),) if damped else ())
    t0 = time.perf_counter()
    kernel(*lead, Gs, sas_o, ps_o, *mid, out["area"], out["load"], out["detached_area"],
           out["detached_load"], out["error_estimate"], status, counts)
    timings["solve"] = time.perf_counter() - t0
    inverse = np.empty_like(order)
    inverse[order] = np.arange(n_p)
    for key in out:
        out[key] = out[key][inverse]
    out["load"] *= scale
    out["detached_load"] *= scale
    out["status"] = status[inverse]
    out["counts"] = counts[inverse]
    return out, timings


def _scene_scale(G, sa_rows, pressures) -> float:
    """A stress scale of the scene [Pa]: sqrt of the largest G, else the largest stress."""
    candidates = [np.sqrt(np.max(G)) if G.size else 0.0,
                  np.max(np.abs(pressures)) if pressures.size else 0.0,
                  np.max(np.abs(sa_rows)) if sa_rows.size else 0.0]
    scale = max(candidates)
    return float(scale) if scale > 0 and np.isfinite(scale) else 1.0


def _warm(kernel, lead=(0,), damped=True) -> None:
    G = np.array([0.0, 1.0])
    sa = np.zeros((1, 2))
    p = np.array([1.0])
    outs = [np.zeros((1, 2)) for _ in range(5)]
    mid = (1e-3, -1) + ((2,) if damped else ())
    kernel(*lead, G, sa, p, *mid, *outs, np.zeros(1, dtype=np.int64),
           np.zeros((1, 3), dtype=np.int64))


def warmup(parallel: bool = True) -> dict:
    """Compile (or load from the cache) the sweep kernels now; return the seconds spent."""
    from .adhesion import warm_adhesion

    timings = {}
    for name, kernel in (("serial", sweep_serial), ("parallel", sweep_parallel)):
        if name == "parallel" and not parallel:
            continue
        t0 = time.perf_counter()
        _warm(kernel)
        timings[name] = time.perf_counter() - t0
    t0 = time.perf_counter()
    warm_adhesion(parallel)
    timings["adhesion"] = time.perf_counter() - t0
    return timings
