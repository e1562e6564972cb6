"""The separation figure of the README: u/h_rms against log p and K against p.

Run::

    python -m benchmarks.separation_figure          # writes benchmarks/separation.png

Scenes: the self-affine surface of the separation issue (H = 0.8, q0 = 1e4 /m, q1 = 1e9 /m,
h_rms = 1 um, E* = 1 GPa) and the seed scene (frozen capillary waves on PMMA); S = 1 (solid)
and gamma_S = 0.45 (dashed); dotted: the small-pressure law p ~ exp(-u/u0) of S = 1 through
the first point. Closed form of :func:`persson_fast.solve_separation` (no diffusion solve).
"""
from __future__ import annotations

import pathlib
import sys

import numpy as np

import persson_fast as pf

OUT = pathlib.Path(__file__).with_name("separation.png")


def main(path=OUT) -> int:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    scenes = {"self-affine": (pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6), 1e9),
              "seed scene": (pf.seed_scene(), pf.seed_e_star())}
    p = np.geomspace(1e0, 1e9, 400)
    fig, (ax_u, ax_k) = plt.subplots(1, 2, figsize=(11, 4))
    for (name, (surface, e_star)), color in zip(scenes.items(), ("C0", "C1")):
        for gamma, style in ((None, "-"), (0.45, "--")):
            r = pf.solve_separation(surface, p, e_star=e_star, energy_correction=gamma)
            if not r.success:
                raise RuntimeError(r.message)
            label = f"{name}, " + ("S = 1" if gamma is None else "gamma_S = 0.45")
            ax_u.semilogx(p, r.separation / surface.h_rms, style, color=color, label=label)
            ax_k.loglog(p, r.stiffness, style, color=color, label=label)
            u0 = pf.decay_length(surface, e_star=e_star, energy_correction=gamma)
            print(f"{label:28s} u0 = {u0:.4g} m = {u0 / surface.h_rms:.3f} h_rms")
        u0 = pf.decay_length(surface, e_star=e_star)
        first = pf.solve_separation(surface, p[:1], e_star=e_star).separation[0]
        ax_u.semilogx(p, (first - u0 * np.log(p / p[0])) / surface.h_rms, ":", color=color,
                      lw=1)
    ax_u.set(xlabel="nominal pressure p [Pa]", ylabel="mean separation u / h_rms",
             ylim=(0, None), title="u(p) (dotted: p ~ exp(-u/u0))")
    ax_k.set(xlabel="nominal pressure p [Pa]", ylabel="K = -dp/du [Pa/m]",
             title="contact stiffness", ylim=(1e6, 1e24))
    ax_u.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
