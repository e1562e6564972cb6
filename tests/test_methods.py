"""Every registered method: convergence at its theoretical order against exact solutions,
its tolerance met (or flagged), clear errors for scenes it cannot serve, auto's choice."""
import math

import numpy as np
import pytest

import persson_fast as pf
from persson_fast._reference.diffusion import cn_baseline
from persson_fast.methods import AUTO_POLICY, METHODS, check_serves, choose_auto

from tolerances import ATOL

#: five decades of G, few schedule points (each piece needs at least one step, so a dense
#: schedule would hide the coarse levels' step count)
G = np.r_[0.0, np.geomspace(1e-2, 1e3, 6)]
PRESSURES = np.array([0.3, 1.0, 3.0])
WALLS = {"images": (0.0, 0.0), "receding": (0.5, 0.05), "approaching": (2.0, -0.002)}
#: levels whose error ratios measure the order (the asymptotic range of each method)
LADDER = {"cn": (1, 2, 3, 4), "cn-plain": (2, 3, 4, 5), "implicit-euler": (3, 4, 5, 6),
          "fixed-grid": (1, 2, 3, 4), "bnr": (0, 1, 2, 3)}
#: |measured - theoretical| allowed: the pre-asymptotic drift over the ladder above
ORDER_SLACK = 0.35

#: the one-wall compiled methods ("strip" needs a yield wall: tests/test_yield_scale.py)
COMPILED = [m for m, i in METHODS.items()
            if i["family"] not in (None, "closed-form") and not i.get("two_walls")]


def _exact(wall):
    a, b = WALLS[wall]
    if a == 0.0 and b == 0.0:
        return pf.images_area(PRESSURES[:, None], G[None, :])
    return pf.linear_boundary_area(PRESSURES[:, None], G[None, :], a, b)


def _sigma_a(wall):
    a, b = WALLS[wall]
    return a + b * G


def _errors(method, wall, levels):
    ref = _exact(wall)
    out = []
    for level in levels:
        r = pf.solve_diffusion(G, PRESSURES, _sigma_a(wall), method=method, level=level)
        assert r.success, r.message
        out.append(np.max(np.abs(r.area - ref) / ref))
    return np.array(out)


@pytest.mark.parametrize("wall", sorted(WALLS))
@pytest.mark.parametrize("method", sorted(LADDER))
def test_grid_variants_converge_at_their_order(method, wall):
    levels = LADDER[method]
    err = _errors(method, wall, levels)
    orders = np.log2(err[:-1] / err[1:])
    theory = METHODS[method]["order"]
    assert abs(np.median(orders) - theory) <= ORDER_SLACK, (orders, err)


@pytest.mark.parametrize("wall", sorted(WALLS))
@pytest.mark.parametrize("method", COMPILED)
@pytest.mark.parametrize("rtol", [1e-3, 1e-4])
def test_every_compiled_method_meets_rtol_or_flags(method, wall, rtol):
    r = pf.solve_diffusion(G, PRESSURES, _sigma_a(wall), method=method, rtol=rtol)
    assert r.method == method
    ref = _exact(wall)
    ok = np.abs(r.area - ref) <= rtol * ref + ATOL
    # a method that cannot reach rtol within its work cap says so in the status
    assert np.all(ok | (r.status[:, None] != 0)), (np.max(np.abs(r.area - ref) / ref), r.message)


def test_cn_reaches_1e_8_relative_error():
    for wall in WALLS:
        err = _errors("cn", wall, (5,))
        assert err[0] <= 1e-8, (wall, err)


def test_levels_double_the_work():
    r = [pf.solve_diffusion(G, 1.0, 0.0, method="cn", level=k).counts[0] for k in (2, 3, 4)]
    nodes = [c[0] for c in r]
    steps = [c[1] for c in r]
    assert all(1.8 <= b / a <= 2.2 for a, b in zip(nodes[:-1], nodes[1:]))
    assert all(1.8 <= b / a <= 2.2 for a, b in zip(steps[:-1], steps[1:]))


