"""The adhesive fixed point (seed Eqs. 8-9): limits, bookkeeping, monotonicity, hard cases."""
import numpy as np
from hypothesis import given, settings, strategies as st

import persson_fast as pf
from persson_fast.adhesion.zeta_grid import adhesion_zeta
from persson_fast.adhesion.fixed_point import solve_adhesive_contact

SEED = pf.seed_scene()
E_STAR = 2.9e9 / (1 - 0.3**2)
DGAMMA = 0.06
#: bookkeeping identities of every adhesive run (issue contract: 1e-8 relative)
BOOKS = 1e-8
#: seed-scene areas at p = 0, 10 MPa, 100 MPa from an rtol = 1e-9 solve (regression values;
#: rtol = 1e-6 results agree to 8e-7, rtol = 1e-4 to 2e-5)
SEED_REFERENCE = np.array([0.48482033, 0.56202034, 0.81118054])


def seed(p, rtol=1e-4, **kw):
    return pf.solve_contact(SEED, p, e_star=E_STAR, work_of_adhesion=kw.pop("dg", DGAMMA),
                            rtol=rtol, **kw)


def check_books(r):
    scale = np.maximum(np.abs(r.pressure), np.max(np.abs(r.sigma_a), axis=1))
    assert np.all(np.abs(r.area + r.detached_area - 1) <= BOOKS)
    assert np.all(np.abs(r.load - r.pressure - r.detached_load) <= BOOKS * scale)
    assert np.all((r.area >= 0) & (r.area <= 1))


def test_seed_regression_default_tolerance():
    r = seed(np.array([0.0, 1e7, 1e8]), rtol=1e-6)
    assert r.success, r.message
    assert np.all(np.abs(r.area - SEED_REFERENCE) <= 2e-6 * SEED_REFERENCE)
    assert np.all(r.sticky)
    check_books(r)


def test_seed_regression_loose_tolerance():
    r = seed(np.array([0.0, 1e7, 1e8]), rtol=1e-4)
    assert r.success, r.message
    assert np.all(np.abs(r.area - SEED_REFERENCE) <= 1e-4 * SEED_REFERENCE)


def test_vanishing_adhesion_reproduces_images():
    p = np.array([1e6, 1e7, 1e8])
    r = seed(p, rtol=1e-6, dg=1e-16)
    assert r.success, r.message
    exact = pf.images_area(p, float(SEED.diffusion_time(SEED.q1, E_STAR)))
    assert np.all(np.abs(r.area - exact) <= 1e-6 * exact + 1e-12)
    assert not np.any(r.sticky)


def test_area_rises_with_work_of_adhesion():
    areas = [seed(1e7, dg=dg).area[0] for dg in (0.0, 0.01, 0.03, 0.06, 0.1)]
    assert np.all(np.diff(areas) > 0), areas


def test_adhesion_raises_the_area_at_every_pressure():
    p = np.linspace(0, 1e8, 9)
    ra = seed(p)
    r0 = pf.solve_contact(SEED, p, e_star=E_STAR)
    assert np.all(ra.area >= r0.area)
    assert np.all(np.diff(ra.area) > 0)          # and rises with the pressure


def test_profiles_and_energies():
    r = seed(np.array([1e7]))
    assert r.zeta[0] == 1.0 and r.area_zeta[0, 0] == 1.0
    g = r.gamma_eff[0]
    assert abs(g[-1] - DGAMMA) < 1e-12                 # gamma_eff(zeta1) = dgamma (Eq. 9)
    assert r.elastic_energy_zeta[0, -1] == 0.0              # nothing stored below the cut-off
    assert np.all(np.diff(r.elastic_energy_zeta[0]) <= 1e-15)
    beta = 2**-0.5
    q = r.zeta * SEED.q0
    expect = beta * np.sqrt(np.maximum(g, 0) * E_STAR * q)  # Eq. 8 on the returned profile
    assert np.allclose(r.sigma_a[0], expect, rtol=1e-3, atol=1e-3 * expect.max())


def test_zeta_grid_convergence_order():
    """A(zeta1) on nested grids: the error before extrapolation falls by ~4 per doubling."""
    s = SEED
    areas = []
    for per_decade in (6, 12, 24):
        z = adhesion_zeta(s, per_decade=per_decade)
        G, c, wa, wb, scale, _ = pf.adhesion._scene_arrays(s, z, E_STAR, DGAMMA, 2**-0.5)
        outs, status, *_ = pf.adhesion._run(G, c, wa, wb, -1.0, np.array([1e7 / scale]), 1e-8,
                                            False, pf.adhesion._controls(None))
        assert status[0] == 0
        areas.append(outs[0][0, -1])
    d1, d2 = areas[1] - areas[0], areas[2] - areas[1]
    assert 3.0 < d1 / d2 < 5.0, (areas, d1 / d2)


