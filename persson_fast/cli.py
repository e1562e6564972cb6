"""The ``persson-fast`` command.

Subcommands
-----------
figure2
    The seed paper's PMMA scene: A/A0 against the nominal pressure 0-100 MPa,
    without adhesion and, once adhesion is available, with Delta gamma = 0.06 J/m^2. Writes a CSV
    file and a PNG plot.
contact
    A user's own scene (capillary waves, a self-affine spectrum, a measured height map or line
    scan, or a spectrum file) from flags and/or a TOML file.
info
    Versions, threads and the time to compile (or load from the cache) the kernels.

The surface models of ``contact`` (``--surface NAME``, ``--topography``, ``--psd``), their flags
and their ``[surface]`` keys in a TOML file come from the models' own declarations,
``persson_fast.surfaces.SURFACE_MODELS``: a model registered before the parser is built (a
``Surface`` subclass with ``MODEL`` and ``PARAMETERS``, in any imported module) is one more
choice with its own flags.

Running ``persson-fast`` with no subcommand runs ``figure2``. A ValueError raised by the package
(an invalid input) is printed as ``error: <message>`` and the exit code is 2.

Negative numbers are values, also in exponent notation: ``--pressure -0.5e6`` and
``--pressure-range -1e6 1e6 3`` ask for tensile nominal stresses (which need adhesion).

Output files
------------
Each output is written to a temporary file in its folder and renamed onto its name only when
complete, and the CSV and PNG of one ``figure2`` run are renamed together (Ctrl-C is held back
during the renames): an error or a Ctrl-C leaves the previous outputs as they were and no
temporary file behind. Replacing an existing file is said (``wrote PATH (replaced the existing
file)``).

``figure2.csv`` has one row per nominal pressure and the columns (units in the names):

pressure_Pa
    Nominal pressure p_nom. [Pa]
area_no_adhesion
    A/A0, relative real contact area without adhesion. [-]
area_adhesion
    A/A0 with adhesion, work of adhesion Delta gamma = 0.06 J/m^2. [-]
force_per_contact_area_adhesion_Pa
    p_nom A0/A with adhesion: the net normal force per unit real contact area (compression
    minus the tension of the detached rims), by force balance; nan where A = 0. [Pa]
compression_per_contact_area_adhesion_Pa
    load/A with adhesion: the compressive load carried in the contact per unit real contact
    area, the mean of the compressive stress distribution; larger than the previous column by
    the rims' tension; nan where A = 0. [Pa]
pull_off_stress_Pa
    Pull-off stress sigma_c of the adhesive scene (contact exists for p_nom > -sigma_c), the
    same on every row. [Pa]

``contact --csv FILE`` writes pressure_Pa, area, force_per_contact_area_Pa,
compression_per_contact_area_Pa (the same quantities for the chosen scene, equal without
adhesion), status (0 ok, else the package's status code) and, with ``--pull-off``,
pull_off_stress_Pa.
"""
from __future__ import annotations

import argparse
import contextlib
import csv
import math
import os
import re
import signal
import stat
import sys
import tempfile
import time

import numpy as np

from .methods import METHODS
from .surfaces import SEED_POISSON as SEED_POISSON_DEFAULT
from .surfaces import BAND, SEED_WORK_OF_ADHESION, SEED_YOUNG_MODULUS, SURFACE_MODELS, seed_e_star

__all__ = ["main", "build_parser"]

#: largest nominal pressure of the seed's Fig. 2. [Pa]
SEED_P_MAX = 100e6

_COMMANDS = ("figure2", "contact", "info")
#: the area theories of ``contact --theory`` (``persson_fast.theories.THEORIES``, spelt out
#: here so that the parser does not import the compiled theory kernels; a test keeps the two
#: equal)
THEORY_NAMES = ("persson01", "yp08", "wm17", "xu24")

#: title of the group of flags every surface model shares (the band, ``surfaces.BAND``)
_ALL_MODELS = "all models"


#: the columns of figure2.csv and what each holds (the module docstring says the same)
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

