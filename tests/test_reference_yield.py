"""The slow two-wall twin persson_fast._reference.yield_wall against exact results.

translating_walls (the exact series for two walls translating together) is held to the
constant-wall series plastic_area, to the single moving wall (linear_boundary_*), to its own
bookkeeping identities and to the scaling sigma -> lambda sigma, G -> lambda^2 G, b -> b/lambda.
two_wall_reference (Crank-Nicolson between the walls, Richardson-extrapolated) is held to both
oracles, to the single moving wall with a far yield wall, to its identities and, at a jump of
the yield wall, to the exact cut of the sine series. Measured: translating_walls vs
plastic_area <= 5e-15, its identities <= 4e-16; two_wall_reference <= 1.1e-7 (areas) and
<= 2e-8 (loads / W) against the oracles.
"""
import math

import numpy as np
import pytest

import persson_fast as pf
from persson_fast._reference.yield_wall import OUTPUTS, translating_walls, two_wall_reference

AREAS = ("elastic_area", "plastic_area", "detached_area")
LOADS = ("load", "plastic_load", "detached_load")

#: translating_walls against the constant-wall series (both exact series; measured 4e-16)
EXACT = 1e-12
#: bookkeeping identities of translating_walls (rounding; measured <= 5e-16)
IDENTITY = 1e-10
#: two_wall_reference against an exact oracle (areas absolute, loads / strip width W;
#: measured <= 1.1e-7)
REF = 1e-6


def _close_all(got, want, scale, tol):
    for k in OUTPUTS:
        s = 1.0 if k in AREAS else scale
        np.testing.assert_allclose(got[k], want[k], rtol=0, atol=tol * s, err_msg=k)


# ---------------------------------------------------------------------------------------------
# translating_walls
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("ratio", [0.0, 1e-3, 0.3, 0.5, 0.77, 0.999, 1.0])
@pytest.mark.parametrize("Y", [1e6, 3e8])
def test_translating_walls_is_plastic_area_at_rest(ratio, Y):
    G = np.array([0.0, 1e-6, 1e-4, 1e-2, 0.1, 0.5, 2.0, 20.0]) * Y ** 2
    s0 = ratio * Y
    r = translating_walls(s0, G, 0.0, Y, 0.0)
    el, pl = pf.plastic_area(s0, G, Y)
    np.testing.assert_allclose(r["elastic_area"], el, rtol=0, atol=EXACT)
    np.testing.assert_allclose(r["plastic_area"], pl, rtol=0, atol=EXACT)
    np.testing.assert_allclose(r["detached_area"], 1.0 - el - pl, rtol=0, atol=EXACT)
    # no adhesion: the lower wall carries no load; the plastic load is Y A_pl
    np.testing.assert_allclose(r["detached_load"], 0.0, rtol=0, atol=EXACT * Y)
    np.testing.assert_allclose(r["plastic_load"], Y * pl, rtol=0, atol=EXACT * Y)


@pytest.mark.parametrize("scale", [1e6, 1e7, 1e8])
@pytest.mark.parametrize("bW", [-8.0, -3.0, -0.5, -1e-6, 1e-6, 0.5, 3.0, 8.0])
@pytest.mark.parametrize("a_frac", [0.0, 0.3, -0.2])
def test_translating_walls_identities(scale, bW, a_frac):
    Y = scale
    a = a_frac * Y                      # a < 0: the lower wall starts at a positive stress
    W = Y + a
    b = bW / W
    G = np.geomspace(1e-4, 10.0, 12) * W ** 2
    for s0 in (-a + 0.1 * W, -a + 0.5 * W, -a + 0.93 * W):
        r = translating_walls(s0, G, a, Y, b)
        total = r["elastic_area"] + r["plastic_area"] + r["detached_area"]
        np.testing.assert_allclose(total, 1.0, rtol=0, atol=IDENTITY)
        balance = r["load"] + r["plastic_load"] + r["detached_load"]
        np.testing.assert_allclose(balance, s0, rtol=0, atol=IDENTITY * W)
        for k in AREAS:
            assert np.all(r[k] >= -1e-13) and np.all(r[k] <= 1 + 1e-13)
        # the areas absorbed only grow
        assert np.all(np.diff(r["plastic_area"]) >= -1e-13)
        assert np.all(np.diff(r["detached_area"]) >= -1e-13)


@pytest.mark.parametrize("lam", [1e-3, 7.0, 1e4])
@pytest.mark.parametrize("bW", [-4.0, 2.5])
def test_translating_walls_scale_invariance(lam, bW):
    Y, a, s0 = 2e7, 5e6, 1.1e7
    W = Y + a
    b = bW / W
    G = np.array([1e-3, 0.03, 0.2, 1.5]) * W ** 2
    r1 = translating_walls(s0, G, a, Y, b)
    r2 = translating_walls(lam * s0, lam ** 2 * G, lam * a, lam * Y, b / lam)
    for k in AREAS:
        np.testing.assert_allclose(r2[k], r1[k], rtol=0, atol=EXACT)
    for k in LOADS:
        np.testing.assert_allclose(r2[k], lam * r1[k], rtol=0, atol=EXACT * lam * W)


