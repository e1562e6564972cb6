"""Surface models declare their parameters once (``PARAMETERS``, ``MODEL``); the command line
and scan read the registry ``SURFACE_MODELS``. A new model is one file: a Surface subclass in a
module of its own, with no edit to scan.py or cli.py."""
import csv
import importlib
import pathlib
import sys
import textwrap

import numpy as np
import pytest

import persson_fast as pf
from persson_fast.cli import main as cli
from persson_fast.surfaces.models import (SURFACE_MODELS, Parameter, SurfaceModel, band_parameters,
                                   register_surface_model)

#: the module (``pf.scan`` is the function)
scan_module = importlib.import_module("persson_fast.scan.grid")
#: the command line and scan, with the modules their code lives in
ENTRY_MODULES = ("persson_fast.cli", "persson_fast.cli.parser", "persson_fast.cli.config",
                 "persson_fast.cli.output", "persson_fast.scan", "persson_fast.scan.grid",
                 "persson_fast.scan.run", "persson_fast.scan.results")

# --------------------------------------------------------------------------------------------
# the package's own models: what the command line accepted before the declarations
# --------------------------------------------------------------------------------------------

#: [surface] keys per model, in order (the error message of an unknown key lists them so)
BUILTIN_KEYS = {
    "capillary": ("temperature", "surface_tension", "q_c", "q0", "q1", "density", "gravity"),
    "self-affine": ("hurst", "q0", "q1", "q_r", "h_rms", "slope_rms", "C0"),
    "topography": ("file", "q0", "q1", "hurst", "bins_per_decade", "unit", "physical_sizes"),
    "psd": ("file", "q_unit", "C_unit", "q0", "q1"),
}
BUILTIN_REQUIRED = {
    "capillary": ("temperature", "surface_tension", "q_c", "q0", "q1"),
    "self-affine": ("hurst", "q0", "q1"),
    "topography": ("file",),
    "psd": ("file",),
}
#: the flag of each key (the file's flag is the model's own)
BUILTIN_FLAGS = {
    "temperature": "--temperature", "surface_tension": "--surface-tension", "q_c": "--q-c",
    "q0": "--q0", "q1": "--q1", "density": "--density", "gravity": "--gravity",
    "hurst": "--hurst", "q_r": "--q-r", "h_rms": "--h-rms", "slope_rms": "--slope-rms",
    "C0": "--c0", "bins_per_decade": "--bins-per-decade", "unit": "--height-unit",
    "physical_sizes": "--physical-size", "q_unit": "--q-unit", "C_unit": "--c-unit",
}
#: [surface] keys whose values are text
BUILTIN_TEXT = {"file", "unit", "q_unit", "C_unit"}
#: the units scan labels the package's parameters with
BUILTIN_UNITS = {
    "e_star": "Pa", "work_of_adhesion": "J/m^2", "energy_correction": "-",
    "detachment_prefactor": "-", "hardness": "Pa", "hurst": "-", "q0": "1/m", "q1": "1/m",
    "q_r": "1/m", "h_rms": "m", "slope_rms": "-", "C0": "m^4", "temperature": "K",
    "surface_tension": "J/m^2", "q_c": "1/m", "density": "kg/m^3", "gravity": "m/s^2",
}
#: (flag, metavar, help) of every surface flag of ``contact --help``, by group, in order
BUILTIN_HELP = {
    "capillary-wave surface": [
        ("--temperature", "T", "temperature [K]"),
        ("--surface-tension", "GAMMA", "surface tension [J/m^2]"),
        ("--q-c", "QC", "crossover wavevector [1/m]"),
        ("--density", "RHO", "mass density [kg/m^3] (default 0)"),
        ("--gravity", "G", "gravity [m/s^2] (default 9.81)")],
    "self-affine surface": [
        ("--hurst", "H", "Hurst exponent [-]"),
        ("--q-r", "QR", "roll-off wavevector [1/m]"),
        ("--h-rms", "HRMS", "rms height [m]"),
        ("--slope-rms", "S", "rms slope [-]"),
        ("--c0", "C0", "plateau of the spectrum [m^4]")],
    "measured surface": [
        ("--topography", "MAP", "height map or line scan; q0 defaults to 2 pi/L, q1 to "
                                "pi/pixel (or the file's reliability cut-off)"),
        ("--psd", "FILE.csv", "two-column spectrum file q, C"),
        ("--bins-per-decade", "NBINS", "log bins per decade of the measured spectrum "
                                       "(default 10)"),
        ("--height-unit", "HUNIT", "length unit of a topography file that names none (m, mm, "
                                   "um, nm, A, pm, km)"),
        ("--physical-size", "SIZE", "scan size of a topography file that gives none, in "
                                    "--height-unit"),
        ("--q-unit", "QUNIT", "unit of q in --psd (1/m, 1/mm, 1/um, 1/nm, 1/A)"),
        ("--c-unit", "CUNIT", "unit of C in --psd (m^4, mm^4, um^4, nm^4, A^4)")],
    "all models": [
        ("--q0", "Q0", "smallest wavevector [1/m]"),
        ("--q1", "Q1", "largest wavevector [1/m]")],
}


