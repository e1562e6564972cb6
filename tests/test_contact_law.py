"""The tabulated contact law p(u), K(u) (persson_fast.separation.contact_law, embed.law_*).

Oracle: the closed form (pf.solve_separation, ~1e-12, itself tested in test_separation.py)
at separations the builder never saw (random, and the tails)."""
import math
import os

import numba
import numpy as np
import pytest

import persson_fast as pf
from persson_fast import embed
from persson_fast._kernels.status import BAD_PRESSURE, BAD_SEPARATION, LAW_EXTRAPOLATED, OK
from persson_fast.surfaces.models import seed_e_star, seed_scene

SELF_AFFINE = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
SCENES = {"self_affine": (SELF_AFFINE, 1e9), "seed": (seed_scene(), seed_e_star())}


def _random_pressures(law, n, rng):
    return np.exp(rng.uniform(math.log(law.pressure_min), math.log(law.pressure_max), n))


@pytest.mark.parametrize("name", SCENES)
@pytest.mark.parametrize("gamma", [None, 0.45])
@pytest.mark.parametrize("rtol", [1e-4, 1e-6, 1e-8])
def test_law_within_rtol_between_nodes(name, gamma, rtol):
    surface, e = SCENES[name]
    law = embed.contact_law(surface, e_star=e, energy_correction=gamma, rtol=rtol)
    assert law.error_estimate <= rtol
    rng = np.random.default_rng(7)
    p = _random_pressures(law, 3000, rng)
    exact = pf.solve_separation(surface, p, e_star=e, energy_correction=gamma)
    got_p, got_k, status = law.evaluate(exact.separation)
    assert np.all(status == OK)
    err = np.maximum(np.abs(got_p / p - 1.0), np.abs(got_k / exact.stiffness - 1.0))
    assert err.max() <= rtol
    # the estimate is the largest error at the check points: the random points find no
    # larger one (beyond 1.5x) and the estimate is not far above what they find
    assert err.max() <= 1.5 * law.error_estimate
    assert law.error_estimate <= 10 * err.max()


@pytest.mark.parametrize("name", SCENES)
def test_small_pressure_tail_is_the_exponential_law(name):
    surface, e = SCENES[name]
    rtol = 1e-6
    law = embed.contact_law(surface, e_star=e, rtol=rtol)
    u_end = law.separation[-1]
    u0 = law.decay_length
    u = u_end + np.array([0.1, 1.0, 5.0, 20.0]) * u0
    p, k, status = law.evaluate(u)
    assert np.all(status == OK)
    exact_p = pf.pressure_at_separation(surface, u, e_star=e, rtol=1e-12)
    exact_k = pf.solve_separation(surface, exact_p, e_star=e).stiffness
    np.testing.assert_allclose(p, exact_p, rtol=rtol)
    np.testing.assert_allclose(k, exact_k, rtol=rtol)


def test_monotone_and_positive_stiffness():
    law = embed.contact_law(SELF_AFFINE, e_star=1e9, energy_correction=0.45, rtol=1e-4)
    u = np.geomspace(law.separation[0], 2 * law.separation[-1], 20001)
    p, k, status = law.evaluate(u)
    assert np.all(status == OK)
    assert np.all(np.diff(p) < 0)
    assert np.all(k > 0)


def test_outside_and_bad_separations():
    law = embed.contact_law(SELF_AFFINE, e_star=1e9, rtol=1e-6)
    p, k, status = law.evaluate([law.separation[0] / 10, 0.0, -1.0, np.nan, np.inf])
    assert list(status) == [LAW_EXTRAPOLATED] + [BAD_SEPARATION] * 4
    assert np.isfinite(p[0]) and p[0] > law.pressure_max
    assert np.all(np.isnan(p[1:])) and np.all(np.isnan(k[1:]))
    with pytest.raises(ValueError, match=r"below the contact law's table.*separation\[0\]"):
        law.pressure_at([law.separation[0] / 10])
    with pytest.raises(ValueError, match=r"separation must be finite and > 0.*separation\[1\]"):
        law.stiffness_at([1e-6, 0.0])
    assert isinstance(law.pressure_at(1e-6), float)
    assert law.stiffness_at([[1e-6]]).shape == (1, 1)


@numba.njit(cache=False)
def _user_kernel(table, gaps):
    p = np.empty(gaps.size)
    k = np.empty(gaps.size)
    bad = 0
    for i in range(gaps.size):
        p[i], k[i], status = embed.law_pressure_stiffness(table, gaps[i])
        q, s2 = embed.law_pressure(table, gaps[i])
        kk, s3 = embed.law_stiffness(table, gaps[i])
        if status != 0 or s2 != 0 or s3 != 0 or q != p[i] or kk != k[i]:
            bad += 1
    return p, k, bad


