"""Mean interfacial separation, contact stiffness and stored elastic energy (no adhesion).

Physics
-------
Persson, Phys. Rev. Lett. 99, 125502 (2007); Yang & Persson, J. Phys.: Condens. Matter 20,
215214 (2008). The elastic energy stored per unit nominal area at nominal pressure p is

    U_el(p) = (pi/2) E* int_{q0}^{q1} q^2 C(q) P(q, p) S(P) dq,

P(q, p) = A(zeta = q/q0)/A0, S = gamma_S + (1 - gamma_S) P^2 (``energy_correction``; S = 1
when it is None): U_el(zeta = 1) of seed Eq. 9. Moving the surfaces together by du stores
dU_el = -p du, so the mean interfacial separation is

    u(p) = int_p^inf (1/p') dU_el/dp' dp'.

Without adhesion P = erf(w p / E*), w(q) = (pi int_{q0}^{q} q'^3 C dq')^(-1/2), i.e.
w p / E* = p / (2 sqrt(G(q))), and

    u(p) = sqrt(pi) int dq q^2 C w Kfun(w p / E*),
    Kfun(s) = int_s^inf [gamma_S + 3 (1 - gamma_S) erf(t)^2] exp(-t^2) dt / t
            = gamma_S E1(s^2)/2 + 3 (1 - gamma_S) J(s),
    K(p) = -dp/du = p / (sqrt(pi) int dq q^2 C w [gamma_S + 3 (1 - gamma_S) P^2] exp(-(w p/E*)^2)).

Limits: at small p, d ln p / du -> -1/u0 with u0 = sqrt(pi) gamma_S int q^2 C w dq
(:func:`decay_length`), i.e. p ~ exp(-u/u0); at large p, u -> 0 (like exp(-p^2/(4 G1))).

Numerics
--------
The q integrals are composite Gauss-Legendre sums on a node set fixed by the surface alone
(so a pressure's result does not depend on the other pressures asked for):

* ln q panels at most half a decade wide and at most ``LN_G_STEP`` = 1 wide in ln G(q)
  (where G grows fast, e.g. G ~ q^4 below a roll-off, exp(-s^2) has a narrow front in
  ln q), split at the spectrum's breakpoints;
* on the first panel [q0, q_a] (q_a the first edge >= 2 q0), q = q0 + (q_a - q0) tau^2 (w
  has a 1/sqrt(q - q0) singularity at q0), on dyadic panels in tau (split at the
  breakpoints inside) down to tau ~ 1e-12; where q - q0 is below
  1e-8 q0, G = (pi/4) E*^2 q0^3 C(q0) (q - q0) (relative error ~1e-8 on nodes that carry
  less than 1e-4 of the integral);
* toward q1, ``Q1_LEVELS`` dyadic cuts in ln q, from the widest panel's width down,
  merged with the other edges: at large p, u and K come from a layer at q1 whose width in
  ln q shrinks like 4 G1 / p^2.

Measured against an independent double quadrature (``persson_fast._reference.separation``)
and against this rule with three times the nodes (40 random self-affine scenes with and
without roll-off, three capillary-wave scenes, p from 1e-5 to 5 sqrt(G1), S = 1 and
gamma_S = 0.45): relative error of u, K and U_el below 2e-13 (tests/test_separation.py
holds it to 1e-10); against this rule with three times the nodes per panel, four times the
panels and a quarter of the ln G step, 130 random self-affine scenes (0.05 to 7 decades,
with and without roll-off), p from 1e-3 to 40 sqrt(G1): below 8e-14 from 0.4 decades up,
1.2e-9 on a 0.33-decade scene at 40 sqrt(G1) (u ~ 1e-187 m). The accuracy does not depend on
``rtol``. Pressures below ``pressure_floor`` (where the tau levels end before the stress
distribution has left the node nearest q0; ~1e-11 sqrt(G(q_a)), far below any load of
interest) are flagged.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # names of the type hints only
    from numpy.typing import ArrayLike
    
    from ..scene import Scene
    from ..surfaces.base import Surface

import functools
import math
import time
from dataclasses import dataclass, field

import numpy as np
from ..analytic.special import erf, erfc, exp1

from .._kernels.contact_law import law_sweep
from .._kernels.separation import (J_END, J_SPLIT, build_kfun_table,
                                  chebyshev, separation_sweep, separation_sweep_prange)
from .._kernels.status import BELOW_RESOLVED, OK, STATUS_MESSAGES
from .._validation import as_float_array, check_finite, check_nonnegative
from ..scene import _check_rtol, unpack_scene
from ..surfaces.models import SelfAffine
from ..sweep import run_rows

#: Gauss-Legendre nodes per panel (ln q panels; tau panels near q0)
PANEL_NODES = 10
TAU_PANEL_NODES = 10
#: ln q panels per decade of the main band (at least)
PANELS_PER_DECADE = 2
#: geometric tau panels on the first panel, ratio Q0_RATIO (q - q0 down to
#: Q0_RATIO^(-2 Q0_LEVELS) (q_a - q0), i.e. 1e-24 of it): G ~ tau^2 there, so a panel spans
#: ln 4 in ln G (the ln q panels span at most LN_G_STEP = 1)
Q0_RATIO = 2.0
Q0_LEVELS = 40
#: largest change of ln G(q) across a ln q panel
LN_G_STEP = 1.0
#: the first panel, in tau = sqrt((q - q0)/(q_a - q0)), reaches the first panel edge
#: q_a >= TAU_REGION q0: beyond it the 1/sqrt(q - q0) singularity of w is far enough from
#: every ln q panel for Gauss-Legendre to keep its geometric convergence
TAU_REGION = 2.0
#: dyadic ln q levels toward q1
Q1_LEVELS = 16
#: below this q - q0 (relative to q0), G and C are taken to first order at q0
TAYLOR_BELOW = 1e-8
#: a node is "left" by the distribution when s = p w / E* exceeds this (exp(-64) ~ 1e-28)
RESOLVED_S = 8.0
#: nodes of the Chebyshev expansions of J
J_CHEB_NODES = 48
#: the table of V(x) = Kfun(e^x) exp(e^(2x)): x from ln 1e-8 to ln 26, spacing 1/512
#: (cubic Hermite with exact slopes; relative error of Kfun below ~1e-13)
KFUN_X_LOW = math.log(1e-8)
KFUN_X_HIGH = math.log(26.0)
KFUN_STEPS_PER_UNIT = 512


@functools.lru_cache(maxsize=1)
def j_coefficients() -> tuple[np.ndarray, np.ndarray]:
    """Chebyshev coefficients of J(s) on [0, 2] and of R(s) on [2, 6].

    J(s) = int_s^inf erf(t)^2 exp(-t^2) dt / t; on [2, 6] J = E1(s^2)/2 - exp(-2 s^2) R(s)/s^3.
    Values at the Chebyshev points come from 80-point Gauss-Legendre rules on intervals where
    the integrands are smooth (J(2) from E1 and R(2)); the expansions are then truncated where
    their coefficients fall below 1e-17 of the largest.
    """
    x, w = np.polynomial.legendre.leggauss(80)

    def integral(f, a, b):
        a = np.asarray(a, float)[..., None]
        b = np.asarray(b, float)[..., None]
        t = 0.5 * (b - a) * x + 0.5 * (b + a)
        return (0.5 * (b - a)[..., 0]) * np.sum(w * f(t), axis=-1)

    def one_minus_erf2_tail(t):            # (1 - erf^2) exp(-t^2) / t, no cancellation
        c = erfc(t)
        return c * (2.0 - c) * np.exp(-t * t) / t

    def r_of(s):                            # R(s) = s^3 exp(2 s^2) int_s^inf (1 - erf^2) e^-t^2/t
        tail = integral(one_minus_erf2_tail, s, s + 6.0)
        return tail * s ** 3 * np.exp(2.0 * s * s)

    j2 = 0.5 * exp1(J_SPLIT ** 2) - math.exp(-2.0 * J_SPLIT ** 2) * r_of(J_SPLIT) / J_SPLIT ** 3

    def erf2_over_t(t):
        safe = np.where(t > 0, t, 1.0)
        return np.where(t > 0, erf(safe) ** 2 * np.exp(-t * t) / safe, 0.0)

    k = np.arange(J_CHEB_NODES)
    cheb_pts = np.cos(np.pi * (k + 0.5) / J_CHEB_NODES)          # on [-1, 1]
    s_low = 0.5 * J_SPLIT * (cheb_pts + 1.0)
    j_low = j2 + integral(erf2_over_t, s_low, J_SPLIT)
    s_high = J_SPLIT + 0.5 * (J_END - J_SPLIT) * (cheb_pts + 1.0)
    r_high = r_of(s_high)
    out = []
    for values in (j_low, r_high):
        c = np.polynomial.chebyshev.chebfit(cheb_pts, values, J_CHEB_NODES - 1)
        keep = np.nonzero(np.abs(c) > 1e-17 * np.max(np.abs(c)))[0]
        out.append(np.ascontiguousarray(c[: keep[-1] + 1]))
    return out[0], out[1]


@functools.lru_cache(maxsize=16)
def kfun_table(gamma_s: float) -> tuple[np.ndarray, np.ndarray, float]:
    """(V, dV/dx, J(0)) of :func:`persson_fast._kernels.separation.build_kfun_table`."""
    low, high = j_coefficients()
    n = int(math.ceil((KFUN_X_HIGH - KFUN_X_LOW) * KFUN_STEPS_PER_UNIT)) + 1
    v = np.empty(n)
    dv = np.empty(n)
    build_kfun_table(float(gamma_s), low, high, KFUN_X_LOW, 1.0 / KFUN_STEPS_PER_UNIT, v, dv)
    return v, dv, float(chebyshev(low, 0.0, J_SPLIT, 0.0))


@functools.lru_cache(maxsize=4)
def _gauss(n: int):
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (x + 1.0), 0.5 * w                              # on [0, 1]


@dataclass(frozen=True)
class SeparationNodes:
    """Quadrature nodes of the q integrals for one (surface, E*), sorted by q descending.

    Attributes
    ----------
    q : (n,) -- wavevectors. [1/m]
    s_scale : (n,) -- w(q)/E* = 1/(2 sqrt(G(q))). [1/Pa]
    a_sep : (n,) -- sqrt(pi) W q^2 C w per node. [m]
    b_energy : (n,) -- (pi/2) E* W q^2 C per node. [J/m^2]
    b_suffix : (n + 1,) -- b_suffix[k] = sum(b_energy[k:]). [J/m^2]
    ln_s_scale : (n,) -- ln s_scale. [-]
    c_free : (n,) -- W q^2 C per node (the spectral weight). [m]
    pressure_floor : float -- smallest pressure whose distribution has left the innermost
        node near q0 (s >= ``RESOLVED_S`` there); below it the result is flagged. [Pa]
    """

    q: np.ndarray
    s_scale: np.ndarray
    a_sep: np.ndarray
    b_energy: np.ndarray
    b_suffix: np.ndarray
    ln_s_scale: np.ndarray
    c_free: np.ndarray
    pressure_floor: float
    e_star: float = field(default=0.0)


def _main_boundaries(surface) -> np.ndarray:
    """Panel edges: a ln q grid, the breakpoints, and the q where ln G(q) crosses a grid of
    spacing ``LN_G_STEP`` (s^2 = p^2/(4 G) must not change by more than a factor
    e^LN_G_STEP across a panel: where G grows fast, e.g. G ~ q^4 below a roll-off, the front
    of exp(-s^2) is narrow in ln q)."""
    q0, q1 = surface.q0, surface.q1
    decades = math.log10(q1 / q0)
    n = max(2, int(math.ceil(decades * PANELS_PER_DECADE)))
    grid = q0 * (q1 / q0) ** (np.arange(n + 1) / n)
    grid[0], grid[-1] = q0, q1
    bp = np.asarray(surface.breakpoints(), float)
    fine = np.geomspace(q0 * (1.0 + 1e-3), q1, max(64, int(64 * decades)))
    with np.errstate(divide="ignore"):
        ln_g = np.log(np.asarray(surface.moment(3, q0, fine)))
    ok = np.isfinite(ln_g)
    level_q = np.zeros(0)
    if np.count_nonzero(ok) > 1:
        ln_g, ln_q = np.maximum.accumulate(ln_g[ok]), np.log(fine[ok])
        levels = np.arange(math.ceil(ln_g[0] / LN_G_STEP), math.floor(ln_g[-1] / LN_G_STEP) + 1)
        uniq, first = np.unique(ln_g, return_index=True)
        level_q = np.exp(np.interp(levels * LN_G_STEP, uniq, ln_q[first]))
    edges = np.unique(np.concatenate([grid, bp[(bp > q0) & (bp < q1)],
                                      level_q[(level_q > q0) & (level_q < q1)]]))
    # drop panels narrower than 1e-12 relative (coincident breakpoints)
    keep = np.concatenate([[True], np.diff(np.log(edges)) > 1e-12])
    edges = edges[keep]
    edges[-1] = q1
    return edges


def separation_nodes(surface, e_star: float) -> SeparationNodes:
    """Build the quadrature nodes of :mod:`persson_fast.separation` for one surface and E*."""
    xg, wg = _gauss(PANEL_NODES)
    xt, wt_g = _gauss(TAU_PANEL_NODES)
    q0, q1 = surface.q0, surface.q1
    edges = _main_boundaries(surface)
    pieces_q, pieces_w = [], []
    # --- first panel, q = q0 + delta, delta = span tau^2, dyadic in tau ---------------------
    i_tau = int(np.searchsorted(edges, TAU_REGION * q0))
    i_tau = min(max(i_tau, 1), edges.size - 1)
    qa = edges[i_tau]
    span = qa - q0
    cuts = Q0_RATIO ** -np.arange(Q0_LEVELS, 0, -1, dtype=float)
    inner = np.sqrt((edges[1:i_tau] - q0) / span)               # breakpoints inside, as tau
    if i_tau == edges.size - 1:                                 # the tau region reaches q1
        inner = np.concatenate([inner, 1.0 - 0.5 ** np.arange(1, Q1_LEVELS + 1)])
    cuts = np.unique(np.concatenate([cuts, inner[(inner > 0) & (inner < 1)]]))
    lo = np.concatenate([[0.0], cuts])
    hi = np.concatenate([cuts, [1.0]])
    tau = (lo[:, None] + (hi - lo)[:, None] * xt[None, :]).ravel()
    wt = ((hi - lo)[:, None] * wt_g[None, :]).ravel()
    delta = span * tau * tau
    w_delta = 2.0 * span * tau * wt                               # d delta = 2 span tau d tau
    # --- main ln q panels, refined dyadically toward q1 -----------------------------------------
    if i_tau < edges.size - 1:
        # the dyadic cuts toward q1 are measured from the widest panel width of the main
        # grid, not from the last panel's: an edge just below q1 (a ln G level, a breakpoint)
        # would otherwise leave the panel before it, where the layer of exp(-s^2) at q1 lies
        # at large p, unrefined (relative errors of u up to 0.4 at p = 40 sqrt(G1) measured)
        ln_edges = np.log(edges[i_tau:])
        last_b = math.log(q1)
        width = max(float(np.max(np.diff(ln_edges))), last_b - ln_edges[-2])
        width = min(width, last_b - ln_edges[0])
        cuts = last_b - width * 0.5 ** np.arange(Q1_LEVELS + 1)
        ln_all = np.unique(np.concatenate([ln_edges, cuts[cuts > ln_edges[0]]]))
        keep = np.concatenate([[True], np.diff(ln_all) > 1e-12 * np.maximum(1.0, np.abs(
            ln_all[1:]))])
        ln_all = ln_all[keep]
        ln_all[-1] = last_b
        la, lb = ln_all[:-1], ln_all[1:]
        lnq = (la[:, None] + (lb - la)[:, None] * xg[None, :]).ravel()
        wl = ((lb - la)[:, None] * wg[None, :]).ravel()
        q_main = np.exp(lnq)
        pieces_q.append(q_main)
        pieces_w.append(wl * q_main)                              # dq = q d ln q
    q_main = np.concatenate(pieces_q) if pieces_q else np.zeros(0)
    w_main = np.concatenate(pieces_w) if pieces_w else np.zeros(0)
    e = float(e_star)
    g_const = 0.25 * math.pi * e * e
    # near q0: exact G where q - q0 is representable well, first order below
    c0 = float(surface.psd(q0))
    taylor = delta < TAYLOR_BELOW * q0
    q_first = np.where(taylor, q0, q0 + delta)
    G_first = np.where(taylor, g_const * q0 ** 3 * c0 * delta,
                       g_const * np.asarray(surface.moment(3, q0, q_first)))
    C_first = np.where(taylor, c0, np.asarray(surface.psd(q_first)))
    G_main = g_const * np.asarray(surface.moment(3, q0, q_main))
    C_main = np.asarray(surface.psd(q_main))
    q = np.concatenate([q_first, q_main])
    weight = np.concatenate([w_delta, w_main])
    G = np.concatenate([G_first, G_main])
    C = np.concatenate([C_first, C_main])
    order = np.argsort(-G, kind="stable")
    q, weight, G, C = q[order], weight[order], G[order], C[order]
    with np.errstate(divide="ignore"):
        s_scale = 0.5 / np.sqrt(G)
    c_free = weight * q * q * C
    w_of_q = e * s_scale                                         # w = E*/(2 sqrt G)
    a_sep = math.sqrt(math.pi) * c_free * w_of_q
    b_energy = 0.5 * math.pi * e * c_free
    innermost = float(np.min(G[G > 0])) if np.any(G > 0) else 0.0
    floor = 2.0 * RESOLVED_S * math.sqrt(innermost)
    return SeparationNodes(q=q, s_scale=np.ascontiguousarray(s_scale),
                           a_sep=np.ascontiguousarray(a_sep),
                           b_energy=np.ascontiguousarray(b_energy),
                           b_suffix=np.append(np.cumsum(b_energy[::-1])[::-1], 0.0),
                           ln_s_scale=np.log(s_scale), c_free=c_free,
                           pressure_floor=floor, e_star=e)


# ----------------------------------------------------------------------------------------------
# public layer
# ----------------------------------------------------------------------------------------------
@functools.lru_cache(maxsize=32)
def _cached_nodes(surface, e_star: float) -> SeparationNodes:
    return separation_nodes(surface, e_star)


def nodes_for(surface, e_star: float) -> SeparationNodes:
    """:func:`separation_nodes`, cached per (surface object, E*) when the surface hashes."""
    try:
        return _cached_nodes(surface, float(e_star))
    except TypeError:                                   # an unhashable user surface
        return separation_nodes(surface, float(e_star))


def _gamma(energy_correction) -> float:
    return 1.0 if energy_correction is None else float(energy_correction)


def _scene(surface, e_star, energy_correction, where: str, refused: str | None = None,
           work_of_adhesion=0.0):
    """(surface, e_star, gamma_S) of a scene without adhesion; adhesion (the Scene's, or a
    ``work_of_adhesion`` keyword > 0, checked first: the adhesion is then the reason given,
    not a Scene given together with the keyword) is refused with the message ``refused``
    (default ``ADHESION_REFUSED``; fields ``where`` and ``dg``)."""
    from ..scene import plan_scene

    dg = as_float_array(work_of_adhesion, "work_of_adhesion", "J/m^2", ndim=(0,))
    check_finite(dg, "work_of_adhesion", "J/m^2")
    check_nonnegative(dg, "work_of_adhesion", "J/m^2")
    if float(dg) > 0:
        raise ValueError((refused or ADHESION_REFUSED).format(where=where, dg=float(dg)))
    surface, kw = unpack_scene(surface, {"e_star": e_star, "energy_correction": energy_correction},
                               where)
    plan = plan_scene(surface, kw)
    if plan.route != "elastic":          # a Scene's adhesion (hardness and theories are
        raise ValueError((refused or ADHESION_REFUSED).format(   # refused when unpacked)
            where=where, dg=plan.work_of_adhesion))
    return surface, plan.e_star, _gamma(plan.energy_correction)


#: the message of every entry point asked for the separation of an adhesive scene
ADHESION_REFUSED = (
    "{where}: the mean separation and the contact stiffness are derived here for scenes "
    "without adhesion only (work_of_adhesion = 0); got work_of_adhesion = {dg!r} [J/m^2]. With "
    "adhesion the energy route dU_el = -p du still holds for the repulsive part, but the load "
    "balance changes (the detached rims carry tension) and no derivation of u(p) with the "
    "self-consistent detachment stress of seed Eqs. 8-9 is implemented")


@dataclass(frozen=True, repr=False)
class SeparationResult:
    """Result of :func:`solve_separation` (one scene without adhesion, many pressures).

    Attributes
    ----------
    pressure : numpy.ndarray, shape (n_p,)
        Nominal pressures. [Pa]
    separation : numpy.ndarray, shape (n_p,)
        Mean interfacial separation u(p). [m]
    stiffness : numpy.ndarray, shape (n_p,)
        Contact stiffness K = -dp/du per nominal area. [Pa/m]
    elastic_energy : numpy.ndarray, shape (n_p,)
        Stored elastic energy U_el per nominal area. [J/m^2]
    area : numpy.ndarray, shape (n_p,)
        A/A0 = erf(p / (2 sqrt G1)), the area the three rest on. [-]
    decay_length : float
        u0 of the small-pressure law p ~ exp(-u/u0). [m]
    energy_correction : float or None
        gamma_S of S (None: S = 1). [-]
    status : numpy.ndarray of int, shape (n_p,)
        0 ok (p = 0 included: u = inf, K = 0, U_el = 0 exactly); ``BELOW_RESOLVED`` (17)
        for pressures below ``pressure_floor`` (the quadrature near q0 is not resolved
        there); ``SEPARATION_UNDERFLOW`` (22) where u or Q = p/K falls below ~1e-292 m
        (pressures far above sqrt(G1): u may be 0 and K inf).
    pressure_floor : float
        The smallest pressure the quadrature resolves. [Pa]
    success : bool
        Whether every status is 0.
    message : str
        What the status codes mean.
    timings : dict
        Seconds spent. [s]

    See Also
    --------
    persson_fast.solve_separation : Returns a SeparationResult.
    persson_fast.GapDistribution : The distribution of the gaps.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> r = pf.solve_separation(s, [1e5, 1e6], e_star=1e9)
    >>> print(bool(np.all(r.success)), np.round(r.separation * 1e6, 4))
    True [3.7111 1.4316]
    """

    pressure: np.ndarray
    separation: np.ndarray
    stiffness: np.ndarray
    elastic_energy: np.ndarray
    area: np.ndarray
    decay_length: float
    energy_correction: float | None
    status: np.ndarray
    pressure_floor: float
    success: bool
    message: str
    timings: dict = field(default_factory=dict)

    def __repr__(self) -> str:
        from ..results import _span, _timings

        return (f"<SeparationResult: success={self.success}, message={self.message!r}\n"
                f"  pressure        {_span(self.pressure, 'Pa')}\n"
                f"  separation      {_span(self.separation, 'm')}\n"
                f"  stiffness       {_span(self.stiffness, 'Pa/m')}\n"
                f"  elastic_energy  {_span(self.elastic_energy, 'J/m^2')}\n"
                f"  decay_length    u0 = {self.decay_length:.6g} m; "
                f"timings: {_timings(self.timings)}>")


def _evaluate(nodes: SeparationNodes, gamma_s: float, p: np.ndarray, parallel=None,
              slope: bool = False):
    """(u, Q, U_el, status) at pressures p > 0 (no checks); with ``slope``, dQ/dp too:
    (u, Q, dQ/dp, U_el, status)."""
    v, dv, j0 = kfun_table(gamma_s)
    n = p.size
    outs = [np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.zeros(n, dtype=np.int64)]
    args = [np.ascontiguousarray(p, dtype=float), nodes.s_scale, nodes.ln_s_scale, nodes.a_sep,
            nodes.b_energy, nodes.b_suffix, gamma_s, j0, v, dv, KFUN_X_LOW,
            float(KFUN_STEPS_PER_UNIT), *outs]
    if n:
        run_rows(separation_sweep, separation_sweep_prange, args, (0,), (12, 13, 14, 15, 16), n,
                 parallel)
    u, q, dq, energy, status = args[12:17]
    return (u, q, dq, energy, status) if slope else (u, q, energy, status)


def decay_length(surface: Surface | Scene, *, e_star: float | None = None,
                 energy_correction: float | None = None,
                 work_of_adhesion: float = 0.0) -> float:
    """u0 of the small-pressure law p ~ exp(-u/u0) (no adhesion). [m]

    Parameters
    ----------
    surface : Surface or Scene
        The roughness, or a Scene without adhesion and without a hardness.
    e_star : float
        Effective modulus E* > 0 (with a surface). [Pa]
    energy_correction : float or None
        gamma_S of S = gamma_S + (1 - gamma_S) P^2; None: S = 1. [-]
    work_of_adhesion : float
        Delta gamma; must be 0 (the default): the decay length is derived without adhesion
        only, and a value > 0 is a ValueError that says so. [J/m^2]

    Returns
    -------
    float
        :math:`u_0 = \\sqrt{\\pi}\\, \\gamma_S \\int_{q_0}^{q_1} q^2 C(q) w(q) dq`
        (gamma_S = 1 for S = 1): -d ln p/du -> 1/u0 as p -> 0. It does not depend on E*
        (w/E* ... cancel: w = E*/(2 sqrt G) and G ~ E*^2). [m]

    Raises
    ------
    ValueError
        For bad input (``e_star`` not > 0, ``energy_correction`` outside [0, 1], a
        Scene with adhesion or a yield wall), naming the argument.

    See Also
    --------
    persson_fast.solve_separation : Mean separation and stiffness.
    persson_fast.pressure_at_separation : p(u).

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> print(f"{pf.decay_length(s, e_star=1e9) * 1e6:.4f} um")
    1.0638 um
    """
    surface, e, gamma_s = _scene(surface, e_star, energy_correction, "decay_length",
                                 work_of_adhesion=work_of_adhesion)
    return gamma_s * float(np.sum(nodes_for(surface, e).a_sep))


def solve_separation(surface: Surface | Scene, pressure: ArrayLike, *,
                     e_star: float | None = None, energy_correction: float | None = None,
                     parallel: bool | str | None = None,
                     work_of_adhesion: float = 0.0) -> SeparationResult:
    """Mean interfacial separation, contact stiffness and elastic energy (no adhesion).

    Parameters
    ----------
    surface : Surface or Scene
        The roughness, or a :class:`~persson_fast.Scene` without adhesion and without
        a hardness.
    pressure : float or array_like, shape (n_p,)
        Nominal pressures, >= 0 and finite. At p = 0 the surfaces are apart: u = inf,
        K = 0, U_el = 0 and A = 0 (the limits, exactly; status 0), as
        ``ContactResult.separation`` and ``persson-fast contact --separation`` give. [Pa]
    e_star : float
        Effective modulus E* = E/(1 - nu^2) > 0 (with a surface). [Pa]
    energy_correction : float or None
        gamma_S of S = gamma_S + (1 - gamma_S) P^2 in [0, 1]; None: S = 1 (the seed's). [-]
    parallel : None, bool, "threads" or "prange"
        As in :func:`persson_fast.solve_contact`.
    work_of_adhesion : float
        Delta gamma; must be 0 (the default): the separation is derived without adhesion
        only, and a value > 0 is a ValueError that says so. [J/m^2]

    Returns
    -------
    SeparationResult

    Raises
    ------
    ValueError
        For bad input (a pressure not finite and >= 0, ``e_star`` not > 0,
        ``energy_correction`` outside [0, 1], a Scene with adhesion or a yield wall), naming
        the argument.

    See Also
    --------
    persson_fast.SeparationResult : What it returns.
    persson_fast.pressure_at_separation : The inverse, p(u).
    persson_fast.decay_length : The decay length of p(u) at large u.
    persson_fast.gap_distribution : The distribution of the gaps.
    persson_fast.embed.contact_law : p(u) and K(u) tabulated for numba code.

    Notes
    -----
    Closed form of the module docstring (Persson, PRL 99, 125502 (2007); Yang & Persson,
    J. Phys.: Condens. Matter 20, 215214 (2008)); no diffusion solve. Relative accuracy
    ~1e-12 (measured, see the module docstring), whatever a solver's rtol. A scene with
    adhesion or a yield wall raises a ValueError (not derived here).

    Round trip: :func:`pressure_at_separation` of every u with status 0 returns its pressure
    (to its rtol; u = inf gives p = 0). At large pressure u ~ exp(-p^2/(4 G1)) leaves double
    precision (below ~1e-292 m its sum loses terms, below ~5e-324 m it is 0): such a u is
    flagged ``SEPARATION_UNDERFLOW``, and a u of 0 cannot be inverted (the inverse raises a
    ValueError saying so).

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> r = pf.solve_separation(s, [1e5, 1e6], e_star=1e9)
    >>> print(np.round(r.separation * 1e6, 4))
    [3.7111 1.4316]
    >>> print(np.round(r.stiffness / 1e12, 4))
    [0.0958 1.1318]
    """
    surface, e, gamma_s = _scene(surface, e_star, energy_correction, "solve_separation",
                                 work_of_adhesion=work_of_adhesion)
    p = as_float_array(pressure, "pressure", "Pa", ndim=(0, 1)).reshape(-1)
    check_finite(p, "pressure", "Pa")
    if np.any(p < 0):
        bad = int(np.argmax(p < 0))
        raise ValueError(f"pressure must be >= 0 for the separation [Pa] (tension needs "
                         f"adhesion, which is not derived here; at p = 0 the surfaces are "
                         f"apart, u = inf); got pressure[{bad}] = {float(p[bad])!r}")
    t0 = time.perf_counter()
    nodes = nodes_for(surface, e)
    t1 = time.perf_counter()
    apart = p == 0
    if np.any(apart):
        # the exact limits at p = 0: u = inf, K = 0, U_el = 0 (Q -> u0 > 0, so K = p/Q = 0)
        pos = ~apart
        u = np.full(p.size, np.inf)
        q = np.ones(p.size)
        energy = np.zeros(p.size)
        status = np.zeros(p.size, dtype=np.int64)
        u[pos], q[pos], energy[pos], status[pos] = _evaluate(nodes, gamma_s, p[pos], parallel)
    else:
        u, q, energy, status = _evaluate(nodes, gamma_s, p, parallel)
    t2 = time.perf_counter()
    status = np.where((status == OK) & (p < nodes.pressure_floor) & ~apart, BELOW_RESOLVED,
                      status)
    with np.errstate(divide="ignore", over="ignore"):
        stiffness = p / q
    area = erf(p * nodes.s_scale[0])
    ok = bool(np.all(status == OK))
    if ok:
        message = "ok"
    else:
        bad = int(np.argmax(status != OK))
        message = (f"{int(np.count_nonzero(status != OK))} of {p.size} pressures flagged; "
                   f"first: pressure[{bad}] = {float(p[bad])!r} Pa: "
                   f"{STATUS_MESSAGES[int(status[bad])]}")
    return SeparationResult(
        pressure=p, separation=u, stiffness=stiffness, elastic_energy=energy, area=area,
        decay_length=gamma_s * float(np.sum(nodes.a_sep)),
        energy_correction=None if gamma_s == 1.0 else gamma_s,
        status=status, pressure_floor=nodes.pressure_floor, success=ok, message=message,
        timings={"nodes": t1 - t0, "solve": t2 - t1})



#: Newton iterations of pressure_at_separation before it gives up (it converges in ~4-8)
INVERSE_MAX_ITER = 60


def pressure_at_separation(surface: Surface | Scene, separation: ArrayLike, *,
                           e_star: float | None = None, energy_correction: float | None = None,
                           rtol: float = 1e-10,
                           work_of_adhesion: float = 0.0) -> float | np.ndarray:
    """Nominal pressure at a given mean interfacial separation: the inverse of u(p).

    Parameters
    ----------
    surface : Surface or Scene
        The roughness, or a Scene without adhesion and without a hardness.
    separation : float or array_like
        Mean interfacial separation u > 0 (inf allowed: the surfaces apart, p = 0). A u of
        0 is refused: it is full contact, reached at no finite pressure (a 0 from
        :func:`solve_separation` is an underflow, flagged there). [m]
    e_star : float
        Effective modulus E* > 0 (with a surface). [Pa]
    energy_correction : float or None
        gamma_S of S = gamma_S + (1 - gamma_S) P^2; None: S = 1. [-]
    rtol : float
        Relative accuracy of the pressure, in [1e-12, 0.1] (default 1e-10) [-]; it is the
        tolerance of the root; u(p) itself is exact to ~1e-12.
    work_of_adhesion : float
        Delta gamma; must be 0 (the default): u(p) is derived without adhesion
        only, and a value > 0 is a ValueError that says so. [J/m^2]

    Returns
    -------
    float or numpy.ndarray
        p(u), same shape as ``separation``; monotone decreasing in u. [Pa]

    Raises
    ------
    ValueError
        For bad input (a separation not finite and > 0, ``e_star`` not > 0,
        ``rtol`` outside [1e-12, 0.1], a Scene with adhesion or a yield wall), naming the
        argument.

    See Also
    --------
    persson_fast.solve_separation : u(p), the inverse.
    persson_fast.embed.contact_law : p(u) tabulated for numba code.

    Notes
    -----
    Newton's method on ln u(e^x) = ln u_target in x = ln p, with the exact slope
    d ln u / d ln p = -p / (K u), safeguarded by a bracket (bisection when a step leaves it),
    from a bracket of log-spaced pressures; stops when the step in ln p (the relative
    change of p) is below rtol/10. Separations larger than u(``pressure_floor``) are
    continued by the exact small-pressure law p = p_f exp(-(u - u(p_f))/u0) (its error there
    is below the quadrature's). The bracket reaches the pressure where u underflows (about
    40 sqrt(G1)), so every positive double has its pressure.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> u = pf.solve_separation(s, [1e6], e_star=1e9).separation
    >>> p = pf.pressure_at_separation(s, u, e_star=1e9)
    >>> print(f"{p[0]:.6g} Pa")
    1e+06 Pa
    """
    surface, e, gamma_s = _scene(surface, e_star, energy_correction,
                                 "pressure_at_separation", work_of_adhesion=work_of_adhesion)
    rtol = _check_rtol(rtol)
    u_in = as_float_array(separation, "separation", "m")
    target = u_in.reshape(-1)
    if np.any(np.isnan(target)):
        bad = int(np.argmax(np.isnan(target)))
        raise ValueError(f"separation must be a number > 0 [m] (inf allowed: p = 0); got "
                         f"separation[{bad}] = nan")
    if np.any(target <= 0):
        bad = int(np.argmax(target <= 0))
        why = (" (full contact, reached at no finite pressure; a u of 0 from solve_separation "
               "is an underflow at a pressure far above sqrt(G1), flagged there with status "
               "SEPARATION_UNDERFLOW = 22, and its pressure cannot be recovered from it)"
               if target[bad] == 0 else "")
        raise ValueError(f"separation must be > 0 [m]{why}; got separation[{bad}] = "
                         f"{float(target[bad])!r}")
    nodes = nodes_for(surface, e)
    u0 = gamma_s * float(np.sum(nodes.a_sep))
    root_g1 = 0.5 / nodes.s_scale[0]
    # bracket: log-spaced pressures from the floor to where u underflows
    p_lo = max(nodes.pressure_floor, 1e-300)
    p_grid = np.geomspace(p_lo, 60.0 * root_g1, 64)
    u_grid = _evaluate(nodes, gamma_s, p_grid)[0]
    out = np.empty_like(target)
    below = target >= u_grid[0]             # u = inf included: p = 0 exactly (exp(-inf))
    out[below] = p_grid[0] * np.exp(-(target[below] - u_grid[0]) / u0)
    idx = np.nonzero(~below)[0]
    if idx.size:
        # u_grid decreasing to 0 (underflow): j with u_grid[j] > target >= u_grid[j+1]
        j = np.searchsorted(-u_grid, -target[idx], side="left") - 1
        j = np.clip(j, 0, p_grid.size - 2)
        lo = np.log(p_grid[j])
        hi = np.log(p_grid[j + 1])
        x = 0.5 * (lo + hi)
        ln_t = np.log(target[idx])
        for _ in range(INVERSE_MAX_ITER):
            u, q, _, _ = _evaluate(nodes, gamma_s, np.exp(x))
            with np.errstate(divide="ignore"):
                f = np.log(u) - ln_t
            lo = np.where(f > 0, x, lo)                 # u too large: p too small
            hi = np.where(f > 0, hi, x)
            with np.errstate(invalid="ignore", divide="ignore"):
                slope = -q / u                          # d ln u / d ln p (u = 0: bisect)
                step = -f / slope
            x_new = x + step
            bad = ~np.isfinite(x_new) | (x_new <= lo) | (x_new >= hi)
            x_new = np.where(bad, 0.5 * (lo + hi), x_new)
            done = np.abs(x_new - x) <= 0.1 * rtol
            x = x_new
            if np.all(done):
                break
        else:
            raise RuntimeError(f"pressure_at_separation: Newton's method did not converge in "
                               f"{INVERSE_MAX_ITER} steps (a bug: please report the scene)")
        out[idx] = np.exp(x)
    out = out.reshape(u_in.shape)
    return float(out) if u_in.ndim == 0 else out


def contact_fields(surface, e_star, energy_correction, parallel, pressure):
    """(separation, stiffness, elastic_energy, seconds) at pressures >= 0 of a validated
    scene without adhesion: the lazy fields of :class:`persson_fast.ContactResult`
    (p = 0: u = inf, K = 0, U_el = 0, as :func:`solve_separation` gives).

    The fields carry no status of their own: where :func:`solve_separation` flags a pressure
    (``BELOW_RESOLVED``, ``SEPARATION_UNDERFLOW``) a ``RuntimeWarning`` says which and why.
    """
    t0 = time.perf_counter()
    p = np.asarray(pressure, dtype=float)
    r = solve_separation(surface, p, e_star=e_star, energy_correction=energy_correction,
                         parallel=parallel)
    if not r.success:
        import warnings

        warnings.warn(f"separation: {r.message} (solve_separation gives the status per "
                      f"pressure)", RuntimeWarning, stacklevel=4)
    return r.separation, r.stiffness, r.elastic_energy, time.perf_counter() - t0


def warm_separation() -> None:
    """Compile (or load from the disk cache) the separation and contact-law kernels."""
    from .._kernels.contact_law import law_separation, law_sweep_unchecked

    nodes = nodes_for(SelfAffine(hurst=0.8, q0=1.0, q1=10.0, C0=1.0), 1.0)
    _evaluate(nodes, 1.0, np.array([0.1]), parallel=False, slope=True)
    kfun_table(1.0)
    table = (np.array([-1.0, 0.0]), np.array([1.0, 0.0]), np.array([-1.0, -1.0]),
             np.array([1.0, 0.0]), np.array([-1.0, -1.0]))
    out = [np.empty(1), np.empty(1), np.empty(1, dtype=np.int64)]
    law_sweep(table, np.array([0.5]), *out)
    law_sweep_unchecked(table, np.array([0.5]), *out)
    law_separation(table, 1.5)
