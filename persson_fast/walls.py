"""Walls given as functions: sample a callable sigma_a(G) to the tolerance of the solve.

The kernels take the absorbing wall as samples on the schedule G, linear in G between them.
A wall given as a vectorised callable ``G [Pa^2] -> sigma_a [Pa]`` is turned into such a
schedule here: the user's output times, G = 0, the declared kinks, and points inserted
adaptively until the piecewise-linear interpolant is within a stress tolerance of the callable
everywhere. The sampling error then belongs to ``rtol`` instead of being a hidden floor.

Tolerance (a documented, conservative bound)
-------------------------------------------
Comparison principle: a wall displaced by at most eps towards or away from the distribution
changes the area by at most A(sigma0 + eps) - A(sigma0 - eps), the effect of moving the start.
Localised in time, a wall error e at diffusion time G acts on the surviving mass through the
density next to the wall, whose stress scale is the profile width sqrt(2G) (or the layer width
1/|v| of a wall moving into the distribution at v = d sigma_a/dG < 0), and which is reduced by
the Gaussian factor exp(-gap^2 / 4G) while the wall is still a gap = sigma0 + sigma_a(G) away
from the start. The relative area error contributed per e-fold of G is then about

    |dA| / A  <~  kappa * e / l(G) * exp(-gap^2 / 4G),   l = min(sqrt(2G), 1/|v|),

with kappa = 1 an upper bound (measured 0.2-0.3 for sigma_a = 0.1 + 0.5 sqrt(G)); errors of the
same sign add over the L e-folds of G in which the wall meets the distribution. The interpolant
is therefore refined until, at every probe point,

    |sigma_a(G) - chord(G)|  <=  WALL_BUDGET * rtol * l(G) * exp(gap^2 / 4G) / L,

with the smallest gap over the pressures in contact (the most demanding one) and a rounding
floor. The wall's share of the error budget is WALL_BUDGET = 0.25 of rtol with kappa = 1,
about 0.06 rtol in practice. The kernels estimate the error of the sampled wall only;
:meth:`WallSampling.area_error` estimates the chords' own part, per pressure and output time,
by the same bound summed over the final intervals with their actual deviations (1-5x the
sampling error on the square-root wall); a caller adds it to the kernel's estimate.

Refinement
----------
Intervals are bisected (in ln G when b/a > 1.5, else in G) while any of the three probes at
their quarter points (the midpoints of the children) misses the tolerance; all failing
intervals of a round are split together and the new probes evaluated in one vectorised call.
A smooth wall's deviation falls x4 per bisection; one that falls less than x KINK_DROP marks a
kink (slope jump), which is then refined until its deviation is below KINK_FRACTION of the
tolerance, leaving a sample next to it. A deviation that does not fall at all down to an
interval of relative width ~1e-14 is a jump: a ValueError (a jump is given as samples with a
repeated G). At most ``max_points`` schedule points: past that the worst intervals are split
first and the sampling is reported as capped.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ._validation import _bool_in, check_not_bool

__all__ = ["WallSampling", "sample_wall", "check_wall_callable", "check_kinks",
           "CallableWallError"]

#: share of rtol given to the wall's interpolation error (with the bound's kappa = 1) [-]
WALL_BUDGET = 0.25
#: the constant of the bound in :meth:`WallSampling.area_error` (an upper bound; measured
#: 0.2-0.3 on the square-root wall) [-]
KAPPA = 1.0
#: a child interval whose deviation fell less than this factor marks a kink (smooth: 4) [-]
KINK_DROP = 2.8
#: a kink is refined until its deviation is below this fraction of the tolerance [-]
KINK_FRACTION = 1e-3
#: seed: every interval of the schedule is split into at least this many pieces, and pieces
#: away from G = 0 span at most a factor SEED_RATIO in G [-]
N_SEED = 4
SEED_RATIO = 2.0
#: bisection in ln G above this ratio b/a, in G below [-]
GEOMETRIC_RATIO = 1.5
#: largest number of e-folds of G over which the wall errors are assumed to add up [-]
L_MAX = 40.0
#: relative rounding floor of the stress tolerance (the chord is computed in float64) [-]
ROUND_REL = 1e-13
#: default cap on the number of schedule points [-]
MAX_POINTS = 200_000
#: smallest relative width of an interval (then a failing one is a jump) [-]
MIN_REL_WIDTH = 1e-14
#: smallest first positive time next to G = 0, relative to G[-1] [-]
MIN_REL_FIRST = 1e-60
#: most bisection rounds
MAX_ROUNDS = 400


@dataclass(frozen=True)
class WallSampling:
    """A callable wall sampled for the kernels.

    Attributes
    ----------
    G : (n_s,) -- the schedule: 0, the user's times, the kinks and the inserted points,
        strictly increasing. [Pa^2]
    sigma_a : (n_s,) -- the callable on the schedule. [Pa]
    index : (n_t,) int -- position of each of the user's times in ``G``.
    at_user : (n_t,) -- the callable at the user's times. [Pa]
    kinks_found : (k,) -- kinks found by the refinement: schedule points within the width of
        the last kink-marked interval of a slope jump (informative). [Pa^2]
    capped : bool -- the point cap stopped the refinement before the tolerance was met.
    worst_ratio : float -- largest probe deviation over its tolerance at the end (<= 1 when
        the tolerance was met). [-]
    n_inserted : int -- points added to the user's times, G = 0 and the kinks.
    leaves : (5, n_l) -- the final intervals of the refinement: their ends a, b [Pa^2], the
        largest deviation of the callable from the chord at their probes [Pa], the callable
        at their midpoints [Pa] and the chord's slope [-]; what :meth:`area_error` sums.
    """

    G: np.ndarray
    sigma_a: np.ndarray
    index: np.ndarray
    at_user: np.ndarray
    kinks_found: np.ndarray = field(default_factory=lambda: np.zeros(0))
    capped: bool = False
    worst_ratio: float = 0.0
    n_inserted: int = 0
    leaves: np.ndarray = field(default_factory=lambda: np.zeros((5, 0)))

    def area_error(self, pressure, area, kappa: float = KAPPA) -> np.ndarray:
        """An estimate of the area error the chords make, at the user's times.

        The comparison-principle bound of the module docstring, summed over the final
        intervals with their own deviations instead of the tolerance: an interval [a, b]
        whose chord is e off the callable moves the area at every later G by at most

            kappa * A * e / l * exp(-gap^2 / 4m) * ln(b / a),

        l = min(sqrt(2m), 1/|v|) (v the chord's slope where the wall moves into the
        distribution), m the midpoint, gap = pressure + sigma_a(m) (zero where the pressure
        is separated from the start); ln(b/a) is the e-folds of G it spans (1 for the
        interval from G = 0). Errors of one sign add, so the sum over the intervals up to G
        is the estimate there. kappa = 1 bounds what was measured (0.2-0.3 on the square-root
        wall): the estimate is 1-5x the sampling error.

        Parameters
        ----------
        pressure : (n_p,) -- nominal stresses. [Pa]
        area : (n_p, n_t) -- the area at the user's times. [-]
        kappa : float -- the constant of the bound. [-]

        Returns
        -------
        (n_p, n_t) -- the estimated absolute error of the area. [-]
        """
        p = np.atleast_1d(np.asarray(pressure, dtype=np.float64))
        area = np.asarray(area, dtype=np.float64)
        user_G = self.G[self.index]
        out = np.zeros(area.shape)
        if self.leaves.shape[1] == 0:
            return out
        a, b, dev, f_mid, slope = self.leaves
        m = 0.5 * (a + b)
        ell = np.sqrt(2.0 * m)
        ell = np.where(slope < 0, np.minimum(ell, 1.0 / np.maximum(-slope, 1e-300)), ell)
        efolds = np.where(a > 0, np.log(np.where(a > 0, b / np.where(a > 0, a, 1.0), 1.0)),
                          1.0)
        order = np.argsort(b, kind="stable")
        b_sorted = b[order]
        # the last interval ending at or before each user time
        upto = np.searchsorted(b_sorted, user_G * (1.0 + 1e-12), side="right")
        for k in range(p.size):
            if not p[k] + self.sigma_a[0] > 0:
                continue
            gap = np.maximum(0.0, p[k] + f_mid)
            factor = np.exp(-np.minimum(gap * gap / (4.0 * m), 700.0))
            c = kappa * dev / ell * factor * efolds
            cum = np.concatenate([[0.0], np.cumsum(c[order])])
            out[k] = area[k] * cum[upto]
        return out


class CallableWallError(ValueError):
    """A callable wall (or the callable it is built from, e.g. a hardness of zeta) failed or
    returned what a wall cannot be; the message names the argument the user gave."""


def _call(func, x: np.ndarray, name: str = "sigma_a") -> np.ndarray:
    """func(x) as a finite float64 array of x's shape, or a ValueError naming the wall
    ``name`` (the argument the callable was given as: "sigma_a" or "sigma_y"). A
    :class:`CallableWallError` raised inside ``func`` (by a wrapper that names the user's own
    argument, e.g. ``hardness``) passes through unchanged."""
    try:
        y = func(x.copy())
    except CallableWallError:
        raise
    except Exception as exc:  # noqa: BLE001 -- any failure of the user's code is reported
        raise CallableWallError(
            f"{name} must be samples or a vectorised callable G [Pa^2] -> {name} [Pa]; "
            f"calling it on an array of {x.size} diffusion times in [{x.min() if x.size else 0:.6g}, "
            f"{x.max() if x.size else 0:.6g}] Pa^2 raised {type(exc).__name__}: {exc}"
        ) from exc
    found = _bool_in(y, f"{name}(G)")
    if found is not None:
        raise CallableWallError(f"{name}(G) must return real numbers [Pa], not bools "
                                f"(True/False is not read as 1/0); got {found}")
    try:
        arr = np.asarray(y, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise CallableWallError(
            f"{name}(G) must return real numbers [Pa]; got {type(y).__name__} {y!r:.80}"
        ) from exc
    if arr.shape != x.shape:
        raise CallableWallError(
            f"{name}(G) must return an array of G's shape {x.shape} (a vectorised callable, "
            f"e.g. written with numpy functions) [Pa]; got shape {arr.shape}"
        )
    bad = ~np.isfinite(arr)
    if np.any(bad):
        i = int(np.argmax(bad))
        raise CallableWallError(
            f"{name}(G) must be finite [Pa] for every G in [0, G[-1]] (a callable wall is "
            f"followed from G = 0); got {name}({float(x[i])!r}) = {float(arr[i])!r}"
        )
    return arr


def check_wall_callable(func, G: np.ndarray, name: str = "sigma_a") -> np.ndarray:
    """Validate a callable wall on the user's times: the finite values there [Pa]; errors
    name the wall as ``name``."""
    return _call(func, np.ascontiguousarray(G, dtype=np.float64), name)


def check_kinks(kinks, g_end: float) -> np.ndarray:
    """Declared kink times, sorted and unique, inside (0, g_end) [Pa^2]."""
    if kinks is None:
        return np.zeros(0)
    check_not_bool(kinks, "kinks", "Pa^2")
    try:
        k = np.atleast_1d(np.asarray(kinks, dtype=np.float64))
    except (TypeError, ValueError) as exc:
        raise ValueError(f"kinks must be diffusion times [Pa^2]; got kinks = {kinks!r}") from exc
    if k.ndim != 1:
        raise ValueError(f"kinks must be one-dimensional [Pa^2]; got shape {k.shape}")
    bad = ~(np.isfinite(k) & (k >= 0))
    if np.any(bad):
        i = int(np.argmax(bad))
        raise ValueError(f"kinks must be finite and >= 0 [Pa^2]; got kinks[{i}] = {k[i]!r}")
    k = np.unique(k)
    return k[(k > 0) & (k < g_end)]


def _split_points(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Where [a, b] is bisected: sqrt(ab) for a > 0 and b/a > GEOMETRIC_RATIO, else (a+b)/2."""
    geo = (a > 0) & (b > GEOMETRIC_RATIO * a)
    mid = 0.5 * (a + b)
    out = np.where(geo, np.sqrt(np.where(geo, a * b, 1.0)), mid)
    # rounding must keep the point strictly inside
    return np.where((out > a) & (out < b), out, mid)


