"""Tests of persson_fast.surfaces: closed-form moments against 30-digit quadrature, the seed's
numbers, normalisations, tabulated spectra, properties of G(q) and argument validation."""
from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from persson_fast.surfaces.models import (
    BOLTZMANN,
    CapillaryWaves,
    SelfAffine,
    Surface,
    TabulatedPSD,
    seed_scene,
)

# Tolerances (and why)
# closed forms / Gauss-Legendre vs 30-digit mpmath quadrature: the contract is 1e-10; measured
# errors are <= 1e-14, so 1e-12 keeps a margin of 100 and still catches a lost digit or two
RTOL_QUAD = 1e-12
RTOL_EXACT = 1e-12  # two exact float64 evaluations of the same quantity (rounding only)
MP_DPS = 30

Q0_SEED = 2 * np.pi / 1e-4


# ----------------------------------------------------------------------------------------------
# 30-digit reference: integrate q^k C(q) in t = ln q, split at breakpoints and every 2 units,
# with mpmath's degree-adaptive Gauss-Legendre rule (same values as tanh-sinh here, twice as fast)
# ----------------------------------------------------------------------------------------------
def mp_moment(c_mp, k, a, b, breaks=()):
    with mp.workdps(MP_DPS):
        la, lb = mp.log(mp.mpf(a)), mp.log(mp.mpf(b))
        cuts = sorted({la, lb, *(mp.log(mp.mpf(x)) for x in breaks if a < x < b)})
        pts = [cuts[0]]
        for lo, hi in zip(cuts[:-1], cuts[1:]):
            n = max(1, int(mp.ceil((hi - lo) / 2)))
            pts.extend(lo + (hi - lo) * i / n for i in range(1, n + 1))

        def f(t):
            q = mp.exp(t)
            return q ** (k + 1) * c_mp(q)

        # mp.quad's tolerance is absolute: scale the integrand to O(1) first
        scale = max(abs(f(x)) for x in pts) or mp.mpf(1)
        return mp.quad(lambda t: f(t) / scale, pts, method="gauss-legendre") * scale


def mp_capillary(s: CapillaryWaves):
    with mp.workdps(MP_DPS):
        return _mp_capillary(s)


def _mp_capillary(s: CapillaryWaves):
    amp = mp.mpf(BOLTZMANN) * mp.mpf(s.temperature) / (4 * mp.pi**2)
    gam, kap = mp.mpf(s.surface_tension), mp.mpf(s.bending_stiffness)
    rho_g = mp.mpf(s.density) * mp.mpf(s.gravity)
    return lambda q: amp / (rho_g + gam * q**2 + kap * q**4)


def mp_self_affine(s: SelfAffine):
    c0, qr, h = mp.mpf(s.C0), mp.mpf(s.q_r), mp.mpf(s.hurst)
    return lambda q: c0 if q < qr else c0 * (q / qr) ** (-2 * (1 + h))


def mp_table(qt, ct):
    qt = [mp.mpf(float(x)) for x in qt]
    ct = [mp.mpf(float(x)) for x in ct]

    def c(q):
        for j in range(len(qt) - 1):
            if qt[j] <= q <= qt[j + 1]:
                if ct[j] == 0 or ct[j + 1] == 0:
                    return mp.mpf(0)
                alpha = mp.log(ct[j + 1] / ct[j]) / mp.log(qt[j + 1] / qt[j])
                return ct[j] * (q / qt[j]) ** alpha
        return mp.mpf(0)

    return c


def assert_rel(actual, expected, rtol, what=""):
    expected = float(expected)
    if expected == 0.0:
        assert actual == 0.0, f"{what}: got {actual!r}, expected 0"
        return
    err = abs(actual - expected) / abs(expected)
    assert err <= rtol, f"{what}: got {actual!r}, expected {expected!r}, rel err {err:.3e}"


