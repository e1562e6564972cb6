"""Random self-affine adhesive scenes: the time per pressure of the scenes an adhesion study
scans, beside the seed scene's.

    python -m benchmarks.adhesive_scenes --rtol 1e-4                 # times, one thread
    python -m benchmarks.adhesive_scenes --rtol 1e-4 --check         # and errors, flags
    python -m benchmarks.adhesive_scenes --rtol 1e-4 --json out.json # rows for the report
    python -m benchmarks.adhesive_scenes --rtol 1e-3 --pull-off      # pull_off per scene

The scenes (fixed seed, ``--seed``, ``--scenes``): self-affine surfaces with Hurst exponent
0.6-0.9, q0 = 10^3.5-10^5.5 1/m, 2.5-5 decades of roughness, h_rms 10 nm-1 um, E* 3 MPa-10 GPa,
a work of adhesion of 3 mJ/m^2-0.3 J/m^2 (all log-uniform but the Hurst exponent), each at the
nominal pressures 0, 0.3, 1 and 3 sqrt(G1). Every scene is solved once untimed (so that no
compilation is timed) and then timed with ``solve_contact(..., rtol=rtol, parallel=False)``;
``--check`` also solves it at rtol/100 and reports, per row, the error against that solve, the
error estimate and the status: a status-0 row outside rtol is a silent miss, and a flagged row
whose error is within rtol a flag that did not need to be raised.

The seed scene (the PMMA lens of the seed paper, Delta gamma = 0.06 J/m^2, 101 pressures
0-100 MPa) is timed the same way. The module uses only the public API, so the same file copied
into the ``benchmarks/`` of an older checkout times that version (run the two one after the
other on one machine).
"""
from __future__ import annotations

import argparse
import json
import math
import time
import warnings

import numpy as np

import persson_fast as pf

#: the ranges of the random scenes (log10 where the name says so)
HURST = (0.6, 0.9)
LOG_Q0 = (3.5, 5.5)
DECADES = (2.5, 5.0)
LOG_H_RMS = (-8.0, -6.0)
LOG_E_STAR = (math.log10(3e6), 10.0)
LOG_DGAMMA = (math.log10(3e-3), math.log10(0.3))
#: the nominal pressures of every scene, in units of sqrt(G1)
PRESSURES = (0.0, 0.3, 1.0, 3.0)


def draw(rng):
    """One random scene: a dict of its parameters."""
    q0 = 10 ** rng.uniform(*LOG_Q0)
    return dict(hurst=float(rng.uniform(*HURST)), q0=float(q0),
                q1=float(q0 * 10 ** rng.uniform(*DECADES)),
                h_rms=float(10 ** rng.uniform(*LOG_H_RMS)),
                e_star=float(10 ** rng.uniform(*LOG_E_STAR)),
                work_of_adhesion=float(10 ** rng.uniform(*LOG_DGAMMA)))


def scenes(seed=1, n=40):
    """The first ``n`` scenes of ``seed``."""
    rng = np.random.default_rng(seed)
    return [draw(rng) for _ in range(n)]


def build(params):
    """(surface, keywords of solve_contact, pressures [Pa]) of a scene."""
    s = pf.SelfAffine(hurst=params["hurst"], q0=params["q0"], q1=params["q1"],
                      h_rms=params["h_rms"])
    root_g1 = math.sqrt(float(s.diffusion_time(s.q1, params["e_star"])))
    kw = dict(e_star=params["e_star"], work_of_adhesion=params["work_of_adhesion"])
    return s, kw, root_g1 * np.array(PRESSURES)


def seed_scene():
    """The seed paper's scene with adhesion, its keywords and its 101 pressures."""
    s = pf.CapillaryWaves(temperature=370.0, surface_tension=0.04, q_c=1.7e9,
                          q0=2 * np.pi / 1e-4, q1=7e9)
    kw = dict(e_star=2.9e9 / (1 - 0.3 ** 2), work_of_adhesion=0.06)
    return s, kw, np.linspace(0.0, 100e6, 101)


