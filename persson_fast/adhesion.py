"""Adhesion: the self-consistent detachment stress sigma_a(zeta) around the diffusion kernel.

Seed Eqs. 8-9:

    sigma_a(zeta) = beta (gamma_eff(zeta) E* q)^(1/2)                      (Eq. 8)
    A(zeta) gamma_eff(zeta) = A(zeta1) dgamma - U_el(zeta)                    (Eq. 9)
    U_el(zeta)/A0 = (pi E*/2) int_{zeta q0}^{q1} q^2 C(q) P(q) S(q) dq,  P(q) = A(q/q0)/A0

(Persson, PRL 89, 245502 (2002); Eur. Phys. J. E 8, 385 (2002)). S = 1, or the later
correction S = gamma_S + (1 - gamma_S) P^2 (Persson 2008). Where gamma_eff <= 0, sigma_a = 0.
The fixed point runs entirely in compiled code (:mod:`persson_fast._kernels.adhesion`), one
pressure per ``prange`` iteration.
"""
from __future__ import annotations

import time

import numpy as np

from ._kernels.adhesion import adhesive_sweep_parallel, adhesive_sweep_serial
from ._kernels.status import NOT_CONVERGED, WALL_JUMP
from ._validation import as_float_array, check_finite
from .methods import METHODS, check_serves, choose_auto
from .results import ContactResult, per_contact_area, summarize_status
from .sweep import choose_parallel, interleave, is_compiled

__all__ = ["adhesion_zeta", "solve_adhesive_contact", "pull_off", "ADHESION_DEFAULTS"]

#: iteration controls of the fixed point (Anderson depth 0 = plain relaxation)
ADHESION_DEFAULTS = {"max_iter": 100, "m_hist": 5, "omega": 0.5, "n_damp": 2}
#: magnifications per decade of the coarser of the two nested default zeta grids at
#: rtol = 1e-6, scaled as rtol^(-1/3). Measured on the seed scene (inner rtol 1e-9): the
#: zeta-grid error of A(zeta1) is second order before extrapolation (ratio 3.9-4.0 per
#: doubling) and third order after it (3.6e-6 at 20/decade, 4.5e-7 at 40, 7e-8 at 80);
#: 46/decade keeps it near 0.3 rtol.
ZETA_PER_DECADE_ADHESION = 46
#: near zeta = 1, where an absorbing layer forms close to pull-off, points are also spaced
#: in ln(zeta - 1) from NEAR_ONE_MIN to 1 with this fraction of the per-decade density
NEAR_ONE_MIN = 1e-6
NEAR_ONE_FRACTION = 0.5


def adhesion_zeta(surface, rtol: float = 1e-6, per_decade: int | None = None) -> np.ndarray:
    """Default magnification grid of the adhesive problem. [-]

    Log-spaced from 1 to zeta1 with ``per_decade`` points per decade (default
    46 (1e-6/rtol)^(1/3), at least 4), plus the spectrum's breakpoints and points at
    zeta - 1 = 1e-4 ... 0.3 (the grid must be fine near 1).
    """
    if per_decade is None:
        per_decade = max(4, int(np.ceil(ZETA_PER_DECADE_ADHESION * (1e-6 / rtol) ** (1 / 3))))
    zeta1 = surface.q1 / surface.q0
    n = max(2, int(np.ceil(np.log10(zeta1) * per_decade)) + 1)
    z = np.geomspace(1.0, zeta1, n)
    bp = np.asarray(surface.breakpoints(), dtype=float) / surface.q0
    n_near = max(2, int(np.ceil(-np.log10(NEAR_ONE_MIN) * per_decade * NEAR_ONE_FRACTION)))
    near = 1.0 + np.geomspace(NEAR_ONE_MIN, 1.0, n_near)[:-1]
    z = np.unique(np.concatenate([z, bp, near[near < zeta1]]))
    z = z[(z >= 1.0) & (z <= zeta1)]
    z[0], z[-1] = 1.0, zeta1
    return z


def refine_zeta(zeta: np.ndarray) -> np.ndarray:
    """The grid with the geometric midpoint of every interval inserted (nests ``zeta``)."""
    mid = np.sqrt(zeta[:-1] * zeta[1:])
    out = np.empty(2 * zeta.size - 1)
    out[0::2] = zeta
    out[1::2] = mid
    return out


