"""The compiled two-wall "strip" solver against exact series and the slow twin.

Oracles: translating_walls (exact series for two walls translating together), the constant-wall
series plastic_area, and two_wall_reference (slow Crank-Nicolson twin) for curved walls. The
twin reports detached_load with the opposite sign (the integral of -sigma_a dD); it is
converted here. Measured (rtol = 1e-6): error of A = A_el + A_pl <= 0.3 rtol A against
translating_walls, error estimate ~2x the true error; <= 0.15 rtol against plastic_area;
<= 1e-7 against two_wall_reference on curved walls (the twin's own accuracy).
"""
import numpy as np
import pytest
from hypothesis import assume, example, given, settings, strategies as hs

import persson_fast as pf
from persson_fast._kernels import status as st
from persson_fast._reference.yield_wall import translating_walls, two_wall_reference
from persson_fast.plasticity.strip import solve_two_walls

RTOL = 1e-6
ATOL = 1e-12
#: error estimate: at most this many times the true error (where the error exceeds rounding)
EST_FACTOR = 30.0
#: true errors below this are rounding (the estimate is not held to them)
ROUNDING = 1e-11


def _twin(out, i=0):
    """Our outputs of row i in the twin's convention (detached_load = integral -sigma_a dD)."""
    d = {k: out[k][i] for k in ("elastic_area", "plastic_area", "detached_area", "load",
                                "plastic_load")}
    d["detached_load"] = -out["detached_load"][i]
    return d


@pytest.mark.parametrize("bW", [-6.0, -2.0, 0.0, 2.0, 6.0])
@pytest.mark.parametrize("Y, a_frac, s_frac", [(3e8, 0.0, 0.2), (1e9, 0.2, 0.5),
                                               (1e8, 0.0, 0.8), (3e8, 0.5, -0.3)])
def test_vs_translating_walls(bW, Y, a_frac, s_frac):
    a = a_frac * Y
    W = Y + a
    b = bW / W
    s0 = s_frac * Y
    G = np.concatenate([[0.0], np.geomspace(1e-4, 1.0, 30)]) * W ** 2
    ex = translating_walls(s0, G, a, Y, b)
    out, _ = solve_two_walls(G, [s0], a - b * G, Y + b * G, rtol=RTOL)
    assert out["status"][0] == st.OK
    got = _twin(out)
    A = got["elastic_area"] + got["plastic_area"]
    A_ex = ex["elastic_area"] + ex["plastic_area"]
    err = np.abs(A - A_ex)
    assert np.all(err <= RTOL * A_ex + ATOL)
    for k in ("plastic_area", "detached_area"):
        np.testing.assert_allclose(got[k], ex[k], rtol=0, atol=RTOL, err_msg=k)
    for k in ("load", "plastic_load", "detached_load"):
        np.testing.assert_allclose(got[k], ex[k], rtol=0, atol=RTOL * W, err_msg=k)
    # the estimate bounds the error and is not wildly larger
    est = out["error_estimate"][0]
    assert np.all(err <= est + ROUNDING)
    big = err > ROUNDING
    assert np.all(est[big] <= EST_FACTOR * err[big] + ATOL)


@pytest.mark.parametrize("ratio", [0.01, 0.2, 0.5, 0.8, 0.99])
def test_vs_plastic_area(ratio):
    Y = 3e8
    G = np.concatenate([[0.0], np.geomspace(1e-6, 1.0, 25)]) * Y ** 2
    s0 = ratio * Y
    out, _ = solve_two_walls(G, [s0], np.zeros_like(G), np.full_like(G, Y), rtol=RTOL)
    assert out["status"][0] == st.OK
    el, pl = pf.plastic_area(s0, G, Y)
    A = out["elastic_area"][0] + out["plastic_area"][0]
    assert np.all(np.abs(A - (el + pl)) <= RTOL * (el + pl) + ATOL)
    np.testing.assert_allclose(out["plastic_area"][0], pl, rtol=0, atol=RTOL)
    np.testing.assert_allclose(out["plastic_load"][0], Y * pl, rtol=0, atol=RTOL * Y)
    np.testing.assert_allclose(out["detached_load"][0], 0.0, rtol=0, atol=RTOL * Y)


def test_vs_reference_curved_walls():
    Y = 3e8
    G = np.linspace(0.0, 1.0, 200) * Y ** 2
    sy = Y * (1.0 + 0.5 * np.sqrt(G) / Y)
    sa = 0.3 * Y * np.exp(-G / (0.3 * Y ** 2))
    s0 = 0.3 * Y
    out, _ = solve_two_walls(G, [s0], sa, sy, rtol=RTOL)
    assert out["status"][0] == st.OK
    ref = two_wall_reference(G, s0, sa, sy)
    got = _twin(out)
    for k in ("elastic_area", "plastic_area", "detached_area"):
        np.testing.assert_allclose(got[k], ref[k], rtol=0, atol=1e-5, err_msg=k)
    for k in ("load", "plastic_load", "detached_load"):
        np.testing.assert_allclose(got[k], ref[k], rtol=0, atol=1e-5 * Y, err_msg=k)


