"""Sweeps over pressures: one compiled one-pressure solve, two drivers (serial, ``prange``).

Each iteration writes only its own output row, so the serial and the parallel sweep give
bitwise-equal results.
"""
from __future__ import annotations

from .._jit import njit_parallel, njit_serial, prange
from .diffusion import solve_one


@njit_serial
def sweep_serial(G, sa_rows, pressures, rtol, n_damp, area, load, det_area, det_load, error,
                 status):
    """Solve every pressure in turn. ``sa_rows``: (n_p, n_t); outputs (n_p, n_t); status (n_p,)."""
    for k in range(pressures.shape[0]):
        status[k] = solve_one(G, sa_rows[k], pressures[k], rtol, n_damp, area[k], load[k],
                              det_area[k], det_load[k], error[k])


@njit_parallel
def sweep_parallel(G, sa_rows, pressures, rtol, n_damp, area, load, det_area, det_load, error,
                   status):
    """Same as :func:`sweep_serial`, pressures spread over threads with ``prange``."""
    for k in prange(pressures.shape[0]):
        status[k] = solve_one(G, sa_rows[k], pressures[k], rtol, n_damp, area[k], load[k],
                              det_area[k], det_load[k], error[k])
