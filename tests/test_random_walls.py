"""Random kinked walls against an independent reference (issue 33): the accuracy contract at
every returned G.

The walls (``benchmarks/random_walls.py``): continuous, piecewise linear, 1-4 kinks at random
places, random values (receding and approaching pieces), a random nominal stress and a random
stress scale; output times at the breakpoints, the midpoints and an eighth into each piece
(just after a kink, where a kinked wall's errors peak). Each is solved as samples and as a
callable (``np.interp`` of the breakpoints: the sampling must find the kinks). The reference
is ``persson_fast._reference.walls`` (the exact linear-wall kernel carried from kink to kink
by quadrature, NumPy/SciPy only: it shares nothing with the solvers), its uncertainty from
panels twice as wide.

The contract (tolerances.py): every result is within rtol, |A - A_ref| <= rtol A_ref +
1e-12 at every returned G, or flagged (status != 0); never NaN. The estimate: at least
EST_FLOOR_RATIO times the error at every returned G where the error is above
EST_JUDGED_FRACTION of the tolerance (smaller errors cannot break the contract) and above
ten times the reference's own uncertainty, except at the first output after a kink, where it
is known to fall to 0.18-0.36x (pinned by ``test_estimate_just_after_a_kink``); for a flagged
result, which says by how much it misses rtol, its largest estimate against its largest
error.

``test_random_walls_quick`` runs 12 walls with cn; the ``slow`` ones run 200 walls, every
compiled one-wall method and "auto", rtol 1e-4 ... 1e-8.
"""
from __future__ import annotations

import numpy as np
import pytest

import persson_fast as pf
from benchmarks.random_walls import walls

from tolerances import (RANDOM_WALL_EST_FLOOR_RATIO as EST_FLOOR_RATIO,
                        RANDOM_WALL_EST_JUDGED_FRACTION as EST_JUDGED_FRACTION)

ATOL = 1e-12
RTOLS = (1e-4, 1e-5, 1e-6, 1e-7, 1e-8)
#: methods whose estimate is held to EST_FLOOR_RATIO (the others: within rtol or flagged)
ESTIMATE_METHODS = ("cn", "auto")


def first_after_kink(wall):
    """The output times an eighth into the piece after each kink (the first output there)."""
    lo, hi = wall.G_nodes[1:-1], wall.G_nodes[2:]
    at = lo + 0.125 * (hi - lo)
    return np.any(np.abs(wall.G[:, None] - at[None, :]) <= 1e-12 * wall.G[-1], axis=1)


def check(wall, method, rtol, form):
    """Solve one wall and judge it; returns (verdict, worst estimate/error ratio or None)."""
    sa = wall.samples() if form == "samples" else wall.callable()
    r = pf.solve_diffusion(wall.G, wall.sigma0, sa, method=method, rtol=rtol, parallel=False)
    area, est, status = r.area[0], r.error_estimate[0], int(r.status[0])
    where = f"seed {wall.seed}, {form}, {method}, rtol {rtol:g}, status {status}"
    assert np.all(np.isfinite(area)) and np.all(np.isfinite(est)), where
    err = np.abs(area - wall.ref)
    tol = rtol * wall.ref + ATOL
    if status == 0:
        assert np.all(err <= tol), f"silent miss: {where}, {np.max(err / tol):.3g} rtol"
    judged = (err > EST_JUDGED_FRACTION * tol) & (err > 10.0 * wall.ref_unc)
    judged &= ~first_after_kink(wall)           # pinned apart: test_estimate_just_after_a_kink
    if not np.any(judged):
        return ("ok" if status == 0 else "flagged"), None
    if status == 0:
        ratio = float(np.min(est[judged] / err[judged]))
    else:
        # a flagged result says by how much rtol is missed: its largest estimate against its
        # largest error (pointwise it can sit lower where the error is far below its peak)
        ratio = float(np.max(est[judged]) / np.max(err[judged]))
    return ("ok" if status == 0 else "flagged"), ratio


@pytest.fixture(scope="module")
def quick_walls():
    return walls(12)


@pytest.mark.parametrize("form", ["samples", "callable"])
@pytest.mark.parametrize("rtol", [1e-4, 1e-6])
def test_random_walls_quick(quick_walls, rtol, form):
    for wall in quick_walls:
        _, ratio = check(wall, "cn", rtol, form)
        assert ratio is None or ratio >= EST_FLOOR_RATIO, (wall.seed, ratio)


def test_reference_is_converged(quick_walls):
    """The reference's uncertainty (panels twice as wide) is far below the tightest rtol."""
    for wall in quick_walls:
        assert np.all(wall.ref_unc <= 1e-11 * wall.ref), wall.seed