def _contact_parser():
    parser = cli.build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    return sub.choices["contact"]


def test_builtin_declarations_are_what_the_command_line_accepted():
    builtin = {name: m for name, m in SURFACE_MODELS.items() if name in BUILTIN_KEYS}
    assert list(builtin) == list(BUILTIN_KEYS)
    for name, model in builtin.items():
        assert tuple(model.parameters) == BUILTIN_KEYS[name], name
        assert model.required == BUILTIN_REQUIRED[name], name
        for key, p in model.parameters.items():
            if key == "file":
                assert p.selects and p.path and p.flag_for(key) == f"--{name}"
            else:
                assert not p.selects and p.flag_for(key) == BUILTIN_FLAGS[key], (name, key)
            assert (p.type is str) == (key in BUILTIN_TEXT), (name, key)
    assert pf.CapillaryWaves.PARAMETERS is not pf.SelfAffine.PARAMETERS
    assert SURFACE_MODELS["capillary"].build is pf.CapillaryWaves
    assert SURFACE_MODELS["self-affine"].build is pf.SelfAffine
    assert cli._surface_choices() == ("capillary", "self-affine")


def test_builtin_units_of_scan():
    assert scan_module.PARAMETER_UNITS == BUILTIN_UNITS
    for cls in (pf.CapillaryWaves, pf.SelfAffine):
        for key, p in cls.PARAMETERS.items():
            assert scan_module._parameter_units(cls)[key] == p.unit == BUILTIN_UNITS[key]


def test_builtin_help_is_generated_as_before():
    ct = _contact_parser()
    for title, rows in BUILTIN_HELP.items():
        group = next(g for g in ct._action_groups if g.title == title)
        got = [(a.option_strings[0], a.metavar, a.help) for a in group._group_actions]
        assert got == rows, title
    titles = [g.title for g in ct._action_groups]
    assert titles.index("measured surface") < titles.index("all models") < titles.index("adhesion")
    surface = next(a for a in ct._actions if a.dest == "surface")
    assert surface.choices == ("capillary", "self-affine")
    nargs = {a.option_strings[0]: (a.type, a.nargs) for a in ct._actions if a.option_strings}
    assert nargs["--physical-size"] == (float, "+")
    assert nargs["--bins-per-decade"] == (int, None)
    assert nargs["--psd"] == (str, None)


# --------------------------------------------------------------------------------------------
# a new model: one file, a Surface subclass that declares its parameters
# --------------------------------------------------------------------------------------------

NEW_MODEL = '''
"""A power-law spectrum given by its value at q0: C(q) = C(q0) (q/q0)^-exponent on [q0, q1]."""
import numpy as np

from persson_fast.surfaces.models import Parameter, Surface, band_parameters


class PowerLawPSD(Surface):
    """C(q) = c_q0 (q/q0)^(-exponent) for q0 <= q <= q1.

    Parameters
    ----------
    c_q0 : float
        C at q0, > 0. [m^4]
    exponent : float
        Power of the decay, C ~ q^-exponent. [-]
    q0, q1 : float
        Band limits. [1/m]
    """

    MODEL = "power-law"
    PARAMETERS = {
        "c_q0": Parameter("m^4", "spectrum at q0", required=True, metavar="C_Q0"),
        "exponent": Parameter("-", "power of the decay", required=True, metavar="N"),
        **band_parameters(),
    }

    def __init__(self, c_q0, exponent, q0, q1):
        if not c_q0 > 0:
            raise ValueError(f"c_q0 must be > 0 [m^4]; got c_q0 = {c_q0!r}")
        self.c_q0, self.exponent = float(c_q0), float(exponent)
        self.q0, self.q1 = float(q0), float(q1)

    def _psd_inside(self, q):
        return self.c_q0 * (q / self.q0) ** -self.exponent

    def _integral(self, k, a, b):
        s = k + 1.0 - self.exponent
        c = self.c_q0 * self.q0 ** self.exponent
        if s == 0.0:
            return c * np.log(b / a)
        return c * (b ** s - a ** s) / s

    def _repr_params(self):
        return {"c_q0": self.c_q0, "exponent": self.exponent, "q0": self.q0, "q1": self.q1}
'''