def limit_sets(s: Surface):
    """Full band, a lower and an upper part, an interior piece crossing breakpoints, a narrow one."""
    q0, q1 = s.q0, s.q1
    g = math.sqrt(q0 * q1)
    return [
        (q0, q1),
        (q0, g),
        (g * 1.37, q1),
        (q0 * 1.5, q1 / 3.0),
        (g, g * (1 + 1e-6)),
    ]


def check_moments_against_mp(s: Surface, c_mp, ks=(0, 1, 2, 3), limits=None):
    for k in ks:
        for a, b in limits or limit_sets(s):
            ref = mp_moment(c_mp, k, a, b, s.breakpoints())
            assert_rel(s.moment(k, a, b), ref, RTOL_QUAD, f"{s!r} k={k} [{a:g},{b:g}]")


# ----------------------------------------------------------------------------------------------
# capillary waves
# ----------------------------------------------------------------------------------------------
CAPILLARY_CASES = {
    "seed": dict(temperature=370.0, surface_tension=0.04, q_c=1.7e9, q0=Q0_SEED, q1=7e9),
    "seed_gravity": dict(
        temperature=370.0, surface_tension=0.04, q_c=1.7e9, q0=Q0_SEED, q1=7e9, density=1190.0
    ),
    # gravity dominant at long wavelengths: regimes u << p, p < u < s and u >> s all in the band
    "strong_gravity": dict(
        temperature=300.0, surface_tension=0.04, q_c=1e4, q0=10.0, q1=1e7, density=1000.0
    ),
    # nearly coincident roots of rho g + gamma u + kappa u^2 (s < 3p): quadrature branch for k = 3
    "near_degenerate": dict(
        temperature=300.0, surface_tension=0.04, q_c=1e3, q0=1.0, q1=1e6, density=1000.0
    ),
    # complex roots (discriminant < 0)
    "complex_roots": dict(
        temperature=300.0, surface_tension=0.04, q_c=1e3, q0=1.0, q1=1e6, density=2000.0
    ),
    # just above the s = 3p switch of the k = 3 closed form (largest cancellation it allows)
    "gravity_near_switch": dict(
        temperature=300.0, surface_tension=0.04, q_c=1e3, q0=1.0, q1=1e6, density=760.0
    ),
    "band_above_qc": dict(temperature=500.0, surface_tension=0.07, q_c=1e6, q0=1e7, q1=1e10),
}


@pytest.mark.parametrize("case", sorted(CAPILLARY_CASES))
def test_capillary_moments_match_mpmath(case):
    s = CapillaryWaves(**CAPILLARY_CASES[case])
    check_moments_against_mp(s, mp_capillary(s))


def test_capillary_discriminant_branches_are_exercised():
    sg = CapillaryWaves(**CAPILLARY_CASES["strong_gravity"])
    assert sg._disc > 0 and sg._s >= 3 * sg._p and sg.q0**2 < sg._p < sg._s < sg.q1**2
    nd = CapillaryWaves(**CAPILLARY_CASES["near_degenerate"])
    assert nd._disc > 0 and nd._s < 3 * nd._p
    assert CapillaryWaves(**CAPILLARY_CASES["complex_roots"])._disc < 0
    ns = CapillaryWaves(**CAPILLARY_CASES["gravity_near_switch"])
    assert 3 * ns._p <= ns._s < 3.1 * ns._p


def test_seed_h_rms_and_eq2():
    s = seed_scene()
    h = s.h_rms()
    assert 0.45e-9 < h < 0.46e-9  # 0.455 nm; the paper rounds to 0.5 nm
    assert round(h * 1e9, 1) == 0.5
    kt, gam, qc, q0, q1 = BOLTZMANN * 370.0, 0.04, 1.7e9, Q0_SEED, 7e9
    eq2 = kt / (2 * math.pi * gam) * math.log(q1 / q0 * math.sqrt((q0**2 + qc**2) / (q1**2 + qc**2)))
    assert_rel(h**2, eq2, RTOL_EXACT, "Eq. 2")
    assert s.bending_stiffness == pytest.approx(gam / qc**2, rel=1e-15)


