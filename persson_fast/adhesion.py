"""Adhesion: the self-consistent detachment stress sigma_a(zeta) around the diffusion kernel.

Seed Eqs. 8-9:

    sigma_a(zeta) = beta (gamma_eff(zeta) E* q)^(1/2)                      (Eq. 8)
    A(zeta) gamma_eff(zeta) = A(zeta1) dgamma - U_el(zeta)                    (Eq. 9)
    U_el(zeta)/A0 = (pi E*/2) int_{zeta q0}^{q1} q^2 C(q) P(q) S(q) dq,  P(q) = A(q/q0)/A0

(Persson, PRL 89, 245502 (2002); Eur. Phys. J. E 8, 385 (2002)). S = 1, or the later
correction S = gamma_S + (1 - gamma_S) P^2 (Persson 2008). Where gamma_eff <= 0, sigma_a = 0.
The fixed point of :func:`solve_adhesive_contact` runs entirely in compiled code
(:mod:`persson_fast._kernels.adhesion`), one pressure per ``prange`` iteration, on the
nested zeta grids of :mod:`persson_fast.zeta_grid`; :mod:`persson_fast.pulloff` follows the
contact branch to the pull-off stress.
"""
from __future__ import annotations

import threading
import time

import numpy as np

from ._jit import compile_for, compiling_beside
from ._kernels.adhesion import (DEFAULT_M_HIST, DEFAULT_MAX_ITER, DEFAULT_N_DAMP, DEFAULT_OMEGA,
                               FIXED_POINT_SIGNATURE, STEP_SIGNATURE, adhesive_sweep_parallel,
                               adhesive_sweep_serial, elastic_step, elastic_step_linked,
                               fixed_point, yield_step, yield_step_linked)
from ._kernels.similarity import GRID_SIGNATURE, _solve_grid_tol
from ._kernels.status import NOT_CONVERGED, RTOL_NOT_MET
from ._kernels.theories import WM17, YP08
from ._validation import as_float_array, check_finite
from .methods import check_serves, choose_auto, variant_of
from .results import ContactResult, per_contact_area, summarize_status
from .scene import DETACHMENT_PREFACTOR
from .yield_api import FAR_MASS, yield_wall_reach
from .sweep import choose_parallel, is_compiled, prange_guard, run_rows
from .zeta_grid import (NARROW_CELL_RTOL, _scene_arrays, adhesion_zeta, coarsen_zeta,
                        refine_zeta)

__all__ = ["adhesion_zeta", "solve_adhesive_contact", "ADHESION_DEFAULTS"]

#: the corrected theories the fixed point serves, and their kernel codes
THEORY_CODES = {"yp08": YP08, "wm17": WM17}

#: iteration controls of the fixed point (Anderson depth 0 = plain relaxation; see
#: :data:`persson_fast._kernels.adhesion.DEFAULT_OMEGA`)
ADHESION_DEFAULTS = {"max_iter": DEFAULT_MAX_ITER, "m_hist": DEFAULT_M_HIST,
                     "omega": DEFAULT_OMEGA, "n_damp": DEFAULT_N_DAMP}


def _run(G, c, wa, wb, gamma_s, p_scaled, rtol, parallel, controls, x_init=None, variant=0,
         onset=True, theory=0, theory_gamma=1.0, sy=None):
    """The compiled fixed point of every pressure: outputs (8 arrays (n_p, n_z): area,
    sigma_a, g, u, load, detached area and load, error; with a yield wall ``sy`` (n_p, n_z)
    two more, the plastic area and load), status, iterations, residual and timings."""
    n_p, n_z = p_scaled.size, G.size
    outs = [np.zeros((n_p, n_z)) for _ in range(8 if sy is None else 10)]
    if sy is None:                       # no yield wall: rows of length 0
        step = elastic_step
        yield_args = [np.zeros((n_p, 0)) for _ in range(3)]
    else:
        step = yield_step
        yield_args = [np.ascontiguousarray(sy, dtype=float), outs[8], outs[9]]
    status = np.zeros(n_p, dtype=np.int64)
    iterations = np.zeros(n_p, dtype=np.int64)
    residual = np.zeros(n_p)
    if x_init is None:
        x_init = np.full((n_p, n_z), -1.0)
    mode = choose_parallel(parallel, n_p)
    if mode == "prange":                 # compiled per process: the solvers linked in
        kernel, callees = adhesive_sweep_parallel, [fixed_point, LINKED_STEPS[step], None]
    else:
        kernel, callees = adhesive_sweep_serial, [fixed_point, step, _solve_grid_tol]
    timings = {}
    if not is_compiled(kernel):
        t0 = time.perf_counter()
        first = [*callees, variant, G, c, wa, wb, gamma_s, p_scaled[:1], 1e-2, controls["n_damp"],
                 2, controls["m_hist"], controls["omega"], x_init[:1],
                 *[o[:1] for o in outs[:8]], status[:1], iterations[:1], residual[:1],
                 bool(onset), int(theory), float(theory_gamma), *[a[:1] for a in yield_args]]
        with _compile_lock:
            if mode == "prange":
                with prange_guard():
                    kernel(*first)
            else:
                _compile_fixed_point(first)
                kernel(*first)
        timings["compile"] = time.perf_counter() - t0
    args = [*callees, variant, G, c, wa, wb, gamma_s, np.ascontiguousarray(p_scaled), rtol,
            controls["n_damp"], controls["max_iter"], controls["m_hist"], controls["omega"],
            np.ascontiguousarray(x_init), *outs[:8], status, iterations, residual, bool(onset),
            int(theory), float(theory_gamma), *yield_args]
    t0 = time.perf_counter()
    run_rows(adhesive_sweep_serial, adhesive_sweep_parallel, args, (9, 15, 30),
             tuple(range(16, 27)) + (31, 32), n_p, parallel)
    timings["solve"] = time.perf_counter() - t0
    return outs, status, iterations, residual, timings


