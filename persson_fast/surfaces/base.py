"""The base class of the surface models, :class:`Surface`, and what the models share: the
physical constants (:data:`BOLTZMANN`, :data:`E_STAR_WARN_BELOW`), argument checks
(:func:`check_e_star`), exact power-law and ratio helpers, and the Gauss-Legendre rule in ln q.

Persson's isotropic convention for C(q), the moments and G(q) are described in
:mod:`persson_fast.surfaces`, which re-exports every name here.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # names of the type hints only
    from numpy.typing import ArrayLike

import abc
import math
import os
import sys
import warnings

import numpy as np

from .._io import write_text_atomic
from .._validation import (as_float_array, check_choice, check_finite, check_nonnegative,
                           check_not_bool, check_positive, check_whole_number)
from .registry import SurfaceModel, register_surface_model

__all__ = [
    "BOLTZMANN",
    "E_STAR_WARN_BELOW",
    "check_e_star",
    "RmsValue",
    "Surface",
]

#: Boltzmann constant (exact, SI 2019) [J/K].
BOLTZMANN = 1.380649e-23

#: an effective modulus below this draws a UserWarning: it is most likely a modulus typed in
#: GPa or MPa where Pa is meant (``e_star=1.0`` for 1 GPa gives A = 1 at any pressure). Soft
#: gels (~1e3-1e4 Pa) warn too; ``warnings.filterwarnings("ignore", "e_star")`` silences it. [Pa]
E_STAR_WARN_BELOW = 1e5

_PACKAGE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__))) + os.sep   # persson_fast/


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

    ``h_rms`` and ``slope_rms`` are properties whose value (a ``RmsValue``) is a float
    that may also be called: ``s.h_rms * 1e9`` and ``s.h_rms()`` both work.

    A subclass declares its parameters once, for the command line and
    :func:`persson_fast.scan`: ``MODEL`` (its name there), ``PARAMETERS`` (name ->
    ``Parameter``, the constructor's keyword arguments) and optionally ``MODEL_TITLE`` and
    ``MODEL_DESCRIPTION`` (its group in the command line's help). Setting ``MODEL`` registers it
    in ``persson_fast.surfaces.models.SURFACE_MODELS`` when the class is created.

    Attributes
    ----------
    q0 : float
        Long-wavelength cut-off, 2π/L with L the diameter of the nominal contact. [1/m]
    q1 : float
        Short-wavelength cut-off. [1/m]

    See Also
    --------
    persson_fast.SelfAffine : A self-affine surface.
    persson_fast.CapillaryWaves : Frozen capillary waves.
    persson_fast.TabulatedPSD : A tabulated spectrum.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> s = pf.seed_scene()
    >>> isinstance(s, pf.Surface)
    True
    >>> print(f"{s.q0:.4g} {s.q1:.4g} {s.h_rms:.3g}")
    6.283e+04 7e+09 4.55e-10
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
    def psd(self, q: ArrayLike) -> float | np.ndarray:
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

    def moment(self, k: int, q_lo: ArrayLike | None = None,
               q_hi: ArrayLike | None = None) -> float | np.ndarray:
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
        ``s.h_rms()`` returns the same value as a plain float (see ``RmsValue``).
        """
        return RmsValue(math.sqrt(2.0 * math.pi * self.moment(1)))

    @property
    def slope_rms(self) -> RmsValue:
        """Root-mean-square slope, :math:`(2\\pi \\int q^3 C dq)^{1/2}`. [-]

        A float that may also be called: ``s.slope_rms()`` returns the same value (see
        ``RmsValue``).
        """
        return RmsValue(math.sqrt(2.0 * math.pi * self.moment(3)))

    def diffusion_time(self, q: ArrayLike, e_star: float) -> float | np.ndarray:
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

    def to_csv(self, path: str | os.PathLike, *, points_per_decade: int = 20) -> str:
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
        check_not_bool(points_per_decade, "points_per_decade", "-")
        return write_spectrum_csv(self, path, points_per_decade=points_per_decade)

    def elastic_energy_full_contact(self, e_star: float) -> float:
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


def _grid(surface, points_per_decade: int) -> np.ndarray:
    """The q at which ``to_csv`` tabulates a surface: a table's own nodes, or a log grid."""
    q0, q1 = surface.q0, surface.q1
    if hasattr(surface, "q_table"):
        inner = surface.q_table[(surface.q_table > q0) & (surface.q_table < q1)]
        return np.concatenate(([q0], inner, [q1]))
    n = max(1, int(math.ceil(points_per_decade * math.log10(q1 / q0))))
    grid = q0 * (q1 / q0) ** (np.arange(n + 1) / n)
    grid[0], grid[-1] = q0, q1
    extra = []
    if hasattr(surface, "breakpoints"):
        extra = [b for b in np.asarray(surface.breakpoints()) if q0 < b < q1]
    return np.unique(np.concatenate((grid, extra)))


def write_spectrum_csv(surface, path, *, points_per_decade=20) -> str:
    """Write ``surface``'s C(q) to a CSV file, atomically (see ``Surface.to_csv``)."""
    ppd = check_whole_number(points_per_decade, "points_per_decade")
    q = _grid(surface, ppd)
    c = np.asarray(surface.psd(q), dtype=np.float64)
    path = os.fspath(path)
    if os.path.isdir(path):
        raise IsADirectoryError(f"cannot write {path!r}: it is a folder")
    how = ("the table's own nodes inside [q0, q1]" if hasattr(surface, "q_table") else
           f"{ppd} points per decade, log-spaced, plus the model's breakpoints")
    lines = ["# persson_fast spectrum C(q), Persson's isotropic 2-D convention: "
             "h_rms^2 = 2 pi int q C dq",
             f"# surface: {surface!r}",
             f"# q0 = {surface.q0!r} 1/m, q1 = {surface.q1!r} 1/m; tabulated on {q.size} "
             f"points: {how}",
             "q [1/m],C [m^4]"]
    lines += [f"{a!r},{b!r}" for a, b in zip(q.tolist(), c.tolist())]
    write_text_atomic(path, "\n".join(lines) + "\n")
    return path
