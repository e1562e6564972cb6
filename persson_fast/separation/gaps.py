"""The distribution of interfacial gaps at a nominal pressure (no adhesion).

Physics
-------
Persson's picture of the gaps (Almqvist, Campana, Prodanov & Persson, J. Mech. Phys. Solids
59, 2355 (2011); Persson's reviews): as the magnification grows from zeta to zeta + dzeta, a
part -A'(zeta) dzeta of the nominal area leaves apparent contact; there the surfaces are
apart by some mean gap u1(zeta), around which the roughness of the shorter wavelengths
(q > zeta q0, rms h(zeta)) spreads the gap. What is still in contact at zeta1 has u = 0:

    P(u) = A1 delta(u) + int_1^zeta1 dzeta [-A'(zeta)] P_zeta(u),
    h(zeta)^2 = 2 pi int_{zeta q0}^{q1} q C(q) dq,

A(zeta) = erf(p / (2 sqrt(G(zeta)))) the original theory's contact area, A1 = A(zeta1). The
weight of the continuous part is 1 - A1 for any P_zeta of unit weight.

The mean gap of the area that leaves contact at zeta follows from the separation. Let B(zeta)
be the gap volume (per nominal area) of the area still in apparent contact at zeta: B(1) is
the mean separation u(p) (Persson, PRL 99, 125502 (2007); Yang & Persson, J. Phys.: Condens.
Matter 20, 215214 (2008); :mod:`persson_fast.separation`), B(zeta1) = 0. The area that leaves
between zeta and zeta + dzeta carries -dB, so its mean gap is u1 = dB/dA, and the mean of P(u)
is int (-dA) u1 = B(1) - B(zeta1) = u(p) exactly, whatever the shape of each P_zeta as long as
its mean is u1 (Almqvist et al. write u1 = u(zeta) + u'(zeta) A/A', the same with
B = A u(zeta)). The area in apparent contact at zeta carries the mean pressure p/A(zeta) and
only the roughness above zeta q0, so, in the form of the separation,

    B(zeta) = A(zeta) u_zeta,
    u_zeta = sqrt(pi) int_{zeta q0}^{q1} dq q^2 C(q) w(q) Kfun(w(q) p / (A(zeta) E*)),

w = E*/(2 sqrt G(q)), Kfun with the energy correction S = gamma_S + (1 - gamma_S) P^2 where
``energy_correction`` is given (as :func:`persson_fast.solve_separation`). Yang & Persson's
u(zeta) takes w(q, zeta) from G(q) - G(zeta), a new start of the stress distribution at
zeta; that u(zeta) falls with zeta where A(zeta) is still 1 to rounding, so that u1 grows
without bound there (measured: at p = 0.19 E* on a two-decade self-affine scene, cells
0.15 decade wide, 7.8 % of u(p) sat in the first two cells, of weight 1e-48 and 1.5e-12). With the whole spectrum's w, as here, B changes
there only as fast as A does (both carry exp(-s^2), s = p/(2 sqrt G)).

Shapes of P_zeta (``shape``):

``"truncated"`` (default)
    A Gaussian of width h(zeta) truncated to u >= 0, its location chosen so that its mean is
    u1 exactly: N(u1, h^2) where u1 >> h (the form of Almqvist et al.), an exponential of mean
    u1 where u1 << h (the area that has just left contact stays close to it). Total weight 1
    and mean u(p) hold by construction.
``"folded"``
    Almqvist et al.'s published form: N(u1, h^2) mirrored at u = 0, (phi((u - u1)/h) +
    phi((u + u1)/h))/h. Weight 1; its mean, u1 erf(u1/(sqrt 2 h)) + h sqrt(2/pi)
    exp(-u1^2/(2 h^2)) per component, exceeds u1 where u1 is not >> h, so ``mean`` exceeds
    u(p) (at large pressures by far: there the area leaves contact at u1 << h).

Numerics
--------
The magnification integral is a sum over cells of a partition in ln G (``LN_G_STEP`` wide,
split at the spectrum's breakpoints and packed towards G1, where the width of the finer
roughness vanishes like sqrt(G1 - G)), from G = p^2 / (4 s_max^2), s_max = s1 + ``S_MARGIN``
(below it the weight is under exp(-S_MARGIN^2) of the rest), to G1. A cell's weight is the
exact A(zeta_a) - A(zeta_b) (from erfc), its mean gap (B_a - B_b)/(A_a - A_b), so that weight
and mean telescope exactly; B at the edges is a Gauss-Legendre sum (``PANEL_NODES`` nodes per
cell, each node's wavevector from G(q) = G_node by bisection on the surface's own G). The
error estimate of the density compares it with that of cells twice as wide (pairs merged),
which have the same weight and mean; ``mean_error`` is the difference from
:func:`persson_fast.solve_separation`'s u(p), an independent quadrature. The density is
returned on ``gaps``; by default a grid built per pressure so that the trapezoid rule of the
density matches the exact mass of every interval (from the components' cumulative
distributions) to its share of ``rtol`` of the continuous weight, the pressures' grids merged.
"""
from __future__ import annotations

