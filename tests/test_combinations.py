"""What combines with what: the table of docs/user-guide/combinations.md, call by call.

Each case runs the call the table describes and checks that it is accepted (and solved by
the method the table names) or refused with a ValueError, as the docs, the docstrings and
the command line's help say. Small scenes and loose tolerances: the point is acceptance,
not accuracy (the accuracy tests are elsewhere).
"""
from __future__ import annotations

import subprocess
import sys
import warnings

import numpy as np
import pytest

import persson_fast as pf
from persson_fast import embed

E_STAR = 1e9
RTOL = 1e-3
PRESSURE = [1e6]


@pytest.fixture(scope="module")
def surface():
    return pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e7, h_rms=1e-7)


#: yield walls the distribution reaches at PRESSURE (sqrt(G1) of the scene is 2.7 MPa): an
#: unreachable one is answered by the elastic closed form, whatever the table says
HARDNESS = {
    "none": None,
    "constant": 2e6,
    "scale-dependent": pf.hardness_power_law(2e6, 0.3),
}

#: (work of adhesion, hardness, theory) -> the method "auto" takes, or None for a ValueError
SOLVE_CONTACT = {}
for _theory in ("persson01", "yp08", "wm17", "xu24"):
    for _dg in (0.0, 0.02):
        for _h in HARDNESS:
            if _theory == "xu24" and (_dg > 0 or _h != "none"):
                method = None
            elif _dg == 0 and _h == "none":
                method = "analytic"
            elif _dg == 0 and _h == "constant" and _theory == "persson01":
                method = "analytic"
            elif _h != "none":
                method = "strip"
            else:
                method = "cn"
            SOLVE_CONTACT[(_dg, _h, _theory)] = method


@pytest.mark.parametrize("dg, hardness, theory", list(SOLVE_CONTACT),
                         ids=[f"dg{d}-{h}-{t}" for d, h, t in SOLVE_CONTACT])
def test_solve_contact_combination(surface, dg, hardness, theory):
    expected = SOLVE_CONTACT[(dg, hardness, theory)]
    call = lambda: pf.solve_contact(surface, PRESSURE, e_star=E_STAR, work_of_adhesion=dg,  # noqa: E731
                                    hardness=HARDNESS[hardness], theory=theory, rtol=RTOL)
    if expected is None:
        with pytest.raises(ValueError, match="xu24"):
            call()
        return
    r = call()
    assert r.method == expected
    assert r.success, r.message
    assert r.theory == theory
    if hardness != "none":
        np.testing.assert_array_equal(r.area, r.elastic_area + r.plastic_area)
        assert r.plastic_area[0] > 0.01            # the wall is reached: it is solved


def test_scene_with_hardness_and_adhesion_is_solved(surface):
    scene = pf.Scene(surface, e_star=E_STAR, work_of_adhesion=0.02, hardness=3e8)
    r = pf.solve_contact(scene, PRESSURE, rtol=RTOL)
    assert r.method == "strip" and r.success
    assert r.plastic_load is not None


def test_scan_takes_a_scale_dependent_hardness_held_fixed(surface):
    pytest.importorskip("xarray")
    scene = pf.Scene(surface, e_star=E_STAR, hardness=pf.hardness_power_law(3e8, 0.3))
    ds = pf.scan(scene, {}, PRESSURE, rtol=RTOL, progress=False)
    assert bool(ds.success.all())
    assert "plastic_area" in ds


def test_pull_off_takes_a_yield_wall(surface):
    """The table: pull_off follows the branch with the yield wall of a Scene (a value with
    its estimate; the scene is not sticky or sticky, either way a number >= 0)."""
    scene = pf.Scene(surface, e_star=E_STAR, work_of_adhesion=0.02, hardness=3e8)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)        # judged by its estimate
        sigma_c, info = pf.pull_off(scene, rtol=RTOL, full_output=True, bracket=False)
    assert sigma_c >= 0.0 and np.isfinite(info["error_estimate"])


def test_pull_off_refuses_xu24_with_adhesion(surface):
    with pytest.raises(ValueError, match="xu24"):
        pf.pull_off(surface, e_star=E_STAR, work_of_adhesion=0.02, theory="xu24", rtol=RTOL)


@pytest.mark.parametrize("kw", [{"work_of_adhesion": 0.02}, {"hardness": 3e8}],
                         ids=["adhesion", "hardness"])
def test_gap_distribution_refuses_adhesion_and_hardness(surface, kw):
    scene = pf.Scene(surface, e_star=E_STAR, **kw)
    with pytest.raises(ValueError):
        pf.gap_distribution(scene, PRESSURE)


