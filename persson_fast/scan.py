"""Parameter scans: many scenes, each swept over the same nominal pressures.

:func:`scan` crosses a grid of scene parameters -- any keyword argument of a surface model
(``hurst``, ``h_rms``, ``slope_rms``, ``q0``, ``q1``, ``temperature``, ...) and the solve
parameters ``e_star``, ``work_of_adhesion``, ``energy_correction``,
``detachment_prefactor`` and (given a sequence) the area ``theory`` -- with a vector of
nominal pressures. Every scene is one call of :func:`persson_fast.solve_contact` over all
pressures (and, on request, one call of :func:`persson_fast.pull_off`), so a scan returns
exactly the numbers those calls return.

Why xarray
----------
A scan is a labelled N-dimensional grid: one axis per scanned parameter plus ``pressure``
(and ``zeta`` for profiles), with per-scene variables (``success``, ``message``,
``pull_off``) living on a sub-grid of the same axes. :class:`xarray.Dataset` holds exactly
that: ``ds.area.sel(hurst=0.8, work_of_adhesion=0.06)`` selects by value,
``ds.area.plot(x="pressure", hue="hurst")`` plots with labelled axes, the units travel in
``attrs``, ``ds.to_netcdf`` stores the scan, and a tidy table (one row per scene and
pressure) is one ``ds.to_dataframe()`` away. A flat DataFrame as the primary result would
lose the grid structure (and repeat every per-scene value on every pressure row).

Failures
--------
A scan of 10^4 scenes should not be lost to one scene, nor hide it: a scene whose
``solve_contact`` or ``pull_off`` raises is recorded (NaN, ``success`` False, the error in
``message``, ``status`` :data:`SCENE_ERROR` for a raised solve) and the other scenes run on;
flagged points (``status`` != 0) and unconverged pull-offs keep their numbers with ``success``
False. A failed scene's ``message`` starts with what failed. When any scene failed, the scan
issues one :class:`ScanWarning` naming how many and the worst few (parameters and messages).

Execution
---------
*Local* (``client=None``). The compiled kernels release the GIL, so scenes run on a pool of
threads, each scene with the serial (disk-cached) kernels; scenes whose answer is a closed
form (no adhesion, ``method`` "auto" or "analytic") cost microseconds of Python and run in
the calling thread. ``python -m benchmarks.scan_scale`` compares this with running the
scenes one after another, each pressure sweep spread over threads (``prange``). On a
2-core machine shared with other jobs (load average 3-4), threads over scenes were as fast
or faster in every case and run (minimum of 5 interleaved runs: 1.39 s against 1.59 s for
20 scenes x 100 pressures with "cn", 1.24 s against 1.36 s for 10 adhesive scenes x 20
pressures, 0.56 s against 0.69 s for 3 adhesive scenes x 60 pressures), and they never pay
the 12-28 s per process that compiling the parallel kernels costs (those are not cached on
disk). A single scene, or ``workers=1``, runs in the calling thread with
:func:`~persson_fast.solve_contact`'s own choice of pressure parallelism; with only a few
expensive scenes and the parallel kernels already compiled (``pf.warmup()``), that can
balance better.

*Distributed* (``client`` a :class:`dask.distributed.Client`, a scheduler address, or
``"local"``). Contiguous chunks of the scene grid become tasks of the module-level function
:func:`solve_chunk`; the results are gathered and placed by scene index, so the dataset
equals the local one bitwise. Workers load the serial kernels from numba's on-disk cache
(``client.run(persson_fast.warmup, False)`` once per scan). A ``KeyboardInterrupt`` (or any
error) while waiting cancels every pending task of the scan; a cluster that :func:`scan`
created itself (``client="local"``) is closed in every case, and a client passed in stays
open.
"""
from __future__ import annotations

import inspect
import itertools
import math
import sys
import time
import uuid
import warnings
from concurrent.futures import ThreadPoolExecutor, wait, FIRST_COMPLETED

import numpy as np

from ._validation import (as_float_array, check_finite, check_nonnegative, check_positive,
                          optional_import)
from .adhesion import adhesion_zeta
from .pulloff import pull_off as _pull_off
from .api import solve_contact
from .scene import DETACHMENT_PREFACTOR, Scene, _check_rtol, default_zeta, unpack_scene
from .theories import THEORIES, check_theory, check_theory_scene
from .methods import METHODS
from .plasticity import check_hardness
from .surfaces import SURFACE_MODELS, Surface

__all__ = ["scan", "solve_chunk", "ScanWarning", "SCENE_ERROR", "SOLVE_PARAMETERS",
           "PARAMETER_UNITS"]

#: parameters that go to :func:`solve_contact` / :func:`pull_off` rather than to the surface
SOLVE_PARAMETERS = ("e_star", "work_of_adhesion", "energy_correction", "detachment_prefactor",
                    "hardness")
#: solve parameters where None (NaN in a coordinate) means "none"
_NONE_ALLOWED = ("energy_correction", "hardness")

_SOLVE_DEFAULTS = {
    "e_star": None,
    "work_of_adhesion": 0.0,
    "energy_correction": None,
    "detachment_prefactor": DETACHMENT_PREFACTOR,
    "hardness": None,
}

#: units of the solve parameters
_SOLVE_UNITS = {
    "e_star": "Pa",
    "work_of_adhesion": "J/m^2",
    "energy_correction": "-",
    "detachment_prefactor": "-",
    "hardness": "Pa",
}


def _declared_units(parameters) -> dict:
    """name -> unit of declared surface parameters (those with a unit)."""
    return {k: p.unit for k, p in parameters.items() if p.unit is not None}


#: units of the parameters of the package's surface models (from their declarations,
#: ``persson_fast.surfaces.SURFACE_MODELS``) and of the solve, for ``attrs``; a scan of any
#: declared model takes its units from its own declaration
PARAMETER_UNITS = {**{k: u for m in SURFACE_MODELS.values()
                      for k, u in _declared_units(m.parameters).items()}, **_SOLVE_UNITS}


def _parameter_units(factory) -> dict:
    """Units of the parameters a scan of ``factory`` may have: its declaration where it has
    one (a Surface subclass's ``PARAMETERS``, a registered model's build, also inside a
    functools.partial), over :data:`PARAMETER_UNITS`; the solve parameters' own always."""
    inner = getattr(factory, "func", factory)
    declared = next((m.parameters for m in SURFACE_MODELS.values() if m.build is inner), None)
    if declared is None and isinstance(inner, type) and issubclass(inner, Surface):
        declared = inner.PARAMETERS
    return {**PARAMETER_UNITS, **_declared_units(declared or {}), **_SOLVE_UNITS}


#: keys that cannot be scan parameters (they name the result's own axes)
_RESERVED = ("pressure", "zeta")

#: ``progress=None`` shows a bar when a scan has more scenes than this ...
PROGRESS_MIN_SCENES = 50
#: ... or is estimated to take longer than this [s] (and stderr is a terminal)
PROGRESS_MIN_SECONDS = 2.0