#: the clock of the timings: wall time, or (``--cpu``) the process's CPU time, which a busy
#: machine inflates less (one thread: the same on a quiet one)
CLOCK = {"clock": time.perf_counter}


def _timed(surface, kw, p, rtol, repeat=1):
    best = math.inf
    clock = CLOCK["clock"]
    for _ in range(repeat):
        t0 = clock()
        r = pf.solve_contact(surface, p, rtol=rtol, parallel=False, **kw)
        best = min(best, clock() - t0)
    return r, best


def run(rtol, seed=1, n=40, check=False, repeat=1, out=print):
    """Time every scene (and the seed scene); with ``check`` compare with rtol/100. Returns
    a dict of rows."""
    warnings.simplefilter("ignore")
    s, kw, p = seed_scene()
    pf.solve_contact(s, p[:2], rtol=rtol, parallel=False, **kw)        # compile untimed
    r, t = _timed(s, kw, p, rtol, repeat)
    seed_ms = 1e3 * t / p.size
    out(f"seed scene, 101 pressures at rtol {rtol:g}: {seed_ms:.2f} ms per pressure, "
        f"status {np.bincount(r.status).tolist()}")
    rows = []
    for i, params in enumerate(scenes(seed, n)):
        s, kw, p = build(params)
        try:
            pf.solve_contact(s, p[:1], rtol=max(rtol, 1e-3), parallel=False, **kw)
            r, t = _timed(s, kw, p, rtol, repeat)
        except (ValueError, RuntimeError) as exc:
            out(f"scene {i}: {type(exc).__name__}: {exc}")
            rows.append(dict(scene=i, params=params, error=str(exc)))
            continue
        row = dict(scene=i, params=params, ms_per_pressure=1e3 * t / p.size,
                   status=r.status.tolist(), area=r.area.tolist(),
                   estimate=r.error_estimate.tolist(),
                   iterations=np.asarray(r.iterations).tolist())
        if check:
            ref = pf.solve_contact(s, p, rtol=rtol / 100, parallel=False, **kw)
            row["reference"] = ref.area.tolist()
            row["reference_status"] = ref.status.tolist()
        rows.append(row)
        sticky = "sticky" if bool(np.any(r.sticky)) else "not sticky"
        line = (f"scene {i:3d} H={params['hurst']:.3f} q0={params['q0']:.3g} "
                f"q1={params['q1']:.3g} h={params['h_rms']:.3g} E*={params['e_star']:.3g} "
                f"dg={params['work_of_adhesion']:.3g} ({sticky}): "
                f"{row['ms_per_pressure']:8.2f} ms/p, status {row['status']}, "
                f"iterations {row['iterations']}")
        if check:
            err = np.abs(r.area - ref.area)
            tol = rtol * ref.area + 1e-12
            line += f", error/tol {np.round(err / tol, 3).tolist()}"
        out(line)
    summary = summarize(rows, rtol, seed_ms)
    out(format_summary(summary, rtol))
    return dict(rtol=rtol, seed=seed, seed_ms_per_pressure=seed_ms, rows=rows,
                summary=summary)


def run_pull_off(rtol, seed=1, n=40, out=print):
    """pull_off of every scene at ``rtol``: its value, error estimate and time (or the error
    it raised). Returns the rows."""
    warnings.simplefilter("ignore")
    rows = []
    for i, params in enumerate(scenes(seed, n)):
        s, kw, _ = build(params)
        clock = CLOCK["clock"]
        t0 = clock()
        try:
            sigma_c, info = pf.pull_off(s, rtol=rtol, full_output=True, **kw)
            row = dict(scene=i, sigma_c=float(sigma_c), seconds=clock() - t0,
                       estimate=float(info.get("error_estimate", 0.0)),
                       converged=bool(info.get("converged", True)))
        except (ValueError, RuntimeError) as exc:
            row = dict(scene=i, error=f"{type(exc).__name__}: {exc}", seconds=clock() - t0)
        rows.append(row)
        out(f"scene {i:3d}: " + (f"sigma_c {row['sigma_c']:.6g} Pa, estimate "
                                 f"{row['estimate']:.3g} Pa, converged {row['converged']}"
                                 if "error" not in row else row["error"])
            + f", {row['seconds']:.3f} s")
    t = np.array([r["seconds"] for r in rows])
    out(f"pull_off at rtol {rtol:g}: {sum('error' in r for r in rows)} raised, "
        f"{sum(not r.get('converged', True) for r in rows)} not converged; time per scene "
        f"median {np.median(t):.3f} s, worst {t.max():.3f} s, total {t.sum():.2f} s")
    return rows


