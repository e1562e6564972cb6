"""Wall times of :func:`persson_fast.scan` at scale, and the choice of the local strategy.

Usage::

    python -m benchmarks.scan_scale [--quick] [--repeat N] [--json FILE]

Run in a fresh process, on a machine as idle as can be had; every figure is the wall time
(``time.perf_counter``) of one call, taken after ``pf.warmup(False)`` has loaded the serial
kernels from numba's disk cache and a first tiny scan has imported xarray, so that neither
compilation nor imports are mixed in. Printed:

1. **strategy** -- the same scans run (a) as plain serial ``solve_contact`` calls on one
   thread (the baseline), (b) on a pool of threads over scenes with the serial kernels
   (``scan``'s default) and (c) one scene after another with each pressure sweep spread over
   threads (``workers=1``; the ``prange`` kernels, compiled beforehand and timed apart, since
   they are not cached on disk), interleaved ``--repeat`` times (minimum and median);
2. **scale** -- 100 scenes x 100 pressures without adhesion (10,000 points; closed form, and
   the "cn" kernel), and 10 scenes x 100 pressures with adhesion at rtol = 1e-4 (1,000
   points).
"""
from __future__ import annotations

import argparse
import itertools
import json
import os
import platform
import time

import numpy as np

import persson_fast as pf
from persson_fast.scan.api import scan

#: E* of the seed's PMMA [Pa] and its work of adhesion [J/m^2]
E_STAR = pf.seed_e_star()
DGAMMA = pf.SEED_WORK_OF_ADHESION


def _timed(func, *args, **kwargs):
    t0 = time.perf_counter()
    out = func(*args, **kwargs)
    return time.perf_counter() - t0, out


def _self_affine_grid(n_hurst, n_h):
    return {"hurst": np.linspace(0.5, 0.95, n_hurst), "h_rms": np.geomspace(1e-7, 1e-5, n_h),
            "q0": 1e4, "q1": 1e9}


def _seed_adhesion_grid(n):
    seed = pf.seed_scene()
    return {"temperature": np.linspace(340.0, 400.0, n), "surface_tension": 0.04,
            "q_c": 1.7e9, "q0": seed.q0, "q1": 7e9}


def _serial_baseline(surface, params, pressure, **solve_kw):
    """The same scenes as plain serial solve_contact calls on one thread."""
    fixed = {k: v for k, v in params.items() if np.ndim(v) == 0}
    axes = {k: v for k, v in params.items() if np.ndim(v) > 0}
    t0 = time.perf_counter()
    for values in itertools.product(*axes.values()):
        kw = dict(fixed, **dict(zip(axes, values)))
        pf.solve_contact(surface(**kw), pressure, parallel=False, **solve_kw)
    return time.perf_counter() - t0


def strategy(quick: bool, repeat: int) -> dict:
    """Threads over scenes (serial kernels) against scenes in sequence with prange sweeps.

    The three variants run interleaved ``repeat`` times; the minimum and the median of each
    are reported (on a shared machine the minimum is the least disturbed figure).
    """
    n = 6 if quick else 20
    adh = dict(surface=pf.CapillaryWaves, e_star=E_STAR, work_of_adhesion=DGAMMA, rtol=1e-4)
    cases = {
        f"cn, {n} scenes x 100 pressures": dict(
            surface=pf.SelfAffine, params=_self_affine_grid(n // 2, 2),
            pressure=np.linspace(1e5, 5e7, 100), e_star=1e9, method="cn"),
        f"adhesion rtol 1e-4, {n // 2} scenes x 20 pressures": dict(
            params=_seed_adhesion_grid(n // 2), pressure=np.linspace(0.0, 50e6, 20), **adh),
        "adhesion rtol 1e-4, 3 scenes x 60 pressures": dict(
            params=_seed_adhesion_grid(3), pressure=np.linspace(0.0, 50e6, 60), **adh),
    }
    t_compile, _ = _timed(pf.warmup, True)
    out = {"compile_parallel_kernels_s": t_compile}
    for name, kw in cases.items():
        rest = dict(kw)
        surface, params, pressure = rest.pop("surface"), rest.pop("params"), rest.pop("pressure")
        times = {"serial_one_thread": [], "threads_over_scenes": [], "sequential_prange": []}
        equal = True
        for _ in range(repeat):
            times["serial_one_thread"].append(_serial_baseline(surface, params, pressure, **rest))
            t, a = _timed(scan, progress=False, **kw)
            times["threads_over_scenes"].append(t)
            t, b = _timed(scan, progress=False, workers=1, **kw)
            times["sequential_prange"].append(t)
            equal &= bool(np.array_equal(a.area.values, b.area.values))
        out[name] = {f"{k}_s": {"min": min(v), "median": float(np.median(v))}
                     for k, v in times.items()}
        out[name]["bitwise_equal"] = equal
    return out


def scale(quick: bool) -> dict:
    """The timed scale check: >= 10,000 points without and >= 1,000 with adhesion."""
    n10 = 4 if quick else 10
    p100 = np.linspace(0.0, 5e7, 100)
    out = {}
    t, ds = _timed(scan, pf.SelfAffine, _self_affine_grid(n10, n10), p100, e_star=1e9,
                   progress=False)
    out[f"no adhesion, closed form, {ds.area.size} points"] = t
    t, ds = _timed(scan, pf.SelfAffine, _self_affine_grid(n10, n10), p100 + 1e5, e_star=1e9,
                   method="cn", progress=False)
    out[f"no adhesion, cn, {ds.area.size} points"] = t
    n_adh = 3 if quick else 10
    t, ds = _timed(scan, pf.CapillaryWaves, _seed_adhesion_grid(n_adh),
                   np.linspace(-0.5e6, 50e6, 100), e_star=E_STAR, work_of_adhesion=DGAMMA,
                   rtol=1e-4, progress=False)
    out[f"adhesion rtol 1e-4, {ds.area.size} points"] = t
    out["adhesion points flagged (status != 0)"] = int((ds.status != 0).sum())
    return out


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller grids (a smoke run)")
    parser.add_argument("--repeat", type=int, default=5,
                        help="interleaved repeats of the strategy comparison (default 5)")
    parser.add_argument("--json", help="also write the figures to this JSON file")
    args = parser.parse_args(argv)
    t_load, _ = _timed(pf.warmup, False)
    # the first scan imports xarray (about 1 s); keep that out of the figures below
    t_first, _ = _timed(scan, pf.seed_scene(), {}, [1e6], e_star=E_STAR, progress=False)
    report = {
        "machine": {
            "cpus": (len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity")
                     else os.cpu_count()),
            "python": platform.python_version(),
            "load_average_at_start": os.getloadavg() if hasattr(os, "getloadavg") else None,
        },
        "load_serial_kernels_s": t_load,
        "first_scan_call_s": t_first,
        "scale": scale(args.quick),
        "strategy": strategy(args.quick, args.repeat),
    }
    print(json.dumps(report, indent=2))
    if args.json:
        with open(args.json, "w", encoding="utf-8") as fh:
            json.dump(report, fh, indent=2)
    return report


if __name__ == "__main__":
    main()
