"""Every validation rule of the public API: a ValueError that names the argument (and the value).

API.md: "Bad input ... is a ValueError naming the argument, the rule and the offending value";
an unknown method lists the valid ones. Valid edge inputs must not raise.
"""
import contextlib
import re

import numpy as np
import pytest

import persson_fast as pf

G3 = np.array([0.0, 1.0, 4.0])
SURFACE = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e8, h_rms=1e-7)
E_STAR = 1e9


@contextlib.contextmanager
def raises(match, *names):
    """pytest.raises(ValueError, match=match), then re.search each regex of `names` in it."""
    with pytest.raises(ValueError, match=match) as info:
        yield info
    msg = str(info.value)
    for name in names:
        assert re.search(name, msg), (name, msg)


def lit(text):
    """Regex for a literal piece of a message."""
    return re.escape(text)


def num(x):
    """Regex for the offending value x as shown in a message.

    Accepts numpy's scalar repr ``np.float64(x)`` beside the plain ``x``: which one a message
    shows is checked once, in test_messages_show_plain_numbers.
    """
    return rf"(?:np\.float64\()?{re.escape(repr(float(x)))}\)?"


# =============================================================================================
# solve_diffusion
# =============================================================================================
@pytest.mark.parametrize("method", ["foo", "CN-fast", "", 3])
def test_diffusion_unknown_method_lists_valid(method):
    # (method=None is the default: "cn" for one wall, "auto" with a yield wall)
    with raises(r"^method must be one of", "'analytic'", "'cn'", "'auto'", lit(repr(method))):
        pf.solve_diffusion(G3, 1.0, method=method)


def test_diffusion_G_decreasing():
    with raises(r"^G must be non-decreasing \[Pa\^2\]",
                rf"got G\[1\] = {num(2.0)} > G\[2\] = {num(1.0)}$"):
        pf.solve_diffusion([0.0, 2.0, 1.0], 1.0)


def test_diffusion_G_negative():
    with raises(r"^G must be >= 0 \[Pa\^2\]; got G\[0\] = -1\.0"):
        pf.solve_diffusion([-1.0, 0.0, 1.0], 1.0)


@pytest.mark.parametrize("bad, shown", [(np.nan, "nan"), (np.inf, "inf"), (-np.inf, "-inf")])
def test_diffusion_G_not_finite(bad, shown):
    with raises(rf"^G must be finite \[Pa\^2\]; got G\[1\] = {re.escape(shown)}$"):
        pf.solve_diffusion([0.0, bad, 2.0], 1.0)


def test_diffusion_G_empty():
    with raises(r"^G must hold at least one diffusion time \[Pa\^2\]", "empty"):
        pf.solve_diffusion([], 1.0)


def test_diffusion_G_two_dimensional():
    with raises(r"^G must have 1 dimension", lit("shape (2, 2)")):
        pf.solve_diffusion(np.ones((2, 2)), 1.0)


def test_diffusion_G_not_numeric():
    with raises(r"^G must be a real number or array", lit("'abc'")):
        pf.solve_diffusion("abc", 1.0)


@pytest.mark.parametrize("bad, shown", [(np.nan, "nan"), (np.inf, "inf")])
def test_diffusion_pressure_not_finite(bad, shown):
    with raises(rf"^pressure must be finite \[Pa\]; got pressure\[1\] = {shown}$"):
        pf.solve_diffusion(G3, [1.0, bad])


def test_diffusion_pressure_scalar_nan_names_argument():
    with raises(r"^pressure must be finite \[Pa\]; got pressure = nan$"):
        pf.solve_diffusion(G3, np.nan)


def test_diffusion_negative_pressure_without_wall():
    with raises(r"^pressure must be >= 0 \[Pa\] without adhesion",
                rf"got pressure\[1\] = {num(-0.5)}$"):
        pf.solve_diffusion(G3, [1.0, -0.5])


def test_diffusion_negative_pressure_scalar_without_wall():
    with raises(r"^pressure must be >= 0 \[Pa\]", rf"got pressure = {num(-2.0)}$"):
        pf.solve_diffusion(G3, -2.0, sigma_a=0.0)


def test_diffusion_pressure_two_dimensional():
    with raises(r"^pressure must have 0 or 1 dimension", lit("shape (1, 2)")):
        pf.solve_diffusion(G3, [[1.0, 2.0]])


def test_diffusion_sigma_a_wrong_length():
    with raises(r"^sigma_a must have the length of G \(3\) \[Pa\]; got shape \(2,\)$"):
        pf.solve_diffusion(G3, 1.0, [0.1, 0.2])


