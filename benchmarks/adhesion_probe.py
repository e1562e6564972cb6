"""Random probing of the adhesive accuracy contract: within rtol, or flagged.

    python -m benchmarks.adhesion_probe --seed 1 --seconds 600   # or --scenes N
    python -m benchmarks.adhesion_probe --theory yp08 --hardness  # other fixed points

Draws self-affine scenes (Hurst 0.4-0.95, 1-5 decades, q0 1e4-1e6 1/m, h_rms 3 nm-0.3 um,
E* 1 MPa-10 GPa), a work of adhesion of 1e-3-1 J/m^2, three pressures (a small tension,
zero, a compression of 1e-3-3 sqrt(G1)) and an rtol of 1e-5-1e-3, and solves each with
``solve_contact`` at rtol and at rtol/100 (the reference; rows where it is flagged are left
out). Prints every row that comes back with status 0 but misses |dA| <= rtol A + 1e-12 (by
more than the reference's own tolerance), with its scene, and a summary: rows checked,
misses, rows flagged (status != 0 where the reference is not), the worst error / tolerance
among the unflagged rows. One process, one thread.

``--theory yp08`` or ``wm17`` solves the corrected theories' fixed point instead (sigma_a and
the corrected time together); ``--hardness`` adds a yield wall, a constant hardness drawn
between 1.5x and 30x the compression (the two-wall solver inside the fixed point).
"""
from __future__ import annotations

import argparse
import math
import time
import warnings

import numpy as np

import persson_fast as pf


def draw(rng, hardness=False):
    """One random scene: surface, E*, work of adhesion, pressures, rtol, and its parameters
    (``hardness``: also a constant hardness, 1.5-30x the compression, in the parameters)."""
    hurst, decades, q0 = rng.uniform(0.4, 0.95), rng.uniform(1, 5), 10 ** rng.uniform(4, 6)
    h_rms, e_star = 10 ** rng.uniform(-8.5, -6.5), 10 ** rng.uniform(6, 10)
    surface = pf.SelfAffine(hurst=hurst, q0=q0, q1=q0 * 10 ** decades, h_rms=h_rms)
    root_g1 = math.sqrt(surface.diffusion_time(surface.q1, e_star))
    dgamma = 10 ** rng.uniform(-3, 0)
    pressures = root_g1 * np.array([rng.uniform(-0.05, 0.0), 0.0, 10 ** rng.uniform(-3, 0.5)])
    rtol = 10 ** rng.uniform(-5, -3)
    params = dict(hurst=hurst, decades=decades, q0=q0, h_rms=h_rms, e_star=e_star,
                  work_of_adhesion=dgamma, rtol=rtol)
    if hardness:
        params["hardness"] = float(pressures[2] * 10 ** rng.uniform(math.log10(1.5), 1.5))
    return surface, e_star, dgamma, pressures, rtol, params


def probe(seed, seconds, scenes=None, theory="persson01", hardness=False):
    rng = np.random.default_rng(seed)
    checked = misses = flagged = drawn = 0
    worst = 0.0
    t0 = time.perf_counter()
    while time.perf_counter() - t0 < seconds and (scenes is None or drawn < scenes):
        surface, e_star, dgamma, pressures, rtol, params = draw(rng, hardness)
        drawn += 1
        kw = dict(e_star=e_star, work_of_adhesion=dgamma, theory=theory,
                  hardness=params.get("hardness"))
        params = params | ({} if theory == "persson01" else {"theory": theory})
        try:
            ref = pf.solve_contact(surface, pressures, rtol=rtol * 1e-2, **kw)
            res = pf.solve_contact(surface, pressures, rtol=rtol, **kw)
        except ValueError:          # a scene the package refuses (e.g. beyond its ranges)
            continue
        for i, p in enumerate(pressures):
            if ref.status[i] != 0 or not np.isfinite(ref.area[i]):
                continue
            if res.status[i] != 0:
                flagged += 1
                continue
            checked += 1
            err = abs(res.area[i] - ref.area[i])
            tol = rtol * ref.area[i] + 1e-12
            worst = max(worst, err / tol)
            if err > tol + 1e-2 * rtol * ref.area[i]:
                misses += 1
                print(f"MISS {params | {'pressure': float(p)}}: error {err / tol:.2f} rtol, "
                      f"estimate {res.error_estimate[i] / err:.2f}x the error, "
                      f"A = {ref.area[i]:.6g}", flush=True)
    print(f"{drawn} scenes: checked {checked} rows, {misses} misses, {flagged} flagged; "
          f"worst error among status-0 rows {worst:.3g} rtol")
    return checked, misses, flagged, worst


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--seconds", type=float, default=600.0)
    parser.add_argument("--scenes", type=int, default=None, help="stop after N scenes")
    parser.add_argument("--theory", choices=("persson01", "yp08", "wm17"), default="persson01")
    parser.add_argument("--hardness", action="store_true", help="add a yield wall")
    args = parser.parse_args(argv)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        probe(args.seed, args.seconds, args.scenes, args.theory, args.hardness)


if __name__ == "__main__":
    main()