#: the new model's scene and the self-affine surface with the same spectrum (q_r = q0,
#: exponent 2(1 + H))
HURST, C_Q0, Q0, Q1, E_STAR = 0.8, 1e-30, 1e5, 1e9, 1e9
PRESSURES = [1e5, 1e6]


@pytest.fixture
def new_model(tmp_path, monkeypatch):
    """The module file power_law_surface.py, imported: its class registers itself."""
    (tmp_path / "power_law_surface.py").write_text(textwrap.dedent(NEW_MODEL))
    monkeypatch.syspath_prepend(str(tmp_path))
    sys.modules.pop("power_law_surface", None)
    module = importlib.import_module("power_law_surface")
    yield module.PowerLawPSD
    SURFACE_MODELS.pop("power-law", None)
    sys.modules.pop("power_law_surface", None)


def _self_affine():
    return pf.SelfAffine(hurst=HURST, q0=Q0, q1=Q1, C0=C_Q0)


def test_new_model_registers_itself(new_model):
    model = SURFACE_MODELS["power-law"]
    assert model.build is new_model and model.title == "power-law surface"
    assert tuple(model.parameters) == ("c_q0", "exponent", "q0", "q1")
    assert model.required == ("c_q0", "exponent", "q0", "q1")
    s = new_model(c_q0=C_Q0, exponent=2 * (1 + HURST), q0=Q0, q1=Q1)
    ref = _self_affine()
    np.testing.assert_allclose(s.h_rms, ref.h_rms, rtol=1e-12)
    np.testing.assert_allclose(s.slope_rms, ref.slope_rms, rtol=1e-12)
    # neither entry point (nor a module it was split into) names it: the declaration is all
    # they read
    for name in ENTRY_MODULES:
        text = pathlib.Path(importlib.import_module(name).__file__).read_text()
        assert "power-law" not in text and "c_q0" not in text


def test_scan_takes_the_new_models_parameters_as_axes(new_model):
    ds = pf.scan(new_model, {"c_q0": [C_Q0, 2 * C_Q0], "exponent": 2 * (1 + HURST), "q0": Q0,
                             "q1": Q1}, PRESSURES, e_star=E_STAR)
    assert ds.area.dims == ("c_q0", "pressure")
    assert ds.c_q0.attrs["units"] == "m^4" and ds.exponent.attrs["units"] == "-"
    assert ds.q0.attrs["units"] == "1/m"
    assert ds.attrs["surface_model"] == "PowerLawPSD"
    ref = pf.scan(pf.SelfAffine, {"C0": [C_Q0, 2 * C_Q0], "hurst": HURST, "q0": Q0, "q1": Q1},
                  PRESSURES, e_star=E_STAR)
    np.testing.assert_allclose(ds.area.values, ref.area.values, rtol=1e-9)
    # the declared unit in scan's messages
    with pytest.raises(ValueError, match=r"params\['c_q0'\] must be finite \[m\^4\]"):
        pf.scan(new_model, {"c_q0": [C_Q0, np.inf], "exponent": 3.6, "q0": Q0, "q1": Q1},
                PRESSURES, e_star=E_STAR)


def _contact_area(path):
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    return np.array([float(r["area"]) for r in rows])


