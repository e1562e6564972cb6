"""What a finished parameter scan hands back: its dataset and its one failure warning.

:func:`_assemble` places the per-scene results of :func:`persson_fast.scan` on the labelled
grid of an :class:`xarray.Dataset` (the scanned axes, ``pressure`` and ``zeta``, with units
in ``attrs``); :func:`_failure_summary` writes the text of the
:class:`~persson_fast.ScanWarning` that a scan with failed scenes issues.
"""
from __future__ import annotations

import math

import numpy as np

from .run import SCENE_ERROR

__all__ = ["WARN_SCENES", "WARN_MESSAGE_CHARS"]

#: scenes the warning of a scan with failures names (the worst first)
WARN_SCENES = 3
#: characters of each scene's message quoted in that warning
WARN_MESSAGE_CHARS = 300


def _failure_summary(grid, results, n_p):
    """The text of the scan's one ScanWarning; None when every scene succeeded."""
    failed = [i for i, res in enumerate(results) if not res["success"]]
    if not failed:
        return None
    flagged = [int(np.count_nonzero(res["status"])) for res in results]

    def severity(i):
        res = results[i]
        no_numbers = bool(np.any(res["status"] == SCENE_ERROR))
        no_pull_off = math.isnan(res.get("pull_off", 0.0))
        return (no_numbers, no_pull_off, flagged[i])

    worst = sorted(failed, key=severity, reverse=True)[:WARN_SCENES]   # stable: grid order
    n_points = sum(flagged)
    lines = [f"scan: {len(failed)} of {grid.n_scenes} scenes failed (success False) and "
             f"{n_points} of {grid.n_scenes * n_p} (scene, pressure) points are flagged "
             f"(status != 0): a failed solve or pull-off is NaN, a flagged or unconverged value "
             f"is kept; see ds.success, ds.message and ds.status. "
             f"{'The worst' if len(failed) > len(worst) else 'Failed'}:"]
    for i in worst:
        msg = str(results[i]["message"])
        if len(msg) > WARN_MESSAGE_CHARS:
            msg = msg[:WARN_MESSAGE_CHARS - 3] + "..."
        lines.append(f"  {grid.labels[i]}: {msg}")
    if len(failed) > len(worst):
        lines.append(f"  ... and {len(failed) - len(worst)} more")
    return "\n".join(lines)


def _gap_variables(data, coords, results, options, shape, per_p, n_p):
    """``gap_density``, ``mean_gap`` and ``gap_weight_error`` on a common ``gap`` axis: the
    given gaps, or the union of the scenes' default grids (each scene's components evaluated
    there, :meth:`~persson_fast.separation.gaps.GapDistribution.density_at`)."""
    dists = [res["gaps"] for res in results]
    if options["gaps"] is True:
        grids = [g.gaps for _, g in dists if g is not None]
        u = np.unique(np.concatenate(grids)) if grids else np.array([0.0, 1.0])
    else:
        u = np.asarray(options["gaps"], dtype=float)
    n = len(results)
    density = np.full((n, n_p, u.size), np.nan)
    mean = np.full((n, n_p), np.nan)
    weight_error = np.full((n, n_p), np.nan)
    for i, (positive, g) in enumerate(dists):
        if g is None:
            continue
        dens = g.density if g.gaps.size == u.size and np.array_equal(g.gaps, u) else \
            g.density_at(u)
        density[i, positive] = dens
        mean[i, positive] = g.mean
        trap = np.sum(0.5 * (dens[:, 1:] + dens[:, :-1]) * np.diff(u), axis=1)
        weight_error[i, positive] = np.abs(trap + g.contact_fraction - 1.0)
    coords["gap"] = ("gap", u, {"long_name": "interfacial gap", "units": "m"})
    data["gap_density"] = (per_p + ("gap",), density.reshape(shape + (n_p, u.size)),
                           {"long_name": "probability density of the interfacial gap outside "
                                         "the contact", "units": "1/m"})
    data["mean_gap"] = (per_p, mean.reshape(shape + (n_p,)),
                        {"long_name": "mean interfacial gap (the separation u)", "units": "m"})
    data["gap_weight_error"] = (per_p, weight_error.reshape(shape + (n_p,)),
                                {"long_name": "|trapz(gap_density, gap) + area - 1|",
                                 "units": "-"})


