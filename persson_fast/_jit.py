"""The only place that sets numba options.

* serial kernels: cached on disk (compiled once per machine, reused by later processes), each
  entry stamped with a hash of every kernel source file (:func:`kernel_source_stamp`: numba
  itself checks only the cached function's own file, not the files of what it calls); the
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

import hashlib
from pathlib import Path

import numba
from numba.core import caching

__all__ = ["njit_serial", "njit_inline", "njit_parallel", "njit_sweeps", "prange",
           "kernel_source_stamp"]

prange = numba.prange

_PACKAGE = Path(__file__).resolve().parent
#: every file that holds compiled code: a cached kernel is stale when any of them changes
_KERNEL_FILES = ("_jit.py", "embed.py", "_kernels")


def _kernel_paths():
    out = []
    for name in _KERNEL_FILES:
        path = _PACKAGE / name
        out.extend(sorted(path.glob("*.py")) if path.is_dir() else [path])
    return out


def _current_stamp() -> str:
    h = hashlib.sha256()
    for path in _kernel_paths():
        h.update(str(path).encode())
        h.update(path.read_bytes())
    return h.hexdigest()


def kernel_source_stamp() -> str:
    """A hash of the source of every file with compiled code in the package, as this process
    found it when it imported the package.

    numba's disk cache checks only the source file of the cached function itself, so a
    cached sweep kernel would keep running an old version of the solver it calls from another
    file (after an upgrade or an edit). The package's cache entries carry this stamp instead,
    so a change to any kernel file invalidates them all. The stamp is taken once, when this
    module is imported: a module imported later (``persson_fast.embed`` is imported on
    demand) compiles against the kernels already in memory, and labelling that code with the
    hash of files changed on disk since (an upgrade under a running session) would make a
    later process load the old code as current.
    """
    return _IMPORT_STAMP


_IMPORT_STAMP = _current_stamp()


class _PackageStamp:
    def get_source_stamp(self):
        return (super().get_source_stamp(), kernel_source_stamp())


class _UserDirLocator(_PackageStamp, caching.UserProvidedCacheLocator):
    pass


class _InTreeLocator(_PackageStamp, caching.InTreeCacheLocator):
    pass


class _UserWideLocator(_PackageStamp, caching.UserWideCacheLocator):
    pass


class _CacheImpl(caching.CompileResultCacheImpl):
    _locator_classes = [_UserDirLocator, _InTreeLocator, _UserWideLocator]


class _FunctionCache(caching.FunctionCache):
    _impl_class = _CacheImpl


def _cached(dispatcher):
    """Give a dispatcher the package's disk cache (stamped by :func:`kernel_source_stamp`)."""
    if hasattr(dispatcher, "enable_caching"):       # not under NUMBA_DISABLE_JIT=1
        dispatcher._cache = _FunctionCache(dispatcher.py_func)
    return dispatcher


def njit_serial(func):
    """Compile ``func`` in nopython mode, cached on disk, no fastmath."""
    return _cached(numba.njit(fastmath=False, nogil=True, error_model="numpy")(func))


def njit_inline(func):
    """Like :func:`njit_serial`, but inlined into compiled callers at numba IR level.

    For thin wrappers only: a call boundary between compiled functions costs a whole extra
    optimisation of everything below it at compile time (each numba function is finalised
    with its callees linked in), and nothing at run time once inlined.
    """
    return _cached(numba.njit(fastmath=False, nogil=True, error_model="numpy",
                              inline="always")(func))


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
