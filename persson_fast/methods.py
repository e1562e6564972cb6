"""The registry of solution methods (a plain dict, as scipy's ``METHODS``), what each can
serve, and the ``method="auto"`` policy.

Every entry says:

* ``family`` -- ``"closed-form"``, ``"grid"`` (the front-fixed similarity grid of
  :mod:`persson_fast._kernels.similarity`), ``"fixed-grid"`` (a grid attached to the stress
  axis, the wall off-grid) or ``"integral"`` (the Volterra equation, no stress grid);
* ``sweep`` (compiled methods) -- where its kernels are: (module, base name of the serial
  and ``prange`` sweeps ``<base>_serial`` / ``<base>_parallel``, the name of the grid
  variant constant in :mod:`persson_fast._kernels.similarity` or None); :func:`sweep_kernels`
  reads it. Every sweep has the one signature of
  :mod:`persson_fast._kernels.signature`, ``(lead..., G, sa_rows, sy_rows, pressures, rtol,
  level, n_damp, area, load, det_area, det_load, error, pl_area, pl_load, status, counts)``,
  ``lead`` the variant where the entry names one, else nothing: the lower wall -sigma_a and
  the upper wall sigma_Y per row, rows of length 0 (or +inf throughout) meaning "no upper
  wall" and, for ``pl_area``/``pl_load``, "not requested"; a one-wall sweep answers a finite
  upper wall with status BAD_INPUT. :func:`persson_fast.sweep.run_sweep` drives every entry
  the same way, so a new grid method is its kernel file and one entry here;
* ``scene_scale`` (default True) -- the sweep layer divides the stresses by a scene scale
  (G by its square) before the kernel and multiplies the loads back; False for a kernel that
  takes stresses as given and scales them itself ("strip": by the width of the strip at
  G = 0);
* ``controls_error`` (default True) -- False for a method whose kernel does not refine until
  its estimate meets rtol: the sweep layer then flags (status 15) a result whose estimate
  exceeds rtol at a returned G;
* ``order`` -- the theoretical order of convergence in the resolution (node spacing and
  step halved together), measured by ``python -m benchmarks.report``;
* ``adhesion`` -- whether it can serve the self-consistent fixed point of seed Eqs. 8-9;
* ``jumps`` -- whether it can serve a wall that jumps (a flat stretch of G);
* ``nonlinear`` -- whether it can serve a wall that is not linear in G;
* ``two_walls`` (default False) -- a method that needs the yield wall (``sigma_y``,
  ``hardness``) and serves nothing else ("strip"); with a yield wall, "auto" takes
  "analytic" for a constant one without a detachment wall and "strip" otherwise
  (:mod:`persson_fast.plasticity.yield_wall`);
* ``rtol_range`` -- where the method keeps the accuracy contract without flagging, as
  measured by ``python -m benchmarks.contract_table`` (``benchmarks/CONTRACT.md``): on the
  fixed scenes (images, linear and fast walls, the square-root wall as samples and callable, a
  kinked wall) and on random walls with 1-4 kinks. Outside it results are still within rtol
  or flagged (no silent miss was measured), but flagged often: ask a looser rtol, or another
  method.

Where each method keeps the contract without flagging (``benchmarks/CONTRACT.md``: the fixed
scenes, and 100 random walls with 1-4 kinks, each as samples and as a callable, so 200 probes
per method and rtol):

* ``cn`` (and ``auto``, which takes it for every wall that is not linear): smooth walls, the
  square-root wall as samples or callable and the fast straight walls to rtol 1e-8 (no flag);
  kinked walls to rtol 1e-5 (no flag), at 1e-6 6 % flagged (half of them in fact within
  rtol), at 1e-7 24 % and at 1e-8 40 % flagged, three quarters of those real misses of the
  work cap; no silent miss. A wall that jumps is always flagged (WALL_JUMP). So: 1e-8 on
  smooth walls, 1e-6 on kinked ones;
* ``cn-plain`` (second order, not extrapolated): kinked walls to rtol 1e-5; 26 % flagged at
  1e-6, 86-100 % below (the work cap);
* ``implicit-euler`` (first order in the step): rtol 1e-3; on kinked walls 30 % flagged at
  1e-4 (nearly all in fact within rtol), 87-100 % below;
* ``fixed-grid`` (it does not refine; its estimate |F - C|/3 flags what misses rtol): rtol
  1e-3; on kinked walls 21 % flagged at 1e-4, 32 % at 1e-5, 60 % at 1e-6, two thirds of those
  in fact within rtol (the closure's error depends on where the wall sits between the nodes,
  so the two runs' difference is a noisy estimate, pointwise down to 0.05x the error), and 2
  silent misses of 1.05-1.07 rtol in 200 probes at 1e-5: a cross-check, not a tool for tight
  tolerances;
* ``bnr``: few flags on kinked walls (1-4 % at rtol 1e-4 ... 1e-7, 12 % at 1e-8), its cost
  growing with the number of schedule points; its estimate |R_2N - R_N|/7 can sit far below
  the error after kinks (3 silent misses of 1.07-1.51 rtol in 1000 probes, at 1e-4 and 1e-8).

What the grid methods report as ``error_estimate`` (the estimated error of the *returned*
area, at every returned G): each solve runs three resolutions in exact 2:1 ratio (N/2, N,
2N nodes; steps alike). ``cn`` returns the Richardson extrapolation of the two finer runs and
estimates its error as |R(h) - R(2h)|/7 (R(2h) the extrapolation of the two coarser runs;
7 = 2^3 - 1, i.e. assuming order 3 where smooth walls show 3.6-4, so the estimate is about 2x
the error there); ``cn-plain`` returns the finest run, with the Richardson estimate |F - C|/3;
``implicit-euler`` the finest run, whose error a dt + b h^2 is first order in the step and
second in the nodes: the three runs give it as (d1 - 5 d2)/3 (d1 = C - B, d2 = F - C), and
the larger of that and |F - C| is reported. Where the ratio of successive differences is far
from 2^p (the ladder is not in its asymptotic range) the larger, un-extrapolated difference
is reported. From the first kink of a prescribed wall on, ``cn`` assumes order 2 for the
extrapolated value; the steps after an isolated kink are graded (twice as many over one
e-fold of G, (G - G_kink) ~ u^2), which keeps the ladder second order through the transient
the kink starts. Where a prescribed wall recedes faster than a diffusion length per node
spacing (cell Peclet number above 1) the flux through the wall face is first order in h, and
half its advective part is added to the estimate (the ladder cannot cancel it). With ``rtol``
given (no explicit ``level``), a result whose estimate exceeds rtol A + 1e-12 at any returned
G is refined (nodes and steps doubled) up to the work cap, and flagged (status 15,
RTOL_NOT_MET, or 4, GRID_CAP) when it still misses.
"""
from __future__ import annotations