#: the extra that brings matplotlib, and how to install it
_PLOT_EXTRA_HINT = ("matplotlib is not installed; install the 'plot' extra: "
                    "python -m pip install \"persson_fast[plot]\" "
                    "(in a checkout: python -m pip install -e \".[plot]\")")

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
    from . import __version__

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

    ct = sub.add_parser(
        "contact", help="contact area of your own scene",
        description="Relative contact area of a capillary-wave or self-affine surface. A TOML "
                    "file (--config) may give the same settings; flags override it.",
    )
    ct.add_argument("--config", metavar="FILE.toml",
                    help="TOML file: a [surface] table with model = "
                         + " | ".join(f"'{name}'" for name in SURFACE_MODELS)
                         + " and its parameters" + _path_keys_text()
                         + "; top-level e_star, pressures (or pressure_range = "
                         "[pmin, pmax, n]), method, rtol, csv")
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
    g.add_argument("--pull-off", action="store_true", help="also compute the pull-off stress")
    ct.add_argument("--hardness", type=float, metavar="SIGMA_Y",
                    help="penetration hardness [Pa]: the yield wall; adds the elastic and "
                         "plastic area columns (no adhesion); constant, or at zeta = 1 with "
                         "--hardness-exponent (in a TOML file also a table: hardness = "
                         "{zeta = [...], sigma_y = [...]})")
    ct.add_argument("--hardness-exponent", type=float, metavar="EXPONENT",
                    help="a scale-dependent hardness SIGMA_Y zeta^EXPONENT (needs --hardness)")
    ct.add_argument("--separation", action="store_true",
                    help="also print (and write to --csv) the mean interfacial separation u "
                         "[m], the contact stiffness K = -dp/du [Pa/m] and the stored elastic "
                         "energy U_el [J/m^2] (scenes without adhesion; --energy-correction "
                         "sets S)")
    g = ct.add_argument_group("area theory")
    g.add_argument("--theory", choices=THEORY_NAMES,
                   help="area theory: persson01 (the original, default) or a corrected one "
                        "(yp08, wm17 with or without adhesion; xu24 without adhesion)")
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
    ct.add_argument("--csv", metavar="FILE",
                    help="also write the table to this CSV file (replaced if it exists); "
                         "columns: pressure_Pa, area, force_per_contact_area_Pa, "
                         "compression_per_contact_area_Pa, status[, elastic_area, "
                         "plastic_area][, separation_m, stiffness_Pa_per_m, "
                         "elastic_energy_J_per_m2][, pull_off_stress_Pa]")

    sub.add_parser("info", help="versions, threads and kernel compile time",
                   description="Print versions and threads, then compile (or load from the "
                               "cache) the kernels and print the seconds it took.")
    return parser


# --------------------------------------------------------------------------------------------
# the surface models' flags, from their declarations (persson_fast.surfaces.SURFACE_MODELS)
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


# --------------------------------------------------------------------------------------------
# figure2
# --------------------------------------------------------------------------------------------


