"""Mean separation, contact stiffness and elastic energy without adhesion (persson_fast.separation).

Oracles: scipy's own special functions and quadrature for the one-dimensional pieces (E1,
J, the table of Kfun); the same closed form on a doubled node set (convergence of the q
quadrature); the energy route u = -U_el/p + int_p^inf U_el/p'^2 dp' with the package's U_el
(an independent route to u); finite differences of u for K; the asymptotic laws. The
independent double quadrature of the whole formula is in tests/test_reference_separation.py.
"""
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st
from scipy import integrate, special

import persson_fast as pf
from persson_fast.separation import elastic as sep
from persson_fast._kernels import separation as ksep
from persson_fast.surfaces.models import seed_e_star, seed_scene

SELF_AFFINE = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
E_SA = 1e9
SCENES = {"self_affine": (SELF_AFFINE, E_SA), "seed": (seed_scene(), seed_e_star())}
#: relative accuracy the closed form is held to against its own doubled node set and the
#: one-dimensional oracles (measured ~1e-12; rounding of sums of ~600 terms ~1e-14)
QUAD_RTOL = 1e-10


def _with_nodes(monkeypatch_values, surface, e, p, gamma):
    saved = {k: getattr(sep, k) for k in monkeypatch_values}
    try:
        for k, v in monkeypatch_values.items():
            setattr(sep, k, v)
        nodes = sep.separation_nodes(surface, e)
    finally:
        for k, v in saved.items():
            setattr(sep, k, v)
    u, q, energy, status = sep._evaluate(nodes, gamma, np.asarray(p, float), parallel=False)
    return u, np.asarray(p) / q, energy


DOUBLED = {"PANEL_NODES": 20, "TAU_PANEL_NODES": 20, "PANELS_PER_DECADE": 8, "Q0_RATIO": 2 ** 0.5,
           "Q0_LEVELS": 80, "LN_G_STEP": 0.5,
           "Q1_LEVELS": 24}


# --- one-dimensional pieces ---------------------------------------------------------------
@pytest.mark.parametrize("x", [1e-12, 1e-3, 0.3, 0.999, 1.0, 1.001, 2.5, 10.0, 80.0, 700.0])
def test_exp1_matches_mpmath(x):
    """Series below 1, continued fraction above: ~3e-15 relative next to x = 1 (measured)."""
    import mpmath

    with mpmath.workdps(30):
        exact = float(mpmath.e1(x))
    assert ksep.exp1(x) == pytest.approx(exact, rel=5e-15, abs=0)


def _j_quad(s):
    f = lambda t: special.erf(t) ** 2 * math.exp(-t * t) / t   # noqa: E731
    return integrate.quad(f, s, s + 40.0, epsabs=0, epsrel=1e-13, limit=200)[0]


@pytest.mark.parametrize("s", [1e-6, 0.1, 0.7, 1.9, 2.0, 2.1, 3.3, 5.9, 6.0, 6.5])
def test_erf_squared_tail_matches_quadrature(s):
    low, high = sep.j_coefficients()
    assert ksep.erf_squared_tail(s, low, high) == pytest.approx(_j_quad(s), rel=1e-12)


@pytest.mark.parametrize("gamma", [1.0, 0.45, 0.0])
def test_kfun_table_matches_direct_evaluation(gamma):
    low, high = sep.j_coefficients()
    v, dv, j0 = sep.kfun_table(gamma)
    rng = np.random.default_rng(3)
    for x in np.concatenate([rng.uniform(-25.0, 3.5, 400), [-18.4, -18.5, 3.25, 3.3]]):
        s = math.exp(x)
        exact = ksep.separation_integrand(s, gamma, low, high)
        got = ksep.kfun_scaled(x, s * s, gamma, j0, v, dv, sep.KFUN_X_LOW,
                               float(sep.KFUN_STEPS_PER_UNIT)) * math.exp(-s * s)
        assert got == pytest.approx(exact, rel=1e-12), x


def test_kfun_is_half_e1_for_s_equal_1():
    low, high = sep.j_coefficients()
    for s in (1e-3, 0.5, 2.0, 7.0):
        assert ksep.separation_integrand(s, 1.0, low, high) == pytest.approx(
            0.5 * special.exp1(s * s), rel=2e-15)


