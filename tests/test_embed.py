"""The compiled one-pressure solves run inside a user's own @njit function (nopython mode)."""
import numba
import numpy as np
import pytest

import persson_fast as pf
from persson_fast import embed

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