def _cmd_figure2(args) -> int:
    import persson_fast as pf

    nu = float(args.poisson)
    if not (math.isfinite(nu) and -1.0 < nu <= 0.5):
        raise CommandError(f"--poisson must lie in (-1, 0.5] [-]; got {nu!r}")
    if args.points < 2:
        raise CommandError(f"--points must be >= 2; got {args.points}")
    e_star = seed_e_star(nu)
    surface = pf.seed_scene()
    pressure = np.linspace(0.0, SEED_P_MAX, int(args.points))

    print("Seed scene (Persson, PMMA on a silanised wafer)")
    print(f"  surface: {surface!r}")
    print(f"  E = {SEED_YOUNG_MODULUS:.3g} Pa; Poisson ratio nu = {nu:g} "
          f"{'assumed (the paper gives none)' if nu == SEED_POISSON_DEFAULT else 'given'}; "
          f"E* = E/(1-nu^2) = {e_star:.4g} Pa")
    slope = surface.slope_rms()
    sqrt_g1 = e_star * slope / (2.0 * math.sqrt(2.0))
    print(f"  h_rms = {surface.h_rms() * 1e9:.4g} nm, rms slope = {slope:.4g}, "
          f"sqrt(G1) = E* slope_rms/(2 sqrt 2) = {sqrt_g1:.4g} Pa")
    print(f"  {pressure.size} pressures from 0 to {SEED_P_MAX / 1e6:g} MPa, rtol = {args.rtol:g}")

    t_start = time.perf_counter()
    res = pf.solve_contact(surface, pressure, e_star=e_star, method="auto", rtol=args.rtol)
    t_auto = time.perf_counter() - t_start
    t0 = time.perf_counter()
    res_cn = pf.solve_contact(surface, pressure, e_star=e_star, method="cn", rtol=args.rtol)
    t_cn = time.perf_counter() - t0
    diff = float(np.max(np.abs(res.area - res_cn.area)))
    for label, r in (("auto", res), ("cn", res_cn)):
        if not r.success:
            print(f"  warning ({label}): {r.message}")

    t0 = time.perf_counter()
    res_adh = pf.solve_contact(surface, pressure, e_star=e_star,
                               work_of_adhesion=SEED_WORK_OF_ADHESION, method="auto",
                               rtol=args.rtol)
    t_adh = time.perf_counter() - t0
    area_adh = res_adh.area
    if not res_adh.success:
        print(f"  warning (adhesion): {res_adh.message}")
    t0 = time.perf_counter()
    rtol_pull = max(args.rtol, 1e-4)
    sigma_c, info = pf.pull_off(surface, e_star=e_star, work_of_adhesion=SEED_WORK_OF_ADHESION,
                                rtol=rtol_pull, full_output=True, bracket=False)
    t_pull = time.perf_counter() - t0
    t_total = time.perf_counter() - t_start

    print(f"A/A0 at {SEED_P_MAX / 1e6:g} MPa without adhesion: {res.area[-1]:.6g} "
          f"(method {res.method!r}; 'cn' gives {res_cn.area[-1]:.6g})")
    print(f"largest |A_auto - A_cn| over the pressures: {diff:.3g}")
    print(f"A/A0 with adhesion (Delta gamma = {SEED_WORK_OF_ADHESION:g} J/m^2): "
          f"{area_adh[0]:.6g} at 0 MPa, {area_adh[-1]:.6g} at {SEED_P_MAX / 1e6:g} MPa "
          f"(fixed point: {int(res_adh.iterations.max())} iterations at most; sticky: "
          f"{bool(res_adh.sticky[0])})")
    print(f"pull-off stress: {sigma_c / 1e6:.6g} MPa +- {info['error_estimate'] / 1e6:.2g} MPa "
          f"(end of the contact branch, rtol {rtol_pull:g}"
          f"{'' if info['converged'] else '; NOT converged to rtol'}), {t_pull:.3g} s")

    os.makedirs(args.out, exist_ok=True)
    csv_path = os.path.join(args.out, "figure2.csv")
    png_path = os.path.join(args.out, "figure2.png")
    columns = {"pressure_Pa": pressure, "area_no_adhesion": res.area,
               "area_adhesion": area_adh,
               "force_per_contact_area_adhesion_Pa": res_adh.mean_contact_pressure,
               "compression_per_contact_area_adhesion_Pa": res_adh.mean_contact_stress,
               "pull_off_stress_Pa": np.full(pressure.shape, sigma_c)}
    assert list(columns) == list(FIGURE2_COLUMNS)
    # both files go to temporary names first and are renamed together at the end
    with _OutputSet() as outputs:
        _write_csv(outputs.path(csv_path), columns)
        plt = None if args.no_plot else _pyplot()
        if args.no_plot:
            plot_skipped = "--no-plot"
        elif plt is None:
            plot_skipped = _PLOT_EXTRA_HINT
        else:
            plot_skipped = None
            _plot_figure2(plt, outputs.path(png_path), pressure, res.area, area_adh, nu)
        outputs.commit()
    if plot_skipped is not None:
        print(f"plot: skipped ({plot_skipped})")
        if os.path.exists(png_path):
            print(f"note: {png_path} is left from an earlier run; it does not show this one")

    compile_s = sum(r.timings.get("compile", 0.0) for r in (res, res_cn, res_adh))
    timing = (f"time: {t_total + t_pull:.3g} s (auto {t_auto:.3g} s, cn {t_cn:.3g} s, "
              f"adhesion {t_adh:.3g} s, pull-off {t_pull:.3g} s)")
    print(timing)
    if compile_s > 0:
        print(f"compile time (included above): {compile_s:.3g} s")
    else:
        print("compile time: 0 s (kernels were already compiled in this process)")
    return 0