METHODS = {
    "analytic": {
        "description": "closed form: method of images (no adhesion) or a linearly moving wall",
        "family": "closed-form", "order": None, "adhesion": False, "jumps": False,
        "nonlinear": False,
    },
    "cn": {
        "description": (
            "Crank-Nicolson on the front-fixed similarity grid, Rannacher start after wall "
            "jumps, Richardson-extrapolated (h, dt) -> (h/2, dt/2)"
        ),
        "family": "grid", "order": 4, "adhesion": True, "jumps": True, "nonlinear": True,
        "sweep": ("persson_fast._kernels.sweep", "sweep", "CN"),
        "rtol_range": "smooth walls to 1e-8; kinked walls to 1e-6 (6 % flagged), 40 % at 1e-8",
    },
    "cn-plain": {
        "description": "Crank-Nicolson on the front-fixed similarity grid, no extrapolation",
        "family": "grid", "order": 2, "adhesion": True, "jumps": True, "nonlinear": True,
        "sweep": ("persson_fast._kernels.sweep", "sweep", "CN_PLAIN"),
        "rtol_range": "to 1e-5 (26 % flagged at 1e-6 on kinked walls)",
    },
    "implicit-euler": {
        "description": "implicit Euler on the front-fixed similarity grid (first order in the step)",
        "family": "grid", "order": 1, "adhesion": True, "jumps": True, "nonlinear": True,
        "sweep": ("persson_fast._kernels.sweep", "sweep", "IMPLICIT_EULER"),
        "rtol_range": "to 1e-3 (30 % flagged at 1e-4 on kinked walls)",
    },
    "fixed-grid": {
        "description": (
            "Crank-Nicolson on a grid fixed to the stress axis (similarity-stretched), the "
            "wall off-grid with a second-order Shortley-Weller Dirichlet closure"
        ),
        "family": "fixed-grid", "order": 2, "adhesion": False, "jumps": False,
        "nonlinear": True,
        "sweep": ("persson_fast._kernels.fixedgrid", "fixedgrid_sweep", None),
        "controls_error": False,
        "rtol_range": "to 1e-3 (21-60 % flagged at 1e-4 ... 1e-6 on kinked walls)",
    },
    "bnr": {
        "description": (
            "the Volterra integral equation of the detachment rate (Buonocore, Nobile & "
            "Ricciardi 1987), trapezoid rule on a geometric time grid, two Richardson steps; "
            "no stress grid"
        ),
        "family": "integral", "order": 4, "adhesion": False, "jumps": False,
        "nonlinear": True,
        "sweep": ("persson_fast._kernels.bnr", "bnr_sweep", None),
        "rtol_range": "to 1e-7 (1-4 % flagged on kinked walls), 12 % at 1e-8",
    },
    "strip": {
        "description": (
            "two walls (detachment and yield): Crank-Nicolson on the strip between them mapped "
            "onto [0, 1], Rannacher start, Richardson-extrapolated ladder with a-posteriori "
            "refinement; only with a yield wall (sigma_y, hardness)"
        ),
        "family": "two-wall", "order": 4, "adhesion": False, "jumps": False, "nonlinear": True,
        "two_walls": True, "scene_scale": False,
        "sweep": ("persson_fast._kernels.strip", "sweep", None),
    },
    "auto": {
        "description": "the cheapest method that meets rtol for the scene (see AUTO_POLICY)",
        "family": None, "order": None, "adhesion": True, "jumps": True, "nonlinear": True,
    },
}

