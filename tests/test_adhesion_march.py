"""Issue 41 prototype: the scalar form of the adhesive fixed point and the forward march."""
import numpy as np
import pytest
from scipy.special import erf

import persson_fast as pf
from persson_fast.adhesion import march as am

E_SEED = pf.seed_e_star()
DG = pf.SEED_WORK_OF_ADHESION


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


def test_phi_bracket_and_root_matches_todays_K(seed_today):
    """Phi(-U_full/dgamma) <= 0 <= Phi(1); the march's root K agrees with today's
    K = A(zeta1) - U_el(1)/dgamma.

    It failed (K off by 1.1e-5 and 2.6e-5 at 20 and 80 MPa, the area right) while j up to the
    start (A = 1) was a trapezoid on the level-0 points only: a level-independent error in j
    that Richardson cannot remove; the root absorbs it in K (only K + j enters the wall).
    j there is now the exact j_1(G) (closed-form int q^2 C dq) by its cubic Hermite."""
    surf = pf.seed_scene()
    r = am.solve_march(surf, [0.0, 2e7, 8e7], e_star=E_SEED, work_of_adhesion=DG, rtol=1e-8)
    K_today = seed_today.area - seed_today.elastic_energy_zeta[:, 0] / DG
    K_march = (4 * r["K"][-1] - r["K"][-2]) / 3
    assert np.allclose(K_march, K_today, rtol=1e-5, atol=0)
    mesh = am.MarchMesh(surf, E_SEED, DG, 2 ** -0.5, *am.resolution(1e-4)[1:], 1)
    lev = am._Level(mesh, 0, am.resolution(1e-4)[0], 2e7 / mesh.scale, 0.5, -1.0)
    u_full = surf.elastic_energy_full_contact(E_SEED) / DG
    assert lev.phi(-u_full)[0] <= 0.0 <= lev.phi(1.0)[0]


@pytest.mark.xfail(strict=True, reason="prototype: at the rtol-1e-6 mapping (level-0 mesh 8 per "
                   "decade of zeta, 2.5 per e-fold of G) the seed scene is not asymptotic; "
                   "measured errors up to 2e-5 relative with estimates below them")
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


@pytest.mark.parametrize("dgamma", [1e-12, 1e-20])
def test_weak_adhesion_root_is_found_and_estimate_covers(dgamma):
    """U_el/dgamma up to 1e19: K + j(zeta1) is a difference at K's rounding; the root must
    still close (it raised 'no slope and no bracket' at dgamma 1e-16) and the estimate must
    cover the error against erf (the weak-adhesion limit)."""
    s = pf.SelfAffine(hurst=0.8, q0=1e5, q1=1e9, h_rms=1e-7)
    p = np.array([1e6, 1e7])
    r = am.solve_march(s, p, e_star=1e9, work_of_adhesion=dgamma, rtol=1e-4)
    G1 = float(s.diffusion_time(s.q1, 1e9))
    exact = erf(p / (2 * np.sqrt(G1)))
    assert np.all(np.abs(r["area"] - exact) <= r["error_estimate"] + 1e-8 * exact)
