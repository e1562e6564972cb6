"""The contact branch of one adhesive scene on one zeta grid, and the descent along it.

:class:`_Branch` holds the adhesive fixed point of seed Eqs. 8-9 on one grid, parametrised by
y0 = sigma0 + sigma_a(1): a branch point at given y0 (Anderson-accelerated, with a trust
region), the state at p_nom = 0 and whether it is sticky (:func:`_rest_start`). The same
branch serves the corrected theories yp08 and wm17 (the iterate then carries the corrected
diffusion time T(G) = int S(A) dG beside sigma_a, as the compiled fixed point does) and a
yield wall sigma_Y(zeta) (every diffusion solve is then the two-wall solver, Eqs. 8-9 with
U_el of the elastic area and gamma_eff per unit real area).
:func:`_descend` follows the branch down in y0 to where sigma0 is least (:func:`_tail_estimate`
and :func:`_locate_minimum` say where that is); :func:`_replay` repeats given branch points on
a finer grid. :func:`persson_fast.pull_off` builds on these.
"""
from __future__ import annotations

import numpy as np

from .._kernels.adhesion import corrected_times, yield_detachment_update
from .._kernels.status import (BAD_INPUT, FAR_LEAK, GRID_CAP, NEGATIVE_DENSITY, NONFINITE,
                              NOT_CONVERGED, RTOL_NOT_MET, START_UNRESOLVED, WALL_JUMP)
from .runner import _run
from .._kernels.similarity import SMOOTH_WALL
from ..results import summarize_status
from .zeta_grid import _scene_arrays

__all__ = ["PULL_OFF_STEP", "PULL_OFF_TAIL", "PULL_OFF_INNER", "PULL_OFF_INNER_LOOSE",
           "PULL_OFF_INNER_RTOLS", "PULL_OFF_INNER_MIN",
           "PULL_OFF_EARLY", "PULL_OFF_RESIDUAL", "PULL_OFF_TRUST", "PULL_OFF_RETRY",
           "PULL_OFF_MAX_ITER", "PULL_OFF_STALL", "PULL_OFF_BLOWUP", "PULL_OFF_MAX_STAGES",
           "PULL_OFF_MAX_FOLD_STEPS", "PULL_OFF_LOOSE", "PULL_OFF_COLLAPSE",
           "PULL_OFF_REST_ITER", "PULL_OFF_REST_RETRIES"]