def test_diffusion_sigma_a_wrong_2d_shape():
    with raises(r"^sigma_a must have shape \(n_p, n_t\) = \(2, 3\) \[Pa\]; got shape \(3, 2\)$"):
        pf.solve_diffusion(G3, [1.0, 2.0], np.zeros((3, 2)))


def test_diffusion_sigma_a_three_dimensional():
    with raises(r"^sigma_a must have 0 or 1 or 2 dimension", lit("shape (1, 1, 3)")):
        pf.solve_diffusion(G3, 1.0, np.zeros((1, 1, 3)))


@pytest.mark.parametrize("bad, shown", [(np.nan, "nan"), (np.inf, "inf")])
def test_diffusion_sigma_a_not_finite(bad, shown):
    with raises(rf"^sigma_a must be finite \[Pa\]; got sigma_a\[2\] = {shown}$"):
        pf.solve_diffusion(G3, 1.0, [0.0, 0.1, bad])


def test_diffusion_sigma_a_2d_not_finite_names_index():
    sa = np.zeros((2, 3))
    sa[1, 2] = np.nan
    with raises(r"^sigma_a must be finite \[Pa\]; got sigma_a\[1,2\] = nan$"):
        pf.solve_diffusion(G3, [1.0, 2.0], sa)


@pytest.mark.parametrize("rtol", [0.0, 1e-13, 0.11, 1.0, -1e-6])
def test_diffusion_rtol_out_of_range(rtol):
    with raises(r"^rtol must lie in \[1e-12, 0\.1\] \[-\]", rf"got rtol = {num(rtol)}$"):
        pf.solve_diffusion(G3, 1.0, rtol=rtol)


@pytest.mark.parametrize("rtol, shown", [(np.nan, "nan"), (np.inf, "inf")])
def test_diffusion_rtol_not_finite(rtol, shown):
    with raises(rf"^rtol must be finite \[-\]; got rtol = {shown}$"):
        pf.solve_diffusion(G3, 1.0, rtol=rtol)


@pytest.mark.parametrize("n_damp", [-1, 1.5, "2", 2.0])
def test_diffusion_n_damp_bad(n_damp):
    with raises(r"^n_damp must be an integer >= 0 \[-\]", lit(f"got n_damp = {n_damp!r}")):
        pf.solve_diffusion(G3, 1.0, n_damp=n_damp)


def test_diffusion_analytic_needs_linear_wall():
    G = np.array([0.0, 1.0, 2.0, 3.0])
    with raises(r"^method 'analytic' cannot serve a sigma_a that is not linear in G", lit("method='cn'")):
        pf.solve_diffusion(G, 1.0, [0.0, 0.5, 0.5, 0.5], method="analytic")


def test_diffusion_analytic_needs_no_jump():
    G = np.array([0.0, 1.0, 1.0, 2.0])
    with raises(r"^method 'analytic' cannot serve a sigma_a that jumps", lit("method='cn'")):
        pf.solve_diffusion(G, 1.0, [0.3, 0.3, 0.5, 0.5], method="analytic")


def test_diffusion_analytic_moving_wall_must_start_at_zero():
    G = np.array([1.0, 2.0, 3.0])
    with raises(r"^method 'analytic' needs the linear wall to start at G = 0", lit("G[0] = 0")):
        pf.solve_diffusion(G, 1.0, 0.5 + 0.1 * G, method="analytic")


# --- valid edge inputs do not raise --------------------------------------------------------
def test_diffusion_pressure_zero_gives_zero_area():
    for method in ("cn", "analytic", "auto"):
        r = pf.solve_diffusion(np.geomspace(1e-2, 1e2, 5), 0.0, method=method)
        assert r.area.shape == (1, 5)
        assert np.all(r.area == 0.0), method


def test_diffusion_scalar_pressure():
    r = pf.solve_diffusion(G3, 2.0)
    assert r.pressure.shape == (1,) and r.area.shape == (1, 3) and r.load.shape == (1, 3)
    assert r.success


def test_diffusion_sigma_a_scalar():
    r = pf.solve_diffusion(G3, [1.0, 2.0], 0.5)
    assert r.sigma_a.shape == (2, 3) and np.all(r.sigma_a == 0.5)
    assert np.all(np.isfinite(r.area)) and r.success, r.message


