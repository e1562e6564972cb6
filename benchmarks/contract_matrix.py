"""The accuracy-contract matrix: every compiled method x wall x rtol, against references.

Usage::

    python -m benchmarks.contract_matrix            # the full matrix (a few minutes)
    python -m benchmarks.contract_matrix --quick    # rtol 1e-3 and 1e-6 only

For each method of :data:`persson_fast.METHODS` that solves a prescribed wall, each scene and
each rtol it reports: ``error/rtol`` = max over the returned G of |A - A_ref| / (rtol A_ref +
1e-12); ``est/actual`` = error_estimate / |A - A_ref| at the last G ("-" where the actual
error is below 1e-13 A_ref: rounding); the status; and the verdict -- "ok" (within rtol,
status 0), "flagged" (status != 0) or "MISS" (outside rtol with status 0: the contract
broken). A method that cannot serve a scene (a ValueError before any solve) is "n/a". A second
table does the same for the adhesive fixed point of a self-affine scene whose gamma_eff
changes sign (square-root onset of sigma_a). Writes ``benchmarks/CONTRACT_MATRIX.md``
(atomically) or into ``--out``.

References: the closed forms (images, linearly moving walls); ``bnr`` at rtol 1e-11 on the
samples for the sampled walls (checked against ``cn`` at rtol 1e-10, agreement printed in the
header); for the callable wall ``cn`` at rtol 1e-10 on dense samples extrapolated in their
number (:func:`callable_reference`); the adhesive scene the 160-per-decade reference of
``tests/test_adhesive_error_control.py``.
"""
from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import persson_fast as pf

HERE = Path(__file__).resolve().parent
RTOLS = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8)
METHOD_NAMES = ("cn", "cn-plain", "implicit-euler", "fixed-grid", "bnr")

G_SMOOTH = np.concatenate([[0.0], np.geomspace(1e-4, 1e3, 36)])
G_SQRT = np.concatenate([[0.0], np.geomspace(1e-6, 1e2, 200)])
G_KINK = np.array([0.0, 0.5, 1.0, 4.0 / 3.0, 2.0])
G_FAST = np.array([0.0, 1e4, 1e11])
G_JUMP = np.array([0.0, 0.3, 0.6, 0.6, 1.0, 2.0])
SA_JUMP = np.array([0.2, 0.2, 0.2, 0.35, 0.35, 0.35])
#: the adhesive scene of tests/test_adhesive_error_control.py and its reference
SA_SCENE = dict(hurst=0.8, q0=1e4, q1=1e9, C0=1e-22)
SA_PRESSURES = np.array([1e5, 1e6, 1e7])
SA_REFERENCE = np.array([0.023332581259, 0.229924055933, 0.990857611202])
SA_REFERENCE_ERR = np.array([6.3e-8, 5.2e-7, 2.0e-8])


def sqrt_wall(G):
    return 0.1 + 0.5 * np.sqrt(G)


def callable_reference():
    """A_ref of the square-root wall as a function, at G_SQRT: cn at rtol 1e-10 on dense
    geometric samples nested with G_SQRT (m = 80 and 160 per interval), extrapolated in the
    sample count, (4 A_2m - A_m)/3: the piecewise-linear error of a geometric grid is
    c m^-2 + O(m^-4). (bnr cannot serve here: that many samples exceed its node cap, and it
    thins them -- status 16 -- which left a reference 1e-7 off.)"""
    areas = []
    for m in (80, 160):
        dense = np.concatenate([[0.0], np.geomspace(G_SQRT[1], G_SQRT[-1], 199 * m + 1)])
        at = np.concatenate([[0], 1 + np.arange(0, 199 * m + 1, m)])
        r = pf.solve_diffusion(dense, 1.0, sqrt_wall(dense), method="cn", rtol=1e-10,
                               parallel=False)
        areas.append(r.area[0][at])
    return (4.0 * areas[1] - areas[0]) / 3.0


