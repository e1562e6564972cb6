"""Slow, obvious twins of :mod:`persson_fast.theories`, for tests and benchmarks.

* :func:`reference_area` -- the corrected theories straight from their definitions, in the
  uncorrected variance Vc = 2 G: yp08 and wm17 by ``scipy.integrate.solve_ivp`` (DOP853,
  rtol 1e-13) of dV/dVc = S(erf(p / sqrt(2 V))) from the delta start, written in
  (ln Vc, ln V) so that the many decades of Vc cost a bounded number of steps; xu24 by
  ``scipy.optimize.brentq`` of A = erf(p / sqrt(2 (gamma + (1 - gamma) A) Vc)) at each Vc.
  It shares no code and no change of variables with the compiled tables.
* :func:`stepped_area` -- the straightforward implementation of the published codes: a
  log-spaced magnification grid and, at each step, a root solve of the implicit (first-order)
  update V_{n+1} = V_n + S(A_{n+1}) (Vc_{n+1} - Vc_n) with A_{n+1} = erf(p / sqrt(2 V_{n+1}));
  xu24 one root solve at zeta1. The benchmark's baseline.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq
from scipy.special import erf

from ..theories import DEFAULT_GAMMA


def _factor(theory, gamma, a):
    a2 = a * a
    if theory == "yp08":
        return gamma + (1.0 - gamma) * a2
    if theory == "wm17":
        return gamma - (2.0 / 9.0) * a2 + (11.0 / 9.0 - gamma) * a2 * a2
    if theory == "persson01":
        return 1.0
    raise ValueError(f"no spread factor for theory {theory!r}")


def _xu24_one(gamma, p, vc):
    if p == 0.0:
        return 0.0
    if vc == 0.0:
        return 1.0

    def h(a):
        return a - erf(p / math.sqrt(2.0 * (gamma + (1.0 - gamma) * a) * vc))

    if h(1.0) <= 0.0:
        return 1.0
    return brentq(h, 0.0, 1.0, xtol=1e-300, rtol=4 * np.finfo(float).eps, maxiter=500)


def _ode_one(theory, gamma, p, vc, rtol):
    """A at the non-decreasing variances vc (>= 0) for one pressure p > 0."""
    out = np.ones(vc.size)
    vc_start = p * p / 200.0            # y = p / sqrt(2 Vc) = 10: A = 1, S = 1 exactly before
    later = vc > vc_start
    if not np.any(later):
        out[:] = erf(p / np.sqrt(2.0 * np.maximum(vc, 1e-300)))
        out[vc == 0] = 1.0
        return out
    out[~later] = np.where(vc[~later] > 0, erf(p / np.sqrt(2.0 * np.maximum(vc[~later], 1e-300))),
                           1.0)
    u = np.log(vc[later])

    def rhs(u_, w):                     # w = ln V, u = ln Vc: dw/du = (Vc / V) S(A)
        a = erf(p / math.sqrt(2.0 * math.exp(w[0])))
        return [math.exp(u_ - w[0]) * _factor(theory, gamma, a)]

    u0 = math.log(vc_start)
    if u[-1] == u0:
        out[later] = erf(p / np.sqrt(2.0 * vc[later]))
        return out
    sol = solve_ivp(rhs, (u0, u[-1]), [u0], method="DOP853", t_eval=u, rtol=rtol,
                    atol=1e-15)
    if not sol.success:                 # pragma: no cover
        raise RuntimeError(sol.message)
    out[later] = erf(p / np.sqrt(2.0 * np.exp(sol.y[0])))
    return out


def reference_area(theory, pressure, G, theory_gamma=None, rtol=1e-13):
    """(n_p, n_z) A/A0 of a corrected theory at pressures [Pa] and diffusion times G [Pa^2].

    xu24 applies its relation at each G (as the package's profiles do).
    """
    gamma = DEFAULT_GAMMA.get(theory) if theory_gamma is None else float(theory_gamma)
    p = np.atleast_1d(np.asarray(pressure, dtype=float))
    vc = 2.0 * np.atleast_1d(np.asarray(G, dtype=float))
    out = np.zeros((p.size, vc.size))
    for i, pi in enumerate(p):
        if pi == 0.0:
            continue
        if theory == "xu24":
            out[i] = [_xu24_one(gamma, pi, v) for v in vc]
        else:
            out[i] = _ode_one(theory, gamma, pi, vc, rtol)
    return out


def stepped_area(theory, pressure, surface, e_star, theory_gamma=None, n_steps=500):
    """A(zeta1)/A0 as the published codes compute it: a root solve per magnification step.

    Parameters
    ----------
    theory : "yp08", "wm17" or "xu24".
    pressure : (n_p,) -- nominal pressures. [Pa]
    surface, e_star : the scene. [-], [Pa]
    theory_gamma : gamma (None: the default). [-]
    n_steps : int -- magnification steps, log-spaced from 1 to zeta1 (first order). [-]
    """
    gamma = DEFAULT_GAMMA[theory] if theory_gamma is None else float(theory_gamma)
    zeta = np.logspace(0.0, math.log10(surface.q1 / surface.q0), n_steps)
    vc = 2.0 * np.asarray(surface.diffusion_time(zeta * surface.q0, e_star), dtype=float)
    vc[0] = 0.0
    p = np.atleast_1d(np.asarray(pressure, dtype=float))
    out = np.zeros(p.size)
    for i, pi in enumerate(p):
        if pi == 0.0:
            continue
        if theory == "xu24":
            out[i] = _xu24_one(gamma, pi, vc[-1])
            continue
        v = 0.0
        a = 1.0
        for n in range(1, vc.size):
            dvc = vc[n] - vc[n - 1]
            v_prev = v

            def h(a_, v_prev=v_prev, dvc=dvc):
                var = v_prev + _factor(theory, gamma, a_) * dvc
                return a_ - erf(pi / math.sqrt(2.0 * var)) if var > 0 else a_ - 1.0

            if h(1.0) >= 0.0 and h(0.0) < 0.0:
                a = brentq(h, 0.0, 1.0, xtol=1e-15)
            elif h(1.0) < 0.0:
                a = 1.0
            v = v_prev + _factor(theory, gamma, a) * dvc
        out[i] = a
    return out