# rough costs per pressure on one core, only used to decide whether to show a progress bar:
# closed form, the "cn" kernel without adhesion, the adhesive fixed point at rtol = 1e-4
_COST_CLOSED_FORM = 2e-6
_COST_CN = 6e-4
_COST_ADHESION = 5e-3
_COST_SCENE = 2e-4
_PULL_OFF_SOLVES = 40

#: ``status`` of every pressure of a scene whose solve raised an exception (its numbers are
#: NaN and ``message`` names the error); kernel status codes are >= 0
SCENE_ERROR = -1
#: scenes the warning of a scan with failures names (the worst first)
WARN_SCENES = 3
#: characters of each scene's message quoted in that warning
WARN_MESSAGE_CHARS = 300


class ScanWarning(UserWarning):
    """Some scenes of a :func:`scan` failed: issued once per scan, with the number of failed
    scenes and flagged points and the worst scenes' parameters and messages.

    ``warnings.simplefilter("error", ScanWarning)`` turns it into an error (raised after every
    scene has run); ``ds.success``, ``ds.message`` and ``ds.status`` say which scene and point.
    """


# ----------------------------------------------------------------------------------------------
# the work: one scene, one chunk of scenes (module level, so that dask can ship it)
# ----------------------------------------------------------------------------------------------
def _failure(what, exc) -> str:
    """'<what> raised <Type>: <text>' for an exception of solve_contact or pull_off."""
    text = str(exc)
    if text.startswith(f"{what}: "):
        text = text[len(what) + 2:]
    return f"{what} raised {type(exc).__name__}" + (f": {text}" if text else "")


def _solve_scene(surface, solve_kw, pressure, options):
    """Solve one scene at every pressure; a dict of plain arrays and strings.

    A failure of the scene does not raise: an exception of :func:`solve_contact` leaves its
    numbers NaN with status :data:`SCENE_ERROR`, one of :func:`pull_off` leaves ``pull_off``
    NaN, and a pull-off whose error estimate exceeds its tolerance keeps its value; each sets
    ``success`` False and puts what failed first in ``message`` (never "ok ..."), so that one
    scene cannot stop a scan of thousands and no failure passes as a number.
    """
    n_p = pressure.size
    dg = solve_kw["work_of_adhesion"]
    adhesive = dg > 0.0
    zeta = options["zeta_adhesive"] if adhesive else options["zeta_plain"]
    # without adhesion a tensile nominal stress separates the surfaces: A = 0, no solve
    rows = np.arange(n_p) if adhesive else np.flatnonzero(pressure >= 0.0)
    out = {
        "area": np.zeros(n_p),
        "mean_contact_pressure": np.full(n_p, np.nan),
        "error_estimate": np.zeros(n_p),
        "status": np.zeros(n_p, dtype=np.int64),
        "success": True,
        "message": "ok",
        "method": "none",
    }
    failures = []          # what failed, first in the message
    solve_message = "ok"   # solve_contact's own message when it succeeded
    n_z = 0 if options["profile_zeta"] is None else options["profile_zeta"].size
    if options["profiles"]:
        for name in ("area_zeta", "sigma_a", "gamma_eff"):
            out[name] = np.zeros((n_p, n_z))
    if options.get("yield_wall"):
        out["elastic_area"] = np.zeros(n_p)
        out["plastic_area"] = np.zeros(n_p)
    if options.get("separation"):
        out["separation"] = np.full(n_p, np.inf)
        out["stiffness"] = np.zeros(n_p)
        out["elastic_energy"] = np.zeros(n_p)
    if rows.size:
        try:
            r = solve_contact(surface, pressure[rows], method=options["method"],
                              rtol=options["rtol"], zeta=zeta, parallel=options["parallel"],
                              **solve_kw)
        except Exception as exc:  # noqa: BLE001 -- recorded: the scan goes on
            for name in ("area", "mean_contact_pressure", "error_estimate", "area_zeta",
                         "sigma_a", "gamma_eff", "separation", "stiffness", "elastic_energy",
                         "elastic_area", "plastic_area"):
                if name in out:
                    out[name][:] = np.nan
            out["status"][:] = SCENE_ERROR
            failures.append(_failure("solve_contact", exc))
        else:
            out["area"][rows] = r.area
            mcp = getattr(r, "mean_contact_pressure", None)
            if mcp is None:
                mcp = np.where(r.area > 0, r.load / np.where(r.area > 0, r.area, 1.0), np.nan)
            out["mean_contact_pressure"][rows] = mcp
            out["error_estimate"][rows] = r.error_estimate
            out["status"][rows] = r.status
            out["method"] = str(r.method)
            if options.get("yield_wall"):
                plastic = r.plastic_area if r.plastic_area is not None else 0.0
                out["plastic_area"][rows] = plastic
                out["elastic_area"][rows] = r.area - plastic
            if options.get("separation"):
                out["separation"][rows] = r.separation
                out["stiffness"][rows] = r.stiffness
                out["elastic_energy"][rows] = r.elastic_energy
            if r.success:
                solve_message = str(r.message)
            else:
                failures.append(str(r.message))
            if options["profiles"]:
                if not np.array_equal(r.zeta, options["profile_zeta"]):
                    raise RuntimeError("scan: a scene returned profiles on another zeta grid "
                                       "than the scan's; pass zeta= explicitly")
                out["area_zeta"][rows] = r.area_zeta
                out["sigma_a"][rows] = r.sigma_a
                out["gamma_eff"][rows] = r.gamma_eff
    if options["pull_off"]:
        try:
            # pull_off warns when its estimate misses rtol; info["converged"] says the same
            # and is recorded below (the outer catch_warnings of scan undoes any interleaving
            # of these filter changes between threads)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                if solve_kw.get("hardness") is not None:
                    raise ValueError("pull_off with a yield wall (hardness) is not available")
                adhesive_kw = {k: v for k, v in solve_kw.items() if k in SOLVE_PARAMETERS
                               and k != "hardness"}
                sigma_c, info = _pull_off(surface, rtol=options["pull_off_rtol"],
                                          full_output=True, bracket=False, **adhesive_kw)
        except Exception as exc:  # noqa: BLE001 -- recorded: the scan goes on
            out["pull_off"] = out["pull_off_error"] = math.nan
            failures.append(_failure("pull_off", exc))
        else:
            out["pull_off"] = float(sigma_c)
            out["pull_off_error"] = float(info["error_estimate"])
            if not info["converged"]:
                failures.append(
                    f"pull_off did not converge: estimated error {info['error_estimate']:.3g} Pa "
                    f"of pull_off = {sigma_c:.6g} Pa exceeds pull_off_rtol * pull_off")
    if failures:
        out["success"] = False
        if solve_message != "ok":
            failures.append(f"solve_contact: {solve_message}")
        message = "; ".join(failures)
        out["message"] = f"failed: {message}" if message.lower().startswith("ok") else message
    else:
        out["message"] = solve_message
    return out


def solve_chunk(scenes, pressure, options):
    """Solve a chunk of scenes one after another (the task of the distributed path).

    Parameters
    ----------
    scenes : list of (int, Surface, dict)
        Flat scene index, surface, and the keyword arguments of :func:`solve_contact`
        (``e_star``, ``work_of_adhesion``, ``energy_correction``, ``detachment_prefactor``,
        ``hardness``; ``theory`` and ``theory_gamma`` for a corrected theory).
    pressure : numpy.ndarray, shape (n_p,)
        Nominal pressures. [Pa]
    options : dict
        Solve options built by :func:`scan`.

    Returns
    -------
    list of (int, dict)
        The scene index and its results, in the order of ``scenes``.
    """
    return [(index, _solve_scene(surface, kw, pressure, options))
            for index, surface, kw in scenes]


