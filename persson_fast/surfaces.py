"""Surface roughness power spectra C(q) in Persson's isotropic convention.

Every model here describes a randomly rough, isotropic surface through its 2-D power
spectral density

.. math::

    C(q) = (2\\pi)^{-2} \\int d^2x \\, \\langle h(\\mathbf{x}) h(\\mathbf{0}) \\rangle
           e^{-i \\mathbf{q}\\cdot\\mathbf{x}}                                   [m^4]

cut off outside the band :math:`[q_0, q_1]` (Persson, J. Chem. Phys. 115, 3840 (2001);
Persson et al., J. Phys.: Condens. Matter 17, R1 (2005)). With this convention

.. math::

    h_{rms}^2 = 2\\pi \\int q C dq, \\qquad
    \\langle |\\nabla h|^2 \\rangle = 2\\pi \\int q^3 C dq,

and the contact theory sees the surface only through the diffusion time

.. math::

    G(q) = \\frac{\\pi}{4} E^{*2} \\int_{q_0}^{q} q'^3 C(q') dq'            [Pa^2]

(seed paper Eqs. 4-5 integrated over ζ; Persson 2001).

The public classes are :class:`CapillaryWaves` (seed Eq. 1), :class:`SelfAffine` (power law
with roll-off) and :class:`TabulatedPSD` (measured spectra, log-log interpolated). All three
share :class:`Surface`, whose :meth:`Surface.moment` returns the partial moments
:math:`\\int q^k C dq` (k = 0..3) in closed form wherever one exists. SI units, float64.

Surface models declare their parameters once: a subclass that sets ``MODEL`` (its name on the
command line and in TOML files) and ``PARAMETERS`` (name -> :class:`Parameter`: unit, help,
whether required) enters :data:`SURFACE_MODELS` when its class is created, in whatever module
that happens. The ``persson-fast contact`` command builds its flags and TOML keys from that
registry, and :func:`persson_fast.scan` reads the units of a declared class's parameters from
it; neither keeps its own list.
"""
from __future__ import annotations

import abc
import inspect
import math
import os
import sys
import warnings
from dataclasses import dataclass

import numpy as np

from ._validation import as_float_array, check_choice, check_finite, check_nonnegative, check_positive

__all__ = [
    "BOLTZMANN",
    "E_STAR_WARN_BELOW",
    "RmsValue",
    "Parameter",
    "SurfaceModel",
    "SURFACE_MODELS",
    "BAND",
    "band_parameters",
    "register_surface_model",
    "Surface",
    "CapillaryWaves",
    "SelfAffine",
    "TabulatedPSD",
    "seed_scene",
]

#: Boltzmann constant (exact, SI 2019) [J/K].
BOLTZMANN = 1.380649e-23

#: an effective modulus below this draws a UserWarning: it is most likely a modulus typed in
#: GPa or MPa where Pa is meant (``e_star=1.0`` for 1 GPa gives A = 1 at any pressure). Soft
#: gels (~1e3-1e4 Pa) warn too; ``warnings.filterwarnings("ignore", "e_star")`` silences it. [Pa]
E_STAR_WARN_BELOW = 1e5

_PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__)) + os.sep


def _user_stacklevel() -> int:
    """``stacklevel`` for ``warnings.warn`` in the caller that points at the first frame
    outside this package (the user's line), so that one call warns once under the default
    filter even when several layers check the same argument."""
    frame = sys._getframe(2)          # the caller of the function that warns: stacklevel 2
    level = 2
    while frame is not None and frame.f_code.co_filename.startswith(_PACKAGE_DIR):
        frame = frame.f_back
        level += 1
    return level


def check_e_star(e_star) -> float:
    """``e_star`` as a float: finite and > 0 (else a ValueError); a UserWarning below
    :data:`E_STAR_WARN_BELOW` (a modulus in GPa or MPa where Pa is meant). [Pa]"""
    e = _positive_scalar(e_star, "e_star", "Pa")
    if e < E_STAR_WARN_BELOW:
        warnings.warn(
            f"e_star = {e!r} Pa is below {E_STAR_WARN_BELOW:g} Pa, softer than any rubber: "
            f"e_star is in Pa (E* = 1 GPa is e_star=1e9, not 1.0); with so soft a solid the "
            f"contact is nearly complete at any pressure",
            UserWarning, stacklevel=_user_stacklevel())
    return e

_MOMENT_ORDERS = (0, 1, 2, 3)

# Gauss-Legendre rule used where no closed form exists (CapillaryWaves with gravity, k = 0, 2).
# The integrand is integrated in t = ln q on panels no wider than _GL_PANEL_WIDTH; its poles lie at
# least pi/4 off the real t axis, so a 20-point rule on unit panels converges to ~1e-20.
_GL_ORDER = 20
_GL_PANEL_WIDTH = 1.0
_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(_GL_ORDER)


# ----------------------------------------------------------------------------------------------
# scalar argument checks (built on the shared helpers)
# ----------------------------------------------------------------------------------------------
def _positive_scalar(value, name: str, unit: str) -> float:
    arr = as_float_array(value, name, unit, ndim=(0,))
    check_positive(arr, name, unit)
    return float(arr)


def _nonnegative_scalar(value, name: str, unit: str) -> float:
    arr = as_float_array(value, name, unit, ndim=(0,))
    check_nonnegative(arr, name, unit)
    return float(arr)


def _check_band(q0: float, q1: float) -> None:
    if not q1 > q0:
        raise ValueError(f"q1 must be > q0 [1/m]; got q1 = {q1!r}, q0 = {q0!r}")


def _check_hurst(hurst) -> float:
    arr = as_float_array(hurst, "hurst", "-", ndim=(0,))
    check_finite(arr, "hurst", "-")
    h = float(arr)
    if not 0.0 <= h <= 1.0:
        raise ValueError(f"hurst must be in [0, 1] [-]; got hurst = {h!r}")
    return h


def _check_order(k) -> int:
    check_choice(k, "k", _MOMENT_ORDERS)
    return int(k)


# ----------------------------------------------------------------------------------------------
# numerically stable elementary pieces (all arguments float64 arrays)
# ----------------------------------------------------------------------------------------------
def _expm1_ratio(x: np.ndarray) -> np.ndarray:
    """(e^x - 1)/x, equal to 1 at x = 0, accurate to a few ulp for every finite x."""
    x = np.asarray(x, dtype=np.float64)
    out = np.ones_like(x)
    nz = x != 0.0
    out[nz] = np.expm1(x[nz]) / x[nz]
    return out


def _log1p_ratio(x: np.ndarray) -> np.ndarray:
    """ln(1 + x)/x for x >= 0, equal to 1 at x = 0."""
    x = np.asarray(x, dtype=np.float64)
    out = np.ones_like(x)
    nz = x != 0.0
    out[nz] = np.log1p(x[nz]) / x[nz]
    return out


def _atan_ratio(x: np.ndarray) -> np.ndarray:
    """atan(x)/x for x >= 0, equal to 1 at x = 0."""
    x = np.asarray(x, dtype=np.float64)
    out = np.ones_like(x)
    nz = x != 0.0
    out[nz] = np.arctan(x[nz]) / x[nz]
    return out


def _x_minus_atan(x: np.ndarray) -> np.ndarray:
    """x - atan(x) for x >= 0 without cancellation (odd Taylor series below 0.1)."""
    x = np.asarray(x, dtype=np.float64)
    out = x - np.arctan(x)
    small = x < 0.1
    if np.any(small):
        xs = x[small]
        x2 = xs * xs
        # x - atan x = sum_{j>=1} (-1)^(j+1) x^(2j+1)/(2j+1); 10 terms reach 1e-18 relative.
        # Horner in x2: x^3 (1/3 - x2 (1/5 - x2 (1/7 - ...)))
        acc = np.zeros_like(xs)
        for j in range(10, 0, -1):
            acc = 1.0 / (2 * j + 1) - x2 * acc
        out[small] = xs * x2 * acc
    return out


def _x_minus_log1p(x: np.ndarray) -> np.ndarray:
    """x - ln(1 + x) for x >= 0 without cancellation (Taylor series below 0.1)."""
    x = np.asarray(x, dtype=np.float64)
    out = x - np.log1p(x)
    small = x < 0.1
    if np.any(small):
        xs = x[small]
        # x - ln(1+x) = x^2 (1/2 - x (1/3 - x (1/4 - ...))); 20 terms reach 1e-19 relative.
        acc = np.zeros_like(xs)
        for j in range(21, 1, -1):
            acc = 1.0 / j - xs * acc
        out[small] = xs * xs * acc
    return out