def test_diffusion_sigma_a_per_time():
    sa = np.array([0.5, 0.4, 0.2])
    r = pf.solve_diffusion(G3, [1.0, 2.0], sa)
    assert r.sigma_a.shape == (2, 3) and np.array_equal(r.sigma_a[1], sa)
    assert np.all(np.isfinite(r.area))


def test_diffusion_negative_pressure_allowed_with_wall():
    r = pf.solve_diffusion(G3, [-0.2, -1.0], 0.5)
    assert np.all(np.isfinite(r.area))
    assert np.all(r.area[1] == 0.0)           # at or below -sigma_a: separated


def test_diffusion_G_flat_stretch():
    G = np.array([0.0, 1.0, 1.0, 1.0, 4.0])
    r = pf.solve_diffusion(G, 1.0, method="cn")
    assert r.area.shape == (1, 5) and np.all(np.isfinite(r.area))
    assert r.area[0, 1] == r.area[0, 2] == r.area[0, 3]


def test_diffusion_single_time():
    r = pf.solve_diffusion([4.0], 1.0)
    assert r.area.shape == (1, 1) and np.isfinite(r.area[0, 0])


@pytest.mark.parametrize("rtol", [1e-12, 0.1])
def test_diffusion_rtol_bounds_accepted(rtol):
    r = pf.solve_diffusion(np.geomspace(1e-2, 1e2, 5), 1.0, rtol=rtol)
    assert np.all(np.isfinite(r.area))


@pytest.mark.parametrize("method", ["CN", "Analytic", "AUTO"])
def test_diffusion_method_case_insensitive(method):
    pf.solve_diffusion(G3, 1.0, method=method)


@pytest.mark.parametrize("n_damp", [0, np.int64(3)])
def test_diffusion_n_damp_valid(n_damp):
    pf.solve_diffusion(G3, 1.0, n_damp=n_damp)


# =============================================================================================
# solve_contact
# =============================================================================================
def contact(**kw):
    args = dict(e_star=E_STAR)
    args.update(kw)
    pressure = args.pop("pressure", 1e5)
    surface = args.pop("surface", SURFACE)
    return pf.solve_contact(surface, pressure, **args)


@pytest.mark.parametrize("e_star", [0.0, -1e9])
def test_contact_e_star_not_positive(e_star):
    with raises(r"^e_star must be > 0 \[Pa\]", rf"got e_star = {num(e_star)}$"):
        contact(e_star=e_star)


@pytest.mark.parametrize("e_star, shown", [(np.nan, "nan"), (np.inf, "inf")])
def test_contact_e_star_not_finite(e_star, shown):
    with raises(rf"^e_star must be finite \[Pa\]; got e_star = {shown}$"):
        contact(e_star=e_star)


def test_contact_negative_pressure_without_adhesion():
    with raises(r"^pressure must be >= 0 \[Pa\] without adhesion",
                rf"got pressure\[2\] = {num(-1.0)}$"):
        contact(pressure=[1e5, 0.0, -1.0])


def test_contact_pressure_nan():
    with raises(r"^pressure must be finite \[Pa\]; got pressure\[0\] = nan$"):
        contact(pressure=[np.nan, 1.0])


@pytest.mark.parametrize("dg", [-0.06, -np.inf, np.nan])
def test_contact_work_of_adhesion_negative_or_nan(dg):
    with raises(r"^work_of_adhesion must be (>= 0|finite) \[J/m\^2\]",
                rf"got work_of_adhesion = {num(dg)}$"):
        contact(work_of_adhesion=dg)


@pytest.mark.parametrize("beta", [0.0, -0.7, np.nan])
def test_contact_detachment_prefactor_not_positive(beta):
    with raises(r"^detachment_prefactor must be (> 0|finite) \[-\]",
                rf"got detachment_prefactor = {num(beta)}$"):
        contact(detachment_prefactor=beta)


@pytest.mark.parametrize("gs", [-0.1, 1.5])
def test_contact_energy_correction_out_of_range(gs):
    with raises(r"^energy_correction must lie in \[0, 1\] \[-\]",
                rf"got energy_correction = {num(gs)}$"):
        contact(energy_correction=gs)


def test_contact_energy_correction_nan():
    with raises(r"^energy_correction must be finite \[-\]; got energy_correction = nan$"):
        contact(energy_correction=np.nan)


def test_contact_zeta_must_start_at_one():
    with raises(r"^zeta must start at 1 \[-\]", rf"got zeta\[0\] = {num(2.0)}$"):
        contact(zeta=[2.0, 10.0, 100.0])