#: ratio of successive y0 = sigma0 + sigma_a(1) on the descent along the contact branch
PULL_OFF_STEP = 2.0
#: the descent stops once its tail estimate is below this fraction of rtol * sigma_c
PULL_OFF_TAIL = 0.25
#: diffusion tolerance of the branch points: f(rtol) * rtol * min(1, 2 g1), g1 =
#: gamma_eff(1)/dgamma = (sigma_a(1)/c_1)^2, and at least PULL_OFF_INNER_MIN. sigma_a(1) =
#: c_1 g1^(1/2) moves by dA/(2 g1) relative for an error dA of the area profile, and
#: measured at the end of the seed scene's branch (2 g1 = 0.2) one application of Eqs. 8-9
#: moved sigma_a(1) by up to 7x the diffusion tolerance (1.5 Pa at 3e-7; 0.1 Pa between
#: 3e-8 and 3e-10). The factor f is PULL_OFF_INNER at rtol <= 1e-6 and PULL_OFF_INNER_LOOSE
#: at rtol >= 1e-5 (log-linear between, :func:`_inner_factor`). The inner error of sigma_c
#: has two parts: about 2.3 x the diffusion tolerance (seed scene at rtol 1e-4, measured by
#: the end-point check of pull_off: 7.1 / 16 / 23 Pa of 7.8e5 Pa at tolerances 4e-6 / 1e-5 /
#: 2e-5), and the kernel's scatter at tight tolerances, about 5e-7 sigma_c (see
#: PULL_OFF_INNER_FLOOR). Where rtol is loose the first part rules, and f = 0.2 keeps it near
#: 0.1 rtol sigma_c (f = 0.05 there put it below the scatter, 20x under what rtol asks, and
#: made the branch points 2.3x slower); at rtol 1e-6 the scatter is the whole budget, and
#: there 0.25 left the seed's inner error at 0.78 Pa (1.0e-6 sigma_c) while 0.05 brings it
#: to the 5e-7 floor
PULL_OFF_INNER = 0.05
PULL_OFF_INNER_LOOSE = 0.2
PULL_OFF_INNER_RTOLS = (1e-6, 1e-5)
PULL_OFF_INNER_MIN = 1e-9
#: diffusion tolerance of an early iteration of a branch point, relative to its residual
#: (one application of Eqs. 8-9 has an error of up to ~10x the diffusion tolerance)
PULL_OFF_EARLY = 0.01
#: fixed-point tolerance of a branch point, relative to rtol: max_i |F_i(x) - x_i| / c_i,
#: c_i = beta (dgamma E* q_i)^(1/2) the full-contact scale of sigma_a at node i
PULL_OFF_RESIDUAL = 0.02
#: a step may move the wall at a node by at most this fraction of its distance from the
#: start of the distribution, y0 + sigma_a(zeta_i) - sigma_a(1) (the scale on which the
#: detachment near zeta = 1 is nonlinear)
PULL_OFF_TRUST = 0.5
#: relaxation factor and trust fraction of the retry after a failed branch point
PULL_OFF_RETRY = (0.3, 0.2)
#: iteration cap of one branch point, and iterations without halving the best residual
#: after which it gives up
PULL_OFF_MAX_ITER = 300
PULL_OFF_STALL = 30
#: a residual this many times the best so far restarts the iteration from the best iterate
PULL_OFF_BLOWUP = 30.0
#: cap on the descent's stages and on the parabolic steps that locate an interior minimum
PULL_OFF_MAX_STAGES = 80
PULL_OFF_MAX_FOLD_STEPS = 8
#: early stages run at this fraction of their relative change of sigma0 (at most 1e-3)
PULL_OFF_LOOSE = 0.01
#: stickiness (see :func:`_rest_state`): iterating Eqs. 8-9 at p_nom = 0, the state is not
#: sticky once gamma_eff(1)/dgamma lies below minus its error bar on this many successive
#: iterates while A(zeta1) falls (the iteration is on its way to the separated state A = 0)
PULL_OFF_COLLAPSE = 3
#: iterations of that test before it gives up undecided (the descent then decides)
PULL_OFF_REST_ITER = 30
#: the solve at p_nom = 0 that starts the descent is repeated this many times at most, each
#: time with a 10x tighter tolerance, while a resolution flag (not a failure of the input)
#: stops it (a near-full-contact self-affine scene, A/A0 = 0.987 at p_nom = 0, reached the
#: far end of the diffusion grid at tolerances 2e-4 and 5e-6 and not at 5e-5 or 5e-7)
PULL_OFF_REST_RETRIES = 2
#: a converged branch point whose last diffusion solve is flagged FAR_LEAK (the distribution
#: reached the far end of the diffusion grid) is solved on with a diffusion tolerance this
#: factor tighter, once (down to PULL_OFF_INNER_MIN)
PULL_OFF_LEAK_RETRY = 0.1
#: with a yield wall, a branch point stops at once (unconverged) when a diffusion solve
#: returns one of these: the two-wall solver cannot resolve a start this close to the
#: detachment wall (its grid spans the whole strip between the walls; seed scene, sigma_Y =
#: 2e8 Pa: negative areas from y0 = 1.1e4 Pa = 0.8 % of sigma_a(1) down, at every tolerance
#: and on both the pull-off grid and solve_contact's; a self-affine scene with sigma_Y =
#: 3e7 Pa: its node cap from y0 = 2e5 Pa = 4 % of sigma_a(1)), and no relaxation or trust
#: region changes that; the descent's tail estimate then charges what is left of the branch
STRIP_UNRESOLVED = (NEGATIVE_DENSITY, START_UNRESOLVED, GRID_CAP)


class _AndersonHistory:
    """The past iterates of an Anderson (type II) iteration of the branch points, and its step:
    least squares by normal equations with a Tikhonov guard, weights ``w``, relaxation
    ``omega``; ``m_hist`` = 0 gives plain relaxation."""

    def __init__(self, m_hist):
        self.m_hist = m_hist
        self.reset()

    def reset(self):
        self.dX, self.dF = [], []
        self.x_prev = self.f_prev = None

    def step(self, x, f, w, omega):
        if self.m_hist > 0 and self.x_prev is not None:
            self.dX.append(x - self.x_prev)
            self.dF.append(f - self.f_prev)
            if len(self.dX) > self.m_hist:
                self.dX.pop(0)
                self.dF.pop(0)
        self.x_prev, self.f_prev = x, f
        if not self.dX:
            return omega * f
        DX = np.array(self.dX).T
        DF = np.array(self.dF).T
        A = DF * w[:, None]
        M = A.T @ A
        M += np.eye(len(self.dX)) * (1e-10 * np.trace(M) + 1e-300)
        gamma = np.linalg.solve(M, A.T @ (f * w))
        return omega * f - (DX + omega * DF) @ gamma


