"""pf.Scene: one record of a scene, taken by every entry point; bitwise the keyword form."""
import dataclasses
import pathlib

import numpy as np
import pytest

import persson_fast as pf
from persson_fast import embed

SA = pf.SelfAffine(hurst=0.8, q0=1e4, q1=1e8, h_rms=1e-6)


def _same(a, b):
    for name in ("area", "area_zeta", "sigma_a", "error_estimate", "status", "load"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name


def test_scene_equals_keywords_without_adhesion():
    scene = pf.Scene(SA, e_star=1e9)
    p = np.geomspace(1e5, 1e8, 7)
    _same(pf.solve_contact(scene, p), pf.solve_contact(SA, p, e_star=1e9))
    _same(pf.solve_contact(scene, p, method="cn", rtol=1e-5),
          pf.solve_contact(SA, p, e_star=1e9, method="cn", rtol=1e-5))


def test_scene_equals_keywords_with_adhesion():
    scene = pf.Scene(pf.seed_scene(), e_star=pf.seed_e_star(), work_of_adhesion=0.06,
                     energy_correction=0.45, detachment_prefactor=0.7)
    p = np.array([-1e5, 0.0, 1e7])
    kw = dict(e_star=pf.seed_e_star(), work_of_adhesion=0.06, energy_correction=0.45,
              detachment_prefactor=0.7)
    _same(pf.solve_contact(scene, p, rtol=1e-3), pf.solve_contact(pf.seed_scene(), p, rtol=1e-3, **kw))
    assert scene.adhesive and scene.keywords() == kw


def test_scene_in_pull_off_scan_and_embed():
    scene = pf.Scene(pf.seed_scene(), e_star=pf.seed_e_star(), work_of_adhesion=0.06)
    kw = dict(e_star=pf.seed_e_star(), work_of_adhesion=0.06)
    assert pf.pull_off(scene, rtol=1e-3) == pf.pull_off(pf.seed_scene(), rtol=1e-3, **kw)
    a = embed.adhesive_scene(scene, rtol=1e-3)
    b = embed.adhesive_scene(pf.seed_scene(), rtol=1e-3, **kw)
    assert all(np.array_equal(x, y) for x, y in zip(a, b))
    plain = pf.Scene(SA, e_star=1e9)
    ds = pf.scan(plain, {}, [1e6, 1e7], workers=1)
    assert np.array_equal(ds.area.values.ravel(),
                          pf.solve_contact(SA, [1e6, 1e7], e_star=1e9).area)


def test_scene_validates_once_and_is_frozen():
    with pytest.raises(ValueError, match="e_star"):
        pf.Scene(SA, e_star=-1.0)
    with pytest.raises(ValueError, match="work_of_adhesion"):
        pf.Scene(SA, e_star=1e9, work_of_adhesion=-0.1)
    with pytest.raises(ValueError, match="energy_correction"):
        pf.Scene(SA, e_star=1e9, energy_correction=1.5)
    with pytest.raises(ValueError, match="surface must be a persson_fast surface"):
        pf.Scene(object(), e_star=1e9)
    with pytest.raises(ValueError, match="hardness must be > 0"):
        pf.Scene(SA, e_star=1e9, hardness=0.0)
    with pytest.raises(ValueError, match="hardness must be a number"):
        pf.Scene(SA, e_star=1e9, hardness=[3e8, 1e9])
    assert callable(pf.Scene(SA, e_star=1e9, hardness=lambda zeta: 3e8 + 0 * zeta).hardness)
    assert pf.Scene(SA, e_star=1e9, hardness=3e8).hardness == 3e8
    s = pf.Scene(SA, e_star=1e9)
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.e_star = 2e9
    assert isinstance(s.e_star, float) and s.detachment_prefactor == 2 ** -0.5


def test_scene_and_keywords_together_are_refused():
    s = pf.Scene(SA, e_star=1e9)
    with pytest.raises(ValueError, match="either in the Scene or as keywords"):
        pf.solve_contact(s, [1e6], e_star=2e9)
    with pytest.raises(ValueError, match="either in the Scene or as keywords"):
        pf.pull_off(s, work_of_adhesion=0.05)
    with pytest.raises(ValueError, match="e_star .* is required"):
        pf.solve_contact(SA, [1e6])
    with pytest.raises(ValueError, match="work_of_adhesion .* is required"):
        pf.pull_off(SA, e_star=1e9)


def test_one_place_for_the_detachment_prefactor_default():
    """The default 1/sqrt 2 of seed Eq. 8 is written once (scene.DETACHMENT_PREFACTOR)."""
    root = pathlib.Path(pf.__file__).parent
    hits = [p.name for p in root.rglob("*.py") if "2 ** -0.5" in p.read_text()]
    assert hits == ["scene.py"], hits