def test_anderson_and_plain_relaxation_agree():
    p = np.array([0.0, 5e7])
    a = seed(p, rtol=1e-5)
    b = seed(p, rtol=1e-5, adhesion_controls={"m_hist": 0, "omega": 0.5})
    assert a.success and b.success
    assert np.all(np.abs(a.area - b.area) <= 1e-5 * a.area)
    assert np.all(a.iterations < b.iterations)


def test_unconverged_is_flagged():
    r = seed(np.array([1e7]), adhesion_controls={"max_iter": 2})
    assert not r.success and r.status[0] == 6
    assert "residual" in r.message


def test_serial_equals_parallel():
    p = np.linspace(-2e5, 5e7, 6)
    a = seed(p, parallel=False)
    b = seed(p, parallel=True)
    assert np.array_equal(a.area, b.area) and np.array_equal(a.sigma_a, b.sigma_a)


# --- hard cases --------------------------------------------------------------------------
def test_pressure_range_to_1GPa_and_tension():
    p = np.array([-5e5, -1e5, 0.0, 1e6, 1e8, 1e9])
    r = seed(p)
    assert r.success, r.message
    check_books(r)
    assert r.area[-1] > 0.999


def test_pull_off_brackets_the_contact():
    sigma_c, info = pf.pull_off(SEED, e_star=E_STAR, work_of_adhesion=DGAMMA, rtol=1e-4,
                                full_output=True)
    assert 5e5 < sigma_c < 1e6
    lo, hi = info["bracket"]
    assert hi - lo <= 1e-4 * sigma_c * 1.01
    z = adhesion_zeta(SEED, 1e-4)
    r0 = solve_adhesive_contact(SEED, [0.0], z, e_star=E_STAR, work_of_adhesion=DGAMMA,
                                rtol=1e-4, zeta_given=True)
    inside = solve_adhesive_contact(SEED, [-lo], z, e_star=E_STAR, work_of_adhesion=DGAMMA,
                                    rtol=1e-4, start=r0.sigma_a, zeta_given=True)
    outside = seed(-1.05 * sigma_c)
    assert inside.area[0] > 0.3 and outside.area[0] == 0.0


def test_not_sticky_gamma_eff_crosses_zero():
    r = seed(np.array([1e7]), dg=0.01)
    assert r.success, r.message
    g = r.gamma_eff[0]
    assert not r.sticky[0] and g[0] <= 0 < g[-1]         # crosses zero inside the zeta range
    assert np.all(r.sigma_a[0][g <= 0] == 0)
    assert pf.pull_off(SEED, e_star=E_STAR, work_of_adhesion=0.01, rtol=1e-3) == 0.0


def test_energy_correction_variant():
    p = np.array([1e7])
    r1 = seed(p)
    rs = seed(p, energy_correction=0.45)
    assert rs.success, rs.message
    check_books(rs)
    # S <= 1 stores less elastic energy, so more adhesion and more contact
    assert rs.area[0] > r1.area[0]


def test_self_affine_zeta1_1e6():
    s = pf.SelfAffine(hurst=0.8, q0=1e3, q1=1e9, h_rms=1e-6)
    r = pf.solve_contact(s, np.array([1e5, 1e6, 1e7]), e_star=1e9, work_of_adhesion=0.05,
                         rtol=1e-4)
    assert np.all(np.isfinite(r.area)) and np.all((r.area >= 0) & (r.area <= 1))
    assert r.success or r.message        # converged, or clearly flagged
    if r.success:
        check_books(r)


@settings(max_examples=12, deadline=None, database=None, derandomize=True)
@given(hurst=st.floats(0.2, 1.0), h_rms=st.floats(1e-8, 1e-6), dg=st.floats(1e-3, 0.1),
       frac=st.floats(0.0, 3.0))
def test_properties_self_affine(hurst, h_rms, dg, frac):
    s = pf.SelfAffine(hurst=hurst, q0=1e4, q1=1e7, h_rms=h_rms)
    e_star = 1e9
    p = frac * e_star * s.slope_rms() / (2 * np.sqrt(2))
    r = pf.solve_contact(s, p, e_star=e_star, work_of_adhesion=dg, rtol=1e-4)
    assert np.all(np.isfinite(r.area)) and 0.0 <= r.area[0] <= 1.0
    if r.success:
        check_books(r)
        r0 = pf.solve_contact(s, p, e_star=e_star)
        assert r.area[0] >= r0.area[0] * (1 - 1e-4) - 1e-12