class _Branch:
    """The adhesive fixed point on one zeta grid, parametrised by y0 = sigma0 + sigma_a(1).

    Along the contact branch the nominal pressure sigma0(y0) turns (or flattens) at the
    pull-off, where the fixed point at fixed sigma0 is singular; at fixed y0 it is regular.
    All stresses inside are scaled by the scene scale of :func:`_scene_arrays`.

    The iterate is sigma_a at the nodes (scaled); with a corrected theory (``theory_code``
    YP08 or WM17 of :mod:`persson_fast._kernels.theories`) it is followed by t = T/G(zeta1)
    at the nodes, the corrected diffusion time T = int S(A) dG of the real area, iterated
    with sigma_a as in :func:`persson_fast._kernels.adhesion.solve_adhesive_one` (kept
    non-decreasing from t = 0). With ``hardness`` (the validated yield wall sigma_Y(zeta))
    every diffusion solve is the two-wall solver; the area of a branch point is then the
    real area A_el + A_pl, and Eqs. 8-9 take U_el of the elastic area A_el and gamma_eff
    per unit real area (:func:`persson_fast._kernels.adhesion.yield_detachment_update`).
    A yield wall that the distribution cannot reach from p_nom = 0 (the reflection-principle
    bound of :func:`persson_fast.plasticity.yield_wall.yield_wall_reach` at most ``FAR_MASS``; along the
    branch p_nom <= 0, where it is reached less) is left out, as solve_contact does.
    """

    def __init__(self, surface, zeta, e_star, work_of_adhesion, beta, gamma_s, variant, n_damp,
                 theory_code=0, theory_gamma=1.0, hardness=None):
        from .._jit import callable_with
        from .._kernels.adhesion import STEP_SIGNATURE, elastic_step, yield_step
        from .._kernels.similarity import GRID_SIGNATURE, _solve_grid_tol

        self.zeta = np.asarray(zeta, dtype=float)
        self.work_of_adhesion = float(work_of_adhesion)
        G, c, wa, wb, scale, G_dim = _scene_arrays(surface, self.zeta, e_star,
                                                   work_of_adhesion, beta)
        self.G, self.c, self.wa, self.wb, self.scale = G, c, wa, wb, scale
        self.gamma_s = gamma_s
        self.theory_code = int(theory_code)
        self.theory_gamma = float(theory_gamma)
        self.corrected = self.theory_code != 0
        n = self.zeta.size
        self.n = n
        # the residual's weights: sigma_a at node i against its full-contact scale c_i, the
        # corrected times (already relative to G(zeta1)) as they are
        self.weights = (np.concatenate([1.0 / c, np.ones(n)]) if self.corrected else 1.0 / c)
        self.has_yield = hardness is not None
        self.sy = np.zeros(0)               # no yield wall
        if self.has_yield:
            from .fixed_point import yield_wall_on
            from ..plasticity.yield_wall import FAR_MASS, yield_wall_reach

            sy_dim = yield_wall_on(hardness, self.zeta)
            reach = float(yield_wall_reach(G_dim, np.zeros(1), sy_dim[None, :])[0])
            self.sy = np.full(n, np.inf) if reach <= FAR_MASS else sy_dim / scale
        # the adhesive wall: no kink detection, as in the fixed point of solve_contact
        self.variant = int(variant) | SMOOTH_WALL
        self.n_damp = int(n_damp)
        # one diffusion solve against the wall linear between the nodes (onset False): the
        # fixed point's own step (compiled or loaded already for solve_contact)
        self._grid = _solve_grid_tol
        self._kernel = callable_with(yield_step if self.has_yield else elastic_step,
                                     STEP_SIGNATURE, [(_solve_grid_tol, GRID_SIGNATURE)])
        self._out = [np.zeros(n) for _ in range(7)]
        self._absent = np.zeros(0)       # no yield wall: no plastic outputs
        self._counts = np.zeros(3, dtype=np.int64)
        self.solves = 0
        self.area = np.ones(n)           # real contact area A_el + A_pl of the last solve
        self.elastic = np.ones(n)        # its elastic part
        self.area_error = np.zeros(n)

    def sy_rows(self, n_rows):
        """The yield wall (scaled) as rows for :func:`persson_fast.adhesion.runner._run`, or None."""
        if not self.has_yield:
            return None
        return np.tile(self.sy, (n_rows, 1))

    def clip(self, x):
        """An iterate made admissible: sigma_a >= 0; corrected times from 0, non-decreasing."""
        x = np.array(x, dtype=float)
        n = self.n
        x[:n] = np.maximum(x[:n], 0.0)
        if self.corrected:
            t = np.maximum(x[n:], 0.0)
            t[0] = 0.0
            x[n:] = np.maximum.accumulate(t)
        return x

    def state(self, sigma_a, area):
        """The iterate of a detachment stress profile (scaled) and its real area profile: the
        corrected times of that area appended (a fixed point's times are those of its own
        area, :func:`persson_fast._kernels.adhesion.corrected_times`)."""
        x = np.array(sigma_a, dtype=float)
        if not self.corrected:
            return x
        t = np.empty(self.n)
        corrected_times(self.G, np.ascontiguousarray(area, dtype=float), self.theory_code,
                        self.theory_gamma, t)
        return np.concatenate([x, t])

    def carry(self, other, x):
        """An iterate of the branch ``other`` (another zeta grid of the same scene) carried
        to this grid: every part linear in ln zeta (sigma_a in Pa, t = T/G(zeta1) as it is,
        G(zeta1) being the scene's on every grid)."""
        lz, lo = np.log(self.zeta), np.log(other.zeta)
        parts = [np.interp(lz, lo, x[:other.n] * other.scale) / self.scale]
        if self.corrected:
            parts.append(np.interp(lz, lo, x[other.n:]))
        return self.clip(np.concatenate(parts))

    def update(self, elastic, real):
        """Eqs. 8-9 (the detachment stress, scaled) and, with a corrected theory, the
        corrected times of an area profile: ``elastic`` A_el, ``real`` A_el + A_pl."""
        n = self.n
        x = np.empty(2 * n if self.corrected else n)
        yield_detachment_update(np.ascontiguousarray(elastic), np.ascontiguousarray(real),
                                self.c, self.wa, self.wb, self.gamma_s, np.empty(n),
                                np.empty(n), x[:n])
        if self.corrected:
            corrected_times(self.G, np.ascontiguousarray(real), self.theory_code,
                            self.theory_gamma, x[n:])
        return x

    def inner_rtol(self, rtol, x):
        """Diffusion tolerance of a branch point at target ``rtol`` near the profile ``x``."""
        return _inner_rtol(rtol, (x[0] / self.c[0]) ** 2)

    def evaluate(self, x, sigma0, rtol):
        """F(x): diffuse against the wall x (in the times of x with a corrected theory,
        between the walls -x and sigma_Y with a yield wall) at nominal stress sigma0
        (scaled), then Eqs. 8-9 (and the corrected times of the result's area)."""
        area, load, pl, pl_load, det_a, det_l, err = self._out
        n = self.n
        x = np.ascontiguousarray(x, dtype=float)
        wall = np.ascontiguousarray(x[:n])
        times = np.ascontiguousarray(x[n:] * self.G[-1]) if self.corrected else self.G
        if self.has_yield:
            pl[:] = 0.0                  # left untouched where the yield wall is left out
            pl_load[:] = 0.0
            status = self._kernel(self._grid, self.variant, times, wall, wall, self.sy,
                                  float(sigma0), float(rtol), False, self.n_damp, area, load,
                                  pl, pl_load, det_a, det_l, err, self._counts)
        else:
            status = self._kernel(self._grid, self.variant, times, wall, wall, self._absent,
                                  float(sigma0), float(rtol), False, self.n_damp, area, load,
                                  self._absent, self._absent, det_a, det_l, err, self._counts)
        self.solves += 1
        self.elastic = area.copy()
        self.area = area + pl if self.has_yield else self.elastic
        self.area_error = err.copy()
        return self.update(self.elastic, self.area), int(status)

    def adhesion_at_one(self, area=None, area_error=None, elastic=None):
        """gamma_eff(1)/dgamma of an area profile (default: the last one evaluated) and its
        error bar from the diffusion solves' area error estimates. [-]

        g1 = (A(zeta1) - U_el(1)/dgamma) / A(1) (A the real area, U_el of the elastic area
        ``elastic``, which is ``area`` without a yield wall); an error dA_k of the profile
        moves it by at most (|dA(zeta1)| + sum_k (wa_k |dA_k| + wb_k |dA_k+1|) max|dF/dA|)
        / A(1), with F = A S(A) (max|dF/dA| = 1 for S = 1, at most 3 with the energy
        correction).
        """
        from .._kernels.adhesion import elastic_energy_ratio

        if area is None:
            a, el = self.area, self.elastic
        else:
            a = np.asarray(area, dtype=float)
            el = a if elastic is None else np.asarray(elastic, dtype=float)
        err = np.abs(self.area_error if area_error is None else np.asarray(area_error, float))
        if a[0] <= 0.0:
            return 0.0, 0.0
        u = np.empty(a.size)
        elastic_energy_ratio(np.ascontiguousarray(el), self.wa, self.wb, self.gamma_s, u)
        slope = 1.0 if self.gamma_s < 0.0 else 3.0
        g1 = (a[-1] - u[0]) / a[0]
        bar = (err[-1] + slope * float(np.sum(self.wa * err[:-1] + self.wb * err[1:]))) / a[0]
        return float(g1), float(bar)

    def _limit_step(self, step, reach):
        """``step`` scaled down so that it moves the wall at no node by more than ``reach``
        (the corrected times move with it: one Anderson direction)."""
        big = float(np.max(np.abs(step[:self.n]) / np.where(reach > 0.0, reach, np.inf)))
        return step / big if big > 1.0 else step

    def rest_state(self, x_start, rtol, *, m_hist, omega, max_iter):
        """Is there a contact state at p_nom = 0 near ``x_start`` (the scaled iterate)?

        Iterates Eqs. 8-9 at sigma0 = 0 (Anderson, the step limited to half the wall's
        value at each node so that no node is clipped to 0, plain relaxation once the
        iterate collapses) with the diffusion solves at ``_inner_rtol(rtol)``. Verdict:

        - False (not sticky): g1 = gamma_eff(1)/dgamma is below minus its error bar
          (:meth:`adhesion_at_one`) on ``PULL_OFF_COLLAPSE`` successive iterates while
          A(zeta1) falls, or A(zeta1) = 0 (the start is the separated state): sigma_a(1) = 0,
          the wall sits where the distribution starts and the iteration heads for A = 0;
        - True (sticky): the fixed-point residual (as in :meth:`point`) is below
          ``PULL_OFF_RESIDUAL * rtol`` and g1 is above its error bar;
        - None: neither within ``max_iter`` iterations.

        Where the sign of g1 is within its error bar, the next diffusion solve is 10x
        tighter (down to ``PULL_OFF_INNER_MIN``).

        Returns a dict (sticky, x, area, g1, g1_error, iterations, residual).
        """
        w = self.weights
        tol = max(PULL_OFF_RESIDUAL * rtol, 1e-13)
        inner = _inner_rtol(rtol)
        x = self.clip(x_start)
        history = _AndersonHistory(m_hist)
        collapse, a_prev = 0, np.inf
        verdict, res, g1, bar, it = None, np.inf, 0.0, 0.0, 0
        while it < max_iter:
            it += 1
            fx, status = self.evaluate(x, 0.0, inner)
            if status in (NONFINITE, BAD_INPUT):
                break
            a1 = float(self.area[-1])
            g1, bar = self.adhesion_at_one()
            if a1 <= 0.0:
                verdict = False
                break
            f = fx - x
            res = float(np.max(np.abs(f) * w))
            if not np.isfinite(res):
                break
            collapse = collapse + 1 if (g1 + bar < 0.0 and a1 < a_prev) else 0
            a_prev = a1
            if abs(g1) <= bar:
                # the sign of gamma_eff(1) is within the diffusion error: solve tighter
                inner = max(0.1 * inner, PULL_OFF_INNER_MIN)
            if collapse >= PULL_OFF_COLLAPSE:
                verdict = False
                break
            if res <= tol and g1 - bar > 0.0:
                verdict = True
                break
            if collapse:
                # plain relaxation: sigma_a(1) falls by the factor 1 - omega, never to 0
                history.reset()
                x = self.clip(x + omega * f)
                continue
            step = history.step(x, f, w, omega)
            step = self._limit_step(step, PULL_OFF_TRUST * np.maximum(x[:self.n], x[0]))
            x = self.clip(x + step)
        return {"sticky": verdict, "x": x.copy(), "area": self.area.copy(), "g1": g1,
                "g1_error": bar, "iterations": it, "residual": res}

    def point(self, y0, x_start, rtol, *, m_hist, omega, trust, max_iter):
        """Branch point at y0 [Pa]: Anderson-accelerated fixed point with a trust region.

        Returns a dict (y0, sigma0 [Pa], x (the scaled iterate), area (the real area
        profile), status, iterations, residual, converged). A point that converges with its
        last diffusion solve flagged FAR_LEAK goes on once with that tolerance
        ``PULL_OFF_LEAK_RETRY`` times tighter.
        """
        y = y0 / self.scale
        w = self.weights
        n = self.n
        x = self.clip(x_start)
        tol = max(PULL_OFF_RESIDUAL * rtol, 1e-13)
        inner = self.inner_rtol(rtol, x)
        res = np.inf
        best = best_mark = np.inf
        x_best = f_best = None
        it_mark = 0
        final = False
        leak_retried = False
        lost = 0
        history = _AndersonHistory(m_hist)
        status = 0
        it = 0
        out = None
        r_it = 1e-3
        while it < max_iter:
            it += 1
            # early iterations solve the diffusion loosely; the tolerance only tightens, so
            # that the grid of the diffusion solve (and with it F) stops changing near the end
            r_it = min(r_it, PULL_OFF_EARLY * res)
            if r_it < inner or final:
                r_it = inner
            fx, status = self.evaluate(x, y - x[0], r_it)
            if status in (NONFINITE, BAD_INPUT):
                break
            if self.has_yield and status in STRIP_UNRESOLVED:
                break
            f = fx - x
            res = float(np.max(np.abs(f) * w))
            if not np.isfinite(res):
                break
            if res < best:
                if res < 0.5 * best_mark:
                    best_mark, it_mark = res, it
                best, x_best, f_best = res, x, f
            if it - it_mark > PULL_OFF_STALL:
                break
            if res > PULL_OFF_BLOWUP * best and not final:
                # the step left the region where the map is near-linear: back to the best
                # iterate, forget the history, relax more
                omega = max(0.5 * omega, 0.1)
                trust = max(0.5 * trust, 0.05)
                history.reset()
                x = self.clip(x_best + omega * f_best)
                continue
            # the branch is lost when the contact vanishes or sigma_a(1) does
            lost = lost + 1 if (self.area[-1] <= 0.0 or fx[0] <= 0.0) else 0
            if lost >= 3:
                break
            if res <= tol:
                if r_it == inner:
                    if (status == FAR_LEAK and not leak_retried
                            and inner > PULL_OFF_INNER_MIN):
                        # the far end of the diffusion grid reached: once more, tighter
                        leak_retried = True
                        inner = max(PULL_OFF_LEAK_RETRY * inner, PULL_OFF_INNER_MIN)
                        final = True
                    else:
                        out = x
                        break
                else:
                    final = True        # converged on a loose inner solve: confirm
            step = history.step(x, f, w, omega)
            step = self._limit_step(step, trust * np.maximum(y + x[:n] - x[0], y))
            x = self.clip(x + step)
        converged = out is not None
        return {"y0": float(y0), "sigma0": float((y - x[0]) * self.scale), "x": x.copy(),
                "area": self.area.copy(), "area_error": self.area_error.copy(),
                "status": status, "iterations": it, "residual": res, "converged": converged,
                "flag_error": self.flag_error(status)}

    def flag_error(self, status):
        """Error of sigma0 [Pa] charged for a last diffusion solve flagged RTOL_NOT_MET or
        GRID_CAP (refined to its work cap or its node cap).

        Such a solve still returns its best area profile and its error estimate; the
        estimate moves gamma_eff(1)/dgamma = g1 by its error bar (:meth:`adhesion_at_one`),
        and sigma_a(1) = c_1 g1^(1/2) (so sigma0 = y0 - sigma_a(1) at fixed y0) by the
        corresponding interval, doubled for the fixed point's response. 0 when not flagged.
        """

        if status not in (RTOL_NOT_MET, GRID_CAP):
            return 0.0
        g1, bar = self.adhesion_at_one()
        lo, hi = np.sqrt(max(g1 - bar, 0.0)), np.sqrt(max(g1 + bar, 0.0))
        return float(2.0 * self.c[0] * self.scale * (hi - lo))

    def follow(self, y0, starts, rtol, controls):
        """Branch point at y0 from the first start that converges (normal, then cautious)."""
        m_hist, omega = controls["m_hist"], controls["omega"]
        tries = [(m_hist, omega, PULL_OFF_TRUST), (min(m_hist, 3), *PULL_OFF_RETRY)]
        iterations = 0
        for x_start in starts:
            for m, om, tr in tries:
                p = self.point(y0, x_start, rtol, m_hist=m, omega=om, trust=tr,
                               max_iter=controls["max_iter"])
                iterations += p["iterations"]
                if p["converged"]:
                    p["iterations"] = iterations
                    return p
                if self.has_yield and p["status"] in STRIP_UNRESOLVED:
                    break               # the solver's limit, not the iteration's
        p["iterations"] = iterations
        return p

