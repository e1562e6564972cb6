"""The scene: one record of what a contact problem is made of (model layer).

A :class:`Scene` holds the surface, the effective modulus and the optional physics a scene
may carry (adhesion: work of adhesion, energy correction S, detachment prefactor beta of
seed Eq. 8), validated once, with one place for each default. :func:`persson_fast.solve_contact`,
:func:`persson_fast.pull_off` and :func:`persson_fast.scan` take one in place of the keywords.
The argument checks shared by the entry points (rtol, the scene, the zeta grid) live here too.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .theories import check_theory, check_theory_scene
from ._validation import (as_float_array, check_finite, check_nonnegative, check_positive,
                          check_whole_number)
from .surfaces.models import E_STAR_WARN_BELOW, Surface, check_e_star

__all__ = ["Scene", "DETACHMENT_PREFACTOR", "default_zeta", "ZETA_PER_DECADE"]

#: beta of seed Eq. 8, sigma_a = beta (dgamma_eff E* q)^(1/2): the default 1/sqrt 2 [-]
DETACHMENT_PREFACTOR = 2 ** -0.5
#: default number of magnifications per decade of the profile grid of solve_contact
ZETA_PER_DECADE = 8


def _check_rtol(rtol, name: str = "rtol") -> float:
    arr = as_float_array(rtol, name, "-", ndim=(0,))
    check_finite(arr, name, "-")
    value = float(arr)
    if not 1e-12 <= value <= 0.1:
        raise ValueError(f"{name} must lie in [1e-12, 0.1] [-]; got {name} = {value!r}")
    return value


def default_zeta(surface: Surface, per_decade: int = ZETA_PER_DECADE) -> np.ndarray:
    """Magnifications 1 ... zeta1 log-spaced, with the surface's breakpoints included. [-]

    Parameters
    ----------
    surface : Surface
        The rough surface (its q0, q1 and breakpoints are used).
    per_decade : int
        Points per decade of zeta (default 8, the profile grid of ``solve_contact``
        without adhesion). [-]

    Returns
    -------
    numpy.ndarray
        Increasing magnifications from 1 to zeta1 = q1/q0 exactly. [-]

    Raises
    ------
    ValueError
        If ``per_decade`` is not a whole number >= 1.

    See Also
    --------
    persson_fast.adhesion_zeta : The grid of an adhesive solve.
    persson_fast.contact_area_no_adhesion : Evaluates A(zeta) on such a grid.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> z = pf.default_zeta(s)
    >>> print(z.size, z[0], f"{z[-1]:.4g}")
    41 1.0 1e+05
    """
    per_decade = check_whole_number(per_decade, "per_decade")
    zeta1 = surface.q1 / surface.q0
    n = max(2, int(np.ceil(np.log10(zeta1) * per_decade)) + 1)
    z = np.geomspace(1.0, zeta1, n)
    bp = np.asarray(surface.breakpoints(), dtype=float) / surface.q0
    z = np.unique(np.concatenate([z, bp[(bp >= 1.0) & (bp <= zeta1)]]))
    z[0], z[-1] = 1.0, zeta1
    return z


def _kept(surface, key, compute, e_star=None):
    """``compute()``, kept on a :class:`Surface` instance under ``key`` (see
    ``Surface._memoized``). Computed anew for other surface objects, and for an ``e_star``
    [Pa] below ``E_STAR_WARN_BELOW``, whose every G(q) evaluation warns."""
    if isinstance(surface, Surface) and (e_star is None or e_star >= E_STAR_WARN_BELOW):
        return surface._memoized(key, compute)
    return compute()


def _diffusion_times(surface, z, e_star: float, *, default_grid: bool = False) -> np.ndarray:
    """G(zeta) on the magnifications ``z`` with G[0] = 0 exactly, a fresh array. [Pa^2]

    ``default_grid=True`` says that ``z`` is :func:`default_zeta` of the surface: its G is
    then computed once per surface and ``e_star`` [Pa] and copied.
    """
    def compute():
        G = np.asarray(surface.diffusion_time(z * surface.q0, e_star), dtype=float)
        G[0] = 0.0
        return G

    if not default_grid:
        return compute()
    return _kept(surface, ("G", e_star), compute, e_star).copy()


#: relative distance from zeta1 = q1/q0 within which the last point of a user zeta grid is
#: taken as zeta1 (and set to it exactly)
ZETA1_RTOL = 1e-12


def _check_zeta(zeta, surface) -> np.ndarray:
    """A user zeta grid: starts at 1, increasing, and ends at zeta1 = q1/q0.

    ``area`` is A(zeta1)/A0 by definition, and with adhesion the grid is the discretisation
    of the fixed point, whose Eq. 9 needs the profile up to zeta1: a grid that stops short
    of zeta1 (or goes beyond it) is refused, not silently extended. A last point within a
    relative ``ZETA1_RTOL`` of zeta1 is set to zeta1 exactly (``np.logspace`` rounding).
    """
    if zeta is None:
        return _kept(surface, "zeta", lambda: default_zeta(surface)).copy()
    z = as_float_array(zeta, "zeta", "-", ndim=(1,))
    check_finite(z, "zeta", "-")
    zeta1 = surface.q1 / surface.q0
    if z.size < 1 or z[0] != 1.0:
        raise ValueError(f"zeta must start at 1 [-]; got zeta[0] = {z[0].item() if z.size else None!r}")
    bad = (z < 1.0) | (z > zeta1 * (1 + ZETA1_RTOL))
    if np.any(bad):
        i = int(np.argmax(bad))
        raise ValueError(f"zeta must lie in [1, q1/q0 = {float(zeta1)!r}] [-]; got zeta[{i}] = {z[i].item()!r}")
    if np.any(np.diff(z) <= 0):
        i = int(np.argmax(np.diff(z) <= 0))
        raise ValueError(f"zeta must be increasing [-]; got zeta[{i}] = {z[i].item()!r} >= zeta[{i + 1}] = {z[i + 1].item()!r}")
    n = z.size
    if n < 2 or abs(z[-1] - zeta1) > ZETA1_RTOL * zeta1:
        raise ValueError(
            f"zeta must end at zeta1 = q1/q0 = {float(zeta1)!r} (within a relative "
            f"{ZETA1_RTOL:g}) [-]: result.area is A(zeta1)/A0, and with adhesion the grid "
            f"is that of the fixed point; got zeta[{n - 1}] = {z[-1].item()!r}. Append "
            f"q1/q0 (np.append(zeta, surface.q1 / surface.q0)) or pass zeta=None")
    z = z.copy()
    z[-1] = zeta1
    return z


def _check_scene_args(surface, e_star, work_of_adhesion, detachment_prefactor,
                      energy_correction):
    """Validate the scene arguments shared by solve_contact and pull_off; return floats.

    Besides each argument's own rule, the scene must stay finite in float64: G(q1) (e_star
    with the surface) and, with adhesion, the detachment stress scale beta (dgamma E* q1)^(1/2)
    and U_el(1)/dgamma (work_of_adhesion) -- a non-finite one would come back as a silent A.
    An e_star below ``E_STAR_WARN_BELOW`` (1e5 Pa) warns: a modulus in GPa where Pa is meant.
    """
    e = check_e_star(e_star)
    dg = as_float_array(work_of_adhesion, "work_of_adhesion", "J/m^2", ndim=(0,))
    check_nonnegative(dg, "work_of_adhesion", "J/m^2")
    beta = as_float_array(detachment_prefactor, "detachment_prefactor", "-", ndim=(0,))
    check_positive(beta, "detachment_prefactor", "-")
    if energy_correction is not None:
        gs = as_float_array(energy_correction, "energy_correction", "-", ndim=(0,))
        check_finite(gs, "energy_correction", "-")
        if not 0.0 <= float(gs) <= 1.0:
            raise ValueError(
                f"energy_correction must lie in [0, 1] [-]; got energy_correction = {float(gs)!r}"
            )
    for attr in ("q0", "q1", "diffusion_time", "breakpoints"):
        if not hasattr(surface, attr):
            raise ValueError(f"surface must be a persson_fast surface model; {type(surface).__name__} has no {attr!r}")
    dg, beta = float(dg), float(beta)
    _check_scene_finite(surface, e, dg, beta)
    return e, dg, beta


def _check_scene_finite(surface, e: float, dg: float, beta: float) -> None:
    """Refuse an e_star / work_of_adhesion for which the scene overflows float64 (see
    :func:`_check_scene_args`); G(zeta) <= G(q1), sigma_a(zeta) <= its value at q1 and the
    U_el quadrature weights <= U_el(1)/dgamma, so the full-band values bound the grid's."""
    def full_band():
        with np.errstate(all="ignore"):
            return float(np.asarray(surface.diffusion_time(surface.q1, e), dtype=float))

    G1 = _kept(surface, ("G1", e), full_band, e)
    if not np.isfinite(G1):
        raise ValueError(f"e_star must keep the diffusion time G(q1) of the surface finite [Pa]; "
                         f"got e_star = {e!r}, which gives G(q1) = {G1!r} [Pa^2]")
    if dg == 0.0:
        return
    with np.errstate(all="ignore"):
        c1_squared = beta * beta * dg * e * float(surface.q1)
        u_per_dg = (0.5 * np.pi * e / dg) * float(surface.moment(2)) if hasattr(
            surface, "moment") else 0.0
    for what, value, unit in (
            ("sigma_a(q1)^2 = (beta^2 work_of_adhesion e_star q1)", c1_squared, "Pa^2"),
            ("U_el(zeta = 1)/work_of_adhesion = (pi e_star/2) int q^2 C dq/work_of_adhesion",
             u_per_dg, "-")):
        if not np.isfinite(value):
            raise ValueError(
                f"work_of_adhesion [J/m^2], e_star [Pa] and detachment_prefactor [-] must keep "
                f"{what} finite; got work_of_adhesion = {dg!r}, e_star = {e!r}, "
                f"detachment_prefactor = {beta!r}, which give {float(value)!r} [{unit}]")



