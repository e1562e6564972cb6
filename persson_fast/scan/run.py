"""How a parameter scan runs: one scene, a chunk of scenes, threads or a dask cluster.

:func:`_solve_scene` solves one scene of :func:`persson_fast.scan` (its
:func:`~persson_fast.solve_contact` and, on request, its :func:`~persson_fast.pull_off`) and
records a failure instead of raising; :func:`solve_chunk` is the task of the distributed path.
:func:`_run_local` runs the scenes in the calling thread or on a pool of threads,
:func:`_run_distributed` as chunks on a dask cluster (:func:`_open_client` opens one); both
place each result by its scene index. :class:`_Progress` is the optional progress bar.
"""
from __future__ import annotations

import math
import sys
import uuid
import warnings
from concurrent.futures import ThreadPoolExecutor, wait, FIRST_COMPLETED

import numpy as np

from .._validation import optional_import
from ..adhesion.pulloff import pull_off as _pull_off
from ..api import solve_contact
from .grid import SOLVE_PARAMETERS

__all__ = ["solve_chunk", "SCENE_ERROR", "PROGRESS_MIN_SCENES", "PROGRESS_MIN_SECONDS"]

#: ``progress=None`` shows a bar when a scan has more scenes than this ...
PROGRESS_MIN_SCENES = 50
#: ... or is estimated to take longer than this [s] (and stderr is a terminal)
PROGRESS_MIN_SECONDS = 2.0

# rough costs per pressure on one core, only used to decide whether to show a progress bar:
# closed form, the "cn" kernel without adhesion, the adhesive fixed point at rtol = 1e-4
_COST_CLOSED_FORM = 2e-6
_COST_CN = 6e-4
_COST_ADHESION = 5e-3
_COST_SCENE = 2e-4
_PULL_OFF_SOLVES = 40

#: ``status`` of every pressure of a scene whose solve raised an exception (its numbers are
#: NaN and ``message`` names the error); kernel status codes are >= 0
SCENE_ERROR = -1


# ----------------------------------------------------------------------------------------------
# the work: one scene, one chunk of scenes (module level, so that dask can ship it)
# ----------------------------------------------------------------------------------------------
def _failure(what, exc) -> str:
    """'<what> raised <Type>: <text>' for an exception of solve_contact or pull_off."""
    text = str(exc)
    if text.startswith(f"{what}: "):
        text = text[len(what) + 2:]
    return f"{what} raised {type(exc).__name__}" + (f": {text}" if text else "")


def _gap_part(surface, solve_kw, pressure, options, out, failures):
    """The scene's gap distribution at its pressures > 0 (``out["gaps"]``: the pressure mask
    and the :class:`~persson_fast.separation.gaps.GapDistribution`, or None where it raised)."""
    from ..separation.gaps import gap_distribution

    positive = pressure > 0.0
    grid = options["gaps"]
    try:
        g = gap_distribution(surface, pressure[positive], e_star=solve_kw["e_star"],
                             energy_correction=solve_kw.get("energy_correction"),
                             gaps=None if grid is True else grid, rtol=options["gaps_rtol"])
    except Exception as exc:  # noqa: BLE001 -- recorded: the scan goes on
        out["gaps"] = (positive, None)
        failures.append(_failure("gap_distribution", exc))
        return
    out["gaps"] = (positive, g)
    if not g.success:
        failures.append(f"gap_distribution: {g.message}")


