"""Tests of persson_fast.analytic against mpmath at 40+ digits and against exact identities.

Errors are judged in units of the tolerance (scipy style): |x - ref| / (atol + rtol |ref|) < 1.
"""
from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import persson_fast as an

# --- tolerances and why ---------------------------------------------------------------------
RTOL = 1e-12  # the closed forms are evaluated to ~1e-15; 1e-12 leaves room for libm differences
RTOL_QUAD = 1e-11  # mpmath quadrature of a float64 integrand: the integrand itself is only ~1e-15
RTOL_SCALE = 1e-13  # scale invariance: both sides are float evaluations of the same formula
TINY = 1e-290  # below this a reference is in the subnormal range: judged absolutely
SETTINGS = settings(max_examples=40, deadline=None, derandomize=True, database=None)

mp.mp.dps = 40


def assert_close(actual, expected, rtol=RTOL, atol=0.0, what=""):
    actual = float(actual)
    expected = mp.mpf(expected)
    if abs(expected) < TINY:
        assert abs(actual) <= max(atol, 1e-280), (what, actual, expected)
        return
    err = abs(mp.mpf(actual) - expected) / (atol + rtol * abs(expected))
    assert err < 1, f"{what}: got {actual!r}, expected {mp.nstr(expected, 20)}, error {float(err):.3g} tolerances"


# --- mpmath references (inputs are the exact binary floats) ----------------------------------
def _phi_cdf(z):
    return mp.erfc(-z / mp.sqrt(2)) / 2


def ref_images_area(p, G):
    p, G = mp.mpf(p), mp.mpf(G)
    return mp.erf(p / (2 * mp.sqrt(G)))


def _extra_digits(x):
    """Digits lost by exp(-u) - exp(-v) with v - u = x: work at 50 + that precision."""
    x = abs(mp.mpf(x))
    return 50 + (int(-mp.log10(x)) + 5 if 0 < x < 1 else 0)


def ref_images_density(s, p, G):
    s, p, G = mp.mpf(s), mp.mpf(p), mp.mpf(G)
    if s < 0:
        return mp.mpf(0)
    with mp.workdps(_extra_digits(s * p / G)):
        two = mp.exp(-((s - p) ** 2) / (4 * G)) - mp.exp(-((s + p) ** 2) / (4 * G))
        return +(two / mp.sqrt(4 * mp.pi * G))


def ref_images_second(p, G):
    p, G = mp.mpf(p), mp.mpf(G)
    s = p / (2 * mp.sqrt(G))
    return (p * p + 2 * G) * mp.erf(s) + 2 * p * mp.sqrt(G / mp.pi) * mp.exp(-s * s)


def ref_linear_area(p, G, a, b):
    with mp.workdps(60):
        p, G, a, b = (mp.mpf(v) for v in (p, G, a, b))
        y0 = p + a
        if y0 == 0:
            return mp.mpf(0)
        r = mp.sqrt(2 * G)
        return +(_phi_cdf((y0 + b * G) / r) - mp.exp(-b * y0) * _phi_cdf((b * G - y0) / r))


def ref_linear_rate(p, G, a, b):
    with mp.workdps(60):
        p, G, a, b = (mp.mpf(v) for v in (p, G, a, b))
        y0 = p + a
        return +(y0 / mp.sqrt(4 * mp.pi * G**3) * mp.exp(-((y0 + b * G) ** 2) / (4 * G)))


def ref_linear_density(s, p, G, a, b):
    s, p, G, a, b = (mp.mpf(v) for v in (s, p, G, a, b))
    with mp.workdps(400):
        y0 = p + a
        y = s + a + b * G
    with mp.workdps(_extra_digits(y * y0 / G) + 20):
        if y <= 0:  # on or behind the absorbing wall P = 0 exactly; at y = 0 the two terms
            return mp.mpf(0)  # cancel completely and any finite precision leaves only noise
        v = 2 * G
        norm = lambda x: mp.exp(-x * x / (2 * v)) / mp.sqrt(2 * mp.pi * v)  # noqa: E731
        return +(norm(y - y0 - b * G) - mp.exp(-b * y0) * norm(y + y0 - b * G))


