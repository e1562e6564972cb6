"""Frozen result objects (arrays + status/message + timings)."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ._kernels.status import STATUS_MESSAGES


def summarize_status(status: np.ndarray) -> tuple[bool, str]:
    """(success, message) from per-pressure integer status codes."""
    status = np.asarray(status)
    if status.size == 0 or not status.any():
        return True, "ok"
    parts = []
    for code in np.unique(status[status != 0]):
        idx = np.flatnonzero(status == code)
        shown = ", ".join(str(i) for i in idx[:5]) + (", ..." if idx.size > 5 else "")
        parts.append(f"{STATUS_MESSAGES.get(int(code), 'unknown status')} (code {int(code)}) "
                     f"at pressure index {shown}")
    return False, "; ".join(parts)


def _span(x, unit: str = "") -> str:
    """'n values in [lo, hi] unit' of an array (finite values only), for the short reprs."""
    x = np.asarray(x, dtype=float)
    n = x.size
    finite = x[np.isfinite(x)]
    unit = f" {unit}" if unit else ""
    if finite.size == 0:
        return f"{n} values" if n != 1 else "1 value"
    lo, hi = float(finite.min()), float(finite.max())
    if n == 1:
        return f"1 value, {lo:.6g}{unit}"
    rng = f"{lo:.6g}{unit}" if lo == hi else f"[{lo:.6g}, {hi:.6g}]{unit}"
    return f"{n} values in {rng}"


def _largest(x) -> float:
    """Largest finite value of an array (0 when there is none), for the short reprs."""
    x = np.asarray(x, dtype=float)
    finite = x[np.isfinite(x)]
    return float(finite.max()) if finite.size else 0.0


def _timings(timings: dict) -> str:
    return ", ".join(f"{k} {v:.3g} s" for k, v in timings.items()) or "none"


def per_contact_area(x, area):
    """x / area where there is contact, nan where A = 0 (mean stresses in the contact)."""
    x = np.asarray(x, dtype=float)
    area = np.asarray(area, dtype=float)
    contact = area > 0
    if contact.all():                        # the usual case: the same quotients, one pass
        return np.asarray(x / area)
    safe = np.where(contact, area, 1.0)
    return np.where(contact, x / safe, np.nan)


@dataclass(frozen=True, repr=False)
class DiffusionResult:
    """Result of :func:`persson_fast.solve_diffusion`.

    ``repr`` (and ``print``) show a short summary; the arrays are the attributes below.

    Attributes
    ----------
    G : numpy.ndarray, shape (n_t,)
        Diffusion times. [Pa^2]
    pressure : numpy.ndarray, shape (n_p,)
        Nominal pressures sigma0. [Pa]
    sigma_a : numpy.ndarray, shape (n_p, n_t)
        Detachment stress of the wall at -sigma_a. [Pa]
    area : numpy.ndarray, shape (n_p, n_t)
        Relative contact area A(G)/A0 (with a yield wall: the elastic part). [-]
    load : numpy.ndarray, shape (n_p, n_t)
        Load carried in contact, int sigma P dsigma. [Pa]
    detached_area : numpy.ndarray, shape (n_p, n_t)
        Area detached through the wall (area + plastic_area + detached_area = 1). [-]
    detached_load : numpy.ndarray, shape (n_p, n_t)
        int sigma_a g dG (load = pressure + detached_load without a yield wall). [Pa]
    error_estimate : numpy.ndarray, shape (n_p, n_t)
        Estimate of the absolute error of ``area`` (with a yield wall solved by "strip":
        of the real contact area area + plastic_area). [-]
    method : str
        The method that produced the numbers.
    status : numpy.ndarray of int, shape (n_p,)
        0 ok, otherwise see ``message`` (the codes of ``persson_fast.embed.STATUS_MESSAGES``).
    success : bool
        Whether every status is 0.
    message : str
        What the status codes mean.
    timings : dict
        Seconds spent (``solve``; ``compile`` when this call compiled). [s]
    counts : numpy.ndarray of int, shape (n_p, 3), or None
        Work of a compiled method per pressure: nodes (or time nodes of "bnr"), steps,
        node-steps (kernel evaluations of "bnr").
    plastic_area : numpy.ndarray, shape (n_p, n_t)
        Area absorbed at the yield wall sigma_y (zeros without one). [-]
    plastic_load : numpy.ndarray, shape (n_p, n_t)
        int sigma_y dA_pl, the load the yielded area carries (load + plastic_load -
        detached_load = pressure with a yield wall; detached_load = int sigma_a dD as
        without one). [Pa]
    sigma_y : float, numpy.ndarray of shape (n_p, n_t), or None
        The yield wall: the constant, or its values at G (samples or a callable evaluated
        there). [Pa]

    See Also
    --------
    persson_fast.solve_diffusion : Returns a DiffusionResult.
    persson_fast.ContactResult : The result of a contact scene.

    Notes
    -----
    With a yield wall solved by "strip", ``error_estimate`` and rtol refer to the real
    contact area A = area + plastic_area (abs(dA) <= rtol A + 1e-12; the grid is refined
    until the estimates of the elastic and plastic parts meet that bound too).

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> r = pf.solve_diffusion(np.linspace(0.0, 1.0, 11), [0.5, 1.0])
    >>> print(r.method, r.area.shape, np.round(r.area[:, -1], 6))
    cn (2, 11) [0.276326 0.5205  ]
    """

    G: np.ndarray
    pressure: np.ndarray
    sigma_a: np.ndarray
    area: np.ndarray
    load: np.ndarray
    detached_area: np.ndarray
    detached_load: np.ndarray
    error_estimate: np.ndarray
    method: str
    status: np.ndarray
    success: bool
    message: str
    timings: dict = field(default_factory=dict)
    counts: np.ndarray | None = None
    plastic_area: np.ndarray | None = None
    plastic_load: np.ndarray | None = None
    sigma_y: float | None = None

    def __post_init__(self):
        for name in ("plastic_area", "plastic_load"):
            if getattr(self, name) is None:
                object.__setattr__(self, name, np.zeros(np.shape(self.area)))

    def __repr__(self) -> str:
        """A few lines (method, shapes, status, ranges), not every array."""
        n_p, n_t = np.shape(self.area) if np.ndim(self.area) == 2 else (0, 0)
        end = np.asarray(self.area)[:, -1] if n_p and n_t else np.zeros(0)
        return (
            f"<DiffusionResult: method={self.method!r}, success={self.success}, "
            f"message={self.message!r}\n"
            f"  pressure        {_span(self.pressure, 'Pa')}\n"
            f"  G               {_span(self.G, 'Pa^2')}\n"
            f"  area            shape ({n_p}, {n_t}); A(G[-1])/A0: {_span(end)}\n"
            f"  error_estimate  max {_largest(self.error_estimate):.3g}; "
            f"timings: {_timings(self.timings)}>"
        )


class Deferred:
    """A value computed on first access, ``func(*args)`` (picklable when ``func`` is a
    module-level function): :class:`ContactResult` takes it for a profile that a closed form
    can give cheaply but that most callers never read."""

    __slots__ = ("func", "args")

    def __init__(self, func, *args):
        self.func = func
        self.args = args

    def __reduce__(self):
        return (Deferred, (self.func, *self.args))


#: the ContactResult fields that may be given as a Deferred
_DEFERRABLE = ("area_zeta", "sigma_a", "gamma_eff")


@dataclass(frozen=True, repr=False)
class ContactResult:
    """Result of :func:`persson_fast.solve_contact` (one scene, many pressures).

    ``repr`` (and ``print``) show a short summary; the arrays are the attributes below.
    n_p is the number of pressures, n_z that of the magnifications ``zeta``.

    Attributes
    ----------
    pressure : numpy.ndarray, shape (n_p,)
        Nominal pressures. [Pa]
    area : numpy.ndarray, shape (n_p,)
        A(zeta1)/A0, the relative real contact area (with a yield wall: elastic plus
        plastic). [-]
    zeta : numpy.ndarray, shape (n_z,)
        Magnifications of the profiles; zeta[0] == 1, zeta[-1] == q1/q0. [-]
    G : numpy.ndarray, shape (n_z,)
        Diffusion time G(zeta) (of the original theory also for a corrected one). [Pa^2]
    area_zeta : numpy.ndarray, shape (n_p, n_z)
        A(zeta)/A0. [-]
    sigma_a : numpy.ndarray, shape (n_p, n_z)
        Detachment stress sigma_a(zeta) (zeros without adhesion). [Pa]
    gamma_eff : numpy.ndarray, shape (n_p, n_z)
        Effective interfacial energy gamma_eff(zeta) (zeros without adhesion). [J/m^2]
    load : numpy.ndarray, shape (n_p,)
        Load carried in contact at zeta1, int sigma P dsigma; with a yield wall the load of
        the elastic part, p - hardness * plastic_area (the yielded area carries the
        rest). [Pa]
    mean_contact_pressure : numpy.ndarray, shape (n_p,)
        p_nom A0 / A, the mean stress in the contact by force balance, F_N = p_nom A0
        carried by the real contact area A (nan where A = 0). [Pa]
    detached_area : numpy.ndarray, shape (n_p,)
        Area detached at zeta1 (area + detached_area = 1 without a yield wall). [-]
    detached_load : numpy.ndarray, shape (n_p,)
        Load carried off by the detached area at zeta1. [Pa]
    error_estimate : numpy.ndarray, shape (n_p,)
        Estimate of the absolute error of ``area``. With adhesion: the zeta-grid error of
        the returned (Richardson-extrapolated) area from three nested grids, plus the inner
        diffusion solves' estimate; measured 0.5-10x the error against converged
        references, 2-5x after a square-root onset of sigma_a (where gamma_eff changes
        sign). A pressure whose estimate exceeds rtol is solved on finer grids, and flagged
        (status 15) if the work cap leaves it above. [-]
    method : str
        The method used ("analytic", "cn", "strip", ...).
    status : numpy.ndarray of int, shape (n_p,)
        0 ok, otherwise see ``message`` (the codes of ``persson_fast.embed.STATUS_MESSAGES``).
    success : bool
        Whether every status is 0.
    message : str
        What the status codes mean.
    timings : dict
        Seconds spent (``solve``; ``compile`` when this call compiled). [s]
    elastic_energy_zeta : numpy.ndarray, shape (n_p, n_z), or None
        U_el(zeta) per nominal area (adhesion only). [J/m^2]
    iterations : numpy.ndarray of int, shape (n_p,), or None
        Fixed-point iterations (adhesion).
    residual : numpy.ndarray, shape (n_p,), or None
        Final fixed-point residual, sup abs(F(x) - x) / max(abs(x), abs(p)) (adhesion). [-]
    sticky : numpy.ndarray of bool, shape (n_p,), or None
        gamma_eff(zeta = 1) > 0: macroscopically sticky (adhesion).
    load_zeta, detached_load_zeta : numpy.ndarray, shape (n_p, n_z), or None
        Load in contact and detached load (adhesion). [Pa]
    zeta_error : numpy.ndarray, shape (n_p,), or None
        Adhesion: the estimated error of ``area`` from the zeta grid; included in
        ``error_estimate``. [-]
    mean_contact_stress : numpy.ndarray, shape (n_p,), or None
        load / A, the mean of the compressive stress distribution over the contact, int
        sigma P dsigma / A (equal to ``mean_contact_pressure`` without adhesion; larger with
        it, since the contact also carries the tension of the detached rims; nan where
        A = 0). [Pa]
    theory : str
        The area theory: "persson01" (the original) or a corrected one, "yp08", "wm17",
        "xu24".
    theory_gamma : float or None
        The gamma the corrected theory ran with (its published default when none was
        given); None for "persson01". [-]
    elastic_area, plastic_area : numpy.ndarray, shape (n_p,), or None
        With a yield wall (``hardness``): the elastic and the yielded (plastically
        deformed) fractions of A0 at zeta1; ``area`` is their sum, the real contact area
        (both parts are in contact). None without one. [-]
    plastic_area_zeta : numpy.ndarray, shape (n_p, n_z), or None
        A_pl(zeta)/A0 (with a yield wall). [-]
    plastic_load : numpy.ndarray, shape (n_p,), or None
        With a yield wall and adhesion: int sigma_Y dA_pl, the load the yielded area
        carries (load + plastic_load - detached_load = pressure). [Pa]
    hardness : float, callable or None
        The yield stress sigma_Y of the solve: a constant [Pa] or a scale-dependent one (a
        callable of zeta, a hardness table).
    separation : numpy.ndarray, shape (n_p,)
        Mean interfacial separation u(p), computed on first access by the closed form of
        :func:`persson_fast.solve_separation` and kept (inf at p = 0). Derived for the
        original theory of elastic contact without adhesion: with adhesion, a yield wall or
        a corrected theory reading it raises a ValueError that says why. [m]
    stiffness : numpy.ndarray, shape (n_p,)
        Contact stiffness K = -dp/du per nominal area (as ``separation``; 0 at p = 0).
        [Pa/m]
    elastic_energy : numpy.ndarray, shape (n_p,)
        Stored elastic energy U_el per nominal area at zeta = 1: the closed form without
        adhesion (on first access, as ``separation``), ``elastic_energy_zeta[:, 0]`` with
        it. [J/m^2]

    See Also
    --------
    persson_fast.solve_contact : Returns a ContactResult.
    persson_fast.DiffusionResult : The result of the diffusion alone.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> r = pf.solve_contact(s, [1e5, 1e6], e_star=1e9)
    >>> print(r.method, bool(np.all(r.success)), np.round(r.area, 5))
    analytic True [0.0008  0.00802]
    """

    pressure: np.ndarray
    area: np.ndarray
    zeta: np.ndarray
    G: np.ndarray
    area_zeta: np.ndarray
    sigma_a: np.ndarray
    gamma_eff: np.ndarray
    load: np.ndarray
    mean_contact_pressure: np.ndarray
    detached_area: np.ndarray
    detached_load: np.ndarray
    error_estimate: np.ndarray
    method: str
    status: np.ndarray
    success: bool
    message: str
    timings: dict = field(default_factory=dict)
    elastic_energy_zeta: np.ndarray | None = None
    iterations: np.ndarray | None = None
    residual: np.ndarray | None = None
    sticky: np.ndarray | None = None
    load_zeta: np.ndarray | None = None
    detached_load_zeta: np.ndarray | None = None
    zeta_error: np.ndarray | None = None
    mean_contact_stress: np.ndarray | None = None
    theory: str = "persson01"
    theory_gamma: float | None = None
    elastic_area: np.ndarray | None = None
    plastic_area: np.ndarray | None = None
    plastic_area_zeta: np.ndarray | None = None
    hardness: float | None = None
    plastic_load: np.ndarray | None = None
    # a callable pressure -> (separation, stiffness, elastic_energy, seconds) for a scene
    # whose separation is served (see persson_fast.separation.elastic.contact_fields), or the
    # reason (a str) why it is not; set by solve_contact
    separation_source: object = field(default=None, repr=False, compare=False)
    _derived: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self):
        pending = {name: self.__dict__[name] for name in _DEFERRABLE
                   if isinstance(self.__dict__.get(name), Deferred)}
        if pending:
            # removed from the instance: the first read goes to __getattr__, which computes
            # and keeps the value (bitwise what an eager solve stores)
            object.__setattr__(self, "_pending", pending)
            for name in pending:
                object.__delattr__(self, name)

    def __getattr__(self, name):
        pending = self.__dict__.get("_pending")
        if pending is not None and name in pending:
            d = pending[name]
            value = d.func(*d.args)
            object.__setattr__(self, name, value)
            pending.pop(name, None)
            return value
        raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")

    def _separation_result(self):
        src = self.separation_source
        if isinstance(src, str) or src is None:
            raise ValueError(src or "this result carries no scene for the separation")
        if "separation" not in self._derived:
            u, k, energy, seconds = src(np.asarray(self.pressure, dtype=float))
            self.timings["separation"] = seconds
            self._derived["separation"] = (u, k, energy)
        return self._derived["separation"]

    @property
    def separation(self) -> np.ndarray:
        """Mean interfacial separation u(p), computed on first access (see the class
        docstring). [m]"""
        return self._separation_result()[0]

    @property
    def stiffness(self) -> np.ndarray:
        """Contact stiffness K = -dp/du per nominal area (see the class docstring). [Pa/m]"""
        return self._separation_result()[1]

    @property
    def elastic_energy(self) -> np.ndarray:
        """Stored elastic energy U_el per nominal area at zeta = 1. [J/m^2]"""
        if self.elastic_energy_zeta is not None:
            return np.asarray(self.elastic_energy_zeta)[:, 0]
        return self._separation_result()[2]

    def __repr__(self) -> str:
        """A few lines (method, shapes, status, ranges), not every array."""
        n_p, n_z = np.size(self.pressure), np.size(self.zeta)
        lines = [
            f"<ContactResult: method={self.method!r}, success={self.success}, "
            f"message={self.message!r}",
            f"  pressure        {_span(self.pressure, 'Pa')}",
            f"  zeta            {_span(self.zeta)} (profiles area_zeta, sigma_a, "
            f"gamma_eff: ({n_p}, {n_z}))",
            f"  area            A(zeta1)/A0: {_span(self.area)}",
        ]
        if self.iterations is not None:          # the adhesive solver's extra fields
            sticky = int(np.count_nonzero(self.sticky)) if self.sticky is not None else 0
            sa1 = np.asarray(self.sigma_a)[:, 0] if n_p and n_z else np.zeros(0)
            residual = self.residual if self.residual is not None else np.zeros(0)
            lines.append(f"  sigma_a(zeta=1) {_span(sa1, 'Pa')}; sticky at {sticky} of {n_p}")
            lines.append(f"  fixed point     iterations max {_largest(self.iterations):.0f}; "
                         f"residual max {_largest(residual):.3g}")
        if self.theory != "persson01":
            lines.append(f"  theory          {self.theory} (gamma = {self.theory_gamma:.6g})")
        if self.hardness is not None:
            h = (f"{self.hardness:.6g} Pa" if isinstance(self.hardness, float)
                 else repr(self.hardness))
            lines.append(f"  yield wall      hardness {h}; area = elastic + plastic; "
                         f"plastic_area {_span(self.plastic_area)}")
        lines.append(f"  error_estimate  max {_largest(self.error_estimate):.3g}; "
                     f"timings: {_timings(self.timings)}>")
        return "\n".join(lines)