def test_capillary_diffusion_time_closed_form():
    s = seed_scene()
    e_star = 2.9e9 / (1 - 0.4**2)
    kap, gam = s.bending_stiffness, s.surface_tension
    q = np.geomspace(s.q0 * 1.0001, s.q1, 17)
    g = s.diffusion_time(q, e_star)
    with mp.workdps(MP_DPS):
        kap_mp, gam_mp = mp.mpf(kap), mp.mpf(gam)
        pref = mp.mpf(e_star) ** 2 * mp.mpf(BOLTZMANN) * 370 / (32 * mp.pi * kap_mp)
        for gi, qi in zip(g, q):
            expect = pref * mp.log((gam_mp + kap_mp * mp.mpf(qi) ** 2) / (gam_mp + kap_mp * mp.mpf(s.q0) ** 2))
            assert_rel(gi, expect, RTOL_EXACT, f"G({qi:g})")
    # sqrt(G1) ~ 3e8 Pa for the seed scene
    assert 1e8 < math.sqrt(s.diffusion_time(s.q1, e_star)) < 1e9


def test_gravity_negligible_for_seed_but_present():
    plain = seed_scene()
    grav = CapillaryWaves(**CAPILLARY_CASES["seed_gravity"])
    for k in range(4):
        r = grav.moment(k) / plain.moment(k)
        assert 1 - 1e-3 < r < 1.0  # gravity lowers C slightly at the longest wavelengths
    # gravity with zero density is no gravity
    zero = CapillaryWaves(**{**CAPILLARY_CASES["seed"], "density": 0.0, "gravity": 9.81})
    assert zero.moment(0) == plain.moment(0)


# ----------------------------------------------------------------------------------------------
# self-affine
# ----------------------------------------------------------------------------------------------
HURST_VALUES = [0.0, 1e-9, 0.5 - 1e-9, 0.5, 0.5 + 1e-9, 0.8, 1 - 1e-9, 1.0]


@pytest.mark.parametrize("hurst", HURST_VALUES)
def test_self_affine_moments_match_mpmath(hurst):
    s = SelfAffine(hurst=hurst, q0=1e4, q1=1e9, q_r=3e5, h_rms=1e-9)
    check_moments_against_mp(s, mp_self_affine(s), limits=limit_sets(s)[:4] + [(3e5, 3e5 * 1.001)])


@pytest.mark.parametrize("hurst", [0.0, 0.5, 1.0])
def test_self_affine_without_rolloff(hurst):
    s = SelfAffine(hurst=hurst, q0=1e3, q1=1e8, C0=1e-30)
    assert s.q_r == s.q0
    np.testing.assert_array_equal(s.breakpoints(), [1e3, 1e8])
    check_moments_against_mp(s, mp_self_affine(s), limits=[(1e3, 1e8), (2e3, 5e5)])


@pytest.mark.parametrize("k,hurst", [(1, 0.0), (2, 0.5), (3, 1.0)])
@pytest.mark.parametrize("eps", [0.0, 1e-8, -1e-8, 1e-12])
def test_self_affine_logarithmic_case(k, hurst, eps):
    """At k - 2(1+H) = -1 the tail moment is C0 qr^(k+1) ln(b/a); nearby it is continuous."""
    h = min(max(hurst + eps, 0.0), 1.0)
    s = SelfAffine(hurst=h, q0=1e4, q1=1e9, C0=2.0e-30)
    a, b = 2e4, 5e8
    sigma = k - 1 - 2 * h
    with mp.workdps(MP_DPS):
        qr, L = mp.mpf(s.q_r), mp.log(mp.mpf(b) / mp.mpf(a))
        coef = mp.mpf(s.C0) * qr ** (k + 1) * (mp.mpf(a) / qr) ** sigma
        ref = coef * L if sigma == 0 else coef * mp.expm1(sigma * L) / sigma
    assert_rel(s.moment(k, a, b), ref, 1e-14, f"k={k} H={h}")


