"""A prescribed wall's pieces: its kinks, and the steps in G each piece of it takes.

The schedule of a grid solve (:mod:`persson_fast._kernels.similarity`) is built piece by
piece between the wall's samples: how many steps the tolerance needs per unit of ln G and per
profile width the wall travels (:func:`_wall_steps`, :func:`_piece_steps`,
:func:`_schedule_steps`), where the wall's slope jumps (a kink: :func:`_is_kink`,
:func:`_is_graded_kink`, :func:`_first_kink`, :func:`_kink_count`) and which pieces are paired
in the coarsest run of the ladder (:func:`_pair_pieces`).
"""
from __future__ import annotations

import math

import numpy as np

from .._jit import njit_serial
from .schedule import boundary_at

RECEDING_FACTOR = 0.25 # a receding wall (sigma_a growing) needs fewer steps per width travelled
KINK_EXTRAPOLATED_ORDER = 2.0  # ... from the first kink of the wall on
PIECE_HALVE = 1       # piece_flags: the piece takes half the steps (paired in the coarsest run)
PIECE_GRADE = 4      # piece_flags: the piece starts at a kink: the steps of the next
                     # GRADE_SPAN e-folds of G are graded (see march)
PIECE_GRADED = 8     # piece_flags: the piece starts within GRADE_SPAN after a graded kink
GRADE_STEPS = 2      # ... with this many times the steps
GRADE_SLOPE_JUMP = 0.02  # a graded kink: the slope jumps by this fraction of the larger slope
GRADE_ISOLATION = 2.0    # ... and by this factor more than at the neighbouring points
GRADE_CLUSTER = 0.05     # (a neighbour across a piece this much shorter than the other side's
                         # is part of the same kink)
PIECE_KINK = 2        # piece_flags: damped restart at the piece's end (march supports it;
                      # not set: see _first_kink)
KINK_SLOPE_JUMP = 0.25 # a slope change above this fraction of the larger slope is a kink


@njit_serial
def _wall_steps(g_a, g_b, sa_a, sa_b, per_width, lng, n_steps_per_lng):
    """Steps (uniform in ln G) that keep the wall's travel per step within 1/``per_width`` of
    the profile width sqrt(2G) at the step's start, on a linear piece [g_a, g_b]; ``lng`` is
    ln(g_b/g_a).

    With L = ln(g_b/g_a), m steps of ratio r = e^(L/m) and slope b, the last step travels
    b g_b (1 - 1/r) over a width sqrt(2 g_b / r): the ratio b sqrt(g_b/2) 2 sinh(L/(2m)),
    the largest of the piece. For a short piece this is the plain |sa_b - sa_a| per_width /
    sqrt(2 g_a); over many e-folds the width grows with the wall's travel (a fast receding
    wall from a tiny start distance: the plain count gave 1e10 steps where 200 do).

    Returns 0 where the count is certainly below the L ``n_steps_per_lng`` steps the caller
    takes anyway (its maximum is then unchanged): 1/(2c) >= x (1 + 0.27 x^2) (1 + 1e-9) >=
    sinh(x), x = 1/(2 n_steps_per_lng) <= 1, a test without the inverse sinh.
    """
    d = abs(sa_b - sa_a)
    if d == 0.0 or per_width <= 0.0:
        return 0
    c = per_width * d / (g_b - g_a) * math.sqrt(0.5 * g_b)
    if n_steps_per_lng > 0.0:
        x = 0.5 / n_steps_per_lng
        if x <= 1.0 and 0.5 / c >= x * (1.0 + 0.27 * x * x) * (1.0 + 1e-9):
            return 0
    # 2 sinh(L/(2m)) <= 1/c  <=>  m >= L / (2 asinh(1/(2c)))
    m = lng / (2.0 * math.asinh(0.5 / c))
    if not m < 9e18:
        return np.int64(9e18)
    return int(math.ceil(m - 1e-9))


