"""Kinked and fast walls of issue 12 with "cn": within rtol with status 0 at rtol 1e-6 ... 1e-8;
random kinks: within rtol or flagged, never NaN. And the ladder's thinned coarsest run: a
densely sampled wall costs the coarse and fine runs one and two steps per piece.
"""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings, strategies as hst

import persson_fast as pf
from persson_fast._kernels import pieces

ATOL = 1e-12
RTOLS = (1e-6, 1e-7, 1e-8)

_G_KINK = np.array([0.0, 0.5, 1.0, 4.0 / 3.0, 2.0])
#: bnr at rtol 1e-11 (as in test_accuracy_contract)
_KINK_REF = np.array([1.0, 0.3372562102870542, 0.22417479035311683, 0.1865877402638022,
                      0.14778051784786672])
_A, _SIGMA0, _G_END = 2e5, 8e5, 1e11


def _within(area, ref, rtol):
    return np.abs(area - ref) <= rtol * ref + ATOL


def test_the_found_kink_case_is_within_rtol():
    """The case hypothesis found before kinks were detected (1.01 rtol with status 0)."""
    G = np.unique(np.concatenate([[0.0], np.geomspace(1e-2, 4.0, 12), [0.25]]))
    sa = np.maximum(0.0, 0.3 + np.where(G <= 0.25, 0.0, -0.5 * (G - 0.25)))
    r = pf.solve_diffusion(G, 2.0, sa, method="cn", rtol=1e-6)
    ref = pf.solve_diffusion(G, 2.0, sa, method="bnr", rtol=1e-9)
    assert r.status[0] == 0 and ref.status[0] == 0
    assert np.all(_within(r.area[0], ref.area[0], 1e-6)), np.abs(r.area[0] - ref.area[0])
    assert np.all(np.abs(r.area[0] - ref.area[0]) <= r.error_estimate[0] + 1e-9 * ref.area[0])
    G_k = np.concatenate([[0.0], G])
    sa_k = np.concatenate([[sa[0]], sa])
    assert pieces._first_kink(G_k, sa_k, np.int64(1)) == int(np.flatnonzero(G_k == 0.25)[0])
    straight = 0.3 - 0.1 * G_k
    assert pieces._first_kink(G_k, straight, np.int64(1)) == G_k.size


@pytest.mark.parametrize("rtol", RTOLS)
def test_kinked_wall_within_rtol(rtol):
    sa = np.maximum(0.0, 0.4 - 0.3 * _G_KINK)
    r = pf.solve_diffusion(_G_KINK, 0.1, sa, method="cn", rtol=rtol)
    assert r.status[0] == 0, r.message
    assert np.all(_within(r.area[0], _KINK_REF, rtol)), np.abs(r.area[0] - _KINK_REF) / (
        rtol * _KINK_REF)


@pytest.mark.parametrize("rtol", RTOLS)
@pytest.mark.parametrize("b_y0", (-30.0, -10.0, -1.0, 1.0, 5.0, 20.0))
@pytest.mark.parametrize("first", (1e4, 1e-7 * _G_END))
def test_fast_straight_wall_within_rtol(first, b_y0, rtol):
    """sigma_a = a + b G sampled at (0, first, G_end), b y0 from -30 to +20: the sampled
    first piece is tiny (the exact start covers it only), the wall layer is thin."""
    b = b_y0 / (_SIGMA0 + _A)
    G = np.array([0.0, first, _G_END])
    ref = pf.linear_boundary_area(_SIGMA0, G, _A, b)
    r = pf.solve_diffusion(G, _SIGMA0, _A + b * G, method="cn", rtol=rtol)
    assert r.status[0] == 0, r.message
    assert np.all(_within(r.area[0], ref, rtol)), np.abs(r.area[0] - ref) / (rtol * ref)


@settings(max_examples=40, deadline=None)
@given(g_kink=hst.floats(0.05, 3.0), slope1=hst.floats(-0.6, 0.6),
       slope2=hst.floats(-0.6, 0.6), sigma0=hst.floats(0.05, 2.0),
       rtol=hst.sampled_from((1e-4, 1e-6)))