def test_self_affine_normalisations_round_trip():
    base = dict(hurst=0.7, q0=2e4, q1=4e9, q_r=1e6)
    s_h = SelfAffine(**base, h_rms=3e-9)
    assert_rel(s_h.h_rms(), 3e-9, 1e-14, "h_rms")
    s_g = SelfAffine(**base, slope_rms=0.4)
    assert_rel(s_g.slope_rms(), 0.4, 1e-14, "slope_rms")
    s_c = SelfAffine(**base, C0=s_h.C0)
    assert s_c.C0 == s_h.C0 and s_c.h_rms() == s_h.h_rms()
    s_back = SelfAffine(**base, h_rms=s_g.h_rms())
    assert_rel(s_back.C0, s_g.C0, 1e-14, "C0")
    assert_rel(SelfAffine(**base, slope_rms=s_c.slope_rms()).C0, s_c.C0, 1e-14, "C0")


def test_self_affine_closed_form_normalisation_no_rolloff():
    """h_rms² = 2π C0 q0² ∫ t^(-1-2H) dt = π C0 q0² (1 - ζ1^(-2H))/H."""
    H, q0, q1, c0 = 0.8, 1e4, 1e9, 1e-30
    s = SelfAffine(hurst=H, q0=q0, q1=q1, C0=c0)
    expect = math.pi * c0 * q0**2 * (1 - (q1 / q0) ** (-2 * H)) / H
    assert_rel(s.h_rms() ** 2, expect, RTOL_EXACT, "h_rms²")


def test_self_affine_psd_shape():
    s = SelfAffine(hurst=0.6, q0=1e4, q1=1e9, q_r=1e6, C0=1e-30)
    assert s.psd(5e3) == 0.0 and s.psd(2e9) == 0.0
    assert s.psd(1e4) == 1e-30 and s.psd(9.99e5) == 1e-30 and s.psd(1e6) == 1e-30
    assert_rel(s.psd(1e8), 1e-30 * 100.0 ** (-3.2), RTOL_EXACT, "tail")
    assert s.psd(1e9) > 0


# ----------------------------------------------------------------------------------------------
# tabulated spectra
# ----------------------------------------------------------------------------------------------
@pytest.mark.parametrize("hurst", [0.0, 0.5, 0.75, 1.0])
def test_table_from_self_affine_samples_is_exact(hurst):
    sa = SelfAffine(hurst=hurst, q0=1e4, q1=1e9, q_r=2e5, h_rms=1e-9)
    nodes = np.array([1e4, 5e4, 2e5, 1e6, 3.3e7, 1e9])
    tab = TabulatedPSD(nodes, sa.psd(nodes))
    qs = np.geomspace(1e4, 1e9, 101)
    np.testing.assert_allclose(tab.psd(qs), sa.psd(qs), rtol=1e-13)
    lo = np.array([1e4, 3e4, 2e5, 7e5, 1e8])
    hi = np.array([1e9, 2e5, 9e8, 7.0001e5, 2e8])
    for k in range(4):
        np.testing.assert_allclose(tab.moment(k, lo, hi), sa.moment(k, lo, hi), rtol=1e-13)
    np.testing.assert_array_equal(tab.breakpoints(), nodes)


def test_table_moments_match_mpmath():
    qt = np.array([1e3, 4e3, 1e4, 2.5e5, 1e6, 5e7])
    ct = np.array([1e-26, 3e-27, 1e-27, 2e-31, 1.5e-32, 1e-38])
    tab = TabulatedPSD(qt, ct)
    check_moments_against_mp(tab, mp_table(qt, ct))