# ----------------------------------------------------------------------------------------------
# argument checks
# ----------------------------------------------------------------------------------------------
def _factory_name(factory) -> str:
    if isinstance(factory, Surface):
        return type(factory).__name__
    inner = getattr(factory, "func", factory)          # functools.partial
    return getattr(inner, "__qualname__", type(inner).__name__)


def _factory_parameters(factory):
    """Names the factory accepts as keywords; None when it takes ``**kwargs``."""
    try:
        sig = inspect.signature(factory)
    except (TypeError, ValueError):
        return None
    names = []
    for p in sig.parameters.values():
        if p.kind is inspect.Parameter.VAR_KEYWORD:
            return None
        if p.kind in (inspect.Parameter.POSITIONAL_OR_KEYWORD, inspect.Parameter.KEYWORD_ONLY):
            names.append(p.name)
    return tuple(names)


def _check_values(name, values, unit="-"):
    """One entry of ``params``: (is_dimension, coordinate array, values to pass on); ``unit``
    is the parameter's, for the messages."""
    label = f"params[{name!r}]"
    if isinstance(values, (str, bytes)) or np.ndim(values) == 0:
        if name in _NONE_ALLOWED and values is None:
            return False, np.array(np.nan), [None]
        arr = np.asarray(values)
        if arr.dtype.kind in "iuf":
            check_finite(arr.astype(float), label, unit)
        return False, arr, [values.item() if isinstance(values, np.generic) else values]
    try:
        raw = list(values)
    except TypeError as exc:
        raise ValueError(f"{label} must be a scalar or a 1-D sequence of values; "
                         f"got {values!r}") from exc
    if name in _NONE_ALLOWED:
        raw = [math.nan if v is None else v for v in raw]
    arr = np.asarray(raw)
    if arr.ndim != 1:
        raise ValueError(f"{label} must be a scalar or a 1-D sequence of values; "
                         f"got shape {arr.shape}")
    if arr.size == 0:
        raise ValueError(f"{label} must hold at least one value; got an empty sequence")
    if arr.dtype.kind in "iuf":
        values_out = arr.tolist()
        finite = np.isfinite(arr.astype(float))
        if name in _NONE_ALLOWED:
            values_out = [None if math.isnan(v) else v for v in values_out]
        elif not np.all(finite):
            i = int(np.argmin(finite))
            raise ValueError(f"{label} must be finite [{unit}]; "
                             f"got {label}[{i}] = {arr[i].item()!r}")
    else:
        arr = np.empty(len(raw), dtype=object)
        arr[:] = raw
        values_out = raw
    seen = {}
    for i, v in enumerate(arr.tolist()):
        key = "nan" if isinstance(v, float) and math.isnan(v) else v
        try:
            if key in seen:
                raise ValueError(f"{label} must hold distinct values (they label an axis); got "
                                 f"{label}[{seen[key]}] = {label}[{i}] = {v!r}")
            seen[key] = i
        except TypeError:
            break                                          # unhashable values: no check
    return True, arr, values_out


def _check_solve_value(name, value, label, axis=False):
    """Validate one value of a solve parameter; return it as a float (or None); a fixed
    hardness may also be scale-dependent (a callable of zeta or a table)."""
    if name == "hardness":
        if value is None or (isinstance(value, float) and math.isnan(value)):
            return None
        return check_hardness(value, label, scale_dependent=not axis)
    if name == "energy_correction":
        if value is None:
            return None
        arr = as_float_array(value, label, "-", ndim=(0,))
        check_finite(arr, label, "-")
        if not 0.0 <= float(arr) <= 1.0:
            raise ValueError(f"{label} must lie in [0, 1] [-] (or be None); "
                             f"got {label} = {float(arr)!r}")
        return float(arr)
    unit = _SOLVE_UNITS[name]
    arr = as_float_array(value, label, unit, ndim=(0,))
    if name == "work_of_adhesion":
        check_nonnegative(arr, label, unit)
    else:
        check_positive(arr, label, unit)
    return float(arr)


def _check_pressure(pressure):
    p = as_float_array(pressure, "pressure", "Pa", ndim=(0, 1))
    check_finite(p, "pressure", "Pa")
    p = np.atleast_1d(p).astype(np.float64)
    if p.size == 0:
        raise ValueError("pressure must hold at least one nominal pressure [Pa]; "
                         "got an empty array")
    return p


def _check_positive_int(value, name):
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise ValueError(f"{name} must be a positive integer or None; got {name} = {value!r}")
    return int(value)


def _check_progress(progress):
    if progress is None or isinstance(progress, bool) or callable(progress):
        return progress
    raise ValueError(f"progress must be None, True, False or a callable progress(done, total); "
                     f"got progress = {progress!r}")


def _check_theories(theory, theory_gamma):
    """``theory`` and ``theory_gamma`` of a scan: (list of (theory, gamma used), is_axis).

    A string is one theory held fixed (:func:`check_theory`); a sequence is an axis of
    distinct theories, ``theory_gamma`` (None or one value) going to each corrected one.
    """
    if isinstance(theory, str) or np.ndim(theory) == 0:
        return [check_theory(theory, theory_gamma)], False
    names = list(theory) if np.ndim(theory) == 1 else None
    if names is None:
        raise ValueError(f"theory must be one theory or a 1-D sequence of theories [-]; "
                         f"got theory of shape {np.shape(theory)}")
    if not names:
        raise ValueError("theory must hold at least one theory (a sequence is an axis of the "
                         "result) [-]; got an empty sequence")
    valid = ", ".join(repr(t) for t in THEORIES)
    seen = {}
    for i, name in enumerate(names):
        if not isinstance(name, str) or name not in THEORIES:
            raise ValueError(f"theory[{i}] must be one of {valid} [-]; got theory[{i}] = "
                             f"{name!r}")
        if name in seen:
            raise ValueError(f"theory must hold distinct theories (they label an axis) [-]; "
                             f"got theory[{seen[name]}] = theory[{i}] = {name!r}")
        seen[name] = i
    if theory_gamma is not None and names == ["persson01"]:
        check_theory("persson01", theory_gamma)          # raises: persson01 has no gamma
    return [check_theory(str(n), None if n == "persson01" else theory_gamma)
            for n in names], True


#: relative distance from q1/q0 within which the last point of a user zeta grid counts as it
#: (as in solve_contact, which sets that point to q1/q0 exactly)
ZETA1_RTOL = 1e-12


