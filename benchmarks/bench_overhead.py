"""Per-call overhead of one pressure: the public Python path against the bare kernel.

Run::

    python -m pytest benchmarks/bench_overhead.py --benchmark-only --benchmark-columns=median,iqr

The same one-pressure problem (the seed scene's G on its default magnification grid, no
adhesion, rtol 1e-6) through ``pf.solve_diffusion`` (validation, scaling, result object),
through ``pf.solve_contact`` (plus G(zeta) from the spectrum), and through the compiled
``embed.diffusion_area`` called from Python (numba dispatch only). The difference of the
medians is the overhead of the Python layer per call.
"""
import numpy as np
import pytest

import persson_fast as pf
from persson_fast import embed

RTOL = 1e-6
PRESSURE = 1e7


@pytest.fixture(scope="module")
def scene():
    s = pf.seed_scene()
    e_star = pf.seed_e_star()
    z = pf.default_zeta(s)
    G = np.asarray(s.diffusion_time(z * s.q0, e_star), dtype=float)
    G[0] = 0.0
    embed.diffusion_area(G, np.zeros_like(G), PRESSURE, RTOL)      # compile / load
    pf.solve_diffusion(G, PRESSURE, 0.0, rtol=RTOL, parallel=False)
    return s, e_star, G


def test_one_pressure_kernel(benchmark, scene):
    benchmark.group = "one pressure"
    _, _, G = scene
    sa = np.zeros_like(G)
    area, status = benchmark(embed.diffusion_area, G, sa, PRESSURE, RTOL)
    assert status == 0
    assert abs(area - pf.images_area(PRESSURE, G[-1])) <= RTOL * area


def test_one_pressure_solve_diffusion(benchmark, scene):
    benchmark.group = "one pressure"
    _, _, G = scene
    r = benchmark(pf.solve_diffusion, G, PRESSURE, 0.0, method="cn", rtol=RTOL, parallel=False)
    assert r.success


def test_one_pressure_solve_contact_cn(benchmark, scene):
    benchmark.group = "one pressure"
    s, e_star, _ = scene
    r = benchmark(pf.solve_contact, s, PRESSURE, e_star=e_star, method="cn", rtol=RTOL,
                  parallel=False)
    assert r.success


def test_one_pressure_solve_contact_closed_form(benchmark, scene):
    benchmark.group = "one pressure"
    s, e_star, _ = scene
    r = benchmark(pf.solve_contact, s, PRESSURE, e_star=e_star, rtol=RTOL)
    assert r.success and r.method == "analytic"


CLOSED_FORM_PRESSURES = np.geomspace(1e3, 1e8, 10_000)
SELF_AFFINE = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)


def test_closed_form_10k_solve_contact(benchmark):
    """The closed form through solve_contact (final areas; the A(zeta) profiles are computed
    only when read), 10,000 pressures: compare with test_closed_form_10k_bare_erf."""
    benchmark.group = "closed form, 10k pressures"
    r = benchmark(pf.solve_contact, SELF_AFFINE, CLOSED_FORM_PRESSURES, e_star=1e9)
    assert r.method == "analytic"


def test_closed_form_10k_bare_erf(benchmark):
    """The bare NumPy/SciPy erf(p / 2 sqrt(G1)) of the same pressures (G1 computed once)."""
    from scipy.special import erf

    benchmark.group = "closed form, 10k pressures"
    g1 = float(SELF_AFFINE.diffusion_time(SELF_AFFINE.q1, 1e9))
    a = benchmark(lambda: erf(CLOSED_FORM_PRESSURES / (2.0 * np.sqrt(g1))))
    r = pf.solve_contact(SELF_AFFINE, CLOSED_FORM_PRESSURES, e_star=1e9)
    np.testing.assert_allclose(r.area, a, rtol=1e-14)
