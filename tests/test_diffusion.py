"""The compiled stress-diffusion solver against exact solutions, identities and hard cases."""
import numpy as np
import pytest

import persson_fast as pf
from persson_fast._reference import diffusion as ref
from persson_fast._kernels.tridiag import thomas, theta_step
from persson_fast.sweep import run_sweep
from tolerances import ATOL, BOUNDS, IDENTITY, LOAD_CONSERVATION, RTOL, TWIN


def within(area, exact, rtol=RTOL, atol=ATOL):
    """Scaled error |A - A_exact| / (atol + rtol |A_exact|); < 1 passes."""
    return np.max(np.abs(area - exact) / (atol + rtol * np.abs(exact)))


# --- exact oracle: the method of images --------------------------------------------------
@pytest.mark.parametrize("scale", [1.0, 1e3, 1e6, 1e9])
@pytest.mark.parametrize("ratio", [2e-6, 1e-4, 1e-2, 0.3, 1.0, 3.0])
def test_images_through_solve_diffusion(scale, ratio):
    sigma0 = scale
    G1 = (sigma0 / ratio) ** 2
    G = np.geomspace(G1 * 1e-8, G1, 41)           # eight decades, physical units [Pa^2]
    r = pf.solve_diffusion(G, sigma0, method="cn")
    assert r.success, r.message
    exact = pf.images_area(sigma0, G)
    assert within(r.area[0], exact) < 1
    # load conservation, A + detached = 1
    assert np.max(np.abs(r.load[0] / sigma0 - 1)) < LOAD_CONSERVATION
    assert np.max(np.abs(r.area + r.detached_area - 1)) < IDENTITY


@pytest.mark.parametrize("ratio", [1e-4, 1e-3, 1e-2, 0.1, 0.5, 1.0, 2.0, 10.0])
def test_images_through_solve_contact_cn(ratio):
    s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    e_star = 1e9
    G1 = float(s.diffusion_time(s.q1, e_star))
    p = ratio * np.sqrt(G1)
    r = pf.solve_contact(s, p, e_star=e_star, method="cn")
    assert r.success and r.method == "cn"
    exact = pf.images_area(p, r.G)
    assert within(r.area_zeta[0], exact) < 1
    assert abs(r.load[0] / p - 1) < LOAD_CONSERVATION


# --- exact oracle: a wall moving linearly in G ------------------------------------------
def linear_wall_case(scale, b_scaled, a_frac, g_lo, g_hi, n):
    """sigma0 = scale, wall a + b G (a = a_frac scale, b y0 = b_scaled), G/y0^2 log-spaced
    from g_lo to g_hi plus 0; returns (sigma0, a, b, G, sa, cn result)."""
    sigma0, a = scale, a_frac * scale
    y0 = sigma0 + a
    b = b_scaled / y0
    G = np.concatenate([[0.0], np.geomspace(g_lo, g_hi, n) * y0**2])
    sa = a + b * G
    r = pf.solve_diffusion(G, sigma0, sa, method="cn")
    assert r.success, r.message
    return sigma0, a, b, G, sa, r


@pytest.mark.parametrize("scale", [1.0, 1e4, 1e8])
@pytest.mark.parametrize("b_scaled", [-1.0, -0.3, 0.3, 1.0, 3.0, 20.0])
def test_linear_wall(scale, b_scaled):
    sigma0, a, b, G, sa, r = linear_wall_case(scale, b_scaled, 0.2, 1e-2, 10.0, 40)
    exact = pf.linear_boundary_area(sigma0, G, a, b)
    assert within(r.area[0], exact) < 1
    assert np.max(np.abs(r.area + r.detached_area - 1)) < IDENTITY
    # load bookkeeping: int sigma P = sigma0 + int sigma_a g dG
    assert np.max(np.abs(r.load - sigma0 - r.detached_load)) < IDENTITY * 10 * max(sigma0, np.max(np.abs(sa)))
    exact_load = pf.linear_boundary_load(sigma0, G, a, b)
    assert np.max(np.abs(r.load[0] - exact_load)) < 1e-5 * max(sigma0, np.max(np.abs(sa)))


@pytest.mark.parametrize("scale", [1.0, 1e9])
@pytest.mark.parametrize("b_scaled", [-0.3, 0.3])
def test_linear_wall_eight_decades(scale, b_scaled):
    sigma0, a, b, G, _, r = linear_wall_case(scale, b_scaled, 0.1, 1e-6, 1e2, 41)
    assert within(r.area[0], pf.linear_boundary_area(sigma0, G, a, b)) < 1
    assert np.max(np.abs(r.area + r.detached_area - 1)) < IDENTITY


def test_auto_picks_analytic_for_linear_wall():
    G = np.linspace(0, 4.0, 9)
    r = pf.solve_diffusion(G, 1.0, 0.5 - 0.1 * G, method="auto")
    assert r.method == "analytic"
    c = pf.solve_diffusion(G, 1.0, 0.5 - 0.1 * G, method="cn")
    assert within(c.area[0], r.area[0]) < 1


