"""Prototype of issue 41: adhesion as one forward march in G and a scalar root in K.

**Status: a private prototype.** :func:`persson_fast.solve_contact` does not use it (no route,
no public name); nothing here is API and it may change or go. The measured status (one
thread, CPU time per pressure; the table and how it was measured are in the docstring of
``benchmarks/march_prototype.py``): errors 0.2-0.9 rtol at rtol 1e-4 to 1e-6 on the
self-affine and seed scenes, but the error estimate falls below the error on the self-affine
scene at rtol 1e-6 (estimate/error 0.42) and is pessimistic on the seed scene at p = 0
(tests/test_adhesion_march.py, the strict xfail); 0.10x to 19x today's speed (slower than
today at rtol 1e-6 where there is no sign change of gamma_eff). With very weak adhesion
(U_el/dgamma above ~1e14, where the rounding of K ~ -U_el/dgamma is the size of A) Phi is
quantised at K's rounding; the root then stops on a bracket whose end areas agree to the
tolerance (the area is resolved, K only to its rounding; tested down to dgamma 1e-30).

Seed Eq. 9, A(zeta) gamma_eff(zeta) = A(zeta1) dgamma - U_el(zeta), with
U_el(zeta) = U_el(1) - J(zeta) and J(zeta) = (pi E*/2) int_{q0}^{zeta q0} q^2 C F(A) dq:

    A(zeta) gamma_eff(zeta) = dgamma K + J(zeta),     K = A(zeta1) - U_el(1)/dgamma.

J holds only scales coarser than zeta, so for a given K a forward march computes sigma_a on
the fly (:func:`persson_fast._kernels.march.march_k`), and the fixed point is the scalar
equation Phi(K) = K + J(zeta1; K)/dgamma - A(zeta1; K) = 0 (U_el(zeta1) = 0, so
U_el(1) = J(zeta1)), bracketed by K in [-U_el,full/dgamma, 1]: at K = 1, Phi >= 1 - A >= 0;
at K = -U_full/dgamma, Phi = (J - U_full)/dgamma - A <= 0 (F(A) <= 1, A >= 0).

The driver here: the mesh of G (union of points uniform in ln zeta and in ln G, each level
bisecting the previous level's intervals in ln zeta), the root at each of three levels (node
spacing and steps halved each time; each level has its own root), Richardson extrapolation of
the coupled end area and an error estimate with an observed-order term. Only the original
theory (S = 1 or the S correction), no yield wall, a spectrum without flat stretches of G.
"""
from __future__ import annotations

import math
import time

import numpy as np

from .._kernels.march import (I_AREA, I_GSTAR, I_J, I_SOLVES, I_STATUS, I_WORK, N_INFO,
                             ST_SEPARATED, march_k)
from ..scene import DETACHMENT_PREFACTOR

#: resolution of level 0 at rtol 1e-6 (node spacing in xi, mesh points per decade of zeta and
#: per e-fold of G, onset steps); scaled with rtol as (rtol/1e-6)^(1/RES_ORDER)
H0 = 0.01
N_ZETA = 16.0
N_G = 5.0
ONSET_M = 16
M_START = 4
M_PRE = 2
RES_ORDER = 1.8
RES_ORDER_M = 4.0
N_DAMP = 0
#: the root at each level stops when the bracket's two end areas differ by at most this
#: fraction of rtol A
ROOT_TOL = 1e-3