import inspect
import math
import time
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from .._kernels.gaps import (FOLDED, TRUNCATED, component_locations, component_means,
                            mixture_cdf, mixture_density)
from .._kernels.status import OK, RTOL_NOT_MET, SEPARATION_UNDERFLOW, STATUS_MESSAGES
from .._validation import as_float_array, check_finite
from ..scene import _check_rtol
from .elastic import (KFUN_STEPS_PER_UNIT, KFUN_X_LOW, _scene, kfun_table,
                         solve_separation)

if TYPE_CHECKING:  # names of the type hints only
    from numpy.typing import ArrayLike

    from ..scene import Scene
    from ..surfaces.base import Surface

__all__ = ["gap_distribution", "GapDistribution", "GAP_SHAPES"]

#: the shapes of the component distributions (see the module docstring)
GAP_SHAPES = {"truncated": TRUNCATED, "folded": FOLDED}
#: Gauss-Legendre nodes per cell of the ln G partition, the first cell width in ln G, and
#: the narrowest: the cells are halved until the density's estimated error is below rtol
#: (seed of measurements on a two-decade self-affine scene, p/E* from 1e-4 to 0.19: errors
#: relative to the peak 1e-2 / 3e-3 / 7.5e-4 / 2e-4 at widths 1/4 / 1/8 / 1/16 / 1/32)
PANEL_NODES = 8
LN_G_STEP = 0.25
MIN_LN_G_STEP = 1.0 / 64.0
#: the integral starts where s = p/(2 sqrt G) exceeds s1 by this (weight below e^-100 of
#: the rest)
S_MARGIN = 10.0
#: the default gap grid reaches the largest component mean plus this many of its widths
#: (tail mass below 1e-22)
TAIL_WIDTHS = 10.0
#: points of the starting grid per pressure: evenly spaced, and per decade (log-spaced from
#: the smallest component scale up)
START_LINEAR = 64
START_PER_DECADE = 16
#: at most this many refinement passes (each splits the intervals that miss their share)
MAX_PASSES = 30
#: the most gaps a default grid may hold (per pressure, before merging)
MAX_GAPS = 20000
#: bisection steps of q(G) (a bracket of the table's cells shrinks to rounding)
Q_BISECTIONS = 64
#: cells packed towards G1 down to 1 - G/G1 = 2^-TOWARD_G1_LEVELS (edges uniform in
#: ln(1 - G/G1), refined with the cell width: fixed edges there left a floor of the error,
#: 1e-4 of the peak at widths below 1/32 on the seed scene)
TOWARD_G1_LEVELS = 40


