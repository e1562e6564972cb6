"""A pressure-separation contact law p(u), K(u) for other codes (no adhesion).

:func:`contact_law` tabulates the closed form of :mod:`persson_fast.separation` once per
scene and returns a :class:`ContactLaw`: its ``table`` is a tuple of three float64 arrays
that compiled code evaluates with :func:`persson_fast.embed.law_pressure`,
:func:`~persson_fast.embed.law_stiffness` or
:func:`~persson_fast.embed.law_pressure_stiffness` (inside a user's ``@numba.njit``), and
that :meth:`ContactLaw.to_csv` / :meth:`ContactLaw.to_xarray` export for codes outside
Python.

Every compiled function checks the table it is given before it reads it (the rules of
:func:`persson_fast._kernels.contact_law.law_status`: five arrays of one length, ln u
increasing, ln p decreasing, finite, ln K = ln p - ln u + ln(-d ln p/d ln u), every interval
monotone): a table that is not one this module builds gives NaN and status ``BAD_LAW`` (21),
never a number; so does every swap or other permutation of the five arrays (a wrong
d ln K/d ln u array alone, or a table of another scene, cannot be detected: the notes of
``law_status``). The arrays must be 1-D float64: a table of another dtype (a float32 copy)
does not compile (numba's ``TypingError`` says why) and :class:`ContactLaw`'s methods
refuse it with a ValueError. The check is one pass
over the nodes, so a call costs O(n) (184 nodes at rtol 1e-6 and 610 at 1e-8 on the
self-affine scene of ``benchmarks/bench_separation.py``, ~1,700 at 1e-10): there a call took
4-5x (rtol 1e-6) and 8x (1e-8) the time of the look-up alone (``test_law_call``, the
previous and this version side by side on one 2-core machine).
:func:`persson_fast.embed.law_sweep` evaluates many separations with one check.

Interpolation: ln p and ln K as cubic Hermite polynomials of v = ln u between nodes, with
the exact slopes d ln p/dv = -u K/p and d ln K/dv = (1 - d ln Q/d ln p) d ln p/dv (Q = p/K,
its derivative summed by the same kernel); ln p and ln K are smooth in ln u at both ends,
which they are not in u. The builder refines
the nodes (bisecting in ln p) until, at three points inside every interval (at 21 %, 50 %
and 79 % of its ln p span), both p and K of the interpolant are within rtol/4 of the closed
form, and every interval meets the Fritsch-Carlson condition (so p(u) is monotone and
K >= 0 everywhere). ``error_estimate`` is the largest relative error found at those checks.

Tails: above the table's largest separation (small pressures) ln p continues linearly with
the last node's exact slope: the law p ~ exp(-u/u0) that holds there; the table starts low
enough (``pressure_min``) that the slope has converged to rtol/8 (it approaches 1/u0
linearly in p). Below the smallest separation (pressures above ``pressure_max``, default
10 sqrt(G1), where u is ~1e-11 of the roughness) the law is a continuation and says so
(status ``LAW_EXTRAPOLATED``; the Python methods raise a ValueError).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # names of the type hints only
    from ..scene import Scene
    from ..surfaces.base import Surface

import math
from dataclasses import dataclass, field

import numpy as np

from .._io import write_text_atomic
from .._kernels.contact_law import (TABLE_TYPE_RULE, law_status, law_sweep, law_sweep_unchecked,
                                    table_type_problem)
from .._kernels.status import BAD_LAW, BAD_SEPARATION, LAW_EXTRAPOLATED, OK, STATUS_MESSAGES
from .._validation import as_float_array, check_finite, optional_import
from ..scene import _check_rtol
from .elastic import _evaluate, _scene, nodes_for

#: default upper end of the table, in units of sqrt(G1) (u there is ~1e-11 of u0)
PRESSURE_MAX_ROOT_G1 = 10.0
#: initial nodes per decade of pressure
NODES_PER_DECADE = 8
#: the interpolant is checked at these fractions of each interval's ln p span
CHECK_POINTS = (0.21, 0.5, 0.79)
#: refinement stops with an error beyond this many nodes
MAX_NODES = 200_000


@dataclass(frozen=True, repr=False)
class ContactLaw:
    """A tabulated p(u), K(u) of one scene without adhesion (see the module docstring).

    Attributes
    ----------
    table : tuple of five numpy.ndarray of float64, shape (n,)
        (ln u ascending [ln m], ln p [ln Pa], d ln p/d ln u [-], ln K [ln Pa/m],
        d ln K/d ln u [-]): pass it to the compiled ``embed.law_*`` functions (which
        refuse, with NaN and ``BAD_LAW``, a table that breaks the rules of
        ``embed.law_status``).
    separation, pressure, stiffness : numpy.ndarray, shape (n,)
        The nodes: u [m], p [Pa], K [Pa/m].
    rtol : float
        The tolerance the table was built to (relative, p and K). [-]
    error_estimate : float
        Largest relative error of p or K found at the checks. [-]
    pressure_min, pressure_max : float
        The table's pressure range. [Pa]
    decay_length : float
        u0 of p ~ exp(-u/u0) at small p. [m]
    scene : str
        The surface and parameters it was built for.
    info : dict
        How the table was built (nodes, refinements).

    See Also
    --------
    persson_fast.embed.contact_law : Builds a ContactLaw.
    persson_fast.embed.law_pressure : p(u) from numba code.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> from persson_fast import embed
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> law = embed.contact_law(s, e_star=1e9, rtol=1e-6)
    >>> u = pf.solve_separation(s, [1e6], e_star=1e9).separation[0]
    >>> print(f"{law.pressure_at(u):.5g} Pa")
    1e+06 Pa
    """

    table: tuple
    separation: np.ndarray
    pressure: np.ndarray
    stiffness: np.ndarray
    rtol: float
    error_estimate: float
    pressure_min: float
    pressure_max: float
    decay_length: float
    scene: str
    info: dict = field(default_factory=dict)

    # --- Python evaluation -------------------------------------------------------------------
    def evaluate(self, separation):
        """(p [Pa], K [Pa/m], status) at separations u [m], as compiled code gets them.

        Parameters
        ----------
        separation : array_like
            Mean interfacial separations u, any shape. [m]

        Returns
        -------
        tuple of numpy.ndarray
            p [Pa], K [Pa/m] and the status per value (0 ok, ``BAD_SEPARATION``,
            ``LAW_EXTRAPOLATED``; ``BAD_LAW`` everywhere when the table breaks a rule of
            ``law_status``), each of the shape of ``separation``.

        Raises
        ------
        ValueError
            If ``table`` is not a tuple of five 1-D float64 arrays (a float32 copy, say:
            the compiled functions refuse it when they compile), or ``separation`` is not
            real numbers.
        """
        problem = table_type_problem(self.table)
        if problem is not None:
            raise ValueError(f"{TABLE_TYPE_RULE}; got {problem}")
        u = as_float_array(separation, "separation", "m")
        flat = np.ascontiguousarray(u.reshape(-1))
        p = np.empty(flat.size)
        k = np.empty(flat.size)
        status = np.empty(flat.size, dtype=np.int64)
        law_sweep(self.table, flat, p, k, status)
        return p.reshape(u.shape), k.reshape(u.shape), status.reshape(u.shape)

    def _checked(self, separation, which: int):
        p, k, status = self.evaluate(separation)
        if np.any(status == BAD_LAW):
            raise ValueError(f"table: {STATUS_MESSAGES[BAD_LAW]}; got arrays of lengths "
                             f"{[int(np.size(a)) for a in self.table]}")
        for code in (BAD_SEPARATION, LAW_EXTRAPOLATED):
            if np.any(status == code):
                idx = int(np.argmax(np.reshape(status, -1) == code))
                got = float(np.reshape(np.asarray(separation, dtype=float), -1)[idx])
                rng = (f"; the table covers u >= {self.separation[0]!r} m (p <= "
                       f"{self.pressure_max!r} Pa)" if code == LAW_EXTRAPOLATED else "")
                raise ValueError(f"separation: {STATUS_MESSAGES[code]}{rng}; got "
                                 f"separation[{idx}] = {got!r}")
        out = (p, k)[which]
        return float(out) if out.ndim == 0 else out

    def pressure_at(self, separation):
        """p(u) [Pa] at separations u [m] > 0 inside the table or above it.

        Parameters
        ----------
        separation : array_like
            Mean interfacial separations u > 0, any shape. [m]

        Returns
        -------
        numpy.ndarray
            p(u), of the shape of ``separation``. [Pa]
        """
        return self._checked(separation, 0)

    def stiffness_at(self, separation):
        """K(u) = -dp/du [Pa/m] at separations u [m] (as :meth:`pressure_at`).

        Parameters
        ----------
        separation : array_like
            Mean interfacial separations u > 0, any shape. [m]

        Returns
        -------
        numpy.ndarray
            K(u), of the shape of ``separation``. [Pa/m]
        """
        return self._checked(separation, 1)

    # --- export --------------------------------------------------------------------------------
    def _header(self) -> list[str]:
        return [
            "# persson_fast contact law p(u), K(u) without adhesion "
            "(Persson, PRL 99, 125502 (2007))",
            f"# scene: {self.scene}",
            f"# {self.separation.size} nodes; between nodes ln p and ln K are the cubic "
            f"Hermite interpolants in ln u of the nodes' values and slopes; "
            f"relative error of p and K <= {self.error_estimate:.3g} (built to rtol "
            f"{self.rtol:.3g})",
            f"# above the largest u: ln p and ln K linear in u with slope "
            f"dlnp_dlnu/u of the last node (p ~ exp(-u/u0), K = p/u0, u0 = "
            f"{self.decay_length!r} m); below the smallest u (p > "
            f"{self.pressure_max!r} Pa): not covered",
        ]

    def to_csv(self, path) -> str:
        """Write the nodes to a CSV file (atomically; an existing file is replaced whole).

        Columns: ``ln_separation``, ``ln_pressure``, ``dlnp_dlnu``, ``ln_stiffness``,
        ``dlnK_dlnu`` (the interpolation data: ln p and ln K as cubic Hermite polynomials of
        ln u with these slopes), then ``separation [m]``, ``pressure [Pa]``, ``stiffness
        [Pa/m]`` at the nodes; comment lines (#) say
        how to interpolate and continue. Numbers are written with ``repr`` (they read back
        bit for bit).

        Parameters
        ----------
        path : str or os.PathLike
            The file; replaced if it exists.

        Returns
        -------
        str
            ``path``.
        """
        cols = [a.tolist() for a in self.table] + [self.separation.tolist(),
                                                   self.pressure.tolist(),
                                                   self.stiffness.tolist()]
        lines = self._header() + ["ln_separation [ln m],ln_pressure [ln Pa],dlnp_dlnu [-],"
                                  "ln_stiffness [ln Pa/m],dlnK_dlnu [-],"
                                  "separation [m],pressure [Pa],stiffness [Pa/m]"]
        lines += [",".join(repr(x) for x in row) for row in zip(*cols)]
        return write_text_atomic(path, "\n".join(lines) + "\n")

    def to_xarray(self):
        """The nodes as an ``xarray.Dataset`` on the coordinate ``separation`` [m], with
        ``pressure``, ``stiffness``, ``dlnp_dlnu``, ``dlnK_dlnu`` and the header as
        attributes (needs the
        ``scan`` or ``notebooks`` extra)."""
        xr = optional_import("xarray", "scan", "ContactLaw.to_xarray")
        dy, dz = self.table[2], self.table[4]
        return xr.Dataset(
            {"pressure": ("separation", self.pressure.copy(), {"units": "Pa"}),
             "stiffness": ("separation", self.stiffness.copy(), {"units": "Pa/m"}),
             "dlnp_dlnu": ("separation", dy.copy(), {"units": "1"}),
             "dlnK_dlnu": ("separation", dz.copy(), {"units": "1"})},
            coords={"separation": ("separation", self.separation.copy(), {"units": "m"})},
            attrs={"description": " ".join(line.lstrip("# ") for line in self._header()),
                   "rtol": self.rtol, "error_estimate": self.error_estimate,
                   "decay_length": self.decay_length, "pressure_max": self.pressure_max,
                   "pressure_min": self.pressure_min})

    def __repr__(self) -> str:
        return (f"<ContactLaw: {self.separation.size} nodes, p in [{self.pressure_min:.4g}, "
                f"{self.pressure_max:.4g}] Pa, u in [{self.separation[0]:.4g}, "
                f"{self.separation[-1]:.4g}] m; error <= {self.error_estimate:.2g} (rtol "
                f"{self.rtol:.2g}); u0 = {self.decay_length:.4g} m>")


def _hermite_ok(u, y, dy) -> np.ndarray:
    """Fritsch-Carlson monotonicity of each interval (True where the cubic is monotone)."""
    secant = np.diff(y) / np.diff(u)
    a = dy[:-1] / secant
    b = dy[1:] / secant
    return (a >= 0) & (b >= 0) & (a * a + b * b <= 9.0)


def _separation_ok(nodes, gamma_s: float, p: float) -> bool:
    """Whether u(p), Q = p/K and dQ/dp are representable at the pressure p [Pa] (status 0)."""
    with np.errstate(all="ignore"):
        *_, status = _evaluate(nodes, gamma_s, np.array([p]), slope=True)
    return int(status[0]) == OK


def _check_representable_top(nodes, gamma_s: float, p_hi: float, root_g1: float) -> None:
    """Refuse a ``pressure_max`` [Pa] at which the separation underflows double precision
    (u ~ exp(-p^2/(4 G1)) below ~1e-292 m, status ``SEPARATION_UNDERFLOW``): the table's
    ln u would be -inf there. The message gives the largest pressure that is representable,
    found by bisection in ln p above sqrt(G1) (where u is ~1e-1 of the roughness)."""
    if _separation_ok(nodes, gamma_s, p_hi):
        return
    lo, hi = math.log(root_g1), math.log(p_hi)
    if _separation_ok(nodes, gamma_s, root_g1):
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            if _separation_ok(nodes, gamma_s, math.exp(mid)):
                lo = mid
            else:
                hi = mid
    limit = math.exp(lo)
    raise ValueError(
        f"pressure_max must be at most {limit!r} for this scene [Pa]: above it (about "
        f"{limit / root_g1:.3g} sqrt(G1)) the mean separation u(p) ~ exp(-p^2/(4 G1)) "
        f"underflows double precision (below ~1e-292 m: the surfaces are in full contact to "
        f"rounding) and a table of ln u cannot reach it; got pressure_max = {p_hi!r}")


def contact_law(surface: Surface | Scene, *, e_star: float | None = None,
                energy_correction: float | None = None, rtol: float = 1e-6,
                pressure_max: float | None = None, work_of_adhesion: float = 0.0) -> ContactLaw:
    """Tabulate p(u) and K(u) of a scene without adhesion for compiled callers.

    Parameters
    ----------
    surface : Surface or Scene
        The roughness, or a Scene without adhesion and without a hardness.
    e_star : float
        Effective modulus E* > 0 (with a surface). [Pa]
    energy_correction : float or None
        gamma_S of S = gamma_S + (1 - gamma_S) P^2; None: S = 1. [-]
    rtol : float
        Relative accuracy of p and K between the nodes, in [1e-12, 0.1] (default 1e-6). [-]
    pressure_max : float or None
        Upper end of the table; default 10 sqrt(G1) (u there is ~1e-11 of the roughness).
        At most the pressure where u(p) underflows double precision (about 50 sqrt(G1));
        beyond it a ValueError gives that pressure. [Pa]
    work_of_adhesion : float
        Delta gamma; must be 0 (the default): the contact law is derived without adhesion
        only, and a value > 0 is a ValueError that says so. [J/m^2]

    Returns
    -------
    ContactLaw

    Raises
    ------
    ValueError
        For bad input (``e_star`` not > 0, ``rtol`` outside [1e-12, 0.1], a
        ``pressure_max`` below ten times the smallest pressure the scene resolves, a Scene
        with adhesion or a yield wall), naming the argument.

    See Also
    --------
    persson_fast.embed.ContactLaw : What it returns.
    persson_fast.embed.law_pressure : p(u) from numba code.
    persson_fast.solve_separation : u(p) and K(p) from Python.

    Notes
    -----
    See the module docstring for the interpolation, its error control and the tails. The
    closed form behind it is :func:`persson_fast.solve_separation` (relative accuracy
    ~1e-12); building a law took 14 ms at rtol 1e-6 and 37 ms at rtol 1e-8 on the
    self-affine scene of ``benchmarks/bench_separation.py`` (2-core Intel Xeon machine).

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> from persson_fast import embed
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> law = embed.contact_law(s, e_star=1e9, rtol=1e-6)
    >>> print(law.table[0].size > 10, law.rtol)
    True 1e-06
    """
    surface, e, gamma_s = _scene(surface, e_star, energy_correction, "contact_law",
                                 work_of_adhesion=work_of_adhesion)
    rtol = _check_rtol(rtol)
    nodes = nodes_for(surface, e)
    root_g1 = 0.5 / nodes.s_scale[0]
    u0 = gamma_s * float(np.sum(nodes.a_sep))
    if pressure_max is None:
        p_hi = PRESSURE_MAX_ROOT_G1 * root_g1
    else:
        arr = as_float_array(pressure_max, "pressure_max", "Pa", ndim=(0,))
        check_finite(arr, "pressure_max", "Pa")
        p_hi = float(arr)
        if not p_hi > 10.0 * nodes.pressure_floor:
            raise ValueError(f"pressure_max must be > {10.0 * nodes.pressure_floor!r} Pa (ten "
                             f"times the smallest resolved pressure of this scene); got "
                             f"pressure_max = {p_hi!r}")
        _check_representable_top(nodes, gamma_s, p_hi, root_g1)
    # the small-pressure end: where K u0 / p has converged to 1 within rtol / 8
    p_lo = min(1e-3 * root_g1, p_hi / 10.0)
    while True:
        _, q, _, _ = _evaluate(nodes, gamma_s, np.array([p_lo]))
        if abs(u0 / q[0] - 1.0) <= rtol / 8.0 or p_lo / 10.0 < 10.0 * nodes.pressure_floor:
            break
        p_lo /= 10.0
    tail_error = abs(u0 / q[0] - 1.0)
    n0 = max(2, int(math.ceil(math.log10(p_hi / p_lo) * NODES_PER_DECADE)) + 1)
    x = np.linspace(math.log(p_lo), math.log(p_hi), n0)
    theta = np.asarray(CHECK_POINTS)
    while True:
        p = np.exp(x)
        u, q, dq, _, _ = _evaluate(nodes, gamma_s, p, slope=True)
        order = np.argsort(u, kind="stable")
        u, q, dq, xs = u[order], q[order], dq[order], x[order]
        dy = -u / q                                  # d ln p / d ln u = -u K / p = -u / Q
        table = tuple(np.ascontiguousarray(a) for a in (
            np.log(u), xs, dy, xs - np.log(q),       # ln K = ln p - ln Q
            (1.0 - np.exp(xs) * dq / q) * dy))       # d ln K/d ln u = (1 - d ln Q/d ln p) dy
        if np.any(np.diff(table[0]) <= 0) or not np.all(u > 0):
            raise RuntimeError("contact_law: the separations of the nodes are not strictly "
                               "decreasing in p (a bug: please report the scene)")
        xc = (x[:-1, None] + (x[1:] - x[:-1])[:, None] * theta[None, :]).ravel()
        uc, qc, _, _ = _evaluate(nodes, gamma_s, np.exp(xc))
        p_int = np.empty(xc.size)
        k_int = np.empty(xc.size)
        status = np.empty(xc.size, dtype=np.int64)
        law_sweep_unchecked(table, uc, p_int, k_int, status)
        err_p = np.abs(p_int / np.exp(xc) - 1.0)
        err_k = np.abs(k_int * qc / np.exp(xc) - 1.0)        # K = p / Q
        err = np.maximum(err_p, err_k).reshape(-1, theta.size).max(axis=1)
        monotone = _hermite_ok(*table[:3])
        # intervals in x order: table is in u order (x descending), so flip
        bad = (err > rtol / 4.0) | ~monotone[::-1]
        if not np.any(bad):
            break
        if x.size + np.count_nonzero(bad) > MAX_NODES:
            raise RuntimeError(f"contact_law: more than {MAX_NODES} nodes needed for rtol = "
                               f"{rtol!r} (largest error {err.max():.3g}); use a larger rtol")
        mids = 0.5 * (x[:-1] + x[1:])[bad]
        x = np.sort(np.concatenate([x, mids]))
    if law_status(table) != OK:
        raise RuntimeError("contact_law: the finished table breaks a rule of law_status (a "
                           "bug: please report the scene)")
    v_n, y_n, dy_n, z_n, _ = table
    u_n = np.exp(v_n)
    p_n = np.exp(y_n)
    return ContactLaw(
        table=table, separation=u_n, pressure=p_n, stiffness=np.exp(z_n), rtol=rtol,
        error_estimate=float(max(err.max(), tail_error)), pressure_min=float(p_n[-1]),
        pressure_max=float(p_n[0]), decay_length=u0,
        scene=f"{surface!r}, e_star = {e!r} Pa, energy_correction = "
              f"{None if gamma_s == 1.0 else gamma_s!r}",
        info={"tail_slope_error": tail_error, "pressure_floor": nodes.pressure_floor})