# --- hard cases -----------------------------------------------------------------------------
def test_pressure_zero_has_no_contact():
    r = pf.solve_diffusion(np.geomspace(1e-3, 1e3, 7), [0.0, 1.0])
    assert np.all(r.area[0] == 0.0)
    assert np.all(r.area[1] > 0)


@pytest.mark.parametrize("hurst", [0.0, 1.0])
def test_extreme_hurst_and_zeta1_1e8(hurst):
    s = pf.SelfAffine(hurst=hurst, q0=1.0, q1=1e8, slope_rms=1.0)
    e_star = 1e9
    G1 = float(s.diffusion_time(s.q1, e_star))
    p = np.sqrt(G1) * np.array([1e-4, 0.1, 1.0, 5.0])
    r = pf.solve_contact(s, p, e_star=e_star, method="cn")
    assert r.success, r.message
    assert within(r.area_zeta, pf.images_area(p[:, None], r.G[None, :])) < 1


def test_zero_band_flat_G():
    q = np.array([1e3, 1e4, 2e4, 1e5, 1e6])
    C = np.array([1e-20, 1e-22, 0.0, 1e-24, 1e-27])      # a zero band between 1e4 and 1e5
    s = pf.TabulatedPSD(q, C)
    e_star = 1e9
    r = pf.solve_contact(s, np.array([1e3, 1e5, 1e7]), e_star=e_star, method="cn",
                         zeta=np.array([1.0, 5.0, 10.0, 20.0, 50.0, 100.0, 1000.0]))
    assert r.success, r.message
    assert r.G[2] == r.G[3] == r.G[4] or np.allclose(r.G[2:5], r.G[2])
    assert within(r.area_zeta, pf.images_area(r.pressure[:, None], r.G[None, :])) < 1


def _jump_schedule(direction):
    """Wall at 0 that jumps at G = 1 by +-0.5 (units of sigma0 = 1), then stays."""
    G = np.array([0.0, 0.5, 1.0, 1.0, 2.0, 4.0, 8.0, 16.0])
    sa = np.array([0.0, 0.0, 0.0, 0.5 * direction, 0.5 * direction, 0.5 * direction,
                   0.5 * direction, 0.5 * direction])
    return G, sa


@pytest.mark.parametrize("direction", [+1, -1])
def test_wall_jump_converges_and_keeps_books(direction):
    G, sa = _jump_schedule(direction)
    r = pf.solve_diffusion(G, 1.0, sa, method="cn")
    ref_ = pf.solve_diffusion(G, 1.0, sa, method="cn", rtol=1e-10)
    assert np.all(np.isfinite(r.area)) and np.all((r.area >= -BOUNDS) & (r.area <= 1 + BOUNDS))
    # a jump lowers the order: the result is flagged, and it still converges
    assert r.status[0] == 8 and "jumped" in r.message
    errs = [np.max(np.abs(pf.solve_diffusion(G, 1.0, sa, rtol=rt).area[0] - ref_.area[0]))
            for rt in (1e-5, 1e-7, 1e-9)]
    assert errs[2] < errs[0] / 5, errs     # converges (at reduced order), hence flagged
    assert np.max(np.abs(r.area + r.detached_area - 1)) < IDENTITY
    assert np.max(np.abs(r.load - 1.0 - r.detached_load)) < 1e-11
    if direction < 0:     # the mass below the new wall is cut at once (and more drains)
        from scipy.integrate import quad
        cut = quad(lambda s: float(pf.images_density(s, 1.0, 1.0)), 0.0, 0.5)[0]
        assert r.area[0, 3] < r.area[0, 2] - cut
        assert r.area[0, 3] > r.area[0, 2] - cut - 0.05


def test_wall_moving_right_fast_stays_bounded():
    G = np.concatenate([[0.0], np.geomspace(1e-2, 10.0, 30)])
    sa = 1.0 - 10.0 * G                  # sweeps through the whole distribution
    r = pf.solve_diffusion(G, 1.0, sa, method="cn")
    assert np.all(np.isfinite(r.area))
    assert np.all((r.area >= -BOUNDS) & (r.area <= 1 + BOUNDS))
    exact = pf.linear_boundary_area(1.0, G, 1.0, -10.0)
    # either within tolerance or flagged
    assert within(r.area[0], exact, atol=1e-10) < 1 or not r.success


def test_sigma0_much_larger_than_sqrtG():
    r = pf.solve_diffusion(np.geomspace(1.0, 1e4, 9), 1e6)
    assert np.all(np.abs(r.area - 1) < 1e-12)


# --- sweeps ------------------------------------------------------------------------------
def test_serial_equals_parallel_bitwise():
    G = np.geomspace(1e-4, 1e4, 25)
    p = np.geomspace(1e-3, 1e2, 37)
    sa = np.outer(np.linspace(0, 0.5, 37), np.ones(25)) + 0.01 * np.sqrt(G)[None, :]
    a, _ = run_sweep(G, sa, p, rtol=1e-6, parallel=False)
    b, _ = run_sweep(G, sa, p, rtol=1e-6, parallel=True)
    for key in ("area", "load", "detached_area", "detached_load", "status"):
        assert np.array_equal(a[key], b[key]), key


