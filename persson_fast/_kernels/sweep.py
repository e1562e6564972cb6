"""Sweeps over pressures: one compiled one-pressure solve, two drivers (serial, ``prange``).

The signature is the one of every grid method (:mod:`persson_fast._kernels.signature`), led
by ``variant``, which selects the grid variant of
:func:`persson_fast._kernels.similarity.solve_variant`. The front-fixed grid has one wall (the
lower one): a row with a finite upper wall is answered BAD_INPUT. Each iteration writes only
its own output row, so the serial and the parallel sweep give bitwise-equal results.
"""
from __future__ import annotations

from .._jit import njit_sweeps, prange
from .signature import no_upper_wall
from .similarity import solve_variant
from .status import BAD_INPUT


def _sweep(variant, G, sa_rows, sy_rows, pressures, rtol, level, n_damp, area, load, det_area,
           det_load, error, pl_area, pl_load, status, counts):
    """Solve every pressure with grid variant ``variant``.

    Arguments as in :mod:`persson_fast._kernels.signature`: ``sy_rows`` must be absent (rows
    of length 0, or +inf at every G), ``pl_area``/``pl_load`` rows of length 0 (not
    requested) or n_t (set to zero); ``level`` >= 0 an explicit resolution (else ``rtol``
    sets it); ``counts`` (n_p, 3) receives nodes, steps and node-steps.
    """
    n_p = pressures.shape[0]
    n_t = G.shape[0]
    for k in prange(n_p):
        if no_upper_wall(sy_rows, pl_area, pl_load, k, n_p, n_t):
            status[k] = solve_variant(variant, G, sa_rows[k], pressures[k], rtol, level,
                                      n_damp, area[k], load[k], det_area[k], det_load[k],
                                      error[k], counts[k])
        else:
            status[k] = BAD_INPUT


sweep_serial, sweep_parallel = njit_sweeps(_sweep)
