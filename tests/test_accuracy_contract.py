"""The accuracy contract of the grid methods (issue 12).

A result is within ``rtol`` (|A - A_ref| <= rtol A_ref + 1e-12) with status 0, or its status
says it is not; never NaN. The ``cn`` error estimate is that of the returned (extrapolated)
value: within a small factor of the real error on exact cases. ``implicit-euler``: a tighter
rtol never returns a worse answer.
"""
from __future__ import annotations

import numpy as np
import pytest

import persson_fast as pf

ATOL = 1e-12
RTOLS = (1e-3, 1e-4, 1e-6, 1e-8)
GRID_METHODS = ("cn", "cn-plain", "implicit-euler")
#: every compiled method that solves a prescribed wall (the within-rtol-or-flagged matrix)
ALL_METHODS = GRID_METHODS + ("fixed-grid", "bnr")
#: the error estimate of "cn" against the actual error on exact cases, at the returned G
EST_LO, EST_HI = 0.5, 10.0
#: actual errors below this (relative) are rounding: no ratio is judged there
EST_FLOOR = 1e-13

_G = np.concatenate([[0.0], np.geomspace(1e-4, 1e3, 36)])
_G_KINK = np.array([0.0, 0.5, 1.0, 4.0 / 3.0, 2.0])
#: bnr at rtol 1e-11 (error estimate <= 1.3e-12; bnr at 1e-10 agrees to 3e-11)
_KINK_REF = np.array([1.0, 0.3372562102870542, 0.22417479035311683, 0.1865877402638022,
                      0.14778051784786672])
_G_FAST = np.array([0.0, 1e4, 1e11])


def _case(name):
    """(G, sigma0, sigma_a, reference area, exact?) of a named scene."""
    if name == "images":
        return _G, 1.0, np.zeros_like(_G), pf.images_area(1.0, _G), True
    if name == "wall-receding":
        return _G, 1.0, 0.2 + 0.5 * _G, pf.linear_boundary_area(1.0, _G, 0.2, 0.5), True
    if name == "wall-approaching":
        return _G, 1.0, 0.5 - 0.3 * _G, pf.linear_boundary_area(1.0, _G, 0.5, -0.3), True
    if name == "kinked-wall":
        return _G_KINK, 0.1, np.maximum(0.0, 0.4 - 0.3 * _G_KINK), _KINK_REF, False
    if name == "fast-wall":
        return (_G_FAST, 8e5, 2e5 - 3e-5 * _G_FAST,
                pf.linear_boundary_area(8e5, _G_FAST, 2e5, -3e-5), True)
    raise KeyError(name)


CASES = ("images", "wall-receding", "wall-approaching", "kinked-wall", "fast-wall")


@pytest.mark.parametrize("rtol", RTOLS)
@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("method", ALL_METHODS)
def test_within_rtol_or_flagged(method, case, rtol):
    G, sigma0, sa, ref, _ = _case(case)
    r = pf.solve_diffusion(G, sigma0, sa, method=method, rtol=rtol)
    area = r.area[0]
    assert np.all(np.isfinite(area)) and np.all(np.isfinite(r.error_estimate[0]))
    ok = np.abs(area - ref) <= rtol * ref + ATOL
    assert np.all(ok) or r.status[0] != 0, (
        f"silent miss: max |dA|/(rtol A) = {np.max(np.abs(area - ref) / (rtol * ref + ATOL)):.3g}"
        f", status {r.status[0]}")


@pytest.mark.parametrize("rtol", RTOLS)
@pytest.mark.parametrize("case", ("images", "wall-receding", "wall-approaching", "fast-wall"))
def test_cn_estimate_is_the_error_of_the_returned_value(case, rtol):
    G, sigma0, sa, ref, _ = _case(case)
    r = pf.solve_diffusion(G, sigma0, sa, method="cn", rtol=rtol)
    actual = abs(r.area[0, -1] - ref[-1])
    est = r.error_estimate[0, -1]
    if actual > EST_FLOOR * ref[-1]:
        assert EST_LO <= est / actual <= EST_HI, (est, actual)
    else:
        assert est <= rtol * ref[-1] + ATOL


@pytest.mark.parametrize("case", ("images", "wall-receding", "wall-approaching"))
def test_cn_estimate_never_far_below_the_error(case):
    """At every returned G whose error matters (above a tenth of rtol), the estimate is at
    least half the actual error (where the error changes sign along G, a smaller one may
    locally be underestimated)."""
    G, sigma0, sa, ref, _ = _case(case)
    for rtol in RTOLS:
        r = pf.solve_diffusion(G, sigma0, sa, method="cn", rtol=rtol)
        actual = np.abs(r.area[0] - ref)
        big = actual > 0.1 * rtol * ref + ATOL
        assert np.all(r.error_estimate[0][big] >= 0.5 * actual[big]), rtol


@pytest.mark.parametrize("case", ("images", "wall-receding", "wall-approaching"))
def test_implicit_euler_tighter_rtol_is_never_worse(case):
    G, sigma0, sa, ref, _ = _case(case)
    errs = [np.max(np.abs(pf.solve_diffusion(G, sigma0, sa, method="implicit-euler",
                                              rtol=rt).area[0] - ref))
            for rt in (1e-3, 1e-4, 1e-5, 1e-6)]
    assert all(b <= a * 1.001 for a, b in zip(errs[:-1], errs[1:])), errs


def test_cn_dense_samples_of_a_smooth_wall_are_no_false_alarm():
    """60,000 samples of a linear wall: the samples force steps, they are not needed
    resolution; the answer is within rtol and the status is 0."""
    G = np.concatenate([[0.0], np.geomspace(1.0, 10.0, 60_000)])
    a, b = 0.5, -0.3
    r = pf.solve_diffusion(G, 1.0, a + b * G, method="cn", rtol=1e-6)
    ref = pf.linear_boundary_area(1.0, G[-1], a, b)
    assert abs(r.area[0, -1] - ref) <= 1e-6 * ref + ATOL
    assert r.status[0] == 0, r.message


@pytest.mark.parametrize("rtol", (1e-6, 1e-8))
def test_issue_walls_are_never_silently_wrong(rtol):
    """The kinked and the fast straight wall of issue 12: status 0 only when within rtol."""
    for case in ("kinked-wall", "fast-wall"):
        G, sigma0, sa, ref, _ = _case(case)
        r = pf.solve_diffusion(G, sigma0, sa, method="cn", rtol=rtol)
        err = abs(r.area[0, -1] - ref[-1])
        assert err <= rtol * ref[-1] + ATOL or r.status[0] != 0, (case, err / ref[-1])
        # the estimate reports the error reached
        assert r.error_estimate[0, -1] >= 0.5 * err, (case, r.error_estimate[0, -1], err)


@pytest.mark.parametrize("rtol", (1e-6, 1e-7, 1e-8))
@pytest.mark.parametrize("case", ("kinked-wall", "fast-wall"))
def test_issue_walls_are_within_rtol_with_status_0(case, rtol):
    """Issue 12: the kinked and the fast straight wall are solved, not only flagged."""
    G, sigma0, sa, ref, _ = _case(case)
    r = pf.solve_diffusion(G, sigma0, sa, method="cn", rtol=rtol)
    assert r.status[0] == 0, r.message
    assert np.all(np.abs(r.area[0] - ref) <= rtol * ref + ATOL), (
        np.max(np.abs(r.area[0] - ref) / (rtol * ref + ATOL)))