def test_random_kinks_within_rtol_or_flagged(g_kink, slope1, slope2, sigma0, rtol):
    """A wall with one kink (slopes, position, pressure random): never NaN; with status 0
    it is within rtol of bnr at a tolerance 100 times tighter."""
    G = np.unique(np.concatenate([[0.0], np.geomspace(1e-2, 4.0, 12), [g_kink]]))
    sa = np.maximum(0.0, 0.3 + np.where(G <= g_kink, slope1 * G,
                                        slope1 * g_kink + slope2 * (G - g_kink)))
    r = pf.solve_diffusion(G, sigma0, sa, method="cn", rtol=rtol)
    assert np.all(np.isfinite(r.area[0])) and np.all(np.isfinite(r.error_estimate[0]))
    if r.status[0] != 0:
        return
    ref = pf.solve_diffusion(G, sigma0, sa, method="bnr", rtol=rtol * 1e-2)
    if ref.status[0] != 0:
        return
    err = np.abs(r.area[0] - ref.area[0])
    assert np.all(err <= rtol * ref.area[0] + ATOL + ref.error_estimate[0]), (
        np.max(err / (rtol * ref.area[0] + ATOL)))


@pytest.mark.parametrize("g_kink, slope1, slope2, sigma0, rtol", [
    (2.507629567985174, -0.5379912730567248, 0.3931141966310524, 1.6348618046627137, 1e-4),
    (2.0, -0.5, 0.0, 2.0, 1e-4),
    (0.16004295323830436, -0.07189237504432833, -0.5632258449149876, 1.8407590122331827, 1e-4),
    (2.3405612784902194, -0.4430579595383788, 0.3769314096426032, 1.8392762740002857, 1e-6),
    (0.4705907270147578, -0.2874753416920268, 0.32258690405835755, 1.3082954664881123, 1e-6),
])
def test_kinked_walls_that_missed(g_kink, slope1, slope2, sigma0, rtol):
    """Draws of the random test above that came back 1.1-3.7 rtol off with status 0: the
    ladder after a kink at a coarse resolution (now at least KINK_MIN_SCALE, times
    KINK_SCALE), and a kink at the point where the exact start ends (now detected)."""
    G = np.unique(np.concatenate([[0.0], np.geomspace(1e-2, 4.0, 12), [g_kink]]))
    sa = np.maximum(0.0, 0.3 + np.where(G <= g_kink, slope1 * G,
                                        slope1 * g_kink + slope2 * (G - g_kink)))
    r = pf.solve_diffusion(G, sigma0, sa, method="cn", rtol=rtol)
    ref = pf.solve_diffusion(G, sigma0, sa, method="bnr", rtol=rtol * 1e-2)
    assert ref.status[0] == 0
    err = np.abs(r.area[0] - ref.area[0])
    assert r.status[0] != 0 or np.all(err <= rtol * ref.area[0] + ATOL + ref.error_estimate[0]), (
        np.max(err / (rtol * ref.area[0] + ATOL)))


def test_kink_where_the_exact_start_ends_is_found():
    """A straight wall up to a kink: the linear-wall start covers the first piece and the
    march begins on the kink, which counts as the first kink."""
    G_k = np.array([0.0, 0.1, 0.2, 0.4, 0.8])
    sa_k = np.array([0.0, -0.1, -0.2, 0.0, 0.4])     # slope -1, then +1 from G = 0.2
    assert pieces._first_kink(G_k, sa_k, np.int64(3)) == 2
    assert pieces._first_kink(G_k, np.zeros(5), np.int64(3)) == 5


def test_dense_schedule_pairs_pieces_for_the_coarsest_run():
    """Pieces that need less than one coarse step are paired for the coarsest run only (the
    wall straight across them, none across a grid coarsening, never the first piece)."""
    G = np.concatenate([[0.0], np.geomspace(1e-2, 10.0, 200)])
    sa = np.zeros_like(G)
    flags = np.zeros(G.shape[0], dtype=np.int64)
    keep = np.ones(G.shape[0], dtype=np.bool_)
    n_keep = pieces._pair_pieces(G, sa, np.int64(2), 1e-2, 5.0, 40.0, np.empty(0), flags, keep)
    assert n_keep < G.shape[0] - 80          # most pieces are paired
    assert keep[:3].all() and keep[-1]       # the start, the first piece and the end are kept
    skipped = np.flatnonzero(~keep)
    assert np.all(np.diff(skipped) >= 2)     # pairs share no point
    assert np.all(flags[skipped] & pieces.PIECE_HALVE) and np.all(flags[skipped + 1] & pieces.PIECE_HALVE)
    # a kink at a would-be shared point stops that pair
    sa_kink = np.where(G > G[3], G - G[3], 0.0)
    flags[:] = 0
    keep[:] = True
    pieces._pair_pieces(G, sa_kink, np.int64(2), 1e-2, 5.0, 40.0, np.empty(0), flags, keep)
    assert keep[3]