def _check_zeta(zeta, surfaces):
    """A user zeta grid: 1-D, starting at 1, increasing, ending at every scene's q1/q0.

    Checked here, before anything is solved, rather than by each scene's solve_contact (which
    refuses such a grid too): one wrong grid is an input error of the scan, not a failure of
    every scene.
    """
    if zeta is None:
        return None
    z = as_float_array(zeta, "zeta", "-", ndim=(1,))
    check_finite(z, "zeta", "-")
    if z.size == 0 or z[0] != 1.0:
        first = z[0].item() if z.size else None
        raise ValueError(f"zeta must start at 1 [-]; got zeta[0] = {first!r}")
    if np.any(np.diff(z) <= 0):
        i = int(np.argmax(np.diff(z) <= 0))
        raise ValueError(f"zeta must be increasing [-]; got zeta[{i}] = {z[i].item()!r} >= "
                         f"zeta[{i + 1}] = {z[i + 1].item()!r}")
    for label, s in surfaces:
        zeta1 = s.q1 / s.q0
        if z[-1] > zeta1 * (1 + ZETA1_RTOL):
            raise ValueError(f"zeta must lie in [1, q1/q0] [-] for every scene; the scene {label} "
                             f"has q1/q0 = {zeta1!r}, got zeta[-1] = {z[-1].item()!r}")
        if abs(z[-1] - zeta1) > ZETA1_RTOL * zeta1:
            raise ValueError(f"zeta must end at q1/q0 [-] of every scene (area is A(zeta1)/A0); "
                             f"the scene {label} has q1/q0 = {zeta1!r}, got zeta[-1] = "
                             f"{z[-1].item()!r}; append q1/q0 or pass zeta=None")
    z = z.copy()
    z[-1] = surfaces[0][1].q1 / surfaces[0][1].q0       # as solve_contact sets it
    return z


# ----------------------------------------------------------------------------------------------
# the grid of scenes
# ----------------------------------------------------------------------------------------------
class _Grid:
    """The scene grid: dimensions, coordinates, fixed values, surfaces and solve arguments."""

    def __init__(self, surface, params, solve_keywords, theories, theory_axis):
        if not isinstance(params, dict):
            raise ValueError(f"params must be a dict {{name: values}}; got {type(params).__name__}")
        is_instance = isinstance(surface, Surface)
        if not is_instance and not callable(surface):
            raise ValueError("surface must be a surface model class or factory "
                             f"(e.g. pf.SelfAffine) or a Surface instance; got {surface!r}")
        self.factory = surface
        self.factory_name = _factory_name(surface)
        accepted = () if is_instance else _factory_parameters(surface)
        self.units = _parameter_units(surface)
        self.dims, self.coords, self.values = [], {}, {}
        self.fixed_coords, fixed = {}, {}
        for name, values in params.items():
            if not isinstance(name, str) or not name.isidentifier():
                raise ValueError(f"params keys must be parameter names (identifiers); got {name!r}")
            if name in _RESERVED:
                raise ValueError(f"params cannot hold {name!r}: it is an axis of the result "
                                 f"(pass the pressures as the `pressure` argument)")
            if name in ("theory", "theory_gamma"):
                raise ValueError(f"params cannot hold {name!r}: pass it as the `{name}` "
                                 f"argument of scan (a sequence of theories is an axis)")
            if name not in SOLVE_PARAMETERS:
                if is_instance:
                    raise ValueError(
                        f"params[{name!r}] is a surface parameter, but surface is an instance of "
                        f"{self.factory_name}; pass the class or a factory (e.g. pf.SelfAffine) to "
                        f"scan its parameters, or scan only {', '.join(SOLVE_PARAMETERS)}")
                if accepted is not None and name not in accepted:
                    raise ValueError(
                        f"params key {name!r} is neither a parameter of {self.factory_name} "
                        f"({', '.join(accepted)}) nor a solve parameter "
                        f"({', '.join(SOLVE_PARAMETERS)})")
            is_dim, coord, passed = _check_values(name, values, self.units.get(name, "-"))
            if is_dim:
                self.dims.append(name)
                self.coords[name] = coord
                self.values[name] = passed
            else:
                if passed[0] is not None:
                    self.fixed_coords[name] = coord
                fixed[name] = passed[0]
        # the theory axis, after the axes of params; the gamma each theory uses rides along
        self.theories = theories
        self.aux_coords = {}
        if theory_axis:
            self.dims.append("theory")
            self.values["theory"] = [t for t, _ in theories]
            self.coords["theory"] = np.empty(len(theories), dtype=object)
            self.coords["theory"][:] = self.values["theory"]
            self.aux_coords["theory_gamma"] = (
                "theory", np.array([math.nan if g is None else g for _, g in theories]),
                {"long_name": "theory_gamma used (NaN: persson01, no parameter)", "units": "-"})
        # solve parameters: from params, or from the keywords of scan
        for name in SOLVE_PARAMETERS:
            given = solve_keywords[name]
            if name in params:
                default = _SOLVE_DEFAULTS[name]
                if not (given is default or (given is not None and default is not None
                                             and np.ndim(given) == 0 and given == default)):
                    raise ValueError(f"{name} is given twice: as a keyword ({given!r}) and "
                                     f"as a key of params; keep one")
            elif name == "e_star" and given is None:
                raise ValueError("e_star must be given, as a keyword or as a key of params [Pa]; "
                                 "got none")
            else:
                fixed[name] = given
        self.checked = {}
        for name in SOLVE_PARAMETERS:
            if name in self.values:
                self.checked[name] = [
                    _check_solve_value(name, v, f"params[{name!r}][{i}]", axis=True)
                    for i, v in enumerate(self.values[name])]
            else:
                label = f"params[{name!r}]" if name in params else name
                fixed[name] = _check_solve_value(name, fixed[name], label)
        self.fixed = fixed
        self.shape = tuple(len(self.values[d]) for d in self.dims)
        self.n_scenes = int(np.prod(self.shape, dtype=np.int64)) if self.shape else 1
        self.surface_dims = [d for d in self.dims
                             if d not in SOLVE_PARAMETERS and d != "theory"]
        self._build(surface, is_instance)

    def _label(self, index_tuple) -> str:
        parts = [f"{d}={self.values[d][i]!r}" for d, i in zip(self.dims, index_tuple)]
        return "(" + ", ".join(parts) + ")" if parts else "(the only scene)"

    def _build(self, surface, is_instance):
        fixed_surface = {k: v for k, v in self.fixed.items() if k not in SOLVE_PARAMETERS}
        surf_pos = [self.dims.index(d) for d in self.surface_dims]
        cache = {}
        self.scenes = []          # (flat index, surface, solve kwargs)
        self.labels = []
        self.surfaces = []        # distinct surfaces with a label, for checks
        for flat, idx in enumerate(itertools.product(*[range(n) for n in self.shape])):
            key = tuple(idx[k] for k in surf_pos)
            if key not in cache:
                if is_instance:
                    s = surface
                else:
                    kw = dict(fixed_surface)
                    kw.update({d: self.values[d][idx[self.dims.index(d)]]
                               for d in self.surface_dims})
                    try:
                        s = surface(**kw)
                    except (ValueError, TypeError) as exc:
                        raise ValueError(f"{self.factory_name}(...) failed for the scene "
                                         f"{self._label(idx)}: {exc}") from exc
                    if not isinstance(s, Surface):
                        raise ValueError(f"surface factory {self.factory_name} must return a "
                                         f"persson_fast Surface; got {type(s).__name__}")
                cache[key] = s
                self.surfaces.append((self._label(idx), s))
            kw = {}
            for name in SOLVE_PARAMETERS:
                if name in self.values:
                    kw[name] = self.checked[name][idx[self.dims.index(name)]]
                else:
                    kw[name] = self.fixed[name]
            t, g = self.theories[idx[-1] if "theory" in self.dims else 0]
            if t != "persson01":
                kw.update(theory=t, theory_gamma=g)
            self.scenes.append((flat, cache[key], kw))
            self.labels.append(self._label(idx))


