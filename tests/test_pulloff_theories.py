"""Pull-off stress of the corrected theories (yp08, wm17) and with a yield wall (issue 36):
the contact branch of the scene solve_contact solves, followed to its end."""
import warnings

import numpy as np
import pytest

import persson_fast as pf
from persson_fast.adhesion import branch as pb
from persson_fast.adhesion.runner import ADHESION_DEFAULTS, THEORY_CODES, _controls
from persson_fast.methods import choose_auto, variant_of
from persson_fast.adhesion.pulloff import PULL_OFF_OMEGA, _near_one_min
from persson_fast.theories import DEFAULT_GAMMA, correction_factor
from persson_fast.adhesion.zeta_grid import adhesion_zeta

SEED = pf.seed_scene()
E_STAR = 2.9e9 / (1 - 0.3**2)
DGAMMA = 0.06
#: a self-affine scene with a visible pull-off (as in test_pulloff.py)
SA = pf.SelfAffine(hurst=0.8, q0=1e5, q1=1e8, h_rms=2e-8)
SA_E_STAR = 1e9
SA_DGAMMA = 0.05
#: references [Pa]: pull_off at a tight rtol on its default grid and on that grid refined
#: once (refine_zeta); REFERENCE_TOL covers their difference and their estimates (the values
#: in the comments)
REFERENCES = {
    # seed wm17: 1129099.33 +- 0.93 at rtol 1e-6 (618 s); on the refined grid 1129086.0 +- 37
    # (a branch point of its end correction failed); the difference, 13 Pa, is the tolerance
    ("seed", "wm17"): 1129099.33,
    # seed yp08: 1060393.06 +- 24.9 at rtol 1e-5, refined 1060396.03 +- 16.8
    ("seed", "yp08"): 1060395.0,
    # self-affine wm17: 578012.72 +- 3.97 at rtol 1e-5, refined 578013.08 +- 2.52
    ("sa", "wm17"): 578012.9,
    # self-affine yp08: 591314.86 +- 148 at rtol 1e-5 (its zeta-grid part not converged),
    # refined 591309.41 +- 6.7
    ("sa", "yp08"): 591309.4,
}
REFERENCE_TOL = {("seed", "wm17"): 15.0, ("seed", "yp08"): 25.0, ("sa", "wm17"): 4.0,
                 ("sa", "yp08"): 7.0}
SCENES = {"seed": (SEED, E_STAR, DGAMMA), "sa": (SA, SA_E_STAR, SA_DGAMMA)}


def _pull_off(scene, rtol, **kw):
    surface, e, dg = SCENES[scene]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", RuntimeWarning)
        sigma_c, info = pf.pull_off(surface, e_star=e, work_of_adhesion=dg, rtol=rtol,
                                    full_output=True, bracket=False, **kw)
    flagged = any("exceeds rtol" in str(w.message) for w in caught)
    return sigma_c, info, flagged


def _check(sigma_c, info, flagged, reference, ref_tol, rtol):
    """The contract: within the estimate of the reference; converged exactly when the
    estimate meets rtol (else warned)."""
    assert abs(sigma_c - reference) <= info["error_estimate"] + ref_tol, (
        sigma_c, reference, info["error_parts"])
    assert info["error_estimate"] == pytest.approx(sum(info["error_parts"].values()))
    if info["converged"]:
        assert info["error_estimate"] <= rtol * sigma_c
    else:
        assert flagged


# --- the end of the branch is a contact state: an independent check ---------------------

def _branch_end(surface, e, dg, theory, hardness, rtol=1e-3):
    """The descent of pull_off on its coarsest grid; its converged point of least sigma0."""
    beta = 2 ** -0.5
    z = adhesion_zeta(surface, rtol, near_one_min=_near_one_min(surface, e, dg, beta))
    ctl = _controls(None, {**ADHESION_DEFAULTS, "omega": PULL_OFF_OMEGA})
    ctl["max_iter"] = 300
    variant = variant_of(choose_auto("adhesion"))
    gamma = 1.0 if theory == "persson01" else DEFAULT_GAMMA[theory]
    b = pb._Branch(surface, z, e, dg, beta, -1.0, variant, ctl["n_damp"],
                   THEORY_CODES.get(theory, 0), gamma, hardness)
    rest = pb._rest_start(b, rtol, ctl, -1.0, variant)
    samples, *_ = pb._descend(b, rest["x"], rest["x"][0] * b.scale, rtol, ctl)
    return b, min((s for s in samples if s["converged"]), key=lambda s: s["sigma0"]), gamma


