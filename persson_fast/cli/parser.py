"""The argument parser of the ``persson-fast`` command.

:func:`build_parser` builds the parser of the subcommands figure2, contact and info; the
flags of the surface models (``--surface NAME``, ``--topography``, ``--psd`` and one flag per
declared parameter, with its unit in the help) are made from the models' declarations,
``persson_fast.surfaces.models.SURFACE_MODELS``. :class:`_Parser` reads any negative number as a
value; :class:`CommandError` is an invalid command line or configuration file.
"""
from __future__ import annotations

import argparse
import re

from ..methods import METHODS
from ..plan import refusal_reasons
from ..surfaces.models import SEED_POISSON as SEED_POISSON_DEFAULT
from ..surfaces.models import BAND, SURFACE_MODELS

__all__ = ["build_parser", "CommandError", "THEORY_NAMES", "FIGURE2_COLUMNS"]

#: the area theories of ``contact --theory`` (``persson_fast.theories.THEORIES``, spelt out
#: here so that the parser does not import the compiled theory kernels; a test keeps the two
#: equal)
THEORY_NAMES = ("persson01", "yp08", "wm17", "xu24")

#: title of the group of flags every surface model shares (the band, ``surfaces.BAND``)
_ALL_MODELS = "all models"


#: the columns of figure2.csv and what each holds (the docstring of persson_fast.cli says the
#: same)
FIGURE2_COLUMNS = {
    "pressure_Pa": "nominal pressure p_nom [Pa]",
    "area_no_adhesion": "A/A0 without adhesion [-]",
    "area_adhesion": "A/A0 with adhesion (Delta gamma = 0.06 J/m^2) [-]",
    "force_per_contact_area_adhesion_Pa":
        "p_nom A0/A with adhesion: net force per real contact area [Pa]",
    "compression_per_contact_area_adhesion_Pa":
        "load/A with adhesion: compressive load per real contact area, i.e. the net force "
        "plus the tension of the detached rims [Pa]",
    "pull_off_stress_Pa": "pull-off stress sigma_c, the same on every row [Pa]",
}

#: a negative number written any way float() reads it, exponent notation included. argparse's
#: own pattern (Python <= 3.12: '^-\d+$|^-\d*\.\d+$') takes -1e6 and -0.5e6 for flags.
_NEGATIVE_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$",
                              re.IGNORECASE)


class CommandError(ValueError):
    """An invalid command line or configuration file (printed like a package ValueError)."""


