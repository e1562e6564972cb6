"""The ``persson-fast`` command, run in-process through ``persson_fast.cli.main.main``.

Covers: figure2 and its CSV columns, contact from flags and from a TOML file, the error path
(``error: ...`` and exit code 2), outputs replaced only when complete and as a set (issue 11,
item 12), negative pressures in exponent notation (item 13), the pull-off column, distinct
metavars, the missing ``plot`` extra and ``.gitignore`` (item 14).

Kept fast: few pressures, ``--rtol 1e-3``, adhesion only where a test needs it.
"""
import csv
import os
import re
import pathlib
import signal
import stat
import sys
import threading
import types

import numpy as np
import pytest

import persson_fast as pf
from persson_fast.cli import main as cli
from persson_fast.cli import output as cli_output

#: a self-affine scene that is sticky but not in full contact: pull-off about 0.1 MPa
SCENE = ["--surface", "self-affine", "--hurst", "0.8", "--q0", "1e5", "--q1", "1e9",
         "--h-rms", "1e-8", "--e-star", "1e9", "--rtol", "1e-3"]
ADHESION = ["--work-of-adhesion", "0.01"]

FIGURE2_HEADER = ["pressure_Pa", "area_no_adhesion", "area_adhesion",
                  "force_per_contact_area_adhesion_Pa",
                  "compression_per_contact_area_adhesion_Pa", "pull_off_stress_Pa"]
CONTACT_HEADER = ["pressure_Pa", "area", "force_per_contact_area_Pa",
                  "compression_per_contact_area_Pa", "status"]


def read_csv(path):
    """(header, float array of the rows) of a CSV file."""
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    return rows[0], np.array([[float(v) for v in row] for row in rows[1:]])


def figure2(out, points, *extra):
    return cli.main(["figure2", "--points", str(points), "--rtol", "1e-3", "--out", str(out),
                     *extra])


def contact(*argv):
    return cli.main(["contact", *SCENE, *argv])


def snapshot(folder):
    """{name: bytes} of every file in ``folder`` (temporary files included)."""
    return {p.name: p.read_bytes() for p in pathlib.Path(folder).iterdir()}


@pytest.fixture
def old_figure2(tmp_path):
    """A folder holding the figure2.csv and figure2.png of a 3-point run, and their bytes."""
    pytest.importorskip("matplotlib")
    assert figure2(tmp_path, 3) == 0
    old = snapshot(tmp_path)
    assert sorted(old) == ["figure2.csv", "figure2.png"]
    return tmp_path, old


# --------------------------------------------------------------------------------------------
# figure2
# --------------------------------------------------------------------------------------------