def _profile_grid(grid, zeta, rtol, any_adhesive):
    """The common zeta grid of the profiles, and the zeta to pass to each kind of scene."""
    if zeta is not None:
        return zeta, zeta, zeta
    if any_adhesive:
        grids = [(lab, adhesion_zeta(s, rtol)) for lab, s in grid.surfaces]
        what = "adhesion_zeta(surface, rtol)"
    else:
        grids = [(lab, default_zeta(s)) for lab, s in grid.surfaces]
        what = "default_zeta(surface)"
    first_label, common = grids[0]
    for lab, g in grids[1:]:
        if not np.array_equal(g, common):
            raise ValueError(
                f"profiles=True needs one zeta grid for all scenes, but the default grids "
                f"({what}) of the scenes {first_label} and {lab} differ (the scan changes the "
                f"band q0, q1 or the roll-off); pass zeta= explicitly")
    # adhesive scenes keep their default grid (None, bitwise as solve_contact); scenes without
    # adhesion are evaluated on the same grid (their closed form is exact on any grid)
    return common, (None if any_adhesive else common), common


def _estimate_seconds(grid, n_p, options, workers):
    total = 0.0
    closed = options["method"] in ("auto", "analytic")
    for _, _, kw in grid.scenes:
        if kw["work_of_adhesion"] > 0:
            per = _COST_ADHESION * (1e-4 / options["rtol"]) ** 0.45
            total += per * n_p
            if options["pull_off"]:
                per_po = _COST_ADHESION * (1e-4 / options["pull_off_rtol"]) ** 0.45
                total += _PULL_OFF_SOLVES * per_po
        else:
            total += (_COST_CLOSED_FORM if closed else _COST_CN) * n_p
        total += _COST_SCENE
    return total / max(1, workers)


class _Progress:
    """A tqdm bar, a user callback progress(done, total), or nothing."""

    def __init__(self, progress, total, estimate):
        self.callback = progress if callable(progress) and not isinstance(progress, bool) else None
        self.bar = None
        self.done = 0
        self.total = total
        show = progress is True or (
            progress is None
            and (total > PROGRESS_MIN_SCENES or estimate > PROGRESS_MIN_SECONDS)
            and _stderr_is_terminal())
        if show:
            tqdm = optional_import("tqdm", "scan", "a scan's progress bar").tqdm

            self.bar = tqdm(total=total, unit="scene", desc="scan", file=sys.stderr,
                            dynamic_ncols=True)

    def update(self, n):
        self.done += n
        if self.bar is not None:
            self.bar.update(n)
        if self.callback is not None:
            self.callback(self.done, self.total)

    def close(self):
        if self.bar is not None:
            self.bar.close()


def _stderr_is_terminal() -> bool:
    try:
        return bool(sys.stderr.isatty())
    except (AttributeError, ValueError):
        return False


# ----------------------------------------------------------------------------------------------
# execution paths
# ----------------------------------------------------------------------------------------------
def _run_local(grid, pressure, options, workers, progress, results):
    closed = (options["method"] in ("auto", "analytic")
              and all(kw["work_of_adhesion"] == 0 for _, _, kw in grid.scenes))
    if closed or workers == 1 or grid.n_scenes == 1:
        # closed forms are microseconds of Python (threads would only add overhead); one
        # scene or one worker: solve_contact picks its own pressure parallelism
        for index, surface, kw in grid.scenes:
            try:
                results[index] = _solve_scene(surface, kw, pressure, options)
            except Exception as exc:      # a failure of the scan itself, not of the scene
                _add_note(exc, f"in scan scene {grid.labels[index]}")
                raise
            progress.update(1)
        return "local, sequential"
    opts = dict(options, parallel=False)      # threads over scenes, serial kernels inside
    pool = ThreadPoolExecutor(max_workers=workers, thread_name_prefix="persson-scan")
    futures = {}
    try:
        for index, surface, kw in grid.scenes:
            futures[pool.submit(_solve_scene, surface, kw, pressure, opts)] = index
        pending = set(futures)
        while pending:
            done, pending = wait(pending, timeout=0.2, return_when=FIRST_COMPLETED)
            for fut in done:
                index = futures[fut]
                try:
                    results[index] = fut.result()
                except BaseException as exc:
                    _add_note(exc, f"in scan scene {grid.labels[index]}")
                    raise
                progress.update(1)
    finally:
        # on an interrupt or error: drop the scenes not started, wait for the running ones
        for fut in futures:
            fut.cancel()
        pool.shutdown(wait=True, cancel_futures=True)
    return f"local, {workers} threads over scenes"


def _add_note(exc, note):
    if hasattr(exc, "add_note"):
        exc.add_note(note)


def _warm_worker():
    """Load the serial kernels on a worker (from numba's disk cache after the first time)."""
    from .api import warmup

    return warmup(False)


def _worker_threads(client) -> int:
    try:
        info = client.scheduler_info()
        return max(1, sum(int(w.get("nthreads", 1)) for w in info.get("workers", {}).values()))
    except Exception:  # noqa: BLE001 -- a best guess only decides the chunk size
        return 1


