"""The scene grid of a parameter scan: its inputs checked and crossed into scenes.

:class:`_Grid` turns the ``params`` of :func:`persson_fast.scan` into the axes of the result
(names, coordinates, units) and into one surface and one set of solve arguments per scene;
the other checks here validate the remaining arguments of a scan (pressures, theories, the
zeta grid, workers, progress) before anything is solved. The units of the parameters come
from the surface models' declarations (:data:`PARAMETER_UNITS`, :func:`_parameter_units`).
"""
from __future__ import annotations

import inspect
import itertools
import math

import numpy as np

from .._validation import as_float_array, check_finite, check_nonnegative, check_positive
from ..adhesion.zeta_grid import adhesion_zeta
from ..scene import DETACHMENT_PREFACTOR, default_zeta
from ..theories import THEORIES, check_theory
from ..plasticity.hardness import check_hardness
from ..surfaces.models import SURFACE_MODELS, Surface

__all__ = ["SOLVE_PARAMETERS", "PARAMETER_UNITS", "ZETA1_RTOL"]


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
#: ``persson_fast.surfaces.models.SURFACE_MODELS``) and of the solve, for ``attrs``; a scan of any
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
