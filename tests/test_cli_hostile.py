"""The ``persson-fast contact`` command against a hostile or careless user (issue 42, items 2,
7 and 12): outputs that are one file, empty outputs and pressures in a TOML file, both
spellings of the pressures, errors that name the flags, statuses by name, ``--strict``,
warnings on one line, and SIGTERM while a large CSV file is written."""
import os
import pathlib
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

import persson_fast as pf
from persson_fast._kernels import status as status_codes
from persson_fast.cli import main as cli
from persson_fast.cli import parser as cli_parser

SCENE = ["--surface", "self-affine", "--hurst", "0.8", "--q0", "1e4", "--q1", "1e6",
         "--h-rms", "6e-6", "--e-star", "1e9"]
TOML_SCENE = ("e_star = 1e9\n{extra}\n[surface]\nmodel = 'self-affine'\nhurst = 0.8\n"
              "q0 = 1e4\nq1 = 1e6\nh_rms = 6e-6\n")
#: the scene of the status tests: sqrt(G1) = 2.7e5 Pa, so that u underflows at 1e8 Pa
UNDERFLOW = ["--surface", "self-affine", "--hurst", "0.8", "--q0", "1e4", "--q1", "1e7",
             "--h-rms", "1e-8", "--e-star", "1e9", "--separation"]


def _toml(tmp_path, extra):
    path = tmp_path / "scene.toml"
    path.write_text(TOML_SCENE.format(extra=extra))
    return path


@pytest.fixture
def nothing_solved(monkeypatch):
    """solve_contact and gap_distribution fail the test if they are reached."""
    def refuse(*args, **kwargs):
        raise AssertionError("solved, although the command line was refused")

    monkeypatch.setattr(pf, "solve_contact", refuse)
    monkeypatch.setattr(pf, "gap_distribution", refuse)


# --------------------------------------------------------------------------------------------
# item 2: two outputs of one run that are one file
# --------------------------------------------------------------------------------------------


def _spellings(tmp_path):
    """(csv, gaps) pairs that are one file, each spelt its own way."""
    target = tmp_path / "same.csv"
    (tmp_path / "sub").mkdir()
    (tmp_path / "link.csv").symlink_to(target)                 # dangling until written
    return {
        "identical": ("same.csv", "same.csv"),
        "dot": ("same.csv", "./same.csv"),
        "absolute": (str(target), "same.csv"),
        "dotdot": ("sub/../same.csv", "same.csv"),
        "double slash": (".//same.csv", "same.csv"),
        "symlink": ("link.csv", "same.csv"),
    }


@pytest.mark.parametrize("how", ["identical", "dot", "absolute", "dotdot", "double slash",
                                 "symlink"])
def test_csv_and_gaps_that_are_one_file_are_refused(tmp_path, monkeypatch, capsys,
                                                    nothing_solved, how):
    monkeypatch.chdir(tmp_path)
    csv_path, gaps_path = _spellings(tmp_path)[how]
    code = cli.main(["contact", *SCENE, "--pressure", "1e6", "--csv", csv_path, "--gaps",
                     gaps_path])
    err = capsys.readouterr().err
    assert code == 2, err
    assert "--csv and --gaps name the same file" in err, err
    assert str(tmp_path / "same.csv") in err
    assert not (tmp_path / "same.csv").exists()
    assert not [p for p in os.listdir(tmp_path) if p.endswith(".tmp")]


def test_a_hard_link_is_the_same_file_and_the_old_one_stays(tmp_path, capsys, nothing_solved):
    old = tmp_path / "old.csv"
    old.write_bytes(b"pressure_Pa,area\n1.0,0.5\n")
    os.link(old, tmp_path / "hard.csv")
    code = cli.main(["contact", *SCENE, "--pressure", "1e6", "--csv", str(old), "--gaps",
                     str(tmp_path / "hard.csv")])
    assert code == 2
    assert "name the same file" in capsys.readouterr().err
    assert old.read_bytes() == b"pressure_Pa,area\n1.0,0.5\n"


def test_same_file_from_toml_and_flag(tmp_path, monkeypatch, capsys, nothing_solved):
    monkeypatch.chdir(tmp_path)
    config = _toml(tmp_path, "pressures = [1e6]\ngaps = 'same.csv'")
    assert cli.main(["contact", "--config", str(config), "--csv", "./same.csv"]) == 2
    assert "--csv and --gaps name the same file" in capsys.readouterr().err