def _run_distributed(client, grid, pressure, options, chunks, progress, results):
    as_completed = optional_import("distributed", "scan", "pf.scan(client=...)").as_completed

    opts = dict(options, parallel=False)
    if chunks is None:
        n_tasks = 4 * _worker_threads(client)
        chunks = max(1, -(-grid.n_scenes // n_tasks))
    groups = [grid.scenes[i:i + chunks] for i in range(0, grid.n_scenes, chunks)]
    client.run(_warm_worker)
    token = uuid.uuid4().hex[:12]
    keys = [f"persson-scan-{token}-{k}" for k in range(len(groups))]
    futures = None
    try:
        futures = client.map(solve_chunk, groups, [pressure] * len(groups),
                             [opts] * len(groups), key=keys, pure=False)
        for fut in as_completed(futures):
            chunk = fut.result()
            for index, res in chunk:
                results[index] = res
            progress.update(len(chunk))
            del fut
    except BaseException:
        # an interrupt or a failed chunk: no task of this scan may stay on the cluster
        if futures is None:
            from distributed import Future

            futures = [Future(k, client=client) for k in keys]
        client.cancel(futures, force=True)
        raise
    finally:
        futures = None
    return f"distributed, {len(groups)} tasks of <= {chunks} scenes"


def _open_client(client):
    """(client, cluster we own or None, client we own or None)."""
    if client is None:
        return None, None, None
    if isinstance(client, str):
        distributed = optional_import("distributed", "scan", "pf.scan(client=...)")
        Client, LocalCluster = distributed.Client, distributed.LocalCluster

        if client == "local":
            cluster = LocalCluster(n_workers=None, threads_per_worker=1, processes=True,
                                   dashboard_address=":0")
            try:
                own = Client(cluster)
            except BaseException:
                cluster.close()
                raise
            return own, cluster, own
        own = Client(client)
        return own, None, own
    for attr in ("map", "cancel", "run", "submit"):
        if not hasattr(client, attr):
            raise ValueError(f"client must be None, 'local', a scheduler address or a "
                             f"dask.distributed.Client; got {client!r}")
    return client, None, None


# ----------------------------------------------------------------------------------------------
# the public function
# ----------------------------------------------------------------------------------------------
def scan(surface, params, pressure, *, e_star=None, work_of_adhesion=0.0, energy_correction=None,
         detachment_prefactor=DETACHMENT_PREFACTOR, method="auto", rtol=1e-6, zeta=None, profiles=False,
         pull_off=False, pull_off_rtol=None, client=None, chunks=None, workers=None,
         progress=None, theory="persson01", theory_gamma=None, separation=False,
         hardness=None):
    """Contact area over a grid of scenes crossed with nominal pressures.

    Parameters
    ----------
    surface : type, callable, Surface or Scene
        A surface model class or factory called as ``surface(**surface_parameters)`` for
        each scene (e.g. ``pf.SelfAffine``, ``pf.CapillaryWaves``, a ``functools.partial``
        or any function returning a :class:`~persson_fast.Surface`); or one Surface
        instance when only solve parameters are scanned; or one
        :class:`~persson_fast.Scene`, whose parameters are then the fixed ones (a solve
        parameter in ``params`` still makes an axis).
    params : dict of str to scalar or sequence
        The scene parameters. A sequence makes an axis of the result (named by its key, in
        the order of the dict; its values must be distinct); a scalar is held fixed (a scalar
        coordinate of the result). Keys are the factory's keyword arguments (``hurst``,
        ``h_rms``, ``slope_rms``, ``q0``, ``q1``, ``temperature``, ...) or the solve
        parameters ``e_star``, ``work_of_adhesion``, ``energy_correction`` (None or NaN: no
        correction) and ``detachment_prefactor``.
    pressure : float or array_like, shape (n_p,)
        Nominal pressures, the last axis of the result. Negative values (tension) are
        allowed: with adhesion they are solved, without adhesion the surfaces separate and
        the area is 0 (no solve). [Pa]
    e_star : float, optional
        Effective modulus E* > 0, unless scanned in ``params``. [Pa]
    work_of_adhesion : float
        Delta gamma >= 0, unless scanned (default 0, no adhesion). [J/m^2]
    energy_correction : float or None
        gamma_S of the elastic-energy correction, in [0, 1], unless scanned. [-]
    detachment_prefactor : float
        beta of seed Eq. 8 (default 1/sqrt 2), unless scanned. [-]
    method : str
        As in :func:`~persson_fast.solve_contact` (a key of ``pf.METHODS``).
    rtol : float
        Target relative accuracy of every solve, in [1e-12, 0.1]. [-]
    zeta : array_like or None
        Magnifications passed to every solve (as in :func:`~persson_fast.solve_contact`; with
        adhesion the fixed point runs on this grid). None: each scene's default. [-]
    profiles : bool
        Also return A(zeta)/A0, sigma_a(zeta) and gamma_eff(zeta) on a ``zeta`` axis. All
        scenes need one grid: with ``zeta=None`` the default grids must agree (true unless
        the band or roll-off is scanned); scenes without adhesion are then evaluated on the
        adhesive scenes' grid, which is exact for their closed form.
    pull_off : bool
        Also compute the pull-off stress of every scene with :func:`~persson_fast.pull_off`
        (0 without adhesion or where the surfaces are not sticky; NaN, with ``success``
        False, where it raises; kept, with ``success`` False, where its error estimate
        exceeds ``pull_off_rtol``). [Pa]
    pull_off_rtol : float or None
        Relative accuracy of the pull-off stress (default ``rtol``). [-]
    client : None, "local", str or dask.distributed.Client
        None: run here (threads). A Client: chunks of scenes become tasks on its cluster (the
        client stays open). ``"local"``: start a ``LocalCluster`` of single-threaded worker
        processes for this scan and close it afterwards (in a script, call scan under
        ``if __name__ == "__main__":``, as worker processes are spawned). Any other string:
        the address of a scheduler to connect to (the connection is closed afterwards).
    chunks : int or None
        Scenes per distributed task (default: about four tasks per worker thread).
    workers : int or None
        Threads of the local path (default ``numba.get_num_threads()``); 1 runs the scenes one
        after another, each spreading its pressures over threads as ``solve_contact`` does.
    progress : None, bool or callable
        Show a tqdm progress bar: None shows it for scans of more than 50 scenes or longer
        than about 2 s, when stderr is a terminal; True / False force it on / off. A callable
        is called as ``progress(done, total)`` (in scenes) after each scene or chunk.

    theory : str or sequence of str
        The area theory of the solves (as in :func:`~persson_fast.solve_contact`:
        "persson01", the default, or a corrected one: "yp08" and "wm17" for every scene,
        "xu24" for scenes without adhesion or hardness; ``pull_off`` with adhesion needs
        "persson01"). A string is held fixed and recorded in ``attrs``. A
        sequence of distinct theories is an axis ``theory`` of the result, after the axes of
        ``params``; each of its entries gives bitwise the numbers of a scan with that theory
        held fixed, and ``attrs["theory"]`` and ``attrs["theory_gamma"]`` are then "". [-]
    theory_gamma : float or None
        The gamma of the corrected theories (None: each one's published default,
        ``persson_fast.theories.DEFAULT_GAMMA``). Held fixed: recorded in ``attrs``. With a
        theory axis it goes to every corrected theory of the axis and not to "persson01",
        which has no parameter (a value with "persson01" alone is a ValueError); the
        coordinate ``theory_gamma`` along ``theory`` records the gamma each theory used
        (NaN for "persson01"). [-]
    hardness : float or None
        The yield wall of every scene, unless scanned in ``params`` (values: a constant
        hardness [Pa], or None / NaN for none; see ``solve_contact(hardness=...)``). Held
        fixed, it may also be scale-dependent (a callable of zeta or a table; ``attrs``
        records its repr; a callable must pickle for process workers). With a
        yield wall anywhere in the scan the dataset has ``elastic_area`` and
        ``plastic_area`` ((..., pressure); ``area`` is their sum).
    separation : bool
        Also return the mean interfacial separation, the contact stiffness and the stored
        elastic energy of every scene and pressure (scenes without adhesion, theory
        "persson01"; otherwise a ValueError before anything is solved).

    Returns
    -------
    xarray.Dataset
        Dimensions: the scanned parameters in the order of ``params``, then ``theory`` (with
        a sequence of theories), then ``pressure`` (then ``zeta`` with ``profiles``).
        Variables:

        * ``area`` (..., pressure) -- A(zeta1)/A0. [-]
        * ``mean_contact_pressure`` (..., pressure) -- load / area, NaN without contact. [Pa]
        * ``error_estimate`` (..., pressure) -- estimated absolute error of ``area``. [-]
        * ``status`` (..., pressure) -- 0 ok, else see ``message``; :data:`SCENE_ERROR`
          (-1) where the scene's ``solve_contact`` raised.
        * ``success``, ``message``, ``method`` (...) -- per scene. ``message`` is
          ``solve_contact``'s message when the scene succeeded; when it failed it starts with
          what failed (never with "ok").
        * ``area_zeta``, ``sigma_a`` [Pa], ``gamma_eff`` [J/m^2] (..., pressure, zeta) -- with
          ``profiles``.
        * ``pull_off``, ``pull_off_error`` (...) -- with ``pull_off``: the pull-off stress
          and its estimated error. [Pa]
        * ``separation`` [m], ``stiffness`` [Pa/m], ``elastic_energy`` [J/m^2]
          (..., pressure) -- with ``separation``: the mean interfacial separation, the
          contact stiffness -dp/du and U_el of each scene (closed form,
          :func:`~persson_fast.solve_separation`; inf, 0, 0 where p <= 0).

        Fixed parameters are scalar coordinates; ``attrs`` hold the surface model, method,
        rtol and how the scan ran. ``ds.to_dataframe()`` gives one row per (scene, pressure).

    Raises
    ------
    ValueError
        For invalid input, naming the argument, the rule and the offending value, before
        anything is solved (every scene's surface is built and checked first).

    Warns
    -----
    ScanWarning
        Once per scan when any scene failed (``success`` False): the number of failed scenes
        and of flagged (scene, pressure) points, and the parameters and messages of the
        worst few scenes (a raised solve first, then a failed pull-off, then the most
        flagged points).

    Notes
    -----
    Scene ``s`` of the grid is ``solve_contact(surface_s, pressure, e_star=..., ...)``; the
    dataset holds exactly its numbers, whichever execution path ran (see the module
    docstring). A scene that fails does not stop the scan: an exception raised by its
    ``solve_contact`` or ``pull_off`` is recorded (NaN numbers, ``status`` -1 for a raised
    solve, ``success`` False, the exception's type and text in ``message``), the other
    scenes run on, and the scan ends with one :class:`ScanWarning`. A ``KeyboardInterrupt``
    stops the scan: scenes not yet started are dropped (distributed: the pending tasks are
    cancelled) and the interrupt propagates.

    Examples
    --------
    >>> import numpy as np, persson_fast as pf
    >>> ds = pf.scan(pf.SelfAffine, {"hurst": [0.6, 0.8], "h_rms": [1e-7, 1e-6],
    ...              "q0": 1e4, "q1": 1e9}, np.linspace(0, 1e7, 11), e_star=3e9)
    >>> ds.area.dims
    ('hurst', 'h_rms', 'pressure')
    """
    xr = optional_import("xarray", "scan", "pf.scan")
    if isinstance(surface, Scene):
        # one scene, only solve parameters (or none) scanned: its values are the fixed ones
        surface, kw = unpack_scene(surface, {"e_star": e_star,
                                             "work_of_adhesion": work_of_adhesion,
                                             "energy_correction": energy_correction,
                                             "detachment_prefactor": detachment_prefactor,
                                             "hardness": hardness},
                                   "scan")
        hardness = kw.get("hardness")
        e_star, work_of_adhesion = kw["e_star"], kw["work_of_adhesion"]
        energy_correction = kw["energy_correction"]
        detachment_prefactor = kw["detachment_prefactor"]

    from ._version import __version__

    solve_keywords = {"e_star": e_star, "work_of_adhesion": work_of_adhesion,
                      "energy_correction": energy_correction,
                      "detachment_prefactor": detachment_prefactor, "hardness": hardness}
    if not isinstance(method, str) or method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(repr(m) for m in METHODS)}; "
                         f"got method = {method!r}")
    rtol = _check_rtol(rtol)
    theories, theory_axis = _check_theories(theory, theory_gamma)
    pull_off_rtol = rtol if pull_off_rtol is None else _check_rtol(pull_off_rtol, "pull_off_rtol")
    p = _check_pressure(pressure)
    for name, flag in (("profiles", profiles), ("pull_off", pull_off),
                       ("separation", separation)):
        if not isinstance(flag, (bool, np.bool_)):
            raise ValueError(f"{name} must be True or False; got {name} = {flag!r}")
    chunks = _check_positive_int(chunks, "chunks")
    workers = _check_positive_int(workers, "workers")
    progress = _check_progress(progress)
    grid = _Grid(surface, params, solve_keywords, theories, theory_axis)
    zeta = _check_zeta(zeta, grid.surfaces)
    adhesive = [kw["work_of_adhesion"] > 0 for _, _, kw in grid.scenes]
    if method == "analytic" and any(adhesive):
        i = adhesive.index(True)
        raise ValueError(f"method 'analytic' has no closed form with adhesion; the scene "
                         f"{grid.labels[i]} has work_of_adhesion > 0; use method='auto' or 'cn'")
    corrected = [kw.get("theory", "persson01") != "persson01" for _, _, kw in grid.scenes]
    yielding = [kw.get("hardness") is not None for _, _, kw in grid.scenes]
    for k in range(len(corrected)):
        if corrected[k] and (adhesive[k] or yielding[k]):
            kw = grid.scenes[k][2]
            check_theory_scene(kw["theory"], kw["work_of_adhesion"], kw.get("hardness"))
            if pull_off and adhesive[k]:
                raise ValueError(
                    f"pull_off=True follows the original theory's contact branch only: the "
                    f"scene {grid.labels[k]} has work_of_adhesion > 0 and theory = "
                    f"{grid.scenes[k][2]['theory']!r}; scan the pull-off with "
                    f"theory='persson01'")
    if any(yielding):
        i = yielding.index(True)
        if separation:
            raise ValueError(f"separation=True needs elastic scenes: the scene "
                             f"{grid.labels[i]} has hardness (the separation is not derived "
                             f"with a yield wall here)")
        if method not in ("auto", "analytic", "strip"):
            raise ValueError(f"method {method!r} cannot carry a yield wall (hardness); use "
                             f"'auto', 'analytic' (a constant one) or 'strip' (the scene "
                             f"{grid.labels[i]} has hardness)")
    if separation and (any(corrected) or any(adhesive)):
        which = (f"theory = {grid.scenes[corrected.index(True)][2]['theory']!r}"
                 if any(corrected) else
                 f"the scene {grid.labels[adhesive.index(True)]} has work_of_adhesion > 0")
        raise ValueError(f"separation=True needs scenes without adhesion and the original "
                         f"theory (persson01): the separation is not derived otherwise here; "
                         f"{which}")
    profile_zeta = None
    zeta_plain = zeta_adhesive = zeta
    if profiles:
        profile_zeta, zeta_adhesive, zeta_plain = _profile_grid(
            grid, zeta, rtol, any(adhesive))
    options = {"method": method, "rtol": rtol, "zeta_plain": zeta_plain,
               "zeta_adhesive": zeta_adhesive, "profile_zeta": profile_zeta,
               "profiles": bool(profiles), "pull_off": bool(pull_off),
               "pull_off_rtol": pull_off_rtol, "parallel": None,
               "separation": bool(separation), "yield_wall": any(yielding)}
    if workers is None:
        import numba

        workers = max(1, int(numba.get_num_threads()))

    results = [None] * grid.n_scenes
    t0 = time.perf_counter()
    client_, own_cluster, own_client = None, None, None
    bar = None
    try:
        client_, own_cluster, own_client = _open_client(client)
        threads = _worker_threads(client_) if client_ is not None else workers
        bar = _Progress(progress, grid.n_scenes, _estimate_seconds(grid, p.size, options, threads))
        # solve_contact and pull_off change the warning filters inside each scene
        # (catch_warnings), which is not thread-safe before Python 3.14: whatever state the
        # scene threads interleave to is undone here, when the scan ends
        with warnings.catch_warnings():
            if client_ is None:
                execution = _run_local(grid, p, options, workers, bar, results)
            else:
                execution = _run_distributed(client_, grid, p, options, chunks, bar, results)
    finally:
        if bar is not None:
            bar.close()
        if own_client is not None:
            own_client.close()
        if own_cluster is not None:
            own_cluster.close()
    wall = time.perf_counter() - t0
    ds = _assemble(xr, grid, p, results, options, profile_zeta,
                   {"surface_model": grid.factory_name, "method": method, "rtol": rtol,
                    "theory": "" if theory_axis else theories[0][0],
                    "theory_gamma": ("" if theory_axis or theories[0][1] is None else
                                     theories[0][1]),
                    "hardness": ("" if hardness is None or "hardness" in params else
                                 hardness if isinstance(hardness, float) else repr(hardness)),
                    "pull_off_rtol": pull_off_rtol if pull_off else "",
                    "execution": execution, "wall_time_s": wall,
                    "persson_fast_version": __version__})
    summary = _failure_summary(grid, results, p.size)
    if summary is not None:
        warnings.warn(summary, ScanWarning, stacklevel=2)
    return ds


