"""The yield wall: elastoplastic contact with a penetration hardness sigma_Y(zeta).

Physics (Persson, J. Chem. Phys. 115, 3840 (2001); Surf. Sci. Rep. 61, 201 (2006), sec. 3):
the stress distribution diffuses between two absorbing walls, the detachment wall at
-sigma_a (0 without adhesion) and the yield wall at sigma_Y, the penetration hardness. What
crosses the lower wall loses contact; what crosses the upper wall has yielded and stays in
contact, carrying sigma_Y. So

* elastic area A_el(G) = int P dsigma between the walls; plastic area A_pl(G) = the mass
  absorbed at sigma_Y up to G; detached = the mass absorbed at -sigma_a;
  A_el + A_pl + detached = 1;
* the real contact area is A = A_el + A_pl;
* load: int sigma P dsigma + int sigma_Y dA_pl - int sigma_a d(detached) = p_nom.

Two ways to solve it:

* a constant sigma_Y with sigma_a = 0: the strip [0, sigma_Y] has the exact sine series of
  :func:`persson_fast.plastic_area` (its image form at small G), served here
  (``method="analytic"``; ``"auto"`` takes it): relative accuracy ~1e-15, whatever rtol.
  Then int sigma P dsigma = p_nom - sigma_Y A_pl exactly (the wall at 0 carries no stress);
* any other pair of walls (a scale-dependent sigma_Y, a moving detachment wall): the
  compiled two-wall solver :mod:`persson_fast.plasticity.strip` (``method="strip"``), error-controlled
  to rtol like the one-wall grid methods.

A scale-dependent hardness is a callable of the magnification zeta (vectorised, [Pa]); this
module builds the common forms: :func:`hardness_power_law` (sigma_Y0 zeta^n, the form of
Persson's 2001 elastoplastic program), :func:`hardness_nix_gao` (H0 sqrt(1 + l q), the
indentation size effect of W.D. Nix and H. Gao, J. Mech. Phys. Solids 46, 411 (1998), with
q = zeta q0) and :func:`hardness_table` (values on zeta, interpolated linearly in
ln sigma_Y against ln zeta; its points are kinks of the wall, put on the schedule exactly).
In diffusion time the wall is sigma_Y(zeta(G)), zeta(G) the inverse of the surface's G(zeta)
(:func:`hardness_in_diffusion_time`, to rounding), sampled to rtol by
:func:`persson_fast.walls.sample_wall`, so the result does not depend on the zeta points a
user asks for.

Not in this version: the yield wall together with adhesion (the self-consistent detachment
wall of seed Eqs. 8-9 would have to be iterated with the elastic area and the yielded area's
share of the elastic energy, which the 2006 review does not settle); every entry point
refuses it with a ValueError that says so, rather than answer with another model.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # names of the type hints only
    from numpy.typing import ArrayLike

from dataclasses import dataclass

import numpy as np

from .._validation import _bool_in, as_float_array, check_finite
from ..analytic.plastic import plastic_area
from ..walls import CallableWallError

#: the methods that can carry a yield wall (the others raise a ValueError naming these):
#: "analytic" a constant one without a detachment wall, "strip" any pair of walls
YIELD_METHODS = ("analytic", "strip", "auto")


SCALE_FORMS = ("a number [Pa], a callable of zeta returning sigma_Y [Pa] (e.g. "
               "hardness_power_law, hardness_nix_gao) or a table (zeta, sigma_Y) "
               "(hardness_table)")


def check_hardness(value, name: str = "hardness", *, scale_dependent: bool = False):
    """The yield stress: a finite number > 0 [Pa] (returned as float), None (passes through)
    or, where ``scale_dependent``, a callable of zeta or a table -- a pair (zeta, sigma_Y) or
    a mapping with those keys -- (returned as a :class:`HardnessTable`). A callable of the
    user's own is returned wrapped in a :class:`CheckedHardness` (the package's forms and a
    table as they are), so that wherever it is called, a failure or a value that is no
    hardness is a ValueError naming ``name`` and the zeta it was called at.

    Where not ``scale_dependent``, a callable or a table is refused with the reason.
    """
    if value is None:
        return None
    if isinstance(value, HardnessTable) or (scale_dependent and isinstance(
            value, (CheckedHardness, PowerLawHardness, NixGaoHardness))):
        return value
    if callable(value) and scale_dependent:
        return CheckedHardness(value, name)
    pair = (isinstance(value, (tuple, list)) and len(value) == 2
            and all(np.ndim(v) == 1 for v in value))
    if scale_dependent and isinstance(value, dict):
        missing = {"zeta", "sigma_y"} - set(value)
        if missing:
            raise ValueError(f"{name} as a table needs the keys 'zeta' and 'sigma_y'; got keys "
                             f"{sorted(value)!r}")
        return hardness_table(value["zeta"], value["sigma_y"])
    if scale_dependent and pair:
        return hardness_table(*value)
    if callable(value) or isinstance(value, dict) or np.ndim(value) > 0:
        if scale_dependent:
            raise ValueError(f"{name} must be {SCALE_FORMS}; got {name} = {value!r}")
        raise ValueError(f"{name} must be a number [Pa]; a scale-dependent hardness is taken by "
                         f"solve_contact and solve_diffusion(sigma_y=...), not here; got "
                         f"{name} = {value!r}")
    arr = as_float_array(value, name, "Pa", ndim=(0,))
    check_finite(arr, name, "Pa")
    out = float(arr)
    if not out > 0:
        raise ValueError(f"{name} must be > 0 [Pa] (the penetration hardness sigma_Y); got "
                         f"{name} = {out!r}")
    return out


def _positive(value, name: str, unit: str, *, allow_zero: bool = False) -> float:
    arr = as_float_array(value, name, unit, ndim=(0,))
    check_finite(arr, name, unit)
    out = float(arr)
    if not (out >= 0 if allow_zero else out > 0):
        rule = ">= 0" if allow_zero else "> 0"
        raise ValueError(f"{name} must be {rule} [{unit}]; got {name} = {out!r}")
    return out


@dataclass(frozen=True, eq=False)
class CheckedHardness:
    """A hardness callable of the user's own, checked at every call.

    Calling it calls ``func`` on the magnifications; an exception raised there, a result of
    another shape, or a value that is not finite and > 0 is a ValueError
    (:class:`persson_fast.walls.CallableWallError`) naming the argument (``name``, e.g.
    ``hardness``) and the zeta it was called at, the user's own exception chained. Its repr
    is the user's callable's.

    Attributes
    ----------
    func : callable -- the user's vectorised callable zeta [-] -> sigma_Y [Pa].
    name : str -- the argument it was given as.
    """

    func: object
    name: str = "hardness"

    def _where(self, z: np.ndarray) -> str:
        flat = z.ravel()
        if flat.size == 1:
            return f"zeta = {float(flat[0])!r}"
        return (f"{flat.size} values of zeta in [{float(np.min(flat)):.6g}, "
                f"{float(np.max(flat)):.6g}]")

    def __call__(self, zeta):
        z = np.asarray(zeta, dtype=float)
        try:
            out = self.func(z.copy())
        except CallableWallError:
            raise
        except Exception as exc:  # noqa: BLE001 -- any failure of the user's code is reported
            raise CallableWallError(
                f"{self.name} must be a vectorised callable zeta [-] -> sigma_Y [Pa]; calling "
                f"it at {self._where(z)} raised {type(exc).__name__}: {exc}") from exc
        found = _bool_in(out, f"{self.name}(zeta)")
        if found is not None:
            raise CallableWallError(
                f"{self.name}(zeta) must return real numbers [Pa], not bools (True/False is "
                f"not read as 1/0); got {found} at {self._where(z)}")
        try:
            arr = np.asarray(out, dtype=float)
        except (TypeError, ValueError) as exc:
            raise CallableWallError(
                f"{self.name}(zeta) must return real numbers [Pa]; got {type(out).__name__} "
                f"{out!r:.80} at {self._where(z)}") from exc
        if arr.shape != z.shape:
            raise CallableWallError(
                f"{self.name}(zeta) must return finite values > 0 [Pa] of zeta's shape {z.shape} "
                f"(a vectorised callable); got shape {arr.shape} at {self._where(z)}")
        bad = ~(np.isfinite(arr) & (arr > 0))
        if np.any(bad):
            i = int(np.argmax(bad.ravel()))
            raise CallableWallError(
                f"{self.name}(zeta) must return finite values > 0 [Pa] of zeta's shape; got "
                f"{self.name}({float(z.ravel()[i])!r}) = {float(arr.ravel()[i])!r}")
        return arr

    def __repr__(self) -> str:
        return repr(self.func)


@dataclass(frozen=True)
class PowerLawHardness:
    """sigma_Y(zeta) = sigma_y0 zeta^exponent [Pa] (zeta >= 1)."""

    sigma_y0: float
    exponent: float

    def __call__(self, zeta):
        return self.sigma_y0 * np.asarray(zeta, dtype=float) ** self.exponent


@dataclass(frozen=True)
class NixGaoHardness:
    """sigma_Y(zeta) = h0 sqrt(1 + length q0 zeta) [Pa] (Nix & Gao 1998, q = zeta q0)."""

    h0: float
    length: float
    q0: float

    def __call__(self, zeta):
        return self.h0 * np.sqrt(1.0 + self.length * self.q0 * np.asarray(zeta, dtype=float))


@dataclass(frozen=True, eq=False)
class HardnessTable:
    """sigma_Y on zeta points, interpolated linearly in ln sigma_Y against ln zeta.

    Evaluating outside [zeta[0], zeta[-1]] raises a ValueError (no extrapolation); the
    table's points are the wall's kinks (:attr:`kinks_zeta`).
    """

    zeta: np.ndarray
    sigma_y: np.ndarray

    def __call__(self, zeta):
        z = np.asarray(zeta, dtype=float)
        lo, hi = self.zeta[0], self.zeta[-1]
        bad = (z < lo * (1 - 1e-12)) | (z > hi * (1 + 1e-12))
        if np.any(bad):
            raise CallableWallError(f"hardness table covers zeta in [{lo:.6g}, {hi:.6g}] [-]; "
                                    f"asked at zeta = {float(z[bad].ravel()[0])!r} (give a "
                                    f"table that spans the solve's zeta range)")
        return np.exp(np.interp(np.log(np.clip(z, lo, hi)), np.log(self.zeta),
                                np.log(self.sigma_y)))

    @property
    def kinks_zeta(self) -> np.ndarray:
        return self.zeta[1:-1].copy()

    def __repr__(self) -> str:
        return (f"HardnessTable({self.zeta.size} points, zeta {self.zeta[0]:.4g}.."
                f"{self.zeta[-1]:.4g}, sigma_y {self.sigma_y.min():.4g}.."
                f"{self.sigma_y.max():.4g} Pa)")


def hardness_power_law(sigma_y0: float, exponent: float) -> PowerLawHardness:
    """A hardness rising (exponent > 0) as a power of the magnification: sigma_y0 zeta^n.

    Parameters
    ----------
    sigma_y0 : float
        The macroscopic hardness (zeta = 1), > 0. [Pa]
    exponent : float
        n, finite. [-]

    Returns
    -------
    callable
        The law sigma_Y(zeta) = sigma_y0 zeta^n, vectorised over zeta [-] -> [Pa] (a frozen
        record with the fields ``sigma_y0`` and ``exponent``), to pass as ``hardness`` to
        :func:`persson_fast.solve_contact`, :func:`persson_fast.pull_off`,
        :func:`persson_fast.scan` or a :class:`persson_fast.Scene`.

    Raises
    ------
    ValueError
        If ``sigma_y0`` is not finite and > 0 or ``exponent`` is not finite.

    See Also
    --------
    persson_fast.hardness_nix_gao : The indentation size effect.
    persson_fast.hardness_table : A hardness given on magnifications.
    persson_fast.solve_contact : Takes it as ``hardness``.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> h = pf.hardness_power_law(1e7, 0.2)
    >>> print(np.round(h(np.array([1.0, 10.0, 100.0])) / 1e6, 3))    # [MPa]
    [10.    15.849 25.119]
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> r = pf.solve_contact(s, [1e6], e_star=1e9, hardness=h, rtol=1e-4)
    >>> print(f"elastic {r.elastic_area[0]:.4f}, plastic {r.plastic_area[0]:.4f}")
    elastic 0.0000, plastic 0.0838
    """
    arr = as_float_array(exponent, "exponent", "-", ndim=(0,))
    check_finite(arr, "exponent", "-")
    return PowerLawHardness(_positive(sigma_y0, "sigma_y0", "Pa"), float(arr))


def hardness_nix_gao(h0: float, length: float, q0: float) -> NixGaoHardness:
    """The indentation size effect H0 sqrt(1 + l q) at the wavenumber q = zeta q0.

    Parameters
    ----------
    h0 : float
        The hardness at large scales, > 0. [Pa]
    length : float
        The material length l (Nix & Gao's h*), >= 0. [m]
    q0 : float
        The wavenumber of zeta = 1 (the surface's q0), > 0. [1/m]

    Returns
    -------
    callable
        The law sigma_Y(zeta) = h0 sqrt(1 + length q0 zeta), vectorised over zeta [-] ->
        [Pa] (a frozen record with the fields ``h0``, ``length`` and ``q0``), to pass as
        ``hardness`` (as :func:`persson_fast.hardness_power_law`).

    Raises
    ------
    ValueError
        If ``h0`` or ``q0`` is not finite and > 0, or ``length`` not finite and >= 0.

    See Also
    --------
    persson_fast.hardness_power_law : A power law in the magnification.
    persson_fast.hardness_table : A hardness given on magnifications.
    persson_fast.solve_contact : Takes it as ``hardness``.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> h = pf.hardness_nix_gao(1e8, 1e-6, q0=1e4)
    >>> print(h(np.array([1.0, 100.0])))
    [1.00498756e+08 1.41421356e+08]
    """
    return NixGaoHardness(_positive(h0, "h0", "Pa"), _positive(length, "length", "m",
                                                               allow_zero=True),
                          _positive(q0, "q0", "1/m"))


def hardness_table(zeta: ArrayLike, sigma_y: ArrayLike) -> HardnessTable:
    """A hardness given on magnifications: interpolated linearly in ln sigma_Y against ln zeta.

    Parameters
    ----------
    zeta : array_like, shape (n,)
        Strictly increasing magnifications >= 1, n >= 2. [-]
    sigma_y : array_like, shape (n,)
        Hardness values > 0 at them. [Pa]

    Returns
    -------
    callable
        The table as a vectorised law zeta [-] -> sigma_Y [Pa], interpolated linearly in
        ln sigma_Y against ln zeta; evaluating it outside [zeta[0], zeta[-1]] raises a
        ValueError (no extrapolation). Its inner points are the yield wall's kinks. Pass it
        as ``hardness`` (as :func:`persson_fast.hardness_power_law`).

    Raises
    ------
    ValueError
        If the arrays are not finite, of different lengths or shorter than 2, ``zeta`` is
        below 1 or not strictly increasing, or a ``sigma_y`` is not > 0.

    See Also
    --------
    persson_fast.hardness_power_law : A power law in the magnification.
    persson_fast.hardness_nix_gao : The indentation size effect.
    persson_fast.solve_contact : Takes it as ``hardness``.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> h = pf.hardness_table([1.0, 1e3, 1e5], [1e8, 2e8, 4e8])
    >>> print(h(np.array([1.0, np.sqrt(1e3), 1e5])))
    [1.00000000e+08 1.41421356e+08 4.00000000e+08]
    """
    z = as_float_array(zeta, "zeta", "-", ndim=(1,))
    v = as_float_array(sigma_y, "sigma_y", "Pa", ndim=(1,))
    check_finite(z, "zeta", "-")
    check_finite(v, "sigma_y", "Pa")
    if z.size < 2 or v.shape != z.shape:
        raise ValueError(f"a hardness table needs zeta and sigma_y of one length >= 2; got "
                         f"shapes {z.shape} and {v.shape}")
    if z[0] < 1.0 or np.any(np.diff(z) <= 0):
        raise ValueError(f"hardness table zeta must be >= 1 and strictly increasing [-]; got "
                         f"zeta = {z!r}")
    if np.any(v <= 0):
        i = int(np.argmax(v <= 0))
        raise ValueError(f"hardness table sigma_y must be > 0 [Pa]; got sigma_y[{i}] = "
                         f"{float(v[i])!r}")
    z.setflags(write=False)
    v.setflags(write=False)
    return HardnessTable(z.copy(), v.copy())


def hardness_in_diffusion_time(hardness, surface, e_star: float, zeta_end: float):
    """A scale-dependent hardness as a wall in diffusion time: (callable G -> sigma_Y, kinks).

    zeta(G) inverts the surface's G(zeta) = diffusion_time(zeta q0, E*) by bisection in
    ln zeta on [0, ln zeta_end] (64 halvings: to rounding). The kinks are the G of a table's
    inner points (a callable is taken as smooth; sample_wall finds undeclared kinks).
    """
    q0 = float(surface.q0)
    lz_end = float(np.log(zeta_end))

    def g_of(lz):
        return np.asarray(surface.diffusion_time(np.exp(lz) * q0, e_star), dtype=float)

    g_end = float(g_of(np.array([lz_end]))[0])

    def zeta_of(g):
        g = np.asarray(g, dtype=float)
        lo = np.zeros(g.shape)
        hi = np.full(g.shape, lz_end)
        for _ in range(64):
            mid = 0.5 * (lo + hi)
            below = g_of(mid) < g
            lo = np.where(below, mid, lo)
            hi = np.where(below, hi, mid)
        out = np.exp(0.5 * (lo + hi))
        out = np.where(g <= 0.0, 1.0, np.where(g >= g_end, zeta_end, out))
        return out

    def wall(g):
        return np.asarray(hardness(zeta_of(g)), dtype=float) * np.ones(np.shape(g))

    kinks = None
    if isinstance(hardness, HardnessTable):
        kz = hardness.kinks_zeta
        kz = kz[(kz > 1.0) & (kz < zeta_end)]
        if kz.size:
            kinks = g_of(np.log(kz))
    return wall, kinks


def check_yield_method(method: str, name: str = "sigma_y") -> None:
    if method not in YIELD_METHODS:
        raise ValueError(f"method {method!r} cannot carry a yield wall ({name}); the methods "
                         f"that can: {', '.join(repr(m) for m in YIELD_METHODS)} (the exact "
                         f"series for a constant {name} without a detachment wall)")


def check_below_hardness(pressure: np.ndarray, hardness: float, name: str = "hardness") -> None:
    """p_nom <= sigma_Y: above it the whole nominal area yields at once (no diffusion)."""
    bad = pressure > hardness
    if np.any(bad):
        i = int(np.argmax(bad))
        raise ValueError(f"pressure must be <= {name} [Pa]: a nominal pressure above the "
                         f"hardness yields the whole nominal area at the macroscopic scale; got "
                         f"pressure[{i}] = {float(pressure[i])!r} with {name} = {hardness!r}")


def constant_yield(pressure: np.ndarray, G: np.ndarray, hardness: float) -> dict:
    """The six bookkeeping arrays (n_p, n_t) of a constant yield wall without adhesion.

    Parameters
    ----------
    pressure : (n_p,) -- nominal pressures, 0 <= p <= hardness. [Pa]
    G : (n_t,) -- diffusion times >= 0. [Pa^2]
    hardness : float -- sigma_Y > 0. [Pa]

    Returns
    -------
    dict of (n_p, n_t) arrays: ``elastic_area``, ``plastic_area``, ``detached_area``
    (1 - A_el - A_pl), ``load`` (int sigma P dsigma = p - sigma_Y A_pl), ``plastic_load``
    (sigma_Y A_pl), ``detached_load`` (0: the wall at sigma = 0 carries no stress).
    """
    p = np.asarray(pressure, dtype=float)[:, None]
    g = np.asarray(G, dtype=float)[None, :]
    elastic, plastic = plastic_area(np.broadcast_to(p, (p.shape[0], g.shape[1])),
                                    np.broadcast_to(g, (p.shape[0], g.shape[1])), hardness)
    elastic = np.asarray(elastic, dtype=float).reshape(p.shape[0], g.shape[1])
    plastic = np.asarray(plastic, dtype=float).reshape(p.shape[0], g.shape[1])
    return {
        "elastic_area": elastic,
        "plastic_area": plastic,
        "detached_area": 1.0 - elastic - plastic,
        "load": p - hardness * plastic,
        "plastic_load": hardness * plastic,
        "detached_load": np.zeros_like(elastic),
    }


def hardness_limit(pressure, hardness: float) -> np.ndarray:
    """A_pl at G -> infinity: p/sigma_Y (the whole load carried at the hardness). [-]"""
    return np.asarray(pressure, dtype=float) / hardness


__all__ = ["check_hardness", "constant_yield", "hardness_limit", "hardness_power_law",
           "hardness_nix_gao", "hardness_table", "hardness_in_diffusion_time",
           "PowerLawHardness", "NixGaoHardness", "HardnessTable", "CheckedHardness",
           "YIELD_METHODS"]