def ref_linear_load_formula(p, G, a, b):
    """The derived closed form L = y0 B - a A, in mpmath."""
    with mp.workdps(60):
        p, G, a, b = (mp.mpf(v) for v in (p, G, a, b))
        y0 = p + a
        r = mp.sqrt(2 * G)
        big_a = _phi_cdf((y0 + b * G) / r) - mp.exp(-b * y0) * _phi_cdf((b * G - y0) / r)
        big_b = _phi_cdf((y0 + b * G) / r) + mp.exp(-b * y0) * _phi_cdf((b * G - y0) / r)
        return +(y0 * big_b - a * big_a)


def ref_plastic_fourier(p, G, sy, dps=160):
    """Elastic and plastic fractions by the eigenfunction series, summed in mpmath."""
    if p == 0 or p == sy:  # exact: no elastic area; plastic 0 or 1
        return mp.mpf(0), mp.mpf(1 if p == sy and G > 0 else 0)
    with mp.workdps(dps):
        p, G, sy = mp.mpf(p), mp.mpf(G), mp.mpf(sy)
        x = mp.pi * p / sy
        gs = G / sy**2
        n_max = int(mp.sqrt((dps + 5) * mp.log(10) / (mp.pi**2 * gs))) + 2
        el = mp.mpf(0)
        pl = mp.mpf(0)
        for n in range(1, n_max + 1):
            e = mp.exp(-(n**2) * mp.pi**2 * gs)
            if n % 2:
                el += mp.sin(n * x) / n * e
            pl += (-1) ** (n + 1) * mp.sin(n * x) / n * e
        # sum (-1)^(n+1) sin(nx)/n (1 - e_n) with sum (-1)^(n+1) sin(nx)/n = x/2 (|x| < pi)
        return +(4 / mp.pi * el), +(p / sy - 2 / mp.pi * pl)


def ref_plastic_flux_quad(p, G, sy):
    """Plastic fraction as the time integral of the flux -dP/dsigma at sigma_Y, P built from
    free Gaussians by the method of images (independent of the Fourier derivation)."""
    with mp.workdps(30):
        p, G, sy = mp.mpf(p), mp.mpf(G), mp.mpf(sy)

        def flux(g):
            if g == 0:
                return mp.mpf(0)
            tot = mp.mpf(0)
            for k in range(-6, 7):
                for mu, sign in ((p + 2 * k * sy, 1), (-p + 2 * k * sy, -1)):
                    x = sy - mu
                    # -d/dsigma of N(sigma - mu; 2g) at sigma_Y = x/(2g) N(x; 2g)
                    tot += sign * x / (2 * g) * mp.exp(-x * x / (4 * g)) / mp.sqrt(4 * mp.pi * g)
            return tot

        return mp.quad(flux, [0, G / 4, G])


# --- strategies ---------------------------------------------------------------------------
log_uniform = lambda lo, hi: st.floats(lo, hi).map(lambda e: 10.0**e)  # noqa: E731
ratio_st = log_uniform(-8, 3)  # y0 / sqrt(G)
root_g_st = log_uniform(0, 9)  # sqrt(G) from 1 Pa to 1e9 Pa: G up to 1e18 Pa^2
drift_st = st.one_of(
    st.just(0.0),
    st.tuples(st.sampled_from([-1.0, 1.0]), log_uniform(-6, np.log10(50))).map(lambda t: t[0] * t[1]),
)  # b sqrt(G)

HARD_RATIOS = [1e-8, 1e-5, 1e-2, 0.3, 1.0, 3.0, 30.0, 1e3]
HARD_DRIFTS = [-50.0, -20.0, -3.0, -1e-3, 0.0, 1e-6, 1e-3, 0.5, 3.0, 20.0, 50.0]


# ============================================================================================
# method of images
# ============================================================================================
@SETTINGS
@given(ratio=ratio_st, root_g=root_g_st)
def test_images_area_vs_mpmath(ratio, root_g):
    G = root_g**2
    p = ratio * root_g
    assert_close(an.images_area(p, G), ref_images_area(p, G), what="images_area")


@pytest.mark.parametrize("ratio", [1e-12, 1e-8, 1e-3, 0.5, 2.0, 10.0, 1e3, 1e8])
@pytest.mark.parametrize("G", [1e-6, 1.0, 1e18])
def test_images_area_pinned(ratio, G):
    p = ratio * np.sqrt(G)
    assert_close(an.images_area(p, G), ref_images_area(p, G), what="images_area")