@dataclass(frozen=True)
class Scene:
    """One contact scene: a rough surface pressed against an elastic solid, with adhesion
    optionally.

    Parameters
    ----------
    surface : Surface
        The roughness (:class:`~persson_fast.SelfAffine`, :class:`~persson_fast.CapillaryWaves`,
        :class:`~persson_fast.TabulatedPSD`, ...).
    e_star : float
        Effective modulus E* = E / (1 - nu^2) > 0. [Pa]
    work_of_adhesion : float
        Delta gamma >= 0 (default 0: no adhesion). [J/m^2]
    energy_correction : float or None
        gamma_S of S = gamma_S + (1 - gamma_S) P^2, in [0, 1]; None: S = 1. [-]
    detachment_prefactor : float
        beta of seed Eq. 8 (default ``DETACHMENT_PREFACTOR`` = 1/sqrt 2). [-]
    hardness : float, callable, table or None
        The yield wall, with or without adhesion (see ``persson_fast.plasticity``): a
        constant penetration hardness sigma_Y > 0 [Pa], a callable of zeta
        (``hardness_power_law``, ``hardness_nix_gao``, your own), a table (zeta, sigma_Y)
        (``hardness_table``), or None (default, elastic). ``solve_contact``, ``scan`` and
        ``pull_off`` take every form (``pull_off`` then follows the two-wall fixed point's
        contact branch); the separation (``solve_separation``, ``pressure_at_separation``,
        ``decay_length``, ``gap_distribution``, ``embed.contact_law``) and
        ``embed.adhesive_scene`` refuse a scene with one.

    Raises
    ------
    ValueError
        For a parameter that breaks its rule (those of
        :func:`persson_fast.solve_contact`), naming it.

    See Also
    --------
    persson_fast.solve_contact : Takes a Scene in place of the keywords.
    persson_fast.pull_off : Takes a Scene, with a yield wall too.
    persson_fast.scan : Takes a Scene.

    Notes
    -----
    The values are validated on construction (the rules of :func:`persson_fast.solve_contact`,
    including that the scene stays finite in float64) and stored as floats.
    ``solve_contact(scene, pressure, ...)`` equals ``solve_contact(scene.surface, pressure,
    **scene.keywords(), ...)`` bitwise.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> scene = pf.Scene(pf.seed_scene(), e_star=pf.seed_e_star(), work_of_adhesion=0.06)
    >>> scene.adhesive
    True
    >>> sorted(scene.keywords())
    ['detachment_prefactor', 'e_star', 'energy_correction', 'work_of_adhesion']
    >>> r = pf.solve_contact(scene, [1e6], rtol=1e-3)
    >>> print(r.method)
    cn
    """

    surface: object
    e_star: float
    work_of_adhesion: float = 0.0
    energy_correction: float | None = None
    detachment_prefactor: float = DETACHMENT_PREFACTOR
    hardness: object = None

    def __post_init__(self):
        from .plasticity.hardness import check_hardness

        object.__setattr__(self, "hardness", check_hardness(self.hardness,
                                                           scale_dependent=True))
        e, dg, beta = _check_scene_args(self.surface, self.e_star, self.work_of_adhesion,
                                        self.detachment_prefactor, self.energy_correction)
        object.__setattr__(self, "e_star", e)
        object.__setattr__(self, "work_of_adhesion", dg)
        object.__setattr__(self, "detachment_prefactor", beta)
        if self.energy_correction is not None:
            object.__setattr__(self, "energy_correction", float(self.energy_correction))

    @property
    def adhesive(self) -> bool:
        """True when the scene has adhesion (work_of_adhesion > 0)."""
        return self.work_of_adhesion > 0.0

    def keywords(self) -> dict:
        """The scene as the keywords of :func:`persson_fast.solve_contact` (all but the
        surface)."""
        out = {"e_star": self.e_star, "work_of_adhesion": self.work_of_adhesion,
               "energy_correction": self.energy_correction,
               "detachment_prefactor": self.detachment_prefactor}
        if self.hardness is not None:
            out["hardness"] = self.hardness
        return out