def test_distinct_outputs_are_both_written(tmp_path, monkeypatch, capsys):
    """The refusal is for one file only: two names in one folder are two files."""
    monkeypatch.chdir(tmp_path)
    assert cli.main(["contact", *SCENE, "--pressure", "1e6", "--csv", "same.csv", "--gaps",
                     "./other.csv"]) == 0
    assert (tmp_path / "same.csv").read_text().startswith("pressure_Pa,area,")
    assert (tmp_path / "other.csv").read_text().startswith("pressure_Pa,gap_m,")


@pytest.mark.parametrize("flag", ["--csv", "--gaps"])
def test_an_output_that_is_the_config_file_is_refused(tmp_path, capsys, nothing_solved, flag):
    config = _toml(tmp_path, "pressures = [1e6]")
    before = config.read_bytes()
    link = tmp_path / "cfg-link.toml"
    link.symlink_to(config)
    assert cli.main(["contact", "--config", str(config), flag, str(link)]) == 2
    err = capsys.readouterr().err
    assert f"{flag} names the input file of --config" in err, err
    assert config.read_bytes() == before


def test_an_output_that_is_the_spectrum_file_is_refused(tmp_path, capsys):
    spectrum = tmp_path / "spec.csv"
    spectrum.write_text("q [1/m], C [m^4]\n1e4,1e-30\n1e5,1e-33\n1e6,1e-36\n")
    before = spectrum.read_bytes()
    assert cli.main(["contact", "--psd", str(spectrum), "--e-star", "1e9", "--pressure", "1e6",
                     "--csv", str(tmp_path / "." / "spec.csv")]) == 2
    assert "--csv names the input file of --psd" in capsys.readouterr().err
    assert spectrum.read_bytes() == before


# --------------------------------------------------------------------------------------------
# item 7: empty settings in a TOML file are refused, not a run without output
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize("extra, message", [
    ("pressures = []", "pressures in --config must hold at least one nominal pressure [Pa]; "
                       "got []"),
    ("pressure = []", "pressure in --config must hold at least one nominal pressure [Pa]; "
                      "got []"),
    ("pressures = [1e6]\ngaps = ''", "gaps in --config must name a file; got ''"),
    ("pressures = [1e6]\ngaps = '  '", "gaps in --config must name a file; got '  '"),
    ("pressures = [1e6]\ncsv = ''", "csv in --config must name a file; got ''"),
    ("pressures = [1e6]\npressure = [2e6]", "--config gives 'pressures' and 'pressure'"),
    ("pressure = [1e6]\npressure_range = [1, 2, 2]",
     "--config gives 'pressure' and 'pressure_range'"),
    ("pressures = [1e6]\nstrict = 'yes'", "strict must be true or false"),
])
def test_empty_or_doubled_toml_settings_are_refused(tmp_path, capsys, nothing_solved, extra,
                                                    message):
    config = _toml(tmp_path, extra)
    assert cli.main(["contact", "--config", str(config)]) == 2
    captured = capsys.readouterr()
    assert message in captured.err, captured.err
    assert captured.out == ""


@pytest.mark.parametrize("flag", ["--csv", "--gaps"])
def test_empty_output_flags_are_refused(flag, capsys, nothing_solved):
    assert cli.main(["contact", *SCENE, "--pressure", "1e6", flag, ""]) == 2
    assert f"{flag} must name a file; got ''" in capsys.readouterr().err


# --------------------------------------------------------------------------------------------
# item 12: pressures spelt both ways, in both places
# --------------------------------------------------------------------------------------------


def _table(out):
    return [ln for ln in out.splitlines() if ln[:14].strip().replace("e+", "").isdigit()]


def test_pressure_and_pressures_are_one_setting(tmp_path, capsys):
    tables = []
    for argv in (["--pressure", "1e5", "1e6"], ["--pressures", "1e5", "1e6"]):
        assert cli.main(["contact", *SCENE, *argv]) == 0
        tables.append(_table(capsys.readouterr().out))
    for key in ("pressures", "pressure"):
        config = _toml(tmp_path, f"{key} = [1e5, 1e6]")
        assert cli.main(["contact", "--config", str(config)]) == 0
        tables.append(_table(capsys.readouterr().out))
    assert len(tables[0]) == 2
    assert all(t == tables[0] for t in tables), tables


