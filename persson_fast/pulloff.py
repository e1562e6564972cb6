"""The pull-off stress: the contact branch of one adhesive scene followed to its end.

:func:`pull_off` follows the contact branch parametrised by y0 = sigma0 + sigma_a(1) (at
fixed sigma0 the fixed point of seed Eqs. 8-9 is nearly singular along the flat end of the
branch; at fixed y0 it is regular), with a fixed-point loop in Python around the compiled
diffusion solve (one scene, a few dozen branch points: the loop is not the cost), on nested
zeta grids with Richardson extrapolation.
"""
from __future__ import annotations

import time

import numpy as np

from ._kernels.adhesion import detachment_update
from ._kernels.status import RTOL_NOT_MET, WALL_JUMP
from .adhesion import _controls, _run, solve_adhesive_contact
from ._kernels.similarity import SMOOTH_WALL
from .methods import choose_auto, variant_of
from .results import summarize_status
from .scene import DETACHMENT_PREFACTOR
from .zeta_grid import NEAR_ONE_MIN, _scene_arrays, adhesion_zeta, refine_zeta

__all__ = ["pull_off"]

#: ratio of successive y0 = sigma0 + sigma_a(1) on the descent along the contact branch
PULL_OFF_STEP = 2.0
#: the descent stops once its tail estimate is below this fraction of rtol * sigma_c
PULL_OFF_TAIL = 0.25
#: diffusion tolerance of the branch points: PULL_OFF_INNER * rtol * min(1, 2 g1), g1 =
#: gamma_eff(1)/dgamma = (sigma_a(1)/c_1)^2, and at least PULL_OFF_INNER_MIN. sigma_a(1) =
#: c_1 g1^(1/2) moves by dA/(2 g1) relative for an error dA of the area profile, and
#: measured at the end of the seed scene's branch (2 g1 = 0.2) one application of Eqs. 8-9
#: moved sigma_a(1) by up to 7x the diffusion tolerance (1.5 Pa at 3e-7; 0.1 Pa between
#: 3e-8 and 3e-10); the factor keeps that at about 0.35 rtol. Since the cn kernel reports the
#: error of its extrapolated value (about 2x the actual error, no longer a large over-
#: estimate) it stops at a coarser grid for the same tolerance: 0.25 left the seed's inner
#: error at 0.78 Pa (1.0e-6 sigma_c) at rtol 1e-6, 0.05 brings it to the 5e-7 floor
PULL_OFF_INNER = 0.05
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
#: nested zeta grids: at least 3 (two Richardson values to compare), at most this many
PULL_OFF_MAX_GRIDS = 5
#: the inner-solve error is measured by re-solving the end point with a tolerance this
#: factor tighter (looser where that would pass PULL_OFF_INNER_MIN); it is never taken below
#: PULL_OFF_INNER_FLOOR * sigma_c: the diffusion kernel's result does not converge
#: monotonically in its tolerance (one application of Eqs. 8-9 at the end of the seed
#: scene's branch scattered by +-0.11 Pa of 7.8e5 Pa between tolerances 3e-8 and 3e-10, and
#: the branch's end moved by 0.64 Pa between 1.25e-8 and 3.1e-9), so one comparison can
#: come out small by chance
PULL_OFF_INNER_CHECK = 4.0
PULL_OFF_INNER_FLOOR = 5e-7
#: weight of the error of a branch point flagged RTOL_NOT_MET in sigma_c (|4/3| + |1/3|,
#: its largest weight in a Richardson value)
PULL_OFF_FLAG_WEIGHT = 5.0 / 3.0
#: resolution of the optional bracket of where solve_contact stops finding contact
PULL_OFF_BRACKET_RTOL = 1e-4
#: early stages run at this fraction of their relative change of sigma0 (at most 1e-3)
PULL_OFF_LOOSE = 0.01
#: the near-one points of the pull-off grids reach down to where sqrt(G) is this fraction
#: of the full-contact sigma_a(1) (never below zeta - 1 = PULL_OFF_NEAR_FLOOR): the layer
#: near the end of the branch sits at sqrt(G) ~ y0 / 20 and y0 ~ 1e-4 sigma_a(1) there
PULL_OFF_NEAR_STRESS = 1e-6
PULL_OFF_NEAR_FLOOR = 1e-14
#: the finer grids are solved at y0 = y_best * PULL_OFF_STEP**PULL_OFF_GRID_STAGES
PULL_OFF_GRID_STAGES = 2
#: stickiness (see :func:`_rest_state`): iterating Eqs. 8-9 at p_nom = 0, the state is not
#: sticky once gamma_eff(1)/dgamma lies below minus its error bar on this many successive
#: iterates while A(zeta1) falls (the iteration is on its way to the separated state A = 0)
PULL_OFF_COLLAPSE = 3
#: iterations of that test before it gives up undecided (the descent then decides)
PULL_OFF_REST_ITER = 30
#: a scene counts as not sticky only when it is not sticky on this many nested zeta grids
#: (the coarsest and its refinements, the fewest pull_off extrapolates over): the threshold
#: work of adhesion falls with the grid spacing at second order (seed scene: 0.052176,
#: 0.051903, 0.051833, 0.051816, 0.051811 J/m^2 at 5, 10, 20, 40, 80 points per decade)
PULL_OFF_STICKY_GRIDS = 3


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
    """

    def __init__(self, surface, zeta, e_star, work_of_adhesion, beta, gamma_s, variant, n_damp):
        from ._kernels.sweep import sweep_serial

        self.zeta = np.asarray(zeta, dtype=float)
        self.work_of_adhesion = float(work_of_adhesion)
        G, c, wa, wb, scale, _ = _scene_arrays(surface, self.zeta, e_star, work_of_adhesion, beta)
        self.G, self.c, self.wa, self.wb, self.scale = G, c, wa, wb, scale
        self.gamma_s = gamma_s
        # the adhesive wall: no kink detection, as in the fixed point of solve_contact
        self.variant = int(variant) | SMOOTH_WALL
        self.n_damp = int(n_damp)
        self._kernel = sweep_serial
        n = self.zeta.size
        self._out = [np.zeros((1, n)) for _ in range(5)]
        self._status = np.zeros(1, dtype=np.int64)
        self._counts = np.zeros((1, 3), dtype=np.int64)
        self.solves = 0
        self.area = np.ones(n)
        self.area_error = np.zeros(n)

    def update(self, area):
        """Eqs. 8-9: the detachment stress (scaled) of an area profile."""
        n = area.size
        x = np.empty(n)
        detachment_update(area, self.c, self.wa, self.wb, self.gamma_s, np.empty(n),
                          np.empty(n), x)
        return x

    def inner_rtol(self, rtol, x):
        """Diffusion tolerance of a branch point at target ``rtol`` near the profile ``x``."""
        return _inner_rtol(rtol, (x[0] / self.c[0]) ** 2)

    def evaluate(self, x, sigma0, rtol):
        """F(x): diffuse against the wall x at nominal stress sigma0 (scaled), then Eqs. 8-9."""
        area, load, det_a, det_l, err = self._out
        self._kernel(self.variant, self.G, x[None, :], np.array([sigma0]), float(rtol), -1,
                     self.n_damp, area, load, det_a, det_l, err, self._status, self._counts)
        self.solves += 1
        self.area = area[0].copy()
        self.area_error = err[0].copy()
        return self.update(self.area), int(self._status[0])

    def adhesion_at_one(self, area=None, area_error=None):
        """gamma_eff(1)/dgamma of an area profile (default: the last one evaluated) and its
        error bar from the diffusion solves' area error estimates. [-]

        g1 = (A(zeta1) - U_el(1)/dgamma) / A(1); an error dA_k of the profile moves it by at
        most (|dA(zeta1)| + sum_k (wa_k |dA_k| + wb_k |dA_k+1|) max|dF/dA|) / A(1), with
        F = A S(A) (max|dF/dA| = 1 for S = 1, at most 3 with the energy correction).
        """
        from ._kernels.adhesion import elastic_energy_ratio

        a = self.area if area is None else np.asarray(area, dtype=float)
        err = np.abs(self.area_error if area_error is None else np.asarray(area_error, float))
        if a[0] <= 0.0:
            return 0.0, 0.0
        u = np.empty(a.size)
        elastic_energy_ratio(a, self.wa, self.wb, self.gamma_s, u)
        slope = 1.0 if self.gamma_s < 0.0 else 3.0
        g1 = (a[-1] - u[0]) / a[0]
        bar = (err[-1] + slope * float(np.sum(self.wa * err[:-1] + self.wb * err[1:]))) / a[0]
        return float(g1), float(bar)

    def rest_state(self, x_start, rtol, *, m_hist, omega, max_iter):
        """Is there a contact state at p_nom = 0 near ``x_start`` (scaled sigma_a)?

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
        from ._kernels.status import BAD_INPUT, NONFINITE

        w = 1.0 / self.c
        tol = max(PULL_OFF_RESIDUAL * rtol, 1e-13)
        inner = _inner_rtol(rtol)
        x = np.maximum(np.array(x_start, dtype=float), 0.0)
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
                x = x + omega * f
                continue
            step = history.step(x, f, w, omega)
            reach = PULL_OFF_TRUST * np.maximum(x, x[0])
            big = float(np.max(np.abs(step) / np.where(reach > 0.0, reach, np.inf)))
            if big > 1.0:
                step = step / big
            x = np.maximum(x + step, 0.0)
        return {"sticky": verdict, "x": x.copy(), "area": self.area.copy(), "g1": g1,
                "g1_error": bar, "iterations": it, "residual": res}

    def point(self, y0, x_start, rtol, *, m_hist, omega, trust, max_iter):
        """Branch point at y0 [Pa]: Anderson-accelerated fixed point with a trust region.

        Returns a dict (y0, sigma0 [Pa], x (scaled sigma_a), area, status, iterations,
        residual, converged).
        """
        from ._kernels.status import BAD_INPUT, NONFINITE

        y = y0 / self.scale
        w = 1.0 / self.c
        x = np.maximum(np.array(x_start, dtype=float), 0.0)
        tol = max(PULL_OFF_RESIDUAL * rtol, 1e-13)
        inner = self.inner_rtol(rtol, x)
        res = np.inf
        best = best_mark = np.inf
        x_best = f_best = None
        it_mark = 0
        final = False
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
                x = np.maximum(x_best + omega * f_best, 0.0)
                continue
            # the branch is lost when the contact vanishes or sigma_a(1) does
            lost = lost + 1 if (self.area[-1] <= 0.0 or fx[0] <= 0.0) else 0
            if lost >= 3:
                break
            if res <= tol:
                if r_it == inner:
                    out = x
                    break
                final = True        # converged on a loose inner solve: confirm
            step = history.step(x, f, w, omega)
            reach = trust * np.maximum(y + x - x[0], y)
            big = float(np.max(np.abs(step) / reach))
            if big > 1.0:
                step = step / big
            x = np.maximum(x + step, 0.0)
        converged = out is not None
        return {"y0": float(y0), "sigma0": float((y - x[0]) * self.scale), "x": x.copy(),
                "area": self.area.copy(), "area_error": self.area_error.copy(),
                "status": status, "iterations": it, "residual": res, "converged": converged,
                "flag_error": self.flag_error(status)}

    def flag_error(self, status):
        """Error of sigma0 [Pa] charged for a last diffusion solve flagged RTOL_NOT_MET.

        Such a solve still returns its best area profile and its error estimate; the
        estimate moves gamma_eff(1)/dgamma = g1 by its error bar (:meth:`adhesion_at_one`),
        and sigma_a(1) = c_1 g1^(1/2) (so sigma0 = y0 - sigma_a(1) at fixed y0) by the
        corresponding interval, doubled for the fixed point's response. 0 when not flagged.
        """

        if status != RTOL_NOT_MET:
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
        p["iterations"] = iterations
        return p


