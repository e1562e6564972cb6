"""The a-posteriori error control of the adhesive fixed point: a ladder of nested zeta grids.

:class:`_ZetaLadder` solves a batch of pressures on three or more nested magnification grids
(cells halved each time), extrapolates the end area and its profiles in the cell width,
estimates the error of the coupled result, refines where the ladder is not asymptotic and
resolves the onset of adhesion (the sign change of gamma_eff) on graded grids.
"""

from typing import NamedTuple

import numpy as np

from .._kernels.status import GRID_CAP, NOT_CONVERGED, RTOL_NOT_MET
from .zeta_grid import (NARROW_CELL_RTOL, _merged_breakpoints, coarsen_zeta, onset_at,
                        onset_coordinate, onset_grid, refine_zeta)


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
#: a graded level is solved again, centred on its own sign change, while that lies more than
#: this fraction of the level's narrowest graded cell from the centre (at most
#: ONSET_CENTRE_PASSES times); measured on a self-affine scene (H 0.64, rtol 1e-4): centres
#: 0.1 and 0.03 of level 2's narrowest cell off left the end area 0.026 and 0.016 rtol off,
#: 0.27 of it 0.24 rtol
ONSET_CENTRE_TOL = 0.05
ONSET_CENTRE_PASSES = 3
#: the least estimate of a graded row's zeta-grid error, as a fraction of its last
#: difference |a2 - a1|: the extrapolated values of the coarse levels scatter about the
#: limit by 2.5-5 % of it (measured on a random self-affine scene, H 0.71, rtol 1.5e-4, with
#: the levels' ratio 3.6-3.9 looking asymptotic; |R - R0|/3 was 0.02-0.26x the error)
ONSET_FLOOR = 0.1
#: a graded row whose estimate misses rtol mostly through its diffusion solves tightens
#: them (by CROSSING_INNER_DIV) at most this many times before it refines the zeta grid
INNER_TIGHTENINGS = 2
#: the probe of the fixed point's amplification (see _ZetaLadder._probe_inner): the factor
#: of its diffusion tolerance over (or under) the row's; the factor by which the measured inner error e
#: is charged to the returned value (4 a2 - a1)/3, whose levels carry errors of e's size
#: but not the same ones (the schedules' resolution choices differ): (4 e + e)/3; rows whose
#: diffusion estimate is below rtol A over INNER_PROBE_SKIP are not probed (amplified 30x it
#: stays below rtol A / 10)
INNER_PROBE_FACTOR = 4.0
INNER_PROBE_SAFETY = 5.0 / 3.0
INNER_PROBE_SKIP = 300.0
INNER_PROBE_SATURATED = 0.25
#: kernel flags that only say a diffusion solve missed its own (tighter) tolerance or reached
#: its node cap: its error estimate is part of the row's, which decides the row's flag
ACCURACY_FLAGS = (RTOL_NOT_MET, GRID_CAP)

def _ladder_estimate(a0, a1, a2, ok0):
    """Error estimate of R = (4 a2 - a1)/3 (the end area extrapolated from the two finest
    levels) from three levels of halved cells. [-]

    R0 = (4 a1 - a0)/3 is the same extrapolation one level coarser; R converges at order
    q >= 2 (3 on smooth scenes, about 2 after a square-root onset of the wall where gamma_eff
    changes sign), so |R - R0| / (2^q - 1) with q = 2 is its error, at most ~2.3x over for
    q = 3. A ladder whose ratio r = d1/d2 is not 4 converges at another order than the
    extrapolation assumes: the extrapolation with the observed one, a2 + d2/(r - 1), differs
    from R by |d2| |1/(r - 1) - 1/3|, which the estimate never falls below. Where the ladder
    is not asymptotic (differences of two signs, a ratio outside ``LADDER_RATIO``, or no
    valid a0) it is |a2 - a1|, and at least |a1 - a0| / 4 where a0 is valid: R may then be
    no better than the last correction, which may itself have cancelled by chance (and where
    the two finest levels agree exactly, e.g. both separated, the coarsest one's difference
    says nothing about R).
    """
    d1 = a1 - a0
    d2 = a2 - a1
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.abs(d1) / np.abs(d2)
        order = np.abs(d2) * np.abs(1.0 / (ratio - 1.0) - 1.0 / 3.0)
    est = np.maximum(np.abs((4.0 * d2 - d1) / 3.0) / 3.0, np.where(np.isfinite(order), order, 0.0))
    asymptotic = ok0 & (d1 * d2 > 0) & (ratio >= LADDER_RATIO[0]) & (ratio <= LADDER_RATIO[1])
    # not asymptotic: the last difference, but where a valid coarsest level exists never
    # below a quarter of the one before (a ladder that turns back can end on a difference
    # that cancelled by chance: measured, the finest level 2.9x its last difference off)
    rough = np.where(ok0 & np.isfinite(d1), np.maximum(np.abs(d2), 0.25 * np.abs(d1)),
                     np.abs(d2))
    est = np.where(asymptotic, est, rough)
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