@njit_serial
def _piece_steps(g_a, g_b, sa_a, sa_b, n_steps_per_lng, n_steps_per_width):
    """Steps :func:`march` takes on a piece [g_a, g_b] of the wall (before ``refine``)."""
    lng = math.log(g_b / g_a)
    m = int(math.ceil(lng * n_steps_per_lng - 1e-9))
    per_width = n_steps_per_width if sa_b < sa_a else n_steps_per_width * RECEDING_FACTOR
    m_wall = _wall_steps(g_a, g_b, sa_a, sa_b, per_width, lng, n_steps_per_lng)
    if m_wall > m:
        m = m_wall
    if m < 1:
        m = 1
    return m


@njit_serial
def _schedule_steps(G_k, sa_k, i_first, g_start, nper, nper_width, piece_flags, refine,
                    n_levels):
    """Steps one run of :func:`march` takes beyond the one step per piece that the schedule
    forces (a dense schedule's steps are the caller's, not resolution: they are not capped;
    damping aside; each coarsening may split a piece: one more step per level)."""
    total = 0.0
    g_prev = g_start
    sa_prev = boundary_at(G_k, sa_k, g_start)
    for i in range(i_first, G_k.shape[0]):
        g = G_k[i]
        if g > g_prev:
            m = _piece_steps(g_prev, g, sa_prev, sa_k[i], nper, nper_width)
            if piece_flags[i] & (PIECE_GRADE | PIECE_GRADED):
                total += GRADE_STEPS * m * refine - 1
            elif piece_flags[i] & PIECE_HALVE and refine >= 2:
                total += (m - 1) * (refine // 2)
            else:
                total += (m - 1) * refine
            g_prev = g
        sa_prev = sa_k[i]
    return total + (n_levels + 1) * refine


@njit_serial
def _is_kink(G_k, sa_k, i):
    """The wall's slope jumps at schedule point i by more than KINK_SLOPE_JUMP of the larger
    of its two slopes (both pieces of positive length)."""
    d1 = G_k[i] - G_k[i - 1]
    d2 = G_k[i + 1] - G_k[i]
    if not (d1 > 0.0 and d2 > 0.0):
        return False
    s1 = (sa_k[i] - sa_k[i - 1]) / d1
    s2 = (sa_k[i + 1] - sa_k[i]) / d2
    return abs(s2 - s1) > KINK_SLOPE_JUMP * max(abs(s1), abs(s2))


@njit_serial
def _slope_change(G_k, sa_k, i):
    """(|slope jump| at schedule point i, larger of the two slopes); (0, 0) where a piece
    next to i has no length (a jump or the ends of the schedule)."""
    if i < 1 or i + 1 >= G_k.shape[0]:
        return 0.0, 0.0
    d1 = G_k[i] - G_k[i - 1]
    d2 = G_k[i + 1] - G_k[i]
    if not (d1 > 0.0 and d2 > 0.0):
        return 0.0, 0.0
    s1 = (sa_k[i] - sa_k[i - 1]) / d1
    s2 = (sa_k[i + 1] - sa_k[i]) / d2
    return abs(s2 - s1), max(abs(s1), abs(s2))


@njit_serial
def _is_graded_kink(G_k, sa_k, i):
    """A kink whose steps after it are graded (:func:`march`): the slope jumps at point i by
    more than GRADE_SLOPE_JUMP of the larger slope, and by more than GRADE_ISOLATION times
    the slope jumps at both neighbouring points (an isolated slope jump; a smooth wall
    sampled at many points changes its slope a little at each, and is not graded). A
    neighbour across a piece shorter than GRADE_CLUSTER times the piece on the other side
    is part of the same kink and not compared."""
    jump, slope = _slope_change(G_k, sa_k, i)
    if not jump > GRADE_SLOPE_JUMP * slope:
        return False
    # a neighbour across a piece far shorter than the piece on the other side belongs to the
    # same kink (an adaptive sampling puts points on both sides of a kink, close together)
    d1 = G_k[i] - G_k[i - 1]
    d2 = G_k[i + 1] - G_k[i]
    j_lo = 0.0
    j_hi = 0.0
    if d1 >= GRADE_CLUSTER * d2:
        j_lo, _ = _slope_change(G_k, sa_k, i - 1)
    if d2 >= GRADE_CLUSTER * d1:
        j_hi, _ = _slope_change(G_k, sa_k, i + 1)
    return jump > GRADE_ISOLATION * max(j_lo, j_hi)


@njit_serial
def _first_kink(G_k, sa_k, i_first):
    """The first schedule point from the start on where the wall kinks (:func:`_is_kink`), or
    the number of points when there is none. The last point the exact start covers counts:
    a linear-wall start ends at the first kink, and the march then starts on it. From there
    on the ladder's extrapolated estimate assumes order KINK_EXTRAPOLATED_ORDER (the
    extrapolation loses order across a jump of the wall speed; at the default order 3 the
    estimate sat up to 2x below the error: issue 12). (A damped restart at kinks,
    PIECE_KINK, was tried: it fixed some kinked cases and broke others at coarse tolerances,
    so it is not set here.)"""
    n = G_k.shape[0]
    for i in range(max(i_first - 1, 1), n - 1):
        if _is_kink(G_k, sa_k, i):
            return i
    return n


@njit_serial
def _kink_count(G_k, sa_k, i_from):
    """The number of kinks (:func:`_is_kink`) from schedule point ``i_from`` on."""
    count = 0
    for i in range(max(i_from, 1), G_k.shape[0] - 1):
        if _is_kink(G_k, sa_k, i):
            count += 1
    return count


@njit_serial
def _pair_pieces(G_k, sa_k, i_first, g_start, nper, nper_width, coarsen_at, piece_flags, keep):
    """Pair schedule pieces that the coarsest run of the ladder can cross in one step.

    The ladder's runs take 1/2, 1, 2 times the coarse steps of each piece. Where the schedule
    is denser than the resolution (a piece needs at most one coarse step at densities
    ``nper``, ``nper_width``), the coarse run takes one step per piece and the coarsest run
    one step across a pair: two neighbouring such pieces are paired when the wall is straight
    across both (no kink at the shared point), no grid coarsening falls inside the pair, the
    first is not the drain piece after a jump, and the pair needs one step of the coarsest
    run. The shared point is dropped from the coarsest run's schedule (``keep`` False) and
    both pieces are flagged PIECE_HALVE. Returns the number of points kept.
    """
    n = G_k.shape[0]
    n_keep = n
    # the first piece is not paired: the error jumps from zero at the exact start, and the
    # coarsest run's value at its end is not interpolable
    i = i_first + 1
    while i + 1 < n:
        g_a = G_k[i - 1]
        sa_a = sa_k[i - 1]
        g_m = G_k[i]
        g_b = G_k[i + 1]
        ok = g_a < g_m < g_b
        if ok and G_k[i - 1] <= G_k[i - 2]:
            ok = False
        if ok and (piece_flags[i] | piece_flags[i + 1]) & (PIECE_GRADE | PIECE_GRADED):
            ok = False
        if ok:
            for c in coarsen_at:
                if g_a < c < g_b:
                    ok = False
        if ok:
            pred = sa_a + (sa_k[i + 1] - sa_a) * (g_m - g_a) / (g_b - g_a)
            ok = abs(sa_k[i] - pred) <= 1e-13 * (1.0 + abs(pred))
        if ok:
            ok = (_piece_steps(g_a, g_m, sa_a, sa_k[i], nper, nper_width) == 1
                  and _piece_steps(g_m, g_b, sa_k[i], sa_k[i + 1], nper, nper_width) == 1
                  and _piece_steps(g_a, g_b, sa_a, sa_k[i + 1], 0.5 * nper,
                                   0.5 * nper_width) == 1)
        if ok:
            piece_flags[i] |= PIECE_HALVE
            piece_flags[i + 1] |= PIECE_HALVE
            keep[i] = False
            n_keep -= 1
            i += 2
        else:
            i += 1
    return n_keep
