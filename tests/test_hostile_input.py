"""Hostile input: bad, extreme and contradictory arguments get a clear refusal or a flag.

Each test is one reproducer (or a family of them): the answer is a result within its
tolerance, a result flagged by its status, or a ValueError that names the argument.
"""
import math
import re
import warnings

import numba
import numpy as np
import pytest

import persson_fast as pf
from persson_fast import embed
from tolerances import ATOL, RTOL

from persson_fast._kernels.status import (BAD_INPUT, BAD_LAW, BAD_PRESSURE, BAD_SEPARATION,
                                          OK, SEPARATION_UNDERFLOW, STATUS_MESSAGES)

SEED = pf.seed_scene()


# ---------------------------------------------------------------------------------------------
# contact-law tables inside @numba.njit
# ---------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def law():
    return embed.contact_law(SEED, e_star=1e9, rtol=1e-8)


def _copy(table):
    return tuple(a.copy() for a in table)


def _reversed(t):
    return tuple(a[::-1].copy() for a in t)


def _nan_in_ln_p(t):
    t = _copy(t)
    t[1][5] = np.nan
    return t


def _short_ln_p(t):
    return (t[0], t[1][:10].copy(), t[2], t[3], t[4])


def _swapped_pair(t):
    t = _copy(t)
    n = t[0].size // 2
    for a in t:
        a[n], a[n + 1] = a[n + 1], a[n]
    return t


def _inf_in_ln_k(t):
    t = _copy(t)
    t[3][-3] = np.inf
    return t


def _nan_in_dlnk(t):
    t = _copy(t)
    t[4][0] = np.nan
    return t


def _positive_slope(t):
    t = _copy(t)
    t[2][7] = -t[2][7]
    return t


def _steep_slope(t):
    # monotone nodes, but a node slope 10x too steep: the cubic on its intervals overshoots
    # (Fritsch-Carlson fails), so p(u) would not be monotone there
    t = _copy(t)
    t[2][7] *= 10.0
    return t


def _short_last(t):
    return (t[0], t[1], t[2], t[3], t[4][:-1].copy())


def _one_node(t):
    return tuple(a[:1].copy() for a in t)


def _empty(t):
    return tuple(a[:0].copy() for a in t)


def _beyond_doubles(t):
    t = _copy(t)
    t[0][:] = t[0] + 1000.0                  # ln u above ln(max double)
    return t


def _mixed_up(t):
    return (t[1], t[0], t[2], t[3], t[4])     # ln p where ln u belongs


BAD_TABLES = {
    # the three reproducers of the issue
    "reversed nodes": _reversed,
    "nan in ln p": _nan_in_ln_p,
    "ln p shorter than ln u": _short_ln_p,
    # and more
    "two nodes swapped": _swapped_pair,
    "inf in ln K": _inf_in_ln_k,
    "nan in d ln K": _nan_in_dlnk,
    "positive slope": _positive_slope,
    "slope breaking monotonicity": _steep_slope,
    "last array shorter": _short_last,
    "one node": _one_node,
    "no node": _empty,
    "ln u beyond doubles": _beyond_doubles,
    "columns mixed up": _mixed_up,
}


@numba.njit(cache=False)
def _user_calls(table, u, p):
    """A user's kernel calling every compiled law entry point."""
    out = np.empty(6)
    codes = np.empty(6, dtype=np.int64)
    out[0], codes[0] = embed.law_pressure(table, u)
    out[1], codes[1] = embed.law_stiffness(table, u)
    a, b, codes[2] = embed.law_pressure_stiffness(table, u)
    out[2] = a + b
    out[3], codes[3] = embed.law_separation(table, p)
    codes[4] = embed.law_status(table)
    out[4] = 0.0
    gaps = np.full(3, u)
    op = np.empty(3)
    ok = np.empty(3)
    st = np.empty(3, dtype=np.int64)
    embed.law_sweep(table, gaps, op, ok, st)
    out[5] = op[0] + ok[1]
    codes[5] = st[2]
    return out, codes