def test_table_zero_band():
    qt = np.array([1e3, 1e4, 1e5, 1e6, 1e7])
    ct = np.array([1e-26, 1e-28, 0.0, 1e-33, 1e-36])
    tab = TabulatedPSD(qt, ct)
    assert tab.psd(5e4) == 0.0 and tab.psd(3e5) == 0.0 and tab.psd(1e5) == 0.0
    assert tab.psd(1e4) == 1e-28  # a node keeps its tabulated value
    assert tab.psd(3e6) > 0 and tab.psd(3e3) > 0
    assert tab.moment(3, 1e4, 1e6) == 0.0
    g = tab.diffusion_time(np.array([1e4, 5e4, 1e5, 9e5, 1e6]), 1e9)
    assert np.all(g == g[0])  # G is flat across the zero band
    check_moments_against_mp(tab, mp_table(qt, ct), limits=[(1e3, 1e7), (2e3, 4e6), (5e4, 5e5)])
    assert TabulatedPSD([1.0, 2.0], [0.0, 0.0]).h_rms() == 0.0


def test_table_restricted_band():
    qt = np.geomspace(1e3, 1e8, 11)
    ct = 1e-25 * (qt / 1e3) ** -3.1
    full = TabulatedPSD(qt, ct)
    part = TabulatedPSD(qt, ct, q0=2e3, q1=5e7)
    assert part.q0 == 2e3 and part.q1 == 5e7
    assert part.psd(1.5e3) == 0.0 and part.psd(6e7) == 0.0
    for k in range(4):
        assert_rel(part.moment(k), full.moment(k, 2e3, 5e7), 1e-14, f"k={k}")
    bp = part.breakpoints()
    assert bp[0] == 2e3 and bp[-1] == 5e7 and np.all(np.diff(bp) > 0)


def test_table_many_nodes_block_sums():
    """Block sums over full segments equal a plain per-segment sum, also far out in the tail."""
    cap = seed_scene()
    qt = np.geomspace(cap.q0, cap.q1, 1001)
    tab = TabulatedPSD(qt, cap.psd(qt))
    rng = np.random.default_rng(1)
    lo = np.exp(rng.uniform(np.log(cap.q0), np.log(cap.q1), 200))
    hi = lo * np.exp(rng.uniform(0, 4, 200))
    for k in range(4):
        got = tab.moment(k, lo, hi)
        # brute force for the first 20 intervals: one moment per overlapped segment, fsum
        for i, (a, b) in enumerate(zip(lo[:20], hi[:20])):
            parts = tab.moment(k, np.maximum(a, qt[:-1]), np.minimum(b, qt[1:]))
            assert_rel(got[i], math.fsum(parts), 1e-13, f"k={k} i={i}")
        # the tabulated capillary spectrum approximates the smooth one closely
        np.testing.assert_allclose(got, cap.moment(k, lo, hi), rtol=2e-4)


def test_from_line_scan_factor_and_convention():
    q = np.geomspace(1e4, 1e8, 9)
    c1 = 1e-20 * q**-2.0
    tab = TabulatedPSD.from_line_scan(q, c1, hurst=0.5)
    np.testing.assert_allclose(tab.psd(q), c1 / (2 * q), rtol=1e-15)
    tab0 = TabulatedPSD.from_line_scan(q, c1, hurst=0.0)
    np.testing.assert_allclose(tab0.psd(q), c1 / (math.pi * q), rtol=1e-15)
    # convention: C_1D(qx) = ∫ dqy C(sqrt(qx²+qy²)); for an isotropic power law C = K q^(-2(1+H))
    # this is K qx^(-1-2H) I(H), I(H) = ∫ (1+v²)^(-(1+H)) dv over the real line (v = qy/qx)
    qs = np.array([1e5, 1e6, 1e7])
    for H in (0.0, 0.3, 0.8, 1.0):
        with mp.workdps(MP_DPS):
            i_h = float(2 * mp.quad(lambda v: (1 + v**2) ** (-(1 + H)), [0, 1, mp.inf]))
        K = 1e-40
        c1d = K * qs ** (-1 - 2 * H) * i_h
        tab = TabulatedPSD.from_line_scan(qs, c1d, hurst=H)
        np.testing.assert_allclose(tab.psd(qs), K * qs ** (-2 * (1 + H)), rtol=1e-13)