@dataclass(frozen=True, repr=False)
class GapDistribution:
    """Result of :func:`gap_distribution` (one scene without adhesion, many pressures).

    Attributes
    ----------
    pressure : (n_p,) -- nominal pressures. [Pa]
    gaps : (n_u,) -- interfacial gaps u >= 0 at which the density is given. [m]
    density : (n_p, n_u) -- probability density of the gap outside the contact. [1/m]
    contact_fraction : (n_p,) -- A/A0 = erf(p / (2 sqrt G1)), the weight at u = 0:
        trapz(density, gaps) + contact_fraction == 1 to ``weight_error``. [-]
    mean : (n_p,) -- the mean gap of the distribution (the contact counted at u = 0); with
        shape "truncated" it equals ``separation`` (to ``mean_error``). [m]
    separation : (n_p,) -- :func:`persson_fast.solve_separation`'s u(p), for comparison. [m]
    weight_error : (n_p,) -- abs(trapz(density, gaps) + contact_fraction - 1) on ``gaps``. [-]
    mean_error : (n_p,) -- shape "truncated": abs(mean - separation), the difference from an
        independent quadrature of u(p); "folded": the change of the mean from cells twice as
        wide. [m]
    error_estimate : (n_p,) -- estimated error of the density from the magnification
        quadrature, relative to its largest value (half the change from cells twice as
        wide). [-]
    shape : str -- "truncated" or "folded".
    energy_correction : float or None -- gamma_S of S (None: S = 1). [-]
    status : (n_p,) int -- 0 ok; ``RTOL_NOT_MET`` (15) where weight_error, error_estimate or
        mean_error / mean exceeds rtol; ``BELOW_RESOLVED`` (17) and ``SEPARATION_UNDERFLOW``
        (22) as :func:`persson_fast.solve_separation` gives them (the continuous part then has
        no weight left in double precision: density 0, mean 0).
    success : bool, message : str, timings : dict

    See Also
    --------
    persson_fast.gap_distribution : Returns a GapDistribution.
    persson_fast.SeparationResult : The mean separation alone.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> g = pf.gap_distribution(s, [1e6], e_star=1e9)
    >>> print(bool(np.all(g.success)), round(float(g.contact_fraction[0]), 5))
    True 0.00802
    >>> c = g.cumulative([1e-6, 1e-5])
    >>> print(np.round(c, 4))
    [[0.3933 1.    ]]
    """

    pressure: np.ndarray
    gaps: np.ndarray
    density: np.ndarray
    contact_fraction: np.ndarray
    mean: np.ndarray
    separation: np.ndarray
    weight_error: np.ndarray
    mean_error: np.ndarray
    error_estimate: np.ndarray
    shape: str
    energy_correction: float | None
    status: np.ndarray
    success: bool
    message: str
    timings: dict = field(default_factory=dict)
    _components: tuple = field(default=(), repr=False, compare=False)

    def density_at(self, gaps: ArrayLike) -> np.ndarray:
        """The density at other gaps (the same components as ``density``): (n_p, n). [1/m]

        Parameters
        ----------
        gaps : array_like, shape (n,) -- gaps >= 0, finite. [m]
        """
        u = _check_gaps(gaps, minimum=1)
        return np.array([mix.density(u) if mix.weight.size else np.zeros(u.size)
                         for mix in self._components])

    def cumulative(self, gaps: ArrayLike) -> np.ndarray:
        """Probability that the gap is at most u, the contact (u = 0) included: (n_p, n),
        exact for the components (no grid), 1 beyond the last of them. [-]

        Parameters
        ----------
        gaps : array_like, shape (n,) -- gaps >= 0, finite. [m]
        """
        u = _check_gaps(gaps, minimum=1)
        out = np.empty((len(self._components), u.size))
        for k, mix in enumerate(self._components):
            cont = mix.cdf(u) if mix.weight.size else np.zeros(u.size)
            # the continuous part's weight is 1 - A1 to its quadrature error: scaled to it
            total = mix.total
            scale = (1.0 - self.contact_fraction[k]) / total if total > 0 else 0.0
            out[k] = self.contact_fraction[k] + cont * scale
        return out

    def __repr__(self) -> str:
        from ..results import _span, _timings

        return (f"<GapDistribution ({self.shape}): success={self.success}, "
                f"message={self.message!r}\n"
                f"  pressure          {_span(self.pressure, 'Pa')}\n"
                f"  gaps              "
                + (f"{self.gaps.size} from {self.gaps[0]:.4g} to {self.gaps[-1]:.4g} m\n"
                   if self.gaps.size else "0 values\n") +
                f"  contact_fraction  {_span(self.contact_fraction, '')}\n"
                f"  mean              {_span(self.mean, 'm')}\n"
                f"  timings: {_timings(self.timings)}>")


#: the signature users see (``help``, the API page): the private field ``_components`` (the
#: mixture components behind ``density_at`` and ``cumulative``) is not an argument of theirs
GapDistribution.__signature__ = inspect.Signature(
    [p for p in inspect.signature(GapDistribution).parameters.values()
     if not p.name.startswith("_")])

def _check_gaps(gaps, minimum=2) -> np.ndarray:
    """Gaps [m]: finite, >= 0, strictly increasing, at least ``minimum`` of them."""
    u = as_float_array(gaps, "gaps", "m", ndim=(0, 1)).reshape(-1)
    check_finite(u, "gaps", "m")
    if u.size < minimum or np.any(u < 0) or np.any(np.diff(u) <= 0):
        raise ValueError(f"gaps must hold at least {minimum} value{'s' if minimum > 1 else ''} "
                         f">= 0, strictly increasing [m]; got gaps = {u!r}")
    return u