def test_dense_schedule_costs_about_one_coarse_step_per_piece():
    """16 samples per decade of G (about 0.7 coarse steps each at rtol 1e-6): the three runs
    take 1/2, 1 and 2 steps per piece, not 1, 2 and 4; the answer stays within rtol."""
    G = np.concatenate([[0.0], np.geomspace(1e-4, 1e3, 113)])
    r = pf.solve_diffusion(G, 1.0, 0.0, method="cn", rtol=1e-6)
    ref = pf.images_area(1.0, G)
    assert r.status[0] == 0
    assert np.all(_within(r.area[0], ref, 1e-6))
    # 112 pieces after the start: an unpaired ladder takes >= 7 steps per piece (1 + 2 + 4)
    assert r.counts[0, 1] < 5.0 * 112, r.counts[0]


def _late_recession_wall(g_star, top=0.0089, m=8):
    """Zero up to g_star, then a square-root rise to ``top`` at G = 1 on m samples graded as
    (k/m)^2: shaped like the fixed point's final wall of the late-onset scene of
    tests/test_adhesion_probe_cases.py (a sign change of gamma_eff in the last zeta cell)."""
    G = np.concatenate([[0.0], np.geomspace(1e-3, 0.9, 30), [g_star],
                        g_star + (1.0 - g_star) * (np.arange(1, m + 1) / m) ** 2])
    sa = np.where(G > g_star, top * np.sqrt(np.clip((G - g_star) / (1.0 - g_star), 0.0, None)),
                  0.0)
    return G, sa


@pytest.mark.parametrize("g_star", [0.99993, 0.9999, 0.9995])
def test_late_fast_recession_within_rtol(g_star):
    """A wall that recedes by more than sigma0 within the last 5e-4 of G1 (sigma0 = 0.0072,
    A = 0.004; issue 33, item 3). The recession moves the wall by 0.03 of a node spacing, at
    cell Peclet numbers of 1e2-1e3: the layer it leaves is far below the grid, and the flux
    through the wall face is first order in h (the extrapolated result was 1.5-2.3 rtol off
    with status 0 and an estimate of 0.9 rtol). The estimate now carries that sub-grid term
    (SUB_GRID), so the ladder refines until it meets rtol."""
    G, sa = _late_recession_wall(g_star)
    sigma0, rtol = 0.0072, 5e-5
    ref = pf.solve_diffusion(G, sigma0, sa, method="bnr", rtol=1e-10, parallel=False)
    twin = pf.solve_diffusion(G, sigma0, sa, method="fixed-grid", rtol=1e-9, parallel=False)
    a_ref = ref.area[0, -1]
    assert abs(twin.area[0, -1] - a_ref) <= 1e-6 * a_ref     # two methods agree: the oracle
    r = pf.solve_diffusion(G, sigma0, sa, method="cn", rtol=rtol, parallel=False)
    assert r.status[0] == 0
    assert abs(r.area[0, -1] - a_ref) <= rtol * a_ref + ATOL


@pytest.mark.parametrize("g_star", [0.99993, 0.9995, 0.999])
@pytest.mark.parametrize("rtol", [1e-4, 1e-5])
def test_late_fast_recession_estimate_bounds_the_error(g_star, rtol):
    """The same walls at other tolerances: within rtol or flagged, and the estimate at least
    half the error at every returned G (bnr at rtol 1e-10 as the reference, checked against
    fixed-grid to 1e-6)."""
    G, sa = _late_recession_wall(g_star)
    sigma0 = 0.0072
    ref = pf.solve_diffusion(G, sigma0, sa, method="bnr", rtol=1e-10, parallel=False).area[0]
    twin = pf.solve_diffusion(G, sigma0, sa, method="fixed-grid", rtol=1e-9, parallel=False)
    assert np.max(np.abs(twin.area[0] - ref) / ref) <= 1e-6
    r = pf.solve_diffusion(G, sigma0, sa, method="cn", rtol=rtol, parallel=False)
    err = np.abs(r.area[0] - ref)
    assert r.status[0] != 0 or np.all(err <= rtol * ref + ATOL), np.max(err / (rtol * ref))
    judged = err > 1e-6 * ref                  # above the reference's own uncertainty
    assert np.all(r.error_estimate[0][judged] >= 0.5 * err[judged]), np.min(
        r.error_estimate[0][judged] / err[judged])
