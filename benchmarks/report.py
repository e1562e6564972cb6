"""The speed-versus-error report of every solution method.

Usage::

    python -m benchmarks.report            # the full report (a few minutes)
    python -m benchmarks.report --quick    # a small version (smoke test, ~1 minute)

For every method of :data:`persson_fast.METHODS` and a ladder of resolutions (``level``: each
level halves the node spacing and the step), on three scenes:

* ``images`` -- no adhesion, a wall at rest: exact (method of images);
* ``moving-wall`` -- a wall receding linearly in G: exact (Buonocore et al. 1987 closed form);
* ``seed-adhesive`` -- the seed's PMMA lens with Delta gamma = 0.06 J/m^2: reference the
  converged fixed point at the finest tolerance, with its own error estimate;

it measures the error and the time per pressure (one thread), the ratio to the NumPy/SciPy
Crank-Nicolson baseline at equal error (:func:`persson_fast._reference.diffusion.cn_baseline`, same
run), the convergence order, the cheapest method per tolerance (what ``method="auto"``
should take), the thread scaling of a 1000-pressure sweep, the compile time cold and cached,
and the cost per pressure x node x step. It writes ``benchmarks/RESULTS.md``,
``benchmarks/results.json`` and ``benchmarks/pareto.png`` (or into ``--out``).
"""
from __future__ import annotations

import argparse
import datetime
import json
import math
import os
import platform
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numba
import numpy as np
import scipy

import persson_fast as pf
from persson_fast._reference.diffusion import cn_baseline
from persson_fast.methods import AUTO_POLICY, METHODS

HERE = Path(__file__).resolve().parent
MPA = 1e6

#: the exact scenes: diffusion times [Pa^2] (five decades), pressures [Pa], wall a + b G
G_EXACT = np.r_[0.0, np.geomspace(1e-3, 1e2, 11)] * MPA**2
PRESSURES_EXACT = np.array([0.3, 1.0, 3.0]) * MPA
WALLS = {"images": (0.0, 0.0), "moving-wall": (0.5 * MPA, 0.05 / MPA)}
#: the adhesive scene
SEED_PRESSURES = np.array([0.0, 1e7, 1e8])
#: tolerances of the "auto" table
RTOLS = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8)
RTOLS_ADHESIVE = {"cn": (1e-2, 1e-3, 1e-4, 1e-5, 1e-6), "cn-plain": (1e-2, 1e-3, 1e-4, 1e-5),
                  "implicit-euler": (1e-2, 1e-3)}


def compiled_methods():
    """The registered one-wall methods with a compiled kernel (everything but analytic, auto
    and the two-wall "strip", which needs a yield wall: benchmarks/bench_yield.py)."""
    return [m for m, info in METHODS.items()
            if info["family"] not in (None, "closed-form") and not info.get("two_walls")]


def warm_methods():
    """One tiny solve per compiled method, so that no timed call includes compilation."""
    G = np.array([0.0, 1.0, 2.0])
    for method in compiled_methods():
        pf.solve_diffusion(G, 1.0, np.array([0.0, 0.1, 0.3]), method=method, rtol=1e-2,
                           parallel=False)


def timed(func, min_total=0.2, max_repeat=7):
    """(median seconds, result) of repeated calls: at least 3 (or one call > min_total)."""
    times = []
    result = None
    t_all = time.perf_counter()
    while len(times) < max_repeat:
        t0 = time.perf_counter()
        result = func()
        times.append(time.perf_counter() - t0)
        if len(times) >= 3 and time.perf_counter() - t_all > min_total:
            break
        if times[0] > min_total:
            break
    return statistics.median(times), result


def exact_area(scene):
    a, b = WALLS[scene]
    p = PRESSURES_EXACT[:, None]
    if a == 0.0 and b == 0.0:
        return pf.images_area(p, G_EXACT[None, :])
    return pf.linear_boundary_area(p, G_EXACT[None, :], a, b)


def wall(scene):
    a, b = WALLS[scene]
    return a + b * G_EXACT


def rel_error(area, ref):
    return float(np.max(np.abs(area - ref) / ref))


