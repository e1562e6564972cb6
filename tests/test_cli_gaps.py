"""contact --gaps FILE: the gap distribution as a CSV file (issue 36)."""
import csv
import os

import numpy as np
import pytest

import persson_fast as pf
from persson_fast.cli import main as cli

SCENE = ["--surface", "self-affine", "--hurst", "0.8", "--q0", "1e4", "--q1", "1e6",
         "--h-rms", "6e-6", "--e-star", "1e9"]
HEADER = ["pressure_Pa", "gap_m", "density_per_m", "cumulative", "contact_fraction",
          "mean_gap_m", "status"]


def _read(path):
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    return rows[0], np.array(rows[1:], dtype=float)


def test_gaps_csv_holds_the_distribution(tmp_path, capsys):
    path = tmp_path / "gaps.csv"
    assert cli.main(["contact", *SCENE, "--pressure", "0", "1e6", "1e7", "--gaps",
                     str(path)]) == 0
    header, rows = _read(path)
    assert header == HEADER
    g = pf.gap_distribution(pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e6, h_rms=6e-6),
                            [1e6, 1e7], e_star=1e9, rtol=1e-3)
    n_u = g.gaps.size
    assert rows.shape == (2 * n_u, len(HEADER))               # p = 0 has no distribution
    np.testing.assert_array_equal(rows[:n_u, 1], g.gaps)
    np.testing.assert_array_equal(rows[:, 2].reshape(2, n_u), g.density)
    np.testing.assert_array_equal(rows[:, 3].reshape(2, n_u), g.cumulative(g.gaps))
    np.testing.assert_array_equal(rows[::n_u, 5], g.mean)
    assert np.all(rows[:, 6] == 0)
    out = capsys.readouterr().out
    assert "gap distribution: 2 pressure(s)" in out and f"wrote {path}" in out
    assert not [f for f in os.listdir(tmp_path) if f.endswith(".tmp")]


def test_gaps_from_config(tmp_path):
    path = tmp_path / "g.csv"
    config = tmp_path / "scene.toml"
    config.write_text(f"e_star = 1e9\npressures = [1e6]\ngaps = '{path}'\n[surface]\nmodel = "
                      f"'self-affine'\nhurst = 0.8\nq0 = 1e4\nq1 = 1e6\nh_rms = 6e-6\n")
    assert cli.main(["contact", "--config", str(config)]) == 0
    assert _read(path)[0] == HEADER


@pytest.mark.parametrize("flags, match", [
    (["--work-of-adhesion", "0.05"], "--gaps is available for elastic scenes"),
    (["--theory", "wm17"], "--gaps is available for elastic scenes"),
    (["--hardness", "1e8"], "--gaps is available for elastic scenes"),
])
def test_gaps_refused_where_not_derived(tmp_path, capsys, flags, match):
    path = tmp_path / "g.csv"
    assert cli.main(["contact", *SCENE, "--pressure", "1e6", *flags, "--gaps",
                     str(path)]) == 2
    assert match in capsys.readouterr().err and not path.exists()


def test_gaps_need_a_positive_pressure(tmp_path, capsys):
    path = tmp_path / "g.csv"
    csv_path = tmp_path / "c.csv"
    assert cli.main(["contact", *SCENE, "--pressure", "0", "--gaps", str(path), "--csv",
                     str(csv_path)]) == 2
    assert "--gaps needs a pressure > 0" in capsys.readouterr().err
    assert not path.exists() and not csv_path.exists()     # neither file is written