_compile_lock = threading.Lock()
#: the diffusion step the ``prange`` sweep links in, for the one the cached sweep calls
LINKED_STEPS = {elastic_step: elastic_step_linked, yield_step: yield_step_linked}


def _compile_fixed_point(first):
    """Compile (or load) the cached sweep, the fixed point and its diffusion step for the
    arguments ``first`` of a one-row sweep: on a cold cache the grid solver (the larger share)
    in a second process while this one compiles the rest
    (:func:`persson_fast._jit.compile_beside`)."""
    with compiling_beside([(_solve_grid_tol, GRID_SIGNATURE)]):
        compile_for(fixed_point, FIXED_POINT_SIGNATURE)
        compile_for(first[1], STEP_SIGNATURE)
        adhesive_sweep_serial.compile_alone(*first)


#: what :func:`persson_fast.warmup` compiles in a second process on a cold cache while it
#: compiles the contact sweeps (with the grid solver): the adhesive fixed point and its step
ADHESIVE_JOBS = [(fixed_point, FIXED_POINT_SIGNATURE), (elastic_step, STEP_SIGNATURE)]


def warm_adhesion(prange: bool = False) -> None:
    """Compile (or load) the adhesive sweep kernels on a tiny problem (``prange``: also the
    ``prange`` sweep)."""
    G = np.array([0.0, 1.0, 2.0])
    c = np.array([0.1, 0.2, 0.3])
    w = np.array([0.1, 0.1])
    ctl = _controls(None)
    for par in ((False, "prange") if prange else (False,)):
        _run(G, c, w, w, -1.0, np.array([1.0, 2.0]), 1e-2, par, ctl)  # 1 row runs serially


def warm_adhesive_yield(prange: bool = False) -> None:
    """Compile (or load) the adhesive sweep with a yield wall (the two-wall solver inside)."""
    G = np.array([0.0, 1.0, 2.0])
    c = np.array([0.1, 0.2, 0.3])
    w = np.array([0.1, 0.1])
    ctl = _controls(None)
    sy = np.full((2, 3), 10.0)
    for par in ((False, "prange") if prange else (False,)):
        _run(G, c, w, w, -1.0, np.array([1.0, 2.0]), 1e-2, par, ctl, sy=sy)


def _controls(overrides, defaults=None):
    """The fixed point's iteration controls: ``defaults`` (``ADHESION_DEFAULTS``) updated by
    ``overrides`` -- None, or a mapping of control name to value (``adhesion_controls`` of
    solve_contact, ``controls`` of pull_off) -- each value checked."""
    from collections.abc import Mapping

    def whole(name, minimum):
        value = controls[name]
        if (isinstance(value, bool)
                or not isinstance(value, (int, np.integer, float, np.floating))
                or not float(value).is_integer() or value < minimum):
            raise ValueError(f"{name} must be a whole number >= {minimum} [-]; got {name} = "
                             f"{value!r}")
        return int(value)

    controls = dict(ADHESION_DEFAULTS if defaults is None else defaults)
    if overrides is not None:
        if not isinstance(overrides, Mapping):
            raise ValueError(
                f"adhesion controls (adhesion_controls of solve_contact, controls of pull_off) "
                f"must be a dict of control names to values, e.g. {{'max_iter': 500}}; valid "
                f"names: {sorted(controls)}; got {overrides!r} (a {type(overrides).__name__})")
        unknown = set(overrides) - set(controls)
        if unknown:
            raise ValueError(f"unknown adhesion control(s) {sorted(unknown, key=repr)}; valid: "
                             f"{sorted(controls)}")
        controls.update(overrides)
    omega = controls["omega"]
    if (isinstance(omega, bool) or not isinstance(omega, (int, float, np.integer, np.floating))
            or not 0.0 < float(omega) <= 1.0):
        raise ValueError(f"omega must lie in (0, 1] [-]; got omega = {omega!r}")
    return {"max_iter": whole("max_iter", 1), "m_hist": whole("m_hist", 0),
            "omega": float(omega), "n_damp": whole("n_damp", 0)}