@pytest.mark.parametrize("name", BAD_TABLES)
def test_bad_law_table_gives_nan_and_bad_law_inside_user_njit(law, name):
    table = BAD_TABLES[name](law.table)
    for u, p in [(law.separation[law.separation.size // 2] * 1.01, 1e6),
                 (law.separation[-1] * 2.0, 1e-6), (law.separation[0] / 2.0, 1e10),
                 (law.separation[3], law.pressure[3])]:
        out, codes = _user_calls(table, u, p)
        assert list(codes) == [BAD_LAW] * 6, (name, codes)
        assert np.all(np.isnan(out[[0, 1, 2, 3, 5]])), (name, out)


@pytest.mark.parametrize("name", ["reversed nodes", "nan in ln p", "ln p shorter than ln u"])
def test_bad_law_table_through_python_layer(law, name):
    from dataclasses import replace

    bad = replace(law, table=BAD_TABLES[name](law.table))
    p, k, status = bad.evaluate([1e-9, 2e-9])
    assert np.all(status == BAD_LAW) and np.all(np.isnan(p)) and np.all(np.isnan(k))
    with pytest.raises(ValueError, match=r"table: the contact law's table must be"):
        bad.pressure_at(1e-9)
    assert "Fritsch-Carlson" in STATUS_MESSAGES[BAD_LAW]


def test_valid_table_is_accepted_and_unchanged(law):
    """The builder's tables pass the check, and the checked entry points give what the
    table gives (the bad-value codes still come first for a good table)."""
    out, codes = _user_calls(law.table, law.separation[10] * 1.001, law.pressure[20] * 0.999)
    assert list(codes) == [OK] * 6 and np.all(np.isfinite(out))
    for rtol in (1e-4, 1e-6, 1e-10):
        for surface, e in ((SEED, 1e9), (pf.SelfAffine(hurst=0.3, q0=1e3, q1=1e10,
                                                        h_rms=1e-6), 1e8)):
            t = embed.contact_law(surface, e_star=e, energy_correction=0.45, rtol=rtol).table
            assert embed.law_status(t) == OK
    assert embed.law_pressure(law.table, 0.0) == (pytest.approx(np.nan, nan_ok=True),
                                                  BAD_SEPARATION)
    assert embed.law_separation(law.table, -1.0)[1] == BAD_PRESSURE
    # the table read back from the CSV columns is the same table
    assert embed.law_status(tuple(a.copy() for a in law.table)) == OK


def test_law_sweep_refuses_outputs_of_another_length(law):
    u = np.full(4, 1e-9)
    p, k, st = np.empty(3), np.empty(4), np.empty(4, dtype=np.int64)
    embed.law_sweep(law.table, u, p, k, st)
    assert np.all(st == BAD_INPUT) and np.all(np.isnan(k)) and np.all(np.isnan(p))


# ---------------------------------------------------------------------------------------------
# item 13: separation at the ends of the pressure range
# ---------------------------------------------------------------------------------------------
def test_separation_underflow_is_flagged_and_its_inverse_says_why():
    r = pf.solve_separation(SEED, [1e9, 1e11], e_star=1e9)
    assert list(r.status) == [OK, SEPARATION_UNDERFLOW] and not r.success
    assert r.separation[1] == 0.0 and "underflows" in r.message
    back = pf.pressure_at_separation(SEED, r.separation[0], e_star=1e9)
    assert abs(back - 1e9) <= 1e-10 * 1e9
    with pytest.raises(ValueError, match=r"separation must be > 0 \[m\].*underflow.*"
                                         r"SEPARATION_UNDERFLOW"):
        pf.pressure_at_separation(SEED, r.separation, e_star=1e9)


def test_separation_round_trip_up_to_the_underflow():
    """Every u with status 0 maps back to its pressure; the flag starts where terms of u's
    sum can leave the doubles' normal range (u < 1e-292 m). A flagged u that is not 0 has
    lost digits (the sum's terms underflowed: here 3.5e-9 off in p), so only its order is
    checked: its inverse lies beyond every unflagged pressure."""
    e = 1e9
    p = np.geomspace(1e-3, 2e10, 400)
    r = pf.solve_separation(SEED, p, e_star=e)
    ok = r.status == OK
    assert ok[:100].all() and not ok[-1]
    flagged = r.status == SEPARATION_UNDERFLOW
    assert np.all(ok | flagged)
    assert np.all(r.separation[ok] >= 1e-292) and np.all(r.separation[flagged] < 1e-292)
    rtol = 1e-10
    back = pf.pressure_at_separation(SEED, r.separation[ok], e_star=e, rtol=rtol)
    np.testing.assert_allclose(back, p[ok], rtol=rtol)
    tiny = flagged & (r.separation > 0)
    assert tiny.any()
    back = pf.pressure_at_separation(SEED, r.separation[tiny], e_star=e, rtol=rtol)
    assert np.all(np.isfinite(back)) and np.all(back > p[ok].max())
    assert np.all(np.diff(back) > 0)


def test_zero_pressure_is_one_behaviour_everywhere():
    """p = 0: u = inf, K = 0, U_el = 0 from solve_separation, ContactResult.separation and
    the inverse (inf -> 0), all unflagged."""
    r = pf.solve_separation(SEED, [0.0, 1e6], e_star=1e9)
    assert r.success and list(r.status) == [OK, OK]
    assert r.separation[0] == math.inf and r.stiffness[0] == 0.0 and r.elastic_energy[0] == 0.0
    assert r.area[0] == 0.0
    c = pf.solve_contact(SEED, [0.0, 1e6], e_star=1e9)
    np.testing.assert_array_equal(c.separation, r.separation)
    np.testing.assert_array_equal(c.stiffness, r.stiffness)
    assert pf.pressure_at_separation(SEED, math.inf, e_star=1e9) == 0.0
    back = pf.pressure_at_separation(SEED, r.separation, e_star=1e9)
    assert back[0] == 0.0 and abs(back[1] / 1e6 - 1) <= 1e-10
    with pytest.raises(ValueError, match=r"pressure must be >= 0.*pressure\[0\] = -1.0"):
        pf.solve_separation(SEED, [-1.0], e_star=1e9)


def test_contact_result_separation_warns_where_flagged():
    c = pf.solve_contact(SEED, [1e6, 1e11], e_star=1e9)
    with pytest.warns(RuntimeWarning, match=r"separation: 1 of 2 pressures flagged.*underflows"):
        u = c.separation
    assert u[1] == 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert np.isfinite(pf.solve_contact(SEED, [1e6], e_star=1e9).separation).all()


# ---------------------------------------------------------------------------------------------
# items 7, 8: TabulatedPSD.from_heights
# ---------------------------------------------------------------------------------------------
_RNG_MAP = np.random.default_rng(11).normal(size=(64, 64)) * 1e-6


def test_bins_per_decade_is_bounded():
    with pytest.raises(ValueError, match=r"bins_per_decade must be a whole number in \[1, 1000\]"
                                         r".*got bins_per_decade = 1000000"):
        pf.TabulatedPSD.from_heights(_RNG_MAP, 1e-6, bins_per_decade=10**6)
    s = pf.TabulatedPSD.from_heights(_RNG_MAP, 1e-6, bins_per_decade=1000)
    assert s.info["bins_per_decade"] == 1000
    with pytest.raises(ValueError, match=r"bins_per_decade must be a whole number"):
        pf.TabulatedPSD.from_heights(_RNG_MAP, 1e-6, bins_per_decade=10.5)


@pytest.mark.parametrize("heights, pixel, kw, match", [
    (np.zeros((0, 0)), 1e-6, {}, r"heights: a map must have at least 4 x 4 pixels.*\(0, 0\)"),
    (np.zeros(0), 1e-6, {}, r"heights: a line scan must have at least 4 points.*\(0,\)"),
    (np.zeros((0, 8)), 1e-6, {"line_scans": True}, r"heights: a line scan must have"),
    (np.ones((1, 1)), 1e-6, {}, r"heights: a map must have at least 4 x 4 pixels.*\(1, 1\)"),
    (np.ones((2, 2)), 1e-6, {}, r"heights: a map must have at least 4 x 4 pixels.*\(2, 2\)"),
    (np.ones((2, 64)), 1e-6, {}, r"\(2, 64\) \(parallel profiles: pass line_scans=True\)"),
    (_RNG_MAP, 1e-300, {}, r"pixel_size must give a scan whose size, area and wavevectors "
                           r"are normal.*pixel_size = 1e-300"),
    (_RNG_MAP, 1e300, {}, r"pixel_size must give a scan.*pixel_size = 1e\+300"),
    (_RNG_MAP[0], 1e-320, {}, r"pixel_size must give a scan.*scan length"),
    (_RNG_MAP * 1e306, 1e-6, {}, r"heights and pixel_size give a spectrum .* not "
                                 r"representable in double precision \[m\^4\]: it overflows"),
    (_RNG_MAP * 1e-200, 1e-6, {}, r"heights and pixel_size give a spectrum .* underflows"),
    (_RNG_MAP[:8] * 1e-200, 1e-6, {"line_scans": True}, r"underflows"),
    (_RNG_MAP * 1e140, 1e-100, {}, r"heights and pixel_size must give a spectrum whose moments "
                                 r"are finite.*max \|heights\|"),
    (_RNG_MAP, 1e-6, {"hurst": 1.5}, r"hurst must be in \[0, 1\] \[-\]; got hurst = 1.5"),
    (_RNG_MAP, 1e-6, {"hurst": 0.5}, r"hurst applies to line scans only.*hurst = 0.5 with a "
                                     r"map of shape \(64, 64\)"),
])
def test_from_heights_refuses_in_the_users_terms(heights, pixel, kw, match):
    with warnings.catch_warnings():
        warnings.simplefilter("error")          # no numpy over/underflow warnings first
        with pytest.raises(ValueError, match=match):
            pf.TabulatedPSD.from_heights(heights, pixel, **kw)


def test_from_heights_extreme_but_representable_scales_agree():
    """Heights and pixels scaled by powers of ten that double precision still carries give
    the same relative spectrum (C scales as h^2 dx^2, q as 1/dx)."""
    ref = pf.TabulatedPSD.from_heights(_RNG_MAP, 1e-6, periodic=True)
    for hs, px in [(1e-100, 1e-6), (1e-140, 1e-6), (1e100, 1e-6), (1e-6, 1e-40), (1e-20, 1e20)]:
        s = pf.TabulatedPSD.from_heights(_RNG_MAP * (hs / 1e-6), px, periodic=True)
        np.testing.assert_allclose(s.q_table * px, ref.q_table * 1e-6, rtol=1e-12)
        np.testing.assert_allclose(s.C_table / (hs * px) ** 2, ref.C_table / 1e-24, rtol=1e-9)
    line = pf.TabulatedPSD.from_heights(_RNG_MAP[:4], 1e-6, line_scans=True, hurst=0.5)
    assert line.info["hurst"] == 0.5 and not line.info["hurst_fitted"]


# ---------------------------------------------------------------------------------------------
# items 10, 11: the command line
# ---------------------------------------------------------------------------------------------
_SA_FLAGS = ["--surface", "self-affine", "--hurst", "0.8", "--q0", "1e4", "--q1", "1e9",
             "--h-rms", "1e-6", "--e-star", "1e9"]


def _contact(*flags):
    from persson_fast.cli import main as cli

    return cli.main(["contact", *flags])


@pytest.mark.parametrize("line, match", [
    ('separation = "yes"', r"separation must be true or false \(a TOML boolean, unquoted\); "
                           r"got 'yes'"),
    ("separation = 1", r"separation must be true or false.*got 1"),
    ('pull_off = "true"', r"pull_off must be true or false.*got 'true'"),
    ("csv = 5", r"csv must be a string; got 5"),
    ("method = 3", r"method must be a string; got 3"),
    ("theory = 1", r"theory must be a string; got 1"),
])
def test_config_refuses_wrong_types(tmp_path, capsys, line, match):
    config = tmp_path / "scene.toml"
    config.write_text(f"e_star = 1e9\npressures = [1e6]\n{line}\n[surface]\nmodel = "
                      f"'self-affine'\nhurst = 0.8\nq0 = 1e4\nq1 = 1e9\nh_rms = 1e-6\n")
    assert _contact("--config", str(config)) == 2
    assert re.search(match, capsys.readouterr().err)


def test_config_whole_number_keys_are_not_truncated(tmp_path, capsys):
    config = tmp_path / "scene.toml"
    config.write_text("e_star = 1e9\npressures = [1e6]\n[surface]\nmodel = 'topography'\n"
                      "file = 'map.npy'\nbins_per_decade = 10.5\n")
    assert _contact("--config", str(config)) == 2
    assert "surface.bins_per_decade must be a whole number; got 10.5" in capsys.readouterr().err


@pytest.mark.parametrize("flags, kw", [
    (["--theory", "wm17", "--work-of-adhesion", "0.05"], {"theory": "wm17",
                                                          "work_of_adhesion": 0.05}),
    (["--theory", "yp08", "--work-of-adhesion", "0.05"], {"theory": "yp08",
                                                          "work_of_adhesion": 0.05}),
    (["--theory", "xu24"], {"theory": "xu24", "work_of_adhesion": 0.0}),
    (["--hardness", "1e8", "--work-of-adhesion", "0.05"], {"hardness": 1e8,
                                                            "work_of_adhesion": 0.05}),
])
def test_pull_off_of_the_scene_as_solved(capsys, flags, kw):
    """--pull-off with a corrected theory or a yield wall prints that scene's pull-off
    stress (refused before pull_off served them); this scene is not sticky: 0."""
    assert _contact(*_SA_FLAGS, "--pressure", "1e5", "--rtol", "1e-3", *flags,
                    "--pull-off") == 0
    out = capsys.readouterr()
    expected = pf.pull_off(pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6), e_star=1e9,
                           rtol=1e-3, **kw)
    assert f"pull-off stress: {expected:.5g} Pa" in out.out and "Traceback" not in out.err


def test_pull_off_refusal_is_in_one_place(monkeypatch, capsys):
    """A theory outside cli_config.PULL_OFF_THEORIES (or a yield wall while
    PULL_OFF_WITH_HARDNESS is False) is refused there, before solving (exit code 2)."""
    from persson_fast.cli import config as cli_config

    monkeypatch.setattr(cli_config, "PULL_OFF_THEORIES", ("persson01",))
    assert _contact(*_SA_FLAGS, "--pressure", "1e5", "--theory", "wm17", "--pull-off") == 2
    out = capsys.readouterr()
    assert re.search(r"--pull-off is not available for --theory wm17", out.err)
    assert "pull-off stress" not in out.out
    monkeypatch.setattr(cli_config, "PULL_OFF_WITH_HARDNESS", False)
    assert _contact(*_SA_FLAGS, "--pressure", "1e5", "--hardness", "1e8", "--pull-off") == 2
    assert "--pull-off is not available with a yield wall" in capsys.readouterr().err


def test_pull_off_from_config_with_a_corrected_theory(tmp_path, capsys):
    config = tmp_path / "scene.toml"
    config.write_text("e_star = 1e9\npressures = [1e5]\nrtol = 1e-3\ntheory = 'wm17'\n"
                      "work_of_adhesion = 0.05\npull_off = true\n[surface]\nmodel = "
                      "'self-affine'\nhurst = 0.8\nq0 = 1e4\nq1 = 1e9\nh_rms = 1e-6\n")
    assert _contact("--config", str(config)) == 0
    assert "pull-off stress: " in capsys.readouterr().out


def test_pull_off_without_adhesion_is_zero_not_silent(tmp_path, capsys):
    path = tmp_path / "out.csv"
    assert _contact(*_SA_FLAGS, "--pressure", "1e5", "--pull-off", "--csv", str(path)) == 0
    assert "pull-off stress: 0 Pa" in capsys.readouterr().out
    rows = path.read_text().splitlines()
    assert rows[0].split(",")[-1] == "pull_off_stress_Pa" and float(rows[1].split(",")[-1]) == 0


def test_separation_status_column_flags_an_underflow(tmp_path, capsys):
    path = tmp_path / "out.csv"
    assert _contact(*_SA_FLAGS, "--pressure", "0", "1e6", "2e10", "--separation", "--csv",
                    str(path)) == 0
    out = capsys.readouterr().out
    assert "SEPARATION_UNDERFLOW" in out and "warning (separation):" in out
    header, *rows = [line.split(",") for line in path.read_text().splitlines()]
    status = [int(r[header.index("status")]) for r in rows]
    assert status == [OK, OK, SEPARATION_UNDERFLOW]
    assert rows[0][header.index("separation_m")] == "inf"


# ---------------------------------------------------------------------------------------------
# item 12: adhesion controls
# ---------------------------------------------------------------------------------------------
_SA = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)