def test_both_spellings_are_documented():
    helps = build_help()
    assert "--pressures is the same flag" in helps
    assert "pressures (or pressure, the same key" in helps
    page = (pathlib.Path(__file__).parents[1] / "docs" / "user-guide" / "cli.md").read_text()
    assert "`--pressures`" in page and "`pressure`" in page


def build_help():
    parser = cli.build_parser()
    sub = next(a for a in parser._actions if hasattr(a, "choices") and a.choices
               and "contact" in a.choices)
    return " ".join(sub.choices["contact"].format_help().split())


# --------------------------------------------------------------------------------------------
# item 12: errors of --psd name the flags
# --------------------------------------------------------------------------------------------


def test_psd_without_units_names_the_flags(tmp_path, capsys, nothing_solved):
    spectrum = tmp_path / "spec.txt"
    spectrum.write_text("1e4 1e-30\n1e5 1e-33\n1e6 1e-36\n")
    assert cli.main(["contact", "--psd", str(spectrum), "--e-star", "1e9", "--pressure",
                     "1e6"]) == 2
    err = capsys.readouterr().err
    assert "give --q-unit (one of 1/m" in err and "and --c-unit (one of m^4" in err, err
    assert "q_unit" not in err and "C_unit" not in err


@pytest.mark.parametrize("flags, message", [
    (["--q-unit", "1/x", "--c-unit", "m^4"], "--q-unit must be one of 1/m"),
    (["--q-unit", "1/m", "--c-unit", "m4"], "--c-unit must be one of m^4"),
])
def test_psd_bad_unit_names_the_flag(tmp_path, capsys, nothing_solved, flags, message):
    spectrum = tmp_path / "spec.txt"
    spectrum.write_text("1e4 1e-30\n1e5 1e-33\n1e6 1e-36\n")
    assert cli.main(["contact", "--psd", str(spectrum), *flags, "--e-star", "1e9",
                     "--pressure", "1e6"]) == 2
    err = capsys.readouterr().err
    assert message in err, err
    assert "_unit" not in err


# --------------------------------------------------------------------------------------------
# item 12: statuses by name; --strict
# --------------------------------------------------------------------------------------------


def test_every_status_code_has_its_name():
    for code in status_codes.STATUS_MESSAGES:
        name = cli.status_name(code)
        assert name == "ok" if code == 0 else getattr(status_codes, name) == code
    names = [cli.status_name(c) for c in status_codes.STATUS_MESSAGES]
    assert len(set(names)) == len(names)
    assert cli.status_name(999) == "code 999"


def test_flagged_row_prints_its_name_and_strict_exits_3(tmp_path, capsys):
    path = tmp_path / "c.csv"
    argv = ["contact", *UNDERFLOW, "--pressure", "1e5", "1e8", "--csv", str(path)]
    assert cli.main(argv) == 0                       # without --strict: said, exit 0
    out = capsys.readouterr().out
    rows = _table(out)
    assert rows[0].endswith("  ok") and rows[1].endswith("  SEPARATION_UNDERFLOW"), rows
    assert "code 22" not in out
    assert cli.main([*argv, "--strict"]) == cli.FLAGGED_EXIT_CODE == 3
    captured = capsys.readouterr()
    assert "error: --strict: 1 of 2 pressure(s) flagged (SEPARATION_UNDERFLOW)" in captured.err
    assert f"wrote {path}" in captured.out          # the files are written first
    status = np.loadtxt(path, delimiter=",", skiprows=1, usecols=4)
    assert list(status) == [0, status_codes.SEPARATION_UNDERFLOW]


def test_strict_from_toml_and_a_clean_run(tmp_path, capsys):
    config = _toml(tmp_path, "pressures = [1e5, 1e6]\nstrict = true")
    assert cli.main(["contact", "--config", str(config)]) == 0     # nothing flagged
    assert "--strict" not in capsys.readouterr().err
    config = tmp_path / "u.toml"
    config.write_text("e_star = 1e9\npressures = [1e8]\nstrict = true\nseparation = true\n"
                      "[surface]\nmodel = 'self-affine'\nhurst = 0.8\nq0 = 1e4\nq1 = 1e7\n"
                      "h_rms = 1e-8\n")
    assert cli.main(["contact", "--config", str(config)]) == 3


