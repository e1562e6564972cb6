"""The prototype of a forward-march adhesive solver (persson_fast.adhesion.march, not used by
solve_contact): the scalar form of the adhesive fixed point and the march, against today's
solver and the closed form without adhesion.

The whole file runs in the slow suite: compiling the march's kernels costs about a minute of
CPU on a cold cache, which the CI suite does not pay for a prototype (cached, the file takes
about 4 s, the tight test about 80 s)."""
import numpy as np
import pytest
from scipy.special import erf

import persson_fast as pf
from persson_fast.adhesion import march as am

E_SEED = pf.seed_e_star()
DG = pf.SEED_WORK_OF_ADHESION

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def seed_today():
    return pf.solve_contact(pf.seed_scene(), [0.0, 2e7, 8e7], e_star=E_SEED,
                            work_of_adhesion=DG, rtol=1e-6, parallel=False)


def test_identity_on_todays_solution(seed_today):
    """A(zeta) gamma_eff(zeta) = dgamma K + J(zeta), K = A(zeta1) - U_el(1)/dgamma,
    J = U_el(1) - U_el(zeta): Eq. 9 rewritten, checked on today's profiles."""
    r = seed_today
    u = r.elastic_energy_zeta                       # U_el(zeta) [J/m^2]
    K = r.area - u[:, 0] / DG
    J = u[:, :1] - u
    lhs = r.area_zeta * r.gamma_eff
    rhs = DG * K[:, None] + J
    assert np.allclose(lhs, rhs, rtol=0, atol=1e-9 * DG)


def _march_K_against_today(today, rtol):
    r = am.solve_march(pf.seed_scene(), [0.0, 2e7, 8e7], e_star=E_SEED, work_of_adhesion=DG,
                       rtol=rtol)
    K_today = today.area - today.elastic_energy_zeta[:, 0] / DG
    return (4 * r["K"][-1] - r["K"][-2]) / 3, K_today


def test_phi_bracket_and_root_matches_todays_K(seed_today):
    """Phi(-U_full/dgamma) <= 0 <= Phi(1); the march's root K agrees with today's
    K = A(zeta1) - U_el(1)/dgamma.

    It failed (K off by 1.1e-5 and 2.6e-5 at 20 and 80 MPa at the rtol-1e-8 mapping, the area
    right) while j up to the start (A = 1) was a trapezoid on the level-0 points only: a
    level-independent error in j that Richardson cannot remove; the root absorbs it in K
    (only K + j enters the wall). j there is now the exact j_1(G) (closed-form int q^2 C dq)
    by its cubic Hermite.

    The cheap version: the rtol-1e-6 mapping (0.4 s CPU), K within 1e-6 relative of today's
    (rtol 1e-6; measured 3.8e-7 / 3.0e-7 / 2.2e-7 at 0 / 20 / 80 MPa, today's K itself is
    3e-7 from today's at rtol 1e-8). The code before the fix (c83da25, at its own rtol-1e-6
    mapping) misses it by 8e-6 / 2.1e-4 / 5.1e-4. The rtol-1e-8 version is the slow test below."""
    K_march, K_today = _march_K_against_today(seed_today, 1e-6)
    assert np.allclose(K_march, K_today, rtol=1e-6, atol=0)
    surf = pf.seed_scene()
    mesh = am.MarchMesh(surf, E_SEED, DG, 2 ** -0.5, *am.resolution(1e-4)[1:], 1)
    lev = am._Level(mesh, 0, am.resolution(1e-4)[0], 2e7 / mesh.scale, 0.5, -1.0)
    u_full = surf.elastic_energy_full_contact(E_SEED) / DG
    assert lev.phi(-u_full)[0] <= 0.0 <= lev.phi(1.0)[0]


@pytest.mark.slow
def test_phi_root_matches_todays_K_tight():
    """As above at the rtol-1e-8 mapping (the original test, then K to 1e-5 against today at
    rtol 1e-6), now against today at rtol 1e-8 and to 1e-7 (measured 1.8e-9 / 6.9e-9 /
    5.9e-10 at 0 / 20 / 80 MPa; 80 s CPU: the march 65 s, today 13 s)."""
    today = pf.solve_contact(pf.seed_scene(), [0.0, 2e7, 8e7], e_star=E_SEED,
                             work_of_adhesion=DG, rtol=1e-8, parallel=False)
    K_march, K_today = _march_K_against_today(today, 1e-8)
    assert np.allclose(K_march, K_today, rtol=1e-7, atol=0)