def test_contact_zeta_beyond_q1_over_q0():
    zeta1 = SURFACE.q1 / SURFACE.q0
    with raises(r"^zeta must lie in \[1, q1/q0 = ", lit(repr(zeta1)),
                rf"got zeta\[2\] = {num(2 * zeta1)}$"):
        contact(zeta=[1.0, 10.0, 2 * zeta1])


@pytest.mark.parametrize("zeta", [[1.0, 5.0, 5.0], [1.0, 50.0, 10.0]])
def test_contact_zeta_not_increasing(zeta):
    bad = rf"got zeta\[1\] = {num(zeta[1])} >= zeta\[2\] = {num(zeta[2])}$"
    with raises(r"^zeta must be increasing \[-\]", bad):
        contact(zeta=zeta)


def test_contact_zeta_nan():
    with raises(r"^zeta must be finite \[-\]; got zeta\[1\] = nan$"):
        contact(zeta=[1.0, np.nan, 10.0])


@pytest.mark.parametrize("dg", [0.0, 0.05])
def test_contact_zeta_must_end_at_q1_over_q0(dg):
    zeta1 = SURFACE.q1 / SURFACE.q0
    with raises(r"^zeta must end at zeta1 = q1/q0 = ", lit(repr(zeta1)),
                rf"got zeta\[2\] = {num(100.0)}\. Append q1/q0"):
        contact(zeta=[1.0, 10.0, 100.0], work_of_adhesion=dg)


def test_contact_e_star_overflowing_G():
    with raises(r"^e_star must keep G\(q1\) = .* finite \[Pa\]", rf"got e_star = {num(1e300)}"):
        contact(e_star=1e300)


def test_contact_e_star_below_1e5_pa_warns():
    with pytest.warns(UserWarning, match=r"^e_star = 1\.0 Pa is below 100000 Pa"):
        contact(e_star=1.0)


class _NotASurface:
    q0 = 1e4
    q1 = 1e8


@pytest.mark.parametrize("surface, missing, typename", [
    (object(), "'q0'", "object"),
    (_NotASurface(), "'diffusion_time'", "_NotASurface"),
])
def test_contact_surface_without_attributes(surface, missing, typename):
    with raises(r"^surface must be a persson_fast surface model", missing, typename):
        contact(surface=surface)


@pytest.mark.parametrize("method", ["images", "fd", ""])
def test_contact_unknown_method_lists_valid(method):
    with raises(r"^method must be one of", "'analytic'", "'cn'", "'auto'", lit(repr(method))):
        contact(method=method)


def test_contact_rtol_out_of_range():
    with raises(r"^rtol must lie in \[1e-12, 0\.1\]", rf"got rtol = {num(0.5)}$"):
        contact(rtol=0.5)


# --- valid edge inputs do not raise --------------------------------------------------------
@pytest.mark.parametrize("method", ["cn", "analytic", "auto"])
def test_contact_pressure_zero_gives_zero_area(method):
    r = contact(pressure=[0.0, 1e5], method=method)
    assert r.area[0] == 0.0 and r.area[1] > 0.0


def test_contact_scalar_pressure():
    r = contact(pressure=1e5)
    assert r.pressure.shape == (1,) and r.area.shape == (1,)
    assert r.zeta[0] == 1.0 and r.area_zeta.shape == (1, r.zeta.size)


def test_contact_zeta_edges_accepted():
    zeta1 = SURFACE.q1 / SURFACE.q0
    r = contact(zeta=[1.0, 10.0, zeta1])
    assert np.array_equal(r.zeta, [1.0, 10.0, zeta1])


@pytest.mark.parametrize("gs", [0.0, 0.45, 1.0])
def test_contact_energy_correction_edges_accepted_without_adhesion(gs):
    r = contact(energy_correction=gs)
    assert np.isfinite(r.area[0])


# =============================================================================================
# surfaces (representative; the surfaces have their own tests)
# =============================================================================================
def test_self_affine_two_normalisations():
    with raises(r"^exactly one of h_rms \[m\], slope_rms \[-\], C0 \[m\^4\] must be given",
                lit("h_rms = 1e-06"), lit("slope_rms = 0.1")):
        pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e8, h_rms=1e-6, slope_rms=0.1)


def test_self_affine_no_normalisation():
    with raises(r"^exactly one of h_rms", "got none"):
        pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e8)


@pytest.mark.parametrize("q0, q1", [(1e4, 1e4), (1e8, 1e4)])
def test_self_affine_q1_not_above_q0(q0, q1):
    with raises(r"^q1 must be > q0 \[1/m\]", rf"q1 = {num(q1)}", rf"q0 = {num(q0)}$"):
        pf.SelfAffine(hurst=0.8, q0=q0, q1=q1, h_rms=1e-6)