#: the keyword defaults of the scene arguments in the entry points' signatures
SCENE_DEFAULTS = {"e_star": None, "work_of_adhesion": 0.0, "energy_correction": None,
                  "detachment_prefactor": DETACHMENT_PREFACTOR, "hardness": None}

#: the entry points that take a Scene with a yield wall (hardness); pull_off moves the Scene's
#: hardness to its own keyword before it unpacks the rest, so it never reaches the check below
TAKES_HARDNESS = ("solve_contact", "pull_off", "scan")


def unpack_scene(surface, given: dict, where: str):
    """(surface, scene keywords) from an entry point's first argument and its keywords.

    A :class:`Scene` as first argument carries the scene: keywords that differ from their
    defaults then raise a ValueError (one record, not two). Otherwise ``surface`` is the
    surface and ``given`` the keywords; ``e_star`` is required.
    """
    if isinstance(surface, Scene):
        clash = [k for k, v in given.items() if not _is_default(k, v)]
        if clash:
            raise ValueError(f"{where}: give the scene's parameters either in the Scene or as "
                             f"keywords, not both; got a Scene and {', '.join(clash)}")
        if surface.hardness is not None and where not in TAKES_HARDNESS:
            takes = ", ".join(TAKES_HARDNESS) + (" takes" if len(TAKES_HARDNESS) == 1
                                                 else " take")
            raise ValueError(f"{where} does not take a yield wall: the Scene has hardness = "
                             f"{surface.hardness!r} Pa (use a Scene without hardness; {takes} "
                             f"one)")
        return surface.surface, surface.keywords()
    if given.get("e_star") is None:
        raise ValueError(f"{where}: e_star (the effective modulus E* > 0, in Pa) is required "
                         f"with a surface (or pass a Scene); got e_star = None")
    return surface, dict(given)