def test_figure2_writes_csv_and_png(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    out = tmp_path / "new" / "folder"
    assert figure2(out, 5) == 0
    text = capsys.readouterr().out
    assert sorted(os.listdir(out)) == ["figure2.csv", "figure2.png"]
    assert (out / "figure2.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert f"wrote {out / 'figure2.csv'}\n" in text
    assert f"wrote {out / 'figure2.png'}\n" in text
    assert "replaced" not in text

    header, rows = read_csv(out / "figure2.csv")
    assert header == FIGURE2_HEADER == list(cli.FIGURE2_COLUMNS)
    col = dict(zip(header, rows.T))
    np.testing.assert_allclose(col["pressure_Pa"], np.linspace(0.0, 100e6, 5))
    assert np.all((col["area_no_adhesion"] >= 0) & (col["area_no_adhesion"] <= 1))
    assert np.all(col["area_adhesion"] > col["area_no_adhesion"])
    # pull-off: one positive value on every row, as printed
    sigma_c = col["pull_off_stress_Pa"]
    assert sigma_c[0] > 0 and np.all(sigma_c == sigma_c[0])
    assert f"pull-off stress: {sigma_c[0] / 1e6:.6g} MPa" in text
    # force balance: p_nom = (A/A0) * force per contact area; the compression exceeds it
    force = col["force_per_contact_area_adhesion_Pa"]
    np.testing.assert_allclose(force[1:] * col["area_adhesion"][1:], col["pressure_Pa"][1:],
                               rtol=1e-12)
    assert np.all(col["compression_per_contact_area_adhesion_Pa"] > force)


def _timing(text):
    """The parts and the total of figure2's 'time:' line [s]."""
    line = next(ln for ln in text.splitlines() if ln.startswith("time: "))
    total = float(line.split()[1])
    parts = dict((name, float(v)) for name, v in re.findall(r"([a-z-]+) ([0-9.e+-]+) s", line))
    return total, parts


def test_figure2_checks_the_closed_form_only_on_request(tmp_path, capsys):
    """The closed form is exact for the scene without adhesion: the grid solver (and its
    compile) runs only with --check, which prints the comparison. The time line's total is
    the wall time once: the parts in sequence, the adhesive curve, the pull-off stress and
    the closed form (computed at once) counted by the longest (the printed figures have
    three digits)."""
    def wall(parts):
        return (parts.get("cn", 0.0) + parts["kernels"]
                + max(parts["adhesion"], parts["pull-off"], parts["auto"]))

    assert figure2(tmp_path / "a", 3, "--no-plot") == 0
    text = capsys.readouterr().out
    assert "--check also solves it with the grid solver 'cn'" in text
    assert "A_cn" not in text
    total, parts = _timing(text)
    assert "cn" not in parts and {"auto", "kernels", "adhesion", "pull-off"} <= set(parts)
    assert 0.99 * wall(parts) <= total <= 1.05 * wall(parts) + 0.05
    assert figure2(tmp_path / "b", 3, "--no-plot", "--check") == 0
    text = capsys.readouterr().out
    diff = float(re.search(r"largest \|A_auto - A_cn\| over the pressures: (\S+)", text)[1])
    assert diff <= 1e-3 * 0.1        # rtol 1e-3 of areas below 0.1 (at most 100 MPa)
    total, parts = _timing(text)
    assert "cn" in parts
    assert 0.99 * wall(parts) <= total <= 1.05 * wall(parts) + 0.05


def test_figure2_columns_are_documented(capsys):
    with pytest.raises(SystemExit) as info:
        cli.main(["figure2", "--help"])
    assert info.value.code == 0
    help_text = capsys.readouterr().out
    for name in FIGURE2_HEADER:
        assert name in cli.__doc__, name
        assert f"  {name}: " in help_text, name


def test_figure2_default_command_and_bad_points(tmp_path, capsys):
    """No subcommand runs figure2; an invalid --points is an error with exit code 2."""
    assert cli.main(["--points", "1", "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: --points must be >= 2; got 1")
    assert os.listdir(tmp_path) == []


# --------------------------------------------------------------------------------------------
# contact: flags, TOML, errors
# --------------------------------------------------------------------------------------------


def test_contact_flags_csv(tmp_path, capsys):
    path = tmp_path / "sub" / "c.csv"
    assert contact("--pressure", "1e5", "1e6", "--csv", str(path)) == 0
    text = capsys.readouterr().out
    assert f"wrote {path}\n" in text and "replaced" not in text
    header, rows = read_csv(path)
    assert header == CONTACT_HEADER
    col = dict(zip(header, rows.T))
    np.testing.assert_array_equal(col["pressure_Pa"], [1e5, 1e6])
    assert np.all(np.diff(col["area"]) > 0)
    assert np.all(col["status"] == 0)
    # without adhesion the net force and the compression per contact area are one number
    np.testing.assert_allclose(col["compression_per_contact_area_Pa"],
                               col["force_per_contact_area_Pa"], rtol=1e-9)
    assert os.listdir(path.parent) == ["c.csv"]


def test_contact_toml(tmp_path, capsys):
    path = tmp_path / "c.csv"
    config = tmp_path / "scene.toml"
    config.write_text(
        'e_star = 1e9\n'
        'pressure_range = [1e5, 1e6, 3]\n'
        'rtol = 1e-3\n'
        f'csv = "{path.as_posix()}"\n'
        '[surface]\n'
        'model = "self-affine"\n'
        'hurst = 0.8\nq0 = 1e5\nq1 = 1e9\nh_rms = 1e-8\n')
    assert cli.main(["contact", "--config", str(config)]) == 0
    header, rows = read_csv(path)
    assert header == CONTACT_HEADER
    np.testing.assert_allclose(rows[:, 0], [1e5, 5.5e5, 1e6])
    # a flag overrides the file
    assert cli.main(["contact", "--config", str(config), "--pressure", "2e5"]) == 0
    _, rows_flag = read_csv(path)
    np.testing.assert_array_equal(rows_flag[:, 0], [2e5])
    assert "(replaced the existing file)" in capsys.readouterr().out


@pytest.mark.parametrize("lines", [
    ["pressures = [-0.5e5, 1e6]"],
    ["pressure_range = [-1e5, 1e6, 3]"],
])
def test_contact_toml_negative_pressures(tmp_path, lines):
    path = tmp_path / "c.csv"
    config = tmp_path / "scene.toml"
    config.write_text("\n".join([
        "e_star = 1e9", "rtol = 1e-3", "work_of_adhesion = 0.01", *lines,
        f'csv = "{path.as_posix()}"',
        "[surface]", 'model = "self-affine"', "hurst = 0.8", "q0 = 1e5", "q1 = 1e9",
        "h_rms = 1e-8"]) + "\n")
    assert cli.main(["contact", "--config", str(config)]) == 0
    _, rows = read_csv(path)
    assert rows[0, 0] < 0 and 0 < rows[0, 1] < 1


def test_contact_value_error_is_exit_code_2(capsys):
    """A ValueError of the package: 'error: <message>' on stderr, exit code 2."""
    assert contact("--pressure", "1e6", "--q1", "1e4") == 2
    captured = capsys.readouterr()
    assert captured.err.startswith("error: ")
    assert "q1" in captured.err
    assert captured.out == ""


def test_contact_command_error_is_exit_code_2(capsys):
    assert cli.main(["contact", "--surface", "self-affine", "--hurst", "0.8", "--q0", "1e5",
                     "--q1", "1e9", "--pressure", "1e6"]) == 2
    assert capsys.readouterr().err.startswith("error: no effective modulus: give --e-star")


def test_contact_pull_off_column(tmp_path, capsys):
    path = tmp_path / "c.csv"
    assert contact(*ADHESION, "--pressure", "0", "1e6", "--pull-off", "--csv", str(path)) == 0
    header, rows = read_csv(path)
    assert header == CONTACT_HEADER + ["pull_off_stress_Pa"]
    sigma_c = rows[:, -1]
    assert sigma_c[0] > 0 and np.all(sigma_c == sigma_c[0])
    assert f"pull-off stress: {sigma_c[0]:.5g} Pa" in capsys.readouterr().out


# --------------------------------------------------------------------------------------------
# item 13: negative numbers in exponent notation are values
# --------------------------------------------------------------------------------------------


def test_parser_reads_negative_exponent_notation():
    parser = cli.build_parser()
    args = parser.parse_args(["contact", "--pressure", "-0.5e6", "-1E+6", "-.5", "-2", "3e5"])
    assert args.pressure == [-0.5e6, -1e6, -0.5, -2.0, 3e5]
    args = parser.parse_args(["contact", "--pressure-range", "-1e6", "1e6", "3"])
    assert args.pressure_range == [-1e6, 1e6, 3.0]
    args = parser.parse_args(["contact", "--pressure-range", "-1e6", "-1e-3", "3",
                              "--e-star", "1e9"])
    assert args.pressure_range == [-1e6, -1e-3, 3.0] and args.e_star == 1e9


@pytest.mark.parametrize("pressure_args, expected", [
    (["--pressure", "-0.5e5", "1e6"], [-0.5e5, 1e6]),
    (["--pressure-range", "-1e5", "1e6", "3"], [-1e5, 4.5e5, 1e6]),
])
def test_contact_negative_pressures(tmp_path, pressure_args, expected):
    path = tmp_path / "c.csv"
    assert contact(*ADHESION, *pressure_args, "--csv", str(path)) == 0
    header, rows = read_csv(path)
    col = dict(zip(header, rows.T))
    np.testing.assert_allclose(col["pressure_Pa"], expected)
    assert 0 < col["area"][0] < col["area"][-1] <= 1
    assert col["force_per_contact_area_Pa"][0] < 0 < col["compression_per_contact_area_Pa"][0]


def test_contact_negative_pressure_spaced_and_equals_forms_agree(tmp_path):
    spaced, equals = tmp_path / "spaced.csv", tmp_path / "equals.csv"
    assert contact(*ADHESION, "--pressure", "-1e5", "--csv", str(spaced)) == 0
    assert contact(*ADHESION, "--pressure=-1e5", "--csv", str(equals)) == 0
    assert spaced.read_bytes() == equals.read_bytes()
    assert read_csv(spaced)[1][0, 0] == -1e5


def test_contact_negative_pressure_without_adhesion_is_the_package_error(capsys):
    """-1e6 reaches the package (not argparse), whose ValueError says adhesion is needed."""
    assert contact("--pressure", "-1e6") == 2
    err = capsys.readouterr().err
    assert err.startswith("error: pressure must be >= 0 [Pa] without adhesion")
    assert "-1000000.0" in err


# --------------------------------------------------------------------------------------------
# item 12: outputs are replaced only when complete, the CSV and PNG of a run as a set
# --------------------------------------------------------------------------------------------


def test_figure2_says_when_it_replaces(old_figure2, capsys):
    out, _ = old_figure2
    capsys.readouterr()
    assert figure2(out, 4) == 0
    text = capsys.readouterr().out
    assert f"wrote {out / 'figure2.csv'} (replaced the existing file)\n" in text
    assert f"wrote {out / 'figure2.png'} (replaced the existing file)\n" in text
    assert sorted(os.listdir(out)) == ["figure2.csv", "figure2.png"]
    assert len(read_csv(out / "figure2.csv")[1]) == 4


def test_contact_says_when_it_replaces(tmp_path, capsys):
    path = tmp_path / "c.csv"
    path.write_text("an older table\n")
    assert contact("--pressure", "1e6", "--csv", str(path)) == 0
    assert f"wrote {path} (replaced the existing file)\n" in capsys.readouterr().out
    assert read_csv(path)[0] == CONTACT_HEADER


def test_figure2_interrupt_while_plotting_keeps_the_old_pair(old_figure2, monkeypatch, capsys):
    """Ctrl-C after the new CSV is written, during the plot: the old CSV and PNG stay."""
    out, old = old_figure2

    def interrupted_plot(*args, **kwargs):
        path = next(a for a in args if isinstance(a, (str, os.PathLike)))
        with open(path, "wb") as fh:
            fh.write(b"\x89PNG half a picture")
        raise KeyboardInterrupt

    monkeypatch.setattr(cli, "_plot_figure2", interrupted_plot)
    assert figure2(out, 5) == 130
    assert "interrupted" in capsys.readouterr().err
    assert snapshot(out) == old  # same two files, same bytes, no temporary file left


class _InterruptedWriter:
    """csv.writer that raises KeyboardInterrupt at its third row (the header is the first)."""

    def __init__(self, fh, *args, **kwargs):
        import csv as real_csv

        self._writer = real_csv.writer(fh, *args, **kwargs)
        self._rows = 0

    def writerow(self, row):
        self._rows += 1
        if self._rows == 3:
            raise KeyboardInterrupt
        return self._writer.writerow(row)


@pytest.fixture(autouse=True)
def default_sigint():
    """Ctrl-C raises KeyboardInterrupt during each test, as in an interactive shell.

    A process started in the background by a non-interactive shell (as CI may be) inherits
    SIGINT ignored; the tests of the Ctrl-C handling need Python's default handler.
    """
    before = signal.getsignal(signal.SIGINT)
    signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, before)


@pytest.fixture
def interrupted_csv(monkeypatch):
    # the CSV tables are written in cli_output, which looks up csv.writer there
    monkeypatch.setattr(cli_output, "csv", types.SimpleNamespace(writer=_InterruptedWriter))


def test_figure2_interrupt_while_writing_csv_keeps_the_old_pair(old_figure2, interrupted_csv):
    out, old = old_figure2
    assert figure2(out, 5) == 130
    assert snapshot(out) == old


def test_contact_interrupt_while_writing_csv_keeps_the_old_file(tmp_path, interrupted_csv):
    path = tmp_path / "c.csv"
    path.write_bytes(b"pressure_Pa,area\n1.0,0.5\n2.0,0.6\n3.0,0.7\n")
    old = snapshot(tmp_path)
    assert contact("--pressure", "1e5", "1e6", "2e6", "--csv", str(path)) == 130
    assert snapshot(tmp_path) == old


def test_figure2_ctrl_c_between_the_renames_still_gives_one_runs_pair(old_figure2,
                                                                       monkeypatch, capsys):
    """SIGINT right after figure2.csv is renamed into place: figure2.png (of the same run) is
    renamed too before the KeyboardInterrupt, never a new CSV beside an old PNG."""
    out, old = old_figure2
    real_replace = os.replace

    def replace_then_sigint(src, dst, *args, **kwargs):
        real_replace(src, dst, *args, **kwargs)
        if os.path.basename(dst) == "figure2.csv":
            signal.raise_signal(signal.SIGINT)

    monkeypatch.setattr(os, "replace", replace_then_sigint)
    assert figure2(out, 5) == 130
    assert "interrupted" in capsys.readouterr().err
    new = snapshot(out)
    assert sorted(new) == ["figure2.csv", "figure2.png"]
    assert len(read_csv(out / "figure2.csv")[1]) == 5
    assert new["figure2.png"] != old["figure2.png"]
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_output_set_works_outside_the_main_thread(tmp_path, capsys):
    """Where no signal handler can be set, the files are still written whole and renamed."""
    final = tmp_path / "t.csv"
    errors = []

    def write():
        try:
            with cli._OutputSet() as outputs:
                with open(outputs.path(str(final)), "w") as fh:
                    fh.write("a\n1\n")
                outputs.commit()
        except BaseException as exc:  # pragma: no cover - reported below
            errors.append(exc)

    thread = threading.Thread(target=write)
    thread.start()
    thread.join()
    assert errors == []
    assert os.listdir(tmp_path) == ["t.csv"] and final.read_text() == "a\n1\n"
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


@pytest.mark.skipif(os.name != "posix", reason="POSIX permission bits")
def test_outputs_get_the_usual_permissions(tmp_path):
    """Not mkstemp's 0o600: a new file gets 0o666 less the umask, a replaced one keeps its own."""
    umask = os.umask(0o022)
    try:
        new, kept = tmp_path / "new.csv", tmp_path / "kept.csv"
        kept.write_text("old\n")
        kept.chmod(0o640)
        with cli._OutputSet() as outputs:
            for final in (new, kept):
                with open(outputs.path(str(final)), "w") as fh:
                    fh.write("x\n")
            outputs.commit()
    finally:
        os.umask(umask)
    assert stat.S_IMODE(new.stat().st_mode) == 0o644
    assert stat.S_IMODE(kept.stat().st_mode) == 0o640
    assert kept.read_text() == "x\n"


def test_output_folder_that_is_a_file_is_an_os_error(tmp_path, capsys):
    blocker = tmp_path / "taken"
    blocker.write_text("")
    assert figure2(blocker, 3, "--no-plot") == 1
    assert capsys.readouterr().err.startswith("error: ")


# --------------------------------------------------------------------------------------------
# item 14: missing plot extra, metavars, .gitignore
# --------------------------------------------------------------------------------------------


def test_figure2_without_matplotlib_names_the_extra(old_figure2, monkeypatch, capsys):
    out, old = old_figure2
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # import matplotlib fails
    monkeypatch.setitem(sys.modules, "matplotlib.pyplot", None)
    capsys.readouterr()
    assert figure2(out, 4) == 0
    text = capsys.readouterr().out
    assert "plot: skipped (matplotlib is not installed; install the 'plot' extra" in text
    assert 'persson_fast[plot]' in text and '.[plot]' in text
    assert f"note: {out / 'figure2.png'} is left from an earlier run" in text
    assert len(read_csv(out / "figure2.csv")[1]) == 4  # the CSV is still written
    assert (out / "figure2.png").read_bytes() == old["figure2.png"]


def test_figure2_no_plot_writes_only_the_csv(tmp_path, capsys):
    assert figure2(tmp_path, 3, "--no-plot") == 0
    assert os.listdir(tmp_path) == ["figure2.csv"]
    assert "plot: skipped (--no-plot)" in capsys.readouterr().out


def test_metavars_are_distinct():
    parser = cli.build_parser()
    contact_parser = next(a for a in parser._actions
                          if isinstance(a, type(parser._subparsers._group_actions[0])))
    contact_parser = contact_parser.choices["contact"]
    metavars = []
    for action in contact_parser._actions:
        if action.metavar is None:
            continue
        names = action.metavar if isinstance(action.metavar, tuple) else (action.metavar,)
        metavars.extend(names)
    assert len(metavars) == len(set(metavars)), sorted(metavars)
    help_text = contact_parser.format_help()
    assert "--hurst H " in help_text and "--h-rms HRMS" in help_text


def test_gitignore_lists_the_default_output_folder():
    gitignore = pathlib.Path(__file__).resolve().parents[1] / ".gitignore"
    if not gitignore.exists():
        pytest.skip("not a checkout")
    assert "persson_fast_out/" in gitignore.read_text().split()


# --------------------------------------------------------------------------------------------
# measured surfaces: --topography FILE, --psd FILE and the same keys in the TOML file
# --------------------------------------------------------------------------------------------
def _small_map(tmp_path):
    """A 64 x 64 synthetic map, 1 um wide, heights in um, as SurfaceTopography writes it."""
    pytest.importorskip("SurfaceTopography")
    from SurfaceTopography.Generation import fourier_synthesis

    return fourier_synthesis((64, 64), (1.0, 1.0), hurst=0.8, rms_slope=0.1, unit="um",
                             rng=np.random.default_rng(1))


def _area_of(capsys):
    rows = [line.split() for line in capsys.readouterr().out.splitlines()]
    return [float(r[1]) for r in rows if len(r) == 4 and r[-1] == "ok"]


@pytest.mark.parametrize("fmt", ["x3p", "gwy", "npy"])
def test_contact_topography_file_formats(fmt, tmp_path, capsys):
    import persson_fast as pf

    t = _small_map(tmp_path)
    path = tmp_path / f"map.{fmt}"
    extra = []
    if fmt == "x3p":
        t.to_x3p(str(path))
    elif fmt == "gwy":
        t.to_gwy(str(path))
    else:  # a bare matrix: the scan size and unit come from the flags
        np.save(path, np.asarray(t.heights()))
        extra = ["--physical-size", "1", "1", "--height-unit", "um"]
    code = cli.main(["contact", "--topography", str(path), "--e-star", "1e9",
                     "--pressure", "1e6", "1e7", *extra])
    assert code == 0
    area = _area_of(capsys)
    expect = pf.solve_contact(pf.TabulatedPSD.from_topography(t, window="hann",
                                                              detrend="plane"),
                              [1e6, 1e7], e_star=1e9).area
    np.testing.assert_allclose(area, expect, rtol=1e-5)


def test_contact_topography_q_band_and_toml(tmp_path, capsys):
    t = _small_map(tmp_path)
    t.to_x3p(str(tmp_path / "map.x3p"))
    (tmp_path / "scene.toml").write_text(
        'e_star = 1e9\npressures = [1e6]\n[surface]\nmodel = "topography"\n'
        'file = "map.x3p"\nq0 = 1.3e7\nq1 = 1e8\n')
    assert cli.main(["contact", "--config", str(tmp_path / "scene.toml")]) == 0
    out = capsys.readouterr().out
    assert "band [1.3e+07, 1e+08] 1/m" in out and "reliable up to" in out
    code = cli.main(["contact", "--topography", str(tmp_path / "map.x3p"), "--e-star", "1e9",
                     "--pressure", "1e6", "--q0", "1e5"])
    assert code == 2
    assert "scan is too small" in capsys.readouterr().err


def test_contact_psd_file_flags_and_toml(tmp_path, capsys):
    import persson_fast as pf

    s = pf.SelfAffine(hurst=0.8, q0=1e6, q1=1e9, slope_rms=0.1)
    s.to_csv(tmp_path / "psd.csv")
    assert cli.main(["contact", "--psd", str(tmp_path / "psd.csv"), "--e-star", "1e9",
                     "--pressure", "1e6"]) == 0
    a_flag = _area_of(capsys)
    (tmp_path / "scene.toml").write_text(
        'e_star = 1e9\npressures = [1e6]\n[surface]\nmodel = "psd"\nfile = "psd.csv"\n')
    assert cli.main(["contact", "--config", str(tmp_path / "scene.toml")]) == 0
    a_toml = _area_of(capsys)
    expect = pf.solve_contact(s, [1e6], e_star=1e9).area
    np.testing.assert_allclose(a_flag, expect, rtol=1e-3)
    assert a_toml == a_flag
    # a spectrum without units in a file: the flags give them
    (tmp_path / "bare.txt").write_text("1 2e-3\n10 3e-5\n100 1e-7\n")
    assert cli.main(["contact", "--psd", str(tmp_path / "bare.txt"), "--q-unit", "1/um",
                     "--c-unit", "um^4", "--e-star", "1e9", "--pressure", "1e6"]) == 0
    capsys.readouterr()
    assert cli.main(["contact", "--psd", str(tmp_path / "bare.txt"), "--e-star", "1e9",
                     "--pressure", "1e6"]) == 2
    assert "names no units" in capsys.readouterr().err


def test_contact_psd_and_surface_flags_conflict(tmp_path, capsys):
    assert cli.main(["contact", "--psd", "x.csv", "--surface", "capillary", "--e-star", "1e9",
                     "--pressure", "1e6"]) == 2
    assert "give one of --surface, --topography, --psd" in capsys.readouterr().err


# --- area theories (--theory, --theory-gamma) ---------------------------------------------

def test_cli_theory_names_match_the_package():
    from persson_fast import theories
    from persson_fast.cli import main as cli
    assert cli.THEORY_NAMES == theories.THEORIES


def test_cli_contact_theory(tmp_path, capsys):
    from persson_fast.cli import main as cli
    out = tmp_path / "t.csv"
    args = ["contact", "--surface", "self-affine", "--hurst", "0.8", "--q0", "1e4", "--q1", "1e9",
            "--h-rms", "1e-6", "--e-star", "1e9", "--pressure", "1e5", "1e6",
            "--theory", "yp08", "--theory-gamma", "0.45", "--csv", str(out)]
    assert cli.main(args) == 0
    text = capsys.readouterr().out
    assert "area theory: yp08, gamma = 0.45" in text
    import csv
    rows = list(csv.DictReader(open(out)))
    s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    ref = pf.solve_contact(s, [1e5, 1e6], e_star=1e9, theory="yp08", theory_gamma=0.45)
    assert np.allclose([float(r["area"]) for r in rows], ref.area, rtol=1e-12)
    base = pf.solve_contact(s, [1e5, 1e6], e_star=1e9)
    assert np.all(ref.area > base.area)


def test_cli_theory_with_adhesion(capsys):
    """wm17 serves adhesion; xu24 is refused with the reason."""
    from persson_fast.cli import main as cli
    args = ["contact", "--surface", "self-affine", "--hurst", "0.8", "--q0", "1e4", "--q1", "1e9",
            "--h-rms", "1e-6", "--e-star", "1e9", "--pressure", "1e6", "--theory", "wm17",
            "--work-of-adhesion", "0.05", "--rtol", "1e-3"]
    assert cli.main(args) == 0
    capsys.readouterr()
    rc = cli.main(args[:-5] + ["xu24"] + args[-4:])
    err = capsys.readouterr().err
    assert rc != 0 and "defined only at full magnification" in err


def test_cli_theory_from_config(tmp_path, capsys):
    from persson_fast.cli import main as cli
    cfg = tmp_path / "c.toml"
    cfg.write_text('e_star = 1e9\npressures = [1e6]\ntheory = "xu24"\n'
                   '[surface]\nmodel = "self-affine"\nhurst = 0.8\nq0 = 1e4\nq1 = 1e9\n'
                   'h_rms = 1e-6\n')
    assert cli.main(["contact", "--config", str(cfg)]) == 0
    assert "area theory: xu24" in capsys.readouterr().out
    cfg.write_text('e_star = 1e9\npressures = [1e6]\ntheory = "nope"\n'
                   '[surface]\nmodel = "self-affine"\nhurst = 0.8\nq0 = 1e4\nq1 = 1e9\n'
                   'h_rms = 1e-6\n')
    assert cli.main(["contact", "--config", str(cfg)]) != 0
    assert "theory must be one of" in capsys.readouterr().err


def test_console_script_exits_with_mains_code_and_frozen_objects():
    """``persson-fast`` (``cli.run``): main's exit code, the objects frozen out of the
    collector (its collections skip them) and its youngest generation's threshold raised;
    main called in-process leaves the collector alone."""
    import gc
    import subprocess
    import sys

    frozen, threshold = gc.get_freeze_count(), gc.get_threshold()
    assert cli.main(["--points", "1", "--out", "unused"]) == 2
    assert gc.get_freeze_count() == frozen and gc.get_threshold() == threshold
    code = ("import atexit, gc, sys; from persson_fast.cli import main as cli; "
            "atexit.register(lambda: print('frozen', gc.get_freeze_count() > 0, "
            "gc.get_threshold()[0])); "
            "sys.argv = ['persson-fast', '--points', '1']; cli.run()")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 2 and "--points must be >= 2" in proc.stderr
    assert proc.stdout.strip().endswith(f"frozen True {cli.RUN_GC_THRESHOLD}"), proc.stdout
