"""The closed form computes A(zeta) profiles only when read (persson_fast.results.Deferred):
the values are bitwise those of an eager solve, and the result still pickles, copies and
compares."""
import copy
import pickle

import numpy as np

import persson_fast as pf

S = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
P = np.array([0.0, 1e3, 1e6, 1e8])


def test_deferred_profiles_are_bitwise_the_eager_ones():
    r = pf.solve_contact(S, P, e_star=1e9)
    assert "area_zeta" not in r.__dict__            # not computed yet
    eager = np.broadcast_to(pf.images_area(P[:, None], r.G[None, :]),
                            (P.size, r.zeta.size)).astype(float)
    np.testing.assert_array_equal(r.area_zeta, eager)
    assert "area_zeta" in r.__dict__                # kept after the first read
    np.testing.assert_array_equal(r.area, r.area_zeta[:, -1])
    np.testing.assert_array_equal(r.sigma_a, np.zeros((P.size, r.zeta.size)))
    np.testing.assert_array_equal(r.gamma_eff, np.zeros((P.size, r.zeta.size)))
    cn = pf.solve_contact(S, P, e_star=1e9, method="cn", rtol=1e-8)
    np.testing.assert_allclose(cn.area_zeta, r.area_zeta, rtol=1e-7, atol=1e-12)


def test_deferred_result_pickles_copies_and_compares():
    r = pf.solve_contact(S, P, e_star=1e9)
    back = pickle.loads(pickle.dumps(r))
    assert "area_zeta" not in back.__dict__
    np.testing.assert_array_equal(back.area_zeta, r.area_zeta)
    c = copy.deepcopy(pf.solve_contact(S, P, e_star=1e9))
    np.testing.assert_array_equal(c.area_zeta, r.area_zeta)
    fresh = pf.solve_contact(S, P[1:], e_star=1e9)
    assert "pressure" in repr(fresh) and "area_zeta" not in fresh.__dict__
    try:
        fresh.no_such_attribute
    except AttributeError as exc:
        assert "no_such_attribute" in str(exc)
    else:
        raise AssertionError("expected an AttributeError")


def _fields(r):
    return {name: np.asarray(getattr(r, name)).tobytes()
            for name in ("pressure", "area", "zeta", "G", "area_zeta", "load", "detached_area",
                         "detached_load", "mean_contact_pressure", "mean_contact_stress",
                         "error_estimate", "status")}


def test_grid_kept_on_the_surface_follows_it():
    """The default zeta grid and G(zeta) kept on the surface between calls: the results are
    bitwise those of a fresh surface, a result's arrays are its own, a parameter set later is
    seen, and the kept values are not pickled with the surface."""
    s = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6)
    p = np.concatenate([[0.0, 5e-324], np.geomspace(1e3, 1e8, 20)])
    first = pf.solve_contact(s, p, e_star=1e9)
    expected = _fields(first)
    first.G[:] = 0.0
    first.zeta[:] = 0.0
    assert _fields(pf.solve_contact(s, p, e_star=1e9)) == expected
    assert "_memo" in s.__dict__ and "_memo" not in pickle.loads(pickle.dumps(s)).__dict__
    s.C0 = 4.0 * s.C0
    changed = pf.solve_contact(s, p, e_star=1e9)
    fresh = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, C0=s.C0)
    assert _fields(changed) == _fields(pf.solve_contact(fresh, p, e_star=1e9))
    before = pf.solve_contact(pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, h_rms=1e-6), p, e_star=1e9)
    np.testing.assert_allclose(changed.G, 4.0 * before.G, rtol=1e-14)