def test_baseline_converges_at_second_order():
    g = np.r_[0.0, np.geomspace(1e-2, 10.0, 6)]
    ref = pf.images_area(3.0, g)
    errs = [np.max(np.abs(cn_baseline(g, 0 * g, 3.0, n, n / 8) - ref) / ref)
            for n in (100, 200, 400)]
    orders = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all(np.abs(orders - 2.0) <= 0.3), (errs, orders)


def test_analytic_cannot_serve_adhesion():
    s = pf.seed_scene()
    with pytest.raises(ValueError, match=r"method 'analytic' cannot serve adhesion .*method='cn'"):
        pf.solve_contact(s, 0.0, e_star=3e9, work_of_adhesion=0.06, method="analytic")


def test_check_serves_names_the_scene_feature():
    for method, info in METHODS.items():
        for key in ("adhesion", "jumps", "nonlinear"):
            if info[key]:
                check_serves(method, **{key: True})
            else:
                with pytest.raises(ValueError, match=f"method '{method}' cannot serve"):
                    check_serves(method, **{key: True})


def test_auto_policy_serves_every_kind_and_is_recorded():
    for kind in AUTO_POLICY:
        name = choose_auto(kind)
        assert name in METHODS and name != "auto"
    r = pf.solve_diffusion(G, 1.0, 0.5 + 0.05 * G, method="auto")
    assert r.method == "analytic"
    late = np.array([1.0, 2.0, 3.0])        # a moving wall held at sigma_a[0] before G[0]
    r = pf.solve_diffusion(late, 1.0, 0.5 + 0.1 * late, method="auto")
    assert r.method == choose_auto("smooth") and r.success
    r = pf.solve_diffusion(G, 1.0, 0.5 + 0.05 * np.sqrt(G), method="auto")
    assert r.method == choose_auto("smooth")
    s = pf.seed_scene()
    r = pf.solve_contact(s, 1e7, e_star=3e9, work_of_adhesion=0.06, method="auto", rtol=1e-3)
    assert r.method == choose_auto("adhesion")


def test_unknown_method_lists_every_name():
    with pytest.raises(ValueError) as info:
        pf.solve_diffusion(G, 1.0, method="euler")
    for name in METHODS:
        assert repr(name) in str(info.value)


def test_mean_contact_pressure_and_stress():
    s = pf.seed_scene()
    p = np.array([-1e5, 0.0, 1e7])
    r = pf.solve_contact(s, p, e_star=3e9, work_of_adhesion=0.06, rtol=1e-3)
    has = r.area > 0
    assert np.allclose(r.mean_contact_pressure[has], p[has] / r.area[has], rtol=1e-14)
    assert np.allclose(r.mean_contact_stress[has], r.load[has] / r.area[has], rtol=1e-14)
    r0 = pf.solve_contact(s, p[1:] + 1e6, e_star=3e9)
    assert np.array_equal(r0.mean_contact_pressure, r0.mean_contact_stress)
    assert math.isnan(pf.solve_contact(s, 0.0, e_star=3e9).mean_contact_pressure[0])


def test_registry_carries_the_kernels():
    """Every compiled method names its sweep kernels in its entry; the sweep layer has no
    per-method branch (a new method is its kernel file and one registry entry)."""
    import inspect

    from persson_fast import methods, sweep
    from persson_fast.plasticity import strip
    from persson_fast._kernels import similarity

    compiled = [m for m, i in pf.METHODS.items() if i.get("family") not in (None, "closed-form")]
    assert set(compiled) == {"cn", "cn-plain", "implicit-euler", "fixed-grid", "bnr", "strip"}
    for m in compiled:
        serial, parallel, lead = methods.sweep_kernels(m)
        assert callable(serial) and callable(parallel)
        assert lead == ((methods.variant_of(m),) if METHODS[m]["sweep"][2] else ())
    assert [methods.variant_of(m) for m in ("cn", "cn-plain", "implicit-euler")] == [
        similarity.CN, similarity.CN_PLAIN, similarity.IMPLICIT_EULER]
    src = inspect.getsource(sweep)
    assert '"family"' not in src and "fixedgrid" not in src and "bnr" not in src
    # the two-wall driver builds no kernel arguments of its own: it calls run_sweep
    assert "from ._kernels" not in inspect.getsource(strip)
    with pytest.raises(ValueError, match="no compiled sweep"):
        methods.sweep_kernels("analytic")