def _pyplot():
    """matplotlib.pyplot on the Agg backend, or None when matplotlib is not installed."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return None
    return plt


def _plot_figure2(plt, path, pressure, area, area_adh, nu) -> None:
    """Plot A/A0 against p_nom into the PNG file ``path`` (any name: the format is explicit)."""
    fig, ax = plt.subplots(figsize=(5.5, 4.0))
    p_mpa = pressure / 1e6
    ax.plot(p_mpa, area, color="C0", label="no adhesion")
    if area_adh is not None:
        ax.plot(p_mpa, area_adh, color="C3",
                label=rf"adhesion, $\Delta\gamma$ = {SEED_WORK_OF_ADHESION:g} J/m$^2$")
    ax.set_xlabel(r"nominal pressure $p_\mathrm{nom}$ (MPa)")
    ax.set_ylabel(r"relative contact area $A/A_0$")
    ax.set_xlim(0.0, p_mpa[-1])
    ax.set_ylim(bottom=0.0)
    assumed = " (assumed)" if nu == SEED_POISSON_DEFAULT else ""
    ax.set_title(rf"PMMA, E = 2.9 GPa, $\nu$ = {nu:g}{assumed}", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper left", frameon=False)
    fig.tight_layout()
    try:
        fig.savefig(path, dpi=150, format="png")
    finally:
        plt.close(fig)


def _write_csv(path, columns: dict) -> None:
    """Write equal-length columns; floats round-trip (repr), integer columns stay integers."""
    names = list(columns)
    arrays = [np.asarray(columns[n]) for n in names]
    def as_int(v):
        return str(int(v))

    def as_float(v):
        return repr(float(v))

    fmt = [as_int if np.issubdtype(a.dtype, np.integer) else as_float for a in arrays]
    with open(path, "w", newline="") as fh:
        writer = csv.writer(fh)
        writer.writerow(names)
        for i in range(len(arrays[0]) if arrays else 0):
            writer.writerow([f(a[i]) for f, a in zip(fmt, arrays)])


@contextlib.contextmanager
def _sigint_held():
    """Hold back SIGINT (Ctrl-C) inside the block; one that came meanwhile is raised after it.

    Outside the main thread (where Python cannot install signal handlers), or when SIGINT has a
    handler that Python did not install (and so could not put back), the block runs as it is.
    """
    caught = []
    previous = signal.getsignal(signal.SIGINT)
    held = False
    if previous is not None:
        try:
            signal.signal(signal.SIGINT, lambda signum, frame: caught.append(signum))
            held = True
        except ValueError:  # not the main thread of the main interpreter
            pass
    try:
        yield
    finally:
        if held:
            signal.signal(signal.SIGINT, previous)
            if caught and previous is not signal.SIG_IGN:
                if callable(previous):
                    previous(signal.SIGINT, None)  # the default one raises KeyboardInterrupt
                else:
                    raise KeyboardInterrupt


class _OutputSet:
    """The output files of one run, written under temporary names and renamed together.

    ``path(final)`` creates an empty temporary file in the folder of ``final`` and returns its
    name, to be written instead of ``final``; ``commit()`` renames each onto its final name
    (``os.replace``: atomic within a folder) with Ctrl-C held back, so an interrupt leaves either
    all the old files or all the new ones, and prints ``wrote PATH``, adding when an existing
    file was replaced. Leaving the ``with`` block otherwise (an error, a KeyboardInterrupt)
    removes the temporary files and leaves the existing outputs untouched.
    """

    def __init__(self):
        self._pending = []  # (temporary name, final name)

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        self.discard()
        return False

    def path(self, final: str) -> str:
        folder = os.path.dirname(os.path.abspath(final))
        fd, tmp = tempfile.mkstemp(prefix=f".{os.path.basename(final)}.", suffix=".tmp",
                                   dir=folder)
        self._pending.append((tmp, final))
        os.close(fd)
        return tmp

    def discard(self) -> None:
        """Remove the temporary files not yet renamed."""
        while self._pending:
            tmp, _ = self._pending.pop()
            with contextlib.suppress(OSError):
                os.remove(tmp)

    def commit(self) -> None:
        """Rename every temporary file onto its final name; say which existed before."""
        for _, final in self._pending:
            if os.path.isdir(final):
                raise IsADirectoryError(f"cannot write {final!r}: it is a folder")
        for tmp, final in self._pending:
            _set_mode(tmp, final)
        with _sigint_held():
            while self._pending:
                tmp, final = self._pending[0]
                existed = os.path.exists(final)
                os.replace(tmp, final)
                self._pending.pop(0)
                print(f"wrote {final}" + (" (replaced the existing file)" if existed else ""))


def _set_mode(tmp: str, final: str) -> None:
    """Give ``tmp`` the permissions ``final`` has (or a new file would get: 0o666 - umask),
    instead of mkstemp's 0o600."""
    try:
        mode = stat.S_IMODE(os.stat(final).st_mode)
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        mode = 0o666 & ~umask
    with contextlib.suppress(OSError):
        os.chmod(tmp, mode)