#: the most zeta-grid levels the a-posteriori error control adds to the three of every solve
#: (each halves the cells of the finest; a pressure refined to the cap costs ~10x the three levels)
ZETA_EXTRA_LEVELS = 3
#: a ladder of end areas a0, a1, a2 (cells halved each time) is taken as asymptotic when the
#: successive differences have one sign and shrink by a factor in this range (order 1.8-4):
#: the extrapolation assumes order 2, and ladders shrinking by 2-3.5 (order 1-1.8) were
#: measured up to 2.1 rtol off with the estimate 0.42x the error (random adhesive scenes,
#: 15 of 67 such ladders; the seed scene's shrink by 4.0-4.2)
LADDER_RATIO = (3.5, 16.0)
#: where gamma_eff changes sign sigma_a starts as a square root (an infinite slope); measured
#: on a self-affine scene (H = 0.8, five decades), a ladder whose coarsest level has cells
#: wider than 1/10 decade there looks asymptotic but is not (its extrapolated area was off by
#: 4e-4 relative with an estimate of 5e-5; a tabulated spectrum at 9.4 per decade: 1.8e-4
#: with 0.7e-4); such a ladder is refined until its coarsest level has this many per decade
CROSSING_MIN_PER_DECADE = 20
#: where gamma_eff changes sign the fixed point amplifies the diffusion solves' errors:
#: sigma_a = c sqrt(g) has an infinite slope at the sign change, so an inner error moves the
#: onset and with it the end area (measured on random weak-adhesion scenes, the onset in the
#: last cells before zeta1: end-area errors up to 2.0x the inner estimate, 1.9 rtol with
#: status 0; every one of them had its sign change late, at G >= 0.71 G1, where the end area
#: follows the onset directly). Rows whose sign change lies at G >= CROSSING_LATE G1 solve
#: level 1 again with their diffusions to rtol / CROSSING_INNER_DIV, and every level from
#: then on, and charge CROSSING_INNER_MARGIN times the diffusion's own estimate (measured
#: on those scenes: errors 0.04-0.35 rtol, estimates 1.2-3.6x the error). An early sign
#: change (G* = 0.02 G1 on the self-affine test scene) is smoothed by the diffusion after
#: it: its estimate was already 2-4x the error, and the treatment made it 10-45x
CROSSING_LATE = 0.1
CROSSING_INNER_DIV = 4.0
CROSSING_INNER_MARGIN = 2.5

def _ladder_estimate(a0, a1, a2, ok0):
    """Error estimate of R = (4 a2 - a1)/3 (the end area extrapolated from the two finest
    levels) from three levels of halved cells. [-]

    R0 = (4 a1 - a0)/3 is the same extrapolation one level coarser; R converges at order
    q >= 2 (3 on smooth scenes, about 2 after a square-root onset of the wall where gamma_eff
    changes sign), so |R - R0| / (2^q - 1) with q = 2 is its error, at most ~2.3x over for
    q = 3. Where the ladder is not asymptotic (differences of two signs, a ratio outside
    ``LADDER_RATIO``, or no valid a0) it is |a2 - a1|: R may then be no better than the last
    correction (and where the two finest levels agree exactly, e.g. both separated, the
    coarsest one's difference says nothing about R).
    """
    d1 = a1 - a0
    d2 = a2 - a1
    est = np.abs((4.0 * d2 - d1) / 3.0) / 3.0
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.abs(d1) / np.abs(d2)
    asymptotic = ok0 & (d1 * d2 > 0) & (ratio >= LADDER_RATIO[0]) & (ratio <= LADDER_RATIO[1])
    est = np.where(asymptotic, est, np.abs(d2))
    return np.where(np.isfinite(est), est, np.abs(d2))


#: the ladder's start of a finer level is interpolated cubically where the three cells
#: around a midpoint differ in width by at most this factor (else linearly)
MIDPOINT_CUBIC_RATIO = 4.0


