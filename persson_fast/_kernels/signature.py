"""The one sweep signature of every grid method, and the row check its one-wall sweeps share.

Walls: the lower (detachment) wall sits at sigma = -sigma_a(G), the upper (yield) wall at
sigma = sigma_Y(G), +inf where there is none; both piecewise linear in G between the schedule
samples, prescribed (sampled by the calling layer) or self-consistent (the adhesive fixed
point supplies sigma_a). Every grid method of :data:`persson_fast.METHODS` (its ``sweep``
entry) provides a serial and a ``prange`` sweep, made by :func:`persson_fast._jit.njit_sweeps`
from one body with the positional arguments

    (lead..., G, sa_rows, sy_rows, pressures, rtol, level, n_damp,
     area, load, det_area, det_load, error, pl_area, pl_load, status, counts)

lead
    The grid variant (int) for the front-fixed similarity grid
    (:func:`persson_fast._kernels.similarity.solve_variant`), read from the named constant its
    registry entry gives; nothing for the other methods.
G : (n_t,) float64
    Diffusion times, non-decreasing, G[0] >= 0.
sa_rows : (n_p, n_t) float64
    sigma_a at G, one row per pressure: the lower wall.
sy_rows : (n_p, n_t) or (n_p, 0) float64
    sigma_Y at G, one row per pressure: the upper wall. Rows of length 0, or rows that are
    +inf at every G, mean "no upper wall".
pressures : (n_p,) float64
    Nominal stresses sigma0.
rtol : float
    Target relative accuracy (``level`` < 0).
level : int
    >= 0: explicit resolution, no refinement; -1: from ``rtol``, refined a posteriori.
n_damp : int
    Implicit-Euler half-step pairs after a start or a jump/kink (Rannacher); a method without
    such steps ignores it.
area, load, det_area, det_load, error : (n_p, n_t) float64
    Outputs: the (elastic) contact area, the load carried in contact, the area and load
    absorbed by the lower wall, the error estimate of the real contact area.
pl_area, pl_load : (n_p, n_t) or (n_p, 0) float64
    Outputs: the area and load absorbed by the upper wall. Rows of length 0 mean "not
    requested" (nothing is written); a method without an upper wall writes zeros into rows of
    length n_t.
status : (n_p,) int64
    Codes of :mod:`persson_fast._kernels.status`.
counts : (n_p, 3) int64
    Work counters of the method.

A method without an upper wall answers BAD_INPUT (writing nothing else) for a row whose upper
wall is finite at some G, or whose ``sy_rows`` / ``pl_*`` rows have another length than 0 or
n_t (:func:`no_upper_wall`); a two-wall method answers BAD_INPUT where ``sy_rows`` or the
``pl_*`` rows are not of length n_t. The conventions of length-0 rows spare the one-wall
callers arrays of +inf and of zeros; every argument keeps one numba type, so each sweep
compiles once. Each iteration writes only its own rows, so the serial and the ``prange`` sweep
give bitwise-equal results.
"""
from __future__ import annotations

import math

from .._jit import njit_serial


@njit_serial
def no_upper_wall(sy_rows, pl_area, pl_load, k, n_p, n_t):
    """True when row ``k`` of a one-wall sweep carries no upper wall; its plastic outputs
    (rows of length n_t) are then set to zero.

    Parameters
    ----------
    sy_rows : (n_p, n_t) or (n_p, 0) float64 -- the upper wall; absent when of length 0 or
        +inf at every G.
    pl_area, pl_load : (n_p, n_t) or (n_p, 0) float64 -- the plastic outputs (length 0: not
        requested).
    k : int -- the row.
    n_p, n_t : int -- pressures and diffusion times of the sweep.

    Returns
    -------
    bool -- False for a finite upper wall or arrays of another shape (the sweep then returns
    BAD_INPUT for the row).
    """
    for m, r in ((sy_rows.shape[1], sy_rows.shape[0]), (pl_area.shape[1], pl_area.shape[0]),
                 (pl_load.shape[1], pl_load.shape[0])):
        if m != 0 and (m != n_t or r != n_p):
            return False
    for j in range(sy_rows.shape[1]):
        if not sy_rows[k, j] == math.inf:
            return False
    for j in range(pl_area.shape[1]):
        pl_area[k, j] = 0.0
    for j in range(pl_load.shape[1]):
        pl_load[k, j] = 0.0
    return True
