"""The interfacial gap distribution (issue 36): weight 1, mean u(p), an independent twin,
honest error estimates, bad input."""
import numpy as np
import pytest

import persson_fast as pf
from persson_fast._reference import gaps as ref
from persson_fast._kernels.status import RTOL_NOT_MET
from tolerances import GAP_MEAN, GAP_TWIN

H_RMS = 6e-6
#: the scene of Xu, Zhu, Xiao & Zhou (Tribol. Lett. 2024): H = 0.8, two decades, no roll-off
XU = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e6, h_rms=H_RMS)
SCENES = {
    "xu": (XU, 1e9, 1e9 * np.array([1e-4, 1e-3, 1e-2, 0.04, 0.113, 0.3])),
    "seed": (pf.seed_scene(), pf.seed_e_star(), np.array([1e5, 1e6, 1e7, 5e7])),
    "roll-off": (pf.SelfAffine(hurst=0.7, q0=1e4, q_r=1e5, q1=1e9, slope_rms=0.3), 1e9,
                 np.array([1e6, 1e7, 3e7])),
}
#: a measured-like spectrum (log-log table with wiggles), pressures as fractions of sqrt(G1)
_TAB = pf.TabulatedPSD(np.geomspace(1e4, 1e7, 40),
                       1e-30 * (np.geomspace(1e4, 1e7, 40) / 1e4) ** -3.4
                       * (1.0 + 0.3 * np.sin(np.linspace(0.0, 9.0, 40))))
SCENES["tabulated"] = (_TAB, 1e9, np.array([0.01, 0.1, 1.0])
                       * np.sqrt(_TAB.diffusion_time(_TAB.q1, 1e9)))


def trapz(y, x):
    return np.sum(0.5 * (y[..., 1:] + y[..., :-1]) * np.diff(x), axis=-1)


@pytest.fixture(scope="module", params=sorted(SCENES))
def scene(request):
    return request.param, SCENES[request.param]


@pytest.mark.parametrize("energy_correction", [None, 0.45])
def test_total_weight_is_one_and_mean_is_the_separation(scene, energy_correction):
    """trapz(density, gaps) + contact_fraction == 1 within rtol (the default grid is built for
    it; measured below 2e-5), the mean equals solve_separation's u(p) (two quadratures of one
    integral), the trapezoid first moment matches the mean within rtol, and the contact
    fraction is the original theory's area."""
    name, (surface, e, p) = scene
    rtol = 1e-3
    g = pf.gap_distribution(surface, p, e_star=e, energy_correction=energy_correction,
                            rtol=rtol)
    assert g.success and np.all(g.status == 0), g.message
    weight = trapz(g.density, g.gaps) + g.contact_fraction
    np.testing.assert_allclose(weight, 1.0, rtol=0, atol=rtol)
    np.testing.assert_allclose(g.weight_error, np.abs(weight - 1.0), rtol=1e-9, atol=1e-15)
    sep = pf.solve_separation(surface, p, e_star=e, energy_correction=energy_correction)
    np.testing.assert_allclose(g.mean, sep.separation, rtol=GAP_MEAN)
    np.testing.assert_array_equal(g.separation, sep.separation)
    first = trapz(g.gaps * g.density, g.gaps)
    np.testing.assert_allclose(first, g.mean, rtol=2 * rtol)
    area = pf.solve_contact(surface, p, e_star=e).area
    np.testing.assert_allclose(g.contact_fraction, area, rtol=1e-14, atol=1e-300)
    assert np.all(g.density >= 0) and g.gaps[0] == 0.0 and np.all(np.diff(g.gaps) > 0)
    assert np.all(g.error_estimate <= rtol)


def test_density_against_the_twin():
    """At two gaps of the Xu scene at p = 0.04 E*, the density against the slow twin
    (quad in zeta of finite differences of quad-in-q gap volumes; no shared code)."""
    surface, e = XU, 1e9
    p = 0.04e9
    u = np.array([0.0, 0.05, 0.3, 2.0]) * H_RMS
    g = pf.gap_distribution(surface, p, e_star=e, gaps=u, rtol=1e-5)
    for k in (1, 2):
        twin = ref.density(surface, e, p, u[k])
        assert abs(g.density[0, k] - twin) <= GAP_TWIN * twin, (u[k], g.density[0, k], twin)
    assert g.contact_fraction[0] == pytest.approx(ref.contact_fraction(surface, e, p),
                                                  rel=1e-14)