def unpack_adhesive_scene(surface, e_star, work_of_adhesion, energy_correction,
                          detachment_prefactor, where: str):
    """:func:`unpack_scene` for an entry point that needs adhesion (``work_of_adhesion``
    defaults to None there and is required with a surface); returns (surface, keywords)."""
    if work_of_adhesion is None and not isinstance(surface, Scene):
        raise ValueError(f"{where}: work_of_adhesion (Delta gamma > 0, in J/m^2) is required "
                         f"with a surface (or pass a Scene); got work_of_adhesion = None")
    return unpack_scene(
        surface, {"e_star": e_star,
                  "work_of_adhesion": 0.0 if work_of_adhesion is None else work_of_adhesion,
                  "energy_correction": energy_correction,
                  "detachment_prefactor": detachment_prefactor}, where)


def _is_default(key, value) -> bool:
    default = SCENE_DEFAULTS[key]
    if default is None:
        return value is None
    try:
        return value == default
    except Exception:  # noqa: BLE001 -- an array or odd object is not the default
        return False


@dataclass(frozen=True)
class Plan:
    """A checked scene: its pieces and the route that solves their composition.

    Attributes
    ----------
    surface : Surface -- the roughness.
    e_star, work_of_adhesion, detachment_prefactor : float -- checked scene values (SI).
    energy_correction : float or None -- gamma_S of S, or None (S = 1).
    theory : str -- the time of the diffusion ("persson01", "yp08", "wm17", "xu24").
    theory_gamma : float or None -- the corrected theory's gamma.
    hardness : object or None -- the checked yield wall (None: no upper wall).
    method : str -- the method asked for.
    """
    surface: object
    e_star: float
    work_of_adhesion: float
    detachment_prefactor: float
    energy_correction: float | None
    theory: str
    theory_gamma: float | None
    hardness: object
    method: str

    @property
    def lower_wall(self) -> str:
        """"adhesion" (the detachment wall) or "none"."""
        return "adhesion" if self.work_of_adhesion > 0 else "none"

    @property
    def upper_wall(self) -> str:
        """"none", or "yield" (the hardness)."""
        return "none" if self.hardness is None else "yield"

    @property
    def route(self) -> str:
        """The key of :data:`persson_fast.plan.ROUTES` that solves this composition."""
        corrected = self.theory != "persson01"
        if self.upper_wall == "yield":
            return ("two-wall-fixed-point" if self.lower_wall == "adhesion" or corrected
                    else "yield")
        if self.lower_wall == "adhesion":
            return "adhesive-fixed-point"
        return "theory" if corrected else "elastic"


