"""The ``persson-fast`` command.

Subcommands
-----------
figure2
    The seed paper's PMMA scene: A/A0 against the nominal pressure 0-100 MPa, without
    adhesion and with Delta gamma = 0.06 J/m^2, and the pull-off stress. Writes a CSV file
    and a PNG plot.
contact
    A user's own scene (capillary waves, a self-affine spectrum, a measured height map or line
    scan, or a spectrum file) from flags and/or a TOML file.
info
    Versions, threads and the time to compile (or load from the cache) the kernels.

The surface models of ``contact`` (``--surface NAME``, ``--topography``, ``--psd``), their flags
and their ``[surface]`` keys in a TOML file come from the models' own declarations,
``persson_fast.surfaces.models.SURFACE_MODELS``: a model registered before the parser is built (a
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
adhesion), status (0 ok, else the package's status code: the area's, or where that is 0 and
``--separation`` is given, the separation's, e.g. 22 for a u that underflowed) and, with
``--pull-off``, pull_off_stress_Pa (0 without adhesion): the pull-off stress of the scene as
solved, its area theory (``--theory``) and yield wall (``--hardness``) included; its estimated
error is printed beside it.

``contact --gaps FILE`` writes the distribution of interfacial gaps
(:func:`persson_fast.gap_distribution`, elastic scenes of the original theory) at every
pressure > 0, one row per (pressure, gap): pressure_Pa, gap_m, density_per_m, cumulative
(the probability of a gap <= gap_m, the contact included), contact_fraction, mean_gap_m
(= the separation u(p)) and status; written with the --csv file, atomically.

This module holds the subcommands and :func:`main`; the parser is in
:mod:`persson_fast.cli.parser`, the settings of ``contact`` (TOML file and flags) in
:mod:`persson_fast.cli.config` and the writing of the output files in
:mod:`persson_fast.cli.output`. The names importable from here before are re-exported
(``persson_fast.cli.<name>`` keeps working).
"""
from __future__ import annotations

import gc
import math
import os
import sys
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from ..surfaces.models import SEED_POISSON as SEED_POISSON_DEFAULT
from ..surfaces.models import SEED_WORK_OF_ADHESION, SEED_YOUNG_MODULUS, seed_e_star
from .parser import (FIGURE2_COLUMNS, THEORY_NAMES, CommandError, _Parser, _surface_choices,
                         build_parser)
from .config import _resolve_contact, _make_surface
from .output import _OutputSet, _write_csv

__all__ = ["main", "build_parser",
           # re-exported (persson_fast.cli.<name> as before the split)
           "CommandError", "THEORY_NAMES", "FIGURE2_COLUMNS", "_Parser", "_surface_choices"]

#: largest nominal pressure of the seed's Fig. 2. [Pa]
SEED_P_MAX = 100e6

_COMMANDS = ("figure2", "contact", "info")

#: the extra that brings matplotlib, and how to install it
_PLOT_EXTRA_HINT = ("matplotlib is not installed; install the 'plot' extra: "
                    "python -m pip install \"persson_fast[plot]\" "
                    "(in a checkout: python -m pip install -e \".[plot]\")")


# --------------------------------------------------------------------------------------------
# figure2
# --------------------------------------------------------------------------------------------