def test_images_area_limits_and_small_load():
    assert an.images_area(5.0, 0.0) == 1.0
    assert an.images_area(0.0, 0.0) == 0.0
    assert an.images_area(0.0, 3.0) == 0.0
    # small-load asymptote A -> sigma0 / sqrt(pi G), relative error ~ s^2 / 3
    G = 1e12
    for p in [1e-3, 1.0, 10.0]:
        assert_close(an.images_area(p, G), p / mp.sqrt(mp.pi * G), rtol=1e-10, what="small load")


def test_images_area_broadcast_and_types():
    out = an.images_area(np.array([1.0, 2.0, 3.0])[:, None], np.array([0.0, 1.0, 4.0, 9.0]))
    assert out.shape == (3, 4) and out.dtype == np.float64
    assert isinstance(an.images_area(1.0, 1.0), np.float64)
    assert np.all(np.diff(out, axis=0) >= 0)  # A rises with sigma0
    assert np.all(np.diff(out[:, 1:], axis=1) <= 0)  # A falls with G


@SETTINGS
@given(ratio=ratio_st, root_g=root_g_st, where=st.floats(0.0, 12.0))
def test_images_density_vs_mpmath(ratio, root_g, where):
    G = root_g**2
    p = ratio * root_g
    s = where * root_g  # sigma from 0 to 12 sqrt(G)
    assert_close(an.images_density(s, p, G), ref_images_density(s, p, G), what="images_density")


@pytest.mark.parametrize(
    "s,p,G",
    [(1e-3, 1e-4, 1e6), (1.0, 1e-9, 1.0), (1e9, 1e9, 1e16), (2e9, 1e9, 1e16), (5.0, 5.0, 1e-2), (3.0, 2.0, 0.5)],
)
def test_images_density_pinned(s, p, G):
    assert_close(an.images_density(s, p, G), ref_images_density(s, p, G), what="images_density")


def test_images_density_edges():
    assert an.images_density(-1.0, 2.0, 1.0) == 0.0
    assert an.images_density(0.0, 2.0, 1.0) == 0.0
    assert an.images_density(2.0, 2.0, 0.0) == np.inf  # the delta function at G = 0
    assert an.images_density(1.0, 2.0, 0.0) == 0.0
    assert an.images_density(1.0, 0.0, 1.0) == 0.0
    assert an.images_density(1.0, 2.0, 5e-324) == 0.0  # subnormal G: no overflow, no NaN


@pytest.mark.parametrize("p,G", [(1.0, 1.0), (1e-4, 1.0), (3e6, 1e12), (10.0, 1.0)])
def test_images_density_integrates_to_area_and_moments(p, G):
    rg = np.sqrt(G)
    f = lambda s: mp.mpf(float(an.images_density(float(s), p, G)))  # noqa: E731
    pts = [0, p, p + 45 * rg] if p < 45 * rg else [0, p - 45 * rg, p, p + 45 * rg]
    with mp.workdps(20):
        area = mp.quad(f, pts)
        load = mp.quad(lambda s: s * f(s), pts)
        second = mp.quad(lambda s: s * s * f(s), pts)
    a_, l_, s_ = an.images_moments(p, G)
    assert_close(a_, area, rtol=RTOL_QUAD, what="area")
    assert_close(l_, load, rtol=RTOL_QUAD, what="load")
    assert_close(s_, second, rtol=RTOL_QUAD, what="second")


@SETTINGS
@given(ratio=ratio_st, root_g=root_g_st)
def test_images_moments_vs_mpmath(ratio, root_g):
    G = root_g**2
    p = ratio * root_g
    area, load, second = an.images_moments(p, G)
    assert_close(area, ref_images_area(p, G), what="area")
    assert load == p  # load conservation, exactly
    assert_close(second, ref_images_second(p, G), what="second moment")


def test_images_moments_shapes_and_g0():
    area, load, second = an.images_moments(np.array([0.0, 1.0, 2.0]), np.array([[0.0], [1.0]]))
    assert area.shape == load.shape == second.shape == (2, 3)
    np.testing.assert_array_equal(area[0], [0.0, 1.0, 1.0])
    np.testing.assert_array_equal(second[0], [0.0, 1.0, 4.0])
    np.testing.assert_array_equal(load[1], [0.0, 1.0, 2.0])


# ============================================================================================
# linearly moving wall
# ============================================================================================
def _linear_case(ratio, drift, root_g, a_frac=0.0):
    G = root_g**2
    y0 = ratio * root_g
    a = a_frac * y0
    p = y0 - a
    b = drift / root_g
    return p, G, a, b