def summarize(rows, rtol, seed_ms):
    """Median, 90th percentile, slowest tenth and worst time per pressure; with references:
    silent misses, flags and the share of flags within rtol."""
    t = np.array([r["ms_per_pressure"] for r in rows if "ms_per_pressure" in r])
    out = dict(n=int(t.size), failed=sum("error" in r for r in rows))
    if t.size:
        slow = np.sort(t)[-max(1, t.size // 10):]
        out.update(median=float(np.median(t)), p90=float(np.percentile(t, 90)),
                   slowest_tenth=float(slow.mean()), worst=float(t.max()),
                   p90_over_seed=float(np.percentile(t, 90) / seed_ms))
    checked = [r for r in rows if "reference" in r]
    if checked:
        rows_ok = misses = flags = flags_within = 0
        worst = 0.0
        ratios = []
        for r in checked:
            for a, e, st, ref, rst in zip(r["area"], r["estimate"], r["status"],
                                          r["reference"], r["reference_status"]):
                if rst != 0:
                    continue
                err = abs(a - ref)
                tol = rtol * ref + 1e-12
                if st != 0:
                    flags += 1
                    flags_within += err <= tol
                    continue
                rows_ok += 1
                worst = max(worst, err / tol)
                misses += err > tol + 1e-2 * rtol * ref
                if err > 0.1 * tol:
                    ratios.append(e / err)
        out.update(rows=rows_ok, misses=misses, flags=flags, flags_within=flags_within,
                   worst_error_over_tol=worst,
                   estimate_over_error=(float(min(ratios)), float(max(ratios)))
                   if ratios else None)
    return out


def format_summary(s, rtol):
    if not s["n"]:
        return "no scene solved"
    text = (f"rtol {rtol:g}: {s['n']} scenes ({s['failed']} failed), time per pressure median "
            f"{s['median']:.2f} ms, 90th percentile {s['p90']:.2f} ms "
            f"({s['p90_over_seed']:.2f}x the seed scene's), slowest tenth {s['slowest_tenth']:.2f} "
            f"ms, worst {s['worst']:.2f} ms")
    if "rows" in s:
        text += (f"; {s['rows']} status-0 rows, {s['misses']} silent misses, worst "
                 f"{s['worst_error_over_tol']:.3g} rtol; {s['flags']} flagged, "
                 f"{s['flags_within']} of them within rtol; estimate/error (errors > 0.1 rtol) "
                 f"{s['estimate_over_error']}")
    return text


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rtol", type=float, default=1e-4)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--scenes", type=int, default=40)
    ap.add_argument("--repeat", type=int, default=1, help="best of this many timed runs")
    ap.add_argument("--check", action="store_true", help="compare with a solve at rtol/100")
    ap.add_argument("--json", help="write the rows to this file")
    ap.add_argument("--cpu", action="store_true", help="time with the process's CPU time")
    ap.add_argument("--pull-off", action="store_true",
                    help="time pull_off of every scene instead (at --rtol)")
    a = ap.parse_args(argv)
    if a.cpu:
        CLOCK["clock"] = time.process_time
    if a.pull_off:
        rows = run_pull_off(a.rtol, a.seed, a.scenes, out=lambda s: print(s, flush=True))
        if a.json:
            with open(a.json, "w") as f:
                json.dump(rows, f, indent=1)
        return
    res = run(a.rtol, a.seed, a.scenes, a.check, a.repeat, out=lambda s: print(s, flush=True))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(res, f, indent=1)


if __name__ == "__main__":
    main()