@pytest.mark.parametrize("bb", [-0.3, 0.2, 2.0])
def test_translating_walls_far_yield_wall_is_linear_boundary(bb):
    """Y far beyond the spread: the lower wall sigma_a = a - b G alone (linear_boundary with
    speed -b), the upper wall absorbs nothing."""
    a, s0 = 2e7, 5e7
    b = bb / s0
    G = np.array([1e12, 1e14, 1e15, 4e15])
    r = translating_walls(s0, G, a, 1.5e9, b)
    area = pf.linear_boundary_area(s0, G, a, -b)
    load = pf.linear_boundary_load(s0, G, a, -b)
    np.testing.assert_allclose(r["elastic_area"], area, rtol=0, atol=1e-12)
    np.testing.assert_allclose(r["detached_area"], 1.0 - area, rtol=0, atol=1e-12)
    np.testing.assert_allclose(r["load"], load, rtol=0, atol=1e-11 * s0)
    assert np.all(np.abs(r["plastic_area"]) < 1e-12)  # rounding x amplification e^2.6


def test_translating_walls_start_and_refusals():
    r = translating_walls(1e7, [0.0], 0.0, 3e7, 1e-7)
    assert [float(r[k][0]) for k in OUTPUTS] == [1.0, 0.0, 0.0, 1e7, 0.0, 0.0]
    on_wall = translating_walls(3e7, [0.0, 1e14], 0.0, 3e7, 0.0)
    np.testing.assert_allclose(on_wall["plastic_area"], 1.0, atol=1e-15)
    with pytest.raises(ValueError, match="small G"):
        translating_walls(1e7, [1e-12 * 9e14], 0.0, 3e7, 0.0)
    with pytest.raises(ValueError, match="drifted"):
        translating_walls(1e7, [1e9], 0.0, 3e7, 100.0 / 3e7)
    with pytest.raises(ValueError):
        translating_walls(4e7, [1.0], 0.0, 3e7, 0.0)
    with pytest.raises(ValueError):
        translating_walls(1e7, [-1.0], 0.0, 3e7, 0.0)


# ---------------------------------------------------------------------------------------------
# two_wall_reference
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("ratio", [0.2, 0.5, 0.8])
def test_reference_vs_plastic_area(ratio):
    Y = 3e8
    s0 = ratio * Y
    G = np.array([0.0, 1e-4, 1e-3, 1e-2, 0.05, 0.1, 0.3, 1.0]) * Y ** 2
    r = two_wall_reference(G, s0, 0.0, Y)
    el, pl = pf.plastic_area(s0, G, Y)
    want = {"elastic_area": el, "plastic_area": pl, "detached_area": 1.0 - el - pl,
            "plastic_load": Y * pl, "detached_load": 0.0 * el, "load": s0 - Y * pl}
    _close_all(r, want, Y, REF)


@pytest.mark.parametrize("bW", [-6.0, -2.0, 2.0, 6.0])
@pytest.mark.parametrize("form", ["samples", "callable"])
def test_reference_vs_translating_walls(bW, form):
    Y, a, s0 = 2e8, 5e7, 6e7
    W = Y + a
    b = bW / W
    G = np.array([0.0, 1e-3, 1e-2, 0.05, 0.1, 0.3, 1.0]) * W ** 2
    if form == "samples":
        sa, sy = a - b * G, Y + b * G
    else:
        def sa(g):
            return a - b * g

        def sy(g):
            return Y + b * g
    r = two_wall_reference(G, s0, sa, sy)
    _close_all(r, translating_walls(s0, G, a, Y, b), W, REF)


@pytest.mark.parametrize("bb", [-0.5, 0.5])
def test_reference_far_yield_wall_is_linear_boundary(bb):
    a, s0 = 2e7, 5e7
    b = bb / s0
    G = np.array([0.0, 1e12, 1e14, 1e15, 4e15])
    r = two_wall_reference(G, s0, lambda g: a + b * g, 1e9)
    area = pf.linear_boundary_area(s0, G, a, b)
    load = pf.linear_boundary_load(s0, G, a, b)
    np.testing.assert_allclose(r["elastic_area"], area, rtol=0, atol=REF)
    np.testing.assert_allclose(r["detached_area"], 1.0 - area, rtol=0, atol=REF)
    np.testing.assert_allclose(r["load"], load, rtol=0, atol=REF * s0)
    np.testing.assert_allclose(r["plastic_area"], 0.0, rtol=0, atol=1e-15)