@settings(max_examples=25, deadline=None)
@given(s_frac=hs.floats(0.05, 0.95), a_frac=hs.floats(0.0, 0.5),
       c1=hs.floats(-0.5, 0.5), c2=hs.floats(-0.5, 0.5), curv=hs.floats(0.0, 1.0))
# walls that meet at the last sample to 1e-16 of their width: the step plan asked for steps
# ~ w^2 and its count ran for hours (now stopped, and the steps floored by the work cap)
@example(s_frac=0.9161993273316018, a_frac=0.05278223694345198, c1=1.2349452116009255e-118,
         c2=-0.5, curv=1.0)
def test_bookkeeping_identities(s_frac, a_frac, c1, c2, curv):
    Y = 2e8
    a = a_frac * Y
    W = Y + a
    G = np.concatenate([[0.0], np.geomspace(1e-3, 1.0, 15)]) * W ** 2
    x = G / W ** 2
    sa = a + c1 * W * x * (1.0 - 0.5 * curv * x)
    sy = Y + c2 * W * x * (1.0 + curv * np.sqrt(x))
    assume(np.all(sa + sy > 0))       # the walls meet at G = W^2 when c1 = c2 = -1/2, a = 0
    s0 = -a + s_frac * W
    out, _ = solve_two_walls(G, [s0], sa, sy, rtol=1e-5)
    total = out["elastic_area"][0] + out["plastic_area"][0] + out["detached_area"][0]
    np.testing.assert_allclose(total, 1.0, rtol=0, atol=1e-10)
    balance = out["load"][0] + out["plastic_load"][0] - out["detached_load"][0]
    np.testing.assert_allclose(balance, s0, rtol=0, atol=1e-10 * W)
    if out["status"][0] == st.OK:
        assert np.all(out["error_estimate"][0] <= 1e-5 * (1 - out["detached_area"][0]) + ATOL)


def test_start_next_to_a_wall():
    """sigma0 = 1e-3 Y above a lower wall at rest: the exact one-wall start keeps the grid
    small."""
    Y = 3e8
    s0 = 1e-3 * Y
    G = np.concatenate([[0.0], np.geomspace(1e-9, 1.0, 30)]) * Y ** 2
    out, _ = solve_two_walls(G, [s0], np.zeros_like(G), np.full_like(G, Y), rtol=RTOL)
    assert out["status"][0] == st.OK
    assert out["counts"][0, 0] <= 400
    el, pl = pf.plastic_area(s0, G, Y)
    A = out["elastic_area"][0] + out["plastic_area"][0]
    assert np.all(np.abs(A - (el + pl)) <= RTOL * (el + pl) + ATOL)


@pytest.mark.parametrize("frac", [0.0, 0.8])
def test_start_next_to_a_receding_wall(frac):
    """sigma0 at most 0.004 W above a lower wall that recedes like G^(1/4) on 41 geometric
    samples from 1e-15 W^2 (the shape of the seed scene's adhesive wall at p_nom = 0): the
    wall runs away faster than the distribution spreads, so the free start lasts until the
    distribution spans ~70 coarse intervals. Bounding the hit probability with the least
    distance over [0, G_s] alone allowed only a start narrower than 4096 intervals resolve
    (status 3 or 7 before); here OK on 131 intervals, within 0.03 rtol of the slow twin."""
    Y, a = 3e8, 1.2e6
    W = Y + a
    G = np.concatenate([[0.0], np.geomspace(1e-15, 1.2, 41)]) * W ** 2
    sa = a + 2.6 * W * (G / W ** 2) ** 0.25
    sy = np.full_like(G, Y)
    s0 = frac * a
    rtol = 1e-5
    out, _ = solve_two_walls(G, [s0], sa, sy, rtol=rtol)
    assert out["status"][0] == st.OK
    assert out["counts"][0, 0] <= 400
    ref = two_wall_reference(G, s0, sa, sy)
    A = out["elastic_area"][0] + out["plastic_area"][0]
    A_ref = ref["elastic_area"] + ref["plastic_area"]
    assert np.all(np.abs(A - A_ref) <= rtol * A_ref + ATOL)
    assert out["plastic_area"][0, -1] > 0.5      # the yield wall matters at the end


@pytest.mark.parametrize("bW", [30.0, 100.0])
def test_hostile_wall_racing_in(bW):
    """The lower wall races into the distribution: within rtol or flagged."""
    Y = 3e8
    W = Y
    b = bW / W
    s0 = 0.5 * Y
    g0 = max(1e-4, (0.5 * bW * s0 / W - 9.0) / (0.25 * bW ** 2))  # oracle's amplification
    G = np.concatenate([[0.0], np.geomspace(g0, 0.3, 20)]) * W ** 2
    try:
        ex = translating_walls(s0, G, 0.0, Y, b)
    except ValueError:
        pytest.skip("oracle refuses this drift")
    out, _ = solve_two_walls(G, [s0], -b * G, Y + b * G, rtol=RTOL)
    A = out["elastic_area"][0] + out["plastic_area"][0]
    A_ex = ex["elastic_area"] + ex["plastic_area"]
    ok = np.all(np.abs(A - A_ex) <= RTOL * A_ex + ATOL)
    assert ok or out["status"][0] != st.OK