@settings(max_examples=80, deadline=None, derandomize=True, database=None)
@given(ratio=ratio_st, drift=drift_st, root_g=root_g_st, a_frac=st.sampled_from([0.0, -0.5, 0.25, 3.0]))
def test_linear_area_vs_mpmath(ratio, drift, root_g, a_frac):
    p, G, a, b = _linear_case(ratio, drift, root_g, a_frac)
    assert_close(an.linear_boundary_area(p, G, a, b), ref_linear_area(p, G, a, b), what="linear area")


@pytest.mark.parametrize("root_g", [1.0, 3.3e4, 1e9])
def test_linear_area_pinned_hard_cases(root_g):
    ps, Gs, bs, refs = [], [], [], []
    for ratio in HARD_RATIOS:
        for drift in HARD_DRIFTS:
            p, G, a, b = _linear_case(ratio, drift, root_g)
            ps.append(p), Gs.append(G), bs.append(b)
            refs.append(ref_linear_area(p, G, 0.0, b))
    got = an.linear_boundary_area(np.array(ps), np.array(Gs), 0.0, np.array(bs))
    for i, ref in enumerate(refs):
        assert_close(got[i], ref, what=f"A(y0={ps[i]}, G={Gs[i]}, b={bs[i]})")


def test_linear_area_limits():
    assert an.linear_boundary_area(2.0, 0.0, 1.0, -3.0) == 1.0
    assert an.linear_boundary_area(-1.0, 0.0, 1.0, 3.0) == 0.0  # start on the wall, G = 0+
    np.testing.assert_array_equal(an.linear_boundary_area(-1.0, np.array([1e-9, 1.0, 1e18]), 1.0, 0.3), 0.0)
    # G -> infinity: 1 - exp(-b y0) for a receding wall, 0 for an approaching one
    assert_close(an.linear_boundary_area(1.0, 1e30, 0.0, 1e-3), -mp.expm1(-1e-3), rtol=1e-13)
    assert an.linear_boundary_area(1.0, 1e30, 0.0, -1e-3) == 0.0


@SETTINGS
@given(ratio=ratio_st, drift=drift_st, root_g=root_g_st)
def test_linear_rate_vs_mpmath(ratio, drift, root_g):
    p, G, a, b = _linear_case(ratio, drift, root_g, 0.5)
    assert_close(an.linear_boundary_detachment_rate(p, G, a, b), ref_linear_rate(p, G, a, b), what="rate")


def test_linear_rate_limits():
    assert an.linear_boundary_detachment_rate(1.0, 0.0, 0.0, 1.0) == 0.0
    assert an.linear_boundary_detachment_rate(0.0, 1.0, 0.0, 1.0) == 0.0
    assert an.linear_boundary_detachment_rate(1e9, 5e-324, 0.0, 1.0) == 0.0


@SETTINGS
@given(ratio=ratio_st, drift=drift_st, root_g=root_g_st, where=st.floats(-1.0, 12.0))
def test_linear_density_vs_mpmath(ratio, drift, root_g, where):
    p, G, a, b = _linear_case(ratio, drift, root_g, 0.5)
    sigma_a = a + b * G
    s = -sigma_a + where * root_g + (where > 0) * p  # around the wall and the start
    assert_close(
        an.linear_boundary_density(s, p, G, a, b),
        ref_linear_density(s, p, G, a, b),
        atol=1e-300,
        what="linear density",
    )


def _density_quad(p, G, a, b, weight):
    """mpmath quad of weight(sigma) * P(sigma) over the contact, P from the implementation."""
    rg = np.sqrt(G)
    sigma_a = a + b * G
    lo = -sigma_a
    hi = max(lo, p + b * G) + 45 * rg  # the Gaussian is centred at sigma0 (the drift only moves the wall)
    hi = max(hi, p + 45 * rg)
    pts = sorted({lo, min(max(p, lo), hi), hi})
    f = lambda s: weight(s) * mp.mpf(float(an.linear_boundary_density(float(s), p, G, a, b)))  # noqa: E731
    with mp.workdps(20):
        return mp.quad(f, pts)


LINEAR_CASES = [  # (p, G, a, b): receding, approaching, adhesive, tensile start, physical scale
    (1.0, 1.0, 0.0, 0.7),
    (1.0, 1.0, 0.0, -0.7),
    (0.2, 1.0, 0.5, 2.0),
    (-0.3, 2.0, 0.5, -0.4),
    (3e6, 4e12, 1e6, 2e-7),
    (5e7, 1e16, -2e7, -3e-9),
]