class _Inverse:
    """q(G) of one surface and modulus: a table of G on a ln q grid (with points packed
    towards q0, where G ~ q - q0) brackets the root, bisection on the surface's own G
    refines it to rounding."""

    def __init__(self, surface, e_star):
        self.surface, self.e_star = surface, e_star
        q0, q1 = surface.q0, surface.q1
        span = q1 / q0 - 1.0
        near = q0 * (1.0 + np.geomspace(1e-15 * span, 0.5 * span, 64))
        main = np.geomspace(q0, q1, max(2, int(math.ceil(64 * math.log10(q1 / q0)))) + 1)
        extra = np.asarray(surface.breakpoints(), dtype=float) if hasattr(
            surface, "breakpoints") else np.array([q0, q1])
        q = np.unique(np.clip(np.concatenate([near, main, extra, [q0, q1]]), q0, q1))
        self.q = q
        self.G = np.maximum.accumulate(self._g(q))

    def _g(self, q):
        g = np.asarray(self.surface.diffusion_time(q, self.e_star), dtype=float)
        return np.where(q <= self.surface.q0, 0.0, g)

    def __call__(self, g_target):
        g_target = np.asarray(g_target, dtype=float)
        k = np.clip(np.searchsorted(self.G, g_target, side="left"), 1, self.q.size - 1)
        lo, hi = self.q[k - 1].copy(), self.q[k].copy()
        for _ in range(Q_BISECTIONS):
            mid = 0.5 * (lo + hi)
            below = self._g(mid) < g_target
            lo = np.where(below, mid, lo)
            hi = np.where(below, hi, mid)
        return 0.5 * (lo + hi)


class _Cells:
    """The partition of ln G shared by every pressure of one call, and its quadrature nodes:
    edges, per node its s-independent weight k_m [m] (sqrt(pi) q^2 C w dq in ln G times the
    Gauss-Legendre weight) and sqrt(G_m), per cell the rms h [m] of the roughness above the
    cell's middle."""

    def __init__(self, surface, e, inverse, ln_lo, ln_step=None):
        ln_step = LN_G_STEP if ln_step is None else ln_step
        G1 = float(inverse.G[-1])
        ln_hi = math.log(G1)
        breaks = np.asarray(surface.breakpoints(), dtype=float) if hasattr(
            surface, "breakpoints") else np.array([surface.q0, surface.q1])
        g_breaks = np.asarray(surface.diffusion_time(breaks, e), dtype=float)
        n = max(1, int(math.ceil((ln_hi - ln_lo) / ln_step)))
        # packed towards G1 uniformly in ln(1 - G/G1), a factor 2 per cell at the first
        # width (LN_G_STEP) and refined with it, down to 1 - G/G1 = 2^-TOWARD_G1_LEVELS
        dv = math.log(2.0) * ln_step / LN_G_STEP
        v = -dv * np.arange(1.0, math.ceil(TOWARD_G1_LEVELS * math.log(2.0) / dv) + 1.0)
        toward = ln_hi + np.log1p(-np.exp(v))
        edges = np.concatenate([np.linspace(ln_lo, ln_hi, n + 1),
                                np.log(g_breaks[g_breaks > 0]), toward])
        self.edges = np.unique(edges[(edges >= ln_lo) & (edges <= ln_hi)])
        x, w = np.polynomial.legendre.leggauss(PANEL_NODES)
        a, b = self.edges[:-1, None], self.edges[1:, None]
        nodes = (0.5 * (b - a) * x + 0.5 * (a + b)).ravel()
        g = np.exp(nodes)
        q = inverse(g)
        self.root_g = np.sqrt(g)
        self.k = (0.5 * (b - a) * w).ravel() * 2.0 * self.root_g / (math.sqrt(math.pi) * e * q)
        self.first = np.arange(self.edges.size, dtype=np.int64) * PANEL_NODES
        q_mid = inverse(np.exp(0.5 * (self.edges[:-1] + self.edges[1:])))
        m1 = np.asarray(surface.moment(1, q_mid, np.full(q_mid.shape, surface.q1)), float)
        self.width = np.sqrt(2.0 * math.pi * np.maximum(m1, 0.0))
        self.root_g_edges = np.sqrt(np.exp(self.edges))


