"""Parameter scans: many scenes, each swept over the same nominal pressures.

:func:`scan` crosses a grid of scene parameters -- any keyword argument of a surface model
(``hurst``, ``h_rms``, ``slope_rms``, ``q0``, ``q1``, ``temperature``, ...) and the solve
parameters ``e_star``, ``work_of_adhesion``, ``energy_correction``,
``detachment_prefactor`` and (given a sequence) the area ``theory`` -- with a vector of
nominal pressures. Every scene is one call of :func:`persson_fast.solve_contact` over all
pressures (and, on request, one call of :func:`persson_fast.pull_off`), so a scan returns
exactly the numbers those calls return.

Why xarray
----------
A scan is a labelled N-dimensional grid: one axis per scanned parameter plus ``pressure``
(and ``zeta`` for profiles), with per-scene variables (``success``, ``message``,
``pull_off``) living on a sub-grid of the same axes. :class:`xarray.Dataset` holds exactly
that: ``ds.area.sel(hurst=0.8, work_of_adhesion=0.06)`` selects by value,
``ds.area.plot(x="pressure", hue="hurst")`` plots with labelled axes, the units travel in
``attrs``, ``ds.to_netcdf`` stores the scan, and a tidy table (one row per scene and
pressure) is one ``ds.to_dataframe()`` away. A flat DataFrame as the primary result would
lose the grid structure (and repeat every per-scene value on every pressure row).

Failures
--------
A scan of 10^4 scenes should not be lost to one scene, nor hide it: a scene whose
``solve_contact`` or ``pull_off`` raises is recorded (NaN, ``success`` False, the error in
``message``, ``status`` :data:`SCENE_ERROR` for a raised solve) and the other scenes run on;
flagged points (``status`` != 0) and unconverged pull-offs keep their numbers with ``success``
False. A failed scene's ``message`` starts with what failed. When any scene failed, the scan
issues one :class:`ScanWarning` naming how many and the worst few (parameters and messages).

Execution
---------
*Local* (``client=None``). The compiled kernels release the GIL, so scenes run on a pool of
threads, each scene with the serial (disk-cached) kernels; scenes whose answer is a closed
form (no adhesion, ``method`` "auto" or "analytic") cost microseconds of Python and run in
the calling thread. ``python -m benchmarks.scan_scale`` compares this with running the
scenes one after another, each pressure sweep spread over threads (``prange``). On a
2-core machine shared with other jobs (load average 3-4), threads over scenes were as fast
or faster in every case and run (minimum of 5 interleaved runs: 1.39 s against 1.59 s for
20 scenes x 100 pressures with "cn", 1.24 s against 1.36 s for 10 adhesive scenes x 20
pressures, 0.56 s against 0.69 s for 3 adhesive scenes x 60 pressures), and they never pay
the 12-28 s per process that compiling the parallel kernels costs (those are not cached on
disk). A single scene, or ``workers=1``, runs in the calling thread with
:func:`~persson_fast.solve_contact`'s own choice of pressure parallelism; with only a few
expensive scenes and the parallel kernels already compiled (``pf.warmup()``), that can
balance better.

*Distributed* (``client`` a :class:`dask.distributed.Client`, a scheduler address, or
``"local"``). Contiguous chunks of the scene grid become tasks of the module-level function
:func:`solve_chunk`; the results are gathered and placed by scene index, so the dataset
equals the local one bitwise. Workers load the serial kernels from numba's on-disk cache
(``client.run(persson_fast.warmup, False)`` once per scan). A ``KeyboardInterrupt`` (or any
error) while waiting cancels every pending task of the scan; a cluster that :func:`scan`
created itself (``client="local"``) is closed in every case, and a client passed in stays
open.

This module holds :func:`scan` and :class:`ScanWarning`; the rest lives in
:mod:`persson_fast.scan.grid` (the checks of a scan's inputs and the grid of scenes, with
the parameters' units), :mod:`persson_fast.scan.run` (one scene, the local and distributed
execution, the progress bar) and :mod:`persson_fast.scan.results` (the dataset and the
failure warning's text). The names importable from here before are re-exported
(``__all__``), so ``persson_fast.scan.<name>`` keeps working.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # names of the type hints only
    from collections.abc import Callable, Sequence
    
    import xarray
    from numpy.typing import ArrayLike
    
    from ..surfaces.base import Surface

import time
import warnings

import numpy as np

from .._validation import optional_import
from ..scene import DETACHMENT_PREFACTOR, Scene, _check_rtol, unpack_scene
from ..scene import check_composition
from ..methods import METHODS
from .grid import (PARAMETER_UNITS, SOLVE_PARAMETERS, ZETA1_RTOL, _check_positive_int,
                        _check_pressure, _check_progress, _check_theories, _check_zeta, _Grid,
                        _parameter_units, _profile_grid)
from .run import (PROGRESS_MIN_SCENES, PROGRESS_MIN_SECONDS, SCENE_ERROR, _estimate_seconds,
                       _open_client, _Progress, _run_distributed, _run_local, _worker_threads,
                       solve_chunk)
from .results import WARN_MESSAGE_CHARS, WARN_SCENES, _assemble, _failure_summary

__all__ = ["scan", "solve_chunk", "ScanWarning", "SCENE_ERROR", "SOLVE_PARAMETERS",
           "PARAMETER_UNITS",
           # re-exported from the modules above (persson_fast.scan.<name> as before the split)
           "PROGRESS_MIN_SCENES", "PROGRESS_MIN_SECONDS", "WARN_SCENES", "WARN_MESSAGE_CHARS",
           "ZETA1_RTOL", "_parameter_units"]


class ScanWarning(UserWarning):
    """Some scenes of a :func:`scan` failed: issued once per scan, with the number of failed
    scenes and flagged points and the worst scenes' parameters and messages.

    ``warnings.simplefilter("error", ScanWarning)`` turns it into an error (raised after every
    scene has run); ``ds.success``, ``ds.message`` and ``ds.status`` say which scene and point.

    Attributes
    ----------
    args : tuple
        ``(message,)``: the text :func:`scan` wrote, as for every warning.

    See Also
    --------
    persson_fast.scan : Issues it.

    Examples
    --------
    >>> import warnings
    >>> import persson_fast as pf
    >>> issubclass(pf.ScanWarning, UserWarning)
    True
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("error", pf.ScanWarning)
    ...     try:
    ...         warnings.warn("1 of 4 scenes failed", pf.ScanWarning)
    ...     except pf.ScanWarning as w:
    ...         print("raised:", w)
    raised: 1 of 4 scenes failed
    """


# ----------------------------------------------------------------------------------------------
# the public function
# ----------------------------------------------------------------------------------------------
def _check_gap_option(gaps):
    """False, True, or the gaps [m] of ``scan(gaps=...)`` (validated)."""
    if isinstance(gaps, (bool, np.bool_)):
        return bool(gaps)
    from ..separation.gaps import _check_gaps

    try:
        return _check_gaps(gaps)
    except ValueError as exc:
        raise ValueError(f"gaps must be True, False or an array of gaps [m]: {exc}") from None


def scan(surface: type | Callable[..., Surface] | Surface | Scene, params: dict,
         pressure: ArrayLike, *, e_star: float | None = None, work_of_adhesion: float = 0.0,
         energy_correction: float | None = None,
         detachment_prefactor: float = DETACHMENT_PREFACTOR, method: str = "auto",
         rtol: float = 1e-6, zeta: ArrayLike | None = None, profiles: bool = False,
         pull_off: bool = False, pull_off_rtol: float | None = None,
         client: object | str | None = None, chunks: int | None = None,
         workers: int | None = None, progress: bool | Callable[[int, int], object] | None = None,
         theory: str | Sequence[str] = "persson01", theory_gamma: float | None = None,
         separation: bool = False,
         hardness: float | Callable[[np.ndarray], np.ndarray] | ArrayLike | None = None,
         gaps: bool | ArrayLike = False, gaps_rtol: float | None = None,
         ) -> xarray.Dataset:
    """Contact area over a grid of scenes crossed with nominal pressures.

    Parameters
    ----------
    surface : type, callable, Surface or Scene
        A surface model class or factory called as ``surface(**surface_parameters)`` for
        each scene (e.g. ``pf.SelfAffine``, ``pf.CapillaryWaves``, a ``functools.partial``
        or any function returning a :class:`~persson_fast.Surface`); or one Surface
        instance when only solve parameters are scanned; or one
        :class:`~persson_fast.Scene`, whose parameters are then the fixed ones (a solve
        parameter in ``params`` still makes an axis).
    params : dict of str to scalar or sequence
        The scene parameters. A sequence makes an axis of the result (named by its key, in
        the order of the dict; its values must be distinct); a scalar is held fixed (a scalar
        coordinate of the result). Keys are the factory's keyword arguments (``hurst``,
        ``h_rms``, ``slope_rms``, ``q0``, ``q1``, ``temperature``, ...) or the solve
        parameters ``e_star``, ``work_of_adhesion``, ``energy_correction`` (None or NaN: no
        correction) and ``detachment_prefactor``.
    pressure : float or array_like, shape (n_p,)
        Nominal pressures, the last axis of the result. Negative values (tension) are
        allowed: with adhesion they are solved, without adhesion the surfaces separate and
        the area is 0 (no solve). [Pa]
    e_star : float, optional
        Effective modulus E* > 0, unless scanned in ``params``. [Pa]
    work_of_adhesion : float
        Delta gamma >= 0, unless scanned (default 0, no adhesion). [J/m^2]
    energy_correction : float or None
        gamma_S of the elastic-energy correction, in [0, 1], unless scanned. [-]
    detachment_prefactor : float
        beta of seed Eq. 8 (default 1/sqrt 2), unless scanned. [-]
    method : str
        As in :func:`~persson_fast.solve_contact` (a key of ``pf.METHODS``).
    rtol : float
        Target relative accuracy of every solve, in [1e-12, 0.1]. [-]
    zeta : array_like or None
        Magnifications passed to every solve (as in :func:`~persson_fast.solve_contact`; with
        adhesion the fixed point runs on this grid). None: each scene's default. [-]
    profiles : bool
        Also return A(zeta)/A0, sigma_a(zeta) and gamma_eff(zeta) on a ``zeta`` axis. All
        scenes need one grid: with ``zeta=None`` the default grids must agree (true unless
        the band or roll-off is scanned); scenes without adhesion are then evaluated on the
        adhesive scenes' grid, which is exact for their closed form.
    pull_off : bool
        Also compute the pull-off stress of every scene with :func:`~persson_fast.pull_off`
        (of the scene's theory and yield wall; 0 without adhesion or where the surfaces are not sticky; NaN, with ``success``
        False, where it raises; kept, with ``success`` False, where its error estimate
        exceeds ``pull_off_rtol``). [Pa]
    pull_off_rtol : float or None
        Relative accuracy of the pull-off stress (default ``rtol``); only with
        ``pull_off=True`` (otherwise a ValueError). [-]
    client : None, "local", str or dask.distributed.Client
        None: run here (threads). A Client: chunks of scenes become tasks on its cluster (the
        client stays open). ``"local"``: start a ``LocalCluster`` of single-threaded worker
        processes for this scan and close it afterwards (in a script, call scan under
        ``if __name__ == "__main__":``, as worker processes are spawned). Any other string:
        the address of a scheduler to connect to (the connection is closed afterwards).
    chunks : int or None
        Scenes per distributed task (default: about four tasks per worker thread).
    workers : int or None
        Threads of the local path (default ``numba.get_num_threads()``); 1 runs the scenes one
        after another, each spreading its pressures over threads as ``solve_contact`` does.
    progress : None, bool or callable
        Show a tqdm progress bar: None shows it for scans of more than 50 scenes or longer
        than about 2 s, when stderr is a terminal; True / False force it on / off. A callable
        is called as ``progress(done, total)`` (in scenes) after each scene or chunk.

    theory : str or sequence of str
        The area theory of the solves (as in :func:`~persson_fast.solve_contact`:
        "persson01", the default, or a corrected one: "yp08" and "wm17" for every scene,
        "xu24" for scenes without adhesion or hardness; ``pull_off`` follows each scene's
        own theory and yield wall). A string is held fixed and recorded in ``attrs``. A
        sequence of distinct theories is an axis ``theory`` of the result, after the axes of
        ``params``; each of its entries gives bitwise the numbers of a scan with that theory
        held fixed, and ``attrs["theory"]`` and ``attrs["theory_gamma"]`` are then "". [-]
    theory_gamma : float or None
        The gamma of the corrected theories (None: each one's published default,
        ``persson_fast.theories.DEFAULT_GAMMA``). Held fixed: recorded in ``attrs``. With a
        theory axis it goes to every corrected theory of the axis and not to "persson01",
        which has no parameter (a value with "persson01" alone is a ValueError); the
        coordinate ``theory_gamma`` along ``theory`` records the gamma each theory used
        (NaN for "persson01"). [-]
    hardness : float or None
        The yield wall of every scene, unless scanned in ``params`` (values: a constant
        hardness [Pa], or None / NaN for none; see ``solve_contact(hardness=...)``). Held
        fixed, it may also be scale-dependent (a callable of zeta or a table; ``attrs``
        records its repr; a callable must pickle for process workers). With a
        yield wall anywhere in the scan the dataset has ``elastic_area`` and
        ``plastic_area`` ((..., pressure); ``area`` is their sum).
    separation : bool
        Also return the mean interfacial separation, the contact stiffness and the stored
        elastic energy of every scene and pressure (scenes without adhesion, theory
        "persson01"; otherwise a ValueError before anything is solved).
    gaps : bool or array_like
        Also return the distribution of interfacial gaps (:func:`~persson_fast.gap_distribution`)
        of every scene and pressure > 0, on a common ``gap`` axis: True takes the union of the
        scenes' default grids, an array (increasing, >= 0) [m] is taken as it is. Scenes as for
        ``separation`` (otherwise a ValueError before anything is solved).
    gaps_rtol : float or None
        Tolerance of the gap distributions (default 1e-3, that of gap_distribution); only
        with ``gaps`` (otherwise a ValueError). [-]

    Returns
    -------
    xarray.Dataset
        Dimensions: the scanned parameters in the order of ``params``, then ``theory`` (with
        a sequence of theories), then ``pressure`` (then ``zeta`` with ``profiles``).
        Variables:

        * ``area`` (..., pressure) -- A(zeta1)/A0. [-]
        * ``mean_contact_pressure`` (..., pressure) -- load / area, NaN without contact. [Pa]
        * ``error_estimate`` (..., pressure) -- estimated absolute error of ``area``. [-]
        * ``status`` (..., pressure) -- 0 ok, else see ``message``; ``SCENE_ERROR``
          (-1) where the scene's ``solve_contact`` raised.
        * ``success``, ``message``, ``method`` (...) -- per scene. ``message`` is
          ``solve_contact``'s message when the scene succeeded; when it failed it starts with
          what failed (never with "ok").
        * ``area_zeta``, ``sigma_a`` [Pa], ``gamma_eff`` [J/m^2] (..., pressure, zeta) -- with
          ``profiles``.
        * ``pull_off``, ``pull_off_error`` (...) -- with ``pull_off``: the pull-off stress
          and its estimated error. [Pa]
        * ``separation`` [m], ``stiffness`` [Pa/m], ``elastic_energy`` [J/m^2]
          (..., pressure) -- with ``separation``: the mean interfacial separation, the
          contact stiffness -dp/du and U_el of each scene (closed form,
          :func:`~persson_fast.solve_separation`; inf, 0, 0 where p <= 0).
        * ``gap_density`` [1/m] (..., pressure, gap), ``mean_gap`` [m] and
          ``gap_weight_error`` [-] (..., pressure) -- with ``gaps``: the density of the
          interfacial gap outside the contact (the contact fraction, at u = 0, is ``area``),
          its mean (u(p)) and abs(trapz(density, gap) + area - 1) on the ``gap`` axis; NaN where
          p <= 0 or the scene's gap distribution raised. A flagged distribution sets the
          scene's ``success`` False and says why in ``message``.

        Fixed parameters are scalar coordinates; ``attrs`` hold the surface model, method,
        rtol and how the scan ran. ``ds.to_dataframe()`` gives one row per (scene, pressure).

    Raises
    ------
    ValueError
        For invalid input, naming the argument, the rule and the offending value, before
        anything is solved (every scene's surface is built and checked first).

    Warns
    -----
    ScanWarning
        Once per scan when any scene failed (``success`` False): the number of failed scenes
        and of flagged (scene, pressure) points, and the parameters and messages of the
        worst few scenes (a raised solve first, then a failed pull-off, then the most
        flagged points).

    See Also
    --------
    persson_fast.solve_contact : One scene.
    persson_fast.pull_off : The pull-off stress of one scene.
    persson_fast.Scene : A scene to pass in place of the keywords.
    persson_fast.ScanWarning : What a scan with failed scenes issues.

    Notes
    -----
    Scene ``s`` of the grid is ``solve_contact(surface_s, pressure, e_star=..., ...)``; the
    dataset holds exactly its numbers, whichever execution path ran (see the module
    docstring). A scene that fails does not stop the scan: an exception raised by its
    ``solve_contact`` or ``pull_off`` is recorded (NaN numbers, ``status`` -1 for a raised
    solve, ``success`` False, the exception's type and text in ``message``), the other
    scenes run on, and the scan ends with one :class:`ScanWarning`. A ``KeyboardInterrupt``
    stops the scan: scenes not yet started are dropped (distributed: the pending tasks are
    cancelled) and the interrupt propagates.

    Examples
    --------
    >>> import numpy as np, persson_fast as pf
    >>> ds = pf.scan(pf.SelfAffine, {"hurst": [0.6, 0.8], "h_rms": [1e-7, 1e-6],
    ...              "q0": 1e4, "q1": 1e9}, np.linspace(0, 1e7, 11), e_star=3e9)
    >>> ds.area.dims
    ('hurst', 'h_rms', 'pressure')
    """
    xr = optional_import("xarray", "scan", "pf.scan")
    if isinstance(surface, Scene):
        # one scene, only solve parameters (or none) scanned: its values are the fixed ones
        surface, kw = unpack_scene(surface, {"e_star": e_star,
                                             "work_of_adhesion": work_of_adhesion,
                                             "energy_correction": energy_correction,
                                             "detachment_prefactor": detachment_prefactor,
                                             "hardness": hardness},
                                   "scan")
        hardness = kw.get("hardness")
        e_star, work_of_adhesion = kw["e_star"], kw["work_of_adhesion"]
        energy_correction = kw["energy_correction"]
        detachment_prefactor = kw["detachment_prefactor"]

    from .._version import __version__

    solve_keywords = {"e_star": e_star, "work_of_adhesion": work_of_adhesion,
                      "energy_correction": energy_correction,
                      "detachment_prefactor": detachment_prefactor, "hardness": hardness}
    if not isinstance(method, str) or method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(repr(m) for m in METHODS)}; "
                         f"got method = {method!r}")
    rtol = _check_rtol(rtol)
    theories, theory_axis = _check_theories(theory, theory_gamma)
    given_pull_off_rtol = pull_off_rtol
    pull_off_rtol = rtol if pull_off_rtol is None else _check_rtol(pull_off_rtol, "pull_off_rtol")
    p = _check_pressure(pressure)
    for name, flag in (("profiles", profiles), ("pull_off", pull_off),
                       ("separation", separation)):
        if not isinstance(flag, (bool, np.bool_)):
            raise ValueError(f"{name} must be True or False; got {name} = {flag!r}")
    if given_pull_off_rtol is not None and not pull_off:
        raise ValueError(f"pull_off_rtol is the accuracy of the pull-off stress and needs "
                         f"pull_off=True [-]; got pull_off_rtol = {pull_off_rtol!r} with "
                         f"pull_off = {pull_off!r}")
    chunks = _check_positive_int(chunks, "chunks")
    workers = _check_positive_int(workers, "workers")
    progress = _check_progress(progress)
    grid = _Grid(surface, params, solve_keywords, theories, theory_axis)
    zeta = _check_zeta(zeta, grid.surfaces)
    adhesive = [kw["work_of_adhesion"] > 0 for _, _, kw in grid.scenes]
    if method == "analytic" and any(adhesive):
        i = adhesive.index(True)
        raise ValueError(f"method 'analytic' has no closed form with adhesion; the scene "
                         f"{grid.labels[i]} has work_of_adhesion > 0; use method='auto' or 'cn'")
    corrected = [kw.get("theory", "persson01") != "persson01" for _, _, kw in grid.scenes]
    yielding = [kw.get("hardness") is not None for _, _, kw in grid.scenes]
    for k in range(len(corrected)):
        if corrected[k] and (adhesive[k] or yielding[k]):
            kw = grid.scenes[k][2]
            check_composition(kw["theory"], kw["work_of_adhesion"], kw.get("hardness"))
    if any(yielding):
        i = yielding.index(True)
        if separation:
            raise ValueError(f"separation=True needs elastic scenes: the scene "
                             f"{grid.labels[i]} has hardness (the separation is not derived "
                             f"with a yield wall here)")
        if method not in ("auto", "analytic", "strip"):
            raise ValueError(f"method {method!r} cannot carry a yield wall (hardness); use "
                             f"'auto', 'analytic' (a constant one) or 'strip' (the scene "
                             f"{grid.labels[i]} has hardness)")
    if separation and (any(corrected) or any(adhesive)):
        which = (f"theory = {grid.scenes[corrected.index(True)][2]['theory']!r}"
                 if any(corrected) else
                 f"the scene {grid.labels[adhesive.index(True)]} has work_of_adhesion > 0")
        raise ValueError(f"separation=True needs scenes without adhesion and the original "
                         f"theory (persson01): the separation is not derived otherwise here; "
                         f"{which}")
    gap_grid = _check_gap_option(gaps)
    if gaps_rtol is not None and gap_grid is False:
        raise ValueError(f"gaps_rtol is the tolerance of the gap distributions and needs gaps "
                         f"(True or an array of gaps) [-]; got gaps_rtol = {gaps_rtol!r} with "
                         f"gaps = {gaps!r}")
    gaps_rtol = 1e-3 if gaps_rtol is None else _check_rtol(gaps_rtol, "gaps_rtol")
    if gap_grid is not False and (any(corrected) or any(adhesive) or any(yielding)):
        which = (f"theory = {grid.scenes[corrected.index(True)][2]['theory']!r}"
                 if any(corrected) else
                 f"the scene {grid.labels[adhesive.index(True)]} has work_of_adhesion > 0"
                 if any(adhesive) else
                 f"the scene {grid.labels[yielding.index(True)]} has hardness")
        raise ValueError(f"gaps needs scenes without adhesion or yield wall and the original "
                         f"theory (persson01): the gap distribution is not derived otherwise "
                         f"here; {which}")
    profile_zeta = None
    zeta_plain = zeta_adhesive = zeta
    if profiles:
        profile_zeta, zeta_adhesive, zeta_plain = _profile_grid(
            grid, zeta, rtol, any(adhesive))
    options = {"method": method, "rtol": rtol, "zeta_plain": zeta_plain,
               "zeta_adhesive": zeta_adhesive, "profile_zeta": profile_zeta,
               "profiles": bool(profiles), "pull_off": bool(pull_off),
               "pull_off_rtol": pull_off_rtol, "parallel": None,
               "separation": bool(separation), "yield_wall": any(yielding),
               "gaps": gap_grid, "gaps_rtol": gaps_rtol}
    if workers is None:
        import numba

        workers = max(1, int(numba.get_num_threads()))

    results = [None] * grid.n_scenes
    t0 = time.perf_counter()
    client_, own_cluster, own_client = None, None, None
    bar = None
    try:
        client_, own_cluster, own_client = _open_client(client)
        threads = _worker_threads(client_) if client_ is not None else workers
        bar = _Progress(progress, grid.n_scenes, _estimate_seconds(grid, p.size, options, threads))
        # solve_contact and pull_off change the warning filters inside each scene
        # (catch_warnings), which is not thread-safe before Python 3.14: whatever state the
        # scene threads interleave to is undone here, when the scan ends
        with warnings.catch_warnings():
            if client_ is None:
                execution = _run_local(grid, p, options, workers, bar, results)
            else:
                execution = _run_distributed(client_, grid, p, options, chunks, bar, results)
    finally:
        if bar is not None:
            bar.close()
        if own_client is not None:
            own_client.close()
        if own_cluster is not None:
            own_cluster.close()
    wall = time.perf_counter() - t0
    ds = _assemble(xr, grid, p, results, options, profile_zeta,
                   {"surface_model": grid.factory_name, "method": method, "rtol": rtol,
                    "theory": "" if theory_axis else theories[0][0],
                    "theory_gamma": ("" if theory_axis or theories[0][1] is None else
                                     theories[0][1]),
                    "hardness": ("" if hardness is None or "hardness" in params else
                                 hardness if isinstance(hardness, float) else repr(hardness)),
                    "pull_off_rtol": pull_off_rtol if pull_off else "",
                    "gaps_rtol": gaps_rtol if options["gaps"] is not False else "",
                    "execution": execution, "wall_time_s": wall,
                    "persson_fast_version": __version__})
    summary = _failure_summary(grid, results, p.size)
    if summary is not None:
        warnings.warn(summary, ScanWarning, stacklevel=2)
    return ds