# ----------------------------------------------------------------------------------------------
# the base-class interface, shared by all three models
# ----------------------------------------------------------------------------------------------
def _surfaces():
    sa = SelfAffine(hurst=0.8, q0=1e4, q1=1e9, q_r=1e5, h_rms=1e-9)
    nodes = np.geomspace(1e4, 1e9, 7)
    return [
        seed_scene(),
        CapillaryWaves(**CAPILLARY_CASES["strong_gravity"]),
        sa,
        TabulatedPSD(nodes, sa.psd(nodes) * (1 + 0.3 * np.sin(np.arange(7)))),
    ]


@pytest.mark.parametrize("s", _surfaces(), ids=repr)
def test_g1_rms_slope_identity(s):
    e_star = 3.45e9
    g1 = s.diffusion_time(s.q1, e_star)
    assert_rel(math.sqrt(g1), e_star * s.slope_rms() / (2 * math.sqrt(2)), RTOL_EXACT, "sqrt(G1)")
    assert s.diffusion_time(s.q0, e_star) == 0.0 and s.diffusion_time(0.5 * s.q0, e_star) == 0.0
    assert s.diffusion_time(10 * s.q1, e_star) == g1
    assert_rel(s.h_rms() ** 2, 2 * math.pi * s.moment(1), RTOL_EXACT, "h_rms")
    u = s.elastic_energy_full_contact(e_star)
    assert_rel(u, 0.5 * math.pi * e_star * s.moment(2), RTOL_EXACT, "U_el")


@pytest.mark.parametrize("s", _surfaces(), ids=repr)
def test_vectorisation_and_clipping(s):
    assert isinstance(s.psd(s.q0), float) and isinstance(s.moment(1), float)
    qs = np.geomspace(s.q0 / 2, 2 * s.q1, 12).reshape(3, 4)
    c = s.psd(qs)
    assert c.shape == (3, 4)
    assert np.all(c[qs < s.q0] == 0) and np.all(c[qs > s.q1] == 0) and np.all(c[(qs >= s.q0) & (qs <= s.q1)] > 0)
    # moments: broadcast, clip, zero where q_hi <= q_lo, agree with scalar calls
    lo = np.array([s.q0 / 10, s.q0 * 3, s.q1 / 2, s.q1])
    hi = np.array([[s.q1 * 10], [s.q0 * 30]])
    m = s.moment(2, lo, hi)
    assert m.shape == (2, 4)
    for i in range(2):
        for j in range(4):
            assert m[i, j] == s.moment(2, float(lo[j]), float(hi[i, 0]))
    assert m[1, 2] == 0.0 and m[0, 3] == 0.0
    assert m[0, 0] == s.moment(2)
    g = s.diffusion_time(qs, 1e9)
    assert g.shape == (3, 4) and isinstance(s.diffusion_time(s.q1, 1e9), float)
    bp = s.breakpoints()
    assert bp[0] == s.q0 and bp[-1] == s.q1 and np.all(np.diff(bp) > 0)


def test_reprs_show_parameters():
    assert "q_c=1700000000.0" in repr(seed_scene()) and "temperature=370.0" in repr(seed_scene())
    r = repr(SelfAffine(hurst=0.8, q0=1e4, q1=1e9, q_r=1e5, C0=1e-30))
    assert r.startswith("SelfAffine(") and "hurst=0.8" in r and "q_r=100000.0" in r and "C0=1e-30" in r
    assert "3 nodes" in repr(TabulatedPSD([1.0, 2.0, 3.0], [1.0, 1.0, 1.0]))


_PROPERTY_SURFACES = _surfaces()