def _cmd_figure2(args) -> int:
    import persson_fast as pf
    from persson_fast.adhesion.runner import warm_adhesion

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
    # the closed form is exact here; the grid solver only checks it, on request (--check),
    # so that the main job compiles only the adhesive kernels it needs
    res_cn, t_cn = None, 0.0
    if args.check:
        t0 = time.perf_counter()
        res_cn = pf.solve_contact(surface, pressure, e_star=e_star, method="cn", rtol=args.rtol)
        t_cn = time.perf_counter() - t0

    # the adhesive curve (on the package's threads) and the pull-off stress (one sequential
    # branch follower) run at once; the kernels they share are compiled (on a cold cache)
    # or loaded first, so that the two do not compile the same code side by side
    t0 = time.perf_counter()
    warm_adhesion()
    t_kernels = time.perf_counter() - t0
    t0 = time.perf_counter()
    rtol_pull = max(args.rtol, 1e-4)
    with ThreadPoolExecutor(max_workers=2) as pool:
        pulling = pool.submit(_timed, pf.pull_off, surface, e_star=e_star,
                              work_of_adhesion=SEED_WORK_OF_ADHESION, rtol=rtol_pull,
                              full_output=True, bracket=False)
        # meanwhile the closed form without adhesion (its first call imports scipy.special)
        # and the plot's empty axes (importing matplotlib and laying out its text): Python
        # work that overlaps the compiled adhesive sweep, which releases the GIL; only this
        # thread touches matplotlib until the result is taken
        plain = pool.submit(_timed, pf.solve_contact, surface, pressure, e_star=e_star,
                            method="auto", rtol=args.rtol)
        axes = None if args.no_plot else pool.submit(_figure2_axes, nu)
        try:
            res_adh = pf.solve_contact(surface, pressure, e_star=e_star,
                                       work_of_adhesion=SEED_WORK_OF_ADHESION, method="auto",
                                       rtol=args.rtol)
        finally:
            t_adh = time.perf_counter() - t0
            res, t_auto = plain.result()
            (sigma_c, info), t_pull = pulling.result()
    for label, r in (("auto", res), ("cn", res_cn)):
        if r is not None and not r.success:
            print(f"  warning ({label}): {r.message}")
    area_adh = res_adh.area
    if not res_adh.success:
        print(f"  warning (adhesion): {res_adh.message}")
    t_total = time.perf_counter() - t_start

    if res_cn is None:
        print(f"A/A0 at {SEED_P_MAX / 1e6:g} MPa without adhesion: {res.area[-1]:.6g} "
              f"(method {res.method!r}; --check also solves it with the grid solver 'cn')")
    else:
        diff = float(np.max(np.abs(res.area - res_cn.area)))
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
        fig_ax = None if axes is None else axes.result()
        if args.no_plot:
            plot_skipped = "--no-plot"
        elif fig_ax is None:
            plot_skipped = _PLOT_EXTRA_HINT
        else:
            plot_skipped = None
            _plot_figure2(*fig_ax, outputs.path(png_path), pressure, res.area, area_adh)
        outputs.commit()
    if plot_skipped is not None:
        print(f"plot: skipped ({plot_skipped})")
        if os.path.exists(png_path):
            print(f"note: {png_path} is left from an earlier run; it does not show this one")

    compile_s = t_kernels + sum(r.timings.get("compile", 0.0) for r in (res, res_cn, res_adh)
                                if r is not None)
    timing = (f"time: {t_total:.3g} s ("
              + (f"cn {t_cn:.3g} s, " if res_cn is not None else "")
              + f"kernels {t_kernels:.3g} s, then adhesion {t_adh:.3g} s, pull-off "
              f"{t_pull:.3g} s and auto {t_auto:.3g} s at once)")
    print(timing)
    if compile_s > 0:
        print(f"compile time (included above): {compile_s:.3g} s")
    else:
        print("compile time: 0 s (kernels were already compiled in this process)")
    return 0


def _timed(func, *args, **kwargs):
    """(func(*args, **kwargs), seconds it took)."""
    t0 = time.perf_counter()
    out = func(*args, **kwargs)
    return out, time.perf_counter() - t0


