"""Corrected theories (yp08, wm17) with adhesion: the corrected diffusion dT/dG = S(A) solved
together with the self-consistent detachment stress (issue 17, item 2)."""
import numpy as np
import pytest

import persson_fast as pf
from persson_fast._kernels.status import LOST_CONTACT

SEED = pf.seed_scene()
E = pf.seed_e_star()
DG = pf.SEED_WORK_OF_ADHESION


def _within(res, exact, rtol):
    """Every row within rtol of ``exact`` or flagged; returns the errors."""
    err = np.abs(res.area - exact)
    ok = (err <= rtol * np.abs(exact) + 1e-12) | (res.status != 0)
    assert np.all(ok), (res.theory, rtol, err / (rtol * exact), res.status)
    return err


@pytest.mark.parametrize("theory", ["yp08", "wm17"])
@pytest.mark.parametrize("rtol", [1e-4, 1e-6])
def test_vanishing_detachment_wall_is_the_wall_free_theory(theory, rtol):
    """With a detachment prefactor of 1e-20 the wall is ~1e-11 Pa: the adhesive corrected
    diffusion must then give the wall-free corrected theory (an exact, independent path: a
    tabulated ODE in y = p / (2 sqrt(G)), accurate to 1e-12), within rtol, with an error
    estimate that is neither far below nor absurdly above the error."""
    p = np.array([1e4, 1e5, 3e5, 1e6])
    res = pf.solve_contact(SEED, p, e_star=E, work_of_adhesion=DG, detachment_prefactor=1e-20,
                           theory=theory, rtol=rtol)
    exact = pf.solve_contact(SEED, p, e_star=E, theory=theory).area
    assert np.all(res.status == 0), res.message
    err = _within(res, exact, rtol)
    # the estimate bounds the error from above (up to a factor 2 under) and stays within
    # rtol (it drives the refinement, so a wild over-estimate would cost work, not accuracy)
    assert np.all(res.error_estimate >= 0.5 * err)
    assert np.all(res.error_estimate <= rtol * exact)
    assert res.theory == theory and res.theory_gamma == pf.theories.DEFAULT_GAMMA[theory]


@pytest.fixture(scope="module")
def seed_reference():
    """The seed scene with adhesion, each theory at rtol 1e-8 (the converged reference)."""
    p = np.array([-2e5, 0.0, 1e5, 1e6])
    return p, {th: pf.solve_contact(SEED, p, e_star=E, work_of_adhesion=DG, theory=th,
                                    rtol=1e-8)
               for th in ("yp08", "wm17")}


@pytest.mark.parametrize("theory", ["yp08", "wm17"])
@pytest.mark.parametrize("rtol", [1e-4, 1e-6])
def test_seed_scene_with_adhesion_converges(theory, rtol, seed_reference):
    p, ref = seed_reference
    assert np.all(ref[theory].status == 0), ref[theory].message
    res = pf.solve_contact(SEED, p, e_star=E, work_of_adhesion=DG, theory=theory, rtol=rtol)
    assert np.all(res.status == 0), res.message
    err = _within(res, ref[theory].area, rtol)
    assert np.all(res.error_estimate >= 0.5 * err)
    # the corrections raise the area of the original theory (S <= 1 slows the spread)
    orig = pf.solve_contact(SEED, p, e_star=E, work_of_adhesion=DG, rtol=rtol)
    assert np.all(res.area > orig.area + 0.1)


@pytest.mark.parametrize("theory", ["yp08", "wm17"])
def test_load_bookkeeping(theory):
    """load - detached_load = p_nom (the carried load, plus what the detached parts pull)
    at every magnification, to 1e-10 of the stress scale."""
    p = np.array([-3e5, 0.0, 2e5, 2e6])
    res = pf.solve_contact(SEED, p, e_star=E, work_of_adhesion=DG, theory=theory, rtol=1e-6)
    scale = np.maximum(np.abs(p), np.max(np.abs(res.load_zeta), axis=1))
    gap = np.abs(res.load_zeta - res.detached_load_zeta - p[:, None])
    assert np.all(gap <= 1e-10 * scale[:, None]), np.max(gap / scale[:, None])
    assert np.all(np.abs(res.load - res.detached_load - p) <= 1e-10 * scale)


def test_yp08_gamma_one_is_the_original_theory():
    """S = 1 for yp08 with gamma = 1: the same answer as the original theory, both within
    rtol of the truth (not bitwise: the corrected path integrates T = G numerically)."""
    p = np.array([-1e5, 0.0, 5e5])
    rtol = 1e-6
    a = pf.solve_contact(SEED, p, e_star=E, work_of_adhesion=DG, theory="yp08",
                         theory_gamma=1.0, rtol=rtol)
    b = pf.solve_contact(SEED, p, e_star=E, work_of_adhesion=DG, rtol=rtol)
    assert np.all(a.status == 0) and np.all(b.status == 0)
    assert np.all(np.abs(a.area - b.area) <= 2 * rtol * b.area)


def test_separated_tension_is_flagged():
    """A tension far beyond the pull-off stress separates; for a corrected theory no
    pull-off stress is computed to confirm it, so the row is flagged, never a silent A = 0."""
    res = pf.solve_contact(SEED, np.array([-5e6, 1e5]), e_star=E, work_of_adhesion=DG,
                           theory="yp08", rtol=1e-4)
    assert res.area[0] == 0.0 and res.status[0] == LOST_CONTACT
    assert res.status[1] == 0 and "theory='yp08'" in res.message


def test_walls_a_theory_cannot_serve():
    with pytest.raises(ValueError, match=r"theory='xu24' is defined only at full magnification"
                                         r".*theory='persson01', 'yp08', 'wm17'"):
        pf.solve_contact(SEED, 1e5, e_star=E, work_of_adhesion=DG, theory="xu24")
    with pytest.raises(ValueError, match=r"theory='yp08'"):
        pf.solve_contact(SEED, 1e5, e_star=E, theory="yp08", hardness=3e8)
    with pytest.raises(ValueError, match=r"theory='persson01'$"):
        pf.theories.check_theory_scene("wm17", DG, hardness=3e8)
    pf.theories.check_theory_scene("wm17", DG)          # served: no error