def test_whole_anderson_steps_are_the_cheaper_default():
    """omega = 1 (the default) reaches the half-step fixed point within rtol, in fewer
    iterations (summed over the zeta levels) on every pressure of the seed scene."""
    p = np.linspace(0.0, 1e8, 6)
    a = seed(p, rtol=1e-4)
    b = seed(p, rtol=1e-4, adhesion_controls={"omega": 0.5})
    assert pf.adhesion.ADHESION_DEFAULTS["omega"] == 1.0
    assert a.success and b.success
    assert np.all(np.abs(a.area - b.area) <= 1e-4 * a.area)
    assert np.all(a.iterations < b.iterations), (a.iterations, b.iterations)


def test_defaults_baked_into_compiled_entry_points_live_in_kernel_files():
    """embed's compiled entry points bake the fixed point's default controls
    (``DEFAULT_*`` of the kernel file) in at compile time; they must live in a file whose
    change invalidates cached kernels, and ADHESION_DEFAULTS must be those values."""
    from pathlib import Path

    from persson_fast import _jit
    from persson_fast._kernels import adhesion as kern

    assert Path(kern.__file__).resolve() in {p.resolve() for p in _jit._kernel_paths()}
    assert pf.adhesion.ADHESION_DEFAULTS == {
        "max_iter": kern.DEFAULT_MAX_ITER, "m_hist": kern.DEFAULT_M_HIST,
        "omega": kern.DEFAULT_OMEGA, "n_damp": kern.DEFAULT_N_DAMP}


def test_tension_takes_at_most_half_steps():
    """In nominal tension the relaxation factor is capped at TENSION_OMEGA (whole steps lose
    the end of the contact branch sooner near the pull-off stress): omega = 1 and 0.5 give
    bitwise the same result there, and different ones in compression."""
    from persson_fast._kernels.adhesion import TENSION_OMEGA

    assert TENSION_OMEGA == 0.5
    tension = np.array([-2e5, -5e5])
    a = seed(tension, adhesion_controls={"omega": 1.0})
    b = seed(tension, adhesion_controls={"omega": 0.5})
    assert a.success and np.all(a.area > 0)
    assert np.array_equal(a.area, b.area) and np.array_equal(a.iterations, b.iterations)
    c = seed(np.array([1e7]), adhesion_controls={"omega": 1.0})
    d = seed(np.array([1e7]), adhesion_controls={"omega": 0.5})
    assert not np.array_equal(c.iterations, d.iterations)


def test_ladder_start_interpolates_cubically_and_predicts_the_finer_level():
    """The start of a finer zeta level: the coarser level's values at its nodes, their cubic
    interpolant (in ln zeta) at the midpoints, exact for cubics on an uneven grid (linear in
    the end cells, clipped at 0), plus the second-order prediction (x_k - x_k-1)/4."""
    from persson_fast.adhesion.ladder import _midpoints_cubic, _Solution, _ZetaLadder
    from persson_fast.adhesion.zeta_grid import refine_zeta

    u = np.cumsum(np.r_[0.0, np.linspace(0.1, 0.4, 9)])
    cubic = lambda v: 0.3 + v - 0.5 * v**2 + 0.2 * v**3      # noqa: E731
    out = _midpoints_cubic(u, cubic(u)[None, :])[0]
    mid = 0.5 * (u[:-1] + u[1:])
    assert np.array_equal(out[0::2], cubic(u))
    np.testing.assert_allclose(out[3:-2:2], cubic(mid[1:-1]), rtol=1e-13)
    assert out[1] == 0.5 * (cubic(u[0]) + cubic(u[1]))
    assert np.all(_midpoints_cubic(u, np.where(u < 1.0, 0.0, 1.0)[None, :]) >= 0.0)

    # a level whose value is f + h^2 g (h the cell width in ln zeta): from levels 0 and 1 the
    # start of level 2 is f + h2^2 g at level 1's nodes (g, f linear: no interpolation error)
    z1 = np.exp(np.linspace(0.0, 4.0, 9))
    grids = [z1[0::2], z1, refine_zeta(z1)]
    f = lambda z: 2.0 + np.log(z)                             # noqa: E731
    g = lambda z: 3.0 + 0.5 * np.log(z)                        # noqa: E731
    h = [1.0, 0.5, 0.25]
    ladder = _ZetaLadder(z1, 1, None)
    ladder.std = grids
    ladder.sol = [[_Solution([np.zeros(z.size), f(z) + h[k] ** 2 * g(z)], 0, z, None)]
                  for k, z in enumerate(grids[:2])]
    start = ladder._start_from(1, np.arange(1))[0]
    np.testing.assert_allclose(start, f(grids[2]) + h[2] ** 2 * g(grids[2]), rtol=1e-13)