def _rest_start(branch, rtol, controls, gamma_s, variant, x_start=None,
                max_iter=PULL_OFF_REST_ITER):
    """The contact state at p_nom = 0 on one grid and whether it is sticky.

    Without ``x_start`` the compiled fixed point is solved at p_nom = 0 from full contact
    (as :func:`persson_fast.solve_contact` does). Its state is sticky when A(zeta1) > 0 and
    g1 = gamma_eff(1)/dgamma exceeds its error bar (:meth:`_Branch.adhesion_at_one`); not
    sticky when A(zeta1) = 0; otherwise :meth:`_Branch.rest_state` decides from it (or
    from ``x_start``) within ``max_iter`` iterations. The compiled fixed point measures its
    residual against the largest sigma_a (at zeta1, ~sqrt(zeta1) c_1), so it stops with a
    sigma_a(1) that can be wrong by far more than itself: at seed Delta gamma = 0.04 and
    rtol 1e-3 it returned sigma_a(1) = 16 Pa and A(zeta1) = 1.25e-7 while F(x) had
    sigma_a(1) = 0 (gamma_eff(1) < 0), a state on its way to A = 0.

    Returns a dict: sticky (True, False or None: undecided), x (the scaled iterate to start
    the descent from: sigma_a, and the corrected times with a corrected theory), summary (n_zeta, area = A(zeta1)/A0, sigma_a_1 [Pa], gamma_eff_1 and
    gamma_eff_1_error [J/m^2] = g1 dgamma and its error bar, sticky, iterations).
    """

    iterations = 0
    if x_start is None:
        inner = _inner_rtol(rtol)
        for _ in range(PULL_OFF_REST_RETRIES + 1):
            outs, status, its, _, _ = _run(branch.G, branch.c, branch.wa, branch.wb, gamma_s,
                                           np.array([0.0]), inner, False, controls, None,
                                           variant, onset=False, theory=branch.theory_code,
                                           theory_gamma=branch.theory_gamma,
                                           sy=branch.sy_rows(1))
            branch.solves += 1
            iterations += int(its[0])
            if (status[0] in (0, WALL_JUMP, RTOL_NOT_MET, NONFINITE, BAD_INPUT)
                    or inner <= PULL_OFF_INNER_MIN):
                break
            # a resolution flag of a loose solve (e.g. the far end of the grid reached):
            # again with a tighter tolerance
            inner = max(0.1 * inner, PULL_OFF_INNER_MIN)
        if status[0] not in (0, WALL_JUMP, RTOL_NOT_MET, NOT_CONVERGED):
            raise RuntimeError(f"pull_off: the contact problem failed at p_nom = 0 Pa "
                               f"({summarize_status(status)[1]}); try a smaller rtol or a "
                               f"finer zeta grid")
        area = outs[0][0].copy()                 # the real area (A_el + A_pl)
        elastic = area - outs[8][0] if branch.has_yield else area
        x = branch.state(outs[1][0], area)
        g1, bar = branch.adhesion_at_one(area, outs[7][0], elastic)
        if status[0] == NOT_CONVERGED:
            # the compiled fixed point stopped short (seen with a yield wall at tight
            # tolerances): its last iterate starts the branch's own iteration, which decides
            sticky = None
        elif area[-1] <= 0.0 or x[0] <= 0.0:
            sticky = False
        elif g1 - bar > 0.0:
            sticky = True
        else:
            sticky = None
    else:
        x, sticky = branch.clip(x_start), None
    if sticky is None:
        r = branch.rest_state(x, rtol, m_hist=controls["m_hist"], omega=controls["omega"],
                              max_iter=max_iter)
        iterations += r["iterations"]
        sticky, area, g1, bar = r["sticky"], r["area"], r["g1"], r["g1_error"]
        if sticky:
            x = r["x"]
    dg = branch.work_of_adhesion
    summary = {"n_zeta": int(branch.zeta.size), "area": float(area[-1]),
               "sigma_a_1": float(x[0] * branch.scale), "gamma_eff_1": float(g1 * dg),
               "gamma_eff_1_error": float(bar * dg), "sticky": sticky,
               "iterations": iterations}
    return {"sticky": sticky, "x": x, "summary": summary}