def test_convergence_order():
    """Error of the extrapolated result falls at least as h^3 (rtol ~ h^4 by design)."""
    sigma0 = 1.0
    G = np.geomspace(1.0, 1e6, 13)
    exact = pf.images_area(sigma0, G)
    errs = []
    for rtol in (1e-5, 1e-5 / 16, 1e-5 / 256):
        r = pf.solve_diffusion(G, sigma0, rtol=rtol)
        errs.append(np.max(np.abs(r.area[0] - exact) / exact))
    orders = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all(orders > 3.0), (errs, orders)


# --- twins of the compiled building blocks ------------------------------------------------
def test_thomas_matches_solve_banded():
    rng = np.random.default_rng(1)
    n = 200
    lo, up = rng.normal(size=n), rng.normal(size=n)
    di = 3 + np.abs(lo) + np.abs(up)
    rhs = rng.normal(size=n)
    x = np.empty(n)
    thomas(lo, di, up, rhs, np.empty(n), x)
    assert np.max(np.abs(x - ref.thomas(lo, di, up, rhs))) < TWIN * np.max(np.abs(x)) * n


@pytest.mark.parametrize("scale", [1e-3, 1.0, 1e6])
def test_thomas_continuants_stay_in_range(scale):
    """The continuant form of the Thomas algorithm on systems whose pivot products leave the
    double range without rescaling (2000 rows, pivots ~1e-3 ... ~1e6), solved in place."""
    rng = np.random.default_rng(2)
    n = 2000
    lo, up = rng.uniform(-0.3, 0.3, size=n) * scale, rng.uniform(-0.3, 0.3, size=n) * scale
    di = (1.0 + rng.uniform(size=n)) * scale
    x_true = rng.normal(size=n)
    rhs = di * x_true
    rhs[1:] += lo[1:] * x_true[:-1]
    rhs[:-1] += up[:-1] * x_true[1:]
    if scale != 1.0:  # a plain product of the pivots would leave the double range
        assert abs(np.sum(np.log10(di))) > 400
    x = rhs.copy()
    thomas(lo, di, up, x, np.empty(n), x)
    assert np.all(np.isfinite(x))
    assert np.max(np.abs(x - x_true)) < 1e-12 * np.max(np.abs(x_true))
    assert np.max(np.abs(x - ref.thomas(lo, di, up, rhs))) < TWIN * np.max(np.abs(x)) * n


@pytest.mark.parametrize("n_nodes", [3, 4, 5, 6, 7, 61, 62])
@pytest.mark.parametrize("theta", [0.5, 1.0])
def test_theta_step_any_size(n_nodes, theta):
    """The twisted solve meets in the middle row: odd and even interior counts, down to one."""
    h = 0.3
    xi = np.arange(n_nodes) * h
    p = (xi + 0.1) * np.exp(-(xi - 0.4) ** 2)
    p[0] = p[-1] = 0.0
    expected = ref.theta_step(p, h, -0.5, 1.02, 0.07, theta)
    got = p.copy()
    theta_step(got, h, -0.5, 1.02, 0.07, theta, *[np.empty(n_nodes) for _ in range(3)])
    assert np.max(np.abs(got - expected)) < TWIN * 100


def test_theta_step_large_steps_many_nodes():
    """A theta step whose pivots (~dt/h^2 = 2e4) overflow a product over 2000 nodes."""
    n_nodes = 2000
    h = 5e-3
    xi = np.arange(n_nodes) * h
    p = xi * np.exp(-xi**2)
    p[0] = p[-1] = 0.0
    expected = ref.theta_step(p, h, 0.0, 1.0, 0.5, 0.5)
    got = p.copy()
    theta_step(got, h, 0.0, 1.0, 0.5, 0.5, *[np.empty(n_nodes) for _ in range(3)])
    assert np.all(np.isfinite(got))
    assert np.max(np.abs(got - expected)) < TWIN * 100


@pytest.mark.parametrize("theta", [0.5, 1.0])
@pytest.mark.parametrize("drift", [0.0, 3.0, -7.0])
def test_theta_step_matches_dense(theta, drift):
    n_nodes = 60
    h = 0.1
    xi = np.arange(n_nodes) * h
    p = xi * np.exp(-xi**2)
    p[0] = p[-1] = 0.0
    diff = 1.0 + (drift * h) ** 2 / 12
    expected = ref.theta_step(p, h, drift, diff, 0.05, theta)
    got = p.copy()
    scratch = [np.empty(n_nodes) for _ in range(3)]
    theta_step(got, h, drift, diff, 0.05, theta, *scratch)
    assert np.max(np.abs(got - expected)) < TWIN * 100