def _seed(points: np.ndarray) -> np.ndarray:
    """Split every interval into >= N_SEED pieces, and pieces away from 0 to ratio <= SEED_RATIO."""
    out = [points[:1]]
    for a, b in zip(points[:-1], points[1:]):
        n = N_SEED
        if a > 0 and b / a > SEED_RATIO:
            n = max(n, int(math.ceil(math.log(b / a) / math.log(SEED_RATIO))))
            inner = np.geomspace(a, b, n + 1)[1:]
        else:
            inner = np.linspace(a, b, n + 1)[1:]
        inner[-1] = b
        out.append(inner)
    return np.unique(np.concatenate(out))


def _cluster(found, g_end: float) -> np.ndarray:
    """The last-recorded point of each cluster of kink records (a chain of refinements records
    ever closer points; clusters: relative spacing below 1e-3 of max(G, 1e-3 G[-1]))."""
    if not found:
        return np.zeros(0)
    x = np.asarray(found, dtype=np.float64)
    rank = np.arange(x.size)
    order = np.argsort(x, kind="stable")
    x, rank = x[order], rank[order]
    gaps = np.diff(x) > 1e-3 * np.maximum(x[1:], 1e-3 * g_end)
    groups = np.concatenate([[0], np.cumsum(gaps)])
    out = [x[groups == k][np.argmax(rank[groups == k])] for k in range(int(groups[-1]) + 1)]
    return np.asarray(out)


