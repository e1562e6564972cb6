"""The compiled one-pressure solves run inside a user's own @njit function (nopython mode)."""
import numba
import numpy as np
import pytest

import persson_fast as pf
from persson_fast import embed
from persson_fast._kernels import status as st
from persson_fast._kernels.adhesion import (DEFAULT_M_HIST, DEFAULT_MAX_ITER, DEFAULT_N_DAMP,
                                            DEFAULT_OMEGA, solve_adhesive_one)
from persson_fast._kernels.similarity import solve_one

E_STAR = 2.9e9 / (1 - 0.3**2)


@numba.njit
def _areas_no_adhesion(G, sigma_a, local_pressure, rtol):
    """A user kernel: the contact area at every node of a larger simulation."""
    out = np.empty(local_pressure.size)
    worst = 0
    for i in range(local_pressure.size):
        out[i], status = embed.diffusion_area(G, sigma_a, local_pressure[i], rtol)
        worst = max(worst, status)
    return out, worst


@numba.njit
def _areas_adhesive(scene, local_pressure, rtol):
    out = np.empty(local_pressure.size)
    worst = 0
    for i in range(local_pressure.size):
        out[i], status = embed.adhesive_area(scene, local_pressure[i], rtol)
        worst = max(worst, status)
    return out, worst


def _nopython_only(func):
    """Compiled, with every signature a nopython one (no object-mode fallback)."""
    return len(func.nopython_signatures) >= 1 and len(func.nopython_signatures) == len(func.signatures)


def test_no_adhesion_inside_njit_matches_public_api():
    s = pf.seed_scene()
    z = pf.default_zeta(s)
    G = np.asarray(s.diffusion_time(z * s.q0, E_STAR), dtype=float)
    G[0] = 0.0
    p = np.array([1e5, 1e6, 1e7, 5e7, 1e8])
    areas, worst = _areas_no_adhesion(G, np.zeros_like(G), p, 1e-6)
    assert _nopython_only(_areas_no_adhesion)
    assert worst == 0
    exact = pf.contact_area_no_adhesion(s, p, E_STAR)[1][:, -1]
    assert np.all(np.abs(areas - exact) <= 1e-6 * exact + 1e-12)


def test_prescribed_wall_inside_njit_matches_exact():
    G = np.r_[0.0, np.geomspace(1e-2, 1e2, 9)]
    a, b = 0.5, 0.05
    areas, worst = _areas_no_adhesion(G, a + b * G, np.array([0.3, 1.0, 3.0]), 1e-6)
    exact = pf.linear_boundary_area(np.array([0.3, 1.0, 3.0]), G[-1], a, b)
    assert worst == 0
    assert np.all(np.abs(areas - exact) <= 1e-6 * exact + 1e-12)


def test_adhesive_inside_njit_matches_solve_contact():
    s = pf.seed_scene()
    rtol = 1e-4
    scene = embed.adhesive_scene(s, e_star=E_STAR, work_of_adhesion=0.06, rtol=rtol)
    p = np.array([-2e5, 0.0, 1e7])
    areas, worst = _areas_adhesive(scene, p, rtol)
    assert _nopython_only(_areas_adhesive)
    assert worst == 0
    ref = pf.solve_contact(s, p, e_star=E_STAR, work_of_adhesion=0.06, rtol=rtol)
    # same fixed point, the public path warm-starts its fine grid: agreement to rtol
    assert np.all(np.abs(areas - ref.area) <= rtol * ref.area + 1e-12)


def test_adhesive_scene_validates():
    s = pf.seed_scene()
    with pytest.raises(ValueError, match="work_of_adhesion must be > 0"):
        embed.adhesive_scene(s, e_star=E_STAR, work_of_adhesion=0.0)
    with pytest.raises(ValueError, match="e_star"):
        embed.adhesive_scene(s, e_star=-1.0, work_of_adhesion=0.06)


# --- argument checks inside the compiled entry points (issue 11, item 9) -----------------