@pytest.mark.parametrize("p,G,a,b", LINEAR_CASES)
def test_linear_density_integrates_to_area_and_load(p, G, a, b):
    area = _density_quad(p, G, a, b, lambda s: 1)
    assert_close(an.linear_boundary_area(p, G, a, b), area, rtol=RTOL_QUAD, what="area = int P")
    load = _density_quad(p, G, a, b, lambda s: s)
    scale = abs(p) + abs(a)
    got = an.linear_boundary_load(p, G, a, b)
    assert_close(got, load, rtol=RTOL_QUAD, atol=1e-12 * scale, what="load = int sigma P")


@pytest.mark.parametrize("p,G,a,b", LINEAR_CASES)
def test_linear_identities_in_G(p, G, a, b):
    """A(G) + int_0^G g = 1 and int sigma P = sigma0 + int_0^G sigma_a g dG'."""
    rate = lambda g: mp.mpf(float(an.linear_boundary_detachment_rate(p, float(g), a, b)))  # noqa: E731
    pts = [0, G * 1e-3, G * 0.05, G * 0.3, G]
    with mp.workdps(20):
        detached = mp.quad(rate, pts)
        bookkept = mp.quad(lambda g: (a + b * g) * rate(g), pts)
    total = mp.mpf(float(an.linear_boundary_area(p, G, a, b))) + detached
    assert abs(total - 1) < 1e-12
    scale = abs(p) + abs(a) + abs(b) * G
    got = an.linear_boundary_load(p, G, a, b)
    assert_close(got, p + bookkept, rtol=RTOL_QUAD, atol=1e-12 * scale, what="load")


@SETTINGS
@given(ratio=ratio_st, drift=drift_st, root_g=root_g_st, a_frac=st.sampled_from([0.0, -0.5, 0.25, 3.0]))
def test_linear_load_vs_mpmath(ratio, drift, root_g, a_frac):
    p, G, a, b = _linear_case(ratio, drift, root_g, a_frac)
    ref = ref_linear_load_formula(p, G, a, b)
    # tensile start with a > 0: L may cross zero, so its accuracy is absolute on the scale of the terms
    atol = 1e-13 * abs(a) if (p < 0 < a) else 0.0
    assert_close(an.linear_boundary_load(p, G, a, b), ref, atol=atol, what="load")


def test_linear_load_limits():
    assert an.linear_boundary_load(2.0, 0.0, 1.0, 0.5) == 2.0
    assert an.linear_boundary_load(-1.0, 0.0, 1.0, 0.5) == 0.0
    assert an.linear_boundary_load(-1.0, 3.0, 1.0, 0.5) == 0.0


@pytest.mark.parametrize("ratio", [1e-8, 1e-3, 0.4, 2.0, 30.0])
@pytest.mark.parametrize("root_g", [1.0, 1e7])
def test_linear_b0_reduces_to_images(ratio, root_g):
    G = root_g**2
    p = ratio * root_g
    np.testing.assert_allclose(an.linear_boundary_area(p, G, 0.0, 0.0), an.images_area(p, G), rtol=1e-14)
    s = np.linspace(-root_g, p + 8 * root_g, 41)
    np.testing.assert_allclose(
        an.linear_boundary_density(s, p, G, 0.0, 0.0), an.images_density(s, p, G), rtol=1e-14, atol=0
    )
    np.testing.assert_allclose(an.linear_boundary_load(p, G, 0.0, 0.0), p, rtol=1e-14)


@SETTINGS
@given(
    ratio=ratio_st,
    drift=drift_st,
    lam=st.sampled_from([1e-3, 0.37, 8.0, 1e5, 2.0**20]),
    a_frac=st.sampled_from([0.0, -0.5, 0.25]),
)
def test_linear_scale_invariance(ratio, drift, lam, a_frac):
    p, G, a, b = _linear_case(ratio, drift, 1.0, a_frac)
    s = p + 0.3
    base = (
        an.linear_boundary_area(p, G, a, b),
        an.linear_boundary_detachment_rate(p, G, a, b),
        an.linear_boundary_density(s, p, G, a, b),
        an.linear_boundary_load(p, G, a, b),
    )
    scaled = (
        an.linear_boundary_area(lam * p, lam**2 * G, lam * a, b / lam),
        an.linear_boundary_detachment_rate(lam * p, lam**2 * G, lam * a, b / lam) * lam**2,
        an.linear_boundary_density(lam * s, lam * p, lam**2 * G, lam * a, b / lam) * lam,
        an.linear_boundary_load(lam * p, lam**2 * G, lam * a, b / lam) / lam,
    )
    for x, y in zip(base, scaled):
        np.testing.assert_allclose(y, x, rtol=RTOL_SCALE, atol=1e-300)