def test_pull_off_without_adhesion_is_zero(surface):
    assert pf.pull_off(surface, e_star=E_STAR, work_of_adhesion=0.0) == 0.0


@pytest.mark.parametrize("what", ["adhesion", "hardness", "theory"])
def test_separation_refuses_what_it_does_not_derive(surface, what):
    kw = {"adhesion": {"work_of_adhesion": 0.02}, "hardness": {"hardness": 3e8},
          "theory": {"theory": "yp08"}}[what]
    r = pf.solve_contact(surface, PRESSURE, e_star=E_STAR, rtol=RTOL, **kw)
    with pytest.raises(ValueError):
        r.separation
    if what != "theory":                     # solve_separation takes no theory
        scene = pf.Scene(surface, e_star=E_STAR, **kw)
        for func in (lambda: pf.solve_separation(scene, PRESSURE),
                     lambda: pf.pressure_at_separation(scene, 1e-8),
                     lambda: pf.decay_length(scene),
                     lambda: embed.contact_law(scene)):
            with pytest.raises(ValueError):
                func()


def test_energy_correction_enters_the_separation_not_the_area(surface):
    plain = pf.solve_contact(surface, PRESSURE, e_star=E_STAR)
    corrected = pf.solve_contact(surface, PRESSURE, e_star=E_STAR, energy_correction=0.45)
    np.testing.assert_array_equal(plain.area, corrected.area)
    assert corrected.separation[0] != plain.separation[0]


def test_embed_adhesive_scene_refuses_a_yield_wall(surface):
    scene = pf.Scene(surface, e_star=E_STAR, work_of_adhesion=0.02, hardness=3e8)
    with pytest.raises(ValueError, match="yield wall"):
        embed.adhesive_scene(scene, rtol=RTOL)


def test_scan_takes_pull_off_with_a_corrected_adhesive_theory(surface):
    pytest.importorskip("xarray")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")                       # judged by its values
        ds = pf.scan(pf.SelfAffine, {"hurst": 0.8, "q0": 1e4, "q1": 1e7, "h_rms": 1e-7},
                     PRESSURE, e_star=E_STAR, work_of_adhesion=0.02, theory="yp08",
                     pull_off=True, rtol=RTOL, progress=False)
    assert np.all(np.isfinite(ds.pull_off.values)) and np.all(ds.pull_off.values >= 0.0)


def test_scan_refuses_separation_with_a_yield_wall(surface):
    pytest.importorskip("xarray")
    with pytest.raises(ValueError, match="separation"):
        pf.scan(pf.SelfAffine, {"hurst": 0.8, "q0": 1e4, "q1": 1e7, "h_rms": 1e-7}, PRESSURE,
                e_star=E_STAR, hardness=3e8, separation=True, progress=False)


def test_pressure_above_the_hardness_is_refused(surface):
    with pytest.raises(ValueError, match="hardness"):
        pf.solve_contact(surface, [5e8], e_star=E_STAR, hardness=3e8)


# --------------------------------------------------------------------------------------------
# the command line says and does the same
# --------------------------------------------------------------------------------------------

CLI_SCENE = ["--surface", "self-affine", "--hurst", "0.8", "--q0", "1e4", "--q1", "1e7",
             "--h-rms", "1e-7", "--e-star", "1e9", "--rtol", "1e-3", "--pressure", "1e6"]


def _cli(*args):
    return subprocess.run([sys.executable, "-m", "persson_fast.cli", "contact", *args],
                          capture_output=True, text=True, timeout=300)


def test_cli_hardness_with_adhesion_is_solved():
    proc = _cli(*CLI_SCENE, "--hardness", "3e8", "--work-of-adhesion", "0.02")
    assert proc.returncode == 0, proc.stderr
    assert "A_pl/A0" in proc.stdout


def test_cli_hardness_with_a_corrected_theory_is_solved_and_xu24_refused():
    proc = _cli(*CLI_SCENE, "--hardness", "3e8", "--theory", "wm17")
    assert proc.returncode == 0, proc.stderr
    proc = _cli(*CLI_SCENE, "--hardness", "3e8", "--theory", "xu24")
    assert proc.returncode != 0 and "xu24" in proc.stderr


def test_cli_help_does_not_limit_what_the_command_serves():
    proc = _cli("--help")
    text = " ".join(proc.stdout.split())
    assert proc.returncode == 0
    assert "(no adhesion)" not in text
    assert "capillary-wave or self-affine surface." not in text
    for flag in ("--topography", "--psd", "--hardness", "--theory", "--pull-off"):
        assert flag in text