def test_the_issue_reproducer_is_within_rtol_or_flagged():
    """Issue 33, item 1: A(0.80730) was 1.12 rtol off with status 0 and an estimate of 0.78
    rtol (a point just after a kink the coarsest run skipped)."""
    from persson_fast._reference.walls import piecewise_linear_area

    br = np.array([0, 0.75435330, 0.86025527, 0.92032264])
    sa_br = np.array([0.13802327, 0.75050109, 0.80108797, 0.79578172])
    G = np.unique(np.r_[br, (br[1:] + br[:-1]) / 2])
    sa = np.interp(G, br, sa_br)
    ref = piecewise_linear_area(G, br, sa_br, 0.0609812194)
    for rtol in (1e-4, 1e-5, 1e-6):
        for method in ("cn", "auto"):
            r = pf.solve_diffusion(G, [0.0609812194], sa, method=method, rtol=rtol)
            err = np.abs(r.area[0] - ref)
            assert r.status[0] != 0 or np.all(err <= rtol * ref), (rtol, err / (rtol * ref))
            assert np.all(r.error_estimate[0] >= 0.5 * err), (rtol, r.error_estimate[0] / err)


@pytest.mark.xfail(strict=True, reason=(
    "known: at the first output after a kink (an eighth into the next piece) the extrapolated "
    "value can converge at order 0.6-1 while the plain runs look asymptotic (ratios 3.8-3.9: "
    "the wall layer the kink restarts is thinner than a few nodes at first), and the estimate "
    "|R(h) - R(2h)|/3 is then 0.18-0.36x the error: in 2000 cn probes of 200 walls, errors of "
    "0.29-0.71 rtol (status 0) at 4 such points, no miss. A floor of 0.03 |F - C| there fixed "
    "them but flagged 31-34 of 40 walls at rtol 1e-8 (15-16 without), 20 of them within rtol"))
@pytest.mark.parametrize("seed, rtol", [(177, 1e-6), (179, 1e-7), (111, 1e-6), (144, 1e-7)])
def test_estimate_just_after_a_kink(seed, rtol):
    from benchmarks.random_walls import draw_wall, with_reference

    wall = with_reference(draw_wall(seed))
    r = pf.solve_diffusion(wall.G, wall.sigma0, wall.samples(), method="cn", rtol=rtol,
                           parallel=False)
    err = np.abs(r.area[0] - wall.ref)
    judged = first_after_kink(wall) & (err > EST_JUDGED_FRACTION * (rtol * wall.ref + ATOL))
    assert np.any(judged)
    assert np.all(r.error_estimate[0][judged] >= EST_FLOOR_RATIO * err[judged])


@pytest.fixture(scope="module")
def many_walls():
    return walls(200)


#: bnr's estimate |R_2N - R_N| / 7 (the error of R_2N, taken for its fourth-order F) sits
#: below the error after kinks: a known silent miss, not of the kinds issue 33 lists
BNR_MISS = ("known: bnr on wall seed 13 (4 kinks, samples) at rtol 1e-8 is 1.12 rtol off "
            "with status 0 and an estimate of 0.34 of the error (bnr at 1e-9 and 1e-10 agree "
            "with the reference to 2.5e-10 and 1.3e-11)")


#: fixed-grid does not refine: it flags a result whose estimate |F - C|/3 exceeds rtol, and
#: an estimate just below the error lets a result just outside rtol through
FIXED_GRID_MISS = ("known: fixed-grid on wall seed 46 (samples) at rtol 1e-5 is 1.05 rtol off "
                   "just after the first kink with status 0, its estimate 0.92x the error "
                   "there (0.97 rtol)")


@pytest.mark.slow
@pytest.mark.parametrize("method", [
    "cn", "auto", "cn-plain", "implicit-euler",
    pytest.param("fixed-grid", marks=pytest.mark.xfail(strict=True, reason=FIXED_GRID_MISS)),
    pytest.param("bnr", marks=pytest.mark.xfail(strict=True, reason=BNR_MISS))])
def test_random_walls_all_methods(many_walls, method):
    """200 walls x samples and callables x rtol 1e-4 ... 1e-8: no silent miss; cn's (and
    auto's) estimate at least EST_FLOOR_RATIO of the error. cn-plain, implicit-euler and
    fixed-grid only down to rtol 1e-6: below it they are capped and flagged nearly always, at
    0.1-1.7 s a probe (benchmarks/CONTRACT.md)."""
    for wall in many_walls:
        for form in ("samples", "callable"):
            for rtol in RTOLS:
                if method in ("implicit-euler", "cn-plain", "fixed-grid") and rtol < 1e-6:
                    continue
                _, ratio = check(wall, method, rtol, form)
                if method in ESTIMATE_METHODS:
                    assert ratio is None or ratio >= EST_FLOOR_RATIO, (
                        wall.seed, form, method, rtol, ratio)
