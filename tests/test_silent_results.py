"""No silent results (issue 11, items 7, 8, 11, 14): a scene the solver cannot serve as asked
is refused with a ValueError that names the argument the user gave, never returned as a
plausible number with status 0 and "ok"."""
import re
import warnings

import numpy as np
import pytest

import persson_fast as pf

SELF_AFFINE = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
ZETA1_SA = SELF_AFFINE.q1 / SELF_AFFINE.q0
SEED = pf.seed_scene()
ZETA1_SEED = SEED.q1 / SEED.q0
E_SEED = pf.seed_e_star()
DGAMMA = pf.SEED_WORK_OF_ADHESION


def _value_error(call):
    with pytest.raises(ValueError) as info:
        call()
    return str(info.value)


# --- item 7: result.area is A(zeta1)/A0 for every zeta grid --------------------------------
@pytest.mark.parametrize("method", ["analytic", "cn"])
def test_zeta_short_of_zeta1_refused_without_adhesion(method):
    # was: area = A(zeta = 10) = 0.0648 with "ok" (A(zeta1) = 0.00802)
    msg = _value_error(lambda: pf.solve_contact(SELF_AFFINE, 1e6, e_star=1e9, zeta=[1.0, 10.0],
                                                method=method))
    assert msg.startswith("zeta must end at zeta1 = q1/q0 = 100000.0"), msg
    assert "got zeta[1] = 10.0" in msg and "np.append(zeta, surface.q1 / surface.q0)" in msg


def test_zeta_short_of_zeta1_refused_with_adhesion():
    # was: area = 1.0 with "ok" (A(zeta1) = 0.495 on the default grid)
    msg = _value_error(lambda: pf.solve_contact(SEED, 1e6, e_star=E_SEED, work_of_adhesion=DGAMMA,
                                                zeta=[1.0, 10.0, 100.0], rtol=1e-3))
    assert msg.startswith(f"zeta must end at zeta1 = q1/q0 = {ZETA1_SEED!r}"), msg
    assert "got zeta[2] = 100.0" in msg


def test_zeta_short_of_zeta1_refused_by_pull_off():
    msg = _value_error(lambda: pf.pull_off(SEED, e_star=E_SEED, work_of_adhesion=DGAMMA,
                                           zeta=[1.0, 10.0, 100.0], rtol=1e-3))
    assert msg.startswith("zeta must end at zeta1 = q1/q0"), msg


def test_zeta_single_point_refused():
    msg = _value_error(lambda: pf.solve_contact(SELF_AFFINE, 1e6, e_star=1e9, zeta=[1.0]))
    assert msg.startswith("zeta must end at zeta1") and "got zeta[0] = 1.0" in msg, msg


def test_zeta_beyond_zeta1_refused():
    msg = _value_error(lambda: pf.solve_contact(SELF_AFFINE, 1e6, e_star=1e9,
                                                zeta=[1.0, 10.0, 2 * ZETA1_SA]))
    assert msg.startswith("zeta must lie in [1, q1/q0 = 100000.0]"), msg


def test_zeta_ending_at_zeta1_gives_area_at_zeta1():
    ref = pf.solve_contact(SELF_AFFINE, 1e6, e_star=1e9)
    # a logspace grid ends within rounding of zeta1: taken as zeta1, set exactly
    z = np.logspace(0.0, np.log10(ZETA1_SA), 11)
    r = pf.solve_contact(SELF_AFFINE, 1e6, e_star=1e9, zeta=z)
    assert r.zeta[-1] == ZETA1_SA and r.zeta.size == z.size
    np.testing.assert_allclose(r.area, ref.area, rtol=1e-12)
    assert r.area[0] == r.area_zeta[0, -1]
    r2 = pf.solve_contact(SELF_AFFINE, 1e6, e_star=1e9, zeta=[1.0, 10.0, ZETA1_SA])
    np.testing.assert_allclose(r2.area, ref.area, rtol=1e-12)


def test_zeta_ending_at_zeta1_with_adhesion():
    z = pf.adhesion_zeta(SEED, 1e-3)
    r = pf.solve_contact(SEED, 1e6, e_star=E_SEED, work_of_adhesion=DGAMMA, zeta=z, rtol=1e-3)
    ref = pf.solve_contact(SEED, 1e6, e_star=E_SEED, work_of_adhesion=DGAMMA, rtol=1e-3)
    assert r.success and r.zeta[-1] == ZETA1_SEED
    assert np.array_equal(r.area, ref.area)