def _solve_scene(surface, solve_kw, pressure, options):
    """Solve one scene at every pressure; a dict of plain arrays and strings.

    A failure of the scene does not raise: an exception of :func:`solve_contact` leaves its
    numbers NaN with status :data:`SCENE_ERROR`, one of :func:`pull_off` leaves ``pull_off``
    NaN, and a pull-off whose error estimate exceeds its tolerance keeps its value; each sets
    ``success`` False and puts what failed first in ``message`` (never "ok ..."), so that one
    scene cannot stop a scan of thousands and no failure passes as a number.
    """
    n_p = pressure.size
    dg = solve_kw["work_of_adhesion"]
    adhesive = dg > 0.0
    zeta = options["zeta_adhesive"] if adhesive else options["zeta_plain"]
    # without adhesion a tensile nominal stress separates the surfaces: A = 0, no solve
    rows = np.arange(n_p) if adhesive else np.flatnonzero(pressure >= 0.0)
    out = {
        "area": np.zeros(n_p),
        "mean_contact_pressure": np.full(n_p, np.nan),
        "error_estimate": np.zeros(n_p),
        "status": np.zeros(n_p, dtype=np.int64),
        "success": True,
        "message": "ok",
        "method": "none",
    }
    failures = []          # what failed, first in the message
    solve_message = "ok"   # solve_contact's own message when it succeeded
    n_z = 0 if options["profile_zeta"] is None else options["profile_zeta"].size
    if options["profiles"]:
        for name in ("area_zeta", "sigma_a", "gamma_eff"):
            out[name] = np.zeros((n_p, n_z))
    if options.get("yield_wall"):
        out["elastic_area"] = np.zeros(n_p)
        out["plastic_area"] = np.zeros(n_p)
    if options.get("separation"):
        out["separation"] = np.full(n_p, np.inf)
        out["stiffness"] = np.zeros(n_p)
        out["elastic_energy"] = np.zeros(n_p)
    if rows.size:
        try:
            r = solve_contact(surface, pressure[rows], method=options["method"],
                              rtol=options["rtol"], zeta=zeta, parallel=options["parallel"],
                              **solve_kw)
        except Exception as exc:  # noqa: BLE001 -- recorded: the scan goes on
            for name in ("area", "mean_contact_pressure", "error_estimate", "area_zeta",
                         "sigma_a", "gamma_eff", "separation", "stiffness", "elastic_energy",
                         "elastic_area", "plastic_area"):
                if name in out:
                    out[name][:] = np.nan
            out["status"][:] = SCENE_ERROR
            failures.append(_failure("solve_contact", exc))
        else:
            out["area"][rows] = r.area
            mcp = getattr(r, "mean_contact_pressure", None)
            if mcp is None:
                mcp = np.where(r.area > 0, r.load / np.where(r.area > 0, r.area, 1.0), np.nan)
            out["mean_contact_pressure"][rows] = mcp
            out["error_estimate"][rows] = r.error_estimate
            out["status"][rows] = r.status
            out["method"] = str(r.method)
            if options.get("yield_wall"):
                plastic = r.plastic_area if r.plastic_area is not None else 0.0
                out["plastic_area"][rows] = plastic
                out["elastic_area"][rows] = r.area - plastic
            if options.get("separation"):
                out["separation"][rows] = r.separation
                out["stiffness"][rows] = r.stiffness
                out["elastic_energy"][rows] = r.elastic_energy
            if r.success:
                solve_message = str(r.message)
            else:
                failures.append(str(r.message))
            if options["profiles"]:
                if not np.array_equal(r.zeta, options["profile_zeta"]):
                    raise RuntimeError("scan: a scene returned profiles on another zeta grid "
                                       "than the scan's; pass zeta= explicitly")
                out["area_zeta"][rows] = r.area_zeta
                out["sigma_a"][rows] = r.sigma_a
                out["gamma_eff"][rows] = r.gamma_eff
    if options.get("gaps") is not False and options.get("gaps") is not None:
        _gap_part(surface, solve_kw, pressure, options, out, failures)
    if options["pull_off"]:
        try:
            # pull_off warns when its estimate misses rtol; info["converged"] says the same
            # and is recorded below (the outer catch_warnings of scan undoes any interleaving
            # of these filter changes between threads)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                # the scene as solved: its theory and yield wall included
                pull_kw = {k: v for k, v in solve_kw.items()
                           if k in SOLVE_PARAMETERS or k in ("theory", "theory_gamma")}
                sigma_c, info = _pull_off(surface, rtol=options["pull_off_rtol"],
                                          full_output=True, bracket=False, **pull_kw)
        except Exception as exc:  # noqa: BLE001 -- recorded: the scan goes on
            out["pull_off"] = out["pull_off_error"] = math.nan
            failures.append(_failure("pull_off", exc))
        else:
            out["pull_off"] = float(sigma_c)
            out["pull_off_error"] = float(info["error_estimate"])
            if not info["converged"]:
                failures.append(
                    f"pull_off did not converge: estimated error {info['error_estimate']:.3g} Pa "
                    f"of pull_off = {sigma_c:.6g} Pa exceeds pull_off_rtol * pull_off")
    if failures:
        out["success"] = False
        if solve_message != "ok":
            failures.append(f"solve_contact: {solve_message}")
        message = "; ".join(failures)
        out["message"] = f"failed: {message}" if message.lower().startswith("ok") else message
    else:
        out["message"] = solve_message
    return out


