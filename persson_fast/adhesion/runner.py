"""The compiled adhesive fixed point, called: its inputs per row, its controls, its compile.

One call of :func:`_run` solves seed Eqs. 8-9 for a batch of pressures on one zeta grid in
compiled code (:mod:`persson_fast._kernels.adhesion`); :mod:`persson_fast.adhesion.ladder`
runs it on nested grids, :mod:`persson_fast.adhesion.fixed_point` is the entry point.
"""

import threading
import time

import numpy as np

from .._jit import announce_compile, compile_for, compiling_beside
from .._kernels.adhesion import (DEFAULT_M_HIST, DEFAULT_MAX_ITER, DEFAULT_N_DAMP, DEFAULT_OMEGA,
                               FIXED_POINT_SIGNATURE, STEP_SIGNATURE, adhesive_sweep_parallel,
                               adhesive_sweep_serial, elastic_step, elastic_step_linked,
                               fixed_point, yield_step, yield_step_linked)
from .._kernels.similarity import GRID_SIGNATURE, _solve_grid_tol
from .._kernels.theories import WM17, YP08
from ..sweep import choose_parallel, is_compiled, prange_guard, run_rows


__all__ = ["ADHESION_DEFAULTS", "THEORY_CODES", "warm_adhesion", "warm_adhesive_yield"]

#: the corrected theories the fixed point serves, and their kernel codes
THEORY_CODES = {"yp08": YP08, "wm17": WM17}

#: iteration controls of the fixed point (Anderson depth 0 = plain relaxation; see
#: :data:`persson_fast._kernels.adhesion.DEFAULT_OMEGA`)
ADHESION_DEFAULTS = {"max_iter": DEFAULT_MAX_ITER, "m_hist": DEFAULT_M_HIST,
                     "omega": DEFAULT_OMEGA, "n_damp": DEFAULT_N_DAMP}


def _rows(a, n_p, width):
    """``a`` as (n_p, width) C-contiguous rows: a 1-D array (one grid for every row) repeated,
    or rows of at most ``width`` entries padded with zeros."""
    a = np.asarray(a, dtype=float)
    if a.ndim == 1:
        return np.repeat(a[None, :], n_p, axis=0)
    if a.shape[1] == width and a.flags.c_contiguous and a.flags.writeable:
        return a
    out = np.zeros((n_p, width))
    out[:, :a.shape[1]] = a
    return out


def _run(G, c, wa, wb, gamma_s, p_scaled, rtol, parallel, controls, x_init=None, variant=0,
         onset=True, theory=0, theory_gamma=1.0, sy=None, n_z=None):
    """The compiled fixed point of every pressure: outputs (8 arrays (n_p, n_z): area,
    sigma_a, g, u, load, detached area and load, error; with a yield wall ``sy`` (n_p, n_z)
    two more, the plastic area and load), status, iterations, residual and timings.

    ``G``, ``c`` (n_z,) and ``wa``, ``wb`` (n_z - 1,): one zeta grid for every pressure; or
    rows (n_p, n_max) and (n_p, n_max - 1) with ``n_z`` (n_p,) the number of nodes of each
    row's own grid (the outputs then (n_p, n_max), each row's first n_z entries). ``rtol``:
    the diffusion tolerance, one for every pressure or one per pressure (n_p,).
    """
    p_scaled = np.ascontiguousarray(p_scaled, dtype=float)
    n_p = p_scaled.size
    G = np.asarray(G, dtype=float)
    if n_z is None:
        n_z = np.full(n_p, G.shape[-1], dtype=np.int64)
    n_z = np.ascontiguousarray(n_z, dtype=np.int64)
    n_max = int(G.shape[-1])
    G, c = _rows(G, n_p, n_max), _rows(c, n_p, n_max)
    wa, wb = _rows(wa, n_p, n_max - 1), _rows(wb, n_p, n_max - 1)
    rtol = np.ascontiguousarray(np.broadcast_to(np.asarray(rtol, dtype=float), (n_p,)))
    outs = [np.zeros((n_p, n_max)) for _ in range(8 if sy is None else 10)]
    if sy is None:                       # no yield wall: rows of length 0
        step = elastic_step
        yield_args = [np.zeros((n_p, 0)) for _ in range(3)]
    else:
        step = yield_step
        yield_args = [_rows(sy, n_p, n_max), outs[8], outs[9]]
    status = np.zeros(n_p, dtype=np.int64)
    iterations = np.zeros(n_p, dtype=np.int64)
    residual = np.zeros(n_p)
    if x_init is None:
        x_init = np.full((n_p, n_max), -1.0)
    x_init = _rows(x_init, n_p, n_max)
    mode = choose_parallel(parallel, n_p)
    if mode == "prange":                 # compiled per process: the solvers linked in
        kernel, callees = adhesive_sweep_parallel, [fixed_point, LINKED_STEPS[step], None]
    else:
        kernel, callees = adhesive_sweep_serial, [fixed_point, step, _solve_grid_tol]
    timings = {}
    if not is_compiled(kernel):
        t0 = time.perf_counter()
        first = [*callees, variant, G[:1], c[:1], wa[:1], wb[:1], n_z[:1], gamma_s,
                 p_scaled[:1], np.full(1, 1e-2), controls["n_damp"], 2, controls["m_hist"],
                 controls["omega"], x_init[:1], *[o[:1] for o in outs[:8]], status[:1],
                 iterations[:1], residual[:1], bool(onset), int(theory), float(theory_gamma),
                 *[a[:1] for a in yield_args]]
        with _compile_lock:
            if mode == "prange":
                with prange_guard():
                    kernel(*first)
            else:
                _compile_fixed_point(first)
                kernel(*first)
        timings["compile"] = time.perf_counter() - t0
    args = [*callees, variant, G, c, wa, wb, n_z, gamma_s, p_scaled, rtol, controls["n_damp"],
            controls["max_iter"], controls["m_hist"], controls["omega"], x_init, *outs[:8],
            status, iterations, residual, bool(onset), int(theory), float(theory_gamma),
            *yield_args]
    t0 = time.perf_counter()
    run_rows(adhesive_sweep_serial, adhesive_sweep_parallel, args,
             (4, 5, 6, 7, 8, 10, 11, 16, 31), tuple(range(17, 28)) + (32, 33), n_p, parallel)
    timings["solve"] = time.perf_counter() - t0
    return outs, status, iterations, residual, timings