def test_a_new_method_is_one_registry_entry(monkeypatch):
    """Trial: a method registered by one entry (here naming the fixed-grid kernel module
    under a new name) is served by solve_diffusion with nothing else edited."""
    from persson_fast import methods

    entry = dict(METHODS["fixed-grid"], description="trial entry")
    monkeypatch.setitem(methods.METHODS, "trial-grid", entry)
    G = np.concatenate([[0.0], np.geomspace(1e-3, 10.0, 12)])
    a = pf.solve_diffusion(G, [1.0, 2.0], 0.1 + 0.05 * np.sqrt(G), method="trial-grid", rtol=1e-5)
    b = pf.solve_diffusion(G, [1.0, 2.0], 0.1 + 0.05 * np.sqrt(G), method="fixed-grid", rtol=1e-5)
    assert a.method == "trial-grid" and np.array_equal(a.area, b.area)


def _one_signature_call(method, kernel, sy_rows, pl_len, pressures=(1.0, 2.0)):
    """Call a sweep of the one signature directly (serial kernel of ``method``) on a small
    scene; the outputs, status and counts."""
    from persson_fast import methods

    _, _, lead = methods.sweep_kernels(method)
    G = np.concatenate([[0.0], np.geomspace(1e-3, 10.0, 9)])
    p = np.array(pressures, dtype=float)
    n_p, n_t = p.size, G.size
    sa = np.tile(0.1 + 0.05 * np.sqrt(G), (n_p, 1))
    outs = [np.zeros((n_p, n_t)) for _ in range(5)]
    pl = [np.full((n_p, pl_len), 7.0) for _ in range(2)]
    status = np.full(n_p, -1, dtype=np.int64)
    counts = np.zeros((n_p, 3), dtype=np.int64)
    sy = np.zeros((n_p, 0)) if sy_rows is None else np.broadcast_to(sy_rows, (n_p, n_t)).copy()
    kernel(*lead, G, sa, sy, p, 1e-4, -1, 2, *outs, *pl, status, counts)
    return outs, pl, status, counts


@pytest.mark.parametrize("method", [m for m in METHODS if "sweep" in METHODS[m]
                                    and not METHODS[m].get("two_walls")])
def test_one_wall_kernel_refuses_a_finite_upper_wall(method):
    """Every one-wall sweep, called through the registry with the one signature: an upper
    wall that is finite anywhere in a row is BAD_INPUT for that row (nothing written); rows
    of +inf, or of length 0, are no upper wall and give bitwise the same results, with
    plastic outputs of length n_t set to zero."""
    from persson_fast import methods
    from persson_fast._kernels import status as st

    serial, _, _ = methods.sweep_kernels(method)
    none_outs, _, none_status, none_counts = _one_signature_call(method, serial, None, 0)
    assert np.all(none_status == st.OK)
    inf_outs, inf_pl, inf_status, inf_counts = _one_signature_call(method, serial, np.inf, 10)
    assert np.array_equal(inf_status, none_status)
    assert np.array_equal(inf_counts, none_counts)
    for a, b in zip(inf_outs, none_outs):
        assert np.array_equal(a, b)
    assert all(np.all(x == 0.0) for x in inf_pl)
    # a finite value in the second row only (the first is +inf throughout)
    sy = np.full((2, 10), np.inf)
    sy[1, 4] = 5.0
    outs, pl, status, counts = _one_signature_call(method, serial, sy, 10)
    assert status.tolist() == [st.OK, st.BAD_INPUT]
    assert all(np.all(x[1] == 0.0) for x in outs) and np.all(counts[1] == 0)
    assert all(np.all(x[1] == 7.0) for x in pl)
    assert np.array_equal(outs[0][0], none_outs[0][0])
    # rows neither of length 0 nor of n_t: bad input
    _, _, status, _ = _one_signature_call(method, serial, None, 3)
    assert np.all(status == st.BAD_INPUT)