class MarchMesh:
    """The G mesh of one scene at ``levels`` levels (scene units: G / scale^2, c^2 / scale^2)."""

    def __init__(self, surface, e_star, dgamma, beta, n_z, n_g, levels):
        q0 = float(surface.q0)
        zeta1 = float(surface.q1) / q0
        lnz1 = math.log(zeta1)
        # candidates: uniform in ln zeta ...
        nz = max(2, int(math.ceil(math.log10(zeta1) * n_z)))
        x_a = np.expm1(np.linspace(0.0, lnz1, nz + 1))
        # ... and uniform in ln G (from a table of G(zeta))
        x_t = np.concatenate([np.geomspace(1e-12, 1e-3, 400, endpoint=False),
                              np.expm1(np.linspace(math.log1p(1e-3), lnz1, 1600))])
        G_t = np.asarray(surface.diffusion_time(q0 * (1.0 + x_t), e_star), dtype=float)
        G1 = float(G_t[-1])
        ok = G_t > 0
        x_t, G_t = x_t[ok], G_t[ok]
        n_geo = int(math.floor(math.log(G1 / G_t[0]) * n_g))
        G_k = G1 * np.exp(-np.arange(n_geo + 1) / n_g)
        x_b = np.exp(np.interp(np.log(G_k), np.log(G_t), np.log(x_t)))
        x = np.unique(np.concatenate([[0.0], x_a, x_b, [zeta1 - 1.0]]))
        G = np.asarray(surface.diffusion_time(q0 * (1.0 + x), e_star), dtype=float)
        G[0] = 0.0
        # merge points closer than 0.3 of the finer of the two spacings
        def dist(a, k):
            dz = n_z * (math.log1p(x[k]) - math.log1p(x[a])) / math.log(10.0)
            dg = n_g * (math.log(G[k] / G[a])) if G[a] > 0 else np.inf
            return max(dz, dg)

        last = x.size - 1
        keep = [0]
        for k in range(1, last):
            if dist(keep[-1], k) >= 0.3 and dist(k, last) >= 0.3:
                keep.append(k)
        keep.append(last)
        x0 = x[keep]
        # levels: bisect in ln zeta
        xs = x0
        for _ in range(levels - 1):
            mid = np.expm1(0.5 * (np.log1p(xs[:-1]) + np.log1p(xs[1:])))
            new = np.empty(2 * xs.size - 1)
            new[0::2] = xs
            new[1::2] = mid
            xs = new
        q = q0 * (1.0 + xs)
        q[0], q[-1] = q0, float(surface.q1)
        G = np.asarray(surface.diffusion_time(q, e_star), dtype=float)
        G[0] = 0.0
        G = np.maximum.accumulate(G)
        scale = math.sqrt(G[-1])
        self.scale = scale
        self.levels = levels
        self.q = q
        self.zeta = 1.0 + xs
        self.G = G / scale**2
        c2 = beta**2 * dgamma * e_star * q
        C = np.asarray(surface.psd(np.clip(q, q0 * (1 + 1e-15), q[-1] * (1 - 1e-15))),
                       dtype=float)
        self.c2 = c2 / scale**2
        self.dc2 = beta**2 * dgamma * e_star / (0.25 * math.pi * e_star**2 * q**3 * C)
        # j with A = 1: (pi E*/(2 dgamma)) int_{q0}^{q} q'^2 C dq' (closed form of the model)
        j1 = 0.5 * math.pi * e_star * np.asarray(surface.moment(2, q0, q), dtype=float) / dgamma
        j1[0] = 0.0
        self.j1 = np.maximum.accumulate(j1)
        self.stride = [2 ** (levels - 1 - L) for L in range(levels)]
        base = np.zeros(xs.size, dtype=np.int64)
        base[::2 ** (levels - 1)] = 1
        self.base = base
        self.n0 = x0.size

    def level(self, L):
        s = self.stride[L]
        return (np.ascontiguousarray(self.G[::s]), np.ascontiguousarray(self.c2[::s]),
                np.ascontiguousarray(self.dc2[::s]), np.ascontiguousarray(self.j1[::s]),
                np.ascontiguousarray(self.base[::s]))


class _Level:
    def __init__(self, mesh, L, h, sig0, beta2, gamma_s):
        self.G, self.c2, self.dc2, self.j1, self.base = mesh.level(L)
        self.refine = 2 ** L
        self.h, self.sig0, self.beta2, self.gamma_s = h, sig0, beta2, gamma_s
        n = self.G.size
        self.pa, self.ps, self.pj = np.empty(n), np.empty(n), np.empty(n)
        self.info = np.empty(N_INFO)
        self.calls = 0
        self.work = 0.0

    def phi(self, K):
        march_k(K, self.sig0, self.beta2, self.gamma_s, self.G, self.c2, self.dc2, self.j1,
                self.base,
                self.h, N_DAMP, self.refine, M_START, M_PRE, ONSET_M, self.pa, self.ps, self.pj, self.info)
        self.calls += 1
        self.work += self.info[I_WORK]
        return K + self.info[I_J] - self.info[I_AREA], self.info[I_AREA], self.info.copy()