def _midpoints_cubic(u, x):
    """Rows ``x`` (n_r, n) on nodes ``u`` and, between them, their cubic Lagrange
    interpolant at the midpoints (linear in the first and last cell, and where the cells
    around a midpoint differ in width by more than ``MIDPOINT_CUBIC_RATIO``), clipped at 0:
    (n_r, 2 n - 1)."""
    n = u.size
    out = np.empty((x.shape[0], 2 * n - 1))
    out[:, 0::2] = x
    t = 0.5 * (u[:-1] + u[1:])
    mid = 0.5 * (x[:, :-1] + x[:, 1:])
    if n >= 4:
        j = np.arange(1, n - 2)
        nodes = np.stack([u[j - 1], u[j], u[j + 1], u[j + 2]])
        w = np.ones((4, j.size))
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            for a in range(4):
                for b in range(4):
                    if a != b:
                        w[a] *= (t[j] - nodes[b]) / (nodes[a] - nodes[b])
        # only where the three cells are of similar width (a user's grid may hold cells
        # a few ulps wide, where the weights would blow up): elsewhere linear
        width = np.diff(u)
        cells = np.stack([width[j - 1], width[j], width[j + 1]])
        ok = np.all(np.isfinite(w), axis=0) & (
            cells.max(axis=0) <= MIDPOINT_CUBIC_RATIO * cells.min(axis=0))
        jj = j[ok]
        mid[:, jj] = (w[0, ok] * x[:, jj - 1] + w[1, ok] * x[:, jj] + w[2, ok] * x[:, jj + 1]
                      + w[3, ok] * x[:, jj + 2])
    out[:, 1::2] = np.maximum(mid, 0.0)
    return out