def _scene_arrays(surface, zeta, e_star, work_of_adhesion, detachment_prefactor):
    """Scaled kernel inputs (G, c, wa, wb) and the stress scale [Pa]."""
    q = zeta * surface.q0
    G = np.asarray(surface.diffusion_time(q, e_star), dtype=float)
    G[0] = 0.0
    scale = float(np.sqrt(G[-1])) if G[-1] > 0 else 1.0
    c_dim = detachment_prefactor * np.sqrt(work_of_adhesion * e_star * q)
    scale = max(scale, float(c_dim[0]))
    m2 = np.asarray(surface.moment(2, q[:-1], q[1:]), dtype=float)
    m3 = np.asarray(surface.moment(3, q[:-1], q[1:]), dtype=float)
    dq = q[1:] - q[:-1]
    pref = 0.5 * np.pi * e_star / work_of_adhesion
    wa = pref * (q[1:] * m2 - m3) / dq
    wb = pref * (m3 - q[:-1] * m2) / dq
    return G / scale**2, c_dim / scale, np.maximum(wa, 0.0), np.maximum(wb, 0.0), scale, G


def _run(G, c, wa, wb, gamma_s, p_scaled, rtol, parallel, controls, x_init=None, variant=0):
    n_p, n_z = p_scaled.size, G.size
    outs = [np.zeros((n_p, n_z)) for _ in range(8)]
    status = np.zeros(n_p, dtype=np.int64)
    iterations = np.zeros(n_p, dtype=np.int64)
    residual = np.zeros(n_p)
    if x_init is None:
        x_init = np.full((n_p, n_z), -1.0)
    parallel = choose_parallel(parallel, n_p, adhesive_sweep_parallel)
    kernel = adhesive_sweep_parallel if parallel else adhesive_sweep_serial
    timings = {}
    if not is_compiled(kernel):
        t0 = time.perf_counter()
        kernel(variant, G, c, wa, wb, gamma_s, p_scaled[:1], 1e-2, controls["n_damp"], 2,
               controls["m_hist"], controls["omega"], x_init[:1], *[o[:1] for o in outs], status[:1],
               iterations[:1], residual[:1])
        timings["compile"] = time.perf_counter() - t0
    order = interleave(n_p) if parallel else np.arange(n_p)
    t0 = time.perf_counter()
    kernel(variant, G, c, wa, wb, gamma_s, np.ascontiguousarray(p_scaled[order]), rtol,
           controls["n_damp"], controls["max_iter"], controls["m_hist"], controls["omega"],
           np.ascontiguousarray(x_init[order]), *outs, status, iterations, residual)
    timings["solve"] = time.perf_counter() - t0
    inverse = np.empty_like(order)
    inverse[order] = np.arange(n_p)
    outs = [o[inverse] for o in outs]
    return outs, status[inverse], iterations[inverse], residual[inverse], timings


def warm_adhesion(parallel: bool = True) -> None:
    """Compile (or load) the adhesive sweep kernels on a tiny problem."""
    G = np.array([0.0, 1.0, 2.0])
    c = np.array([0.1, 0.2, 0.3])
    w = np.array([0.1, 0.1])
    ctl = _controls(None)
    for par in ((False, True) if parallel else (False,)):
        _run(G, c, w, w, -1.0, np.array([1.0]), 1e-2, par, ctl)


def _controls(overrides):
    controls = dict(ADHESION_DEFAULTS)
    if overrides:
        unknown = set(overrides) - set(controls)
        if unknown:
            raise ValueError(f"unknown adhesion control(s) {sorted(unknown)}; valid: {sorted(controls)}")
        controls.update(overrides)
    if int(controls["max_iter"]) < 1:
        raise ValueError(f"max_iter must be >= 1 [-]; got max_iter = {controls['max_iter']!r}")
    if int(controls["m_hist"]) < 0:
        raise ValueError(f"m_hist must be >= 0 [-]; got m_hist = {controls['m_hist']!r}")
    if not 0.0 < float(controls["omega"]) <= 1.0:
        raise ValueError(f"omega must lie in (0, 1] [-]; got omega = {controls['omega']!r}")
    return {"max_iter": int(controls["max_iter"]), "m_hist": int(controls["m_hist"]),
            "omega": float(controls["omega"]), "n_damp": int(controls["n_damp"])}