def run_exact_scene(scene, levels, baseline_nodes, log):
    """Rows (method, resolution, error, time per pressure, work) of one exact scene."""
    ref = exact_area(scene)
    sa = wall(scene)
    n_p = PRESSURES_EXACT.size
    rows = []
    for method in compiled_methods():
        for level in range(levels[method] + 1):
            def call(level=level, method=method):
                return pf.solve_diffusion(G_EXACT, PRESSURES_EXACT, sa, method=method,
                                          level=level, parallel=False)
            t, res = timed(call)
            counts = res.counts.mean(axis=0)
            rows.append({"scene": scene, "method": method, "resolution": f"level {level}",
                         "level": level, "error": rel_error(res.area, ref),
                         "time": t / n_p, "nodes": float(counts[0]), "steps": float(counts[1]),
                         "node_steps": float(counts[2]), "status": int(res.status.max())})
        log(f"  {scene}: {method} done")
    for n in baseline_nodes:
        spd = n / 8.0

        def call(n=n, spd=spd):
            return np.array([cn_baseline(G_EXACT, sa, p, n, spd) for p in PRESSURES_EXACT])
        t, area = timed(call, min_total=0.5, max_repeat=3)
        rows.append({"scene": scene, "method": "baseline", "resolution": f"N = {n}",
                     "level": int(round(math.log2(n / baseline_nodes[0]))),
                     "error": rel_error(area, ref), "time": t / n_p, "nodes": float(n),
                     "steps": float(spd * math.log10(G_EXACT[-1] / G_EXACT[1])),
                     "node_steps": float("nan"), "status": 0})
    log(f"  {scene}: baseline done")
    return rows


def run_adhesive_scene(rtols, ref_rtol, log):
    """Rows of the seed's adhesive scene (each grid method over a tolerance ladder)."""
    surface = pf.seed_scene()
    kw = dict(e_star=pf.seed_e_star(), work_of_adhesion=pf.SEED_WORK_OF_ADHESION,
              parallel=False)
    t0 = time.perf_counter()
    ref = pf.solve_contact(surface, SEED_PRESSURES, method="cn", rtol=ref_rtol, **kw)
    ref2 = pf.solve_contact(surface, SEED_PRESSURES, method="cn", rtol=10 * ref_rtol, **kw)
    ref_err = float(np.max(np.abs(ref.area - ref2.area) / ref.area))
    log(f"  seed-adhesive: reference at rtol {ref_rtol:g} in {time.perf_counter() - t0:.1f} s")
    rows = []
    n_p = SEED_PRESSURES.size
    for method in compiled_methods():
        if not METHODS[method]["adhesion"]:
            rows.append({"scene": "seed-adhesive", "method": method, "resolution": "-",
                         "level": -1, "error": float("nan"), "time": float("nan"),
                         "nodes": float("nan"), "steps": float("nan"),
                         "node_steps": float("nan"), "status": -1,
                         "note": "cannot serve adhesion"})
            continue
        for rtol in rtols.get(method, ()):
            def call(rtol=rtol, method=method):
                return pf.solve_contact(surface, SEED_PRESSURES, method=method, rtol=rtol, **kw)
            t, res = timed(call, min_total=0.5, max_repeat=3)
            rows.append({"scene": "seed-adhesive", "method": method,
                         "resolution": f"rtol {rtol:g}", "level": -1, "rtol": rtol,
                         "error": rel_error(res.area, ref.area), "time": t / n_p,
                         "nodes": float("nan"), "steps": float("nan"),
                         "node_steps": float("nan"), "status": int(res.status.max()),
                         "iterations": float(res.iterations.mean())})
        log(f"  seed-adhesive: {method} done")
    return rows, {"reference_rtol": ref_rtol, "reference_error_estimate": ref_err,
                  "reference_area": ref.area.tolist()}


def measured_orders(rows):
    """Per (scene, method): log2 of successive error ratios over the ladder, and a summary
    (median of the last three ratios with errors above 1e-12)."""
    out = {}
    keys = sorted({(r["scene"], r["method"]) for r in rows if r["level"] >= 0})
    for key in keys:
        ladder = sorted((r for r in rows if (r["scene"], r["method"]) == key and r["level"] >= 0),
                        key=lambda r: r["level"])
        ratios = []
        for a, b in zip(ladder[:-1], ladder[1:]):
            if a["error"] > 1e-12 and b["error"] > 1e-12 and b["level"] > a["level"]:
                ratios.append(math.log2(a["error"] / b["error"]) / (b["level"] - a["level"]))
            else:
                ratios.append(float("nan"))
        for r, o in zip(ladder[1:], ratios):
            r["order"] = o
        finite = [o for o in ratios if math.isfinite(o)]
        out[key] = statistics.median(finite[-3:]) if finite else float("nan")
    return out


