"""Convergence of the adhesive A(zeta1) under zeta-grid refinement (seed scene).

    python -m benchmarks.adhesion_convergence

For each density of the magnification grid (points per decade), the fixed point of
Eqs. 8-9 is solved with a diffusion tolerance of 1e-9 (so that the zeta grid dominates the
error) on that grid alone ("single") and as :func:`persson_fast.solve_contact` returns it,
Richardson-extrapolated over the grid and its refinement ("extrapolated"). Printed: A(zeta1)
at two nominal pressures, the change per doubling of the density and the observed order
log2(change ratio). Takes about a minute on a 2-core machine.
"""
from __future__ import annotations

import numpy as np

import persson_fast as pf
from persson_fast.adhesion.runner import _controls, _run
from persson_fast.adhesion.zeta_grid import _scene_arrays, adhesion_zeta
from persson_fast.adhesion.fixed_point import solve_adhesive_contact

E_STAR = pf.seed_e_star()
DGAMMA = pf.SEED_WORK_OF_ADHESION
PRESSURES = np.array([0.0, 1e7])        # [Pa]
DENSITIES = (4, 8, 16, 32, 64)           # points per decade
INNER = 1e-9


def single(surface, zeta):
    G, c, wa, wb, scale, _ = _scene_arrays(surface, zeta, E_STAR, DGAMMA, 2 ** -0.5)
    outs, status, *_ = _run(G, c, wa, wb, -1.0, PRESSURES / scale, INNER, False,
                            _controls(None))
    if np.any(status != 0):
        raise RuntimeError(f"status {status}")
    return outs[0][:, -1]


def extrapolated(surface, zeta):
    r = solve_adhesive_contact(surface, PRESSURES, zeta, e_star=E_STAR, work_of_adhesion=DGAMMA,
                               rtol=INNER, parallel=False, zeta_given=True)
    if not r.success:
        raise RuntimeError(r.message)
    return r.area


def table(name, values):
    values = np.array(values)
    lines = [f"{name}", "| per decade | " + " | ".join(f"A(zeta1), p = {p / 1e6:g} MPa | change"
                                                      for p in PRESSURES) + " | order |",
             "|---" * (2 * PRESSURES.size + 2) + "|"]
    for k, d in enumerate(DENSITIES):
        cells = []
        for j in range(PRESSURES.size):
            change = "" if k == 0 else f"{values[k, j] - values[k - 1, j]:.2e}"
            cells += [f"{values[k, j]:.9f}", change]
        order = ""
        if k >= 2:
            d1 = values[k - 1, 0] - values[k - 2, 0]
            d2 = values[k, 0] - values[k - 1, 0]
            order = f"{np.log2(abs(d1 / d2)):.2f}" if d2 != 0 else "inf"
        lines.append(f"| {d} | " + " | ".join(cells) + f" | {order} |")
    return "\n".join(lines)


def main():
    surface = pf.seed_scene()
    grids = [adhesion_zeta(surface, per_decade=d) for d in DENSITIES]
    print(table("single grid", [single(surface, z) for z in grids]))
    print()
    print(table("extrapolated (grid and its refinement)", [extrapolated(surface, z) for z in grids]))
    print("\n(order: from the p = 0 column; zeta grids also refined in ln(zeta - 1) near 1)")


if __name__ == "__main__":
    main()