# --------------------------------------------------------------------------------------------
# contact
# --------------------------------------------------------------------------------------------


def _load_toml(path) -> dict:
    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        try:
            import tomli as tomllib
        except ModuleNotFoundError:
            raise CommandError(
                "--config needs Python 3.11+ (tomllib) or the 'tomli' package") from None
    try:
        with open(path, "rb") as fh:
            return tomllib.load(fh)
    except OSError as exc:
        raise CommandError(f"cannot read --config {path!r}: {exc.strerror}") from None
    except tomllib.TOMLDecodeError as exc:
        raise CommandError(f"--config {path!r} is not valid TOML: {exc}") from None


def _number(value, key):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise CommandError(f"{key} must be a number; got {value!r}")
    return float(value)


def _resolve_contact(args) -> dict:
    """Merge the TOML file (if any) and the flags (which win) into one settings dict."""
    cfg = _load_toml(args.config) if args.config else {}
    known_top = {"surface", "e_star", "pressures", "pressure_range", "method", "rtol", "csv",
                 "work_of_adhesion", "energy_correction", "detachment_prefactor", "pull_off",
                 "theory", "theory_gamma", "separation", "hardness", "hardness_exponent"}
    unknown = sorted(set(cfg) - known_top)
    if unknown:
        raise CommandError(f"unknown key(s) in --config: {', '.join(unknown)}; "
                           f"expected {', '.join(sorted(known_top))}")
    surf_cfg = cfg.get("surface", {})
    if not isinstance(surf_cfg, dict):
        raise CommandError("'surface' in --config must be a table ([surface])")
    surf_cfg = dict(surf_cfg)

    selectors = _selector_flags()
    from_flags = [name for name, (flag, _) in selectors.items()
                  if getattr(args, _dest(flag), None)]
    if len(from_flags) > 1 or (from_flags and args.surface):
        raise CommandError("give one of " + ", ".join(
            ["--surface", *(flag for flag, _ in selectors.values())]))
    model = (from_flags[0] if from_flags else None) or args.surface or surf_cfg.pop("model", None)
    surf_cfg.pop("model", None)
    if model is None:
        picks = [f"{flag} {'FILE' if p.path else p.metavar or 'VALUE'}"
                 for flag, p in selectors.values()]
        raise CommandError("no surface model: give " + _or(
            [f"--surface {{{','.join(_surface_choices())}}}", *picks])
            + ", or model = ... in the [surface] table of --config")
    if model not in SURFACE_MODELS:
        raise CommandError(
            f"surface model must be one of {', '.join(SURFACE_MODELS)}; got {model!r}")
    declared = SURFACE_MODELS[model].parameters
    keys = tuple(declared)
    unknown = sorted(set(surf_cfg) - set(keys))
    if unknown:
        raise CommandError(f"unknown [surface] key(s) for model {model!r}: {', '.join(unknown)}; "
                           f"expected {', '.join(keys)}")
    params = {k: _config_value(k, v, args.config, declared[k]) for k, v in surf_cfg.items()}
    own_flags = {p.flag_for(k) for k, p in declared.items()}
    for key, param in declared.items():
        value = getattr(args, _dest(param.flag_for(key)), None)
        if value is not None:
            params[key] = value
    # flags of the other models are an error, not silently ignored (a flag that picks a
    # model is the conflict above)
    stray = sorted({(k, p.flag_for(k)) for m in SURFACE_MODELS.values()
                    for k, p in m.parameters.items()
                    if not p.selects and p.flag_for(k) not in own_flags
                    and getattr(args, _dest(p.flag_for(k)), None) is not None})
    if stray:
        raise CommandError(f"{', '.join(flag for _, flag in stray)} do(es) not apply to surface "
                           f"model {model!r}")
    missing = [k for k in SURFACE_MODELS[model].required if k not in params]
    if missing:
        raise CommandError(f"surface model {model!r} needs " + ", ".join(
            f"{declared[k].flag_for(k)} (or {k} in [surface])" for k in missing))

    e_star = args.e_star if args.e_star is not None else cfg.get("e_star")
    if e_star is None:
        raise CommandError("no effective modulus: give --e-star E [Pa] (or e_star in --config)")
    e_star = _number(e_star, "e_star")

    if args.pressure is not None:
        pressure = np.asarray(args.pressure, dtype=float)
    elif args.pressure_range is not None:
        pressure = _pressure_range(*args.pressure_range)
    elif "pressures" in cfg and "pressure_range" in cfg:
        raise CommandError("--config gives both 'pressures' and 'pressure_range'; keep one")
    elif "pressures" in cfg:
        raw = cfg["pressures"]
        raw = raw if isinstance(raw, list) else [raw]
        pressure = np.asarray([_number(v, "pressures") for v in raw], dtype=float)
    elif "pressure_range" in cfg:
        raw = cfg["pressure_range"]
        if not isinstance(raw, list) or len(raw) != 3:
            raise CommandError(f"pressure_range must be [pmin, pmax, n]; got {raw!r}")
        pressure = _pressure_range(*(_number(v, "pressure_range") for v in raw))
    else:
        raise CommandError("no pressures: give --pressure P [P ...] or "
                           "--pressure-range PMIN PMAX N "
                           "(or pressures / pressure_range in --config)")

    method = args.method or cfg.get("method", "auto")
    rtol = args.rtol if args.rtol is not None else _number(cfg.get("rtol", 1e-6), "rtol")
    csv_path = args.csv or cfg.get("csv")
    adhesion = {}
    for key in ("work_of_adhesion", "energy_correction", "detachment_prefactor"):
        value = getattr(args, key)
        if value is None and key in cfg:
            value = _number(cfg[key], key)
        if value is not None:
            adhesion[key] = value
    want_pull_off = bool(args.pull_off or cfg.get("pull_off", False))
    want_separation = bool(args.separation or cfg.get("separation", False))
    hardness = args.hardness
    if hardness is None and "hardness" in cfg:
        if isinstance(cfg["hardness"], dict):
            from .plasticity import check_hardness
            try:
                hardness = check_hardness(cfg["hardness"], "hardness", scale_dependent=True)
            except ValueError as exc:
                raise CommandError(f"--config: {exc}") from None
        else:
            hardness = _number(cfg["hardness"], "hardness")
    exponent = args.hardness_exponent
    if exponent is None and "hardness_exponent" in cfg:
        exponent = _number(cfg["hardness_exponent"], "hardness_exponent")
    if exponent is not None:
        if not isinstance(hardness, float):
            raise CommandError(f"--hardness-exponent needs a constant --hardness (sigma_Y at "
                               f"zeta = 1) [Pa]; got hardness = {hardness!r}")
        from .plasticity import hardness_power_law
        try:
            hardness = hardness_power_law(hardness, exponent)
        except ValueError as exc:
            raise CommandError(str(exc)) from None
    theory = {}
    name = args.theory or cfg.get("theory")
    if name is not None:
        if name not in THEORY_NAMES:
            raise CommandError(f"theory must be one of {', '.join(THEORY_NAMES)}; got {name!r}")
        theory["theory"] = name
    gamma = args.theory_gamma
    if gamma is None and "theory_gamma" in cfg:
        gamma = _number(cfg["theory_gamma"], "theory_gamma")
    if gamma is not None:
        theory["theory_gamma"] = gamma
    return {"model": model, "params": params, "e_star": e_star, "pressure": pressure,
            "method": method, "rtol": rtol, "csv": csv_path, "adhesion": adhesion,
            "pull_off": want_pull_off, "theory": theory, "separation": want_separation,
            "hardness": hardness}