def solve_adhesive_contact(surface, pressure, zeta, *, e_star, work_of_adhesion,
                           energy_correction=None, detachment_prefactor=2 ** -0.5,
                           method="auto", rtol=1e-6, parallel=None, controls=None,
                           zeta_given=False, start=None) -> ContactResult:
    """Adhesive contact of one scene at many pressures (called by :func:`solve_contact`).

    Arguments are validated by :func:`persson_fast.solve_contact`; ``zeta`` is the grid of
    the fixed point (``adhesion_zeta`` unless the user gave one). ``start``: optional
    (n_p, n_z) detachment stresses [Pa] on ``zeta`` to start the fixed point from
    (continuation); default the full-contact detachment stress.
    """
    if method == "auto":
        method = choose_auto("adhesion")
    check_serves(method, adhesion=True)
    variant = int(METHODS[method]["variant"])
    p = as_float_array(pressure, "pressure", "Pa", ndim=(0, 1))
    check_finite(p, "pressure", "Pa")
    p = np.atleast_1d(p).astype(float)
    ctl = _controls(controls)
    if not zeta_given:
        zeta = adhesion_zeta(surface, rtol)
    gamma_s = -1.0 if energy_correction is None else float(energy_correction)
    # the fixed point on two nested grids, Richardson-extrapolated at the coarse nodes; the
    # fine grid starts from the coarse solution (interpolated in ln zeta)
    fine = refine_zeta(zeta)
    timings = {}

    def fixed_point(grid, start_pa):
        G, c, wa, wb, scale, G_dim = _scene_arrays(surface, grid, e_star, work_of_adhesion,
                                                   detachment_prefactor)
        x_init = None if start_pa is None else start_pa / scale
        outs, status, iterations, residual, tim = _run(G, c, wa, wb, gamma_s, p / scale, rtol,
                                                       parallel, ctl, x_init, variant)
        for key, val in tim.items():
            timings[key] = timings.get(key, 0.0) + val
        outs = [o * (scale if k in (1, 4, 6) else 1.0) for k, o in enumerate(outs)]
        return outs, status, iterations, residual, G_dim

    oc, sc, ic, rc, G_dim = fixed_point(zeta, None if start is None else np.array(start, float))
    start_fine = np.array([np.interp(np.log(fine), np.log(zeta), row) for row in oc[1]])
    start_fine[sc != 0] = -np.inf          # a failed coarse row starts from full contact
    of, sf, if_, rf, _ = fixed_point(fine, start_fine)
    of = [o[:, 0::2] for o in of]
    ex = [(4.0 * f_ - c_) / 3.0 for f_, c_ in zip(of, oc)]
    # near pull-off one grid may still have contact and the other not: no extrapolation there
    split = (oc[0][:, -1] > 0) != (of[0][:, -1] > 0)
    for k in range(len(ex)):
        ex[k][split] = of[k][split]
    area_z, sa, g, u, load, det_a, det_l, _ = ex
    # an extrapolated profile outside [0, 1] is a zeta-grid error: clip it and charge the
    # overshoot to the error estimate
    over = np.maximum(area_z - 1.0, 0.0) + np.maximum(-area_z, 0.0)
    area_z = np.clip(area_z, 0.0, 1.0)
    err = np.abs(of[7]) + np.abs(of[0] - oc[0]) / 3.0
    zeta_err = np.abs(of[0][:, -1] - oc[0][:, -1]) / np.where(split, 1.0, 3.0)
    zeta_err = np.maximum(zeta_err, over.max(axis=1))
    err[:, -1] = np.maximum(err[:, -1], zeta_err)
    status = np.where(sf != 0, sf, sc)
    iterations = ic + if_
    residual = np.maximum(rc, rf)
    area = area_z[:, -1].copy()
    success, message = summarize_status(status)
    if np.any(status == NOT_CONVERGED):
        bad = np.flatnonzero(status == NOT_CONVERGED)
        message += f"; largest fixed-point residual {residual[bad].max():.3g} after {iterations[bad].max()} iterations"
    return ContactResult(
        pressure=p, area=area, zeta=zeta, G=G_dim, area_zeta=area_z, sigma_a=sa,
        gamma_eff=g * work_of_adhesion, load=load[:, -1].copy(),
        mean_contact_pressure=per_contact_area(p, area),
        mean_contact_stress=per_contact_area(load[:, -1], area),
        detached_area=det_a[:, -1].copy(), detached_load=det_l[:, -1].copy(),
        error_estimate=err[:, -1].copy(), method=method, status=status, success=success,
        message=message, timings=timings, elastic_energy=u * work_of_adhesion,
        iterations=iterations, residual=residual, sticky=g[:, 0] > 0,
        load_zeta=load, detached_load_zeta=det_l, zeta_error=zeta_err,
    )


