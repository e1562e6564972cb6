"""The contact branch of one adhesive scene on one zeta grid, and the descent along it.

:class:`_Branch` holds the adhesive fixed point of seed Eqs. 8-9 on one grid, parametrised by
y0 = sigma0 + sigma_a(1): a branch point at given y0 (Anderson-accelerated, with a trust
region), the state at p_nom = 0 and whether it is sticky (:func:`_rest_start`).
:func:`_descend` follows the branch down in y0 to where sigma0 is least (:func:`_tail_estimate`
and :func:`_locate_minimum` say where that is); :func:`_replay` repeats given branch points on
a finer grid. :func:`persson_fast.pull_off` builds on these.
"""
from __future__ import annotations

import numpy as np

from ._kernels.adhesion import detachment_update
from ._kernels.status import BAD_INPUT, FAR_LEAK, NONFINITE, RTOL_NOT_MET, WALL_JUMP
from .adhesion import _run
from ._kernels.similarity import SMOOTH_WALL
from .results import summarize_status
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
        from ._jit import callable_with
        from ._kernels.adhesion import STEP_SIGNATURE, elastic_step
        from ._kernels.similarity import GRID_SIGNATURE, _solve_grid_tol

        self.zeta = np.asarray(zeta, dtype=float)
        self.work_of_adhesion = float(work_of_adhesion)
        G, c, wa, wb, scale, _ = _scene_arrays(surface, self.zeta, e_star, work_of_adhesion, beta)
        self.G, self.c, self.wa, self.wb, self.scale = G, c, wa, wb, scale
        self.gamma_s = gamma_s
        # the adhesive wall: no kink detection, as in the fixed point of solve_contact
        self.variant = int(variant) | SMOOTH_WALL
        self.n_damp = int(n_damp)
        # one diffusion solve against the wall linear between the nodes (onset False): the
        # fixed point's own step (compiled or loaded already for solve_contact)
        self._grid = _solve_grid_tol
        self._kernel = callable_with(elastic_step, STEP_SIGNATURE,
                                     [(_solve_grid_tol, GRID_SIGNATURE)])
        n = self.zeta.size
        self._out = [np.zeros(n) for _ in range(5)]
        self._absent = np.zeros(0)       # no yield wall, no plastic outputs
        self._counts = np.zeros(3, dtype=np.int64)
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
        x = np.ascontiguousarray(x, dtype=float)
        status = self._kernel(self._grid, self.variant, self.G, x, x, self._absent,
                              float(sigma0), float(rtol), False, self.n_damp, area, load,
                              self._absent, self._absent, det_a, det_l, err, self._counts)
        self.solves += 1
        self.area = area.copy()
        self.area_error = err.copy()
        return self.update(self.area), int(status)

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
        if converged and status == FAR_LEAK and inner > PULL_OFF_INNER_MIN:
            # the loose diffusion grid let mass reach its far end (a resolution flag, as at
            # p_nom = 0 in _rest_start): the point again, from here, 10x tighter
            again = self.point(y0, x, 0.1 * rtol, m_hist=m_hist, omega=omega, trust=trust,
                               max_iter=max_iter)
            again["iterations"] += it
            return again
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
        inner = _inner_rtol(rtol)
        for _ in range(PULL_OFF_REST_RETRIES + 1):
            outs, status, its, _, _ = _run(branch.G, branch.c, branch.wa, branch.wb, gamma_s,
                                           np.array([0.0]), inner, False, controls, None,
                                           variant, onset=False)
            branch.solves += 1
            iterations += int(its[0])
            if (status[0] in (0, WALL_JUMP, RTOL_NOT_MET, NONFINITE, BAD_INPUT)
                    or inner <= PULL_OFF_INNER_MIN):
                break
            # a resolution flag of a loose solve (e.g. the far end of the grid reached):
            # again with a tighter tolerance
            inner = max(0.1 * inner, PULL_OFF_INNER_MIN)
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