def sample_wall(func, G, pressure, rtol: float, kinks=None, *, max_points: int = MAX_POINTS,
                at_user: np.ndarray | None = None, name: str = "sigma_a") -> WallSampling:
    """Sample a callable wall on a schedule fine enough for ``rtol``.

    Parameters
    ----------
    func : callable -- vectorised, G [Pa^2] -> sigma_a [Pa], finite on [0, G[-1]].
    G : (n_t,) -- the user's non-decreasing output times, G[0] >= 0. [Pa^2]
    pressure : (n_p,) -- nominal stresses; the smallest in contact sets the tolerance. [Pa]
    rtol : float -- target relative accuracy of the area. [-]
    kinks : array_like or None -- times where the wall's slope jumps, put on the schedule
        exactly. [Pa^2]
    max_points : int -- cap on the schedule length.
    at_user : (n_t,) or None -- func(G) when already evaluated (validated). [Pa]
    name : str -- the argument the wall was given as, named in errors ("sigma_a", "sigma_y").

    Returns
    -------
    WallSampling

    Raises
    ------
    ValueError -- func fails, returns a wrong shape or non-finite values, or is discontinuous.
    """
    G = np.ascontiguousarray(G, dtype=np.float64)
    p = np.atleast_1d(np.asarray(pressure, dtype=np.float64))
    if at_user is None:
        at_user = check_wall_callable(func, G, name)
    g_end = float(G[-1])
    k_decl = check_kinks(kinks, g_end)
    base = np.unique(np.concatenate([[0.0], G, k_decl]))
    if base.size < 2:
        f0 = _call(func, base, name)
        return WallSampling(G=base, sigma_a=f0, index=np.searchsorted(base, G), at_user=at_user)
    pts = _seed(base)
    vals = _call(func, pts, name)
    # the most demanding pressure: the smallest one in contact at G = 0
    in_contact = p + vals[0] > 0
    if not np.any(in_contact):
        # every pressure is separated from the start: the wall is never met
        sched = base
        sv = _call(func, sched, name)
        return WallSampling(G=sched, sigma_a=sv, index=np.searchsorted(sched, G),
                            at_user=at_user)
    p_min = float(np.min(p[in_contact]))
    # e-folds over which the wall meets the distribution: from the first seed point where the
    # Gaussian factor exp(-gap^2/4G) is above 1/e
    gap = np.maximum(0.0, p_min + vals)
    pos = pts > 0
    near = pos & (gap * gap <= 4.0 * pts)
    if np.any(near):
        g_on = float(pts[near][0])
        # the factor is near 1 from about gap^2/4 on, possibly before that seed point
        i_on = int(np.flatnonzero(near)[0])
        g_on = min(g_on, max(float(gap[i_on]) ** 2 / 4.0, g_end * MIN_REL_FIRST))
        n_efolds = min(max(1.0, math.log(g_end / g_on)), L_MAX)
    else:
        n_efolds = 1.0
    scale = WALL_BUDGET * rtol / n_efolds

    def tolerance(x, fx, fa, fb, a, b):
        v = (fb - fa) / (b - a)
        ell = np.sqrt(2.0 * x)
        ell = np.where(v < 0, np.minimum(ell, 1.0 / np.maximum(-v, 1e-300)), ell)
        g = np.maximum(0.0, p_min + fx)
        expo = np.minimum(g * g / (4.0 * x), 600.0)
        tol = scale * ell * np.exp(expo)
        floor = ROUND_REL * np.maximum(np.maximum(np.abs(fa), np.abs(fb)), np.abs(fx))
        return np.maximum(tol, floor)

    def probes(a, b):
        m = _split_points(a, b)
        return _split_points(a, m), m, _split_points(m, b)

    def ratios(a, b, fa, fb, xs, fs):
        r = np.zeros(a.shape)
        dev = np.zeros(a.shape)
        for x, fx in zip(xs, fs):
            chord = fa + (fb - fa) * ((x - a) / (b - a))
            d = np.abs(fx - chord)
            dev = np.maximum(dev, d)
            r = np.maximum(r, d / tolerance(x, fx, fa, fb, a, b))
        return r, dev

    # active intervals: endpoints, their values, three probes and their values
    a, b = pts[:-1], pts[1:]
    fa, fb = vals[:-1], vals[1:]
    q1, m, q3 = probes(a, b)
    fq = _call(func, np.concatenate([q1, m, q3]), name).reshape(3, -1)
    fq1, fm, fq3 = fq
    kink = np.zeros(a.shape, dtype=bool)
    r, dev = ratios(a, b, fa, fb, (q1, m, q3), (fq1, fm, fq3))
    done_a, done_f = [pts], [vals]
    kinks_found = []
    n_points = pts.size
    capped = False
    for _ in range(MAX_ROUNDS):
        limit = np.where(kink, KINK_FRACTION, 1.0)
        fail = r > limit
        # intervals that can no longer be split
        tiny = np.where(a > 0, (b - a) <= MIN_REL_WIDTH * b, b <= MIN_REL_FIRST * g_end)
        stuck = fail & tiny
        if np.any(stuck & (r > 1.0)):
            i = int(np.flatnonzero(stuck & (r > 1.0))[0])
            raise CallableWallError(
                f"{name}(G) must be continuous [Pa] (a callable wall is sampled linearly "
                f"between points); near G = {a[i]:.17g} Pa^2 it changes from {fa[i]!r} to "
                f"{fb[i]!r} over an interval of {b[i] - a[i]:.3g} Pa^2. Give a jumping wall "
                f"as samples with a repeated G value at the jump"
            )
        if np.any(stuck):
            kinks_found.extend(0.5 * (a[stuck] + b[stuck]))
        fail &= ~tiny
        if not np.any(fail):
            break
        idx = np.flatnonzero(fail)
        room = (max_points - n_points)
        if idx.size > room:
            capped = True
            order = np.argsort(-r[idx], kind="stable")
            idx = idx[order[:max(room, 0)]]
            if idx.size == 0:
                break
        # split: children [a, m] (probes q1 is its midpoint) and [m, b] (q3)
        A, B, FA, FB = a[idx], b[idx], fa[idx], fb[idx]
        M, FM = m[idx], fm[idx]
        Q1, FQ1, Q3, FQ3 = q1[idx], fq1[idx], q3[idx], fq3[idx]
        parent_dev = dev[idx]
        na = np.concatenate([A, M])
        nb = np.concatenate([M, B])
        nfa = np.concatenate([FA, FM])
        nfb = np.concatenate([FM, FB])
        nm = np.concatenate([Q1, Q3])
        nfm = np.concatenate([FQ1, FQ3])
        nq1 = _split_points(na, nm)
        nq3 = _split_points(nm, nb)
        fnew = _call(func, np.concatenate([nq1, nq3]), name).reshape(2, -1)
        nr, ndev = ratios(na, nb, nfa, nfb, (nq1, nm, nq3), (fnew[0], nfm, fnew[1]))
        pd = np.concatenate([parent_dev, parent_dev])
        # deviation falling less than x KINK_DROP: a kink (or a jump) in the child
        nkink = (ndev * KINK_DROP > pd) & (pd > 0) & (nr > KINK_FRACTION)
        # a kink-marked interval whose children are both unmarked: the kink is pinned
        n_split = idx.size
        pinned = kink[idx] & ~nkink[:n_split] & ~nkink[n_split:]
        kinks_found.extend(M[pinned])
        done_a.append(M)
        done_f.append(FM)
        n_points += idx.size
        keep_i = np.flatnonzero(~fail)
        if capped:
            keep_i = np.setdiff1d(np.arange(a.size), idx)
        a = np.concatenate([a[keep_i], na])
        b = np.concatenate([b[keep_i], nb])
        fa = np.concatenate([fa[keep_i], nfa])
        fb = np.concatenate([fb[keep_i], nfb])
        q1 = np.concatenate([q1[keep_i], nq1])
        m = np.concatenate([m[keep_i], nm])
        q3 = np.concatenate([q3[keep_i], nq3])
        fq1 = np.concatenate([fq1[keep_i], fnew[0]])
        fm = np.concatenate([fm[keep_i], nfm])
        fq3 = np.concatenate([fq3[keep_i], fnew[1]])
        r = np.concatenate([r[keep_i], nr])
        dev = np.concatenate([dev[keep_i], ndev])
        kink = np.concatenate([kink[keep_i], nkink])
        if capped:
            break
    else:
        capped = True
    worst = float(np.max(r)) if r.size else 0.0
    sched = np.concatenate(done_a)
    sval = np.concatenate(done_f)
    order = np.argsort(sched, kind="stable")
    sched, sval = sched[order], sval[order]
    uniq = np.concatenate([[True], np.diff(sched) > 0])
    sched, sval = sched[uniq], sval[uniq]
    # kinks still marked at the end (capped): record where they are
    if np.any(kink):
        kinks_found.extend(0.5 * (a[kink] + b[kink]))
    index = np.searchsorted(sched, G)
    slope = (fb - fa) / (b - a)
    return WallSampling(
        G=sched, sigma_a=sval, index=index, at_user=at_user,
        kinks_found=_cluster(kinks_found, g_end), capped=capped,
        worst_ratio=worst, n_inserted=int(sched.size - base.size),
        leaves=np.stack([a, b, dev, fm, slope]),
    )