@pytest.mark.parametrize("controls, match", [
    ("fast", r"adhesion controls \(adhesion_controls of solve_contact, controls of pull_off\) "
             r"must be a dict of control names to values.*got 'fast' \(a str\)"),
    (["max_iter"], r"must be a dict.*got \['max_iter'\] \(a list\)"),
    ({"fast": 1}, r"unknown adhesion control\(s\) \['fast'\]; valid: \['m_hist', 'max_iter', "
                  r"'n_damp', 'omega'\]"),
    ({"max_iter": 2.5}, r"max_iter must be a whole number >= 1 \[-\]; got max_iter = 2.5"),
    ({"max_iter": "many"}, r"max_iter must be a whole number >= 1"),
    ({"m_hist": math.inf}, r"m_hist must be a whole number >= 0.*inf"),
    ({"n_damp": -1}, r"n_damp must be a whole number >= 0 \[-\]; got n_damp = -1"),
    ({"omega": math.nan}, r"omega must lie in \(0, 1\] \[-\]; got omega = nan"),
])
def test_adhesion_controls_refused_clearly(controls, match):
    with pytest.raises(ValueError, match=match):
        pf.solve_contact(_SA, [1e6], e_star=1e9, work_of_adhesion=0.05, rtol=1e-3,
                         adhesion_controls=controls)
    with pytest.raises(ValueError, match=match):
        pf.pull_off(_SA, e_star=1e9, work_of_adhesion=0.05, rtol=1e-3, controls=controls)


