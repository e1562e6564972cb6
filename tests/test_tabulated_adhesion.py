"""Tabulated spectra with adhesion on any node layout (issue 12, item 3).

A table C = 1e-22 (q/1e4)^-3.6 on q in [1e4, 1e9] is, node for node, the self-affine
spectrum H = 0.8 (2(1+H) = 3.6), C0 = 1e-22 m^4, q0 = 1e4, q1 = 1e9 /m: TabulatedPSD
interpolates log-log, which is exact for a power law (the exponent of each segment is
-3.6 up to rounding), so both spectra have the same moments to ~1e-14. The areas with
adhesion must then agree:

- on the same zeta grid: within the contract, rtol A + ATOL (observed: 1e-14 relative);
- each on its own default grid (the table's nodes are breakpoints of its grid, so the two
  discretisations differ): within rtol A plus the two reported error estimates.

Before the fix, the table's nodes merged with the log-spaced points of the adhesion grid left
cells one ulp wide: q = zeta q0 repeated on the refined grid, dq = 0, NaN weights, and
A = [0, 0, 0.307] flagged as a wall jump where the analytic spectrum gives
[0.0233, 0.230, 0.991].
"""
import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import persson_fast as pf
from persson_fast.adhesion.zeta_grid import (BREAKPOINT_MERGE_RTOL, ZETA_MERGE_FRACTION, _scene_arrays,
                                   adhesion_zeta, refine_zeta)
from tolerances import ATOL

Q0, Q1, C0, HURST = 1e4, 1e9, 1e-22, 0.8
E_STAR = 1e9                      # [Pa]
DGAMMA = 0.05                     # [J/m^2]
BETA = 2 ** -0.5
PRESSURES = np.array([1e5, 1e6, 1e7])   # [Pa]
#: the issue's tolerance: this scene's default grids are small, so the file stays fast
RTOL = 1e-4
ANALYTIC = pf.SelfAffine(HURST, Q0, Q1, C0=C0)


def power_law(q):
    return C0 * (q / Q0) ** (-2.0 * (1.0 + HURST))


def log_nodes(n):
    return np.logspace(4, 9, n)


def random_nodes(n, seed):
    rng = np.random.default_rng(seed)
    inner = 10.0 ** rng.uniform(4.0, 9.0, n - 2)
    return np.unique(np.concatenate(([Q0], inner, [Q1])))


def with_ulp_duplicates(q, seed, fraction=0.5):
    """q plus, for a random share of its nodes and for both ends, a node one ulp away."""
    rng = np.random.default_rng(seed)
    inner = q[1:-1][rng.random(q.size - 2) < fraction]
    extra = [np.nextafter(inner, np.inf), [np.nextafter(q[0], np.inf)],
             [np.nextafter(q[-1], -np.inf)]]
    return np.unique(np.concatenate([q, *extra]))


LAYOUTS = {
    **{f"log{n}": log_nodes(n) for n in (6, 7, 11, 21, 41, 51, 64, 101)},
    **{f"random{n}-seed{s}": random_nodes(n, s) for n, s in ((6, 1), (17, 2), (50, 3), (101, 4))},
    **{f"log{n}-ulp": with_ulp_duplicates(log_nodes(n), n) for n in (6, 21, 101)},
    "random40-ulp": with_ulp_duplicates(random_nodes(40, 5), 5, fraction=1.0),
}


def table(q):
    return pf.TabulatedPSD(q, power_law(q))


def solve(surface, zeta=None):
    return pf.solve_contact(surface, PRESSURES, e_star=E_STAR, work_of_adhesion=DGAMMA,
                            rtol=RTOL, zeta=zeta)


@pytest.fixture(scope="module")
def analytic():
    r = solve(ANALYTIC)
    assert np.all(r.status == 0), r.message
    return r


def assert_no_nan(r):
    for name in ("area", "area_zeta", "sigma_a", "gamma_eff", "elastic_energy_zeta", "load_zeta",
                 "error_estimate"):
        arr = np.asarray(getattr(r, name))
        assert np.all(np.isfinite(arr)), f"{name} has non-finite entries"


def check_layout(q, analytic):
    r = solve(table(q))
    assert_no_nan(r)
    assert np.all(r.status == 0), r.message
    # the same spectrum on the same grid: the contract
    same = solve(ANALYTIC, zeta=r.zeta)
    assert np.all(same.status == 0), same.message
    err = np.abs(r.area - same.area)
    assert np.all(err <= RTOL * same.area + ATOL), (r.area, same.area)
    prof = np.abs(r.area_zeta - same.area_zeta)
    assert np.all(prof <= RTOL * same.area_zeta + ATOL)
    # each on its own default grid: each within its error estimate of the exact area
    tol = RTOL * analytic.area + r.error_estimate + analytic.error_estimate + ATOL
    assert np.all(np.abs(r.area - analytic.area) <= tol), (r.area, analytic.area, tol)
    return r


@pytest.mark.parametrize("name", list(LAYOUTS))
def test_tabulated_area_equals_analytic(name, analytic):
    check_layout(LAYOUTS[name], analytic)