class _Mixture:
    """The components of one pressure's distribution on one quadrature level: weights
    [-], locations t [-] and widths [m], their means [m]."""

    def __init__(self, weight, t, width, shape):
        self.weight, self.t, self.width, self.shape = weight, t, width, shape
        self.means = np.empty(weight.size)
        component_means(shape, t, width, self.means)

    @property
    def total(self) -> float:
        return float(np.sum(self.weight))

    @property
    def mean(self) -> float:
        return float(np.sum(self.weight * self.means))

    def density(self, gaps):
        out = np.empty(gaps.size)
        mixture_density(self.shape, self.weight, self.t, self.width, gaps, out)
        return out

    def cdf(self, gaps):
        out = np.empty(gaps.size)
        mixture_cdf(self.shape, self.weight, self.t, self.width, gaps, out)
        return out

    def reach(self) -> float:
        """A gap beyond which the continuous part has no weight left (TAIL_WIDTHS widths
        beyond the largest location). [m]"""
        if self.weight.size == 0:
            return 0.0
        return float(np.max(self.width * (np.maximum(self.t, 0.0) + TAIL_WIDTHS)))

    def smallest_scale(self) -> float:
        """The smallest length a component varies on (its mean or its width). [m]"""
        live = self.weight > 0
        if not np.any(live):
            return 0.0
        return float(np.min(np.minimum(self.means[live], self.width[live])))


def _mixture(p, gamma_s, cells, shape, table):
    """The components of the distribution at pressure p [Pa] on ``cells``: one per cell,
    of weight A_a - A_b and mean (B_a - B_b)/(A_a - A_b) (see the module docstring)."""
    from .._kernels.gaps import partial_separations

    s_edges = p / (2.0 * cells.root_g_edges)
    area = np.array([math.erf(x) for x in s_edges])
    outside = np.array([math.erfc(x) for x in s_edges])          # 1 - A, without cancellation
    v, dv, j0 = table
    u_edges = np.empty(area.size)
    partial_separations(p, area, cells.first, p / (2.0 * cells.root_g), cells.k, gamma_s, j0,
                        v, dv, KFUN_X_LOW, float(KFUN_STEPS_PER_UNIT), u_edges)
    volume = area * u_edges                                        # B at the edges
    d_area = outside[1:] - outside[:-1]
    d_volume = volume[:-1] - volume[1:]
    with np.errstate(divide="ignore", invalid="ignore"):
        mean = d_volume / d_area
    keep = (d_area > 0.0) & (d_volume > 0.0) & np.isfinite(mean) & (cells.width > 0.0)
    weight, mean, width = d_area[keep], mean[keep], cells.width[keep]
    t = np.empty(mean.size)
    component_locations(shape, mean, width, t)
    return _Mixture(weight, t, width, shape)


def _probe_gaps(mix: _Mixture) -> np.ndarray:
    """Gaps [m] on which two quadrature levels of one pressure are compared: evenly spaced up
    to the reach and log-spaced from the smallest component scale."""
    top = mix.reach()
    if top <= 0.0:
        return np.array([0.0])
    small = max(mix.smallest_scale(), top * 1e-12)
    return np.unique(np.concatenate([np.linspace(0.0, top, 401),
                                     np.geomspace(0.1 * small, top, 201)]))


def _level_estimate(fine: _Mixture, coarse: _Mixture) -> float:
    """Estimated error of ``fine``'s density relative to its peak: half the largest change
    from cells twice as wide (the cell sum converges at second order; measured ratios of
    successive changes 3.2-4, so half the change is 1-1.5x the error of the finer)."""
    u = _probe_gaps(fine)
    f = fine.density(u)
    peak = float(np.max(f))
    if not peak > 0.0:
        return 0.0
    return 0.5 * float(np.max(np.abs(f - coarse.density(u)))) / peak