def test_cli_runs_the_new_model_from_flags_and_toml(new_model, tmp_path, capsys):
    expect = pf.solve_contact(_self_affine(), PRESSURES, e_star=E_STAR).area
    out = tmp_path / "flags.csv"
    args = ["contact", "--surface", "power-law", "--c-q0", str(C_Q0), "--exponent",
            str(2 * (1 + HURST)), "--q0", str(Q0), "--q1", str(Q1), "--e-star", str(E_STAR),
            "--pressure", *map(str, PRESSURES), "--csv", str(out)]
    assert cli.main(args) == 0
    assert "surface: PowerLawPSD(" in capsys.readouterr().out
    np.testing.assert_allclose(_contact_area(out), expect, rtol=1e-9)

    cfg = tmp_path / "c.toml"
    cfg.write_text(f'e_star = {E_STAR}\npressures = {PRESSURES}\ncsv = "toml.csv"\n'
                   f'[surface]\nmodel = "power-law"\nc_q0 = {C_Q0}\nexponent = '
                   f'{2 * (1 + HURST)}\nq0 = {Q0}\nq1 = {Q1}\n')
    monkey_out = tmp_path / "toml.csv"
    assert cli.main(["contact", "--config", str(cfg), "--csv", str(monkey_out)]) == 0
    np.testing.assert_allclose(_contact_area(monkey_out), expect, rtol=1e-9)

    help_text = _contact_parser().format_help()
    assert "power-law surface:" in help_text
    assert "--c-q0 C_Q0" in help_text and "spectrum at q0 [m^4]" in help_text
    assert "{capillary,self-affine,power-law}" in help_text


def test_cli_checks_the_new_model_from_its_declaration(new_model, capsys):
    base = ["--e-star", "1e9", "--pressure", "1e6"]
    assert cli.main(["contact", "--surface", "power-law", "--q0", "1e5", "--q1", "1e9",
                     *base]) == 2
    assert ("surface model 'power-law' needs --c-q0 (or c_q0 in [surface]), --exponent (or "
            "exponent in [surface])") in capsys.readouterr().err
    assert cli.main(["contact", "--surface", "power-law", "--c-q0", "1e-30", "--exponent", "3",
                     "--q0", "1e5", "--q1", "1e9", "--hurst", "0.8", *base]) == 2
    assert "--hurst do(es) not apply to surface model 'power-law'" in capsys.readouterr().err
    # its flags are another model's strays
    assert cli.main(["contact", "--surface", "self-affine", "--hurst", "0.8", "--q0", "1e5",
                     "--q1", "1e9", "--h-rms", "1e-8", "--exponent", "3", *base]) == 2
    assert "--exponent do(es) not apply to surface model 'self-affine'" in capsys.readouterr().err


def test_register_refuses_what_the_command_line_could_not_take(new_model):
    def build(a, q0=None):
        return None

    with pytest.raises(ValueError, match="surface model 'power-law' is registered already"):
        register_surface_model(SurfaceModel("power-law", {"a": Parameter("m", "a")}, build,
                                            "t"))
    with pytest.raises(ValueError, match="lower-case letters, digits and '-'"):
        register_surface_model(SurfaceModel("Power Law", {"a": Parameter("m", "a")}, build,
                                            "t"))
    with pytest.raises(ValueError, match="parameter 'b' of surface model 'x-test' is not a "
                                         "keyword argument"):
        register_surface_model(SurfaceModel("x-test", {"b": Parameter("m", "b")}, build, "t"))
    with pytest.raises(ValueError, match="flag --q0 of surface model 'x-test'"):
        register_surface_model(SurfaceModel(
            "x-test", {"q0": Parameter("1/m", "q0", type=str)}, build, "t"))
    with pytest.raises(ValueError, match="must be a Parameter"):
        register_surface_model(SurfaceModel("x-test", {"a": ("m", "a")}, build, "t"))
    assert "x-test" not in SURFACE_MODELS
    assert band_parameters(required=False)["q0"].required is False


def test_unit_help_lists_every_accepted_ascii_unit():
    """The help of --q-unit, --c-unit and --height-unit lists the units the readers take (it
    listed fewer: 1/A, mm^4, A^4, A, pm and km were accepted but not named)."""
    from persson_fast.surfaces.topography import _LENGTH_UNITS, C_UNITS, Q_UNITS

    helps = {a.option_strings[0]: a.help for a in _contact_parser()._actions if a.option_strings}
    for flag, table in (("--q-unit", Q_UNITS), ("--c-unit", C_UNITS),
                        ("--height-unit", _LENGTH_UNITS)):
        listed = helps[flag].rsplit("(", 1)[1].rstrip(")").split(", ")
        assert listed == [u for u in table if u.isascii()], flag