def test_linear_small_load_asymptote():
    G = 1e14
    for y0 in [1e-2, 1.0]:
        # A -> y0 / sqrt(pi G) as y0 / sqrt(G) -> 0, for b = 0 and for a moving wall alike
        # (with the drift: A -> y0 [exp(-c^2)/sqrt(pi) + c erfc(-c)] / sqrt(G), c = b sqrt(G)/2)
        rtol = 10 * y0 / np.sqrt(G)  # first correction is O(y0 / sqrt(G))
        assert_close(an.linear_boundary_area(y0, G, 0.0, 0.0), y0 / mp.sqrt(mp.pi * G), rtol=rtol, what="b=0")
        c = mp.mpf(0.5)
        expected = y0 / mp.sqrt(G) * (mp.exp(-c * c) / mp.sqrt(mp.pi) + c * mp.erfc(-c))
        assert_close(an.linear_boundary_area(y0, G, 0.0, 1.0 / np.sqrt(G)), expected, rtol=rtol, what="b>0")


def test_linear_never_nan_at_extremes():
    p = np.array([0.0, 1e-300, 1.0, 1e9, 1e300])[:, None, None]
    G = np.array([0.0, 5e-324, 1e-300, 1.0, 1e18, 1e300])[None, :, None]
    b = np.array([-1e300, -1e3, -1e-12, 0.0, 1e-12, 1e3, 1e300])[None, None, :]
    for fn in (an.linear_boundary_area, an.linear_boundary_load):
        out = fn(p, G, 0.0, b)
        assert out.shape == (5, 6, 7)
        assert np.all(np.isfinite(out)), fn.__name__
    # the rate may exceed the float range (g ~ y0 G^-3/2 at G = 1e-300): inf, never NaN
    rate = an.linear_boundary_detachment_rate(p, G, 0.0, b)
    assert not np.any(np.isnan(rate)) and np.all(rate >= 0)
    area = an.linear_boundary_area(p, G, 0.0, b)
    assert np.all((area >= 0) & (area <= 1))
    dens = an.linear_boundary_density(1.0, p, G, 0.0, b)
    assert not np.any(np.isnan(dens))


# ============================================================================================
# elastic-plastic strip
# ============================================================================================
@settings(max_examples=30, deadline=None, derandomize=True, database=None)
@given(s=st.floats(1e-6, 1.0), gs=log_uniform(-3, 1.5), sy=log_uniform(6, 10))
def test_plastic_vs_mpmath_series(s, gs, sy):
    p = s * sy
    G = gs * sy * sy
    el_ref, pl_ref = ref_plastic_fourier(p, G, sy)
    el, pl = an.plastic_area(p, G, sy)
    assert_close(el, el_ref, atol=1e-300, what="elastic")
    assert_close(pl, pl_ref, atol=1e-300, what="plastic")


@pytest.mark.parametrize("s", [1e-7, 0.01, 0.3, 0.5, 0.9, 1 - 1e-9, 1.0])
@pytest.mark.parametrize("gs", [1e-3, 0.05, 0.0999, 0.1, 0.3, 3.0])
def test_plastic_pinned(s, gs):
    sy = 2.0e9
    p, G = s * sy, gs * sy * sy
    el_ref, pl_ref = ref_plastic_fourier(p, G, sy)
    el, pl = an.plastic_area(p, G, sy)
    assert_close(el, el_ref, atol=1e-300, what="elastic")
    assert_close(pl, pl_ref, atol=1e-300, what="plastic")
    # forcing the Fourier series with many terms agrees with the automatic choice
    el_f, pl_f = an.plastic_area(p, G, sy, n_terms=400)
    assert_close(el_f, el_ref, rtol=1e-10, atol=1e-15, what="elastic, n_terms=400")
    assert_close(pl_f, pl_ref, rtol=1e-10, atol=1e-15, what="plastic, n_terms=400")


@pytest.mark.parametrize("s,gs", [(0.4, 0.02), (0.9, 0.2), (0.05, 0.5), (0.999, 0.03)])
def test_plastic_flux_series_vs_image_flux_quadrature(s, gs):
    sy = 1.0e8
    p, G = s * sy, gs * sy * sy
    _, pl = an.plastic_area(p, G, sy)
    assert_close(pl, ref_plastic_flux_quad(p, G, sy), rtol=1e-11, what="plastic = int flux")