def _power_law_integral(coef, q_ref, exponent, a, b) -> np.ndarray:
    """Exact ∫_a^b coef (q/q_ref)^exponent dq for 0 < a <= b (arrays broadcast).

    With s = exponent + 1 and L = ln(b/a) the integral is
    coef q_ref (a/q_ref)^s L (e^{sL} - 1)/(sL); the ratio (e^x - 1)/x is evaluated with expm1,
    so the logarithmic case s = 0 is exact and s within 1e-8 of 0 loses nothing.
    """
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    s = np.asarray(exponent, dtype=np.float64) + 1.0
    log_ratio = np.log1p((b - a) / a)
    return (
        np.asarray(coef, dtype=np.float64)
        * q_ref
        * np.exp(s * np.log(a / q_ref))
        * log_ratio
        * _expm1_ratio(s * log_ratio)
    )


def _gauss_legendre_log(integrand_t, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """∫_a^b f dq computed as ∫ q f(q) d(ln q) with composite Gauss-Legendre, vectorised.

    ``integrand_t(q)`` must return q f(q). Panels are uniform in ln q, at most
    ``_GL_PANEL_WIDTH`` wide; each carries ``_GL_ORDER`` nodes.
    """
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    log_ratio = np.log1p((b - a) / a)
    n_panel = np.maximum(1, np.ceil(log_ratio / _GL_PANEL_WIDTH).astype(np.int64))
    owner = np.repeat(np.arange(a.size), n_panel)
    first = np.cumsum(n_panel) - n_panel
    panel = np.arange(owner.size) - np.repeat(first, n_panel)
    width = (log_ratio / n_panel)[owner]  # panel width in ln q
    frac = panel[:, None] + 0.5 * (_GL_NODES[None, :] + 1.0)  # position in panels
    q = a[owner][:, None] * np.exp(width[:, None] * frac)
    panel_sum = (integrand_t(q) * _GL_WEIGHTS[None, :]).sum(axis=1) * (0.5 * width)
    return np.bincount(owner, weights=panel_sum, minlength=a.size)


# ----------------------------------------------------------------------------------------------
# the base class
# ----------------------------------------------------------------------------------------------
# ----------------------------------------------------------------------------------------------
# declared parameters and the registry of surface models
# ----------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Parameter:
    """One declared parameter of a surface model.

    Parameters
    ----------
    unit : str or None
        SI unit of the value as the model takes it ('m', '1/m', 'J/m^2', '-' for a
        dimensionless number); None for text (file names, unit names), counts and values in a
        unit chosen by another parameter. The command line's help shows it in brackets, and
        :func:`persson_fast.scan` labels its axes with it.
    help : str
        What the parameter is, without the unit (e.g. 'rms height').
    required : bool, optional
        Whether the model needs it (default False). [-]
    metavar : str, optional
        The value's name in the command line's help; default the parameter's name in capitals.
    flag : str, optional
        The command-line flag; default ``--`` and the name in lower case with '-' for '_'
        (``h_rms`` -> ``--h-rms``, ``C0`` -> ``--c0``).
    type : {float, int, str}, optional
        The type of the value (default float); str for text, which TOML must give as a string.
    nargs : str, optional
        '+' for a list of numbers (argparse's nargs); default one value.
    path : bool, optional
        A file name: in a TOML file taken relative to the TOML file's folder (default False).
    selects : bool, optional
        Its flag also picks the model (``--psd FILE``); such a model is not one of the choices
        of ``--surface`` (default False).

    Notes
    -----
    The default a model uses when a parameter is not given is its constructor's (the help
    shows it, read from the signature); every flag's own default is "not given".
    """

    unit: str | None
    help: str
    required: bool = False
    metavar: str | None = None
    flag: str | None = None
    type: type = float
    nargs: str | None = None
    path: bool = False
    selects: bool = False

    def flag_for(self, name: str) -> str:
        """The command-line flag of the parameter ``name``."""
        return self.flag or "--" + name.lower().replace("_", "-")


@dataclass(frozen=True)
class SurfaceModel:
    """A surface model as the command line and :func:`persson_fast.scan` see it.

    Parameters
    ----------
    name : str
        The model's name: ``--surface NAME``, ``model = 'NAME'`` in a TOML file.
    parameters : dict of str to Parameter
        The keyword arguments of ``build`` the model offers, in the order shown.
    build : callable
        ``build(**values)`` returns the :class:`Surface`; it gets the parameters that were
        given, no others.
    title : str
        Title of the model's group of flags in the command line's help.
    description : str, optional
        Text under that title.
    """

    name: str
    parameters: dict
    build: object
    title: str
    description: str | None = None

    @property
    def required(self) -> tuple:
        """Names of the parameters the model needs."""
        return tuple(k for k, p in self.parameters.items() if p.required)

    @property
    def selector(self):
        """Name of the parameter whose flag picks the model, or None."""
        return next((k for k, p in self.parameters.items() if p.selects), None)

    def defaults(self) -> dict:
        """The defaults ``build`` uses for the parameters it has one for (not None)."""
        try:
            sig = inspect.signature(self.build)
        except (TypeError, ValueError):
            return {}
        return {k: v.default for k, v in sig.parameters.items()
                if k in self.parameters and v.default is not inspect.Parameter.empty
                and v.default is not None}


#: the surface models by name, in the order they were registered (the package's own first:
#: capillary, self-affine, topography, psd)
SURFACE_MODELS: dict = {}

#: names of the band limits every model has; the command line lists their flags once
BAND = ("q0", "q1")

_MODEL_NAME_CHARS = frozenset("abcdefghijklmnopqrstuvwxyz0123456789-")


def band_parameters(required: bool = True) -> dict:
    """The declarations of the band limits q0 and q1 (for a model's ``PARAMETERS``).

    Parameters
    ----------
    required : bool, optional
        Whether the model needs them (default True); measured spectra have their own. [-]
    """
    return {"q0": Parameter("1/m", "smallest wavevector", required=required),
            "q1": Parameter("1/m", "largest wavevector", required=required)}


def register_surface_model(model: SurfaceModel) -> SurfaceModel:
    """Add ``model`` to :data:`SURFACE_MODELS` (a model of the same name and the same build
    replaces it: a module imported again); return it.

    A :class:`Surface` subclass that sets ``MODEL`` is registered when it is created; call this
    for a model built by another function (as ``TabulatedPSD.from_file`` for 'psd').

    Raises
    ------
    ValueError
        For a name that is not lower-case letters, digits and '-', a name another model
        has, a parameter that is not a :class:`Parameter` or not a keyword of ``build``, more
        than one parameter that ``selects``, or a flag another model declares with another
        type or number of values.
    """
    if not isinstance(model, SurfaceModel):
        raise ValueError(f"model must be a SurfaceModel; got {type(model).__name__}")
    name = model.name
    if not isinstance(name, str) or not name or not set(name) <= _MODEL_NAME_CHARS \
            or name.startswith("-"):
        raise ValueError(f"a surface model name must be lower-case letters, digits and '-' "
                         f"(a command-line choice); got name = {name!r}")
    old = SURFACE_MODELS.get(name)
    if old is not None and _origin(old.build) != _origin(model.build):
        raise ValueError(f"surface model {name!r} is registered already (built by "
                         f"{_origin(old.build)}); choose another name")
    if not isinstance(model.parameters, dict):
        raise ValueError(f"parameters of surface model {name!r} must be a dict of name to "
                         f"Parameter; got {type(model.parameters).__name__}")
    try:
        sig = inspect.signature(model.build)
        takes = None if any(p.kind is inspect.Parameter.VAR_KEYWORD
                            for p in sig.parameters.values()) else set(sig.parameters)
    except (TypeError, ValueError):
        takes = None
    for key, p in model.parameters.items():
        if not isinstance(p, Parameter):
            raise ValueError(f"parameter {key!r} of surface model {name!r} must be a Parameter; "
                             f"got {p!r}")
        if not isinstance(key, str) or not key.isidentifier():
            raise ValueError(f"parameter names of surface model {name!r} must be identifiers "
                             f"(keyword arguments); got {key!r}")
        if takes is not None and key not in takes:
            raise ValueError(f"parameter {key!r} of surface model {name!r} is not a keyword "
                             f"argument of its build {_origin(model.build)}")
        flag = p.flag_for(key)
        for other in SURFACE_MODELS.values():
            if other.name == name:
                continue
            for okey, op in other.parameters.items():
                if op.flag_for(okey) == flag and (op.type, op.nargs) != (p.type, p.nargs):
                    raise ValueError(
                        f"flag {flag} of surface model {name!r} (parameter {key!r}) is "
                        f"declared by model {other.name!r} with type {op.type.__name__}, "
                        f"nargs {op.nargs!r}; got type {p.type.__name__}, nargs {p.nargs!r}")
    if sum(p.selects for p in model.parameters.values()) > 1:
        raise ValueError(f"surface model {name!r} may have one parameter that selects it; got "
                         f"{', '.join(k for k, p in model.parameters.items() if p.selects)}")
    SURFACE_MODELS[name] = model
    return model


def _origin(build) -> str:
    inner = getattr(build, "__func__", build)
    return f"{getattr(inner, '__module__', '?')}.{getattr(inner, '__qualname__', repr(inner))}"



class RmsValue(float):
    """A float that may also be called: ``s.h_rms`` and ``s.h_rms()`` are the same number.

    :attr:`Surface.h_rms` and :attr:`Surface.slope_rms` return it, so that the attribute form
    (as the constructor's ``h_rms=``) and the call form of earlier versions both work.
    Arithmetic on it gives plain floats; calling it returns a plain float.
    """

    __slots__ = ()

    def __call__(self) -> float:
        return float(self)


class Surface(abc.ABC):
    """Isotropic rough surface described by its power spectrum C(q), zero outside [q0, q1].

    Subclasses provide C(q) inside the band and the exact partial moments
    :math:`\\int_a^b q^k C(q) dq`; everything else (rms height and slope, the diffusion time
    G(q), the full-contact elastic energy) is derived here from those moments. Constructors
    refuse parameters whose full-band moments are not finite in float64, naming them.

    ``h_rms`` and ``slope_rms`` are properties whose value (a :class:`RmsValue`) is a float
    that may also be called: ``s.h_rms * 1e9`` and ``s.h_rms()`` both work.

    A subclass declares its parameters once, for the command line and
    :func:`persson_fast.scan`: ``MODEL`` (its name there), ``PARAMETERS`` (name ->
    :class:`Parameter`, the constructor's keyword arguments) and optionally ``MODEL_TITLE`` and
    ``MODEL_DESCRIPTION`` (its group in the command line's help). Setting ``MODEL`` registers it
    in :data:`SURFACE_MODELS` when the class is created.

    Attributes
    ----------
    q0 : float
        Long-wavelength cut-off, 2π/L with L the diameter of the nominal contact. [1/m]
    q1 : float
        Short-wavelength cut-off. [1/m]
    """

    q0: float
    q1: float

    #: the declared parameters (name -> Parameter), for the command line and scan
    PARAMETERS: dict = {}

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        name = cls.__dict__.get("MODEL")
        if name is not None:
            register_surface_model(SurfaceModel(
                name=name, parameters=dict(cls.PARAMETERS), build=cls,
                title=cls.__dict__.get("MODEL_TITLE") or f"{name} surface",
                description=cls.__dict__.get("MODEL_DESCRIPTION")))

    # --- values derived once per instance ----------------------------------------------------
    def __setattr__(self, name, value):
        # a parameter set after construction drops what was derived from the old ones
        self.__dict__.pop("_memo", None)
        object.__setattr__(self, name, value)

    def __getstate__(self):
        state = self.__dict__.copy()
        state.pop("_memo", None)          # derived values are not part of the surface
        return state

    def _memoized(self, key, compute):
        """``compute()`` the first time ``key`` is asked for, the kept value after that.

        For values the entry points derive from the surface alone on every call (the default
        magnification grid, G(zeta) on it for one e_star). Setting an attribute forgets them
        all; the parameters are not meant to be changed in place (as a ``TabulatedPSD``
        table's derived segment data would not follow either). The kept value is shared:
        callers hand out copies of arrays.
        """
        memo = self.__dict__.get("_memo")
        if memo is None:
            memo = self.__dict__["_memo"] = {}
        try:
            return memo[key]
        except KeyError:
            value = memo[key] = compute()
            return value

    # --- what a subclass supplies ------------------------------------------------------------
    @abc.abstractmethod
    def _psd_inside(self, q: np.ndarray) -> np.ndarray:
        """C(q) for q0 <= q <= q1 (1-D float64 array in, same shape out)."""

    @abc.abstractmethod
    def _integral(self, k: int, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """∫_a^b q^k C dq for 1-D arrays with q0 <= a < b <= q1."""

    @abc.abstractmethod
    def _repr_params(self) -> dict:
        """Constructor parameters shown by ``repr``."""

    def _require_finite_spectrum(self, given: dict, derived: str = "") -> None:
        """Refuse constructor arguments whose spectrum overflows float64.

        ``given`` maps the arguments to blame to how they are shown ("h_rms = 1.0 [m]");
        ``derived`` names a derived
        quantity already found non-finite (e.g. "C0 = inf [m^4]"). Otherwise every full-band
        moment int q^k C dq (k = 0..3) must be finite: G(q), U_el and h_rms are built on them.
        """
        if not derived:
            for k in _MOMENT_ORDERS:
                with np.errstate(all="ignore"):
                    m = self.moment(k)
                if not math.isfinite(m):
                    derived = f"int q^{k} C dq over [q0, q1] = {m!r} [m^{3 - k}]"
                    break
        if derived:
            names = ", ".join(given)
            got = ", ".join(given.values())
            verb = "gives" if len(given) == 1 else "give"
            raise ValueError(
                f"{names} must give a spectrum whose moments int q^k C dq over [q0, q1] "
                f"(k = 0..3) are finite in float64; got {got}, which {verb} {derived}")

    # --- public interface --------------------------------------------------------------------
    def psd(self, q):
        """Power spectral density C(q).

        Parameters
        ----------
        q : array_like
            Wavevector magnitude, >= 0. [1/m]

        Returns
        -------
        float or numpy.ndarray
            C(q), zero outside [q0, q1]; a float for scalar input. [m^4]
        """
        arr = as_float_array(q, "q", "1/m")
        check_nonnegative(arr, "q", "1/m")
        flat = arr.reshape(-1)
        out = np.zeros_like(flat)
        inside = (flat >= self.q0) & (flat <= self.q1)
        if np.any(inside):
            out[inside] = self._psd_inside(flat[inside])
        out = out.reshape(arr.shape)
        return float(out) if arr.ndim == 0 else out

    def moment(self, k, q_lo=None, q_hi=None):
        """Partial spectral moment :math:`\\int_{q_{lo}}^{q_{hi}} q^k C(q) dq`.

        Parameters
        ----------
        k : {0, 1, 2, 3}
            Power of q in the integrand. [-]
        q_lo, q_hi : array_like, optional
            Integration limits (default q0 and q1); clipped to [q0, q1]; broadcast against
            each other. [1/m]

        Returns
        -------
        float or numpy.ndarray
            The moment, 0 where q_hi <= q_lo; a float when both limits are scalars.
            [m^(3-k)]

        Notes
        -----
        Exact in closed form for every model and order except :class:`CapillaryWaves` with
        gravity at k = 0, 2 (and k = 3 in the unphysical case of nearly coincident or complex
        roots of ρg + γu + κu², u = q²), where composite Gauss-Legendre quadrature in ln q is
        used; its relative error is below 1e-13. Every closed form is written as a sum of
        positive terms, so narrow intervals keep full relative accuracy.
        """
        k = _check_order(k)
        lo = self.q0 if q_lo is None else q_lo
        hi = self.q1 if q_hi is None else q_hi
        lo = as_float_array(lo, "q_lo", "1/m")
        hi = as_float_array(hi, "q_hi", "1/m")
        check_finite(lo, "q_lo", "1/m")
        check_finite(hi, "q_hi", "1/m")
        lo_b, hi_b = np.broadcast_arrays(lo, hi)
        shape = lo_b.shape
        a = np.clip(lo_b.reshape(-1), self.q0, self.q1)
        b = np.clip(hi_b.reshape(-1), self.q0, self.q1)
        out = np.zeros(a.shape, dtype=np.float64)
        mask = b > a
        if np.any(mask):
            out[mask] = self._integral(k, a[mask], b[mask])
        out = out.reshape(shape)
        return float(out) if out.ndim == 0 else out

    @property
    def h_rms(self) -> RmsValue:
        """Root-mean-square height, :math:`(2\\pi \\int q C dq)^{1/2}`. [m]

        A float (``s.h_rms * 1e9``, ``f"{s.h_rms:.3g}"``) that may also be called:
        ``s.h_rms()`` returns the same value as a plain float (see :class:`RmsValue`).
        """
        return RmsValue(math.sqrt(2.0 * math.pi * self.moment(1)))

    @property
    def slope_rms(self) -> RmsValue:
        """Root-mean-square slope, :math:`(2\\pi \\int q^3 C dq)^{1/2}`. [-]

        A float that may also be called: ``s.slope_rms()`` returns the same value (see
        :class:`RmsValue`).
        """
        return RmsValue(math.sqrt(2.0 * math.pi * self.moment(3)))

    def diffusion_time(self, q, e_star):
        """Diffusion time G(q) of the stress distribution.

        Parameters
        ----------
        q : array_like
            Wavevector magnitude ζ q0, >= 0. [1/m]
        e_star : float
            Effective modulus E/(1-ν²), > 0. [Pa]

        Returns
        -------
        float or numpy.ndarray
            :math:`G(q) = (\\pi/4) E^{*2} \\int_{q_0}^{q} q'^3 C(q') dq'`; 0 for q <= q0 and
            G1 = G(q1) for q >= q1. [Pa^2]

        Notes
        -----
        Integral of the diffusion coefficient of seed Eq. 5 over the magnification,
        :math:`G(\\zeta) = \\int_1^\\zeta D d\\zeta'`; the stress distribution then obeys the heat
        equation ∂P/∂G = ∂²P/∂σ² (Persson, J. Chem. Phys. 115, 3840 (2001)). For the full band
        √G1 = E* slope_rms/(2√2).
        """
        e = check_e_star(e_star)
        arr = as_float_array(q, "q", "1/m")
        check_nonnegative(arr, "q", "1/m")
        with np.errstate(over="ignore", invalid="ignore"):
            out = (0.25 * math.pi * e * e) * np.asarray(self.moment(3, self.q0, arr))
        if not np.all(np.isfinite(out)):
            self._refuse_e_star(e, "G(q1)", "(pi/4) e_star^2 int q^3 C dq",
                                (0.25 * math.pi * e * e) * self.moment(3), "Pa^2")
        return float(out) if arr.ndim == 0 else out

    def _refuse_e_star(self, e: float, name: str, formula: str, value: float, unit: str) -> None:
        """Raise the ValueError of an e_star that makes a scene quantity overflow float64."""
        raise ValueError(
            f"e_star must keep {name} = {formula} finite [Pa]; got e_star = {e!r}, which gives "
            f"{name} = {value!r} [{unit}] for this surface (slope_rms = {float(self.slope_rms)!r} [-], "
            f"h_rms = {float(self.h_rms)!r} [m]); e_star is in Pa (E* = 1 GPa is 1e9)")

    def to_csv(self, path, *, points_per_decade=20) -> str:
        """Write C(q) to a CSV file that :meth:`TabulatedPSD.from_file` reads back.

        Parameters
        ----------
        path : str or os.PathLike
            The file; replaced if it exists. It is written to a temporary file in the same
            folder and renamed onto ``path`` when complete, so an error leaves no partial file.
        points_per_decade : int, optional
            Log-spaced points per decade of q for analytic models (default 20), plus the
            model's breakpoints and the band ends; a :class:`TabulatedPSD` writes its own nodes
            inside [q0, q1] and the band ends. [-]

        Returns
        -------
        str
            ``path``.

        Notes
        -----
        Comment lines give the surface's repr and the grid; the header is ``q [1/m],C [m^4]``;
        numbers are written with ``repr`` (they read back bit for bit).
        """
        from .topography import write_spectrum_csv

        return write_spectrum_csv(self, path, points_per_decade=points_per_decade)

    def elastic_energy_full_contact(self, e_star) -> float:
        """Elastic energy per nominal area stored at full contact. [J/m^2]

        Parameters
        ----------
        e_star : float
            Effective modulus E/(1-ν²), > 0. [Pa]

        Returns
        -------
        float
            :math:`U_{el}/A_0 = (\\pi E^*/2) \\int_{q_0}^{q_1} q^2 C(q) dq`. [J/m^2]

        Notes
        -----
        Persson, Eur. Phys. J. E 8, 385 (2002); Persson et al., J. Phys.: Condens. Matter 17,
        R1 (2005). It is U_el(ζ = 1) with P = S = 1.
        """
        e = check_e_star(e_star)
        with np.errstate(over="ignore"):
            out = 0.5 * math.pi * e * self.moment(2)
        if not math.isfinite(out):
            self._refuse_e_star(e, "U_el/A0", "(pi e_star/2) int q^2 C dq", out, "J/m^2")
        return out

    def breakpoints(self) -> np.ndarray:
        """Sorted wavevectors in [q0, q1] where C(q) is not smooth (q0 and q1 included). [1/m]"""
        return np.array([self.q0, self.q1], dtype=np.float64)

    def __repr__(self) -> str:
        args = ", ".join(f"{key}={value!r}" for key, value in self._repr_params().items())
        return f"{type(self).__name__}({args})"


# ----------------------------------------------------------------------------------------------
# frozen capillary waves (seed Eq. 1)
# ----------------------------------------------------------------------------------------------
class CapillaryWaves(Surface):
    """Roughness of frozen capillary waves (seed paper Eq. 1).

    Parameters
    ----------
    temperature : float
        Temperature at which the waves freeze (the glass transition T_g), > 0. [K]
    surface_tension : float
        Surface tension γ of the melt, > 0. [J/m^2]
    q_c : float
        Cross-over wavevector q_c = (γ/κ)^{1/2}, > 0; sets the bending stiffness. [1/m]
    q0, q1 : float
        Band limits, 0 < q0 < q1, finite. [1/m]
    density : float, optional
        Mass density ρ of the melt, >= 0; 0 (default) neglects gravity. [kg/m^3]
    gravity : float, optional
        Gravitational acceleration g, >= 0 (default 9.81). [m/s^2]

    Attributes
    ----------
    bending_stiffness : float
        κ = γ/q_c². [J]

    Notes
    -----
    The spectrum is (B.N.J. Persson, "Influence of frozen capillary waves on contact mechanics",
    arXiv:cond-mat/0512604, Eq. 1; also Surf. Sci. Rep. 61, 201 (2006) §2.2)

    .. math:: C(q) = \\frac{1}{(2\\pi)^2} \\frac{k_B T}{\\rho g + \\gamma q^2 + \\kappa q^4}.

    Write A = k_B T/(2π)². Without gravity (ρg = 0), for q0 <= a < b <= q1 and w = q_c(b-a)/(ab+q_c²):

    .. math::

        \\int_a^b C dq &= \\frac{A}{\\kappa}\\frac{b-a}{ab(ab+q_c^2)}
                          + \\frac{A}{\\gamma q_c}(w - \\arctan w) \\\\
        \\int_a^b q C dq &= \\frac{A}{2\\gamma}
                  \\ln\\left[1 + \\frac{q_c^2 (b^2-a^2)}{a^2 (b^2+q_c^2)}\\right] \\\\
        \\int_a^b q^2 C dq &= \\frac{A}{\\kappa q_c} \\arctan\\frac{q_c (b-a)}{q_c^2 + ab} \\\\
        \\int_a^b q^3 C dq &= \\frac{A}{2\\kappa} \\ln\\left[1 + \\frac{b^2-a^2}{q_c^2+a^2}\\right]

    (partial fractions of 1/(q²(γ+κq²)) and the arctan/log addition theorems, arranged as sums
    of positive terms). With a = q0, b = q1 the second line is Eq. 2,
    h_rms² = (k_B T/2πγ) ln[(q1/q0)((q0²+q_c²)/(q1²+q_c²))^{1/2}], and the last gives
    G(q) = (E*² k_B T/(32πκ)) ln[(γ+κq²)/(γ+κq0²)] (from Eq. 6).

    With gravity, u = q² turns the k = 1, 3 moments into ½∫du/P and ½∫u du/P with
    P(u) = κu² + γu + ρg = κ(u+p)(u+s), Δ = γ² - 4κρg, s = (γ+√Δ)/(2κ), p = 2ρg/(γ+√Δ)
    (the cancellation-free small root). For Δ >= 0, with δ = u_b - u_a,

    .. math:: \\int \\frac{du}{P} = \\frac{\\delta}{\\kappa (u_a+p)(u_b+s)}
              \\frac{\\ln(1+x)}{x}, \\qquad x = \\frac{\\delta (s-p)}{(u_a+p)(u_b+s)},

    and for Δ < 0 (m = γ/2κ, n = √-Δ/2κ) the same with arctan(y)/y,
    y = nδ/(n² + (u_a+m)(u_b+m)), in place of ln(1+x)/x. For k = 3 and s >= 3p,

    .. math:: \\int \\frac{u\\,du}{P} = \\frac{g(p) - g(s)}{\\kappa (s-p)},\\quad
              g(t) = \\int \\frac{u\\,du}{u+t} = \\frac{\\delta u_a}{u_a+t}
              + t\\,\\psi\\!\\left(\\frac{\\delta}{u_a+t}\\right),\\ \\psi(x) = x - \\ln(1+x)

    on u <= s, and :math:`\\frac{1}{2\\kappa}[\\ln(P(u_b)/P(u_a)) - \\gamma\\int du/P]` on u >= s;
    each loses at most a factor 3 to cancellation. The k = 0, 2 moments with gravity (and k = 3
    when s < 3p, which needs q_c² < 16ρg/3γ, far outside physical ranges) use 20-point
    Gauss-Legendre panels of unit width in ln q: the poles of C lie at least π/4 off the real
    ln q axis, which gives a relative error below 1e-13.
    """

    MODEL = "capillary"
    MODEL_TITLE = "capillary-wave surface"
    PARAMETERS = {
        "temperature": Parameter("K", "temperature", required=True, metavar="T"),
        "surface_tension": Parameter("J/m^2", "surface tension", required=True, metavar="GAMMA"),
        "q_c": Parameter("1/m", "crossover wavevector", required=True, metavar="QC"),
        **band_parameters(),
        "density": Parameter("kg/m^3", "mass density", metavar="RHO"),
        "gravity": Parameter("m/s^2", "gravity", metavar="G"),
    }

    def __init__(self, temperature, surface_tension, q_c, q0, q1, density=0.0, gravity=9.81):
        self.temperature = _positive_scalar(temperature, "temperature", "K")
        self.surface_tension = _positive_scalar(surface_tension, "surface_tension", "J/m^2")
        self.q_c = _positive_scalar(q_c, "q_c", "1/m")
        self.q0 = _positive_scalar(q0, "q0", "1/m")
        self.q1 = _positive_scalar(q1, "q1", "1/m")
        _check_band(self.q0, self.q1)
        self.density = _nonnegative_scalar(density, "density", "kg/m^3")
        self.gravity = _nonnegative_scalar(gravity, "gravity", "m/s^2")
        self.bending_stiffness = self.surface_tension / (self.q_c * self.q_c)
        # C = A/(rho g + gamma q^2 + kappa q^4) with A = k_B T/(2 pi)^2 [J]
        self._amp = BOLTZMANN * self.temperature / (4.0 * math.pi * math.pi)
        self._rho_g = self.density * self.gravity
        if self._rho_g > 0.0:
            gam, kap, c = self.surface_tension, self.bending_stiffness, self._rho_g
            disc = gam * gam - 4.0 * kap * c
            self._disc = disc
            if disc >= 0.0:
                root = math.sqrt(disc)
                self._s = (gam + root) / (2.0 * kap)
                self._p = 2.0 * c / (gam + root)
            else:
                self._m = gam / (2.0 * kap)
                self._n = math.sqrt(-disc) / (2.0 * kap)
        self._require_finite_spectrum({
            "temperature": f"temperature = {self.temperature!r} [K]",
            "surface_tension": f"surface_tension = {self.surface_tension!r} [J/m^2]",
            "q_c": f"q_c = {self.q_c!r} [1/m]",
        })

    def _repr_params(self) -> dict:
        return {
            "temperature": self.temperature,
            "surface_tension": self.surface_tension,
            "q_c": self.q_c,
            "q0": self.q0,
            "q1": self.q1,
            "density": self.density,
            "gravity": self.gravity,
        }

    def _psd_inside(self, q):
        q2 = q * q
        return self._amp / (self._rho_g + q2 * (self.surface_tension + self.bending_stiffness * q2))

    # --- moments -------------------------------------------------------------------------------
    def _integral(self, k, a, b):
        if self._rho_g == 0.0:
            return self._integral_no_gravity(k, a, b)
        # u = q^2; u_b - u_a = (b - a)(b + a) keeps narrow intervals exact
        if k == 1:
            return 0.5 * self._amp * self._inv_quadratic(a * a, b * b, (b - a) * (b + a))
        if k == 3 and self._disc >= 0.0 and self._s >= 3.0 * self._p:
            return 0.5 * self._amp * self._u_over_quadratic(a * a, b * b, (b - a) * (b + a))
        return _gauss_legendre_log(lambda q: q ** (k + 1) * self._psd_inside(q), a, b)

    def _integral_no_gravity(self, k, a, b):
        amp, gam, kap, qc = self._amp, self.surface_tension, self.bending_stiffness, self.q_c
        qc2 = qc * qc
        diff = b - a
        if k == 0:
            ab = a * b
            w = qc * diff / (ab + qc2)
            return (amp / kap) * diff / (ab * (ab + qc2)) + (amp / (gam * qc)) * _x_minus_atan(w)
        if k == 1:
            return (0.5 * amp / gam) * np.log1p(qc2 * diff * (b + a) / (a * a * (b * b + qc2)))
        if k == 2:
            return (amp / (kap * qc)) * np.arctan(qc * diff / (qc2 + a * b))
        return (0.5 * amp / kap) * np.log1p(diff * (b + a) / (qc2 + a * a))

    def _inv_quadratic(self, ua, ub, delta):
        """∫_{ua}^{ub} du/(κu² + γu + ρg), exact for every sign of the discriminant.

        ``delta`` is ub - ua, passed in so that the caller can compute it without cancellation.
        """
        kap = self.bending_stiffness
        if self._disc >= 0.0:
            p, s = self._p, self._s
            den = (ua + p) * (ub + s)
            return delta / (kap * den) * _log1p_ratio(delta * (s - p) / den)
        m, n = self._m, self._n
        den = n * n + (ua + m) * (ub + m)
        return delta / (kap * den) * _atan_ratio(n * delta / den)

    def _u_over_quadratic(self, ua, ub, delta):
        """∫_{ua}^{ub} u du/(κu² + γu + ρg) for real roots with s >= 3p (see class Notes).

        ``delta`` is ub - ua, computed by the caller without cancellation.
        """
        kap, gam, p, s = self.bending_stiffness, self.surface_tension, self._p, self._s
        out = np.zeros_like(ua)
        # part below s: divided difference of g(t) = ∫ u/(u+t) du
        lo_hi = np.minimum(ub, s)
        m1 = lo_hi > ua
        if np.any(m1):
            x0 = ua[m1]
            d = np.where(ub[m1] <= s, delta[m1], s - x0)

            def g(t):
                return d * x0 / (x0 + t) + t * _x_minus_log1p(d / (x0 + t))

            out[m1] += (g(p) - g(s)) / (kap * (s - p))
        # part above s: (1/2κ)[ln P(ub)/P(ua) - γ ∫ du/P]
        hi_lo = np.maximum(ua, s)
        m2 = ub > hi_lo
        if np.any(m2):
            x0, x1 = hi_lo[m2], ub[m2]
            d = np.where(ua[m2] >= s, delta[m2], x1 - s)
            p_x0 = x0 * (kap * x0 + gam) + self._rho_g
            log_term = np.log1p(d * (kap * (x0 + x1) + gam) / p_x0)
            out[m2] += (log_term - gam * self._inv_quadratic(x0, x1, d)) / (2.0 * kap)
        return out


# ----------------------------------------------------------------------------------------------
# self-affine fractal with roll-off
# ----------------------------------------------------------------------------------------------
class SelfAffine(Surface):
    """Self-affine fractal spectrum with an optional roll-off.

    Parameters
    ----------
    hurst : float
        Hurst exponent H in [0, 1] (fractal dimension D_f = 3 - H). [-]
    q0, q1 : float
        Band limits, 0 < q0 < q1, finite. [1/m]
    q_r : float, optional
        Roll-off wavevector, q0 <= q_r <= q1; None (default) means q_r = q0, no roll-off. [1/m]
    h_rms : float, optional
        Root-mean-square height, > 0. [m]
    slope_rms : float, optional
        Root-mean-square slope, > 0. [-]
    C0 : float, optional
        Plateau value of C, > 0. [m^4]

    Exactly one of ``h_rms``, ``slope_rms`` and ``C0`` must be given; the others follow. It
    must leave C0 and the moments of C finite in float64 (``slope_rms=1e200`` would give
    C0 = inf): otherwise a ValueError names it.

    Attributes
    ----------
    hurst : float
        H. [-]
    q_r : float
        Roll-off wavevector. [1/m]
    C0 : float
        Plateau value C(q0 <= q < q_r). [m^4]

    Notes
    -----
    .. math::

        C(q) = C_0 \\ (q_0 \\le q < q_r), \\qquad
        C(q) = C_0 (q/q_r)^{-2(1+H)} \\ (q_r \\le q \\le q_1)

    (Persson et al., J. Phys.: Condens. Matter 17, R1 (2005)). Every moment is a sum of power-law
    integrals, evaluated exactly as

    .. math:: \\int_a^b c (q/q_r)^{e} dq = c\\, q_r\\, t_a^{\\sigma} L \\frac{e^{\\sigma L} - 1}{\\sigma L},
              \\quad \\sigma = e + 1,\\ t_a = a/q_r,\\ L = \\ln(b/a),

    with (e^x - 1)/x from ``expm1``: the logarithmic cases σ = k - 1 - 2H = 0 (k=1, H=0; k=2,
    H=½; k=3, H=1) come out exactly and σ near 0 keeps full precision. The normalisations are
    C0 = h_rms²/(2π m1) and C0 = slope_rms²/(2π m3), m_k being the k-th moment at C0 = 1.
    """

    MODEL = "self-affine"
    PARAMETERS = {
        "hurst": Parameter("-", "Hurst exponent", required=True, metavar="H"),
        **band_parameters(),
        "q_r": Parameter("1/m", "roll-off wavevector", metavar="QR"),
        "h_rms": Parameter("m", "rms height", metavar="HRMS"),
        "slope_rms": Parameter("-", "rms slope", metavar="S"),
        "C0": Parameter("m^4", "plateau of the spectrum"),
    }

    def __init__(self, hurst, q0, q1, q_r=None, h_rms=None, slope_rms=None, C0=None):
        self.hurst = _check_hurst(hurst)
        self.q0 = _positive_scalar(q0, "q0", "1/m")
        self.q1 = _positive_scalar(q1, "q1", "1/m")
        _check_band(self.q0, self.q1)
        if q_r is None:
            self.q_r = self.q0
        else:
            self.q_r = _positive_scalar(q_r, "q_r", "1/m")
            if not self.q0 <= self.q_r <= self.q1:
                raise ValueError(
                    f"q_r must lie in [q0, q1] [1/m]; got q_r = {self.q_r!r}, "
                    f"q0 = {self.q0!r}, q1 = {self.q1!r}"
                )
        given = {"h_rms": h_rms, "slope_rms": slope_rms, "C0": C0}
        chosen = [name for name, value in given.items() if value is not None]
        if len(chosen) != 1:
            got = ", ".join(f"{name} = {given[name]!r}" for name in chosen) or "none"
            raise ValueError(
                "exactly one of h_rms [m], slope_rms [-], C0 [m^4] must be given; got " + got
            )
        self.C0 = 1.0
        if C0 is not None:
            self.C0 = _positive_scalar(C0, "C0", "m^4")
            given = {"C0": f"C0 = {self.C0!r} [m^4]"}
        elif h_rms is not None:
            h = _positive_scalar(h_rms, "h_rms", "m")
            with np.errstate(all="ignore"):
                self.C0 = h * h / (2.0 * math.pi * self.moment(1))
            given = {"h_rms": f"h_rms = {h!r} [m]"}
        else:
            g = _positive_scalar(slope_rms, "slope_rms", "-")
            with np.errstate(all="ignore"):
                self.C0 = g * g / (2.0 * math.pi * self.moment(3))
            given = {"slope_rms": f"slope_rms = {g!r} [-]"}
        finite_c0 = math.isfinite(self.C0)
        self._require_finite_spectrum(given, "" if finite_c0 else f"C0 = {self.C0!r} [m^4]")

    def _repr_params(self) -> dict:
        return {"hurst": self.hurst, "q0": self.q0, "q1": self.q1, "q_r": self.q_r, "C0": self.C0}

    def _psd_inside(self, q):
        out = np.full_like(q, self.C0)
        tail = q >= self.q_r
        out[tail] = self.C0 * np.exp(-2.0 * (1.0 + self.hurst) * np.log(q[tail] / self.q_r))
        return out

    def _integral(self, k, a, b):
        out = np.zeros_like(a)
        qr = self.q_r
        # plateau [q0, q_r): C0 q^k = C0 qr^k (q/qr)^k
        lo, hi = a, np.minimum(b, qr)
        m = hi > lo
        if np.any(m):
            out[m] += _power_law_integral(self.C0 * qr**k, qr, float(k), lo[m], hi[m])
        # power-law tail [q_r, q1]
        lo, hi = np.maximum(a, qr), b
        m = hi > lo
        if np.any(m):
            expo = k - 2.0 * (1.0 + self.hurst)
            out[m] += _power_law_integral(self.C0 * qr**k, qr, expo, lo[m], hi[m])
        return out

    def breakpoints(self) -> np.ndarray:
        return np.unique(np.array([self.q0, self.q_r, self.q1], dtype=np.float64))


# ----------------------------------------------------------------------------------------------
# tabulated (measured) spectrum
# ----------------------------------------------------------------------------------------------
class TabulatedPSD(Surface):
    """Measured isotropic spectrum, interpolated log-log between its nodes.

    Parameters
    ----------
    q : array_like
        Node wavevectors, 1-D, strictly increasing, positive and finite, at least 2. [1/m]
    C : array_like
        C at the nodes, same length, >= 0 and finite. [m^4]
    q0, q1 : float, optional
        Band limits inside [q[0], q[-1]], q0 < q1; default the ends of the table. [1/m]

    Attributes
    ----------
    q_table, C_table : numpy.ndarray
        The nodes as given (the whole table, also when q0/q1 restrict it). [1/m], [m^4]

    Notes
    -----
    Between nodes j and j+1 with C_j, C_{j+1} > 0 the spectrum is the power law
    C = C_j (q/q_j)^{α_j}, α_j = ln(C_{j+1}/C_j)/ln(q_{j+1}/q_j), so every moment is a sum of
    exact power-law integrals (see :class:`SelfAffine`; the logarithmic case k + α_j = -1 is exact).
    **Zero bands:** a segment with C = 0 at either end is taken as C = 0 on the whole segment
    (log-log interpolation towards 0 is undefined); at a node C is the tabulated value. C is 0
    outside [q0, q1]. Sums over many full segments use a table of block sums (powers of two), so
    a partial moment is a sum of at most ~2 log2(n) positive terms and keeps full relative
    accuracy even far out in a decaying tail.
    """

    def __init__(self, q, C, q0=None, q1=None):
        qa = as_float_array(q, "q", "1/m", ndim=(1,))
        ca = as_float_array(C, "C", "m^4", ndim=(1,))
        check_positive(qa, "q", "1/m")
        check_nonnegative(ca, "C", "m^4")
        if qa.size != ca.size:
            raise ValueError(
                f"q and C must have the same length [-]; got len(q) = {qa.size}, len(C) = {ca.size}"
            )
        if qa.size < 2:
            raise ValueError(f"q must hold at least 2 nodes [1/m]; got len(q) = {qa.size}")
        steps = np.diff(qa)
        if np.any(steps <= 0):
            i = int(np.argmax(steps <= 0))
            raise ValueError(
                f"q must be strictly increasing [1/m]; got q[{i}] = {float(qa[i])!r} "
                f">= q[{i + 1}] = {float(qa[i + 1])!r}"
            )
        self.q_table = qa.copy()
        self.C_table = ca.copy()
        lo_end, hi_end = float(qa[0]), float(qa[-1])
        self.q0 = lo_end if q0 is None else _positive_scalar(q0, "q0", "1/m")
        self.q1 = hi_end if q1 is None else _positive_scalar(q1, "q1", "1/m")
        for name, val in (("q0", self.q0), ("q1", self.q1)):
            if not lo_end <= val <= hi_end:
                raise ValueError(
                    f"{name} must lie inside the table [q[0], q[-1]] = [{lo_end!r}, {hi_end!r}] [1/m]; "
                    f"got {name} = {val!r}"
                )
        _check_band(self.q0, self.q1)
        positive = (ca[:-1] > 0) & (ca[1:] > 0)
        self._active = positive
        self._coef = np.where(positive, ca[:-1], 0.0)
        with np.errstate(divide="ignore", invalid="ignore"):
            alpha = np.log(ca[1:] / ca[:-1]) / np.log(qa[1:] / qa[:-1])
        self._alpha = np.where(positive, alpha, 0.0)
        self._block_sums = {}
        self._require_finite_spectrum({"q": f"max(q) = {float(qa.max())!r} [1/m]",
                                       "C": f"max(C) = {float(ca.max())!r} [m^4]"})

    @classmethod
    def from_line_scan(cls, q, C1d, hurst, q0=None, q1=None):
        """Isotropic 2-D spectrum from a 1-D (line-scan) spectrum.

        Parameters
        ----------
        q : array_like
            Node wavevectors of the line scan, strictly increasing, > 0. [1/m]
        C1d : array_like
            1-D spectrum at the nodes, >= 0. [m^3]
        hurst : float
            Hurst exponent H in [0, 1] of the power law the conversion assumes. [-]
        q0, q1 : float, optional
            Band limits, as for :class:`TabulatedPSD`. [1/m]

        Returns
        -------
        TabulatedPSD
            Nodes q with C(q) = C_1D(q) Γ(1+H)/(√π Γ(H+½) q).

        Notes
        -----
        Convention: :math:`C_{1D}(q) = (2\\pi)^{-1}\\int dx \\langle h(x)h(0)\\rangle e^{-iqx}`,
        defined for q of both signs, so :math:`h_{rms}^2 = \\int_{-\\infty}^{\\infty} C_{1D} dq =
        2\\int_0^\\infty C_{1D} dq`, and :math:`C_{1D}(q_x) = \\int dq_y\\, C(\\sqrt{q_x^2+q_y^2})`.
        For an isotropic power law C = K q^{-2(1+H)} this integral is
        K q^{-(1+2H)} √π Γ(H+½)/Γ(1+H), hence the factor above (C_1D/(2q) at H = ½, C_1D/(πq) at
        H = 0). Persson, Tribol. Lett. 54, 99 (2014). Spectra normalised per one-sided q
        (h_rms² = ∫_0^∞ C dq) must be halved first; spectra in cycles per length (f = q/2π)
        must be converted to angular q first.
        """
        h = _check_hurst(hurst)
        qa = as_float_array(q, "q", "1/m", ndim=(1,))
        c1 = as_float_array(C1d, "C1d", "m^3", ndim=(1,))
        check_positive(qa, "q", "1/m")
        check_nonnegative(c1, "C1d", "m^3")
        if qa.size != c1.size:
            raise ValueError(
                f"q and C1d must have the same length [-]; got len(q) = {qa.size}, len(C1d) = {c1.size}"
            )
        factor = math.gamma(1.0 + h) / (math.sqrt(math.pi) * math.gamma(h + 0.5))
        return cls(qa, c1 * factor / qa, q0=q0, q1=q1)

    @classmethod
    def from_heights(cls, heights, pixel_size, *, q0=None, q1=None, bins_per_decade=10,
                     window=None, periodic=False, detrend=None, line_scans=None, hurst=None):
        """Isotropic spectrum of a height map or of line scans given as a numpy array.

        Parameters
        ----------
        heights : array_like
            Heights on a uniform grid, all defined (no NaN): 1-D (one line scan), 2-D (a map,
            rows along y), or 2-D with ``line_scans=True`` (parallel line scans, one per row,
            whose 1-D spectra are averaged). [m]
        pixel_size : float or sequence of float
            Grid spacing: one value, or (Δy, Δx) for a map. [m]
        q0 : float, optional
            Lower band limit, >= 2π/L (L the longer side of the scan); default 2π/L. [1/m]
        q1 : float, optional
            Upper band limit, <= π/Δx (Nyquist); default π/Δx, the reliability cut-off
            ``info['q_reliable']`` of a topography that knows a better one. [1/m]
        bins_per_decade : int, optional
            Logarithmic bins per decade of q in which the raw spectrum is averaged (default
            10). [-]
        window : {'hann', 'none'}, optional
            Window against the leakage of non-periodic data; default 'none' for periodic data,
            'hann' otherwise (normalised to a mean square of 1). [-]
        periodic : bool, optional
            Whether the data are periodic (synthetic surfaces); default False. [-]
        detrend : {'mean', 'plane'}, optional
            What is removed first: default the mean for periodic data, the least-squares plane
            (line, for line scans) otherwise. [-]
        line_scans : bool, optional
            Treat 2-D heights as line scans; default False (1-D heights are always one). [-]
        hurst : float, optional
            H of the 1-D to 2-D conversion of line scans; default fitted to the 1-D spectrum
            over the band (``info['hurst']``). [-]

        Returns
        -------
        TabulatedPSD
            With ``info``: a dict holding the band limits of the data (``q_lowest`` = 2π/L,
            ``q_nyquist``, ``q_reliable``), the bins, the window, the data's own rms height
            (``h_rms_data``) and, for line scans, ``hurst``, ``line_factor`` and the 1-D table
            ``psd_1d``. [SI]

        Notes
        -----
        Persson's C(q) = |h~(q)|²/((2π)² A) for each Fourier mode of a map (h~ = Δx Δy Σ h
        e^{-iq·x}, A the scan area), averaged in log bins so that every bin keeps the power
        of its modes: with the default band h_rms is the data's own rms height. Line scans:
        C_1D = |h~|²/(2π L), then C = C_1D Γ(1+H)/(√π Γ(H+½) q) (see :meth:`from_line_scan`).
        The module :mod:`persson_fast.topography` gives the derivation and the expected
        errors.
        """
        from .topography import spectrum_from_heights

        q, c, lo, hi, info = spectrum_from_heights(
            heights, pixel_size, q0=q0, q1=q1, bins_per_decade=bins_per_decade, window=window,
            periodic=periodic, detrend=detrend, line_scans=line_scans, hurst=hurst)
        out = cls(q, c, q0=lo, q1=hi)
        out.info = info
        return out

    @classmethod
    def from_topography(cls, topography, *, q0=None, q1=None, bins_per_decade=10,
                        window=None, detrend=None, line_scans=None, hurst=None):
        """Isotropic spectrum of a SurfaceTopography map or uniform line scan.

        Parameters
        ----------
        topography : SurfaceTopography.Topography or SurfaceTopography.UniformLineScan
            Measured (or synthetic) surface with a length unit; every pixel defined. Its
            periodicity sets the default window and detrending, and its short reliability
            cut-off λ_c, where known, the default q1 = 2π/λ_c.
        q0, q1, bins_per_decade, window, detrend, line_scans, hurst
            As for :meth:`from_heights`.

        Returns
        -------
        TabulatedPSD
            As :meth:`from_heights`, ``info`` included.

        Notes
        -----
        Needs the optional extra: ``pip install "persson_fast[topography]"``. The heights are
        converted to m; the spectrum is this package's own (:meth:`from_heights`), equal to
        SurfaceTopography's ``power_spectrum_from_area`` divided by (2π)² mode by mode.
        """
        from .topography import spectrum_from_topography

        q, c, lo, hi, info = spectrum_from_topography(
            topography, q0=q0, q1=q1, bins_per_decade=bins_per_decade, window=window,
            detrend=detrend, line_scans=line_scans, hurst=hurst)
        out = cls(q, c, q0=lo, q1=hi)
        out.info = info
        return out

    @classmethod
    def from_file(cls, path, *, q_unit=None, C_unit=None, q0=None, q1=None):
        """Spectrum from a plain two-column text file (CSV or whitespace-separated).

        Parameters
        ----------
        path : str or os.PathLike
            File with rows ``q, C`` (Persson's isotropic 2-D C); '#' starts a comment; a header
            line may name the units, ``q [1/m], C [m^4]`` (as :meth:`Surface.to_csv` writes).
        q_unit : str, optional
            Unit of q: '1/m', '1/mm', '1/um', '1/nm'; overrides the header. [-]
        C_unit : str, optional
            Unit of C: 'm^4', 'mm^4', 'um^4', 'nm^4'; overrides the header. [-]
        q0, q1 : float, optional
            Band limits inside the table; default its ends. [1/m]

        Returns
        -------
        TabulatedPSD
        """
        from .topography import read_spectrum

        q, c = read_spectrum(path, q_unit=q_unit, C_unit=C_unit)
        out = cls(q, c, q0=q0, q1=q1)
        out.info = {"source": os.fspath(path)}
        return out

    def _repr_params(self) -> dict:
        return {"n_nodes": int(self.q_table.size), "q0": self.q0, "q1": self.q1}

    def __repr__(self) -> str:
        return (
            f"TabulatedPSD(<{self.q_table.size} nodes in [{float(self.q_table[0])!r}, "
            f"{float(self.q_table[-1])!r}]>, "
            f"q0={self.q0!r}, q1={self.q1!r}{self._repr_source()})"
        )

    def _repr_source(self) -> str:
        info = getattr(self, "info", None)
        if not info or "q_reliable" not in info:
            return ""
        return (f", from {info.get('kind', 'data')}: reliable up to "
                f"q={info['q_reliable']!r}, Nyquist {info['q_nyquist']!r}")

    def _psd_inside(self, q):
        qt = self.q_table
        seg = np.clip(np.searchsorted(qt, q, side="right") - 1, 0, qt.size - 2)
        out = self._coef[seg] * np.exp(self._alpha[seg] * np.log(q / qt[seg]))
        # at a node, C is the tabulated value (matters only next to a zero band)
        node = np.clip(np.searchsorted(qt, q, side="left"), 0, qt.size - 1)
        at_node = qt[node] == q
        out[at_node] = self.C_table[node[at_node]]
        return out

    def _segment_integral(self, k, seg, a, b):
        """Exact ∫_a^b q^k C dq with [a, b] inside segment ``seg`` (arrays)."""
        qref = self.q_table[seg]
        coef = self._coef[seg] * qref**k
        return _power_law_integral(coef, qref, self._alpha[seg] + k, a, b)

    def _levels(self, k):
        """Block sums of full-segment moments: level l holds sums over 2**l consecutive segments."""
        if k not in self._block_sums:
            nseg = self.q_table.size - 1
            seg = np.arange(nseg)
            full = np.zeros(nseg)
            act = self._active
            if np.any(act):
                full[act] = self._segment_integral(
                    k, seg[act], self.q_table[:-1][act], self.q_table[1:][act]
                )
            levels = [full]
            while 2 ** len(levels) <= nseg:
                prev = levels[-1]
                half = 2 ** (len(levels) - 1)
                levels.append(prev[: prev.size - half] + prev[half:])
            self._block_sums[k] = levels
        return self._block_sums[k]

    def _range_sum(self, k, j1, j2):
        """Sum of full-segment moments over segments j1 .. j2-1 (arrays), positive terms only."""
        levels = self._levels(k)
        total = np.zeros(j1.shape, dtype=np.float64)
        j = j1.copy()
        for lev in range(len(levels) - 1, -1, -1):
            size = 2**lev
            take = j + size <= j2
            if np.any(take):
                total[take] += levels[lev][j[take]]
                j[take] += size
        return total

    def _integral(self, k, a, b):
        qt = self.q_table
        nseg = qt.size - 1
        ja = np.clip(np.searchsorted(qt, a, side="right") - 1, 0, nseg - 1)
        jb = np.clip(np.searchsorted(qt, b, side="left") - 1, 0, nseg - 1)
        out = np.zeros_like(a)
        same = ja == jb
        if np.any(same):
            out[same] = self._segment_integral(k, ja[same], a[same], b[same])
        diff = ~same
        if np.any(diff):
            ja_d, jb_d = ja[diff], jb[diff]
            head = self._segment_integral(k, ja_d, a[diff], qt[ja_d + 1])
            tail = self._segment_integral(k, jb_d, qt[jb_d], b[diff])
            out[diff] = head + self._range_sum(k, ja_d + 1, jb_d) + tail
        return out

    def breakpoints(self) -> np.ndarray:
        inner = self.q_table[(self.q_table > self.q0) & (self.q_table < self.q1)]
        return np.concatenate(([self.q0], inner, [self.q1]))


# the measured spectra: TabulatedPSD from a height map or line scan, or from a spectrum file
_MEASURED_TITLE = "measured surface"
_MEASURED_TEXT = (
    "a height map or line scan in any format SurfaceTopography reads (needs the extra: "
    "pip install \"persson_fast[topography]\"), or a two-column spectrum file q, C "
    "(Persson's isotropic 2-D C; units from its header 'q [1/m], C [m^4]' or the flags)")


def _surface_from_topography_file(file, q0=None, q1=None, hurst=None, bins_per_decade=10,
                                  unit=None, physical_sizes=None) -> TabulatedPSD:
    """The 'topography' model: :meth:`TabulatedPSD.from_topography` of a file read with
    :func:`persson_fast.topography.read_topography`."""
    from .topography import read_topography

    topography = read_topography(file, unit=unit,
                                 physical_sizes=tuple(physical_sizes) if physical_sizes else None)
    return TabulatedPSD.from_topography(topography, q0=q0, q1=q1, hurst=hurst,
                                        bins_per_decade=int(bins_per_decade))


def _surface_from_spectrum_file(file, q_unit=None, C_unit=None, q0=None, q1=None) -> TabulatedPSD:
    """The 'psd' model: :meth:`TabulatedPSD.from_file`."""
    return TabulatedPSD.from_file(file, q_unit=q_unit, C_unit=C_unit, q0=q0, q1=q1)


register_surface_model(SurfaceModel(
    name="topography",
    parameters={
        "file": Parameter(None, "height map or line scan; q0 defaults to 2 pi/L, q1 to "
                                "pi/pixel (or the file's reliability cut-off)",
                          required=True, metavar="MAP", flag="--topography", type=str,
                          path=True, selects=True),
        **band_parameters(required=False),
        "hurst": Parameter("-", "Hurst exponent of the 1-D to 2-D conversion of line scans "
                                "(default fitted)", metavar="H"),
        "bins_per_decade": Parameter(None, "log bins per decade of the measured spectrum",
                                     metavar="NBINS", type=int),
        "unit": Parameter(None, "length unit of a topography file that names none (m, mm, um, "
                                "nm)", metavar="HUNIT", flag="--height-unit", type=str),
        "physical_sizes": Parameter(None, "scan size of a topography file that gives none, in "
                                          "--height-unit", metavar="SIZE",
                                    flag="--physical-size", nargs="+"),
    },
    build=_surface_from_topography_file, title=_MEASURED_TITLE, description=_MEASURED_TEXT))

register_surface_model(SurfaceModel(
    name="psd",
    parameters={
        "file": Parameter(None, "two-column spectrum file q, C", required=True,
                          metavar="FILE.csv", flag="--psd", type=str, path=True, selects=True),
        "q_unit": Parameter(None, "unit of q in --psd (1/m, 1/mm, 1/um, 1/nm)", metavar="QUNIT",
                            type=str),
        "C_unit": Parameter(None, "unit of C in --psd (m^4, um^4, nm^4)", metavar="CUNIT",
                            type=str),
        **band_parameters(required=False),
    },
    build=_surface_from_spectrum_file, title=_MEASURED_TITLE, description=_MEASURED_TEXT))


#: Young's modulus of the seed's PMMA. [Pa]
SEED_YOUNG_MODULUS = 2.9e9
#: Poisson ratio assumed for PMMA (the seed paper gives none). [-]
SEED_POISSON = 0.3
#: work of adhesion of the seed's adhesive curve (Fig. 2). [J/m^2]
SEED_WORK_OF_ADHESION = 0.06


def seed_e_star(poisson: float = SEED_POISSON) -> float:
    """Effective modulus E* = E / (1 - nu^2) of the seed's PMMA (E = 2.9 GPa). [Pa]

    The seed paper gives no Poisson ratio; ``poisson`` (default 0.3, assumed) must lie in
    [0, 0.5].
    """
    nu = float(poisson)
    if not (math.isfinite(nu) and 0.0 <= nu <= 0.5):
        raise ValueError(f"poisson must lie in [0, 0.5] [-]; got poisson = {poisson!r}")
    return SEED_YOUNG_MODULUS / (1.0 - nu * nu)


def seed_scene() -> CapillaryWaves:
    """The seed paper's PMMA surface: frozen capillary waves at T_g.

    Returns
    -------
    CapillaryWaves
        T = 370 K, γ = 0.04 J/m², q_c = 1.7e9 1/m, q0 = 2π/(0.1 mm), q1 = 7e9 1/m, no gravity;
        its h_rms is 0.455 nm (the paper quotes ≈ 0.5 nm, Eq. 2).

    Notes
    -----
    Persson, arXiv:cond-mat/0512604.
    """
    return CapillaryWaves(
        temperature=370.0, surface_tension=0.04, q_c=1.7e9, q0=2.0 * np.pi / 1e-4, q1=7e9
    )
