"""Adhesion: the self-consistent detachment stress sigma_a(zeta) around the diffusion kernel.

Seed Eqs. 8-9:

    sigma_a(zeta) = beta (gamma_eff(zeta) E* q)^(1/2)                      (Eq. 8)
    A(zeta) gamma_eff(zeta) = A(zeta1) dgamma - U_el(zeta)                    (Eq. 9)
    U_el(zeta)/A0 = (pi E*/2) int_{zeta q0}^{q1} q^2 C(q) P(q) S(q) dq,  P(q) = A(q/q0)/A0

(Persson, PRL 89, 245502 (2002); Eur. Phys. J. E 8, 385 (2002)). S = 1, or the later
correction S = gamma_S + (1 - gamma_S) P^2 (Persson 2008). Where gamma_eff <= 0, sigma_a = 0.
The fixed point of :func:`solve_adhesive_contact` runs entirely in compiled code
(:mod:`persson_fast._kernels.adhesion`), one pressure per ``prange`` iteration, on the
nested zeta grids of :mod:`persson_fast.adhesion.zeta_grid`; :mod:`persson_fast.adhesion.pulloff` follows the
contact branch to the pull-off stress.
"""
from __future__ import annotations


import numpy as np

from .._kernels.status import NOT_CONVERGED, RTOL_NOT_MET
from .._validation import as_float_array, check_finite
from ..methods import check_serves, choose_auto, variant_of
from ..results import ContactResult, per_contact_area, summarize_status
from ..scene import DETACHMENT_PREFACTOR
from ..plasticity.yield_wall import FAR_MASS, yield_wall_reach
from .zeta_grid import (_scene_arrays, _scene_rows, adhesion_zeta)

from .ladder import _ZetaLadder, _breakpoints, _miss_message
from .runner import ADHESION_DEFAULTS, THEORY_CODES, _controls, _run

__all__ = ["adhesion_zeta", "solve_adhesive_contact", "ADHESION_DEFAULTS"]

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

    scale, G_dim = _scene_arrays(surface, zeta, e_star, work_of_adhesion,
                                 detachment_prefactor)[4:]

    def fixed_point(grids, starts, rows, inner_div):
        """The fixed point of ``rows`` on their grids (one per row) from ``starts`` (per
        row: sigma_a [Pa] on its grid, or None for full contact): the outputs (n_rows,
        n_max) in Pa where they are stresses, the number of nodes per row, status,
        iterations and residual."""
        G, c, wa, wb, n_z, _, G_dims = _scene_rows(surface, grids, e_star, work_of_adhesion,
                                                   detachment_prefactor)
        n_max = int(n_z.max())
        x_init = np.full((rows.size, n_max), -1.0)
        sy = None if hardness is None else np.full((rows.size, n_max), np.inf)
        for i, grid in enumerate(grids):
            n = grid.size
            if starts[i] is not None:
                x_init[i, :n] = starts[i] / scale
            if hardness is not None:
                sy_i = yield_wall_on(hardness, grid)
                # a yield wall the distribution cannot reach (reflection-principle bound
                # without the detachment wall, which only removes mass): solved without it
                if yield_wall_reach(G_dims[i], p[rows[i]:rows[i] + 1], sy_i[None, :])[0] > FAR_MASS:
                    sy[i, :n] = sy_i / scale
        outs, status, iterations, residual, tim = _run(
            G, c, wa, wb, gamma_s, p[rows] / scale, rtol / inner_div, parallel, ctl, x_init,
            variant, False, theory_code, theory_g, sy, n_z)
        for key, val in tim.items():
            timings[key] = timings.get(key, 0.0) + val
        outs = [o * (scale if k in (1, 4, 6, 9) else 1.0) for k, o in enumerate(outs)]
        return outs, n_z, status, iterations, residual

    if start is not None:
        start = np.array(start, dtype=float)
        if start.shape not in ((p.size, zeta.size), (zeta.size,)):
            raise ValueError(f"start must have shape (n_p, n_zeta) = ({p.size}, {zeta.size}) "
                             f"[Pa] (detachment stresses on the zeta grid); got shape "
                             f"{start.shape}")
        start = np.broadcast_to(start, (p.size, zeta.size)).copy()
    ladder = _ZetaLadder(zeta, p.size, fixed_point, _breakpoints(surface, zeta), graded=onset)
    ladder.G_dim = G_dim
    ladder.rtol = rtol
    ladder.solve(start)
    ladder.refine_until(rtol)
    area_z, sa, g, u, load, det_a, det_l, err, zeta_err, *plastic = ladder.profiles()
    status, iterations, residual = ladder.status, ladder.iterations, ladder.residual
    area = area_z[:, -1].copy()
    success, message = summarize_status(status)
    if np.any(status == NOT_CONVERGED):
        bad = np.flatnonzero(status == NOT_CONVERGED)
        message += f"; largest fixed-point residual {residual[bad].max():.3g} after {iterations[bad].max()} iterations"
    if np.any(status == RTOL_NOT_MET):
        message += _miss_message(ladder, p, area, rtol)
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