_G = np.r_[0.0, np.geomspace(1e-2, 1e2, 9)]
_SA = 0.5 + 0.05 * _G

#: (G, sigma_a, sigma0, rtol, status name): each breaks one rule of embed's table. Every
#: array is a C-contiguous float64 copy, so the user kernels compile once for all of them.
_BAD_DIFFUSION = {
    "nan pressure": (_G, _SA, np.nan, 1e-6, "BAD_PRESSURE"),
    "inf pressure": (_G, _SA, np.inf, 1e-6, "BAD_PRESSURE"),
    "-inf pressure": (_G, _SA, -np.inf, 1e-6, "BAD_PRESSURE"),
    "negated G": (-_G, _SA, 1.0, 1e-6, "BAD_G"),
    "reversed G": (_G[::-1].copy(), _SA, 1.0, 1e-6, "BAD_G"),
    "empty G": (np.empty(0), np.empty(0), 1.0, 1e-6, "BAD_G"),
    "nan in G": (np.r_[_G[:4], np.nan, _G[5:]], _SA, 1.0, 1e-6, "BAD_G"),
    "inf G[-1]": (np.r_[_G[:-1], np.inf], _SA, 1.0, 1e-6, "BAD_G"),
    "all-nan sigma_a": (_G, np.full_like(_G, np.nan), 1.0, 1e-6, "BAD_SIGMA_A"),
    "inf in sigma_a": (_G, np.r_[_SA[:3], np.inf, _SA[4:]], 1.0, 1e-6, "BAD_SIGMA_A"),
    "sigma_a shorter than G": (_G, _SA[:5].copy(), 1.0, 1e-6, "BAD_SIGMA_A"),
    "sigma_a longer than G": (_G, np.r_[_SA, 0.5], 1.0, 1e-6, "BAD_SIGMA_A"),
    "rtol 0": (_G, _SA, 1.0, 0.0, "BAD_RTOL"),
    "rtol negative": (_G, _SA, 1.0, -1e-6, "BAD_RTOL"),
    "rtol nan": (_G, _SA, 1.0, np.nan, "BAD_RTOL"),
    "rtol too large": (_G, _SA, 1.0, 0.5, "BAD_RTOL"),
    "rtol too small": (_G, _SA, 1.0, 1e-13, "BAD_RTOL"),
}


@numba.njit
def _solve_one_pressure(G, sigma_a, sigma0, rtol, n_damp, n_out):
    """A user kernel calling the full one-pressure solve with its own output arrays."""
    outs = np.empty((5, n_out))
    status = embed.diffusion_solve(G, sigma_a, sigma0, rtol, n_damp, outs[0], outs[1],
                                   outs[2], outs[3], outs[4])
    return outs, status


@pytest.mark.parametrize("case", list(_BAD_DIFFUSION))
def test_diffusion_area_inside_njit_rejects_bad_arguments(case):
    G, sa, p, rtol, code = _BAD_DIFFUSION[case]
    areas, status = _areas_no_adhesion(G, sa, np.array([p]), rtol)
    assert np.isnan(areas[0]) and status != 0, (areas[0], status)
    assert status == getattr(st, code)


@pytest.mark.parametrize("case", list(_BAD_DIFFUSION))
def test_diffusion_solve_inside_njit_rejects_bad_arguments(case):
    G, sa, p, rtol, code = _BAD_DIFFUSION[case]
    outs, status = _solve_one_pressure(G, sa, p, rtol, 2, G.size)
    assert np.all(np.isnan(outs)) and status != 0, (outs[0], status)
    assert status == getattr(st, code)


@pytest.mark.parametrize("n_damp, n_out", [(-1, _G.size), (2, _G.size - 1), (2, _G.size + 1)])
def test_diffusion_solve_inside_njit_rejects_bad_outputs(n_damp, n_out):
    outs, status = _solve_one_pressure(_G, _SA, 1.0, 1e-6, n_damp, n_out)
    assert np.all(np.isnan(outs)) and status == st.BAD_INPUT