def plan_scene(surface, kw: dict, *, theory: str = "persson01", theory_gamma=None,
               method: str = "auto") -> Plan:
    """The :class:`Plan` of an unpacked scene (``kw``: e_star, work_of_adhesion,
    energy_correction, detachment_prefactor and optionally hardness, as given): the scene's
    values checked, the theory checked against the walls it must carry
    (:func:`check_composition`). Every entry point reads its scene through here:
    :func:`persson_fast.plan.plan_contact` (solve_contact), pull_off, solve_separation, gap_distribution and
    the contact law (which refuse every route but "elastic")."""
    from .plasticity.hardness import check_hardness

    e, dg, beta = _check_scene_args(surface, kw["e_star"], kw.get("work_of_adhesion", 0.0),
                                    kw.get("detachment_prefactor", DETACHMENT_PREFACTOR),
                                    kw.get("energy_correction"))
    theory, theory_gamma = check_theory(theory, theory_gamma)
    hardness = kw.get("hardness")
    check_composition(theory, float(dg), hardness)
    if hardness is not None:
        hardness = check_hardness(hardness, scale_dependent=True)
    return Plan(surface=surface, e_star=e, work_of_adhesion=dg,
                detachment_prefactor=float(beta), energy_correction=kw.get("energy_correction"),
                theory=theory, theory_gamma=theory_gamma, hardness=hardness, method=method)


def check_composition(theory: str, work_of_adhesion: float, hardness=None) -> None:
    """Refuse a time law that cannot carry the scene's walls (xu24 with adhesion or a yield
    wall): the first row of the refused combinations, shared by every entry point and by
    each scene of a scan."""
    if theory != "persson01":
        check_theory_scene(theory, float(work_of_adhesion), hardness)