def _inner_factor(rtol):
    """f(rtol) of the branch points' diffusion tolerance (see PULL_OFF_INNER)."""
    lo, hi = PULL_OFF_INNER_RTOLS
    if rtol <= lo:
        return PULL_OFF_INNER
    if rtol >= hi:
        return PULL_OFF_INNER_LOOSE
    t = np.log(rtol / lo) / np.log(hi / lo)
    return float(PULL_OFF_INNER * (PULL_OFF_INNER_LOOSE / PULL_OFF_INNER) ** t)


def _inner_rtol(rtol, g1=1.0):
    """Tolerance of the diffusion solves inside a branch point at target ``rtol``, where
    gamma_eff(1)/dgamma is about ``g1`` (see PULL_OFF_INNER)."""
    return max(_inner_factor(rtol) * rtol * min(1.0, 2.0 * g1), PULL_OFF_INNER_MIN)


def _tail_estimate(d_last, d_prev):
    """Remaining change of sigma0 as y0 -> 0, from the last two stage differences [Pa].

    The differences shrink at least geometrically with the observed ratio, and the model
    is not trusted beyond quadratic convergence in y0 (ratio 1/PULL_OFF_STEP^2).
    """
    if d_last == 0.0:
        return 0.0
    if d_prev == 0.0 or not np.isfinite(d_prev):
        return np.inf
    q = max(abs(d_last / d_prev), PULL_OFF_STEP ** -2)
    return np.inf if q >= 1.0 else abs(d_last) * q / (1.0 - q)


