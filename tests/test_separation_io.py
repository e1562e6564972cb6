"""The separation through the command line (``contact --separation``) and scans
(``scan(..., separation=True)``): the same numbers as pf.solve_separation."""
import csv

import numpy as np
import pytest

import persson_fast as pf
from persson_fast.cli import main as cli

SCENE = ["--surface", "self-affine", "--hurst", "0.8", "--q0", "1e4", "--q1", "1e9",
         "--h-rms", "1e-6", "--e-star", "1e9"]
SURFACE = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)


@pytest.mark.parametrize("gamma", [None, 0.45])
def test_contact_separation_columns(tmp_path, capsys, gamma):
    out = tmp_path / "t.csv"
    extra = [] if gamma is None else ["--energy-correction", str(gamma)]
    assert cli.main(["contact", *SCENE, "--pressure", "0", "1e5", "1e7", "--separation",
                     "--csv", str(out), *extra]) == 0
    text = capsys.readouterr().out
    assert "u [m]" in text and "decay length u0" in text
    rows = list(csv.DictReader(out.open()))
    ref = pf.solve_separation(SURFACE, [1e5, 1e7], e_star=1e9, energy_correction=gamma)
    assert rows[0]["separation_m"] == "inf" and float(rows[0]["stiffness_Pa_per_m"]) == 0.0
    for row, u, k, e in zip(rows[1:], ref.separation, ref.stiffness, ref.elastic_energy):
        assert float(row["separation_m"]) == u
        assert float(row["stiffness_Pa_per_m"]) == k
        assert float(row["elastic_energy_J_per_m2"]) == e


def test_contact_separation_from_toml(tmp_path, capsys):
    config = tmp_path / "c.toml"
    config.write_text('e_star = 1e9\npressures = [1e6]\nseparation = true\n'
                      '[surface]\nmodel = "self-affine"\nhurst = 0.8\nq0 = 1e4\nq1 = 1e9\n'
                      'h_rms = 1e-6\n')
    assert cli.main(["contact", "--config", str(config)]) == 0
    u = pf.solve_separation(SURFACE, [1e6], e_star=1e9).separation[0]
    assert f"{u:12.6g}" in capsys.readouterr().out


@pytest.mark.parametrize("flags", [["--work-of-adhesion", "0.01"], ["--theory", "yp08"],
                                   ["--hardness", "1e9"]])
def test_contact_separation_refused(capsys, flags):
    assert cli.main(["contact", *SCENE, "--pressure", "1e5", "--separation", *flags]) == 2
    err = capsys.readouterr().err
    assert "--separation is available for elastic scenes without adhesion" in err


def test_scan_separation_variables():
    pytest.importorskip("xarray")
    ds = pf.scan(pf.SelfAffine, {"hurst": [0.6, 0.8], "q0": 1e4, "q1": 1e9, "h_rms": 1e-6},
                 [0.0, 1e5, 1e7], e_star=1e9, energy_correction=0.45, separation=True)
    assert ds["separation"].dims == ("hurst", "pressure")
    assert ds["stiffness"].attrs["units"] == "Pa/m"
    for h in (0.6, 0.8):
        ref = pf.solve_separation(pf.SelfAffine(hurst=h, q0=1e4, q1=1e9, h_rms=1e-6),
                                  [1e5, 1e7], e_star=1e9, energy_correction=0.45)
        sel = ds.sel(hurst=h)
        np.testing.assert_array_equal(sel["separation"].values[1:], ref.separation)
        np.testing.assert_array_equal(sel["stiffness"].values[1:], ref.stiffness)
        np.testing.assert_array_equal(sel["elastic_energy"].values[1:], ref.elastic_energy)
        assert sel["separation"].values[0] == np.inf
    plain = pf.scan(pf.SelfAffine, {"hurst": [0.6], "q0": 1e4, "q1": 1e9, "h_rms": 1e-6},
                    [1e5], e_star=1e9)
    assert "separation" not in plain


def test_scan_separation_refused_before_solving():
    pytest.importorskip("xarray")
    with pytest.raises(ValueError, match="separation=True needs scenes without adhesion"):
        pf.scan(pf.SelfAffine, {"hurst": 0.8, "q0": 1e4, "q1": 1e9, "h_rms": 1e-6,
                                "work_of_adhesion": [0.0, 0.01]}, [1e5], e_star=1e9,
                separation=True)
    with pytest.raises(ValueError, match="theory = 'wm17'"):
        pf.scan(SURFACE, {"e_star": [1e9]}, [1e5], theory="wm17", separation=True)
    with pytest.raises(ValueError, match="separation must be True or False"):
        pf.scan(SURFACE, {"e_star": [1e9]}, [1e5], separation="yes")