def _pyplot():
    """matplotlib.pyplot on the Agg backend, or None when matplotlib is not installed."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return None
    return plt


def _figure2_axes(nu):
    """(pyplot, figure, axes) of figure2 with its two curves still empty (labels, title,
    grid, legend and layout done, drawn once so that fonts and mathtext are ready), or None
    when matplotlib is not installed."""
    plt = _pyplot()
    if plt is None:
        return None
    fig, ax = plt.subplots(figsize=(5.5, 4.0))
    ax.set_xlabel(r"nominal pressure $p_\mathrm{nom}$ (MPa)")
    ax.set_ylabel(r"relative contact area $A/A_0$")
    assumed = " (assumed)" if nu == SEED_POISSON_DEFAULT else ""
    ax.set_title(rf"PMMA, E = 2.9 GPa, $\nu$ = {nu:g}{assumed}", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.plot([], [], color="C0", label="no adhesion")
    ax.plot([], [], color="C3",
            label=rf"adhesion, $\Delta\gamma$ = {SEED_WORK_OF_ADHESION:g} J/m$^2$")
    ax.set_xlim(0.0, SEED_P_MAX / 1e6)
    ax.set_ylim(0.0, 1.0)                # A/A0: fixed, so that the layout is final here
    ax.legend(loc="upper left", frameon=False)
    fig.tight_layout()
    fig.canvas.draw()
    return plt, fig, ax


def _plot_figure2(plt, fig, ax, path, pressure, area, area_adh) -> None:
    """Put A/A0 against p_nom (without and with adhesion) into the curves of
    :func:`_figure2_axes` and write the PNG file ``path`` (any name: the format is
    explicit)."""
    p_mpa = pressure / 1e6
    try:
        plain, adhesive = ax.get_lines()
        plain.set_data(p_mpa, area)
        adhesive.set_data(p_mpa, area_adh)
        fig.savefig(path, dpi=150, format="png")
    finally:
        plt.close(fig)


# --------------------------------------------------------------------------------------------
# contact
# --------------------------------------------------------------------------------------------


def _cmd_contact(args) -> int:
    import persson_fast as pf

    s = _resolve_contact(args)
    surface = _make_surface(s["model"], s["params"])
    e_star = s["e_star"]
    elastic_original = not (s["adhesion"].get("work_of_adhesion", 0.0) > 0
                            or s["theory"].get("theory", "persson01") != "persson01"
                            or s["hardness"] is not None)
    if s["separation"] and not elastic_original:
        raise CommandError("--separation is available for elastic scenes without adhesion and "
                           "the original theory (persson01) only: the separation is not "
                           "derived with adhesion, a yield wall or the corrected theories here")
    if s.get("gaps") and not elastic_original:
        raise CommandError("--gaps is available for elastic scenes without adhesion and the "
                           "original theory (persson01) only: the gap distribution is not "
                           "derived with adhesion, a yield wall or the corrected theories here")
    t0 = time.perf_counter()
    yield_wall = {} if s["hardness"] is None else {"hardness": s["hardness"]}
    res = _solve_with_progress(
        pf, surface, s["pressure"], args.quiet or not sys.stderr.isatty(),
        bool(s["adhesion"].get("work_of_adhesion", 0.0) > 0 or yield_wall),
        e_star=e_star, method=s["method"], rtol=s["rtol"], **s["adhesion"], **s["theory"],
        **yield_wall)
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
    status = res.status
    sep = None
    if s["separation"]:
        gamma_s = s["adhesion"].get("energy_correction")
        try:
            sep = pf.solve_separation(surface, res.pressure, e_star=e_star,
                                      energy_correction=gamma_s)
        except ValueError as exc:
            raise CommandError(f"--separation: {exc}") from None
        extra.update({"separation_m": sep.separation, "stiffness_Pa_per_m": sep.stiffness,
                      "elastic_energy_J_per_m2": sep.elastic_energy})
        # a row's status: the area's, else the separation's (e.g. 22, an underflowed u)
        status = np.where(res.status != 0, res.status, sep.status)
        print(f"separation: closed form (Persson 2007); decay length u0 = "
              f"{sep.decay_length:.5g} m (p ~ exp(-u/u0) at small p)")
    head = f"{'pressure [Pa]':>14}  {'A/A0':>12}  {'mean p_c [Pa]':>13}"
    titles = {"elastic_area": "A_el/A0", "plastic_area": "A_pl/A0", "separation_m": "u [m]",
              "stiffness_Pa_per_m": "K [Pa/m]", "elastic_energy_J_per_m2": "U_el [J/m^2]"}
    for key in extra:
        head += f"  {titles[key]:>12}"
    print(head + "  status")
    for i, (p, a, mp, st) in enumerate(zip(res.pressure, res.area, res.mean_contact_pressure,
                                           status)):
        mp_s = f"{mp:13.5g}" if np.isfinite(mp) else f"{'-':>13}"
        more = "".join(f"  {col[i]:12.6g}" for col in extra.values())
        print(f"{p:14.6g}  {a:12.6g}  {mp_s}{more}  {'ok' if st == 0 else f'code {int(st)}'}")
    if not res.success:
        print(f"warning: {res.message}")
    if sep is not None and not sep.success:
        print(f"warning (separation): {sep.message}")
    if s["adhesion"].get("work_of_adhesion", 0.0) > 0:
        print(f"adhesion: work of adhesion {s['adhesion']['work_of_adhesion']:g} J/m^2, sticky "
              f"(gamma_eff(1) > 0): {bool(res.sticky[0])}, fixed-point iterations <= "
              f"{int(res.iterations.max())}")
    if s["pull_off"]:
        # the scene as solved: its theory and yield wall (what pull_off does not serve was
        # refused with the settings: cli_config)
        t1 = time.perf_counter()
        if not args.quiet and sys.stderr.isatty():
            print("pull-off: following the contact branch into tension ...", file=sys.stderr,
                  flush=True)
        sigma_c, po = pf.pull_off(surface, e_star=e_star, rtol=max(s["rtol"], 1e-4),
                                  full_output=True, bracket=False, **s["theory"],
                                  **yield_wall, **{"work_of_adhesion": 0.0, **s["adhesion"]})
        how = ("no adhesion" if not s["adhesion"].get("work_of_adhesion", 0.0) > 0
               else f"+- {po['error_estimate']:.2g} Pa"
               + ("" if po["converged"] else ", NOT converged to rtol"))
        print(f"pull-off stress: {sigma_c:.5g} Pa ({how}, {time.perf_counter() - t1:.3g} s)")
    timing = f"time: {elapsed:.3g} s"
    if "compile" in res.timings:
        timing += f" (compile {res.timings['compile']:.3g} s)"
    print(timing)
    gap_columns = None
    if s.get("gaps"):
        gap_columns = _gap_columns(pf, surface, e_star, res.pressure,
                                   s["adhesion"].get("energy_correction"), max(s["rtol"], 1e-3))
    files = [path for path in (s["csv"], s.get("gaps")) if path]
    for path in files:
        folder = os.path.dirname(path)
        if folder:
            os.makedirs(folder, exist_ok=True)
    if files:
        # both files go to temporary names first and are renamed together at the end
        with _OutputSet() as outputs:
            if s["csv"]:
                columns = {"pressure_Pa": res.pressure, "area": res.area,
                           "force_per_contact_area_Pa": res.mean_contact_pressure,
                           "compression_per_contact_area_Pa": res.mean_contact_stress,
                           "status": status, **extra}
                if sigma_c is not None:
                    columns["pull_off_stress_Pa"] = np.full(res.pressure.shape, sigma_c)
                _write_csv(outputs.path(s["csv"]), columns)
            if gap_columns is not None:
                _write_csv(outputs.path(s["gaps"]), gap_columns)
            outputs.commit()
    return 0


#: seconds a contact solve runs before its progress bar appears
PROGRESS_DELAY = 2.0
#: at most this many progress updates along the pressures (each a solve of a block of them)
PROGRESS_UPDATES = 25


def _solve_with_progress(pf, surface, pressure, quiet, slow, **kwargs):
    """``pf.solve_contact`` of the pressures, with a progress bar on stderr (tqdm) that
    appears after ``PROGRESS_DELAY`` seconds, where the scene is ``slow`` (adhesion or a
    yield wall), not ``quiet`` and tqdm is installed: the pressures are then solved in blocks
    (every row's result is computed alone, so bitwise as in one call), and the result is the
    blocks joined (:class:`_Joined`)."""
    p = np.atleast_1d(np.asarray(pressure, dtype=float))
    try:
        from tqdm import tqdm
    except ImportError:
        tqdm = None
    if quiet or not slow or tqdm is None or p.size < 2:
        return pf.solve_contact(surface, p, **kwargs)
    import numba

    block = max(2 * int(numba.get_num_threads()), -(-p.size // PROGRESS_UPDATES))
    parts = []
    with tqdm(total=p.size, unit="pressure", delay=PROGRESS_DELAY, file=sys.stderr,
              leave=False, dynamic_ncols=True) as bar:
        for lo in range(0, p.size, block):
            parts.append(pf.solve_contact(surface, p[lo:lo + block], **kwargs))
            bar.update(parts[-1].pressure.size)
    return parts[0] if len(parts) == 1 else _Joined(parts)


class _Joined:
    """The fields of several ContactResults of consecutive pressure blocks that ``contact``
    reads, joined along the pressures."""

    ROWS = ("pressure", "area", "mean_contact_pressure", "mean_contact_stress", "status",
            "sticky", "iterations")

    def __init__(self, parts):
        from ..results import summarize_status

        first = parts[0]
        for name in self.ROWS:
            setattr(self, name, np.concatenate([getattr(r, name) for r in parts]))
        for name in ("elastic_area", "plastic_area"):
            if getattr(first, name, None) is not None:
                setattr(self, name, np.concatenate([getattr(r, name) for r in parts]))
        self.method, self.theory, self.theory_gamma = first.method, first.theory, first.theory_gamma
        self.success, self.message = summarize_status(self.status)
        offset, notes = 0, []
        for r in parts:
            if not r.success:
                notes.append(f"pressures {offset}-{offset + r.pressure.size - 1}: {r.message}")
            offset += r.pressure.size
        if notes:
            self.message += " (" + "; ".join(notes) + ")"
        self.timings = {}
        for r in parts:
            for key, val in r.timings.items():
                self.timings[key] = self.timings.get(key, 0.0) + val


_log_handler = None


def _log_to_stderr(quiet: bool) -> None:
    """Print the package's INFO messages (that kernels are being compiled) on stderr, unless
    ``quiet``."""
    import logging

    global _log_handler
    from .._jit import logger

    if _log_handler is None:
        _log_handler = logging.StreamHandler(sys.stderr)
        _log_handler.setFormatter(logging.Formatter("note: %(message)s"))
        logger.addHandler(_log_handler)
    _log_handler.setLevel(logging.WARNING if quiet else logging.INFO)
    if logger.level == logging.NOTSET or logger.level > logging.INFO:
        logger.setLevel(logging.INFO)


def _gap_columns(pf, surface, e_star, pressure, energy_correction, rtol) -> dict:
    """The columns of ``contact --gaps``: one row per (pressure > 0, gap) of
    :func:`persson_fast.gap_distribution` on its default grid, at ``rtol`` (the command's,
    at least 1e-3); prints a line per call (and the message where a pressure is flagged)."""
    positive = pressure[pressure > 0]
    if positive.size == 0:
        raise CommandError("--gaps needs a pressure > 0 [Pa]: at p_nom <= 0 the surfaces are "
                           "apart and the gap distribution is not defined")
    g = pf.gap_distribution(surface, positive, e_star=e_star,
                            energy_correction=energy_correction, rtol=rtol)
    n_p, n_u = g.density.shape
    cumulative = g.cumulative(g.gaps)
    print(f"gap distribution: {n_p} pressure(s) x {n_u} gaps from 0 to {g.gaps[-1]:.4g} m "
          f"(Persson's theory, shape {g.shape!r}, rtol {rtol:g}); mean gap = u(p)")
    if not g.success:
        print(f"warning (gaps): {g.message}")
    return {"pressure_Pa": np.repeat(g.pressure, n_u), "gap_m": np.tile(g.gaps, n_p),
            "density_per_m": g.density.ravel(), "cumulative": cumulative.ravel(),
            "contact_fraction": np.repeat(g.contact_fraction, n_u),
            "mean_gap_m": np.repeat(g.mean, n_u), "status": np.repeat(g.status, n_u)}


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
    try:
        parser = build_parser()
        args = parser.parse_args(argv)
        _log_to_stderr(getattr(args, "quiet", False))
        handler = {"figure2": _cmd_figure2, "contact": _cmd_contact,
                   "info": _cmd_info}[args.command]
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


#: allocations between collections of the youngest generation in the console script
#: (:func:`run`; Python's default is 700)
RUN_GC_THRESHOLD = 50_000


def run() -> None:
    """The ``persson-fast`` console script: :func:`main` on the command line, then exit.

    The objects the imports made, and at the end all that are left, are frozen out of the
    garbage collector (``gc.freeze``): they live to the end of the process, and no
    collection walks them again; and the youngest generation is collected every
    ``RUN_GC_THRESHOLD`` allocations instead of 700 (a short process: a few megabytes more
    at most). Collections took about 0.15 s of a warm ``figure2`` (0.03 s so), and those at
    shutdown 0.3 s (about 170 000 objects, most of them numba's). The atexit handlers run
    and files are flushed and closed as usual; the operating system frees the memory.
    (Called in-process, :func:`main` leaves the collector alone.)

    A Ctrl-C outside :func:`main`'s own handling (here, or at exit) is answered as main
    answers it: "interrupted", exit code 130. The console script reaches this function
    through the module ``_persson_fast_cli``, which gives the same answer to a Ctrl-C
    while the package is still being imported (before any code here exists).
    """
    try:
        gc.freeze()
        gc.set_threshold(RUN_GC_THRESHOLD)
        code = main()
        gc.freeze()
    except KeyboardInterrupt:
        import signal

        signal.signal(signal.SIGINT, signal.SIG_IGN)      # exiting: a second Ctrl-C ignored
        print("interrupted", file=sys.stderr)
        code = 130
    raise SystemExit(code)


if __name__ == "__main__":
    run()
