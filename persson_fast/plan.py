"""Which pieces of physics a scene holds, and how their composition is solved.

A scene of Persson's theory is the diffusion of the stress distribution in magnification
with up to two absorbing walls. Three pieces say which problem it is:

* the **time** of the diffusion: the original G(zeta) ("persson01"), or a corrected theory
  ("yp08", "wm17": dT/dG = S(A); "xu24": an algebraic relation at zeta1);
* the **lower wall**: none, or the detachment stress -sigma_a(zeta), self-consistent with
  adhesion (seed Eqs. 8-9);
* the **upper wall**: none, or the yield stress sigma_Y(zeta) (a constant hardness or a
  scale-dependent one).

:func:`plan_contact` checks a scene once, reads these pieces and picks the **route** that
solves their composition (:data:`ROUTES`: a closed form where one exists, else the solver
that carries those walls, inside the adhesive fixed point where there is adhesion). Every
combination that is refused is one row of :data:`REFUSALS`, with its reason; the entry
points' docstrings and the command line's help take their words from it
(:func:`refusals_text`). A new piece of physics is a field of :class:`Plan`, a new route a
row of :data:`ROUTES`, a new refusal a row of :data:`REFUSALS`.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

from .methods import check_method
from .results import summarize_status
from .scene import _check_scene_args, unpack_scene
from .theories import check_theory, check_theory_scene

__all__ = ["Plan", "ROUTES", "REFUSALS", "plan_contact", "refusal_reasons", "refusals_text",
           "finish_contact"]


@dataclass(frozen=True)
class Refusal:
    """One refused combination: when it applies, what the error says, and why."""
    name: str
    applies: Callable[["Plan"], bool]
    message: Callable[["Plan"], str]
    why: str


def _walls(plan):
    return ("with adhesion" if plan.work_of_adhesion > 0 else f"with theory={plan.theory!r}")


#: the combinations solve_contact refuses (after each argument's own checks), in the order
#: they are checked; the corrected theory that cannot carry a wall (xu24 with adhesion or a
#: yield wall) is refused before these, by :func:`persson_fast.theories.check_theory_scene`
REFUSALS = (
    Refusal(
        "strip-without-yield-wall",
        lambda p: p.hardness is None and p.method == "strip",
        lambda p: ("method 'strip' is the two-wall solver: it needs a yield wall "
                   "(hardness=...); use 'auto' or 'cn' without one"),
        "the two-wall solver 'strip' needs an upper wall",
    ),
    Refusal(
        "corrected-theory-on-a-grid",
        lambda p: (p.route == "theory" and p.method not in ("auto", "analytic")),
        lambda p: (f"method must be 'auto' or 'analytic' for theory={p.theory!r} [-] (the "
                   f"corrected theories without walls are a near-closed form, not a grid "
                   f"solve); got method = {p.method!r}"),
        "a corrected theory without walls is a near-closed form (method 'auto' or "
        "'analytic')",
    ),
    Refusal(
        "two-wall-fixed-point-method",
        lambda p: p.route == "two-wall-fixed-point" and p.method not in ("auto", "strip"),
        lambda p: (f"method must be 'auto' or 'strip' for a yield wall {_walls(p)} [-] (the "
                   f"fixed point runs the two-wall solver 'strip'); got method = "
                   f"{p.method!r}"),
        "a yield wall with adhesion or with yp08/wm17 runs the two-wall solver inside the "
        "fixed point (method 'auto' or 'strip')",
    ),
)

#: why the derived fields (separation, stiffness, elastic_energy) are refused, per route
_SEPARATION_REFUSED = {
    "theory": ("separation, stiffness and elastic_energy are derived for the original theory "
               "(theory='persson01') only; got theory = {theory!r}"),
    "two-wall-fixed-point": (
        "separation, stiffness and elastic_energy are derived for elastic contact with the "
        "original theory only; got hardness = {hardness!r}, work_of_adhesion = {dg!r} and "
        "theory = {theory!r}"),
}


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
        """The key of :data:`ROUTES` that solves this composition."""
        corrected = self.theory != "persson01"
        if self.upper_wall == "yield":
            return ("two-wall-fixed-point" if self.lower_wall == "adhesion" or corrected
                    else "yield")
        if self.lower_wall == "adhesion":
            return "adhesive-fixed-point"
        return "theory" if corrected else "elastic"


def plan_contact(where: str, surface, given: dict, *, method: str, theory: str,
                 theory_gamma, check_extra: Callable[[], object] | None = None) -> Plan:
    """Check a scene and its method once; the :class:`Plan` that solves it.

    Parameters
    ----------
    where : str -- the entry point's name, for the messages.
    surface : Surface or Scene -- the first argument of the entry point.
    given : dict -- the scene keywords as given (e_star, work_of_adhesion, energy_correction,
        detachment_prefactor, hardness).
    method, theory, theory_gamma -- as given to the entry point.
    check_extra : callable or None -- further argument checks, run after the method's and
        before the scene's (their order is that of the error a user sees first).

    Raises
    ------
    ValueError
        For a bad argument, or a combination in :data:`REFUSALS` (or a theory that cannot
        carry the scene's walls).
    """
    from .plasticity.hardness import check_hardness

    surface, kw = unpack_scene(surface, given, where)
    method = check_method(method)
    if check_extra is not None:
        check_extra()
    e, dg, beta = _check_scene_args(surface, kw["e_star"], kw["work_of_adhesion"],
                                    kw["detachment_prefactor"], kw["energy_correction"])
    theory, theory_gamma = check_theory(theory, theory_gamma)
    hardness = kw.get("hardness")
    if theory != "persson01":
        check_theory_scene(theory, float(dg), hardness)
    if hardness is not None:
        hardness = check_hardness(hardness, scale_dependent=True)
    plan = Plan(surface=surface, e_star=e, work_of_adhesion=dg,
                detachment_prefactor=float(beta), energy_correction=kw["energy_correction"],
                theory=theory, theory_gamma=theory_gamma, hardness=hardness, method=method)
    for refusal in REFUSALS:
        if refusal.applies(plan):
            raise ValueError(refusal.message(plan))
    return plan


def refusal_reasons() -> list[str]:
    """The refused combinations, one sentence each (docstrings, the command line)."""
    lines = ["xu24 (an algebraic relation at full magnification) carries no wall: neither "
             "adhesion nor a yield wall"]
    lines += [r.why for r in REFUSALS]
    lines += ["separation, stiffness and elastic_energy (and solve_separation, "
              "gap_distribution) are derived for elastic contact with the original theory "
              "without adhesion"]
    return lines


def refusals_text(indent: str = "") -> str:
    """:func:`refusal_reasons` as a bulleted list, each line indented by ``indent``."""
    return "\n".join(f"{indent}* {line}" for line in refusal_reasons())


def finish_contact(plan: Plan, res, rtol: float):
    """The steps every route's result goes through: the reason the derived fields are
    refused where they are, adhesive profiles zero without adhesion, and the separated
    tensions of an adhesive scene checked against the pull-off stress."""
    from .separation.elastic import ADHESION_REFUSED

    route, dg = plan.route, plan.work_of_adhesion
    if route in _SEPARATION_REFUSED:
        res = replace(res, separation_source=_SEPARATION_REFUSED[route].format(
            theory=plan.theory, hardness=plan.hardness, dg=dg))
    if route == "two-wall-fixed-point" and dg == 0:
        zeros = np.zeros_like(res.area_zeta)
        return replace(res, sigma_a=zeros, gamma_eff=zeros.copy(), elastic_energy_zeta=None,
                       sticky=None)
    if plan.lower_wall == "adhesion":
        res = flag_lost_contact(res, plan, rtol)
        if route == "adhesive-fixed-point":
            res = replace(res, separation_source=ADHESION_REFUSED.format(
                where="solve_contact", dg=float(dg)))
    return res


#: tolerance bounds of the pull-off check of separated tensions in solve_contact
LOST_CONTACT_RTOL = (1e-4, 1e-3)


def flag_lost_contact(res, plan: Plan, rtol: float):
    """Flag tensions where the fixed point separated although the contact branch reaches them.

    Near the pull-off stress the end of the contact branch on one zeta grid falls short of
    the converged one (a second-order grid error; about 0.6 % of sigma_c on the seed scene at
    rtol 1e-4), and the fixed point at fixed p_nom is nearly singular there (with the
    corrected theories it loses the branch earlier: seed scene, yp08, from about 0.9 sigma_c
    at rtol 1e-4). When a tension ends separated, :func:`persson_fast.pull_off` of the same
    scene (theory and yield wall included; at rtol clipped to LOST_CONTACT_RTOL) says whether
    contact exists there; such pressures get status LOST_CONTACT, and so do those within its
    error estimate of sigma_c, where separation cannot be confirmed. A corrected theory or a
    yield wall is checked at the looser bound of LOST_CONTACT_RTOL.

    pull_off's own warning (estimate above its rtol) is not issued here: the private
    :func:`persson_fast.adhesion.pulloff._pull_off` returns it instead, and its error
    estimate already widens the flagged band. No warning filter is touched, so this is safe
    on the worker threads of a scan (``warnings.catch_warnings`` is not thread-safe before
    Python 3.14 and could leave an 'ignore' filter behind for good).
    """
    from .adhesion.pulloff import _pull_off

    sep = (res.pressure < 0) & (res.area <= 0) & (res.status == 0)
    if not np.any(sep):
        return res
    rtol_c = min(max(rtol, LOST_CONTACT_RTOL[0]), LOST_CONTACT_RTOL[1])
    if plan.theory != "persson01" or plan.hardness is not None:
        # their branch points cost more (the corrected times; the two-wall solver): the check
        # runs at the looser bound, which only widens the flagged band (seed scene, yp08: 1.3 s
        # against 25 s at 1e-4)
        rtol_c = LOST_CONTACT_RTOL[1]
    try:
        sigma_c, info, _ = _pull_off(plan.surface, e_star=plan.e_star,
                                     work_of_adhesion=plan.work_of_adhesion,
                                     energy_correction=plan.energy_correction,
                                     detachment_prefactor=plan.detachment_prefactor,
                                     theory=plan.theory, theory_gamma=plan.theory_gamma,
                                     hardness=plan.hardness, rtol=rtol_c, bracket=False)
    except RuntimeError as exc:
        # the end of the branch is unknown: no separated tension can be confirmed
        return _flag_rows(res, sep, f"; separated tensions not checked against the pull-off "
                                    f"stress ({exc})")
    lost = sep & (res.pressure > -(sigma_c + info["error_estimate"]))
    if not np.any(lost):
        return res
    return _flag_rows(res, lost, f"; pull-off stress {sigma_c:.6g} +- "
                                 f"{info['error_estimate']:.2g} Pa")


def _flag_rows(res, rows, note):
    """``res`` with status LOST_CONTACT at ``rows`` (a mask) and ``note`` added to its
    message."""
    from ._kernels.status import LOST_CONTACT

    status = np.where(rows, LOST_CONTACT, res.status)
    success, message = summarize_status(status)
    return replace(res, status=status, success=success, message=message + note)


#: route -> (what it is, where it is solved); the solver functions are looked up in api.py
ROUTES = {
    "elastic": "no wall: the closed form erf(p / 2 sqrt G1) ('analytic') or a grid method",
    "theory": "a corrected theory without walls: a near-closed form",
    "yield": "a yield wall alone: the exact two-wall series (constant hardness) or the "
             "two-wall solver 'strip'",
    "adhesive-fixed-point": "the detachment wall: the fixed point of seed Eqs. 8-9 around "
                            "the diffusion",
    "two-wall-fixed-point": "a yield wall with adhesion or a corrected theory: the fixed "
                            "point with the two-wall solver inside",
}