def test_callable_from_user_njit_code():
    law = embed.contact_law(SELF_AFFINE, e_star=1e9, rtol=1e-6)
    gaps = np.geomspace(law.separation[0], law.separation[-1], 101)
    p, k, bad = _user_kernel(law.table, gaps)
    assert bad == 0
    ref_p, ref_k, _ = law.evaluate(gaps)
    np.testing.assert_array_equal(p, ref_p)
    np.testing.assert_array_equal(k, ref_k)


def test_csv_round_trip_and_atomic_write(tmp_path):
    law = embed.contact_law(SELF_AFFINE, e_star=1e9, rtol=1e-5)
    path = tmp_path / "law.csv"
    path.write_text("old\n")
    assert law.to_csv(path) == str(path)
    text = path.read_text()
    assert text.startswith("# persson_fast contact law")
    data = np.genfromtxt(path, delimiter=",", comments="#", skip_header=5)
    assert data.shape == (law.separation.size, 8)
    for col, arr in enumerate(law.table):
        np.testing.assert_array_equal(data[:, col], arr)
    np.testing.assert_array_equal(data[:, 5], law.separation)
    # a failing write leaves the old file and no temporary behind
    os.chmod(tmp_path, 0o500)
    try:
        if not os.access(tmp_path, os.W_OK):           # (root can write anyway)
            with pytest.raises(OSError):
                law.to_csv(path)
            assert path.read_text() == text
    finally:
        os.chmod(tmp_path, 0o700)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["law.csv"]


def test_to_xarray():
    pytest.importorskip("xarray")
    law = embed.contact_law(SELF_AFFINE, e_star=1e9, rtol=1e-5)
    ds = law.to_xarray()
    np.testing.assert_array_equal(ds["separation"].values, law.separation)
    np.testing.assert_array_equal(ds["pressure"].values, law.pressure)
    assert ds["stiffness"].attrs["units"] == "Pa/m"
    assert ds.attrs["rtol"] == 1e-5


def test_refusals():
    scene = pf.Scene(SELF_AFFINE, e_star=1e9, work_of_adhesion=0.01)
    with pytest.raises(ValueError, match="without adhesion only"):
        embed.contact_law(scene)
    with pytest.raises(ValueError, match="rtol"):
        embed.contact_law(SELF_AFFINE, e_star=1e9, rtol=1.0)
    with pytest.raises(ValueError, match="pressure_max"):
        embed.contact_law(SELF_AFFINE, e_star=1e9, pressure_max=-1.0)
    law = embed.contact_law(pf.Scene(SELF_AFFINE, e_star=1e9), pressure_max=1e7)
    assert law.pressure_max == pytest.approx(1e7, rel=1e-12)
    assert "ContactLaw" in repr(law)


@numba.njit(cache=False)
def _inverse(table, pressures):
    u = np.empty(pressures.size)
    back = np.empty(pressures.size)
    status = np.empty(pressures.size, dtype=np.int64)
    for i in range(pressures.size):
        u[i], status[i] = embed.law_separation(table, pressures[i])
        back[i], _ = embed.law_pressure(table, u[i])
    return u, back, status


def test_law_separation_inverts_law_pressure():
    law = embed.contact_law(SELF_AFFINE, e_star=1e9, rtol=1e-6)
    p = np.geomspace(law.pressure_min / 1e3, law.pressure_max, 2001)
    u, back, status = _inverse(law.table, p)
    assert np.all(status == OK)
    # to rounding: ln u is rounded (|ln u| ~ 11-55) and |d ln p / d ln u| reaches ~20
    np.testing.assert_allclose(back, p, rtol=5e-13)
    assert np.all(np.diff(u) < 0)
    exact = pf.solve_separation(SELF_AFFINE, p, e_star=1e9).separation
    # u(p) is the inverse of a law within rtol in p: |du| <= rtol p / K
    k = pf.solve_separation(SELF_AFFINE, p, e_star=1e9).stiffness
    assert np.all(np.abs(u - exact) <= 1e-6 * p / k)
    u_out, _, st = _inverse(law.table, np.array([law.pressure_max * 2, 0.0, -1.0, np.nan]))
    assert list(st) == [LAW_EXTRAPOLATED, BAD_PRESSURE, BAD_PRESSURE, BAD_PRESSURE]
    assert u_out[0] < law.separation[0] and np.all(np.isnan(u_out[1:]))