def scenes():
    """name -> (G, sigma0, sigma_a (samples or callable), reference area on G, how)."""
    out = {}
    out["images"] = (G_SMOOTH, 1.0, np.zeros_like(G_SMOOTH), pf.images_area(1.0, G_SMOOTH),
                     "closed form")
    out["wall receding"] = (G_SMOOTH, 1.0, 0.2 + 0.5 * G_SMOOTH,
                            pf.linear_boundary_area(1.0, G_SMOOTH, 0.2, 0.5), "closed form")
    out["wall approaching"] = (G_SMOOTH, 1.0, 0.5 - 0.3 * G_SMOOTH,
                               pf.linear_boundary_area(1.0, G_SMOOTH, 0.5, -0.3), "closed form")
    out["fast wall (b y0 = -30)"] = (G_FAST, 8e5, 2e5 - 3e-5 * G_FAST,
                                     pf.linear_boundary_area(8e5, G_FAST, 2e5, -3e-5),
                                     "closed form")
    ref_s = pf.solve_diffusion(G_SQRT, 1.0, sqrt_wall(G_SQRT), method="bnr", rtol=1e-11).area[0]
    out["0.1 + 0.5 sqrt(G), 200 samples"] = (G_SQRT, 1.0, sqrt_wall(G_SQRT), ref_s,
                                             "bnr 1e-11 on the samples")
    out["0.1 + 0.5 sqrt(G), callable"] = (G_SQRT, 1.0, sqrt_wall, callable_reference(),
                                          "cn 1e-10 on 80 and 160 geometric samples per "
                                          "sample interval, extrapolated in their number")
    kink = np.maximum(0.0, 0.4 - 0.3 * G_KINK)
    ref_k = pf.solve_diffusion(G_KINK, 0.1, kink, method="bnr", rtol=1e-11).area[0]
    out["kinked max(0, 0.4 - 0.3 G)"] = (G_KINK, 0.1, kink, ref_k, "bnr 1e-11")
    ref_j = pf.solve_diffusion(G_JUMP, 0.5, SA_JUMP, method="cn", rtol=1e-10).area[0]
    out["jump (flat G)"] = (G_JUMP, 0.5, SA_JUMP, ref_j, "cn 1e-10 (bnr serves no jumps)")
    return out


def verdict(err_over_rtol: float, status: int) -> str:
    """"ok", "flagged" or "MISS" of one result (see the module docstring)."""
    if not np.isfinite(err_over_rtol):
        return "MISS" if status == 0 else "flagged"
    if status != 0:
        return "flagged"
    return "ok" if err_over_rtol <= 1.0 else "MISS"


def row(method, G, sigma0, sa, ref, rtol, repeats=3):
    """(error/rtol, est/actual or None, status, verdict, seconds) of one solve."""
    try:
        r = pf.solve_diffusion(G, sigma0, sa, method=method, rtol=rtol)
    except ValueError:
        return None
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        pf.solve_diffusion(G, sigma0, sa, method=method, rtol=rtol, parallel=False)
        times.append(time.perf_counter() - t0)
    a = r.area[0]
    if not np.all(np.isfinite(a)):
        return (np.inf, None, int(r.status[0]), verdict(np.inf, int(r.status[0])),
                statistics.median(times))
    e = float(np.max(np.abs(a - ref) / (rtol * ref + 1e-12)))
    actual = abs(a[-1] - ref[-1])
    ratio = r.error_estimate[0, -1] / actual if actual > 1e-13 * ref[-1] else None
    s = int(r.status[0])
    return e, ratio, s, verdict(e, s), statistics.median(times)


def adhesive_rows(rtols):
    S = pf.SelfAffine(**SA_SCENE)
    out = []
    for rtol in rtols:
        t0 = time.perf_counter()
        r = pf.solve_contact(S, SA_PRESSURES, e_star=1e9, work_of_adhesion=0.05, rtol=rtol,
                             parallel=False)
        sec = (time.perf_counter() - t0) / SA_PRESSURES.size
        for k, p in enumerate(SA_PRESSURES):
            err = abs(r.area[k] - SA_REFERENCE[k])
            e = err / (rtol * SA_REFERENCE[k] + 1e-12)
            ratio = r.error_estimate[k] / err if err > 3 * SA_REFERENCE_ERR[k] else None
            s = int(r.status[k])
            out.append((rtol, p, e, ratio, s, verdict(e, s), sec))
    return out