# --- the q quadrature ------------------------------------------------------------------------
@pytest.mark.parametrize("name", SCENES)
@pytest.mark.parametrize("gamma", [1.0, 0.45])
def test_doubled_nodes_agree(name, gamma):
    surface, e = SCENES[name]
    p = np.logspace(-2, 9.5, 24)
    u1, k1, e1 = _with_nodes({}, surface, e, p, gamma)
    u2, k2, e2 = _with_nodes(DOUBLED, surface, e, p, gamma)
    keep = u2 > 1e-290
    np.testing.assert_allclose(u1[keep], u2[keep], rtol=QUAD_RTOL)
    np.testing.assert_allclose(k1[keep], k2[keep], rtol=QUAD_RTOL)
    np.testing.assert_allclose(e1, e2, rtol=QUAD_RTOL)


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(hurst=st.floats(0.3, 1.0), decades=st.floats(0.4, 7.0), rolloff=st.floats(0.0, 1.0),
       gamma=st.sampled_from([1.0, 0.45, 0.1]), log_p=st.floats(-3.0, 1.5))
# p = 10 sqrt(G1): a ln G level just below q1 left the panel before it unrefined (8.9e-10)
@example(hurst=0.5, decades=1.0, rolloff=0.0, gamma=1.0, log_p=1.0)
def test_doubled_nodes_agree_on_random_self_affine_scenes(hurst, decades, rolloff, gamma, log_p):
    q0 = 1e5
    q1 = q0 * 10 ** decades
    q_r = q0 * (q1 / q0) ** (0.5 * rolloff)
    surface = pf.SelfAffine(hurst=hurst, q0=q0, q1=q1, q_r=None if rolloff == 0 else q_r,
                            h_rms=1e-7)
    e = 1e9
    root_g1 = math.sqrt(surface.diffusion_time(q1, e))
    p = root_g1 * 10.0 ** np.array([log_p - 2.0, log_p - 1.0, log_p])
    u1, k1, e1 = _with_nodes({}, surface, e, p, gamma)
    u2, k2, e2 = _with_nodes(DOUBLED, surface, e, p, gamma)
    keep = u2 > 1e-290
    np.testing.assert_allclose(u1[keep], u2[keep], rtol=QUAD_RTOL)
    np.testing.assert_allclose(k1[keep], k2[keep], rtol=QUAD_RTOL)
    np.testing.assert_allclose(e1, e2, rtol=QUAD_RTOL)


@pytest.mark.parametrize("hurst, decades, rolloff", [
    (0.5, 1.0, 0.0), (0.7062326701907955, 2.371394476604889, 0.6719948779563594)])
def test_layer_at_q1_is_resolved_at_large_pressure(hurst, decades, rolloff):
    """At large p, u comes from a layer at q1 whose width in ln q shrinks like 4 G1 / p^2;
    the dyadic panels toward q1 must cover it whatever edge lies just below q1. Against a
    rule with three times the nodes per panel, four times the panels and a quarter of the
    ln G step, p up to 40 sqrt(G1): below 1e-12 (before: 8.9e-10 at 10 sqrt(G1) on the first
    scene, 0.43 at 40 sqrt(G1) on the second, status 0)."""
    q0 = 1e5
    q1 = q0 * 10 ** decades
    surface = pf.SelfAffine(hurst=hurst, q0=q0, q1=q1,
                            q_r=q0 * (q1 / q0) ** (0.5 * rolloff) if rolloff else None,
                            h_rms=1e-7)
    e = 1e9
    p = math.sqrt(surface.diffusion_time(q1, e)) * np.geomspace(1.0, 40.0, 25)
    fine = {"PANEL_NODES": 30, "TAU_PANEL_NODES": 20, "PANELS_PER_DECADE": 8,
            "LN_G_STEP": 0.25, "Q1_LEVELS": 32}
    for gamma in (1.0, 0.45):
        u1, k1, _ = _with_nodes({}, surface, e, p, gamma)
        u2, k2, _ = _with_nodes(fine, surface, e, p, gamma)
        keep = u2 > 1e-290
        assert keep.sum() >= 20
        np.testing.assert_allclose(u1[keep], u2[keep], rtol=1e-12)
        np.testing.assert_allclose(k1[keep], k2[keep], rtol=1e-12)


def test_full_contact_energy_is_the_closed_form():
    for surface, e in SCENES.values():
        r = pf.solve_separation(surface, [1e12], e_star=e)
        assert r.elastic_energy[0] == pytest.approx(surface.elastic_energy_full_contact(e),
                                                    rel=1e-13)
        assert r.area[0] == 1.0