@pytest.mark.filterwarnings("ignore:e_star = .* Pa is below:UserWarning")  # lam e_star < 1e5 Pa
@settings(max_examples=60, deadline=None, derandomize=True, database=None)
@given(
    which=st.integers(0, len(_PROPERTY_SURFACES) - 1),
    u=st.lists(st.floats(-0.2, 1.2), min_size=2, max_size=30),
    log_e=st.floats(5.0, 12.0),
    lam=st.floats(1e-3, 1e3),
)
def test_diffusion_time_monotone_and_scales_as_e_star_squared(which, u, log_e, lam):
    s = _PROPERTY_SURFACES[which]
    q = np.sort(s.q0 * (s.q1 / s.q0) ** np.asarray(u))
    e_star = 10.0**log_e
    g = s.diffusion_time(q, e_star)
    assert np.all(np.diff(g) >= -4 * np.spacing(g[1:]))  # non-decreasing up to rounding
    assert np.all(g >= 0)
    np.testing.assert_allclose(s.diffusion_time(q, lam * e_star), lam**2 * g, rtol=1e-13)


# ----------------------------------------------------------------------------------------------
# validation: one check per rule
# ----------------------------------------------------------------------------------------------
CW = dict(temperature=370.0, surface_tension=0.04, q_c=1.7e9, q0=Q0_SEED, q1=7e9)
SA = dict(hurst=0.8, q0=1e4, q1=1e9)


@pytest.mark.parametrize(
    "kwargs,match",
    [
        ({"temperature": -1.0}, r"temperature must be > 0 \[K\]; got temperature = -1.0"),
        ({"temperature": float("nan")}, r"temperature must be finite \[K\]; got temperature = nan"),
        ({"surface_tension": 0.0}, r"surface_tension must be > 0 \[J/m\^2\]"),
        ({"q_c": -1e9}, r"q_c must be > 0 \[1/m\]"),
        ({"q0": 0.0}, r"q0 must be > 0 \[1/m\]"),
        ({"q1": float("inf")}, r"q1 must be finite \[1/m\]; got q1 = inf"),
        ({"q0": 2.0, "q1": 1.0}, r"q1 must be > q0 \[1/m\]; got q1 = 1.0, q0 = 2.0"),
        ({"q0": 2.0, "q1": 2.0}, r"q1 must be > q0"),
        ({"density": -1.0}, r"density must be >= 0 \[kg/m\^3\]; got density = -1.0"),
        ({"gravity": -9.81}, r"gravity must be >= 0 \[m/s\^2\]"),
        ({"temperature": "hot"}, r"temperature must be a real number"),
        ({"temperature": [1.0, 2.0]}, r"temperature must have 0 dimension"),
    ],
)
def test_capillary_validation(kwargs, match):
    with pytest.raises(ValueError, match=match):
        CapillaryWaves(**{**CW, **kwargs})


@pytest.mark.parametrize(
    "kwargs,match",
    [
        ({}, r"exactly one of h_rms \[m\], slope_rms \[-\], C0 \[m\^4\] must be given; got none"),
        ({"h_rms": 1e-9, "C0": 1e-30}, r"exactly one of .*got h_rms = 1e-09, C0 = 1e-30"),
        ({"h_rms": 1e-9, "slope_rms": 0.1, "C0": 1e-30}, r"exactly one of"),
        ({"h_rms": -1e-9}, r"h_rms must be > 0 \[m\]"),
        ({"slope_rms": float("nan")}, r"slope_rms must be finite \[-\]"),
        ({"C0": 0.0}, r"C0 must be > 0 \[m\^4\]"),
        ({"hurst": 1.5, "C0": 1.0}, r"hurst must be in \[0, 1\] \[-\]; got hurst = 1.5"),
        ({"hurst": -1e-12, "C0": 1.0}, r"hurst must be in \[0, 1\]"),
        ({"hurst": float("nan"), "C0": 1.0}, r"hurst must be finite"),
        ({"q_r": 1e3, "C0": 1.0}, r"q_r must lie in \[q0, q1\] \[1/m\]; got q_r = 1000.0"),
        ({"q_r": 2e9, "C0": 1.0}, r"q_r must lie in \[q0, q1\]"),
        ({"q0": 1e9, "q1": 1e4, "C0": 1.0}, r"q1 must be > q0"),
    ],
)
def test_self_affine_validation(kwargs, match):
    with pytest.raises(ValueError, match=match):
        SelfAffine(**{**SA, **kwargs})