def _predict(samples, y0):
    """Start profile at y0: linear extrapolation in y0 from the last two branch points."""
    if len(samples) < 2:
        return samples[-1]["x"]
    a, b = samples[-2], samples[-1]
    t = (y0 - b["y0"]) / (b["y0"] - a["y0"])
    return np.maximum(b["x"] + t * (b["x"] - a["x"]), 0.0)


def _stage_rtol(samples, rtol):
    """Tolerance of the next stage: loose while sigma0 still changes a lot per stage."""
    ok = [s for s in samples if s["converged"]]
    if len(ok) < 2:
        return max(rtol, min(1e-3, 1e3 * rtol))
    d = abs(ok[-1]["sigma0"] - ok[-2]["sigma0"]) / max(abs(ok[-1]["sigma0"]), 1e-300)
    return max(rtol, min(1e-3, PULL_OFF_LOOSE * d))


def _descend(branch, x_start, y_start, rtol, controls):
    """Follow the contact branch from y_start down in y0 to where sigma0(y0) is least.

    Early stages, where sigma0 still changes by much more than the tolerance per stage, run
    at a looser tolerance; the points the result depends on are refreshed at ``rtol``.

    Returns (samples, y_best, tail, fold, lost): the branch points in the order computed,
    the y0 of the least sigma0 (an interior minimum located by parabolic steps in ln y0, or
    the last point where sigma0 has stopped falling), the estimated change of sigma0 still
    to come [Pa] (beyond the last point as y0 -> 0, or what the last parabola predicted
    below the best point), whether an interior minimum was found, and whether the branch
    was lost (a branch point failed) before either.
    """
    samples = []
    p = branch.follow(y_start, [x_start], _stage_rtol(samples, rtol), controls)
    p["rtol"] = _stage_rtol(samples, rtol)
    samples.append(p)
    if not p["converged"]:
        return samples, y_start, np.inf, False, True
    y = y_start
    lost = False
    for _ in range(PULL_OFF_MAX_STAGES):
        rt = _stage_rtol(samples, rtol)
        y_new = y / PULL_OFF_STEP
        p = branch.follow(y_new, [_predict(samples, y_new), samples[-1]["x"]], rt, controls)
        if not p["converged"]:
            y_new = y / np.sqrt(PULL_OFF_STEP)          # one half step before giving up
            p = branch.follow(y_new, [samples[-1]["x"]], rt, controls)
        p["rtol"] = rt
        samples.append(p)
        if not p["converged"]:
            lost = True
            break
        y = y_new
        if rt > rtol:
            continue
        ok = [s for s in samples if s["converged"]]
        s_min = min(s["sigma0"] for s in ok)
        tol_s = PULL_OFF_TAIL * rtol * abs(s_min)
        if p["sigma0"] > s_min + tol_s:
            _refresh(branch, samples, rtol, controls, 3)
            y_best, remaining = _locate_minimum(branch, samples, rtol, controls, tol_s)
            return samples, y_best, remaining, True, False
        if len(ok) >= 3:
            _refresh(branch, samples, rtol, controls, 3)
            ok = [s for s in samples if s["converged"]]
            tail = _tail_estimate(ok[-1]["sigma0"] - ok[-2]["sigma0"],
                                  ok[-2]["sigma0"] - ok[-3]["sigma0"])
            if tail <= tol_s:
                return samples, min(ok, key=lambda s: s["sigma0"])["y0"], tail, False, False
    _refresh(branch, samples, rtol, controls, 3)
    ok = [s for s in samples if s["converged"]]
    tail = np.inf
    if len(ok) >= 3:
        tail = _tail_estimate(ok[-1]["sigma0"] - ok[-2]["sigma0"],
                              ok[-2]["sigma0"] - ok[-3]["sigma0"])
    return samples, min(ok, key=lambda s: s["sigma0"])["y0"], tail, False, lost