def _failure_summary(grid, results, n_p):
    """The text of the scan's one ScanWarning; None when every scene succeeded."""
    failed = [i for i, res in enumerate(results) if not res["success"]]
    if not failed:
        return None
    flagged = [int(np.count_nonzero(res["status"])) for res in results]

    def severity(i):
        res = results[i]
        no_numbers = bool(np.any(res["status"] == SCENE_ERROR))
        no_pull_off = math.isnan(res.get("pull_off", 0.0))
        return (no_numbers, no_pull_off, flagged[i])

    worst = sorted(failed, key=severity, reverse=True)[:WARN_SCENES]   # stable: grid order
    n_points = sum(flagged)
    lines = [f"scan: {len(failed)} of {grid.n_scenes} scenes failed (success False) and "
             f"{n_points} of {grid.n_scenes * n_p} (scene, pressure) points are flagged "
             f"(status != 0): a failed solve or pull-off is NaN, a flagged or unconverged value "
             f"is kept; see ds.success, ds.message and ds.status. "
             f"{'The worst' if len(failed) > len(worst) else 'Failed'}:"]
    for i in worst:
        msg = str(results[i]["message"])
        if len(msg) > WARN_MESSAGE_CHARS:
            msg = msg[:WARN_MESSAGE_CHARS - 3] + "..."
        lines.append(f"  {grid.labels[i]}: {msg}")
    if len(failed) > len(worst):
        lines.append(f"  ... and {len(failed) - len(worst)} more")
    return "\n".join(lines)