class _ZetaLadder:
    """The fixed point on nested zeta grids, Richardson-extrapolated, with a-posteriori
    control of the zeta-grid error of the end area (issue 12).

    Level 0 is :func:`coarsen_zeta` of the grid, level 1 the grid (the result's ``zeta``),
    level k >= 2 its (k-1)-fold :func:`refine_zeta`. Every pressure is solved on levels 0-2;
    one whose estimate (:func:`_ladder_estimate`) exceeds rtol A gets further levels, up to
    ``ZETA_EXTRA_LEVELS``, and then, if still above, status RTOL_NOT_MET. Each level starts
    from level 1's detachment stress (level 0 at its nodes, level 2 interpolated in ln
    zeta), level k > 2 from level k - 1's; level 1 from the given start or full contact.
    """

    def __init__(self, zeta, n_p, solve):
        self.zeta = zeta
        self.n_p = n_p
        self.solve_fn = solve
        z0, self.idx0 = coarsen_zeta(zeta)
        self.grids = [z0, zeta, refine_zeta(zeta)]
        self.levels = []          # per level: outs (8 arrays (n_p, n_k), nan where unsolved), status
        self.last = np.full(n_p, 2, dtype=np.int64)
        self.iterations = np.zeros(n_p, dtype=np.int64)
        self.residual = np.zeros(n_p)
        self.max_extra = 0
        self.G_dim = None
        self.inner_div = np.ones(n_p)   # per pressure: rtol / (its diffusion tolerance)

    def _solve_level(self, k, rows, start_pa):
        grid = self.grids[k]
        outs, status, iterations, residual, G_dim = self.solve_fn(grid, start_pa, rows,
                                                                 self.inner_div[rows])
        if k == 1:
            self.G_dim = G_dim
        if k >= len(self.levels):
            self.levels.extend([None] * (k + 1 - len(self.levels)))
        if self.levels[k] is None:
            self.levels[k] = ([np.full((self.n_p, grid.size), np.nan) for _ in outs],
                              np.zeros(self.n_p, dtype=np.int64))
        full, st_full = self.levels[k]
        for f_, o in zip(full, outs):
            f_[rows] = o
        st_full[rows] = status
        self.iterations[rows] += iterations
        self.residual[rows] = np.maximum(self.residual[rows], residual)
        return status

    def _start_from(self, k, rows):
        """Start of level k + 1 from level k's detachment stress (full contact where level k
        failed): level k's values at its own nodes and their cubic interpolant in ln zeta
        between them (:func:`_midpoints_cubic`), plus, where level k - 1 is solved too, the
        change to the finer level that second-order convergence predicts, (x_k - x_k-1)/4
        (linear in ln zeta). Only the start: the fixed point's stop is the same, but from
        it the seed scene's level 2 takes 4.1 iterations instead of 5.1 (linear
        interpolation alone), at rtol 1e-6."""
        outs, status = self.levels[k]
        z_from, z_to = self.grids[k], self.grids[k + 1]
        lz_from, lz_to = np.log(z_from), np.log(z_to)
        if z_to.size == 2 * z_from.size - 1 and np.array_equal(z_to[0::2], z_from):
            start = _midpoints_cubic(lz_from, outs[1][rows])
        else:
            start = np.array([np.interp(lz_to, lz_from, outs[1][r]) for r in rows])
        start = start.reshape(rows.size, z_to.size)
        regular = bool(np.all(np.diff(z_to) > NARROW_CELL_RTOL * z_to[:-1]))
        # (not on a grid with cells a few ulps wide, a user's: the change, interpolated
        # across such a cell, would make the wall jump where G is flat)
        if regular and k >= 1 and self.levels[k - 1] is not None:
            outs_c, status_c = self.levels[k - 1]
            lz_c = np.log(self.grids[k - 1])
            for i, r in enumerate(rows):
                x_c = outs_c[1][r]
                if status_c[r] != 0 or not np.all(np.isfinite(x_c)):
                    continue
                change = (np.interp(lz_c, lz_from, outs[1][r]) - x_c) / 4.0
                start[i] = np.maximum(start[i] + np.interp(lz_to, lz_c, change), 0.0)
        start[status[rows] != 0] = -np.inf
        return start

    def solve(self, start):
        rows = np.arange(self.n_p)
        # level 1 first, from the given start or full contact (where a two-level solve
        # started: from a coarser profile it would, at p_nom = 0 on a surface that is not
        # sticky, end on a contact area of 1e-13 instead of the separated state); level 0
        # starts from level 1's profile at its nodes (about half the iterations of a start
        # from full contact), level 2 from level 1's profile interpolated
        self.levels = [None, None]
        self._solve_level(1, rows, start)
        # a late sign change of gamma_eff: the level again with the tighter diffusion
        # tolerance, from its own profile (CROSSING_LATE, CROSSING_INNER_DIV)
        cross = np.array([self.levels[1][1][r] == 0 and self._late_crossing(r)
                          for r in rows], dtype=bool)
        if cross.any():
            again = rows[cross]
            self.inner_div[again] = CROSSING_INNER_DIV
            self._solve_level(1, again, self.levels[1][0][1][again].copy())
        outs1, status1 = self.levels[1]
        start0 = outs1[1][:, self.idx0].copy()
        start0[status1 != 0] = -np.inf
        self._solve_level(0, rows, start0)
        self._solve_level(2, rows, self._start_from(1, rows))

    def _ends(self, k):
        return self.levels[k][0][0][:, -1]

    def _end_estimate(self):
        """Estimate of the end area's zeta-grid error per pressure, the split mask (one of
        the two finest levels separated, the other in contact: no extrapolation) and the
        returned end area. The estimate includes the inner (diffusion) error estimate of the
        finest level's end area."""
        n = np.arange(self.n_p)
        K = self.last
        a2 = np.array([self._ends(K[r])[r] for r in n])
        a1 = np.array([self._ends(K[r] - 1)[r] for r in n])
        a0 = np.array([self._ends(K[r] - 2)[r] for r in n])
        ok0 = np.array([self.levels[K[r] - 2][1][r] == 0 for r in n]) & np.isfinite(a0)
        ok0 &= (a0 > 0) == (a1 > 0)
        resolved = np.array([self._crossing_resolved(K[r] - 2, r) for r in n])
        ok0 &= resolved
        split = (a1 > 0) != (a2 > 0)
        est = np.where(split, np.abs(a2 - a1), _ladder_estimate(a0, a1, a2, ok0))
        # after a square-root onset of sigma_a the extrapolated value converges at an order
        # near 1.5 with a constant that depends on where the sign change falls between the
        # nodes: its ladder can look asymptotic and still be off by several times the ladder
        # estimate (measured: 0.17x at rtol 1e-5); there the last un-extrapolated difference
        # bounds the estimate from below: the error of the finest un-extrapolated value at
        # order 1.5, |a2 - a1| / (2^1.5 - 1), which the extrapolated value betters (measured
        # 2-5x the error of the returned value)
        crossing = np.array([self._has_crossing(K[r], r) for r in n])
        est = np.where(crossing, np.maximum(est, np.abs(a2 - a1) / (2.0 ** 1.5 - 1.0)), est)
        area = np.where(split, a2, np.clip((4.0 * a2 - a1) / 3.0, 0.0, 1.0))
        # an area falling towards 0 whose extrapolation clips to 0 (contact vanishing as the
        # grid refines, e.g. at p_nom = 0 on a surface that is not sticky): the limit lies in
        # [0, a2], so 0 is off by at most a2
        vanishing = ~split & (4.0 * a2 - a1 <= 0.0) & (a2 <= a1)
        # a sign change of gamma_eff that the ladder's coarsest level does not resolve: the
        # ladder says little (measured: an estimate 0.38x the error on a tabulated spectrum);
        # such a row is refined, and flagged if the work cap leaves it unresolved
        self.unresolved = ~resolved & ~split & ~vanishing
        est = np.where(self.unresolved, np.maximum(est, np.maximum(np.abs(a1 - a0), np.abs(a2 - a1))),
                       est)
        inner = np.array([abs(self.levels[K[r]][0][7][r, -1]) for r in n])
        inner = np.where(self.inner_div > 1.0, CROSSING_INNER_MARGIN * inner, inner)
        est = np.where(vanishing, np.minimum(est + inner, a2), est + inner)
        return est, split, area

    def _crossing_cells(self, k, r):
        """The cells of level k where row r's gamma_eff changes sign."""
        g = self.levels[k][0][2][r]
        return np.flatnonzero((g[:-1] > 0) != (g[1:] > 0))

    def _has_crossing(self, k, r):
        return self._crossing_cells(k, r).size > 0

    def _late_crossing(self, r):
        """Row r's gamma_eff on level 1 changes sign in a cell ending at G >= CROSSING_LATE G1
        (level 1: the one whose diffusion times are kept)."""
        cells = self._crossing_cells(1, r)
        return bool(cells.size and self.G_dim[cells[-1] + 1] >= CROSSING_LATE * self.G_dim[-1])

    def _crossing_resolved(self, k, r):
        """Level k resolves every sign change of row r's gamma_eff with cells of at most
        1/CROSSING_MIN_PER_DECADE decade (ladders coarser there are not yet asymptotic)."""
        cells = self._crossing_cells(k, r)
        if cells.size == 0:
            return True
        z = self.grids[k]
        width = np.log10(z[cells + 1] / z[cells])
        return bool(np.all(width <= 1.01 / CROSSING_MIN_PER_DECADE))

    def _status_of(self, r):
        s2 = self.levels[self.last[r]][1][r]
        s1 = self.levels[self.last[r] - 1][1][r]
        return s2 if s2 != 0 else s1

    def refine_until(self, rtol):
        for extra in range(1, ZETA_EXTRA_LEVELS + 1):
            est, _, area = self._end_estimate()
            status = np.array([self._status_of(r) for r in range(self.n_p)])
            rows = np.flatnonzero((status == 0) & ((est > rtol * area + 1e-12) | self.unresolved))
            if rows.size == 0:
                break
            k = 2 + extra
            if len(self.grids) <= k:
                self.grids.append(refine_zeta(self.grids[-1]))
            self._solve_level(k, rows, self._start_from(k - 1, rows))
            self.last[rows] = k
            self.max_extra = extra
        est, _, area = self._end_estimate()
        self.status = np.array([self._status_of(r) for r in range(self.n_p)], dtype=np.int64)
        self.status[(self.status == 0) & ((est > rtol * area + 1e-12) | self.unresolved)] = RTOL_NOT_MET

    def profiles(self):
        """Profiles on the level-1 nodes: the extrapolation of the two finest levels of each
        pressure (the finer alone where one of them separated), and the error estimates."""
        n_z = self.zeta.size
        n_out = len(self.levels[1][0])
        res = [np.zeros((self.n_p, n_z)) for _ in range(n_out)]
        err = np.zeros((self.n_p, n_z))
        zeta_err = np.zeros(self.n_p)
        est, split, _ = self._end_estimate()
        for r in range(self.n_p):
            K = self.last[r]
            fine = [o[r, ::2 ** (K - 1)] for o in self.levels[K][0]]
            prev = [o[r, ::2 ** (K - 2)] for o in self.levels[K - 1][0]]
            for j in range(n_out):
                res[j][r] = fine[j] if split[r] else (4.0 * fine[j] - prev[j]) / 3.0
            # an extrapolated profile outside [0, 1] is a zeta-grid error: clip it and charge
            # the overshoot to the error estimate
            a = res[0][r]
            over = np.maximum(a - 1.0, 0.0) + np.maximum(-a, 0.0)
            res[0][r] = np.clip(a, 0.0, 1.0)
            err[r] = np.abs(fine[7]) + np.abs(fine[0] - prev[0]) / 3.0
            zeta_err[r] = max(est[r] - abs(fine[7][-1]), over.max(), 0.0)
            err[r, -1] = max(est[r], over.max())
        area_z, sa, g, u, load, det_a, det_l = res[:7]
        # sigma_a = c sqrt(max(gamma_eff, 0)): extrapolation must not make it negative, nor
        # non-zero where the extrapolated gamma_eff is not positive
        sa = np.where(g > 0, np.maximum(sa, 0.0), 0.0)
        if n_out > 8:                 # the plastic area and load (a yield wall)
            res[8] = np.clip(res[8], 0.0, area_z)
        return (area_z, sa, g, u, load, det_a, det_l, err, zeta_err) + tuple(res[8:])