def _pressure_range(pmin, pmax, n) -> np.ndarray:
    if n != int(n) or n < 1:
        raise CommandError(f"the number of pressures N must be a whole number >= 1; got {n!r}")
    return np.linspace(float(pmin), float(pmax), int(n))


def _config_value(key, value, config_path, param):
    """A [surface] value as its declaration says: text (a relative file name is taken from the
    folder of the config file), a list of numbers, or a number."""
    if param.type is str:
        if not isinstance(value, str):
            raise CommandError(f"surface.{key} must be a string; got {value!r}")
        if param.path and config_path and not os.path.isabs(value):
            value = os.path.join(os.path.dirname(os.path.abspath(config_path)), value)
        return value
    if param.nargs:
        raw = value if isinstance(value, list) else [value]
        return [_number(v, f"surface.{key}") for v in raw]
    number = _number(value, f"surface.{key}")
    return int(number) if param.type is int else number


def _make_surface(model: str, params: dict):
    """The surface of a declared model (``SURFACE_MODELS[model].build(**params)``)."""
    return SURFACE_MODELS[model].build(**params)


def _cmd_contact(args) -> int:
    import persson_fast as pf

    s = _resolve_contact(args)
    surface = _make_surface(s["model"], s["params"])
    e_star = s["e_star"]
    if s["separation"] and (s["adhesion"].get("work_of_adhesion", 0.0) > 0
                            or s["theory"].get("theory", "persson01") != "persson01"
                            or s["hardness"] is not None):
        raise CommandError("--separation is available for elastic scenes without adhesion and "
                           "the original theory (persson01) only: the separation is not "
                           "derived with adhesion, a yield wall or the corrected theories here")
    t0 = time.perf_counter()
    yield_wall = {} if s["hardness"] is None else {"hardness": s["hardness"]}
    res = pf.solve_contact(surface, s["pressure"], e_star=e_star, method=s["method"],
                           rtol=s["rtol"], **s["adhesion"], **s["theory"], **yield_wall)
    elapsed = time.perf_counter() - t0
    sigma_c = None
    slope = surface.slope_rms()
    print(f"surface: {surface!r}")
    info = getattr(surface, "info", None)
    if info and "q_lowest" in info:
        print(f"measured {info['kind']}: band [{surface.q0:.4g}, {surface.q1:.4g}] 1/m "
              f"(2 pi/L = {info['q_lowest']:.4g}, reliable up to {info['q_reliable']:.4g}, "
              f"Nyquist {info['q_nyquist']:.4g}); window {info['window']}"
              + (f"; H = {info['hurst']:.3g}" if "hurst" in info else ""))
    print(f"h_rms = {surface.h_rms():.4g} m, rms slope = {slope:.4g}, E* = {e_star:.4g} Pa, "
          f"sqrt(G1) = {e_star * slope / (2.0 * math.sqrt(2.0)):.4g} Pa")
    print(f"method: {res.method} (asked {s['method']!r}), rtol = {s['rtol']:g}")
    if res.theory != "persson01":
        print(f"area theory: {res.theory}, gamma = {res.theory_gamma:g}")
    extra = {}
    if yield_wall:
        h = s["hardness"]
        what = f"constant hardness {h:.5g} Pa" if isinstance(h, float) else f"hardness {h!r}"
        print(f"yield wall: {what}; A/A0 = elastic + plastic")
        extra = {"elastic_area": res.elastic_area, "plastic_area": res.plastic_area}
    if s["separation"]:
        try:
            extra.update({"separation_m": res.separation, "stiffness_Pa_per_m": res.stiffness,
                          "elastic_energy_J_per_m2": res.elastic_energy})
        except ValueError as exc:
            raise CommandError(f"--separation: {exc}") from None
        print(f"separation: closed form (Persson 2007); decay length u0 = "
              f"{pf.decay_length(surface, e_star=e_star, energy_correction=s['adhesion'].get('energy_correction')):.5g} m "
              f"(p ~ exp(-u/u0) at small p)")
    head = f"{'pressure [Pa]':>14}  {'A/A0':>12}  {'mean p_c [Pa]':>13}"
    titles = {"elastic_area": "A_el/A0", "plastic_area": "A_pl/A0", "separation_m": "u [m]",
              "stiffness_Pa_per_m": "K [Pa/m]", "elastic_energy_J_per_m2": "U_el [J/m^2]"}
    for key in extra:
        head += f"  {titles[key]:>12}"
    print(head + "  status")
    for i, (p, a, mp, st) in enumerate(zip(res.pressure, res.area, res.mean_contact_pressure,
                                           res.status)):
        mp_s = f"{mp:13.5g}" if np.isfinite(mp) else f"{'-':>13}"
        more = "".join(f"  {col[i]:12.6g}" for col in extra.values())
        print(f"{p:14.6g}  {a:12.6g}  {mp_s}{more}  {'ok' if st == 0 else f'code {int(st)}'}")
    if not res.success:
        print(f"warning: {res.message}")
    if s["adhesion"].get("work_of_adhesion", 0.0) > 0:
        print(f"adhesion: work of adhesion {s['adhesion']['work_of_adhesion']:g} J/m^2, sticky "
              f"(gamma_eff(1) > 0): {bool(res.sticky[0])}, fixed-point iterations <= "
              f"{int(res.iterations.max())}")
        if s["pull_off"]:
            t1 = time.perf_counter()
            sigma_c = pf.pull_off(surface, e_star=e_star, rtol=max(s["rtol"], 1e-4),
                                  **s["adhesion"])
            print(f"pull-off stress: {sigma_c:.5g} Pa ({time.perf_counter() - t1:.3g} s)")
    timing = f"time: {elapsed:.3g} s"
    if "compile" in res.timings:
        timing += f" (compile {res.timings['compile']:.3g} s)"
    print(timing)
    if s["csv"]:
        folder = os.path.dirname(s["csv"])
        if folder:
            os.makedirs(folder, exist_ok=True)
        columns = {"pressure_Pa": res.pressure, "area": res.area,
                   "force_per_contact_area_Pa": res.mean_contact_pressure,
                   "compression_per_contact_area_Pa": res.mean_contact_stress,
                   "status": res.status, **extra}
        if sigma_c is not None:
            columns["pull_off_stress_Pa"] = np.full(res.pressure.shape, sigma_c)
        with _OutputSet() as outputs:
            _write_csv(outputs.path(s["csv"]), columns)
            outputs.commit()
    return 0


