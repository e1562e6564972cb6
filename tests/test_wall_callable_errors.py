"""A wall or hardness callable that fails (issue 33, item 9): the ValueError names the
argument the user gave (``sigma_a``, ``sigma_y``, ``hardness``) and where it was called."""
from __future__ import annotations

import numpy as np
import pytest

import persson_fast as pf
from persson_fast.plasticity.hardness import CheckedHardness, check_hardness
from persson_fast.walls import CallableWallError

G = np.array([0.0, 0.5, 1.0])
SA = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e9, C0=1e-22)


def _raises(exc=RuntimeError("boom")):
    def f(x):
        raise exc
    return f


@pytest.mark.parametrize("func, words", [
    (lambda g: g * np.nan, "sigma_y(G) must be finite"),
    (_raises(), "sigma_y must be samples or a vectorised callable"),
    (lambda g: 0.3, "sigma_y(G) must return an array of G's shape"),
    (lambda g: np.where(g < 0.7, 0.3, 0.6), "sigma_y(G) must be continuous"),
])
def test_a_bad_yield_wall_is_named_sigma_y(func, words):
    """The reproducer of item 9 (a NaN yield wall with "strip") said "sigma_a(G) must be
    finite": the wrong wall."""
    with pytest.raises(ValueError) as info:
        pf.solve_diffusion(G, 0.2, sigma_y=func, method="strip")
    msg = str(info.value)
    assert words in msg, msg
    assert "sigma_a" not in msg, msg


def test_a_bad_detachment_wall_beside_a_yield_wall_is_named_sigma_a():
    with pytest.raises(ValueError, match=r"sigma_a\(G\) must be finite") as info:
        pf.solve_diffusion(G, 0.2, lambda g: g * np.nan, sigma_y=1.0, method="strip")
    assert "sigma_y" not in str(info.value)


@pytest.mark.parametrize("kwargs", [{}, {"work_of_adhesion": 0.01}])
def test_a_hardness_that_raises_names_hardness_and_zeta(kwargs):
    """The user's own exception is chained, not let through bare."""
    with pytest.raises(ValueError) as info:
        pf.solve_contact(SA, [1e6], e_star=1e9, hardness=_raises(), **kwargs)
    msg = str(info.value)
    assert msg.startswith("hardness must be a vectorised callable"), msg
    assert "zeta" in msg and "RuntimeError: boom" in msg, msg
    assert isinstance(info.value.__cause__, RuntimeError)


def test_a_hardness_that_fails_inside_the_sampling_names_hardness():
    """Called on the zeta of a diffusion time (the two-wall solver samples the wall): the
    error names hardness and the zeta, not the wall sigma_y of G it became."""
    def late_nan(z):
        return np.where(np.asarray(z) > 10.0, np.nan, 3e8)

    with pytest.raises(ValueError) as info:
        pf.solve_contact(SA, [1e6], e_star=1e9, hardness=late_nan)
    msg = str(info.value)
    assert msg.startswith("hardness(zeta) must return finite values > 0 [Pa]"), msg
    bad_zeta = float(msg.split("got hardness(")[1].split(")")[0])
    assert bad_zeta > 10.0


@pytest.mark.parametrize("func, words", [
    (lambda z: np.zeros_like(z), "must return finite values > 0 [Pa] of zeta's shape; got"),
    (lambda z: 3e8, "got shape ()"),
    (lambda z: ["a"] * np.size(z), "must return real numbers"),
])
def test_checked_hardness(func, words):
    h = check_hardness(func, scale_dependent=True)
    assert isinstance(h, CheckedHardness) and h.func is func
    assert repr(h) == repr(func)
    assert check_hardness(h, scale_dependent=True) is h          # not wrapped twice
    with pytest.raises(CallableWallError, match="hardness") as info:
        h(np.array([1.0, 2.0]))
    assert words in str(info.value)
    good = check_hardness(pf.hardness_power_law(1e8, 0.1), scale_dependent=True)
    assert not isinstance(good, CheckedHardness)                  # the package's own forms
    np.testing.assert_array_equal(check_hardness(lambda z: 2e8 * np.asarray(z) ** 0.1,
                                                 scale_dependent=True)(np.array([1.0])), 2e8)
