"""Compiled one-pressure solves to call from your own ``@numba.njit`` code.

Everything here takes plain float64 arrays and scalars and runs in nopython mode, so a
simulation kernel can ask for the contact area at each of its nodes without returning to
Python. The Python side builds the scene arrays once (validated); the compiled side only
calls.

No adhesion, a prescribed wall (any consistent stress unit, e.g. Pa and Pa^2)::

    import numba, numpy as np, persson_fast as pf
    from persson_fast import embed

    G = pf.seed_scene().diffusion_time(q, e_star)       # (n,), G[0] >= 0
    sigma_a = np.zeros_like(G)

    @numba.njit
    def areas(G, sigma_a, local_pressure, rtol):
        out = np.empty(local_pressure.size)
        for i in range(local_pressure.size):
            out[i], status = embed.diffusion_area(G, sigma_a, local_pressure[i], rtol)
        return out

With adhesion::

    scene = embed.adhesive_scene(surface, e_star=e_star, work_of_adhesion=0.06, rtol=1e-4)

    @numba.njit
    def areas(scene, local_pressure, rtol):
        out = np.empty(local_pressure.size)
        for i in range(local_pressure.size):
            out[i], status = embed.adhesive_area(scene, local_pressure[i], rtol)
        return out

Elastoplastic, a yield wall at sigma_y(G) beside the detachment wall (the "strip" solver,
error-controlled in the real area A_el + A_pl)::

    @numba.njit
    def plastic(G, sigma_a, sigma_y, local_pressure, rtol):
        out = np.empty(local_pressure.size)
        for i in range(local_pressure.size):
            a_el, a_pl, status = embed.elastoplastic_area(G, sigma_a, sigma_y,
                                                          local_pressure[i], rtol)
            out[i] = a_pl
        return out

A contact law p(u), K(u) of a scene without adhesion (the mean interfacial separation u of
:func:`persson_fast.solve_separation`), tabulated once with error control::

    law = embed.contact_law(surface, e_star=e_star, rtol=1e-8)     # a ContactLaw
    table = law.table                                                # pass this to njit code

    @numba.njit
    def gap_pressure(table, gaps):
        out = np.empty(gaps.size)
        for i in range(gaps.size):
            out[i], status = embed.law_pressure(table, gaps[i])      # or law_stiffness,
        return out                                   # law_pressure_stiffness, law_separation

``law.to_csv(path)`` and ``law.to_xarray()`` export the nodes for other codes
(:mod:`persson_fast.separation.contact_law` says how to interpolate them). Status 18
(``BAD_SEPARATION``): u not finite or <= 0; 19 (``LAW_EXTRAPOLATED``): u below the table;
21 (``BAD_LAW``): the table is not one ``contact_law`` can have built (module table below),
and p, K, u are NaN. Each call checks the whole table (one pass over its n nodes, O(n): a
few hundred nodes at rtol 1e-6 to 1e-8), so for many separations at once ``law_sweep(table,
gaps, out_p, out_k, out_status)`` checks it once and evaluates them all; ``law_status(table)``
is the check alone.

A non-zero status is one of :mod:`persson_fast._kernels.status` (``STATUS_MESSAGES`` says
what it means); check it as you would a result's ``status``. ``adhesive_area`` is the fixed
point of :func:`persson_fast.solve_contact` on two nested grids, Richardson-extrapolated,
without its a-posteriori error control.

Every entry point checks its arguments first (O(n) reads, no allocation; valid input gives
bitwise the results of the raw kernels). A bad argument solves nothing: the area is NaN
(``diffusion_solve`` fills all its outputs with NaN) and the status names the argument --
the first failing row of this table:

============  ====  ======================================================================
status        code  rule broken
============  ====  ======================================================================
BAD_RTOL      11    ``rtol`` finite and in [RTOL_MIN, RTOL_MAX] = [1e-12, 0.1] (the range
                    of the Python layer)
BAD_PRESSURE  10    ``sigma0`` / ``pressure`` finite (any sign)
BAD_G         12    ``G``: at least one point, finite, ``G[0] >= 0``, non-decreasing
BAD_SIGMA_A   13    ``sigma_a``: the length of ``G``, finite (``elastoplastic_area``: and no
                    jump, a repeated G with different values)
BAD_SIGMA_Y   20    ``elastoplastic_area`` only: ``sigma_y`` of G's length, finite, no jump,
                    ``sigma_a + sigma_y > 0`` at every G
BAD_PRESSURE  10    ``elastoplastic_area``: also ``-sigma_a[0] < sigma0 < sigma_y[0]``
BAD_INPUT     5     ``diffusion_solve`` only: ``n_damp >= 0`` and every output of G's length
BAD_SCENE     14    ``adhesive_area`` only: ``scene`` as :func:`adhesive_scene` builds it --
                    each grid's G at least 2 points, finite, ``G[0] >= 0``, non-decreasing;
                    c of G's length, wa and wb one shorter, all finite and >= 0; the energy
                    correction finite and <= 1 (< 0: S = 1); the stress scale finite, > 0
BAD_LAW       21    ``law_*`` only: ``table`` as :func:`contact_law` builds it -- five
                    arrays of one length n >= 2, ln u strictly increasing and ln p strictly
                    decreasing (both logarithms of doubles, in [-746, 710]), d ln p/d ln u
                    < 0, ln K and d ln K/d ln u finite, ln K = ln p - ln u + ln(-d ln p/d
                    ln u) (K = -dp/du; at 5 nodes, the ends included), every interval
                    monotone (Fritsch-Carlson); checked before the separation or pressure.
                    Any swap or other permutation of the five arrays breaks a rule; a wrong
                    d ln K/d ln u array (finite) or a table of another scene cannot be seen.
                    Arrays other than 1-D float64 (a float32 copy) do not compile: numba
                    raises a TypingError that says so (``ContactLaw``'s methods: ValueError)
BAD_INPUT     5     ``law_sweep`` only: outputs of another length than the separations
============  ====  ======================================================================

The codes are importable as ``persson_fast._kernels.status.BAD_RTOL`` etc. (integers, so
your ``@njit`` code can compare with them).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # names of the type hints only
    from .scene import Scene
    from .surfaces.base import Surface

import math

import numpy as np

from ._jit import njit_serial as _njit_serial
from ._kernels import status as _status
from ._kernels.adhesion import DEFAULT_M_HIST as _DEFAULT_M_HIST
from ._kernels.adhesion import DEFAULT_MAX_ITER as _DEFAULT_MAX_ITER
from ._kernels.adhesion import DEFAULT_N_DAMP as _DEFAULT_N_DAMP
from ._kernels.adhesion import DEFAULT_OMEGA as _DEFAULT_OMEGA
from ._kernels.adhesion import solve_adhesive_one as _solve_adhesive_one
from ._kernels.contact_law import (law_pressure, law_pressure_stiffness, law_separation,
                                   law_status, law_stiffness, law_sweep)
from ._kernels.similarity import solve_one as _solve_one
from ._kernels.strip import N_DAMP as _STRIP_N_DAMP
from ._kernels.strip import solve_strip as _solve_strip
from .adhesion.zeta_grid import _scene_arrays
from .adhesion.zeta_grid import adhesion_zeta as _adhesion_zeta
from .adhesion.zeta_grid import refine_zeta as _refine_zeta
from .separation.contact_law import ContactLaw, contact_law
from .scene import DETACHMENT_PREFACTOR as _DETACHMENT_PREFACTOR

__all__ = ["diffusion_area", "diffusion_solve", "elastoplastic_area", "adhesive_scene", "adhesive_area",
           "contact_law", "ContactLaw", "law_pressure", "law_stiffness",
           "law_pressure_stiffness", "law_separation", "law_status", "law_sweep",
           "STATUS_MESSAGES", "RTOL_MIN", "RTOL_MAX"]

STATUS_MESSAGES = _status.STATUS_MESSAGES

#: the tolerances the entry points accept (those of the Python layer's ``_check_rtol``)
RTOL_MIN = 1e-12
RTOL_MAX = 0.1


@_njit_serial
def _rtol_ok(rtol):
    return RTOL_MIN <= rtol <= RTOL_MAX      # False for NaN


@_njit_serial
def _times_ok(G, n_min):
    """G holds >= n_min points, G[0] >= 0, non-decreasing, finite (False for any NaN)."""
    n = G.shape[0]
    if n < n_min or n == 0 or not G[0] >= 0.0:
        return False
    for k in range(1, n):
        if not G[k] >= G[k - 1]:
            return False
    return G[n - 1] < math.inf


@_njit_serial
def _finite_ok(x, n, lower):
    """x holds n finite values, each >= lower (-inf: any)."""
    if x.shape[0] != n:
        return False
    for k in range(n):
        if not (x[k] >= lower and x[k] < math.inf):
            return False
    return True


@_njit_serial
def _diffusion_args_status(G, sigma_a, sigma0, rtol):
    """The first failing argument rule of a diffusion solve (see the module table), or 0."""
    if not _rtol_ok(rtol):
        return _status.BAD_RTOL
    if not math.isfinite(sigma0):
        return _status.BAD_PRESSURE
    if not _times_ok(G, 1):
        return _status.BAD_G
    if not _finite_ok(sigma_a, G.shape[0], -math.inf):
        return _status.BAD_SIGMA_A
    return _status.OK


@_njit_serial
def diffusion_solve(G: np.ndarray, sigma_a: np.ndarray, sigma0: float, rtol: float,
                    n_damp: int, out_area: np.ndarray, out_load: np.ndarray,
                    out_detached_area: np.ndarray, out_detached_load: np.ndarray,
                    out_error: np.ndarray) -> int:
    """The one-pressure diffusion solve, every output an (n,) array written in place.

    The "cn" kernel (``persson_fast._kernels.similarity.solve_one``) with every output of
    :func:`persson_fast.solve_diffusion` for one pressure. The arguments are checked first
    (the table of this module's docstring): on a bad one every output is filled with NaN
    and its code returned.

    Parameters
    ----------
    G : numpy.ndarray, shape (n,)
        Diffusion times, non-decreasing, G[0] >= 0. [stress^2]
    sigma_a : numpy.ndarray, shape (n,)
        The detachment stress at G: the wall sits at -sigma_a, linear between the
        points. [stress]
    sigma0 : float
        Nominal stress (any sign; at or below -sigma_a[0] the area is 0). [stress]
    rtol : float
        Target relative accuracy of the area, in [RTOL_MIN, RTOL_MAX]. [-]
    n_damp : int
        Implicit-Euler half steps after a wall jump (Rannacher damping), >= 0 (2 is the
        default of the Python layer). [-]
    out_area, out_load, out_detached_area, out_detached_load, out_error : numpy.ndarray
        Outputs of shape (n,), written in place: A(G)/A0, the load in contact, the detached
        area and load, and the error estimate of the area. [-], [stress], [-], [stress], [-]

    Returns
    -------
    int
        The status (0 ok; see ``STATUS_MESSAGES``).

    See Also
    --------
    persson_fast.embed.diffusion_area : The area alone.
    persson_fast.solve_diffusion : The same from Python.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> from persson_fast import embed
    >>> G = np.linspace(0.0, 1.0, 11)
    >>> outs = [np.empty(G.size) for _ in range(5)]
    >>> embed.diffusion_solve(G, np.zeros_like(G), 1.0, 1e-6, 2, *outs)
    0
    >>> print(np.round(outs[0][[0, -1]], 6))
    [1.     0.5205]
    """
    s = _diffusion_args_status(G, sigma_a, sigma0, rtol)
    n = G.shape[0]
    if s == _status.OK and (n_damp < 0 or out_area.shape[0] != n or out_load.shape[0] != n
                            or out_detached_area.shape[0] != n
                            or out_detached_load.shape[0] != n or out_error.shape[0] != n):
        s = _status.BAD_INPUT
    if s != _status.OK:
        out_area[:] = np.nan
        out_load[:] = np.nan
        out_detached_area[:] = np.nan
        out_detached_load[:] = np.nan
        out_error[:] = np.nan
        return s
    return _solve_one(G, sigma_a, sigma0, rtol, n_damp, out_area, out_load,
                      out_detached_area, out_detached_load, out_error)


@_njit_serial
def diffusion_area(G: np.ndarray, sigma_a: np.ndarray, sigma0: float,
                   rtol: float) -> tuple[float, int]:
    """(A(G[-1]) / A0, status) of one pressure with the wall at -sigma_a(G).

    Any consistent units: stress and sqrt(G) alike (e.g. Pa and Pa^2).

    Parameters
    ----------
    G : numpy.ndarray, shape (n,)
        Diffusion times, non-decreasing, G[0] >= 0. [stress^2]
    sigma_a : numpy.ndarray, shape (n,)
        The detachment stress at G, linear between the points (zeros: no adhesion). [stress]
    sigma0 : float
        Nominal stress (any sign; at or below -sigma_a[0] the area is 0). [stress]
    rtol : float
        Target relative accuracy of the area, in [RTOL_MIN, RTOL_MAX]. [-]

    Returns
    -------
    area : float
        A(G[-1])/A0; NaN for a bad argument. [-]
    status : int
        0 ok, else a code of ``STATUS_MESSAGES`` (the argument codes in the table of this
        module's docstring).

    See Also
    --------
    persson_fast.embed.diffusion_solve : Every output of the solve.
    persson_fast.embed.elastoplastic_area : With a yield wall.
    persson_fast.solve_diffusion : The same from Python, many pressures.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> from persson_fast import embed
    >>> G = np.linspace(0.0, 1.0, 11)
    >>> area, status = embed.diffusion_area(G, np.zeros_like(G), 1.0, 1e-6)
    >>> print(f"{area:.6f}", status)
    0.520500 0
    >>> print(f"{pf.images_area(1.0, 1.0):.6f}")
    0.520500
    """
    s = _diffusion_args_status(G, sigma_a, sigma0, rtol)
    if s != _status.OK:
        return np.nan, s
    n = G.shape[0]
    a = np.empty(n)
    ld = np.empty(n)
    da = np.empty(n)
    dl = np.empty(n)
    er = np.empty(n)
    s = _solve_one(G, sigma_a, sigma0, rtol, 2, a, ld, da, dl, er)
    return a[n - 1], s


@_njit_serial
def _no_jump(G, v):
    for k in range(1, G.shape[0]):
        if G[k] == G[k - 1] and v[k] != v[k - 1]:
            return False
    return True


@_njit_serial
def _elastoplastic_args_status(G, sigma_a, sigma_y, sigma0, rtol):
    """The first failing argument rule of a two-wall solve (see the module table), or 0."""
    s = _diffusion_args_status(G, sigma_a, sigma0, rtol)
    if s != _status.OK:
        return s
    n = G.shape[0]
    if not _no_jump(G, sigma_a):
        return _status.BAD_SIGMA_A
    if not _finite_ok(sigma_y, n, -math.inf) or not _no_jump(G, sigma_y):
        return _status.BAD_SIGMA_Y
    for k in range(n):
        if not sigma_a[k] + sigma_y[k] > 0.0:
            return _status.BAD_SIGMA_Y
    if not (-sigma_a[0] < sigma0 < sigma_y[0]):
        return _status.BAD_PRESSURE
    return _status.OK


@_njit_serial
def elastoplastic_area(G: np.ndarray, sigma_a: np.ndarray, sigma_y: np.ndarray,
                       sigma0: float, rtol: float) -> tuple[float, float, int]:
    """(A_el, A_pl, status) at G[-1] of one pressure between two walls.

    The detachment wall sits at -sigma_a(G), the yield wall at sigma_y(G); the real contact
    area is A_el + A_pl. The same solver as ``solve_diffusion(..., sigma_y=...,
    method="strip")``, error-controlled in A_el + A_pl. Any consistent units: stress and
    sqrt(G) alike.

    Parameters
    ----------
    G : numpy.ndarray, shape (n,)
        Diffusion times, non-decreasing, G[0] >= 0. [stress^2]
    sigma_a : numpy.ndarray, shape (n,)
        The detachment stress at G, linear between the points, no jumps. [stress]
    sigma_y : numpy.ndarray, shape (n,)
        The yield stress at G, linear between the points, no jumps, with
        sigma_a + sigma_y > 0. [stress]
    sigma0 : float
        Nominal stress, strictly between the walls at G[0]. [stress]
    rtol : float
        Target relative accuracy of the real area, in [RTOL_MIN, RTOL_MAX]. [-]

    Returns
    -------
    elastic : float
        A_el(G[-1])/A0; NaN for a bad argument. [-]
    plastic : float
        A_pl(G[-1])/A0, the yielded area; NaN for a bad argument. [-]
    status : int
        0 ok, else a code of ``STATUS_MESSAGES``.

    See Also
    --------
    persson_fast.plastic_area : The closed form of a constant yield stress.
    persson_fast.solve_diffusion : The same from Python (``sigma_y``).

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> from persson_fast import embed
    >>> G = np.linspace(0.0, 1.0, 11)
    >>> el, pl, status = embed.elastoplastic_area(G, np.zeros_like(G), np.full(G.size, 2.0),
    ...                                           1.0, 1e-6)
    >>> print(f"{el:.5f} {pl:.5f}", status)
    0.10798 0.44601 0
    >>> print(np.round(pf.plastic_area(1.0, 1.0, 2.0), 5))
    [0.10798 0.44601]
    """
    s = _elastoplastic_args_status(G, sigma_a, sigma_y, sigma0, rtol)
    if s != _status.OK:
        return np.nan, np.nan, s
    n = G.shape[0]
    el = np.empty(n)
    ld = np.empty(n)
    pl = np.empty(n)
    pll = np.empty(n)
    da = np.empty(n)
    dl = np.empty(n)
    er = np.empty(n)
    counts = np.zeros(3, dtype=np.int64)
    s = _solve_strip(G, sigma_a, sigma_y, sigma0, rtol, -1, _STRIP_N_DAMP, el, ld, pl, pll,
                     da, dl, er, counts)
    return el[n - 1], pl[n - 1], s


def adhesive_scene(surface: Surface | Scene, *, e_star: float | None = None,
                   work_of_adhesion: float | None = None,
                   energy_correction: float | None = None,
                   detachment_prefactor: float = _DETACHMENT_PREFACTOR,
                   rtol: float = 1e-6) -> tuple:
    """The plain-array scene of :func:`adhesive_area` (validated, built once in Python).

    Parameters
    ----------
    surface : Surface or Scene
        The rough surface (with the keywords below), or a :class:`~persson_fast.Scene`
        with adhesion and without a hardness.
    e_star : float
        Effective modulus E* > 0 (with a surface). [Pa]
    work_of_adhesion : float
        Delta gamma > 0 (with a surface). [J/m^2]
    energy_correction : float or None
        gamma_S of S = gamma_S + (1 - gamma_S) P^2, in [0, 1]; None: S = 1. [-]
    detachment_prefactor : float
        beta of seed Eq. 8 (default 1/sqrt 2). [-]
    rtol : float
        The tolerance the magnification grids are made for (``adhesion_zeta(surface,
        rtol)`` and its refinement), in [1e-12, 0.1]. [-]

    Returns
    -------
    tuple
        (G, c, wa, wb, G_fine, c_fine, wa_fine, wb_fine, gamma_s, scale): the scaled kernel
        inputs on the two nested grids, gamma_s (< 0 for S = 1) and the stress scale [Pa].

    Raises
    ------
    ValueError
        For bad input (as :func:`persson_fast.solve_contact`), a ``work_of_adhesion``
        that is not > 0, or a Scene with a yield wall.

    See Also
    --------
    persson_fast.embed.adhesive_area : Solves one pressure of the scene.
    persson_fast.solve_contact : The same with error control, from Python.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> from persson_fast import embed
    >>> scene = embed.adhesive_scene(pf.seed_scene(), e_star=pf.seed_e_star(),
    ...                              work_of_adhesion=0.06, rtol=1e-3)
    >>> len(scene)
    10
    """
    from .scene import _check_rtol, _check_scene_args, unpack_adhesive_scene

    surface, kw = unpack_adhesive_scene(surface, e_star, work_of_adhesion, energy_correction,
                                        detachment_prefactor, "adhesive_scene")
    e_star, work_of_adhesion = kw["e_star"], kw["work_of_adhesion"]
    energy_correction, detachment_prefactor = kw["energy_correction"], kw["detachment_prefactor"]

    rtol = _check_rtol(rtol)
    e, dg, beta = _check_scene_args(surface, e_star, work_of_adhesion, detachment_prefactor,
                                    energy_correction)
    if dg <= 0:
        raise ValueError(f"work_of_adhesion must be > 0 [J/m^2] for an adhesive scene; got "
                         f"work_of_adhesion = {work_of_adhesion!r} (use diffusion_area without "
                         "adhesion)")
    zeta = _adhesion_zeta(surface, rtol)
    Gc, cc, wac, wbc, scale, _ = _scene_arrays(surface, zeta, e, dg, beta)
    # the nested grids share their end points, hence the stress scale
    Gf, cf, waf, wbf, _, _ = _scene_arrays(surface, _refine_zeta(zeta), e, dg, beta)
    gamma_s = -1.0 if energy_correction is None else float(energy_correction)
    return (Gc, cc, wac, wbc, Gf, cf, waf, wbf, gamma_s, float(scale))


@_njit_serial
def _fixed_point_area(G, c, wa, wb, gamma_s, sigma0, rtol):
    n = G.shape[0]
    x0 = np.full(n, -1.0)
    outs = np.empty((8, n))
    s, it, res = _solve_adhesive_one(0, G, c, wa, wb, gamma_s, sigma0, rtol,
                                     _DEFAULT_N_DAMP, _DEFAULT_MAX_ITER, _DEFAULT_M_HIST,
                                     _DEFAULT_OMEGA, x0, outs[0], outs[1], outs[2], outs[3],
                                     outs[4], outs[5], outs[6], outs[7])
    return outs[0, n - 1], s


@_njit_serial
def _scene_grid_ok(G, c, wa, wb):
    """One grid of a scene: G of >= 2 points (as _times_ok), c (n,), wa, wb (n - 1,), all
    finite and >= 0."""
    n = G.shape[0]
    return (_times_ok(G, 2) and _finite_ok(c, n, 0.0) and _finite_ok(wa, n - 1, 0.0)
            and _finite_ok(wb, n - 1, 0.0))


@_njit_serial
def _adhesive_args_status(scene, pressure, rtol):
    """The first failing argument rule of adhesive_area (see the module table), or 0."""
    Gc, cc, wac, wbc, Gf, cf, waf, wbf, gamma_s, scale = scene
    if not _rtol_ok(rtol):
        return _status.BAD_RTOL
    if not math.isfinite(pressure):
        return _status.BAD_PRESSURE
    if not (_scene_grid_ok(Gc, cc, wac, wbc) and _scene_grid_ok(Gf, cf, waf, wbf)
            and gamma_s <= 1.0 and math.isfinite(gamma_s)
            and 0.0 < scale < math.inf):
        return _status.BAD_SCENE
    return _status.OK


@_njit_serial
def adhesive_area(scene: tuple, pressure: float, rtol: float) -> tuple[float, int]:
    """(A(zeta1) / A0, status) of one nominal pressure (tension < 0 allowed).

    The fixed point of seed Eqs. 8-9 on the scene's two nested grids, Richardson-
    extrapolated: the value :func:`persson_fast.solve_contact` returns from the same two
    grids, without its warm start of the fine grid and without its a-posteriori error
    control (no error estimate, no refinement beyond the two grids).

    Parameters
    ----------
    scene : tuple
        What :func:`adhesive_scene` returns.
    pressure : float
        Nominal pressure (tension < 0 allowed). [Pa]
    rtol : float
        Tolerance of the inner diffusion solves, in [RTOL_MIN, RTOL_MAX]. [-]

    Returns
    -------
    area : float
        A(zeta1)/A0; NaN for a bad argument. [-]
    status : int
        0 ok, else a code of ``STATUS_MESSAGES``.

    See Also
    --------
    persson_fast.embed.adhesive_scene : Builds its ``scene``.
    persson_fast.solve_contact : The same with error control, from Python.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> from persson_fast import embed
    >>> scene = embed.adhesive_scene(pf.seed_scene(), e_star=pf.seed_e_star(),
    ...                              work_of_adhesion=0.06, rtol=1e-3)
    >>> area, status = embed.adhesive_area(scene, 1e6, 1e-3)
    >>> print(f"{area:.3f}", status)
    0.495 0
    """
    s = _adhesive_args_status(scene, pressure, rtol)
    if s != _status.OK:
        return np.nan, s
    Gc, cc, wac, wbc, Gf, cf, waf, wbf, gamma_s, scale = scene
    p = pressure / scale
    ac, sc = _fixed_point_area(Gc, cc, wac, wbc, gamma_s, p, rtol)
    af, sf = _fixed_point_area(Gf, cf, waf, wbf, gamma_s, p, rtol)
    s = sf if sf != 0 else sc
    if (ac > 0.0) != (af > 0.0):
        return af, s
    a = (4.0 * af - ac) / 3.0
    if a < 0.0:
        a = 0.0
    elif a > 1.0:
        a = 1.0
    return a, s