# --- item 8: non-finite diffusion times, refused at construction, naming the argument ---------
@pytest.mark.parametrize("kw, name", [
    ({"slope_rms": 1e200}, "slope_rms"),
    ({"h_rms": 1e200}, "h_rms"),
    ({"C0": 1e300}, "C0"),
])
def test_self_affine_nonfinite_spectrum_refused(kw, name):
    # was: accepted with C0 = inf; with adhesion it came back as area = 0, status 0, "ok"
    msg = _value_error(lambda: pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, **kw))
    value = repr(float(kw[name]))
    assert msg.startswith(f"{name} must give a spectrum whose moments"), msg
    assert f"got {name} = {value}" in msg and "finite" in msg


def test_capillary_waves_nonfinite_spectrum_refused():
    msg = _value_error(lambda: pf.CapillaryWaves(temperature=1e300, surface_tension=1e-300,
                                                 q_c=1e9, q0=1e4, q1=1e10))
    assert msg.startswith("temperature, surface_tension, q_c must give a spectrum"), msg
    assert "temperature = 1e+300" in msg


def test_tabulated_nonfinite_spectrum_refused():
    msg = _value_error(lambda: pf.TabulatedPSD([1e4, 1e9], [1e300, 1e290]))
    assert msg.startswith("q, C must give a spectrum") and "max(C) = 1e+300" in msg, msg


@pytest.mark.parametrize("kw", [
    {"method": "analytic"},
    {"method": "cn"},
    {"work_of_adhesion": DGAMMA},
])
def test_e_star_with_nonfinite_G_refused(kw):
    # was: with adhesion area = 0, status 0, "ok"; without it a ValueError about an internal G
    msg = _value_error(lambda: pf.solve_contact(SEED, 1e6, e_star=1e300, rtol=1e-3, **kw))
    assert msg.startswith("e_star must keep G(q1)"), msg
    assert "got e_star = 1e+300" in msg and "[Pa]" in msg


def test_e_star_with_nonfinite_G_refused_by_pull_off_and_diffusion_time():
    msg = _value_error(lambda: pf.pull_off(SEED, e_star=1e300, work_of_adhesion=DGAMMA))
    assert msg.startswith("e_star must keep G(q1)") and "got e_star = 1e+300" in msg, msg
    msg = _value_error(lambda: SEED.diffusion_time(SEED.q1, 1e300))
    assert msg.startswith("e_star must keep G(q1)"), msg
    rough = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, C0=1e10)      # int q^2 C dq = 1.7e22 m
    msg = _value_error(lambda: rough.elastic_energy_full_contact(1e290))
    assert msg.startswith("e_star must keep U_el/A0") and "got e_star = 1e+290" in msg, msg


def test_work_of_adhesion_with_nonfinite_scene_refused():
    msg = _value_error(lambda: pf.solve_contact(SEED, 1e6, e_star=E_SEED,
                                                work_of_adhesion=1e-320, rtol=1e-3))
    assert msg.startswith("work_of_adhesion [J/m^2], e_star [Pa] and detachment_prefactor"), msg
    assert "work_of_adhesion = 1e-320" in msg


# --- item 11: an empty pressure array with adhesion ------------------------------------------
def test_empty_pressure_with_adhesion_returns_empty_result():
    # was: a numba TypingError after seconds of compilation
    r = pf.solve_contact(SEED, [], e_star=E_SEED, work_of_adhesion=DGAMMA, rtol=1e-3)
    plain = pf.solve_contact(SEED, [], e_star=E_SEED)
    assert r.success and r.message == "ok" and r.method == "cn"
    n_z = r.zeta.size
    assert r.zeta[0] == 1.0 and r.zeta[-1] == ZETA1_SEED and r.G.shape == (n_z,)
    for name in ("pressure", "area", "load", "status", "error_estimate", "iterations",
                 "residual", "sticky", "mean_contact_pressure", "zeta_error"):
        assert getattr(r, name).shape == (0,), name
    for name in ("area_zeta", "sigma_a", "gamma_eff", "elastic_energy_zeta", "load_zeta"):
        assert getattr(r, name).shape == (0, n_z), name
    # the same shapes as without adhesion
    assert plain.area.shape == (0,) and plain.area_zeta.shape == (0, plain.zeta.size)