def solve_chunk(scenes, pressure, options):
    """Solve a chunk of scenes one after another (the task of the distributed path).

    Parameters
    ----------
    scenes : list of (int, Surface, dict)
        Flat scene index, surface, and the keyword arguments of :func:`solve_contact`
        (``e_star``, ``work_of_adhesion``, ``energy_correction``, ``detachment_prefactor``,
        ``hardness``; ``theory`` and ``theory_gamma`` for a corrected theory).
    pressure : numpy.ndarray, shape (n_p,)
        Nominal pressures. [Pa]
    options : dict
        Solve options built by :func:`scan`.

    Returns
    -------
    list of (int, dict)
        The scene index and its results, in the order of ``scenes``.
    """
    return [(index, _solve_scene(surface, kw, pressure, options))
            for index, surface, kw in scenes]


def _estimate_seconds(grid, n_p, options, workers):
    total = 0.0
    closed = options["method"] in ("auto", "analytic")
    for _, _, kw in grid.scenes:
        if kw["work_of_adhesion"] > 0:
            per = _COST_ADHESION * (1e-4 / options["rtol"]) ** 0.45
            total += per * n_p
            if options["pull_off"]:
                per_po = _COST_ADHESION * (1e-4 / options["pull_off_rtol"]) ** 0.45
                total += _PULL_OFF_SOLVES * per_po
        else:
            total += (_COST_CLOSED_FORM if closed else _COST_CN) * n_p
        total += _COST_SCENE
    return total / max(1, workers)


class _Progress:
    """A tqdm bar, a user callback progress(done, total), or nothing."""

    def __init__(self, progress, total, estimate):
        self.callback = progress if callable(progress) and not isinstance(progress, bool) else None
        self.bar = None
        self.done = 0
        self.total = total
        show = progress is True or (
            progress is None
            and (total > PROGRESS_MIN_SCENES or estimate > PROGRESS_MIN_SECONDS)
            and _stderr_is_terminal())
        if show:
            tqdm = optional_import("tqdm", "scan", "a scan's progress bar").tqdm

            self.bar = tqdm(total=total, unit="scene", desc="scan", file=sys.stderr,
                            dynamic_ncols=True)

    def update(self, n):
        self.done += n
        if self.bar is not None:
            self.bar.update(n)
        if self.callback is not None:
            self.callback(self.done, self.total)

    def close(self):
        if self.bar is not None:
            self.bar.close()


def _stderr_is_terminal() -> bool:
    try:
        return bool(sys.stderr.isatty())
    except (AttributeError, ValueError):
        return False


