"""A yield wall with adhesion (issue 14): the adhesive fixed point with the two-wall solver
inside, Eqs. 8-9 on the elastic contact area."""
import numpy as np
import pytest
from hypothesis import assume, given, settings, strategies as hs

import persson_fast as pf

E = 1e9
#: a self-affine scene where the contact stress reaches sigma_Y ~ sqrt(G1) (H = 0.8, three
#: decades, h_rms = 10 nm): yielding and adhesion both matter
SURF = pf.SelfAffine(hurst=0.8, q0=1e6, q1=1e9, h_rms=1e-8)
H0 = float(np.sqrt(SURF.diffusion_time(np.array([SURF.q1]), E)[-1]))     # sqrt(G1) [Pa]
P = np.array([-0.05, 0.0, 0.01, 0.1]) * H0


def _contract(res, exact, rtol):
    err = np.abs(res.area - exact)
    ok = (err <= rtol * exact + 1e-12) | (res.status != 0)
    assert np.all(ok), (rtol, err / (rtol * exact), res.status)
    return err


@pytest.mark.parametrize("factor", [1.0, 3.0])
@pytest.mark.parametrize("rtol", [1e-4, 1e-6])
def test_vanishing_detachment_wall_is_the_exact_yield_series(factor, rtol):
    """Detachment prefactor 1e-20 (a wall of ~1e-11 Pa): the constant yield wall without
    adhesion, whose exact answer is the two-wall image series (an independent path)."""
    p = np.array([0.01, 0.1, 0.5]) * H0
    res = pf.solve_contact(SURF, p, e_star=E, work_of_adhesion=0.2, detachment_prefactor=1e-20,
                           hardness=factor * H0, rtol=rtol)
    exact = pf.solve_contact(SURF, p, e_star=E, hardness=factor * H0)
    assert exact.method == "analytic"
    assert np.all(res.status == 0), res.message
    _contract(res, exact.area, rtol)
    np.testing.assert_allclose(res.plastic_area, exact.plastic_area, rtol=2 * rtol, atol=1e-12)
    assert res.method == "strip"


def test_far_yield_wall_is_the_adhesive_contact():
    """sigma_Y far above every stress the distribution reaches: the adhesive answer, no
    plastic area."""
    rtol = 1e-6
    res = pf.solve_contact(SURF, P, e_star=E, work_of_adhesion=0.2, hardness=1e3 * H0,
                           rtol=rtol)
    ref = pf.solve_contact(SURF, P, e_star=E, work_of_adhesion=0.2, rtol=rtol)
    assert np.all(res.status == 0) and np.all(ref.status == 0)
    np.testing.assert_array_less(res.plastic_area, 1e-12)
    assert np.all(np.abs(res.area - ref.area) <= 2 * rtol * ref.area)


@pytest.fixture(scope="module")
def reference():
    """Scale-dependent hardness sigma_Y = sqrt(G1) zeta^0.15 with Delta gamma = 0.2 J/m^2,
    tension included, at rtol 1e-8 (the converged reference)."""
    h = pf.hardness_power_law(H0, 0.15)
    return h, pf.solve_contact(SURF, P, e_star=E, work_of_adhesion=0.2, hardness=h, rtol=1e-8)


@pytest.mark.parametrize("rtol", [1e-4, 1e-6])
def test_scale_dependent_hardness_with_adhesion_converges(rtol, reference):
    h, ref = reference
    assert np.all(ref.status == 0), ref.message
    res = pf.solve_contact(SURF, P, e_star=E, work_of_adhesion=0.2, hardness=h, rtol=rtol)
    assert np.all(res.status == 0), res.message
    err = _contract(res, ref.area, rtol)
    assert np.all(res.error_estimate >= 0.3 * err)
    # both parts in contact, each in [0, A]; adhesion raises the area, yield caps the stress
    np.testing.assert_allclose(res.elastic_area + res.plastic_area, res.area, rtol=0, atol=1e-15)
    assert np.all((res.plastic_area > 0) & (res.plastic_area < res.area))
    dry = pf.solve_contact(SURF, P[1:], e_star=E, hardness=h, rtol=rtol)
    assert np.all(res.area[1:] > dry.area + 0.1)


@pytest.mark.parametrize("rtol", [1e-4, 1e-6])
def test_load_bookkeeping(reference, rtol):
    """load (elastic part) + plastic_load - detached_load = p_nom to 1e-10 of the stress scale
    (measured <= 7e-13: the two-wall scheme conserves the load moment exactly, the Richardson
    combination keeps linear identities); the areas' own balance A_el + A_pl + D = 1 holds to
    rounding (each level's to ~1e-14, the Richardson combination of two levels and the
    fixed point's clipping of the profiles leave up to ~7e-13)."""
    h, _ = reference
    res = pf.solve_contact(SURF, P, e_star=E, work_of_adhesion=0.2, hardness=h, rtol=rtol)
    scale = np.max(np.abs([P, res.load, res.plastic_load, res.detached_load]), axis=0)
    gap = np.abs(res.load + res.plastic_load - res.detached_load - P)
    assert np.all(gap <= 1e-10 * scale), gap / scale
    np.testing.assert_allclose(res.area + res.detached_area, 1.0, rtol=0, atol=1e-11)


