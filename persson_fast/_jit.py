"""The only place that sets numba options.

* serial kernels: ``cache=True`` (compiled once per machine, reused by later processes); the
  default parallel driver (:func:`persson_fast.sweep.run_rows`) runs them on a pool of Python
  threads (they release the GIL), so it needs nothing else compiled;
* ``prange`` sweeps (``parallel="prange"`` only): ``parallel=True`` **without** ``cache`` --
  caching parallel functions from several processes at once is known to crash (numba issue
  4807);
* thin wrappers: ``inline="always"`` (:func:`njit_inline`), which spares compiled callers a
  call boundary (numba finalises every function with its callees linked in and optimised
  again, so each boundary re-optimises everything below it);
* ``fastmath`` stays off: the accuracy tests are written for IEEE arithmetic.

Setting the environment variable ``NUMBA_DISABLE_JIT=1`` runs every kernel as plain Python,
which is how line coverage is measured honestly.
"""
from __future__ import annotations

import numba

__all__ = ["njit_serial", "njit_inline", "njit_parallel", "njit_sweeps", "prange"]

prange = numba.prange


def njit_serial(func):
    """Compile ``func`` in nopython mode, cached on disk, no fastmath."""
    return numba.njit(cache=True, fastmath=False, nogil=True, error_model="numpy")(func)


def njit_inline(func):
    """Like :func:`njit_serial`, but inlined into compiled callers at numba IR level.

    For thin wrappers only: a call boundary between compiled functions costs a whole extra
    optimisation of everything below it at compile time (each numba function is finalised
    with its callees linked in), and nothing at run time once inlined.
    """
    return numba.njit(cache=True, fastmath=False, nogil=True, error_model="numpy",
                      inline="always")(func)


def njit_parallel(func):
    """Compile ``func`` in nopython mode with ``prange`` parallelism (not cached)."""
    return numba.njit(parallel=True, cache=False, fastmath=False, nogil=True, error_model="numpy")(func)


def njit_sweeps(func):
    """(serial, parallel) dispatchers of one sweep body written with ``prange``.

    Compiled without ``parallel=True``, ``prange`` is a plain ``range``: one body serves both
    drivers, so their results are the same code's (bitwise equal, each iteration writing only
    its own rows).
    """
    return njit_serial(func), njit_parallel(func)