def _assemble(xr, grid, p, results, options, profile_zeta, attrs):
    shape = grid.shape
    n_p = p.size
    dims = tuple(grid.dims)
    per_p = dims + ("pressure",)

    def stack(name, dtype, tail=()):
        arr = np.empty((grid.n_scenes,) + tail, dtype=dtype)
        for i, res in enumerate(results):
            arr[i] = res[name]
        return arr.reshape(shape + tail)

    data = {
        "area": (per_p, stack("area", float, (n_p,)),
                 {"long_name": "relative real contact area A(zeta1)/A0", "units": "-"}),
        "mean_contact_pressure": (per_p, stack("mean_contact_pressure", float, (n_p,)),
                                  {"long_name": "mean stress in the contact, load/area",
                                   "units": "Pa"}),
        "error_estimate": (per_p, stack("error_estimate", float, (n_p,)),
                           {"long_name": "estimated absolute error of area", "units": "-"}),
        "status": (per_p, stack("status", np.int64, (n_p,)),
                   {"long_name": f"status per pressure (0 ok, {SCENE_ERROR} the scene's solve "
                                 f"raised, others a kernel code; see message)"}),
        "success": (dims, stack("success", bool),
                    {"long_name": "scene solved: every pressure (and the pull-off) ok"}),
        "message": (dims, stack("message", object).astype(str), {"long_name": "solver message"}),
        "method": (dims, stack("method", object).astype(str),
                   {"long_name": "method that produced the numbers"}),
    }
    coords = {d: (d, grid.coords[d], {"units": grid.units[d]} if d in grid.units else {})
              for d in dims}
    coords["pressure"] = ("pressure", p, {"long_name": "nominal pressure", "units": "Pa"})
    for name, value in grid.fixed_coords.items():
        units = {"units": grid.units[name]} if name in grid.units else {}
        coords[name] = ((), value, units)
    coords.update(grid.aux_coords)
    if options["profiles"]:
        n_z = profile_zeta.size
        per_z = per_p + ("zeta",)
        coords["zeta"] = ("zeta", profile_zeta, {"long_name": "magnification", "units": "-"})
        data["area_zeta"] = (per_z, stack("area_zeta", float, (n_p, n_z)),
                             {"long_name": "relative contact area A(zeta)/A0", "units": "-"})
        data["sigma_a"] = (per_z, stack("sigma_a", float, (n_p, n_z)),
                           {"long_name": "detachment stress sigma_a(zeta)", "units": "Pa"})
        data["gamma_eff"] = (per_z, stack("gamma_eff", float, (n_p, n_z)),
                             {"long_name": "effective interfacial energy", "units": "J/m^2"})
    if options.get("yield_wall"):
        data["elastic_area"] = (per_p, stack("elastic_area", float, (n_p,)),
                                {"long_name": "elastic contact area A_el/A0", "units": "-"})
        data["plastic_area"] = (per_p, stack("plastic_area", float, (n_p,)),
                                {"long_name": "yielded (plastic) contact area A_pl/A0",
                                 "units": "-"})
    if options.get("separation"):
        data["separation"] = (per_p, stack("separation", float, (n_p,)),
                              {"long_name": "mean interfacial separation u", "units": "m"})
        data["stiffness"] = (per_p, stack("stiffness", float, (n_p,)),
                             {"long_name": "contact stiffness -dp/du", "units": "Pa/m"})
        data["elastic_energy"] = (per_p, stack("elastic_energy", float, (n_p,)),
                                  {"long_name": "stored elastic energy U_el per nominal area",
                                   "units": "J/m^2"})
    if options["pull_off"]:
        data["pull_off"] = (dims, stack("pull_off", float),
                            {"long_name": "pull-off stress sigma_c", "units": "Pa"})
        data["pull_off_error"] = (dims, stack("pull_off_error", float),
                                  {"long_name": "estimated error of pull_off", "units": "Pa"})
    return xr.Dataset(data, coords=coords, attrs=attrs)