# --- routes, derivatives, inverse -----------------------------------------------------------
@pytest.mark.parametrize("name", SCENES)
@pytest.mark.parametrize("gamma", [None, 0.45])
def test_energy_route_agrees(name, gamma):
    """u = int_p^inf (1/p') dU_el/dp' dp' = -U_el(p)/p + int_p^inf U_el(p')/p'^2 dp'.

    U_el is the package's; the integral in x = ln p' by scipy's quad."""
    surface, e = SCENES[name]

    def energy(x):
        return pf.solve_separation(surface, [math.exp(x)], e_star=e,
                                   energy_correction=gamma, parallel=False).elastic_energy[0]

    root_g1 = math.sqrt(surface.diffusion_time(surface.q1, e))
    for p in (1e4, 1e6, 1e8):
        x_end = math.log(40.0 * root_g1)
        tail = integrate.quad(lambda x: energy(x) * math.exp(-x), math.log(p), x_end,
                              epsabs=0, epsrel=1e-11, limit=200)[0]
        tail += energy(x_end) * math.exp(-x_end)          # U_el constant beyond: int U/p'^2
        route = -energy(math.log(p)) / p + tail
        r = pf.solve_separation(surface, [p], e_star=e, energy_correction=gamma)
        assert r.separation[0] == pytest.approx(route, rel=1e-8), p


@pytest.mark.parametrize("name", SCENES)
@pytest.mark.parametrize("gamma", [None, 0.45])
def test_stiffness_is_minus_dp_du(name, gamma):
    surface, e = SCENES[name]
    for p in (1e3, 1e5, 1e7, 3e8):
        h = 1e-4
        pp = p * np.exp([-h, h])
        r = pf.solve_separation(surface, np.concatenate([[p], pp]), e_star=e,
                                energy_correction=gamma)
        fd = -(pp[1] - pp[0]) / (r.separation[2] - r.separation[1])
        # central difference in ln p: relative error ~ h^2 (d^3 u/d(ln p)^3 / du/d ln p) / 6
        assert r.stiffness[0] == pytest.approx(fd, rel=1e-6), p


@pytest.mark.parametrize("name", SCENES)
@pytest.mark.parametrize("gamma", [None, 0.45])
@pytest.mark.parametrize("rtol", [1e-6, 1e-10])
def test_pressure_at_separation_inverts(name, gamma, rtol):
    surface, e = SCENES[name]
    p = np.geomspace(1e-2, 2e9, 60)
    u = pf.solve_separation(surface, p, e_star=e, energy_correction=gamma).separation
    back = pf.pressure_at_separation(surface, u, e_star=e, energy_correction=gamma, rtol=rtol)
    np.testing.assert_allclose(back, p, rtol=rtol)
    grid = np.geomspace(u.min(), 3 * u.max(), 300)[::-1]
    inv = pf.pressure_at_separation(surface, grid, e_star=e, energy_correction=gamma)
    assert np.all(np.diff(inv) > 0)                      # p rises as u falls


def test_pressure_at_separation_scalar_shape_and_far_tails():
    u0 = pf.decay_length(SELF_AFFINE, e_star=E_SA)
    p = pf.pressure_at_separation(SELF_AFFINE, 1e-6, e_star=E_SA)
    assert isinstance(p, float)
    arr = pf.pressure_at_separation(SELF_AFFINE, [[1e-6, 2e-6]], e_star=E_SA)
    assert arr.shape == (1, 2)
    # far beyond the floor: the exact small-pressure law, p ratio exp(-du/u0)
    a, b = pf.pressure_at_separation(SELF_AFFINE, [40e-6, 41e-6], e_star=E_SA)
    assert b / a == pytest.approx(math.exp(-1e-6 / u0), rel=1e-9)
    # a separation far below the roughness: a pressure of many sqrt(G1), finite
    high = pf.pressure_at_separation(SELF_AFFINE, 1e-200, e_star=E_SA)
    u_back = pf.solve_separation(SELF_AFFINE, [high], e_star=E_SA).separation[0]
    assert u_back == pytest.approx(1e-200, rel=1e-7)