# ----------------------------------------------------------------------------------------------
# execution paths
# ----------------------------------------------------------------------------------------------
def _run_local(grid, pressure, options, workers, progress, results):
    closed = (options["method"] in ("auto", "analytic")
              and all(kw["work_of_adhesion"] == 0 for _, _, kw in grid.scenes))
    if closed or workers == 1 or grid.n_scenes == 1:
        # closed forms are microseconds of Python (threads would only add overhead); one
        # scene or one worker: solve_contact picks its own pressure parallelism
        for index, surface, kw in grid.scenes:
            try:
                results[index] = _solve_scene(surface, kw, pressure, options)
            except Exception as exc:      # a failure of the scan itself, not of the scene
                _add_note(exc, f"in scan scene {grid.labels[index]}")
                raise
            progress.update(1)
        return "local, sequential"
    opts = dict(options, parallel=False)      # threads over scenes, serial kernels inside
    pool = ThreadPoolExecutor(max_workers=workers, thread_name_prefix="persson-scan")
    futures = {}
    try:
        for index, surface, kw in grid.scenes:
            futures[pool.submit(_solve_scene, surface, kw, pressure, opts)] = index
        pending = set(futures)
        while pending:
            done, pending = wait(pending, timeout=0.2, return_when=FIRST_COMPLETED)
            for fut in done:
                index = futures[fut]
                try:
                    results[index] = fut.result()
                except BaseException as exc:
                    _add_note(exc, f"in scan scene {grid.labels[index]}")
                    raise
                progress.update(1)
    finally:
        # on an interrupt or error: drop the scenes not started, wait for the running ones
        for fut in futures:
            fut.cancel()
        pool.shutdown(wait=True, cancel_futures=True)
    return f"local, {workers} threads over scenes"


def _add_note(exc, note):
    if hasattr(exc, "add_note"):
        exc.add_note(note)


def _warm_worker():
    """Load the serial kernels on a worker (from numba's disk cache after the first time)."""
    from ..api import warmup

    return warmup(False)


def _worker_threads(client) -> int:
    try:
        info = client.scheduler_info()
        return max(1, sum(int(w.get("nthreads", 1)) for w in info.get("workers", {}).values()))
    except Exception:  # noqa: BLE001 -- a best guess only decides the chunk size
        return 1


def _run_distributed(client, grid, pressure, options, chunks, progress, results):
    as_completed = optional_import("distributed", "scan", "pf.scan(client=...)").as_completed

    opts = dict(options, parallel=False)
    if chunks is None:
        n_tasks = 4 * _worker_threads(client)
        chunks = max(1, -(-grid.n_scenes // n_tasks))
    groups = [grid.scenes[i:i + chunks] for i in range(0, grid.n_scenes, chunks)]
    client.run(_warm_worker)
    token = uuid.uuid4().hex[:12]
    keys = [f"persson-scan-{token}-{k}" for k in range(len(groups))]
    futures = None
    try:
        futures = client.map(solve_chunk, groups, [pressure] * len(groups),
                             [opts] * len(groups), key=keys, pure=False)
        for fut in as_completed(futures):
            chunk = fut.result()
            for index, res in chunk:
                results[index] = res
            progress.update(len(chunk))
            del fut
    except BaseException:
        # an interrupt or a failed chunk: no task of this scan may stay on the cluster
        if futures is None:
            from distributed import Future

            futures = [Future(k, client=client) for k in keys]
        client.cancel(futures, force=True)
        raise
    finally:
        futures = None
    return f"distributed, {len(groups)} tasks of <= {chunks} scenes"


def _open_client(client):
    """(client, cluster we own or None, client we own or None)."""
    if client is None:
        return None, None, None
    if isinstance(client, str):
        distributed = optional_import("distributed", "scan", "pf.scan(client=...)")
        Client, LocalCluster = distributed.Client, distributed.LocalCluster

        if client == "local":
            cluster = LocalCluster(n_workers=None, threads_per_worker=1, processes=True,
                                   dashboard_address=":0")
            try:
                own = Client(cluster)
            except BaseException:
                cluster.close()
                raise
            return own, cluster, own
        own = Client(client)
        return own, None, own
    for attr in ("map", "cancel", "run", "submit"):
        if not hasattr(client, attr):
            raise ValueError(f"client must be None, 'local', a scheduler address or a "
                             f"dask.distributed.Client; got {client!r}")
    return client, None, None