def _independent_residual(surface, e, dg, branch, point, theory, gamma, hardness):
    """max |F(x) - x| of a branch point, F evaluated without the branch's code: the public
    solve_diffusion in the point's times against its wall (and the yield wall), then Eqs.
    8-9 with U_el by Gauss-Legendre quadrature of (pi E*/2) q^2 C(q) F(A_el) (F linear in q
    between the nodes, as the fixed point discretises it) and the corrected times by the
    trapezoid rule of S(A) dG. sigma_a relative to beta (dgamma E* q)^(1/2), T to G1."""
    beta = 2 ** -0.5
    z = branch.zeta
    n = z.size
    q = z * surface.q0
    G = np.maximum.accumulate(np.asarray(surface.diffusion_time(q, e), dtype=float))
    G[0] = 0.0
    x = point["x"]
    sa = x[:n] * branch.scale
    T = x[n:] * G[-1] if theory != "persson01" else G
    walls = {} if hardness is None else {"sigma_y": np.full(n, float(hardness))}
    d = pf.solve_diffusion(T, point["sigma0"], sigma_a=sa, rtol=1e-7, **walls)
    assert d.status[0] == 0, d.message
    el = d.area[0]
    real = el + (d.plastic_area[0] if hardness is not None else 0.0)
    xg, wg = np.polynomial.legendre.leggauss(20)
    U = np.zeros(n)
    for k in range(n - 2, -1, -1):
        qq = 0.5 * (q[k + 1] - q[k]) * xg + 0.5 * (q[k + 1] + q[k])
        f = el[k] + (el[k + 1] - el[k]) * (qq - q[k]) / (q[k + 1] - q[k])
        U[k] = U[k + 1] + 0.25 * np.pi * e / dg * (q[k + 1] - q[k]) * np.sum(
            wg * qq**2 * surface.psd(qq) * f)
    g = (real[-1] - U) / real
    c = beta * np.sqrt(dg * e * q)
    res = np.max(np.abs(c * np.sqrt(np.maximum(g, 0.0)) - sa) / c)
    if theory != "persson01":
        s = correction_factor(theory, gamma, real)
        T_new = np.concatenate([[0.0], np.cumsum(0.5 * (s[1:] + s[:-1]) * np.diff(G))])
        res = max(res, np.max(np.abs(T_new - T)) / G[-1])
    return res, real[-1]


@pytest.mark.parametrize("theory, hardness", [("yp08", None), ("wm17", None),
                                              ("persson01", 2e8)])
def test_end_of_branch_is_contact_and_beyond_is_separated(theory, hardness):
    """Both sides of sigma_c, for the seed scene: the branch point of least sigma0 is a
    contact state (A(zeta1) > 0.4) by an independent evaluation of Eqs. 8-9 (residual a
    fraction of rtol), within the estimate below -sigma_c + estimate; solve_contact separates
    (status 0, confirmed) 1 % beyond sigma_c + estimate, and at a tension just inside it
    never returns a silent A = 0."""
    kw = {} if hardness is None else {"hardness": hardness}
    kw_theory = {} if theory == "persson01" else {"theory": theory}
    sigma_c, info, _ = _pull_off("seed", 1e-3, **kw, **kw_theory)
    err = info["error_estimate"]
    branch, end, gamma = _branch_end(SEED, E_STAR, DGAMMA, theory, hardness)
    res, area = _independent_residual(SEED, E_STAR, DGAMMA, branch, end, theory, gamma,
                                      hardness)
    assert res <= 0.05 * 1e-3 and area > 0.4, (res, area)
    assert -sigma_c - err <= end["sigma0"] <= -sigma_c + err + 0.01 * sigma_c
    r = pf.solve_contact(SEED, np.array([-0.995 * sigma_c, -1.01 * (sigma_c + err)]),
                         e_star=E_STAR, work_of_adhesion=DGAMMA, rtol=1e-3, **kw, **kw_theory)
    assert not (r.area[0] == 0 and r.status[0] == 0), r.message
    assert r.area[1] == 0 and r.status[1] == 0, r.message


@pytest.mark.parametrize("rtol", [1e-3, pytest.param(1e-4, marks=pytest.mark.slow)])
@pytest.mark.parametrize("scene, theory", [("seed", "wm17"), ("seed", "yp08"),
                                           ("sa", "wm17"), ("sa", "yp08")])
def test_corrected_theory_within_estimate(scene, theory, rtol):
    ref = REFERENCES[(scene, theory)]
    sigma_c, info, flagged = _pull_off(scene, rtol, theory=theory)
    _check(sigma_c, info, flagged, ref, REFERENCE_TOL[(scene, theory)], rtol)
    if rtol >= 1e-3:        # the reference's own uncertainty is far below rtol sigma_c
        assert info["converged"] and abs(sigma_c - ref) <= rtol * ref
    else:
        assert abs(sigma_c - ref) <= rtol * ref + REFERENCE_TOL[(scene, theory)]


def test_corrected_theories_stick_harder():
    """The corrected theories spread the stress less (S(A) <= 1): more contact at p_nom = 0
    and a larger pull-off stress than the original theory, on the seed scene."""
    base, _, _ = _pull_off("seed", 1e-3)
    for theory in ("yp08", "wm17"):
        sigma_c, info, _ = _pull_off("seed", 1e-3, theory=theory)
        assert sigma_c > 1.3 * base and info["theory"] == theory
        assert info["theory_gamma"] == DEFAULT_GAMMA[theory]


