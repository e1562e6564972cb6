"""A-posteriori control of the zeta-grid error of the adhesive fixed point (issue 12).

The fixed point runs on three nested zeta grids (the grid, one coarser, one finer); the end
area is extrapolated from the two finest and its error estimated from the three
(:func:`persson_fast.adhesion.fixed_point._ladder_estimate`); a pressure whose estimate exceeds rtol is
refined, and flagged RTOL_NOT_MET if the work cap leaves it above. Where gamma_eff changes
sign sigma_a starts as a square root, which the kernel samples (``wall_solve``).

References: converged solutions of the same scenes on much finer zeta grids (inner rtol
1e-8), computed here and compared with each other before they are used.
"""
import numpy as np
import pytest

import persson_fast as pf
from persson_fast._kernels.status import RTOL_NOT_MET
from persson_fast.adhesion.ladder import _ladder_estimate
from persson_fast.adhesion.zeta_grid import adhesion_zeta, coarsen_zeta, refine_zeta
from persson_fast.adhesion.fixed_point import solve_adhesive_contact

SA = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, C0=1e-22)
E_SA = 1e9
DG_SA = 0.05
P_SA = np.array([1e5, 1e6, 1e7])


def _fixed_grid(surface, pressure, per_decade, e_star, dg, rtol=1e-8):
    """The fixed point on a given (fine) grid, Richardson-extrapolated over one refinement."""
    z = adhesion_zeta(surface, per_decade=per_decade)
    return pf.solve_contact(surface, pressure, e_star=e_star, work_of_adhesion=dg, rtol=rtol,
                            zeta=z)


#: A(zeta1)/A0 of the self-affine scene at P_SA, from the fixed point on 160 points per
#: decade (inner rtol 1e-8), and its uncertainty: the difference from 80 per decade.
#: Recomputed by the slow test ``test_sa_reference_values``.
SA_REFERENCE = np.array([0.023332581259, 0.229924055933, 0.990857611202])
SA_REFERENCE_ERR = np.array([6.3e-8, 5.2e-7, 2.0e-8])


def test_sa_reference_scene_crosses_zero():
    """gamma_eff changes sign inside the zeta range at every pressure (sqrt onset)."""
    r = pf.solve_contact(SA, P_SA, e_star=E_SA, work_of_adhesion=DG_SA, rtol=1e-3)
    g = r.gamma_eff
    assert np.all(np.any((g[:, :-1] > 0) != (g[:, 1:] > 0), axis=1))


@pytest.mark.slow
def test_sa_reference_values():
    a = _fixed_grid(SA, P_SA, 80, E_SA, DG_SA)
    b = _fixed_grid(SA, P_SA, 160, E_SA, DG_SA)
    assert np.all(np.abs(b.area - SA_REFERENCE) <= 1e-8)
    assert np.all(np.abs(a.area - b.area) <= 1.5 * SA_REFERENCE_ERR)


@pytest.fixture(scope="module")
def sa_reference():
    return SA_REFERENCE, SA_REFERENCE_ERR


@pytest.mark.parametrize("rtol", [1e-3, 1e-4, pytest.param(1e-5, marks=pytest.mark.slow)])
def test_sqrt_onset_scene_within_rtol_or_flagged(sa_reference, rtol):
    """Before: A(1 MPa) came back 2.8e-4 off at rtol 1e-6 (and 5x rtol at 1e-4) with status
    0; the ladder of two grids could not see the erratic convergence after the onset."""
    ref, ref_err = sa_reference
    r = pf.solve_contact(SA, P_SA, e_star=E_SA, work_of_adhesion=DG_SA, rtol=rtol)
    assert np.all(np.isfinite(r.area))
    err = np.abs(r.area - ref)
    ok = r.status == 0
    assert np.all(err[ok] <= rtol * ref[ok] + 1e-12 + ref_err[ok]), (r.area, ref, r.status)
    # the estimate is not below the error by more than 2x where the error is measurable
    big = ok & (err > 10 * ref_err + 1e-12)
    assert np.all(r.error_estimate[big] >= 0.5 * err[big]), (r.error_estimate, err)


def test_estimate_not_far_above_the_error_where_met(sa_reference):
    """Where the error is measurable against the reference (3x its error bar), the
    estimate is within 0.5-10x of it (the fixed point's area-settling stop made the middle
    pressure's error 9e-8, below that bar; the last one's is 2.4e-6)."""
    ref, ref_err = sa_reference
    r = pf.solve_contact(SA, P_SA, e_star=E_SA, work_of_adhesion=DG_SA, rtol=1e-4)
    err = np.abs(r.area - ref)
    assert np.all(r.status == 0)
    meas = err > 3 * ref_err
    assert np.any(meas)
    ratio = r.error_estimate[meas] / err[meas]
    assert np.all((ratio >= 0.5) & (ratio <= 10)), ratio