@SETTINGS
@given(s=st.floats(0.0, 1.0), gs=log_uniform(-6, 2))
def test_plastic_bounds_and_conservation(s, gs):
    sy = 3.0e8
    p, G = s * sy, gs * sy * sy
    el, pl = an.plastic_area(p, G, sy)
    _, pl_lower = an.plastic_area(sy - p, G, sy)  # flux through sigma = 0, by reflection
    assert 0.0 <= el <= 1.0 and 0.0 <= pl <= 1.0
    assert el + pl <= 1.0 + 1e-15
    assert abs(el + pl + pl_lower - 1.0) < 1e-13


def test_plastic_large_yield_stress_reduces_to_images():
    p = np.array([1e-3, 1.0, 5.0, 40.0])
    G = 4.0
    el, pl = an.plastic_area(p, G, 1e7)
    np.testing.assert_allclose(el, an.images_area(p, G), rtol=1e-14)
    assert np.all(pl < 1e-300)


def test_plastic_limits():
    el, pl = an.plastic_area(np.array([0.0, 1.0, 2.0]), 0.0, 2.0)
    np.testing.assert_array_equal(el, [0.0, 1.0, 0.0])
    np.testing.assert_array_equal(pl, [0.0, 0.0, 1.0])
    el, pl = an.plastic_area(np.array([0.0, 2.0]), 1.0, 2.0)
    np.testing.assert_array_equal(el, [0.0, 0.0])
    np.testing.assert_array_equal(pl, [0.0, 1.0])
    # long times: everything has left; plastic -> sigma0 / sigma_Y (gambler's ruin)
    el, pl = an.plastic_area(0.3, 100.0, 1.0)
    assert el == 0.0 and abs(pl - 0.3) < 1e-15
    assert isinstance(el, np.float64)


# ============================================================================================
# surface-level convenience
# ============================================================================================
class LogSurface:
    """G(q) = K E*^2 ln(q / q0): the shape of the capillary-wave diffusion time."""

    q0 = 2 * np.pi / 1e-4
    q1 = 7e9

    def diffusion_time(self, q, e_star):
        return 1e-4 * e_star**2 * np.log(np.asarray(q) / self.q0)


def test_contact_area_no_adhesion_default_grid():
    surf = LogSurface()
    pressure = np.array([0.0, 1e5, 1e7, 1e8])
    zeta, area = an.contact_area_no_adhesion(surf, pressure, 3.2e9)
    assert zeta.shape == (64,) and area.shape == (4, 64)
    assert zeta[0] == 1.0 and zeta[-1] == surf.q1 / surf.q0
    assert np.all(np.diff(zeta) > 0)
    G = surf.diffusion_time(zeta * surf.q0, 3.2e9)
    np.testing.assert_array_equal(area, an.images_area(pressure[:, None], G[None, :]))
    np.testing.assert_array_equal(area[:, 0], [0.0, 1.0, 1.0, 1.0])
    assert np.all(np.diff(area[:, 1:], axis=1) <= 0)


def test_contact_area_no_adhesion_custom_zeta_and_scalar_pressure():
    surf = LogSurface()
    zeta, area = an.contact_area_no_adhesion(surf, 1e6, 3.2e9, zeta=[1.0, 10.0, 1e3])
    assert area.shape == (1, 3)
    G = surf.diffusion_time(zeta * surf.q0, 3.2e9)
    for j in range(3):
        assert_close(area[0, j], ref_images_area(1e6, G[j]) if G[j] > 0 else 1.0, what="area")


def test_contact_area_no_adhesion_seed_surface():
    import persson_fast as pf

    surf = pf.seed_scene()
    e_star = 2.9e9 / (1 - 0.35**2)
    zeta, area = an.contact_area_no_adhesion(surf, [1e6, 1e8], e_star)
    assert area.shape == (2, 64) and zeta[-1] == surf.q1 / surf.q0
    G1 = surf.diffusion_time(surf.q1, e_star)
    assert_close(area[1, -1], ref_images_area(1e8, G1), what="A(zeta1)")
    assert np.all((area >= 0) & (area <= 1)) and area[0, -1] < area[1, -1]