class _Parser(argparse.ArgumentParser):
    """An ArgumentParser that reads ``-1e6``, ``-0.5e6``, ``-.5`` (any negative number) as a
    value, never as a flag; its subparsers are of the same class (``add_subparsers``)."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = _NEGATIVE_NUMBER


# --------------------------------------------------------------------------------------------
# parser
# --------------------------------------------------------------------------------------------


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``persson-fast`` (exposed for documentation and tests)."""
    from .._version import __version__

    parser = _Parser(
        prog="persson-fast",
        description="Persson contact mechanics: real contact area of rough surfaces.",
        epilog="Without a subcommand, 'figure2' is run.",
    )
    parser.add_argument("--version", action="version", version=f"persson_fast {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="{figure2,contact,info}")

    f2 = sub.add_parser(
        "figure2", help="the seed paper's PMMA scene: A/A0 against pressure (its Fig. 2)",
        description="Relative contact area of the seed paper's PMMA scene (frozen capillary "
                    "waves, E = 2.9 GPa) against the nominal pressure 0-100 MPa, with and "
                    "without adhesion, and its pull-off stress. Writes DIR/figure2.csv and "
                    "DIR/figure2.png; existing files are replaced (and said so).",
        epilog="columns of figure2.csv:\n" + "\n".join(
            f"  {name}: {text}" for name, text in FIGURE2_COLUMNS.items()),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    f2.add_argument("--out", default="persson_fast_out", metavar="DIR",
                    help="output folder (default: %(default)s)")
    f2.add_argument("--points", type=int, default=101, metavar="N",
                    help="number of pressures from 0 to 100 MPa (default: %(default)s)")
    f2.add_argument("--poisson", type=float, default=SEED_POISSON_DEFAULT, metavar="NU",
                    help="Poisson ratio of PMMA, not given by the paper (default: %(default)s)")
    f2.add_argument("--rtol", type=float, default=1e-6, metavar="R",
                    help="target relative accuracy (default: %(default)s)")
    f2.add_argument("--no-plot", action="store_true", help="do not write figure2.png")
    f2.add_argument("--quiet", action="store_true",
                    help="no note on stderr that kernels are being compiled")
    f2.add_argument("--check", action="store_true",
                    help="also solve the scene without adhesion with the grid solver 'cn' and "
                         "print its largest difference from the closed form (on a cold "
                         "numba cache this compiles the grid solver first)")

    ct = sub.add_parser(
        "contact", help="contact area of your own scene",
        description="Relative real contact area of a rough surface: a model (--surface), a "
                    "measured height map (--topography) or a spectrum file (--psd), with "
                    "adhesion, a yield wall (--hardness) and the corrected area theories "
                    "(--theory) as options, alone or together. Refused: "
                    + "; ".join(refusal_reasons()) + ". A TOML file (--config) may give "
                    "the same settings; flags override it.",
    )
    ct.add_argument("--config", metavar="FILE.toml",
                    help="TOML file: a [surface] table with model = "
                         + " | ".join(f"'{name}'" for name in SURFACE_MODELS)
                         + " and its parameters" + _path_keys_text()
                         + "; top-level e_star, pressures (or pressure_range = "
                         "[pmin, pmax, n]), method, rtol, csv, work_of_adhesion, "
                         "energy_correction, detachment_prefactor, pull_off, hardness, "
                         "hardness_exponent, theory, theory_gamma, separation")
    ct.add_argument("--surface", choices=_surface_choices(), help="surface model")
    _add_surface_flags(ct)
    ct.add_argument("--e-star", type=float, metavar="E", help="effective modulus E/(1-nu^2) [Pa]")
    g = ct.add_argument_group("adhesion")
    g.add_argument("--work-of-adhesion", type=float, metavar="DGAMMA",
                   help="work of adhesion [J/m^2] (default 0: no adhesion)")
    g.add_argument("--energy-correction", type=float, metavar="GAMMA_S",
                   help="gamma_S of S = gamma_S + (1 - gamma_S) P^2 (default: S = 1)")
    g.add_argument("--detachment-prefactor", type=float, metavar="BETA",
                   help="beta of seed Eq. 8 (default 1/sqrt 2)")
    g.add_argument("--pull-off", action="store_true",
                   help="also compute the pull-off stress (0 without adhesion) of the scene "
                        "as solved, its --theory and --hardness included")
    ct.add_argument("--hardness", type=float, metavar="SIGMA_Y",
                    help="penetration hardness [Pa]: the yield wall, with or without "
                         "adhesion; adds the elastic and plastic area columns; constant, or "
                         "at zeta = 1 with --hardness-exponent (in a TOML file also a table: "
                         "hardness = {zeta = [...], sigma_y = [...]})")
    ct.add_argument("--hardness-exponent", type=float, metavar="EXPONENT",
                    help="a scale-dependent hardness SIGMA_Y zeta^EXPONENT (needs --hardness)")
    ct.add_argument("--separation", action="store_true",
                    help="also print (and write to --csv) the mean interfacial separation u "
                         "[m], the contact stiffness K = -dp/du [Pa/m] and the stored elastic "
                         "energy U_el [J/m^2] (elastic scenes without adhesion, the original "
                         "theory; --energy-correction sets S)")
    g = ct.add_argument_group("area theory")
    g.add_argument("--theory", choices=THEORY_NAMES,
                   help="area theory: persson01 (the original, default) or a corrected one "
                        "(yp08, wm17 with or without adhesion and hardness; xu24 with "
                        "neither)")
    g.add_argument("--theory-gamma", type=float, metavar="THEORY_GAMMA",
                   help="the corrected theory's parameter gamma (default: the published one)")
    pr = ct.add_mutually_exclusive_group()
    pr.add_argument("--pressure", type=float, nargs="+", metavar="P",
                    help="nominal pressures [Pa]; negative (tension, e.g. -0.5e6) needs "
                         "adhesion")
    pr.add_argument("--pressure-range", type=float, nargs=3, metavar=("PMIN", "PMAX", "N"),
                    help="N pressures from PMIN to PMAX [Pa], evenly spaced (e.g. "
                         "-1e6 1e6 5)")
    ct.add_argument("--method", choices=tuple(METHODS),
                    help="solution method (default: auto)")
    ct.add_argument("--rtol", type=float, metavar="R",
                    help="target relative accuracy (default 1e-6)")
    ct.add_argument("--quiet", action="store_true",
                    help="no progress bar and no note that kernels are being compiled (both "
                         "go to stderr, and the bar only to a terminal, after a few seconds)")
    ct.add_argument("--csv", metavar="FILE",
                    help="also write the table to this CSV file (replaced if it exists); "
                         "columns: pressure_Pa, area, force_per_contact_area_Pa, "
                         "compression_per_contact_area_Pa, status[, elastic_area, "
                         "plastic_area][, separation_m, stiffness_Pa_per_m, "
                         "elastic_energy_J_per_m2][, pull_off_stress_Pa]")
    ct.add_argument("--gaps", metavar="GAPS_FILE",
                    help="also write the distribution of interfacial gaps at every pressure "
                         "> 0 to this CSV file (replaced if it exists; scenes without "
                         "adhesion or yield wall, theory persson01; --energy-correction sets "
                         "the mean gaps): one row per (pressure, gap), columns pressure_Pa, "
                         "gap_m, density_per_m, cumulative (probability of a gap <= gap_m, "
                         "the contact included), contact_fraction, mean_gap_m, status")

    sub.add_parser("info", help="versions, threads and kernel compile time",
                   description="Print versions and threads, then compile (or load from the "
                               "cache) the kernels and print the seconds it took.")
    return parser


# --------------------------------------------------------------------------------------------
# the surface models' flags, from their declarations (persson_fast.surfaces.models.SURFACE_MODELS)
# --------------------------------------------------------------------------------------------


def _surface_choices() -> tuple:
    """The models ``--surface`` picks: those without a flag of their own (``--psd FILE``)."""
    return tuple(name for name, m in SURFACE_MODELS.items() if m.selector is None)


def _selector_flags() -> dict:
    """Model name -> (flag that picks it, its parameter) for the models that have one."""
    return {name: (m.parameters[m.selector].flag_for(m.selector), m.parameters[m.selector])
            for name, m in SURFACE_MODELS.items() if m.selector is not None}


def _dest(flag: str) -> str:
    """The attribute of the parsed flags that ``flag`` sets."""
    return flag[2:].replace("-", "_")


def _or(items) -> str:
    items = list(items)
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " or " + items[-1]


def _path_keys_text() -> str:
    """' (file = 'NAME' for topography and psd, relative to the TOML file)' for --config."""
    models = {}
    for name, m in SURFACE_MODELS.items():
        for key, p in m.parameters.items():
            if p.path:
                models.setdefault(key, []).append(name)
    if not models:
        return ""
    parts = [f"{key} = 'NAME' for {' and '.join(names)}" for key, names in models.items()]
    return f" ({'; '.join(parts)}, relative to the TOML file)"


def _help_text(param, default) -> str:
    """A flag's help: the declared text, the unit in brackets, the model's default."""
    text = param.help
    if param.unit is not None:
        text += f" [{param.unit}]"
    if default is not None:
        text += f" (default {default:g})" if isinstance(default, float) else f" (default {default})"
    return text


def _add_surface_flags(parser) -> None:
    """One flag per declared surface parameter, grouped by the first model that declares it;
    the band (q0, q1) under 'all models', the flags that pick a model first in their group."""
    owner = {}                      # flag -> (parameter name, Parameter, model, group title)
    for model in SURFACE_MODELS.values():
        for key, param in model.parameters.items():
            flag = param.flag_for(key)
            if flag not in owner:
                owner[flag] = (key, param, model, _ALL_MODELS if key in BAND else model.title)
    titles = list(dict.fromkeys(title for *_, title in owner.values() if title != _ALL_MODELS))
    if any(title == _ALL_MODELS for *_, title in owner.values()):
        titles.append(_ALL_MODELS)
    for title in titles:
        description = next((m.description for m in SURFACE_MODELS.values()
                            if m.title == title and m.description), None)
        group = parser.add_argument_group(title, description)
        flags = [f for f, (*_, t) in owner.items() if t == title]
        flags.sort(key=lambda f: not owner[f][1].selects)          # stable: pickers first
        for flag in flags:
            key, param, model, _ = owner[flag]
            kwargs = {"nargs": param.nargs} if param.nargs else {}
            group.add_argument(flag, type=param.type, metavar=param.metavar or key.upper(),
                               help=_help_text(param, model.defaults().get(key)), **kwargs)