def _assemble(xr, grid, p, results, options, profile_zeta, attrs):
    shape = grid.shape
    n_p = p.size
    dims = tuple(grid.dims)
    per_p = dims + ("pressure",)

    def stack(name, dtype, tail=()):
        arr = np.empty((grid.n_scenes,) + tail, dtype=dtype)
        for i, res in enumerate(results):
            arr[i] = res[name]
        return arr.reshape(shape + tail)

    data = {
        "area": (per_p, stack("area", float, (n_p,)),
                 {"long_name": "relative real contact area A(zeta1)/A0", "units": "-"}),
        "mean_contact_pressure": (per_p, stack("mean_contact_pressure", float, (n_p,)),
                                  {"long_name": "mean stress in the contact, load/area",
                                   "units": "Pa"}),
        "error_estimate": (per_p, stack("error_estimate", float, (n_p,)),
                           {"long_name": "estimated absolute error of area", "units": "-"}),
        "status": (per_p, stack("status", np.int64, (n_p,)),
                   {"long_name": f"status per pressure (0 ok, {SCENE_ERROR} the scene's solve "
                                 f"raised, others a kernel code; see message)"}),
        "success": (dims, stack("success", bool),
                    {"long_name": "scene solved: every pressure (and the pull-off) ok"}),
        "message": (dims, stack("message", object).astype(str), {"long_name": "solver message"}),
        "method": (dims, stack("method", object).astype(str),
                   {"long_name": "method that produced the numbers"}),
    }
    coords = {d: (d, grid.coords[d], {"units": grid.units[d]} if d in grid.units else {})
              for d in dims}
    coords["pressure"] = ("pressure", p, {"long_name": "nominal pressure", "units": "Pa"})
    for name, value in grid.fixed_coords.items():
        units = {"units": grid.units[name]} if name in grid.units else {}
        coords[name] = ((), value, units)
    coords.update(grid.aux_coords)
    if options["profiles"]:
        n_z = profile_zeta.size
        per_z = per_p + ("zeta",)
        coords["zeta"] = ("zeta", profile_zeta, {"long_name": "magnification", "units": "-"})
        data["area_zeta"] = (per_z, stack("area_zeta", float, (n_p, n_z)),
                             {"long_name": "relative contact area A(zeta)/A0", "units": "-"})
        data["sigma_a"] = (per_z, stack("sigma_a", float, (n_p, n_z)),
                           {"long_name": "detachment stress sigma_a(zeta)", "units": "Pa"})
        data["gamma_eff"] = (per_z, stack("gamma_eff", float, (n_p, n_z)),
                             {"long_name": "effective interfacial energy", "units": "J/m^2"})
    if options.get("yield_wall"):
        data["elastic_area"] = (per_p, stack("elastic_area", float, (n_p,)),
                                {"long_name": "elastic contact area A_el/A0", "units": "-"})
        data["plastic_area"] = (per_p, stack("plastic_area", float, (n_p,)),
                                {"long_name": "yielded (plastic) contact area A_pl/A0",
                                 "units": "-"})
    if options.get("separation"):
        data["separation"] = (per_p, stack("separation", float, (n_p,)),
                              {"long_name": "mean interfacial separation u", "units": "m"})
        data["stiffness"] = (per_p, stack("stiffness", float, (n_p,)),
                             {"long_name": "contact stiffness -dp/du", "units": "Pa/m"})
        data["elastic_energy"] = (per_p, stack("elastic_energy", float, (n_p,)),
                                  {"long_name": "stored elastic energy U_el per nominal area",
                                   "units": "J/m^2"})
    if options.get("gaps") is not False and options.get("gaps") is not None:
        _gap_variables(data, coords, results, options, shape, per_p, n_p)
    if options["pull_off"]:
        data["pull_off"] = (dims, stack("pull_off", float),
                            {"long_name": "pull-off stress sigma_c", "units": "Pa"})
        data["pull_off_error"] = (dims, stack("pull_off_error", float),
                                  {"long_name": "estimated error of pull_off", "units": "Pa"})
    return xr.Dataset(data, coords=coords, attrs=attrs)