# ============================================================================================
# validation: one test per rule
# ============================================================================================
def test_negative_pressure_without_adhesion():
    with pytest.raises(ValueError, match=r"pressure must be >= 0 \[Pa\] without adhesion.*no contact.*-1\.0"):
        an.images_area(-1.0, 1.0)


def test_nonfinite_pressure():
    with pytest.raises(ValueError, match=r"pressure must be finite \[Pa\]; got pressure\[1\] = nan"):
        an.images_area([1.0, np.nan], 1.0)


def test_negative_G():
    with pytest.raises(ValueError, match=r"G must be >= 0 \[Pa\^2\]; got G = -1\.0"):
        an.images_density(1.0, 1.0, -1.0)


def test_nonfinite_G():
    with pytest.raises(ValueError, match=r"G must be finite \[Pa\^2\]; got G\[0\] = inf"):
        an.linear_boundary_area(1.0, [np.inf], 0.0, 0.0)


def test_nonfinite_sigma():
    with pytest.raises(ValueError, match=r"sigma must be finite \[Pa\]"):
        an.linear_boundary_density(np.nan, 1.0, 1.0, 0.0, 0.0)


def test_non_numeric_argument():
    with pytest.raises(ValueError, match=r"pressure must be a real number"):
        an.images_moments("abc", 1.0)


def test_start_below_wall():
    with pytest.raises(ValueError, match=r"pressure must be >= -a \[Pa\].*pressure = -2\.0 with a = 1\.0"):
        an.linear_boundary_load(-2.0, 1.0, 1.0, 0.0)


def test_nonfinite_wall_parameters():
    with pytest.raises(ValueError, match=r"a must be finite \[Pa\]"):
        an.linear_boundary_area(1.0, 1.0, np.nan, 0.0)
    with pytest.raises(ValueError, match=r"b must be finite \[1/Pa\]"):
        an.linear_boundary_detachment_rate(1.0, 1.0, 0.0, np.inf)


def test_yield_stress_positive():
    with pytest.raises(ValueError, match=r"yield_stress must be > 0 \[Pa\]; got yield_stress = 0\.0"):
        an.plastic_area(0.0, 1.0, 0.0)


def test_pressure_above_yield_stress():
    with pytest.raises(ValueError, match=r"pressure must be <= yield_stress \[Pa\].*pressure = 3\.0"):
        an.plastic_area([1.0, 3.0], 1.0, 2.0)


def test_plastic_negative_pressure():
    with pytest.raises(ValueError, match=r"pressure must be >= 0 \[Pa\]"):
        an.plastic_area(-1.0, 1.0, 2.0)


@pytest.mark.parametrize("bad", [0, -3, 2.5, True, "7"])
def test_n_terms(bad):
    with pytest.raises(ValueError, match=r"n_terms must be None or an integer >= 1"):
        an.plastic_area(1.0, 1.0, 2.0, n_terms=bad)


def test_e_star_positive():
    with pytest.raises(ValueError, match=r"e_star must be > 0 \[Pa\]; got e_star = -1\.0"):
        an.contact_area_no_adhesion(LogSurface(), 1e6, -1.0)


def test_zeta_range():
    with pytest.raises(ValueError, match=r"zeta must lie in \[1, q1/q0\].*zeta\[1\] = 0\.5"):
        an.contact_area_no_adhesion(LogSurface(), 1e6, 1e9, zeta=[1.0, 0.5])


def test_pressure_dimension():
    with pytest.raises(ValueError, match=r"pressure must have 0 or 1 dimension"):
        an.contact_area_no_adhesion(LogSurface(), np.ones((2, 2)), 1e9)


def test_surface_interface():
    with pytest.raises(ValueError, match=r"surface must have attributes q0, q1.*'diffusion_time'"):
        an.contact_area_no_adhesion(object.__new__(type("S", (), {"q0": 1.0, "q1": 2.0})), 1e6, 1e9)


def test_surface_cutoffs():
    bad = LogSurface()
    bad.q1 = bad.q0 / 2
    with pytest.raises(ValueError, match=r"surface.q1 must be > surface.q0"):
        an.contact_area_no_adhesion(bad, 1e6, 1e9)


def test_surface_diffusion_time_values():
    class Broken(LogSurface):
        def diffusion_time(self, q, e_star):
            return np.full(np.shape(q), np.nan)

    with pytest.raises(ValueError, match=r"surface.diffusion_time must return finite values >= 0"):
        an.contact_area_no_adhesion(Broken(), 1e6, 1e9)