def test_strict_and_exit_codes_are_documented():
    helps = build_help()
    assert "--strict exit with code 3 when a result is flagged" in helps
    assert "exit codes:" in helps and "3 --strict, and a result is flagged" in helps
    assert "143 terminated (SIGTERM)" in helps
    page = (pathlib.Path(__file__).parents[1] / "docs" / "user-guide" / "cli.md").read_text()
    assert "--strict" in page and "exit code 3" in page and "143" in page


# --------------------------------------------------------------------------------------------
# item 12: a warning is one clean line
# --------------------------------------------------------------------------------------------


def test_a_warning_is_one_line_once(capsys):
    assert cli.main(["contact", *SCENE[:-2], "--e-star", "1e4", "--pressure", "1e3"]) == 0
    err = capsys.readouterr().err
    lines = err.splitlines()
    assert len(lines) == 1, err                   # the package warns 3 times: printed once
    assert lines[0].startswith("warning: e_star = 10000.0 Pa is below 100000 Pa")
    assert ".py" not in err and "UserWarning" not in err


def test_warnings_filters_are_put_back():
    import warnings

    before = (warnings.showwarning, list(warnings.filters))
    assert cli.main(["contact", *SCENE[:-2], "--e-star", "1e4", "--pressure", "1e3"]) == 0
    assert (warnings.showwarning, list(warnings.filters)) == before


# --------------------------------------------------------------------------------------------
# item 7: SIGTERM while a large CSV file is written
# --------------------------------------------------------------------------------------------


def test_sigterm_while_writing_a_large_csv_keeps_the_old_file(tmp_path):
    """SIGTERM once the temporary file exists (the table being written): exit code 143,
    'terminated', the temporary file removed and the old file byte for byte as it was."""
    if os.environ.get("NUMBA_DISABLE_JIT") == "1":
        pytest.skip("compiled code only (a subprocess)")
    path = tmp_path / "big.csv"
    old = b"pressure_Pa,area\n1.0,0.5\n"
    path.write_bytes(old)
    argv = [sys.executable, "-m", "persson_fast.cli", "contact", *SCENE, "--quiet",
            "--pressure-range", "1e4", "1e6", "400000", "--csv", str(path)]
    proc = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            cwd=tmp_path)
    deadline = time.monotonic() + 120
    try:
        while time.monotonic() < deadline and proc.poll() is None:
            if any(p.endswith(".tmp") for p in os.listdir(tmp_path)):
                break
            time.sleep(0.002)
        assert proc.poll() is None, "the run ended before its temporary file was seen"
        time.sleep(0.05)                                       # rows being written
        proc.send_signal(signal.SIGTERM)
        err = proc.communicate(timeout=60)[1].decode()
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert proc.returncode == 143, err
    assert err.strip().endswith("terminated"), err
    assert sorted(os.listdir(tmp_path)) == ["big.csv"]
    assert path.read_bytes() == old


def test_sigterm_is_held_during_the_renames(tmp_path, monkeypatch, capsys):
    """SIGTERM between the renames of one run's files: the set is completed, then the run
    ends as terminated (143); the handler before the run is put back."""
    real_replace = os.replace
    reached_outside = []        # the SIGTERMs that reached the handler in place before the run

    def outside(signum, frame):
        reached_outside.append(signum)

    def replace_then_sigterm(src, dst, *args, **kwargs):
        real_replace(src, dst, *args, **kwargs)
        if os.path.basename(dst) == "c.csv":
            signal.raise_signal(signal.SIGTERM)

    before = signal.signal(signal.SIGTERM, outside)    # this process is not ended meanwhile
    try:
        monkeypatch.setattr(os, "replace", replace_then_sigterm)
        code = cli.main(["contact", *SCENE, "--pressure", "1e6", "--csv",
                         str(tmp_path / "c.csv"), "--gaps", str(tmp_path / "g.csv")])
        assert signal.getsignal(signal.SIGTERM) is outside         # put back after the run
    finally:
        signal.signal(signal.SIGTERM, before)
    assert code == 143 and not reached_outside
    captured = capsys.readouterr()
    assert "terminated" in captured.err
    assert sorted(os.listdir(tmp_path)) == ["c.csv", "g.csv"]       # both, no .tmp


def test_parser_exit_codes_match_main():
    assert cli_parser.FLAGGED_EXIT_CODE == cli.FLAGGED_EXIT_CODE
    assert cli.INTERRUPTED_EXIT_CODE == 130