def _default_grid(mix: _Mixture, rtol: float):
    """A gap grid [m] on which the trapezoid rule of ``mix``'s density matches the exact mass
    of every interval to its share of rtol times the continuous weight (see the module
    docstring): intervals that miss are halved, at most ``MAX_PASSES`` times and up to
    ``MAX_GAPS`` gaps; each pass evaluates the density and the cumulative distribution at the
    new gaps only."""
    total = mix.total
    top = mix.reach()
    if total <= 0.0 or top <= 0.0:
        return np.array([0.0, 1.0])
    small = max(mix.smallest_scale(), top * 1e-12)
    decades = max(1.0, math.log10(top / small))
    u = np.unique(np.concatenate([np.linspace(0.0, top, START_LINEAR + 1),
                                  np.geomspace(small * 0.1, top,
                                               int(math.ceil(START_PER_DECADE * decades)) + 1)]))
    f, cdf = mix.density(u), mix.cdf(u)
    for _ in range(MAX_PASSES):
        mass = np.diff(cdf)
        trap = 0.5 * (f[1:] + f[:-1]) * np.diff(u)
        allowed = 0.25 * rtol * (mass + total / mass.size)
        bad = np.flatnonzero(np.abs(trap - mass) > allowed)
        if bad.size == 0 or u.size + bad.size > MAX_GAPS:
            break
        mid = 0.5 * (u[bad] + u[bad + 1])
        u_new = np.concatenate([u, mid])
        order = np.argsort(u_new, kind="stable")
        u = u_new[order]
        f = np.concatenate([f, mix.density(mid)])[order]
        cdf = np.concatenate([cdf, mix.cdf(mid)])[order]
    return u


#: the message of gap_distribution asked for the gaps of an adhesive scene
GAPS_ADHESION_REFUSED = (
    "{where}: work_of_adhesion must be 0 [J/m^2]: the gap distribution is defined here for "
    "scenes without adhesion only; got work_of_adhesion = {dg!r}. Its weights are the "
    "original theory's contact area without adhesion and its mean is the separation u(p), "
    "derived without adhesion too (Almqvist et al. 2011); with adhesion the detached rims "
    "carry tension and no derivation of P(u) with the self-consistent detachment stress of "
    "seed Eqs. 8-9 is implemented")


