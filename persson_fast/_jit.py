"""The only place that sets numba options.

* serial kernels: ``cache=True`` (compiled once per machine, reused by later processes);
* parallel sweeps: ``parallel=True`` **without** ``cache`` -- caching parallel functions from
  several processes at once is known to crash (numba issue 4807);
* ``fastmath`` stays off: the accuracy tests are written for IEEE arithmetic.

Setting the environment variable ``NUMBA_DISABLE_JIT=1`` runs every kernel as plain Python,
which is how line coverage is measured honestly.
"""
from __future__ import annotations

import numba

__all__ = ["njit_serial", "njit_parallel", "prange"]

prange = numba.prange


def njit_serial(func):
    """Compile ``func`` in nopython mode, cached on disk, no fastmath."""
    return numba.njit(cache=True, fastmath=False, nogil=True, error_model="numpy")(func)


def njit_parallel(func):
    """Compile ``func`` in nopython mode with ``prange`` parallelism (not cached)."""
    return numba.njit(parallel=True, cache=False, fastmath=False, nogil=True, error_model="numpy")(func)