@pytest.mark.slow
@pytest.mark.parametrize("shape", ["truncated", "folded"])
def test_density_against_the_twin_more(shape):
    surface, e = pf.seed_scene(), pf.seed_e_star()
    p = 1e7
    g0 = pf.gap_distribution(surface, p, e_star=e, shape=shape, rtol=1e-5)
    u = np.array([0.1, 0.5, 1.5]) * g0.mean[0]
    g = pf.gap_distribution(surface, p, e_star=e, gaps=u, shape=shape, rtol=1e-5)
    for k in range(u.size):
        twin = ref.density(surface, e, p, u[k], shape=shape)
        assert abs(g.density[0, k] - twin) <= GAP_TWIN * max(twin, 0.01 * g0.density.max())


def test_components_against_the_twin():
    """The mean gap of the area leaving contact at zeta, u1 = dB/dA, of the package's cells
    (cell width 1/64 in ln G) against centred differences of the twin's gap volumes (B by
    quad in q): the cell means, interpolated in the width h (monotone in zeta) to the twin's
    h(zeta), agree to 1e-4."""
    from persson_fast.separation import gaps as gp
    from persson_fast.separation.elastic import kfun_table

    surface, e, p = XU, 1e9, 0.04e9
    inverse = gp._Inverse(surface, e)
    cells = gp._Cells(surface, e, inverse, np.log(p * p / 4.0 / 12.0**2), 1.0 / 64.0)
    mix = gp._mixture(p, 1.0, cells, gp.TRUNCATED, kfun_table(1.0))
    order = np.argsort(mix.width)
    for zeta in (1.5, 5.0, 30.0):
        w, u1, h = ref.components(surface, e, p, zeta)
        mean = np.interp(np.log(h), np.log(mix.width[order]), mix.means[order])
        assert abs(mean - u1) <= 1e-4 * u1, (zeta, mean, u1)


def test_folded_shape_keeps_weight_and_overshoots_the_mean():
    """Almqvist et al.'s mirrored Gaussians: weight 1 as well, but the mean exceeds u(p), by
    more where the area leaves contact at gaps below the finer roughness (large p)."""
    surface, e, p = SCENES["xu"]
    g = pf.gap_distribution(surface, p, e_star=e, shape="folded", rtol=1e-3)
    np.testing.assert_allclose(trapz(g.density, g.gaps) + g.contact_fraction, 1.0, atol=1e-3)
    excess = g.mean / g.separation - 1.0
    assert np.all(excess > 0) and np.all(np.diff(excess) > 0), excess
    np.testing.assert_allclose(trapz(g.gaps * g.density, g.gaps), g.mean, rtol=2e-3)


def test_estimate_is_honest():
    """The density's estimated error (half the change from cells twice as wide) is 1-2x its
    actual error against a run at 100x tighter rtol, on three scenes."""
    for name in ("xu", "seed", "roll-off"):
        surface, e, p = SCENES[name]
        fine = pf.gap_distribution(surface, p, e_star=e, rtol=1e-5)
        g = pf.gap_distribution(surface, p, e_star=e, gaps=fine.gaps, rtol=1e-3)
        actual = np.max(np.abs(g.density - fine.density), axis=1) / fine.density.max(axis=1)
        assert np.all(actual <= g.error_estimate) and np.all(g.error_estimate <= 4 * actual), (
            name, actual, g.error_estimate)


def test_limits():
    """Small load: the contact fraction tends to p/sqrt(pi G1) and the mean to u(p), far
    above h_rms; large load: nearly all in contact, the mean a tiny fraction of h_rms."""
    surface, e = XU, 1e9
    g1 = float(surface.diffusion_time(surface.q1, e))
    g = pf.gap_distribution(surface, [1e3, 0.5e9], e_star=e)
    assert g.contact_fraction[0] == pytest.approx(1e3 / np.sqrt(np.pi * g1), rel=1e-6)
    assert g.mean[0] > 5 * H_RMS and g.mean[1] < 1e-5 * H_RMS
    assert g.contact_fraction[1] > 0.999


def test_given_gaps_that_do_not_resolve_are_flagged():
    surface, e, p = SCENES["xu"]
    g = pf.gap_distribution(surface, p[2], e_star=e, gaps=np.linspace(0, 10 * H_RMS, 6))
    assert g.status[0] == RTOL_NOT_MET and not g.success
    assert "do not resolve" in g.message and g.weight_error[0] > 1e-3


def test_scene_and_repr():
    scene = pf.Scene(XU, e_star=1e9)
    a = pf.gap_distribution(scene, 1e7)
    b = pf.gap_distribution(XU, 1e7, e_star=1e9)
    np.testing.assert_array_equal(a.density, b.density)
    assert "GapDistribution" in repr(a)