def _refresh(branch, samples, rtol, controls, count):
    """Re-solve at ``rtol`` the last ``count`` converged points that ran looser."""
    idx = [i for i, s in enumerate(samples) if s["converged"]][-count:]
    for i in idx:
        s = samples[i]
        if s.get("rtol", rtol) > rtol:
            p = branch.follow(s["y0"], [s["x"]], rtol, controls)
            p["rtol"] = rtol
            if p["converged"]:
                samples[i] = p


def _locate_minimum(branch, samples, rtol, controls, tol_s):
    """Parabolic steps in ln y0 to the interior minimum of sigma0(y0).

    Returns (y0 of the least sigma0 found, the improvement the last parabola still
    predicted beyond it [Pa]).
    """
    remaining = tol_s
    for _ in range(PULL_OFF_MAX_FOLD_STEPS):
        ok = sorted((s for s in samples if s["converged"]), key=lambda s: s["y0"])
        k = min(range(len(ok)), key=lambda i: ok[i]["sigma0"])
        if k == 0 or k == len(ok) - 1:
            break
        u = np.log([ok[k - 1]["y0"], ok[k]["y0"], ok[k + 1]["y0"]])
        s = np.array([ok[k - 1]["sigma0"], ok[k]["sigma0"], ok[k + 1]["sigma0"]])
        d1 = (s[1] - s[0]) / (u[1] - u[0])
        d2 = (s[2] - s[1]) / (u[2] - u[1])
        curv = (d2 - d1) / (u[2] - u[0])
        if curv <= 0.0:
            break
        u_v = 0.5 * (u[0] + u[1]) - d1 / (2.0 * curv)
        s_v = s[0] + d1 * (u_v - u[0]) + curv * (u_v - u[0]) * (u_v - u[1])
        remaining = max(s[1] - s_v, 0.0)
        if remaining <= 0.1 * tol_s:
            break
        # keep the new point away from the old ones (golden-section safeguard)
        lo, hi = u[0], u[2]
        u_v = min(max(u_v, lo + 0.1 * (u[1] - lo)), hi - 0.1 * (hi - u[1]))
        if abs(u_v - u[1]) < 0.05 * (hi - lo):
            u_v = u[1] + 0.382 * ((hi if hi - u[1] > u[1] - lo else lo) - u[1])
        nearest = min(ok, key=lambda p: abs(np.log(p["y0"]) - u_v))
        p = branch.follow(float(np.exp(u_v)), [nearest["x"]], rtol, controls)
        p["rtol"] = rtol
        samples.append(p)
        if not p["converged"]:
            break
    ok = [s for s in samples if s["converged"]]
    return min(ok, key=lambda s: s["sigma0"])["y0"], remaining


def _replay(branch, targets, x_start, rtol, controls):
    """Branch points of a finer grid at the given y0 (descending), from ``x_start``, an
    iterate on this grid (e.g. a coarser grid's carried over, :meth:`_Branch.carry`)."""
    x = x_start
    points = []
    for y0 in targets:
        p = branch.follow(y0, [x] if not points else [points[-1]["x"], x], rtol, controls)
        points.append(p)
        if p["converged"]:
            x = p["x"]
    return points