def yield_wall_on(hardness, zeta) -> np.ndarray:
    """sigma_Y [Pa] at the magnifications ``zeta`` of a validated hardness (a number or a
    callable of zeta), checked finite and > 0."""
    if not callable(hardness):
        return np.full(zeta.size, float(hardness))
    sy = np.asarray(hardness(zeta), dtype=float)
    if sy.shape != zeta.shape or not np.all(np.isfinite(sy)) or np.any(sy <= 0):
        raise ValueError(f"hardness(zeta) must return finite values > 0 [Pa] of zeta's shape; "
                         f"got {sy!r} at zeta = {zeta!r}")
    return sy


def _plastic_fields(area, plastic, hardness) -> dict:
    """The yield fields of an adhesive result (none without a yield wall)."""
    if hardness is None:
        return {}
    pl, pl_load = plastic
    return {"elastic_area": area - pl[:, -1], "plastic_area": pl[:, -1].copy(),
            "plastic_area_zeta": pl, "plastic_load": pl_load[:, -1].copy(),
            "hardness": hardness}


def solve_adhesive_contact(surface, pressure, zeta, *, e_star, work_of_adhesion,
                           energy_correction=None, detachment_prefactor=DETACHMENT_PREFACTOR,
                           method="auto", rtol=1e-6, parallel=None, controls=None,
                           zeta_given=False, start=None, onset=True, theory="persson01",
                           theory_gamma=None, hardness=None) -> ContactResult:
    """Adhesive contact of one scene at many pressures (called by :func:`solve_contact`).

    Arguments are validated by :func:`persson_fast.solve_contact`; ``zeta`` is the grid of
    the fixed point (``adhesion_zeta`` unless the user gave one). ``start``: optional
    (n_p, n_z) detachment stresses [Pa] on ``zeta`` to start the fixed point from
    (continuation); default the full-contact detachment stress. ``onset``: shape the
    square-root onset of sigma_a where gamma_eff changes sign (see
    :func:`persson_fast._kernels.adhesion.wall_solve`); pull_off's checks pass False, the
    discretisation of its branch follower. ``theory``, ``theory_gamma``: the area theory
    (validated): "persson01", or "yp08"/"wm17" with their gamma, whose corrected diffusion
    dT/dG = S(A) the fixed point solves together with sigma_a (see
    :func:`persson_fast._kernels.adhesion.solve_adhesive_one`). ``hardness``: None, or the
    validated yield wall sigma_Y(zeta) (a number [Pa] or a callable of zeta): then every
    solve of the fixed point is the two-wall solver, sigma_Y taken at the zeta grid's nodes
    (linear in G between them, as the detachment wall; the zeta ladder controls the error),
    and the result carries ``elastic_area``, ``plastic_area``, ``plastic_area_zeta`` and
    ``plastic_load`` (``area`` the real contact area, ``load`` the elastic part's).
    """
    if method == "auto":
        method = choose_auto("adhesion")
    check_serves(method, adhesion=True)
    variant = variant_of(method)
    p = as_float_array(pressure, "pressure", "Pa", ndim=(0, 1))
    check_finite(p, "pressure", "Pa")
    p = np.atleast_1d(p).astype(float)
    ctl = _controls(controls)
    if not zeta_given:
        zeta = adhesion_zeta(surface, rtol)
    if p.size == 0:
        # no pressure, nothing to solve: an empty result on the grid, as without adhesion
        G_dim = _scene_arrays(surface, zeta, e_star, work_of_adhesion, detachment_prefactor)[5]
        none, rows = np.zeros(0), np.zeros((0, zeta.size))
        return ContactResult(
            pressure=p, area=none, zeta=zeta, G=G_dim, area_zeta=rows, sigma_a=rows,
            gamma_eff=rows, load=none, mean_contact_pressure=none, mean_contact_stress=none,
            detached_area=none, detached_load=none, error_estimate=none, method=method,
            status=np.zeros(0, dtype=np.int64), success=True, message="ok", timings={},
            elastic_energy_zeta=rows, iterations=np.zeros(0, dtype=np.int64), residual=none,
            sticky=np.zeros(0, dtype=bool), load_zeta=rows, detached_load_zeta=rows,
            zeta_error=none, theory=theory, theory_gamma=theory_gamma)
    gamma_s = -1.0 if energy_correction is None else float(energy_correction)
    theory_code = THEORY_CODES.get(theory, 0)
    theory_g = 1.0 if theory_gamma is None else float(theory_gamma)
    timings = {}

    def fixed_point(grid, start_pa, rows, inner_div):
        G, c, wa, wb, scale, G_dim = _scene_arrays(surface, grid, e_star, work_of_adhesion,
                                                   detachment_prefactor)
        x_init = None if start_pa is None else start_pa / scale
        sy = None
        if hardness is not None:
            sy = np.broadcast_to(yield_wall_on(hardness, grid), (rows.size, grid.size)).copy()
            # a yield wall the distribution cannot reach (reflection-principle bound without
            # the detachment wall, which only removes mass): solved without it (inf)
            far = yield_wall_reach(G_dim, p[rows], sy) <= FAR_MASS
            sy[far] = np.inf
            sy = sy / scale
        # one call per diffusion tolerance (the rows of a late sign change of gamma_eff take
        # a tighter one); a pressure's result does not depend on the others in its call
        outs = None
        status = np.zeros(rows.size, dtype=np.int64)
        iterations = np.zeros(rows.size, dtype=np.int64)
        residual = np.zeros(rows.size)
        for div in np.unique(inner_div):
            sel = np.flatnonzero(inner_div == div)
            o_p, status[sel], iterations[sel], residual[sel], tim = _run(
                G, c, wa, wb, gamma_s, p[rows][sel] / scale, rtol / div, parallel, ctl,
                None if x_init is None else x_init[sel], variant, onset, theory_code,
                theory_g, None if sy is None else sy[sel])
            if outs is None:
                outs = [np.zeros((rows.size, grid.size)) for _ in o_p]
            for full, o in zip(outs, o_p):
                full[sel] = o
            for key, val in tim.items():
                timings[key] = timings.get(key, 0.0) + val
        outs = [o * (scale if k in (1, 4, 6, 9) else 1.0) for k, o in enumerate(outs)]
        return outs, status, iterations, residual, G_dim

    if start is not None:
        start = np.array(start, dtype=float)
        if start.shape not in ((p.size, zeta.size), (zeta.size,)):
            raise ValueError(f"start must have shape (n_p, n_zeta) = ({p.size}, {zeta.size}) "
                             f"[Pa] (detachment stresses on the zeta grid); got shape "
                             f"{start.shape}")
        start = np.broadcast_to(start, (p.size, zeta.size)).copy()
    ladder = _ZetaLadder(zeta, p.size, fixed_point)
    ladder.solve(start)
    ladder.refine_until(rtol)
    area_z, sa, g, u, load, det_a, det_l, err, zeta_err, *plastic = ladder.profiles()
    status, iterations, residual = ladder.status, ladder.iterations, ladder.residual
    G_dim = ladder.G_dim
    area = area_z[:, -1].copy()
    success, message = summarize_status(status)
    if np.any(status == NOT_CONVERGED):
        bad = np.flatnonzero(status == NOT_CONVERGED)
        message += f"; largest fixed-point residual {residual[bad].max():.3g} after {iterations[bad].max()} iterations"
    if np.any(status == RTOL_NOT_MET):
        bad = np.flatnonzero(status == RTOL_NOT_MET)
        rel = err[bad, -1] / np.maximum(area[bad], 1e-300)
        message += (f"; zeta grid refined {ladder.max_extra} times, estimated relative error of "
                    f"the area up to {rel.max():.3g} (rtol {rtol:.3g})")
    return ContactResult(
        pressure=p, area=area, zeta=zeta, G=G_dim, area_zeta=area_z, sigma_a=sa,
        gamma_eff=g * work_of_adhesion, load=load[:, -1].copy(),
        mean_contact_pressure=per_contact_area(p, area),
        mean_contact_stress=per_contact_area(load[:, -1], area),
        detached_area=det_a[:, -1].copy(), detached_load=det_l[:, -1].copy(),
        error_estimate=err[:, -1].copy(), method=method, status=status, success=success,
        message=message, timings=timings, elastic_energy_zeta=u * work_of_adhesion,
        iterations=iterations, residual=residual, sticky=g[:, 0] > 0,
        load_zeta=load, detached_load_zeta=det_l, zeta_error=zeta_err,
        theory=theory, theory_gamma=theory_gamma, **_plastic_fields(area, plastic, hardness),
    )