class _Solution(NamedTuple):
    """A row's solve of one zeta level: its outputs (8 arrays, 10 with a yield wall), the
    fixed point's status, and the grid and Onset (or None) it was solved on."""
    outs: list
    status: int
    grid: np.ndarray
    onset: object


class _ZetaLadder:
    """The fixed point on nested zeta grids, Richardson-extrapolated, with a-posteriori
    control of the zeta-grid error of the end area (issue 12).

    Level 0 is :func:`coarsen_zeta` of the grid, level 1 the grid (the result's ``zeta``),
    level k >= 2 its (k-1)-fold :func:`refine_zeta`. Every pressure is solved on levels 0-2;
    one whose estimate (:func:`_ladder_estimate`) exceeds rtol A gets further levels, up to
    ``ZETA_EXTRA_LEVELS``, and then, if still above, status RTOL_NOT_MET. Each level starts
    from level 1's detachment stress (level 0 at its nodes, level 2 interpolated in ln
    zeta), level k > 2 from level k - 1's; level 1 from the given start or full contact.

    With ``graded`` (the default of :func:`solve_contact`), a pressure whose gamma_eff
    changes sign on level 1 gets grids of its own, graded around the sign change
    (:func:`persson_fast.adhesion.zeta_grid.onset_grid`): sigma_a starts there as a square root, which
    a grid of even cells in ln zeta resolves at order 1-1.5 only, with an error constant
    that depends on where the sign change falls between the nodes (the ladder can then look
    asymptotic and be off by several times its estimate). On the graded grids the wall is
    linear between the nodes as everywhere else, and the ladder converges at order 2
    again. Every row's solution is kept on its own grids; the profiles are reported on
    the standard level-1 nodes.
    """

    def __init__(self, zeta, n_p, solve, breakpoints=None, graded=False):
        self.zeta = zeta
        self.n_p = n_p
        self.solve_fn = solve
        z0, self.idx0 = coarsen_zeta(zeta)
        self.std = [z0, zeta, refine_zeta(zeta)]
        self.bp = (np.array([zeta[0], zeta[-1]]) if breakpoints is None
                   else np.asarray(breakpoints, dtype=float))
        self.graded = graded
        self.onset = [None] * n_p      # per row: the Onset (interval, cells) of its grids
        self._centred = {}             # (row, level) -> that Onset centred on the level's own
        self._grids = {}               # (row, level) -> the graded grid of an onset row
        self.sol = []                  # per level, per row: (outputs (8 or 10 arrays), status)
        self.last = np.full(n_p, 2, dtype=np.int64)
        self.iterations = np.zeros(n_p, dtype=np.int64)
        self.residual = np.zeros(n_p)
        self.max_extra = 0
        self.inner_div = np.ones(n_p)   # per pressure: rtol / (its diffusion tolerance)
        self.late = np.zeros(n_p, dtype=bool)   # a late sign change of gamma_eff on level 1
        self.amplification = np.zeros(n_p)      # measured by _probe_inner (0: not probed)

    def standard(self, k):
        """The standard grid of level k (refined as needed)."""
        while len(self.std) <= k:
            self.std.append(refine_zeta(self.std[-1]))
        return self.std[k]

    def level_onset(self, r, k):
        """Row r's Onset on level k (centred on that level's own sign change), or None."""
        return self._centred.get((r, k), self.onset[r])

    def grid(self, r, k):
        """Row r's grid of level k: the standard one, or graded around its onset."""
        o = self.level_onset(r, k)
        if o is None:
            return self.standard(k)
        g = self._grids.get((r, k))
        if g is None:
            g = self._grids[(r, k)] = onset_grid(self.standard(k), o, k)
        return g

    def _centre(self, r, k, u):
        """Centre row r's level-k grid on the sign change at ln zeta = u (a new interval
        around it where u lies outside the row's)."""
        o = self.onset[r]
        if o is None or not o.u_a < u < o.u_b:
            o = self.onset[r] = onset_at(np.exp(u), self.std[0], self.bp)
            for key in [key for key in self._centred if key[0] == r]:
                del self._centred[key]
                self._grids.pop(key, None)
        self._centred[(r, k)] = o.centred(np.exp(u))
        self._grids.pop((r, k), None)

    def solved_grid(self, k, r):
        """The grid row r's level k was solved on."""
        return self.sol[k][r].grid

    def solved_v(self, k, r, zeta=None):
        """Points ``zeta`` (default: the nodes row r's level k was solved on) in the
        coordinate of :func:`onset_coordinate` of that solve's grid."""
        entry = self.sol[k][r]
        return onset_coordinate(entry.grid if zeta is None else zeta, entry.onset)

    def _replan_as_solved(self, k, r):
        """Solve row r's level k again on the grid of its stored solution."""
        entry = self.sol[k][r]
        if entry.onset is not None:
            self._centred[(r, k)] = entry.onset
            self._grids[(r, k)] = entry.grid

    def _solve_level(self, k, rows, starts):
        """Solve level k of ``rows`` from ``starts`` (per row: detachment stresses [Pa] on
        its grid, or None for full contact)."""
        rows = np.asarray(rows, dtype=np.int64)
        grids = [self.grid(r, k) for r in rows]
        outs, n_z, status, iterations, residual = self.solve_fn(grids, starts, rows,
                                                               self.inner_div[rows])
        # a row that did not converge from a given start (at p_nom = 0 on a surface that is
        # not sticky, a start extrapolated from two coarser levels can leave the iteration
        # alternating between contact and separation): once more from the next coarser
        # level's profile alone, else from full contact
        again = np.flatnonzero((status == NOT_CONVERGED)
                               & np.array([s is not None for s in starts], dtype=bool))
        if again.size:
            c = k + 1 if k == 0 else k - 1
            plain = [self._profile_on(c, rows[i], grids[i]) for i in again]
            more = self.solve_fn([grids[i] for i in again], plain, rows[again],
                                 self.inner_div[rows[again]])
            width = outs[0].shape[1]
            for i, j in enumerate(again):
                for o, o2 in zip(outs, more[0]):
                    o[j, :more[1][i]] = o2[i, :more[1][i]]
                    o[j, more[1][i]:width] = np.nan
                n_z[j] = more[1][i]
                status[j] = more[2][i]
                iterations[j] += more[3][i]
                residual[j] = more[4][i]
        while len(self.sol) <= k:
            self.sol.append([None] * self.n_p)
        for i, r in enumerate(rows):
            self.sol[k][r] = _Solution([o[i, :n_z[i]] for o in outs], int(status[i]), grids[i],
                                       self.level_onset(r, k))
        self.iterations[rows] += iterations
        self.residual[rows] = np.maximum(self.residual[rows], residual)
        return status

    def _profile_on(self, k, r, grid):
        """Row r's level-k detachment stress interpolated onto ``grid`` (linear in the
        solve's :func:`onset_coordinate`), or None where level k failed."""
        if not self._ok(k, r):
            return None
        return np.interp(self.solved_v(k, r, grid), self.solved_v(k, r), self.sol[k][r].outs[1])

    def _ok(self, k, r):
        entry = self.sol[k][r] if k < len(self.sol) else None
        return (entry is not None and entry.status == 0
                and bool(np.all(np.isfinite(entry.outs[1]))))

    def _start_from(self, k, rows):
        """Start of level k + 1 from level k's detachment stress (full contact where level k
        failed): level k's values at its own nodes and their cubic interpolant between them
        (:func:`_midpoints_cubic`, in the row's :func:`onset_coordinate`), plus, where level
        k - 1 is solved too, the change to the finer level that second-order convergence
        predicts, (x_k - x_k-1)/4 (linear in that coordinate). Only the start: the fixed
        point's stop is the same, but from it the seed scene's level 2 takes 4.1 iterations
        instead of 5.1 (linear interpolation alone), at rtol 1e-6."""
        starts = []
        for r in rows:
            if not self._ok(k, r):
                starts.append(None)
                continue
            x = self.sol[k][r].outs[1]
            z_from, z_to = self.solved_grid(k, r), self.grid(r, k + 1)
            v_from, v_to = self.solved_v(k, r), self.solved_v(k, r, z_to)
            if z_to.size == 2 * z_from.size - 1 and np.array_equal(z_to[0::2], z_from):
                start = _midpoints_cubic(v_from, x[None, :])[0]
            else:
                start = np.interp(v_to, v_from, x)
            regular = bool(np.all(np.diff(z_to) > NARROW_CELL_RTOL * z_to[:-1]))
            # (not on a grid with cells a few ulps wide, a user's: the change, interpolated
            # across such a cell, would make the wall jump where G is flat)
            if regular and k >= 1 and self._ok(k - 1, r):
                z_c = self.solved_grid(k - 1, r)
                v_c = self.solved_v(k - 1, r)
                change = (np.interp(self.solved_v(k, r, z_c), v_from, x)
                          - self.sol[k - 1][r].outs[1]) / 4.0
                start = np.maximum(start + np.interp(self.solved_v(k - 1, r, z_to), v_c,
                                                     change), 0.0)
            starts.append(start)
        return starts

    def _crossing(self, k, r):
        """ln zeta where row r's gamma_eff on level k changes sign (g linear in ln zeta in
        the cell), or None (no sign change, or more than one)."""
        entry = self.sol[k][r]
        if entry is None:
            return None
        g = entry.outs[2]
        cells = np.flatnonzero((g[:-1] > 0) != (g[1:] > 0))
        if cells.size != 1:
            return None
        i = int(cells[0])
        u = np.log(entry.grid)
        return float(u[i] + (u[i + 1] - u[i]) * g[i] / (g[i] - g[i + 1]))

    def _solve_centred(self, k, rows, starts):
        """Solve level k of ``rows``; a row with an onset is solved again, from its last
        solution, on a grid centred on the sign change of that solution while it lies more
        than ``ONSET_CENTRE_TOL`` of the level's narrowest graded cell away from the centre
        (at most ``ONSET_CENTRE_PASSES`` times). Each level is graded around its own sign
        change: the error of a level then follows the grid's spacing alone, as the ladder's
        extrapolation assumes (with one centre for all levels its share of a cell changes
        4x per level, and the end area erred by up to 0.24 rtol for a centre a quarter of
        level 2's narrowest cell off)."""
        self._solve_level(k, rows, starts)
        todo = [r for r in rows if self.onset[r] is not None]
        for _ in range(ONSET_CENTRE_PASSES):
            redo, starts = [], []
            for r in todo:
                u = self._crossing(k, r)
                o = self.level_onset(r, k)
                if u is None or abs(u - o.u_star) <= ONSET_CENTRE_TOL * o.first_cell(k):
                    continue
                v_old, x_old = self.solved_v(k, r), self.sol[k][r].outs[1]
                ok = self._ok(k, r)
                self._centre(r, k, u)
                redo.append(r)
                starts.append(np.interp(self.solved_v(k, r, self.grid(r, k)), v_old, x_old)
                              if ok else None)
            if not redo:
                return
            self._solve_level(k, np.array(redo), starts)
            todo = redo

    def _predict_centre(self, k, rows):
        """Centre the graded rows' level k on their predicted sign change: that of level
        k - 1 plus the second-order change from level k - 2 to k - 1, (u_k-1 - u_k-2)/4
        (level 0: level 1's)."""
        for r in rows:
            if self.onset[r] is None:
                continue
            prev = [self._crossing(j, r) for j in ((1,) if k == 0 else (k - 1, k - 2))]
            if prev[0] is None:
                continue
            u = prev[0]
            if len(prev) > 1 and prev[1] is not None:
                u += (prev[0] - prev[1]) / 4.0
            self._centre(r, k, u)

    def solve(self, start):
        rows = np.arange(self.n_p)
        # level 1 first, from the given start or full contact (where a two-level solve
        # started: from a coarser profile it would, at p_nom = 0 on a surface that is not
        # sticky, end on a contact area of 1e-13 instead of the separated state); level 0
        # starts from level 1's profile at its nodes (about half the iterations of a start
        # from full contact), level 2 from level 1's profile interpolated
        self._solve_level(1, rows, [None if start is None else start[r] for r in rows])
        # a late sign change of gamma_eff: the diffusion tolerance is tightened from here on
        # (CROSSING_LATE, CROSSING_INNER_DIV)
        late = [r for r in rows if self.sol[1][r].status == 0 and self._late_crossing(r)]
        self.late[late] = True
        graded = []
        if self.graded:
            for r in rows:
                u = self._crossing(1, r)
                if u is not None and 0.0 < u < np.log(self.zeta[-1]):
                    graded.append(r)
                    self._centre(r, 1, u)
            if graded:
                self._solve_centred(1, np.array(graded), [
                    self._profile_on(1, r, self.grid(r, 1)) for r in graded])
        # (an ungraded row: its diffusions to rtol / CROSSING_INNER_DIV from here on; a graded
        # row tightens them only where its estimate asks for it, see refine_until)
        late = [r for r in late if r not in graded]
        self.inner_div[late] = CROSSING_INNER_DIV
        if late:
            self._solve_level(1, np.array(late), [self.sol[1][r].outs[1].copy() for r in late])
        self._predict_centre(0, rows)
        self._solve_centred(0, rows, [self._profile_on(1, r, self.grid(r, 0)) for r in rows])
        self._predict_centre(2, rows)
        self._solve_centred(2, rows, self._start_from(1, rows))
        self._probe_inner(rows)

    def _probe_inner(self, rows):
        """Measure by how much the fixed point amplifies its diffusion solves' errors in the
        end area: level 0 again with the diffusions INNER_PROBE_FACTOR (F) times looser
        (cheaper; from its own solution; the level keeps its first solution): the change of
        the end area over F - 1 is the error the solves at the row's tolerance make in it;
        over the diffusion's own estimate of the end area, the amplification
        (``self.amplification``, at least 1), which the estimate of every level's diffusion
        error is then charged with. Where the looser solves change the end area by less
        than INNER_PROBE_SATURATED of that estimate (both tolerances then reached the
        kernel's coarsest resolution), the level again F times tighter instead: the change
        times F / (F - 1). A sign change of gamma_eff amplifies most: a diffusion error
        moves the sign change and with it the end area (measured on a self-affine scene,
        H 0.89: 17x). Rows whose diffusion estimate could not matter even amplified (below
        rtol A / INNER_PROBE_SKIP) are not probed. Level 0's own diffusion error differs
        from the finer levels' (their schedules force other steps), the amplification is
        the fixed point's."""
        sel = [r for r in rows if self._ok(0, r) and self._end(0, r) > 0.0
               and abs(self.sol[0][r].outs[7][-1]) * INNER_PROBE_SKIP
               > self.rtol * self._end(0, r) + 1e-12]
        f = INNER_PROBE_FACTOR
        for factor, scale in ((1.0 / f, 1.0 / (f - 1.0)), (f, f / (f - 1.0))):
            if not sel:
                return
            sel = np.array(sel, dtype=np.int64)
            kept = [self.sol[0][r] for r in sel]
            for r in sel:
                self._replan_as_solved(0, r)
            self.inner_div[sel] *= factor
            self._solve_level(0, sel, [self.sol[0][r].outs[1].copy() for r in sel])
            self.inner_div[sel] /= factor
            again = []
            for i, r in enumerate(sel):
                probe = self.sol[0][r]
                self.sol[0][r] = kept[i]
                if probe.status != 0:
                    continue
                change = abs(kept[i].outs[0][-1] - probe.outs[0][-1])
                own = abs(kept[i].outs[7][-1])
                if factor < 1.0 and change < INNER_PROBE_SATURATED * own:
                    again.append(r)
                    continue
                self.amplification[r] = max(1.0, change * scale / own) if own > 0 else 1.0
            sel = again

    def _end(self, k, r):
        return self.sol[k][r].outs[0][-1]

    def _end_estimate(self):
        """Estimate of the end area's zeta-grid error per pressure, the split mask (one of
        the two finest levels separated, the other in contact: no extrapolation) and the
        returned end area. The estimate includes the inner (diffusion) error estimate of the
        finest level's end area (``self.inner``)."""
        n = np.arange(self.n_p)
        K = self.last
        a2 = np.array([self._end(K[r], r) for r in n])
        a1 = np.array([self._end(K[r] - 1, r) for r in n])
        a0 = np.array([self._end(K[r] - 2, r) for r in n])
        ok0 = np.array([self.sol[K[r] - 2][r].status == 0 for r in n]) & np.isfinite(a0)
        ok0 &= (a0 > 0) == (a1 > 0)
        graded = np.array([o is not None for o in self.onset], dtype=bool)
        # an ungraded sign change (pull_off's discretisation, or one that appears on
        # another level than 1) keeps the rules of the even grid below
        resolved = np.array([graded[r] or self._crossing_resolved(K[r] - 2, r) for r in n])
        ok0 &= resolved
        split = (a1 > 0) != (a2 > 0)
        est = np.where(split, np.abs(a2 - a1), _ladder_estimate(a0, a1, a2, ok0))
        # after a square-root onset of sigma_a on an even grid the extrapolated value
        # converges at an order near 1.5 with a constant that depends on where the sign
        # change falls between the nodes: its ladder can look asymptotic and still be off by
        # several times the ladder estimate (measured: 0.17x at rtol 1e-5); there the last
        # un-extrapolated difference bounds the estimate from below: the error of the finest
        # un-extrapolated value at order 1.5, |a2 - a1| / (2^1.5 - 1), which the
        # extrapolated value betters (measured 2-5x the error of the returned value)
        crossing = np.array([not graded[r] and self._has_crossing(K[r], r) for r in n])
        est = np.where(crossing, np.maximum(est, np.abs(a2 - a1) / (2.0 ** 1.5 - 1.0)), est)
        # on graded grids the extrapolated values still scatter, at coarse levels, by a few
        # per cent of the last difference (ONSET_FLOOR)
        est = np.where(graded, np.maximum(est, ONSET_FLOOR * np.abs(a2 - a1)), est)
        area = np.where(split, a2, np.clip((4.0 * a2 - a1) / 3.0, 0.0, 1.0))
        # an area falling towards 0 whose extrapolation clips to 0 (contact vanishing as the
        # grid refines, e.g. at p_nom = 0 on a surface that is not sticky): the limit lies in
        # [0, a2], so 0 is off by at most a2
        vanishing = ~split & (4.0 * a2 - a1 <= 0.0) & (a2 <= a1)
        # a sign change of gamma_eff that the ladder's coarsest level does not resolve: the
        # ladder says little (measured: an estimate 0.38x the error on a tabulated spectrum);
        # such a row is refined, and flagged if the work cap leaves it unresolved
        self.unresolved = ~resolved & ~split & ~vanishing
        est = np.where(self.unresolved,
                       np.maximum(est, np.maximum(np.abs(a1 - a0), np.abs(a2 - a1))), est)
        inner = np.array([abs(self.sol[K[r]][r].outs[7][-1]) for r in n])
        probed = self.amplification > 0.0
        # a late sign change: the diffusions' own estimates fall short on its fast receding
        # wall by a factor the probe at level 0 need not see (its coarse wall recedes
        # otherwise), so its margin stays beside the measured amplification
        factor = np.where(probed, INNER_PROBE_SAFETY * self.amplification, 1.0)
        factor = np.where(self.late, np.maximum(factor, CROSSING_INNER_MARGIN), factor)
        inner = factor * inner
        self.ladder_part = np.where(vanishing, np.minimum(est, a2), est)
        self.inner = inner
        est = np.where(vanishing, np.minimum(est + inner, a2), est + inner)
        return est, split, area

    def _crossing_cells(self, k, r):
        """The cells of level k where row r's gamma_eff changes sign."""
        g = self.sol[k][r].outs[2]
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
        z = self.solved_grid(k, r)
        width = np.log10(z[cells + 1] / z[cells])
        return bool(np.all(width <= 1.01 / CROSSING_MIN_PER_DECADE))

    def _status_of(self, r):
        s2 = self.sol[self.last[r]][r].status
        s1 = self.sol[self.last[r] - 1][r].status
        return s2 if s2 != 0 else s1

    def _statuses(self, est, area, rtol):
        """The status per pressure: that of the two finest levels' solves, except that a
        diffusion solve that missed its (tighter) tolerance or reached its node cap is not a
        flag of its own: its estimate is part of ``est``, and a row whose ``est`` exceeds
        rtol A (or whose sign change stays unresolved) is RTOL_NOT_MET."""
        status = np.array([self._status_of(r) for r in range(self.n_p)], dtype=np.int64)
        status[np.isin(status, ACCURACY_FLAGS)] = 0
        miss = (est > rtol * area + 1e-12) | self.unresolved
        status[(status == 0) & miss] = RTOL_NOT_MET
        return status

    def refine_until(self, rtol):
        """Refine the rows whose estimate misses rtol A: where the diffusion solves' share
        of the estimate (charged with the fixed point's amplification) is the larger, the
        row solves its three finest levels again with a diffusion tolerance
        CROSSING_INNER_DIV times tighter (at most ``INNER_TIGHTENINGS`` times); else a
        finer zeta level (at most ``ZETA_EXTRA_LEVELS``)."""
        tightened = 0
        extra = 0
        while True:
            est, _, area = self._end_estimate()
            status = self._statuses(est, area, rtol)
            rows = np.flatnonzero(status == RTOL_NOT_MET)
            if rows.size == 0:
                break
            inner_led = self.inner[rows] >= self.ladder_part[rows]
            if tightened < INNER_TIGHTENINGS and np.any(inner_led):
                tightened += 1
                sel = rows[inner_led]
                self.inner_div[sel] *= CROSSING_INNER_DIV
                for back in (2, 1, 0):
                    for k in np.unique(self.last[sel] - back):
                        at = sel[self.last[sel] - back == k]
                        for r in at:
                            self._replan_as_solved(k, r)
                        self._solve_centred(k, at, [self.sol[k][r].outs[1].copy()
                                                    if self._ok(k, r) else None for r in at])
                continue
            rows = rows[~inner_led | (tightened >= INNER_TIGHTENINGS)]
            if extra >= ZETA_EXTRA_LEVELS or rows.size == 0:
                break
            extra += 1
            k = 2 + extra
            rows = rows[self.last[rows] == k - 1]
            self._predict_centre(k, rows)
            self._solve_centred(k, rows, self._start_from(k - 1, rows))
            self.last[rows] = k
            self.max_extra = extra
        est, _, area = self._end_estimate()
        self.status = self._statuses(est, area, rtol)

    def _on_zeta(self, k, r):
        """Row r's level-k outputs at the result's nodes (level 1 of the standard grids):
        the nodes its grid shares with them, and the cubic interpolant (in its
        :func:`onset_coordinate`) at those that an onset grid replaced."""
        outs = self.sol[k][r].outs
        z = self.solved_grid(k, r)
        if self.sol[k][r].onset is None and z is self.std[k]:
            return [o[::2 ** (k - 1)] for o in outs]
        i = np.minimum(np.searchsorted(z, self.zeta), z.size - 1)
        exact = z[i] == self.zeta
        stacked = np.array(outs)
        res = stacked[:, i]
        if not np.all(exact):
            res[:, ~exact] = _cubic_at(self.solved_v(k, r), stacked,
                                       self.solved_v(k, r, self.zeta[~exact]))
        return list(res)

    def profiles(self):
        """Profiles on the level-1 nodes: the extrapolation of the two finest levels of each
        pressure (the finer alone where one of them separated), and the error estimates."""
        n_z = self.zeta.size
        n_out = len(self.sol[1][0].outs)
        res = [np.zeros((self.n_p, n_z)) for _ in range(n_out)]
        err = np.zeros((self.n_p, n_z))
        zeta_err = np.zeros(self.n_p)
        est, split, _ = self._end_estimate()
        for r in range(self.n_p):
            K = self.last[r]
            fine = self._on_zeta(K, r)
            prev = self._on_zeta(K - 1, r)
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


