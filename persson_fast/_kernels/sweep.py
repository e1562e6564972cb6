"""Sweeps over pressures: one compiled one-pressure solve, two drivers (serial, ``prange``).

Each iteration writes only its own output row, so the serial and the parallel sweep give
bitwise-equal results. ``variant`` selects the grid variant of
:func:`persson_fast._kernels.similarity.solve_variant`; ``level`` >= 0 an explicit resolution
(else ``rtol`` sets it); ``counts`` (n_p, 3) receives nodes, steps and node-steps.
"""
from __future__ import annotations

from .._jit import njit_sweeps, prange
from .similarity import solve_variant


def _sweep(variant, G, sa_rows, pressures, rtol, level, n_damp, area, load, det_area, det_load,
           error, status, counts):
    """Solve every pressure. ``sa_rows``: (n_p, n_t); outputs (n_p, n_t); status (n_p,)."""
    for k in prange(pressures.shape[0]):
        status[k] = solve_variant(variant, G, sa_rows[k], pressures[k], rtol, level, n_damp,
                                  area[k], load[k], det_area[k], det_load[k], error[k],
                                  counts[k])


sweep_serial, sweep_parallel = njit_sweeps(_sweep)