def test_seed_estimate_calibrated():
    """Seed scene (no sign change of gamma_eff at these pressures): the three-level estimate
    of the extrapolated area is within 0.5-10x its error, against a 4x finer grid."""
    S, E, DG = pf.seed_scene(), pf.seed_e_star(), pf.SEED_WORK_OF_ADHESION
    p = np.array([5e6, 2e7, 6e7])
    ref = _fixed_grid(S, p, 184, E, DG, rtol=1e-9).area
    r = pf.solve_contact(S, p, e_star=E, work_of_adhesion=DG, rtol=1e-4)
    err = np.abs(r.area - ref)
    assert np.all(r.status == 0) and np.all(err <= 1e-4 * ref)
    meas = err > 1e-8
    assert np.any(meas)
    ratio = r.error_estimate[meas] / err[meas]
    assert np.all((ratio >= 0.5) & (ratio <= 30)), ratio
    # the two-level estimate this replaced was 10-100x above the error on this scene
    assert np.all(r.error_estimate <= 1e-4 * r.area)


@pytest.mark.slow
def test_tighter_rtol_is_not_worse(sa_reference):
    # errors below the reference's own error bar (5.2e-7 here) are not resolved by it: the
    # comparison is of max(error, bar) (rtol 1e-4 and 1e-5 both land below the bar)
    ref, ref_err = sa_reference
    errs = []
    for rtol in (1e-3, 1e-4, 1e-5):
        r = pf.solve_contact(SA, P_SA[1:2], e_star=E_SA, work_of_adhesion=DG_SA, rtol=rtol)
        errs.append(max(abs(r.area[0] - ref[1]), ref_err[1]))
    assert errs[1] <= errs[0] * 1.5 and errs[2] <= errs[1] * 1.5, errs


def test_coarse_user_grid_is_refined_or_flagged():
    """A very coarse user zeta grid: before, its area came back silently wrong."""
    S, E, DG = pf.seed_scene(), pf.seed_e_star(), pf.SEED_WORK_OF_ADHESION
    z1 = S.q1 / S.q0
    coarse = np.array([1.0, 10.0, 100.0, 1000.0, 1e4, z1])
    ref = _fixed_grid(S, [3e7], 92, E, DG, rtol=1e-9).area[0]
    r = pf.solve_contact(S, [3e7], e_star=E, work_of_adhesion=DG, rtol=1e-4, zeta=coarse)
    err = abs(r.area[0] - ref)
    assert r.status[0] in (0, RTOL_NOT_MET)
    if r.status[0] == 0:
        assert err <= 1e-4 * ref
    else:
        assert "zeta grid refined" in r.message
        assert r.error_estimate[0] >= 0.5 * err


def test_ladder_estimate_formula():
    """Order-2 ladder of the raw areas (differences shrinking by 4): R is exact, the
    estimate is |R - R0|/3 = 0; an order-3 error left after extrapolation is estimated
    within 2.3x; a non-asymptotic ladder falls back to the last difference."""
    h = np.array([1.0, 0.5, 0.25])
    a = 1.0 + 0.1 * h ** 2
    est = _ladder_estimate(np.array([a[0]]), np.array([a[1]]), np.array([a[2]]), np.array([True]))
    assert est[0] == pytest.approx(0.0, abs=1e-15)
    a = 1.0 + 0.1 * h ** 2 + 0.05 * h ** 3
    R = (4 * a[2] - a[1]) / 3
    est = _ladder_estimate(np.array([a[0]]), np.array([a[1]]), np.array([a[2]]), np.array([True]))
    assert abs(R - 1.0) <= est[0] <= 2.5 * abs(R - 1.0)
    est = _ladder_estimate(np.array([1.0]), np.array([1.1]), np.array([1.0]), np.array([True]))
    assert est[0] == pytest.approx(0.1)


def test_coarsen_nests():
    z = adhesion_zeta(SA, 1e-4)
    zc, idx = coarsen_zeta(z)
    assert zc[0] == 1.0 and zc[-1] == z[-1] and np.all(np.diff(zc) > 0)
    assert np.all(np.isin(zc, z)) and np.array_equal(z[idx], zc)
    assert np.all(np.isin(z, refine_zeta(z)))


def test_onset_flag_off_is_the_plain_wall():
    """pull_off's checks run the fixed point with the wall linear between the nodes (the
    discretisation of its branch follower); solve_contact shapes the onset. Both agree to
    the zeta-grid error, and differ (the shaping does something) where gamma_eff crosses 0."""
    z = adhesion_zeta(SA, 1e-4)
    kw = dict(e_star=E_SA, work_of_adhesion=DG_SA, rtol=1e-6, zeta_given=True)
    on = solve_adhesive_contact(SA, [1e6], z, **kw)
    off = solve_adhesive_contact(SA, [1e6], z, onset=False, **kw)
    assert on.area[0] != off.area[0]
    assert abs(on.area[0] - off.area[0]) <= 1e-3 * on.area[0]
