"""Issue 41 prototype: the forward march + scalar root in K against today's fixed point.

CPU time (time.process_time), one thread, per pressure; errors of A(zeta1)/A0 against a
reference (today's solver at a tight rtol, cross-checked with the march at a fine resolution).
Usage: NUMBA_NUM_THREADS=1 python -m benchmarks.march_prototype [--out results.json]

Measured side by side in one run (AMD EPYC, 2 shared cores, NUMBA_NUM_THREADS=1,
time.process_time per pressure; march at the calibrated mapping of commit 5d1d141, today =
pf.solve_contact, parallel=False; "diff" = max |march - today| / A at the same rtol;
random scenes: benchmarks.adhesive_scenes seed 1, the first three, its pressures):

| scene                     | rtol 1e-4 today / march (x) | diff   | rtol 1e-6 today / march (x) | diff   | onset |
|---------------------------|-----------------------------|--------|-----------------------------|--------|-------|
| self-affine H0.8, 1, 5 MPa| 26.2 / 6.0 ms (4.4x)        | 7.0e-5 | 2056 / 107 ms (19.2x)       | 3.2e-7 | yes   |
| seed, 11 p, 0-100 MPa     | 6.1 / 4.3 ms (1.4x)         | 8.2e-5 | 46.5 / 96.7 ms (0.48x)      | 3.5e-7 | no    |
| random #0                 | 12.6 / 5.6 ms (2.3x)        | 5.1e-5 | 768 / 91 ms (8.4x)          | 3.2e-7 | yes   |
| random #1                 | 10.6 / 3.3 ms (3.2x)        | 8.6e-6 | 118 / 83 ms (1.4x)          | 1.1e-7 | no    |
| random #2                 | 2.6 / 3.5 ms (0.73x)        | 1.9e-4 | 7.7 / 73.9 ms (0.10x)       | 1.4e-9 | no    |

Errors against references (self-affine: the march at 7 levels, extrapolated; seed: today at
rtol 1e-8, agreeing with the fine march to 5e-8): err/rtol self-affine 0.60 / 0.44 / 0.54,
seed 0.89 / 0.18 / 0.24 at rtol 1e-4 / 1e-5 / 1e-6; smallest estimate/error 0.59 / 0.89 /
0.42 (self-affine; 0.42 < 0.5 at 1e-6) and 0.68 / 3.2 / 1.4 (seed). Observed order of the
level differences on the self-affine scene (old mapping, 5 levels): 0.9-1.6 raw, 1.6-1.95
after extrapolation: the post-onset layer is not fixed (no self-similar start yet).
"""
from __future__ import annotations

import argparse
import json
import time

import numpy as np

import persson_fast as pf
from persson_fast.adhesion import march as am


def scenes():
    sa = pf.SelfAffine(hurst=0.8, q0=1e5, q1=1e9, h_rms=1e-7)
    yield ("self-affine H0.8", sa, np.array([1e6, 5e6]), 1e9, 0.05, 1e-7)
    yield ("seed", pf.seed_scene(), np.linspace(0.0, 1e8, 11), pf.seed_e_star(),
           pf.SEED_WORK_OF_ADHESION, 1e-8)


def cpu(f):
    t = time.process_time()
    out = f()
    return out, time.process_time() - t


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default=None)
    args = ap.parse_args()
    # compile both once
    s0 = pf.SelfAffine(hurst=0.8, q0=1e5, q1=1e9, h_rms=1e-7)
    pf.solve_contact(s0, [1e6], e_star=1e9, work_of_adhesion=0.05, rtol=1e-2, parallel=False)
    am.solve_march(s0, [1e6], e_star=1e9, work_of_adhesion=0.05, rtol=1e-4)
    report = {"cpu": open("/proc/cpuinfo").read().split("model name")[1].split("\n")[0]
              .strip(": \t")}
    for name, surf, p, E, dg, ref_rtol in scenes():
        kw = dict(e_star=E, work_of_adhesion=dg)
        ref, t_ref = cpu(lambda: pf.solve_contact(surf, p, rtol=ref_rtol, parallel=False, **kw))
        fine, t_fine = cpu(lambda: am.solve_march(surf, p, rtol=1e-9, levels=4, **kw))
        rows = {"pressure": p.tolist(), "ref_rtol": ref_rtol, "ref_area": ref.area.tolist(),
                "ref_est": ref.error_estimate.tolist(), "ref_status": ref.status.tolist(),
                "ref_cpu_per_p": t_ref / p.size, "march_fine_area": fine["area"].tolist(),
                "march_fine_est": fine["error_estimate"].tolist()}
        print(name, "reference", ref_rtol, ref.area, ref.error_estimate, "march fine",
              fine["area"], fine["error_estimate"], flush=True)
        a_ref = ref.area
        for rtol in (1e-4, 1e-6):
            old, t_old = cpu(lambda: pf.solve_contact(surf, p, rtol=rtol, parallel=False, **kw))
            new, t_new = cpu(lambda: am.solve_march(surf, p, rtol=rtol, **kw))
            ok = a_ref > 0
            e_old = np.abs(old.area - a_ref)[ok] / a_ref[ok]
            e_new = np.abs(new["area"] - a_ref)[ok] / a_ref[ok]
            est_new = new["error_estimate"][ok] / a_ref[ok]
            rows[f"rtol {rtol:g}"] = {
                "today_cpu_per_p": t_old / p.size, "march_cpu_per_p": t_new / p.size,
                "today_err_max": float(e_old.max()), "march_err_max": float(e_new.max()),
                "today_err": e_old.tolist(), "march_err": e_new.tolist(),
                "march_est": est_new.tolist(), "today_status": old.status.tolist(),
                "march_marches": new["marches"].tolist(), "march_order": new["order"].tolist()}
            print(f"{name} rtol {rtol:g}: today {t_old / p.size * 1e3:.1f} ms/p err max "
                  f"{e_old.max():.2e}; march {t_new / p.size * 1e3:.1f} ms/p err max "
                  f"{e_new.max():.2e} (est/A {est_new.min():.1e}..{est_new.max():.1e}, marches "
                  f"per level {new['marches'].mean(axis=1)})", flush=True)
        report[name] = rows
    if args.out:
        with open(args.out, "w") as fh:
            json.dump(report, fh, indent=1)


if __name__ == "__main__":
    main()