# ---------------------------------------------------------------------------------------------
# item 14: the default method of solve_diffusion serves every wall
# ---------------------------------------------------------------------------------------------
_G = np.r_[0.0, np.geomspace(1e9, 1e13, 30)]


def test_default_method_serves_a_yield_wall():
    p = np.array([1e5, 1e6])
    d = pf.solve_diffusion(_G, p, sigma_y=3e6)
    ref = pf.solve_diffusion(_G, p, sigma_y=3e6, method="auto")
    assert d.success and d.method == ref.method == "analytic"
    np.testing.assert_array_equal(d.area, ref.area)
    np.testing.assert_array_equal(d.plastic_area, ref.plastic_area)
    # with a detachment wall too: the two-wall solver, within rtol of its own tighter run
    d2 = pf.solve_diffusion(_G, p, 2e5, sigma_y=3e6, rtol=RTOL)
    assert d2.success and d2.method == "strip"
    tight = pf.solve_diffusion(_G, p, 2e5, sigma_y=3e6, method="strip", rtol=1e-10)
    real, real_tight = d2.area + d2.plastic_area, tight.area + tight.plastic_area
    assert np.all(np.abs(real - real_tight) <= RTOL * real_tight + ATOL)
    # level asks for a grid method: the default takes "strip" then
    assert pf.solve_diffusion(_G, p, sigma_y=3e6, level=1).method == "strip"