def test_reference_identities_curved_walls():
    """Walls that are neither constant nor linear: A_el + A_pl + D = 1 (the discrete fluxes
    conserve the area) and the load balance (to the discretisation error)."""
    Y0, a0, s0 = 1e8, 3e7, 4e7
    G = np.geomspace(1e12, 3e16, 9)

    def sa(g):
        return a0 + 0.3 * math.sqrt(g)

    def sy(g):
        return Y0 * (1.0 + 0.5 * g / 1e16) ** 0.5

    r = two_wall_reference(G, s0, sa, sy)
    total = r["elastic_area"] + r["plastic_area"] + r["detached_area"]
    np.testing.assert_allclose(total, 1.0, rtol=0, atol=1e-10)
    balance = r["load"] + r["plastic_load"] + r["detached_load"]
    np.testing.assert_allclose(balance, s0, rtol=0, atol=1e-7 * Y0)
    # without Richardson the identities are the same, the values ~1e-5 off
    f = two_wall_reference(G, s0, sa, sy, richardson=False)
    np.testing.assert_allclose(f["elastic_area"], r["elastic_area"], rtol=0, atol=1e-3)


def test_reference_yield_jump_books_the_exact_cut():
    """sigma_Y jumps from Y to c < Y at G_j (sigma_a = 0): at the jump, the mass of the series
    beyond c goes to the plastic account at stress c, so the load balance is short by
    integral_c^Y (sigma - c) P dsigma; both are sine-series integrals."""
    Y, s0, frac = 3e8, 1e8, 0.7
    c = frac * Y
    G = np.array([0.0, 0.02, 0.05, 0.05, 0.06, 0.3]) * Y ** 2
    sy = np.array([Y, Y, Y, c, c, c])
    r = two_wall_reference(G, s0, 0.0, sy)
    n = np.arange(1, 201)
    k = n * np.pi / Y
    amp = (2.0 / Y) * np.sin(k * s0) * np.exp(-k * k * G[2])
    cut = np.sum(amp * (np.cos(k * c) - np.cos(k * Y)) / k)
    defect = np.sum(amp * (-(Y - c) * (-1.0) ** n / k - np.sin(k * c) / k ** 2))
    el, pl = pf.plastic_area(s0, G[2], Y)
    np.testing.assert_allclose(r["elastic_area"][2:4], [el, el - cut], rtol=0, atol=REF)
    np.testing.assert_allclose(r["plastic_area"][2:4], [pl, pl + cut], rtol=0, atol=REF)
    total = r["elastic_area"] + r["plastic_area"] + r["detached_area"]
    np.testing.assert_allclose(total, 1.0, rtol=0, atol=1e-10)
    balance = r["load"] + r["plastic_load"] + r["detached_load"] - s0
    np.testing.assert_allclose(balance[:3], 0.0, rtol=0, atol=REF * Y)
    np.testing.assert_allclose(balance[3:], -defect, rtol=0, atol=REF * Y)
    # the resolution does not matter after the jump either
    r2 = two_wall_reference(G, s0, 0.0, sy, n_nodes=400)
    _close_all(r2, r, Y, REF)


def test_reference_refusals():
    G = np.array([0.0, 1e14])
    with pytest.raises(ValueError):
        two_wall_reference(G, 4e7, 0.0, 3e7)
    with pytest.raises(ValueError):
        two_wall_reference(G[::-1], 1e7, 0.0, 3e7)
    with pytest.raises(ValueError):
        two_wall_reference(G, 1e7, np.zeros(3), 3e7)


@pytest.mark.parametrize("bW", [-9.0, 9.0])
def test_reference_vs_translating_walls_strong_drift_fine_grid(bW):
    """Strong drift, start near the lower wall, late times: a finer run still within REF."""
    Y, a, s0 = 1e7, 2e6, 1e6
    W = Y + a
    b = bW / W
    G = np.array([0.0, 1e-3, 1e-2, 0.1, 0.5, 2.0]) * W ** 2
    r = two_wall_reference(G, s0, a - b * G, Y + b * G, n_nodes=800, rel_step=0.01,
                           max_step=5e-4)
    _close_all(r, translating_walls(s0, G, a, Y, b), W, REF)


@pytest.mark.parametrize("ratio", [0.05, 0.5, 0.95])
def test_package_yield_wall_vs_reference(ratio):
    """The package's constant yield wall (exact series) against the twin's grid solve, for all
    the quantities the package reports: elastic area, plastic area and plastic load."""
    Y = 2.5e8
    G = np.array([0.0, 1e-5, 1e-3, 0.02, 0.2, 1.5]) * Y ** 2
    r = pf.solve_diffusion(G, [ratio * Y], 0.0, sigma_y=Y, method="auto", rtol=1e-10)
    assert r.status[0] == 0
    ref = two_wall_reference(G, ratio * Y, 0.0, Y)
    got = {"elastic_area": r.area[0], "plastic_area": r.plastic_area[0],
           "plastic_load": r.plastic_load[0]}
    for k, v in got.items():
        s = 1.0 if k in AREAS else Y
        np.testing.assert_allclose(v, ref[k], rtol=0, atol=REF * s, err_msg=k)