# --------------------------------------------------------------------------------------------
# info
# --------------------------------------------------------------------------------------------


def _cmd_info(args) -> int:
    import platform

    import numba

    import persson_fast as pf

    print(f"persson_fast {pf.__version__}")
    print(f"python {platform.python_version()}, numpy {np.__version__}, numba {numba.__version__}")
    print(f"platform: {platform.platform()}, {os.cpu_count()} CPUs")
    print(f"numba threads: {numba.config.NUMBA_NUM_THREADS}")
    cache = os.environ.get("NUMBA_CACHE_DIR")
    print(f"numba cache dir: {cache if cache else 'next to the sources (__pycache__)'}")
    t0 = time.perf_counter()
    timings = pf.warmup()
    total = time.perf_counter() - t0
    parts = ", ".join(f"{k} {v:.3g} s" for k, v in timings.items())
    print(f"warmup (compile or load from the cache): {total:.3g} s ({parts})")
    return 0


# --------------------------------------------------------------------------------------------
# entry point
# --------------------------------------------------------------------------------------------


def main(argv=None) -> int:
    """Run ``persson-fast``; return the exit code (0 ok, 1 file error, 2 invalid input)."""
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or (argv[0].startswith("-") and argv[0] not in ("-h", "--help", "--version")):
        argv = ["figure2", *argv]
    parser = build_parser()
    args = parser.parse_args(argv)
    handler = {"figure2": _cmd_figure2, "contact": _cmd_contact, "info": _cmd_info}[args.command]
    try:
        return int(handler(args) or 0)
    except ValueError as exc:  # the package's (and this module's) invalid-input errors
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:  # an output file or folder that cannot be written
        print(f"error: {exc}", file=sys.stderr)
        return 1
    except RuntimeError as exc:  # a numerical failure the package reports (e.g. pull_off)
        print(f"error: {exc}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    raise SystemExit(main())