def test_single_point_G_is_valid_as_in_solve_diffusion():
    """One diffusion time is a valid schedule for solve_diffusion, so also for embed."""
    G, sa = np.array([1.0]), np.array([0.5])
    areas, status = _areas_no_adhesion(G, sa, np.array([1.0]), 1e-6)
    ref = pf.solve_diffusion(G, sa, 1.0, rtol=1e-6)       # the same solve, scaled in Python
    exact = pf.linear_boundary_area(np.array([1.0]), 1.0, 0.5, 0.0)[0]
    assert status == 0 and areas[0] == pytest.approx(ref.area[0, -1], rel=1e-12)
    assert abs(areas[0] - exact) <= 1e-6 * exact


def test_rtol_range_is_the_python_layers():
    from persson_fast.scene import _check_rtol

    for rtol in (embed.RTOL_MIN, embed.RTOL_MAX):
        assert _check_rtol(rtol) == rtol and embed._rtol_ok(rtol)
    for rtol in (np.nextafter(embed.RTOL_MIN, 0.0), np.nextafter(embed.RTOL_MAX, 1.0)):
        with pytest.raises(ValueError, match="rtol must lie in"):
            _check_rtol(rtol)
        assert not embed._rtol_ok(rtol)


def test_argument_status_codes_are_distinct_and_documented():
    codes = [st.BAD_PRESSURE, st.BAD_RTOL, st.BAD_G, st.BAD_SIGMA_A, st.BAD_SCENE]
    assert len(set(codes)) == len(codes) and 0 not in codes and st.BAD_INPUT not in codes
    for name in ("BAD_PRESSURE", "BAD_RTOL", "BAD_G", "BAD_SIGMA_A", "BAD_SCENE"):
        assert getattr(st, name) in embed.STATUS_MESSAGES
        assert name in embed.__doc__


@pytest.fixture(scope="module")
def scene():
    return embed.adhesive_scene(pf.seed_scene(), e_star=E_STAR, work_of_adhesion=0.06, rtol=1e-3)


def _corrupt(scene, **changes):
    """A copy of the scene tuple with some entries replaced (same numba types)."""
    names = ("G", "c", "wa", "wb", "G_fine", "c_fine", "wa_fine", "wb_fine", "gamma_s", "scale")
    parts = dict(zip(names, scene))
    parts.update(changes)
    return tuple(np.ascontiguousarray(parts[k], dtype=float) if k not in ("gamma_s", "scale")
                 else float(parts[k]) for k in names)


#: scene tuples that adhesive_scene never builds: name -> changes to the valid scene
_BAD_SCENES = {
    "reversed G": lambda s: {"G": s[0][::-1]},
    "negated G": lambda s: {"G": -s[0]},
    "nan in fine G": lambda s: {"G_fine": np.r_[s[4][:-1], np.nan]},
    "single-point G": lambda s: {"G": s[0][:1], "c": s[1][:1], "wa": s[2][:0], "wb": s[3][:0]},
    "empty fine grid": lambda s: {"G_fine": s[4][:0], "c_fine": s[5][:0], "wa_fine": s[6][:0],
                                  "wb_fine": s[7][:0]},
    "c shorter than G": lambda s: {"c": s[1][:-1]},
    "wa as long as G": lambda s: {"wa": np.r_[s[2], 0.0]},
    "nan in wb": lambda s: {"wb": np.r_[np.nan, s[3][1:]]},
    "negative c": lambda s: {"c": -s[1]},
    "nan energy correction": lambda s: {"gamma_s": np.nan},
    "energy correction > 1": lambda s: {"gamma_s": 2.0},
    "zero scale": lambda s: {"scale": 0.0},
    "nan scale": lambda s: {"scale": np.nan},
}