def test_separated_tension_is_checked_against_the_yield_pull_off():
    """A tension three times the pull-off stress with this yield wall (about 4.5 MPa = 0.17
    H0) separates, and pull_off with the same yield wall confirms it (status 0)."""
    res = pf.solve_contact(SURF, np.array([-0.5 * H0, 0.01 * H0]), e_star=E,
                           work_of_adhesion=0.2, hardness=H0, rtol=1e-3)
    assert res.area[0] == 0 and res.status[0] == 0, res.message
    assert res.status[1] == 0


def test_refusals():
    with pytest.raises(ValueError, match=r"method must be 'auto' or 'strip' for a yield wall "
                                         r"with adhesion.*'cn'"):
        pf.solve_contact(SURF, 1e5, e_star=E, work_of_adhesion=0.2, hardness=H0, method="cn")
    with pytest.raises(ValueError, match=r"pressure must be <= hardness at zeta = 1"):
        pf.solve_contact(SURF, 2 * H0, e_star=E, work_of_adhesion=0.2, hardness=H0)
    with pytest.raises(ValueError, match=r"hardness\(zeta\) must return finite values > 0"):
        pf.solve_contact(SURF, 1e5, e_star=E, work_of_adhesion=0.2,
                         hardness=lambda z: -np.ones_like(z))


def test_threads_bitwise_equal_to_serial(reference):
    """The per-pressure yield rows are dealt to the threads with their pressures."""
    h, _ = reference
    p = np.linspace(-0.05, 0.5, 9) * H0
    kw = dict(e_star=E, work_of_adhesion=0.2, hardness=h, rtol=1e-4)
    a = pf.solve_contact(SURF, p, parallel=False, **kw)
    b = pf.solve_contact(SURF, p, parallel=None, **kw)
    for name in ("area", "plastic_area", "error_estimate", "status", "sigma_a"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))


@pytest.mark.parametrize("hardness, rtols, ref_rtol", [
    (300e6, (1e-4,), 1e-6),
    pytest.param("soft", (1e-4, 1e-6), 1e-7, marks=pytest.mark.slow)])
def test_seed_scene_near_the_detachment_wall(hardness, rtols, ref_rtol):
    """The seed scene with adhesion at p_nom = 0 and 1 MPa: the start sits ~1 MPa from the
    detachment wall in a strip 300 MPa wide (status 3, START_UNRESOLVED, before). The wall
    recedes faster than the distribution spreads, so the free start lasts; now OK, within
    rtol of a tighter solution (measured <= 0.25 rtol at rtol 1e-3 ... 1e-6 against rtol
    1e-7), the estimate covering the error (measured 1.7-12x). (At rtol 1e-7 the 300 MPa
    scene needs more than the work cap and is flagged GRID_CAP.)"""
    surface, e_star = pf.seed_scene(), pf.seed_e_star()
    h = pf.hardness_power_law(150e6, 0.15) if hardness == "soft" else hardness
    p = np.array([0.0, 1e6])
    kw = dict(e_star=e_star, work_of_adhesion=pf.SEED_WORK_OF_ADHESION, hardness=h)
    ref = pf.solve_contact(surface, p, rtol=ref_rtol, **kw)
    assert np.all(ref.status == 0), ref.message
    for rtol in rtols:
        res = pf.solve_contact(surface, p, rtol=rtol, **kw)
        assert np.all(res.status == 0), res.message
        err = _contract(res, ref.area, rtol)
        assert np.all(res.error_estimate >= 0.5 * err)
        assert np.all(res.plastic_area > 0.05)


@settings(max_examples=12, deadline=None)
# (normal numbers only: below the smallest normal double the balance has no relative digits)
@given(p_frac=hs.floats(-0.05, 0.5, allow_subnormal=False), h_frac=hs.floats(0.5, 3.0),
       n=hs.sampled_from([0.0, 0.15, 0.3]), dgamma=hs.floats(0.02, 0.4))
def test_bookkeeping_with_adhesion_property(p_frac, h_frac, n, dgamma):
    """Random pressures (tension included), hardness (constant or rising as zeta^n) and work
    of adhesion: A_el + A_pl + D = 1 and load + plastic_load - detached_load = p_nom, both
    to 1e-10 (of 1 and of the stress scale), wherever the contact is not separated."""
    p = np.array([p_frac * H0])
    h = h_frac * H0 if n == 0.0 else pf.hardness_power_law(h_frac * H0, n)
    res = pf.solve_contact(SURF, p, e_star=E, work_of_adhesion=dgamma, hardness=h, rtol=1e-4)
    assume(res.area[0] > 0.0)
    total = res.elastic_area + res.plastic_area + res.detached_area
    np.testing.assert_allclose(total, 1.0, rtol=0, atol=1e-10)
    scale = np.max(np.abs([p, res.load, res.plastic_load, res.detached_load]), axis=0)
    gap = np.abs(res.load + res.plastic_load - res.detached_load - p)
    assert np.all(gap <= 1e-10 * scale), gap / scale
