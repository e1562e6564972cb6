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
* the reverse, for a large callee under a large caller: the callee called by address (a
  numba first-class function, made in the kernel from an integer jit address:
  :class:`CallingKernel`, :func:`function_at`; or passed from Python: :func:`callable_with`),
  so the caller is compiled without the callee's code inside it and the two are compiled
  (and cached) apart; on a cold cache the larger part can then compile in a second process at
  the same time (:func:`compile_beside`). The adhesive sweep is built so: sweep, fixed point,
  diffusion step and grid solver are four compile units (measured on 2 cores: the grid
  solver alone 7.2 s, everything above it 5 s, where one unit with the solver inside each
  caller took 15 s);
* ``fastmath`` stays off: the accuracy tests are written for IEEE arithmetic.

Setting the environment variable ``NUMBA_DISABLE_JIT=1`` runs every kernel as plain Python,
which is how line coverage is measured honestly.
"""
from __future__ import annotations

import contextlib
import hashlib
import logging
import os
import subprocess
import sys
import threading
import warnings
from pathlib import Path

import numba
import numpy as np
from numba.core import caching, cgutils, types
from numba.extending import intrinsic

#: the oldest numba the kernels run on: a first-class function is called through its jit
#: address (``FunctionModel.jit_addr``, :func:`function_at`), which numba has from 0.61 on;
#: pyproject.toml declares the same floor and CI runs the tests once on it
NUMBA_MIN = (0, 61)


def _release(version: str) -> tuple[int, ...]:
    parts = []
    for piece in version.split(".")[:2]:
        digits = "".join(ch for ch in piece if ch.isdigit())
        parts.append(int(digits) if digits else 0)
    return tuple(parts)


if _release(numba.__version__) < NUMBA_MIN:
    _floor = ".".join(map(str, NUMBA_MIN))
    raise ImportError(f"persson_fast needs numba >= {_floor} (its kernels call compiled "
                      f"functions through their jit address); found numba {numba.__version__}: "
                      f"pip install --upgrade 'numba>={_floor}'")


__all__ = ["njit_serial", "njit_inline", "njit_parallel", "njit_sweeps", "prange",
           "kernel_source_stamp", "CallingKernel", "function_at", "jit_address",
           "callable_with", "compile_for", "in_disk_cache", "compile_beside",
           "compiling_beside", "announce_compile", "compile_note", "FIRST_CALL_COST",
           "FIRST_CALL_MEASURE", "logger"]

#: the package's logger: it says (INFO) when a first call compiles kernels
logger = logging.getLogger("persson_fast")

prange = numba.prange

#: numba marks first-class functions experimental and says so when it compiles one; the
#: package's own kernels use them on purpose (tested: bitwise equal to the linked code), so
#: the note is silenced for warnings located in the package's files only. numba 0.61 says it a
#: second time while lowering, located in its own numba/core/utils.py rather than in the
#: compiled function's file; that repeat is silenced too (the first note, raised while typing,
#: still reaches a user who compiles a first-class function of their own: it is located in
#: their file)
warnings.filterwarnings("ignore", category=numba.core.errors.NumbaExperimentalFeatureWarning,
                        module=r".*persson_fast[/\\.]")
warnings.filterwarnings("ignore", category=numba.core.errors.NumbaExperimentalFeatureWarning,
                        module=r"numba\.core\.utils$")

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


def _locator(name):
    # numba 0.61 names its cache locators with a leading underscore; later versions without
    return getattr(caching, name, None) or getattr(caching, "_" + name)


class _UserDirLocator(_PackageStamp, _locator("UserProvidedCacheLocator")):
    pass


class _InTreeLocator(_PackageStamp, _locator("InTreeCacheLocator")):
    pass


class _UserWideLocator(_PackageStamp, _locator("UserWideCacheLocator")):
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


def _fingerprint(value):
    """What decides the numba type of an argument, cheaply (no ``numba.typeof``)."""
    if isinstance(value, np.ndarray):
        return (value.dtype.str, value.ndim, value.flags.c_contiguous, value.flags.f_contiguous,
                value.flags.writeable)
    return type(value)


def function_at(signature):
    """An intrinsic that makes the numba first-class function of ``signature`` from the jit
    address of a compiled function (an integer, :func:`jit_address`): the function is then
    called through its own entry point (numba's calling convention, so its
    exceptions propagate). Under ``NUMBA_DISABLE_JIT`` the identity (the callee itself is
    passed)."""
    if numba.config.DISABLE_JIT:
        return lambda callee: callee
    ftype = types.FunctionType(signature)

    @intrinsic
    def at(typingctx, address):
        if not isinstance(address, types.Integer):
            return None

        def codegen(context, builder, sig, args):
            fn = cgutils.create_struct_proxy(ftype)(context, builder)
            fn.jit_addr = builder.inttoptr(args[0], context.get_value_type(types.voidptr))
            return fn._getvalue()

        return ftype(address), codegen

    return at


_addresses = {}


def jit_address(dispatcher, signature) -> int:
    """The address of ``dispatcher`` compiled (or loaded) for the argument types of
    ``signature``, in numba's calling convention (kept per process: a dispatcher keeps its
    compiled code alive)."""
    key = (dispatcher, signature)
    address = _addresses.get(key)
    if address is None:
        from numba.experimental.function_type import _get_jit_address

        compile_for(dispatcher, signature)
        address = _addresses[key] = _get_jit_address(dispatcher, signature)
    return address


class CallingKernel:
    """A cached kernel whose first arguments are other compiled functions, called by address.

    numba links every compiled callee into its caller and optimises and generates the machine
    code of the whole again, so a kernel above the diffusion solver pays for the solver's
    code again on the first call on a machine. Called by address, the callees are compiled
    (and cached) on their own, the caller without them, and on a cold cache in two processes
    at once (:func:`compile_beside`). ``dispatcher`` takes the callees' jit addresses
    (integers; its body makes them first-class functions with :func:`function_at`, one per
    signature of ``callee_signatures``), so a call passes plain integers: numba's own
    first-class function arguments cost about 30 us each to unbox from a dispatcher, paid
    under the GIL on every call. Called as ``kernel(*callees, *args)`` with dispatchers;
    each new combination of argument types is compiled (or loaded from the disk cache) once,
    for the exact types given, and each callee for its signature. The same body may also be
    compiled as an ordinary function for compiled callers, with the callees linked in: numba
    generates the same arithmetic either way (no fast-math, no reassociation).
    """

    def __init__(self, dispatcher, callee_signatures):
        self.dispatcher = dispatcher
        self.callee_signatures = tuple(callee_signatures)
        self._n = len(self.callee_signatures)
        self._entries = {}
        self._lock = threading.Lock()

    @property
    def overloads(self):
        return getattr(self.dispatcher, "overloads", {})

    @property
    def stats(self):
        return self.dispatcher.stats

    def _entry(self, args):
        key = tuple(_fingerprint(a) for a in args)
        entry = self._entries.get(key)
        if entry is None:
            with self._lock:
                signature = (types.int64,) * self._n + tuple(numba.typeof(a) for a in args)
                entry = self._entries[key] = self.dispatcher.compile(signature)
        return entry

    def compile_alone(self, *args):
        """Compile (or load) the kernel for these arguments' types (callees first, as in a
        call), but not its callees."""
        if hasattr(self.dispatcher, "compile"):
            self._entry(args[self._n:])

    def __call__(self, *args):
        callees, rest = args[:self._n], args[self._n:]
        if not hasattr(self.dispatcher, "compile"):      # NUMBA_DISABLE_JIT=1
            return self.dispatcher(*callees, *rest)
        addresses = [jit_address(c, s) for c, s in zip(callees, self.callee_signatures)]
        return self._entry(rest)(*addresses, *rest)


def callable_with(dispatcher, signature, callees=()):
    """``dispatcher`` compiled (or loaded) for ``signature``, whose leading arguments are
    first-class functions: the entry point, to be called from Python with the dispatchers
    ``callees`` (pairs (dispatcher, signature), compiled first) in their places. Under
    ``NUMBA_DISABLE_JIT`` the plain function."""
    if not hasattr(dispatcher, "compile"):
        return dispatcher
    for callee, sig in callees:
        compile_for(callee, sig)
    return compile_for(dispatcher, signature)


def compile_for(dispatcher, signature):
    """``dispatcher.compile`` for the argument types of ``signature`` (its return type is
    inferred): the disk-cache key is then the one numba uses when a compiled caller compiles
    the same function (the argument types alone), so one cache entry serves both."""
    if not hasattr(dispatcher, "compile"):              # NUMBA_DISABLE_JIT=1
        return dispatcher
    return dispatcher.compile(tuple(signature.args))


def njit_sweeps(func):
    """(serial, parallel) dispatchers of one sweep body written with ``prange``.

    Compiled without ``parallel=True``, ``prange`` is a plain ``range``: one body serves both
    drivers, so their results are the same code's (bitwise equal, each iteration writing only
    its own rows).
    """
    return njit_serial(func), njit_parallel(func)


def in_disk_cache(dispatcher, signature) -> bool:
    """True when numba's disk cache holds ``dispatcher`` compiled for the argument types of
    ``signature`` (:func:`compile_for`; or a tuple of argument types) with the current kernel
    sources; nothing is loaded.
    When the cache cannot be read this way (another numba version), True: the caller then
    compiles in this process, as it would anyway."""
    try:
        cache = dispatcher._cache
        args = signature.args if hasattr(signature, "args") else signature
        key = cache._index_key(tuple(args), dispatcher.targetctx.codegen())
        return key in cache._cache_file._load_index()
    except Exception:
        return True


_announced = set()

#: what a first call on a machine costs, in the words of the compile note, README.md and the
#: install page (a test keeps the three in agreement): from an empty cache on a shared 2-core
#: machine the main job took 39-48 s of CPU and a first adhesive solve_contact 40-42 s
#: (docs/user-guide/performance.md); the figure changes with the machine, its load and the
#: numba version, so the note names the command that measures it where the user is
FIRST_CALL_COST = "tens of seconds of CPU"
#: the command that compiles everything and says how long it took on this machine
FIRST_CALL_MEASURE = "persson-fast info"


def announce_compile(what: str, jobs) -> bool:
    """Log once per process, at INFO on the ``persson_fast`` logger, that ``what`` compiles
    its kernels now (``jobs``: (dispatcher, signature or argument types) pairs, one missing
    from the disk cache suffices): "compiling kernels for <what>, once per machine:
    <FIRST_CALL_COST> (`<FIRST_CALL_MEASURE>` measures it on this machine); ...". True when
    it logged. The command line prints these messages; an API user sees them with
    ``logging.basicConfig(level=logging.INFO)``."""
    if what in _announced or numba.config.DISABLE_JIT:
        return False
    if all(in_disk_cache(d, s) for d, s in jobs):
        _announced.add(what)
        return False
    _announced.add(what)
    logger.info(compile_note(what))
    return True


def compile_note(what: str) -> str:
    """The text :func:`announce_compile` logs for ``what``."""
    return (f"compiling kernels for {what}, once per machine: {FIRST_CALL_COST} "
            f"(`{FIRST_CALL_MEASURE}` measures it on this machine); later calls and processes "
            f"load them from the disk cache")


def _usable_cpus() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        return os.cpu_count() or 1


#: what the second process runs: the package's folder on its path (where this process found
#: the package, unless the path has it already), then module.name compiled for the argument
#: types of module.signature_name, for each job
_WORKER = ("import importlib, sys\n"
           "root = sys.argv[1]\n"
           "if root not in sys.path:\n"
           "    sys.path.insert(0, root)\n"
           "for job in sys.argv[2:]:\n"
           "    module, name, sig = job.split(':')\n"
           "    m = importlib.import_module(module)\n"
           "    getattr(m, name).compile(tuple(getattr(m, sig).args))\n")


class _Beside:
    """A second Python process compiling kernels into the shared disk cache."""

    def __init__(self, jobs):
        self.proc = subprocess.Popen([sys.executable, "-c", _WORKER, str(_PACKAGE.parent), *jobs],
                                     stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                     stderr=subprocess.DEVNULL)

    def wait(self, timeout: float = 900.0) -> bool:
        """Wait for the second process; True when it finished without error. A failed or
        timed-out one costs nothing but time: the caller compiles what is missing itself."""
        try:
            return self.proc.wait(timeout) == 0
        except subprocess.TimeoutExpired:
            return False
        finally:
            self.stop()

    def stop(self) -> None:
        """End the second process now if it still runs (an interrupted caller)."""
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()


#: set to "0" to compile everything in the calling process (:func:`compile_beside`)
SECOND_PROCESS_ENV = "PERSSON_FAST_COMPILE_BESIDE"


def _needs_compile(dispatcher, signature) -> bool:
    """Neither compiled in this process nor in the disk cache for ``signature``."""
    return (tuple(signature.args) not in getattr(dispatcher, "overloads", {})
            and not in_disk_cache(dispatcher, signature))


def compile_beside(jobs):
    """Start compiling kernels in a second process while this one goes on, or None.

    ``jobs``: (dispatcher, signature) pairs, both module-level names of one module
    (``"module:name:signature_name"`` strings are built from them). Only those not compiled
    here and not in the disk cache are sent; None when none is left, with fewer than two
    usable CPUs, under ``NUMBA_DISABLE_JIT``, without a Python interpreter to start (a
    bundled application), or with the environment variable ``PERSSON_FAST_COMPILE_BESIDE=0``
    (for many processes starting on one cold cache at once, e.g. a cluster's workers: each
    would start its own). numba compiles one function at a time per process (a global lock),
    so on a cold cache the first call on a machine with two cores takes about the larger of
    the two shares instead of their sum; the results come back through the disk cache (numba
    writes its files atomically), where this process loads them (``dispatcher.compile``)
    after :meth:`_Beside.wait`.
    """
    if (_usable_cpus() < 2 or numba.config.DISABLE_JIT or not sys.executable
            or getattr(sys, "frozen", False)     # a bundled application: no interpreter to run
            or os.environ.get(SECOND_PROCESS_ENV, "1") == "0"):
        return None
    names = []
    for dispatcher, signature in jobs:
        if not _needs_compile(dispatcher, signature):
            continue
        module = sys.modules[dispatcher.py_func.__module__]
        name = next((k for k, v in vars(module).items() if v is dispatcher), None)
        sig_name = next((k for k, v in vars(module).items() if v is signature), None)
        if name is None or sig_name is None:
            raise ValueError(f"compile_beside: {dispatcher.py_func.__name__} and its signature "
                             f"must be module-level names of {module.__name__}")
        names.append(f"{module.__name__}:{name}:{sig_name}")
    if not names:
        return None
    try:
        return _Beside(names)
    except OSError:
        return None


@contextlib.contextmanager
def compiling_beside(jobs):
    """``with compiling_beside(jobs):`` -- :func:`compile_beside` while the body compiles other
    kernels, then wait for the second process (stop it at once if the body raises, e.g. on
    Ctrl-C); afterwards the jobs' kernels load from the disk cache."""
    beside = compile_beside(jobs)
    try:
        yield beside
    except BaseException:
        if beside is not None:
            beside.stop()
        raise
    if beside is not None:
        beside.wait()