def test_default_method_is_cn_for_one_wall_and_explicit_cn_refuses_a_yield_wall():
    p = np.array([1e5, 1e6])
    sa = 1e4 + 1e-9 * _G
    d = pf.solve_diffusion(_G, p, sa)
    cn = pf.solve_diffusion(_G, p, sa, method="cn")
    assert d.method == "cn"
    np.testing.assert_array_equal(d.area, cn.area)
    np.testing.assert_array_equal(d.error_estimate, cn.error_estimate)
    with pytest.raises(ValueError, match=r"method 'cn' cannot carry a yield wall \(sigma_y\).*"
                                         r"leave method out"):
        pf.solve_diffusion(_G, p, sigma_y=3e6, method="cn")


# ---------------------------------------------------------------------------------------------
# item 15: Ctrl-C at any moment of the console script
# ---------------------------------------------------------------------------------------------
_ROOT = __import__("pathlib").Path(__file__).resolve().parents[1]

#: the console script's own lines (what pip writes for the entry point), run in a child that
#: raises SIGINT when the module IMPORT_AT is imported (during the package's import)
_CHILD = """
import signal, sys
# a console script started from a terminal has Python's Ctrl-C handler; a process started in
# the background inherits SIGINT ignored (Python then installs none), where a Ctrl-C cannot
# arrive at all: the child takes the terminal's case whatever started the test run
signal.signal(signal.SIGINT, signal.default_int_handler)
class _Interrupt:
    def find_spec(self, name, path=None, target=None):
        if name == {at!r}:
            {action}
        return None
sys.meta_path.insert(0, _Interrupt())
sys.argv = ["persson-fast", "figure2", "--points", "3", "--no-plot", "--out", {out!r}]
from _persson_fast_cli import run
sys.exit(run())
"""