@pytest.mark.parametrize("case", list(_BAD_SCENES))
def test_adhesive_area_inside_njit_rejects_corrupted_scene(scene, case):
    bad = _corrupt(scene, **_BAD_SCENES[case](scene))
    areas, status = _areas_adhesive(bad, np.array([1e6]), 1e-3)
    assert np.isnan(areas[0]) and status != 0, (areas[0], status)
    assert status == st.BAD_SCENE


@pytest.mark.parametrize("pressure, rtol, code", [
    (np.nan, 1e-3, "BAD_PRESSURE"), (np.inf, 1e-3, "BAD_PRESSURE"),
    (-np.inf, 1e-3, "BAD_PRESSURE"),
    (1e6, 0.5, "BAD_RTOL"), (1e6, 1e-13, "BAD_RTOL"),
    # before the check these ran the fixed point for about a minute each
    (1e6, 0.0, "BAD_RTOL"), (1e6, -1e-3, "BAD_RTOL"), (1e6, np.nan, "BAD_RTOL"),
], ids=["nan-pressure", "inf-pressure", "-inf-pressure", "rtol-too-large", "rtol-too-small",
        "rtol-0", "rtol-negative", "rtol-nan"])
def test_adhesive_area_inside_njit_rejects_bad_pressure_and_rtol(scene, pressure, rtol, code):
    areas, status = _areas_adhesive(scene, np.array([pressure]), rtol)
    assert np.isnan(areas[0]) and status != 0, (areas[0], status)
    assert status == getattr(st, code)


# --- valid input: the checks change nothing -----------------------------------------------

@numba.njit
def _raw_diffusion(G, sigma_a, sigma0, rtol, n_damp):
    n = G.shape[0]
    outs = np.empty((5, n))
    status = solve_one(G, sigma_a, sigma0, rtol, n_damp, outs[0], outs[1], outs[2], outs[3],
                       outs[4])
    return outs, status


@numba.njit
def _raw_fixed_point(G, c, wa, wb, gamma_s, sigma0, rtol):
    n = G.shape[0]
    outs = np.empty((8, n))
    s, it, res = solve_adhesive_one(0, G, c, wa, wb, gamma_s, sigma0, rtol, DEFAULT_N_DAMP,
                                    DEFAULT_MAX_ITER, DEFAULT_M_HIST,
                                    DEFAULT_OMEGA, np.full(n, -1.0), outs[0], outs[1],
                                    outs[2], outs[3], outs[4], outs[5], outs[6], outs[7])
    return outs[0, n - 1], s


def test_valid_input_is_bitwise_the_raw_kernels(scene):
    p = np.array([0.3, 1.0, 3.0])
    for G, sa in ((_G, _SA), (_G, np.zeros_like(_G)), (np.array([1.0]), np.array([0.5]))):
        areas, worst = _areas_no_adhesion(G, sa, p, 1e-6)
        for i, sigma0 in enumerate(p):
            raw, raw_status = _raw_diffusion(G, sa, sigma0, 1e-6, 2)
            outs, status = _solve_one_pressure(G, sa, sigma0, 1e-6, 2, G.size)
            assert status == raw_status and np.array_equal(outs, raw)
            assert areas[i] == raw[0, -1]
    # adhesive_area: the raw fixed point on both grids, Richardson-extrapolated as before
    Gc, cc, wac, wbc, Gf, cf, waf, wbf, gamma_s, scale = scene
    pressures = np.array([-2e5, 0.0, 1e6, 1e7])
    areas, _ = _areas_adhesive(scene, pressures, 1e-3)
    for i, pressure in enumerate(pressures):
        ac, sc = _raw_fixed_point(Gc, cc, wac, wbc, gamma_s, pressure / scale, 1e-3)
        af, sf = _raw_fixed_point(Gf, cf, waf, wbf, gamma_s, pressure / scale, 1e-3)
        a = af if (ac > 0.0) != (af > 0.0) else min(max((4.0 * af - ac) / 3.0, 0.0), 1.0)
        assert areas[i] == a