@pytest.mark.parametrize(
    "args,kwargs,match",
    [
        (([1.0, 3.0, 2.0], [1.0, 1.0, 1.0]), {}, r"q must be strictly increasing \[1/m\]; got q\[1\] = 3.0 >= q\[2\] = 2.0"),
        (([1.0, 1.0], [1.0, 1.0]), {}, r"q must be strictly increasing"),
        (([1.0, 2.0], [1.0, -1.0]), {}, r"C must be >= 0 \[m\^4\]; got C\[1\] = (np\.float64\()?-1\.0"),
        (([1.0, 2.0], [1.0, float("nan")]), {}, r"C must be finite \[m\^4\]; got C\[1\] = (np\.float64\()?nan"),
        (([0.0, 2.0], [1.0, 1.0]), {}, r"q must be > 0 \[1/m\]; got q\[0\] = (np\.float64\()?0\.0"),
        (([1.0, 2.0, 3.0], [1.0, 1.0]), {}, r"q and C must have the same length"),
        (([1.0], [1.0]), {}, r"q must hold at least 2 nodes"),
        (([[1.0, 2.0]], [[1.0, 1.0]]), {}, r"q must have 1 dimension"),
        (([1.0, 2.0], [1.0, 1.0]), {"q0": 0.5}, r"q0 must lie inside the table \[q\[0\], q\[-1\]\]"),
        (([1.0, 2.0], [1.0, 1.0]), {"q1": 2.5}, r"q1 must lie inside the table"),
        (([1.0, 2.0], [1.0, 1.0]), {"q0": 1.8, "q1": 1.2}, r"q1 must be > q0"),
    ],
)
def test_table_validation(args, kwargs, match):
    with pytest.raises(ValueError, match=match):
        TabulatedPSD(*args, **kwargs)


def test_from_line_scan_validation():
    with pytest.raises(ValueError, match=r"hurst must be in \[0, 1\]"):
        TabulatedPSD.from_line_scan([1.0, 2.0], [1.0, 1.0], hurst=2.0)
    with pytest.raises(ValueError, match=r"C1d must be >= 0 \[m\^3\]"):
        TabulatedPSD.from_line_scan([1.0, 2.0], [1.0, -1.0], hurst=0.5)


@pytest.mark.parametrize(
    "call,match",
    [
        (lambda s: s.diffusion_time(1e6, 0.0), r"e_star must be > 0 \[Pa\]; got e_star = 0.0"),
        (lambda s: s.diffusion_time(1e6, -1e9), r"e_star must be > 0 \[Pa\]"),
        (lambda s: s.diffusion_time(1e6, float("inf")), r"e_star must be finite \[Pa\]"),
        (lambda s: s.diffusion_time([1e6, float("nan")], 1e9), r"q must be finite \[1/m\]; got q\[1\] = (np\.float64\()?nan"),
        (lambda s: s.diffusion_time(-1.0, 1e9), r"q must be >= 0 \[1/m\]"),
        (lambda s: s.elastic_energy_full_contact(-1.0), r"e_star must be > 0"),
        (lambda s: s.psd(float("nan")), r"q must be finite"),
        (lambda s: s.moment(4), r"k must be one of 0, 1, 2, 3; got 4"),
        (lambda s: s.moment(1, float("nan")), r"q_lo must be finite \[1/m\]"),
        (lambda s: s.moment(1, None, [1e6, float("inf")]), r"q_hi must be finite \[1/m\]; got q_hi\[1\] = (np\.float64\()?inf"),
    ],
)
def test_method_validation(call, match):
    with pytest.raises(ValueError, match=match):
        call(seed_scene())