@pytest.mark.parametrize("hurst", [-0.1, 1.2])
def test_self_affine_hurst_out_of_range(hurst):
    with raises(r"^hurst must be in \[0, 1\] \[-\]", rf"got hurst = {num(hurst)}$"):
        pf.SelfAffine(hurst=hurst, q0=1e4, q1=1e8, h_rms=1e-6)


def test_self_affine_h_rms_not_positive():
    with raises(r"^h_rms must be > 0 \[m\]", rf"got h_rms = {num(-1e-6)}$"):
        pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e8, h_rms=-1e-6)


# =============================================================================================
# the offending value is shown as a plain number (STYLE.md: "got pressure[3] = nan")
# =============================================================================================
def _message(call):
    with pytest.raises(ValueError) as info:
        call()
    return str(info.value)


_PLAIN_OK = {
    "G nan": (lambda: pf.solve_diffusion([0.0, np.nan], 1.0), "got G[1] = nan"),
    "sigma_a 2-D": (lambda: pf.solve_diffusion(G3, [1.0], [[0.0, 0.0, np.inf]]),
                    "got sigma_a[0,2] = inf"),
    "e_star": (lambda: contact(e_star=-1e9), "got e_star = -1000000000.0"),
    "hurst": (lambda: pf.SelfAffine(hurst=2.0, q0=1.0, q1=2.0, C0=1.0), "got hurst = 2.0"),
}

_PLAIN_LEAKS = {
    "G decreasing": (lambda: pf.solve_diffusion([0.0, 2.0, 1.0], 1.0),
                     "got G[1] = 2.0 > G[2] = 1.0"),
    "pressure negative": (lambda: pf.solve_diffusion(G3, [1.0, -0.5]), "got pressure[1] = -0.5"),
    "pressure negative scalar": (lambda: pf.solve_diffusion(G3, -2.0), "got pressure = -2.0"),
    "contact pressure negative": (lambda: contact(pressure=[1.0, -1.0]),
                                  "got pressure[1] = -1.0"),
    "zeta start": (lambda: contact(zeta=[2.0, 10.0]), "got zeta[0] = 2.0"),
    "zeta beyond": (lambda: contact(zeta=[1.0, 20000.0]), "got zeta[1] = 20000.0"),
    "zeta not increasing": (lambda: contact(zeta=[1.0, 50.0, 10.0]),
                            "got zeta[1] = 50.0 >= zeta[2] = 10.0"),
}


@pytest.mark.parametrize("case", list(_PLAIN_OK))
def test_messages_show_plain_numbers_shared_checks(case):
    call, expected = _PLAIN_OK[case]
    msg = _message(call)
    assert expected in msg and "np." not in msg, msg


@pytest.mark.parametrize("case", list(_PLAIN_LEAKS))
def test_messages_show_plain_numbers(case):
    call, expected = _PLAIN_LEAKS[case]
    msg = _message(call)
    assert expected in msg and "np." not in msg, msg


def test_diffusion_level_range():
    G = np.array([0.0, 1.0])
    for bad in (-1, 11, 2.5, True):
        with raises(r"^level must be an integer in \[0, 10\]", lit(repr(bad))):
            pf.solve_diffusion(G, 1.0, level=bad)


def test_diffusion_level_needs_a_compiled_method():
    with raises(r"^level applies to compiled methods only", lit("'analytic'")):
        pf.solve_diffusion(np.array([0.0, 1.0]), 1.0, method="analytic", level=1)


def test_seed_e_star_poisson_range():
    for bad in (-0.1, 0.6, float("nan")):
        with raises(r"^poisson must lie in \[0, 0.5\]", "poisson = "):
            pf.seed_e_star(bad)
    assert pf.seed_e_star(0.0) == pf.SEED_YOUNG_MODULUS


def test_adhesive_start_shape():
    from persson_fast.adhesion.zeta_grid import adhesion_zeta
    from persson_fast.adhesion.fixed_point import solve_adhesive_contact

    s = pf.seed_scene()
    z = adhesion_zeta(s, 1e-2)
    with raises(r"^start must have shape \(n_p, n_zeta\)", lit("got shape (3,)")):
        solve_adhesive_contact(s, [0.0], z, e_star=3e9, work_of_adhesion=0.06, rtol=1e-2,
                               zeta_given=True, start=np.zeros(3))