def _solve_root(level, pts, tol_rel, k_min, k_max, max_iter=60):
    """The root of Phi(K) from the evaluated points ``pts`` [(K, Phi, A), ...] (at least two):
    secant steps through the two newest points, inside the bracket once a sign change is
    known (bisection when a step leaves it or the bracket shrinks too slowly: Dekker's
    method). Stops when the best point's area error, estimated as |Phi| |dA/dK| / |dPhi/dK|
    (slopes from the two newest points; at least |Phi|, so that a stretch where A does not
    depend on K stops nothing), is at most tol_rel A; returns (K, A, slope of Phi)
    corrected by that secant step."""
    neg = pos = None

    def note(k, f, a):
        nonlocal neg, pos
        if f <= 0 and (neg is None or k_closer(k, neg, pos)):
            neg = (k, f, a)
        if f >= 0 and (pos is None or k_closer(k, pos, neg)):
            pos = (k, f, a)

    def k_closer(k, old, other):
        # the bracket end nearest the other end (the bracket shrinks)
        return other is None or abs(k - other[0]) < abs(old[0] - other[0])

    for k, f, a in pts:
        note(k, f, a)
    width0 = None
    stall = 0
    n_expand = 0
    for it in range(max_iter):
        (ka, fa, aa), (kb, fb, ab) = pts[-2], pts[-1]
        s_phi = (fb - fa) / (kb - ka) if kb != ka else np.nan
        s_a = (ab - aa) / (kb - ka) if kb != ka else 0.0
        best = min(pts, key=lambda t: abs(t[1]))
        if np.isfinite(s_phi) and s_phi != 0:
            err = abs(best[1]) * max(abs(s_a / s_phi), 1.0)
            if err <= tol_rel * max(best[2], 1e-12) or best[1] == 0.0:
                return best[0] - best[1] / s_phi, best[2] - best[1] * s_a / s_phi, s_phi
            k = kb - fb / s_phi
        else:
            k = np.nan
        if neg is not None and pos is not None:
            lo, hi = min(neg[0], pos[0]), max(neg[0], pos[0])
            width = hi - lo
            # a bracket at K's rounding, or one whose two end areas agree to the tolerance
            # (A is continuous in K: the root's area lies between them)
            if (width <= 32.0 * np.spacing(max(abs(lo), abs(hi), 1e-300))
                    or abs(pos[2] - neg[2]) <= tol_rel * max(min(pos[2], neg[2]), 1e-12)):
                t = -neg[1] / (pos[1] - neg[1]) if pos[1] != neg[1] else 0.5
                return neg[0] + t * (pos[0] - neg[0]), neg[2] + t * (pos[2] - neg[2]), s_phi
            if width0 is not None and width > 0.5 * width0:
                stall += 1
            else:
                stall = 0
                width0 = width
            if not (lo < k < hi) or stall >= 3:
                k = 0.5 * (lo + hi)
                stall = 0
                width0 = width
        else:
            # no bracket yet. K + j(zeta1) is a difference of two numbers of size
            # ~U_el(1)/dgamma: with weak adhesion (U_el/dgamma ~ 1e19 at dgamma 1e-20) Phi is
            # quantised at K's rounding (thousands, against A ~ 1e-2), the secant slope is
            # noise or NaN (the same K twice), and steps of a few ulps stay on the side where
            # the onset's j increments round away (Phi = -A). Phi(k_min) <= 0 <= Phi(k_max):
            # where the secant step is NaN, goes away from the sign change (down where Phi < 0)
            # or is below 4 ulps of K, step towards the sign change by 64 ulps, 4 times more
            # with each such step, so that a bracket is found in a few marches
            up = fb < 0.0 if fb != 0.0 else (np.isfinite(k) and k > kb)
            ulp = np.spacing(max(abs(kb), 1e-300))
            if not np.isfinite(k) or (k > kb) != up or abs(k - kb) < 4.0 * ulp:
                d = 64.0 * ulp * 4.0 ** n_expand
                n_expand += 1
                k = kb + (d if up else -d)
        k = min(max(k, k_min), k_max)
        if any(k == t[0] for t in pts):
            raise RuntimeError(f"Phi: K = {k!r} evaluated twice (no progress of the root)")
        f, a, _ = level.phi(k)
        pts.append((k, f, a))
        note(k, f, a)
    raise RuntimeError("root of Phi(K) not found within max_iter marches")


def resolution(rtol):
    """Level-0 resolution (h, mesh points per decade of zeta, per e-fold of G) for rtol: the
    node spacing scales as (rtol/1e-6)^(1/RES_ORDER), the mesh as (rtol/1e-6)^(1/RES_ORDER_M)
    (the leading error after extrapolation is the post-onset layer, set by h)."""
    f = rtol / 1e-6
    fm = f ** (1.0 / RES_ORDER_M)
    return min(H0 * f ** (1.0 / RES_ORDER), 0.2), max(N_ZETA / fm, 4.0), max(N_G / fm, 1.0)


