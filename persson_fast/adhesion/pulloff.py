"""The pull-off stress: the contact branch of one adhesive scene followed to its end.

:func:`pull_off` follows the contact branch (of the original theory, of the corrected
theories yp08 and wm17, and with a yield wall) parametrised by y0 = sigma0 + sigma_a(1) (at
fixed sigma0 the fixed point of seed Eqs. 8-9 is nearly singular along the flat end of the
branch; at fixed y0 it is regular), with a fixed-point loop in Python around the compiled
diffusion solve (one scene, a few dozen branch points: the loop is not the cost), on nested
zeta grids with Richardson extrapolation.

This module holds :func:`pull_off`, its grids and its error estimate; the contact branch on
one grid and the descent along it are in :mod:`persson_fast.adhesion.branch`, whose names
are re-exported here (``persson_fast.adhesion.pulloff.<name>`` keeps working).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # names of the type hints only
    from collections.abc import Callable

    from numpy.typing import ArrayLike

    from ..scene import Scene
    from ..surfaces.base import Surface

import time
from dataclasses import replace

import numpy as np

from .._kernels.status import GRID_CAP, RTOL_NOT_MET, STATUS_MESSAGES, WALL_JUMP
from .fixed_point import solve_adhesive_contact
from .runner import ADHESION_DEFAULTS, THEORY_CODES, _controls
from ..methods import choose_auto, variant_of
from ..scene import DETACHMENT_PREFACTOR
from .zeta_grid import NEAR_ONE_MIN, adhesion_zeta, refine_zeta
from .branch import (PULL_OFF_BLOWUP, PULL_OFF_COLLAPSE, PULL_OFF_EARLY,
                             PULL_OFF_INNER, PULL_OFF_INNER_LOOSE, PULL_OFF_INNER_MIN,
                             PULL_OFF_INNER_RTOLS, PULL_OFF_LOOSE,
                             PULL_OFF_MAX_FOLD_STEPS, PULL_OFF_MAX_ITER, PULL_OFF_MAX_STAGES,
                             PULL_OFF_REST_ITER, PULL_OFF_RESIDUAL, PULL_OFF_RETRY,
                             PULL_OFF_STALL, PULL_OFF_STEP, PULL_OFF_TAIL, PULL_OFF_TRUST,
                             _AndersonHistory, _Branch, _descend, _replay, _rest_start)

__all__ = ["pull_off",
           # re-exported from pulloff_branch (persson_fast.adhesion.pulloff.<name> as before the split)
           "PULL_OFF_STEP", "PULL_OFF_TAIL", "PULL_OFF_INNER", "PULL_OFF_INNER_LOOSE",
           "PULL_OFF_INNER_RTOLS", "PULL_OFF_INNER_MIN",
           "PULL_OFF_EARLY", "PULL_OFF_RESIDUAL", "PULL_OFF_TRUST", "PULL_OFF_RETRY",
           "PULL_OFF_MAX_ITER", "PULL_OFF_STALL", "PULL_OFF_BLOWUP", "PULL_OFF_MAX_STAGES",
           "PULL_OFF_MAX_FOLD_STEPS", "PULL_OFF_LOOSE", "PULL_OFF_COLLAPSE",
           "PULL_OFF_REST_ITER", "_AndersonHistory"]

#: nested zeta grids: at least 3 (two Richardson values to compare), at most this many
PULL_OFF_MAX_GRIDS = 5
#: relaxation of the branch follower's Anderson steps (and of its compiled rest-state solve):
#: half steps (seed scene, rtol 1e-4: 134 iterations against 139 with whole steps, the same
#: pull-off stress within 0.5 Pa, its error estimate 39 Pa)
PULL_OFF_OMEGA = 0.5
#: the inner-solve error is measured by re-solving the end point with a tolerance this
#: factor tighter (looser where that would pass PULL_OFF_INNER_MIN); it is never taken below
#: PULL_OFF_INNER_FLOOR * sigma_c: the diffusion kernel's result does not converge
#: monotonically in its tolerance (one application of Eqs. 8-9 at the end of the seed
#: scene's branch scattered by +-0.11 Pa of 7.8e5 Pa between tolerances 3e-8 and 3e-10, and
#: the branch's end moved by 0.64 Pa between 1.25e-8 and 3.1e-9), so one comparison can
#: come out small by chance
PULL_OFF_INNER_CHECK = 4.0
PULL_OFF_INNER_FLOOR = 5e-7
#: weight of the error of a branch point flagged RTOL_NOT_MET in sigma_c (|4/3| + |1/3|,
#: its largest weight in a Richardson value)
PULL_OFF_FLAG_WEIGHT = 5.0 / 3.0
#: resolution of the optional bracket of where solve_contact stops finding contact
PULL_OFF_BRACKET_RTOL = 1e-4
#: the near-one points of the pull-off grids reach down to where sqrt(G) is this fraction
#: of the full-contact sigma_a(1) (never below zeta - 1 = PULL_OFF_NEAR_FLOOR): the layer
#: near the end of the branch sits at sqrt(G) ~ y0 / 20 and y0 ~ 1e-4 sigma_a(1) there
PULL_OFF_NEAR_STRESS = 1e-6
PULL_OFF_NEAR_FLOOR = 1e-14
#: the finer grids are solved at y0 = y_best * PULL_OFF_STEP**PULL_OFF_GRID_STAGES
PULL_OFF_GRID_STAGES = 2
#: a scene counts as not sticky only when it is not sticky on this many nested zeta grids
#: (the coarsest and its refinements, the fewest pull_off extrapolates over): the threshold
#: work of adhesion falls with the grid spacing at second order (seed scene: 0.052176,
#: 0.051903, 0.051833, 0.051816, 0.051811 J/m^2 at 5, 10, 20, 40, 80 points per decade)
PULL_OFF_STICKY_GRIDS = 3


def _near_one_min(surface, e_star, work_of_adhesion, beta):
    """Smallest zeta - 1 of the near-one points of the pull-off grids. [-]

    Close to pull-off an absorbing layer forms where sqrt(G) is a small fraction of
    y0 = sigma0 + sigma_a(1), and y0 at the end of the branch is a small fraction of
    sigma_a(1); the near-one points must reach down to where sqrt(G) is
    ``PULL_OFF_NEAR_STRESS`` times the full-contact sigma_a(1) (at most ``NEAR_ONE_MIN``).
    """
    target = PULL_OFF_NEAR_STRESS * beta * np.sqrt(work_of_adhesion * e_star * surface.q0)
    lo, hi = np.log(PULL_OFF_NEAR_FLOOR), np.log(NEAR_ONE_MIN)

    def root_g(log_d):
        q = surface.q0 * (1.0 + np.exp(log_d))
        return float(np.sqrt(max(float(surface.diffusion_time(q, e_star)), 0.0)))

    if root_g(hi) <= target:
        return NEAR_ONE_MIN
    if root_g(lo) >= target:
        return PULL_OFF_NEAR_FLOOR
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if root_g(mid) > target:
            hi = mid
        else:
            lo = mid
    return float(np.exp(lo))


def _solver_bracket(surface, z, e, dg, energy_correction, beta, rtol, controls, upper,
                    theory="persson01", theory_gamma=None, hardness=None):
    """Where :func:`solve_adhesive_contact` on the grid ``z`` stops finding contact.

    Bisection in the tension between 0 and ``upper`` [Pa], each solve continuing from the
    contact state at the nearest tension with contact (the scene's theory and yield wall as
    given). Returns ((lo, hi), solves): contact
    found at tension lo, none at hi [Pa].
    """

    solves = 0

    def contact(sigma0, start):
        nonlocal solves
        r = solve_adhesive_contact(surface, np.array([sigma0]), z, e_star=e, work_of_adhesion=dg,
                                   energy_correction=energy_correction,
                                   detachment_prefactor=beta, rtol=rtol, parallel=False,
                                   controls=controls, zeta_given=True, start=start,
                                   onset=False, theory=theory, theory_gamma=theory_gamma,
                                   hardness=hardness)
        solves += 1
        if r.status[0] not in (0, WALL_JUMP, RTOL_NOT_MET):
            return False, r
        return r.area[0] > 0, r

    has, r_hi = contact(0.0, None)
    hi, lo = 0.0, -upper
    tol = max(rtol, PULL_OFF_BRACKET_RTOL)
    while hi - lo > tol * max(abs(lo), abs(hi)):
        mid = 0.5 * (lo + hi)
        has, r = contact(mid, r_hi.sigma_a)
        if has:
            hi, r_hi = mid, r
        else:
            lo = mid
    return (float(-hi), float(-lo)), solves


def pull_off(surface: Surface | Scene, *, e_star: float | None = None,
             work_of_adhesion: float | None = None, energy_correction: float | None = None,
             detachment_prefactor: float = DETACHMENT_PREFACTOR, theory: str = "persson01",
             theory_gamma: float | None = None,
             hardness: float | Callable[[np.ndarray], np.ndarray] | ArrayLike | None = None,
             rtol: float = 1e-6, zeta: ArrayLike | None = None, controls: dict | None = None,
             full_output: bool = False, bracket: bool = True) -> float | tuple[float, dict]:
    """Pull-off stress of a nominally flat contact: contact exists for p_nom > -sigma_c. [Pa]

    Parameters
    ----------
    surface : Surface or Scene
        The rough surface, or a :class:`~persson_fast.Scene` that carries it with the scene's
        parameters, its yield wall included (the keywords below then stay unset).
    e_star : float
        Effective modulus E* > 0 (required with a surface). [Pa]
    work_of_adhesion : float
        Delta gamma >= 0 (required with a surface). [J/m^2]
    energy_correction, detachment_prefactor
        As in :func:`persson_fast.solve_contact`.
    theory : str
        The area theory whose contact branch is followed, as in
        :func:`persson_fast.solve_contact`: "persson01" (default, the original), "yp08" or
        "wm17" (the corrected diffusion dT/dG = S(A), solved with sigma_a). "xu24" has no
        diffusion that could carry the detachment wall and raises a ValueError, as in
        solve_contact. [-]
    theory_gamma : float or None
        gamma of the corrected theory (None: its default), as in solve_contact. [-]
    hardness : float, callable, table or None
        A yield wall sigma_Y(zeta), as in :func:`persson_fast.solve_contact` (a constant [Pa],
        a callable of zeta, or a table): the branch is then that of the two-wall fixed point
        solve_contact solves at each nominal stress (see Notes). None (default): elastic.
    rtol : float
        Relative accuracy of sigma_c. [-]
    zeta : array_like, optional
        The coarsest of the nested magnification grids; the others are its refinements
        (``refine_zeta``); from 1 to zeta1 = q1/q0, as in
        :func:`persson_fast.solve_contact`. Default: :func:`adhesion_zeta` at ``rtol`` with
        its points near zeta = 1 extended down to ``_near_one_min``. Where the scene is
        not sticky on it, its refinements are tried (see Notes). [-]
    controls : dict, optional
        Fixed-point controls (see ``ADHESION_DEFAULTS``); ``max_iter`` defaults to
        ``PULL_OFF_MAX_ITER`` and ``omega`` to ``PULL_OFF_OMEGA`` (0.5) here.
    full_output : bool
        Also return a dict of diagnostics (see Returns).
    bracket : bool
        With ``full_output``, also bisect for where :func:`persson_fast.solve_contact` on the
        default grid stops finding contact (``info["bracket"]``; costs about 15 solves).

    Returns
    -------
    sigma_c : float
        Pull-off stress, >= 0; 0 when the surfaces are not sticky (see Notes). [Pa]
    info : dict
        Only with ``full_output``:

        - ``sticky``: whether the surfaces stick at p_nom = 0 (see Notes); ``reason``: why
          sigma_c = 0 where they do not (``error_estimate`` 0 and ``converged`` True there);
          ``rest``: per zeta grid tried, the state at p_nom = 0 (``n_zeta``, ``area`` =
          A(zeta1)/A0, ``sigma_a_1`` [Pa], ``gamma_eff_1`` and ``gamma_eff_1_error``
          [J/m^2], ``sticky`` True, False or None (undecided), ``iterations``);

        - ``error_estimate`` [Pa]: estimated error of sigma_c, the sum of ``error_parts``:
          ``zeta_grid`` (difference of the last two Richardson values at ``y0_grids``),
          ``end_zeta_grid`` (zeta-grid error of the branch's change from ``y0_grids`` to its
          end), ``tail`` (change left beyond the last point as y0 -> 0) and ``inner`` (the
          diffusion solves: from re-solving the end point at another tolerance, at least
          ``PULL_OFF_INNER_FLOOR * sigma_c``);
        - ``converged``: ``error_estimate <= rtol * sigma_c`` and no branch point failed
          (otherwise a ``RuntimeWarning`` is issued too);
        - ``y0`` [Pa]: sigma0 + sigma_a(1) at the end of the branch; ``fold``: the end is an
          interior minimum of sigma0(y0) (True) or the branch flattens as y0 -> 0 (False);
        - ``y0_grids`` [Pa], ``grids``: the y0 where the nested grids are compared, and per
          grid its size and -sigma0 there [Pa]; ``extrapolated``: the Richardson values [Pa];
          ``end_correction``: the branch's change from ``y0_grids`` to the end on the two
          coarsest grids [Pa];
        - ``branch``: the descent on the coarsest grid, arrays ``y0``, ``sigma0`` [Pa] and
          ``area`` (A(zeta1)/A0);
        - ``solves``, ``iterations``, ``unconverged`` (branch points that failed), ``lost``
          (where and why the last one failed; "" if none), ``time`` [s];
        - ``theory``, ``theory_gamma``, ``hardness``: the scene's area theory and yield wall
          as used;
        - ``bracket`` (with ``bracket=True``): tensions (lo, hi) [Pa] between which
          :func:`persson_fast.solve_contact` at this ``rtol`` (on the grid
          ``adhesion_zeta(surface, rtol)`` or ``zeta``) stops finding contact: contact at lo,
          none at hi, resolution max(rtol, 1e-4). It lies below sigma_c by the zeta-grid
          error of a single unextrapolated grid and where its fixed point stops converging.

    Raises
    ------
    ValueError
        For bad input (as solve_contact), and for theory="xu24" with adhesion.
    RuntimeError
        If the contact problem at p_nom = 0 fails, or the branch cannot be left from p_nom = 0
        although the state there is sticky (or undecided on the last grid tried). A branch
        point whose diffusion solve is flagged returns the value with its flag's error
        charged (``RTOL_NOT_MET``, ``GRID_CAP``: the solve's own estimate) or an infinite
        estimate (other flags), ``converged`` False and a warning.

    Warns
    -----
    RuntimeWarning
        When the estimated error exceeds ``rtol * sigma_c`` or a branch point failed.

    See Also
    --------
    persson_fast.solve_contact : The contact area under tension.
    persson_fast.Scene : A scene to pass in place of the keywords.
    persson_fast.scan : Pull-off stresses over a grid of scenes.

    Notes
    -----
    **Stickiness.** Surfaces brought into full contact and unloaded to p_nom = 0 stick when
    a contact state survives there: the fixed point of Eqs. 8-9 at p_nom = 0, started from
    full contact, keeps A(zeta1) > 0 with gamma_eff(1) > 0, i.e. sigma_a(1) > 0 (at
    p_nom = 0 the distribution starts on the wall unless sigma_a(1) > 0, so A > 0 needs
    it). Where instead gamma_eff(1) <= 0, the wall sits where the distribution starts, the
    contact vanishes (A = 0 is then the only state) and no tension is needed to separate
    the surfaces: sigma_c = 0. The decision is made on the converged state, with an error
    bar, not on the compiled fixed point's stopping point: that measures its residual
    against the largest sigma_a (at zeta1, ~sqrt(zeta1) times sigma_a(1) at full contact),
    so it can stop on a remnant on its way to A = 0 (seed scene, Delta gamma = 0.04, rtol
    1e-3: A(zeta1) = 1.25e-7, sigma_a(1) = 16 Pa, while one more application of Eqs. 8-9
    gives sigma_a(1) = 0). From that state the iteration continues at p_nom = 0
    (``_Branch.rest_state``): not sticky once g1 = gamma_eff(1)/Delta gamma lies below
    minus its error bar (propagated from the diffusion solves' area error estimates) on
    ``PULL_OFF_COLLAPSE`` successive iterates while A(zeta1) falls; sticky once converged
    (as a branch point) with g1 above its error bar; a state whose sign of g1 is within the
    error bar is re-solved with 10x tighter diffusion solves. A sticky state may have a
    tiny area: the onset is continuous (seed scene, converged threshold
    Delta gamma_c = 0.05181 J/m^2: A(zeta1) at p_nom = 0 grows like
    (Delta gamma - Delta gamma_c)^(1/2), 0.04 at 0.05185 and 0.11 at 0.052, and sigma_c
    from 0: 13 kPa at 0.05185, 26 kPa at 0.0519, 50 kPa at 0.052), so a small area
    or sigma_a(1) alone says nothing. The threshold moves with the zeta grid (second order;
    seed: 0.05218 / 0.05190 / 0.05183 J/m^2 at 5 / 10 / 20 points per decade), so a scene
    counts as not sticky only when it is not sticky on ``PULL_OFF_STICKY_GRIDS`` nested
    grids (the coarsest and its refinements, the fewest the extrapolation of a sticky scene
    uses); the first grid on which it is sticky becomes the coarsest. Within the finest
    grid's threshold shift of Delta gamma_c (seed, rtol 1e-3: 2e-5 J/m^2, where sigma_c
    < 7 kPa) a sticky scene can still come back as not sticky.

    On the contact branch of the fixed point of Eqs. 8-9 the nominal stress sigma0 is a
    function of y0 = sigma0 + sigma_a(zeta = 1), the start's distance from the wall, and the
    pull-off stress is -min sigma0 along the branch. Close to its end the branch flattens:
    an absorbing layer just above zeta = 1 takes up every change of y0 (on the seed scene
    sigma0 changes by 7 Pa as y0 falls from 1 kPa to 0), so the fixed point at fixed sigma0
    is nearly singular over the whole flat stretch and stops converging well before its
    end. At fixed y0 it stays regular, so the branch is followed in y0: from the state at
    p_nom = 0, y0 falls by ``PULL_OFF_STEP`` per stage (Anderson-accelerated fixed points
    with a trust region on the wall near zeta = 1, each starting from the extrapolated
    previous ones; loose while sigma0 still changes much) until sigma0 rises again (an
    interior minimum, located by parabolic steps in ln y0) or the estimated remaining change
    is below ``PULL_OFF_TAIL * rtol * sigma_c``.

    A single zeta grid leaves a large second-order error (1.6e-3 of sigma_c at 20 points
    per decade on the seed scene, mostly from the bulk of the spectrum), so the branch point
    at ``y0_grids`` (``PULL_OFF_GRID_STAGES`` stages above the end, where the fixed point is
    robust) is computed on at least three nested grids and Richardson-extrapolated, and the
    branch's change from there to the end is extrapolated from the two coarsest grids. The
    grids reach down to where sqrt(G) is ``PULL_OFF_NEAR_STRESS`` of sigma_a(1), so that the
    layer near zeta = 1 is resolved (see ``_near_one_min``).

    sigma_a(1) = c_1 (gamma_eff(1)/dgamma)^(1/2) magnifies an error of the area profile by
    dgamma/(2 gamma_eff(1)), so the diffusion solves of a branch point run at
    ``f * rtol * min(1, 2 gamma_eff(1)/dgamma)``, f = ``PULL_OFF_INNER`` (0.05) at rtol
    <= 1e-6 and ``PULL_OFF_INNER_LOOSE`` (0.2) at rtol >= 1e-5, log-linear between (1e-8 at
    the end of the seed scene's branch for rtol = 1e-6, 4e-6 for rtol = 1e-4). The inner part
    of the estimate is never below ``PULL_OFF_INNER_FLOOR * sigma_c`` (5e-7), so an rtol
    below about 5e-7 cannot be confirmed and warns. Seed scene on a 2-core Intel Xeon machine: 0.15 /
    0.56 / 5.3 / 36 s at rtol 1e-3 / 1e-4 / 1e-5 / 1e-6, every value
    within its estimate of the reference.

    **Corrected theories and the yield wall.** The same branch is followed, with the fixed
    point solve_contact solves for them (``persson_fast.adhesion.fixed_point.solve_adhesive_contact``):
    for yp08 and wm17 the iterate carries the corrected diffusion time T = int S(A) dG at the
    nodes beside sigma_a (T of the real area, as in
    ``persson_fast._kernels.adhesion.solve_adhesive_one``); with a yield wall every
    diffusion solve is the two-wall solver, the area is the real area A_el + A_pl, U_el that
    of the elastic area and gamma_eff per unit real area. The pull-off stress is then the
    end of that model's contact branch at fixed sigma_Y(zeta): the yield wall acts at each
    nominal stress as solve_contact has it, not as the memory of an earlier, higher load
    (unloading a plastically flattened contact is not modelled). The stickiness test, the
    nested grids, the extrapolation and the error estimate are those above. With a yield wall
    the two-wall solver cannot resolve a start closer to the detachment wall than a small
    fraction of the strip between the walls (seed scene, sigma_Y = 2e8 Pa: from y0 = 1.1e4 Pa
    = 0.8 % of sigma_a(1) down); the descent stops there and what is left of the branch is
    charged to the estimate (``tail``, about y0 there): seed scene, sigma_Y = 2e8 Pa,
    1.42899e6 +- 1.4e3 Pa at rtol 1e-4, flagged (converged False) where that exceeds rtol.
    Measured (seed scene, rtol 1e-4, 2-core machine): yp08 1.06037e6 +- 80 Pa, wm17
    1.12908e6 +- 49 Pa, 17-29 s with the bracket; at rtol 1e-3 about 1-2 s each.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> sigma_c = pf.pull_off(pf.seed_scene(), e_star=pf.seed_e_star(),
    ...                      work_of_adhesion=0.06, rtol=1e-3)
    >>> print(f"{sigma_c / 1e6:.2f} MPa")
    0.78 MPa
    """
    from ..scene import Scene, _is_default, unpack_adhesive_scene

    if isinstance(surface, Scene) and surface.hardness is not None:
        if not _is_default("hardness", hardness):
            raise ValueError("pull_off: give the scene's parameters either in the Scene or as "
                             "keywords, not both; got a Scene and hardness")
        hardness = surface.hardness
        surface = replace(surface, hardness=None)     # the yield wall goes on as a keyword
    surface, kw = unpack_adhesive_scene(surface, e_star, work_of_adhesion, energy_correction,
                                        detachment_prefactor, "pull_off")
    e_star, work_of_adhesion = kw["e_star"], kw["work_of_adhesion"]
    energy_correction, detachment_prefactor = kw["energy_correction"], kw["detachment_prefactor"]
    sigma_c, info, warning = _pull_off(
        surface, e_star=e_star, work_of_adhesion=work_of_adhesion,
        energy_correction=energy_correction, detachment_prefactor=detachment_prefactor,
        theory=theory, theory_gamma=theory_gamma, hardness=hardness, rtol=rtol, zeta=zeta,
        controls=controls, bracket=bool(full_output and bracket))
    if warning is not None:
        import warnings

        warnings.warn(warning, RuntimeWarning, stacklevel=2)
    return (sigma_c, info) if full_output else sigma_c


def _pull_off(surface, *, e_star, work_of_adhesion, energy_correction=None,
              detachment_prefactor=DETACHMENT_PREFACTOR, theory="persson01", theory_gamma=None,
              hardness=None, rtol=1e-6, zeta=None, controls=None, bracket=False):
    """:func:`pull_off` without its warning: returns (sigma_c [Pa], info, warning), the
    warning's text or None. Thread-safe (no warning filters touched), for callers that
    record ``info["converged"]`` themselves (:func:`persson_fast.api._flag_lost_contact`).
    """
    from ..scene import _check_rtol, _check_zeta, plan_scene

    t_start = time.perf_counter()
    rtol = _check_rtol(rtol)
    plan = plan_scene(surface, {"e_star": e_star, "work_of_adhesion": work_of_adhesion,
                                "energy_correction": energy_correction,
                                "detachment_prefactor": detachment_prefactor,
                                "hardness": hardness},
                      theory=theory, theory_gamma=theory_gamma)
    e, dg, beta = plan.e_star, plan.work_of_adhesion, plan.detachment_prefactor
    theory, theory_gamma, hardness = plan.theory, plan.theory_gamma, plan.hardness
    info = {"solves": 0, "iterations": 0, "unconverged": 0, "error_estimate": 0.0,
            "error_parts": {}, "converged": True, "fold": False, "y0": 0.0, "grids": [],
            "extrapolated": [], "branch": {}, "bracket": (0.0, 0.0), "time": 0.0,
            "sticky": False, "reason": "", "rest": [], "theory": theory,
            "theory_gamma": theory_gamma, "hardness": hardness, "lost": ""}
    if dg == 0.0:
        info["reason"] = "not sticky: no adhesion (work_of_adhesion = 0)"
        return 0.0, info, None
    if zeta is None:
        z0 = adhesion_zeta(surface, rtol, near_one_min=_near_one_min(surface, e, dg, beta))
    else:
        z0 = _check_zeta(zeta, surface)
    z_user = z0
    ctl = _controls(controls, {**ADHESION_DEFAULTS, "omega": PULL_OFF_OMEGA})
    if not (controls and "max_iter" in controls):
        ctl["max_iter"] = PULL_OFF_MAX_ITER
    gamma_s = -1.0 if energy_correction is None else float(energy_correction)
    variant = variant_of(choose_auto("adhesion"))
    theory_code = THEORY_CODES.get(theory, 0)
    theory_g = 1.0 if theory_gamma is None else float(theory_gamma)

    def make(grid):
        return _Branch(surface, grid, e, dg, beta, gamma_s, variant, ctl["n_damp"],
                       theory_code, theory_g, hardness)

    # the contact state at p_nom = 0 (from full contact) starts the descent on the coarsest
    # grid on which it is sticky; on none of PULL_OFF_STICKY_GRIDS nested grids: sigma_c = 0
    z_try, rest_branches = z0, []
    for _ in range(PULL_OFF_STICKY_GRIDS):
        b0 = make(z_try)
        rest = _rest_start(b0, rtol, ctl, gamma_s, variant)
        info["rest"].append(rest["summary"])
        info["iterations"] += rest["summary"]["iterations"]
        if rest["sticky"] is not False:
            x_p0 = rest["x"]
            samples, y_best, tail, fold, lost = _descend(b0, x_p0, x_p0[0] * b0.scale, rtol,
                                                         ctl)
            ok = sorted((s for s in samples if s["converged"]), key=lambda s: -s["y0"])
            if ok:
                break
            if rest["sticky"] or len(info["rest"]) == PULL_OFF_STICKY_GRIDS:
                raise RuntimeError(
                    f"pull_off: the contact branch could not be followed from p_nom = 0 on a "
                    f"zeta grid of {b0.zeta.size} points (the contact state there is "
                    + ("sticky" if rest["sticky"] else "undecided: the scene lies within the "
                       "grid's resolution of the stickiness threshold") + "); try another rtol "
                    "or a finer zeta grid")
            # undecided and no branch: as not sticky on this grid; the finer grid decides
        rest_branches.append(b0)
        z_try = refine_zeta(z_try)
    else:
        undecided = sum(r["sticky"] is None for r in info["rest"])
        info["reason"] = (
            f"not sticky: at p_nom = 0 the fixed point falls to the separated state (A = 0; "
            f"gamma_eff(1) < 0 beyond its error bar, or no contact) on the nested zeta grids "
            f"of {', '.join(str(r['n_zeta']) for r in info['rest'])} points"
            + (f" (on {undecided} of them undecided, and no contact branch leaves p_nom = 0)"
               if undecided else ""))
        info["solves"] += sum(b.solves for b in rest_branches)
        info["time"] = time.perf_counter() - t_start
        return 0.0, info, None
    z0 = z_try
    info["sticky"] = True
    best = min(ok, key=lambda s: s["sigma0"])
    # the nested grids are compared at y_g, a few stages above the end, where the fixed
    # point is robust; the change of sigma0 from y_g to the end (the part of the branch the
    # thin layer above zeta = 1 shapes) comes from the two coarsest grids
    y_above = best["y0"] * PULL_OFF_STEP ** PULL_OFF_GRID_STAGES * 0.99
    above = [s for s in ok if s["y0"] >= y_above]
    g_pt = above[-1] if above else ok[0]
    if g_pt.get("rtol", rtol) > rtol:
        g_pt = b0.follow(g_pt["y0"], [g_pt["x"]], rtol, ctl)
    y_g = g_pt["y0"]
    down = [s["y0"] for s in ok if best["y0"] <= s["y0"] < y_g]
    if best["y0"] not in down:
        down.append(best["y0"])
    down = sorted(set(down), reverse=True)
    ends = [g_pt["sigma0"]]
    used = [g_pt, best]
    branches = [b0]
    t_coarse = best["sigma0"] - g_pt["sigma0"]
    t_fine = None
    prev_b, prev_x = b0, g_pt["x"]
    err_grid = np.inf
    while len(ends) < PULL_OFF_MAX_GRIDS:
        grid = refine_zeta(prev_b.zeta)
        b = make(grid)
        branches.append(b)
        p = b.follow(y_g, [b.carry(prev_b, prev_x)], rtol, ctl)
        if not p["converged"]:
            # near the stickiness threshold the branch moves much with the grid (the
            # threshold does): walk this grid's own branch down the coarse ladder to y_g,
            # from the coarse grid's state at p_nom = 0
            ladder = [s["y0"] for s in ok if s["y0"] >= y_g]
            walk = _replay(b, ladder, b.carry(b0, ok[0]["x"]), rtol, ctl)
            if walk and walk[-1]["converged"] and walk[-1]["y0"] == y_g:
                walk[-1]["iterations"] += p["iterations"] + sum(
                    q["iterations"] for q in walk[:-1])
                p = walk[-1]
        used.append(p)
        if not p["converged"]:
            lost = True
            break
        ends.append(p["sigma0"])
        if len(ends) == 2:
            pts = _replay(b, down, p["x"], rtol, ctl)
            if pts and pts[-1]["converged"]:
                used.append(pts[-1])
                t_fine = pts[-1]["sigma0"] - p["sigma0"]
        prev_b, prev_x = b, p["x"]
        if len(ends) >= 3:
            s = np.array(ends)
            rich = (4.0 * s[1:] - s[:-1]) / 3.0
            err_grid = abs(rich[-1] - rich[-2])
            steps = np.diff(s)
            ratio = steps[-2] / steps[-1] if steps[-1] != 0.0 else np.inf
            if not 2.0 <= ratio <= 8.0:
                # not in the asymptotic range: charge the last difference itself
                err_grid = max(err_grid, abs(steps[-1]))
            if err_grid <= 0.5 * rtol * abs(rich[-1]):
                break
    s = np.array(ends)
    if s.size >= 2:
        rich = (4.0 * s[1:] - s[:-1]) / 3.0
        if s.size == 2:
            err_grid = abs(s[1] - s[0])
    else:
        rich = s.copy()
    if t_fine is not None:
        t_end = (4.0 * t_fine - t_coarse) / 3.0
        err_t = abs(t_fine - t_coarse) / 3.0
    else:
        t_end = t_coarse
        err_t = 0.5 * abs(t_coarse)
    sigma_c = max(-float(rich[-1] + t_end), 0.0)
    # error of the inner (diffusion) solves: re-solve the coarsest grid's end point with a
    # tighter tolerance (the inner error taken as linear in it), or, at the floor, a looser
    # one (the whole difference charged)
    inner_used = b0.inner_rtol(rtol, best["x"])
    inner_check = b0.inner_rtol(rtol / PULL_OFF_INNER_CHECK, best["x"])
    tighter = inner_check < inner_used
    r_check = rtol / PULL_OFF_INNER_CHECK if tighter else rtol * PULL_OFF_INNER_CHECK
    check = b0.point(best["y0"], best["x"], r_check, m_hist=ctl["m_hist"], omega=ctl["omega"],
                     trust=PULL_OFF_TRUST, max_iter=ctl["max_iter"])
    err_inner = abs(check["sigma0"] - best["sigma0"])
    if tighter:
        # the check's tolerance is k times tighter (k = PULL_OFF_INNER_CHECK, more where the
        # factor of _inner_factor falls with rtol): the error at the used one is k/(k-1) x
        # the difference
        k = inner_used / inner_check
        err_inner *= k / (k - 1.0)
    if not check["converged"] or check["status"] not in (0, WALL_JUMP, RTOL_NOT_MET):
        err_inner += rtol * sigma_c
    err_inner = max(err_inner, PULL_OFF_INNER_FLOOR * sigma_c)
    # a diffusion solve flagged RTOL_NOT_MET (refined to its work cap) still returns its
    # best value: its estimated error is charged, with the largest weight (4/3 + 1/3) a
    # point gets in the Richardson values, instead of failing
    err_flag = PULL_OFF_FLAG_WEIGHT * (
        sum(p["flag_error"] for p in used if p["converged"]) + check["flag_error"])
    err_tail = float(tail)
    # a branch point whose diffusion solve was flagged otherwise (a far-field leak, ...)
    # has no error bar: the value is returned with an infinite estimate, flagged
    unbounded = [p for p in used if p["converged"]
                 and p["status"] not in (0, WALL_JUMP, RTOL_NOT_MET, GRID_CAP)]
    if unbounded:
        err_flag = float("inf")
    error = err_grid + err_t + err_tail + err_inner + err_flag
    converged = bool(error <= rtol * sigma_c and not lost)
    failed = [p for p in samples + used if not p["converged"]]
    why_lost = ""
    if failed:
        code = int(failed[-1]["status"])
        why_lost = (f"at y0 = {failed[-1]['y0']:.4g} Pa, last diffusion solve: "
                    f"{STATUS_MESSAGES.get(code, 'flagged')} (code {code})" if code else
                    f"at y0 = {failed[-1]['y0']:.4g} Pa, its fixed point did not converge")
    info["lost"] = why_lost
    warning = None
    if not converged:
        warning = (f"pull_off: estimated error {error:.3g} Pa of sigma_c = {sigma_c:.6g} Pa "
                   f"exceeds rtol * sigma_c" + (f"; a branch point failed ({why_lost})"
                                                if lost else ""))
        if unbounded:
            code = int(unbounded[0]["status"])
            warning += (f"; the diffusion solve of the branch point at y0 = "
                        f"{unbounded[0]['y0']:.4g} Pa was flagged "
                        f"({STATUS_MESSAGES.get(code, 'flagged')}, code {code}) and bounds no "
                        f"error: try a smaller rtol or a finer zeta grid")
    info["solves"] += sum(b.solves for b in branches + rest_branches)
    info["iterations"] += sum(p["iterations"] for p in samples + used) + check["iterations"]
    info["unconverged"] = sum(not p["converged"] for p in samples) + sum(
        not p["converged"] for p in used)
    info["error_estimate"] = float(error)
    info["error_parts"] = {"zeta_grid": float(err_grid), "end_zeta_grid": float(err_t),
                           "tail": err_tail, "inner": float(err_inner),
                           "flagged": float(err_flag)}
    info["converged"] = converged
    info["fold"] = bool(fold)
    info["y0"] = float(best["y0"])
    info["y0_grids"] = float(y_g)
    info["end_correction"] = (float(-t_coarse), None if t_fine is None else float(-t_fine))
    info["grids"] = [(int(b.zeta.size), float(-s_)) for b, s_ in zip(branches, ends)]
    info["extrapolated"] = [float(-r) for r in rich]
    info["branch"] = {"y0": np.array([p["y0"] for p in ok]),
                      "sigma0": np.array([p["sigma0"] for p in ok]),
                      "area": np.array([p["area"][-1] for p in ok])}
    if bracket:
        upper = max(sigma_c + error, float(-min(ends))) * (1.0 + 2.0 * rtol)
        z_solver = adhesion_zeta(surface, rtol) if zeta is None else z_user
        info["bracket"], n = _solver_bracket(surface, z_solver, e, dg, energy_correction,
                                             beta, rtol, controls, upper, theory,
                                             theory_gamma, hardness)
        info["solves"] += n
    info["time"] = time.perf_counter() - t_start
    return sigma_c, info, warning