def gap_distribution(surface: Surface | Scene, pressure: ArrayLike, *,
                     e_star: float | None = None, energy_correction: float | None = None,
                     gaps: ArrayLike | None = None, shape: str = "truncated",
                     rtol: float = 1e-3, work_of_adhesion: float = 0.0) -> GapDistribution:
    """Probability distribution of the interfacial gap at nominal pressures (no adhesion).

    Parameters
    ----------
    surface : Surface or Scene
        The roughness, or a :class:`~persson_fast.Scene` without adhesion or yield wall.
    pressure : float or array_like, shape (n_p,)
        Nominal pressures, > 0 and finite (at p = 0 the surfaces are apart: every gap is
        infinite). [Pa]
    e_star : float
        Effective modulus E* > 0 (with a surface). [Pa]
    energy_correction : float or None
        gamma_S of S = gamma_S + (1 - gamma_S) P^2 in [0, 1], as in
        :func:`persson_fast.solve_separation` (it sets the mean gaps; the contact area is the
        original theory's either way); None: S = 1. [-]
    gaps : array_like or None
        Gaps at which to give the density: increasing, >= 0, finite, at least two. [m]
        None: a grid on which the trapezoid rule of every pressure's density matches its
        intervals' exact masses to ``rtol`` (see Notes), the pressures' grids merged.
    shape : str
        Shape of the gap distribution of the area that leaves contact at one magnification:
        "truncated" (default: a Gaussian of the finer roughness' rms, truncated at u = 0,
        with the mean Persson's theory gives it; the mean of the whole is then
        :func:`persson_fast.solve_separation`'s u(p)) or "folded" (Almqvist et al. 2011: the
        same Gaussian mirrored at u = 0, whose mean exceeds u(p)). See
        the module ``persson_fast.separation.gaps``.
    rtol : float
        Tolerance (default 1e-3) of the density's magnification quadrature (relative to its
        peak: the cells are halved until the estimate meets it, down to a width of 1/64 in
        ln G), of the trapezoid weight on the default grid and of a given grid, and of the
        mean against solve_separation's u(p); a pressure that misses one is flagged. In
        [1e-12, 0.1]. [-]
    work_of_adhesion : float
        Delta gamma; must be 0 (the default): the distribution is defined without adhesion
        only, and a value > 0 is a ValueError that says so. [J/m^2]

    Returns
    -------
    GapDistribution
        ``gaps``, ``density``, ``contact_fraction``, ``mean`` (and ``separation``,
        ``weight_error``, ``mean_error``, ``error_estimate``, ``status``).

    Raises
    ------
    ValueError
        For bad input (naming the argument), a scene with adhesion (a Scene's, or
        ``work_of_adhesion`` > 0) or a yield wall.

    See Also
    --------
    persson_fast.GapDistribution : What it returns.
    persson_fast.solve_separation : The mean separation u(p), its mean.

    Notes
    -----
    P(u) = A1 delta(u) + int dzeta (-A'(zeta)) P_zeta(u) (Almqvist, Campana, Prodanov &
    Persson, J. Mech. Phys. Solids 59, 2355 (2011)), where P_zeta has the mean gap of the
    area leaving contact at zeta, u1 = dB/dA with B(zeta) = A(zeta) u_zeta the gap volume of
    the area still in apparent contact, from the scale decomposition of the mean separation
    (Persson 2007; Yang & Persson 2008; the module docstring derives it). With s = p/(2 sqrt
    G(zeta)), A = erf(s), w(q) = E*/(2 sqrt G(q)), x(q) = w(q) p/(A E*) and
    u_zeta = sqrt(pi) int_{zeta q0}^{q1} dq q^2 C(q) w(q) Kfun(x(q))::

        u1 = u_zeta + A (du_zeta/dzeta) / A'(zeta)
           = u_zeta + (A p/(E* zeta q0 s^2)) exp(s^2) Kfun(s/A)
             - (p/(A E*)) sqrt(pi) int_{zeta q0}^{q1} dq q^2 C(q) w(q)^2 Kfun'(x(q)),

    the second term from the lower limit of u_zeta's integral, the third (>= 0, Kfun
    decreasing) from the pressure p/A(zeta) on the area still in contact (where A = 1 to
    rounding the second term is (p/E*) Kfun(s) exp(s^2)/(zeta q0 s^2); checked against a
    numerical dB/dA: the two other terms carry about half of u1 at A = 0.5-0.75). The
    solver takes the exact differences (B_a - B_b)/(A_a - A_b) over each cell of its ln G
    partition, whose limit this is. Weight 1 and (shape "truncated") mean u(p) hold by
    construction, numerically to the reported errors. The magnification integral is a sum
    over cells in ln G (second order in their width; its error is estimated against cells
    twice as wide; measured 1-2x the actual error on four scenes). Cost, seed scene, ten
    pressures on one core of a shared machine: 0.55 s at rtol 1e-3, 5.7 s at 1e-4.

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    >>> g = pf.gap_distribution(s, [1e6], e_star=1e9)
    >>> print(g.density.shape[0], g.gaps.size > 100)
    1 True
    >>> print(np.isclose(g.mean[0], g.separation[0], rtol=1e-3))
    True
    """
    t0 = time.perf_counter()
    surface, e, gamma_s = _scene(surface, e_star, energy_correction, "gap_distribution",
                                 GAPS_ADHESION_REFUSED, work_of_adhesion)
    if not isinstance(shape, str) or shape not in GAP_SHAPES:
        raise ValueError(f"shape must be one of {', '.join(repr(s) for s in GAP_SHAPES)} [-]; "
                         f"got shape = {shape!r}")
    rtol = _check_rtol(rtol)
    p = as_float_array(pressure, "pressure", "Pa", ndim=(0, 1)).reshape(-1)
    check_finite(p, "pressure", "Pa")
    if np.any(p <= 0):
        i = int(np.argmax(p <= 0))
        raise ValueError(f"pressure must be > 0 for a gap distribution [Pa] (at p = 0 the "
                         f"surfaces are apart and every gap is infinite; tension needs "
                         f"adhesion, which is not derived here); got pressure[{i}] = "
                         f"{float(p[i])!r}")
    user_gaps = None if gaps is None else _check_gaps(gaps)
    if p.size == 0:                  # as solve_contact and solve_separation: an empty result
        u = np.zeros(0) if user_gaps is None else user_gaps
        empty = np.zeros(0)
        return GapDistribution(
            pressure=p, gaps=u, density=np.zeros((0, u.size)), contact_fraction=empty,
            mean=empty.copy(), separation=empty.copy(), weight_error=empty.copy(),
            mean_error=empty.copy(), error_estimate=empty.copy(), shape=shape,
            energy_correction=None if energy_correction is None else float(energy_correction),
            status=np.zeros(0, dtype=np.int64), success=True, message="ok",
            timings={"components": 0.0, "total": time.perf_counter() - t0}, _components=())
    code = GAP_SHAPES[shape]
    sep = solve_separation(surface, p, e_star=e, energy_correction=energy_correction)
    inverse = _Inverse(surface, e)
    table = kfun_table(gamma_s)
    G1 = float(inverse.G[-1])
    s1 = p / (2.0 * math.sqrt(G1))
    positive = inverse.G[inverse.G > 0]
    with np.errstate(over="ignore", invalid="ignore"):
        ln_g = np.log(p * p / (4.0 * (s1 + S_MARGIN) ** 2))
    # p beyond ~1e154 Pa overflows p * p (inf/inf): the same in logarithms
    ln_g = np.where(np.isnan(ln_g), 2.0 * (np.log(p) - np.log(2.0 * (s1 + S_MARGIN))), ln_g)
    ln_lo = max(float(np.min(ln_g)), math.log(positive[0]))
    ln_start = min(ln_lo, math.log(G1) - LN_G_STEP)
    contact = np.asarray([math.erf(x) for x in s1])
    step = LN_G_STEP
    coarse = [_mixture(pk, gamma_s, _Cells(surface, e, inverse, ln_start, 2.0 * step), code,
                       table) for pk in p]
    while True:
        cells = _Cells(surface, e, inverse, ln_start, step)
        fine = [_mixture(pk, gamma_s, cells, code, table) for pk in p]
        estimate = np.array([_level_estimate(a, b) for a, b in zip(fine, coarse)])
        # the folded shape's mean is not fixed by construction: it converges with the cells
        mean_change = np.array([abs(a.mean - b.mean) for a, b in zip(fine, coarse)])
        mean_ok = code == TRUNCATED or np.all(
            mean_change <= rtol * np.array([a.mean for a in fine]))
        if (np.all(estimate <= rtol) and mean_ok) or step <= MIN_LN_G_STEP * 1.0001:
            break
        step *= 0.5
        coarse = fine
    t1 = time.perf_counter()
    if user_gaps is None:
        grids = [_default_grid(m, rtol) for m in fine]
        u = np.unique(np.concatenate(grids))
    else:
        u = user_gaps
    n_p = p.size
    density = np.zeros((n_p, u.size))
    weight_error = np.zeros(n_p)
    mean = np.zeros(n_p)
    mean_error = np.zeros(n_p)
    status = np.where(sep.status != OK, sep.status, OK).astype(np.int64)
    for k in range(n_p):
        mix, rough = fine[k], coarse[k]
        if mix.weight.size:
            density[k] = mix.density(u)
        mean[k] = mix.mean
        mean_error[k] = abs(mix.mean - sep.separation[k]) if code == TRUNCATED else abs(
            mix.mean - rough.mean)
        trap = float(np.sum(0.5 * (density[k, 1:] + density[k, :-1]) * np.diff(u)))
        weight_error[k] = abs(trap + contact[k] - 1.0)
        if mix.total <= 0.0 and status[k] == OK and contact[k] < 1.0:
            status[k] = SEPARATION_UNDERFLOW
        if status[k] == OK and (weight_error[k] > rtol or estimate[k] > rtol
                                or mean_error[k] > rtol * mean[k]):
            status[k] = RTOL_NOT_MET
    flagged = np.flatnonzero(status != OK)
    if flagged.size == 0:
        success, message = True, "ok"
    else:
        success, parts = False, []
        for c in sorted(set(int(c) for c in status[flagged])):
            first = int(flagged[status[flagged] == c][0])
            if c == RTOL_NOT_MET:
                rows = np.flatnonzero(status == RTOL_NOT_MET)
                parts.append(
                    f"gap distribution less accurate than rtol {rtol:g} at {rows.size} "
                    f"pressure(s), first at index {first}: trapezoid weight off by up to "
                    f"{weight_error[rows].max():.3g}, density quadrature up to "
                    f"{estimate[rows].max():.3g} of its peak, mean up to "
                    f"{np.max(mean_error[rows] / np.maximum(mean[rows], 1e-300)):.3g} relative"
                    + ("; the given gaps do not resolve the distribution"
                       if user_gaps is not None else "; cells at their narrowest"))
            else:
                parts.append(f"{STATUS_MESSAGES.get(c, 'status')} (code {c}) at pressure "
                             f"index {first}")
        message = "; ".join(parts)
    timings = {"components": t1 - t0, "total": time.perf_counter() - t0}
    return GapDistribution(
        pressure=p, gaps=u, density=density, contact_fraction=contact, mean=mean,
        separation=np.asarray(sep.separation, dtype=float), weight_error=weight_error,
        mean_error=mean_error, error_estimate=estimate, shape=shape,
        energy_correction=None if energy_correction is None else float(energy_correction),
        status=status, success=success, message=message, timings=timings,
        _components=tuple(fine))