def baseline_ratio(rows):
    """Speed ratios to the baseline at equal or better error (conservative both ways).

    Each method row gets ``baseline_ratio`` = time of the cheapest baseline run at least as
    accurate / the row's time (None when no baseline run is that accurate). Returns, per
    scene, for each baseline run the cheapest ``cn`` run at least as accurate and the ratio
    of their times.
    """
    summary = []
    for scene in sorted({r["scene"] for r in rows}):
        base = [r for r in rows if r["scene"] == scene and r["method"] == "baseline"]
        cn = [r for r in rows if r["scene"] == scene and r["method"] == "cn"
              and math.isfinite(r["error"])]
        for r in rows:
            if r["scene"] != scene or r["method"] == "baseline" or not math.isfinite(r["error"]):
                continue
            better = [b["time"] for b in base if b["error"] <= r["error"]]
            r["baseline_ratio"] = min(better) / r["time"] if better else None
        for b in base:
            better = [c for c in cn if c["error"] <= b["error"]]
            if better:
                c = min(better, key=lambda c: c["time"])
                summary.append({"scene": scene, "baseline": b["resolution"],
                                "baseline_error": b["error"], "baseline_time": b["time"],
                                "cn": c["resolution"], "cn_error": c["error"],
                                "cn_time": c["time"], "ratio": b["time"] / c["time"]})
    return summary


def auto_table(rows_by_rtol):
    """Per scene and tolerance: the cheapest method whose error met rtol."""
    table = {}
    for (scene, rtol), cands in rows_by_rtol.items():
        ok = [r for r in cands if math.isfinite(r["error"]) and r["error"] <= rtol
              and r["status"] in (0, 8)]
        best = min(ok, key=lambda r: r["time"]) if ok else None
        table[(scene, rtol)] = best["method"] if best else None
    return table


def run_rtol_ladder(scene, rtols, log):
    """Every compiled method at each tolerance on an exact scene (for the auto table)."""
    ref = exact_area(scene)
    sa = wall(scene)
    out = {}
    for rtol in rtols:
        cands = []
        for method in compiled_methods():
            def call(method=method, rtol=rtol):
                return pf.solve_diffusion(G_EXACT, PRESSURES_EXACT, sa, method=method,
                                          rtol=rtol, parallel=False)
            t, res = timed(call, min_total=0.1, max_repeat=3)
            cands.append({"method": method, "error": rel_error(res.area, ref),
                          "time": t / PRESSURES_EXACT.size, "status": int(res.status.max())})
        out[(scene, rtol)] = cands
    log(f"  auto ladder {scene} done")
    return out


def thread_scaling(n_pressures, log):
    """Seconds of a cn sweep over n_pressures (5-decade self-affine scene) per thread count."""
    surface = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    e_star = 1e9
    g1 = e_star * surface.slope_rms() / (2 * math.sqrt(2))
    p = np.geomspace(1e-3, 3.0, n_pressures) * g1
    out = []
    n_max = numba.config.NUMBA_NUM_THREADS
    pf.warmup()
    for t in range(1, n_max + 1):
        numba.set_num_threads(t)
        sec, _ = timed(lambda: pf.solve_contact(surface, p, e_star=e_star, method="cn",
                                                parallel=True), min_total=1.0, max_repeat=5)
        out.append({"threads": t, "seconds": sec})
    numba.set_num_threads(n_max)
    for r in out:
        r["speedup"] = out[0]["seconds"] / r["seconds"]
    log("  thread scaling done")
    return out


def compile_times(log):
    from benchmarks.compile_time import measure

    cache = tempfile.mkdtemp(prefix="persson_fast_report_cache_")
    cold = measure(cache)
    cached = measure(cache)
    log("  compile time done")
    return {"cold": cold, "cached": cached}


def fmt(x, spec=".2e"):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "-"
    return format(x, spec)