#: ``method="auto"``: per kind of scene, the candidates in order of measured cost per
#: pressure at equal error (``benchmarks/RESULTS.md``, table "auto"); the first that can
#: serve the scene is taken. Kinds: "linear" (no wall, or a wall a + b G from G = 0),
#: "smooth" (any other wall without jumps), "jumps", "adhesion".
AUTO_POLICY = {
    "linear": ("analytic",),
    "smooth": ("cn",),
    "jumps": ("cn",),
    "adhesion": ("cn",),
}


def sweep_kernels(method: str):
    """(serial, parallel, leading arguments) of a compiled method's sweep.

    Read from the method's ``sweep`` entry (module, kernel base name -- the serial and the
    ``prange`` driver are ``<base>_serial`` and ``<base>_parallel`` --, and the name of the
    grid variant constant in :mod:`persson_fast._kernels.similarity` or None); the kernel
    module is imported on first use. The leading arguments are ``(variant,)`` where the entry
    names a variant, else empty; the rest of the signature is the one of
    :mod:`persson_fast._kernels.signature`.
    """
    import importlib

    entry = METHODS[method].get("sweep")
    if entry is None:
        raise ValueError(f"method {method!r} has no compiled sweep")
    module, base, variant = entry
    mod = importlib.import_module(module)
    lead = (variant_of(method),) if variant is not None else ()
    return getattr(mod, base + "_serial"), getattr(mod, base + "_parallel"), lead


def variant_of(method: str) -> int:
    """The grid variant number of a front-fixed-grid method (its kernel's named constant)."""
    entry = METHODS[method].get("sweep")
    if entry is None or entry[2] is None:
        raise ValueError(f"method {method!r} is not a variant of the front-fixed grid solver")
    from ._kernels import similarity

    return int(getattr(similarity, entry[2]))


def check_method(method: str) -> str:
    """Return the canonical method name or raise a ValueError listing the valid ones."""
    if not isinstance(method, str) or method.lower() not in METHODS:
        valid = ", ".join(repr(m) for m in METHODS)
        raise ValueError(f"method must be one of {valid}; got method = {method!r}")
    return method.lower()


def check_serves(method: str, *, adhesion: bool = False, jumps: bool = False,
                 nonlinear: bool = False) -> None:
    """Raise a ValueError when ``method`` cannot serve a scene with these features."""
    info = METHODS[method]
    needs = (("adhesion", adhesion, "adhesion (work_of_adhesion > 0)"),
             ("jumps", jumps, "a sigma_a that jumps (repeated G with different sigma_a)"),
             ("nonlinear", nonlinear, "a sigma_a that is not linear in G (a + b G)"))
    for key, needed, what in needs:
        if needed and not info[key]:
            able = [m for m, i in METHODS.items() if i[key] and m != "auto"]
            others = ", ".join(repr(m) for m in able[1:])
            raise ValueError(f"method {method!r} cannot serve {what}; use method={able[0]!r} "
                             f"or 'auto' (also able: {others})")


def choose_auto(kind: str) -> str:
    """The method ``"auto"`` takes for a scene of this kind (see AUTO_POLICY)."""
    need = {"adhesion": kind == "adhesion", "jumps": kind == "jumps",
            "nonlinear": kind in ("smooth", "jumps", "adhesion")}
    for name in AUTO_POLICY[kind]:
        info = METHODS[name]
        if all(info[key] or not needed for key, needed in need.items()):
            return name
    raise RuntimeError(f"AUTO_POLICY has no method for scenes of kind {kind!r}")
