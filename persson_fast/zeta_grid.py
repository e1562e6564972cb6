"""The magnification (zeta) grids of the adhesive problem and its scaled kernel inputs.

:func:`adhesion_zeta` builds the default grid (log-spaced, the spectrum's breakpoints, and
points in ln(zeta - 1) near zeta = 1), :func:`refine_zeta` / :func:`coarsen_zeta` the nested
grids of the Richardson ladder, and :func:`_scene_arrays` the dimensionless arrays the
kernels take (G, c, and the exact U_el weights wa, wb of seed Eq. 9).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # names of the type hints only
    from .surface_base import Surface

import numpy as np

__all__ = ["adhesion_zeta", "refine_zeta", "coarsen_zeta"]

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

    Notes
    -----
    Breakpoints closer than ``BREAKPOINT_MERGE_RTOL`` (relative) count once, and a
    log-spaced or near-one point within ``ZETA_MERGE_FRACTION`` of its own spacing of a
    breakpoint is dropped for it. Without that, a tabulated spectrum's nodes (which
    ``np.logspace`` may put one ulp off the log-spaced points, or a user may give one ulp
    apart) left cells one ulp wide: dq = 0 once scaled to q, NaN weights on the refined grid
    and a wrong, flagged area (issue 12).
    """
    if per_decade is None:
        per_decade = max(4, int(np.ceil(ZETA_PER_DECADE_ADHESION * (1e-6 / rtol) ** (1 / 3))))
    near_min = NEAR_ONE_MIN if near_one_min is None else float(near_one_min)
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
    q = zeta * surface.q0
    G_dim = np.asarray(surface.diffusion_time(q, e_star), dtype=float)
    G_dim[0] = 0.0
    G_dim = np.maximum.accumulate(G_dim)
    scale = float(np.sqrt(G_dim[-1])) if G_dim[-1] > 0 else 1.0
    c_dim = detachment_prefactor * np.sqrt(work_of_adhesion * e_star * q)
    scale = max(scale, float(c_dim[0]))
    m2 = np.asarray(surface.moment(2, q[:-1], q[1:]), dtype=float)
    m3 = np.asarray(surface.moment(3, q[:-1], q[1:]), dtype=float)
    dq = q[1:] - q[:-1]
    pref = 0.5 * np.pi * e_star / work_of_adhesion
    narrow = ~(dq > NARROW_CELL_RTOL * q[1:])
    dq_safe = np.where(narrow, 1.0, dq)
    wa = np.where(narrow, pref * 0.5 * m2, pref * (q[1:] * m2 - m3) / dq_safe)
    wb = np.where(narrow, pref * 0.5 * m2, pref * (m3 - q[:-1] * m2) / dq_safe)
    wa, wb = np.maximum(wa, 0.0), np.maximum(wb, 0.0)
    G, c = G_dim, c_dim
    empty = narrow & (G_dim[1:] - G_dim[:-1] <= EMPTY_CELL_GTOL * G_dim[1:])
    if np.any(empty):
        src = np.maximum.accumulate(np.where(np.concatenate(([False], empty)), 0,
                                             np.arange(q.size)))
        G, c = G_dim[src], c_dim[src]
        wa[empty] = 0.0
        wb[empty] = 0.0
    for name, arr in (("G", G), ("c", c), ("wa", wa), ("wb", wb)):
        if not np.all(np.isfinite(arr)):
            i = int(np.argmax(~np.isfinite(arr)))
            raise RuntimeError(f"adhesion: non-finite kernel input {name}[{i}] = {arr[i]!r} "
                               f"at zeta = {zeta[min(i, zeta.size - 1)]!r}; please report "
                               f"this scene")
    return G / scale**2, c / scale, wa, wb, scale, G_dim


def coarsen_zeta(zeta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every other point of ``zeta`` (the last always kept) and their indices: the coarser
    level of the ladder, whose cells are (but for the last) two cells of ``zeta``."""
    idx = np.arange(0, zeta.size, 2)
    if idx[-1] != zeta.size - 1:
        idx = np.append(idx, zeta.size - 1)
    return zeta[idx], idx