def write_png(rows, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    scenes = ["images", "moving-wall", "seed-adhesive"]
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    methods = compiled_methods() + ["baseline"]
    for ax, scene in zip(axes, scenes):
        for m in methods:
            pts = sorted(((r["time"], r["error"]) for r in rows
                          if r["scene"] == scene and r["method"] == m
                          and math.isfinite(r["error"]) and r["error"] > 0), key=lambda x: x[0])
            if pts:
                ax.loglog([1e3 * t for t, _ in pts], [e for _, e in pts],
                          marker="o", label=m, ms=4, ls="--" if m == "baseline" else "-")
        ax.set_title(scene)
        ax.set_xlabel("time per pressure [ms], one thread")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("max relative error of A")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def cpu_model() -> str:
    """The processor's model name (Linux /proc/cpuinfo), else platform.processor()."""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown processor"


def random_adhesive(rtols, n_scenes, log):
    """The random self-affine adhesive scenes (:mod:`benchmarks.adhesive_scenes`) at each
    rtol, each checked against the same solve at rtol/100: the summary per rtol."""
    from benchmarks.adhesive_scenes import run

    out = []
    for rtol in rtols:
        res = run(rtol, seed=1, n=n_scenes, check=True, out=lambda _: None)
        s = res["summary"]
        s.update(rtol=rtol, seed_ms_per_pressure=res["seed_ms_per_pressure"])
        out.append(s)
        log(f"random adhesive scenes at rtol {rtol:g}: median {s['median']:.2f} ms, "
            f"90th percentile {s['p90']:.2f} ms, misses {s['misses']}, flags {s['flags']}")
    return out


def write_markdown(path, meta, rows, orders, auto, scaling, compile_t, adhesive_ref, versus,
                   random_rows=()):
    L = []
    L.append("# Speed versus error of the persson_fast methods\n")
    L.append(f"Generated by `{meta['command']}` in {meta['seconds']:.0f} s on {meta['date']}.\n")
    L.append(f"Machine: {meta['cpu']}, {meta['machine']}; {meta['cpus']} CPUs; Python {meta['python']}, "
             f"numpy {meta['numpy']}, scipy {meta['scipy']}, numba {meta['numba']}. "
             "Times are medians of repeated calls on one thread (`parallel=False`), per "
             "pressure; absolute times on a small shared machine are noisy, ratios measured "
             "in the same run are not.\n")
    L.append("Error: the largest relative error of A over the pressures "
             f"({', '.join(f'{p / MPA:g}' for p in PRESSURES_EXACT)} MPa) and the 11 diffusion "
             "times G = 1e-3 ... 1e2 MPa^2 of the exact scenes; over the pressures "
             f"{', '.join(f'{p / MPA:g}' for p in SEED_PRESSURES)} MPa for the adhesive scene. "
             "Ratio: time of the cheapest NumPy/SciPy Crank-Nicolson baseline run that is at "
             "least as accurate / the method's time; '-' where no baseline run is that "
             "accurate. Order: log2 of the error ratio of successive levels (each "
             "level halves node spacing and step).\n")
    L.append("![Pareto front](pareto.png)\n")
    for scene in ("images", "moving-wall", "seed-adhesive"):
        L.append(f"## {scene}\n")
        if scene == "seed-adhesive":
            L.append(f"Reference: `cn` at rtol {adhesive_ref['reference_rtol']:g}, areas "
                     f"{', '.join(f'{a:.10f}' for a in adhesive_ref['reference_area'])}; its "
                     f"error estimate (difference to rtol "
                     f"{10 * adhesive_ref['reference_rtol']:g}): "
                     f"{adhesive_ref['reference_error_estimate']:.1e}. The ladder is the "
                     "tolerance (it sets the magnification grid and the inner resolution).\n")
        L.append("| method | resolution | nodes | steps | error | time/pressure [ms] "
                 "| ratio to baseline | order | ns per node-step (bnr: per kernel evaluation) | status |")
        L.append("|---|---|---|---|---|---|---|---|---|---|")
        for r in rows:
            if r["scene"] != scene:
                continue
            ns = (1e9 * r["time"] / r["node_steps"]
                  if math.isfinite(r.get("node_steps", float("nan"))) and r["node_steps"] > 0
                  else None)
            status = r.get("note", str(r["status"]))
            L.append(f"| {r['method']} | {r['resolution']} | {fmt(r['nodes'], '.0f')} "
                     f"| {fmt(r['steps'], '.0f')} | {fmt(r['error'])} "
                     f"| {fmt(1e3 * r['time'], '.3g')} | {fmt(r.get('baseline_ratio'), '.0f')} "
                     f"| {fmt(r.get('order'), '.2f')} | {fmt(ns, '.1f')} | {status} |")
        L.append("")
    L.append("## cn against the NumPy/SciPy baseline at equal or better error\n")
    L.append("For every baseline run, the cheapest `cn` run at least as accurate (same run, one "
             "thread; the ratio is a lower bound of the speed-up at equal error).\n")
    L.append("| scene | baseline | baseline error | baseline ms | cn | cn error | cn ms | ratio |")
    L.append("|---|---|---|---|---|---|---|---|")
    for v in versus:
        L.append(f"| {v['scene']} | {v['baseline']} | {v['baseline_error']:.2e} | "
                 f"{1e3 * v['baseline_time']:.3g} | {v['cn']} | {v['cn_error']:.2e} | "
                 f"{1e3 * v['cn_time']:.3g} | {v['ratio']:.0f} |")
    L.append("")
    L.append("## Measured convergence order\n")
    L.append("| scene | method | theoretical | measured (median of the last three levels) |")
    L.append("|---|---|---|---|")
    for (scene, method), o in orders.items():
        theo = METHODS[method]["order"] if method in METHODS else 2
        L.append(f"| {scene} | {method} | {theo} | {fmt(o, '.2f')} |")
    L.append("")
    L.append("## auto: the cheapest method that met rtol\n")
    L.append("| scene | " + " | ".join(f"rtol {r:g}" for r in RTOLS) + " |")
    L.append("|---|" + "---|" * len(RTOLS))
    for scene in ("images", "moving-wall", "seed-adhesive"):
        cells = [auto.get((scene, r)) or "-" for r in RTOLS]
        L.append(f"| {scene} | " + " | ".join(cells) + " |")
    L.append("")
    disagree = []
    for scene, kind in (("images", "smooth"), ("moving-wall", "smooth"),
                        ("seed-adhesive", "adhesion")):
        for r in RTOLS:
            best = auto.get((scene, r))
            if best is not None and best != AUTO_POLICY[kind][0]:
                disagree.append(f"{scene} at rtol {r:g}: measured {best}, policy "
                                f"{AUTO_POLICY[kind][0]}")
    L.append("Check of the policy against these measurements: "
             + ("it agrees at every tolerance where a method met it.\n" if not disagree
                else "DISAGREES: " + "; ".join(disagree) + ".\n"))
    L.append("`method=\"auto\"` follows `persson_fast.methods.AUTO_POLICY`: "
             + "; ".join(f"{k}: {', '.join(v)}" for k, v in AUTO_POLICY.items())
             + " (a linear wall has a closed form; the table above compares the compiled "
             "methods).\n")
    if random_rows:
        L.append("## Random self-affine adhesive scenes\n")
        L.append("The scenes of `python -m benchmarks.adhesive_scenes` (seed 1: H 0.6-0.9, q0 "
                 "10^3.5-10^5.5 1/m, 2.5-5 decades, h_rms 10 nm-1 um, E* 3 MPa-10 GPa, "
                 "Delta gamma 3 mJ/m^2-0.3 J/m^2, each at p = 0, 0.3, 1, 3 sqrt(G1)), one thread, "
                 "time per pressure of each scene; errors against the same solve at rtol/100. "
                 "The seed scene (101 pressures 0-100 MPa) in the same run for scale.\n")
        L.append("| rtol | scenes | median [ms] | 90th percentile [ms] | slowest tenth [ms] | "
                 "worst [ms] | seed scene [ms] | 90th pct / seed | silent misses | worst "
                 "error [rtol] | flagged (within rtol) | estimate / error |")
        L.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
        for r in random_rows:
            ratio = r.get("estimate_over_error")
            ratio = "-" if not ratio else f"{ratio[0]:.2f} - {ratio[1]:.2f}"
            L.append(f"| {r['rtol']:g} | {r['n']} | {r['median']:.2f} | {r['p90']:.2f} | "
                     f"{r['slowest_tenth']:.2f} | {r['worst']:.2f} | "
                     f"{r['seed_ms_per_pressure']:.2f} | {r['p90_over_seed']:.2f} | "
                     f"{r['misses']} | {r['worst_error_over_tol']:.3f} | "
                     f"{r['flags']} ({r['flags_within']}) | {ratio} |")
        L.append("")
    if scaling:
        L.append("## Thread scaling\n")
        L.append("`cn` sweep of the 5-decade self-affine scene, "
                 f"{meta['scaling_pressures']} pressures, `parallel=True`:\n")
        L.append("| threads | seconds | speed-up |")
        L.append("|---|---|---|")
        for r in scaling:
            L.append(f"| {r['threads']} | {r['seconds']:.3f} | {r['speedup']:.2f} |")
        L.append("")
    if compile_t:
        L.append("## Compile time\n")
        L.append("Fresh processes sharing one empty numba cache folder (`benchmarks/compile_time.py`): "
                 "import, `warmup()` (sweep and adhesive kernels), then a first "
                 "128-pressure `cn` call.\n")
        L.append("| run | import [s] | warmup serial [s] | warmup adhesion [s] | first call [s] | process [s] |")
        L.append("|---|---|---|---|---|---|")
        for name in ("cold", "cached"):
            c = compile_t[name]
            L.append(f"| {name} | {c['import']:.2f} | {c['warmup_serial']:.2f} | "
                     f"{c['warmup_adhesion']:.2f} | {c['first_cn']:.2f} | {c['process']:.1f} |")
        L.append("")
    path.write_text("\n".join(L))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m benchmarks.report",
                                     description="Speed versus error of every method.")
    parser.add_argument("--quick", action="store_true",
                        help="short ladders, no compile-time or thread-scaling runs")
    parser.add_argument("--out", default=str(HERE), help="output folder (default: benchmarks/)")
    args = parser.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    t_start = time.perf_counter()

    def log(msg):
        print(f"[{time.perf_counter() - t_start:6.1f} s] {msg}", flush=True)

    pf.warmup(prange=not args.quick)
    warm_methods()
    full = not args.quick
    # ladders up to each method's work cap (cn 6: ~3e-11, fixed-grid 5 and implicit-euler 6:
    # about a second per pressure)
    top = {"cn": 6, "cn-plain": 6, "implicit-euler": 6, "fixed-grid": 5, "bnr": 5}
    levels = {m: (top.get(m, 4) if full else 2) for m in compiled_methods()}
    baseline_nodes = [100, 200, 400, 800, 1600, 3200] if full else [100, 200, 400]
    rows = []
    for scene in ("images", "moving-wall"):
        rows += run_exact_scene(scene, levels, baseline_nodes, log)
    quick_adh = {"cn": (1e-3, 1e-4), "cn-plain": (1e-3,), "implicit-euler": (1e-2,)}
    adh_rows, adh_ref = run_adhesive_scene(RTOLS_ADHESIVE if full else quick_adh,
                                           1e-8 if full else 1e-5, log)
    rows += adh_rows
    orders = measured_orders(rows)
    versus = baseline_ratio(rows)
    by_rtol = {}
    for scene in ("images", "moving-wall"):
        by_rtol.update(run_rtol_ladder(scene, RTOLS if full else (1e-3, 1e-5), log))
    for r in adh_rows:
        if r.get("rtol") is not None:
            by_rtol.setdefault(("seed-adhesive", r["rtol"]), []).append(r)
    auto = auto_table(by_rtol)
    random_rows = random_adhesive((1e-4, 1e-5) if full else (1e-4,), 40 if full else 8, log)
    scaling = thread_scaling(1000, log) if full else []
    compile_t = compile_times(log) if full else {}
    seconds = time.perf_counter() - t_start
    meta = {
        "command": "python -m benchmarks.report" + (" --quick" if args.quick else ""),
        "seconds": seconds,
        "date": datetime.datetime.now().astimezone().isoformat(timespec="seconds"),
        "machine": f"{platform.platform()} ({platform.machine()})", "cpu": cpu_model(),
        "cpus": os.cpu_count(), "python": platform.python_version(),
        "numpy": np.__version__, "scipy": scipy.__version__, "numba": numba.__version__,
        "scaling_pressures": 1000,
    }
    write_png(rows, out / "pareto.png")
    write_markdown(out / "RESULTS.md", meta, rows, orders, auto, scaling, compile_t, adh_ref,
                   versus, random_rows)
    (out / "results.json").write_text(json.dumps({
        "meta": meta, "rows": rows,
        "orders": [{"scene": s, "method": m, "order": o} for (s, m), o in orders.items()],
        "auto": [{"scene": s, "rtol": r, "method": m} for (s, r), m in auto.items()],
        "cn_versus_baseline": versus, "thread_scaling": scaling, "compile_time": compile_t,
        "adhesive_reference": adh_ref, "random_adhesive": random_rows,
    }, indent=1, default=float))
    log(f"wrote {out / 'RESULTS.md'}, results.json, pareto.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