# --- asymptotics -----------------------------------------------------------------------------
@pytest.mark.parametrize("name", SCENES)
@pytest.mark.parametrize("gamma", [None, 0.45])
def test_small_pressure_law_and_large_pressure_limit(name, gamma):
    surface, e = SCENES[name]
    u0 = pf.decay_length(surface, e_star=e, energy_correction=gamma)
    root_g1 = math.sqrt(surface.diffusion_time(surface.q1, e))
    p = root_g1 * np.array([1e-12, 1e-11, 1e-10])
    r = pf.solve_separation(surface, p, e_star=e, energy_correction=gamma)
    slope = np.diff(np.log(p)) / np.diff(r.separation)   # d ln p / du
    np.testing.assert_allclose(slope, -1.0 / u0, rtol=1e-5)
    np.testing.assert_allclose(r.stiffness / p, 1.0 / u0, rtol=1e-5)
    # the approach is linear in p: K u0 / p - 1 = O(p) (1e-11 to 1e-9 of sqrt(G1) here)
    dev = r.stiffness * u0 / p - 1.0
    np.testing.assert_allclose(dev[1:] / dev[:-1], 10.0, rtol=1e-2)
    # u0 with S = gamma_S + (1 - gamma_S) P^2 is gamma_S times that of S = 1
    if gamma is not None:
        assert u0 == pytest.approx(gamma * pf.decay_length(surface, e_star=e), rel=1e-14)
    big = pf.solve_separation(surface, root_g1 * np.array([4.0, 8.0, 16.0]), e_star=e,
                              energy_correction=gamma)
    assert np.all(np.diff(big.separation) < 0)
    assert big.separation[-1] < 1e-30 * surface.h_rms


def test_decay_length_does_not_depend_on_e_star():
    a = pf.decay_length(SELF_AFFINE, e_star=1e9)
    b = pf.decay_length(SELF_AFFINE, e_star=3.7e6)
    assert a == pytest.approx(b, rel=1e-13)
    assert 0.5 * SELF_AFFINE.h_rms < a < 2 * SELF_AFFINE.h_rms


def test_separation_scales_with_the_roughness():
    """C -> lambda^2 C: u -> lambda u at p -> lambda p (G -> lambda^2 G)."""
    lam = 7.0
    big = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=lam * 1e-6)
    p = np.geomspace(1e3, 1e8, 6)
    a = pf.solve_separation(SELF_AFFINE, p, e_star=E_SA, energy_correction=0.45)
    b = pf.solve_separation(big, lam * p, e_star=E_SA, energy_correction=0.45)
    np.testing.assert_allclose(b.separation, lam * a.separation, rtol=1e-12)
    np.testing.assert_allclose(b.stiffness, a.stiffness, rtol=1e-12)
    np.testing.assert_allclose(b.elastic_energy, lam ** 2 * a.elastic_energy, rtol=1e-12)


# --- through solve_contact, Scene, threads, status, bad input ----------------------------------
def test_solve_contact_fields():
    p = np.array([0.0, 1e4, 1e6, 1e8])
    r = pf.solve_contact(SELF_AFFINE, p, e_star=E_SA, energy_correction=0.45)
    ref = pf.solve_separation(SELF_AFFINE, p[1:], e_star=E_SA, energy_correction=0.45)
    assert r.separation[0] == math.inf and r.stiffness[0] == 0.0 and r.elastic_energy[0] == 0.0
    np.testing.assert_array_equal(r.separation[1:], ref.separation)
    np.testing.assert_array_equal(r.stiffness[1:], ref.stiffness)
    np.testing.assert_array_equal(r.elastic_energy[1:], ref.elastic_energy)
    assert "separation" in r.timings
    scene = pf.Scene(SELF_AFFINE, e_star=E_SA, energy_correction=0.45)
    rs = pf.solve_contact(scene, p, method="cn", rtol=1e-4)
    np.testing.assert_array_equal(rs.separation, r.separation)
    np.testing.assert_array_equal(pf.solve_separation(scene, p[1:]).separation, ref.separation)