def pull_off(surface, *, e_star, work_of_adhesion, energy_correction=None,
             detachment_prefactor=2 ** -0.5, rtol=1e-6, zeta=None, controls=None,
             full_output=False):
    """Pull-off stress of a nominally flat contact: contact exists for p_nom > -sigma_c. [Pa]

    Parameters
    ----------
    surface : Surface
    e_star : float -- effective modulus E* > 0. [Pa]
    work_of_adhesion : float -- Delta gamma >= 0. [J/m^2]
    energy_correction, detachment_prefactor : as in :func:`solve_contact`.
    rtol : float -- relative accuracy of sigma_c (and of the inner solves). [-]

    full_output : bool -- also return a dict with the final bracket [Pa], the number of
        solves, and how many of them ended unconverged.

    Returns
    -------
    sigma_c : float -- >= 0; 0 when the surfaces are not macroscopically sticky. [Pa]
    info : dict -- only with ``full_output``.

    Notes
    -----
    The pull-off stress is the largest tension -p_nom for which the fixed point of Eqs. 8-9
    still has contact. It is bracketed between 0 and the full-contact bound
    beta (Delta gamma E* q0)^(1/2) and found by bisection to ``rtol``, each solve starting
    from the contact solution at the nearest tension known to have contact (continuation
    along the contact branch). Close to the end of the branch the fixed point can stop
    converging (the iteration is drawn to the separated state); such a tension counts as
    "no contact found", and ``info["unconverged"]`` says how often that decided a step.
    Raises ``RuntimeError`` if the solve at p_nom = 0 fails or a solve is flagged for another
    reason (resolution cap, far-field leak).
    """
    from .api import _check_rtol, _check_scene_args, _check_zeta

    rtol = _check_rtol(rtol)
    e, dg, beta = _check_scene_args(surface, e_star, work_of_adhesion, detachment_prefactor,
                                    energy_correction)
    if dg == 0.0:
        return (0.0, {"solves": 0, "unconverged": 0, "bracket": (0.0, 0.0)}) if full_output else 0.0
    z = adhesion_zeta(surface, rtol) if zeta is None else _check_zeta(zeta, surface)

    def contact(sigma0, start):
        r = solve_adhesive_contact(surface, np.array([sigma0]), z, e_star=e, work_of_adhesion=dg,
                                   energy_correction=energy_correction,
                                   detachment_prefactor=beta, rtol=rtol, parallel=False,
                                   controls=controls, zeta_given=True, start=start)
        info["solves"] += 1
        if r.status[0] == NOT_CONVERGED and sigma0 < 0.0:
            info["unconverged"] += 1      # stalled at the edge of the branch
            return False, r
        if r.status[0] not in (0, WALL_JUMP):
            raise RuntimeError(f"pull_off: the contact problem failed at p_nom = {sigma0!r} Pa "
                               f"({r.message}); try a smaller rtol or a finer zeta grid")
        return r.area[0] > 0, r

    info = {"solves": 0, "unconverged": 0}

    has, r_hi = contact(0.0, None)
    if not has:
        info["bracket"] = (0.0, 0.0)
        return (0.0, info) if full_output else 0.0
    hi = 0.0                                     # contact
    lo = -beta * np.sqrt(dg * e * surface.q0)    # surely separated (sigma_a(1) <= this)
    while hi - lo > rtol * max(abs(lo), abs(hi)):
        mid = 0.5 * (lo + hi)
        # continuation: start from the contact solution at the nearest pressure with contact,
        # so that the fixed point follows the contact branch as far as it exists
        has, r = contact(mid, r_hi.sigma_a)
        if has:
            hi, r_hi = mid, r
        else:
            lo = mid
    info["bracket"] = (float(-hi), float(-lo))
    sigma_c = float(-0.5 * (lo + hi))
    return (sigma_c, info) if full_output else sigma_c