@pytest.mark.parametrize("rtol", [1e-4, 1e-6, 1e-8])
@pytest.mark.parametrize("ratio, drift, curve, detach", [(0.9375, 0.0, 0.5, 0.0),
                                                         (0.8886, -2.858, 0.0078, 0.1635)])
def test_mass_absorbed_next_to_a_kinked_or_racing_wall(rtol, ratio, drift, curve, detach):
    """A start 0.06 Y below a yield wall Y + 0.5 sqrt(G) on 7 samples (kinks), and a yield wall
    racing in (2e-8 of the mass left elastic at the end): within rtol of the twin with status
    OK. Measured against the twin at 8x its resolution: errors <= 0.013 rtol (0.004 at rtol
    1e-4); the twin's own error is 3e-10 and 6e-12 relative, hence the slack 0.1."""
    Y = 1e8
    G = np.geomspace(1e-4, 1.0, 7) * Y ** 2
    sy = Y * (1.0 + drift * 0.2 * G / Y ** 2 + curve * np.sqrt(G) / Y)
    sa = detach * Y * (1.0 - 0.5 * G / Y ** 2)
    s0 = ratio * Y
    out, _ = solve_two_walls(G, [s0], sa, sy, rtol=rtol)
    assert out["status"][0] == st.OK
    ref = two_wall_reference(G, s0, sa, sy)
    A = out["elastic_area"][0] + out["plastic_area"][0]
    A_ref = ref["elastic_area"] + ref["plastic_area"]
    assert np.all(np.abs(A - A_ref) <= 0.1 * rtol * A_ref + ATOL)


def test_threads_equal_serial():
    Y = 3e8
    G = np.geomspace(1e-6, 1.5, 60) * Y ** 2
    P = np.linspace(0.05, 0.95, 13) * Y
    sa = np.outer(np.linspace(0.0, 0.1, 13) * Y, np.ones(60))
    sy = Y * (1.0 + 0.2 * np.sqrt(G) / Y)
    a, _ = solve_two_walls(G, P, sa, sy, rtol=RTOL, parallel=False)
    b, _ = solve_two_walls(G, P, sa, sy, rtol=RTOL, parallel="threads")
    for k in a:
        assert np.array_equal(a[k], b[k]), k


def test_level_converges():
    Y = 3e8
    G = np.concatenate([[0.0], np.geomspace(1e-3, 1.0, 10)]) * Y ** 2
    s0 = 0.3 * Y
    el, pl = pf.plastic_area(s0, G, Y)
    errs = []
    for level in (0, 1, 2):
        out, _ = solve_two_walls(G, [s0], 0.0 * G, Y + 0.0 * G, rtol=RTOL, level=level)
        errs.append(np.max(np.abs(out["elastic_area"][0] + out["plastic_area"][0] - el - pl)))
    assert errs[2] < errs[1] < errs[0]


def test_bad_input():
    G = np.array([0.0, 1e16])
    sa, sy = np.zeros(2), np.full(2, 3e8)
    with pytest.raises(ValueError, match="strictly between"):
        solve_two_walls(G, [4e8], sa, sy, rtol=RTOL)
    with pytest.raises(ValueError, match="strictly between"):
        solve_two_walls(G, [0.0], sa, sy, rtol=RTOL)
    with pytest.raises(ValueError, match="non-decreasing"):
        solve_two_walls(G[::-1], [1e8], sa, sy, rtol=RTOL)
    with pytest.raises(ValueError, match="shape"):
        solve_two_walls(G, [1e8, 2e8], np.zeros((3, 2)), sy, rtol=RTOL)
    with pytest.raises(ValueError, match="finite"):
        solve_two_walls(G, [np.nan], sa, sy, rtol=RTOL)
    with pytest.raises(ValueError, match="cross"):
        solve_two_walls(G, [1e8], np.array([0.0, -4e8]), sy, rtol=RTOL)
    with pytest.raises(ValueError, match="jump"):
        solve_two_walls(np.array([0.0, 1e16, 1e16]), [1e8], np.zeros(3),
                        np.array([3e8, 3e8, 2e8]), rtol=RTOL)
    with pytest.raises(ValueError, match="rtol"):
        solve_two_walls(G, [1e8], sa, sy, rtol=0.5)
    with pytest.raises(ValueError, match="parallel"):
        solve_two_walls(G, [1e8], sa, sy, rtol=RTOL, parallel="gpu")