def _console_child(tmp_path, at, action):
    import subprocess
    import sys

    code = _CHILD.format(at=at, action=action, out=str(tmp_path / "out"))
    return subprocess.Popen([sys.executable, "-c", code], cwd=_ROOT, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)


def test_console_script_is_the_launcher_module():
    import tomllib

    scripts = tomllib.loads((_ROOT / "pyproject.toml").read_text())["project"]["scripts"]
    assert scripts["persson-fast"] == "_persson_fast_cli:run"


@pytest.mark.parametrize("at", ["numpy", "numba", "persson_fast.api", "persson_fast.cli"])
def test_ctrl_c_while_the_package_imports_exits_130_without_traceback(tmp_path, at):
    proc = _console_child(tmp_path, at, "signal.raise_signal(signal.SIGINT)")
    out, err = proc.communicate(timeout=300)
    assert proc.returncode == 130, (at, err)
    assert err == "interrupted\n" and "Traceback" not in err
    assert not (tmp_path / "out").exists()


def test_ctrl_c_sent_from_outside_early_exits_130_without_traceback(tmp_path):
    """A real SIGINT from another process, sent as soon as the package starts importing."""
    import os
    import signal

    proc = _console_child(tmp_path, "persson_fast",
                          "print('importing', flush=True); sys.meta_path.pop(0)")
    assert proc.stdout.readline() == "importing\n"
    os.kill(proc.pid, signal.SIGINT)
    out, err = proc.communicate(timeout=300)
    assert proc.returncode == 130, err
    assert err == "interrupted\n"


def test_ctrl_c_while_parsing_is_answered_by_main(monkeypatch, capsys):
    from persson_fast.cli import main as cli

    def interrupted():
        raise KeyboardInterrupt

    monkeypatch.setattr(cli, "build_parser", interrupted)
    assert cli.main(["info"]) == 130
    assert capsys.readouterr().err == "interrupted\n"