#: a self-affine scene where yield and adhesion both matter (test_yield_adhesion.py)
YSURF = pf.SelfAffine(hurst=0.8, q0=1e6, q1=1e9, h_rms=1e-8)
H0 = float(np.sqrt(YSURF.diffusion_time(np.array([YSURF.q1]), 1e9)[-1]))


@pytest.mark.parametrize("surface, dg, hardness", [(SEED, DGAMMA, 2e8), (SEED, DGAMMA, 5e7),
                                                   (YSURF, 0.2, H0)])
def test_yield_wall_value_with_estimate_on_both_sides(surface, dg, hardness):
    """With a yield wall the branch is followed as far as the two-wall solver resolves its
    start; the rest is charged (tail): a value with a finite estimate, flagged when it misses
    rtol, and solve_contact agrees on both sides of it (contact or a flag 0.5 % inside,
    confirmed separation beyond sigma_c + estimate)."""
    e = E_STAR if surface is SEED else 1e9
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", RuntimeWarning)
        sigma_c, info = pf.pull_off(surface, e_star=e, work_of_adhesion=dg, hardness=hardness,
                                    rtol=1e-3, full_output=True, bracket=False)
    err = info["error_estimate"]
    assert info["sticky"] and 0 < err < 0.02 * sigma_c, info["error_parts"]
    if info["converged"]:
        assert err <= 1e-3 * sigma_c
    else:
        assert any("exceeds rtol" in str(w.message) for w in caught)
    if info["lost"]:
        assert "code" in info["lost"] or "did not converge" in info["lost"]
    r = pf.solve_contact(surface, np.array([-(sigma_c - err) * 0.995, -1.01 * (sigma_c + err)]),
                         e_star=e, work_of_adhesion=dg, hardness=hardness, rtol=1e-3)
    assert not (r.area[0] == 0 and r.status[0] == 0), r.message
    assert r.area[1] == 0 and r.status[1] == 0, r.message
    # the yield wall changes the answer: the elastic scene's pull-off is outside the estimate
    elastic = pf.pull_off(surface, e_star=e, work_of_adhesion=dg, rtol=1e-3)
    assert abs(elastic - sigma_c) > err


def test_scene_with_hardness_is_the_keyword_form():
    scene = pf.Scene(YSURF, e_star=1e9, work_of_adhesion=0.2, hardness=H0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        a = pf.pull_off(scene, rtol=1e-3)
        b = pf.pull_off(YSURF, e_star=1e9, work_of_adhesion=0.2, hardness=H0, rtol=1e-3)
    assert a == b
    with pytest.raises(ValueError, match="either in the Scene or as keywords"):
        pf.pull_off(scene, hardness=H0, rtol=1e-3)


@pytest.mark.parametrize("kw", [{"theory": "yp08"}, {"theory": "wm17"}, {"hardness": 1e8},
                                {"theory": "wm17", "hardness": 1e8}])
def test_not_sticky_is_zero_with_its_reason(kw):
    """A scene that does not stick (this one loses its contact at p_nom = 0 for every
    theory): 0, converged, with the reason."""
    s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    sigma_c, info = pf.pull_off(s, e_star=1e9, work_of_adhesion=0.05, rtol=1e-3,
                                full_output=True, **kw)
    assert sigma_c == 0.0 and info["converged"] and not info["sticky"]
    assert info["reason"].startswith("not sticky")
    sigma_c, info = pf.pull_off(s, e_star=1e9, work_of_adhesion=0.0, rtol=1e-3,
                                full_output=True, **kw)
    assert sigma_c == 0.0 and "no adhesion" in info["reason"]


def test_refusals():
    with pytest.raises(ValueError, match=r"theory='xu24' is defined only at full magnification"):
        pf.pull_off(SA, e_star=1e9, work_of_adhesion=0.05, theory="xu24")
    with pytest.raises(ValueError, match="theory must be one of"):
        pf.pull_off(SA, e_star=1e9, work_of_adhesion=0.05, theory="yp09")
    with pytest.raises(ValueError, match="theory_gamma must be None for theory='persson01'"):
        pf.pull_off(SA, e_star=1e9, work_of_adhesion=0.05, theory_gamma=0.5)
    with pytest.raises(ValueError, match="hardness"):
        pf.pull_off(SA, e_star=1e9, work_of_adhesion=0.05, hardness=-1.0)
    # xu24 without adhesion has no detachment wall: 0
    assert pf.pull_off(SA, e_star=1e9, work_of_adhesion=0.0, theory="xu24") == 0.0


def test_scan_pull_off_per_theory():
    """scan(pull_off=True) along a theory axis gives each theory's own pull_off."""
    ds = pf.scan(SA, {"work_of_adhesion": [SA_DGAMMA]}, [1e5], e_star=SA_E_STAR, rtol=1e-3,
                 theory=["persson01", "wm17"], pull_off=True, progress=False)
    for theory in ("persson01", "wm17"):
        kw = {} if theory == "persson01" else {"theory": theory}
        expected = pf.pull_off(SA, e_star=SA_E_STAR, work_of_adhesion=SA_DGAMMA, rtol=1e-3,
                               **kw)
        got = float(ds.pull_off.sel(theory=theory).squeeze())
        assert got == expected > 0