def test_threads_are_bitwise_serial():
    p = np.geomspace(1e2, 1e9, 257)
    a = pf.solve_separation(SELF_AFFINE, p, e_star=E_SA, energy_correction=0.45, parallel=False)
    b = pf.solve_separation(SELF_AFFINE, p, e_star=E_SA, energy_correction=0.45, parallel=True)
    c = pf.solve_separation(SELF_AFFINE, p[::-1], e_star=E_SA, energy_correction=0.45)
    for name in ("separation", "stiffness", "elastic_energy"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
        np.testing.assert_array_equal(getattr(a, name), getattr(c, name)[::-1])


def test_adhesion_and_corrected_theories_are_refused():
    r = pf.solve_contact(SELF_AFFINE, [1e6], e_star=E_SA, work_of_adhesion=0.01)
    with pytest.raises(ValueError, match="without adhesion only"):
        r.separation
    with pytest.raises(ValueError, match="without adhesion only"):
        r.stiffness
    assert r.elastic_energy.shape == (1,)
    np.testing.assert_array_equal(r.elastic_energy, r.elastic_energy_zeta[:, 0])
    for call in (lambda: pf.solve_separation(SELF_AFFINE, [1e6], e_star=E_SA),):
        call()
    scene = pf.Scene(SELF_AFFINE, e_star=E_SA, work_of_adhesion=0.01)
    for call in (lambda: pf.solve_separation(scene, [1e6]),
                 lambda: pf.pressure_at_separation(scene, 1e-6),
                 lambda: pf.decay_length(scene)):
        with pytest.raises(ValueError, match="without adhesion only"):
            call()
    t = pf.solve_contact(SELF_AFFINE, [1e6], e_star=E_SA, theory="yp08")
    with pytest.raises(ValueError, match="persson01"):
        t.separation


def test_pressure_below_the_resolved_range_is_flagged():
    floor = sep.nodes_for(SELF_AFFINE, E_SA).pressure_floor
    r = pf.solve_separation(SELF_AFFINE, [floor / 10, floor * 10], e_star=E_SA)
    assert list(r.status) == [pf.separation.BELOW_RESOLVED, 0]
    assert not r.success and "resolved range" in r.message


@pytest.mark.parametrize("bad, match", [
    ([1e5, -1e3], r"pressure must be >= 0.*pressure\[1\] = -1000.0"),
    ([-1.0], r"pressure must be >= 0"),
    ([np.nan], r"pressure must be finite"),
    ("abc", r"pressure must be a real number"),
])
def test_bad_pressure(bad, match):
    with pytest.raises(ValueError, match=match):
        pf.solve_separation(SELF_AFFINE, bad, e_star=E_SA)


@pytest.mark.parametrize("bad, match", [
    (0.0, r"separation must be > 0"),
    ([1e-6, -1e-9], r"separation\[1\] = -1e-09"),
    (np.nan, r"separation must be a number > 0"),
    (-np.inf, r"separation must be > 0"),
])
def test_bad_separation(bad, match):
    with pytest.raises(ValueError, match=match):
        pf.pressure_at_separation(SELF_AFFINE, bad, e_star=E_SA)


def test_bad_scene_arguments():
    with pytest.raises(ValueError, match="e_star"):
        pf.solve_separation(SELF_AFFINE, [1e5], e_star=-1.0)
    with pytest.raises(ValueError, match="e_star"):
        pf.solve_separation(SELF_AFFINE, [1e5])
    with pytest.raises(ValueError, match="energy_correction"):
        pf.solve_separation(SELF_AFFINE, [1e5], e_star=E_SA, energy_correction=1.5)
    with pytest.raises(ValueError, match="rtol"):
        pf.pressure_at_separation(SELF_AFFINE, 1e-6, e_star=E_SA, rtol=0.0)


# --- against the slow reference twin (scipy quad of the double integral) ---------------------
def _reference():
    from persson_fast._reference import separation as ref
    return ref


@pytest.mark.parametrize("name", SCENES)
@pytest.mark.parametrize("gamma", [None, 0.45])
def test_matches_reference_twin(name, gamma):
    """u, K and U_el at p = 1e3 ... 1e9 Pa within 1e-9 (measured ~1e-13; the issue asks 1e-6)."""
    ref = _reference()
    surface, e = SCENES[name]
    p = np.array([1e3, 1e5, 1e7, 1e9])
    r = pf.solve_separation(surface, p, e_star=e, energy_correction=gamma)
    for i, pi in enumerate(p):
        assert r.separation[i] == pytest.approx(ref.separation_quad(surface, pi, e, gamma),
                                                rel=1e-9)
        assert r.stiffness[i] == pytest.approx(ref.stiffness_quad(surface, pi, e, gamma),
                                               rel=1e-9)
        assert r.elastic_energy[i] == pytest.approx(
            ref.elastic_energy_quad(surface, pi, e, gamma), rel=1e-9)


@pytest.mark.slow
@pytest.mark.parametrize("name", SCENES)
@pytest.mark.parametrize("gamma", [None, 0.45])
def test_matches_reference_energy_route_every_decade(name, gamma):
    """u at every decade from 1e3 to 1e9 Pa against the twin's energy route (its U_el inside
    the integration by parts), and K against its stiffness, within 1e-9."""
    ref = _reference()
    surface, e = SCENES[name]
    p = np.logspace(3, 9, 7)
    r = pf.solve_separation(surface, p, e_star=e, energy_correction=gamma)
    for i, pi in enumerate(p):
        assert r.separation[i] == pytest.approx(
            ref.separation_energy_route(surface, pi, e, gamma), rel=1e-9)
        assert r.stiffness[i] == pytest.approx(ref.stiffness_quad(surface, pi, e, gamma),
                                               rel=1e-9)