def _cubic_at(v, y, t):
    """The cubic Lagrange interpolant of the rows of y (n_rows, n) on the increasing nodes v
    at the points t, from the four nodes around each (the two end cells: linear)."""
    n = v.size
    j = np.clip(np.searchsorted(v, t) - 1, 0, n - 2)
    lam = (t - v[j]) / (v[j + 1] - v[j])
    out = y[:, j] + (y[:, j + 1] - y[:, j]) * lam
    inner = (j >= 1) & (j <= n - 3)
    if n >= 4 and np.any(inner):
        jj, tt = j[inner], t[inner]
        nodes = [jj - 1, jj, jj + 1, jj + 2]
        val = np.zeros((y.shape[0], jj.size))
        for a in range(4):
            w = np.ones(jj.size)
            for b in range(4):
                if a != b:
                    w *= (tt - v[nodes[b]]) / (v[nodes[a]] - v[nodes[b]])
            val += w * y[:, nodes[a]]
        out[:, inner] = val
    return out


def _breakpoints(surface, zeta):
    """The spectrum's breakpoints on the zeta axis (with 1 and zeta1), merged as in
    :func:`adhesion_zeta`: an onset grid never grades across one."""
    return _merged_breakpoints(np.asarray(surface.breakpoints(), dtype=float) / surface.q0,
                               float(zeta[-1]))


def _miss_message(ladder, p, area, rtol):
    """What the rows flagged RTOL_NOT_MET missed, in the user's terms: the worst one's
    estimated error of A/A0 against rtol A, split into the zeta grid's part and that of
    the diffusion solves and the fixed point's last change."""
    bad = np.flatnonzero(ladder.status == RTOL_NOT_MET)
    est = ladder.ladder_part + ladder.inner
    rel = est[bad] / np.maximum(rtol * area[bad] + 1e-12, 1e-300)
    r = int(bad[np.argmax(rel)])
    return (f"; estimated error of A/A0 up to {rel.max():.3g}x the tolerance rtol A + 1e-12 "
            f"(rtol {rtol:.3g}), worst at p = {p[r]:.6g} Pa: A = {area[r]:.6g}, estimated "
            f"error {est[r]:.3g} of which the zeta grid {ladder.ladder_part[r]:.3g} (refined "
            f"{ladder.last[r] - 2} of {ZETA_EXTRA_LEVELS} times) and the diffusion solves and "
            f"fixed-point iteration {ladder.inner[r]:.3g}")