@pytest.mark.xfail(strict=True, reason="prototype, measured after the calibration (5d1d141): "
                   "the areas pass (|march - today|/A 3.5e-7 / 4.3e-8 / 8.0e-8 at 0 / 20 / 80 "
                   "MPa, within 1e-6 A + today's estimate; 2.4e-7 / 4.0e-8 / 1.6e-8 against "
                   "today at rtol 1e-8), but the march's estimate at p = 0 is 1.8e-6 A > rtol "
                   "1e-6 (|R2 - R1|/2: pessimistic there, 7x the error)")
def test_march_area_against_today(seed_today):
    r = am.solve_march(pf.seed_scene(), [0.0, 2e7, 8e7], e_star=E_SEED, work_of_adhesion=DG,
                       rtol=1e-6)
    err = np.abs(r["area"] - seed_today.area)
    assert np.all(err <= 1e-6 * seed_today.area + seed_today.error_estimate)
    assert np.all(r["error_estimate"] <= 1e-6 * r["area"])


def test_weak_adhesion_limit_is_erf():
    """dgamma -> 0: A = erf(sigma0 / (2 sqrt(G1))). It failed on the rtol -> resolution
    mapping (not the physics: today's solver gives erf to 1.8e-8 at dgamma 1e-12): without
    adhesion the march missed rtol 1e-6 (1.9e-6 at 10 MPa); passes with the calibration."""
    s = pf.SelfAffine(hurst=0.8, q0=1e5, q1=1e9, h_rms=1e-7)
    p = np.array([1e6, 1e7])
    r = am.solve_march(s, p, e_star=1e9, work_of_adhesion=1e-12, rtol=1e-6)
    G1 = float(s.diffusion_time(s.q1, 1e9))
    exact = erf(p / (2 * np.sqrt(G1)))
    assert np.allclose(r["area"], exact, rtol=1e-6)


@pytest.mark.parametrize("dgamma", [1e-12, 1e-16, 1e-20, 1e-30])
def test_weak_adhesion_root_is_found_and_estimate_covers(dgamma):
    """U_el/dgamma up to ~7e29 (U_full/dgamma): the root must close and the estimate must
    cover the error against erf (the weak-adhesion limit). Fixed in the code, not refused.

    K ~ -U_el(1)/dgamma (-1e19 at dgamma 1e-20) and Phi = K + j(zeta1) - A is a difference of
    numbers ~1e19 whose result is ~A ~ 1e-2: Phi is quantised at K's rounding (ulp 2048), and
    the onset's j increments (K + j rises from 0 to a few ulps over the steps after G*) round
    away, so K a few ulps above -j gives Phi = -A again. At dgamma 1e-20 the level-1 root
    from level 0's K made secant steps of 4 ulps that stayed at Phi = -A, evaluated the same K
    twice (NaN slope) and raised 'Phi: no slope and no bracket'. Now, without a bracket, a
    step that is NaN, below 4 ulps or away from the sign change is replaced by one of 64 ulps
    (4 times more each time) towards it: Phi > 0 follows at once, and the bracket stops when
    its end areas agree to the tolerance (they differ by 5e-9 relative: A is resolved where
    K is not)."""
    s = pf.SelfAffine(hurst=0.8, q0=1e5, q1=1e9, h_rms=1e-7)
    p = np.array([1e6, 1e7])
    r = am.solve_march(s, p, e_star=1e9, work_of_adhesion=dgamma, rtol=1e-4)
    G1 = float(s.diffusion_time(s.q1, 1e9))
    exact = erf(p / (2 * np.sqrt(G1)))
    assert np.all(np.isfinite(r["areas"]))
    assert np.all(np.abs(r["area"] - exact) <= r["error_estimate"] + 1e-8 * exact)