def _near_one_min(surface, e_star, work_of_adhesion, beta):
    """Smallest zeta - 1 of the near-one points of the pull-off grids. [-]

    Close to pull-off an absorbing layer forms where sqrt(G) is a small fraction of
    y0 = sigma0 + sigma_a(1), and y0 at the end of the branch is a small fraction of
    sigma_a(1); the near-one points must reach down to where sqrt(G) is
    ``PULL_OFF_NEAR_STRESS`` times the full-contact sigma_a(1) (at most ``NEAR_ONE_MIN``).
    """
    target = PULL_OFF_NEAR_STRESS * beta * np.sqrt(work_of_adhesion * e_star * surface.q0)
    lo, hi = np.log(PULL_OFF_NEAR_FLOOR), np.log(NEAR_ONE_MIN)

    def root_g(log_d):
        q = surface.q0 * (1.0 + np.exp(log_d))
        return float(np.sqrt(max(float(surface.diffusion_time(q, e_star)), 0.0)))

    if root_g(hi) <= target:
        return NEAR_ONE_MIN
    if root_g(lo) >= target:
        return PULL_OFF_NEAR_FLOOR
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if root_g(mid) > target:
            hi = mid
        else:
            lo = mid
    return float(np.exp(lo))


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

    Returns a dict: sticky (True, False or None: undecided), x (scaled sigma_a to start
    the descent from), summary (n_zeta, area = A(zeta1)/A0, sigma_a_1 [Pa], gamma_eff_1 and
    gamma_eff_1_error [J/m^2] = g1 dgamma and its error bar, sticky, iterations).
    """

    iterations = 0
    if x_start is None:
        outs, status, its, _, _ = _run(branch.G, branch.c, branch.wa, branch.wb, gamma_s,
                                       np.array([0.0]), _inner_rtol(rtol), False, controls,
                                       None, variant, onset=False)
        branch.solves += 1
        iterations += int(its[0])
        if status[0] not in (0, WALL_JUMP, RTOL_NOT_MET):
            raise RuntimeError(f"pull_off: the contact problem failed at p_nom = 0 Pa "
                               f"({summarize_status(status)[1]}); try a smaller rtol or a "
                               f"finer zeta grid")
        x, area = outs[1][0].copy(), outs[0][0].copy()
        g1, bar = branch.adhesion_at_one(area, outs[7][0])
        if area[-1] <= 0.0 or x[0] <= 0.0:
            sticky = False
        elif g1 - bar > 0.0:
            sticky = True
        else:
            sticky = None
    else:
        x, sticky = np.array(x_start, dtype=float), None
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


def _inner_rtol(rtol, g1=1.0):
    """Tolerance of the diffusion solves inside a branch point at target ``rtol``, where
    gamma_eff(1)/dgamma is about ``g1`` (see PULL_OFF_INNER)."""
    return max(PULL_OFF_INNER * rtol * min(1.0, 2.0 * g1), PULL_OFF_INNER_MIN)


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


def _replay(branch, targets, x_dim_start, rtol, controls):
    """Branch points of a finer grid at the given y0 (descending), from a coarser profile."""
    x = x_dim_start / branch.scale
    points = []
    for y0 in targets:
        p = branch.follow(y0, [x] if not points else [points[-1]["x"], x], rtol, controls)
        points.append(p)
        if p["converged"]:
            x = p["x"]
    return points


def _interp_profile(zeta_to, zeta_from, x_dim):
    """A detachment-stress profile [Pa] carried to another grid (linear in ln zeta)."""
    return np.interp(np.log(zeta_to), np.log(zeta_from), x_dim)


def _solver_bracket(surface, z, e, dg, energy_correction, beta, rtol, controls, upper):
    """Where :func:`solve_adhesive_contact` on the grid ``z`` stops finding contact.

    Bisection in the tension between 0 and ``upper`` [Pa], each solve continuing from the
    contact state at the nearest tension with contact. Returns ((lo, hi), solves): contact
    found at tension lo, none at hi [Pa].
    """

    solves = 0

    def contact(sigma0, start):
        nonlocal solves
        r = solve_adhesive_contact(surface, np.array([sigma0]), z, e_star=e, work_of_adhesion=dg,
                                   energy_correction=energy_correction,
                                   detachment_prefactor=beta, rtol=rtol, parallel=False,
                                   controls=controls, zeta_given=True, start=start,
                                   onset=False)
        solves += 1
        if r.status[0] not in (0, WALL_JUMP, RTOL_NOT_MET):
            return False, r
        return r.area[0] > 0, r

    has, r_hi = contact(0.0, None)
    hi, lo = 0.0, -upper
    tol = max(rtol, PULL_OFF_BRACKET_RTOL)
    while hi - lo > tol * max(abs(lo), abs(hi)):
        mid = 0.5 * (lo + hi)
        has, r = contact(mid, r_hi.sigma_a)
        if has:
            hi, r_hi = mid, r
        else:
            lo = mid
    return (float(-hi), float(-lo)), solves


def pull_off(surface, *, e_star=None, work_of_adhesion=None, energy_correction=None,
             detachment_prefactor=DETACHMENT_PREFACTOR, rtol=1e-6, zeta=None, controls=None,
             full_output=False, bracket=True):
    """Pull-off stress of a nominally flat contact: contact exists for p_nom > -sigma_c. [Pa]

    Parameters
    ----------
    surface : Surface or Scene
        The rough surface, or a :class:`~persson_fast.Scene` that carries it with the scene's
        parameters (the keywords below then stay unset).
    e_star : float
        Effective modulus E* > 0 (required with a surface). [Pa]
    work_of_adhesion : float
        Delta gamma >= 0 (required with a surface). [J/m^2]
    energy_correction, detachment_prefactor
        As in :func:`persson_fast.solve_contact`.
    rtol : float
        Relative accuracy of sigma_c. [-]
    zeta : array_like, optional
        The coarsest of the nested magnification grids; the others are its refinements
        (:func:`refine_zeta`); from 1 to zeta1 = q1/q0, as in
        :func:`persson_fast.solve_contact`. Default: :func:`adhesion_zeta` at ``rtol`` with
        its points near zeta = 1 extended down to :func:`_near_one_min`. Where the scene is
        not sticky on it, its refinements are tried (see Notes). [-]
    controls : dict, optional
        Fixed-point controls (see :data:`ADHESION_DEFAULTS`); ``max_iter`` defaults to
        ``PULL_OFF_MAX_ITER`` here.
    full_output : bool
        Also return a dict of diagnostics (see Returns).
    bracket : bool
        With ``full_output``, also bisect for where :func:`persson_fast.solve_contact` on the
        default grid stops finding contact (``info["bracket"]``; costs about 15 solves).

    Returns
    -------
    sigma_c : float
        Pull-off stress, >= 0; 0 when the surfaces are not sticky (see Notes). [Pa]
    info : dict
        Only with ``full_output``:

        - ``sticky``: whether the surfaces stick at p_nom = 0 (see Notes); ``reason``: why
          sigma_c = 0 where they do not (``error_estimate`` 0 and ``converged`` True there);
          ``rest``: per zeta grid tried, the state at p_nom = 0 (``n_zeta``, ``area`` =
          A(zeta1)/A0, ``sigma_a_1`` [Pa], ``gamma_eff_1`` and ``gamma_eff_1_error``
          [J/m^2], ``sticky`` True, False or None (undecided), ``iterations``);

        - ``error_estimate`` [Pa]: estimated error of sigma_c, the sum of ``error_parts``:
          ``zeta_grid`` (difference of the last two Richardson values at ``y0_grids``),
          ``end_zeta_grid`` (zeta-grid error of the branch's change from ``y0_grids`` to its
          end), ``tail`` (change left beyond the last point as y0 -> 0) and ``inner`` (the
          diffusion solves: from re-solving the end point at another tolerance, at least
          ``PULL_OFF_INNER_FLOOR * sigma_c``);
        - ``converged``: ``error_estimate <= rtol * sigma_c`` and no branch point failed
          (otherwise a ``RuntimeWarning`` is issued too);
        - ``y0`` [Pa]: sigma0 + sigma_a(1) at the end of the branch; ``fold``: the end is an
          interior minimum of sigma0(y0) (True) or the branch flattens as y0 -> 0 (False);
        - ``y0_grids`` [Pa], ``grids``: the y0 where the nested grids are compared, and per
          grid its size and -sigma0 there [Pa]; ``extrapolated``: the Richardson values [Pa];
          ``end_correction``: the branch's change from ``y0_grids`` to the end on the two
          coarsest grids [Pa];
        - ``branch``: the descent on the coarsest grid, arrays ``y0``, ``sigma0`` [Pa] and
          ``area`` (A(zeta1)/A0);
        - ``solves``, ``iterations``, ``unconverged`` (branch points that failed), ``time`` [s];
        - ``bracket`` (with ``bracket=True``): tensions (lo, hi) [Pa] between which
          :func:`persson_fast.solve_contact` at this ``rtol`` (on the grid
          ``adhesion_zeta(surface, rtol)`` or ``zeta``) stops finding contact: contact at lo,
          none at hi, resolution max(rtol, 1e-4). It lies below sigma_c by the zeta-grid
          error of a single unextrapolated grid and where its fixed point stops converging.

    Raises
    ------
    RuntimeError
        If the contact problem at p_nom = 0 fails, the branch cannot be left from p_nom = 0
        although the state there is sticky (or undecided on the last grid tried), or a
        branch point used for sigma_c is flagged by the diffusion kernel (resolution cap,
        far-field leak).

    Warns
    -----
    RuntimeWarning
        When the estimated error exceeds ``rtol * sigma_c`` or a branch point failed.

    Notes
    -----
    **Stickiness.** Surfaces brought into full contact and unloaded to p_nom = 0 stick when
    a contact state survives there: the fixed point of Eqs. 8-9 at p_nom = 0, started from
    full contact, keeps A(zeta1) > 0 with gamma_eff(1) > 0, i.e. sigma_a(1) > 0 (at
    p_nom = 0 the distribution starts on the wall unless sigma_a(1) > 0, so A > 0 needs
    it). Where instead gamma_eff(1) <= 0, the wall sits where the distribution starts, the
    contact vanishes (A = 0 is then the only state) and no tension is needed to separate
    the surfaces: sigma_c = 0. The decision is made on the converged state, with an error
    bar, not on the compiled fixed point's stopping point: that measures its residual
    against the largest sigma_a (at zeta1, ~sqrt(zeta1) times sigma_a(1) at full contact),
    so it can stop on a remnant on its way to A = 0 (seed scene, Delta gamma = 0.04, rtol
    1e-3: A(zeta1) = 1.25e-7, sigma_a(1) = 16 Pa, while one more application of Eqs. 8-9
    gives sigma_a(1) = 0). From that state the iteration continues at p_nom = 0
    (:meth:`_Branch.rest_state`): not sticky once g1 = gamma_eff(1)/Delta gamma lies below
    minus its error bar (propagated from the diffusion solves' area error estimates) on
    ``PULL_OFF_COLLAPSE`` successive iterates while A(zeta1) falls; sticky once converged
    (as a branch point) with g1 above its error bar; a state whose sign of g1 is within the
    error bar is re-solved with 10x tighter diffusion solves. A sticky state may have a
    tiny area: the onset is continuous (seed scene, converged threshold
    Delta gamma_c = 0.05181 J/m^2: A(zeta1) at p_nom = 0 grows like
    (Delta gamma - Delta gamma_c)^(1/2), 0.04 at 0.05185 and 0.11 at 0.052, and sigma_c
    from 0: 13 kPa at 0.05185, 26 kPa at 0.0519, 50 kPa at 0.052), so a small area
    or sigma_a(1) alone says nothing. The threshold moves with the zeta grid (second order;
    seed: 0.05218 / 0.05190 / 0.05183 J/m^2 at 5 / 10 / 20 points per decade), so a scene
    counts as not sticky only when it is not sticky on ``PULL_OFF_STICKY_GRIDS`` nested
    grids (the coarsest and its refinements, the fewest the extrapolation of a sticky scene
    uses); the first grid on which it is sticky becomes the coarsest. Within the finest
    grid's threshold shift of Delta gamma_c (seed, rtol 1e-3: 2e-5 J/m^2, where sigma_c
    < 7 kPa) a sticky scene can still come back as not sticky.

    On the contact branch of the fixed point of Eqs. 8-9 the nominal stress sigma0 is a
    function of y0 = sigma0 + sigma_a(zeta = 1), the start's distance from the wall, and the
    pull-off stress is -min sigma0 along the branch. Close to its end the branch flattens:
    an absorbing layer just above zeta = 1 takes up every change of y0 (on the seed scene
    sigma0 changes by 7 Pa as y0 falls from 1 kPa to 0), so the fixed point at fixed sigma0
    is nearly singular over the whole flat stretch and stops converging well before its
    end. At fixed y0 it stays regular, so the branch is followed in y0: from the state at
    p_nom = 0, y0 falls by ``PULL_OFF_STEP`` per stage (Anderson-accelerated fixed points
    with a trust region on the wall near zeta = 1, each starting from the extrapolated
    previous ones; loose while sigma0 still changes much) until sigma0 rises again (an
    interior minimum, located by parabolic steps in ln y0) or the estimated remaining change
    is below ``PULL_OFF_TAIL * rtol * sigma_c``.

    A single zeta grid leaves a large second-order error (1.6e-3 of sigma_c at 20 points
    per decade on the seed scene, mostly from the bulk of the spectrum), so the branch point
    at ``y0_grids`` (``PULL_OFF_GRID_STAGES`` stages above the end, where the fixed point is
    robust) is computed on at least three nested grids and Richardson-extrapolated, and the
    branch's change from there to the end is extrapolated from the two coarsest grids. The
    grids reach down to where sqrt(G) is ``PULL_OFF_NEAR_STRESS`` of sigma_a(1), so that the
    layer near zeta = 1 is resolved (see :func:`_near_one_min`).

    sigma_a(1) = c_1 (gamma_eff(1)/dgamma)^(1/2) magnifies an error of the area profile by
    dgamma/(2 gamma_eff(1)), so the diffusion solves of a branch point run at
    ``PULL_OFF_INNER * rtol * min(1, 2 gamma_eff(1)/dgamma)`` (1e-8 at the end of the seed
    scene's branch for rtol = 1e-6). The inner part of the estimate is never below
    ``PULL_OFF_INNER_FLOOR * sigma_c`` (5e-7), so an rtol below about 5e-7 cannot be
    confirmed and warns. Seed scene on a 2-core machine: 0.55 / 1.7 / 8.9 / 18.8 s at rtol
    1e-3 / 1e-4 / 1e-5 / 1e-6, every value within its estimate of the reference.
    """
    from .scene import unpack_adhesive_scene

    surface, kw = unpack_adhesive_scene(surface, e_star, work_of_adhesion, energy_correction,
                                        detachment_prefactor, "pull_off")
    e_star, work_of_adhesion = kw["e_star"], kw["work_of_adhesion"]
    energy_correction, detachment_prefactor = kw["energy_correction"], kw["detachment_prefactor"]
    sigma_c, info, warning = _pull_off(
        surface, e_star=e_star, work_of_adhesion=work_of_adhesion,
        energy_correction=energy_correction, detachment_prefactor=detachment_prefactor,
        rtol=rtol, zeta=zeta, controls=controls, bracket=bool(full_output and bracket))
    if warning is not None:
        import warnings

        warnings.warn(warning, RuntimeWarning, stacklevel=2)
    return (sigma_c, info) if full_output else sigma_c


def _pull_off(surface, *, e_star, work_of_adhesion, energy_correction=None,
              detachment_prefactor=DETACHMENT_PREFACTOR, rtol=1e-6, zeta=None, controls=None,
              bracket=False):
    """:func:`pull_off` without its warning: returns (sigma_c [Pa], info, warning), the
    warning's text or None. Thread-safe (no warning filters touched), for callers that
    record ``info["converged"]`` themselves (:func:`persson_fast.api._flag_lost_contact`).
    """
    from .scene import _check_rtol, _check_scene_args, _check_zeta

    t_start = time.perf_counter()
    rtol = _check_rtol(rtol)
    e, dg, beta = _check_scene_args(surface, e_star, work_of_adhesion, detachment_prefactor,
                                    energy_correction)
    info = {"solves": 0, "iterations": 0, "unconverged": 0, "error_estimate": 0.0,
            "error_parts": {}, "converged": True, "fold": False, "y0": 0.0, "grids": [],
            "extrapolated": [], "branch": {}, "bracket": (0.0, 0.0), "time": 0.0,
            "sticky": False, "reason": "", "rest": []}
    if dg == 0.0:
        info["reason"] = "not sticky: no adhesion (work_of_adhesion = 0)"
        return 0.0, info, None
    if zeta is None:
        z0 = adhesion_zeta(surface, rtol, near_one_min=_near_one_min(surface, e, dg, beta))
    else:
        z0 = _check_zeta(zeta, surface)
    z_user = z0
    ctl = _controls(controls)
    if not (controls and "max_iter" in controls):
        ctl["max_iter"] = PULL_OFF_MAX_ITER
    gamma_s = -1.0 if energy_correction is None else float(energy_correction)
    variant = variant_of(choose_auto("adhesion"))

    def make(grid):
        return _Branch(surface, grid, e, dg, beta, gamma_s, variant, ctl["n_damp"])

    # the contact state at p_nom = 0 (from full contact) starts the descent on the coarsest
    # grid on which it is sticky; on none of PULL_OFF_STICKY_GRIDS nested grids: sigma_c = 0
    z_try, rest_branches = z0, []
    for _ in range(PULL_OFF_STICKY_GRIDS):
        b0 = make(z_try)
        rest = _rest_start(b0, rtol, ctl, gamma_s, variant)
        info["rest"].append(rest["summary"])
        info["iterations"] += rest["summary"]["iterations"]
        if rest["sticky"] is not False:
            x_p0 = rest["x"]
            samples, y_best, tail, fold, lost = _descend(b0, x_p0, x_p0[0] * b0.scale, rtol,
                                                         ctl)
            ok = sorted((s for s in samples if s["converged"]), key=lambda s: -s["y0"])
            if ok:
                break
            if rest["sticky"] or len(info["rest"]) == PULL_OFF_STICKY_GRIDS:
                raise RuntimeError(
                    f"pull_off: the contact branch could not be followed from p_nom = 0 on a "
                    f"zeta grid of {b0.zeta.size} points (the contact state there is "
                    + ("sticky" if rest["sticky"] else "undecided: the scene lies within the "
                       "grid's resolution of the stickiness threshold") + "); try another rtol "
                    "or a finer zeta grid")
            # undecided and no branch: as not sticky on this grid; the finer grid decides
        rest_branches.append(b0)
        z_try = refine_zeta(z_try)
    else:
        undecided = sum(r["sticky"] is None for r in info["rest"])
        info["reason"] = (
            f"not sticky: at p_nom = 0 the fixed point falls to the separated state (A = 0; "
            f"gamma_eff(1) < 0 beyond its error bar, or no contact) on the nested zeta grids "
            f"of {', '.join(str(r['n_zeta']) for r in info['rest'])} points"
            + (f" (on {undecided} of them undecided, and no contact branch leaves p_nom = 0)"
               if undecided else ""))
        info["solves"] += sum(b.solves for b in rest_branches)
        info["time"] = time.perf_counter() - t_start
        return 0.0, info, None
    z0 = z_try
    info["sticky"] = True
    best = min(ok, key=lambda s: s["sigma0"])
    # the nested grids are compared at y_g, a few stages above the end, where the fixed
    # point is robust; the change of sigma0 from y_g to the end (the part of the branch the
    # thin layer above zeta = 1 shapes) comes from the two coarsest grids
    y_above = best["y0"] * PULL_OFF_STEP ** PULL_OFF_GRID_STAGES * 0.99
    above = [s for s in ok if s["y0"] >= y_above]
    g_pt = above[-1] if above else ok[0]
    if g_pt.get("rtol", rtol) > rtol:
        g_pt = b0.follow(g_pt["y0"], [g_pt["x"]], rtol, ctl)
    y_g = g_pt["y0"]
    down = [s["y0"] for s in ok if best["y0"] <= s["y0"] < y_g]
    if best["y0"] not in down:
        down.append(best["y0"])
    down = sorted(set(down), reverse=True)
    ends = [g_pt["sigma0"]]
    used = [g_pt, best]
    branches = [b0]
    t_coarse = best["sigma0"] - g_pt["sigma0"]
    t_fine = None
    prev_z, prev_x = z0, g_pt["x"] * b0.scale
    err_grid = np.inf
    while len(ends) < PULL_OFF_MAX_GRIDS:
        grid = refine_zeta(prev_z)
        b = make(grid)
        branches.append(b)
        p = b.follow(y_g, [_interp_profile(grid, prev_z, prev_x) / b.scale], rtol, ctl)
        if not p["converged"]:
            # near the stickiness threshold the branch moves much with the grid (the
            # threshold does): walk this grid's own branch down the coarse ladder to y_g,
            # from the coarse grid's state at p_nom = 0
            ladder = [s["y0"] for s in ok if s["y0"] >= y_g]
            start = _interp_profile(grid, b0.zeta, ok[0]["x"] * b0.scale)
            walk = _replay(b, ladder, start, rtol, ctl)
            if walk and walk[-1]["converged"] and walk[-1]["y0"] == y_g:
                walk[-1]["iterations"] += p["iterations"] + sum(
                    q["iterations"] for q in walk[:-1])
                p = walk[-1]
        used.append(p)
        if not p["converged"]:
            lost = True
            break
        ends.append(p["sigma0"])
        if len(ends) == 2:
            pts = _replay(b, down, p["x"] * b.scale, rtol, ctl)
            if pts and pts[-1]["converged"]:
                used.append(pts[-1])
                t_fine = pts[-1]["sigma0"] - p["sigma0"]
        prev_z, prev_x = grid, p["x"] * b.scale
        if len(ends) >= 3:
            s = np.array(ends)
            rich = (4.0 * s[1:] - s[:-1]) / 3.0
            err_grid = abs(rich[-1] - rich[-2])
            steps = np.diff(s)
            ratio = steps[-2] / steps[-1] if steps[-1] != 0.0 else np.inf
            if not 2.0 <= ratio <= 8.0:
                # not in the asymptotic range: charge the last difference itself
                err_grid = max(err_grid, abs(steps[-1]))
            if err_grid <= 0.5 * rtol * abs(rich[-1]):
                break
    s = np.array(ends)
    if s.size >= 2:
        rich = (4.0 * s[1:] - s[:-1]) / 3.0
        if s.size == 2:
            err_grid = abs(s[1] - s[0])
    else:
        rich = s.copy()
    if t_fine is not None:
        t_end = (4.0 * t_fine - t_coarse) / 3.0
        err_t = abs(t_fine - t_coarse) / 3.0
    else:
        t_end = t_coarse
        err_t = 0.5 * abs(t_coarse)
    sigma_c = max(-float(rich[-1] + t_end), 0.0)
    # error of the inner (diffusion) solves: re-solve the coarsest grid's end point with a
    # tighter tolerance (the inner error taken as linear in it), or, at the floor, a looser
    # one (the whole difference charged)
    tighter = (b0.inner_rtol(rtol / PULL_OFF_INNER_CHECK, best["x"])
               < b0.inner_rtol(rtol, best["x"]))
    r_check = rtol / PULL_OFF_INNER_CHECK if tighter else rtol * PULL_OFF_INNER_CHECK
    check = b0.point(best["y0"], best["x"], r_check, m_hist=ctl["m_hist"], omega=ctl["omega"],
                     trust=PULL_OFF_TRUST, max_iter=ctl["max_iter"])
    err_inner = abs(check["sigma0"] - best["sigma0"])
    if tighter:
        err_inner *= PULL_OFF_INNER_CHECK / (PULL_OFF_INNER_CHECK - 1.0)
    if not check["converged"] or check["status"] not in (0, WALL_JUMP, RTOL_NOT_MET):
        err_inner += rtol * sigma_c
    err_inner = max(err_inner, PULL_OFF_INNER_FLOOR * sigma_c)
    # a diffusion solve flagged RTOL_NOT_MET (refined to its work cap) still returns its
    # best value: its estimated error is charged, with the largest weight (4/3 + 1/3) a
    # point gets in the Richardson values, instead of failing
    err_flag = PULL_OFF_FLAG_WEIGHT * (
        sum(p["flag_error"] for p in used if p["converged"]) + check["flag_error"])
    err_tail = float(tail)
    for p in used:
        if p["converged"] and p["status"] not in (0, WALL_JUMP, RTOL_NOT_MET):
            raise RuntimeError(f"pull_off: a branch point at y0 = {p['y0']!r} Pa was flagged "
                               f"({summarize_status(np.array([p['status']]))[1]}); try a "
                               f"smaller rtol or a finer zeta grid")
    error = err_grid + err_t + err_tail + err_inner + err_flag
    converged = bool(error <= rtol * sigma_c and not lost)
    warning = None
    if not converged:
        warning = (f"pull_off: estimated error {error:.3g} Pa of sigma_c = {sigma_c:.6g} Pa "
                   f"exceeds rtol * sigma_c" + ("; a branch point failed" if lost else ""))
    info["solves"] += sum(b.solves for b in branches + rest_branches)
    info["iterations"] += sum(p["iterations"] for p in samples + used) + check["iterations"]
    info["unconverged"] = sum(not p["converged"] for p in samples) + sum(
        not p["converged"] for p in used)
    info["error_estimate"] = float(error)
    info["error_parts"] = {"zeta_grid": float(err_grid), "end_zeta_grid": float(err_t),
                           "tail": err_tail, "inner": float(err_inner),
                           "flagged": float(err_flag)}
    info["converged"] = converged
    info["fold"] = bool(fold)
    info["y0"] = float(best["y0"])
    info["y0_grids"] = float(y_g)
    info["end_correction"] = (float(-t_coarse), None if t_fine is None else float(-t_fine))
    info["grids"] = [(int(b.zeta.size), float(-s_)) for b, s_ in zip(branches, ends)]
    info["extrapolated"] = [float(-r) for r in rich]
    info["branch"] = {"y0": np.array([p["y0"] for p in ok]),
                      "sigma0": np.array([p["sigma0"] for p in ok]),
                      "area": np.array([p["area"][-1] for p in ok])}
    if bracket:
        upper = max(sigma_c + error, float(-min(ends))) * (1.0 + 2.0 * rtol)
        z_solver = adhesion_zeta(surface, rtol) if zeta is None else z_user
        info["bracket"], n = _solver_bracket(surface, z_solver, e, dg, energy_correction,
                                             beta, rtol, controls, upper)
        info["solves"] += n
    info["time"] = time.perf_counter() - t_start
    return sigma_c, info, warning