_compile_lock = threading.Lock()
#: the diffusion step the ``prange`` sweep links in, for the one the cached sweep calls
LINKED_STEPS = {elastic_step: elastic_step_linked, yield_step: yield_step_linked}


def _compile_fixed_point(first):
    """Compile (or load) the cached sweep, the fixed point and its diffusion step for the
    arguments ``first`` of a one-row sweep: on a cold cache the grid solver (the larger share)
    in a second process while this one compiles the rest
    (:func:`persson_fast._jit.compile_beside`)."""
    # the first adhesive solve on a machine compiles the sweep, the fixed point, its diffusion
    # step and the grid solver (the grid solver in a second process)
    announce_compile("adhesion", [(fixed_point, FIXED_POINT_SIGNATURE), (first[1], STEP_SIGNATURE),
                                  (_solve_grid_tol, GRID_SIGNATURE)])
    with compiling_beside([(_solve_grid_tol, GRID_SIGNATURE)]):
        compile_for(fixed_point, FIXED_POINT_SIGNATURE)
        compile_for(first[1], STEP_SIGNATURE)
        adhesive_sweep_serial.compile_alone(*first)


#: what :func:`persson_fast.warmup` compiles in a second process on a cold cache while it
#: compiles the contact sweeps (with the grid solver): the adhesive fixed point and its step
ADHESIVE_JOBS = [(fixed_point, FIXED_POINT_SIGNATURE), (elastic_step, STEP_SIGNATURE)]


def warm_adhesion(prange: bool = False) -> None:
    """Compile (or load) the adhesive sweep kernels on a tiny problem (``prange``: also the
    ``prange`` sweep)."""
    G = np.array([0.0, 1.0, 2.0])
    c = np.array([0.1, 0.2, 0.3])
    w = np.array([0.1, 0.1])
    ctl = _controls(None)
    for par in ((False, "prange") if prange else (False,)):
        _run(G, c, w, w, -1.0, np.array([1.0, 2.0]), 1e-2, par, ctl)  # 1 row runs serially


def warm_adhesive_yield(prange: bool = False) -> None:
    """Compile (or load) the adhesive sweep with a yield wall (the two-wall solver inside)."""
    G = np.array([0.0, 1.0, 2.0])
    c = np.array([0.1, 0.2, 0.3])
    w = np.array([0.1, 0.1])
    ctl = _controls(None)
    sy = np.full((2, 3), 10.0)
    for par in ((False, "prange") if prange else (False,)):
        _run(G, c, w, w, -1.0, np.array([1.0, 2.0]), 1e-2, par, ctl, sy=sy)


def _controls(overrides, defaults=None):
    """The fixed point's iteration controls: ``defaults`` (``ADHESION_DEFAULTS``) updated by
    ``overrides`` -- None, or a mapping of control name to value (``adhesion_controls`` of
    solve_contact, ``controls`` of pull_off) -- each value checked."""
    from collections.abc import Mapping

    def whole(name, minimum):
        value = controls[name]
        if (isinstance(value, bool)
                or not isinstance(value, (int, np.integer, float, np.floating))
                or not float(value).is_integer() or value < minimum):
            raise ValueError(f"{name} must be a whole number >= {minimum} [-]; got {name} = "
                             f"{value!r}")
        return int(value)

    controls = dict(ADHESION_DEFAULTS if defaults is None else defaults)
    if overrides is not None:
        if not isinstance(overrides, Mapping):
            raise ValueError(
                f"adhesion controls (adhesion_controls of solve_contact, controls of pull_off) "
                f"must be a dict of control names to values, e.g. {{'max_iter': 500}}; valid "
                f"names: {sorted(controls)}; got {overrides!r} (a {type(overrides).__name__})")
        unknown = set(overrides) - set(controls)
        if unknown:
            raise ValueError(f"unknown adhesion control(s) {sorted(unknown, key=repr)}; valid: "
                             f"{sorted(controls)}")
        controls.update(overrides)
    omega = controls["omega"]
    if (isinstance(omega, bool) or not isinstance(omega, (int, float, np.integer, np.floating))
            or not 0.0 < float(omega) <= 1.0):
        raise ValueError(f"omega must lie in (0, 1] [-]; got omega = {omega!r}")
    return {"max_iter": whole("max_iter", 1), "m_hist": whole("m_hist", 0),
            "omega": float(omega), "n_damp": whole("n_damp", 0)}