# --- item 14: implausible moduli warn, naming e_star, the value and the unit ------------------
E_STAR_WARNING = r"e_star = 1\.0 Pa is below 100000 Pa"


def test_e_star_in_gpa_warns_in_solve_contact():
    # was: e_star=1.0 (GPa typed where Pa is meant) gave A = 1 silently
    with pytest.warns(UserWarning, match=E_STAR_WARNING):
        r = pf.solve_contact(SEED, 1e6, e_star=1.0)
    assert r.area[0] == pytest.approx(1.0)


def test_e_star_in_gpa_warns_once_per_call_under_default_filter():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("default")
        pf.solve_contact(SEED, [1e6, 2e6], e_star=1.0, method="cn")
    hits = [w for w in caught if re.search(E_STAR_WARNING, str(w.message))]
    assert len(hits) == 1 and hits[0].filename == __file__, [str(w.message) for w in caught]


def test_e_star_in_gpa_warns_everywhere():
    with pytest.warns(UserWarning, match=E_STAR_WARNING):
        pf.solve_contact(SEED, 1e6, e_star=1.0, work_of_adhesion=DGAMMA, rtol=1e-3)
    with pytest.warns(UserWarning, match=E_STAR_WARNING):
        assert pf.pull_off(SEED, e_star=1.0, work_of_adhesion=0.0) == 0.0
    with pytest.warns(UserWarning, match=E_STAR_WARNING):
        SEED.diffusion_time(SEED.q1, 1.0)
    with pytest.warns(UserWarning, match=E_STAR_WARNING):
        SEED.elastic_energy_full_contact(1.0)


def test_plausible_e_star_does_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        pf.solve_contact(SEED, 1e6, e_star=1e5)
        SEED.diffusion_time(SEED.q1, 3e6)


# --- item 14: h_rms / slope_rms as attributes and as calls ------------------------------------
def test_h_rms_and_slope_rms_are_floats_and_callable():
    s = SELF_AFFINE
    assert isinstance(s.h_rms, float) and isinstance(s.slope_rms, float)
    assert s.h_rms == s.h_rms() and s.slope_rms == s.slope_rms()
    assert type(s.h_rms()) is float and type(s.slope_rms()) is float
    assert s.h_rms == pytest.approx(1e-6, rel=1e-14)
    assert f"{s.h_rms * 1e9:.4g}" == "1000"
    assert float(SEED.slope_rms) == SEED.slope_rms()


# --- item 14: short reprs, AUTO_POLICY exported ------------------------------------------------
def test_contact_result_repr_is_short():
    p = np.linspace(0.0, 1e7, 51)
    r = pf.solve_contact(SELF_AFFINE, p, e_star=1e9)
    text = repr(r)
    assert len(text.splitlines()) <= 8, text
    assert text.startswith("<ContactResult: method='analytic', success=True, message='ok'")
    assert "51 values in [0, 1e+07] Pa" in text and "(51, 41)" in text
    assert str(r) == text
    r_adh = pf.solve_contact(SEED, [0.0, 1e6], e_star=E_SEED, work_of_adhesion=DGAMMA, rtol=1e-3)
    text = repr(r_adh)
    assert len(text.splitlines()) <= 8 and "sigma_a(zeta=1)" in text and "iterations" in text


def test_diffusion_result_repr_is_short():
    G = np.linspace(0.0, 4e12, 41)
    d = pf.solve_diffusion(G, np.linspace(1e5, 1e7, 51), method="analytic")
    text = repr(d)
    assert len(text.splitlines()) <= 6, text
    assert text.startswith("<DiffusionResult: method='analytic', success=True")
    assert "shape (51, 41)" in text


def test_auto_policy_exported():
    from persson_fast.methods import AUTO_POLICY

    assert pf.AUTO_POLICY is AUTO_POLICY and "AUTO_POLICY" in pf.__all__


def test_contact_result_docstring_cites_no_missing_file():
    assert "THEORY" not in (pf.ContactResult.__doc__ or "")