def solve_march(surface, pressure, *, e_star, work_of_adhesion, rtol=1e-6,
                energy_correction=None, detachment_prefactor=DETACHMENT_PREFACTOR, levels=3,
                res=None, mesh=None):
    """Adhesive contact by the forward march and the root in K, at each pressure.

    Returns a dict: ``area`` (the Richardson-extrapolated A(zeta1)/A0), ``error_estimate``,
    ``areas`` (levels, n_p) the end areas of each level at its own root, ``K`` (levels, n_p),
    ``g_star`` (the sign change's G [Pa^2], NaN if none), ``marches`` (levels, n_p),
    ``order`` (observed order of the level differences), ``cpu`` seconds.
    """
    t0 = time.process_time()
    p = np.atleast_1d(np.asarray(pressure, dtype=float))
    beta = float(detachment_prefactor)
    dg = float(work_of_adhesion)
    gamma_s = -1.0 if energy_correction is None else float(energy_correction)
    h0, n_z, n_g = res if res is not None else resolution(rtol)
    if mesh is None:
        mesh = MarchMesh(surface, e_star, dg, beta, n_z, n_g, levels)
    scale = mesh.scale
    u_full = surface.elastic_energy_full_contact(e_star) / dg
    n_p = p.size
    areas = np.full((levels, n_p), np.nan)
    Ks = np.full((levels, n_p), np.nan)
    calls = np.zeros((levels, n_p), dtype=np.int64)
    work = np.zeros((levels, n_p))
    g_star = np.full(n_p, np.nan)
    status = np.zeros(n_p, dtype=np.int64)
    for r in range(n_p):
        sig0 = p[r] / scale
        slope = 0.0
        for L in range(levels):
            lev = _Level(mesh, L, h0 / 2**L, sig0, beta**2, gamma_s)
            k_min, k_max = -u_full * (1.0 + 1e-12) - 1e-14, 1.0
            if L == 0:
                f_lo, a_lo, _ = lev.phi(k_min)
                f_hi, a_hi, _ = lev.phi(k_max)
                if not (f_lo <= 0.0 <= f_hi):
                    raise RuntimeError(f"Phi not bracketed: {f_lo}, {f_hi}")
                pts = [(k_min, f_lo, a_lo), (k_max, f_hi, a_hi)]
            else:
                k_guess = Ks[L - 1, r]
                if L >= 2:
                    k_guess = Ks[L - 1, r] + (Ks[L - 1, r] - Ks[L - 2, r]) / 4.0
                f0, a0, _ = lev.phi(k_guess)
                k1 = min(max(k_guess - f0 / slope, k_min), k_max)
                if k1 == k_guess:
                    k1 = k_guess * (1 + 1e-9) + 1e-12
                f1, a1, _ = lev.phi(k1)
                pts = [(k_guess, f0, a0), (k1, f1, a1)]
            k, a, slope = _solve_root(lev, pts, ROOT_TOL * rtol, k_min, k_max)
            info = lev.info
            Ks[L, r], areas[L, r] = k, a
            calls[L, r] = lev.calls
            work[L, r] = lev.work
            if info is not None and info[I_GSTAR] >= 0:
                g_star[r] = info[I_GSTAR] * scale**2
            if info is not None:
                status[r] |= int(info[I_STATUS]) & ~ST_SEPARATED
    area, est, order = richardson(areas)
    return {"area": area, "error_estimate": est, "areas": areas, "K": Ks, "g_star": g_star,
            "marches": calls, "work": work, "order": order, "status": status,
            "cpu": time.process_time() - t0, "mesh_points": mesh.n0, "h0": h0}


def richardson(areas):
    """Extrapolated end area (4 A2 - A1)/3 and its error estimate from three levels: the
    larger of the extrapolated values' difference / 7 (order 3 after extrapolation) and the
    observed-order term |d2| |1/(rho - 1) - 1/3|, rho = d1/d2 the ratio of the successive
    differences (order 2: rho = 4, term 0; a first-order error left: rho = 2, term 2/3 |d2|)."""
    a0, a1, a2 = areas[-3], areas[-2], areas[-1]
    d1 = a1 - a0
    d2 = a2 - a1
    R1 = (4 * a1 - a0) / 3
    R2 = (4 * a2 - a1) / 3
    with np.errstate(divide="ignore", invalid="ignore"):
        rho = np.where(d2 != 0, d1 / d2, np.inf)
        order = np.log2(np.abs(rho))
        rho_c = np.where(rho > 1.25, rho, 1.25)
        obs = np.abs(d2) * np.abs(1.0 / (rho_c - 1.0) - 1.0 / 3.0)
        obs = np.where(np.isfinite(rho) & (rho > 0), obs, 2.0 * np.abs(d2))
    # the extrapolated values converge at order 1.6-2 where the post-onset layer remains
    # (measured on the self-affine scene H 0.8), not 3: |R2 - R1| / (2^1.6 - 1)
    est = np.maximum(np.abs(R2 - R1) / 2.0, obs)
    return R2, est, order