def test_issue_example(analytic):
    """The issue's numbers: 21 log-spaced nodes gave A = [0, 0, 0.307], flagged."""
    r = check_layout(log_nodes(21), analytic)
    assert np.allclose(r.area, [0.0233, 0.230, 0.991], rtol=0.01)


def check_grid(q):
    """The adhesion grid keeps every table node (merged within BREAKPOINT_MERGE_RTOL), leaves
    no gap wider than the log spacing allows, and every grid of the nested family gives
    finite kernel inputs."""
    s = table(q)
    zeta1 = Q1 / Q0
    per_decade = 8
    z = adhesion_zeta(s, per_decade=per_decade)
    assert z[0] == 1.0 and z[-1] == zeta1 and np.all(np.diff(z) > 0)
    assert np.all(np.diff(z) > BREAKPOINT_MERGE_RTOL * z[1:])
    nodes = q[(q > Q0) & (q < Q1)] / Q0
    dist = np.min(np.abs(np.log(z)[None, :] - np.log(nodes)[:, None]), axis=1)
    assert np.all(dist <= 2 * BREAKPOINT_MERGE_RTOL)
    # a dropped log-spaced point widens each of its two cells by at most the merge distance
    h = np.log(10.0) / per_decade
    assert np.max(np.diff(np.log(z))) <= (1 + 2 * ZETA_MERGE_FRACTION) * h * (1 + 1e-9)
    for grid in (z, refine_zeta(z), refine_zeta(refine_zeta(z))):
        G, c, wa, wb, scale, G_dim = _scene_arrays(s, grid, E_STAR, DGAMMA, BETA)
        for arr in (G, c, wa, wb, G_dim):
            assert np.all(np.isfinite(arr))
        assert np.all(np.diff(G) >= 0) and np.all(wa >= 0) and np.all(wb >= 0)
        m2 = s.moment(2, grid[:-1] * Q0, grid[1:] * Q0) * 0.5 * np.pi * E_STAR / DGAMMA
        assert np.allclose(wa + wb, m2, rtol=1e-8, atol=0.0)


@pytest.mark.parametrize("name", list(LAYOUTS))
def test_adhesion_grid_on_table(name):
    check_grid(LAYOUTS[name])


@settings(max_examples=15, deadline=None)
@given(n=st.integers(6, 101), seed=st.integers(0, 2**31 - 1),
       fraction=st.sampled_from([0.0, 0.3, 1.0]))
def test_adhesion_grid_on_random_tables(n, seed, fraction):
    check_grid(with_ulp_duplicates(random_nodes(n, seed), seed, fraction))


def ulp_user_grid():
    """The analytic spectrum's grid with a point one ulp above each inner node, and one
    whose scaled q repeats its neighbour's (dq = 0 after zeta * q0)."""
    z = adhesion_zeta(ANALYTIC, RTOL)
    up = np.nextafter(z[1:-1], np.inf)
    repeat = up[up * Q0 == z[1:-1] * Q0]
    assert repeat.size > 0             # some zeta one ulp apart give the same q
    return z, np.unique(np.concatenate([z, up]))


def test_ulp_user_grid_gives_finite_inputs():
    _, zu = ulp_user_grid()
    for grid in (zu, refine_zeta(zu)):
        q = grid * Q0
        G, c, wa, wb, _, _ = _scene_arrays(ANALYTIC, grid, E_STAR, DGAMMA, BETA)
        for arr in (G, c, wa, wb):
            assert np.all(np.isfinite(arr))
        empty = np.diff(q) == 0
        assert np.any(empty) and np.all(wa[empty] == 0) and np.all(wb[empty] == 0)


def test_ulp_user_grid_gives_the_clean_grids_area():
    z, zu = ulp_user_grid()
    clean, dup = solve(ANALYTIC, zeta=z), solve(ANALYTIC, zeta=zu)
    assert_no_nan(dup)
    assert np.all(dup.status == 0), dup.message
    assert np.all(np.abs(dup.area - clean.area) <= RTOL * clean.area + ATOL)


def test_refine_zeta_on_narrow_cells():
    """Cells 0..4 ulps wide: the refined grid nests the coarse one, keeps its points in
    order, and puts a point strictly inside every cell at least 2 ulps wide."""
    base = 1.7
    z = [1.0, base]
    for k in range(5):
        nxt = z[-1]
        for _ in range(k):
            nxt = np.nextafter(nxt, np.inf)
        z.append(nxt)
        z.append(z[-1] * 1.3)
    z = np.array(z)
    f = refine_zeta(z)
    assert np.array_equal(f[0::2], z)
    assert np.all(np.diff(f) >= 0)
    lo, hi, mid = z[:-1], z[1:], f[1::2]
    wide = hi > np.nextafter(lo, np.inf)
    assert np.all((mid[wide] > lo[wide]) & (mid[wide] < hi[wide]))


@pytest.mark.slow
@pytest.mark.parametrize("n", range(6, 102))
def test_node_count_sweep(n, analytic):
    """Every node count from 6 to 101: log-spaced, random, random with ulp duplicates."""
    check_layout(log_nodes(n), analytic)
    check_layout(random_nodes(n, 1000 + n), analytic)
    check_layout(with_ulp_duplicates(random_nodes(n, 2000 + n), n), analytic)