def test_two_wall_kernel_needs_its_upper_wall():
    """The strip sweep through the registry: without an upper wall (rows of length 0) or
    without plastic outputs it answers BAD_INPUT; with both it solves."""
    from persson_fast import methods
    from persson_fast._kernels import status as st

    serial, _, _ = methods.sweep_kernels("strip")
    _, _, status, _ = _one_signature_call("strip", serial, None, 10)
    assert np.all(status == st.BAD_INPUT)
    _, _, status, _ = _one_signature_call("strip", serial, 4.0, 0)
    assert np.all(status == st.BAD_INPUT)
    outs, pl, status, _ = _one_signature_call("strip", serial, 4.0, 10)
    assert np.all(status == st.OK) and np.all(pl[0][:, -1] > 0.0)
    np.testing.assert_allclose(outs[0] + pl[0] + outs[2], 1.0, rtol=0.0, atol=1e-12)


TRIAL_KERNEL = '''"""A grid method in its own kernel module: a sweep of the one signature (no variant) around
the fixed-grid solver of one pressure."""
from persson_fast._jit import njit_sweeps, prange
from persson_fast._kernels.fixedgrid import solve_fixedgrid_one
from persson_fast._kernels.signature import no_upper_wall
from persson_fast._kernels.status import BAD_INPUT


def _sweep(G, sa_rows, sy_rows, pressures, rtol, level, n_damp, area, load, det_area,
           det_load, error, pl_area, pl_load, status, counts):
    n_p = pressures.shape[0]
    for k in prange(n_p):
        if no_upper_wall(sy_rows, pl_area, pl_load, k, n_p, G.shape[0]):
            status[k] = solve_fixedgrid_one(G, sa_rows[k], pressures[k], rtol, level, n_damp,
                                            area[k], load[k], det_area[k], det_load[k],
                                            error[k], counts[k])
        else:
            status[k] = BAD_INPUT


trial_sweep_serial, trial_sweep_parallel = njit_sweeps(_sweep)
'''


def test_a_new_grid_method_is_a_kernel_module_and_one_entry(tmp_path, monkeypatch):
    """Trial: a new kernel module (written here, outside the package) and one registry entry
    naming it; solve_diffusion serves the method serially and on threads, with nothing else
    edited, and it matches the method whose solver it wraps."""
    from persson_fast import methods

    (tmp_path / "trial_grid_kernels.py").write_text(TRIAL_KERNEL)
    monkeypatch.syspath_prepend(str(tmp_path))
    entry = {"description": "trial", "family": "fixed-grid", "order": 2, "adhesion": False,
             "jumps": False, "nonlinear": True, "controls_error": False,
             "sweep": ("trial_grid_kernels", "trial_sweep", None)}
    monkeypatch.setitem(methods.METHODS, "trial-module", entry)
    G = np.concatenate([[0.0], np.geomspace(1e-3, 10.0, 12)])
    p = [0.5, 1.0, 2.0, 3.0]
    ref = pf.solve_diffusion(G, p, 0.1 + 0.05 * np.sqrt(G), method="fixed-grid", rtol=1e-5,
                             parallel=False)
    for parallel in (False, "threads"):
        r = pf.solve_diffusion(G, p, 0.1 + 0.05 * np.sqrt(G), method="trial-module",
                               rtol=1e-5, parallel=parallel)
        assert r.method == "trial-module"
        for name in ("area", "load", "detached_area", "detached_load", "error_estimate",
                     "status", "counts"):
            assert np.array_equal(getattr(r, name), getattr(ref, name)), name
