"""The magnification (zeta) grids of the adhesive problem and its scaled kernel inputs.

:func:`adhesion_zeta` builds the default grid (log-spaced, the spectrum's breakpoints, and
points in ln(zeta - 1) near zeta = 1), :func:`refine_zeta` / :func:`coarsen_zeta` the nested
grids of the Richardson ladder, and :func:`_scene_arrays` the dimensionless arrays the
kernels take (G, c, and the exact U_el weights wa, wb of seed Eq. 9).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # names of the type hints only
    from ..surfaces.base import Surface

import numpy as np

from .._validation import as_float_array, check_finite, check_whole_number

__all__ = ["adhesion_zeta", "refine_zeta", "coarsen_zeta", "Onset", "onset_at", "onset_grid",
           "onset_coordinate"]

#: magnifications per decade of the coarser of the two nested default zeta grids at
#: rtol = 1e-6, scaled as rtol^(-1/3). Measured on the seed scene (inner rtol 1e-9): the
#: zeta-grid error of A(zeta1) is second order before extrapolation (ratio 3.9-4.0 per
#: doubling) and third order after it (3.6e-6 at 20/decade, 4.5e-7 at 40, 7e-8 at 80);
#: 46/decade keeps it near 0.3 rtol.
ZETA_PER_DECADE_ADHESION = 46
#: near zeta = 1, where an absorbing layer forms close to pull-off, points are also spaced
#: in ln(zeta - 1) from NEAR_ONE_MIN to 1 with this fraction of the per-decade density
NEAR_ONE_MIN = 1e-6
NEAR_ONE_FRACTION = 0.5
#: breakpoints of the spectrum closer than this relative distance are one kink to the grid
#: (the first is kept; 1 and zeta1 always): a measured table may hold nodes one ulp apart,
#: and a cell that narrow has dq = 0 once zeta is scaled to q (issue 12)
BREAKPOINT_MERGE_RTOL = 1e-9
#: a log-spaced (or near-one) point closer to a breakpoint than this fraction of its own
#: spacing in ln(zeta) (or ln(zeta - 1)) is dropped and the breakpoint takes its place: the
#: cells beside it stay within 0.9-1.1 of the spacing instead of leaving a sliver
ZETA_MERGE_FRACTION = 0.1
#: a cell of a zeta grid narrower than this relative width splits the elastic-energy weight
#: of its interval evenly (see :func:`_scene_arrays`): the exact split loses ~eps q/dq to
#: cancellation, the even one is off by O(dq/q); both are below 1.5e-8 of the cell's weight
NARROW_CELL_RTOL = 1.5e-8
#: a narrow cell across which G grows by at most this relative amount is empty to the kernel
#: (rounding, not diffusion: genuine cells, also those near zeta = 1 where G ~ zeta - 1, grow
#: by percents); treating it as flat moves G at one node by at most this much
EMPTY_CELL_GTOL = 1e-12


def adhesion_zeta(surface: Surface, rtol: float = 1e-6, per_decade: int | None = None,
                  near_one_min: float | None = None) -> np.ndarray:
    """Default magnification grid of the adhesive problem. [-]

    Parameters
    ----------
    surface : Surface
        The rough surface (its q0, q1 and breakpoints are used).
    rtol : float
        Target relative accuracy; sets the default ``per_decade``. [-]
    per_decade : int, optional
        Points per decade of zeta (default 46 (1e-6/rtol)^(1/3), at least 4). [-]
    near_one_min : float, optional
        Smallest zeta - 1 of the points near zeta = 1 (default ``NEAR_ONE_MIN``). [-]

    Returns
    -------
    zeta : ndarray
        Log-spaced from 1 to zeta1 with ``per_decade`` points per decade, plus the
        spectrum's breakpoints and points spaced in ln(zeta - 1) from ``near_one_min`` to 1
        with ``NEAR_ONE_FRACTION`` of that density (the grid must be fine near 1). [-]

    Raises
    ------
    ValueError
        If ``rtol`` or ``near_one_min`` is not a number in (0, 1), or ``per_decade`` is not a
        whole number >= 1.

    See Also
    --------
    persson_fast.default_zeta : The grid of a scene without adhesion.
    persson_fast.solve_contact : Takes the grid as ``zeta``.

    Notes
    -----
    Breakpoints closer than ``BREAKPOINT_MERGE_RTOL`` (relative) count once, and a
    log-spaced or near-one point within ``ZETA_MERGE_FRACTION`` of its own spacing of a
    breakpoint is dropped for it. Without that, a tabulated spectrum's nodes (which
    ``np.logspace`` may put one ulp off the log-spaced points, or a user may give one ulp
    apart) left cells one ulp wide: dq = 0 once scaled to q, NaN weights on the refined grid
    and a wrong, flagged area (issue 12).

    Examples
    --------
    >>> import numpy as np
    >>> import persson_fast as pf
    >>> z = pf.adhesion_zeta(pf.seed_scene(), rtol=1e-4)
    >>> print(z.size, z[0], f"{z[-1]:.4g}")
    81 1.0 1.114e+05
    """
    rtol = _open_unit(rtol, "rtol")
    if per_decade is None:
        per_decade = max(4, int(np.ceil(ZETA_PER_DECADE_ADHESION * (1e-6 / rtol) ** (1 / 3))))
    else:
        per_decade = check_whole_number(per_decade, "per_decade")
    near_min = NEAR_ONE_MIN if near_one_min is None else _open_unit(near_one_min, "near_one_min")
    zeta1 = surface.q1 / surface.q0
    n = max(2, int(np.ceil(np.log10(zeta1) * per_decade)) + 1)
    z = np.geomspace(1.0, zeta1, n)
    bp = _merged_breakpoints(np.asarray(surface.breakpoints(), dtype=float) / surface.q0, zeta1)
    n_near = max(2, int(np.ceil(-np.log10(near_min) * per_decade * NEAR_ONE_FRACTION)))
    near_dist = np.geomspace(near_min, 1.0, n_near)[:-1]
    near = 1.0 + near_dist
    # a breakpoint replaces the log-spaced and near-one points beside it (no slivers)
    z = z[_far_from(np.log(z), np.log(bp), ZETA_MERGE_FRACTION * np.log(zeta1) / (n - 1))]
    h_near = -np.log(near_min) / (n_near - 1)
    keep = (near < zeta1) & _far_from(np.log(near_dist), np.log(bp[1:] - 1.0),
                                      ZETA_MERGE_FRACTION * h_near)
    z = np.unique(np.concatenate([z, bp, near[keep]]))
    z = z[(z >= 1.0) & (z <= zeta1)]
    z[0], z[-1] = 1.0, zeta1
    return z


def _open_unit(value, name):
    """``value`` as a float in the open interval (0, 1), or a ValueError naming it."""
    arr = as_float_array(value, name, "-", ndim=(0,))
    check_finite(arr, name, "-")
    if not 0.0 < float(arr) < 1.0:
        raise ValueError(f"{name} must lie in (0, 1) [-]; got {name} = {value!r}")
    return float(arr)


def _merged_breakpoints(bp, zeta1):
    """Sorted breakpoints inside [1, zeta1], both ends included, no two closer than
    ``BREAKPOINT_MERGE_RTOL`` (relative): of a run of closer ones the first is kept, and
    one too close to 1 or zeta1 gives way to the end. [-]"""
    tol = BREAKPOINT_MERGE_RTOL
    inner = np.unique(bp[np.isfinite(bp)])
    inner = inner[(inner - 1.0 > tol * inner) & (zeta1 - inner > tol * zeta1)]
    if inner.size > 1:
        inner = inner[np.concatenate(([True], np.diff(inner) > tol * inner[1:]))]
    return np.concatenate(([1.0], inner, [zeta1]))


def _far_from(x, anchors, min_dist):
    """Mask of the points ``x`` farther than ``min_dist`` from every one of the sorted,
    non-empty ``anchors``."""
    i = np.searchsorted(anchors, x)
    below = anchors[np.clip(i - 1, 0, anchors.size - 1)]
    above = anchors[np.clip(i, 0, anchors.size - 1)]
    return (np.abs(x - below) > min_dist) & (np.abs(above - x) > min_dist)


def refine_zeta(zeta: np.ndarray) -> np.ndarray:
    """The grid with the geometric midpoint of every interval inserted (nests ``zeta``).

    Where rounding puts sqrt(a b) on an end of a cell only a few ulps wide, the arithmetic
    midpoint is taken (the two agree to (dz/z)^2); a cell one ulp wide or empty has no
    interior point and its midpoint repeats an end (:func:`_scene_arrays` gives such an
    empty cell no weight).
    """
    lo, hi = zeta[:-1], zeta[1:]
    mid = np.sqrt(lo * hi)
    on_end = (mid <= lo) | (mid >= hi)
    mid[on_end] = lo[on_end] + 0.5 * (hi[on_end] - lo[on_end])
    mid = np.minimum(np.maximum(mid, lo), hi)
    out = np.empty(2 * zeta.size - 1)
    out[0::2] = zeta
    out[1::2] = mid
    return out


def _scene_arrays(surface, zeta, e_star, work_of_adhesion, detachment_prefactor):
    """Scaled kernel inputs (G, c, wa, wb), the stress scale [Pa] and G(zeta) [Pa^2].

    wa_k, wb_k integrate (pi E*/2) q^2 C(q) / dgamma times the two hat functions of
    [q_k, q_k+1] exactly (their sum is the cell's moment m2). No node layout gives a NaN or
    an inf (a user grid with points one ulp apart, a repeated q after scaling included):

    - a cell narrower than ``NARROW_CELL_RTOL`` (relative) splits m2 evenly, the exact
      split's cancellation being worse than the even split's O(dq/q) there;
    - such a narrow cell across which G grows by no more than rounding
      (``EMPTY_CELL_GTOL``) is empty: its upper node takes the lower node's G and c for the
      kernel and the cell no weight, so the wall neither 'jumps' by rounding in a flat stretch
      (a spurious WALL_JUMP) nor moves with a velocity made of rounding noise;
    - G is made non-decreasing against rounding of the partial moments.

    The returned G(zeta) [Pa^2] is the surface's, unchanged by the empty-cell rule.
    """
    G, c, wa, wb, _, scale, G_dims = _scene_rows(surface, [zeta], e_star, work_of_adhesion,
                                                 detachment_prefactor)
    return G[0], c[0], wa[0], wb[0], scale, G_dims[0]


def _scene_rows(surface, grids, e_star, work_of_adhesion, detachment_prefactor):
    """:func:`_scene_arrays` of several zeta grids that share their end points (hence the
    stress scale), with one evaluation of the surface for all of them: the kernel inputs as
    rows padded with zeros, G and c (n_grids, n_max), wa and wb (n_grids, n_max - 1), the
    number of nodes per grid, the scale [Pa] and G(zeta) [Pa^2] of each grid."""
    n_z = np.array([z.size for z in grids], dtype=np.int64)
    ends = np.cumsum(n_z)
    starts = ends - n_z
    q = np.concatenate(grids) * surface.q0
    # cells: every pair of neighbours inside one grid
    inside = np.ones(q.size - 1, dtype=bool)
    inside[ends[:-1] - 1] = False
    lo, hi = q[:-1][inside], q[1:][inside]
    G_all = np.asarray(surface.diffusion_time(q, e_star), dtype=float)
    c_all = detachment_prefactor * np.sqrt(work_of_adhesion * e_star * q)
    m2 = np.asarray(surface.moment(2, lo, hi), dtype=float)
    m3 = np.asarray(surface.moment(3, lo, hi), dtype=float)
    dq = hi - lo
    pref = 0.5 * np.pi * e_star / work_of_adhesion
    narrow = ~(dq > NARROW_CELL_RTOL * hi)
    dq_safe = np.where(narrow, 1.0, dq)
    wa_all = np.maximum(np.where(narrow, pref * 0.5 * m2, pref * (hi * m2 - m3) / dq_safe), 0.0)
    wb_all = np.maximum(np.where(narrow, pref * 0.5 * m2, pref * (m3 - lo * m2) / dq_safe), 0.0)
    n_max = int(n_z.max())
    G = np.zeros((n_z.size, n_max))
    c = np.zeros((n_z.size, n_max))
    wa = np.zeros((n_z.size, n_max - 1))
    wb = np.zeros((n_z.size, n_max - 1))
    G_dims = []
    scale = None
    for i, (a, n) in enumerate(zip(starts, n_z)):
        G_dim = G_all[a:a + n].copy()
        G_dim[0] = 0.0
        G_dim = np.maximum.accumulate(G_dim)
        if scale is None:
            scale = float(np.sqrt(G_dim[-1])) if G_dim[-1] > 0 else 1.0
            scale = max(scale, float(c_all[a]))
        c_dim = c_all[a:a + n]
        cells = slice(a - i, a - i + n - 1)
        wa_i, wb_i = wa_all[cells], wb_all[cells]
        G_i, c_i = G_dim, c_dim
        empty = narrow[cells] & (G_dim[1:] - G_dim[:-1] <= EMPTY_CELL_GTOL * G_dim[1:])
        if np.any(empty):
            src = np.maximum.accumulate(np.where(np.concatenate(([False], empty)), 0,
                                                 np.arange(n)))
            G_i, c_i = G_dim[src], c_dim[src]
            wa_i, wb_i = np.where(empty, 0.0, wa_i), np.where(empty, 0.0, wb_i)
        G[i, :n], c[i, :n], wa[i, :n - 1], wb[i, :n - 1] = G_i, c_i, wa_i, wb_i
        G_dims.append(G_dim)
    for name, arr in (("G", G), ("c", c), ("wa", wa), ("wb", wb)):
        if not np.all(np.isfinite(arr)):
            i, j = np.unravel_index(int(np.argmax(~np.isfinite(arr))), arr.shape)
            z = grids[i]
            raise RuntimeError(f"adhesion: non-finite kernel input {name}[{j}] = {arr[i, j]!r} "
                               f"at zeta = {z[min(j, z.size - 1)]!r}; please report "
                               f"this scene")
    return G / scale**2, c / scale, wa, wb, n_z, scale, G_dims


def coarsen_zeta(zeta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every other point of ``zeta`` (the last always kept) and their indices: the coarser
    level of the ladder, whose cells are (but for the last) two cells of ``zeta``."""
    idx = np.arange(0, zeta.size, 2)
    if idx[-1] != zeta.size - 1:
        idx = np.append(idx, zeta.size - 1)
    return zeta[idx], idx


#: decades of zeta above and below a sign change of gamma_eff that the onset grid grades (see
#: :func:`onset_at`); measured on a self-affine scene (H = 0.88, 2.9 decades) with 10 points
#: per decade: 0.5, 1 and 2 decades above all converge at order 2 (ladder ratios 4.1-4.3),
#: with errors 1.2e-5, 3.4e-5 and 6.5e-6 relative at the coarsest level
ONSET_DECADES_ABOVE = 1.0
ONSET_DECADES_BELOW = 0.25
#: the fewest graded cells on either side of the onset at level 0
ONSET_MIN_CELLS = 4
#: graded cells per standard cell of the interval at level 0 (the last graded cells are then
#: as wide as the standard cells beside them), and at least ONSET_PER_DECADE per decade of
#: zeta: measured on a random self-affine scene (H 0.71, rtol 1.5e-4, level 0 at 4.3 points
#: per decade), 8.6 graded cells per decade left the extrapolated end areas of the coarse
#: levels 450 and 250 ppm off (still pre-asymptotic), 17 of them 44 and 41 ppm; at rtol
#: 1e-6 the standard spacing gives 46 per decade
ONSET_DENSITY = 2
ONSET_PER_DECADE = 20
#: below the onset the standard nodes stay (sigma_a = 0 there: they shape no wall, but the
#: points near zeta = 1 resolve the area's fast change there), but for those closer to a
#: graded node than this fraction of the graded cell around them
ONSET_GAP = 0.1


class Onset:
    """Where a row's gamma_eff changes sign, and the graded interval around it.

    In u = ln zeta the onset grid of level k holds, in [u_a, u_b], the nodes
    u* -/+ (u* - u_a or u_b - u*) (j/m)^2, j = 0..m, with m = m_below 2^k below u* and
    m_above 2^k above it, and the standard nodes of level k outside. sigma_a = c sqrt(g) is
    a square root of the distance to the sign change, a smooth function of
    v = u* + sqrt((u - u*)(u_b - u*)) (above; mirrored below), in which those nodes are
    equally spaced: the ladder converges at its design order again (:func:`onset_grid`).
    """

    __slots__ = ("z_star", "z_a", "z_b", "u_star", "u_a", "u_b", "m_below", "m_above")

    def __init__(self, z_star, z_a, z_b, m_below, m_above):
        self.z_star, self.z_a, self.z_b = float(z_star), float(z_a), float(z_b)
        self.u_star, self.u_a, self.u_b = np.log(self.z_star), np.log(self.z_a), np.log(self.z_b)
        self.m_below, self.m_above = int(m_below), int(m_above)

    def centred(self, z_star: float) -> "Onset":
        """The same interval and cells, graded around another sign change ``z_star`` inside
        it (its own level's, see :class:`persson_fast.adhesion.ladder._ZetaLadder`)."""
        z = min(max(float(z_star), self.z_a), self.z_b)
        return Onset(z, self.z_a, self.z_b, self.m_below, self.m_above)

    def first_cell(self, k: int) -> float:
        """Width in ln zeta of the narrowest graded cell above the onset at level k."""
        m = self.m_above << k
        return (self.u_b - self.u_star) / (m * m) if m else 0.0


def onset_at(z_star: float, zeta0: np.ndarray, breakpoints: np.ndarray) -> Onset:
    """The graded interval around a sign change at ``z_star`` (1 < z_star < zeta1).

    Its ends are nodes of the coarsest level ``zeta0`` (or breakpoints of the spectrum,
    which it never crosses): the first at least ``ONSET_DECADES_ABOVE`` above z_star and the
    last at least ``ONSET_DECADES_BELOW`` below it. Each side gets cells that end about as
    wide as the standard cells next to it (twice its width over theirs), at least
    ``ONSET_MIN_CELLS``.
    """
    zeta1 = float(zeta0[-1])
    z_star = min(max(float(z_star), 1.0), zeta1)
    i_b = int(np.searchsorted(zeta0, z_star * 10.0 ** ONSET_DECADES_ABOVE))
    z_b = float(zeta0[min(i_b, zeta0.size - 1)])
    i_a = int(np.searchsorted(zeta0, z_star * 10.0 ** -ONSET_DECADES_BELOW, side="right")) - 1
    z_a = float(zeta0[max(i_a, 0)])
    bp = np.asarray(breakpoints, dtype=float)
    above = bp[bp > z_star * (1.0 + BREAKPOINT_MERGE_RTOL)]
    below = bp[bp < z_star * (1.0 - BREAKPOINT_MERGE_RTOL)]
    if above.size:
        z_b = min(z_b, float(above[0]))
    if below.size:
        z_a = max(z_a, float(below[-1]))
    z_a = min(z_a, z_star)
    z_b = max(z_b, z_star)

    def cells(z_lo, z_hi):
        width = np.log(z_hi / z_lo)
        if not width > BREAKPOINT_MERGE_RTOL:
            return 0
        inside = zeta0[(zeta0 >= z_lo) & (zeta0 <= z_hi)]
        near = zeta0[max(int(np.searchsorted(zeta0, z_hi)) - 1, 0):][:2]
        spacing = np.log(near[1] / near[0]) if near.size == 2 else width
        m = int(np.ceil(ONSET_DENSITY * width / spacing)) if spacing > 0 else ONSET_MIN_CELLS
        m = int(min(m, ONSET_DENSITY * max(inside.size, 1) + ONSET_MIN_CELLS))
        return max(m, ONSET_MIN_CELLS, int(np.ceil(ONSET_PER_DECADE * width / np.log(10.0))))

    return Onset(z_star, z_a, z_b, cells(z_a, z_star), cells(z_star, z_b))


def onset_grid(standard: np.ndarray, onset: Onset, level: int) -> np.ndarray:
    """The zeta grid of ``level`` graded around ``onset`` (see :class:`Onset`): the standard
    grid of that level outside [z*, z_b] and the graded nodes inside [z_a, z_b] (below z*
    the standard nodes stay too, but for those within ``ONSET_GAP`` of a graded cell's ends).
    The graded nodes of level k are every other one of level k + 1.""" 
    o = onset
    parts = [standard[standard < o.z_a]]
    m = o.m_below << level
    if m:
        t = (np.arange(m, 0, -1) / m) ** 2
        below = np.exp(o.u_star - (o.u_star - o.u_a) * t)
        below[0] = o.z_a
        # the standard nodes inside, away from the graded ones
        inner = standard[(standard > o.z_a) & (standard < o.z_star)]
        if inner.size:
            ub = np.log(np.append(below, o.z_star))
            ui = np.log(inner)
            j = np.clip(np.searchsorted(ub, ui), 1, ub.size - 1)
            cell = ub[j] - ub[j - 1]
            near = np.minimum(ui - ub[j - 1], ub[j] - ui)
            below = np.sort(np.concatenate([below, inner[near > ONSET_GAP * cell]]))
        parts.append(below)
    parts.append(np.array([o.z_star]))
    m = o.m_above << level
    if m:
        t = (np.arange(1, m + 1) / m) ** 2
        above = np.exp(o.u_star + (o.u_b - o.u_star) * t)
        above[-1] = o.z_b
        parts.append(above)
    parts.append(standard[standard > o.z_b])
    z = np.concatenate(parts)
    z[0], z[-1] = standard[0], standard[-1]
    return z


def onset_coordinate(zeta: np.ndarray, onset: Onset | None) -> np.ndarray:
    """A coordinate in which the onset grids are equally spaced inside [z_a, z_b] and sigma_a
    is smooth across the sign change: v = u* -/+ sqrt(|u - u*| (u* - u_a or u_b - u*)), and
    u = ln zeta outside (or everywhere without an onset)."""
    u = np.log(zeta)
    if onset is None:
        return u
    o = onset
    v = u.copy()
    lo = (u > o.u_a) & (u < o.u_star)
    v[lo] = o.u_star - np.sqrt((o.u_star - u[lo]) * (o.u_star - o.u_a))
    hi = (u > o.u_star) & (u < o.u_b)
    v[hi] = o.u_star + np.sqrt((u[hi] - o.u_star) * (o.u_b - o.u_star))
    return v