@pytest.mark.parametrize("kwargs, match", [
    ({"pressure": 0.0}, r"pressure must be > 0 for a gap distribution \[Pa\].*pressure\[0\] = 0.0"),
    ({"pressure": [1e6, -1.0]}, r"pressure\[1\] = -1.0"),
    ({"pressure": np.nan}, r"pressure must be finite \[Pa\]"),
    ({"gaps": [0.0, 2e-6, 1e-6]}, r"gaps must hold at least 2 values >= 0, strictly "
                                  r"increasing \[m\]"),
    ({"gaps": [-1e-9, 1e-6]}, r"gaps must hold"),
    ({"gaps": [0.0]}, r"gaps must hold"),
    ({"shape": "mirror"}, r"shape must be one of 'truncated', 'folded' \[-\]; got shape = 'mirror'"),
    ({"rtol": 0.0}, r"rtol"),
    ({"energy_correction": 2.0}, r"energy_correction"),
])
def test_bad_input(kwargs, match):
    args = {"pressure": 1e6, **kwargs}
    p = args.pop("pressure")
    with pytest.raises(ValueError, match=match):
        pf.gap_distribution(XU, p, e_star=1e9, **args)


def test_adhesion_and_yield_are_refused():
    with pytest.raises(ValueError, match="without adhesion only"):
        pf.gap_distribution(pf.Scene(XU, e_star=1e9, work_of_adhesion=0.05), 1e6)
    with pytest.raises(ValueError, match="does not take a yield wall"):
        pf.gap_distribution(pf.Scene(XU, e_star=1e9, hardness=1e8), 1e6)
    with pytest.raises(ValueError, match="e_star"):
        pf.gap_distribution(XU, 1e6)


def test_density_at_and_cumulative():
    """density_at gives the density at other gaps (bitwise where they coincide); cumulative is
    the exact probability of a gap <= u, the contact included: the contact fraction at 0,
    1 far out, and its differences match the trapezoid masses of a fine grid."""
    surface, e, p = SCENES["seed"]
    g = pf.gap_distribution(surface, p, e_star=e)
    np.testing.assert_array_equal(g.density_at(g.gaps), g.density)
    c = g.cumulative(np.array([0.0, 1.0]))
    np.testing.assert_array_equal(c[:, 0], g.contact_fraction)
    np.testing.assert_allclose(c[:, 1], 1.0, rtol=0, atol=1e-15)
    mass = np.diff(g.cumulative(g.gaps), axis=1)
    trap = 0.5 * (g.density[:, 1:] + g.density[:, :-1]) * np.diff(g.gaps)
    assert np.max(np.abs(np.sum(trap - mass, axis=1))) <= 1e-3
    with pytest.raises(ValueError, match="gaps must hold at least 1 value"):
        g.cumulative([-1.0])


def test_scan_gaps():
    """scan(gaps=True): every scene's distribution on the union of their default grids, the
    numbers of gap_distribution (density_at on that axis); NaN where p <= 0; a given axis
    taken as it is; scenes with adhesion refused before solving."""
    pytest.importorskip("xarray")
    params = {"hurst": [0.7, 0.8], "q0": 1e4, "q1": 1e6, "h_rms": H_RMS}
    p = np.array([0.0, 1e6, 1e7])
    ds = pf.scan(pf.SelfAffine, params, p, e_star=1e9, gaps=True, progress=False)
    assert ds.gap_density.dims == ("hurst", "pressure", "gap") and bool(ds.success.all())
    for hurst in (0.7, 0.8):
        g = pf.gap_distribution(pf.SelfAffine(hurst=hurst, q0=1e4, q1=1e6, h_rms=H_RMS),
                                p[1:], e_star=1e9)
        got = ds.gap_density.sel(hurst=hurst).values
        assert np.all(np.isnan(got[0]))
        np.testing.assert_array_equal(got[1:], g.density_at(ds.gap.values))
        np.testing.assert_array_equal(ds.mean_gap.sel(hurst=hurst).values[1:], g.mean)
        assert np.all(ds.gap_weight_error.sel(hurst=hurst).values[1:] <= 1e-3)
    axis = np.linspace(0.0, 20 * H_RMS, 4001)
    ds2 = pf.scan(pf.SelfAffine, params, p, e_star=1e9, gaps=axis, progress=False)
    np.testing.assert_array_equal(ds2.gap.values, axis)
    with pytest.raises(ValueError, match="gaps needs scenes without adhesion"):
        pf.scan(pf.SelfAffine, params, p, e_star=1e9, work_of_adhesion=0.05, gaps=True,
                progress=False)
    with pytest.raises(ValueError, match="gaps must be True, False or an array of gaps"):
        pf.scan(pf.SelfAffine, params, p, e_star=1e9, gaps=[2.0, 1.0], progress=False)