def _fmt(x, spec=".2g"):
    return "-" if x is None else format(x, spec)


def write_atomic(path: Path, text: str) -> None:
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name, suffix=".tmp")
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out", default=str(HERE))
    args = ap.parse_args(argv)
    rtols = (1e-3, 1e-6) if args.quick else RTOLS
    t_start = time.perf_counter()
    pf.warmup()
    sc = scenes()
    # the sampled references against cn at 1e-10
    agree = {}
    for name in ("0.1 + 0.5 sqrt(G), 200 samples", "kinked max(0, 0.4 - 0.3 G)"):
        G, s0, sa, ref, _ = sc[name]
        c = pf.solve_diffusion(G, s0, sa, method="cn", rtol=1e-10).area[0]
        agree[name] = float(np.max(np.abs(c - ref) / ref))
    lines = ["# The accuracy contract, measured", "",
             f"`python -m benchmarks.contract_matrix{' --quick' if args.quick else ''}`; "
             f"persson_fast {pf.__version__}, Python {sys.version.split()[0]}, one thread, "
             "times are medians of 3 solves.", "",
             "Verdict: ok = within rtol (|A - A_ref| <= rtol A_ref + 1e-12 at every returned G) "
             "with status 0; flagged = status != 0 (the result says it is not within rtol); "
             "MISS = outside rtol with status 0 (the contract broken); n/a = the method refuses "
             "the scene with a ValueError.", "",
             "References: " + "; ".join(f"{n}: {v[4]}" for n, v in sc.items()) + ". "
             + "Sampled references against cn at rtol 1e-10: "
             + ", ".join(f"{n} {v:.1e}" for n, v in agree.items()) + " (max relative).", "",
             "| method | scene | rtol | error/rtol | est/actual | status | verdict | time [ms] |",
             "|---|---|---|---|---|---|---|---|"]
    counts = {"ok": 0, "flagged": 0, "MISS": 0, "n/a": 0}
    misses = []
    for method in METHOD_NAMES:
        for name, (G, s0, sa, ref, _) in sc.items():
            for rtol in rtols:
                res = row(method, G, s0, sa, ref, rtol)
                if res is None:
                    counts["n/a"] += 1
                    lines.append(f"| {method} | {name} | {rtol:g} | - | - | - | n/a | - |")
                    continue
                e, ratio, s, v, sec = res
                counts[v] += 1
                if v == "MISS":
                    misses.append(f"{method}, {name}, rtol {rtol:g}: error {e:.3g} rtol, "
                                  f"estimate/actual {_fmt(ratio)}")
                lines.append(f"| {method} | {name} | {rtol:g} | {e:.2g} | {_fmt(ratio)} | {s} | "
                             f"{v} | {sec * 1e3:.3g} |")
    lines += ["", "## The adhesive fixed point (self-affine scene, H = 0.8, q1/q0 = 1e5, "
              "Delta gamma = 0.05 J/m^2, E* = 1 GPa; gamma_eff changes sign)", "",
              "| rtol | p [Pa] | error/rtol | est/actual | status | verdict | time per pressure [s] |",
              "|---|---|---|---|---|---|---|"]
    for rtol, p, e, ratio, s, v, sec in adhesive_rows(rtols if args.quick else (1e-3, 1e-4, 1e-5)):
        counts[v] += 1
        if v == "MISS":
            misses.append(f"adhesive, p = {p:g} Pa, rtol {rtol:g}: error {e:.3g} rtol")
        lines.append(f"| {rtol:g} | {p:g} | {e:.2g} | {_fmt(ratio)} | {s} | {v} | {sec:.3g} |")
    summary = (f"ok {counts['ok']}, flagged {counts['flagged']}, MISS {counts['MISS']}, "
               f"n/a {counts['n/a']}; {time.perf_counter() - t_start:.0f} s in all")
    lines += ["", f"Summary: {summary}.", ""]
    if misses:
        lines += ["Every MISS:", ""] + [f"- {m}" for m in misses] + [""]
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    write_atomic(out / "CONTRACT_MATRIX.md", "\n".join(lines))
    print(summary)
    for m in misses:
        print("MISS:", m)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
